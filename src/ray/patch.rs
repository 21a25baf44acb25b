//! Ray intersection for tensor-product surfaces by subdivision of the
//! ray's two plane distances.
//!
//! The ray `o + t·d` is the intersection of two planes through it, with unit
//! normals `e₁`, `e₂` perpendicular to `d`. On a rational Bézier patch
//! `S = A/w` (`A = Σ wᵢⱼPᵢⱼBᵢBⱼ`, `w = Σ wᵢⱼBᵢBⱼ > 0`) the ray meets the
//! surface where both `α = e₁·(A − w·o)` and `β = e₂·(A − w·o)` vanish; both
//! are tensor Bernstein polynomials with coefficients `e·wᵢⱼ(Pᵢⱼ − o)`,
//! computed once per ray and patch, and `γ = d̂·(A − w·o)` gives the distance
//! along the ray, `γ/w`. A parameter box is discarded when all its `α`
//! coefficients, or all its `β` coefficients, are of one sign beyond their
//! rounding bound (the convex hull property: the polynomial then has that
//! sign on the whole box), or when all its `γ/w` ratios lie outside the
//! range still searched. Boxes that survive are halved (de Casteljau, in the
//! parameter whose box is wider) until Krawczyk's test proves that a box
//! holds exactly one root ([`unique_root`]) or the box is smaller than
//! [`SMALL`]; Newton's method on the 2 × 2 system
//! `(e₁·(S − o), e₂·(S − o)) = 0` then runs from the box's centre (and its
//! corners if needed), and a point it reaches on the patch (inside the box,
//! for a box proven to hold one root) with a residual within the tolerance
//! is a hit.
//! Boxes are visited nearest first along the ray (depth-first, the nearer
//! half first) and the search stops at the best hit so far.
//!
//! No root is discarded: a box is dropped only where a certain sign rules
//! a hit out, so every hit lies in some small box; a transversal hit is then
//! found by Newton's method from within `SMALL` of it. A ray that grazes the
//! surface (a double root) may be found or not, as for the other
//! intersectors; no hit is reported that is not on the surface to the
//! tolerance.

use super::patch_tree::{PatchTree, Slab};
use crate::surface::tensor_patch::{Patch, tensor_jet};
use crate::{Ray, Tolerance};
use nalgebra::Vector3;

/// Boxes narrower than this (in a patch's own parameters, both sides) are
/// handed to Newton's method.
const SMALL: f64 = 1.0 / (1u64 << 14) as f64;

/// Hits whose residual is within `max(tolerance, ACCEPT) ×` the scale are
/// accepted (as the exact revolution intersector does).
const ACCEPT: f64 = 1e-12;

/// How far outside its patch (in the patch's parameters) Newton may land and
/// still count: rounding only.
const SLACK: f64 = 1e-9;

/// Boxes the depth-first search holds at once: two per level, and levels
/// are at most `2·log₂(1/SMALL)`.
const STACK: usize = 2 * 2 * 14 + 4;

/// A hit in a surface's own parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PatchHit {
    /// Index of the patch hit.
    pub(crate) patch: usize,
    pub(crate) t: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
}

/// One box of the search: its parameter ranges within the patch, its depth
/// and where its coefficients `(α, β, γ, w)` start in the buffer.
#[derive(Debug, Clone, Copy)]
struct Cell {
    s: (f64, f64),
    t: (f64, f64),
    depth: u32,
}

/// Control points per patch whose search runs on the stack (bicubic).
const STACK_NET: usize = 16;

/// The patches a search runs over: their common degrees, the patches and
/// the hierarchy over them.
#[derive(Clone, Copy)]
pub(crate) struct PatchSet<'a> {
    pub(crate) degrees: (usize, usize),
    pub(crate) patches: &'a [Patch],
    pub(crate) tree: &'a PatchTree,
}

/// The nearest hit of `ray` with `t_min < t < t_max` on the patches of
/// `set`.
pub(crate) fn intersect(
    set: PatchSet<'_>,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    tol: &Tolerance,
) -> Option<PatchHit> {
    let tol = tol.clamped();
    let (o, d) = (ray.origin.coords, ray.dir);
    let m = d.amax();
    // NaN-safe: false when either is NaN.
    let ordered = t_min < t_max;
    let usable = ordered && m > 0.0 && m.is_finite() && o.iter().all(|c| c.is_finite());
    if !usable {
        return None;
    }
    let dn = m * (d / m).norm();
    let dh = d / dn;
    // Two unit normals of planes through the ray.
    let helper = if dh.x.abs() <= dh.y.abs() && dh.x.abs() <= dh.z.abs() {
        Vector3::x()
    } else if dh.y.abs() <= dh.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    let e1 = dh.cross(&helper).normalize();
    let e2 = dh.cross(&e1);
    let scale = set.tree.scale.max(f64::MIN_POSITIVE);
    let accept = (tol.relative * scale).max(ACCEPT * scale.max(o.amax()));
    // Hits within the position uncertainty of the origin are the origin.
    let t_floor = t_min + accept / dn;
    let (p, q) = set.degrees;
    let n = (p + 1) * (q + 1);
    let frame = Frame {
        o,
        dn,
        e1,
        e2,
        dh,
        accept,
        target: tol.relative * scale,
        iterations: tol.max_iterations,
        t_floor,
    };
    let mut on_stack = [[0.0_f64; 4]; STACK_NET * (STACK + 1)];
    let mut on_heap = Vec::new();
    let buf: &mut [[f64; 4]] = if n <= STACK_NET {
        &mut on_stack[..n * (STACK + 1)]
    } else {
        on_heap.resize(n * (STACK + 1), [0.0; 4]);
        &mut on_heap
    };
    let mut best: Option<PatchHit> = None;
    let slab = Slab::new(ray);
    set.tree.visit(&slab, t_floor, t_max, |k, _| {
        let t_best = best.map_or(t_max, |h| h.t);
        if let Some(hit) = search_patch(set, k, &frame, buf, t_best) {
            best = Some(hit);
            return hit.t;
        }
        t_best
    });
    best
}

/// The nearest hit on patch `k` of `set` with `frame.t_floor < t < t_best`,
/// searched with the scratch space `buf` (`(STACK + 1)·n` entries for `n`
/// control points).
fn search_patch(
    set: PatchSet<'_>,
    k: usize,
    frame: &Frame,
    buf: &mut [[f64; 4]],
    mut t_best: f64,
) -> Option<PatchHit> {
    let (p, q) = set.degrees;
    let n = (p + 1) * (q + 1);
    let patch = &set.patches[k];
    let (o, e1, e2, dh, dn) = (frame.o, frame.e1, frame.e2, frame.dh, frame.dn);
    let t_floor = frame.t_floor;
    let mut best = None;
    // Coefficients (α, β, γ, w) of the patch.
    let mut magnitude = 0.0_f64;
    for (slot, h) in buf[..n].iter_mut().zip(&patch.net) {
        let rel = h.wp - o * h.w;
        *slot = [e1.dot(&rel), e2.dot(&rel), dh.dot(&rel), h.w];
        magnitude = magnitude.max(h.wp.abs().sum() + o.abs().sum() * h.w);
    }
    let err = 8.0 * f64::EPSILON * magnitude;
    let mut cells = [Cell {
        s: (0.0, 1.0),
        t: (0.0, 1.0),
        depth: 0,
    }; STACK];
    let mut len = 1;
    // Cell i's coefficients live at buf[(i + 1)·n ..]; slot 0 is the
    // patch's own.
    let (head, rest) = buf.split_at_mut(n);
    rest[..n].copy_from_slice(head);
    while len > 0 {
        len -= 1;
        let cell = cells[len];
        let coef = &rest[len * n..(len + 1) * n];
        let bound = err * (1.0 + cell.depth as f64);
        if excluded(coef, bound, t_floor * dn, t_best * dn) {
            continue;
        }
        let (ws, wt) = (cell.s.1 - cell.s.0, cell.t.1 - cell.t.0);
        if (ws <= SMALL && wt <= SMALL) || len + 2 >= STACK {
            if let Some(hit) = polish(patch, k, q + 1, frame, cell) {
                if hit.t > t_floor && hit.t < t_best {
                    t_best = hit.t;
                    best = Some(hit);
                }
            }
            continue;
        }
        // A box that holds exactly one root (Krawczyk's test) is
        // finished by Newton's method if it lands inside the box.
        if ws.max(wt) <= TRY_UNIQUE && unique_root(coef, p, q, bound) {
            if let Some(hit) = polish(patch, k, q + 1, frame, cell) {
                let s_hit = (hit.u - patch.u.0) / (patch.u.1 - patch.u.0);
                let t_hit = (hit.v - patch.v.0) / (patch.v.1 - patch.v.0);
                let inside = s_hit >= cell.s.0 - SLACK
                    && s_hit <= cell.s.1 + SLACK
                    && t_hit >= cell.t.0 - SLACK
                    && t_hit <= cell.t.1 + SLACK;
                if inside {
                    if hit.t > t_floor && hit.t < t_best {
                        t_best = hit.t;
                        best = Some(hit);
                    }
                    continue;
                }
            }
        }
        // Halve in the wider parameter; the nearer half is searched
        // first (pushed last).
        let split_s = ws >= wt;
        let (lo, hi) = rest.split_at_mut((len + 1) * n);
        let parent = &mut lo[len * n..];
        let child = &mut hi[..n];
        halve(parent, child, p, q, split_s);
        let (first, second) = if split_s {
            let mid = 0.5 * (cell.s.0 + cell.s.1);
            ((cell.s.0, mid), (mid, cell.s.1))
        } else {
            let mid = 0.5 * (cell.t.0 + cell.t.1);
            ((cell.t.0, mid), (mid, cell.t.1))
        };
        let make = |r: (f64, f64)| Cell {
            s: if split_s { r } else { cell.s },
            t: if split_s { cell.t } else { r },
            depth: cell.depth + 1,
        };
        // parent now holds the first half, child the second.
        let near_first = min_distance(parent) <= min_distance(child);
        if near_first {
            // Second half below, first half on top.
            swap_slices(parent, child);
            cells[len] = make(second);
            cells[len + 1] = make(first);
        } else {
            cells[len] = make(first);
            cells[len + 1] = make(second);
        }
        len += 2;
    }
    best
}

/// Boxes at most this wide (in both parameters) try the uniqueness test.
const TRY_UNIQUE: f64 = 1.0 / 8.0;

/// Krawczyk's test on the box's coefficients (in the box's own parameters
/// `x ∈ [0, 1]²`): with `c` the centre, `J` an interval enclosure of the
/// Jacobian of `F = (α, β)` over the box (from the derivative nets: `p` times
/// the range of the differences in the first parameter, `q` times in the
/// second) and `Y` the inverse of its midpoint,
/// `K = c − Y·F(c) + (I − Y·J)·([0, 1]² − c)`. If `K` lies strictly inside
/// the box, the box holds exactly one root of `F` (Krawczyk 1969; Moore,
/// Kearfott & Cloud, *Introduction to Interval Analysis*, §8.2). Every
/// coefficient carries `bound` of rounding, which widens `F(c)` and `J`;
/// `K` must clear the box's sides by `1e-6`.
// Index loops mirror the matrix formulas.
#[allow(clippy::needless_range_loop)]
fn unique_root(coef: &[[f64; 4]], p: usize, q: usize, bound: f64) -> bool {
    let cols = q + 1;
    // Interval Jacobian: rows α, β; columns ∂/∂x₀ (rows of the net), ∂/∂x₁.
    let mut jac = [[(f64::INFINITY, f64::NEG_INFINITY); 2]; 2];
    let widen = |r: &mut (f64, f64), x: f64| {
        r.0 = r.0.min(x);
        r.1 = r.1.max(x);
    };
    for i in 0..=p {
        for j in 0..=q {
            let c = coef[i * cols + j];
            for f in 0..2 {
                if i < p {
                    widen(
                        &mut jac[f][0],
                        p as f64 * (coef[(i + 1) * cols + j][f] - c[f]),
                    );
                }
                if j < q {
                    widen(
                        &mut jac[f][1],
                        q as f64 * (coef[i * cols + j + 1][f] - c[f]),
                    );
                }
            }
        }
    }
    for row in jac.iter_mut() {
        for (k, r) in row.iter_mut().enumerate() {
            let degree = if k == 0 { p } else { q };
            if degree == 0 {
                *r = (0.0, 0.0);
            }
            let pad = 2.0 * degree as f64 * bound;
            *r = (r.0 - pad, r.1 + pad);
        }
    }
    // F at the centre: de Casteljau at ½ in both parameters.
    if p + 1 > 32 || cols > 32 {
        return false;
    }
    let mut centre = [0.0_f64; 2];
    for (f, value) in centre.iter_mut().enumerate() {
        let mut row_values = [0.0_f64; 32];
        for (i, slot) in row_values.iter_mut().enumerate().take(p + 1) {
            let mut w = [0.0_f64; 32];
            for j in 0..cols {
                w[j] = coef[i * cols + j][f];
            }
            *slot = half_value(&mut w[..cols]);
        }
        *value = half_value(&mut row_values[..p + 1]);
    }
    let mid = |r: (f64, f64)| 0.5 * (r.0 + r.1);
    let m = [
        [mid(jac[0][0]), mid(jac[0][1])],
        [mid(jac[1][0]), mid(jac[1][1])],
    ];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if det == 0.0 || !det.is_finite() {
        return false;
    }
    let y = [
        [m[1][1] / det, -m[0][1] / det],
        [-m[1][0] / det, m[0][0] / det],
    ];
    for i in 0..2 {
        // c − Y F(c), with F(c) ± bound.
        let yf = y[i][0] * centre[0] + y[i][1] * centre[1];
        let mut radius = (y[i][0].abs() + y[i][1].abs()) * bound;
        // (I − Y J)(x − c), x − c ∈ [−½, ½]².
        for k in 0..2 {
            let identity = if i == k { 1.0 } else { 0.0 };
            // (Y J)_{ik} = Σ_j Y_ij J_jk: an interval.
            let (mut lo, mut hi) = (0.0, 0.0);
            for j in 0..2 {
                let (a, b) = (y[i][j] * jac[j][k].0, y[i][j] * jac[j][k].1);
                lo += a.min(b);
                hi += a.max(b);
            }
            let magnitude = (identity - lo).abs().max((identity - hi).abs());
            radius += 0.5 * magnitude;
        }
        let centre_i = 0.5 - yf;
        if !(centre_i - radius > 1e-6 && centre_i + radius < 1.0 - 1e-6) {
            return false;
        }
    }
    true
}

/// The value at ½ of the Bernstein polynomial with coefficients `w`
/// (overwritten).
fn half_value(w: &mut [f64]) -> f64 {
    let n = w.len();
    for level in 1..n {
        for k in 0..n - level {
            w[k] = 0.5 * (w[k] + w[k + 1]);
        }
    }
    w[0]
}

/// Exchanges the contents of two equal-length slices.
fn swap_slices(a: &mut [[f64; 4]], b: &mut [[f64; 4]]) {
    for (x, y) in a.iter_mut().zip(b.iter_mut()) {
        std::mem::swap(x, y);
    }
}

/// The least distance along the ray (`γ/w`) the box's coefficients allow.
fn min_distance(coef: &[[f64; 4]]) -> f64 {
    coef.iter().fold(f64::INFINITY, |m, c| m.min(c[2] / c[3]))
}

/// Whether the box certainly holds no hit in the searched range: all `α`
/// (or all `β`) beyond `bound` of one sign, all distances `γ/w` below `lo`
/// or above `hi` (with slack for rounding), or all points `(αᵢⱼ, βᵢⱼ)` on
/// the far side of a line through the origin (perpendicular to their mean,
/// by more than the projection's rounding: `|g|₁ = 1`, so `2·bound`).
fn excluded(coef: &[[f64; 4]], bound: f64, lo: f64, hi: f64) -> bool {
    let (mut a_pos, mut a_neg, mut b_pos, mut b_neg) = (true, true, true, true);
    let (mut g_lo, mut g_hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for c in coef {
        a_pos &= c[0] > bound;
        a_neg &= c[0] < -bound;
        b_pos &= c[1] > bound;
        b_neg &= c[1] < -bound;
        let g = c[2] / c[3];
        g_lo = g_lo.min(g);
        g_hi = g_hi.max(g);
    }
    let slack = bound / coef.iter().fold(f64::INFINITY, |m, c| m.min(c[3]));
    if a_pos || a_neg || b_pos || b_neg || g_hi < lo - slack || g_lo > hi + slack {
        return true;
    }
    // A separating direction in the (α, β) plane: the mean of the points.
    // If every point lies beyond the line through the origin perpendicular
    // to it (by more than the rounding of the projection), their hull, and
    // so every value of (α, β) on the box, misses the origin.
    let (mut ga, mut gb) = (0.0, 0.0);
    for c in coef {
        ga += c[0];
        gb += c[1];
    }
    let norm = ga.abs() + gb.abs();
    if !(norm > 0.0 && norm.is_finite()) {
        return false;
    }
    let (ga, gb) = (ga / norm, gb / norm);
    coef.iter().all(|c| ga * c[0] + gb * c[1] > 2.0 * bound)
}

/// Splits the box coefficients `parent` at the middle of `s` (rows) or of
/// `t` (columns): `parent` receives the first half, `child` the second.
fn halve(parent: &mut [[f64; 4]], child: &mut [[f64; 4]], p: usize, q: usize, split_s: bool) {
    let cols = q + 1;
    child.copy_from_slice(parent);
    let (count, len, stride, step): (usize, usize, usize, usize) = if split_s {
        (cols, p + 1, 1, cols)
    } else {
        (p + 1, cols, cols, 1)
    };
    for line in 0..count {
        let at = |k: usize| line * stride + k * step;
        // de Casteljau at ½: the left half's coefficients are the first
        // entries of each level, the right half's the last.
        let mut work = [[0.0_f64; 4]; 32];
        let mut heap = Vec::new();
        let w: &mut [[f64; 4]] = if len <= 32 {
            &mut work[..len]
        } else {
            heap.resize(len, [0.0; 4]);
            &mut heap
        };
        for (k, slot) in w.iter_mut().enumerate() {
            *slot = parent[at(k)];
        }
        for level in 0..len {
            parent[at(level)] = w[0];
            child[at(len - 1 - level)] = w[len - 1 - level];
            for k in 0..len - 1 - level {
                let next = w[k + 1];
                for (x, y) in w[k].iter_mut().zip(next) {
                    *x = 0.5 * (*x + y);
                }
            }
        }
    }
}

/// The ray in the frame the search uses, and the Newton settings.
struct Frame {
    o: Vector3<f64>,
    dn: f64,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    dh: Vector3<f64>,
    accept: f64,
    target: f64,
    iterations: u32,
    /// Hits at or below this ray parameter are the origin's own.
    t_floor: f64,
}

/// Newton's method on `(e₁·(S − o), e₂·(S − o)) = 0` over `patch` (number
/// `k`, with `cols` control points a row) from the
/// centre of `cell` (then its corners); the hit if a start converges to a
/// point of the patch within the acceptance.
fn polish(patch: &Patch, k: usize, cols: usize, f: &Frame, cell: Cell) -> Option<PatchHit> {
    let starts = [
        (0.5 * (cell.s.0 + cell.s.1), 0.5 * (cell.t.0 + cell.t.1)),
        (cell.s.0, cell.t.0),
        (cell.s.1, cell.t.1),
        (cell.s.0, cell.t.1),
        (cell.s.1, cell.t.0),
    ];
    for (s0, t0) in starts {
        let (mut s, mut t) = (s0, t0);
        for _ in 0..f.iterations.max(8) {
            let jet = tensor_jet(&patch.net, cols, s.clamp(-0.5, 1.5), t.clamp(-0.5, 1.5), 1);
            let (h, hs, ht) = (jet[0][0], jet[1][0], jet[0][1]);
            let x = h.wp / h.w;
            let xs = (hs.wp - x * hs.w) / h.w;
            let xt = (ht.wp - x * ht.w) / h.w;
            let r = x - f.o;
            let (fa, fb) = (f.e1.dot(&r), f.e2.dot(&r));
            let (j00, j01, j10, j11) = (f.e1.dot(&xs), f.e1.dot(&xt), f.e2.dot(&xs), f.e2.dot(&xt));
            let det = j00 * j11 - j01 * j10;
            let residual = (fa * fa + fb * fb).sqrt();
            if residual <= f.target.max(f.accept * 1e-3) || det == 0.0 || !det.is_finite() {
                break;
            }
            let ds = (fa * j11 - fb * j01) / det;
            let dt = (fb * j00 - fa * j10) / det;
            s -= ds;
            t -= dt;
            if !(s.is_finite() && t.is_finite()) || (ds.abs() < 1e-17 && dt.abs() < 1e-17) {
                break;
            }
        }
        if !((-SLACK..=1.0 + SLACK).contains(&s) && (-SLACK..=1.0 + SLACK).contains(&t)) {
            continue;
        }
        let (s, t) = (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
        let jet = tensor_jet(&patch.net, cols, s, t, 0);
        let x = jet[0][0].wp / jet[0][0].w;
        let r = x - f.o;
        let along = f.dh.dot(&r);
        let off = (r - f.dh * along).norm();
        if off <= f.accept {
            return Some(PatchHit {
                patch: k,
                t: along / f.dn,
                u: patch.u.0 + (patch.u.1 - patch.u.0) * s,
                v: patch.v.0 + (patch.v.1 - patch.v.0) * t,
            });
        }
    }
    None
}

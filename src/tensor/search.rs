//! Ray intersection for tensor-product surfaces by Bézier clipping and
//! subdivision of the ray's two plane distances.
//!
//! The ray `o + t·d` is the intersection of two planes through it, with unit
//! normals `e₁`, `e₂` perpendicular to `d`. On a rational Bézier patch
//! `S = A/w` (`A = Σ wᵢⱼPᵢⱼBᵢBⱼ`, `w = Σ wᵢⱼBᵢBⱼ > 0`) the ray meets the
//! surface where both `α = e₁·(A − w·o)` and `β = e₂·(A − w·o)` vanish; both
//! are tensor Bernstein polynomials with coefficients `e·wᵢⱼ(Pᵢⱼ − o)`,
//! computed once per ray and patch, and `γ = d̂·(A − w·o)` gives the distance
//! along the ray, `γ/w`. Every coefficient carries a rounding bound that
//! grows with each subdivision that made it.
//!
//! A parameter box is discarded when all its `α` coefficients, or all its
//! `β` coefficients, are of one sign beyond their rounding bound (the convex
//! hull property: the polynomial then has that sign on the whole box), when
//! the points `(αᵢⱼ, βᵢⱼ)` all lie beyond a line through the origin, or when
//! all its `γ/w` ratios lie outside the range still searched. A box that
//! survives is first *clipped* ([`clip`]; Nishita, Sederberg & Nakajima,
//! "Ray tracing trimmed rational surface patches", SIGGRAPH 1990): in each
//! parameter, the convex hull of a distance function's control points
//! bounds the range where it can vanish, and the box shrinks to that range
//! (de Casteljau restriction). Clipping converges quadratically to a
//! transversal root; where it stalls (the box keeps more than
//! [`CLIP_ENOUGH`] of its area: several roots, or a tangency) the box is
//! halved in its wider parameter, the nearer half searched first. A box at
//! most [`TRY_UNIQUE`] wide that Krawczyk's test proves to hold exactly one
//! root ([`unique_root`]) is finished by Newton's method on the 2 × 2
//! system `(e₁·(S − o), e₂·(S − o)) = 0` from its centre (then its
//! corners), and the point is a hit if it lands in the box on the surface
//! within the tolerance; a box below [`SMALL`] on both sides is handed to
//! Newton's method without that proof.
//! The patches, cut once into nearly bilinear pieces
//! ([`SearchPieces`](super::patch_pieces::SearchPieces)), are visited
//! nearest first through their hierarchy ([`Bvh`]) and the search
//! stops at the best hit so far.
//!
//! No root is discarded: a box is dropped or shrunk only where a certain
//! sign rules a hit out, so every hit lies in a box that is proven to hold
//! one root or is small; a transversal hit is then found by Newton's method
//! from within that box. A ray that grazes the surface (a double root) may
//! be found or not, as for the other intersectors; no hit is reported that
//! is not on the surface to the tolerance.

use super::patch::{Patch, tensor_jet};
use crate::curve::unit_direction;
use crate::ray::acceptance::Acceptance;
use crate::ray::bvh::{Bvh, Slab};
use crate::{Hit, Ray, Tolerance};
use nalgebra::{Point3, Unit, Vector3};

/// Boxes narrower than this (in a patch's own parameters, both sides) are
/// handed to Newton's method.
const SMALL: f64 = 1.0 / (1u64 << 14) as f64;

/// How far outside its patch (in the patch's parameters) Newton may land and
/// still count: rounding only.
const SLACK: f64 = 1e-9;

/// Boxes the depth-first search leaves for later at once: one per halving
/// of the box at hand, which is halved at most `2·log₂(1/SMALL)` times
/// before it is small.
const STACK: usize = 2 * 14 + 4;

/// A hit in a surface's own parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PatchHit {
    /// Index of the patch hit.
    pub(crate) patch: usize,
    pub(crate) t: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
}

impl PatchHit {
    /// The crate's hit for `ray`, with the surface's `point` and `normal`
    /// at `(u, v)`; where the surface has no tangent plane the normal faces
    /// the ray.
    pub(crate) fn to_hit(
        self,
        ray: &Ray,
        point: Point3<f64>,
        normal: Option<Unit<Vector3<f64>>>,
    ) -> Option<Hit> {
        let normal = normal.or_else(|| unit_direction(-ray.dir))?;
        Some(Hit {
            t: self.t,
            point,
            normal,
            uv: (self.u, self.v),
        })
    }
}

/// One box of the search: its parameter ranges within the patch and how
/// many subdivisions made its coefficients `(α, β, γ, w)`.
#[derive(Debug, Clone, Copy)]
struct Cell {
    s: (f64, f64),
    t: (f64, f64),
    /// Subdivisions since the patch's own coefficients (each adds rounding).
    steps: u32,
}

/// Control points per patch whose search runs on the stack (bicubic).
const STACK_NET: usize = 16;

/// The patches a search runs over: their common degrees, the patches and
/// the hierarchy over them.
#[derive(Clone, Copy)]
pub(crate) struct PatchSet<'a> {
    pub(crate) degrees: (usize, usize),
    pub(crate) patches: &'a [Patch],
    pub(crate) tree: &'a Bvh,
    /// Largest control-point coordinate: the scale of the tolerance.
    pub(crate) scale: f64,
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
    let scale = set.scale.max(f64::MIN_POSITIVE);
    let acceptance = Acceptance::certified(&tol, scale, &o);
    // Hits within the position uncertainty of the origin are the origin.
    let t_floor = acceptance.t_floor(t_min, dn);
    let (p, q) = set.degrees;
    let n = (p + 1) * (q + 1);
    let frame = Frame {
        o,
        dn,
        e1,
        e2,
        dh,
        acceptance,
        // Every hit is polished to full precision, whatever the tolerance.
        target: Tolerance::default().relative * scale,
        iterations: tol.max_iterations,
        t_floor,
        t_min,
    };
    let mut on_stack = [[0.0_f64; 4]; 3 * STACK_NET];
    let mut on_heap = Vec::new();
    let buf: &mut [[f64; 4]] = if n <= STACK_NET {
        &mut on_stack[..3 * n]
    } else {
        on_heap.resize(3 * n, [0.0; 4]);
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
/// searched with the scratch space `buf` (`3·n` entries for `n` control
/// points: the patch's coefficients, the box at hand's, a half box's).
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
    // Coefficients (α, β, γ, w) of the patch and, for each of α, β, γ
    // (`e · (wP − w·o)` for its unit vector `e`), the size that bounds its
    // coefficients and their rounding, `Σₖ |eₖ|(|wPₖ| + |oₖ|w)`, and the
    // same per unit weight (what bounds the rounding of a point's
    // coordinate `(α, β, γ)/w`, a ratio of convex combinations, whatever
    // the weights). Each function gets its own bound, so that a coordinate
    // the ray's planes do not see (a control point far along the ray) does
    // not blur them.
    let mut magnitude = [0.0_f64; 3];
    let mut spatial = [0.0_f64; 3];
    let axes = [e1.abs(), e2.abs(), dh.abs()];
    let oa = o.abs();
    for (slot, h) in buf[..n].iter_mut().zip(&patch.net) {
        let rel = h.wp - o * h.w;
        *slot = [e1.dot(&rel), e2.dot(&rel), dh.dot(&rel), h.w];
        let size = h.wp.abs() + oa * h.w;
        for f in 0..3 {
            let m = axes[f].dot(&size);
            magnitude[f] = magnitude[f].max(m);
            spatial[f] = spatial[f].max(m / h.w);
        }
    }
    // Rounding of the coefficients as computed, and what each subdivision
    // (de Casteljau: convex combinations, `max(p, q)` levels of at most
    // three roundings each) adds.
    let err = magnitude.map(|m| 8.0 * f64::EPSILON * m);
    let step = magnitude.map(|m| 2.0 * (p.max(q) + 1) as f64 * f64::EPSILON * m);
    let per_weight: [f64; 3] =
        std::array::from_fn(|f| spatial[f] / magnitude[f].max(f64::MIN_POSITIVE));
    // Boxes still to search (their coefficients are made again from the
    // patch's when their turn comes); the box at hand is in `work`.
    let mut pending = [Cell {
        s: (0.0, 1.0),
        t: (0.0, 1.0),
        steps: 0,
    }; STACK];
    let mut len = 1;
    let (own, rest) = buf.split_at_mut(n);
    let (work, spare) = rest.split_at_mut(n);
    let spare = &mut spare[..n];
    'cells: while len > 0 {
        len -= 1;
        let mut cell = pending[len];
        work.copy_from_slice(own);
        if cell.s != (0.0, 1.0) {
            restrict_lines(work, p, q, true, cell.s);
            cell.steps += 2;
        }
        if cell.t != (0.0, 1.0) {
            restrict_lines(work, p, q, false, cell.t);
            cell.steps += 2;
        }
        loop {
            let bound: Bounds = std::array::from_fn(|f| err[f] + step[f] * cell.steps as f64);
            if excluded(work, bound, t_floor * dn, t_best * dn) {
                continue 'cells;
            }
            let (ws, wt) = (cell.s.1 - cell.s.0, cell.t.1 - cell.t.0);
            if ws <= SMALL && wt <= SMALL {
                if let Some(hit) = polish(patch, k, q + 1, frame, cell) {
                    if hit.t > t_floor && hit.t < t_best {
                        t_best = hit.t;
                        best = Some(hit);
                    }
                }
                continue 'cells;
            }
            // A box whose image is within the acceptance of one point (a
            // thin box at a collapsed edge, where the Jacobian is singular
            // and neither clipping across the edge nor Krawczyk's test can
            // finish; or a whole patch no bigger than the rounding of its
            // coordinates; tried on those only, as it costs a pass of
            // divisions): its corner `(s₀, t₀)`, which is the surface point
            // at that corner, is the hit if it is within the acceptance of
            // the ray. If the box held a root, the corner would be within
            // the box's extent of it, so a corner farther off the ray
            // rules a root out.
            let whole = cell.s == (0.0, 1.0) && cell.t == (0.0, 1.0);
            let noise = || (0..3).map(|f| bound[f] * per_weight[f]).sum();
            if (whole || ws <= SMALL || wt <= SMALL)
                && extent(work, noise()) <= frame.acceptance.distance
            {
                let c = work[0];
                let off = c[0].hypot(c[1]) / c[3];
                let t_hit = c[2] / c[3] / dn;
                if frame.acceptance.accepts(off) && t_hit > t_floor && t_hit < t_best {
                    t_best = t_hit;
                    best = Some(PatchHit {
                        patch: k,
                        t: t_hit,
                        u: patch.u.0 + (patch.u.1 - patch.u.0) * cell.s.0,
                        v: patch.v.0 + (patch.v.1 - patch.v.0) * cell.t.0,
                    });
                }
                continue 'cells;
            }
            // A box that holds exactly one root (Krawczyk's test) is
            // finished by Newton's method if it lands inside the box.
            if ws.max(wt) <= TRY_UNIQUE && unique_root(work, p, q, [bound[0], bound[1]]) {
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
                        continue 'cells;
                    }
                }
            }
            // Bézier clipping: the parameter ranges outside which the
            // hull of a distance function stays off zero hold no root.
            let Some((s_range, t_range)) = clip(work, (p, q), [bound[0], bound[1]]) else {
                continue 'cells;
            };
            let kept = (s_range.1 - s_range.0) * (t_range.1 - t_range.0);
            let (new_s, new_t) = (within(cell.s, s_range), within(cell.t, t_range));
            // Clip again while it pays and the box still shrinks in
            // floating point.
            if kept <= CLIP_ENOUGH && (new_s != cell.s || new_t != cell.t) {
                if new_s != cell.s {
                    restrict_lines(work, p, q, true, s_range);
                    cell.s = new_s;
                    cell.steps += 2;
                }
                if new_t != cell.t {
                    restrict_lines(work, p, q, false, t_range);
                    cell.t = new_t;
                    cell.steps += 2;
                }
                if cell.steps > FRESH_AFTER {
                    // Restricted so often that its rounding bound grows:
                    // made again from the patch's own coefficients.
                    work.copy_from_slice(own);
                    restrict_lines(work, p, q, true, cell.s);
                    restrict_lines(work, p, q, false, cell.t);
                    cell.steps = 4;
                }
                continue;
            }
            // Clipping stalls (several roots, or a tangency): halve in the
            // wider parameter, go on with the nearer half and leave the
            // other for later.
            let split_s = ws >= wt;
            halve(work, spare, p, q, split_s);
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
                steps: 0,
            };
            // `work` now holds the first half, `spare` the second.
            let near_first = min_distance(work) <= min_distance(spare);
            let (near, far) = if near_first {
                (first, second)
            } else {
                work.copy_from_slice(spare);
                (second, first)
            };
            if len < STACK {
                pending[len] = make(far);
                len += 1;
            } else {
                // Out of room (not seen: boxes split at most
                // 2·log₂(1/SMALL) times): the far half is finished now
                // by Newton's method, unproven.
                if let Some(hit) = polish(patch, k, q + 1, frame, make(far)) {
                    if hit.t > t_floor && hit.t < t_best {
                        t_best = hit.t;
                        best = Some(hit);
                    }
                }
            }
            cell = Cell {
                steps: cell.steps + 1,
                ..make(near)
            };
        }
    }
    best
}

/// A box made by more subdivisions than this is made again from its patch's
/// coefficients (four), which keeps its rounding bound small.
const FRESH_AFTER: u32 = 24;

/// A clipped box is clipped again (rather than halved) while it keeps at
/// most this fraction of its area.
const CLIP_ENOUGH: f64 = 0.64;

/// A bound on the diameter of the box's image: the sum of the ranges of
/// its control points' coordinates `(α, β, γ)/w` in the ray's orthonormal
/// frame, widened by their rounding (`noise` in all, in those units).
fn extent(coef: &[[f64; 4]], noise: f64) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for c in coef {
        for a in 0..3 {
            let x = c[a] / c[3];
            lo[a] = lo[a].min(x);
            hi[a] = hi[a].max(x);
        }
    }
    (0..3).map(|a| hi[a] - lo[a]).sum::<f64>() + 2.0 * noise
}

/// The sub-range `r` (of `[0, 1]`) of the interval `x`.
fn within(x: (f64, f64), r: (f64, f64)) -> (f64, f64) {
    let w = x.1 - x.0;
    let hi = if r.1 >= 1.0 { x.1 } else { x.0 + w * r.1 };
    (x.0 + w * r.0, hi)
}

/// Bézier clipping (Nishita, Sederberg & Nakajima 1990) of a box's
/// coefficients: the ranges `(s, t)` (of the box's own `[0, 1]²`) outside
/// which the box holds no root of `(α, β)`, or `None` if it holds none.
///
/// For `s`, `d = n·(α, β)` with `n` perpendicular to the net's mean
/// direction along `t` (so that `d` varies mostly with `s`); its
/// coefficients `dᵢⱼ`, widened by their rounding, give points
/// `(i/p, dᵢⱼ)` whose convex hull contains the graph of `d` over each line
/// of constant `t` (the convex hull property in `s`, for every `t` at once:
/// the `dᵢ(t)` are convex combinations of the `dᵢⱼ`). Where the hull misses
/// `d = 0` there is no root. The same with the roles of `s` and `t`
/// exchanged. The ends are widened by `8ε` for the rounding of the hull's
/// crossings.
fn clip(
    coef: &[[f64; 4]],
    (p, q): (usize, usize),
    bound: [f64; 2],
) -> Option<((f64, f64), (f64, f64))> {
    let cols = q + 1;
    let at = |i: usize, j: usize| coef[i * cols + j];
    // Mean direction of the net along t (last column minus first) and
    // along s (last row minus first).
    let (mut vt, mut vs) = ([0.0_f64; 2], [0.0_f64; 2]);
    for i in 0..=p {
        let (a, b) = (at(i, 0), at(i, q));
        vt[0] += b[0] - a[0];
        vt[1] += b[1] - a[1];
    }
    for j in 0..=q {
        let (a, b) = (at(0, j), at(p, j));
        vs[0] += b[0] - a[0];
        vs[1] += b[1] - a[1];
    }
    let mut s_range = if p == 0 {
        (0.0, 1.0)
    } else {
        clip_line(coef, p, q, true, normal_to(vt), bound)?
    };
    let mut t_range = if q == 0 {
        (0.0, 1.0)
    } else {
        clip_line(coef, p, q, false, normal_to(vs), bound)?
    };
    let kept = (s_range.1 - s_range.0) * (t_range.1 - t_range.0);
    if kept > CLIP_ENOUGH {
        // Where the image's directions along s and t are nearly parallel
        // (near a collapsed corner, or a fold) the lines across them say
        // little; the lines along them may say more. Both ranges hold
        // every root, so their intersection does.
        let meet = |a: (f64, f64), b: (f64, f64)| {
            let r = (a.0.max(b.0), a.1.min(b.1));
            (r.0 <= r.1).then_some(r)
        };
        if p > 0 {
            let along = normal_to(normal_to(vt));
            s_range = meet(s_range, clip_line(coef, p, q, true, along, bound)?)?;
        }
        if q > 0 {
            let along = normal_to(normal_to(vs));
            t_range = meet(t_range, clip_line(coef, p, q, false, along, bound)?)?;
        }
    }
    Some((s_range, t_range))
}

/// A unit vector perpendicular to `v` (`(1, 0)` if `v` vanishes).
fn normal_to(v: [f64; 2]) -> [f64; 2] {
    let norm = v[0].hypot(v[1]);
    if norm > 0.0 && norm.is_finite() {
        [-v[1] / norm, v[0] / norm]
    } else {
        [1.0, 0.0]
    }
}

/// The range in `s` (`along_s`) or in `t` where the hull of the points
/// `(index/degree, n·(α, β))` meets zero (see [`clip`]); `None` if nowhere.
fn clip_line(
    coef: &[[f64; 4]],
    p: usize,
    q: usize,
    along_s: bool,
    n: [f64; 2],
    bound: [f64; 2],
) -> Option<(f64, f64)> {
    let cols = q + 1;
    let (degree, other) = if along_s { (p, q) } else { (q, p) };
    // Per abscissa, the least and greatest ordinate, widened by the
    // coefficients' rounding and the projection's.
    let pad = n[0].abs() * bound[0] + n[1].abs() * bound[1];
    let mut low = [0.0_f64; 33];
    let mut high = [0.0_f64; 33];
    if degree >= low.len() {
        return Some((0.0, 1.0));
    }
    for i in 0..=degree {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for j in 0..=other {
            let c = if along_s {
                coef[i * cols + j]
            } else {
                coef[j * cols + i]
            };
            let d = n[0] * c[0] + n[1] * c[1];
            lo = lo.min(d);
            hi = hi.max(d);
        }
        let slop = pad + 2.0 * f64::EPSILON * lo.abs().max(hi.abs());
        low[i] = lo - slop;
        high[i] = hi + slop;
    }
    // The hull is bounded below by the lower hull of the lows and above by
    // the upper hull of the highs; it meets zero where the first is ≤ 0
    // and the second ≥ 0.
    let below = non_positive_range(&low[..=degree])?;
    for h in high[..=degree].iter_mut() {
        *h = -*h;
    }
    let above = non_positive_range(&high[..=degree])?;
    let (from, to) = (below.0.max(above.0), below.1.min(above.1));
    if from > to {
        return None;
    }
    let widen = 8.0 * f64::EPSILON;
    Some(((from - widen).max(0.0), (to + widen).min(1.0)))
}

/// The range of `x ∈ [0, 1]` where the lower convex hull `L` of the points
/// `(i/n, ys[i])` (`n = ys.len() − 1 ≥ 1`) is `≤ 0`, or `None` if `L > 0`
/// throughout. `L` is convex, so the range is an interval, and `L` is least
/// at a vertex.
fn non_positive_range(ys: &[f64]) -> Option<(f64, f64)> {
    let n = ys.len() - 1;
    let x = |i: usize| i as f64 / n as f64;
    // Monotone chain (Andrew 1979): the lower hull's vertices, left to right.
    let mut hull = [0_usize; 33];
    let mut len = 0;
    for i in 0..=n {
        while len >= 2 {
            let (a, b) = (hull[len - 2], hull[len - 1]);
            let cross = (x(b) - x(a)) * (ys[i] - ys[a]) - (ys[b] - ys[a]) * (x(i) - x(a));
            if cross <= 0.0 {
                len -= 1;
            } else {
                break;
            }
        }
        hull[len] = i;
        len += 1;
    }
    let hull = &hull[..len];
    let first = hull.iter().position(|&i| ys[i] <= 0.0)?;
    let last = hull.iter().rposition(|&i| ys[i] <= 0.0)?;
    let crossing = |a: usize, b: usize| x(a) + (x(b) - x(a)) * (ys[a] / (ys[a] - ys[b]));
    let from = if first == 0 {
        0.0
    } else {
        crossing(hull[first - 1], hull[first])
    };
    let to = if last == len - 1 {
        1.0
    } else {
        crossing(hull[last], hull[last + 1])
    };
    Some((from, to))
}

/// Replaces the box coefficients by those of the sub-box `r` (of
/// `[0, 1]`) in `s` (`along_s`) or in `t`: each line of coefficients is
/// split at `r.1` (keeping the left part), then at `r.0/r.1` (keeping the
/// right part).
fn restrict_lines(coef: &mut [[f64; 4]], p: usize, q: usize, along_s: bool, r: (f64, f64)) {
    let cols = q + 1;
    let (count, len, stride, step): (usize, usize, usize, usize) = if along_s {
        (cols, p + 1, 1, cols)
    } else {
        (p + 1, cols, cols, 1)
    };
    let mut work = [[0.0_f64; 4]; 33];
    if len > work.len() {
        return restrict_long_lines(coef, count, len, stride, step, r);
    }
    for line in 0..count {
        let at = |k: usize| line * stride + k * step;
        let w = &mut work[..len];
        for (k, slot) in w.iter_mut().enumerate() {
            *slot = coef[at(k)];
        }
        if r.1 < 1.0 {
            split_keep(w, r.1, true);
        }
        if r.0 > 0.0 {
            split_keep(w, r.0 / r.1, false);
        }
        for (k, slot) in w.iter().enumerate() {
            coef[at(k)] = *slot;
        }
    }
}

/// [`restrict_lines`] for lines longer than its stack buffer.
fn restrict_long_lines(
    coef: &mut [[f64; 4]],
    count: usize,
    len: usize,
    stride: usize,
    step: usize,
    r: (f64, f64),
) {
    let mut w = vec![[0.0_f64; 4]; len];
    for line in 0..count {
        for (k, slot) in w.iter_mut().enumerate() {
            *slot = coef[line * stride + k * step];
        }
        if r.1 < 1.0 {
            split_keep(&mut w, r.1, true);
        }
        if r.0 > 0.0 {
            split_keep(&mut w, r.0 / r.1, false);
        }
        for (k, slot) in w.iter().enumerate() {
            coef[line * stride + k * step] = *slot;
        }
    }
}

/// De Casteljau at `x` on the Bernstein coefficients `w` (in place): `w`
/// becomes the coefficients on `[0, x]` (`left`) or on `[x, 1]`.
fn split_keep(w: &mut [[f64; 4]], x: f64, left: bool) {
    let n = w.len();
    if left {
        // Level by level from the right: w[k] holds the k-th left
        // coefficient once level k is done.
        for level in 1..n {
            for k in (level..n).rev() {
                let (a, b) = (w[k - 1], w[k]);
                for c in 0..4 {
                    w[k][c] = a[c] + x * (b[c] - a[c]);
                }
            }
        }
    } else {
        for level in 1..n {
            for k in 0..n - level {
                let (a, b) = (w[k], w[k + 1]);
                for c in 0..4 {
                    w[k][c] = a[c] + x * (b[c] - a[c]);
                }
            }
        }
    }
}

/// Rounding bounds of a box's `α`, `β` and `γ` coefficients.
type Bounds = [f64; 3];

/// Boxes at most this wide (in both parameters) try the uniqueness test.
const TRY_UNIQUE: f64 = 1.0 / 8.0;

/// Krawczyk's test on the box's coefficients (in the box's own parameters
/// `x ∈ [0, 1]²`): with `c` the centre, `J` an interval enclosure of the
/// Jacobian of `F = (α, β)` over the box (from the derivative nets: `p` times
/// the range of the differences in the first parameter, `q` times in the
/// second) and `Y` the inverse of its midpoint,
/// `K = c − Y·F(c) + (I − Y·J)·([0, 1]² − c)`. If `K` lies strictly inside
/// the box, the box holds exactly one root of `F` (Krawczyk 1969; Moore,
/// Kearfott & Cloud, *Introduction to Interval Analysis*, §8.2); `Y` may
/// be any matrix, so its own rounding does not matter. The enclosures are
/// widened for every rounding on the way: each coefficient carries `bound`
/// (so `F(c)` gains `bound` and `J` `2·degree·bound`), the differences of
/// `J` and the averages of `F(c)` (`p + q` levels) their own rounding, and
/// `K`'s sums and products `4ε` times the sum of their terms' magnitudes
/// (Higham, *Accuracy and Stability of Numerical Algorithms*, §3.1).
/// Beyond that, `K` must clear the box's sides by `1e-6`.
// Index loops mirror the matrix formulas.
#[allow(clippy::needless_range_loop)]
fn unique_root(coef: &[[f64; 4]], p: usize, q: usize, bound: [f64; 2]) -> bool {
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
    for (f, row) in jac.iter_mut().enumerate() {
        for (k, r) in row.iter_mut().enumerate() {
            let degree = if k == 0 { p } else { q };
            if degree == 0 {
                *r = (0.0, 0.0);
            }
            let pad = 2.0 * degree as f64 * bound[f];
            let own = 2.0 * f64::EPSILON * r.0.abs().max(r.1.abs());
            *r = (r.0 - pad - own, r.1 + pad + own);
        }
    }
    // F at the centre: de Casteljau at ½ in both parameters.
    if p + 1 > 32 || cols > 32 {
        return false;
    }
    let mut centre = [0.0_f64; 2];
    // Averages round by at most ε/2 of the largest coefficient each.
    let f_bound: [f64; 2] = std::array::from_fn(|f| {
        let largest = coef.iter().fold(0.0_f64, |m, c| m.max(c[f].abs()));
        bound[f] + 0.5 * (p + q) as f64 * f64::EPSILON * largest
    });
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
        // c − Y F(c), with F(c) ± f_bound.
        let yf = y[i][0] * centre[0] + y[i][1] * centre[1];
        let mut radius = y[i][0].abs() * f_bound[0] + y[i][1].abs() * f_bound[1];
        // Magnitudes of the terms summed, for their rounding.
        let mut terms = (y[i][0] * centre[0]).abs() + (y[i][1] * centre[1]).abs() + 0.5;
        // (I − Y J)(x − c), x − c ∈ [−½, ½]².
        for k in 0..2 {
            let identity = if i == k { 1.0 } else { 0.0 };
            // (Y J)_{ik} = Σ_j Y_ij J_jk: an interval.
            let (mut lo, mut hi) = (0.0, 0.0);
            for j in 0..2 {
                let (a, b) = (y[i][j] * jac[j][k].0, y[i][j] * jac[j][k].1);
                lo += a.min(b);
                hi += a.max(b);
                terms += a.abs().max(b.abs());
            }
            let magnitude = (identity - lo).abs().max((identity - hi).abs());
            radius += 0.5 * magnitude;
            terms += magnitude;
        }
        radius += 4.0 * f64::EPSILON * (terms + radius);
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

/// The least distance along the ray (`γ/w`) the box's coefficients allow.
fn min_distance(coef: &[[f64; 4]]) -> f64 {
    coef.iter().fold(f64::INFINITY, |m, c| m.min(c[2] / c[3]))
}

/// Whether the box certainly holds no hit in the searched range: all `α`
/// (or all `β`) beyond `bound` of one sign, all distances `γ/w` below `lo`
/// or above `hi` (with slack for rounding), or all points `(αᵢⱼ, βᵢⱼ)` on
/// the far side of a line through the origin (perpendicular to their mean,
/// by more than the projection's rounding: `|g|₁ = 1`, so `2·bound`).
fn excluded(coef: &[[f64; 4]], bound: Bounds, lo: f64, hi: f64) -> bool {
    let (mut a_pos, mut a_neg, mut b_pos, mut b_neg) = (true, true, true, true);
    let (mut g_lo, mut g_hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for c in coef {
        a_pos &= c[0] > bound[0];
        a_neg &= c[0] < -bound[0];
        b_pos &= c[1] > bound[1];
        b_neg &= c[1] < -bound[1];
        let g = c[2] / c[3];
        g_lo = g_lo.min(g);
        g_hi = g_hi.max(g);
    }
    let slack = bound[2] / coef.iter().fold(f64::INFINITY, |m, c| m.min(c[3]));
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
    let margin = 2.0 * (ga.abs() * bound[0] + gb.abs() * bound[1]);
    coef.iter().all(|c| ga * c[0] + gb * c[1] > margin)
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
    /// The residual within which a hit is accepted.
    acceptance: Acceptance,
    target: f64,
    iterations: u32,
    /// Hits at or below this ray parameter are the origin's own.
    t_floor: f64,
    /// The ray parameter searched from.
    t_min: f64,
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
        // The jet at the last point evaluated, if Newton stopped there.
        let mut last = None;
        for _ in 0..f.iterations.max(8) {
            let (sc, tc) = (s.clamp(-0.5, 1.5), t.clamp(-0.5, 1.5));
            let jet = tensor_jet(&patch.net, cols, sc, tc, 1);
            let (h, hs, ht) = (jet[0][0], jet[1][0], jet[0][1]);
            let x = h.wp / h.w;
            let xs = (hs.wp - x * hs.w) / h.w;
            let xt = (ht.wp - x * ht.w) / h.w;
            let r = x - f.o;
            let (fa, fb) = (f.e1.dot(&r), f.e2.dot(&r));
            let (j00, j01, j10, j11) = (f.e1.dot(&xs), f.e1.dot(&xt), f.e2.dot(&xs), f.e2.dot(&xt));
            let det = j00 * j11 - j01 * j10;
            let residual = (fa * fa + fb * fb).sqrt();
            if residual <= f.target || det == 0.0 || !det.is_finite() {
                last = Some((sc, tc, jet));
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
        let jet = match last {
            Some((sc, tc, jet)) if (sc, tc) == (s, t) => jet,
            _ => tensor_jet(&patch.net, cols, s, t, 1),
        };
        let (h, hs, ht) = (jet[0][0], jet[1][0], jet[0][1]);
        let x = h.wp / h.w;
        let r = x - f.o;
        let along = f.dh.dot(&r);
        let off = (r - f.dh * along).norm();
        // The point is uncertain by `accept` off the surface, so its ray
        // parameter by `accept/(|d|·cos)` for the angle of incidence: a
        // root that close to `t_min` is the ray's own start (a secondary
        // ray's origin on the surface), however grazing.
        let normal = ((hs.wp - x * hs.w) / h.w).cross(&((ht.wp - x * ht.w) / h.w));
        let cos = (f.dh.dot(&normal).abs() / normal.norm()).clamp(1e-6, 1.0);
        let own = along / f.dn - f.t_min
            <= f.acceptance.distance / (f.dn * if cos.is_nan() { 1.0 } else { cos });
        if f.acceptance.accepts(off) && !own {
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

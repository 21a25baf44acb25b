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
//! Newton's method without that proof, and so is a box below [`SMALL`] on
//! one side whose image is below [`SMALL`] of the patch's (a strip along a
//! collapsed edge, where the other parameter hardly moves the point).
//! The patches, cut once into nearly bilinear pieces
//! ([`SearchPieces`](super::search_pieces::SearchPieces)), are visited
//! nearest first through their four-wide hierarchy ([`WideBvh`]) and the
//! search stops at the best hit so far. Most polynomial pieces a ray
//! reaches never get to clipping: their projection certificate
//! ([`ProjectionCertificate`]) rules them out by a box in the piece's
//! frame, or proves that the ray meets the piece at most once and settles
//! it by Newton's method alone; clipping is the fallback for the rest
//! (grazing rays, collapsed edges, rational pieces).
//!
//! No root is discarded: a box is dropped or shrunk only where a certain
//! sign rules a hit out, so every hit lies in a box that is proven to hold
//! one root or is small; a transversal hit is then found by Newton's method
//! from within that box. A ray that grazes the surface (a double root) may
//! be found or not, as for the other intersectors; no hit is reported that
//! is not on the surface to the tolerance.

use super::clip::{CLIP_ENOUGH, clip, restrict_lines};
use super::krawczyk::{TRY_UNIQUE, unique_root};
use super::newton_polish::{Frame, SLACK, jet, polish};
use super::patch::{Patch, PatchHit};
use super::projection_certificate::{ProjectionCertificate, Settled};
use crate::ray::bvh::BoxRay;
use crate::ray::wide_bvh::WideBvh;
use crate::{Ray, Tolerance};
use nalgebra::Vector3;
use std::ops::ControlFlow;

/// Boxes narrower than this (in a patch's own parameters, both sides) are
/// handed to Newton's method.
const SMALL: f64 = 1.0 / (1u64 << 14) as f64;

/// Boxes the depth-first search leaves for later at once: one per halving
/// of the box at hand, which is halved at most `2·log₂(1/SMALL)` times
/// before it is small.
const PENDING_BOXES: usize = 2 * 14 + 4;

/// One box of the search: its parameter ranges within the patch and how
/// many subdivisions made its coefficients `(α, β, γ, w)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct SearchBox {
    pub(super) s: (f64, f64),
    pub(super) t: (f64, f64),
    /// Subdivisions since the patch's own coefficients (each adds rounding).
    pub(super) steps: u32,
}

/// Control points per patch whose search runs on the stack (bicubic).
const NET_ON_STACK: usize = 16;

/// The patches a search runs over: their common degrees, the patches and
/// the hierarchy over them.
#[derive(Clone, Copy)]
pub(crate) struct PatchSet<'a> {
    pub(crate) degrees: (usize, usize),
    pub(crate) patches: &'a [Patch],
    pub(crate) tree: &'a WideBvh,
    /// Each patch's projection certificate, if it has one.
    pub(crate) certificates: &'a [Option<ProjectionCertificate>],
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
    // NaN-safe: false when either is NaN.
    let ordered = t_min < t_max;
    if !ordered {
        return None;
    }
    let frame = Frame::new(ray, t_min, set.scale, tol)?;
    let t_floor = frame.t_floor;
    let mut scratch = Scratch::default();
    let mut best: Option<PatchHit> = None;
    set.tree
        .traverse(&BoxRay::new(ray), t_floor, t_max, |k, t_best| {
            if let Some(hit) = search_patch(set, k, &frame, &mut scratch, t_best) {
                best = Some(hit);
                return ControlFlow::Continue(hit.t);
            }
            ControlFlow::Continue(t_best)
        });
    match best {
        Some(hit) if hit.past_side => Some(across_the_side(set, ray, &frame, t_max, hit)),
        _ => best,
    }
}

/// Whether `ray` hits a patch of `set` with `t_min < t < t_max`: exactly
/// [`intersect`]`(…).is_some()`, but the traversal stops at the first patch
/// piece with a hit instead of going on for a nearer one (a hit past a
/// side is still a hit: [`intersect`] only moves it).
pub(crate) fn occluded(
    set: PatchSet<'_>,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    tol: &Tolerance,
) -> bool {
    // NaN-safe: false when either is NaN.
    let ordered = t_min < t_max;
    let Some(frame) = Frame::new(ray, t_min, set.scale, tol).filter(|_| ordered) else {
        return false;
    };
    let mut scratch = Scratch::default();
    let mut found = false;
    set.tree
        .traverse(&BoxRay::new(ray), frame.t_floor, t_max, |k, t_best| {
            if search_patch(set, k, &frame, &mut scratch, t_best).is_some() {
                found = true;
                return ControlFlow::Break(());
            }
            ControlFlow::Continue(t_best)
        });
    found
}

/// A hit whose Newton iterate ended just past its patch's side, moved onto
/// that side, lies off the ray by up to that gap times the surface's speed
/// (about 1e-12 of the size). The root is then inside a neighbouring piece
/// (of the same patch, or of the patch across a shared edge): the pieces
/// the ray enters within `NEIGHBOUR_WINDOW` of the hit are polished, and a
/// hit strictly inside one of them, at the same root (within
/// `SAME_ROOT`), replaces it.
fn across_the_side(
    set: PatchSet<'_>,
    ray: &Ray,
    frame: &Frame,
    t_max: f64,
    hit: PatchHit,
) -> PatchHit {
    let cols = set.degrees.1 + 1;
    let window = NEIGHBOUR_WINDOW * set.scale.max(frame.o.amax()) / frame.dn;
    let same = SAME_ROOT * set.scale.max(frame.o.amax()) / frame.dn;
    let (lo, hi) = (
        (hit.t - window).max(frame.t_floor),
        (hit.t + window).min(t_max),
    );
    let point = ray.at(hit.t).coords;
    let mut better = hit;
    set.tree.traverse(&BoxRay::new(ray), lo, hi, |j, t_best| {
        if j != hit.patch && better.past_side {
            // Newton starts at the point of the piece's sides nearest the
            // hit (the root lies just inside a side), so that it finds
            // this root and not another.
            let piece = &set.patches[j];
            let start = nearest_on_sides(piece, cols, &point);
            // Newton from just inside that point first (on a collapsed
            // side, as at a pole, the side point itself has no Jacobian),
            // then from the point.
            let inward = |x: f64| (x - INWARD, x + INWARD);
            let at = (clamp_range(inward(start.0)), clamp_range(inward(start.1)));
            let found = polish(piece, j, cols, frame, at);
            let fits = |h: &PatchHit| {
                !h.past_side && (h.t - hit.t).abs() <= same && h.t > frame.t_floor && h.t < t_max
            };
            if let Some(inside) = found.filter(fits) {
                better = inside;
            }
        }
        ControlFlow::Continue(t_best)
    });
    better
}

/// How far inside a piece's side Newton starts, in its parameters.
const INWARD: f64 = 1e-6;

/// A parameter range kept within `[0, 1]`.
fn clamp_range((a, b): (f64, f64)) -> (f64, f64) {
    (a.clamp(0.0, 1.0), b.clamp(0.0, 1.0))
}

/// The point `(s, t)` of the sides of `piece` (`cols` points a row)
/// nearest to `point`: the nearest of [`SIDE_SAMPLES`] samples a side,
/// refined by Newton's method on `(C(τ) − point)·C′(τ) = 0` along its side.
fn nearest_on_sides(piece: &Patch, cols: usize, point: &Vector3<f64>) -> (f64, f64) {
    let at = |s: f64, t: f64| {
        let [h, hs, ht] = jet(piece, cols, s, t);
        let x = h.wp / h.w;
        (x, (hs.wp - x * hs.w) / h.w, (ht.wp - x * ht.w) / h.w)
    };
    let mut best = ((0.5, 0.5), f64::INFINITY);
    // Each side: a fixed parameter and which one runs.
    for (fixed, along_s) in [(0.0, false), (1.0, false), (0.0, true), (1.0, true)] {
        let st = |tau: f64| if along_s { (tau, fixed) } else { (fixed, tau) };
        let mut tau = 0.0;
        let mut gap = f64::INFINITY;
        for k in 0..=SIDE_SAMPLES {
            let x = k as f64 / SIDE_SAMPLES as f64;
            let (s, t) = st(x);
            let d = (at(s, t).0 - point).norm();
            if d < gap {
                (gap, tau) = (d, x);
            }
        }
        for _ in 0..SIDE_STEPS {
            let (s, t) = st(tau);
            let (x, xs, xt) = at(s, t);
            let tangent = if along_s { xs } else { xt };
            let slope = tangent.norm_squared();
            if slope.is_nan() || slope <= 0.0 {
                break;
            }
            tau = (tau - (x - point).dot(&tangent) / slope).clamp(0.0, 1.0);
        }
        let (s, t) = st(tau);
        let d = (at(s, t).0 - point).norm();
        if d < best.1 {
            best = ((s, t), d);
        }
    }
    best.0
}

/// Samples a side of a piece for [`nearest_on_sides`], and Newton steps after.
const SIDE_SAMPLES: usize = 16;
const SIDE_STEPS: usize = 6;
/// How far along the ray (relative to the scale) pieces are looked for
/// around a hit found past its piece's side.
const NEIGHBOUR_WINDOW: f64 = 1e-6;
/// How close (relative to the scale) a neighbour's hit must be to stand
/// for the same root.
const SAME_ROOT: f64 = 1e-9;

/// The clipping search's scratch space for one ray, made when a piece
/// first needs it (most rays settle every piece they reach without it):
/// `3·n` entries for `n` control points (the patch's coefficients, the box
/// at hand's, a half box's), on the stack up to bicubic nets.
#[derive(Default)]
struct Scratch {
    on_stack: Option<[[f64; 4]; 3 * NET_ON_STACK]>,
    on_heap: Vec<[f64; 4]>,
}

impl Scratch {
    /// The space for nets of `n` points.
    fn get(&mut self, n: usize) -> &mut [[f64; 4]] {
        if n <= NET_ON_STACK {
            &mut self.on_stack.get_or_insert([[0.0; 4]; 3 * NET_ON_STACK])[..3 * n]
        } else {
            if self.on_heap.len() < 3 * n {
                self.on_heap.resize(3 * n, [0.0; 4]);
            }
            &mut self.on_heap[..3 * n]
        }
    }
}

/// The nearest hit on patch `k` of `set` with `frame.t_floor < t < t_best`:
/// settled by the piece's projection certificate where it can, by
/// clipping (in `scratch`) otherwise.
fn search_patch(
    set: PatchSet<'_>,
    k: usize,
    frame: &Frame,
    scratch: &mut Scratch,
    t_best: f64,
) -> Option<PatchHit> {
    let q = set.degrees.1;
    let patch = &set.patches[k];
    if let Some(certificate) = set.certificates.get(k).and_then(Option::as_ref) {
        match certificate.settle(patch, k, q + 1, frame, t_best) {
            Settled::Hit(hit) => return Some(hit),
            Settled::Nothing => return None,
            Settled::Unknown => {}
        }
    }
    let (p, q) = set.degrees;
    clip_search(set, k, frame, scratch.get((p + 1) * (q + 1)), t_best)
}

/// [`search_patch`] by Bézier clipping and subdivision alone.
pub(super) fn clip_search(
    set: PatchSet<'_>,
    k: usize,
    frame: &Frame,
    buf: &mut [[f64; 4]],
    t_best: f64,
) -> Option<PatchHit> {
    let (p, q) = set.degrees;
    let n = (p + 1) * (q + 1);
    let patch = &set.patches[k];
    let dn = frame.dn;
    let t_floor = frame.t_floor;
    let mut nearest = Nearest {
        t_floor,
        t_best,
        hit: None,
    };
    let (own, rest) = buf.split_at_mut(n);
    let Rounding {
        err,
        step,
        per_weight,
    } = coefficients(patch, frame, (p, q), own);
    // Boxes still to search (their coefficients are made again from the
    // patch's when their turn comes); the box at hand is in `work`.
    let mut pending = [SearchBox {
        s: (0.0, 1.0),
        t: (0.0, 1.0),
        steps: 0,
    }; PENDING_BOXES];
    let mut len = 1;
    // The extent of the patch's image, once a thin box needs it.
    let mut patch_image: Option<f64> = None;
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
            #[cfg(test)]
            tests::BOXES.with(|b| b.set(b.get() + 1));
            let bound: Bounds = std::array::from_fn(|f| err[f] + step[f] * cell.steps as f64);
            if excluded(work, bound, t_floor * dn, nearest.t_best * dn) {
                continue 'cells;
            }
            let (ws, wt) = (cell.s.1 - cell.s.0, cell.t.1 - cell.t.0);
            if ws <= SMALL && wt <= SMALL {
                if let Some(hit) = polish(patch, k, q + 1, frame, (cell.s, cell.t)) {
                    nearest.offer(hit);
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
            let thin = ws <= SMALL || wt <= SMALL;
            let image = if whole || thin {
                extent(work, noise())
            } else {
                f64::INFINITY
            };
            // A thin box whose image is as small, beside the patch's, as
            // a box below SMALL in both parameters of a regular patch:
            // a strip along a collapsed edge (where the other parameter
            // moves the point by almost nothing, so neither clipping nor
            // halving across it gets anywhere, and a ray through the
            // edge's point would otherwise be searched in 1/SMALL boxes).
            // It is finished as a small box is, by Newton's method.
            if thin && image > frame.acceptance.distance {
                let patch_image = *patch_image.get_or_insert_with(|| {
                    let own_noise: f64 = (0..3).map(|f| err[f] * per_weight[f]).sum();
                    extent(own, own_noise)
                });
                if image <= SMALL * patch_image {
                    if let Some(hit) = polish(patch, k, q + 1, frame, (cell.s, cell.t)) {
                        nearest.offer(hit);
                    }
                    continue 'cells;
                }
            }
            if image <= frame.acceptance.distance {
                decide_by_corner(&mut nearest, (patch, k, q + 1), work[0], &cell, frame);
                continue 'cells;
            }
            // A box that holds exactly one root (Krawczyk's test) is
            // finished by Newton's method if it lands inside the box.
            if ws.max(wt) <= TRY_UNIQUE && unique_root(work, p, q, [bound[0], bound[1]]) {
                if let Some(hit) = polish(patch, k, q + 1, frame, (cell.s, cell.t)) {
                    let s_hit = (hit.u - patch.u.0) / (patch.u.1 - patch.u.0);
                    let t_hit = (hit.v - patch.v.0) / (patch.v.1 - patch.v.0);
                    let inside = s_hit >= cell.s.0 - SLACK
                        && s_hit <= cell.s.1 + SLACK
                        && t_hit >= cell.t.0 - SLACK
                        && t_hit <= cell.t.1 + SLACK;
                    if inside {
                        nearest.offer(hit);
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
            // Clipping stalls (several roots, a tangency, or coefficients
            // that rounding blurs, as on a patch not much bigger than the
            // acceptance): a box whose image is already within the
            // acceptance of one point is decided by its corner, as above;
            // any other is halved in the wider parameter, the search going
            // on with the nearer half and leaving the other for later.
            if !(whole || thin) && extent(work, noise()) <= frame.acceptance.distance {
                decide_by_corner(&mut nearest, (patch, k, q + 1), work[0], &cell, frame);
                continue 'cells;
            }
            // A box all of whose image lies within the acceptance of the
            // ray (a patch lying along the ray, as a needle can): every
            // point of it is a hit, so its corners are offered at once (the
            // nearest is kept), and the halving goes on only while some of
            // the box could be nearer than that (the window prunes the
            // rest), instead of halving a box no clip can shrink down to
            // 2⁻¹⁴ on a side everywhere.
            if lateral(work) + noise() <= frame.acceptance.distance {
                let cols = q + 1;
                for (i, j) in [(0, 0), (0, q), (p, 0), (p, q)] {
                    let s_at = if i == 0 { cell.s.0 } else { cell.s.1 };
                    let t_at = if j == 0 { cell.t.0 } else { cell.t.1 };
                    let c = work[i * cols + j];
                    nearest.offer(corner_hit(patch, k, c, (s_at, t_at), dn));
                }
                // Corners on both sides of the floor: hits lie just past
                // it, and none can be nearer than the floor.
                let floor = (t_floor * dn, frame.acceptance.distance);
                // (The best may be another piece's: then this one has
                // nothing nearer by more than the acceptance either.)
                if let Some((c, st)) = hit_past_floor(work, (p, q), &cell, floor) {
                    nearest.offer(corner_hit(patch, k, c, st, dn));
                    if (nearest.t_best - t_floor) * dn <= floor.1 {
                        return nearest.hit;
                    }
                }
            }
            let split_s = ws >= wt;
            halve(work, spare, p, q, split_s);
            let (first, second) = if split_s {
                let mid = 0.5 * (cell.s.0 + cell.s.1);
                ((cell.s.0, mid), (mid, cell.s.1))
            } else {
                let mid = 0.5 * (cell.t.0 + cell.t.1);
                ((cell.t.0, mid), (mid, cell.t.1))
            };
            let make = |r: (f64, f64)| SearchBox {
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
            if len < PENDING_BOXES {
                pending[len] = make(far);
                len += 1;
            } else {
                // Out of room (not seen: boxes split at most
                // 2·log₂(1/SMALL) times): the far half is finished now
                // by Newton's method, unproven.
                let far = make(far);
                if let Some(hit) = polish(patch, k, q + 1, frame, (far.s, far.t)) {
                    nearest.offer(hit);
                }
            }
            cell = SearchBox {
                steps: cell.steps + 1,
                ..make(near)
            };
        }
    }
    nearest.hit
}

/// The hit at the corner `(s, t)` (in the patch's own parameters) of a
/// box whose control point there, `c = (α, β, γ, w)`, is that corner's
/// surface point: at `t = γ/(w·|d|)`.
fn corner_hit(patch: &Patch, k: usize, c: [f64; 4], (s, t): (f64, f64), dn: f64) -> PatchHit {
    PatchHit {
        patch: k,
        t: c[2] / c[3] / dn,
        u: patch.u.0 + (patch.u.1 - patch.u.0) * s,
        v: patch.v.0 + (patch.v.1 - patch.v.0) * t,
        st: (s, t),
        past_side: false,
    }
}

/// A box whose image is within the acceptance of one point, decided by its
/// first corner (control point `c`): that surface point is the hit if it
/// is within the acceptance of the ray; if the box held a root, the corner
/// would be within the box's extent of it, so a corner farther off rules
/// a root out. The corner is a hit within the acceptance only: Newton's
/// method from the box polishes it to full precision where it converges to
/// the same point (within the acceptance along the ray; at a pole the root
/// may lie at another `t` of the collapsed edge, even past the piece's side).
fn decide_by_corner(
    nearest: &mut Nearest,
    (patch, k, cols): (&Patch, usize, usize),
    c: [f64; 4],
    cell: &SearchBox,
    frame: &Frame,
) {
    let off = c[0].hypot(c[1]) / c[3];
    if frame.acceptance.accepts(off) {
        let corner = corner_hit(patch, k, c, (cell.s.0, cell.t.0), frame.dn);
        let same_point =
            |h: &PatchHit| (h.t - corner.t).abs() * frame.dn <= 2.0 * frame.acceptance.distance;
        // Unpolished, the corner is marked unfinished (as a hit past a
        // side is): the pieces beside it are polished for the root.
        let hit = polish(patch, k, cols, frame, (cell.s, cell.t))
            .filter(same_point)
            .unwrap_or(PatchHit {
                past_side: true,
                ..corner
            });
        nearest.offer(hit);
    }
}

/// The nearest hit so far and the window of ray parameters a new one must
/// fall in: `(t_floor, t_best)`.
struct Nearest {
    t_floor: f64,
    t_best: f64,
    hit: Option<PatchHit>,
}

impl Nearest {
    /// Keeps `hit` if it lies in the window: the one place a hit is taken.
    fn offer(&mut self, hit: PatchHit) {
        if hit.t > self.t_floor && hit.t < self.t_best {
            self.t_best = hit.t;
            self.hit = Some(hit);
        }
    }
}

/// Rounding bounds of a patch's coefficients for one ray: of the
/// coefficients as computed (`err`), what each subdivision adds (`step`),
/// and per unit weight (`per_weight`), for each of `α`, `β`, `γ`.
struct Rounding {
    err: [f64; 3],
    step: [f64; 3],
    per_weight: [f64; 3],
}

/// Writes the coefficients `(α, β, γ, w)` of `patch` (degrees `(p, q)`) for
/// the ray of `frame` into `own`, and returns their rounding bounds.
fn coefficients(
    patch: &Patch,
    frame: &Frame,
    (p, q): (usize, usize),
    own: &mut [[f64; 4]],
) -> Rounding {
    let (o, e1, e2, dh) = (frame.o, frame.e1, frame.e2, frame.dh);
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
    for (slot, h) in own.iter_mut().zip(&patch.net) {
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
    Rounding {
        err,
        step,
        per_weight,
    }
}

/// A box made by more subdivisions than this is made again from its patch's
/// coefficients (four), which keeps its rounding bound small.
const FRESH_AFTER: u32 = 24;

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

/// The largest distance from the ray of a control point of the box,
/// `|(α, β)|/w`: the whole image lies within it of the ray.
fn lateral(coef: &[[f64; 4]]) -> f64 {
    coef.iter()
        .fold(0.0_f64, |m, c| m.max(c[0].hypot(c[1]) / c[3]))
}

/// A side of a box for [`hit_past_floor`]: its control points (the first
/// `count`), and the parameters `(s, t)` of its two ends.
type Side = ([[f64; 4]; 8], usize, (f64, f64), (f64, f64));

/// In a box all of whose image lies within the acceptance of the ray
/// (coefficients `work`, degrees `(p, q)`), a point just past the floor
/// `floor.0` along the ray: where two adjacent corners lie on either side
/// of it, the side between them crosses it, and by continuity has points
/// just past it, every one a hit. Bisection along that side (de Casteljau
/// on its control points) brackets the crossing until the point past it
/// is within `floor.1` (the acceptance) of it, or 64 halvings. Returns the
/// point's homogeneous coefficients and its `(s, t)` in the patch, or
/// `None` if no side crosses the floor.
///
/// A ray that starts on a surface lying along it (within the acceptance
/// everywhere, as a needle at 1e100 can be) would otherwise halve every
/// box along the floor's level curve down to the smallest size, each
/// finished by Newton's method: seconds a ray.
fn hit_past_floor(
    work: &[[f64; 4]],
    (p, q): (usize, usize),
    cell: &SearchBox,
    (floor, accept): (f64, f64),
) -> Option<([f64; 4], (f64, f64))> {
    let cols = q + 1;
    let along = |c: &[f64; 4]| c[2] / c[3];
    // The four sides: control points, and the parameters of their ends.
    let side = |k: usize| -> Side {
        let mut pts = [[0.0; 4]; 8];
        let (n, start, end) = match k {
            0 => (cols, (cell.s.0, cell.t.0), (cell.s.0, cell.t.1)),
            1 => (cols, (cell.s.1, cell.t.0), (cell.s.1, cell.t.1)),
            2 => (p + 1, (cell.s.0, cell.t.0), (cell.s.1, cell.t.0)),
            _ => (p + 1, (cell.s.0, cell.t.1), (cell.s.1, cell.t.1)),
        };
        for (m, pt) in pts.iter_mut().enumerate().take(n.min(8)) {
            *pt = match k {
                0 => work[m],
                1 => work[p * cols + m],
                2 => work[m * cols],
                _ => work[m * cols + q],
            };
        }
        (pts, n, start, end)
    };
    for k in 0..4 {
        let (pts, n, start, end) = side(k);
        if n > 8 {
            continue;
        }
        let point_at = |x: f64| {
            let mut c = pts;
            for level in 1..n {
                for m in 0..n - level {
                    let next = c[m + 1];
                    for (a, b) in c[m].iter_mut().zip(next) {
                        *a = *a * (1.0 - x) + b * x;
                    }
                }
            }
            c[0]
        };
        let (first, last) = (along(&pts[0]), along(&pts[n - 1]));
        // The end at or before the floor, and the one past it.
        let (mut before, mut past) = match (first <= floor, last <= floor) {
            (true, false) => (0.0, 1.0),
            (false, true) => (1.0, 0.0),
            _ => continue,
        };
        let mut c = point_at(past);
        for _ in 0..64 {
            if along(&c) - floor <= accept {
                break;
            }
            let mid = 0.5 * (before + past);
            let m = point_at(mid);
            if along(&m) <= floor {
                before = mid;
            } else {
                (past, c) = (mid, m);
            }
        }
        let at = |a: f64, b: f64| a + (b - a) * past;
        return Some((c, (at(start.0, end.0), at(start.1, end.1))));
    }
    None
}

/// The sub-range `r` (of `[0, 1]`) of the interval `x`.
fn within(x: (f64, f64), r: (f64, f64)) -> (f64, f64) {
    let w = x.1 - x.0;
    let hi = if r.1 >= 1.0 { x.1 } else { x.0 + w * r.1 };
    (x.0 + w * r.0, hi)
}

/// Rounding bounds of a box's `α`, `β` and `γ` coefficients.
type Bounds = [f64; 3];

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

#[cfg(test)]
mod tests {
    use crate::nalgebra::{Point3, Vector3};
    use crate::{BezierSurface, Intersect, Ray};
    use std::cell::Cell;

    thread_local! {
        /// Boxes the search has looked at on this thread.
        pub(super) static BOXES: Cell<usize> = const { Cell::new(0) };
    }

    /// A quarter of the teapot lid's knob top (Newell's patch 20): its
    /// first row collapses to the pole (0, 0, 3.15) and its second row lies
    /// in the pole's horizontal tangent plane.
    fn knob_top() -> BezierSurface {
        let p = |x, y, z| Point3::new(x, y, z);
        let pole = p(0.0, 0.0, 3.15);
        BezierSurface::new(vec![
            vec![pole; 4],
            vec![
                p(0.8, 0.0, 3.15),
                p(0.8, -0.45, 3.15),
                p(0.45, -0.8, 3.15),
                p(0.0, -0.8, 3.15),
            ],
            vec![p(0.0, 0.0, 2.85); 4],
            vec![
                p(0.2, 0.0, 2.7),
                p(0.2, -0.112, 2.7),
                p(0.112, -0.2, 2.7),
                p(0.0, -0.2, 2.7),
            ],
        ])
        .unwrap()
    }

    /// Rays in the tangent plane through the pole, from every side and a
    /// rounding's height above or below it, graze the patch at a collapsed
    /// edge: the whole edge is one root. Before thin strips at such an
    /// edge were finished by Newton's method, the search halved them down
    /// to 1/SMALL boxes (16 000 and more, 38 ms a ray on the teapot).
    #[test]
    fn a_ray_grazing_a_collapsed_edge_searches_few_boxes() {
        let surface = knob_top();
        let mut worst = 0;
        for k in 0..64 {
            let angle = std::f64::consts::TAU * k as f64 / 64.0;
            for dz in [0.0, 4e-16, -4e-16, 1e-13, -1e-13] {
                let dir = Vector3::new(angle.cos(), angle.sin(), 0.0);
                let ray = Ray::new(Point3::new(0.0, 0.0, 3.15 + dz) - dir * 10.0, dir);
                BOXES.with(|b| b.set(0));
                let hit = surface.intersect(&ray, 0.0, f64::INFINITY);
                worst = worst.max(BOXES.with(Cell::get));
                if let Some(hit) = hit {
                    // Any hit is on the ray and at the pole's height.
                    let off = ray.at(hit.t) - hit.point;
                    assert!(off.norm() <= 1e-12, "{ray:?}: {hit:?}");
                    assert!((hit.point.z - 3.15).abs() <= 1e-6, "{ray:?}: {hit:?}");
                }
            }
        }
        assert!(worst <= 200, "{worst} boxes for one ray");
    }
}

//! The nearest point of a tensor-product surface (or a model of Bézier
//! patches) to a query point: a certified branch and bound over the
//! surface's (rational) Bézier patches. The method and what it certifies
//! are documented on [`BezierSurface::nearest_point`].

use super::distance_bound::{DistanceForm, MAX_FORM_DEGREE};
use super::nearest_newton::newton;
use super::patch_table::PatchTable;
use crate::curve::{Homogeneous, check_query_point, power_of_two_near};
use crate::surface_nearest::distance;
use crate::{
    BSplineSurface, BezierPatches, BezierSurface, Error, NurbsSurface, Surface, SurfaceNearest,
};
use nalgebra::Point3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// The most pieces a query examines (patches included); past it the best
/// point so far is returned with `certified: false`.
const MAX_PIECES: usize = 4096;

/// The largest allowance `δ`, relative to the problem's size, for which an
/// answer is called certified (weights within a patch so unequal that the
/// rounding allowance would exceed it are searched with this allowance,
/// uncertified).
const MAX_RELATIVE_ALLOWANCE: f64 = 1e-8;

/// Newton steps per piece at most.
const NEWTON_STEPS: usize = 8;

/// A piece's Newton's method stops at a step this short (in the piece's
/// parameters): its point then is within about the square of that of the
/// piece's nearest, which is all the bounds need; the winner is polished
/// to full precision at the end ([`POLISH_STEP`]).
const PIECE_STEP: f64 = 1e-9;

/// Newton steps of the final polish at most.
const POLISH_STEPS: usize = 16;

/// The polish of the winner stops at a step this short (in the patch's
/// parameters).
const POLISH_STEP: f64 = 4.0 * f64::EPSILON;

/// The unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

/// One Bézier patch of the query: its homogeneous net and degrees.
pub(super) struct PatchRef<'a> {
    pub(super) net: &'a [Homogeneous<3>],
    pub(super) degrees: (usize, usize),
}

/// The search's answer: the patch (index into the query's list), the
/// patch's own parameters `(s, t) ∈ [0, 1]²`, and whether it is certified.
pub(super) struct Found {
    pub(super) patch: usize,
    pub(super) st: (f64, f64),
    pub(super) certified: bool,
}

/// A patch of the query, translated so that the query point is the origin
/// and scaled by the query's power of two.
struct Slot {
    /// Where its net starts in the query's arena.
    offset: usize,
    degrees: (usize, usize),
    rational: bool,
    /// Error bounds of the restricted nets' `Y` coordinates and weights.
    errors: (f64, f64),
    /// The least weight (the projected points' division).
    w_min: f64,
    /// Its [`DistanceForm`] in the query's list, if its degrees allow one.
    form: Option<usize>,
}

/// A piece of a patch waiting to be examined.
#[derive(Debug, Clone, Copy)]
struct Piece {
    /// A lower bound of the squared distance (scaled) of every point of the
    /// piece.
    key: f64,
    slot: usize,
    s: (f64, f64),
    t: (f64, f64),
    /// Where Newton's method starts, in the patch's parameters.
    start: (f64, f64),
}

impl PartialEq for Piece {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Piece {}
impl PartialOrd for Piece {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
/// The least key first (a max-heap of reversed keys).
impl Ord for Piece {
    fn cmp(&self, other: &Self) -> Ordering {
        other.key.total_cmp(&self.key)
    }
}

/// The nearest point found so far (scaled distance).
#[derive(Debug, Clone, Copy)]
struct Best {
    distance: f64,
    slot: usize,
    st: (f64, f64),
}

impl Best {
    fn offer(&mut self, distance: f64, slot: usize, st: (f64, f64)) {
        if distance < self.distance {
            *self = Best { distance, slot, st };
        }
    }
}

/// The query's state: the translated nets, their forms and the best point.
struct Search {
    slots: Vec<Slot>,
    /// The translated, scaled nets of every patch, one after another.
    arena: Vec<Homogeneous<3>>,
    forms: Vec<DistanceForm>,
    /// The piece being examined.
    net: Vec<Homogeneous<3>>,
    best: Best,
    /// The allowance `δ`, scaled.
    delta: f64,
    /// Whether `δ` is the rounding allowance (not capped at
    /// [`MAX_RELATIVE_ALLOWANCE`]).
    trusted: bool,
}

/// The nearest point of the patches to `p` (finite, checked by the caller);
/// `None` only for an empty list.
pub(super) fn nearest_on_patches(patches: &[PatchRef<'_>], p: &Point3<f64>) -> Option<Found> {
    let mut search = Search::new(patches, p)?;
    let mut heap = BinaryHeap::with_capacity(patches.len() + 16);
    for slot in 0..search.slots.len() {
        let whole = ((0.0, 1.0), (0.0, 1.0));
        search.restrict(slot, whole);
        let key = search.box_bound(slot);
        let start = search.nearest_net_point(slot);
        heap.push(Piece {
            key,
            slot,
            s: whole.0,
            t: whole.1,
            start,
        });
    }
    let mut certified = true;
    let mut examined = 0;
    while let Some(piece) = heap.pop() {
        let Some(level) = search.level() else {
            break; // the best point is within δ of P
        };
        if piece.key >= level {
            break; // every piece left is at least as far
        }
        examined += 1;
        if examined > MAX_PIECES {
            certified = false;
            break;
        }
        if let Some(children) = search.examine(&piece) {
            match children {
                Some((a, b)) => {
                    heap.push(a);
                    heap.push(b);
                }
                None => certified = false,
            }
        }
    }
    search.polish();
    let best = search.best;
    Some(Found {
        patch: best.slot,
        st: best.st,
        certified: certified && search.trusted,
    })
}

impl Search {
    /// Translates and scales every net, and offers the patches' corners.
    fn new(patches: &[PatchRef<'_>], p: &Point3<f64>) -> Option<Self> {
        let (mut arena, mut slots) = (Vec::new(), Vec::with_capacity(patches.len()));
        let (mut size, mut largest, mut ratio) = (p.coords.amax(), 0.0_f64, 1.0_f64);
        let (mut p_max, mut q_max) = (0, 0);
        let mut forms: Vec<DistanceForm> = Vec::new();
        let mut magnitudes = Vec::with_capacity(patches.len());
        for patch in patches {
            let (w_min, w_max) = patch
                .net
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(lo, hi), h| {
                    (lo.min(h.w), hi.max(h.w))
                });
            let rational = patch.net.iter().any(|h| h.w != 1.0);
            let mut magnitude = 0.0_f64;
            let offset = arena.len();
            for h in patch.net {
                size = size.max((h.wp / h.w).amax());
                magnitude = magnitude.max(h.wp.amax() + p.coords.amax() * h.w);
                let y = h.wp - p.coords * h.w;
                largest = largest.max(y.amax() / h.w);
                arena.push(Homogeneous { wp: y, w: h.w });
            }
            let (pd, qd) = patch.degrees;
            (p_max, q_max) = (p_max.max(pd), q_max.max(qd));
            ratio = ratio.max(w_max / w_min);
            let form = (pd <= MAX_FORM_DEGREE && qd <= MAX_FORM_DEGREE).then(|| {
                match forms.iter().position(|f| f.degrees == patch.degrees) {
                    Some(k) => k,
                    None => {
                        forms.push(DistanceForm::new(patch.degrees));
                        forms.len() - 1
                    }
                }
            });
            magnitudes.push((magnitude, w_max));
            slots.push(Slot {
                offset,
                degrees: patch.degrees,
                rational,
                errors: (0.0, 0.0),
                w_min,
                form,
            });
        }
        if slots.is_empty() {
            return None;
        }
        // Scaled by a power of two (exactly) so that the largest projected
        // coordinate is about 1: no overflow or underflow in the squares.
        let scale = if largest > 0.0 && largest.is_finite() {
            1.0 / power_of_two_near(largest)
        } else {
            1.0
        };
        for h in &mut arena {
            h.wp *= scale;
        }
        for (slot, &(magnitude, w_max)) in slots.iter_mut().zip(&magnitudes) {
            // Translation (two roundings) and four de Casteljau passes.
            let (pd, qd) = slot.degrees;
            let steps = (4 + 6 * (pd + qd)) as f64;
            let e_w = if slot.rational {
                (6 * (pd + qd)) as f64 * U * w_max
            } else {
                0.0
            };
            slot.errors = (steps * U * magnitude * scale, e_w);
        }
        let delta = allowance((p_max, q_max), ratio, size);
        let trusted = delta <= MAX_RELATIVE_ALLOWANCE * size;
        let delta = delta.min(MAX_RELATIVE_ALLOWANCE * size) * scale;
        let most = patches
            .iter()
            .map(|patch| patch.net.len())
            .max()
            .unwrap_or(0);
        let mut search = Search {
            slots,
            arena,
            forms,
            net: vec![Homogeneous::zero(); most],
            best: Best {
                distance: f64::INFINITY,
                slot: 0,
                st: (0.0, 0.0),
            },
            delta,
            trusted,
        };
        for slot in 0..search.slots.len() {
            search.offer_corners(slot);
        }
        Some(search)
    }

    /// Polishes the best point by Newton's method on its whole patch.
    fn polish(&mut self) {
        let Best { slot, st, .. } = self.best;
        if !self.best.distance.is_finite() {
            return;
        }
        self.restrict(slot, ((0.0, 1.0), (0.0, 1.0)));
        let cols = self.slots[slot].degrees.1 + 1;
        let len = (self.slots[slot].degrees.0 + 1) * cols;
        let net = &self.net[..len];
        let (st, distance) = newton(net, cols, st, (POLISH_STEPS, POLISH_STEP));
        // Kept unless farther beyond rounding: Newton's point is the more
        // accurate one where distances differ by rounding only.
        let reach = net.iter().fold(0.0_f64, |m, h| m.max(h.wp.amax() / h.w));
        if distance <= self.best.distance + 16.0 * f64::EPSILON * reach {
            self.best = Best { distance, slot, st };
        }
    }

    /// `(best − δ)²`, the squared distance a piece must beat, or `None`
    /// once the best point is within `δ`.
    fn level(&self) -> Option<f64> {
        let limit = self.best.distance - self.delta;
        (limit > 0.0).then_some(limit * limit)
    }

    /// The patch's four corner points (its corner control points).
    fn offer_corners(&mut self, slot: usize) {
        let Slot {
            offset, degrees, ..
        } = self.slots[slot];
        let (p, q) = degrees;
        let cols = q + 1;
        for (i, s) in [(0, 0.0), (p, 1.0)] {
            for (j, t) in [(0, 0.0), (q, 1.0)] {
                let h = self.arena[offset + i * cols + j];
                self.best.offer((h.wp / h.w).norm(), slot, (s, t));
            }
        }
    }

    /// The patch parameters of the control point nearest to `P` (its
    /// Greville abscissae `(i/p, j/q)`): where Newton's method starts on a
    /// whole patch.
    fn nearest_net_point(&self, slot: usize) -> (f64, f64) {
        let Slot {
            offset, degrees, ..
        } = self.slots[slot];
        let (p, q) = degrees;
        let len = (p + 1) * (q + 1);
        let net = &self.arena[offset..offset + len];
        let k = (0..len)
            .min_by(|&a, &b| {
                let d = |h: &Homogeneous<3>| (h.wp / h.w).norm_squared();
                d(&net[a]).total_cmp(&d(&net[b]))
            })
            .unwrap_or(0);
        let at = |i: usize, n: usize| if n == 0 { 0.5 } else { i as f64 / n as f64 };
        (at(k / (q + 1), p), at(k % (q + 1), q))
    }

    /// Copies the patch's net restricted to `s × t` into `self.net`.
    fn restrict(&mut self, slot: usize, (s, t): ((f64, f64), (f64, f64))) {
        let Slot {
            offset, degrees, ..
        } = self.slots[slot];
        let (rows, cols) = (degrees.0 + 1, degrees.1 + 1);
        let net = &mut self.net[..rows * cols];
        net.copy_from_slice(&self.arena[offset..offset + rows * cols]);
        for i in 0..rows {
            restrict_line(net, i * cols, 1, cols, t);
        }
        for j in 0..cols {
            restrict_line(net, j, cols, rows, s);
        }
        if !self.slots[slot].rational {
            net.iter_mut().for_each(|h| h.w = 1.0);
        }
    }

    /// A lower bound of the squared distance of the piece in `self.net`:
    /// the box of its projected control points, rounding allowed for.
    fn box_bound(&self, slot: usize) -> f64 {
        let Slot {
            degrees,
            rational,
            errors: (e_y, e_w),
            w_min,
            ..
        } = self.slots[slot];
        let net = &self.net[..(degrees.0 + 1) * (degrees.1 + 1)];
        let first = net[0].wp / net[0].w;
        let (mut lo, mut hi) = (first, first);
        if rational {
            for h in &net[1..] {
                let x = h.wp / h.w;
                lo = lo.inf(&x);
                hi = hi.sup(&x);
            }
        } else {
            for h in &net[1..] {
                lo = lo.inf(&h.wp);
                hi = hi.sup(&h.wp);
            }
        }
        let reach = lo.abs().sup(&hi.abs()).amax();
        let pad = (e_y + reach * e_w) / w_min + 4.0 * U * reach;
        let mut gap2 = 0.0;
        for c in 0..3 {
            let gap = (lo[c] - pad).max(-hi[c] - pad).max(0.0);
            gap2 += gap * gap;
        }
        gap2
    }

    /// Whether to cut the piece in `self.net` across `s`: its control
    /// polygon is at least as long along `s` as along `t`.
    fn cut_in_s(&self, slot: usize) -> bool {
        let (rows, cols) = (
            self.slots[slot].degrees.0 + 1,
            self.slots[slot].degrees.1 + 1,
        );
        let net = &self.net[..rows * cols];
        let point = |k: usize| net[k].wp / net[k].w;
        let (mut along_s, mut along_t) = (0.0, 0.0);
        for i in 0..rows {
            for j in 0..cols {
                let x = point(i * cols + j);
                if i + 1 < rows {
                    along_s += (point((i + 1) * cols + j) - x).amax();
                }
                if j + 1 < cols {
                    along_t += (point(i * cols + j + 1) - x).amax();
                }
            }
        }
        along_s >= along_t
    }

    /// Examines a piece: `None` when it is settled (no point of it can beat
    /// the best by `δ`), else its two halves (`Some(None)` if it can be
    /// halved no more).
    fn examine(&mut self, piece: &Piece) -> Option<Option<(Piece, Piece)>> {
        let slot = piece.slot;
        self.restrict(slot, (piece.s, piece.t));
        let key = self.box_bound(slot);
        if key >= self.level()? {
            return None;
        }
        let (rows, cols) = (
            self.slots[slot].degrees.0 + 1,
            self.slots[slot].degrees.1 + 1,
        );
        let net = &self.net[..rows * cols];
        // The least coefficient of the squared distance's form first: it
        // settles most pieces away from the nearest point without Newton.
        let slot_data = &self.slots[slot];
        let mut form = slot_data.form.map(|k| &mut self.forms[k]);
        if let Some(form) = form.as_deref_mut() {
            form.load(net, slot_data.rational, slot_data.errors, slot_data.w_min);
            if form.set_limit(self.best.distance - self.delta) > 0.0 {
                return None;
            }
        }
        // Newton's method from the start point, in the piece's parameters.
        let local = |x: f64, (a, b): (f64, f64)| ((x - a) / (b - a)).clamp(0.0, 1.0);
        let start = (local(piece.start.0, piece.s), local(piece.start.1, piece.t));
        let (c, distance) = newton(net, cols, start, (NEWTON_STEPS, PIECE_STEP));
        let global = |x: f64, (a, b): (f64, f64)| {
            if x <= 0.0 {
                a
            } else if x >= 1.0 {
                b
            } else {
                a + (b - a) * x
            }
        };
        let st = (global(c.0, piece.s), global(c.1, piece.t));
        self.best.offer(distance, slot, st);
        let limit = self.best.distance - self.delta;
        if limit <= 0.0 || limit.is_nan() {
            return None;
        }
        if let Some(form) = form {
            if form.set_limit(limit) > 0.0 || form.lower_bound(c) > 0.0 {
                return None;
            }
        }
        Some(halves(piece, key, self.cut_in_s(slot), st))
    }
}

/// The two halves of `piece` (cut in `s` if `cut_s`, else in `t`; the
/// other way if that side can be cut no more), with the key `key` and the
/// start `start`; `None` if neither side can be cut.
fn halves(piece: &Piece, key: f64, cut_s: bool, start: (f64, f64)) -> Option<(Piece, Piece)> {
    let split = |(a, b): (f64, f64)| {
        let m = 0.5 * (a + b);
        (m > a && m < b).then_some(((a, m), (m, b)))
    };
    let child = |s, t| Piece {
        key: key.max(piece.key),
        slot: piece.slot,
        s,
        t,
        start,
    };
    let in_s = || split(piece.s).map(|(a, b)| (child(a, piece.t), child(b, piece.t)));
    let in_t = || split(piece.t).map(|(a, b)| (child(piece.s, a), child(piece.s, b)));
    if cut_s {
        in_s().or_else(in_t)
    } else {
        in_t().or_else(in_s)
    }
}

/// The search's allowance `δ` (see [`BezierSurface::nearest_point`]):
/// `16(p + 2)(q + 2)·ρ²·ε·size` for the largest degrees `(p, q)`, the
/// largest ratio `ρ` of weights within a patch and `size` the largest
/// coordinate of the query point and the control points.
fn allowance((p, q): (usize, usize), ratio: f64, size: f64) -> f64 {
    16.0 * (p + 2) as f64 * (q + 2) as f64 * ratio * ratio * f64::EPSILON * size
}

/// Restricts the Bernstein coefficients `c[start + k·stride]`, `k < n`, on
/// `[0, 1]` to `[a, b]` (two de Casteljau passes, in place: the left part
/// at `b`, then the right part of that at `a/b`).
fn restrict_line(
    c: &mut [Homogeneous<3>],
    start: usize,
    stride: usize,
    n: usize,
    (a, b): (f64, f64),
) {
    let at = |k: usize| start + k * stride;
    let degree = n - 1;
    if b < 1.0 {
        for level in 1..=degree {
            for j in (level..=degree).rev() {
                c[at(j)] = c[at(j - 1)] * (1.0 - b) + c[at(j)] * b;
            }
        }
    }
    if a > 0.0 {
        let tau = if b < 1.0 { (a / b).min(1.0) } else { a };
        for level in 1..=degree {
            for j in 0..=(degree - level) {
                c[at(j)] = c[at(j)] * (1.0 - tau) + c[at(j + 1)] * tau;
            }
        }
    }
}

impl PatchTable {
    /// The nearest point of the table's patches to `p`, with `uv` in the
    /// surface's parameters (see [`BezierSurface::nearest_point`]).
    pub(crate) fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        check_query_point(p)?;
        let refs: Vec<PatchRef<'_>> = self
            .patches
            .iter()
            .map(|patch| PatchRef {
                net: &patch.net,
                degrees: self.degrees,
            })
            .collect();
        let found = nearest_on_patches(&refs, p).ok_or(Error::NoPatches)?;
        let patch = &self.patches[found.patch];
        let along = |x: f64, (a, b): (f64, f64)| {
            if x <= 0.0 {
                a
            } else if x >= 1.0 {
                b
            } else {
                a + (b - a) * x
            }
        };
        let uv = (along(found.st.0, patch.u), along(found.st.1, patch.v));
        // From the patch at the exact parameters (`uv` rounds them: see
        // `Hit::uv` for where that matters).
        let point = self.point_on(patch, found.st);
        Ok(SurfaceNearest {
            uv,
            point,
            distance: distance(&point, p),
            certified: found.certified,
            patch: 0,
        })
    }
}

impl BezierSurface {
    /// The point of the surface nearest to `p`: the least `|S(u, v) − p|`
    /// over the whole domain `[0, 1]²`, edges, corners and collapsed edges
    /// included, certified.
    ///
    /// # Method
    /// A branch and bound over pieces of the patch (Bézier subdivision).
    /// Each piece is first bounded by the distance from `p` to the box of
    /// its control points (convex hull property); a piece that may still
    /// hold a nearer point gets Newton's method on `|S − p|²` in its
    /// parameter square (sides included: a coordinate whose gradient points
    /// out of the square is held on that side), whose result is a candidate,
    /// and then a bound from the Bernstein form of the squared distance
    /// `F − L·W` (`F = |w(S − p)|²`, `W = w²`, degree `(2p, 2q)`, `L` the
    /// squared distance to beat): its least coefficient, and a second-order
    /// bound about Newton's point with the Hessian bounded by the form's
    /// second differences, which settles a whole piece about a minimum
    /// once the distance is convex there. A piece not settled is halved
    /// across its longer side. Pieces are taken nearest box first.
    ///
    /// # What is certified
    /// With `certified: true`, no point of the surface is nearer to `p`
    /// than `distance − δ`, where
    /// `δ = 16(p + 2)(q + 2)·ρ²·ε·size` (`(p, q)` the degrees, `ρ` the
    /// largest ratio of two weights in one patch, 1 for polynomial
    /// surfaces, `ε` the machine epsilon and `size` the largest absolute
    /// coordinate of `p` and of the control points; a bicubic: `400ε·size`,
    /// about `9·10⁻¹⁴` of the size). Every bound is lowered by a bound on
    /// its rounding, so `δ` covers the arithmetic; edges and corners are
    /// part of every closed piece, and a collapsed edge is one point of the
    /// box. `distance` itself is `|point − p|` for the point found, accurate
    /// to rounding (Newton's method converges quadratically there).
    ///
    /// The search examines at most 4096 pieces: a bicubic takes from one to
    /// a few dozen, more for a point very near the surface but not on it
    /// (the pieces about the nearest point are halved until they are within
    /// a few orders of magnitude of the distance: a few dozen more at
    /// `10⁻¹²` of the size). Past the cap, for degrees above 24 (no
    /// Bernstein form: boxes alone, which settle a minimum only by luck),
    /// and where `δ` would exceed `10⁻⁸` of the size (weights within a
    /// patch differing by a factor of about 300 or more, for a bicubic; the
    /// search then uses `δ = 10⁻⁸·size`), the best point found is returned
    /// with `certified: false`. The point is the patch's at the exact
    /// parameters found; `uv` rounds them (see [`Hit::uv`](crate::Hit::uv)
    /// for where that matters).
    ///
    /// ```
    /// use revolve::{BezierSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // The bilinear saddle S(u, v) = (u, v, u·v), from a point above it.
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let p = Point3::new(0.5, 0.5, 1.0);
    /// let near = s.nearest_point(&p)?;
    /// assert!(near.certified);
    /// // No sample of the surface is nearer.
    /// for i in 0..=50 {
    ///     for j in 0..=50 {
    ///         let q = s.eval(i as f64 / 50.0, j as f64 / 50.0);
    ///         assert!(near.distance <= (q - p).norm() + 1e-14);
    ///     }
    /// }
    /// assert_eq!(near.point, s.eval(near.uv.0, near.uv.1));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.table().nearest_point(p)
    }
}

impl BSplineSurface {
    /// The point of the surface nearest to `p` over the whole domain,
    /// certified: the branch and bound of
    /// [`BezierSurface::nearest_point`] over the surface's Bézier patches
    /// (all of them at once, nearest box first), with the same allowance
    /// `δ` and cap; `uv` is in the surface's own parameters.
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.core().table.nearest_point(p)
    }
}

impl NurbsSurface {
    /// The point of the surface nearest to `p` over the whole domain,
    /// certified: the branch and bound of
    /// [`BezierSurface::nearest_point`] over the surface's rational Bézier
    /// patches (boxes of the projected control points, positive weights;
    /// the form `F − L·W` with `W = w²`), with the same allowance `δ`
    /// (including the weights' ratio `ρ`) and cap; `uv` is in the
    /// surface's own parameters.
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A quarter of the cylinder x² + y² = 1, 0 ≤ z ≤ 2 (exact).
    /// let w = std::f64::consts::FRAC_1_SQRT_2;
    /// let arc = [(1.0, 0.0, 1.0), (1.0, 1.0, w), (0.0, 1.0, 1.0)];
    /// let points = arc.iter().map(|&(x, y, _)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, 2.0)]).collect();
    /// let weights = arc.iter().map(|&(_, _, a)| vec![a, a]).collect();
    /// let k = (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let cylinder = NurbsSurface::new((2, 1), k, points, weights)?;
    /// // From (3, 3, 1) the nearest point is on the axis's perpendicular.
    /// let near = cylinder.nearest_point(&Point3::new(3.0, 3.0, 1.0))?;
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// assert!((near.point - Point3::new(h, h, 1.0)).norm() < 1e-14);
    /// assert!((near.distance - (18f64.sqrt() - 1.0)).abs() < 1e-14 && near.certified);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.core().table.nearest_point(p)
    }
}

impl BezierPatches {
    /// The point of the model nearest to `p`, over all its patches,
    /// certified: the branch and bound of
    /// [`BezierSurface::nearest_point`] over every patch at once (the
    /// patches' boxes first, so far patches cost one box each), with the
    /// same allowance `δ` (for the largest degrees) and cap. `patch` is
    /// the index of the patch the point is on (the order given, as
    /// [`intersect_patch`](Self::intersect_patch) numbers them) and `uv`
    /// is in that patch's `[0, 1]²`.
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        check_query_point(p)?;
        let refs: Vec<PatchRef<'_>> = self
            .patches()
            .iter()
            .map(|s| PatchRef {
                net: &s.table().patches[0].net,
                degrees: s.degrees(),
            })
            .collect();
        let found = nearest_on_patches(&refs, p).ok_or(Error::NoPatches)?;
        let surface = &self.patches()[found.patch];
        let point = surface.eval(found.st.0, found.st.1);
        Ok(SurfaceNearest {
            uv: found.st,
            point,
            distance: distance(&point, p),
            certified: found.certified,
            patch: found.patch,
        })
    }
}

//! The per-ray search of a span table: the front end that brings a ray
//! into the table's working frame and back, the visit of the spans the ray
//! can meet (nearest first, stopping once the best hit is nearer than the
//! next span), and the polish of each candidate by Newton's method in the
//! meridian plane. See [`span_table`](super::span_table) for the
//! polynomial each span gives.

use super::candidates::{CANDIDATE_WIDTH, Candidates, candidate_times, height_root, root_samples};
use super::meridian_cells::Cell;
use super::meridian_newton::{meridian_angle, meridian_newton};
use super::one_root::{EndRoots, EndValues, monotone_root};
use super::query::{LocalHit, Query};
use super::span_culling::{circle_times, height_entry, span_entry};
use super::span_form::{Fixed, ProfilePoint, Slices, SpanForm, Unweighted};
use super::span_table::SpanTable;
use super::turn_angle::turn_angle;
use crate::Tolerance;
use crate::bernstein::{Polynomial, eval_with_derivative};
use crate::ray::SplitDirection;
use crate::roots::{QuickRoots, find_roots_to, quick_roots};
use nalgebra::{Point3, Vector3};
use std::cmp::Ordering::Less;

/// Ray origins farther than this many times the object's scale from the
/// axis origin, or this many times its largest radius from the axis, are
/// moved along their line first (see [`SpanTable::intersect`]).
const REORIGIN: f64 = 1e3;
/// Ray directions whose largest component is in this range are used as
/// they are; others are first brought to unit length (see
/// [`SpanTable::intersect`]).
const DIRECTION_RANGE: (f64, f64) = (1e-100, 1e100);
/// Spans visited nearest first; more than this are visited after, in
/// profile order.
const SORTED_SPANS: usize = 16;
/// Marks a span in the visiting order as holding exactly one root
/// ([`EndRoots::One`]).
const ONE_ROOT: u32 = 1 << 31;
/// How far the polish may move a one-root span's root (in the span's
/// parameter) and still be taken as that root.
const ROOT_AGREEMENT: f64 = 1e-6;
/// Runs `body` with `span` bound to the coefficients `xs`, `ys` (and, when
/// `ws` is `Some`, the weights of a rational span) as a fixed-size
/// [`Fixed`] form when their length is 2 to 6 (degree ≤ 5), else as
/// [`Slices`].
macro_rules! with_span_form {
    ($xs:expr, $ys:expr, $ws:expr, |$span:ident| $body:expr) => {{
        let (xs, ys, ws): (&[f64], &[f64], Option<&[f64]>) = ($xs, $ys, $ws);
        match ws {
            None => with_span_form!(@fixed xs, ys, Unweighted, $span, $body, 2, 3, 4, 5, 6),
            Some(ws) => with_span_form!(@rational xs, ys, ws, $span, $body, 2, 3, 4, 5, 6),
        }
    }};
    (@fixed $xs:ident, $ys:ident, $ws:expr, $span:ident, $body:expr, $($w:literal),*) => {
        'done: {
            $(
                if let (Ok(xs), Ok(ys)) = (<&[f64; $w]>::try_from($xs), <&[f64; $w]>::try_from($ys)) {
                    let $span = Fixed { xs, ys, ws: $ws };
                    break 'done ($body);
                }
            )*
            let $span = Slices { xs: $xs, ys: $ys, ws: $ws };
            $body
        }
    };
    (@rational $xs:ident, $ys:ident, $ws:ident, $span:ident, $body:expr, $($w:literal),*) => {
        'done: {
            $(
                if let (Ok(xs), Ok(ys), Ok(ws)) = (
                    <&[f64; $w]>::try_from($xs),
                    <&[f64; $w]>::try_from($ys),
                    <&[f64; $w]>::try_from($ws),
                ) {
                    let $span = Fixed { xs, ys, ws };
                    break 'done ($body);
                }
            )*
            let $span = Slices { xs: $xs, ys: $ys, ws: $ws };
            $body
        }
    };
}
/// How far past its span's ends (in the span's parameter) Newton may land
/// and still count: rounding only. A hit beyond belongs to the neighbour
/// span, whose own roots find it.
const SPAN_SLACK: f64 = 1e-12;
/// How the exact intersector finished one ray
/// ([`Revolution::intersect_with_report`](crate::Revolution::intersect_with_report)).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ExactReport {
    /// Spans whose bounding cylinder the ray entered (after culling).
    pub spans_entered: u32,
    /// Spans whose polynomial was formed and solved (the rest were passed
    /// over because a nearer hit was already known).
    pub spans_solved: u32,
    /// Roots (and zero intervals) the root isolation reported.
    pub roots: u32,
    /// Candidate hits handed to Newton's method.
    pub candidates: u32,
    /// Newton iterations in total.
    pub iterations: u32,
    /// The residual `|o + t·d − S(u, θ)|` of the returned hit, if any.
    pub residual: Option<f64>,
}

impl SpanTable {
    /// The nearest hit of `o + t·d` with `t_min < t < t_max`, in the local
    /// frame (the profile's own units; `t` in units of `|d|`).
    ///
    /// The ray is first brought to the table's working frame, where every
    /// step of the solver runs at a moderate scale whatever the object's
    /// size and the ray's:
    /// - a direction whose largest component is outside [`DIRECTION_RANGE`]
    ///   becomes a unit vector (its length found without overflow), so that
    ///   `|d|` anywhere in the floating-point range works;
    /// - an origin farther than [`REORIGIN`] times the object's scale from
    ///   the axis origin, or than `REORIGIN` times its largest radius from
    ///   the axis, moves along the line to the line's point nearest that
    ///   origin (a line that passes farther than twice the object's
    ///   bounding ball is a miss), so that far origins neither overflow the
    ///   squares nor blur the culling, nor drown a thin profile's radius;
    /// - lengths are multiplied by the table's power of two (`unit`), which
    ///   is exact.
    ///
    /// `tol` is taken as valid ([`Tolerance::clamped`]).
    ///
    /// `t_min`/`t_max` that are NaN, or `t_min ≥ t_max`, give `None`.
    ///
    /// With `FIRST`, the search stops at the first span with a hit, which
    /// need not be the nearest (for [`Intersect::occluded`](crate::Intersect::occluded)).
    pub(crate) fn intersect<const FIRST: bool>(
        &self,
        o: Point3<f64>,
        d: Vector3<f64>,
        t_min: f64,
        t_max: f64,
        tol: &Tolerance,
        report: &mut ExactReport,
    ) -> Option<LocalHit> {
        // NaN-safe: `ordered` is false when either is NaN.
        let ordered = t_min < t_max;
        if !ordered || o.coords.iter().any(|c| !c.is_finite()) {
            return None;
        }
        let original = (o, d);
        let m = d.amax();
        if !(m > 0.0 && m.is_finite()) {
            return None;
        }
        // A direction of moderate length is used as it is (`dn = 1`); any
        // other is brought to unit length (found without overflow), `t`
        // then being measured in units of `dn = |d|`.
        let (d, dn) = if (DIRECTION_RANGE.0..=DIRECTION_RANGE.1).contains(&m) {
            (d, 1.0)
        } else {
            let split = SplitDirection::new(&d)?;
            (split.unit, split.largest * split.norm_of_scaled)
        };
        if !dn.is_finite() {
            return None;
        }
        // Along the ray: t·dn before the move, minus `shift` after (in units
        // of the working |d|).
        // Far compared with the size, or, from the axis, with the largest
        // radius: the squared distances from the axis would otherwise
        // drown a thin profile's squared radius in their rounding.
        let far = o.coords.amax() * self.unit > REORIGIN * self.scale
            || o.x.abs().max(o.z.abs()) * self.unit > REORIGIN * self.r_max;
        let shift = if far {
            -o.coords.dot(&d) / d.norm_squared()
        } else {
            0.0
        };
        let o = o.coords + d * shift;
        // The object lies in the ball of radius √2·scale about the origin.
        if far {
            let near_enough = o.norm() * self.unit <= 3.0 * self.scale;
            if !near_enough {
                return None;
            }
        }
        let to_working = |t: f64| (t * dn - shift) * self.unit;
        let (lo, hi) = (to_working(t_min), to_working(t_max));
        let q = Query::new(o * self.unit, d, tol, self.scale);
        let mut hit = SpanSearch::new(self, &q, lo, hi, report).run::<FIRST>()?;
        let back = 1.0 / self.unit;
        hit.t = (hit.t * back + shift) / dn;
        hit.point = Point3::from(hit.point.coords * back);
        hit.x *= back;
        hit.residual *= back;
        if FIRST && !(hit.t > t_min && hit.t < t_max) {
            // Taken back to the caller's units, the first hit found fell
            // out of the range by rounding; the nearest may not have.
            return self.intersect::<false>(original.0, original.1, t_min, t_max, tol, report);
        }
        (hit.t > t_min && hit.t < t_max).then_some(hit)
    }

    /// Newton's method on `o + t d − S(s, θ) = 0` for span `k` from `(s, t)`.
    /// Returns the hit if its residual is acceptable and `s` stays on the
    /// span.
    ///
    /// The angle is eliminated exactly: for the ray point `p(t)` at distance
    /// `ρ(t) = |p_xz|` from the axis, the nearest point of the circle
    /// `S(s, ·)` is the one in `p`'s direction, so
    /// `|p(t) − S(s, θ(t))|² = (ρ(t) − |x(s)|)² + (p_y(t) − y(s))²` and Newton
    /// runs on the 2 × 2 system `ρ(t) = |x(s)|`, `p_y(t) = y(s)` in the
    /// meridian plane, with `ρ′ = (p_xz · d_xz)/ρ`. No trigonometry per
    /// iteration; `θ` is one `atan2` at the end.
    #[inline(always)]
    fn polish<P: SpanForm>(
        &self,
        k: usize,
        span: P,
        q: &Query,
        s0: f64,
        t0: f64,
        iterations: &mut u32,
    ) -> Option<LocalHit> {
        let eval = |s: f64| span.point(s);
        let mut best = meridian_newton(
            &q.o,
            &q.d,
            (s0, t0),
            (-0.5, 1.5),
            q.acceptance.target,
            q.max_iterations,
            eval,
            iterations,
        );
        // On the axis (a pole or an apex) the system is singular, so Newton
        // stalls a little off. There the hit is where the ray meets the axis
        // point (0, y(s*), 0) with x(s*) = 0: solve that directly and keep it
        // if it fits better.
        let (_, s_best, _, at_best) = best;
        if q.d.y != 0.0 && at_best.x.abs() <= 1e-6 * self.scale {
            // x = X/W vanishes where X does (W > 0).
            let s_axis = span.with_homogeneous(|hx, _, _| axis_root(hx.coeffs(), s_best));
            if let Some(s_axis) = s_axis {
                let axis = eval(s_axis);
                let y = axis.y;
                let t_axis = (y - q.o.y) / q.d.y;
                let r_axis = (q.o + q.d * t_axis - Vector3::new(0.0, y, 0.0)).norm();
                if r_axis < best.0 {
                    best = (r_axis, s_axis, t_axis, axis);
                }
            }
        }
        let (r, s, t, ProfilePoint { x, y, dx, dy }) = best;
        // A hit at a span join may converge a rounding error past the
        // span's end: the point is kept as Newton found it and only u is
        // moved into the profile's domain.
        let slack = SPAN_SLACK;
        let accepted =
            q.acceptance.accepts(r) && (-slack..=1.0 + slack).contains(&s) && t.is_finite();
        if !accepted {
            return None;
        }
        let (u0, u1) = self.spans[k].u;
        // Trust the span's derivative for the normal only well away from
        // zero (relative to the span's size): near poles and cusps it is
        // dominated by rounding and the profile's exact limit is needed.
        let span = &self.spans[k];
        let size = span.r.1.max(span.y.0.abs()).max(span.y.1.abs());
        let tangent = nalgebra::Vector2::new(dx, dy);
        // Only strictly inside the span and off the axis: at a span end the
        // surface's normal is the limit from the next span, on the axis it
        // follows the pole rules.
        let inside = s > 1e-9 && s < 1.0 - 1e-9 && x != 0.0;
        let tangent = (inside && tangent.norm() > 1e-6 * size)
            .then(|| nalgebra::Unit::new_normalize(tangent));
        // The surface point in the ray point's direction from the axis
        // (θ = 0 on the axis), S = (x cos θ, y, −x sin θ): for x < 0 the
        // point is |x| in p's direction, at θ + π.
        let (sn, cs) = meridian_angle(&(q.o + q.d * t), x);
        let theta = turn_angle(sn, cs);
        let u = (u0 + (u1 - u0) * s).clamp(self.domain.0, self.domain.1);
        Some(LocalHit {
            t,
            u,
            theta,
            sin_cos: (sn, cs),
            point: Point3::new(x * cs, y, -x * sn),
            tangent,
            x,
            residual: r,
            s,
        })
    }
}

/// The state of one ray's search over the spans of a table, in the working
/// frame: the query, the window of accepted ray parameters
/// `(t_floor, t_best)` (a hit at or before `t_floor` is the ray's own
/// origin, `t_best` the nearest hit so far), that hit, and the report.
struct SpanSearch<'a> {
    table: &'a SpanTable,
    q: &'a Query,
    t_floor: f64,
    t_best: f64,
    best: Option<LocalHit>,
    report: &'a mut ExactReport,
}

/// The spans a ray enters, with where it enters them: the first
/// [`SORTED_SPANS`] are visited nearest first, any more after them in
/// profile order.
struct SpanOrder {
    entries: [(f64, u32); SORTED_SPANS],
    sorted: usize,
    overflow: bool,
}

impl SpanOrder {
    fn new() -> Self {
        SpanOrder {
            entries: [(0.0, 0); SORTED_SPANS],
            sorted: 0,
            overflow: false,
        }
    }

    /// Adds span `k`, entered at `entry`.
    fn push(&mut self, entry: f64, k: usize, one_root: bool) {
        if self.sorted < SORTED_SPANS {
            self.entries[self.sorted] = (entry, k as u32 | if one_root { ONE_ROOT } else { 0 });
            self.sorted += 1;
        } else {
            self.overflow = true;
        }
    }

    /// The nearest span not yet visited whose entry is below `t_best`
    /// (and whether it holds exactly one root), marked visited. The least
    /// entry is found by selects rather than branches on the data (whose
    /// order follows no pattern from one ray to the next); a visited span's
    /// entry becomes infinite.
    // Inlined by force: with two instantiations of the search (nearest and
    // first hit) it was left out of line, 2.5 % more instructions a ray.
    #[inline(always)]
    fn next_nearest(&mut self, t_best: f64) -> Option<(usize, bool)> {
        let (mut pick, mut least) = (usize::MAX, t_best);
        for (i, &(entry, _)) in self.entries[..self.sorted].iter().enumerate() {
            // Less, or unordered (a NaN is visited, never passed over).
            let take = matches!(entry.partial_cmp(&least), Some(Less) | None);
            least = if take { entry } else { least };
            pick = if take { i } else { pick };
        }
        let &mut (ref mut entry, tag) = self.entries.get_mut(pick)?;
        *entry = f64::INFINITY;
        Some(((tag & !ONE_ROOT) as usize, tag & ONE_ROOT != 0))
    }

    /// Whether span `k` is among the sorted ones.
    fn holds(&self, k: usize) -> bool {
        self.entries[..self.sorted]
            .iter()
            .any(|&(_, j)| (j & !ONE_ROOT) as usize == k)
    }
}

impl<'a> SpanSearch<'a> {
    /// The search for `o + t·d` in the working frame (`d` as the front end
    /// left it, lengths multiplied by `unit`, `t_min < t_max`).
    fn new(
        table: &'a SpanTable,
        q: &'a Query,
        t_min: f64,
        t_max: f64,
        report: &'a mut ExactReport,
    ) -> Self {
        SpanSearch {
            table,
            t_floor: q.acceptance.t_floor(t_min, q.d.norm()),
            q,
            t_best: t_max,
            best: None,
            report,
        }
    }

    /// Keeps `hit` if it lies in the window `(t_floor, t_best)`: the one
    /// place a span's hit is taken.
    #[inline(always)]
    fn offer(&mut self, hit: LocalHit) {
        if hit.t > self.t_floor && hit.t < self.t_best {
            self.t_best = hit.t;
            self.best = Some(hit);
        }
    }

    /// Adds span `k` to `order` if the ray enters it below the best hit. A
    /// span that holds exactly one root (`one_root`) is entered at the
    /// least `t` its heights allow; the others at their bounding cylinder.
    fn consider(&mut self, order: &mut SpanOrder, k: usize, one_root: bool) {
        let span = &self.table.spans[k];
        let entry = if one_root {
            height_entry(span, self.q, self.t_floor, self.t_best)
        } else {
            span_entry(span, self.q, self.t_floor, self.t_best)
        };
        if let Some(entry) = entry {
            self.report.spans_entered += 1;
            order.push(entry, k, one_root);
        }
    }

    /// The nearest hit: the spans the ray's cell (or, outside the cells,
    /// the groups it enters) lists, nearest entry first while it is below
    /// the best hit.
    // Inlined into the front end by force: called out of line, as it was
    // from `a79d1b0` on, the search took 1.10 times as long (same
    // instructions; `ray_profile glass 2000000` run alternately against
    // `2455fa3`: 1.03 inlined).
    #[inline(always)]
    fn run<const FIRST: bool>(mut self) -> Option<LocalHit> {
        let table = self.table;
        let q = self.q;
        let dn = q.d.norm();
        let mut order = SpanOrder::new();
        let cell = match &table.cells {
            Some(cells) => cells.classify(q.o, q.d, dn, q.acceptance.distance),
            None => Cell::Outside,
        };
        match cell {
            Cell::Miss => return None,
            Cell::Spans(words) => {
                // The monotonic spans and the others in two passes, so that
                // no branch asks which kind each span is.
                let ends = (q.d.y != 0.0).then(|| EndValues::new(q, table));
                for (w, (word, steady)) in words.enumerate() {
                    let steady = match ends {
                        Some(ends) => {
                            let steady = word & steady;
                            for k in set_bits(steady, w) {
                                match ends.roots(table.end_points(k)) {
                                    EndRoots::None => {}
                                    EndRoots::One => self.consider(&mut order, k, true),
                                    EndRoots::Unknown => self.consider(&mut order, k, false),
                                }
                            }
                            steady
                        }
                        None => 0,
                    };
                    for k in set_bits(word & !steady, w) {
                        self.consider(&mut order, k, false);
                    }
                }
            }
            Cell::Outside => {
                for group in &table.groups {
                    if span_entry(&group.bounds, q, self.t_floor, self.t_best).is_none() {
                        continue;
                    }
                    for k in group.first..group.end {
                        self.consider(&mut order, k, false);
                    }
                }
            }
        }
        while let Some((k, one_root)) = order.next_nearest(self.t_best) {
            self.span_hits(k, one_root);
            if FIRST && self.best.is_some() {
                return self.best;
            }
        }
        if order.overflow {
            for k in 0..table.spans.len() {
                if !order.holds(k) {
                    self.span_hits(k, false);
                    if FIRST && self.best.is_some() {
                        return self.best;
                    }
                }
            }
        }
        self.best
    }

    /// Finds the hits of span `k` and keeps the nearest.
    ///
    /// The roots become candidates `(t, s)`; they are polished nearest first,
    /// and candidates whose guessed `t` is beyond the best hit so far (with
    /// slack for the guess's error) are not polished at all. A span known
    /// to hold exactly one root (`one_root`: a monotonic hit function with
    /// certainly opposite end values, [`EndRoots::One`]) has it found by
    /// safeguarded Newton on the hit function itself and polished, without
    /// forming the polynomial; should the polish not land within
    /// [`ROOT_AGREEMENT`] of it, the span is solved in full.
    fn span_hits(&mut self, k: usize, one_root: bool) {
        self.report.spans_solved += 1;
        let (xs, ys, ws) = self.table.coeffs(k);
        with_span_form!(xs, ys, ws, |span| {
            if !(one_root && self.polish_one_root(k, span)) {
                self.hits_on(k, span);
            }
        });
    }

    /// The one root of span `k`'s monotonic hit function, polished; `false`
    /// if the polish did not reach it.
    #[inline(always)]
    fn polish_one_root<P: SpanForm>(&mut self, k: usize, span: P) -> bool {
        let q = self.q;
        self.report.roots += 1;
        let s = monotone_root(span, q);
        for t in candidate_times(span, q, s).into_iter().flatten() {
            if !t.is_finite() {
                continue;
            }
            self.report.candidates += 1;
            let Some(hit) = self
                .table
                .polish(k, span, q, s, t, &mut self.report.iterations)
            else {
                continue;
            };
            if (hit.s - s).abs() > ROOT_AGREEMENT {
                continue;
            }
            self.offer(hit);
            return true;
        }
        false
    }

    /// [`span_hits`](Self::span_hits) on the span's Bézier form `span`.
    #[inline(always)]
    fn hits_on<P: SpanForm>(&mut self, k: usize, span: P) {
        let q = self.q;
        if q.d.y == 0.0 {
            // Perpendicular to the axis: the ray stays at height o_y, and
            // crosses the circle of each root's radius.
            // The root is refined on y(s) = o_y first: its radius decides
            // whether a grazing ray crosses the circle at all.
            let times = |s: f64| {
                let s = height_root(span, q.o.y, s);
                (s, circle_times(q, span.x(s)))
            };
            span.with_height_polynomial(q.o.y, |g, err| {
                self.root_hits(k, span, g, err, times);
            });
        } else {
            let times = |s: f64| (s, candidate_times(span, q, s));
            span.with_hit_polynomial(q, &self.table.weights, |f, err| {
                self.root_hits(k, span, f, err, times);
            });
        }
    }

    /// The hits of span `k` from `poly` (coefficients known to within
    /// `err`), which vanishes at the profile parameter of every hit: each
    /// root `s` gives up to two ray parameters `times(s)`, polished nearest
    /// first. No root or one is decided by [`quick_roots`] (the one root's
    /// candidates sorted on the stack), anything else by the full search.
    #[inline(always)]
    fn root_hits<P: SpanForm, Q: Polynomial + ?Sized>(
        &mut self,
        k: usize,
        span: P,
        poly: &Q,
        err: f64,
        times: impl Fn(f64) -> (f64, [Option<f64>; 2]),
    ) {
        match quick_roots(poly, err, CANDIDATE_WIDTH) {
            QuickRoots::None => {}
            QuickRoots::One(s) => {
                // At most two candidates: sorted on the stack.
                self.report.roots += 1;
                let (s, ts) = times(s);
                let mut pair = [(0.0, s); 2];
                let mut n = 0;
                for t in ts.into_iter().flatten() {
                    if t.is_finite() {
                        pair[n].0 = t;
                        n += 1;
                    }
                }
                if n == 2 && pair[1].0 < pair[0].0 {
                    pair.swap(0, 1);
                }
                self.polish_candidates(k, span, &pair[..n]);
            }
            QuickRoots::Search => {
                let mut cands = Candidates::default();
                let report = &mut *self.report;
                find_roots_to(poly.coeffs(), err, CANDIDATE_WIDTH, |root| {
                    report.roots += 1;
                    for s in root_samples(root) {
                        let (s, ts) = times(s);
                        for t in ts.into_iter().flatten() {
                            cands.push(t, s);
                        }
                    }
                });
                cands.sort();
                self.polish_candidates(k, span, cands.as_slice());
            }
        }
    }

    /// Polishes the candidates `(t, s)` of span `k` (sorted by `t`) and keeps
    /// the nearest hit: candidates whose guessed `t` is beyond the best hit
    /// so far, with slack for the guess's error, are not polished.
    #[inline(always)]
    fn polish_candidates<P: SpanForm>(&mut self, k: usize, span: P, candidates: &[(f64, f64)]) {
        // A guess can be off by the root's uncertainty: allow a margin of
        // the object's size along the ray before skipping a candidate.
        let slack = 1e-3 * self.table.scale / self.q.d.norm();
        for &(t, s) in candidates {
            if t > self.t_best + slack {
                break;
            }
            if t < self.t_floor - slack {
                continue;
            }
            self.report.candidates += 1;
            let polished = self
                .table
                .polish(k, span, self.q, s, t, &mut self.report.iterations);
            if let Some(hit) = polished {
                self.offer(hit);
            }
        }
    }
}

/// The indices `64 w + i` of the set bits `i` of `word`, lowest first.
#[inline(always)]
fn set_bits(mut word: u64, w: usize) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (word != 0).then(|| {
            let i = word.trailing_zeros() as usize;
            word &= word - 1;
            w * 64 + i
        })
    })
}

/// The root of `x(s)` (Bernstein coefficients `xs`) near `s0`: Newton's
/// method, kept within `±0.05` of `s0` and slightly beyond the span; `None`
/// if it does not reach `|x| ≤ 4ε·max|xᵢ|`.
fn axis_root(xs: &[f64], s0: f64) -> Option<f64> {
    let scale = xs.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let (lo, hi) = (
        (s0 - 0.05).max(-SPAN_SLACK),
        (s0 + 0.05).min(1.0 + SPAN_SLACK),
    );
    let tol = 4.0 * f64::EPSILON * scale;
    // Span ends on the axis are exact (repeated control points there give a
    // root of high multiplicity that Newton only approaches).
    for end in [0.0, 1.0] {
        if (lo..=hi).contains(&end) && xs[if end == 0.0 { 0 } else { xs.len() - 1 }].abs() <= tol {
            return Some(end);
        }
    }
    let mut s = s0;
    for _ in 0..64 {
        let (x, dx) = eval_with_derivative(xs, s)?;
        if x.abs() <= tol {
            return Some(s);
        }
        if dx == 0.0 {
            return None;
        }
        let next = s - x / dx;
        if !(lo..=hi).contains(&next) || next == s {
            return None;
        }
        s = next;
    }
    None
}

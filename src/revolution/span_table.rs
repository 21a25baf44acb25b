//! Exact ray intersection for surfaces of revolution: the angle is
//! eliminated and each Bézier span of the profile gives one polynomial.
//!
//! In the local frame (axis = `y`) a ray `o + t·d` meets the surface where, for
//! some profile parameter `u`, the ray point at height `y(u)` is at distance
//! `|x(u)|` from the axis. Multiplying by `d_y²` instead of dividing by `d_y`:
//!
//! `f(u) = A(u)² + B(u)² − (d_y·x(u))² = 0`, with
//! `A = o_x d_y + (y(u) − o_y) d_x`, `B = o_z d_y + (y(u) − o_y) d_z`.
//!
//! `A`, `B` and `d_y x` are polynomials of the span's degree `n` whose Bernstein
//! coefficients come straight from the control points, so `f` has degree `2n`
//! with coefficients `f_k = Σ_{i+j=k} C(n,i)C(n,j)/C(2n,k) (aᵢaⱼ + bᵢbⱼ − cᵢcⱼ)`.
//! The same sums over magnitudes give a rounding bound for every
//! coefficient, so [`find_roots`](crate::roots::find_roots) can isolate all roots without missing one.
//! Each root `u` gives `t` (from the height, or from the radius for shallow
//! rays), and Newton's method on the unsquared system polishes the hit: in
//! the meridian plane, with the angle eliminated exactly (`θ` is the ray
//! point's own angle), `ρ(t) = |x(u)|`, `p_y(t) = y(u)`.
//! Rays perpendicular to the axis (`d_y = 0`) solve `y(u) = o_y` instead.
//!
//! Spans are culled by their height and radius ranges and visited in order of
//! where the ray enters their bounding cylinder; the search stops once the
//! best hit is nearer than the next span. Which spans a ray tests at all is
//! looked up in a table built once per surface
//! ([`MeridianCells`]): from the ray's distance from the axis, the height of
//! its closest approach and its angle with the axis, to the spans a line
//! like it can meet.
//!
//! The same table marks the spans on which every line of the ray's class
//! has a strictly monotonic `f`. On those, `f` at the span's two end
//! control points decides: certainly of one sign, no root (the span is
//! passed over without its cylinder test); certainly of opposite signs,
//! exactly one simple root, which safeguarded Newton on `f` itself finds
//! from the chord's crossing before the polish, with no polynomial formed
//! (such a span is ordered by the least `t` its heights allow). An end
//! value within its rounding of zero, or a span not so marked, takes the
//! path below.
//!
//! Spans of degree ≤ 5 are worked on as fixed-size arrays
//! ([`span_form`](super::span_form)): the polynomial, the root decision, the
//! refinement and the polish are compiled for that size. Most spans are
//! decided by [`quick_roots`] (no root, or one certain sign change and its
//! refined root); the rest go to the full search, [`find_roots_to`].

use super::meridian_cells::{Cell, MeridianCells, SpanBox, SpanCurves, product_weights};
use super::meridian_newton::{meridian_angle, meridian_newton};
use super::select::select;
use super::span_form::{Fixed, ProfilePoint, Slices, SpanForm, Unweighted};
use super::turn_angle::turn_angle;
use crate::bernstein::{Coefficient, Polynomial, eval_with_derivative};
use crate::ray::SplitDirection;
use crate::roots::{QuickRoots, Root, find_roots_to, quick_roots};
use crate::{RationalBezierSpan, Tolerance};
use nalgebra::{Point3, Vector3};
use nalgebra::{Vector2, Vector3 as Homogeneous2};
use std::cmp::Ordering::Less;

/// Profiles of more spans than this get no [`MeridianCells`] (its masks and
/// its construction grow with cells × spans); they cull by groups alone.
const MAX_CELL_SPANS: usize = 1024;

/// Ray origins farther than this many times the object's scale from the
/// axis origin are moved along their line first (see
/// [`SpanTable::intersect`]).
const REORIGIN: f64 = 1e3;

/// Ray directions whose largest component is in this range are used as
/// they are; others are first brought to unit length (see
/// [`SpanTable::intersect`]).
const DIRECTION_RANGE: (f64, f64) = (1e-100, 1e100);

/// Spans visited nearest first; more than this are visited after, in
/// profile order.
const SORTED_SPANS: usize = 16;

/// Root pieces narrower than this (in a span's parameter) are handed to
/// Newton's method as candidates instead of being split further: from there
/// Newton on the unsquared system converges, and near-tangent rays (double
/// roots) do not drive the subdivision to the bottom.
const CANDIDATE_WIDTH: f64 = 1.0 / (1u64 << 30) as f64;

/// Marks a span in the visiting order as holding exactly one root
/// ([`EndRoots::One`]).
const ONE_ROOT: u32 = 1 << 31;

/// Safeguarded Newton on a one-root span stops once a step is this small
/// (in the span's parameter): the point it reaches is then accurate to
/// about its square, and the polish finishes it.
const NEWTON_DONE: f64 = 1e-6;

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

/// Candidates stored per span before sorting; more are polished unsorted.
const MAX_CANDIDATES: usize = 16;

/// The candidate hits `(t, s)` of one span, on the stack.
struct Candidates {
    items: [(f64, f64); MAX_CANDIDATES],
    len: usize,
    /// Candidates beyond the capacity, kept in order of discovery.
    spill: Vec<(f64, f64)>,
}

impl Default for Candidates {
    fn default() -> Self {
        Candidates {
            items: [(0.0, 0.0); MAX_CANDIDATES],
            len: 0,
            spill: Vec::new(),
        }
    }
}

impl Candidates {
    fn push(&mut self, t: f64, s: f64) {
        if !t.is_finite() {
            return;
        }
        if self.len < MAX_CANDIDATES {
            self.items[self.len] = (t, s);
            self.len += 1;
        } else {
            self.spill.push((t, s));
        }
    }

    /// Sorts by `t` (insertion sort: there are few).
    fn sort(&mut self) {
        if !self.spill.is_empty() {
            // Rare: many roots. Merge everything on the heap.
            let mut all: Vec<_> = self.items[..self.len].to_vec();
            all.append(&mut self.spill);
            all.sort_by(|a, b| a.0.total_cmp(&b.0));
            self.spill = all;
            self.len = 0;
            return;
        }
        let items = &mut self.items[..self.len];
        for i in 1..items.len() {
            let mut j = i;
            while j > 0 && items[j - 1].0 > items[j].0 {
                items.swap(j - 1, j);
                j -= 1;
            }
        }
    }

    fn as_slice(&self) -> &[(f64, f64)] {
        if self.len == 0 {
            &self.spill
        } else {
            &self.items[..self.len]
        }
    }
}

/// Hits whose Newton residual is within `max(tolerance, ACCEPT) × scale` are
/// accepted; farther candidates are misses. `scale` is the larger of the
/// object's size and the ray origin's distance from the axis origin (the
/// rounding of `o + t·d` grows with it). Newton from an isolated root
/// reaches a few ulps of the scale, so `1e-12` accepts every hit while a
/// ray that misses a silhouette by more than that is a miss.
pub(crate) const ACCEPT: f64 = 1e-12;

/// How far past its span's ends (in the span's parameter) Newton may land
/// and still count: rounding only. A hit beyond belongs to the neighbour
/// span, whose own roots find it.
const SPAN_SLACK: f64 = 1e-12;

/// The per-surface data of the exact intersector, computed once.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SpanTable {
    degree: usize,
    spans: Vec<Span>,
    /// Runs of [`group_size`] consecutive spans with their joint ranges: a
    /// ray that misses a group's cylinder skips its spans' tests.
    groups: Vec<Group>,
    /// The spans each kind of line can meet (profiles of two spans or more,
    /// up to [`MAX_CELL_SPANS`]); rays it cannot place use the groups.
    cells: Option<MeridianCells>,
    /// `x` and `y` Bernstein coefficients, `degree + 1` per span: the
    /// control points (of a rational span too).
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// The weights, `degree + 1` per span (the largest of each span 1);
    /// empty when every span is polynomial.
    ws: Vec<f64>,
    /// `C(n,i)·C(n,j)/C(2n,i+j)`, row-major `(n + 1) × (n + 1)`.
    weights: Vec<f64>,
    /// Largest `|x|`, and the height range, over all control points.
    r_max: f64,
    y_range: (f64, f64),
    /// Largest absolute local coordinate: the scale of relative tolerances.
    pub(crate) scale: f64,
    /// The power of two that brought the profile into the working frame
    /// (every length above is in it): it brings the object's scale into
    /// `[0.5, 1)`, exactly.
    unit: f64,
    /// The profile's parameter domain (first span's start, last span's end).
    domain: (f64, f64),
}

/// Spans per culling group for a profile of `n` spans: `⌈√n⌉`. A ray tests
/// all `n / g` groups and the `g` spans of each group it enters; for the one
/// or two groups a ray typically enters, that is least for `g` near `√n`.
fn group_size(n: usize) -> usize {
    let root = n.isqrt();
    if root * root < n {
        root + 1
    } else {
        root.max(1)
    }
}

/// Consecutive spans `first..end` and the union of their ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Group {
    bounds: Span,
    first: usize,
    end: usize,
}

/// One profile span and its conservative ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Span {
    /// The profile parameters the span covers.
    u: (f64, f64),
    y: (f64, f64),
    /// `|x|` ranges between `r.0` and `r.1` on the span.
    r: (f64, f64),
}

/// A hit in the local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalHit {
    pub(crate) t: f64,
    pub(crate) u: f64,
    pub(crate) theta: f64,
    /// `(sin θ, cos θ)`, as the point was formed from them (no
    /// trigonometry needed for the normal).
    pub(crate) sin_cos: (f64, f64),
    pub(crate) point: Point3<f64>,
    /// The profile's unit tangent there, from the span's Bézier form, when
    /// the derivative is clearly non-zero (`None` near a pole: the caller
    /// then takes the limit from the profile itself).
    pub(crate) tangent: Option<nalgebra::Unit<nalgebra::Vector2<f64>>>,
    /// The profile's (signed) `x` there.
    pub(crate) x: f64,
    /// `|o + t·d − S(u, θ)|` after Newton's polish.
    pub(crate) residual: f64,
    /// The span's own parameter of the hit.
    pub(crate) s: f64,
}

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

/// A ray in the local frame and the interval searched.
pub(super) struct Query {
    pub(super) o: Vector3<f64>,
    pub(super) d: Vector3<f64>,
    /// Position error accepted for a hit.
    accept: f64,
    /// Residual at which Newton stops.
    target: f64,
    max_iterations: u32,
    /// Per-ray constants of the span culling: `1/d_y` (0 when `d_y = 0`),
    /// `accept/|d|`, the squared distance from the axis
    /// `r²(t) = a t² + 2 b t + c`, and where it is least (`−b/a`, or 0).
    inv_dy: f64,
    pad_t: f64,
    radius: (f64, f64, f64),
    t_closest: f64,
}

impl Query {
    /// The query for the ray `o + t·d` (finite, `d ≠ 0`) at tolerance `tol`
    /// on an object of size `scale`.
    pub(super) fn new(o: Vector3<f64>, d: Vector3<f64>, tol: &Tolerance, scale: f64) -> Self {
        // The tolerance is relative to the object; the rounding floor also
        // grows with the ray origin's distance.
        let scale = scale.max(f64::MIN_POSITIVE);
        let floor = ACCEPT * scale.max(o.amax());
        let accept = (tol.relative * scale).max(floor);
        let (a, b) = (d.x * d.x + d.z * d.z, o.x * d.x + o.z * d.z);
        Query {
            o,
            d,
            accept,
            target: tol.relative * scale,
            max_iterations: tol.max_iterations,
            inv_dy: if d.y == 0.0 { 0.0 } else { 1.0 / d.y },
            pad_t: accept / d.norm(),
            radius: (a, b, o.x * o.x + o.z * o.z),
            t_closest: if a > 0.0 { -b / a } else { 0.0 },
        }
    }
}

impl SpanTable {
    /// The table for a profile given as (rational) Bézier spans (in
    /// parameter order, as
    /// [`Curve::rational_bezier_spans`](crate::Curve::rational_bezier_spans)
    /// promises); `None` when there are none. Spans of lower degree are
    /// raised to the highest.
    ///
    /// With positive weights a rational span lies in the convex hull of its
    /// control points, so the height and radius ranges below hold for it as
    /// for a polynomial one.
    pub(crate) fn new(spans: &[RationalBezierSpan<2>]) -> Option<Self> {
        let degree = spans.iter().map(|s| s.curve.degree()).max()?;
        let unit = working_unit(spans);
        let split = refine_spans(spans, degree, unit);
        let spans = &split[..];
        let rational = spans.iter().any(|s| s.weights.is_some());
        let mut xs = Vec::with_capacity(spans.len() * (degree + 1));
        let mut ys = Vec::with_capacity(xs.capacity());
        let mut ws = Vec::with_capacity(if rational { xs.capacity() } else { 0 });
        let mut table = Vec::with_capacity(spans.len());
        for s in spans {
            let pts = &s.points[..];
            xs.extend(pts.iter().map(|p| p.x));
            ys.extend(pts.iter().map(|p| p.y));
            if rational {
                match &s.weights {
                    Some(w) => ws.extend_from_slice(w),
                    None => ws.extend(pts.iter().map(|_| 1.0)),
                }
            }
            let (y0, y1) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.y), b.max(p.y))
                });
            let r1 = pts.iter().fold(0.0_f64, |m, p| m.max(p.x.abs()));
            // If the control points' x keep one sign, |x| ≥ min |xᵢ|.
            let one_side = pts.iter().all(|p| p.x > 0.0) || pts.iter().all(|p| p.x < 0.0);
            let r0 = if one_side {
                pts.iter().fold(f64::INFINITY, |m, p| m.min(p.x.abs()))
            } else {
                0.0
            };
            table.push(Span {
                u: s.knots,
                y: (y0, y1),
                r: (r0, r1),
            });
        }
        let weights = product_weights(degree);
        let r_max = table.iter().fold(0.0_f64, |m, s| m.max(s.r.1));
        let y_range = table
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                (a.min(s.y.0), b.max(s.y.1))
            });
        let scale = r_max.max(y_range.0.abs()).max(y_range.1.abs());
        let domain = (table[0].u.0, table[table.len() - 1].u.1);
        let group = group_size(table.len());
        let boxes: Vec<SpanBox> = table.iter().map(|s| SpanBox { y: s.y, r: s.r }).collect();
        let cells = (table.len() > 1 && table.len() <= MAX_CELL_SPANS && scale > 0.0).then(|| {
            let mut cells = MeridianCells::new(&boxes, scale);
            // The monotonicity certificates are for polynomial spans; a
            // rational profile's spans all take the full search.
            if !rational {
                cells.certify_monotone(SpanCurves {
                    xs: &xs,
                    ys: &ys,
                    w: degree + 1,
                    weights: &weights,
                });
            }
            cells
        });
        Some(SpanTable {
            cells,
            domain,
            degree,
            groups: table
                .chunks(group)
                .enumerate()
                .map(|(g, run)| Group {
                    bounds: run.iter().skip(1).fold(run[0], |b, s| Span {
                        u: (b.u.0, s.u.1),
                        y: (b.y.0.min(s.y.0), b.y.1.max(s.y.1)),
                        r: (b.r.0.min(s.r.0), b.r.1.max(s.r.1)),
                    }),
                    first: g * group,
                    end: g * group + run.len(),
                })
                .collect(),
            spans: table,
            xs,
            ys,
            ws,
            weights,
            r_max,
            y_range,
            scale,
            unit,
        })
    }

    /// The bytes the table holds on the heap: its spans, groups and
    /// coefficients, and the line-class cells.
    pub(crate) fn heap_bytes(&self) -> usize {
        fn held<T>(v: &Vec<T>) -> usize {
            v.capacity() * size_of::<T>()
        }
        held(&self.spans)
            + held(&self.groups)
            + held(&self.xs)
            + held(&self.ys)
            + held(&self.ws)
            + held(&self.weights)
            + self.cells.as_ref().map_or(0, MeridianCells::heap_bytes)
    }

    /// The first and last control points `(x, y)` of span `k`.
    fn end_points(&self, k: usize) -> [(f64, f64); 2] {
        let w = self.degree + 1;
        let (first, last) = (k * w, k * w + self.degree);
        [
            (self.xs[first], self.ys[first]),
            (self.xs[last], self.ys[last]),
        ]
    }

    /// Span `k`'s `x` and `y` coefficients, and its weights if the profile
    /// is rational.
    fn coeffs(&self, k: usize) -> (&[f64], &[f64], Option<&[f64]>) {
        let w = self.degree + 1;
        let range = k * w..(k + 1) * w;
        let ws = (!self.ws.is_empty()).then(|| &self.ws[range.clone()]);
        (&self.xs[range.clone()], &self.ys[range], ws)
    }

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
    ///   the axis origin moves along the line to the line's point nearest
    ///   that origin (a line that passes farther than twice the object's
    ///   bounding ball is a miss), so that far origins neither overflow the
    ///   squares nor blur the culling;
    /// - lengths are multiplied by the table's power of two (`unit`), which
    ///   is exact.
    ///
    /// `tol` is taken as valid ([`Tolerance::clamped`]).
    ///
    /// `t_min`/`t_max` that are NaN, or `t_min ≥ t_max`, give `None`.
    pub(crate) fn intersect(
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
        let far = o.coords.amax() * self.unit > REORIGIN * self.scale;
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
        let mut hit = self.intersect_working(o * self.unit, d, lo, hi, tol, report)?;
        let back = 1.0 / self.unit;
        hit.t = (hit.t * back + shift) / dn;
        hit.point = Point3::from(hit.point.coords * back);
        hit.x *= back;
        hit.residual *= back;
        (hit.t > t_min && hit.t < t_max).then_some(hit)
    }

    /// The largest `|x|` and the height range of the profile's control
    /// points, in the profile's own units.
    pub(crate) fn local_bounds(&self) -> (f64, (f64, f64)) {
        let back = 1.0 / self.unit;
        (
            self.r_max * back,
            (self.y_range.0 * back, self.y_range.1 * back),
        )
    }

    /// [`intersect`](Self::intersect) in the working frame: `d` as the front
    /// end left it, lengths multiplied by `unit`, `t_min < t_max`.
    fn intersect_working(
        &self,
        o: Vector3<f64>,
        d: Vector3<f64>,
        t_min: f64,
        t_max: f64,
        tol: &Tolerance,
        report: &mut ExactReport,
    ) -> Option<LocalHit> {
        let dn = d.norm();
        let q = Query::new(o, d, tol, self.scale);
        // Hits within the position uncertainty of the origin are the origin
        // itself (a secondary ray leaving the surface).
        let t_floor = t_min + q.accept / dn;
        let mut best: Option<LocalHit> = None;
        let mut t_best = t_max;
        let mut order = [(0.0_f64, 0_u32); SORTED_SPANS];
        let mut sorted = 0;
        let mut overflow = false;
        // Before any span is solved, `t_best` is still `t_max`. A span
        // tagged `ONE_ROOT` has exactly one root, entered at the least `t`
        // its heights allow; the others at their bounding cylinder.
        let mut consider = |k: usize, one_root: bool| {
            let entry = if one_root {
                height_entry(&self.spans[k], &q, t_floor, t_best)
            } else {
                span_entry(&self.spans[k], &q, t_floor, t_best)
            };
            let Some(entry) = entry else {
                return;
            };
            report.spans_entered += 1;
            if sorted < SORTED_SPANS {
                order[sorted] = (entry, k as u32 | if one_root { ONE_ROOT } else { 0 });
                sorted += 1;
            } else {
                overflow = true;
            }
        };
        let cell = match &self.cells {
            Some(cells) => cells.classify(q.o, d, dn, q.accept),
            None => Cell::Outside,
        };
        match cell {
            Cell::Miss => return None,
            Cell::Spans(words) => {
                // The monotonic spans and the others in two passes, so that
                // no branch asks which kind each span is.
                let ends = (q.d.y != 0.0).then(|| EndValues::new(&q, self));
                for (w, (word, steady)) in words.enumerate() {
                    let steady = match ends {
                        Some(ends) => {
                            let steady = word & steady;
                            for k in set_bits(steady, w) {
                                match ends.roots(self.end_points(k)) {
                                    EndRoots::None => {}
                                    EndRoots::One => consider(k, true),
                                    EndRoots::Unknown => consider(k, false),
                                }
                            }
                            steady
                        }
                        None => 0,
                    };
                    for k in set_bits(word & !steady, w) {
                        consider(k, false);
                    }
                }
            }
            Cell::Outside => {
                for group in &self.groups {
                    if span_entry(&group.bounds, &q, t_floor, t_best).is_none() {
                        continue;
                    }
                    for k in group.first..group.end {
                        consider(k, false);
                    }
                }
            }
        }
        // Nearest entry first, while it is below the best hit: each time the
        // least entry left, found by selects rather than branches on the
        // data (sorting the spans as they came mispredicted about two
        // branches a ray). A visited span's entry becomes infinite.
        loop {
            let (mut pick, mut least) = (usize::MAX, t_best);
            for (i, &(entry, _)) in order[..sorted].iter().enumerate() {
                // Less, or unordered (a NaN is visited, never passed over).
                let take = matches!(entry.partial_cmp(&least), Some(Less) | None);
                least = if take { entry } else { least };
                pick = if take { i } else { pick };
            }
            let Some(&mut (ref mut entry, tag)) = order.get_mut(pick) else {
                break;
            };
            *entry = f64::INFINITY;
            let (k, one_root) = ((tag & !ONE_ROOT) as usize, tag & ONE_ROOT != 0);
            self.span_hits(k, &q, one_root, t_floor, &mut t_best, &mut best, report);
        }
        if overflow {
            for k in 0..self.spans.len() {
                if !order[..sorted]
                    .iter()
                    .any(|&(_, j)| (j & !ONE_ROOT) as usize == k)
                {
                    self.span_hits(k, &q, false, t_floor, &mut t_best, &mut best, report);
                }
            }
        }
        best
    }

    /// Finds the hits of span `k` and keeps the nearest in `best`.
    ///
    /// The roots become candidates `(t, s)`; they are polished nearest first,
    /// and candidates whose guessed `t` is beyond the best hit so far (with
    /// slack for the guess's error) are not polished at all. A span known
    /// to hold exactly one root (`one_root`: a monotonic hit function with
    /// certainly opposite end values, [`EndRoots::One`]) has it found by
    /// safeguarded Newton on the hit function itself and polished, without
    /// forming the polynomial; should the polish not land within
    /// [`ROOT_AGREEMENT`] of it, the span is solved in full.
    #[allow(clippy::too_many_arguments)]
    fn span_hits(
        &self,
        k: usize,
        q: &Query,
        one_root: bool,
        t_floor: f64,
        t_best: &mut f64,
        best: &mut Option<LocalHit>,
        report: &mut ExactReport,
    ) {
        report.spans_solved += 1;
        let (xs, ys, ws) = self.coeffs(k);
        with_span_form!(xs, ys, ws, |span| {
            if !(one_root && self.polish_one_root(k, span, q, t_floor, t_best, best, report)) {
                self.hits_on(k, span, q, t_floor, t_best, best, report);
            }
        });
    }

    /// The one root of span `k`'s monotonic hit function, polished; `false`
    /// if the polish did not reach it.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn polish_one_root<P: SpanForm>(
        &self,
        k: usize,
        span: P,
        q: &Query,
        t_floor: f64,
        t_best: &mut f64,
        best: &mut Option<LocalHit>,
        report: &mut ExactReport,
    ) -> bool {
        report.roots += 1;
        let s = monotone_root(span, q);
        for t in candidate_times(span, q, s).into_iter().flatten() {
            if !t.is_finite() {
                continue;
            }
            report.candidates += 1;
            let Some(hit) = self.polish(k, span, q, s, t, &mut report.iterations) else {
                continue;
            };
            if (hit.s - s).abs() > ROOT_AGREEMENT {
                continue;
            }
            if hit.t > t_floor && hit.t < *t_best {
                *t_best = hit.t;
                *best = Some(hit);
            }
            return true;
        }
        false
    }

    /// [`span_hits`](Self::span_hits) on the span's Bézier form `span`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn hits_on<P: SpanForm>(
        &self,
        k: usize,
        span: P,
        q: &Query,
        t_floor: f64,
        t_best: &mut f64,
        best: &mut Option<LocalHit>,
        report: &mut ExactReport,
    ) {
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
                self.root_hits(k, span, q, g, err, times, t_floor, t_best, best, report);
            });
        } else {
            let times = |s: f64| (s, candidate_times(span, q, s));
            span.with_hit_polynomial(q, &self.weights, |f, err| {
                self.root_hits(k, span, q, f, err, times, t_floor, t_best, best, report);
            });
        }
    }

    /// The hits of span `k` from `poly` (coefficients known to within
    /// `err`), which vanishes at the profile parameter of every hit: each
    /// root `s` gives up to two ray parameters `times(s)`, polished nearest
    /// first. No root or one is decided by [`quick_roots`] (the one root's
    /// candidates sorted on the stack), anything else by the full search.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn root_hits<P: SpanForm, Q: Polynomial + ?Sized>(
        &self,
        k: usize,
        span: P,
        q: &Query,
        poly: &Q,
        err: f64,
        times: impl Fn(f64) -> (f64, [Option<f64>; 2]),
        t_floor: f64,
        t_best: &mut f64,
        best: &mut Option<LocalHit>,
        report: &mut ExactReport,
    ) {
        match quick_roots(poly, err, CANDIDATE_WIDTH) {
            QuickRoots::None => {}
            QuickRoots::One(s) => {
                // At most two candidates: sorted on the stack.
                report.roots += 1;
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
                let found = &pair[..n];
                self.polish_candidates(k, span, q, found, t_floor, t_best, best, report);
            }
            QuickRoots::Search => {
                let mut cands = Candidates::default();
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
                let found = cands.as_slice();
                self.polish_candidates(k, span, q, found, t_floor, t_best, best, report);
            }
        }
    }

    /// Polishes the candidates `(t, s)` of span `k` (sorted by `t`) and keeps
    /// the nearest hit in `best`: candidates whose guessed `t` is beyond the
    /// best hit so far, with slack for the guess's error, are not polished.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn polish_candidates<P: SpanForm>(
        &self,
        k: usize,
        span: P,
        q: &Query,
        candidates: &[(f64, f64)],
        t_floor: f64,
        t_best: &mut f64,
        best: &mut Option<LocalHit>,
        report: &mut ExactReport,
    ) {
        // A guess can be off by the root's uncertainty: allow a margin of
        // the object's size along the ray before skipping a candidate.
        let slack = 1e-3 * self.scale / q.d.norm();
        for &(t, s) in candidates {
            if t > *t_best + slack {
                break;
            }
            if t < t_floor - slack {
                continue;
            }
            report.candidates += 1;
            if let Some(hit) = self.polish(k, span, q, s, t, &mut report.iterations) {
                if hit.t > t_floor && hit.t < *t_best {
                    *t_best = hit.t;
                    *best = Some(hit);
                }
            }
        }
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
            q.target,
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
        let accepted = r <= q.accept && (-slack..=1.0 + slack).contains(&s) && t.is_finite();
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

/// Ray parameters to try for the root `s` of `span`: from the height when
/// the ray is steep, else from the radius (both crossings), nearest the
/// height's answer first.
#[inline(always)]
fn candidate_times<P: SpanForm>(span: P, q: &Query, s: f64) -> [Option<f64>; 2] {
    let y = span.y(s);
    let t_height = (y - q.o.y) / q.d.y;
    // |d_y| ≥ |d_xz|, compared squared (|d| is finite, so the squares
    // are too).
    if q.d.y * q.d.y >= q.radius.0 {
        [Some(t_height), None]
    } else {
        let [a, b] = circle_times(q, span.x(s));
        // Keep the radius solution that agrees with the height.
        match (a, b) {
            (Some(a), Some(b)) => {
                if (a - t_height).abs() <= (b - t_height).abs() {
                    [Some(a), Some(b)]
                } else {
                    [Some(b), Some(a)]
                }
            }
            _ => [Some(t_height), None],
        }
    }
}

/// The root `s0` of `y(s) = h` (as isolated, to [`CANDIDATE_WIDTH`])
/// refined by Newton's method on the span: at most four steps, each kept
/// only if it brings `y` closer to `h` and stays within the isolating
/// width of `s0` and in `[0, 1]`.
#[inline(always)]
fn height_root<P: SpanForm>(span: P, h: f64, s0: f64) -> f64 {
    let (lo, hi) = (
        (s0 - CANDIDATE_WIDTH).max(0.0),
        (s0 + CANDIDATE_WIDTH).min(1.0),
    );
    let mut s = s0;
    let mut p = span.point(s);
    for _ in 0..4 {
        let g = p.y - h;
        if g == 0.0 || p.dy == 0.0 {
            break;
        }
        let next = s - g / p.dy;
        if !(next >= lo && next <= hi) {
            break;
        }
        let q = span.point(next);
        if (q.y - h).abs() >= g.abs() {
            break;
        }
        (s, p) = (next, q);
    }
    s
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

/// Profiles are cut into at least this many pieces (each span into equal
/// parameter parts): tighter height and radius ranges cull more spans per
/// ray and leave simpler polynomials to the ones that remain.
const MIN_PIECES: usize = 8;

/// One refined span in the working frame: its profile parameters, control
/// points and, for a rational span, weights (the largest 1).
struct Piece {
    knots: (f64, f64),
    points: Vec<Vector2<f64>>,
    weights: Option<Vec<f64>>,
}

/// The power of two that brings the largest control-point coordinate of
/// `spans` into `[0.5, 1)` (1 when they are all zero): multiplying by it is
/// exact, so the working frame is the same profile, only rescaled.
fn working_unit(spans: &[RationalBezierSpan<2>]) -> f64 {
    let size = spans
        .iter()
        .flat_map(|s| s.curve.points())
        .fold(0.0_f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return 1.0;
    }
    // size = f·2^e with f in [0.5, 1): the unit is 2^−e.
    let e = size.log2().floor() as i32 + 1;
    let unit = 2.0_f64.powi(-e);
    // log2 may round across a power of two: settle it exactly.
    if size * unit >= 1.0 {
        unit * 0.5
    } else if size * unit < 0.5 {
        unit * 2.0
    } else {
        unit
    }
}

/// The spans raised to `degree` and cut by de Casteljau subdivision into
/// `⌈MIN_PIECES / n⌉` equal parameter parts each (the same curve, exactly
/// up to rounding), control points multiplied by `unit`. Nothing is dropped.
///
/// Polynomial spans (equal weights) are worked on as points; rational ones
/// as homogeneous points `(wx, wy, w)`, whose raising and subdivision are
/// the same linear steps, then divided back into points and weights.
fn refine_spans(spans: &[RationalBezierSpan<2>], degree: usize, unit: f64) -> Vec<Piece> {
    let parts = MIN_PIECES.div_ceil(spans.len()).max(1);
    let mut out = Vec::with_capacity(spans.len() * parts);
    for span in spans {
        let curve = &span.curve;
        let points = curve.points().iter().map(|p| p.coords * unit);
        if curve.is_polynomial() {
            for (knots, points) in split_span(points.collect(), span.knots, degree, parts) {
                out.push(Piece {
                    knots,
                    points,
                    weights: None,
                });
            }
        } else {
            let homogeneous = points
                .zip(curve.weights())
                .map(|(p, &w)| Homogeneous2::new(p.x * w, p.y * w, w))
                .collect();
            for (knots, h) in split_span(homogeneous, span.knots, degree, parts) {
                let top = h.iter().fold(0.0_f64, |m, h| m.max(h.z));
                out.push(Piece {
                    knots,
                    points: h
                        .iter()
                        .map(|h| Vector2::new(h.x / h.z, h.y / h.z))
                        .collect(),
                    weights: Some(h.iter().map(|h| h.z / top).collect()),
                });
            }
        }
    }
    out
}

/// The Bézier coefficients `rest` on `knots`, raised to `degree` and cut
/// into `parts` equal parameter parts.
fn split_span<T: Coefficient>(
    mut rest: Vec<T>,
    (a, b): (f64, f64),
    degree: usize,
    parts: usize,
) -> Vec<((f64, f64), Vec<T>)> {
    use crate::bernstein::subdivide;
    while rest.len() <= degree {
        rest = raise_degree(&rest);
    }
    let (mut left, mut right) = (rest.clone(), rest.clone());
    let mut out = Vec::with_capacity(parts);
    for k in 0..parts {
        let (lo, hi) = (
            a + (b - a) * k as f64 / parts as f64,
            if k + 1 == parts {
                b
            } else {
                a + (b - a) * (k + 1) as f64 / parts as f64
            },
        );
        let points = if k + 1 == parts {
            rest.clone()
        } else {
            // Split what remains at the share this part takes of it.
            subdivide(&rest, 1.0 / (parts - k) as f64, &mut left, &mut right);
            rest.copy_from_slice(&right);
            left.clone()
        };
        out.push(((lo, hi), points));
    }
    out
}

/// The control points of the same Bézier curve one degree higher:
/// `Qᵢ = (i/(n+1))·Pᵢ₋₁ + (1 − i/(n+1))·Pᵢ`, `i = 0 … n+1` (Farin, *Curves
/// and Surfaces for CAGD*, §5.1).
fn raise_degree<T: Coefficient>(points: &[T]) -> Vec<T> {
    let m = points.len() as f64;
    (0..=points.len())
        .filter_map(|i| {
            let a = i as f64 / m;
            match (i.checked_sub(1).map(|j| points[j]), points.get(i)) {
                (Some(p), Some(q)) => Some(p * a + *q * (1.0 - a)),
                (Some(p), None) => Some(p),
                (None, Some(q)) => Some(*q),
                (None, None) => None,
            }
        })
        .collect()
}

/// The parameters to try for one root report: the root itself, or the ends
/// and middle of an interval on which the polynomial vanishes.
fn root_samples(root: Root) -> impl Iterator<Item = f64> {
    let v = match root {
        Root::At(s) => [Some(s), None, None],
        Root::Flat { from, to } => [Some(from), Some(0.5 * (from + to)), Some(to)],
    };
    v.into_iter().flatten()
}

/// What a span's end values say about the roots of a hit function that
/// is strictly monotonic on it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum EndRoots {
    /// Certainly of one sign: no root.
    None,
    /// Certainly of opposite signs: exactly one root, strictly inside.
    One,
    /// An end within the rounding of zero.
    Unknown,
}

/// The hit function `f = A² + B² − (d_y x)²` of one ray (see the module
/// docs) at profile points.
#[derive(Debug, Clone, Copy)]
struct HitFunction {
    o: Vector3<f64>,
    d: Vector3<f64>,
    /// `o_x d_y` and `o_z d_y`.
    oxdy: f64,
    ozdy: f64,
}

impl HitFunction {
    #[inline(always)]
    fn new(q: &Query) -> Self {
        let (o, d) = (q.o, q.d);
        HitFunction {
            o,
            d,
            oxdy: o.x * d.y,
            ozdy: o.z * d.y,
        }
    }

    /// `f` at the profile point `(x, y)`, with `A` and `B` there.
    #[inline(always)]
    fn parts(&self, x: f64, y: f64) -> (f64, f64, f64) {
        let h = y - self.o.y;
        let a = self.oxdy + h * self.d.x;
        let b = self.ozdy + h * self.d.z;
        let c = self.d.y * x;
        (a * a + b * b - c * c, a, b)
    }
}

/// The hit function of one ray (`d_y ≠ 0`) at control points, with a bound
/// on its rounding there.
#[derive(Debug, Clone, Copy)]
struct EndValues {
    f: HitFunction,
    err: f64,
}

impl EndValues {
    /// For the ray `q` on the profile of `table`. With `m_A = |o_x d_y| +
    /// (|y|_max + |o_y|)|d_x|`, likewise `m_B`, and `m_C = |d_y| |x|_max`,
    /// each of `A`, `B`, `d_y x` is computed to within `3ε` of its `m`,
    /// their squares to within `7ε m²` and `f` to within `9ε Σ m²`; the
    /// bound takes `16ε Σ m²`.
    fn new(q: &Query, table: &SpanTable) -> Self {
        let f = HitFunction::new(q);
        let (o, d) = (f.o, f.d);
        let reach = table.y_range.0.abs().max(table.y_range.1.abs()) + o.y.abs();
        let ma = f.oxdy.abs() + reach * d.x.abs();
        let mb = f.ozdy.abs() + reach * d.z.abs();
        let mc = d.y.abs() * table.r_max;
        EndValues {
            f,
            err: 16.0 * f64::EPSILON * (ma * ma + mb * mb + mc * mc),
        }
    }

    /// `f` at the profile point `(x, y)`.
    #[inline(always)]
    fn value(&self, (x, y): (f64, f64)) -> f64 {
        self.f.parts(x, y).0
    }

    /// What the end values at the span's end points `ends` say.
    #[inline(always)]
    fn roots(&self, ends: [(f64, f64); 2]) -> EndRoots {
        let (f0, f1) = (self.value(ends[0]), self.value(ends[1]));
        let e = self.err;
        let sign = |f: f64| i32::from(f > e) - i32::from(f < -e);
        match sign(f0) * sign(f1) {
            1 => EndRoots::None,
            -1 => EndRoots::One,
            _ => EndRoots::Unknown,
        }
    }
}

/// The one root in `(0, 1)` of the hit function `f` of `span` for the ray
/// `q` (`d_y ≠ 0`), where `f` is strictly monotonic with certainly
/// opposite end values ([`EndRoots::One`]): Newton's method on `f`
/// evaluated from the span's point and derivative, from the chord's
/// crossing, kept in the bracket its signs maintain (bisection when a
/// step leaves it), until a step is below [`NEWTON_DONE`].
#[inline(always)]
fn monotone_root<P: SpanForm>(span: P, q: &Query) -> f64 {
    let hit = HitFunction::new(q);
    let (d, dy2) = (q.d, q.d.y * q.d.y);
    let value = |x: f64, y: f64| hit.parts(x, y);
    let (xs, ys) = (span.xs().coeffs(), span.ys().coeffs());
    let n = xs.len() - 1;
    let (f0, _, _) = value(xs[0], ys[0]);
    let (f1, _, _) = value(xs[n], ys[n]);
    let rising = f1 > f0;
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut s = (f0 / (f0 - f1)).clamp(0.0, 1.0);
    for _ in 0..64 {
        let p = span.point(s);
        let (f, a, b) = value(p.x, p.y);
        if f == 0.0 {
            return s;
        }
        // Selects, not branches: which side s is on follows no pattern.
        let past = (f > 0.0) == rising;
        hi = select(past, s, hi);
        lo = select(past, lo, s);
        let slope = 2.0 * ((a * d.x + b * d.z) * p.dy - dy2 * p.x * p.dx);
        let newton = s - f / slope;
        let next = select(newton > lo && newton < hi, newton, 0.5 * (lo + hi));
        let step = (next - s).abs();
        s = next;
        if step <= NEWTON_DONE {
            break;
        }
    }
    s
}

/// The least `t` at which the ray is within the span's padded height
/// range, clipped to `(t_floor, t_best)` as [`span_entry`]'s height slab
/// is; `None` when that range lies outside.
#[inline]
fn height_entry(span: &Span, q: &Query, t_floor: f64, t_best: f64) -> Option<f64> {
    let (near, far) = height_slab(span, q);
    let lo = t_floor - q.pad_t;
    let enter = if near > lo { near } else { lo };
    let leave = if far < t_best { far } else { t_best };
    (enter <= leave).then_some(enter)
}

/// The `t` at which the ray (`d_y ≠ 0`) enters and leaves the span's
/// height range padded by the position tolerance, in order.
#[inline(always)]
fn height_slab(span: &Span, q: &Query) -> (f64, f64) {
    let pad = q.accept;
    let (a, b) = (
        (span.y.0 - pad - q.o.y) * q.inv_dy,
        (span.y.1 + pad - q.o.y) * q.inv_dy,
    );
    if a < b { (a, b) } else { (b, a) }
}

/// Where `o + t d` is at distance `|x|` from the axis: the roots of
/// `|o_xz + t d_xz|² = x²`, nearest first. A ray that only approaches the
/// circle (negative discriminant within rounding) gets its closest approach.
#[inline(always)]
fn circle_times(q: &Query, x: f64) -> [Option<f64>; 2] {
    let a = q.d.x * q.d.x + q.d.z * q.d.z;
    if a == 0.0 {
        return [None, None];
    }
    let b = q.o.x * q.d.x + q.o.z * q.d.z; // half of the linear coefficient
    let c = q.o.x * q.o.x + q.o.z * q.o.z - x * x;
    let disc = b * b - a * c;
    if disc <= 0.0 {
        return [Some(-b / a), None];
    }
    // Stable: the larger-magnitude root first, the other from the product.
    let h = -(b + b.signum() * disc.sqrt());
    let (t1, t2) = if h != 0.0 { (h / a, c / h) } else { (0.0, 0.0) };
    [Some(t1.min(t2)), Some(t1.max(t2))]
}

/// Where the ray enters span's bounding cylinder (clipped to
/// `(t_floor, t_best)`), or `None` if it misses it or stays within the
/// span's inner radius.
///
/// The height slab gives an interval of `t`; on it the squared distance
/// from the axis `r²(t)` is convex, so the span is missed when `r²` at the
/// closest approach (clamped to the interval) exceeds the outer radius, or
/// when both ends lie inside the inner radius. Only spans that pass get the
/// square root that moves the entry to the outer cylinder.
#[inline]
fn span_entry(span: &Span, q: &Query, t_floor: f64, t_best: f64) -> Option<f64> {
    let o = q.o;
    let pad = q.accept;
    let (mut lo, mut hi) = (t_floor - q.pad_t, t_best);
    // Height slab.
    let (y0, y1) = (span.y.0 - pad, span.y.1 + pad);
    if q.inv_dy == 0.0 {
        if o.y < y0 || o.y > y1 {
            return None;
        }
    } else {
        let (near, far) = height_slab(span, q);
        if near > lo {
            lo = near;
        }
        if far < hi {
            hi = far;
        }
    }
    if lo > hi {
        return None;
    }
    // r²(t) as the squared length of the ray point's horizontal part: no
    // cancellation between large terms for distant origins.
    let r2 = |t: f64| {
        let (x, z) = (o.x + t * q.d.x, o.z + t * q.d.z);
        x * x + z * z
    };
    let outer = span.r.1 + pad;
    let outer2 = outer * outer;
    // (Plain comparisons rather than `clamp`/`max`: no NaN reaches here,
    // and this loop runs for every span.)
    let closest = if q.t_closest < lo { lo } else { q.t_closest };
    let closest = if closest > hi { hi } else { closest };
    if r2(closest) > outer2 {
        return None;
    }
    let inner = span.r.0 - pad;
    if inner > 0.0 && r2(lo) < inner * inner && r2(hi) < inner * inner {
        return None;
    }
    // Enter at the outer cylinder when the slab starts outside it.
    let (a, b, c) = q.radius;
    if a > 0.0 && r2(lo) > outer2 {
        let disc = b * b - a * (c - outer2);
        if disc > 0.0 {
            let enter = (-b - disc.sqrt()) / a;
            if enter > lo {
                lo = enter;
            }
        }
    }
    Some(lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BSpline, Curve};
    use nalgebra::Point2;

    use crate::revolution::test_unit::unit;

    /// A clamped cubic B-spline profile of `count` points at size `scale`:
    /// radii in `[0, scale]` (the ends on the axis), heights rising with
    /// random steps, some of them backwards (overhangs).
    fn profile(state: &mut u64, count: usize, scale: f64) -> BSpline<2> {
        let mut y = -scale;
        let points = (0..count)
            .map(|i| {
                let x = if i == 0 || i + 1 == count {
                    0.0
                } else {
                    scale * (0.1 + 0.9 * unit(state))
                };
                y += scale * (0.3 * unit(state) - 0.08);
                Point2::new(x, y)
            })
            .collect();
        BSpline::clamped(3, points).expect("valid profile")
    }

    /// The table of `curve`, and the same table with no span certified
    /// monotonic (every span then takes the full solve).
    fn tables(curve: &BSpline<2>) -> (SpanTable, SpanTable) {
        let spans = curve.rational_bezier_spans().expect("spans");
        let table = SpanTable::new(&spans).expect("one degree");
        let mut full = table.clone();
        if let Some(cells) = &mut full.cells {
            cells.forget_monotone();
        }
        (table, full)
    }

    /// Spans decided by the monotonicity table and their end values
    /// (exactly one root, found by Newton on the hit function) give the
    /// same hits as the full solve (the polynomial, its certified root
    /// isolation and refinement): same t, parameter and point to rounding,
    /// and the same misses. Rays through the profile's box from all
    /// directions, at three scales; the table must decide a good share of
    /// the spans solved, or the comparison would be vacuous.
    #[test]
    fn one_root_spans_agree_with_the_full_solve() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let (mut decided, mut hits) = (0, 0);
        for (case, scale) in [1e-3, 1.0, 1e3].into_iter().cycle().take(12).enumerate() {
            let curve = profile(&mut state, 8 + case * 2, scale);
            let (table, full) = tables(&curve);
            let tol = Tolerance::default();
            for _ in 0..4000 {
                let pick = |state: &mut u64| {
                    Vector3::new(
                        (2.0 * unit(state) - 1.0) * scale,
                        (3.0 * unit(state) - 1.5) * scale,
                        (2.0 * unit(state) - 1.0) * scale,
                    )
                };
                let target = pick(&mut state);
                let o = pick(&mut state) * 4.0;
                let d = target - o;
                let o = Point3::from(o);
                let (mut report, mut report_full) =
                    (ExactReport::default(), ExactReport::default());
                let got = table.intersect(o, d, 0.0, f64::INFINITY, &tol, &mut report);
                let want = full.intersect(o, d, 0.0, f64::INFINITY, &tol, &mut report_full);
                if report != report_full {
                    decided += 1;
                }
                match (got, want) {
                    (None, None) => {}
                    (Some(a), Some(b)) => {
                        hits += 1;
                        let size = scale + o.coords.amax();
                        assert!(
                            (a.t - b.t).abs() * d.norm() <= 1e-12 * size,
                            "t {} against {} (o {o:?}, d {d:?})",
                            a.t,
                            b.t
                        );
                        assert!((a.point - b.point).norm() <= 1e-12 * size);
                        assert!((a.u - b.u).abs() <= 1e-9 * (1.0 + b.u.abs()));
                    }
                    (a, b) => panic!("one-root path {a:?}, full solve {b:?}: o {o:?}, d {d:?}"),
                }
            }
        }
        assert!(hits > 10_000, "only {hits} hits");
        assert!(
            decided > 5_000,
            "the table decided spans on only {decided} rays"
        );
    }

    /// The hit function at control points is within [`EndValues`]' bound
    /// of its value in double-double arithmetic, for random rays and
    /// points, origins up to 1e6 away and rays aimed at the point itself
    /// (where `A² + B²` and `(d_y x)²` cancel); and the bound is not
    /// vacuous (a worst case, but no more than a thousand times the worst
    /// error seen).
    #[test]
    fn end_values_are_within_their_rounding_bound() {
        use super::super::double_double::Dd;
        let mut state = 0x5851_f42d_4c95_7f2d_u64;
        let mut worst = 0.0_f64;
        let curve = profile(&mut state, 10, 1.0);
        let spans = curve.rational_bezier_spans().expect("spans");
        let table = SpanTable::new(&spans).expect("one degree");
        for case in 0..20_000 {
            let k = case % table.spans.len();
            let point = table.end_points(k)[case / 7 % 2];
            let far = [1.0, 1e3, 1e6][case % 3];
            let pick = |state: &mut u64| 2.0 * unit(state) - 1.0;
            let o = Vector3::new(pick(&mut state), pick(&mut state), pick(&mut state)) * far;
            let d = if case % 2 == 0 {
                // At the point's circle, at a random angle.
                let angle = 6.0 * unit(&mut state);
                Vector3::new(point.0 * angle.cos(), point.1, point.0 * angle.sin()) - o
            } else {
                Vector3::new(pick(&mut state), pick(&mut state), pick(&mut state))
            };
            if d.y == 0.0 {
                continue;
            }
            let q = Query::new(o, d, &Tolerance::default(), table.scale);
            let ends = EndValues::new(&q, &table);
            let got = ends.value(point);
            let dd = Dd::from;
            let h = dd(point.1).add(dd(-o.y));
            let a = dd(o.x).mul(dd(d.y)).add(h.mul(dd(d.x)));
            let b = dd(o.z).mul(dd(d.y)).add(h.mul(dd(d.z)));
            let c = dd(d.y).mul(dd(point.0));
            let exact = a.mul(a).add(b.mul(b)).add(c.mul(c).neg());
            let off = ((got - exact.0) - exact.1).abs();
            assert!(
                off <= ends.err,
                "f = {got} is {off:e} off {}, bound {:e}",
                exact.value(),
                ends.err
            );
            worst = worst.max(off / ends.err);
        }
        assert!(worst > 1e-3, "largest error only {worst:e} of the bound");
    }

    /// A rational quarter circle (weights 1, √½, 1) turned about the axis
    /// is the upper unit hemisphere: the exact intersector's hits agree with
    /// the ray–sphere quadratic (its roots with `y ≥ 0`), to 1e-12, with
    /// the same misses, for rays from all directions at three scales, and
    /// perpendicular rays (`d_y = 0`) too.
    #[test]
    fn rational_hemisphere_matches_the_sphere_quadratic() {
        use crate::RationalBezier;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut hits = 0;
        for scale in [1e-3, 1.0, 1e3] {
            let quarter = RationalBezier::new(
                vec![
                    Point2::new(scale, 0.0),
                    Point2::new(scale, scale),
                    Point2::new(0.0, scale),
                ],
                vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
            )
            .expect("valid arc");
            let spans = quarter.rational_bezier_spans().expect("spans");
            let table = SpanTable::new(&spans).expect("spans");
            let tol = Tolerance::default();
            for case in 0..20_000 {
                let pick = |state: &mut u64| {
                    Vector3::new(
                        (2.4 * unit(state) - 1.2) * scale,
                        (1.4 * unit(state) - 0.2) * scale,
                        (2.4 * unit(state) - 1.2) * scale,
                    )
                };
                let target = pick(&mut state);
                let mut o = pick(&mut state) * 3.0;
                if case % 10 == 0 {
                    o.y = target.y;
                }
                let d = target - o;
                let o = Point3::from(o);
                // Reference: |o + t d|² = r², roots with y ≥ 0, nearest > 0.
                let (a, b, c) = (
                    d.norm_squared(),
                    o.coords.dot(&d),
                    o.coords.norm_squared() - scale * scale,
                );
                let disc = b * b - a * c;
                let mut want = None;
                if disc >= 0.0 {
                    let q = -(b + b.signum() * disc.sqrt());
                    let mut roots = [q / a, c / q];
                    roots.sort_by(f64::total_cmp);
                    want = roots
                        .into_iter()
                        .find(|&t| t > 0.0 && (o.y + t * d.y) >= 0.0);
                }
                // Skip rays whose reference hit is within rounding of the
                // rim (y = 0) or of tangency: either answer is right there.
                let near_rim = want.is_some_and(|t| (o.y + t * d.y).abs() < 1e-9 * scale)
                    || disc.abs() < 1e-9 * a * scale * scale;
                if near_rim {
                    continue;
                }
                let got =
                    table.intersect(o, d, 0.0, f64::INFINITY, &tol, &mut ExactReport::default());
                match (got, want) {
                    (None, None) => {}
                    (Some(g), Some(t)) => {
                        hits += 1;
                        assert!(
                            (g.t - t).abs() * d.norm() <= 1e-12 * scale * 10.0,
                            "t {} against {t} (o {o:?}, d {d:?})",
                            g.t
                        );
                        let p = o + d * g.t;
                        assert!((p.coords.norm() - scale).abs() <= 1e-12 * scale * 10.0);
                    }
                    (g, t) => panic!("got {g:?}, want {t:?}: o {o:?}, d {d:?}"),
                }
            }
        }
        assert!(hits > 20_000, "only {hits} hits");
    }
}

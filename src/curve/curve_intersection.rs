//! Every common point of two planar curves with rational Bézier spans,
//! certified where a crossing is transversal (see [`intersect_curves`]).

use super::intersection_search::{LocalRoot, MAX_BOXES, MAX_SYSTEM, Net, PairOutcome, search_pair};
use super::overlap::coincident_stretch;
use super::query::validate_spans;
use super::{
    Homogeneous, RationalBezier, RationalBezierSpan, max_abs_coordinate, power_of_two_near,
};
use crate::{Curve, Error};
use nalgebra::Point;

/// The smallest tolerance accepted, relative to the largest absolute
/// control-point coordinate of the inputs (`1e-10`): below it the search
/// would split pieces down to rounding noise near every tangency.
pub const MIN_INTERSECTION_TOLERANCE: f64 = 1e-10;

/// Boxes a pair of spans may take before the overlap certificate is tried
/// (a transversal pair takes far fewer; two copies of a curve far more).
const FIRST_BUDGET: usize = 1 << 10;

/// Results closer than this in both parameters (relative to each span's
/// width) are one intersection found twice (at a span join, or by two
/// neighbouring boxes).
const DUPLICATE: f64 = 1e-9;

/// A result with the widths of its spans and its parameter region (the
/// cluster's hull for an uncertified one).
type Entry = (CurveIntersection, f64, f64, [(f64, f64); 2]);

/// A result with the indices of its spans and its parameter region.
type Found = (CurveIntersection, usize, usize, [(f64, f64); 2]);

/// One common point of two curves `a` and `b`: `a(t_a) = b(t_b) = point`.
///
/// `t_a` and `t_b` are in the curves' own domains. `point` is the midpoint
/// of the two curves' points at those parameters, evaluated on their spans.
///
/// `certified` is `true` when the crossing was proven single: a box of
/// parameters around `(t_a, t_b)` holds exactly one root of
/// `a(s) − b(t)` (Krawczyk's test, see [`intersect_curves`]), and the
/// parameters are that root polished by Newton's method to about double
/// precision. `false` marks a place where the curves come within about the
/// tolerance of each other and no single crossing could be proven: a
/// tangency (a double root), two crossings closer than the tolerance, or a
/// near miss closer than the tolerance; the parameters are then accurate
/// to about the tolerance (in the curves' units).
///
/// ```
/// use revolve::curve::{CurveIntersection, intersect_curves};
/// use revolve::{Bezier, Nurbs};
/// use revolve::nalgebra::Point2;
///
/// let circle = Nurbs::circle(Point2::new(0.0, 0.0), 1.0)?;
/// let line = Bezier::new(vec![Point2::new(-2.0, 0.5), Point2::new(2.0, 0.5)])?;
/// let hits: Vec<CurveIntersection> = intersect_curves(&circle, &line, 1e-9)?;
/// assert_eq!(hits.len(), 2);
/// let x = 0.75f64.sqrt();
/// assert!((hits[0].point - Point2::new(x, 0.5)).norm() < 1e-14);
/// assert!((hits[1].point - Point2::new(-x, 0.5)).norm() < 1e-14);
/// assert!(hits.iter().all(|h| h.certified));
/// # Ok::<(), revolve::Error>(())
/// ```
///
/// The same type (`CurveIntersection<3>`) describes the intersections of
/// space curves, [`intersect_space_curves`](super::intersect_space_curves).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveIntersection<const D: usize = 2> {
    /// The parameter on the first curve.
    pub t_a: f64,
    /// The parameter on the second curve.
    pub t_b: f64,
    /// The common point.
    pub point: Point<f64, D>,
    /// Whether the crossing is proven single (see the type's docs).
    pub certified: bool,
}

/// Every intersection of the planar curves `a` and `b`, in increasing
/// `t_a` (then `t_b`).
///
/// # Method
/// Both curves are taken as their [rational Bézier
/// spans](Curve::rational_bezier_spans). For each pair of spans, `a(s) =
/// X(s)/W(s)` and `b(t) = Y(t)/V(t)`, the common points are the roots in
/// `[0, 1]²` of the polynomial system `G(s, t) = X(s)·V(t) − Y(t)·W(s) = 0`
/// (two equations; equivalent, the weights being positive), whose Bernstein
/// coefficients on a box are products of the two spans' restricted control
/// points. Boxes are examined from a stack:
/// - a box is dropped when the two restricted control polygons are
///   separated along an axis or along the normal of either chord (the fat
///   line test of Bézier clipping), with a bound on every rounding error;
/// - a box is done when Krawczyk's interval Newton operator maps it, widened
///   by an eighth on each side, strictly into itself: it then holds exactly
///   one root, which is polished by Newton's method on `a(s) − b(t)`;
/// - otherwise each curve piece wider than `tolerance` is halved.
///
/// Boxes whose pieces are both within `tolerance` and still undecided are
/// grouped into clusters of touching boxes; each cluster gives one result
/// with `certified: false`. The search, its rounding bounds and its caps
/// are documented in the `curve::intersection_search` module.
///
/// # What is certified
/// No intersection is missed: a box is dropped only on a proof that it
/// holds no root (rounding included). Every `certified` result is a true,
/// single crossing. A transversal crossing is found `certified` once the
/// boxes around it are small enough for Krawczyk's test (well above the
/// tolerance unless the crossing angle is tiny). A tangency, or crossings
/// closer together than the tolerance, are reported once with `certified:
/// false`; so is a near miss closer than the tolerance. Results at a span
/// join, found from both spans, are reported once.
///
/// # Edge rules and caps
/// Intersections at the ends of the domains are included (an end lying on
/// the other curve is a result). On a closed curve (its two ends one point,
/// as a full circle) an intersection at the seam is reported once, at
/// either end. A root just outside a span, by at most
/// `1e-12` of its width, counts as at its end. Two results closer than
/// `1e-9` of their spans' widths in both parameters are one (found twice,
/// from neighbouring boxes or spans); an uncertified result within four
/// times the tolerance of another result, or whose cluster touches
/// another uncertified cluster, is merged into it. A curve of degree 0 (a
/// point) is never certified. Work is bounded: at most 2¹⁸ boxes and 2¹³
/// undecided leaves per pair of spans, boxes at most 48 halvings deep.
/// A pair of spans still undecided after 2¹⁰ boxes is tested for being one
/// arc: when their control points, restricted to the stretch between the
/// span ends that lie on the other span and compared after a change of
/// parameter, prove every point of each within `tolerance` of the other,
/// the overlap is reported at once (copies of a curve, with other knots,
/// reversed, raised in degree or moved by less than half the tolerance,
/// take under a millisecond where the caps take 0.1–0.8 s).
///
/// ```
/// use revolve::curve::intersect_curves;
/// use revolve::{Bezier, Nurbs};
/// use revolve::nalgebra::Point2;
///
/// // Two unit circles whose centres are 1 apart meet at x = 1/2, y = ±√3/2.
/// let a = Nurbs::circle(Point2::new(0.0, 0.0), 1.0)?;
/// let b = Nurbs::circle(Point2::new(1.0, 0.0), 1.0)?;
/// let hits = intersect_curves(&a, &b, 1e-9)?;
/// assert_eq!(hits.len(), 2);
/// for h in &hits {
///     assert!(h.certified && (h.point.x - 0.5).abs() < 1e-14);
///     assert!((h.point.y.abs() - 0.75f64.sqrt()).abs() < 1e-14);
/// }
/// // A line tangent to the circle: one uncertified touch.
/// let tangent = Bezier::new(vec![Point2::new(-2.0, 1.0), Point2::new(2.0, 1.0)])?;
/// let touch = intersect_curves(&a, &tangent, 1e-9)?;
/// assert_eq!(touch.len(), 1);
/// assert!(!touch[0].certified && (touch[0].point - Point2::new(0.0, 1.0)).norm() < 1e-4);
/// # Ok::<(), revolve::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidTolerance`] unless `tolerance` is finite and positive;
/// [`Error::ToleranceTooSmall`] below [`MIN_INTERSECTION_TOLERANCE`] times
/// the largest absolute control-point coordinate;
/// [`Error::NotPiecewiseRational`] for a curve without rational spans;
/// [`Error::SpansOutOfOrder`] or [`Error::SpanPointNotFinite`] for spans
/// that break their contract; [`Error::IntersectionTooLarge`] when a pair
/// of spans has more than `2¹⁴` products of control points (degrees too
/// high); [`Error::CurvesOverlap`] when the curves run within `tolerance`
/// of each other along a stretch (coincide there), with the parameter
/// ranges of the part of the stretch found.
pub fn intersect_curves<A: Curve<2> + ?Sized, B: Curve<2> + ?Sized>(
    a: &A,
    b: &B,
    tolerance: f64,
) -> Result<Vec<CurveIntersection>, Error> {
    let (spans_a, spans_b) = checked_spans(a, b, tolerance)?;
    intersect_spans(&spans_a, &spans_b, tolerance)
}

/// The two curves' rational spans, checked as [`intersect_curves`]
/// documents (the tolerance, the spans' presence and contract).
pub(crate) type SpanPair<const D: usize> = (Vec<RationalBezierSpan<D>>, Vec<RationalBezierSpan<D>>);

/// See [`SpanPair`].
pub(crate) fn checked_spans<A, B, const D: usize>(
    a: &A,
    b: &B,
    tolerance: f64,
) -> Result<SpanPair<D>, Error>
where
    A: Curve<D> + ?Sized,
    B: Curve<D> + ?Sized,
{
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidTolerance { tolerance });
    }
    let spans_a = a
        .rational_bezier_spans()
        .ok_or(Error::NotPiecewiseRational)?;
    let spans_b = b
        .rational_bezier_spans()
        .ok_or(Error::NotPiecewiseRational)?;
    validate_spans(&spans_a)?;
    validate_spans(&spans_b)?;
    Ok((spans_a, spans_b))
}

/// The largest absolute control-point coordinate of both curves' spans,
/// and the size of their largest pair's system (the product of the two
/// largest control polygons' point counts).
pub(crate) fn spans_extent<const D: usize>(
    spans_a: &[RationalBezierSpan<D>],
    spans_b: &[RationalBezierSpan<D>],
) -> (f64, usize) {
    let magnitude = spans_a
        .iter()
        .chain(spans_b)
        .map(|s| max_abs_coordinate(s.curve.points()))
        .fold(0.0, f64::max);
    let largest = |spans: &[RationalBezierSpan<D>]| {
        spans
            .iter()
            .map(|s| s.curve.points().len())
            .max()
            .unwrap_or(0)
    };
    (magnitude, largest(spans_a) * largest(spans_b))
}

/// [`intersect_curves`] on checked spans.
pub(crate) fn intersect_spans(
    spans_a: &[RationalBezierSpan<2>],
    spans_b: &[RationalBezierSpan<2>],
    tolerance: f64,
) -> Result<Vec<CurveIntersection>, Error> {
    let (magnitude, coefficients) = spans_extent(spans_a, spans_b);
    let scale = working_scale(tolerance, magnitude, coefficients)?;
    let nets_a: Vec<Net<2>> = spans_a.iter().map(|s| span_net(&s.curve, scale)).collect();
    let nets_b: Vec<Net<2>> = spans_b.iter().map(|s| span_net(&s.curve, scale)).collect();
    let mut found: Vec<Found> = Vec::new();
    for (i, (sa, na)) in spans_a.iter().zip(&nets_a).enumerate() {
        for (j, (sb, nb)) in spans_b.iter().zip(&nets_b).enumerate() {
            if !boxes_meet(&sa.curve, &sb.curve, tolerance) {
                continue;
            }
            let mut outcome = search_pair(na, nb, tolerance / scale, FIRST_BUDGET);
            if let PairOutcome::Unfinished = outcome {
                if let Some([sa_range, sb_range]) =
                    coincident_stretch(&sa.curve, &sb.curve, tolerance)
                {
                    let sorted = |(x, y): (f64, f64)| (x.min(y), x.max(y));
                    let (ra, rb) = (sorted(sa_range), sorted(sb_range));
                    return Err(Error::CurvesOverlap {
                        a: (parameter(sa, ra.0), parameter(sa, ra.1)),
                        b: (parameter(sb, rb.0), parameter(sb, rb.1)),
                    });
                }
                outcome = search_pair(na, nb, tolerance / scale, MAX_BOXES);
            }
            match outcome {
                PairOutcome::Roots(roots) => {
                    for LocalRoot { x, certified, hull } in roots {
                        let pa = sa.curve.eval(x[0]);
                        let pb = sb.curve.eval(x[1]);
                        found.push((
                            CurveIntersection {
                                t_a: parameter(sa, x[0]),
                                t_b: parameter(sb, x[1]),
                                point: Point::from((pa.coords + pb.coords) * 0.5),
                                certified,
                            },
                            i,
                            j,
                            [
                                (parameter(sa, hull[0].0), parameter(sa, hull[0].1)),
                                (parameter(sb, hull[1].0), parameter(sb, hull[1].1)),
                            ],
                        ));
                    }
                }
                // With the full budget the search ends at the caps, as an
                // overlap (an unfinished one would be reported so too).
                outcome @ (PairOutcome::Overlap(_) | PairOutcome::Unfinished) => {
                    let h = match outcome {
                        PairOutcome::Overlap(h) => h,
                        _ => [(0.0, 1.0); 2],
                    };
                    return Err(Error::CurvesOverlap {
                        a: (parameter(sa, h[0].0), parameter(sa, h[0].1)),
                        b: (parameter(sb, h[1].0), parameter(sb, h[1].1)),
                    });
                }
            }
        }
    }
    let width = |spans: &[RationalBezierSpan<2>], k: usize| spans[k].knots.1 - spans[k].knots.0;
    let ends = |spans: &[RationalBezierSpan<2>]| (spans[0].knots.0, spans[spans.len() - 1].knots.1);
    let (ends_a, ends_b) = (ends(spans_a), ends(spans_b));
    // The two ends of a closed curve's domain are one point (its seam).
    let seam = |x: f64, y: f64, (s, e): (f64, f64)| {
        let at = |p: f64, q: f64| (p - q).abs() <= DUPLICATE * (e - s);
        (at(x, s) && at(y, e)) || (at(x, e) && at(y, s))
    };
    let coincide = 64.0 * f64::EPSILON * magnitude;
    let mut out: Vec<Entry> = Vec::new();
    for (hit, i, j, region) in found {
        let (wa, wb) = (width(spans_a, i), width(spans_b, j));
        let same = |o: &Entry| {
            let on_seam = (o.0.point - hit.point).norm() <= coincide;
            let same_a = (o.0.t_a - hit.t_a).abs() <= DUPLICATE * wa.max(o.1)
                || (on_seam && seam(o.0.t_a, hit.t_a, ends_a));
            let same_b = (o.0.t_b - hit.t_b).abs() <= DUPLICATE * wb.max(o.2)
                || (on_seam && seam(o.0.t_b, hit.t_b, ends_b));
            let near = same_a && same_b;
            let close = (!o.0.certified || !hit.certified)
                && (o.0.point - hit.point).norm() <= 4.0 * tolerance;
            // Clusters that touch across a span join are one.
            let slack = [DUPLICATE * wa.max(o.1), DUPLICATE * wb.max(o.2)];
            let touch = !o.0.certified
                && !hit.certified
                && (0..2).all(|k| {
                    region[k].0 <= o.3[k].1 + slack[k] && o.3[k].0 <= region[k].1 + slack[k]
                });
            near || close || touch
        };
        match out.iter_mut().find(|o| same(o)) {
            Some(o) => {
                if hit.certified && !o.0.certified {
                    *o = (hit, wa, wb, region);
                } else if !hit.certified && !o.0.certified {
                    for (slot, r) in o.3.iter_mut().zip(&region) {
                        *slot = (slot.0.min(r.0), slot.1.max(r.1));
                    }
                }
            }
            None => out.push((hit, wa, wb, region)),
        }
    }
    let mut out: Vec<CurveIntersection> = out.into_iter().map(|o| o.0).collect();
    out.sort_by(|x, y| x.t_a.total_cmp(&y.t_a).then(x.t_b.total_cmp(&y.t_b)));
    Ok(out)
}

/// Checks spans as [`CurveProjector::from_spans`](super::CurveProjector::from_spans)
/// documents: [`Error::SpansOutOfOrder`], [`Error::SpanPointNotFinite`].
pub(crate) fn check_spans<const D: usize>(spans: &[RationalBezierSpan<D>]) -> Result<(), Error> {
    validate_spans(spans)
}

/// The curve parameter of a span's local parameter `s ∈ [0, 1]`.
pub(crate) fn parameter<const D: usize>(span: &RationalBezierSpan<D>, s: f64) -> f64 {
    let (a, b) = span.knots;
    if s <= 0.0 {
        a
    } else if s >= 1.0 {
        b
    } else {
        (a + (b - a) * s).clamp(a, b)
    }
}

/// The span's homogeneous net for the search: points divided by `scale`
/// and weights by a power of two near the largest (both exact).
pub(crate) fn span_net<const D: usize>(curve: &RationalBezier<D>, scale: f64) -> Net<D> {
    let ws = power_of_two_near(curve.weights().iter().fold(0.0_f64, |m, &w| m.max(w)));
    let coefs = curve
        .points()
        .iter()
        .zip(curve.weights())
        .map(|(p, &w)| Homogeneous::new(&Point::from(p.coords / scale), w / ws))
        .collect();
    Net {
        coefs,
        degrees: vec![curve.degree()],
    }
}

/// Whether the control points' boxes of two spans come within `tolerance`
/// (a cheap first cull; the search itself is rigorous).
fn boxes_meet(a: &RationalBezier<2>, b: &RationalBezier<2>, tolerance: f64) -> bool {
    let ((alo, ahi), (blo, bhi)) = (a.bounds(), b.bounds());
    (0..2).all(|k| {
        let pad = tolerance + 1e-12 * (alo[k].abs() + ahi[k].abs() + blo[k].abs() + bhi[k].abs());
        alo[k] <= bhi[k] + pad && blo[k] <= ahi[k] + pad
    })
}

/// The checks every intersection search makes before it starts, and its
/// working scale: the tolerance at least [`MIN_INTERSECTION_TOLERANCE`]
/// times `magnitude` (the largest coordinate), else
/// [`Error::ToleranceTooSmall`]; the largest pair of pieces' system
/// (`coefficients`, products of control points) within [`MAX_SYSTEM`],
/// else [`Error::IntersectionTooLarge`]. The scale is the power of two
/// nearest `magnitude` (1 for zero), by which the nets are divided exactly.
pub(crate) fn working_scale(
    tolerance: f64,
    magnitude: f64,
    coefficients: usize,
) -> Result<f64, Error> {
    let min = MIN_INTERSECTION_TOLERANCE * magnitude;
    if tolerance < min {
        return Err(Error::ToleranceTooSmall { tolerance, min });
    }
    if coefficients > MAX_SYSTEM {
        return Err(Error::IntersectionTooLarge {
            coefficients,
            max: MAX_SYSTEM,
        });
    }
    Ok(if magnitude > 0.0 {
        power_of_two_near(magnitude)
    } else {
        1.0
    })
}

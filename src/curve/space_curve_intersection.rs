//! Every common point of two space curves with rational Bézier spans,
//! through the planar search on a projection (see
//! [`intersect_space_curves`]).

use super::curve_intersection::{checked_spans, intersect_spans, spans_extent, working_scale};
use super::{CurveIntersection, RationalBezier, RationalBezierSpan};
use crate::{Curve, Error};
use nalgebra::{Matrix2, Matrix3, Point, Point2, Point3, SymmetricEigen, Unit, Vector2, Vector3};

/// Gauss–Newton steps of the polish in space at most.
const POLISH_STEPS: usize = 8;

/// Every point where the space curves `a` and `b` meet or come within
/// `tolerance` of each other, in increasing `t_a` (then `t_b`).
///
/// # Method
/// A common point of two space curves projects to a common point of their
/// projections on any plane, so no intersection is lost by projecting.
/// Both curves' rational spans are projected (an affine map of the
/// control points, the weights kept) along a direction tilted about 20°
/// from the normal of the plane that fits all their control points best
/// (for coplanar curves, their plane, whose crossings the projection then
/// keeps transversal), and [`intersect_curves`] finds every
/// common point of the projections within `tolerance`. Each is polished
/// in space by Gauss–Newton on `a(t_a) − b(t_b)` (least squares, two
/// unknowns) and kept when the curves there are within `tolerance` of each
/// other; the others are crossings of the projections only (one curve
/// passes in front of the other).
///
/// A touch of the projections (an uncertified result) may be a crossing
/// seen edge-on (both tangents in one plane with the projection
/// direction): the search then starts again along the next direction (the
/// plane's normal, the coordinate axes, a skew one) until a projection
/// has no touch, and keeps the one with the fewest (a tangency in space
/// touches in every projection). When the projections overlap along
/// every direction, the curves overlap in space: [`Error::CurvesOverlap`].
///
/// # What is certified
/// `certified` is `true` when the projections cross at a proven single
/// crossing and the curves' points at the polished parameters are within
/// `2⁻⁴⁰` (about `1e-12`) of the largest coordinate of each other: a true
/// intersection, to rounding. A near miss within the tolerance, or a
/// tangency, is reported with `certified: false`. `point` is the midpoint
/// of the two curves' points.
///
/// ```
/// use revolve::curve::intersect_space_curves;
/// use revolve::Nurbs;
/// use revolve::nalgebra::{Point3, Vector3};
/// use std::f64::consts::TAU;
///
/// // Two unit circles about the origin, in the planes z = 0 and x = 0:
/// // they meet at (0, ±1, 0).
/// let o = Point3::origin();
/// let a = Nurbs::arc_3d(o, Vector3::z(), Vector3::x(), 1.0, 0.0, TAU)?;
/// let b = Nurbs::arc_3d(o, Vector3::x(), Vector3::y(), 1.0, 0.0, TAU)?;
/// let hits = intersect_space_curves(&a, &b, 1e-9)?;
/// assert_eq!(hits.len(), 2);
/// for h in &hits {
///     assert!(h.certified);
///     assert!((h.point.y.abs() - 1.0).abs() < 1e-14 && h.point.x.abs() < 1e-14);
/// }
/// # Ok::<(), revolve::Error>(())
/// ```
///
/// # Errors
/// As [`intersect_curves`], with [`Error::ToleranceTooSmall`] below
/// [`MIN_INTERSECTION_TOLERANCE`](super::MIN_INTERSECTION_TOLERANCE) times
/// twice the largest absolute control-point coordinate (a projected
/// coordinate can exceed the largest by `√3`).
///
/// [`intersect_curves`]: super::intersect_curves
pub fn intersect_space_curves<A: Curve<3> + ?Sized, B: Curve<3> + ?Sized>(
    a: &A,
    b: &B,
    tolerance: f64,
) -> Result<Vec<CurveIntersection<3>>, Error> {
    let (spans_a, spans_b) = checked_spans(a, b, tolerance)?;
    let (magnitude, coefficients) = spans_extent(&spans_a, &spans_b);
    working_scale(tolerance, 2.0 * magnitude, coefficients)?;
    let directions = projection_directions(&spans_a, &spans_b);
    let mut overlap = None;
    let mut best: Option<(usize, Vec<CurveIntersection<3>>)> = None;
    for d in &directions {
        let (e1, e2) = plane_basis(d);
        let (pa, pb) = (project(&spans_a, &e1, &e2), project(&spans_b, &e1, &e2));
        let found = match intersect_spans(&pa, &pb, tolerance) {
            Ok(found) => found,
            Err(e @ Error::CurvesOverlap { .. }) => {
                overlap = Some(e);
                continue;
            }
            Err(e) => return Err(e),
        };
        let mut kept = Vec::with_capacity(found.len());
        let touches = found.iter().filter(|h| !h.certified).count();
        for h in found {
            let (t_a, t_b, gap, pa, pb) = polish(a, b, h.t_a, h.t_b);
            if gap <= tolerance {
                kept.push(CurveIntersection {
                    t_a,
                    t_b,
                    point: Point::from((pa.coords + pb.coords) * 0.5),
                    certified: h.certified && gap <= magnitude * 2f64.powi(-40),
                });
            }
        }
        // A touch of the projections may be a crossing seen edge-on: the
        // direction with the fewest touches is kept.
        if best.as_ref().is_none_or(|(t, _)| touches < *t) {
            best = Some((touches, kept));
        }
        if touches == 0 {
            break;
        }
    }
    if let Some((_, mut kept)) = best {
        kept.sort_by(|x, y| x.t_a.total_cmp(&y.t_a).then(x.t_b.total_cmp(&y.t_b)));
        // Two results polished onto one point are one (the certified kept):
        // equal parameters, or a closed curve's two ends at one point.
        let coincide = 64.0 * f64::EPSILON * magnitude;
        let same = |x: &CurveIntersection<3>, y: &CurveIntersection<3>| {
            let close = |p: f64, q: f64, (lo, hi): (f64, f64)| {
                let near = (p - q).abs() <= 1e-9 * (hi - lo);
                let ends = |e: f64| (e - lo).abs().min((e - hi).abs()) <= 1e-9 * (hi - lo);
                near || (ends(p) && ends(q) && (x.point - y.point).norm() <= coincide)
            };
            close(x.t_a, y.t_a, a.domain()) && close(x.t_b, y.t_b, b.domain())
        };
        let mut out: Vec<CurveIntersection<3>> = Vec::with_capacity(kept.len());
        for h in kept {
            match out.iter_mut().find(|o| same(o, &h)) {
                Some(last) => {
                    if h.certified && !last.certified {
                        *last = h;
                    }
                }
                _ => out.push(h),
            }
        }
        return Ok(out);
    }
    Err(overlap.unwrap_or(Error::CurvesOverlap {
        a: a.domain(),
        b: b.domain(),
    }))
}

/// The directions to project along, best first: the normal of the plane
/// that fits every control point best (least spread) tilted by about 20°,
/// that normal, then the axes and one skew direction.
fn projection_directions(
    a: &[RationalBezierSpan<3>],
    b: &[RationalBezierSpan<3>],
) -> Vec<Unit<Vector3<f64>>> {
    let points: Vec<Point3<f64>> = a
        .iter()
        .chain(b)
        .flat_map(|s| s.curve.points().iter().copied())
        .collect();
    let mut out = Vec::with_capacity(5);
    let count = points.len().max(1) as f64;
    let centre = points
        .iter()
        .fold(Vector3::zeros(), |c, p| c + p.coords / count);
    let scale = points
        .iter()
        .map(|p| (p.coords - centre).amax())
        .fold(0.0_f64, f64::max);
    if scale > 0.0 && scale.is_finite() {
        let spread = points.iter().fold(Matrix3::zeros(), |m, p| {
            let x = (p.coords - centre) / scale;
            m + x * x.transpose()
        });
        let eigen = SymmetricEigen::new(spread);
        let least = eigen.eigenvalues.imin();
        if let Some(n) = Unit::try_new(eigen.eigenvectors.column(least).into_owned(), 1e-6) {
            // Tilted off the normal first: inputs are often symmetric about
            // their own planes and axes (circles in perpendicular planes are
            // seen edge-on at their crossings from either normal), and a
            // tilt of about 20° keeps a plane's curves well in view.
            let (e1, e2) = plane_basis(&n);
            out.push(Unit::new_normalize(n.into_inner() + 0.31 * e1 + 0.17 * e2));
            out.push(n);
        }
    }
    for d in [
        Vector3::z(),
        Vector3::x(),
        Vector3::y(),
        Vector3::new(0.36, 0.48, 0.8),
    ] {
        let d = Unit::new_normalize(d);
        if out
            .iter()
            .all(|o: &Unit<Vector3<f64>>| o.dot(&d).abs() < 1.0 - 1e-6)
        {
            out.push(d);
        }
    }
    out
}

/// Two unit vectors completing `d` to an orthonormal frame.
fn plane_basis(d: &Unit<Vector3<f64>>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if d.x.abs() < 0.6 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = d.cross(&helper).normalize();
    (e1, d.cross(&e1))
}

/// The spans projected on the plane spanned by `e1`, `e2`.
fn project(
    spans: &[RationalBezierSpan<3>],
    e1: &Vector3<f64>,
    e2: &Vector3<f64>,
) -> Vec<RationalBezierSpan<2>> {
    spans
        .iter()
        .map(|s| RationalBezierSpan {
            knots: s.knots,
            curve: RationalBezier::from_valid_parts(
                s.curve
                    .points()
                    .iter()
                    .map(|p| Point2::new(e1.dot(&p.coords), e2.dot(&p.coords)))
                    .collect(),
                s.curve.weights().to_vec(),
            ),
        })
        .collect()
}

/// Gauss–Newton on `a(s) − b(t) = 0` from `(s, t)`, kept within the
/// domains, a step taken only while it brings the points closer: the
/// parameters, the distance and the two points.
fn polish<A: Curve<3> + ?Sized, B: Curve<3> + ?Sized>(
    a: &A,
    b: &B,
    mut s: f64,
    mut t: f64,
) -> (f64, f64, f64, Point3<f64>, Point3<f64>) {
    let (da, db) = (a.domain(), b.domain());
    let (mut pa, mut va) = a.eval_with_derivative(s);
    let (mut pb, mut vb) = b.eval_with_derivative(t);
    let mut gap = (pa - pb).norm();
    for _ in 0..POLISH_STEPS {
        if gap.is_nan() || gap <= 0.0 {
            break;
        }
        let r = pa - pb;
        let normal = Matrix2::new(va.dot(&va), -va.dot(&vb), -va.dot(&vb), vb.dot(&vb));
        let rhs = Vector2::new(-va.dot(&r), vb.dot(&r));
        let Some(step) = normal.lu().solve(&rhs) else {
            break;
        };
        let (s1, t1) = (
            (s + step.x).clamp(da.0, da.1),
            (t + step.y).clamp(db.0, db.1),
        );
        let (qa, wa) = a.eval_with_derivative(s1);
        let (qb, wb) = b.eval_with_derivative(t1);
        let g = (qa - qb).norm();
        if g.is_nan() || g >= gap {
            break;
        }
        (s, t, pa, va, pb, vb, gap) = (s1, t1, qa, wa, qb, wb, g);
    }
    (s, t, gap, pa, pb)
}

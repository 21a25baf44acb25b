//! Parametric curves: the [`Curve`] trait, its samples, and the curve types.
//!
//! A curve is a map `t ↦ P(t) ∈ ℝᴰ` on a closed parameter interval, its
//! [domain](Curve::domain). The trait asks for three methods (domain, point,
//! first derivative) so that users can implement it for their own curves and
//! use everything built on it (uniform sampling here, surfaces of revolution
//! elsewhere in the crate).
//!
//! ```
//! use revolve::{Bezier, Curve};
//! use revolve::nalgebra::Point2;
//!
//! let quarter = Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(0.0, 1.0)])?;
//! let samples = quarter.discretize(4);
//! assert_eq!(samples.len(), 5);
//! assert_eq!(samples[0].point, Point2::new(1.0, 0.0));
//! assert_eq!(samples[4].point, Point2::new(0.0, 1.0));
//! // The derivative at the start points along the first leg of the control polygon.
//! assert_eq!(samples[0].derivative, revolve::nalgebra::Vector2::new(0.0, 2.0));
//! # Ok::<(), revolve::Error>(())
//! ```

mod arc_length;
mod banded_solve;
mod bezier;
mod bspline;
mod conic;
mod conic_3d;
mod curve_intersection;
mod elevate;
mod fit;
mod flatten;
mod frenet;
mod gauss_remainder;
mod homogeneous;
mod interpolate;
mod intersection_search;
mod knot_removal;
mod knots;
mod length_parameter;
mod nurbs;
mod overlap;
mod pieces;
mod query;
mod rational_bezier;
mod reduce;
mod space_curve_intersection;
mod split;
mod transform;
mod unit_scale;
mod wrappers;
pub use arc_length::ArcLength;
pub use bezier::{Bezier, BezierSpan};
pub use bspline::BSpline;
pub use curve_intersection::{CurveIntersection, MIN_INTERSECTION_TOLERANCE, intersect_curves};
pub(crate) use curve_intersection::{
    check_spans, parameter as span_parameter, span_net, working_scale,
};
pub use elevate::{ELEVATION_ACCURACY, MAX_ELEVATED_DEGREE};
pub use flatten::Flattening;
pub(crate) use flatten::{MIN_RELATIVE_TOLERANCE, flatten_controls, flatten_pieces};
pub use frenet::FrenetFrame;
pub use homogeneous::MAX_DERIVATIVE_ORDER;
pub(crate) use homogeneous::{Homogeneous, power_of_two_near, quotient_rule};
pub(crate) use interpolate::{
    Interpolation, averaged_parameters, first_short_step, length, normalized_sums,
};
pub(crate) use intersection_search::{LocalRoot, MAX_BOXES, Net, PairOutcome, search_pair};
pub(crate) use knots::{boehm_insert, check_derivative_points, knot_to_insert, validate_knots};
pub use nurbs::Nurbs;
pub(crate) use query::check_query_point;
pub use query::{CurveProjector, NearestPoint};
pub use rational_bezier::{MAX_WEIGHT_RATIO, RationalBezier, RationalBezierSpan};
pub(crate) use rational_bezier::{normalized_weights, validate_weights};
pub use space_curve_intersection::intersect_space_curves;

pub use crate::limits::MAX_DERIVATIVE;

use crate::Error;
use nalgebra::{Point, SVector, Unit};

/// The most segments [`Curve::discretize`] makes (`2²⁴`, so at most
/// `2²⁴ + 1` samples); [`Curve::try_discretize`] refuses more.
pub const MAX_SEGMENTS: usize = 1 << 24;

/// A parametric curve in `D` dimensions.
///
/// Implementors provide the domain, the point and the first derivative; the
/// other methods have default implementations in terms of those.
///
/// ```
/// use revolve::Curve;
/// use revolve::nalgebra::{Point2, Vector2};
///
/// /// Your own curve type: a circular arc of radius r.
/// struct Arc { r: f64 }
///
/// impl Curve<2> for Arc {
///     fn domain(&self) -> (f64, f64) { (0.0, std::f64::consts::FRAC_PI_2) }
///     fn eval(&self, t: f64) -> Point2<f64> {
///         let t = t.clamp(0.0, std::f64::consts::FRAC_PI_2);
///         Point2::new(self.r * t.cos(), self.r * t.sin())
///     }
///     fn derivative(&self, t: f64) -> Vector2<f64> {
///         let t = t.clamp(0.0, std::f64::consts::FRAC_PI_2);
///         Vector2::new(-self.r * t.sin(), self.r * t.cos())
///     }
/// }
///
/// let samples = Arc { r: 2.0 }.discretize(8);
/// assert_eq!(samples.len(), 9);
/// assert!(samples.iter().all(|s| (s.point.coords.norm() - 2.0).abs() < 1e-15));
/// assert!(samples.iter().all(|s| s.point.coords.dot(&s.derivative).abs() < 1e-15));
/// ```
///
/// # Contract
/// - `domain()` returns `(a, b)` with `a < b`, both finite.
/// - `eval` and `derivative` accept any `f64`. The crate's own curves evaluate
///   a parameter outside the domain at the nearest end of the domain, and a NaN
///   parameter at the start of the domain, so that they never return NaN;
///   users' curves should do the same.
pub trait Curve<const D: usize> {
    /// The parameter interval `(a, b)` on which the curve is defined.
    fn domain(&self) -> (f64, f64);

    /// The point `P(t)`.
    fn eval(&self, t: f64) -> Point<f64, D>;

    /// The first derivative `dP/dt`.
    fn derivative(&self, t: f64) -> SVector<f64, D>;

    /// The point and the first derivative together. The crate's curves compute
    /// both in one pass; the default calls [`eval`](Curve::eval) and
    /// [`derivative`](Curve::derivative).
    fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
        (self.eval(t), self.derivative(t))
    }

    /// The unit tangent, pointing toward increasing `t`: the first derivative
    /// normalized, or, where it vanishes (repeated control points, a pole of
    /// a profile), the limit of the tangent from inside the domain (from the
    /// right, and from the left at the end of the domain). `None` where the
    /// curve is locally constant.
    ///
    /// The default falls back to a short chord (`10⁻⁶` of the domain) when the
    /// derivative is exactly zero; the crate's curves use their exact higher
    /// derivatives instead. Vectors are scaled by their largest component
    /// before normalizing, so derivatives of any finite size (`1e-320` to
    /// `1e308`) give a unit tangent; a NaN or infinite derivative gives `None`.
    fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
        let d = self.derivative(t);
        if d != SVector::<f64, D>::zeros() {
            return unit_direction(d);
        }
        let (a, b) = self.domain();
        // Scaled before subtracting: no overflow for ends near ±f64::MAX.
        let h = b * 1e-6 - a * 1e-6;
        let t = clamp_to_domain(t, (a, b));
        let chord = if t + h <= b {
            self.eval(t + h) - self.eval(t)
        } else {
            self.eval(t) - self.eval(t - h)
        };
        unit_direction(chord)
    }

    /// The curve as a sequence of Bézier pieces in parameter order, if it is
    /// piecewise polynomial; `None` (the default) otherwise.
    ///
    /// Exact algorithms use it: a [`Revolution`](crate::Revolution) whose
    /// profile has Bézier spans gets the exact ray intersector, and bounds
    /// from control points. [`Bezier`] and [`BSpline`] provide it.
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        None
    }

    /// The curve as a sequence of rational Bézier pieces in parameter order,
    /// if it is piecewise rational; `None` otherwise. The default gives the
    /// [polynomial spans](Curve::bezier_spans) with unit weights.
    ///
    /// A [`Revolution`](crate::Revolution) whose profile has rational spans
    /// (a [`Nurbs`] profile: exact spheres, tori, lathed
    /// parts) gets the exact ray intersector.
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<D>>> {
        self.bezier_spans()
            .map(|spans| spans.into_iter().map(RationalBezierSpan::from).collect())
    }

    /// The point of the curve nearest to `p`, its parameter and distance.
    ///
    /// For curves with [rational Bézier spans](Curve::rational_bezier_spans)
    /// (Bezier, BSpline, RationalBezier, and your own curve if it provides
    /// them) the answer is certified global: on each span every root of
    /// `(C(t) − P)·C′(t)`, written as one polynomial in Bernstein form
    /// (`W³` times it for a rational span, degree `3n − 2`; `2n − 1` for a
    /// polynomial one), is isolated with a rounding bound on its
    /// coefficients so that none is missed, each root is polished by
    /// Newton's method, and the span ends are candidates too; spans whose
    /// control points' box is farther than the best candidate are skipped.
    /// The distance returned exceeds the true minimum by rounding only
    /// (see [`CurveProjector`] and the `curve::query` module docs).
    /// `certified` is `true`. For many queries on one curve, build a
    /// [`CurveProjector`] once.
    ///
    /// A curve without spans (the default `rational_bezier_spans`, e.g. a
    /// user's analytic curve) gets a best-effort answer with
    /// `certified: false`: 4097 uniform samples, the 16 nearest local
    /// minima among them refined by bisection on the sign of `(C − P)·C′`,
    /// and the domain ends. A minimum narrower than the sample spacing can
    /// be missed.
    ///
    /// ```
    /// use revolve::Curve;
    /// use revolve::curve::RationalBezier;
    /// use revolve::nalgebra::Point2;
    ///
    /// // From the centre of a circular arc every point is nearest, at the radius.
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let quarter = RationalBezier::new(
    ///     vec![Point2::new(2.0, 0.0), Point2::new(2.0, 2.0), Point2::new(0.0, 2.0)],
    ///     vec![1.0, h, 1.0],
    /// )?;
    /// let near = quarter.nearest_point(&Point2::origin())?;
    /// assert!(near.certified && (near.distance - 2.0).abs() < 1e-15);
    /// // From outside, the nearest point is on the ray from the centre.
    /// let near = quarter.nearest_point(&Point2::new(3.0, 3.0))?;
    /// assert!((near.point - Point2::new(2.0 * h, 2.0 * h)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE);
    /// [`Error::SpansOutOfOrder`] or [`Error::SpanPointNotFinite`] for
    /// spans that break their contract; for a curve without spans
    /// [`Error::InvalidDomain`] or [`Error::CurveNotFinite`] when the
    /// curve breaks the [contract](Curve#contract).
    fn nearest_point(&self, p: &Point<f64, D>) -> Result<NearestPoint<D>, Error> {
        query::nearest_point(self, p)
    }

    /// The arc length `∫ |C′(t)| dt` over the domain, to `tolerance`
    /// (absolute), with a rigorous bracket and the estimated error.
    ///
    /// Adaptive Gauss–Legendre quadrature (8 and 16 points per piece) on
    /// each [rational Bézier span](Curve::rational_bezier_spans); `lower ≤ L
    /// ≤ upper` is rigorous (Gauss–Legendre's certified remainder where the
    /// speed is analytic, else chords and control polygons of the final
    /// pieces; positive weights), `error_bound` is an estimate (the
    /// difference of the two rules plus rounding), at most `tolerance` and
    /// at most the bracket allows; see [`ArcLength`] and the
    /// `curve::arc_length` module docs. A curve without spans gets the same
    /// quadrature on its `derivative`, with only `lower` rigorous (`upper`
    /// is infinite).
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// // The parabola y = x² for x in [0, 1] has length √5/2 + asinh(2)/4.
    /// let parabola = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(0.5, 0.0), Point2::new(1.0, 1.0)])?;
    /// let arc = parabola.arc_length(1e-12)?;
    /// let exact = 5f64.sqrt() / 2.0 + 2f64.asinh() / 4.0;
    /// assert!((arc.length - exact).abs() <= arc.error_bound.max(1e-15));
    /// assert!(arc.error_bound <= 1e-12 && arc.lower <= exact && exact <= arc.upper);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; [`Error::ToleranceTooSmall`] below `1e-13 ×` the control
    /// polygon's length (the sampled chords' for curves without spans) or
    /// below four times the bound on the evaluation's rounding (which grows
    /// with the control points' distance from the origin and the weight
    /// ratio); the span and contract errors of
    /// [`nearest_point`](Curve::nearest_point).
    fn arc_length(&self, tolerance: f64) -> Result<ArcLength, Error> {
        arc_length::arc_length(self, tolerance)
    }

    /// The parameter `t` at which the arc length from the start of the
    /// domain, `L(a, t) = ∫ₐᵗ |C′|`, is `s`, to `tolerance` (absolute):
    /// `|L(a, t) − s| ≤ tolerance`.
    ///
    /// The spans are measured once by [`arc_length`](Curve::arc_length);
    /// inside the span where `s` is reached, safeguarded Newton on
    /// `L(t) − s` with `L′ = |C′|` (bisection when a step leaves the
    /// bracket), each `L` measured on the exact de Casteljau piece. For
    /// curves with [rational spans](Curve::rational_bezier_spans) the answer
    /// is certified by the rigorous brackets of those lengths; for others it
    /// rests on the quadrature's error estimate. See the
    /// `curve::length_parameter` module docs.
    ///
    /// # Edge rules
    /// `s = 0` gives `a` exactly; `s` from the estimated length `L` up to
    /// `L + tolerance` gives `b` exactly. Where the curve stops (zero speed
    /// over an interval) any parameter of the stop may be returned.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// // On a circle of radius 2 the length s is reached at angle s/2.
    /// let circle = Nurbs::circle(Point2::origin(), 2.0)?;
    /// let t = circle.parameter_at_length(1.0, 1e-10)?;
    /// let p = circle.eval(t);
    /// assert!((p.y.atan2(p.x) - 0.5).abs() < 1e-9);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; [`Error::LengthOutOfRange`] for `s` NaN, negative or beyond
    /// the length plus `tolerance`; [`Error::ToleranceTooSmall`] when the
    /// lengths' brackets cannot be made narrow enough, and the errors of
    /// [`arc_length`](Curve::arc_length) (each measurement gets a quarter
    /// of the tolerance, so the smallest tolerance accepted is four times
    /// `arc_length`'s).
    fn parameter_at_length(&self, s: f64, tolerance: f64) -> Result<f64, Error> {
        length_parameter::parameter_at_length(self, s, tolerance)
    }

    /// The `pieces + 1` parameters `a = t₀ < … < t_pieces = b` that divide
    /// the curve into `pieces` pieces of equal length: `tᵢ` is
    /// [`parameter_at_length`](Curve::parameter_at_length)`(i·L/pieces)`,
    /// `L` the estimated length, so `|L(a, tᵢ) − i·L/pieces| ≤ tolerance`.
    /// The ends are exactly `a` and `b`. Certified as
    /// [`parameter_at_length`](Curve::parameter_at_length) is.
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// // A straight segment traced at non-uniform speed (x = t²·3).
    /// let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(0.0, 0.0), Point2::new(3.0, 0.0)])?;
    /// let ts = c.divide_by_length(3, 1e-10)?;
    /// assert_eq!(ts.len(), 4);
    /// assert_eq!((ts[0], ts[3]), (0.0, 1.0));
    /// assert!((c.eval(ts[1]).x - 1.0).abs() <= 1e-10);
    /// assert!((ts[1] - (1.0f64 / 3.0).sqrt()).abs() < 1e-9);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ZeroPieces`] for `pieces = 0`; [`Error::TooManySegments`]
    /// beyond [`MAX_SEGMENTS`]; those of
    /// [`parameter_at_length`](Curve::parameter_at_length).
    fn divide_by_length(&self, pieces: usize, tolerance: f64) -> Result<Vec<f64>, Error> {
        length_parameter::divide_by_length(self, pieces, tolerance)
    }

    /// `segments + 1` samples at uniformly spaced parameters
    /// `tᵢ = a + (b − a)·i/segments`, `i = 0 … segments`, each with its point and
    /// first derivative. The first and last parameters are exactly `a` and `b`.
    ///
    /// `segments == 0` is treated as `1` (the two end points), so the result
    /// always spans the whole curve; more than [`MAX_SEGMENTS`] are capped to
    /// it. If the samples cannot be allocated the result is empty (use
    /// [`try_discretize`](Curve::try_discretize) to get the error).
    ///
    /// A domain that breaks the [contract](Curve#contract) is sampled as
    /// given: a reversed one from `a` down to `b`; a NaN or infinite end
    /// gives NaN or infinite parameters, passed to `eval` as they are. It
    /// never panics.
    fn discretize(&self, segments: usize) -> Vec<CurveSample<D>> {
        self.try_discretize(segments.min(MAX_SEGMENTS))
            .unwrap_or_default()
    }

    /// As [`discretize`](Curve::discretize), with the limits reported.
    ///
    /// # Errors
    /// [`Error::TooManySegments`] above [`MAX_SEGMENTS`];
    /// [`Error::AllocationFailed`] if the samples cannot be allocated.
    fn try_discretize(&self, segments: usize) -> Result<Vec<CurveSample<D>>, Error> {
        if segments > MAX_SEGMENTS {
            return Err(Error::TooManySegments {
                segments,
                max: MAX_SEGMENTS,
            });
        }
        let segments = segments.max(1);
        let (a, b) = self.domain();
        let mut samples = crate::allocation::try_with_capacity(segments + 1)?;
        samples.extend((0..=segments).map(|i| {
            let s = i as f64 / segments as f64;
            let t = match i {
                0 => a,
                i if i == segments => b,
                _ => a * (1.0 - s) + b * s,
            };
            let (point, derivative) = self.eval_with_derivative(t);
            CurveSample {
                t,
                point,
                derivative,
            }
        }));
        Ok(samples)
    }
}

/// One sample of a curve: the parameter, the point and the first derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSample<const D: usize> {
    /// The curve parameter.
    pub t: f64,
    /// The point `P(t)`.
    pub point: Point<f64, D>,
    /// The derivative `dP/dt` at `t`.
    pub derivative: SVector<f64, D>,
}

/// Checks that there is at least one control point and that every coordinate
/// is finite and at most [`MAX_COORDINATE`](crate::MAX_COORDINATE) in magnitude.
pub(crate) fn validate_points<const D: usize>(points: &[Point<f64, D>]) -> Result<(), Error> {
    if points.is_empty() {
        return Err(Error::NoControlPoints);
    }
    for (index, p) in points.iter().enumerate() {
        for &value in p.coords.iter() {
            if !value.is_finite() {
                return Err(Error::NonFinitePoint { index });
            }
            if value.abs() > crate::MAX_COORDINATE {
                return Err(Error::CoordinateTooLarge { index, value });
            }
        }
    }
    Ok(())
}

/// The parameter moved into `[a, b]`: clamped, and NaN mapped to `a`.
#[inline(always)]
pub(crate) fn clamp_to_domain(t: f64, (a, b): (f64, f64)) -> f64 {
    if t >= a {
        if t <= b { t } else { b }
    } else {
        // Below the domain, or NaN.
        a
    }
}

/// Checks that `t` is a number inside `[a, b]`.
pub(crate) fn check_in_domain(t: f64, domain: (f64, f64)) -> Result<(), Error> {
    if t >= domain.0 && t <= domain.1 {
        Ok(())
    } else {
        Err(Error::ParameterOutOfDomain { t, domain })
    }
}

/// The axis-aligned box of a set of points, as (min corner, max corner).
pub(crate) fn point_bounds<const D: usize>(
    points: &[Point<f64, D>],
) -> (Point<f64, D>, Point<f64, D>) {
    let first = points.first().map_or_else(SVector::zeros, |p| p.coords);
    let (lo, hi) = points.iter().fold((first, first), |(lo, hi), p| {
        (lo.inf(&p.coords), hi.sup(&p.coords))
    });
    (Point::from(lo), Point::from(hi))
}

/// The largest absolute coordinate of the points (`0` for none).
pub(crate) fn max_abs_coordinate<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points.iter().fold(0.0_f64, |m, p| m.max(p.coords.amax()))
}

/// [`Error::InvalidTolerance`] unless `tolerance` is finite and positive.
pub(crate) fn check_tolerance(tolerance: f64) -> Result<(), Error> {
    if tolerance.is_finite() && tolerance > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidTolerance { tolerance })
    }
}

/// `|v|`, computed as `m·|v/m|` with `m` the largest absolute component, so
/// that no size of `v` underflows or overflows the squares (a length of
/// 1e-200 would otherwise come out as 0).
pub(crate) fn scaled_norm<const D: usize>(v: SVector<f64, D>) -> f64 {
    let m = v.amax();
    if m > 0.0 && m.is_finite() {
        m * (v / m).norm()
    } else {
        v.norm()
    }
}

/// `v / |v|`, computed as `(v/m) / |v/m|` with `m` the largest absolute
/// component, so that no size of `v` overflows or underflows the norm.
/// `None` for the zero vector and for vectors with a NaN or infinite
/// component.
pub(crate) fn unit_direction<const D: usize>(v: SVector<f64, D>) -> Option<Unit<SVector<f64, D>>> {
    let m = v.amax();
    if !(m > 0.0 && v.iter().all(|c| c.is_finite())) {
        return None;
    }
    Unit::try_new(v / m, 0.0)
}

/// `v` moved into the box `[lo, hi]` (per coordinate). For a convex
/// combination of points whose box that is, this only removes rounding: the
/// exact value lies in the box.
#[inline]
pub(crate) fn clamp_to_box<const D: usize>(
    v: SVector<f64, D>,
    (lo, hi): (Point<f64, D>, Point<f64, D>),
) -> SVector<f64, D> {
    v.sup(&lo.coords).inf(&hi.coords)
}

/// The size `scale · n!/(n − k)! / wᵏ` that the `k`-th derivative of a
/// polynomial piece of degree `n`, coordinates up to `scale` and parameter
/// width `w` has at most: what "negligible" is relative to.
pub(crate) struct NaturalSize {
    /// The largest absolute control-point coordinate.
    pub(crate) scale: f64,
    /// The degree `n`.
    pub(crate) degree: usize,
    /// The parameter width `w` of the piece.
    pub(crate) width: f64,
}

impl NaturalSize {
    /// The size for a piece of degree `degree` and parameter width `width`
    /// of a curve with control points `points` (their largest absolute
    /// coordinate is the scale).
    pub(crate) fn of_points<const D: usize>(
        points: &[Point<f64, D>],
        degree: usize,
        width: f64,
    ) -> Self {
        NaturalSize {
            scale: max_abs_coordinate(points),
            degree,
            width,
        }
    }

    /// Whether `|v| > 1e-12 · size(k)`, for `v` with largest absolute
    /// component `m > 0` and `rel = |v/m|`. Compared directly when the size
    /// is a normal number, else in logarithms, so that neither side
    /// overflows or underflows.
    fn is_exceeded_by(&self, k: usize, m: f64, rel: f64) -> bool {
        const NEGLIGIBLE: f64 = 1e-12;
        if self.scale == 0.0 {
            return true;
        }
        let falling: f64 = (self.degree + 1 - k.min(self.degree)..=self.degree)
            .map(|x| x as f64)
            .product();
        let size = self.scale * falling / self.width.powi(k as i32);
        if size.is_finite() && size >= 1e-290 {
            return m * rel > NEGLIGIBLE * size;
        }
        let ln_falling: f64 = (self.degree + 1 - k.min(self.degree)..=self.degree)
            .map(|x| (x as f64).ln())
            .sum();
        let ln_size = self.scale.ln() + ln_falling - k as f64 * self.width.ln();
        m.ln() + rel.ln() > NEGLIGIBLE.ln() + ln_size
    }
}

/// The unit tangent from the first derivative of order `1 ..= size.degree`
/// that is not negligible, oriented toward increasing `t`.
///
/// Near `t₀` the curve is `C(t₀) + C⁽ᵏ⁾(t₀)(t − t₀)ᵏ/k! + …`, so the limit of
/// the tangent from the right is `C⁽ᵏ⁾` and from the left (`from_left`, used at
/// the end of the domain) `(−1)ᵏ⁺¹ C⁽ᵏ⁾`. Derivative `k` counts as zero when
/// it is below `1e-12 ·` its [`NaturalSize`] for a curve of that scale.
pub(crate) fn tangent_from_derivatives<const D: usize>(
    size: NaturalSize,
    from_left: bool,
    nth: impl Fn(usize) -> SVector<f64, D>,
) -> Option<Unit<SVector<f64, D>>> {
    for k in 1..=size.degree {
        let d = nth(k);
        let Some(unit) = unit_direction(d) else {
            continue;
        };
        let m = d.amax();
        if size.is_exceeded_by(k, m, (d / m).norm()) {
            let flip = from_left && k % 2 == 0;
            return Some(if flip { -unit } else { unit });
        }
    }
    None
}

/// Checks that the derivatives of orders `1 ..= n` of the Bézier piece with
/// coefficients `c` (degree `n = c.len() − 1`) on a parameter interval of
/// width `w` stay within [`MAX_DERIVATIVE`] as the crate evaluates them.
///
/// The order-`k` hodograph's coefficients are computed as the evaluators
/// compute them, `h⁽ᵏ⁾ᵢ = ((h⁽ᵏ⁻¹⁾ᵢ₊₁ − h⁽ᵏ⁻¹⁾ᵢ)·(n − k + 1))/w`, so de Casteljau
/// on them (a convex combination) stays within their maximum. The derivative
/// of order `k` can also be computed by de Casteljau on order `k − 1` and a
/// difference of its last level, whose rounding adds at most
/// `4n²ε·max|h⁽ᵏ⁻¹⁾|/w`; that is added to the maximum before comparing.
/// Pieces with `max|cᵢ|·(2n/w)ⁿ ≤ MAX_DERIVATIVE/2` pass at once (a bound on
/// every order, rounding included).
///
/// # Errors
/// [`Error::DerivativeOverflow`] with the first order that could exceed it.
pub(crate) fn check_derivatives<const D: usize>(
    c: &[SVector<f64, D>],
    w: f64,
) -> Result<(), Error> {
    let n = c.len().saturating_sub(1);
    let rounding = 4.0 * (n as f64) * (n as f64) * f64::EPSILON;
    let magnitude = |h: &[SVector<f64, D>]| {
        h.iter().fold(0.0_f64, |m, v| {
            v.iter().fold(m, |m, x| {
                if x.is_nan() {
                    f64::INFINITY
                } else {
                    m.max(x.abs())
                }
            })
        })
    };
    // Each order multiplies the magnitude by at most 2n/w (and rounding by
    // 1 + 3ε), so small enough pieces pass without computing hodographs.
    let growth = (2.0 * n as f64 / w).max(1.0);
    let first = magnitude(c);
    if first * growth.powi(n.min(i32::MAX as usize) as i32) <= 0.5 * MAX_DERIVATIVE {
        return Ok(());
    }
    crate::scratch::with_scratch(c.len(), SVector::zeros(), |h| {
        h.copy_from_slice(c);
        let mut previous = first;
        for order in 1..=n {
            let len = n + 1 - order;
            let factor = len as f64;
            for j in 0..len {
                h[j] = ((h[j + 1] - h[j]) * factor) / w;
            }
            let current = magnitude(&h[..len]);
            let bound = current + rounding * previous / w;
            if bound > MAX_DERIVATIVE || bound.is_nan() {
                return Err(Error::DerivativeOverflow { order });
            }
            if current == 0.0 {
                // Every higher derivative is zero too.
                break;
            }
            previous = current;
        }
        Ok(())
    })
}

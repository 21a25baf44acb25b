//! Rational Bézier curves: one piece of a NURBS curve, and exact conics.

use super::homogeneous::{
    Homogeneous, check_derivative_order, finish_derivatives, homogeneous_points, one_derivative,
    project, project_with_derivative, quotient_rule, weight_scale,
};
use super::{
    NaturalSize, check_derivatives, clamp_to_box, clamp_to_domain, point_bounds,
    tangent_from_derivatives, validate_points,
};
use crate::bernstein::{self, nth_derivative_in_place};
use crate::scratch::with_scratch;
use crate::{Bezier, BezierSpan, Curve, Error};
use nalgebra::{Point, SVector, Unit};

/// The largest ratio between a rational curve's largest and smallest weight
/// (`1e8`). Beyond it the curve is, to rounding, its control polygon near the
/// heavy points, and derivatives grow with the ratio.
pub const MAX_WEIGHT_RATIO: f64 = 1e8;

/// A rational Bézier curve `P(t) = Σᵢ wᵢPᵢBᵢⁿ(t) / Σᵢ wᵢBᵢⁿ(t)`,
/// `t ∈ [0, 1]`, with positive weights `wᵢ`.
///
/// Evaluation runs de Casteljau's algorithm on the homogeneous points
/// `(wᵢPᵢ, wᵢ)` and divides (Farin, *Curves and Surfaces for CAGD*, ch. 13);
/// derivatives of order `k` come from the homogeneous hodographs by the
/// quotient rule. With positive weights the curve lies in the convex hull of
/// its control points; the evaluated point is kept in their bounding box.
/// Equal weights give the polynomial [`Bezier`] of the same points.
///
/// Parameters outside `[0, 1]` evaluate at the nearest end and NaN at `t = 0`.
///
/// ```
/// use revolve::Curve;
/// use revolve::curve::RationalBezier;
/// use revolve::nalgebra::Point2;
///
/// // A quarter of the unit circle: weights 1, √2/2, 1.
/// let h = std::f64::consts::FRAC_1_SQRT_2;
/// let quarter = RationalBezier::new(
///     vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(0.0, 1.0)],
///     vec![1.0, h, 1.0],
/// )?;
/// for k in 0..=10 {
///     let p = quarter.eval(k as f64 / 10.0);
///     assert!((p.coords.norm() - 1.0).abs() < 1e-15);
/// }
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBezier<const D: usize> {
    points: Vec<Point<f64, D>>,
    weights: Vec<f64>,
    /// `(wᵢPᵢ, wᵢ)`, with the weights divided by a power of two near the
    /// largest.
    homogeneous: Vec<Homogeneous<D>>,
    /// The control points' bounding box, which contains the curve.
    bounds: (Point<f64, D>, Point<f64, D>),
}

/// One rational piece of a curve as a [`RationalBezier`]: on the knot
/// interval `knots = (a, b)` the curve equals `curve((t − a)/(b − a))`.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBezierSpan<const D: usize> {
    /// The knot interval `(a, b)` the piece covers, `a < b`.
    pub knots: (f64, f64),
    /// The piece over `[0, 1]`.
    pub curve: RationalBezier<D>,
}

impl<const D: usize> From<BezierSpan<D>> for RationalBezierSpan<D> {
    /// The polynomial span with unit weights.
    fn from(span: BezierSpan<D>) -> Self {
        RationalBezierSpan {
            knots: span.knots,
            curve: RationalBezier::from(span.curve),
        }
    }
}

impl<const D: usize> From<Bezier<D>> for RationalBezier<D> {
    /// The same curve with unit weights.
    fn from(curve: Bezier<D>) -> Self {
        let n = curve.points().len();
        RationalBezier::from_valid_parts(curve.points().to_vec(), vec![1.0; n])
    }
}

/// Checks `weights` for a curve of `count` control points: one per point,
/// each finite and positive, largest over smallest at most
/// [`MAX_WEIGHT_RATIO`].
///
/// # Errors
/// [`Error::WeightCount`], [`Error::InvalidWeight`] (the first bad one),
/// [`Error::WeightRatioTooLarge`].
pub(crate) fn validate_weights(weights: &[f64], count: usize) -> Result<(), Error> {
    if weights.len() != count {
        return Err(Error::WeightCount {
            expected: count,
            found: weights.len(),
        });
    }
    if let Some(index) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
        return Err(Error::InvalidWeight {
            index,
            weight: weights[index],
        });
    }
    let (lo, hi) = weights
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &w| {
            (lo.min(w), hi.max(w))
        });
    // Compared as `hi > ratio·lo` so that tiny weights do not overflow.
    if hi > MAX_WEIGHT_RATIO * lo {
        return Err(Error::WeightRatioTooLarge {
            ratio: hi / lo,
            max: MAX_WEIGHT_RATIO,
        });
    }
    Ok(())
}

/// Weights whose largest lies outside `[2⁻⁵⁰⁰, 2⁵⁰⁰]` scaled by one power of
/// two (exactly: the product of a float and a power of two is exact while it
/// neither overflows nor underflows) so that the largest is in `[1, 2)`; other
/// weights unchanged. A rational curve does not change when all its weights
/// are multiplied by one factor, and subnormal weights (a few bits each) would
/// otherwise lose what knot insertion and elevation compute from them.
pub(crate) fn normalized_weights(mut weights: Vec<f64>) -> Vec<f64> {
    const EXTREME: f64 = 500.0;
    let max = weights.iter().fold(0.0_f64, |m, &w| m.max(w));
    if max > 0.0 && max.is_finite() && max.log2().abs() > EXTREME {
        // 2^−e in two exact factors (2^±1074 alone is out of range).
        let e = max.log2().floor() as i32;
        let (a, b) = (-e / 2, -e - (-e / 2));
        let (fa, fb) = (2.0_f64.powi(a), 2.0_f64.powi(b));
        for w in &mut weights {
            *w = *w * fa * fb;
        }
    }
    weights
}

impl<const D: usize> RationalBezier<D> {
    /// A rational Bézier curve of the given control points and weights
    /// (degree = count − 1).
    ///
    /// # Errors
    /// As [`Bezier::new`] for the points; then [`Error::WeightCount`],
    /// [`Error::InvalidWeight`] (zero, negative, NaN or infinite) or
    /// [`Error::WeightRatioTooLarge`]; [`Error::DerivativeOverflow`] when a
    /// homogeneous hodograph could exceed
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE).
    pub fn new(points: Vec<Point<f64, D>>, weights: Vec<f64>) -> Result<Self, Error> {
        validate_points(&points)?;
        validate_weights(&weights, points.len())?;
        let curve = Self::from_valid_parts(points, normalized_weights(weights));
        let coords: Vec<SVector<f64, D>> = curve.homogeneous.iter().map(|h| h.wp).collect();
        check_derivatives(&coords, 1.0)?;
        Ok(curve)
    }

    /// Wraps points and weights the crate computed from valid input.
    pub(crate) fn from_valid_parts(points: Vec<Point<f64, D>>, weights: Vec<f64>) -> Self {
        debug_assert_eq!(points.len(), weights.len());
        // Divided by a power of two (exact), so that end points come out
        // exactly.
        let scale = weight_scale(&weights);
        let homogeneous = homogeneous_points(&points, weights.iter().map(|&w| w / scale));
        let bounds = point_bounds(&points);
        RationalBezier {
            points,
            weights,
            homogeneous,
            bounds,
        }
    }

    /// The control points.
    pub fn points(&self) -> &[Point<f64, D>] {
        &self.points
    }

    /// The weights, as given; weights that all lie below `2⁻⁵⁰⁰` or above
    /// `2⁵⁰⁰` are scaled by one power of two at construction (exactly, the
    /// curve unchanged) so that the largest is in `[1, 2)`.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The degree `n` (number of control points − 1).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The same curve traced backward: `P_rev(t) = P(1 − t)` on `[0, 1]`,
    /// the control points and weights in reverse order (exact), so
    /// `P_rev⁽ᵏ⁾(t) = (−1)ᵏ P⁽ᵏ⁾(1 − t)` and `reversed().reversed()` is the
    /// original.
    pub fn reversed(&self) -> Self {
        let points = self.points.iter().rev().copied().collect();
        let weights = self.weights.iter().rev().copied().collect();
        Self::from_valid_parts(points, weights)
    }

    /// Whether all weights are equal: the curve is then the polynomial
    /// [`Bezier`] of its points.
    pub fn is_polynomial(&self) -> bool {
        self.weights.iter().all(|&w| w == self.weights[0])
    }

    /// The axis-aligned bounding box of the control points, `(min, max)`. By
    /// the convex hull property (positive weights) it contains the curve.
    pub fn bounds(&self) -> (Point<f64, D>, Point<f64, D>) {
        self.bounds
    }

    /// The derivatives `P, P′, …, P⁽ᵏ⁾` at `t`, `k = out.len() − 1`, by the
    /// quotient rule on the homogeneous hodographs. Unlike a polynomial's,
    /// a rational curve's derivatives do not vanish above the degree; they
    /// grow like `k!`, and orders whose value leaves the floating-point
    /// range give an error.
    ///
    /// # Errors
    /// [`Error::DerivativeOrderTooHigh`] beyond
    /// [`MAX_DERIVATIVE_ORDER`](crate::curve::MAX_DERIVATIVE_ORDER);
    /// [`Error::DerivativeOverflow`] with the first order that is not finite.
    pub fn derivatives(&self, t: f64, out: &mut [SVector<f64, D>]) -> Result<(), Error> {
        let orders = out.len();
        if orders == 0 {
            return Ok(());
        }
        check_derivative_order(orders - 1)?;
        let t = clamp_to_domain(t, (0.0, 1.0));
        let n = self.homogeneous.len();
        with_scratch(orders + n, Homogeneous::zero(), |s| {
            let (h, work) = s.split_at_mut(orders);
            for (k, hk) in h.iter_mut().enumerate() {
                // The k-th homogeneous derivative: the k-th hodograph at t.
                if k >= n {
                    *hk = Homogeneous::zero();
                    continue;
                }
                work.copy_from_slice(&self.homogeneous);
                *hk = nth_derivative_in_place(work, k, t).unwrap_or_else(Homogeneous::zero);
            }
            quotient_rule(h, out);
        });
        finish_derivatives(out, self.bounds)
    }

    /// The `order`-th derivative at `t` (order 0 is the point as a vector).
    ///
    /// # Errors
    /// As [`derivatives`](Self::derivatives).
    pub fn nth_derivative(&self, t: f64, order: usize) -> Result<SVector<f64, D>, Error> {
        check_derivative_order(order)?;
        one_derivative(order, |out| self.derivatives(t, out))
    }
}

impl<const D: usize> Curve<D> for RationalBezier<D> {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    #[inline]
    fn eval(&self, t: f64) -> Point<f64, D> {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let h = bernstein::eval(&self.homogeneous, t).unwrap_or_else(Homogeneous::zero);
        Point::from(clamp_to_box(project(h).coords, self.bounds))
    }

    #[inline]
    fn derivative(&self, t: f64) -> SVector<f64, D> {
        self.eval_with_derivative(t).1
    }

    #[inline]
    fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let (h, dh) = bernstein::eval_with_derivative(&self.homogeneous, t)
            .unwrap_or_else(|| (Homogeneous::zero(), Homogeneous::zero()));
        let (p, d) = project_with_derivative(h, dh);
        (Point::from(clamp_to_box(p.coords, self.bounds)), d)
    }

    /// The curve itself as a polynomial span when its weights are equal;
    /// `None` otherwise (see
    /// [`rational_bezier_spans`](Curve::rational_bezier_spans)).
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        self.is_polynomial().then(|| {
            vec![BezierSpan {
                knots: (0.0, 1.0),
                curve: Bezier::from_valid_points(self.points.clone()),
            }]
        })
    }

    /// One span: the curve itself on `(0, 1)`.
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<D>>> {
        Some(vec![RationalBezierSpan {
            knots: (0.0, 1.0),
            curve: self.clone(),
        }])
    }

    /// Exact: the first non-negligible derivative of order `1 … n`.
    fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let size = NaturalSize::of_points(&self.points, self.degree(), 1.0);
        tangent_from_derivatives(size, t >= 1.0, |k| {
            self.nth_derivative(t, k)
                .unwrap_or_else(|_| SVector::zeros())
        })
    }
}

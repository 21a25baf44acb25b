//! Bézier curves of any degree and dimension.

use super::flatten::{Flattening, flatten_pieces};
use super::{
    NaturalSize, check_derivatives, check_in_domain, clamp_to_box, clamp_to_domain, point_bounds,
    tangent_from_derivatives, validate_points,
};
use crate::bernstein::{self, nth_derivative_in_place, subdivide};
use crate::scratch::with_scratch;
use crate::{Curve, Error};
use nalgebra::{Point, SVector, Unit};

/// A Bézier curve `P(t) = Σᵢ Pᵢ Bᵢⁿ(t)`, `t ∈ [0, 1]`, of degree `n` (one less
/// than the number of control points) in `D` dimensions.
///
/// Evaluation runs de Casteljau's algorithm on stack scratch space (no heap
/// allocation up to degree 16). Derivatives of order `k` come from the `k`-th
/// hodograph, `n!/(n−k)! · Σ Δᵏ Pᵢ Bᵢⁿ⁻ᵏ(t)` (Farin, *Curves and Surfaces for
/// CAGD*, §5.3).
///
/// Parameters outside `[0, 1]` evaluate at the nearest end (the curve is not
/// extrapolated) and NaN evaluates at `t = 0`, so evaluation never returns NaN.
///
/// ```
/// use revolve::{Bezier, Curve};
/// use revolve::nalgebra::Point2;
///
/// // The parabola y = x² on [0, 1] as a quadratic Bézier.
/// let parabola = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(0.5, 0.0), Point2::new(1.0, 1.0)])?;
/// let p = parabola.eval(0.5);
/// assert!((p.y - p.x * p.x).abs() < 1e-15);
/// assert_eq!(parabola.nth_derivative(0.3, 2)?.y, 2.0); // second derivative of t²
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Bezier<const D: usize> {
    points: Vec<Point<f64, D>>,
    /// The same points as vectors: the form the Bernstein kernels evaluate.
    coeffs: Vec<SVector<f64, D>>,
}

/// One polynomial piece of a B-spline as a Bézier curve: on the knot interval
/// `knots = (a, b)` the spline equals `curve((t − a)/(b − a))`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSpan<const D: usize> {
    /// The knot interval `(a, b)` the piece covers, `a < b`.
    pub knots: (f64, f64),
    /// The piece as a Bézier curve over `[0, 1]`, of the spline's degree.
    pub curve: Bezier<D>,
}

impl<const D: usize> Bezier<D> {
    /// A Bézier curve through the given control points (degree = count − 1).
    ///
    /// # Errors
    /// [`Error::NoControlPoints`] for an empty list, [`Error::NonFinitePoint`]
    /// for a NaN or infinite coordinate, [`Error::CoordinateTooLarge`] beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), and
    /// [`Error::DerivativeOverflow`] when the hodograph of some order `k` has
    /// a control point `n!/(n−k)!·ΔᵏPᵢ` beyond
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE) (high degrees with
    /// large, alternating coordinates). Derivatives of every order of an
    /// accepted curve are finite.
    pub fn new(points: Vec<Point<f64, D>>) -> Result<Self, Error> {
        validate_points(&points)?;
        let curve = Self::from_valid_points(points);
        check_derivatives(&curve.coeffs, 1.0)?;
        Ok(curve)
    }

    /// Wraps points the crate computed from valid input (finite, non-empty;
    /// derived curves such as hodographs may exceed `MAX_COORDINATE`).
    pub(crate) fn from_valid_points(points: Vec<Point<f64, D>>) -> Self {
        debug_assert!(
            !points.is_empty()
                && points
                    .iter()
                    .all(|p| p.coords.iter().all(|c| c.is_finite()))
        );
        let coeffs = points.iter().map(|p| p.coords).collect();
        Self { points, coeffs }
    }

    /// Wraps points that are convex combinations of `hull`'s points
    /// (subdivision, blossoms), moved into `hull`'s bounding box first: the
    /// exact values lie there, so this only removes rounding, and the result
    /// stays within [`MAX_COORDINATE`](crate::MAX_COORDINATE) when `hull` is.
    pub(crate) fn from_combinations(
        points: impl IntoIterator<Item = SVector<f64, D>>,
        hull: &[Point<f64, D>],
    ) -> Self {
        let bounds = point_bounds(hull);
        Self::from_valid_points(
            points
                .into_iter()
                .map(|v| Point::from(clamp_to_box(v, bounds)))
                .collect(),
        )
    }

    /// The control points.
    pub fn points(&self) -> &[Point<f64, D>] {
        &self.points
    }

    /// The degree `n` (number of control points − 1).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The same curve traced backward: `P_rev(t) = P(1 − t)` on `[0, 1]`,
    /// the control points in reverse order (exact: no arithmetic), so
    /// `P_rev⁽ᵏ⁾(t) = (−1)ᵏ P⁽ᵏ⁾(1 − t)` and `reversed().reversed()` is the
    /// original.
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 0.0)])?;
    /// let back = c.reversed();
    /// assert_eq!(back.points()[0], Point2::new(3.0, 0.0));
    /// assert_eq!(back.eval(0.25), c.eval(0.75));
    /// assert_eq!(back.derivative(0.0), -c.derivative(1.0));
    /// assert_eq!(back.reversed(), c);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn reversed(&self) -> Self {
        Self::from_valid_points(self.points.iter().rev().copied().collect())
    }

    /// The `order`-th derivative `dᵏP/dtᵏ` at `t` (order 0 is the point as a
    /// vector). Orders above the degree give the zero vector.
    ///
    /// No heap allocation up to degree 16. Never an `Err`: the `Result` is the
    /// shape every curve's `nth_derivative` has (a rational curve's refuses
    /// orders beyond [`MAX_DERIVATIVE_ORDER`](crate::curve::MAX_DERIVATIVE_ORDER)).
    ///
    /// ```
    /// use revolve::Bezier;
    /// use revolve::nalgebra::Point2;
    ///
    /// let parabola = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(0.5, 0.0), Point2::new(1.0, 1.0)])?;
    /// assert_eq!(parabola.nth_derivative(0.3, 2)?.y, 2.0);
    /// assert_eq!(parabola.nth_derivative(0.3, 3)?.norm(), 0.0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn nth_derivative(&self, t: f64, order: usize) -> Result<SVector<f64, D>, Error> {
        Ok(self.derivative_of_order(t, order))
    }

    /// [`nth_derivative`](Self::nth_derivative)'s value.
    fn derivative_of_order(&self, t: f64, order: usize) -> SVector<f64, D> {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let n = self.points.len();
        if order >= n {
            return SVector::zeros();
        }
        with_scratch(n, SVector::zeros(), |s| {
            s.copy_from_slice(&self.coeffs);
            nth_derivative_in_place(s, order, t).unwrap_or_else(SVector::zeros)
        })
    }

    /// The hodograph: the derivative curve `P′(t)`, a Bézier of degree `n − 1`
    /// with control points `n·(Pᵢ₊₁ − Pᵢ)`. The derivative of a constant curve
    /// (degree 0) is the constant zero curve. Its points may exceed
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE) (up to
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE)); its derivatives are
    /// this curve's higher ones, finite.
    pub fn hodograph(&self) -> Bezier<D> {
        let n = self.degree();
        if n == 0 {
            return Bezier::from_valid_points(vec![Point::origin()]);
        }
        let points = self
            .coeffs
            .windows(2)
            .map(|w| Point::from((w[1] - w[0]) * n as f64))
            .collect();
        Bezier::from_valid_points(points)
    }

    /// Splits the curve at `t` into the pieces on `[0, t]` and `[t, 1]`, each a
    /// Bézier of the same degree reparametrized to `[0, 1]` (de Casteljau
    /// subdivision).
    ///
    /// The pieces' control points are convex combinations of this curve's
    /// and are kept in its bounding box (no rounding outside it).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside `[0, 1]`;
    /// [`Error::DerivativeOverflow`] if rounding made a piece's derivatives
    /// exceed the bound of [`new`](Self::new) (only for curves at that bound).
    pub fn subdivide(&self, t: f64) -> Result<(Bezier<D>, Bezier<D>), Error> {
        check_in_domain(t, (0.0, 1.0))?;
        let mut left = self.coeffs.clone();
        let mut right = self.coeffs.clone();
        subdivide(&self.coeffs, t, &mut left, &mut right);
        let left = Bezier::from_combinations(left, &self.points);
        let right = Bezier::from_combinations(right, &self.points);
        check_derivatives(&left.coeffs, 1.0)?;
        check_derivatives(&right.coeffs, 1.0)?;
        Ok((left, right))
    }

    /// The axis-aligned bounding box of the control points, `(min, max)`. By
    /// the convex hull property it contains the whole curve.
    pub fn bounds(&self) -> (Point<f64, D>, Point<f64, D>) {
        point_bounds(&self.points)
    }

    /// Adaptive flattening: samples (with derivatives) such that the polyline
    /// through them is within `tolerance` of the curve, with the bound it
    /// guarantees. See [`Flattening`] for how the bound is obtained.
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] for a tolerance that is not finite and
    /// positive; [`Error::ToleranceTooSmall`] below `1e-10 ×` the largest
    /// control-point coordinate (double precision cannot certify less).
    pub fn flatten(&self, tolerance: f64) -> Result<Flattening<D>, Error> {
        flatten_pieces(
            self,
            std::iter::once((&self.points[..], (0.0, 1.0))),
            tolerance,
        )
    }
}

impl<const D: usize> Curve<D> for Bezier<D> {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    #[inline]
    fn eval(&self, t: f64) -> Point<f64, D> {
        let t = clamp_to_domain(t, (0.0, 1.0));
        Point::from(bernstein::eval(&self.coeffs, t).unwrap_or_else(SVector::zeros))
    }

    #[inline]
    fn derivative(&self, t: f64) -> SVector<f64, D> {
        self.eval_with_derivative(t).1
    }

    /// One span: the curve itself on `(0, 1)`.
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        Some(vec![BezierSpan {
            knots: (0.0, 1.0),
            curve: self.clone(),
        }])
    }

    /// Exact: the first non-negligible hodograph of order `1 … n`.
    fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let size = NaturalSize::of_points(&self.points, self.degree(), 1.0);
        tangent_from_derivatives(size, t >= 1.0, |k| self.derivative_of_order(t, k))
    }

    #[inline]
    fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let t = clamp_to_domain(t, (0.0, 1.0));
        let (p, d) = bernstein::eval_with_derivative(&self.coeffs, t)
            .unwrap_or_else(|| (SVector::zeros(), SVector::zeros()));
        (Point::from(p), d)
    }
}

//! Rational B-spline curves (NURBS).
//!
//! Notation as for [`BSpline`] (Piegl & Tiller, *The NURBS Book*, ch. 4):
//! degree `p`, control points `P₀ … P_{n−1}` with weights `wᵢ > 0`, knots
//! `t₀ ≤ … ≤ t_{n+p}`. The curve
//!
//! `C(t) = Σᵢ wᵢPᵢNᵢ,ₚ(t) / Σᵢ wᵢNᵢ,ₚ(t)`
//!
//! is the projection of the B-spline `H(t) = Σᵢ (wᵢPᵢ, wᵢ) Nᵢ,ₚ(t)` of the
//! homogeneous points, one dimension up. Every polynomial algorithm
//! (blossoming, knot insertion, de Casteljau, hodographs) runs on the
//! homogeneous points; the division comes last.

use super::flatten::{Flattening, flatten_controls};
use super::homogeneous::{
    check_derivative_order, finish_derivatives, homogeneous_points, max_weight, one_derivative,
    power_of_two_near, project, project_with_derivative, weight_scale,
};
use super::knots::{
    self, boehm_insert, check_derivative_points, de_boor, derivative_control_step, validate_knots,
};
use super::pieces::PieceTable;
use super::{
    Homogeneous, MAX_DERIVATIVE, NaturalSize, check_derivatives, clamp_to_box, clamp_to_domain,
    normalized_weights, point_bounds, quotient_rule, tangent_from_derivatives, validate_points,
    validate_weights,
};
use crate::bernstein::lerp;
use crate::scratch::with_scratch;
use crate::{BSpline, BezierSpan, Curve, Error, RationalBezier, RationalBezierSpan};
use nalgebra::{Point, Point1, SVector, Unit, Vector1};

/// A rational B-spline curve (NURBS) of any degree in `D` dimensions:
/// `C(t) = Σᵢ wᵢPᵢNᵢ,ₚ(t) / Σᵢ wᵢNᵢ,ₚ(t)` with positive weights `wᵢ`, on the
/// domain `[t_p, t_n]`.
///
/// At construction every non-empty knot span gets its rational Bézier form
/// (blossoms of the homogeneous points `(wᵢPᵢ, wᵢ)`, Piegl & Tiller §5.2,
/// weights scaled so that each piece's largest is 1). Evaluation finds the
/// piece, runs de Casteljau's algorithm on its homogeneous points and
/// divides; derivatives of order `k` come from the homogeneous hodographs by
/// the quotient rule (Piegl & Tiller eq. 4.8). With positive weights the
/// curve lies in the convex hull of its control points; the evaluated point
/// is kept in their bounding box. No heap allocation up to degree 16.
///
/// All weights equal give the [`BSpline`] of the same degree, knots and
/// points (its Bézier pieces exactly, its values to rounding), and
/// [`bezier_spans`](Curve::bezier_spans) then gives the polynomial pieces.
///
/// # Edge rules
/// As [`BSpline`]: spans are half-open, `[tᵢ, tᵢ₊₁)`, so at an interior knot
/// of full multiplicity the value is the limit from the right; the end of
/// the domain belongs to the last non-empty span. Parameters outside the
/// domain evaluate (value and derivatives) at the nearest end, NaN at the
/// start. Evaluation never returns NaN.
///
/// ```
/// use revolve::{Curve, Nurbs};
/// use revolve::nalgebra::Point2;
///
/// // The whole circle of radius 2 about (1, 1), exactly: four rational quarter arcs.
/// let circle = Nurbs::circle(Point2::new(1.0, 1.0), 2.0)?;
/// assert_eq!(circle.degree(), 2);
/// for s in circle.discretize(64) {
///     let radius = s.point - Point2::new(1.0, 1.0);
///     assert!((radius.norm() - 2.0).abs() < 1e-15);
///     // The tangent is perpendicular to the radius.
///     assert!(radius.dot(&s.derivative).abs() < 1e-13 * s.derivative.norm());
/// }
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs<const D: usize> {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Point<f64, D>>,
    weights: Vec<f64>,
    /// `(wᵢPᵢ, wᵢ)` with the weights scaled by a power of two (exactly) so
    /// that the largest is in `[1, 2)`; all 1 when the curve is polynomial.
    homogeneous: Vec<Homogeneous<D>>,
    /// The rational Bézier form of every non-empty span as homogeneous
    /// points, scaled by a power of two so that the piece's largest weight
    /// is in `[1, 2)` (exactly 1 for all of them when the curve is
    /// polynomial). Exact scaling keeps the end points of clamped curves
    /// exact where the weight there is a power of two times the largest.
    pieces: PieceTable<Homogeneous<D>>,
    /// The control points' bounding box, which contains the curve.
    bounds: (Point<f64, D>, Point<f64, D>),
    /// All weights are equal: the curve is the B-spline of its points.
    polynomial: bool,
}

impl<const D: usize> Nurbs<D> {
    /// A rational B-spline of the given degree, knot vector, control points
    /// and weights (one per point).
    ///
    /// # Errors
    /// In the order checked: the errors of [`BSpline::new`] for the points
    /// and knots ([`Error::NoControlPoints`], [`Error::NonFinitePoint`],
    /// [`Error::CoordinateTooLarge`], [`Error::DegreeTooHigh`],
    /// [`Error::KnotCount`], [`Error::NonFiniteKnot`],
    /// [`Error::KnotTooLarge`], [`Error::DecreasingKnots`],
    /// [`Error::KnotGapTooSmall`], [`Error::KnotMultiplicity`],
    /// [`Error::EmptyDomain`]); then the weights: [`Error::WeightCount`],
    /// [`Error::InvalidWeight`] (zero, negative, NaN or infinite),
    /// [`Error::WeightRatioTooLarge`] (largest over smallest beyond
    /// [`MAX_WEIGHT_RATIO`](crate::curve::MAX_WEIGHT_RATIO)); then
    /// [`Error::DerivativeOverflow`] when, on some piece, a homogeneous
    /// hodograph (of `wP` or of `w`, of any order `1 ..= degree`, in `t` or
    /// in the piece's own parameter) or the bound
    /// `(max|A′| + max|w′|·max|P|)/min w` on the first derivative
    /// `C′ = (A′ − w′C)/w` could exceed
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE). The point and first
    /// derivative of an accepted curve are finite everywhere.
    ///
    /// ```
    /// use revolve::{Curve, Error, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 1.0), Point2::new(2.0, 0.0)];
    /// let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    /// // A heavier middle weight pulls the curve toward the middle point.
    /// let heavy = Nurbs::new(2, knots.clone(), pts.clone(), vec![1.0, 3.0, 1.0])?;
    /// assert_eq!(heavy.eval(0.5), Point2::new(1.0, 0.75)); // (3·1)/(1/4 + 3/2 + 1/4)·(1/2)
    /// let err = Nurbs::new(2, knots, pts, vec![1.0, 0.0, 1.0]).unwrap_err();
    /// assert_eq!(err, Error::InvalidWeight { index: 1, weight: 0.0 });
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point<f64, D>>,
        weights: Vec<f64>,
    ) -> Result<Self, Error> {
        validate_points(&points)?;
        validate_knots(degree, &knots, points.len())?;
        validate_weights(&weights, points.len())?;
        Self::from_checked_parts(degree, knots, points, normalized_weights(weights))
    }

    /// Builds the curve from valid parts and checks its pieces' derivatives
    /// ([`Error::DerivativeOverflow`]).
    fn from_checked_parts(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point<f64, D>>,
        weights: Vec<f64>,
    ) -> Result<Self, Error> {
        let curve = Self::from_valid_parts(degree, knots, points, weights);
        // The homogeneous derivative splines, coordinate by coordinate (the
        // operations are), as `derivatives` computes them.
        let wp: Vec<Point<f64, D>> = curve
            .homogeneous
            .iter()
            .map(|h| Point::from(h.wp))
            .collect();
        check_derivative_points(degree, &curve.knots, &wp)?;
        let w: Vec<Point1<f64>> = curve.homogeneous.iter().map(|h| Point1::new(h.w)).collect();
        check_derivative_points(degree, &curve.knots, &w)?;
        curve.pieces.check_each(check_piece)?;
        Ok(curve)
    }

    /// Builds the curve and its pieces from parts already known to be valid.
    /// A piece's homogeneous points are blossoms, convex combinations of the
    /// span's homogeneous points, kept in their bounding box (so the weights
    /// stay positive).
    fn from_valid_parts(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point<f64, D>>,
        weights: Vec<f64>,
    ) -> Self {
        let polynomial = weights.iter().all(|&w| w == weights[0]);
        let scale = weight_scale(&weights);
        let homogeneous = homogeneous_points(
            &points,
            weights
                .iter()
                .map(|&w| if polynomial { 1.0 } else { w / scale }),
        );
        let pieces = PieceTable::blossomed(
            degree,
            &knots,
            &homogeneous,
            Homogeneous::zero(),
            |span, out| {
                let hull = Homogeneous::bounds(&homogeneous[span - degree..=span]);
                out.iter_mut().for_each(|h| *h = h.clamp(hull));
                if polynomial {
                    // Equal weights stay exactly equal (and the points are
                    // the B-spline's Bézier points, computed as it does).
                    out.iter_mut().for_each(|h| h.w = 1.0);
                } else {
                    let scale = power_of_two_near(max_weight(out.iter().map(|h| h.w)));
                    out.iter_mut().for_each(|h| *h = *h / scale);
                }
            },
        );
        let bounds = point_bounds(&points);
        Nurbs {
            degree,
            knots,
            points,
            weights,
            homogeneous,
            pieces,
            bounds,
            polynomial,
        }
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector (`points + degree + 1` non-decreasing values).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points.
    pub fn points(&self) -> &[Point<f64, D>] {
        &self.points
    }

    /// The weights, as given (one per control point); weights that all lie
    /// below `2⁻⁵⁰⁰` or above `2⁵⁰⁰` are scaled by one power of two at
    /// construction (exactly, the curve unchanged) so that the largest is in
    /// `[1, 2)`.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The axis-aligned bounding box of the control points, `(min, max)`.
    /// With positive weights it contains the curve (convex hull property,
    /// Piegl & Tiller P4.9).
    pub fn bounds(&self) -> (Point<f64, D>, Point<f64, D>) {
        self.bounds
    }

    /// The same curve traced backward on the same domain `[a, b]`:
    /// `C_rev(t) = C(a + b − t)`, so `C_rev⁽ᵏ⁾(t) = (−1)ᵏ C⁽ᵏ⁾(a + b − t)`.
    /// The control points and weights are reversed and the knots mirrored,
    /// `tᵢ ↦ a + b − t_{n+p−i}`, with the edge rules of
    /// [`BSpline::reversed`] (ends exact, knots that rounding brings
    /// together kept apart, the limit from the left at a jump); the pieces
    /// are rebuilt. `reversed().reversed()` has the original's points and
    /// weights, and its knots to rounding.
    pub fn reversed(&self) -> Self {
        let knots = knots::reflected_knots(&self.knots, self.degree, self.points.len());
        let points = self.points.iter().rev().copied().collect();
        let weights = self.weights.iter().rev().copied().collect();
        Self::from_valid_parts(self.degree, knots, points, weights)
    }

    /// The derivatives `C, C′, …, C⁽ᵏ⁾` at `t`, `k = out.len() − 1`.
    ///
    /// The homogeneous derivatives `(A⁽ʲ⁾, w⁽ʲ⁾)` come from de Boor's
    /// algorithm on the control points of the homogeneous derivative spline
    /// of order `j` (differences of the span's `(wᵢPᵢ, wᵢ)` divided by knot
    /// spacings, Piegl & Tiller eq. 3.8, as [`BSpline::nth_derivative`]; zero
    /// above the degree), and `C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σ_{j=1}^{k} C(k, j) w⁽ʲ⁾ C⁽ᵏ⁻ʲ⁾)/w` (Piegl & Tiller
    /// eq. 4.8). Unlike a polynomial's, a rational curve's derivatives do not
    /// vanish above the degree (those of a curve with equal weights do, and
    /// are the [`BSpline`]'s). `t` is moved into the domain first (NaN to the
    /// start); at an interior knot the derivatives are those from the right,
    /// at the end of the domain those from the left. No heap allocation for
    /// `out.len() + 2·degree ≤ 100`.
    ///
    /// # Errors
    /// [`Error::DerivativeOrderTooHigh`] if `out.len() − 1` exceeds
    /// [`MAX_DERIVATIVE_ORDER`](crate::curve::MAX_DERIVATIVE_ORDER);
    /// [`Error::DerivativeOverflow`] with the first order whose value is not
    /// finite (the values are written anyway, the lower orders valid).
    ///
    /// ```
    /// use revolve::Nurbs;
    /// use revolve::nalgebra::{Point2, Vector2};
    ///
    /// // On the unit circle C″ = −C at unit speed; here the speed is 2π.
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let mut d = [Vector2::zeros(); 3];
    /// circle.derivatives(0.1, &mut d)?;
    /// let speed = d[1].norm();
    /// assert!((d[0].norm() - 1.0).abs() < 1e-15);
    /// assert!(d[0].dot(&d[1]).abs() < 1e-12);
    /// // Normal component of C″ is −speed²·C.
    /// assert!((d[2].dot(&d[0]) + speed * speed).abs() < 1e-10 * speed * speed);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn derivatives(&self, t: f64, out: &mut [SVector<f64, D>]) -> Result<(), Error> {
        let orders = out.len();
        if orders == 0 {
            return Ok(());
        }
        check_derivative_order(orders - 1)?;
        let p = self.degree;
        let t = clamp_to_domain(t, self.domain());
        let span = self.pieces.span_at(t);
        let knots = &self.knots;
        with_scratch(orders + 2 * (p + 1), Homogeneous::zero(), |s| {
            let (h, rest) = s.split_at_mut(orders);
            let (control, work) = rest.split_at_mut(p + 1);
            control.copy_from_slice(&self.homogeneous[span - p..=span]);
            for (k, hk) in h.iter_mut().enumerate() {
                if k > p {
                    *hk = Homogeneous::zero();
                    continue;
                }
                if k > 0 {
                    derivative_control_step(knots, p, span, control, k);
                }
                let q = p - k;
                work[..=q].copy_from_slice(&control[..=q]);
                *hk = de_boor(knots, q, span, &mut work[..=q], t);
            }
            if self.polynomial {
                for (o, hk) in out.iter_mut().zip(h.iter()) {
                    *o = hk.wp;
                }
            } else {
                quotient_rule(h, out);
            }
        });
        finish_derivatives(out, self.bounds)
    }

    /// The `order`-th derivative `dᵏC/dtᵏ` at `t` (order 0 is the point as a
    /// vector), as [`derivatives`](Self::derivatives) computes it.
    ///
    /// # Errors
    /// As [`derivatives`](Self::derivatives).
    ///
    /// ```
    /// use revolve::Nurbs;
    /// use revolve::nalgebra::Point2;
    ///
    /// // A rational line segment: straight, but not at constant speed, so its
    /// // derivatives above the degree do not vanish.
    /// let knots = vec![0.0, 0.0, 1.0, 1.0];
    /// let line = Nurbs::new(1, knots, vec![Point2::new(0.0, 0.0), Point2::new(2.0, 0.0)], vec![1.0, 3.0])?;
    /// // C(t) = 6t/(1 + 2t)·(1, 0), so C″(t) = −24/(1 + 2t)³·(1, 0).
    /// let second = line.nth_derivative(0.5, 2)?;
    /// assert!((second.x + 3.0).abs() < 1e-14 && second.y == 0.0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn nth_derivative(&self, t: f64, order: usize) -> Result<SVector<f64, D>, Error> {
        check_derivative_order(order)?;
        if self.polynomial && order > self.degree {
            return Ok(SVector::zeros());
        }
        one_derivative(order, |out| self.derivatives(t, out))
    }

    /// Inserts the knot `t` `times` times (Boehm's algorithm on the
    /// homogeneous points, Piegl & Tiller §5.2); the curve is unchanged, it
    /// gains `times` control points. A new point
    /// `Qⱼ = ((1 − α)wⱼ₋₁Pⱼ₋₁ + αwⱼPⱼ)/((1 − α)wⱼ₋₁ + αwⱼ)` with weight
    /// `(1 − α)wⱼ₋₁ + αwⱼ` stays in the box of the two points (and weights)
    /// it combines. A `t` within rounding (`4ε ×` the knot range) of an
    /// existing knot inserts that knot, as [`BSpline::insert_knot`].
    ///
    /// # Errors
    /// As [`BSpline::insert_knot`]: [`Error::ParameterOutOfDomain`] if `t`
    /// is NaN or outside the domain; [`Error::KnotMultiplicity`] if `t` would
    /// then occur more than `degree + 1` times; [`Error::DerivativeOverflow`]
    /// if the new pieces' rounding broke the bound of [`new`](Self::new)
    /// (only for curves at that bound).
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let refined = circle.insert_knot(0.1, 2)?;
    /// assert_eq!(refined.points().len(), 11);
    /// for k in 0..=20 {
    ///     let t = k as f64 / 20.0;
    ///     assert!((refined.eval(t) - circle.eval(t)).norm() < 1e-15);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<Nurbs<D>, Error> {
        let knots = (&self.knots[..], self.degree, self.domain());
        knots::insert_knot(self, knots, t, times, Self::insert_once)
    }

    /// One Boehm insertion of `t` (a valid knot to insert).
    fn insert_once(&self, t: f64) -> Result<Nurbs<D>, Error> {
        let p = self.degree;
        let k = self.pieces.span_at(t);
        let scale = weight_scale(&self.weights);
        let control: Vec<(Point<f64, D>, f64)> = self
            .points
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
            .collect();
        let (knots, values) = boehm_insert(
            &self.knots,
            p,
            k,
            t,
            &control,
            |(pa, wa), (pb, wb), alpha| {
                let h = lerp(
                    Homogeneous::new(&pa, wa / scale),
                    Homogeneous::new(&pb, wb / scale),
                    alpha,
                );
                let point = clamp_to_box(project(h).coords, point_bounds(&[pa, pb]));
                let weight = lerp(wa, wb, alpha).clamp(wa.min(wb), wa.max(wb));
                (Point::from(point), weight)
            },
        );
        let (points, weights) = values.into_iter().unzip();
        Self::from_checked_parts(p, knots, points, weights)
    }

    /// The rational pieces of the curve as [`RationalBezier`] curves, one per
    /// non-empty knot span of the domain, in parameter order.
    ///
    /// The homogeneous control points of the piece on `[a, b]` are the
    /// blossoms `f(a, …, a, b, …, b)` of the homogeneous B-spline
    /// `Σ (wᵢPᵢ, wᵢ)Nᵢ,ₚ` (`p − r` times `a`, `r` times `b`; Ramshaw's
    /// blossoming principle), computed at construction; a piece's points are
    /// their projections (kept in the box of the span's control points), its
    /// weights their last coordinates, scaled by a power of two so that the
    /// largest is in `[1, 2)`.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let spans = circle.to_bezier_spans();
    /// assert_eq!(spans.len(), 4);
    /// // The second quarter: from (0, 1) over the corner (−1, 1) to (−1, 0).
    /// assert_eq!(spans[1].knots, (0.25, 0.5));
    /// assert_eq!(spans[1].curve.points(), &[Point2::new(0.0, 1.0), Point2::new(-1.0, 1.0), Point2::new(-1.0, 0.0)]);
    /// assert!((spans[1].curve.eval(0.5) - circle.eval(0.375)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn to_bezier_spans(&self) -> Vec<RationalBezierSpan<D>> {
        (0..self.pieces.len())
            .map(|j| {
                let span = self.pieces.span(j);
                let hull = point_bounds(&self.points[span - self.degree..=span]);
                let c = self.pieces.coeffs(j);
                let points = c
                    .iter()
                    .map(|&h| Point::from(clamp_to_box(project(h).coords, hull)))
                    .collect();
                let weights = c.iter().map(|h| h.w).collect();
                RationalBezierSpan {
                    knots: self.pieces.interval(j),
                    curve: RationalBezier::from_valid_parts(points, weights),
                }
            })
            .collect()
    }

    /// Adaptive flattening of the whole curve (piece by piece) to
    /// `tolerance`, with the guaranteed bound; see [`Flattening`].
    ///
    /// The pieces are subdivided at parameter midpoints on their homogeneous
    /// points until each is certified: with positive weights a rational piece
    /// lies in the convex hull of its control points (Farin, *Curves and
    /// Surfaces for CAGD*, §13.2; Piegl & Tiller P4.9), and the distance to
    /// the chord is convex, so `dist(C(t), [P₀, Pₙ]) ≤ maxᵢ dist(Pᵢ, [P₀, Pₙ])`
    /// over the piece. The reported bound is that maximum plus twice the
    /// polynomial rounding allowance (see [`Flattening`]). A curve with equal
    /// weights is flattened as its [`BSpline`].
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] for a tolerance that is not finite and
    /// positive; [`Error::ToleranceTooSmall`] below `1e-10 ×` the largest
    /// control-point coordinate of the pieces, or when rounding keeps a piece
    /// from being certified.
    ///
    /// ```
    /// use revolve::Nurbs;
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let flat = circle.flatten(1e-3)?;
    /// assert!(flat.bound <= 1e-3);
    /// // Every chord midpoint is within the bound of the circle.
    /// for pair in flat.samples.windows(2) {
    ///     let mid = pair[0].point + (pair[1].point - pair[0].point) * 0.5;
    ///     assert!(1.0 - mid.coords.norm() <= flat.bound);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn flatten(&self, tolerance: f64) -> Result<Flattening<D>, Error> {
        let pieces =
            (0..self.pieces.len()).map(|j| (self.pieces.coeffs(j), self.pieces.interval(j)));
        if self.polynomial {
            flatten_controls(self, pieces, |h| h.wp, tolerance)
        } else {
            flatten_controls(self, pieces, |h| *h, tolerance)
        }
    }
}

impl<const D: usize> From<BSpline<D>> for Nurbs<D> {
    /// The same curve with unit weights: its pieces are the B-spline's
    /// Bézier pieces, bit for bit.
    fn from(spline: BSpline<D>) -> Self {
        let n = spline.points().len();
        Nurbs::from_valid_parts(
            spline.degree(),
            spline.knots().to_vec(),
            spline.points().to_vec(),
            vec![1.0; n],
        )
    }
}

impl<const D: usize> Curve<D> for Nurbs<D> {
    #[inline]
    fn domain(&self) -> (f64, f64) {
        knots::domain(&self.knots, self.degree, self.points.len())
    }

    /// Finds the piece, runs de Casteljau on its homogeneous points at
    /// `u = (t − a)/(b − a)` and divides.
    #[inline]
    fn eval(&self, t: f64) -> Point<f64, D> {
        let t = clamp_to_domain(t, self.domain());
        let h = self.pieces.eval(t).unwrap_or_else(Homogeneous::zero);
        let p = if self.polynomial { h.wp } else { h.wp / h.w };
        Point::from(clamp_to_box(p, self.bounds))
    }

    #[inline]
    fn derivative(&self, t: f64) -> SVector<f64, D> {
        self.eval_with_derivative(t).1
    }

    /// One de Casteljau pass gives `(A, w)` and `(A′, w′)` (scaled by
    /// `1/(b − a)`); then `C = A/w`, `C′ = (A′ − w′C)/w`.
    #[inline]
    fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let t = clamp_to_domain(t, self.domain());
        let (h, dh) = self
            .pieces
            .eval_with_derivative(t)
            .unwrap_or_else(|| (Homogeneous::zero(), Homogeneous::zero()));
        let (p, d) = if self.polynomial {
            (h.wp, dh.wp)
        } else {
            let (p, d) = project_with_derivative(h, dh);
            (p.coords, d)
        };
        (Point::from(clamp_to_box(p, self.bounds)), d)
    }

    /// The polynomial pieces when all weights are equal (the curve is then
    /// the [`BSpline`] of its points); `None` otherwise (see
    /// [`rational_bezier_spans`](Curve::rational_bezier_spans)).
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        self.polynomial
            .then(|| self.pieces.bezier_spans(|h: &Homogeneous<D>| h.wp))
    }

    /// The rational pieces ([`to_bezier_spans`](Nurbs::to_bezier_spans)).
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<D>>> {
        Some(self.to_bezier_spans())
    }

    /// Exact: the first non-negligible derivative of order `1 … p` (if
    /// `C′ … C⁽ᵖ⁾` vanish at `t₀`, so do those of the numerator
    /// `A − C(t₀)w`, a polynomial of degree `p` on the piece, and the curve is
    /// constant there). At an interior knot the limit is from the right, at
    /// the end of the domain from the left.
    fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
        let domain = self.domain();
        let t = clamp_to_domain(t, domain);
        let size = NaturalSize::of_points(&self.points, self.degree, self.pieces.width_at(t));
        tangent_from_derivatives(size, t >= domain.1, |k| {
            self.nth_derivative(t, k)
                .unwrap_or_else(|_| SVector::zeros())
        })
    }
}

/// Checks one rational piece `c` (homogeneous Bézier points, positive
/// weights) on a parameter interval of width `width`: the hodographs of
/// every order of `wP` and of `w` as [`check_derivatives`] does, then the
/// first derivative `C′ = (A′ − w′C)/w` through the bound
/// `(max|A′| + max|w′|·max|P|)/min w` (per coordinate; `|A′|` and `|w′|`
/// bounded by the hodograph's control points, `|C|` by the projected control
/// points, `w` by the smallest weight, all by the convex hull property).
///
/// # Errors
/// [`Error::DerivativeOverflow`] with the first order that could exceed
/// [`MAX_DERIVATIVE`].
fn check_piece<const D: usize>(c: &[Homogeneous<D>], width: f64) -> Result<(), Error> {
    with_scratch(c.len(), SVector::<f64, D>::zeros(), |v| {
        for (v, h) in v.iter_mut().zip(c) {
            *v = h.wp;
        }
        check_derivatives(v, width)
    })?;
    with_scratch(c.len(), Vector1::zeros(), |v| {
        for (v, h) in v.iter_mut().zip(c) {
            *v = Vector1::new(h.w);
        }
        check_derivatives(v, width)
    })?;
    let n = c.len() - 1;
    if n == 0 {
        return Ok(());
    }
    let (a1, w1) = c.windows(2).fold((0.0_f64, 0.0_f64), |(a, w), pair| {
        (
            a.max((pair[1].wp - pair[0].wp).amax()),
            w.max((pair[1].w - pair[0].w).abs()),
        )
    });
    let a1 = a1 * n as f64 / width;
    let w1 = w1 * n as f64 / width;
    let w_min = c.iter().fold(f64::INFINITY, |m, h| m.min(h.w));
    let p_max = c.iter().fold(0.0_f64, |m, h| m.max(h.wp.amax() / h.w));
    let bound = (a1 + w1 * p_max) / w_min;
    if bound <= MAX_DERIVATIVE {
        Ok(())
    } else {
        Err(Error::DerivativeOverflow { order: 1 })
    }
}

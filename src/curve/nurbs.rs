//! Rational B-spline curves (NURBS), and exact circles and arcs.
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

use super::bspline::{
    blossom, boehm_insert, check_derivative_points, de_boor_levels, derivative_control_step,
    knot_to_insert, validate_knots,
};
use super::flatten::{Flattening, flatten_controls};
use super::homogeneous::{project, project_with_derivative};
use super::pieces::PieceTable;
use super::{
    Homogeneous, MAX_DERIVATIVE, NaturalSize, check_derivatives, clamp_to_box, clamp_to_domain,
    elevate_spline, point_bounds, quotient_rule, tangent_from_derivatives, validate_points,
    validate_weights,
};
use crate::bernstein::{self, lerp};
use crate::scratch::with_scratch;
use crate::{BSpline, Bezier, BezierSpan, Curve, Error, RationalBezier, RationalBezierSpan};
use nalgebra::{Point, Point1, Point2, SVector, Unit, Vector1, Vector2};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, TAU};
use std::ops::Div;

/// The highest derivative order [`Nurbs::derivatives`] and
/// [`Nurbs::nth_derivative`] compute (`1024`). A rational curve's
/// derivatives do not vanish above its degree, and order `k` costs `O(k²)`
/// operations; beyond order ~170 they overflow for most curves anyway
/// (they grow like `k!`).
pub const MAX_DERIVATIVE_ORDER: usize = 1024;

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
        Self::from_checked_parts(degree, knots, points, weights)
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
        for j in 0..curve.pieces.len() {
            let (a, b) = curve.pieces.interval(j);
            let c = curve.pieces.coeffs(j);
            check_piece(c, 1.0)?;
            check_piece(c, b - a)?;
        }
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
        let homogeneous: Vec<Homogeneous<D>> = points
            .iter()
            .zip(&weights)
            .map(|(p, &w)| Homogeneous::new(p, if polynomial { 1.0 } else { w / scale }))
            .collect();
        let pieces = PieceTable::new(
            degree,
            &knots,
            points.len(),
            Homogeneous::zero(),
            |span, out| {
                let (a, b) = (knots[span], knots[span + 1]);
                let control = &homogeneous[span - degree..=span];
                let hull = homogeneous_bounds(control);
                for (r, dst) in out.iter_mut().enumerate() {
                    let value = blossom(&knots, control, degree, span, degree - r, a, b);
                    *dst = clamp_homogeneous(value, hull);
                }
                if polynomial {
                    // Equal weights stay exactly equal (and the points are
                    // the B-spline's Bézier points, computed as it does).
                    out.iter_mut().for_each(|h| h.w = 1.0);
                } else {
                    let scale = power_of_two_near(out.iter().fold(0.0_f64, |m, h| m.max(h.w)));
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

    /// The weights, as given (one per control point).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The axis-aligned bounding box of the control points, `(min, max)`.
    /// With positive weights it contains the curve (convex hull property,
    /// Piegl & Tiller P4.9).
    pub fn bounds(&self) -> (Point<f64, D>, Point<f64, D>) {
        self.bounds
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
    /// [`MAX_DERIVATIVE_ORDER`]; [`Error::DerivativeOverflow`] with the first
    /// order whose value is not finite (the values are written anyway, the
    /// lower orders valid).
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
        if orders - 1 > MAX_DERIVATIVE_ORDER {
            return Err(Error::DerivativeOrderTooHigh {
                order: orders - 1,
                max: MAX_DERIVATIVE_ORDER,
            });
        }
        let p = self.degree;
        let t = clamp_to_domain(t, self.domain());
        let span = self.pieces.span(self.pieces.locate(t));
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
                de_boor_levels(knots, q, span, &mut work[..=q], t, q);
                *hk = work[q];
            }
            if self.polynomial {
                for (o, hk) in out.iter_mut().zip(h.iter()) {
                    *o = hk.wp;
                }
            } else {
                quotient_rule(h, out);
            }
        });
        out[0] = clamp_to_box(out[0], self.bounds);
        match out.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            Some(order) => Err(Error::DerivativeOverflow { order }),
            None => Ok(()),
        }
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
        if order > MAX_DERIVATIVE_ORDER {
            return Err(Error::DerivativeOrderTooHigh {
                order,
                max: MAX_DERIVATIVE_ORDER,
            });
        }
        if self.polynomial && order > self.degree {
            return Ok(SVector::zeros());
        }
        with_scratch(order + 1, SVector::zeros(), |out| {
            self.derivatives(t, out)?;
            Ok(out[order])
        })
    }

    /// The same curve with its degree raised by `times`: the B-spline
    /// elevation of [`BSpline::elevate_degree`] run on the homogeneous points
    /// `(wᵢPᵢ, wᵢ)`, then divided back into points and weights. Every
    /// interior knot's multiplicity grows by `times`; the ends are clamped
    /// (full multiplicity), so every new homogeneous point is a convex
    /// combination of the old ones and the weights stay positive.
    ///
    /// # Errors
    /// [`Error::ElevationTooHigh`] beyond
    /// [`MAX_ELEVATED_DEGREE`](crate::curve::MAX_ELEVATED_DEGREE); the
    /// errors of [`new`](Self::new) should rounding break its bounds.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 2.0)?;
    /// let cubic = circle.elevate_degree(1)?;
    /// assert_eq!(cubic.degree(), 3);
    /// for k in 0..=40 {
    ///     let t = k as f64 / 40.0;
    ///     assert!((cubic.eval(t).coords.norm() - 2.0).abs() < 1e-14);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn elevate_degree(&self, times: usize) -> Result<Nurbs<D>, Error> {
        let scale = weight_scale(&self.weights);
        let homogeneous: Vec<Homogeneous<D>> = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(p, &w)| Homogeneous::new(p, w / scale))
            .collect();
        let (knots, raised) = elevate_spline(self.degree, &self.knots, &homogeneous, times)?;
        let bounds = point_bounds(&self.points);
        let (points, weights) = raised
            .iter()
            .map(|h| {
                let p = Point::from(clamp_to_box(h.wp / h.w, bounds));
                (p, h.w * scale)
            })
            .unzip();
        Nurbs::new(self.degree + times, knots, points, weights)
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
        let t = knot_to_insert(&self.knots, self.degree, self.domain(), t, times)?;
        let mut curve = self.clone();
        for _ in 0..times {
            curve = curve.insert_once(t)?;
        }
        Ok(curve)
    }

    /// One Boehm insertion of `t` (a valid knot to insert).
    fn insert_once(&self, t: f64) -> Result<Nurbs<D>, Error> {
        let p = self.degree;
        let k = self.pieces.span(self.pieces.locate(t));
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

impl Nurbs<2> {
    /// The whole circle of the given center and radius, exactly: degree 2,
    /// nine control points (the corners and edge midpoints of the square
    /// about it, starting at angle 0 and running counter-clockwise), weights
    /// `1, √2/2, 1, √2/2, …` and knots `[0, 0, 0, ¼, ¼, ½, ½, ¾, ¾, 1, 1, 1]`:
    /// four rational quarter arcs (Piegl & Tiller §7.5). The parametrization
    /// is not by arc length; `C(0) = C(1) = center + (radius, 0)`,
    /// `C(¼) = center + (0, radius)`.
    ///
    /// # Errors
    /// [`Error::InvalidCenter`] for a center with a NaN, infinite or too
    /// large coordinate; [`Error::InvalidRadius`] for a radius that is not
    /// finite and positive or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE);
    /// [`Error::CoordinateTooLarge`] if a control point (up to `radius` from
    /// the center in each coordinate) lies beyond it.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let c = Nurbs::circle(Point2::new(0.0, 0.0), 3.0)?;
    /// assert_eq!(c.eval(0.25), Point2::new(0.0, 3.0));
    /// assert!((c.eval(0.6).coords.norm() - 3.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn circle(center: Point2<f64>, radius: f64) -> Result<Nurbs<2>, Error> {
        check_circle(center, radius)?;
        let r = radius;
        let offsets = [
            (r, 0.0),
            (r, r),
            (0.0, r),
            (-r, r),
            (-r, 0.0),
            (-r, -r),
            (0.0, -r),
            (r, -r),
            (r, 0.0),
        ];
        let points = offsets
            .iter()
            .map(|&(x, y)| center + Vector2::new(x, y))
            .collect();
        let weights = (0..9)
            .map(|i| if i % 2 == 0 { 1.0 } else { FRAC_1_SQRT_2 })
            .collect();
        Self::conic_pieces(points, weights)
    }

    /// The arc of the circle of the given center and radius from angle
    /// `start` to angle `end` (radians, counter-clockwise), on the domain
    /// `[0, 1]`.
    ///
    /// The sweep `end − start` must lie in `(0, 2π]`; a sweep of `2π` is the
    /// full circle starting (and ending, exactly) at `start`, and a sweep
    /// within the rounding of the angles (`2ε·max(|start|, |end|)`) of `2π`,
    /// below or above, counts as `2π` (so `arc(c, r, a, a + TAU)` is a full
    /// turn for any `a`). The arc is split into `m = ⌈sweep/(π/2)⌉` equal pieces,
    /// each a rational quadratic Bézier (Piegl & Tiller §7.5) with end points
    /// `center + radius·uᵢ` on the circle (`uᵢ = (cos θᵢ, sin θᵢ)`), middle
    /// point on the bisector at distance `radius/cos(φ/2)` from the center and
    /// middle weight `cos(φ/2)`, `φ` the piece's angle; these are computed from
    /// the two end directions as they are rounded
    /// (`center + 2·radius·(uᵢ + uᵢ₊₁)/|uᵢ + uᵢ₊₁|²`, weight `|uᵢ + uᵢ₊₁|/2`),
    /// so each piece is exactly the circular arc between its rounded end
    /// points. The interior knots `i/m` are double; the arc starts at angle
    /// `start` at `t = 0` and ends at angle `end` at `t = 1`. An angle
    /// within rounding (`4ε·max(|angle|, 1)`) of a multiple of `π/2` gives
    /// the exact axis direction, so `arc(c, r, −π/2, π/2)` (a sphere's
    /// profile) ends exactly on the axis, not `6e-17·r` off it.
    ///
    /// # Errors
    /// As [`circle`](Self::circle) for the center and radius;
    /// [`Error::InvalidSweep`] for a sweep that is not in `(0, 2π]` or an
    /// angle that is NaN or infinite.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    /// use std::f64::consts::PI;
    ///
    /// // The upper half of the unit circle, from angle 0 to π: two quarter pieces.
    /// let half = Nurbs::arc(Point2::origin(), 1.0, 0.0, PI)?;
    /// assert_eq!(half.degree(), 2);
    /// assert_eq!(half.points().len(), 5);
    /// let p = half.eval(0.3);
    /// assert!((p.coords.norm() - 1.0).abs() < 1e-15 && p.y > 0.0);
    /// assert!(Nurbs::arc(Point2::origin(), 1.0, 1.0, 0.5).is_err());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn arc(center: Point2<f64>, radius: f64, start: f64, end: f64) -> Result<Nurbs<2>, Error> {
        check_circle(center, radius)?;
        let sweep = end - start;
        let slack = 2.0 * f64::EPSILON * start.abs().max(end.abs());
        if !(start.is_finite() && end.is_finite() && sweep > 0.0 && sweep <= TAU + slack) {
            return Err(Error::InvalidSweep { start, end });
        }
        let full = sweep >= TAU - slack;
        let sweep = if full { TAU } else { sweep };
        let m = ((sweep / FRAC_PI_2).ceil() as usize).clamp(1, 4);
        let step = sweep / m as f64;
        let direction = axis_snapped_direction;
        let first = direction(start);
        let last = if full { first } else { direction(end) };
        let mut points = Vec::with_capacity(2 * m + 1);
        let mut weights = Vec::with_capacity(2 * m + 1);
        let mut u0 = first;
        for i in 0..m {
            let u1 = if i + 1 == m {
                last
            } else {
                direction(start + step * (i + 1) as f64)
            };
            let s = u0 + u1;
            let s2 = s.norm_squared();
            points.push(center + u0 * radius);
            weights.push(1.0);
            points.push(center + s * (2.0 * radius / s2));
            weights.push(0.5 * s2.sqrt());
            u0 = u1;
        }
        points.push(center + last * radius);
        weights.push(1.0);
        Self::conic_pieces(points, weights)
    }

    /// The degree-2 NURBS of `m = (points − 1)/2` rational quadratic pieces
    /// on `[0, 1]`, with double interior knots `i/m`.
    fn conic_pieces(points: Vec<Point2<f64>>, weights: Vec<f64>) -> Result<Nurbs<2>, Error> {
        let m = (points.len() - 1) / 2;
        let mut knots = vec![0.0; 3];
        for i in 1..m {
            let k = i as f64 / m as f64;
            knots.extend([k, k]);
        }
        knots.extend([1.0; 3]);
        Nurbs::new(2, knots, points, weights)
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
        (self.knots[self.degree], self.knots[self.points.len()])
    }

    /// Finds the piece, runs de Casteljau on its homogeneous points at
    /// `u = (t − a)/(b − a)` and divides.
    #[inline]
    fn eval(&self, t: f64) -> Point<f64, D> {
        let t = clamp_to_domain(t, self.domain());
        let j = self.pieces.locate(t);
        let (a, b) = self.pieces.interval(j);
        let h = bernstein::eval(self.pieces.coeffs(j), (t - a) / (b - a))
            .unwrap_or_else(Homogeneous::zero);
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
        let j = self.pieces.locate(t);
        let (a, b) = self.pieces.interval(j);
        let width = b - a;
        let (h, dh) = bernstein::eval_with_derivative(self.pieces.coeffs(j), (t - a) / width)
            .unwrap_or_else(|| (Homogeneous::zero(), Homogeneous::zero()));
        let (p, d) = if self.polynomial {
            (h.wp, dh.wp / width)
        } else {
            let (p, d) = project_with_derivative(h, dh / width);
            (p.coords, d)
        };
        (Point::from(clamp_to_box(p, self.bounds)), d)
    }

    /// The polynomial pieces when all weights are equal (the curve is then
    /// the [`BSpline`] of its points); `None` otherwise (see
    /// [`rational_bezier_spans`](Curve::rational_bezier_spans)).
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        self.polynomial.then(|| {
            (0..self.pieces.len())
                .map(|j| BezierSpan {
                    knots: self.pieces.interval(j),
                    curve: Bezier::from_valid_points(
                        self.pieces
                            .coeffs(j)
                            .iter()
                            .map(|h| Point::from(h.wp))
                            .collect(),
                    ),
                })
                .collect()
        })
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
        let j = self.pieces.locate(t);
        let (a, b) = self.pieces.interval(j);
        let scale = self
            .points
            .iter()
            .fold(0.0_f64, |m, c| m.max(c.coords.amax()));
        let size = NaturalSize {
            scale,
            degree: self.degree,
            width: b - a,
        };
        tangent_from_derivatives(size, t >= domain.1, |k| {
            self.nth_derivative(t, k)
                .unwrap_or_else(|_| SVector::zeros())
        })
    }
}

impl<const D: usize> Div<f64> for Homogeneous<D> {
    type Output = Self;
    /// Both coordinates divided by `s` (division, not multiplication by
    /// `1/s`, which could overflow for tiny `s`).
    #[inline(always)]
    fn div(self, s: f64) -> Self {
        Homogeneous {
            wp: self.wp / s,
            w: self.w / s,
        }
    }
}

/// The power of two by which the weights are divided: the largest weight
/// becomes a number in `[1, 2)`, the others are scaled exactly.
pub(crate) fn weight_scale(weights: &[f64]) -> f64 {
    power_of_two_near(weights.iter().fold(0.0_f64, |m, &w| m.max(w)))
}

/// `2^⌊log₂ x⌋` for a positive finite `x` (subnormal ones too): a power of
/// two within a factor 2 of `x`, by which division is exact. Rounding of the
/// logarithm can only make it `x`'s neighbouring power, still within a
/// factor 2.
fn power_of_two_near(x: f64) -> f64 {
    let e = (x.log2().floor() as i32).clamp(-1074, 1023);
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1_u64 << (e + 1074))
    }
}

/// The box of homogeneous points: `(min, max)` of `wP` per coordinate and of `w`.
fn homogeneous_bounds<const D: usize>(h: &[Homogeneous<D>]) -> (Homogeneous<D>, Homogeneous<D>) {
    h.iter().fold((h[0], h[0]), |(lo, hi), x| {
        (
            Homogeneous {
                wp: lo.wp.inf(&x.wp),
                w: lo.w.min(x.w),
            },
            Homogeneous {
                wp: hi.wp.sup(&x.wp),
                w: hi.w.max(x.w),
            },
        )
    })
}

/// `h` moved into the box `(lo, hi)`: for a convex combination of the points
/// whose box it is, this only removes rounding.
#[inline]
fn clamp_homogeneous<const D: usize>(
    h: Homogeneous<D>,
    (lo, hi): (Homogeneous<D>, Homogeneous<D>),
) -> Homogeneous<D> {
    Homogeneous {
        wp: h.wp.sup(&lo.wp).inf(&hi.wp),
        w: h.w.clamp(lo.w, hi.w),
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

/// Checks a circle's center and radius.
fn check_circle(center: Point2<f64>, radius: f64) -> Result<(), Error> {
    if !center
        .iter()
        .all(|c| c.is_finite() && c.abs() <= crate::MAX_COORDINATE)
    {
        return Err(Error::InvalidCenter { center });
    }
    if !(radius.is_finite() && radius > 0.0 && radius <= crate::MAX_COORDINATE) {
        return Err(Error::InvalidRadius { radius });
    }
    Ok(())
}

/// `(cos θ, sin θ)`, exactly `(±1, 0)` or `(0, ±1)` when `θ` is within
/// rounding (`4ε·max(|θ|, 1)`) of a multiple of `π/2` (where `cos` and `sin`
/// of the rounded angle give `6e-17` instead of 0).
fn axis_snapped_direction(angle: f64) -> Vector2<f64> {
    let quarters = (angle / FRAC_PI_2).round();
    let near = (angle - quarters * FRAC_PI_2).abs() <= 4.0 * f64::EPSILON * angle.abs().max(1.0);
    if near && quarters.abs() < 1e15 {
        match (quarters as i64).rem_euclid(4) {
            0 => Vector2::new(1.0, 0.0),
            1 => Vector2::new(0.0, 1.0),
            2 => Vector2::new(-1.0, 0.0),
            _ => Vector2::new(0.0, -1.0),
        }
    } else {
        Vector2::new(angle.cos(), angle.sin())
    }
}

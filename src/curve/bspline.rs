//! B-spline curves: evaluation on the precomputed Bézier pieces and by de
//! Boor's algorithm, the Cox–de Boor basis, derivative splines, knot
//! insertion and Bézier spans (the knot-vector kernels are in `knots`,
//! shared with the rational B-spline).
//!
//! Notation (Piegl & Tiller, *The NURBS Book*, ch. 2–5): degree `p`, control
//! points `P₀ … P_{n−1}` (`n` of them), knots `t₀ ≤ … ≤ t_{n+p}` (`n + p + 1` of
//! them). The curve `C(t) = Σᵢ Nᵢ,ₚ(t) Pᵢ` is defined on the domain
//! `[t_p, t_n]`, where the basis functions sum to one.

use super::flatten::{Flattening, flatten_pieces};
use super::knots::{
    self, boehm_insert, check_degree, check_derivative_points, de_boor, derivative_control,
    derivative_control_step, derivative_gap, validate_knots,
};
use super::pieces::PieceTable;
use super::{
    NaturalSize, check_derivatives, clamp_to_box, clamp_to_domain, point_bounds,
    tangent_from_derivatives, validate_points,
};
use crate::bernstein::lerp;
use crate::scratch::with_scratch;
use crate::{BezierSpan, Curve, Error};
use nalgebra::{Point, SVector, Unit};

/// A B-spline curve of any degree in `D` dimensions.
///
/// Evaluation finds the knot span by binary search and runs de Boor's
/// algorithm on the `p + 1` control points of that span, on stack scratch
/// space (no heap allocation up to degree 16).
///
/// # Edge rules
/// - Spans are half-open, `[tᵢ, tᵢ₊₁)`, so at an interior knot of full
///   multiplicity (`p + 1`, where the curve may jump) the value is the limit
///   from the right. The end of the domain `t_n` belongs to the last non-empty
///   span, so it evaluates the end point, not zero.
/// - Parameters outside the domain evaluate at the nearest end of the domain
///   (no extrapolation); NaN evaluates at the start. Evaluation never returns
///   NaN.
///
/// ```
/// use revolve::{BSpline, Curve};
/// use revolve::nalgebra::Point2;
///
/// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0)];
/// // The course framework's convention: knots i/(n + k), drawn over [t_k, t_n].
/// let uniform = BSpline::uniform(3, pts.clone())?;
/// assert_eq!(uniform.domain(), (3.0 / 7.0, 4.0 / 7.0));
/// // A clamped cubic on four points is the Bézier curve of those points.
/// let clamped = BSpline::clamped(3, pts)?;
/// assert_eq!(clamped.eval(1.0), Point2::new(4.0, 0.0));
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline<const D: usize> {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Point<f64, D>>,
    /// The Bézier form of every non-empty span, computed at construction.
    pieces: PieceTable<SVector<f64, D>>,
}

impl<const D: usize> BSpline<D> {
    /// A B-spline of the given degree, knot vector and control points.
    ///
    /// # Errors
    /// In the order checked: [`Error::NoControlPoints`],
    /// [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`] (beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE)), [`Error::DegreeTooHigh`]
    /// (fewer than `degree + 1` points), [`Error::KnotCount`] (not
    /// `points + degree + 1` knots), [`Error::NonFiniteKnot`] or
    /// [`Error::KnotTooLarge`], [`Error::DecreasingKnots`],
    /// [`Error::KnotGapTooSmall`] (distinct knots closer than `4ε ×` the knot
    /// range, which rounding cannot tell apart), [`Error::KnotMultiplicity`]
    /// (a knot repeated more than `degree + 1` times), [`Error::EmptyDomain`] (`t_p = t_n`),
    /// [`Error::DerivativeOverflow`] (knots too close for the points: a
    /// control point of the derivative spline of some order `1 ..= degree`, or
    /// of a Bézier piece's hodograph in `t` or in its own parameter, beyond
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE)). Derivatives of every
    /// order of an accepted curve are finite everywhere.
    pub fn new(degree: usize, knots: Vec<f64>, points: Vec<Point<f64, D>>) -> Result<Self, Error> {
        validate_points(&points)?;
        validate_knots(degree, &knots, points.len())?;
        Self::from_checked_parts(degree, knots, points)
    }

    /// Builds the curve from valid parts and checks its derivatives
    /// ([`Error::DerivativeOverflow`]).
    fn from_checked_parts(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point<f64, D>>,
    ) -> Result<Self, Error> {
        check_derivative_points(degree, &knots, &points)?;
        let curve = Self::from_valid_parts(degree, knots, points);
        curve.pieces.check_each(check_derivatives)?;
        Ok(curve)
    }

    /// Builds the curve and its piece table from parts already known to be
    /// valid (checked by [`new`](Self::new), or derived from a valid curve).
    /// The pieces' control points are blossoms, convex combinations of the
    /// span's control points, kept in their bounding box.
    fn from_valid_parts(degree: usize, knots: Vec<f64>, points: Vec<Point<f64, D>>) -> Self {
        let coords: Vec<SVector<f64, D>> = points.iter().map(|p| p.coords).collect();
        let pieces =
            PieceTable::blossomed(degree, &knots, &coords, SVector::zeros(), |span, out| {
                let hull = point_bounds(&points[span - degree..=span]);
                out.iter_mut().for_each(|v| *v = clamp_to_box(*v, hull));
            });
        Self {
            degree,
            knots,
            points,
            pieces,
        }
    }

    /// The course framework's uniform B-spline: knots `tᵢ = i/(n + k)`,
    /// `i = 0 … n + k`, for `n` points and degree `k`; domain `[t_k, t_n]`.
    ///
    /// # Errors
    /// As [`new`](Self::new); in particular [`Error::DegreeTooHigh`] when
    /// `degree ≥ points.len()`.
    pub fn uniform(degree: usize, points: Vec<Point<f64, D>>) -> Result<Self, Error> {
        validate_points(&points)?;
        check_degree(degree, points.len())?;
        let knots = knots::uniform_knots(degree, points.len());
        Self::new(degree, knots, points)
    }

    /// The clamped (open uniform) B-spline: `degree + 1` knots at 0 and at 1
    /// and uniform interior knots, so the curve starts at the first control
    /// point and ends at the last; domain `[0, 1]`.
    ///
    /// # Errors
    /// As [`new`](Self::new); in particular [`Error::DegreeTooHigh`] when
    /// `degree ≥ points.len()`.
    pub fn clamped(degree: usize, points: Vec<Point<f64, D>>) -> Result<Self, Error> {
        validate_points(&points)?;
        check_degree(degree, points.len())?;
        let knots = knots::clamped_knots(degree, points.len());
        Self::new(degree, knots, points)
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

    /// The axis-aligned bounding box of the control points, `(min, max)`,
    /// which contains the curve (convex hull property).
    pub fn bounds(&self) -> (Point<f64, D>, Point<f64, D>) {
        point_bounds(&self.points)
    }

    /// The same curve traced backward on the same domain `[a, b]`:
    /// `C_rev(t) = C(a + b − t)`, so `C_rev⁽ᵏ⁾(t) = (−1)ᵏ C⁽ᵏ⁾(a + b − t)`.
    /// The control points are reversed and the knots mirrored,
    /// `tᵢ ↦ a + b − t_{n+p−i}`; the Bézier pieces are rebuilt from them.
    ///
    /// # Edge rules
    /// - The domain's ends are exactly `a` and `b` again.
    /// - Mirrored knots are rounded: where that brings two distinct knots
    ///   together (or closer than the gap rule of [`new`](Self::new)), the
    ///   one that is not a domain end is moved apart by that gap (a few
    ///   ulps), so multiplicities are kept and the result is always valid;
    ///   the curve moves by that much times its speed. An outer knot whose
    ///   mirror image would exceed [`MAX_COORDINATE`](crate::MAX_COORDINATE)
    ///   is clamped to it.
    /// - Spans stay half-open `[tᵢ, tᵢ₊₁)`, so at a knot of full
    ///   multiplicity (a jump) the reversed curve takes the original's limit
    ///   from the left.
    /// - `reversed().reversed()` has the original's control points and
    ///   degree, and its knots to rounding.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0), Point2::new(5.0, 1.0)];
    /// let curve = BSpline::uniform(3, pts)?;
    /// let back = curve.reversed();
    /// let (a, b) = curve.domain();
    /// assert_eq!(back.domain(), (a, b));
    /// assert_eq!(back.eval(a), curve.eval(b));
    /// let t = a + 0.3 * (b - a);
    /// assert!((back.eval(t) - curve.eval(a + b - t)).norm() < 1e-14);
    /// assert!((back.derivative(t) + curve.derivative(a + b - t)).norm() < 1e-12);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn reversed(&self) -> Self {
        let knots = knots::reflected_knots(&self.knots, self.degree, self.points.len());
        let points = self.points.iter().rev().copied().collect();
        Self::from_valid_parts(self.degree, knots, points)
    }

    /// The index `i` of the knot span `[tᵢ, tᵢ₊₁)` containing `t`, with
    /// `p ≤ i < n` and `tᵢ < tᵢ₊₁`. `t` is first moved into the domain; the
    /// domain end belongs to the last non-empty span. The search runs over
    /// the distinct break points: binary search, or constant time when they
    /// are equally spaced (uniform and clamped knots).
    pub fn span(&self, t: f64) -> usize {
        let t = clamp_to_domain(t, self.domain());
        self.span_of_clamped(t)
    }

    #[inline]
    fn span_of_clamped(&self, t: f64) -> usize {
        self.pieces.span_at(t)
    }

    /// The point `C(t)` by de Boor's algorithm on the control points (the
    /// reference for [`Curve::eval`], which evaluates the precomputed Bézier
    /// form of the span; the two agree to rounding).
    pub fn eval_de_boor(&self, t: f64) -> Point<f64, D> {
        Point::from(self.derivative_of_order(t, 0))
    }

    /// The `order`-th derivative `dᵏC/dtᵏ` at `t` (order 0 is the point as a
    /// vector); zero for orders above the degree.
    ///
    /// Differences the span's control points `order` times with the knot
    /// spacing (the control points of the derivative spline, Piegl & Tiller
    /// eq. 3.8) and runs de Boor at degree `p − order`. No heap allocation up
    /// to degree 16. Never an `Err` (the `Result` is the shape every curve's
    /// `nth_derivative` has).
    pub fn nth_derivative(&self, t: f64, order: usize) -> Result<SVector<f64, D>, Error> {
        Ok(self.derivative_of_order(t, order))
    }

    /// [`nth_derivative`](Self::nth_derivative)'s value.
    fn derivative_of_order(&self, t: f64, order: usize) -> SVector<f64, D> {
        let p = self.degree;
        if order > p {
            return SVector::zeros();
        }
        let t = clamp_to_domain(t, self.domain());
        let span = self.span_of_clamped(t);
        let knots = &self.knots;
        with_scratch(p + 1, SVector::zeros(), |s| {
            self.load_span(span, s);
            for r in 1..=order {
                derivative_control_step(knots, p, span, s, r);
            }
            let q = p - order;
            de_boor(knots, q, span, &mut s[..=q], t)
        })
    }

    /// Copies the `p + 1` control points that act on `span` into `s`.
    #[inline(always)]
    fn load_span(&self, span: usize, s: &mut [SVector<f64, D>]) {
        let first = span - self.degree;
        for (dst, p) in s.iter_mut().zip(&self.points[first..=span]) {
            *dst = p.coords;
        }
    }

    /// Writes the values `N_{i−p+r, p}(t)`, `r = 0 … p`, of the `p + 1` basis
    /// functions that can be nonzero at `t` into `out[..=p]` and returns the
    /// index `i − p` of the first. All other basis functions are zero at `t`.
    ///
    /// Cox–de Boor recurrence in its triangular, division-safe form (Piegl &
    /// Tiller, A2.2); no allocation up to degree 16. `t` is moved into the
    /// domain first.
    ///
    /// # Errors
    /// [`Error::BufferLength`] if `out` has fewer than `p + 1` entries.
    pub fn basis_functions(&self, t: f64, out: &mut [f64]) -> Result<usize, Error> {
        let p = self.degree;
        check_buffer(out.len(), p + 1)?;
        let t = clamp_to_domain(t, self.domain());
        let span = self.span_of_clamped(t);
        with_scratch(2 * (p + 1), 0.0, |lr| {
            let (left, right) = lr.split_at_mut(p + 1);
            basis_up_to(&self.knots, span, t, p, &mut out[..=p], left, right);
        });
        Ok(span - p)
    }

    /// Derivatives of the basis functions: writes `dᵏ/dtᵏ N_{i−p+r, p}(t)` to
    /// `out[k·(p + 1) + r]` for `k = 0 … order`, `r = 0 … p`, and returns the
    /// index `i − p` of the first function. Orders above `p` are zero.
    ///
    /// Uses `N⁽ᵏ⁾_{j,p} = p!/(p−k)! Σₘ a_{k,m} N_{j+m, p−k}` with the recursively
    /// defined coefficients `a_{k,m}` of Piegl & Tiller eq. 2.10 (a zero knot
    /// difference contributes zero). No allocation up to degree 16.
    ///
    /// # Errors
    /// [`Error::BufferLength`] if `out` has fewer than `(order + 1)(p + 1)`
    /// entries.
    pub fn basis_derivatives(&self, t: f64, order: usize, out: &mut [f64]) -> Result<usize, Error> {
        let p = self.degree;
        let width = p + 1;
        let needed = (order.saturating_add(1)).saturating_mul(width);
        check_buffer(out.len(), needed)?;
        let t = clamp_to_domain(t, self.domain());
        let span = self.span_of_clamped(t);
        let knots = &self.knots;
        out[..needed].fill(0.0);
        // Scratch: lower-degree basis row, left/right differences, two rows of a.
        with_scratch(5 * width, 0.0, |buf| {
            let (lower, rest) = buf.split_at_mut(width);
            let (left, rest) = rest.split_at_mut(width);
            let (right, rest) = rest.split_at_mut(width);
            let (a_prev, a_next) = rest.split_at_mut(width);
            for k in 0..=order.min(p) {
                let q = p - k;
                basis_up_to(knots, span, t, q, &mut lower[..=q], left, right);
                let falling: f64 = (q + 1..=p).map(|x| x as f64).product();
                for r in 0..=p {
                    let j = span - p + r; // global index of the basis function
                    // a_{k,·} for N_{j,p}, built from a_{0,0} = 1.
                    a_prev[0] = 1.0;
                    for kk in 1..=k {
                        let qq = p - kk;
                        for m in 0..=kk {
                            let prev_m = if m < kk { a_prev[m] } else { 0.0 };
                            let prev_m1 = if m > 0 { a_prev[m - 1] } else { 0.0 };
                            let den = knots[j + qq + m + 1] - knots[j + m];
                            a_next[m] = safe_div(prev_m - prev_m1, den);
                        }
                        a_prev[..=kk].copy_from_slice(&a_next[..=kk]);
                    }
                    let mut sum = 0.0;
                    for (m, &a) in a_prev.iter().enumerate().take(k + 1) {
                        // N_{j+m, q} is stored at lower[(j + m) − (span − q)] when in range.
                        let idx = (j + m + q).checked_sub(span);
                        if let Some(idx) = idx.filter(|&i| i <= q) {
                            sum += a * lower[idx];
                        }
                    }
                    out[k * width + r] = falling * sum;
                }
            }
        });
        Ok(span - p)
    }

    /// The derivative curve `C′(t)` as a B-spline of degree `p − 1` on the
    /// knots `t₁ … t_{n+p−1}` with control points
    /// `Qᵢ = p·(Pᵢ₊₁ − Pᵢ)/(tᵢ₊ₚ₊₁ − tᵢ₊₁)` (Piegl & Tiller eq. 3.8). Same
    /// domain. Where an interior knot has full multiplicity `p + 1` (a jump),
    /// the basis function of `Qᵢ` vanishes identically (`tᵢ₊ₚ₊₁ = tᵢ₊₁`): that
    /// `Qᵢ` and one copy of the knot are dropped, so the result again satisfies
    /// the multiplicity rule of [`new`](Self::new). For degree 0 the
    /// derivative is the zero spline on the same knots. Its points may exceed
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE) (up to
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE)); its pieces are the
    /// hodographs of this curve's, so its derivatives are this curve's higher
    /// ones, finite.
    pub fn derivative_spline(&self) -> BSpline<D> {
        let p = self.degree;
        if p == 0 {
            let zeros = vec![Point::origin(); self.points.len()];
            return BSpline::from_valid_parts(0, self.knots.clone(), zeros);
        }
        let n = self.points.len();
        let inner = &self.knots[1..self.knots.len() - 1];
        let mut knots = Vec::with_capacity(inner.len());
        let mut points = Vec::with_capacity(n - 1);
        for (i, pair) in self.points.windows(2).enumerate() {
            // The basis function of Qᵢ lives on inner[i ..= i + p].
            let gap = derivative_gap(&self.knots, p, i, 1);
            if gap > 0.0 {
                let q = derivative_control(pair[0].coords, pair[1].coords, gap, p, 1);
                points.push(Point::from(q));
                knots.push(inner[i]);
            }
        }
        knots.extend_from_slice(&inner[n - 1..]);
        // The pieces are the hodographs of this curve's pieces, computed as
        // `new` checked them, so derivatives of the result stay finite.
        let mut piece = 0;
        let pieces = PieceTable::new(p - 1, &knots, points.len(), SVector::zeros(), |_, out| {
            let (a, b) = self.pieces.interval(piece);
            let c = self.pieces.coeffs(piece);
            for (j, dst) in out.iter_mut().enumerate() {
                *dst = ((c[j + 1] - c[j]) * p as f64) / (b - a);
            }
            piece = (piece + 1).min(self.pieces.len() - 1);
        });
        BSpline {
            degree: p - 1,
            knots,
            points,
            pieces,
        }
    }

    /// The `order`-th derivative spline (order 0 is a copy of the curve;
    /// orders above the degree give the zero spline of degree 0).
    pub fn nth_derivative_spline(&self, order: usize) -> BSpline<D> {
        (0..order.min(self.degree + 1)).fold(self.clone(), |c, _| c.derivative_spline())
    }

    /// Inserts the knot `t` `times` times (Boehm's algorithm); the curve is
    /// unchanged, it gains `times` control points. A `t` within rounding
    /// (`4ε ×` the knot range) of an existing knot inserts that knot, so the
    /// result always satisfies the rules of [`new`](Self::new).
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside the domain;
    /// [`Error::KnotMultiplicity`] if `t` would then occur more than
    /// `degree + 1` times; [`Error::DerivativeOverflow`] if the new pieces'
    /// rounding broke the bound of [`new`](Self::new) (only for curves at
    /// that bound).
    pub fn insert_knot(&self, t: f64, times: usize) -> Result<BSpline<D>, Error> {
        let knots = (&self.knots[..], self.degree, self.domain());
        knots::insert_knot(self, knots, t, times, Self::insert_once)
    }

    /// One Boehm insertion ([`boehm_insert`]); the new points stay in the
    /// box of the two they combine.
    fn insert_once(&self, t: f64) -> Result<BSpline<D>, Error> {
        let p = self.degree;
        let k = self.span_of_clamped(t);
        let (knots, points) = boehm_insert(&self.knots, p, k, t, &self.points, |a, b, alpha| {
            let q = lerp(a.coords, b.coords, alpha);
            Point::from(clamp_to_box(q, point_bounds(&[a, b])))
        });
        BSpline::from_checked_parts(p, knots, points)
    }

    /// The polynomial pieces of the curve as Bézier curves, one per non-empty
    /// knot span of the domain, in parameter order.
    ///
    /// The control points of the piece on `[a, b]` are the blossom values
    /// `bᵣ = f(a, …, a, b, …, b)` (`p − r` times `a`, `r` times `b`), computed
    /// at construction by de Boor's algorithm with a different argument at
    /// each level (Ramshaw's blossoming principle).
    pub fn to_bezier_spans(&self) -> Vec<BezierSpan<D>> {
        self.pieces.bezier_spans(|&c| c)
    }

    /// Adaptive flattening of the whole curve (span by span) to `tolerance`,
    /// with the guaranteed bound; see [`Flattening`].
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] for a tolerance that is not finite and
    /// positive; [`Error::ToleranceTooSmall`] below `1e-10 ×` the largest
    /// control-point coordinate.
    pub fn flatten(&self, tolerance: f64) -> Result<Flattening<D>, Error> {
        let spans = self.to_bezier_spans();
        flatten_pieces(
            self,
            spans.iter().map(|s| (s.curve.points(), s.knots)),
            tolerance,
        )
    }
}

impl<const D: usize> Curve<D> for BSpline<D> {
    #[inline]
    fn domain(&self) -> (f64, f64) {
        knots::domain(&self.knots, self.degree, self.points.len())
    }

    /// Finds the piece, then runs de Casteljau on its precomputed Bézier
    /// form at `u = (t − a)/(b − a)`.
    #[inline]
    fn eval(&self, t: f64) -> Point<f64, D> {
        let t = clamp_to_domain(t, self.domain());
        Point::from(self.pieces.eval(t).unwrap_or_else(SVector::zeros))
    }

    #[inline]
    fn derivative(&self, t: f64) -> SVector<f64, D> {
        self.eval_with_derivative(t).1
    }

    /// The precomputed Bézier form of every non-empty span
    /// ([`to_bezier_spans`](BSpline::to_bezier_spans)).
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
        Some(self.to_bezier_spans())
    }

    /// Exact: the first non-negligible derivative of order `1 … p`, by de
    /// Boor on the control points' differences (repeated control points give
    /// exact zeros there). At an interior knot the limit is from the right.
    fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
        let domain = self.domain();
        let t = clamp_to_domain(t, domain);
        let size = NaturalSize::of_points(&self.points, self.degree, self.pieces.width_at(t));
        tangent_from_derivatives(size, t >= domain.1, |k| self.derivative_of_order(t, k))
    }

    /// As [`eval`](Curve::eval); the derivative of the piece's Bézier form is
    /// scaled by `1/(b − a)`.
    #[inline]
    fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let t = clamp_to_domain(t, self.domain());
        let (p, d) = self
            .pieces
            .eval_with_derivative(t)
            .unwrap_or_else(|| (SVector::zeros(), SVector::zeros()));
        (Point::from(p), d)
    }
}

/// The values `N_{span−q+r, q}(t)`, `r = 0 … q`, into `out[..=q]` by the
/// triangular Cox–de Boor recurrence; `left`, `right` are scratch of length
/// `≥ q + 1`.
fn basis_up_to(
    knots: &[f64],
    span: usize,
    t: f64,
    q: usize,
    out: &mut [f64],
    left: &mut [f64],
    right: &mut [f64],
) {
    out[0] = 1.0;
    for j in 1..=q {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut carry = 0.0;
        for r in 0..j {
            // right[r + 1] + left[j − r] = t_{span+r+1} − t_{span+r+1−j} > 0.
            let w = out[r] / (right[r + 1] + left[j - r]);
            out[r] = carry + right[r + 1] * w;
            carry = left[j - r] * w;
        }
        out[j] = carry;
    }
}

/// `num / den`, or zero where the knot difference `den` vanishes (the basis
/// function it belongs to is identically zero there).
#[inline]
fn safe_div(num: f64, den: f64) -> f64 {
    if den > 0.0 { num / den } else { 0.0 }
}

fn check_buffer(found: usize, expected: usize) -> Result<(), Error> {
    if found < expected {
        Err(Error::BufferLength { expected, found })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point1;

    fn spline(p: usize, knots: &[f64], n: usize) -> BSpline<1> {
        let points = (0..n).map(|i| Point1::new(i as f64 * i as f64)).collect();
        BSpline::new(p, knots.to_vec(), points).unwrap()
    }

    #[test]
    fn uniform_cubic_basis_is_one_sixth_two_thirds_one_sixth() {
        let c = spline(3, &[0., 1., 2., 3., 4., 5., 6., 7.], 4);
        let mut out = [0.0; 4];
        let first = c.basis_functions(3.0, &mut out).unwrap();
        assert_eq!(first, 0);
        let expect = [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0];
        for (a, b) in out.iter().zip(expect) {
            assert!((a - b).abs() < 1e-15, "{out:?}");
        }
        let mut d = [0.0; 12];
        c.basis_derivatives(3.0, 2, &mut d).unwrap();
        let d1 = [-0.5, 0.0, 0.5, 0.0];
        let d2 = [1.0, -2.0, 1.0, 0.0];
        for r in 0..4 {
            assert!((d[4 + r] - d1[r]).abs() < 1e-14, "{d:?}");
            assert!((d[8 + r] - d2[r]).abs() < 1e-14, "{d:?}");
        }
    }

    #[test]
    fn domain_end_belongs_to_last_nonempty_span() {
        // Degree 2, knots with a double knot at the domain end t_4 = 1.
        let c = spline(2, &[0., 0., 0., 1., 1., 2., 2.], 4);
        assert_eq!(c.domain(), (0.0, 1.0));
        assert_eq!(c.span(1.0), 2);
        // The end value is the limit from the left (P2 here), not zero.
        assert!((c.eval(1.0).x - 4.0).abs() < 1e-14);
        assert!((c.eval(1.0 - 1e-12).x - 4.0).abs() < 1e-10);
    }

    #[test]
    fn span_search_skips_repeated_knots() {
        let c = spline(2, &[0., 0., 0., 0.5, 0.5, 1., 1., 1.], 5);
        assert_eq!(c.span(0.0), 2);
        assert_eq!(c.span(0.49), 2);
        assert_eq!(c.span(0.5), 4);
        assert_eq!(c.span(1.0), 4);
        assert_eq!(c.span(f64::NAN), 2);
        assert_eq!(c.span(7.0), 4);
    }
}

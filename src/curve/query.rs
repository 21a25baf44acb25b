//! The nearest point of a curve to a given point, certified global: the
//! method, its rounding bound and why the answer is global are in the docs
//! of [`CurveProjector`]; curves without spans get a sampled answer (see
//! [`Curve::nearest_point`]).

use super::homogeneous::max_weight;
use super::unit_scale::UnitScale;
use super::{RationalBezier, RationalBezierSpan, max_abs_coordinate};
use crate::bernstein::binomial_row;
use crate::roots::{Root, find_roots_to};
use crate::scratch::with_scratch;
use crate::{Curve, Error};
use nalgebra::{Point, SVector};

/// Roots of `g` closer together than this (in a span's own parameter) may be
/// reported as one; Newton's polish and the distance comparison finish them.
const CANDIDATE_WIDTH: f64 = 1.0 / (1u64 << 32) as f64;

/// Newton steps at most when polishing the winner.
const POLISH_STEPS: usize = 8;

/// Uniform samples of a curve without spans (see [`Curve::nearest_point`]).
const FALLBACK_SEGMENTS: usize = 4096;

/// Local minima of the samples refined by the fallback.
const FALLBACK_MINIMA: usize = 16;

/// The point of a curve nearest to a query point `P`:
/// `distance = |point − P| = min over the domain of |C(t) − P|`.
///
/// `point` is the curve's point at `t`, as evaluated on the span that
/// holds `t` (equal to [`Curve::eval`] at `t` up to rounding). When several
/// points are equally near (the centre of a circle) any of them is a right
/// answer; the one with the smallest computed distance, then the smallest
/// `t`, is returned.
///
/// ```
/// use revolve::{Bezier, Curve};
/// use revolve::nalgebra::Point2;
///
/// // The parabola y = x² on [0, 1]; from (0, 1) the nearest point has
/// // x² = 1/2 (the distance² x² + (x² − 1)² is least there).
/// let parabola = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(0.5, 0.0), Point2::new(1.0, 1.0)])?;
/// let near = parabola.nearest_point(&Point2::new(0.0, 1.0))?;
/// assert!((near.point.x - 0.5f64.sqrt()).abs() < 1e-15);
/// assert!((near.distance - 0.75f64.sqrt()).abs() < 1e-15);
/// assert!(near.certified && (near.t - 0.5f64.sqrt()).abs() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearestPoint<const D: usize> {
    /// The parameter of the nearest point, in the curve's domain.
    pub t: f64,
    /// The nearest point `C(t)`.
    pub point: Point<f64, D>,
    /// Its distance `|C(t) − P|` from the query point.
    pub distance: f64,
    /// `true` when the answer is certified global (curves with rational
    /// Bézier spans: every critical point isolated); `false` for the
    /// sampled answer of a curve without spans (see
    /// [`Curve::nearest_point`]).
    pub certified: bool,
}

/// A curve prepared for many nearest-point queries: its rational Bézier
/// spans with the `P`-independent part of each span's condition
/// polynomial (the derivative numerator `N = X′W − XW′`, below) computed
/// once. [`Curve::nearest_point`] builds one per call; keep one to answer
/// many queries on the same curve.
///
/// # The condition
/// A point `C(t)` nearest to `P` is an end of the domain or a critical point
/// of the squared distance, where `f(t) = (C(t) − P)·C′(t) = 0`. On a
/// rational Bézier span `C = X/W` (homogeneous numerator `X = Σ wᵢPᵢBᵢⁿ`,
/// weight `W = Σ wᵢBᵢⁿ > 0`) write `Y = X − P·W = Σ wᵢ(Pᵢ − P)Bᵢⁿ`; then
/// `C − P = Y/W` and `C′ = (X′W − XW′)/W² = (Y′W − YW′)/W²`, so
///
/// ```text
/// W³·f = g = Y · N,   N = X′W − XW′ = Σₖ dₖ Bₖ^{2n−2},
/// dₖ = Σ_{i+j=k+1, i>j} C(n,i)·C(n,j)·(i − j)/C(2n−2,k) · wᵢwⱼ(Pᵢ − Pⱼ),
/// ```
///
/// a polynomial of degree `3n − 2` with the same roots as `f`. The formula
/// for `N` follows from `Bᵢⁿ′Bⱼⁿ − BᵢⁿBⱼⁿ′ = C(n,i)C(n,j)(i − j)/C(2n−2,i+j−1)
/// · B_{i+j−1}^{2n−2}` (differentiate `sⁱ(1 − s)ⁿ⁻ⁱ`; the degree `2n − 1`
/// terms cancel), summed with the pairs `(i, j)`, `(j, i)` together, which
/// removes `P` (rational Bézier curves: Farin, *Curves and Surfaces for
/// CAGD*, the chapter on rational Bézier curves). `N` does not depend on `P`
/// and is computed once per span. With equal weights `N = C′` (degree
/// `n − 1`, coefficients `n(Pᵢ₊₁ − Pᵢ)`) and `g = (C − P)·C′` has degree
/// `2n − 1`. The product is formed in the Bernstein basis,
/// `gᵣ = Σ_{i+k=r} C(n,i)C(m,k)/C(n+m,r) · yᵢ·dₖ`, with a bound on its
/// rounding error (below), and every root of `g` in the span is isolated by
/// [`find_roots_to`](crate::roots::find_roots_to), which misses none for
/// coefficients within that bound, and refined there to double precision;
/// the span ends are candidates too; the nearest candidate of all wins, and
/// is then polished by Newton's method on the
/// unsquared condition `f` (the curve's own derivatives, not the formed
/// polynomial), the polished value kept if it is nearer. (Polishing only the
/// winner is enough: near a critical point the distance is flat to second
/// order, so an unpolished root's distance is already within rounding.)
///
/// # The rounding bound
/// `yᵢ = wᵢ(Pᵢ − P)` carries `2ε` relative error, each `dₖ` at most
/// `(n + 8)ε·Mₖ` where `Mₖ` bounds its terms' magnitudes (componentwise),
/// and the products, the `D` dot-product terms, the binomial ratios and the
/// sum over `i + k = r` add `(n + D + 5)ε`: every `gᵣ` is within
/// `(2n + D + 20)ε · Σ_{i+k=r} β·|yᵢ|·Mₖ ≤ (2n + D + 20)ε · maxᵢ‖yᵢ‖∞ ·
/// maxₖ‖Mₖ‖₁` of the exact value (the weights `β` of one `r` sum to one;
/// the exact value is the polynomial of the exact `P` and control points,
/// with the span's weights scaled so the largest is 1).
///
/// # Why the answer is global
/// The nearest point is an end or a root of `g` on some span; no root is
/// missed, spans are skipped only when the distance from `P` to their
/// control points' box (which holds the span: positive weights) exceeds the
/// best distance found. Near a double root (the point is a centre of
/// curvature) the root is reported within the coefficients' noise, where
/// the distance is flat to second order; an interval where `g` vanishes
/// within its error (`P` at the centre of a circular arc: every point is
/// nearest) gives its ends and midpoint as candidates. So the distance
/// returned exceeds the true minimum by rounding only.
///
/// ```
/// use revolve::{BSpline, Curve};
/// use revolve::curve::CurveProjector;
/// use revolve::nalgebra::Point2;
///
/// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(2.0, -2.0),
///                Point2::new(3.0, 2.0), Point2::new(4.0, 0.0)];
/// let spline = BSpline::clamped(3, pts)?;
/// let projector = CurveProjector::new(&spline)?;
/// let near = projector.nearest(&Point2::new(2.0, 3.0))?;
/// assert!(near.certified);
/// // No sample of the curve is nearer.
/// for k in 0..=1000 {
///     let d = (spline.eval(k as f64 / 1000.0) - Point2::new(2.0, 3.0)).norm();
///     assert!(near.distance <= d + 1e-12);
/// }
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct CurveProjector<const D: usize> {
    spans: Vec<SpanForm<D>>,
    /// The largest absolute control-point coordinate (tiny geometry is
    /// queried rescaled, see [`UnitScale`]).
    magnitude: f64,
}

/// One span and the `P`-independent data of its condition polynomial.
#[derive(Debug, Clone)]
struct SpanForm<const D: usize> {
    knots: (f64, f64),
    curve: RationalBezier<D>,
    /// The weights scaled so the largest is 1 (all 1 for equal weights).
    weights: Vec<f64>,
    /// The Bernstein coefficients `dₖ` of `N` (degree `m`).
    numerator: Vec<SVector<f64, D>>,
    /// `maxₖ‖Mₖ‖₁`, with `Mₖ` the componentwise bounds on the terms that
    /// form `dₖ` (for the rounding bound).
    magnitude: f64,
    /// `C(n,i)·C(m,k)/C(n+m,i+k)`, row-major `(n + 1) × (m + 1)`.
    product: Vec<f64>,
}

impl<const D: usize> SpanForm<D> {
    fn new(span: RationalBezierSpan<D>) -> Self {
        let curve = span.curve;
        let n = curve.degree();
        let points: Vec<SVector<f64, D>> = curve.points().iter().map(|p| p.coords).collect();
        let (weights, numerator, magnitude) = if curve.is_polynomial() {
            // N = C′: n(Pᵢ₊₁ − Pᵢ), degree n − 1.
            let d: Vec<SVector<f64, D>> = points
                .windows(2)
                .map(|w| (w[1] - w[0]) * n as f64)
                .collect();
            let m = d.iter().fold(0.0_f64, |m, v| m.max(v.abs().sum()));
            (vec![1.0; n + 1], d, m)
        } else {
            let top = max_weight(curve.weights().iter().copied());
            let w: Vec<f64> = curve.weights().iter().map(|&w| w / top).collect();
            let (row_n, row_m) = (binomial_row(n), binomial_row(2 * n - 2));
            let mut d = vec![SVector::zeros(); 2 * n - 1];
            let mut m = vec![SVector::zeros(); 2 * n - 1];
            for i in 1..=n {
                for j in 0..i.min(2 * n - i) {
                    let k = i + j - 1;
                    // Divided before multiplying: no overflow at high degree.
                    let c = row_n[i] / row_m[k] * row_n[j] * (i - j) as f64 * w[i] * w[j];
                    let term = (points[i] - points[j]) * c;
                    d[k] += term;
                    m[k] += term.abs();
                }
            }
            (w, d, m.iter().fold(0.0_f64, |a, v| a.max(v.sum())))
        };
        let mdeg = numerator.len().saturating_sub(1);
        let (row_n, row_m, row_nm) = (binomial_row(n), binomial_row(mdeg), binomial_row(n + mdeg));
        let product = (0..=n)
            .flat_map(|i| {
                let (row_n, row_m, row_nm) = (&row_n, &row_m, &row_nm);
                // C(n,i)/C(n+m,i+k) ≤ 1/C(m,k): divided first, no overflow.
                (0..=mdeg).map(move |k| row_n[i] / row_nm[i + k] * row_m[k])
            })
            .collect();
        SpanForm {
            knots: span.knots,
            curve,
            weights,
            numerator,
            magnitude,
            product,
        }
    }

    /// The parameter of the curve at the span's own parameter `s`.
    fn parameter(&self, s: f64) -> f64 {
        let (a, b) = self.knots;
        if s <= 0.0 {
            a
        } else if s >= 1.0 {
            b
        } else {
            a + (b - a) * s
        }
    }

    /// The distance from `p` to the box of the span's control points,
    /// which holds the span.
    fn distance_bound(&self, p: &Point<f64, D>) -> f64 {
        let (lo, hi) = self.curve.bounds();
        let mut sum = 0.0;
        for c in 0..D {
            let gap = (lo[c] - p[c]).max(p[c] - hi[c]).max(0.0);
            sum += gap * gap;
        }
        sum.sqrt()
    }

    /// Hands the coefficients of `g = Y·N` for the query point `p`, and their
    /// rounding bound, to `then` (no root search for a constant span).
    fn with_condition<R>(&self, p: &Point<f64, D>, then: impl FnOnce(&[f64], f64) -> R) -> R {
        let n = self.curve.degree();
        let m = self.numerator.len().saturating_sub(1);
        let len = if self.numerator.is_empty() {
            0
        } else {
            n + m + 1
        };
        with_scratch(len, 0.0, |g| {
            let mut largest = 0.0_f64;
            for (i, (pi, &wi)) in self.curve.points().iter().zip(&self.weights).enumerate() {
                let y = (pi - p) * wi;
                largest = largest.max(y.amax());
                for (k, d) in self.numerator.iter().enumerate() {
                    g[i + k] += self.product[i * (m + 1) + k] * y.dot(d);
                }
            }
            let gamma = (2 * n + D + 20) as f64 * f64::EPSILON * 1.01;
            then(g, gamma * largest * self.magnitude)
        })
    }

    /// The span's point at `s` and its distance from `p` (at the ends, the
    /// end control points themselves).
    fn candidate(&self, p: &Point<f64, D>, s: f64) -> (Point<f64, D>, f64) {
        let points = self.curve.points();
        let point = if s <= 0.0 {
            points[0]
        } else if s >= 1.0 {
            points[points.len() - 1]
        } else {
            self.curve.eval(s)
        };
        (point, (point - p).norm())
    }

    /// Newton's method on `f(s) = (C(s) − P)·C′(s)`, `f′ = |C′|² + (C − P)·C″`,
    /// from `s`, kept in `[0, 1]`; stops on a step below `4ε`, a step no
    /// smaller than the one before (rounding noise, or no convergence), or
    /// a derivative that is zero or not finite.
    fn polish(&self, p: &Point<f64, D>, mut s: f64) -> f64 {
        let mut d = [SVector::<f64, D>::zeros(); 3];
        let mut last_step = f64::INFINITY;
        for _ in 0..POLISH_STEPS {
            if self.curve.derivatives(s, &mut d).is_err() {
                break;
            }
            let r = d[0] - p.coords;
            let f = r.dot(&d[1]);
            let df = d[1].norm_squared() + r.dot(&d[2]);
            if !(df.is_finite() && df != 0.0 && f.is_finite()) {
                break;
            }
            let next = (s - f / df).clamp(0.0, 1.0);
            let step = (next - s).abs();
            if step >= last_step {
                break;
            }
            s = next;
            last_step = step;
            if step <= 4.0 * f64::EPSILON {
                break;
            }
        }
        s
    }
}

/// The best candidate so far.
struct Best<const D: usize> {
    t: f64,
    point: Point<f64, D>,
    distance: f64,
    /// Where the projector found it: span index and local parameter.
    at: (usize, f64),
}

impl<const D: usize> Best<D> {
    /// No candidate yet.
    fn none() -> Self {
        Best {
            t: f64::INFINITY,
            point: Point::origin(),
            distance: f64::INFINITY,
            at: (0, 0.0),
        }
    }

    /// Keeps the candidate if it is nearer, or as near with a smaller
    /// parameter.
    fn offer(&mut self, candidate: Best<D>) {
        let (t, d) = (candidate.t, candidate.distance);
        if d < self.distance || (d == self.distance && t < self.t) {
            *self = candidate;
        }
    }

    fn answer(&self, certified: bool) -> NearestPoint<D> {
        NearestPoint {
            t: self.t,
            point: self.point,
            distance: self.distance,
            certified,
        }
    }
}

impl<const D: usize> CurveProjector<D> {
    /// Prepares the curve's [rational Bézier spans](Curve::rational_bezier_spans).
    ///
    /// # Errors
    /// [`Error::NotPiecewiseRational`] when the curve has no spans;
    /// otherwise as [`from_spans`](Self::from_spans).
    pub fn new<C: Curve<D> + ?Sized>(curve: &C) -> Result<Self, Error> {
        let spans = curve
            .rational_bezier_spans()
            .ok_or(Error::NotPiecewiseRational)?;
        Self::from_spans(spans)
    }

    /// Prepares the given spans (in parameter order).
    ///
    /// # Errors
    /// [`Error::SpansOutOfOrder`] for no spans, or a span whose knot
    /// interval is not finite and increasing or starts before the previous
    /// one ends; [`Error::SpanPointNotFinite`] for a control point beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn from_spans(spans: Vec<RationalBezierSpan<D>>) -> Result<Self, Error> {
        validate_spans(&spans)?;
        Ok(CurveProjector {
            magnitude: spans_magnitude(&spans),
            spans: spans.into_iter().map(SpanForm::new).collect(),
        })
    }

    /// The nearest point of the curve to `p`, certified global (the method
    /// and its guarantee are in the [type's docs](CurveProjector)).
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate that is NaN, infinite
    /// or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn nearest(&self, p: &Point<f64, D>) -> Result<NearestPoint<D>, Error> {
        check_query_point(p)?;
        // Tiny geometry (the curve and the point): the same query on the
        // spans and the point rescaled exactly, the lengths scaled back.
        if let Some(unit) = UnitScale::for_magnitude(self.magnitude.max(p.coords.amax())) {
            let spans = self.spans.iter().map(|form| {
                scaled_span(
                    &unit,
                    &RationalBezierSpan {
                        knots: form.knots,
                        curve: form.curve.clone(),
                    },
                )
            });
            let scaled = CurveProjector {
                spans: spans.map(SpanForm::new).collect(),
                magnitude: 1.0,
            };
            let near = scaled.nearest_at_scale(&Point::from(unit.up_vector(p.coords)));
            return Ok(NearestPoint {
                point: Point::from(unit.down_vector(near.point.coords)),
                distance: unit.down(near.distance),
                ..near
            });
        }
        Ok(self.nearest_at_scale(p))
    }

    /// [`nearest`](Self::nearest) for geometry that is not tiny.
    fn nearest_at_scale(&self, p: &Point<f64, D>) -> NearestPoint<D> {
        let mut best = Best::none();
        // Every span's ends first: a good bound to skip spans by.
        for i in 0..self.spans.len() {
            best.offer(self.candidate(i, p, 0.0));
            best.offer(self.candidate(i, p, 1.0));
        }
        // The span whose box is nearest, then the others unless their box
        // is farther than the best candidate.
        let first = (0..self.spans.len())
            .map(|i| (i, self.spans[i].distance_bound(p)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
            .0;
        self.search(first, p, &mut best);
        for (i, span) in self.spans.iter().enumerate() {
            if i != first && span.distance_bound(p) * (1.0 - 8.0 * f64::EPSILON) <= best.distance {
                self.search(i, p, &mut best);
            }
        }
        // Polish the winner if it is a root (a span end is exact).
        let (i, s) = best.at;
        if s > 0.0 && s < 1.0 {
            let polished = self.spans[i].polish(p, s);
            if polished != s {
                best.offer(self.candidate(i, p, polished));
            }
        }
        best.answer(true)
    }

    /// The candidate at the local parameter `s` of span `i`.
    fn candidate(&self, i: usize, p: &Point<f64, D>, s: f64) -> Best<D> {
        let span = &self.spans[i];
        let (point, distance) = span.candidate(p, s);
        Best {
            t: span.parameter(s),
            point,
            distance,
            at: (i, s),
        }
    }

    /// Offers span `i`'s critical points (the roots of its condition
    /// polynomial) to `best`.
    fn search(&self, i: usize, p: &Point<f64, D>, best: &mut Best<D>) {
        self.spans[i].with_condition(p, |g, err| {
            if g.is_empty() {
                return;
            }
            let mut offer = |s: f64| best.offer(self.candidate(i, p, s));
            find_roots_to(g, err, CANDIDATE_WIDTH, |root| match root {
                Root::At(s) => offer(s),
                Root::Flat { from, to } => {
                    offer(from);
                    offer(0.5 * (from + to));
                    offer(to);
                }
            });
        });
    }
}

/// The largest absolute control-point coordinate of `spans`.
pub(super) fn spans_magnitude<const D: usize>(spans: &[RationalBezierSpan<D>]) -> f64 {
    spans
        .iter()
        .map(|s| max_abs_coordinate(s.curve.points()))
        .fold(0.0, f64::max)
}

/// `span` with its control points times `unit`'s power of two (weights
/// unchanged): the same span at another scale, exactly.
pub(super) fn scaled_span<const D: usize>(
    unit: &UnitScale,
    span: &RationalBezierSpan<D>,
) -> RationalBezierSpan<D> {
    let points = span
        .curve
        .points()
        .iter()
        .map(|p| Point::from(unit.up_vector(p.coords)))
        .collect();
    RationalBezierSpan {
        knots: span.knots,
        curve: RationalBezier::from_valid_parts(points, span.curve.weights().to_vec()),
    }
}

/// Checks spans as [`CurveProjector::from_spans`] documents:
/// [`Error::SpansOutOfOrder`], [`Error::SpanPointNotFinite`].
pub(super) fn validate_spans<const D: usize>(spans: &[RationalBezierSpan<D>]) -> Result<(), Error> {
    if spans.is_empty() {
        return Err(Error::SpansOutOfOrder { index: 0 });
    }
    let mut end = f64::NEG_INFINITY;
    for (index, span) in spans.iter().enumerate() {
        let (a, b) = span.knots;
        if !(a.is_finite() && b.is_finite() && a < b && a >= end) {
            return Err(Error::SpansOutOfOrder { index });
        }
        end = b;
        let fits = span
            .curve
            .points()
            .iter()
            .all(|p| p.coords.iter().all(|c| c.abs() <= crate::MAX_COORDINATE));
        if !fits {
            return Err(Error::SpanPointNotFinite { span: index });
        }
    }
    Ok(())
}

/// [`Error::InvalidQueryPoint`] for a coordinate that is not finite or
/// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
pub(crate) fn check_query_point<const D: usize>(p: &Point<f64, D>) -> Result<(), Error> {
    match p
        .coords
        .iter()
        .position(|c| !c.is_finite() || c.abs() > crate::MAX_COORDINATE)
    {
        Some(coordinate) => Err(Error::InvalidQueryPoint {
            coordinate,
            value: p[coordinate],
        }),
        None => Ok(()),
    }
}

/// [`Curve::nearest_point`]: certified on the curve's rational spans, else
/// the sampled answer.
pub(crate) fn nearest_point<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    p: &Point<f64, D>,
) -> Result<NearestPoint<D>, Error> {
    check_query_point(p)?;
    match CurveProjector::new(curve) {
        Ok(projector) => projector.nearest(p),
        Err(Error::NotPiecewiseRational) => sampled_nearest(curve, p),
        Err(e) => Err(e),
    }
}

/// The nearest point of a curve known only by `eval` and `derivative`:
/// [`FALLBACK_SEGMENTS`] uniform samples, the [`FALLBACK_MINIMA`] nearest
/// local minima among them refined by bisection on the sign of
/// `(C − P)·C′` between their neighbours, the domain ends. Not certified.
fn sampled_nearest<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    p: &Point<f64, D>,
) -> Result<NearestPoint<D>, Error> {
    let (a, b) = curve.domain();
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::InvalidDomain { start: a, end: b });
    }
    let at = |i: usize| match i {
        0 => a,
        i if i == FALLBACK_SEGMENTS => b,
        i => {
            let s = i as f64 / FALLBACK_SEGMENTS as f64;
            a * (1.0 - s) + b * s
        }
    };
    let point_at = |t: f64| {
        let c = curve.eval(t);
        if c.coords.iter().all(|x| x.abs() <= crate::MAX_COORDINATE) {
            Ok(c)
        } else {
            Err(Error::CurveNotFinite { t })
        }
    };
    let mut distances = Vec::with_capacity(FALLBACK_SEGMENTS + 1);
    for i in 0..=FALLBACK_SEGMENTS {
        distances.push((point_at(at(i))? - p).norm());
    }
    let last = FALLBACK_SEGMENTS;
    let mut minima: Vec<usize> = (0..=last)
        .filter(|&i| {
            (i == 0 || distances[i] <= distances[i - 1])
                && (i == last || distances[i] <= distances[i + 1])
        })
        .collect();
    minima.sort_by(|&i, &j| distances[i].total_cmp(&distances[j]));
    minima.truncate(FALLBACK_MINIMA);

    let mut best = Best::none();
    let mut offer = |t: f64| -> Result<(), Error> {
        let point = point_at(t)?;
        best.offer(Best {
            t,
            point,
            distance: (point - p).norm(),
            at: (0, t),
        });
        Ok(())
    };
    offer(a)?;
    offer(b)?;
    // f = (C − P)·C′ rises through a minimum: bisect its sign change.
    let slope = |t: f64| {
        let (c, d) = curve.eval_with_derivative(t);
        (c - p).dot(&d)
    };
    for i in minima {
        offer(at(i))?;
        let (mut lo, mut hi) = (at(i.saturating_sub(1)), at((i + 1).min(last)));
        if !(slope(lo) < 0.0 && slope(hi) > 0.0) {
            continue;
        }
        for _ in 0..128 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if slope(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        offer(lo)?;
        offer(hi)?;
    }
    Ok(best.answer(false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bernstein::{bernstein_sum, eval};
    use nalgebra::Point2;

    /// The formed condition polynomial agrees with `W³·(C − P)·C′`
    /// evaluated from the curve, within its rounding bound (plus that of
    /// the direct evaluation), for polynomial and rational spans.
    #[test]
    fn condition_polynomial_is_w_cubed_times_f() {
        let points = vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 3.0),
            Point2::new(2.5, -1.0),
            Point2::new(4.0, 2.0),
        ];
        for weights in [vec![1.0; 4], vec![1.0, 0.3, 4.0, 0.8]] {
            let curve = RationalBezier::new(points.clone(), weights.clone()).unwrap();
            let span = SpanForm::new(RationalBezierSpan {
                knots: (0.0, 1.0),
                curve: curve.clone(),
            });
            let top = weights.iter().fold(0.0_f64, |m, &w| m.max(w));
            let w: Vec<f64> = weights.iter().map(|w| w / top).collect();
            let p = Point2::new(1.5, 0.7);
            span.with_condition(&p, |g, err| {
                for k in 0..=20 {
                    let s = k as f64 / 20.0;
                    let mut d = [SVector::zeros(); 2];
                    curve.derivatives(s, &mut d).unwrap();
                    let big_w = bernstein_sum(&w, s).unwrap();
                    let f = (d[0] - p.coords).dot(&d[1]);
                    let want = big_w.powi(3) * f;
                    let got = eval(g, s).unwrap();
                    assert!((got - want).abs() <= err + 1e-13, "s={s}: {got} vs {want}");
                }
                assert!(err < 1e-12, "bound {err}");
            });
        }
    }

    #[test]
    fn homogeneous_numerator_is_translation_free() {
        // N = X′W − XW′ has no P in it: the same for the curve moved.
        let moved = |dx: f64| {
            let pts = vec![
                Point2::new(dx, 0.0),
                Point2::new(1.0 + dx, 1.0),
                Point2::new(dx, 1.0),
            ];
            SpanForm::new(RationalBezierSpan {
                knots: (0.0, 1.0),
                curve: RationalBezier::new(pts, vec![1.0, 0.5, 2.0]).unwrap(),
            })
            .numerator
        };
        assert_eq!(moved(0.0), moved(8.0));
    }
}

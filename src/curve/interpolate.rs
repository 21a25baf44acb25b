//! Spline interpolation through data points, and the pieces every
//! construction through data shares (least-squares fitting, surface
//! interpolation, lofting): centripetal parameters, knots by averaging,
//! the basis functions at a parameter and the collocation system.
//!
//! Notation (Piegl & Tiller, *The NURBS Book*, §9.2): data points
//! `Q₀ … Q_{N−1}`, degree `p`, parameters `ū₀ = 0 < ū₁ < … < ū_{N−1} = 1`.
//! The interpolating spline `C(t) = Σᵢ Nᵢ,ₚ(t) Pᵢ` has `N` control points
//! and satisfies `C(ūₖ) = Qₖ`, a banded linear system for the `Pᵢ` (row `k`
//! holds the `p + 1` basis functions that do not vanish at `ūₖ`).
//!
//! - Centripetal parameters (Lee, 1989): `ūₖ − ūₖ₋₁` proportional to
//!   `√|Qₖ − Qₖ₋₁|`. They follow sharp turns better than chord lengths and
//!   are invariant under rotations, translations and uniform scaling.
//! - Knots by averaging (Piegl & Tiller eq. 9.8): `p + 1` knots at 0 and at
//!   1, and `t_{j+p} = (ū_j + … + ū_{j+p−1})/p` for `j = 1 … N − p − 1`.
//!   Then `t_k < ū_k < t_{k+p+1}` for every interior `k`
//!   (Schoenberg–Whitney), so the system is non-singular, and each row's
//!   non-zeros lie within `p` of the diagonal.

use super::banded_solve::BandedMatrix;
use super::validate_points;
use crate::{BSpline, Error, MAX_COORDINATE};
use nalgebra::{Point, SVector};

/// The smallest step between consecutive parameters (`16ε`, the
/// parameters running from 0 to 1): points closer together than that,
/// relative to the other chords, are [coincident](Error::CoincidentPoints).
/// Knots by averaging are then at least that far apart too, well above the
/// rounding limit of [`BSpline::new`].
pub(crate) const MIN_PARAMETER_STEP: f64 = 16.0 * f64::EPSILON;

/// [`Error::ZeroDegree`] for degree 0, [`Error::TooFewPoints`] for fewer
/// than `degree + 1` points.
pub(crate) fn check_degree_and_count(degree: usize, points: usize) -> Result<(), Error> {
    if degree == 0 {
        return Err(Error::ZeroDegree);
    }
    if points < degree.saturating_add(1) {
        return Err(Error::TooFewPoints { degree, points });
    }
    Ok(())
}

/// The Euclidean length of `v`, scaled by its largest component first so
/// that it neither overflows nor underflows (`1e-300`-long chords are not
/// zero).
pub(crate) fn length<const K: usize>(v: &SVector<f64, K>) -> f64 {
    let m = v.amax();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    m * (v / m).norm()
}

/// The centripetal steps `√|Qₖ − Qₖ₋₁|`, `k = 1 … N − 1`.
pub(crate) fn centripetal_steps<const D: usize>(points: &[Point<f64, D>]) -> Vec<f64> {
    points
        .windows(2)
        .map(|w| length(&(w[1] - w[0])).sqrt())
        .collect()
}

/// The normalized running sums of `steps`: `0`, then `(s₁ + … + sₖ)/S`,
/// the last exactly 1; `None` when the total `S` is zero.
pub(crate) fn normalized_sums(steps: &[f64]) -> Option<Vec<f64>> {
    let total: f64 = steps.iter().sum();
    if !total.is_finite() || total <= 0.0 {
        return None;
    }
    let mut params = Vec::with_capacity(steps.len() + 1);
    params.push(0.0);
    let mut sum = 0.0;
    for &s in steps {
        sum += s;
        params.push((sum / total).min(1.0));
    }
    if let Some(last) = params.last_mut() {
        *last = 1.0;
    }
    Some(params)
}

/// The index `k` of the first step `ūₖ − ūₖ₋₁` below
/// [`MIN_PARAMETER_STEP`], if any.
pub(crate) fn first_short_step(params: &[f64]) -> Option<usize> {
    (1..params.len()).find(|&k| {
        let step = params[k] - params[k - 1];
        step.is_nan() || step < MIN_PARAMETER_STEP
    })
}

/// The centripetal parameters of a curve's data points (at least two).
///
/// # Errors
/// [`Error::CoincidentPoints`] with the index of the second point of the
/// first pair at zero distance, or whose parameter step is below
/// [`MIN_PARAMETER_STEP`].
pub(crate) fn centripetal_parameters<const D: usize>(
    points: &[Point<f64, D>],
) -> Result<Vec<f64>, Error> {
    let steps = centripetal_steps(points);
    if let Some(k) = steps.iter().position(|&s| s == 0.0) {
        return Err(Error::CoincidentPoints { index: k + 1 });
    }
    let params = normalized_sums(&steps).ok_or(Error::CoincidentPoints { index: 1 })?;
    match first_short_step(&params) {
        Some(index) => Err(Error::CoincidentPoints { index }),
        None => Ok(params),
    }
}

/// The parameters of a family of lines of points (the columns or rows of
/// a grid, each of `count` points), averaged (Piegl & Tiller §9.2.5): each
/// line with positive length gets its centripetal parameters, and their
/// mean is taken; lines of zero length (a collapsed edge, a pole) are left
/// out.
///
/// # Errors
/// `Err(k)` when the averaged step `ūₖ − ūₖ₋₁` is below
/// [`MIN_PARAMETER_STEP`] (points `k − 1` and `k` coincide in every line
/// with length), or `Err(1)` when no line has any length.
pub(crate) fn averaged_parameters<'a, const D: usize>(
    count: usize,
    lines: impl Iterator<Item = &'a [Point<f64, D>]>,
) -> Result<Vec<f64>, usize> {
    let mut sum = vec![0.0; count];
    let mut used = 0usize;
    for line in lines {
        if let Some(params) = normalized_sums(&centripetal_steps(line)) {
            for (s, u) in sum.iter_mut().zip(params) {
                *s += u;
            }
            used += 1;
        }
    }
    if used == 0 {
        return Err(1);
    }
    let mut params: Vec<f64> = sum.iter().map(|s| (s / used as f64).min(1.0)).collect();
    params[0] = 0.0;
    params[count - 1] = 1.0;
    match first_short_step(&params) {
        Some(k) => Err(k),
        None => Ok(params),
    }
}

/// Knots by averaging (Piegl & Tiller eq. 9.8) for `N = params.len()`
/// increasing parameters and degree `p ≥ 1`, `p < N`: `p + 1` copies of
/// the first parameter, the means `t_{j+p} = (ū_j + … + ū_{j+p−1})/p` for
/// `j = 1 … N − p − 1`, and `p + 1` copies of the last (`N + p + 1`
/// knots).
pub(crate) fn averaged_knots(degree: usize, params: &[f64]) -> Vec<f64> {
    let (p, n) = (degree, params.len());
    let (first, last) = (params[0], params[n - 1]);
    let mut knots = Vec::with_capacity(n + p + 1);
    knots.extend(std::iter::repeat_n(first, p + 1));
    for j in 1..n - p {
        let mean = params[j..j + p].iter().sum::<f64>() / p as f64;
        knots.push(mean.clamp(first, last));
    }
    knots.extend(std::iter::repeat_n(last, p + 1));
    knots
}

/// Scratch space for [`basis_at`]: the basis values and the two rows of
/// knot differences of the recurrence.
pub(crate) struct BasisScratch {
    pub(crate) values: Vec<f64>,
    left: Vec<f64>,
    right: Vec<f64>,
}

impl BasisScratch {
    /// Room for degree `degree`.
    pub(crate) fn new(degree: usize) -> Self {
        Self {
            values: vec![0.0; degree + 1],
            left: vec![0.0; degree + 1],
            right: vec![0.0; degree + 1],
        }
    }
}

/// The knot span `s` (`p ≤ s < n`, `t_s < t_{s+1}`) of a clamped knot
/// vector with `n` control points that contains `t` (clamped into the
/// domain; the domain's end belongs to the last span), and the values
/// `N_{s−p+r, p}(t)`, `r = 0 … p`, written to `scratch.values`: the
/// triangular Cox–de Boor recurrence, in which every division is by a
/// positive knot difference.
pub(crate) fn basis_at(
    knots: &[f64],
    degree: usize,
    n: usize,
    t: f64,
    scratch: &mut BasisScratch,
) -> usize {
    let p = degree;
    let (a, b) = (knots[p], knots[n]);
    let t = if t >= a { t.min(b) } else { a };
    // The last of t_p … t_{n−1} at or below t.
    let span = p + knots[p..n].partition_point(|&k| k <= t) - 1;
    let BasisScratch {
        values,
        left,
        right,
    } = scratch;
    values[0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let den = right[r + 1] + left[j - r];
            let temp = if den > 0.0 { values[r] / den } else { 0.0 };
            values[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        values[j] = saved;
    }
    span
}

/// The interpolation system of degree `p` at given parameters, factored:
/// the knots by averaging and the LU factors of the collocation matrix
/// `A_{k,i} = N_{i,p}(ūₖ)`. One factorization serves any number of
/// right-hand sides (every row of a grid, every column of a loft).
#[derive(Debug, Clone)]
pub(crate) struct Interpolation {
    knots: Vec<f64>,
    matrix: BandedMatrix,
}

impl Interpolation {
    /// The system for `params` (strictly increasing from 0 to 1, at least
    /// `degree + 1` of them, `degree ≥ 1`).
    ///
    /// # Errors
    /// [`Error::SingularSystem`] (rounding only: the knots by averaging
    /// make the matrix non-singular), [`Error::AllocationFailed`].
    pub(crate) fn new(degree: usize, params: &[f64]) -> Result<Self, Error> {
        let knots = averaged_knots(degree, params);
        let matrix = collocation(degree, &knots, params)?;
        Ok(Self { knots, matrix })
    }

    /// The knots by averaging.
    pub(crate) fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control values `Pᵢ` with `Σᵢ Nᵢ,ₚ(ūₖ) Pᵢ = values[k]`. The first
    /// and last are exactly the first and last values (clamped knots).
    pub(crate) fn solve<const K: usize>(&self, values: &[SVector<f64, K>]) -> Vec<SVector<f64, K>> {
        let mut x = values.to_vec();
        self.matrix.solve(&mut x);
        if let (Some(first), Some(last)) = (values.first(), values.last()) {
            x[0] = *first;
            let end = x.len() - 1;
            x[end] = *last;
        }
        x
    }
}

/// The factored collocation matrix `N_{i,p}(ūₖ)` (rows `k`, columns `i`),
/// its band measured from the spans.
fn collocation(degree: usize, knots: &[f64], params: &[f64]) -> Result<BandedMatrix, Error> {
    let n = params.len();
    let mut scratch = BasisScratch::new(degree);
    let spans: Vec<usize> = params
        .iter()
        .map(|&u| basis_at(knots, degree, n, u, &mut scratch))
        .collect();
    // Row k's non-zeros are the columns span − p … span.
    let kl = spans
        .iter()
        .enumerate()
        .map(|(k, &s)| k.saturating_sub(s - degree))
        .max()
        .unwrap_or(0);
    let ku = spans
        .iter()
        .enumerate()
        .map(|(k, &s)| s.saturating_sub(k))
        .max()
        .unwrap_or(0);
    let mut matrix = BandedMatrix::zeros(n, kl, ku)?;
    for (k, &u) in params.iter().enumerate() {
        let span = basis_at(knots, degree, n, u, &mut scratch);
        for (r, &value) in scratch.values.iter().enumerate() {
            matrix.add(k, span - degree + r, value);
        }
    }
    matrix.factor()?;
    Ok(matrix)
}

/// The spline of degree `degree` through `points` at the parameters
/// `params` (valid: see [`Interpolation::new`]).
pub(crate) fn interpolate_at<const D: usize>(
    degree: usize,
    points: &[Point<f64, D>],
    params: &[f64],
) -> Result<BSpline<D>, Error> {
    let system = Interpolation::new(degree, params)?;
    let values: Vec<SVector<f64, D>> = points.iter().map(|p| p.coords).collect();
    let control = system.solve(&values).into_iter().map(Point::from).collect();
    BSpline::new(degree, system.knots, control)
}

impl<const D: usize> BSpline<D> {
    /// The clamped B-spline of degree `degree` through every point, in order
    /// (global interpolation, Piegl & Tiller §9.2.1).
    ///
    /// With `N` points `Q₀ … Q_{N−1}`:
    /// - parameters are centripetal, `ū₀ = 0`, `ūₖ − ūₖ₋₁ ∝ √|Qₖ − Qₖ₋₁|`,
    ///   `ū_{N−1} = 1`: the curve's domain is `[0, 1]` and `C(ūₖ) = Qₖ`;
    /// - knots by averaging (eq. 9.8): `p + 1` knots at 0 and at 1, and
    ///   `t_{j+p} = (ū_j + … + ū_{j+p−1})/p` inside;
    /// - the `N` control points solve the banded system
    ///   `Σᵢ Nᵢ,ₚ(ūₖ) Pᵢ = Qₖ` (LU with partial pivoting). `P₀ = Q₀` and
    ///   `P_{N−1} = Q_{N−1}` exactly.
    ///
    /// The result is invariant under rotations, translations and uniform
    /// scaling of the points (to rounding). `N = p + 1` points give a
    /// single Bézier piece. Collinear points give a curve on their line;
    /// equally spaced collinear points give the line at uniform speed.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let points = [
    ///     Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 3.0),
    ///     Point2::new(4.0, 1.0), Point2::new(6.0, 0.0),
    /// ];
    /// let curve = BSpline::interpolate(3, &points)?;
    /// assert_eq!(curve.domain(), (0.0, 1.0));
    /// assert_eq!(curve.points().len(), 5);
    /// // The curve passes through each point at its centripetal parameter.
    /// let steps: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).norm().sqrt()).collect();
    /// let total: f64 = steps.iter().sum();
    /// let mut u = 0.0;
    /// for (k, q) in points.iter().enumerate() {
    ///     assert!((curve.eval(u) - q).norm() < 1e-13);
    ///     if k < steps.len() { u += steps[k] / total; }
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// In the order checked: [`Error::ZeroDegree`];
    /// [`Error::TooFewPoints`] (fewer than `degree + 1` points);
    /// [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`] (beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE)) with the index of the
    /// data point; [`Error::CoincidentPoints`] with the index of the second
    /// point of two consecutive equal ones (or of a chord too short beside
    /// the others to give distinct parameters); [`Error::SingularSystem`]
    /// (rounding only); then the errors of [`BSpline::new`] for the result
    /// (e.g. [`Error::CoordinateTooLarge`] with the index of a *control*
    /// point, when the interpolant swings beyond `MAX_COORDINATE`).
    pub fn interpolate(degree: usize, points: &[Point<f64, D>]) -> Result<BSpline<D>, Error> {
        check_degree_and_count(degree, points.len())?;
        validate_points(points)?;
        let params = centripetal_parameters(points)?;
        interpolate_at(degree, points, &params)
    }

    /// The clamped B-spline of degree `degree` through every point at the
    /// given parameters, `C(parameters[k]) = points[k]`, with knots by
    /// averaging the parameters (Piegl & Tiller eq. 9.8) and the domain
    /// `[parameters[0], parameters[N − 1]]`.
    ///
    /// Use it for chord-length, uniform or your own parameters. Since the
    /// knots by averaging satisfy the Schoenberg–Whitney condition, the
    /// interpolant is the only spline of that degree and those knots
    /// through the points: points sampled from such a spline at these
    /// parameters give that spline back (to rounding).
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// // A cubic whose knots are the averages of (0, 1, 2, 3, 4, 5):
    /// // 0 0 0 0 2 3 5 5 5 5.
    /// let knots = vec![0.0, 0.0, 0.0, 0.0, 2.0, 3.0, 5.0, 5.0, 5.0, 5.0];
    /// let control: Vec<Point2<f64>> = [(0.0, 0.0), (1.0, 3.0), (2.0, -1.0), (4.0, 2.0),
    ///     (5.0, 0.5), (6.0, 1.0)].iter().map(|&(x, y)| Point2::new(x, y)).collect();
    /// let spline = BSpline::new(3, knots, control)?;
    /// let params = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0];
    /// let samples: Vec<Point2<f64>> = params.iter().map(|&t| spline.eval(t)).collect();
    /// let again = BSpline::interpolate_with_parameters(3, &samples, &params)?;
    /// assert_eq!(again.knots(), spline.knots());
    /// for (p, q) in again.points().iter().zip(spline.points()) {
    ///     assert!((p - q).norm() < 1e-13);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ZeroDegree`]; [`Error::TooFewPoints`];
    /// [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`] for a
    /// data point; [`Error::ParameterCount`] unless there is one parameter
    /// per point; [`Error::InvalidParameter`] for a parameter that is not
    /// finite, beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), or not
    /// above the previous one by `16ε` of the range;
    /// [`Error::SingularSystem`] (rounding only); then the errors of
    /// [`BSpline::new`] for the result.
    pub fn interpolate_with_parameters(
        degree: usize,
        points: &[Point<f64, D>],
        parameters: &[f64],
    ) -> Result<BSpline<D>, Error> {
        check_degree_and_count(degree, points.len())?;
        validate_points(points)?;
        if parameters.len() != points.len() {
            return Err(Error::ParameterCount {
                expected: points.len(),
                found: parameters.len(),
            });
        }
        let bad = |index: usize| Error::InvalidParameter {
            index,
            value: parameters[index],
        };
        if let Some(index) = parameters
            .iter()
            .position(|t| !(t.is_finite() && t.abs() <= MAX_COORDINATE))
        {
            return Err(bad(index));
        }
        let range = parameters[parameters.len() - 1] - parameters[0];
        if let Some(index) = (1..parameters.len()).find(|&k| {
            let step = parameters[k] - parameters[k - 1];
            !(range > 0.0 && step >= MIN_PARAMETER_STEP * range)
        }) {
            return Err(bad(index));
        }
        interpolate_at(degree, points, parameters)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averaged_knots_follow_the_formula() {
        let params = [0.0, 0.1, 0.3, 0.6, 0.8, 1.0];
        let knots = averaged_knots(3, &params);
        let expect = [
            0.0,
            0.0,
            0.0,
            0.0,
            (0.1 + 0.3 + 0.6) / 3.0,
            (0.3 + 0.6 + 0.8) / 3.0,
            1.0,
            1.0,
            1.0,
            1.0,
        ];
        assert_eq!(knots.len(), expect.len());
        for (a, b) in knots.iter().zip(expect) {
            assert!((a - b).abs() < 1e-16, "{knots:?}");
        }
        // Degree 1: the knots are the parameters.
        assert_eq!(
            averaged_knots(1, &params),
            [0.0, 0.0, 0.1, 0.3, 0.6, 0.8, 1.0, 1.0]
        );
    }

    #[test]
    fn basis_sums_to_one_and_finds_the_span() {
        let knots = [0.0, 0.0, 0.0, 0.25, 0.5, 1.0, 1.0, 1.0];
        let mut s = BasisScratch::new(2);
        for &(t, span) in &[
            (0.0, 2),
            (0.3, 3),
            (0.5, 4),
            (1.0, 4),
            (-1.0, 2),
            (f64::NAN, 2),
        ] {
            assert_eq!(basis_at(&knots, 2, 5, t, &mut s), span, "{t}");
            assert!((s.values.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(s.values.iter().all(|&v| v >= 0.0));
        }
    }

    #[test]
    fn averaged_parameters_skip_lines_of_zero_length() {
        use nalgebra::Point1;
        let pole = [Point1::new(2.0); 3];
        let line = [Point1::new(0.0), Point1::new(1.0), Point1::new(5.0)];
        let params = averaged_parameters(3, [&pole[..], &line[..]].into_iter()).unwrap();
        assert_eq!(params, vec![0.0, 1.0 / 3.0, 1.0]);
        assert_eq!(averaged_parameters(3, [&pole[..]].into_iter()), Err(1));
        let repeat = [Point1::new(0.0), Point1::new(0.0), Point1::new(5.0)];
        assert_eq!(averaged_parameters(3, [&repeat[..]].into_iter()), Err(1));
    }

    #[test]
    fn lengths_neither_overflow_nor_underflow() {
        use nalgebra::Vector3;
        assert_eq!(length(&Vector3::new(3e-300, 4e-300, 0.0)), 5e-300);
        assert!((length(&Vector3::new(3e300, 4e300, 0.0)) - 5e300).abs() < 1e286);
        assert_eq!(length(&Vector3::<f64>::zeros()), 0.0);
    }
}

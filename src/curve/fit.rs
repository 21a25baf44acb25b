//! Least-squares approximation of data points by a B-spline with fewer
//! control points, the end points interpolated (Piegl & Tiller, *The NURBS
//! Book*, §9.4.1).
//!
//! Notation: data points `Q₀ … Q_{M−1}` at centripetal parameters
//! `ū₀ = 0 < … < ū_{M−1} = 1` (as for
//! [`BSpline::interpolate`]), degree `p`, `C` control points
//! `P₀ … P_{C−1}`, `p < C ≤ M`. `P₀ = Q₀` and `P_{C−1} = Q_{M−1}`; the
//! inner points minimize `Σₖ |Qₖ − C(ūₖ)|²` over the inner data points,
//! `k = 1 … M − 2`: the normal equations `(NᵀN) P = R` with
//! `N_{k,i} = Nᵢ,ₚ(ūₖ)` (`i = 1 … C − 2`) and
//! `Rᵢ = Σₖ Nᵢ,ₚ(ūₖ) (Qₖ − N₀,ₚ(ūₖ) Q₀ − N_{C−1},ₚ(ūₖ) Q_{M−1})`, symmetric,
//! positive definite and banded (`p` diagonals on each side).
//!
//! The knots (eq. 9.69) place `p + 1` at 0 and at 1 and, with
//! `d = M/(C − p)`, `t_{p+j} = (1 − α) ū_{i−1} + α ū_i` where
//! `i = ⌊j d⌋`, `α = j d − i`, `j = 1 … C − p − 1`: every knot span holds
//! at least one parameter, which makes `NᵀN` non-singular.

use super::banded_solve::BandedMatrix;
use super::interpolate::{
    BasisScratch, basis_at, centripetal_parameters, check_degree_and_count, interpolate_at,
};
use super::validate_points;
use crate::{BSpline, Error};
use nalgebra::{Point, SVector};

/// The knots of the fit (Piegl & Tiller eq. 9.69) for `params.len() = M`
/// parameters, degree `p` and `C` control points (`p < C < M`).
fn fit_knots(degree: usize, params: &[f64], control_points: usize) -> Vec<f64> {
    let (p, m, c) = (degree, params.len(), control_points);
    let mut knots = Vec::with_capacity(c + p + 1);
    knots.extend(std::iter::repeat_n(0.0, p + 1));
    let den = c - p;
    for j in 1..c - p {
        // j·d = j·M/(C − p), split exactly into its integer part and rest.
        let num = j * m;
        let i = num / den;
        let alpha = (num % den) as f64 / den as f64;
        let t = (1.0 - alpha) * params[i - 1] + alpha * params[i];
        knots.push(t.clamp(0.0, 1.0));
    }
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    knots
}

impl<const D: usize> BSpline<D> {
    /// The clamped B-spline of degree `degree` with `control_points` control
    /// points that passes through the first and last point and fits the
    /// others in the least-squares sense (Piegl & Tiller §9.4.1).
    ///
    /// With `M` points `Q₀ … Q_{M−1}` and `C = control_points`:
    /// - parameters are centripetal, as for [`interpolate`](Self::interpolate)
    ///   (domain `[0, 1]`);
    /// - knots by the averaging of eq. 9.69: `p + 1` at 0 and at 1, and
    ///   with `d = M/(C − p)` the interior knots
    ///   `t_{p+j} = (1 − α) ū_{i−1} + α ū_i`, `i = ⌊j d⌋`, `α = j d − i`,
    ///   `j = 1 … C − p − 1`;
    /// - `P₀ = Q₀`, `P_{C−1} = Q_{M−1}` exactly, and the inner control points
    ///   minimize `Σₖ |Qₖ − C(ūₖ)|²` over the inner points (the banded normal
    ///   equations, solved by LU with partial pivoting).
    ///
    /// `C = M` is interpolation: the result is
    /// [`interpolate`](Self::interpolate)'s (its knots, eq. 9.8). Data on a
    /// spline the fit's knots can represent (e.g. a polynomial of degree at
    /// most `p`) are reproduced to rounding; the error falls as `C` grows.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// // 50 points on a quarter circle, fitted by a cubic with 6 control points.
    /// let points: Vec<Point2<f64>> = (0..50)
    ///     .map(|k| {
    ///         let a = std::f64::consts::FRAC_PI_2 * k as f64 / 49.0;
    ///         Point2::new(a.cos(), a.sin())
    ///     })
    ///     .collect();
    /// let curve = BSpline::fit(3, &points, 6)?;
    /// assert_eq!(curve.points().len(), 6);
    /// assert_eq!(curve.eval(0.0), points[0]);
    /// assert_eq!(curve.eval(1.0), points[49]);
    /// let error = curve.discretize(200).iter()
    ///     .map(|s| (s.point.coords.norm() - 1.0).abs())
    ///     .fold(0.0, f64::max);
    /// assert!(error < 2e-4, "{error}");
    /// // Twice the control points: a far closer fit.
    /// let finer = BSpline::fit(3, &points, 12)?;
    /// assert!(finer.discretize(200).iter().all(|s| (s.point.coords.norm() - 1.0).abs() < error / 10.0));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// In the order checked: [`Error::ZeroDegree`]; [`Error::TooFewPoints`]
    /// (fewer than `degree + 1` points); [`Error::TooFewControlPoints`]
    /// (`control_points ≤ degree`); [`Error::TooManyControlPoints`] (more
    /// control points than points); [`Error::NonFinitePoint`] or
    /// [`Error::CoordinateTooLarge`] with the index of the data point;
    /// [`Error::CoincidentPoints`] as for
    /// [`interpolate`](Self::interpolate); [`Error::SingularSystem`]
    /// (rounding only); then the errors of [`BSpline::new`] for the result
    /// ([`Error::KnotGapTooSmall`] only when nearly coincident points crowd
    /// the parameters).
    pub fn fit(
        degree: usize,
        points: &[Point<f64, D>],
        control_points: usize,
    ) -> Result<BSpline<D>, Error> {
        check_degree_and_count(degree, points.len())?;
        if control_points <= degree {
            return Err(Error::TooFewControlPoints {
                control_points,
                degree,
            });
        }
        if control_points > points.len() {
            return Err(Error::TooManyControlPoints {
                control_points,
                points: points.len(),
            });
        }
        validate_points(points)?;
        let params = centripetal_parameters(points)?;
        if control_points == points.len() {
            return interpolate_at(degree, points, &params);
        }
        let knots = fit_knots(degree, &params, control_points);
        let control = least_squares(degree, &knots, points, &params, control_points)?;
        BSpline::new(degree, knots, control)
    }
}

/// The control points of the fit: the ends are the data's, the inner ones
/// solve the normal equations.
fn least_squares<const D: usize>(
    degree: usize,
    knots: &[f64],
    points: &[Point<f64, D>],
    params: &[f64],
    control_points: usize,
) -> Result<Vec<Point<f64, D>>, Error> {
    let (p, c, m) = (degree, control_points, points.len());
    let (first, last) = (points[0].coords, points[m - 1].coords);
    // Unknowns P₁ … P_{C−2}, at 0 … C − 3.
    let unknowns = c - 2;
    let mut matrix = BandedMatrix::zeros(unknowns, p, p)?;
    let mut rhs = vec![SVector::<f64, D>::zeros(); unknowns];
    let mut scratch = BasisScratch::new(p);
    for k in 1..m - 1 {
        let span = basis_at(knots, p, c, params[k], &mut scratch);
        let values = &scratch.values;
        let index = |r: usize| span - p + r;
        // Rₖ: the data point less the parts of the fixed end points.
        let mut r_k = points[k].coords;
        for (r, &n) in values.iter().enumerate() {
            if index(r) == 0 {
                r_k -= first * n;
            } else if index(r) == c - 1 {
                r_k -= last * n;
            }
        }
        for (a, &na) in values.iter().enumerate() {
            let i = index(a);
            if i == 0 || i == c - 1 || na == 0.0 {
                continue;
            }
            rhs[i - 1] += r_k * na;
            for (b, &nb) in values.iter().enumerate() {
                let j = index(b);
                if j != 0 && j != c - 1 {
                    matrix.add(i - 1, j - 1, na * nb);
                }
            }
        }
    }
    matrix.factor()?;
    matrix.solve(&mut rhs);
    let mut control = Vec::with_capacity(c);
    control.push(points[0]);
    control.extend(rhs.into_iter().map(Point::from));
    control.push(points[m - 1]);
    Ok(control)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_knots_follow_the_formula() {
        // M = 7 parameters, degree 2, C = 5: d = 7/3.
        let params = [0.0, 0.1, 0.2, 0.4, 0.7, 0.9, 1.0];
        let knots = fit_knots(2, &params, 5);
        // j = 1: jd = 7/3, i = 2, α = 1/3; j = 2: jd = 14/3, i = 4, α = 2/3.
        let t1 = (2.0 / 3.0) * 0.1 + (1.0 / 3.0) * 0.2;
        let t2 = (1.0 / 3.0) * 0.4 + (2.0 / 3.0) * 0.7;
        let expect = [0.0, 0.0, 0.0, t1, t2, 1.0, 1.0, 1.0];
        for (a, b) in knots.iter().zip(expect) {
            assert!((a - b).abs() < 1e-16, "{knots:?}");
        }
        assert_eq!(knots.len(), expect.len());
    }
}

//! Degree reduction: a curve of degree one lower within a tolerance of the
//! original (`reduce_degree` on [`Bezier`] and [`BSpline`]), with a
//! rigorous bound on the distance.
//!
//! # Bézier curves
//! Of degree `n`, control points `P₀ … Pₙ`. A curve `Q` of degree `n − 1`
//! elevated to degree `n` has the points `(EQ)ᵢ = (i/n)·Qᵢ₋₁ + (1 − i/n)·Qᵢ`
//! (Farin), and since both are then degree-`n` Bézier curves,
//!
//! ```text
//! |P(t) − Q(t)| = |Σᵢ Bᵢⁿ(t)·(Pᵢ − (EQ)ᵢ)| ≤ maxᵢ |Pᵢ − (EQ)ᵢ|
//! ```
//!
//! (the Bernstein weights are non-negative and sum to one). `Q` keeps the
//! end points (`Q₀ = P₀`, `Qₙ₋₁ = Pₙ`, so that pieces of a spline stay
//! joined) and its inner points minimize `Σᵢ |Pᵢ − (EQ)ᵢ|²`: a tridiagonal,
//! symmetric positive definite system (each row of `E` has two neighbouring
//! non-zeros), solved by elimination without pivoting. A curve that is an
//! elevation comes back exactly (to rounding). The bound, with the
//! rounding of its computation added, is what the tolerance is held to.
//!
//! # Splines
//! Each Bézier piece is reduced as above (ends kept: the pieces join, a
//! spline with every interior knot of multiplicity `n − 1`), a piece whose
//! bound exceeds the tolerance halved (de Casteljau) until its parts'
//! bounds are within it (the bound falls as the part's length to the
//! power `n`); then each
//! interior knot is removed as often as the remaining tolerance allows
//! ([`BSpline::remove_knot`]). A removal changes the curve by at most the
//! largest change of the control points whose basis functions are non-zero
//! there (the removed knot inserted back, the control points compared), so
//! a bound on the distance to the joined pieces is kept piece by piece; a
//! removal that would take a piece's bound plus the reduction's over the
//! tolerance is refused.

use super::check_tolerance;
use crate::bernstein::elevate_degree;
use crate::{BSpline, Bezier, Curve, Error};
use nalgebra::{Point, SVector};

/// The reduced points and the bound `maxᵢ |Pᵢ − (EQ)ᵢ|` (with rounding).
fn reduce_points<const D: usize>(p: &[Point<f64, D>]) -> (Vec<Point<f64, D>>, f64) {
    let n = p.len() - 1;
    let m = n - 1;
    let nf = n as f64;
    // (EQ)ᵢ = a(i)·Qᵢ₋₁ + b(i)·Qᵢ.
    let a = |i: usize| i as f64 / nf;
    let b = |i: usize| (n - i) as f64 / nf;
    let mut q: Vec<SVector<f64, D>> = vec![SVector::zeros(); m + 1];
    q[0] = p[0].coords;
    q[m] = p[n].coords;
    // Free unknowns Q₁ … Q_{m−1}: row j is
    // a(j)b(j)·Qⱼ₋₁ + (b(j)² + a(j+1)²)·Qⱼ + a(j+1)b(j+1)·Qⱼ₊₁
    //   = b(j)·Pⱼ + a(j+1)·Pⱼ₊₁.
    if m >= 2 {
        let free = m - 1;
        let mut diag = vec![0.0; free];
        let mut upper = vec![0.0; free];
        let mut rhs: Vec<SVector<f64, D>> = vec![SVector::zeros(); free];
        for k in 0..free {
            let j = k + 1;
            diag[k] = b(j) * b(j) + a(j + 1) * a(j + 1);
            upper[k] = a(j + 1) * b(j + 1);
            rhs[k] = p[j].coords * b(j) + p[j + 1].coords * a(j + 1);
        }
        rhs[0] -= q[0] * (a(1) * b(1));
        rhs[free - 1] -= q[m] * (a(m) * b(m));
        // Forward elimination (the lower diagonal equals the upper one,
        // shifted: row k's is a(k+1)b(k+1) = upper[k − 1]).
        for k in 1..free {
            let factor = upper[k - 1] / diag[k - 1];
            diag[k] -= factor * upper[k - 1];
            let previous = rhs[k - 1];
            rhs[k] -= previous * factor;
        }
        for k in (0..free).rev() {
            let next = if k + 1 < free {
                q[k + 2] * upper[k]
            } else {
                SVector::zeros()
            };
            q[k + 1] = (rhs[k] - next) / diag[k];
        }
    }
    let magnitude = p.iter().map(|x| x.coords.amax()).fold(0.0_f64, f64::max);
    let bound = elevate_degree(&q, 1)
        .iter()
        .zip(p)
        .map(|(e, pi)| (pi.coords - e).norm())
        .fold(0.0_f64, f64::max);
    // The elevation, differences and norm of the check err by a few ε of
    // the largest coordinate; the reduced points can exceed the original
    // ones by the condition of the system (below 4 for these weights).
    let q_magnitude = q.iter().map(|x| x.amax()).fold(0.0_f64, f64::max);
    let rounding = 8.0 * (D as f64 + 2.0) * f64::EPSILON * magnitude.max(q_magnitude);
    (q.into_iter().map(Point::from).collect(), bound + rounding)
}

/// [`Error::DegreeTooLowToReduce`] below degree 2.
fn check_reducible(degree: usize) -> Result<(), Error> {
    if degree < 2 {
        Err(Error::DegreeTooLowToReduce { degree })
    } else {
        Ok(())
    }
}

impl<const D: usize> Bezier<D> {
    /// The Bézier curve of degree `n − 1` within `tolerance` of this one
    /// everywhere, keeping both end points (least squares on the control
    /// points of its elevation; the method and the bound are in the
    /// `curve::reduce` module docs). An elevated curve comes back exactly
    /// (to rounding).
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let cubic = Bezier::new(vec![
    ///     Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0),
    /// ])?;
    /// let raised = cubic.elevate_degree(2)?;
    /// let back = raised.reduce_degree(1e-12)?.reduce_degree(1e-12)?;
    /// for (p, q) in back.points().iter().zip(cubic.points()) {
    ///     assert!((p - q).norm() < 1e-14);
    /// }
    /// // A true cubic is not within 1e-3 of any quadratic.
    /// let s = Bezier::new(vec![
    ///     Point2::new(0.0, 0.0), Point2::new(1.0, 1.0), Point2::new(2.0, -1.0), Point2::new(3.0, 0.0),
    /// ])?;
    /// assert!(s.reduce_degree(1e-3).is_err());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; [`Error::DegreeTooLowToReduce`] below degree 2 (a line
    /// would lose an end point); [`Error::ReductionInexact`] with the bound
    /// reached when it exceeds `tolerance`.
    pub fn reduce_degree(&self, tolerance: f64) -> Result<Bezier<D>, Error> {
        check_tolerance(tolerance)?;
        check_reducible(self.degree())?;
        let (q, bound) = reduce_points(self.points());
        if bound.is_nan() || bound > tolerance {
            return Err(Error::ReductionInexact {
                deviation: bound,
                tolerance,
            });
        }
        Bezier::new(q)
    }
}

impl<const D: usize> BSpline<D> {
    /// The B-spline of degree `p − 1` within `tolerance` of this one
    /// everywhere on its domain, with as few knots as the tolerance allows
    /// (each Bézier piece reduced with its ends kept, halved where its
    /// bound exceeds the tolerance, then interior knots removed while the
    /// bound holds; see the `curve::reduce` module docs). The domain is
    /// kept.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let quadratic = BSpline::clamped(2, vec![
    ///     Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0),
    ///     Point2::new(4.0, 0.0), Point2::new(6.0, 1.0),
    /// ])?;
    /// let cubic = quadratic.elevate_degree(1)?;
    /// let back = cubic.reduce_degree(1e-12)?;
    /// assert_eq!(back.degree(), 2);
    /// assert_eq!(back.knots(), quadratic.knots());
    /// assert!((back.eval(0.3) - quadratic.eval(0.3)).norm() < 1e-13);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`]; [`Error::DegreeTooLowToReduce`] below
    /// degree 2; [`Error::ReductionInexact`] with the bound of a part
    /// halved 20 times and still not within `tolerance`, or when the whole
    /// would need more than 1024 parts (a tolerance near the rounding of
    /// the curve's coordinates); the errors of [`BSpline::new`] for the
    /// result.
    pub fn reduce_degree(&self, tolerance: f64) -> Result<BSpline<D>, Error> {
        check_tolerance(tolerance)?;
        let p = self.degree();
        check_reducible(p)?;
        let m = p - 1;
        let spans = self.bezier_spans().ok_or(Error::NotPiecewisePolynomial)?;
        let mut pieces = Vec::with_capacity(spans.len());
        let mut reduction = 0.0_f64;
        for span in &spans {
            reduction = reduction.max(reduce_piece(
                &span.curve,
                span.knots,
                tolerance,
                0,
                &mut pieces,
            )?);
        }
        let mut points: Vec<Point<f64, D>> = Vec::with_capacity(pieces.len() * m + 1);
        let mut knots: Vec<f64> = Vec::with_capacity((pieces.len() + 1) * m + 2);
        for (k, (start, q)) in pieces.iter().enumerate() {
            let skip = usize::from(k > 0);
            points.extend_from_slice(&q[skip..]);
            let copies = if k == 0 { m + 1 } else { m };
            knots.extend(std::iter::repeat_n(*start, copies));
        }
        let end = spans.last().map_or(self.domain().1, |s| s.knots.1);
        knots.extend(std::iter::repeat_n(end, m + 1));
        let joined = BSpline::new(m, knots, points)?;
        let budget = tolerance - reduction;
        let breaks: Vec<f64> = pieces.iter().skip(1).map(|(start, _)| *start).collect();
        // dev[k]: a bound on |current − joined| over the joined spline's
        // piece k, kept as knots are removed.
        let mut bounds: Vec<f64> = pieces.iter().map(|(start, _)| *start).collect();
        bounds.push(end);
        let mut dev = vec![0.0_f64; pieces.len()];
        let magnitude = joined
            .points()
            .iter()
            .map(|x| x.coords.amax())
            .fold(0.0_f64, f64::max);
        let rounding = 16.0 * f64::EPSILON * magnitude;
        let mut current = joined;
        let mut step = vec![0.0_f64; pieces.len()];
        for &t in &breaks {
            let Ok((candidate, removed)) = current.remove_knot(t, m, budget) else {
                continue;
            };
            if removed == 0 {
                continue;
            }
            let Some(()) = removal_steps(&current, &candidate, t, removed, &bounds, &mut step)
            else {
                continue;
            };
            let fits = dev
                .iter()
                .zip(&step)
                .all(|(d, s)| *s == 0.0 || d + s + rounding <= budget);
            if fits {
                for (d, s) in dev.iter_mut().zip(&step) {
                    if *s > 0.0 {
                        *d += s + rounding;
                    }
                }
                current = candidate;
            }
        }
        Ok(current)
    }
}

/// Halvings of a piece at most before reduction gives up.
const MAX_HALVINGS: usize = 20;

/// Parts of the whole spline at most (`2¹⁰`) before reduction gives up: the
/// knot removal that follows costs the square of their number.
const MAX_PARTS: usize = 1 << 10;

/// Appends the reduced parts of `piece` (over `knots`) to `out`, each with
/// the start of its knot interval: the whole piece if its bound is within
/// `tolerance`, else its two halves, recursively. Returns the largest
/// bound.
fn reduce_piece<const D: usize>(
    piece: &Bezier<D>,
    (a, b): (f64, f64),
    tolerance: f64,
    depth: usize,
    out: &mut Vec<(f64, Vec<Point<f64, D>>)>,
) -> Result<f64, Error> {
    let (q, bound) = reduce_points(piece.points());
    let mid = 0.5 * (a + b);
    if bound <= tolerance && out.len() < MAX_PARTS {
        out.push((a, q));
        return Ok(bound);
    }
    if depth >= MAX_HALVINGS || out.len() >= MAX_PARTS || !(a < mid && mid < b) {
        return Err(Error::ReductionInexact {
            deviation: bound,
            tolerance,
        });
    }
    let (left, right) = piece.subdivide(0.5)?;
    let l = reduce_piece(&left, (a, mid), tolerance, depth + 1, out)?;
    let r = reduce_piece(&right, (mid, b), tolerance, depth + 1, out)?;
    Ok(l.max(r))
}

/// The change that removing `t` (`removed` times) from `current` makes,
/// piece by piece: `candidate` with `t` inserted back has `current`'s knots,
/// and `|candidate(x) − current(x)| ≤ max |ΔPᵢ|` over the control points
/// whose basis functions are non-zero at `x` (`Nᵢ` lives on
/// `[tᵢ, tᵢ₊ₘ₊₁]`). Writes, for each piece `[bounds[k], bounds[k+1]]`, that
/// maximum to `step[k]` (zero where nothing changes); `None` if the knots
/// do not line up.
fn removal_steps<const D: usize>(
    current: &BSpline<D>,
    candidate: &BSpline<D>,
    t: f64,
    removed: usize,
    bounds: &[f64],
    step: &mut [f64],
) -> Option<()> {
    let back = candidate.insert_knot(t, removed).ok()?;
    let knots = current.knots();
    if back.knots() != knots {
        return None;
    }
    let m = current.degree();
    step.iter_mut().for_each(|s| *s = 0.0);
    for (i, (a, b)) in back.points().iter().zip(current.points()).enumerate() {
        let d = (a - b).norm();
        if d == 0.0 {
            continue;
        }
        let (lo, hi) = (knots[i], knots[i + m + 1]);
        // Pieces meeting the open support (lo, hi).
        let first = bounds.partition_point(|&x| x <= lo).saturating_sub(1);
        let last = bounds.partition_point(|&x| x < hi).min(step.len());
        for s in &mut step[first..last] {
            *s = s.max(d);
        }
    }
    Some(())
}

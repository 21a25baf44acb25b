//! Knot removal within a tolerance ([`BSpline::remove_knot`],
//! [`Nurbs::remove_knot`]): the inverse of knot insertion, in the spirit of
//! Piegl & Tiller's algorithm A5.8 (*The NURBS Book*, §5.4), with the
//! acceptance test replaced by a rigorous bound on the distance between
//! the curves.
//!
//! # One removal
//! Removing one copy of the knot `u` from the knot vector `U` gives `U′`;
//! inserting `u` into `U′` maps the unknown control points `Q` to the known
//! `P` by Boehm's equations `Pⱼ = (1 − αⱼ)Qⱼ₋₁ + αⱼQⱼ` (the others copied).
//! With `s` the multiplicity of `u` in `U′`, `p − s − 1` points of `Q` are
//! unknown and `p − s` equations involve them: the unknowns are solved from the left
//! (`Qⱼ = (Pⱼ − (1 − αⱼ)Qⱼ₋₁)/αⱼ`) up to the middle and from the right
//! (`Qⱼ₋₁ = (Pⱼ − αⱼQⱼ)/(1 − αⱼ)`) down to it; one equation is left over,
//! and it holds exactly when the knot is removable exactly. For a NURBS the
//! same runs on the homogeneous points `(wP, w)`.
//!
//! # The deviation bound
//! A candidate is accepted only if it stays within the tolerance of the
//! original curve everywhere. To check, `u` is inserted back into the
//! candidate as many times as it was removed, which gives the original's
//! knot vector; on one knot vector two B-splines differ by the B-spline of
//! the control points' differences, so by the partition of unity
//! `max |C(t) − C′(t)| ≤ maxᵢ |Pᵢ − P′ᵢ|`. For a NURBS with weights `wᵢ`
//! (original) and `vᵢ` (candidate re-inserted), shifted to the center `c`
//! of the control points' box,
//! `|C − C′| ≤ (maxᵢ |wᵢ(Pᵢ − c) − vᵢ(P′ᵢ − c)| + R·maxᵢ |wᵢ − vᵢ|) / minᵢ wᵢ`
//! with `R = maxᵢ |P′ᵢ − c|` (the candidate lies in its control points'
//! hull, and the original's denominator is at least the smallest weight).
//! Both bounds are rigorous for the exact re-inserted points; the
//! re-insertion's own rounding (a few `ε` times the coordinates) is not
//! added.

use super::check_tolerance;
use super::knots::min_knot_gap;
use super::{Homogeneous, scaled_norm};
use crate::bernstein::Coefficient;
use crate::{BSpline, Curve, Error, Nurbs};
use nalgebra::{Point, SVector};

/// The knot vector and control values after removing one copy of `u`
/// (an interior knot of `knots`), by the two-sided solve of the module
/// docs; `None` when a division is degenerate.
fn remove_once<T: Coefficient>(
    knots: &[f64],
    p: usize,
    control: &[T],
    u: f64,
) -> Option<(Vec<f64>, Vec<T>)> {
    let first = knots.iter().position(|&k| k == u)?;
    let mut reduced = knots.to_vec();
    reduced.remove(first);
    let s = reduced.iter().filter(|&&k| k == u).count();
    // The span of `reduced` where `u` would be inserted: last index with
    // knot ≤ u.
    let k = reduced.partition_point(|&x| x <= u).checked_sub(1)?;
    if k < p || s > p {
        return None;
    }
    let alpha = |j: usize| (u - reduced[j]) / (reduced[j + p] - reduced[j]);
    let n = control.len();
    // Inserting u into `reduced` (where it has multiplicity s, at indices
    // k − s + 1 ..= k, so αⱼ = 0 there): Pⱼ = Qⱼ for j ≤ k − p,
    // Pⱼ = (1 − αⱼ)Qⱼ₋₁ + αⱼQⱼ for k − p < j ≤ k − s, Pⱼ = Qⱼ₋₁ beyond. So
    // Q has n − 1 values: Qⱼ = Pⱼ for j ≤ k − p, Qⱼ = Pⱼ₊₁ for j ≥ k − s,
    // and p − s − 1 unknowns between (for s = p, none: P_{k−p+1} should
    // repeat P_{k−p}, and is dropped).
    let mut q: Vec<T> = Vec::with_capacity(n - 1);
    q.extend_from_slice(&control[..=k - p]);
    let lo = k - p + 1; // first unknown
    let count = (p - s).saturating_sub(1); // unknowns lo ..= lo + count − 1
    q.extend(std::iter::repeat_n(control[0], count));
    q.extend_from_slice(&control[(k - s + 1).max(lo + 1)..]);
    if q.len() != n - 1 {
        return None;
    }
    if count > 0 {
        let hi = lo + count - 1;
        let mid = lo + (count - 1) / 2;
        for j in lo..=mid {
            let a = alpha(j);
            if a.is_nan() || a <= 0.0 {
                return None;
            }
            q[j] = (control[j] - q[j - 1] * (1.0 - a)) * (1.0 / a);
        }
        for j in (mid + 2..=hi + 1).rev() {
            let a = alpha(j);
            if a.is_nan() || a >= 1.0 {
                return None;
            }
            q[j - 1] = (control[j] - q[j] * a) * (1.0 / (1.0 - a));
        }
    }
    Some((reduced, q))
}

/// The knot `t` as it is in `knots` (an exact match, or the knot within
/// rounding, `4ε ×` the knot range), if it is an interior knot of the
/// domain `(a, b)`.
fn interior_knot(knots: &[f64], domain: (f64, f64), t: f64) -> Result<f64, Error> {
    let gap = min_knot_gap(knots);
    knots
        .iter()
        .copied()
        .find(|&k| k == t || (k - t).abs() < gap)
        .filter(|&k| k > domain.0 && k < domain.1)
        .ok_or(Error::NotAnInteriorKnot { t })
}

impl<const D: usize> BSpline<D> {
    /// The curve with the interior knot `t` removed up to `times` times,
    /// as long as the result stays within `tolerance` of this curve
    /// everywhere on the domain; returns the curve and how many times the
    /// knot was removed (`0` gives a copy of this curve).
    ///
    /// Each removal inverts Boehm's insertion from both sides (see the
    /// `curve::knot_removal` module docs) and is accepted when the rigorous
    /// bound `maxᵢ |Pᵢ − P′ᵢ|` on the distance to the original (the
    /// candidate with `t` inserted back, on the original knots) is at most
    /// `tolerance`; the first refused removal ends the loop. The domain and
    /// the degree are kept; a knot that is essential (the curve is not
    /// that smooth there) is not removed.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let c = BSpline::clamped(3, vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0), Point2::new(5.0, 1.0)])?;
    /// let refined = c.insert_knot(0.3, 2)?;
    /// let (back, removed) = refined.remove_knot(0.3, 2, 1e-12)?;
    /// assert_eq!(removed, 2);
    /// assert_eq!(back.knots(), c.knots());
    /// assert!((back.eval(0.7) - c.eval(0.7)).norm() < 1e-13);
    /// // The knot 0.5 of the original is essential: nothing is removed.
    /// assert_eq!(c.remove_knot(0.5, 1, 1e-6)?.1, 0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; [`Error::NotAnInteriorKnot`] unless `t` is a knot strictly
    /// inside the domain (NaN included).
    pub fn remove_knot(
        &self,
        t: f64,
        times: usize,
        tolerance: f64,
    ) -> Result<(BSpline<D>, usize), Error> {
        check_tolerance(tolerance)?;
        let u = interior_knot(self.knots(), self.domain(), t)?;
        let p = self.degree();
        let mut current = self.clone();
        let mut removed = 0;
        while removed < times {
            let coords: Vec<SVector<f64, D>> = current.points().iter().map(|x| x.coords).collect();
            let Some((knots, q)) = remove_once(current.knots(), p, &coords, u) else {
                break;
            };
            let points = q.into_iter().map(Point::from).collect();
            let Ok(candidate) = BSpline::new(p, knots, points) else {
                break;
            };
            let Ok(back) = candidate.insert_knot(u, removed + 1) else {
                break;
            };
            if back.knots() != self.knots() {
                break;
            }
            let deviation = back
                .points()
                .iter()
                .zip(self.points())
                .fold(0.0_f64, |m, (a, b)| m.max(scaled_norm(a - b)));
            if deviation.is_nan() || deviation > tolerance {
                break;
            }
            current = candidate;
            removed += 1;
        }
        Ok((current, removed))
    }
}

impl<const D: usize> Nurbs<D> {
    /// The curve with the interior knot `t` removed up to `times` times
    /// within `tolerance` of this curve everywhere, as
    /// [`BSpline::remove_knot`]: the removal runs on the homogeneous points
    /// `(wP, w)`, and a candidate is accepted when the rigorous bound
    /// `(maxᵢ |wᵢ(Pᵢ − c) − vᵢ(P′ᵢ − c)| + R·maxᵢ |wᵢ − vᵢ|) / minᵢ wᵢ` of the
    /// `curve::knot_removal` module docs is at most `tolerance` (and its
    /// weights are positive). Returns the curve and the number of removals.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let refined = circle.insert_knot(0.1, 1)?;
    /// let (back, removed) = refined.remove_knot(0.1, 1, 1e-12)?;
    /// assert_eq!(removed, 1);
    /// assert_eq!(back.points().len(), circle.points().len());
    /// // The circle's double knots at the quarters are essential.
    /// assert_eq!(circle.remove_knot(0.25, 1, 1e-3)?.1, 0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::remove_knot`].
    pub fn remove_knot(
        &self,
        t: f64,
        times: usize,
        tolerance: f64,
    ) -> Result<(Nurbs<D>, usize), Error> {
        check_tolerance(tolerance)?;
        let u = interior_knot(self.knots(), self.domain(), t)?;
        let p = self.degree();
        let (lo, hi) = self.bounds();
        let center = lo.coords * 0.5 + hi.coords * 0.5;
        let min_weight = self.weights().iter().fold(f64::INFINITY, |m, &w| m.min(w));
        let mut current = self.clone();
        let mut removed = 0;
        while removed < times {
            let h: Vec<Homogeneous<D>> = current
                .points()
                .iter()
                .zip(current.weights())
                .map(|(x, &w)| Homogeneous::new(&Point::from(x.coords - center), w))
                .collect();
            let Some((knots, q)) = remove_once(current.knots(), p, &h, u) else {
                break;
            };
            if !q.iter().all(|x| x.w > 0.0) {
                break;
            }
            let points = q.iter().map(|x| Point::from(x.wp / x.w + center)).collect();
            let weights = q.iter().map(|x| x.w).collect();
            let Ok(candidate) = Nurbs::new(p, knots, points, weights) else {
                break;
            };
            let Ok(back) = candidate.insert_knot(u, removed + 1) else {
                break;
            };
            if back.knots() != self.knots() {
                break;
            }
            let mut da = 0.0_f64;
            let mut dw = 0.0_f64;
            let mut radius = 0.0_f64;
            for ((q, &v), (x, &w)) in back
                .points()
                .iter()
                .zip(back.weights())
                .zip(self.points().iter().zip(self.weights()))
            {
                let a = (x.coords - center) * w - (q.coords - center) * v;
                da = da.max(scaled_norm(a));
                dw = dw.max((w - v).abs());
                radius = radius.max(scaled_norm(q.coords - center));
            }
            let deviation = (da + radius * dw) / min_weight;
            if deviation.is_nan() || deviation > tolerance {
                break;
            }
            current = candidate;
            removed += 1;
        }
        Ok((current, removed))
    }
}

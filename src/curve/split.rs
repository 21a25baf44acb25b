//! Splitting a curve at a parameter into two curves, exactly: de Casteljau
//! subdivision for the Bézier kinds, knot insertion to full multiplicity for
//! the splines (Piegl & Tiller, *The NURBS Book*, §5.2 and §5.3).
//!
//! # Domains of the halves
//! - [`BSpline`] and [`Nurbs`]: the halves keep the original parameters, the
//!   left one on `[a, t]`, the right one on `[t, b]`; `left.eval(s)` is the
//!   curve at `s` for `s ≤ t` (to rounding), `right.eval(s)` for `s ≥ t`.
//! - [`Bezier`] and [`RationalBezier`]: a Bézier curve is always on
//!   `[0, 1]`, so the halves are reparametrized: `left(s) = C(t·s)` and
//!   `right(s) = C(t + (1 − t)·s)` for `s ∈ [0, 1]`.
//!
//! In all cases both halves have the curve's degree; the left one starts at
//! the curve's start point, the right one ends at its end point, and they
//! meet at `C(t)` (exactly: the same control point ends one and starts the
//! other).

use super::homogeneous::project;
use super::knots::knot_to_insert;
use super::{Homogeneous, check_in_domain, clamp_to_box, point_bounds};
use crate::bernstein::subdivide;
use crate::{BSpline, Bezier, Curve, Error, Nurbs, RationalBezier};
use nalgebra::Point;

/// Checks that `t` is a number strictly inside `domain`.
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] for NaN or `t` outside `[a, b]`;
/// [`Error::SplitAtDomainEnd`] for `t = a` or `t = b`.
fn check_interior(t: f64, domain: (f64, f64)) -> Result<(), Error> {
    check_in_domain(t, domain)?;
    if t == domain.0 || t == domain.1 {
        return Err(Error::SplitAtDomainEnd { t, domain });
    }
    Ok(())
}

/// The knots and control values of one piece of a spline.
type Half<T> = (Vec<f64>, Vec<T>);

/// The knots and control values of the two halves of a spline of degree `p`
/// split at `t`, where `t` occurs at least `p` times in `knots` (or is not
/// a knot when `p = 0`).
///
/// With `r` the index of the first knot `≥ t` and `m` the multiplicity of
/// `t`, the left half has the knots before `r` then `t` repeated `p + 1`
/// times and the first `r` control values; the right half `t` repeated
/// `p + 1` times then the knots after the run of `t`, and the control values
/// from index `r + m − p − 1` (for `m = p` the point `C(t)`, shared with the
/// left half; for a jump, `m = p + 1`, the limit from the right).
fn split_parts<T: Copy>(knots: &[f64], p: usize, control: &[T], t: f64) -> (Half<T>, Half<T>) {
    let r = knots.partition_point(|&k| k < t);
    let m = knots[r..].iter().take_while(|&&k| k == t).count();
    let mut left_knots = knots[..r].to_vec();
    left_knots.extend(std::iter::repeat_n(t, p + 1));
    let left = control[..r].to_vec();
    let mut right_knots = vec![t; p + 1];
    right_knots.extend_from_slice(&knots[r + m..]);
    let right = control[r + m - p - 1..].to_vec();
    ((left_knots, left), (right_knots, right))
}

/// The parameter `t` as knot insertion would use it (snapped to a knot
/// within rounding), checked to be strictly inside `domain`, with the
/// number of insertions that bring its multiplicity to `p`.
fn spline_split_parameter(
    knots: &[f64],
    p: usize,
    dom: (f64, f64),
    t: f64,
) -> Result<(f64, usize), Error> {
    check_interior(t, dom)?;
    let snapped = knot_to_insert(knots, p, dom, t, 0)?;
    check_interior(snapped, dom).map_err(|_| Error::SplitAtDomainEnd { t, domain: dom })?;
    let m = knots.iter().filter(|&&k| k == snapped).count();
    Ok((snapped, p.saturating_sub(m)))
}

impl<const D: usize> Bezier<D> {
    /// The two halves of the curve at `t ∈ (0, 1)`, by de Casteljau
    /// subdivision: `left(s) = C(t·s)` and `right(s) = C(t + (1 − t)·s)`,
    /// `s ∈ [0, 1]` (both halves are Bézier curves on `[0, 1]`, so they are
    /// reparametrized). Both have this curve's
    /// degree; `left` starts at `P₀`, `right` ends at `Pₙ`, and they meet at
    /// `C(t)`. The halves' control points are convex combinations of this
    /// curve's, kept in its bounding box.
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 0.0)])?;
    /// let (left, right) = c.split(0.25)?;
    /// assert_eq!(left.points()[2], right.points()[0]);
    /// assert!((left.eval(0.5) - c.eval(0.125)).norm() < 1e-15);
    /// assert!((right.eval(0.5) - c.eval(0.625)).norm() < 1e-15);
    /// assert!(c.split(1.0).is_err());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside `[0, 1]`;
    /// [`Error::SplitAtDomainEnd`] for `t = 0` or `t = 1`;
    /// [`Error::DerivativeOverflow`] as [`subdivide`](Self::subdivide).
    pub fn split(&self, t: f64) -> Result<(Self, Self), Error> {
        check_interior(t, (0.0, 1.0))?;
        self.subdivide(t)
    }
}

impl<const D: usize> RationalBezier<D> {
    /// The two halves of the curve at `t ∈ (0, 1)`: de Casteljau
    /// subdivision of the homogeneous points `(wᵢPᵢ, wᵢ)`, then projection.
    /// As for [`Bezier::split`], `left(s) = C(t·s)` and
    /// `right(s) = C(t + (1 − t)·s)` on `[0, 1]` (reparametrized); both have
    /// this curve's degree, and they meet at `C(t)`. The new points are kept
    /// in this curve's control-point box and the new weights between its
    /// smallest and largest.
    ///
    /// ```
    /// use revolve::{Curve, RationalBezier};
    /// use revolve::nalgebra::Point2;
    ///
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let quarter = RationalBezier::new(
    ///     vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(0.0, 1.0)],
    ///     vec![1.0, h, 1.0],
    /// )?;
    /// let (left, right) = quarter.split(0.5)?;
    /// // Each half is still on the unit circle.
    /// for k in 0..=10 {
    ///     let s = k as f64 / 10.0;
    ///     assert!((left.eval(s).coords.norm() - 1.0).abs() < 1e-15);
    ///     assert!((right.eval(s) - quarter.eval(0.5 + 0.5 * s)).norm() < 1e-15);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside `[0, 1]`;
    /// [`Error::SplitAtDomainEnd`] for `t = 0` or `t = 1`; the errors of
    /// [`RationalBezier::new`] for a half (only for curves at its limits).
    pub fn split(&self, t: f64) -> Result<(Self, Self), Error> {
        check_interior(t, (0.0, 1.0))?;
        let hull = point_bounds(self.points());
        let (w_lo, w_hi) = self
            .weights()
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &w| {
                (lo.min(w), hi.max(w))
            });
        // Scaled by a power of two so that the largest weight is near 1.
        let scale = super::power_of_two_near(w_hi);
        let h: Vec<Homogeneous<D>> = self
            .points()
            .iter()
            .zip(self.weights())
            .map(|(p, &w)| Homogeneous::new(p, w / scale))
            .collect();
        let mut left = h.clone();
        let mut right = h.clone();
        subdivide(&h, t, &mut left, &mut right);
        let half = |hs: Vec<Homogeneous<D>>| {
            let (points, weights): (Vec<_>, Vec<_>) = hs
                .into_iter()
                .map(|x| {
                    let p = Point::from(clamp_to_box(project(x).coords, hull));
                    (p, (x.w * scale).clamp(w_lo, w_hi))
                })
                .unzip();
            RationalBezier::new(points, weights)
        };
        Ok((half(left)?, half(right)?))
    }
}

impl<const D: usize> BSpline<D> {
    /// The two halves of the curve at `t`, strictly inside the domain
    /// `[a, b]`: `t` is inserted until it has multiplicity `p` (Boehm's
    /// algorithm, as [`insert_knot`](Self::insert_knot), so a `t` within
    /// rounding of a knot is that knot), then the knots and control points
    /// are cut there. The halves keep the original parameters: the left one
    /// is the curve on `[a, t]`, the right one on `[t, b]`, both of degree
    /// `p`, both clamped at `t` (the knot `t` repeated `p + 1` times) and the
    /// other end as the curve's. They meet at `C(t)`; at a knot of full
    /// multiplicity (a jump) the left half ends at the limit from the left
    /// and the right half starts at the limit from the right.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0), Point2::new(5.0, 1.0)];
    /// let c = BSpline::clamped(3, pts)?;
    /// let (left, right) = c.split(0.3)?;
    /// assert_eq!(left.domain(), (0.0, 0.3));
    /// assert_eq!(right.domain(), (0.3, 1.0));
    /// assert!((left.eval(0.1) - c.eval(0.1)).norm() < 1e-14);
    /// assert!((right.eval(0.8) - c.eval(0.8)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside the domain;
    /// [`Error::SplitAtDomainEnd`] for `t` at (or within rounding of) an
    /// end of the domain; the errors of [`insert_knot`](Self::insert_knot)
    /// and [`new`](Self::new) (only for curves at their limits).
    pub fn split(&self, t: f64) -> Result<(Self, Self), Error> {
        let p = self.degree();
        let (t, times) = spline_split_parameter(self.knots(), p, self.domain(), t)?;
        let refined = self.insert_knot(t, times)?;
        let ((lk, lp), (rk, rp)) = split_parts(refined.knots(), p, refined.points(), t);
        Ok((BSpline::new(p, lk, lp)?, BSpline::new(p, rk, rp)?))
    }
}

impl<const D: usize> Nurbs<D> {
    /// The two halves of the curve at `t`, strictly inside the domain, as
    /// [`BSpline::split`]: knot insertion to multiplicity `p` on the
    /// homogeneous points, then a cut; the halves keep the original
    /// parameters (left on `[a, t]`, right on `[t, b]`), the degree, and
    /// the weights of the refined curve.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 2.0)?;
    /// let (left, right) = circle.split(0.4)?;
    /// assert_eq!(left.domain(), (0.0, 0.4));
    /// assert_eq!(right.domain(), (0.4, 1.0));
    /// assert!((left.eval(0.2) - circle.eval(0.2)).norm() < 1e-14);
    /// assert!((right.eval(0.7).coords.norm() - 2.0).abs() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BSpline::split`], and the weight errors of
    /// [`new`](Self::new) (only for curves at their limits).
    pub fn split(&self, t: f64) -> Result<(Self, Self), Error> {
        let p = self.degree();
        let (t, times) = spline_split_parameter(self.knots(), p, self.domain(), t)?;
        let refined = self.insert_knot(t, times)?;
        let control: Vec<(Point<f64, D>, f64)> = refined
            .points()
            .iter()
            .copied()
            .zip(refined.weights().iter().copied())
            .collect();
        let ((lk, lc), (rk, rc)) = split_parts(refined.knots(), p, &control, t);
        let (lp, lw) = lc.into_iter().unzip();
        let (rp, rw) = rc.into_iter().unzip();
        Ok((Nurbs::new(p, lk, lp, lw)?, Nurbs::new(p, rk, rp, rw)?))
    }
}

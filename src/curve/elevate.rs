//! Degree elevation: the same curve written with a higher degree
//! (`elevate_degree` on [`Bezier`], [`RationalBezier`], [`BSpline`] and
//! [`Nurbs`]).
//!
//! A polynomial of degree `n` is also one of degree `n + k`. Its Bernstein
//! coefficients of degree `n + k` come from Farin's formula (the kernel
//! `bernstein::elevate_degree`): convex combinations of the old ones, so the
//! computation is stable and the new points stay in the old points' box.
//! Rational curves are elevated on their homogeneous points, then divided.
//!
//! Splines are elevated by blossoming the elevated Bézier pieces at the new
//! knots: the method, and why it was chosen over knot removal, are in the
//! docs of [`BSpline::elevate_degree`].

use super::homogeneous::{homogeneous_points, max_weight, weight_scale};
use super::knots::{nonempty_spans, span_bezier_points};
use super::{clamp_to_box, point_bounds};
use crate::allocation::try_with_capacity;
use crate::bernstein::{Coefficient, elevate_degree, lerp};
use crate::scratch::with_scratch;
use crate::{BSpline, Bezier, Curve, Error, Nurbs, RationalBezier};
use nalgebra::{Point, SVector};

/// The largest degree that degree elevation produces (`64`); asking for
/// more is [`Error::ElevationTooHigh`]. Elevating by zero is always allowed
/// (it returns a copy), whatever the degree.
pub const MAX_ELEVATED_DEGREE: usize = 64;

/// The largest distance, relative to the largest control-point coordinate,
/// that an elevated spline may lie from the original at the points checked
/// (`1e-11`); beyond, `elevate_degree` is [`Error::ElevationInexact`].
pub const ELEVATION_ACCURACY: f64 = 1e-11;

/// Parameters checked per non-empty span, besides its ends.
const CHECKS_PER_SPAN: usize = 7;

/// That `raised` (the elevation of `curve` by `times`) is the same curve:
/// both evaluated at the ends and [`CHECKS_PER_SPAN`] points of every
/// non-empty span of `curve`, no farther apart than
/// [`ELEVATION_ACCURACY`] of the size of `curve`'s box `(lo, hi)`.
fn same_curve<const D: usize, C: Curve<D>>(
    curve: &C,
    raised: &C,
    knots: &[f64],
    degree: usize,
    times: usize,
    (lo, hi): (Point<f64, D>, Point<f64, D>),
) -> Result<(), Error> {
    let size = lo.coords.amax().max(hi.coords.amax());
    let n = knots.len() - degree - 1;
    let mut worst = 0.0_f64;
    for i in nonempty_spans(knots, degree, n) {
        let (a, b) = (knots[i], knots[i + 1]);
        for k in 0..=CHECKS_PER_SPAN + 1 {
            let t = a + (b - a) * k as f64 / (CHECKS_PER_SPAN + 1) as f64;
            worst = worst.max((curve.eval(t) - raised.eval(t)).amax());
        }
    }
    let deviation = if size > 0.0 { worst / size } else { worst };
    if deviation > ELEVATION_ACCURACY || deviation.is_nan() {
        return Err(Error::ElevationInexact {
            degree,
            times,
            deviation,
        });
    }
    Ok(())
}

/// The degree `degree + times`, or [`Error::ElevationTooHigh`] when that
/// exceeds [`MAX_ELEVATED_DEGREE`] or overflows (`times == 0` always
/// passes).
pub(crate) fn elevated_degree(degree: usize, times: usize) -> Result<usize, Error> {
    match degree.checked_add(times) {
        Some(q) if times == 0 || q <= MAX_ELEVATED_DEGREE => Ok(q),
        _ => Err(Error::ElevationTooHigh {
            degree,
            times,
            max: MAX_ELEVATED_DEGREE,
        }),
    }
}

/// Elevates the B-spline of degree `degree`, knots `knots` and control
/// coefficients `points` (a valid spline: as [`BSpline::new`] accepts) by
/// `times`: returns the knots and control coefficients of the same curve at
/// degree `degree + times`, every distinct interior knot of the domain
/// `[t_p, t_n]` repeated `times` more times and the ends clamped
/// (multiplicity `degree + times + 1`; knots beyond the domain dropped).
///
/// Generic over the coefficients: points (`SVector`) for [`BSpline`],
/// homogeneous points `(w·P, w)` for rational splines (elevate the
/// homogeneous spline, then divide). The method is in the module docs.
///
/// # Errors
/// [`Error::ElevationTooHigh`] (see [`elevated_degree`]);
/// [`Error::AllocationFailed`] when the result cannot be allocated.
pub(crate) fn elevate_spline<T: Coefficient>(
    degree: usize,
    knots: &[f64],
    points: &[T],
    times: usize,
) -> Result<(Vec<f64>, Vec<T>), Error> {
    let p = degree;
    let q = elevated_degree(p, times)?;
    let n = points.len();
    debug_assert!(n > p && knots.len() == n + p + 1);
    if times == 0 {
        return Ok((knots.to_vec(), points.to_vec()));
    }
    let (a, b) = (knots[p], knots[n]);
    let interior = || {
        knots
            .chunk_by(|x, y| x == y)
            .filter(move |run| run[0] > a && run[0] < b)
    };

    // The new knots: a and b q + 1 times, each interior knot `times` more.
    let count = interior().map(|run| run.len() + times).sum::<usize>() + 2 * (q + 1);
    let mut new_knots = try_with_capacity(count)?;
    new_knots.extend(std::iter::repeat_n(a, q + 1));
    for run in interior() {
        new_knots.extend(std::iter::repeat_n(run[0], run.len() + times));
    }
    new_knots.extend(std::iter::repeat_n(b, q + 1));
    let n_new = new_knots.len() - q - 1;

    // Every non-empty span of the domain as an elevated Bézier piece
    // (q + 1 coefficients each), in order.
    let spans: Vec<usize> = nonempty_spans(knots, p, n).collect();
    let mut pieces = try_with_capacity(spans.len() * (q + 1))?;
    let mut bezier = vec![points[0]; p + 1];
    for &i in &spans {
        span_bezier_points(knots, p, i, &points[i - p..=i], &mut bezier);
        pieces.extend(elevate_degree(&bezier, times));
    }
    // The same pieces as spans of the new knot vector.
    let new_spans: Vec<usize> = nonempty_spans(&new_knots, q, n_new).collect();
    debug_assert_eq!(new_spans.len(), spans.len());

    let mut new_points = try_with_capacity(n_new)?;
    for i in 0..n_new {
        // Pieces j whose span lies in the support [i, i + q] of basis i.
        let first = new_spans.partition_point(|&l| l < i);
        let last = new_spans.partition_point(|&l| l <= i + q);
        // Clamped ends leave no basis function without a span; guard anyway.
        let (first, last) = if first < last {
            (first, last)
        } else {
            let j = first.min(new_spans.len() - 1);
            (j, j + 1)
        };
        let args = &new_knots[i + 1..=i + q];
        let local = |j: usize| {
            let l = new_spans[j];
            let (c, d) = (new_knots[l], new_knots[l + 1]);
            move |t: f64| (t - c) / (d - c)
        };
        // The admissible piece whose blossom extrapolates least.
        let growth = |j: usize| {
            let u = local(j);
            args.iter()
                .map(|&t| ((1.0 - u(t)).abs() + u(t).abs()).ln())
                .sum::<f64>()
        };
        let j = (first + 1..last).fold(
            first,
            |best, j| {
                if growth(j) < growth(best) { j } else { best }
            },
        );
        let u = local(j);
        let piece = &pieces[j * (q + 1)..(j + 1) * (q + 1)];
        let value = with_scratch(q + 1, points[0], |s| {
            s.copy_from_slice(piece);
            for (level, &t) in args.iter().enumerate() {
                let x = u(t);
                for m in 0..q - level {
                    s[m] = lerp(s[m], s[m + 1], x);
                }
            }
            s[0]
        });
        new_points.push(value);
    }
    Ok((new_knots, new_points))
}

impl<const D: usize> Bezier<D> {
    /// The same curve as a Bézier of degree `n + times` (`n + times + 1`
    /// control points), by Farin's elevation formula
    /// `Qᵢ = Σⱼ C(n, j) C(times, i − j) / C(n + times, i) · Pⱼ`. The
    /// parametrization is unchanged: `elevate_degree(k)?.eval(t) == eval(t)`
    /// to rounding. The new points are convex combinations of the old ones,
    /// kept in their box.
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// // A line elevated once gains its midpoint.
    /// let line = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(2.0, 4.0)])?;
    /// let quadratic = line.elevate_degree(1)?;
    /// assert_eq!(quadratic.points()[1], Point2::new(1.0, 2.0));
    /// assert!((quadratic.eval(0.3) - line.eval(0.3)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ElevationTooHigh`] beyond
    /// [`MAX_ELEVATED_DEGREE`]; otherwise as [`Bezier::new`] on the new
    /// points ([`Error::DerivativeOverflow`] only for a curve at that bound).
    pub fn elevate_degree(&self, times: usize) -> Result<Bezier<D>, Error> {
        elevated_degree(self.degree(), times)?;
        let coords: Vec<SVector<f64, D>> = self.points().iter().map(|p| p.coords).collect();
        let bounds = point_bounds(self.points());
        let points = elevate_degree(&coords, times)
            .into_iter()
            .map(|v| Point::from(clamp_to_box(v, bounds)))
            .collect();
        Bezier::new(points)
    }

    /// [`elevate_degree`](Self::elevate_degree) under its other name, kept
    /// so that code calling it compiles.
    ///
    /// # Errors
    /// As [`elevate_degree`](Self::elevate_degree).
    #[deprecated(note = "renamed elevate_degree")]
    pub fn elevate(&self, times: usize) -> Result<Bezier<D>, Error> {
        self.elevate_degree(times)
    }
}

impl<const D: usize> RationalBezier<D> {
    /// The same curve as a rational Bézier of degree `n + times`: Farin's
    /// elevation formula on the homogeneous points `(wᵢPᵢ, wᵢ)` (weights
    /// first scaled so that the largest is 1, and the scale restored
    /// after), then the division `P = wP/w`. The parametrization is
    /// unchanged; the new weights are convex combinations of the old ones
    /// (positive, their ratio no larger), the new points convex combinations
    /// of the old points, kept in their box. A conic stays exactly the same
    /// conic.
    ///
    /// ```
    /// use revolve::Curve;
    /// use revolve::curve::RationalBezier;
    /// use revolve::nalgebra::Point2;
    ///
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let quarter = RationalBezier::new(
    ///     vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(0.0, 1.0)],
    ///     vec![1.0, h, 1.0],
    /// )?;
    /// let cubic = quarter.elevate_degree(1)?;
    /// assert_eq!(cubic.degree(), 3);
    /// for k in 0..=10 {
    ///     let p = cubic.eval(k as f64 / 10.0);
    ///     assert!((p.coords.norm() - 1.0).abs() < 1e-15);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ElevationTooHigh`] beyond [`MAX_ELEVATED_DEGREE`];
    /// otherwise as [`RationalBezier::new`] on the new points and weights.
    pub fn elevate_degree(&self, times: usize) -> Result<RationalBezier<D>, Error> {
        elevated_degree(self.degree(), times)?;
        let top = max_weight(self.weights().iter().copied());
        let homogeneous =
            homogeneous_points(self.points(), self.weights().iter().map(|&w| w / top));
        let bounds = self.bounds();
        let (mut points, weights): (Vec<_>, Vec<_>) = elevate_degree(&homogeneous, times)
            .into_iter()
            .map(|h| (Point::from(clamp_to_box(h.wp / h.w, bounds)), h.w * top))
            .unzip();
        // The ends are the old ends (one term each): exactly, not wP/w.
        let (first, last) = (self.points()[0], self.points()[self.degree()]);
        points[0] = first;
        points[self.degree() + times] = last;
        RationalBezier::new(points, weights)
    }

    /// [`elevate_degree`](Self::elevate_degree) under its other name, kept
    /// so that code calling it compiles.
    ///
    /// # Errors
    /// As [`elevate_degree`](Self::elevate_degree).
    #[deprecated(note = "renamed elevate_degree")]
    pub fn elevate(&self, times: usize) -> Result<RationalBezier<D>, Error> {
        self.elevate_degree(times)
    }
}

impl<const D: usize> BSpline<D> {
    /// The same curve as a B-spline of degree `p + times`: every distinct
    /// interior knot gains `times` in multiplicity (so the continuity
    /// `C^{p−m}` at a knot of multiplicity `m` is kept), the ends of the
    /// domain `[t_p, t_n]` get multiplicity `p + times + 1` (clamped; knots
    /// beyond the domain are dropped), and the domain and the
    /// parametrization are the same. A clamped spline (every knot `times`
    /// more often) gains `times × (distinct knots − 1)` control points.
    ///
    /// # Method
    /// A B-spline of degree `p` whose interior knot `u` has multiplicity `m` is
    /// `C^{p−m}` there. Elevated to degree `q = p + k` (`k = times`) it is the same curve, still
    /// `C^{p−m} = C^{q−(m+k)}`: it lies in the spline space of degree `q` whose
    /// interior knots are the old ones, each repeated `k` more times.
    ///
    /// The ends of the domain `[a, b] = [t_p, t_n]` get multiplicity `q + 1`
    /// (clamped ends; knots beyond the domain are dropped). For a clamped
    /// spline, the usual case (and every NURBS conic), that is again "every
    /// knot `k` more times". For the course framework's uniform knots, whose
    /// knots beyond the domain shape only the control polygon, raising those
    /// knots too would move `t_q` and `t_n` and change the domain, and keeping
    /// them makes the end control points extrapolations that can leave the
    /// control points' hull (and, for rational splines, make weights
    /// negative). Clamped ends avoid both: the result is the old spline with
    /// `a` and `b` inserted to full multiplicity (Boehm's insertion, a corner
    /// cutting) and then elevated as a clamped spline, whose new control points
    /// are convex combinations of the old (degree raising of splines is a
    /// positive process: Cohen, Lyche & Schumaker, *Algorithms for
    /// degree-raising of splines*, ACM TOG 4, 1985; Prautzsch & Piper, *A fast
    /// algorithm to raise the degree of spline curves*, CAGD 8, 1991; the unit
    /// test `elevated_points_are_in_the_old_range` checks it). So the new
    /// points stay in the old points' box and new weights are positive.
    ///
    /// Piegl and Tiller's algorithm A5.9 (*The NURBS Book*, §5.5) computes the
    /// new control points by splitting into Bézier pieces, elevating each, and
    /// then removing the knots back to multiplicity `m + k` one at a time,
    /// sequentially along the curve. Here the last step is replaced by its
    /// closed form, the dual functional property of B-splines (de Boor–Fix;
    /// Ramshaw's blossoming principle): the control point `Q′ᵢ` of a spline of
    /// degree `q` with knots `t′` is the blossom of any of its polynomial pieces
    /// on a span inside the support of its basis function,
    ///
    /// ```text
    /// Q′ᵢ = F_l(t′ᵢ₊₁, …, t′ᵢ₊q),   l ∈ [i, i + q],  t′_l < t′_{l+1}.
    /// ```
    ///
    /// The blossom of an elevated Bézier piece at `q` arguments is de Casteljau's
    /// algorithm with one argument per level. So each new control point is
    /// computed independently, from one elevated piece, with no knot-removal
    /// tolerance to choose and no error carried from point to point (sequential
    /// removal accumulates it). Arguments outside the chosen span extrapolate;
    /// of the admissible spans the one with the smallest growth factor
    /// `Π (|1 − u| + |u|)` over the local arguments `u` is used (1 when every
    /// argument is in the span: the ends, interior knots of multiplicity
    /// `≥ p`). Cost: `O(q²)` per control point.
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::Point2;
    ///
    /// let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0),
    ///                Point2::new(4.0, 0.0), Point2::new(5.0, 1.0)];
    /// let cubic = BSpline::clamped(3, pts)?;   // knots 0 0 0 0 ½ 1 1 1 1
    /// let quartic = cubic.elevate_degree(1)?;
    /// assert_eq!(quartic.degree(), 4);
    /// assert_eq!(quartic.knots(), &[0.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0]);
    /// for k in 0..=20 {
    ///     let t = k as f64 / 20.0;
    ///     assert!((quartic.eval(t) - cubic.eval(t)).norm() < 1e-14);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::ElevationTooHigh`] beyond [`MAX_ELEVATED_DEGREE`];
    /// [`Error::AllocationFailed`] if the new points cannot be allocated;
    /// otherwise as [`BSpline::new`] on the result
    /// ([`Error::DerivativeOverflow`] only for a curve at that bound).
    pub fn elevate_degree(&self, times: usize) -> Result<BSpline<D>, Error> {
        let coords: Vec<SVector<f64, D>> = self.points().iter().map(|p| p.coords).collect();
        let (knots, points) = elevate_spline(self.degree(), self.knots(), &coords, times)?;
        let bounds = self.bounds();
        let points = points
            .into_iter()
            .map(|v| Point::from(clamp_to_box(v, bounds)))
            .collect();
        let raised = BSpline::new(self.degree() + times, knots, points)?;
        same_curve(self, &raised, self.knots(), self.degree(), times, bounds)?;
        Ok(raised)
    }
}

impl<const D: usize> Nurbs<D> {
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
        let scale = weight_scale(self.weights());
        let homogeneous =
            homogeneous_points(self.points(), self.weights().iter().map(|&w| w / scale));
        let (knots, raised) = elevate_spline(self.degree(), self.knots(), &homogeneous, times)?;
        let bounds = self.bounds();
        let (points, weights) = raised
            .iter()
            .map(|h| {
                let p = Point::from(clamp_to_box(h.wp / h.w, bounds));
                (p, h.w * scale)
            })
            .unzip();
        let raised = Nurbs::new(self.degree() + times, knots, points, weights)?;
        same_curve(self, &raised, self.knots(), self.degree(), times, bounds)?;
        Ok(raised)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Homogeneous;
    use nalgebra::{Point2, Vector1, Vector3};

    /// The raw new control points (before they are kept in the box) are
    /// convex combinations of the old: in their range, to rounding, for
    /// unclamped knot vectors with repeated and outside knots (the module
    /// docs' claim; with the old outside knots kept they would not be).
    #[test]
    fn elevated_points_are_in_the_old_range() {
        let mut state = 12345_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..400 {
            let p = case % 6;
            let mut knots = Vec::new();
            let mut value = 0.0;
            while knots.len() < 2 * p + 2 + case % 7 {
                let m = if next() < 0.3 {
                    1 + (next() * (p + 1) as f64) as usize
                } else {
                    1
                };
                knots.extend(std::iter::repeat_n(value, m.min(p + 1)));
                value += 0.2 + next();
            }
            let n = knots.len() - p - 1;
            if knots[p] >= knots[n] {
                continue;
            }
            let points: Vec<Vector1<f64>> =
                (0..n).map(|_| Vector1::new(next() * 2.0 - 1.0)).collect();
            let (lo, hi) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v.x), h.max(v.x))
                });
            for times in 1..4 {
                let (_, new) = elevate_spline(p, &knots, &points, times).unwrap();
                for v in new {
                    assert!(
                        v.x >= lo - 1e-14 && v.x <= hi + 1e-14,
                        "p={p}, +{times}, knots {knots:?}: {} outside [{lo}, {hi}]",
                        v.x
                    );
                }
            }
        }
    }

    /// The generic spline routine computes the same numbers on homogeneous
    /// points as on the equivalent 3-vectors `(w·x, w·y, w)` (it is linear
    /// in the coefficients), so rational splines get exactly the tested
    /// polynomial path.
    #[test]
    fn homogeneous_and_vector_coefficients_agree() {
        let knots = [0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0];
        let pts = [
            (0.0, 0.0),
            (1.0, 2.0),
            (2.0, -1.0),
            (3.0, 1.0),
            (4.0, 0.5),
            (5.0, 2.0),
        ];
        let weights = [1.0, 0.5, 2.0, 0.7, 1.3, 1.0];
        let h: Vec<Homogeneous<2>> = pts
            .iter()
            .zip(weights)
            .map(|(&(x, y), w)| Homogeneous::new(&Point2::new(x, y), w))
            .collect();
        let v: Vec<Vector3<f64>> = h
            .iter()
            .map(|h| Vector3::new(h.wp.x, h.wp.y, h.w))
            .collect();
        for times in 0..4 {
            let (kh, ph) = elevate_spline(2, &knots, &h, times).unwrap();
            let (kv, pv) = elevate_spline(2, &knots, &v, times).unwrap();
            assert_eq!(kh, kv);
            assert_eq!(ph.len(), pv.len());
            for (a, b) in ph.iter().zip(&pv) {
                assert_eq!((a.wp.x, a.wp.y, a.w), (b.x, b.y, b.z));
                assert!(a.w > 0.0, "elevated weights stay positive");
            }
        }
        assert_eq!(
            elevate_spline(2, &knots, &h, usize::MAX).unwrap_err(),
            Error::ElevationTooHigh {
                degree: 2,
                times: usize::MAX,
                max: MAX_ELEVATED_DEGREE
            }
        );
    }
}

//! Exact circles and arcs as degree-2 [`Nurbs`] curves: rational quadratic
//! pieces (Piegl & Tiller, *The NURBS Book*, §7.5).

use crate::{Error, Nurbs};
use nalgebra::{Point2, Vector2};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, TAU};

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

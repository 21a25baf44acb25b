//! Circular arcs in space and elliptic arcs in the plane, exactly, as
//! degree-2 [`Nurbs`] curves: the images of [`Nurbs::arc`] under an
//! affine map (affine maps keep a NURBS curve's weights and knots and map
//! its control points, so the image of the exact circular arc is exactly
//! the mapped arc).

use super::unit_direction;
use crate::{Error, MAX_COORDINATE, Nurbs};
use nalgebra::{Point2, Point3, Vector3};

impl Nurbs<3> {
    /// The arc of the circle of the given center and radius in the plane
    /// through `center` perpendicular to `normal`, from angle `start` to
    /// angle `end` (radians, counter-clockwise about `normal`: right-handed),
    /// angles measured from `start_dir` projected onto that plane; on the
    /// domain `[0, 1]`.
    ///
    /// With `n = normal/|normal|`, `e₁` the unit projection of `start_dir`
    /// onto the plane (`start_dir − (start_dir·n)n`, normalized) and
    /// `e₂ = n × e₁`, the curve is `center + x(t)e₁ + y(t)e₂` where
    /// `(x, y)` is [`Nurbs::arc`]`(origin, radius, start, end)`: the same
    /// weights, knots, pieces and edge rules (sweep in `(0, 2π]`, `2π` the
    /// full circle starting at `start`). The point at angle `θ` is
    /// `center + radius·(cos θ e₁ + sin θ e₂)`.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::{Point3, Vector3};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // A quarter circle of radius 2 about the z axis, from x toward y.
    /// let arc = Nurbs::arc_3d(Point3::new(0.0, 0.0, 1.0), Vector3::z(), Vector3::x(), 2.0, 0.0, FRAC_PI_2)?;
    /// assert_eq!(arc.eval(0.0), Point3::new(2.0, 0.0, 1.0));
    /// assert!((arc.eval(1.0) - Point3::new(0.0, 2.0, 1.0)).norm() < 1e-15);
    /// let p = arc.eval(0.3);
    /// assert!(((p - Point3::new(0.0, 0.0, 1.0)).norm() - 2.0).abs() < 1e-15 && p.z == 1.0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidCenter3`] for a center with a NaN, infinite or too
    /// large coordinate; [`Error::InvalidArcFrame`] for a `normal` or
    /// `start_dir` that is zero, NaN or infinite, or a `start_dir` parallel
    /// to `normal` (its projection below `1e-12` of its length);
    /// [`Error::InvalidRadius`] and [`Error::InvalidSweep`] as
    /// [`Nurbs::arc`]; [`Error::CoordinateTooLarge`] for a control point
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn arc_3d(
        center: Point3<f64>,
        normal: Vector3<f64>,
        start_dir: Vector3<f64>,
        radius: f64,
        start: f64,
        end: f64,
    ) -> Result<Nurbs<3>, Error> {
        if !center
            .iter()
            .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
        {
            return Err(Error::InvalidCenter3 {
                center: [center.x, center.y, center.z],
            });
        }
        let frame_error = Error::InvalidArcFrame {
            normal: [normal.x, normal.y, normal.z],
            start_dir: [start_dir.x, start_dir.y, start_dir.z],
        };
        let (Some(n), Some(d)) = (unit_direction(normal), unit_direction(start_dir)) else {
            return Err(frame_error);
        };
        let projected = d.into_inner() - n.into_inner() * d.dot(&n);
        if projected.norm().is_nan() || projected.norm() <= 1e-12 {
            return Err(frame_error);
        }
        let Some(e1) = unit_direction(projected) else {
            return Err(frame_error);
        };
        let e2 = n.cross(&e1);
        let e2 = unit_direction(e2).map_or(e2, |u| u.into_inner());
        let plane = Nurbs::arc(Point2::origin(), radius, start, end)?;
        let points = plane
            .points()
            .iter()
            .map(|p| center + e1.into_inner() * p.x + e2 * p.y)
            .collect();
        Nurbs::new(2, plane.knots().to_vec(), points, plane.weights().to_vec())
    }
}

impl Nurbs<2> {
    /// The arc of the axis-aligned ellipse of the given center and radii
    /// `(a, b)` from parameter angle `start` to `end` (radians,
    /// counter-clockwise), exactly: [`Nurbs::arc`] of the unit circle with
    /// its control points scaled by `(a, b)` and moved to `center` (same
    /// weights and knots), so the point at angle `θ` is
    /// `center + (a cos θ, b sin θ)` (`θ` is the eccentric angle, not the
    /// polar angle of the point). Domain `[0, 1]`; sweep rules as
    /// [`Nurbs::arc`]. Equal radii give the circular arc.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::Point2;
    /// use std::f64::consts::PI;
    ///
    /// let e = Nurbs::ellipse_arc(Point2::new(1.0, 0.0), (3.0, 2.0), 0.0, PI)?;
    /// assert_eq!(e.eval(0.0), Point2::new(4.0, 0.0));
    /// let p = e.eval(0.37) - Point2::new(1.0, 0.0);
    /// assert!(((p.x / 3.0).powi(2) + (p.y / 2.0).powi(2) - 1.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidCenter`] for a center with a NaN, infinite or too
    /// large coordinate; [`Error::InvalidRadius`] for either radius not
    /// finite and positive or beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE); [`Error::InvalidSweep`]
    /// as [`Nurbs::arc`]; [`Error::CoordinateTooLarge`] for a control point
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    pub fn ellipse_arc(
        center: Point2<f64>,
        radii: (f64, f64),
        start: f64,
        end: f64,
    ) -> Result<Nurbs<2>, Error> {
        if !center
            .iter()
            .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
        {
            return Err(Error::InvalidCenter { center });
        }
        for radius in [radii.0, radii.1] {
            if !(radius.is_finite() && radius > 0.0 && radius <= MAX_COORDINATE) {
                return Err(Error::InvalidRadius { radius });
            }
        }
        let unit = Nurbs::arc(Point2::origin(), 1.0, start, end)?;
        let points = unit
            .points()
            .iter()
            .map(|p| Point2::new(center.x + radii.0 * p.x, center.y + radii.1 * p.y))
            .collect();
        Nurbs::new(2, unit.knots().to_vec(), points, unit.weights().to_vec())
    }
}

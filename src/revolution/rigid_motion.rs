//! Revolutions moved by rigid motions ([`Revolution::transformed`]).

use super::surface::{axis_rotation, placement};
use crate::{Curve, Error, Revolution};
use nalgebra::{Isometry3, Point3, Unit, Vector3};

impl<C: Curve<2>> Revolution<C> {
    /// The surface moved by the rigid motion `motion` (a rotation, then a
    /// translation), exactly: its placement becomes `motion ∘ to_world`,
    /// so `S′(u, θ) = motion(S(u, θ))` at every parameter, and the
    /// partials and normals turn with the rotation (the orientation, the
    /// profile, the tolerance and the parameters are kept).
    ///
    /// Only rigid motions: a revolution is defined by a profile turned
    /// about an axis in an orthonormal frame, and a general affine map
    /// (a scaling along one direction, a shear) takes its circles to
    /// ellipses, which no revolution is; convert to a
    /// [`NurbsSurface`](crate::NurbsSurface) (`NurbsSurface::from_revolution`)
    /// for those. Unlike [`with_axis`](Self::with_axis), whose rotation is
    /// the shortest one taking `y` to the axis, the composed rotation may
    /// also turn the surface about its own axis (which moves where `θ = 0`
    /// lies); serialization writes that turn.
    ///
    /// Never panics. A motion with a NaN or infinite component, or one that
    /// takes the axis's origin beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), is not applied: as for
    /// `with_axis`, the surface stays where it was, becomes empty to rays
    /// and [`contract_error`](Self::contract_error) says why;
    /// [`try_transformed`](Self::try_transformed) returns the error instead.
    ///
    /// ```
    /// use revolve::{Bezier, Revolution, Surface};
    /// use revolve::nalgebra::{Isometry3, Point2, Vector3};
    ///
    /// let profile = Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(2.0, 1.0), Point2::new(1.0, 2.0)])?;
    /// let r = Revolution::new(profile);
    /// let motion = Isometry3::new(Vector3::new(1.0, -2.0, 3.0), Vector3::new(0.3, 0.5, -0.2));
    /// let moved = r.transformed(&motion);
    /// for (u, theta) in [(0.0, 0.0), (0.3, 1.0), (0.9, 5.0)] {
    ///     assert!((moved.eval(u, theta) - motion * r.eval(u, theta)).norm() < 1e-14);
    ///     let (n, m) = (r.normal(u, theta).unwrap(), moved.normal(u, theta).unwrap());
    ///     assert!((m.into_inner() - motion.rotation * n.into_inner()).norm() < 1e-14);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, motion: &Isometry3<f64>) -> Self
    where
        C: Clone,
    {
        match self.try_transformed(motion) {
            Ok(surface) => surface,
            Err(e) => {
                let mut surface = self.clone();
                surface.exact = None;
                surface.broken = Some(e);
                surface
            }
        }
    }

    /// As [`transformed`](Self::transformed), but a motion that cannot be
    /// applied is an error.
    ///
    /// # Errors
    /// [`Error::InvalidPlacement`] (with the origin and axis the motion
    /// would give) for a motion with a NaN or infinite component or one
    /// taking the origin beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    ///
    /// ```
    /// use revolve::{Bezier, Error, Revolution};
    /// use revolve::nalgebra::{Isometry3, Point2, Vector3};
    ///
    /// let r = Revolution::new(Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0)])?);
    /// let far = Isometry3::translation(1e101, 0.0, 0.0);
    /// assert!(matches!(r.try_transformed(&far), Err(Error::InvalidPlacement { .. })));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn try_transformed(&self, motion: &Isometry3<f64>) -> Result<Self, Error>
    where
        C: Clone,
    {
        let to_world = motion * self.to_world;
        let origin = Point3::from(to_world.translation.vector);
        let axis = to_world.rotation * Vector3::y();
        let finite = motion
            .translation
            .vector
            .iter()
            .chain(motion.rotation.coords.iter())
            .all(|x| x.is_finite());
        if !finite {
            return Err(Error::InvalidPlacement { origin, axis });
        }
        let unit = placement(origin, Unit::new_unchecked(axis))?;
        // The turn about the local y axis before the shortest rotation:
        // R_axisᵀ·R = R_y(φ) = [[cos φ, 0, sin φ], [0, 1, 0], [−sin φ, 0, cos φ]].
        let relative = axis_rotation(&unit).inverse() * to_world.rotation.to_rotation_matrix();
        let turn = relative[(0, 2)].atan2(relative[(0, 0)]);
        let mut surface = self.clone();
        surface.rotation = to_world.rotation.to_rotation_matrix();
        surface.to_world = to_world;
        surface.scaled_axis = unit.into_inner() / unit.amax();
        surface.turn = turn;
        Ok(surface)
    }

    /// The turn about the axis that [`transformed`](Self::transformed)
    /// composed (0 after a placement by `with_axis`), for serialization.
    #[cfg(feature = "serde")]
    pub(crate) fn turn(&self) -> f64 {
        self.turn
    }

    /// The surface (placed by `with_axis`) turned by `angle` about its
    /// local `y` axis before the placement's rotation, as serialization
    /// reads a [`transformed`](Self::transformed) surface back (to
    /// rounding of the composed rotation).
    #[cfg(feature = "serde")]
    pub(crate) fn with_turn(mut self, angle: f64) -> Self {
        if angle != 0.0 && angle.is_finite() {
            let spin = nalgebra::UnitQuaternion::from_axis_angle(&Vector3::y_axis(), angle);
            self.to_world =
                Isometry3::from_parts(self.to_world.translation, self.to_world.rotation * spin);
            self.rotation = self.to_world.rotation.to_rotation_matrix();
            self.turn = angle;
        }
        self
    }
}

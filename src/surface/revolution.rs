//! Surfaces of revolution: a planar profile turned about an axis.

use crate::ray::revolution::SpanTable;
use crate::{Aabb, Curve, Hit, Intersect, Ray, Surface, Tolerance};
use nalgebra::{Isometry3, Point3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::TAU;

/// The surface swept by a profile curve `(x(u), y(u))` turning about an axis.
///
/// In its local frame the axis is the `y` axis and
///
/// `S(u, θ) = (x(u) cos θ, y(u), −x(u) sin θ)`, `u` in the profile's domain,
/// `θ ∈ [0, 2π]`.
///
/// Partial derivatives are analytic: `∂S/∂u = (x′ cos θ, y′, −x′ sin θ)` and
/// `∂S/∂θ = (−x sin θ, 0, −x cos θ)`. Their cross product is
/// `x·(−y′ cos θ, x′, y′ sin θ)`, so the unit normal (orientation of the
/// parametrization, `∂S/∂u × ∂S/∂θ`) is `sign(x)·(−y′ cos θ, x′, y′ sin θ)`
/// with `(x′, y′)` the profile's unit tangent. For a profile traced upward
/// (increasing `y`) it points toward the axis, on either side of it (negative
/// `x`, as course scene files write profiles, gives the same surface and
/// orientation as positive `x`).
///
/// # Edge rules: the axis
/// Where the profile meets the axis (`x = 0`) the cross product vanishes. The
/// normal there is the limit from the profile's neighbourhood: the profile's
/// tangent comes from its first non-vanishing derivative (so repeated control
/// points on the axis work), and `sign(x)` from the side the profile leaves
/// the axis to. If the profile meets the axis perpendicularly (a pole, as at
/// the bottom of a vase) the normal is `±` the axis; if it meets it at an angle
/// (a cone's apex) there is no tangent plane and the normal is `None`.
///
/// A revolution can be placed anywhere with [`with_axis`](Self::with_axis).
#[derive(Debug, Clone, PartialEq)]
pub struct Revolution<C> {
    profile: C,
    /// Local frame → world: rotation taking the local `y` axis to the axis,
    /// then translation to the axis origin.
    to_world: Isometry3<f64>,
    /// The exact intersector's per-surface data, when the profile has
    /// Bézier spans of one degree.
    exact: Option<SpanTable>,
    tolerance: Tolerance,
}

impl<C: Curve<2>> Revolution<C> {
    /// The surface of `profile` turned about the `y` axis through the origin.
    ///
    /// If the profile provides [Bézier spans](Curve::bezier_spans) (as
    /// [`Bezier`](crate::Bezier) and [`BSpline`](crate::BSpline) do), the data
    /// of the exact intersector is computed here, once.
    pub fn new(profile: C) -> Self {
        let exact = profile.bezier_spans().and_then(|s| SpanTable::new(&s));
        Revolution {
            profile,
            to_world: Isometry3::identity(),
            exact,
            tolerance: Tolerance::default(),
        }
    }

    /// The same surface with the given intersection accuracy (the default is
    /// full double precision).
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The intersection accuracy.
    pub fn tolerance(&self) -> &Tolerance {
        &self.tolerance
    }

    /// The same surface placed so that its axis passes through `origin` along
    /// `axis` (the local `y` axis maps to `axis`, the local origin to
    /// `origin`). The rotation is the shortest one taking `y` to `axis`; for
    /// `axis = −y` it is the half turn about `x`.
    pub fn with_axis(mut self, origin: Point3<f64>, axis: Unit<Vector3<f64>>) -> Self {
        let y = Vector3::y_axis();
        let rotation = Rotation3::rotation_between(&y, &axis).unwrap_or_else(|| {
            Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        });
        self.to_world = Isometry3::from_parts(
            Translation3::from(origin.coords),
            UnitQuaternion::from_rotation_matrix(&rotation),
        );
        self
    }

    /// The profile curve.
    pub fn profile(&self) -> &C {
        &self.profile
    }

    /// The rigid motion from the local frame (axis = `y`) to the world.
    pub fn to_world(&self) -> &Isometry3<f64> {
        &self.to_world
    }

    /// The point in the local frame.
    #[inline]
    pub fn eval_local(&self, u: f64, theta: f64) -> Point3<f64> {
        let p = self.profile.eval(u);
        let (s, c) = theta.sin_cos();
        Point3::new(p.x * c, p.y, -p.x * s)
    }

    /// The partials `(∂S/∂u, ∂S/∂θ)` in the local frame.
    #[inline]
    pub fn partials_local(&self, u: f64, theta: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (p, d) = self.profile.eval_with_derivative(u);
        let (s, c) = theta.sin_cos();
        (
            Vector3::new(d.x * c, d.y, -d.x * s),
            Vector3::new(-p.x * s, 0.0, -p.x * c),
        )
    }

    /// The unit normal in the local frame (see the type's edge rules).
    pub fn normal_local(&self, u: f64, theta: f64) -> Option<Unit<Vector3<f64>>> {
        let tangent = self.profile.tangent(u)?;
        let (dx, dy) = (tangent.x, tangent.y);
        let x = self.profile.eval(u).x;
        let side = if x != 0.0 {
            x.signum()
        } else {
            // On the axis. A tangent plane exists only if the profile meets
            // the axis perpendicularly (to within √ε: a steeper "cone" is a
            // disk to double precision).
            if dy.abs() > f64::EPSILON.sqrt() {
                return None;
            }
            let (_, u_end) = self.profile.domain();
            // The profile leaves the axis toward sign(x′) on the right, and
            // arrives from −sign(x′) at the end of the domain.
            if u >= u_end {
                -dx.signum()
            } else {
                dx.signum()
            }
        };
        let (s, c) = theta.sin_cos();
        Unit::try_new(Vector3::new(-dy * c, dx, dy * s) * side, 0.0)
    }
}

impl<C: Curve<2>> Surface for Revolution<C> {
    fn domain(&self) -> [(f64, f64); 2] {
        [self.profile.domain(), (0.0, TAU)]
    }

    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        self.to_world * self.eval_local(u, v)
    }

    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (su, sv) = self.partials_local(u, v);
        (self.to_world * su, self.to_world * sv)
    }

    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        self.normal_local(u, v)
            .map(|n| Unit::new_unchecked(self.to_world.rotation * n.into_inner()))
    }
}

/// The world box of the local box `[−r, y₀, −r] × [r, y₁, r]` (the cylinder
/// around the profile's radius and height ranges), conservatively: the box of
/// its eight transformed corners.
pub(crate) fn world_bounds(to_world: &Isometry3<f64>, r: f64, y0: f64, y1: f64) -> Aabb {
    let mut b = Aabb::EMPTY;
    for &x in &[-r, r] {
        for &y in &[y0, y1] {
            for &z in &[-r, r] {
                b = b.include(&(to_world * Point3::new(x, y, z)));
            }
        }
    }
    b
}

impl<C: Curve<2>> Intersect for Revolution<C> {
    /// The exact intersector (see the `ray` module): the nearest hit with
    /// `t_min < t < t_max`, or `None`. Profiles without Bézier spans have no
    /// exact intersector yet and report no hits.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let exact = self.exact.as_ref()?;
        let o = self.to_world.inverse_transform_point(&ray.origin);
        let d = self.to_world.inverse_transform_vector(&ray.dir);
        let local = exact.intersect(o, d, t_min, t_max, &self.tolerance)?;
        let normal_local = self
            .normal_local(local.u, local.theta)
            // No tangent plane (a cone's apex): face the ray.
            .or_else(|| Unit::try_new(-d, 0.0))?;
        let point = self.to_world * local.point;
        if !point.coords.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Hit {
            t: local.t,
            point,
            normal: Unit::new_unchecked(self.to_world.rotation * normal_local.into_inner()),
            uv: (local.u, local.theta),
        })
    }

    fn bounds(&self) -> Aabb {
        match &self.exact {
            Some(e) => world_bounds(&self.to_world, e.r_max, e.y_range.0, e.y_range.1),
            None => Aabb::EMPTY,
        }
    }
}

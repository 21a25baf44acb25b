//! Rays, hits, the [`Intersect`] trait and the accuracy setting.
//!
//! A ray is `R(t) = origin + t·dir`. `dir` need not be unit length: `t` is
//! measured in units of `|dir|`, so `t` of a hit is the same number whatever
//! the caller's normalization convention, and `t_min`/`t_max` are in the same
//! units.

#[cfg(test)]
mod double_double;
mod meridian_cells;
pub mod newton;
pub(crate) mod revolution;
mod select;
mod span_form;
#[cfg(test)]
mod test_unit;
mod turn_angle;

pub use revolution::ExactReport;

pub use newton::{NewtonFinish, NewtonIntersector, NewtonReport, NewtonRun};

use crate::Aabb;
use nalgebra::{Point3, Unit, Vector3};

/// A ray `R(t) = origin + t·dir`, `t` in units of `|dir|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts (`t = 0`).
    pub origin: Point3<f64>,
    /// The direction; need not be unit length, must not be zero.
    pub dir: Vector3<f64>,
}

impl Ray {
    /// The ray from `origin` along `dir`.
    pub fn new(origin: Point3<f64>, dir: Vector3<f64>) -> Self {
        Ray { origin, dir }
    }

    /// The point `origin + t·dir`.
    #[inline]
    pub fn at(&self, t: f64) -> Point3<f64> {
        self.origin + self.dir * t
    }
}

/// A ray–surface intersection.
///
/// - `t`: the ray parameter, in units of `|dir|`.
/// - `point`: the surface point `S(uv)`; `origin + t·dir` lies within the
///   solver's accepted residual of it (`max(tolerance, 1e-9) ×` the object's
///   scale; after Newton's polish usually a few ulps).
/// - `normal`: the surface's unit normal at the hit, oriented as the surface
///   defines it ([`Surface::normal`](crate::Surface::normal)), not flipped
///   toward the ray; compare its sign with `dir` to tell front from back.
/// - `uv`: the surface parameters of the hit.
///
/// Never holds NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f64,
    /// The hit point.
    pub point: Point3<f64>,
    /// Unit surface normal at the hit (orientation of the surface).
    pub normal: Unit<Vector3<f64>>,
    /// Surface parameters `(u, v)` of the hit.
    pub uv: (f64, f64),
}

/// Something a ray can hit.
pub trait Intersect {
    /// The nearest hit with `t_min < t < t_max`, or `None` for a miss.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit>;

    /// A box containing everything the object can be hit at.
    fn bounds(&self) -> Aabb;
}

/// How accurately a solver works: an explicit setting, no hidden epsilon.
///
/// `relative` is the target error of a hit (in `t`, and in the distance of the
/// hit point from the surface) relative to the object's scale (the largest
/// absolute coordinate of its bounding box). The default, `4ε ≈ 8.9e-16`, is
/// full double precision: solvers iterate until rounding stops them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Target error relative to the object's scale.
    pub relative: f64,
    /// Cap on the iterations of any one Newton refinement.
    pub max_iterations: u32,
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance {
            relative: 4.0 * f64::EPSILON,
            max_iterations: 32,
        }
    }
}

impl Tolerance {
    /// A tolerance with the given relative target and the default cap.
    pub fn relative(relative: f64) -> Self {
        Tolerance {
            relative,
            ..Self::default()
        }
    }
}

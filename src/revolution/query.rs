//! A ray in the revolution's local frame (axis `y`) with the per-ray
//! constants of the span search, and a hit in that frame.

use crate::Tolerance;
use crate::ray::acceptance::Acceptance;
use nalgebra::{Point3, Vector3};

/// A hit in the local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalHit {
    pub(crate) t: f64,
    pub(crate) u: f64,
    pub(crate) theta: f64,
    /// `(sin θ, cos θ)`, as the point was formed from them (no
    /// trigonometry needed for the normal).
    pub(crate) sin_cos: (f64, f64),
    pub(crate) point: Point3<f64>,
    /// The profile's unit tangent there, from the span's Bézier form, when
    /// the derivative is clearly non-zero (`None` near a pole: the caller
    /// then takes the limit from the profile itself).
    pub(crate) tangent: Option<nalgebra::Unit<nalgebra::Vector2<f64>>>,
    /// The profile's (signed) `x` there.
    pub(crate) x: f64,
    /// `|o + t·d − S(u, θ)|` after Newton's polish.
    pub(crate) residual: f64,
    /// The span's own parameter of the hit.
    pub(crate) s: f64,
}

/// A ray in the local frame and the constants of its search.
#[derive(Debug, Clone, Copy)]
pub(super) struct Query {
    pub(super) o: Vector3<f64>,
    pub(super) d: Vector3<f64>,
    /// The residual within which a hit is accepted, and at which Newton
    /// stops.
    pub(super) acceptance: Acceptance,
    pub(super) max_iterations: u32,
    /// Per-ray constants of the span culling: `1/d_y` (0 when `d_y = 0`),
    /// `accept/|d|`, the squared distance from the axis
    /// `r²(t) = a t² + 2 b t + c`, and where it is least (`−b/a`, or 0).
    pub(super) inv_dy: f64,
    pub(super) pad_t: f64,
    pub(super) radius: (f64, f64, f64),
    pub(super) t_closest: f64,
}

impl Query {
    /// The query for the ray `o + t·d` (finite, `d ≠ 0`) at tolerance `tol`
    /// on an object of size `scale`.
    #[inline(always)]
    pub(super) fn new(o: Vector3<f64>, d: Vector3<f64>, tol: &Tolerance, scale: f64) -> Self {
        // The tolerance is relative to the object; the rounding floor also
        // grows with the ray origin's distance.
        let acceptance = Acceptance::certified(tol, scale.max(f64::MIN_POSITIVE), &o);
        let accept = acceptance.distance;
        let (a, b) = (d.x * d.x + d.z * d.z, o.x * d.x + o.z * d.z);
        Query {
            o,
            d,
            acceptance,
            max_iterations: tol.max_iterations,
            inv_dy: if d.y == 0.0 { 0.0 } else { 1.0 / d.y },
            pad_t: accept / d.norm(),
            radius: (a, b, o.x * o.x + o.z * o.z),
            t_closest: if a > 0.0 { -b / a } else { 0.0 },
        }
    }
}

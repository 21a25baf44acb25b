//! Certified references for the nearest hit of a ray, shared by the
//! integration tests and the accuracy study (`studies/accuracy_cost`).
//!
//! - [`revolution`]: surfaces of revolution with a Bézier or B-spline
//!   profile, in exact rational arithmetic (the angle eliminated, exact
//!   Bézier spans, Descartes' rule in the Bernstein basis), rounded once.
//! - [`patch`]: tensor-product Bézier patches (the teapot), certified by
//!   interval subdivision, Miranda's theorem and an injectivity test.
//! - [`exact`]: the exact numbers they rest on (`f64`s as dyadic rationals,
//!   unreduced fractions, correct rounding back to `f64`).
//! - [`Certifier`]: what a consumer asks of any of them, also implemented by
//!   the closed forms of the rational sphere and torus
//!   ([`ClosedForm`]).
//!
//! Independence: none of the library's intersection, root finding, knot
//! insertion, Bézier-span, de Casteljau or rounding-bound code is used; the
//! only inputs shared with the library are the shapes' numbers (control
//! points, knots) and the ray.
//!
//! The other references of this crate answer different questions and stay
//! separate: [`exact_roots`](crate::exact_roots) (Sturm sequences in the
//! power basis: every root of an integer polynomial, for the closed forms)
//! and [`patch_reference`](crate::patch_reference) (every root of a ray on a
//! rational patch, power form and Newton; not certified for tangent rays).

pub mod exact;
pub mod patch;
pub mod revolution;

use crate::closed_forms::ClosedForm;
use revolve::Ray;

/// A reference as a consumer uses it: for each ray, the certified nearest
/// hit or miss, or nothing certain (the ray is then left out).
pub trait Certifier: Sync {
    /// The nearest hit's `t` with `t_min < t < t_max` (`Some(None)`: a
    /// certain miss); `None` when the answer cannot be certified.
    fn certify(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Option<f64>>;
}

impl Certifier for ClosedForm {
    fn certify(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Option<f64>> {
        Some(self.roots(ray)?.first_in(t_min, t_max))
    }
}

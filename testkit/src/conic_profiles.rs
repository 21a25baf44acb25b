//! Exact conic profiles for rational revolutions: the half circle of a
//! sphere and the full circle of a torus, as NURBS (rational quadratic
//! quarter arcs, weights `1, √2/2, 1`).

use revolve::Nurbs;
use revolve::nalgebra::Point2;
use std::f64::consts::FRAC_PI_2;

/// The sphere's profile: the half circle of radius `radius` about the
/// origin from the south pole `(0, −R)` to the north pole `(0, R)` through
/// `(R, 0)` (`Nurbs::arc` from `−π/2` to `π/2`: two quarter arcs, joined at
/// the equator).
pub fn sphere_profile(radius: f64) -> Nurbs<2> {
    Nurbs::arc(Point2::origin(), radius, -FRAC_PI_2, FRAC_PI_2).expect("a valid half circle")
}

/// The torus's profile: the circle of radius `minor` about `(major, 0)`,
/// counter-clockwise from `(major + minor, 0)` (`Nurbs::circle`: four
/// quarter arcs, joined on the outer and inner equators and on the top and
/// bottom circles).
pub fn torus_profile(major: f64, minor: f64) -> Nurbs<2> {
    Nurbs::circle(Point2::new(major, 0.0), minor).expect("a valid circle")
}

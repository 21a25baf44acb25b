//! Hits on a surface of revolution whose profile has no Bézier spans: the
//! hit of the profile's cubic approximation, refined on the profile itself.

use super::meridian_newton::{meridian_angle, meridian_newton};
use super::query::LocalHit;
use super::span_form::ProfilePoint;
use super::turn_angle::turn_angle;
use crate::ray::acceptance::Acceptance;
use crate::{Curve, Tolerance};
use nalgebra::{Point3, Vector3};

/// Newton's method in the meridian plane ([`meridian_newton`]) on `profile`
/// over its `domain`, for the local ray `o + t·d`, from the approximation's
/// hit `(u, t) = start`. The hit is kept if the residual on the profile is
/// within the exact intersector's acceptance, `max(tolerance, 1e-12) ×` the
/// object's `scale` (and the origin's distance), and `u` stays in the domain.
/// `tol` is taken as valid ([`Tolerance::clamped`], as the surface stores it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn refine_on_profile<C: Curve<2>>(
    profile: &C,
    domain: (f64, f64),
    o: &Vector3<f64>,
    d: &Vector3<f64>,
    start: (f64, f64),
    scale: f64,
    tol: &Tolerance,
    iterations: &mut u32,
) -> Option<LocalHit> {
    let acceptance = Acceptance::certified(tol, scale, o);
    let target = acceptance.target;
    let eval = |u: f64| {
        let (p, dp) = profile.eval_with_derivative(u);
        ProfilePoint {
            x: p.x,
            y: p.y,
            dx: dp.x,
            dy: dp.y,
        }
    };
    let (r, u, t, at) = meridian_newton(
        o,
        d,
        start,
        domain,
        target,
        tol.max_iterations,
        eval,
        iterations,
    );
    if !(acceptance.accepts(r) && t.is_finite()) {
        return None;
    }
    let (sn, cs) = meridian_angle(&(o + d * t), at.x);
    Some(LocalHit {
        t,
        u,
        theta: turn_angle(sn, cs),
        sin_cos: (sn, cs),
        point: Point3::new(at.x * cs, at.y, -at.x * sn),
        // The caller takes the normal from the profile's own tangent.
        tangent: None,
        x: at.x,
        residual: r,
        s: u,
    })
}

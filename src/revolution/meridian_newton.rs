//! Newton's method for a ray and a surface of revolution, in the meridian
//! plane.
//!
//! For the ray point `p(t) = o + t·d` at distance `ρ(t) = |p_xz|` from the
//! axis, the nearest point of the circle swept by the profile point
//! `(x(s), y(s))` is the one in `p`'s direction, so
//!
//! `|p(t) − S(s, θ(t))|² = (ρ(t) − |x(s)|)² + (p_y(t) − y(s))²`,
//!
//! and a hit is a root of the 2 × 2 system `ρ(t) = |x(s)|`, `p_y(t) = y(s)`,
//! with Jacobian `[[ρ′, −σx′], [d_y, −y′]]` (`σ = sign x`,
//! `ρ′ = (p_xz · d_xz)/ρ`) acting on `(Δt, Δs)`. No trigonometry per
//! iteration; the angle is that of `p` at the end ([`meridian_angle`]).
//! The exact intersector polishes its isolated roots with it, on a span's
//! Bézier form; surfaces whose profile has no Bézier spans refine the hits
//! of their approximation with it, on the profile itself.

use super::span_form::ProfilePoint;
use nalgebra::Vector3;

/// Newton's method on the meridian-plane system from `(s, t) = start`,
/// with `s` kept in `s_range`, until the residual is at most `target`, a
/// step fails to reduce it, or `max_iterations` steps (each counted in
/// `iterations`). `eval(s)` gives the profile's point and derivative.
///
/// Returns the best iterate: `(residual, s, t, profile point there)`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn meridian_newton(
    o: &Vector3<f64>,
    d: &Vector3<f64>,
    start: (f64, f64),
    s_range: (f64, f64),
    target: f64,
    max_iterations: u32,
    eval: impl Fn(f64) -> ProfilePoint,
    iterations: &mut u32,
) -> (f64, f64, f64, ProfilePoint) {
    // The residual (ρ − |x|, p_y − y) at (s, t), with ρ, the profile there
    // and the ray point; the profile is evaluated once per iterate and kept
    // with it.
    let residual = |s: f64, t: f64| {
        let profile = eval(s);
        let p = o + d * t;
        let rho = (p.x * p.x + p.z * p.z).sqrt();
        ((rho - profile.x.abs(), p.y - profile.y), rho, profile, p)
    };
    let (mut s, mut t) = start;
    let (mut f, mut rho, mut profile, mut p) = residual(s, t);
    let mut r = (f.0 * f.0 + f.1 * f.1).sqrt();
    let mut best = (r, s, t, profile);
    for _ in 0..max_iterations {
        *iterations += 1;
        if r <= target || rho == 0.0 {
            break;
        }
        let ProfilePoint { x, dx, dy, .. } = profile;
        let sigma = if x < 0.0 { -1.0 } else { 1.0 };
        let drho = (p.x * d.x + p.z * d.z) / rho;
        let (j00, j01, j10, j11) = (drho, -sigma * dx, d.y, -dy);
        let det = j00 * j11 - j01 * j10;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let step_t = (-f.0 * j11 + f.1 * j01) / det;
        let step_s = (-f.1 * j00 + f.0 * j10) / det;
        if !(step_t.is_finite() && step_s.is_finite()) {
            break;
        }
        t += step_t;
        s = (s + step_s).clamp(s_range.0, s_range.1);
        (f, rho, profile, p) = residual(s, t);
        let r_new = (f.0 * f.0 + f.1 * f.1).sqrt();
        if r_new < best.0 {
            best = (r_new, s, t, profile);
        }
        if r_new >= r {
            break;
        }
        r = r_new;
    }
    best
}

/// `(sin θ, cos θ)` of the surface point nearest the ray point `p` on the
/// circle of the profile point with radius coordinate `x`:
/// `S = (x cos θ, y, −x sin θ)` lies in `p`'s direction from the axis, so
/// for `x < 0` it is `|x|` in that direction at `θ + π`. On the axis
/// (`ρ = 0`) the angle is 0.
#[inline(always)]
pub(super) fn meridian_angle(p: &Vector3<f64>, x: f64) -> (f64, f64) {
    let rho = (p.x * p.x + p.z * p.z).sqrt();
    if rho > 0.0 {
        let sigma = if x < 0.0 { -1.0 } else { 1.0 };
        (-sigma * p.z / rho, sigma * p.x / rho)
    } else {
        (0.0, 1.0)
    }
}

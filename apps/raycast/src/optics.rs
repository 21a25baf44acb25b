//! Mirror reflection, refraction, Fresnel weights and absorption.
//!
//! Conventions: `d` is the unit direction of the incoming ray, `n` the unit
//! normal on the side the ray comes from (`d·n < 0`), `eta = n₁/n₂` the ratio
//! of the refractive indices on the incoming and the outgoing side.
//!
//! - Reflection: `r = d − 2(d·n)n`.
//! - Refraction (Snell, `n₁ sin θ₁ = n₂ sin θ₂`): with `cos θ₁ = −d·n` and
//!   `sin² θ₂ = eta² (1 − cos² θ₁)`, `t = eta·d + (eta·cos θ₁ − cos θ₂)·n`;
//!   when `sin² θ₂ > 1` there is no transmitted ray (total internal
//!   reflection).
//! - Fresnel: the exact reflectance of unpolarized light at a smooth
//!   dielectric interface, the mean of
//!   `r_s = (n₁cos θ₁ − n₂cos θ₂)/(n₁cos θ₁ + n₂cos θ₂)` and
//!   `r_p = (n₂cos θ₁ − n₁cos θ₂)/(n₂cos θ₁ + n₁cos θ₂)` squared; 1 under
//!   total internal reflection, 0 when `n₁ = n₂`.
//! - Beer–Lambert: light that travels a distance `s` through a medium with
//!   absorption coefficient `σ` (per unit length, per channel) keeps the
//!   fraction `exp(−σ s)`.

use revolve::nalgebra::Vector3;

use crate::scene::Color;

/// The mirror direction of `d` about `n`.
#[inline]
pub fn reflect(d: &Vector3<f64>, n: &Vector3<f64>) -> Vector3<f64> {
    d - n * (2.0 * d.dot(n))
}

/// The refracted direction, or `None` under total internal reflection.
/// `n` faces the incoming ray; the result is unit when `d` and `n` are.
#[inline]
pub fn refract(d: &Vector3<f64>, n: &Vector3<f64>, eta: f64) -> Option<Vector3<f64>> {
    let cos_i = (-d.dot(n)).min(1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(d * eta + n * (eta * cos_i - cos_t))
}

/// The refractive indices `(n₁, n₂)` on the incoming and the far side of a
/// surface of index `ior` (a non-positive `ior` counts as 1, vacuum) with
/// air outside: `(1, ior)` entering through the front, `(ior, 1)` leaving.
pub fn indices(ior: f64, front: bool) -> (f64, f64) {
    let ior = if ior > 0.0 { ior } else { 1.0 };
    if front { (1.0, ior) } else { (ior, 1.0) }
}

/// The exact unpolarized Fresnel reflectance for light arriving at the
/// angle with cosine `cos_i` (≥ 0) from the medium of index `n1` onto the
/// medium of index `n2`.
pub fn fresnel(cos_i: f64, n1: f64, n2: f64) -> f64 {
    if n1 == n2 {
        return 0.0;
    }
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (n1 / n2).powi(2) * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    let r = 0.5 * (rs * rs + rp * rp);
    if r.is_finite() {
        r.clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// The fraction `exp(−σ s)` of light kept over the distance `s`.
#[inline]
pub fn beer_lambert(absorption: &Color, distance: f64) -> Color {
    absorption.map(|sigma| (-sigma * distance).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_flips_the_normal_component() {
        let d = Vector3::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(&d, &Vector3::y());
        assert!((r - Vector3::new(1.0, 1.0, 0.0).normalize()).norm() < 1e-15);
    }

    #[test]
    fn refraction_obeys_snell() {
        let d = Vector3::new(0.6, -0.8, 0.0);
        let n = Vector3::y();
        let t = refract(&d, &n, 1.0 / 1.5).unwrap();
        assert!((t.norm() - 1.0).abs() < 1e-12);
        // sin θ₂ = sin θ₁ / 1.5
        assert!((t.x - 0.6 / 1.5).abs() < 1e-12);
        assert!(t.y < 0.0);
        // Equal indices: straight through.
        assert!((refract(&d, &n, 1.0).unwrap() - d).norm() < 1e-15);
    }

    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        // Critical angle for glass→air: sin θ = 1/1.5 ≈ 0.667.
        let d = Vector3::new(0.7, -(1.0f64 - 0.49).sqrt(), 0.0);
        assert!(refract(&d, &Vector3::y(), 1.5).is_none());
        assert_eq!(fresnel(d.y.abs(), 1.5, 1.0), 1.0);
        let d = Vector3::new(0.6, -0.8, 0.0);
        assert!(refract(&d, &Vector3::y(), 1.5).is_some());
    }

    #[test]
    fn fresnel_matches_known_values() {
        // Normal incidence: ((n1 − n2)/(n1 + n2))² = 0.04 for glass.
        assert!((fresnel(1.0, 1.0, 1.5) - 0.04).abs() < 1e-15);
        assert!((fresnel(1.0, 1.5, 1.0) - 0.04).abs() < 1e-15);
        assert_eq!(fresnel(0.3, 1.33, 1.33), 0.0);
        // Grazing incidence reflects everything.
        assert!((fresnel(0.0, 1.0, 1.5) - 1.0).abs() < 1e-12);
        // Brewster's angle: r_p = 0, so R = r_s²/2.
        let theta_b = 1.5f64.atan();
        let r = fresnel(theta_b.cos(), 1.0, 1.5);
        let cos_t = (1.0 - (theta_b.sin() / 1.5).powi(2)).sqrt();
        let rs = (theta_b.cos() - 1.5 * cos_t) / (theta_b.cos() + 1.5 * cos_t);
        assert!((r - rs * rs / 2.0).abs() < 1e-12);
    }

    #[test]
    fn absorption_is_exponential_in_distance() {
        let sigma = Color::new(0.0, 1.0, 2.0);
        let k = beer_lambert(&sigma, 0.5);
        assert_eq!(k.x, 1.0);
        assert!((k.y - (-0.5f64).exp()).abs() < 1e-15);
        let k2 = beer_lambert(&sigma, 1.0);
        assert!((k2.z - k.z * k.z).abs() < 1e-15);
    }
}

//! The Newton intersector tests' surface and rays: a cubic Bézier vase with
//! a pole, a small xorshift64 generator and random rays toward a box (shared
//! by the Newton tests and the allocation tests, so both see the same rays).

use crate::bezier;
use revolve::nalgebra::Vector3;
use revolve::{Aabb, Bezier, Ray, Revolution};
use std::f64::consts::TAU;

/// A cubic Bézier vase: a flat bottom meeting the axis at a pole, a belly
/// and a flaring neck.
pub const POLE_VASE: [(f64, f64); 4] = [(0.0, 0.0), (1.4, 0.0), (0.1, 1.6), (0.6, 2.0)];

/// [`POLE_VASE`], revolved.
pub fn pole_vase() -> Revolution<Bezier<2>> {
    bezier(&POLE_VASE)
}

/// A deterministic generator of uniform numbers in `[0, 1)` (xorshift64).
pub struct Xorshift64(pub u64);

// `next` is the next number in `[0, 1)`, not an iterator's `Option`.
#[allow(clippy::should_implement_trait)]
impl Xorshift64 {
    pub fn new(seed: u64) -> Self {
        Xorshift64(seed.max(1))
    }

    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1_u64 << 53) as f64
    }

    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

/// A ray from a random point on the sphere of radius `5·scale` about the
/// box's centre toward a random point of the box (most such rays hit), with a
/// direction of random length.
pub fn random_ray(rng: &mut Xorshift64, b: &Aabb) -> Ray {
    let theta = rng.range(0.0, TAU);
    let cos_phi = rng.range(-1.0, 1.0);
    let sin_phi = (1.0 - cos_phi * cos_phi).sqrt();
    let radius = 5.0 * b.extent().norm();
    let o =
        b.center() + Vector3::new(sin_phi * theta.cos(), cos_phi, sin_phi * theta.sin()) * radius;
    let e = b.extent();
    let target = b.min + Vector3::new(rng.next() * e.x, rng.next() * e.y, rng.next() * e.z);
    Ray::new(o, (target - o) * rng.range(0.1, 3.0))
}

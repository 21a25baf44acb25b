//! The slab test of a ray against an axis-aligned box: [`Aabb::clip`] for
//! one box, and [`Slab`], the ray's reciprocal direction computed once for
//! the many boxes of a hierarchy.

use super::Ray;
use crate::Aabb;
use nalgebra::Point3;

impl Aabb {
    /// The parameter interval `[t_enter, t_exit]` in which the ray is inside
    /// the closed box, clipped to `[t_min, t_max]`; `None` when they do not
    /// overlap (the slab test).
    ///
    /// Direction components that are zero are handled without dividing: the
    /// ray is then inside that slab for all `t` or for none. The comparisons
    /// are arranged so that a NaN from `0 · ∞` never passes as a hit. A ray
    /// or range with a NaN, or `t_min > t_max`, gives `None`.
    pub fn clip(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        let nan_ray = ray.origin.iter().chain(ray.dir.iter()).any(|c| c.is_nan());
        let bad_range = t_min > t_max || t_min.is_nan() || t_max.is_nan();
        if self.is_empty() || nan_ray || bad_range {
            return None;
        }
        let (mut lo, mut hi) = (t_min, t_max);
        for i in 0..3 {
            let (o, d) = (ray.origin[i], ray.dir[i]);
            if d == 0.0 {
                if o < self.min[i] || o > self.max[i] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / d;
            let (mut t0, mut t1) = ((self.min[i] - o) * inv, (self.max[i] - o) * inv);
            if t0 > t1 {
                std::mem::swap(&mut t0, &mut t1);
            }
            // Written so that NaN keeps the old bound.
            if t0 > lo {
                lo = t0;
            }
            if t1 < hi {
                hi = t1;
            }
            if lo > hi || lo.is_nan() || hi.is_nan() {
                return None;
            }
        }
        Some((lo, hi))
    }
}

/// The ray's slab data, computed once per ray.
pub(crate) struct Slab {
    origin: Point3<f64>,
    inverse: [f64; 3],
}

impl Slab {
    /// The slab data of `ray` (a finite origin and direction).
    pub(crate) fn new(ray: &Ray) -> Self {
        Slab {
            origin: ray.origin,
            inverse: [1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z],
        }
    }

    /// Where the ray enters `b` within `[lo, hi]`, if it meets it there.
    /// A zero direction component (infinite inverse) keeps the range when
    /// the origin is within the slab and empties it otherwise.
    #[inline]
    pub(crate) fn enter(&self, b: &Aabb, lo: f64, hi: f64) -> Option<f64> {
        let (mut lo, mut hi) = (lo, hi);
        for i in 0..3 {
            let inv = self.inverse[i];
            let (a, c) = (b.min[i] - self.origin[i], b.max[i] - self.origin[i]);
            if inv.is_infinite() {
                if a > 0.0 || c < 0.0 {
                    return None;
                }
                continue;
            }
            let (t0, t1) = (a * inv, c * inv);
            let (t0, t1) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
            lo = lo.max(t0);
            hi = hi.min(t1);
        }
        (lo <= hi).then_some(lo)
    }
}

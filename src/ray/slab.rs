//! The slab test of a ray against one axis-aligned box, [`Aabb::clip`]
//! (a hierarchy's many boxes use [`BoxRay`](super::bvh::BoxRay)).

use super::Ray;
use crate::Aabb;

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

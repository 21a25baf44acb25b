//! Axis-aligned bounding boxes and the slab test.

use crate::ray::Ray;
use nalgebra::{Isometry3, Point3, Vector3};

/// An axis-aligned box `[min, max]` in 3D. A box with `min > max` on some axis
/// is empty ([`Aabb::EMPTY`]); it contains nothing and no ray hits it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// The corner with the smallest coordinates.
    pub min: Point3<f64>,
    /// The corner with the largest coordinates.
    pub max: Point3<f64>,
}

impl Aabb {
    /// The empty box: the identity of [`union`](Self::union).
    pub const EMPTY: Aabb = Aabb {
        min: Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
        max: Point3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    /// The box with the given corners (their coordinates are sorted per axis).
    pub fn new(a: Point3<f64>, b: Point3<f64>) -> Self {
        Aabb {
            min: a.inf(&b),
            max: a.sup(&b),
        }
    }

    /// The smallest box containing all the points (empty for none).
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> Self {
        points.into_iter().fold(Self::EMPTY, |b, p| b.include(p))
    }

    /// Whether the box contains nothing.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// The box grown to contain `p`.
    pub fn include(&self, p: &Point3<f64>) -> Self {
        Aabb {
            min: self.min.inf(p),
            max: self.max.sup(p),
        }
    }

    /// The smallest box containing both boxes.
    pub fn union(&self, other: &Aabb) -> Self {
        Aabb {
            min: self.min.inf(&other.min),
            max: self.max.sup(&other.max),
        }
    }

    /// The box grown by `margin` on every side.
    pub fn expand(&self, margin: f64) -> Self {
        let m = Vector3::repeat(margin);
        Aabb {
            min: self.min - m,
            max: self.max + m,
        }
    }

    /// The smallest box containing this box moved by the rigid motion `m`:
    /// the centre is moved, and the half-extents are multiplied by the
    /// absolute rotation matrix (exact for the box of a rotated box).
    pub fn transformed(&self, m: &Isometry3<f64>) -> Self {
        if self.is_empty() {
            return *self;
        }
        let center = m * self.center();
        let half = m.rotation.to_rotation_matrix().matrix().abs() * (self.extent() * 0.5);
        Aabb {
            min: center - half,
            max: center + half,
        }
    }

    /// Whether `p` lies in the closed box.
    pub fn contains(&self, p: &Point3<f64>) -> bool {
        (0..3).all(|i| self.min[i] <= p[i] && p[i] <= self.max[i])
    }

    /// The centre of the box.
    pub fn center(&self) -> Point3<f64> {
        nalgebra::center(&self.min, &self.max)
    }

    /// The edge lengths.
    pub fn extent(&self) -> Vector3<f64> {
        self.max - self.min
    }

    /// The largest absolute coordinate of the box: its scale for relative
    /// tolerances.
    pub fn scale(&self) -> f64 {
        self.min.coords.amax().max(self.max.coords.amax())
    }

    /// The parameter interval `[t_enter, t_exit]` in which the ray is inside
    /// the closed box, clipped to `[t_min, t_max]`; `None` when they do not
    /// overlap (the slab test).
    ///
    /// Direction components that are zero are handled without dividing: the
    /// ray is then inside that slab for all `t` or for none. The comparisons
    /// are arranged so that a NaN from `0 · ∞` never passes as a hit.
    pub fn clip(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, f64)> {
        if self.is_empty() {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb::new(Point3::new(-1.0, -1.0, -1.0), Point3::new(1.0, 1.0, 1.0))
    }

    #[test]
    fn slab_test_enters_and_exits() {
        let r = Ray::new(Point3::new(-5.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0));
        assert_eq!(unit().clip(&r, 0.0, f64::INFINITY), Some((2.0, 3.0)));
        assert_eq!(unit().clip(&r, 2.5, 10.0), Some((2.5, 3.0)));
        assert_eq!(unit().clip(&r, 3.5, 10.0), None);
    }

    #[test]
    fn axis_parallel_rays_outside_a_slab_miss() {
        let r = Ray::new(Point3::new(-5.0, 2.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
        assert_eq!(unit().clip(&r, 0.0, f64::INFINITY), None);
        // On the boundary plane: inside the closed slab.
        let r = Ray::new(Point3::new(-5.0, 1.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
        assert_eq!(unit().clip(&r, 0.0, f64::INFINITY), Some((4.0, 6.0)));
    }

    #[test]
    fn transformed_box_is_the_box_of_the_moved_corners() {
        let b = Aabb::new(Point3::new(-1.0, 0.5, -2.0), Point3::new(3.0, 2.0, 1.0));
        let m = Isometry3::new(Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.3, -0.7, 1.1));
        let corners: Vec<Point3<f64>> = (0..8)
            .map(|i| {
                let pick = |bit: usize, k: usize| if i & bit == 0 { b.min[k] } else { b.max[k] };
                m * Point3::new(pick(1, 0), pick(2, 1), pick(4, 2))
            })
            .collect();
        let want = Aabb::from_points(&corners);
        let got = b.transformed(&m);
        assert!((got.min - want.min).norm() < 1e-14 && (got.max - want.max).norm() < 1e-14);
        assert!(Aabb::EMPTY.transformed(&m).is_empty());
    }

    #[test]
    fn empty_box_is_never_hit() {
        let r = Ray::new(Point3::origin(), Vector3::new(1.0, 1.0, 1.0));
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.clip(&r, 0.0, f64::INFINITY), None);
        let b = Aabb::from_points(&[Point3::new(1.0, 2.0, 3.0), Point3::new(-1.0, 0.0, 5.0)]);
        assert_eq!(b.min, Point3::new(-1.0, 0.0, 3.0));
        assert_eq!(b.max, Point3::new(1.0, 2.0, 5.0));
    }
}

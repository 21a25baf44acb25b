//! Axis-aligned bounding boxes and the slab test.

use nalgebra::{Isometry3, Point3, Vector3};

/// An axis-aligned box `[min, max]` in 3D. A box with `min > max`, a NaN,
/// `min = +∞` or `max = −∞` on some axis contains no finite point: it is
/// empty (like [`Aabb::EMPTY`]), and no ray hits it. Infinite boxes (ends at
/// `±∞`) are allowed.
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

    /// Whether the box contains no finite point: on some axis `min > max`,
    /// a NaN, `min = +∞` or `max = −∞`.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| {
            let (lo, hi) = (self.min[i], self.max[i]);
            lo > hi || lo.is_nan() || hi.is_nan() || lo == f64::INFINITY || hi == f64::NEG_INFINITY
        })
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

    /// The box grown by `margin` on every side (shrunk for a negative one).
    /// An empty box, or a NaN margin, gives [`Aabb::EMPTY`].
    pub fn expand(&self, margin: f64) -> Self {
        if self.is_empty() || margin.is_nan() {
            return Aabb::EMPTY;
        }
        let m = Vector3::repeat(margin);
        Aabb {
            min: self.min - m,
            max: self.max + m,
        }
    }

    /// The smallest box containing this box moved by the rigid motion `m`
    /// (`x ↦ Rx + t`), by interval arithmetic: on axis `i`,
    /// `tᵢ + Σⱼ min(Rᵢⱼ minⱼ, Rᵢⱼ maxⱼ)` to `tᵢ + Σⱼ max(…)`, terms with
    /// `Rᵢⱼ = 0` left out. Exact for the box of a rotated box; infinite boxes
    /// stay infinite only along the axes they reach, and no NaN arises. An
    /// empty box stays empty.
    pub fn transformed(&self, m: &Isometry3<f64>) -> Self {
        if self.is_empty() {
            return *self;
        }
        let r = m.rotation.to_rotation_matrix();
        let t = m.translation.vector;
        let mut out = Aabb {
            min: Point3::from(t),
            max: Point3::from(t),
        };
        for i in 0..3 {
            for j in 0..3 {
                let rij = r[(i, j)];
                if rij == 0.0 {
                    continue;
                }
                let (a, b) = (rij * self.min[j], rij * self.max[j]);
                out.min[i] += a.min(b);
                out.max[i] += a.max(b);
            }
        }
        out
    }

    /// Whether `p` lies in the closed box.
    pub fn contains(&self, p: &Point3<f64>) -> bool {
        (0..3).all(|i| self.min[i] <= p[i] && p[i] <= self.max[i])
    }

    /// The centre of the box: per axis `(min + max)/2`, computed without
    /// overflow; `0` on an axis infinite both ways, `±∞` on a half-infinite
    /// one. The centre of an empty box is the origin.
    pub fn center(&self) -> Point3<f64> {
        if self.is_empty() {
            return Point3::origin();
        }
        Point3::from(Vector3::from_fn(|i, _| {
            let (lo, hi) = (self.min[i], self.max[i]);
            let sum = lo + hi;
            if sum.is_finite() {
                0.5 * sum
            } else if lo == f64::NEG_INFINITY && hi == f64::INFINITY {
                0.0
            } else {
                0.5 * lo + 0.5 * hi
            }
        }))
    }

    /// The edge lengths `max − min` (infinite for an infinite box, or when
    /// the difference overflows); zero for an empty box.
    pub fn extent(&self) -> Vector3<f64> {
        if self.is_empty() {
            return Vector3::zeros();
        }
        self.max - self.min
    }

    /// The largest absolute coordinate of the box: its scale for relative
    /// tolerances. Zero for an empty box.
    pub fn scale(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        self.min.coords.amax().max(self.max.coords.amax())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Ray;

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

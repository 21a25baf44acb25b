//! Placing an object in the world by its object-to-world matrix.
//!
//! `M` is affine: `p_world = L·p + c` with `L` its upper-left 3×3 block and
//! `c` its last column (the bottom row is taken to be `(0, 0, 0, 1)` and not
//! read). `L` may hold rotations, reflections and non-uniform scales.
//!
//! - A world ray `o + t·d` becomes the object-frame ray `L⁻¹(o − c) + t·L⁻¹d`.
//!   The direction is *not* normalized, so a hit's `t` in the object frame is
//!   the world `t`, and `t_min`/`t_max` pass through unchanged.
//! - Points map by `M`, tangent vectors by `L`, normals by the inverse
//!   transpose `L⁻ᵀ` (if `v` is tangent, `n·v = 0`, then
//!   `(L⁻ᵀn)·(Lv) = n·v = 0`); the orientation is kept even when `det L < 0`.
//! - The world box of an object is the box of its local box's eight corners
//!   under `M` (exact for the box of a transformed box).
//!
//! All matrices are computed once, at build time. A matrix that is singular
//! or holds non-finite entries places nothing: such objects are dropped.

use revolve::nalgebra::{Matrix3, Matrix4, Point3, Vector3};
use revolve::{Aabb, Ray};

/// An affine object-to-world map and the inverses that rays and normals use.
#[derive(Debug, Clone)]
pub struct Frame {
    linear: Matrix3<f64>,
    translation: Vector3<f64>,
    inverse: Matrix3<f64>,
    /// `L⁻ᵀ`.
    normal: Matrix3<f64>,
}

impl Frame {
    /// The frame of `m`, or `None` when it is singular or not finite.
    pub fn new(m: &Matrix4<f64>) -> Option<Frame> {
        if !m.iter().all(|x| x.is_finite()) {
            return None;
        }
        let linear: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
        let translation: Vector3<f64> = m.fixed_view::<3, 1>(0, 3).into_owned();
        let inverse = linear.try_inverse()?;
        if !inverse.iter().all(|x| x.is_finite()) {
            return None;
        }
        Some(Frame {
            linear,
            translation,
            inverse,
            normal: inverse.transpose(),
        })
    }

    /// The world ray in the object frame (direction not normalized).
    #[inline]
    pub fn ray_to_local(&self, ray: &Ray) -> Ray {
        Ray {
            origin: Point3::from(self.inverse * (ray.origin.coords - self.translation)),
            dir: self.inverse * ray.dir,
        }
    }

    /// An object-frame point in the world.
    #[inline]
    pub fn point(&self, p: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.linear * p.coords + self.translation)
    }

    /// An object-frame tangent vector in the world.
    #[inline]
    pub fn vector(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.linear * v
    }

    /// An object-frame normal in the world (`L⁻ᵀn`, not normalized).
    #[inline]
    pub fn normal(&self, n: &Vector3<f64>) -> Vector3<f64> {
        self.normal * n
    }

    /// The world box of an object-frame box (its eight corners mapped).
    pub fn bounds(&self, b: &Aabb) -> Aabb {
        if b.is_empty() {
            return *b;
        }
        (0..8).fold(Aabb::EMPTY, |acc, i| {
            let pick = |bit: usize, k: usize| if i & bit == 0 { b.min[k] } else { b.max[k] };
            acc.include(&self.point(&Point3::new(pick(1, 0), pick(2, 1), pick(4, 2))))
        })
    }

    /// The scale `s` when `L = s·R` with `R` orthogonal (a similarity, to a
    /// relative `1e-9` on `LᵀL = s²I`), else `None`.
    pub fn similarity_scale(&self) -> Option<f64> {
        let g = self.linear.transpose() * self.linear;
        let s2 = g.trace() / 3.0;
        let off = (g - Matrix3::identity() * s2).amax();
        (s2 > 0.0 && off <= 1e-9 * s2).then(|| s2.sqrt())
    }
}

//! Ray–object intersection for the whole scene: every shape of
//! [`crate::scene::Shape`] in its own frame, placed by its transform, behind
//! a bounding volume hierarchy. Being written.

use revolve::Ray;
use revolve::nalgebra::{Point3, Unit, Vector3};

use crate::scene::Scene;

/// The nearest hit of a ray with the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// Ray parameter (in units of the world ray's direction).
    pub t: f64,
    /// World-space hit point.
    pub point: Point3<f64>,
    /// World-space unit geometric normal, oriented outward for closed
    /// shapes (spheres, boxes, meshes as written, revolution bodies
    /// oriented so that it points away from the inside of the body); as
    /// given for open ones (planes, disks, triangles). Not flipped toward
    /// the ray: the renderer does that where it needs to.
    pub normal: Unit<Vector3<f64>>,
    /// Texture coordinates in `[0, 1]²`.
    pub uv: (f64, f64),
    /// Index into `Scene::objects`.
    pub object: usize,
}

/// Time spent in revolution intersection, for the report.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IntersectStats {
    /// Calls of revolve's exact intersector.
    pub revolution_calls: u64,
    /// Nanoseconds spent in them.
    pub revolution_nanos: u64,
}

/// The scene's objects ready for ray queries (world bounds, BVH).
pub struct World {
    _private: (),
}

impl World {
    /// Builds the acceleration structures for `scene`'s objects.
    pub fn new(_scene: &Scene) -> World {
        todo!("geometry helper")
    }

    /// The nearest hit with `t_min < t < t_max`.
    pub fn intersect(
        &self,
        _ray: &Ray,
        _t_min: f64,
        _t_max: f64,
        _stats: &mut IntersectStats,
    ) -> Option<SurfaceHit> {
        todo!("geometry helper")
    }

    /// Whether anything lies on the ray with `t_min < t < t_max` (shadow
    /// rays; may stop at the first hit found).
    pub fn occluded(
        &self,
        _ray: &Ray,
        _t_min: f64,
        _t_max: f64,
        _stats: &mut IntersectStats,
    ) -> bool {
        todo!("geometry helper")
    }
}

/// An object whose material emits light, sampled uniformly by area for
/// next-event estimation (rectangles, disks, spheres, triangles, meshes and
/// boxes; other emissive shapes only light what their rays happen to hit).
pub struct Emitter {
    /// Index into `Scene::objects`.
    pub object: usize,
    _private: (),
}

impl Emitter {
    /// World-space area.
    pub fn area(&self) -> f64 {
        todo!("geometry helper")
    }

    /// The point for `(a, b) ∈ [0, 1)²` (uniform by area) and its unit
    /// normal there (oriented as `SurfaceHit::normal`).
    pub fn sample(&self, _a: f64, _b: f64) -> (Point3<f64>, Unit<Vector3<f64>>) {
        todo!("geometry helper")
    }
}

impl World {
    /// The emissive objects that can be sampled.
    pub fn emitters(&self) -> &[Emitter] {
        todo!("geometry helper")
    }
}

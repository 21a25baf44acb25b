//! Ray–object intersection for the whole scene: every shape of
//! [`crate::scene::Shape`] in its own frame, placed by its transform, behind
//! a bounding volume hierarchy.
//!
//! - [`shapes`]: sphere, plane, triangle, box, disk/ring, rectangle;
//!   [`mesh`], [`tube`], [`revolution`], [`surface`]: the composite shapes.
//! - [`transform`]: rays into an object's frame by `M⁻¹` (direction not
//!   normalized, so `t` is the world `t`), normals out by `L⁻ᵀ`.
//! - [`object`]: a shape and its placement; [`bvh`] (the library's): the hierarchy used for
//!   the world and inside meshes and tubes; [`emitter`]: area-light sampling;
//!   [`batch`]: the nearest hits of several rays at once.
//!
//! Bounded objects sit in a BVH over their world boxes (the box of the local
//! box's eight corners under the transform); unbounded ones (planes) in a
//! list tested for every ray. Objects that can never be hit (degenerate
//! shapes, singular transforms) are left out at build time. Queries do not
//! allocate.

/// Rays traced together at most (longer batches are cut into chunks).
pub const LANES: usize = 8;

mod batch;
mod emitter;
mod mesh;
mod object;
mod revolution;
mod shapes;
mod surface;
#[cfg(test)]
mod surface_tests;
#[cfg(test)]
mod tests;
mod transform;
mod tube;

use std::ops::ControlFlow;

use revolve::Ray;
use revolve::nalgebra::{Point3, Unit, Vector3};

use crate::scene::Scene;
use object::{Placed, Shared};
use revolve::ray::bvh;
use revolve::{BoxRay, Bvh};
use shapes::LocalHit;

pub use emitter::Emitter;

/// Objects per BVH leaf: one, since an object test (a transform, maybe a
/// revolution solve) costs more than a box test.
const WORLD_LEAF: usize = 1;

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

impl SurfaceHit {
    /// The normal on the side the ray `d` comes from, and whether that is
    /// the front (`d·n ≤ 0` for the stored normal `n`: the ray enters a
    /// closed body).
    pub fn facing(&self, d: &Vector3<f64>) -> (Vector3<f64>, bool) {
        let outward = self.normal.into_inner();
        let front = d.dot(&outward) <= 0.0;
        (if front { outward } else { -outward }, front)
    }
}

/// Time spent in revolution intersection, for the report.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IntersectStats {
    /// Calls of revolve's exact intersector.
    pub revolution_calls: u64,
    /// Nanoseconds spent in them.
    pub revolution_nanos: u64,
}

impl std::ops::AddAssign for IntersectStats {
    /// Sums the counters (to merge per-thread statistics).
    fn add_assign(&mut self, other: IntersectStats) {
        self.revolution_calls += other.revolution_calls;
        self.revolution_nanos += other.revolution_nanos;
    }
}

/// The nearest hit `local` of `ray`, on `placed`, in the world.
#[inline(always)]
fn surface_hit(ray: &Ray, placed: &Placed, local: LocalHit) -> Option<SurfaceHit> {
    let h = placed.to_world(local);
    // A zero normal cannot come from a valid shape; face the ray then.
    let normal = Unit::try_new(h.normal, 0.0)
        .filter(|n| n.iter().all(|c| c.is_finite()))
        .or_else(|| Unit::try_new(-ray.dir, 0.0))?;
    Some(SurfaceHit {
        t: h.t,
        point: h.point,
        normal,
        uv: h.uv,
        object: placed.object,
    })
}

/// The scene's objects ready for ray queries (world bounds, BVH).
pub struct World {
    /// Bounded objects in BVH leaf order.
    bounded: Vec<Placed>,
    bvh: Bvh,
    /// Planes and anything else without a finite box.
    unbounded: Vec<Placed>,
    emitters: Vec<Emitter>,
}

impl World {
    /// Builds the acceleration structures for `scene`'s objects.
    ///
    /// Meshes, revolution bodies and tubes shared between objects (the same
    /// `Arc`) are prepared once. An object with emission in its material
    /// (any component `> 0`) becomes an [`Emitter`] if its shape can be
    /// sampled.
    pub fn new(scene: &Scene) -> World {
        let mut shared = Shared::default();
        let (mut bounded, mut boxes, mut unbounded) = (Vec::new(), Vec::new(), Vec::new());
        let mut emitters = Vec::new();
        for (index, object) in scene.objects.iter().enumerate() {
            let Some(placed) = Placed::new(index, object, &mut shared) else {
                continue;
            };
            let emissive = scene
                .materials
                .get(object.material)
                .is_some_and(|m| m.emission.iter().any(|&c| c > 0.0));
            if emissive {
                emitters.extend(Emitter::new(index, &object.shape, placed.frame.as_ref()));
            }
            match placed.world_bounds() {
                Some(b) if b.is_empty() => {}
                Some(b) => {
                    boxes.push(bvh::pad(&b));
                    bounded.push(Some(placed));
                }
                None => unbounded.push(placed),
            }
        }
        let (bvh, order) = Bvh::build(&boxes, WORLD_LEAF);
        let bounded = order
            .into_iter()
            .filter_map(|i| bounded[i].take())
            .collect();
        World {
            bounded,
            bvh,
            unbounded,
            emitters,
        }
    }

    /// The nearest hit with `t_min < t < t_max`.
    pub fn intersect(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut IntersectStats,
    ) -> Option<SurfaceHit> {
        let mut best: Option<(&Placed, LocalHit)> = None;
        let mut t_max = t_max;
        for p in &self.unbounded {
            if let Some(h) = p.intersect(ray, t_min, t_max, stats) {
                t_max = h.t;
                best = Some((p, h));
            }
        }
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                let p = &self.bounded[k];
                match p.intersect(ray, t_min, t_max, stats) {
                    Some(h) => {
                        best = Some((p, h));
                        ControlFlow::Continue(h.t)
                    }
                    None => ControlFlow::Continue(t_max),
                }
            });
        let (placed, local) = best?;
        surface_hit(ray, placed, local)
    }

    /// Whether anything lies on the ray with `t_min < t < t_max` (shadow
    /// rays; may stop at the first hit found).
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut IntersectStats) -> bool {
        if self
            .unbounded
            .iter()
            .any(|p| p.occluded(ray, t_min, t_max, stats))
        {
            return true;
        }
        let mut hit = false;
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                if self.bounded[k].occluded(ray, t_min, t_max, stats) {
                    hit = true;
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(t_max)
                }
            });
        hit
    }

    /// The emissive objects that can be sampled.
    pub fn emitters(&self) -> &[Emitter] {
        &self.emitters
    }
}

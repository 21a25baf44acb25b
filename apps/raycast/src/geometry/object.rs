//! One scene object ready for ray queries: its shape prepared in its own
//! frame ([`Prim`]) and its placement ([`Frame`], absent for the identity).
//!
//! Queries take the world ray; a placed object maps it into its frame (see
//! [`super::transform`]) and returns the hit still in the object frame, with
//! `t` equal to the world `t`. Only the nearest hit of the whole scene is
//! mapped back to the world ([`Placed::to_world`]).

use std::collections::HashMap;
use std::sync::Arc;

use revolve::nalgebra::{Matrix4, Point3, Vector3};
use revolve::{Aabb, Ray};

use super::IntersectStats;
use super::LANES;
use super::mesh::MeshShape;
use super::revolution::RevolutionShape;
use super::shapes::{Annulus, BoxShape, LocalHit, Parallelogram, Plane, Sphere, Triangle};
use super::surface::SurfaceShape;
use super::transform::Frame;
use super::tube::TubeShape;
use crate::scene::{Object, RevolutionBody, Shape, SurfaceBody, TriangleMesh, Tube};

/// A shape prepared for intersection in its own frame.
#[derive(Debug, Clone)]
pub enum Prim {
    Sphere(Sphere),
    Plane(Plane),
    Triangle(Triangle),
    Mesh(Arc<MeshShape>),
    Box(BoxShape),
    /// Disk or ring.
    Annulus(Annulus),
    Rectangle(Parallelogram),
    Revolution(Arc<RevolutionShape>),
    Tube(Arc<TubeShape>),
    /// A tensor-product surface or a Bézier patch model.
    Surface(Arc<SurfaceShape>),
}

/// Prepared meshes, revolution bodies, tubes and surfaces by the address of the
/// scene's `Arc`, so that an instanced one is prepared once.
#[derive(Default)]
pub struct Shared {
    meshes: HashMap<*const TriangleMesh, Option<Arc<MeshShape>>>,
    revolutions: HashMap<*const RevolutionBody, Option<Arc<RevolutionShape>>>,
    tubes: HashMap<*const Tube, Option<Arc<TubeShape>>>,
    surfaces: HashMap<*const SurfaceBody, Option<Arc<SurfaceShape>>>,
}

impl Prim {
    /// The prepared shape; `None` for degenerate input that can never be
    /// hit (zero radius or area, zero normal, no valid triangle, …).
    pub fn new(shape: &Shape, shared: &mut Shared) -> Option<Prim> {
        Some(match shape {
            Shape::Sphere { center, radius } => Prim::Sphere(Sphere::new(*center, *radius)?),
            Shape::Plane { normal, offset } => Prim::Plane(Plane::new(*normal, *offset)?),
            Shape::Triangle { vertices } => Prim::Triangle(Triangle::new(*vertices)?),
            Shape::Mesh(m) => Prim::Mesh(
                shared
                    .meshes
                    .entry(Arc::as_ptr(m))
                    .or_insert_with(|| MeshShape::new(m).map(Arc::new))
                    .clone()?,
            ),
            Shape::Box { min, max } => Prim::Box(BoxShape::new(*min, *max)?),
            Shape::Disk {
                center,
                normal,
                radius,
            } => Prim::Annulus(Annulus::new(*center, *normal, 0.0, *radius)?),
            Shape::Ring {
                center,
                normal,
                inner,
                outer,
            } => Prim::Annulus(Annulus::new(*center, *normal, *inner, *outer)?),
            Shape::Rectangle {
                corner,
                edge1,
                edge2,
            } => Prim::Rectangle(Parallelogram::new(*corner, *edge1, *edge2)?),
            Shape::Revolution(body) => Prim::Revolution(
                shared
                    .revolutions
                    .entry(Arc::as_ptr(body))
                    .or_insert_with(|| RevolutionShape::new(body.clone()).map(Arc::new))
                    .clone()?,
            ),
            Shape::Tube(tube) => Prim::Tube(
                shared
                    .tubes
                    .entry(Arc::as_ptr(tube))
                    .or_insert_with(|| TubeShape::new(tube).map(Arc::new))
                    .clone()?,
            ),
            Shape::Surface(body) => Prim::Surface(
                shared
                    .surfaces
                    .entry(Arc::as_ptr(body))
                    .or_insert_with(|| SurfaceShape::new(body.clone()).map(Arc::new))
                    .clone()?,
            ),
        })
    }

    /// The object-frame box (infinite for a plane).
    pub fn bounds(&self) -> Aabb {
        match self {
            Prim::Sphere(s) => s.bounds(),
            Prim::Plane(p) => p.bounds(),
            Prim::Triangle(t) => t.bounds(),
            Prim::Mesh(m) => m.bounds(),
            Prim::Box(b) => b.bounds(),
            Prim::Annulus(a) => a.bounds(),
            Prim::Rectangle(r) => r.bounds(),
            Prim::Revolution(r) => r.bounds(),
            Prim::Tube(t) => t.bounds(),
            Prim::Surface(s) => s.bounds(),
        }
    }

    /// The nearest hit in the object frame.
    #[inline]
    pub fn intersect(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut IntersectStats,
    ) -> Option<LocalHit> {
        match self {
            Prim::Sphere(s) => s.intersect(ray, t_min, t_max),
            Prim::Plane(p) => p.intersect(ray, t_min, t_max),
            Prim::Triangle(t) => t.intersect(ray, t_min, t_max),
            Prim::Mesh(m) => m.intersect(ray, t_min, t_max),
            Prim::Box(b) => b.intersect(ray, t_min, t_max),
            Prim::Annulus(a) => a.intersect(ray, t_min, t_max),
            Prim::Rectangle(r) => r.intersect(ray, t_min, t_max),
            Prim::Revolution(r) => r.intersect(ray, t_min, t_max, stats),
            Prim::Tube(t) => t.intersect(ray, t_min, t_max),
            Prim::Surface(s) => s.intersect(ray, t_min, t_max),
        }
    }

    /// [`Self::intersect`] for each lane (at most [`LANES`]): `out[i]` for
    /// `rays[i]` in `ranges[i]`; revolution bodies answer the lanes together.
    #[inline]
    pub fn intersect_batch(
        &self,
        rays: &[Ray],
        ranges: &[(f64, f64)],
        out: &mut [Option<LocalHit>],
        stats: &mut IntersectStats,
    ) {
        match self {
            Prim::Revolution(r) => r.intersect_batch(rays, ranges, out, stats),
            _ => {
                for ((ray, &(t_min, t_max)), o) in rays.iter().zip(ranges).zip(out) {
                    *o = self.intersect(ray, t_min, t_max, stats);
                }
            }
        }
    }

    /// The UV of a hit from [`intersect`](Self::intersect) (computed here,
    /// for the nearest hit only, by the shapes that defer it).
    pub fn uv(&self, hit: &LocalHit) -> (f64, f64) {
        match self {
            Prim::Sphere(s) => s.uv(hit),
            Prim::Plane(p) => p.uv(hit),
            Prim::Annulus(a) => a.uv(hit),
            _ => hit.uv,
        }
    }

    /// Whether anything is hit (meshes, tubes, revolutions and surfaces stop
    /// at the first).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut IntersectStats) -> bool {
        match self {
            Prim::Mesh(m) => m.occluded(ray, t_min, t_max),
            Prim::Tube(t) => t.occluded(ray, t_min, t_max),
            Prim::Revolution(r) => r.occluded(ray, t_min, t_max, stats),
            Prim::Surface(s) => s.occluded(ray, t_min, t_max),
            Prim::Triangle(t) => t.hit(ray, t_min, t_max).is_some(),
            _ => self.intersect(ray, t_min, t_max, stats).is_some(),
        }
    }
}

/// A scene object: its index in `Scene::objects`, shape and placement.
#[derive(Debug, Clone)]
pub struct Placed {
    pub object: usize,
    pub prim: Prim,
    pub frame: Option<Frame>,
}

impl Placed {
    /// The object's prepared shape and frame; `None` when it can never be
    /// hit (degenerate shape, singular or non-finite transform). An identity
    /// transform is dropped.
    pub fn new(index: usize, object: &Object, shared: &mut Shared) -> Option<Placed> {
        let frame = match &object.transform {
            Some(m) if *m != Matrix4::identity() => Some(Frame::new(m)?),
            _ => None,
        };
        Some(Placed {
            object: index,
            prim: Prim::new(&object.shape, shared)?,
            frame,
        })
    }

    /// The world box: `None` when unbounded (a plane; or coordinates beyond
    /// `1e100`, too large for the BVH's arithmetic); empty when the object
    /// can never be hit.
    pub fn world_bounds(&self) -> Option<Aabb> {
        let local = self.prim.bounds();
        if local.is_empty() {
            return Some(local);
        }
        let finite = |b: &Aabb| b.min.iter().chain(b.max.iter()).all(|c| c.abs() <= 1e100);
        if !finite(&local) {
            return None;
        }
        let world = match &self.frame {
            Some(f) => f.bounds(&local),
            None => local,
        };
        finite(&world).then_some(world)
    }

    /// The nearest hit, in the object frame (`t` is the world `t`).
    #[inline]
    pub fn intersect(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut IntersectStats,
    ) -> Option<LocalHit> {
        match &self.frame {
            None => self.prim.intersect(ray, t_min, t_max, stats),
            Some(f) => self
                .prim
                .intersect(&f.ray_to_local(ray), t_min, t_max, stats),
        }
    }

    /// [`Self::intersect`] for each lane (at most [`LANES`]), the rays
    /// mapped into the object frame together.
    #[inline]
    pub fn intersect_batch(
        &self,
        rays: &[Ray],
        ranges: &[(f64, f64)],
        out: &mut [Option<LocalHit>],
        stats: &mut IntersectStats,
    ) {
        match &self.frame {
            None => self.prim.intersect_batch(rays, ranges, out, stats),
            Some(f) => {
                let n = rays.len().min(LANES);
                let mut local = [Ray::new(Point3::origin(), Vector3::zeros()); LANES];
                for (l, r) in local.iter_mut().zip(&rays[..n]) {
                    *l = f.ray_to_local(r);
                }
                self.prim.intersect_batch(&local[..n], ranges, out, stats);
            }
        }
    }

    #[inline]
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut IntersectStats) -> bool {
        match &self.frame {
            None => self.prim.occluded(ray, t_min, t_max, stats),
            Some(f) => self
                .prim
                .occluded(&f.ray_to_local(ray), t_min, t_max, stats),
        }
    }

    /// An object-frame hit in the world, with its UV: point by `M`, normal
    /// by `L⁻ᵀ` (normalized by the caller).
    #[inline]
    pub fn to_world(&self, mut hit: LocalHit) -> LocalHit {
        hit.uv = self.prim.uv(&hit);
        if let Some(f) = &self.frame {
            hit.point = f.point(&hit.point);
            hit.normal = f.normal(&hit.normal);
        }
        hit
    }
}

//! Tensor-product surfaces and Bézier patch models: revolve's certified
//! patch search (its `Intersect`), behind a hierarchy of the patches' boxes
//! for a model.
//!
//! Normals are revolve's, `∂S/∂u × ∂S/∂v` (the limit normal on a collapsed
//! edge), as given: the renderer faces them toward the ray where it needs
//! to. UV: revolve's `(u, v)` mapped from the surface's domain to
//! `[0, 1]²`; for a model, the `(u, v)` of the patch hit.

use std::ops::ControlFlow;
use std::sync::Arc;

use revolve::{Aabb, BezierSurface, Hit, Intersect, Ray, Surface};

use super::bvh::{BoxRay, Bvh, pad};
use super::shapes::LocalHit;
use crate::scene::SurfaceBody;

/// Patches per leaf of a model's hierarchy: one, since a patch search costs
/// far more than a box test.
const PATCH_LEAF: usize = 1;

/// A surface or patch model ready for ray queries.
#[derive(Debug, Clone)]
pub struct SurfaceShape {
    body: Arc<SurfaceBody>,
    bounds: Aabb,
    /// The surface's `(u, v)` domain (`[0, 1]²` for Bézier patches).
    domain: [(f64, f64); 2],
    /// A model's hierarchy over its patches and the patches' indices in
    /// its leaf order.
    hierarchy: Option<(Bvh, Vec<usize>)>,
}

impl SurfaceShape {
    /// `None` when nothing can be hit (empty bounds).
    pub fn new(body: Arc<SurfaceBody>) -> Option<SurfaceShape> {
        let (domain, hierarchy) = match &*body {
            SurfaceBody::Bezier(s) => (s.domain(), None),
            SurfaceBody::BSpline(s) => (s.domain(), None),
            SurfaceBody::Nurbs(s) => (s.domain(), None),
            SurfaceBody::Patches(patches) => {
                let boxes: Vec<Aabb> = patches.iter().map(|p| pad(&p.bounds())).collect();
                let (bvh, order) = Bvh::build(&boxes, PATCH_LEAF);
                ([(0.0, 1.0), (0.0, 1.0)], Some((bvh, order)))
            }
        };
        let bounds = body.bounds();
        if bounds.is_empty() {
            return None;
        }
        Some(SurfaceShape {
            body,
            bounds,
            domain,
            hierarchy,
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// revolve's nearest hit.
    #[inline]
    fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        match (&*self.body, &self.hierarchy) {
            (SurfaceBody::Bezier(s), _) => s.intersect(ray, t_min, t_max),
            (SurfaceBody::BSpline(s), _) => s.intersect(ray, t_min, t_max),
            (SurfaceBody::Nurbs(s), _) => s.intersect(ray, t_min, t_max),
            (SurfaceBody::Patches(patches), Some((bvh, order))) => {
                nearest(patches, bvh, order, ray, t_min, t_max)
            }
            (SurfaceBody::Patches(_), None) => None,
        }
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let h = self.hit(ray, t_min, t_max)?;
        let unit = |x: f64, (a, b): (f64, f64)| ((x - a) / (b - a)).clamp(0.0, 1.0);
        Some(LocalHit {
            t: h.t,
            point: h.point,
            normal: h.normal.into_inner(),
            uv: (unit(h.uv.0, self.domain[0]), unit(h.uv.1, self.domain[1])),
        })
    }
}

/// The nearest hit among `patches` (stored in the hierarchy's leaf order
/// `order`).
fn nearest(
    patches: &[BezierSurface],
    bvh: &Bvh,
    order: &[usize],
    ray: &Ray,
    t_min: f64,
    t_max: f64,
) -> Option<Hit> {
    let mut best = None;
    bvh.traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
        match patches[order[k]].intersect(ray, t_min, t_max) {
            Some(h) => {
                best = Some(h);
                ControlFlow::Continue(h.t)
            }
            None => ControlFlow::Continue(t_max),
        }
    });
    best
}

//! Tensor-product surfaces and Bézier patch models: revolve's certified
//! patch search (its `Intersect`; a `BezierPatches` model keeps its own
//! hierarchy over the patches).
//!
//! Normals are revolve's, `∂S/∂u × ∂S/∂v` (the limit normal on a collapsed
//! edge), as given: the renderer faces them toward the ray where it needs
//! to. UV: revolve's `(u, v)` mapped from the surface's domain to
//! `[0, 1]²`; for a model, the `(u, v)` of the patch hit.

use std::sync::Arc;

use revolve::{Aabb, Ray, Surface};

use super::shapes::LocalHit;
use crate::scene::SurfaceBody;

/// A surface or patch model ready for ray queries.
#[derive(Debug, Clone)]
pub struct SurfaceShape {
    body: Arc<SurfaceBody>,
    bounds: Aabb,
    /// The surface's `(u, v)` domain (`[0, 1]²` for Bézier patches).
    domain: [(f64, f64); 2],
}

impl SurfaceShape {
    /// `None` when nothing can be hit (empty bounds).
    pub fn new(body: Arc<SurfaceBody>) -> Option<SurfaceShape> {
        let domain = match &*body {
            SurfaceBody::Bezier(s) => s.domain(),
            SurfaceBody::BSpline(s) => s.domain(),
            SurfaceBody::Nurbs(s) => s.domain(),
            SurfaceBody::Patches(_) => [(0.0, 1.0), (0.0, 1.0)],
        };
        let bounds = body.bounds();
        if bounds.is_empty() {
            return None;
        }
        Some(SurfaceShape {
            body,
            bounds,
            domain,
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// revolve's [`Intersect::occluded`]: the patch search stops at the
    /// first piece with a hit.
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.body.target().occluded(ray, t_min, t_max)
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let h = self.body.target().intersect(ray, t_min, t_max)?;
        let unit = |x: f64, (a, b): (f64, f64)| ((x - a) / (b - a)).clamp(0.0, 1.0);
        Some(LocalHit {
            t: h.t,
            point: h.point,
            normal: h.normal.into_inner(),
            uv: (unit(h.uv.0, self.domain[0]), unit(h.uv.1, self.domain[1])),
        })
    }
}

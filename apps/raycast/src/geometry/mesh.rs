//! A triangle mesh behind its own BVH.
//!
//! Triangles with an index out of range or zero area are left out (they could
//! never be hit). The triangles are stored in the BVH's leaf order, so a leaf
//! is a contiguous run. Normals are flat, `(v1 − v0) × (v2 − v0)` of each
//! triangle as written (outward for a closed mesh wound counter-clockwise
//! seen from outside, the OBJ convention); UV the barycentric `(b1, b2)`.

use std::ops::ControlFlow;

use revolve::{Aabb, Ray};

use super::bvh::{BoxRay, Bvh, pad};
use super::shapes::{LocalHit, Triangle};
use crate::scene::TriangleMesh;

/// Triangles per leaf at most (unless no plane separates them).
const MAX_LEAF: usize = 4;

/// A mesh ready for ray queries.
#[derive(Debug, Clone)]
pub struct MeshShape {
    triangles: Vec<Triangle>,
    bvh: Bvh,
}

impl MeshShape {
    /// `None` when no triangle is valid.
    pub fn new(mesh: &TriangleMesh) -> Option<MeshShape> {
        let valid: Vec<Triangle> = mesh
            .triangles
            .iter()
            .filter_map(|tri| {
                let v = |k: usize| mesh.vertices.get(tri[k] as usize).copied();
                Triangle::new([v(0)?, v(1)?, v(2)?])
            })
            .collect();
        if valid.is_empty() {
            return None;
        }
        let boxes: Vec<Aabb> = valid.iter().map(|t| pad(&t.bounds())).collect();
        let (bvh, order) = Bvh::build(&boxes, MAX_LEAF);
        let triangles = order.into_iter().map(|i| valid[i]).collect();
        Some(MeshShape { triangles, bvh })
    }

    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let mut best: Option<(usize, (f64, f64, f64))> = None;
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                match self.triangles[k].hit(ray, t_min, t_max) {
                    Some(h) => {
                        best = Some((k, h));
                        ControlFlow::Continue(h.0)
                    }
                    None => ControlFlow::Continue(t_max),
                }
            });
        best.map(|(k, h)| self.triangles[k].local_hit(ray, h))
    }

    /// Whether any triangle is hit (stops at the first).
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let mut hit = false;
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                if self.triangles[k].hit(ray, t_min, t_max).is_some() {
                    hit = true;
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(t_max)
                }
            });
        hit
    }
}

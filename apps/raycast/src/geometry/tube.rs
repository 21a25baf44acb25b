//! A curve drawn as a tube: a chain of capsules (segments swept by a sphere
//! of the tube's radius) between consecutive points, behind a BVH.
//!
//! # One capsule
//! A capsule is convex, so a ray meets it in one interval `[t_in, t_out]`.
//! The capsule is the union of its two end spheres and the piece of the
//! infinite cylinder between the end planes, so the interval is the hull of
//! those pieces' intervals (each piece lies inside the capsule, and the ray
//! enters and leaves through one of them):
//!
//! - the spheres: `|o + t·d − a|² = r²` (and `b`);
//! - the cylinder about `a + s·(b − a)`: `|(o − a + t·d) × (b − a)|² =
//!   r²·|b − a|²` (the distance to the axis line, without cancellation),
//!   clipped to the slab `0 ≤ (o − a + t·d)·(b − a) ≤ |b − a|²`.
//!
//! Both quadratics share [`norm_roots`]. The hit is `t_in`, or `t_out` when
//! `t_in ≤ t_min`. The normal is `(p − q)/r` with `q` the closest point of the
//! segment to the hit `p` (outward). A zero-length segment is a sphere.
//!
//! # The chain
//! Neighbouring capsules overlap around their shared point. A candidate hit
//! strictly inside the previous or next capsule (distance to its segment
//! below `r·(1 − 10⁻⁶)`) is inside the tube, not on it, and is skipped (then
//! the capsule's other end is tried); so a ray travelling inside a
//! transparent tube sees no joints. Overlaps of capsules further apart along
//! the curve (a curve crossing itself) are not resolved.
//!
//! UV: `u = (i + s)/n` for segment `i` of `n` at segment parameter `s`; `v` the
//! angle about the segment over `2π`.

use std::ops::ControlFlow;

use revolve::nalgebra::{Point3, Vector3};
use revolve::{Aabb, Ray};

use super::bvh::{BoxRay, Bvh, pad};
use super::shapes::{LocalHit, basis, finite, in_range, norm_roots, turn};
use crate::scene::Tube;

const MAX_LEAF: usize = 4;

/// Segment `a → a + ba`, with a frame about it for the angle.
#[derive(Debug, Clone)]
struct Capsule {
    a: Point3<f64>,
    ba: Vector3<f64>,
    baba: f64,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
}

impl Capsule {
    fn new(a: Point3<f64>, b: Point3<f64>) -> Capsule {
        let ba = b - a;
        let baba = ba.norm_squared();
        let axis = if baba > 0.0 {
            ba / baba.sqrt()
        } else {
            Vector3::y()
        };
        let (e1, e2) = basis(&axis);
        Capsule {
            a,
            ba,
            baba,
            e1,
            e2,
        }
    }

    fn bounds(&self, r: f64) -> Aabb {
        Aabb::new(self.a, self.a + self.ba).expand(r)
    }

    /// The segment parameter of the closest point to `p`, in `[0, 1]`.
    #[inline]
    fn param(&self, p: &Point3<f64>) -> f64 {
        if self.baba > 0.0 {
            ((p - self.a).dot(&self.ba) / self.baba).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// `p` minus its closest point on the segment.
    #[inline]
    fn offset(&self, p: &Point3<f64>) -> Vector3<f64> {
        p - (self.a + self.ba * self.param(p))
    }

    /// The interval in which the ray is inside the capsule (module docs).
    #[inline]
    fn interval(&self, ray: &Ray, r: f64) -> Option<(f64, f64)> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let oa = ray.origin - self.a;
        if let Some((t0, t1)) = norm_roots(&oa, &ray.dir, r) {
            (lo, hi) = (t0, t1);
        }
        if self.baba > 0.0 {
            if let Some((t0, t1)) = norm_roots(&(oa - self.ba), &ray.dir, r) {
                (lo, hi) = (lo.min(t0), hi.max(t1));
            }
            let (m, n) = (oa.cross(&self.ba), ray.dir.cross(&self.ba));
            if let Some((mut t0, mut t1)) = norm_roots(&m, &n, r * self.baba.sqrt()) {
                let (y, dy) = (oa.dot(&self.ba), ray.dir.dot(&self.ba));
                let inside_slab = if dy != 0.0 {
                    let (s0, s1) = (-y / dy, (self.baba - y) / dy);
                    t0 = t0.max(s0.min(s1));
                    t1 = t1.min(s0.max(s1));
                    true
                } else {
                    (0.0..=self.baba).contains(&y)
                };
                if inside_slab && t0 <= t1 {
                    (lo, hi) = (lo.min(t0), hi.max(t1));
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }
}

/// A tube ready for ray queries.
#[derive(Debug, Clone)]
pub struct TubeShape {
    /// In curve order (for the neighbour test and UV).
    capsules: Vec<Capsule>,
    /// Capsule index of each BVH item.
    order: Vec<u32>,
    bvh: Bvh,
    radius: f64,
}

impl TubeShape {
    /// `None` for a radius that is not positive and finite, or no finite
    /// point. Segments with a non-finite end are left out; a single point is
    /// a sphere.
    pub fn new(tube: &Tube) -> Option<TubeShape> {
        let r = tube.radius;
        if !(r > 0.0 && r.is_finite()) {
            return None;
        }
        let pts: Vec<Point3<f64>> = tube
            .points
            .iter()
            .copied()
            .filter(|p| finite(&p.coords))
            .collect();
        let capsules: Vec<Capsule> = match pts.len() {
            0 => return None,
            1 => vec![Capsule::new(pts[0], pts[0])],
            _ => pts.windows(2).map(|w| Capsule::new(w[0], w[1])).collect(),
        };
        let boxes: Vec<Aabb> = capsules.iter().map(|c| pad(&c.bounds(r))).collect();
        let (bvh, order) = Bvh::build(&boxes, MAX_LEAF);
        Some(TubeShape {
            capsules,
            order: order.into_iter().map(|i| i as u32).collect(),
            bvh,
            radius: r,
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// Whether `p` is strictly inside capsule `j` (if it exists).
    #[inline]
    fn inside(&self, j: Option<usize>, p: &Point3<f64>) -> bool {
        let limit = self.radius * self.radius * (1.0 - 2e-6);
        j.and_then(|j| self.capsules.get(j))
            .is_some_and(|c| c.offset(p).norm_squared() < limit)
    }

    /// The first boundary crossing of capsule `i` in `(t_min, t_max)` that
    /// is not inside its neighbours.
    #[inline]
    fn capsule_hit(&self, i: usize, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let (lo, hi) = self.capsules[i].interval(ray, self.radius)?;
        [lo, hi].into_iter().find(|&t| {
            in_range(t, t_min, t_max) && {
                let p = ray.at(t);
                !self.inside(i.checked_sub(1), &p) && !self.inside(Some(i + 1), &p)
            }
        })
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let mut best: Option<(usize, f64)> = None;
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                let i = self.order[k] as usize;
                match self.capsule_hit(i, ray, t_min, t_max) {
                    Some(t) => {
                        best = Some((i, t));
                        ControlFlow::Continue(t)
                    }
                    None => ControlFlow::Continue(t_max),
                }
            });
        let (i, t) = best?;
        let c = &self.capsules[i];
        let point = ray.at(t);
        let normal = c.offset(&point) / self.radius;
        let n = self.capsules.len() as f64;
        Some(LocalHit {
            t,
            point,
            normal,
            uv: (
                ((i as f64 + c.param(&point)) / n).clamp(0.0, 1.0),
                turn(normal.dot(&c.e2), normal.dot(&c.e1)),
            ),
        })
    }

    /// Whether any capsule is hit (stops at the first).
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let mut hit = false;
        self.bvh
            .traverse(&BoxRay::new(ray), t_min, t_max, |k, t_max| {
                if self
                    .capsule_hit(self.order[k] as usize, ray, t_min, t_max)
                    .is_some()
                {
                    hit = true;
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(t_max)
                }
            });
        hit
    }
}

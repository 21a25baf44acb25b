//! What both integrators share: the scene, its world, the effects, the
//! prepared lights, and the rules for secondary and shadow rays.
//!
//! Secondary rays start at `p + ε·n_side`, where `n_side` is the unit normal
//! on the side the ray leaves by, and ignore hits with `t ≤ ε`;
//! `ε = 1e-6 × scene scale` ([`crate::scale`]). All rays have unit
//! directions, so `t` is a distance. A shadow ray towards a point looks
//! for occluders from `ε` to `ε` short of the point, so the surface of an
//! emitter being sampled does not shadow itself.

use std::sync::LazyLock;

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::effects::Effects;
use crate::geometry::{SurfaceHit, World};
use crate::lights::Lights;
use crate::scale;
use crate::scene::{Material, Scene};
use crate::stats::Stats;

/// The material of an object whose index is out of range (the parser
/// rejects such scenes; scenes built in code might not): black, inert.
static FALLBACK_MATERIAL: LazyLock<Material> = LazyLock::new(Material::default);

/// The read-only state of a render, shared by all threads.
pub struct Tracer<'a> {
    pub scene: &'a Scene,
    pub world: &'a World,
    pub effects: Effects,
    pub lights: Lights,
    /// The self-intersection offset `ε`.
    pub eps: f64,
    /// Per object: whether `World::emitters` samples it (its emission is
    /// then gathered by next-event estimation, not by BSDF-sampled hits).
    pub sampled_emitter: Vec<bool>,
}

impl<'a> Tracer<'a> {
    /// Prepares `scene` (whose `world` has been built) for rendering with
    /// `effects`.
    pub fn new(scene: &'a Scene, world: &'a World, effects: Effects) -> Tracer<'a> {
        let mut sampled_emitter = vec![false; scene.objects.len()];
        if effects.emissive {
            for e in world.emitters() {
                if let Some(s) = sampled_emitter.get_mut(e.object) {
                    *s = true;
                }
            }
        }
        Tracer {
            scene,
            world,
            effects,
            lights: Lights::of(scene),
            eps: scale::EPSILON_RELATIVE * scale::scene_scale(scene),
            sampled_emitter,
        }
    }

    /// The material of the object `object`.
    #[inline]
    pub fn material(&self, object: usize) -> &'a Material {
        self.scene
            .objects
            .get(object)
            .and_then(|o| self.scene.materials.get(o.material))
            .unwrap_or(&FALLBACK_MATERIAL)
    }

    /// The nearest hit of `ray` beyond `t_min`.
    #[inline]
    pub fn nearest(&self, ray: &Ray, t_min: f64, stats: &mut Stats) -> Option<SurfaceHit> {
        self.world
            .intersect(ray, t_min, f64::INFINITY, &mut stats.intersect)
    }

    /// A secondary ray from the surface point `p` along the unit `dir`,
    /// leaving by the side of the unit normal `n_side`. Trace it with
    /// `t_min = self.eps`.
    #[inline]
    pub fn spawn(&self, p: &Point3<f64>, n_side: &Vector3<f64>, dir: Vector3<f64>) -> Ray {
        Ray::new(p + n_side * self.eps, dir)
    }

    /// Whether the point at distance `dist` (may be infinite) from the
    /// surface point `p` along the unit `dir` is visible from `p`, `n` being
    /// the surface's unit normal on either side. Counts one shadow ray.
    ///
    /// The shadow ray starts at `o = p + ε·n_side` (the side facing `dir`)
    /// and, for a finite distance, is aimed from `o` at the target point
    /// itself and stops `ε` short of it: keeping `dir` from the shifted
    /// origin would meet the target's surface up to `ε / cos` early at
    /// grazing angles and report the light as its own occluder.
    #[inline]
    pub fn visible(
        &self,
        p: &Point3<f64>,
        n: &Vector3<f64>,
        dir: &Vector3<f64>,
        dist: f64,
        stats: &mut Stats,
    ) -> bool {
        let n_side = if n.dot(dir) >= 0.0 { *n } else { -n };
        let origin = p + n_side * self.eps;
        let (ray, t_max) = if dist.is_finite() {
            let w = (p + dir * dist) - origin;
            let d = w.norm();
            if d <= 2.0 * self.eps {
                return true;
            }
            (Ray::new(origin, w / d), d - self.eps)
        } else {
            (Ray::new(origin, *dir), f64::INFINITY)
        };
        stats.rays.shadow += 1;
        !self
            .world
            .occluded(&ray, self.eps, t_max, &mut stats.intersect)
    }
}

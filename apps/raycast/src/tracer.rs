//! What both integrators share: the scene, its world, the effects, the
//! prepared lights, and the rules for secondary and shadow rays.
//!
//! Secondary rays start at `p + ε·n_side`, where `n_side` is the unit normal
//! on the side the ray leaves by, and ignore hits with `t ≤ ε`;
//! `ε = 1e-6 × scene scale` ([`crate::scale`]). All rays have unit
//! directions, so `t` is a distance. A shadow ray towards a point looks
//! for occluders from `ε` to `ε` short of the point, so the surface of an
//! emitter being sampled does not shadow itself.
//!
//! # Shadows through transparent objects
//! When the scene uses a transparent material ([`Effects::transparent_shadows`]),
//! a shadow ray does not stop at the first surface it meets
//! ([`Tracer::transmittance`]): it walks the surfaces between the point and
//! the light in order of distance. An opaque one (zero `transparency`) blocks
//! the light; a transparent one lets through its `transparency` colour, once
//! per surface crossed (a closed body is crossed twice, as the refracted
//! camera ray through it is weighted twice); and where the ray leaves a body
//! with `absorption σ` (it meets the back of the surface) it keeps
//! `exp(−σ s)` of the light, `s` being the distance since the previous
//! surface (or the start), as Beer–Lambert for camera rays. The shadow ray
//! goes straight: refraction does not bend it and Fresnel reflection does not
//! dim it (caustics are the path tracer's business). After
//! [`MAX_SHADOW_CROSSINGS`] transparent surfaces the light counts as blocked.
//! Scenes without transparent materials keep the plain yes/no test
//! ([`Tracer::visible`]) and render exactly as before.

use std::sync::LazyLock;

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::effects::Effects;
use crate::geometry::{SurfaceHit, World};
use crate::lights::Lights;
use crate::optics;
use crate::scale;
use crate::scene::{Color, Material, Scene};
use crate::stats::Stats;

/// Transparent surfaces a shadow ray crosses at most; beyond, the light
/// counts as blocked (bounds the cost of a shadow ray through, say, a mesh of
/// many glass triangles).
pub const MAX_SHADOW_CROSSINGS: usize = 64;

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

    /// The nearest hit of each of `rays` beyond `t_min`, into `hits`: the
    /// same as [`Self::nearest`] for each, found together.
    #[inline]
    pub fn nearest_batch(
        &self,
        rays: &[Ray],
        t_min: f64,
        hits: &mut [Option<SurfaceHit>],
        stats: &mut Stats,
    ) {
        self.world
            .intersect_batch(rays, t_min, hits, &mut stats.intersect);
    }

    /// A secondary ray from the surface point `p` along the unit `dir`,
    /// leaving by the side of the unit normal `n_side`. Trace it with
    /// `t_min = self.eps`.
    #[inline]
    pub fn spawn(&self, p: &Point3<f64>, n_side: &Vector3<f64>, dir: Vector3<f64>) -> Ray {
        Ray::new(p + n_side * self.eps, dir)
    }

    /// The shadow ray from the surface point `p` towards the point at
    /// distance `dist` (may be infinite) along the unit `dir`, `n` being the
    /// surface's unit normal on either side: the ray and the end of its
    /// search interval; `None` when the target is within `2ε` of the origin
    /// (nothing can lie between them).
    ///
    /// The shadow ray starts at `o = p + ε·n_side` (the side facing `dir`)
    /// and, for a finite distance, is aimed from `o` at the target point
    /// itself and stops `ε` short of it: keeping `dir` from the shifted
    /// origin would meet the target's surface up to `ε / cos` early at
    /// grazing angles and report the light as its own occluder.
    #[inline]
    fn shadow_ray(
        &self,
        p: &Point3<f64>,
        n: &Vector3<f64>,
        dir: &Vector3<f64>,
        dist: f64,
    ) -> Option<(Ray, f64)> {
        let n_side = if n.dot(dir) >= 0.0 { *n } else { -n };
        let origin = p + n_side * self.eps;
        if dist.is_finite() {
            let w = (p + dir * dist) - origin;
            let d = w.norm();
            if d <= 2.0 * self.eps {
                return None;
            }
            Some((Ray::new(origin, w / d), d - self.eps))
        } else {
            Some((Ray::new(origin, *dir), f64::INFINITY))
        }
    }

    /// Whether the point at distance `dist` (may be infinite) from the
    /// surface point `p` along the unit `dir` is visible from `p`, `n` being
    /// the surface's unit normal on either side: any surface in between
    /// blocks it. Counts one shadow ray (see [`Self::shadow_ray`]).
    #[inline]
    pub fn visible(
        &self,
        p: &Point3<f64>,
        n: &Vector3<f64>,
        dir: &Vector3<f64>,
        dist: f64,
        stats: &mut Stats,
    ) -> bool {
        let Some((ray, t_max)) = self.shadow_ray(p, n, dir, dist) else {
            return true;
        };
        stats.rays.shadow += 1;
        !self
            .world
            .occluded(&ray, self.eps, t_max, &mut stats.intersect)
    }

    /// The fraction of a light's colour that reaches the surface point `p`
    /// from the point at distance `dist` along the unit `dir` (arguments as
    /// [`Self::visible`]): `None` when an opaque surface blocks it, else the
    /// product of the transparent surfaces' transmissions (exactly 1 in every
    /// channel when nothing is in the way). Without transparent materials in
    /// the scene it is [`Self::visible`]; with them, see the module docs.
    /// Counts one shadow ray, plus one for each transparent surface the ray
    /// is continued past.
    #[inline]
    pub fn transmittance(
        &self,
        p: &Point3<f64>,
        n: &Vector3<f64>,
        dir: &Vector3<f64>,
        dist: f64,
        stats: &mut Stats,
    ) -> Option<Color> {
        let clear = Color::repeat(1.0);
        if !self.effects.transparent_shadows {
            return self.visible(p, n, dir, dist, stats).then_some(clear);
        }
        let Some((ray, t_max)) = self.shadow_ray(p, n, dir, dist) else {
            return Some(clear);
        };
        let mut kept = clear;
        let (mut t_min, mut previous) = (self.eps, 0.0);
        for _ in 0..MAX_SHADOW_CROSSINGS {
            if t_min.is_nan() || t_min >= t_max {
                return Some(kept);
            }
            stats.rays.shadow += 1;
            let Some(hit) = self
                .world
                .intersect(&ray, t_min, t_max, &mut stats.intersect)
            else {
                return Some(kept);
            };
            let material = self.material(hit.object);
            if material.transparency == Color::zeros() {
                return None;
            }
            kept = kept.component_mul(&material.transparency);
            let (_, front) = hit.facing(&ray.dir);
            if self.effects.absorption && !front && material.absorption != Color::zeros() {
                let inside = hit.t - previous;
                kept = kept.component_mul(&optics::beer_lambert(&material.absorption, inside));
            }
            if kept == Color::zeros() {
                return None;
            }
            previous = hit.t;
            t_min = hit.t + self.eps;
        }
        None
    }
}

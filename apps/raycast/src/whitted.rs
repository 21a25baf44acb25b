//! The recursive ray tracer of the course framework (Whitted), with the
//! optional effects the scene calls for.
//!
//! At the nearest hit `p` of a ray with unit direction `d`, with `N` the
//! geometric normal flipped to face the viewer and `V = −d`:
//!
//! ```text
//! colour = emission                                   (emissive objects only)
//!        + Σ delta lights  Phong(L)                   ⊙ shadow    (hard shadows only)
//!        + Σ area lights   1/k Σᵢ Phong(Lᵢ)           ⊙ shadowᵢ   (k stratified samples)
//!        + (reflectivity + transparency·F) ⊙ trace(reflected)        (depth < maxDepth)
//!        + transparency·(1 − F) ⊙ trace(refracted)                    (depth < maxDepth)
//! ```
//!
//! `shadow` is 0 when an opaque surface lies between the point and the
//! light, 1 when nothing does, and with transparent materials in the scene
//! the product of the transmissions of the transparent surfaces in between
//! ([`Tracer::transmittance`]).
//!
//! An area light (or a sampled emitter) is treated as `k` point lights of
//! its full colour at stratified points of its surface, averaged: it is as
//! bright as a point light, with a penumbra.
//!
//! `F` is the exact Fresnel reflectance of the interface ([`optics`]); the
//! ray enters the object when `d·n < 0` for the outward normal `n`
//! (indices 1 → `refractionIndex`) and leaves it otherwise (the reverse).
//! Under total internal reflection `F = 1`. A ray that reaches a surface
//! from inside an object with `absorption σ` has its colour multiplied by
//! `exp(−σ t)`, `t` being the distance travelled inside (Beer–Lambert).
//!
//! The recursion stops at `maxDepth` bounces, a branch whose weight
//! (the product of the reflection/transmission factors along it, largest
//! channel) falls below [`MIN_WEIGHT`] is not traced, and a camera sample
//! traces at most [`MAX_SECONDARY_RAYS`] secondary rays. A miss returns the
//! background colour. Each disabled effect costs one boolean test.

use revolve::Ray;
use revolve::nalgebra::Vector3;

use crate::geometry::SurfaceHit;
use crate::optics;
use crate::sampling::{self, Rng};
use crate::scene::{Color, Material};
use crate::shading;
use crate::stats::Stats;
use crate::tracer::Tracer;

/// Branches contributing less than this (relative to the camera ray) are not
/// traced.
pub const MIN_WEIGHT: f64 = 1e-3;

fn nonzero(c: &Color) -> bool {
    c.iter().any(|v| *v != 0.0)
}

/// Reflection and refraction rays one camera sample may spawn in all; the
/// branches past it are not traced. A full binary tree of the default depth
/// (5) holds 62, and pruning by [`MIN_WEIGHT`] keeps real scenes far below;
/// the budget bounds the work of materials whose reflectivity and
/// transparency add up to more than 1, whose branches never get light
/// enough to prune (2^maxDepth rays otherwise).
pub const MAX_SECONDARY_RAYS: u32 = 1024;

/// Where a branch of the ray tree stands: bounces so far, and its weight
/// (the product of the reflection/transmission factors along it, largest
/// channel).
#[derive(Debug, Clone, Copy)]
struct Branch {
    depth: u32,
    weight: f64,
}

/// The colour seen along the camera ray `ray` (unit direction), whose
/// nearest hit is `hit`.
pub fn trace(
    tracer: &Tracer<'_>,
    ray: &Ray,
    hit: Option<SurfaceHit>,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let mut budget = MAX_SECONDARY_RAYS;
    let camera = Branch {
        depth: 0,
        weight: 1.0,
    };
    shade(tracer, ray, hit, camera, &mut budget, rng, stats)
}

/// Takes one ray from the `budget`; false when it is spent.
fn spend(budget: &mut u32) -> bool {
    if *budget == 0 {
        return false;
    }
    *budget -= 1;
    true
}

/// The colour seen along `ray` (unit direction), ignoring hits with
/// `t ≤ t_min`, on the branch `branch`, with `budget` secondary rays left
/// for the camera sample.
fn trace_branch(
    tracer: &Tracer<'_>,
    ray: &Ray,
    t_min: f64,
    branch: Branch,
    budget: &mut u32,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let hit = tracer.nearest(ray, t_min, stats);
    shade(tracer, ray, hit, branch, budget, rng, stats)
}

/// The colour seen along `ray` whose nearest hit is `hit` (the background
/// for none), the rest as [`trace_branch`].
fn shade(
    tracer: &Tracer<'_>,
    ray: &Ray,
    hit: Option<SurfaceHit>,
    branch: Branch,
    budget: &mut u32,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let Branch { depth, weight } = branch;
    let Some(hit) = hit else {
        return tracer.scene.background;
    };
    let effects = &tracer.effects;
    let material = tracer.material(hit.object);
    let d = ray.dir;
    let (n, front) = hit.facing(&d);
    let v = -d;
    let p = hit.point;
    let kd = shading::diffuse_at(material, hit.uv, effects.textures);

    let mut color = Color::zeros();
    if effects.emissive {
        color += material.emission;
    }
    for light in &tracer.lights.delta {
        let Some((l, dist)) = light.toward(&p) else {
            continue;
        };
        let mut arriving = *light.color();
        if effects.hard_shadows {
            match tracer.transmittance(&p, &n, &l, dist, stats) {
                Some(kept) => arriving = arriving.component_mul(&kept),
                None => continue,
            }
        }
        color += shading::phong(&kd, material, &n, &v, &l, &arriving);
    }
    if effects.area_lights || effects.emissive {
        color += area_lights(tracer, &p, &n, &v, &kd, material, rng, stats);
    }

    if depth < effects.max_depth {
        let mut mirror = Color::zeros();
        if effects.reflection {
            mirror += material.reflectivity;
        }
        if effects.refraction && nonzero(&material.transparency) {
            let (n1, n2) = optics::indices(material.refraction_index, front);
            let f = optics::fresnel(v.dot(&n), n1, n2);
            match optics::refract(&d, &n, n1 / n2) {
                Some(t) if f < 1.0 => {
                    let k = material.transparency * (1.0 - f);
                    let w = weight * k.max();
                    if w >= MIN_WEIGHT && spend(budget) {
                        stats.rays.refraction += 1;
                        let ray = tracer.spawn(&p, &-n, t.normalize());
                        let next = Branch {
                            depth: depth + 1,
                            weight: w,
                        };
                        let c = trace_branch(tracer, &ray, tracer.eps, next, budget, rng, stats);
                        color += k.component_mul(&c);
                    }
                    mirror += material.transparency * f;
                }
                _ => mirror += material.transparency,
            }
        }
        let w = weight * mirror.max();
        if nonzero(&mirror) && w >= MIN_WEIGHT && spend(budget) {
            stats.rays.reflection += 1;
            let ray = tracer.spawn(&p, &n, optics::reflect(&d, &n));
            let next = Branch {
                depth: depth + 1,
                weight: w,
            };
            let c = trace_branch(tracer, &ray, tracer.eps, next, budget, rng, stats);
            color += mirror.component_mul(&c);
        }
    }

    if effects.absorption && !front && nonzero(&material.absorption) {
        color = color.component_mul(&optics::beer_lambert(&material.absorption, hit.t));
    }
    color
}

/// The Phong light of the area lights and sampled emitters at `p`, each
/// averaged over `k = light_samples` stratified points of its surface.
#[allow(clippy::too_many_arguments)]
fn area_lights(
    tracer: &Tracer<'_>,
    p: &revolve::nalgebra::Point3<f64>,
    n: &Vector3<f64>,
    v: &Vector3<f64>,
    kd: &Color,
    material: &Material,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let effects = &tracer.effects;
    let k = effects.light_samples;
    let scale = 1.0 / f64::from(k);
    let mut color = Color::zeros();
    let mut add = |q: revolve::nalgebra::Point3<f64>, light: &Color, stats: &mut Stats| {
        let w = q - p;
        let dist = w.norm();
        if dist <= 0.0 {
            return;
        }
        let l = w / dist;
        let mut arriving = *light;
        if effects.soft_shadows {
            match tracer.transmittance(p, n, &l, dist, stats) {
                Some(kept) => arriving = arriving.component_mul(&kept),
                None => return,
            }
        }
        color += shading::phong(kd, material, n, v, &l, &arriving) * scale;
    };
    for light in &tracer.lights.area {
        for i in 0..k {
            let (a, b) = sampling::stratum(i, k, rng.next_2d());
            add(light.point(a, b), &light.color, stats);
        }
    }
    if effects.emissive {
        for e in tracer.world.emitters() {
            let emission = tracer.material(e.object).emission;
            if !nonzero(&emission) {
                continue;
            }
            for i in 0..k {
                let (a, b) = sampling::stratum(i, k, rng.next_2d());
                add(e.sample(a, b).0, &emission, stats);
            }
        }
    }
    color
}

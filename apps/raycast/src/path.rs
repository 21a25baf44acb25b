//! The Monte Carlo path tracer.
//!
//! A material is the sum of three lobes, chosen per bounce with probability
//! proportional to their weights (largest channel), the throughput being
//! divided by that probability:
//!
//! - diffuse: Lambertian `f = kd/π` (kd from the texture when there is
//!   one), sampled with density `cos θ/π`, so the throughput gains `kd`;
//! - mirror: a delta reflection weighted by `reflectivity`;
//! - glass: a delta dielectric weighted by `transparency`: reflection with
//!   the exact Fresnel probability `F`, refraction otherwise (total internal
//!   reflection: always reflection); absorption `exp(−σ t)` for the distance
//!   `t` travelled inside an object (Beer–Lambert).
//!
//! Next-event estimation at every hit gathers the direct light on the
//! diffuse lobe, plus a normalized Phong lobe
//! `ks (s+2)/(2π) max(0, R·V)^s` for highlights (evaluated for light samples
//! only, never sampled):
//!
//! - point and directional lights: `π f · colour · cos θ`, with no fall-off
//!   (as the course framework, so a diffuse surface is exactly as bright as
//!   under Phong), times the transmission of the transparent surfaces in
//!   between ([`Tracer::transmittance`]; no path can carry a delta light's
//!   light through glass, so this is its only way through);
//! - area lights and the emitters of `World::emitters`, `k` stratified
//!   samples by area: `f · Le · cos θ · |cos θ'| · area / r²` averaged
//!   (`θ'` at the light; both faces emit), where any surface in between
//!   blocks the sample, transparent or not: the light they let through
//!   arrives along paths refracted through them, which count the emission
//!   they meet.
//!
//! Emission met by a ray is counted only for camera rays and rays after a
//! delta (mirror or glass) bounce, since next-event estimation has already
//! counted it after a diffuse bounce — except for emissive objects that
//! `World::emitters` cannot sample, which are counted always. A diffuse ray
//! that meets an area light stops there. A miss returns the background
//! colour as constant environment light. Paths stop after `maxDepth`
//! bounces; from the third bounce on, Russian roulette continues a path with
//! probability `q = min(0.95, max throughput)` and divides by `q`.

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::geometry::SurfaceHit;
use crate::optics;
use crate::sampling::{self, Rng};
use crate::scene::{Color, Material};
use crate::shading;
use crate::stats::Stats;
use crate::tracer::Tracer;

/// Bounces after which Russian roulette starts.
pub const ROULETTE_AFTER: u32 = 3;

fn nonzero(c: &Color) -> bool {
    c.iter().any(|v| *v != 0.0)
}

/// The radiance arriving along the camera ray `camera_ray` (unit
/// direction), whose nearest hit is `camera_hit`: one path sample.
pub fn radiance(
    tracer: &Tracer<'_>,
    camera_ray: &Ray,
    camera_hit: Option<SurfaceHit>,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let effects = &tracer.effects;
    let mut ray = *camera_ray;
    let mut t_min = 0.0;
    let mut throughput = Color::repeat(1.0);
    let mut radiance = Color::zeros();
    // Camera ray or the last bounce was a delta one: emission counts.
    let mut count_emission = true;
    for depth in 0..=effects.max_depth {
        let hit = if depth == 0 {
            camera_hit
        } else {
            tracer.nearest(&ray, t_min, stats)
        };
        let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
        if let Some((_, le)) = tracer.lights.hit_area(&ray, t_min, t_hit) {
            if count_emission {
                radiance += throughput.component_mul(&le);
            }
            break;
        }
        let Some(hit) = hit else {
            radiance += throughput.component_mul(&tracer.scene.background);
            break;
        };
        let material = tracer.material(hit.object);
        let d = ray.dir;
        let (n, front) = hit.facing(&d);
        let v = -d;
        let p = hit.point;

        if effects.absorption && !front && nonzero(&material.absorption) {
            throughput =
                throughput.component_mul(&optics::beer_lambert(&material.absorption, hit.t));
        }
        if effects.emissive
            && nonzero(&material.emission)
            && (count_emission
                || !tracer
                    .sampled_emitter
                    .get(hit.object)
                    .copied()
                    .unwrap_or(false))
        {
            radiance += throughput.component_mul(&material.emission);
        }
        let kd = shading::diffuse_at(material, hit.uv, effects.textures);
        if nonzero(&kd) || nonzero(&material.specular) {
            let direct = direct_light(tracer, &p, &n, &v, &kd, material, rng, stats);
            radiance += throughput.component_mul(&direct);
        }
        if depth == effects.max_depth {
            break;
        }

        // Choose the lobe that continues the path.
        let wd = kd.max().max(0.0);
        let wr = if effects.reflection {
            material.reflectivity.max().max(0.0)
        } else {
            0.0
        };
        let wt = if effects.refraction {
            material.transparency.max().max(0.0)
        } else {
            0.0
        };
        let total = wd + wr + wt;
        if total <= 0.0 || !total.is_finite() {
            break;
        }
        let u = rng.next_f64() * total;
        let dir = if u < wd {
            stats.rays.indirect += 1;
            count_emission = false;
            throughput = throughput.component_mul(&kd) * (total / wd);
            ray = tracer.spawn(&p, &n, sampling::cosine_hemisphere(&n, rng.next_2d()));
            ray.dir
        } else if u < wd + wr {
            stats.rays.reflection += 1;
            count_emission = true;
            throughput = throughput.component_mul(&material.reflectivity) * (total / wr);
            ray = tracer.spawn(&p, &n, optics::reflect(&d, &n));
            ray.dir
        } else {
            count_emission = true;
            throughput = throughput.component_mul(&material.transparency) * (total / wt);
            let (n1, n2) = optics::indices(material.refraction_index, front);
            let f = optics::fresnel(v.dot(&n), n1, n2);
            match optics::refract(&d, &n, n1 / n2) {
                Some(t) if rng.next_f64() >= f => {
                    stats.rays.refraction += 1;
                    ray = tracer.spawn(&p, &-n, t.normalize());
                }
                _ => {
                    stats.rays.reflection += 1;
                    ray = tracer.spawn(&p, &n, optics::reflect(&d, &n));
                }
            }
            ray.dir
        };
        debug_assert!(dir.iter().all(|c| c.is_finite()));
        t_min = tracer.eps;

        if depth + 1 >= ROULETTE_AFTER {
            let q = throughput.max().min(0.95);
            if q.is_nan() || q <= 0.0 || rng.next_f64() >= q {
                break;
            }
            throughput /= q;
        }
    }
    radiance
}

/// `π f(l)` for the diffuse lobe plus the normalized Phong lobe:
/// `kd + ks (s+2)/2 · max(0, R·V)^s` with `R = 2(N·L)N − L`.
#[inline]
fn brdf_pi(
    kd: &Color,
    m: &Material,
    n: &Vector3<f64>,
    v: &Vector3<f64>,
    l: &Vector3<f64>,
) -> Color {
    if nonzero(&m.specular) {
        let r = n * (2.0 * n.dot(l)) - l;
        let lobe = v.dot(&r).max(0.0).powf(m.shininess) * (m.shininess + 2.0) / 2.0;
        kd + m.specular * lobe
    } else {
        *kd
    }
}

/// Next-event estimation: the light arriving directly at `p` from every
/// light and sampled emitter, reflected towards `v`.
#[allow(clippy::too_many_arguments)]
fn direct_light(
    tracer: &Tracer<'_>,
    p: &Point3<f64>,
    n: &Vector3<f64>,
    v: &Vector3<f64>,
    kd: &Color,
    material: &Material,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let mut sum = Color::zeros();
    for light in &tracer.lights.delta {
        let Some((l, dist)) = light.toward(p) else {
            continue;
        };
        let cos = n.dot(&l);
        if cos <= 0.0 {
            continue;
        }
        if let Some(kept) = tracer.transmittance(p, n, &l, dist, stats) {
            sum += light
                .color()
                .component_mul(&kept)
                .component_mul(&brdf_pi(kd, material, n, v, &l))
                * cos;
        }
    }
    let k = tracer.effects.light_samples;
    let inv_pi_k = std::f64::consts::FRAC_1_PI / f64::from(k);
    // One light sample at `q` with unit normal `nq` on a light of radiance
    // `le` and area `area`, sampled by area.
    let mut sample =
        |q: Point3<f64>, nq: &Vector3<f64>, le: &Color, area: f64, stats: &mut Stats| {
            let w = q - p;
            let d2 = w.norm_squared();
            if d2 <= 0.0 {
                return;
            }
            let dist = d2.sqrt();
            let l = w / dist;
            let cos = n.dot(&l);
            let cos_light = nq.dot(&l).abs();
            if cos <= 0.0 || cos_light <= 0.0 || !tracer.visible(p, n, &l, dist, stats) {
                return;
            }
            let g = cos * cos_light * area / d2 * inv_pi_k;
            sum += le.component_mul(&brdf_pi(kd, material, n, v, &l)) * g;
        };
    for light in &tracer.lights.area {
        for i in 0..k {
            let (a, b) = sampling::stratum(i, k, rng.next_2d());
            sample(
                light.point(a, b),
                &light.normal,
                &light.color,
                light.area,
                stats,
            );
        }
    }
    if tracer.effects.emissive {
        for e in tracer.world.emitters() {
            let le = tracer.material(e.object).emission;
            if !nonzero(&le) {
                continue;
            }
            let area = e.area();
            for i in 0..k {
                let (a, b) = sampling::stratum(i, k, rng.next_2d());
                let (q, nq) = e.sample(a, b);
                sample(q, &nq, &le, area, stats);
            }
        }
    }
    sum
}

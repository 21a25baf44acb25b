//! Intersection throughput: the exact revolution intersector and the generic
//! Newton intersector (patch-tree depths 6 and 10) on a vase (one
//! cubic Bézier) and a wine glass (25-point cubic uniform B-spline), against a
//! Möller–Trumbore ray–triangle test in the same run, so the headline is the
//! cost of one revolution intersection in triangle tests. The floor: an
//! open cylinder intersected in closed form (a quadratic) and by the exact
//! intersector (as a degree-1 profile), on the same rays, with the same
//! outputs (checked to agree): what the simplest surface of revolution costs
//! without splines, and what the exact intersector's machinery costs on it.
//! The same for a rational profile: a NURBS sphere (`Nurbs::arc`, two
//! rational quarter arcs) through the exact intersector against the
//! ray–sphere quadratic, on the same rays, outputs checked to agree.
//! Tensor-product patches (`intersect_patch_*`): the certified patch search
//! and the Newton intersector on a gently curved bicubic, a folded bicubic
//! and the teapot's 32 patches (certified through `BezierPatches`' hierarchy,
//! Newton as a loop with a box test per patch), so the ray–patch cost reads
//! in triangle tests too.
//!
//! Each measured iteration is ONE ray from a precomputed set of 1024,
//! cycled: the median reads as time per ray. Ray sets:
//! - `random`: from a sphere around the bounding box through a random point
//!   of the box (hits and misses mixed, as in rendering);
//! - `perpendicular`: the same but with no component along the axis (the
//!   special path for `d_y = 0`);
//! - `grazing`: along the tangent plane of a random surface point, starting
//!   outside (near-tangent rays on silhouettes, the hard case).
//!
//! Batches (`intersect_batch_*`, issue 19): the single-ray `intersect` and
//! `Intersect::intersect_batch` on the same rays in batches of
//! [`LANES`], each iteration one batch, the measured time divided by
//! `LANES`: the median reads as time per ray, like every other figure here
//! (`intersect_triangle/moller_trumbore/random` is the unit). Ray sets:
//! `random` (as above, the same rays as `exact/random`) and `camera`, the
//! primary rays of a pinhole camera looking at the object (64×64 pixels,
//! each batch 8 neighbouring pixels of one row: coherent rays;
//! `revolve_testkit::camera`, the ray caster's formulas).
//!
//! Run: `cargo bench -p revolve-benches --bench intersect` (CI: `-- --test`); the batch groups
//! and their unit alone: `cargo bench -p revolve-benches --bench intersect --
//! 'intersect_batch|intersect_triangle'`. The hit rate of every set is
//! printed once.

use revolve_testkit as common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use common::Rng;
use common::camera::{Camera, PinholeCamera};
use common::patch_shapes;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use revolve::nalgebra::{Point3, Unit, Vector3};
use revolve::{
    Aabb, BezierPatches, BezierSurface, Curve, Hit, Intersect, NewtonIntersector, PatchBounds, Ray,
    Revolution, Surface,
};

const N_RAYS: usize = 1024;
const MASK: usize = N_RAYS - 1;

/// Rays from a sphere around `b` through random points of `b`; with
/// `perpendicular`, the direction's y component is zero (axis = y).
fn box_rays(b: &Aabb, perpendicular: bool, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let radius = 2.0 * b.extent().norm();
    (0..N_RAYS)
        .map(|_| {
            let target = rng.point_in(b);
            let mut dir = rng.direction();
            if perpendicular {
                dir.y = 0.0;
                if dir.norm() < 1e-3 {
                    dir = Vector3::x();
                }
            }
            Ray::new(target - dir * radius, dir)
        })
        .collect()
}

/// Rays in the tangent plane of random surface points, starting outside.
fn grazing_rays<S: Surface + Intersect>(s: &S, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let [(u0, u1), (v0, v1)] = s.domain();
    let radius = 2.0 * s.bounds().extent().norm();
    let mut rays = Vec::with_capacity(N_RAYS);
    while rays.len() < N_RAYS {
        let (u, v) = (rng.range(u0, u1), rng.range(v0, v1));
        let Some(n) = s.normal(u, v) else { continue };
        let tangent = n.cross(&rng.direction());
        if tangent.norm() < 1e-3 {
            continue;
        }
        let dir = tangent.normalize();
        rays.push(Ray::new(s.eval(u, v) - dir * radius, dir));
    }
    rays
}

/// The Möller–Trumbore ray–triangle test (one-sided tolerance-free form):
/// the baseline unit of cost.
#[inline]
fn moller_trumbore(ray: &Ray, tri: &[Point3<f64>; 3], t_max: f64) -> Option<f64> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = ray.dir.cross(&e2);
    let det = e1.dot(&p);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = ray.origin - tri[0];
    let u = s.dot(&p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(&e1);
    let v = ray.dir.dot(&q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(&q) * inv;
    (t > 0.0 && t < t_max).then_some(t)
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(50)
}

/// Patch-tree depths of the Newton intersector benchmarked.
const NEWTON_DEPTHS: [u32; 2] = [6, 10];

fn bench_surface<S: PatchBounds + Intersect>(c: &mut Criterion, name: &str, s: &S) {
    let b = s.bounds();
    let sets = [
        ("random", box_rays(&b, false, 1)),
        ("perpendicular", box_rays(&b, true, 2)),
        ("grazing", grazing_rays(s, 3)),
    ];
    let newton: Vec<_> = NEWTON_DEPTHS
        .iter()
        .map(|&depth| (depth, NewtonIntersector::new(s, depth)))
        .collect();
    let mut group = c.benchmark_group(format!("intersect_{name}"));
    for (set, rays) in &sets {
        let hits = rays
            .iter()
            .filter(|r| s.intersect(r, 0.0, f64::INFINITY).is_some())
            .count();
        eprintln!("{name}/{set}: {hits} of {N_RAYS} rays hit (exact)");
        let mut i = 0;
        group.bench_function(BenchmarkId::new("exact", set), |bench| {
            bench.iter(|| {
                i = (i + 1) & MASK;
                black_box(s).intersect(black_box(&rays[i]), 0.0, f64::INFINITY)
            })
        });
        for (depth, n) in &newton {
            let hits = rays
                .iter()
                .filter(|r| n.intersect(r, 0.0, f64::INFINITY).is_some())
                .count();
            eprintln!("{name}/{set}: {hits} of {N_RAYS} rays hit (Newton, depth {depth})");
            let mut i = 0;
            let id = BenchmarkId::new(format!("newton_depth_{depth}"), set);
            group.bench_function(id, |bench| {
                bench.iter(|| {
                    i = (i + 1) & MASK;
                    black_box(n).intersect(black_box(&rays[i]), 0.0, f64::INFINITY)
                })
            });
        }
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    let vase = Revolution::new(common::vase());
    let glass_profile = common::wine_glass();
    eprintln!(
        "wine glass: {} control points, {} spans",
        glass_profile.points().len(),
        glass_profile.bezier_spans().map_or(0, |s| s.len())
    );
    let glass = Revolution::new(glass_profile);
    bench_surface(c, "vase", &vase);
    bench_surface(c, "wine_glass", &glass);
    bench_batches(c, "vase", &vase);
    bench_batches(c, "wine_glass", &glass);

    // The baseline: one triangle, rays through its bounding box.
    let tri = [
        Point3::new(-1.0, -1.0, 0.0),
        Point3::new(1.0, -0.5, 0.2),
        Point3::new(0.1, 1.0, -0.1),
    ];
    let rays = box_rays(&Aabb::from_points(&tri).expand(0.1), false, 4);
    let hits = rays
        .iter()
        .filter(|r| moller_trumbore(r, &tri, f64::INFINITY).is_some())
        .count();
    eprintln!("triangle: {hits} of {N_RAYS} rays hit");
    let mut group = c.benchmark_group("intersect_triangle");
    let mut i = 0;
    group.bench_function(BenchmarkId::new("moller_trumbore", "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            moller_trumbore(black_box(&rays[i]), black_box(&tri), f64::INFINITY)
        })
    });
    group.finish();

    bench_cylinder_floor(c);
    bench_sphere_floor(c);
    bench_patches(c);
}

/// Rays per batch in the batch benches: the widest SIMD batch issue 19
/// asks for.
const LANES: usize = 8;

/// Pixels per side of the camera's image.
const CAMERA_PIXELS: u32 = 64;

/// The primary rays of a pinhole camera looking at the centre of `b` from
/// the direction `(0.35, 0.25, 1)` (slightly above and to the side), at
/// three times the radius of `b`'s bounding sphere, its vertical field of
/// view just wide enough for that sphere: [`CAMERA_PIXELS`]² rays through
/// the pixel centres, row by row, so consecutive [`LANES`] rays are
/// neighbours in one row.
fn camera_rays(b: &Aabb) -> Vec<Ray> {
    let radius = 0.5 * b.extent().norm();
    let back = Vector3::new(0.35, 0.25, 1.0).normalize();
    let distance = 3.0 * radius;
    PinholeCamera::new(&Camera {
        center: b.center() + back * distance,
        direction: -back,
        up: Vector3::y(),
        angle_degrees: 2.0 * (radius / distance).asin().to_degrees(),
        width: CAMERA_PIXELS,
        height: CAMERA_PIXELS,
    })
    .primary_rays()
}

/// Benchmarks `one_batch(k)` (the `k`-th batch of [`LANES`] rays, cycled
/// over `batches`) and reports the time per ray.
fn bench_per_ray(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: BenchmarkId,
    batches: usize,
    mut one_batch: impl FnMut(usize),
) {
    group.bench_function(id, |bench| {
        bench.iter_custom(|iters| {
            let start = Instant::now();
            for k in 0..iters {
                one_batch(k as usize % batches);
            }
            start.elapsed() / LANES as u32
        })
    });
}

/// The single-ray `intersect` (`single`) and `intersect_batch` in batches
/// of [`LANES`] (`batch8`) on the same random and camera rays, as time per
/// ray; the set-up checks that both give the same hits.
fn bench_batches<S: PatchBounds + Intersect>(c: &mut Criterion, name: &str, s: &S) {
    let b = s.bounds();
    let sets = [
        ("random", box_rays(&b, false, 1)),
        ("camera", camera_rays(&b)),
    ];
    let ranges = [(0.0, f64::INFINITY); LANES];
    let mut group = c.benchmark_group(format!("intersect_batch_{name}"));
    for (set, rays) in &sets {
        assert_eq!(rays.len() % LANES, 0);
        let batches = rays.len() / LANES;
        let mut hits = vec![None; rays.len()];
        for (chunk, out) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
            s.intersect_batch(chunk, &ranges, out);
        }
        for (ray, hit) in rays.iter().zip(&hits) {
            assert_eq!(*hit, s.intersect(ray, 0.0, f64::INFINITY), "{ray:?}");
        }
        let count = hits.iter().flatten().count();
        eprintln!(
            "{name}/{set}: {count} of {} rays hit (single and batch agree)",
            rays.len()
        );
        bench_per_ray(&mut group, BenchmarkId::new("single", set), batches, |k| {
            for ray in &rays[k * LANES..(k + 1) * LANES] {
                black_box(black_box(s).intersect(black_box(ray), 0.0, f64::INFINITY));
            }
        });
        let mut out = [None; LANES];
        bench_per_ray(&mut group, BenchmarkId::new("batch8", set), batches, |k| {
            let lanes = black_box(&rays[k * LANES..(k + 1) * LANES]);
            black_box(s).intersect_batch(lanes, &ranges, &mut out);
            black_box(&out);
        });
    }
    group.finish();
}

/// Radius and height of [`common::CYLINDER`].
fn cylinder_size() -> (f64, f64) {
    let [(r, _), (_, h)] = common::CYLINDER;
    (r, h)
}

/// The open cylinder `x² + z² = R²`, `0 ≤ y ≤ H`, in closed form, with every
/// output the exact intersector gives (t, point, unit normal, `(u, v)` in the
/// contract's parametrization `(R cos v, H u, −R sin v)`): what the simplest
/// surface of revolution costs with no spline at all.
#[inline]
fn closed_form_cylinder(ray: &Ray, t_max: f64) -> Option<Hit> {
    let (r, h) = cylinder_size();
    let (o, d) = (ray.origin, ray.dir);
    let a = d.x * d.x + d.z * d.z;
    let b = o.x * d.x + o.z * d.z;
    let c = o.x * o.x + o.z * o.z - r * r;
    let disc = b * b - a * c;
    if a == 0.0 || disc < 0.0 {
        return None;
    }
    // The root without cancellation, and its partner from the product.
    let q = -(b + b.signum() * disc.sqrt());
    let (t0, t1) = (q / a, c / q);
    let (t0, t1) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
    for t in [t0, t1] {
        let p = o + d * t;
        if t > 0.0 && t < t_max && (0.0..=h).contains(&p.y) {
            let v = (-p.z).atan2(p.x).rem_euclid(std::f64::consts::TAU);
            // The contract orients the normal as ∂S/∂u × ∂S/∂v: inward here.
            let normal = Unit::new_unchecked(Vector3::new(-p.x / r, 0.0, -p.z / r));
            let uv = (p.y / h, v);
            return Some(Hit {
                t,
                point: p,
                normal,
                uv,
            });
        }
    }
    None
}

/// The floor: the cylinder of [`common::CYLINDER`] in closed form and through the
/// exact intersector (a degree-1 profile), on the same random rays. The
/// set-up checks that both give the same hits.
fn bench_cylinder_floor(c: &mut Criterion) {
    let (_, h) = cylinder_size();
    let cylinder = common::bezier(&common::CYLINDER);
    let rays = box_rays(&cylinder.bounds(), false, 5);
    let mut hits = 0;
    for ray in &rays {
        let exact = cylinder.intersect(ray, 0.0, f64::INFINITY);
        let closed = closed_form_cylinder(ray, f64::INFINITY);
        match (exact, closed) {
            (None, None) => {}
            (Some(e), Some(c)) => {
                hits += 1;
                let agree = (e.t - c.t).abs() <= 1e-12 * c.t.max(1.0)
                    && (e.point - c.point).norm() <= 1e-12 * h
                    && (e.normal.into_inner() - c.normal.into_inner()).norm() <= 1e-12
                    && (e.uv.0 - c.uv.0).abs() <= 1e-12
                    && (e.uv.1 - c.uv.1).abs() <= 1e-12;
                assert!(
                    agree,
                    "closed form and exact differ on {ray:?}: {e:?} vs {c:?}"
                );
            }
            (e, cf) => panic!("closed form and exact disagree on {ray:?}: {e:?} vs {cf:?}"),
        }
    }
    eprintln!("cylinder: {hits} of {N_RAYS} rays hit (closed form and exact agree)");
    let mut group = c.benchmark_group("intersect_cylinder");
    let mut i = 0;
    group.bench_function(BenchmarkId::new("closed_form", "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            closed_form_cylinder(black_box(&rays[i]), f64::INFINITY)
        })
    });
    let mut i = 0;
    group.bench_function(BenchmarkId::new("exact", "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            black_box(&cylinder).intersect(black_box(&rays[i]), 0.0, f64::INFINITY)
        })
    });
    group.finish();
}

/// Radius of the benchmarked sphere.
const SPHERE_RADIUS: f64 = 1.0;

/// The sphere of radius [`SPHERE_RADIUS`] about the origin in closed form
/// (the stable ray–sphere quadratic), with every output the exact
/// intersector gives: `t`, the point, the unit normal (into the ball, as
/// the NURBS profile from the south to the north pole orients it), and
/// `(u, v)` in the sphere's own parametrization, `u` the latitude in
/// `[−π/2, π/2]` and `v` the angle of the contract
/// (`S = (R cos u cos v, R sin u, −R cos u sin v)`).
#[inline]
fn closed_form_sphere(ray: &Ray, t_max: f64) -> Option<Hit> {
    let r = SPHERE_RADIUS;
    let (o, d) = (ray.origin, ray.dir);
    let a = d.dot(&d);
    let b = o.coords.dot(&d);
    let c = o.coords.dot(&o.coords) - r * r;
    let disc = b * b - a * c;
    if a == 0.0 || disc < 0.0 {
        return None;
    }
    // The root without cancellation, and its partner from the product.
    let q = -(b + b.signum() * disc.sqrt());
    let (t0, t1) = (q / a, c / q);
    let (t0, t1) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
    let t = if t0 > 0.0 { t0 } else { t1 };
    if !(t > 0.0 && t < t_max) {
        return None;
    }
    let p = o + d * t;
    let normal = Unit::new_unchecked(-p.coords / r);
    let u = (p.y / r).clamp(-1.0, 1.0).asin();
    let v = (-p.z).atan2(p.x).rem_euclid(std::f64::consts::TAU);
    Some(Hit {
        t,
        point: p,
        normal,
        uv: (u, v),
    })
}

/// A NURBS sphere through the exact intersector against the closed-form
/// sphere, on the same random rays. The set-up checks that both give the
/// same hits (`t`, point, normal, and the angle `v`; `u` follows each one's
/// own parametrization of the meridian).
fn bench_sphere_floor(c: &mut Criterion) {
    let sphere = Revolution::new(common::conic_profiles::sphere_profile(SPHERE_RADIUS));
    assert!(sphere.has_exact_intersector());
    let rays = box_rays(&sphere.bounds(), false, 6);
    let mut hits = 0;
    for ray in &rays {
        let exact = sphere.intersect(ray, 0.0, f64::INFINITY);
        let closed = closed_form_sphere(ray, f64::INFINITY);
        match (exact, closed) {
            (None, None) => {}
            (Some(e), Some(c)) => {
                hits += 1;
                // Relative errors of 1e-12 plus 64 ulps amplified by the
                // hit's condition |d|/|d·n| (near-grazing rays); v as an
                // arc length on its parallel of radius ρ.
                let kappa = ray.dir.norm() / ray.dir.dot(&c.normal).abs();
                let tol = 1e-12 + 64.0 * f64::EPSILON * kappa;
                let rho = c.point.x.hypot(c.point.z);
                let dv = (e.uv.1 - c.uv.1).abs();
                let dv = dv.min((dv - std::f64::consts::TAU).abs());
                let agree = (e.t - c.t).abs() <= tol * c.t.max(1.0)
                    && (e.point - c.point).norm() <= tol * SPHERE_RADIUS
                    && (e.normal.into_inner() - c.normal.into_inner()).norm() <= tol
                    && dv * rho <= tol * SPHERE_RADIUS;
                assert!(
                    agree,
                    "closed form and exact differ on {ray:?}: {e:?} vs {c:?}"
                );
            }
            (e, cf) => panic!("closed form and exact disagree on {ray:?}: {e:?} vs {cf:?}"),
        }
    }
    eprintln!("sphere: {hits} of {N_RAYS} rays hit (closed form and exact NURBS agree)");
    let mut group = c.benchmark_group("intersect_sphere");
    let mut i = 0;
    group.bench_function(BenchmarkId::new("closed_form", "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            closed_form_sphere(black_box(&rays[i]), f64::INFINITY)
        })
    });
    let mut i = 0;
    group.bench_function(BenchmarkId::new("exact_nurbs", "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            black_box(&sphere).intersect(black_box(&rays[i]), 0.0, f64::INFINITY)
        })
    });
    group.finish();
}

/// Per-patch intersectors, each with its patch's box.
type PatchParts<T> = Vec<(Aabb, T)>;

/// A model of Bézier patches ray-cast as a loop over its patches, each
/// behind a test of its box (no hierarchy); `hit` is the per-patch
/// intersector, searched up to the nearest hit so far. One patch is
/// intersected directly.
fn patch_loop<T>(
    parts: &[(Aabb, T)],
    ray: &Ray,
    hit: impl Fn(&T, &Ray, f64) -> Option<Hit>,
) -> Option<Hit> {
    if let [(_, only)] = parts {
        return hit(only, ray, f64::INFINITY);
    }
    let mut best: Option<Hit> = None;
    let mut reach = f64::INFINITY;
    for (bounds, part) in parts {
        if bounds.clip(ray, 0.0, reach).is_none() {
            continue;
        }
        if let Some(h) = hit(part, ray, reach) {
            reach = h.t;
            best = Some(h);
        }
    }
    best
}

/// Tensor-product patches: the certified patch search and the Newton
/// intersector (patch-tree depths 6 and 10) on a gently curved bicubic
/// patch, a folded bicubic (rays can cross it several times) and Newell's
/// teapot (32 bicubic patches: the certified search through
/// `BezierPatches`' hierarchy, `certified_bvh`; Newton as a loop over the
/// patches with a box test each, `newton_depth_*_patch_loop`), on random
/// rays through each model's box.
fn bench_patches(c: &mut Criterion) {
    let teapot = common::teapot::patches();
    let teapot_model = BezierPatches::new(teapot.clone()).expect("32 patches");
    let gentle = patch_shapes::gentle_bicubic();
    let folded = common::tensor_shapes::folded_bicubic();
    let models: [(&str, Vec<BezierSurface>, &dyn Intersect); 3] = [
        ("bicubic", vec![gentle.clone()], &gentle),
        ("folded", vec![folded.clone()], &folded),
        ("teapot", teapot, &teapot_model),
    ];
    for (name, patches, certified) in &models {
        let (suffix, loop_suffix) = if patches.len() > 1 {
            ("_bvh", "_patch_loop")
        } else {
            ("", "")
        };
        // Through the box of the control points (not the search's own,
        // tighter box), so that the rays do not depend on how the search
        // cuts the patches.
        let net_box = Aabb::from_points(patches.iter().flat_map(|p| p.points().iter().flatten()));
        let rays = box_rays(&net_box, false, 9);
        let newton: Vec<(u32, PatchParts<NewtonIntersector<&BezierSurface>>)> = NEWTON_DEPTHS
            .iter()
            .map(|&depth| {
                let parts = patches
                    .iter()
                    .map(|p| (p.bounds(), NewtonIntersector::new(p, depth)))
                    .collect();
                (depth, parts)
            })
            .collect();
        let hits = rays
            .iter()
            .filter(|r| certified.intersect(r, 0.0, f64::INFINITY).is_some())
            .count();
        eprintln!("{name}: {hits} of {N_RAYS} rays hit (certified)");
        let mut group = c.benchmark_group(format!("intersect_patch_{name}"));
        let mut i = 0;
        let id = BenchmarkId::new(format!("certified{suffix}"), "random");
        group.bench_function(id, |bench| {
            bench.iter(|| {
                i = (i + 1) & MASK;
                black_box(*certified).intersect(black_box(&rays[i]), 0.0, f64::INFINITY)
            })
        });
        for (depth, parts) in &newton {
            let newton_hit =
                |ray: &Ray| patch_loop(parts, ray, |n, r, reach| n.intersect(r, 0.0, reach));
            let hits = rays.iter().filter(|r| newton_hit(r).is_some()).count();
            eprintln!("{name}: {hits} of {N_RAYS} rays hit (Newton, depth {depth})");
            let mut i = 0;
            let id = BenchmarkId::new(format!("newton_depth_{depth}{loop_suffix}"), "random");
            group.bench_function(id, |bench| {
                bench.iter(|| {
                    i = (i + 1) & MASK;
                    newton_hit(black_box(&rays[i]))
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = intersect;
    config = config();
    targets = benches
}
criterion_main!(intersect);

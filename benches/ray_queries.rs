//! What the other ray queries cost beside `intersect`: `occluded` (is
//! anything in the way) and `intersect_all` (every hit in order), per ray,
//! on a vase, the wine glass, a rational torus, a folded bicubic and the
//! teapot (32 patches through `BezierPatches`).
//!
//! Ray sets (1024 rays, cycled; each iteration one ray, so the median reads
//! as time per ray):
//! - `random`: from a sphere around the bounding box through a random point
//!   of the box, `t` in `(0, ∞)` (hits and misses mixed);
//! - `shadow`: from the hit points of the `random` rays toward a light
//!   outside the box (`t` in `(0, 1)`, the light at `t = 1`), leaving the
//!   surface as a shadow ray does: the workload `occluded` is for.
//!
//! The hit rate and the mean number of hits of each set are printed once.
//!
//! Run: `cargo bench -p revolve-benches --bench ray_queries` (CI: `-- --test`).

use revolve_testkit as common;

use std::hint::black_box;
use std::time::Duration;

use common::Rng;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use revolve::nalgebra::Vector3;
use revolve::{Aabb, BezierPatches, Intersect, Ray, Revolution};

const N_RAYS: usize = 1024;
const MASK: usize = N_RAYS - 1;

/// Rays from a sphere around `b` through random points of `b`.
fn box_rays(b: &Aabb, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let radius = 2.0 * b.extent().norm();
    (0..N_RAYS)
        .map(|_| {
            let target = rng.point_in(b);
            let dir = rng.direction();
            Ray::new(target - dir * radius, dir)
        })
        .collect()
}

/// From each hit of `rays` (cycled until there are [`N_RAYS`]) toward a
/// light above and beside the box: `t = 1` at the light.
fn shadow_rays<S: Intersect + ?Sized>(s: &S, rays: &[Ray]) -> Vec<Ray> {
    let b = s.bounds();
    let light = b.center() + Vector3::new(0.6, 1.0, 0.4) * b.extent().norm();
    let points: Vec<_> = rays
        .iter()
        .filter_map(|r| s.intersect(r, 0.0, f64::INFINITY))
        .map(|h| h.point)
        .collect();
    (0..N_RAYS)
        .map(|i| {
            let p = points[i % points.len()];
            Ray::new(p, light - p)
        })
        .collect()
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(50)
}

/// The three queries on each ray set of one object.
fn bench_object<S: Intersect + ?Sized>(c: &mut Criterion, name: &str, s: &S) {
    let random = box_rays(&s.bounds(), 5);
    let shadow = shadow_rays(s, &random);
    let mut group = c.benchmark_group(format!("ray_queries_{name}"));
    for (set, rays, t_max) in [("random", &random, f64::INFINITY), ("shadow", &shadow, 1.0)] {
        let mut hits = Vec::new();
        let (mut hit_rays, mut all_hits) = (0, 0);
        for r in rays.iter() {
            s.intersect_all(r, 0.0, t_max, &mut hits);
            hit_rays += usize::from(!hits.is_empty());
            all_hits += hits.len();
        }
        eprintln!(
            "{name}/{set}: {hit_rays} of {N_RAYS} rays hit, {:.2} hits a ray",
            all_hits as f64 / N_RAYS as f64
        );
        let mut i = 0;
        group.bench_function(BenchmarkId::new("intersect", set), |bench| {
            bench.iter(|| {
                i = (i + 1) & MASK;
                black_box(s).intersect(black_box(&rays[i]), 0.0, t_max)
            })
        });
        group.bench_function(BenchmarkId::new("occluded", set), |bench| {
            bench.iter(|| {
                i = (i + 1) & MASK;
                black_box(s).occluded(black_box(&rays[i]), 0.0, t_max)
            })
        });
        group.bench_function(BenchmarkId::new("intersect_all", set), |bench| {
            bench.iter(|| {
                i = (i + 1) & MASK;
                black_box(s).intersect_all(black_box(&rays[i]), 0.0, t_max, &mut hits);
                hits.len()
            })
        });
    }
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_object(c, "vase", &Revolution::new(common::vase()));
    bench_object(c, "wine_glass", &Revolution::new(common::wine_glass()));
    let torus = common::conic_profiles::torus_profile(1.0, 0.4);
    bench_object(c, "torus", &Revolution::new(torus));
    bench_object(c, "folded", &common::tensor_shapes::folded_bicubic());
    let teapot = BezierPatches::new(common::teapot::patches()).expect("32 patches");
    bench_object(c, "teapot", &teapot);
}

criterion_group! {
    name = ray_queries;
    config = config();
    targets = benches
}
criterion_main!(ray_queries);

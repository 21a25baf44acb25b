//! Nearest-point queries on surfaces (`nearest_point`): one query per
//! measured iteration, the query point cycling through 1024 pseudo-random
//! points of the surface's bounding box widened by half its extent on
//! every side (inside and outside closed surfaces, near and off open ones),
//! so the median reads as time per query. One surface per kind:
//!
//! - `revolution_sphere`: a NURBS half circle turned (the profile's
//!   certified nearest point in the query's meridian plane);
//! - `revolution_goblet`: the course wine glass (a 25-point uniform cubic
//!   B-spline, 22 spans);
//! - `bicubic`: the gently curved bicubic Bézier patch of the other benches;
//! - `nurbs_sphere_octant`: a biquadratic rational patch with a collapsed
//!   edge (the pole);
//! - `teapot`: Newell's 32 bicubic patches (`BezierPatches`).
//!
//! The fraction of certified answers is printed once per surface.
//!
//! Run: `cargo bench -p revolve-benches --bench nearest -- nearest_point`
//! (CI: `-- --test`).

use revolve_testkit as common;

use std::hint::black_box;
use std::time::Duration;

use common::Rng;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use revolve::nalgebra::Point3;
use revolve::{Aabb, BezierPatches, Error, Intersect, Revolution, SurfaceNearest};

const N_POINTS: usize = 1024;
const MASK: usize = N_POINTS - 1;

/// Points of `b` widened by half its extent on every side.
fn query_points(b: &Aabb, seed: u64) -> Vec<Point3<f64>> {
    let mut rng = Rng(seed);
    let wide = b.expand(0.5 * b.extent().amax());
    (0..N_POINTS).map(|_| rng.point_in(&wide)).collect()
}

/// One group member: the queries on one surface.
fn bench_kind(
    c: &mut Criterion,
    name: &str,
    bounds: &Aabb,
    nearest: impl Fn(&Point3<f64>) -> Result<SurfaceNearest, Error>,
) {
    let points = query_points(bounds, 11);
    let certified = points
        .iter()
        .filter(|p| nearest(p).is_ok_and(|n| n.certified))
        .count();
    eprintln!("{name}: {certified} of {N_POINTS} answers certified");
    let mut group = c.benchmark_group("nearest_point");
    let mut i = 0;
    group.bench_function(BenchmarkId::new(name, "random"), |bench| {
        bench.iter(|| {
            i = (i + 1) & MASK;
            nearest(black_box(&points[i]))
        })
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.0));
    bench_kind(c, "revolution_sphere", &sphere.bounds(), |p| {
        sphere.nearest_point(p)
    });
    let goblet = Revolution::new(common::wine_glass());
    bench_kind(c, "revolution_goblet", &goblet.bounds(), |p| {
        goblet.nearest_point(p)
    });
    let bicubic = common::patch_shapes::gentle_bicubic();
    bench_kind(c, "bicubic", &bicubic.bounds(), |p| {
        bicubic.nearest_point(p)
    });
    let octant = common::tensor_shapes::sphere_octant(1.0);
    bench_kind(c, "nurbs_sphere_octant", &octant.bounds(), |p| {
        octant.nearest_point(p)
    });
    let teapot = BezierPatches::new(common::teapot::patches()).expect("32 patches");
    bench_kind(c, "teapot", &teapot.bounds(), |p| teapot.nearest_point(p));
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(50)
}

criterion_group! {
    name = nearest;
    config = config();
    targets = benches
}
criterion_main!(nearest);

//! Discretization benches: uniform sampling (`Curve::discretize`) and adaptive
//! flattening to a tolerance (`flatten`).
//!
//! `discretize/*` measures one whole call; its throughput line is samples per
//! second (`segments + 1` samples per call). `flatten_*` measures one whole
//! flattening at each tolerance and prints, once per tolerance and outside the
//! timed loop, how many samples it produced and the bound it certified.
//!
//! Run: `cargo bench --bench discretize` (CI: `cargo bench --bench discretize -- --test`).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use revolve::nalgebra::{Point2, Point3};
use revolve::{BSpline, Bezier, Curve, Flattening};

const SEGMENTS: [usize; 3] = [16, 256, 4096];

/// Tolerances 1e-2, 1e-3, …, 1e-8.
const TOLERANCE_EXPONENTS: [i32; 7] = [2, 3, 4, 5, 6, 7, 8];

/// A deterministic pseudo-random walk (SplitMix64-driven), coordinates of order 1.
fn points3(count: usize, seed: u64) -> Vec<Point3<f64>> {
    let mut state = seed;
    let mut unit = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    };
    (0..count)
        .map(|i| {
            let s = i as f64 / (count - 1) as f64;
            Point3::new(
                (6.0 * s).cos() + 0.6 * unit() - 0.3,
                (6.0 * s).sin() + 0.6 * unit() - 0.3,
                2.0 * s - 1.0 + 0.2 * unit() - 0.1,
            )
        })
        .collect()
}

fn cubic_bezier_3d() -> Bezier<3> {
    Bezier::new(vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(0.3, 1.0, 0.2),
        Point3::new(0.8, -0.4, 0.7),
        Point3::new(1.0, 0.5, 1.0),
    ])
    .expect("valid cubic")
}

/// An S-shaped planar cubic, coordinates of order 1.
fn cubic_bezier_2d() -> Bezier<2> {
    Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(0.4, 1.0),
        Point2::new(0.6, -0.5),
        Point2::new(1.0, 0.5),
    ])
    .expect("valid cubic")
}

/// A wine-glass profile, (radius, height), 25 control points: foot, stem,
/// bowl outside up to the rim, then the inside of the bowl back down to the
/// axis.
fn wine_glass() -> BSpline<2> {
    let pts = [
        (0.00, 0.00),
        (0.00, 0.00),
        (0.20, 0.00),
        (0.35, 0.00),
        (0.36, 0.02),
        (0.30, 0.04),
        (0.12, 0.06),
        (0.05, 0.10),
        (0.04, 0.25),
        (0.04, 0.40),
        (0.05, 0.50),
        (0.12, 0.55),
        (0.28, 0.62),
        (0.38, 0.75),
        (0.40, 0.90),
        (0.36, 1.05),
        (0.33, 1.15),
        (0.34, 1.16),
        (0.32, 1.15),
        (0.36, 1.02),
        (0.37, 0.88),
        (0.34, 0.74),
        (0.24, 0.63),
        (0.00, 0.58),
        (0.00, 0.58),
    ];
    let pts = pts.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    BSpline::uniform(3, pts).expect("valid profile")
}

fn discretize(c: &mut Criterion) {
    let bezier = cubic_bezier_3d();
    let spline = BSpline::uniform(3, points3(100, 0x5EED)).expect("valid cubic B-spline");

    let mut group = c.benchmark_group("discretize_bezier_cubic");
    for segments in SEGMENTS {
        group.throughput(Throughput::Elements(segments as u64 + 1));
        group.bench_function(BenchmarkId::new("segments", segments), |b| {
            let curve = black_box(&bezier);
            b.iter(|| curve.discretize(black_box(segments)));
        });
    }
    group.finish();

    let mut group = c.benchmark_group("discretize_bspline_100_points");
    for segments in SEGMENTS {
        group.throughput(Throughput::Elements(segments as u64 + 1));
        group.bench_function(BenchmarkId::new("segments", segments), |b| {
            let curve = black_box(&spline);
            b.iter(|| curve.discretize(black_box(segments)));
        });
    }
    group.finish();
}

/// Benches `flatten(tolerance)` of one curve at every tolerance, printing the
/// sample count and certified bound once per tolerance.
fn bench_flatten<const D: usize>(
    c: &mut Criterion,
    name: &str,
    flatten: impl Fn(f64) -> Result<Flattening<D>, revolve::Error>,
) {
    let mut group = c.benchmark_group(name);
    for exp in TOLERANCE_EXPONENTS {
        let tolerance = 10f64.powi(-exp);
        let flat = flatten(tolerance).expect("tolerance within the supported range");
        eprintln!(
            "{name}: tolerance 1e-{exp}: {} samples, bound {:.3e}",
            flat.samples.len(),
            flat.bound
        );
        group.throughput(Throughput::Elements(flat.samples.len() as u64));
        group.bench_function(BenchmarkId::new("tolerance", format!("1e-{exp}")), |b| {
            b.iter(|| flatten(black_box(tolerance)));
        });
    }
    group.finish();
}

fn flatten(c: &mut Criterion) {
    let bezier2 = cubic_bezier_2d();
    let bezier3 = cubic_bezier_3d();
    let glass = wine_glass();
    bench_flatten(c, "flatten_bezier_cubic_2d", |tol| {
        black_box(&bezier2).flatten(tol)
    });
    bench_flatten(c, "flatten_bezier_cubic_3d", |tol| {
        black_box(&bezier3).flatten(tol)
    });
    bench_flatten(c, "flatten_bspline_wine_glass", |tol| {
        black_box(&glass).flatten(tol)
    });
}

fn config() -> Criterion {
    // 27 benches; this keeps a full run under two minutes.
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = discretize, flatten
}
criterion_main!(benches);

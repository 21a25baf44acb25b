//! Discretization benches: uniform sampling (`Curve::discretize`) and adaptive
//! flattening to a tolerance (`flatten`), and the arc length with its
//! certified bracket (`arc_length`).
//!
//! `discretize/*` measures one whole call; its throughput line is samples per
//! second (`segments + 1` samples per call). `flatten_*` measures one whole
//! flattening at each tolerance and prints, once per tolerance and outside the
//! timed loop, how many samples it produced and the bound it certified.
//! `arc_length/*` measures one whole call and prints, once, the bracket's
//! width and the number of pieces.
//!
//! Run: `cargo bench -p revolve-benches --bench discretize` (CI: `cargo bench -p revolve-benches --bench discretize -- --test`).

use revolve_testkit as common;

use std::hint::black_box;
use std::time::Duration;

use common::helix_points;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use revolve::nalgebra::{Point2, Point3};
use revolve::{BSpline, Bezier, Curve, Flattening, Nurbs};

const SEGMENTS: [usize; 3] = [16, 256, 4096];

/// Tolerances 1e-2, 1e-3, …, 1e-8.
const TOLERANCE_EXPONENTS: [i32; 7] = [2, 3, 4, 5, 6, 7, 8];

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

fn discretize(c: &mut Criterion) {
    let bezier = cubic_bezier_3d();
    let spline = BSpline::uniform(3, helix_points(100, 0x5EED)).expect("valid cubic B-spline");

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
    let glass = common::wine_glass();
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

/// One `arc_length` case: its bracket printed once, then timed.
fn bench_arc_length<C: Curve<2>>(c: &mut Criterion, name: &str, curve: &C, tolerance: f64) {
    let arc = curve.arc_length(tolerance).expect("a valid tolerance");
    println!(
        "arc_length/{name}: length {}, bracket width {:.2e}, error bound {:.2e}, {} pieces",
        arc.length,
        arc.upper - arc.lower,
        arc.error_bound,
        arc.pieces
    );
    c.bench_function(&format!("arc_length/{name}"), |b| {
        b.iter(|| black_box(curve).arc_length(tolerance))
    });
}

/// A circle (rational quadratics), a parabola, and a clamped cubic through
/// 30 random points of the unit square (sharp turns, where the speed dips).
fn arc_length(c: &mut Criterion) {
    let circle = Nurbs::circle(Point2::origin(), 3.0).expect("a valid circle");
    let parabola = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(0.5, 0.0),
        Point2::new(1.0, 1.0),
    ])
    .expect("a valid parabola");
    let mut rng = common::Rng(4);
    let points = (0..30)
        .map(|_| Point2::new(rng.unit(), rng.unit()))
        .collect();
    let spline = BSpline::clamped(3, points).expect("a valid spline");
    bench_arc_length(c, "circle_r3_tol_3e-12", &circle, 3e-12);
    bench_arc_length(c, "parabola_tol_1e-12", &parabola, 1e-12);
    bench_arc_length(c, "random_spline_30_tol_1e-10", &spline, 1e-10);
    bench_arc_length(c, "random_spline_30_tol_1e-6", &spline, 1e-6);
}

fn config() -> Criterion {
    // 31 benches; this keeps a full run under two minutes.
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = discretize, flatten, arc_length
}
criterion_main!(benches);

//! Constructions and ray-free intersections: one call per measured
//! iteration, on fixed inputs, so the median reads as time per call.
//!
//! - `interpolate/helix_100`: a cubic through 100 points of a noisy helix
//!   (centripetal parameters, knots by averaging, the banded solve);
//! - `fit/helix_400_to_40`: a least-squares cubic with 40 control points
//!   through 400 points;
//! - `split/goblet`: the course wine glass (22 cubic spans) split at a
//!   parameter inside a span (knot insertion to full multiplicity);
//! - `parameter_at_length/goblet`: the parameter at half the glass's
//!   length, tolerance `1e-9` of it;
//! - `reduce_degree/goblet_1e-4`: the glass as a quadratic within `1e-4`
//!   (pieces halved where needed, then knots removed);
//! - `from_revolution/goblet`: the glass's exact NURBS surface of
//!   revolution (degree 2 in the angle, four quarter arcs);
//! - `loft/five_circles`: a cubic loft through five parallel circles;
//! - `intersect_curves/circle_line`: every crossing of a circle and a line;
//! - `intersect_curves/wave_line`: a 40-point cubic zig-zag and a line
//!   (37 certified crossings, tolerance `1e-8`: the coordinates reach 11);
//! - `intersect_curves/copies`: a 9-span cubic against the same curve with
//!   two knots inserted (the overlap error, found by the one-arc proof);
//! - `intersect_space_curves/perpendicular_circles`: two unit circles in
//!   perpendicular planes through one centre (two crossings, the first
//!   projection seeing them edge-on);
//! - `intersect_surface/sphere_plane_1e-6`: the NURBS unit sphere and an
//!   oblique plane (one circle of radius 0.92, chords within `1e-6`);
//! - `intersect_curve/space_curve_bicubic`: a cubic space curve through
//!   the gently curved bicubic patch of the other benches.
//!
//! Run: `cargo bench -p revolve-benches --bench constructions`
//! (CI: `-- --test`).

use revolve_testkit as common;

use std::f64::consts::{FRAC_PI_2, TAU};
use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use revolve::curve::{intersect_curves, intersect_space_curves};
use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::{BSpline, Bezier, Curve, Error, Nurbs, NurbsSurface, Revolution};

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(30)
}

fn through_points(c: &mut Criterion) {
    let mut group = c.benchmark_group("constructions");
    let helix = common::helix_points(100, 7);
    group.bench_function(BenchmarkId::new("interpolate", "helix_100"), |b| {
        b.iter(|| BSpline::interpolate(3, black_box(&helix)))
    });
    let dense = common::helix_points(400, 7);
    group.bench_function(BenchmarkId::new("fit", "helix_400_to_40"), |b| {
        b.iter(|| BSpline::fit(3, black_box(&dense), 40))
    });
    let glass = common::wine_glass();
    let (lo, hi) = glass.domain();
    let inside = lo + 0.4321 * (hi - lo);
    group.bench_function(BenchmarkId::new("split", "goblet"), |b| {
        b.iter(|| black_box(&glass).split(inside))
    });
    let half = 0.5 * glass.arc_length(1e-12).expect("a length").length;
    group.bench_function(BenchmarkId::new("parameter_at_length", "goblet"), |b| {
        b.iter(|| black_box(&glass).parameter_at_length(half, 1e-9 * half))
    });
    let reduced = glass.reduce_degree(1e-4).expect("a quadratic within 1e-4");
    assert_eq!(reduced.degree(), 2);
    group.bench_function(BenchmarkId::new("reduce_degree", "goblet_1e-4"), |b| {
        b.iter(|| black_box(&glass).reduce_degree(1e-4))
    });
    let turned = Revolution::new(glass.clone());
    group.bench_function(BenchmarkId::new("from_revolution", "goblet"), |b| {
        b.iter(|| NurbsSurface::from_revolution(black_box(&turned)))
    });
    let circles: Vec<Nurbs<3>> = (0..5)
        .map(|k| {
            let z = k as f64;
            let radius = 1.0 + 0.3 * (1.3 * z).sin();
            Nurbs::arc_3d(
                Point3::new(0.0, 0.0, z),
                Vector3::z(),
                Vector3::x(),
                radius,
                0.0,
                TAU,
            )
            .expect("a circle")
        })
        .collect();
    group.bench_function(BenchmarkId::new("loft", "five_circles"), |b| {
        b.iter(|| NurbsSurface::loft(black_box(&circles), 3))
    });
    group.finish();
}

fn intersections(c: &mut Criterion) {
    let mut group = c.benchmark_group("constructions");
    let line = |a: (f64, f64), b: (f64, f64)| {
        Bezier::new(vec![Point2::new(a.0, a.1), Point2::new(b.0, b.1)]).expect("a line")
    };
    let circle = Nurbs::circle(Point2::new(0.1, -0.2), 1.5).expect("a circle");
    let chord = line((-2.0, 0.3), (2.5, -0.4));
    assert_eq!(
        intersect_curves(&circle, &chord, 1e-9).map(|x| x.len()),
        Ok(2)
    );
    group.bench_function(BenchmarkId::new("intersect_curves", "circle_line"), |b| {
        b.iter(|| intersect_curves(black_box(&circle), black_box(&chord), 1e-9))
    });
    let zigzag: Vec<Point2<f64>> = (0..40)
        .map(|i| Point2::new(i as f64 / 4.0, if i % 2 == 0 { 1.0 } else { -1.0 }))
        .collect();
    let wave = BSpline::clamped(3, zigzag).expect("a wave");
    let axis = line((-1.0, 0.0), (11.0, 0.0));
    // Coordinates up to 11: the tolerance at least 1.1e-9.
    let crossings = intersect_curves(&wave, &axis, 1e-8).expect("crossings");
    assert!(crossings.len() >= 37 && crossings.iter().all(|x| x.certified));
    group.bench_function(BenchmarkId::new("intersect_curves", "wave_line"), |b| {
        b.iter(|| intersect_curves(black_box(&wave), black_box(&axis), 1e-8))
    });
    let pts: Vec<Point2<f64>> = (0..12)
        .map(|i| Point2::new(i as f64 * 0.3, ((i * 7) % 5) as f64 * 0.2))
        .collect();
    let spline = BSpline::clamped(3, pts).expect("a spline");
    let refined = spline
        .insert_knot(0.37, 1)
        .and_then(|s| s.insert_knot(0.81, 2))
        .expect("knots inserted");
    assert!(matches!(
        intersect_curves(&spline, &refined, 1e-9),
        Err(Error::CurvesOverlap { .. })
    ));
    group.bench_function(BenchmarkId::new("intersect_curves", "copies"), |b| {
        b.iter(|| intersect_curves(black_box(&spline), black_box(&refined), 1e-9))
    });
    let o = Point3::new(0.2, -0.1, 0.3);
    let flat = Nurbs::arc_3d(o, Vector3::z(), Vector3::x(), 1.0, 0.0, TAU).expect("a circle");
    let upright = Nurbs::arc_3d(o, Vector3::x(), Vector3::y(), 1.0, 0.0, TAU).expect("a circle");
    assert_eq!(
        intersect_space_curves(&flat, &upright, 1e-9).map(|x| x.len()),
        Ok(2)
    );
    group.bench_function(
        BenchmarkId::new("intersect_space_curves", "perpendicular_circles"),
        |b| b.iter(|| intersect_space_curves(black_box(&flat), black_box(&upright), 1e-9)),
    );
    let sphere = NurbsSurface::from_revolution(&Revolution::new(
        Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2).expect("a half circle"),
    ))
    .expect("a sphere");
    let slope = Vector3::new(0.3, 1.0, 0.2).normalize();
    let e1 = slope.cross(&Vector3::z()).normalize();
    let e2 = slope.cross(&e1);
    let o = Point3::from(slope * 0.4);
    let cut = NurbsSurface::bilinear(
        o - 2.0 * e1 - 2.0 * e2,
        o + 2.0 * e1 - 2.0 * e2,
        o - 2.0 * e1 + 2.0 * e2,
        o + 2.0 * e1 + 2.0 * e2,
    )
    .expect("a plane");
    let curves = sphere.intersect_surface(&cut, 1e-6).expect("a circle");
    assert!(curves.len() == 1 && curves[0].closed);
    group.bench_function(
        BenchmarkId::new("intersect_surface", "sphere_plane_1e-6"),
        |b| b.iter(|| black_box(&sphere).intersect_surface(black_box(&cut), 1e-6)),
    );
    let patch = common::patch_shapes::gentle_bicubic();
    let bounds = revolve::Intersect::bounds(&patch);
    let (lo, hi) = (bounds.min, bounds.max);
    let through = BSpline::interpolate(
        3,
        &[
            Point3::new(lo.x, lo.y, hi.z + 1.0),
            Point3::new(0.7 * lo.x + 0.3 * hi.x, 0.5 * (lo.y + hi.y), hi.z),
            Point3::new(0.3 * lo.x + 0.7 * hi.x, 0.4 * lo.y + 0.6 * hi.y, lo.z),
            Point3::new(hi.x, hi.y, lo.z - 1.0),
        ],
    )
    .expect("a space curve");
    let hits = patch.intersect_curve(&through, 1e-9).expect("hits");
    assert!(
        !hits.is_empty() && hits.iter().all(|h| h.certified),
        "{hits:?}"
    );
    group.bench_function(
        BenchmarkId::new("intersect_curve", "space_curve_bicubic"),
        |b| b.iter(|| black_box(&patch).intersect_curve(black_box(&through), 1e-9)),
    );
    group.finish();
}

criterion_group! {
    name = constructions;
    config = config();
    targets = through_points, intersections
}
criterion_main!(constructions);

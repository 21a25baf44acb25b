//! Evaluation benches: points, first derivatives and higher derivatives of
//! Bézier curves and B-splines, the evaluation algorithms side by side, the
//! Cox–de Boor basis, and NURBS against the B-spline of the same degree,
//! knots and points (what the weights cost).
//!
//! Every measured iteration is ONE evaluation at the next parameter of a
//! precomputed table of 1024 pseudo-random parameters (cycled), so the median
//! reads directly as time per evaluation, the B-spline span search sees a new
//! span almost every call and the branch predictor cannot learn the sequence.
//! Consecutive evaluations are independent, so the figure is a throughput
//! (the CPU may overlap neighbouring calls), as in a sampling loop.
//! `eval_overhead/t_lookup` measures the parameter lookup alone.
//!
//! `nearest_point`: one certified nearest-point query per iteration, the
//! query point cycling through 1024 pseudo-random points around the curve;
//! `projector/…` on a prepared [`CurveProjector`], `method/…` through
//! [`Curve::nearest_point`] (which prepares the spans on every call).
//!
//! Run: `cargo bench -p revolve-benches --bench eval` (CI: `cargo bench -p revolve-benches --bench eval -- --test`).

use revolve_testkit as common;

use std::hint::black_box;
use std::time::Duration;

use common::{Rng, helix_points};
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use revolve::bernstein::{bernstein_sum, de_casteljau, horner, to_power_basis};
use revolve::nalgebra::{Point, Point2, Vector3};
use revolve::{BSpline, Bezier, Curve, CurveProjector, Nurbs, RationalBezier};

/// Number of precomputed parameters; a power of two so that cycling is a mask.
const N_T: usize = 1024;
const MASK: usize = N_T - 1;

/// Bézier degrees benchmarked.
const DEGREES: [usize; 3] = [3, 7, 15];

/// Control-point counts of the cubic B-splines benchmarked.
const POINT_COUNTS: [usize; 3] = [10, 100, 1000];

/// 1024 pseudo-random parameters in `[a, b)`.
fn parameters((a, b): (f64, f64), seed: u64) -> Box<[f64; N_T]> {
    let mut rng = Rng(seed);
    let mut ts = Box::new([0.0; N_T]);
    for t in ts.iter_mut() {
        *t = rng.range(a, b);
    }
    ts
}

/// Cycles through a parameter table, one parameter per call.
struct Cycle<'a> {
    ts: &'a [f64; N_T],
    i: usize,
}

impl<'a> Cycle<'a> {
    fn new(ts: &'a [f64; N_T]) -> Self {
        Self { ts, i: 0 }
    }

    #[inline(always)]
    fn next(&mut self) -> f64 {
        let t = self.ts[self.i & MASK];
        self.i = self.i.wrapping_add(1);
        black_box(t)
    }
}

fn bezier_curve(degree: usize) -> Bezier<3> {
    Bezier::new(helix_points(degree + 1, 0xB2 + degree as u64)).expect("valid control points")
}

fn cubic_bspline(points: usize) -> BSpline<3> {
    BSpline::uniform(3, helix_points(points, 0x5B + points as u64)).expect("valid cubic B-spline")
}

/// Benches `f(curve, t)` as `group/label/param`, one parameter per iteration.
fn bench_per_t<C, R>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: BenchmarkId,
    curve: &C,
    ts: &[f64; N_T],
    f: impl Fn(&C, f64) -> R,
) {
    group.bench_function(id, |b| {
        let curve = black_box(curve);
        let mut cycle = Cycle::new(ts);
        b.iter(|| f(curve, cycle.next()));
    });
}

fn overhead(c: &mut Criterion) {
    let ts = parameters((0.0, 1.0), 1);
    let mut group = c.benchmark_group("eval_overhead");
    group.throughput(Throughput::Elements(1));
    group.bench_function("t_lookup", |b| {
        let mut cycle = Cycle::new(&ts);
        b.iter(|| cycle.next());
    });
    group.finish();
}

fn bezier(c: &mut Criterion) {
    let ts = parameters((0.0, 1.0), 2);
    let curves: Vec<_> = DEGREES.iter().map(|&d| (d, bezier_curve(d))).collect();

    let mut group = c.benchmark_group("bezier_eval");
    group.throughput(Throughput::Elements(1));
    for (degree, curve) in &curves {
        let id = BenchmarkId::new("degree", degree);
        bench_per_t(&mut group, id, curve, &ts, |c, t| c.eval(t));
    }
    group.finish();

    let mut group = c.benchmark_group("bezier_derivative");
    group.throughput(Throughput::Elements(1));
    for (degree, curve) in &curves {
        let id = BenchmarkId::new("degree", degree);
        bench_per_t(&mut group, id, curve, &ts, |c, t| c.derivative(t));
    }
    group.finish();

    let mut group = c.benchmark_group("bezier_eval_with_derivative");
    group.throughput(Throughput::Elements(1));
    for (degree, curve) in &curves {
        let id = BenchmarkId::new("degree", degree);
        bench_per_t(&mut group, id, curve, &ts, |c, t| c.eval_with_derivative(t));
    }
    group.finish();

    // Orders 1..3 of the cubic (order 3 is the constant third hodograph).
    let cubic = &curves[0].1;
    let mut group = c.benchmark_group("bezier_nth_derivative_cubic");
    group.throughput(Throughput::Elements(1));
    for order in 1..=3 {
        let id = BenchmarkId::new("order", order);
        bench_per_t(&mut group, id, cubic, &ts, move |c, t| {
            c.nth_derivative(t, order).unwrap()
        });
    }
    group.finish();
}

fn bspline(c: &mut Criterion) {
    let curves: Vec<_> = POINT_COUNTS
        .iter()
        .map(|&n| {
            let curve = cubic_bspline(n);
            let ts = parameters(curve.domain(), 3 + n as u64);
            (n, curve, ts)
        })
        .collect();

    let mut group = c.benchmark_group("bspline_eval");
    group.throughput(Throughput::Elements(1));
    for (n, curve, ts) in &curves {
        let id = BenchmarkId::new("points", n);
        bench_per_t(&mut group, id, curve, ts, |c, t| c.eval(t));
    }
    group.finish();

    let mut group = c.benchmark_group("bspline_derivative");
    group.throughput(Throughput::Elements(1));
    for (n, curve, ts) in &curves {
        let id = BenchmarkId::new("points", n);
        bench_per_t(&mut group, id, curve, ts, |c, t| c.derivative(t));
    }
    group.finish();

    let mut group = c.benchmark_group("bspline_eval_with_derivative");
    group.throughput(Throughput::Elements(1));
    for (n, curve, ts) in &curves {
        let id = BenchmarkId::new("points", n);
        bench_per_t(&mut group, id, curve, ts, |c, t| c.eval_with_derivative(t));
    }
    group.finish();

    let mut group = c.benchmark_group("bspline_basis_functions");
    group.throughput(Throughput::Elements(1));
    for (n, curve, ts) in &curves {
        let id = BenchmarkId::new("points", n);
        group.bench_function(id, |b| {
            let curve = black_box(curve);
            let mut cycle = Cycle::new(ts);
            let mut out = [0.0; 4];
            b.iter(|| {
                let first = curve.basis_functions(cycle.next(), &mut out);
                black_box(&out);
                first
            });
        });
    }
    group.finish();

    // Orders 1..3 of the 100-point cubic.
    let (_, curve, ts) = &curves[1];
    let mut group = c.benchmark_group("bspline_nth_derivative_100_points");
    group.throughput(Throughput::Elements(1));
    for order in 1..=3 {
        let id = BenchmarkId::new("order", order);
        bench_per_t(&mut group, id, curve, ts, move |c, t| {
            c.nth_derivative(t, order).unwrap()
        });
    }
    group.finish();
}

/// The cubic B-spline of [`cubic_bspline`] and NURBS on the same degree,
/// knots and points: with weights drawn from `[0.5, 2]` (rational pieces:
/// de Casteljau on homogeneous points, then the division) and with unit
/// weights (the polynomial pieces, no division). Points and first
/// derivatives, one parameter per iteration as above.
fn nurbs(c: &mut Criterion) {
    let n = POINT_COUNTS[1];
    let spline = cubic_bspline(n);
    let mut rng = Rng(0x4E);
    let weights: Vec<f64> = (0..n).map(|_| rng.range(0.5, 2.0)).collect();
    let rational = Nurbs::new(
        3,
        spline.knots().to_vec(),
        spline.points().to_vec(),
        weights,
    )
    .expect("valid NURBS");
    let unit = Nurbs::from(spline.clone());
    let ts = parameters(spline.domain(), 5);

    for (what, with_derivative) in [("eval", false), ("eval_with_derivative", true)] {
        let mut group = c.benchmark_group(format!("nurbs_vs_bspline_{what}_{n}_points"));
        group.throughput(Throughput::Elements(1));
        let id = |name: &str| BenchmarkId::new(name, "cubic");
        if with_derivative {
            bench_per_t(&mut group, id("bspline"), &spline, &ts, |c, t| {
                c.eval_with_derivative(t)
            });
            bench_per_t(&mut group, id("nurbs"), &rational, &ts, |c, t| {
                c.eval_with_derivative(t)
            });
            bench_per_t(&mut group, id("nurbs_unit_weights"), &unit, &ts, |c, t| {
                c.eval_with_derivative(t)
            });
        } else {
            bench_per_t(&mut group, id("bspline"), &spline, &ts, |c, t| c.eval(t));
            bench_per_t(&mut group, id("nurbs"), &rational, &ts, |c, t| c.eval(t));
            bench_per_t(&mut group, id("nurbs_unit_weights"), &unit, &ts, |c, t| {
                c.eval(t)
            });
        }
        group.finish();
    }
}

/// The same 3D Bernstein polynomial evaluated three ways: de Casteljau (the
/// library's evaluator; on a copy, since it works in place), the term-by-term
/// Bernstein sum, and Horner on power-basis coefficients converted once up
/// front.
fn algorithms(c: &mut Criterion) {
    let ts = parameters((0.0, 1.0), 4);
    let mut group = c.benchmark_group("bezier_algorithms");
    group.throughput(Throughput::Elements(1));
    for degree in DEGREES {
        let coeffs: Vec<Vector3<f64>> = helix_points(degree + 1, 0xA1 + degree as u64)
            .into_iter()
            .map(|p| p.coords)
            .collect();
        let power = to_power_basis(&coeffs);

        group.bench_function(BenchmarkId::new("de_casteljau", degree), |b| {
            let coeffs = black_box(&coeffs[..]);
            let mut scratch = [Vector3::zeros(); 16];
            let mut cycle = Cycle::new(&ts);
            b.iter(|| {
                let s = &mut scratch[..coeffs.len()];
                s.copy_from_slice(coeffs);
                de_casteljau(s, cycle.next())
            });
        });
        group.bench_function(BenchmarkId::new("bernstein_sum", degree), |b| {
            let coeffs = black_box(&coeffs[..]);
            let mut cycle = Cycle::new(&ts);
            b.iter(|| bernstein_sum(coeffs, cycle.next()));
        });
        group.bench_function(BenchmarkId::new("horner", degree), |b| {
            let power = black_box(&power[..]);
            let mut cycle = Cycle::new(&ts);
            b.iter(|| horner(power, cycle.next()));
        });
    }
    group.finish();
}

/// 1024 pseudo-random points in the curve's box grown by half its size
/// on every side.
fn query_points<const D: usize>(curve: &impl Curve<D>, seed: u64) -> Vec<Point<f64, D>> {
    let samples = curve.discretize(256);
    let (mut lo, mut hi) = (samples[0].point, samples[0].point);
    for s in &samples {
        lo = lo.inf(&s.point);
        hi = hi.sup(&s.point);
    }
    let margin = (hi - lo) * 0.5;
    let mut rng = Rng(seed);
    (0..N_T)
        .map(|_| {
            Point::from(std::array::from_fn(|c| {
                rng.range(lo[c] - margin[c], hi[c] + margin[c])
            }))
        })
        .collect()
}

/// Benches one nearest-point query per iteration on `projector`.
fn bench_nearest<const D: usize>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    projector: &CurveProjector<D>,
    points: &[Point<f64, D>],
) {
    group.bench_function(BenchmarkId::new("projector", id), |b| {
        let projector = black_box(projector);
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & MASK;
            projector.nearest(black_box(&points[i]))
        });
    });
}

fn nearest_point(c: &mut Criterion) {
    let spline = cubic_bspline(10);
    let bezier = bezier_curve(7);
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let quarter = RationalBezier::new(
        vec![
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ],
        vec![1.0, h, 1.0],
    )
    .expect("valid quarter circle");
    let spline_points = query_points(&spline, 21);
    let mut group = c.benchmark_group("nearest_point");
    group.throughput(Throughput::Elements(1));
    bench_nearest(
        &mut group,
        "cubic_bspline_10",
        &CurveProjector::new(&spline).expect("curve with spans"),
        &spline_points,
    );
    bench_nearest(
        &mut group,
        "bezier_7",
        &CurveProjector::new(&bezier).expect("curve with spans"),
        &query_points(&bezier, 22),
    );
    bench_nearest(
        &mut group,
        "rational_quarter_circle",
        &CurveProjector::new(&quarter).expect("curve with spans"),
        &query_points(&quarter, 23),
    );
    group.bench_function(BenchmarkId::new("method", "cubic_bspline_10"), |b| {
        let spline = black_box(&spline);
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & MASK;
            spline.nearest_point(black_box(&spline_points[i]))
        });
    });
    group.finish();
}

fn config() -> Criterion {
    // About 45 benches; this keeps a full run around three minutes.
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = overhead, bezier, bspline, nurbs, algorithms, nearest_point
}
criterion_main!(benches);

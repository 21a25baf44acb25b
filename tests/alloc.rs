//! Evaluation does not touch the heap for degrees up to 16.
//!
//! A counting global allocator wraps the system allocator and counts
//! allocations (including zeroed allocations and reallocations) per thread,
//! so the test threads running in parallel do not see each other's
//! allocations. Each check runs the operation between two readings of the
//! current thread's counter.

mod common;

use common::{allocations_in, allocations_so_far};
use revolve::nalgebra::{Point, SVector};
use revolve::{BSpline, Bezier, Curve};
use std::hint::black_box;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

#[global_allocator]
static GLOBAL: common::CountingAllocator = common::CountingAllocator;

/// `n` control points in `D` dimensions with distinct coordinates.
fn points<const D: usize>(n: usize) -> Vec<Point<f64, D>> {
    (0..n)
        .map(|i| {
            let v = SVector::<f64, D>::from_fn(|r, _| ((i * 7 + r * 3) % 11) as f64 - 5.0);
            Point::from(v)
        })
        .collect()
}

const PARAMS: [f64; 9] = [
    0.0,
    1e-9,
    0.25,
    0.5,
    0.7,
    1.0,
    f64::NAN,
    -3.0,
    f64::INFINITY,
];

/// Asserts that every evaluation entry point of a degree-`degree` Bézier in
/// `D` dimensions runs without allocating.
fn check_bezier<const D: usize>(degree: usize) {
    let c = Bezier::new(points::<D>(degree + 1)).unwrap();
    for t in PARAMS {
        let t = black_box(t);
        let what = format!("Bezier<{D}> degree {degree} t={t}");
        assert_eq!(allocations_in(|| c.eval(t)), 0, "eval: {what}");
        assert_eq!(allocations_in(|| c.derivative(t)), 0, "derivative: {what}");
        assert_eq!(
            allocations_in(|| c.eval_with_derivative(t)),
            0,
            "eval_with_derivative: {what}"
        );
        for order in 0..=degree + 1 {
            assert_eq!(
                allocations_in(|| c.nth_derivative(t, order)),
                0,
                "nth_derivative({order}): {what}"
            );
        }
    }
}

/// Splines of degree `p` in `D` dimensions: framework uniform, clamped, and
/// one with a repeated interior knot.
fn splines<const D: usize>(p: usize) -> Vec<BSpline<D>> {
    let n = p + 4;
    let mut knots: Vec<f64> = (0..=n + p).map(|i| i as f64).collect();
    // Repeat the knot at the middle of the domain p times (allowed up to p + 1).
    let mid = (p + n) / 2;
    for k in knots.iter_mut().skip(mid).take(p) {
        *k = mid as f64;
    }
    knots.sort_by(f64::total_cmp);
    vec![
        BSpline::uniform(p, points::<D>(n)).unwrap(),
        BSpline::clamped(p, points::<D>(n)).unwrap(),
        BSpline::new(p, knots, points::<D>(n)).unwrap(),
    ]
}

/// Asserts that every evaluation entry point of degree-`p` B-splines in `D`
/// dimensions runs without allocating.
fn check_bspline<const D: usize>(p: usize) {
    for c in splines::<D>(p) {
        let (a, b) = c.domain();
        let mut basis = vec![0.0; p + 1];
        let mut derivs = vec![0.0; (p + 2) * (p + 1)];
        let interior = c.knots()[p + 1..c.points().len()].to_vec();
        let ts = PARAMS
            .iter()
            .map(|&s| a + (b - a) * s)
            .chain(interior)
            .chain([a, b, f64::NAN]);
        for t in ts.collect::<Vec<_>>() {
            let t = black_box(t);
            let what = format!("BSpline<{D}> degree {p} knots {:?} t={t}", c.knots());
            assert_eq!(allocations_in(|| c.eval(t)), 0, "eval: {what}");
            assert_eq!(allocations_in(|| c.derivative(t)), 0, "derivative: {what}");
            assert_eq!(
                allocations_in(|| c.eval_with_derivative(t)),
                0,
                "eval_with_derivative: {what}"
            );
            for order in 0..=p + 1 {
                assert_eq!(
                    allocations_in(|| c.nth_derivative(t, order)),
                    0,
                    "nth_derivative({order}): {what}"
                );
            }
            assert_eq!(allocations_in(|| c.span(t)), 0, "span: {what}");
            assert_eq!(
                allocations_in(|| c.basis_functions(t, &mut basis).unwrap()),
                0,
                "basis_functions: {what}"
            );
            for order in 0..=p + 1 {
                assert_eq!(
                    allocations_in(|| c.basis_derivatives(t, order, &mut derivs).unwrap()),
                    0,
                    "basis_derivatives({order}): {what}"
                );
            }
        }
    }
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_1d() {
    (0..=16).for_each(check_bezier::<1>);
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_2d() {
    (0..=16).for_each(check_bezier::<2>);
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_3d() {
    (0..=16).for_each(check_bezier::<3>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_1d() {
    (0..=16).for_each(check_bspline::<1>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_2d() {
    (0..=16).for_each(check_bspline::<2>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_3d() {
    (0..=16).for_each(check_bspline::<3>);
}

// -------------------------------------- the counter can see allocations ----

#[test]
fn counter_sees_a_plain_allocation() {
    assert_eq!(allocations_in(|| Vec::<u64>::with_capacity(4)), 1);
    assert_eq!(allocations_in(|| Box::new(7u32)), 1);
    assert_eq!(allocations_in(|| String::from("spline")), 1);
    assert_eq!(allocations_in(|| 2 + 2), 0);
}

#[test]
fn very_high_degree_bezier_eval_allocates() {
    // Scratch beyond the stack buffers comes from the heap. (Degree 30 still
    // fits the crate's largest stack buffer, 102 entries, so it does not
    // allocate; 110 does not fit. Much higher degrees have derivatives too
    // large for a double and are refused: `Error::DerivativeOverflow`.)
    let c = Bezier::new(points::<2>(111)).unwrap();
    let t = black_box(0.3);
    assert!(allocations_in(|| c.eval(t)) >= 1);
    assert!(allocations_in(|| c.nth_derivative(t, 2)) >= 1);
    let s = BSpline::clamped(110, points::<2>(111)).unwrap();
    let u = black_box(s.domain().0);
    assert!(allocations_in(|| s.eval(u)) >= 1);
}

#[test]
fn operations_that_return_collections_allocate() {
    let c = Bezier::new(points::<2>(4)).unwrap();
    assert!(allocations_in(|| c.discretize(8)) >= 1);
    assert!(allocations_in(|| c.subdivide(0.5).unwrap()) >= 1);
    assert!(allocations_in(|| c.hodograph()) >= 1);
    let s = BSpline::clamped(3, points::<2>(7)).unwrap();
    assert!(allocations_in(|| s.discretize(8)) >= 1);
    assert!(allocations_in(|| s.to_bezier_spans()) >= 1);
    assert!(allocations_in(|| s.derivative_spline()) >= 1);
}

#[test]
fn counts_are_per_thread() {
    // Another thread allocates continuously while this one evaluates; this
    // thread's count must stay at zero, and the other thread's must grow.
    let stop = Arc::new(AtomicBool::new(false));
    let churned = Arc::new(AtomicUsize::new(0));
    let worker = {
        let (stop, churned) = (Arc::clone(&stop), Arc::clone(&churned));
        std::thread::spawn(move || {
            let start = allocations_so_far();
            while !stop.load(Ordering::Relaxed) {
                black_box(vec![0u8; 64]);
                churned.store(allocations_so_far() - start, Ordering::Relaxed);
            }
        })
    };
    let c = BSpline::uniform(3, points::<3>(10)).unwrap();
    let mut spins = 0u64;
    let during = allocations_in(|| {
        // Evaluate until the other thread has made many allocations.
        while churned.load(Ordering::Relaxed) < 10_000 {
            black_box(c.eval(black_box(0.5)));
            spins += 1;
        }
    });
    stop.store(true, Ordering::Relaxed);
    worker.join().unwrap();
    assert!(churned.load(Ordering::Relaxed) >= 10_000);
    assert_eq!(during, 0, "after {spins} evaluations");
}

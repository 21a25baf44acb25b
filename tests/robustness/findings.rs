//! The minimal reproductions of the findings of a seeded fuzzer and of a
//! new user's first hours, one named test each: every call returns (an
//! `Err`, a miss or a documented value) promptly, never panics, and never
//! returns NaN where a number is promised.

use revolve::bernstein::{bernstein, binomial};
use revolve::nalgebra::{Point2, Point3, Vector2, Vector3};
use revolve::{Bezier, Intersect, Nurbs, RationalBezier, Ray, Revolution};
use std::sync::mpsc;
use std::thread;
use std::time::Duration;

/// Runs `f` on a worker thread and returns its value, failing the test if
/// it has not returned within `seconds` (the worker is then left behind).
fn returns_within<R: Send + 'static>(seconds: u64, f: impl FnOnce() -> R + Send + 'static) -> R {
    let (send, receive) = mpsc::channel();
    thread::spawn(move || {
        let _ = send.send(f());
    });
    match receive.recv_timeout(Duration::from_secs(seconds)) {
        Ok(value) => value,
        Err(_) => panic!("the call did not return within {seconds} s"),
    }
}

fn p(x: f64, y: f64) -> Point2<f64> {
    Point2::new(x, y)
}

#[test]
fn rational_bezier_derivatives_into_an_empty_slice_do_nothing() {
    let curve = RationalBezier::new(vec![p(0.0, 0.0), p(1.0, 1.0)], vec![1.0, 2.0]).unwrap();
    let mut none: [Vector2<f64>; 0] = [];
    assert_eq!(curve.derivatives(0.5, &mut none), Ok(()));
    // As a NURBS curve does.
    let nurbs = Nurbs::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![p(0.0, 0.0), p(1.0, 1.0)],
        vec![1.0, 2.0],
    )
    .unwrap();
    assert_eq!(nurbs.derivatives(0.5, &mut none), Ok(()));
}

#[test]
fn binomials_of_huge_arguments_return_at_once() {
    let (huge, half) = returns_within(5, || {
        (
            binomial(usize::MAX, usize::MAX / 2),
            binomial(usize::MAX, 3),
        )
    });
    assert_eq!(huge, f64::INFINITY);
    // C(n, 3) = n(n−1)(n−2)/6, here about 1.05e56.
    let n = usize::MAX as f64;
    assert!((half / (n * n * n / 6.0) - 1.0).abs() < 1e-12, "{half}");
    assert_eq!(binomial(2000, 1000), f64::INFINITY);
    assert_eq!(binomial(60, 30), 118_264_581_564_861_424.0);
}

#[test]
fn bernstein_values_are_never_nan_and_sum_to_one() {
    let degrees = [0, 1, 5, 30, 1_000, 5_000, 1 << 20, usize::MAX];
    let ts = [
        0.0,
        1e-300,
        0.25,
        0.5,
        1.0,
        -0.5,
        1.5,
        1e10,
        -1e10,
        f64::INFINITY,
    ];
    let values = returns_within(10, move || {
        let mut values = Vec::new();
        for n in degrees {
            for i in [0, 1, n / 3, n / 2, n - n.min(1), n] {
                for t in ts {
                    values.push((n, i, t, bernstein(n, i, t)));
                }
            }
        }
        values
    });
    for (n, i, t, b) in values {
        assert!(!b.is_nan(), "B({i}, {n})({t}) is NaN");
        if (0.0..=1.0).contains(&t) {
            assert!((0.0..=1.0).contains(&b), "B({i}, {n})({t}) = {b}");
        }
    }
    // Partition of unity at degrees whose binomials overflow.
    for (n, t) in [(2_000, 0.3), (5_000, 0.5), (3_000, 1e-3)] {
        let sum: f64 = (0..=n).map(|i| bernstein(n, i, t)).sum();
        assert!((sum - 1.0).abs() < 1e-9, "degree {n} at {t}: {sum}");
    }
}

#[test]
fn a_revolution_of_subnormal_size_is_intersected_at_once() {
    // A cylinder of radius and half-height 1e-310 about the origin.
    let profile = Bezier::new(vec![p(1e-310, -1e-310), p(1e-310, 1e-310)]).unwrap();
    let surface = Revolution::new(profile);
    // Through the origin at t = 2, and 1e-3 beside it.
    let through = Ray::new(Point3::new(2.0, 0.3, 0.4), Vector3::new(-1.0, -0.15, -0.2));
    let beside = Ray::new(
        Point3::new(2.0, 0.301, 0.4),
        Vector3::new(-1.0, -0.15, -0.2),
    );
    let (hit, miss, bounds) = returns_within(5, move || {
        (
            surface.intersect(&through, 0.0, f64::INFINITY),
            surface.intersect(&beside, 0.0, f64::INFINITY),
            surface.bounds(),
        )
    });
    let hit = hit.expect("the ray through the origin meets the cylinder");
    assert!((hit.t - 2.0).abs() < 1e-12, "{hit:?}");
    let radius = hit.point.x.hypot(hit.point.z);
    assert!((radius / 1e-310 - 1.0).abs() < 1e-6, "{hit:?}");
    assert!(hit.point.y.abs() <= 1e-310, "{hit:?}");
    assert!(miss.is_none(), "{miss:?}");
    assert!(
        bounds.min.x <= -1e-310 && bounds.max.y >= 1e-310,
        "{bounds:?}"
    );
    assert!(bounds.max.x < 1e-300, "{bounds:?}");
}

//! Degree reduction (`Bezier::reduce_degree`, `BSpline::reduce_degree`):
//! an elevated curve comes back (a second algorithm, degree elevation, as
//! the reference: the points and knots within `1e-13` of the size); the
//! bound the reduction reports holds against dense sampling of the two
//! curves (an independent measure of their distance); the end points are
//! kept exactly; every error path.

use revolve_testkit as common;

use common::Rng;
use proptest::prelude::*;
use revolve::nalgebra::{Point, Point2, Point3};
use revolve::{BSpline, Bezier, Curve, Error};

fn random_points<const D: usize>(rng: &mut Rng, count: usize) -> Vec<Point<f64, D>> {
    (0..count)
        .map(|_| Point::from(std::array::from_fn(|_| rng.range(-1.0, 1.0))))
        .collect()
}

/// The largest distance between the curves at 4001 common parameters.
fn sampled_distance<const D: usize>(a: &impl Curve<D>, b: &impl Curve<D>) -> f64 {
    let (lo, hi) = a.domain();
    (0..=4000)
        .map(|k| {
            let t = lo + (hi - lo) * k as f64 / 4000.0;
            (a.eval(t) - b.eval(t)).norm()
        })
        .fold(0.0, f64::max)
}

/// The bound reduction reports: asked for a tolerance nothing meets.
fn reported_bound<const D: usize>(c: &Bezier<D>) -> f64 {
    match c.reduce_degree(f64::MIN_POSITIVE) {
        Err(Error::ReductionInexact { deviation, .. }) => deviation,
        other => panic!("{other:?}"),
    }
}

#[test]
fn an_elevated_bezier_comes_back() {
    let mut rng = Rng(0x2ed0);
    for n in 2..=9 {
        for _ in 0..20 {
            let c = Bezier::new(random_points::<3>(&mut rng, n)).unwrap();
            let back = c.elevate_degree(1).unwrap().reduce_degree(1e-13).unwrap();
            assert_eq!(back.degree(), c.degree());
            for (p, q) in back.points().iter().zip(c.points()) {
                assert!((p - q).norm() < 1e-13, "degree {}: {p} vs {q}", n - 1);
            }
        }
    }
}

#[test]
fn the_reported_bound_holds_and_the_ends_are_kept() {
    let mut rng = Rng(0x2ed1);
    for n in 3..=10 {
        for _ in 0..20 {
            let c = Bezier::new(random_points::<2>(&mut rng, n)).unwrap();
            let bound = reported_bound(&c);
            let reduced = c.reduce_degree(bound).unwrap();
            assert_eq!(reduced.degree(), n - 2);
            assert_eq!(reduced.points()[0], c.points()[0]);
            assert_eq!(reduced.points().last(), c.points().last());
            let sampled = sampled_distance(&c, &reduced);
            assert!(sampled <= bound, "degree {}: {sampled} > {bound}", n - 1);
        }
    }
}

#[test]
fn a_quadratic_reduced_is_its_chord_with_the_closed_form_bound() {
    // P₀ = (0, 0), P₁ = (1, h), P₂ = (2, 0): the line from P₀ to P₂; the
    // elevated line's middle point is (1, 0), so the bound is h; the true
    // distance is h/2 (at t = ½).
    for h in [1e-6, 0.25, 3.0] {
        let c = Bezier::new(vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, h),
            Point2::new(2.0, 0.0),
        ])
        .unwrap();
        let bound = reported_bound(&c);
        assert!((bound - h).abs() <= 1e-15 * 8.0 * 4.0, "{bound} vs {h}");
        let line = c.reduce_degree(h * 1.01).unwrap();
        assert_eq!(
            line.points(),
            &[Point2::new(0.0, 0.0), Point2::new(2.0, 0.0)]
        );
        assert!((sampled_distance(&c, &line) - h / 2.0).abs() < 1e-12);
    }
}

#[test]
fn an_elevated_spline_comes_back_with_its_knots() {
    let mut rng = Rng(0x2ed2);
    for p in 1..=5 {
        for case in 0..10 {
            let count = p + 1 + case;
            let c = BSpline::clamped(p, random_points::<3>(&mut rng, count)).unwrap();
            let back = c.elevate_degree(1).unwrap().reduce_degree(1e-12).unwrap();
            assert_eq!(back.degree(), p);
            assert_eq!(
                back.knots().len(),
                c.knots().len(),
                "degree {p}, case {case}"
            );
            for (a, b) in back.knots().iter().zip(c.knots()) {
                assert!((a - b).abs() < 1e-15, "{a} vs {b}");
            }
            assert!(sampled_distance(&c, &back) < 1e-12);
        }
    }
}

#[test]
fn a_spline_reduced_within_a_tolerance_stays_within_it() {
    // A cubic interpolant of a wave, reduced to a quadratic within
    // tolerances from 1e-2 to 1e-8: sampled against the original, within
    // the tolerance; pieces are halved where needed, so the knots grow as
    // the tolerance shrinks; at 1e-2 fewer knots than the pieces joined at
    // every break.
    let data: Vec<Point2<f64>> = (0..40)
        .map(|k| {
            let x = k as f64 / 39.0;
            Point2::new(x, (6.0 * x).sin() * 0.3)
        })
        .collect();
    let cubic = BSpline::interpolate(3, &data).unwrap();
    let pieces = cubic.bezier_spans().unwrap().len();
    let mut previous = 0;
    for tolerance in [1e-2, 1e-3, 1e-4, 1e-6, 1e-8] {
        let quadratic = cubic.reduce_degree(tolerance).unwrap();
        assert_eq!(quadratic.degree(), 2);
        assert_eq!(quadratic.domain(), cubic.domain());
        let d = sampled_distance(&cubic, &quadratic);
        assert!(d <= tolerance, "{tolerance}: {d}");
        let count = quadratic.knots().len();
        assert!(count >= previous, "{tolerance}: {count} < {previous}");
        if tolerance == 1e-2 {
            assert!(count < 2 * (pieces - 1) + 6, "{count}");
        }
        eprintln!(
            "tolerance {tolerance:e}: {count} knots (the cubic has {})",
            cubic.knots().len()
        );
        previous = count;
    }
}

#[test]
fn reduction_errors_name_the_problem() {
    let line = Bezier::new(vec![Point3::origin(), Point3::new(1.0, 1.0, 1.0)]).unwrap();
    assert_eq!(
        line.reduce_degree(1.0),
        Err(Error::DegreeTooLowToReduce { degree: 1 })
    );
    let c = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(2.0, -1.0),
        Point2::new(3.0, 0.0),
    ])
    .unwrap();
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.reduce_degree(bad),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    match c.reduce_degree(1e-3) {
        Err(Error::ReductionInexact {
            deviation,
            tolerance,
        }) => {
            assert!(deviation > 0.1 && tolerance == 1e-3);
            let text = Error::ReductionInexact {
                deviation,
                tolerance,
            }
            .to_string();
            assert!(text.contains("tolerance"), "{text}");
        }
        other => panic!("{other:?}"),
    }
    let spline = BSpline::clamped(1, vec![Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)]).unwrap();
    assert_eq!(
        spline.reduce_degree(1.0),
        Err(Error::DegreeTooLowToReduce { degree: 1 })
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

    /// For any Bézier curve of degree 2–12 in a box of any size, the
    /// reduction within its own bound stays within that bound.
    #[test]
    fn the_bound_holds_for_random_curves(
        n in 3usize..=13,
        seed in any::<u64>(),
        size in -3.0f64..3.0,
    ) {
        let mut rng = Rng(seed | 1);
        let scale = 10f64.powf(size * 10.0);
        let pts: Vec<Point2<f64>> = random_points::<2>(&mut rng, n)
            .into_iter()
            .map(|p| Point2::from(p.coords * scale))
            .collect();
        let c = Bezier::new(pts).unwrap();
        let bound = reported_bound(&c);
        let reduced = c.reduce_degree(bound).unwrap();
        prop_assert!(sampled_distance(&c, &reduced) <= bound);
    }
}

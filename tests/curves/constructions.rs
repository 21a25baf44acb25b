//! Curves through data: `BSpline::interpolate` and `BSpline::fit`.
//!
//! References, all independent of the library's code:
//! - the centripetal parameters and the knots (by averaging, eq. 9.8 of
//!   Piegl & Tiller) recomputed here from their definitions, and the curve
//!   evaluated there: interpolation passes through every point to
//!   `1e-12 ×` the data's size;
//! - closed forms: equally spaced collinear points give the straight line
//!   at uniform speed (the line is in every spline space, so interpolation
//!   and the least-squares fit reproduce it exactly); unequally spaced
//!   ones give a curve on that line; points on a circle give curves whose
//!   radial error falls at the rate of a cubic spline (`h⁴`) as the points
//!   grow;
//! - similarity invariance (centripetal parameters are invariant under
//!   rotation, translation and uniform scaling);
//! - the least-squares optimality conditions: the fit's residuals at the
//!   data are orthogonal to every free basis function,
//!   `Σₖ Nᵢ(ūₖ)(Qₖ − C(ūₖ)) = 0` for `i = 1 … C − 2`, with the basis
//!   values from `BSpline::basis_functions`; the end points are exact;
//! - every error path, with its exact variant.

use revolve_testkit as common;

use common::Rng;
use proptest::prelude::*;
use revolve::nalgebra::{Point, Point1, Point2, Point3, Rotation3, SVector, Vector3};
use revolve::{BSpline, Curve, Error, MAX_COORDINATE};

/// `count` points with coordinates uniform in `[−1, 1]`.
fn random_points<const D: usize>(rng: &mut Rng, count: usize) -> Vec<Point<f64, D>> {
    (0..count)
        .map(|_| Point::from(std::array::from_fn(|_| rng.range(-1.0, 1.0))))
        .collect()
}

/// The largest coordinate magnitude (the data's size).
fn size<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points.iter().fold(0.0_f64, |m, p| m.max(p.coords.amax()))
}

/// Centripetal parameters from their definition: `ū₀ = 0`, steps
/// proportional to the square roots of the chord lengths, `ū_{N−1} = 1`.
fn centripetal<const D: usize>(points: &[Point<f64, D>]) -> Vec<f64> {
    let steps: Vec<f64> = points
        .windows(2)
        .map(|w| (w[1] - w[0]).norm().sqrt())
        .collect();
    let total: f64 = steps.iter().sum();
    let mut params = vec![0.0];
    let mut sum = 0.0;
    for s in &steps {
        sum += s;
        params.push(sum / total);
    }
    *params.last_mut().unwrap() = 1.0;
    params
}

/// Knots by averaging (Piegl & Tiller eq. 9.8), for parameters on any
/// range: `p + 1` copies of each end, the means of `p` consecutive
/// interior parameters between.
fn averaged_knots(p: usize, params: &[f64]) -> Vec<f64> {
    let n = params.len();
    let mut knots = vec![params[0]; p + 1];
    for j in 1..n - p {
        knots.push(params[j..j + p].iter().sum::<f64>() / p as f64);
    }
    knots.extend(vec![params[n - 1]; p + 1]);
    knots
}

/// The largest miss relative to the data's size.
fn check_passes_through<const D: usize>(
    rng: &mut Rng,
    degrees: std::ops::RangeInclusive<usize>,
) -> f64 {
    let mut worst = 0.0_f64;
    for p in degrees {
        for extra in [0, 1, 2, 5, 13, 30] {
            let points = random_points::<D>(rng, p + 1 + extra);
            let curve = BSpline::interpolate(p, &points).unwrap();
            let params = centripetal(&points);
            assert_eq!(curve.domain(), (0.0, 1.0));
            assert_eq!(curve.degree(), p);
            assert_eq!(curve.points().len(), points.len());
            let knots = averaged_knots(p, &params);
            assert_eq!(curve.knots().len(), knots.len());
            for (a, b) in curve.knots().iter().zip(&knots) {
                assert!(
                    (a - b).abs() <= 1e-15,
                    "p {p}: {:?} vs {knots:?}",
                    curve.knots()
                );
            }
            let tol = 1e-12 * size(&points);
            for (k, (q, &u)) in points.iter().zip(&params).enumerate() {
                let miss = (curve.eval(u) - q).norm();
                assert!(
                    miss <= tol,
                    "p {p}, n {}: point {k} missed by {miss:e}",
                    points.len()
                );
                worst = worst.max(miss / size(&points));
            }
            assert_eq!(curve.points()[0], points[0]);
            assert_eq!(curve.points().last(), points.last());
        }
    }
    worst
}

#[test]
fn interpolation_passes_through_every_point_at_its_centripetal_parameter() {
    let mut rng = Rng(0x1234_5678);
    let worst = check_passes_through::<1>(&mut rng, 1..=5)
        .max(check_passes_through::<2>(&mut rng, 1..=7))
        .max(check_passes_through::<3>(&mut rng, 1..=7));
    println!("interpolation misses its points by at most {worst:e} of their size");
}

#[test]
fn long_random_walks_are_interpolated() {
    // 5000 points: the banded solve at scale, every degree up to 7.
    let mut rng = Rng(2024);
    let mut walk = vec![Point3::origin()];
    for _ in 1..5000 {
        let last = *walk.last().unwrap();
        walk.push(
            last + Vector3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(0.1, 1.0),
            ),
        );
    }
    let params = centripetal(&walk);
    for p in [1, 3, 7] {
        let curve = BSpline::interpolate(p, &walk).unwrap();
        let tol = 1e-12 * size(&walk);
        for (q, &u) in walk.iter().zip(&params) {
            assert!((curve.eval(u) - q).norm() <= tol, "p {p}");
        }
        let fit = BSpline::fit(p, &walk, 700).unwrap();
        assert_eq!(fit.points().len(), 700);
    }
}

#[test]
fn degree_one_interpolation_is_the_polyline() {
    let points = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(1.0, 4.0),
        Point2::new(-2.0, 0.0),
    ];
    let curve = BSpline::interpolate(1, &points).unwrap();
    let params = centripetal(&points);
    assert_eq!(curve.points(), &points);
    for (k, w) in points.windows(2).enumerate() {
        for s in [0.25, 0.5, 0.75] {
            let u = params[k] + s * (params[k + 1] - params[k]);
            let expect = w[0] + (w[1] - w[0]) * s;
            assert!((curve.eval(u) - expect).norm() < 1e-14);
        }
    }
}

#[test]
fn p_plus_one_points_give_one_bezier_piece() {
    let mut rng = Rng(77);
    for p in 1..=9 {
        let points: Vec<Point3<f64>> = random_points(&mut rng, p + 1);
        let curve = BSpline::interpolate(p, &points).unwrap();
        let mut knots = vec![0.0; p + 1];
        knots.extend(vec![1.0; p + 1]);
        assert_eq!(curve.knots(), &knots[..]);
        assert_eq!(curve.to_bezier_spans().len(), 1);
        for (q, u) in points.iter().zip(centripetal(&points)) {
            assert!((curve.eval(u) - q).norm() < 1e-12, "p {p}");
        }
    }
}

#[test]
fn equally_spaced_collinear_points_give_the_line_at_uniform_speed() {
    let a = Point3::new(1.0, -2.0, 0.5);
    let h = Vector3::new(0.3, 0.1, -0.7);
    for p in 1..=6 {
        for n in [p + 1, p + 2, 10, 25] {
            let points: Vec<Point3<f64>> = (0..n).map(|k| a + h * k as f64).collect();
            let chord = h * (n - 1) as f64;
            let curve = BSpline::interpolate(p, &points).unwrap();
            let fit = BSpline::fit(p, &points, (p + 1).max(n / 2)).unwrap();
            for c in [&curve, &fit] {
                for s in c.discretize(100) {
                    let expect = a + chord * s.t;
                    // The data themselves are rounded to ε of their size.
                    let (miss, slip) = ((s.point - expect).norm(), (s.derivative - chord).norm());
                    assert!(
                        miss < 1e-14 * chord.norm(),
                        "p {p} n {n} t {}: {miss:e}",
                        s.t
                    );
                    assert!(
                        slip < 1e-12 * chord.norm(),
                        "p {p} n {n} t {}: {slip:e}",
                        s.t
                    );
                }
            }
        }
    }
}

#[test]
fn unequally_spaced_collinear_points_stay_on_their_line() {
    let a = Point2::new(-1.0, 2.0);
    let dir = Point2::new(3.0, 1.0).coords.normalize();
    let normal = SVector::<f64, 2>::new(-dir.y, dir.x);
    let along = [0.0, 0.1, 0.5, 0.6, 2.0, 2.05, 3.5, 7.0, 7.2];
    let points: Vec<Point2<f64>> = along.iter().map(|&s| a + dir * s).collect();
    for p in 1..=5 {
        let curve = BSpline::interpolate(p, &points).unwrap();
        let fit = BSpline::fit(p, &points, p + 2).unwrap();
        for c in [&curve, &fit] {
            for s in c.discretize(400) {
                let off = (s.point - a).dot(&normal).abs();
                assert!(off < 1e-13, "p {p}: {off:e} off the line");
            }
        }
    }
}

#[test]
fn interpolation_is_invariant_under_similarities() {
    let mut rng = Rng(4242);
    let rotation = Rotation3::from_euler_angles(0.3, -1.1, 2.0);
    let shift = Vector3::new(5.0, -3.0, 0.25);
    let scale = 7.5;
    let map = |q: &Point3<f64>| rotation * (q * scale) + shift;
    for p in 1..=5 {
        let points: Vec<Point3<f64>> = random_points(&mut rng, 12);
        let moved: Vec<Point3<f64>> = points.iter().map(map).collect();
        let a = BSpline::interpolate(p, &points).unwrap();
        let b = BSpline::interpolate(p, &moved).unwrap();
        for (x, y) in a.knots().iter().zip(b.knots()) {
            assert!((x - y).abs() < 1e-14);
        }
        for (x, y) in a.discretize(200).iter().zip(b.discretize(200)) {
            assert!((map(&x.point) - y.point).norm() < 1e-12 * scale, "p {p}");
        }
        let fa = BSpline::fit(p, &points, p + 3).unwrap();
        let fb = BSpline::fit(p, &moved, p + 3).unwrap();
        for (x, y) in fa.discretize(200).iter().zip(fb.discretize(200)) {
            assert!((map(&x.point) - y.point).norm() < 1e-12 * scale, "p {p}");
        }
    }
}

/// `n` points on the unit circle over three quarters of a turn, equally
/// spaced in angle.
/// Random increasing parameters from `start`, steps in `[0.2, 2]`.
fn random_parameters(rng: &mut Rng, count: usize, start: f64) -> Vec<f64> {
    let mut t = start;
    (0..count)
        .map(|k| {
            if k > 0 {
                t += rng.range(0.2, 2.0);
            }
            t
        })
        .collect()
}

/// Samples a random spline of degree `p` whose knots are those by
/// averaging of `params`, at `params`, and interpolates the samples at
/// them: the spline comes back (the interpolant is unique in its space).
/// Returns the largest control-point difference over the spline's size.
fn reproduction_error(rng: &mut Rng, p: usize, params: &[f64]) -> f64 {
    let spline = BSpline::new(
        p,
        averaged_knots(p, params),
        random_points::<3>(rng, params.len()),
    )
    .unwrap();
    let samples: Vec<Point3<f64>> = params.iter().map(|&t| spline.eval(t)).collect();
    let again = BSpline::interpolate_with_parameters(p, &samples, params).unwrap();
    assert_eq!(again.domain(), (params[0], params[params.len() - 1]));
    for (a, b) in again.knots().iter().zip(spline.knots()) {
        assert!((a - b).abs() <= 1e-14 * (1.0 + b.abs()), "{a} vs {b}");
    }
    again
        .points()
        .iter()
        .zip(spline.points())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
        / size(spline.points())
}

#[test]
fn interpolation_at_a_splines_parameters_reproduces_the_spline() {
    let mut rng = Rng(0x5eed_2901);
    let mut worst = 0.0_f64;
    for p in 1..=7 {
        for case in 0..40 {
            let count = p + 1 + case % 17;
            let start = rng.range(-50.0, 50.0);
            let params = random_parameters(&mut rng, count, start);
            let error = reproduction_error(&mut rng, p, &params);
            assert!(error < 1e-11, "degree {p}, case {case}: {error:e}");
            worst = worst.max(error);
        }
    }
    eprintln!("largest control-point difference over size: {worst:e}");
}

#[test]
fn interpolation_at_given_parameters_refuses_bad_ones() {
    let pts: Vec<Point2<f64>> = (0..5)
        .map(|i| Point2::new(i as f64, (i * i) as f64))
        .collect();
    let interp = |params: &[f64]| BSpline::interpolate_with_parameters(2, &pts, params);
    assert_eq!(
        interp(&[0.0, 1.0, 2.0]),
        Err(Error::ParameterCount {
            expected: 5,
            found: 3
        })
    );
    let invalid = |params: &[f64], index: usize| match interp(params) {
        Err(Error::InvalidParameter { index: i, value }) => {
            assert_eq!(i, index, "{params:?}");
            assert_eq!(value.to_bits(), params[index].to_bits(), "{params:?}");
        }
        other => panic!("{params:?}: {other:?}"),
    };
    invalid(&[0.0, 1.0, f64::NAN, 3.0, 4.0], 2);
    invalid(&[0.0, 1.0, 2.0, 3.0, f64::INFINITY], 4);
    invalid(&[0.0, 1.0, 2.0, 3.0, 2.0 * MAX_COORDINATE], 4);
    invalid(&[0.0, 1.0, 1.0, 3.0, 4.0], 2);
    invalid(&[0.0, 2.0, 1.0, 3.0, 4.0], 2);
    invalid(&[0.0, 1.0, 1.0 + 1e-15, 3.0, 4.0], 2);
    // The data are checked first, then the parameters.
    assert_eq!(
        BSpline::interpolate_with_parameters(0, &pts, &[0.0; 5]),
        Err(Error::ZeroDegree)
    );
    let text = Error::InvalidParameter {
        index: 2,
        value: 1.0,
    }
    .to_string();
    assert!(
        text.contains("parameter 2") && text.contains("increasing"),
        "{text}"
    );
}

fn arc_points(n: usize) -> Vec<Point2<f64>> {
    (0..n)
        .map(|k| {
            let a = 1.5 * std::f64::consts::PI * k as f64 / (n - 1) as f64;
            Point2::new(a.cos(), a.sin())
        })
        .collect()
}

/// The largest `| |C(t)| − 1 |` over dense samples.
fn radial_error(curve: &BSpline<2>) -> f64 {
    curve
        .discretize(4000)
        .iter()
        .map(|s| (s.point.coords.norm() - 1.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn interpolation_of_circle_points_converges_to_the_circle() {
    let mut previous = f64::INFINITY;
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64, 128] {
        let error = radial_error(&BSpline::interpolate(3, &arc_points(n)).unwrap());
        errors.push((n, error));
        // A cubic spline converges as h⁴: each doubling divides the error by
        // about 16; ask for 8.
        assert!(error < previous / 8.0, "{errors:?}");
        previous = error;
    }
    assert!(previous < 1e-7, "{errors:?}");
    println!("cubic interpolation of a 270° arc, radial error by point count: {errors:?}");
}

#[test]
fn fit_of_circle_points_improves_with_more_control_points() {
    let points = arc_points(400);
    let mut previous = f64::INFINITY;
    let mut errors = Vec::new();
    for c in [5, 9, 17, 33, 65] {
        let curve = BSpline::fit(3, &points, c).unwrap();
        assert_eq!(curve.points().len(), c);
        assert_eq!(curve.eval(0.0), points[0]);
        assert_eq!(curve.eval(1.0), points[399]);
        let error = radial_error(&curve);
        errors.push((c, error));
        assert!(error < previous / 4.0, "{errors:?}");
        previous = error;
    }
    assert!(previous < 1e-7, "{errors:?}");
    println!(
        "cubic least-squares fit of 400 points on a 270° arc, radial error by control points: {errors:?}"
    );
}

/// The optimality conditions of the least-squares fit: the residual at the
/// data is orthogonal to every free basis function.
fn check_fit_is_least_squares<const D: usize>(points: &[Point<f64, D>], p: usize, c: usize) {
    let curve = BSpline::fit(p, points, c).unwrap();
    assert_eq!(curve.points().len(), c);
    assert_eq!(curve.points()[0], points[0]);
    assert_eq!(curve.points()[c - 1], points[points.len() - 1]);
    let params = centripetal(points);
    // Evaluation rounds to ε of the control points' size, which a fit with
    // short end spans can make larger than the data's.
    let magnitude = size(points).max(size(curve.points()));
    let mut normal = vec![SVector::<f64, D>::zeros(); c];
    let mut scale = vec![0.0_f64; c];
    let mut basis = vec![0.0; p + 1];
    for (k, (q, &u)) in points.iter().zip(&params).enumerate() {
        if k == 0 || k == points.len() - 1 {
            continue;
        }
        let first = curve.basis_functions(u, &mut basis).unwrap();
        let residual = q - curve.eval(u);
        for (r, &b) in basis.iter().enumerate() {
            normal[first + r] += residual * b;
            scale[first + r] += b * magnitude;
        }
    }
    for i in 1..c - 1 {
        let bad = normal[i].amax();
        assert!(
            bad <= 1e-12 * scale[i].max(1e-300),
            "p {p}, {c} control points: condition {i} is {bad:e} (size {magnitude:e})"
        );
    }
}

#[test]
fn fit_satisfies_the_least_squares_conditions() {
    let mut rng = Rng(99);
    for p in 1..=5 {
        for (m, c) in [(p + 2, p + 1), (20, p + 1), (20, p + 4), (50, 30), (50, 49)] {
            if c > m {
                continue;
            }
            let points: Vec<Point3<f64>> = random_points(&mut rng, m);
            check_fit_is_least_squares(&points, p, c);
            let points: Vec<Point2<f64>> = random_points(&mut rng, m);
            check_fit_is_least_squares(&points, p, c);
        }
    }
}

#[test]
fn fit_with_as_many_control_points_as_points_is_interpolation() {
    let mut rng = Rng(5);
    for p in 1..=4 {
        let points: Vec<Point2<f64>> = random_points(&mut rng, 11);
        let fit = BSpline::fit(p, &points, 11).unwrap();
        assert_eq!(fit, BSpline::interpolate(p, &points).unwrap());
    }
}

#[test]
fn fit_end_points_are_exact() {
    let mut rng = Rng(31);
    for p in 1..=5 {
        let points: Vec<Point3<f64>> = random_points(&mut rng, 40);
        for c in [p + 1, p + 2, 20, 39] {
            let curve = BSpline::fit(p, &points, c).unwrap();
            assert_eq!(curve.eval(0.0), points[0]);
            assert_eq!(curve.eval(1.0), points[39]);
        }
    }
}

#[test]
fn interpolation_errors_name_the_problem() {
    let p2 = |x: f64, y: f64| Point2::new(x, y);
    let good = [p2(0.0, 0.0), p2(1.0, 0.0), p2(2.0, 1.0), p2(3.0, 0.0)];
    assert_eq!(BSpline::interpolate(0, &good), Err(Error::ZeroDegree));
    assert_eq!(
        BSpline::interpolate(4, &good),
        Err(Error::TooFewPoints {
            degree: 4,
            points: 4
        })
    );
    assert_eq!(
        BSpline::<2>::interpolate(1, &[]),
        Err(Error::TooFewPoints {
            degree: 1,
            points: 0
        })
    );
    assert_eq!(
        BSpline::interpolate(usize::MAX, &good),
        Err(Error::TooFewPoints {
            degree: usize::MAX,
            points: 4
        })
    );
    let mut bad = good;
    bad[2] = p2(f64::NAN, 0.0);
    assert_eq!(
        BSpline::interpolate(2, &bad),
        Err(Error::NonFinitePoint { index: 2 })
    );
    bad[2] = p2(0.0, f64::NEG_INFINITY);
    assert_eq!(
        BSpline::interpolate(2, &bad),
        Err(Error::NonFinitePoint { index: 2 })
    );
    bad[2] = p2(2.0 * MAX_COORDINATE, 0.0);
    assert_eq!(
        BSpline::interpolate(2, &bad),
        Err(Error::CoordinateTooLarge {
            index: 2,
            value: 2.0 * MAX_COORDINATE
        })
    );
    let mut twice = good;
    twice[2] = twice[1];
    assert_eq!(
        BSpline::interpolate(2, &twice),
        Err(Error::CoincidentPoints { index: 2 })
    );
    // A chord of 1e-40 beside chords of 1: its parameter step (1e-20 of
    // the whole) cannot be told apart from zero at the knots.
    let close = [p2(0.0, 0.0), p2(1e-40, 0.0), p2(1.0, 0.0), p2(2.0, 1.0)];
    assert_eq!(
        BSpline::interpolate(1, &close),
        Err(Error::CoincidentPoints { index: 1 })
    );
    // A tiny curve is fine: only relative closeness counts.
    let tiny: Vec<Point2<f64>> = good.iter().map(|q| q * 1e-200).collect();
    let curve = BSpline::interpolate(3, &tiny).unwrap();
    assert!((curve.eval(1.0) - tiny[3]).norm() == 0.0);
    // Huge coordinates within the limit are fine too.
    let huge: Vec<Point2<f64>> = good.iter().map(|q| q * 1e99).collect();
    assert!(BSpline::interpolate(3, &huge).is_ok());
}

#[test]
fn fit_errors_name_the_problem() {
    let points: Vec<Point1<f64>> = (0..10).map(|k| Point1::new(k as f64)).collect();
    assert_eq!(BSpline::fit(0, &points, 5), Err(Error::ZeroDegree));
    assert_eq!(
        BSpline::fit(10, &points, 10),
        Err(Error::TooFewPoints {
            degree: 10,
            points: 10
        })
    );
    assert_eq!(
        BSpline::fit(3, &points, 3),
        Err(Error::TooFewControlPoints {
            control_points: 3,
            degree: 3
        })
    );
    assert_eq!(
        BSpline::fit(3, &points, 11),
        Err(Error::TooManyControlPoints {
            control_points: 11,
            points: 10
        })
    );
    let mut bad = points.clone();
    bad[4] = Point1::new(f64::INFINITY);
    assert_eq!(
        BSpline::fit(3, &bad, 5),
        Err(Error::NonFinitePoint { index: 4 })
    );
    bad[4] = Point1::new(-1e101);
    assert_eq!(
        BSpline::fit(3, &bad, 5),
        Err(Error::CoordinateTooLarge {
            index: 4,
            value: -1e101
        })
    );
    let mut twice = points.clone();
    twice[7] = twice[6];
    assert_eq!(
        BSpline::fit(3, &twice, 5),
        Err(Error::CoincidentPoints { index: 7 })
    );
}

#[test]
fn error_messages_name_indices_and_counts() {
    let text = |e: Error| e.to_string();
    assert_eq!(
        text(Error::CoincidentPoints { index: 3 }),
        "data points 2 and 3 coincide (zero chord, or too short beside the others for their \
         parameters to differ): remove one of them"
    );
    assert_eq!(
        text(Error::TooFewPoints {
            degree: 3,
            points: 2
        }),
        "degree 3 needs at least 4 data points, got 2"
    );
    assert!(
        text(Error::TooManyControlPoints {
            control_points: 9,
            points: 4
        })
        .contains("9 control points")
    );
    assert!(
        text(Error::TooFewControlPoints {
            control_points: 2,
            degree: 3
        })
        .contains("at least 4 control points, got 2")
    );
    assert!(text(Error::ZeroDegree).contains("got 0"));
    assert!(text(Error::SingularSystem { column: 5 }).contains("unknown 5"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    /// Interpolation passes through random points (consecutive ones kept
    /// apart) at their centripetal parameters, for degrees 1–6.
    #[test]
    fn interpolation_passes_through_random_points(
        p in 1usize..=6,
        coords in proptest::collection::vec((-100.0f64..100.0, -100.0f64..100.0), 8..40),
    ) {
        let mut points: Vec<Point2<f64>> = Vec::new();
        for (x, y) in coords {
            let q = Point2::new(x, y);
            if points.last().is_none_or(|last: &Point2<f64>| (q - last).norm() > 1e-3) {
                points.push(q);
            }
        }
        prop_assume!(points.len() > p);
        let curve = BSpline::interpolate(p, &points).unwrap();
        let tol = 1e-11 * size(&points);
        for (q, u) in points.iter().zip(centripetal(&points)) {
            prop_assert!((curve.eval(u) - q).norm() <= tol);
        }
    }

    /// Samples of a random spline at parameters whose averages are its
    /// knots give the spline back, for degrees 1–7.
    #[test]
    fn interpolation_reproduces_splines_sampled_at_their_parameters(
        p in 1usize..=7,
        extra in 0usize..20,
        seed in any::<u64>(),
        start in -1e3f64..1e3,
    ) {
        let mut rng = Rng(seed | 1);
        let params = random_parameters(&mut rng, p + 1 + extra, start);
        let error = reproduction_error(&mut rng, p, &params);
        prop_assert!(error < 1e-11, "{error:e}");
    }

    /// The fit keeps its ends and meets the least-squares conditions.
    #[test]
    fn fit_is_least_squares_on_random_points(
        p in 1usize..=5,
        extra in 0usize..20,
        coords in proptest::collection::vec((-10.0f64..10.0, -10.0f64..10.0, -10.0f64..10.0), 30..60),
    ) {
        let mut points: Vec<Point3<f64>> = Vec::new();
        for (x, y, z) in coords {
            let q = Point3::new(x, y, z);
            if points.last().is_none_or(|last: &Point3<f64>| (q - last).norm() > 1e-3) {
                points.push(q);
            }
        }
        let c = (p + 1 + extra).min(points.len());
        prop_assume!(points.len() > p);
        check_fit_is_least_squares(&points, p, c);
    }
}

/// A coordinate that is now and then hostile: NaN, infinite, beyond the
/// limit, at the limit, tiny, zero.
fn wild_coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => -10.0f64..10.0,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(2.0 * MAX_COORDINATE),
        1 => Just(-MAX_COORDINATE),
        1 => Just(1e-300),
        1 => Just(0.0),
    ]
}

/// Points with wild coordinates, a tenth of them repeating their
/// predecessor.
fn wild_points() -> impl Strategy<Value = Vec<Point2<f64>>> {
    proptest::collection::vec((wild_coordinate(), wild_coordinate(), 0u8..10), 0..30).prop_map(
        |raw| {
            let mut points: Vec<Point2<f64>> = Vec::new();
            for (x, y, repeat) in raw {
                match points.last() {
                    Some(&last) if repeat == 0 => points.push(last),
                    _ => points.push(Point2::new(x, y)),
                }
            }
            points
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any input gives a curve whose points are finite, or an error; never
    /// a panic.
    #[test]
    fn hostile_input_is_an_error_or_a_finite_curve(
        p in 0usize..8,
        c in 0usize..32,
        points in wild_points(),
    ) {
        let results = [BSpline::interpolate(p, &points), BSpline::fit(p, &points, c)];
        for curve in results.iter().flatten() {
            prop_assert_eq!(curve.domain(), (0.0, 1.0));
            for s in curve.discretize(50) {
                prop_assert!(s.point.coords.iter().all(|x| x.is_finite()));
                prop_assert!(s.derivative.iter().all(|x| x.is_finite()));
            }
        }
    }
}

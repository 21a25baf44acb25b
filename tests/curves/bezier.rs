//! Closed-form tests of `Bezier`: curves whose coordinates are known
//! polynomials, so every value and derivative has an exact reference.
//!
//! The monomial `tᵏ` written in the degree-`n` Bernstein basis has the
//! coefficients `C(i, k) / C(n, k)`, `i = 0 … n` (degree elevation), so a
//! Bézier with those coordinates is exactly `tᵏ` whatever `n ≥ k` is.

use revolve_testkit as common;

use common::assert_close;
use revolve::nalgebra::{Point1, Point2, Point3, Vector2, Vector3};
use revolve::{Bezier, Curve};

/// `C(n, k)` as an `f64` (exact for the small arguments used here).
fn choose(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

/// Bernstein coefficients of `tᵏ` in degree `n`.
fn monomial(n: usize, k: usize) -> Vec<f64> {
    (0..=n).map(|i| choose(i, k) / choose(n, k)).collect()
}

/// `dʲ/dtʲ tᵏ = k!/(k − j)! · tᵏ⁻ʲ` (zero for `j > k`).
fn monomial_derivative(k: usize, j: usize, t: f64) -> f64 {
    if j > k {
        return 0.0;
    }
    let falling: f64 = ((k - j + 1)..=k).map(|x| x as f64).product();
    falling * t.powi((k - j) as i32)
}

/// The planar curve `(tᵃ, tᵇ)` as a Bézier of degree `n`.
fn monomial_curve_2d(n: usize, a: usize, b: usize) -> Bezier<2> {
    let xs = monomial(n, a);
    let ys = monomial(n, b);
    Bezier::new(
        xs.iter()
            .zip(&ys)
            .map(|(&x, &y)| Point2::new(x, y))
            .collect(),
    )
    .unwrap()
}

/// Parameters in `[0, 1]` including both ends and points close to them.
fn params() -> Vec<f64> {
    let mut ts: Vec<f64> = (0..=64).map(|i| i as f64 / 64.0).collect();
    ts.extend([
        1e-12,
        1e-6,
        0.1,
        0.3,
        1.0 / 3.0,
        0.7,
        1.0 - 1e-6,
        1.0 - 1e-12,
    ]);
    ts
}

fn sample_curve() -> Bezier<2> {
    Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 3.0),
        Point2::new(2.5, -1.0),
        Point2::new(4.0, 2.0),
        Point2::new(5.0, 0.5),
    ])
    .unwrap()
}

#[test]
fn degree_elevated_identity_is_x_equals_t() {
    for n in 1..=8 {
        let c = monomial_curve_2d(n, 1, 1);
        for t in params() {
            let p = c.eval(t);
            assert_close(p.x, t, 4.0 * f64::EPSILON, &format!("n={n} t={t}"));
        }
    }
}

#[test]
fn parabola_x_t_y_t_squared_values_and_derivatives() {
    for n in 2..=8 {
        let c = monomial_curve_2d(n, 1, 2);
        for t in params() {
            let p = c.eval(t);
            assert_close(p.x, t, 4.0 * f64::EPSILON, "x");
            assert_close(p.y, t * t, 4.0 * f64::EPSILON, "y");
            let d = c.derivative(t);
            assert_close(d.x, 1.0, 1e-14, "x'");
            assert_close(d.y, 2.0 * t, 1e-14, "y'");
            let d2 = c.nth_derivative(t, 2).unwrap();
            assert_close(d2.x, 0.0, 1e-13, "x''");
            assert_close(d2.y, 2.0, 1e-13, "y''");
        }
    }
}

#[test]
fn cubic_y_t_cubed_values_and_derivatives_of_every_order() {
    for n in 3..=9 {
        let c = monomial_curve_2d(n, 1, 3);
        for t in params() {
            for order in 0..=n + 2 {
                let d = c.nth_derivative(t, order).unwrap();
                // Differencing n times multiplies by up to n!/(n−order)!; the
                // tolerance scales with that growth of rounding.
                let growth: f64 = ((n + 1 - order.min(n))..=n).map(|x| x as f64).product();
                let tol = 8.0 * f64::EPSILON * growth * 2f64.powi(order.min(n) as i32);
                assert_close(
                    d.x,
                    monomial_derivative(1, order, t),
                    tol,
                    &format!("x^({order}) n={n} t={t}"),
                );
                assert_close(
                    d.y,
                    monomial_derivative(3, order, t),
                    tol,
                    &format!("y^({order}) n={n} t={t}"),
                );
            }
        }
    }
}

#[test]
fn twisted_cubic_in_3d_is_exact_at_dyadic_parameters() {
    // (t, t², t³) as a cubic Bézier: control points (i/3, C(i,2)/3, C(i,3)).
    let c = Bezier::new(vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0 / 3.0, 0.0, 0.0),
        Point3::new(2.0 / 3.0, 1.0 / 3.0, 0.0),
        Point3::new(1.0, 1.0, 1.0),
    ])
    .unwrap();
    for t in params() {
        let p = c.eval(t);
        assert_close(p.x, t, 4.0 * f64::EPSILON, "x");
        assert_close(p.y, t * t, 4.0 * f64::EPSILON, "y");
        assert_close(p.z, t * t * t, 4.0 * f64::EPSILON, "z");
        let d = c.derivative(t);
        assert_close(d.x, 1.0, 1e-14, "x'");
        assert_close(d.y, 2.0 * t, 1e-14, "y'");
        assert_close(d.z, 3.0 * t * t, 1e-14, "z'");
        let d3 = c.nth_derivative(t, 3).unwrap();
        assert_close(d3.x, 0.0, 1e-13, "x'''");
        assert_close(d3.y, 0.0, 1e-13, "y'''");
        assert_close(d3.z, 6.0, 1e-13, "z'''");
    }
    // The z coordinate t³ has only exact binary digits at t = 1/2.
    assert_eq!(c.eval(0.5).z, 0.125);
}

#[test]
fn derivatives_above_the_degree_are_exactly_zero() {
    let c = sample_curve();
    for t in params() {
        for order in [5, 6, 17, 1000, usize::MAX] {
            assert_eq!(
                c.nth_derivative(t, order).unwrap(),
                Vector2::zeros(),
                "order {order}"
            );
        }
    }
    let constant = Bezier::new(vec![Point2::new(3.0, -4.0)]).unwrap();
    assert_eq!(constant.nth_derivative(0.4, 1).unwrap(), Vector2::zeros());
    assert_eq!(constant.derivative(0.4), Vector2::zeros());
}

#[test]
fn zeroth_derivative_is_the_point() {
    let c = sample_curve();
    for t in params() {
        assert_eq!(c.nth_derivative(t, 0).unwrap(), c.eval(t).coords);
    }
}

#[test]
fn end_points_are_interpolated_exactly() {
    let c = sample_curve();
    let pts = c.points();
    assert_eq!(c.eval(0.0), pts[0]);
    assert_eq!(c.eval(1.0), pts[4]);
    assert_eq!(c.eval_with_derivative(0.0).0, pts[0]);
    assert_eq!(c.eval_with_derivative(1.0).0, pts[4]);
}

#[test]
fn end_tangents_are_n_times_first_and_last_legs() {
    let c = sample_curve();
    let pts = c.points();
    let n = 4.0;
    assert_eq!(c.derivative(0.0), (pts[1] - pts[0]) * n);
    assert_eq!(c.derivative(1.0), (pts[4] - pts[3]) * n);
    assert_eq!(c.nth_derivative(0.0, 1).unwrap(), (pts[1] - pts[0]) * n);
    assert_eq!(c.nth_derivative(1.0, 1).unwrap(), (pts[4] - pts[3]) * n);
}

#[test]
fn end_second_derivative_is_n_n_minus_1_times_second_difference() {
    let c = sample_curve();
    let p = c.points();
    let want0 = (p[2].coords - p[1].coords * 2.0 + p[0].coords) * 12.0;
    let want1 = (p[4].coords - p[3].coords * 2.0 + p[2].coords) * 12.0;
    assert!((c.nth_derivative(0.0, 2).unwrap() - want0).norm() < 1e-13);
    assert!((c.nth_derivative(1.0, 2).unwrap() - want1).norm() < 1e-13);
}

#[test]
fn eval_with_derivative_agrees_with_eval_and_derivative() {
    let c = sample_curve();
    for t in params() {
        let (p, d) = c.eval_with_derivative(t);
        assert!((p - c.eval(t)).norm() < 1e-14, "t={t}");
        assert!(
            (d - c.nth_derivative(t, 1).unwrap()).norm() < 1e-13,
            "t={t}"
        );
        assert_eq!(d, c.derivative(t));
    }
}

#[test]
fn degree_is_point_count_minus_one_and_domain_is_unit_interval() {
    for count in 1..=7 {
        let c = Bezier::new(vec![Point1::new(1.0); count]).unwrap();
        assert_eq!(c.degree(), count - 1);
        assert_eq!(c.domain(), (0.0, 1.0));
    }
}

#[test]
fn constant_curve_is_constant_with_zero_derivative() {
    let c = Bezier::new(vec![Point3::new(1.5, -2.0, 7.0)]).unwrap();
    for t in params() {
        assert_eq!(c.eval(t), Point3::new(1.5, -2.0, 7.0));
        assert_eq!(c.derivative(t), Vector3::zeros());
    }
}

#[test]
fn bounds_are_the_control_point_box_and_contain_the_curve() {
    let c = sample_curve();
    let (lo, hi) = c.bounds();
    assert_eq!(lo, Point2::new(0.0, -1.0));
    assert_eq!(hi, Point2::new(5.0, 3.0));
    for i in 0..=1000 {
        let p = c.eval(i as f64 / 1000.0);
        assert!(
            lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y,
            "{p}"
        );
    }
}

#[test]
fn subdivision_at_zero_gives_a_point_and_the_whole_curve() {
    let c = sample_curve();
    let (left, right) = c.subdivide(0.0).unwrap();
    assert_eq!(left.degree(), 4);
    assert!(left.points().iter().all(|&p| p == c.points()[0]));
    assert_eq!(right, c);
}

#[test]
fn subdivision_at_one_gives_the_whole_curve_and_a_point() {
    let c = sample_curve();
    let (left, right) = c.subdivide(1.0).unwrap();
    assert_eq!(left, c);
    assert_eq!(right.degree(), 4);
    assert!(right.points().iter().all(|&p| p == c.points()[4]));
}

#[test]
fn subdivision_pieces_reparametrize_the_curve() {
    let c = sample_curve();
    for split in [0.25, 0.5, 0.8] {
        let (left, right) = c.subdivide(split).unwrap();
        assert_eq!(left.points()[4], right.points()[0]);
        assert!((left.points()[4] - c.eval(split)).norm() < 1e-14);
        for s in params() {
            let l = left.eval(s) - c.eval(split * s);
            let r = right.eval(s) - c.eval(split + (1.0 - split) * s);
            assert!(l.norm() < 1e-14 && r.norm() < 1e-14, "split {split} s {s}");
        }
    }
}

#[test]
fn subdivision_of_parabola_at_half_has_known_control_points() {
    // y = t² on [0, 1/2], reparametrized: (s/2)² = s²/4 → coefficients 0, 0, 1/4.
    let c = monomial_curve_2d(2, 1, 2);
    let (left, right) = c.subdivide(0.5).unwrap();
    let want_left = [(0.0, 0.0), (0.25, 0.0), (0.5, 0.25)];
    // On [1/2, 1]: y = (1/2 + s/2)² → coefficients 1/4, 1/2, 1.
    let want_right = [(0.5, 0.25), (0.75, 0.5), (1.0, 1.0)];
    for (p, (x, y)) in left.points().iter().zip(want_left) {
        assert_eq!(*p, Point2::new(x, y));
    }
    for (p, (x, y)) in right.points().iter().zip(want_right) {
        assert_eq!(*p, Point2::new(x, y));
    }
}

#[test]
fn hodograph_has_control_points_n_times_the_legs() {
    let c = sample_curve();
    let h = c.hodograph();
    assert_eq!(h.degree(), 3);
    for (i, q) in h.points().iter().enumerate() {
        assert_eq!(q.coords, (c.points()[i + 1] - c.points()[i]) * 4.0);
    }
}

#[test]
fn hodograph_evaluates_the_derivative() {
    let c = sample_curve();
    let h = c.hodograph();
    let hh = h.hodograph();
    for t in params() {
        assert!((h.eval(t).coords - c.derivative(t)).norm() < 1e-13, "t={t}");
        assert!((hh.eval(t).coords - c.nth_derivative(t, 2).unwrap()).norm() < 1e-12);
    }
}

#[test]
fn hodograph_of_parabola_is_the_line_one_two_t() {
    let h = monomial_curve_2d(2, 1, 2).hodograph();
    // d/dt (t, t²) = (1, 2t): control points (1, 0), (1, 2).
    assert_eq!(h.points(), &[Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)]);
}

#[test]
fn hodograph_of_a_constant_is_the_zero_constant() {
    let c = Bezier::new(vec![Point2::new(4.0, 5.0)]).unwrap();
    let h = c.hodograph();
    assert_eq!(h.degree(), 0);
    assert_eq!(h.points(), &[Point2::origin()]);
}

#[test]
fn parameters_outside_the_unit_interval_evaluate_at_the_nearest_end() {
    let c = sample_curve();
    assert_eq!(c.eval(-3.0), c.eval(0.0));
    assert_eq!(c.eval(7.0), c.eval(1.0));
    assert_eq!(c.derivative(-3.0), c.derivative(0.0));
    assert_eq!(c.derivative(7.0), c.derivative(1.0));
    assert_eq!(
        c.nth_derivative(1.5, 2).unwrap(),
        c.nth_derivative(1.0, 2).unwrap()
    );
}

#[test]
fn discretize_samples_uniformly_with_exact_ends() {
    let c = monomial_curve_2d(3, 1, 2);
    let s = c.discretize(10);
    assert_eq!(s.len(), 11);
    assert_eq!(s[0].t, 0.0);
    assert_eq!(s[10].t, 1.0);
    for (i, sample) in s.iter().enumerate() {
        assert_close(sample.t, i as f64 / 10.0, 1e-16, "t");
        assert_close(sample.point.y, sample.t * sample.t, 1e-15, "y");
        assert_close(sample.derivative.y, 2.0 * sample.t, 1e-14, "y'");
    }
    assert_eq!(c.discretize(0).len(), 2);
}

#[test]
fn straight_line_flattens_to_its_two_end_points() {
    let c = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(2.0, 2.0),
        Point2::new(3.0, 3.0),
    ])
    .unwrap();
    let f = c.flatten(1e-6).unwrap();
    assert_eq!(f.samples.len(), 2);
    assert_eq!(f.samples[0].point, Point2::new(0.0, 0.0));
    assert_eq!(f.samples[1].point, Point2::new(3.0, 3.0));
    assert!(f.bound <= 1e-6);
}

#[test]
fn flattened_parabola_stays_within_its_bound() {
    let c = monomial_curve_2d(2, 1, 2);
    for tol in [1e-1, 1e-3, 1e-6] {
        let f = c.flatten(tol).unwrap();
        assert!(f.bound <= tol);
        // Over a piece of width h the parabola (slope ≤ 2) is at least
        // h²/(4√5) from its chord, and the bound cannot be below that, so at
        // least 1/(2·5^¼·√tol) ≈ 0.334/√tol pieces are needed.
        let pieces = (f.samples.len() - 1) as f64;
        assert!(pieces >= 0.33 / tol.sqrt(), "{tol}: {pieces} pieces");
        for w in f.samples.windows(2) {
            let (a, b) = (w[0].point, w[1].point);
            for k in 0..=16 {
                let t = w[0].t + (w[1].t - w[0].t) * k as f64 / 16.0;
                let p = c.eval(t);
                let ab = b - a;
                let s = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
                let dist = (p - (a + ab * s)).norm();
                assert!(dist <= f.bound + 1e-15, "tol {tol} t {t} dist {dist}");
            }
        }
    }
}

/// Flattening a parabola is as economical as its curvature allows: with
/// `|C″| = 8` everywhere, equal parts of width `w` deviate exactly `w²` from
/// their chords, so 32 parts are the fewest that meet `1e-3` (31 would
/// deviate 1.04e-3), and the certified bound is the true deviation.
#[test]
fn flattened_parabola_is_tight() {
    let c = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 2.0),
        Point2::new(2.0, 0.0),
    ])
    .unwrap();
    let f = c.flatten(1e-3).unwrap();
    assert_eq!(f.samples.len(), 33);
    let exact = (1.0_f64 / 32.0).powi(2);
    assert!(f.bound >= exact && f.bound <= 1e-3, "bound {}", f.bound);
    assert!(
        f.bound - exact < 1e-12,
        "bound {} vs deviation {exact}",
        f.bound
    );
}

#[test]
fn bezier_new_keeps_points_in_order() {
    let pts: Vec<_> = (0..5).map(|i| Point2::new(i as f64, -(i as f64))).collect();
    let c = Bezier::new(pts.clone()).unwrap();
    assert_eq!(c.points(), &pts[..]);
}

/// Flattening certifies a true bound up to the largest accepted coordinate
/// (`MAX_COORDINATE = 1e100`); beyond it the constructor refuses the points,
/// so squared chord lengths can never overflow (they did at 1e154 before the
/// limit existed).
#[test]
fn flatten_bound_holds_for_huge_coordinates() {
    assert!(matches!(
        Bezier::new(vec![Point2::new(-1e154, 0.0), Point2::new(1e154, 0.0)]),
        Err(revolve::Error::CoordinateTooLarge { index: 0, .. })
    ));
    let m = revolve::MAX_COORDINATE;
    let c = Bezier::new(vec![
        Point2::new(-m, 0.0),
        Point2::new(0.0, m),
        Point2::new(m, 0.0),
    ])
    .unwrap();
    let f = c.flatten(1e-3 * m).unwrap();
    for w in f.samples.windows(2) {
        let mid = c.eval(0.5 * (w[0].t + w[1].t));
        let (a, b) = (w[0].point / m, w[1].point / m);
        let p = mid / m;
        let ab = b - a;
        let s = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
        let dist = (p - (a + ab * s)).norm() * m;
        assert!(dist <= f.bound, "distance {dist:e} > bound {:e}", f.bound);
    }
}

//! Closed-form tests of `BSpline`: basis values with known fractions, the
//! course framework's knot conventions, the edge rules at knots and at the end
//! of the domain, polynomial reproduction, knot insertion, Bézier spans and
//! derivative splines.

use revolve_testkit as common;

use common::assert_close;
use revolve::bernstein::bernstein;
use revolve::nalgebra::{Point1, Point2, Vector1, Vector2};
use revolve::{BSpline, Bezier, Curve};

fn assert_all_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: lengths");
    for (i, (&g, &w)) in got.iter().zip(want).enumerate() {
        assert_close(g, w, tol, &format!("{what}[{i}] (all: {got:?})"));
    }
}

/// `n` distinct planar control points with no special structure.
fn points(n: usize) -> Vec<Point2<f64>> {
    (0..n)
        .map(|i| {
            let x = i as f64;
            Point2::new(
                x + 0.25 * (x * 1.7).sin(),
                (x * 0.9).cos() * 3.0 + 0.1 * x * x,
            )
        })
        .collect()
}

/// Integer knots 0, 1, …, 10 and seven points: a uniform cubic with unit spacing.
fn integer_uniform_cubic() -> BSpline<2> {
    BSpline::new(3, (0..=10).map(f64::from).collect(), points(7)).unwrap()
}

// ---------------------------------------------------------------- basis ----

#[test]
fn uniform_cubic_basis_at_a_knot_is_one_sixth_two_thirds_one_sixth() {
    let c = integer_uniform_cubic();
    let mut out = [f64::NAN; 4];
    let first = c.basis_functions(5.0, &mut out).unwrap();
    // t = 5 lies in the span [t5, t6), whose basis functions are N2 … N5.
    assert_eq!(first, 2);
    assert_all_close(&out, &[1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0], 1e-15, "N");
}

#[test]
fn uniform_cubic_basis_derivatives_at_a_knot_are_half_and_one_minus_two_one() {
    let c = integer_uniform_cubic();
    let mut d = [f64::NAN; 20];
    let first = c.basis_derivatives(5.0, 4, &mut d).unwrap();
    assert_eq!(first, 2);
    assert_all_close(
        &d[0..4],
        &[1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0],
        1e-15,
        "N",
    );
    assert_all_close(&d[4..8], &[-0.5, 0.0, 0.5, 0.0], 1e-15, "N'");
    assert_all_close(&d[8..12], &[1.0, -2.0, 1.0, 0.0], 1e-14, "N''");
    // The third derivative is constant on the span [5, 6): −1, 3, −3, 1.
    assert_all_close(&d[12..16], &[-1.0, 3.0, -3.0, 1.0], 1e-14, "N'''");
    assert_eq!(&d[16..20], &[0.0; 4], "fourth derivative of a cubic");
}

#[test]
fn uniform_cubic_basis_at_span_midpoint_is_1_23_23_1_over_48() {
    let c = integer_uniform_cubic();
    let mut out = [0.0; 4];
    let first = c.basis_functions(5.5, &mut out).unwrap();
    assert_eq!(first, 2);
    let want = [1.0 / 48.0, 23.0 / 48.0, 23.0 / 48.0, 1.0 / 48.0];
    assert_all_close(&out, &want, 1e-15, "N");
    let mut d = [0.0; 12];
    c.basis_derivatives(5.5, 2, &mut d).unwrap();
    assert_all_close(&d[4..8], &[-0.125, -0.625, 0.625, 0.125], 1e-15, "N'");
    assert_all_close(&d[8..12], &[0.5, -0.5, -0.5, 0.5], 1e-14, "N''");
}

#[test]
fn framework_uniform_cubic_basis_derivatives_scale_with_knot_spacing() {
    // Knots i/10: derivatives pick up a factor 10 per order.
    let c = BSpline::uniform(3, points(7)).unwrap();
    let mut d = [0.0; 12];
    let first = c.basis_derivatives(0.5, 2, &mut d).unwrap();
    assert_eq!(first, 2);
    assert_all_close(
        &d[0..4],
        &[1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0, 0.0],
        1e-15,
        "N",
    );
    assert_all_close(&d[4..8], &[-5.0, 0.0, 5.0, 0.0], 1e-13, "N'");
    assert_all_close(&d[8..12], &[100.0, -200.0, 100.0, 0.0], 1e-11, "N''");
}

#[test]
fn basis_functions_fill_only_degree_plus_one_entries() {
    let c = integer_uniform_cubic();
    let mut out = [7.0; 6];
    c.basis_functions(5.5, &mut out).unwrap();
    assert_eq!(&out[4..], &[7.0, 7.0]);
}

#[test]
fn clamped_single_span_basis_is_the_bernstein_basis() {
    for p in 0..=6 {
        let c = BSpline::clamped(p, points(p + 1)).unwrap();
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let mut d = vec![0.0; 2 * (p + 1)];
            assert_eq!(c.basis_derivatives(t, 1, &mut d).unwrap(), 0);
            for i in 0..=p {
                assert_close(
                    d[i],
                    bernstein(p, i, t),
                    1e-14,
                    &format!("p={p} i={i} t={t}"),
                );
                // d/dt Bᵢᵖ = p (B_{i−1}^{p−1} − Bᵢ^{p−1}).
                let want = if p == 0 {
                    0.0
                } else {
                    let lower = |j: usize| if j < p { bernstein(p - 1, j, t) } else { 0.0 };
                    let prev = if i > 0 { lower(i - 1) } else { 0.0 };
                    p as f64 * (prev - lower(i))
                };
                assert_close(d[p + 1 + i], want, 1e-13, &format!("p={p} i={i} t={t} '"));
            }
        }
    }
}

#[test]
fn basis_is_a_partition_of_unity_and_derivatives_sum_to_zero() {
    let knots = vec![0.0, 0.0, 0.0, 0.3, 0.3, 0.45, 1.0, 1.7, 2.0, 2.0, 2.0];
    let c = BSpline::new(2, knots, points(8)).unwrap();
    for k in 0..=200 {
        let t = 2.0 * k as f64 / 200.0;
        let mut d = [0.0; 9];
        c.basis_derivatives(t, 2, &mut d).unwrap();
        let sums: Vec<f64> = d.chunks(3).map(|r| r.iter().sum()).collect();
        assert_close(sums[0], 1.0, 1e-15, "sum N");
        assert_close(sums[1], 0.0, 1e-12, "sum N'");
        assert_close(sums[2], 0.0, 1e-10, "sum N''");
        assert!(d[..3].iter().all(|&v| v >= 0.0), "N >= 0 at {t}: {d:?}");
    }
}

#[test]
fn basis_functions_combine_to_the_curve_point() {
    let c = BSpline::new(
        3,
        vec![0.0, 0.0, 0.5, 1.0, 1.0, 2.5, 3.0, 3.5, 4.0, 4.0, 4.0],
        points(7),
    )
    .unwrap();
    let (a, b) = c.domain();
    for k in 0..=100 {
        let t = a + (b - a) * k as f64 / 100.0;
        let mut d = [0.0; 8];
        let first = c.basis_derivatives(t, 1, &mut d).unwrap();
        let (mut p, mut dp) = (Vector2::zeros(), Vector2::zeros());
        for r in 0..4 {
            p += c.points()[first + r].coords * d[r];
            dp += c.points()[first + r].coords * d[4 + r];
        }
        assert!((p - c.eval(t).coords).norm() < 1e-13, "t={t}");
        assert!((dp - c.derivative(t)).norm() < 1e-12, "t={t}");
    }
}

// ---------------------------------------------------- knot conventions ----

#[test]
fn framework_uniform_knots_are_i_over_n_plus_3_with_domain_t3_to_tn() {
    for n in 4..=15 {
        let c = BSpline::uniform(3, points(n)).unwrap();
        let m = (n + 3) as f64;
        let want: Vec<f64> = (0..=n + 3).map(|i| i as f64 / m).collect();
        assert_eq!(c.knots(), &want[..], "n={n}");
        assert_eq!(c.domain(), (3.0 / m, n as f64 / m), "n={n}");
        assert_eq!(c.degree(), 3);
        assert_eq!(c.points().len(), n);
    }
}

#[test]
fn framework_uniform_of_degree_k_has_domain_k_to_n_over_n_plus_k() {
    for k in 0..=6 {
        for n in k + 1..=k + 6 {
            let c = BSpline::uniform(k, points(n)).unwrap();
            let m = (n + k) as f64;
            assert_eq!(c.knots().len(), n + k + 1);
            assert_eq!(c.domain(), (k as f64 / m, n as f64 / m), "k={k} n={n}");
        }
    }
}

#[test]
fn clamped_knots_are_open_uniform_on_the_unit_interval() {
    let c = BSpline::clamped(2, points(5)).unwrap();
    assert_eq!(
        c.knots(),
        &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
    );
    assert_eq!(c.domain(), (0.0, 1.0));
    let line = BSpline::clamped(1, points(2)).unwrap();
    assert_eq!(line.knots(), &[0.0, 0.0, 1.0, 1.0]);
    let steps = BSpline::clamped(0, points(4)).unwrap();
    assert_eq!(steps.knots(), &[0.0, 0.25, 0.5, 0.75, 1.0]);
}

#[test]
fn clamped_interpolates_its_end_points() {
    for p in 0..=6 {
        for n in p + 1..=p + 5 {
            let pts = points(n);
            let c = BSpline::clamped(p, pts.clone()).unwrap();
            assert_eq!(c.domain(), (0.0, 1.0));
            assert_eq!(c.eval(0.0), pts[0], "p={p} n={n}");
            assert_eq!(c.eval(1.0), pts[n - 1], "p={p} n={n}");
        }
    }
}

#[test]
fn clamped_end_tangents_follow_the_end_legs() {
    // C'(0) = p/t_{p+1} (P1 − P0) and C'(1) = p/(1 − t_{n−1}) (P_{n−1} − P_{n−2}).
    let pts = points(6);
    let c = BSpline::clamped(3, pts.clone()).unwrap();
    // Three spans: interior knots 1/3 and 2/3.
    let d0 = (pts[1] - pts[0]) * 9.0;
    let d1 = (pts[5] - pts[4]) * 9.0;
    assert!((c.derivative(0.0) - d0).norm() < 1e-13);
    assert!((c.derivative(1.0) - d1).norm() < 1e-13);
}

#[test]
fn clamped_cubic_on_four_points_is_the_bezier_curve() {
    let pts = points(4);
    let s = BSpline::clamped(3, pts.clone()).unwrap();
    let b = Bezier::new(pts).unwrap();
    for k in 0..=64 {
        let t = k as f64 / 64.0;
        assert!((s.eval(t) - b.eval(t)).norm() < 1e-14, "t={t}");
        assert!((s.derivative(t) - b.derivative(t)).norm() < 1e-13, "t={t}");
        for order in 2..=4 {
            let diff = s.nth_derivative(t, order).unwrap() - b.nth_derivative(t, order).unwrap();
            assert!(diff.norm() < 1e-12, "t={t} order={order}");
        }
    }
}

// ---------------------------------------------- low degrees, edge rules ----

#[test]
fn degree_one_is_the_polyline_through_its_points() {
    let knots = vec![0.0, 0.0, 0.3, 0.5, 1.2, 2.0, 2.0];
    let pts = points(5);
    let c = BSpline::new(1, knots.clone(), pts.clone()).unwrap();
    assert_eq!(c.domain(), (0.0, 2.0));
    // Point i sits at knot t_{i+1}.
    for (i, p) in pts.iter().enumerate() {
        assert!((c.eval(knots[i + 1]) - p).norm() < 1e-15, "P{i}");
    }
    for i in 0..4 {
        let (a, b) = (knots[i + 1], knots[i + 2]);
        let slope = (pts[i + 1] - pts[i]) / (b - a);
        for s in [0.0, 0.25, 0.5, 0.9] {
            let t = a + (b - a) * s;
            let want = pts[i] + (pts[i + 1] - pts[i]) * s;
            assert!((c.eval(t) - want).norm() < 1e-14, "leg {i} s {s}");
            assert!((c.derivative(t) - slope).norm() < 1e-13, "leg {i} s {s}");
            assert_eq!(c.nth_derivative(t, 2).unwrap(), Vector2::zeros());
        }
    }
}

#[test]
fn degree_zero_is_piecewise_constant_and_right_continuous() {
    let knots = vec![0.0, 1.0, 2.5, 3.0, 4.0];
    let pts = points(4);
    let c = BSpline::new(0, knots, pts.clone()).unwrap();
    assert_eq!(c.domain(), (0.0, 4.0));
    let cases = [
        (0.0, 0),
        (0.5, 0),
        (1.0 - 1e-12, 0),
        (1.0, 1), // interior knot: the value from the right
        (2.0, 1),
        (2.5, 2),
        (2.9, 2),
        (3.0, 3),
        (3.7, 3),
    ];
    for (t, i) in cases {
        assert_eq!(c.eval(t), pts[i], "t={t}");
        assert_eq!(c.derivative(t), Vector2::zeros(), "t={t}");
        let (p, d) = c.eval_with_derivative(t);
        assert_eq!((p, d), (pts[i], Vector2::zeros()), "t={t}");
        assert_eq!(c.span(t), i, "t={t}");
    }
}

#[test]
fn degree_zero_at_the_domain_end_takes_the_last_value_not_zero() {
    let pts = points(4);
    let c = BSpline::new(0, vec![0.0, 1.0, 2.5, 3.0, 4.0], pts.clone()).unwrap();
    assert_eq!(c.eval(4.0), pts[3]);
    assert_eq!(c.span(4.0), 3);
    let mut out = [0.0];
    assert_eq!(c.basis_functions(4.0, &mut out).unwrap(), 3);
    assert_eq!(out, [1.0]);
    let framework = BSpline::uniform(0, pts.clone()).unwrap();
    assert_eq!(framework.eval(framework.domain().1), pts[3]);
}

#[test]
fn domain_end_evaluates_the_last_span_for_every_degree() {
    // Every domain end must give the limit from the left: compare with a
    // parameter a hair below it.
    for p in 0..=5 {
        let c = BSpline::uniform(p, points(p + 4)).unwrap();
        let b = c.domain().1;
        let below = c.eval(b - 1e-13);
        assert!((c.eval(b) - below).norm() < 1e-9, "p={p}");
        let mut out = vec![0.0; p + 1];
        c.basis_functions(b, &mut out).unwrap();
        assert_close(out.iter().sum(), 1.0, 1e-14, "partition of unity at end");
    }
}

#[test]
fn domain_end_at_a_repeated_knot_evaluates_the_end_point() {
    // Degree 2, the domain end t_4 = 1 is a double knot followed by 2, 2.
    let pts = points(4);
    let c = BSpline::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0], pts.clone()).unwrap();
    assert_eq!(c.domain(), (0.0, 1.0));
    assert_eq!(c.span(1.0), 2);
    assert!((c.eval(1.0) - pts[2]).norm() < 1e-15);
}

// ------------------------------------------------ polynomial reproduction ----

/// Knot vectors of several degrees, with repeated and uneven interior knots.
fn assorted_knot_vectors() -> Vec<(usize, Vec<f64>)> {
    let mut out = vec![
        (1, vec![0.0, 0.5, 0.7, 0.7, 1.9, 2.0, 3.5]),
        (2, vec![-1.0, 0.0, 0.0, 0.25, 1.0, 1.0, 3.0, 3.1, 4.0]),
        (
            3,
            vec![
                0.0, 0.0, 0.0, 0.0, 0.1, 0.1, 0.1, 2.0, 2.2, 5.0, 5.0, 5.0, 5.0,
            ],
        ),
        (3, (0..=12).map(|i| f64::from(i) * 0.37 - 1.0).collect()),
        (
            4,
            vec![0.0, 1.0, 1.5, 2.0, 2.0, 3.0, 3.0, 3.25, 4.0, 6.0, 7.0, 8.0],
        ),
        (5, (0..=14).map(|i| f64::from(i * i) / 7.0).collect()),
    ];
    // A pseudo-random knot vector (a fixed linear congruential sequence).
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut knots: Vec<f64> = (0..16).map(|_| 3.0 * next()).collect();
    knots.sort_by(f64::total_cmp);
    out.push((4, knots));
    out
}

/// A rounding bound for the `order`-th derivative of a spline whose control
/// coordinates carry relative errors of a few ulps at `scale`: each of the
/// `order` differencing steps divides a difference by a knot window that is at
/// least the smallest positive knot gap `h` and multiplies it by at most `p`,
/// so the error can grow by up to `2p/h` per order.
fn derivative_tolerance(p: usize, order: usize, knots: &[f64], scale: f64) -> f64 {
    let h = knots
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&g| g > 0.0)
        .fold(f64::INFINITY, f64::min);
    let growth: f64 = (0..order.min(p))
        .map(|s| 2.0 * (p - s) as f64 / h)
        .product();
    16.0 * f64::EPSILON * scale * growth
}

/// Greville abscissae ξᵢ = (t_{i+1} + … + t_{i+p})/p.
fn greville(p: usize, knots: &[f64]) -> Vec<f64> {
    let n = knots.len() - p - 1;
    (0..n)
        .map(|i| knots[i + 1..=i + p].iter().sum::<f64>() / p as f64)
        .collect()
}

/// Coefficients of t² for degree p ≥ 2: the blossom Σ_{j<k} t_j t_k / C(p, 2)
/// over t_{i+1} … t_{i+p}.
fn square_coefficients(p: usize, knots: &[f64]) -> Vec<f64> {
    let n = knots.len() - p - 1;
    let pairs = (p * (p - 1) / 2) as f64;
    (0..n)
        .map(|i| {
            let u = &knots[i + 1..=i + p];
            let mut s = 0.0;
            for j in 0..p {
                for k in j + 1..p {
                    s += u[j] * u[k];
                }
            }
            s / pairs
        })
        .collect()
}

#[test]
fn greville_control_points_reproduce_x_equals_t_for_any_knot_vector() {
    for (p, knots) in assorted_knot_vectors() {
        let xs = greville(p, &knots);
        let pts = xs.iter().map(|&x| Point1::new(x)).collect();
        let c = BSpline::new(p, knots.clone(), pts).unwrap();
        let (a, b) = c.domain();
        let scale = 1.0 + xs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut ts: Vec<f64> = (0..=300).map(|k| a + (b - a) * k as f64 / 300.0).collect();
        ts.extend(knots.iter().copied().filter(|&k| a <= k && k <= b));
        for t in ts {
            assert_close(
                c.eval(t).x,
                t,
                1e-14 * (1.0 + t.abs()),
                &format!("p={p} t={t}"),
            );
            let tol1 = derivative_tolerance(p, 1, &knots, scale);
            assert_close(c.derivative(t).x, 1.0, tol1, &format!("p={p} t={t} '"));
            for order in 2..=p {
                let d = c.nth_derivative(t, order).unwrap().x;
                let tol = derivative_tolerance(p, order, &knots, scale);
                assert_close(d, 0.0, tol, &format!("p={p} t={t} order {order}"));
            }
            assert_eq!(c.nth_derivative(t, p + 1).unwrap().x, 0.0);
        }
    }
}

#[test]
fn blossom_control_points_reproduce_t_squared_for_any_knot_vector() {
    for (p, knots) in assorted_knot_vectors().into_iter().filter(|(p, _)| *p >= 2) {
        let xs = greville(p, &knots);
        let ys = square_coefficients(p, &knots);
        let pts = xs
            .iter()
            .zip(&ys)
            .map(|(&x, &y)| Point2::new(x, y))
            .collect();
        let c = BSpline::new(p, knots.clone(), pts).unwrap();
        let (a, b) = c.domain();
        let scale = 1.0 + a.abs().max(b.abs()).powi(2);
        for k in 0..=300 {
            let t = a + (b - a) * k as f64 / 300.0;
            let (pt, d) = c.eval_with_derivative(t);
            assert_close(pt.x, t, 1e-14 * scale, &format!("p={p} t={t} x"));
            assert_close(pt.y, t * t, 1e-14 * scale, &format!("p={p} t={t} y"));
            assert_close(d.y, 2.0 * t, 1e-12 * scale, &format!("p={p} t={t} y'"));
            let d2 = c.nth_derivative(t, 2).unwrap();
            assert_close(d2.y, 2.0, 1e-10 * scale, &format!("p={p} t={t} y''"));
        }
    }
}

// ---------------------------------------------------- repeated knots ----

#[test]
fn interior_knot_of_multiplicity_p_passes_through_a_control_point() {
    let pts = points(5);
    let quadratic =
        BSpline::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0], pts.clone()).unwrap();
    assert!((quadratic.eval(1.0) - pts[2]).norm() < 1e-15);
    let pts = points(7);
    let cubic = BSpline::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0],
        pts.clone(),
    )
    .unwrap();
    assert!((cubic.eval(1.0) - pts[3]).norm() < 1e-15);
    // The curve is continuous there: the left limit is the same point.
    assert!((cubic.eval(1.0 - 1e-12) - pts[3]).norm() < 1e-9);
}

#[test]
fn interior_knot_of_full_multiplicity_takes_the_right_limit() {
    let pts = points(6);
    let c = BSpline::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        pts.clone(),
    )
    .unwrap();
    // Two Bézier pieces that jump from P2 (left limit) to P3 (value) at t = 1.
    assert!((c.eval(1.0) - pts[3]).norm() < 1e-15);
    assert!((c.eval(1.0 - 1e-12) - pts[2]).norm() < 1e-9);
    assert_eq!(c.span(1.0), 5);
    // The derivative there is the right derivative: 2 (P4 − P3) / (2 − 1).
    assert!((c.derivative(1.0) - (pts[4] - pts[3]) * 2.0).norm() < 1e-13);
    assert!((c.nth_derivative(1.0, 1).unwrap() - (pts[4] - pts[3]) * 2.0).norm() < 1e-13);
    let mut out = [0.0; 3];
    assert_eq!(c.basis_functions(1.0, &mut out).unwrap(), 3);
    assert_eq!(out, [1.0, 0.0, 0.0]);
}

// ----------------------------------------------------------------- span ----

#[test]
fn span_finds_the_half_open_knot_interval() {
    // Knots i/10, degree 3, 7 points: domain [0.3, 0.7], spans 3 … 6.
    let c = BSpline::uniform(3, points(7)).unwrap();
    let knots = c.knots().to_vec();
    assert_eq!(c.span(knots[3]), 3);
    assert_eq!(c.span(0.35), 3);
    assert_eq!(c.span(knots[4]), 4);
    assert_eq!(c.span(0.45), 4);
    assert_eq!(c.span(knots[5]), 5);
    assert_eq!(c.span(knots[6]), 6);
    assert_eq!(c.span(0.69), 6);
    assert_eq!(c.span(knots[7]), 6); // domain end: last span
    assert_eq!(c.span(-1.0), 3);
    assert_eq!(c.span(2.0), 6);
    assert_eq!(c.span(f64::NAN), 3);
    assert_eq!(c.span(f64::INFINITY), 6);
    assert_eq!(c.span(f64::NEG_INFINITY), 3);
}

#[test]
fn span_skips_empty_spans_of_repeated_knots() {
    let c = BSpline::new(2, vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], points(5)).unwrap();
    assert_eq!(c.span(0.0), 2);
    assert_eq!(c.span(0.25), 2);
    assert_eq!(c.span(0.5), 4);
    assert_eq!(c.span(0.75), 4);
    assert_eq!(c.span(1.0), 4);
    for k in 0..=100 {
        let t = k as f64 / 100.0;
        let i = c.span(t);
        let kn = c.knots();
        assert!(kn[i] <= t && kn[i] < kn[i + 1], "t={t} span {i}");
        assert!(t < kn[i + 1] || t == 1.0, "t={t} span {i}");
    }
}

// ------------------------------------------------------- Bézier spans ----

#[test]
fn bezier_span_count_is_the_number_of_nonempty_spans() {
    let cases: Vec<(BSpline<2>, usize)> = vec![
        (BSpline::clamped(3, points(7)).unwrap(), 4),
        (BSpline::uniform(3, points(7)).unwrap(), 4),
        (BSpline::clamped(3, points(4)).unwrap(), 1),
        (BSpline::clamped(0, points(5)).unwrap(), 5),
        (
            BSpline::new(2, vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], points(5)).unwrap(),
            2,
        ),
        (
            BSpline::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
                points(6),
            )
            .unwrap(),
            2,
        ),
    ];
    for (c, want) in cases {
        let spans = c.to_bezier_spans();
        assert_eq!(spans.len(), want, "knots {:?}", c.knots());
        // The spans tile the domain in order.
        assert_eq!(spans[0].knots.0, c.domain().0);
        assert_eq!(spans[want - 1].knots.1, c.domain().1);
        for w in spans.windows(2) {
            assert_eq!(w[0].knots.1, w[1].knots.0);
        }
        for s in &spans {
            assert!(s.knots.0 < s.knots.1);
            assert_eq!(s.curve.degree(), c.degree());
        }
    }
}

#[test]
fn bezier_spans_evaluate_the_spline() {
    let c = BSpline::new(
        3,
        vec![0.0, 0.0, 0.5, 1.0, 1.0, 2.5, 3.0, 3.5, 4.0, 4.0, 4.0],
        points(7),
    )
    .unwrap();
    for span in c.to_bezier_spans() {
        let (a, b) = span.knots;
        for k in 0..=32 {
            let s = k as f64 / 32.0;
            // Inside each span (the right end is the next span's start).
            let t = a + (b - a) * s;
            assert!((span.curve.eval(s) - c.eval(t)).norm() < 1e-12, "t={t}");
            if s < 1.0 {
                let d = span.curve.derivative(s) / (b - a) - c.derivative(t);
                assert!(d.norm() < 1e-11 * (1.0 + c.derivative(t).norm()), "t={t}");
            }
        }
    }
}

#[test]
fn clamped_cubic_on_four_points_is_one_span_with_the_same_control_points() {
    let pts = points(4);
    let spans = BSpline::clamped(3, pts.clone()).unwrap().to_bezier_spans();
    assert_eq!(spans.len(), 1);
    assert_eq!(spans[0].knots, (0.0, 1.0));
    for (q, p) in spans[0].curve.points().iter().zip(&pts) {
        assert!((q - p).norm() < 1e-15);
    }
}

#[test]
fn uniform_cubic_bezier_points_are_the_classic_one_third_two_thirds_rule() {
    // For uniform knots, the Bézier points of span [t3, t4] are
    // b0 = (P0 + 4P1 + P2)/6, b1 = (2P1 + P2)/3, b2 = (P1 + 2P2)/3,
    // b3 = (P1 + 4P2 + P3)/6.
    let pts: Vec<Point1<f64>> = [1.0, -2.0, 5.0, 3.0]
        .iter()
        .map(|&x| Point1::new(x))
        .collect();
    let c = BSpline::new(3, (0..=7).map(f64::from).collect(), pts).unwrap();
    let spans = c.to_bezier_spans();
    assert_eq!(spans.len(), 1);
    let want = [
        (1.0 - 8.0 + 5.0) / 6.0,
        (-4.0 + 5.0) / 3.0,
        (-2.0 + 10.0) / 3.0,
        (-2.0 + 20.0 + 3.0) / 6.0,
    ];
    let got: Vec<f64> = spans[0].curve.points().iter().map(|p| p.x).collect();
    assert_all_close(&got, &want, 1e-14, "Bézier points");
}

// --------------------------------------------------------- knot insertion ----

#[test]
fn insert_knot_matches_the_nurbs_book_example() {
    // Piegl & Tiller, Example 5.1: p = 3, U = {0,0,0,0,1,2,3,4,5,5,5,5},
    // insert u = 5/2: α₃ = 5/6, α₄ = 1/2, α₅ = 1/6.
    let pts = points(8);
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0];
    let c = BSpline::new(3, knots, pts.clone()).unwrap();
    let d = c.insert_knot(2.5, 1).unwrap();
    assert_eq!(
        d.knots(),
        &[
            0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.5, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0
        ]
    );
    let q = d.points();
    assert_eq!(q.len(), 9);
    assert_eq!(&q[..3], &pts[..3]);
    let mix = |a: Point2<f64>, b: Point2<f64>, alpha: f64| a + (b - a) * alpha;
    assert!((q[3] - mix(pts[2], pts[3], 5.0 / 6.0)).norm() < 1e-14);
    assert!((q[4] - mix(pts[3], pts[4], 0.5)).norm() < 1e-14);
    assert!((q[5] - mix(pts[4], pts[5], 1.0 / 6.0)).norm() < 1e-14);
    assert_eq!(&q[6..], &pts[5..]);
    assert_eq!(d.domain(), c.domain());
    for k in 0..=100 {
        let t = 5.0 * k as f64 / 100.0;
        assert!((d.eval(t) - c.eval(t)).norm() < 1e-13, "t={t}");
    }
}

#[test]
fn inserting_a_knot_p_times_puts_a_control_point_on_the_curve() {
    let c = BSpline::clamped(3, points(7)).unwrap();
    let u = 0.6;
    let d = c.insert_knot(u, 3).unwrap();
    assert_eq!(d.points().len(), 10);
    assert_eq!(d.knots().iter().filter(|&&k| k == u).count(), 3);
    let on_curve = c.eval(u);
    assert!(
        d.points().iter().any(|p| (p - on_curve).norm() < 1e-14),
        "no control point at C({u}) = {on_curve}"
    );
    for k in 0..=100 {
        let t = k as f64 / 100.0;
        assert!((d.eval(t) - c.eval(t)).norm() < 1e-13, "t={t}");
        assert!((d.derivative(t) - c.derivative(t)).norm() < 1e-11, "t={t}");
    }
}

#[test]
fn inserting_an_existing_knot_raises_its_multiplicity() {
    let c = BSpline::uniform(2, points(6)).unwrap();
    let u = c.knots()[4];
    let d = c.insert_knot(u, 1).unwrap();
    assert_eq!(d.knots().len(), c.knots().len() + 1);
    assert_eq!(d.knots().iter().filter(|&&k| k == u).count(), 2);
    assert_eq!(d.domain(), c.domain());
    let (a, b) = c.domain();
    for k in 0..=50 {
        let t = a + (b - a) * k as f64 / 50.0;
        assert!((d.eval(t) - c.eval(t)).norm() < 1e-13, "t={t}");
    }
}

#[test]
fn inserting_at_the_domain_ends_keeps_the_curve() {
    let c = BSpline::uniform(3, points(6)).unwrap();
    let (a, b) = c.domain();
    for u in [a, b] {
        let d = c.insert_knot(u, 2).unwrap();
        assert_eq!(d.domain(), (a, b), "u={u}");
        for k in 0..=50 {
            let t = a + (b - a) * k as f64 / 50.0;
            assert!((d.eval(t) - c.eval(t)).norm() < 1e-13, "u={u} t={t}");
        }
    }
}

#[test]
fn inserting_zero_times_is_the_identity() {
    let c = BSpline::clamped(2, points(5)).unwrap();
    assert_eq!(c.insert_knot(0.3, 0).unwrap(), c);
}

#[test]
fn inserting_a_knot_into_a_degree_zero_spline_splits_a_step() {
    let pts = points(3);
    let c = BSpline::new(0, vec![0.0, 1.0, 2.0, 3.0], pts.clone()).unwrap();
    let d = c.insert_knot(1.5, 1).unwrap();
    assert_eq!(d.knots(), &[0.0, 1.0, 1.5, 2.0, 3.0]);
    assert_eq!(d.points(), &[pts[0], pts[1], pts[1], pts[2]]);
}

// ---------------------------------------------------------- derivatives ----

#[test]
fn derivative_spline_of_a_cubic_is_a_quadratic_on_the_same_domain() {
    let c = BSpline::new(
        3,
        vec![0.0, 0.0, 0.5, 1.0, 1.0, 2.5, 3.0, 3.5, 4.0, 4.0, 4.0],
        points(7),
    )
    .unwrap();
    let d = c.derivative_spline();
    assert_eq!(d.degree(), 2);
    assert_eq!(d.domain(), c.domain());
    assert_eq!(d.knots(), &c.knots()[1..c.knots().len() - 1]);
    assert_eq!(d.points().len(), 6);
    let (a, b) = c.domain();
    for k in 0..=200 {
        let t = a + (b - a) * k as f64 / 200.0;
        let want = c.derivative(t);
        assert!(
            (d.eval(t).coords - want).norm() < 1e-12 * (1.0 + want.norm()),
            "t={t}"
        );
        let want2 = c.nth_derivative(t, 2).unwrap();
        assert!(
            (d.derivative(t) - want2).norm() < 1e-11 * (1.0 + want2.norm()),
            "t={t}"
        );
    }
}

#[test]
fn nth_derivative_spline_matches_nth_derivative() {
    let c = BSpline::uniform(4, points(9)).unwrap();
    let (a, b) = c.domain();
    for order in 0..=5 {
        let d = c.nth_derivative_spline(order);
        assert_eq!(d.degree(), 4usize.saturating_sub(order));
        assert_eq!(d.domain(), c.domain());
        for k in 0..=50 {
            let t = a + (b - a) * k as f64 / 50.0;
            let want = c.nth_derivative(t, order).unwrap();
            let got = d.eval(t).coords;
            assert!(
                (got - want).norm() <= 1e-12 * (1.0 + want.norm()),
                "order {order} t={t}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn derivative_spline_of_degree_zero_is_the_zero_spline() {
    let c = BSpline::new(0, vec![0.0, 1.0, 2.0], points(2)).unwrap();
    let d = c.derivative_spline();
    assert_eq!(d.degree(), 0);
    assert_eq!(d.knots(), c.knots());
    assert!(d.points().iter().all(|p| *p == Point2::origin()));
}

#[test]
fn nth_derivative_above_the_degree_is_exactly_zero() {
    let c = BSpline::uniform(3, points(7)).unwrap();
    for t in [0.3, 0.41, 0.5, 0.7] {
        for order in [4, 5, 100, usize::MAX] {
            assert_eq!(c.nth_derivative(t, order).unwrap(), Vector2::zeros());
        }
    }
}

#[test]
fn uniform_cubic_is_twice_continuously_differentiable_at_knots() {
    let c = BSpline::uniform(3, points(8)).unwrap();
    for &u in &c.knots()[4..8] {
        let h = 1e-7;
        for order in 0..=2 {
            let left = c.nth_derivative(u - h, order).unwrap();
            let right = c.nth_derivative(u, order).unwrap();
            let scale = 1.0 + right.norm();
            // Left limit differs from the value by O(h · next derivative).
            assert!((left - right).norm() < 1e-3 * scale, "u={u} order {order}");
        }
        // The third derivative jumps (generic control points).
        let jump = c.nth_derivative(u - 1e-9, 3).unwrap() - c.nth_derivative(u, 3).unwrap();
        assert!(jump.norm() > 1.0, "u={u}");
    }
}

#[test]
fn eval_with_derivative_agrees_with_eval_and_nth_derivative() {
    let c = BSpline::new(
        3,
        vec![0.0, 0.0, 0.5, 1.0, 1.0, 2.5, 3.0, 3.5, 4.0, 4.0, 4.0],
        points(7),
    )
    .unwrap();
    let (a, b) = c.domain();
    for k in 0..=200 {
        let t = a + (b - a) * k as f64 / 200.0;
        let (p, d) = c.eval_with_derivative(t);
        assert!((p - c.eval(t)).norm() < 1e-14, "t={t}");
        let d1 = c.nth_derivative(t, 1).unwrap();
        assert!((d - d1).norm() < 1e-12 * (1.0 + d1.norm()), "t={t}");
        assert_eq!(d, c.derivative(t));
        assert!((c.nth_derivative(t, 0).unwrap() - p.coords).norm() < 1e-14);
    }
}

// ---------------------------------------------------------------- misc ----

#[test]
fn bounds_contain_the_curve() {
    let c = BSpline::uniform(3, points(9)).unwrap();
    let (lo, hi) = c.bounds();
    let (a, b) = c.domain();
    for k in 0..=500 {
        let p = c.eval(a + (b - a) * k as f64 / 500.0);
        assert!(lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y);
    }
    let xs: Vec<f64> = c.points().iter().map(|p| p.x).collect();
    assert_eq!(lo.x, xs.iter().copied().fold(f64::INFINITY, f64::min));
    assert_eq!(hi.x, xs.iter().copied().fold(f64::NEG_INFINITY, f64::max));
}

#[test]
fn discretize_covers_the_domain_exactly() {
    let c = BSpline::uniform(3, points(7)).unwrap();
    let s = c.discretize(12);
    assert_eq!(s.len(), 13);
    assert_eq!(s[0].t, c.domain().0);
    assert_eq!(s[12].t, c.domain().1);
    for sample in &s {
        let (p, d) = c.eval_with_derivative(sample.t);
        assert_eq!((sample.point, sample.derivative), (p, d));
    }
}

#[test]
fn parameters_outside_the_domain_evaluate_at_the_nearest_end() {
    let c = BSpline::uniform(3, points(7)).unwrap();
    let (a, b) = c.domain();
    assert_eq!(c.eval(a - 0.1), c.eval(a));
    assert_eq!(c.eval(b + 0.1), c.eval(b));
    assert_eq!(c.derivative(-10.0), c.derivative(a));
    assert_eq!(
        c.nth_derivative(10.0, 2).unwrap(),
        c.nth_derivative(b, 2).unwrap()
    );
}

#[test]
fn one_dimensional_spline_derivative_is_a_vector1() {
    let c = BSpline::clamped(1, vec![Point1::new(0.0), Point1::new(2.0)]).unwrap();
    assert_eq!(c.derivative(0.5), Vector1::new(2.0));
    assert_eq!(c.eval(0.25), Point1::new(0.5));
}

/// A derivative spline is itself a valid B-spline: its knots and points pass
/// `BSpline::new`, also where an interior knot of full multiplicity `p + 1`
/// (a jump) would otherwise keep that multiplicity at degree `p − 1`, which
/// `new` rejects (the vanishing control point and one knot copy are dropped).
#[test]
fn derivative_spline_of_a_jump_is_a_valid_spline() {
    let c = BSpline::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        points(6),
    )
    .unwrap();
    let d = c.derivative_spline();
    for t in [0.25, 1.0, 1.5] {
        assert!((d.eval(t).coords - c.derivative(t)).norm() < 1e-12);
    }
    let rebuilt = BSpline::new(d.degree(), d.knots().to_vec(), d.points().to_vec());
    assert_eq!(rebuilt.as_ref().err(), None);
    assert!(d.insert_knot(1.0, 0).is_ok());
}

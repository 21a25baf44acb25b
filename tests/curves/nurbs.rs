//! Tests of `Nurbs`: evaluation and derivatives against exact rational
//! arithmetic (Cox–de Boor and the quotient rule in `BigRational`), equal
//! weights against the `BSpline` of the same data, circles and arcs against
//! their closed forms, knot insertion, rational Bézier spans and flattening
//! against evaluation, the edge rules, bad inputs, and derivatives against
//! central finite differences.

use revolve_testkit as common;

use common::Rng;
use common::random_nurbs::{Random, parameters, random_parts};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use proptest::prelude::*;
use revolve::curve::{MAX_DERIVATIVE_ORDER, MAX_WEIGHT_RATIO};
use revolve::nalgebra::{Point2, Point3, SVector, Vector2};
use revolve::{BSpline, Curve, Error, Nurbs};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI, TAU};

type Q = BigRational;

/// The exact value of a finite `f64`.
fn q(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

fn f(x: &Q) -> f64 {
    x.to_f64().expect("representable")
}

// ------------------------------------------------------------ generators ----

// The random NURBS (`Random`, `random_parts`, `parameters`) come from
// `revolve_testkit::random_nurbs`: `tests/alloc.rs` checks on the same
// curves that evaluation does not allocate.

// ------------------------------------------------------ exact reference ----

/// The index `i` of the knot span `[tᵢ, tᵢ₊₁)` containing `t` (half-open; the
/// end of the domain `t_n` belongs to the last non-empty span), by a plain
/// scan: independent of the library's search.
fn span_of(knots: &[f64], p: usize, n: usize, t: f64) -> usize {
    if t >= knots[n] {
        return (p..n).rev().find(|&i| knots[i] < knots[i + 1]).unwrap();
    }
    (p..n).find(|&i| knots[i] <= t && t < knots[i + 1]).unwrap()
}

/// The derivatives `N⁽ᵏ⁾_{i,q}(t)` of all basis functions, exactly, as
/// `table[k][q][i]` for `k < orders`, `q ≤ p`: Cox–de Boor for the values
/// (`N_{i,0}` is 1 on the span containing `t`), and
/// `N⁽ᵏ⁾_{i,q} = q·(N⁽ᵏ⁻¹⁾_{i,q−1}/(t_{i+q} − tᵢ) − N⁽ᵏ⁻¹⁾_{i+1,q−1}/(t_{i+q+1} − t_{i+1}))`
/// for the derivatives (Piegl & Tiller eq. 2.5 and 2.9), with `0/0 = 0`.
fn basis_table(knots: &[Q], p: usize, span: usize, t: &Q, orders: usize) -> Vec<Vec<Vec<Q>>> {
    let m = knots.len() - 1;
    let mut d = vec![vec![vec![Q::zero(); m]; p + 1]; orders];
    d[0][0][span] = Q::one();
    for k in 0..orders {
        for q in 1..=p {
            let qq = Q::from_integer(BigInt::from(q));
            for i in 0..m - q {
                let left = &knots[i + q] - &knots[i];
                let right = &knots[i + q + 1] - &knots[i + 1];
                let mut value = Q::zero();
                if k == 0 {
                    let (lower, upper) = (&d[0][q - 1][i], &d[0][q - 1][i + 1]);
                    if !left.is_zero() && !lower.is_zero() {
                        value += (t - &knots[i]) / &left * lower;
                    }
                    if !right.is_zero() && !upper.is_zero() {
                        value += (&knots[i + q + 1] - t) / &right * upper;
                    }
                } else {
                    let (lower, upper) = (&d[k - 1][q - 1][i], &d[k - 1][q - 1][i + 1]);
                    if !left.is_zero() && !lower.is_zero() {
                        value += &qq * lower / &left;
                    }
                    if !right.is_zero() && !upper.is_zero() {
                        value -= &qq * upper / &right;
                    }
                }
                d[k][q][i] = value;
            }
        }
    }
    d
}

/// `C⁽ᵏ⁾(t)` for `k = 0 … orders − 1`, exactly, as f64 vectors, with the
/// size `Sₖ` each is compared against: the quotient rule
/// `C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σⱼ C(k, j) w⁽ʲ⁾ C⁽ᵏ⁻ʲ⁾)/w` with every term taken in
/// absolute value, `A⁽ᵏ⁾` as `Σᵢ |wᵢPᵢ|·|Nᵢ⁽ᵏ⁾|` (the sums whose rounding
/// any floating-point evaluation suffers).
fn exact_derivatives(c: &Random, t: f64, orders: usize) -> Vec<(Vector2<f64>, f64)> {
    let p = c.degree;
    let n = c.points.len();
    let span = span_of(&c.knots, p, n, t);
    let knots: Vec<Q> = c.knots.iter().map(|&k| q(k)).collect();
    let tq = q(t);
    let table = basis_table(&knots, p, span, &tq, orders);
    // Homogeneous derivatives (A⁽ᵏ⁾, w⁽ᵏ⁾) and their absolute sizes.
    let mut a = vec![[Q::zero(), Q::zero()]; orders];
    let mut w = vec![Q::zero(); orders];
    let mut a_abs = vec![Q::zero(); orders];
    let mut w_abs = vec![Q::zero(); orders];
    let controls = c.points.iter().zip(&c.weights).enumerate();
    for (i, (point, &weight)) in controls.take(span + 1).skip(span - p) {
        let wi = q(weight);
        let (x, y) = (q(point.x), q(point.y));
        let size = &wi * (x.abs() + y.abs());
        for (k, row) in table.iter().enumerate() {
            let nk = &row[p][i];
            a[k][0] += &wi * &x * nk;
            a[k][1] += &wi * &y * nk;
            w[k] += &wi * nk;
            a_abs[k] += &size * nk.abs();
            w_abs[k] += &wi * nk.abs();
        }
    }
    let mut out: Vec<[Q; 2]> = Vec::with_capacity(orders);
    let mut sizes: Vec<Q> = Vec::with_capacity(orders);
    for k in 0..orders {
        let mut v = a[k].clone();
        let mut s = a_abs[k].clone();
        let mut binom = Q::one();
        for j in 1..=k {
            binom =
                binom * Q::from_integer(BigInt::from(k + 1 - j)) / Q::from_integer(BigInt::from(j));
            for d in 0..2 {
                v[d] -= &binom * &w[j] * &out[k - j][d];
            }
            s += &binom * &w_abs[j] * &sizes[k - j];
        }
        let v = [&v[0] / &w[0], &v[1] / &w[0]];
        out.push(v);
        sizes.push(s / &w[0]);
    }
    out.iter()
        .zip(&sizes)
        .map(|(v, s)| (Vector2::new(f(&v[0]), f(&v[1])), f(s)))
        .collect()
}

/// Every evaluator against exact rational arithmetic on 12 random NURBS of
/// each degree in `degrees` (knots, weights from 0.05 to 20, 6 parameters
/// each, orders 0 to 3): relative error at most 1e-12. Degree `d`'s curves
/// come from the seed `17 + d`, so the degrees split into tests that the
/// harness runs side by side.
fn check_against_exact_rational_arithmetic(degrees: std::ops::RangeInclusive<usize>) {
    let mut worst = 0.0_f64;
    let mut checked = 0;
    for degree in degrees {
        let mut rng = Rng(17 + degree as u64);
        for _ in 0..12 {
            let parts = random_parts(&mut rng, degree, 0.05, 20.0);
            let c = parts.nurbs();
            for t in parameters(&mut rng, &c, 6) {
                let exact = exact_derivatives(&parts, t, 4);
                let mut got = [Vector2::zeros(); 4];
                c.derivatives(t, &mut got).unwrap();
                let (point, first) = c.eval_with_derivative(t);
                let pairs = [
                    (got[0], 0),
                    (got[1], 1),
                    (got[2], 2),
                    (got[3], 3),
                    (c.eval(t).coords, 0),
                    (point.coords, 0),
                    (first, 1),
                    (c.derivative(t), 1),
                    (c.nth_derivative(t, 3).unwrap(), 3),
                ];
                for (value, k) in pairs {
                    let (want, size) = exact[k];
                    let error = (value - want).amax() / size;
                    worst = worst.max(error);
                    assert!(
                        error <= 1e-12,
                        "degree {degree}, t = {t}, order {k}: got {value:?}, exact {want:?}, \
                         relative error {error:e}; knots {:?}, weights {:?}",
                        parts.knots,
                        parts.weights
                    );
                    checked += 1;
                }
            }
        }
    }
    eprintln!("{checked} values, worst relative error {worst:e}");
}

#[test]
fn evaluation_and_derivatives_match_exact_rational_arithmetic_degrees_1_to_5() {
    check_against_exact_rational_arithmetic(1..=5);
}

#[test]
fn evaluation_and_derivatives_match_exact_rational_arithmetic_degree_6() {
    check_against_exact_rational_arithmetic(6..=6);
}

#[test]
fn evaluation_and_derivatives_match_exact_rational_arithmetic_degree_7() {
    check_against_exact_rational_arithmetic(7..=7);
}

#[test]
fn derivatives_of_high_order_match_exact_rational_arithmetic() {
    // Above the degree the rational derivatives keep going.
    let mut rng = Rng(71);
    for degree in 1..=3 {
        for _ in 0..6 {
            let parts = random_parts(&mut rng, degree, 0.2, 5.0);
            let c = parts.nurbs();
            for t in parameters(&mut rng, &c, 3) {
                let exact = exact_derivatives(&parts, t, 7);
                let mut got = [Vector2::zeros(); 7];
                c.derivatives(t, &mut got).unwrap();
                for (k, (value, (want, size))) in got.iter().zip(&exact).enumerate() {
                    let error = (value - want).amax() / size;
                    assert!(error <= 1e-12, "degree {degree} t {t} order {k}: {error:e}");
                }
            }
        }
    }
}

#[test]
fn a_heavy_middle_weight_gives_the_closed_form_quadratic() {
    // Degree 2, one piece: C(t) = Σ wᵢPᵢBᵢ / Σ wᵢBᵢ, computed by hand.
    let pts = vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 2.0),
        Point2::new(3.0, 0.0),
    ];
    let w = [0.5, 4.0, 2.0];
    let c = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        pts.clone(),
        w.to_vec(),
    )
    .unwrap();
    for k in 0..=20 {
        let t = k as f64 / 20.0;
        let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t];
        let den: f64 = (0..3).map(|i| w[i] * b[i]).sum();
        let num: Vector2<f64> = (0..3).map(|i| pts[i].coords * (w[i] * b[i])).sum();
        assert!((c.eval(t).coords - num / den).norm() < 1e-15, "t = {t}");
    }
}

// ------------------------------------------------ equal weights: BSpline ----

#[test]
fn equal_weights_give_the_bspline_of_the_same_data() {
    let mut rng = Rng(3);
    for degree in 0..=6 {
        for _ in 0..8 {
            let parts = random_parts(&mut rng, degree, 1.0, 1.0);
            let weight = rng.range(0.1, 10.0);
            let spline = BSpline::new(degree, parts.knots.clone(), parts.points.clone()).unwrap();
            let n = parts.points.len();
            let nurbs = Nurbs::new(
                degree,
                parts.knots.clone(),
                parts.points.clone(),
                vec![weight; n],
            )
            .unwrap();
            let from = Nurbs::from(spline.clone());
            assert_eq!(from.weights(), vec![1.0; n].as_slice());
            assert_eq!(from.knots(), spline.knots());
            assert_eq!(from.points(), spline.points());
            for c in [&nurbs, &from] {
                assert_eq!(c.domain(), spline.domain());
                assert_eq!(c.bezier_spans(), spline.bezier_spans());
                for span in c.to_bezier_spans() {
                    assert!(span.curve.is_polynomial());
                }
                for t in parameters(&mut rng, c, 10) {
                    let scale = 1.0 + spline.eval(t).coords.amax();
                    assert!((c.eval(t) - spline.eval(t)).amax() <= 1e-15 * scale);
                    let (p, d) = c.eval_with_derivative(t);
                    let (sp, sd) = spline.eval_with_derivative(t);
                    assert!((p - sp).amax() <= 1e-15 * scale);
                    assert_eq!(d, sd, "t = {t}");
                    let mut out = [Vector2::zeros(); 9];
                    c.derivatives(t, &mut out).unwrap();
                    for (k, v) in out.iter().enumerate() {
                        let want = spline.nth_derivative(t, k).unwrap();
                        assert!(
                            (v - want).amax() <= 1e-15 * (scale + want.amax()),
                            "degree {degree} t {t} order {k}: {v:?} vs {want:?}"
                        );
                        assert_eq!(c.nth_derivative(t, k).unwrap(), *v);
                    }
                }
            }
        }
    }
}

#[test]
fn scaling_all_weights_leaves_the_curve_unchanged() {
    let mut rng = Rng(5);
    for degree in 1..=5 {
        let parts = random_parts(&mut rng, degree, 0.05, 20.0);
        let c = parts.nurbs();
        let scaled = Nurbs::new(
            degree,
            parts.knots.clone(),
            parts.points.clone(),
            parts.weights.iter().map(|w| w * 1e6).collect(),
        )
        .unwrap();
        for t in parameters(&mut rng, &c, 20) {
            let scale = 10.0;
            assert!((c.eval(t) - scaled.eval(t)).norm() <= 1e-13 * scale);
        }
    }
}

// ------------------------------------------------------- circle and arc ----

/// `|v|` without underflow or overflow (scaled by the largest component).
fn length(v: Vector2<f64>) -> f64 {
    let m = v.amax();
    if m == 0.0 { 0.0 } else { m * (v / m).norm() }
}

/// The largest `|dist(C(t), center) − radius|` over `samples + 1` parameters,
/// in units of `ε·(radius + |center|)`, and the largest `|cos(radius, C′)|`
/// (also how far the unit tangent is from `C′/|C′|`); checks that the curve
/// turns counter-clockwise.
fn circle_errors(c: &Nurbs<2>, center: Point2<f64>, radius: f64, samples: usize) -> (f64, f64) {
    let unit = f64::EPSILON * (radius + center.coords.amax());
    let mut worst = (0.0_f64, 0.0_f64);
    for k in 0..=samples {
        let t = k as f64 / samples as f64;
        let (p, d) = c.eval_with_derivative(t);
        let r = p - center;
        let (r_unit, d_unit) = (r / length(r), d / length(d));
        worst.0 = worst.0.max((length(r) - radius).abs() / unit);
        worst.1 = worst.1.max(r_unit.dot(&d_unit).abs());
        // Counter-clockwise: the radius turns left into the velocity.
        assert!(r_unit.perp(&d_unit) > 0.0, "t = {t}: r = {r:?}, C′ = {d:?}");
        let tangent = c.tangent(t).unwrap();
        worst.1 = worst.1.max((tangent.into_inner() - d_unit).norm());
    }
    worst
}

#[test]
fn circle_is_four_exact_quarter_arcs() {
    let center = Point2::new(1.5, -2.0);
    let c = Nurbs::circle(center, 3.0).unwrap();
    assert_eq!(c.degree(), 2);
    assert_eq!(
        c.knots(),
        &[
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
        ]
    );
    let h = FRAC_1_SQRT_2;
    assert_eq!(c.weights(), &[1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0]);
    assert_eq!(c.points().len(), 9);
    assert_eq!(c.domain(), (0.0, 1.0));
    // Quarter points exactly.
    assert_eq!(c.eval(0.0), Point2::new(4.5, -2.0));
    assert_eq!(c.eval(0.25), Point2::new(1.5, 1.0));
    assert_eq!(c.eval(0.5), Point2::new(-1.5, -2.0));
    assert_eq!(c.eval(0.75), Point2::new(1.5, -5.0));
    assert_eq!(c.eval(1.0), Point2::new(4.5, -2.0));
    let (radial, perpendicular) = circle_errors(&c, center, 3.0, 4000);
    assert!(radial <= 2.0, "radial error {radial} ulps");
    assert!(perpendicular <= 1e-15, "{perpendicular}");
    // The bounds are the square about the circle.
    assert_eq!(c.bounds(), (Point2::new(-1.5, -5.0), Point2::new(4.5, 1.0)));
    assert!(c.bezier_spans().is_none());
    assert_eq!(c.rational_bezier_spans().unwrap().len(), 4);
}

#[test]
fn circles_of_many_sizes_are_round() {
    for (center, radius) in [
        (Point2::new(0.0, 0.0), 1.0),
        (Point2::new(0.0, 0.0), 1e-200),
        (Point2::new(1e-3, 2e-3), 1e-6),
        (Point2::new(-7.0, 3.0), 1e6),
        (Point2::new(0.0, 0.0), 1e99),
    ] {
        let c = Nurbs::circle(center, radius).unwrap();
        let (radial, perpendicular) = circle_errors(&c, center, radius, 1000);
        assert!(radial <= 2.0, "r = {radius}: {radial} ulps");
        // The control points' rounding, ε·|c|, is ε|c|/r relative to the radius.
        let limit = 1e-15 + 8.0 * f64::EPSILON * center.coords.amax() / radius;
        assert!(perpendicular <= limit, "r = {radius}: {perpendicular}");
    }
}

#[test]
fn arcs_lie_on_the_circle_and_end_at_their_angles() {
    let mut rng = Rng(11);
    let mut sweeps = vec![1e-9, 0.1, FRAC_PI_2, 1.0, 2.0, PI, 3.0, 4.5, 5.0, 6.0, TAU];
    sweeps.extend((0..20).map(|_| rng.range(0.0, TAU)));
    let (mut worst_radial, mut worst_perpendicular) = (0.0_f64, 0.0_f64);
    for &sweep in &sweeps {
        for start in [0.0, -2.5, 1.0, -PI, 7.0, rng.range(-10.0, 10.0)] {
            let (center, radius) = (
                Point2::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)),
                rng.range(0.1, 10.0),
            );
            let end = start + sweep;
            let a = Nurbs::arc(center, radius, start, end).unwrap();
            let pieces = (sweep / FRAC_PI_2).ceil().max(1.0) as usize;
            assert_eq!(a.points().len(), 2 * pieces + 1, "sweep {sweep}");
            assert_eq!(a.domain(), (0.0, 1.0));
            let (radial, perpendicular) = circle_errors(&a, center, radius, 2000);
            assert!(radial <= 4.0, "sweep {sweep} start {start}: {radial} ulps");
            // The control points' rounding (ε·(r + |c|)) is a relative error
            // ε(1 + |c|/r)/sweep of the chord directions.
            let limit = 1e-14 + 8.0 * f64::EPSILON * (1.0 + center.coords.amax() / radius) / sweep;
            worst_perpendicular = worst_perpendicular.max(perpendicular / limit);
            assert!(
                perpendicular <= limit,
                "sweep {sweep} start {start}: {perpendicular}"
            );
            worst_radial = worst_radial.max(radial);
            let at = |angle: f64| center + Vector2::new(angle.cos(), angle.sin()) * radius;
            let tol = 4.0 * f64::EPSILON * (radius + center.coords.amax());
            assert!((a.eval(0.0) - at(start)).amax() <= tol);
            assert!((a.eval(1.0) - at(end)).amax() <= tol, "sweep {sweep}");
            // Angles advance monotonically and add up to the sweep.
            let mut total = 0.0;
            let mut previous = a.eval(0.0) - center;
            for k in 1..=400 {
                let r = a.eval(k as f64 / 400.0) - center;
                let step = previous.perp(&r).atan2(previous.dot(&r));
                assert!(step >= 0.0);
                total += step;
                previous = r;
            }
            assert!(
                (total - sweep).abs() <= 1e-12 * (1.0 + start.abs()),
                "{total} vs {sweep}"
            );
            // The middle weight is cos(half piece angle).
            let half = 0.5 * sweep / pieces as f64;
            assert!((a.weights()[1] - half.cos()).abs() <= 1e-15);
        }
    }
    eprintln!(
        "worst radial error {worst_radial} ulps, perpendicularity {worst_perpendicular} of the limit"
    );
}

#[test]
fn a_full_turn_arc_is_a_closed_circle_starting_at_start() {
    for start in [0.0, 0.7, -3.0, 100.0] {
        let center = Point2::new(2.0, 1.0);
        let a = Nurbs::arc(center, 2.0, start, start + TAU).unwrap();
        assert_eq!(a.points().len(), 9);
        assert_eq!(a.eval(0.0), a.eval(1.0));
        let want = center + Vector2::new(start.cos(), start.sin()) * 2.0;
        assert!((a.eval(0.0) - want).amax() <= 8.0 * f64::EPSILON);
        // Each quarter ends a quarter turn further.
        for i in 1..4 {
            let angle = start + FRAC_PI_2 * i as f64;
            let want = center + Vector2::new(angle.cos(), angle.sin()) * 2.0;
            assert!((a.eval(i as f64 / 4.0) - want).amax() <= 1e-14);
        }
    }
    // A sweep beyond 2π by the rounding of the angles is a full turn.
    let start = 0.1;
    let end = start + TAU;
    assert!(Nurbs::arc(Point2::origin(), 1.0, start, end).is_ok());
    assert!(Nurbs::arc(Point2::origin(), 1.0, start, end + 1e-9).is_err());
}

#[test]
fn half_circle_derivatives_match_the_closed_form_rational_parametrization() {
    // The upper half circle from angle 0 to π is two quarter pieces; the
    // unit quarter (1, 0) → (0, 1) with middle weight √2/2 is
    // C(u) = ((1 − u)² + √2 u(1 − u), √2 u(1 − u) + u²)/W, W = 1 − (2 − √2)u(1 − u).
    let a = Nurbs::arc(Point2::origin(), 1.0, 0.0, PI).unwrap();
    let s = std::f64::consts::SQRT_2;
    for k in 0..=50 {
        let u = k as f64 / 50.0;
        let w = 1.0 - (2.0 - s) * u * (1.0 - u);
        let x = ((1.0 - u) * (1.0 - u) + s * u * (1.0 - u)) / w;
        let y = (s * u * (1.0 - u) + u * u) / w;
        // Its derivative in u by the quotient rule, in t = u/2 twice as fast.
        let dw = -(2.0 - s) * (1.0 - 2.0 * u);
        let dx = (-2.0 * (1.0 - u) + s * (1.0 - 2.0 * u) - x * dw) / w;
        let dy = (s * (1.0 - 2.0 * u) + 2.0 * u - y * dw) / w;
        let (p, d) = a.eval_with_derivative(0.5 * u);
        assert!((p - Point2::new(x, y)).norm() < 1e-15, "u = {u}");
        assert!(
            (d - Vector2::new(2.0 * dx, 2.0 * dy)).norm() < 1e-14,
            "u = {u}"
        );
    }
}

// ------------------------------------------------------- knot insertion ----

#[test]
fn knot_insertion_leaves_the_curve_unchanged() {
    let mut rng = Rng(23);
    for degree in 1..=6 {
        for _ in 0..6 {
            let parts = random_parts(&mut rng, degree, 0.05, 20.0);
            let c = parts.nurbs();
            let (a, b) = c.domain();
            let mut targets = vec![rng.range(a, b), rng.range(a, b), a, b];
            targets.extend(c.knots().iter().copied().filter(|&k| a <= k && k <= b));
            for t in targets {
                let existing = c.knots().iter().filter(|&&k| k == t).count();
                let room = degree + 1 - existing.min(degree + 1);
                if room == 0 {
                    assert!(matches!(
                        c.insert_knot(t, 1),
                        Err(Error::KnotMultiplicity { .. })
                    ));
                    continue;
                }
                let times = 1 + rng.below(room);
                let refined = c.insert_knot(t, times).unwrap();
                assert_eq!(refined.points().len(), c.points().len() + times);
                assert_eq!(refined.domain(), c.domain());
                for s in parameters(&mut rng, &c, 30) {
                    let (p, q) = (c.eval(s), refined.eval(s));
                    assert!(
                        (p - q).amax() <= 1e-13 * 10.0,
                        "degree {degree} t {t} s {s}: {p} vs {q}"
                    );
                    let (d, e) = (c.derivative(s), refined.derivative(s));
                    assert!(
                        (d - e).amax() <= 1e-12 * (1.0 + d.amax()),
                        "s {s}: {d} vs {e}"
                    );
                }
                // Weights stay within the original range.
                let (lo, hi) = minmax(c.weights());
                let (rlo, rhi) = minmax(refined.weights());
                assert!(lo <= rlo && rhi <= hi);
            }
        }
    }
}

fn minmax(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        })
}

#[test]
fn knot_insertion_errors_are_bsplines() {
    let c = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    assert!(matches!(
        c.insert_knot(1.5, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(f64::NAN, 1),
        Err(Error::ParameterOutOfDomain { .. })
    ));
    assert_eq!(
        c.insert_knot(0.25, 2),
        Err(Error::KnotMultiplicity {
            knot: 0.25,
            multiplicity: 4,
            max: 3
        })
    );
    // Within rounding of an existing knot inserts that knot.
    let d = c.insert_knot(0.25 + 1e-17, 1).unwrap();
    assert_eq!(d.knots().iter().filter(|&&k| k == 0.25).count(), 3);
    assert_eq!(c.insert_knot(0.3, 0).unwrap(), c);
    // Equal weights stay equal (the curve stays polynomial).
    let s = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Point2::origin(),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
        ],
        vec![0.3; 3],
    )
    .unwrap();
    let r = s.insert_knot(0.37, 2).unwrap();
    assert!(r.weights().iter().all(|&w| w == 0.3));
    assert!(r.bezier_spans().is_some());
}

// ------------------------------------------------------ spans, flattening ----

#[test]
fn rational_bezier_spans_agree_with_evaluation() {
    let mut rng = Rng(29);
    for degree in 0..=7 {
        for _ in 0..6 {
            let parts = random_parts(&mut rng, degree, 0.05, 20.0);
            let c = parts.nurbs();
            let spans = c.to_bezier_spans();
            assert_eq!(c.rational_bezier_spans().unwrap(), spans);
            let (a, b) = c.domain();
            assert_eq!(spans[0].knots.0, a);
            assert_eq!(spans[spans.len() - 1].knots.1, b);
            for pair in spans.windows(2) {
                assert_eq!(pair[0].knots.1, pair[1].knots.0);
            }
            for span in &spans {
                assert_eq!(span.curve.degree(), degree);
                let (lo, hi) = span.knots;
                for k in 0..=20 {
                    let u = k as f64 / 20.0;
                    let t = if k == 20 { hi } else { lo + (hi - lo) * u };
                    if k == 20 && t < b {
                        continue; // the next span's value (right limit) at a jump
                    }
                    let p = span.curve.eval(u);
                    assert!(
                        (p - c.eval(t)).amax() <= 1e-13 * 10.0,
                        "degree {degree} t {t}"
                    );
                    let d = span.curve.derivative(u) / (hi - lo);
                    let e = c.derivative(t);
                    assert!(
                        (d - e).amax() <= 1e-12 * (1.0 + e.amax()),
                        "t {t}: {d} vs {e}"
                    );
                }
            }
        }
    }
}

/// Distance from `p` to the segment `[a, b]`.
fn segment_distance(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let ab = b - a;
    let s = if ab.norm_squared() > 0.0 {
        ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * s)).norm()
}

/// Checks the flattening's claim against dense samples of the curve.
fn check_flattening(c: &Nurbs<2>, tolerance: f64) -> usize {
    let flat = c.flatten(tolerance).unwrap();
    assert!(flat.bound <= tolerance);
    let samples = &flat.samples;
    assert_eq!(samples[0].t, c.domain().0);
    assert_eq!(samples[samples.len() - 1].t, c.domain().1);
    for pair in samples.windows(2) {
        let (s0, s1) = (&pair[0], &pair[1]);
        assert!(s0.t <= s1.t);
        assert_eq!(s0.point, c.eval(s0.t));
        if s0.t == s1.t {
            continue; // a jump: the left limit, then the value
        }
        for k in 1..32 {
            let t = s0.t + (s1.t - s0.t) * (k as f64 / 32.0);
            let d = segment_distance(c.eval(t), s0.point, s1.point);
            assert!(
                d <= flat.bound * (1.0 + 1e-9),
                "t {t}: {d:e} > {:e}",
                flat.bound
            );
        }
    }
    samples.len()
}

#[test]
fn flattening_bound_holds_against_dense_samples() {
    let mut rng = Rng(31);
    for degree in 1..=6 {
        for _ in 0..4 {
            let parts = random_parts(&mut rng, degree, 0.05, 20.0);
            let c = parts.nurbs();
            for tolerance in [1.0, 1e-2, 1e-4] {
                check_flattening(&c, tolerance);
            }
        }
    }
    let circle = Nurbs::circle(Point2::new(1.0, 2.0), 5.0).unwrap();
    for tolerance in [1e-1, 1e-3, 1e-6, 1e-8] {
        let n = check_flattening(&circle, tolerance);
        // The sagitta of a chord of angle θ is r(1 − cos(θ/2)) ≈ rθ²/8: the
        // count needed at the tolerance is about 2π/√(8·tol/r); the bound from
        // the control polygon costs at most a small factor more.
        let needed = TAU / (8.0 * tolerance / 5.0).sqrt();
        assert!(
            (n as f64) < 4.0 * needed + 8.0,
            "tol {tolerance}: {n} samples, ~{needed} needed"
        );
    }
    // Strongly weighted: ratio 1e6 between neighbours.
    let c = Nurbs::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 3.0),
            Point2::new(2.0, -1.0),
            Point2::new(3.0, 2.0),
            Point2::new(4.0, 0.0),
        ],
        vec![1.0, 1e6, 1.0, 1e-2, 1.0],
    )
    .unwrap();
    check_flattening(&c, 1e-5);
    // Equal weights flatten as the B-spline does.
    let parts = random_parts(&mut rng, 3, 2.0, 2.0);
    let spline = BSpline::new(3, parts.knots.clone(), parts.points.clone()).unwrap();
    assert_eq!(
        parts.nurbs().flatten(1e-3).unwrap(),
        spline.flatten(1e-3).unwrap()
    );
}

#[test]
fn flattening_rejects_bad_tolerances() {
    let c = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    for tolerance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.flatten(tolerance),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    assert!(matches!(
        c.flatten(1e-13),
        Err(Error::ToleranceTooSmall { .. })
    ));
}

// ----------------------------------------------------------- edge rules ----

#[test]
fn edge_rules_follow_the_bspline() {
    // Degree 2 with a full-multiplicity interior knot: the curve jumps at 1.
    let c = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
            Point2::new(5.0, 5.0),
            Point2::new(6.0, 6.0),
            Point2::new(7.0, 5.0),
        ],
        vec![1.0, 2.0, 1.0, 1.0, 3.0, 1.0],
    )
    .unwrap();
    assert_eq!(c.domain(), (0.0, 2.0));
    // At the interior knot: the limit from the right.
    assert_eq!(c.eval(1.0), Point2::new(5.0, 5.0));
    assert!((c.eval(1.0 - 1e-12) - Point2::new(2.0, 0.0)).norm() < 1e-10);
    // At the end of the domain: the last point (limit from the left).
    assert_eq!(c.eval(2.0), Point2::new(7.0, 5.0));
    // Outside: the nearest end; NaN: the start.
    assert_eq!(c.eval(-5.0), c.eval(0.0));
    assert_eq!(c.eval(f64::NEG_INFINITY), c.eval(0.0));
    assert_eq!(c.eval(9.0), c.eval(2.0));
    assert_eq!(c.eval(f64::INFINITY), c.eval(2.0));
    assert_eq!(c.eval(f64::NAN), c.eval(0.0));
    assert_eq!(
        c.eval_with_derivative(f64::NAN),
        c.eval_with_derivative(0.0)
    );
    assert_eq!(c.eval_with_derivative(3.0), c.eval_with_derivative(2.0));
    let mut out = [Vector2::zeros(); 4];
    let mut end = [Vector2::zeros(); 4];
    c.derivatives(f64::NAN, &mut out).unwrap();
    c.derivatives(0.0, &mut end).unwrap();
    assert_eq!(out, end);
    c.derivatives(1e300, &mut out).unwrap();
    c.derivatives(2.0, &mut end).unwrap();
    assert_eq!(out, end);
    // The end derivative is the limit from the left: 2·(w₄/w₅)·(P₅ − P₄)/width.
    let d = c.derivative(2.0);
    assert!(
        (d - Vector2::new(1.0, -1.0) * (2.0 * 3.0)).norm() < 1e-13,
        "{d}"
    );
    // Tangent at the end from the left, at the interior knot from the right.
    let t = c.tangent(2.0).unwrap();
    assert!((t.into_inner() - Vector2::new(1.0, -1.0) / 2f64.sqrt()).norm() < 1e-15);
    let t = c.tangent(1.0).unwrap();
    assert!((t.into_inner() - Vector2::new(1.0, 1.0) / 2f64.sqrt()).norm() < 1e-15);
}

#[test]
fn tangent_at_a_repeated_point_is_the_limit() {
    // The first two control points coincide: C′(0) = 0, the tangent at the
    // start is the direction toward P₂ (second derivative, weights aside).
    let c = Nurbs::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 2.0),
            Point2::new(3.0, 0.0),
        ],
        vec![1.0, 5.0, 0.5, 2.0],
    )
    .unwrap();
    assert_eq!(c.derivative(0.0), Vector2::zeros());
    let t = c.tangent(0.0).unwrap().into_inner();
    assert!(
        (t - Vector2::new(1.0, 2.0) / 5f64.sqrt()).norm() < 1e-15,
        "{t}"
    );
    // A constant curve has no tangent.
    let flat = Nurbs::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Point2::new(1.0, 1.0); 2],
        vec![1.0, 3.0],
    )
    .unwrap();
    assert!(flat.tangent(0.5).is_none());
}

#[test]
fn three_dimensional_curves_work_too() {
    let mut rng = Rng(37);
    let points: Vec<Point3<f64>> = (0..6)
        .map(|_| {
            Point3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        })
        .collect();
    let weights: Vec<f64> = (0..6).map(|_| rng.range(0.1, 3.0)).collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.6, 1.0, 1.0, 1.0, 1.0];
    let c = Nurbs::new(3, knots, points.clone(), weights.clone()).unwrap();
    // Each coordinate is the rational function of the 1-D data.
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        let p = c.eval(t);
        for axis in 0..3 {
            let line: Vec<_> = points
                .iter()
                .map(|q| revolve::nalgebra::Point1::new(q[axis]))
                .collect();
            let one = Nurbs::new(3, c.knots().to_vec(), line, weights.clone()).unwrap();
            assert!((one.eval(t).x - p[axis]).abs() < 1e-15);
        }
        let (lo, hi) = c.bounds();
        assert!((0..3).all(|i| lo[i] <= p[i] && p[i] <= hi[i]));
    }
}

// ------------------------------------------------------------ bad input ----

fn unit_parts() -> (Vec<f64>, Vec<Point2<f64>>) {
    (
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
            Point2::new(3.0, 1.0),
        ],
    )
}

#[test]
fn bad_weights_are_named_errors() {
    let (knots, points) = unit_parts();
    let with = |w: Vec<f64>| Nurbs::new(2, knots.clone(), points.clone(), w);
    assert_eq!(
        with(vec![1.0, 0.0, 1.0, 1.0]),
        Err(Error::InvalidWeight {
            index: 1,
            weight: 0.0
        })
    );
    assert_eq!(
        with(vec![1.0, 1.0, 1.0, -2.0]),
        Err(Error::InvalidWeight {
            index: 3,
            weight: -2.0
        })
    );
    assert_eq!(
        with(vec![1.0, 1.0, f64::INFINITY, 1.0]),
        Err(Error::InvalidWeight {
            index: 2,
            weight: f64::INFINITY
        })
    );
    assert!(matches!(
        with(vec![f64::NAN, 1.0, 1.0, 1.0]),
        Err(Error::InvalidWeight { index: 0, weight }) if weight.is_nan()
    ));
    assert!(matches!(
        with(vec![1.0, -0.0, 1.0, 1.0]),
        Err(Error::InvalidWeight { index: 1, .. })
    ));
    assert_eq!(
        with(vec![1.0, 1.0, 1.0]),
        Err(Error::WeightCount {
            expected: 4,
            found: 3
        })
    );
    assert_eq!(
        with(vec![1.0; 5]),
        Err(Error::WeightCount {
            expected: 4,
            found: 5
        })
    );
    assert!(matches!(
        with(vec![1.0, 1e-9, 1.0, 1.0]),
        Err(Error::WeightRatioTooLarge { max, .. }) if max == MAX_WEIGHT_RATIO
    ));
    assert!(with(vec![1.0, 1e-8, 1.0, 1.0]).is_ok());
    // The point and knot checks come first, as in BSpline::new.
    let mut bad_points = points.clone();
    bad_points[2].x = f64::NAN;
    assert_eq!(
        Nurbs::new(2, knots.clone(), bad_points, vec![0.0; 4]),
        Err(Error::NonFinitePoint { index: 2 })
    );
    assert!(matches!(
        Nurbs::new(2, vec![0.0; 6], points.clone(), vec![0.0; 4]),
        Err(Error::KnotCount { .. })
    ));
}

#[test]
fn bad_knots_give_the_bspline_errors() {
    let (knots, points) = unit_parts();
    let weights = [1.0, 2.0, 1.0, 0.5];
    let cases: Vec<(usize, Vec<f64>, Vec<Point2<f64>>)> = vec![
        (2, knots.clone(), vec![]),
        (4, knots.clone(), points.clone()),
        (2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0], points.clone()),
        (
            2,
            vec![0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0],
            points.clone(),
        ),
        (
            2,
            vec![0.0, 0.0, 0.0, 1e200, 1e200, 1e200, 1e200],
            points.clone(),
        ),
        (2, vec![0.0, 0.0, 0.0, 0.7, 0.5, 1.0, 1.0], points.clone()),
        (
            2,
            vec![0.0, 0.0, 0.0, 0.5, 0.500_000_000_000_000_1, 1.0, 1.0],
            points.clone(),
        ),
        (1, vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0], points.clone()),
        (2, vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], points.clone()),
        (2, vec![0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0], points.clone()),
    ];
    for (degree, knots, points) in cases {
        let want = BSpline::new(degree, knots.clone(), points.clone()).unwrap_err();
        let n = points.len();
        let got = Nurbs::new(degree, knots, points, weights[..n.min(4)].to_vec()).unwrap_err();
        assert_eq!(got.to_string(), want.to_string());
    }
}

#[test]
fn bad_circles_and_arcs_are_named_errors() {
    let o = Point2::origin();
    for radius in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e101, -0.0] {
        assert!(
            matches!(Nurbs::circle(o, radius), Err(Error::InvalidRadius { .. })),
            "{radius}"
        );
        assert!(matches!(
            Nurbs::arc(o, radius, 0.0, 1.0),
            Err(Error::InvalidRadius { .. })
        ));
    }
    for center in [
        Point2::new(f64::NAN, 0.0),
        Point2::new(0.0, f64::INFINITY),
        Point2::new(-1e101, 0.0),
    ] {
        assert!(matches!(
            Nurbs::circle(center, 1.0),
            Err(Error::InvalidCenter { .. })
        ));
        assert!(matches!(
            Nurbs::arc(center, 1.0, 0.0, 1.0),
            Err(Error::InvalidCenter { .. })
        ));
    }
    // Control points beyond the coordinate limit.
    assert!(matches!(
        Nurbs::circle(Point2::new(1e100, 0.0), 1e99),
        Err(Error::CoordinateTooLarge { .. })
    ));
    for (start, end) in [
        (0.0, 0.0),
        (1.0, 0.5),
        (0.0, TAU + 1e-6),
        (0.0, 7.0),
        (f64::NAN, 1.0),
        (0.0, f64::NAN),
        (f64::NEG_INFINITY, 0.0),
        (0.0, f64::INFINITY),
        (1e300, 1e300),
    ] {
        assert_eq!(
            Nurbs::arc(o, 1.0, start, end)
                .map(|_| ())
                .unwrap_err()
                .to_string(),
            Error::InvalidSweep { start, end }.to_string()
        );
    }
    let e = Nurbs::arc(o, 1.0, 2.0, 1.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "arc from 2 to 1 radians: the sweep end − start must be a number in (0, 2π]"
    );
    assert_eq!(
        Nurbs::circle(o, -1.0).unwrap_err().to_string(),
        "radius -1 is not a finite positive number at most 1e100"
    );
}

#[test]
fn new_error_messages_name_the_numbers_and_are_distinct() {
    let errors = [
        Error::InvalidRadius { radius: -2.5 },
        Error::InvalidCenter {
            center: Point2::new(f64::NAN, 3.25),
        },
        Error::InvalidSweep {
            start: 1.5,
            end: 9.75,
        },
        Error::DerivativeOrderTooHigh {
            order: 2000,
            max: MAX_DERIVATIVE_ORDER,
        },
    ];
    let parts: [&[&str]; 4] = [
        &["radius", "-2.5"],
        &["center", "NaN", "3.25"],
        &["arc", "1.5", "9.75", "sweep"],
        &["2000", "1024"],
    ];
    let messages: Vec<String> = errors.iter().map(|e| e.to_string()).collect();
    for (message, parts) in messages.iter().zip(parts) {
        for part in parts {
            assert!(message.contains(part), "{message:?} lacks {part:?}");
        }
    }
    for (i, a) in messages.iter().enumerate() {
        assert!(messages[i + 1..].iter().all(|b| a != b));
    }
}

#[test]
fn derivative_orders_are_capped_not_panicking() {
    let c = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    assert_eq!(
        c.nth_derivative(0.3, usize::MAX),
        Err(Error::DerivativeOrderTooHigh {
            order: usize::MAX,
            max: MAX_DERIVATIVE_ORDER
        })
    );
    let mut big = vec![Vector2::zeros(); MAX_DERIVATIVE_ORDER + 2];
    assert!(matches!(
        c.derivatives(0.3, &mut big),
        Err(Error::DerivativeOrderTooHigh { .. })
    ));
    // The highest order is computed; it overflows for the circle (orders
    // grow like k!), which is reported with the first order that does.
    let result = c.nth_derivative(0.3, MAX_DERIVATIVE_ORDER);
    let Err(Error::DerivativeOverflow { order }) = result else {
        panic!("{result:?}");
    };
    assert!((100..=MAX_DERIVATIVE_ORDER).contains(&order), "{order}");
    let mut out = vec![Vector2::zeros(); order];
    c.derivatives(0.3, &mut out).unwrap();
    assert!(out.iter().all(|v| v.iter().all(|x| x.is_finite())));
    c.derivatives(0.3, &mut []).unwrap();
    // A polynomial curve's derivatives above the degree are zero.
    let line = Nurbs::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Point2::origin(), Point2::new(1.0, 1.0)],
        vec![2.0, 2.0],
    )
    .unwrap();
    assert_eq!(line.nth_derivative(0.5, 1000).unwrap(), Vector2::zeros());
}

#[test]
fn derivative_overflow_is_refused_at_construction() {
    // Close knots with large coordinates and varying weights.
    let knots = vec![0.0, 0.0, 0.0, 1e-250, 1e-250, 1e-250];
    let points = vec![
        Point2::new(1e80, 0.0),
        Point2::new(-1e80, 1e80),
        Point2::new(1e80, 1e80),
    ];
    let result = Nurbs::new(2, knots, points, vec![1.0, 0.5, 2.0]);
    assert!(
        matches!(result, Err(Error::DerivativeOverflow { .. })),
        "{result:?}"
    );
    // Constant points with strongly varying weights over a tiny domain: the
    // homogeneous derivative of w overflows even though the curve is constant.
    let knots = vec![0.0, 0.0, 1e-300, 1e-300];
    let result = Nurbs::new(1, knots, vec![Point2::new(1.0, 1.0); 2], vec![1.0, 1e-8]);
    assert!(
        matches!(result, Err(Error::DerivativeOverflow { .. })),
        "{result:?}"
    );
}

/// A garbage value for fuzzing: special floats and ordinary ones.
fn garbage(rng: &mut Rng) -> f64 {
    const SPECIAL: [f64; 14] = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MIN_POSITIVE,
        5e-324,
        1e-300,
        1e100,
        1e101,
        f64::MAX,
        1e-9,
    ];
    match rng.below(3) {
        0 => SPECIAL[rng.below(SPECIAL.len())],
        _ => rng.range(-3.0, 3.0),
    }
}

#[test]
fn garbage_input_never_panics() {
    let mut rng = Rng(41);
    let mut accepted = 0;
    for _ in 0..20_000 {
        let degree = rng.below(5);
        let n = rng.below(8);
        let knot_count = match rng.below(6) {
            0 => rng.below(14),
            _ => n + degree + 1,
        };
        // Mostly plausible knots (sorted, some repeated), sometimes spoiled.
        let mut knots: Vec<f64> = (0..knot_count)
            .map(|_| (rng.range(-3.0, 3.0) * 4.0).round() / 4.0)
            .collect();
        knots.sort_by(|a, b| a.total_cmp(b));
        if knot_count > 0 && rng.below(3) == 0 {
            let i = rng.below(knot_count);
            knots[i] = garbage(&mut rng);
        }
        let points: Vec<Point2<f64>> = (0..n)
            .map(|_| match rng.below(8) {
                0 => Point2::new(garbage(&mut rng), garbage(&mut rng)),
                _ => Point2::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)),
            })
            .collect();
        let weight_count = if rng.below(6) == 0 { rng.below(8) } else { n };
        let mut weights: Vec<f64> = (0..weight_count)
            .map(|_| 0.01 * 1e4f64.powf(rng.unit()))
            .collect();
        if weight_count > 0 && rng.below(3) == 0 {
            let i = rng.below(weight_count);
            weights[i] = garbage(&mut rng);
        }
        let ts: Vec<f64> = (0..4).map(|_| garbage(&mut rng)).collect();
        let outcome = std::panic::catch_unwind(|| {
            let Ok(c) = Nurbs::new(degree, knots, points, weights) else {
                return false;
            };
            for &t in &ts {
                let (p, d) = c.eval_with_derivative(t);
                assert!(
                    p.iter().chain(d.iter()).all(|x| x.is_finite()),
                    "t {t}: {p} {d}"
                );
                assert_eq!(c.eval(t), p);
                let mut out = [Vector2::zeros(); 4];
                match c.derivatives(t, &mut out) {
                    Ok(()) => assert!(out.iter().all(|v| v.iter().all(|x| x.is_finite()))),
                    Err(Error::DerivativeOverflow { order }) => assert!(order >= 1),
                    Err(e) => panic!("{e}"),
                }
                let _ = c.tangent(t);
                let _ = c.insert_knot(t, 1);
            }
            let _ = c.flatten(1e-3);
            let _ = c.to_bezier_spans();
            true
        });
        accepted += usize::from(outcome.expect("no panic on garbage input"));
    }
    assert!(
        accepted > 2000,
        "only {accepted} accepted: the generator is too harsh"
    );
    for _ in 0..2000 {
        let center = Point2::new(garbage(&mut rng), garbage(&mut rng));
        let (radius, start, end) = (garbage(&mut rng), garbage(&mut rng), garbage(&mut rng));
        std::panic::catch_unwind(|| {
            for c in [
                Nurbs::circle(center, radius),
                Nurbs::arc(center, radius, start, end),
            ]
            .into_iter()
            .flatten()
            {
                for k in 0..=8 {
                    let p = c.eval(k as f64 / 8.0);
                    assert!(p.iter().all(|x| x.is_finite()));
                }
            }
        })
        .expect("no panic on garbage circles");
    }
}

// ------------------------------------------------- finite differences ----

fn random_nurbs_strategy() -> impl Strategy<Value = (u64, f64)> {
    (any::<u64>(), 0.02..0.98f64)
}

/// The check of `derivatives_match_central_differences` for one curve
/// (`seed`) and parameter (`s` of the domain).
fn derivatives_against_differences(seed: u64, s: f64) -> Result<(), TestCaseError> {
    let mut rng = Rng(seed);
    let degree = 1 + rng.below(5);
    let parts = random_parts(&mut rng, degree, 0.2, 5.0);
    let c = parts.nurbs();
    let (a, b) = c.domain();
    let t = a + (b - a) * s;
    let h = 1e-5;
    let near_knot = c.knots().iter().any(|&k| (k - t).abs() < 10.0 * h);
    prop_assume!(!near_knot);
    // Two orders beyond the last compared: the central difference's
    // error is h²/6·C⁽ᵏ⁺²⁾ at a point of [t − h, t + h].
    let mut at = [SVector::<f64, 2>::zeros(); 7];
    let mut plus = at;
    let mut minus = at;
    c.derivatives(t, &mut at).unwrap();
    c.derivatives(t + h, &mut plus).unwrap();
    c.derivatives(t - h, &mut minus).unwrap();
    for k in 1..5 {
        let difference = (plus[k - 1] - minus[k - 1]) / (2.0 * h);
        let scale = at[k].amax() + at[k - 1].amax() + plus[k].amax();
        let truncation =
            h * h / 6.0 * (at[k + 2].amax() + plus[k + 2].amax() + minus[k + 2].amax());
        prop_assert!(
            (difference - at[k]).amax() <= 1e-5 * scale + truncation,
            "order {}: {:?} vs {:?}",
            k,
            at[k],
            difference
        );
    }
    // The Curve methods agree with the derivatives.
    prop_assert!((c.derivative(t) - at[1]).amax() <= 1e-13 * at[1].amax().max(1.0));
    prop_assert!((c.eval(t).coords - at[0]).amax() <= 1e-14 * 10.0);
    Ok(())
}

/// A case whose fourth and fifth derivatives are large (3e8 at order 3):
/// the central difference is off by its truncation error, h²/6·C⁽ᵏ⁺²⁾, which
/// the check allows for.
#[test]
fn derivatives_against_differences_where_higher_ones_are_large() {
    derivatives_against_differences(3573648231465257294, 0.9661337168284572).unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Each derivative against the central difference of the one below it:
    /// `(C⁽ᵏ⁻¹⁾(t + h) − C⁽ᵏ⁻¹⁾(t − h))/2h`, error `O(h²·C⁽ᵏ⁺²⁾)`, away from
    /// the knots (where the derivatives may jump).
    #[test]
    fn derivatives_match_central_differences((seed, s) in random_nurbs_strategy()) {
        derivatives_against_differences(seed, s)?;
    }
}

// ------------------------------------------------------------- arc ends ----

/// Arcs whose ends are at multiples of π/2 end exactly on the axes (a
/// sphere's profile meets the axis exactly at its poles).
#[test]
fn arc_ends_at_quarter_turns_are_exact() {
    use std::f64::consts::{FRAC_PI_2, PI};
    let c = Point2::new(0.25, -2.0);
    let half = Nurbs::arc(c, 1.5, -FRAC_PI_2, FRAC_PI_2).unwrap();
    assert_eq!(half.eval(0.0), Point2::new(0.25, -3.5));
    assert_eq!(half.eval(1.0), Point2::new(0.25, -0.5));
    assert_eq!(half.eval(0.5), Point2::new(1.75, -2.0));
    let upper = Nurbs::arc(Point2::origin(), 2.0, 0.0, PI).unwrap();
    assert_eq!(upper.eval(1.0), Point2::new(-2.0, 0.0));
    let three = Nurbs::arc(Point2::origin(), 1.0, 3.0 * PI, 3.0 * FRAC_PI_2 + 2.0 * PI).unwrap();
    assert_eq!(three.eval(0.0), Point2::new(-1.0, 0.0));
    assert_eq!(three.eval(1.0), Point2::new(0.0, -1.0));
    // Angles off the axes keep their own directions.
    let tilted = Nurbs::arc(Point2::origin(), 1.0, 0.1, 1.0).unwrap();
    assert_eq!(tilted.eval(0.0), Point2::new(0.1f64.cos(), 0.1f64.sin()));
}

//! `RationalBezier`: conics exactly, unit weights as the polynomial curve,
//! derivatives against finite differences and the closed form of the
//! circle, bad input as named errors.

use revolve::curve::MAX_DERIVATIVE_ORDER;
use revolve::nalgebra::{Point2, Point3, Vector2};
use revolve::{Bezier, Curve, Error, RationalBezier};
use std::f64::consts::FRAC_1_SQRT_2;

/// The quarter of the circle of radius `r` from angle 0 to π/2.
fn quarter(r: f64) -> RationalBezier<2> {
    RationalBezier::new(
        vec![Point2::new(r, 0.0), Point2::new(r, r), Point2::new(0.0, r)],
        vec![1.0, FRAC_1_SQRT_2, 1.0],
    )
    .expect("valid arc")
}

/// Every point of the rational quarter circle is on the circle (to a few
/// ulps), its end points are exact, and its derivative is perpendicular to
/// the radius.
#[test]
fn quarter_circle_is_exact() {
    for r in [1e-6, 1.0, 3.5, 1e6] {
        let arc = quarter(r);
        assert_eq!(arc.eval(0.0), Point2::new(r, 0.0));
        assert_eq!(arc.eval(1.0), Point2::new(0.0, r));
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            let (p, d) = arc.eval_with_derivative(t);
            assert!(
                (p.coords.norm() - r).abs() <= 4.0 * f64::EPSILON * r,
                "t {t}"
            );
            assert!(p.coords.dot(&d).abs() <= 1e-14 * r * d.norm());
        }
    }
}

/// The circle's derivatives of the quarter arc against the closed form:
/// with `θ(t)` the angle, `C = r(cos θ, sin θ)`, the first derivative has
/// length `r θ′` and `C″·C = −|C′|²` (the normal part of the acceleration).
/// Checked orders 0–4 against central finite differences of the order
/// below.
#[test]
fn derivatives_agree_with_finite_differences() {
    let arc = quarter(2.0);
    let mut d = [Vector2::zeros(); 5];
    let mut plus = [Vector2::zeros(); 5];
    let mut minus = [Vector2::zeros(); 5];
    let h = 1e-5;
    for k in 1..20 {
        let t = k as f64 / 20.0;
        arc.derivatives(t, &mut d).unwrap();
        arc.derivatives(t + h, &mut plus).unwrap();
        arc.derivatives(t - h, &mut minus).unwrap();
        for order in 1..5 {
            let fd = (plus[order - 1] - minus[order - 1]) / (2.0 * h);
            let size = 1.0 + d[order].norm();
            assert!(
                (fd - d[order]).norm() <= 1e-6 * size,
                "order {order} at {t}: {:?} against {fd:?}",
                d[order]
            );
        }
        assert!((d[2].dot(&d[0]) + d[1].norm_squared()).abs() <= 1e-12 * d[1].norm_squared());
        assert_eq!(arc.nth_derivative(t, 3).unwrap(), d[3]);
    }
}

/// Equal weights give the polynomial Bézier curve of the same points (to
/// rounding), and `bezier_spans` is then `Some`; unequal weights give
/// `None` there but rational spans.
#[test]
fn equal_weights_are_the_polynomial_curve() {
    let points = vec![
        Point3::new(0.0, 0.0, 1.0),
        Point3::new(1.0, 2.0, -1.0),
        Point3::new(3.0, 2.5, 0.5),
        Point3::new(4.0, -1.0, 2.0),
    ];
    let poly = Bezier::new(points.clone()).unwrap();
    let rational = RationalBezier::new(points.clone(), vec![2.5; 4]).unwrap();
    for k in 0..=100 {
        let t = k as f64 / 100.0;
        assert!((poly.eval(t) - rational.eval(t)).norm() <= 1e-14 * 4.0);
        assert!((poly.derivative(t) - rational.derivative(t)).norm() <= 1e-13 * 12.0);
    }
    assert!(rational.bezier_spans().is_some());
    let bent = RationalBezier::new(points, vec![1.0, 3.0, 0.5, 1.0]).unwrap();
    assert!(bent.bezier_spans().is_none());
    let spans = bent.rational_bezier_spans().unwrap();
    assert_eq!(spans.len(), 1);
    assert_eq!(spans[0].curve, bent);
}

/// Bad weights and orders are named errors, never panics.
#[test]
fn bad_input_is_an_error() {
    let pts = || {
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
        ]
    };
    assert!(matches!(
        RationalBezier::new(pts(), vec![1.0, 1.0]),
        Err(Error::WeightCount {
            expected: 3,
            found: 2
        })
    ));
    for (bad, index) in [(0.0, 1), (-1.0, 1), (f64::NAN, 1), (f64::INFINITY, 1)] {
        let got = RationalBezier::new(pts(), vec![1.0, bad, 1.0]);
        assert!(
            matches!(got, Err(Error::InvalidWeight { index: i, .. }) if i == index),
            "{bad}: {got:?}"
        );
    }
    assert!(matches!(
        RationalBezier::new(pts(), vec![1.0, 1e9, 1.0]),
        Err(Error::WeightRatioTooLarge { .. })
    ));
    assert!(matches!(
        RationalBezier::<2>::new(vec![], vec![]),
        Err(Error::NoControlPoints)
    ));
    let arc = quarter(1.0);
    assert!(matches!(
        arc.nth_derivative(0.5, usize::MAX),
        Err(Error::DerivativeOrderTooHigh { .. })
    ));
    // The highest allowed order is finite or the named overflow, never NaN.
    match arc.nth_derivative(0.5, MAX_DERIVATIVE_ORDER) {
        Ok(v) => assert!(v.iter().all(|c| c.is_finite())),
        Err(e) => assert!(matches!(e, Error::DerivativeOverflow { .. }), "{e:?}"),
    }
    // NaN and out-of-domain parameters evaluate at the ends.
    assert_eq!(arc.eval(f64::NAN), Point2::new(1.0, 0.0));
    assert_eq!(arc.eval(7.0), Point2::new(0.0, 1.0));
}

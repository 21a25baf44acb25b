//! Tests of `Nurbs`: against exact rational arithmetic, the B-spline of equal
//! weights, closed forms of circles and arcs, knot insertion, rational Bézier
//! spans, flattening bounds, bad inputs and finite differences.

use revolve::nalgebra::{Point2, Vector2};
use revolve::{BSpline, Curve, Nurbs};
use std::f64::consts::PI;

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

#[test]
fn equal_weights_give_the_bspline() {
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0];
    let spline = BSpline::new(3, knots.clone(), points(7)).unwrap();
    let nurbs = Nurbs::new(3, knots, points(7), vec![2.5; 7]).unwrap();
    let from = Nurbs::from(spline.clone());
    for k in 0..=100 {
        let t = k as f64 / 100.0;
        assert_eq!(nurbs.eval(t), spline.eval(t));
        assert_eq!(from.eval(t), spline.eval(t));
        assert_eq!(nurbs.derivative(t), spline.derivative(t));
        for order in 0..5 {
            let d = nurbs.nth_derivative(t, order).unwrap();
            let e = spline.nth_derivative(t, order);
            assert!(
                (d - e).norm() <= 1e-12 * (1.0 + e.norm()),
                "{t} {order} {d} {e}"
            );
        }
    }
    assert_eq!(nurbs.bezier_spans(), spline.bezier_spans());
}

#[test]
fn circle_points_are_at_radius() {
    let c = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    for k in 0..=1000 {
        let t = k as f64 / 1000.0;
        let (p, d) = c.eval_with_derivative(t);
        assert!(
            (p.coords.norm() - 1.0).abs() <= 4.0 * f64::EPSILON,
            "{t} {p}"
        );
        assert!(p.coords.dot(&d).abs() <= 1e-14 * d.norm(), "{t}");
    }
    for (start, end) in [
        (0.0, 0.1),
        (-1.0, 2.0),
        (0.3, 0.3 + 2.0 * PI),
        (-5.0, -5.0 + PI),
    ] {
        let a = Nurbs::arc(Point2::new(1.0, -2.0), 3.0, start, end).unwrap();
        for k in 0..=1000 {
            let p = a.eval(k as f64 / 1000.0);
            let dist = (p - Point2::new(1.0, -2.0)).norm();
            assert!(
                (dist - 3.0).abs() <= 16.0 * f64::EPSILON * 3.0,
                "{start} {end} {k} {dist}"
            );
        }
        let want = Vector2::new(end.cos(), end.sin()) * 3.0;
        assert!((a.eval(1.0) - Point2::new(1.0, -2.0) - want).norm() < 1e-14);
    }
}

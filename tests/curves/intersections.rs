//! Intersections of planar curves (`revolve::curve::intersect_curves`)
//! against closed forms (circle–line by the quadratic formula, circle–circle
//! by the radical line), a curve against shifted and reversed copies of
//! itself, random Bézier pairs against an independent dense-sampling
//! reference (crossings of fine polylines, refined by Newton's method on
//! the curves), and every error path.
//!
//! Tolerances: certified points within `1e-12` of the closed forms (the
//! inputs are of size 1–3); tangential touches within `1e-5`; the sampled
//! reference's roots within `1e-9` in parameter.

use revolve_testkit as common;

use common::Rng;
use revolve::curve::{CurveIntersection, MIN_INTERSECTION_TOLERANCE, intersect_curves};
use revolve::nalgebra::{Point2, Vector2};
use revolve::{BSpline, Bezier, Curve, Error, Nurbs, RationalBezier, RationalBezierSpan};
use std::time::Instant;

const TOL: f64 = 1e-9;

fn line(a: (f64, f64), b: (f64, f64)) -> Bezier<2> {
    Bezier::new(vec![Point2::new(a.0, a.1), Point2::new(b.0, b.1)]).unwrap()
}

/// Every result lies on both curves at its parameters.
fn check_on_curves(a: &impl Curve<2>, b: &impl Curve<2>, hits: &[CurveIntersection], within: f64) {
    for h in hits {
        let (pa, pb) = (a.eval(h.t_a), b.eval(h.t_b));
        assert!((pa - h.point).norm() <= within, "{h:?}: a at {pa}");
        assert!((pb - h.point).norm() <= within, "{h:?}: b at {pb}");
        assert!(h.point.coords.iter().all(|c| c.is_finite()));
    }
}

/// Matches `hits` to `expected` points (any order): equal counts, each
/// within `within`.
fn assert_points(hits: &[CurveIntersection], expected: &[Point2<f64>], within: f64) {
    assert_eq!(hits.len(), expected.len(), "{hits:?} vs {expected:?}");
    for e in expected {
        let d = hits
            .iter()
            .map(|h| (h.point - e).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(d <= within, "{e} missed by {d}: {hits:?}");
    }
}

#[test]
fn circle_and_horizontal_lines_by_the_quadratic_formula() {
    let (cx, cy, r) = (0.3, -0.2, 1.5);
    let circle = Nurbs::circle(Point2::new(cx, cy), r).unwrap();
    for k in 0..=40 {
        // From well below the circle to well above, avoiding the tangents.
        let y = cy - 1.8 + 3.6 * k as f64 / 40.0;
        let h = y - cy;
        if (h.abs() - r).abs() < 1e-3 {
            continue;
        }
        // A clamped B-spline line (degree 2, two spans) and a Bézier one.
        let bs = BSpline::clamped(
            2,
            vec![
                Point2::new(-3.0, y),
                Point2::new(-0.5, y),
                Point2::new(1.0, y),
                Point2::new(3.0, y),
            ],
        )
        .unwrap();
        let bz = line((-3.0, y), (3.0, y));
        let expected: Vec<Point2<f64>> = if h.abs() < r {
            let dx = (r * r - h * h).sqrt();
            vec![Point2::new(cx - dx, y), Point2::new(cx + dx, y)]
        } else {
            vec![]
        };
        for hits in [
            intersect_curves(&circle, &bs, TOL).unwrap(),
            intersect_curves(&bz, &circle, TOL).unwrap(),
        ] {
            assert_points(&hits, &expected, 1e-12);
            assert!(hits.iter().all(|h| h.certified), "{hits:?}");
        }
        check_on_curves(
            &circle,
            &bs,
            &intersect_curves(&circle, &bs, TOL).unwrap(),
            1e-12,
        );
    }
}

#[test]
fn oblique_lines_through_the_circle() {
    let circle = Nurbs::circle(Point2::new(0.0, 0.0), 2.0).unwrap();
    for k in 0..24 {
        let angle = 0.1 + k as f64 * 0.27;
        let d = Vector2::new(angle.cos(), angle.sin());
        let n = Vector2::new(-d.y, d.x);
        let offset = 1.3 * ((k % 5) as f64 - 2.0) / 2.0;
        let (p, q) = (n * offset - d * 3.0, n * offset + d * 3.0);
        let l = line((p.x, p.y), (q.x, q.y));
        let half = (4.0 - offset * offset).sqrt();
        let expected = [
            Point2::from(n * offset - d * half),
            Point2::from(n * offset + d * half),
        ];
        let hits = intersect_curves(&circle, &l, TOL).unwrap();
        assert_points(&hits, &expected, 1e-12);
        assert!(hits.iter().all(|h| h.certified));
        check_on_curves(&circle, &l, &hits, 1e-12);
    }
}

#[test]
fn lines_through_span_joins_hit_once_each() {
    // The circle's spans join at its quarter points: the axes cross it there.
    let circle = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    let vertical = line((0.0, -2.0), (0.0, 2.0));
    let hits = intersect_curves(&circle, &vertical, TOL).unwrap();
    assert_points(
        &hits,
        &[Point2::new(0.0, -1.0), Point2::new(0.0, 1.0)],
        1e-15,
    );
    assert!(hits.iter().all(|h| h.certified));
    let horizontal = line((-2.0, 0.0), (2.0, 0.0));
    let hits = intersect_curves(&horizontal, &circle, TOL).unwrap();
    assert_points(
        &hits,
        &[Point2::new(-1.0, 0.0), Point2::new(1.0, 0.0)],
        1e-15,
    );
    assert!((hits[0].t_a - 0.25).abs() < 1e-15 && (hits[1].t_a - 0.75).abs() < 1e-15);
}

#[test]
fn tangent_lines_touch_once_uncertified() {
    let circle = Nurbs::circle(Point2::new(0.5, 0.25), 1.0).unwrap();
    for k in 0..8 {
        let angle = 0.3 + k as f64 * 0.8;
        let n = Vector2::new(angle.cos(), angle.sin());
        let d = Vector2::new(-n.y, n.x);
        let touch = Point2::new(0.5, 0.25) + n;
        let (p, q) = (touch - d * 2.0, touch + d * 1.5);
        let l = line((p.x, p.y), (q.x, q.y));
        let hits = intersect_curves(&circle, &l, TOL).unwrap();
        assert_eq!(hits.len(), 1, "{hits:?}");
        assert!(!hits[0].certified);
        assert!(
            (hits[0].point - touch).norm() < 1e-5,
            "{:?} vs {touch}",
            hits[0]
        );
        // Moved off by 1e-3 outward: nothing; inward: two certified hits.
        let out = line(
            ((p + n * 1e-3).x, (p + n * 1e-3).y),
            ((q + n * 1e-3).x, (q + n * 1e-3).y),
        );
        assert!(intersect_curves(&circle, &out, TOL).unwrap().is_empty());
        let inside = line(
            ((p - n * 1e-3).x, (p - n * 1e-3).y),
            ((q - n * 1e-3).x, (q - n * 1e-3).y),
        );
        let two = intersect_curves(&circle, &inside, TOL).unwrap();
        assert_eq!(two.len(), 2);
        assert!(two.iter().all(|h| h.certified));
        check_on_curves(&circle, &inside, &two, 1e-12);
    }
}

#[test]
fn circle_pairs_by_the_radical_line() {
    let (r1, r2) = (1.0, 0.7);
    let a = Nurbs::circle(Point2::new(0.0, 0.0), r1).unwrap();
    for (k, d) in [0.2, 0.35, 0.5, 0.9, 1.2, 1.6, 1.69, 1.71, 2.5]
        .iter()
        .enumerate()
    {
        let angle = 0.4 + k as f64;
        let u = Vector2::new(angle.cos(), angle.sin());
        let b = Nurbs::circle(Point2::from(u * *d), r2).unwrap();
        let hits = intersect_curves(&a, &b, TOL).unwrap();
        // The radical line: at distance x from a's centre, half-chord h.
        let x = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
        let expected: Vec<Point2<f64>> = if *d > r1 - r2 && *d < r1 + r2 {
            let h = (r1 * r1 - x * x).sqrt();
            let v = Vector2::new(-u.y, u.x);
            vec![Point2::from(u * x + v * h), Point2::from(u * x - v * h)]
        } else {
            vec![]
        };
        assert_points(&hits, &expected, 1e-12);
        assert!(hits.iter().all(|h| h.certified));
        check_on_curves(&a, &b, &hits, 1e-12);
    }
}

#[test]
fn tangent_circles_touch_once() {
    let a = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    // Externally tangent at (0.6, 0.8); internally tangent at (-1, 0).
    let outer = Nurbs::circle(Point2::new(1.2, 1.6), 1.0).unwrap();
    let hits = intersect_curves(&a, &outer, TOL).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!((hits[0].point - Point2::new(0.6, 0.8)).norm() < 1e-5);
    let inner = Nurbs::circle(Point2::new(-0.5, 0.0), 0.5).unwrap();
    let hits = intersect_curves(&a, &inner, TOL).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!((hits[0].point - Point2::new(-1.0, 0.0)).norm() < 1e-5);
}

fn s_cubic() -> Bezier<2> {
    Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 2.0),
        Point2::new(2.0, -2.0),
        Point2::new(3.0, 0.5),
    ])
    .unwrap()
}

#[test]
fn a_cubic_and_its_shifted_reparametrized_copy_do_not_meet() {
    let c = s_cubic();
    // x is increasing along the curve: a copy moved up is disjoint.
    for dy in [1e-6, 1e-3, 0.1, 1.0] {
        let copy = Bezier::new(
            c.points()
                .iter()
                .rev()
                .map(|p| p + Vector2::new(0.0, dy))
                .collect(),
        )
        .unwrap();
        let hits = intersect_curves(&c, &copy, TOL).unwrap();
        assert!(hits.is_empty(), "dy = {dy}: {hits:?}");
        // The same curve as a clamped B-spline of two spans (knot inserted).
        let spline = BSpline::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            copy.points().to_vec(),
        )
        .unwrap()
        .insert_knot(0.4, 1)
        .unwrap();
        assert!(intersect_curves(&spline, &c, TOL).unwrap().is_empty());
    }
    // Moved sideways it crosses itself: every result is on both curves.
    let copy = Bezier::new(
        c.points()
            .iter()
            .map(|p| p + Vector2::new(0.4, 0.0))
            .collect(),
    )
    .unwrap();
    let hits = intersect_curves(&c, &copy, TOL).unwrap();
    assert!(!hits.is_empty());
    check_on_curves(&c, &copy, &hits, 1e-12);
}

#[test]
fn coincident_curves_are_an_overlap_error() {
    let c = s_cubic();
    let started = Instant::now();
    let err = intersect_curves(&c, &c.reversed(), TOL).unwrap_err();
    assert!(matches!(err, Error::CurvesOverlap { .. }), "{err}");
    assert!(err.to_string().contains("overlap"));
    let circle = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    let arc = Nurbs::arc(Point2::new(0.0, 0.0), 1.0, 0.5, 2.0).unwrap();
    let err = intersect_curves(&circle, &arc, TOL).unwrap_err();
    match err {
        Error::CurvesOverlap { a, b } => {
            assert!(a.0 <= a.1 && b.0 <= b.1);
            assert!(a.0 >= 0.0 && a.1 <= 1.0);
        }
        e => panic!("{e}"),
    }
    assert!(started.elapsed().as_secs_f64() < 20.0);
}

#[test]
fn shared_end_points_are_one_hit() {
    let a = line((0.0, 0.0), (1.0, 1.0));
    let b = line((1.0, 1.0), (2.0, 0.0));
    let hits = intersect_curves(&a, &b, TOL).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(hits[0].certified && (hits[0].point - Point2::new(1.0, 1.0)).norm() < 1e-15);
    assert!((hits[0].t_a - 1.0).abs() < 1e-15 && hits[0].t_b.abs() < 1e-15);
}

#[test]
fn rational_spans_and_far_coordinates() {
    // The same circle–line configuration moved far from the origin and
    // scaled small: the same answers, scaled.
    for (shift, scale) in [(0.0, 1.0), (1e6, 1.0), (0.0, 1e-200), (0.0, 1e90)] {
        let c = Point2::new(shift, shift);
        let circle = Nurbs::circle(c, 2.0 * scale).unwrap();
        let l = line(
            (shift - 3.0 * scale, shift + scale),
            (shift + 3.0 * scale, shift + scale),
        );
        let hits = intersect_curves(&circle, &l, 1e-9 * (shift + 3.0 * scale)).unwrap();
        let dx = 3f64.sqrt() * scale;
        let want = [
            Point2::new(shift - dx, shift + scale),
            Point2::new(shift + dx, shift + scale),
        ];
        let size = shift.abs() + 3.0 * scale;
        assert_points(&hits, &want, 1e-14 * size);
        assert!(hits.iter().all(|h| h.certified));
    }
}

/// Reference intersections: crossings of the polylines through `n + 1`
/// samples of each curve, refined by Newton's method on `a(s) − b(t)`.
fn sampled_reference(a: &Bezier<2>, b: &Bezier<2>, n: usize) -> Vec<(f64, f64)> {
    let pa: Vec<Point2<f64>> = (0..=n).map(|i| a.eval(i as f64 / n as f64)).collect();
    let pb: Vec<Point2<f64>> = (0..=n).map(|i| b.eval(i as f64 / n as f64)).collect();
    let cross = |u: Vector2<f64>, v: Vector2<f64>| u.x * v.y - u.y * v.x;
    let mut roots: Vec<(f64, f64)> = Vec::new();
    for i in 0..n {
        let (p0, p1) = (pa[i], pa[i + 1]);
        for j in 0..n {
            let (q0, q1) = (pb[j], pb[j + 1]);
            // Signed distances of one segment's ends from the other's line.
            let d = p1 - p0;
            let e = q1 - q0;
            let (s0, s1) = (cross(d, q0 - p0), cross(d, q1 - p0));
            let (r0, r1) = (cross(e, p0 - q0), cross(e, p1 - q0));
            if s0 * s1 > 0.0 || r0 * r1 > 0.0 {
                continue;
            }
            let (mut s, mut t) = (
                (i as f64 + r0 / (r0 - r1).clamp(f64::MIN, f64::MAX)) / n as f64,
                (j as f64 + s0 / (s0 - s1)) / n as f64,
            );
            if !s.is_finite() || !t.is_finite() {
                continue;
            }
            for _ in 0..50 {
                let (f, da) = a.eval_with_derivative(s);
                let (g, db) = b.eval_with_derivative(t);
                let r = f - g;
                let det = cross(da, -db);
                if det == 0.0 {
                    break;
                }
                let ds = cross(-r, -db) / det;
                let dt = cross(da, -r) / det;
                s = (s + ds).clamp(0.0, 1.0);
                t = (t + dt).clamp(0.0, 1.0);
            }
            if (a.eval(s) - b.eval(t)).norm() < 1e-12
                && !roots
                    .iter()
                    .any(|r| (r.0 - s).abs() < 1e-7 && (r.1 - t).abs() < 1e-7)
            {
                roots.push((s, t));
            }
        }
    }
    roots.sort_by(|x, y| x.0.total_cmp(&y.0));
    roots
}

#[test]
fn random_bezier_pairs_against_dense_sampling() {
    let mut rng = Rng(0x1234_5678);
    let mut compared = 0;
    let mut total_time = 0.0;
    let mut pairs = 0;
    for case in 0..60 {
        let degree = |rng: &mut Rng| 1 + rng.below(5);
        let (da, db) = (degree(&mut rng), degree(&mut rng));
        let pts = |rng: &mut Rng, d: usize| -> Vec<Point2<f64>> {
            (0..=d)
                .map(|_| Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
                .collect()
        };
        let a = Bezier::new(pts(&mut rng, da)).unwrap();
        let b = Bezier::new(pts(&mut rng, db)).unwrap();
        let started = Instant::now();
        let hits = intersect_curves(&a, &b, TOL).unwrap();
        total_time += started.elapsed().as_secs_f64();
        pairs += 1;
        let reference = sampled_reference(&a, &b, 600);
        // Skip configurations the sampled reference cannot resolve: roots
        // closer than 1e-3 in parameter, or crossing at a tiny angle.
        let cross =
            |u: Vector2<f64>, v: Vector2<f64>| (u.x * v.y - u.y * v.x) / (u.norm() * v.norm());
        let hard = reference.windows(2).any(|w| (w[0].0 - w[1].0).abs() < 1e-3)
            || reference
                .iter()
                .any(|r| cross(a.derivative(r.0), b.derivative(r.1)).abs() < 1e-3)
            || hits.iter().any(|h| !h.certified);
        if hard {
            continue;
        }
        compared += 1;
        assert_eq!(
            hits.len(),
            reference.len(),
            "case {case}: {hits:?} vs {reference:?}"
        );
        for (h, r) in hits.iter().zip(&reference) {
            assert!(
                (h.t_a - r.0).abs() < 1e-9 && (h.t_b - r.1).abs() < 1e-9,
                "case {case}: {h:?} vs {r:?}"
            );
        }
        check_on_curves(&a, &b, &hits, 1e-12);
    }
    assert!(compared >= 45, "only {compared} cases compared");
    eprintln!(
        "random Bézier pairs: {:.1} µs per pair",
        1e6 * total_time / pairs as f64
    );
}

#[test]
fn rational_bezier_pairs_cross_where_both_curves_are() {
    let mut rng = Rng(99);
    for _ in 0..30 {
        let pts: Vec<Point2<f64>> = (0..4)
            .map(|_| Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
            .collect();
        let w: Vec<f64> = (0..4).map(|_| rng.range(0.2, 5.0)).collect();
        let a = RationalBezier::new(pts, w).unwrap();
        let b = s_cubic();
        let hits = intersect_curves(&a, &b, TOL).unwrap();
        for h in hits.iter().filter(|h| h.certified) {
            assert!((a.eval(h.t_a) - b.eval(h.t_b)).norm() < 1e-12, "{h:?}");
        }
        check_on_curves(&a, &b, &hits, 1e-6);
    }
}

/// A curve known only by its formula (no spans).
struct Parabola;
impl Curve<2> for Parabola {
    fn domain(&self) -> (f64, f64) {
        (-1.0, 1.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let t = t.clamp(-1.0, 1.0);
        Point2::new(t, t * t)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        Vector2::new(1.0, 2.0 * t.clamp(-1.0, 1.0))
    }
}

/// A curve whose spans break their contract.
struct BadSpans(Vec<RationalBezierSpan<2>>);
impl Curve<2> for BadSpans {
    fn domain(&self) -> (f64, f64) {
        (0.0, 2.0)
    }
    fn eval(&self, _: f64) -> Point2<f64> {
        Point2::origin()
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::zeros()
    }
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<2>>> {
        Some(self.0.clone())
    }
}

#[test]
fn every_error_path() {
    let circle = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    let l = line((-2.0, 0.0), (2.0, 0.0));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            intersect_curves(&circle, &l, bad),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    let err = intersect_curves(&circle, &l, 1e-12).unwrap_err();
    match err {
        Error::ToleranceTooSmall { min, .. } => {
            assert!((min - 2.0 * MIN_INTERSECTION_TOLERANCE).abs() < 1e-25)
        }
        e => panic!("{e}"),
    }
    assert_eq!(
        intersect_curves(&Parabola, &l, TOL),
        Err(Error::NotPiecewiseRational)
    );
    assert_eq!(
        intersect_curves(&l, &Parabola, TOL),
        Err(Error::NotPiecewiseRational)
    );
    let span = |a: f64, b: f64| RationalBezierSpan {
        knots: (a, b),
        curve: RationalBezier::from(line((0.0, -1.0), (0.0, 1.0))),
    };
    let out_of_order = BadSpans(vec![span(1.0, 2.0), span(0.0, 1.0)]);
    assert_eq!(
        intersect_curves(&out_of_order, &l, TOL),
        Err(Error::SpansOutOfOrder { index: 1 })
    );
    assert_eq!(
        intersect_curves(&l, &BadSpans(vec![]), TOL),
        Err(Error::SpansOutOfOrder { index: 0 })
    );
    // Degree 150 against degree 150 (a constant curve, so that its
    // derivatives stay finite): 151² products, more than accepted.
    let high: Vec<Point2<f64>> = vec![Point2::new(0.5, 0.5); 151];
    let high = Bezier::new(high).unwrap();
    let err = intersect_curves(&high, &high, TOL).unwrap_err();
    assert!(
        matches!(
            err,
            Error::IntersectionTooLarge {
                coefficients: 22801,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("degrees are too high"));
}

#[test]
fn degenerate_curves_never_panic() {
    let point = Bezier::new(vec![Point2::new(0.5, 0.0)]).unwrap();
    let l = line((0.0, 0.0), (1.0, 0.0));
    let hits = intersect_curves(&point, &l, TOL).unwrap();
    assert_eq!(hits.len(), 1);
    assert!((hits[0].point - Point2::new(0.5, 0.0)).norm() < 1e-9);
    let off = Bezier::new(vec![Point2::new(0.5, 0.1)]).unwrap();
    assert!(intersect_curves(&off, &l, TOL).unwrap().is_empty());
    // Repeated control points (a zero derivative at the ends).
    let cusp = Bezier::new(vec![
        Point2::new(0.0, -1.0),
        Point2::new(0.0, -1.0),
        Point2::new(0.0, 1.0),
        Point2::new(0.0, 1.0),
    ])
    .unwrap();
    let across = line((-1.0, 0.25), (1.0, 0.25));
    let hits = intersect_curves(&cusp, &across, TOL).unwrap();
    assert_points(&hits, &[Point2::new(0.0, 0.25)], 1e-14);
}

#[test]
fn random_rational_pairs_never_panic_and_certified_results_are_true() {
    let mut rng = Rng(0xfeed);
    let started = Instant::now();
    for case in 0..80 {
        let curve = |rng: &mut Rng| {
            let d = 1 + rng.below(6);
            let pts: Vec<Point2<f64>> = (0..=d)
                .map(|_| Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
                .collect();
            // Log-uniform weights in [1e-3, 1e3].
            let w: Vec<f64> = (0..=d).map(|_| rng.range(-6.9, 6.9).exp()).collect();
            RationalBezier::new(pts, w).unwrap()
        };
        let (a, b) = (curve(&mut rng), curve(&mut rng));
        let hits = intersect_curves(&a, &b, TOL).unwrap();
        for h in &hits {
            assert!(h.t_a.is_finite() && h.t_b.is_finite(), "case {case}: {h:?}");
            assert!((0.0..=1.0).contains(&h.t_a) && (0.0..=1.0).contains(&h.t_b));
            let gap = (a.eval(h.t_a) - b.eval(h.t_b)).norm();
            if h.certified {
                assert!(gap < 1e-12, "case {case}: {h:?} gap {gap}");
            } else {
                assert!(gap < 1e-6, "case {case}: {h:?} gap {gap}");
            }
        }
    }
    assert!(started.elapsed().as_secs_f64() < 20.0);
}

#[test]
fn near_coincident_curves_finish_quickly() {
    let c = s_cubic();
    for dy in [1e-13, 1e-10, 1e-8, 1e-6] {
        let copy = Bezier::new(
            c.points()
                .iter()
                .map(|p| p + Vector2::new(0.0, dy))
                .collect(),
        )
        .unwrap();
        let started = Instant::now();
        let result = intersect_curves(&c, &copy, TOL);
        let elapsed = started.elapsed().as_secs_f64();
        match result {
            // Within the tolerance: an overlap.
            Err(Error::CurvesOverlap { .. }) => assert!(dy < TOL, "dy = {dy}"),
            Ok(hits) => assert!(hits.is_empty() && dy > TOL, "dy = {dy}: {hits:?}"),
            Err(e) => panic!("dy = {dy}: {e}"),
        }
        assert!(elapsed < 10.0, "dy = {dy}: {elapsed} s");
        eprintln!("copy moved by {dy:e}: {:.2} ms", 1e3 * elapsed);
    }
}

#[test]
fn many_crossings_of_a_wave_and_a_line() {
    // A clamped cubic B-spline zig-zag crossing y = 0 between each pair of
    // control points of opposite sign: every crossing found, certified.
    let n = 40;
    let pts: Vec<Point2<f64>> = (0..n)
        .map(|i| Point2::new(i as f64 / 4.0, if i % 2 == 0 { 1.0 } else { -1.0 }))
        .collect();
    let wave = BSpline::clamped(3, pts).unwrap();
    let axis = line((-1.0, 0.0), (11.0, 0.0));
    let started = Instant::now();
    let hits = intersect_curves(&wave, &axis, 1e-8).unwrap();
    let elapsed = started.elapsed().as_secs_f64();
    assert!(hits.len() >= n - 3, "{}", hits.len());
    assert!(hits.iter().all(|h| h.certified && h.point.y.abs() < 1e-14));
    // The sign of y alternates between consecutive crossings.
    for w in hits.windows(2) {
        let mid = wave.eval(0.5 * (w[0].t_a + w[1].t_a));
        assert!(mid.y.abs() > 1e-3);
    }
    eprintln!(
        "{} crossings of a 37-span wave: {:.2} ms",
        hits.len(),
        1e3 * elapsed
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 128, ..Default::default() })]

    /// A random line segment against a random circle: the hits are the
    /// quadratic formula's roots inside the segment (configurations within
    /// 1e-6 of a tangency or of a segment end are left out).
    #[test]
    fn segments_against_circles_match_the_quadratic_formula(
        cx in -2.0..2.0f64, cy in -2.0..2.0f64, r in 0.1..3.0f64,
        px in -4.0..4.0f64, py in -4.0..4.0f64, qx in -4.0..4.0f64, qy in -4.0..4.0f64,
    ) {
        let (p, q) = (Point2::new(px, py), Point2::new(qx, qy));
        proptest::prop_assume!((q - p).norm() > 1e-3);
        let circle = Nurbs::circle(Point2::new(cx, cy), r).unwrap();
        let seg = line((px, py), (qx, qy));
        // |p + s(q − p) − c|² = r²: a s² + b s + k = 0.
        let d = q - p;
        let f = p - Point2::new(cx, cy);
        let (a, b, k) = (d.norm_squared(), 2.0 * f.dot(&d), f.norm_squared() - r * r);
        let disc = b * b - 4.0 * a * k;
        proptest::prop_assume!(disc.abs() > 1e-6);
        let mut roots = Vec::new();
        if disc > 0.0 {
            for s in [(-b - disc.sqrt()) / (2.0 * a), (-b + disc.sqrt()) / (2.0 * a)] {
                proptest::prop_assume!((s.abs() > 1e-6) && ((s - 1.0).abs() > 1e-6));
                if (0.0..=1.0).contains(&s) {
                    roots.push(p + d * s);
                }
            }
        }
        let hits = intersect_curves(&circle, &seg, TOL).unwrap();
        assert_points(&hits, &roots, 1e-11);
        proptest::prop_assert!(hits.iter().all(|h| h.certified));
    }
}

/// Samples the reported stretch of `a` and checks that every sample lies
/// within the tolerance of `b` (an independent check by nearest points).
fn assert_stretch_within(a: &impl Curve<2>, b: &impl Curve<2>, range: (f64, f64), within: f64) {
    let on_b = revolve::curve::CurveProjector::new(b).unwrap();
    assert!(range.0 < range.1, "{range:?}");
    for k in 0..=64 {
        let t = range.0 + (range.1 - range.0) * k as f64 / 64.0;
        let near = on_b.nearest(&a.eval(t)).unwrap();
        assert!(
            near.distance <= within,
            "a({t}) is {} from b",
            near.distance
        );
    }
}

#[test]
fn copies_of_a_curve_are_an_overlap_found_early() {
    // The same arc in other forms: knots inserted, reversed, moved by a
    // third of the tolerance, raised in degree, a part of a circle. Each is
    // an overlap; the reported stretch lies within the tolerance of the
    // other curve, sample by sample.
    let pts: Vec<Point2<f64>> = (0..12)
        .map(|i| Point2::new(i as f64 * 0.3, ((i * 7) % 5) as f64 * 0.2))
        .collect();
    let spline = BSpline::clamped(3, pts.clone()).unwrap();
    let refined = spline
        .insert_knot(0.37, 1)
        .unwrap()
        .insert_knot(0.81, 2)
        .unwrap();
    let moved = BSpline::clamped(
        3,
        pts.iter()
            .map(|p| p + Vector2::new(0.0, TOL / 3.0))
            .collect(),
    )
    .unwrap();
    let raised = spline.elevate_degree(1).unwrap();
    type Case = (&'static str, Box<dyn Curve<2>>, Box<dyn Curve<2>>);
    let cases: Vec<Case> = vec![
        (
            "knots inserted",
            Box::new(spline.clone()),
            Box::new(refined),
        ),
        (
            "reversed",
            Box::new(spline.clone()),
            Box::new(spline.reversed()),
        ),
        ("moved", Box::new(spline.clone()), Box::new(moved)),
        ("raised", Box::new(spline.clone()), Box::new(raised)),
        (
            "arc of the circle",
            Box::new(Nurbs::circle(Point2::new(0.5, -0.25), 2.0).unwrap()),
            Box::new(Nurbs::arc(Point2::new(0.5, -0.25), 2.0, 0.5, 2.0).unwrap()),
        ),
    ];
    for (name, a, b) in &cases {
        let started = Instant::now();
        let err = intersect_curves(a, b, TOL).unwrap_err();
        let elapsed = started.elapsed().as_secs_f64();
        let Error::CurvesOverlap { a: ra, b: rb } = err else {
            panic!("{name}: {err}");
        };
        assert_stretch_within(a, b, ra, TOL);
        assert_stretch_within(b, a, rb, TOL);
        eprintln!("{name}: overlap {ra:?} / {rb:?} in {:.2} ms", 1e3 * elapsed);
        assert!(elapsed < 10.0, "{name}: {elapsed} s");
    }
}

#[test]
fn concentric_circles_apart_by_twice_the_tolerance_do_not_overlap() {
    // A gap of 2·TOL everywhere: no common point and no overlap; a gap of
    // TOL/3: an overlap.
    let c = Point2::new(0.25, 0.5);
    let inner = Nurbs::circle(c, 1.0).unwrap();
    let outer = Nurbs::circle(c, 1.0 + 2.0 * TOL).unwrap();
    let hits = intersect_curves(&inner, &outer, TOL).unwrap();
    assert!(hits.is_empty(), "{hits:?}");
    let close = Nurbs::circle(c, 1.0 + TOL / 3.0).unwrap();
    let err = intersect_curves(&inner, &close, TOL).unwrap_err();
    assert!(matches!(err, Error::CurvesOverlap { .. }), "{err}");
}

//! Curve queries: the nearest point (certified global) and the arc length
//! (a rigorous bracket and an estimated error), against independent
//! references: dense sampling with local refinement, closed forms (lines,
//! circles, parabolas), and composite Gauss–Legendre quadrature written
//! here.

use revolve_testkit as common;

use common::Rng;
use revolve::nalgebra::{Point, Point2, Point3, Vector2};
use revolve::{
    BSpline, Bezier, Curve, CurveProjector, Error, NearestPoint, RationalBezier, RationalBezierSpan,
};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

fn random_points<const D: usize>(rng: &mut Rng, count: usize) -> Vec<Point<f64, D>> {
    (0..count)
        .map(|_| Point::from(std::array::from_fn(|_| rng.range(-1.0, 1.0))))
        .collect()
}

/// Log-uniform weights in `[0.05, 20]`.
fn random_weights(rng: &mut Rng, count: usize) -> Vec<f64> {
    (0..count)
        .map(|_| rng.range(0.05_f64.ln(), 20.0_f64.ln()).exp())
        .collect()
}

/// The nearest point by brute force: `10⁵` uniform samples, then golden
/// section on the neighbourhood of every sampled local minimum within 1% of
/// the best sample. Returns `(t, distance)`.
fn dense_nearest<const D: usize>(curve: &impl Curve<D>, p: &Point<f64, D>) -> (f64, f64) {
    const N: usize = 100_000;
    let (a, b) = curve.domain();
    let t_at = |i: usize| a + (b - a) * i as f64 / N as f64;
    let dist = |t: f64| (curve.eval(t) - p).norm();
    let d: Vec<f64> = (0..=N).map(|i| dist(t_at(i))).collect();
    let best_sample = d.iter().cloned().fold(f64::INFINITY, f64::min);
    let mut best = (a, dist(a));
    for i in 0..=N {
        let local = (i == 0 || d[i] <= d[i - 1]) && (i == N || d[i] <= d[i + 1]);
        if !local || d[i] > best_sample * 1.01 + 1e-300 {
            continue;
        }
        let (mut lo, mut hi) = (t_at(i.saturating_sub(1)), t_at((i + 1).min(N)));
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..120 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if dist(x1) <= dist(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        for t in [lo, hi, t_at(i)] {
            if dist(t) < best.1 {
                best = (t, dist(t));
            }
        }
    }
    best
}

/// The largest coordinate magnitude of the points and the query point.
fn scale<const D: usize>(points: &[Point<f64, D>], p: &Point<f64, D>) -> f64 {
    points
        .iter()
        .fold(p.coords.amax(), |m, q| m.max(q.coords.amax()))
}

/// Checks a certified answer: in the domain, the point is the curve's at
/// `t` and at the stated distance, and no dense sample (refined) is nearer
/// than rounding allows (`16ε` of the scale; the worst seen is about `1.5ε`).
fn check_nearest<const D: usize>(
    curve: &impl Curve<D>,
    p: &Point<f64, D>,
    near: &NearestPoint<D>,
    scale: f64,
    what: &str,
) {
    let (a, b) = curve.domain();
    assert!(near.certified, "{what}");
    assert!(near.t >= a && near.t <= b, "{what}: t = {} outside", near.t);
    assert!(
        (curve.eval(near.t) - near.point).norm() <= 1e-14 * scale,
        "{what}: point is not C(t)"
    );
    assert!(((near.point - p).norm() - near.distance).abs() <= 1e-15 * scale);
    let (t_ref, d_ref) = dense_nearest(curve, p);
    assert!(
        near.distance <= d_ref + 16.0 * f64::EPSILON * scale,
        "{what}: distance {:e} at t = {}, but {:e} at t = {t_ref}",
        near.distance,
        near.t,
        d_ref
    );
}

/// A full circle as four rational quarter arcs, on the parameter `[0, 4]`:
/// a user's curve type that provides rational spans.
struct Circle {
    quarters: Vec<RationalBezier<2>>,
}

impl Circle {
    fn new(center: Point2<f64>, r: f64) -> Self {
        let quarters = (0..4)
            .map(|k| {
                let turn = |v: Vector2<f64>| match k {
                    0 => v,
                    1 => Vector2::new(-v.y, v.x),
                    2 => -v,
                    _ => Vector2::new(v.y, -v.x),
                };
                let pts = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                    .map(|(x, y)| center + turn(Vector2::new(x, y)) * r);
                RationalBezier::new(pts.to_vec(), vec![1.0, FRAC_1_SQRT_2, 1.0]).unwrap()
            })
            .collect();
        Circle { quarters }
    }

    fn piece(&self, t: f64) -> (usize, f64) {
        let t = if t >= 0.0 { t.min(4.0) } else { 0.0 };
        let k = (t as usize).min(3);
        (k, t - k as f64)
    }
}

impl Curve<2> for Circle {
    fn domain(&self) -> (f64, f64) {
        (0.0, 4.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let (k, s) = self.piece(t);
        self.quarters[k].eval(s)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        let (k, s) = self.piece(t);
        self.quarters[k].derivative(s)
    }
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<2>>> {
        Some(
            self.quarters
                .iter()
                .enumerate()
                .map(|(k, q)| RationalBezierSpan {
                    knots: (k as f64, k as f64 + 1.0),
                    curve: q.clone(),
                })
                .collect(),
        )
    }
}

/// A circular arc of radius `r` on `[0, θ]`, analytic: a user's curve
/// without spans.
struct Arc {
    r: f64,
    theta: f64,
}

impl Curve<2> for Arc {
    fn domain(&self) -> (f64, f64) {
        (0.0, self.theta)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let t = if t >= 0.0 { t.min(self.theta) } else { 0.0 };
        Point2::new(self.r * t.cos(), self.r * t.sin())
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        let t = if t >= 0.0 { t.min(self.theta) } else { 0.0 };
        Vector2::new(-self.r * t.sin(), self.r * t.cos())
    }
}

/// A rational quadratic arc of radius `r` from angle 0 to `θ < π`
/// (middle point at the tangents' intersection, weight `cos(θ/2)`).
fn rational_arc(r: f64, theta: f64) -> RationalBezier<2> {
    let h = (0.5 * theta).tan();
    RationalBezier::new(
        vec![
            Point2::new(r, 0.0),
            Point2::new(r, r * h),
            Point2::new(r * theta.cos(), r * theta.sin()),
        ],
        vec![1.0, (0.5 * theta).cos(), 1.0],
    )
    .unwrap()
}

// ---------------------------------------------------------------------------
// Nearest point
// ---------------------------------------------------------------------------

/// Random Béziers of degrees 1–7 in 2D and 3D, query points near, far and
/// on the curve: dense sampling never beats the certified answer.
#[test]
fn nearest_point_on_random_beziers_is_never_beaten() {
    let mut rng = Rng(0x9EA7);
    for case in 0..60 {
        let degree = 1 + case % 7;
        let pts = random_points::<2>(&mut rng, degree + 1);
        let curve = Bezier::new(pts.clone()).unwrap();
        let far = [1.0, 2.0, 30.0][case % 3];
        let p = Point2::new(rng.range(-far, far), rng.range(-far, far));
        let near = curve.nearest_point(&p).unwrap();
        check_nearest(
            &curve,
            &p,
            &near,
            scale(&pts, &p),
            &format!("2D degree {degree}"),
        );

        let pts3 = random_points::<3>(&mut rng, degree + 1);
        let curve3 = Bezier::new(pts3.clone()).unwrap();
        let p3 = Point3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        let near3 = curve3.nearest_point(&p3).unwrap();
        check_nearest(
            &curve3,
            &p3,
            &near3,
            scale(&pts3, &p3),
            &format!("3D degree {degree}"),
        );
    }
}

#[test]
fn nearest_point_on_random_splines_and_rational_curves() {
    let mut rng = Rng(0x5A11);
    for case in 0..30 {
        let pts = random_points::<2>(&mut rng, 6 + case % 8);
        let spline = if case % 2 == 0 {
            BSpline::clamped(3, pts.clone()).unwrap()
        } else {
            BSpline::uniform(2 + case % 3, pts.clone()).unwrap()
        };
        let p = Point2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5));
        let near = spline.nearest_point(&p).unwrap();
        check_nearest(
            &spline,
            &p,
            &near,
            scale(&pts, &p),
            &format!("spline {case}"),
        );

        let degree = 1 + case % 7;
        let pts = random_points::<2>(&mut rng, degree + 1);
        let rational =
            RationalBezier::new(pts.clone(), random_weights(&mut rng, degree + 1)).unwrap();
        let p = Point2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5));
        let near = rational.nearest_point(&p).unwrap();
        check_nearest(
            &rational,
            &p,
            &near,
            scale(&pts, &p),
            &format!("rational {case}"),
        );
    }
}

/// High degrees: the condition polynomial has degree `2n − 1` (39 for
/// `n = 20`, the degree the hard cases of DESIGN.md §5 go up to) or
/// `3n − 2` for rational curves.
#[test]
fn nearest_point_at_high_degree() {
    let mut rng = Rng(0x41);
    for degree in [10, 15, 20] {
        for _ in 0..3 {
            let pts = random_points::<2>(&mut rng, degree + 1);
            let p = Point2::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5));
            let curve = Bezier::new(pts.clone()).unwrap();
            let near = curve.nearest_point(&p).unwrap();
            check_nearest(
                &curve,
                &p,
                &near,
                scale(&pts, &p),
                &format!("degree {degree}"),
            );
            let weights = random_weights(&mut rng, degree + 1);
            let rational = RationalBezier::new(pts.clone(), weights).unwrap();
            let near = rational.nearest_point(&p).unwrap();
            let what = format!("rational degree {degree}");
            check_nearest(&rational, &p, &near, scale(&pts, &p), &what);
        }
    }
}

/// Curves with many local minima of the distance: a zigzag Bézier of degree
/// 12 seen from above its middle (every crest is a local minimum), and a
/// B-spline spiral around the query point (every turn is one). A local
/// method started anywhere else would stop at the wrong one.
#[test]
fn nearest_point_with_several_local_minima() {
    let zigzag: Vec<Point2<f64>> = (0..=12)
        .map(|i| Point2::new(i as f64 / 12.0, if i % 2 == 0 { 0.0 } else { 1.0 }))
        .collect();
    let curve = Bezier::new(zigzag.clone()).unwrap();
    let mut rng = Rng(3);
    for _ in 0..10 {
        let p = Point2::new(rng.range(0.3, 0.7), rng.range(0.6, 3.0));
        let near = curve.nearest_point(&p).unwrap();
        check_nearest(&curve, &p, &near, scale(&zigzag, &p), "zigzag");
    }
    let spiral: Vec<Point2<f64>> = (0..40)
        .map(|i| {
            let a = i as f64 * 0.7;
            let r = 1.0 + 0.02 * i as f64;
            Point2::new(r * a.cos(), r * a.sin())
        })
        .collect();
    let spline = BSpline::clamped(3, spiral.clone()).unwrap();
    for _ in 0..6 {
        let p = Point2::new(rng.range(-0.1, 0.1), rng.range(-0.1, 0.1));
        let near = spline.nearest_point(&p).unwrap();
        check_nearest(&spline, &p, &near, scale(&spiral, &p), "spiral");
    }
}

/// Points on the curve are found at distance zero (to rounding); points at
/// a centre of curvature (a double root of the condition) are handled.
#[test]
fn nearest_point_on_the_curve_and_at_centres_of_curvature() {
    let mut rng = Rng(0xC0C0);
    for case in 0..40 {
        let degree = 2 + case % 5;
        let pts = random_points::<2>(&mut rng, degree + 1);
        let curve = Bezier::new(pts.clone()).unwrap();
        let t0 = rng.range(0.05, 0.95);
        let on = curve.eval(t0);
        let near = curve.nearest_point(&on).unwrap();
        assert!(
            near.distance <= 1e-15 * scale(&pts, &on),
            "degree {degree}: on-curve point at distance {:e}",
            near.distance
        );
        // The centre of curvature at t0: C + n/κ.
        let (d1, d2) = (
            curve.nth_derivative(t0, 1).unwrap(),
            curve.nth_derivative(t0, 2).unwrap(),
        );
        let cross = d1.x * d2.y - d1.y * d2.x;
        if cross.abs() < 1e-3 {
            continue;
        }
        let normal = Vector2::new(-d1.y, d1.x) * (d1.norm_squared() / cross);
        let centre = on + normal;
        if centre.coords.amax() > 20.0 {
            continue;
        }
        let near = curve.nearest_point(&centre).unwrap();
        check_nearest(
            &curve,
            &centre,
            &near,
            scale(&pts, &centre),
            "centre of curvature",
        );
    }
}

/// From the centre of a circle every point is nearest: any answer at the
/// radius is right; near the centre the answer is on the ray through it.
#[test]
fn nearest_point_at_the_centre_of_circles() {
    for (cx, cy, r) in [
        (0.0, 0.0, 1.0),
        (3.0, -2.0, 0.5),
        (1e3, 1e3, 1e-2),
        (0.0, 0.0, 1e4),
    ] {
        let centre = Point2::new(cx, cy);
        let circle = Circle::new(centre, r);
        let near = circle.nearest_point(&centre).unwrap();
        assert!(near.certified);
        let scale = centre.coords.amax().max(r);
        assert!(
            (near.distance - r).abs() <= 4.0 * f64::EPSILON * scale,
            "r={r}: distance {}",
            near.distance
        );
        assert!(((near.point - centre).norm() - r).abs() <= 4.0 * f64::EPSILON * scale);
        // Slightly off the centre, by δ towards angle φ: the nearest point
        // is at angle φ, at distance r − δ. The circle itself is known to
        // η = 8ε·scale (its control points' rounding), so angles within
        // √(4η/δ) of φ are as near to rounding: the answer is that close.
        let eta = 8.0 * f64::EPSILON * scale;
        for phi in [0.3_f64, 2.0, 4.0, 5.9] {
            let delta = 1e-3 * r;
            let p = centre + Vector2::new(phi.cos(), phi.sin()) * delta;
            let near = circle.nearest_point(&p).unwrap();
            assert!(
                near.distance <= r - delta + eta,
                "r={r}, φ={phi}: {} > {}",
                near.distance,
                r - delta
            );
            let want = centre + Vector2::new(phi.cos(), phi.sin()) * r;
            let angle = (4.0 * eta / delta).sqrt();
            assert!(
                (near.point - want).norm() <= 2.0 * r * angle,
                "r={r}, φ={phi}: {} from the answer",
                (near.point - want).norm()
            );
        }
    }
    // One rational quarter: the same at its centre.
    let quarter = rational_arc(2.0, FRAC_PI_2);
    let near = quarter.nearest_point(&Point2::origin()).unwrap();
    assert!((near.distance - 2.0).abs() <= 4.0 * f64::EPSILON * 2.0);
}

/// Query points far away (a thousand times the curve's size) and the
/// projector used for many queries give the same answers as the method.
#[test]
fn projector_and_far_points() {
    let mut rng = Rng(99);
    let pts = random_points::<3>(&mut rng, 9);
    let spline = BSpline::clamped(3, pts.clone()).unwrap();
    let projector = CurveProjector::new(&spline).unwrap();
    for _ in 0..20 {
        let p = Point3::new(
            rng.range(-1e3, 1e3),
            rng.range(-1e3, 1e3),
            rng.range(-1e3, 1e3),
        );
        let a = projector.nearest(&p).unwrap();
        assert_eq!(a, spline.nearest_point(&p).unwrap());
        check_nearest(&spline, &p, &a, scale(&pts, &p), "far point");
    }
}

/// A user's curve without spans gets a sampled, uncertified answer, right
/// for a smooth curve (closed form: the arc point at the query's angle, or
/// the nearer end).
#[test]
fn curves_without_spans_get_an_uncertified_answer() {
    let arc = Arc { r: 2.0, theta: 2.5 };
    for (x, y) in [
        (3.0, 1.0),
        (0.1, 0.3),
        (-1.0, -3.0),
        (-4.0, 0.5),
        (0.0, 0.0),
    ] {
        let p = Point2::new(x, y);
        let near = arc.nearest_point(&p).unwrap();
        assert!(!near.certified);
        let angle = y.atan2(x);
        let want = if (0.0..=2.5).contains(&angle) {
            (p.coords.norm() - 2.0).abs()
        } else {
            (arc.eval(0.0) - p).norm().min((arc.eval(2.5) - p).norm())
        };
        assert!(
            (near.distance - want).abs() <= 1e-14,
            "({x}, {y}): {} vs {want}",
            near.distance
        );
    }
    assert_eq!(
        CurveProjector::new(&arc).unwrap_err(),
        Error::NotPiecewiseRational
    );
}

/// A user's curve whose spans break the contract.
struct BadSpans(Vec<RationalBezierSpan<2>>);

impl Curve<2> for BadSpans {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
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

/// A user's curve without spans that breaks the contract.
struct Broken {
    domain: (f64, f64),
}

impl Curve<2> for Broken {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(if t > 0.5 { f64::NAN } else { t }, 0.0)
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(1.0, 0.0)
    }
}

#[test]
fn bad_query_inputs_are_errors() {
    let curve = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 1.0)]).unwrap();
    for (bad, index) in [
        (Point2::new(f64::NAN, 0.0), 0),
        (Point2::new(0.0, f64::INFINITY), 1),
        (Point2::new(0.0, -1e101), 1),
    ] {
        let err = curve.nearest_point(&bad).unwrap_err();
        assert!(
            matches!(err, Error::InvalidQueryPoint { coordinate, .. } if coordinate == index),
            "{err:?}"
        );
        assert!(err.to_string().contains("query point coordinate"));
    }
    let line = |a: f64, b: f64| RationalBezierSpan {
        knots: (a, b),
        curve: RationalBezier::new(
            vec![Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)],
            vec![1.0, 1.0],
        )
        .unwrap(),
    };
    let p = Point2::new(0.5, 0.5);
    assert_eq!(
        BadSpans(vec![]).nearest_point(&p).unwrap_err(),
        Error::SpansOutOfOrder { index: 0 }
    );
    assert_eq!(
        BadSpans(vec![line(0.0, 1.0), line(0.5, 2.0)])
            .nearest_point(&p)
            .unwrap_err(),
        Error::SpansOutOfOrder { index: 1 }
    );
    assert_eq!(
        BadSpans(vec![line(f64::NAN, 1.0)])
            .nearest_point(&p)
            .unwrap_err(),
        Error::SpansOutOfOrder { index: 0 }
    );
    assert_eq!(
        BadSpans(vec![line(0.0, 1.0), line(2.0, 2.0)])
            .arc_length(1e-6)
            .unwrap_err(),
        Error::SpansOutOfOrder { index: 1 }
    );
    let reversed = Broken { domain: (1.0, 0.0) };
    assert!(matches!(
        reversed.nearest_point(&p),
        Err(Error::InvalidDomain { .. })
    ));
    assert!(matches!(
        reversed.arc_length(1e-6),
        Err(Error::InvalidDomain { .. })
    ));
    let nan = Broken { domain: (0.0, 1.0) };
    assert!(matches!(
        nan.nearest_point(&p),
        Err(Error::CurveNotFinite { .. })
    ));
    assert!(matches!(
        nan.arc_length(1e-6),
        Err(Error::CurveNotFinite { .. })
    ));
}

// ---------------------------------------------------------------------------
// Arc length
// ---------------------------------------------------------------------------

/// `∫ₐᵇ |C′(t)| dt` by composite 5-point Gauss–Legendre on `intervals`
/// equal intervals (closed-form nodes and weights, the intervals summed
/// with Kahan's compensation), and an estimate of its error: the difference
/// from the same with half the intervals, plus the rounding of the speeds
/// (`16ε` of the total).
fn composite_length<const D: usize>(
    speed: impl Fn(f64) -> f64,
    (a, b): (f64, f64),
    intervals: usize,
) -> (f64, f64) {
    let s = (10.0_f64 / 7.0).sqrt();
    let (x1, x2) = ((5.0 - 2.0 * s).sqrt() / 3.0, (5.0 + 2.0 * s).sqrt() / 3.0);
    let r = 70f64.sqrt();
    let (w0, w1, w2) = (
        128.0 / 225.0,
        (322.0 + 13.0 * r) / 900.0,
        (322.0 - 13.0 * r) / 900.0,
    );
    let rule = [(0.0, w0), (x1, w1), (-x1, w1), (x2, w2), (-x2, w2)];
    let integrate = |m: usize| {
        let h = (b - a) / m as f64;
        let (mut sum, mut carry) = (0.0_f64, 0.0_f64);
        for i in 0..m {
            let c = a + h * (i as f64 + 0.5);
            let piece = rule
                .iter()
                .map(|&(x, w)| w * speed(c + 0.5 * h * x))
                .sum::<f64>()
                * 0.5
                * h;
            let y = piece - carry;
            let t = sum + y;
            carry = (t - sum) - y;
            sum = t;
        }
        sum
    };
    let fine = integrate(intervals);
    (
        fine,
        (fine - integrate(intervals / 2)).abs() + 16.0 * f64::EPSILON * fine,
    )
}

/// Checks an arc length against an exact value (within `reference_error`):
/// the bracket holds it, the error bound is within the tolerance and covers
/// the actual error. A tolerance below what rounding allows for the curve
/// may be refused, but only below `1e-10` of the length.
fn check_length<C: Curve<D>, const D: usize>(
    curve: &C,
    tolerance: f64,
    exact: f64,
    reference_error: f64,
    what: &str,
) {
    let arc = match curve.arc_length(tolerance) {
        Err(Error::ToleranceTooSmall { tolerance: t, min }) => {
            assert!(
                t == tolerance && t < min && min <= 1e-10 * exact,
                "{what}: min {min:e}"
            );
            return;
        }
        other => other.unwrap(),
    };
    assert!(
        arc.error_bound <= tolerance,
        "{what}: bound {:e}",
        arc.error_bound
    );
    assert!(
        (arc.length - exact).abs() <= arc.error_bound + reference_error,
        "{what}: {} vs {exact}: off by {:e}, bound {:e}",
        arc.length,
        (arc.length - exact).abs(),
        arc.error_bound
    );
    assert!(
        arc.lower <= exact + reference_error && exact - reference_error <= arc.upper,
        "{what}: [{}, {}] misses {exact}",
        arc.lower,
        arc.upper
    );
    // As tight as the tolerance (curves with spans; others have no upper
    // bound).
    assert!(
        arc.upper.is_infinite() || arc.upper - arc.lower <= 2.0 * tolerance,
        "{what}: [{}, {}] is {:e} wide for a tolerance of {tolerance:e} ({} pieces)",
        arc.lower,
        arc.upper,
        arc.upper - arc.lower,
        arc.pieces
    );
}

#[test]
fn arc_length_of_lines_circles_and_parabolas() {
    // A straight cubic, unevenly parametrized: the length of the segment.
    let dir = Vector2::new(2.0, 4.0);
    let line = Bezier::new(
        [0.0, 0.1, 0.7, 1.0]
            .iter()
            .map(|&s| Point2::origin() + dir * s)
            .collect(),
    )
    .unwrap();
    for tol in [1e-3, 1e-8, 1e-12] {
        check_length(&line, tol, 20f64.sqrt(), 0.0, "line");
    }
    // Circular arcs r·θ: one rational quadratic, elevated, and whole circles.
    for r in [1e-3, 1.0, 250.0] {
        for theta in [0.1, 1.0, FRAC_PI_2, 2.5, 3.0] {
            let arc = rational_arc(r, theta);
            for tol in [1e-4 * r, 1e-10 * r, 1e-12 * r] {
                check_length(&arc, tol, r * theta, 0.0, &format!("arc r={r} θ={theta}"));
                let up = arc.elevate_degree(3).unwrap();
                check_length(&up, tol, r * theta, 0.0, "elevated arc");
            }
        }
        let circle = Circle::new(Point2::new(1.0, -1.0), r);
        check_length(&circle, 1e-11 * r, 2.0 * PI * r, 0.0, "circle");
    }
    // The parabola y = x² on [0, X]: X√(1+4X²)/2 + asinh(2X)/4.
    for x in [0.5, 1.0, 3.0, 10.0] {
        let parabola = Bezier::new(vec![
            Point2::new(0.0, 0.0),
            Point2::new(0.5 * x, 0.0),
            Point2::new(x, x * x),
        ])
        .unwrap();
        let exact = x * (1.0 + 4.0 * x * x).sqrt() / 2.0 + (2.0 * x).asinh() / 4.0;
        for tol in [1e-6 * exact, 1e-12 * exact] {
            check_length(
                &parabola,
                tol,
                exact,
                2.0 * f64::EPSILON * exact,
                "parabola",
            );
        }
    }
}

/// Random curves against composite Gauss–Legendre with 2·10⁴ intervals.
#[test]
fn arc_length_of_random_curves_against_composite_quadrature() {
    let mut rng = Rng(0xA7C);
    for case in 0..40 {
        let degree = 1 + case % 7;
        let pts = random_points::<3>(&mut rng, degree + 1);
        let bezier = Bezier::new(pts.clone()).unwrap();
        let (exact, err) =
            composite_length::<3>(|t| bezier.derivative(t).norm(), (0.0, 1.0), 20_000);
        for tol in [1e-4, 1e-9, 1e-12] {
            check_length(
                &bezier,
                tol * exact,
                exact,
                err,
                &format!("Bézier {degree}"),
            );
        }
        let rational = RationalBezier::new(pts, random_weights(&mut rng, degree + 1)).unwrap();
        let (exact, err) =
            composite_length::<3>(|t| rational.derivative(t).norm(), (0.0, 1.0), 20_000);
        for tol in [1e-4, 1e-9, 1e-12] {
            check_length(
                &rational,
                tol * exact,
                exact,
                err,
                &format!("rational {degree}"),
            );
        }
        let spline = BSpline::uniform(3, random_points::<2>(&mut rng, 5 + case % 6)).unwrap();
        let (a, b) = spline.domain();
        let spans = spline.to_bezier_spans();
        let (mut exact, mut err) = (0.0, 0.0);
        for s in &spans {
            let (l, e) = composite_length::<2>(|t| spline.derivative(t).norm(), s.knots, 4_000);
            exact += l;
            err += e;
        }
        assert_eq!((spans[0].knots.0, spans[spans.len() - 1].knots.1), (a, b));
        check_length(&spline, 1e-10 * exact, exact, err, "uniform cubic");
    }
}

/// Clamped cubics through 30 random points turn sharply (the speed dips
/// near zero between spans' ends): the bracket is still certified to the
/// tolerance, not left at the chords and polygons of the turns (it was
/// 3.9e-6 wide at a tolerance of 1e-10).
#[test]
fn arc_length_of_sharply_turning_splines() {
    let mut rng = Rng(0x7A2);
    for case in 0..6 {
        let spline = BSpline::clamped(3, random_points::<2>(&mut rng, 30)).unwrap();
        let (mut exact, mut err) = (0.0, 0.0);
        for s in &spline.to_bezier_spans() {
            let (l, e) = composite_length::<2>(|t| spline.derivative(t).norm(), s.knots, 4_000);
            exact += l;
            err += e;
        }
        for tol in [1e-6, 1e-10] {
            check_length(&spline, tol * exact, exact, err, &format!("spline {case}"));
        }
    }
}

/// A cubic with a cusp (`C′(½) = 0`): the speed has a kink there. The
/// reference integrates each smooth half separately.
#[test]
fn arc_length_through_a_cusp() {
    let cusp = Bezier::new(vec![
        Point2::new(-1.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(-1.0, 1.0),
        Point2::new(1.0, 0.0),
    ])
    .unwrap();
    assert!(cusp.derivative(0.5).norm() < 1e-15);
    let speed = |t: f64| cusp.derivative(t).norm();
    let (l1, e1) = composite_length::<2>(speed, (0.0, 0.5), 20_000);
    let (l2, e2) = composite_length::<2>(speed, (0.5, 1.0), 20_000);
    for tol in [1e-3, 1e-8, 1e-11] {
        check_length(&cusp, tol, l1 + l2, e1 + e2, "cusp");
    }
}

/// A user's curve without spans: the quadrature on its derivative, only the
/// lower bound rigorous.
#[test]
fn arc_length_without_spans() {
    for (r, theta) in [(2.0, 2.5), (0.01, 6.0)] {
        let arc = Arc { r, theta };
        let got = arc.arc_length(1e-10 * r).unwrap();
        assert!(got.upper.is_infinite());
        assert!(got.lower <= r * theta && got.error_bound <= 1e-10 * r);
        assert!(
            (got.length - r * theta).abs() <= got.error_bound,
            "{} vs {}",
            got.length,
            r * theta
        );
    }
}

#[test]
fn arc_length_limits() {
    let curve = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(3.0, 4.0)]).unwrap();
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(curve.arc_length(bad), Err(Error::InvalidTolerance { .. })),
            "{bad}"
        );
    }
    assert!(matches!(
        curve.arc_length(1e-15),
        Err(Error::ToleranceTooSmall { .. })
    ));
    let five = curve.arc_length(1e-12).unwrap();
    assert!((five.length - 5.0).abs() <= five.error_bound && five.error_bound <= 1e-12);
    assert!(five.lower <= 5.0 && 5.0 <= five.upper);
    // A curve that is a point has length zero.
    let point = Bezier::new(vec![Point2::new(1.0, 2.0); 4]).unwrap();
    let got = point.arc_length(1e-9).unwrap();
    assert_eq!(
        (got.length, got.error_bound, got.lower, got.upper),
        (0.0, 0.0, 0.0, 0.0)
    );
}

//! Degree elevation: the elevated curve is the same curve (dense samples,
//! relative `1e-13`), `times` degrees higher, with every interior knot
//! `times` more times and clamped ends; against closed forms (monomials,
//! lines, circles) and a second algorithm (the elevated spline's Bézier
//! spans against Farin's formula on the original spans).

use revolve_testkit as common;

use common::Rng;
use revolve::curve::MAX_ELEVATED_DEGREE;
use revolve::nalgebra::{Point, Point1, Point2, Point3};
use revolve::{BSpline, Bezier, Curve, Error, RationalBezier};

/// Control points with coordinates uniform in `[−1, 1]`.
fn random_points<const D: usize>(rng: &mut Rng, count: usize) -> Vec<Point<f64, D>> {
    (0..count)
        .map(|_| Point::from(std::array::from_fn(|_| rng.range(-1.0, 1.0))))
        .collect()
}

/// The largest coordinate magnitude of the points (the curve's scale).
fn scale<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points.iter().fold(0.0_f64, |m, p| m.max(p.coords.amax()))
}

/// `samples + 1` parameters spread over the domain.
fn parameters((a, b): (f64, f64), samples: usize) -> impl Iterator<Item = f64> {
    (0..=samples).map(move |i| a + (b - a) * i as f64 / samples as f64)
}

/// Both curves have the same domain and agree at `samples + 1` parameters
/// to `1e-13 × scale`.
fn assert_same_curve<const D: usize>(
    a: &impl Curve<D>,
    b: &impl Curve<D>,
    scale: f64,
    samples: usize,
    what: &str,
) {
    assert_eq!(a.domain(), b.domain(), "{what}: domain");
    let mut worst = 0.0_f64;
    for t in parameters(a.domain(), samples) {
        worst = worst.max((a.eval(t) - b.eval(t)).norm());
    }
    assert!(
        worst <= 1e-13 * scale,
        "{what}: the curves differ by {worst:e} (scale {scale})"
    );
}

/// `C(n, k)` by the product formula (exact for small arguments).
fn choose(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    (0..k).fold(1.0, |acc, j| acc * (n - j) as f64 / (j + 1) as f64)
}

/// The multiplicity of every distinct value of a knot vector.
fn multiplicities(knots: &[f64]) -> Vec<(f64, usize)> {
    knots
        .chunk_by(|a, b| a == b)
        .map(|run| (run[0], run.len()))
        .collect()
}

#[test]
fn bezier_elevation_keeps_the_curve() {
    let mut rng = Rng(0xE1E7);
    for case in 0..300 {
        let degree = case % 13;
        let times = 1 + rng.below(6);
        let points = random_points::<3>(&mut rng, degree + 1);
        let curve = Bezier::new(points.clone()).unwrap();
        let up = curve.elevate_degree(times).unwrap();
        assert_eq!(up.degree(), degree + times);
        assert_eq!(up.points().len(), degree + times + 1);
        // The ends are the old ends, exactly.
        assert_eq!(up.points()[0], points[0]);
        assert_eq!(up.points()[degree + times], points[degree]);
        let what = format!("degree {degree} + {times}");
        assert_same_curve(&curve, &up, scale(&points), 10_000, &what);
        // The derivative curve is the same too (its scale is n·scale).
        for t in parameters((0.0, 1.0), 100) {
            let (d0, d1) = (curve.derivative(t), up.derivative(t));
            let bound = 1e-13 * scale(&points) * (degree + times) as f64 * 4.0;
            assert!((d0 - d1).norm() <= bound, "{what}: derivative at {t}");
        }
    }
}

/// `tᵏ` of degree `k` (coefficients `0, …, 0, 1`) elevated to degree `n`
/// has the coefficients `C(i, k)/C(n, k)`.
#[test]
fn monomials_elevate_to_their_closed_form_coefficients() {
    for k in 0..=5 {
        let mut coeffs = vec![Point1::new(0.0); k + 1];
        coeffs[k] = Point1::new(1.0);
        let monomial = Bezier::new(coeffs).unwrap();
        for n in k..=k + 9 {
            let up = monomial.elevate_degree(n - k).unwrap();
            for (i, p) in up.points().iter().enumerate() {
                let want = choose(i, k) / choose(n, k);
                assert!(
                    (p.x - want).abs() <= 2.0 * f64::EPSILON * want,
                    "t^{k} at degree {n}: coefficient {i} is {} not {want}",
                    p.x
                );
            }
        }
    }
    // A line elevated to degree k: the points are equally spaced on it.
    let line = Bezier::new(vec![Point2::new(-1.0, 2.0), Point2::new(3.0, -6.0)]).unwrap();
    let up = line.elevate_degree(7).unwrap();
    for (i, p) in up.points().iter().enumerate() {
        let s = i as f64 / 8.0;
        let want = Point2::new(-1.0 + 4.0 * s, 2.0 - 8.0 * s);
        assert!((p - want).norm() < 1e-15, "point {i}: {p} not {want}");
    }
}

/// Elevating by `k` at once and by one `k` times give the same points.
#[test]
fn elevation_composes() {
    let mut rng = Rng(77);
    for degree in 0..8 {
        let curve = Bezier::new(random_points::<2>(&mut rng, degree + 1)).unwrap();
        let once = curve.elevate_degree(5).unwrap();
        let steps = (0..5).fold(curve.clone(), |c, _| c.elevate_degree(1).unwrap());
        for (a, b) in once.points().iter().zip(steps.points()) {
            assert!((a - b).norm() < 1e-15, "degree {degree}: {a} vs {b}");
        }
    }
}

/// A random valid knot vector: distinct values with gaps in `[0.2, 1]`, each
/// repeated 1 to `p + 1` times (interior discontinuities and repeated ends
/// included), at least `2p + 2` knots, domain `t_p < t_n` non-empty.
fn random_knots(rng: &mut Rng, p: usize) -> Vec<f64> {
    loop {
        let mut knots = Vec::new();
        let mut value = rng.range(-2.0, 2.0);
        let target = 2 * p + 2 + rng.below(8);
        while knots.len() < target {
            // Mostly simple knots, sometimes repeated ones.
            let m = if rng.below(3) == 0 {
                1 + rng.below(p + 1)
            } else {
                1
            };
            knots.extend(std::iter::repeat_n(value, m));
            value += rng.range(0.2, 1.0);
        }
        let n = knots.len() - p - 1;
        if knots[p] < knots[n] {
            return knots;
        }
    }
}

/// Checks `up` against `curve` elevated by `times`: degree, knots (every
/// distinct interior knot `times` more often, the ends of the domain
/// clamped at multiplicity `q + 1`, nothing beyond), control point count,
/// the same curve, and the same Bézier spans as Farin's formula gives on the
/// original spans.
fn check_spline_elevation<const D: usize>(curve: &BSpline<D>, up: &BSpline<D>, times: usize) {
    let (p, q) = (curve.degree(), up.degree());
    assert_eq!(q, p + times);
    let (a, b) = curve.domain();
    let old: Vec<(f64, usize)> = multiplicities(curve.knots())
        .into_iter()
        .filter(|&(v, _)| v > a && v < b)
        .collect();
    let new = multiplicities(up.knots());
    assert_eq!(new.len(), old.len() + 2, "the interior knots and the ends");
    assert_eq!(new[0], (a, q + 1), "clamped start");
    assert_eq!(new[new.len() - 1], (b, q + 1), "clamped end");
    for (&(v, m), &(v2, m2)) in old.iter().zip(&new[1..]) {
        assert_eq!((v2, m2), (v, m + times), "interior knot {v}");
    }
    let interior: usize = old.iter().map(|&(_, m)| m + times).sum();
    assert_eq!(up.points().len(), q + 1 + interior);
    let what = format!("degree {p} + {times}, knots {:?}", curve.knots());
    assert_same_curve(curve, up, scale(curve.points()), 10_000, &what);
    // A second algorithm: the elevated spline's own Bézier spans (blossoms
    // of its new control points) against Farin's elevation of the old spans.
    let (old_spans, new_spans) = (curve.to_bezier_spans(), up.to_bezier_spans());
    assert_eq!(old_spans.len(), new_spans.len());
    for (o, n) in old_spans.iter().zip(&new_spans) {
        assert_eq!(o.knots, n.knots);
        let farin = o.curve.elevate_degree(times).unwrap();
        for (x, y) in farin.points().iter().zip(n.curve.points()) {
            assert!(
                (x - y).norm() <= 1e-13 * scale(curve.points()),
                "{what}: span {:?}: {x} vs {y}",
                o.knots
            );
        }
    }
}

#[test]
fn bspline_elevation_keeps_the_curve_and_raises_every_knot() {
    let mut rng = Rng(0xB5E1);
    for case in 0..240 {
        let p = case % 6;
        let times = 1 + rng.below(3);
        let knots = random_knots(&mut rng, p);
        let n = knots.len() - p - 1;
        let curve = BSpline::new(p, knots, random_points::<2>(&mut rng, n)).unwrap();
        let up = curve.elevate_degree(times).unwrap();
        check_spline_elevation(&curve, &up, times);
    }
}

/// The course framework's uniform knots (outside knots on both sides) and
/// clamped knots, and the derivative at interior parameters.
#[test]
fn uniform_and_clamped_splines_elevate() {
    let mut rng = Rng(31);
    for p in 1..=5 {
        for count in [p + 1, p + 3, 12] {
            let pts = random_points::<3>(&mut rng, count);
            for curve in [
                BSpline::uniform(p, pts.clone()).unwrap(),
                BSpline::clamped(p, pts.clone()).unwrap(),
            ] {
                for times in 1..=3 {
                    let up = curve.elevate_degree(times).unwrap();
                    check_spline_elevation(&curve, &up, times);
                    // The same derivative off the knots (scale: the knot
                    // spacing divides it, up to (n + p) per unit).
                    let (a, b) = curve.domain();
                    let d_scale = scale(&pts) * (count + p) as f64 * (p + times) as f64 / (b - a);
                    for t in parameters((a, b), 97).skip(1) {
                        let t = t - 1e-3 * (b - a) / 97.0;
                        let (d0, d1) = (curve.derivative(t), up.derivative(t));
                        assert!(
                            (d0 - d1).norm() <= 1e-13 * d_scale,
                            "p={p}, n={count}, +{times}: derivative at {t}: {d0} vs {d1}"
                        );
                    }
                }
            }
        }
    }
}

/// A repeated end knot beyond position p (a control point whose basis
/// vanishes on the domain) and a piecewise constant spline.
#[test]
fn degenerate_splines_elevate() {
    // Degree 1, knots 0 1 1 2 3: t_1 = t_2 = 1 starts the domain [1, 2];
    // the first point's basis vanishes there.
    let pts = vec![
        Point2::new(9.0, 9.0),
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 2.0),
    ];
    let curve = BSpline::new(1, vec![0.0, 1.0, 1.0, 2.0, 3.0], pts).unwrap();
    for times in 1..=3 {
        let up = curve.elevate_degree(times).unwrap();
        check_spline_elevation(&curve, &up, times);
        assert_eq!(
            up.points()[0],
            Point2::new(0.0, 0.0),
            "the unused point is gone"
        );
    }
    // Degree 0: a step function; elevated, still discontinuous.
    let steps = BSpline::new(
        0,
        vec![0.0, 1.0, 2.0, 3.0],
        vec![Point1::new(1.0), Point1::new(-2.0), Point1::new(5.0)],
    )
    .unwrap();
    for times in 1..=4 {
        let up = steps.elevate_degree(times).unwrap();
        check_spline_elevation(&steps, &up, times);
        assert_eq!(up.eval(1.5).x, -2.0);
        assert_eq!(up.eval(2.0).x, 5.0, "right limit at the jump");
    }
}

#[test]
fn rational_quarter_circle_stays_on_the_circle() {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for r in [1e-3, 1.0, 7.5, 1e4] {
        let quarter = RationalBezier::new(
            vec![Point2::new(r, 0.0), Point2::new(r, r), Point2::new(0.0, r)],
            vec![1.0, h, 1.0],
        )
        .unwrap();
        for times in 1..=8 {
            let up = quarter.elevate_degree(times).unwrap();
            assert_eq!(up.degree(), 2 + times);
            assert!(up.weights().iter().all(|&w| w > 0.0));
            for t in parameters((0.0, 1.0), 10_000) {
                let p = up.eval(t);
                // De Casteljau of degree q rounds by about qε.
                let q = (2 + times) as f64;
                assert!(
                    (p.coords.norm() - r).abs() <= 2.0 * q * f64::EPSILON * r,
                    "r={r}, +{times}: |C({t})| = {}",
                    p.coords.norm()
                );
                // Same parametrization: the same point at the same t.
                assert!((p - quarter.eval(t)).norm() <= 1e-14 * r);
            }
        }
    }
}

#[test]
fn random_rational_beziers_elevate() {
    let mut rng = Rng(0x4A7);
    for case in 0..200 {
        let degree = 1 + case % 7;
        let points = random_points::<3>(&mut rng, degree + 1);
        // Weights from 0.05 to 20, log-uniform.
        let weights: Vec<f64> = (0..=degree)
            .map(|_| (rng.range(0.05_f64.ln(), 20.0_f64.ln())).exp())
            .collect();
        let curve = RationalBezier::new(points.clone(), weights).unwrap();
        let times = 1 + rng.below(5);
        let up = curve.elevate_degree(times).unwrap();
        assert_eq!(up.degree(), degree + times);
        assert_eq!(up.points()[0], points[0]);
        assert_eq!(up.points()[degree + times], points[degree]);
        let what = format!("rational degree {degree} + {times}");
        assert_same_curve(&curve, &up, scale(&points), 10_000, &what);
    }
}

#[test]
fn elevation_limits_are_errors() {
    let mut rng = Rng(5);
    let high = Bezier::new(random_points::<2>(&mut rng, 61)).unwrap();
    assert_eq!(
        high.elevate_degree(5).unwrap_err(),
        Error::ElevationTooHigh {
            degree: 60,
            times: 5,
            max: MAX_ELEVATED_DEGREE
        }
    );
    assert_eq!(high.elevate_degree(4).unwrap().degree(), 64);
    for times in [65, usize::MAX] {
        assert!(matches!(
            Bezier::new(vec![Point3::origin()])
                .unwrap()
                .elevate_degree(times),
            Err(Error::ElevationTooHigh { .. })
        ));
    }
    // Elevating by zero is a copy at any degree.
    let very_high = Bezier::new(random_points::<2>(&mut rng, 101)).unwrap();
    assert_eq!(very_high.elevate_degree(0).unwrap(), very_high);
    let spline = BSpline::clamped(3, random_points::<2>(&mut rng, 7)).unwrap();
    assert_eq!(spline.elevate_degree(0).unwrap(), spline);
    let err = spline.elevate_degree(usize::MAX).unwrap_err();
    assert_eq!(
        err.to_string(),
        format!(
            "elevating degree 3 by {} would exceed the largest supported degree 64",
            usize::MAX
        )
    );
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let quarter = RationalBezier::new(
        vec![
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ],
        vec![1.0, h, 1.0],
    )
    .unwrap();
    assert!(matches!(
        quarter.elevate_degree(63),
        Err(Error::ElevationTooHigh { degree: 2, .. })
    ));
}

/// NURBS elevation: random rational B-splines (degrees 0–5, weights 0.05
/// to 20, repeated knots) elevated by 1–3 are the same curve, with every
/// interior knot `times` more often and positive weights; the circle stays
/// on the circle.
#[test]
fn nurbs_elevation_keeps_the_curve() {
    use revolve::Nurbs;
    let mut rng = Rng(0x4E0B);
    for case in 0..120 {
        let p = case % 6;
        let times = 1 + rng.below(3);
        let knots = random_knots(&mut rng, p);
        let n = knots.len() - p - 1;
        let weights: Vec<f64> = (0..n)
            .map(|_| 0.05 * 400f64.powf(rng.range(0.0, 1.0)))
            .collect();
        let curve = Nurbs::new(p, knots, random_points::<3>(&mut rng, n), weights).unwrap();
        let up = curve.elevate_degree(times).unwrap();
        assert_eq!(up.degree(), p + times);
        assert!(up.weights().iter().all(|&w| w > 0.0));
        let (a, b) = curve.domain();
        let old: Vec<(f64, usize)> = multiplicities(curve.knots())
            .into_iter()
            .filter(|&(v, _)| v > a && v < b)
            .collect();
        let new = multiplicities(up.knots());
        assert_eq!(new.len(), old.len() + 2);
        for (&(v, m), &(v2, m2)) in old.iter().zip(&new[1..]) {
            assert_eq!((v2, m2), (v, m + times), "interior knot {v}");
        }
        let what = format!("NURBS degree {p} + {times}");
        assert_same_curve(&curve, &up, scale(curve.points()), 5_000, &what);
    }
    let circle = Nurbs::circle(Point2::new(0.5, -1.0), 3.0).unwrap();
    for times in 1..=4 {
        let up = circle.elevate_degree(times).unwrap();
        for t in parameters(up.domain(), 1000) {
            let r = (up.eval(t) - Point2::new(0.5, -1.0)).norm();
            assert!(
                (r - 3.0).abs() <= 1e-14 * 4.0,
                "times {times}, t {t}: radius {r}"
            );
        }
    }
}

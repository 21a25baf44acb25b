//! Odd inputs and users' curves that break the [`Curve`] contract, one named
//! test each, asserting the documented error or value: discretization sizes,
//! derivative overflow, tangents of huge derivatives, spans at the coordinate
//! limit, the `testing` strategies' bad arguments, mesh sizes, the Newton
//! intersector with tiny and huge directions, NaN ranges and odd tolerances,
//! and empty and infinite boxes.

use revolve_testkit as common;

use revolve::nalgebra::{
    Isometry3, Point1, Point2, Point3, Translation3, UnitQuaternion, Vector2, Vector3,
};
use revolve::{
    Aabb, BSpline, Bezier, Curve, Error, Intersect, MAX_COORDINATE, MAX_DERIVATIVE, MAX_SEGMENTS,
    Mesh, NewtonIntersector, Ray, Revolution, Tolerance,
};

// ---------------------------------------------------------------------------
// Users' curves that break the contract
// ---------------------------------------------------------------------------

/// The parabola `(t, t²)` on a domain of the user's choosing.
struct Parabola {
    domain: (f64, f64),
}

impl Curve<2> for Parabola {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(t, t * t)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        Vector2::new(1.0, 2.0 * t)
    }
}

/// A straight line with a fixed derivative `d` (possibly huge or tiny), or
/// NaN everywhere when `d` is NaN.
struct Constant {
    d: Vector2<f64>,
}

impl Curve<2> for Constant {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::from(self.d * t)
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        self.d
    }
}

#[test]
fn reversed_domain_is_sampled_from_start_down_to_end() {
    let c = Parabola { domain: (1.0, 0.0) };
    let ts: Vec<f64> = c.discretize(4).iter().map(|s| s.t).collect();
    assert_eq!(ts, [1.0, 0.75, 0.5, 0.25, 0.0]);
    let s = c.discretize(4);
    assert_eq!(s[1].point, Point2::new(0.75, 0.5625));
    assert_eq!(s[1].derivative, Vector2::new(1.0, 1.5));
    // The tangent is the normalized derivative: (1, 2t)/√(1 + 4t²).
    let t = c.tangent(0.5).unwrap();
    assert!((t.into_inner() - Vector2::new(1.0, 1.0) / 2f64.sqrt()).norm() < 1e-15);
}

#[test]
fn nan_domain_gives_nan_parameters_and_exact_end() {
    let c = Parabola {
        domain: (f64::NAN, 1.0),
    };
    let s = c.discretize(3);
    assert_eq!(s.len(), 4);
    assert!(s[..3].iter().all(|s| s.t.is_nan()));
    assert_eq!(s[3].t, 1.0);
    assert_eq!(s[3].point, Point2::new(1.0, 1.0));
    assert_eq!(c.try_discretize(3).map(|v| v.len()), Ok(4));
}

#[test]
fn infinite_domain_keeps_its_infinite_ends() {
    let c = Parabola {
        domain: (f64::NEG_INFINITY, f64::INFINITY),
    };
    let s = c.discretize(2);
    assert_eq!(s.len(), 3);
    assert_eq!(s[0].t, f64::NEG_INFINITY);
    assert!(s[1].t.is_nan(), "−∞·½ + ∞·½");
    assert_eq!(s[2].t, f64::INFINITY);
    // The largest finite domain does not overflow the parameters.
    let c = Parabola {
        domain: (-f64::MAX, f64::MAX),
    };
    let ts: Vec<f64> = c.discretize(2).iter().map(|s| s.t).collect();
    assert_eq!(ts, [-f64::MAX, 0.0, f64::MAX]);
}

#[test]
fn nan_curve_has_no_tangent() {
    let c = Constant {
        d: Vector2::new(f64::NAN, 1.0),
    };
    assert_eq!(c.tangent(0.5), None);
    // A NaN end point makes the chord fallback NaN too.
    struct Stuck;
    impl Curve<2> for Stuck {
        fn domain(&self) -> (f64, f64) {
            (0.0, 1.0)
        }
        fn eval(&self, t: f64) -> Point2<f64> {
            Point2::new(if t > 0.5 { f64::NAN } else { 0.0 }, 0.0)
        }
        fn derivative(&self, _: f64) -> Vector2<f64> {
            Vector2::zeros()
        }
    }
    assert_eq!(Stuck.tangent(0.7), None);
}

#[test]
fn tangents_of_huge_and_tiny_derivatives_have_unit_length() {
    let diagonal = Vector2::new(1.0, 1.0) / 2f64.sqrt();
    for scale in [1e300, f64::MAX, 1e-300, 5e-324] {
        let c = Constant {
            d: Vector2::new(scale, scale),
        };
        let t = c
            .tangent(0.5)
            .unwrap_or_else(|| panic!("no tangent at {scale:e}"));
        assert!(
            (t.into_inner() - diagonal).norm() < 1e-15,
            "{scale:e}: {t:?}"
        );
    }
    // An accepted B-spline whose derivative is (1e299, 1e299): |d|² overflows.
    let h = 1e-299;
    let s = BSpline::new(
        1,
        vec![0.0, 0.0, h, h],
        vec![Point2::origin(), Point2::new(1.0, 1.0)],
    )
    .unwrap();
    assert_eq!(s.derivative(0.5 * h), Vector2::new(1.0 / h, 1.0 / h));
    let t = s.tangent(0.5 * h).unwrap();
    assert!((t.into_inner() - diagonal).norm() < 1e-15, "{t:?}");
}

// ---------------------------------------------------------------------------
// Discretization sizes
// ---------------------------------------------------------------------------

#[test]
fn discretize_caps_the_segments_at_max_segments() {
    assert_eq!(MAX_SEGMENTS, 1 << 24);
    let line = Bezier::new(vec![Point1::new(0.0), Point1::new(2.0)]).unwrap();
    for segments in [1_000_000_000_000, usize::MAX] {
        let s = line.discretize(segments);
        assert_eq!(s.len(), MAX_SEGMENTS + 1, "{segments}");
        assert_eq!((s[0].t, s[MAX_SEGMENTS].t), (0.0, 1.0));
        // Uniform: sample i at i/2²⁴, exactly (a power of two).
        assert_eq!(s[MAX_SEGMENTS / 4].t, 0.25);
        assert_eq!(s[MAX_SEGMENTS / 4].point, Point1::new(0.5));
    }
}

#[test]
fn try_discretize_refuses_more_than_max_segments() {
    let line = Bezier::new(vec![Point1::new(0.0), Point1::new(2.0)]).unwrap();
    for segments in [MAX_SEGMENTS + 1, 1_000_000_000_000, usize::MAX] {
        assert_eq!(
            line.try_discretize(segments),
            Err(Error::TooManySegments {
                segments,
                max: MAX_SEGMENTS
            })
        );
    }
    assert_eq!(line.try_discretize(0).map(|v| v.len()), Ok(2));
    assert_eq!(
        Error::TooManySegments {
            segments: 1_000_000_000_000,
            max: MAX_SEGMENTS
        }
        .to_string(),
        "1000000000000 segments asked for, more than the 16777216 a discretization can have"
    );
    assert_eq!(
        Error::AllocationFailed { bytes: 1 << 40 }.to_string(),
        "could not allocate 1099511627776 bytes for the result"
    );
}

// ---------------------------------------------------------------------------
// Derivative overflow
// ---------------------------------------------------------------------------

#[test]
fn short_knot_spans_whose_derivatives_overflow_are_refused() {
    assert_eq!(MAX_DERIVATIVE, 1e300);
    // Degree 1 on [0, 1e-250] from 0 to 1e100: the derivative is 1e350.
    let h = 1e-250;
    let steep = BSpline::new(
        1,
        vec![0.0, 0.0, h, h],
        vec![Point2::origin(), Point2::new(1e100, 0.0)],
    );
    assert_eq!(steep, Err(Error::DerivativeOverflow { order: 1 }));
    // Degree 2 on [0, 1e-200]: first derivatives ~2e200 pass, second ~2e400
    // do not.
    let h = 1e-200;
    let bent = BSpline::new(
        2,
        vec![0.0, 0.0, 0.0, h, h, h],
        vec![
            Point2::origin(),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
        ],
    );
    assert_eq!(bent, Err(Error::DerivativeOverflow { order: 2 }));
    assert_eq!(
        Error::DerivativeOverflow { order: 2 }.to_string(),
        "the derivative of order 2 could exceed 1e300 in magnitude: spread the knots or \
         bring the control points closer together"
    );
    // A short span inside an ordinary knot vector, with the same points.
    let short = BSpline::new(
        2,
        vec![0.0, 0.0, 0.0, 1e-300, 1.0, 1.0, 1.0],
        vec![
            Point2::origin(),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ],
    );
    assert!(
        matches!(short, Err(Error::KnotGapTooSmall { .. })),
        "{short:?}"
    );
    let narrow = 1e-20;
    let ok = BSpline::new(
        2,
        vec![0.0, 0.0, 0.0, narrow, narrow, narrow],
        vec![
            Point2::origin(),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
        ],
    );
    assert!(ok.is_ok(), "second derivative 2e40 is fine: {ok:?}");
}

#[test]
fn high_degree_bezier_whose_hodographs_overflow_is_refused() {
    // Alternating ±1: the k-th forward difference is ±2ᵏ, so the k-th
    // hodograph's control points are ±2ᵏ·n!/(n − k)!.
    let n = 200;
    let points: Vec<Point2<f64>> = (0..=n)
        .map(|i| Point2::new(if i % 2 == 0 { 1.0 } else { -1.0 }, 0.0))
        .collect();
    let mut size = 1.0_f64;
    let order = (1..=n)
        .find(|&k| {
            size *= 2.0 * (n - k + 1) as f64;
            size > MAX_DERIVATIVE
        })
        .unwrap();
    assert!(order > 50 && order < n, "{order}");
    assert_eq!(
        Bezier::new(points.clone()),
        Err(Error::DerivativeOverflow { order })
    );
    // The same points scaled down enough are accepted, and every
    // derivative is finite.
    let small: Vec<Point2<f64>> = points.iter().map(|p| p * 1e-200).collect();
    let c = Bezier::new(small).unwrap();
    for k in 0..=n {
        let d = c.nth_derivative(0.3, k).unwrap();
        assert!(d.iter().all(|x| x.is_finite()), "order {k}: {d:?}");
    }
}

#[test]
fn accepted_spline_near_the_bound_has_its_closed_form_derivatives() {
    // A clamped cubic on [0, h] is the Bézier curve B(t/h): its k-th
    // derivative is B⁽ᵏ⁾(t/h)/hᵏ. With h = 1e-99 the third is 1.2e298.
    let h = 1e-99;
    let pts = vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(0.0, 1.0),
    ];
    let s = BSpline::new(3, vec![0.0, 0.0, 0.0, 0.0, h, h, h, h], pts).unwrap();
    let t = 0.5 * h;
    let close = |got: Vector2<f64>, want: Vector2<f64>| (got - want).amax() <= 1e-14 * want.amax();
    // B′(½) = (0, 1.5), B″(½) = (−6, 0), B‴ = (0, −12).
    assert!(
        close(s.derivative(t), Vector2::new(0.0, 1.5 / h)),
        "{:?}",
        s.derivative(t)
    );
    let second = s.nth_derivative(t, 2).unwrap();
    assert!(
        close(second, Vector2::new(-6.0 / (h * h), 0.0)),
        "{second:?}"
    );
    let third = s.nth_derivative(t, 3).unwrap();
    assert!(
        close(third, Vector2::new(0.0, -12.0 / (h * h * h))),
        "{third:?}"
    );
    assert_eq!(s.nth_derivative(t, 4).unwrap(), Vector2::zeros());
    // The derivative spline's own derivative is the second derivative.
    let d = s.derivative_spline();
    let (_, d2) = d.eval_with_derivative(t);
    assert!(close(d2, second), "{d2:?}");
    // The tangent at the start follows P1 − P0.
    assert_eq!(s.tangent(0.0).unwrap().into_inner(), Vector2::new(1.0, 0.0));
}

// ---------------------------------------------------------------------------
// Bézier spans at the coordinate limit
// ---------------------------------------------------------------------------

/// A uniform cubic whose x coordinates all sit at ±1e100: every blossom is a
/// convex combination of them, which rounding used to push beyond the limit.
fn at_the_limit() -> BSpline<2> {
    let points = (0..14)
        .map(|i| {
            let x = if (i / 3) % 2 == 0 {
                MAX_COORDINATE
            } else {
                -MAX_COORDINATE
            };
            Point2::new(x, MAX_COORDINATE * (i as f64 / 7.0 - 1.0))
        })
        .collect();
    BSpline::uniform(3, points).unwrap()
}

#[test]
fn spans_of_a_spline_at_the_coordinate_limit_are_all_kept() {
    let s = at_the_limit();
    let spans = s.to_bezier_spans();
    assert_eq!(spans.len(), 14 - 3, "one span per non-empty knot interval");
    assert_eq!(s.bezier_spans().map(|v| v.len()), Some(11));
    for (i, span) in spans.iter().enumerate() {
        for p in span.curve.points() {
            assert!(
                p.x.abs() <= MAX_COORDINATE && p.y.abs() <= MAX_COORDINATE,
                "{i}: {p:?}"
            );
        }
        assert!(
            Bezier::new(span.curve.points().to_vec()).is_ok(),
            "span {i}"
        );
        // The span is the spline on its interval.
        let (a, b) = span.knots;
        for u in [0.0, 0.3, 1.0] {
            let want = s.eval(a + (b - a) * u);
            let got = span.curve.eval(u);
            assert!((got - want).amax() <= 1e-14 * MAX_COORDINATE, "{i} at {u}");
        }
    }
    // Knot insertion and subdivision keep their points within the limit too.
    let (a, b) = s.domain();
    let refined = s.insert_knot(a + (b - a) / 3.0, 2).unwrap();
    assert!(
        refined
            .points()
            .iter()
            .all(|p| p.x.abs() <= MAX_COORDINATE && p.y.abs() <= MAX_COORDINATE)
    );
    for span in refined.to_bezier_spans() {
        let (left, right) = span.curve.subdivide(1.0 / 3.0).unwrap();
        for p in left.points().iter().chain(right.points()) {
            assert!(
                p.x.abs() <= MAX_COORDINATE && p.y.abs() <= MAX_COORDINATE,
                "{p:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// The testing feature's bad arguments
// ---------------------------------------------------------------------------

#[cfg(feature = "testing")]
mod testing_support {
    use super::*;
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::TestRunner;
    use revolve::testing::{self, MAX_DEGREE};

    fn values<S: Strategy>(strategy: S, n: usize) -> Vec<S::Value> {
        let mut runner = TestRunner::deterministic();
        (0..n)
            .map(|_| strategy.new_tree(&mut runner).unwrap().current())
            .collect()
    }

    #[test]
    fn bad_scales_are_clamped() {
        for bad in [f64::NAN, -1.0, 0.0, f64::NEG_INFINITY] {
            for p in values(testing::point::<3>(bad), 20) {
                assert_eq!(p, Point3::origin(), "scale {bad}");
            }
            for p in values(testing::profile(bad), 10) {
                let (lo, hi) = p.bounds();
                assert!(
                    lo.x >= 0.05e-100 && hi.x <= 1e-100 && hi.y.abs() <= 3e-100,
                    "{bad}"
                );
            }
            for r in values(testing::ray(bad), 10) {
                assert!(r.dir.norm() > 0.0 && r.dir.iter().all(|c| c.is_finite()));
                assert!((r.origin.coords.norm() - 3e-100).abs() < 1e-114, "{r:?}");
            }
        }
        for huge in [f64::INFINITY, 1e300] {
            for p in values(testing::point::<2>(huge), 20) {
                assert!(p.iter().all(|c| c.abs() <= MAX_COORDINATE), "{p:?}");
            }
            for p in values(testing::profile(huge), 10) {
                let (lo, hi) = p.bounds();
                assert!(lo.x > 0.0 && hi.x <= MAX_COORDINATE / 8.0, "{lo:?} {hi:?}");
                assert!(hi.y.abs().max(lo.y.abs()) <= 3.0 * MAX_COORDINATE / 8.0);
            }
        }
    }

    #[test]
    fn bad_degree_ranges_are_clamped() {
        // An empty range means its start.
        let (start, end) = (5, 2);
        for c in values(testing::bezier_curve::<2>(start..=end, 1.0), 10) {
            assert_eq!(c.degree(), 5);
        }
        // Degrees above MAX_DEGREE (or beyond the points any count allows).
        for c in values(testing::bezier_curve::<2>(usize::MAX..=usize::MAX, 1.0), 5) {
            assert_eq!(c.degree(), MAX_DEGREE);
        }
        for c in values(testing::bspline_curve::<3>(usize::MAX..=usize::MAX, 1.0), 5) {
            assert_eq!(c.degree(), MAX_DEGREE);
            assert!(c.points().len() > MAX_DEGREE);
        }
        for c in values(testing::bspline_curve::<1>(40..=usize::MAX, 2.0), 5) {
            assert_eq!(c.degree(), MAX_DEGREE);
        }
    }

    #[test]
    fn checkers_report_broken_domains_and_clamp_counts() {
        let err =
            testing::check_curve_derivatives(&Parabola { domain: (1.0, 0.0) }, 16).unwrap_err();
        assert_eq!(err.law, "domain is finite with start < end");
        assert_eq!(err.at, [1.0, 0.0]);
        assert_eq!((err.error, err.limit), (1.0, 0.0));
        let err = testing::check_curve_derivatives(
            &Parabola {
                domain: (f64::NAN, 1.0),
            },
            16,
        )
        .unwrap_err();
        assert_eq!(err.error, f64::INFINITY);
        // A sample count beyond MAX_SAMPLES is clamped, not allocated.
        let good = Parabola { domain: (0.0, 1.0) };
        assert_eq!(testing::check_curve_derivatives(&good, usize::MAX), Ok(()));
        let surface = Revolution::new(Parabola { domain: (2.0, 1.0) });
        assert_eq!(
            testing::check_surface_partials(&surface, 8)
                .unwrap_err()
                .law,
            "domain is finite with start < end"
        );
        let vase = Revolution::new(common::vase());
        assert_eq!(testing::check_surface_partials(&vase, usize::MAX), Ok(()));
        assert_eq!(testing::check_surface_normals(&vase, usize::MAX), Ok(()));
    }
}

// ---------------------------------------------------------------------------
// Mesh sizes
// ---------------------------------------------------------------------------

#[test]
fn meshes_beyond_max_vertices_are_refused() {
    assert_eq!(Mesh::MAX_VERTICES, 1 << 24);
    // The vase at 5e-9: about 57 000 angular steps (within their cap) but
    // thousands of rings, far beyond 2²⁴ vertices.
    let vase = Revolution::new(common::vase());
    match vase.tessellate(5e-9) {
        Err(Error::MeshTooLarge {
            tolerance,
            vertices,
            max,
            min,
        }) => {
            assert_eq!((tolerance, max), (5e-9, Mesh::MAX_VERTICES));
            assert!(vertices > max as f64, "{vertices}");
            assert!(min > 5e-9, "{min:e}");
            assert!(vase.tessellate(min).is_ok());
        }
        other => panic!("{:?}", other.map(|m| m.positions.len())),
    }
    let mesh = vase.tessellate(1e-4).unwrap();
    assert!(mesh.positions.len() <= Mesh::MAX_VERTICES && mesh.bound <= 1e-4);
}

/// A line profile whose one Bézier span claims the knots `knots`.
struct Spans {
    knots: (f64, f64),
}

impl Curve<2> for Spans {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(1.0, t)
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(0.0, 1.0)
    }
    fn bezier_spans(&self) -> Option<Vec<revolve::BezierSpan<2>>> {
        let curve = Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0)]).unwrap();
        Some(vec![revolve::BezierSpan {
            knots: self.knots,
            curve,
        }])
    }
}

#[test]
fn tessellating_spans_that_are_not_finite_is_an_error() {
    for knots in [(f64::NEG_INFINITY, f64::INFINITY), (f64::NAN, 1.0)] {
        let surface = Revolution::new(Spans { knots });
        assert!(
            matches!(
                surface.contract_error(),
                Some(Error::SpansOutOfOrder { index: 0 })
            ),
            "{knots:?}"
        );
        assert_eq!(
            surface.tessellate(0.1),
            Err(Error::SpansOutOfOrder { index: 0 }),
            "{knots:?}"
        );
    }
    // The same span on finite knots is a cylinder.
    let surface = Revolution::new(Spans { knots: (0.0, 1.0) });
    let mesh = surface.tessellate(0.1).unwrap();
    assert!(
        mesh.positions
            .iter()
            .all(|p| (p.x.hypot(p.z) - 1.0).abs() < 1e-12)
    );
}

// ---------------------------------------------------------------------------
// The Newton intersector
// ---------------------------------------------------------------------------

/// A cylinder of radius 1 and height 2 about the y axis.
fn cylinder() -> Revolution<Bezier<2>> {
    Revolution::new(Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)]).unwrap())
}

/// The side ray from (−5, 1, 0.5) along +x with direction length `len`:
/// it enters the cylinder at x = −√0.75, `t = (5 − √0.75)/len`.
fn side_ray(len: f64) -> Ray {
    Ray::new(Point3::new(-5.0, 1.0, 0.5), Vector3::new(len, 0.0, 0.0))
}

const ENTRY: f64 = 5.0 - 0.866_025_403_784_438_6;

#[test]
fn newton_finds_hits_with_direction_lengths_from_1e_minus_300_to_1e300() {
    let s = cylinder();
    let newton = NewtonIntersector::new(&s, 6);
    for e in (-300..=300).step_by(20) {
        let len = 10f64.powi(e);
        let hit = newton
            .intersect(&side_ray(len), 0.0, f64::INFINITY)
            .unwrap_or_else(|| panic!("missed with |dir| = {len:e}"));
        let want = ENTRY / len;
        assert!(
            (hit.t - want).abs() <= 1e-13 * want,
            "{len:e}: {} vs {want}",
            hit.t
        );
        assert!(
            (hit.point.x + 0.75f64.sqrt()).abs() < 1e-13,
            "{:?}",
            hit.point
        );
        // The same for the one-run entry point, from the leaf's start.
        let run = newton.newton(&side_ray(len), 4.0 / len, 0.5, 3.5);
        assert!(run.converged, "{len:e}: {run:?}");
        assert!((run.t - want).abs() <= 1e-13 * want, "{len:e}: {run:?}");
    }
}

#[test]
fn newton_nan_and_empty_ranges_miss() {
    let s = cylinder();
    let newton = NewtonIntersector::new(&s, 4);
    let ray = side_ray(1.0);
    for (lo, hi) in [
        (f64::NAN, f64::INFINITY),
        (0.0, f64::NAN),
        (f64::NAN, f64::NAN),
        (5.0, 5.0),
        (6.0, 5.0),
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    ] {
        assert_eq!(newton.intersect(&ray, lo, hi), None, "({lo}, {hi})");
    }
    let hit = newton
        .intersect(&ray, f64::NEG_INFINITY, f64::INFINITY)
        .unwrap();
    assert!((hit.t - ENTRY).abs() < 1e-13);
    // Degenerate rays miss.
    for dir in [
        Vector3::zeros(),
        Vector3::new(f64::NAN, 0.0, 0.0),
        Vector3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        let r = Ray::new(Point3::new(-5.0, 1.0, 0.5), dir);
        assert_eq!(newton.intersect(&r, 0.0, f64::INFINITY), None, "{dir:?}");
    }
}

#[test]
fn newton_tolerances_out_of_range_are_clamped() {
    let s = cylinder();
    let ray = side_ray(1.0);
    // Scale 2 (the box's largest coordinate): runs stop at a residual of
    // τ·2, which the ray crossing at cos 0.866 turns into t errors up to
    // 2.31·τ; τ is clamped into [ε, 1e-3] (NaN → 4ε).
    for (tolerance, error) in [
        (Tolerance::relative(f64::INFINITY), 2.5e-3),
        (Tolerance::relative(10.0), 2.5e-3),
        (Tolerance::relative(f64::NAN), 1e-13),
        (Tolerance::relative(-1.0), 1e-13),
        (
            Tolerance {
                relative: 1e-12,
                max_iterations: u32::MAX,
            },
            2.5e-12,
        ),
    ] {
        let newton = NewtonIntersector::new(&s, 6).with_tolerance(tolerance);
        let (hit, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
        let hit = hit.unwrap_or_else(|| panic!("{tolerance:?} missed"));
        assert!((hit.t - ENTRY).abs() <= error, "{tolerance:?}: {}", hit.t);
        assert!(
            report.iterations <= 1000 * report.leaves_tried,
            "{report:?}"
        );
    }
    // A cap of 0 is one iteration per run.
    let newton = NewtonIntersector::new(&s, 6).with_tolerance(Tolerance {
        relative: 1e-12,
        max_iterations: 0,
    });
    let (_, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
    assert!(
        report.leaves_tried > 0 && report.iterations <= report.leaves_tried,
        "{report:?}"
    );
}

// ---------------------------------------------------------------------------
// Boxes
// ---------------------------------------------------------------------------

#[test]
fn empty_box_has_its_centre_at_the_origin_and_nothing_nan() {
    let e = Aabb::EMPTY;
    assert!(e.is_empty());
    assert_eq!(e.center(), Point3::origin());
    assert_eq!(e.extent(), Vector3::zeros());
    assert_eq!(e.scale(), 0.0);
    assert!(e.expand(1.0).is_empty() && e.expand(f64::INFINITY).is_empty());
    let m = Isometry3::new(Vector3::new(1.0, 2.0, 3.0), Vector3::new(0.1, 0.2, 0.3));
    assert!(e.transformed(&m).is_empty());
    let r = Ray::new(Point3::origin(), Vector3::new(1.0, 0.0, 0.0));
    assert_eq!(e.clip(&r, f64::NEG_INFINITY, f64::INFINITY), None);
    let b = Aabb::new(Point3::new(1.0, 2.0, 3.0), Point3::new(4.0, 5.0, 6.0));
    assert_eq!(e.union(&b), b);
    // Boxes with a NaN, or only at infinity, contain no finite point.
    let nan = Aabb {
        min: Point3::new(f64::NAN, 0.0, 0.0),
        max: Point3::new(1.0, 1.0, 1.0),
    };
    assert!(nan.is_empty() && nan.center() == Point3::origin());
    assert_eq!(nan.clip(&r, 0.0, f64::INFINITY), None);
    let at_infinity = Aabb {
        min: Point3::new(f64::INFINITY, 0.0, 0.0),
        max: Point3::new(f64::INFINITY, 1.0, 1.0),
    };
    assert!(at_infinity.is_empty());
    // A NaN margin gives the empty box.
    assert!(b.expand(f64::NAN).is_empty());
}

#[test]
fn infinite_boxes_have_no_nan() {
    let inf = f64::INFINITY;
    let all = Aabb::new(Point3::new(-inf, -inf, -inf), Point3::new(inf, inf, inf));
    assert_eq!(all.center(), Point3::origin());
    assert_eq!(all.extent(), Vector3::new(inf, inf, inf));
    assert_eq!(all.scale(), inf);
    // Turned and moved: still everything.
    let m = Isometry3::new(Vector3::new(1.0, 2.0, 3.0), Vector3::new(0.1, 0.2, 0.3));
    assert_eq!(all.transformed(&m), all);
    // Half-infinite along x, moved by (1, 0, 0) without turning.
    let half = Aabb::new(Point3::new(0.0, 0.0, 0.0), Point3::new(inf, 1.0, 1.0));
    assert_eq!(half.center(), Point3::new(inf, 0.5, 0.5));
    let shift = Isometry3::from_parts(Translation3::new(1.0, 0.0, 0.0), UnitQuaternion::identity());
    assert_eq!(
        half.transformed(&shift),
        Aabb::new(Point3::new(1.0, 0.0, 0.0), Point3::new(inf, 1.0, 1.0))
    );
    // A quarter turn about z takes x to y: the infinite axis moves (the
    // rotation's rounding leaves x and y infinite downward or upward only
    // where the box reaches).
    let turn = Isometry3::new(Vector3::zeros(), Vector3::z() * std::f64::consts::FRAC_PI_2);
    let t = half.transformed(&turn);
    assert!(
        t.min.iter().chain(t.max.iter()).all(|c| !c.is_nan()),
        "{t:?}"
    );
    assert_eq!(t.max.y, inf);
    assert!(
        t.min.y > -1e-15 && t.min.z == 0.0 && t.max.z == 1.0,
        "{t:?}"
    );
    // The largest finite box: centre 0, extent overflows to ∞ (not NaN).
    let max = f64::MAX;
    let big = Aabb::new(Point3::new(-max, -max, -max), Point3::new(max, max, max));
    assert_eq!(big.center(), Point3::origin());
    assert_eq!(big.extent(), Vector3::new(inf, inf, inf));
    // The slab test against an infinite box.
    let r = Ray::new(Point3::new(3.0, 0.5, 0.5), Vector3::new(-1.0, 0.0, 0.0));
    assert_eq!(half.clip(&r, 0.0, inf), Some((0.0, 3.0)));
}

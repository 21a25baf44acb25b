//! Bad input is an `Error` value that names the problem, never a panic; and
//! evaluation at any parameter (NaN, infinities, far outside the domain) gives
//! finite values at the clamped parameter.
//!
//! One test per `Error` variant checks the exact variant with its fields and
//! that the `Display` message carries the offending numbers.

use revolve::nalgebra::{Point1, Point2, Point3};
use revolve::{BSpline, Bezier, Curve, Error};

fn pts2(n: usize) -> Vec<Point2<f64>> {
    (0..n)
        .map(|i| Point2::new(i as f64, ((i * 7) % 5) as f64 - 2.0))
        .collect()
}

fn assert_message(err: &Error, parts: &[&str]) {
    let msg = err.to_string();
    for part in parts {
        assert!(msg.contains(part), "message {msg:?} lacks {part:?}");
    }
}

// ------------------------------------------------------ one per variant ----

#[test]
fn no_control_points_is_reported_by_every_constructor() {
    let errs = [
        Bezier::<2>::new(vec![]).unwrap_err(),
        BSpline::<2>::new(0, vec![0.0, 1.0], vec![]).unwrap_err(),
        BSpline::<2>::uniform(0, vec![]).unwrap_err(),
        BSpline::<2>::clamped(3, vec![]).unwrap_err(),
    ];
    for err in errs {
        assert_eq!(err, Error::NoControlPoints);
        assert_message(&err, &["control point", "none"]);
    }
}

#[test]
fn non_finite_point_names_the_index_of_the_first_bad_point() {
    let mut pts = pts2(5);
    pts[2].y = f64::NAN;
    pts[4].x = f64::INFINITY;
    let errs = [
        Bezier::new(pts.clone()).unwrap_err(),
        BSpline::new(1, (0..=6).map(f64::from).collect(), pts.clone()).unwrap_err(),
        BSpline::uniform(2, pts.clone()).unwrap_err(),
        BSpline::clamped(2, pts.clone()).unwrap_err(),
    ];
    for err in errs {
        assert_eq!(err, Error::NonFinitePoint { index: 2 });
        assert_message(&err, &["control point 2", "NaN or infinite"]);
    }
    let neg = Bezier::new(vec![Point1::new(0.0), Point1::new(f64::NEG_INFINITY)]).unwrap_err();
    assert_eq!(neg, Error::NonFinitePoint { index: 1 });
}

#[test]
fn non_finite_knot_names_the_index() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let knots = vec![0.0, 1.0, 2.0, bad, 4.0, 5.0, 6.0];
        let err = BSpline::new(2, knots, pts2(4)).unwrap_err();
        assert_eq!(err, Error::NonFiniteKnot { index: 3 }, "{bad}");
        assert_message(&err, &["knot 3", "NaN or infinite"]);
    }
}

#[test]
fn knot_count_gives_expected_and_found() {
    // 4 points, degree 2: 7 knots needed.
    let err = BSpline::new(2, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0], pts2(4)).unwrap_err();
    assert_eq!(
        err,
        Error::KnotCount {
            expected: 7,
            found: 6
        }
    );
    assert_message(&err, &["expected 7", "found 6"]);
    let err = BSpline::new(2, vec![0.0; 9], pts2(4)).unwrap_err();
    assert_eq!(
        err,
        Error::KnotCount {
            expected: 7,
            found: 9
        }
    );
    let err = BSpline::new(0, vec![], pts2(1)).unwrap_err();
    assert_eq!(
        err,
        Error::KnotCount {
            expected: 2,
            found: 0
        }
    );
}

#[test]
fn decreasing_knots_names_the_first_smaller_knot() {
    let knots = vec![0.0, 1.0, 2.0, 1.5, 4.0, 3.0, 6.0];
    let err = BSpline::new(2, knots, pts2(4)).unwrap_err();
    assert_eq!(err, Error::DecreasingKnots { index: 3 });
    assert_message(&err, &["non-decreasing", "knot 3", "knot 2"]);
}

#[test]
fn knot_multiplicity_gives_the_knot_its_count_and_the_limit() {
    // Degree 2 allows a knot at most 3 times; 0.5 occurs 4 times.
    let knots = vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0];
    let err = BSpline::new(2, knots, pts2(7)).unwrap_err();
    assert_eq!(
        err,
        Error::KnotMultiplicity {
            knot: 0.5,
            multiplicity: 4,
            max: 3
        }
    );
    assert_message(&err, &["knot 0.5", "4 times", "= 3"]);
    // Also at the ends.
    let knots = vec![0.0, 0.0, 0.0, 1.0, 2.0];
    let err = BSpline::new(1, knots, pts2(3)).unwrap_err();
    assert_eq!(
        err,
        Error::KnotMultiplicity {
            knot: 0.0,
            multiplicity: 3,
            max: 2
        }
    );
}

#[test]
fn knot_multiplicity_from_insert_knot() {
    let c = BSpline::clamped(2, pts2(5)).unwrap();
    let err = c.insert_knot(0.5, 4).unwrap_err();
    assert_eq!(
        err,
        Error::KnotMultiplicity {
            knot: 0.5,
            multiplicity: 4,
            max: 3
        }
    );
    assert_message(&err, &["0.5", "4 times", "3"]);
    // The domain start of a clamped spline already has full multiplicity.
    let err = c.insert_knot(0.0, 1).unwrap_err();
    assert_eq!(
        err,
        Error::KnotMultiplicity {
            knot: 0.0,
            multiplicity: 4,
            max: 3
        }
    );
}

#[test]
fn empty_domain_gives_start_and_end() {
    // Degree 2, 3 points: domain [t2, t3] = [1, 1].
    let knots = vec![0.0, 1.0, 1.0, 1.0, 2.0, 3.0];
    let err = BSpline::new(2, knots, pts2(3)).unwrap_err();
    assert_eq!(
        err,
        Error::EmptyDomain {
            start: 1.0,
            end: 1.0
        }
    );
    assert_message(&err, &["[1, 1]", "empty"]);
    // Degree 1, 2 points: domain [t1, t2], a double knot (allowed).
    let err = BSpline::new(1, vec![0.0, 2.5, 2.5, 3.0], pts2(2)).unwrap_err();
    assert_eq!(
        err,
        Error::EmptyDomain {
            start: 2.5,
            end: 2.5
        }
    );
    assert_message(&err, &["[2.5, 2.5]"]);
}

#[test]
fn degree_too_high_from_new_uniform_and_clamped() {
    let err = BSpline::new(3, vec![0.0; 7], pts2(3)).unwrap_err();
    assert_eq!(
        err,
        Error::DegreeTooHigh {
            degree: 3,
            points: 3
        }
    );
    assert_message(&err, &["degree 3", "at least 4 control points", "got 3"]);
    let err = BSpline::uniform(3, pts2(3)).unwrap_err();
    assert_eq!(
        err,
        Error::DegreeTooHigh {
            degree: 3,
            points: 3
        }
    );
    let err = BSpline::clamped(5, pts2(2)).unwrap_err();
    assert_eq!(
        err,
        Error::DegreeTooHigh {
            degree: 5,
            points: 2
        }
    );
    assert_message(&err, &["degree 5", "at least 6", "got 2"]);
}

#[test]
fn degree_usize_max_is_an_error_not_an_overflow() {
    let err = BSpline::uniform(usize::MAX, pts2(4)).unwrap_err();
    assert_eq!(
        err,
        Error::DegreeTooHigh {
            degree: usize::MAX,
            points: 4
        }
    );
    assert_message(&err, &[&usize::MAX.to_string(), "got 4"]);
    for degree in [usize::MAX, usize::MAX - 1, usize::MAX / 2, 1 << 40] {
        for n in [1, 2, 5] {
            let want = Error::DegreeTooHigh { degree, points: n };
            assert_eq!(BSpline::uniform(degree, pts2(n)).unwrap_err(), want);
            assert_eq!(BSpline::clamped(degree, pts2(n)).unwrap_err(), want);
            assert_eq!(
                BSpline::new(degree, vec![0.0; 3], pts2(n)).unwrap_err(),
                want
            );
        }
    }
}

#[test]
fn parameter_out_of_domain_from_bezier_subdivide() {
    let c = Bezier::new(pts2(4)).unwrap();
    for t in [
        1.5,
        -0.25,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1.0 + f64::EPSILON,
    ] {
        let err = c.subdivide(t).unwrap_err();
        assert_eq!(
            err,
            Error::ParameterOutOfDomain {
                t,
                domain: (0.0, 1.0)
            }
        );
        assert_message(&err, &[&format!("parameter {t}"), "[0, 1]"]);
    }
    // NaN is not equal to itself: match the variant.
    let err = c.subdivide(f64::NAN).unwrap_err();
    assert!(
        matches!(err, Error::ParameterOutOfDomain { t, domain: (0.0, 1.0) } if t.is_nan()),
        "{err:?}"
    );
    assert_message(&err, &["parameter NaN", "[0, 1]"]);
}

#[test]
fn parameter_out_of_domain_from_insert_knot() {
    let c = BSpline::new(2, (0..=7).map(f64::from).collect(), pts2(5)).unwrap();
    assert_eq!(c.domain(), (2.0, 5.0));
    for t in [1.0, 5.5, f64::INFINITY, f64::NEG_INFINITY] {
        let err = c.insert_knot(t, 1).unwrap_err();
        assert_eq!(
            err,
            Error::ParameterOutOfDomain {
                t,
                domain: (2.0, 5.0)
            }
        );
        assert_message(&err, &[&format!("parameter {t}"), "[2, 5]"]);
    }
    let err = c.insert_knot(f64::NAN, 1).unwrap_err();
    assert!(
        matches!(err, Error::ParameterOutOfDomain { t, domain: (2.0, 5.0) } if t.is_nan()),
        "{err:?}"
    );
}

#[test]
fn invalid_tolerance_for_flatten() {
    let b = Bezier::new(pts2(4)).unwrap();
    let s = BSpline::uniform(3, pts2(6)).unwrap();
    for tol in [0.0, -0.0, -1e-3, f64::INFINITY, f64::NEG_INFINITY] {
        let err = b.flatten(tol).unwrap_err();
        assert_eq!(err, Error::InvalidTolerance { tolerance: tol });
        assert_message(&err, &["finite positive", &format!("got {tol}")]);
        assert_eq!(
            s.flatten(tol).unwrap_err(),
            Error::InvalidTolerance { tolerance: tol }
        );
    }
    let err = b.flatten(f64::NAN).unwrap_err();
    assert!(
        matches!(err, Error::InvalidTolerance { tolerance } if tolerance.is_nan()),
        "{err:?}"
    );
    assert_message(&err, &["got NaN"]);
}

#[test]
fn tolerance_too_small_for_flatten_gives_the_minimum() {
    // Largest control-point coordinate 4 → the smallest tolerance is 4e-10.
    let b = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 4.0),
        Point2::new(2.0, -1.0),
    ])
    .unwrap();
    let err = b.flatten(1e-12).unwrap_err();
    assert_eq!(
        err,
        Error::ToleranceTooSmall {
            tolerance: 1e-12,
            min: 4e-10
        }
    );
    // Very small numbers are written in scientific notation.
    assert_message(&err, &["tolerance 1e-12 ", "at least 4e-10"]);
    assert!(b.flatten(4e-10).is_ok());
    let s = BSpline::clamped(2, b.points().to_vec()).unwrap();
    assert!(matches!(
        s.flatten(5e-324).unwrap_err(),
        Error::ToleranceTooSmall { tolerance, .. } if tolerance == 5e-324
    ));
}

#[test]
fn buffer_length_for_basis_functions_and_derivatives() {
    let c = BSpline::uniform(3, pts2(6)).unwrap();
    let mut short = [0.0; 3];
    let err = c.basis_functions(0.5, &mut short).unwrap_err();
    assert_eq!(
        err,
        Error::BufferLength {
            expected: 4,
            found: 3
        }
    );
    assert_message(&err, &["needs 4", "has 3"]);
    let mut buf = [0.0; 11];
    let err = c.basis_derivatives(0.5, 2, &mut buf).unwrap_err();
    assert_eq!(
        err,
        Error::BufferLength {
            expected: 12,
            found: 11
        }
    );
    assert_message(&err, &["needs 12", "has 11"]);
    let err = c.basis_derivatives(0.5, usize::MAX, &mut buf).unwrap_err();
    assert_eq!(
        err,
        Error::BufferLength {
            expected: usize::MAX,
            found: 11
        }
    );
    let err = c.basis_functions(0.5, &mut []).unwrap_err();
    assert_eq!(
        err,
        Error::BufferLength {
            expected: 4,
            found: 0
        }
    );
}

// ------------------------------------------------------ check ordering ----

#[test]
fn bspline_new_checks_in_the_documented_order() {
    let mut nan_pts = pts2(2);
    nan_pts[1].x = f64::NAN;
    // No points beats everything else.
    assert_eq!(
        BSpline::<2>::new(9, vec![f64::NAN], vec![]).unwrap_err(),
        Error::NoControlPoints
    );
    // A bad point beats a too-high degree.
    assert_eq!(
        BSpline::new(9, vec![], nan_pts).unwrap_err(),
        Error::NonFinitePoint { index: 1 }
    );
    // Degree beats knot count.
    assert_eq!(
        BSpline::new(2, vec![], pts2(2)).unwrap_err(),
        Error::DegreeTooHigh {
            degree: 2,
            points: 2
        }
    );
    // Knot count beats a NaN knot.
    assert_eq!(
        BSpline::new(1, vec![f64::NAN; 3], pts2(2)).unwrap_err(),
        Error::KnotCount {
            expected: 4,
            found: 3
        }
    );
    // A NaN knot beats decreasing order.
    assert_eq!(
        BSpline::new(1, vec![3.0, 2.0, f64::NAN, 0.0], pts2(2)).unwrap_err(),
        Error::NonFiniteKnot { index: 2 }
    );
    // Decreasing beats multiplicity.
    assert_eq!(
        BSpline::new(1, vec![1.0, 1.0, 1.0, 0.0], pts2(2)).unwrap_err(),
        Error::DecreasingKnots { index: 3 }
    );
    // Multiplicity beats an empty domain.
    assert_eq!(
        BSpline::new(1, vec![1.0, 1.0, 1.0, 1.0], pts2(2)).unwrap_err(),
        Error::KnotMultiplicity {
            knot: 1.0,
            multiplicity: 4,
            max: 2
        }
    );
}

// ------------------------------------------------------- the error type ----

#[test]
fn error_implements_std_error_and_is_clone_and_comparable() {
    fn takes_std_error<E: std::error::Error + Send + Sync + 'static>(_: &E) {}
    let err = BSpline::uniform(4, pts2(3)).unwrap_err();
    takes_std_error(&err);
    let boxed: Box<dyn std::error::Error> = Box::new(err.clone());
    assert_eq!(
        boxed.to_string(),
        "degree 4 needs at least 5 control points, got 3"
    );
    assert!(boxed.source().is_none());
    assert_eq!(err.clone(), err);
    assert_ne!(err, Error::NoControlPoints);
    assert!(format!("{err:?}").contains("DegreeTooHigh"));
    // `?` converts it into a boxed error.
    fn build() -> Result<Bezier<2>, Box<dyn std::error::Error>> {
        Ok(Bezier::new(vec![])?)
    }
    assert_eq!(
        build().unwrap_err().to_string(),
        Error::NoControlPoints.to_string()
    );
}

#[test]
fn every_display_message_is_distinct_and_nonempty() {
    let all = [
        Error::NoControlPoints,
        Error::NonFinitePoint { index: 1 },
        Error::NonFiniteKnot { index: 1 },
        Error::KnotCount {
            expected: 1,
            found: 2,
        },
        Error::DecreasingKnots { index: 1 },
        Error::KnotMultiplicity {
            knot: 1.0,
            multiplicity: 2,
            max: 1,
        },
        Error::EmptyDomain {
            start: 1.0,
            end: 1.0,
        },
        Error::DegreeTooHigh {
            degree: 1,
            points: 1,
        },
        Error::ParameterOutOfDomain {
            t: 2.0,
            domain: (0.0, 1.0),
        },
        Error::BufferLength {
            expected: 2,
            found: 1,
        },
        Error::InvalidTolerance { tolerance: -1.0 },
        Error::ToleranceTooSmall {
            tolerance: 1e-20,
            min: 1e-10,
        },
        Error::MeshTooLarge {
            tolerance: 1e-9,
            vertices: 1e10,
            max: 1 << 24,
            min: 1e-6,
        },
        Error::DepthTooLarge { depth: 20, max: 16 },
        Error::EmptyGrid,
        Error::NonFiniteGridPoint { row: 1, column: 2 },
        Error::GridCoordinateTooLarge {
            row: 1,
            column: 2,
            value: 1e101,
        },
        Error::InvalidGridWeight {
            row: 1,
            column: 2,
            weight: 0.0,
        },
        Error::SurfaceKnots {
            direction: revolve::ParameterDirection::U,
            error: Box::new(Error::DecreasingKnots { index: 1 }),
        },
    ];
    let msgs: Vec<String> = all.iter().map(ToString::to_string).collect();
    for (i, m) in msgs.iter().enumerate() {
        assert!(m.len() > 10, "{m:?}");
        for other in &msgs[i + 1..] {
            assert_ne!(m, other);
        }
    }
}

// ------------------------------------------------- no input panics ----

#[test]
fn nasty_inputs_return_errors_not_panics() {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    let mut results: Vec<(&str, Result<(), Error>)> = Vec::new();
    let mut push = |name: &'static str, r: Result<(), Error>| results.push((name, r));

    for bad in [nan, inf, -inf] {
        push(
            "bezier x",
            Bezier::new(vec![Point2::new(bad, 0.0)]).map(drop),
        );
        push(
            "bezier late",
            Bezier::new(vec![Point3::origin(), Point3::new(0.0, 0.0, bad)]).map(drop),
        );
        push(
            "uniform pt",
            BSpline::uniform(1, vec![Point1::new(bad); 3]).map(drop),
        );
        push(
            "clamped pt",
            BSpline::clamped(1, vec![Point1::new(bad); 3]).map(drop),
        );
        push(
            "new knot",
            BSpline::new(1, vec![0.0, bad, 1.0, 2.0], pts2(2)).map(drop),
        );
        push(
            "new all knots",
            BSpline::new(1, vec![bad; 4], pts2(2)).map(drop),
        );
    }
    push("bezier empty", Bezier::<3>::new(vec![]).map(drop));
    push("new empty", BSpline::<1>::new(0, vec![], vec![]).map(drop));
    push("new no knots", BSpline::new(0, vec![], pts2(1)).map(drop));
    push(
        "new equal knots",
        BSpline::new(0, vec![0.0, 0.0], pts2(1)).map(drop),
    );
    push(
        "new reversed",
        BSpline::new(1, vec![3.0, 2.0, 1.0, 0.0], pts2(2)).map(drop),
    );
    push(
        "new huge degree",
        BSpline::new(usize::MAX, vec![0.0, 1.0], pts2(1)).map(drop),
    );
    for degree in [usize::MAX, usize::MAX - 1, usize::MAX / 2 + 1] {
        for n in [0, 1, 3] {
            push("uniform huge", BSpline::uniform(degree, pts2(n)).map(drop));
            push("clamped huge", BSpline::clamped(degree, pts2(n)).map(drop));
        }
    }

    let s = BSpline::clamped(3, pts2(6)).unwrap();
    for times in [usize::MAX, usize::MAX - 1, 5] {
        push("insert times", s.insert_knot(0.5, times).map(drop));
        push("insert times at end", s.insert_knot(1.0, times).map(drop));
    }
    for t in [nan, inf, -inf, 1.0 + 1e-15, -1e-300, f64::MAX, f64::MIN] {
        push("insert t", s.insert_knot(t, 1).map(drop));
        let b = Bezier::new(pts2(3)).unwrap();
        push("subdivide t", b.subdivide(t).map(drop));
    }
    for tol in [nan, inf, -inf, 0.0, -1.0, 5e-324, f64::MIN_POSITIVE] {
        push(
            "flatten bezier",
            Bezier::new(pts2(3)).unwrap().flatten(tol).map(drop),
        );
        push("flatten spline", s.flatten(tol).map(drop));
    }
    for order in [usize::MAX, usize::MAX / 2, 1 << 60] {
        push(
            "basis derivs",
            s.basis_derivatives(0.5, order, &mut [0.0; 8]).map(drop),
        );
    }
    push("basis empty", s.basis_functions(0.5, &mut []).map(drop));

    assert!(results.len() > 60);
    for (name, r) in results {
        assert!(r.is_err(), "{name}: expected an error");
    }
}

// ---------------------------------------- evaluation at any parameter ----

const WILD: [f64; 8] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    -0.0,
];

/// The parameter each wild value should act as: below → start, above → end,
/// NaN → start.
fn clamped_param(t: f64, (a, b): (f64, f64)) -> f64 {
    if t.is_nan() || t < a {
        a
    } else if t > b {
        b
    } else {
        t
    }
}

#[test]
fn bezier_evaluation_at_wild_parameters_is_finite_and_clamped() {
    for degree in [0, 1, 3, 7, 20] {
        let c = Bezier::new(pts2(degree + 1)).unwrap();
        for t in WILD.into_iter().chain([-5.0, 5.0, 1.0 + 1e-9]) {
            let u = clamped_param(t, (0.0, 1.0));
            let p = c.eval(t);
            let d = c.derivative(t);
            let (p2, d2) = c.eval_with_derivative(t);
            assert!(
                p.coords.iter().chain(d.iter()).all(|v| v.is_finite()),
                "t={t}"
            );
            assert_eq!(p, c.eval(u), "degree {degree} t={t}");
            assert_eq!(d, c.derivative(u), "degree {degree} t={t}");
            assert_eq!((p2, d2), c.eval_with_derivative(u), "degree {degree} t={t}");
            for order in 0..=degree + 2 {
                let dk = c.nth_derivative(t, order).unwrap();
                assert!(dk.iter().all(|v| v.is_finite()), "t={t} order {order}");
                assert_eq!(
                    dk,
                    c.nth_derivative(u, order).unwrap(),
                    "t={t} order {order}"
                );
            }
        }
    }
}

#[test]
fn nan_parameter_evaluates_at_the_domain_start() {
    let b = Bezier::new(pts2(4)).unwrap();
    assert_eq!(b.eval(f64::NAN), b.points()[0]);
    let s = BSpline::clamped(2, pts2(5)).unwrap();
    assert_eq!(s.eval(f64::NAN), s.points()[0]);
    assert_eq!(s.span(f64::NAN), 2);
    let u = BSpline::uniform(3, pts2(7)).unwrap();
    assert_eq!(u.eval(f64::NAN), u.eval(u.domain().0));
}

#[test]
fn bspline_evaluation_at_wild_parameters_is_finite_and_clamped() {
    let splines = vec![
        BSpline::uniform(0, pts2(4)).unwrap(),
        BSpline::uniform(1, pts2(4)).unwrap(),
        BSpline::uniform(3, pts2(8)).unwrap(),
        BSpline::clamped(2, pts2(6)).unwrap(),
        BSpline::clamped(5, pts2(6)).unwrap(),
        BSpline::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
            pts2(6),
        )
        .unwrap(),
        BSpline::new(2, vec![-3.0, -2.0, -1.0, 1e-3, 4.0, 5.0, 6.0], pts2(4)).unwrap(),
    ];
    for c in &splines {
        let p = c.degree();
        let dom = c.domain();
        for t in WILD.into_iter().chain([dom.0 - 1.0, dom.1 + 1.0]) {
            let u = clamped_param(t, dom);
            let what = format!("degree {p} knots {:?} t={t}", c.knots());
            let pt = c.eval(t);
            let d = c.derivative(t);
            assert!(
                pt.coords.iter().chain(d.iter()).all(|v| v.is_finite()),
                "{what}"
            );
            assert_eq!(pt, c.eval(u), "{what}");
            assert_eq!(d, c.derivative(u), "{what}");
            assert_eq!(
                c.eval_with_derivative(t),
                c.eval_with_derivative(u),
                "{what}"
            );
            assert_eq!(c.span(t), c.span(u), "{what}");
            for order in 0..=p + 2 {
                let dk = c.nth_derivative(t, order).unwrap();
                assert!(dk.iter().all(|v| v.is_finite()), "{what} order {order}");
                assert_eq!(
                    dk,
                    c.nth_derivative(u, order).unwrap(),
                    "{what} order {order}"
                );
            }
            let mut n1 = vec![0.0; p + 1];
            let mut n2 = vec![0.0; p + 1];
            assert_eq!(
                c.basis_functions(t, &mut n1).unwrap(),
                c.basis_functions(u, &mut n2).unwrap()
            );
            assert!(n1.iter().all(|v| v.is_finite()));
            assert_eq!(n1, n2, "{what}");
            let mut d1 = vec![0.0; 3 * (p + 1)];
            let mut d2 = vec![0.0; 3 * (p + 1)];
            c.basis_derivatives(t, 2, &mut d1).unwrap();
            c.basis_derivatives(u, 2, &mut d2).unwrap();
            assert!(d1.iter().all(|v| v.is_finite()));
            assert_eq!(d1, d2, "{what}");
        }
    }
}

// ------------------------------------- extreme magnitudes are refused ----

/// A knot range beyond `f64::MAX` would overflow knot differences (NaN in
/// evaluation); knots beyond `MAX_COORDINATE` are refused instead.
#[test]
fn knot_beyond_max_coordinate_is_refused() {
    let m = 1e308;
    let r = BSpline::new(
        1,
        vec![-m, -m, m, m],
        vec![Point1::new(0.0), Point1::new(1.0)],
    );
    assert_eq!(
        r,
        Err(Error::KnotTooLarge {
            index: 0,
            value: -m
        })
    );
    assert!(r.unwrap_err().to_string().contains("knot 0 is -1e308"));
    // At the limit itself everything stays finite.
    let l = revolve::MAX_COORDINATE;
    let c = BSpline::new(
        1,
        vec![-l, -l, l, l],
        vec![Point1::new(0.0), Point1::new(1.0)],
    )
    .unwrap();
    assert_eq!(c.eval(l), Point1::new(1.0));
    assert!(c.derivative(0.0).x.is_finite());
    assert_eq!(c.to_bezier_spans().len(), 1);
}

/// A subnormal knot gap would make `p / (t₁ − t₀)` overflow (NaN from
/// `0 · ∞`); distinct knots closer than `4ε ×` the knot range are refused.
#[test]
fn subnormal_knot_gap_is_refused() {
    let r = BSpline::new(
        1,
        vec![0.0, 0.0, 5e-324, 1.0, 1.0],
        vec![Point1::new(1.0), Point1::new(1.0), Point1::new(2.0)],
    );
    match r {
        Err(Error::KnotGapTooSmall { index, gap, min }) => {
            assert_eq!(index, 2);
            assert_eq!(gap, 5e-324);
            assert_eq!(min, 4.0 * f64::EPSILON);
        }
        other => panic!("expected KnotGapTooSmall, got {other:?}"),
    }
    // A tiny but distinguishable gap is accepted and its derivative is finite.
    let c = BSpline::new(
        1,
        vec![0.0, 0.0, 1e-12, 1.0, 1.0],
        vec![Point1::new(1.0), Point1::new(1.0), Point1::new(2.0)],
    )
    .unwrap();
    assert_eq!(c.derivative(0.0).x, 0.0);
    assert_eq!(c.nth_derivative(0.0, 1).unwrap().x, 0.0);
}

/// Control points near `f64::MAX` would overflow the hodograph differences
/// (`∞ − ∞ = NaN`); coordinates beyond `MAX_COORDINATE` are refused, and at
/// the limit the second derivative of a straight line is exactly zero.
#[test]
fn huge_control_points_are_refused_and_the_limit_is_safe() {
    let m = 1e308;
    let r = Bezier::new(vec![Point1::new(-m), Point1::new(0.0), Point1::new(m)]);
    assert_eq!(
        r,
        Err(Error::CoordinateTooLarge {
            index: 0,
            value: -m
        })
    );
    let l = revolve::MAX_COORDINATE;
    let c = Bezier::new(vec![Point1::new(-l), Point1::new(0.0), Point1::new(l)]).unwrap();
    assert_eq!(c.nth_derivative(0.5, 2).unwrap().x, 0.0);
    assert_eq!(c.nth_derivative(0.5, 1).unwrap().x, 2.0 * l);
}

/// `nth_derivative_spline(order)` stops at the zero spline once the degree
/// is exhausted, so `order = usize::MAX` returns at once (it used to keep
/// differentiating, about 40 ns per step, and never returned).
#[test]
fn nth_derivative_spline_of_huge_order_returns_promptly() {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let c = BSpline::uniform(3, pts2(6)).unwrap();
        let d = c.nth_derivative_spline(usize::MAX);
        let _ = tx.send(d.degree());
    });
    let got = rx.recv_timeout(std::time::Duration::from_secs(5));
    assert_eq!(got, Ok(0), "no result within 5 s");
}

//! Intersections of space curves (`revolve::curve::intersect_space_curves`)
//! against closed forms (circles in perpendicular planes, a circle and
//! lines through it, skew lines at a known distance), planar pairs lifted
//! into space by a rigid motion against the planar search's own answers,
//! and random cubic pairs built to meet at a known point (the point must be
//! found, certified, at its parameters).
//!
//! Tolerances: certified points within `1e-13` of the closed forms (inputs
//! of size 1–3); constructed meeting points within `1e-9` in parameter.

use revolve_testkit as common;

use common::Rng;
use revolve::curve::{intersect_curves, intersect_space_curves};
use revolve::nalgebra::{Isometry3, Point, Point2, Point3, Translation3, UnitQuaternion, Vector3};
use revolve::{Bezier, Curve, Error, MAX_COORDINATE, Nurbs};
use std::f64::consts::{FRAC_PI_2, TAU};

const TOL: f64 = 1e-9;

fn circle_3d(center: Point3<f64>, normal: Vector3<f64>, start: Vector3<f64>) -> Nurbs<3> {
    Nurbs::arc_3d(center, normal, start, 1.0, 0.0, TAU).unwrap()
}

fn segment(a: Point3<f64>, b: Point3<f64>) -> Bezier<3> {
    Bezier::new(vec![a, b]).unwrap()
}

fn motion(seed: u64) -> Isometry3<f64> {
    let mut rng = Rng(seed);
    let axis = Vector3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    Isometry3::from_parts(
        Translation3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        ),
        UnitQuaternion::from_scaled_axis(axis.normalize() * rng.range(0.1, 3.0)),
    )
}

#[test]
fn circles_in_perpendicular_planes_meet_at_two_points() {
    for seed in 1..=20 {
        let m = motion(seed);
        let o = m * Point3::origin();
        let a = circle_3d(o, m * Vector3::z(), m * Vector3::x());
        let b = circle_3d(o, m * Vector3::x(), m * Vector3::y());
        let hits = intersect_space_curves(&a, &b, TOL).unwrap();
        assert_eq!(hits.len(), 2, "seed {seed}: {hits:?}");
        for want in [
            m * Point3::new(0.0, 1.0, 0.0),
            m * Point3::new(0.0, -1.0, 0.0),
        ] {
            let h = hits
                .iter()
                .find(|h| (h.point - want).norm() < 1e-13 * 4.0)
                .unwrap_or_else(|| panic!("seed {seed}: {want} not in {hits:?}"));
            assert!(h.certified);
            assert!((a.eval(h.t_a) - want).norm() < 4e-13 && (b.eval(h.t_b) - want).norm() < 4e-13);
        }
    }
}

#[test]
fn a_circle_and_lines_through_its_plane() {
    // The circle x² + y² = 1 in z = 0; slanted segments centred on
    // (r cos θ, r sin θ, 0) meet it iff r = 1, at their middle.
    let circle = circle_3d(Point3::origin(), Vector3::z(), Vector3::x());
    for k in 0..24 {
        let theta = TAU * k as f64 / 24.0 + 0.1;
        for r in [1.0, 0.5, 1.5] {
            let p = Point3::new(r * theta.cos(), r * theta.sin(), 0.0);
            let slant = Vector3::new(0.3, 0.2, 1.0);
            let line = segment(p - slant, p + slant);
            let hits = intersect_space_curves(&circle, &line, TOL).unwrap();
            if r == 1.0 {
                assert_eq!(hits.len(), 1, "θ {theta}: {hits:?}");
                assert!(
                    hits[0].certified && (hits[0].point - p).norm() < 1e-13,
                    "{hits:?}"
                );
                assert!((hits[0].t_b - 1.0 / 2.0).abs() < 1e-13, "{hits:?}");
            } else {
                assert!(hits.is_empty(), "θ {theta}, r {r}: {hits:?}");
            }
        }
    }
}

#[test]
fn skew_lines_meet_only_within_the_tolerance() {
    // The x axis and a line along y at height d: closest at the origin and
    // (0, 0, d), distance d.
    let a = segment(Point3::new(-1.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0));
    for d in [0.0, 1e-13, 1e-11, 0.5 * TOL, 2.0 * TOL, 1e-3] {
        let b = segment(Point3::new(0.0, -1.0, d), Point3::new(0.0, 1.0, d));
        let hits = intersect_space_curves(&a, &b, TOL).unwrap();
        if d <= TOL {
            assert_eq!(hits.len(), 1, "d {d}: {hits:?}");
            let h = hits[0];
            assert!(
                (h.t_a - 0.5).abs() < 1e-12 && (h.t_b - 0.5).abs() < 1e-12,
                "{h:?}"
            );
            assert!((h.point - Point3::new(0.0, 0.0, 0.5 * d)).norm() < 1e-15);
            // Certified only where the lines meet to rounding: within
            // 2⁻⁴⁰ of the largest coordinate (1 here).
            assert_eq!(h.certified, d <= 2f64.powi(-40), "d {d}: {h:?}");
        } else {
            assert!(hits.is_empty(), "d {d}: {hits:?}");
        }
    }
}

#[test]
fn planar_pairs_lifted_into_space_give_the_planar_answers() {
    let a2 = Nurbs::circle(Point2::new(0.0, 0.0), 1.0).unwrap();
    let b2 = Nurbs::circle(Point2::new(1.0, 0.3), 1.2).unwrap();
    let planar = intersect_curves(&a2, &b2, TOL).unwrap();
    assert_eq!(planar.len(), 2);
    let lift = |c: &Nurbs<2>, m: &Isometry3<f64>| {
        Nurbs::new(
            c.degree(),
            c.knots().to_vec(),
            c.points()
                .iter()
                .map(|p| m * Point3::new(p.x, p.y, 0.0))
                .collect(),
            c.weights().to_vec(),
        )
        .unwrap()
    };
    for seed in 1..=10 {
        let m = motion(100 + seed);
        let hits = intersect_space_curves(&lift(&a2, &m), &lift(&b2, &m), TOL).unwrap();
        assert_eq!(hits.len(), planar.len(), "seed {seed}: {hits:?}");
        for (h, p) in hits.iter().zip(&planar) {
            assert!(h.certified);
            assert!((h.t_a - p.t_a).abs() < 1e-12 && (h.t_b - p.t_b).abs() < 1e-12);
            let want = m * Point3::new(p.point.x, p.point.y, 0.0);
            assert!((h.point - want).norm() < 1e-13, "{h:?} vs {want}");
        }
    }
}

#[test]
fn random_cubics_built_to_meet_are_found_at_their_parameters() {
    // b is translated so that b(t₀) = a(s₀): the meeting point must be
    // found, at (s₀, t₀), certified (the tangents are random: transversal).
    let mut rng = Rng(0x3d_c0de);
    let mut found = 0;
    for case in 0..300 {
        let cubic = |rng: &mut Rng| {
            Bezier::new(
                (0..4)
                    .map(|_| {
                        Point::from([
                            rng.range(-1.0, 1.0),
                            rng.range(-1.0, 1.0),
                            rng.range(-1.0, 1.0),
                        ])
                    })
                    .collect(),
            )
            .unwrap()
        };
        let a = cubic(&mut rng);
        let b0 = cubic(&mut rng);
        let (s0, t0) = (rng.range(0.05, 0.95), rng.range(0.05, 0.95));
        let shift = a.eval(s0) - b0.eval(t0);
        let b = Bezier::new(b0.points().iter().map(|p| p + shift).collect()).unwrap();
        let angle = a
            .derivative(s0)
            .normalize()
            .cross(&b.derivative(t0).normalize())
            .norm();
        let hits = intersect_space_curves(&a, &b, TOL).unwrap();
        let near = hits
            .iter()
            .find(|h| (h.t_a - s0).abs() < 1e-9 && (h.t_b - t0).abs() < 1e-9);
        let h = near.unwrap_or_else(|| panic!("case {case}: ({s0}, {t0}) not in {hits:?}"));
        if angle > 1e-3 {
            assert!(h.certified, "case {case}: {h:?}");
        }
        for h in &hits {
            assert!(
                (a.eval(h.t_a) - b.eval(h.t_b)).norm() <= TOL,
                "case {case}: {h:?}"
            );
        }
        found += 1;
    }
    assert_eq!(found, 300);
}

#[test]
fn copies_overlap_and_bad_input_is_an_error() {
    let a = circle_3d(
        Point3::new(0.5, 0.0, 1.0),
        Vector3::new(1.0, 1.0, 1.0),
        Vector3::x(),
    );
    let err = intersect_space_curves(&a, &a.reversed(), TOL).unwrap_err();
    assert!(matches!(err, Error::CurvesOverlap { .. }), "{err}");
    let half = Nurbs::arc_3d(
        Point3::new(0.5, 0.0, 1.0),
        Vector3::new(1.0, 1.0, 1.0),
        Vector3::x(),
        1.0,
        0.0,
        FRAC_PI_2,
    )
    .unwrap();
    let err = intersect_space_curves(&a, &half, TOL).unwrap_err();
    assert!(matches!(err, Error::CurvesOverlap { .. }), "{err}");
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            intersect_space_curves(&a, &half, bad),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    assert!(matches!(
        intersect_space_curves(&a, &half, 1e-12),
        Err(Error::ToleranceTooSmall { .. })
    ));
    let far = segment(
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(MAX_COORDINATE, 0.0, 0.0),
    );
    assert!(matches!(
        intersect_space_curves(&far, &far, 1.0),
        Err(Error::ToleranceTooSmall { .. })
    ));
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 128, failure_persistence: None, ..Default::default() })]

    /// A random cubic pair built to meet at `(s₀, t₀)` under a random
    /// rigid motion: the meeting is found there, and every result is a
    /// place where the curves are within the tolerance.
    #[test]
    fn a_meeting_built_in_is_found(seed in proptest::prelude::any::<u64>(), s0 in 0.05f64..0.95, t0 in 0.05f64..0.95) {
        let mut rng = Rng(seed | 1);
        let m = motion(seed);
        let cubic = |rng: &mut Rng| {
            let pts: Vec<Point3<f64>> = (0..4)
                .map(|_| m * Point3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
                .collect();
            Bezier::new(pts).unwrap()
        };
        let a = cubic(&mut rng);
        let b0 = cubic(&mut rng);
        let shift = a.eval(s0) - b0.eval(t0);
        let b = Bezier::new(b0.points().iter().map(|p| p + shift).collect()).unwrap();
        let hits = intersect_space_curves(&a, &b, TOL).unwrap();
        proptest::prop_assert!(
            hits.iter().any(|h| (h.t_a - s0).abs() < 1e-8 && (h.t_b - t0).abs() < 1e-8),
            "({}, {}) not in {:?}", s0, t0, hits
        );
        for h in &hits {
            proptest::prop_assert!((a.eval(h.t_a) - b.eval(h.t_b)).norm() <= TOL);
        }
    }
}

//! `NurbsCurve`: as a `RevSurface` profile and as a tube, its fields, and
//! every way it can be written wrong (located, with revolve's message where
//! revolve is the one refusing).

use std::f64::consts::FRAC_1_SQRT_2;

use revolve::nalgebra::{Point2, Point3};
use revolve::{Curve, Error, Nurbs};

use super::{assert_error, fail, in_group, objects_of};
use crate::scene::{RevolutionBody, Shape};

/// `√2/2` as the scenes write it (17 digits: the same double).
const W: &str = "0.7071067811865476";

/// A `NurbsCurve` block with the given fields.
fn quarter(fields: &str) -> String {
    format!("NurbsCurve {{ {fields} }}")
}

/// The three fields of the radius-2 quarter circle in the `z = 0` plane.
fn quarter_fields() -> String {
    format!("degree 2 knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 2 0 {W} ] [ 0 2 0 ]")
}

/// The revolution body of a group holding `RevSurface { profile BODY }`.
fn profile_of(curve: &str) -> Nurbs<2> {
    let objects = objects_of(&format!("RevSurface {{ profile {curve} }}"));
    let Shape::Revolution(body) = &objects[0].shape else {
        panic!("not a revolution: {:?}", objects[0].shape);
    };
    let RevolutionBody::Nurbs(surface) = &**body else {
        panic!("not a NURBS profile");
    };
    surface.profile().clone()
}

#[test]
fn nurbs_profile_reads_degree_knots_points_and_weights() {
    let profile = profile_of(&quarter(&quarter_fields()));
    assert_eq!(profile.degree(), 2);
    assert_eq!(profile.knots(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    assert_eq!(
        profile.points(),
        &[
            Point2::new(2.0, 0.0),
            Point2::new(2.0, 2.0),
            Point2::new(0.0, 2.0)
        ]
    );
    // Weight 1 where the point has three numbers.
    assert_eq!(profile.weights(), &[1.0, FRAC_1_SQRT_2, 1.0]);
    // The curve is the exact quarter circle.
    for k in 0..=32 {
        let p = profile.eval(f64::from(k) / 32.0);
        assert!((p.coords.norm() - 2.0).abs() < 1e-14, "{p}");
    }
}

#[test]
fn nurbs_keys_come_in_any_order() {
    let reordered = quarter(&format!(
        "controls [ 2 0 0 1 ] [ 2 2 0 {W} ] [ 0 2 0 1 ] knots 0 0 0 1 1 1 degree 2"
    ));
    assert_eq!(
        profile_of(&reordered),
        profile_of(&quarter(&quarter_fields()))
    );
}

#[test]
fn nurbs_curve_in_a_group_is_a_tube_on_the_curve() {
    // A full circle of radius 1 in the plane x + z = 0 tilted out of z = 0:
    // a tube may leave the z = 0 plane.
    let s = FRAC_1_SQRT_2;
    let at = |x: f64, y: f64| format!("{} {y} {}", x * s, -x * s);
    let controls: String = [
        (1.0, 0.0, "1"),
        (1.0, 1.0, W),
        (0.0, 1.0, "1"),
        (-1.0, 1.0, W),
        (-1.0, 0.0, "1"),
        (-1.0, -1.0, W),
        (0.0, -1.0, "1"),
        (1.0, -1.0, W),
        (1.0, 0.0, "1"),
    ]
    .iter()
    .map(|&(x, y, w)| format!("[ {} {w} ] ", at(x, y)))
    .collect();
    let objects = objects_of(&format!(
        "NurbsCurve {{ degree 2 knots 0 0 0 1 1 2 2 3 3 4 4 4 controls {controls}}}"
    ));
    let Shape::Tube(tube) = &objects[0].shape else {
        panic!("not a tube: {:?}", objects[0].shape);
    };
    // The control points' box: x and z in [−√2/2, √2/2], y in [−1, 1].
    let extent = 8f64.sqrt();
    assert!(
        (tube.radius - 0.01 * extent).abs() < 1e-15,
        "{}",
        tube.radius
    );
    let start = Point3::new(s, 0.0, -s);
    assert!((tube.points[0] - start).norm() < 1e-15);
    assert!((tube.points[tube.points.len() - 1] - start).norm() < 1e-15);
    // Every flattening point is on the circle, in its plane; the pieces are
    // short enough to follow it to the flattening tolerance 1e-3 × extent
    // (a chord of length c is off the circle by about c²/8).
    for p in &tube.points {
        assert!((p.coords.norm() - 1.0).abs() < 1e-14, "{p}");
        assert!((p.x + p.z).abs() < 1e-15, "{p}");
    }
    for pair in tube.points.windows(2) {
        let chord = (pair[1] - pair[0]).norm();
        assert!(
            chord * chord / 8.0 <= 1e-3 * extent * 1.0001,
            "chord {chord}"
        );
    }
    assert!(tube.points.len() > 16, "{} points", tube.points.len());
}

/// The error of a group holding `RevSurface { profile CURVE }` on line 3
/// (the profile starts at column 22).
fn profile_error(curve: &str) -> crate::parse::ParseError {
    fail(&in_group(&format!("RevSurface {{ profile {curve} }}")))
}

/// The column of the `index`-th occurrence of `needle` in the profile
/// `curve` of [`profile_error`] (1-based, as the parser reports).
fn column_of(curve: &str, needle: &str, index: usize) -> usize {
    let start = curve
        .match_indices(needle)
        .nth(index)
        .unwrap_or_else(|| panic!("'{needle}' #{index} not in {curve}"))
        .0;
    "RevSurface { profile ".len() + start + 1
}

#[test]
fn weights_that_are_not_positive_are_refused_at_the_weight() {
    for weight in ["0", "-0", "-0.5", "-1e300"] {
        let curve = quarter(&format!(
            "degree 2 knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 2 0 {weight} ] [ 0 2 0 ]"
        ));
        let e = profile_error(&curve);
        let value: f64 = weight.parse().unwrap();
        let revolve = Nurbs::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Point2::new(2.0, 0.0),
                Point2::new(2.0, 2.0),
                Point2::new(0.0, 2.0),
            ],
            vec![1.0, value, 1.0],
        )
        .expect_err("revolve refuses the weight");
        assert!(matches!(revolve, Error::InvalidWeight { index: 1, .. }));
        assert_eq!(e.message, format!("invalid NurbsCurve: {revolve}"));
        let column = column_of(&curve, &format!("2 2 0 {weight}"), 0) + 6;
        assert_eq!((e.line, e.column), (3, column), "{e}");
    }
}

#[test]
fn weights_that_are_no_finite_number_are_refused_at_the_weight() {
    for (weight, message) in [
        ("NaN", "expected a number for 'weight', found 'NaN'"),
        ("inf", "expected a number for 'weight', found 'inf'"),
        ("1e999", "the number '1e999' for 'weight' is not finite"),
    ] {
        let curve = quarter(&format!(
            "degree 2 knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 2 0 {weight} ] [ 0 2 0 ]"
        ));
        let column = column_of(&curve, &format!("2 2 0 {weight}"), 0) + 6;
        assert_error(
            &in_group(&format!("RevSurface {{ profile {curve} }}")),
            3,
            column,
            message,
        );
    }
}

#[test]
fn a_weight_ratio_beyond_revolves_limit_is_refused() {
    let curve = quarter("degree 1 knots 0 0 1 1 controls [ 1 0 0 1e-5 ] [ 1 1 0 1e5 ]");
    let e = profile_error(&curve);
    let revolve = Nurbs::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0)],
        vec![1e-5, 1e5],
    )
    .expect_err("revolve refuses the ratio");
    assert!(matches!(revolve, Error::WeightRatioTooLarge { .. }));
    assert_eq!(e.message, format!("invalid NurbsCurve: {revolve}"));
    // At the curve's keyword: no one weight is to blame.
    assert_eq!((e.line, e.column), (3, column_of(&curve, "NurbsCurve", 0)));
}

#[test]
fn wrong_knot_counts_are_refused_at_the_knots_keyword() {
    for knots in ["0 0 0 1 1", "0 0 0 1 1 1 1", "0"] {
        let curve = quarter(&format!(
            "degree 2 knots {knots} controls [ 2 0 0 ] [ 2 2 0 {W} ] [ 0 2 0 ]"
        ));
        let e = profile_error(&curve);
        let found = knots.split_whitespace().count();
        let revolve = Error::KnotCount { expected: 6, found };
        assert_eq!(e.message, format!("invalid NurbsCurve: {revolve}"));
        assert_eq!((e.line, e.column), (3, column_of(&curve, "knots", 0)));
    }
}

#[test]
fn decreasing_knots_are_refused_at_the_knot() {
    let curve = quarter(&format!(
        "degree 2 knots 0 0 0.5 0.25 1 1 controls [ 2 0 0 ] [ 2 2 0 {W} ] [ 0 2 0 ]"
    ));
    let e = profile_error(&curve);
    let revolve = Error::DecreasingKnots { index: 3 };
    assert_eq!(e.message, format!("invalid NurbsCurve: {revolve}"));
    assert_eq!((e.line, e.column), (3, column_of(&curve, "0.25", 0)));
}

#[test]
fn a_control_point_revolve_refuses_is_named_at_its_bracket() {
    let curve = quarter(&format!(
        "degree 2 knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 1e200 0 {W} ] [ 0 2 0 ]"
    ));
    let e = profile_error(&curve);
    assert!(
        e.message.starts_with("invalid NurbsCurve: ") && e.message.contains("1e200"),
        "{e}"
    );
    assert_eq!((e.line, e.column), (3, column_of(&curve, "[", 1)));
}

#[test]
fn missing_fields_are_named_at_the_closing_brace() {
    for (fields, missing) in [
        (
            format!("knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 2 0 {W} ] [ 0 2 0 ]"),
            "degree",
        ),
        (
            format!("degree 2 controls [ 2 0 0 ] [ 2 2 0 {W} ] [ 0 2 0 ]"),
            "knots",
        ),
        ("degree 2 knots 0 0 0 1 1 1".to_string(), "controls"),
    ] {
        let curve = quarter(&fields);
        let closing = column_of(&curve, "}", 0);
        assert_error(
            &in_group(&format!("RevSurface {{ profile {curve} }}")),
            3,
            closing,
            &format!("NurbsCurve needs '{missing}'"),
        );
    }
}

#[test]
fn malformed_fields_are_located() {
    let cases: [(String, &str, usize, &str); 6] = [
        (
            quarter("degree 0 knots 0 0 1 1 controls [ 2 0 0 ] [ 0 2 0 ]"),
            "0",
            0,
            "expected a positive whole number for 'degree', found '0'",
        ),
        (
            quarter("degree 1.5 knots 0 0 1 1 controls [ 2 0 0 ] [ 0 2 0 ]"),
            "1.5",
            0,
            "expected a positive whole number for 'degree', found '1.5'",
        ),
        (
            quarter("degree 1 knots controls [ 2 0 0 ] [ 0 2 0 ]"),
            "controls",
            0,
            "expected a number for 'knots', found 'controls'",
        ),
        (
            quarter("degree 1 knots 0 0 1 1 controls [ 2 0 0 1 1 ] [ 0 2 0 ]"),
            "1 ]",
            0,
            "expected ']' closing the '[' at",
        ),
        (
            quarter("degree 1 degree 1 knots 0 0 1 1 controls [ 2 0 0 ] [ 0 2 0 ]"),
            "degree",
            1,
            "duplicate 'degree' in NurbsCurve",
        ),
        (
            quarter("degree 1 knots 0 0 1 1 weights 1 1 controls [ 2 0 0 ] [ 0 2 0 ]"),
            "weights",
            0,
            "unknown keyword 'weights' in NurbsCurve",
        ),
    ];
    for (curve, needle, index, message) in cases {
        let column = column_of(&curve, needle, index);
        assert_error(
            &in_group(&format!("RevSurface {{ profile {curve} }}")),
            3,
            column,
            message,
        );
    }
}

#[test]
fn a_nurbs_profile_lies_in_the_z0_plane() {
    let curve = quarter(&format!(
        "degree 2 knots 0 0 0 1 1 1 controls [ 2 0 0 ] [ 2 2 0.5 {W} ] [ 0 2 0 ]"
    ));
    assert_error(
        &in_group(&format!("RevSurface {{ profile {curve} }}")),
        3,
        column_of(&curve, "[", 1),
        "a RevSurface profile lies in the z = 0 plane, but this control point has z = 0.5",
    );
}

#[test]
fn only_a_nurbs_control_point_has_a_weight() {
    assert_error(
        &in_group("BezierCurve { controls [ 0 0 0 1 ] [ 1 1 1 ] }"),
        3,
        32,
        "expected ']' closing the '[' at 3:24, found '1'",
    );
    assert_error(
        &in_group("BezierCurve { degree 2 controls [ 0 0 0 ] [ 1 1 1 ] }"),
        3,
        15,
        "unknown keyword 'degree' in BezierCurve",
    );
}

#[test]
fn the_documented_example_is_a_half_circle() {
    // The first `NurbsCurve { … }` in a code block of the format's page.
    let page = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/scene-format.md"
    ));
    let start = page
        .find("```text\nNurbsCurve {")
        .expect("the page has a NurbsCurve example")
        + "```text\n".len();
    let end = start + page[start..].find("```").expect("the code block ends");
    let profile = profile_of(&page[start..end]);
    assert_eq!(profile.degree(), 2);
    assert_eq!(
        profile.weights(),
        &[1.0, FRAC_1_SQRT_2, 1.0, FRAC_1_SQRT_2, 1.0]
    );
    let (a, b) = profile.domain();
    assert_eq!(profile.eval(a), Point2::new(0.0, -1.0));
    assert_eq!(profile.eval(b), Point2::new(0.0, 1.0));
    for k in 0..=64 {
        let p = profile.eval(a + (b - a) * f64::from(k) / 64.0);
        assert!((p.coords.norm() - 1.0).abs() < 1e-15 && p.x >= 0.0, "{p}");
    }
}

//! `BezierSurface` and `BsplineSurface`: their fields land in revolve's
//! surfaces (polynomial, or rational when a point has a weight), and every
//! way they can be written wrong is reported where it is.

use std::f64::consts::FRAC_1_SQRT_2;

use revolve::nalgebra::Point3;
use revolve::{BSplineSurface, Error, ParameterDirection, Surface};

use super::{assert_error, fail, in_group, objects_of};
use crate::scene::{Shape, SurfaceBody};

/// `√2/2` as the scenes write it (17 digits: the same double).
const W: &str = "0.7071067811865476";

/// The surface of a group holding the one object `text`.
fn body_of(text: &str) -> SurfaceBody {
    let objects = objects_of(text);
    assert_eq!(objects.len(), 1);
    let Shape::Surface(body) = &objects[0].shape else {
        panic!("not a surface: {:?}", objects[0].shape);
    };
    (**body).clone()
}

/// The 1-based column of the `n`-th (0-based) occurrence of `needle` in
/// `line`.
fn column_of(line: &str, needle: &str, n: usize) -> usize {
    line.match_indices(needle)
        .nth(n)
        .unwrap_or_else(|| panic!("'{needle}' not in {line}"))
        .0
        + 1
}

/// A bilinear patch `S(u, v) = (u, v, u·v)`: corners row by row (`u` = 0
/// then 1).
const BILINEAR: &str = "rows 2 cols 2 controls [0 0 0] [0 1 0] [1 0 0] [1 1 1]";

#[test]
fn bezier_surface_reads_its_grid_row_by_row() {
    let SurfaceBody::Bezier(s) = body_of(&format!("BezierSurface {{ {BILINEAR} }}")) else {
        panic!("not a Bézier surface");
    };
    assert_eq!(s.degrees(), (1, 1));
    assert_eq!(
        s.points(),
        &[
            vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
            vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
        ]
    );
    for (u, v) in [(0.25, 0.5), (0.75, 0.125), (1.0, 0.0)] {
        assert!((s.eval(u, v) - Point3::new(u, v, u * v)).norm() < 1e-15);
    }
}

#[test]
fn surface_keys_come_in_any_order() {
    let a = body_of(&format!("BezierSurface {{ {BILINEAR} }}"));
    let b = body_of("BezierSurface { controls [0 0 0] [0 1 0] [1 0 0] [1 1 1] cols 2 rows 2 }");
    let (SurfaceBody::Bezier(a), SurfaceBody::Bezier(b)) = (a, b) else {
        panic!("not Bézier surfaces");
    };
    assert_eq!(a, b);
}

#[test]
fn a_weighted_bezier_surface_is_rational() {
    // A quarter of the unit cylinder: the rational quadratic quarter circle
    // (middle weight √2/2) along u, a straight line in z along v; [x y z]
    // has weight 1.
    let body = body_of(&format!(
        "BezierSurface {{ rows 3 cols 2 controls [1 0 0] [1 0 2] [1 1 0 {W}] [1 1 2 {W}] \
         [0 1 0 1] [0 1 2] }}"
    ));
    let SurfaceBody::Nurbs(s) = body else {
        panic!("not rational");
    };
    assert_eq!(s.degrees(), (2, 1));
    assert_eq!(
        s.weights(),
        &[vec![1.0, 1.0], vec![FRAC_1_SQRT_2; 2], vec![1.0, 1.0]]
    );
    for k in 0..=16 {
        let u = f64::from(k) / 16.0;
        let p = s.eval(u, 0.75);
        assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-14, "{p}");
        assert!((p.z - 1.5).abs() < 1e-14, "{p}");
    }
}

#[test]
fn bspline_surface_reads_degrees_knots_and_points() {
    // Biquadratic in u over two spans, linear in v: a 3 × 2 grid.
    let body = body_of(
        "BsplineSurface { uDegree 2 vDegree 1 uKnots 0 0 0 1 1 1 vKnots 0 0 2 2 rows 3 cols 2 \
         controls [0 0 0] [0 2 0] [1 0 1] [1 2 1] [2 0 0] [2 2 0] }",
    );
    let SurfaceBody::BSpline(s) = body else {
        panic!("not a polynomial B-spline surface");
    };
    let expected = BSplineSurface::new(
        (2, 1),
        (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 2.0, 2.0]),
        vec![
            vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 2.0, 0.0)],
            vec![Point3::new(1.0, 0.0, 1.0), Point3::new(1.0, 2.0, 1.0)],
            vec![Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 2.0, 0.0)],
        ],
    )
    .unwrap();
    assert_eq!(s, expected);
    // A parabolic cylinder: x = 2u, z = 2u(1 − u), y = v.
    let p = s.eval(0.25, 0.5);
    assert!((p - Point3::new(0.5, 0.5, 0.375)).norm() < 1e-15, "{p}");
}

#[test]
fn a_weighted_bspline_surface_is_rational() {
    let body = body_of(&format!(
        "BsplineSurface {{ uDegree 2 vDegree 1 uKnots 0 0 0 1 1 1 vKnots 0 0 1 1 rows 3 cols 2 \
         controls [2 0 0] [2 0 1] [2 2 0 {W}] [2 2 1 {W}] [0 2 0] [0 2 1] }}"
    ));
    let SurfaceBody::Nurbs(s) = body else {
        panic!("not rational");
    };
    assert_eq!(s.degrees(), (2, 1));
    // The quarter cylinder of radius 2.
    for k in 0..=8 {
        let p = s.eval(f64::from(k) / 8.0, 0.5);
        assert!((p.x.hypot(p.y) - 2.0).abs() < 1e-14, "{p}");
    }
}

#[test]
fn too_few_control_points_are_refused_at_controls() {
    // Ragged: one row short of its last point.
    let line = "BezierSurface { rows 2 cols 3 controls [0 0 0] [0 1 0] [0 2 0] [1 0 0] [1 1 0] }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "controls", 0),
        "BezierSurface needs rows 2 × cols 3 = 6 control points, found 5",
    );
}

#[test]
fn too_many_control_points_are_refused_at_the_first_extra_one() {
    let line = "BezierSurface { rows 2 cols 2 controls [0 0 0] [0 1 0] [1 0 0] [1 1 1] [2 2 2] }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "[", 4),
        "BezierSurface has rows 2 × cols 2 = 4 control points, but this is control point 5",
    );
}

/// One rule with revolve's constructors: a surface of one row or one
/// column is accepted (it is a curve); zero rows is refused at the count.
#[test]
fn one_row_or_column_is_accepted_and_zero_refused() {
    for line in [
        "BezierSurface { rows 1 cols 2 controls [0 0 0] [0 1 0] }",
        "BezierSurface { rows 2 cols 1 controls [0 0 0] [1 0 0] }",
    ] {
        assert_eq!(objects_of(line).len(), 1, "{line}");
    }
    let line = "BezierSurface { rows 0 cols 2 controls }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "0", 0),
        "expected a positive whole number for 'rows', found '0'",
    );
}

#[test]
fn weights_that_are_not_positive_are_refused_at_the_weight() {
    for weight in ["0", "-1", "-0"] {
        let line = format!(
            "BezierSurface {{ rows 2 cols 2 controls [0 0 0] [0 1 0] [1 0 0 {weight}] [1 1 1] }}"
        );
        let e = fail(&in_group(&line));
        let column = column_of(&line, &format!("1 0 0 {weight}"), 0) + 6;
        assert_eq!((e.line, e.column), (3, column), "{e}");
        assert!(
            e.message
                .starts_with("invalid BezierSurface: the surface's weight at row 1, column 0 is "),
            "{e}"
        );
    }
}

#[test]
fn numbers_that_are_not_finite_are_refused_where_they_are() {
    for (text, message) in [
        ("NaN", "expected a number for 'controls', found 'NaN'"),
        ("1e999", "the number '1e999' for 'controls' is not finite"),
    ] {
        let line = format!(
            "BezierSurface {{ rows 2 cols 2 controls [0 0 0] [0 {text} 0] [1 0 0] [1 1 1] }}"
        );
        assert_error(&in_group(&line), 3, column_of(&line, text, 0), message);
    }
    let line = "BezierSurface { rows 2 cols 2 controls [0 0 0] [0 1 0] [1 0 0 NaN] [1 1 1] }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "NaN", 0),
        "expected a number for 'weight', found 'NaN'",
    );
}

#[test]
fn a_coordinate_beyond_revolves_range_is_refused_at_its_point() {
    let line = "BezierSurface { rows 2 cols 2 controls [0 0 0] [0 1 0] [1 0 0] [1 1 1e101] }";
    let e = fail(&in_group(line));
    assert_eq!((e.line, e.column), (3, column_of(line, "[", 3)), "{e}");
    assert!(e.message.starts_with("invalid BezierSurface: "), "{e}");
}

#[test]
fn a_control_point_with_five_numbers_is_refused() {
    let line = "BezierSurface { rows 2 cols 2 controls [0 0 0 1 2] [0 1 0] [1 0 0] [1 1 1] }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "2]", 0),
        "expected ']' closing the '['",
    );
}

/// A 3 × 2 biquadratic-by-linear `BsplineSurface` with the given knots.
fn spline(u_knots: &str, v_knots: &str) -> String {
    format!(
        "BsplineSurface {{ uDegree 2 vDegree 1 uKnots {u_knots} vKnots {v_knots} rows 3 cols 2 \
         controls [0 0 0] [0 1 0] [1 0 1] [1 1 1] [2 0 0] [2 1 0] }}"
    )
}

#[test]
fn a_wrong_knot_count_is_refused_at_its_knot_vector() {
    let line = spline("0 0 0 1 1", "0 0 1 1");
    let e = fail(&in_group(&line));
    assert_eq!(
        (e.line, e.column),
        (3, column_of(&line, "uKnots", 0)),
        "{e}"
    );
    assert_eq!(
        e.message,
        format!(
            "invalid BsplineSurface: {}",
            Error::SurfaceKnots {
                direction: ParameterDirection::U,
                error: Box::new(Error::KnotCount {
                    expected: 6,
                    found: 5
                })
            }
        )
    );
    let line = spline("0 0 0 1 1 1", "0 0 1 1 1");
    let e = fail(&in_group(&line));
    assert_eq!(
        (e.line, e.column),
        (3, column_of(&line, "vKnots", 0)),
        "{e}"
    );
    assert_eq!(
        e.message,
        format!(
            "invalid BsplineSurface: {}",
            Error::SurfaceKnots {
                direction: ParameterDirection::V,
                error: Box::new(Error::KnotCount {
                    expected: 4,
                    found: 5
                })
            }
        )
    );
}

#[test]
fn a_decreasing_knot_is_refused_at_the_knot() {
    let line = spline("0 0 0 1 1 1", "0 0.5 0.25 1");
    let e = fail(&in_group(&line));
    assert_eq!((e.line, e.column), (3, column_of(&line, "0.25", 0)), "{e}");
    assert!(
        e.message.starts_with(
            "invalid BsplineSurface: the surface's v knots: knots must be non-decreasing"
        ),
        "{e}"
    );
}

#[test]
fn a_degree_too_high_for_the_rows_is_refused_at_the_degree() {
    let line = "BsplineSurface { uDegree 3 vDegree 1 uKnots 0 0 0 0 1 1 1 vKnots 0 0 1 1 rows 3 \
                cols 2 controls [0 0 0] [0 1 0] [1 0 1] [1 1 1] [2 0 0] [2 1 0] }";
    let e = fail(&in_group(line));
    assert_eq!((e.line, e.column), (3, column_of(line, "3", 0)), "{e}");
    assert!(
        e.message
            .starts_with("invalid BsplineSurface: the surface's u knots: "),
        "{e}"
    );
}

#[test]
fn missing_and_misplaced_keys_are_refused() {
    let line = "BsplineSurface { uDegree 2 vDegree 1 uKnots 0 0 0 1 1 1 rows 3 cols 2 controls }";
    assert_error(
        &in_group(line),
        3,
        column_of(line, "}", 0),
        "BsplineSurface needs 'vKnots'",
    );
    let line = format!("BezierSurface {{ uDegree 2 {BILINEAR} }}");
    assert_error(
        &in_group(&line),
        3,
        column_of(&line, "uDegree", 0),
        "unknown keyword 'uDegree' in BezierSurface",
    );
    let line = format!("BezierSurface {{ {BILINEAR} rows 2 }}");
    assert_error(
        &in_group(&line),
        3,
        column_of(&line, "rows", 1),
        "duplicate 'rows' in BezierSurface",
    );
}

#[test]
fn the_documented_examples_parse() {
    // The two surface blocks of docs/scene-format.md, verbatim.
    let objects = objects_of(
        "BezierSurface {
    rows 2  cols 3
    controls [0 0 0] [0 1 1] [0 2 0]      # row 0 (u = 0), along v
             [1 0 1] [1 1 2] [1 2 1]      # row 1 (u = 1)
}
BsplineSurface {
    uDegree 2  vDegree 1
    uKnots 0 0 0 1 1 1  vKnots 0 0 1 1
    rows 3  cols 2
    controls [1 0 0] [1 0 2]
             [1 1 0 0.7071067811865476] [1 1 2 0.7071067811865476]
             [0 1 0] [0 1 2]             # a quarter of the unit cylinder
}",
    );
    let kinds: Vec<&str> = objects
        .iter()
        .map(|o| match &o.shape {
            Shape::Surface(body) => match **body {
                SurfaceBody::Bezier(_) => "Bezier",
                SurfaceBody::Nurbs(_) => "Nurbs",
                _ => "other",
            },
            _ => "not a surface",
        })
        .collect();
    assert_eq!(kinds, ["Bezier", "Nurbs"]);
}

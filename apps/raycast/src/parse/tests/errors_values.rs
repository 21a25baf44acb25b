//! Errors of values: numbers, sizes, directions, named values, indices and
//! revolve's checks of curves.

use revolve::nalgebra::{Point2, Point3};
use revolve::{BSpline, Bezier};

use super::{CAMERA, assert_error, fail, in_group};

#[test]
fn expected_a_number() {
    assert_error(
        &in_group("Sphere { center 0 0 0 radius abc }"),
        3,
        30,
        "expected a number for 'radius', found 'abc'",
    );
}

#[test]
fn non_finite_number() {
    assert_error(
        &in_group("Sphere { center 0 0 0 radius 1e999 }"),
        3,
        30,
        "the number '1e999' for 'radius' is not finite",
    );
    assert_error(
        &in_group("Sphere { center 0 0 0 radius nan }"),
        3,
        30,
        "expected a number for 'radius', found 'nan'",
    );
}

#[test]
fn negative_and_zero_radius() {
    assert_error(
        &in_group("Sphere { center 0 0 0 radius -1 }"),
        3,
        30,
        "'radius' must be positive, found -1",
    );
    assert_error(
        &in_group("Sphere { center 0 0 0 radius 0 }"),
        3,
        30,
        "'radius' must be positive, found 0",
    );
}

#[test]
fn zero_scale() {
    let sphere = "Sphere { center 0 0 0 radius 1 }";
    assert_error(
        &in_group(&format!("Transform {{ Scale 1 0 1 {sphere} }}")),
        3,
        19,
        "'Scale' must not be zero in any coordinate",
    );
    assert_error(
        &in_group(&format!("Transform {{ UniformScale 0 {sphere} }}")),
        3,
        26,
        "'UniformScale' must not be zero",
    );
}

#[test]
fn zero_rotation_axis() {
    assert_error(
        &in_group("Transform { Rotate { 0 0 0 90 } Sphere { center 0 0 0 radius 1 } }"),
        3,
        22,
        "'Rotate' must not be the zero vector",
    );
}

#[test]
fn zero_normal() {
    assert_error(
        &in_group("Plane { normal 0 0 0 offset 1 }"),
        3,
        16,
        "'normal' must not be the zero vector",
    );
}

#[test]
fn box_with_zero_or_negative_size() {
    assert_error(
        &in_group("Box { min 0 0 0 max 1 0 1 }"),
        3,
        21,
        "the box's 'max' must exceed its 'min' in every coordinate",
    );
}

#[test]
fn ring_with_inner_not_below_outer() {
    assert_error(
        &in_group("Ring { center 0 0 0 normal 0 1 0 inner 2 outer 1 }"),
        3,
        48,
        "the ring's 'outer' radius 1 must exceed its 'inner' radius 2",
    );
}

#[test]
fn rectangle_with_parallel_edges() {
    assert_error(
        &in_group("Rectangle { corner 0 0 0 edge1 1 0 0 edge2 2 0 0 }"),
        3,
        44,
        "'edge1' and 'edge2' are parallel",
    );
}

#[test]
fn area_light_with_parallel_edges() {
    let text = format!(
        "{CAMERA}Lights {{\nAreaLight {{ corner 0 0 0 edge1 1 0 0 edge2 -3 0 0 color 1 1 1 }} }}"
    );
    assert_error(&text, 3, 44, "'edge1' and 'edge2' are parallel");
}

#[test]
fn triangle_without_area() {
    assert_error(
        &in_group("Triangle { vertex0 0 0 0 vertex1 1 1 1 vertex2 2 2 2 }"),
        3,
        1,
        "the triangle has no area",
    );
}

#[test]
fn camera_up_parallel_to_direction() {
    assert_error(
        "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 0 2 angle 45 width 4 height 3 }",
        1,
        55,
        "'up' must not be parallel to 'direction'",
    );
}

#[test]
fn camera_angle_out_of_range() {
    assert_error(
        "PerspectiveCamera {\n angle 180\n}",
        2,
        8,
        "'angle' must be between 0 and 180 degrees",
    );
}

#[test]
fn camera_size_not_a_positive_whole_number() {
    assert_error(
        "PerspectiveCamera {\n width 2.5\n}",
        2,
        8,
        "expected a positive whole number for 'width', found '2.5'",
    );
    assert_error(
        "PerspectiveCamera {\n height 0\n}",
        2,
        9,
        "expected a positive whole number for 'height', found '0'",
    );
}

#[test]
fn negative_colour() {
    assert_error(
        &format!("{CAMERA}Background {{ color 0.1 -0.2 0.3 }}"),
        2,
        24,
        "'color' must not be negative, found -0.2",
    );
}

#[test]
fn unknown_render_values() {
    assert_error(
        &format!("{CAMERA}Render {{ integrator photon }}"),
        2,
        21,
        "expected 'whitted' or 'path' for 'integrator', found 'photon'",
    );
    assert_error(
        &format!("{CAMERA}Render {{ shadows yes }}"),
        2,
        18,
        "expected 'true' or 'false' for 'shadows', found 'yes'",
    );
    assert_error(
        &format!("{CAMERA}Render {{ toneMap aces }}"),
        2,
        18,
        "expected 'clamp' or 'reinhard' for 'toneMap', found 'aces'",
    );
    assert_error(
        &format!("{CAMERA}Render {{ samples 0 }}"),
        2,
        18,
        "expected a positive whole number for 'samples', found '0'",
    );
}

#[test]
fn material_index_out_of_range() {
    let text = format!(
        "{CAMERA}Materials {{ Material {{ }} Material {{ }} }}\nGroup {{ MaterialIndex 2 Sphere {{ center 0 0 0 radius 1 }} }}"
    );
    assert_error(
        &text,
        3,
        23,
        "MaterialIndex 2, but the scene defines 2 materials (indices 0 to 1)",
    );
    let text = format!("{CAMERA}Group {{ MaterialIndex 1 Sphere {{ center 0 0 0 radius 1 }} }}");
    assert_error(&text, 2, 23, "the scene defines no materials");
    assert_error(
        &in_group("MaterialIndex -1"),
        3,
        15,
        "expected a whole number for 'MaterialIndex', found '-1'",
    );
}

#[test]
fn rev_surface_profile_off_the_plane() {
    assert_error(
        &in_group("RevSurface { profile BezierCurve { controls [ 1 0 0 ]\n [ 1 1 0.5 ] } }"),
        4,
        2,
        "a RevSurface profile lies in the z = 0 plane, but this control point has z = 0.5",
    );
}

#[test]
fn revolve_rejects_a_bspline_with_too_few_points() {
    let e = fail(&in_group(
        "RevSurface { profile\n  BsplineCurve { controls [ 1 0 0 ] [ 1 1 0 ] [ 2 2 0 ] } }",
    ));
    assert_eq!((e.line, e.column), (4, 3), "{e}");
    let revolve = BSpline::uniform(3, vec![Point2::new(1.0, 0.0); 3])
        .expect_err("revolve rejects three points");
    assert_eq!(e.message, format!("invalid BsplineCurve: {revolve}"));
}

#[test]
fn revolve_rejects_a_curve_without_control_points() {
    let e = fail(&in_group("BezierCurve { controls }"));
    assert_eq!((e.line, e.column), (3, 1), "{e}");
    let revolve = Bezier::<3>::new(Vec::new()).expect_err("revolve rejects no points");
    assert_eq!(e.message, format!("invalid BezierCurve: {revolve}"));
}

#[test]
fn revolve_rejects_huge_coordinates() {
    let e = fail(&in_group(
        "  BezierCurve { controls [ 1e200 0 0 ] [ 0 0 0 ] }",
    ));
    // At the control point revolve names.
    assert_eq!((e.line, e.column), (3, 26), "{e}");
    let revolve = Bezier::new(vec![Point3::new(1e200, 0.0, 0.0), Point3::origin()])
        .expect_err("revolve rejects 1e200");
    assert_eq!(e.message, format!("invalid BezierCurve: {revolve}"));
}

#[test]
fn tube_of_coincident_points() {
    assert_error(
        &in_group("BsplineCurve { controls [1 1 1] [1 1 1] [1 1 1] [1 1 1] }"),
        3,
        1,
        "the BsplineCurve's control points all coincide",
    );
}

#[test]
fn reflectances_are_fractions_of_the_light() {
    // Line 2 column 32 is the second component of the colour.
    for key in [
        "diffuseColor",
        "specularColor",
        "reflectivity",
        "transparency",
    ] {
        let text = format!("{CAMERA}Materials {{ Material {{ {key} 1 1.5 0 }} }}");
        let column = text.lines().nth(1).unwrap().find("1.5").unwrap() + 1;
        assert_error(
            &text,
            2,
            column,
            &format!("'{key}' is a fraction of the light, at most 1, found 1.5"),
        );
    }
    // 1 itself is allowed, and absorption is a rate: any finite value.
    let scene = super::parse(&format!(
        "{CAMERA}Materials {{ Material {{ transparency 1 1 1 absorption 1e308 0 0 }} }}"
    ));
    assert_eq!(scene.materials[0].absorption.x, 1e308);
}

#[test]
fn radiances_are_at_most_1e100() {
    let text = format!("{CAMERA}Lights {{ PointLight {{ position 0 0 0 color 1 1 1e101 }} }}");
    assert_error(
        &text,
        2,
        48,
        "'color' is a radiance, at most 1e100, found 1e101",
    );
    let text = format!("{CAMERA}Materials {{ Material {{ emission 2e100 0 0 }} }}");
    assert_error(
        &text,
        2,
        33,
        "'emission' is a radiance, at most 1e100, found 2e100",
    );
    let scene = super::parse(&format!("{CAMERA}Background {{ color 1e100 5 0 }}"));
    assert_eq!(scene.background.x, 1e100);
}

#[test]
fn tiny_and_huge_numbers_print_in_exponent_form() {
    assert_error(
        &format!("{CAMERA}Background {{ color -1e-320 0 0 }}"),
        2,
        20,
        "'color' must not be negative, found -1e-320",
    );
}

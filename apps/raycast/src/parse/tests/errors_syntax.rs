//! Errors of structure: braces, keywords, counts, missing and repeated keys.

use super::{CAMERA, assert_error, fail, in_group};

#[test]
fn display_is_file_line_column_message() {
    let e = fail("PerspectiveCamera\n  center 0 0 10");
    assert_eq!(
        e.to_string(),
        "test.txt:2:3: expected '{' after PerspectiveCamera, found 'center'"
    );
}

#[test]
fn missing_open_brace() {
    assert_error(
        "PerspectiveCamera\n  center 0 0 10",
        2,
        3,
        "expected '{' after PerspectiveCamera, found 'center'",
    );
}

#[test]
fn unknown_keyword_in_group_with_suggestion() {
    let text = in_group("  Shpere { center 0 0 0 radius 1 }");
    assert_error(&text, 3, 3, "unknown keyword 'Shpere' in Group");
    assert_error(&text, 3, 3, "(did you mean 'Sphere'?)");
}

#[test]
fn unknown_keyword_lists_what_is_expected() {
    assert_error(
        &in_group("Cylinder { }"),
        3,
        1,
        "unknown keyword 'Cylinder' in Group; expected one of Group, Transform, Sphere",
    );
}

#[test]
fn unknown_top_level_keyword() {
    assert_error(
        &format!("{CAMERA}Objects {{ }}"),
        2,
        1,
        "unknown keyword 'Objects' in the scene file",
    );
}

#[test]
fn top_level_token_that_is_no_keyword() {
    assert_error("{ }", 1, 1, "expected a block keyword");
    assert_error(&format!("{CAMERA}\n  42"), 3, 3, "found '42'");
}

#[test]
fn missing_close_brace_at_end_of_file() {
    let text = format!("{CAMERA}Group {{\nBox {{\n min 0 0 0 max 1 1 1\n");
    assert_error(&text, 5, 1, "missing '}' (the block opened at 3:5)");
}

#[test]
fn premature_end_inside_a_value() {
    assert_error(
        &format!("{CAMERA}Group {{ Sphere {{ center 0 0"),
        2,
        28,
        "expected a number for 'center', found end of file",
    );
}

#[test]
fn number_where_a_keyword_belongs() {
    assert_error(
        &in_group("Sphere { 1 2 3 }"),
        3,
        10,
        "expected a keyword or '}' in Sphere, found '1'",
    );
}

#[test]
fn block_keyword_inside_another_block_hints_at_a_missing_brace() {
    let text = in_group("Sphere { center 0 0 0 radius 1\nPlane { normal 0 1 0 offset 0 }");
    assert_error(&text, 4, 1, "unknown keyword 'Plane' in Sphere");
    assert_error(&text, 4, 1, "is a '}' missing?");
}

#[test]
fn duplicate_key() {
    assert_error(
        &in_group("Sphere { radius 1 center 0 0 0 radius 2 }"),
        3,
        32,
        "duplicate 'radius' in Sphere",
    );
}

#[test]
fn duplicate_block() {
    assert_error(
        &format!("{CAMERA}{CAMERA}"),
        2,
        1,
        "a second PerspectiveCamera block (the first is at 1:1)",
    );
}

#[test]
fn required_key_missing_points_at_the_closing_brace() {
    assert_error(
        &in_group("Sphere { center 0 0 0 }"),
        3,
        23,
        "Sphere needs 'radius'",
    );
}

#[test]
fn missing_camera_is_about_the_whole_file() {
    assert_error("Group { }", 0, 0, "no PerspectiveCamera");
}

#[test]
fn num_objects_larger_than_the_group() {
    let text = in_group(
        "numObjects 3\nSphere { center 0 0 0 radius 1 }\nMaterialIndex 0\nSphere { center 0 0 0 radius 1 }",
    );
    assert_error(
        &text,
        3,
        12,
        "numObjects is 3 but the group holds 2 objects",
    );
}

#[test]
fn num_objects_smaller_than_the_group() {
    let text = in_group(
        "numObjects 1\nSphere { center 0 0 0 radius 1 }\nSphere { center 0 0 0 radius 1 }",
    );
    assert_error(
        &text,
        3,
        12,
        "numObjects is 1 but the group holds 2 objects",
    );
}

#[test]
fn num_lights_mismatch() {
    let text = format!(
        "{CAMERA}Lights {{\n  numLights 2\n  PointLight {{ position 0 0 0 color 1 1 1 }}\n}}"
    );
    assert_error(&text, 3, 13, "numLights is 2 but the block holds 1 light");
}

#[test]
fn num_materials_mismatch() {
    let text = format!("{CAMERA}Materials {{ numMaterials 1 Material {{ }} Material {{ }} }}");
    assert_error(
        &text,
        2,
        26,
        "numMaterials is 1 but the block holds 2 materials",
    );
}

#[test]
fn transform_without_an_object() {
    assert_error(
        &in_group("Transform { Translate 1 0 0 }"),
        3,
        29,
        "a Transform holds exactly one object, but this one holds none",
    );
}

#[test]
fn transform_with_two_objects() {
    let text = in_group(
        "Transform {\n Sphere { center 0 0 0 radius 1 }\n Sphere { center 0 0 0 radius 1 } }",
    );
    assert_error(&text, 5, 2, "a Transform holds exactly one object");
    assert_error(&text, 5, 2, "follows 'Sphere' at 4:2");
}

#[test]
fn transformation_after_the_object() {
    assert_error(
        &in_group("Transform { Sphere { center 0 0 0 radius 1 } Scale 1 2 1 }"),
        3,
        46,
        "transformations come first",
    );
}

#[test]
fn material_index_directly_in_a_transform() {
    assert_error(
        &in_group("Transform { MaterialIndex 0 Sphere { center 0 0 0 radius 1 } }"),
        3,
        13,
        "MaterialIndex belongs in a Group",
    );
}

#[test]
fn missing_close_bracket() {
    assert_error(
        &in_group("BezierCurve { controls [ 0 0 0 [ 1 1 1 ] }"),
        3,
        32,
        "expected ']' closing the '[' at 3:24, found '['",
    );
}

#[test]
fn profile_that_is_no_curve() {
    assert_error(
        &in_group("RevSurface { profile Sphere { } }"),
        3,
        22,
        "expected BezierCurve, BsplineCurve or NurbsCurve after 'profile', found 'Sphere'",
    );
}

#[test]
fn unknown_render_key() {
    assert_error(
        &format!("{CAMERA}Render {{ sample 4 }}"),
        2,
        10,
        "unknown keyword 'sample' in Render (did you mean 'samples'?)",
    );
}

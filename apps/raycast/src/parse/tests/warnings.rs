//! Warnings: valid input that is most likely a mistake parses, with a
//! located warning (the field of view in radians).

use std::path::Path;

use super::super::parse_str_with_warnings;
use super::{CAMERA, parse};

/// A camera line with the field of view `angle` (written as given).
fn camera_with_angle(angle: &str) -> String {
    CAMERA.replace("angle 45", &format!("angle {angle}"))
}

#[test]
fn an_angle_under_two_degrees_warns_at_its_value_with_the_degrees_it_means() {
    let text = camera_with_angle("0.7");
    let parsed = parse_str_with_warnings(&text, Path::new("test.txt")).unwrap();
    assert_eq!(parsed.scene.camera.angle_degrees, 0.7);
    assert_eq!(parsed.warnings.len(), 1);
    let w = &parsed.warnings[0];
    let column = text.find("0.7").unwrap() + 1;
    assert_eq!((w.line, w.column), (1, column));
    // 0.7 rad = 0.7 · 180/π = 40.107°.
    assert_eq!(
        w.to_string(),
        format!(
            "test.txt:1:{column}: warning: angle 0.7 is under 2 degrees; the angle is in degrees \
             (0.7 rad = 40.1°)"
        )
    );
}

#[test]
fn the_warning_quotes_the_number_as_written() {
    let parsed =
        parse_str_with_warnings(&camera_with_angle("1.5e0"), Path::new("test.txt")).unwrap();
    assert_eq!(
        parsed.warnings[0].message,
        "angle 1.5e0 is under 2 degrees; the angle is in degrees (1.5e0 rad = 85.9°)"
    );
}

#[test]
fn angles_from_two_degrees_on_do_not_warn() {
    for angle in ["2", "2.0", "45", "179.9"] {
        let parsed =
            parse_str_with_warnings(&camera_with_angle(angle), Path::new("test.txt")).unwrap();
        assert!(
            parsed.warnings.is_empty(),
            "angle {angle}: {:?}",
            parsed.warnings
        );
    }
    let parsed =
        parse_str_with_warnings(&camera_with_angle("1.999"), Path::new("test.txt")).unwrap();
    assert_eq!(parsed.warnings.len(), 1);
}

#[test]
fn parse_str_keeps_the_scene_of_a_warned_file() {
    assert_eq!(parse(&camera_with_angle("0.7")).camera.angle_degrees, 0.7);
}

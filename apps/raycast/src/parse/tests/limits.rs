//! The limits that keep hostile files from exhausting the stack: nesting
//! depth of groups and transforms, and the render depth.

use super::{CAMERA, assert_error, in_group, parse};
use crate::effects::{MAX_DEPTH, MAX_SAMPLES};
use crate::parse::MAX_NESTING;

/// `levels` blocks opened by `open` (their keyword, `{` and any steps)
/// nested inside the top-level group (so the innermost is at depth
/// `levels + 1`), the innermost holding a sphere.
fn nested(levels: usize, open: &str) -> String {
    let sphere = "Sphere { center 0 0 0 radius 1 }";
    format!(
        "{}{sphere}{}",
        format!("{open} ").repeat(levels),
        " }".repeat(levels)
    )
}

#[test]
fn groups_and_transforms_nest_up_to_the_limit() {
    for open in ["Group {", "Transform { Translate 0 0 1"] {
        // The top-level group is depth 1.
        let scene = parse(&in_group(&nested(MAX_NESTING - 1, open)));
        assert_eq!(scene.objects.len(), 1);
    }
    let scene = parse(&in_group(&nested(
        MAX_NESTING - 1,
        "Transform { Translate 0 0 1",
    )));
    let m = scene.objects[0].transform.unwrap();
    // The translations compose: 199 units along z.
    assert_eq!(m[(2, 3)], (MAX_NESTING - 1) as f64);
}

#[test]
fn one_level_deeper_is_an_error_at_its_keyword() {
    let text = in_group(&nested(MAX_NESTING, "Group {"));
    // Line 3 holds the nested groups: "Group { " is 8 characters, so the
    // 200th nested one starts at column 8·199 + 1.
    assert_error(
        &text,
        3,
        8 * (MAX_NESTING - 1) + 1,
        "this Group is nested more than 200 deep",
    );
}

#[test]
fn seventeen_thousand_nested_groups_are_an_error_not_a_stack_overflow() {
    // Parsed on a thread with a small stack: the bound, not luck, keeps the
    // recursion shallow.
    let text = in_group(&nested(17_000, "Group {"));
    let error = std::thread::Builder::new()
        .stack_size(512 * 1024)
        .spawn(move || super::fail(&text))
        .unwrap()
        .join()
        .unwrap();
    assert!(
        error.message.contains("nested more than 200 deep"),
        "{error}"
    );
    let text = in_group(&nested(17_000, "Transform { UniformScale 2"));
    let error = std::thread::Builder::new()
        .stack_size(512 * 1024)
        .spawn(move || super::fail(&text))
        .unwrap()
        .join()
        .unwrap();
    assert!(
        error
            .message
            .contains("this Transform is nested more than 200 deep"),
        "{error}"
    );
}

#[test]
fn the_deepest_accepted_nesting_parses_and_renders_on_a_small_stack() {
    let text = in_group(&nested(MAX_NESTING - 1, "Transform { XRotate 1"));
    let image = std::thread::Builder::new()
        .stack_size(512 * 1024)
        .spawn(move || {
            let scene = parse(&text);
            crate::render::render(&scene, &crate::render::Options::default())
                .map(|(image, _)| image)
        })
        .unwrap()
        .join()
        .unwrap()
        .unwrap();
    assert_eq!(image.pixels.len(), 40 * 30);
}

#[test]
fn max_depth_is_bounded() {
    let ok = parse(&format!("{CAMERA}Render {{ maxDepth {MAX_DEPTH} }}"));
    assert_eq!(ok.render.max_depth, Some(MAX_DEPTH));
    assert_error(
        &format!("{CAMERA}Render {{ maxDepth 4000000000 }}"),
        2,
        19,
        "'maxDepth' is 4000000000, more than the largest, 100",
    );
}

#[test]
fn samples_are_bounded() {
    let ok = parse(&format!("{CAMERA}Render {{ samples {MAX_SAMPLES} }}"));
    assert_eq!(ok.render.samples, Some(MAX_SAMPLES));
    // 1e9 samples a pixel of a 640 × 480 image would be 3·10¹⁴ rays.
    assert_error(
        &format!("{CAMERA}Render {{ samples 1e9 }}"),
        2,
        18,
        "'samples' is 1000000000, more than the largest, 65536",
    );
}

#[test]
fn image_sides_are_bounded_at_their_value() {
    let camera = |w: &str, h: &str| {
        CAMERA
            .replace("width 40", &format!("width {w}"))
            .replace("height 30", &format!("height {h}"))
    };
    let column = |text: &str, key: &str| text.find(key).unwrap() + key.len() + 2;
    let text = camera("1e9", "30");
    assert_error(
        &text,
        1,
        column(&text, "width"),
        "'width' is 1000000000 pixels, more than the largest side, 16384",
    );
    let text = camera("40", "16385");
    assert_error(
        &text,
        1,
        column(&text, "height"),
        "more than the largest side",
    );
    // Both sides allowed, the pixel count not: at the size given last.
    let text = camera("16384", "16384");
    assert_error(
        &text,
        1,
        column(&text, "height"),
        "16384×16384 = 268435456 pixels, more than the largest, 33554432",
    );
    let ok = parse(&camera("8192", "4096"));
    assert_eq!((ok.camera.width, ok.camera.height), (8192, 4096));
}

#[test]
fn a_texture_wider_than_the_limit_is_refused_by_the_decoder() {
    let dir = super::TempDir::new("wide-texture");
    let png = dir.0.join("wide.png");
    crate::png_file::write_raw(&png, 16385, 1, png::ColorType::Rgb, &vec![0; 3 * 16385]).unwrap();
    let text = format!("{CAMERA}Materials {{ Material {{ texture wide.png }} }}\n");
    let e = dir.parse_scene(&text).unwrap_err();
    assert_eq!((e.line, e.column), (2, 32));
    assert!(e.message.contains("cannot read texture 'wide.png'"), "{e}");
    assert!(e.message.to_lowercase().contains("limit"), "{e}");
}

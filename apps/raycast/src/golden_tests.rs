//! Golden images: every bundled base-format scene renders as it did when its
//! reference image in `scenes/golden/` was made.
//!
//! A base-format scene traces primary rays only, with one sample per pixel
//! and no randomness, so the render is deterministic up to floating-point
//! differences between platforms (libm's trigonometry, fused multiply-adds).
//! Those move a channel by at most a code value or two, and only on a few
//! pixels where a ray grazes a silhouette or a shading term crosses a
//! rounding boundary. So a scene passes when at most 0.5% of its pixels
//! differ by more than 2/255 in any channel, and no more than 0.1% by more
//! than 64/255. A change in geometry, shading or the camera moves whole
//! regions and fails both.
//!
//! Regenerate after an intended change with
//! `cargo run --release -p raycast -- scenes/NAME.txt -o scenes/golden/NAME.png`
//! (from the repository's root)
//! and look at the difference before committing.

use std::path::PathBuf;

use crate::effects::Effects;
use crate::image_out::to_rgb8;
use crate::parse::parse_file;
use crate::png_file::{self, Rgb8};
use crate::render::{Options, render};

/// The bundled scenes in the base format (the showcase uses effects and
/// random sampling, and is covered by the rendering tests instead).
const BASE_SCENES: [&str; 8] = [
    "basic",
    "vase",
    "wine_glass",
    "curves",
    "mesh",
    "nurbs",
    "teapot",
    "constructions",
];

fn scenes_dir() -> PathBuf {
    crate::repo_root().join("scenes")
}

/// Pixel counts `(over 2/255, over 64/255)` between two images of one size.
fn differences(a: &Rgb8, b: &Rgb8) -> (usize, usize) {
    a.pixels()
        .zip(b.pixels())
        .fold((0, 0), |(small, large), (p, q)| {
            let worst = p
                .iter()
                .zip(q.iter())
                .map(|(&x, &y)| x.abs_diff(y))
                .max()
                .unwrap_or(0);
            (
                small + usize::from(worst > 2),
                large + usize::from(worst > 64),
            )
        })
}

#[test]
fn base_scenes_match_their_golden_images() {
    for name in BASE_SCENES {
        let scene =
            parse_file(&scenes_dir().join(format!("{name}.txt"))).unwrap_or_else(|e| panic!("{e}"));
        let effects = Effects::of(&scene, None);
        let (image, stats) = render(&scene, &Options::default()).unwrap();
        assert_eq!(
            stats.rays.shadow + stats.rays.reflection + stats.rays.refraction + stats.rays.indirect,
            0,
            "{name} is a base-format scene: primary rays only"
        );
        let got = to_rgb8(&image, effects.tone_map).unwrap();
        let golden_path = scenes_dir().join("golden").join(format!("{name}.png"));
        let golden = png_file::read(&golden_path, png_file::any_size)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", golden_path.display()));
        assert_eq!(
            (got.width, got.height),
            (golden.width, golden.height),
            "{name}: image size"
        );
        let pixels = got.pixels().count();
        let (small, large) = differences(&got, &golden);
        assert!(
            small * 200 <= pixels && large * 1000 <= pixels,
            "{name}: {small} pixels differ by more than 2/255 and {large} by more than \
             64/255 of {pixels} (allowed {} and {})",
            pixels / 200,
            pixels / 1000
        );
    }
}

#[test]
fn the_comparison_sees_a_changed_scene() {
    // The basic scene with its camera turned a little must fail the same
    // criterion against the basic golden image.
    let mut scene = parse_file(&scenes_dir().join("basic.txt")).unwrap_or_else(|e| panic!("{e}"));
    scene.camera.direction.x += 0.05;
    let effects = Effects::of(&scene, None);
    let (image, _) = render(&scene, &Options::default()).unwrap();
    let got = to_rgb8(&image, effects.tone_map).unwrap();
    let golden = png_file::read(&scenes_dir().join("golden/basic.png"), png_file::any_size)
        .unwrap_or_else(|e| panic!("{e}"));
    let (small, large) = differences(&got, &golden);
    let pixels = got.pixels().count();
    assert!(
        small * 200 > pixels || large * 1000 > pixels,
        "{small} / {large} of {pixels}"
    );
}

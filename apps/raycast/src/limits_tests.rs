//! The renderer's own bounds, for scenes built in code (the parser rejects
//! such input earlier): image size, render depth, and the Whitted tracer's
//! secondary-ray budget.

use revolve::nalgebra::Point3;

use crate::effects::{Effects, MAX_DEPTH};
use crate::render::{MAX_IMAGE_PIXELS, Options, check_size, render};
use crate::render_tests::{look_at, object, run, scene};
use crate::scene::{Color, Material, Shape};
use crate::whitted::MAX_SECONDARY_RAYS;

#[test]
fn an_image_too_large_is_an_error_before_any_allocation() {
    let mut s = scene(
        look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 1, 40.0),
        vec![],
        vec![],
        vec![],
    );
    s.camera.width = 1_000_000_000;
    let e = render(&s, &Options::default()).unwrap_err();
    assert!(e.contains("a side may be at most 16384"), "{e}");
    s.camera.width = 0;
    let e = render(&s, &Options::default()).unwrap_err();
    assert!(e.contains("empty"), "{e}");
    assert!(check_size(8192, 4096).is_ok());
    assert!(check_size(8192, 4097).is_err());
    assert_eq!(8192 * 4096, MAX_IMAGE_PIXELS);
}

/// A camera inside a box whose material reflects and transmits everything
/// (reflectivity + transparency = 2: no branch ever gets light enough to
/// prune), itself inside a mirror box that sends every transmitted ray
/// back, at the deepest render depth: every branch splits in two at every
/// bounce.
fn hall_of_glass_mirrors() -> crate::scene::Scene {
    let cube = |half: f64, material: usize| {
        object(
            Shape::Box {
                min: Point3::new(-half, -half, -half),
                max: Point3::new(half, half, half),
            },
            material,
        )
    };
    let mut s = scene(
        look_at([0.0; 3], [0.1, 0.2, -1.0], [0.0, 1.0, 0.0], 1, 1.0),
        vec![],
        vec![
            Material {
                reflectivity: Color::repeat(1.0),
                transparency: Color::repeat(1.0),
                refraction_index: 1.0,
                ..Material::default()
            },
            Material {
                reflectivity: Color::repeat(1.0),
                ..Material::default()
            },
        ],
        vec![cube(1.0, 0), cube(3.0, 1)],
    );
    s.render.max_depth = Some(u32::MAX);
    s
}

#[test]
fn the_depth_of_a_scene_built_in_code_is_clamped() {
    assert_eq!(
        Effects::of(&hall_of_glass_mirrors(), None).max_depth,
        MAX_DEPTH
    );
}

#[test]
fn a_camera_sample_traces_at_most_the_secondary_ray_budget() {
    // Without the budget this ray tree has 2^100 branches.
    let (image, stats) = run(&hall_of_glass_mirrors());
    assert_eq!(stats.rays.primary, 1);
    let secondary = stats.rays.reflection + stats.rays.refraction;
    assert_eq!(secondary, u64::from(MAX_SECONDARY_RAYS));
    assert!(image.pixels[0].iter().all(|c| c.is_finite()));
}

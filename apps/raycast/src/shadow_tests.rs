//! Shadows through transparent objects: a pane between a light straight
//! above and a diffuse floor lets through its transparency colour (once per
//! surface crossed, with Beer–Lambert absorption inside a closed body), an
//! opaque pane blocks the light, and a scene without transparent materials
//! keeps the one-query yes/no shadow test.

use revolve::nalgebra::{Point3, Vector3};

use crate::effects::Effects;
use crate::render_tests::{diffuse, directional, floor, look_at, object, run, scene};
use crate::scene::{Color, Integrator, Material, Scene, Shape};
use crate::stats::Stats;

/// The floor's diffuse grey; the light is white and straight above, so the
/// unshadowed floor is exactly this bright (Phong: `kd · N·L`, `N·L = 1`).
const FLOOR_GREY: f64 = 0.5;

/// A material letting through `transparency`, with `absorption`.
fn glass(transparency: Color, absorption: Color) -> Material {
    Material {
        transparency,
        refraction_index: 1.5,
        absorption,
        ..Material::default()
    }
}

/// The floor `y = −1` (material 0, grey) under a white directional light
/// pointing down, with `pane` (material 1, `pane_material`) above the
/// floor's patch `|x|, |z| ≤ 1`, and hard shadows on.
fn under_a_pane(pane: Shape, pane_material: Material) -> Scene {
    let mut s = scene(
        look_at([0.0, -0.5, 5.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 1, 1.0),
        vec![directional([0.0, -1.0, 0.0], [1.0, 1.0, 1.0])],
        vec![diffuse(FLOOR_GREY, FLOOR_GREY, FLOOR_GREY), pane_material],
        vec![floor(-1.0, 0), object(pane, 1)],
    );
    s.render.shadows = Some(true);
    s
}

/// A flat pane at height 1 (one surface).
fn sheet() -> Shape {
    Shape::Rectangle {
        corner: Point3::new(-1.0, 1.0, -1.0),
        edge1: Vector3::new(2.0, 0.0, 0.0),
        edge2: Vector3::new(0.0, 0.0, 2.0),
    }
}

/// A slab of thickness `THICKNESS` around height 1 (a closed body: two
/// surfaces on the way up).
fn slab() -> Shape {
    Shape::Box {
        min: Point3::new(-1.0, 1.0 - THICKNESS / 2.0, -1.0),
        max: Point3::new(1.0, 1.0 + THICKNESS / 2.0, 1.0),
    }
}

const THICKNESS: f64 = 0.2;

/// The one-pixel render of the floor point `(x, −1, 0)` seen from below the
/// pane's height (the camera ray does not cross the pane).
fn floor_at(mut s: Scene, x: f64) -> (Color, Stats) {
    s.camera = look_at([x, -0.5, 5.0], [x, -1.0, 0.0], [0.0, 1.0, 0.0], 1, 1.0);
    let (image, stats) = run(&s);
    (image.get(0, 0), stats)
}

#[test]
fn a_pane_lets_through_its_transparency_colour() {
    let transparency = Color::new(0.5, 0.25, 1.0);
    let s = under_a_pane(sheet(), glass(transparency, Color::zeros()));
    assert!(Effects::of(&s, None).transparent_shadows);
    assert!(
        Effects::of(&s, None)
            .names()
            .iter()
            .any(|n| n == "shadows through transparent objects")
    );
    let (open, open_stats) = floor_at(s.clone(), 3.0);
    assert_eq!(open, Color::repeat(FLOOR_GREY));
    assert_eq!(open_stats.rays.shadow, 1);
    let (under, stats) = floor_at(s, 0.0);
    // Half the light in red, a quarter in green, all of it in blue.
    assert_eq!(under, open.component_mul(&transparency));
    // The shadow ray meets the pane, then continues past it: two queries.
    assert_eq!(stats.rays.shadow, 2);
    assert_eq!(stats.rays.refraction + stats.rays.reflection, 0);
}

#[test]
fn a_closed_absorbing_body_is_crossed_twice_with_beer_lambert_inside() {
    let transparency = Color::repeat(0.5);
    let sigma = Color::new(1.0, 2.0, 3.0);
    let s = under_a_pane(slab(), glass(transparency, sigma));
    let (under, stats) = floor_at(s, 0.0);
    // In at the bottom face, out at the top: the transparency twice and
    // exp(−σ·thickness) for the way through.
    let expected = Color::repeat(FLOOR_GREY)
        .component_mul(&transparency.component_mul(&transparency))
        .component_mul(&sigma.map(|k| (-k * THICKNESS).exp()));
    assert!(
        (under - expected).amax() < 1e-12,
        "{under:?} vs {expected:?}"
    );
    assert_eq!(stats.rays.shadow, 3);
}

#[test]
fn an_opaque_pane_blocks_the_light_even_among_transparent_materials() {
    // A transparent material is in use (a glass ball away from the light's
    // path), so shadow rays walk through transparency; the pane itself is
    // opaque.
    let mut s = under_a_pane(sheet(), diffuse(0.3, 0.3, 0.3));
    s.materials.push(glass(Color::repeat(0.9), Color::zeros()));
    s.objects.push(object(
        Shape::Sphere {
            center: Point3::new(6.0, 0.0, 0.0),
            radius: 0.5,
        },
        2,
    ));
    assert!(Effects::of(&s, None).transparent_shadows);
    let (under, stats) = floor_at(s, 0.0);
    assert_eq!(under, Color::zeros());
    assert_eq!(stats.rays.shadow, 1);
}

#[test]
fn without_transparent_materials_shadows_are_one_yes_no_query() {
    // The same opaque pane, and an unused glass material: no effect.
    let mut s = under_a_pane(sheet(), diffuse(0.3, 0.3, 0.3));
    s.materials.push(glass(Color::repeat(0.9), Color::zeros()));
    let effects = Effects::of(&s, None);
    assert!(!effects.transparent_shadows && !effects.refraction);
    assert!(
        !effects
            .names()
            .iter()
            .any(|n| n.contains("through transparent"))
    );
    let (under, stats) = floor_at(s.clone(), 0.0);
    assert_eq!(under, Color::zeros());
    assert_eq!(stats.rays.shadow, 1);
    let (open, stats) = floor_at(s, 3.0);
    assert_eq!(open, Color::repeat(FLOOR_GREY));
    assert_eq!(stats.rays.shadow, 1);
}

#[test]
fn the_path_tracer_lets_a_point_light_through_a_pane() {
    // Next-event estimation towards the directional light: kd·colour·cos
    // times the pane's transparency, as the Whitted tracer.
    let transparency = Color::new(0.5, 0.25, 1.0);
    let mut s = under_a_pane(sheet(), glass(transparency, Color::zeros()));
    s.render.integrator = Some(Integrator::Path);
    s.render.max_depth = Some(0);
    assert!(Effects::of(&s, None).shadows_through_transparency());
    let (under, _) = floor_at(s, 0.0);
    assert_eq!(
        under,
        Color::repeat(FLOOR_GREY).component_mul(&transparency)
    );
}

//! Facts about rendered images: small scenes built in code (so they do not
//! depend on the parser) plus a few read through it, each asserting
//! something that a wrong renderer would fail.

use std::sync::Arc;

use revolve::nalgebra::{Point3, Vector3};

use crate::camera::PinholeCamera;
use crate::effects::Effects;
use crate::parse;
use crate::render::{Image, Options, render};
use crate::scene::{
    Camera, Color, Integrator, Light, Material, Object, RenderSettings, Scene, Shape, Texture,
};
use crate::stats::Stats;

pub(crate) const BACKGROUND: Color = Color::new(0.1, 0.2, 0.3);

pub(crate) fn look_at(
    eye: [f64; 3],
    target: [f64; 3],
    up: [f64; 3],
    size: u32,
    angle: f64,
) -> Camera {
    let center = Point3::from(eye);
    Camera {
        center,
        direction: Point3::from(target) - center,
        up: Vector3::from(up),
        angle_degrees: angle,
        width: size,
        height: size,
    }
}

pub(crate) fn scene(
    camera: Camera,
    lights: Vec<Light>,
    materials: Vec<Material>,
    objects: Vec<Object>,
) -> Scene {
    Scene {
        camera,
        lights,
        background: BACKGROUND,
        materials,
        objects,
        render: RenderSettings::default(),
    }
}

pub(crate) fn object(shape: Shape, material: usize) -> Object {
    Object {
        shape,
        material,
        transform: None,
    }
}

pub(crate) fn sphere(center: [f64; 3], radius: f64, material: usize) -> Object {
    object(
        Shape::Sphere {
            center: Point3::from(center),
            radius,
        },
        material,
    )
}

/// The plane `y = height` facing up.
pub(crate) fn floor(height: f64, material: usize) -> Object {
    object(
        Shape::Plane {
            normal: Vector3::y(),
            offset: height,
        },
        material,
    )
}

pub(crate) fn diffuse(r: f64, g: f64, b: f64) -> Material {
    Material {
        diffuse: Color::new(r, g, b),
        ..Material::default()
    }
}

pub(crate) fn directional(direction: [f64; 3], color: [f64; 3]) -> Light {
    Light::Directional {
        direction: Vector3::from(direction),
        color: Color::from(color),
    }
}

fn quiet() -> Options {
    Options::default()
}

pub(crate) fn run(scene: &Scene) -> (Image, Stats) {
    render(scene, &quiet()).unwrap_or_else(|e| panic!("{e}"))
}

/// The pixel in which the world point `p` appears.
pub(crate) fn pixel_of(scene: &Scene, p: [f64; 3]) -> (u32, u32) {
    let (x, y) = PinholeCamera::new(&scene.camera)
        .project(&Point3::from(p))
        .expect("in front of the camera");
    assert!(
        x >= 0.0
            && y >= 0.0
            && x < f64::from(scene.camera.width)
            && y < f64::from(scene.camera.height)
    );
    (x as u32, y as u32)
}

pub(crate) fn close(a: &Color, b: &Color, tolerance: f64) -> bool {
    (a - b).amax() <= tolerance
}

/// A red Phong sphere of radius 1 at the origin, seen head on from z = 5 in
/// a 33×33 image (the centre pixel's ray is the axis), lit by one
/// directional light from (1, 1, 1).
fn lit_sphere() -> Scene {
    scene(
        look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 33, 40.0),
        vec![directional([-1.0, -1.0, -1.0], [1.0, 0.9, 0.8])],
        vec![Material {
            diffuse: Color::new(0.5, 0.2, 0.1),
            specular: Color::new(0.3, 0.3, 0.3),
            shininess: 2.0,
            ..Material::default()
        }],
        vec![sphere([0.0; 3], 1.0, 0)],
    )
}

#[test]
fn the_centre_of_a_lit_sphere_has_the_hand_computed_phong_colour() {
    let s = lit_sphere();
    let (image, _) = run(&s);
    // N = V = (0, 0, 1), L = (1, 1, 1)/√3: N·L = 1/√3,
    // R = 2(N·L)N − L = (−1, −1, 1)/√3, V·R = 1/√3, (V·R)² = 1/3.
    let k = 1.0 / 3f64.sqrt();
    let kd = Color::new(0.5, 0.2, 0.1);
    let ks = Color::new(0.3, 0.3, 0.3);
    let expected = Color::new(1.0, 0.9, 0.8).component_mul(&(kd * k + ks / 3.0));
    let centre = image.get(16, 16);
    assert!(
        close(&centre, &expected, 1.0 / 255.0),
        "{centre:?} vs {expected:?}"
    );
    assert!(
        close(&centre, &expected, 1e-9),
        "{centre:?} vs {expected:?}"
    );
    assert!(centre.sum() > BACKGROUND.sum());
}

#[test]
fn a_background_pixel_is_exactly_the_background() {
    let s = lit_sphere();
    let (image, _) = run(&s);
    assert_eq!(image.get(0, 0), BACKGROUND);
    assert_eq!(image.get(32, 32), BACKGROUND);
    // Row 0 is the top: a sphere moved up shows in the top rows only.
    let mut up = lit_sphere();
    up.objects = vec![sphere([0.0, 1.2, 0.0], 0.3, 0)];
    let (image, _) = run(&up);
    let (_, y) = pixel_of(&up, [0.0, 1.2, 0.0]);
    assert!(y < 10);
    assert_ne!(image.get(16, y), BACKGROUND);
    assert_eq!(image.get(16, 32 - y), BACKGROUND);
}

#[test]
fn a_base_format_scene_traces_primary_rays_only() {
    let s = lit_sphere();
    let effects = Effects::of(&s, None);
    assert!(effects.names().is_empty(), "{:?}", effects.names());
    let (_, stats) = run(&s);
    assert_eq!(stats.rays.primary, 33 * 33);
    assert_eq!(stats.rays.shadow, 0);
    assert_eq!(stats.rays.reflection, 0);
    assert_eq!(stats.rays.refraction, 0);
    assert_eq!(stats.rays.indirect, 0);
}

/// A floor at y = −1, a ball of radius ½ at the origin above it, light
/// straight down, seen from above and in front.
fn ball_over_floor() -> Scene {
    scene(
        look_at([0.0, 1.0, 5.0], [0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 32, 60.0),
        vec![directional([0.0, -1.0, 0.0], [1.0, 1.0, 1.0])],
        vec![diffuse(0.5, 0.5, 0.5), diffuse(0.2, 0.6, 0.2)],
        vec![floor(-1.0, 0), sphere([0.0; 3], 0.5, 1)],
    )
}

/// [`ball_over_floor`] lit by one white unit-square area light at height 3.
fn ball_under_area_light() -> Scene {
    let mut s = ball_over_floor();
    s.lights = vec![Light::Area {
        corner: Point3::new(-0.5, 3.0, -0.5),
        edge1: Vector3::new(1.0, 0.0, 0.0),
        edge2: Vector3::new(0.0, 0.0, 1.0),
        color: Color::repeat(1.0),
    }];
    s
}

#[test]
fn shadows_true_casts_shadows_with_shadow_rays() {
    let mut s = ball_over_floor();
    let behind = pixel_of(&s, [0.0, -1.0, 0.0]);
    let open = pixel_of(&s, [2.0, -1.0, 0.0]);
    let (plain, stats) = run(&s);
    assert_eq!(stats.rays.shadow, 0);
    assert!(close(
        &plain.get(behind.0, behind.1),
        &Color::repeat(0.5),
        1e-12
    ));

    s.render.shadows = Some(true);
    let (shadowed, stats) = run(&s);
    assert!(stats.rays.shadow > 0);
    assert!(
        Effects::of(&s, None)
            .names()
            .iter()
            .any(|n| n == "hard shadows")
    );
    let dark = shadowed.get(behind.0, behind.1);
    assert!(dark.sum() < plain.get(behind.0, behind.1).sum());
    assert_eq!(dark, Color::zeros());
    // Out of the ball's shadow the floor stays lit.
    assert!(close(
        &shadowed.get(open.0, open.1),
        &Color::repeat(0.5),
        1e-12
    ));
}

#[test]
fn an_area_light_gives_a_penumbra() {
    let s = ball_under_area_light();
    let effects = Effects::of(&s, None);
    assert!(effects.soft_shadows && effects.light_samples == 16);
    let (image, stats) = run(&s);
    assert!(stats.rays.shadow > 0);
    // The umbra's centre is black; a point at the penumbra's edge is
    // partly lit: strictly between black and the fully lit floor.
    let centre = pixel_of(&s, [0.0, -1.0, 0.0]);
    assert_eq!(image.get(centre.0, centre.1), Color::zeros());
    let lit = image.get(
        pixel_of(&s, [2.5, -1.0, 0.0]).0,
        pixel_of(&s, [2.5, -1.0, 0.0]).1,
    );
    let found = (0..32).any(|x| {
        let c = image.get(x, centre.1);
        c.x > 0.02 && c.x < lit.x - 0.02
    });
    assert!(found, "no penumbra on the row through the shadow");
}

#[test]
fn a_mirror_material_makes_reflection_rays() {
    let mut s = lit_sphere();
    s.lights.clear();
    s.materials[0] = Material {
        reflectivity: Color::new(0.9, 0.5, 0.25),
        ..Material::default()
    };
    let (image, stats) = run(&s);
    assert!(stats.rays.reflection > 0);
    assert_eq!(stats.rays.refraction, 0);
    // The centre ray comes straight back and sees the background.
    let expected = BACKGROUND.component_mul(&Color::new(0.9, 0.5, 0.25));
    assert!(close(&image.get(16, 16), &expected, 1e-12));
}

#[test]
fn a_transparent_material_makes_refraction_rays() {
    let mut s = lit_sphere();
    s.materials[0].transparency = Color::repeat(0.8);
    s.materials[0].refraction_index = 1.5;
    let (_, stats) = run(&s);
    assert!(stats.rays.refraction > 0);
    // Fresnel reflection comes with it.
    assert!(stats.rays.reflection > 0);
    let (_, base) = run(&lit_sphere());
    assert_eq!(base.rays.refraction, 0);
}

/// One pixel looking down −z at a slab `|x|, |y| ≤ 1`, `|z| ≤ thickness/2`
/// of clear, absorbing material with index 1 in front of a white background.
fn slab(thickness: f64) -> Scene {
    let mut s = scene(
        look_at([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 1, 10.0),
        vec![],
        vec![Material {
            transparency: Color::repeat(1.0),
            refraction_index: 1.0,
            absorption: Color::new(0.5, 1.0, 2.0),
            ..Material::default()
        }],
        vec![object(
            Shape::Box {
                min: Point3::new(-1.0, -1.0, -thickness / 2.0),
                max: Point3::new(1.0, 1.0, thickness / 2.0),
            },
            0,
        )],
    );
    s.background = Color::repeat(1.0);
    s
}

#[test]
fn a_thicker_absorbing_slab_transmits_less() {
    let (thin, stats) = run(&slab(0.2));
    assert!(stats.rays.refraction >= 2);
    let (thick, _) = run(&slab(1.0));
    let (thin, thick) = (thin.get(0, 0), thick.get(0, 0));
    for c in 0..3 {
        assert!(thick[c] < thin[c], "{thin:?} {thick:?}");
    }
    // Beer–Lambert: exp(−σ d), σ = (0.5, 1, 2).
    let expected = Color::new((-0.5f64).exp(), (-1.0f64).exp(), (-2.0f64).exp());
    assert!(close(&thick, &expected, 1e-4), "{thick:?} vs {expected:?}");
}

fn texture(w: u32, h: u32, pixels: Vec<Color>) -> Option<Arc<Texture>> {
    Some(Arc::new(Texture {
        width: w,
        height: h,
        pixels,
    }))
}

/// A 2×2 square at y = 0 seen from straight above, lit straight down.
fn textured_square(t: Option<Arc<Texture>>) -> Scene {
    scene(
        look_at([0.0, 3.0, 0.0], [0.0; 3], [0.0, 0.0, -1.0], 32, 50.0),
        vec![directional([0.0, -1.0, 0.0], [1.0, 1.0, 1.0])],
        vec![Material {
            diffuse: Color::repeat(1.0),
            texture: t,
            ..Material::default()
        }],
        vec![object(
            Shape::Rectangle {
                corner: Point3::new(-1.0, 0.0, 1.0),
                edge1: Vector3::new(2.0, 0.0, 0.0),
                edge2: Vector3::new(0.0, 0.0, -2.0),
            },
            0,
        )],
    )
}

#[test]
fn a_texture_gives_the_diffuse_colour() {
    let plain = textured_square(None);
    let green = Color::new(0.2, 0.9, 0.1);
    let tinted = textured_square(texture(2, 2, vec![green; 4]));
    assert!(Effects::of(&tinted, None).textures);
    assert!(!Effects::of(&plain, None).textures);
    let (a, _) = run(&plain);
    let (b, _) = run(&tinted);
    assert!(close(&a.get(16, 16), &Color::repeat(1.0), 1e-12));
    assert!(close(&b.get(16, 16), &green, 1e-12), "{:?}", b.get(16, 16));

    // A 2×2 checker of four colours: the four quadrants of the square show
    // four different colours, whichever way (u, v) runs over it.
    let checker = textured_square(texture(
        2,
        2,
        vec![
            Color::new(1.0, 0.0, 0.0),
            Color::new(0.0, 1.0, 0.0),
            Color::new(0.0, 0.0, 1.0),
            Color::new(1.0, 1.0, 0.0),
        ],
    ));
    let (image, _) = run(&checker);
    let quadrants: Vec<Color> = [[-0.5, 0.5], [0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]]
        .iter()
        .map(|&[x, z]| {
            let (px, py) = pixel_of(&checker, [x, 0.0, z]);
            image.get(px, py)
        })
        .collect();
    for i in 0..4 {
        for j in 0..i {
            assert!((quadrants[i] - quadrants[j]).amax() > 0.3, "{quadrants:?}");
        }
    }
}

#[test]
fn one_sample_means_one_primary_ray_per_pixel_and_no_jitter() {
    // Without lights the sphere is black: with one sample through each
    // pixel centre every pixel is exactly black or exactly the background;
    // with 4 jittered samples, silhouette pixels mix the two.
    let mut s = lit_sphere();
    s.lights.clear();
    assert!(!Effects::of(&s, None).antialiasing);
    let (sharp, stats) = run(&s);
    assert_eq!(stats.rays.primary, 33 * 33);
    assert!(
        sharp
            .pixels
            .iter()
            .all(|c| *c == BACKGROUND || *c == Color::zeros())
    );
    let options = Options {
        samples: Some(4),
        ..quiet()
    };
    assert!(Effects::of(&s, Some(4)).antialiasing);
    let (smooth, stats) = render(&s, &options).unwrap();
    assert_eq!(stats.rays.primary, 4 * 33 * 33);
    let mixed = smooth
        .pixels
        .iter()
        .filter(|c| **c != BACKGROUND && **c != Color::zeros())
        .count();
    assert!(mixed > 10, "{mixed} mixed pixels");
    // The same render twice is the same image.
    assert_eq!(render(&s, &options).unwrap().0, smooth);
}

/// A path-traced pixel's value: one 1×1 camera looking from `eye` at
/// `target`.
fn path_pixel(mut s: Scene, eye: [f64; 3], target: [f64; 3], samples: u32) -> (Color, Stats) {
    s.camera = look_at(eye, target, [0.0, 1.0, 0.0], 1, 0.5);
    s.render.integrator = Some(Integrator::Path);
    s.render.samples = Some(samples);
    let (image, stats) = run(&s);
    (image.get(0, 0), stats)
}

#[test]
fn the_path_tracer_in_a_white_furnace_returns_the_albedo() {
    // A convex diffuse body under a uniform sky of radiance 1: every bounce
    // escapes, so each sample is exactly the albedo.
    let mut s = lit_sphere();
    s.lights.clear();
    s.materials = vec![diffuse(0.5, 0.25, 0.75)];
    s.background = Color::repeat(1.0);
    s.render.integrator = Some(Integrator::Path);
    s.render.samples = Some(4);
    let (image, stats) = run(&s);
    assert!(close(
        &image.get(16, 16),
        &Color::new(0.5, 0.25, 0.75),
        1e-12
    ));
    assert_eq!(image.get(0, 0), Color::repeat(1.0));
    assert!(stats.rays.indirect > 0);
}

#[test]
fn path_tracing_a_diffuse_sphere_under_a_directional_light_matches_phong() {
    let mut s = lit_sphere();
    s.materials = vec![diffuse(0.6, 0.3, 0.2)];
    s.background = Color::zeros();
    let (whitted, _) = run(&s);
    s.render.integrator = Some(Integrator::Path);
    let (path, stats) = run(&s);
    assert!(stats.rays.shadow > 0 && stats.rays.indirect > 0);
    for (a, b) in whitted.pixels.iter().zip(&path.pixels) {
        assert!(close(a, b, 1e-12), "{a:?} vs {b:?}");
    }
    assert!(whitted.get(16, 16).x > 0.3);
}

/// The fraction of the hemisphere's cosine-weighted solid angle (the form
/// factor) that a square of side 2a, parallel and centred at height h,
/// covers from the point below its centre.
fn square_form_factor(a: f64, h: f64) -> f64 {
    let x = a / h;
    let s = (1.0 + x * x).sqrt();
    4.0 / (2.0 * std::f64::consts::PI) * 2.0 * (x / s) * (x / s).atan()
}

/// A diffuse floor (albedo ½) under a 4×4 light at height 1, seen from
/// between them with 16384 samples (about 1% noise).
fn floor_under_light(light: Option<Light>, emitter: Option<Object>) -> Scene {
    let mut materials = vec![diffuse(0.5, 0.5, 0.5)];
    let mut objects = vec![floor(0.0, 0)];
    if let Some(mut e) = emitter {
        materials.push(Material {
            emission: Color::repeat(1.0),
            ..Material::default()
        });
        e.material = 1;
        objects.push(e);
    }
    let mut s = scene(
        look_at([0.0, 0.5, 0.0], [0.0; 3], [0.0, 0.0, -1.0], 1, 0.5),
        light.into_iter().collect(),
        materials,
        objects,
    );
    s.background = Color::zeros();
    s.render.samples = Some(16384);
    s
}

#[test]
fn next_event_estimation_does_not_double_count_emission() {
    let expected = 0.5 * square_form_factor(2.0, 1.0);
    let emitter = object(
        Shape::Rectangle {
            corner: Point3::new(-2.0, 1.0, -2.0),
            edge1: Vector3::new(4.0, 0.0, 0.0),
            edge2: Vector3::new(0.0, 0.0, 4.0),
        },
        1,
    );
    let s = floor_under_light(None, Some(emitter));
    let effects = Effects::of(&s, None);
    assert_eq!(effects.integrator, Integrator::Path);
    assert!(effects.emissive);
    let (image, stats) = run(&s);
    let got = image.get(0, 0);
    assert!(stats.rays.shadow > 0);
    assert!(
        (got.x / expected - 1.0).abs() < 0.05,
        "{got:?} vs {expected}"
    );

    let light = Light::Area {
        corner: Point3::new(-2.0, 1.0, -2.0),
        edge1: Vector3::new(4.0, 0.0, 0.0),
        edge2: Vector3::new(0.0, 0.0, 4.0),
        color: Color::repeat(1.0),
    };
    let mut s = floor_under_light(Some(light), None);
    s.render.integrator = Some(Integrator::Path);
    let (image, _) = run(&s);
    let got = image.get(0, 0);
    assert!(
        (got.x / expected - 1.0).abs() < 0.05,
        "{got:?} vs {expected}"
    );
}

/// A diffuse floor at y = 0 under a small, bright area light at height 8;
/// optionally a glass ball of radius 1 whose focus falls on the floor.
fn caustic_scene(with_ball: bool) -> Scene {
    let mut objects = vec![floor(0.0, 0)];
    if with_ball {
        objects.push(sphere([0.0, 1.35, 0.0], 1.0, 1));
    }
    let mut s = scene(
        look_at([4.0, 0.3, 0.0], [0.0; 3], [0.0, 1.0, 0.0], 1, 0.5),
        vec![Light::Area {
            corner: Point3::new(-0.5, 8.0, -0.5),
            edge1: Vector3::new(1.0, 0.0, 0.0),
            edge2: Vector3::new(0.0, 0.0, 1.0),
            color: Color::repeat(50.0),
        }],
        vec![
            diffuse(0.8, 0.8, 0.8),
            Material {
                transparency: Color::repeat(1.0),
                refraction_index: 1.5,
                ..Material::default()
            },
        ],
        objects,
    );
    s.background = Color::zeros();
    s
}

#[test]
fn a_glass_ball_focuses_light_on_the_floor_below_it() {
    let below = [0.0, 0.0, 0.0];
    let aside = [2.5, 0.0, 0.0];
    let eye = [4.0, 0.3, 0.0];
    let (focus, stats) = path_pixel(caustic_scene(true), eye, below, 4096);
    assert!(stats.rays.refraction > 0);
    let (bare, _) = path_pixel(caustic_scene(false), eye, below, 4096);
    let (open, _) = path_pixel(caustic_scene(true), [4.0, 0.3, 1.0], aside, 4096);
    // The bare floor under the light and a point away from the ball are
    // lit directly; the caustic under the ball is several times brighter
    // (its direct light is blocked by the ball: all of it is focused).
    assert!(bare.x > 0.05);
    assert!(focus.x > 3.0 * bare.x, "focus {focus:?}, bare {bare:?}");
    assert!(focus.x > 3.0 * open.x, "focus {focus:?}, aside {open:?}");
}

#[test]
fn effects_follow_the_scene_contents() {
    let s = lit_sphere();
    let base = Effects::of(&s, None);
    assert_eq!(base.integrator, Integrator::Whitted);
    assert!(!base.reflection && !base.refraction && !base.textures && !base.hard_shadows);
    assert!(!base.area_lights && !base.emissive && !base.antialiasing);
    assert_eq!(base.max_depth, 5);

    // An unused reflective material turns nothing on.
    let mut unused = lit_sphere();
    unused.materials.push(Material {
        reflectivity: Color::repeat(1.0),
        ..Material::default()
    });
    assert!(!Effects::of(&unused, None).reflection);

    let mut glass = lit_sphere();
    glass.materials[0].transparency = Color::repeat(1.0);
    glass.materials[0].absorption = Color::repeat(0.3);
    let e = Effects::of(&glass, Some(9));
    assert!(e.refraction && e.absorption && e.antialiasing && !e.reflection);
    assert_eq!((e.samples, e.light_samples), (9, 1));

    let mut path = lit_sphere();
    path.render.integrator = Some(Integrator::Path);
    let e = Effects::of(&path, None);
    assert_eq!(e.max_depth, 8);
    assert!(e.names()[0].starts_with("path tracing"));
}

const PARSED_SCENE: &str = "
PerspectiveCamera {
    center 0 0 5
    direction 0 0 -1
    up 0 1 0
    angle 40
    width 33
    height 33
}
Lights {
    numLights 1
    DirectionalLight { direction -1 -1 -1  color 1 0.9 0.8 }
}
Background { color 0.1 0.2 0.3 }
Materials {
    numMaterials 1
    PhongMaterial { diffuseColor 0.5 0.2 0.1  specularColor 0.3 0.3 0.3  shininess 2 }
}
Group {
    numObjects 1
    MaterialIndex 0
    Sphere { center 0 0 0  radius 1 }
}
";

#[test]
fn a_parsed_base_scene_renders_like_the_one_built_in_code() {
    let s = parse::parse_str(PARSED_SCENE, std::path::Path::new("inline.txt")).unwrap();
    let (parsed, stats) = run(&s);
    let (built, _) = run(&lit_sphere());
    assert_eq!(parsed, built);
    assert_eq!(stats.rays.total(), 33 * 33);
}

#[test]
fn a_parsed_render_block_turns_effects_on() {
    let text = PARSED_SCENE.replace(
        "Group {",
        "Render { samples 4 shadows true maxDepth 3 }\nGroup {",
    );
    let text = text.replace("shininess 2 }", "shininess 2 reflectivity 0.5 0.5 0.5 }");
    let s = parse::parse_str(&text, std::path::Path::new("inline.txt")).unwrap();
    let e = Effects::of(&s, None);
    assert!(e.antialiasing && e.hard_shadows && e.reflection);
    assert_eq!(e.max_depth, 3);
    let (_, stats) = run(&s);
    assert_eq!(stats.rays.primary, 4 * 33 * 33);
    assert!(stats.rays.shadow > 0 && stats.rays.reflection > 0);
}

#[test]
fn inside_a_glowing_diffuse_sphere_the_bounces_sum_to_a_geometric_series() {
    // Every surface emits Le = 1 and reflects ρ = ½, so the radiance is
    // Σₖ ρᵏ over the path lengths traced: next-event estimation adds one
    // term per bounce (between two points of a sphere cos·cos'/r² is the
    // constant 1/(4R²), so each estimate is exactly ρ·L), emission met by
    // diffuse rays must not add it again, and Russian roulette must not
    // bias the sum.
    let depth = 20;
    let mut s = scene(
        look_at([0.0; 3], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0], 1, 10.0),
        vec![],
        vec![Material {
            diffuse: Color::repeat(0.5),
            emission: Color::repeat(1.0),
            ..Material::default()
        }],
        vec![sphere([0.0; 3], 1.0, 0)],
    );
    s.render.samples = Some(4096);
    s.render.max_depth = Some(depth);
    let (image, stats) = run(&s);
    let expected: f64 = (0..=depth + 1).map(|k| 0.5f64.powi(k as i32)).sum();
    let got = image.get(0, 0).x;
    assert!((got / expected - 1.0).abs() < 0.02, "{got} vs {expected}");
    assert!(stats.rays.indirect > 4096);
}

#[test]
fn shadows_false_keeps_area_lights_without_shadow_rays() {
    let mut s = ball_under_area_light();
    s.render.shadows = Some(false);
    let (image, stats) = run(&s);
    assert_eq!(stats.rays.shadow, 0);
    let (x, y) = pixel_of(&s, [0.0, -1.0, 0.0]);
    assert!(image.get(x, y).x > 0.4, "{:?}", image.get(x, y));
}

/// The README's first command, `cargo run --release -p raycast`, renders
/// the bundled showcase; the same call here (only the output moved to a
/// temporary folder) must write the whole 640×480 image, and the image must
/// show the scene rather than one colour.
#[test]
fn the_default_command_renders_the_showcase() {
    let dir = crate::temp_dir::TempDir::new("showcase");
    let out = dir.0.join("showcase.png");
    crate::cli::run([
        "-o".to_string(),
        out.display().to_string(),
        "--quiet".into(),
    ])
    .unwrap();
    let png = crate::png_file::read(&out, crate::png_file::any_size).unwrap();
    assert_eq!((png.width, png.height), (640, 480));
    let distinct: std::collections::HashSet<[u8; 3]> = png.pixels().collect();
    assert!(distinct.len() > 1000, "{} colours", distinct.len());
}

#[test]
fn the_command_line_writes_the_png_and_fails_cleanly() {
    let dir = std::env::temp_dir().join(format!("raycast-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene_path = dir.join("s.txt");
    std::fs::write(&scene_path, PARSED_SCENE).unwrap();
    let out = dir.join("sub").join("s.png");
    let args = [
        scene_path.display().to_string(),
        "-o".into(),
        out.display().to_string(),
        "--quiet".into(),
    ];
    crate::cli::run(args.clone()).unwrap();
    let png = crate::png_file::read(&out, crate::png_file::any_size).unwrap();
    assert_eq!((png.width, png.height), (33, 33));
    // Background 0.1 0.2 0.3 written linearly: int(c·255).
    assert_eq!(png.pixel(0, 0), [25, 51, 76]);

    // A warning prints (to the given stream) even under --quiet, and the
    // render goes on.
    std::fs::write(&scene_path, PARSED_SCENE.replace("angle 40", "angle 0.7")).unwrap();
    let mut warnings = Vec::new();
    crate::cli::run_warning_to(args.clone(), &mut warnings).unwrap();
    let warnings = String::from_utf8(warnings).unwrap();
    let line = PARSED_SCENE
        .lines()
        .position(|l| l.contains("angle"))
        .unwrap()
        + 1;
    assert!(
        warnings.starts_with(&format!(
            "raycast: {}:{line}:11: warning: angle 0.7 is under 2 degrees",
            scene_path.display()
        )),
        "{warnings}"
    );
    assert_eq!(warnings.lines().count(), 1);

    std::fs::write(&scene_path, "PerspectiveCamera { center 0 0 x }").unwrap();
    let err = crate::cli::run([scene_path.display().to_string(), "--quiet".into()]).unwrap_err();
    assert!(err.contains("s.txt:1:"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

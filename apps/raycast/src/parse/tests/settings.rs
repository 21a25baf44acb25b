//! Camera, lights, background, materials and render settings.

use revolve::nalgebra::{Point3, Vector3};

use super::{CAMERA, TempDir, parse};
use crate::scene::{Integrator, Light, Material, ToneMap};

#[test]
fn camera_fields_in_any_order() {
    let scene = parse(
        "PerspectiveCamera {\n  height 300 width 400 angle 30\n  up 0 0 1 direction 1 2 3 center -1 -2 -3\n}\n",
    );
    let c = &scene.camera;
    assert_eq!(c.center, Point3::new(-1.0, -2.0, -3.0));
    assert_eq!(c.direction, Vector3::new(1.0, 2.0, 3.0));
    assert_eq!(c.up, Vector3::new(0.0, 0.0, 1.0));
    assert_eq!(c.angle_degrees, 30.0);
    assert_eq!((c.width, c.height), (400, 300));
}

#[test]
fn missing_blocks_have_defaults() {
    let scene = parse(CAMERA);
    assert!(scene.lights.is_empty());
    assert_eq!(scene.background, Vector3::zeros());
    assert!(scene.objects.is_empty());
    assert_eq!(scene.render, Default::default());
    // No materials: one default grey material.
    assert_eq!(scene.materials.len(), 1);
    assert_eq!(scene.materials[0].diffuse, Vector3::repeat(0.8));
    assert_eq!(scene.materials[0].specular, Vector3::zeros());
    assert_eq!(scene.materials[0].refraction_index, 1.0);
}

#[test]
fn directional_light() {
    let scene = parse(&format!(
        "{CAMERA}Lights {{ numLights 1 DirectionalLight {{ direction -0.5 -1 0.25 color 0.9 0.8 0.7 }} }}"
    ));
    assert_eq!(
        scene.lights,
        vec![Light::Directional {
            direction: Vector3::new(-0.5, -1.0, 0.25),
            color: Vector3::new(0.9, 0.8, 0.7),
        }]
    );
}

#[test]
fn point_light() {
    let scene = parse(&format!(
        "{CAMERA}Lights {{ numLights 1 PointLight {{ color 2 3 4 position 0 5 -5 }} }}"
    ));
    assert_eq!(
        scene.lights,
        vec![Light::Point {
            position: Point3::new(0.0, 5.0, -5.0),
            color: Vector3::new(2.0, 3.0, 4.0),
        }]
    );
}

#[test]
fn area_light() {
    let scene = parse(&format!(
        "{CAMERA}Lights {{ AreaLight {{ corner 1 2 3 edge1 1 0 0 edge2 0 0 2 color 5 5 4 }} }}"
    ));
    assert_eq!(
        scene.lights,
        vec![Light::Area {
            corner: Point3::new(1.0, 2.0, 3.0),
            edge1: Vector3::new(1.0, 0.0, 0.0),
            edge2: Vector3::new(0.0, 0.0, 2.0),
            color: Vector3::new(5.0, 5.0, 4.0),
        }]
    );
}

#[test]
fn several_lights_keep_their_order() {
    let scene = parse(&format!(
        "{CAMERA}Lights {{ numLights 3\n PointLight {{ position 0 0 0 color 1 1 1 }}\n DirectionalLight {{ direction 0 -1 0 color 1 1 1 }}\n PointLight {{ position 1 1 1 color 1 1 1 }} }}"
    ));
    assert_eq!(scene.lights.len(), 3);
    assert!(
        matches!(scene.lights[0], Light::Point { position, .. } if position == Point3::origin())
    );
    assert!(matches!(scene.lights[1], Light::Directional { .. }));
    assert!(
        matches!(scene.lights[2], Light::Point { position, .. } if position == Point3::new(1.0, 1.0, 1.0))
    );
}

#[test]
fn background_color_and_ignored_ambient_light() {
    let scene = parse(&format!(
        "{CAMERA}Background {{ color 0.1 0.2 0.3 ambientLight 0.5 0.5 0.5 }}"
    ));
    assert_eq!(scene.background, Vector3::new(0.1, 0.2, 0.3));
}

#[test]
fn phong_material_base_keywords() {
    let scene = parse(&format!(
        "{CAMERA}Materials {{ numMaterials 1\n PhongMaterial {{ diffuseColor 1 0 0.5 specularColor 0.2 0.3 0.4 shininess 20 }} }}"
    ));
    assert_eq!(
        scene.materials,
        vec![Material {
            diffuse: Vector3::new(1.0, 0.0, 0.5),
            specular: Vector3::new(0.2, 0.3, 0.4),
            shininess: 20.0,
            ..Material::default()
        }]
    );
}

#[test]
fn material_effect_keywords() {
    let scene = parse(&format!(
        "{CAMERA}Materials {{ numMaterials 2\n Material {{ diffuseColor 0.9 0.9 1 }}\n Material {{\n reflectivity 0.1 0.2 0.3\n transparency 0.4 0.5 0.6\n refractionIndex 1.5\n absorption 0.7 0.8 0.9\n emission 4 5 6 }} }}"
    ));
    assert_eq!(scene.materials.len(), 2);
    assert_eq!(scene.materials[0].diffuse, Vector3::new(0.9, 0.9, 1.0));
    assert_eq!(scene.materials[0].refraction_index, 1.0);
    let m = &scene.materials[1];
    assert_eq!(m.diffuse, Vector3::zeros());
    assert_eq!(m.reflectivity, Vector3::new(0.1, 0.2, 0.3));
    assert_eq!(m.transparency, Vector3::new(0.4, 0.5, 0.6));
    assert_eq!(m.refraction_index, 1.5);
    assert_eq!(m.absorption, Vector3::new(0.7, 0.8, 0.9));
    assert_eq!(m.emission, Vector3::new(4.0, 5.0, 6.0));
    assert!(m.texture.is_none());
}

#[test]
fn material_texture_is_linear_with_row_zero_on_top() {
    let dir = TempDir::new("texture");
    // RGBA, row 0 on top; the alpha channel is ignored.
    let rgba = [
        [255, 0, 0, 255],
        [0, 255, 0, 0],
        [0, 0, 255, 255],
        [51, 102, 204, 128],
    ]
    .concat();
    crate::png_file::write_raw(&dir.0.join("wood.png"), 2, 2, png::ColorType::Rgba, &rgba)
        .expect("write the PNG fixture");
    let scene = dir
        .parse_scene(&format!(
            "{CAMERA}Materials {{ Material {{ texture wood.png }} Material {{ texture wood.png }} }}"
        ))
        .unwrap_or_else(|e| panic!("{e}"));
    let texture = scene.materials[0].texture.as_ref().expect("a texture");
    assert_eq!((texture.width, texture.height), (2, 2));
    assert_eq!(
        texture.pixels,
        vec![
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(0.2, 0.4, 0.8),
        ]
    );
    // The same file is read once and shared.
    let again = scene.materials[1].texture.as_ref().expect("a texture");
    assert!(std::sync::Arc::ptr_eq(texture, again));
}

#[test]
fn render_block_values() {
    let scene = parse(&format!(
        "{CAMERA}Render {{ samples 64 maxDepth 0 shadows false integrator path toneMap reinhard }}"
    ));
    assert_eq!(scene.render.samples, Some(64));
    assert_eq!(scene.render.max_depth, Some(0));
    assert_eq!(scene.render.shadows, Some(false));
    assert_eq!(scene.render.integrator, Some(Integrator::Path));
    assert_eq!(scene.render.tone_map, Some(ToneMap::Reinhard));

    let scene = parse(&format!(
        "{CAMERA}Render {{ shadows true integrator whitted toneMap clamp }}"
    ));
    assert_eq!(scene.render.samples, None);
    assert_eq!(scene.render.max_depth, None);
    assert_eq!(scene.render.shadows, Some(true));
    assert_eq!(scene.render.integrator, Some(Integrator::Whitted));
    assert_eq!(scene.render.tone_map, Some(ToneMap::Clamp));
}

#[test]
fn blocks_in_any_order() {
    let scene = parse(&format!(
        "Render {{ samples 4 }}\nGroup {{ MaterialIndex 1 Sphere {{ center 0 0 0 radius 1 }} }}\nMaterials {{ Material {{ }} Material {{ shininess 3 }} }}\n{CAMERA}"
    ));
    assert_eq!(scene.render.samples, Some(4));
    assert_eq!(scene.objects[0].material, 1);
    assert_eq!(scene.materials[1].shininess, 3.0);
    assert_eq!(scene.camera.width, 40);
}

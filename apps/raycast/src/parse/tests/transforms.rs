//! Transform steps and their composition, flattening, and material scoping.

use revolve::nalgebra::{Matrix4, Point3};

use super::{CAMERA, objects_of, parse};
use crate::scene::{Object, Shape};

/// The object-to-world image of `p` under the object's matrix.
fn map(object: &Object, p: Point3<f64>) -> Point3<f64> {
    object
        .transform
        .unwrap_or_else(Matrix4::identity)
        .transform_point(&p)
}

/// The single object of a `Transform` holding a unit sphere after `steps`.
fn transformed(steps: &str) -> Object {
    let mut objects = objects_of(&format!(
        "Transform {{ {steps} Sphere {{ center 0 0 0 radius 1 }} }}"
    ));
    assert_eq!(objects.len(), 1);
    objects.remove(0)
}

#[track_caller]
fn assert_maps(object: &Object, from: [f64; 3], to: [f64; 3]) {
    let got = map(object, Point3::from(from));
    let want = Point3::from(to);
    assert!(
        (got - want).norm() < 1e-12,
        "{from:?} -> {got}, want {want}"
    );
}

#[test]
fn translate() {
    let o = transformed("Translate 1 -2 3");
    assert_eq!(
        o.transform,
        Some(Matrix4::new_translation(&[1.0, -2.0, 3.0].into()))
    );
    assert_maps(&o, [1.0, 1.0, 1.0], [2.0, -1.0, 4.0]);
}

#[test]
fn scale_is_non_uniform() {
    let o = transformed("Scale 2 3 -4");
    assert_maps(&o, [1.0, 1.0, 1.0], [2.0, 3.0, -4.0]);
}

#[test]
fn uniform_scale() {
    let o = transformed("UniformScale 0.5");
    assert_maps(&o, [2.0, 4.0, -6.0], [1.0, 2.0, -3.0]);
}

#[test]
fn axis_rotations_are_right_handed_in_degrees() {
    assert_maps(&transformed("XRotate 90"), [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert_maps(&transformed("YRotate 90"), [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    assert_maps(&transformed("ZRotate 90"), [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    assert_maps(
        &transformed("ZRotate -45"),
        [1.0, 0.0, 0.0],
        [0.5f64.sqrt(), -(0.5f64.sqrt()), 0.0],
    );
}

#[test]
fn rotate_about_an_axis() {
    let o = transformed("Rotate { 0 0 2 90 }");
    assert_maps(&o, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
}

#[test]
fn steps_compose_in_the_order_written() {
    // M = T(1,0,0) · Ry(90°) · S(2,1,1): the scale applies first.
    // (1,0,0) → scale (2,0,0) → rotate (0,0,−2) → translate (1,0,−2);
    // (0,0,1) → scale (0,0,1) → rotate (1,0,0)  → translate (2,0,0).
    let o = transformed("Translate 1 0 0  YRotate 90  Scale 2 1 1");
    assert_maps(&o, [1.0, 0.0, 0.0], [1.0, 0.0, -2.0]);
    assert_maps(&o, [0.0, 0.0, 1.0], [2.0, 0.0, 0.0]);
    assert_maps(&o, [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]);
    // And against the hand-built product, entry by entry.
    #[rustfmt::skip]
    let want = Matrix4::new(
        0.0, 0.0, 1.0, 1.0,
        0.0, 1.0, 0.0, 0.0,
        -2.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    );
    let got = o.transform.expect("a matrix");
    assert!((got - want).amax() < 1e-15, "{got}");
}

#[test]
fn nested_transforms_and_groups_compose() {
    let objects = objects_of(
        "Transform { Translate 0 1 0\n\
           Group { numObjects 2\n\
             Transform { UniformScale 3 Sphere { center 0 0 0 radius 1 } }\n\
             Sphere { center 0 0 0 radius 1 } } }\n\
         Sphere { center 0 0 0 radius 1 }",
    );
    assert_eq!(objects.len(), 3);
    assert_maps(&objects[0], [1.0, 0.0, 0.0], [3.0, 1.0, 0.0]);
    assert_maps(&objects[1], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]);
    assert!(objects[2].transform.is_none());
}

#[test]
fn identity_transform_is_none() {
    assert!(transformed("UniformScale 1").transform.is_none());
    assert!(transformed("").transform.is_none());
    assert!(transformed("Translate 1 0 0").transform.is_some());
}

#[test]
fn material_index_is_scoped_to_its_group() {
    let scene = parse(&format!(
        "{CAMERA}Materials {{ numMaterials 3 Material {{ }} Material {{ }} Material {{ }} }}\n\
         Group {{\n\
           Sphere {{ center 0 0 0 radius 1 }}\n\
           MaterialIndex 1\n\
           Sphere {{ center 0 0 0 radius 1 }}\n\
           Group {{\n\
             Sphere {{ center 0 0 0 radius 1 }}\n\
             MaterialIndex 2\n\
             Sphere {{ center 0 0 0 radius 1 }}\n\
           }}\n\
           Sphere {{ center 0 0 0 radius 1 }}\n\
           Transform {{ Translate 1 0 0 Sphere {{ center 0 0 0 radius 1 }} }}\n\
           MaterialIndex 0\n\
           Plane {{ normal 0 1 0 offset 0 }}\n\
         }}"
    ));
    let materials: Vec<usize> = scene.objects.iter().map(|o| o.material).collect();
    assert_eq!(materials, vec![0, 1, 1, 2, 1, 1, 0]);
    assert!(matches!(scene.objects[6].shape, Shape::Plane { .. }));
}

//! Every object kind, with its fields; meshes read from OBJ fixtures.

use std::sync::Arc;

use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::{BSpline, Curve};

use super::{CAMERA, TempDir, objects_of, parse};
use crate::scene::{RevolutionBody, Shape};

#[test]
fn sphere() {
    let objects = objects_of("Sphere { center 1 2 3 radius 0.5 }");
    assert_eq!(objects.len(), 1);
    assert!(matches!(
        objects[0].shape,
        Shape::Sphere { center, radius } if center == Point3::new(1.0, 2.0, 3.0) && radius == 0.5
    ));
    assert_eq!(objects[0].material, 0);
    assert!(objects[0].transform.is_none());
}

#[test]
fn plane() {
    let objects = objects_of("Plane { normal 0 1 0 offset -2 }");
    assert!(matches!(
        objects[0].shape,
        Shape::Plane { normal, offset } if normal == Vector3::y() && offset == -2.0
    ));
}

#[test]
fn triangle() {
    let objects = objects_of("Triangle { vertex0 0 0 0 vertex1 1 0 0 vertex2 0 1 2 }");
    let Shape::Triangle { vertices } = objects[0].shape else {
        panic!("not a triangle: {:?}", objects[0].shape);
    };
    assert_eq!(
        vertices,
        [
            Point3::origin(),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 2.0)
        ]
    );
}

#[test]
fn box_disk_ring_rectangle() {
    let objects = objects_of(
        "Box { min -1 -2 -3 max 1 2 3 }\n\
         Disk { center 0 1 0 normal 0 0 2 radius 3 }\n\
         Ring { center 1 1 1 normal 1 0 0 inner 0.5 outer 2 }\n\
         Rectangle { corner 0 0 1 edge1 2 0 0 edge2 0 3 0 }",
    );
    assert_eq!(objects.len(), 4);
    assert!(matches!(
        objects[0].shape,
        Shape::Box { min, max } if min == Point3::new(-1.0, -2.0, -3.0) && max == Point3::new(1.0, 2.0, 3.0)
    ));
    assert!(matches!(
        objects[1].shape,
        Shape::Disk { center, normal, radius }
            if center == Point3::new(0.0, 1.0, 0.0) && normal == Vector3::new(0.0, 0.0, 2.0) && radius == 3.0
    ));
    assert!(matches!(
        objects[2].shape,
        Shape::Ring { center, normal, inner, outer }
            if center == Point3::new(1.0, 1.0, 1.0) && normal == Vector3::x() && inner == 0.5 && outer == 2.0
    ));
    assert!(matches!(
        objects[3].shape,
        Shape::Rectangle { corner, edge1, edge2 }
            if corner == Point3::new(0.0, 0.0, 1.0) && edge1 == Vector3::new(2.0, 0.0, 0.0) && edge2 == Vector3::new(0.0, 3.0, 0.0)
    ));
}

#[test]
fn ring_may_have_zero_inner_radius() {
    let objects = objects_of("Ring { center 0 0 0 normal 0 1 0 inner 0 outer 1 }");
    assert!(matches!(objects[0].shape, Shape::Ring { inner, .. } if inner == 0.0));
}

/// An OBJ file with every face-corner form, relative indices, a quad and the
/// statements the reader skips.
const OBJ: &str = "# a quad, a triangle and a late vertex\n\
mtllib things.mtl\n\
o thing\n\
v 0 0 0\n\
v 1 0 0\n\
v 1 1 0\n\
v 0 1 0\n\
vt 0 0\n\
vn 0 0 1\n\
g side\n\
s off\n\
usemtl red\n\
f 1/1/1 2/1/1 3/1/1 4/1/1\n\
f -4//1 -2//1 -1//1   # relative\n\
v 0 0 1 1.0\n\
f 5/1 1 2\n";

#[test]
fn triangle_mesh_from_obj_relative_to_the_scene() {
    let dir = TempDir::new("mesh");
    dir.write("mesh/quad.obj", OBJ.as_bytes());
    let scene = dir
        .parse_scene(&format!(
            "{CAMERA}Group {{ numObjects 2 TriangleMesh {{ obj_file mesh/quad.obj }}\nTriangleMesh {{ obj_file mesh/quad.obj }} }}"
        ))
        .unwrap_or_else(|e| panic!("{e}"));
    let Shape::Mesh(mesh) = &scene.objects[0].shape else {
        panic!("not a mesh: {:?}", scene.objects[0].shape);
    };
    assert_eq!(
        mesh.vertices,
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(1.0, 1.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ]
    );
    assert_eq!(
        mesh.triangles,
        vec![[0, 1, 2], [0, 2, 3], [0, 2, 3], [4, 0, 1]]
    );
    // The second use shares the first one's mesh.
    let Shape::Mesh(again) = &scene.objects[1].shape else {
        panic!("not a mesh");
    };
    assert!(Arc::ptr_eq(mesh, again));
}

#[test]
fn rev_surface_bezier_profile_uses_x_and_y() {
    let objects = objects_of(
        "RevSurface { profile BezierCurve { controls [ -1 0 0 ] [ -2 1 0 ] [ -1 2 0 ] } }",
    );
    let Shape::Revolution(body) = &objects[0].shape else {
        panic!("not a revolution: {:?}", objects[0].shape);
    };
    let RevolutionBody::Bezier(surface) = &**body else {
        panic!("not a Bézier profile");
    };
    assert_eq!(
        surface.profile().points(),
        &[
            Point2::new(-1.0, 0.0),
            Point2::new(-2.0, 1.0),
            Point2::new(-1.0, 2.0)
        ]
    );
    assert_eq!(surface.profile().degree(), 2);
}

#[test]
fn rev_surface_bspline_profile_has_uniform_cubic_knots() {
    let objects = objects_of(
        "RevSurface { profile BsplineCurve { controls [ -1 0 0 ] [ -1 1 0 ] [ -2 2 0 ] [ -1 3 0 ] } }",
    );
    let Shape::Revolution(body) = &objects[0].shape else {
        panic!("not a revolution");
    };
    let RevolutionBody::BSpline(surface) = &**body else {
        panic!("not a B-spline profile");
    };
    let spline = surface.profile();
    assert_eq!(spline.degree(), 3);
    let knots: Vec<f64> = (0..=7).map(|i| f64::from(i) / 7.0).collect();
    assert_eq!(spline.knots(), &knots[..]);
    assert_eq!(spline.points()[2], Point2::new(-2.0, 2.0));
    assert_eq!(spline.domain(), (3.0 / 7.0, 4.0 / 7.0));
}

#[test]
fn bezier_curve_in_a_group_is_a_tube() {
    let objects = objects_of("BezierCurve { controls [ 0 0 0 ] [ 1 2 0 ] [ 2 0 0 ] }");
    let Shape::Tube(tube) = &objects[0].shape else {
        panic!("not a tube: {:?}", objects[0].shape);
    };
    let extent = 8f64.sqrt();
    assert_eq!(tube.radius, 0.01 * extent);
    assert_eq!(tube.points.first(), Some(&Point3::origin()));
    assert_eq!(tube.points.last(), Some(&Point3::new(2.0, 0.0, 0.0)));
    assert!(tube.points.len() > 3, "{} points", tube.points.len());
    // The curve peaks at (1, 1, 0); the flattening follows it to 1e-3 × extent.
    let top = tube.points.iter().map(|p| p.y).fold(0.0, f64::max);
    assert!((top - 1.0).abs() <= 1e-3 * extent, "top {top}");
}

#[test]
fn bspline_curve_in_a_group_is_a_tube_over_its_domain() {
    let objects = objects_of("BsplineCurve { controls [ 0 0 0 ] [ 1 1 0 ] [ 2 0 0 ] [ 3 1 0 ] }");
    let Shape::Tube(tube) = &objects[0].shape else {
        panic!("not a tube");
    };
    assert_eq!(tube.radius, 0.01 * 10f64.sqrt());
    // Uniform cubic: the curve runs from (P0 + 4 P1 + P2)/6 to (P1 + 4 P2 + P3)/6.
    let first = tube.points.first().expect("points");
    let last = tube.points.last().expect("points");
    assert!(
        (first - Point3::new(1.0, 2.0 / 3.0, 0.0)).norm() < 1e-12,
        "{first}"
    );
    assert!(
        (last - Point3::new(2.0, 1.0 / 3.0, 0.0)).norm() < 1e-12,
        "{last}"
    );
    // Every flattening point lies on the curve.
    let spline = BSpline::uniform(
        3,
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 1.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
            Point3::new(3.0, 1.0, 0.0),
        ],
    )
    .expect("a valid spline");
    let on_curve = |p: &Point3<f64>| {
        spline
            .discretize(2000)
            .iter()
            .any(|s| (s.point - p).norm() < 2e-3)
    };
    assert!(tube.points.iter().all(on_curve));
}

#[test]
fn tiny_tube_has_the_minimum_radius() {
    let objects = objects_of("BezierCurve { controls [ 0 0 0 ] [ 0.01 0 0 ] }");
    let Shape::Tube(tube) = &objects[0].shape else {
        panic!("not a tube");
    };
    assert_eq!(tube.radius, 0.001);
    assert_eq!(tube.points.len(), 2);
}

#[test]
fn group_counts_objects_not_material_indices_and_nested_groups_count_once() {
    let scene = parse(&format!(
        "{CAMERA}Materials {{ numMaterials 2 Material {{ }} Material {{ }} }}\n\
         Group {{ numObjects 2\n MaterialIndex 0\n Group {{ numObjects 3 Sphere {{ center 0 0 0 radius 1 }}\n\
         MaterialIndex 1 Sphere {{ center 0 0 0 radius 1 }} Group {{ numObjects 0 }} }}\n\
         Plane {{ normal 0 1 0 offset 0 }} }}"
    ));
    assert_eq!(scene.objects.len(), 3);
}

#[test]
fn group_without_num_objects_is_accepted() {
    let objects = objects_of("Sphere { center 0 0 0 radius 1 } Sphere { center 1 0 0 radius 1 }");
    assert_eq!(objects.len(), 2);
}

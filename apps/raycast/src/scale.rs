//! The scene's scale, and the offset that keeps secondary rays off the
//! surface they start from.
//!
//! The scale is the largest absolute world coordinate of the camera, the
//! lights and the objects' bounding points (sphere and disk extremes, box
//! corners, mesh and tube vertices, the corners of a revolution body's or
//! a surface's bounding box, a plane's point nearest the origin), each taken through
//! its object's transform. A hit point carries a rounding error relative to
//! that magnitude (and revolve's solver accepts a residual of about 1e-9
//! times the object's scale), so secondary rays start
//! [`EPSILON_RELATIVE`] × scale off the surface, along the normal on the side
//! they leave by, and ignore hits closer than that.

use revolve::nalgebra::{Matrix4, Point3};
use revolve::{Aabb, Intersect};

use crate::scene::{Light, RevolutionBody, Scene, Shape};

/// The self-intersection offset relative to the scene's scale.
pub const EPSILON_RELATIVE: f64 = 1e-6;

/// The largest absolute coordinate in the scene (see the module docs); 1 for
/// an empty scene with the camera at the origin.
pub fn scene_scale(scene: &Scene) -> f64 {
    let mut scale = scene.camera.center.coords.amax();
    let mut include = |p: &Point3<f64>, m: &Option<Matrix4<f64>>| {
        let q = match m {
            Some(m) => m.transform_point(p),
            None => *p,
        };
        let a = q.coords.amax();
        if a.is_finite() {
            scale = scale.max(a);
        }
    };
    for light in &scene.lights {
        match light {
            Light::Point { position, .. } => include(position, &None),
            Light::Area {
                corner,
                edge1,
                edge2,
                ..
            } => {
                include(corner, &None);
                include(&(corner + edge1 + edge2), &None);
            }
            Light::Directional { .. } => {}
        }
    }
    for object in &scene.objects {
        let m = &object.transform;
        match &object.shape {
            Shape::Sphere { center, radius } => {
                include(&center.map(|c| c + radius.abs()), m);
                include(&center.map(|c| c - radius.abs()), m);
            }
            Shape::Plane { normal, offset } => {
                let n2 = normal.norm_squared();
                if n2 > 0.0 {
                    include(&Point3::from(normal * (offset / n2)), m);
                }
            }
            Shape::Triangle { vertices } => vertices.iter().for_each(|v| include(v, m)),
            Shape::Mesh(mesh) => mesh.vertices.iter().for_each(|v| include(v, m)),
            Shape::Box { min, max } => {
                include(min, m);
                include(max, m);
            }
            Shape::Disk { center, radius, .. } => {
                include(&center.map(|c| c + radius.abs()), m);
                include(&center.map(|c| c - radius.abs()), m);
            }
            Shape::Ring { center, outer, .. } => {
                include(&center.map(|c| c + outer.abs()), m);
                include(&center.map(|c| c - outer.abs()), m);
            }
            Shape::Rectangle {
                corner,
                edge1,
                edge2,
            } => {
                include(corner, m);
                include(&(corner + edge1), m);
                include(&(corner + edge2), m);
                include(&(corner + edge1 + edge2), m);
            }
            Shape::Revolution(body) => {
                let b = match body.as_ref() {
                    RevolutionBody::Bezier(r) => r.bounds(),
                    RevolutionBody::BSpline(r) => r.bounds(),
                    RevolutionBody::Nurbs(r) => r.bounds(),
                };
                corners(&b).iter().for_each(|c| include(c, m));
            }
            Shape::Tube(tube) => tube.points.iter().for_each(|p| include(p, m)),
            Shape::Surface(body) => corners(&body.bounds()).iter().for_each(|c| include(c, m)),
        }
    }
    if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    }
}

/// The eight corners of `b`; none when it is empty.
fn corners(b: &Aabb) -> Vec<Point3<f64>> {
    if b.is_empty() {
        return Vec::new();
    }
    (0..8)
        .map(|i| {
            Point3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Camera, Object, RenderSettings};
    use revolve::nalgebra::Vector3;

    #[test]
    fn scale_follows_the_farthest_transformed_object() {
        let mut scene = Scene {
            camera: Camera {
                center: Point3::new(0.0, 0.0, 2.0),
                direction: -Vector3::z(),
                up: Vector3::y(),
                angle_degrees: 45.0,
                width: 1,
                height: 1,
            },
            lights: vec![],
            background: Vector3::zeros(),
            materials: vec![],
            objects: vec![],
            render: RenderSettings::default(),
        };
        assert_eq!(scene_scale(&scene), 2.0);
        scene.objects.push(Object {
            shape: Shape::Sphere {
                center: Point3::new(1.0, 0.0, 0.0),
                radius: 0.5,
            },
            material: 0,
            transform: Some(Matrix4::new_translation(&Vector3::new(0.0, -10.0, 0.0))),
        });
        assert_eq!(scene_scale(&scene), 10.5);
    }
}

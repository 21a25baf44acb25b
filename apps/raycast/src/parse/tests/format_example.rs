//! The example scene of `SCENE_FORMAT.md`, verbatim, with a cube mesh.

use revolve::nalgebra::{Point3, Vector3};

use super::TempDir;
use crate::scene::{Light, RevolutionBody, Shape};

/// The example of the format's documentation.
const EXAMPLE: &str = r#"PerspectiveCamera {
    center 0 0 10          # eye position
    direction 0 0 -1       # view direction (need not be unit)
    up 0 1 0
    angle 45               # vertical field of view, degrees
    width 400              # image size in pixels
    height 400
}

Lights {
    numLights 2
    DirectionalLight { direction -0.5 -0.5 -0.5  color 0.9 0.9 0.9 }
    PointLight { position 0 5 5  color 0.9 0.9 0.9 }
}

Background { color 0.1 0.1 0.2 }

Materials {
    numMaterials 2
    PhongMaterial { diffuseColor 1 0 0  specularColor 1 1 1  shininess 20 }
    Material { diffuseColor 0.9 0.9 1 }      # same keywords; missing ones default to 0
}

Group {
    numObjects 5           # counts the objects, not the MaterialIndex lines
    MaterialIndex 0        # applies to the objects that follow, until the next one
    Sphere { center 0 0 0  radius 1 }
    Plane { normal 0 1 0  offset -2 }        # points p with dot(normal, p) = offset
    Triangle { vertex0 0 0 0  vertex1 1 0 0  vertex2 0 1 0 }
    TriangleMesh { obj_file mesh/cube.obj }  # path relative to the scene file
    MaterialIndex 1
    Transform {
        Translate 1 0 0      # transforms compose in the order written,
        YRotate 30           # each one applying to what comes after it
        Scale 1 2 1          # also UniformScale s, XRotate/ZRotate deg
        RevSurface {
            profile BsplineCurve {
                controls
                    [ -1 0 0 ]
                    [ -1 1 0 ]
                    [ -2 2 0 ]
                    [ -1 3 0 ]
            }
        }
    }
}
"#;

/// A unit cube: 8 vertices, 6 quads.
const CUBE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

#[test]
fn the_documented_example_parses() {
    let dir = TempDir::new("example");
    dir.write("mesh/cube.obj", CUBE.as_bytes());
    let scene = dir.parse_scene(EXAMPLE).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.camera.center, Point3::new(0.0, 0.0, 10.0));
    assert_eq!((scene.camera.width, scene.camera.height), (400, 400));
    assert_eq!(scene.lights.len(), 2);
    assert!(
        matches!(scene.lights[1], Light::Point { position, .. } if position == Point3::new(0.0, 5.0, 5.0))
    );
    assert_eq!(scene.background, Vector3::new(0.1, 0.1, 0.2));
    assert_eq!(scene.materials.len(), 2);
    assert_eq!(scene.materials[1].diffuse, Vector3::new(0.9, 0.9, 1.0));
    assert_eq!(scene.objects.len(), 5);
    let materials: Vec<usize> = scene.objects.iter().map(|o| o.material).collect();
    assert_eq!(materials, vec![0, 0, 0, 0, 1]);
    let Shape::Mesh(cube) = &scene.objects[3].shape else {
        panic!("not a mesh: {:?}", scene.objects[3].shape);
    };
    assert_eq!((cube.vertices.len(), cube.triangles.len()), (8, 12));
    let revolution = &scene.objects[4];
    assert!(
        matches!(&revolution.shape, Shape::Revolution(body) if matches!(**body, RevolutionBody::BSpline(_)))
    );
    // Translate 1 0 0 · YRotate 30 · Scale 1 2 1: the axis point (0, 1, 0)
    // goes to (0, 2, 0) and then to (1, 2, 0).
    let m = revolution.transform.expect("a transform");
    let p = m.transform_point(&Point3::new(0.0, 1.0, 0.0));
    assert!((p - Point3::new(1.0, 2.0, 0.0)).norm() < 1e-12, "{p}");
}

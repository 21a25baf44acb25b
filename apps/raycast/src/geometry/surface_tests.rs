//! Surfaces and patch models in the world, against closed forms and, for
//! a model (revolve's hierarchy over its patches), against every patch
//! tried in turn.

use std::sync::Arc;

use revolve::nalgebra::{Point3, Vector3};
use revolve::{BSplineSurface, BezierPatches, BezierSurface, Intersect, NurbsSurface, Ray};

use super::{IntersectStats, SurfaceHit, World};
use crate::scene::{Camera, Material, Object, RenderSettings, Scene, Shape, SurfaceBody};

/// A world of the one surface `body`, untransformed.
fn world(body: SurfaceBody) -> World {
    World::new(&Scene {
        camera: Camera {
            center: Point3::origin(),
            direction: -Vector3::z(),
            up: Vector3::y(),
            angle_degrees: 45.0,
            width: 4,
            height: 4,
        },
        lights: vec![],
        background: Vector3::zeros(),
        materials: vec![Material::default()],
        objects: vec![Object {
            shape: Shape::Surface(Arc::new(body)),
            material: 0,
            transform: None,
        }],
        render: RenderSettings::default(),
    })
}

fn first_hit(w: &World, r: &Ray) -> Option<SurfaceHit> {
    w.intersect(r, 0.0, f64::INFINITY, &mut IntersectStats::default())
}

/// Points of a `k × k` grid strictly inside `(0, 1)²`.
fn inner_grid(k: u32) -> impl Iterator<Item = (f64, f64)> {
    (1..k).flat_map(move |i| {
        (1..k).map(move |j| (f64::from(i) / f64::from(k), f64::from(j) / f64::from(k)))
    })
}

#[test]
fn a_bezier_patch_is_hit_where_its_closed_form_says() {
    // S(u, v) = (u, v, u·v); normal ∝ S_u × S_v = (−v, −u, 1).
    let patch = BezierSurface::new(vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
        vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    let w = world(SurfaceBody::Bezier(patch));
    for (x, y) in inner_grid(8) {
        let h = first_hit(&w, &Ray::new(Point3::new(x, y, 10.0), -Vector3::z())).expect("a hit");
        assert!((h.t - (10.0 - x * y)).abs() < 1e-12, "t {}", h.t);
        assert!((h.point - Point3::new(x, y, x * y)).norm() < 1e-12);
        let n = Vector3::new(-y, -x, 1.0).normalize();
        assert!((h.normal.into_inner() - n).norm() < 1e-9, "{:?}", h.normal);
        assert!(
            (h.uv.0 - x).abs() < 1e-9 && (h.uv.1 - y).abs() < 1e-9,
            "{:?}",
            h.uv
        );
    }
    // Beside the patch: no hit.
    assert!(first_hit(&w, &Ray::new(Point3::new(1.5, 0.5, 10.0), -Vector3::z())).is_none());
}

#[test]
fn a_bspline_surface_has_its_uv_scaled_from_its_domain() {
    // x = 2u, y = v on [0, 2], z = 2u(1 − u) = x(1 − x/2).
    let s = BSplineSurface::new(
        (2, 1),
        (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 2.0, 2.0]),
        vec![
            vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 2.0, 0.0)],
            vec![Point3::new(1.0, 0.0, 1.0), Point3::new(1.0, 2.0, 1.0)],
            vec![Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 2.0, 0.0)],
        ],
    )
    .unwrap();
    let w = world(SurfaceBody::BSpline(s));
    for (a, b) in inner_grid(6) {
        let (x, y) = (2.0 * a, 2.0 * b);
        let h = first_hit(&w, &Ray::new(Point3::new(x, y, 5.0), -Vector3::z())).expect("a hit");
        assert!(
            (h.point.z - x * (1.0 - x / 2.0)).abs() < 1e-12,
            "{}",
            h.point
        );
        assert!(
            (h.uv.0 - a).abs() < 1e-9 && (h.uv.1 - b).abs() < 1e-9,
            "{:?}",
            h.uv
        );
    }
}

#[test]
fn a_nurbs_surface_is_hit_on_its_exact_cylinder() {
    // The quarter of the unit cylinder about z, 0 ≤ z ≤ 2.
    let w2 = std::f64::consts::FRAC_1_SQRT_2;
    let s = NurbsSurface::new(
        (2, 1),
        (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
        vec![
            vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 0.0, 2.0)],
            vec![Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 1.0, 2.0)],
            vec![Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 1.0, 2.0)],
        ],
        vec![vec![1.0, 1.0], vec![w2, w2], vec![1.0, 1.0]],
    )
    .unwrap();
    let w = world(SurfaceBody::Nurbs(s));
    for k in 1..16 {
        let angle = f64::from(k) / 16.0 * std::f64::consts::FRAC_PI_2;
        let d = Vector3::new(angle.cos(), angle.sin(), 0.0);
        let h = first_hit(&w, &Ray::new(Point3::new(0.0, 0.0, 1.0), d)).expect("a hit");
        assert!((h.t - 1.0).abs() < 1e-12, "t {}", h.t);
        assert!(h.normal.dot(&d).abs() > 1.0 - 1e-9, "{:?}", h.normal);
    }
}

/// The bundled teapot's patches.
fn teapot() -> Vec<BezierSurface> {
    let scenes = crate::repo_root().join("scenes");
    let text = "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 45 width 4 height 4 }\n\
                Group { BezierPatches { file data/teapot.txt } }";
    let scene = crate::parse::parse_str(text, &scenes.join("test.txt")).unwrap();
    let Shape::Surface(body) = &scene.objects[0].shape else {
        panic!("not a surface");
    };
    let SurfaceBody::Patches(model) = &**body else {
        panic!("not a patch model");
    };
    model.patches().to_vec()
}

#[test]
fn the_teapot_lid_is_hit_at_its_knob() {
    // The knob's top is the collapsed edge of the lid's first patches, at
    // (0, 0, 3.15) in the classic data; its tangent plane is level.
    let w = world(SurfaceBody::Patches(BezierPatches::new(teapot()).unwrap()));
    let h = first_hit(&w, &Ray::new(Point3::new(0.0, 0.0, 10.0), -Vector3::z())).expect("a hit");
    assert!((h.t - 6.85).abs() < 1e-12, "t {}", h.t);
    assert!(h.normal.z.abs() > 1.0 - 1e-9, "{:?}", h.normal);
}

#[test]
fn a_models_hierarchy_finds_the_nearest_patch() {
    // Rays from a sphere round the teapot toward points in its box: the
    // world's hit is the nearest of the hits of all 32 patches, each
    // intersected on its own (to the last few bits).
    let patches = teapot();
    let w = world(SurfaceBody::Patches(
        BezierPatches::new(patches.clone()).unwrap(),
    ));
    let mut seed = 0x7ea_u64;
    let mut next = || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut hits = 0;
    for _ in 0..300 {
        let theta = next() * std::f64::consts::TAU;
        let z = 2.0 * next() - 1.0;
        let r = (1.0 - z * z).sqrt();
        let origin = Point3::new(8.0 * r * theta.cos(), 8.0 * r * theta.sin(), 1.5 + 8.0 * z);
        let target = Point3::new(6.5 * next() - 3.0, 4.0 * next() - 2.0, 3.15 * next());
        let ray = Ray::new(origin, target - origin);
        let brute = patches
            .iter()
            .filter_map(|p| p.intersect(&ray, 0.0, f64::INFINITY))
            .map(|h| h.t)
            .fold(f64::INFINITY, f64::min);
        match first_hit(&w, &ray) {
            Some(h) => {
                hits += 1;
                // Both polished to full precision; the model's tolerance
                // scale (its whole box) may stop Newton one step apart.
                assert!(
                    (h.t - brute).abs() <= 1e-14 * brute,
                    "{ray:?}: {} vs {brute}",
                    h.t
                );
            }
            None => assert!(
                brute.is_infinite(),
                "{ray:?} misses but a patch is hit at {brute}"
            ),
        }
    }
    assert!(hits > 100, "only {hits} of 300 rays hit the teapot");
}

//! Geometry tests against closed-form references.

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::Arc;

use revolve::nalgebra::{Matrix3, Matrix4, Point2, Point3, Vector3};
use revolve::{BSpline, Bezier, Ray, Revolution};

use super::bvh::MAX_DEPTH;
use super::object::Prim;
use super::*;
use crate::scene::{
    Camera, Material, Object, RenderSettings, RevolutionBody, Shape, TriangleMesh, Tube,
};

// ---------------------------------------------------------------- helpers

/// SplitMix64: a small deterministic generator for the random tests.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn vec(&mut self, lo: f64, hi: f64) -> Vector3<f64> {
        Vector3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
    }

    fn point(&mut self, lo: f64, hi: f64) -> Point3<f64> {
        Point3::from(self.vec(lo, hi))
    }
}

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

fn ray(o: Point3<f64>, d: Vector3<f64>) -> Ray {
    Ray::new(o, d)
}

fn object(shape: Shape) -> Object {
    Object {
        shape,
        material: 0,
        transform: None,
    }
}

fn placed(shape: Shape, m: Matrix4<f64>) -> Object {
    Object {
        shape,
        material: 0,
        transform: Some(m),
    }
}

/// Material 0 is plain, material 1 emits.
fn scene(objects: Vec<Object>) -> Scene {
    let emissive = Material {
        emission: Vector3::repeat(1.0),
        ..Material::default()
    };
    Scene {
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
        materials: vec![Material::default(), emissive],
        objects,
        render: RenderSettings::default(),
    }
}

fn world(objects: Vec<Object>) -> World {
    World::new(&scene(objects))
}

fn first_hit(w: &World, r: &Ray) -> Option<SurfaceHit> {
    w.intersect(r, 0.0, f64::INFINITY, &mut IntersectStats::default())
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[track_caller]
fn assert_vec(got: &Vector3<f64>, want: &Vector3<f64>, tol: f64) {
    assert!((got - want).norm() <= tol, "got {got:?}, want {want:?}");
}

#[track_caller]
fn assert_hit(
    h: Option<SurfaceHit>,
    t: f64,
    point: Point3<f64>,
    normal: Vector3<f64>,
    uv: Option<(f64, f64)>,
) -> SurfaceHit {
    let h = h.expect("expected a hit");
    assert!(close(h.t, t, 1e-9), "t = {}, want {t}", h.t);
    assert_vec(&h.point.coords, &point.coords, 1e-9);
    assert_vec(&h.normal, &normal, 1e-9);
    if let Some(uv) = uv {
        assert!(
            close(h.uv.0, uv.0, 1e-9) && close(h.uv.1, uv.1, 1e-9),
            "uv = {:?}, want {uv:?}",
            h.uv
        );
    }
    h
}

/// `T(t)·R_y(angle)·S(s)`.
fn trs(t: Vector3<f64>, angle: f64, s: Vector3<f64>) -> Matrix4<f64> {
    Matrix4::new_translation(&t)
        * Matrix4::from_axis_angle(&Vector3::y_axis(), angle)
        * Matrix4::new_nonuniform_scaling(&s)
}

/// A unit cube `[0, 1]³` as 12 triangles wound counter-clockwise seen from
/// outside.
fn cube_mesh() -> Arc<TriangleMesh> {
    let vertices = (0..8)
        .map(|i| p((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
        .collect();
    // Faces as quads (a, b, c, d) counter-clockwise from outside.
    let quads = [
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 1
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 1
        [0, 2, 3, 1], // z = 0
        [4, 5, 7, 6], // z = 1
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    Arc::new(TriangleMesh {
        vertices,
        triangles,
    })
}

fn bspline_body(points: &[(f64, f64)], degree: usize) -> Shape {
    let pts = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    let curve = BSpline::clamped(degree, pts).unwrap();
    Shape::Revolution(Arc::new(RevolutionBody::BSpline(Revolution::new(curve))))
}

fn bezier_body(points: &[(f64, f64)]) -> Shape {
    let pts = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    let curve = Bezier::new(pts).unwrap();
    Shape::Revolution(Arc::new(RevolutionBody::Bezier(Revolution::new(curve))))
}

// ---------------------------------------------------------------- shapes

#[test]
fn sphere_hit_from_outside_inside_and_miss() {
    let w = world(vec![object(Shape::Sphere {
        center: p(1.0, 0.0, 0.0),
        radius: 2.0,
    })]);
    // Non-unit direction: t in units of |d| = 2.
    let h = first_hit(&w, &ray(p(1.0, 0.0, 10.0), v(0.0, 0.0, -2.0)));
    // n = +z: longitude atan2(−1, 0) = −π/2 → 3/4 of a turn; latitude ½.
    assert_hit(h, 4.0, p(1.0, 0.0, 2.0), Vector3::z(), Some((0.75, 0.5)));
    // Top pole: v = 1.
    let h = first_hit(&w, &ray(p(1.0, 5.0, 0.0), v(0.0, -1.0, 0.0)));
    let h = assert_hit(h, 3.0, p(1.0, 2.0, 0.0), Vector3::y(), None);
    assert!(close(h.uv.1, 1.0, 1e-12));
    // From the centre: the exit, normal still outward.
    let h = first_hit(&w, &ray(p(1.0, 0.0, 0.0), v(1.0, 0.0, 0.0)));
    assert_hit(h, 2.0, p(3.0, 0.0, 0.0), Vector3::x(), Some((0.0, 0.5)));
    // Miss beside, and behind the ray.
    assert!(first_hit(&w, &ray(p(3.01, 0.0, 10.0), v(0.0, 0.0, -1.0))).is_none());
    assert!(first_hit(&w, &ray(p(1.0, 0.0, 10.0), v(0.0, 0.0, 1.0))).is_none());
}

#[test]
fn t_min_skips_the_surface_a_secondary_ray_leaves() {
    let w = world(vec![object(Shape::Sphere {
        center: Point3::origin(),
        radius: 1.0,
    })]);
    let mut s = IntersectStats::default();
    let on = p(0.0, 0.0, 1.0);
    // Leaving outward: nothing. Going in: the far side at t = 2.
    assert!(
        w.intersect(&ray(on, Vector3::z()), 1e-9, 1e9, &mut s)
            .is_none()
    );
    let h = w.intersect(&ray(on, -Vector3::z()), 1e-9, 1e9, &mut s);
    assert_hit(h, 2.0, p(0.0, 0.0, -1.0), -Vector3::z(), None);
    // t_max cuts it off.
    assert!(
        w.intersect(&ray(on, -Vector3::z()), 1e-9, 1.5, &mut s)
            .is_none()
    );
}

#[test]
fn small_far_sphere_is_hit_accurately() {
    // Closest approach 0.999e-6 from the centre of a 1e-6 sphere at 1e4: the
    // discriminant from the closest approach keeps its digits.
    let w = world(vec![object(Shape::Sphere {
        center: p(0.0, 0.0, -1e4),
        radius: 1e-6,
    })]);
    let y = 0.6e-6;
    let h = first_hit(&w, &ray(p(0.0, y, 0.0), -Vector3::z())).expect("hit");
    let want = 1e4 - (1e-12 - y * y).sqrt();
    assert!(close(h.t, want, 1e-12 * 1e4), "t = {}, want {want}", h.t);
    assert_vec(&h.normal, &v(0.0, 0.6, 0.8), 1e-5);
}

#[test]
fn plane_hit_parallel_miss_and_tiling_uv() {
    // 2y = −4: y = −2, normal +y.
    let w = world(vec![object(Shape::Plane {
        normal: v(0.0, 2.0, 0.0),
        offset: -4.0,
    })]);
    let h = first_hit(&w, &ray(p(0.25, 5.0, 0.5), v(0.0, -1.0, 0.0)));
    let h = assert_hit(h, 7.0, p(0.25, -2.0, 0.5), Vector3::y(), None);
    assert!((0.0..1.0).contains(&h.uv.0) && (0.0..1.0).contains(&h.uv.1));
    // From below the normal is the same (not flipped toward the ray).
    let h = first_hit(&w, &ray(p(0.0, -5.0, 0.0), v(0.0, 1.0, 0.0)));
    assert_hit(h, 3.0, p(0.0, -2.0, 0.0), Vector3::y(), None);
    // Parallel and away: miss.
    assert!(first_hit(&w, &ray(p(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0))).is_none());
    assert!(first_hit(&w, &ray(p(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0))).is_none());
    // UV tiles with period 1: shifting by an in-plane unit vector moves the
    // UV by that vector's coordinates modulo 1.
    let at = |x: f64, z: f64| first_hit(&w, &ray(p(x, 1.0, z), -Vector3::y())).unwrap().uv;
    let (a, b) = (at(0.1, 0.2), at(0.1 + 1e-3, 0.2));
    let du = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    assert!(close(du, 1e-3, 1e-9), "uv moved {du}");
}

#[test]
fn triangle_hit_barycentric_uv_winding_normal_and_miss() {
    let tri = Shape::Triangle {
        vertices: [p(0.0, 0.0, 0.0), p(2.0, 0.0, 0.0), p(0.0, 2.0, 0.0)],
    };
    let w = world(vec![object(tri)]);
    let h = first_hit(&w, &ray(p(0.5, 1.0, 1.0), v(0.0, 0.0, -0.5)));
    assert_hit(h, 2.0, p(0.5, 1.0, 0.0), Vector3::z(), Some((0.25, 0.5)));
    // Back side: same normal.
    let h = first_hit(&w, &ray(p(0.5, 1.0, -1.0), v(0.0, 0.0, 1.0)));
    assert_hit(h, 1.0, p(0.5, 1.0, 0.0), Vector3::z(), None);
    assert!(first_hit(&w, &ray(p(1.2, 1.2, 1.0), -Vector3::z())).is_none());
    assert!(first_hit(&w, &ray(p(-0.1, 0.5, 1.0), -Vector3::z())).is_none());
    // Reversed winding: reversed normal.
    let w = world(vec![object(Shape::Triangle {
        vertices: [p(0.0, 0.0, 0.0), p(0.0, 2.0, 0.0), p(2.0, 0.0, 0.0)],
    })]);
    let h = first_hit(&w, &ray(p(0.5, 1.0, 1.0), -Vector3::z()));
    assert_hit(h, 1.0, p(0.5, 1.0, 0.0), -Vector3::z(), None);
}

#[test]
fn box_entry_exit_face_normals_and_uv() {
    let w = world(vec![object(Shape::Box {
        min: p(-1.0, -2.0, -3.0),
        max: p(1.0, 2.0, 3.0),
    })]);
    // +x face; uv along (y, z): ((0.5 + 2)/4, (1 + 3)/6).
    let h = first_hit(&w, &ray(p(5.0, 0.5, 1.0), v(-1.0, 0.0, 0.0)));
    assert_hit(
        h,
        4.0,
        p(1.0, 0.5, 1.0),
        Vector3::x(),
        Some((0.625, 4.0 / 6.0)),
    );
    // −y face from below; uv along (z, x).
    let h = first_hit(&w, &ray(p(0.5, -6.0, 0.0), v(0.0, 2.0, 0.0)));
    assert_hit(h, 2.0, p(0.5, -2.0, 0.0), -Vector3::y(), Some((0.5, 0.75)));
    // From inside: the exit face, outward.
    let h = first_hit(&w, &ray(Point3::origin(), v(0.0, 0.0, 1.0)));
    assert_hit(h, 3.0, p(0.0, 0.0, 3.0), Vector3::z(), None);
    // Axis-parallel rays outside a slab miss; a diagonal miss.
    assert!(first_hit(&w, &ray(p(5.0, 2.5, 0.0), v(-1.0, 0.0, 0.0))).is_none());
    assert!(first_hit(&w, &ray(p(5.0, 0.0, 0.0), v(-1.0, 1.0, 0.0))).is_none());
    // Corners given the other way round are sorted.
    let w = world(vec![object(Shape::Box {
        min: p(1.0, 2.0, 3.0),
        max: p(-1.0, -2.0, -3.0),
    })]);
    assert!(first_hit(&w, &ray(p(5.0, 0.5, 1.0), v(-1.0, 0.0, 0.0))).is_some());
}

#[test]
fn disk_and_ring_polar_uv_and_misses() {
    let w = world(vec![object(Shape::Disk {
        center: p(1.0, 1.0, 1.0),
        normal: v(0.0, 0.0, 2.0),
        radius: 2.0,
    })]);
    let h = first_hit(&w, &ray(p(2.0, 1.0, 5.0), -Vector3::z()));
    let h = assert_hit(h, 4.0, p(2.0, 1.0, 1.0), Vector3::z(), None);
    assert!(close(h.uv.1, 0.5, 1e-12) && (0.0..=1.0).contains(&h.uv.0));
    // A quarter turn further around the centre: u moves by ¼ (mod 1).
    let h2 = first_hit(&w, &ray(p(1.0, 2.0, 5.0), -Vector3::z())).unwrap();
    let du = (h2.uv.0 - h.uv.0).rem_euclid(1.0);
    assert!(
        close(du, 0.25, 1e-12) || close(du, 0.75, 1e-12),
        "du = {du}"
    );
    assert!(first_hit(&w, &ray(p(3.01, 1.0, 5.0), -Vector3::z())).is_none());

    let w = world(vec![object(Shape::Ring {
        center: Point3::origin(),
        normal: Vector3::y(),
        inner: 1.0,
        outer: 2.0,
    })]);
    let h = first_hit(&w, &ray(p(0.0, 3.0, 1.5), -Vector3::y()));
    let h = assert_hit(h, 3.0, p(0.0, 0.0, 1.5), Vector3::y(), None);
    assert!(close(h.uv.1, 0.5, 1e-12));
    assert!(first_hit(&w, &ray(p(0.0, 3.0, 0.5), -Vector3::y())).is_none());
    assert!(first_hit(&w, &ray(p(0.0, 3.0, 2.5), -Vector3::y())).is_none());
}

#[test]
fn rectangle_is_a_parallelogram_with_uv_from_the_dual_basis() {
    let w = world(vec![object(Shape::Rectangle {
        corner: p(0.0, 0.0, 0.0),
        edge1: v(2.0, 0.0, 0.0),
        edge2: v(1.0, 1.0, 0.0),
    })]);
    // corner + 0.25·e1 + 0.5·e2 = (1, 0.5, 0).
    let h = first_hit(&w, &ray(p(1.0, 0.5, 3.0), -Vector3::z()));
    assert_hit(h, 3.0, p(1.0, 0.5, 0.0), Vector3::z(), Some((0.25, 0.5)));
    // (0.05, 0.5, 0) = −0.2·e1 + 0.5·e2... outside; (2.9, 0.95, 0) inside.
    assert!(first_hit(&w, &ray(p(0.05, 0.5, 3.0), -Vector3::z())).is_none());
    let h = first_hit(&w, &ray(p(2.9, 0.95, 3.0), -Vector3::z())).unwrap();
    assert!(close(h.uv.0, 0.975, 1e-12) && close(h.uv.1, 0.95, 1e-12));
}

#[test]
fn mesh_cube_matches_the_box() {
    let mesh = world(vec![object(Shape::Mesh(cube_mesh()))]);
    let boxed = world(vec![object(Shape::Box {
        min: p(0.0, 0.0, 0.0),
        max: p(1.0, 1.0, 1.0),
    })]);
    // Each face from outside: outward normal from the winding.
    for axis in 0..3 {
        for side in [0.0, 1.0] {
            let mut o = p(0.4, 0.3, 0.6);
            o[axis] = if side > 0.5 { 3.0 } else { -2.0 };
            let mut d = Vector3::zeros();
            d[axis] = if side > 0.5 { -1.0 } else { 1.0 };
            let h = first_hit(&mesh, &ray(o, d)).expect("face hit");
            assert!(close(h.t, 2.0, 1e-12));
            assert_vec(&h.normal, &-d, 1e-12);
            assert!((0.0..=1.0).contains(&h.uv.0) && (0.0..=1.0).contains(&h.uv.1));
        }
    }
    // Random rays: same t and normal as the box (edges aside).
    let mut rng = Rng(7);
    let mut hits = 0;
    for _ in 0..3000 {
        let o = rng.point(-3.0, 4.0);
        let r = ray(o, rng.point(-0.2, 1.2) - o);
        let (a, b) = (first_hit(&mesh, &r), first_hit(&boxed, &r));
        match (a, b) {
            (Some(a), Some(b)) => {
                hits += 1;
                assert!(close(a.t, b.t, 1e-9), "{} vs {}", a.t, b.t);
                assert_vec(&a.normal, &b.normal, 1e-9);
            }
            (None, None) => {}
            (a, b) => {
                // Only a graze of an edge may differ.
                let t = a.or(b).unwrap().t;
                let q = r.at(t);
                let edge = (0..3)
                    .filter(|&i| close(q[i], 0.0, 1e-9) || close(q[i], 1.0, 1e-9))
                    .count();
                assert!(edge >= 2, "mesh {a:?} box {b:?}");
            }
        }
    }
    assert!(hits > 2000, "too few hits to mean anything: {hits}");
}

#[test]
fn bad_mesh_indices_and_zero_area_triangles_are_skipped() {
    let mesh = Arc::new(TriangleMesh {
        vertices: vec![
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(2.0, 0.0, 0.0),
        ],
        triangles: vec![[0, 1, 9], [0, 1, 3], [0, 1, 2]],
    });
    let w = world(vec![object(Shape::Mesh(mesh))]);
    let h = first_hit(&w, &ray(p(0.25, 0.25, 1.0), -Vector3::z()));
    assert_hit(h, 1.0, p(0.25, 0.25, 0.0), Vector3::z(), Some((0.25, 0.25)));
    // Only collinear / out-of-range triangles: nothing at all.
    let mesh = Arc::new(TriangleMesh {
        vertices: vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(2.0, 0.0, 0.0)],
        triangles: vec![[0, 1, 2], [0, 1, 7]],
    });
    let w = world(vec![object(Shape::Mesh(mesh))]);
    assert!(w.bounded.is_empty() && w.unbounded.is_empty());
}

#[test]
fn degenerate_input_never_hits_and_never_panics() {
    let singular = Matrix4::new_nonuniform_scaling(&v(1.0, 0.0, 1.0));
    let w = world(vec![
        object(Shape::Sphere {
            center: Point3::origin(),
            radius: 0.0,
        }),
        object(Shape::Sphere {
            center: Point3::origin(),
            radius: f64::NAN,
        }),
        object(Shape::Triangle {
            vertices: [p(0.0, 0.0, 0.0), p(1.0, 1.0, 1.0), p(2.0, 2.0, 2.0)],
        }),
        object(Shape::Plane {
            normal: Vector3::zeros(),
            offset: 1.0,
        }),
        object(Shape::Disk {
            center: Point3::origin(),
            normal: Vector3::z(),
            radius: 0.0,
        }),
        object(Shape::Rectangle {
            corner: Point3::origin(),
            edge1: Vector3::x(),
            edge2: Vector3::x() * 2.0,
        }),
        object(Shape::Tube(Arc::new(Tube {
            points: vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0)],
            radius: 0.0,
        }))),
        placed(
            Shape::Sphere {
                center: Point3::origin(),
                radius: 1.0,
            },
            singular,
        ),
    ]);
    assert!(w.bounded.is_empty() && w.unbounded.is_empty());
    let mut rng = Rng(3);
    for _ in 0..100 {
        let r = ray(rng.point(-2.0, 2.0), rng.vec(-1.0, 1.0));
        assert!(first_hit(&w, &r).is_none());
    }
    // Garbage rays on a real scene: no panic, no NaN hit.
    let w = world(vec![
        object(Shape::Sphere {
            center: Point3::origin(),
            radius: 1.0,
        }),
        object(Shape::Mesh(cube_mesh())),
    ]);
    let mut s = IntersectStats::default();
    for d in [Vector3::zeros(), v(f64::NAN, 0.0, 1.0), v(0.0, 0.0, -1.0)] {
        let r = ray(p(0.0, 0.0, 5.0), d);
        if let Some(h) = w.intersect(&r, 0.0, f64::INFINITY, &mut s) {
            assert!(h.t.is_finite() && h.normal.iter().all(|c| c.is_finite()));
        }
        let _ = w.occluded(&r, 0.0, f64::INFINITY, &mut s);
    }
}

// ---------------------------------------------------------------- tubes

#[test]
fn tube_body_caps_and_no_joints_inside() {
    let tube = |points: Vec<Point3<f64>>| {
        world(vec![object(Shape::Tube(Arc::new(Tube {
            points,
            radius: 0.5,
        })))])
    };
    let w = tube(vec![p(0.0, 0.0, 0.0), p(2.0, 0.0, 0.0)]);
    // Side: t = 5 − 0.5, normal +y, u = ½ along the segment.
    let h = first_hit(&w, &ray(p(1.0, 5.0, 0.0), -Vector3::y()));
    let h = assert_hit(h, 4.5, p(1.0, 0.5, 0.0), Vector3::y(), None);
    assert!(close(h.uv.0, 0.5, 1e-12));
    // Round cap.
    let h = first_hit(&w, &ray(p(-5.0, 0.0, 0.0), Vector3::x()));
    let h = assert_hit(h, 4.5, p(-0.5, 0.0, 0.0), -Vector3::x(), None);
    assert!(close(h.uv.0, 0.0, 1e-12));
    // Oblique onto the cap sphere: |(−5 + t, 0.3, 0)| = 0.5 → t = 5 − 0.4.
    let h = first_hit(&w, &ray(p(-5.0, 0.3, 0.0), Vector3::x()));
    assert_hit(h, 4.6, p(-0.4, 0.3, 0.0), v(-0.8, 0.6, 0.0), None);
    assert!(first_hit(&w, &ray(p(1.0, 5.0, 0.51), -Vector3::y())).is_none());

    // A straight chain, ray inside along it: one exit at the far cap, no
    // joint surfaces at x = 1.5 or 2.5.
    let w = tube(vec![
        p(0.0, 0.0, 0.0),
        p(1.0, 0.0, 0.0),
        p(2.0, 0.0, 0.0),
        p(3.0, 0.0, 0.0),
    ]);
    let h = first_hit(&w, &ray(p(0.5, 0.0, 0.0), Vector3::x()));
    let h = assert_hit(h, 3.0, p(3.5, 0.0, 0.0), Vector3::x(), None);
    assert!(close(h.uv.0, 1.0, 1e-12));
    // Side hit on the middle segment: u = (1 + ½)/3.
    let h = first_hit(&w, &ray(p(1.5, 0.0, 4.0), -Vector3::z()));
    let h = assert_hit(h, 3.5, p(1.5, 0.0, 0.5), Vector3::z(), None);
    assert!(close(h.uv.0, 0.5, 1e-12));
}

#[test]
fn long_tube_bvh_matches_brute_force() {
    // A helix of 400 points.
    let points: Vec<Point3<f64>> = (0..400)
        .map(|i| {
            let s = i as f64 * 0.05;
            p(s.cos() * 2.0, s * 0.1, s.sin() * 2.0)
        })
        .collect();
    let tube = Tube {
        points: points.clone(),
        radius: 0.07,
    };
    let w = world(vec![object(Shape::Tube(Arc::new(tube)))]);
    let mut rng = Rng(11);
    let mut hits = 0;
    for _ in 0..2000 {
        let o = rng.point(-4.0, 4.0);
        let target = rng.point(-2.5, 2.5) + v(0.0, 1.0, 0.0);
        let r = ray(o, target - o);
        // From inside the tube the chain rightly skips joints a lone
        // capsule reports: compare only from outside.
        let inside = points.windows(2).any(|pair| {
            let (a, ab) = (pair[0], pair[1] - pair[0]);
            let s = ((o - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
            (o - (a + ab * s)).norm() <= 0.07
        });
        if inside {
            continue;
        }
        // Brute force: every segment's capsule, each as its own world.
        let mut best = f64::INFINITY;
        for pair in points.windows(2) {
            let single = Tube {
                points: pair.to_vec(),
                radius: 0.07,
            };
            let prim = super::tube::TubeShape::new(&single).unwrap();
            if let Some(h) = prim.intersect(&r, 0.0, best) {
                best = h.t;
            }
        }
        let got = first_hit(&w, &r).map_or(f64::INFINITY, |h| h.t);
        if best.is_finite() {
            hits += 1;
        }
        assert!(
            got == best || close(got, best, 1e-9 * best.abs().max(1.0)),
            "{got} vs {best}"
        );
    }
    assert!(hits > 100, "too few hits: {hits}");
}

// ---------------------------------------------------------------- transforms

#[test]
fn translated_and_scaled_sphere_by_hand() {
    // Unit sphere scaled (2, 1, 1) and moved by (1, 0, 0): x ∈ [−1, 3].
    let m = trs(v(1.0, 0.0, 0.0), 0.0, v(2.0, 1.0, 1.0));
    let w = world(vec![placed(
        Shape::Sphere {
            center: Point3::origin(),
            radius: 1.0,
        },
        m,
    )]);
    let h = first_hit(&w, &ray(p(10.0, 0.0, 0.0), v(-2.0, 0.0, 0.0)));
    assert_hit(h, 3.5, p(3.0, 0.0, 0.0), Vector3::x(), None);
    let h = first_hit(&w, &ray(p(1.0, 0.0, 10.0), -Vector3::z()));
    assert_hit(h, 9.0, p(1.0, 0.0, 1.0), Vector3::z(), None);
    // At x = 1 + 2cos 60°, z = sin 60° the ellipse normal is ∝ (cos 60°/2, 0, sin 60°).
    let (c, s) = (0.5, 0.75f64.sqrt());
    let h = first_hit(&w, &ray(p(2.0, 0.0, 10.0), -Vector3::z())).unwrap();
    assert!(close(h.t, 10.0 - s, 1e-12));
    assert_vec(&h.normal, &v(c / 2.0, 0.0, s).normalize(), 1e-12);
    assert!(first_hit(&w, &ray(p(3.01, 0.0, 10.0), -Vector3::z())).is_none());
}

#[test]
fn rotated_scaled_ellipsoid_normal_is_the_gradient() {
    // M = T·R_y(35°)·S(2, 1, 0.5); the ellipsoid is |L⁻¹(p − c)| = 1 and its
    // outward normal ∝ L⁻ᵀL⁻¹(p − c).
    let c = v(1.0, 2.0, 3.0);
    let m = trs(c, 35f64.to_radians(), v(2.0, 1.0, 0.5));
    let l: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
    let li = l.try_inverse().unwrap();
    let w = world(vec![placed(
        Shape::Sphere {
            center: Point3::origin(),
            radius: 1.0,
        },
        m,
    )]);
    let mut rng = Rng(5);
    let mut hits = 0;
    for _ in 0..500 {
        let o = Point3::from(c + rng.vec(-6.0, 6.0));
        let d = (Point3::from(c + rng.vec(-1.5, 1.5)) - o) * rng.range(0.2, 3.0);
        // Reference: |A + t·B|² = 1 with A = L⁻¹(o − c), B = L⁻¹d.
        let (a, b) = (li * (o.coords - c), li * d);
        let (qa, qb, qc) = (b.dot(&b), 2.0 * a.dot(&b), a.dot(&a) - 1.0);
        let disc = qb * qb - 4.0 * qa * qc;
        let want = (disc >= 0.0).then(|| (-qb - disc.sqrt()) / (2.0 * qa));
        let got = first_hit(&w, &ray(o, d));
        match (got, want.filter(|&t| t > 0.0)) {
            (Some(h), Some(t)) => {
                hits += 1;
                assert!(close(h.t, t, 1e-9), "{} vs {t}", h.t);
                assert_vec(&h.point.coords, &(o + d * t).coords, 1e-9);
                let grad = li.transpose() * (li * (h.point.coords - c));
                assert_vec(&h.normal, &grad.normalize(), 1e-9);
            }
            (None, None) => {}
            (g, t) => panic!("got {g:?}, want {t:?}"),
        }
    }
    assert!(hits > 100, "too few hits: {hits}");
}

#[test]
fn rotated_box_and_rectangle_by_hand() {
    // Box [−1, 1]×[−2, 2]×[−3, 3] turned 90° about y (local x → world −z,
    // local z → world x), moved by (10, 0, 0): world x ∈ [7, 13].
    let m = trs(v(10.0, 0.0, 0.0), FRAC_PI_2, Vector3::repeat(1.0));
    let w = world(vec![placed(
        Shape::Box {
            min: p(-1.0, -2.0, -3.0),
            max: p(1.0, 2.0, 3.0),
        },
        m,
    )]);
    let h = first_hit(&w, &ray(p(0.0, 0.0, 0.0), Vector3::x()));
    assert_hit(h, 7.0, p(7.0, 0.0, 0.0), -Vector3::x(), None);
    let h = first_hit(&w, &ray(p(10.0, 0.0, 5.0), -Vector3::z()));
    assert_hit(h, 4.0, p(10.0, 0.0, 1.0), Vector3::z(), None);

    // A unit square in z = 0 scaled by (3, 1, 1): its normal stays +z; a
    // shear keeps the normal perpendicular to the mapped edges.
    let mut shear = Matrix4::identity();
    shear[(0, 1)] = 2.0; // x += 2y
    let w = world(vec![placed(
        Shape::Rectangle {
            corner: Point3::origin(),
            edge1: Vector3::x(),
            edge2: Vector3::y(),
        },
        shear * Matrix4::new_nonuniform_scaling(&v(3.0, 1.0, 1.0)),
    )]);
    // Local (0.5, 0.5) → world (1.5 + 1, 0.5).
    let h = first_hit(&w, &ray(p(2.5, 0.5, 2.0), -Vector3::z()));
    assert_hit(h, 2.0, p(2.5, 0.5, 0.0), Vector3::z(), Some((0.5, 0.5)));
    // A tilted rectangle (shear in z): normal ⊥ mapped edges.
    let mut tilt = Matrix4::identity();
    tilt[(2, 0)] = 1.0; // z += x
    let w = world(vec![placed(
        Shape::Rectangle {
            corner: Point3::origin(),
            edge1: Vector3::x(),
            edge2: Vector3::y(),
        },
        tilt,
    )]);
    let h = first_hit(&w, &ray(p(0.5, 0.5, 5.0), -Vector3::z())).unwrap();
    assert!(close(h.t, 4.5, 1e-12));
    assert_vec(&h.normal, &v(-1.0, 0.0, 1.0).normalize(), 1e-12);
}

#[test]
fn reflecting_transform_keeps_outward_normals() {
    // Mirror x: the sphere's normal must still point out.
    let w = world(vec![placed(
        Shape::Sphere {
            center: p(1.0, 0.0, 0.0),
            radius: 1.0,
        },
        Matrix4::new_nonuniform_scaling(&v(-1.0, 1.0, 1.0)),
    )]);
    let h = first_hit(&w, &ray(p(-5.0, 0.0, 0.0), Vector3::x()));
    assert_hit(h, 3.0, p(-2.0, 0.0, 0.0), -Vector3::x(), None);
}

// ---------------------------------------------------------------- revolution

/// Open cylinder x = 1 (or −1), y ∈ [0, 2], given either way, as a degree-1
/// B-spline or Bézier: the closed-form hit and an outward normal.
#[test]
fn revolution_cylinder_hits_and_outward_normals_either_direction() {
    let profiles: Vec<Shape> = vec![
        bspline_body(&[(1.0, 0.0), (1.0, 2.0)], 1),
        bspline_body(&[(1.0, 2.0), (1.0, 0.0)], 1),
        bspline_body(&[(-1.0, 0.0), (-1.0, 2.0)], 1),
        bspline_body(&[(-1.0, 2.0), (-1.0, 1.0), (-1.0, 0.0)], 1),
        bezier_body(&[(1.0, 0.0), (1.0, 2.0)]),
        bezier_body(&[(1.0, 2.0), (1.0, 0.0)]),
    ];
    let mut flips = [false; 2];
    for (k, shape) in profiles.into_iter().enumerate() {
        if let Shape::Revolution(body) = &shape {
            let prim = super::revolution::RevolutionShape::new(body.clone()).unwrap();
            flips[usize::from(prim.flipped())] = true;
        }
        let w = world(vec![object(shape)]);
        let mut s = IntersectStats::default();
        // From outside at height 0.5: t = 4, normal +x.
        let r = ray(p(5.0, 0.5, 0.0), -Vector3::x());
        let h = w.intersect(&r, 0.0, f64::INFINITY, &mut s);
        let h = assert_hit(h, 4.0, p(1.0, 0.5, 0.0), Vector3::x(), None);
        // u: a quarter of the way up (or down) the profile.
        assert!(
            close(h.uv.0, 0.25, 1e-9) || close(h.uv.0, 0.75, 1e-9),
            "profile {k}: uv {:?}",
            h.uv
        );
        // An oblique ray: |(o + t·d)_xz| = 1 by the quadratic.
        let (o, d) = (p(3.0, 0.2, 0.5), v(-1.0, 0.3, -0.2));
        let (a, b, c) = (
            d.x * d.x + d.z * d.z,
            2.0 * (o.x * d.x + o.z * d.z),
            o.x * o.x + o.z * o.z - 1.0,
        );
        let t = (-b - (b * b - 4.0 * a * c).sqrt()) / (2.0 * a);
        let q = o + d * t;
        let h = w.intersect(&ray(o, d), 0.0, f64::INFINITY, &mut s);
        assert_hit(h, t, q, v(q.x, 0.0, q.z), None);
        // From the axis (inside the open tube): the wall, normal outward,
        // i.e. along the ray.
        let h = w.intersect(&ray(p(0.0, 1.0, 0.0), Vector3::z()), 0.0, 9.0, &mut s);
        assert_hit(h, 1.0, p(0.0, 1.0, 1.0), Vector3::z(), None);
        // Above the cylinder: miss.
        assert!(
            w.intersect(&ray(p(5.0, 2.5, 0.0), -Vector3::x()), 0.0, 9.0, &mut s)
                .is_none()
        );
        assert!(s.revolution_calls >= 3, "profile {k}");
    }
    // revolve's orientation differs between the directions: both cases ran.
    assert!(flips[0] && flips[1]);
}

#[test]
fn closed_revolution_body_caps_point_out() {
    // A capped cylinder: (0,0) → (1,0) → (1,2) → (0,2), and reversed.
    for pts in [
        vec![(0.0, 0.0), (1.0, 0.0), (1.0, 2.0), (0.0, 2.0)],
        vec![(0.0, 2.0), (1.0, 2.0), (1.0, 0.0), (0.0, 0.0)],
    ] {
        let w = world(vec![object(bspline_body(&pts, 1))]);
        let h = first_hit(&w, &ray(p(0.3, 5.0, 0.2), -Vector3::y()));
        assert_hit(h, 3.0, p(0.3, 2.0, 0.2), Vector3::y(), None);
        let h = first_hit(&w, &ray(p(0.3, -5.0, 0.2), Vector3::y()));
        assert_hit(h, 5.0, p(0.3, 0.0, 0.2), -Vector3::y(), None);
        let h = first_hit(&w, &ray(p(0.0, 1.0, -4.0), Vector3::z()));
        assert_hit(h, 3.0, p(0.0, 1.0, -1.0), -Vector3::z(), None);
    }
    // A flat disk profile (widest point on a horizontal rim, no area): the
    // normal faces up (+axis) for both directions.
    let a = world(vec![object(bspline_body(&[(0.0, 0.0), (1.0, 0.0)], 1))]);
    let b = world(vec![object(bspline_body(&[(1.0, 0.0), (0.0, 0.0)], 1))]);
    let r = ray(p(0.2, 3.0, 0.1), -Vector3::y());
    let (ha, hb) = (first_hit(&a, &r).unwrap(), first_hit(&b, &r).unwrap());
    assert!(close(ha.t, 3.0, 1e-9));
    assert_vec(&ha.normal, &Vector3::y(), 1e-9);
    assert_vec(&hb.normal, &Vector3::y(), 1e-9);
}

#[test]
fn transformed_cubic_revolution_matches_the_untransformed_one() {
    // The format's example vase profile (cubic uniform B-spline, x < 0).
    let pts: Vec<Point2<f64>> = [(-1.0, 0.0), (-1.0, 1.0), (-2.0, 2.0), (-1.0, 3.0)]
        .iter()
        .map(|&(x, y)| Point2::new(x, y))
        .collect();
    let body = Arc::new(RevolutionBody::BSpline(Revolution::new(
        BSpline::uniform(3, pts).unwrap(),
    )));
    let m = trs(v(1.0, -2.0, 0.5), 0.7, v(1.5, 0.8, 1.5));
    let local = world(vec![object(Shape::Revolution(body.clone()))]);
    let moved = world(vec![placed(Shape::Revolution(body), m)]);
    let frame = super::transform::Frame::new(&m).unwrap();
    let mut rng = Rng(13);
    let mut hits = 0;
    let mut stats = IntersectStats::default();
    for _ in 0..300 {
        let o = rng.point(-5.0, 5.0);
        let d = frame.point(&(rng.point(-1.5, 1.5) + v(0.0, 1.5, 0.0))) - o;
        let local_ray = frame.ray_to_local(&ray(o, d));
        let want = local.intersect(&local_ray, 0.0, f64::INFINITY, &mut stats);
        let got = moved.intersect(&ray(o, d), 0.0, f64::INFINITY, &mut stats);
        match (got, want) {
            (Some(g), Some(w)) => {
                hits += 1;
                assert!(close(g.t, w.t, 1e-9 * w.t.max(1.0)));
                assert_vec(&g.point.coords, &frame.point(&w.point).coords, 1e-8);
                let n = frame.normal(&w.normal).normalize();
                assert_vec(&g.normal, &n, 1e-9);
                assert_eq!(g.uv, w.uv);
                // The bulge is outside: the normal points away from the axis
                // there (local frame).
                let lp = w.point;
                if lp.y > 1.4 && lp.y < 1.6 && (lp.x * lp.x + lp.z * lp.z).sqrt() > 1.2 {
                    assert!(w.normal.x * lp.x + w.normal.z * lp.z > 0.0);
                }
            }
            (None, None) => {}
            (g, w) => panic!("moved {g:?} vs local {w:?}"),
        }
    }
    assert!(hits > 50, "too few hits: {hits}");
    assert!(stats.revolution_calls >= 2 * hits as u64 && stats.revolution_nanos > 0);
}

// ---------------------------------------------------------------- BVH

/// A random scene of spheres and triangles, some transformed.
fn random_scene(rng: &mut Rng, n: usize) -> Vec<Object> {
    (0..n)
        .map(|i| {
            let shape = if i % 2 == 0 {
                Shape::Sphere {
                    center: rng.point(-10.0, 10.0),
                    radius: rng.range(0.05, 1.0),
                }
            } else {
                let a = rng.point(-10.0, 10.0);
                Shape::Triangle {
                    vertices: [a, a + rng.vec(-1.5, 1.5), a + rng.vec(-1.5, 1.5)],
                }
            };
            if i % 5 == 0 {
                let m = trs(rng.vec(-1.0, 1.0), rng.range(0.0, PI), rng.vec(0.5, 2.0));
                placed(shape, m)
            } else {
                object(shape)
            }
        })
        .collect()
}

#[test]
fn bvh_nearest_hit_equals_brute_force() {
    let mut rng = Rng(42);
    let mut objects = random_scene(&mut rng, 400);
    objects.push(object(Shape::Plane {
        normal: Vector3::y(),
        offset: -11.0,
    }));
    let w = world(objects);
    assert_eq!(w.bounded.len(), 400);
    assert_eq!(w.unbounded.len(), 1);
    assert!(w.bvh.depth() <= MAX_DEPTH && w.bvh.node_count() >= 2 * 400 - 1);
    let mut stats = IntersectStats::default();
    let mut hits = 0;
    for _ in 0..3000 {
        let o = rng.point(-14.0, 14.0);
        let d = rng.vec(-1.0, 1.0);
        let r = ray(o, d);
        let t_min = if rng.next() < 0.3 {
            rng.range(0.0, 5.0)
        } else {
            0.0
        };
        let t_max = if rng.next() < 0.3 {
            rng.range(5.0, 20.0)
        } else {
            f64::INFINITY
        };
        let mut best: Option<(f64, usize)> = None;
        for pl in w.bounded.iter().chain(&w.unbounded) {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some(h) = pl.intersect(&r, t_min, limit, &mut stats) {
                best = Some((h.t, pl.object));
            }
        }
        let got = w.intersect(&r, t_min, t_max, &mut stats);
        assert_eq!(got.map(|h| (h.t, h.object)), best);
        assert_eq!(w.occluded(&r, t_min, t_max, &mut stats), best.is_some());
        hits += usize::from(best.is_some());
    }
    assert!(hits > 500, "too few hits: {hits}");
}

#[test]
fn bvh_handles_coincident_and_flat_items() {
    // 50 identical spheres (no plane separates them) and axis-aligned
    // triangles (flat boxes) hit by rays lying in their planes' normals.
    let mut objects: Vec<Object> = (0..50)
        .map(|_| {
            object(Shape::Sphere {
                center: p(0.0, 0.0, 0.0),
                radius: 1.0,
            })
        })
        .collect();
    for i in 0..50 {
        let z = i as f64;
        objects.push(object(Shape::Triangle {
            vertices: [p(5.0, 0.0, z), p(6.0, 0.0, z), p(5.0, 1.0, z)],
        }));
    }
    let w = world(objects);
    assert!(w.bvh.depth() <= MAX_DEPTH);
    let h = first_hit(&w, &ray(p(0.0, 0.0, 5.0), -Vector3::z())).unwrap();
    assert!(close(h.t, 4.0, 1e-12) && h.object < 50);
    // Straight down z through the stack of triangles: the first is at z = 49.
    let h = first_hit(&w, &ray(p(5.25, 0.25, 100.0), -Vector3::z())).unwrap();
    assert!(close(h.t, 51.0, 1e-12) && h.object == 99);
    // Travelling in the plane y = 0 of the triangles' edges (direction
    // component 0): the edge at y = 0 is included.
    let h = first_hit(&w, &ray(p(5.5, 0.0, 100.0), -Vector3::z())).unwrap();
    assert!(close(h.t, 51.0, 1e-12));
}

#[test]
fn instanced_mesh_is_prepared_once_and_placed_twice() {
    let mesh = cube_mesh();
    let w = world(vec![
        object(Shape::Mesh(mesh.clone())),
        placed(
            Shape::Mesh(mesh),
            Matrix4::new_translation(&v(5.0, 0.0, 0.0)),
        ),
    ]);
    let arcs: Vec<_> = w
        .bounded
        .iter()
        .map(|pl| match &pl.prim {
            Prim::Mesh(m) => Arc::as_ptr(m),
            _ => panic!("not a mesh"),
        })
        .collect();
    assert_eq!(arcs.len(), 2);
    assert_eq!(arcs[0], arcs[1]);
    let h = first_hit(&w, &ray(p(10.0, 0.5, 0.5), -Vector3::x())).unwrap();
    assert!(close(h.t, 4.0, 1e-12) && h.object == 1);
    assert_vec(&h.normal, &Vector3::x(), 1e-12);
}

// ---------------------------------------------------------------- emitters

/// Mean of an `n`×`n` stratified grid of samples; checks every normal is
/// unit and `normal_ok`, and that each point satisfies `on_surface`.
fn sample_mean(
    e: &Emitter,
    n: usize,
    on_surface: impl Fn(&Point3<f64>) -> bool,
    normal_ok: impl Fn(&Point3<f64>, &Vector3<f64>) -> bool,
) -> Point3<f64> {
    let mut sum = Vector3::zeros();
    for i in 0..n {
        for j in 0..n {
            let (a, b) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let (q, nrm) = e.sample(a, b);
            assert!(on_surface(&q), "{q:?} off the surface");
            assert!(close(nrm.norm(), 1.0, 1e-12));
            assert!(normal_ok(&q, &nrm), "normal {nrm:?} at {q:?}");
            sum += q.coords;
        }
    }
    Point3::from(sum / (n * n) as f64)
}

/// Grid size for the emitter means.
const N: usize = 256;

fn emissive(shape: Shape, transform: Option<Matrix4<f64>>) -> Object {
    Object {
        shape,
        material: 1,
        transform,
    }
}

#[test]
fn rectangle_and_box_emitters_exact_area_centroid_mean() {
    let m = trs(v(1.0, 2.0, 3.0), 0.4, v(2.0, 1.0, 3.0));
    let f = super::transform::Frame::new(&m).unwrap();
    let w = world(vec![
        object(Shape::Sphere {
            center: Point3::origin(),
            radius: 1.0,
        }),
        emissive(
            Shape::Rectangle {
                corner: p(0.0, 0.0, 0.0),
                edge1: v(1.0, 0.0, 0.0),
                edge2: v(0.0, 0.0, 2.0),
            },
            Some(m),
        ),
        emissive(
            Shape::Box {
                min: p(-1.0, -1.0, -1.0),
                max: p(1.0, 2.0, 1.0),
            },
            Some(m),
        ),
    ]);
    let e = w.emitters();
    assert_eq!(e.len(), 2);
    assert_eq!((e[0].object, e[1].object), (1, 2));
    // Rectangle: the y-rotation keeps areas; scale x by 2, z by 3: 1·2·6 = 12.
    assert!(close(e[0].area(), 12.0, 1e-12));
    let centroid = f.point(&p(0.5, 0.0, 1.0));
    let up = f.normal(&v(0.0, -2.0, 0.0)).normalize(); // e1 × e2 = (0, −2, 0)
    let mean = sample_mean(
        &e[0],
        N,
        |q| close((q - f.point(&Point3::origin())).dot(&up), 0.0, 1e-9),
        |_, n| (n - up).norm() < 1e-12,
    );
    assert_vec(&mean.coords, &centroid.coords, 1e-9);
    // Box 2×3×2 scaled to 4×3×6: 2(12 + 18 + 24) = 108.
    assert!(close(e[1].area(), 108.0, 1e-9));
    let center = f.point(&p(0.0, 0.5, 0.0));
    let inv = m.try_inverse().unwrap();
    let local = |q: &Point3<f64>| inv.transform_point(q);
    let mean = sample_mean(
        &e[1],
        1024,
        |q| {
            let l = local(q);
            let inside = (l.x.abs() <= 1.0 + 1e-9)
                && (-1.0 - 1e-9..=2.0 + 1e-9).contains(&l.y)
                && (l.z.abs() <= 1.0 + 1e-9);
            let on_face = close(l.x.abs(), 1.0, 1e-9)
                || close(l.y, -1.0, 1e-9)
                || close(l.y, 2.0, 1e-9)
                || close(l.z.abs(), 1.0, 1e-9);
            inside && on_face
        },
        |q, n| (q - center).dot(n) > 0.0,
    );
    // By symmetry of each opposite face pair the mean is the centre (to the
    // grid's resolution in choosing faces).
    assert_vec(&mean.coords, &center.coords, 1e-2);
    // Faces are chosen by area: the two 4×6 faces (y = const) get 48/108.
    let mut count = 0;
    for i in 0..1000 {
        let (q, _) = e[1].sample((i as f64 + 0.5) / 1000.0, 0.5);
        let l = local(&q);
        if close(l.y, -1.0, 1e-9) || close(l.y, 2.0, 1e-9) {
            count += 1;
        }
    }
    assert!((440..=450).contains(&count), "{count}");
}

#[test]
fn sphere_disk_triangle_mesh_emitters() {
    let sim = trs(v(0.0, 1.0, 0.0), 1.0, Vector3::repeat(2.0));
    let squash = trs(v(0.0, 1.0, 0.0), 0.0, v(2.0, 1.0, 1.0));
    let sphere = Shape::Sphere {
        center: p(1.0, 0.0, 0.0),
        radius: 0.5,
    };
    let w = world(vec![
        emissive(sphere.clone(), Some(sim)),
        emissive(sphere, Some(squash)), // not a similarity: skipped
        emissive(
            Shape::Disk {
                center: p(0.0, 0.0, 0.0),
                normal: Vector3::z(),
                radius: 1.0,
            },
            Some(squash),
        ),
        emissive(
            Shape::Triangle {
                vertices: [p(0.0, 0.0, 0.0), p(3.0, 0.0, 0.0), p(0.0, 3.0, 0.0)],
            },
            None,
        ),
        emissive(Shape::Mesh(cube_mesh()), None),
        emissive(
            Shape::Ring {
                center: p(0.0, 0.0, 0.0),
                normal: Vector3::y(),
                inner: 1.0,
                outer: 2.0,
            },
            None,
        ),
        emissive(
            Shape::Plane {
                normal: Vector3::y(),
                offset: 0.0,
            },
            None,
        ),
    ]);
    let e = w.emitters();
    let objects: Vec<usize> = e.iter().map(|e| e.object).collect();
    assert_eq!(objects, vec![0, 2, 3, 4, 5]);

    // Sphere: centre (0, 1, 0) + 2·R(1, 0, 0), radius 1.
    let c = sim.transform_point(&p(1.0, 0.0, 0.0));
    assert!(close(e[0].area(), 4.0 * PI, 1e-12));
    let mean = sample_mean(
        &e[0],
        N,
        |q| close((q - c).norm(), 1.0, 1e-12),
        |q, n| (q - c - n).norm() < 1e-12,
    );
    assert_vec(&mean.coords, &c.coords, 1e-3);

    // Disk r = 1 stretched ×2 along x: ellipse of area 2π.
    assert!(close(e[1].area(), 2.0 * PI, 1e-12));
    let mean = sample_mean(
        &e[1],
        N,
        |q| close(q.z, 0.0, 1e-12) && (q.x / 2.0).powi(2) + (q.y - 1.0).powi(2) <= 1.0 + 1e-9,
        |_, n| (n - Vector3::z()).norm() < 1e-12,
    );
    assert_vec(&mean.coords, &v(0.0, 1.0, 0.0), 1e-3);

    // Triangle: area 4.5, centroid (1, 1, 0).
    assert!(close(e[2].area(), 4.5, 1e-12));
    let mean = sample_mean(
        &e[2],
        N,
        |q| q.x >= -1e-12 && q.y >= -1e-12 && q.x + q.y <= 3.0 + 1e-12 && q.z == 0.0,
        |_, n| (n - Vector3::z()).norm() < 1e-12,
    );
    assert_vec(&mean.coords, &v(1.0, 1.0, 0.0), 2e-3);

    // Cube mesh: area 6, centroid the centre, normals outward.
    assert!(close(e[3].area(), 6.0, 1e-12));
    let centre = p(0.5, 0.5, 0.5);
    let mean = sample_mean(
        &e[3],
        N,
        |q| (0..3).any(|i| close(q[i], 0.0, 1e-12) || close(q[i], 1.0, 1e-12)),
        |q, n| (q - centre).dot(n) > 0.0,
    );
    assert_vec(&mean.coords, &centre.coords, 5e-3);

    // Ring: area π(4 − 1); the mean radius is (2/3)(8 − 1)/(4 − 1) = 14/9.
    assert!(close(e[4].area(), 3.0 * PI, 1e-12));
    let n = 64;
    let mut radius = 0.0;
    for i in 0..n {
        let (q, _) = e[4].sample((i as f64 + 0.5) / n as f64, 0.3);
        radius += q.coords.norm() / n as f64;
    }
    assert!(close(radius, 14.0 / 9.0, 1e-3), "{radius}");
}

#[test]
fn emitter_estimates_the_form_factor_of_a_square() {
    // A 4×4 emissive square at height 1 over the origin, facing down: the
    // form factor to a point below its centre is
    // (4/2π)·2·(x/s)·atan(x/s), x = 2, s = √(1 + x²) (four corner
    // rectangles). Estimate ∫ cos θ cos θ′/(π r²) dA = area·E[…].
    let w = world(vec![emissive(
        Shape::Rectangle {
            corner: p(-2.0, 1.0, -2.0),
            edge1: v(4.0, 0.0, 0.0),
            edge2: v(0.0, 0.0, 4.0),
        },
        None,
    )]);
    let e = &w.emitters()[0];
    assert!(close(e.area(), 16.0, 1e-12));
    let n = 400;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let (a, b) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let (q, nq) = e.sample(a, b);
            let d = q.coords; // from the origin
            let r2 = d.norm_squared();
            let cos_here = d.y / r2.sqrt();
            let cos_there = (-d).dot(&nq) / r2.sqrt();
            assert!(cos_there > 0.0, "the light faces the floor");
            sum += cos_here * cos_there / (PI * r2);
        }
    }
    let estimate = e.area() * sum / (n * n) as f64;
    let x: f64 = 2.0;
    let s = (1.0 + x * x).sqrt();
    let want = 4.0 / (2.0 * PI) * 2.0 * (x / s) * (x / s).atan();
    assert!(close(estimate, want, 1e-4), "{estimate} vs {want}");
}

// ---------------------------------------------------------------- timing

/// Prints the cost of one `World::intersect` on a small scene, without and
/// with a revolution body (run with `--ignored --nocapture`; not a pass/fail
/// check beyond the hit count).
#[test]
#[ignore]
fn time_intersect_on_a_small_scene() {
    let mut objects = vec![
        object(Shape::Sphere {
            center: p(-1.5, 0.5, 0.0),
            radius: 1.0,
        }),
        object(Shape::Plane {
            normal: Vector3::y(),
            offset: -1.0,
        }),
        object(Shape::Mesh(cube_mesh())),
        object(Shape::Box {
            min: p(2.0, -1.0, -1.0),
            max: p(3.0, 0.0, 1.0),
        }),
        placed(
            Shape::Sphere {
                center: Point3::origin(),
                radius: 0.5,
            },
            trs(v(0.0, 2.0, -1.0), 0.3, v(1.0, 2.0, 1.0)),
        ),
    ];
    let mut rng = Rng(1);
    let eye = p(0.0, 1.0, 10.0);
    let rays: Vec<Ray> = (0..400_000)
        .map(|_| ray(eye, rng.point(-3.0, 3.0) - eye))
        .collect();
    for with_revolution in [false, true] {
        if with_revolution {
            objects.push(object(bspline_body(
                &[(-1.0, 0.0), (-1.0, 1.0), (-2.0, 2.0), (-1.0, 3.0)],
                3,
            )));
        }
        let w = world(objects.clone());
        let mut stats = IntersectStats::default();
        let start = std::time::Instant::now();
        let hits = rays
            .iter()
            .filter(|r| w.intersect(r, 1e-9, f64::INFINITY, &mut stats).is_some())
            .count();
        let ns = start.elapsed().as_nanos() as f64 / rays.len() as f64;
        let start = std::time::Instant::now();
        let blocked = rays
            .iter()
            .filter(|r| w.occluded(r, 1e-9, f64::INFINITY, &mut stats))
            .count();
        let ns_occ = start.elapsed().as_nanos() as f64 / rays.len() as f64;
        println!(
            "{} objects: {ns:.0} ns per intersect, {ns_occ:.0} ns per occluded \
             ({hits} hits; {} revolution calls, {:.0} ns each)",
            objects.len(),
            stats.revolution_calls,
            stats.revolution_nanos as f64 / stats.revolution_calls.max(1) as f64
        );
        assert_eq!(hits, blocked);
    }
}

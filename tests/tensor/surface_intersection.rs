//! Intersections of two NURBS surfaces (`NurbsSurface::intersect_surface`)
//! against closed forms: the unit sphere and planes (circles), two spheres
//! (a circle in the radical plane), a cylinder and an oblique plane (an
//! ellipse), two crossing planes (a segment), a Bézier hump cut level
//! (through its NURBS form; the points checked on the Bézier patch
//! itself). Every traced point must satisfy both surfaces' equations to
//! `1e-10`; closed branches must have the closed form's length to `1e-4`
//! relative (the chords stay within the tolerance `1e-6` of the curve).

use revolve::nalgebra::{Affine3, Matrix4, Point2, Point3, Vector3};
use revolve::tensor::SurfaceIntersectionCurve;
use revolve::{Error, Nurbs, NurbsSurface, Revolution, Surface};
use std::f64::consts::{FRAC_PI_2, TAU};

const TOL: f64 = 1e-6;

/// The unit sphere about the origin (turned about the y axis).
fn sphere() -> NurbsSurface {
    let profile = Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2).unwrap();
    NurbsSurface::from_revolution(&Revolution::new(profile)).unwrap()
}

/// The square `[−2, 2]²` of the plane through `o` spanned by `e1`, `e2`.
fn plane(o: Point3<f64>, e1: Vector3<f64>, e2: Vector3<f64>) -> NurbsSurface {
    NurbsSurface::bilinear(
        o - 2.0 * e1 - 2.0 * e2,
        o + 2.0 * e1 - 2.0 * e2,
        o - 2.0 * e1 + 2.0 * e2,
        o + 2.0 * e1 + 2.0 * e2,
    )
    .unwrap()
}

fn length(c: &SurfaceIntersectionCurve) -> f64 {
    let mut l: f64 = c
        .points
        .windows(2)
        .map(|w| (w[1].point - w[0].point).norm())
        .sum();
    if c.closed {
        l += (c.points[0].point - c.points[c.points.len() - 1].point).norm();
    }
    l
}

/// Every point on both surfaces at its parameters, and on the closed form.
fn check_points(
    c: &SurfaceIntersectionCurve,
    a: &NurbsSurface,
    b: &NurbsSurface,
    closed_form: impl Fn(&Point3<f64>) -> f64,
) {
    for p in &c.points {
        assert!(
            (a.eval(p.uv_a.0, p.uv_a.1) - p.point).norm() < 1e-10,
            "{p:?}"
        );
        assert!(
            (b.eval(p.uv_b.0, p.uv_b.1) - p.point).norm() < 1e-10,
            "{p:?}"
        );
        assert!(
            closed_form(&p.point).abs() < 1e-10,
            "{p:?}: {}",
            closed_form(&p.point)
        );
    }
}

#[test]
fn the_sphere_and_planes_meet_in_circles() {
    let s = sphere();
    for (k, normal) in [
        Vector3::y(),
        Vector3::new(0.3, 1.0, 0.2),
        Vector3::new(1.0, 0.1, -0.4),
        Vector3::z(),
    ]
    .iter()
    .enumerate()
    {
        let n = normal.normalize();
        let e1 = n.cross(&Vector3::new(0.36, 0.48, 0.8)).normalize();
        let e2 = n.cross(&e1);
        for d in [-0.9, -0.5, 0.0, 0.3, 0.999] {
            let p = plane(Point3::from(n * d), e1, e2);
            let curves = s.intersect_surface(&p, TOL).unwrap();
            assert_eq!(
                curves.len(),
                1,
                "normal {k}, d {d}: {} curves",
                curves.len()
            );
            let c = &curves[0];
            assert!(c.closed, "normal {k}, d {d}");
            check_points(c, &s, &p, |x| x.coords.norm() - 1.0);
            check_points(c, &s, &p, |x| x.coords.dot(&n) - d);
            let r = (1.0 - d * d).sqrt();
            let want = TAU * r;
            assert!(
                (length(c) - want).abs() <= 1e-4 * want,
                "normal {k}, d {d}: length {} vs {want}",
                length(c)
            );
        }
    }
}

#[test]
fn two_spheres_meet_in_a_circle_in_their_radical_plane() {
    // |x| = 1 and |x − (0.9, 0, 0)| = 0.8: the plane x = 0.65, radius 0.76.
    let a = sphere();
    let m = Matrix4::new(
        0.8, 0.0, 0.0, 0.9, //
        0.0, 0.8, 0.0, 0.0, //
        0.0, 0.0, 0.8, 0.0, //
        0.0, 0.0, 0.0, 1.0,
    );
    let b = sphere().transformed(&Affine3::from_matrix_unchecked(m));
    let curves = a.intersect_surface(&b, TOL).unwrap();
    assert_eq!(curves.len(), 1);
    let c = &curves[0];
    assert!(c.closed);
    check_points(c, &a, &b, |x| x.x - 0.65);
    check_points(c, &a, &b, |x| (x - Point3::new(0.9, 0.0, 0.0)).norm() - 0.8);
    let want = TAU * 0.76;
    assert!((length(c) - want).abs() <= 1e-4 * want, "{}", length(c));
}

#[test]
fn a_cylinder_and_an_oblique_plane_meet_in_an_ellipse() {
    // x² + y² = 1, 0 ≤ z ≤ 3, and z = 0.5x + 1.5: an ellipse with semi-axes
    // 1 and √1.25, whose length is 4·√1.25·E(e), e² = 1 − 1/1.25.
    let circle =
        Nurbs::arc_3d(Point3::origin(), Vector3::z(), Vector3::x(), 1.0, 0.0, TAU).unwrap();
    let cylinder = NurbsSurface::extrude(&circle, Vector3::new(0.0, 0.0, 3.0)).unwrap();
    let n = Vector3::new(-0.5, 0.0, 1.0).normalize();
    let e1 = Vector3::new(1.0, 0.0, 0.5).normalize();
    let p = plane(Point3::new(0.0, 0.0, 1.5), e1, Vector3::y());
    let curves = cylinder.intersect_surface(&p, TOL).unwrap();
    assert_eq!(curves.len(), 1);
    let c = &curves[0];
    assert!(c.closed);
    check_points(c, &cylinder, &p, |x| x.x.hypot(x.y) - 1.0);
    check_points(c, &cylinder, &p, |x| {
        (x - Point3::new(0.0, 0.0, 1.5)).dot(&n)
    });
    // The ellipse's perimeter by a fine sum (a reference independent of
    // the tracing).
    let (a_axis, b_axis) = (1.25f64.sqrt(), 1.0);
    let want: f64 = (0..200_000)
        .map(|k| {
            let t = TAU * (k as f64 + 0.5) / 200_000.0;
            (a_axis * t.sin()).hypot(b_axis * t.cos()) * TAU / 200_000.0
        })
        .sum();
    assert!(
        (length(c) - want).abs() <= 1e-4 * want,
        "{} vs {want}",
        length(c)
    );
}

#[test]
fn two_crossing_planes_meet_in_a_segment() {
    // z = 0 and x = 0.3 (both squares of side 4 about the origin): the
    // segment x = 0.3, z = 0, |y| ≤ 2, from boundary to boundary.
    let floor = plane(Point3::origin(), Vector3::x(), Vector3::y());
    let wall = plane(Point3::new(0.3, 0.0, 0.0), Vector3::y(), Vector3::z());
    let curves = floor.intersect_surface(&wall, TOL).unwrap();
    assert_eq!(curves.len(), 1);
    let c = &curves[0];
    assert!(!c.closed);
    check_points(c, &floor, &wall, |x| x.z);
    check_points(c, &floor, &wall, |x| x.x - 0.3);
    let (first, last) = (c.points[0].point, c.points[c.points.len() - 1].point);
    assert!((first.y.abs() - 2.0).abs() < 1e-12 && (last.y.abs() - 2.0).abs() < 1e-12);
    assert!((length(c) - 4.0).abs() < 1e-12);
}

#[test]
fn surfaces_apart_do_not_meet_and_bad_tolerances_are_errors() {
    let s = sphere();
    let far = plane(Point3::new(0.0, 2.0, 0.0), Vector3::x(), Vector3::z());
    assert!(s.intersect_surface(&far, TOL).unwrap().is_empty());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            s.intersect_surface(&far, bad),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    // A B-spline surface goes through its NURBS form.
    let grid: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| Point3::new(i as f64 - 1.5, 0.2 * (i * j) as f64 - 0.5, j as f64 - 1.5))
                .collect()
        })
        .collect();
    let bumpy = NurbsSurface::from(revolve::BSplineSurface::clamped((2, 2), grid).unwrap());
    let flat = plane(Point3::origin(), Vector3::x(), Vector3::z());
    let curves = bumpy.intersect_surface(&flat, TOL).unwrap();
    assert!(!curves.is_empty());
    for c in &curves {
        check_points(c, &bumpy, &flat, |x| x.y);
    }
}

#[test]
fn a_bezier_patch_through_its_nurbs_form() {
    // A bicubic hump over [0, 3]² (heights 0 at the rim, 2 inside) cut by
    // z = 0.5: a closed curve, every point on the Bézier patch itself (its
    // own evaluator) and on the plane.
    let net: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let inside = (1..3).contains(&i) && (1..3).contains(&j);
                    Point3::new(i as f64, j as f64, if inside { 2.0 } else { 0.0 })
                })
                .collect()
        })
        .collect();
    let hump = revolve::BezierSurface::new(net).unwrap();
    let nurbs = NurbsSurface::try_from(&hump).unwrap();
    let cut = plane(Point3::new(1.5, 1.5, 0.5), Vector3::x(), Vector3::y());
    let curves = nurbs.intersect_surface(&cut, TOL).unwrap();
    assert_eq!(curves.len(), 1);
    assert!(curves[0].closed);
    for p in &curves[0].points {
        assert!(
            (hump.eval(p.uv_a.0, p.uv_a.1) - p.point).norm() < 1e-10,
            "{p:?}"
        );
        assert!((p.point.z - 0.5).abs() < 1e-10, "{p:?}");
    }
}

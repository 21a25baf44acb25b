//! Intersections of space curves with tensor-product surfaces
//! (`intersect_curve` on `BezierSurface`, `BSplineSurface`, `NurbsSurface`)
//! against closed forms: the plane z = 0 (a bilinear patch) crossed by
//! tilted NURBS ellipses, a helix-like spiral of known height and a cubic
//! of known z(t); a NURBS sphere crossed by horizontal NURBS circles (the
//! crossing angle from the law of cosines); lines across a bicubic patch
//! checked against the crate's own ray intersector (a secondary check);
//! and every error path.
//!
//! Tolerances: certified points within `1e-12` of the closed forms (inputs
//! of size 1–3); tangential touches within `1e-5`.

use revolve::curve::intersect_curves;
use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::tensor::CurveSurfaceHit;
use revolve::{
    BSplineSurface, Bezier, BezierSurface, Curve, Error, Intersect, Nurbs, NurbsSurface,
    RationalBezier, RationalBezierSpan, Ray, Surface,
};
use std::f64::consts::FRAC_PI_2;
use std::time::Instant;

const TOL: f64 = 1e-9;

fn plane(size: f64) -> BezierSurface {
    BezierSurface::new(vec![
        vec![
            Point3::new(-size, -size, 0.0),
            Point3::new(-size, size, 0.0),
        ],
        vec![Point3::new(size, -size, 0.0), Point3::new(size, size, 0.0)],
    ])
    .unwrap()
}

/// The 2D NURBS circle's control points mapped by `f` (exact: rational
/// curves follow affine maps of their control points).
fn mapped_circle(center: Point2<f64>, r: f64, f: impl Fn(Point2<f64>) -> Point3<f64>) -> Nurbs<3> {
    let c = Nurbs::circle(center, r).unwrap();
    let points = c.points().iter().map(|p| f(*p)).collect();
    Nurbs::new(c.degree(), c.knots().to_vec(), points, c.weights().to_vec()).unwrap()
}

fn check_on_both(
    curve: &impl Curve<3>,
    surface: &impl Surface,
    hits: &[CurveSurfaceHit],
    within: f64,
) {
    for h in hits {
        let c = curve.eval(h.t);
        let s = surface.eval(h.uv.0, h.uv.1);
        assert!((c - h.point).norm() <= within, "{h:?}: curve at {c}");
        assert!((s - h.point).norm() <= within, "{h:?}: surface at {s}");
    }
}

fn assert_points(hits: &[CurveSurfaceHit], expected: &[Point3<f64>], within: f64) {
    assert_eq!(hits.len(), expected.len(), "{hits:?} vs {expected:?}");
    for e in expected {
        let d = hits
            .iter()
            .map(|h| (h.point - e).norm())
            .fold(f64::INFINITY, f64::min);
        assert!(d <= within, "{e} missed by {d}: {hits:?}");
    }
}

#[test]
fn tilted_ellipses_cross_the_plane_where_z_vanishes() {
    let p = plane(3.0);
    for k in 0..=20 {
        // z = slope·y + lift on the circle of radius 1.5 about (0.2, −0.1).
        let lift = -2.0 + 4.0 * k as f64 / 20.0;
        let slope = 1.3;
        let (cx, cy, r) = (0.2, -0.1, 1.5);
        let curve = mapped_circle(Point2::new(cx, cy), r, |q| {
            Point3::new(q.x, q.y, slope * q.y + lift)
        });
        let hits = p.intersect_curve(&curve, TOL).unwrap();
        // On the circle, y = −lift/slope: x = cx ± √(r² − (y − cy)²).
        let y = -lift / slope;
        let h = y - cy;
        if (h.abs() - r).abs() < 1e-3 {
            continue;
        }
        let expected: Vec<Point3<f64>> = if h.abs() < r {
            let dx = (r * r - h * h).sqrt();
            vec![Point3::new(cx - dx, y, 0.0), Point3::new(cx + dx, y, 0.0)]
        } else {
            vec![]
        };
        assert_points(&hits, &expected, 1e-12);
        assert!(hits.iter().all(|h| h.certified));
        check_on_both(&curve, &p, &hits, 1e-12);
    }
}

#[test]
fn a_helix_like_spiral_crosses_the_plane_at_known_points() {
    // x, y on a circle of radius 1; z rises linearly in the control points'
    // order, so z(t) is the same Bézier polynomial as the height of the
    // clamped spline of those heights: its zeros are found from the spans.
    // Closed form instead: lift the circle so that z = y/2 + x/4 + c (a
    // plane section, an affine map), which crosses z = 0 where the line
    // y/2 + x/4 + c = 0 meets the circle.
    let p = plane(3.0);
    for c in [-0.5, -0.1, 0.0, 0.2, 0.4] {
        let curve = mapped_circle(Point2::origin(), 1.0, |q| {
            Point3::new(q.x, q.y, q.y / 2.0 + q.x / 4.0 + c)
        });
        let hits = p.intersect_curve(&curve, TOL).unwrap();
        // Line n·q = −c with n = (1/4, 1/2): foot −c·n/|n|², half-chord.
        let n = Vector3::new(0.25, 0.5, 0.0);
        let nn = n.norm_squared();
        let foot: Vector3<f64> = -n * (c / nn);
        let half = (1.0 - foot.norm_squared()).sqrt();
        let along = Vector3::new(-n.y, n.x, 0.0).normalize();
        let expected = [
            Point3::from(foot + along * half),
            Point3::from(foot - along * half),
        ];
        assert_points(&hits, &expected, 1e-12);
        check_on_both(&curve, &p, &hits, 1e-12);
    }
    // A spiral: a cubic whose height is (t − 0.3)(t − 0.8)·4 in Bernstein
    // form (z₀ = 0.96, z₁ = −0.92/3·… computed below), x and y turning.
    // (t − 0.3)(t − 0.8) = t² − 1.1t + 0.24: Bernstein coefficients of
    // degree 3: b₀ = 0.24, b₁ = 0.24 − 1.1/3, b₂ = 0.24 − 2.2/3 + 1/3, b₃ = 0.14.
    let z = [0.24, 0.24 - 1.1 / 3.0, 0.24 - 2.2 / 3.0 + 1.0 / 3.0, 0.14].map(|z| 4.0 * z);
    let xy = [(1.0, 0.0), (1.0, 1.2), (-1.0, 1.2), (-1.0, 0.0)];
    let spiral = Bezier::new(
        (0..4)
            .map(|i| Point3::new(xy[i].0, xy[i].1, z[i]))
            .collect(),
    )
    .unwrap();
    let hits = p.intersect_curve(&spiral, TOL).unwrap();
    assert_eq!(hits.len(), 2, "{hits:?}");
    assert!(
        (hits[0].t - 0.3).abs() < 1e-14 && (hits[1].t - 0.8).abs() < 1e-14,
        "{hits:?}"
    );
    assert!(hits.iter().all(|h| h.certified && h.point.z.abs() < 1e-15));
}

/// A sphere of radius `r` about the origin as a NURBS surface: the
/// half-circle profile (u, from the south pole to the north) turned about
/// z by the full circle (v).
fn sphere(r: f64) -> NurbsSurface {
    let profile = Nurbs::arc(Point2::origin(), r, -FRAC_PI_2, FRAC_PI_2).unwrap();
    let turn = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    let points = profile
        .points()
        .iter()
        .map(|a| {
            turn.points()
                .iter()
                .map(|c| Point3::new(a.x * c.x, a.x * c.y, a.y))
                .collect()
        })
        .collect();
    let weights = profile
        .weights()
        .iter()
        .map(|wa| turn.weights().iter().map(|wc| wa * wc).collect())
        .collect();
    NurbsSurface::new(
        (2, 2),
        (profile.knots().to_vec(), turn.knots().to_vec()),
        points,
        weights,
    )
    .unwrap()
}

#[test]
fn horizontal_circles_cross_a_nurbs_sphere_by_the_law_of_cosines() {
    let r = 2.0;
    let s = sphere(r);
    let started = Instant::now();
    let mut runs = 0;
    for (c, rho, h) in [
        (1.0, 1.5, 0.3),
        (0.5, 1.0, -1.2),
        (1.5, 0.7, 0.9),
        (2.5, 1.0, 0.0),
        (0.2, 0.5, 0.1),
        (1.0, 0.8, 1.0),
    ] {
        let curve = mapped_circle(Point2::new(c, 0.0), rho, |q| Point3::new(q.x, q.y, h));
        let hits = s.intersect_curve(&curve, TOL).unwrap();
        runs += 1;
        // |(c + ρ cos θ, ρ sin θ, h)|² = r²: cos θ = (r² − c² − ρ² − h²)/(2cρ).
        let cos = (r * r - c * c - rho * rho - h * h) / (2.0 * c * rho);
        let expected: Vec<Point3<f64>> = if cos.abs() < 1.0 {
            let sin = (1.0 - cos * cos).sqrt();
            vec![
                Point3::new(c + rho * cos, rho * sin, h),
                Point3::new(c + rho * cos, -rho * sin, h),
            ]
        } else {
            vec![]
        };
        assert_points(&hits, &expected, 1e-12);
        assert!(hits.iter().all(|h| h.certified), "{hits:?}");
        check_on_both(&curve, &s, &hits, 1e-12);
    }
    eprintln!(
        "circle against NURBS sphere: {:.2} ms per curve",
        1e3 * started.elapsed().as_secs_f64() / runs as f64
    );
}

#[test]
fn a_circle_tangent_to_the_plane_touches_once() {
    let p = plane(3.0);
    // A vertical circle of radius 1 resting on z = 0 at (0.3, 0.2, 0).
    let curve = mapped_circle(Point2::new(0.0, 1.0), 1.0, |q| {
        Point3::new(0.3, 0.2 + q.x, q.y)
    });
    let hits = p.intersect_curve(&curve, TOL).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(!hits[0].certified);
    assert!((hits[0].point - Point3::new(0.3, 0.2, 0.0)).norm() < 1e-5);
}

#[test]
fn lines_across_a_bicubic_patch_agree_with_the_ray_intersector() {
    // A wavy bicubic patch over [0, 3]².
    let grid: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let z = [0.0, 0.8, -0.6, 0.3][(i + 2 * j) % 4];
                    Point3::new(i as f64, j as f64, z)
                })
                .collect()
        })
        .collect();
    let patch = BezierSurface::new(grid).unwrap();
    let bspline = BSplineSurface::new(
        (3, 3),
        (
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        ),
        patch.points().to_vec(),
    )
    .unwrap();
    let mut compared = 0;
    for k in 0..40 {
        let a = Point3::new(0.2 + 0.06 * k as f64, 0.3 + 0.05 * k as f64, 2.0);
        let b = Point3::new(
            2.8 - 0.05 * k as f64,
            0.1 + 0.07 * k as f64,
            -2.0 + 0.02 * k as f64,
        );
        let line = Bezier::new(vec![a, b]).unwrap();
        let hits = patch.intersect_curve(&line, TOL).unwrap();
        let again = bspline.intersect_curve(&line, TOL).unwrap();
        assert_eq!(hits.len(), again.len());
        let ray = Ray::new(a, b - a);
        let mut ray_hits = Vec::new();
        patch.intersect_all(&ray, 0.0, 1.0, &mut ray_hits);
        if hits.iter().all(|h| h.certified) {
            assert_eq!(hits.len(), ray_hits.len(), "{hits:?} vs {ray_hits:?}");
            for (h, r) in hits.iter().zip(&ray_hits) {
                assert!((h.t - r.t).abs() < 1e-12, "{h:?} vs {r:?}");
                assert!((h.point - r.point).norm() < 1e-12);
            }
            compared += 1;
        }
        check_on_both(&line, &patch, &hits, 1e-12);
    }
    assert!(compared >= 35);
}

#[test]
fn crossings_on_patch_edges_and_span_joins_are_reported_once() {
    let grid: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| Point3::new(i as f64, j as f64, 0.0))
                .collect()
        })
        .collect();
    let s = BSplineSurface::new(
        (1, 1),
        (
            vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0],
            vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0],
        ),
        grid,
    )
    .unwrap(); // nine patches
    // Through the grid's interior vertex (1, 2, 0), where four patches meet.
    let line = Bezier::new(vec![
        Point3::new(1.0, 2.0, 1.0),
        Point3::new(1.0, 2.0, -1.0),
    ])
    .unwrap();
    let hits = s.intersect_curve(&line, TOL).unwrap();
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(hits[0].certified && (hits[0].t - 0.5).abs() < 1e-15);
    // A circle whose span joins lie on the plane: z = y, crossing at y = 0
    // where its spans join (angles 0 and π).
    let curve = mapped_circle(Point2::new(1.5, 0.0), 1.0, |q| {
        Point3::new(q.x, q.y + 1.5, q.y)
    });
    let hits = s.intersect_curve(&curve, TOL).unwrap();
    assert_points(
        &hits,
        &[Point3::new(0.5, 1.5, 0.0), Point3::new(2.5, 1.5, 0.0)],
        1e-15,
    );
}

/// A curve known only by its formula.
struct Helix;
impl Curve<3> for Helix {
    fn domain(&self) -> (f64, f64) {
        (0.0, 10.0)
    }
    fn eval(&self, t: f64) -> Point3<f64> {
        let t = t.clamp(0.0, 10.0);
        Point3::new(t.cos(), t.sin(), t / 10.0 - 0.5)
    }
    fn derivative(&self, t: f64) -> Vector3<f64> {
        let t = t.clamp(0.0, 10.0);
        Vector3::new(-t.sin(), t.cos(), 0.1)
    }
}

struct BadSpans(Vec<RationalBezierSpan<3>>);
impl Curve<3> for BadSpans {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, _: f64) -> Point3<f64> {
        Point3::origin()
    }
    fn derivative(&self, _: f64) -> Vector3<f64> {
        Vector3::zeros()
    }
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<3>>> {
        Some(self.0.clone())
    }
}

#[test]
fn every_error_path() {
    let p = plane(2.0);
    let line = Bezier::new(vec![
        Point3::new(0.0, 0.0, -1.0),
        Point3::new(0.0, 0.0, 1.0),
    ])
    .unwrap();
    for bad in [0.0, -1e-9, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            p.intersect_curve(&line, bad),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    assert!(matches!(
        p.intersect_curve(&line, 1e-13),
        Err(Error::ToleranceTooSmall { .. })
    ));
    assert_eq!(
        p.intersect_curve(&Helix, TOL),
        Err(Error::NotPiecewiseRational)
    );
    let span = |a: f64, b: f64| RationalBezierSpan {
        knots: (a, b),
        curve: RationalBezier::from(line.clone()),
    };
    assert_eq!(
        p.intersect_curve(&BadSpans(vec![span(0.0, 0.0)]), TOL),
        Err(Error::SpansOutOfOrder { index: 0 })
    );
    // A line lying in the plane: the curve is on the surface.
    let inside = Bezier::new(vec![
        Point3::new(-1.0, -0.5, 0.0),
        Point3::new(1.0, 0.5, 0.0),
    ])
    .unwrap();
    let started = Instant::now();
    let err = p.intersect_curve(&inside, TOL).unwrap_err();
    assert!(matches!(err, Error::CurveOnSurface { .. }), "{err}");
    assert!(err.to_string().contains("lies on the surface"));
    assert!(started.elapsed().as_secs_f64() < 30.0);
    // A constant curve of degree 4100 against a bilinear patch: too large.
    let high = Bezier::new(vec![Point3::new(0.0, 0.0, 0.0); 4101]).unwrap();
    let err = p.intersect_curve(&high, TOL).unwrap_err();
    assert!(matches!(err, Error::IntersectionTooLarge { .. }), "{err}");
    // Curves in the plane still work with the 2D function (sanity of the
    // shared search): the unit circle against a line.
    let c = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    let l = Bezier::new(vec![Point2::new(-2.0, 0.5), Point2::new(2.0, 0.5)]).unwrap();
    assert_eq!(intersect_curves(&c, &l, TOL).unwrap().len(), 2);
}

#[test]
fn random_cubics_against_random_bicubic_patches() {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let started = Instant::now();
    let mut total = 0;
    for case in 0..40 {
        let grid: Vec<Vec<Point3<f64>>> = (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| Point3::new(i as f64 / 1.5 - 1.0, j as f64 / 1.5 - 1.0, 0.6 * next()))
                    .collect()
            })
            .collect();
        let patch = BezierSurface::new(grid).unwrap();
        let curve = Bezier::new(
            (0..4)
                .map(|_| Point3::new(next(), next(), 1.5 * next()))
                .collect(),
        )
        .unwrap();
        let hits = patch.intersect_curve(&curve, TOL).unwrap();
        total += hits.len();
        for h in &hits {
            let gap = (curve.eval(h.t) - patch.eval(h.uv.0, h.uv.1)).norm();
            let within = if h.certified { 1e-12 } else { 1e-6 };
            assert!(gap < within, "case {case}: {h:?} gap {gap}");
        }
    }
    assert!(total > 10);
    eprintln!(
        "cubic against bicubic patch: {:.2} ms per pair",
        1e3 * started.elapsed().as_secs_f64() / 40.0
    );
}

#[test]
fn a_great_circle_lies_on_the_sphere() {
    let s = sphere(2.0);
    let equator = mapped_circle(Point2::origin(), 2.0, |q| Point3::new(q.x, q.y, 0.0));
    let started = Instant::now();
    let err = s.intersect_curve(&equator, TOL).unwrap_err();
    assert!(matches!(err, Error::CurveOnSurface { .. }), "{err}");
    assert!(started.elapsed().as_secs_f64() < 30.0);
    // Tilted and moved off centre it crosses twice.
    let tilted = mapped_circle(Point2::origin(), 2.0, |q| {
        Point3::new(q.x + 0.5, q.y, 0.3 * q.x)
    });
    let hits = s.intersect_curve(&tilted, TOL).unwrap();
    assert_eq!(hits.len(), 2, "{hits:?}");
    assert!(
        hits.iter()
            .all(|h| h.certified && (h.point.coords.norm() - 2.0).abs() < 1e-12)
    );
}

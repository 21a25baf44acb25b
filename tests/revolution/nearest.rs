//! `Revolution::nearest_point`.
//!
//! References, independent of the reduction to the profile: closed forms
//! (a sphere: the radial projection; a torus: through the tube's centre
//! circle; cylinders and cones, also written at negative `x` and crossing
//! the axis: the distance to the profile folded onto `x ≥ 0`, segment by
//! segment), and `revolve_testkit::nearest_reference` (about 10⁵ samples of
//! `Surface::eval` refined by Levenberg–Marquardt steps). Surfaces are
//! placed off the origin along tilted axes. An answer must be certified
//! (profiles with spans), no reference may beat it by more than `1e-12` of
//! the problem's size, its point must be `Surface::eval(uv)` to rounding
//! (`1e-14` of the size) and its distance `|point − p|`; the ray from `p`
//! toward its nearest point meets the surface first there, with the same
//! `uv` (the hit convention).

use revolve_testkit as common;

use common::conic_profiles::{sphere_profile, torus_profile};
use common::nearest_reference::sampled_nearest;
use common::{Rng, bezier, points, wine_glass};
use revolve::nalgebra::{Point2, Point3, Unit, Vector2, Vector3};
use revolve::{BSpline, Curve, Error, Intersect, Ray, Revolution, Surface, SurfaceNearest};
use std::f64::consts::{PI, TAU};

/// A placement off the origin along a tilted axis.
fn placement() -> (Point3<f64>, Unit<Vector3<f64>>) {
    (
        Point3::new(0.7, -1.25, 2.0),
        Unit::new_normalize(Vector3::new(0.3, 1.0, -0.45)),
    )
}

/// `p` in the placement's frame: (distance from the axis, height).
fn meridian(p: &Point3<f64>, (origin, axis): &(Point3<f64>, Unit<Vector3<f64>>)) -> (f64, f64) {
    let d = p - origin;
    let y = d.dot(axis);
    ((d - axis.into_inner() * y).norm(), y)
}

/// The distance from `q` to the segment `ab` in the plane.
fn segment_distance(q: Vector2<f64>, a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    let ab = b - a;
    let t = ((q - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (a + ab * t - q).norm()
}

/// What every answer must satisfy (see the module docs) against the
/// reference distance `reference`.
fn check<C: Curve<2>>(
    s: &Revolution<C>,
    p: &Point3<f64>,
    near: &SurfaceNearest,
    reference: f64,
    size: f64,
) {
    let [du, dv] = s.domain();
    assert!(du.0 <= near.uv.0 && near.uv.0 <= du.1, "{near:?}");
    assert!(dv.0 <= near.uv.1 && near.uv.1 <= dv.1, "{near:?}");
    assert_eq!(near.patch, 0);
    assert!(
        (near.point - s.eval(near.uv.0, near.uv.1)).norm() <= 1e-14 * size,
        "{near:?} vs {:?}",
        s.eval(near.uv.0, near.uv.1)
    );
    assert_eq!(near.distance, (near.point - p).norm());
    assert!(
        near.distance <= reference + 1e-12 * size,
        "p = {p:?}: {near:?} beaten by {reference}"
    );
    // The segment from p to its nearest point crosses the surface nowhere
    // before it: the ray toward it hits it first, with the same uv.
    if near.distance > 1e-6 * size {
        let ray = Ray::new(*p, near.point - p);
        let hit = s
            .intersect(&ray, 0.0, f64::INFINITY)
            .expect("the nearest point is hit");
        assert!((hit.t - 1.0).abs() <= 1e-7, "p = {p:?}: {near:?}, {hit:?}");
        assert!(
            (hit.point - near.point).norm() <= 1e-7 * size,
            "{near:?}, {hit:?}"
        );
        let turn = (hit.uv.1 - near.uv.1).abs();
        let on_axis = near.point.coords.amax() >= 0.0
            && (s.eval(near.uv.0, 0.0) - s.eval(near.uv.0, PI)).norm() <= 1e-9 * size;
        assert!(on_axis || turn.min(TAU - turn) <= 1e-6, "{near:?}, {hit:?}");
        assert!(
            (hit.uv.0 - near.uv.0).abs() <= 1e-6 || on_axis,
            "{near:?}, {hit:?}"
        );
    }
}

/// Query points: random in a box about the surface (inside and out), just
/// off the surface on both sides, on the axis, at the ends of the profile,
/// and far away.
fn queries<C: Curve<2>>(s: &Revolution<C>, seed: u64) -> Vec<Point3<f64>> {
    let mut rng = Rng(seed);
    let b = s.bounds();
    let [du, _] = s.domain();
    let (origin, axis) = (
        s.to_world().translation.vector,
        s.to_world().rotation * Vector3::y(),
    );
    let mut out = Vec::new();
    for k in 0..16 {
        out.push(rng.point_in(&b));
        let (u, v) = (rng.range(du.0, du.1), rng.range(0.0, TAU));
        let q = s.eval(u, v);
        let n = s.normal(u, v).map_or(axis, |n| n.into_inner());
        let offset = [0.2, 1e-3, 1e-7, 1e-11, 0.0][k % 5] * if k % 2 == 0 { 1.0 } else { -1.0 };
        out.push(q + n * offset);
        out.push(Point3::from(origin + axis * rng.range(-2.0, 2.0)));
    }
    out.push(s.eval(du.0, 0.0));
    out.push(s.eval(du.1, 1.0));
    out.push(Point3::from(origin + Vector3::new(30.0, -20.0, 12.0)));
    out
}

/// Runs the queries against the sampled reference; every answer certified.
fn never_beaten<C: Curve<2>>(name: &str, s: &Revolution<C>, seed: u64) {
    let size = s
        .bounds()
        .min
        .coords
        .amax()
        .max(s.bounds().max.coords.amax());
    for p in queries(s, seed) {
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified, "{name}: {p:?}");
        let reference = sampled_nearest(s, &p, 317).distance;
        check(s, &p, &near, reference, size.max(p.coords.amax()));
    }
}

#[test]
fn sphere_is_the_radial_projection() {
    let (origin, axis) = placement();
    let r = 1.25;
    let s = Revolution::new(sphere_profile(r)).with_axis(origin, axis);
    let mut rng = Rng(1);
    let mut queries: Vec<Point3<f64>> = (0..300)
        .map(|k| {
            let rho = [0.0, 0.5, 1.2, 1.25, 1.3, 4.0, 100.0][k % 7];
            origin + rng.direction() * rho
        })
        .collect();
    // On the axis: the poles, beyond them, the centre.
    for h in [-3.0, -1.25, -0.5, 0.0, 0.5, 1.25, 3.0] {
        queries.push(origin + axis.into_inner() * h);
    }
    for p in queries {
        let near = s.nearest_point(&p).unwrap();
        let rho = (p - origin).norm();
        assert!(near.certified);
        let size = rho.max(4.0);
        assert!(
            (near.distance - (rho - r).abs()).abs() <= 4e-15 * size,
            "{p:?}: {near:?}"
        );
        if rho > 1e-9 {
            let want = origin + (p - origin) * (r / rho);
            assert!(
                (near.point - want).norm() <= 4e-15 * size,
                "{p:?}: {near:?}"
            );
        }
        check(&s, &p, &near, (rho - r).abs(), size);
    }
    // On the axis of an unplaced sphere every angle is as near: θ = 0.
    let unplaced = Revolution::new(sphere_profile(r));
    for h in [-3.0, -1.25, 0.0, 0.5, 2.0] {
        let near = unplaced.nearest_point(&Point3::new(0.0, h, 0.0)).unwrap();
        assert_eq!(near.uv.1, 0.0, "on the axis θ = 0");
        assert!((near.distance - (h.abs() - r).abs()).abs() <= 1e-15);
    }
}

#[test]
fn torus_is_the_tube_about_its_centre_circle() {
    let place = placement();
    let (big, small) = (2.0, 0.5);
    let s = Revolution::new(torus_profile(big, small)).with_axis(place.0, place.1);
    let mut rng = Rng(2);
    for k in 0..300 {
        let p = match k % 3 {
            0 => rng.point_in(&s.bounds()),
            1 => place.0 + place.1.into_inner() * rng.range(-2.0, 2.0),
            _ => place.0 + rng.direction() * rng.range(0.0, 10.0),
        };
        let (rho, y) = meridian(&p, &place);
        let want = ((rho - big).hypot(y) - small).abs();
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified);
        assert!(
            (near.distance - want).abs() <= 2e-14,
            "{p:?}: {near:?} vs {want}"
        );
        check(&s, &p, &near, want, 4.0);
    }
}

#[test]
fn cylinders_and_cones_are_their_folded_profiles() {
    let place = placement();
    // Profiles as polylines; the surface is the profile folded onto x ≥ 0.
    let profiles: [&[(f64, f64)]; 5] = [
        &[(1.0, 0.0), (1.0, 2.0)],
        &[(-1.0, 0.0), (-1.0, 2.0)],
        &[(0.0, 0.0), (1.0, 1.5)],
        &[(-0.5, -0.5), (1.0, 1.0)],
        &[(1.5, 0.0), (-1.5, 0.0)],
    ];
    let mut rng = Rng(3);
    for profile in profiles {
        let s = Revolution::new(revolve::Bezier::new(points(profile)).unwrap())
            .with_axis(place.0, place.1);
        let (a, b) = (
            Vector2::new(profile[0].0, profile[0].1),
            Vector2::new(profile[1].0, profile[1].1),
        );
        for k in 0..200 {
            let p = if k % 4 == 0 {
                place.0 + place.1.into_inner() * rng.range(-1.0, 3.0)
            } else {
                place.0 + rng.direction() * rng.range(0.0, 3.0)
            };
            let (rho, y) = meridian(&p, &place);
            let want = segment_distance(Vector2::new(rho, y), a, b).min(segment_distance(
                Vector2::new(-rho, y),
                a,
                b,
            ));
            let near = s.nearest_point(&p).unwrap();
            assert!(near.certified);
            assert!(
                (near.distance - want).abs() <= 2e-14,
                "{profile:?} {p:?}: {near:?} vs {want}"
            );
            check(&s, &p, &near, want, 4.0);
        }
    }
}

#[test]
fn splines_are_never_beaten_by_refined_samples() {
    let place = placement();
    never_beaten(
        "goblet",
        &Revolution::new(wine_glass()).with_axis(place.0, place.1),
        4,
    );
    never_beaten("vase", &bezier(&common::VASE), 5);
    never_beaten(
        "sphere",
        &Revolution::new(sphere_profile(1.0)).with_axis(place.0, place.1),
        6,
    );
    never_beaten("torus", &Revolution::new(torus_profile(1.0, 0.4)), 7);
    // A profile crossing the axis, as scene files write some.
    let crossing = BSpline::clamped(
        3,
        points(&[
            (-0.6, -1.0),
            (0.2, -0.8),
            (0.9, 0.0),
            (-0.3, 0.6),
            (0.5, 1.2),
        ]),
    )
    .unwrap();
    never_beaten(
        "crossing",
        &Revolution::new(crossing).with_axis(place.0, place.1),
        8,
    );
}

/// A half circle known only by `eval` and `derivative` (no spans).
struct Arc;

impl Curve<2> for Arc {
    fn domain(&self) -> (f64, f64) {
        (-PI / 2.0, PI / 2.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(t.cos(), t.sin())
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        Vector2::new(-t.sin(), t.cos())
    }
}

#[test]
fn profile_without_spans_gives_the_sampled_answer() {
    let s = Revolution::new(Arc);
    let mut rng = Rng(9);
    for _ in 0..50 {
        let p = Point3::origin() + rng.direction() * rng.range(0.1, 3.0);
        let near = s.nearest_point(&p).unwrap();
        assert!(!near.certified);
        assert!(
            (near.distance - ((p.coords.norm()) - 1.0).abs()).abs() <= 1e-9,
            "{p:?}: {near:?}"
        );
    }
}

#[test]
fn bad_queries_and_broken_surfaces_are_errors() {
    let s = Revolution::new(sphere_profile(1.0));
    for (p, coordinate) in [
        (Point3::new(f64::NAN, 0.0, 0.0), 0),
        (Point3::new(0.0, f64::NEG_INFINITY, 0.0), 1),
        (Point3::new(0.0, 0.0, 2e100), 2),
    ] {
        assert!(matches!(
            s.nearest_point(&p),
            Err(Error::InvalidQueryPoint { coordinate: c, .. }) if c == coordinate
        ));
    }
    let broken = Revolution::new(sphere_profile(1.0))
        .with_axis(Point3::new(f64::NAN, 0.0, 0.0), Vector3::y_axis());
    assert!(matches!(
        broken.nearest_point(&Point3::origin()),
        Err(Error::InvalidPlacement { .. })
    ));
    // The largest accepted coordinates work.
    let near = s.nearest_point(&Point3::new(1e100, -1e100, 1e100)).unwrap();
    assert!(near.certified && (near.distance / 3f64.sqrt() / 1e100 - 1.0).abs() <= 1e-15);
}

#[test]
fn reversed_surfaces_have_the_same_nearest_points() {
    // Reversal flips normals only: the same points, the same answers.
    let place = placement();
    let goblet = Revolution::new(wine_glass()).with_axis(place.0, place.1);
    let mut rng = Rng(31);
    for _ in 0..20 {
        let p = rng.point_in(&goblet.bounds());
        assert_eq!(
            goblet.reversed().nearest_point(&p),
            goblet.nearest_point(&p)
        );
    }
}

//! Surface and intersection tests for `Revolution`: analytic partials
//! against central differences, normals (perpendicularity, the cross
//! product, limits on the axis, the documented orientation), `with_axis`
//! placement, bounds, and intersections of random rays against a brute-force
//! march along the ray that does not use the library's solver.
//!
//! # Tolerances
//! - Central differences with step `h` (`10⁻⁵` of the parameter range) have
//!   truncation error at most `h²/6·M₃` (`M₃` a bound on the third
//!   derivative: from the third differences of the Bézier control points for
//!   `u`, `max|x|` for `θ`) and rounding error about `ε·M₀/h`; the tests
//!   allow `2·h²/6·M₃ + 16ε·M₀/h`.
//! - Unit normals: unit to `1e-12`; perpendicular to the partials and equal
//!   to the normalized cross product to `1e-12` (`∂S/∂u ⟂ ∂S/∂θ` always, so the
//!   cross product is well conditioned wherever `x ≠ 0` and `x′, y′` are not
//!   both zero).
//! - Hits: on their ray and on the surface (`eval(uv)`) to `1e-12·scale`;
//!   `|t − t_ref|·|d| ≤ (1e-12 + 16ε·κ)·scale` against the bisected bracket,
//!   `κ = |d|/|d·n|` the condition number of the crossing.

use revolve_testkit as common;

use common::{GLASS, REL, Rng, bezier, check_hit, kappa, points, t_tolerance, uniform_cubic};
use proptest::prelude::*;
use revolve::nalgebra::{Point2, Point3, Unit, Vector3};
use revolve::{Aabb, BSpline, Curve, Intersect, Ray, Revolution, Surface, Tolerance};
use std::f64::consts::{PI, TAU};

const EPS: f64 = f64::EPSILON;
const INF: f64 = f64::INFINITY;

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// A closed body of one cubic Bézier, poles at both ends.
const CAPSULE: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

/// A random B-spline profile: degree 1–5, 2–7 spans, clamped or uniform
/// knots; heights strictly increasing (so `y(u)` is strictly monotone);
/// radii in `[0.2, 1.5]`, or with probability 1/4 in `[−1, 1]` (crossing the
/// axis), or with probability 1/4 all negated (scene-file style).
fn random_monotone_profile(rng: &mut Rng) -> BSpline<2> {
    let degree = 1 + rng.below(5);
    let n = degree + 1 + rng.below(6);
    let style = rng.below(4);
    let mut y = rng.range(-1.0, 0.0);
    let pts: Vec<Point2<f64>> = (0..n)
        .map(|_| {
            y += rng.range(0.05, 0.6);
            let x = match style {
                0 => rng.range(-1.0, 1.0),
                1 => -rng.range(0.2, 1.5),
                _ => rng.range(0.2, 1.5),
            };
            Point2::new(x, y)
        })
        .collect();
    if rng.below(2) == 0 {
        BSpline::clamped(degree, pts).unwrap()
    } else {
        BSpline::uniform(degree, pts).unwrap()
    }
}

/// The largest absolute coordinate of a profile's control points (of its
/// Bézier spans): the scene scale.
fn profile_scale<C: Curve<2>>(c: &C) -> f64 {
    c.bezier_spans()
        .unwrap()
        .iter()
        .flat_map(|s| s.curve.points().to_vec())
        .fold(0.0_f64, |m, p| m.max(p.x.abs()).max(p.y.abs()))
}

/// A bound on `|P‴(u)|` over the whole profile: for each Bézier span of degree
/// `n` over a knot interval of length `Δ`, `n(n−1)(n−2)/Δ³ · max|Δ³Pᵢ|`.
fn third_derivative_bound<C: Curve<2>>(c: &C) -> f64 {
    let mut m = 0.0_f64;
    for s in c.bezier_spans().unwrap() {
        let p = s.curve.points();
        let n = p.len() - 1;
        if n < 3 {
            continue;
        }
        let delta = s.knots.1 - s.knots.0;
        let factor = (n * (n - 1) * (n - 2)) as f64 / delta.powi(3);
        for w in p.windows(4) {
            let d3 = (w[3] - w[0]) + (w[1] - w[2]) * 3.0;
            m = m.max(factor * d3.norm());
        }
    }
    m
}

/// A random ray from about `4·size` away toward a random point of the box
/// `center ± half`.
fn random_ray(rng: &mut Rng, center: Point3<f64>, half: Vector3<f64>, size: f64) -> Ray {
    let target = center
        + Vector3::new(
            rng.range(-half.x, half.x),
            rng.range(-half.y, half.y),
            rng.range(-half.z, half.z),
        );
    let origin = center + rng.direction() * 4.0 * size;
    Ray::new(origin, (target - origin) * rng.range(0.1, 3.0))
}

/// A random placement: an axis through a random point in a random direction
/// (also exactly ±y now and then; axes within 1e-3 of ±y are
/// `with_axis_nearly_along_y`).
fn random_axis(rng: &mut Rng) -> (Point3<f64>, Unit<Vector3<f64>>) {
    let origin = Point3::new(
        rng.range(-3.0, 3.0),
        rng.range(-3.0, 3.0),
        rng.range(-3.0, 3.0),
    );
    let axis = match rng.below(6) {
        0 => Vector3::y(),
        1 => -Vector3::y(),
        _ => loop {
            let d = rng.direction();
            if d.y.abs() < 1.0 - 1e-6 {
                break d;
            }
        },
    };
    (origin, Unit::new_normalize(axis))
}

/// An orthonormal right-handed frame `(e₁, a, e₃)` with `a` the given axis,
/// built here (not the library's rotation): any such frame gives the same
/// surface, since it is invariant under rotations about its axis.
fn frame(a: &Unit<Vector3<f64>>) -> [Vector3<f64>; 3] {
    let a = a.into_inner();
    let helper = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::z()
    };
    let e3 = helper.cross(&a).normalize();
    let e1 = a.cross(&e3);
    [e1, a, e3]
}

fn to_local(f: &[Vector3<f64>; 3], origin: &Point3<f64>, p: &Point3<f64>) -> Point3<f64> {
    let v = p - origin;
    Point3::new(v.dot(&f[0]), v.dot(&f[1]), v.dot(&f[2]))
}

fn vec_to_local(f: &[Vector3<f64>; 3], v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.dot(&f[0]), v.dot(&f[1]), v.dot(&f[2]))
}

fn vec_to_world(f: &[Vector3<f64>; 3], v: &Vector3<f64>) -> Vector3<f64> {
    f[0] * v.x + f[1] * v.y + f[2] * v.z
}

/// The test profiles used throughout, as B-splines.
fn profiles(rng: &mut Rng) -> Vec<(String, BSpline<2>)> {
    let mut v = vec![
        (
            "glass".to_string(),
            BSpline::uniform(3, points(&GLASS)).unwrap(),
        ),
        (
            "capsule".to_string(),
            BSpline::clamped(3, points(&CAPSULE)).unwrap(),
        ),
        (
            "negative-x glass".to_string(),
            BSpline::uniform(3, GLASS.iter().map(|&(x, y)| Point2::new(-x, y)).collect()).unwrap(),
        ),
        (
            "cone".to_string(),
            BSpline::clamped(1, points(&[(1.0, 0.0), (0.0, 1.0)])).unwrap(),
        ),
    ];
    for i in 0..12 {
        v.push((format!("random {i}"), random_monotone_profile(rng)));
    }
    v
}

// ---------------------------------------------------------------------------
// Partials, normals, orientation
// ---------------------------------------------------------------------------

/// `∂S/∂u` and `∂S/∂θ` against central differences at random parameters
/// (away from knots by more than the step, where a low-degree spline's
/// derivative may jump), also for placed surfaces.
#[test]
fn partials_match_central_differences() {
    let mut rng = Rng(1);
    for (name, profile) in profiles(&mut rng) {
        let (origin, axis) = random_axis(&mut rng);
        let local = Revolution::new(profile.clone());
        let placed = Revolution::new(profile.clone()).with_axis(origin, axis);
        let (u0, u1) = profile.domain();
        let hu = 1e-5 * (u1 - u0);
        let ht = 1e-5;
        let m3 = third_derivative_bound(&profile);
        let scale = profile_scale(&profile);
        let m0 = scale + origin.coords.norm();
        let tol_u = 2.0 * hu * hu / 6.0 * m3 + 16.0 * EPS * m0 / hu;
        let tol_t = 2.0 * ht * ht / 6.0 * scale + 16.0 * EPS * m0 / ht;
        let knots: Vec<f64> = profile.knots().to_vec();
        let mut checked = 0;
        while checked < 200 {
            let u = rng.range(u0 + 2.0 * hu, u1 - 2.0 * hu);
            if knots.iter().any(|&k| (k - u).abs() < 2.0 * hu) {
                continue;
            }
            let theta = rng.range(-1.0, 7.0);
            for s in [&local as &dyn Surface, &placed] {
                let (su, sv) = s.partials(u, theta);
                let fu = (s.eval(u + hu, theta) - s.eval(u - hu, theta)) / (2.0 * hu);
                let ft = (s.eval(u, theta + ht) - s.eval(u, theta - ht)) / (2.0 * ht);
                assert!(
                    (su - fu).norm() <= tol_u,
                    "{name}: ∂S/∂u {su:?} vs {fu:?} at ({u}, {theta}), tol {tol_u:e}"
                );
                assert!(
                    (sv - ft).norm() <= tol_t,
                    "{name}: ∂S/∂θ {sv:?} vs {ft:?} at ({u}, {theta}), tol {tol_t:e}"
                );
            }
            checked += 1;
        }
    }
}

/// Off the axis, the normal is unit, perpendicular to both partials, and
/// the normalized cross product `∂S/∂u × ∂S/∂θ`.
#[test]
fn normals_are_the_normalized_cross_product_off_the_axis() {
    let mut rng = Rng(2);
    for (name, profile) in profiles(&mut rng) {
        let (origin, axis) = random_axis(&mut rng);
        let placed = Revolution::new(profile.clone()).with_axis(origin, axis);
        let local = Revolution::new(profile.clone());
        let (u0, u1) = profile.domain();
        for _ in 0..300 {
            let u = rng.range(u0, u1);
            let theta = rng.range(0.0, TAU);
            if profile.eval(u).x.abs() < 1e-6 {
                continue;
            }
            for s in [&local as &dyn Surface, &placed] {
                let (su, sv) = s.partials(u, theta);
                let cross = su.cross(&sv);
                if su.norm() < 1e-8 {
                    continue; // a stationary point of the profile
                }
                let n = s
                    .normal(u, theta)
                    .expect("normal off the axis")
                    .into_inner();
                assert!((n.norm() - 1.0).abs() <= 1e-12);
                assert!(n.dot(&su).abs() <= 1e-12 * su.norm(), "{name}");
                assert!(n.dot(&sv).abs() <= 1e-12 * sv.norm(), "{name}");
                assert!(
                    (n - cross.normalize()).norm() <= 1e-12,
                    "{name}: {n:?} vs {:?} at ({u}, {theta})",
                    cross.normalize()
                );
            }
        }
    }
}

/// On the axis: a disk's center and the poles of closed profiles have the
/// limit normal `±y` (the limit of the normals nearby), whatever `θ`; a cone's
/// apex has none. A profile meeting the axis at slope `1e-9` (below `√ε`) counts
/// as perpendicular, at `1e-6` as a cone. Repeated control points on the axis
/// take the tangent from higher derivatives.
#[test]
fn normal_limits_on_the_axis() {
    let thetas = [0.0, 0.5, 2.0, 4.0, TAU];
    let is = |n: Option<Unit<Vector3<f64>>>, want: Vector3<f64>| {
        let n = n.expect("normal at the pole").into_inner();
        assert!((n - want).norm() <= 1e-12, "{n:?} vs {want:?}");
    };
    let disk = bezier(&[(0.0, 0.5), (1.5, 0.5)]);
    let capsule = bezier(&CAPSULE);
    let glass = uniform_cubic(&GLASS);
    let (g0, g1) = glass.profile().domain();
    let repeated = bezier(&[(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
    for &theta in &thetas {
        is(disk.normal(0.0, theta), Vector3::y());
        is(capsule.normal(0.0, theta), Vector3::y());
        is(capsule.normal(1.0, theta), -Vector3::y());
        is(glass.normal(g0, theta), Vector3::y());
        is(glass.normal(g1, theta), -Vector3::y());
        is(repeated.normal(0.0, theta), Vector3::y());
        // The limit: normals next to the pole converge to it.
        for (s, u, want) in [
            (&capsule, 1e-7, Vector3::y()),
            (&capsule, 1.0 - 1e-7, -Vector3::y()),
            (&repeated, 1e-7, Vector3::y()),
        ] {
            let n = s.normal(u, theta).unwrap().into_inner();
            assert!((n - want).norm() <= 1e-6, "{n:?} near the pole");
        }
        assert!(
            (glass.normal(g0 + 1e-9, theta).unwrap().into_inner() - Vector3::y()).norm() <= 1e-6
        );
        // Cones: no tangent plane at the apex.
        assert!(
            bezier(&[(1.0, 0.0), (0.0, 1.0)])
                .normal(1.0, theta)
                .is_none()
        );
        assert!(
            bezier(&[(0.0, 0.0), (1.0, 1.0)])
                .normal(0.0, theta)
                .is_none()
        );
        assert!(
            bezier(&[(0.0, 0.0), (0.0, 0.0), (1.0, 1.0)])
                .normal(0.0, theta)
                .is_none()
        );
        assert!(
            bezier(&[(0.0, 0.0), (1.0, 1e-6)])
                .normal(0.0, theta)
                .is_none()
        );
        // Slope 1e-9 counts as meeting the axis perpendicularly: a normal
        // (the tangent's, 1e-9 from the axis).
        let n = bezier(&[(0.0, 0.0), (1.0, 1e-9)])
            .normal(0.0, theta)
            .expect("a disk");
        assert!((n.into_inner() - Vector3::y()).norm() <= 2e-9);
    }
    // Placed: the pole normal turns with the axis.
    let mut rng = Rng(3);
    for _ in 0..20 {
        let (origin, axis) = random_axis(&mut rng);
        let placed = bezier(&CAPSULE).with_axis(origin, axis);
        is(placed.normal(0.0, 1.0), axis.into_inner());
        is(placed.normal(1.0, 1.0), -axis.into_inner());
        assert!((placed.eval(0.0, 2.0) - origin).norm() <= 1e-14 * (1.0 + origin.coords.norm()));
        assert!(
            bezier(&[(1.0, 0.0), (0.0, 1.0)])
                .with_axis(origin, axis)
                .normal(1.0, 0.0)
                .is_none()
        );
    }
}

/// The orientation rule documented on `Revolution`: the normal is
/// `sign(x)·(−y′ cos θ, x′, y′ sin θ)`, so a profile traced upward has normals
/// toward the axis (with positive or negative `x`), traced downward away
/// from it, and a closed profile traced out along the bottom, up and back in
/// along the top has inward normals everywhere.
#[test]
fn orientation_rule() {
    let mut rng = Rng(4);
    let up = bezier(&[(1.0, 0.0), (1.3, 1.0), (0.8, 2.0)]);
    let up_neg = bezier(&[(-1.0, 0.0), (-1.3, 1.0), (-0.8, 2.0)]);
    let down = bezier(&[(0.8, 2.0), (1.3, 1.0), (1.0, 0.0)]);
    let capsule = bezier(&CAPSULE);
    for _ in 0..500 {
        let u = rng.range(0.0, 1.0);
        let theta = rng.range(0.0, TAU);
        for (s, sign) in [(&up, -1.0), (&up_neg, -1.0), (&down, 1.0)] {
            let p = s.eval(u, theta);
            let radial = Vector3::new(p.x, 0.0, p.z).normalize();
            let n = s.normal(u, theta).unwrap().into_inner();
            assert!(sign * n.dot(&radial) > 0.0, "{n:?} at {p:?}");
            // The formula itself.
            let (x, d) = s.profile().eval_with_derivative(u);
            let t = d.normalize();
            let want = Vector3::new(-t.y * theta.cos(), t.x, t.y * theta.sin()) * x.x.signum();
            assert!((n - want).norm() <= 1e-12);
        }
        // Mirrored profiles: the same surface with the same normals (θ + π).
        let a = up.normal(u, theta).unwrap().into_inner();
        let b = up_neg.normal(u, theta + PI).unwrap().into_inner();
        assert!((a - b).norm() <= 1e-12);
        assert!((up.eval(u, theta) - up_neg.eval(u, theta + PI)).norm() <= 1e-14);
        // Inward on the closed capsule (convex, center (0, 0.5, 0)).
        if u > 0.0 && u < 1.0 {
            let p = capsule.eval(u, theta);
            let n = capsule.normal(u, theta).unwrap().into_inner();
            assert!(
                n.dot(&(p - Point3::new(0.0, 0.5, 0.0))) < 0.0,
                "{n:?} at {p:?}"
            );
        }
    }
}

/// The domain is the profile's domain times `[0, 2π]`, and `θ` turns as
/// documented: `S(u, θ) = (x cos θ, y, −x sin θ)`.
#[test]
fn domain_and_parametrization() {
    let glass = uniform_cubic(&GLASS);
    let profile = glass.profile();
    assert_eq!(glass.domain(), [profile.domain(), (0.0, TAU)]);
    let mut rng = Rng(5);
    for _ in 0..200 {
        let u = rng.range(profile.domain().0, profile.domain().1);
        let theta = rng.range(0.0, TAU);
        let p = profile.eval(u);
        let want = Point3::new(p.x * theta.cos(), p.y, -p.x * theta.sin());
        assert!((glass.eval(u, theta) - want).norm() <= 4.0 * EPS);
    }
}

// ---------------------------------------------------------------------------
// Placement and bounds
// ---------------------------------------------------------------------------

/// `with_axis`: the placed surface's points are at distance `|x(u)|` from the
/// axis line at height `y(u)` along it; its hits on world rays are those of
/// the unplaced surface on the ray transformed by hand into a frame of the
/// axis (same `t`, `u`, mapped points and normals); the axis `−y` is the half
/// turn about `x`.
#[test]
fn with_axis_placement_matches_transforming_the_ray() {
    let mut rng = Rng(6);
    for (name, profile) in profiles(&mut rng) {
        let local = Revolution::new(profile.clone());
        let scale = profile_scale(&profile);
        for _ in 0..4 {
            let (origin, axis) = random_axis(&mut rng);
            let placed = Revolution::new(profile.clone()).with_axis(origin, axis);
            let f = frame(&axis);
            let (u0, u1) = profile.domain();
            let world_scale = scale + origin.coords.amax();
            for _ in 0..50 {
                let u = rng.range(u0, u1);
                let theta = rng.range(0.0, TAU);
                let p = to_local(&f, &origin, &placed.eval(u, theta));
                let q = profile.eval(u);
                assert!(
                    (p.y - q.y).abs() <= 1e-14 * world_scale,
                    "{name}: height {} vs {} (axis {axis:?})",
                    p.y,
                    q.y
                );
                assert!(
                    (p.x.hypot(p.z) - q.x.abs()).abs() <= 1e-14 * world_scale,
                    "{name}: radius {} vs {} (axis {axis:?})",
                    p.x.hypot(p.z),
                    q.x.abs()
                );
            }
            let mut hits = 0;
            for _ in 0..60 {
                let lr = random_ray(
                    &mut rng,
                    Point3::new(0.0, 0.5, 0.0),
                    Vector3::new(1.0, 1.0, 1.0),
                    scale,
                );
                let wr = Ray::new(
                    origin + vec_to_world(&f, &lr.origin.coords),
                    vec_to_world(&f, &lr.dir),
                );
                // Recover the local ray from the world ray by hand, so both
                // intersections see the same rounded input.
                let lr = Ray::new(to_local(&f, &origin, &wr.origin), vec_to_local(&f, &wr.dir));
                match (
                    local.intersect(&lr, 0.0, INF),
                    placed.intersect(&wr, 0.0, INF),
                ) {
                    (None, None) => {}
                    (Some(a), Some(b)) => {
                        check_hit(&placed, &wr, &b, 0.0, INF, world_scale);
                        let k = kappa(&lr.dir, &a.normal.into_inner());
                        let tol = t_tolerance(world_scale, k, &lr.dir);
                        assert!((a.t - b.t).abs() <= 2.0 * tol, "{name}: {a:?} vs {b:?}");
                        assert!((a.uv.0 - b.uv.0).abs() <= 1e-9 * (u1 - u0) * k, "{name}");
                        let pa = origin + vec_to_world(&f, &a.point.coords);
                        assert!((pa - b.point).norm() <= 4.0 * REL * world_scale * k);
                        let na = vec_to_world(&f, &a.normal.into_inner());
                        assert!((na - b.normal.into_inner()).norm() <= 1e-9 * k, "{name}");
                        hits += 1;
                    }
                    (a, b) => {
                        // Only a grazing ray may tip over between frames.
                        let h = a.or(b).unwrap();
                        let k = kappa(&lr.dir, &h.normal.into_inner());
                        assert!(k > 1e4, "{name}: local {a:?} vs placed {b:?}");
                    }
                }
            }
            assert!(hits > 5, "{name}: only {hits} hits");
        }
    }
    // The half turn about x for the axis −y: (x, y, z) ↦ (x, −y, −z).
    let capsule = bezier(&CAPSULE);
    let flipped = bezier(&CAPSULE).with_axis(Point3::origin(), -Vector3::y_axis());
    for &(u, theta) in &[(0.3, 0.7), (0.8, 2.0), (0.5, 5.0)] {
        let p = capsule.eval(u, theta);
        let q = flipped.eval(u, theta);
        assert!((q - Point3::new(p.x, -p.y, -p.z)).norm() <= 1e-15);
    }
}

/// `with_axis` for axes close to `±y` (within 1e-9 … 1e-7 rad): the local
/// `y` axis must map onto the requested axis (the capsule's pole normals and
/// top pole lie on it), and surface points must sit at height `y(u)` along it,
/// to rounding.
#[test]
fn with_axis_nearly_along_y() {
    for a in [
        Vector3::new(1e-9, 1.0, 0.0),
        Vector3::new(1e-9, -1.0, 2e-9),
        Vector3::new(1e-7, 1.0, 0.0),
        Vector3::new(3e-8, -1.0, -1e-8),
    ] {
        let axis = Unit::new_normalize(a);
        let s = bezier(&CAPSULE).with_axis(Point3::origin(), axis);
        let n = s.normal(0.0, 0.3).unwrap().into_inner();
        assert!(
            (n - axis.into_inner()).norm() <= 1e-14,
            "pole normal {n:?} vs axis {axis:?}"
        );
        let top = s.eval(1.0, 0.0);
        assert!(
            (top.coords - axis.into_inner()).norm() <= 1e-14,
            "top pole {top:?} vs {axis:?}"
        );
        for &(u, theta) in &[(0.3, 0.5), (0.5, 2.0), (0.9, 4.0)] {
            let p = s.eval(u, theta).coords;
            let q = s.profile().eval(u);
            let h = p.dot(&axis);
            assert!((h - q.y).abs() <= 1e-14, "height {h} vs {}", q.y);
            assert!(((p - axis.into_inner() * h).norm() - q.x).abs() <= 1e-14);
        }
    }
}

/// `bounds()` contains the surface: a grid of surface points, for local and
/// placed surfaces, and every hit point.
#[test]
fn bounds_contain_the_surface() {
    let mut rng = Rng(7);
    for (name, profile) in profiles(&mut rng) {
        let (origin, axis) = random_axis(&mut rng);
        let scale = profile_scale(&profile) + origin.coords.amax();
        for s in [
            Revolution::new(profile.clone()),
            Revolution::new(profile.clone()).with_axis(origin, axis),
        ] {
            let b: Aabb = s.bounds();
            assert!(!b.is_empty(), "{name}");
            // Rounding of the placement: a few ulps of the scale.
            let b = b.expand(8.0 * EPS * scale);
            let (u0, u1) = profile.domain();
            for i in 0..=200 {
                let u = u0 + (u1 - u0) * f64::from(i) / 200.0;
                for j in 0..64 {
                    let p = s.eval(u, TAU * f64::from(j) / 64.0);
                    assert!(b.contains(&p), "{name}: {p:?} outside {b:?}");
                }
            }
            for _ in 0..50 {
                let r = random_ray(&mut rng, b.center(), b.extent() * 0.5, b.extent().norm());
                if let Some(h) = s.intersect(&r, 0.0, INF) {
                    assert!(b.contains(&h.point), "{name}: hit {h:?} outside {b:?}");
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Intersections
// ---------------------------------------------------------------------------

/// Random ray/profile pairs (proptest picks the seeds; a failure shrinks to a
/// small seed pair): every hit lies on its ray and on the surface, inside
/// `(t_min, t_max)`, with a unit normal; the chain of hits obtained by moving
/// `t_min` up is increasing; `t_max` cuts off exactly the hits beyond it.
#[test]
fn every_hit_lies_on_its_ray_and_the_surface() {
    let config = ProptestConfig {
        cases: 300,
        failure_persistence: None,
        ..ProptestConfig::default()
    };
    proptest!(config, |(profile_seed in 0u64..1_000_000, ray_seed in 0u64..1_000_000)| {
        let mut prng = Rng(profile_seed);
        let profile = random_monotone_profile(&mut prng);
        let (origin, axis) = random_axis(&mut prng);
        let s = Revolution::new(profile.clone()).with_axis(origin, axis);
        let scale = profile_scale(&profile) + origin.coords.amax();
        let b = s.bounds();
        let mut rng = Rng(ray_seed);
        for _ in 0..8 {
            let r = random_ray(&mut rng, b.center(), b.extent() * 0.5, b.extent().norm());
            let mut t_min = if rng.below(3) == 0 { rng.range(0.0, 1.0) } else { 0.0 };
            let mut chain = Vec::new();
            while let Some(h) = s.intersect(&r, t_min, INF) {
                check_hit(&s, &r, &h, t_min, INF, scale);
                prop_assert!(h.t > t_min);
                chain.push(h.t);
                t_min = h.t;
                prop_assert!(chain.len() < 64, "endless chain {chain:?}");
            }
            // t_max just after a hit keeps it; just before drops it.
            if let Some(&t) = chain.first() {
                let dt = 1e-6 * t.abs().max(1e-6);
                prop_assert!(s.intersect(&r, 0.0, t + dt).is_some());
                let before = s.intersect(&r, 0.0, t - dt);
                prop_assert!(before.is_none() || before.unwrap().t < t - dt);
            }
        }
    });
}

/// A y-monotone profile's brute-force crossings: march along the ray in
/// small steps evaluating `g(p) = dist(p, axis) − |x(u*(p_y))|` (`u*` by
/// bisection on the monotone height, evaluated with `Curve::eval`), bracket
/// its sign changes and bisect them to the last bit.
struct March<'a> {
    profile: &'a BSpline<2>,
    y_range: (f64, f64),
    scale: f64,
}

impl March<'_> {
    fn new(profile: &BSpline<2>) -> March<'_> {
        let (u0, u1) = profile.domain();
        March {
            profile,
            y_range: (profile.eval(u0).y, profile.eval(u1).y),
            scale: profile_scale(profile),
        }
    }

    /// `u*` with `y(u*) = y` (clamped to the domain): Newton's method kept
    /// inside a bisection bracket, to adjacent doubles or a zero residual.
    fn invert(&self, y: f64) -> f64 {
        let (mut lo, mut hi) = self.profile.domain();
        if y <= self.y_range.0 {
            return lo;
        }
        if y >= self.y_range.1 {
            return hi;
        }
        let mut u = lo + (hi - lo) * (y - self.y_range.0) / (self.y_range.1 - self.y_range.0);
        for _ in 0..200 {
            let (p, d) = self.profile.eval_with_derivative(u);
            let f = p.y - y;
            if f == 0.0 {
                return u;
            }
            if f < 0.0 {
                lo = u;
            } else {
                hi = u;
            }
            let newton = u - f / d.y;
            let next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if next == u || next <= lo || next >= hi {
                break;
            }
            u = next;
        }
        u
    }

    fn g(&self, r: &Ray, t: f64) -> f64 {
        let p = r.at(t);
        p.x.hypot(p.z) - self.profile.eval(self.invert(p.y)).x.abs()
    }

    /// The bisected sign changes in `(t0, t1)` (only where the ray is within
    /// the profile's height range), with `steps` grid intervals per unit of
    /// `scale` along the ray.
    fn crossings(&self, r: &Ray, t0: f64, t1: f64, steps: f64) -> Vec<f64> {
        let (o, d) = (r.origin, r.dir);
        let (mut lo, mut hi) = (t0, t1);
        if d.y == 0.0 {
            if o.y < self.y_range.0 || o.y > self.y_range.1 {
                return vec![];
            }
        } else {
            let (a, b) = ((self.y_range.0 - o.y) / d.y, (self.y_range.1 - o.y) / d.y);
            lo = lo.max(a.min(b));
            hi = hi.min(a.max(b));
        }
        if lo >= hi {
            return vec![];
        }
        let n = ((hi - lo) * d.norm() / self.scale * steps).ceil().max(8.0) as usize;
        let at = |i: usize| lo + (hi - lo) * i as f64 / n as f64;
        let mut out = Vec::new();
        let mut prev = self.g(r, at(0));
        for i in 1..=n {
            let next = self.g(r, at(i));
            if (prev > 0.0) != (next > 0.0) {
                let (mut a, mut b) = (at(i - 1), at(i));
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break;
                    }
                    if (self.g(r, m) > 0.0) == (prev > 0.0) {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                out.push(0.5 * (a + b));
            }
            prev = next;
        }
        out
    }

    /// The unit normal direction at a crossing (up to sign).
    fn normal(&self, r: &Ray, t: f64) -> Vector3<f64> {
        let p = r.at(t);
        let u = self.invert(p.y);
        let d = self.profile.derivative(u);
        let rho = p.x.hypot(p.z).max(f64::MIN_POSITIVE);
        Vector3::new(-d.y * p.x / rho, d.x, -d.y * p.z / rho).normalize()
    }
}

/// Random rays on random y-monotone profiles (B-splines of degree 1–5, some
/// with negative `x`, some crossing the axis) against the brute-force march:
/// the library never misses a bracketed (transversal) crossing, its nearest
/// hit is the nearest bracket, and the chain of hits is the list of brackets.
/// A library hit without a bracket must be a crossing pair the march stepped
/// over (found by re-marching densely around it) — else it is a false hit.
#[test]
fn random_rays_against_brute_force_march() {
    /// Grid intervals per `scale` of length along the ray: two crossings
    /// closer than this (a near-tangent ray) are caught by the dense
    /// re-march instead.
    const STEPS: f64 = 1000.0;
    let mut rng = Rng(8);
    let (mut rays, mut crossings, mut refined) = (0, 0, 0);
    for _ in 0..60 {
        let profile = random_monotone_profile(&mut rng);
        let s = Revolution::new(profile.clone());
        let march = March::new(&profile);
        let scale = march.scale;
        let (ylo, yhi) = march.y_range;
        let center = Point3::new(0.0, 0.5 * (ylo + yhi), 0.0);
        let r_max = s.bounds().max.x;
        let half = Vector3::new(r_max, 0.5 * (yhi - ylo), r_max);
        for _ in 0..25 {
            let r = match rng.below(4) {
                // Perpendicular to the axis.
                0 => {
                    let phi = rng.range(0.0, TAU);
                    let o = Point3::new(
                        3.0 * r_max * phi.cos(),
                        rng.range(ylo, yhi),
                        3.0 * r_max * phi.sin(),
                    );
                    let target = Point3::new(
                        rng.range(-0.5, 0.5) * r_max,
                        o.y,
                        rng.range(-0.5, 0.5) * r_max,
                    );
                    Ray::new(o, target - o)
                }
                // Parallel to the axis.
                1 => {
                    let o = Point3::new(
                        rng.range(-r_max, r_max),
                        yhi + 1.0,
                        rng.range(-r_max, r_max),
                    );
                    Ray::new(o, Vector3::new(0.0, -rng.range(0.5, 2.0), 0.0))
                }
                _ => random_ray(&mut rng, center, half, scale),
            };
            let t_end = 10.0 * scale / r.dir.norm();
            let brackets = march.crossings(&r, 0.0, t_end, STEPS);
            rays += 1;
            let mut t_min = 0.0;
            let mut i = 0;
            while let Some(h) = s.intersect(&r, t_min, t_end) {
                check_hit(&s, &r, &h, t_min, t_end, scale);
                match brackets.get(i) {
                    Some(&t)
                        if (h.t - t).abs()
                            <= t_tolerance(scale, kappa(&r.dir, &march.normal(&r, t)), &r.dir) =>
                    {
                        i += 1;
                        crossings += 1;
                    }
                    next => {
                        // Before the next bracket (or after all): it must be a
                        // pair of crossings the march stepped over.
                        if let Some(&t) = next {
                            assert!(
                                h.t < t,
                                "missed the crossing at t = {t} (next hit {h:?}) of {r:?}; \
                                 brackets {brackets:?}"
                            );
                        }
                        let dt = 2.0 * scale / STEPS / r.dir.norm();
                        let local = march.crossings(&r, h.t - dt, h.t + dt, 4e6);
                        assert!(
                            local
                                .iter()
                                .any(|&t| (t - h.t).abs() <= 1e-9 * scale / r.dir.norm()),
                            "false hit {h:?} on {r:?}: brackets {brackets:?}, dense {local:?}"
                        );
                        refined += 1;
                    }
                }
                t_min = h.t;
            }
            assert_eq!(
                i,
                brackets.len(),
                "missed crossings {:?} of {r:?}",
                &brackets[i..]
            );
        }
    }
    eprintln!("{rays} rays, {crossings} bracketed crossings matched, {refined} re-marched");
    assert!(
        crossings > 1000,
        "only {crossings} crossings in {rays} rays"
    );
    assert!(
        refined <= rays / 20,
        "{refined} hits needed dense re-marching"
    );
}

/// A looser tolerance is an explicit setting: with `Tolerance::relative(1e-6)`
/// hits are still on the surface and the ray to `1e-6·scale`, and agree with
/// the default's to that accuracy.
#[test]
fn tolerance_setting_is_honoured() {
    let mut rng = Rng(9);
    let profile = BSpline::uniform(3, points(&GLASS)).unwrap();
    let exact = Revolution::new(profile.clone());
    let loose = Revolution::new(profile).with_tolerance(Tolerance::relative(1e-6));
    assert_eq!(loose.tolerance().relative, 1e-6);
    assert_eq!(exact.tolerance(), &Tolerance::default());
    for _ in 0..300 {
        let r = random_ray(&mut rng, Point3::origin(), Vector3::new(0.8, 1.1, 0.8), 1.0);
        match (exact.intersect(&r, 0.0, INF), loose.intersect(&r, 0.0, INF)) {
            (Some(a), Some(b)) => {
                let k = kappa(&r.dir, &a.normal.into_inner());
                assert!((r.at(b.t) - b.point).norm() <= 1e-6 * 1.06);
                assert!((loose.eval(b.uv.0, b.uv.1) - b.point).norm() <= 1e-6 * 1.06);
                assert!((a.t - b.t).abs() * r.dir.norm() <= 1e-6 * 1.06 * k);
            }
            (None, None) => {}
            (a, b) => {
                let h = a.or(b).unwrap();
                assert!(
                    kappa(&r.dir, &h.normal.into_inner()) > 100.0,
                    "{a:?} vs {b:?}"
                );
            }
        }
    }
}

/// `intersect_with_report` returns the same hit as the fast path and a
/// report that says how it was found: a hit comes from at least one solved
/// span, root and polished candidate with a small residual; a ray that
/// misses the bounds enters no span.
#[test]
fn exact_report_describes_the_search() {
    let glass = uniform_cubic(&GLASS);
    let mut rng = Rng(17);
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..300 {
        let r = random_ray(&mut rng, Point3::origin(), Vector3::new(0.8, 1.1, 0.8), 1.0);
        let fast = glass.intersect(&r, 0.0, INF);
        let (hit, report) = glass.intersect_with_report(&r, 0.0, INF);
        assert_eq!(fast, hit);
        match hit {
            Some(_) => {
                hits += 1;
                assert!(
                    report.spans_entered >= 1 && report.spans_solved >= 1,
                    "{report:?}"
                );
                assert!(report.roots >= 1 && report.candidates >= 1, "{report:?}");
                let residual = report.residual.expect("a hit has a residual");
                assert!(residual <= REL * 1.06, "{report:?}");
                assert!(report.spans_solved <= report.spans_entered);
            }
            None => {
                misses += 1;
                assert_eq!(report.residual, None);
            }
        }
    }
    assert!(hits > 50 && misses > 20, "{hits} hits, {misses} misses");
    let away = Ray::new(Point3::new(5.0, 0.0, 5.0), Vector3::new(1.0, 0.0, 0.0));
    let (hit, report) = glass.intersect_with_report(&away, 0.0, INF);
    assert_eq!(hit, None);
    assert_eq!(report.spans_entered, 0);
    assert_eq!(report.spans_solved, 0);
}

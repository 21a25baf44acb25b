//! Rational revolutions: surfaces of revolution whose profile is a rational
//! curve. A sphere (a half circle of two quarter arcs about the axis) and a
//! torus (a full circle of four quarter arcs off the axis), against their
//! closed forms, through every hard case of DESIGN.md §5; the generic Newton
//! intersector, tessellation and the partials on the same surfaces.
//!
//! # References
//! The ray–sphere quadratic `|o + t·d|² = R²` and the ray–torus quartic
//! `(|p|² + R² − r²)² = 4R²(p_x² + p_z²)` with exact rational coefficients
//! (every `f64` input read as the rational it is), their real roots isolated
//! by Sturm sequences and bisected in exact arithmetic to the correctly
//! rounded `f64` (`common::closed_forms`, `common::exact_roots`). Nothing of
//! the library's intersection is used; [`reference_roots_are_exact`] checks
//! the reference itself against the stable quadratic formula and simple
//! closed forms.
//!
//! # Tolerances
//! The profiles' quarter arcs have the weight `√2/2` rounded to `f64`, so the
//! surfaces are the exact sphere and torus to about `1e-16` of their size.
//! A hit must be at the reference's `t` to `1e-9` of the object's size (in
//! `t·|d|`), its point at the reference point to the same, and its normal the
//! closed form's (the radial direction, into the solid: the profiles run
//! counter-clockwise) to `1e-9`; besides, every hit passes
//! `common::check_hit` (on the ray and on `S(uv)` to `1e-12` of the size,
//! normal equal to `Surface::normal` and perpendicular to the partials).
//! Every hit along a ray is compared, one for one with the reference's
//! roots, by continuing from each hit as a secondary ray would.

use revolve_testkit as common;

use common::closed_forms::ClosedForm;
use common::conic_profiles::{sphere_profile, torus_profile};
use common::exact_roots::{RealRoots, common_integers};
use common::{Rng, check_hit, kappa};
use num_bigint::BigInt;
use revolve::nalgebra::{Point3, Vector3};
use revolve::{Curve, Hit, Intersect, NewtonIntersector, Nurbs, Ray, Revolution, Surface};
use std::f64::consts::TAU;

const INF: f64 = f64::INFINITY;

/// Allowed error of a hit's `t·|d|` and point, relative to the object's
/// size, and of its unit normal.
const TOL: f64 = 1e-9;

/// The profile type of the rational revolutions under test.
type Profile = Nurbs<2>;

/// The sphere's radius and the torus's radii in the unscaled tests (exact in
/// binary, so scaled copies stay exact).
const RADIUS: f64 = 1.25;
const MAJOR: f64 = 1.0;
const MINOR: f64 = 0.375;

/// The revolution of `profile`, which must get the exact intersector.
fn exact_revolution(profile: Profile) -> Revolution<Profile> {
    let surface = Revolution::new(profile);
    assert!(surface.has_exact_intersector(), "no exact intersector");
    surface
}

/// A surface under test and its closed form.
struct Shape {
    kind: ClosedForm,
    surface: Revolution<Profile>,
}

impl Shape {
    fn sphere(radius: f64) -> Self {
        Shape {
            kind: ClosedForm::Sphere { radius },
            surface: exact_revolution(sphere_profile(radius)),
        }
    }

    fn torus(major: f64, minor: f64) -> Self {
        Shape {
            kind: ClosedForm::Torus { major, minor },
            surface: exact_revolution(torus_profile(major, minor)),
        }
    }

    /// The object's size: its largest absolute coordinate.
    fn scale(&self) -> f64 {
        self.kind.scale()
    }

    /// The reference's roots along `ray`.
    fn roots(&self, ray: &Ray) -> RealRoots {
        self.kind
            .roots(ray)
            .expect("a finite ray with a non-zero direction")
    }

    /// The closed form's outward unit normal at (or nearest to) `p`.
    fn outward(&self, p: &Point3<f64>) -> Vector3<f64> {
        self.kind.outward(p)
    }
}

/// Asserts that `hit` is the reference's root `t_ref` of `ray`: `t`, point
/// and normal within [`TOL`], and `check_hit`'s facts in its window.
fn check_against(shape: &Shape, ray: &Ray, hit: &Hit, window: (f64, f64), t_ref: f64) {
    let scale = shape.scale();
    check_hit(&shape.surface, ray, hit, window.0, window.1, scale);
    let dn = ray.dir.norm();
    let p_ref = ray.at(t_ref);
    assert!(
        (hit.t - t_ref).abs() * dn <= TOL * scale,
        "t = {} but the reference has {t_ref} (error {:e}) for {ray:?}",
        hit.t,
        (hit.t - t_ref).abs() * dn / scale
    );
    assert!(
        (hit.point - p_ref).norm() <= TOL * scale,
        "point {:?} but the reference has {p_ref:?} for {ray:?}",
        hit.point
    );
    let n_ref = -shape.outward(&p_ref);
    assert!(
        (hit.normal.into_inner() - n_ref).norm() <= TOL,
        "normal {:?} but the closed form has {n_ref:?} at {p_ref:?}",
        hit.normal
    );
}

/// Asserts that the surface's hits along `ray` in `(t_min, t_max)` are the
/// reference's roots there, one for one, found nearest first by continuing
/// from each hit as a secondary ray does (the next `t_min` is the hit's
/// `t`); returns them.
///
/// A root so ill-conditioned (a near-tangent crossing, `κ = |d|/|d·n| >
/// 1e3`) that its hit may land a little before it can be found again from
/// there: such repeats (within [`TOL`] of the same root, at most 4) are
/// passed over. Found again from a transversal root, it is a self-hit and
/// fails.
fn check_ray(shape: &Shape, ray: &Ray, t_min: f64, t_max: f64) -> Vec<Hit> {
    let want = shape.roots(ray).all_in(t_min, t_max);
    let scale = shape.scale();
    let dn = ray.dir.norm();
    let mut got: Vec<Hit> = Vec::new();
    let mut from = t_min;
    let mut repeats = 0;
    while let Some(h) = shape.surface.intersect(ray, from, t_max) {
        if let Some(k) = got.len().checked_sub(1) {
            let off = |t: f64| (h.t - t).abs();
            let same = off(want[k]) * dn <= TOL * scale
                && want.get(k + 1).is_none_or(|&next| off(want[k]) < off(next));
            if same {
                let kappa = kappa(&ray.dir, &shape.outward(&ray.at(want[k])));
                assert!(
                    kappa > 1e3 && repeats < 4,
                    "the root at {} found again at {} from {from} (κ = {kappa:.1e}) for {ray:?}",
                    want[k],
                    h.t
                );
                repeats += 1;
                from = h.t;
                continue;
            }
        }
        let Some(&t_ref) = want.get(got.len()) else {
            panic!(
                "a hit at {} beyond the reference's roots {want:?} for {ray:?}",
                h.t
            );
        };
        check_against(shape, ray, &h, (from, t_max), t_ref);
        got.push(h);
        from = h.t;
    }
    assert_eq!(
        got.len(),
        want.len(),
        "hits at t = {:?}, the reference has {want:?}, for {ray:?} in ({t_min}, {t_max})",
        got.iter().map(|h| h.t).collect::<Vec<_>>()
    );
    // `intersect_all` walks the same way and passes over the same repeats
    // by itself; `occluded` says whether there is a hit.
    let mut all = Vec::new();
    shape.surface.intersect_all(ray, t_min, t_max, &mut all);
    assert_eq!(all, got, "intersect_all for {ray:?} in ({t_min}, {t_max})");
    assert_eq!(shape.surface.occluded(ray, t_min, t_max), !got.is_empty());
    got
}

/// As [`check_ray`], and asserts how many hits there are.
fn expect_hits(shape: &Shape, ray: &Ray, count: usize) -> Vec<Hit> {
    let hits = check_ray(shape, ray, 0.0, INF);
    assert_eq!(hits.len(), count, "{ray:?}");
    hits
}

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(Point3::from(o), Vector3::from(d))
}

/// A random ray from a sphere of radius `4·size` about the origin through a
/// random point of the box `[−1.1·size, 1.1·size] × [−h, h] ×
/// [−1.1·size, 1.1·size]`, its direction of random length in `[0.5, 2)`
/// times the distance (`t` is in units of `|d|`).
fn random_ray(rng: &mut Rng, size: f64, h: f64) -> Ray {
    let origin = Point3::from(rng.direction() * 4.0 * size);
    let w = 1.1 * size;
    let target = rng.point([-w, -h, -w], [w, h, w]);
    Ray::new(origin, (target - origin) * rng.range(0.5, 2.0))
}

/// A unit vector perpendicular to `d`.
fn perpendicular(rng: &mut Rng, d: &Vector3<f64>) -> Vector3<f64> {
    loop {
        let v = d.cross(&rng.direction());
        if v.norm() > 0.1 {
            return v.normalize();
        }
    }
}

/// The line along unit `d` at distance `rho` from the origin, in the
/// direction `e ⊥ d`, starting `back` before its closest point.
fn line_at(d: Vector3<f64>, e: Vector3<f64>, rho: f64, back: f64) -> Ray {
    Ray::new(Point3::from(e * rho - d * back), d)
}

fn sphere() -> Shape {
    Shape::sphere(RADIUS)
}

fn torus() -> Shape {
    Shape::torus(MAJOR, MINOR)
}

// ---------------------------------------------------------------------------
// The reference
// ---------------------------------------------------------------------------

/// The exact roots against independent answers: the stable quadratic
/// formula for the sphere (transversal rays, where it is accurate to a few
/// ulps), and closed forms of the torus for axis-aligned rays.
#[test]
fn reference_roots_are_exact() {
    let z = |v: i64| BigInt::from(v);
    // (t − 1)(t − 3)(t + 2) and t² − 2, exactly; a double root found once.
    let cubic = RealRoots::new(&[z(6), z(-5), z(-2), z(1)]).unwrap();
    assert_eq!(cubic.all_in(-INF, INF), [-2.0, 1.0, 3.0]);
    assert_eq!(cubic.first_in(1.0, 10.0), Some(3.0));
    assert_eq!(cubic.first_in(-2.0, 1.0), None);
    assert_eq!(cubic.count(-2.0, 1.0), 1);
    let two = RealRoots::new(&[z(-2), z(0), z(1)]).unwrap();
    assert_eq!(two.all_in(-5.0, 5.0), [-(2f64.sqrt()), 2f64.sqrt()]);
    // (2ᵏt − m)² with m/2ᵏ = 0.1 as the f64 it is.
    let [m, one] = <[BigInt; 2]>::try_from(common_integers(&[0.1, 1.0]).unwrap()).unwrap();
    let double = RealRoots::new(&[&m * &m, -(&m * &one * z(2)), &one * &one]).unwrap();
    assert_eq!(double.all_in(0.0, 1.0), [0.1]);
    assert!(RealRoots::new(&[z(0)]).is_none());
    assert!(
        RealRoots::new(&[z(3)])
            .unwrap()
            .all_in(-INF, INF)
            .is_empty()
    );

    let mut rng = Rng(0x5EF);
    let mut compared = 0;
    for _ in 0..2000 {
        let r = random_ray(&mut rng, RADIUS, 1.1 * RADIUS);
        let (o, d) = (r.origin.coords, r.dir);
        let (qa, qb, qc) = (d.dot(&d), o.dot(&d), o.dot(&o) - RADIUS * RADIUS);
        let disc = qb * qb - qa * qc;
        let roots = sphere().roots(&r).all_in(-INF, INF);
        if disc < 1e-3 * qb * qb {
            continue; // near tangent: the formula loses digits
        }
        let qq = -(qb + qb.signum() * disc.sqrt());
        let (t0, t1) = (qq / qa, qc / qq);
        let want = [t0.min(t1), t0.max(t1)];
        assert_eq!(roots.len(), 2, "{r:?}");
        for (got, want) in roots.iter().zip(want) {
            assert!((got - want).abs() <= 1e-14 * want.abs(), "{got} vs {want}");
        }
        compared += 1;
    }
    assert!(compared > 500, "{compared}");

    // The torus crossed through its axis in the plane y = 0: the radii
    // R ± r on both sides, exactly.
    let through = ray([-3.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let (big, small) = (MAJOR, MINOR);
    let t = torus();
    let want = [
        3.0 - big - small,
        3.0 - big + small,
        3.0 + big - small,
        3.0 + big + small,
    ];
    assert_eq!(t.roots(&through).all_in(0.0, INF), want);
    // Parallel to the axis at ρ = R + r/2: y = ±r·√3/2.
    let rho = big + 0.5 * small;
    let up = ray([rho, -2.0, 0.0], [0.0, 1.0, 0.0]);
    let roots = t.roots(&up).all_in(0.0, INF);
    let y = small * 3f64.sqrt() / 2.0;
    assert_eq!(roots.len(), 2);
    assert!((roots[0] - (2.0 - y)).abs() < 1e-15 && (roots[1] - (2.0 + y)).abs() < 1e-15);
    // Through the hole along the axis, and beyond the tube: none.
    let axis = ray([0.0, -2.0, 0.0], [0.0, 1.0, 0.0]);
    assert!(t.roots(&axis).all_in(-INF, INF).is_empty());
    let beyond = ray([-3.0, 0.0, big + small + 1e-9], [1.0, 0.0, 0.0]);
    assert!(t.roots(&beyond).all_in(-INF, INF).is_empty());
}

// ---------------------------------------------------------------------------
// Closed forms on random rays
// ---------------------------------------------------------------------------

/// Thousands of random rays at the sphere: every hit (entry and exit) at the
/// quadratic's roots, with the radial normal; misses where it has none.
#[test]
fn random_rays_match_the_sphere_quadratic() {
    let s = sphere();
    let mut rng = Rng(0xA11);
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..4000 {
        let r = random_ray(&mut rng, RADIUS, 1.1 * RADIUS);
        match check_ray(&s, &r, 0.0, INF).len() {
            0 => misses += 1,
            _ => hits += 1,
        }
    }
    assert!(hits > 1500 && misses > 300, "{hits} hits, {misses} misses");
}

/// Lines passing beyond the radius (by `1e-6` of it up to twice it) miss,
/// in any direction, from either side.
#[test]
fn lines_beyond_the_sphere_radius_miss() {
    let s = sphere();
    let mut rng = Rng(0xB0B);
    for i in 0..1000 {
        let d = rng.direction();
        let e = perpendicular(&mut rng, &d);
        let rho = RADIUS
            * if i % 4 == 0 {
                1.0 + 1e-6
            } else {
                rng.range(1.0 + 1e-6, 2.0)
            };
        let r = line_at(d, e, rho, 5.0 * RADIUS);
        assert!(s.roots(&r).all_in(-INF, INF).is_empty(), "{r:?}");
        assert_eq!(s.surface.intersect(&r, 0.0, INF), None, "{r:?}");
        assert_eq!(s.surface.intersect(&r, -INF, INF), None, "{r:?}");
    }
}

/// Random rays at the torus: every hit (up to four) at the quartic's roots,
/// with the normal of the tube; misses through the hole and beyond.
#[test]
fn random_rays_match_the_torus_quartic() {
    let s = torus();
    let mut rng = Rng(0x7035);
    let mut counts = [0usize; 5];
    for _ in 0..2500 {
        let r = random_ray(&mut rng, MAJOR + MINOR, 1.3 * MINOR);
        counts[check_ray(&s, &r, 0.0, INF).len()] += 1;
    }
    assert!(
        counts[0] > 200 && counts[2] > 500 && counts[4] > 50,
        "rays by number of hits: {counts:?}"
    );
}

/// Lines that cannot meet the torus: beyond its outer radius, and through
/// its hole (parallel to the axis inside the inner radius; through the
/// centre at angles whose distance `R·cos α` from the tube's centre circle
/// exceeds `r`).
#[test]
fn lines_through_the_hole_and_beyond_the_torus_miss() {
    let s = torus();
    let mut rng = Rng(0x401E);
    for _ in 0..500 {
        let d = rng.direction();
        let e = perpendicular(&mut rng, &d);
        let rho = (MAJOR + MINOR) * rng.range(1.0 + 1e-6, 2.0);
        let r = line_at(d, e, rho, 5.0);
        assert!(s.roots(&r).all_in(-INF, INF).is_empty(), "{r:?}");
        assert_eq!(s.surface.intersect(&r, -INF, INF), None, "{r:?}");
    }
    for _ in 0..500 {
        let phi = rng.range(0.0, TAU);
        let rho = (MAJOR - MINOR) * rng.range(0.0, 1.0 - 1e-6);
        let r = ray([rho * phi.cos(), -3.0, rho * phi.sin()], [0.0, 1.0, 0.0]);
        assert!(s.roots(&r).all_in(-INF, INF).is_empty(), "{r:?}");
        assert_eq!(s.surface.intersect(&r, -INF, INF), None, "{r:?}");
    }
    let widest = (MINOR / MAJOR).acos();
    for _ in 0..500 {
        let alpha = widest * rng.range(0.0, 0.999);
        let phi = rng.range(0.0, TAU);
        let d = Vector3::new(
            alpha.sin() * phi.cos(),
            alpha.cos(),
            alpha.sin() * phi.sin(),
        );
        let r = Ray::new(Point3::from(-d * 3.0), d);
        assert!(s.roots(&r).all_in(-INF, INF).is_empty(), "{r:?}");
        assert_eq!(s.surface.intersect(&r, -INF, INF), None, "{r:?}");
    }
}

// ---------------------------------------------------------------------------
// Normals
// ---------------------------------------------------------------------------

/// The sphere's normal is the radial direction (into the ball) everywhere,
/// including the poles, where it is the limit `±y`: from `Surface::normal`
/// on a grid of parameters, at both ends of the profile, and in hits of
/// rays through the poles.
#[test]
fn sphere_normals_are_radial_including_the_poles() {
    let s = sphere();
    let (a, b) = s.surface.profile().domain();
    for i in 0..=64 {
        let u = a + (b - a) * i as f64 / 64.0;
        for k in 0..16 {
            let theta = TAU * k as f64 / 16.0;
            let p = s.surface.eval(u, theta);
            let n = s.surface.normal(u, theta).expect("a normal everywhere");
            let want = if i == 0 {
                Vector3::y()
            } else if i == 64 {
                -Vector3::y()
            } else {
                -p.coords.normalize()
            };
            assert!(
                (n.into_inner() - want).norm() <= TOL,
                "u {u}, θ {theta}: {n:?}"
            );
            assert!((p.coords.norm() - RADIUS).abs() <= 1e-15 * 4.0 * RADIUS);
        }
    }
    // Through the poles (and within 1e-12 of them): the hits there have the
    // limit; tilted by 1e-6, the radial normal (checked by `check_ray`).
    for tilt in [0.0, 1e-12, 1e-6] {
        let up = ray([0.0, -3.0, 0.0], [tilt, 1.0, 0.0]);
        let hits = expect_hits(&s, &up, 2);
        if tilt > 1e-9 {
            continue;
        }
        for (h, want) in hits.iter().zip([Vector3::y(), -Vector3::y()]) {
            let n = h.normal.into_inner();
            assert!(
                (n - want).norm() <= TOL,
                "pole normal {n:?} ({:e} off) at {h:?}",
                (n - want).norm()
            );
        }
    }
}

// ---------------------------------------------------------------------------
// The hard cases of DESIGN.md §5
// ---------------------------------------------------------------------------

/// Rays along the axis: through both poles of the sphere (either way, from
/// outside and from the centre); through the torus's hole (a miss).
#[test]
fn rays_along_the_axis() {
    let s = sphere();
    for (o, d, ts) in [
        (
            [0.0, -3.0, 0.0],
            [0.0, 1.0, 0.0],
            [3.0 - RADIUS, 3.0 + RADIUS],
        ),
        (
            [0.0, 3.0, 0.0],
            [0.0, -2.0, 0.0],
            [1.5 - RADIUS / 2.0, 1.5 + RADIUS / 2.0],
        ),
    ] {
        let hits = expect_hits(&s, &ray(o, d), 2);
        for (h, t) in hits.iter().zip(ts) {
            assert!((h.t - t).abs() <= TOL, "t = {} for {t}", h.t);
        }
    }
    let from_centre = ray([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let hits = expect_hits(&s, &from_centre, 1);
    assert!((hits[0].point - Point3::new(0.0, RADIUS, 0.0)).norm() <= TOL * RADIUS);
    // The far pole in a window that excludes the near one.
    let up = ray([0.0, -3.0, 0.0], [0.0, 1.0, 0.0]);
    check_ray(&s, &up, 3.0, INF);
    check_ray(&s, &up, 0.0, 3.0);

    let t = torus();
    for d in [[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]] {
        let r = ray([0.0, -3.0 * d[1], 0.0], d);
        expect_hits(&t, &r, 0);
        assert_eq!(t.surface.intersect(&r, -INF, INF), None);
    }
}

/// Rays parallel to the axis off it: the sphere at `y = ±√(R² − ρ²)`; the
/// torus through the tube (`y = ±√(r² − (ρ − R)²)`), on both sides of the
/// tube's centre circle and on it.
#[test]
fn rays_parallel_to_the_axis_off_it() {
    let s = sphere();
    let mut rng = Rng(0x9A2);
    for _ in 0..300 {
        let rho = RADIUS * rng.range(1e-9, 1.0 - 1e-6);
        let phi = rng.range(0.0, TAU);
        let dir = if rng.unit() < 0.5 { 1.0 } else { -1.0 };
        let r = ray(
            [rho * phi.cos(), -3.0 * dir, rho * phi.sin()],
            [0.0, dir, 0.0],
        );
        let hits = expect_hits(&s, &r, 2);
        let y = (RADIUS * RADIUS - rho * rho).sqrt();
        assert!((hits[0].point.y + dir * y).abs() <= TOL * RADIUS);
    }
    let t = torus();
    for rho in [
        MAJOR - 0.9 * MINOR,
        MAJOR - 0.3 * MINOR,
        MAJOR,
        MAJOR + 0.5 * MINOR,
        MAJOR + 0.99 * MINOR,
    ] {
        for phi in [0.0, 1.0, 2.5, 4.0] {
            let r = ray(
                [rho * f64::cos(phi), 2.0, rho * f64::sin(phi)],
                [0.0, -1.0, 0.0],
            );
            let hits = expect_hits(&t, &r, 2);
            let y = (MINOR * MINOR - (rho - MAJOR) * (rho - MAJOR)).sqrt();
            assert!((hits[0].point.y - y).abs() <= TOL && (hits[1].point.y + y).abs() <= TOL);
        }
    }
}

/// Rays perpendicular to the axis, exactly (`d_y = 0`) and within `1e-12`
/// of it, at heights across the sphere and the torus (through and beside the
/// axis).
#[test]
fn rays_perpendicular_to_the_axis_exactly_and_within_1e_12() {
    let mut rng = Rng(0x9E2);
    for (shape, top) in [(sphere(), RADIUS), (torus(), MINOR)] {
        let mut hits = 0;
        for i in 0..400 {
            let height = top * rng.range(-0.999, 0.999);
            let phi = rng.range(0.0, TAU);
            let d = Vector3::new(phi.cos(), 0.0, phi.sin());
            let side = Vector3::new(-phi.sin(), 0.0, phi.cos());
            let offset = shape.scale()
                * if i % 3 == 0 {
                    0.0
                } else {
                    rng.range(-1.2, 1.2)
                };
            let origin = Point3::new(0.0, height, 0.0) + side * offset - d * 3.0 * shape.scale();
            for dy in [0.0, 1e-12, -1e-12] {
                let r = Ray::new(origin, Vector3::new(d.x, dy, d.z));
                hits += check_ray(&shape, &r, 0.0, INF).len();
            }
        }
        assert!(hits > 1000, "{hits}");
    }
}

/// Rays through the axis at random angles: through the sphere's centre (and
/// near the poles), through the torus's centre and through the axis above
/// and below it.
#[test]
fn rays_through_the_axis() {
    let mut rng = Rng(0x7A1);
    for shape in [sphere(), torus()] {
        let size = shape.scale();
        for _ in 0..500 {
            let through = Point3::new(0.0, size * rng.range(-1.2, 1.2), 0.0);
            let d = rng.direction();
            let r = Ray::new(through - d * 3.0 * size, d);
            check_ray(&shape, &r, 0.0, INF);
        }
    }
}

/// Rays grazing the sphere's silhouette, inside and outside by `1e-6` and
/// `1e-9` of the radius (as `hard_cases.rs` asks of curved polynomial
/// profiles), in random directions, parallel to the axis (tangent on the
/// equator, the arcs' join) and perpendicular to it: inside, both roots;
/// outside, a miss.
#[test]
fn grazing_the_sphere_silhouette_on_both_sides() {
    let s = sphere();
    let mut rng = Rng(0x6A2);
    for i in 0..300 {
        let d = match i % 3 {
            0 => rng.direction(),
            1 => Vector3::y(),
            _ => {
                let phi = rng.range(0.0, TAU);
                Vector3::new(phi.cos(), 0.0, phi.sin())
            }
        };
        let e = perpendicular(&mut rng, &d);
        for delta in [1e-6, 1e-9] {
            let inside = line_at(d, e, RADIUS * (1.0 - delta), 3.0 * RADIUS);
            expect_hits(&s, &inside, 2);
            let outside = line_at(d, e, RADIUS * (1.0 + delta), 3.0 * RADIUS);
            expect_hits(&s, &outside, 0);
        }
    }
}

/// Rays perpendicular to the axis (`d_y = 0`) grazing the sphere's circle
/// of latitude at their height, `1e-10` and `1e-11` of the radius inside
/// (two hits) and outside (a miss), at every height including near the
/// poles, where the circle is small and the profile nearly flat: the
/// height root must be refined before the circle it gives decides the hit
/// (isolated only to `2⁻³⁰`, its radius was off by more than the graze).
#[test]
fn perpendicular_rays_grazing_circles_of_latitude_deeply() {
    let s = sphere();
    let mut rng = Rng(0x9E7);
    for i in 0..400 {
        let h = RADIUS
            * if i % 4 == 0 {
                rng.range(0.95, 0.999)
            } else {
                rng.range(-0.999, 0.999)
            };
        let x = (RADIUS * RADIUS - h * h).sqrt();
        let phi = rng.range(0.0, TAU);
        let d = Vector3::new(phi.cos(), 0.0, phi.sin());
        let e = Vector3::new(-phi.sin(), 0.0, phi.cos());
        for delta in [1e-10, 1e-11] {
            for (side, count) in [(-1.0, 2), (1.0, 0)] {
                let rho = x + side * delta * RADIUS;
                let ray = Ray::new(Point3::new(0.0, h, 0.0) + e * rho - d * 3.0 * RADIUS, d);
                expect_hits(&s, &ray, count);
            }
        }
    }
}

/// Rays grazing the torus's outer silhouettes on both sides: the outer
/// equator (lines in its plane at distance `(R + r)(1 ∓ δ)` from the axis,
/// and tilted by `1e-3`; vertical lines at that radius) and the top and
/// bottom circles (horizontal lines through the axis at heights `±r(1 ∓ δ)`).
#[test]
fn grazing_the_torus_silhouettes_on_both_sides() {
    let t = torus();
    let outer = MAJOR + MINOR;
    for delta in [1e-6, 1e-9] {
        for phi in [0.0, 0.7, 2.0, 4.4] {
            let (c, s) = (f64::cos(phi), f64::sin(phi));
            let d = Vector3::new(c, 0.0, s);
            let e = Vector3::new(-s, 0.0, c);
            for tilt in [0.0, 1e-3] {
                let dir = d + Vector3::y() * tilt;
                let inside = Ray::new(Point3::from(e * outer * (1.0 - delta) - dir * 3.0), dir);
                expect_hits(&t, &inside, 2);
                let outside = Ray::new(Point3::from(e * outer * (1.0 + delta) - dir * 3.0), dir);
                expect_hits(&t, &outside, 0);
            }
            let down = |rho: f64| ray([rho * c, 2.0, rho * s], [0.0, -1.0, 0.0]);
            expect_hits(&t, &down(outer * (1.0 - delta)), 2);
            expect_hits(&t, &down(outer * (1.0 + delta)), 0);
            for sign in [1.0, -1.0] {
                let level = |h: f64| Ray::new(Point3::new(0.0, sign * h, 0.0) - d * 3.0, d);
                expect_hits(&t, &level(MINOR * (1.0 - delta)), 4);
                expect_hits(&t, &level(MINOR * (1.0 + delta)), 0);
            }
        }
    }
}

/// Rays through the torus's hole: along and parallel to the axis (misses,
/// see also `lines_through_the_hole_and_beyond_the_torus_miss`), and oblique
/// ones through the hole that meet the inner wall on the far side, against
/// the quartic.
#[test]
fn rays_through_the_torus_hole() {
    let t = torus();
    let mut rng = Rng(0x401);
    let mut hit = 0;
    for _ in 0..600 {
        let rho = (MAJOR - MINOR) * rng.range(0.0, 0.95);
        let phi = rng.range(0.0, TAU);
        let through = Point3::new(
            rho * phi.cos(),
            rng.range(-0.5, 0.5) * MINOR,
            rho * phi.sin(),
        );
        let d = rng.direction();
        let r = Ray::new(through - d * 3.0, d);
        hit += usize::from(!check_ray(&t, &r, 0.0, INF).is_empty());
        // Starting in the hole.
        check_ray(&t, &Ray::new(through, d), 0.0, INF);
    }
    assert!(hit > 100, "{hit}");
}

/// Rays grazing the torus's inner equator (radius `R − r`): vertical lines
/// at `(R − r)(1 ± δ)` (outside the hole: two close hits; inside: a miss),
/// and lines in the equator's plane at distance `(R − r)(1 ∓ δ)` from the
/// axis (inside the hole: four hits, the middle two close; outside: two).
#[test]
fn grazing_the_inner_equator_of_the_torus() {
    let t = torus();
    let inner = MAJOR - MINOR;
    for delta in [1e-6, 1e-9] {
        for phi in [0.3, 1.9, 3.3, 5.0] {
            let (c, s) = (f64::cos(phi), f64::sin(phi));
            let down = |rho: f64| ray([rho * c, 2.0, rho * s], [0.0, -1.0, 0.0]);
            expect_hits(&t, &down(inner * (1.0 + delta)), 2);
            expect_hits(&t, &down(inner * (1.0 - delta)), 0);
            let d = Vector3::new(c, 0.0, s);
            let e = Vector3::new(-s, 0.0, c);
            for tilt in [0.0, 1e-12] {
                let dir = d + Vector3::y() * tilt;
                let at = |rho: f64| Ray::new(Point3::from(e * rho - dir * 3.0), dir);
                expect_hits(&t, &at(inner * (1.0 - delta)), 4);
                expect_hits(&t, &at(inner * (1.0 + delta)), 2);
            }
        }
    }
}

/// Secondary rays starting on the surface: continuing from a hit finds the
/// next surface point (the sphere's far side, the torus's next crossing),
/// never the start; leaving the sphere outward finds nothing; from the
/// sphere's entry point, any direction into the ball finds the far side.
#[test]
fn secondary_rays_find_the_next_surface() {
    let mut rng = Rng(0x5EC);
    for shape in [sphere(), torus()] {
        let size = shape.scale();
        let mut continued = 0;
        for _ in 0..600 {
            let r = random_ray(&mut rng, size, 1.1 * size);
            let Some(first) = shape.surface.intersect(&r, 0.0, INF) else {
                continue;
            };
            // On along the ray (at another |d|), into the solid (the normal
            // points into it), and out of it.
            let inward = first.normal.into_inner();
            let dirs = [
                r.dir,
                r.dir.normalize() * 3.0,
                inward + rng.direction() * 0.5,
                -inward + rng.direction() * 0.5,
            ];
            for dir in dirs {
                let next = Ray::new(first.point, dir);
                // The start is a root to rounding: the reference looks past
                // it, at 1e-9 of the size.
                let margin = 1e-9 * size / dir.norm();
                let want = shape.roots(&next).first_in(margin, INF);
                let got = shape.surface.intersect(&next, 0.0, INF);
                match (got, want) {
                    (Some(h), Some(t_ref)) => {
                        check_against(&shape, &next, &h, (0.0, INF), t_ref);
                        continued += 1;
                    }
                    (None, None) => {}
                    (g, w) => panic!("{g:?} but the reference has {w:?} for {next:?}"),
                }
            }
            if let ClosedForm::Sphere { .. } = shape.kind {
                // Out of the ball: nothing; into it: the far side.
                let out = Ray::new(first.point, -inward + rng.direction() * 0.5);
                assert_eq!(shape.surface.intersect(&out, 0.0, INF), None);
                let into = Ray::new(first.point, inward + rng.direction() * 0.5);
                assert!(shape.surface.intersect(&into, 0.0, INF).is_some());
            }
        }
        assert!(continued > 500, "{continued}");
    }
}

/// The sphere and the torus scaled by `1e-6` and `1e6`: random rays, rays
/// along and perpendicular to the axis, and grazing ones, as at scale 1.
#[test]
fn scales_1e_minus_6_and_1e6() {
    for k in [1e-6, 1e6] {
        let mut rng = Rng(0x5CA1E);
        for shape in [
            Shape::sphere(RADIUS * k),
            Shape::torus(MAJOR * k, MINOR * k),
        ] {
            let size = shape.scale();
            let mut hits = 0;
            for _ in 0..400 {
                let r = random_ray(&mut rng, size, 1.1 * size);
                hits += check_ray(&shape, &r, 0.0, INF).len();
            }
            assert!(hits > 200, "{hits}");
            // Hits along the axis (the sphere's poles, the torus's hole),
            // parallel to it through the solid, perpendicular through it.
            let (along, parallel_at, across) = match shape.kind {
                ClosedForm::Sphere { radius } => (2, 0.5 * radius, 2),
                ClosedForm::Torus { major, .. } => (0, major, 4),
            };
            expect_hits(
                &shape,
                &ray([0.0, -3.0 * size, 0.0], [0.0, 1.0, 0.0]),
                along,
            );
            let down = ray([parallel_at, 3.0 * size, 0.0], [0.0, -1.0, 0.0]);
            expect_hits(&shape, &down, 2);
            expect_hits(
                &shape,
                &ray([-3.0 * size, 0.0, 0.0], [1.0, 0.0, 0.0]),
                across,
            );
            // Grazing the outer silhouette on both sides.
            let graze = |rho: f64| ray([-3.0 * size, 0.0, rho], [1.0, 0.0, 0.0]);
            expect_hits(&shape, &graze(size * (1.0 - 1e-9)), 2);
            expect_hits(&shape, &graze(size * (1.0 + 1e-9)), 0);
        }
    }
}

/// Hits exactly at the profiles' span joins (the quarter arcs' ends): the
/// sphere's equator, the torus's outer and inner equators and its top and
/// bottom circles; rays perpendicular to the axis at the join heights,
/// oblique rays aimed at join points, and rays within `1e-10` of a join.
#[test]
fn hits_exactly_at_span_joins() {
    let mut rng = Rng(0x101);
    let s = sphere();
    let t = torus();
    // (shape, join radius, join height, outward normal in the profile plane)
    let joins = [
        (&s, RADIUS, 0.0, (1.0, 0.0)),
        (&t, MAJOR + MINOR, 0.0, (1.0, 0.0)),
        (&t, MAJOR, MINOR, (0.0, 1.0)),
        (&t, MAJOR - MINOR, 0.0, (-1.0, 0.0)),
        (&t, MAJOR, -MINOR, (0.0, -1.0)),
    ];
    let mut at_join = 0;
    for (shape, rho, y, (nx, ny)) in joins {
        for _ in 0..100 {
            let phi = rng.range(0.0, TAU);
            let (c, sn) = (phi.cos(), phi.sin());
            let p = Point3::new(rho * c, y, -rho * sn);
            // The profile plane's radial direction; the outward normal and
            // the profile's tangent at the join, in 3D.
            let radial = Vector3::new(c, 0.0, -sn);
            let n = radial * nx + Vector3::y() * ny;
            let along = radial * -ny + Vector3::y() * nx;
            // Aimed at the join point from its outside, at an angle.
            let w = (n + rng.direction() * 0.6).normalize();
            let r = Ray::new(p + w * 0.5 * MINOR, -w);
            let hits = check_ray(shape, &r, 0.0, INF);
            if hits.first().is_some_and(|h| (h.point - p).norm() <= TOL) {
                at_join += 1;
            }
            // Along the normal through the join point, and through points
            // within 1e-10 of it along the profile.
            for off in [0.0, 1e-10, -1e-10] {
                let r = Ray::new(p + n * 0.5 * MINOR + along * off, -n);
                let hits = check_ray(shape, &r, 0.0, INF);
                assert!((hits[0].t - 0.5 * MINOR).abs() <= TOL, "{r:?}: {hits:?}");
            }
        }
    }
    assert!(at_join > 300, "{at_join} hits at the join point aimed at");
    // From the torus's centre to its inner equator: t = R − r exactly.
    for k in 0..8 {
        let phi = TAU * k as f64 / 8.0;
        let r = ray([0.0, 0.0, 0.0], [phi.cos(), 0.0, phi.sin()]);
        let hits = expect_hits(&t, &r, 2);
        assert!((hits[0].t - (MAJOR - MINOR)).abs() <= TOL);
    }
}

// ---------------------------------------------------------------------------
// The generic Newton intersector, tessellation, partials
// ---------------------------------------------------------------------------

/// The generic Newton intersector on the rational sphere and torus: every
/// hit it reports is a root of the closed form (t within `1e-9`), nearer
/// than none of the reference's; on the sphere it finds the nearest root of
/// every ray the quadratic hits.
#[test]
fn newton_intersector_agrees_with_the_closed_forms() {
    let mut rng = Rng(0x4E7);
    for (shape, depth) in [(sphere(), 6), (sphere(), 8), (torus(), 8)] {
        let newton = NewtonIntersector::new(&shape.surface, depth);
        let size = shape.scale();
        let (mut matched, mut failed, mut reference_hits) = (0, 0, 0);
        for _ in 0..1500 {
            let r = random_ray(&mut rng, size, 1.1 * size);
            let roots = shape.roots(&r).all_in(0.0, INF);
            reference_hits += usize::from(!roots.is_empty());
            let Some(h) = newton.intersect(&r, 0.0, INF) else {
                failed += usize::from(!roots.is_empty());
                continue;
            };
            let err = |t: f64| (h.t - t).abs() * r.dir.norm() / size;
            let k = roots
                .iter()
                .position(|&t| err(t) <= TOL)
                .unwrap_or_else(|| panic!("Newton's hit {h:?} is no root of {roots:?} for {r:?}"));
            if k == 0 {
                matched += 1;
                check_against(&shape, &r, &h, (0.0, INF), roots[0]);
            } else {
                failed += 1;
            }
        }
        println!(
            "{:?} depth {depth}: {matched} nearest of {reference_hits}, {failed} missed or farther",
            shape.kind
        );
        assert!(reference_hits > 500, "{reference_hits}");
        // Newton is local: from a leaf's centre it may miss a hit or find
        // a farther root; rarely.
        assert!(
            failed * 100 <= reference_hits,
            "{failed} of {reference_hits}"
        );
    }
}

/// The distance from the origin to the triangle `abc`: to its plane where
/// the foot of the perpendicular lies inside it, else to its nearest edge
/// (a sliver, whose plane is ill-defined, is taken by its edges).
fn distance_from_origin(a: Point3<f64>, b: Point3<f64>, c: Point3<f64>) -> f64 {
    let to_segment = |p: Point3<f64>, q: Point3<f64>| {
        let e = q - p;
        let s = (-p.coords.dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
        if s.is_finite() {
            (p.coords + e * s).norm()
        } else {
            p.coords.norm()
        }
    };
    let edges = to_segment(a, b).min(to_segment(b, c)).min(to_segment(c, a));
    let cross = (b - a).cross(&(c - a));
    let longest = (b - a).norm().max((c - b).norm()).max((a - c).norm());
    if cross.norm() <= 1e-9 * longest * longest {
        return edges;
    }
    let n = cross.normalize();
    let foot = n * n.dot(&a.coords);
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(p, q)| (q - p).cross(&(foot - p.coords)).dot(&n) >= 0.0);
    if inside { foot.norm() } else { edges }
}

/// The sphere's mesh: every vertex on the sphere, and the reported deviation
/// bound honoured. The mesh is a closed polyhedron inscribed in the sphere,
/// so the ray from the centre through any sphere point leaves it through a
/// face F at a point Q with `|Q| ≥ dist(centre, F)`, within
/// `R − dist(centre, F)` of the sphere point: the largest of these over the
/// faces bounds the deviation, and must not exceed the mesh's bound. The
/// torus's vertices lie on the torus.
#[test]
fn meshes_lie_on_the_surface_within_their_bound() {
    let s = sphere();
    for tolerance in [1e-2, 1e-3, 1e-5] {
        let mesh = s
            .surface
            .tessellate(tolerance)
            .expect("a mesh of the sphere");
        assert!(mesh.bound <= tolerance, "{} > {tolerance}", mesh.bound);
        for p in &mesh.positions {
            assert!((p.coords.norm() - RADIUS).abs() <= 1e-14 * RADIUS, "{p:?}");
        }
        let deviation = mesh
            .triangles
            .iter()
            .map(|tri| {
                let [a, b, c] = tri.map(|i| mesh.positions[i as usize]);
                RADIUS - distance_from_origin(a, b, c)
            })
            .fold(0.0, f64::max);
        println!(
            "sphere mesh, tolerance {tolerance:e}: {} triangles, deviation {deviation:e}, bound {:e}",
            mesh.triangles.len(),
            mesh.bound
        );
        assert!(
            deviation <= mesh.bound * (1.0 + 1e-9),
            "deviation {deviation:e} > bound {:e}",
            mesh.bound
        );
        assert!(
            deviation >= 0.1 * mesh.bound,
            "the bound {:e} is far from {deviation:e}",
            mesh.bound
        );
    }
    let t = torus();
    let mesh = t.surface.tessellate(1e-3).expect("a mesh of the torus");
    for p in &mesh.positions {
        let rho = p.x.hypot(p.z);
        let off = ((rho - MAJOR).hypot(p.y) - MINOR).abs();
        assert!(
            off <= 1e-14 * (MAJOR + MINOR),
            "{p:?} is {off:e} off the torus"
        );
    }
}

/// `∂S/∂u` and `∂S/∂θ` of the rational sphere and torus against central
/// differences of `S` (away from the arcs' joins and the profile's ends),
/// and the unit normal against their cross product.
#[test]
fn partials_match_central_differences() {
    let mut rng = Rng(0xFD);
    let h = 1e-5;
    for shape in [sphere(), torus()] {
        let surface = &shape.surface;
        let (a, b) = surface.profile().domain();
        let size = shape.scale();
        let spans = surface
            .profile()
            .rational_bezier_spans()
            .expect("rational spans");
        let knots: Vec<f64> = spans.iter().flat_map(|s| [s.knots.0, s.knots.1]).collect();
        for _ in 0..2000 {
            let u = rng.range(a, b);
            if knots.iter().any(|k| (u - k).abs() < 2.0 * h * (b - a)) {
                continue; // a join or an end of the profile
            }
            let theta = rng.range(0.0, TAU);
            let (su, sv) = surface.partials(u, theta);
            let hu = h * (b - a);
            let fd_u = (surface.eval(u + hu, theta) - surface.eval(u - hu, theta)) / (2.0 * hu);
            let fd_v = (surface.eval(u, theta + h) - surface.eval(u, theta - h)) / (2.0 * h);
            // Truncation h²/6·|S‴| plus rounding ε·|S|/h, with room (in
            // u, relative to the speed of the profile's parametrization).
            let tol = 1e-8 * size;
            assert!(
                (su - fd_u).norm() <= tol * su.norm().max(1.0),
                "∂S/∂u {su:?} vs {fd_u:?} at ({u}, {theta})"
            );
            assert!(
                (sv - fd_v).norm() <= tol,
                "∂S/∂θ {sv:?} vs {fd_v:?} at ({u}, {theta})"
            );
            let n = surface.normal(u, theta).expect("a normal");
            let cross = su.cross(&sv).normalize();
            assert!(
                (n.into_inner() - cross).norm() <= 1e-12,
                "{n:?} vs {cross:?}"
            );
            let p = surface.eval(u, theta);
            assert!((n.into_inner() + shape.outward(&p)).norm() <= TOL);
        }
    }
}

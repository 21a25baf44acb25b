//! `intersect_all` and `occluded` on surfaces of revolution.
//!
//! # Reference
//! Every root of the ray on the profile's exact Bézier spans
//! (`common::reference::revolution::search::all_roots`): exact rational
//! arithmetic with the angle eliminated, each root certified and rounded
//! once; nothing of the library's intersector is used. A ray it cannot
//! certify (a tangent or double root) is left out, and so is one with two
//! roots within `1e-7` of the size (numerically one tangential root).
//!
//! # Tolerances
//! Hits in the reference's order and number, each `t` within
//! `(1e-12 + 16ε·κ)·size/|d|` (`κ = |d|/|d·n|`, the hit's condition) of the
//! reference's root: the hard cases' rule.

use revolve_testkit as common;

use common::reference::revolution::ExactProfile;
use common::reference::revolution::ray::RayData;
use common::reference::revolution::search::all_roots;
use common::{Rng, VASE, points, vase, wine_glass};
use revolve::nalgebra::{Point3, Vector3};
use revolve::{Curve, Intersect, Ray, Revolution};

const INF: f64 = f64::INFINITY;

/// Rays of one run by their number of hits (4 = four or more), and how many
/// were left out.
#[derive(Debug, Default)]
struct Tally {
    rays: usize,
    excluded: usize,
    by_count: [usize; 5],
}

/// Checks `intersect_all`, `occluded` and their agreement with `intersect`
/// on one ray against the reference's roots.
fn check_ray<C: Curve<2>>(
    surface: &Revolution<C>,
    reference: &ExactProfile,
    ray: &Ray,
    rng: &mut Rng,
    tally: &mut Tally,
) {
    tally.rays += 1;
    let size = surface.bounds().scale();
    let dn = ray.dir.norm();
    let spans = reference.spans().expect("a valid profile");
    let roots = RayData::new(ray, 0.0, INF)
        .ok()
        .and_then(|data| all_roots(spans, &data));
    let Some(roots) = roots.filter(|r| r.windows(2).all(|w| (w[1].0 - w[0].0) * dn > 1e-7 * size))
    else {
        tally.excluded += 1;
        return;
    };
    let mut hits = Vec::new();
    surface.intersect_all(ray, 0.0, INF, &mut hits);
    let ts: Vec<f64> = hits.iter().map(|h| h.t).collect();
    assert_eq!(
        hits.len(),
        roots.len(),
        "hits at {ts:?}, the reference has {roots:?}, for {ray:?}"
    );
    for (hit, &(t_ref, _)) in hits.iter().zip(&roots) {
        let kappa = dn / ray.dir.dot(&hit.normal).abs();
        let tol = (1e-12 + 16.0 * f64::EPSILON * kappa) * size / dn;
        assert!(
            (hit.t - t_ref).abs() <= tol,
            "t = {} but the reference has {t_ref} ({ts:?} vs {roots:?}) for {ray:?}",
            hit.t
        );
    }
    assert_eq!(hits.first().copied(), surface.intersect(ray, 0.0, INF));
    assert_eq!(surface.occluded(ray, 0.0, INF), !hits.is_empty());
    // A shadow ray's window ending somewhere along the ray.
    let last = roots.last().map_or(1.0, |r| r.0);
    let t_max = rng.range(0.0, 1.3 * last);
    let near = surface.intersect(ray, 0.0, t_max);
    assert_eq!(
        surface.occluded(ray, 0.0, t_max),
        near.is_some(),
        "t_max {t_max} for {ray:?}"
    );
    let mut window = Vec::new();
    surface.intersect_all(ray, 0.0, t_max, &mut window);
    let inside: Vec<_> = hits.iter().filter(|h| h.t < t_max).collect();
    // Rounding may decide a hit within its uncertainty of t_max either way.
    let unsure = hits.iter().any(|h| (h.t - t_max).abs() * dn <= 1e-9 * size);
    if !unsure {
        assert_eq!(window.len(), inside.len(), "t_max {t_max} for {ray:?}");
    }
    tally.by_count[hits.len().min(4)] += 1;
}

/// Random rays from a sphere of radius `4·size` toward random points of the
/// surface's box, and nearly horizontal rays across it (through both walls
/// of a goblet's bowl or a vase).
fn run<C: Curve<2>>(surface: &Revolution<C>, reference: &ExactProfile, seed: u64) -> Tally {
    let mut rng = Rng(seed);
    let mut tally = Tally::default();
    let b = surface.bounds();
    let size = b.scale();
    for k in 0..3000 {
        let ray = if k % 3 == 0 {
            let y = rng.range(b.min.y, b.max.y);
            let z = rng.range(0.9 * b.min.z, 0.9 * b.max.z);
            // Nearly horizontal: the reference needs d_y ≠ 0.
            let d = Vector3::new(1.0, rng.range(-0.02, 0.02), rng.range(-0.02, 0.02));
            Ray::new(Point3::new(-4.0 * size, y, z), d * rng.range(0.5, 2.0))
        } else {
            let origin = Point3::from(rng.direction() * 4.0 * size);
            let target = rng.point(b.min.coords.into(), b.max.coords.into());
            Ray::new(origin, (target - origin) * rng.range(0.3, 3.0))
        };
        check_ray(surface, reference, &ray, &mut rng, &mut tally);
    }
    tally
}

/// The wine glass (a uniform cubic B-spline profile: stem, foot and a bowl
/// whose walls a ray crosses up to four times) and the vase (one cubic
/// Bézier).
#[test]
fn intersect_all_finds_every_exact_root_in_order() {
    let glass = wine_glass();
    let reference = ExactProfile::from_bspline(3, glass.knots(), glass.points());
    let tally = run(&Revolution::new(glass), &reference, 0xA11);
    eprintln!("wine glass: {tally:?}");
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(
        tally.by_count[2] > 200 && tally.by_count[4] > 100,
        "{tally:?}"
    );
    let reference = ExactProfile::from_bezier(&points(&VASE));
    let tally = run(&Revolution::new(vase()), &reference, 0xA12);
    eprintln!("vase: {tally:?}");
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(tally.by_count[2] > 500, "{tally:?}");
}

/// A ray tangent to a cylinder's wall (the double root of the ray and the
/// circle) is one hit; a ray lying on the wall (every point a root) ends
/// the walk rather than running on; an empty or NaN range is no hit.
#[test]
fn tangent_rays_lying_rays_and_empty_ranges() {
    let cylinder = Revolution::new(
        revolve::Bezier::new(vec![
            revolve::nalgebra::Point2::new(1.0, 0.0),
            revolve::nalgebra::Point2::new(1.0, 2.0),
        ])
        .unwrap(),
    );
    let mut hits = Vec::new();
    let tangent = Ray::new(Point3::new(-3.0, 1.0, 1.0), Vector3::x());
    cylinder.intersect_all(&tangent, 0.0, INF, &mut hits);
    assert!(hits.len() <= 1, "{hits:?}");
    assert_eq!(cylinder.occluded(&tangent, 0.0, INF), !hits.is_empty());
    let lying = Ray::new(Point3::new(1.0, -1.0, 0.0), Vector3::y());
    cylinder.intersect_all(&lying, 0.0, INF, &mut hits);
    assert!(hits.len() <= 2, "{hits:?}");
    for (t_min, t_max) in [(1.0, 1.0), (2.0, 1.0), (f64::NAN, INF), (0.0, f64::NAN)] {
        let across = Ray::new(Point3::new(-3.0, 1.0, 0.0), Vector3::x());
        cylinder.intersect_all(&across, t_min, t_max, &mut hits);
        assert!(hits.is_empty());
        assert!(!cylinder.occluded(&across, t_min, t_max));
    }
}

//! Models made of many Bézier patches ([`BezierPatches`]): the hierarchy
//! over the patches finds what testing every patch finds, on Newell's
//! teapot and on mixed degrees; the teapot's lid apex; errors.

use revolve_testkit as common;

use common::Rng;
use revolve::nalgebra::{Point3, Vector3};
use revolve::{BezierPatches, BezierSurface, Error, Intersect, Ray, Surface};

/// The nearest hit over every patch, each intersected alone: the reference
/// for the hierarchy (patch index and hit).
fn every_patch(
    patches: &[BezierSurface],
    ray: &Ray,
    t_min: f64,
    t_max: f64,
) -> Option<(usize, f64)> {
    let mut best: Option<(usize, f64)> = None;
    for (k, s) in patches.iter().enumerate() {
        if let Some(h) = s.intersect(ray, t_min, t_max) {
            if best.is_none_or(|(_, t)| h.t < t) {
                best = Some((k, h.t));
            }
        }
    }
    best
}

/// A ray from a random point on a sphere around the box toward a random
/// point inside it.
fn random_ray(rng: &mut Rng, b: &revolve::Aabb) -> Ray {
    let c = b.center();
    let r = b.extent().norm();
    let dir = Vector3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    let origin = c + dir.normalize() * r;
    let e = b.extent();
    let target = Point3::new(
        b.min.x + rng.unit() * e.x,
        b.min.y + rng.unit() * e.y,
        b.min.z + rng.unit() * e.z,
    );
    Ray::new(origin, target - origin)
}

#[test]
fn the_hierarchy_finds_what_every_patch_finds_on_the_teapot() {
    let patches = common::teapot::patches();
    let model = BezierPatches::new(patches.clone()).unwrap();
    assert_eq!(model.len(), 32);
    let b = model.bounds();
    let mut rng = Rng(18);
    let (mut hits, mut misses) = (0, 0);
    for _ in 0..3000 {
        let ray = random_ray(&mut rng, &b);
        let expected = every_patch(&patches, &ray, 0.0, f64::INFINITY);
        let got = model.intersect_patch(&ray, 0.0, f64::INFINITY);
        match (expected, got) {
            (None, None) => misses += 1,
            (Some((k, t)), Some((j, h))) => {
                hits += 1;
                // Where two patches meet, either may own the hit.
                assert!(
                    (h.t - t).abs() <= 1e-12 * (1.0 + t),
                    "{ray:?}: t {} vs {t} (patch {j} vs {k})",
                    h.t
                );
                let on = patches[j].eval(h.uv.0, h.uv.1);
                assert!((on - h.point).norm() < 1e-12 && (ray.at(h.t) - h.point).norm() < 1e-9);
            }
            (e, g) => panic!("{ray:?}: every patch gives {e:?}, the model {g:?}"),
        }
    }
    // Both kinds of ray are exercised.
    assert!(hits > 1000 && misses > 300, "{hits} hits, {misses} misses");
}

#[test]
fn a_ray_down_onto_the_lid_apex_hits_its_collapsed_edge_with_the_axis_normal() {
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    let top = model.bounds().max.z;
    let ray = Ray::new(
        Point3::new(0.0, 0.0, top + 1.0),
        Vector3::new(0.0, 0.0, -1.0),
    );
    let (k, hit) = model.intersect_patch(&ray, 0.0, f64::INFINITY).unwrap();
    // The lid's knob reaches the top of the model at the axis.
    assert!((hit.point.z - top).abs() < 1e-9, "{hit:?} top {top}");
    assert!(hit.point.x.abs() < 1e-12 && hit.point.y.abs() < 1e-12);
    // The collapsed edge's limit normal is the axis (the data orients the
    // lid's patches downward, so either sign is the surface's own).
    assert!(hit.normal.z.abs() > 1.0 - 1e-9, "patch {k}: {hit:?}");
    // On the collapsed edge, up to the rounding of Newton's last step there
    // (the point is the apex to 1e-15 either way).
    let edge_gap = [hit.uv.0, 1.0 - hit.uv.0, hit.uv.1, 1.0 - hit.uv.1]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    assert!(edge_gap <= 1e-12, "{hit:?}");
}

#[test]
fn secondary_rays_walk_through_the_teapot_without_finding_their_start() {
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    let patches = model.patches();
    let b = model.bounds();
    let mut rng = Rng(7);
    let mut walked = 0;
    for _ in 0..400 {
        let ray = random_ray(&mut rng, &b);
        let mut t_min = 0.0;
        let mut count = 0;
        while let Some((k, h)) = model.intersect_patch(&ray, t_min, f64::INFINITY) {
            assert!(h.t > t_min);
            let next = every_patch(patches, &ray, t_min, f64::INFINITY).unwrap();
            assert!((next.1 - h.t).abs() <= 1e-12 * (1.0 + h.t), "patch {k}");
            t_min = h.t;
            count += 1;
            assert!(count < 40, "{ray:?} keeps hitting");
        }
        walked += count;
    }
    assert!(walked > 500, "{walked} hits walked");
}

#[test]
fn patches_of_lower_degree_are_raised_without_changing_their_hits() {
    let bilinear = BezierSurface::new(vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.3)],
        vec![Point3::new(1.0, 0.0, 0.2), Point3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    let rows = (0..4)
        .map(|i| {
            (0..3)
                .map(|j| {
                    let (x, y) = (i as f64 / 3.0, j as f64 / 2.0);
                    Point3::new(x + 2.0, y, 0.3 * (3.0 * x).sin() * y)
                })
                .collect()
        })
        .collect();
    let cubic_by_quadratic = BezierSurface::new(rows).unwrap();
    let patches = vec![bilinear, cubic_by_quadratic];
    let model = BezierPatches::new(patches.clone()).unwrap();
    let mut rng = Rng(3);
    let mut hits = [0; 2];
    for _ in 0..2000 {
        let origin = Point3::new(rng.range(-0.2, 3.2), rng.range(-0.2, 1.2), 3.0);
        let dir = Vector3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3), -1.0);
        let ray = Ray::new(origin, dir);
        let expected = every_patch(&patches, &ray, 0.0, f64::INFINITY);
        let got = model.intersect_patch(&ray, 0.0, f64::INFINITY);
        match (expected, got) {
            (None, None) => {}
            (Some((k, t)), Some((j, h))) => {
                assert_eq!(j, k);
                assert!((h.t - t).abs() <= 1e-12 * (1.0 + t));
                let alone = patches[k].intersect(&ray, 0.0, f64::INFINITY).unwrap();
                assert!((alone.uv.0 - h.uv.0).abs() < 1e-9 && (alone.uv.1 - h.uv.1).abs() < 1e-9);
                hits[k] += 1;
            }
            (e, g) => panic!("{ray:?}: {e:?} vs {g:?}"),
        }
    }
    assert!(hits[0] > 200 && hits[1] > 200, "{hits:?}");
}

#[test]
fn an_empty_model_is_an_error() {
    assert_eq!(BezierPatches::new(Vec::new()), Err(Error::NoPatches));
    assert!(Error::NoPatches.to_string().contains("at least one patch"));
}

#[test]
fn the_bounds_hold_every_patch() {
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    let b = model.bounds();
    for s in model.patches() {
        for i in 0..=20 {
            for j in 0..=20 {
                let p = s.eval(i as f64 / 20.0, j as f64 / 20.0);
                assert!(b.contains(&p), "{p:?} outside {b:?}");
            }
        }
    }
}

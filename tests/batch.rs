//! `Intersect::intersect_batch`: every lane gets exactly the single-ray
//! answer (hits, misses, rays along the axis and perpendicular to it, odd
//! ranges in one batch), and slices of unequal length process their common
//! prefix only.

mod common;

use common::Rng;
use revolve::nalgebra::Vector3;
use revolve::{BezierPatches, Hit, Intersect, Ray, Revolution};

/// A mixed batch through the box of `shape`: random rays, rays along the
/// y axis and perpendicular to it, rays that miss, and narrow or empty
/// ranges.
fn mixed_batch<S: Intersect>(shape: &S, n: usize, seed: u64) -> (Vec<Ray>, Vec<(f64, f64)>) {
    let b = shape.bounds();
    let mut rng = Rng(seed);
    let mut rays = Vec::with_capacity(n);
    let mut ranges = Vec::with_capacity(n);
    for i in 0..n {
        let target = rng.point_in(&b);
        let dir: Vector3<f64> = match i % 4 {
            0 => rng.direction(),
            1 => Vector3::new(0.0, -1.0, 0.0),
            2 => {
                let d: Vector3<f64> = rng.direction();
                Vector3::new(d.x, 0.0, d.z + 1e-3)
            }
            _ => rng.direction(),
        };
        let origin = if i % 4 == 3 {
            // Far off to the side: a miss.
            target + Vector3::new(0.0, 0.0, 10.0 * b.scale())
        } else {
            target - dir * 4.0 * b.scale()
        };
        rays.push(Ray::new(origin, dir));
        ranges.push(match i % 7 {
            0 => (0.0, 1.0),
            1 => (f64::NAN, 5.0),
            2 => (3.0, 2.0),
            _ => (0.0, f64::INFINITY),
        });
    }
    (rays, ranges)
}

fn check_lanes<S: Intersect>(shape: &S, seed: u64) {
    let (rays, ranges) = mixed_batch(shape, 512, seed);
    let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
    shape.intersect_batch(&rays, &ranges, &mut hits);
    let mut found = 0;
    for ((ray, &(lo, hi)), hit) in rays.iter().zip(&ranges).zip(&hits) {
        assert_eq!(
            *hit,
            shape.intersect(ray, lo, hi),
            "{ray:?} in ({lo}, {hi})"
        );
        found += usize::from(hit.is_some());
    }
    assert!(found > 50, "only {found} hits");
    // Unequal lengths: the common prefix only; the rest is untouched.
    let sentinel = Some(hits.iter().flatten().next().copied().unwrap());
    let mut short = vec![sentinel; 40];
    shape.intersect_batch(&rays[..30], &ranges[..35], &mut short);
    for i in 0..30 {
        assert_eq!(short[i], hits[i]);
    }
    assert!(short[30..].iter().all(|h| *h == sentinel));
    let mut none: [Option<Hit>; 0] = [];
    shape.intersect_batch(&rays, &ranges, &mut none);
}

#[test]
fn a_revolution_batch_gives_each_ray_its_own_hit() {
    check_lanes(&Revolution::new(common::wine_glass()), 1);
    check_lanes(&Revolution::new(common::vase()), 2);
}

#[test]
fn a_model_of_patches_batch_gives_each_ray_its_own_hit() {
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    check_lanes(&model, 3);
}

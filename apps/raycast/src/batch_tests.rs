//! Batched camera rays: the image, the ray counts and the revolution calls
//! are exactly those of tracing every camera ray alone, and
//! `World::intersect_batch` gives exactly `World::intersect` per lane.

use std::path::PathBuf;

use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::geometry::{IntersectStats, LANES, World};
use crate::parse::parse_file;
use crate::render::{Options, render};
use crate::sampling::Rng;
use crate::scene::{Integrator, Object, Scene, Shape};

fn scene(name: &str, width: u32, height: u32) -> Scene {
    let path: PathBuf = crate::repo_root()
        .join("scenes")
        .join(format!("{name}.txt"));
    let mut s = parse_file(&path).unwrap_or_else(|e| panic!("{e}"));
    (s.camera.width, s.camera.height) = (width, height);
    s
}

/// Renders `s` one camera ray at a time and in batches of 3 (runs that
/// straddle tile edges) and [`LANES`]; asserts the same pixels, bit for bit,
/// and the same counters. Returns the revolution calls.
fn same_both_ways(name: &str, s: &Scene) -> u64 {
    let lanes = |lanes| Options {
        lanes,
        ..Options::default()
    };
    let (single, single_stats) = render(s, &lanes(1)).unwrap();
    assert!(
        single.pixels.iter().any(|c| *c != s.background),
        "{name}: the render shows something"
    );
    for n in [3, LANES] {
        let (batched, stats) = render(s, &lanes(n)).unwrap();
        let differing = single
            .pixels
            .iter()
            .zip(&batched.pixels)
            .filter(|(a, b)| {
                a.iter()
                    .zip(b.iter())
                    .any(|(x, y)| x.to_bits() != y.to_bits())
            })
            .count();
        assert_eq!(differing, 0, "{name}, {n} lanes: pixels differ");
        assert_eq!(stats.rays, single_stats.rays, "{name}, {n} lanes: rays");
        assert_eq!(
            stats.intersect.revolution_calls, single_stats.intersect.revolution_calls,
            "{name}, {n} lanes: revolution calls"
        );
        assert_eq!(stats.non_finite_samples, single_stats.non_finite_samples);
    }
    single_stats.intersect.revolution_calls
}

#[test]
fn batched_renders_equal_single_ray_renders() {
    for name in [
        "basic",
        "vase",
        "wine_glass",
        "curves",
        "mesh",
        "nurbs",
        "teapot",
    ] {
        same_both_ways(name, &scene(name, 53, 37));
    }
    // Effects, random light samples and 2 jittered samples per pixel.
    let mut showcase = scene("showcase", 48, 36);
    showcase.render.samples = Some(2);
    assert!(same_both_ways("showcase", &showcase) > 0);
    showcase.render.integrator = Some(Integrator::Path);
    assert!(same_both_ways("showcase (path)", &showcase) > 0);
}

#[test]
fn world_batches_equal_single_queries() {
    // The showcase's revolution bodies, mirror sphere and floor plus 80
    // overlapping random spheres, queried by coherent rays from the camera
    // and by scattered rays from inside the crowd, with several `t_min`:
    // many rays meet several objects, in every order.
    let mut s = scene("showcase", 8, 8);
    let mut rng = Rng::for_pixel(7, 1, 2);
    let point = |rng: &mut Rng, half: f64| {
        let ((a, b), (c, _)) = (rng.next_2d(), rng.next_2d());
        Point3::new(
            half * (2.0 * a - 1.0),
            0.5 + half * b,
            half * (2.0 * c - 1.0),
        )
    };
    for _ in 0..80 {
        let center = point(&mut rng, 3.0);
        let radius = 0.2 + 0.6 * rng.next_2d().0;
        s.objects.push(Object {
            shape: Shape::Sphere { center, radius },
            material: 0,
            transform: None,
        });
    }
    let world = World::new(&s);
    let eye = Point3::new(0.0, 1.6, 7.5);
    let mut rays = Vec::new();
    for i in 0..2001 {
        let (a, b) = rng.next_2d();
        let ray = if i % 2 == 0 {
            let dir = Vector3::new((a - 0.5) * 0.1, -0.22 + (b - 0.5) * 0.1, -1.0);
            Ray::new(eye, dir.normalize())
        } else {
            let dir = point(&mut rng, 1.0) - Point3::new(0.0, 1.0, 0.0);
            Ray::new(point(&mut rng, 3.0), dir.normalize())
        };
        rays.push(ray);
    }
    let mut hit_count = 0;
    for t_min in [0.0, 0.5, 3.0] {
        let mut single_stats = IntersectStats::default();
        let single: Vec<_> = rays
            .iter()
            .map(|r| world.intersect(r, t_min, f64::INFINITY, &mut single_stats))
            .collect();
        let mut stats = IntersectStats::default();
        let mut batched = vec![None; rays.len()];
        world.intersect_batch(&rays, t_min, &mut batched, &mut stats);
        assert_eq!(batched, single, "t_min {t_min}");
        assert_eq!(stats.revolution_calls, single_stats.revolution_calls);
        hit_count += single.iter().flatten().count();
    }
    assert!(hit_count > 3000, "{hit_count} hits");
}

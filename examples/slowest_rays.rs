//! The slowest rays of a hard family: rays aimed at the edges and corners of
//! the teapot's patches (where its lid and bottom collapse to poles and its
//! patches meet), half of them grazing (in the tangent plane at the aimed
//! point, tilted by at most 1e-3). Each ray is timed three times and keeps
//! its fastest; the example prints the median, the 99th percentile and the
//! maximum, and the slowest rays with the point they aim at.
//!
//! ```sh
//! cargo run --release --example slowest_rays [RAYS_PER_PATCH]
//! ```
//!
//! `RAYS_PER_PATCH` defaults to 400 (12 800 rays). Deterministic rays, so
//! the same command compares two commits.

use std::time::Instant;

use revolve::nalgebra::{Point3, Vector3};
use revolve::{BezierPatches, Intersect, Ray, Surface};
use revolve_testkit as common;

/// Distances from an edge at which rays are aimed (in the patch's
/// parameters); 0.5 is the middle.
const FROM_EDGE: [f64; 6] = [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.5];

fn main() -> Result<(), String> {
    let per_patch: usize = match std::env::args().nth(1) {
        Some(n) => n.parse().map_err(|_| format!("not a ray count: {n:?}"))?,
        None => 400,
    };
    let patches = common::teapot::patches();
    let model = BezierPatches::new(patches.clone()).map_err(|e| e.to_string())?;
    let mut rng = common::Rng(5);
    let mut timed: Vec<(f64, String)> = Vec::with_capacity(per_patch * patches.len());
    for (k, patch) in patches.iter().enumerate() {
        for _ in 0..per_patch {
            // A parameter point on or near an edge, or near a corner.
            let mut uv = [rng.unit(), rng.unit()];
            let edge = FROM_EDGE[rng.below(FROM_EDGE.len())];
            let side = rng.below(4);
            match side {
                0 => uv[0] = edge,
                1 => uv[0] = 1.0 - edge,
                2 => uv[1] = edge,
                _ => uv[1] = 1.0 - edge,
            }
            if rng.below(3) == 0 {
                uv[1 - side / 2] = FROM_EDGE[rng.below(FROM_EDGE.len())];
            }
            let aim = patch.eval(uv[0], uv[1]);
            let random: Vector3<f64> = rng.direction();
            let grazing = rng.below(2) == 0;
            let dir = match patch.normal(uv[0], uv[1]) {
                Some(n) if grazing => {
                    let n = n.into_inner();
                    let tangent = random - n * random.dot(&n);
                    if tangent.norm() > 1e-9 {
                        (tangent.normalize() + n * rng.range(-1e-3, 1e-3)).normalize()
                    } else {
                        random
                    }
                }
                _ => random,
            };
            let ray = Ray::new(Point3::from(aim.coords - dir * 10.0), dir);
            let mut fastest = f64::INFINITY;
            for _ in 0..3 {
                let start = Instant::now();
                std::hint::black_box(model.intersect(&ray, 0.0, f64::INFINITY));
                fastest = fastest.min(start.elapsed().as_secs_f64());
            }
            timed.push((fastest, format!("patch {k} at {uv:?}: {ray:?}")));
        }
    }
    timed.sort_by(|a, b| a.0.total_cmp(&b.0));
    let at = |q: f64| timed[((timed.len() - 1) as f64 * q) as usize].0 * 1e6;
    println!(
        "{} rays: median {:.2} µs, 99th percentile {:.2} µs, slowest {:.2} µs",
        timed.len(),
        at(0.5),
        at(0.99),
        at(1.0)
    );
    for (seconds, ray) in timed.iter().rev().take(5) {
        println!("{:9.2} µs  {ray}", seconds * 1e6);
    }
    Ok(())
}

//! The queries beside the nearest hit, timed against it on each shape:
//! every hit along a ray (`Intersect::intersect_all`), whether anything is
//! in the way (`Intersect::occluded`), and the nearest point of the surface
//! to a point (`nearest_point`).
//!
//! The rays are the shape's study rays (the same random rays through its
//! box); the points are random in its box grown by half its size on every
//! side. Each query's answers are checked against `intersect`'s on the same
//! ray (the first of every hit is the nearest hit, `occluded` is whether
//! there is one): a ray where they differ is counted and fails the run.

use crate::common::Rng;
use crate::study::{T_MAX, median_sorted};
use revolve::nalgebra::Point3;
use revolve::{Aabb, Error, Hit, Intersect, Ray, SurfaceNearest};
use std::hint::black_box;
use std::time::Instant;

/// What the queries cost on one shape.
#[derive(Debug, Clone, PartialEq)]
pub struct QueryRow {
    pub shape: &'static str,
    /// Rays timed, and the hits `intersect_all` found on them.
    pub rays: usize,
    pub hits: usize,
    /// Median seconds a ray of `intersect`, `intersect_all`, `occluded`.
    pub intersect: f64,
    pub all: f64,
    pub occluded: f64,
    /// Rays where `intersect_all`'s first hit is not `intersect`'s, or
    /// `occluded` is not `intersect(..).is_some()`.
    pub disagreements: usize,
    /// Points queried, median seconds a `nearest_point`, and how many
    /// answers were certified.
    pub points: usize,
    pub nearest: f64,
    pub certified: usize,
}

/// Times the three ray queries on `rays` (`repeats` passes each, the
/// median kept) and `nearest` on `points` random points about `bounds`.
pub fn measure<S: Intersect>(
    shape: &'static str,
    surface: &S,
    nearest: &dyn Fn(&Point3<f64>) -> Result<SurfaceNearest, Error>,
    (rays, points): (&[Ray], usize),
    repeats: usize,
    seed: u64,
) -> QueryRow {
    let per_ray = |pass: &mut dyn FnMut(&Ray)| {
        median_time(rays.len(), repeats, || rays.iter().for_each(&mut *pass))
    };
    let intersect = per_ray(&mut |r| {
        black_box(surface.intersect(r, 0.0, T_MAX));
    });
    let mut all: Vec<Hit> = Vec::new();
    let all_time = per_ray(&mut |r| {
        surface.intersect_all(r, 0.0, T_MAX, &mut all);
        black_box(&all);
    });
    let occluded = per_ray(&mut |r| {
        black_box(surface.occluded(r, 0.0, T_MAX));
    });
    let (mut hits, mut disagreements) = (0, 0);
    for r in rays {
        let first = surface.intersect(r, 0.0, T_MAX);
        surface.intersect_all(r, 0.0, T_MAX, &mut all);
        hits += all.len();
        if all.first().copied() != first || surface.occluded(r, 0.0, T_MAX) != first.is_some() {
            disagreements += 1;
        }
    }
    let queries = query_points(&surface.bounds(), points, seed);
    let nearest_time = median_time(points, repeats, || {
        for p in &queries {
            let _ = black_box(nearest(p));
        }
    });
    let certified = queries
        .iter()
        .filter(|p| nearest(p).is_ok_and(|n| n.certified))
        .count();
    QueryRow {
        shape,
        rays: rays.len(),
        hits,
        intersect,
        all: all_time,
        occluded,
        disagreements,
        points,
        nearest: nearest_time,
        certified,
    }
}

/// `count` random points in `bounds` grown by half its largest extent on
/// every side, deterministic for `seed`.
fn query_points(bounds: &Aabb, count: usize, seed: u64) -> Vec<Point3<f64>> {
    let mut rng = Rng(seed);
    let grown = bounds.expand(0.5 * bounds.extent().amax());
    (0..count).map(|_| rng.point_in(&grown)).collect()
}

/// The median over `repeats` runs of `pass` of its time divided by
/// `count` (seconds per item).
fn median_time(count: usize, repeats: usize, mut pass: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let start = Instant::now();
            pass();
            start.elapsed().as_secs_f64() / count.max(1) as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    median_sorted(&times)
}

//! A fixed workload for profiling the exact intersector: the benches' kind of
//! random rays through a shape's bounding box (1024 of them, cycled), run
//! `N` times, with the hit count and, with `--report`, what the intersector
//! did per ray on average. Deterministic, so instruction counts compare
//! across commits:
//!
//! ```sh
//! cargo build --release --example ray_profile
//! valgrind --tool=callgrind target/release/examples/ray_profile glass 100000
//! ```
//!
//! `ray_profile [glass|vase|cylinder|sphere|torus|teapot|folded|bicubic] [N] [--perpendicular] [--report] [--batch]`:
//! the shape (default glass; the sphere and the torus are rational revolutions
//! of NURBS arcs; the teapot, the folded bicubic and the benches' gently
//! curved bicubic are models of Bézier
//! patches), the number of rays (default 100 000), rays perpendicular
//! to the axis instead of in any direction, the per-ray report, and rays sent
//! through `Intersect::intersect_batch` eight at a time instead of one by
//! one.

use revolve_testkit as common;

use common::Rng;
use revolve::nalgebra::{Point2, Vector3};
use revolve::{Aabb, BSpline, Bezier, BezierPatches, Intersect, Nurbs, Ray, Revolution};

/// One of the profiled shapes.
enum Shape {
    Glass(Revolution<BSpline<2>>),
    /// The vase, or the cylinder of radius 1 and height 2 (a degree-1
    /// profile: the floor of what the intersector's machinery costs).
    Bezier(Revolution<Bezier<2>>),
    /// The unit sphere (a half circle, two rational quarter arcs) or the
    /// torus of radii 1 and 0.25 (a full circle, four quarter arcs).
    Nurbs(Revolution<Nurbs<2>>),
    /// Newell's teapot (32 bicubic patches), the benches' folded bicubic or
    /// their gently curved one
    /// patch, as a model of Bézier patches.
    Patches(BezierPatches),
}

/// The teapot, the folded or the gently curved patch as a model of Bézier
/// patches.
fn patches(name: &str) -> Result<Shape, String> {
    let list = match name {
        "teapot" => common::teapot::patches(),
        "folded" => vec![common::tensor_shapes::folded_bicubic()],
        _ => vec![common::patch_shapes::gentle_bicubic()],
    };
    BezierPatches::new(list)
        .map(Shape::Patches)
        .map_err(|e| e.to_string())
}

/// The unit sphere as a rational revolution.
fn sphere() -> Result<Shape, String> {
    let half = std::f64::consts::FRAC_PI_2;
    let arc = Nurbs::arc(Point2::origin(), 1.0, -half, half).map_err(|e| e.to_string())?;
    Ok(Shape::Nurbs(Revolution::new(arc)))
}

/// The torus of radii 1 and 0.25 as a rational revolution.
fn torus() -> Result<Shape, String> {
    let circle = Nurbs::circle(Point2::new(1.0, 0.0), 0.25).map_err(|e| e.to_string())?;
    Ok(Shape::Nurbs(Revolution::new(circle)))
}

fn main() -> Result<(), String> {
    let mut shape = Shape::Glass(Revolution::new(common::wine_glass()));
    let (mut n, mut perpendicular, mut report, mut batch) = (100_000_usize, false, false, false);
    for arg in std::env::args().skip(1) {
        match arg.as_str() {
            "glass" => shape = Shape::Glass(Revolution::new(common::wine_glass())),
            "vase" => shape = Shape::Bezier(Revolution::new(common::vase())),
            "cylinder" => shape = Shape::Bezier(common::bezier(&common::CYLINDER)),
            "sphere" => shape = sphere()?,
            "torus" => shape = torus()?,
            "teapot" | "folded" | "bicubic" => shape = patches(arg.as_str())?,
            "--perpendicular" => perpendicular = true,
            "--report" => report = true,
            "--batch" => batch = true,
            count => {
                n = count
                    .parse()
                    .map_err(|_| format!("unknown argument '{count}': expected glass, vase, cylinder, sphere, torus, teapot, folded, bicubic, a ray count, --perpendicular, --report or --batch"))?
            }
        }
    }
    let bounds = match &shape {
        Shape::Glass(s) => s.bounds(),
        Shape::Bezier(s) => s.bounds(),
        Shape::Nurbs(s) => s.bounds(),
        // The box of the control points (not the search's, which is
        // tighter), so that the rays do not depend on how the search cuts
        // the patches.
        Shape::Patches(s) => {
            Aabb::from_points(s.patches().iter().flat_map(|p| p.points().iter().flatten()))
        }
    };
    let mut rng = Rng(7);
    let radius = 2.0 * bounds.extent().norm();
    let rays: Vec<Ray> = (0..1024)
        .map(|_| {
            let target = rng.point_in(&bounds);
            let mut dir: Vector3<f64> = rng.direction();
            if perpendicular {
                dir.y = 0.0;
                if dir.norm() < 1e-3 {
                    dir = Vector3::x();
                }
            }
            Ray::new(target - dir * radius, dir)
        })
        .collect();
    let mut hits = 0_usize;
    if batch {
        if report {
            return Err("--report and --batch do not go together".into());
        }
        let target: &dyn Intersect = match &shape {
            Shape::Glass(s) => s,
            Shape::Bezier(s) => s,
            Shape::Nurbs(s) => s,
            Shape::Patches(s) => s,
        };
        let ranges = [(0.0, f64::INFINITY); 8];
        let mut out = [None; 8];
        let mut done = 0;
        while done < n {
            let start = done % rays.len();
            let lanes = 8.min(n - done).min(rays.len() - start);
            target.intersect_batch(&rays[start..start + lanes], &ranges, &mut out[..lanes]);
            hits += out[..lanes].iter().filter(|h| h.is_some()).count();
            done += lanes;
        }
        println!("hits {hits} of {n} rays (batches of 8)");
        return Ok(());
    }
    // Spans entered, spans solved, roots, candidates, Newton iterations.
    let mut totals = [0_u64; 5];
    for i in 0..n {
        let ray = &rays[i % rays.len()];
        let hit = if report {
            let (hit, r) = match &shape {
                Shape::Glass(s) => s.intersect_with_report(ray, 0.0, f64::INFINITY),
                Shape::Bezier(s) => s.intersect_with_report(ray, 0.0, f64::INFINITY),
                Shape::Nurbs(s) => s.intersect_with_report(ray, 0.0, f64::INFINITY),
                Shape::Patches(_) => return Err("--report is for revolutions".into()),
            };
            for (total, x) in totals.iter_mut().zip([
                r.spans_entered,
                r.spans_solved,
                r.roots,
                r.candidates,
                r.iterations,
            ]) {
                *total += u64::from(x);
            }
            hit
        } else {
            match &shape {
                Shape::Glass(s) => s.intersect(ray, 0.0, f64::INFINITY),
                Shape::Bezier(s) => s.intersect(ray, 0.0, f64::INFINITY),
                Shape::Nurbs(s) => s.intersect(ray, 0.0, f64::INFINITY),
                Shape::Patches(s) => s.intersect(ray, 0.0, f64::INFINITY),
            }
        };
        hits += usize::from(hit.is_some());
    }
    println!("hits {hits} of {n} rays");
    if report {
        let names = [
            "spans entered",
            "spans solved",
            "roots",
            "candidates",
            "Newton iterations",
        ];
        for (name, total) in names.iter().zip(totals) {
            println!("{name} per ray: {:.2}", total as f64 / n.max(1) as f64);
        }
    }
    Ok(())
}

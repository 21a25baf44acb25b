//! Ray-casts two surfaces to an image with nothing but the library: a vase
//! (a cubic B-spline profile turned about a vertical axis, a `Revolution`)
//! and a wavy sheet (a bicubic `BezierSurface`, a tensor-product patch)
//! checkered by its `(u, v)` parameters. Every pixel sends one ray through
//! a pinhole camera; each surface's `Intersect::intersect` returns its
//! nearest hit, the nearer of the two is shaded with a headlight (a light at
//! the eye, Lambert's cosine between `Hit::normal` and the ray, taken on
//! either side so the sheet's back and the vase's inside are lit too).
//!
//! ```sh
//! cargo run --release --example render_surface [-- OUT.ppm]
//! ```
//!
//! writes a 480×360 binary PPM (P6: a short text header, then 8-bit RGB
//! triples row by row, so no image crate is needed) to `OUT.ppm` (default
//! `out/render_surface.ppm`); most image viewers open it, and
//! `convert out/render_surface.ppm out/render_surface.png` turns it into a
//! PNG.

use std::error::Error;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::{BSpline, BezierSurface, Hit, Intersect, Ray, Revolution};

const WIDTH: usize = 480;
const HEIGHT: usize = 360;
/// Vertical field of view, in degrees.
const FOV: f64 = 40.0;

/// The vase: a clamped cubic B-spline profile, `x` the radius, `y` the
/// height, starting on the axis (a closed bottom) and ending at an open lip.
fn vase() -> Result<Revolution<BSpline<2>>, revolve::Error> {
    let profile = [
        (0.0, -1.0),
        (0.45, -1.0),
        (0.55, -0.85),
        (0.3, -0.4),
        (0.2, 0.1),
        (0.45, 0.55),
        (0.5, 0.9),
        (0.42, 1.0),
    ];
    let points = profile.iter().map(|&(x, y)| Point2::new(x, y)).collect();
    // Placed with its axis through (-0.7, 0, 0), along +y.
    Ok(Revolution::new(BSpline::clamped(3, points)?)
        .with_axis(Point3::new(-0.7, 0.0, 0.0), Vector3::y_axis()))
}

/// The sheet: a bicubic Bézier patch over `x ∈ [0.1, 1.7]`, `z ∈ [-1, 1]`,
/// its heights a wave along both directions.
fn sheet() -> Result<BezierSurface, revolve::Error> {
    let grid = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (x, z) = (0.1 + 0.533 * i as f64, -1.0 + 0.667 * j as f64);
                    let y = -0.6 + 0.5 * ((i + j) % 2) as f64 + 0.15 * i as f64;
                    Point3::new(x, y, z)
                })
                .collect()
        })
        .collect();
    BezierSurface::new(grid)
}

/// The nearest hit of `ray` among `objects`, with the object's index.
fn nearest(objects: &[&dyn Intersect], ray: &Ray) -> Option<(usize, Hit)> {
    let mut best: Option<(usize, Hit)> = None;
    for (k, object) in objects.iter().enumerate() {
        let t_max = best.as_ref().map_or(f64::INFINITY, |(_, h)| h.t);
        if let Some(hit) = object.intersect(ray, 1e-9, t_max) {
            best = Some((k, hit));
        }
    }
    best
}

/// The colour of a pixel whose ray is `ray`, in `[0, 1]³`.
fn shade(objects: &[&dyn Intersect], ray: &Ray) -> Vector3<f64> {
    let Some((k, hit)) = nearest(objects, ray) else {
        // Background: a vertical grey gradient.
        let up = 0.5 + 0.5 * ray.dir.normalize().y;
        return Vector3::repeat(0.75 + 0.2 * up);
    };
    let base = if k == 0 {
        Vector3::new(0.8, 0.45, 0.25) // terracotta vase
    } else {
        // A checkerboard of 8 × 8 squares in the sheet's (u, v).
        let (u, v) = hit.uv;
        let odd = ((u * 8.0).floor() + (v * 8.0).floor()) as i64 % 2 == 1;
        if odd {
            Vector3::new(0.15, 0.5, 0.55)
        } else {
            Vector3::new(0.9, 0.9, 0.85)
        }
    };
    // Headlight: the light is at the eye, so it comes along -ray.dir.
    let cosine = hit.normal.dot(&ray.dir.normalize()).abs();
    base * (0.15 + 0.85 * cosine)
}

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("out/render_surface.ppm"), PathBuf::from);
    let (vase, sheet) = (vase()?, sheet()?);
    let objects: [&dyn Intersect; 2] = [&vase, &sheet];

    // A pinhole camera at `eye` looking at `target`.
    let eye = Point3::new(0.4, 2.2, 4.6);
    let target = Point3::new(0.4, -0.15, 0.0);
    let forward = (target - eye).normalize();
    let right = forward.cross(&Vector3::y()).normalize();
    let up = right.cross(&forward);
    let half_height = (FOV.to_radians() / 2.0).tan();
    let half_width = half_height * WIDTH as f64 / HEIGHT as f64;

    let start = Instant::now();
    let mut pixels = Vec::with_capacity(3 * WIDTH * HEIGHT);
    for row in 0..HEIGHT {
        for col in 0..WIDTH {
            // Through the pixel's centre, rows from the top.
            let x = (2.0 * (col as f64 + 0.5) / WIDTH as f64 - 1.0) * half_width;
            let y = (1.0 - 2.0 * (row as f64 + 0.5) / HEIGHT as f64) * half_height;
            let ray = Ray::new(eye, forward + x * right + y * up);
            let colour = shade(&objects, &ray);
            pixels.extend(
                colour
                    .iter()
                    .map(|c| (255.0 * c.clamp(0.0, 1.0)).round() as u8),
            );
        }
    }
    let elapsed = start.elapsed();

    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let mut file = std::io::BufWriter::new(std::fs::File::create(&out)?);
    write!(file, "P6\n{WIDTH} {HEIGHT}\n255\n")?;
    file.write_all(&pixels)?;
    file.flush()?;
    println!(
        "{} rays in {:.2} s; wrote {}",
        WIDTH * HEIGHT,
        elapsed.as_secs_f64(),
        out.display()
    );
    Ok(())
}

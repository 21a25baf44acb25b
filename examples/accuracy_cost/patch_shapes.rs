//! The tensor-product shapes of the study and the benches: a gently curved
//! bicubic Bézier patch, a folded one (a ray can cross it several times) and
//! Newell's teapot (32 bicubic patches, read from `scenes/teapot.txt`).
//!
//! Shared by the accuracy-cost study and `benches/intersect.rs` (included
//! there by path), so both measure the same surfaces.

use revolve::BezierSurface;
use revolve::nalgebra::Point3;

/// The bicubic patch over the unit square with heights `z(i, j)` at the
/// control point `(i/3, j/3)`, its `x` sheared by `shear·(j − 1.5)²`.
fn bicubic(shear: f64, z: impl Fn(usize, usize) -> f64) -> BezierSurface {
    let net: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (x, y) = (i as f64 / 3.0, j as f64 / 3.0);
                    Point3::new(x + shear * (j as f64 - 1.5).powi(2), y, z(i, j))
                })
                .collect()
        })
        .collect();
    BezierSurface::new(net).expect("a finite 4 × 4 net")
}

/// A gently curved bicubic: the unit square lifted into a low dome with a
/// saddle-like twist (heights up to 0.3), so most rays cross it once.
pub fn gentle_bicubic() -> BezierSurface {
    bicubic(0.0, |i, j| {
        let (a, b) = (i as f64 - 1.5, j as f64 - 1.5);
        0.3 - 0.05 * (a * a + b * b) + 0.02 * a * b
    })
}

/// A folded bicubic: heights alternating `±0.4` in a checkerboard and the
/// rows sheared, so the sheet folds and rays cross it up to several times
/// (the net of the original `bench_patches`).
pub fn folded_bicubic() -> BezierSurface {
    bicubic(0.3, |i, j| if (i + j) % 2 == 0 { 0.4 } else { -0.4 })
}

/// The teapot's data file, compiled in.
const TEAPOT: &str = include_str!("../../scenes/teapot.txt");

/// Newell's teapot: the 32 bicubic patches of `scenes/teapot.txt`.
pub fn teapot() -> Vec<BezierSurface> {
    parse_patches(TEAPOT).expect("scenes/teapot.txt is a valid patch file")
}

/// Patches in the classic layout: the patch count, per patch 16 one-based
/// vertex indices (4 rows of 4, row `i` along `u`), the vertex count and the
/// vertices `x y z`; `#` starts a comment line. Errors name the problem.
pub fn parse_patches(text: &str) -> Result<Vec<BezierSurface>, String> {
    let mut numbers = text
        .lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .flat_map(str::split_whitespace);
    let mut next = |what: &str| -> Result<&str, String> {
        numbers
            .next()
            .ok_or_else(|| format!("the file ends before {what}"))
    };
    let count = |s: &str, what: &str| -> Result<usize, String> {
        s.parse::<usize>()
            .map_err(|_| format!("{what}: '{s}' is not a count"))
    };
    let patches = count(next("the patch count")?, "patch count")?;
    let mut indices = Vec::with_capacity(patches.min(1 << 16));
    for p in 0..patches {
        let mut row = [0usize; 16];
        for (k, slot) in row.iter_mut().enumerate() {
            let s = next(&format!("index {k} of patch {p}"))?;
            *slot = count(s, &format!("patch {p}, index {k}"))?;
        }
        indices.push(row);
    }
    let vertices = count(next("the vertex count")?, "vertex count")?;
    let mut points = Vec::with_capacity(vertices.min(1 << 20));
    for v in 0..vertices {
        let mut xyz = [0.0; 3];
        for (k, c) in xyz.iter_mut().enumerate() {
            let s = next(&format!("coordinate {k} of vertex {v}"))?;
            *c = s
                .parse::<f64>()
                .map_err(|_| format!("vertex {v}: '{s}' is not a number"))?;
        }
        points.push(Point3::from(xyz));
    }
    indices
        .iter()
        .enumerate()
        .map(|(p, row)| {
            let net = (0..4)
                .map(|i| {
                    (0..4)
                        .map(|j| {
                            let k = row[4 * i + j];
                            k.checked_sub(1)
                                .and_then(|k| points.get(k).copied())
                                .ok_or_else(|| {
                                    format!("patch {p}: vertex index {k} is not in 1..={vertices}")
                                })
                        })
                        .collect::<Result<Vec<_>, String>>()
                })
                .collect::<Result<Vec<_>, String>>()?;
            BezierSurface::new(net).map_err(|e| format!("patch {p}: {e}"))
        })
        .collect()
}

//! The single-patch shapes of the study and the benches: a gently curved
//! bicubic Bézier patch and a folded one (a ray can cross it several
//! times). The teapot comes from the shared test reader
//! (`tests/common/teapot.rs`).
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

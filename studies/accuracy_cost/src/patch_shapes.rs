//! The gently curved bicubic patch of the study and the benches (included
//! there by path, so both measure the same surface). The folded bicubic and
//! the teapot come from the shared test code (`tests/common`).

use revolve::BezierSurface;
use revolve::nalgebra::Point3;

/// A gently curved bicubic over the unit square: control point `(i, j)` at
/// `(i/3, j/3, 0.3 − 0.05(a² + b²) + 0.02ab)` with `a = i − 1.5`,
/// `b = j − 1.5` (a low dome with a slight twist), so most rays through its
/// box cross it once.
pub fn gentle_bicubic() -> BezierSurface {
    let net: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (a, b) = (i as f64 - 1.5, j as f64 - 1.5);
                    let z = 0.3 - 0.05 * (a * a + b * b) + 0.02 * a * b;
                    Point3::new(i as f64 / 3.0, j as f64 / 3.0, z)
                })
                .collect()
        })
        .collect();
    BezierSurface::new(net).expect("a finite 4 × 4 net")
}

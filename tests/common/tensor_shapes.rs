//! Tensor-product test surfaces with closed forms.

use revolve::nalgebra::Point3;
use revolve::{BezierSurface, NurbsSurface};

/// The benches' folded bicubic patch: a sheared net whose inner points
/// alternate between heights ±0.4, so that a ray can meet it several times.
pub fn folded_bicubic() -> BezierSurface {
    let net = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (x, y) = (i as f64 / 3.0, j as f64 / 3.0);
                    let z = if (i + j) % 2 == 0 { 0.4 } else { -0.4 };
                    Point3::new(x + 0.3 * (j as f64 - 1.5).powi(2), y, z)
                })
                .collect()
        })
        .collect();
    BezierSurface::new(net).unwrap()
}

/// The octant x, y, z ≥ 0 of the sphere of radius `r`: a quarter meridian
/// (pole to equator) in `u` times a quarter turn in `v`. The row `u = 0` is
/// the pole: a whole edge collapsed to one point.
pub fn sphere_octant(r: f64) -> NurbsSurface {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let meridian = [(0.0, r, 1.0), (r, r, h), (r, 0.0, 1.0)];
    let turn = [(1.0, 0.0, 1.0), (1.0, 1.0, h), (0.0, 1.0, 1.0)];
    let points = meridian
        .iter()
        .map(|&(x, z, _)| {
            turn.iter()
                .map(|&(c, s, _)| Point3::new(x * c, x * s, z))
                .collect()
        })
        .collect();
    let weights = meridian
        .iter()
        .map(|&(_, _, a)| turn.iter().map(|&(_, _, b)| a * b).collect())
        .collect();
    let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new((2, 2), (k.clone(), k), points, weights).unwrap()
}

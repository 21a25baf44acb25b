//! Tensor-product test surfaces with closed forms.

use revolve::NurbsSurface;
use revolve::nalgebra::Point3;

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

//! Tensor-product test surfaces with closed forms.

use revolve::nalgebra::{Point3, Vector3};
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

/// The quarter `x, y ≥ 0` of the cylinder of radius `r` about the `z` axis,
/// `0 ≤ z ≤ h`: degrees (2, 1), a quarter circle in `u` (control points
/// `(r, 0)`, `(r, r)`, `(0, r)`, weights `1, √½, 1`) times a straight line in
/// `v`. `S_u × S_v` points away from the axis.
pub fn quarter_cylinder(r: f64, h: f64) -> NurbsSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [(r, 0.0, 1.0), (r, r, w), (0.0, r, 1.0)];
    let points = arc
        .iter()
        .map(|&(x, y, _)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, h)])
        .collect();
    let weights = arc.iter().map(|&(_, _, a)| vec![a, a]).collect();
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 1.0, 1.0];
    NurbsSurface::new((2, 1), (ku, kv), points, weights).unwrap()
}

/// The real roots of `a·t² + b·t + c` (ascending, stable formula; the
/// linear root when `a = 0`) and the discriminant relative to `b² + |4ac|`
/// (near 0: a double root, a tangent ray).
pub fn quadratic_roots(a: f64, b: f64, c: f64) -> (Vec<f64>, f64) {
    if a == 0.0 {
        return (if b != 0.0 { vec![-c / b] } else { vec![] }, 1.0);
    }
    let disc = b * b - 4.0 * a * c;
    let relative = disc / (b * b + (4.0 * a * c).abs());
    if disc < 0.0 {
        return (vec![], relative);
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut roots = if q != 0.0 {
        vec![q / a, c / q]
    } else {
        vec![0.0, 0.0]
    };
    roots.sort_by(f64::total_cmp);
    (roots, relative)
}

/// Where the line `o + t·d` meets the sphere `|p| = r`: the roots `t` of
/// `|d|²t² + 2(o·d)t + |o|² − r²` and the relative discriminant.
pub fn sphere_roots(r: f64, origin: &Point3<f64>, dir: &Vector3<f64>) -> (Vec<f64>, f64) {
    let o = origin.coords;
    quadratic_roots(
        dir.norm_squared(),
        2.0 * o.dot(dir),
        o.norm_squared() - r * r,
    )
}

/// Where the line `o + t·d` meets the cylinder `x² + y² = r²`: the roots of
/// the quadratic in the `xy` components, and the relative discriminant.
pub fn cylinder_roots(r: f64, origin: &Point3<f64>, dir: &Vector3<f64>) -> (Vec<f64>, f64) {
    let (o, d) = (origin.xy().coords, dir.xy());
    quadratic_roots(d.norm_squared(), 2.0 * o.dot(&d), o.norm_squared() - r * r)
}

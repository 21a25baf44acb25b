//! The ray–sphere quadratic and the ray–torus quartic with exact
//! coefficients, solved exactly ([`exact_roots`](super::exact_roots)): the
//! references for rational revolutions, independent of the library.
//!
//! Along `p(t) = o + t·d` (every `f64` read as the exact rational it is):
//! - the sphere of radius `R` about the origin, `|p|² − R² = 0`, a quadratic;
//! - the torus about the `y` axis through the origin, of major radius `R`
//!   (the tube's centre circle lies in the plane `y = 0`) and tube radius
//!   `r < R`: `(|p|² + R² − r²)² − 4R²(p_x² + p_z²) = 0`, a quartic.
//!
//! The inputs are scaled to integers by one power of two (the roots `t` do
//! not change), so the coefficients are integers. The roots are the exact
//! surfaces' hits; a NURBS sphere or torus built from quarter arcs with
//! weight `√2/2` rounded to `f64` differs from them by about `1e-16` of its
//! size.

use super::exact_roots::{Poly, RealRoots, common_integers, product, scaled, sum};
use num_bigint::BigInt;
use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

/// The ray's origin and direction and the given lengths as integers over
/// one power of two: `([o, d], lengths)`.
fn scaled_inputs(ray: &Ray, lengths: &[f64]) -> Option<([[BigInt; 3]; 2], Vec<BigInt>)> {
    let (o, d) = (ray.origin, ray.dir);
    let mut values = vec![o.x, o.y, o.z, d.x, d.y, d.z];
    values.extend_from_slice(lengths);
    let mut n = common_integers(&values)?.into_iter();
    let mut three = || -> [BigInt; 3] { [(); 3].map(|_| n.next().expect("six values")) };
    let od = [three(), three()];
    Some((od, n.collect()))
}

/// `|u + t·v|²` over the components `axes`, in ascending powers of `t`.
fn squared_norm_along(u: &[BigInt; 3], v: &[BigInt; 3], axes: &[usize]) -> Poly {
    let mut out = vec![BigInt::from(0); 3];
    for &i in axes {
        out[0] += &u[i] * &u[i];
        out[1] += &u[i] * &v[i] * 2;
        out[2] += &v[i] * &v[i];
    }
    out
}

/// A positive multiple of `|o + t·d|² − R²` (ascending); `None` for a
/// non-finite input.
pub fn sphere_polynomial(ray: &Ray, radius: f64) -> Option<Poly> {
    let ([o, d], r) = scaled_inputs(ray, &[radius])?;
    let mut p = squared_norm_along(&o, &d, &[0, 1, 2]);
    p[0] -= &r[0] * &r[0];
    Some(p)
}

/// A positive multiple of `(|p|² + R² − r²)² − 4R²(p_x² + p_z²)`,
/// `p = o + t·d` (ascending); `None` for a non-finite input.
pub fn torus_polynomial(ray: &Ray, major: f64, minor: f64) -> Option<Poly> {
    let ([o, d], radii) = scaled_inputs(ray, &[major, minor])?;
    let (big, small) = (&radii[0], &radii[1]);
    let mut s = squared_norm_along(&o, &d, &[0, 1, 2]);
    s[0] += big * big - small * small;
    let radial = squared_norm_along(&o, &d, &[0, 2]);
    let four_r2: BigInt = big * big * 4;
    Some(sum(&product(&s, &s), &scaled(&radial, &-four_r2)))
}

/// An exact surface of closed form about the `y` axis through the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClosedForm {
    /// The sphere of this radius about the origin.
    Sphere { radius: f64 },
    /// The torus whose tube of radius `minor` follows the circle of radius
    /// `major > minor` in the plane `y = 0`.
    Torus { major: f64, minor: f64 },
}

impl ClosedForm {
    /// The roots `t` of the ray's equation, exactly; `None` for a
    /// non-finite input or an equation that vanishes identically.
    pub fn roots(&self, ray: &Ray) -> Option<RealRoots> {
        let p = match *self {
            ClosedForm::Sphere { radius } => sphere_polynomial(ray, radius),
            ClosedForm::Torus { major, minor } => torus_polynomial(ray, major, minor),
        }?;
        RealRoots::new(&p)
    }

    /// The largest absolute coordinate of the surface.
    pub fn scale(&self) -> f64 {
        match *self {
            ClosedForm::Sphere { radius } => radius,
            ClosedForm::Torus { major, minor } => major + minor,
        }
    }

    /// The outward unit normal at `p` on the surface (off it, that of the
    /// nearest surface point; for the torus, `p` off the axis).
    pub fn outward(&self, p: &Point3<f64>) -> Vector3<f64> {
        match *self {
            ClosedForm::Sphere { .. } => p.coords.normalize(),
            ClosedForm::Torus { major, .. } => {
                let rho = p.x.hypot(p.z);
                let centre = Vector3::new(p.x / rho, 0.0, p.z / rho) * major;
                (p.coords - centre).normalize()
            }
        }
    }
}

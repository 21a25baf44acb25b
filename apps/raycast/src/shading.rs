//! Phong shading as the course framework computes it.
//!
//! For one light with colour `c` seen in the unit direction `L` from the
//! shading point, unit normal `N` facing the viewer (`N·V > 0`), unit view
//! direction `V = −ray direction`, and `R = 2(N·L)N − L` (the mirror image
//! of `L`):
//!
//! ```text
//! colour = c ⊙ (kd · max(0, N·L) + ks · max(0, V·R)^shininess)
//! ```
//!
//! with no ambient term and no fall-off with distance. As in the framework,
//! the specular term is not gated by `N·L`; `0^0 = 1`, so a zero shininess
//! gives `ks` wherever `V·R ≥ 0`. `kd` is the material's diffuse colour, or
//! the texture's colour at the hit when the material has one
//! ([`diffuse_at`]).

use revolve::nalgebra::Vector3;

use crate::scene::{Color, Material};
use crate::texture;

/// The Phong colour of one light (see the module docs).
#[inline]
pub fn phong(
    kd: &Color,
    material: &Material,
    n: &Vector3<f64>,
    v: &Vector3<f64>,
    l: &Vector3<f64>,
    light: &Color,
) -> Color {
    let n_dot_l = n.dot(l);
    let diffuse = kd * n_dot_l.max(0.0);
    let r = n * (2.0 * n_dot_l) - l;
    let specular = material.specular * v.dot(&r).max(0.0).powf(material.shininess);
    light.component_mul(&(diffuse + specular))
}

/// The diffuse colour `kd` at a hit: the texture at `uv` when the material
/// has one and textures are on, the material's `diffuseColor` otherwise.
#[inline]
pub fn diffuse_at(material: &Material, uv: (f64, f64), textures: bool) -> Color {
    match &material.texture {
        Some(t) if textures => texture::lookup(t, uv.0, uv.1),
        _ => material.diffuse,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn head_on_light_gives_diffuse_plus_specular() {
        let m = Material {
            diffuse: Color::new(0.5, 0.2, 0.1),
            specular: Color::new(0.3, 0.3, 0.3),
            shininess: 10.0,
            ..Material::default()
        };
        let z = Vector3::z();
        let c = phong(&m.diffuse, &m, &z, &z, &z, &Color::new(1.0, 0.5, 1.0));
        assert!((c - Color::new(0.8, 0.25, 0.4)).norm() < 1e-15);
    }

    #[test]
    fn oblique_light_follows_the_formula() {
        let m = Material {
            diffuse: Color::new(1.0, 1.0, 1.0),
            specular: Color::new(1.0, 1.0, 1.0),
            shininess: 2.0,
            ..Material::default()
        };
        let n = Vector3::z();
        let l = Vector3::new(0.6, 0.0, 0.8);
        let v = Vector3::new(-0.6, 0.0, 0.8); // along R: V·R = 1
        let c = phong(&m.diffuse, &m, &n, &v, &l, &Color::new(1.0, 1.0, 1.0));
        assert!((c.x - 1.8).abs() < 1e-12);
        let v = Vector3::z(); // V·R = 0.8
        let c = phong(&m.diffuse, &m, &n, &v, &l, &Color::new(1.0, 1.0, 1.0));
        assert!((c.x - (0.8 + 0.64)).abs() < 1e-12);
    }

    #[test]
    fn light_below_the_surface_gives_no_diffuse() {
        let m = Material {
            diffuse: Color::new(1.0, 1.0, 1.0),
            ..Material::default()
        };
        let c = phong(
            &m.diffuse,
            &m,
            &Vector3::z(),
            &Vector3::z(),
            &-Vector3::z(),
            &Color::new(1.0, 1.0, 1.0),
        );
        assert_eq!(c, Color::zeros());
    }
}

//! Texture lookup: the diffuse colour at a hit's `(u, v)`.
//!
//! `u` runs across the image from its left edge (0) to its right edge (1),
//! `v` from its bottom edge (0) to its top edge (1) (the image is stored
//! with row 0 at the top). Texel `(i, j)` has its centre at
//! `((i + ½)/w, 1 − (j + ½)/h)`, and the lookup interpolates bilinearly
//! between the four nearest centres. Coordinates outside `[0, 1]` and the
//! half texel along each edge clamp to the edge texels, so the image is not
//! wrapped around (a seam would appear on a surface of revolution otherwise).
//! A NaN coordinate reads the edge texel; an empty texture reads black.

use crate::scene::{Color, Texture};

/// The bilinearly interpolated colour of `texture` at `(u, v)`.
pub fn lookup(texture: &Texture, u: f64, v: f64) -> Color {
    let (w, h) = (texture.width as usize, texture.height as usize);
    if w == 0 || h == 0 || texture.pixels.len() < w * h {
        return Color::zeros();
    }
    // Continuous texel coordinates: texel centres at integers.
    let x = (u * w as f64 - 0.5).clamp(0.0, (w - 1) as f64);
    let y = ((1.0 - v) * h as f64 - 0.5).clamp(0.0, (h - 1) as f64);
    // `as usize` saturates, and NaN becomes 0.
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
    let (fx, fy) = if x.is_nan() || y.is_nan() {
        (0.0, 0.0)
    } else {
        (x - x0 as f64, y - y0 as f64)
    };
    let at = |i: usize, j: usize| texture.pixels[j * w + i];
    let top = at(x0, y0) * (1.0 - fx) + at(x1, y0) * fx;
    let bottom = at(x0, y1) * (1.0 - fx) + at(x1, y1) * fx;
    top * (1.0 - fy) + bottom * fy
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_by_two() -> Texture {
        // Row 0 (top): red, green; row 1 (bottom): blue, white.
        Texture {
            width: 2,
            height: 2,
            pixels: vec![
                Color::new(1.0, 0.0, 0.0),
                Color::new(0.0, 1.0, 0.0),
                Color::new(0.0, 0.0, 1.0),
                Color::new(1.0, 1.0, 1.0),
            ],
        }
    }

    #[test]
    fn texel_centres_read_their_texel() {
        let t = two_by_two();
        assert_eq!(lookup(&t, 0.25, 0.75), Color::new(1.0, 0.0, 0.0));
        assert_eq!(lookup(&t, 0.75, 0.75), Color::new(0.0, 1.0, 0.0));
        assert_eq!(lookup(&t, 0.25, 0.25), Color::new(0.0, 0.0, 1.0));
        assert_eq!(lookup(&t, 0.75, 0.25), Color::new(1.0, 1.0, 1.0));
    }

    #[test]
    fn the_middle_averages_the_four_texels_and_edges_clamp() {
        let t = two_by_two();
        let c = lookup(&t, 0.5, 0.5);
        assert!((c - Color::new(0.5, 0.5, 0.5)).norm() < 1e-15);
        assert_eq!(lookup(&t, -3.0, 7.0), Color::new(1.0, 0.0, 0.0));
        assert_eq!(lookup(&t, 1.0, 0.0), Color::new(1.0, 1.0, 1.0));
        assert_eq!(lookup(&t, f64::NAN, f64::NAN), Color::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn an_empty_texture_is_black() {
        let t = Texture {
            width: 0,
            height: 0,
            pixels: vec![],
        };
        assert_eq!(lookup(&t, 0.5, 0.5), Color::zeros());
    }
}

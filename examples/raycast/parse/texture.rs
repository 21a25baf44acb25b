//! Image textures: a PNG file to a [`Texture`] in linear `[0, 1]`.
//!
//! Bytes map to `byte / 255` with no gamma decoding, matching the course
//! framework, which writes its colours linearly too. Row 0 is the top row;
//! an alpha channel is ignored and 16-bit images are reduced to 8 bits.

use std::path::Path;

use crate::scene::{Color, Texture};

/// Reads the image at `path` (PNG).
pub(super) fn read_texture(path: &Path) -> Result<Texture, String> {
    let image = image::open(path).map_err(|e| e.to_string())?.to_rgb8();
    let (width, height) = image.dimensions();
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    let pixels = image
        .pixels()
        .map(|p| Color::new(p[0].into(), p[1].into(), p[2].into()) / 255.0)
        .collect();
    Ok(Texture {
        width,
        height,
        pixels,
    })
}

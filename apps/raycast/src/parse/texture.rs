//! Image textures: a PNG file to a [`Texture`] in linear `[0, 1]`.
//!
//! Bytes map to `byte / 255` with no gamma decoding, matching the course
//! framework, which writes its colours linearly too. Row 0 is the top row;
//! an alpha channel is ignored and 16-bit images are reduced to 8 bits.
//!
//! A texture is at most [`MAX_TEXTURE_SIDE`] pixels on a side and
//! [`MAX_TEXTURE_PIXELS`] in all, checked on the file's header before any
//! pixel is decoded; the texels are allocated fallibly.

use std::path::Path;

use crate::png_file;
use crate::scene::{Color, Texture};

/// The longest side of a texture, in pixels.
pub(super) const MAX_TEXTURE_SIDE: u32 = 16384;
/// The most pixels of a texture (4096 × 4096; 384 MiB as colours).
pub(super) const MAX_TEXTURE_PIXELS: u64 = 1 << 24;

/// Reads the image at `path` (PNG).
pub(super) fn read_texture(path: &Path) -> Result<Texture, String> {
    let image = png_file::read(path, texture_size)?;
    let (width, height) = (image.width, image.height);
    let count = u64::from(width) * u64::from(height);
    let mut pixels = Vec::new();
    pixels
        .try_reserve_exact(count as usize)
        .map_err(|e| format!("cannot allocate the texture ({width}×{height} pixels): {e}"))?;
    pixels.extend(
        image
            .pixels()
            .map(|[r, g, b]| Color::new(r.into(), g.into(), b.into()) / 255.0),
    );
    Ok(Texture {
        width,
        height,
        pixels,
    })
}

/// Refuses an empty texture and one over the limits, from its size.
fn texture_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    if width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "the image is {width}×{height} pixels, over the limit of {MAX_TEXTURE_SIDE} pixels \
             a side"
        ));
    }
    let count = u64::from(width) * u64::from(height);
    if count > MAX_TEXTURE_PIXELS {
        return Err(format!(
            "the image is {width}×{height} = {count} pixels, more than the largest texture, \
             {MAX_TEXTURE_PIXELS} pixels"
        ));
    }
    Ok(())
}

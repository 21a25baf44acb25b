//! Image textures: a PNG file to a [`Texture`] in linear `[0, 1]`.
//!
//! Bytes map to `byte / 255` with no gamma decoding, matching the course
//! framework, which writes its colours linearly too. Row 0 is the top row;
//! an alpha channel is ignored and 16-bit images are reduced to 8 bits.
//!
//! A texture is at most [`MAX_TEXTURE_SIDE`] pixels on a side and
//! [`MAX_TEXTURE_PIXELS`] in all (the decoder refuses larger sides before
//! allocating; the texels are allocated fallibly).

use std::path::Path;

use image::{ImageReader, Limits};

use crate::scene::{Color, Texture};

/// The longest side of a texture, in pixels.
pub(super) const MAX_TEXTURE_SIDE: u32 = 16384;
/// The most pixels of a texture (4096 × 4096; 384 MiB as colours).
pub(super) const MAX_TEXTURE_PIXELS: u64 = 1 << 24;

/// Reads the image at `path` (PNG).
pub(super) fn read_texture(path: &Path) -> Result<Texture, String> {
    let mut reader = ImageReader::open(path).map_err(|e| e.to_string())?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    reader.limits(limits);
    let image = reader.decode().map_err(|e| e.to_string())?;
    let (width, height) = (image.width(), image.height());
    if width == 0 || height == 0 {
        return Err("the image is empty".into());
    }
    let count = u64::from(width) * u64::from(height);
    if count > MAX_TEXTURE_PIXELS {
        return Err(format!(
            "the image is {width}×{height} = {count} pixels, more than the largest texture, \
             {MAX_TEXTURE_PIXELS} pixels"
        ));
    }
    let image = image.to_rgb8();
    let mut pixels = Vec::new();
    pixels
        .try_reserve_exact(count as usize)
        .map_err(|e| format!("cannot allocate the texture ({width}×{height} pixels): {e}"))?;
    pixels.extend(
        image
            .pixels()
            .map(|p| Color::new(p[0].into(), p[1].into(), p[2].into()) / 255.0),
    );
    Ok(Texture {
        width,
        height,
        pixels,
    })
}

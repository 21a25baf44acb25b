//! PNG files in and out, as 8-bit RGB.
//!
//! Reading accepts every PNG colour type and depth: palettes and depths
//! below 8 bits are expanded, grey is copied to the three channels, an
//! alpha channel is dropped (not blended), and 16-bit samples are rounded
//! to the nearest 8-bit value, `round(c · 255 / 65535)`. Writing makes an
//! 8-bit RGB PNG (balanced compression, adaptive filtering).

use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::Path;

/// An 8-bit RGB image, row 0 on top, three bytes a pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8 {
    pub width: u32,
    pub height: u32,
    pub bytes: Vec<u8>,
}

impl Rgb8 {
    /// The pixel in column `x` of row `y`.
    #[cfg(test)]
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.bytes[i], self.bytes[i + 1], self.bytes[i + 2]]
    }

    /// The pixels in row order.
    pub fn pixels(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        self.bytes.chunks_exact(3).map(|p| [p[0], p[1], p[2]])
    }
}

/// Reads the PNG at `path`; an error names the problem. `accept` sees the
/// size `(width, height)` from the header, before any pixel is allocated,
/// and may refuse it with an error.
pub fn read(
    path: &Path,
    accept: impl FnOnce(u32, u32) -> Result<(), String>,
) -> Result<Rgb8, String> {
    let file = File::open(path).map_err(|e| e.to_string())?;
    let mut decoder = png::Decoder::new(BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let (width, height) = (reader.info().width, reader.info().height);
    accept(width, height)?;
    let size = reader
        .output_buffer_size()
        .ok_or("the image is too large to decode")?;
    let mut raw = Vec::new();
    raw.try_reserve_exact(size)
        .map_err(|e| format!("cannot allocate the image ({width}×{height} pixels): {e}"))?;
    raw.resize(size, 0);
    let frame = reader.next_frame(&mut raw).map_err(|e| e.to_string())?;
    let channels = frame.color_type.samples();
    let sample_bytes = match frame.bit_depth {
        png::BitDepth::Eight => 1,
        png::BitDepth::Sixteen => 2,
        depth => return Err(format!("unexpected bit depth {depth:?} after expansion")),
    };
    let sample = |row: &[u8], i: usize| -> u8 {
        if sample_bytes == 1 {
            row[i]
        } else {
            let c = u32::from(u16::from_be_bytes([row[2 * i], row[2 * i + 1]]));
            // round(c · 255 / 65535), since 65535 = 255 · 257.
            ((c + 128) / 257) as u8
        }
    };
    let pixel_count = width as usize * height as usize;
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(3 * pixel_count)
        .map_err(|e| format!("cannot allocate the image ({width}×{height} pixels): {e}"))?;
    for row in raw[..frame.buffer_size()].chunks_exact(frame.line_size) {
        for x in 0..width as usize {
            let first = x * channels;
            if channels >= 3 {
                bytes.extend([
                    sample(row, first),
                    sample(row, first + 1),
                    sample(row, first + 2),
                ]);
            } else {
                let grey = sample(row, first);
                bytes.extend([grey; 3]);
            }
        }
    }
    Ok(Rgb8 {
        width,
        height,
        bytes,
    })
}

/// Accepts every size.
#[cfg(test)]
pub fn any_size(_width: u32, _height: u32) -> Result<(), String> {
    Ok(())
}

/// Writes `image` to `path` as an 8-bit RGB PNG.
pub fn write(path: &Path, image: &Rgb8) -> Result<(), String> {
    write_raw(
        path,
        image.width,
        image.height,
        png::ColorType::Rgb,
        &image.bytes,
    )
}

/// Writes 8-bit samples of colour type `color` (rows on top of each other).
pub fn write_raw(
    path: &Path,
    width: u32,
    height: u32,
    color: png::ColorType,
    bytes: &[u8],
) -> Result<(), String> {
    let file = File::create(path).map_err(|e| e.to_string())?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), width, height);
    encoder.set_color(color);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Balanced);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
    writer.write_image_data(bytes).map_err(|e| e.to_string())?;
    writer.finish().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::temp_dir::TempDir;

    /// Writes a PNG of any colour type and depth with the encoder itself.
    fn write_any(
        path: &Path,
        (width, height): (u32, u32),
        color: png::ColorType,
        depth: png::BitDepth,
        palette: Option<Vec<u8>>,
        bytes: &[u8],
    ) {
        let mut encoder = png::Encoder::new(File::create(path).unwrap(), width, height);
        encoder.set_color(color);
        encoder.set_depth(depth);
        if let Some(palette) = palette {
            encoder.set_palette(palette);
        }
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(bytes).unwrap();
    }

    #[test]
    fn rgb_round_trips_bit_for_bit() {
        let dir = TempDir::new("rgb");
        let image = Rgb8 {
            width: 3,
            height: 2,
            bytes: (0..18).map(|i| (i * 14) as u8).collect(),
        };
        let path = dir.0.join("a.png");
        write(&path, &image).unwrap();
        assert_eq!(read(&path, any_size).unwrap(), image);
        assert_eq!(image.pixel(2, 1), [210, 224, 238]);
    }

    #[test]
    fn grey_alpha_palette_and_sixteen_bits_become_rgb8() {
        let dir = TempDir::new("kinds");
        let path = dir.0.join("k.png");
        // Grey with alpha: the grey is copied, the alpha dropped.
        write_any(
            &path,
            (2, 1),
            png::ColorType::GrayscaleAlpha,
            png::BitDepth::Eight,
            None,
            &[10, 0, 200, 255],
        );
        assert_eq!(
            read(&path, any_size).unwrap().bytes,
            [10, 10, 10, 200, 200, 200]
        );
        // RGBA: alpha dropped, not blended.
        write_any(
            &path,
            (1, 1),
            png::ColorType::Rgba,
            png::BitDepth::Eight,
            None,
            &[1, 2, 3, 0],
        );
        assert_eq!(read(&path, any_size).unwrap().bytes, [1, 2, 3]);
        // A 1-bit palette image: two entries, pixels 1 then 0.
        write_any(
            &path,
            (2, 1),
            png::ColorType::Indexed,
            png::BitDepth::One,
            Some(vec![9, 8, 7, 60, 70, 80]),
            &[0b1000_0000],
        );
        assert_eq!(read(&path, any_size).unwrap().bytes, [60, 70, 80, 9, 8, 7]);
        // 16-bit RGB, rounded to the nearest 8-bit value (not the high
        // byte): 0xFF00 / 257 = 254.0 → 254; 0x00FF / 257 = 0.99 → 1;
        // 0xFFFF → 255.
        write_any(
            &path,
            (1, 1),
            png::ColorType::Rgb,
            png::BitDepth::Sixteen,
            None,
            &[0xFF, 0x00, 0x00, 0xFF, 0xFF, 0xFF],
        );
        assert_eq!(read(&path, any_size).unwrap().bytes, [254, 1, 255]);
    }

    #[test]
    fn the_size_is_seen_before_the_pixels() {
        let dir = TempDir::new("wide");
        let path = dir.0.join("w.png");
        write_raw(&path, 17, 1, png::ColorType::Rgb, &[0; 51]).unwrap();
        let refuse = |w, h| Err(format!("{w}×{h} is over the limit"));
        assert_eq!(read(&path, refuse).unwrap_err(), "17×1 is over the limit");
        assert_eq!(read(&path, any_size).unwrap().width, 17);
    }

    #[test]
    fn a_file_that_is_no_png_is_an_error() {
        let dir = TempDir::new("bad");
        let path = dir.0.join("b.png");
        std::fs::write(&path, b"this is not a PNG file").unwrap();
        assert!(read(&path, any_size).is_err());
        assert!(read(&dir.0.join("missing.png"), any_size).is_err());
    }
}

//! From linear radiance to an 8-bit PNG.
//!
//! - [`ToneMap::Clamp`] (the course framework's output): each channel is
//!   clamped to `[0, 1]`, multiplied by 255 and truncated to an integer, as
//!   the framework's `int(c * 255)`; no gamma. NaN writes 0.
//! - [`ToneMap::Reinhard`] (path tracing on request): `c / (1 + c)` per
//!   channel, then the sRGB transfer curve (`12.92 c` below 0.0031308,
//!   `1.055 c^(1/2.4) − 0.055` above), rounded to the nearest of 0…255.

use std::path::Path;

use crate::png_file::{self, Rgb8};
use crate::render::Image;
use crate::scene::ToneMap;

/// One channel's 8-bit value.
pub fn encode(c: f64, tone_map: ToneMap) -> u8 {
    if c.is_nan() {
        return 0;
    }
    match tone_map {
        ToneMap::Clamp => (c.clamp(0.0, 1.0) * 255.0) as u8,
        ToneMap::Reinhard => {
            let c = c.max(0.0);
            let x = if c.is_infinite() { 1.0 } else { c / (1.0 + c) };
            let s = if x <= 0.003_130_8 {
                12.92 * x
            } else {
                1.055 * x.powf(1.0 / 2.4) - 0.055
            };
            (s.clamp(0.0, 1.0) * 255.0).round() as u8
        }
    }
}

/// The image as 8-bit RGB; an error when its bytes cannot be allocated.
pub fn to_rgb8(image: &Image, tone_map: ToneMap) -> Result<Rgb8, String> {
    let mut bytes = Vec::new();
    bytes
        .try_reserve_exact(3 * image.pixels.len())
        .map_err(|e| format!("cannot allocate the 8-bit image: {e}"))?;
    for c in &image.pixels {
        bytes.extend([
            encode(c.x, tone_map),
            encode(c.y, tone_map),
            encode(c.z, tone_map),
        ]);
    }
    if bytes.len() as u64 != 3 * u64::from(image.width) * u64::from(image.height) {
        return Err("the image's pixels do not match its size".to_string());
    }
    Ok(Rgb8 {
        width: image.width,
        height: image.height,
        bytes,
    })
}

/// Checks early that `path` can be written (creating its folder), so a
/// long render does not end in an error. The file is created if missing
/// and left as it is otherwise.
pub fn check_writable(path: &Path) -> Result<(), String> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create the folder {}: {e}", dir.display()))?;
    }
    std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(path)
        .map(|_| ())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Writes the image to `path` as PNG (whatever the file's extension).
pub fn write_png(image: &Image, tone_map: ToneMap, path: &Path) -> Result<(), String> {
    check_writable(path)?;
    png_file::write(path, &to_rgb8(image, tone_map)?)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Color;

    #[test]
    fn clamp_truncates_like_the_framework() {
        assert_eq!(encode(0.0, ToneMap::Clamp), 0);
        assert_eq!(encode(1.0, ToneMap::Clamp), 255);
        assert_eq!(encode(7.0, ToneMap::Clamp), 255);
        assert_eq!(encode(-1.0, ToneMap::Clamp), 0);
        assert_eq!(encode(0.5, ToneMap::Clamp), 127);
        assert_eq!(encode(f64::NAN, ToneMap::Clamp), 0);
    }

    #[test]
    fn reinhard_compresses_and_applies_srgb() {
        assert_eq!(encode(0.0, ToneMap::Reinhard), 0);
        // 1 → 0.5 → sRGB 0.7354 → 188.
        assert_eq!(encode(1.0, ToneMap::Reinhard), 188);
        assert_eq!(encode(f64::INFINITY, ToneMap::Reinhard), 255);
        assert!(encode(100.0, ToneMap::Reinhard) < 255);
    }

    #[test]
    fn png_round_trips_through_a_file() {
        let image = Image {
            width: 2,
            height: 1,
            pixels: vec![Color::new(1.0, 0.0, 0.2), Color::new(0.0, 0.5, 1.0)],
        };
        let dir = std::env::temp_dir().join(format!("raycast-png-{}", std::process::id()));
        let path = dir.join("t.png");
        write_png(&image, ToneMap::Clamp, &path).unwrap();
        let back = png_file::read(&path, png_file::any_size).unwrap();
        assert_eq!(back.pixel(0, 0), [255, 0, 51]);
        assert_eq!(back.pixel(1, 0), [0, 127, 255]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn unwritable_paths_are_reported() {
        let err = check_writable(Path::new("/proc/no/such/dir/x.png")).unwrap_err();
        assert!(err.starts_with("cannot"), "{err}");
    }
}

//! `PerspectiveCamera { center P  direction V  up V  angle DEG  width N  height N }`
//! (keys in any order, each required once). `angle` is the vertical field of
//! view in degrees, in `(0, 180)`; under 2 degrees it draws a warning.
//! `width` and `height` are at most [`MAX_IMAGE_SIDE`] pixels each and
//! [`crate::render::MAX_IMAGE_PIXELS`] together.

use super::cursor::{Cursor, Result};
use super::lexer::Pos;
use crate::render::{MAX_IMAGE_SIDE, check_size};
use crate::scene::Camera;

const BLOCK: &str = "PerspectiveCamera";
const KEYS: &[&str] = &["center", "direction", "up", "angle", "width", "height"];

/// A field of view under this many degrees draws a warning: it is most
/// likely written in radians (a field of view in radians is under π, and
/// hardly anyone means a view narrower than 2°).
const MIN_PLAUSIBLE_ANGLE: f64 = 2.0;

/// An image side: a whole number from 1 to [`MAX_IMAGE_SIDE`], and where it
/// is.
fn side(c: &mut Cursor<'_>, what: &str) -> Result<(u32, Pos)> {
    let (n, at) = c.whole(what, 1)?;
    if n > MAX_IMAGE_SIDE {
        return Err(c.error(
            at,
            format!("'{what}' is {n} pixels, more than the largest side, {MAX_IMAGE_SIDE}"),
        ));
    }
    Ok((n, at))
}

/// Reads a camera block (after its keyword).
pub(super) fn camera(c: &mut Cursor<'_>) -> Result<Camera> {
    let open = c.open(BLOCK)?;
    let (mut center, mut direction, mut up, mut angle, mut width, mut height) =
        (None, None, None, None, None, None);
    let mut up_pos = open;
    while let Some(key) = c.key(BLOCK, open)? {
        match key.text {
            "center" => c.field(&mut center, key, BLOCK, Cursor::point)?,
            "direction" => c.field(&mut direction, key, BLOCK, Cursor::direction)?,
            "up" => {
                up_pos = c.here();
                c.field(&mut up, key, BLOCK, Cursor::direction)?;
            }
            "angle" => {
                let (pos, text) = (c.here(), c.peek().map_or("", |t| t.text));
                c.field(&mut angle, key, BLOCK, Cursor::number)?;
                match angle {
                    Some(a) if !(a > 0.0 && a < 180.0) => {
                        return Err(c.error(pos, "'angle' must be between 0 and 180 degrees"));
                    }
                    Some(a) if a < MIN_PLAUSIBLE_ANGLE => c.warn(
                        pos,
                        format!(
                            "angle {text} is under {MIN_PLAUSIBLE_ANGLE} degrees; the angle is in \
                             degrees ({text} rad = {:.1}°)",
                            a.to_degrees()
                        ),
                    ),
                    _ => {}
                }
            }
            "width" => c.field(&mut width, key, BLOCK, side)?,
            "height" => c.field(&mut height, key, BLOCK, side)?,
            _ => return Err(c.unknown(key, BLOCK, KEYS)),
        }
    }
    let (width, width_at) = c.required(width, "width", BLOCK)?;
    let (height, height_at) = c.required(height, "height", BLOCK)?;
    if let Err(e) = check_size(width, height) {
        // At the size given last, which made the image too large.
        let at = if (height_at.line, height_at.column) > (width_at.line, width_at.column) {
            height_at
        } else {
            width_at
        };
        return Err(c.error(at, e));
    }
    let camera = Camera {
        center: c.required(center, "center", BLOCK)?,
        direction: c.required(direction, "direction", BLOCK)?,
        up: c.required(up, "up", BLOCK)?,
        angle_degrees: c.required(angle, "angle", BLOCK)?,
        width,
        height,
    };
    if camera.direction.cross(&camera.up).norm()
        <= 1e-12 * camera.direction.norm() * camera.up.norm()
    {
        return Err(c.error(up_pos, "'up' must not be parallel to 'direction'"));
    }
    Ok(camera)
}

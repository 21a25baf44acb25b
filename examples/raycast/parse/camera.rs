//! `PerspectiveCamera { center P  direction V  up V  angle DEG  width N  height N }`
//! (keys in any order, each required once). `angle` is the vertical field of
//! view in degrees, in `(0, 180)`; under 2 degrees it draws a warning.

use super::cursor::{Cursor, Result};
use crate::scene::Camera;

const BLOCK: &str = "PerspectiveCamera";
const KEYS: &[&str] = &["center", "direction", "up", "angle", "width", "height"];

/// A field of view under this many degrees draws a warning: it is most
/// likely written in radians (a field of view in radians is under π, and
/// hardly anyone means a view narrower than 2°).
const MIN_PLAUSIBLE_ANGLE: f64 = 2.0;

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
            "width" => c.field(&mut width, key, BLOCK, |c, w| Ok(c.whole(w, 1)?.0))?,
            "height" => c.field(&mut height, key, BLOCK, |c, w| Ok(c.whole(w, 1)?.0))?,
            _ => return Err(c.unknown(key, BLOCK, KEYS)),
        }
    }
    let camera = Camera {
        center: c.required(center, "center", BLOCK)?,
        direction: c.required(direction, "direction", BLOCK)?,
        up: c.required(up, "up", BLOCK)?,
        angle_degrees: c.required(angle, "angle", BLOCK)?,
        width: c.required(width, "width", BLOCK)?,
        height: c.required(height, "height", BLOCK)?,
    };
    if camera.direction.cross(&camera.up).norm()
        <= 1e-12 * camera.direction.norm() * camera.up.norm()
    {
        return Err(c.error(up_pos, "'up' must not be parallel to 'direction'"));
    }
    Ok(camera)
}

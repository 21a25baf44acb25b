//! `Lights { numLights N  light… }` with
//!
//! ```text
//! DirectionalLight { direction V  color C }
//! PointLight       { position P  color C }
//! AreaLight        { corner P  edge1 V  edge2 V  color C }
//! ```
//!
//! `numLights`, when given, must equal the number of lights.

use super::counted::Counter;
use super::cursor::{Cursor, Result};
use super::shapes::check_parallelogram;
use crate::scene::Light;

const BLOCK: &str = "Lights";

/// Reads a `Lights` block (after its keyword).
pub(super) fn lights(c: &mut Cursor<'_>) -> Result<Vec<Light>> {
    let open = c.open(BLOCK)?;
    let mut lights = Vec::new();
    let mut count = Counter::new("numLights", "the block", "light");
    while let Some(key) = c.key(BLOCK, open)? {
        match key.text {
            "numLights" => count.read(c, key)?,
            "DirectionalLight" => lights.push(directional(c)?),
            "PointLight" => lights.push(point(c)?),
            "AreaLight" => lights.push(area(c)?),
            _ => {
                return Err(c.unknown(
                    key,
                    BLOCK,
                    &["numLights", "DirectionalLight", "PointLight", "AreaLight"],
                ));
            }
        }
    }
    count.check(c, lights.len())?;
    Ok(lights)
}

/// `DirectionalLight { direction V  color C }`.
fn directional(c: &mut Cursor<'_>) -> Result<Light> {
    const NAME: &str = "DirectionalLight";
    let open = c.open(NAME)?;
    let (mut direction, mut color) = (None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "direction" => c.field(&mut direction, key, NAME, Cursor::direction)?,
            "color" => c.field(&mut color, key, NAME, Cursor::color)?,
            _ => return Err(c.unknown(key, NAME, &["direction", "color"])),
        }
    }
    Ok(Light::Directional {
        direction: c.required(direction, "direction", NAME)?,
        color: c.required(color, "color", NAME)?,
    })
}

/// `PointLight { position P  color C }`.
fn point(c: &mut Cursor<'_>) -> Result<Light> {
    const NAME: &str = "PointLight";
    let open = c.open(NAME)?;
    let (mut position, mut color) = (None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "position" => c.field(&mut position, key, NAME, Cursor::point)?,
            "color" => c.field(&mut color, key, NAME, Cursor::color)?,
            _ => return Err(c.unknown(key, NAME, &["position", "color"])),
        }
    }
    Ok(Light::Point {
        position: c.required(position, "position", NAME)?,
        color: c.required(color, "color", NAME)?,
    })
}

/// `AreaLight { corner P  edge1 V  edge2 V  color C }`.
fn area(c: &mut Cursor<'_>) -> Result<Light> {
    const NAME: &str = "AreaLight";
    let open = c.open(NAME)?;
    let (mut corner, mut edge1, mut edge2, mut color) = (None, None, None, None);
    let mut edge2_pos = open;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "corner" => c.field(&mut corner, key, NAME, Cursor::point)?,
            "edge1" => c.field(&mut edge1, key, NAME, Cursor::direction)?,
            "edge2" => {
                edge2_pos = c.here();
                c.field(&mut edge2, key, NAME, Cursor::direction)?;
            }
            "color" => c.field(&mut color, key, NAME, Cursor::color)?,
            _ => return Err(c.unknown(key, NAME, &["corner", "edge1", "edge2", "color"])),
        }
    }
    let edge1 = c.required(edge1, "edge1", NAME)?;
    let edge2 = c.required(edge2, "edge2", NAME)?;
    check_parallelogram(c, &edge1, &edge2, edge2_pos)?;
    Ok(Light::Area {
        corner: c.required(corner, "corner", NAME)?,
        edge1,
        edge2,
        color: c.required(color, "color", NAME)?,
    })
}

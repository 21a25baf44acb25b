//! The steps of a `Transform` block, each an object-to-world matrix:
//!
//! ```text
//! Translate x y z
//! Scale x y z                  non-zero factors (negative ones mirror)
//! UniformScale s               non-zero
//! XRotate deg | YRotate deg | ZRotate deg     right-handed, in degrees
//! Rotate { x y z deg }         about a non-zero axis
//! ```
//!
//! Steps compose in the order written, `M = T₁·T₂·…`: the last one written
//! applies first to the object's points (the course framework's
//! `matrix = matrix * T`).

use revolve::nalgebra::{Matrix4, Rotation3, Unit, Vector3};

use super::cursor::{Cursor, Result};
use super::lexer::Token;

/// The transform keywords.
pub(super) const STEPS: &[&str] = &[
    "Translate",
    "Scale",
    "UniformScale",
    "XRotate",
    "YRotate",
    "ZRotate",
    "Rotate",
];

/// Reads the step whose keyword `key` was just consumed; `None` if `key` is
/// not a transform keyword.
pub(super) fn step(c: &mut Cursor<'_>, key: Token<'_>) -> Option<Result<Matrix4<f64>>> {
    let axis = match key.text {
        "Translate" => return Some(c.vector(key.text).map(|v| Matrix4::new_translation(&v))),
        "Scale" => return Some(scale(c, key)),
        "UniformScale" => {
            let at = c.here();
            return Some(c.number(key.text).and_then(|s| {
                if s == 0.0 {
                    Err(c.error(at, "'UniformScale' must not be zero"))
                } else {
                    Ok(Matrix4::new_scaling(s))
                }
            }));
        }
        "Rotate" => return Some(rotate(c)),
        "XRotate" => Vector3::x_axis(),
        "YRotate" => Vector3::y_axis(),
        "ZRotate" => Vector3::z_axis(),
        _ => return None,
    };
    Some(c.number(key.text).map(|degrees| rotation(axis, degrees)))
}

/// The rotation by `degrees` about `axis` (right-handed).
fn rotation(axis: Unit<Vector3<f64>>, degrees: f64) -> Matrix4<f64> {
    Rotation3::from_axis_angle(&axis, degrees.to_radians()).to_homogeneous()
}

/// `Scale x y z` (after the keyword).
fn scale(c: &mut Cursor<'_>, key: Token<'_>) -> Result<Matrix4<f64>> {
    let at = c.here();
    let s = c.vector(key.text)?;
    if s.iter().any(|&x| x == 0.0) {
        return Err(c.error(at, "'Scale' must not be zero in any coordinate"));
    }
    Ok(Matrix4::new_nonuniform_scaling(&s))
}

/// `Rotate { x y z deg }` (after the keyword).
fn rotate(c: &mut Cursor<'_>) -> Result<Matrix4<f64>> {
    let open = c.open("Rotate")?;
    let axis = c.direction("Rotate")?;
    let degrees = c.number("Rotate")?;
    c.close("Rotate", open)?;
    Ok(rotation(Unit::new_normalize(axis), degrees))
}

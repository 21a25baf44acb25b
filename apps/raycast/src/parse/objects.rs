//! Groups, transforms and the objects they hold, flattened into one list.
//!
//! ```text
//! Group     { numObjects N  ( MaterialIndex I | object )… }
//! Transform { step… object }                      exactly one object
//! object    = Group | Transform | primitive | RevSurface | BezierCurve | BsplineCurve
//!           | NurbsCurve | BezierSurface | BsplineSurface | BezierPatches
//! ```
//!
//! `numObjects`, when given, counts the objects (a nested group is one) and
//! must match. `MaterialIndex` applies to the objects after it until the next
//! one; a nested group or transform inherits the current index, and the group
//! that sets one restores the enclosing index at its end. Every object is
//! emitted with the product of the enclosing transforms (`None` for the
//! identity).

use revolve::nalgebra::Matrix4;

use super::counted::Counter;
use super::cursor::{Cursor, Result};
use super::curves::{CONSTRUCTED, CURVES, constructed_surface, rev_surface, tube};
use super::keywords::OBJECTS;
use super::lexer::{Pos, Token};
use super::resources::Resources;
use super::shapes::primitive;
use super::surfaces::{SURFACES, bezier_patches, surface};
use super::transform::{STEPS, step};
use crate::scene::{Object, Shape};

/// The deepest nesting of `Group`s and `Transform`s accepted (the top-level
/// group counts as 1).
pub const MAX_NESTING: usize = 200;

/// What the enclosing groups and transforms impose on an object.
#[derive(Debug, Clone, Copy)]
pub(super) struct Frame {
    /// The product of the enclosing transforms.
    pub(super) transform: Matrix4<f64>,
    /// The material index in force.
    pub(super) material: usize,
    /// How many groups and transforms enclose the object.
    pub(super) depth: usize,
}

impl Frame {
    /// The frame of the top-level group's contents: identity, material 0,
    /// depth 1.
    pub(super) fn root() -> Self {
        Frame {
            transform: Matrix4::identity(),
            material: 0,
            depth: 1,
        }
    }

    /// The frame inside the group or transform whose keyword `key` was just
    /// read in this frame: one level deeper, or an error beyond
    /// [`MAX_NESTING`].
    fn nested(self, c: &Cursor<'_>, key: Token<'_>) -> Result<Self> {
        if self.depth >= MAX_NESTING {
            return Err(c.error(
                key.pos,
                format!(
                    "this {} is nested more than {MAX_NESTING} deep (Groups and Transforms nest \
                     at most {MAX_NESTING} deep)",
                    key.text
                ),
            ));
        }
        Ok(Frame {
            depth: self.depth + 1,
            ..self
        })
    }
}

/// The flattened objects and the material indices they use (with where each
/// index is written, to check them once all materials are known).
#[derive(Debug, Default)]
pub(super) struct Flat {
    /// Every object, in file order.
    pub(super) objects: Vec<Object>,
    /// Each `MaterialIndex` value and its position.
    pub(super) material_uses: Vec<(usize, Pos)>,
}

/// Reads a `Group` block (after its keyword) into `out`.
pub(super) fn group(
    c: &mut Cursor<'_>,
    res: &mut Resources,
    out: &mut Flat,
    frame: Frame,
) -> Result<()> {
    const NAME: &str = "Group";
    let open = c.open(NAME)?;
    let mut count = Counter::new("numObjects", "the group", "object");
    let mut frame = frame;
    let mut held = 0;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "numObjects" => count.read(c, key)?,
            "MaterialIndex" => {
                let (index, at) = c.whole(key.text, 0)?;
                frame.material = index as usize;
                out.material_uses.push((frame.material, at));
            }
            _ => {
                object(c, res, out, key, frame, NAME)?;
                held += 1;
            }
        }
    }
    count.check(c, held)
}

/// Reads a `Transform` block (after its keyword) into `out`.
fn transform(c: &mut Cursor<'_>, res: &mut Resources, out: &mut Flat, frame: Frame) -> Result<()> {
    const NAME: &str = "Transform";
    let open = c.open(NAME)?;
    let mut matrix = Matrix4::identity();
    let mut held: Option<Token<'_>> = None;
    while let Some(key) = c.key(NAME, open)? {
        if let Some(m) = step(c, key) {
            if let Some(object) = held {
                return Err(c.error(
                    key.pos,
                    format!(
                        "'{}' after the Transform's object ('{}' at {}): transformations come first",
                        key.text, object.text, object.pos
                    ),
                ));
            }
            matrix *= m?;
        } else if key.text == "MaterialIndex" {
            return Err(c.error(
                key.pos,
                "MaterialIndex belongs in a Group, not directly in a Transform",
            ));
        } else if let (Some(object), true) = (held, OBJECTS.contains(&key.text)) {
            return Err(c.error(
                key.pos,
                format!(
                    "a Transform holds exactly one object, but '{}' follows '{}' at {} (wrap them in a Group)",
                    key.text, object.text, object.pos
                ),
            ));
        } else {
            let inner = Frame {
                transform: frame.transform * matrix,
                ..frame
            };
            object(c, res, out, key, inner, NAME)?;
            held = Some(key);
        }
    }
    if held.is_none() {
        return Err(c.error(
            c.previous(),
            "a Transform holds exactly one object, but this one holds none",
        ));
    }
    Ok(())
}

/// Reads the object whose keyword `key` was just consumed, in `context`.
fn object(
    c: &mut Cursor<'_>,
    res: &mut Resources,
    out: &mut Flat,
    key: Token<'_>,
    frame: Frame,
    context: &str,
) -> Result<()> {
    let shape = match key.text {
        "Group" => return group(c, res, out, frame.nested(c, key)?),
        "Transform" => return transform(c, res, out, frame.nested(c, key)?),
        "RevSurface" => rev_surface(c)?,
        name if CURVES.contains(&name) => tube(c, key)?,
        name if SURFACES.contains(&name) => surface(c, key)?,
        "BezierPatches" => bezier_patches(c, res)?,
        name if CONSTRUCTED.contains(&name) => constructed_surface(c, key)?,
        name => match primitive(c, res, name, key.pos) {
            Some(shape) => shape?,
            None => return Err(unknown(c, key, context)),
        },
    };
    out.objects.push(place(shape, frame));
    Ok(())
}

/// The object `shape` in `frame`.
fn place(shape: Shape, frame: Frame) -> Object {
    Object {
        shape,
        material: frame.material,
        transform: Some(frame.transform).filter(|m| *m != Matrix4::identity()),
    }
}

/// The error for a keyword that is no object, in `context`.
fn unknown(c: &Cursor<'_>, key: Token<'_>, context: &str) -> super::ParseError {
    let mut known: Vec<&str> = OBJECTS.to_vec();
    if context == "Group" {
        known.extend(["numObjects", "MaterialIndex"]);
    } else {
        known.extend(STEPS);
    }
    c.unknown(key, context, &known)
}

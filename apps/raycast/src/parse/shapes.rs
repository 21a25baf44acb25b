//! The primitive objects (keys in any order, each required once):
//!
//! ```text
//! Sphere       { center P  radius R }
//! Plane        { normal V  offset D }            points p with normal · p = D
//! Triangle     { vertex0 P  vertex1 P  vertex2 P }
//! TriangleMesh { obj_file PATH }                 relative to the scene file
//! Box          { min P  max P }
//! Disk         { center P  normal V  radius R }
//! Ring         { center P  normal V  inner R  outer R }
//! Rectangle    { corner P  edge1 V  edge2 V }
//! ```
//!
//! Sizes must be positive, normals non-zero, triangles and rectangles must
//! have an area, and a box's `min` must be below its `max` in every coordinate.

use revolve::nalgebra::Vector3;

use super::cursor::{Cursor, Result};
use super::lexer::Pos;
use super::resources::Resources;
use crate::scene::Shape;

/// Reads the primitive `name` (after its keyword); `None` if `name` is not one.
pub(super) fn primitive(
    c: &mut Cursor<'_>,
    res: &mut Resources,
    name: &str,
    at: Pos,
) -> Option<Result<Shape>> {
    Some(match name {
        "Sphere" => sphere(c),
        "Plane" => plane(c),
        "Triangle" => triangle(c, at),
        "TriangleMesh" => mesh(c, res),
        "Box" => cuboid(c),
        "Disk" => disk(c),
        "Ring" => ring(c),
        "Rectangle" => rectangle(c),
        _ => return None,
    })
}

/// Checks that two edges span a parallelogram with an area; the error points
/// at `at` (the second edge).
pub(super) fn check_parallelogram(
    c: &Cursor<'_>,
    edge1: &Vector3<f64>,
    edge2: &Vector3<f64>,
    at: Pos,
) -> Result<()> {
    if edge1.cross(edge2).norm() <= 1e-12 * edge1.norm() * edge2.norm() {
        return Err(c.error(at, "'edge1' and 'edge2' are parallel: no area"));
    }
    Ok(())
}

/// `Sphere { center P  radius R }`.
fn sphere(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Sphere";
    let open = c.open(NAME)?;
    let (mut center, mut radius) = (None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "center" => c.field(&mut center, key, NAME, Cursor::point)?,
            "radius" => c.field(&mut radius, key, NAME, Cursor::positive)?,
            _ => return Err(c.unknown(key, NAME, &["center", "radius"])),
        }
    }
    Ok(Shape::Sphere {
        center: c.required(center, "center", NAME)?,
        radius: c.required(radius, "radius", NAME)?,
    })
}

/// `Plane { normal V  offset D }`.
fn plane(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Plane";
    let open = c.open(NAME)?;
    let (mut normal, mut offset) = (None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "normal" => c.field(&mut normal, key, NAME, Cursor::direction)?,
            "offset" => c.field(&mut offset, key, NAME, Cursor::number)?,
            _ => return Err(c.unknown(key, NAME, &["normal", "offset"])),
        }
    }
    Ok(Shape::Plane {
        normal: c.required(normal, "normal", NAME)?,
        offset: c.required(offset, "offset", NAME)?,
    })
}

/// `Triangle { vertex0 P  vertex1 P  vertex2 P }`; a zero-area triangle is an
/// error at `at` (the keyword).
fn triangle(c: &mut Cursor<'_>, at: Pos) -> Result<Shape> {
    const NAME: &str = "Triangle";
    let open = c.open(NAME)?;
    let mut v = [None, None, None];
    while let Some(key) = c.key(NAME, open)? {
        let [v0, v1, v2] = &mut v;
        match key.text {
            "vertex0" => c.field(v0, key, NAME, Cursor::point)?,
            "vertex1" => c.field(v1, key, NAME, Cursor::point)?,
            "vertex2" => c.field(v2, key, NAME, Cursor::point)?,
            _ => return Err(c.unknown(key, NAME, &["vertex0", "vertex1", "vertex2"])),
        }
    }
    let [v0, v1, v2] = v;
    let vertices = [
        c.required(v0, "vertex0", NAME)?,
        c.required(v1, "vertex1", NAME)?,
        c.required(v2, "vertex2", NAME)?,
    ];
    let (a, b) = (vertices[1] - vertices[0], vertices[2] - vertices[0]);
    if a.cross(&b).norm() <= 1e-12 * a.norm() * b.norm() {
        return Err(c.error(at, "the triangle has no area (its vertices are collinear)"));
    }
    Ok(Shape::Triangle { vertices })
}

/// `TriangleMesh { obj_file PATH }`.
fn mesh(c: &mut Cursor<'_>, res: &mut Resources) -> Result<Shape> {
    const NAME: &str = "TriangleMesh";
    let open = c.open(NAME)?;
    let mut mesh = None;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "obj_file" => c.field(&mut mesh, key, NAME, |c, what| {
                let path = c.word(what)?;
                res.mesh(c, path)
            })?,
            _ => return Err(c.unknown(key, NAME, &["obj_file"])),
        }
    }
    Ok(Shape::Mesh(c.required(mesh, "obj_file", NAME)?))
}

/// `Box { min P  max P }`.
fn cuboid(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Box";
    let open = c.open(NAME)?;
    let (mut min, mut max) = (None, None);
    let mut max_at = open;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "min" => c.field(&mut min, key, NAME, Cursor::point)?,
            "max" => {
                max_at = c.here();
                c.field(&mut max, key, NAME, Cursor::point)?;
            }
            _ => return Err(c.unknown(key, NAME, &["min", "max"])),
        }
    }
    let min = c.required(min, "min", NAME)?;
    let max = c.required(max, "max", NAME)?;
    if !(0..3).all(|i| min[i] < max[i]) {
        return Err(c.error(
            max_at,
            "the box's 'max' must exceed its 'min' in every coordinate",
        ));
    }
    Ok(Shape::Box { min, max })
}

/// `Disk { center P  normal V  radius R }`.
fn disk(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Disk";
    let open = c.open(NAME)?;
    let (mut center, mut normal, mut radius) = (None, None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "center" => c.field(&mut center, key, NAME, Cursor::point)?,
            "normal" => c.field(&mut normal, key, NAME, Cursor::direction)?,
            "radius" => c.field(&mut radius, key, NAME, Cursor::positive)?,
            _ => return Err(c.unknown(key, NAME, &["center", "normal", "radius"])),
        }
    }
    Ok(Shape::Disk {
        center: c.required(center, "center", NAME)?,
        normal: c.required(normal, "normal", NAME)?,
        radius: c.required(radius, "radius", NAME)?,
    })
}

/// `Ring { center P  normal V  inner R  outer R }`, `0 ≤ inner < outer`.
fn ring(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Ring";
    let open = c.open(NAME)?;
    let (mut center, mut normal, mut inner, mut outer) = (None, None, None, None);
    let mut outer_at = open;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "center" => c.field(&mut center, key, NAME, Cursor::point)?,
            "normal" => c.field(&mut normal, key, NAME, Cursor::direction)?,
            "inner" => c.field(&mut inner, key, NAME, Cursor::non_negative)?,
            "outer" => {
                outer_at = c.here();
                c.field(&mut outer, key, NAME, Cursor::positive)?;
            }
            _ => return Err(c.unknown(key, NAME, &["center", "normal", "inner", "outer"])),
        }
    }
    let center = c.required(center, "center", NAME)?;
    let normal = c.required(normal, "normal", NAME)?;
    let inner = c.required(inner, "inner", NAME)?;
    let outer = c.required(outer, "outer", NAME)?;
    if inner >= outer {
        return Err(c.error(
            outer_at,
            format!("the ring's 'outer' radius {outer} must exceed its 'inner' radius {inner}"),
        ));
    }
    Ok(Shape::Ring {
        center,
        normal,
        inner,
        outer,
    })
}

/// `Rectangle { corner P  edge1 V  edge2 V }`.
fn rectangle(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "Rectangle";
    let open = c.open(NAME)?;
    let (mut corner, mut edge1, mut edge2) = (None, None, None);
    let mut edge2_at = open;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "corner" => c.field(&mut corner, key, NAME, Cursor::point)?,
            "edge1" => c.field(&mut edge1, key, NAME, Cursor::direction)?,
            "edge2" => {
                edge2_at = c.here();
                c.field(&mut edge2, key, NAME, Cursor::direction)?;
            }
            _ => return Err(c.unknown(key, NAME, &["corner", "edge1", "edge2"])),
        }
    }
    let corner = c.required(corner, "corner", NAME)?;
    let edge1 = c.required(edge1, "edge1", NAME)?;
    let edge2 = c.required(edge2, "edge2", NAME)?;
    check_parallelogram(c, &edge1, &edge2, edge2_at)?;
    Ok(Shape::Rectangle {
        corner,
        edge1,
        edge2,
    })
}

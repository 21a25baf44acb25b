//! The OBJ mesh reader: positions and faces, nothing else.
//!
//! ```text
//! v x y z [w]          a vertex (w and any further values are ignored)
//! f r r r [r…]         a polygon, split into a fan of triangles from its first vertex
//! r = i | i/t | i//n | i/t/n   i: 1-based vertex index, or negative: relative
//!                              to the last vertex read (-1 is the last one)
//! ```
//!
//! Other statements (`vn`, `vt`, `o`, `g`, `s`, `usemtl`, `mtllib`, …) and `#`
//! comments are skipped.

use std::fmt;
use std::path::Path;

use revolve::nalgebra::Point3;

use crate::scene::TriangleMesh;

/// Why an OBJ file could not be read.
#[derive(Debug)]
pub(super) enum ObjError {
    /// The file could not be read.
    Io(std::io::Error),
    /// A malformed statement, at a 1-based line.
    Syntax { line: usize, message: String },
    /// The file holds no faces.
    NoFaces,
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjError::Io(e) => write!(f, "{e}"),
            ObjError::Syntax { line, message } => write!(f, "line {line}: {message}"),
            ObjError::NoFaces => write!(f, "the file holds no faces"),
        }
    }
}

/// Reads the OBJ file at `path`.
pub(super) fn read_obj(path: &Path) -> Result<TriangleMesh, ObjError> {
    let bytes = std::fs::read(path).map_err(ObjError::Io)?;
    parse_obj(&String::from_utf8_lossy(&bytes))
}

/// Parses OBJ text.
pub(super) fn parse_obj(text: &str) -> Result<TriangleMesh, ObjError> {
    let mut mesh = TriangleMesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    for (i, line) in text.lines().enumerate() {
        let syntax = |message: String| ObjError::Syntax {
            line: i + 1,
            message,
        };
        let line = line.split('#').next().unwrap_or("");
        let mut fields = line.split_whitespace();
        match fields.next() {
            Some("v") => {
                let mut coordinate = || -> Result<f64, ObjError> {
                    let field = fields
                        .next()
                        .ok_or_else(|| syntax("a vertex needs three coordinates".into()))?;
                    match field.parse::<f64>() {
                        Ok(x) if x.is_finite() => Ok(x),
                        _ => Err(syntax(format!("bad number '{field}'"))),
                    }
                };
                let point = Point3::new(coordinate()?, coordinate()?, coordinate()?);
                mesh.vertices.push(point);
            }
            Some("f") => {
                let corners = fields
                    .map(|field| vertex_index(field, mesh.vertices.len()).map_err(&syntax))
                    .collect::<Result<Vec<u32>, _>>()?;
                if corners.len() < 3 {
                    return Err(syntax(format!(
                        "a face needs at least 3 vertices, found {}",
                        corners.len()
                    )));
                }
                for pair in corners[1..].windows(2) {
                    mesh.triangles.push([corners[0], pair[0], pair[1]]);
                }
            }
            _ => {}
        }
    }
    if mesh.triangles.is_empty() {
        return Err(ObjError::NoFaces);
    }
    Ok(mesh)
}

/// The 0-based vertex index of a face corner `i`, `i/t`, `i//n` or `i/t/n`,
/// given the number of vertices read so far.
fn vertex_index(field: &str, vertices: usize) -> Result<u32, String> {
    let index = field.split('/').next().unwrap_or("");
    let index: i64 = index
        .parse()
        .map_err(|_| format!("bad vertex reference '{field}'"))?;
    let resolved = match index {
        0 => return Err("vertex index 0 (OBJ indices start at 1)".into()),
        i if i > 0 => i - 1,
        i => vertices as i64 + i,
    };
    if resolved < 0 || resolved >= vertices as i64 {
        return Err(format!(
            "vertex index {index} out of range ({vertices} vertices so far)"
        ));
    }
    u32::try_from(resolved).map_err(|_| format!("vertex index {index} is too large"))
}

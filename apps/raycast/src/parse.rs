//! The scene-file parser (the format of `SCENE_FORMAT.md`: the course
//! framework's scene files plus optional effect keywords).
//!
//! # Grammar
//!
//! Tokens are separated by white space; `#` starts a comment to the end of
//! the line; `{ } [ ]` are tokens of their own; numbers are decimal
//! (`2`, `+3`, `.5`, `-1e-3`). Keys inside a block may come in any order,
//! each at most once. `P`, `V` and `C` are three numbers (a point, a non-zero
//! vector, a colour with non-negative components: at most 1 for the
//! reflectances `diffuseColor`, `specularColor`, `reflectivity` and
//! `transparency`, at most `1e100` for the radiances of lights, emission
//! and background).
//!
//! ```text
//! file        = top-level block…   (each at most once, in any order; the camera is required)
//! PerspectiveCamera { center P  direction V  up V  angle DEG  width N  height N }
//! Lights      { [numLights N]  light… }
//!   light     = DirectionalLight { direction V  color C }
//!             | PointLight { position P  color C }
//!             | AreaLight { corner P  edge1 V  edge2 V  color C }
//! Background  { [color C]  [ambientLight C] }           ambientLight is ignored
//! Materials   { [numMaterials N]  material… }
//!   material  = (PhongMaterial | Material) { [diffuseColor C] [specularColor C]
//!                 [shininess S] [reflectivity C] [transparency C]
//!                 [refractionIndex N] [absorption C] [emission C] [texture PATH] }
//! Group       { [numObjects N]  ( MaterialIndex I | object )… }
//! Transform   { step… object }                          exactly one object
//!   step      = Translate V | Scale x y z | UniformScale s
//!             | XRotate deg | YRotate deg | ZRotate deg | Rotate { V deg }
//! object      = Group | Transform | RevSurface { profile curve } | curve | surface
//!             | Sphere { center P  radius R }
//!             | Plane { normal V  offset D }
//!             | Triangle { vertex0 P  vertex1 P  vertex2 P }
//!             | TriangleMesh { obj_file PATH }
//!             | Box { min P  max P }
//!             | Disk { center P  normal V  radius R }
//!             | Ring { center P  normal V  inner R  outer R }
//!             | Rectangle { corner P  edge1 V  edge2 V }
//! curve       = (BezierCurve | BsplineCurve) { controls [x y z]… }
//!             | NurbsCurve { degree p  knots k…  controls [x y z w]… }   ([x y z]: w = 1)
//! surface     = BezierSurface { rows m  cols n  controls [x y z]… }   (m·n points, row by row)
//!             | BsplineSurface { uDegree p  vDegree q  uKnots k…  vKnots k…
//!                                rows m  cols n  controls [x y z]… }
//!                                ([x y z w] anywhere: rational; [x y z]: w = 1)
//!             | BezierPatches { file PATH }   (bicubic patches, Newell's teapot layout)
//! Render      { [samples N] [maxDepth N] [shadows true|false]
//!               [integrator whitted|path] [toneMap clamp|reinhard] }
//! ```
//!
//! Paths (`obj_file`, `texture`, `file`) are relative to the scene file. The result
//! is flat: nested groups and transforms become one list of objects, each
//! with its material index and composed object-to-world matrix (transforms
//! compose in the order written, `M = T₁·T₂·…`). The submodules hold the
//! details of each part; every malformed input is a [`ParseError`] pointing
//! at the offending token, never a panic.
//!
//! # Warnings
//! Input that is valid but almost certainly a mistake parses, with a
//! [`ParseWarning`] located the same way (`file:line:column`):
//!
//! - `angle` under 2 degrees: the field of view is in degrees, and such a
//!   value is most likely radians (`angle 0.7` would render a blank picture
//!   of a 0.7° cone); the warning gives the value in degrees.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::scene::Scene;

#[cfg(test)]
pub use objects::MAX_NESTING;

mod camera;
mod counted;
mod cursor;
mod curves;
mod document;
mod keywords;
mod lexer;
mod lights;
mod materials;
mod obj;
mod objects;
mod patches;
mod render;
mod resources;
mod shapes;
mod suggest;
mod surfaces;
#[cfg(test)]
mod tests;
mod texture;
mod transform;

/// A malformed scene: where, and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    /// The scene file.
    pub file: PathBuf,
    /// 1-based line and column of the offending token (0 when the error is
    /// about the file as a whole, e.g. it cannot be read).
    pub line: usize,
    /// 1-based column (in characters) of the offending token.
    pub column: usize,
    /// What is wrong, and what was expected.
    pub message: String,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file.display(),
            self.line,
            self.column,
            self.message
        )
    }
}

impl std::error::Error for ParseError {}

/// A scene that parses but probably does not say what its author meant
/// (e.g. a field of view in radians): where, and why. Located like a
/// [`ParseError`] and printed as `file:line:column: warning: message`.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseWarning {
    /// The scene file.
    pub file: PathBuf,
    /// 1-based line of the suspicious token.
    pub line: usize,
    /// 1-based column (in characters) of the suspicious token.
    pub column: usize,
    /// What looks wrong, and what the format expects.
    pub message: String,
}

impl fmt::Display for ParseWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: warning: {}",
            self.file.display(),
            self.line,
            self.column,
            self.message
        )
    }
}

/// A parsed scene and the warnings its file raised, in file order.
#[derive(Debug, Clone)]
pub struct Parsed {
    pub scene: Scene,
    pub warnings: Vec<ParseWarning>,
}

/// Reads and parses the scene file at `path` (meshes and textures are
/// resolved relative to its directory), keeping the warnings.
pub fn parse_file_with_warnings(path: &Path) -> Result<Parsed, ParseError> {
    let bytes = std::fs::read(path).map_err(|e| ParseError {
        file: path.to_path_buf(),
        line: 0,
        column: 0,
        message: format!("cannot read the scene file: {e}"),
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let (line, column) = byte_position(e.as_bytes(), e.utf8_error().valid_up_to());
        ParseError {
            file: path.to_path_buf(),
            line,
            column,
            message: "the scene file is not valid UTF-8 text here (a scene is plain text)"
                .to_string(),
        }
    })?;
    parse_str_with_warnings(&text, path)
}

/// The line and column (both from 1; the column counts characters) of
/// byte `at` of `bytes`, whose bytes before `at` are valid UTF-8.
fn byte_position(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at.min(bytes.len())];
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
    let column = 1 + std::str::from_utf8(&before[line_start..]).map_or(0, |s| s.chars().count());
    (line, column)
}

/// Parses scene text, keeping the warnings; `path` names it in errors and
/// warnings and anchors relative paths.
pub fn parse_str_with_warnings(text: &str, path: &Path) -> Result<Parsed, ParseError> {
    document::scene(text, path)
}

/// Reads and parses the scene file at `path`, dropping the warnings (see
/// [`parse_file_with_warnings`]; for tests, which check warnings apart).
#[cfg(test)]
pub fn parse_file(path: &Path) -> Result<Scene, ParseError> {
    parse_file_with_warnings(path).map(|p| p.scene)
}

/// Parses scene text, dropping the warnings (see
/// [`parse_str_with_warnings`]; for tests, which check warnings apart).
#[cfg(test)]
pub fn parse_str(text: &str, path: &Path) -> Result<Scene, ParseError> {
    parse_str_with_warnings(text, path).map(|p| p.scene)
}

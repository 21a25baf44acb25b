//! The scene-file parser (../shared/SCENE_FORMAT.md). Being written.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::scene::Scene;

/// A malformed scene: where, and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub file: PathBuf,
    /// 1-based line and column of the offending token (0 when the error is
    /// about the file as a whole, e.g. it cannot be read).
    pub line: usize,
    pub column: usize,
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

/// Reads and parses the scene file at `path` (meshes and textures are
/// resolved relative to its directory).
pub fn parse_file(path: &Path) -> Result<Scene, ParseError> {
    let text = std::fs::read_to_string(path).map_err(|e| ParseError {
        file: path.to_path_buf(),
        line: 0,
        column: 0,
        message: format!("cannot read the scene file: {e}"),
    })?;
    parse_str(&text, path)
}

/// Parses scene text; `path` names it in errors and anchors relative paths.
pub fn parse_str(_text: &str, path: &Path) -> Result<Scene, ParseError> {
    Err(ParseError {
        file: path.to_path_buf(),
        line: 0,
        column: 0,
        message: "the parser is not written yet".into(),
    })
}

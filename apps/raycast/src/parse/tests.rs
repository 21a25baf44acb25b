//! Tests of the scene parser: one per keyword (values land in the right
//! fields) and one per kind of error (line, column and message).

use std::path::Path;

use super::{ParseError, parse_str};
use crate::scene::{Object, Scene};
pub(super) use crate::temp_dir::TempDir;

mod constructed;
mod errors_files;
mod errors_syntax;
mod errors_values;
mod format_example;
mod lexing;
mod limits;
mod nurbs;
mod objects;
mod patches;
mod robustness;
mod settings;
mod surfaces;
mod transforms;
mod warnings;

/// A camera block on one line (line 1 of every test scene).
const CAMERA: &str =
    "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 45 width 40 height 30 }\n";

/// Parses `text` (named `test.txt`), panicking with the error.
fn parse(text: &str) -> Scene {
    parse_str(text, Path::new("test.txt")).unwrap_or_else(|e| panic!("{e}"))
}

/// The error for `text`, panicking if it parses.
fn fail(text: &str) -> ParseError {
    match parse_str(text, Path::new("test.txt")) {
        Ok(_) => panic!("parsed without error:\n{text}"),
        Err(e) => e,
    }
}

/// Asserts that `text` fails at `line:column` with a message containing
/// `fragment`.
#[track_caller]
fn assert_error(text: &str, line: usize, column: usize, fragment: &str) {
    let e = fail(text);
    assert_eq!((e.line, e.column), (line, column), "wrong position: {e}");
    assert!(e.message.contains(fragment), "'{fragment}' not in: {e}");
}

/// A scene with the camera on line 1, `Group {` on line 2 and `body` from
/// line 3 on.
fn in_group(body: &str) -> String {
    format!("{CAMERA}Group {{\n{body}\n}}\n")
}

/// The objects of a scene whose group holds `body`.
fn objects_of(body: &str) -> Vec<Object> {
    parse(&in_group(body)).objects
}

impl TempDir {
    /// Writes the scene `text` as `scene.txt` and parses it with
    /// [`super::parse_file`].
    fn parse_scene(&self, text: &str) -> Result<Scene, ParseError> {
        let path = self.write("scene.txt", text.as_bytes());
        super::parse_file(&path)
    }
}

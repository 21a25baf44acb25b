//! Tests of the scene parser: one per keyword (values land in the right
//! fields) and one per kind of error (line, column and message).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use super::{ParseError, parse_str};
use crate::scene::{Object, Scene};

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

/// A fresh directory under the system's temporary directory, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    /// A new empty directory, unique to this process and call.
    fn new(name: &str) -> Self {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "revolve-parse-{}-{name}-{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).expect("create a temporary directory");
        TempDir(dir)
    }

    /// Writes `contents` to `relative` (creating subdirectories); its path.
    fn write(&self, relative: &str, contents: &[u8]) -> PathBuf {
        let path = self.0.join(relative);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).expect("create a fixture directory");
        }
        std::fs::write(&path, contents).expect("write a fixture");
        path
    }

    /// Writes the scene `text` as `scene.txt` and parses it with
    /// [`super::parse_file`].
    fn parse_scene(&self, text: &str) -> Result<Scene, ParseError> {
        let path = self.write("scene.txt", text.as_bytes());
        super::parse_file(&path)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

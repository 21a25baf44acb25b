//! The patches file of `BezierPatches { file PATH }` (the block is parsed in
//! [`super::surfaces`]): bicubic Bézier patches in the classic layout of
//! Newell's teapot.
//!
//! ```text
//! N                       the number of patches, at least 1
//! i₁ i₂ … i₁₆             N times: 16 one-based vertex indices, row by row
//!                         (4 rows of 4 control points; a row runs along v)
//! V                       the number of vertices, at least 1
//! x y z                   V times: a vertex
//! ```
//!
//! Numbers are separated by white space (line breaks are not significant);
//! `#` starts a comment to the end of its line. The counts and indices are
//! whole numbers, the coordinates decimal numbers as in a scene (finite; no
//! `inf` or `nan`). Nothing may follow the last vertex. The path is relative
//! to the scene file.
//!
//! Every mistake is a [`PatchFileError`] with the 1-based line of the
//! offending number (the last line when the file ends too early): a count
//! or index that is not a whole number, an index of 0 or beyond `V`, too few
//! or too many numbers, a coordinate that is not a number, and revolve's own
//! checks of each patch (`BezierSurface::new`). The patches make one
//! revolve `BezierPatches` model (a hierarchy over the patches' boxes).

use std::fmt;
use std::path::Path;

use revolve::nalgebra::Point3;
use revolve::{BezierPatches, BezierSurface};

use super::lexer::is_number;

/// Control points of a bicubic patch.
const PATCH_POINTS: usize = 16;

/// Why a patches file could not be read.
#[derive(Debug)]
pub(super) enum PatchFileError {
    /// The file could not be read.
    Io(std::io::Error),
    /// Malformed contents, at a 1-based line.
    Syntax { line: usize, message: String },
}

impl fmt::Display for PatchFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PatchFileError::Io(e) => write!(f, "{e}"),
            PatchFileError::Syntax { line, message } => write!(f, "line {line}: {message}"),
        }
    }
}

type Result<T> = std::result::Result<T, PatchFileError>;

/// Reads the patches file at `path` into a model.
pub(super) fn read_patches(path: &Path) -> Result<BezierPatches> {
    let bytes = std::fs::read(path).map_err(PatchFileError::Io)?;
    let text = String::from_utf8_lossy(&bytes);
    let patches = parse_patches(&text)?;
    // The file holds at least one patch; revolve's refusal of an empty
    // model cannot happen, but would be reported at the file's start.
    BezierPatches::new(patches).map_err(|e| PatchFileError::Syntax {
        line: 1,
        message: e.to_string(),
    })
}

/// The numbers of a patches file, each with its line, read in order.
struct Fields<'a> {
    words: Vec<(&'a str, usize)>,
    next: usize,
    /// The file's last line (where a too-short file ends).
    last_line: usize,
}

impl<'a> Fields<'a> {
    fn new(text: &'a str) -> Self {
        let mut words = Vec::new();
        let mut last_line = 1;
        for (i, line) in text.lines().enumerate() {
            last_line = i + 1;
            let content = line.split('#').next().unwrap_or("");
            words.extend(content.split_whitespace().map(|w| (w, i + 1)));
        }
        Fields {
            words,
            next: 0,
            last_line,
        }
    }

    /// The next word and its line, or an error saying that `what` is
    /// missing.
    fn take(&mut self, what: &dyn Fn() -> String) -> Result<(&'a str, usize)> {
        match self.words.get(self.next) {
            Some(&word) => {
                self.next += 1;
                Ok(word)
            }
            None => Err(PatchFileError::Syntax {
                line: self.last_line,
                message: format!("the file ends where {} should be", what()),
            }),
        }
    }

    /// A whole number `≥ min` (`what` names it in errors), and its line.
    fn whole(&mut self, min: usize, what: &dyn Fn() -> String) -> Result<(usize, usize)> {
        let (word, line) = self.take(what)?;
        match word.parse::<usize>() {
            Ok(n) if n >= min && word.bytes().all(|b| b.is_ascii_digit()) => Ok((n, line)),
            _ => Err(PatchFileError::Syntax {
                line,
                message: format!(
                    "expected {} (a whole number{}), found '{word}'",
                    what(),
                    if min > 0 {
                        format!(" at least {min}")
                    } else {
                        String::new()
                    }
                ),
            }),
        }
    }

    /// A finite decimal number (`what` names it in errors).
    fn number(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
        let (word, line) = self.take(what)?;
        match word.parse::<f64>() {
            Ok(x) if is_number(word) && x.is_finite() => Ok(x),
            _ => Err(PatchFileError::Syntax {
                line,
                message: format!("expected {} (a finite number), found '{word}'", what()),
            }),
        }
    }
}

/// Parses the text of a patches file.
pub(super) fn parse_patches(text: &str) -> Result<Vec<BezierSurface>> {
    let mut fields = Fields::new(text);
    let (count, _) = fields.whole(1, &|| "the number of patches".to_string())?;
    // Indices of each patch with its first line; the vertices are not
    // known yet, so the ranges are checked after reading them.
    let mut patches: Vec<([(usize, usize); PATCH_POINTS], usize)> = Vec::new();
    for p in 1..=count {
        let mut indices = [(0, 0); PATCH_POINTS];
        for (k, slot) in indices.iter_mut().enumerate() {
            *slot = fields.whole(1, &|| format!("index {} of patch {p} of {count}", k + 1))?;
        }
        patches.push((indices, indices[0].1));
    }
    let (vertex_count, _) = fields.whole(1, &|| "the number of vertices".to_string())?;
    let mut vertices = Vec::new();
    for v in 1..=vertex_count {
        let mut coordinate = |axis: &str| {
            fields.number(&|| format!("coordinate {axis} of vertex {v} of {vertex_count}"))
        };
        vertices.push(Point3::new(
            coordinate("x")?,
            coordinate("y")?,
            coordinate("z")?,
        ));
    }
    if let Some(&(word, line)) = fields.words.get(fields.next) {
        return Err(PatchFileError::Syntax {
            line,
            message: format!(
                "'{word}' after the last vertex (the file declares {vertex_count} vertices)"
            ),
        });
    }
    patches
        .iter()
        .enumerate()
        .map(|(p, (indices, first_line))| {
            let point = |&(index, line): &(usize, usize)| {
                vertices
                    .get(index - 1)
                    .copied()
                    .ok_or_else(|| PatchFileError::Syntax {
                        line,
                        message: format!(
                            "patch {} refers to vertex {index}, but there are {vertex_count} \
                             vertices",
                            p + 1
                        ),
                    })
            };
            let grid = indices
                .chunks(4)
                .map(|row| row.iter().map(point).collect::<Result<Vec<_>>>())
                .collect::<Result<Vec<_>>>()?;
            BezierSurface::new(grid).map_err(|e| PatchFileError::Syntax {
                line: *first_line,
                message: format!("patch {}: {e}", p + 1),
            })
        })
        .collect()
}

//! `BezierPatches { file PATH }`: the patches file's layout (counts,
//! one-based indices row by row, vertices, comments), the bundled teapot,
//! and every malformed file, reported at the path with the file's line.

use std::sync::Arc;

use revolve::BezierSurface;
use revolve::nalgebra::Point3;

use super::{CAMERA, TempDir, parse_str};
use crate::parse::ParseError;
use crate::scene::{Shape, SurfaceBody};

/// The scene line holding the model; the path starts at column 24.
fn model_line(path: &str) -> String {
    format!("  BezierPatches {{ file {path} }}")
}

/// A scene whose group holds one model read from `path` (line 3).
fn model_scene(path: &str) -> String {
    format!("{CAMERA}Group {{\n{}\n}}\n", model_line(path))
}

/// The patches of every `BezierPatches` object of a parsed scene, in order.
fn models(scene: &crate::scene::Scene) -> Vec<Arc<SurfaceBody>> {
    scene
        .objects
        .iter()
        .map(|o| match &o.shape {
            Shape::Surface(body) => Arc::clone(body),
            other => panic!("not a surface: {other:?}"),
        })
        .collect()
}

/// The patches of a model.
fn patches(body: &SurfaceBody) -> &[BezierSurface] {
    match body {
        SurfaceBody::Patches(model) => model.patches(),
        _ => panic!("not a patch model"),
    }
}

/// Vertex `k` (1-based) of the test files: distinct, not on a grid.
fn vertex(k: usize) -> Point3<f64> {
    let k = k as f64;
    Point3::new(k, k * k / 8.0, 0.5 - k)
}

/// A file of one patch whose indices are 16 down to 1 (so row `i`, column
/// `j` is vertex `16 − 4i − j`), the numbers spread over lines in an odd
/// way, with comments.
fn reversed_patch_file() -> String {
    let mut text = String::from(
        "# a test model\n1 # one patch\n16 15 14 13 12 11\n10 9 8 7 6 5 4 3 2 1\n16\n",
    );
    for k in 1..=16 {
        let v = vertex(k);
        text += &format!("{} {}\n{}\n", v.x, v.y, v.z);
    }
    text
}

#[test]
fn a_patches_file_gives_its_patches_row_by_row() {
    let dir = TempDir::new("patches");
    dir.write("models/one.txt", reversed_patch_file().as_bytes());
    let scene = dir
        .parse_scene(&model_scene("models/one.txt"))
        .unwrap_or_else(|e| panic!("{e}"));
    let models = models(&scene);
    let patches = patches(&models[0]);
    assert_eq!(patches.len(), 1);
    assert_eq!(patches[0].degrees(), (3, 3));
    for i in 0..4 {
        for j in 0..4 {
            assert_eq!(
                patches[0].points()[i][j],
                vertex(16 - 4 * i - j),
                "({i}, {j})"
            );
        }
    }
}

#[test]
fn a_model_used_twice_is_read_once() {
    let dir = TempDir::new("patches-shared");
    dir.write("one.txt", reversed_patch_file().as_bytes());
    let line = model_line("one.txt");
    let scene = dir
        .parse_scene(&format!("{CAMERA}Group {{\n{line}\n{line}\n}}\n"))
        .unwrap_or_else(|e| panic!("{e}"));
    let models = models(&scene);
    assert_eq!(models.len(), 2);
    assert!(Arc::ptr_eq(&models[0], &models[1]));
}

/// The bundled teapot file read by a plain second reader: the patches as
/// grids of points, from the counts, indices and vertices.
fn teapot_by_hand(text: &str) -> Vec<Vec<Vec<Point3<f64>>>> {
    let words: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .flat_map(str::split_whitespace)
        .collect();
    let count: usize = words[0].parse().unwrap();
    let indices = &words[1..1 + 16 * count];
    let vertices: Vec<Point3<f64>> = words[2 + 16 * count..]
        .chunks(3)
        .map(|c| {
            Point3::new(
                c[0].parse().unwrap(),
                c[1].parse().unwrap(),
                c[2].parse().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        vertices.len(),
        words[1 + 16 * count].parse::<usize>().unwrap()
    );
    indices
        .chunks(16)
        .map(|patch| {
            patch
                .chunks(4)
                .map(|row| {
                    row.iter()
                        .map(|i| vertices[i.parse::<usize>().unwrap() - 1])
                        .collect()
                })
                .collect()
        })
        .collect()
}

#[test]
fn the_bundled_teapot_has_its_32_bicubic_patches() {
    let scenes = crate::repo_root().join("scenes");
    let text = std::fs::read_to_string(scenes.join("data/teapot.txt")).unwrap();
    let scene = parse_str(&model_scene("data/teapot.txt"), &scenes.join("test.txt"))
        .unwrap_or_else(|e| panic!("{e}"));
    let models = models(&scene);
    let patches = patches(&models[0]);
    let expected = teapot_by_hand(&text);
    assert_eq!(patches.len(), 32);
    assert_eq!(expected.len(), 32);
    for (patch, grid) in patches.iter().zip(&expected) {
        assert_eq!(patch.points(), grid.as_slice());
    }
    // The rim of the body and the lid's knob, from the classic data.
    assert_eq!(patches[0].points()[0][0], Point3::new(1.4, 0.0, 2.4));
    let top = patches[20].points()[0][0];
    assert_eq!(top, Point3::new(0.0, 0.0, 3.15));
}

/// The error of a scene whose model file `model.txt` holds `text`.
fn file_error(text: &str) -> ParseError {
    let dir = TempDir::new("patches-error");
    dir.write("model.txt", text.as_bytes());
    match dir.parse_scene(&model_scene("model.txt")) {
        Ok(_) => panic!("parsed:\n{text}"),
        Err(e) => e,
    }
}

/// Asserts that the model file `text` is refused at the scene's path with
/// `patches file 'model.txt': line LINE: MESSAGE`.
#[track_caller]
fn assert_file_error(text: &str, line: usize, message: &str) {
    let e = file_error(text);
    assert_eq!((e.line, e.column), (3, 24), "{e}");
    assert_eq!(
        e.message,
        format!("patches file 'model.txt': line {line}: {message}")
    );
}

/// One patch of indices `indices`, then the 16 test vertices (one a line,
/// from line 4 on).
fn one_patch(indices: &str) -> String {
    let mut text = format!("1\n{indices}\n16\n");
    for k in 1..=16 {
        let v = vertex(k);
        text += &format!("{} {} {}\n", v.x, v.y, v.z);
    }
    text
}

const INDICES: &str = "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16";

#[test]
fn a_missing_patches_file_is_refused_at_its_path() {
    let dir = TempDir::new("patches-missing");
    let e = dir
        .parse_scene(&model_scene("no/teapot.txt"))
        .expect_err("the file does not exist");
    assert_eq!(e.file, dir.0.join("scene.txt"));
    assert_eq!((e.line, e.column), (3, 24), "{e}");
    assert!(
        e.message
            .starts_with("cannot read patches file 'no/teapot.txt': "),
        "{e}"
    );
}

#[test]
fn an_index_out_of_range_is_refused_at_its_line() {
    let text = one_patch("1 2 3 4 5 6 7 8\n9 10 11 12 13 14 15 17");
    assert_file_error(
        &text,
        3,
        "patch 1 refers to vertex 17, but there are 16 vertices",
    );
    assert_file_error(
        &one_patch("0 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16"),
        2,
        "expected index 1 of patch 1 of 1 (a whole number at least 1), found '0'",
    );
}

#[test]
fn words_that_are_not_whole_numbers_are_refused() {
    assert_file_error(
        &one_patch("1 2 3 4 5 6 x 8 9 10 11 12 13 14 15 16"),
        2,
        "expected index 7 of patch 1 of 1 (a whole number at least 1), found 'x'",
    );
    assert_file_error(
        &one_patch("1 2 3 4 5 6 7.5 8 9 10 11 12 13 14 15 16"),
        2,
        "expected index 7 of patch 1 of 1 (a whole number at least 1), found '7.5'",
    );
    assert_file_error(
        &format!("two\n{INDICES}\n"),
        1,
        "expected the number of patches (a whole number at least 1), found 'two'",
    );
    assert_file_error(
        "0\n",
        1,
        "expected the number of patches (a whole number at least 1), found '0'",
    );
}

#[test]
fn coordinates_that_are_not_finite_numbers_are_refused() {
    for bad in ["nan", "inf", "1e999", "0x1", "--1"] {
        let text = one_patch(INDICES).replacen("0.125", bad, 1);
        assert_file_error(
            &text,
            4,
            &format!("expected coordinate y of vertex 1 of 16 (a finite number), found '{bad}'"),
        );
    }
}

#[test]
fn wrong_counts_are_refused() {
    // Too few indices: the file ends in the middle of the patch.
    assert_file_error(
        "1\n1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\n",
        2,
        "the file ends where index 16 of patch 1 of 1 should be",
    );
    // Two patches declared, one given: the second patch's indices run into
    // the vertex count and the first vertex (1 0.125 -0.5, line 4).
    let text = one_patch(INDICES).replacen('1', "2", 1);
    assert_file_error(
        &text,
        4,
        "expected index 3 of patch 2 of 2 (a whole number at least 1), found '0.125'",
    );
    // More vertices declared than given.
    let text = one_patch(INDICES).replacen("\n16\n", "\n17\n", 1);
    assert_file_error(
        &text,
        19,
        "the file ends where coordinate x of vertex 17 of 17 should be",
    );
    // Fewer declared than given.
    let text = one_patch(INDICES).replacen("\n16\n", "\n15\n", 1);
    assert_file_error(
        &text,
        19,
        "'16' after the last vertex (the file declares 15 vertices)",
    );
}

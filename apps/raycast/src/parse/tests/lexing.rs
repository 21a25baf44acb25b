//! Tokens, positions, comments and number forms.

use revolve::nalgebra::Point3;

use super::super::lexer::{Kind, Pos, tokenize};
use super::super::suggest::did_you_mean;
use super::{CAMERA, objects_of, parse};
use crate::scene::Shape;

#[test]
fn tokens_carry_line_and_column() {
    let (tokens, end) = tokenize("Sphere {\n\tcenter .5 -1e-3 +3 # note { ]\n  [2.]}x");
    let got: Vec<(Kind, &str, usize, usize)> = tokens
        .iter()
        .map(|t| (t.kind, t.text, t.pos.line, t.pos.column))
        .collect();
    assert_eq!(
        got,
        vec![
            (Kind::Word, "Sphere", 1, 1),
            (Kind::Open, "{", 1, 8),
            (Kind::Word, "center", 2, 2),
            (Kind::Number(0.5), ".5", 2, 9),
            (Kind::Number(-1e-3), "-1e-3", 2, 12),
            (Kind::Number(3.0), "+3", 2, 18),
            (Kind::OpenBracket, "[", 3, 3),
            (Kind::Number(2.0), "2.", 3, 4),
            (Kind::CloseBracket, "]", 3, 6),
            (Kind::Close, "}", 3, 7),
            (Kind::Word, "x", 3, 8),
        ]
    );
    assert_eq!(end, Pos { line: 3, column: 9 });
}

#[test]
fn only_decimal_numbers_are_numbers() {
    let (tokens, _) = tokenize("2 1E+2 -.25 inf nan 0x10 1.2.3 e5 . - 1e 3abc 1_000");
    let kinds: Vec<Kind> = tokens.iter().map(|t| t.kind).collect();
    assert_eq!(
        kinds,
        vec![
            Kind::Number(2.0),
            Kind::Number(100.0),
            Kind::Number(-0.25),
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
            Kind::Word,
        ]
    );
}

#[test]
fn columns_count_characters_not_bytes() {
    let (tokens, _) = tokenize("# Bézier\nSphère é x");
    let columns: Vec<(usize, usize)> = tokens.iter().map(|t| (t.pos.line, t.pos.column)).collect();
    assert_eq!(columns, vec![(2, 1), (2, 8), (2, 10)]);
}

#[test]
fn comments_and_number_forms_in_a_scene() {
    let objects = objects_of(
        "# a whole-line comment\n\
         Sphere{center .5 -1e-3 +3 radius 2}# comment right after a token\n\
         \tSphere {\tcenter 1. 1E1 -0 # comment inside a block\n radius .25 }\n\
         RevSurface{profile BezierCurve{controls[-1 0 0][-1 1 0]}}",
    );
    assert_eq!(objects.len(), 3);
    assert!(matches!(
        objects[0].shape,
        Shape::Sphere { center, radius } if center == Point3::new(0.5, -1e-3, 3.0) && radius == 2.0
    ));
    assert!(matches!(
        objects[1].shape,
        Shape::Sphere { center, radius } if center == Point3::new(1.0, 10.0, 0.0) && radius == 0.25
    ));
    assert!(matches!(objects[2].shape, Shape::Revolution(_)));
}

#[test]
fn empty_lines_and_windows_line_ends() {
    let scene = parse(&format!("\r\n\r\n{}\r\n# end\r\n", CAMERA.trim_end()));
    assert_eq!(scene.camera.height, 30);
}

#[test]
fn near_misspellings_are_suggested() {
    let known = ["Sphere", "Plane", "Triangle", "TriangleMesh"];
    assert_eq!(did_you_mean("Shpere", &known), Some("Sphere"));
    assert_eq!(did_you_mean("sphere", &known), Some("Sphere"));
    assert_eq!(did_you_mean("TriangleMsh", &known), Some("TriangleMesh"));
    assert_eq!(did_you_mean("Cylinder", &known), None);
}

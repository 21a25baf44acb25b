//! No input panics: every truncation and every single-token corruption of a
//! scene using all keywords parses or fails with a position inside the text.

use std::path::Path;

use super::super::parse_str;

/// A scene with every keyword that needs no external file.
const ALL: &str =
    "PerspectiveCamera { center 0 0 10 direction 0 0 -1 up 0 1 0 angle 45 width 8 height 6 }
Lights { numLights 3
  DirectionalLight { direction 0 -1 0 color 1 1 1 }
  PointLight { position 0 5 0 color 1 1 1 }
  AreaLight { corner 0 4 0 edge1 1 0 0 edge2 0 0 1 color 2 2 2 } }
Background { color 0.1 0.1 0.1 ambientLight 0.2 0.2 0.2 }
Materials { numMaterials 2
  PhongMaterial { diffuseColor 1 0 0 specularColor 1 1 1 shininess 20 }
  Material { reflectivity 0.5 0.5 0.5 transparency 0.1 0.1 0.1 refractionIndex 1.5
             absorption 0.1 0.1 0.1 emission 0 0 0 } }
Group { numObjects 12
  MaterialIndex 1
  Sphere { center 0 0 0 radius 1 }
  Plane { normal 0 1 0 offset -1 }
  Triangle { vertex0 0 0 0 vertex1 1 0 0 vertex2 0 1 0 }
  Box { min 0 0 0 max 1 1 1 }
  Disk { center 0 0 0 normal 0 1 0 radius 1 }
  Ring { center 0 0 0 normal 0 1 0 inner 1 outer 2 }
  Rectangle { corner 0 0 0 edge1 1 0 0 edge2 0 1 0 }
  Transform { Translate 1 0 0 Scale 1 2 1 UniformScale 2 XRotate 10 YRotate 20 ZRotate 30
              Rotate { 1 1 0 45 }
              RevSurface { profile BezierCurve { controls [ -1 0 0 ] [ -2 1 0 ] [ -1 2 0 ] } } }
  RevSurface { profile BsplineCurve { controls [ -1 0 0 ] [ -1 1 0 ] [ -2 2 0 ] [ -1 3 0 ] } }
  BezierCurve { controls [ 0 0 0 ] [ 1 1 1 ] }
  BsplineCurve { controls [ 0 0 0 ] [ 1 1 1 ] [ 2 0 0 ] [ 3 1 1 ] }
  Group { numObjects 0 } }
Render { samples 2 maxDepth 3 shadows true integrator path toneMap reinhard }
";

/// Parses `text`; on error, checks that the position lies inside it.
fn check(text: &str) -> bool {
    match parse_str(text, Path::new("robust.txt")) {
        Ok(_) => true,
        Err(e) => {
            let lines = text.split('\n').count();
            assert!(
                (1..=lines).contains(&e.line) || (e.line, e.column) == (0, 0),
                "{e}\n---\n{text}"
            );
            assert!(e.column >= 1 || e.line == 0, "{e}");
            assert!(!e.message.is_empty());
            false
        }
    }
}

#[test]
fn the_full_scene_parses() {
    assert!(check(ALL));
}

#[test]
fn every_truncation_is_handled() {
    let cuts = ALL.char_indices().map(|(i, _)| i);
    let failures = cuts.filter(|&i| !check(&ALL[..i])).count();
    // Most prefixes end inside a block, hence errors.
    assert!(failures > ALL.len() / 2, "{failures} failures");
}

#[test]
fn every_token_corruption_is_handled() {
    let words: Vec<&str> = ALL.split(' ').collect();
    let mut failures = 0;
    for i in 0..words.len() {
        for replacement in ["x", "-1", "0", "{", "}", "[", "1e999", ""] {
            let mut corrupted = words.clone();
            corrupted[i] = replacement;
            if !check(&corrupted.join(" ")) {
                failures += 1;
            }
        }
    }
    assert!(failures > words.len(), "{failures} failures");
}

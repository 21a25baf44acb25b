//! Errors of the files a scene refers to (meshes, textures) and of the scene
//! file itself; mesh and texture errors point at the path.

use std::path::Path;

use super::{CAMERA, TempDir};
use crate::parse::ParseError;

/// A scene whose group holds one mesh `path` (the path at line 3, column 27).
fn mesh_scene(path: &str) -> String {
    format!("{CAMERA}Group {{\n  TriangleMesh {{ obj_file {path} }}\n}}\n")
}

/// The error of a scene whose mesh file `mesh.obj` holds `obj`.
fn obj_error(obj: &str) -> ParseError {
    let dir = TempDir::new("obj");
    dir.write("mesh.obj", obj.as_bytes());
    match dir.parse_scene(&mesh_scene("mesh.obj")) {
        Ok(_) => panic!("parsed:\n{obj}"),
        Err(e) => e,
    }
}

#[track_caller]
fn assert_obj_error(obj: &str, message: &str) {
    let e = obj_error(obj);
    assert_eq!((e.line, e.column), (3, 27), "{e}");
    assert_eq!(e.message, message);
}

#[test]
fn mesh_file_missing() {
    let dir = TempDir::new("missing-mesh");
    let e = dir
        .parse_scene(&mesh_scene("mesh/cube.obj"))
        .expect_err("the mesh does not exist");
    assert_eq!(e.file, dir.0.join("scene.txt"));
    assert_eq!((e.line, e.column), (3, 27), "{e}");
    assert!(
        e.message.starts_with("cannot read mesh 'mesh/cube.obj': "),
        "{e}"
    );
    let io = std::fs::read(dir.0.join("mesh/cube.obj")).expect_err("missing");
    assert!(e.message.ends_with(&io.to_string()), "{e}");
}

#[test]
fn obj_bad_number() {
    assert_obj_error(
        "v 0 0 0\nv 1 x 0\n",
        "mesh 'mesh.obj': line 2: bad number 'x'",
    );
    assert_obj_error(
        "v 0 0\n",
        "mesh 'mesh.obj': line 1: a vertex needs three coordinates",
    );
    assert_obj_error(
        "v 0 0 1e400\n",
        "mesh 'mesh.obj': line 1: bad number '1e400'",
    );
}

#[test]
fn obj_index_out_of_range() {
    assert_obj_error(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
        "mesh 'mesh.obj': line 4: vertex index 4 out of range (3 vertices so far)",
    );
    assert_obj_error(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
        "mesh 'mesh.obj': line 4: vertex index -4 out of range (3 vertices so far)",
    );
    assert_obj_error(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "mesh 'mesh.obj': line 4: vertex index 0 (OBJ indices start at 1)",
    );
}

#[test]
fn obj_bad_faces() {
    assert_obj_error(
        "v 0 0 0\nv 1 0 0\nf 1 2\n",
        "mesh 'mesh.obj': line 3: a face needs at least 3 vertices, found 2",
    );
    assert_obj_error(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 two 3\n",
        "mesh 'mesh.obj': line 4: bad vertex reference 'two'",
    );
    assert_obj_error(
        "v 0 0 0\n# nothing else\n",
        "mesh 'mesh.obj': the file holds no faces",
    );
}

#[test]
fn texture_file_missing() {
    let dir = TempDir::new("missing-texture");
    let e = dir
        .parse_scene(&format!(
            "{CAMERA}Materials {{ Material {{ texture img/wood.png }} }}"
        ))
        .expect_err("the texture does not exist");
    assert_eq!((e.line, e.column), (2, 32), "{e}");
    assert!(
        e.message
            .starts_with("cannot read texture 'img/wood.png': "),
        "{e}"
    );
}

#[test]
fn texture_that_is_no_image() {
    let dir = TempDir::new("bad-texture");
    dir.write("wood.png", b"this is not a PNG file");
    let e = dir
        .parse_scene(&format!(
            "{CAMERA}Materials {{ Material {{ texture wood.png }} }}"
        ))
        .expect_err("the texture is no PNG");
    assert_eq!((e.line, e.column), (2, 32), "{e}");
    assert!(
        e.message.starts_with("cannot read texture 'wood.png': "),
        "{e}"
    );
}

#[test]
fn scene_file_missing() {
    let path = Path::new("/nonexistent/revolve/scene.txt");
    let e = crate::parse::parse_file(path).expect_err("no such scene");
    assert_eq!(e.file, path);
    assert_eq!((e.line, e.column), (0, 0));
    assert!(e.message.starts_with("cannot read the scene file: "), "{e}");
}

#[test]
fn scene_file_not_utf8_names_the_first_bad_byte() {
    let dir = TempDir::new("not-utf8");
    // Line 2, after "  Sphere" and a two-byte 'é' (one character).
    let mut bytes = format!("{CAMERA}Group {{\n").into_bytes();
    let line = CAMERA.lines().count() + 2;
    bytes.extend_from_slice("  Sphéré".as_bytes()[..7].as_ref());
    bytes.push(0xff);
    bytes.extend_from_slice(b" { center 0 0 0 radius 1 }\n}\n");
    let path = dir.write("scene.txt", &bytes);
    let e = crate::parse::parse_file(&path).expect_err("not UTF-8");
    assert_eq!((e.line, e.column), (line, 7), "{e}");
    assert!(e.message.contains("not valid UTF-8"), "{e}");
}

//! `RuledSurface`, `ExtrudedSurface` and `LoftedSurface`: revolve's NURBS
//! surfaces built from the curves written, checked against closed forms,
//! and every way they can be written wrong reported.

use revolve::Surface;
use revolve::nalgebra::Point3;

use super::{fail, objects_of};
use crate::scene::{Shape, SurfaceBody};

/// `√2/2` as the scenes write it.
const W: &str = "0.7071067811865476";

/// The NURBS surface of a group holding the one object `text`.
fn nurbs_of(text: &str) -> revolve::NurbsSurface {
    let objects = objects_of(text);
    assert_eq!(objects.len(), 1);
    let Shape::Surface(body) = &objects[0].shape else {
        panic!("not a surface: {:?}", objects[0].shape);
    };
    let SurfaceBody::Nurbs(s) = &**body else {
        panic!("not a NURBS surface");
    };
    s.clone()
}

/// A full circle of radius `r` about the `y` axis at height `y`, as a
/// `NurbsCurve` block (nine points, four quarter arcs).
fn circle(r: f64, y: f64) -> String {
    let p = |x: f64, z: f64, w: &str| format!("[ {x} {y} {z} {w} ]");
    format!(
        "NurbsCurve {{ degree 2 knots 0 0 0 1 1 2 2 3 3 4 4 4 controls {} {} {} {} {} {} {} {} {} }}",
        p(r, 0.0, ""),
        p(r, r, W),
        p(0.0, r, ""),
        p(-r, r, W),
        p(-r, 0.0, ""),
        p(-r, -r, W),
        p(0.0, -r, ""),
        p(r, -r, W),
        p(r, 0.0, ""),
    )
}

#[test]
fn a_loft_through_equal_circles_is_a_cylinder() {
    let s = nurbs_of(&format!(
        "LoftedSurface {{ degree 2 curves {} {} {} }}",
        circle(0.5, 0.0),
        circle(0.5, 1.0),
        circle(0.5, 2.0)
    ));
    let [du, dv] = s.domain();
    for i in 0..=10 {
        for j in 0..=10 {
            let u = du.0 + (du.1 - du.0) * i as f64 / 10.0;
            let v = dv.0 + (dv.1 - dv.0) * j as f64 / 10.0;
            let p = s.eval(u, v);
            assert!((p.x.hypot(p.z) - 0.5).abs() < 1e-12, "{p:?}");
            assert!((-1e-12..=2.0 + 1e-12).contains(&p.y), "{p:?}");
        }
    }
}

#[test]
fn an_extruded_segment_is_a_rectangle_and_a_ruled_pair_a_bilinear_patch() {
    let s = nurbs_of(
        "ExtrudedSurface { curve BezierCurve { controls [ 0 0 0 ] [ 2 0 0 ] } direction 0 0 -3 }",
    );
    let [du, dv] = s.domain();
    let p = s.eval(0.5 * (du.0 + du.1), 0.5 * (dv.0 + dv.1));
    assert!((p - Point3::new(1.0, 0.0, -1.5)).norm() < 1e-14, "{p:?}");
    // Between (0,0,0)–(1,0,0) and (0,1,0)–(1,1,1): S(u, v) = (u, v, u·v).
    let s = nurbs_of(
        "RuledSurface { curves BezierCurve { controls [ 0 0 0 ] [ 1 0 0 ] }\n\
         BezierCurve { controls [ 0 1 0 ] [ 1 1 1 ] } }",
    );
    for (u, v) in [(0.25, 0.5), (0.75, 0.125), (1.0, 1.0)] {
        assert!((s.eval(u, v) - Point3::new(u, v, u * v)).norm() < 1e-14);
    }
}

#[test]
fn constructed_surfaces_report_what_is_wrong() {
    let e = fail(&super::in_group(
        "RuledSurface { curves BezierCurve { controls [ 0 0 0 ] [ 1 0 0 ] } }",
    ));
    assert!(e.message.contains("exactly two curves, got 1"), "{e}");
    let e = fail(&super::in_group(&format!(
        "LoftedSurface {{ curves {} {} }}",
        circle(1.0, 0.0),
        circle(1.0, 1.0)
    )));
    assert!(e.message.contains("degree"), "{e}");
    let e = fail(&super::in_group(&format!(
        "LoftedSurface {{ degree 3 curves {} {} }}",
        circle(1.0, 0.0),
        circle(1.0, 1.0)
    )));
    assert!(e.message.starts_with("invalid LoftedSurface: "), "{e}");
    let e = fail(&super::in_group(
        "ExtrudedSurface { curve BezierCurve { controls [ 0 0 0 ] [ 1 0 0 ] } direction 0 0 0 }",
    ));
    assert!(e.message.starts_with("invalid ExtrudedSurface: "), "{e}");
    let e = fail(&super::in_group(
        "ExtrudedSurface { curve Sphere { } direction 0 0 1 }",
    ));
    assert!(
        e.message
            .contains("BezierCurve, BsplineCurve or NurbsCurve"),
        "{e}"
    );
}

#[test]
fn the_bundled_constructions_scene_parses() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/constructions.txt"),
    )
    .unwrap();
    let scene = super::parse(&text);
    assert!(!scene.objects.is_empty());
}

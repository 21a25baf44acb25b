//! `nearest_point` on the tensor-product kinds (`BezierSurface`,
//! `BSplineSurface`, `NurbsSurface`) and `BezierPatches` (the teapot).
//!
//! References, independent of the search: closed forms (a flat bilinear
//! patch: the clamped projection; a height field from just above an
//! interior point: that point; the NURBS sphere octant and quarter
//! cylinder: the radial projection), and `revolve_testkit::nearest_reference`
//! (about 10⁵ samples of `Surface::eval`, the best local minima refined by
//! Levenberg–Marquardt steps on `eval` and `partials`). Every answer must be
//! certified, no reference may beat it by more than `1e-12` of the problem's
//! size (the certified allowance is below `10⁻¹³` of it for these degrees),
//! its point must be the surface's own evaluation at its `uv` and its
//! distance `|point − p|`.

use revolve_testkit as common;

use common::nearest_reference::{Reference, refine, sampled_nearest};
use common::random_tensors::{Xorshift64Star, clamped_knots};
use common::tensor_shapes::{folded_bicubic, quarter_cylinder, sphere_octant};
use proptest::prelude::*;
use revolve::nalgebra::{Point3, Vector3};
use revolve::{
    BSplineSurface, BezierPatches, BezierSurface, Error, NurbsSurface, Surface, SurfaceNearest,
};

/// Samples per side of the reference grid (about 10⁵ samples).
const SIDE: usize = 317;

/// What every answer must satisfy: `uv` in the domain, `point = S(uv)`
/// (but for the rounding of `uv`),
/// `distance = |point − p|`, and no reference point nearer than `distance`
/// by more than `1e-12·size`.
fn check<S: Surface>(
    s: &S,
    p: &Point3<f64>,
    near: &SurfaceNearest,
    reference: &Reference,
    size: f64,
) {
    let [du, dv] = s.domain();
    assert!(du.0 <= near.uv.0 && near.uv.0 <= du.1, "{near:?}");
    assert!(dv.0 <= near.uv.1 && near.uv.1 <= dv.1, "{near:?}");
    // `point` is the patch's at the exact parameters, `uv` their rounding
    // (the bound `Hit::uv` states).
    let (su, sv) = s.partials(near.uv.0, near.uv.1);
    let rounding = 4.0 * f64::EPSILON * (near.uv.0.abs() * su.norm() + near.uv.1.abs() * sv.norm());
    let on = s.eval(near.uv.0, near.uv.1);
    assert!(
        (near.point - on).norm() <= rounding,
        "point is S(uv): {near:?}, {on:?}"
    );
    assert_eq!(near.distance, (near.point - p).norm());
    assert!(
        near.distance <= reference.distance + 1e-12 * size,
        "p = {p:?}: {near:?} beaten by {reference:?}"
    );
}

/// The largest absolute coordinate of the grid and `p`.
fn size_of(points: &[Vec<Point3<f64>>], p: &Point3<f64>) -> f64 {
    points
        .iter()
        .flatten()
        .fold(p.coords.amax(), |m, q| m.max(q.coords.amax()))
}

/// Query points for a surface: on it, just off it on both sides (normal
/// offsets 10⁻¹ … 10⁻¹²), at corners, and random points in a box three
/// times its size and far away.
fn queries<S: Surface>(s: &S, seed: u64, count: usize) -> Vec<Point3<f64>> {
    let mut rng = Xorshift64Star(seed);
    let [du, dv] = s.domain();
    let mut out = Vec::new();
    let (lo, hi) = (-1.5, 2.5);
    for k in 0..count {
        let (u, v) = (rng.range(du.0, du.1), rng.range(dv.0, dv.1));
        let q = s.eval(u, v);
        let n = s.normal(u, v).map_or(Vector3::z(), |n| n.into_inner());
        let offset = [0.1, 1e-3, 1e-6, 1e-9, 1e-12, 0.0][k % 6];
        let side = if rng.next() < 0.5 { -1.0 } else { 1.0 };
        out.push(q + n * offset * side);
        out.push(Point3::new(
            rng.range(lo, hi),
            rng.range(lo, hi),
            rng.range(lo, hi),
        ));
        if k % 4 == 0 {
            out.push(Point3::new(
                rng.range(-40.0, 40.0),
                rng.range(-40.0, 40.0),
                30.0,
            ));
        }
    }
    out.push(s.eval(du.0, dv.0));
    out.push(s.eval(du.1, dv.1) + Vector3::new(0.25, -0.5, 0.125));
    out
}

/// Runs the queries on a surface kind whose answers must all be certified.
fn never_beaten<S: Surface>(
    name: &str,
    s: &S,
    grid: &[Vec<Point3<f64>>],
    nearest: impl Fn(&Point3<f64>) -> Result<SurfaceNearest, Error>,
    seed: u64,
) {
    for p in queries(s, seed, 12) {
        let near = nearest(&p).unwrap();
        assert!(near.certified, "{name}: {p:?} not certified: {near:?}");
        assert_eq!(near.patch, 0);
        let reference = sampled_nearest(s, &p, SIDE);
        check(s, &p, &near, &reference, size_of(grid, &p));
    }
}

/// A bicubic whose first row is one point (a collapsed edge, as on the
/// teapot's lid), the rest a cap rising to it.
fn collapsed_bicubic() -> BezierSurface {
    let net = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let r = i as f64 / 3.0;
                    let a = j as f64 * 0.6;
                    Point3::new(r * a.cos(), r * a.sin(), 0.8 - 0.5 * r * r)
                })
                .collect()
        })
        .collect();
    BezierSurface::new(net).unwrap()
}

/// A bicubic B-spline surface of 3 × 4 patches over a wavy 6 × 7 net.
fn wavy_bspline() -> BSplineSurface {
    let points: Vec<Vec<Point3<f64>>> = (0..6)
        .map(|i| {
            (0..7)
                .map(|j| {
                    let (x, y) = (i as f64 / 5.0, j as f64 / 6.0);
                    Point3::new(x, y, 0.3 * (7.0 * x).sin() * (5.0 * y).cos())
                })
                .collect()
        })
        .collect();
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.7, 1.0, 1.0, 1.0, 1.0];
    BSplineSurface::new((3, 3), (ku, kv), points).unwrap()
}

/// A biquadratic NURBS surface with random weights in `[0.3, 3]` over a
/// random 5 × 4 net (knots with an interior double knot).
fn random_nurbs(seed: u64) -> NurbsSurface {
    let mut rng = Xorshift64Star(seed);
    let points = rng.grid(5, 4);
    let weights = rng.weights(5, 4);
    let knots = (clamped_knots(&mut rng, 2, 5), clamped_knots(&mut rng, 2, 4));
    NurbsSurface::new((2, 2), knots, points, weights).unwrap()
}

#[test]
fn flat_bilinear_patch_is_the_clamped_projection() {
    // The rectangle [0, 2] × [0, 3] in z = 0: the nearest point is p's
    // projection clamped into it.
    let s = BezierSurface::new(vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 3.0, 0.0)],
        vec![Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 3.0, 0.0)],
    ])
    .unwrap();
    let mut rng = Xorshift64Star(5);
    for _ in 0..200 {
        let p = Point3::new(
            rng.range(-2.0, 4.0),
            rng.range(-2.0, 5.0),
            rng.range(-2.0, 2.0),
        );
        let want = Point3::new(p.x.clamp(0.0, 2.0), p.y.clamp(0.0, 3.0), 0.0);
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified);
        assert!((near.point - want).norm() <= 1e-15 * 4.0, "{p:?}: {near:?}");
        assert!((near.distance - (want - p).norm()).abs() <= 1e-15 * 4.0);
        assert!(
            (near.uv.0 - want.x / 2.0).abs() <= 1e-15 && (near.uv.1 - want.y / 3.0).abs() <= 1e-15
        );
    }
}

#[test]
fn height_field_point_above_an_interior_point() {
    // From S(u, v) + h·N(u, v), h well below the radii of curvature, the
    // nearest point of a gently curved height field is S(u, v) itself.
    let s = common::patch_shapes::gentle_bicubic();
    let mut rng = Xorshift64Star(9);
    for k in 0..100 {
        let (u, v) = (rng.range(0.05, 0.95), rng.range(0.05, 0.95));
        let h = [0.05, 1e-3, 1e-7, 1e-11][k % 4] * if k % 8 < 4 { 1.0 } else { -1.0 };
        let q = s.eval(u, v);
        let p = q + s.normal(u, v).unwrap().into_inner() * h;
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified);
        assert!((near.distance - h.abs()).abs() <= 2e-16, "{h}: {near:?}");
        assert!((near.point - q).norm() <= 1e-14, "{h}: {near:?} vs {q:?}");
        assert!((near.uv.0 - u).abs() <= 1e-12 && (near.uv.1 - v).abs() <= 1e-12);
    }
}

#[test]
fn nurbs_sphere_octant_is_the_radial_projection() {
    let r = 1.5;
    let s = sphere_octant(r);
    let mut rng = Xorshift64Star(13);
    for k in 0..200 {
        // Directions into the octant, inside and outside the sphere.
        let dir = Vector3::new(
            rng.range(0.01, 1.0),
            rng.range(0.01, 1.0),
            rng.range(0.01, 1.0),
        )
        .normalize();
        let rho = [0.0, 0.3, 1.4, 1.5, 1.5 + 1e-9, 3.0, 50.0][k % 7];
        let p = Point3::from(dir * rho);
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified, "{p:?}");
        assert!(
            (near.distance - (rho - r).abs()).abs() <= 4e-15 * rho.max(r),
            "{p:?}: {near:?}"
        );
        if rho > 0.0 {
            assert!(
                (near.point - Point3::from(dir * r)).norm() <= 1e-7,
                "{p:?}: {near:?}"
            );
        }
        assert_eq!(near.point, s.eval(near.uv.0, near.uv.1));
    }
    // The pole (a collapsed edge: the row u = 0) from on and above it.
    for z in [r, 2.0 * r, 0.25] {
        let near = s.nearest_point(&Point3::new(0.0, 0.0, z)).unwrap();
        assert!(near.certified && near.uv.0 == 0.0);
        assert!((near.distance - (z - r).abs()).abs() <= 1e-15 * r);
    }
}

#[test]
fn nurbs_quarter_cylinder_is_the_radial_projection() {
    let (r, h) = (0.75, 2.0);
    let s = quarter_cylinder(r, h);
    let mut rng = Xorshift64Star(17);
    for k in 0..200 {
        let a = rng.range(0.01, 1.56);
        let rho = [0.1, 0.7, 0.75, 1.0, 4.0][k % 5];
        let z = rng.range(0.0, h);
        let p = Point3::new(rho * a.cos(), rho * a.sin(), z);
        let near = s.nearest_point(&p).unwrap();
        assert!(near.certified);
        assert!(
            (near.distance - (rho - r).abs()).abs() <= 4e-15 * 4.0,
            "{p:?}: {near:?}"
        );
        let want = Point3::new(r * a.cos(), r * a.sin(), z);
        assert!((near.point - want).norm() <= 1e-7, "{p:?}: {near:?}");
    }
    // On the axis every point of a horizontal arc is as near.
    let near = s.nearest_point(&Point3::new(0.0, 0.0, 1.0)).unwrap();
    assert!(
        near.certified && (near.distance - r).abs() <= 1e-15 && (near.point.z - 1.0).abs() <= 1e-15
    );
}

#[test]
fn bicubics_are_never_beaten_by_refined_samples() {
    let gentle = common::patch_shapes::gentle_bicubic();
    never_beaten(
        "gentle",
        &gentle,
        gentle.points(),
        |p| gentle.nearest_point(p),
        1,
    );
    let folded = folded_bicubic();
    never_beaten(
        "folded",
        &folded,
        folded.points(),
        |p| folded.nearest_point(p),
        2,
    );
    let collapsed = collapsed_bicubic();
    never_beaten(
        "collapsed",
        &collapsed,
        collapsed.points(),
        |p| collapsed.nearest_point(p),
        3,
    );
    // From the apex of the collapsed edge, and above it.
    for p in [
        Point3::new(0.0, 0.0, 0.8),
        Point3::new(0.0, 0.0, 1.5),
        Point3::new(0.01, -0.02, 0.9),
    ] {
        let near = collapsed.nearest_point(&p).unwrap();
        assert!(near.certified);
        let reference = sampled_nearest(&collapsed, &p, SIDE);
        check(
            &collapsed,
            &p,
            &near,
            &reference,
            size_of(collapsed.points(), &p),
        );
    }
}

#[test]
fn splines_are_never_beaten_by_refined_samples() {
    let bspline = wavy_bspline();
    never_beaten(
        "bspline",
        &bspline,
        bspline.points(),
        |p| bspline.nearest_point(p),
        4,
    );
    let octant = sphere_octant(1.0);
    never_beaten(
        "octant",
        &octant,
        octant.points(),
        |p| octant.nearest_point(p),
        5,
    );
    let cylinder = quarter_cylinder(1.0, 2.0);
    never_beaten(
        "cylinder",
        &cylinder,
        cylinder.points(),
        |p| cylinder.nearest_point(p),
        6,
    );
    for seed in [7, 8] {
        let nurbs = random_nurbs(seed);
        never_beaten(
            "nurbs",
            &nurbs,
            nurbs.points(),
            |p| nurbs.nearest_point(p),
            seed,
        );
    }
}

#[test]
fn teapot_is_never_beaten_and_names_its_patch() {
    let patches = common::teapot::patches();
    let model = BezierPatches::new(patches.clone()).unwrap();
    let mut rng = Xorshift64Star(21);
    let mut queries: Vec<Point3<f64>> = (0..6)
        .map(|_| {
            Point3::new(
                rng.range(-4.0, 4.0),
                rng.range(-3.0, 3.0),
                rng.range(-1.0, 4.0),
            )
        })
        .collect();
    // Near the spout's tip, on the lid's knob (a collapsed edge), just
    // inside the body, far away.
    queries.extend([
        patches[20].eval(0.9, 0.3) + Vector3::new(1e-6, 0.0, 0.0),
        patches[28].eval(0.0, 0.5),
        Point3::new(0.0, 0.0, 3.2),
        Point3::new(0.5, 0.2, 1.0),
        Point3::new(100.0, -50.0, 30.0),
    ]);
    for p in queries {
        let near = model.nearest_point(&p).unwrap();
        assert!(near.certified, "{p:?}: {near:?}");
        let surface = &patches[near.patch];
        assert_eq!(
            near.point,
            surface.eval(near.uv.0, near.uv.1),
            "patch {}",
            near.patch
        );
        assert_eq!(near.distance, (near.point - p).norm());
        let size = patches
            .iter()
            .fold(p.coords.amax(), |m, s| m.max(size_of(s.points(), &p)));
        // The reference over all patches (fewer samples each).
        let best = patches
            .iter()
            .map(|s| sampled_nearest(s, &p, 80).distance)
            .fold(f64::INFINITY, f64::min);
        assert!(
            near.distance <= best + 1e-12 * size,
            "{p:?}: {near:?} vs {best}"
        );
        // The answer is a local minimum on the patch named: refining from
        // it finds nothing nearer.
        let local = refine(surface, &p, near.uv, ((0.0, 1.0), (0.0, 1.0)));
        assert!(
            local.distance >= near.distance - 1e-12 * size,
            "patch {}: {local:?} vs {near:?}",
            near.patch
        );
    }
}

#[test]
fn points_on_the_surface_are_at_distance_zero() {
    let surfaces: Vec<BezierSurface> = vec![
        common::patch_shapes::gentle_bicubic(),
        folded_bicubic(),
        collapsed_bicubic(),
    ];
    let mut rng = Xorshift64Star(23);
    for s in &surfaces {
        for _ in 0..20 {
            let (u, v) = (rng.next(), rng.next());
            let p = s.eval(u, v);
            let near = s.nearest_point(&p).unwrap();
            assert!(near.certified && near.distance <= 2e-15, "{near:?}");
        }
    }
}

#[test]
fn degenerate_patches() {
    // Every control point the same: the surface is one point.
    let one = Point3::new(1.0, -2.0, 0.5);
    let s = BezierSurface::new(vec![vec![one; 3]; 4]).unwrap();
    let p = Point3::new(4.0, 2.0, 0.5);
    let near = s.nearest_point(&p).unwrap();
    assert!(near.certified && near.point == one && near.distance == 5.0);
    // One row: a curve (degrees (0, 3)); the nearest point of a straight
    // one is the clamped projection.
    let line = BezierSurface::new(vec![
        (0..4).map(|j| Point3::new(j as f64, 0.0, 0.0)).collect(),
    ])
    .unwrap();
    let near = line.nearest_point(&Point3::new(1.25, 3.0, 4.0)).unwrap();
    assert!(
        near.certified
            && (near.distance - 5.0).abs() <= 1e-15
            && (near.point.x - 1.25).abs() <= 1e-15
    );
}

#[test]
fn extreme_scales() {
    // The folded bicubic scaled by 2⁻⁴⁰⁰ and 10⁹⁰ with its query point:
    // the same answer, scaled, certified.
    let base = folded_bicubic();
    let p = Point3::new(0.4, 0.3, 0.7);
    let reference = base.nearest_point(&p).unwrap();
    for k in [2f64.powi(-400), 1e-150, 1e90] {
        let grid = base
            .points()
            .iter()
            .map(|row| row.iter().map(|q| q * k).collect())
            .collect();
        let s = BezierSurface::new(grid).unwrap();
        let near = s.nearest_point(&(p * k)).unwrap();
        assert!(near.certified, "{k}");
        assert!(
            (near.distance / k - reference.distance).abs() <= 1e-12,
            "{k}: {near:?}"
        );
    }
}

#[test]
fn high_degrees_are_searched_without_a_certificate() {
    // Degree 25 in u: beyond the Bernstein form's degrees, boxes alone
    // cannot settle the minimum; the answer is still the nearest, but not
    // certified.
    let net: Vec<Vec<Point3<f64>>> = (0..26)
        .map(|i| {
            let x = i as f64 / 25.0;
            vec![
                Point3::new(x, 0.0, 0.2 * (6.0 * x).sin()),
                Point3::new(x, 1.0, 0.0),
            ]
        })
        .collect();
    let s = BezierSurface::new(net).unwrap();
    let p = Point3::new(0.3, 0.4, 0.6);
    let near = s.nearest_point(&p).unwrap();
    assert!(!near.certified);
    let reference = sampled_nearest(&s, &p, SIDE);
    check(&s, &p, &near, &reference, 1.0);
}

#[test]
fn bad_query_points_are_errors() {
    let bezier = folded_bicubic();
    let bspline = wavy_bspline();
    let nurbs = sphere_octant(1.0);
    let model = BezierPatches::new(vec![folded_bicubic()]).unwrap();
    let bad = [
        (Point3::new(f64::NAN, 0.0, 0.0), 0, f64::NAN),
        (Point3::new(0.0, f64::INFINITY, 0.0), 1, f64::INFINITY),
        (Point3::new(0.0, 0.0, -1e101), 2, -1e101),
    ];
    for (p, coordinate, value) in bad {
        let results = [
            bezier.nearest_point(&p),
            bspline.nearest_point(&p),
            nurbs.nearest_point(&p),
            model.nearest_point(&p),
        ];
        for r in results {
            match r {
                Err(Error::InvalidQueryPoint {
                    coordinate: c,
                    value: v,
                }) => {
                    assert_eq!(c, coordinate);
                    assert!(v == value || (v.is_nan() && value.is_nan()));
                }
                other => panic!("{p:?}: {other:?}"),
            }
        }
    }
    // The largest accepted coordinate is fine.
    let near = bezier
        .nearest_point(&Point3::new(1e100, -1e100, 1e100))
        .unwrap();
    assert!(near.distance.is_finite() && near.certified);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random bicubic and biquadratic nets (rational or not) and query
    /// points: certified, and not beaten by a refined 60 × 60 sampling.
    #[test]
    fn random_patches_are_never_beaten(seed in 1u64..1_000_000, rational in any::<bool>()) {
        let mut rng = Xorshift64Star(seed);
        let (rows, cols) = if seed % 2 == 0 { (4, 4) } else { (3, 4) };
        let grid = rng.grid(rows, cols);
        let knots = |n: usize| {
            let mut k = vec![0.0; n];
            k.extend(vec![1.0; n]);
            k
        };
        let weights = if rational { rng.weights(rows, cols) } else { vec![vec![1.0; cols]; rows] };
        let s = NurbsSurface::new((rows - 1, cols - 1), (knots(rows), knots(cols)), grid.clone(), weights).unwrap();
        for _ in 0..4 {
            let p = Point3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let near = s.nearest_point(&p).unwrap();
            prop_assert!(near.certified);
            let reference = sampled_nearest(&s, &p, 60);
            prop_assert_eq!(near.point, s.eval(near.uv.0, near.uv.1));
            prop_assert!(near.distance <= reference.distance + 1e-12 * size_of(&grid, &p), "{:?} vs {:?}", near, reference);
        }
    }
}

#[test]
fn reversed_surfaces_have_the_same_nearest_points() {
    // Reversal flips normals only: the same points, the same answers.
    let gentle = common::patch_shapes::gentle_bicubic();
    let octant = sphere_octant(1.0);
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    let mut rng = Xorshift64Star(29);
    for _ in 0..20 {
        let p = Point3::new(
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
            rng.range(-2.0, 3.0),
        );
        assert_eq!(
            gentle.reversed().nearest_point(&p),
            gentle.nearest_point(&p)
        );
        assert_eq!(
            octant.reversed().nearest_point(&p),
            octant.nearest_point(&p)
        );
        assert_eq!(model.reversed().nearest_point(&p), model.nearest_point(&p));
    }
}

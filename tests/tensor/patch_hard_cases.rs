//! Hard cases of the certified ray–patch intersector (`Intersect` on
//! `BezierSurface`, `BSplineSurface`, `NurbsSurface`), one named test each,
//! against closed forms where there are some and against the independent
//! reference (`common::patch_reference`) elsewhere: collapsed edges and
//! corners, patch boundaries and knot lines, grazing rays on the sphere
//! octant and the quarter cylinder (both sides of tangency), secondary rays
//! and `(t_min, t_max)` windows on a folded patch, scaled and far translated
//! patches, ruled and nearly planar patches, rays in and parallel to a
//! plane, rays starting inside the box, unnormalized directions.
//!
//! Every hit is checked to lie on its ray and on the surface
//! (`check_patch_hit`: `eval(uv)` within `1e-12` of the scale of
//! `origin + t·dir`, the normal the surface's).

use revolve_testkit as common;

use common::Rng;
use common::patch_reference::{
    RefPatch, Tally, bezier_hits, bspline_hits, check_patch_hit, compare, folded_net, walk_hits,
};
use common::tensor_shapes::{
    cylinder_roots, quadratic_roots, quarter_cylinder, sphere_octant, sphere_roots,
};
use revolve::nalgebra::{Matrix3, Point3, Vector3};
use revolve::{BSplineSurface, BezierSurface, Intersect, Ray, Surface};

const INF: f64 = f64::INFINITY;

/// The nearest hit in `(t_min, t_max)`, checked, or `None`.
fn nearest<S: Surface + Intersect>(
    s: &S,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
) -> Option<revolve::Hit> {
    let hit = s.intersect(ray, t_min, t_max);
    if let Some(h) = &hit {
        check_patch_hit(s, ray, h, t_min, t_max);
    }
    hit
}

/// Asserts `|got − want| ≤ tol`.
fn close(got: f64, want: f64, tol: f64, what: &str) {
    common::assert_close(got, want, tol, what);
}

// ---------------------------------------------------------------------------
// Collapsed edges and corners
// ---------------------------------------------------------------------------

/// A bicubic dome over the quarter `x, y ≥ 0`: row `i` (along `u`) is a
/// circle-like cubic of radius `rᵢ` at height `zᵢ`, `(r, z)` = `(0, 1)`,
/// `(0.6, 1)`, `(1, 0.5)`, `(1, 0)`. The whole row `u = 0` is the apex
/// `(0, 0, 1)` (as on the teapot's lid); there the tangent plane is `z = 1`
/// and the limit normal `+z`.
fn dome() -> BezierSurface {
    let c = 0.552_284_749_830_793_4;
    let turn = [(1.0, 0.0), (1.0, c), (c, 1.0), (0.0, 1.0)];
    let rows = [(0.0, 1.0), (0.6, 1.0), (1.0, 0.5), (1.0, 0.0)];
    let net = rows
        .iter()
        .map(|&(r, z)| {
            turn.iter()
                .map(|&(x, y)| Point3::new(r * x, r * y, z))
                .collect()
        })
        .collect();
    BezierSurface::new(net).unwrap()
}

/// Straight down through the dome's apex (a collapsed edge): the hit is the
/// apex at `t = 1`, `u = 0`, with the limit normal `+z`; obliquely from
/// above through the apex too (nothing lies above `z = 1`).
#[test]
fn ray_down_through_a_collapsed_apex_hits_with_the_limit_normal() {
    let s = dome();
    let apex = Point3::new(0.0, 0.0, 1.0);
    let down = Ray::new(Point3::new(0.0, 0.0, 2.0), Vector3::new(0.0, 0.0, -1.0));
    let h = nearest(&s, &down, 0.0, INF).expect("the apex");
    close(h.t, 1.0, 1e-12, "t at the apex");
    assert!((h.point - apex).norm() <= 1e-12, "point {:?}", h.point);
    assert!(h.uv.0 <= 1e-6, "u = {} at the apex", h.uv.0);
    assert!(
        (h.normal.into_inner() - Vector3::z()).norm() <= 1e-9,
        "normal {:?}",
        h.normal
    );
    // The limit normal is the same along the whole collapsed row.
    for v in [0.0, 0.3, 1.0] {
        let n = s.normal(0.0, v).expect("limit normal");
        assert!(
            (n.into_inner() - Vector3::z()).norm() <= 1e-9,
            "normal at v = {v}: {n:?}"
        );
    }
    // Only one hit: only the apex lies on the line x = y = 0 (the rows'
    // radius vanishes only at u = 0).
    assert!(s.intersect(&down, h.t, INF).is_none());
    let mut rng = Rng(0xA9E);
    for _ in 0..500 {
        let d = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, -0.2),
        );
        let ray = Ray::new(apex - d, d);
        let h = nearest(&s, &ray, 0.0, INF).expect("the apex from above");
        close(h.t, 1.0, 1e-9, "t through the apex");
        assert!((h.point - apex).norm() <= 1e-9, "point {:?}", h.point);
        assert!(h.normal.z >= 1.0 - 1e-6, "normal {:?}", h.normal);
    }
}

/// Vertical rays ever closer to the apex (offsets `1e-3 … 1e-12` into the
/// quarter): the dome is a height field over its footprint (radius and
/// angle both increase along their parameters), so each ray hits once, at
/// `t = 2 − z ∈ [1, 1 + offset]`, with a normal tending to `+z`.
#[test]
fn vertical_rays_next_to_a_collapsed_apex_hit_once() {
    let s = dome();
    for k in [3, 6, 9, 12] {
        let e = 10f64.powi(-k);
        for (a, b) in [(e, e), (e, 0.5 * e), (0.1 * e, e)] {
            let ray = Ray::new(Point3::new(a, b, 2.0), Vector3::new(0.0, 0.0, -1.0));
            let hits = walk_hits(&s, &ray, 0.0, INF, 4);
            assert_eq!(hits.len(), 1, "hits {hits:?} at offset {e:e}");
            let h = &hits[0];
            check_patch_hit(&s, &ray, h, 0.0, INF);
            assert!(
                h.t >= 1.0 - 1e-15 && h.t <= 1.0 + e,
                "t {} at offset {e:e}",
                h.t
            );
            assert!(
                h.normal.z >= 1.0 - 10.0 * e.max(1e-9),
                "normal {:?}",
                h.normal
            );
        }
    }
}

/// A planar patch in `z = 0` whose row `u = 0` and column `v = 0` both
/// collapse to the origin (a collapsed corner where two collapsed edges
/// meet): a ray through that corner hits it, and the normal there (a limit
/// twice over) is the plane's, `+z`.
#[test]
fn ray_through_a_corner_where_two_edges_collapse() {
    let net: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    if i == 0 || j == 0 {
                        Point3::origin()
                    } else {
                        Point3::new(i as f64 / 3.0, j as f64 / 3.0, 0.0)
                    }
                })
                .collect()
        })
        .collect();
    let s = BezierSurface::new(net).unwrap();
    let mut rng = Rng(0xC0C);
    for _ in 0..500 {
        let d = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, -0.1),
        );
        let ray = Ray::new(Point3::origin() - d, d);
        let h = nearest(&s, &ray, 0.0, INF).expect("the collapsed corner");
        close(h.t, 1.0, 1e-9, "t at the corner");
        assert!(h.point.coords.norm() <= 1e-9, "point {:?}", h.point);
        assert!(
            (h.normal.into_inner() - Vector3::z()).norm() <= 1e-9,
            "normal {:?}",
            h.normal
        );
    }
}

/// The NURBS sphere octant's pole (its row `u = 0` collapsed) hit
/// obliquely: the point is the pole, the normal `+z`.
#[test]
fn oblique_rays_through_the_sphere_octants_pole() {
    let s = sphere_octant(1.0);
    let pole = Point3::new(0.0, 0.0, 1.0);
    let mut rng = Rng(0x901E);
    for _ in 0..500 {
        // From above and outside the sphere, toward the pole.
        let d = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, -0.3),
        );
        let ray = Ray::new(pole - d, d);
        let h = nearest(&s, &ray, 0.0, INF).expect("the pole");
        close(h.t, 1.0, 1e-9, "t at the pole");
        assert!((h.point - pole).norm() <= 1e-9);
        assert!(
            (h.normal.into_inner() - Vector3::z()).norm() <= 1e-6,
            "normal {:?}",
            h.normal
        );
    }
}

// ---------------------------------------------------------------------------
// Patch boundaries, corners and knot lines
// ---------------------------------------------------------------------------

/// A bicubic height field over `[0, 1]²` whose `x` and `y` control
/// coordinates are `i/3` and `j/3` (linear precision: `S(u, v) = (u, v, z)`),
/// heights random in `±amplitude`.
fn height_field(rng: &mut Rng, amplitude: f64) -> (BezierSurface, RefPatch) {
    let net: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    Point3::new(
                        i as f64 / 3.0,
                        j as f64 / 3.0,
                        rng.range(-amplitude, amplitude),
                    )
                })
                .collect()
        })
        .collect();
    (
        BezierSurface::new(net.clone()).unwrap(),
        RefPatch::polynomial(net),
    )
}

/// Vertical rays onto a height field `S(u, v) = (u, v, z(u, v))` at `(x, y)`
/// hit at `uv = (x, y)` and `t = 2 − z(x, y)` (`z` by the reference's own
/// Bernstein sums), once.
fn assert_vertical_hit(s: &BezierSurface, r: &RefPatch, x: f64, y: f64) {
    let ray = Ray::new(Point3::new(x, y, 2.0), Vector3::new(0.0, 0.0, -1.0));
    let hits = walk_hits(s, &ray, 0.0, INF, 4);
    assert_eq!(hits.len(), 1, "hits {hits:?} at ({x}, {y})");
    let h = &hits[0];
    check_patch_hit(s, &ray, h, 0.0, INF);
    let (p, _, _) = r.jet(x, y);
    close(h.t, 2.0 - p.z, 1e-12, "t of a vertical ray");
    close(h.uv.0, x, 1e-9, "u of a vertical ray");
    close(h.uv.1, y, 1e-9, "v of a vertical ray");
}

/// Rays onto the corners and the four boundary curves (`u` or `v` = 0 or 1)
/// of height-field bicubics hit there (vertical rays: closed form; oblique
/// rays from above: the reference's nearest root); vertical rays `1e-6`
/// outside miss.
#[test]
fn rays_onto_patch_corners_and_boundaries() {
    let mut rng = Rng(0xB0D);
    for _ in 0..20 {
        let (s, r) = height_field(&mut rng, 0.5);
        for (x, y) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)] {
            assert_vertical_hit(&s, &r, x, y);
        }
        for _ in 0..10 {
            let a = rng.unit();
            for (x, y) in [(0.0, a), (1.0, a), (a, 0.0), (a, 1.0)] {
                assert_vertical_hit(&s, &r, x, y);
                let (ox, oy) = (
                    if x == 0.0 {
                        -1e-6
                    } else if x == 1.0 {
                        1.0 + 1e-6
                    } else {
                        x
                    },
                    if y == 0.0 {
                        -1e-6
                    } else if y == 1.0 {
                        1.0 + 1e-6
                    } else {
                        y
                    },
                );
                let outside = Ray::new(Point3::new(ox, oy, 2.0), Vector3::new(0.0, 0.0, -1.0));
                assert!(
                    s.intersect(&outside, 0.0, INF).is_none(),
                    "hit outside at ({ox}, {oy})"
                );
                // Obliquely from above and outside the footprint.
                let (target, _, _) = r.jet(x, y);
                let target = Point3::from(target);
                let d = Vector3::new(
                    if x == 0.0 {
                        0.5
                    } else if x == 1.0 {
                        -0.5
                    } else {
                        rng.range(-0.3, 0.3)
                    },
                    if y == 0.0 {
                        0.5
                    } else if y == 1.0 {
                        -0.5
                    } else {
                        rng.range(-0.3, 0.3)
                    },
                    -1.0,
                );
                let ray = Ray::new(target - 3.0 * d, d);
                let want = bezier_hits(&s, &ray);
                let first = want.within(0.0, INF)[0];
                let h = nearest(&s, &ray, 0.0, INF).expect("boundary hit");
                close(h.t, first.t, 1e-9, "t at a boundary (reference)");
            }
        }
    }
}

/// Greville abscissae of a clamped knot vector: `ξᵢ = (tᵢ₊₁ + … + tᵢ₊ₚ)/p`
/// (control coordinates with which `Σ ξᵢNᵢ(u) = u`).
fn greville(knots: &[f64], p: usize) -> Vec<f64> {
    (0..knots.len() - p - 1)
        .map(|i| knots[i + 1..=i + p].iter().sum::<f64>() / p as f64)
        .collect()
}

/// A bicubic B-spline height field `S(u, v) = (u, v, z)` with interior
/// knots in `u` (0.3, a double 0.5, 0.8) and in `v` (0.4, 0.7): control
/// `x`, `y` at the Greville abscissae.
fn knotted_sheet(rng: &mut Rng) -> BSplineSurface {
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0];
    let (gu, gv) = (greville(&ku, 3), greville(&kv, 3));
    let net = gu
        .iter()
        .map(|&x| {
            gv.iter()
                .map(|&y| Point3::new(x, y, rng.range(-0.4, 0.4)))
                .collect()
        })
        .collect();
    BSplineSurface::new((3, 3), (ku, kv), net).unwrap()
}

/// Vertical rays exactly on the knot lines (single and double knots) and
/// on their crossings, where two or four Bézier pieces meet, hit once at
/// `uv = (x, y)`; oblique rays onto the knot lines agree with the
/// reference's nearest root.
#[test]
fn rays_onto_bspline_knot_lines_and_their_crossings() {
    let mut rng = Rng(0x4E07);
    let (knots_u, knots_v) = ([0.3, 0.5, 0.8], [0.4, 0.7]);
    for _ in 0..10 {
        let s = knotted_sheet(&mut rng);
        let mut spots = Vec::new();
        for &x in &knots_u {
            for &y in &knots_v {
                spots.push((x, y));
            }
            spots.push((x, rng.unit()));
        }
        for &y in &knots_v {
            spots.push((rng.unit(), y));
        }
        for (x, y) in spots {
            let ray = Ray::new(Point3::new(x, y, 2.0), Vector3::new(0.0, 0.0, -1.0));
            let hits = walk_hits(&s, &ray, 0.0, INF, 4);
            assert_eq!(hits.len(), 1, "hits {hits:?} at ({x}, {y})");
            let h = &hits[0];
            check_patch_hit(&s, &ray, h, 0.0, INF);
            close(h.uv.0, x, 1e-9, "u on a knot line");
            close(h.uv.1, y, 1e-9, "v on a knot line");
            close(h.point.x, x, 1e-12, "x on a knot line");
            close(h.point.y, y, 1e-12, "y on a knot line");
            // Obliquely onto the same point.
            let d = Vector3::new(rng.range(-0.5, 0.5), rng.range(-0.5, 0.5), -1.0);
            let ray = Ray::new(h.point - 2.0 * d, d);
            let want = bspline_hits(&s, &ray);
            assert!(!want.doubtful);
            let first = want.within(0.0, INF)[0];
            let g = nearest(&s, &ray, 0.0, INF).expect("knot-line hit");
            close(g.t, first.t, 1e-9, "t on a knot line (reference)");
        }
    }
}

/// The sphere octant with knots inserted (`u = 0.5` once, `v = 0.25`
/// twice) is still the sphere: rays aimed at points of the knot lines hit
/// where the ray–sphere quadratic says.
#[test]
fn rays_onto_nurbs_knot_lines_hit_the_sphere() {
    let s = sphere_octant(1.0)
        .insert_knot_u(0.5, 1)
        .unwrap()
        .insert_knot_v(0.25, 2)
        .unwrap();
    let mut rng = Rng(0x5EA);
    for k in 0..200 {
        let (u, v) = if k % 2 == 0 {
            (0.5, rng.range(0.05, 0.95))
        } else {
            (rng.range(0.05, 0.95), 0.25)
        };
        let target = s.eval(u, v);
        let origin = Point3::from(target.coords * 3.0 + rng.direction() * 0.5);
        let ray = Ray::new(origin, target - origin);
        let (roots, _) = sphere_roots(1.0, &ray.origin, &ray.dir);
        let h = nearest(&s, &ray, 0.0, INF).expect("a knot-line hit");
        close(h.t, roots[0], 1e-9, "t on a NURBS knot line");
        close(h.normal.dot(&h.point.coords), 1.0, 1e-9, "radial normal");
    }
}

// ---------------------------------------------------------------------------
// Grazing rays on silhouettes
// ---------------------------------------------------------------------------

/// Rays tangent to the sphere octant at points inside it, moved `δ` toward
/// the centre (two hits `√(2δ)` apart: both found, the quadratic's) or away
/// from it by a clear margin (a miss); the exactly tangent ray may touch,
/// but only at the tangent point.
#[test]
fn grazing_rays_on_the_sphere_octant_from_both_sides() {
    let s = sphere_octant(1.0);
    let spots = [
        Vector3::new(1.0, 2.0, 2.0) / 3.0,
        Vector3::new(0.6, 0.0, 0.8) + Vector3::new(0.0, 0.3, 0.0),
        Vector3::new(0.3, 0.3, 0.9),
    ];
    let mut rng = Rng(0x6A2);
    for spot in spots {
        let tangent_point = spot.normalize();
        for _ in 0..8 {
            let d = tangent_point.cross(&rng.direction()).normalize();
            for dir in [d, -d] {
                for delta in [1e-3, 1e-5, 1e-7] {
                    let origin = Point3::from(tangent_point * (1.0 - delta) - 3.0 * dir);
                    let ray = Ray::new(origin, dir);
                    let (roots, _) = sphere_roots(1.0, &ray.origin, &ray.dir);
                    let hits = walk_hits(&s, &ray, 0.0, INF, 4);
                    assert_eq!(hits.len(), 2, "δ = {delta:e}: hits {hits:?} for {ray:?}");
                    for (h, t) in hits.iter().zip(&roots) {
                        check_patch_hit(&s, &ray, h, 0.0, INF);
                        close(h.t, *t, 1e-9, "grazing t");
                    }
                }
                for delta in [1e-4, 1e-6] {
                    let origin = Point3::from(tangent_point * (1.0 + delta) - 3.0 * dir);
                    let ray = Ray::new(origin, dir);
                    let got = s.intersect(&ray, 0.0, INF);
                    assert!(got.is_none(), "δ = −{delta:e}: hit {got:?} for {ray:?}");
                }
                let ray = Ray::new(Point3::from(tangent_point - 3.0 * dir), dir);
                for h in walk_hits(&s, &ray, 0.0, INF, 4) {
                    check_patch_hit(&s, &ray, &h, 0.0, INF);
                    close(h.t, 3.0, 1e-6, "tangent touch");
                }
            }
        }
    }
}

/// Rays tangent to the quarter cylinder (radius 1, height 2), across the
/// axis and slanted: `δ` inside gives the quadratic's two hits, `δ` outside
/// a miss. Rays parallel to the axis just inside and just outside the wall
/// miss; a ray along a ruling of the wall (in the surface) may report any
/// point of it, but only one on the ray and the surface.
#[test]
fn grazing_rays_on_the_quarter_cylinder_from_both_sides() {
    let s = quarter_cylinder(1.0, 2.0);
    for phi in [0.3, 0.785, 1.2] {
        let (c, sn) = (f64::cos(phi), f64::sin(phi));
        for slope in [0.0, 0.3, -0.4] {
            for sign in [1.0, -1.0] {
                let dir = Vector3::new(-sn * sign, c * sign, slope);
                let at = |delta: f64| {
                    Point3::new(c * (1.0 - delta), sn * (1.0 - delta), 1.0) - 3.0 * dir
                };
                for delta in [1e-3, 1e-5, 1e-7] {
                    let ray = Ray::new(at(delta), dir);
                    let (roots, _) = cylinder_roots(1.0, &ray.origin, &ray.dir);
                    let hits = walk_hits(&s, &ray, 0.0, INF, 4);
                    assert_eq!(hits.len(), 2, "δ = {delta:e}: hits {hits:?} for {ray:?}");
                    for (h, t) in hits.iter().zip(&roots) {
                        check_patch_hit(&s, &ray, h, 0.0, INF);
                        close(h.t, *t, 1e-9, "grazing t on the cylinder");
                        let radial = Vector3::new(h.point.x, h.point.y, 0.0);
                        close(h.normal.dot(&radial), 1.0, 1e-9, "radial normal");
                    }
                }
                for delta in [-1e-4, -1e-6] {
                    let ray = Ray::new(at(delta), dir);
                    let got = s.intersect(&ray, 0.0, INF);
                    assert!(got.is_none(), "δ = {delta:e}: hit {got:?} for {ray:?}");
                }
            }
        }
        for delta in [1e-6, -1e-6] {
            let r = 1.0 - delta;
            let ray = Ray::new(Point3::new(r * c, r * sn, -1.0), Vector3::z());
            let got = s.intersect(&ray, 0.0, INF);
            assert!(got.is_none(), "parallel to the axis at {r}: {got:?}");
        }
    }
    // Along the ruling u = 0 (x = 1, y = 0, exactly representable).
    let ray = Ray::new(Point3::new(1.0, 0.0, -1.0), Vector3::z());
    for h in walk_hits(&s, &ray, 0.0, INF, 8) {
        check_patch_hit(&s, &ray, &h, 0.0, INF);
    }
}

/// The quarter cylinder against the ray–cylinder quadratic for random
/// rays (rays within `1e-7` of its edges or of tangency skipped): every hit,
/// walked, and the normal radial.
#[test]
fn quarter_cylinder_hits_where_the_quadratic_says() {
    let mut rng = Rng(0xC1C);
    let mut hits = 0;
    for (r, h) in [(1.0, 2.0), (1e-4, 3e-4), (1e5, 1e5)] {
        let s = quarter_cylinder(r, h);
        for _ in 0..500 {
            let origin = Point3::from(rng.direction() * 4.0 * r.max(h));
            let target = Point3::new(
                rng.range(-0.1, 1.1) * r,
                rng.range(-0.1, 1.1) * r,
                rng.range(-0.1, 1.1) * h,
            );
            let ray = Ray::new(origin, (target - origin) * rng.range(0.2, 5.0));
            let (all, disc) = cylinder_roots(r, &ray.origin, &ray.dir);
            let mut near = disc.abs() < 1e-8;
            let mut want = Vec::new();
            for t in all {
                let p = ray.at(t);
                let m = (p.x / r).min(p.y / r).min(p.z / h).min(1.0 - p.z / h);
                near |= m.abs() < 1e-7;
                if t > 0.0 && m >= 0.0 {
                    want.push(t);
                }
            }
            if near {
                continue;
            }
            let got = walk_hits(&s, &ray, 0.0, INF, 4);
            assert_eq!(
                got.len(),
                want.len(),
                "got {got:?}, want {want:?} for {ray:?}"
            );
            let dn = ray.dir.norm();
            for (g, t) in got.iter().zip(&want) {
                check_patch_hit(&s, &ray, g, 0.0, INF);
                close(g.t * dn, t * dn, 1e-9 * r.max(h), "cylinder t·|d|");
                let radial = Vector3::new(g.point.x, g.point.y, 0.0) / r;
                close(g.normal.dot(&radial), 1.0, 1e-9, "radial normal");
                hits += 1;
            }
        }
    }
    assert!(hits > 500, "{hits} hits");
}

/// Secondary rays inside the quarter cylinder (its concave side): a ray
/// from inside hits the wall once (the quadratic's positive root); the ray
/// continued from the hit point finds nothing (no self-hit); the ray
/// reflected there meets the wall again where the quadratic's nonzero root
/// says (when that point is on the quarter), or misses.
#[test]
fn secondary_rays_inside_the_quarter_cylinder() {
    let s = quarter_cylinder(1.0, 2.0);
    let mut rng = Rng(0x2EF);
    let (mut bounces, mut misses) = (0, 0);
    for _ in 0..300 {
        // Near the wall, heading along it (counter-clockwise), so that
        // the reflected ray may meet the quarter again.
        let phi = rng.range(0.05, 0.6);
        let rho = rng.range(0.8, 0.98);
        let origin = Point3::new(rho * phi.cos(), rho * phi.sin(), rng.range(0.5, 1.5));
        let a = phi + rng.range(0.8, 1.5);
        let d = Vector3::new(a.cos(), a.sin(), rng.range(-0.3, 0.3));
        let ray = Ray::new(origin, d);
        let (roots, _) = cylinder_roots(1.0, &ray.origin, &ray.dir);
        let t = roots[1];
        let p = ray.at(t);
        if p.z.min(2.0 - p.z) < 1e-6 {
            continue;
        }
        let h = nearest(&s, &ray, 0.0, INF).expect("the wall from inside");
        close(h.t, t, 1e-9, "t from inside");
        let on = Ray::new(h.point, d);
        let again = s.intersect(&on, 0.0, INF);
        assert!(again.is_none(), "self-hit {again:?} from {:?}", h.point);
        let n = h.normal.into_inner();
        let r = d - 2.0 * d.dot(&n) * n;
        let bounce = Ray::new(h.point, r);
        let (roots, _) = cylinder_roots(1.0, &bounce.origin, &bounce.dir);
        // One root is the start (≈ 0); the other the wall across.
        let far = if roots[0].abs() > roots[1].abs() {
            roots[0]
        } else {
            roots[1]
        };
        let q = bounce.at(far);
        let margin = q.x.min(q.y).min(q.z).min(2.0 - q.z);
        if margin.abs() < 1e-7 {
            continue;
        }
        let got = nearest(&s, &bounce, 0.0, INF);
        if far > 0.0 && margin > 0.0 {
            close(got.expect("the wall across").t, far, 1e-9, "reflected t");
            bounces += 1;
        } else {
            assert!(got.is_none(), "reflected ray {bounce:?}: {got:?}");
            misses += 1;
        }
    }
    assert!(
        bounces > 50 && misses > 20,
        "{bounces} bounces, {misses} misses"
    );
}

/// The hyperbolic paraboloid `z = xy` over `[0, 1]²` has straight
/// boundaries (rulings): rays along them lie in the surface, so any hit
/// reported is a point of that boundary, on the ray and the surface; the
/// same lines moved `1e-6` outside the patch meet `z = xy` only outside it
/// (or not at all) and miss.
#[test]
fn rays_along_the_straight_boundaries_of_a_ruled_patch() {
    let s = BezierSurface::new(vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
        vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    let e = 1e-6;
    // (start, direction, which boundary: (parameter index, value)), and the
    // line moved outside.
    let lines = [
        (
            Point3::new(0.0, -1.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            (0, 0.0),
            Vector3::new(-e, 0.0, 0.0),
        ),
        (
            Point3::new(1.0, -1.0, -1.0),
            Vector3::new(0.0, 1.0, 1.0),
            (0, 1.0),
            Vector3::new(e, 0.0, 0.0),
        ),
        (
            Point3::new(-1.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            (1, 0.0),
            Vector3::new(0.0, -e, 0.0),
        ),
        (
            Point3::new(-1.0, 1.0, -1.0),
            Vector3::new(1.0, 0.0, 1.0),
            (1, 1.0),
            Vector3::new(0.0, e, 0.0),
        ),
    ];
    for (start, dir, (which, value), out) in lines {
        for sign in [1.0, -1.0] {
            let (o, d) = if sign > 0.0 {
                (start, dir)
            } else {
                (start + 3.0 * dir, -dir)
            };
            let ray = Ray::new(o, d);
            for h in walk_hits(&s, &ray, 0.0, INF, 4) {
                check_patch_hit(&s, &ray, &h, 0.0, INF);
                let param = if which == 0 { h.uv.0 } else { h.uv.1 };
                close(param, value, 1e-6, "hit on the ruling's parameter");
            }
            let moved = Ray::new(o + out, d);
            let got = s.intersect(&moved, 0.0, INF);
            assert!(got.is_none(), "line moved outside {moved:?}: {got:?}");
        }
    }
}

// ---------------------------------------------------------------------------
// A folded patch: secondary rays and windows
// ---------------------------------------------------------------------------

/// A ribbon folded like an S: `S(u, v) = (2u − 1, 2v − 1, z(u))` with
/// `z` the cubic of Bézier ordinates `−1, 2, −2, 1`, i.e.
/// `z = 14u³ − 21u² + 9u − 1 = (u − ½)(14u² − 14u + 2)`: the line along `x`
/// at `z = 0` crosses it at `u = ½` and `u = ½ ± √84/28`.
fn s_ribbon() -> BezierSurface {
    let z = [-1.0, 2.0, -2.0, 1.0];
    let net = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| Point3::new(2.0 * i as f64 / 3.0 - 1.0, 2.0 * j as f64 / 3.0 - 1.0, z[i]))
                .collect()
        })
        .collect();
    BezierSurface::new(net).unwrap()
}

/// The three `u` where the ribbon crosses `z = 0`, ascending.
fn ribbon_roots() -> [f64; 3] {
    let h = 84f64.sqrt() / 28.0;
    [0.5 - h, 0.5, 0.5 + h]
}

/// Along `x` at height 0 the S-ribbon is met three times, at
/// `x = 2u − 1` for its three roots: the walk of secondary rays (`t_min` =
/// the previous hit) finds them in order; new rays started at each hit point
/// find the next one and never their own start; rays reflected at each hit
/// agree with the reference's nearest root beyond their start.
#[test]
fn secondary_rays_on_a_folded_patch() {
    let s = s_ribbon();
    let xs = ribbon_roots().map(|u| 2.0 * u - 1.0);
    for y in [-0.7, 0.0, 0.35, 0.9] {
        for sign in [1.0, -1.0] {
            let ray = Ray::new(
                Point3::new(-3.0 * sign, y, 0.0),
                Vector3::new(sign, 0.0, 0.0),
            );
            let mut want: Vec<f64> = xs.iter().map(|x| 3.0 + sign * x).collect();
            want.sort_by(f64::total_cmp);
            let hits = walk_hits(&s, &ray, 0.0, INF, 6);
            assert_eq!(hits.len(), 3, "hits {hits:?} for {ray:?}");
            for (h, t) in hits.iter().zip(&want) {
                check_patch_hit(&s, &ray, h, 0.0, INF);
                close(h.t, *t, 1e-12, "t on the S-ribbon");
                close(h.point.z, 0.0, 1e-12, "z on the S-ribbon");
            }
            for k in 0..3 {
                let from = Ray::new(hits[k].point, ray.dir);
                let next = nearest(&s, &from, 0.0, INF);
                match want.get(k + 1) {
                    Some(t) => close(next.expect("the next fold").t, t - want[k], 1e-12, "next"),
                    None => assert!(next.is_none(), "self-hit {next:?} from the last fold"),
                }
                // Reflected at the hit.
                let n = hits[k].normal.into_inner();
                let d = ray.dir - 2.0 * ray.dir.dot(&n) * n;
                let bounce = Ray::new(hits[k].point, d);
                let reference = bezier_hits(&s, &bounce);
                let beyond = reference.within(1e-9, INF);
                let got = nearest(&s, &bounce, 0.0, INF);
                match (got, beyond.first()) {
                    (Some(g), Some(w)) => close(g.t, w.t, 1e-9, "reflected ray"),
                    (None, None) => {}
                    (g, w) => panic!("reflected ray {bounce:?}: got {g:?}, reference {w:?}"),
                }
            }
        }
    }
}

/// Windows `(t_min, t_max)` cutting between the S-ribbon's three roots
/// `t₁ < t₂ < t₃`: the nearest root inside the window, or a miss; a window
/// behind the origin (negative `t`) finds the roots behind.
#[test]
fn windows_between_the_roots_of_a_folded_patch() {
    let s = s_ribbon();
    let ray = Ray::new(Point3::new(-3.0, 0.2, 0.0), Vector3::new(1.0, 0.0, 0.0));
    let [t1, t2, t3] = ribbon_roots().map(|u| 2.0 * u + 2.0);
    let e = 1e-6;
    let cases: [(f64, f64, Option<f64>); 10] = [
        (0.0, t1 - e, None),
        (t1 - e, t1 + e, Some(t1)),
        (t1 - e, INF, Some(t1)),
        (t1, t3, Some(t2)),
        (t1 + e, t2 - e, None),
        (0.5 * (t1 + t2), 0.5 * (t2 + t3), Some(t2)),
        (t2 + e, t3 - e, None),
        (t2 + e, INF, Some(t3)),
        (t3 - e, t3 + e, Some(t3)),
        (t3 + e, INF, None),
    ];
    for (lo, hi, want) in cases {
        let got = nearest(&s, &ray, lo, hi);
        match (got, want) {
            (Some(h), Some(t)) => close(h.t, t, 1e-12, "t in a window"),
            (None, None) => {}
            (g, w) => panic!("window ({lo}, {hi}): got {g:?}, want {w:?}"),
        }
    }
    // From the middle fold's right: the first two roots lie behind.
    let mid = Ray::new(Point3::new(0.2, 0.2, 0.0), Vector3::new(1.0, 0.0, 0.0));
    let [x1, x2, _] = ribbon_roots().map(|u| 2.0 * u - 1.0);
    let h = nearest(&s, &mid, -10.0, 0.0).expect("a root behind");
    close(h.t, x1 - 0.2, 1e-12, "first root behind the origin");
    let h = nearest(&s, &mid, x1 - 0.2, 0.0).expect("the second root behind");
    close(h.t, x2 - 0.2, 1e-12, "second root behind the origin");
}

// ---------------------------------------------------------------------------
// Scale and translation
// ---------------------------------------------------------------------------

/// Folded bicubics scaled by `1e-6` and `1e6`, and translated by `1e4`,
/// with their rays scaled and moved alike: the hits walked along each ray
/// have the same `t` (to `1e-9`, `t` does not change under the map) and
/// `uv` (to `1e-6`) as the unit-size patch's, which agree with the
/// reference.
#[test]
fn scaled_and_far_translated_patches_hit_alike() {
    let mut rng = Rng(0x5CA1E);
    let offset = Vector3::new(1e4, -1e4, 1e4);
    let maps: [(f64, Vector3<f64>); 4] = [
        (1e-6, Vector3::zeros()),
        (1e6, Vector3::zeros()),
        (1.0, offset),
        (1e6, offset * 1e6),
    ];
    let mut tally = Tally::default();
    let mut compared = 0;
    for n in 0..30 {
        let net = folded_net(&mut rng, n % 3);
        let unit = BezierSurface::new(net.clone()).unwrap();
        for _ in 0..8 {
            let origin = Point3::from(rng.direction() * 4.0);
            let target = rng.point([-1.0; 3], [1.0; 3]);
            let ray = Ray::new(origin, target - origin);
            let want = bezier_hits(&unit, &ray);
            compare(&unit, &want, &ray, 1.0, &mut tally);
            if !want.clear(0.0, INF, 1e-2, 1e-6) {
                continue;
            }
            let base = walk_hits(&unit, &ray, 0.0, INF, 8);
            for (k, o) in maps {
                let moved: Vec<Vec<Point3<f64>>> = net
                    .iter()
                    .map(|row| row.iter().map(|p| Point3::from(p.coords * k + o)).collect())
                    .collect();
                let s = BezierSurface::new(moved).unwrap();
                let r = Ray::new(Point3::from(ray.origin.coords * k + o), ray.dir * k);
                let got = walk_hits(&s, &r, 0.0, INF, 8);
                assert_eq!(
                    got.len(),
                    base.len(),
                    "scale {k:e}, offset {o:?}: {got:?} vs {base:?}"
                );
                for (g, b) in got.iter().zip(&base) {
                    check_patch_hit(&s, &r, g, 0.0, INF);
                    close(g.t, b.t, 1e-9, "t under scaling/translation");
                    close(g.uv.0, b.uv.0, 1e-6, "u under scaling/translation");
                    close(g.uv.1, b.uv.1, 1e-6, "v under scaling/translation");
                }
                compared += 1;
            }
        }
    }
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(compared > 600, "{compared} compared");
}

// ---------------------------------------------------------------------------
// Ruled and nearly planar patches
// ---------------------------------------------------------------------------

/// Bilinear patches `S = P₀₀ + a·u + b·v + c·uv` (`a, b, c` independent)
/// are affine images `P₀₀ + M·(u, v, uv)` of the hyperbolic paraboloid
/// `z = xy`: pulling the ray back by `M⁻¹` gives the quadratic
/// `d′ₓd′ᵧt² + (o′ₓd′ᵧ + o′ᵧd′ₓ − d′_z)t + o′ₓo′ᵧ − o′_z = 0` with the same
/// `t`. Every hit, walked, agrees with it (rays within `1e-7` of an edge or
/// of tangency skipped).
#[test]
fn bilinear_patches_are_affine_hyperbolic_paraboloids() {
    let mut rng = Rng(0xB1);
    let (mut hits, mut doubles) = (0, 0);
    for n in 0..100 {
        let p00 = rng.point([-1.0; 3], [1.0; 3]);
        let m = if n == 0 {
            Matrix3::identity()
        } else {
            Matrix3::from_fn(|_, _| rng.range(-1.0, 1.0))
        };
        let Some(inverse) = m.try_inverse() else {
            continue;
        };
        let at = |u: f64, v: f64| p00 + m * Vector3::new(u, v, u * v);
        let s = BezierSurface::new(vec![
            vec![at(0.0, 0.0), at(0.0, 1.0)],
            vec![at(1.0, 0.0), at(1.0, 1.0)],
        ])
        .unwrap();
        for _ in 0..30 {
            let origin = Point3::from(rng.direction() * 5.0);
            let target = at(rng.range(-0.1, 1.1), rng.range(-0.1, 1.1));
            let ray = Ray::new(origin, target - origin);
            let (o, d) = (inverse * (ray.origin - p00), inverse * ray.dir);
            let (all, disc) =
                quadratic_roots(d.x * d.y, o.x * d.y + o.y * d.x - d.z, o.x * o.y - o.z);
            let mut near = disc.abs() < 1e-7;
            let mut want = Vec::new();
            for t in all {
                let q = o + d * t;
                let edge = q.x.min(q.y).min(1.0 - q.x).min(1.0 - q.y);
                near |= edge.abs() < 1e-7;
                if t > 0.0 && edge >= 0.0 {
                    want.push(t);
                }
            }
            if near {
                continue;
            }
            let got = walk_hits(&s, &ray, 0.0, INF, 4);
            assert_eq!(
                got.len(),
                want.len(),
                "got {got:?}, want {want:?} for {ray:?} on the net {:?}",
                s.points()
            );
            for (g, t) in got.iter().zip(&want) {
                check_patch_hit(&s, &ray, g, 0.0, INF);
                close(g.t * ray.dir.norm(), t * ray.dir.norm(), 1e-9, "bilinear t");
                let q = o + d * *t;
                close(g.uv.0, q.x, 1e-6, "bilinear u");
                close(g.uv.1, q.y, 1e-6, "bilinear v");
                hits += 1;
            }
            doubles += usize::from(want.len() == 2);
        }
    }
    assert!(
        hits > 1000 && doubles > 10,
        "{hits} hits, {doubles} rays with two"
    );
}

/// Degree (1, 5) and (5, 1) ruled patches `S(u, v) = (v, u, (1 − u)a(v) +
/// u·b(v))` (and the transpose), `a` and `b` quintics with random
/// ordinates: vertical rays hit at `(u, v) = (y, x)` and `z` by the
/// reference's Bernstein sums; oblique rays agree with the reference, every
/// hit walked.
#[test]
fn ruled_patches_of_degree_one_by_five() {
    let mut rng = Rng(0x15);
    let mut tally = Tally::default();
    for n in 0..20 {
        let transpose = n % 2 == 1;
        let mut net: Vec<Vec<Point3<f64>>> = (0..2)
            .map(|i| {
                (0..6)
                    .map(|j| Point3::new(j as f64 / 5.0, i as f64, rng.range(-0.8, 0.8)))
                    .collect()
            })
            .collect();
        if transpose {
            // S(u, v) = (u, v, …): rows along u are the old columns.
            net = (0..6)
                .map(|j| (0..2).map(|i| net[i][j]).collect())
                .collect();
        }
        let s = BezierSurface::new(net.clone()).unwrap();
        let reference = RefPatch::polynomial(net);
        for _ in 0..20 {
            let (x, y) = (rng.unit(), rng.unit());
            let ray = Ray::new(Point3::new(x, y, 2.0), Vector3::new(0.0, 0.0, -1.0));
            let hits = walk_hits(&s, &ray, 0.0, INF, 4);
            assert_eq!(hits.len(), 1, "{hits:?}");
            let (u, v) = if transpose { (x, y) } else { (y, x) };
            let (p, _, _) = reference.jet(u, v);
            check_patch_hit(&s, &ray, &hits[0], 0.0, INF);
            close(hits[0].t, 2.0 - p.z, 1e-12, "ruled t");
            close(hits[0].uv.0, u, 1e-9, "ruled u");
            close(hits[0].uv.1, v, 1e-9, "ruled v");
            let ray = common::patch_reference::random_ray(&mut rng, 1.0, -0.1, 1.1);
            compare(&s, &bezier_hits(&s, &ray), &ray, 1.0, &mut tally);
        }
    }
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(tally.by_count[1] + tally.by_count[2] > 120, "{tally:?}");
}

/// Bicubics within `1e-9` of the plane `z = 0` (`S = (u, v, z)`, `|z| ≤
/// 1e-9`): vertical rays hit at `uv = (x, y)` and `t = 2 − z` to `1e-12`;
/// oblique rays down to a slope of `1e-3` agree with the reference; rays
/// parallel to the plane `1e-6` above or below miss.
#[test]
fn nearly_planar_bicubics() {
    let mut rng = Rng(0x9A);
    let mut tally = Tally::default();
    for _ in 0..20 {
        let (s, r) = height_field(&mut rng, 1e-9);
        for _ in 0..10 {
            let (x, y) = (rng.unit(), rng.unit());
            assert_vertical_hit(&s, &r, x, y);
            for slope in [1.0, 1e-1, 1e-2, 1e-3] {
                let a = rng.range(0.0, std::f64::consts::TAU);
                let d = Vector3::new(a.cos(), a.sin(), -slope);
                let ray = Ray::new(Point3::new(x, y, 0.0) - 0.8 * d, d);
                compare(&s, &bezier_hits(&s, &ray), &ray, 1.0, &mut tally);
            }
            for z in [1e-6, -1e-6] {
                let a = rng.range(0.0, std::f64::consts::TAU);
                let d = Vector3::new(a.cos(), a.sin(), 0.0);
                let ray = Ray::new(Point3::new(x, y, z) - 2.0 * d, d);
                let got = s.intersect(&ray, 0.0, INF);
                assert!(got.is_none(), "parallel at z = {z}: {got:?}");
            }
        }
    }
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(tally.by_count[1] > 700, "{tally:?}");
}

/// A planar bicubic in `z = 0` (`S = (u, v, 0)`): rays parallel to it miss;
/// rays in its plane that pass beside it miss; rays in its plane across it
/// (a line of solutions) return nothing or a point of that line, never NaN.
#[test]
fn rays_parallel_to_and_in_the_plane_of_a_planar_patch() {
    let mut rng = Rng(0x91A9);
    let (s, _) = height_field(&mut rng, 0.0);
    for _ in 0..20 {
        let a = rng.range(0.0, std::f64::consts::TAU);
        let d = Vector3::new(a.cos(), a.sin(), 0.0) * rng.range(0.1, 10.0);
        let (x, y) = (rng.unit(), rng.unit());
        for z in [1e-3, -1e-3, 1e-9, -1e-9] {
            let ray = Ray::new(Point3::new(x, y, z) - 3.0 * d, d);
            let got = s.intersect(&ray, 0.0, INF);
            assert!(got.is_none(), "parallel at z = {z}: {got:?}");
        }
        let across = Ray::new(Point3::new(x, y, 0.0) - 3.0 * d, d);
        for h in walk_hits(&s, &across, 0.0, INF, 4) {
            check_patch_hit(&s, &across, &h, 0.0, INF);
            close(h.point.z, 0.0, 1e-15, "in-plane hit");
        }
        // Beside the patch in its plane: the line y = 2 (or x = 2).
        let beside = Ray::new(
            Point3::new(-3.0, 2.0, 0.0),
            Vector3::new(1.0, rng.range(-0.1, 0.1), 0.0),
        );
        assert!(s.intersect(&beside, 0.0, INF).is_none());
    }
}

// ---------------------------------------------------------------------------
// Ray set-ups
// ---------------------------------------------------------------------------

/// Rays that start inside the bounding box of folded bicubics (random
/// origins and directions) find every reference root ahead of them.
#[test]
fn rays_starting_inside_the_bounding_box() {
    let mut rng = Rng(0x1B0);
    let mut tally = Tally::default();
    for n in 0..100 {
        let net = folded_net(&mut rng, n % 3);
        let s = BezierSurface::new(net).unwrap();
        let b = s.bounds();
        for _ in 0..10 {
            let ray = Ray::new(rng.point_in(&b), rng.direction() * rng.range(0.1, 10.0));
            compare(&s, &bezier_hits(&s, &ray), &ray, b.scale(), &mut tally);
        }
    }
    assert!(tally.excluded * 50 < tally.rays, "{tally:?}");
    assert!(
        tally.by_count[1] + tally.by_count[2] + tally.by_count[3] > 150,
        "{tally:?}"
    );
}

/// The same rays with directions of length `1e-3` and `1e3`: the same hit
/// points (to `1e-9`) and `t·|d|`, walked hit by hit.
#[test]
fn unnormalized_directions_give_the_same_hit_points() {
    let mut rng = Rng(0xD12);
    let mut hits = 0;
    for n in 0..40 {
        let s = BezierSurface::new(folded_net(&mut rng, n % 3)).unwrap();
        for _ in 0..10 {
            let origin = Point3::from(rng.direction() * 4.0);
            let d = (rng.point([-1.0; 3], [1.0; 3]) - origin).normalize();
            let want = bezier_hits(&s, &Ray::new(origin, d));
            if !want.clear(0.0, INF, 1e-4, 1e-7) {
                continue;
            }
            let unit = walk_hits(&s, &Ray::new(origin, d), 0.0, INF, 8);
            for k in [1e-3, 1e3] {
                let ray = Ray::new(origin, d * k);
                let got = walk_hits(&s, &ray, 0.0, INF, 8);
                assert_eq!(got.len(), unit.len(), "|d| = {k:e}: {got:?} vs {unit:?}");
                for (g, u) in got.iter().zip(&unit) {
                    check_patch_hit(&s, &ray, g, 0.0, INF);
                    assert!((g.point - u.point).norm() <= 1e-9, "{g:?} vs {u:?}");
                    close(g.t * k, u.t, 1e-9, "t·|d|");
                    hits += 1;
                }
            }
        }
    }
    assert!(hits > 300, "{hits} hits");
}

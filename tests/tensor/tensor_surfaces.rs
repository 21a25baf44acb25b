//! Tensor-product surfaces (Bézier, B-spline, NURBS): closed forms, an
//! independent evaluator (the curve types row by row), finite differences,
//! bounds, collapsed-edge normals, the generic Newton intersector, bad input.
//! (That evaluation does not allocate is checked in `tests/alloc.rs`, on
//! surfaces from the same generator, `revolve_testkit::random_tensors`.)

use revolve_testkit as common;

use common::tensor_shapes::sphere_octant;

use common::random_tensors::{Xorshift64Star as Rng, clamped_knots};
use revolve::nalgebra::{Point2, Point3, Point4, Vector3};
use revolve::{
    BSpline, BSplineSurface, BezierPatch, BezierSurface, Curve, Error, Intersect,
    NewtonIntersector, Nurbs, NurbsSurface, ParameterDirection, PatchBounds, RationalBezierPatch,
    Ray, Revolution, Surface,
};

fn close(a: Point3<f64>, b: Point3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

/// The reference value of a (rational) tensor spline from the curve types:
/// each row as a `BSpline<4>` in homogeneous coordinates `(wP, w)` along `v`,
/// the column of results as another along `u`, then the division.
fn reference(
    degrees: (usize, usize),
    knots: &(Vec<f64>, Vec<f64>),
    points: &[Vec<Point3<f64>>],
    weights: &[Vec<f64>],
    u: f64,
    v: f64,
) -> Point3<f64> {
    let column: Vec<Point4<f64>> = points
        .iter()
        .zip(weights)
        .map(|(row, w)| {
            let h: Vec<Point4<f64>> = row
                .iter()
                .zip(w)
                .map(|(p, &w)| Point4::new(w * p.x, w * p.y, w * p.z, w))
                .collect();
            BSpline::new(degrees.1, knots.1.clone(), h).unwrap().eval(v)
        })
        .collect();
    let h = BSpline::new(degrees.0, knots.0.clone(), column)
        .unwrap()
        .eval(u);
    Point3::new(h.x / h.w, h.y / h.w, h.z / h.w)
}

#[test]
fn planar_bicubic_bezier_is_the_affine_map() {
    // Control points at i/3, j/3 of an affine frame: linear precision gives
    // S(u, v) = O + u·A + v·B exactly (in exact arithmetic).
    let o = Point3::new(0.5, -1.0, 2.0);
    let a = Vector3::new(2.0, 0.5, -1.0);
    let b = Vector3::new(-0.5, 3.0, 0.25);
    let grid = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| o + a * (i as f64 / 3.0) + b * (j as f64 / 3.0))
                .collect()
        })
        .collect();
    let s = BezierSurface::new(grid).unwrap();
    assert_eq!(s.degrees(), (3, 3));
    let n = a.cross(&b).normalize();
    for k in 0..=10 {
        for l in 0..=10 {
            let (u, v) = (k as f64 / 10.0, l as f64 / 10.0);
            assert!(close(s.eval(u, v), o + a * u + b * v, 1e-14));
            let (su, sv) = s.partials(u, v);
            assert!((su - a).norm() < 1e-13 && (sv - b).norm() < 1e-13);
            assert!((s.normal(u, v).unwrap().into_inner() - n).norm() < 1e-14);
        }
    }
}

#[test]
fn planar_bspline_with_greville_points_is_the_affine_map() {
    // Points at the Greville abscissae reproduce the linear function.
    let mut rng = Rng(7);
    let (p, q) = (3, 2);
    let ku = clamped_knots(&mut rng, p, 7);
    let kv = clamped_knots(&mut rng, q, 5);
    let greville =
        |k: &[f64], d: usize, i: usize| (1..=d).map(|r| k[i + r]).sum::<f64>() / d as f64;
    let (a, b) = (Vector3::new(1.0, 2.0, 3.0), Vector3::new(-2.0, 0.5, 1.0));
    let grid = (0..7)
        .map(|i| {
            (0..5)
                .map(|j| Point3::origin() + a * greville(&ku, p, i) + b * greville(&kv, q, j))
                .collect()
        })
        .collect();
    let s = BSplineSurface::new((p, q), (ku, kv), grid).unwrap();
    for _ in 0..200 {
        let (u, v) = (rng.next(), rng.next());
        assert!(close(s.eval(u, v), Point3::origin() + a * u + b * v, 1e-13));
        let (su, sv) = s.partials(u, v);
        assert!((su - a).norm() < 1e-12 && (sv - b).norm() < 1e-12);
    }
}

#[test]
fn bilinear_patch_matches_closed_form() {
    let mut rng = Rng(11);
    for _ in 0..20 {
        let g = rng.grid(2, 2);
        let s = BezierSurface::new(g.clone()).unwrap();
        let (p00, p01, p10, p11) = (
            g[0][0].coords,
            g[0][1].coords,
            g[1][0].coords,
            g[1][1].coords,
        );
        for _ in 0..50 {
            let (u, v) = (rng.next(), rng.next());
            let x = p00 * ((1.0 - u) * (1.0 - v))
                + p01 * ((1.0 - u) * v)
                + p10 * (u * (1.0 - v))
                + p11 * (u * v);
            assert!(close(s.eval(u, v), Point3::from(x), 1e-15 * 8.0));
            let su = (p10 - p00) * (1.0 - v) + (p11 - p01) * v;
            let sv = (p01 - p00) * (1.0 - u) + (p11 - p10) * u;
            let (du, dv) = s.partials(u, v);
            assert!((du - su).norm() < 1e-14 && (dv - sv).norm() < 1e-14);
            let (suu, suv, svv) = s.second_partials(u, v);
            assert!(suu.norm() < 1e-14 && svv.norm() < 1e-14);
            assert!((suv - (p11 - p01 - p10 + p00)).norm() < 1e-14);
        }
    }
}

fn quarter_cylinder(r: f64, height: f64) -> NurbsSurface {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [(r, 0.0), (r, r), (0.0, r)];
    let points = arc
        .iter()
        .map(|&(x, y)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, height)])
        .collect();
    NurbsSurface::new(
        (2, 1),
        (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
        points,
        vec![vec![1.0, 1.0], vec![h, h], vec![1.0, 1.0]],
    )
    .unwrap()
}

#[test]
fn nurbs_quarter_cylinder_is_exact() {
    let r = 2.5;
    let s = quarter_cylinder(r, 3.0);
    let mut rng = Rng(3);
    for _ in 0..500 {
        let (u, v) = (rng.next(), rng.next());
        let p = s.eval(u, v);
        assert!((p.x.hypot(p.y) - r).abs() < 4e-15 * r);
        assert!((p.z - 3.0 * v).abs() < 1e-14);
        let n = s.normal(u, v).unwrap();
        let radial = Vector3::new(p.x, p.y, 0.0).normalize();
        assert!(
            (n.dot(&radial).abs() - 1.0).abs() < 1e-13,
            "{n:?} {radial:?}"
        );
    }
}

#[test]
fn nurbs_sphere_octant_is_exact_with_radial_normals() {
    let r = 1.5;
    let s = sphere_octant(r);
    let mut rng = Rng(5);
    for _ in 0..500 {
        let (u, v) = (rng.next(), rng.next());
        let p = s.eval(u, v);
        assert!((p.coords.norm() - r).abs() < 4e-15 * r);
        assert!(p.x >= 0.0 && p.y >= 0.0 && p.z >= 0.0);
        let n = s.normal(u, v).unwrap();
        // ∂S/∂u points toward the equator, ∂S/∂v around z: outward normal.
        assert!(
            (n.dot(&p.coords.normalize()) - 1.0).abs() < 1e-12,
            "{u} {v}"
        );
    }
}

#[test]
fn sphere_pole_normal_is_the_limit() {
    // The row u = 0 is the pole (∂S/∂v = 0 there); the normal is the limit.
    let s = sphere_octant(1.0);
    for k in 0..=8 {
        let v = k as f64 / 8.0;
        let (_, sv) = s.partials(0.0, v);
        assert!(sv.norm() < 1e-14);
        let n = s.normal(0.0, v).unwrap();
        assert!(
            (n.into_inner() - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-12,
            "{v}: {n:?}"
        );
        for h in [1e-3, 1e-5] {
            let near = s.normal(h, v).unwrap();
            assert!((near.into_inner() - n.into_inner()).norm() < 10.0 * h);
        }
    }
}

#[test]
fn collapsed_edge_normals_are_limits() {
    // A lid-like bicubic: the row u = 0 collapsed to the apex, the second
    // row level with it (as the teapot's lid), the others rings around the
    // z axis at random heights.
    let mut rng = Rng(17);
    for _ in 0..20 {
        let apex = Point3::new(0.0, 0.0, 1.0);
        let mut grid = vec![vec![apex; 4]];
        for i in 1..4 {
            let radius = i as f64 * 0.4;
            let z = if i == 1 {
                1.0
            } else {
                1.0 - 0.2 * i as f64 + rng.range(-0.05, 0.05)
            };
            grid.push(
                (0..4)
                    .map(|j| {
                        let angle = j as f64 * 0.5 + rng.range(-0.1, 0.1);
                        Point3::new(radius * angle.cos(), radius * angle.sin(), z)
                    })
                    .collect(),
            );
        }
        let s = BezierSurface::new(grid).unwrap();
        for k in 0..=6 {
            let v = k as f64 / 6.0;
            let n = s
                .normal(0.0, v)
                .expect("the lid has a tangent plane at its apex");
            assert!((n.norm() - 1.0).abs() < 1e-15);
            // The limit of normals inside.
            let mut previous = f64::INFINITY;
            for h in [1e-2, 1e-3, 1e-4, 1e-5] {
                let near = s.normal(h, v).unwrap();
                let gap = (near.into_inner() - n.into_inner()).norm();
                assert!(gap < 50.0 * h, "{v} {h} {gap}");
                assert!(gap <= previous + 1e-12);
                previous = gap;
            }
        }
        // And at the apex every v gives the same tangent plane, z = 1.
        let n0 = s.normal(0.0, 0.0).unwrap();
        let n1 = s.normal(0.0, 1.0).unwrap();
        assert!(
            (n0.into_inner() - n1.into_inner()).norm() < 1e-12,
            "{n0:?} {n1:?}"
        );
        assert!((n0.z.abs() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn cone_apex_has_no_normal() {
    // A right circular cone's apex as a collapsed edge: the directions
    // leaving it form a cone, not a plane, so there is no tangent plane.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let ring = [(1.0, 0.0, 1.0), (1.0, 1.0, h), (0.0, 1.0, 1.0)];
    let apex = Point3::new(0.0, 0.0, 1.0);
    let s = NurbsSurface::new(
        (1, 2),
        (vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
        vec![
            vec![apex; 3],
            ring.iter()
                .map(|&(x, y, _)| Point3::new(x, y, 0.0))
                .collect(),
        ],
        vec![ring.iter().map(|r| r.2).collect(); 2],
    )
    .unwrap();
    assert!(s.normal(0.0, 0.5).is_none());
    // Off the apex the normal exists and makes 45° with the axis.
    let n = s.normal(1e-3, 0.5).unwrap();
    assert!((n.z.abs() - h).abs() < 1e-12, "{n:?}");
}

/// A surface of revolution about `z` (exact NURBS, four quarter arcs) of a
/// cubic profile `(r, z)` whose first three control points are the pole
/// `(0, 0)`: both derivatives across the pole vanish there.
fn tripled_pole(next: (f64, f64)) -> NurbsSurface {
    let profile = Nurbs::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(0.0, 0.0),
            Point2::new(0.0, 0.0),
            Point2::new(next.0, next.1),
        ],
        vec![1.0; 4],
    )
    .unwrap();
    let turned = Revolution::new(profile).with_axis(Point3::origin(), Vector3::z_axis());
    NurbsSurface::from_revolution(&turned).unwrap()
}

#[test]
fn a_pole_on_a_tripled_control_point_has_the_exact_normal() {
    // Profile (t³, 0): a flat disk, whose normal is ±z everywhere,
    // the pole included (there S_u = S_uu = 0 and only the third
    // derivative leaves the pole).
    let disk = tripled_pole((1.0, 0.0));
    let off = disk.normal(0.5, 0.3).unwrap();
    assert!((off.z.abs() - 1.0).abs() < 1e-15, "{off:?}");
    for k in 0..=16 {
        let v = disk.domain()[1].0 + (disk.domain()[1].1 - disk.domain()[1].0) * k as f64 / 16.0;
        let n = disk
            .normal(0.0, v)
            .unwrap_or_else(|| panic!("no normal at v {v}"));
        assert!(
            (n.into_inner() - off.into_inner()).norm() < 1e-15,
            "v {v}: {n:?} vs {off:?}"
        );
    }
}

#[test]
fn a_cone_apex_on_a_tripled_control_point_has_no_normal() {
    // Profile (t³, t³): a 45° cone with its apex on the tripled point. The
    // directions leaving the apex form a cone: no tangent plane there.
    let cone = tripled_pole((1.0, 1.0));
    let v = 0.5 * (cone.domain()[1].0 + cone.domain()[1].1);
    assert!(cone.normal(0.0, v).is_none());
    let n = cone.normal(0.5, v).unwrap();
    assert!(
        (n.z.abs() - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-14,
        "{n:?}"
    );
}

#[test]
fn bspline_surface_matches_curve_de_boor_and_its_patches() {
    let mut rng = Rng(23);
    for (p, q, rows, cols) in [(3, 3, 6, 5), (2, 3, 5, 7), (1, 2, 3, 4), (3, 1, 4, 2)] {
        let ku = clamped_knots(&mut rng, p, rows);
        let kv = clamped_knots(&mut rng, q, cols);
        let grid = rng.grid(rows, cols);
        let s = BSplineSurface::new((p, q), (ku.clone(), kv.clone()), grid.clone()).unwrap();
        let ones = vec![vec![1.0; cols]; rows];
        let knots = (ku, kv);
        for _ in 0..100 {
            let (u, v) = (rng.next(), rng.next());
            let r = reference((p, q), &knots, &grid, &ones, u, v);
            assert!(close(s.eval(u, v), r, 1e-13));
        }
        let patches: Vec<BezierPatch> = s.to_bezier_patches();
        let distinct = |k: &[f64]| {
            let mut d = k.to_vec();
            d.dedup();
            d.len() - 1
        };
        assert_eq!(patches.len(), distinct(&knots.0) * distinct(&knots.1));
        for patch in &patches {
            assert_eq!(patch.surface.degrees(), (p, q));
            for _ in 0..20 {
                let (a, b) = (rng.next(), rng.next());
                let u = patch.u.0 + a * (patch.u.1 - patch.u.0);
                let v = patch.v.0 + b * (patch.v.1 - patch.v.0);
                assert!(close(patch.surface.eval(a, b), s.eval(u, v), 1e-13));
            }
        }
    }
}

#[test]
fn nurbs_surface_matches_homogeneous_reference_and_patches() {
    let mut rng = Rng(29);
    for (p, q, rows, cols) in [(3, 3, 6, 5), (2, 2, 4, 4), (1, 3, 3, 5)] {
        let knots = (
            clamped_knots(&mut rng, p, rows),
            clamped_knots(&mut rng, q, cols),
        );
        let grid = rng.grid(rows, cols);
        let weights = rng.weights(rows, cols);
        let s = NurbsSurface::new((p, q), knots.clone(), grid.clone(), weights.clone()).unwrap();
        for _ in 0..100 {
            let (u, v) = (rng.next(), rng.next());
            let r = reference((p, q), &knots, &grid, &weights, u, v);
            assert!(close(s.eval(u, v), r, 1e-13));
        }
        let patches: Vec<RationalBezierPatch> = s.to_bezier_patches();
        for patch in &patches {
            // Each patch as a NURBS surface with Bézier knots.
            let bez = |d: usize| {
                let mut k = vec![0.0; d + 1];
                k.extend(vec![1.0; d + 1]);
                k
            };
            let piece = NurbsSurface::new(
                (p, q),
                (bez(p), bez(q)),
                patch.points.clone(),
                patch.weights.clone(),
            )
            .unwrap();
            for _ in 0..10 {
                let (a, b) = (rng.next(), rng.next());
                let u = patch.u.0 + a * (patch.u.1 - patch.u.0);
                let v = patch.v.0 + b * (patch.v.1 - patch.v.0);
                assert!(close(piece.eval(a, b), s.eval(u, v), 1e-13));
            }
        }
    }
}

#[test]
fn equal_weights_give_the_bspline_surface() {
    let mut rng = Rng(31);
    let knots = (clamped_knots(&mut rng, 3, 6), clamped_knots(&mut rng, 2, 5));
    let grid = rng.grid(6, 5);
    let b = BSplineSurface::new((3, 2), knots.clone(), grid.clone()).unwrap();
    let n = NurbsSurface::new((3, 2), knots, grid, vec![vec![2.5; 5]; 6]).unwrap();
    let converted = NurbsSurface::from(b.clone());
    assert!(converted.weights().iter().flatten().all(|&w| w == 1.0));
    for _ in 0..200 {
        let (u, v) = (rng.next(), rng.next());
        assert!(close(n.eval(u, v), b.eval(u, v), 1e-14));
        assert!(close(converted.eval(u, v), b.eval(u, v), 0.0));
        let (nu, nv) = n.partials(u, v);
        let (bu, bv) = b.partials(u, v);
        assert!((nu - bu).norm() < 1e-12 * (1.0 + bu.norm()));
        assert!((nv - bv).norm() < 1e-12 * (1.0 + bv.norm()));
    }
}

#[test]
fn knot_insertion_keeps_the_surface() {
    let mut rng = Rng(37);
    let knots = (clamped_knots(&mut rng, 3, 6), clamped_knots(&mut rng, 2, 5));
    let grid = rng.grid(6, 5);
    let weights = rng.weights(6, 5);
    let n = NurbsSurface::new((3, 2), knots.clone(), grid.clone(), weights).unwrap();
    let b = BSplineSurface::new((3, 2), knots, grid).unwrap();
    let n2 = n
        .insert_knot_u(0.37, 2)
        .unwrap()
        .insert_knot_v(0.61, 1)
        .unwrap();
    let b2 = b.insert_knot_u(0.42, 3).unwrap().insert_knot_v(0.0, 1);
    // v = 0 is a clamped end: already of multiplicity q + 1.
    assert!(
        matches!(
            &b2,
            Err(Error::SurfaceKnots { direction: ParameterDirection::V, error })
                if matches!(**error, Error::KnotMultiplicity { .. })
        ),
        "{b2:?}"
    );
    let b2 = b
        .insert_knot_u(0.42, 3)
        .unwrap()
        .insert_knot_v(0.5, 2)
        .unwrap();
    assert_eq!(n2.points().len(), 8);
    assert_eq!(n2.points()[0].len(), 6);
    assert_eq!(n2.knots().0.len(), 8 + 4);
    assert_eq!(b2.points().len(), 9);
    for _ in 0..300 {
        let (u, v) = (rng.next(), rng.next());
        assert!(close(n2.eval(u, v), n.eval(u, v), 1e-13));
        assert!(close(b2.eval(u, v), b.eval(u, v), 1e-13));
    }
    let outside = |r: Result<_, Error>, d: ParameterDirection| {
        matches!(r, Err(Error::SurfaceKnots { direction, error })
            if direction == d && matches!(*error, Error::ParameterOutOfDomain { .. }))
    };
    assert!(outside(
        b.insert_knot_u(f64::NAN, 1).map(|_| ()),
        ParameterDirection::U
    ));
    assert!(outside(
        n.insert_knot_v(1.5, 1).map(|_| ()),
        ParameterDirection::V
    ));
}

fn assert_partials_match_differences<S: Surface>(s: &S, rng: &mut Rng) {
    let h = 1e-6;
    for _ in 0..100 {
        let (u, v) = (rng.range(0.01, 0.99), rng.range(0.01, 0.99));
        let (su, sv) = s.partials(u, v);
        let fu = (s.eval(u + h, v) - s.eval(u - h, v)) / (2.0 * h);
        let fv = (s.eval(u, v + h) - s.eval(u, v - h)) / (2.0 * h);
        assert!((su - fu).norm() < 1e-6 * (1.0 + su.norm()), "{su:?} {fu:?}");
        assert!((sv - fv).norm() < 1e-6 * (1.0 + sv.norm()), "{sv:?} {fv:?}");
    }
}

#[test]
fn partials_match_central_differences() {
    let mut rng = Rng(41);
    for _ in 0..10 {
        let s = BezierSurface::new(rng.grid(4, 3)).unwrap();
        assert_partials_match_differences(&s, &mut rng);
        // Second partials against differences of the first.
        let h = 1e-6;
        let (u, v) = (rng.range(0.01, 0.99), rng.range(0.01, 0.99));
        let (suu, suv, svv) = s.second_partials(u, v);
        let fuu = (s.partials(u + h, v).0 - s.partials(u - h, v).0) / (2.0 * h);
        let fuv = (s.partials(u, v + h).0 - s.partials(u, v - h).0) / (2.0 * h);
        let fvv = (s.partials(u, v + h).1 - s.partials(u, v - h).1) / (2.0 * h);
        assert!((suu - fuu).norm() < 1e-5 * (1.0 + suu.norm()));
        assert!((suv - fuv).norm() < 1e-5 * (1.0 + suv.norm()));
        assert!((svv - fvv).norm() < 1e-5 * (1.0 + svv.norm()));
        let knots = (clamped_knots(&mut rng, 3, 5), clamped_knots(&mut rng, 2, 4));
        let n = NurbsSurface::new((3, 2), knots, rng.grid(5, 4), rng.weights(5, 4)).unwrap();
        assert_partials_match_differences(&n, &mut rng);
        let (nuu, nuv, nvv) = n.second_partials(u, v);
        let fuu = (n.partials(u + h, v).0 - n.partials(u - h, v).0) / (2.0 * h);
        let fuv = (n.partials(u, v + h).0 - n.partials(u, v - h).0) / (2.0 * h);
        let fvv = (n.partials(u, v + h).1 - n.partials(u, v - h).1) / (2.0 * h);
        // Knots may fall between u ± h: compare only away from them.
        let kn = n.knots();
        let near_knot = kn.0.iter().any(|&k| (k - u).abs() < 2.0 * h)
            || kn.1.iter().any(|&k| (k - v).abs() < 2.0 * h);
        if !near_knot {
            assert!(
                (nuu - fuu).norm() < 1e-4 * (1.0 + nuu.norm()),
                "{nuu:?} {fuu:?}"
            );
            assert!((nuv - fuv).norm() < 1e-4 * (1.0 + nuv.norm()));
            assert!((nvv - fvv).norm() < 1e-4 * (1.0 + nvv.norm()));
        }
    }
}

fn assert_bounds_contain_samples<S: PatchBounds>(s: &S, rng: &mut Rng) {
    let [du, dv] = s.domain();
    for _ in 0..20 {
        let mut u = (rng.range(du.0, du.1), rng.range(du.0, du.1));
        let mut v = (rng.range(dv.0, dv.1), rng.range(dv.0, dv.1));
        if u.0 > u.1 {
            u = (u.1, u.0);
        }
        if v.0 > v.1 {
            v = (v.1, v.0);
        }
        let b = s.bound_patch(u, v);
        for k in 0..=16 {
            for l in 0..=16 {
                let x = u.0 + (u.1 - u.0) * k as f64 / 16.0;
                let y = v.0 + (v.1 - v.0) * l as f64 / 16.0;
                let p = s.eval(x, y);
                assert!(b.contains(&p), "{u:?} {v:?} {p:?} {b:?}");
            }
        }
        // Tight enough to be useful: within the whole surface's box.
        let whole = s.bound_patch(du, dv);
        assert!(b.extent().norm() <= whole.extent().norm() * (1.0 + 1e-12));
    }
}

#[test]
fn bound_patch_contains_dense_samples() {
    let mut rng = Rng(43);
    for _ in 0..10 {
        let s = BezierSurface::new(rng.grid(4, 4)).unwrap();
        assert_bounds_contain_samples(&s, &mut rng);
        let knots = (clamped_knots(&mut rng, 3, 6), clamped_knots(&mut rng, 2, 5));
        let b = BSplineSurface::new((3, 2), knots.clone(), rng.grid(6, 5)).unwrap();
        assert_bounds_contain_samples(&b, &mut rng);
        let n = NurbsSurface::new((3, 2), knots, rng.grid(6, 5), rng.weights(6, 5)).unwrap();
        assert_bounds_contain_samples(&n, &mut rng);
    }
    assert_bounds_contain_samples(&sphere_octant(2.0), &mut rng);
}

#[test]
fn parameters_outside_the_domain_clamp() {
    let mut rng = Rng(47);
    let s = BezierSurface::new(rng.grid(3, 4)).unwrap();
    assert_eq!(s.eval(-1.0, 2.0), s.eval(0.0, 1.0));
    assert_eq!(s.eval(f64::NAN, f64::NAN), s.eval(0.0, 0.0));
    assert_eq!(s.partials(5.0, f64::NAN), s.partials(1.0, 0.0));
    let knots = (clamped_knots(&mut rng, 2, 4), clamped_knots(&mut rng, 2, 4));
    let n = NurbsSurface::new((2, 2), knots, rng.grid(4, 4), rng.weights(4, 4)).unwrap();
    assert_eq!(n.eval(f64::NEG_INFINITY, 3.0), n.eval(0.0, 1.0));
    assert_eq!(n.eval(f64::NAN, 0.5), n.eval(0.0, 0.5));
}

#[test]
fn newton_intersector_finds_bilinear_hits() {
    // S(u, v) = (u, v, u·v) on [0, 1]²: a ray o + t·d hits where
    // (oₓ + t dₓ)(o_y + t d_y) = o_z + t d_z, a quadratic in t.
    let s = BezierSurface::new(vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
        vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    ])
    .unwrap();
    let newton = NewtonIntersector::new(&s, 8);
    let mut rng = Rng(53);
    let mut hits = 0;
    for _ in 0..300 {
        let o = Point3::new(
            rng.range(-0.5, 1.5),
            rng.range(-0.5, 1.5),
            rng.range(1.5, 2.5),
        );
        let target = Point3::new(
            rng.range(-0.2, 1.2),
            rng.range(-0.2, 1.2),
            rng.range(-0.5, 0.8),
        );
        let d = target - o;
        let ray = Ray::new(o, d);
        let (a, b, c) = (d.x * d.y, o.x * d.y + o.y * d.x - d.z, o.x * o.y - o.z);
        let mut roots = Vec::new();
        if a.abs() < 1e-14 {
            roots.push(-c / b);
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                roots.extend([q / a, c / q]);
            }
        }
        let expected = roots
            .into_iter()
            .filter(|&t| {
                let p = ray.at(t);
                t > 1e-9 && (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)
            })
            .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))));
        // Skip rays that pass within rounding of the patch boundary.
        let near_edge = |t: f64| {
            let p = ray.at(t);
            [p.x, p.y]
                .iter()
                .any(|&x| x.abs() < 1e-6 || (x - 1.0).abs() < 1e-6)
        };
        if expected.is_some_and(near_edge) {
            continue;
        }
        let hit = newton.intersect(&ray, 1e-9, f64::INFINITY);
        match (expected, hit) {
            (None, None) => {}
            (Some(t), Some(h)) => {
                hits += 1;
                assert!((h.t - t).abs() < 1e-9 * (1.0 + t), "{t} {}", h.t);
                assert!(close(h.point, s.eval(h.uv.0, h.uv.1), 1e-9));
            }
            (e, h) => panic!("expected {e:?}, got {h:?}"),
        }
    }
    assert!(hits > 50, "{hits}");
}

#[test]
fn bad_input_gives_named_errors() {
    let p = Point3::new(0.0, 0.0, 0.0);
    assert!(matches!(BezierSurface::new(vec![]), Err(Error::EmptyGrid)));
    assert!(matches!(
        BezierSurface::new(vec![vec![]]),
        Err(Error::EmptyGrid)
    ));
    let e = BezierSurface::new(vec![]).unwrap_err().to_string();
    assert!(e.contains("surface") && !e.contains("curve"), "{e}");
    assert!(matches!(
        BezierSurface::new(vec![vec![p, p], vec![p]]),
        Err(Error::RaggedGrid {
            row: 1,
            expected: 2,
            found: 1
        })
    ));
    let nan = Point3::new(0.0, f64::NAN, 0.0);
    assert!(matches!(
        BezierSurface::new(vec![vec![p, p], vec![p, nan]]),
        Err(Error::NonFiniteGridPoint { row: 1, column: 1 })
    ));
    // The example: a NaN at row 1, column 2 of a 3×3 grid.
    let mut grid = vec![vec![p; 3]; 3];
    grid[1][2] = nan;
    let e = BezierSurface::new(grid).unwrap_err().to_string();
    assert!(e.contains("row 1, column 2"), "{e}");
    let inf = Point3::new(f64::INFINITY, 0.0, 0.0);
    assert!(matches!(
        BezierSurface::new(vec![vec![inf]]),
        Err(Error::NonFiniteGridPoint { row: 0, column: 0 })
    ));
    let big = Point3::new(1e101, 0.0, 0.0);
    assert!(matches!(
        BezierSurface::new(vec![vec![p, big]]),
        Err(Error::GridCoordinateTooLarge {
            row: 0,
            column: 1,
            ..
        })
    ));
    // Points near the limit whose hodographs overflow.
    let far = Point3::new(1e100, 0.0, 0.0);
    let grid: Vec<Vec<Point3<f64>>> = (0..121)
        .map(|i| {
            (0..2)
                .map(|_| {
                    if i % 2 == 0 {
                        far
                    } else {
                        Point3::from(-far.coords)
                    }
                })
                .collect()
        })
        .collect();
    assert!(matches!(
        BezierSurface::new(grid),
        Err(Error::DerivativeOverflow { .. })
    ));
    let grid = vec![vec![p; 3]; 3];
    let k3 = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    assert!(matches!(
        BSplineSurface::new((2, 2), (k3.clone(), vec![0.0, 1.0]), grid.clone()),
        Err(Error::SurfaceKnots { direction: ParameterDirection::V, error })
            if *error == Error::KnotCount { expected: 6, found: 2 }
    ));
    let e = BSplineSurface::new((2, 2), (k3.clone(), vec![0.0, 1.0]), grid.clone()).unwrap_err();
    assert!(e.to_string().contains("v knots"), "{e}");
    assert!(matches!(
        BSplineSurface::new((3, 2), (k3.clone(), k3.clone()), grid.clone()),
        Err(Error::SurfaceKnots { direction: ParameterDirection::U, error })
            if matches!(*error, Error::DegreeTooHigh { .. })
    ));
    assert!(matches!(
        BSplineSurface::new(
            (2, 2),
            (vec![0.0, 0.0, 0.0, 1.0, 0.5, 1.0], k3.clone()),
            grid.clone()
        ),
        Err(Error::SurfaceKnots { direction: ParameterDirection::U, error })
            if *error == Error::DecreasingKnots { index: 4 }
    ));
    assert!(matches!(
        BSplineSurface::new(
            (2, 2),
            (k3.clone(), vec![0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0]),
            grid.clone()
        ),
        Err(Error::SurfaceKnots { direction: ParameterDirection::V, error })
            if *error == Error::NonFiniteKnot { index: 3 }
    ));
    assert!(matches!(
        BSplineSurface::new((2, 2), (k3.clone(), k3.clone()), vec![]),
        Err(Error::EmptyGrid)
    ));
    let ones = vec![vec![1.0; 3]; 3];
    let knots = (k3.clone(), k3.clone());
    let mut w = ones.clone();
    w[1][2] = 0.0;
    assert!(matches!(
        NurbsSurface::new((2, 2), knots.clone(), grid.clone(), w),
        Err(Error::InvalidGridWeight {
            row: 1,
            column: 2,
            ..
        })
    ));
    let mut w = ones.clone();
    w[2][0] = -1.0;
    assert!(matches!(
        NurbsSurface::new((2, 2), knots.clone(), grid.clone(), w),
        Err(Error::InvalidGridWeight {
            row: 2,
            column: 0,
            ..
        })
    ));
    let mut w = ones.clone();
    w[0][0] = f64::NAN;
    assert!(matches!(
        NurbsSurface::new((2, 2), knots.clone(), grid.clone(), w),
        Err(Error::InvalidGridWeight {
            row: 0,
            column: 0,
            ..
        })
    ));
    let mut w = ones.clone();
    w[1].pop();
    assert!(matches!(
        NurbsSurface::new((2, 2), knots.clone(), grid.clone(), w),
        Err(Error::RaggedGrid {
            row: 1,
            expected: 3,
            found: 2
        })
    ));
    assert!(matches!(
        NurbsSurface::new((2, 2), knots.clone(), grid.clone(), vec![vec![1.0; 3]; 2]),
        Err(Error::WeightCount {
            expected: 9,
            found: 6
        })
    ));
    let mut w = ones;
    w[0][0] = 1e9;
    assert!(matches!(
        NurbsSurface::new((2, 2), knots, grid, w),
        Err(Error::WeightRatioTooLarge { .. })
    ));
    // The messages name the problem.
    let e = BezierSurface::new(vec![vec![p, p], vec![p]]).unwrap_err();
    assert!(e.to_string().contains("row 1"), "{e}");
}

#[test]
fn corner_where_two_edges_collapse_has_the_limit_normal() {
    // A planar biquadratic "triangle": the edges u = 0 and v = 0 both
    // collapse to the corner (0, 0, 0), so S_u = S_v = 0 there and the
    // first-order limit vanishes too; the plane's normal is still the limit.
    let o = Point3::origin();
    let grid = vec![
        vec![o, o, o],
        vec![o, Point3::new(1.0, 1.0, 0.0), Point3::new(0.5, 2.0, 0.0)],
        vec![o, Point3::new(2.0, 0.5, 0.0), Point3::new(2.0, 2.0, 0.0)],
    ];
    let s = BezierSurface::new(grid).unwrap();
    let (su, sv) = s.partials(0.0, 0.0);
    assert!(su.norm() == 0.0 && sv.norm() == 0.0);
    let n = s.normal(0.0, 0.0).unwrap();
    let inside = s.normal(0.3, 0.4).unwrap();
    assert!(
        (n.into_inner() - inside.into_inner()).norm() < 1e-12,
        "{n:?} {inside:?}"
    );
    assert!((n.z.abs() - 1.0).abs() < 1e-12);
}

/// Patches 21 (the lid's knob, row 0 at the apex) and 29 (the bottom; one-based) of
/// Newell's teapot, as in the classic data (z up).
fn teapot_collapsed_patches() -> [BezierSurface; 2] {
    let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
    let apex = p(0.0, 0.0, 3.15);
    let knob = BezierSurface::new(vec![
        vec![apex; 4],
        vec![
            p(0.8, 0.0, 3.15),
            p(0.8, -0.45, 3.15),
            p(0.45, -0.8, 3.15),
            p(0.0, -0.8, 3.15),
        ],
        vec![p(0.0, 0.0, 2.85); 4],
        vec![
            p(0.2, 0.0, 2.7),
            p(0.2, -0.112, 2.7),
            p(0.112, -0.2, 2.7),
            p(0.0, -0.2, 2.7),
        ],
    ])
    .unwrap();
    let bottom = BezierSurface::new(vec![
        vec![p(0.0, 0.0, 0.0); 4],
        vec![
            p(1.425, 0.0, 0.0),
            p(1.425, 0.798, 0.0),
            p(0.798, 1.425, 0.0),
            p(0.0, 1.425, 0.0),
        ],
        vec![
            p(1.5, 0.0, 0.075),
            p(1.5, 0.84, 0.075),
            p(0.84, 1.5, 0.075),
            p(0.0, 1.5, 0.075),
        ],
        vec![
            p(1.5, 0.0, 0.15),
            p(1.5, 0.84, 0.15),
            p(0.84, 1.5, 0.15),
            p(0.0, 1.5, 0.15),
        ],
    ])
    .unwrap();
    [knob, bottom]
}

#[test]
fn teapot_lid_and_bottom_have_normals_at_their_collapsed_edges() {
    let scaled = |s: &BezierSurface, k: f64| {
        let points = s
            .points()
            .iter()
            .map(|r| r.iter().map(|p| Point3::from(p.coords * k)).collect())
            .collect();
        BezierSurface::new(points).unwrap()
    };
    let patches = teapot_collapsed_patches();
    let all = patches
        .iter()
        .flat_map(|s| [s.clone(), scaled(s, 1e-6), scaled(s, 1e6)]);
    for s in all {
        let inside = s.normal(1e-3, 0.5).unwrap();
        for k in 0..=8 {
            let v = k as f64 / 8.0;
            assert!(s.partials(0.0, v).1.norm() == 0.0);
            let n = s.normal(0.0, v).expect("a tangent plane at the apex");
            // The apex's tangent plane is horizontal, on the side of the
            // normals nearby.
            assert!((n.z.abs() - 1.0).abs() < 1e-12, "{n:?}");
            assert!(n.z * inside.z > 0.0);
            let near = s.normal(1e-6, v).unwrap();
            assert!((near.into_inner() - n.into_inner()).norm() < 1e-5);
        }
    }
}

#[test]
fn knot_rectangles_are_half_open_and_the_end_belongs_to_the_last() {
    // Degree 1 in u with a knot of full multiplicity at 0.5: the surface
    // jumps there; the value at 0.5 is the limit from above (rows 2, 3).
    let row = |x: f64, z: f64| vec![Point3::new(x, 0.0, z), Point3::new(x, 1.0, z)];
    let s = BSplineSurface::new(
        (1, 1),
        (vec![0.0, 0.0, 0.5, 0.5, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
        vec![row(0.0, 0.0), row(1.0, 0.0), row(1.0, 5.0), row(2.0, 5.0)],
    )
    .unwrap();
    for v in [0.0, 0.3, 1.0] {
        assert!(close(s.eval(0.5, v), Point3::new(1.0, v, 5.0), 1e-15));
        assert!(close(
            s.eval(0.5 - 1e-12, v),
            Point3::new(1.0, v, 0.0),
            1e-11
        ));
        assert!(close(s.eval(1.0, v), Point3::new(2.0, v, 5.0), 1e-15));
        assert!(close(s.eval(0.0, v), Point3::new(0.0, v, 0.0), 1e-15));
    }
    assert_eq!(s.to_bezier_patches().len(), 2);
}

#[test]
fn random_input_never_panics_and_valid_surfaces_evaluate_finitely() {
    let mut rng = Rng(61);
    let specials = [f64::NAN, f64::INFINITY, -1.0, 0.0, 1e-300, 1e300, 0.5];
    let mut built = 0;
    for _ in 0..3000 {
        let (p, q) = ((rng.next() * 4.0) as usize, (rng.next() * 4.0) as usize);
        let (rows, cols) = (
            1 + (rng.next() * 6.0) as usize,
            1 + (rng.next() * 6.0) as usize,
        );
        let mut grid = rng.grid(rows, cols);
        let mut weights = rng.weights(rows, cols);
        let mut knots = (
            (0..rows + p + 1).map(|_| rng.next()).collect::<Vec<f64>>(),
            (0..cols + q + 1).map(|_| rng.next()).collect::<Vec<f64>>(),
        );
        if rng.next() < 0.8 {
            knots.0.sort_by(f64::total_cmp);
            knots.1.sort_by(f64::total_cmp);
        }
        if rng.next() < 0.2 {
            let s = specials[(rng.next() * 7.0) as usize];
            match (rng.next() * 4.0) as usize {
                0 => grid[0][0].x = s,
                1 => weights[rows - 1][cols - 1] = s,
                2 => knots.0[0] = s,
                _ => {
                    grid.push(vec![Point3::origin()]);
                }
            }
        }
        let n = NurbsSurface::new((p, q), knots.clone(), grid.clone(), weights);
        let b = BSplineSurface::new((p, q), knots, grid.clone());
        let z = BezierSurface::new(grid);
        let mut check = |s: &dyn PatchBounds| {
            built += 1;
            let params = [
                rng.next(),
                rng.next(),
                f64::NAN,
                -1e300,
                1e300,
                f64::INFINITY,
            ];
            for &u in &params {
                for &v in &params[..3] {
                    let x = s.eval(u, v);
                    assert!(x.coords.iter().all(|c| c.is_finite()), "{x:?}");
                    let (su, sv) = s.partials(u, v);
                    assert!(su.iter().chain(sv.iter()).all(|c| c.is_finite()));
                    if let Some(nrm) = s.normal(u, v) {
                        assert!((nrm.norm() - 1.0).abs() < 1e-12);
                    }
                    let [du, dv] = s.domain();
                    assert!(s.bound_patch(du, dv).contains(&x));
                }
            }
        };
        if let Ok(s) = n {
            check(&s);
        }
        if let Ok(s) = b {
            check(&s);
        }
        if let Ok(s) = z {
            check(&s);
        }
    }
    assert!(built > 1000, "{built}");
}

#[test]
fn newton_intersector_finds_sphere_octant_hits() {
    // Rays from outside toward the octant: the nearest hit is the sphere's
    // (closed form) when that point lies in the octant.
    let r = 2.0;
    let s = sphere_octant(r);
    let newton = NewtonIntersector::new(&s, 8);
    let mut rng = Rng(67);
    let mut hits = 0;
    for _ in 0..200 {
        let o = Point3::new(
            rng.range(-1.0, 5.0),
            rng.range(-1.0, 5.0),
            rng.range(-1.0, 5.0),
        );
        if o.coords.norm() <= r * 1.01 {
            continue;
        }
        let target = Point3::new(rng.range(0.0, r), rng.range(0.0, r), rng.range(0.0, r));
        let d = target - o;
        let ray = Ray::new(o, d);
        // |o + t d|² = r²: the entry root.
        let (a, b, c) = (
            d.dot(&d),
            2.0 * o.coords.dot(&d),
            o.coords.dot(&o.coords) - r * r,
        );
        let disc = b * b - 4.0 * a * c;
        let entry = (disc >= 0.0).then(|| (-b - disc.sqrt()) / (2.0 * a));
        let in_octant = |t: f64| {
            let p = ray.at(t);
            p.x > 1e-6 && p.y > 1e-6 && p.z > 1e-6
        };
        let exit = (disc >= 0.0).then(|| (-b + disc.sqrt()) / (2.0 * a));
        let expected = [entry, exit]
            .into_iter()
            .flatten()
            .find(|&t| t > 0.0 && in_octant(t));
        let grazing = [entry, exit].into_iter().flatten().any(|t| {
            let p = ray.at(t);
            p.x.abs().min(p.y.abs()).min(p.z.abs()) < 1e-6
        });
        if grazing || disc.abs() < 1e-9 {
            continue;
        }
        match (expected, newton.intersect(&ray, 0.0, f64::INFINITY)) {
            (None, None) => {}
            (Some(t), Some(h)) => {
                hits += 1;
                assert!((h.t - t).abs() < 1e-9 * (1.0 + t), "{t} {}", h.t);
                assert!((h.point.coords.norm() - r).abs() < 1e-9);
            }
            (e, h) => panic!("expected {e:?}, got {h:?}"),
        }
    }
    assert!(hits > 40, "{hits}");
}

#[test]
fn rational_partials_beyond_the_limit_are_refused() {
    // A knot span of 1e-195 and coordinates ±1e100: the homogeneous
    // derivatives (~1e295) are in range, the polynomial surface is fine, but
    // a weight of 2e-8 divides them beyond MAX_DERIVATIVE.
    let points = vec![
        vec![Point3::new(-1e100, 0.0, 0.0), Point3::new(-1e100, 1.0, 0.0)],
        vec![Point3::new(1e100, 0.0, 0.0), Point3::new(1e100, 1.0, 0.0)],
    ];
    let knots = (vec![0.0, 0.0, 1e-195, 1e-195], vec![0.0, 0.0, 1.0, 1.0]);
    let b = BSplineSurface::new((1, 1), knots.clone(), points.clone()).unwrap();
    let (su, _) = b.partials(5e-196, 0.5);
    assert!(su.x.is_finite() && su.x <= revolve::MAX_DERIVATIVE);
    let n = NurbsSurface::new((1, 1), knots, points, vec![vec![2e-8; 2], vec![1.0; 2]]);
    assert!(
        matches!(n, Err(Error::DerivativeOverflow { order: 1 })),
        "{n:?}"
    );
}

/// `BoundedSurface`, the former name of `PatchBounds`, still names the same
/// trait: a bound written with it takes every tensor surface, and gives the
/// same boxes.
#[test]
fn former_name_bounded_surface_is_patch_bounds() {
    fn boxes<S: revolve::BoundedSurface>(s: &S) -> revolve::Aabb {
        s.bound_patch((0.25, 0.5), (0.0, 1.0))
    }
    let s = sphere_octant(2.0);
    assert_eq!(
        boxes(&s),
        revolve::PatchBounds::bound_patch(&s, (0.25, 0.5), (0.0, 1.0))
    );
}

//! Orientation: `reversed()` on every curve (the same points traced
//! backward, the domain kept) and on every surface kind (the normals
//! negated, everything else bit for bit the same).
//!
//! Curves: random ones of each type, compared at random parameters with
//! the original at the mirrored parameter `a + b − t` (values, and first
//! and second derivatives with the signs `(−1)ᵏ`), the domain, and the
//! double reversal; knot vectors where mirroring rounds two knots together.
//! Surfaces: the sphere, torus, goblet and a sampled-profile revolution, a
//! bicubic, B-spline and NURBS surfaces and the teapot, compared at random
//! parameters and on thousands of random rays (single and batched), their
//! meshes, and (feature `serde`) their JSON round trips.

use revolve_testkit as common;

use common::random_tensors::{Xorshift64Star, clamped_knots};
use common::{Rng, points};
use revolve::nalgebra::{Point2, Point3, SVector, Unit, Vector2, Vector3};
use revolve::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierPatches, BezierSurface, Curve, Hit, Intersect,
    Mesh, Nurbs, NurbsSurface, RationalBezier, Ray, Revolution, Surface,
};

// ---------------------------------------------------------------------------
// Curves
// ---------------------------------------------------------------------------

/// The largest absolute coordinate of `points`.
fn size<const D: usize>(points: &[revolve::nalgebra::Point<f64, D>]) -> f64 {
    points.iter().fold(0.0_f64, |m, p| m.max(p.coords.amax()))
}

/// Checks `back` against `curve` traced backward at `count` random
/// parameters: `back(t) = curve(a + b − t)` within `32ε` of the size (plus
/// the speed times the rounding of the mirrored parameter), the first
/// derivative negated and the second kept (relative to the largest of
/// them on the curve), the same domain and the same end points.
fn check_reversed_curve<C: Curve<D>, const D: usize>(
    what: &str,
    curve: &C,
    back: &C,
    second: impl Fn(&C, f64) -> SVector<f64, D>,
    size: f64,
    rng: &mut Rng,
    count: usize,
) {
    let (a, b) = curve.domain();
    assert_eq!(back.domain(), (a, b), "{what}: domain");
    let scale = a.abs().max(b.abs());
    let speed = |t: f64| curve.derivative(t).norm();
    let ends = [(a, b), (b, a)];
    for (t, s) in ends {
        let tol = 32.0 * f64::EPSILON * size;
        let err = (back.eval(t) - curve.eval(s)).norm();
        assert!(err <= tol, "{what}: end {t}: {err:e} > {tol:e}");
    }
    for _ in 0..count {
        let t = rng.range(a, b);
        let s = a + b - t;
        let rounding = 4.0 * f64::EPSILON * (scale + t.abs()) * speed(s);
        let tol = 32.0 * f64::EPSILON * size + rounding;
        let err = (back.eval(t) - curve.eval(s)).norm();
        assert!(err <= tol, "{what}: at {t}: {err:e} > {tol:e}");
        let (d, d_back) = (curve.derivative(s), back.derivative(t));
        let (dd, dd_back) = (second(curve, s), second(back, t));
        let tol = 1e-12 * (d.norm() + dd.norm() * (b - a) + size / (b - a));
        let err = (d_back + d).norm();
        assert!(err <= tol, "{what}: derivative at {t}: {err:e} > {tol:e}");
        let tol = 1e-11 * (dd.norm() + size / ((b - a) * (b - a)));
        let err = (dd_back - dd).norm();
        assert!(
            err <= tol,
            "{what}: second derivative at {t}: {err:e} > {tol:e}"
        );
    }
}

/// Random control points in `[−10, 10]ᴰ`.
fn random_points<const D: usize>(
    rng: &mut Rng,
    count: usize,
) -> Vec<revolve::nalgebra::Point<f64, D>> {
    (0..count)
        .map(|_| SVector::<f64, D>::from_fn(|_, _| rng.range(-10.0, 10.0)).into())
        .collect()
}

#[test]
fn reversed_bezier_curves_trace_the_same_points_backward() {
    let mut rng = Rng(0xB1);
    for case in 0..200 {
        let degree = rng.below(9);
        let curve = Bezier::<3>::new(random_points(&mut rng, degree + 1)).unwrap();
        let back = curve.reversed();
        let size = size(curve.points());
        let second = |c: &Bezier<3>, t| c.nth_derivative(t, 2).unwrap();
        check_reversed_curve(
            &format!("Bézier {case}"),
            &curve,
            &back,
            second,
            size,
            &mut rng,
            20,
        );
        let mirrored: Vec<_> = curve.points().iter().rev().copied().collect();
        assert_eq!(back.points(), &mirrored[..]);
        assert_eq!(back.reversed(), curve);
    }
}

#[test]
fn reversed_rational_bezier_curves_trace_the_same_points_backward() {
    let mut rng = Rng(0xB2);
    for case in 0..200 {
        let n = 1 + rng.below(8);
        let weights: Vec<f64> = (0..n).map(|_| 0.2 * 25f64.powf(rng.unit())).collect();
        let curve = RationalBezier::<2>::new(random_points(&mut rng, n), weights).unwrap();
        let back = curve.reversed();
        let size = size(curve.points());
        let second = |c: &RationalBezier<2>, t| c.nth_derivative(t, 2).unwrap();
        check_reversed_curve(
            &format!("rational Bézier {case}"),
            &curve,
            &back,
            second,
            size,
            &mut rng,
            20,
        );
        let mirrored: Vec<f64> = curve.weights().iter().rev().copied().collect();
        assert_eq!(back.weights(), &mirrored[..]);
        assert_eq!(back.reversed(), curve);
    }
}

#[test]
fn reversed_bsplines_and_nurbs_trace_the_same_points_backward() {
    let mut rng = Rng(0xB3);
    for case in 0..300 {
        let degree = rng.below(6);
        let parts = common::random_nurbs::random_parts(&mut rng, degree, 0.2, 5.0);
        let spline = BSpline::new(degree, parts.knots.clone(), parts.points.clone()).unwrap();
        let nurbs = parts.nurbs();
        let size = size(&parts.points);

        let back = spline.reversed();
        let second = |c: &BSpline<2>, t| c.nth_derivative(t, 2).unwrap();
        let what = format!("B-spline {case}");
        check_reversed_curve(&what, &spline, &back, second, size, &mut rng, 20);
        check_mirrored_knots(&what, spline.knots(), back.knots(), degree);
        // Valid by the constructor's own rules.
        let rebuilt = BSpline::new(degree, back.knots().to_vec(), back.points().to_vec());
        assert!(rebuilt.is_ok(), "{what}: {rebuilt:?}");
        let twice = back.reversed();
        assert_eq!(twice.points(), spline.points(), "{what}");
        assert_eq!(twice.domain(), spline.domain(), "{what}");
        check_close_knots(&what, twice.knots(), spline.knots());

        let back = nurbs.reversed();
        let second = |c: &Nurbs<2>, t| c.nth_derivative(t, 2).unwrap();
        let what = format!("NURBS {case}");
        check_reversed_curve(&what, &nurbs, &back, second, size, &mut rng, 20);
        check_mirrored_knots(&what, nurbs.knots(), back.knots(), degree);
        let mirrored: Vec<f64> = nurbs.weights().iter().rev().copied().collect();
        assert_eq!(back.weights(), &mirrored[..], "{what}");
        let twice = back.reversed();
        assert_eq!(twice.points(), nurbs.points(), "{what}");
        assert_eq!(twice.weights(), nurbs.weights(), "{what}");
        check_close_knots(&what, twice.knots(), nurbs.knots());
    }
}

/// `back` is `knots` mirrored about the domain's centre (to rounding) in
/// reverse order, with the same multiplicities, the domain ends exact.
fn check_mirrored_knots(what: &str, knots: &[f64], back: &[f64], degree: usize) {
    let n = knots.len() - degree - 1;
    let (a, b) = (knots[degree], knots[n]);
    assert_eq!((back[degree], back[n]), (a, b), "{what}: domain ends");
    let scale = knots.iter().fold(0.0_f64, |m, k| m.max(k.abs()));
    for (i, &k) in back.iter().enumerate() {
        let want = a + b - knots[knots.len() - 1 - i];
        assert!(
            (k - want).abs() <= 8.0 * f64::EPSILON * scale,
            "{what}: knot {i}: {k} vs {want}"
        );
    }
    let runs = |k: &[f64]| {
        k.chunk_by(|x, y| x == y)
            .map(<[f64]>::len)
            .collect::<Vec<_>>()
    };
    let mut forward = runs(knots);
    forward.reverse();
    assert_eq!(runs(back), forward, "{what}: multiplicities");
}

/// Knot vectors equal to a few ulps of their size.
fn check_close_knots(what: &str, got: &[f64], want: &[f64]) {
    let scale = want.iter().fold(0.0_f64, |m, k| m.max(k.abs()));
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= 8.0 * f64::EPSILON * scale,
            "{what}: {got:?} vs {want:?}"
        );
    }
}

/// The next float above `x > 0`.
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}

#[test]
fn mirrored_knots_that_rounding_merges_are_kept_apart() {
    // 127.5 and the float after it: mirrored about 128 (256 − k) both round
    // to 128.5, the coarser binade, which would make a triple knot of
    // degree 1 (invalid) out of a double and a single one.
    let (k1, k2) = (127.5, up(127.5));
    assert_eq!(256.0 - k1, 256.0 - k2, "the case must merge when rounded");
    let knots = vec![127.0, 127.0, k1, k1, k2, 129.0, 129.0];
    let pts = points(&[(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 1.0), (4.0, 0.0)]);
    let spline = BSpline::new(1, knots.clone(), pts.clone()).unwrap();
    let back = spline.reversed();
    let rebuilt = BSpline::new(1, back.knots().to_vec(), back.points().to_vec());
    assert!(rebuilt.is_ok(), "{:?}: {rebuilt:?}", back.knots());
    check_mirrored_knots("merging", &knots, back.knots(), 1);
    // The mirrored runs met at 128.5: the later one moved up by the least
    // the gap rule allows (a few ulps), the multiplicities kept.
    let k = back.knots();
    assert_eq!(k[2], 128.5);
    assert!(
        k[3] == k[4] && k[3] > 128.5 && k[3] < 128.5 + 1e-12,
        "{k:?}"
    );
    let mut rng = Rng(0xB4);
    let second = |c: &BSpline<2>, t| c.nth_derivative(t, 2).unwrap();
    check_reversed_curve("merging", &spline, &back, second, 4.0, &mut rng, 200);

    // The same for a NURBS, and for degree 2, where the merge would leave a
    // valid but wrong (less smooth) triple knot.
    let weights = vec![1.0, 2.0, 0.5, 1.5, 1.0];
    let nurbs = Nurbs::new(1, knots, pts.clone(), weights).unwrap();
    let back = nurbs.reversed();
    let rebuilt = Nurbs::new(
        1,
        back.knots().to_vec(),
        back.points().to_vec(),
        back.weights().to_vec(),
    );
    assert!(rebuilt.is_ok(), "{rebuilt:?}");
    let knots = vec![127.0, 127.0, 127.0, k1, k1, k2, 129.0, 129.0, 129.0];
    let pts = points(&[
        (0.0, 0.0),
        (1.0, 2.0),
        (2.0, -1.0),
        (3.0, 1.0),
        (4.0, 0.0),
        (5.0, 1.0),
    ]);
    let spline = BSpline::new(2, knots.clone(), pts).unwrap();
    let back = spline.reversed();
    check_mirrored_knots("degree 2", &knots, back.knots(), 2);
    let second = |c: &BSpline<2>, t| c.nth_derivative(t, 2).unwrap();
    check_reversed_curve("degree 2", &spline, &back, second, 5.0, &mut rng, 200);
}

#[test]
fn mirrored_knots_stay_valid_at_the_gap_rule_and_across_binades() {
    // Knots at exactly the least gap the constructor accepts (4ε × range),
    // and knots an ulp or two apart where the mirror lands in a coarser
    // binade, at random offsets and scales: the reversed curve is always
    // valid, with the multiplicities kept.
    let mut rng = Rng(0xB5);
    let mut checked = 0;
    for case in 0..5000 {
        let degree = 1 + rng.below(3);
        let (a, width) = match rng.below(3) {
            0 => (rng.range(-1.0, 1.0), rng.range(0.5, 2.0)),
            1 => (rng.range(60.0, 130.0), rng.range(0.5, 10.0)),
            _ => {
                let e = 2f64.powi(rng.below(40) as i32 - 20);
                (e * rng.range(0.9, 1.1), e * rng.range(0.01, 3.0))
            }
        };
        let b = a + width;
        let mut interior = Vec::new();
        for _ in 0..1 + rng.below(4) {
            let k = rng.range(a, b);
            interior.push(k);
            match rng.below(3) {
                0 => interior.push(k + 4.0 * f64::EPSILON * width),
                1 => interior.push(up(k)),
                _ => interior.push(up(up(k))),
            }
            if rng.below(2) == 0 {
                interior.push(k);
            }
        }
        interior.sort_by(f64::total_cmp);
        let mut knots = vec![a; degree + 1];
        knots.extend(interior.iter().filter(|&&k| k > a && k < b));
        knots.extend(vec![b; degree + 1]);
        let n = knots.len() - degree - 1;
        let pts: Vec<Point2<f64>> = (0..n)
            .map(|_| Point2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
            .collect();
        let Ok(spline) = BSpline::new(degree, knots.clone(), pts) else {
            continue; // too close for the constructor, or too many equal
        };
        checked += 1;
        let back = spline.reversed();
        let what = format!("case {case}: {knots:?}");
        let rebuilt = BSpline::new(degree, back.knots().to_vec(), back.points().to_vec());
        assert!(rebuilt.is_ok(), "{what}: {:?}: {rebuilt:?}", back.knots());
        check_mirrored_knots(&what, &knots, back.knots(), degree);
    }
    assert!(checked > 1000, "only {checked} valid cases");
}

// ---------------------------------------------------------------------------
// Surfaces
// ---------------------------------------------------------------------------

/// `back` is `surface` with every normal negated: the same points and
/// partials (bit for bit) and negated normals at random parameters; on
/// `rays` random rays through its box, the same hits (`t`, `point`, `uv`)
/// with negated normals, one by one and batched.
fn check_reversed_surface<S: Surface + Intersect>(
    what: &str,
    surface: &S,
    back: &S,
    rng: &mut Rng,
    rays: usize,
) {
    let [(u0, u1), (v0, v1)] = surface.domain();
    assert_eq!(back.domain(), surface.domain(), "{what}");
    assert_eq!(back.bounds(), surface.bounds(), "{what}");
    let mut normals = 0;
    for _ in 0..500 {
        let (u, v) = (rng.range(u0, u1), rng.range(v0, v1));
        assert_eq!(back.eval(u, v), surface.eval(u, v), "{what} at ({u}, {v})");
        assert_eq!(back.partials(u, v), surface.partials(u, v), "{what}");
        let negated = surface.normal(u, v).map(|n| -n);
        assert_eq!(back.normal(u, v), negated, "{what} at ({u}, {v})");
        normals += usize::from(negated.is_some());
    }
    assert!(normals > 400, "{what}: {normals} normals");
    // Also on the domain's edges (poles, collapsed edges).
    for (u, v) in [
        (u0, v0),
        (u0, v1),
        (u1, v0),
        (u1, v1),
        (u0, 0.5 * (v0 + v1)),
    ] {
        assert_eq!(
            back.normal(u, v),
            surface.normal(u, v).map(|n| -n),
            "{what}"
        );
    }
    let rays = random_rays(rng, &surface.bounds(), rays);
    let mut hits = 0;
    for ray in &rays {
        let want = surface.intersect(ray, 0.0, f64::INFINITY);
        let got = back.intersect(ray, 0.0, f64::INFINITY);
        assert_eq!(got, want.map(negated), "{what}: {ray:?}");
        hits += usize::from(want.is_some());
    }
    assert!(hits > rays.len() / 5, "{what}: {hits} hits");
    let ranges: Vec<(f64, f64)> = rays
        .iter()
        .map(|_| match rng.below(3) {
            0 => (0.0, f64::INFINITY),
            1 => (rng.range(0.0, 2.0), f64::INFINITY),
            _ => (0.0, rng.range(0.5, 4.0)),
        })
        .collect();
    let (mut want, mut got) = (vec![None; rays.len()], vec![None; rays.len()]);
    surface.intersect_batch(&rays, &ranges, &mut want);
    back.intersect_batch(&rays, &ranges, &mut got);
    let want: Vec<Option<Hit>> = want.into_iter().map(|h| h.map(negated)).collect();
    assert_eq!(got, want, "{what}: batch");
}

/// The hit with its normal negated.
fn negated(hit: Hit) -> Hit {
    Hit {
        normal: -hit.normal,
        ..hit
    }
}

/// Rays from a sphere around `bounds` (twice its half diagonal) toward
/// random points of the box, with random lengths of `dir`.
fn random_rays(rng: &mut Rng, bounds: &Aabb, count: usize) -> Vec<Ray> {
    let centre = Point3::from((bounds.min.coords + bounds.max.coords) * 0.5);
    let radius = (bounds.max - bounds.min).norm().max(1e-3);
    (0..count)
        .map(|_| {
            let origin = centre + rng.direction() * radius;
            let target = rng.point_in(bounds);
            Ray::new(origin, (target - origin) * rng.range(0.2, 2.0) / radius)
        })
        .collect()
}

/// `back` is `mesh` turned the other way round: the same positions, `uv`s
/// and bound, every normal negated, every triangle `[a, b, c]` as
/// `[a, c, b]`.
fn check_reversed_mesh(what: &str, mesh: &Mesh, back: &Mesh) {
    assert!(!mesh.triangles.is_empty(), "{what}");
    assert_eq!(back.positions, mesh.positions, "{what}");
    assert_eq!(back.uvs, mesh.uvs, "{what}");
    assert_eq!(back.bound, mesh.bound, "{what}");
    let normals: Vec<_> = mesh.normals.iter().map(|n| -*n).collect();
    assert_eq!(back.normals, normals, "{what}");
    let triangles: Vec<[u32; 3]> = mesh.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect();
    assert_eq!(back.triangles, triangles, "{what}");
    // Each face still follows its vertices' normals.
    let mut along = 0;
    for t in &back.triangles {
        let [a, b, c] = t.map(|i| back.positions[i as usize]);
        let face = (b - a).cross(&(c - a));
        let vertex = back.normals[t[0] as usize];
        along += usize::from(face.dot(&vertex) > 0.0);
    }
    assert!(
        along * 10 > back.triangles.len() * 9,
        "{what}: {along} of {}",
        back.triangles.len()
    );
}

/// A profile with no Bézier spans (the sampled-profile intersector): the
/// vase's cubic, seen only through the three required methods.
#[derive(Clone)]
struct Sampled(Bezier<2>);

impl Curve<2> for Sampled {
    fn domain(&self) -> (f64, f64) {
        self.0.domain()
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        self.0.eval(t)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        self.0.derivative(t)
    }
}

#[test]
fn reversed_revolutions_negate_every_normal_and_nothing_else() {
    let mut rng = Rng(0xC1);
    let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.5));
    let torus = Revolution::new(common::conic_profiles::torus_profile(2.0, 0.5)).with_axis(
        Point3::new(1.0, -2.0, 0.5),
        Unit::new_normalize(Vector3::new(1.0, 2.0, 3.0)),
    );
    let goblet = Revolution::new(common::wine_glass());
    let vase = Revolution::new(common::vase()).with_axis(Point3::origin(), Vector3::z_axis());
    for (what, surface) in [("sphere", &sphere), ("torus", &torus)] {
        check_reversed_surface(what, surface, &surface.reversed(), &mut rng, 3000);
        assert_eq!(surface.reversed().reversed(), *surface);
        assert_ne!(surface.reversed(), *surface);
    }
    check_reversed_surface("goblet", &goblet, &goblet.reversed(), &mut rng, 3000);
    assert_eq!(goblet.reversed().reversed(), goblet);
    check_reversed_surface("vase", &vase, &vase.reversed(), &mut rng, 3000);
    let sampled = Revolution::new(Sampled(common::vase()));
    assert!(!sampled.has_exact_intersector());
    check_reversed_surface(
        "sampled vase",
        &sampled,
        &sampled.reversed(),
        &mut rng,
        1000,
    );

    // The local normals too; and the sphere's outward after reversing (its
    // profile runs up from the south pole, so its own normals point in).
    let back = sphere.reversed();
    for _ in 0..100 {
        let (u, theta) = (rng.range(-1.5, 1.5), rng.range(0.0, 6.3));
        let n = back.normal_local(u, theta).unwrap();
        assert_eq!(Some(-n), sphere.normal_local(u, theta));
        let p = back.eval(u, theta).coords;
        assert!(n.dot(&p) > 0.999_999 * p.norm(), "{n:?} at {p:?}");
    }
    // The poles: limit normals, negated.
    for u in [-1.5, 1.5] {
        let n = sphere.normal(u, 1.0).unwrap();
        assert_eq!(back.normal(u, 1.0), Some(-n));
        assert!((n.y.abs() - 1.0).abs() < 1e-15);
    }
}

#[test]
fn reversed_revolutions_mesh_the_other_way_round() {
    let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.0));
    let goblet = Revolution::new(common::wine_glass())
        .with_axis(Point3::new(0.5, 0.0, 0.0), Vector3::x_axis());
    let meshes = [
        (
            "sphere",
            sphere.tessellate(1e-3),
            sphere.reversed().tessellate(1e-3),
        ),
        (
            "goblet",
            goblet.tessellate(1e-3),
            goblet.reversed().tessellate(1e-3),
        ),
    ];
    for (what, mesh, back) in meshes {
        let (mesh, back) = (mesh.unwrap(), back.unwrap());
        check_reversed_mesh(what, &mesh, &back);
        check_reversed_mesh(&format!("{what} welded"), &mesh.welded(), &back.welded());
    }
}

/// A random clamped B-spline surface of degrees `(3, 2)` on a `6 × 5` net,
/// and the NURBS surface of the same net with random weights.
fn random_spline_surfaces(seed: u64) -> (BSplineSurface, NurbsSurface) {
    let mut rng = Xorshift64Star(seed);
    let (rows, cols) = (6, 5);
    let knots = (
        clamped_knots(&mut rng, 3, rows),
        clamped_knots(&mut rng, 2, cols),
    );
    let grid = rng.grid(rows, cols);
    let weights = rng.weights(rows, cols);
    let spline = BSplineSurface::new((3, 2), knots.clone(), grid.clone()).unwrap();
    let nurbs = NurbsSurface::new((3, 2), knots, grid, weights).unwrap();
    (spline, nurbs)
}

#[test]
fn reversed_tensor_surfaces_negate_every_normal_and_nothing_else() {
    let mut rng = Rng(0xC2);
    for (what, surface) in [
        ("gentle bicubic", common::patch_shapes::gentle_bicubic()),
        ("folded bicubic", common::tensor_shapes::folded_bicubic()),
    ] {
        let back = surface.reversed();
        check_reversed_surface(what, &surface, &back, &mut rng, 3000);
        assert_eq!(back.reversed(), surface);
        assert_eq!(back.points(), surface.points());
    }
    let (spline, nurbs) = random_spline_surfaces(0x5EED);
    let back = spline.reversed();
    check_reversed_surface("B-spline surface", &spline, &back, &mut rng, 2000);
    assert_eq!(back.reversed(), spline);
    // Its Bézier patches and knot insertion keep the orientation; so does
    // the conversion to NURBS.
    for (piece, original) in back
        .to_bezier_patches()
        .iter()
        .zip(spline.to_bezier_patches())
    {
        let (u, v) = (0.3, 0.6);
        let n = original.surface.normal(u, v).unwrap();
        assert_eq!(piece.surface.normal(u, v), Some(-n));
    }
    let refined = back.insert_knot_u(0.37, 1).unwrap();
    let n = spline.normal(0.2, 0.7).unwrap();
    assert!((refined.normal(0.2, 0.7).unwrap().into_inner() + n.into_inner()).norm() < 1e-12);
    let as_nurbs = NurbsSurface::from(back.clone());
    assert_eq!(as_nurbs.normal(0.2, 0.7), Some(-n));

    let back = nurbs.reversed();
    check_reversed_surface("NURBS surface", &nurbs, &back, &mut rng, 2000);
    assert_eq!(back.reversed(), nurbs);
    let refined = back.insert_knot_v(0.61, 2).unwrap();
    let n = nurbs.normal(0.4, 0.1).unwrap();
    assert!((refined.normal(0.4, 0.1).unwrap().into_inner() + n.into_inner()).norm() < 1e-12);

    // The sphere octant: its pole is a collapsed edge with a limit normal.
    let octant = common::tensor_shapes::sphere_octant(1.0);
    let back = octant.reversed();
    check_reversed_surface("sphere octant", &octant, &back, &mut rng, 2000);
    assert_eq!(back.normal(0.0, 0.3), octant.normal(0.0, 0.3).map(|n| -n));
    assert!(back.normal(0.0, 0.3).is_some());
}

#[test]
fn reversed_tensor_surfaces_mesh_the_other_way_round() {
    let (spline, nurbs) = random_spline_surfaces(0x5EEE);
    let bicubic = common::tensor_shapes::folded_bicubic();
    let octant = common::tensor_shapes::sphere_octant(1.0);
    let meshes = [
        (
            "bicubic",
            bicubic.tessellate(1e-3),
            bicubic.reversed().tessellate(1e-3),
        ),
        (
            "B-spline",
            spline.tessellate(1e-3),
            spline.reversed().tessellate(1e-3),
        ),
        (
            "NURBS",
            nurbs.tessellate(1e-3),
            nurbs.reversed().tessellate(1e-3),
        ),
        (
            "octant",
            octant.tessellate(1e-3),
            octant.reversed().tessellate(1e-3),
        ),
    ];
    for (what, mesh, back) in meshes {
        check_reversed_mesh(what, &mesh.unwrap(), &back.unwrap());
    }
}

#[test]
fn the_reversed_teapot_negates_every_normal_and_nothing_else() {
    let mut rng = Rng(0xC3);
    let teapot = BezierPatches::new(common::teapot::patches()).unwrap();
    let back = teapot.reversed();
    assert_eq!(back.reversed(), teapot);
    for (patch, original) in back.patches().iter().zip(teapot.patches()) {
        assert_eq!(*patch, original.reversed());
    }
    let rays = random_rays(&mut rng, &teapot.bounds(), 3000);
    let mut hits = 0;
    for ray in &rays {
        let want = teapot.intersect_patch(ray, 0.0, f64::INFINITY);
        let got = back.intersect_patch(ray, 0.0, f64::INFINITY);
        assert_eq!(got, want.map(|(k, hit)| (k, negated(hit))), "{ray:?}");
        hits += usize::from(want.is_some());
    }
    assert!(hits > 1000, "{hits} hits");
    check_reversed_surface_hits("teapot", &teapot, &back, &rays);
    let mesh = teapot.tessellate(1e-2).unwrap();
    check_reversed_mesh("teapot", &mesh, &back.tessellate(1e-2).unwrap());

    // Some patches reversed, the others not: each hit and each face takes
    // its own patch's orientation.
    let patches: Vec<BezierSurface> = teapot
        .patches()
        .iter()
        .enumerate()
        .map(|(k, p)| if k % 3 == 0 { p.reversed() } else { p.clone() })
        .collect();
    let mixed = BezierPatches::new(patches).unwrap();
    for ray in &rays {
        let want = teapot.intersect_patch(ray, 0.0, f64::INFINITY);
        let want = want.map(|(k, hit)| (k, if k % 3 == 0 { negated(hit) } else { hit }));
        assert_eq!(
            mixed.intersect_patch(ray, 0.0, f64::INFINITY),
            want,
            "{ray:?}"
        );
    }
    let mixed_mesh = mixed.tessellate(1e-2).unwrap();
    assert_eq!(mixed_mesh.positions, mesh.positions);
    let flipped = mixed_mesh
        .triangles
        .iter()
        .zip(&mesh.triangles)
        .filter(|&(got, &[a, b, c])| {
            assert!(*got == [a, b, c] || *got == [a, c, b]);
            *got == [a, c, b]
        })
        .count();
    assert!(flipped > 0 && flipped < mesh.triangles.len(), "{flipped}");
}

/// The `Intersect` hits and batch of `back` are `surface`'s with negated
/// normals on `rays`.
fn check_reversed_surface_hits<S: Intersect>(what: &str, surface: &S, back: &S, rays: &[Ray]) {
    let ranges = vec![(0.0, f64::INFINITY); rays.len()];
    let (mut want, mut got) = (vec![None; rays.len()], vec![None; rays.len()]);
    surface.intersect_batch(rays, &ranges, &mut want);
    back.intersect_batch(rays, &ranges, &mut got);
    for ((ray, want), got) in rays.iter().zip(want).zip(got) {
        assert_eq!(got, want.map(negated), "{what}: batch {ray:?}");
        assert_eq!(
            back.intersect(ray, 0.0, f64::INFINITY),
            got,
            "{what}: {ray:?}"
        );
    }
}

#[test]
fn where_there_is_no_tangent_plane_a_hit_still_faces_the_ray() {
    // A cone's apex on the axis: no tangent plane, so the hit's normal is
    // the ray's reverse, for either orientation.
    let cone = Revolution::new(Bezier::new(points(&[(0.0, 1.0), (1.0, 0.0)])).unwrap());
    let ray = Ray::new(Point3::new(0.0, 3.0, 0.0), -Vector3::y());
    for surface in [cone.clone(), cone.reversed()] {
        let hit = surface.intersect(&ray, 0.0, f64::INFINITY).unwrap();
        assert_eq!(hit.point, Point3::new(0.0, 1.0, 0.0));
        assert_eq!(hit.normal.into_inner(), Vector3::y());
        assert_eq!(surface.normal(0.0, 0.0), None);
    }
}

// ---------------------------------------------------------------------------
// Serialization and the law checker
// ---------------------------------------------------------------------------

#[cfg(feature = "serde")]
mod serde_flag {
    use super::*;
    use serde::Serialize;
    use serde::de::DeserializeOwned;
    use std::fmt::Debug;

    /// The JSON of `surface` and of its reversal: only the latter writes the
    /// flag, both read back equal (the flag included), and the JSON without
    /// the flag (as written before it existed) reads as not reversed.
    fn round_trip<S>(what: &str, surface: &S, back: &S)
    where
        S: Serialize + DeserializeOwned + PartialEq + Debug,
    {
        let json = serde_json::to_string(surface).unwrap();
        let json_back = serde_json::to_string(back).unwrap();
        assert!(!json.contains("reversed"), "{what}: {json}");
        assert!(
            json_back.contains(r#""reversed":true"#),
            "{what}: {json_back}"
        );
        assert_eq!(
            serde_json::from_str::<S>(&json).unwrap(),
            *surface,
            "{what}"
        );
        assert_eq!(
            serde_json::from_str::<S>(&json_back).unwrap(),
            *back,
            "{what}"
        );
        assert_ne!(
            serde_json::from_str::<S>(&json_back).unwrap(),
            *surface,
            "{what}"
        );
        let explicit = json_back.replace(r#""reversed":true"#, r#""reversed":false"#);
        assert_eq!(
            serde_json::from_str::<S>(&explicit).unwrap(),
            *surface,
            "{what}"
        );
    }

    #[test]
    fn the_orientation_flag_survives_a_round_trip() {
        let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.0))
            .with_axis(Point3::new(1.0, 2.0, 3.0), Vector3::x_axis());
        round_trip("sphere", &sphere, &sphere.reversed());
        let read: Revolution<Nurbs<2>> =
            serde_json::from_str(&serde_json::to_string(&sphere.reversed()).unwrap()).unwrap();
        assert_eq!(read.normal(0.2, 0.3), sphere.normal(0.2, 0.3).map(|n| -n));
        let bicubic = common::patch_shapes::gentle_bicubic();
        round_trip("bicubic", &bicubic, &bicubic.reversed());
        let (spline, nurbs) = random_spline_surfaces(0x5EF0);
        round_trip("B-spline", &spline, &spline.reversed());
        round_trip("NURBS", &nurbs, &nurbs.reversed());
        // A model keeps each patch's flag.
        let teapot = BezierPatches::new(common::teapot::patches()).unwrap();
        let back = teapot.reversed();
        let json = serde_json::to_string(&back).unwrap();
        let read: BezierPatches = serde_json::from_str(&json).unwrap();
        assert_eq!(read, back);
        assert_eq!(json.matches(r#""reversed":true"#).count(), teapot.len());
    }
}

#[cfg(feature = "testing")]
mod laws {
    use super::*;
    use revolve::testing::check_surface_normals;

    /// A plane whose normal flips from `+z` to `−z` halfway.
    struct Flipping;

    impl Surface for Flipping {
        fn domain(&self) -> [(f64, f64); 2] {
            [(0.0, 1.0), (0.0, 1.0)]
        }
        fn eval(&self, u: f64, v: f64) -> Point3<f64> {
            Point3::new(u, v, 0.0)
        }
        fn partials(&self, _: f64, _: f64) -> (Vector3<f64>, Vector3<f64>) {
            (Vector3::x(), Vector3::y())
        }
        fn normal(&self, u: f64, _: f64) -> Option<Unit<Vector3<f64>>> {
            Some(if u < 0.5 {
                Vector3::z_axis()
            } else {
                -Vector3::z_axis()
            })
        }
    }

    #[test]
    fn the_normal_law_holds_for_either_orientation_but_only_one() {
        let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.0));
        let (spline, _) = random_spline_surfaces(0x5EF1);
        assert_eq!(check_surface_normals(&sphere, 12), Ok(()));
        assert_eq!(check_surface_normals(&sphere.reversed(), 12), Ok(()));
        assert_eq!(check_surface_normals(&spline.reversed(), 12), Ok(()));
        assert_eq!(
            check_surface_normals(&Flipping, 8).unwrap_err().law,
            "normal along ±∂S/∂u × ∂S/∂v, one sign throughout"
        );
    }
}

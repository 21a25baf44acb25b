//! The generic Newton intersector (`NewtonIntersector`) and the conservative
//! patch bounds it is seeded from (`PatchBounds` for `Revolution`).
//!
//! References: closed forms for degree-1 profiles (cylinder, cone, disk), and
//! the exact intersector of `Revolution` (univariate reduction, no missed
//! transversal hits) for the curved profiles. Newton is a local method, so
//! the comparisons count what it can get wrong (a missed hit, a farther root
//! than the nearest) separately from what it must never do (a false hit, a
//! hit nearer than the true nearest, an inaccurate converged hit, NaN).
//!
//! That queries do not allocate is checked in `tests/alloc.rs` (the binary
//! with the counting global allocator), on this module's vase and rays
//! (`revolve_testkit::newton_rays`).

use revolve_testkit as common;

use common::newton_rays::{POLE_VASE, Xorshift64 as Rng, pole_vase as vase, random_ray};
use common::{GLASS, uniform_cubic};
use revolve::nalgebra::{Point2, Point3, Unit, Vector2, Vector3};
use revolve::ray::newton::{MAX_DEPTH, NewtonFinish, NewtonReport};
use revolve::{
    Aabb, Bezier, Curve, Hit, Intersect, NewtonIntersector, PatchBounds, Ray, Revolution, Surface,
};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

// ---------------------------------------------------------------------------
// Surfaces and rays

fn line(a: (f64, f64), b: (f64, f64)) -> Revolution<Bezier<2>> {
    Revolution::new(Bezier::new(vec![Point2::new(a.0, a.1), Point2::new(b.0, b.1)]).unwrap())
}

/// `|o + t·d − S(u, v)|` at a hit.
fn residual<S: Surface>(s: &S, ray: &Ray, hit: &Hit) -> f64 {
    (ray.at(hit.t) - s.eval(hit.uv.0, hit.uv.1)).norm()
}

fn assert_sane(hit: &Hit) {
    assert!(hit.t.is_finite(), "{hit:?}");
    assert!(hit.point.coords.iter().all(|c| c.is_finite()), "{hit:?}");
    assert!(hit.normal.iter().all(|c| c.is_finite()), "{hit:?}");
    assert!((hit.normal.norm() - 1.0).abs() < 1e-12, "{hit:?}");
    assert!(hit.uv.0.is_finite() && hit.uv.1.is_finite(), "{hit:?}");
}

/// The real roots of `a t² + 2 b t + c` (`a ≠ 0`), ascending.
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let disc = b * b - a * c;
    if disc < 0.0 || a == 0.0 {
        return Vec::new();
    }
    let s = disc.sqrt();
    let mut roots = vec![(-b - s) / a, (-b + s) / a];
    roots.sort_by(f64::total_cmp);
    roots
}

/// How Newton's hits compare with closed-form roots.
#[derive(Debug, Default)]
struct ClosedForm {
    /// Newton hit the nearest root.
    nearest: usize,
    /// Newton hit another true root, farther than the nearest.
    farther: usize,
    /// Newton found nothing where a root exists.
    missed: usize,
}

/// Checks Newton's answer against the valid roots `roots` (ascending, `t > 0`,
/// on the surface): a hit must be one of them to `tol · max(t, 1)`, and no
/// hit may appear where there is none (up to rays through a rim, `rim`).
fn check_closed_form(
    roots: &[f64],
    got: Option<Hit>,
    tol: f64,
    rim: bool,
    tally: &mut ClosedForm,
    what: &dyn std::fmt::Debug,
) {
    match (roots.first(), got) {
        (Some(&t), Some(hit)) => {
            assert_sane(&hit);
            let close = |r: f64| (hit.t - r).abs() <= tol * r.max(1.0);
            if close(t) {
                tally.nearest += 1;
            } else {
                assert!(
                    roots.iter().any(|&r| close(r)),
                    "{what:?}: {roots:?} vs {hit:?}"
                );
                tally.farther += 1;
            }
        }
        (None, None) => {}
        (Some(_), None) if !rim => tally.missed += 1,
        (None, Some(hit)) if !rim => panic!("false hit {hit:?} on {what:?}"),
        _ => {}
    }
}

// ---------------------------------------------------------------------------
// Closed forms

#[test]
fn cylinder_hits_match_the_closed_form_and_the_exact_solver() {
    // x² + z² = 1, 0 ≤ y ≤ 2.
    let cylinder = line((1.0, 0.0), (1.0, 2.0));
    let newton = NewtonIntersector::new(&cylinder, 8);
    let mut rng = Rng::new(7);
    let mut tally = ClosedForm::default();
    for _ in 0..1000 {
        let o = Point3::new(rng.range(-4.0, 4.0), rng.range(-1.0, 3.0), -4.0);
        let target = Point3::new(
            rng.range(-1.2, 1.2),
            rng.range(-0.2, 2.2),
            rng.range(-1.2, 1.2),
        );
        let ray = Ray::new(o, target - o);
        let (d, o) = (ray.dir, ray.origin);
        // |o_xz + t d_xz|² = 1, then the height must be in [0, 2].
        let a = d.x * d.x + d.z * d.z;
        let b = o.x * d.x + o.z * d.z;
        let c = o.x * o.x + o.z * o.z - 1.0;
        let all = quadratic_roots(a, b, c);
        let height = |t: f64| ray.at(t).y;
        let rim = all
            .iter()
            .any(|&t| height(t).abs() < 1e-9 || (height(t) - 2.0).abs() < 1e-9);
        let roots: Vec<f64> = all
            .into_iter()
            .filter(|&t| t > 0.0 && (0.0..=2.0).contains(&height(t)))
            .collect();
        let got = newton.intersect(&ray, 0.0, f64::INFINITY);
        check_closed_form(&roots, got, 1e-12, rim, &mut tally, &ray);
        if let Some(hit) = got {
            let p = hit.point;
            assert!((p.x.hypot(p.z) - 1.0).abs() < 1e-13);
            // Where Newton found the nearest root, the exact solver agrees.
            if (hit.t - roots[0]).abs() <= 1e-12 * roots[0] {
                let exact = cylinder.intersect(&ray, 0.0, f64::INFINITY).unwrap();
                assert!((hit.t - exact.t).abs() <= 1e-12, "{exact:?} vs {hit:?}");
                assert!((hit.normal.into_inner() - exact.normal.into_inner()).norm() < 1e-9);
            }
        }
    }
    println!("{tally:?}");
    assert!(tally.nearest > 300, "{tally:?}");
    // Misses and farther roots come from near-tangent rays only: rare.
    assert!(
        (tally.farther + tally.missed) * 100 <= tally.nearest,
        "{tally:?}"
    );
}

#[test]
fn cone_hits_match_the_closed_form() {
    // x² + z² = (1 − y)², 0 ≤ y ≤ 1 (apex at (0, 1, 0)).
    let cone = line((1.0, 0.0), (0.0, 1.0));
    let newton = NewtonIntersector::new(&cone, 8);
    let mut rng = Rng::new(11);
    let mut tally = ClosedForm::default();
    for _ in 0..1000 {
        let o = Point3::new(rng.range(-3.0, 3.0), rng.range(-1.0, 3.0), 3.0);
        let target = Point3::new(
            rng.range(-1.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let ray = Ray::new(o, target - o);
        let (d, o) = (ray.dir, ray.origin);
        // (o_x + t d_x)² + (o_z + t d_z)² − (1 − o_y − t d_y)² = 0.
        let h = 1.0 - o.y;
        let a = d.x * d.x + d.z * d.z - d.y * d.y;
        let b = o.x * d.x + o.z * d.z + h * d.y;
        let c = o.x * o.x + o.z * o.z - h * h;
        let all = quadratic_roots(a, b, c);
        let height = |t: f64| ray.at(t).y;
        // The rim (y = 0), and the apex where the root is double.
        let rim = all
            .iter()
            .any(|&t| height(t).abs() < 1e-9 || (height(t) - 1.0).abs() < 1e-6);
        let roots: Vec<f64> = all
            .into_iter()
            .filter(|&t| t > 0.0 && (0.0..=1.0).contains(&height(t)))
            .collect();
        let got = newton.intersect(&ray, 0.0, f64::INFINITY);
        check_closed_form(&roots, got, 1e-11, rim, &mut tally, &ray);
    }
    println!("{tally:?}");
    assert!(tally.nearest > 300, "{tally:?}");
    assert!(
        (tally.farther + tally.missed) * 100 <= tally.nearest,
        "{tally:?}"
    );
}

#[test]
fn disk_hits_match_the_closed_form_including_the_pole() {
    // The unit disk in the plane y = 0 (the profile leaves the axis at u = 0).
    let disk = line((0.0, 0.0), (1.0, 0.0));
    let newton = NewtonIntersector::new(&disk, 6);
    let mut rng = Rng::new(13);
    let mut tally = ClosedForm::default();
    for _ in 0..500 {
        let o = Point3::new(
            rng.range(-2.0, 2.0),
            rng.range(0.5, 3.0),
            rng.range(-2.0, 2.0),
        );
        let target = Point3::new(rng.range(-1.5, 1.5), 0.0, rng.range(-1.5, 1.5));
        let ray = Ray::new(o, target - o);
        let t = -o.y / ray.dir.y;
        let p = ray.at(t);
        let r = p.x.hypot(p.z);
        let roots: Vec<f64> = if r <= 1.0 { vec![t] } else { vec![] };
        let got = newton.intersect(&ray, 0.0, f64::INFINITY);
        check_closed_form(&roots, got, 1e-12, (r - 1.0).abs() < 1e-9, &mut tally, &ray);
        if let Some(hit) = got {
            assert!(hit.point.y.abs() < 1e-14);
        }
    }
    // A plane has one root: Newton never misses it or finds another.
    assert_eq!((tally.farther, tally.missed), (0, 0), "{tally:?}");
    assert!(tally.nearest > 150, "{tally:?}");
    // Along the axis, onto the pole: the Jacobian is singular at the answer
    // (∂S/∂θ = 0 where x = 0), yet the hit is exact and has the limit normal.
    for scale in [1.0, 1e-3, 7.0] {
        let ray = Ray::new(Point3::new(0.0, 4.0, 0.0), Vector3::new(0.0, -scale, 0.0));
        let hit = newton
            .intersect(&ray, 0.0, f64::INFINITY)
            .expect("pole hit");
        assert_sane(&hit);
        assert!((hit.t - 4.0 / scale).abs() < 1e-12 * hit.t, "{hit:?}");
        assert!(hit.point.coords.norm() < 1e-12, "{hit:?}");
        let exact = disk.intersect(&ray, 0.0, f64::INFINITY).unwrap();
        assert!((hit.normal.into_inner() - exact.normal.into_inner()).norm() < 1e-12);
    }
    // Parallel to the plane, above it: a miss.
    let ray = Ray::new(Point3::new(-3.0, 0.1, 0.0), Vector3::new(1.0, 0.0, 0.2));
    assert_eq!(newton.intersect(&ray, 0.0, f64::INFINITY), None);
}

#[test]
fn profiles_without_spans_are_intersected_too() {
    // The exact solver needs Bézier spans; Newton needs only bounds. The arc
    // turns into the upper half of the sphere of radius 2 about (0, −1, 0).
    let dome = Revolution::new(Arc);
    assert_eq!(dome.periodic(), [false, true]);
    let newton = NewtonIntersector::new(&dome, 8);
    let centre = Point3::new(0.0, -1.0, 0.0);
    let mut rng = Rng::new(21);
    let mut tally = ClosedForm::default();
    for _ in 0..500 {
        let o = Point3::new(
            rng.range(-5.0, 5.0),
            rng.range(2.0, 5.0),
            rng.range(-5.0, 5.0),
        );
        let target = Point3::new(
            rng.range(-2.0, 2.0),
            rng.range(-1.0, 1.0),
            rng.range(-2.0, 2.0),
        );
        let ray = Ray::new(o, target - o);
        let oc = ray.origin - centre;
        let all = quadratic_roots(
            ray.dir.norm_squared(),
            oc.dot(&ray.dir),
            oc.norm_squared() - 4.0,
        );
        let rim = all.iter().any(|&t| (ray.at(t).y + 1.0).abs() < 1e-9);
        let roots: Vec<f64> = all
            .into_iter()
            .filter(|&t| t > 0.0 && ray.at(t).y >= -1.0)
            .collect();
        let got = newton.intersect(&ray, 0.0, f64::INFINITY);
        check_closed_form(&roots, got, 1e-12, rim, &mut tally, &ray);
    }
    println!("{tally:?}");
    assert!(tally.nearest > 200, "{tally:?}");
    assert!(
        (tally.farther + tally.missed) * 100 <= tally.nearest,
        "{tally:?}"
    );
}

// ---------------------------------------------------------------------------
// Against the exact solver

/// How Newton's answers compare with the exact solver's over random rays.
#[derive(Debug, Default)]
struct Comparison {
    exact_hits: usize,
    /// Same hit (t within `1e-10 · scale / |d|`).
    matched: usize,
    /// Newton found a farther root than the nearest.
    farther: usize,
    /// Newton found nothing where the exact solver hits.
    missed: usize,
    /// Newton hit nearer than the exact solver, or where it misses.
    wrong: usize,
    /// Largest `|t − t_exact|·|d| / scale` over matched hits.
    worst_match: f64,
}

fn compare<S: PatchBounds>(exact: &dyn Intersect, s: &S, depth: u32, rays: usize) -> Comparison {
    let newton = NewtonIntersector::new(s, depth);
    let bounds = exact.bounds();
    let scale = bounds.scale();
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let mut c = Comparison::default();
    for _ in 0..rays {
        let ray = random_ray(&mut rng, &bounds);
        let dn = ray.dir.norm();
        let reference = exact.intersect(&ray, 0.0, f64::INFINITY);
        let got = newton.intersect(&ray, 0.0, f64::INFINITY);
        if let Some(hit) = &got {
            assert_sane(hit);
            // Every Newton hit is a converged point of ray and surface.
            assert!(residual(s, &ray, hit) <= 1e-12 * scale, "{ray:?} {hit:?}");
        }
        c.exact_hits += reference.is_some() as usize;
        match (reference, got) {
            (Some(e), Some(h)) => {
                let err = (h.t - e.t).abs() * dn / scale;
                if err <= 1e-10 {
                    c.matched += 1;
                    c.worst_match = c.worst_match.max(err);
                } else if h.t > e.t {
                    c.farther += 1;
                } else {
                    c.wrong += 1;
                }
            }
            (Some(_), None) => c.missed += 1,
            (None, Some(_)) => c.wrong += 1,
            (None, None) => {}
        }
    }
    c
}

#[test]
fn vase_newton_agrees_with_the_exact_solver() {
    let vase = vase();
    for (depth, max_failures) in [(6, 15), (8, 0), (10, 0)] {
        // Measured: 5 farther roots at depth 6 (of about 1900 hits), none deeper.
        let c = compare(&vase, &vase, depth, 5000);
        println!("vase depth {depth}: {c:?}");
        assert_eq!(c.wrong, 0, "{c:?}");
        assert!(c.exact_hits > 1500, "{c:?}");
        assert!(c.missed + c.farther <= max_failures, "{c:?}");
        assert!(c.worst_match <= 1e-13, "{c:?}");
    }
}

#[test]
fn wine_glass_newton_agrees_with_the_exact_solver() {
    let glass = uniform_cubic(&GLASS);
    assert_eq!(glass.profile().points().len(), 25);
    // The glass has thin walls and folds (the foot's edge, the rim): rays
    // crossing a fold inside one leaf have two roots there, and Newton from
    // the leaf's centre may pick the farther one. Deeper trees make that
    // rarer; measured rates (per exact hit) are 3.7%, 0.16%, 0.03% at
    // depths 6, 8, 10. The bounds leave a little room.
    for (depth, max_rate) in [(6, 0.05), (8, 0.004), (10, 0.004)] {
        let c = compare(&glass, &glass, depth, 5000);
        println!("glass depth {depth}: {c:?}");
        assert_eq!(c.wrong, 0, "{c:?}");
        assert!(c.exact_hits > 1500, "{c:?}");
        let rate = (c.missed + c.farther) as f64 / c.exact_hits as f64;
        assert!(rate <= max_rate, "rate {rate}: {c:?}");
        assert!(c.worst_match <= 1e-13, "{c:?}");
    }
}

#[test]
fn placed_and_scaled_surfaces_agree_with_the_exact_solver() {
    let axis = Unit::new_normalize(Vector3::new(0.3, -1.0, 0.5));
    for k in [1e-6, 1.0, 1e6] {
        let profile = Bezier::new(
            POLE_VASE
                .iter()
                .map(|&(x, y)| Point2::new(x * k, y * k))
                .collect(),
        );
        let placed =
            Revolution::new(profile.unwrap()).with_axis(Point3::new(2.0 * k, -k, 0.5 * k), axis);
        let c = compare(&placed, &placed, 8, 2000);
        println!("placed vase ×{k:e}: {c:?}");
        assert_eq!(c.wrong, 0, "{c:?}");
        assert!(c.exact_hits > 250, "{c:?}");
        assert!(c.missed + c.farther <= 2, "{c:?}");
    }
}

// ---------------------------------------------------------------------------
// Conservative patch bounds

/// Asserts that `bound_patch` contains a dense sample of `S` over the patch.
fn assert_contains_patch<S: PatchBounds>(s: &S, u: (f64, f64), v: (f64, f64)) {
    let b = s.bound_patch(u, v);
    const N: usize = 24;
    for i in 0..=N {
        for j in 0..=N {
            let pu = u.0 + (u.1 - u.0) * i as f64 / N as f64;
            let pv = v.0 + (v.1 - v.0) * j as f64 / N as f64;
            let p = s.eval(pu, pv);
            assert!(
                b.contains(&p),
                "S({pu}, {pv}) = {p:?} outside {b:?} for {u:?} × {v:?}"
            );
        }
    }
}

/// Random sub-rectangles of the domain, from tiny to the whole.
fn random_patches(rng: &mut Rng, domain: [(f64, f64); 2], n: usize) -> Vec<[(f64, f64); 2]> {
    let mut out = vec![domain];
    for _ in 0..n {
        let width = 10f64.powf(rng.range(-4.0, 0.0));
        let r = |rng: &mut Rng, (a, b): (f64, f64)| {
            let w = (b - a) * width;
            let s = rng.range(a, b - w);
            (s, s + w)
        };
        out.push([r(rng, domain[0]), r(rng, domain[1])]);
    }
    out
}

/// A quarter circle of radius 2 without Bézier spans (exercises the
/// sampled fallback of the patch bounds).
struct Arc;

impl Curve<2> for Arc {
    fn domain(&self) -> (f64, f64) {
        (0.0, FRAC_PI_2)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let t = t.clamp(0.0, FRAC_PI_2);
        Point2::new(2.0 * t.cos(), 2.0 * t.sin() - 1.0)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        let t = t.clamp(0.0, FRAC_PI_2);
        Vector2::new(-2.0 * t.sin(), 2.0 * t.cos())
    }
}

#[test]
fn patch_boxes_contain_the_patch() {
    let mut rng = Rng::new(99);
    let axis = Unit::new_normalize(Vector3::new(1.0, 2.0, -0.5));
    let tilted = vase().with_axis(Point3::new(1.0, -2.0, 3.0), axis);
    let negative = line((-1.0, 0.0), (-0.5, 1.5));
    let crossing = Revolution::new(
        Bezier::new(vec![
            Point2::new(-1.0, 0.0),
            Point2::new(2.0, 0.5),
            Point2::new(-0.5, 1.0),
            Point2::new(0.8, 1.5),
        ])
        .unwrap(),
    );
    check_patches("vase", &vase(), &mut rng);
    check_patches("glass", &uniform_cubic(&GLASS), &mut rng);
    check_patches("tilted vase", &tilted, &mut rng);
    check_patches("negative x", &negative, &mut rng);
    check_patches("crossing the axis", &crossing, &mut rng);
    check_patches("arc (no spans)", &Revolution::new(Arc), &mut rng);
}

fn check_patches<S: PatchBounds>(name: &str, s: &S, rng: &mut Rng) {
    println!("checking {name}");
    for [u, v] in random_patches(rng, s.domain(), 150) {
        assert_contains_patch(s, u, v);
    }
    // The tree's leaves, and the root (the union of everything).
    let newton = NewtonIntersector::new(s, 7);
    for leaf in newton.leaves() {
        assert_contains_patch(s, leaf.u, leaf.v);
        assert!(newton.bounds().contains(&leaf.bounds.min));
        assert!(newton.bounds().contains(&leaf.bounds.max));
    }
}

#[test]
fn sector_boxes_are_tight() {
    // A cylinder's x is constant, so its patch box is exactly the box of the
    // arc (times the height range), up to the rounding pad.
    let cylinder = line((1.0, 0.0), (1.0, 2.0));
    let cases = [
        (
            (0.3, 2.0),
            ((2.0f64.cos(), 0.3f64.cos()), (-1.0, -(0.3f64.sin()))),
        ),
        ((0.0, FRAC_PI_2), ((0.0, 1.0), (-1.0, 0.0))),
        ((PI, 1.5 * PI), ((-1.0, 0.0), (0.0, 1.0))),
        (
            (1.0, 1.2),
            (
                (1.2f64.cos(), 1.0f64.cos()),
                (-(1.2f64.sin()), -(1.0f64.sin())),
            ),
        ),
        ((0.0, TAU), ((-1.0, 1.0), (-1.0, 1.0))),
    ];
    for (v, ((x0, x1), (z0, z1))) in cases {
        let b = cylinder.bound_patch((0.25, 0.75), v);
        let want = [x0, 0.5, z0, x1, 1.5, z1];
        let got = [b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z];
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-13, "θ in {v:?}: {got:?} vs {want:?}");
        }
    }
    // Negative x is |x| half a turn on: the same box.
    let mirrored = line((-1.0, 0.0), (-1.0, 2.0));
    for v in [(0.3, 2.0), (4.0, 5.5)] {
        let (a, b) = (
            cylinder.bound_patch((0.0, 1.0), v),
            mirrored.bound_patch((0.0, 1.0), v),
        );
        let shifted = cylinder.bound_patch((0.0, 1.0), (v.0 + PI, v.1 + PI));
        assert!((b.min - shifted.min).norm() < 1e-13 && (b.max - shifted.max).norm() < 1e-13);
        assert!(a != b);
    }
    // Small patches of a curved profile: the control-point hull converges to
    // the patch, so the box is barely larger than the sampled extent.
    let vase = vase();
    for u0 in [0.1, 0.4, 0.8] {
        let (u, v) = ((u0, u0 + 0.01), (1.0, 1.01));
        let b = vase.bound_patch(u, v);
        let samples: Vec<_> = (0..=20)
            .flat_map(|i| (0..=20).map(move |j| (i, j)))
            .map(|(i, j)| vase.eval(u.0 + 0.01 * i as f64 / 20.0, v.0 + 0.01 * j as f64 / 20.0))
            .collect();
        let tight = Aabb::from_points(&samples);
        let excess = (b.extent() - tight.extent()).amax();
        assert!(excess < 1e-3 * tight.extent().amax(), "{b:?} vs {tight:?}");
    }
}

// ---------------------------------------------------------------------------
// Diagnostics

#[test]
fn diagnostics_tell_how_the_search_went() {
    let vase = vase();
    let newton = NewtonIntersector::new(&vase, 8);
    let scale = newton.scale();

    // A hit: iterations were made, the residual is at rounding level, and the
    // run that produced it ended converging.
    let ray = Ray::new(Point3::new(-4.0, 1.0, 0.2), Vector3::new(1.0, 0.05, 0.0));
    let (hit, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
    let hit = hit.expect("a hit");
    assert_eq!(newton.intersect(&ray, 0.0, f64::INFINITY), Some(hit));
    assert!(report.converged());
    let run = report.hit.unwrap();
    assert_eq!(run.t, hit.t);
    assert_eq!(run.uv, hit.uv);
    assert!(run.converged && run.iterations > 0, "{report:?}");
    assert!(report.residual() <= 1e-14 * scale, "{report:?}");
    assert!(matches!(
        report.finish(),
        Some(NewtonFinish::ResidualSmall | NewtonFinish::StepSmall | NewtonFinish::RoundingFloor)
    ));
    assert!(report.leaves_tried >= 1 && report.boxes_tested > report.leaves_tried);
    assert!(report.converged_runs >= 1 && report.iterations >= run.iterations);
    assert_counts_consistent(&report);

    // A ray that passes just outside the silhouette (horizontal, at distance
    // (1 + δ)·x(u) from the axis at height y(u); the vase's height is
    // monotone in u, so it misses) but through some leaf boxes: runs are
    // made, none converges, and the closest one tells how near it came.
    let p = vase.profile().eval(0.6);
    let (ray, report) = [1e-3, 3e-3, 1e-2, 3e-2]
        .into_iter()
        .map(|inset| {
            let o = Point3::new(-4.0, p.y, p.x * (1.0 + inset));
            let ray = Ray::new(o, Vector3::new(1.0, 0.0, 0.0));
            let (hit, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
            assert_eq!(hit, None);
            assert!(vase.intersect(&ray, 0.0, f64::INFINITY).is_none());
            (ray, report)
        })
        .find(|(_, report)| report.leaves_tried > 0)
        .expect("some near miss enters a leaf box");
    assert!(!report.converged() && report.hit.is_none());
    assert_eq!(report.converged_runs, 0, "{report:?}");
    let closest = report.closest.expect("runs were made");
    assert!(!closest.converged);
    // Newton's closest approach is no nearer than the ray's true distance.
    assert!(report.residual() > 1e-4 * scale, "{report:?} for {ray:?}");
    assert_ne!(report.finish(), Some(NewtonFinish::ResidualSmall));
    assert_counts_consistent(&report);

    // A ray that misses every box: nothing was run.
    let ray = Ray::new(Point3::new(-4.0, 10.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
    let (hit, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
    assert_eq!(hit, None);
    assert_eq!(report.leaves_tried, 0);
    assert_eq!(report.runs(), 0);
    assert_eq!(report.finish(), None);
    assert_eq!(report.residual(), f64::INFINITY);

    // Hits beyond t_max: boxes entered after t_max are pruned; a run from a
    // box entered before it converges to the hit and is rejected for t, not
    // for convergence.
    let ray = Ray::new(Point3::new(-4.0, 1.0, 0.2), Vector3::new(1.0, 0.05, 0.0));
    let t_hit = newton.intersect(&ray, 0.0, f64::INFINITY).unwrap().t;
    let (hit, report) = newton.intersect_with_report(&ray, 0.0, 1.0);
    assert_eq!(hit, None);
    assert_eq!(report.leaves_tried, 0, "pruned by the boxes: {report:?}");
    let (hit, report) = newton.intersect_with_report(&ray, 0.0, t_hit - 1e-3);
    assert_eq!(hit, None);
    assert!(report.leaves_tried > 0, "{report:?}");
    assert!(report.rejected_t >= 1 && report.rejected_t <= report.converged_runs);
    assert!(
        !report.converged() && report.closest.unwrap().converged,
        "{report:?}"
    );
}

fn assert_counts_consistent(report: &NewtonReport) {
    let f = report.finishes;
    let total = f.residual_small
        + f.step_small
        + f.rounding_floor
        + f.iteration_cap
        + f.singular_jacobian
        + f.diverged
        + f.left_domain;
    assert_eq!(total, report.leaves_tried, "{report:?}");
    assert_eq!(f.get(NewtonFinish::ResidualSmall), f.residual_small);
}

#[test]
fn the_report_path_finds_the_same_hits_as_the_fast_path() {
    let glass = uniform_cubic(&GLASS);
    let newton = NewtonIntersector::new(&glass, 8);
    let bounds = newton.bounds();
    let mut rng = Rng::new(5);
    let mut total = NewtonReport::default();
    for _ in 0..2000 {
        let ray = random_ray(&mut rng, &bounds);
        let fast = newton.intersect(&ray, 0.0, f64::INFINITY);
        let (slow, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
        assert_eq!(fast, slow);
        assert_eq!(report.converged(), fast.is_some());
        assert_counts_consistent(&report);
        if let Some(run) = report.hit {
            assert!(run.converged && run.residual <= 1e-9 * newton.scale());
        }
        total.leaves_tried += report.leaves_tried;
        total.iterations += report.iterations;
    }
    // Newton converges quadratically from good starts: a handful of steps per
    // run on average.
    let per_run = total.iterations as f64 / total.leaves_tried as f64;
    println!(
        "{} runs, {per_run:.2} iterations per run",
        total.leaves_tried
    );
    assert!(per_run < 12.0, "{per_run}");
}

// ---------------------------------------------------------------------------
// Depth versus misses on grazing rays

#[test]
fn deeper_trees_miss_less_on_grazing_rays() {
    // Rays passing just inside the vase's silhouette: at height y(u) they
    // pass at distance x(u)·(1 − δ) from the axis, δ = 1e-1 … 1e-6, so they
    // cross the circle of radius x(u) at a shallow angle (cos ≈ √(2δ)); the
    // two roots are close, and the nearer one has a small basin of
    // attraction. The directions turn about the axis by generic angles, so
    // the tangent points do not sit on the tree's splits, and some rays tilt.
    let vase = vase();
    let profile = vase.profile();
    let mut rays = Vec::new();
    for i in 1..40 {
        let u = i as f64 / 40.0;
        let p = profile.eval(u);
        for k in 1..=6 {
            let inset = 10f64.powi(-k);
            let phi = 0.37 + 1.91 * (i * 6 + k as usize) as f64;
            let tilt = [0.0, 0.003, -0.01][(i + k as usize) % 3];
            let d = Vector3::new(phi.cos(), tilt, phi.sin());
            let n = Vector3::new(-phi.sin(), 0.0, phi.cos());
            let o = Point3::new(0.0, p.y, 0.0) + n * (p.x * (1.0 - inset)) - d * 5.0;
            rays.push(Ray::new(o, d));
        }
    }
    let mut failures = Vec::new();
    for depth in [0, 2, 4, 6, 8, 10, 12, 14] {
        let newton = NewtonIntersector::new(&vase, depth);
        let mut failed = 0;
        for ray in &rays {
            let exact = vase.intersect(ray, 0.0, f64::INFINITY);
            let got = newton.intersect(ray, 0.0, f64::INFINITY);
            match (exact, got) {
                (Some(e), Some(h)) if (e.t - h.t).abs() <= 1e-9 * newton.scale() => {}
                (None, None) => {}
                (Some(_), _) => failed += 1,
                (None, Some(h)) => panic!("false hit {h:?} on {ray:?}"),
            }
        }
        println!(
            "depth {depth:2}: {failed:3} of {} grazing rays missed",
            rays.len()
        );
        failures.push(failed);
    }
    // Assert the trend as measured: never worse by more than a couple of rays
    // from one depth to the next, and much better at the deepest than at
    // the shallowest.
    for w in failures.windows(2) {
        assert!(w[1] <= w[0] + 2, "{failures:?}");
    }
    assert!(failures[0] > 0, "depth 0 should struggle: {failures:?}");
    assert!(
        failures[failures.len() - 1] * 4 <= failures[0],
        "{failures:?}"
    );
}

// ---------------------------------------------------------------------------
// Edge rules

#[test]
fn secondary_rays_do_not_hit_their_own_surface() {
    let cylinder = line((1.0, 0.0), (1.0, 2.0));
    let newton = NewtonIntersector::new(&cylinder, 8);
    let ray = Ray::new(Point3::new(-5.0, 1.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
    let first = newton.intersect(&ray, 0.0, f64::INFINITY).unwrap();
    assert!((first.t - 4.0).abs() < 1e-12);
    // Continue from the hit point: the far wall, not the same point.
    let next = Ray::new(first.point, ray.dir);
    let second = newton
        .intersect(&next, 0.0, f64::INFINITY)
        .expect("far wall");
    assert!((second.t - 2.0).abs() < 1e-12, "{second:?}");
    // Leaving outward: nothing more.
    let out = Ray::new(first.point, -ray.dir);
    assert_eq!(newton.intersect(&out, 0.0, f64::INFINITY), None);
}

#[test]
fn bad_rays_and_ranges_are_misses() {
    let vase = vase();
    let newton = NewtonIntersector::new(&vase, 4);
    let o = Point3::new(-4.0, 1.0, 0.2);
    let d = Vector3::new(1.0, 0.0, 0.0);
    for ray in [
        Ray::new(Point3::new(f64::NAN, 1.0, 0.0), d),
        Ray::new(o, Vector3::zeros()),
        Ray::new(o, Vector3::new(f64::INFINITY, 0.0, 0.0)),
        Ray::new(Point3::new(f64::INFINITY, 1.0, 0.0), d),
    ] {
        assert_eq!(newton.intersect(&ray, 0.0, f64::INFINITY), None, "{ray:?}");
        let (hit, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
        assert_eq!(hit, None);
        assert_eq!(report.leaves_tried, 0);
    }
    let ray = Ray::new(o, d);
    assert_eq!(newton.intersect(&ray, f64::NAN, f64::INFINITY), None);
    assert_eq!(newton.intersect(&ray, 0.0, f64::NAN), None);
    assert_eq!(newton.intersect(&ray, 5.0, 1.0), None);
    assert!(
        newton
            .intersect(&ray, f64::NEG_INFINITY, f64::INFINITY)
            .is_some()
    );
}

#[test]
fn cone_apex_hit_faces_the_ray() {
    // Along the axis onto the apex of a cone: no tangent plane there, so the
    // normal faces the ray (as the exact solver's).
    let cone = line((1.0, 0.0), (0.0, 1.0));
    let newton = NewtonIntersector::new(&cone, 6);
    let ray = Ray::new(Point3::new(0.0, 3.0, 0.0), Vector3::new(0.0, -2.0, 0.0));
    let hit = newton.intersect(&ray, 0.0, f64::INFINITY).expect("apex");
    assert_sane(&hit);
    assert!((hit.t - 1.0).abs() < 1e-9, "{hit:?}");
    assert!(hit.normal.dot(&ray.dir) < 0.0);
}

#[test]
fn owned_and_borrowed_intersectors_agree_and_depth_is_clamped() {
    let glass = uniform_cubic(&GLASS);
    let borrowed = NewtonIntersector::new(&glass, 6);
    let owned = NewtonIntersector::new(uniform_cubic(&GLASS), 6);
    assert_eq!(borrowed.bounds(), owned.bounds());
    assert_eq!(owned.surface().profile().points().len(), 25);
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let ray = random_ray(&mut rng, &owned.bounds());
        assert_eq!(
            borrowed.intersect(&ray, 0.0, f64::INFINITY),
            owned.intersect(&ray, 0.0, f64::INFINITY)
        );
    }
    let cylinder = line((1.0, 0.0), (1.0, 2.0));
    let deep = NewtonIntersector::new(&cylinder, 1000);
    assert_eq!(deep.depth(), MAX_DEPTH);
    assert_eq!(deep.leaves().len(), 1 << MAX_DEPTH);
    let flat = NewtonIntersector::new(&cylinder, 0);
    assert_eq!(flat.leaves().len(), 1);
    assert_eq!(flat.leaves()[0].u, (0.0, 1.0));
}

//! The independent patch reference (`common::patch_reference`: interval
//! subdivision of the power form, Newton's method on explicit Bernstein
//! sums) checked against closed forms, then the library's certified
//! intersector checked against the reference on random bicubic and rational
//! bicubic patches, folded ones included: every hit along each ray, in
//! count and order, by walking secondary rays from each hit.

use revolve_testkit as common;

use common::Rng;
use common::patch_reference::{
    RefHits, RefPatch, Tally, bezier_hits, check_patch_hit, compare, folded_net, hits_on,
    nurbs_hits, random_ray,
};
use common::tensor_shapes::{
    cylinder_roots, quadratic_roots, quarter_cylinder, sphere_octant, sphere_roots,
};
use revolve::nalgebra::Point3;
use revolve::{BezierPatches, BezierSurface, Intersect, NurbsSurface, Ray};

/// Compares the reference's roots in `(0, ∞)` with closed-form roots `want`
/// (`t` ascending): same count, `t` within `1e-10·size/|d|`.
fn assert_reference_roots(got: &RefHits, want: &[f64], ray: &Ray, size: f64, what: &str) {
    let got = got.within(0.0, f64::INFINITY);
    assert_eq!(
        got.len(),
        want.len(),
        "{what}: reference {got:?}, closed form {want:?} for {ray:?}"
    );
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g.t - w).abs() * ray.dir.norm() <= 1e-10 * size,
            "{what}: reference t {} vs {w} for {ray:?}",
            g.t
        );
        assert!((ray.at(g.t) - g.point).norm() <= 1e-10 * size);
    }
}

/// The reference on the NURBS sphere octant finds the roots of the
/// ray–sphere quadratic that lie in the octant (rays within `1e-7` of the
/// octant's edges or of tangency skipped: either answer is right there).
#[test]
fn reference_finds_the_sphere_octant_roots() {
    let mut rng = Rng(0x5F0);
    let (mut checked, mut roots) = (0, 0);
    for r in [1e-3, 1.0, 1e3] {
        let s = sphere_octant(r);
        for _ in 0..300 {
            let ray = random_ray(&mut rng, r, -0.1 * r, 1.1 * r);
            let (all, disc) = sphere_roots(r, &ray.origin, &ray.dir);
            let mut near = disc.abs() < 1e-8;
            let mut want = Vec::new();
            for t in all {
                let p = ray.at(t);
                near |= p.coords.min().abs() < 1e-7 * r;
                if t > 0.0 && p.coords.min() >= 0.0 {
                    want.push(t);
                }
            }
            if near {
                continue;
            }
            let got = nurbs_hits(&s, &ray);
            assert!(!got.doubtful, "doubtful on {ray:?}");
            assert_reference_roots(&got, &want, &ray, r, "sphere octant");
            checked += 1;
            roots += want.len();
        }
    }
    assert!(
        checked > 850 && roots > 300,
        "{checked} rays, {roots} roots"
    );
}

/// The reference on the NURBS quarter cylinder (radius 1, height 2) finds
/// the roots of the ray–cylinder quadratic in the quarter and the height.
#[test]
fn reference_finds_the_quarter_cylinder_roots() {
    let mut rng = Rng(0xC71);
    let s = quarter_cylinder(1.0, 2.0);
    let (mut checked, mut roots) = (0, 0);
    for _ in 0..600 {
        let ray = random_ray(&mut rng, 1.0, -0.1, 2.1);
        let (all, disc) = cylinder_roots(1.0, &ray.origin, &ray.dir);
        let mut near = disc.abs() < 1e-8;
        let mut want = Vec::new();
        for t in all {
            let p = ray.at(t);
            let m = p.x.min(p.y).min(p.z).min(2.0 - p.z);
            near |= m.abs() < 1e-7;
            if t > 0.0 && m >= 0.0 {
                want.push(t);
            }
        }
        if near {
            continue;
        }
        let got = nurbs_hits(&s, &ray);
        assert!(!got.doubtful, "doubtful on {ray:?}");
        assert_reference_roots(&got, &want, &ray, 2.0, "quarter cylinder");
        checked += 1;
        roots += want.len();
    }
    assert!(
        checked > 550 && roots > 200,
        "{checked} rays, {roots} roots"
    );
}

/// The reference on the hyperbolic paraboloid `z = xy` over `[0, 1]²` (the
/// bilinear patch of corners `(0,0,0)`, `(1,0,0)`, `(0,1,0)`, `(1,1,1)`):
/// along the ray, `o_z + t·d_z = (o_x + t·d_x)(o_y + t·d_y)`, a quadratic.
#[test]
fn reference_finds_the_hyperbolic_paraboloid_roots() {
    let mut rng = Rng(0x4A7);
    let net = vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
        vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    ];
    let patch = RefPatch::polynomial(net);
    let (mut checked, mut two) = (0, 0);
    for _ in 0..3000 {
        let ray = random_ray(&mut rng, 1.0, -0.1, 1.1);
        let (o, d) = (ray.origin, ray.dir);
        let (all, disc) = quadratic_roots(d.x * d.y, o.x * d.y + o.y * d.x - d.z, o.x * o.y - o.z);
        let mut near = disc.abs() < 1e-8;
        let mut want = Vec::new();
        for t in all {
            let p = ray.at(t);
            let m = p.x.min(p.y).min(1.0 - p.x).min(1.0 - p.y);
            near |= m.abs() < 1e-7;
            if t > 0.0 && m >= 0.0 {
                want.push(t);
            }
        }
        if near {
            continue;
        }
        let got = hits_on(std::slice::from_ref(&patch), &ray);
        assert!(!got.doubtful, "doubtful on {ray:?}");
        assert_reference_roots(&got, &want, &ray, 1.0, "z = xy");
        checked += 1;
        two += usize::from(want.len() == 2);
    }
    assert!(
        checked > 2900 && two > 8,
        "{checked} rays, {two} with two roots"
    );
}

/// Random folded bicubic patches against the reference: rays from afar at
/// points of the patch (sure hits), at random points of its box, and
/// (height fields) nearly horizontal rays that cross the waves several
/// times. At most 2% of the rays are left out as near-tangent or
/// near-edge, and many rays meet their patch two, three and four times.
#[test]
fn folded_bicubics_agree_with_the_reference_hit_by_hit() {
    let mut rng = Rng(0xF01D);
    let mut tally = Tally::default();
    for n in 0..180 {
        let kind = n % 3;
        let net = folded_net(&mut rng, kind);
        let s = BezierSurface::new(net.clone()).unwrap();
        let reference = RefPatch::polynomial(net);
        let size = reference.size();
        for k in 0..14 {
            let ray = match (kind, k % 3) {
                (1, 2) => {
                    let a = rng.range(0.0, std::f64::consts::TAU);
                    let origin = Point3::new(4.0 * a.cos(), 4.0 * a.sin(), rng.range(-0.5, 0.5));
                    let target = rng.point([-0.8, -0.8, -0.5], [0.8, 0.8, 0.5]);
                    Ray::new(origin, target - origin)
                }
                (_, 0) => {
                    let origin = Point3::from(rng.direction() * 4.0);
                    let (x, _, _) = reference.jet(rng.unit(), rng.unit());
                    Ray::new(origin, (Point3::from(x) - origin) * rng.range(0.3, 3.0))
                }
                _ => random_ray(&mut rng, 1.0, -1.2, 1.2),
            };
            let want = bezier_hits(&s, &ray);
            compare(&s, &want, &ray, size, &mut tally);
        }
    }
    let Tally {
        rays,
        excluded,
        by_count,
    } = tally;
    eprintln!("{rays} rays, {excluded} excluded, by hit count {by_count:?}");
    assert!(excluded * 50 < rays, "{excluded} of {rays} rays excluded");
    assert!(
        by_count[1] > 600 && by_count[2] > 200 && by_count[3] > 50 && by_count[4] > 10,
        "hit counts {by_count:?}"
    );
}

/// Random rational bicubic patches (weights in `[0.3, 3]`) on folded nets
/// against the reference, through `NurbsSurface` (one Bézier piece).
#[test]
fn rational_bicubics_agree_with_the_reference_hit_by_hit() {
    let mut rng = Rng(0x7A71);
    let mut tally = Tally::default();
    let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    for n in 0..90 {
        let net = folded_net(&mut rng, n % 3);
        let weights: Vec<Vec<f64>> = (0..4)
            .map(|_| (0..4).map(|_| rng.range(0.3, 3.0)).collect())
            .collect();
        let s = NurbsSurface::new((3, 3), (k.clone(), k.clone()), net.clone(), weights).unwrap();
        let size = RefPatch::polynomial(net).size();
        for _ in 0..10 {
            let ray = random_ray(&mut rng, 1.0, -1.2, 1.2);
            let want = nurbs_hits(&s, &ray);
            compare(&s, &want, &ray, size, &mut tally);
        }
    }
    let Tally {
        rays,
        excluded,
        by_count,
    } = tally;
    eprintln!("{rays} rays, {excluded} excluded, by hit count {by_count:?}");
    assert!(excluded * 50 < rays, "{excluded} of {rays} rays excluded");
    assert!(
        by_count[1] > 200 && by_count[2] > 20 && by_count[3] > 3,
        "hit counts {by_count:?}"
    );
}

/// The reference's interval arithmetic encloses the exact results (exact
/// rationals from `num-rational`) of sums, differences and products of
/// random doubles of all magnitudes and signs, and of chains of them.
#[test]
fn reference_intervals_enclose_exact_results() {
    use common::patch_reference::Interval;
    use num_rational::BigRational;
    let exact = |x: f64| BigRational::from_float(x).expect("finite");
    let inside = |i: Interval, x: &BigRational| exact(i.lo) <= *x && *x <= exact(i.hi);
    let mut rng = Rng(0x1A7);
    let draw = |rng: &mut Rng| {
        let m = rng.range(-1.0, 1.0);
        m * 10f64.powi(rng.below(40) as i32 - 20)
    };
    for _ in 0..2000 {
        let (a, b, c) = (draw(&mut rng), draw(&mut rng), draw(&mut rng));
        let (ia, ib, ic) = (Interval::point(a), Interval::point(b), Interval::point(c));
        let (ea, eb, ec) = (exact(a), exact(b), exact(c));
        assert!(inside(ia.add(ib), &(&ea + &eb)), "{a} + {b}");
        assert!(inside(ia.sub(ib), &(&ea - &eb)), "{a} − {b}");
        assert!(inside(ia.mul(ib), &(&ea * &eb)), "{a} · {b}");
        let chain = ia.mul(ib).add(ic).mul(ia.sub(ic));
        assert!(
            inside(chain, &((&ea * &eb + &ec) * (&ea - &ec))),
            "chain {a} {b} {c}"
        );
        let wide = Interval::new(a, b).mul(Interval::new(c, a));
        for x in [&ea, &eb] {
            for y in [&ec, &ea] {
                assert!(inside(wide, &(x * y)), "[{a}, {b}]·[{c}, {a}]");
            }
        }
        // Exact results are widened by at most one step each way.
        let one = Interval::point(1.0).add(Interval::ZERO);
        assert!(one.lo < 1.0 && one.hi > 1.0 && one.hi - one.lo <= 2.0 * f64::EPSILON);
    }
}

/// Newell's teapot (32 bicubic patches, collapsed edges at the lid's apex
/// and the bottom) through `BezierPatches`: along random rays from around
/// it, every hit walked (`t_min` = the previous hit) is the reference's
/// next root over all patches (`t` to `1e-9` of the teapot's size, the
/// point on the ray and on the reported patch at its `uv`); rays the
/// reference flags (near tangency, a patch edge, a doubtful box) are left
/// out, at most 2%.
#[test]
fn teapot_agrees_with_the_reference_hit_by_hit() {
    let patches = common::teapot::patches();
    let model = BezierPatches::new(patches.clone()).unwrap();
    let reference: Vec<RefPatch> = patches
        .iter()
        .map(|p| RefPatch::polynomial(p.points().to_vec()))
        .collect();
    let b = model.bounds();
    let size = b.scale();
    let centre = b.center();
    let mut rng = Rng(0x7EA);
    let (mut rays, mut excluded, mut hits) = (0, 0, 0);
    for _ in 0..300 {
        let origin = centre + rng.direction() * 2.0 * size;
        let target = rng.point_in(&b);
        let ray = Ray::new(origin, target - origin);
        let dn = ray.dir.norm();
        rays += 1;
        let want = hits_on(&reference, &ray);
        if !want.clear(0.0, f64::INFINITY, 1e-4, 1e-7 * size / dn) {
            excluded += 1;
            continue;
        }
        let want = want.within(0.0, f64::INFINITY);
        let mut from = 0.0;
        for (n, w) in want.iter().enumerate() {
            let (k, h) = model
                .intersect_patch(&ray, from, f64::INFINITY)
                .unwrap_or_else(|| panic!("hit {n} at t = {} missed: {ray:?}", w.t));
            check_patch_hit(&patches[k], &ray, &h, from, f64::INFINITY);
            assert!(
                (h.t - w.t).abs() * dn <= 1e-9 * size,
                "hit {n}: t {} vs reference {} for {ray:?}",
                h.t,
                w.t
            );
            from = h.t;
            hits += 1;
        }
        let extra = model.intersect_patch(&ray, from, f64::INFINITY);
        assert!(
            extra.is_none(),
            "a hit beyond the reference's: {extra:?} for {ray:?}"
        );
    }
    eprintln!("{rays} rays, {excluded} excluded, {hits} hits");
    assert!(excluded * 50 < rays, "{excluded} of {rays} excluded");
    assert!(hits > 300, "{hits} hits");
}

/// The reference flags what it cannot settle, so that comparisons leave
/// those rays out: a ray straight down through the sphere octant's pole
/// (a collapsed edge: the roots fill the row `u = 0`) and a ray exactly
/// tangent to the sphere are not `clear`; both still report the root (the
/// pole at `t = 1`, the touch point at `t = 3` to `1e-7`).
#[test]
fn reference_flags_collapsed_edges_and_tangency() {
    let s = sphere_octant(1.0);
    let down = Ray::new(Point3::new(0.0, 0.0, 2.0), -revolve::nalgebra::Vector3::z());
    let pole = nurbs_hits(&s, &down);
    assert!(!pole.clear(0.0, f64::INFINITY, 1e-4, 1e-7), "{pole:?}");
    assert!(
        pole.hits.iter().any(|h| (h.t - 1.0).abs() <= 1e-9),
        "{pole:?}"
    );
    let touch = revolve::nalgebra::Vector3::new(1.0, 2.0, 2.0) / 3.0;
    let dir = revolve::nalgebra::Vector3::new(2.0, -1.0, 0.0).normalize();
    let tangent = Ray::new(Point3::from(touch - 3.0 * dir), dir);
    let graze = nurbs_hits(&s, &tangent);
    assert!(!graze.clear(0.0, f64::INFINITY, 1e-4, 1e-7), "{graze:?}");
    assert!(
        graze.hits.iter().any(|h| (h.t - 3.0).abs() <= 1e-7),
        "{graze:?}"
    );
}

/// Grazing but transversal rays on folded bicubics: through a random point
/// `P` of the patch at incidence `|d̂·n̂| = c` for `c` from `1e-2` down to
/// `3e-4` (above the reference's tangency cut of `1e-4`), every hit walked
/// agrees with the reference.
#[test]
fn grazing_rays_on_folded_bicubics_agree_with_the_reference() {
    let mut rng = Rng(0x6A7E);
    let mut tally = Tally::default();
    for n in 0..40 {
        let net = folded_net(&mut rng, n % 3);
        let s = BezierSurface::new(net.clone()).unwrap();
        let reference = RefPatch::polynomial(net);
        let size = reference.size();
        for c in [1e-2, 3e-3, 1e-3, 3e-4] {
            let (p, su, sv) = reference.jet(rng.range(0.05, 0.95), rng.range(0.05, 0.95));
            let normal = su.cross(&sv).normalize();
            let along = normal.cross(&rng.direction()).normalize();
            let d = normal * c + along * (1.0 - c * c).sqrt();
            let ray = Ray::new(Point3::from(p - 3.0 * d), d);
            compare(&s, &bezier_hits(&s, &ray), &ray, size, &mut tally);
        }
    }
    eprintln!("{tally:?}");
    assert!(tally.excluded * 10 < tally.rays, "{tally:?}");
    // Every ray passes through a point of its patch, and the folds give
    // many of them more hits.
    assert_eq!(tally.by_count[0], 0, "{tally:?}");
    assert!(tally.by_count[3] + tally.by_count[4] > 30, "{tally:?}");
}

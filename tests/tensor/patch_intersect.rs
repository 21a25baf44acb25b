//! Ray intersection of tensor-product surfaces against closed forms:
//! bilinear patches (a quadratic), planar bicubic patches (a plane and an
//! affine map), a NURBS sphere octant (the ray–sphere quadratic), secondary
//! rays and misses.

use revolve_testkit as common;

use common::tensor_shapes::sphere_octant;

use common::Rng;
use revolve::nalgebra::{Point3, Vector3};
use revolve::{BSplineSurface, BezierSurface, Intersect, Ray, Surface};

/// The roots in `[0, 1]` of `a + b·x + c·x²` (stable formula; a linear or
/// constant equation when `c` is negligible).
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if c.abs() <= 1e-14 * scale {
        return if b != 0.0 { vec![-a / b] } else { vec![] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut r = vec![q / c];
    if q != 0.0 {
        r.push(a / q);
    }
    r
}

/// The hits `(t, u, v)` of `ray` on the bilinear patch of corners `p`
/// (`p[i][j]` at `(u, v) = (i, j)`), with `t > 0`, nearest first: the ray
/// as two planes gives two bilinear equations `aₖ + bₖu + cₖv + dₖuv = 0`;
/// `v` from the first, a quadratic in `u` from the second.
fn bilinear_hits(p: &[[Point3<f64>; 2]; 2], ray: &Ray) -> Vec<(f64, f64, f64)> {
    let d = ray.dir.normalize();
    let helper = if d.x.abs() < 0.5 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let n1 = d.cross(&helper).normalize();
    let n2 = d.cross(&n1);
    let coef = |n: &Vector3<f64>| {
        let f = |q: &Point3<f64>| n.dot(&(q - ray.origin));
        let (f00, f10, f01, f11) = (f(&p[0][0]), f(&p[1][0]), f(&p[0][1]), f(&p[1][1]));
        (f00, f10 - f00, f01 - f00, f11 - f10 - f01 + f00)
    };
    let (a1, b1, c1, d1) = coef(&n1);
    let (a2, b2, c2, d2) = coef(&n2);
    // v = −(a1 + b1 u)/(c1 + d1 u) into the second:
    // (a2 + b2 u)(c1 + d1 u) − (c2 + d2 u)(a1 + b1 u) = 0.
    let (qa, qb, qc) = (
        a2 * c1 - c2 * a1,
        a2 * d1 + b2 * c1 - c2 * b1 - d2 * a1,
        b2 * d1 - d2 * b1,
    );
    let mut hits = Vec::new();
    for u in quadratic_roots(qa, qb, qc) {
        let den = c1 + d1 * u;
        let v = if den.abs() > 1e-12 {
            -(a1 + b1 * u) / den
        } else {
            -(a2 + b2 * u) / (c2 + d2 * u)
        };
        if !(-1e-12..=1.0 + 1e-12).contains(&u) || !(-1e-12..=1.0 + 1e-12).contains(&v) {
            continue;
        }
        let s = p[0][0].coords * (1.0 - u) * (1.0 - v)
            + p[1][0].coords * u * (1.0 - v)
            + p[0][1].coords * (1.0 - u) * v
            + p[1][1].coords * u * v;
        let t = (s - ray.origin.coords).dot(&ray.dir) / ray.dir.norm_squared();
        if t > 0.0 {
            hits.push((t, u, v));
        }
    }
    hits.sort_by(|a, b| a.0.total_cmp(&b.0));
    hits
}

fn random_point(rng: &mut Rng, s: f64) -> Point3<f64> {
    Point3::new(rng.range(-s, s), rng.range(-s, s), rng.range(-s, s))
}

/// Random bilinear patches (twisted, so rays can cross twice) and rays
/// aimed at random points of them and at random points nearby: the nearest
/// hit agrees with the quadratic's (t, point, parameters), the second hit
/// is found as a secondary ray, and misses agree, except for rays within
/// 1e-7 of the patch's edges or of tangency, where either answer is right.
#[test]
fn bilinear_patches_hit_where_the_quadratic_says() {
    let mut rng = Rng(0xB111);
    let (mut hits, mut misses, mut seconds) = (0, 0, 0);
    for _ in 0..300 {
        let p = [
            [random_point(&mut rng, 1.0), random_point(&mut rng, 1.0)],
            [random_point(&mut rng, 1.0), random_point(&mut rng, 1.0)],
        ];
        let net = vec![vec![p[0][0], p[0][1]], vec![p[1][0], p[1][1]]];
        let surface = BezierSurface::new(net).unwrap();
        for _ in 0..40 {
            let origin = Point3::from(rng.direction() * 5.0);
            let target = if rng.below(2) == 0 {
                let (u, v) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                surface.eval(u, v)
            } else {
                random_point(&mut rng, 1.2)
            };
            let ray = Ray::new(origin, (target - origin) * rng.range(0.5, 2.0));
            let want = bilinear_hits(&p, &ray);
            let near_edge = want
                .iter()
                .any(|&(_, u, v)| u.min(v) < 1e-7 || u.max(v) > 1.0 - 1e-7);
            let got = surface.intersect(&ray, 0.0, f64::INFINITY);
            let dn = ray.dir.norm();
            match (got, want.first()) {
                (Some(h), Some(&(t, u, v))) => {
                    hits += 1;
                    assert!((h.t - t).abs() * dn <= 1e-9, "t {} vs {t}", h.t);
                    assert!((h.point - ray.at(t)).norm() <= 1e-9);
                    assert!((h.uv.0 - u).abs() <= 1e-6 && (h.uv.1 - v).abs() <= 1e-6);
                    // Near tangency (the two roots close, |n·d̂| small) the
                    // first hit's t is uncertain beyond the self-hit margin.
                    let transversal = h.normal.dot(&ray.dir.normalize()).abs() > 1e-3;
                    if let Some(&(t2, _, _)) = want.get(1) {
                        if (t2 - t) * dn > 1e-6 && transversal {
                            let second = surface.intersect(&ray, h.t, f64::INFINITY);
                            if let Some(s) = second {
                                seconds += 1;
                                assert!((s.t - t2).abs() * dn <= 1e-9, "second {} vs {t2}", s.t);
                            } else {
                                assert!(near_edge, "second hit at {t2} missed: {ray:?}");
                            }
                        }
                    }
                }
                (None, None) => misses += 1,
                (got, want) => {
                    assert!(
                        near_edge
                            || want.is_none()
                                && got.is_some_and(|h| {
                                    // A hit the reference dropped at an edge.
                                    let (u, v) = h.uv;
                                    u.min(v) < 1e-7 || u.max(v) > 1.0 - 1e-7
                                }),
                        "got {got:?}, want {want:?} for {ray:?} on {p:?}"
                    );
                }
            }
        }
    }
    assert!(
        hits > 4000 && misses > 1000 && seconds > 50,
        "{hits} hits, {misses} misses, {seconds} second hits"
    );
}

/// A bicubic patch whose control net is an affine image of the unit grid
/// is that affine map (linear precision): hits are the ray–plane hits whose
/// preimage lies in the unit square.
#[test]
fn planar_bicubic_patches_are_their_affine_map() {
    let mut rng = Rng(0x91A);
    let mut hits = 0;
    for _ in 0..100 {
        let o = random_point(&mut rng, 1.0);
        let (a, b) = (
            random_point(&mut rng, 1.0).coords,
            random_point(&mut rng, 1.0).coords,
        );
        let net: Vec<Vec<Point3<f64>>> = (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| o + a * (i as f64 / 3.0) + b * (j as f64 / 3.0))
                    .collect()
            })
            .collect();
        let surface = BezierSurface::new(net).unwrap();
        let n = a.cross(&b);
        for _ in 0..40 {
            let origin = Point3::from(rng.direction() * 4.0);
            let (u, v) = (rng.range(-0.2, 1.2), rng.range(-0.2, 1.2));
            let target = o + a * u + b * v;
            let ray = Ray::new(origin, target - origin);
            let got = surface.intersect(&ray, 0.0, f64::INFINITY);
            let inside = (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v);
            let edge = u.min(v).abs() < 1e-7 || (u.max(v) - 1.0).abs() < 1e-7;
            let steep = n.normalize().dot(&ray.dir.normalize()).abs() > 1e-3;
            if edge || !steep {
                continue;
            }
            match got {
                Some(h) => {
                    assert!(inside, "hit outside at ({u}, {v})");
                    hits += 1;
                    assert!((h.t - 1.0).abs() <= 1e-9, "t {}", h.t);
                    assert!((h.uv.0 - u).abs() <= 1e-8 && (h.uv.1 - v).abs() <= 1e-8);
                }
                None => assert!(!inside, "missed ({u}, {v}) for {ray:?}"),
            }
        }
    }
    assert!(hits > 1500, "{hits} hits");
}

/// The NURBS sphere octant against the ray–sphere quadratic: the nearest
/// root in the octant (both roots checked), at three scales; normals are
/// radial; the pole (a collapsed edge) is hit.
#[test]
fn nurbs_sphere_octant_hits_where_the_quadratic_says() {
    let mut rng = Rng(0x0C7A);
    let mut hits = 0;
    for r in [1e-3, 1.0, 1e3] {
        let s = sphere_octant(r);
        for _ in 0..2000 {
            let origin = Point3::from(rng.direction() * 4.0 * r);
            let target = Point3::new(
                rng.range(-0.1, 1.1),
                rng.range(-0.1, 1.1),
                rng.range(-0.1, 1.1),
            ) * r;
            let ray = Ray::new(origin, target - origin);
            let (o, d) = (origin.coords, ray.dir);
            let (a, b, c) = (d.norm_squared(), o.dot(&d), o.norm_squared() - r * r);
            let disc = b * b - a * c;
            let mut want = None;
            let mut near = false;
            if disc > 0.0 {
                let q = -(b + b.signum() * disc.sqrt());
                let mut roots = [q / a, c / q];
                roots.sort_by(f64::total_cmp);
                for t in roots {
                    let p = ray.at(t);
                    let m = p.coords.min();
                    near |= m.abs() < 1e-7 * r;
                    if t > 0.0 && m >= 0.0 && want.is_none() {
                        want = Some(t);
                    }
                }
                near |= disc < 1e-8 * a * r * r;
            }
            if near {
                continue;
            }
            let got = s.intersect(&ray, 0.0, f64::INFINITY);
            match (got, want) {
                (Some(h), Some(t)) => {
                    hits += 1;
                    assert!((h.t - t).abs() * d.norm() <= 1e-9 * r, "t {} vs {t}", h.t);
                    let radial = h.point.coords / r;
                    assert!((h.normal.dot(&radial).abs() - 1.0).abs() <= 1e-8);
                }
                (None, None) => {}
                (g, w) => panic!("got {g:?}, want {w:?} for {ray:?} at r = {r}"),
            }
        }
    }
    assert!(hits > 2000, "{hits} hits");
    // Straight down onto the pole.
    let s = sphere_octant(1.0);
    let down = Ray::new(Point3::new(0.0, 0.0, 3.0), Vector3::new(0.0, 0.0, -1.0));
    let hit = s.intersect(&down, 0.0, f64::INFINITY).expect("the pole");
    assert!((hit.t - 2.0).abs() <= 1e-12);
    assert!((hit.normal.z.abs() - 1.0).abs() <= 1e-9);
}

/// A B-spline surface of several patches (a wavy sheet z = f(x, y)): every
/// vertical ray over its domain hits once, where the surface's own
/// evaluation at the hit's parameters says, and rays beside it miss.
#[test]
fn vertical_rays_hit_a_wavy_bspline_sheet_once() {
    let n = 7;
    let knots: Vec<f64> = [0.0, 0.0, 0.0, 0.0]
        .into_iter()
        .chain((1..n - 3).map(|k| k as f64 / (n - 3) as f64))
        .chain([1.0; 4])
        .collect();
    let net: Vec<Vec<Point3<f64>>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let (x, y) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
                    Point3::new(x, y, 0.3 * ((5.0 * x).sin() * (4.0 * y).cos()))
                })
                .collect()
        })
        .collect();
    let s = BSplineSurface::new((3, 3), (knots.clone(), knots), net).unwrap();
    let mut rng = Rng(0x5EE7);
    for _ in 0..2000 {
        let (x, y) = (rng.range(0.01, 0.99), rng.range(0.01, 0.99));
        let ray = Ray::new(Point3::new(x, y, 2.0), Vector3::new(0.0, 0.0, -1.0));
        let hit = s
            .intersect(&ray, 0.0, f64::INFINITY)
            .expect("over the sheet");
        assert!((hit.point.x - x).abs() <= 1e-9 && (hit.point.y - y).abs() <= 1e-9);
        assert!((s.eval(hit.uv.0, hit.uv.1) - hit.point).norm() <= 1e-12);
        assert!(
            s.intersect(&ray, hit.t, f64::INFINITY).is_none(),
            "a second hit"
        );
        let beside = Ray::new(Point3::new(x + 1.5, y, 2.0), Vector3::new(0.0, 0.0, -1.0));
        assert!(s.intersect(&beside, 0.0, f64::INFINITY).is_none());
    }
    let b = s.bounds();
    assert!(b.contains(&Point3::new(0.5, 0.5, 0.0)));
}

/// A planar patch of degrees (40, 1) (its net an affine image of a uniform
/// grid, so the surface is that affine map): the long direction's
/// subdivision runs beyond the stack kernel's 32 coefficients.
#[test]
fn high_degree_planar_patch_is_its_affine_map() {
    let rows = 41;
    let net: Vec<Vec<Point3<f64>>> = (0..rows)
        .map(|i| {
            let x = i as f64 / (rows - 1) as f64;
            vec![Point3::new(x, 0.0, 0.5 * x), Point3::new(x, 1.0, 0.5 * x)]
        })
        .collect();
    let s = BezierSurface::new(net).unwrap();
    let mut rng = Rng(0x41);
    for _ in 0..300 {
        let (u, v) = (rng.range(0.01, 0.99), rng.range(0.01, 0.99));
        let target = Point3::new(u, v, 0.5 * u);
        let origin = target + Vector3::new(-0.3, 0.2, 2.0);
        let ray = Ray::new(origin, target - origin);
        let hit = s.intersect(&ray, 0.0, f64::INFINITY).expect("on the patch");
        assert!((hit.t - 1.0).abs() <= 1e-9, "t {}", hit.t);
        assert!((hit.uv.0 - u).abs() <= 1e-8 && (hit.uv.1 - v).abs() <= 1e-8);
    }
}

/// A looser tolerance keeps every hit (the search is certified at any
/// tolerance) and places it within that tolerance of the full-precision
/// hit; it is clamped into the valid range and kept by the surface.
#[test]
fn a_looser_tolerance_keeps_every_hit_within_it() {
    use revolve::Tolerance;
    let exact = common::tensor_shapes::folded_bicubic();
    let size = exact.bounds().scale();
    for relative in [1e-10, 1e-6, 1e-4] {
        let loose = exact.clone().with_tolerance(Tolerance::relative(relative));
        assert_eq!(loose.tolerance().relative, relative);
        let mut rng = Rng(5);
        let (mut both, mut compared) = (0, 0);
        for _ in 0..3000 {
            let b = exact.bounds();
            let dir: Vector3<f64> = rng.direction();
            let ray = Ray::new(rng.point_in(&b) - dir * 4.0, dir);
            let (a, l) = (
                exact.intersect(&ray, 0.0, f64::INFINITY),
                loose.intersect(&ray, 0.0, f64::INFINITY),
            );
            compared += 1;
            match (a, l) {
                (Some(a), Some(l)) => {
                    both += 1;
                    // Where two roots lie within the tolerance along the
                    // ray either may be the nearest; both are on the ray.
                    assert!((l.point - ray.at(l.t)).norm() <= 2.0 * relative * size);
                    assert!(
                        (l.t - a.t).abs() * ray.dir.norm() <= 1e3 * relative * size,
                        "{relative}: {} vs {}",
                        l.t,
                        a.t
                    );
                }
                (Some(a), None) => panic!("{relative}: the loose search lost {a:?} on {ray:?}"),
                // A ray passing within the tolerance counts as touching.
                (None, Some(l)) => {
                    let on = exact.eval(l.uv.0, l.uv.1);
                    assert!((on - ray.at(l.t)).norm() <= 2.0 * relative * size);
                }
                (None, None) => {}
            }
        }
        assert!(both > 1000, "{both} of {compared}");
    }
    let clamped = exact.with_tolerance(Tolerance::relative(1.0));
    assert_eq!(clamped.tolerance().relative, 1e-3);
}

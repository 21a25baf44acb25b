//! Surfaces of revolution of users' own profile types: curves that give only
//! points and derivatives (no Bézier spans) are intersected through their
//! approximation, refined on the curve; curves that break the `Curve`
//! contract give an empty surface and a named error, never a panic.
//!
//! References are closed forms (the ray–sphere quadratic) and, for the
//! torus, a root search on its implicit equation along the ray (sampling
//! and bisection), independent of the intersector.

use revolve_testkit as common;

use common::Rng;
use revolve::nalgebra::{Point2, Point3, Vector2, Vector3};
use revolve::{Aabb, BezierSpan, Curve, Error, Intersect, Ray, Revolution, Surface};
use std::f64::consts::{PI, TAU};

/// A circle of radius `r` about `(cx, cy)` from angle `a` to `b`, written
/// with cosine and sine: no Bézier spans.
struct Arc {
    cx: f64,
    cy: f64,
    r: f64,
    a: f64,
    b: f64,
}

impl Curve<2> for Arc {
    fn domain(&self) -> (f64, f64) {
        (self.a, self.b)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(self.cx + self.r * t.cos(), self.cy + self.r * t.sin())
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        Vector2::new(-self.r * t.sin(), self.r * t.cos())
    }
}

/// The sphere of radius `r` about the origin: the half circle from the
/// south pole to the north pole turned about the y axis.
fn sphere(r: f64) -> Revolution<Arc> {
    Revolution::try_new(Arc {
        cx: 0.0,
        cy: 0.0,
        r,
        a: -PI / 2.0,
        b: PI / 2.0,
    })
    .expect("a valid profile")
}

/// The torus of tube radius `r` about the circle of radius `big` in the
/// plane y = 0.
fn torus(big: f64, r: f64) -> Revolution<Arc> {
    Revolution::try_new(Arc {
        cx: big,
        cy: 0.0,
        r,
        a: 0.0,
        b: TAU,
    })
    .expect("a valid profile")
}

/// The nearer root of `|o + t d|² = r²`, if any.
fn sphere_entry(ray: &Ray, r: f64) -> Option<f64> {
    let (o, d) = (ray.origin.coords, ray.dir);
    let a = d.dot(&d);
    let b = o.dot(&d);
    let c = o.dot(&o) - r * r;
    let disc = b * b - a * c;
    (disc >= 0.0).then(|| {
        let q = -(b + b.signum() * disc.sqrt());
        let (t0, t1) = (q / a, c / q);
        t0.min(t1)
    })
}

/// A point uniform in the ball of radius `r` about the origin.
fn in_ball(rng: &mut Rng, r: f64) -> Point3<f64> {
    loop {
        let p = rng.point([-r; 3], [r; 3]);
        if p.coords.norm() <= r {
            return p;
        }
    }
}

/// The case: a half circle written with cos/sin is the unit sphere.
/// Rays aimed at points inside 95% of the radius hit where the quadratic
/// says (to 1e-9 of the size) with the sphere's normal; rays whose line
/// passes 5% outside miss. At three sizes.
#[test]
fn own_curve_sphere_hits_where_the_quadratic_says() {
    let mut rng = Rng(0x5EED_0001);
    for size in [1e-3, 1.0, 1e4] {
        let s = sphere(size);
        assert!(!s.has_exact_intersector());
        let dev = s.approximation_deviation().expect("approximated");
        assert!(dev <= 1e-7 * size, "deviation {dev:e}");
        let b = s.bounds();
        assert!(
            b.contains(&Point3::new(size, 0.0, 0.0)) && b.contains(&Point3::new(0.0, -size, 0.0))
        );
        assert!(b.max.x <= size * (1.0 + 1e-6), "bounds {b:?}");
        for _ in 0..2000 {
            let origin = Point3::from(rng.direction() * 5.0 * size);
            let target = in_ball(&mut rng, 0.95 * size);
            let ray = Ray::new(origin, (target - origin) * rng.range(0.1, 10.0));
            let want = sphere_entry(&ray, size).expect("aimed inside");
            let hit = s.intersect(&ray, 0.0, f64::INFINITY).expect("a clear hit");
            let dn = ray.dir.norm();
            assert!(
                (hit.t - want).abs() * dn <= 1e-9 * size,
                "t {} vs {want} at size {size}",
                hit.t
            );
            assert!((hit.point - ray.at(want)).norm() <= 1e-9 * size);
            let radial = hit.point.coords / size;
            assert!(
                (hit.normal.dot(&radial).abs() - 1.0).abs() <= 1e-8,
                "normal {:?} at {:?}",
                hit.normal,
                hit.point
            );
            assert!((s.eval(hit.uv.0, hit.uv.1) - hit.point).norm() <= 1e-9 * size);
            // A line passing 1.05 radii from the centre.
            let dir = rng.direction();
            let side = dir.cross(&rng.direction()).normalize();
            let ray = Ray::new(Point3::from(side * 1.05 * size - dir * 4.0 * size), dir);
            assert!(s.intersect(&ray, 0.0, f64::INFINITY).is_none(), "false hit");
        }
    }
}

/// The torus implicit function `(ρ − R)² + y² − r²` along the ray.
fn torus_value(ray: &Ray, t: f64, big: f64, r: f64) -> f64 {
    let p = ray.at(t);
    let rho = p.x.hypot(p.z);
    (rho - big).powi(2) + p.y * p.y - r * r
}

/// The first sign change of the torus function along the ray in
/// `(0, t_end)`, by dense sampling and bisection.
fn torus_entry(ray: &Ray, big: f64, r: f64, t_end: f64) -> Option<f64> {
    const STEPS: usize = 20_000;
    let f = |t: f64| torus_value(ray, t, big, r);
    let mut prev = (0.0, f(0.0));
    for k in 1..=STEPS {
        let t = t_end * k as f64 / STEPS as f64;
        let v = f(t);
        if (v < 0.0) != (prev.1 < 0.0) {
            let (mut lo, mut hi) = (prev.0, t);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if (f(mid) < 0.0) == (prev.1 < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        prev = (t, v);
    }
    None
}

/// A torus from an own circle (a full turn, cos/sin): rays aimed inside the
/// tube hit at the first crossing the implicit equation shows; rays through
/// the hole, beyond the rim and above the tube (5% clear) miss.
#[test]
fn own_curve_torus_hits_where_the_implicit_equation_says() {
    let (big, r) = (2.0, 0.5);
    let s = torus(big, r);
    let mut rng = Rng(0x5EED_0002);
    for _ in 0..1500 {
        // A point inside 95% of the tube.
        let angle = rng.range(0.0, TAU);
        let off = in_ball(&mut rng, 0.95 * r);
        let target = Point3::new(
            (big + off.x) * angle.cos(),
            off.y,
            -(big + off.x) * angle.sin(),
        );
        let origin = Point3::from(rng.direction() * 8.0);
        let ray = Ray::new(origin, target - origin);
        let want = torus_entry(&ray, big, r, 1.0).expect("the target is inside");
        let hit = s.intersect(&ray, 0.0, f64::INFINITY).expect("a clear hit");
        let dn = ray.dir.norm();
        assert!(
            (hit.t - want).abs() * dn <= 1e-9 * (big + r),
            "t {} vs {want}",
            hit.t
        );
        // The normal is along the tube's radius at the hit.
        let p = hit.point;
        let rho = p.x.hypot(p.z);
        let core = Vector3::new(p.x / rho * big, 0.0, p.z / rho * big);
        let radial = (p.coords - core) / r;
        assert!((hit.normal.dot(&radial).abs() - 1.0).abs() <= 1e-8);
    }
    for _ in 0..1500 {
        let angle = rng.range(0.0, TAU);
        let (ray, what) = match rng.below(3) {
            // Vertical through the hole, 5% clear of the inner equator.
            0 => {
                let rho = rng.range(0.0, 0.95 * (big - r));
                let o = Point3::new(rho * angle.cos(), 3.0, rho * angle.sin());
                (Ray::new(o, Vector3::new(0.0, -1.0, 0.0)), "hole")
            }
            // Vertical beyond the outer equator.
            1 => {
                let rho = rng.range(1.05 * (big + r), 4.0);
                let o = Point3::new(rho * angle.cos(), -3.0, rho * angle.sin());
                (Ray::new(o, Vector3::new(0.0, 1.0, 0.0)), "rim")
            }
            // Horizontal above the tube.
            _ => {
                let y = rng.range(1.05 * r, 2.0) * if rng.unit() < 0.5 { -1.0 } else { 1.0 };
                let d = Vector3::new(angle.cos(), 0.0, angle.sin());
                (Ray::new(Point3::new(0.0, y, 0.0) - d * 5.0, d), "above")
            }
        };
        assert!(
            s.intersect(&ray, 0.0, f64::INFINITY).is_none(),
            "false hit through the {what}: {ray:?}"
        );
    }
}

/// A ray starting on the own-curve sphere (a secondary ray leaving it) does
/// not hit its own start, and finds the far side.
#[test]
fn own_curve_secondary_ray_finds_the_far_side() {
    let s = sphere(1.0);
    let ray = Ray::new(Point3::new(0.0, 0.0, 5.0), Vector3::new(0.0, 0.0, -1.0));
    let first = s.intersect(&ray, 0.0, f64::INFINITY).unwrap();
    assert!((first.t - 4.0).abs() < 1e-12);
    let inside = Ray::new(first.point, ray.dir);
    let far = s.intersect(&inside, 0.0, f64::INFINITY).unwrap();
    assert!((far.t - 2.0).abs() < 1e-12, "far side at {}", far.t);
}

/// Walking a ray through the own-curve sphere as secondary rays do (from
/// each hit's `t`): every line through the inner 95% of the ball gives
/// exactly its two hits, the entry and the exit, never the entry again a
/// rounding step later (the refined hit once passed `t_min` by an ulp).
#[test]
fn own_curve_secondary_rays_do_not_hit_their_start_again() {
    let mut rng = Rng(0x5EED_0002);
    let s = sphere(1.0);
    for _ in 0..4000 {
        let origin = Point3::from(rng.direction() * 3.0);
        let target = in_ball(&mut rng, 0.95);
        let ray = Ray::new(origin, (target - origin) * rng.range(0.5, 2.0));
        let first = s.intersect(&ray, 0.0, f64::INFINITY).expect("aimed inside");
        let second = s
            .intersect(&ray, first.t, f64::INFINITY)
            .expect("the far side");
        let dn = ray.dir.norm();
        assert!(
            (second.t - first.t) * dn > 1e-3,
            "the entry at {} found again at {} for {ray:?}",
            first.t,
            second.t
        );
        assert!(s.intersect(&ray, second.t, f64::INFINITY).is_none());
    }
}

/// A curve whose domain is `(start, end)` and whose values are a vertical
/// segment at x = 1 (NaN where `nan_from` says).
#[derive(Debug)]
struct Segment {
    start: f64,
    end: f64,
    nan_from: f64,
}

impl Curve<2> for Segment {
    fn domain(&self) -> (f64, f64) {
        (self.start, self.end)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let x = if t >= self.nan_from { f64::NAN } else { 1.0 };
        Point2::new(x, t)
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(0.0, 1.0)
    }
}

fn segment(start: f64, end: f64) -> Segment {
    Segment {
        start,
        end,
        nan_from: f64::INFINITY,
    }
}

/// The surface of a broken profile: no panic, no hit, empty bounds, and
/// `try_new` names the problem.
fn assert_empty<C: Curve<2>>(profile: C, check: impl Fn(&Error) -> bool) {
    let s = Revolution::new(profile);
    let err = s.contract_error().cloned().expect("the contract is broken");
    assert!(check(&err), "unexpected error {err:?}");
    assert!(!err.to_string().is_empty());
    assert_eq!(s.bounds(), Aabb::EMPTY);
    let ray = Ray::new(Point3::new(-5.0, 0.5, 0.0), Vector3::new(1.0, 0.0, 0.0));
    assert!(s.intersect(&ray, 0.0, f64::INFINITY).is_none());
}

#[test]
fn reversed_domain_is_an_error() {
    assert_empty(segment(1.0, 0.0), |e| {
        matches!(e, Error::InvalidDomain { .. })
    });
    let err = Revolution::try_new(segment(1.0, 0.0)).unwrap_err();
    assert_eq!(
        err,
        Error::InvalidDomain {
            start: 1.0,
            end: 0.0
        }
    );
}

#[test]
fn nan_and_infinite_domains_are_errors() {
    assert_empty(segment(f64::NAN, 1.0), |e| {
        matches!(e, Error::InvalidDomain { .. })
    });
    assert_empty(segment(0.0, f64::INFINITY), |e| {
        matches!(e, Error::InvalidDomain { .. })
    });
    assert_empty(segment(f64::NEG_INFINITY, f64::INFINITY), |e| {
        matches!(e, Error::InvalidDomain { .. })
    });
    assert_empty(segment(0.0, 0.0), |e| {
        matches!(e, Error::InvalidDomain { .. })
    });
}

#[test]
fn nan_values_inside_the_domain_are_errors() {
    let profile = Segment {
        start: 0.0,
        end: 1.0,
        nan_from: 0.61,
    };
    assert_empty(
        profile,
        |e| matches!(e, Error::CurveNotFinite { t } if *t >= 0.61),
    );
}

/// A profile that claims Bézier spans, with the spans it returns.
struct Spans {
    spans: Vec<BezierSpan<2>>,
}

impl Curve<2> for Spans {
    fn domain(&self) -> (f64, f64) {
        (0.0, 2.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(1.0, t.clamp(0.0, 2.0))
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(0.0, 1.0)
    }
    fn bezier_spans(&self) -> Option<Vec<BezierSpan<2>>> {
        Some(self.spans.clone())
    }
}

fn span(a: f64, b: f64, points: &[(f64, f64)]) -> BezierSpan<2> {
    BezierSpan {
        knots: (a, b),
        curve: revolve::Bezier::new(points.iter().map(|&(x, y)| Point2::new(x, y)).collect())
            .unwrap(),
    }
}

#[test]
fn empty_spans_are_an_error() {
    assert_empty(Spans { spans: vec![] }, |e| {
        matches!(e, Error::SpansOutOfOrder { index: 0 })
    });
}

#[test]
fn spans_out_of_order_are_an_error() {
    let spans = vec![
        span(1.0, 2.0, &[(1.0, 1.0), (1.0, 2.0)]),
        span(0.0, 1.0, &[(1.0, 0.0), (1.0, 1.0)]),
    ];
    assert_empty(Spans { spans }, |e| {
        matches!(e, Error::SpansOutOfOrder { index: 1 })
    });
    let spans = vec![span(1.0, 1.0, &[(1.0, 1.0), (1.0, 2.0)])];
    assert_empty(Spans { spans }, |e| {
        matches!(e, Error::SpansOutOfOrder { index: 0 })
    });
    // An infinite start would make NaN parameters.
    let spans = vec![span(f64::NEG_INFINITY, 1.0, &[(1.0, 1.0), (1.0, 2.0)])];
    assert_empty(Spans { spans }, |e| {
        matches!(e, Error::SpansOutOfOrder { index: 0 })
    });
}

/// Spans of different degrees are raised to the highest: the exact
/// intersector, and the cylinder's closed-form hit.
#[test]
fn spans_of_mixed_degree_get_the_exact_intersector() {
    let spans = vec![
        span(0.0, 1.0, &[(1.0, 0.0), (1.0, 1.0)]),
        span(1.0, 2.0, &[(1.0, 1.0), (1.0, 1.5), (1.0, 1.75), (1.0, 2.0)]),
    ];
    let s = Revolution::try_new(Spans { spans }).unwrap();
    assert!(s.has_exact_intersector());
    for y in [0.25, 1.0, 1.6] {
        let ray = Ray::new(Point3::new(-5.0, y, 0.0), Vector3::new(1.0, 0.0, 0.0));
        let hit = s.intersect(&ray, 0.0, f64::INFINITY).expect("hit");
        assert!((hit.t - 4.0).abs() < 1e-12, "t {}", hit.t);
    }
}

/// A curve that jumps cannot be followed by cubic pieces: refused, not
/// a hang or a surface with a hole.
#[test]
fn a_profile_with_a_jump_is_too_rough() {
    struct Jump;
    impl Curve<2> for Jump {
        fn domain(&self) -> (f64, f64) {
            (0.0, 1.0)
        }
        fn eval(&self, t: f64) -> Point2<f64> {
            Point2::new(if t < 0.37 { 1.0 } else { 2.0 }, t)
        }
        fn derivative(&self, _: f64) -> Vector2<f64> {
            Vector2::new(0.0, 1.0)
        }
    }
    assert_empty(Jump, |e| matches!(e, Error::ProfileTooRough { .. }));
}

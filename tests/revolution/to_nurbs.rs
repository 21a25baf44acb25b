//! `NurbsSurface::from_revolution` against the revolution it converts, as
//! the independent reference (the revolution evaluates
//! `(x cos θ, y, −x sin θ)` in closed form and intersects by eliminating
//! the angle; the NURBS surface by tensor de Casteljau and Bézier clipping):
//! on a sphere (a NURBS half circle), a torus (a NURBS circle), the vase (a
//! cubic Bézier) and the wine glass (a uniform cubic B-spline of many
//! spans), each placed off the origin along a tilted axis, some reversed or
//! moved by a rigid motion.
//!
//! - points at many `(u, θ)` (span breaks and quarter turns included) agree
//!   to `1e-14·size` at `v = revolution_v(θ)`;
//! - normals agree (to `1e-9`) wherever the revolution has one off the axis;
//! - on 10⁴ random rays through the bounds per shape, the same hits and
//!   misses, `t` within `1e-9·size/|d|`, except rays that either reports
//!   within `1e-6` of tangency (`|d̂·n| < 1e-6`, the angle from the hit
//!   normal);
//! - the angle conversion round-trips; every error path gives its variant.

use revolve_testkit as common;

use common::conic_profiles::{sphere_profile, torus_profile};
use common::newton_rays::{Xorshift64, random_ray};
use common::{vase, wine_glass};
use revolve::nalgebra::{Isometry3, Point2, Point3, Unit, Vector2, Vector3};
use revolve::{
    Bezier, Curve, Error, Intersect, NurbsSurface, RationalBezier, RationalBezierSpan, Revolution,
    Surface,
};
use std::f64::consts::{FRAC_PI_2, TAU};

/// The revolution's point and normal at `(u, θ)`.
type PointAndNormal = dyn Fn(f64, f64) -> (Point3<f64>, Option<Unit<Vector3<f64>>>);
/// The revolution's nearest hit.
type FirstHit = dyn Fn(&revolve::Ray) -> Option<revolve::Hit>;

/// The four shapes, placed, as boxed surfaces with their NURBS forms.
struct Case {
    name: &'static str,
    revolution: Box<PointAndNormal>,
    intersect: Box<FirstHit>,
    domain: (f64, f64),
    breaks: Vec<f64>,
    nurbs: NurbsSurface,
    bounds: revolve::Aabb,
    /// The profile's radius coordinate `x(u)`.
    radius: Box<dyn Fn(f64) -> f64>,
}

impl Case {
    /// Whether the profile point at `u` lies on the axis.
    fn on_axis(&self, u: f64) -> bool {
        (self.radius)(u) == 0.0
    }
}

fn case<C: Curve<2> + Clone + 'static>(name: &'static str, r: Revolution<C>) -> Case {
    let nurbs = NurbsSurface::from_revolution(&r).unwrap();
    let domain = r.profile().domain();
    let breaks = r
        .profile()
        .rational_bezier_spans()
        .unwrap()
        .iter()
        .map(|s| s.knots.0)
        .collect();
    let bounds = r.bounds();
    let (a, b, p) = (r.clone(), r.clone(), r);
    Case {
        radius: Box::new(move |u| p.profile().eval(u).x),
        name,
        revolution: Box::new(move |u, t| (a.eval(u, t), a.normal(u, t))),
        intersect: Box::new(move |ray| b.intersect(ray, 0.0, f64::INFINITY)),
        domain,
        breaks,
        nurbs,
        bounds,
    }
}

fn axis(x: f64, y: f64, z: f64) -> Unit<Vector3<f64>> {
    Unit::new_normalize(Vector3::new(x, y, z))
}

fn cases() -> Vec<Case> {
    let motion = Isometry3::new(Vector3::new(0.5, -1.0, 2.0), Vector3::new(0.4, -0.3, 1.1));
    vec![
        case(
            "sphere",
            Revolution::new(sphere_profile(1.5))
                .with_axis(Point3::new(1.0, 2.0, -1.0), axis(0.3, 1.0, 0.2)),
        ),
        case(
            "torus",
            Revolution::new(torus_profile(2.0, 0.5))
                .with_axis(Point3::new(-1.0, 0.5, 0.0), axis(1.0, 0.2, -0.4))
                .reversed(),
        ),
        case(
            "vase",
            Revolution::new(vase()).with_axis(Point3::new(0.0, 0.0, 3.0), axis(0.0, 0.0, 1.0)),
        ),
        case("glass", Revolution::new(wine_glass()).transformed(&motion)),
    ]
}

/// The largest coordinate of the box: the size the tolerances scale with.
fn size(b: &revolve::Aabb) -> f64 {
    b.min
        .coords
        .amax()
        .max(b.max.coords.amax())
        .max(b.extent().amax())
}

#[test]
fn the_same_points_and_normals() {
    for c in cases() {
        let size = size(&c.bounds);
        let (a, b) = c.domain;
        let mut us: Vec<f64> = (0..=60).map(|k| a + (b - a) * k as f64 / 60.0).collect();
        us.extend(&c.breaks);
        let mut thetas: Vec<f64> = (0..=48).map(|k| TAU * k as f64 / 48.0 + 0.013).collect();
        thetas.extend([0.0, FRAC_PI_2, 3.0 * FRAC_PI_2, TAU]);
        let mut normals = 0;
        for &u in &us {
            for &theta in &thetas {
                let v = NurbsSurface::revolution_v(theta);
                let (p, n) = (c.revolution)(u, theta);
                let q = c.nurbs.eval(u, v);
                assert!(
                    (p - q).norm() <= 1e-14 * size,
                    "{}: u {u} θ {theta}: {} off",
                    c.name,
                    (p - q).norm()
                );
                let m = c.nurbs.normal(u, v);
                // On the axis both normals are exact limits (the glass's
                // profile starts and ends on tripled control points, where
                // the tensor surface's limit comes from the first row of
                // control points leaving the pole).
                let within = if c.on_axis(u) { 1e-13 } else { 1e-9 };
                match (n, m) {
                    (Some(n), Some(m)) => {
                        assert!(
                            (n.into_inner() - m.into_inner()).norm() < within,
                            "{}: normal at u {u} θ {theta}: {n:?} vs {m:?}",
                            c.name
                        );
                        normals += 1;
                    }
                    (Some(n), None) => {
                        panic!("{}: no NURBS normal at u {u} θ {theta}, want {n:?}", c.name)
                    }
                    _ => {}
                }
            }
        }
        assert!(normals > us.len() * thetas.len() / 2, "{}", c.name);
    }
}

#[test]
fn the_same_hits_on_random_rays() {
    for c in cases() {
        let size = size(&c.bounds);
        let mut rng = Xorshift64::new(0x5eed + c.name.len() as u64);
        let (mut hits, mut skipped, mut compared) = (0, 0, 0);
        for _ in 0..10_000 {
            let ray = random_ray(&mut rng, &c.bounds);
            let dir = ray.dir.normalize();
            let grazing = |h: &Option<revolve::Hit>| {
                h.as_ref()
                    .is_some_and(|h| dir.dot(&h.normal.into_inner()).abs() < 1e-6)
            };
            let want = (c.intersect)(&ray);
            let got = c.nurbs.intersect(&ray, 0.0, f64::INFINITY);
            if grazing(&want) || grazing(&got) {
                skipped += 1;
                continue;
            }
            compared += 1;
            match (&want, &got) {
                (None, None) => {}
                (Some(w), Some(g)) => {
                    hits += 1;
                    let tol = 1e-9 * size / ray.dir.norm();
                    assert!(
                        (w.t - g.t).abs() <= tol,
                        "{}: t {} vs {} on {ray:?}",
                        c.name,
                        w.t,
                        g.t
                    );
                    assert!((w.point - g.point).norm() <= 1e-9 * size);
                    assert!(
                        (w.normal.into_inner() - g.normal.into_inner()).norm() < 1e-6,
                        "{}: normals {:?} vs {:?}",
                        c.name,
                        w.normal,
                        g.normal
                    );
                }
                _ => panic!("{}: revolution {want:?}, NURBS {got:?} on {ray:?}", c.name),
            }
        }
        assert!(hits > 3_000, "{}: only {hits} hits", c.name);
        assert!(skipped < 100, "{}: {skipped} skipped", c.name);
        assert!(compared + skipped == 10_000);
    }
}

#[test]
fn the_angle_conversion_round_trips() {
    for k in 0..=400 {
        let theta = TAU * k as f64 / 400.0;
        let v = NurbsSurface::revolution_v(theta);
        assert!((0.0..=TAU).contains(&v));
        assert!(
            (NurbsSurface::revolution_angle(v) - theta).abs() < 1e-14,
            "{theta}"
        );
        if k % 100 == 0 {
            assert_eq!(v, theta);
        }
    }
    // Monotone, and periodic outside [0, 2π].
    let mut last = -1.0;
    for k in 0..=1000 {
        let v = NurbsSurface::revolution_v(TAU * k as f64 / 1000.0);
        assert!(v >= last);
        last = v;
    }
    let v = NurbsSurface::revolution_v(0.3);
    assert!((NurbsSurface::revolution_v(0.3 + TAU) - v).abs() < 1e-14);
    assert!((NurbsSurface::revolution_v(0.3 - TAU) - v).abs() < 1e-14);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(NurbsSurface::revolution_v(bad), 0.0);
    }
    assert_eq!(NurbsSurface::revolution_angle(-1.0), 0.0);
    assert_eq!(NurbsSurface::revolution_angle(10.0), TAU);
}

#[test]
fn placement_and_motions_map_the_control_points() {
    let r = Revolution::new(vase());
    let motion = Isometry3::new(Vector3::new(3.0, 0.0, -1.0), Vector3::new(-0.2, 0.9, 0.4));
    let moved = NurbsSurface::from_revolution(&r.transformed(&motion)).unwrap();
    let local = NurbsSurface::from_revolution(&r).unwrap();
    for (row_a, row_b) in moved.points().iter().zip(local.points()) {
        for (a, b) in row_a.iter().zip(row_b) {
            assert!((a - motion * b).norm() < 1e-14);
        }
    }
    assert_eq!(moved.weights(), local.weights());
    // The surfaces agree at every parameter, and a reversed revolution
    // gives the reversed surface.
    let rev = NurbsSurface::from_revolution(&r.reversed()).unwrap();
    assert_eq!(rev, local.reversed());
}

/// A profile without Bézier spans: a quarter circle by its formula.
#[derive(Clone)]
struct Formula;

impl Curve<2> for Formula {
    fn domain(&self) -> (f64, f64) {
        (0.0, FRAC_PI_2)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let t = if t.is_nan() {
            0.0
        } else {
            t.clamp(0.0, FRAC_PI_2)
        };
        Point2::new(t.cos() + 1.0, t.sin())
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        let t = if t.is_nan() {
            0.0
        } else {
            t.clamp(0.0, FRAC_PI_2)
        };
        Vector2::new(-t.sin(), t.cos())
    }
}

/// Two line spans with a gap in their parameters between them.
#[derive(Clone)]
struct Gapped;

impl Curve<2> for Gapped {
    fn domain(&self) -> (f64, f64) {
        (0.0, 3.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 3.0) };
        Point2::new(1.0, t.min(1.0) + (t - 2.0).max(0.0))
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        let inside = !(1.0..2.0).contains(&t);
        Vector2::new(0.0, if inside { 1.0 } else { 0.0 })
    }
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<2>>> {
        let line = |a: f64, b: f64| {
            RationalBezier::new(
                vec![Point2::new(1.0, a), Point2::new(1.0, b)],
                vec![1.0, 1.0],
            )
            .unwrap()
        };
        Some(vec![
            RationalBezierSpan {
                knots: (0.0, 1.0),
                curve: line(0.0, 1.0),
            },
            RationalBezierSpan {
                knots: (2.0, 3.0),
                curve: line(1.0, 2.0),
            },
        ])
    }
}

/// Two spans out of order (the second starts before the first ends).
#[derive(Clone)]
struct Overlapping;

impl Curve<2> for Overlapping {
    fn domain(&self) -> (f64, f64) {
        (0.0, 2.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(1.0, if t.is_nan() { 0.0 } else { t.clamp(0.0, 2.0) })
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(0.0, 1.0)
    }
    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<2>>> {
        let line = RationalBezier::new(
            vec![Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)],
            vec![1.0, 1.0],
        )
        .unwrap();
        Some(vec![
            RationalBezierSpan {
                knots: (0.0, 1.5),
                curve: line.clone(),
            },
            RationalBezierSpan {
                knots: (1.0, 2.0),
                curve: line,
            },
        ])
    }
}

#[test]
fn errors_name_the_problem() {
    let r = Revolution::new(Formula);
    assert!(r.contract_error().is_none());
    assert_eq!(
        NurbsSurface::from_revolution(&r),
        Err(Error::NotPiecewiseRational)
    );
    let gap = Revolution::new(Gapped);
    assert!(gap.contract_error().is_none());
    assert_eq!(
        NurbsSurface::from_revolution(&gap),
        Err(Error::SpanGap {
            index: 1,
            previous_end: 1.0,
            start: 2.0
        })
    );
    let overlap = Revolution::new(Overlapping);
    assert_eq!(
        NurbsSurface::from_revolution(&overlap),
        Err(Error::SpansOutOfOrder { index: 1 })
    );
    let line = Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0)]).unwrap();
    let badly_placed = Revolution::new(line.clone()).with_axis(
        Point3::new(f64::NAN, 0.0, 0.0),
        Unit::new_normalize(Vector3::y()),
    );
    assert!(matches!(
        NurbsSurface::from_revolution(&badly_placed),
        Err(Error::InvalidPlacement { .. })
    ));
    // A motion that cannot be applied breaks the revolution the same way.
    let far = Revolution::new(line).transformed(&Isometry3::translation(1e101, 0.0, 0.0));
    assert!(matches!(
        far.contract_error(),
        Some(Error::InvalidPlacement { .. })
    ));
    assert!(matches!(
        NurbsSurface::from_revolution(&far),
        Err(Error::InvalidPlacement { .. })
    ));
}

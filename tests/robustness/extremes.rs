//! Extreme inputs to the exact revolution intersector: object sizes across
//! the supported coordinate range, ray directions of any length, far
//! origins, odd `t` ranges and odd tolerances. Each case states the
//! closed-form answer (a cylinder or a cone) it must give, or that it must
//! miss; none may hang, panic or return NaN.

use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::{Bezier, Error, Intersect, MAX_COORDINATE, Ray, Revolution, Surface, Tolerance};

/// The open cylinder of radius `s` from height 0 to `2s`.
fn cylinder(s: f64) -> Revolution<Bezier<2>> {
    Revolution::new(Bezier::new(vec![Point2::new(s, 0.0), Point2::new(s, 2.0 * s)]).unwrap())
}

/// The ray from `(−10s, s, 0)` along `+x` with direction length `len`: it
/// enters the cylinder at `x = −s`, `t = 9s / len`.
fn side_ray(s: f64, len: f64) -> Ray {
    Ray::new(Point3::new(-10.0 * s, s, 0.0), Vector3::new(len, 0.0, 0.0))
}

fn assert_rel(got: f64, want: f64, rel: f64, what: &str) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: got {got:e}, want {want:e}"
    );
}

/// Objects from 1e-100 to the largest accepted coordinate, 1e100 (the
/// cylinder's height is twice its radius): the hit
/// is where the closed form puts it, to 1e-14 relative, with the
/// cylinder's normal.
#[test]
fn object_sizes_across_the_supported_range() {
    let mut size = 1e-100;
    while 2.0 * size <= MAX_COORDINATE {
        let s = cylinder(size);
        let hit = s
            .intersect(&side_ray(size, 1.0), 0.0, f64::INFINITY)
            .unwrap_or_else(|| panic!("missed at size {size:e}"));
        assert_rel(hit.t, 9.0 * size, 1e-14, "t");
        assert_rel(hit.point.x, -size, 1e-14, "x");
        assert!((hit.normal.x.abs() - 1.0).abs() < 1e-14);
        size *= 1e10;
    }
    // The largest accepted coordinate itself.
    let s = cylinder(MAX_COORDINATE / 2.0);
    let hit = s
        .intersect(&side_ray(MAX_COORDINATE / 2.0, 1.0), 0.0, f64::INFINITY)
        .expect("hit at the largest accepted size");
    assert_rel(hit.t, 4.5 * MAX_COORDINATE, 1e-14, "t");
}

/// Direction lengths from 1e-300 to 1e300: `t` is in units of `|dir|`.
#[test]
fn direction_lengths_across_the_range() {
    let s = cylinder(1.0);
    for e in (-300..=300).step_by(25) {
        let len = 10f64.powi(e);
        let hit = s
            .intersect(&side_ray(1.0, len), 0.0, f64::INFINITY)
            .unwrap_or_else(|| panic!("missed with |dir| = {len:e}"));
        assert_rel(hit.t, 9.0 / len, 1e-14, "t");
        assert_rel(hit.point.x, -1.0, 1e-14, "x");
    }
    // Even on an object at the largest scale.
    let s = cylinder(4e99);
    let hit = s
        .intersect(&side_ray(4e99, 1e-200), 0.0, f64::INFINITY)
        .unwrap();
    assert_rel(hit.t, 3.6e300, 1e-14, "t");
}

/// Origins far from the object, up to 1e300: the hit is found, with `t`
/// as accurate as the origin's rounding allows.
#[test]
fn far_origins_find_the_hit() {
    let s = cylinder(1.0);
    for far in [1e3, 1e8, 1e20, 1e100, 1e200, 1e300] {
        let ray = Ray::new(Point3::new(-far, 1.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
        let hit = s
            .intersect(&ray, 0.0, f64::INFINITY)
            .unwrap_or_else(|| panic!("missed from {far:e}"));
        assert_rel(hit.t, far - 1.0, 4.0 * f64::EPSILON, "t");
        assert!((hit.point.x + 1.0).abs() < 1e-12, "point {:?}", hit.point);
        // A line passing just outside misses.
        let ray = Ray::new(Point3::new(-far, 1.0, 1.01), Vector3::new(1.0, 0.0, 0.0));
        assert!(s.intersect(&ray, 0.0, f64::INFINITY).is_none());
    }
    // An origin near the largest float: a miss or a finite hit, quickly.
    let ray = Ray::new(
        Point3::new(-f64::MAX, 1.0, 0.0),
        Vector3::new(1.0, 0.0, 0.0),
    );
    if let Some(hit) = s.intersect(&ray, 0.0, f64::INFINITY) {
        assert!(hit.t.is_finite() && hit.point.x.is_finite());
    }
}

/// NaN or empty `t` ranges are misses and return at once (they used to
/// loop forever); infinite ends are fine.
#[test]
fn odd_t_ranges() {
    let s = cylinder(1.0);
    let ray = side_ray(1.0, 1.0);
    for (lo, hi) in [
        (f64::NAN, f64::INFINITY),
        (0.0, f64::NAN),
        (f64::NAN, f64::NAN),
        (5.0, 5.0),
        (6.0, 5.0),
        (f64::INFINITY, f64::INFINITY),
    ] {
        assert!(s.intersect(&ray, lo, hi).is_none(), "({lo}, {hi})");
    }
    let hit = s.intersect(&ray, f64::NEG_INFINITY, f64::INFINITY).unwrap();
    assert_rel(hit.t, 9.0, 1e-15, "t");
    // The range excludes the entry: the exit at t = 11.
    let hit = s.intersect(&ray, 9.5, 100.0).unwrap();
    assert_rel(hit.t, 11.0, 1e-15, "t");
}

/// Zero, NaN and infinite directions and origins are misses.
#[test]
fn degenerate_rays_miss() {
    let s = cylinder(1.0);
    let o = Point3::new(-10.0, 1.0, 0.0);
    for d in [
        Vector3::zeros(),
        Vector3::new(f64::NAN, 0.0, 0.0),
        Vector3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        assert!(s.intersect(&Ray::new(o, d), 0.0, f64::INFINITY).is_none());
    }
    let d = Vector3::new(1.0, 0.0, 0.0);
    for o in [
        Point3::new(f64::NAN, 1.0, 0.0),
        Point3::new(f64::NEG_INFINITY, 1.0, 0.0),
    ] {
        assert!(s.intersect(&Ray::new(o, d), 0.0, f64::INFINITY).is_none());
    }
}

/// `Tolerance::new` names every bad setting.
#[test]
fn tolerance_new_rejects_bad_settings() {
    let invalid = |r: f64| matches!(Tolerance::new(r, 32), Err(Error::InvalidTolerance { .. }));
    assert!(invalid(f64::NAN) && invalid(f64::INFINITY) && invalid(-1e-9) && invalid(0.0));
    assert!(matches!(
        Tolerance::new(1e-17, 32),
        Err(Error::ToleranceTooSmall { .. })
    ));
    assert!(matches!(
        Tolerance::new(10.0, 32),
        Err(Error::ToleranceTooLarge { max, .. }) if max == Tolerance::MAX_RELATIVE
    ));
    assert!(matches!(
        Tolerance::new(1e-9, 0),
        Err(Error::InvalidIterations { .. })
    ));
    assert!(matches!(
        Tolerance::new(1e-9, 1_000_000),
        Err(Error::InvalidIterations { .. })
    ));
    let ok = Tolerance::new(1e-9, 16).unwrap();
    assert_eq!(ok, ok.clamped());
    assert_eq!(Tolerance::default(), Tolerance::default().clamped());
}

/// Unchecked tolerances (the fields are public) are clamped where they are
/// used: an infinite one used to hang the intersector, 10.0 lost a clear
/// hit, NaN and negative ones were taken as they came. Every setting finds
/// the cylinder's hit within its own accuracy.
#[test]
fn odd_tolerances_still_find_the_hit() {
    for (relative, max_iterations) in [
        (f64::INFINITY, 32),
        (f64::NAN, 32),
        (-1.0, 32),
        (0.0, 32),
        (10.0, 32),
        (1e300, 0),
        (4.0 * f64::EPSILON, u32::MAX),
    ] {
        let tol = Tolerance {
            relative,
            max_iterations,
        };
        let s = cylinder(1.0).with_tolerance(tol);
        assert_eq!(*s.tolerance(), tol.clamped());
        let hit = s
            .intersect(&side_ray(1.0, 1.0), 0.0, f64::INFINITY)
            .unwrap_or_else(|| panic!("missed with {tol:?}"));
        let accuracy = tol.clamped().relative.max(1e-12) * 2.0;
        assert!(
            (hit.t - 9.0).abs() <= accuracy * 10.0,
            "t {} with {tol:?}",
            hit.t
        );
    }
}

/// A NaN or infinite angle evaluates at θ = 0 instead of returning NaN.
#[test]
fn nan_angle_evaluates_at_zero() {
    let s = cylinder(1.0);
    for theta in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(s.eval(0.5, theta), s.eval(0.5, 0.0));
        assert_eq!(s.partials(0.5, theta), s.partials(0.5, 0.0));
        assert_eq!(s.normal(0.5, theta), s.normal(0.5, 0.0));
    }
}

/// A cone's apex hit along the axis at the smallest and largest sizes:
/// the closed-form point, and no NaN in the normal.
#[test]
fn cone_apex_at_extreme_sizes() {
    for size in [1e-90, 1.0, 1e90] {
        let cone = Revolution::new(
            Bezier::new(vec![Point2::new(size, 0.0), Point2::new(0.0, size)]).unwrap(),
        );
        let ray = Ray::new(
            Point3::new(0.0, 3.0 * size, 0.0),
            Vector3::new(0.0, -size, 0.0),
        );
        let hit = cone.intersect(&ray, 0.0, f64::INFINITY).expect("apex");
        assert_rel(hit.t, 2.0, 1e-12, "t");
        assert!(hit.normal.iter().all(|c| c.is_finite()));
    }
}

/// A placement through a NaN or infinite origin, or along a NaN or zero
/// axis, is not applied: `try_with_axis` names it, `with_axis` leaves the
/// surface in place and empty to rays, and evaluation stays finite.
#[test]
fn bad_placements_are_errors() {
    use revolve::nalgebra::Unit;
    let good_axis = Vector3::y_axis();
    let cases = [
        (Point3::new(0.0, f64::NAN, 0.0), good_axis),
        (Point3::new(f64::NEG_INFINITY, 0.0, 0.0), good_axis),
        (Point3::new(0.0, 0.0, 1e101), good_axis),
        (
            Point3::origin(),
            Unit::new_unchecked(Vector3::new(f64::NAN, 0.0, 0.0)),
        ),
        (Point3::origin(), Unit::new_unchecked(Vector3::zeros())),
    ];
    for (origin, axis) in cases {
        let err = cylinder(1.0).try_with_axis(origin, axis).unwrap_err();
        assert!(matches!(err, Error::InvalidPlacement { .. }), "{err:?}");
        let s = cylinder(1.0).with_axis(origin, axis);
        // (NaN ≠ NaN: compare the messages.)
        assert_eq!(
            s.contract_error().map(|e| e.to_string()),
            Some(err.to_string())
        );
        assert!(
            s.intersect(&side_ray(1.0, 1.0), 0.0, f64::INFINITY)
                .is_none()
        );
        assert!(s.bounds().is_empty());
        assert_eq!(s.eval(0.5, 1.0), cylinder(1.0).eval(0.5, 1.0));
    }
    // A unit made unchecked but of another length is renormalized.
    let s = cylinder(1.0)
        .try_with_axis(
            Point3::origin(),
            Unit::new_unchecked(Vector3::new(0.0, 3.0, 0.0)),
        )
        .unwrap();
    let hit = s
        .intersect(&side_ray(1.0, 1.0), 0.0, f64::INFINITY)
        .unwrap();
    assert_rel(hit.t, 9.0, 1e-15, "t");
}

/// An axis within 1e-154 of `−y` (its cross product with `y` has subnormal
/// squares): the placement is still a rotation, so normals and mesh normals
/// are unit vectors and points keep their distance from the axis.
#[test]
fn axes_within_a_subnormal_angle_of_the_y_axis_give_a_rotation() {
    use revolve::nalgebra::Unit;
    let profile = Bezier::new(vec![
        Point2::new(0.0, -1.0),
        Point2::new(2.0, -1.0),
        Point2::new(2.0, 1.0),
        Point2::new(0.0, 1.0),
    ])
    .unwrap();
    for axis in [
        Vector3::new(2.3e-158, -1.0, 8.8e-191),
        Vector3::new(-1e-200, 1.0, 3e-170),
        Vector3::new(1e-160, -1.0, -1e-160),
    ] {
        let origin = Point3::new(-7.8, 2.4, 2.7);
        let s = Revolution::new(profile.clone()).with_axis(origin, Unit::new_normalize(axis));
        for k in 0..20 {
            let (u, v) = (k as f64 / 19.0, 0.3 * k as f64);
            if let Some(n) = s.normal(u, v) {
                assert!(
                    (n.norm() - 1.0).abs() <= 4.0 * f64::EPSILON,
                    "{axis:?}: |n| = {}",
                    n.norm()
                );
            }
            let local = s.eval(u, v) - origin;
            let radial = (local - Vector3::y() * local.dot(&Vector3::y())).norm();
            let x = revolve::Curve::eval(&profile, u).x;
            assert!(
                (radial - x).abs() <= 1e-14 * 4.0,
                "{axis:?}: radius {radial} vs {x}"
            );
        }
        let mesh = s.tessellate(0.5).unwrap();
        assert!(
            mesh.normals
                .iter()
                .all(|n| (n.norm() - 1.0).abs() <= 4.0 * f64::EPSILON)
        );
    }
}

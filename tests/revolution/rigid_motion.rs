//! `Revolution::transformed` (rigid motions): the moved surface against the
//! motion applied to the original's points, partials, normals and hits
//! (the motion is the independent reference), the serde round trip of a
//! moved revolution, and the motions that cannot be applied.

use revolve_testkit as common;

use common::conic_profiles::torus_profile;
use common::newton_rays::{Xorshift64, random_ray};
use common::vase;
use revolve::nalgebra::{Isometry3, Point3, Unit, Vector3};
use revolve::{Error, Intersect, Revolution, Surface};

fn motions() -> Vec<Isometry3<f64>> {
    vec![
        Isometry3::new(Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.3, 0.5, -0.2)),
        Isometry3::new(Vector3::new(-4.0, 0.0, 7.0), Vector3::new(0.0, 2.5, 0.0)),
        Isometry3::new(Vector3::zeros(), Vector3::new(3.0, 0.0, 0.0)),
    ]
}

#[test]
fn motions_commute_with_evaluation_and_intersection() {
    let placed = Revolution::new(torus_profile(2.0, 0.5)).with_axis(
        Point3::new(0.0, 1.0, 0.0),
        Unit::new_normalize(Vector3::new(1.0, 1.0, 0.0)),
    );
    for r in [
        placed.clone(),
        placed.reversed(),
        Revolution::new(torus_profile(1.0, 0.3)),
    ] {
        for m in motions() {
            let t = r.transformed(&m);
            assert!(t.contract_error().is_none());
            assert!(
                (t.to_world().translation.vector - (m * r.to_world()).translation.vector).norm()
                    < 1e-14
            );
            for k in 0..=20 {
                let u = k as f64 / 20.0;
                for j in 0..=16 {
                    let theta = j as f64 * 0.4;
                    assert!((t.eval(u, theta) - m * r.eval(u, theta)).norm() < 1e-13);
                    let (su, sv) = r.partials(u, theta);
                    let (tu, tv) = t.partials(u, theta);
                    assert!((tu - m.rotation * su).norm() < 1e-12);
                    assert!((tv - m.rotation * sv).norm() < 1e-12);
                    let (n, tn) = (r.normal(u, theta).unwrap(), t.normal(u, theta).unwrap());
                    assert!((tn.into_inner() - m.rotation * n.into_inner()).norm() < 1e-13);
                }
            }
            // Rays moved with the surface hit at the same t.
            let mut rng = Xorshift64::new(17);
            for _ in 0..500 {
                let ray = random_ray(&mut rng, &r.bounds());
                let moved = revolve::Ray::new(m * ray.origin, m.rotation * ray.dir);
                let (a, b) = (r.intersect(&ray, 0.0, 1e9), t.intersect(&moved, 0.0, 1e9));
                match (a, b) {
                    (Some(a), Some(b)) => {
                        assert!((a.t - b.t).abs() < 1e-9 * 5.0 / ray.dir.norm());
                        assert!((m * a.point - b.point).norm() < 1e-9 * 5.0);
                    }
                    (None, None) => {}
                    (a, b) => {
                        // Only a grazing ray may differ.
                        let h = a.or(b).unwrap();
                        let graze = ray.dir.normalize().dot(&h.normal.into_inner()).abs();
                        assert!(graze < 1e-6, "{graze}");
                    }
                }
            }
        }
    }
}

#[test]
fn motions_that_cannot_be_applied() {
    let r = Revolution::new(vase());
    let far = Isometry3::translation(2e100, 0.0, 0.0);
    assert!(matches!(
        r.try_transformed(&far),
        Err(Error::InvalidPlacement { .. })
    ));
    let nan = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert!(matches!(
        r.try_transformed(&nan),
        Err(Error::InvalidPlacement { .. })
    ));
    let broken = r.transformed(&nan);
    assert!(matches!(
        broken.contract_error(),
        Some(Error::InvalidPlacement { .. })
    ));
    assert!(
        broken.bounds().is_empty()
            || broken
                .intersect(
                    &revolve::Ray::new(Point3::new(0.0, 0.0, -5.0), Vector3::z()),
                    0.0,
                    1e9
                )
                .is_none()
    );
}

#[cfg(feature = "serde")]
#[test]
fn a_moved_revolution_round_trips_through_serde() {
    let r = Revolution::new(vase());
    for m in motions() {
        let t = r.transformed(&m);
        let json = serde_json::to_string(&t).unwrap();
        let back: Revolution<revolve::Bezier<2>> = serde_json::from_str(&json).unwrap();
        for k in 0..=10 {
            let u = k as f64 / 10.0;
            for j in 0..8 {
                let theta = j as f64 * 0.8;
                assert!(
                    (back.eval(u, theta) - t.eval(u, theta)).norm() < 1e-14,
                    "{json}"
                );
            }
        }
    }
    // Unmoved revolutions write no turn.
    let json = serde_json::to_string(&r).unwrap();
    assert!(!json.contains("turn"));
}

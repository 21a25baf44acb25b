//! The `testing` feature: strategies produce valid objects and the law
//! checkers accept the crate's types and reject broken ones.
#![cfg(feature = "testing")]

use proptest::prelude::*;
use revolve::nalgebra::{Point2, Point3, Vector2, Vector3};
use revolve::testing::{
    bezier_curve, bspline_curve, check_curve_derivatives, check_surface_bounds,
    check_surface_normals, check_surface_partials, profile, ray,
};
use revolve::{Curve, Intersect, Revolution, Surface};

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn crate_curves_obey_the_derivative_law(b in bezier_curve::<3>(0..=9, 5.0), s in bspline_curve::<2>(0..=6, 5.0)) {
        prop_assert!(check_curve_derivatives(&b, 32).is_ok(), "{:?}", check_curve_derivatives(&b, 32));
        prop_assert!(check_curve_derivatives(&s, 32).is_ok(), "{:?}", check_curve_derivatives(&s, 32));
    }

    #[test]
    fn revolutions_obey_the_surface_laws(p in profile(2.0)) {
        let surface = Revolution::new(p);
        prop_assert!(check_surface_partials(&surface, 12).is_ok(), "{:?}", check_surface_partials(&surface, 12));
        prop_assert!(check_surface_normals(&surface, 12).is_ok(), "{:?}", check_surface_normals(&surface, 12));
    }

    #[test]
    fn rays_aim_into_the_cube(r in ray(2.0)) {
        prop_assert!((r.origin.coords.norm() - 6.0).abs() < 1e-12);
        let target = r.at(1.0);
        prop_assert!(target.coords.amax() <= 2.0 + 1e-12);
    }

    #[test]
    fn profiles_are_tubes_with_hits_on_them(p in profile(1.0), r in ray(1.0)) {
        prop_assert!(p.points().windows(2).all(|w| w[1].y > w[0].y && w[0].x > 0.0));
        let surface = Revolution::new(p);
        if let Some(hit) = surface.intersect(&r, 0.0, f64::INFINITY) {
            prop_assert!((surface.eval(hit.uv.0, hit.uv.1) - hit.point).norm() < 1e-9);
        }
    }
}

/// A curve whose derivative is wrong by a factor of two.
struct WrongDerivative;

impl Curve<2> for WrongDerivative {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(t, t * t)
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        Vector2::new(1.0, 4.0 * t)
    }
}

#[test]
fn the_derivative_checker_catches_a_wrong_derivative() {
    let v = check_curve_derivatives(&WrongDerivative, 8).unwrap_err();
    assert_eq!(v.law, "derivative = central difference of eval");
    assert!(v.error > 100.0 * v.limit);
}

/// A plane z = 0 whose normal is tilted and whose ∂S/∂v is wrong.
struct WrongPlane;

impl Surface for WrongPlane {
    fn domain(&self) -> [(f64, f64); 2] {
        [(0.0, 1.0), (0.0, 1.0)]
    }
    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        Point3::new(u, v, 0.0)
    }
    fn partials(&self, _: f64, _: f64) -> (Vector3<f64>, Vector3<f64>) {
        (Vector3::x(), Vector3::new(0.0, 1.0, 0.5))
    }
    fn normal(&self, _: f64, _: f64) -> Option<revolve::nalgebra::Unit<Vector3<f64>>> {
        Some(Vector3::x_axis())
    }
}

#[test]
fn the_surface_checkers_catch_wrong_partials_and_normals() {
    assert_eq!(
        check_surface_partials(&WrongPlane, 4).unwrap_err().law,
        "partials = central differences of eval"
    );
    assert_eq!(
        check_surface_normals(&WrongPlane, 4).unwrap_err().law,
        "normal ⟂ ∂S/∂u"
    );
}

/// A random `rows × cols` net with coordinates in `[−2, 2]`.
fn random_net(state: &mut u64, rows: usize, cols: usize) -> Vec<Vec<Point3<f64>>> {
    let mut next = || {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        4.0 * ((*state >> 11) as f64 / (1u64 << 53) as f64) - 2.0
    };
    (0..rows)
        .map(|_| {
            (0..cols)
                .map(|_| Point3::new(next(), next(), next()))
                .collect()
        })
        .collect()
}

/// The bound checker accepts the crate's surfaces (revolutions, Bézier,
/// B-spline and NURBS patches of several degrees) and catches a box that
/// is too small.
#[test]
fn the_bound_checker_accepts_crate_surfaces_and_catches_a_short_box() {
    use revolve::{Aabb, BSplineSurface, BezierSurface, NurbsSurface, PatchBounds};
    let mut state = 0x0B0D_u64;
    for (rows, cols) in [(2, 2), (4, 4), (3, 5), (6, 2)] {
        let bezier = BezierSurface::new(random_net(&mut state, rows, cols)).unwrap();
        assert!(
            check_surface_bounds(&bezier, 9).is_ok(),
            "{:?}",
            check_surface_bounds(&bezier, 9)
        );
    }
    let knots = (
        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0],
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
    );
    let net = random_net(&mut state, 6, 5);
    let spline = BSplineSurface::new((3, 2), knots.clone(), net.clone()).unwrap();
    assert!(check_surface_bounds(&spline, 12).is_ok());
    let weights = (0..6)
        .map(|i| {
            (0..5)
                .map(|j| 0.1 + ((i * 5 + j) % 7) as f64 * 2.5)
                .collect()
        })
        .collect();
    let nurbs = NurbsSurface::new((3, 2), knots, net, weights).unwrap();
    assert!(
        check_surface_bounds(&nurbs, 12).is_ok(),
        "{:?}",
        check_surface_bounds(&nurbs, 12)
    );
    let vase = Revolution::new(
        revolve::Bezier::new(vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.5, 0.3),
            Point2::new(0.4, 1.2),
            Point2::new(0.8, 2.0),
        ])
        .unwrap(),
    );
    assert!(check_surface_bounds(&vase, 12).is_ok());

    /// A unit square patch whose boxes leave out the top edge.
    struct ShortBox;
    impl Surface for ShortBox {
        fn domain(&self) -> [(f64, f64); 2] {
            [(0.0, 1.0), (0.0, 1.0)]
        }
        fn eval(&self, u: f64, v: f64) -> Point3<f64> {
            Point3::new(u, v, 0.0)
        }
        fn partials(&self, _: f64, _: f64) -> (Vector3<f64>, Vector3<f64>) {
            (Vector3::x(), Vector3::y())
        }
        fn normal(&self, _: f64, _: f64) -> Option<revolve::nalgebra::Unit<Vector3<f64>>> {
            Some(Vector3::z_axis())
        }
    }
    impl PatchBounds for ShortBox {
        fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
            Aabb {
                min: Point3::new(u.0, v.0, 0.0),
                max: Point3::new(u.1, v.1 * 0.999, 0.0),
            }
        }
    }
    let v = check_surface_bounds(&ShortBox, 5).unwrap_err();
    assert_eq!(v.law, "bound_patch contains the sub-patch");
    assert!(v.error > 0.0);
}

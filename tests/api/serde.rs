//! The `serde` feature: round trips give values equal to the originals that
//! evaluate and intersect rays bit for bit alike; bad data is a
//! deserialization error carrying the crate's own error message.
//!
//! JSON (serde_json with `float_roundtrip`, so floats come back bit for bit)
//! is the format of the round trips. JSON cannot carry NaN or infinity, so
//! bad data is fed through [`Tree`], a small in-memory deserializer (a
//! value tree of numbers, sequences and maps) that can; its error's message
//! is exactly what the `Deserialize` impl reported, so the tests compare it
//! with the error the public constructor gives for the same data.

#![cfg(feature = "serde")]

use revolve_testkit as common;

use common::{GLASS, Rng, VASE, points};
use revolve::nalgebra::{Point2, Point3, Unit, Vector3};
use revolve::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierSurface, Curve, Error, Intersect, Nurbs,
    NurbsSurface, RationalBezier, Ray, Revolution, Surface, Tolerance,
};
use serde::de::value::{Error as TreeError, MapDeserializer, SeqDeserializer};
use serde::de::{DeserializeOwned, IntoDeserializer, Visitor};
use serde::{Deserializer, Serialize, forward_to_deserialize_any};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};
use std::fmt::Debug;

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// A value tree that any `Deserialize` impl can read, NaN and infinities
/// included.
#[derive(Clone)]
enum Tree {
    Num(f64),
    Whole(u64),
    Seq(Vec<Tree>),
    Map(Vec<(&'static str, Tree)>),
}

impl<'de> Deserializer<'de> for Tree {
    type Error = TreeError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, TreeError> {
        match self {
            Tree::Num(x) => visitor.visit_f64(x),
            Tree::Whole(n) => visitor.visit_u64(n),
            Tree::Seq(items) => {
                let mut seq = SeqDeserializer::new(items.into_iter());
                let value = visitor.visit_seq(&mut seq)?;
                seq.end()?;
                Ok(value)
            }
            Tree::Map(entries) => {
                let mut map = MapDeserializer::new(entries.into_iter());
                let value = visitor.visit_map(&mut map)?;
                map.end()?;
                Ok(value)
            }
        }
    }

    forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map struct enum identifier ignored_any
    }
}

impl<'de> IntoDeserializer<'de, TreeError> for Tree {
    type Deserializer = Tree;
    fn into_deserializer(self) -> Tree {
        self
    }
}

/// Numbers as a sequence.
fn nums(values: &[f64]) -> Tree {
    Tree::Seq(values.iter().map(|&x| Tree::Num(x)).collect())
}

/// Points `(x, y)` as a sequence of coordinate sequences.
fn pts(p: &[(f64, f64)]) -> Tree {
    Tree::Seq(p.iter().map(|&(x, y)| nums(&[x, y])).collect())
}

/// `T` read from the tree, or the deserialization error's message.
fn read<T: DeserializeOwned>(tree: Tree) -> Result<T, String> {
    T::deserialize(tree).map_err(|e| e.to_string())
}

/// Asserts that reading `tree` as `T` fails with exactly `expected`'s message.
#[track_caller]
fn assert_refused<T: DeserializeOwned + Debug>(tree: Tree, expected: Error) {
    match read::<T>(tree) {
        Ok(v) => panic!("read {v:?}, expected the error '{expected}'"),
        Err(message) => assert_eq!(message, expected.to_string()),
    }
}

/// The value written to JSON and read back.
fn json_round_trip<T: Serialize + DeserializeOwned>(value: &T) -> T {
    let text = serde_json::to_string(value).expect("serializes");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("reads back {text}: {e}"))
}

/// Asserts that `curve` comes back from JSON equal, and evaluates to the
/// same bits (points and first derivatives) across and beyond its domain.
#[track_caller]
fn assert_curve_round_trip<C, const D: usize>(curve: &C)
where
    C: Curve<D> + Serialize + DeserializeOwned + PartialEq + Debug,
{
    let back = json_round_trip(curve);
    assert_eq!(&back, curve);
    let (a, b) = curve.domain();
    for k in -4..=68 {
        let t = a + (b - a) * (k as f64 / 64.0);
        assert_eq!(back.eval(t), curve.eval(t), "point at t = {t}");
        assert_eq!(
            back.derivative(t),
            curve.derivative(t),
            "derivative at t = {t}"
        );
    }
}

/// A quarter of the unit circle from `(1, 0)` to `(0, 1)`: the rational
/// quadratic with middle weight `√2/2`.
fn quarter_circle() -> RationalBezier<2> {
    RationalBezier::new(
        points(&[(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]),
        vec![1.0, FRAC_1_SQRT_2, 1.0],
    )
    .unwrap()
}

/// The right half of the unit circle, from the south pole `(0, −1)` to the
/// north pole `(0, 1)`: a rational cubic (weights `1, 1/3, 1/3, 1`), a
/// sphere when revolved.
fn half_circle() -> RationalBezier<2> {
    let curve = RationalBezier::new(
        points(&[(0.0, -1.0), (2.0, -1.0), (2.0, 1.0), (0.0, 1.0)]),
        vec![1.0, 1.0 / 3.0, 1.0 / 3.0, 1.0],
    )
    .unwrap();
    for k in 0..=16 {
        let p = curve.eval(k as f64 / 16.0);
        assert!((p.coords.norm() - 1.0).abs() < 1e-15 && p.x >= 0.0, "{p}");
    }
    curve
}

// ---------------------------------------------------------------------------
// The written form
// ---------------------------------------------------------------------------

#[test]
fn written_form_is_the_defining_data() {
    let bezier = Bezier::new(points(&[(0.0, 0.5), (1.0, 2.0)])).unwrap();
    assert_eq!(
        serde_json::to_string(&bezier).unwrap(),
        r#"{"points":[[0.0,0.5],[1.0,2.0]]}"#
    );
    let spline = BSpline::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        points(&[(0.0, 0.0), (1.0, 0.0)]),
    )
    .unwrap();
    assert_eq!(
        serde_json::to_string(&spline).unwrap(),
        r#"{"degree":1,"knots":[0.0,0.0,1.0,1.0],"points":[[0.0,0.0],[1.0,0.0]]}"#
    );
    let rational = RationalBezier::new(points(&[(0.0, 0.0), (1.0, 0.0)]), vec![1.0, 2.0]).unwrap();
    assert_eq!(
        serde_json::to_string(&rational).unwrap(),
        r#"{"points":[[0.0,0.0],[1.0,0.0]],"weights":[1.0,2.0]}"#
    );
    assert_eq!(
        serde_json::to_string(&Tolerance::new(1e-9, 16).unwrap()).unwrap(),
        r#"{"relative":1e-9,"max_iterations":16}"#
    );
    let ray = Ray::new(Point3::new(1.0, 2.0, 3.0), Vector3::new(0.0, 0.0, -1.0));
    assert_eq!(
        serde_json::to_string(&ray).unwrap(),
        r#"{"origin":[1.0,2.0,3.0],"dir":[0.0,0.0,-1.0]}"#
    );
    let surface = Revolution::new(bezier)
        .with_axis(Point3::new(0.0, 0.0, 1.0), Vector3::x_axis())
        .with_tolerance(Tolerance::new(1e-10, 8).unwrap());
    assert_eq!(
        serde_json::to_string(&surface).unwrap(),
        r#"{"profile":{"points":[[0.0,0.5],[1.0,2.0]]},"origin":[0.0,0.0,1.0],"axis":[1.0,0.0,0.0],"tolerance":{"relative":1e-10,"max_iterations":8}}"#
    );
}

// ---------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------

#[test]
fn curves_round_trip_equal_and_evaluate_alike() {
    assert_curve_round_trip(&Bezier::new(points(&VASE)).unwrap());
    assert_curve_round_trip(&Bezier::new(vec![Point3::new(0.1, -2.0, 3.0)]).unwrap());
    assert_curve_round_trip(&BSpline::uniform(3, points(&GLASS)).unwrap());
    assert_curve_round_trip(&BSpline::clamped(4, points(&GLASS)).unwrap());
    // Random curves: awkward floats (not short decimals), repeated knots.
    let mut rng = Rng(17);
    for _ in 0..50 {
        let n = 2 + rng.below(9);
        let degree = 1 + rng.below(n - 1);
        let pts3: Vec<Point3<f64>> = (0..n)
            .map(|_| rng.point([-1e3, -1.0, -1e-3], [1e3, 1.0, 1e-3]))
            .collect();
        let mut knots: Vec<f64> = (0..n + degree + 1).map(|_| rng.range(-5.0, 5.0)).collect();
        knots.sort_by(f64::total_cmp);
        knots[degree + 1] = knots[degree]; // a repeated knot
        knots[n] = knots[n - 1].max(knots[degree] + 0.5);
        for i in n + 1..knots.len() {
            knots[i] = knots[i].max(knots[i - 1]);
        }
        let spline = BSpline::new(degree, knots.clone(), pts3.clone()).unwrap();
        assert_curve_round_trip(&spline);
        assert_curve_round_trip(&Bezier::new(pts3.clone()).unwrap());
        let weights: Vec<f64> = (0..n).map(|_| rng.range(0.05, 20.0)).collect();
        let nurbs = Nurbs::new(degree, knots, pts3.clone(), weights.clone()).unwrap();
        assert_curve_round_trip(&nurbs);
        assert_curve_round_trip(&RationalBezier::new(pts3, weights).unwrap());
    }
    assert_curve_round_trip(&quarter_circle());
    assert_curve_round_trip(&half_circle());
    assert_curve_round_trip(&Nurbs::circle(Point2::new(0.3, -7.0), 2.5).unwrap());
    assert_curve_round_trip(&Nurbs::arc(Point2::new(1.0, 2.0), 0.1, -1.0, 4.0).unwrap());
}

#[test]
fn plain_values_round_trip_equal() {
    let mut rng = Rng(5);
    for _ in 0..100 {
        let tolerance = Tolerance::new(
            rng.range(Tolerance::MIN_RELATIVE, Tolerance::MAX_RELATIVE),
            1 + rng.below(Tolerance::MAX_ITERATIONS as usize) as u32,
        )
        .unwrap();
        assert_eq!(json_round_trip(&tolerance), tolerance);
        let ray = Ray::new(
            rng.point([-1e6; 3], [1e6; 3]),
            rng.direction() * rng.range(1e-3, 1e3),
        );
        assert_eq!(json_round_trip(&ray), ray);
        let aabb = Aabb::new(
            rng.point([-9.0; 3], [9.0; 3]),
            rng.point([-9.0; 3], [9.0; 3]),
        );
        assert_eq!(json_round_trip(&aabb), aabb);
    }
    assert_eq!(json_round_trip(&Tolerance::default()), Tolerance::default());
    // A box is read as written, corners unsorted: an inverted box stays
    // inverted (empty).
    let inverted = Aabb {
        min: Point3::new(1.0, 0.0, 0.0),
        max: Point3::new(-1.0, 0.0, 0.0),
    };
    let back = json_round_trip(&inverted);
    assert_eq!(back, inverted);
    assert!(back.is_empty());
    // Infinite corners need a format that carries infinity.
    let tree = Tree::Map(vec![
        ("min", nums(&[f64::INFINITY; 3])),
        ("max", nums(&[f64::NEG_INFINITY; 3])),
    ]);
    assert_eq!(read::<Aabb>(tree), Ok(Aabb::EMPTY));
}

/// Asserts that `surface` comes back from JSON equal and hits `rays` alike.
#[track_caller]
fn assert_surface_round_trip<C>(surface: &Revolution<C>, seed: u64)
where
    C: Curve<2> + Serialize + DeserializeOwned + PartialEq + Debug,
{
    let back = json_round_trip(surface);
    assert_eq!(&back, surface);
    assert_eq!(back.to_world(), surface.to_world());
    assert_eq!(back.bounds(), surface.bounds());
    assert_eq!(
        back.has_exact_intersector(),
        surface.has_exact_intersector()
    );
    // Rays from around the box toward points inside it: most hit.
    let bounds = surface.bounds();
    let far = bounds.expand(bounds.scale());
    let mut rng = Rng(seed);
    let mut hits = 0;
    for _ in 0..2000 {
        let origin = rng.point_in(&far);
        let target = rng.point_in(&bounds);
        let ray = Ray::new(origin, target - origin);
        let hit = surface.intersect(&ray, 0.0, f64::INFINITY);
        assert_eq!(back.intersect(&ray, 0.0, f64::INFINITY), hit, "{ray:?}");
        hits += usize::from(hit.is_some());
    }
    assert!(
        hits > 500,
        "only {hits} of 2000 rays hit: a weak comparison"
    );
}

#[test]
fn revolutions_round_trip_and_intersect_alike() {
    let mut rng = Rng(99);
    let glass = Revolution::new(BSpline::uniform(3, points(&GLASS)).unwrap());
    assert_surface_round_trip(&glass, 1);
    for seed in 0..6 {
        // Random placements: the axis is written as given (the axis read
        // back from the rotation would rebuild it only to an ulp).
        let axis = Unit::new_normalize(rng.direction());
        let origin = rng.point([-10.0; 3], [10.0; 3]);
        let tolerance =
            Tolerance::new(10f64.powf(rng.range(-15.0, -3.0)), 4 + seed as u32).unwrap();
        let vase = Revolution::new(Bezier::new(points(&VASE)).unwrap())
            .with_axis(origin, axis)
            .with_tolerance(tolerance);
        assert_surface_round_trip(&vase, 10 + seed);
        let glass = glass.clone().with_axis(origin, axis);
        assert_surface_round_trip(&glass, 20 + seed);
        let sphere = Revolution::new(half_circle()).with_axis(origin, axis);
        assert_surface_round_trip(&sphere, 30 + seed);
        // A NURBS sphere (an arc from pole to pole) and a torus (a full
        // circle off the axis).
        let arc = Nurbs::arc(Point2::origin(), 1.5, -FRAC_PI_2, FRAC_PI_2).unwrap();
        let sphere = Revolution::new(arc).with_axis(origin, axis);
        assert_surface_round_trip(&sphere, 40 + seed);
        let circle = Nurbs::circle(Point2::new(2.0, 0.5), 0.75).unwrap();
        let torus = Revolution::new(circle).with_axis(origin, axis);
        assert_surface_round_trip(&torus, 50 + seed);
    }
}

#[test]
fn broken_revolution_is_not_written() {
    let vase = Revolution::new(Bezier::new(points(&VASE)).unwrap());
    let nowhere = vase.with_axis(Point3::origin(), Unit::new_unchecked(Vector3::zeros()));
    let e = serde_json::to_string(&nowhere).unwrap_err().to_string();
    let cause = nowhere.contract_error().unwrap().to_string();
    assert!(e.contains(&cause), "'{cause}' not in: {e}");
}

// ---------------------------------------------------------------------------
// Bad data
// ---------------------------------------------------------------------------

/// The tree of a Bézier on `points`.
fn bezier_tree(points: Tree) -> Tree {
    Tree::Map(vec![("points", points)])
}

/// The tree of a B-spline.
fn bspline_tree(degree: u64, knots: &[f64], points: &[(f64, f64)]) -> Tree {
    Tree::Map(vec![
        ("degree", Tree::Whole(degree)),
        ("knots", nums(knots)),
        ("points", pts(points)),
    ])
}

/// The tree of a rational Bézier.
fn rational_tree(points: &[(f64, f64)], weights: &[f64]) -> Tree {
    Tree::Map(vec![("points", pts(points)), ("weights", nums(weights))])
}

/// The tree of a NURBS curve.
fn nurbs_tree(degree: u64, knots: &[f64], points: &[(f64, f64)], weights: &[f64]) -> Tree {
    Tree::Map(vec![
        ("degree", Tree::Whole(degree)),
        ("knots", nums(knots)),
        ("points", pts(points)),
        ("weights", nums(weights)),
    ])
}

/// The tree of a tolerance.
fn tolerance_tree(relative: f64, max_iterations: u64) -> Tree {
    Tree::Map(vec![
        ("relative", Tree::Num(relative)),
        ("max_iterations", Tree::Whole(max_iterations)),
    ])
}

const LINE: [(f64, f64); 2] = [(0.0, 0.0), (1.0, 1.0)];

#[test]
fn bad_control_points_are_refused_with_the_crate_message() {
    assert_refused::<Bezier<2>>(bezier_tree(pts(&[])), Error::NoControlPoints);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_refused::<Bezier<2>>(
            bezier_tree(pts(&[(0.0, 0.0), (1.0, bad)])),
            Error::NonFinitePoint { index: 1 },
        );
        assert_refused::<BSpline<2>>(
            bspline_tree(1, &[0.0, 0.0, 1.0, 1.0], &[(bad, 0.0), (1.0, 1.0)]),
            Error::NonFinitePoint { index: 0 },
        );
        assert_refused::<RationalBezier<2>>(
            rational_tree(&[(0.0, 0.0), (1.0, bad)], &[1.0, 1.0]),
            Error::NonFinitePoint { index: 1 },
        );
    }
    let too_large = Bezier::new(points(&[(0.0, 0.0), (0.0, 1e101)])).unwrap_err();
    assert!(matches!(
        too_large,
        Error::CoordinateTooLarge { index: 1, .. }
    ));
    assert_refused::<Bezier<2>>(bezier_tree(pts(&[(0.0, 0.0), (0.0, 1e101)])), too_large);
    // A point of the wrong dimension is the format's error.
    let e = serde_json::from_str::<Bezier<2>>(r#"{"points": [[1, 2, 3]]}"#).unwrap_err();
    assert!(e.to_string().contains("invalid length"), "{e}");
}

#[test]
fn bad_knots_are_refused_with_the_crate_message() {
    let cases: [(u64, &[f64]); 6] = [
        (1, &[0.0, 0.0, 1.0]),                // one knot short
        (1, &[0.0, 0.0, 1.0, 1.0, 2.0]),      // one too many
        (1, &[0.0, f64::NAN, 1.0, 1.0]),      // not finite
        (1, &[0.0, 1.0, 0.5, 1.0]),           // decreasing
        (1, &[0.0, 0.0, 0.0, 1.0]),           // a knot repeated beyond degree + 1
        (2, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]), // degree too high for two points
    ];
    for (degree, knots) in cases {
        let expected = BSpline::new(degree as usize, knots.to_vec(), points(&LINE)).unwrap_err();
        assert_refused::<BSpline<2>>(bspline_tree(degree, knots, &LINE), expected);
    }
    // Spot checks that the cases above are the errors they are meant to be.
    let short = BSpline::new(1, vec![0.0, 0.0, 1.0], points(&LINE)).unwrap_err();
    assert_eq!(
        short,
        Error::KnotCount {
            expected: 4,
            found: 3
        }
    );
    assert!(matches!(
        read::<BSpline<2>>(bspline_tree(1, &[0.0, 1.0, 0.5, 1.0], &LINE)),
        Err(m) if m == Error::DecreasingKnots { index: 2 }.to_string()
    ));
}

#[test]
fn bad_weights_are_refused_with_the_crate_message() {
    let three = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)];
    assert_refused::<RationalBezier<2>>(
        rational_tree(&three, &[1.0, 1.0]),
        Error::WeightCount {
            expected: 3,
            found: 2,
        },
    );
    assert_refused::<RationalBezier<2>>(
        rational_tree(&three, &[1.0, 1.0, 1.0, 1.0]),
        Error::WeightCount {
            expected: 3,
            found: 4,
        },
    );
    for weight in [0.0, -0.0, -1.0, f64::NAN, f64::INFINITY] {
        let message = read::<RationalBezier<2>>(rational_tree(&three, &[1.0, weight, 1.0]))
            .expect_err("a bad weight is refused");
        // NaN is not equal to itself: compare the message of the same error.
        let expected = RationalBezier::new(points(&three), vec![1.0, weight, 1.0]).unwrap_err();
        assert!(matches!(expected, Error::InvalidWeight { index: 1, .. }));
        assert_eq!(message, expected.to_string());
    }
    let ratio = RationalBezier::new(points(&three), vec![1.0, 1e9, 1.0]).unwrap_err();
    assert!(matches!(ratio, Error::WeightRatioTooLarge { .. }));
    assert_refused::<RationalBezier<2>>(rational_tree(&three, &[1.0, 1e9, 1.0]), ratio);
}

/// Knots, points and weights of a NURBS curve.
type NurbsCase<'a> = (&'a [f64], &'a [(f64, f64)], &'a [f64]);

#[test]
fn bad_nurbs_are_refused_with_the_crate_message() {
    let three = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)];
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let w = [1.0, 0.5, 1.0];
    let cases: Vec<NurbsCase<'_>> = vec![
        (&knots[..5], &three, &w),                                // a knot short
        (&[0.0, 0.0, 0.0, 1.0, f64::NAN, 1.0], &three, &w),       // a knot not finite
        (&[0.0, 0.0, 0.5, 0.25, 1.0, 1.0], &three, &w),           // decreasing
        (&knots, &[(0.0, 0.0), (1.0, f64::NAN), (2.0, 0.0)], &w), // a point not finite
        (&knots, &three, &w[..2]),                                // a weight short
        (&knots, &three, &[1.0, 0.0, 1.0]),                       // weights not positive,
        (&knots, &three, &[1.0, -2.0, 1.0]),                      //   not finite
        (&knots, &three, &[1.0, f64::NAN, 1.0]),
        (&knots, &three, &[1.0, f64::INFINITY, 1.0]),
        (&knots, &three, &[1.0, 1e-9, 1.0]), // ratio beyond the limit
    ];
    for (knots, points_, weights) in cases {
        let expected = Nurbs::new(2, knots.to_vec(), points(points_), weights.to_vec())
            .expect_err("a bad curve");
        let message = read::<Nurbs<2>>(nurbs_tree(2, knots, points_, weights)).unwrap_err();
        assert_eq!(message, expected.to_string());
    }
    assert_refused::<Nurbs<2>>(
        nurbs_tree(2, &knots, &three, &[1.0, 1.0]),
        Error::WeightCount {
            expected: 3,
            found: 2,
        },
    );
    assert_refused::<Nurbs<2>>(
        nurbs_tree(2, &knots[..5], &three, &w),
        Error::KnotCount {
            expected: 6,
            found: 5,
        },
    );
    assert_refused::<Nurbs<2>>(
        nurbs_tree(2, &knots, &three, &[1.0, 0.0, 1.0]),
        Error::InvalidWeight {
            index: 1,
            weight: 0.0,
        },
    );
}

#[test]
fn bad_tolerances_are_refused_with_the_crate_message() {
    let cases = [
        (f64::NAN, 16),
        (-1e-9, 16),
        (0.0, 16),
        (f64::INFINITY, 16),
        (1e-17, 16),
        (0.5, 16),
        (1e-9, 0),
        (1e-9, u64::from(Tolerance::MAX_ITERATIONS) + 1),
    ];
    for (relative, iterations) in cases {
        let expected = Tolerance::new(relative, iterations as u32).unwrap_err();
        let message = read::<Tolerance>(tolerance_tree(relative, iterations)).unwrap_err();
        assert_eq!(message, expected.to_string());
    }
    // An unchecked tolerance is written as it is and refused when read.
    let text = serde_json::to_string(&Tolerance::relative(0.5)).unwrap();
    let e = serde_json::from_str::<Tolerance>(&text)
        .unwrap_err()
        .to_string();
    let expected = Tolerance::new(0.5, Tolerance::default().max_iterations).unwrap_err();
    assert!(e.contains(&expected.to_string()), "{e}");
}

/// The tree of a revolution of [`LINE`] with the given placement.
fn revolution_tree(profile: Tree, origin: [f64; 3], axis: [f64; 3], tolerance: Tree) -> Tree {
    Tree::Map(vec![
        ("profile", profile),
        ("origin", nums(&origin)),
        ("axis", nums(&axis)),
        ("tolerance", tolerance),
    ])
}

#[test]
fn bad_revolutions_are_refused_with_the_crate_message() {
    let line = || bezier_tree(pts(&LINE));
    let good_tolerance = || tolerance_tree(1e-12, 8);
    // The good tree reads, placed as written.
    let tree = revolution_tree(line(), [1.0, 2.0, 3.0], [0.0, 0.0, 2.0], good_tolerance());
    let ok = read::<Revolution<Bezier<2>>>(tree).unwrap();
    assert_eq!(
        ok,
        Revolution::new(Bezier::new(points(&LINE)).unwrap())
            .with_axis(Point3::new(1.0, 2.0, 3.0), Vector3::z_axis())
            .with_tolerance(Tolerance::new(1e-12, 8).unwrap())
    );

    // The profile's own error.
    assert_refused::<Revolution<Bezier<2>>>(
        revolution_tree(
            bezier_tree(pts(&[(f64::NAN, 0.0)])),
            [0.0; 3],
            [0.0, 1.0, 0.0],
            good_tolerance(),
        ),
        Error::NonFinitePoint { index: 0 },
    );
    // Placements `try_with_axis` refuses.
    let profile = Revolution::new(Bezier::new(points(&LINE)).unwrap());
    for (origin, axis) in [
        ([0.0; 3], [0.0; 3]),
        ([0.0; 3], [f64::NAN, 1.0, 0.0]),
        ([0.0; 3], [f64::INFINITY, 1.0, 0.0]),
        ([f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 1e101, 0.0], [0.0, 1.0, 0.0]),
    ] {
        let expected = profile
            .clone()
            .try_with_axis(
                Point3::from(origin),
                Unit::new_unchecked(Vector3::from(axis)),
            )
            .unwrap_err();
        assert!(matches!(expected, Error::InvalidPlacement { .. }));
        let message =
            read::<Revolution<Bezier<2>>>(revolution_tree(line(), origin, axis, good_tolerance()))
                .unwrap_err();
        assert_eq!(message, expected.to_string());
    }
    // A tolerance out of range.
    assert_refused::<Revolution<Bezier<2>>>(
        revolution_tree(line(), [0.0; 3], [0.0, 1.0, 0.0], tolerance_tree(0.5, 8)),
        Tolerance::new(0.5, 8).unwrap_err(),
    );
}

#[test]
fn unknown_and_missing_fields_are_refused() {
    let e = read::<Bezier<2>>(Tree::Map(vec![
        ("points", pts(&LINE)),
        ("weights", nums(&[1.0, 1.0])),
    ]))
    .unwrap_err();
    assert!(e.contains("unknown field `weights`"), "{e}");
    let e = read::<RationalBezier<2>>(bezier_tree(pts(&LINE))).unwrap_err();
    assert!(e.contains("missing field `weights`"), "{e}");
    let e = serde_json::from_str::<BSpline<2>>(r#"{"knots":[0,0,1,1],"points":[[0,0],[1,1]]}"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing field `degree`"), "{e}");
}

#[test]
fn json_errors_carry_the_crate_message() {
    let text = r#"{"degree": 1, "knots": [0, 0, 1], "points": [[0, 0], [1, 1]]}"#;
    let e = serde_json::from_str::<BSpline<2>>(text).unwrap_err();
    let expected = Error::KnotCount {
        expected: 4,
        found: 3,
    };
    assert!(e.to_string().starts_with(&expected.to_string()), "{e}");
    let text = r#"{"points": [[0, 0], [1, 1]], "weights": [1, 0]}"#;
    let e = serde_json::from_str::<RationalBezier<2>>(text).unwrap_err();
    let expected = Error::InvalidWeight {
        index: 1,
        weight: 0.0,
    };
    assert!(e.to_string().starts_with(&expected.to_string()), "{e}");
}

/// A `rows × cols` net of random points.
fn net(rng: &mut Rng, rows: usize, cols: usize) -> Vec<Vec<Point3<f64>>> {
    (0..rows)
        .map(|_| {
            (0..cols)
                .map(|_| {
                    Point3::new(
                        rng.range(-2.0, 2.0),
                        rng.range(-2.0, 2.0),
                        rng.range(-2.0, 2.0),
                    )
                })
                .collect()
        })
        .collect()
}

/// Asserts that `surface` comes back from JSON equal and evaluates to the
/// same bits (points and partials) over its domain.
#[track_caller]
fn assert_tensor_round_trip<S>(surface: &S)
where
    S: Serialize + DeserializeOwned + PartialEq + Debug + Surface,
{
    let back: S = json_round_trip(surface);
    assert_eq!(&back, surface);
    let [(u0, u1), (v0, v1)] = surface.domain();
    for i in 0..=8 {
        for j in 0..=8 {
            let (u, v) = (
                u0 + (u1 - u0) * i as f64 / 8.0,
                v0 + (v1 - v0) * j as f64 / 8.0,
            );
            assert_eq!(back.eval(u, v), surface.eval(u, v));
            assert_eq!(back.partials(u, v), surface.partials(u, v));
        }
    }
}

/// Tensor-product surfaces round-trip equal and evaluate alike; bad data
/// (a ragged row, a wrong knot count, a zero weight, weights on a B-spline
/// surface, missing weights on a NURBS one) is refused.
#[test]
fn tensor_surfaces_round_trip_and_bad_data_is_refused() {
    let mut rng = Rng(0x7E45);
    for _ in 0..20 {
        let bezier = BezierSurface::new(net(&mut rng, 4, 3)).unwrap();
        assert_tensor_round_trip(&bezier);
        let knots = (
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        );
        let points = net(&mut rng, 5, 5);
        let spline = BSplineSurface::new((3, 2), knots.clone(), points.clone()).unwrap();
        assert_tensor_round_trip(&spline);
        let weights: Vec<Vec<f64>> = (0..5)
            .map(|_| (0..5).map(|_| rng.range(0.05, 20.0)).collect())
            .collect();
        let nurbs = NurbsSurface::new((3, 2), knots, points, weights).unwrap();
        assert_tensor_round_trip(&nurbs);
    }
    let ragged = r#"{"points":[[[0,0,0],[1,0,0]],[[0,1,0]]]}"#;
    let err = serde_json::from_str::<BezierSurface>(ragged)
        .unwrap_err()
        .to_string();
    assert!(err.contains("row"), "{err}");
    let short = r#"{"degrees":[1,1],"knots":[[0,0,1],[0,0,1,1]],"points":[[[0,0,0],[1,0,0]],[[0,1,0],[1,1,0]]]}"#;
    let err = serde_json::from_str::<BSplineSurface>(short)
        .unwrap_err()
        .to_string();
    assert!(err.contains("knot count"), "{err}");
    let bilinear = r#""degrees":[1,1],"knots":[[0,0,1,1],[0,0,1,1]],"points":[[[0,0,0],[1,0,0]],[[0,1,0],[1,1,0]]]"#;
    assert!(serde_json::from_str::<BSplineSurface>(&format!("{{{bilinear}}}")).is_ok());
    let zero = format!(r#"{{{bilinear},"weights":[[1,0],[1,1]]}}"#);
    let err = serde_json::from_str::<NurbsSurface>(&zero)
        .unwrap_err()
        .to_string();
    assert!(err.contains("weight"), "{err}");
    let with = format!(r#"{{{bilinear},"weights":[[1,2],[1,1]]}}"#);
    assert!(serde_json::from_str::<NurbsSurface>(&with).is_ok());
    assert!(serde_json::from_str::<BSplineSurface>(&with).is_err());
    let err = serde_json::from_str::<NurbsSurface>(&format!("{{{bilinear}}}"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("weights"), "{err}");
}

/// The teapot model round-trips through JSON with the same patches and the
/// same hits; an empty patch list is refused with the crate's message.
#[test]
fn a_model_of_patches_round_trips_and_an_empty_one_is_refused() {
    use revolve::BezierPatches;
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    let back = json_round_trip(&model);
    assert_eq!(back, model);
    let mut rng = Rng(41);
    let b = model.bounds();
    for _ in 0..200 {
        let dir: Vector3<f64> = rng.direction();
        let ray = Ray::new(rng.point_in(&b) - dir * 10.0, dir);
        assert_eq!(
            back.intersect(&ray, 0.0, f64::INFINITY),
            model.intersect(&ray, 0.0, f64::INFINITY)
        );
    }
    // The tolerance is written only when it is not the default.
    assert!(!serde_json::to_string(&model).unwrap().contains("tolerance"));
    let loose = model.with_tolerance(Tolerance::relative(1e-6));
    let text = serde_json::to_string(&loose).unwrap();
    assert!(text.contains("tolerance"), "{text}");
    let back: BezierPatches = serde_json::from_str(&text).unwrap();
    assert_eq!(back.tolerance().relative, 1e-6);
    assert_eq!(back, loose);
    let surface = loose.patches()[0]
        .clone()
        .with_tolerance(Tolerance::relative(1e-8));
    assert_eq!(json_round_trip(&surface), surface);
    let err = serde_json::from_str::<BezierPatches>(r#"{"patches": []}"#)
        .unwrap_err()
        .to_string();
    assert!(err.contains(&Error::NoPatches.to_string()), "{err}");
}

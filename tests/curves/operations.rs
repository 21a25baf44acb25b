//! Curve operations users of NURBS libraries expect: `Curve` for wrappers
//! (`&C`, `Box<C>`, `Arc<C>`, `Box<dyn Curve<D>>`), `split`, `transformed`,
//! `parameter_at_length` and `divide_by_length`, knot removal, 3D arcs and
//! ellipses, and the Frenet frame.
//!
//! References are independent of the code under test: the unwrapped curve
//! (bit for bit), the original curve at mapped parameters, the images of
//! points under the transformation, closed forms (circle, helix-free exact
//! cases, straight segments with known speed), and central differences.
//! Tolerances are stated at each check as multiples of `ε` times the size
//! of the values compared.

use revolve::nalgebra::{Point2, Point3, Vector2, Vector3};
use revolve::{BSpline, Bezier, Curve, Error, Intersect, Nurbs, RationalBezier, Ray, Revolution};
use std::sync::Arc;

const EPS: f64 = f64::EPSILON;

/// A small deterministic generator (SplitMix64): the tests need no seed file.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
    fn point2(&mut self, r: f64) -> Point2<f64> {
        Point2::new(self.uniform(-r, r), self.uniform(-r, r))
    }
    fn point3(&mut self, r: f64) -> Point3<f64> {
        Point3::new(
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        )
    }
}

// ---------------------------------------------------------------------------
// 1. Wrappers keep exactness
// ---------------------------------------------------------------------------

/// 1000 random rays from a box about the object toward random points near it.
fn random_rays(seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    (0..1000)
        .map(|_| {
            let origin = rng.point3(6.0);
            let target = rng.point3(2.5);
            let dir = target - origin;
            Ray::new(origin, if dir.norm() > 0.0 { dir } else { Vector3::x() })
        })
        .collect()
}

/// The hits of two surfaces agree bit for bit on every ray; returns how many hit.
fn same_hits(a: &impl Intersect, b: &impl Intersect, rays: &[Ray]) -> usize {
    let mut hits = 0;
    for ray in rays {
        let (ha, hb) = (
            a.intersect(ray, 0.0, f64::INFINITY),
            b.intersect(ray, 0.0, f64::INFINITY),
        );
        match (ha, hb) {
            (None, None) => {}
            (Some(x), Some(y)) => {
                hits += 1;
                assert_eq!(x.t.to_bits(), y.t.to_bits(), "ray {ray:?}");
                for k in 0..3 {
                    assert_eq!(x.point[k].to_bits(), y.point[k].to_bits());
                    assert_eq!(x.normal[k].to_bits(), y.normal[k].to_bits());
                }
                assert_eq!(x.uv.0.to_bits(), y.uv.0.to_bits());
                assert_eq!(x.uv.1.to_bits(), y.uv.1.to_bits());
            }
            (x, y) => panic!("one hit, one miss on {ray:?}: {x:?} against {y:?}"),
        }
    }
    hits
}

/// Every way of wrapping `profile` gives the exact intersector and the
/// unwrapped revolution's hits.
fn check_wrapped_profile<C: Curve<2> + Clone + Send + Sync + 'static>(profile: C, seed: u64) {
    let plain = Revolution::new(profile.clone());
    assert!(plain.has_exact_intersector());
    let rays = random_rays(seed);

    let by_ref = Revolution::new(&profile);
    assert!(by_ref.has_exact_intersector());
    let hits = same_hits(&plain, &by_ref, &rays);
    assert!(
        hits > 100,
        "only {hits} of 1000 rays hit: the test would prove little"
    );

    let boxed = Revolution::new(Box::new(profile.clone()));
    assert!(boxed.has_exact_intersector());
    same_hits(&plain, &boxed, &rays);

    let shared = Revolution::new(Arc::new(profile.clone()));
    assert!(shared.has_exact_intersector());
    same_hits(&plain, &shared, &rays);

    let dynamic = Revolution::new(Box::new(profile.clone()) as Box<dyn Curve<2>>);
    assert!(dynamic.has_exact_intersector());
    same_hits(&plain, &dynamic, &rays);

    let shared_dyn = Revolution::new(Arc::new(profile) as Arc<dyn Curve<2> + Send + Sync>);
    assert!(shared_dyn.has_exact_intersector());
    same_hits(&plain, &shared_dyn, &rays);
}

#[test]
fn wrapped_bezier_profile_keeps_the_exact_intersector() {
    let profile = Bezier::new(vec![
        Point2::new(0.0, -1.5),
        Point2::new(2.5, -1.0),
        Point2::new(0.5, 0.5),
        Point2::new(1.5, 1.5),
    ])
    .unwrap();
    check_wrapped_profile(profile, 1);
}

#[test]
fn wrapped_bspline_profile_keeps_the_exact_intersector() {
    let profile = BSpline::clamped(
        3,
        vec![
            Point2::new(0.0, -2.0),
            Point2::new(1.5, -1.5),
            Point2::new(0.5, -0.5),
            Point2::new(2.0, 0.5),
            Point2::new(1.0, 1.5),
            Point2::new(0.0, 2.0),
        ],
    )
    .unwrap();
    check_wrapped_profile(profile, 2);
}

#[test]
fn wrapped_nurbs_profile_keeps_the_exact_intersector() {
    // A torus' meridian: a full circle about (1.5, 0), radius 0.75.
    let profile = Nurbs::circle(Point2::new(1.5, 0.0), 0.75).unwrap();
    check_wrapped_profile(profile, 3);
}

#[test]
fn wrappers_forward_every_method() {
    let curve = RationalBezier::new(
        vec![
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ],
        vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
    )
    .unwrap();
    let wrapped: Vec<Box<dyn Curve<2>>> = vec![
        Box::new(curve.clone()),
        Box::new(&curve),
        Box::new(Box::new(curve.clone())),
        Box::new(Arc::new(curve.clone())),
        Box::new(std::rc::Rc::new(curve.clone())),
    ];
    let q = Point2::new(2.0, 3.0);
    for w in &wrapped {
        assert_eq!(w.domain(), curve.domain());
        for k in 0..=16 {
            let t = k as f64 / 16.0;
            assert_eq!(w.eval(t), curve.eval(t));
            assert_eq!(w.derivative(t), curve.derivative(t));
            assert_eq!(w.eval_with_derivative(t), curve.eval_with_derivative(t));
            assert_eq!(w.tangent(t), curve.tangent(t));
        }
        assert_eq!(w.bezier_spans(), curve.bezier_spans());
        assert_eq!(w.rational_bezier_spans(), curve.rational_bezier_spans());
        assert!(w.rational_bezier_spans().is_some() && w.bezier_spans().is_none());
        assert_eq!(w.nearest_point(&q), curve.nearest_point(&q));
        assert_eq!(w.arc_length(1e-12), curve.arc_length(1e-12));
        assert_eq!(
            w.parameter_at_length(0.5, 1e-10),
            curve.parameter_at_length(0.5, 1e-10)
        );
        assert_eq!(
            w.divide_by_length(3, 1e-10),
            curve.divide_by_length(3, 1e-10)
        );
        assert_eq!(w.discretize(7), curve.discretize(7));
        assert_eq!(w.try_discretize(7), curve.try_discretize(7));
    }
}

// ---------------------------------------------------------------------------
// 2. split
// ---------------------------------------------------------------------------

/// `|a − b| ≤ tol·(1 + |a|)` per coordinate, with a message.
fn assert_close<const D: usize>(
    a: &revolve::nalgebra::Point<f64, D>,
    b: &revolve::nalgebra::Point<f64, D>,
    tol: f64,
    what: &str,
) {
    let size = 1.0 + a.coords.amax();
    assert!((a - b).amax() <= tol * size, "{what}: {a:?} against {b:?}");
}

fn random_points<const D: usize>(rng: &mut Rng, n: usize) -> Vec<revolve::nalgebra::Point<f64, D>> {
    (0..n)
        .map(|_| {
            revolve::nalgebra::Point::from(revolve::nalgebra::SVector::<f64, D>::from_fn(|_, _| {
                rng.uniform(-5.0, 5.0)
            }))
        })
        .collect()
}

#[test]
fn bezier_split_halves_are_the_curve_reparametrized() {
    let mut rng = Rng(10);
    for degree in 0..=9 {
        let c = Bezier::new(random_points::<3>(&mut rng, degree + 1)).unwrap();
        for &t in &[0.5, 0.1, 0.9, 1e-6, 0.3] {
            let (l, r) = c.split(t).unwrap();
            assert_eq!(l.degree(), degree);
            assert_eq!(r.degree(), degree);
            assert_eq!(l.points()[0], c.points()[0]);
            assert_eq!(r.points()[degree], c.points()[degree]);
            assert_eq!(l.points()[degree], r.points()[0]);
            for k in 0..=50 {
                let s = k as f64 / 50.0;
                // Rounding of de Casteljau on both sides: a few ε·n·size.
                let tol = 64.0 * EPS * (degree as f64 + 1.0);
                assert_close(&l.eval(s), &c.eval(t * s), tol, "left half");
                assert_close(&r.eval(s), &c.eval(t + (1.0 - t) * s), tol, "right half");
            }
        }
    }
}

#[test]
fn rational_bezier_split_halves_are_the_curve_reparametrized() {
    let mut rng = Rng(11);
    for degree in 1..=6 {
        let weights = (0..=degree).map(|_| rng.uniform(0.2, 3.0)).collect();
        let c = RationalBezier::new(random_points::<2>(&mut rng, degree + 1), weights).unwrap();
        for &t in &[0.5, 0.2, 0.77] {
            let (l, r) = c.split(t).unwrap();
            assert_eq!((l.degree(), r.degree()), (degree, degree));
            assert_eq!(l.points()[0], c.points()[0]);
            assert_eq!(r.points()[degree], c.points()[degree]);
            for k in 0..=40 {
                let s = k as f64 / 40.0;
                let tol = 1e3 * EPS;
                assert_close(&l.eval(s), &c.eval(t * s), tol, "left half");
                assert_close(&r.eval(s), &c.eval(t + (1.0 - t) * s), tol, "right half");
            }
        }
    }
}

/// Samples of a spline's domain, avoiding nothing: knots included.
fn spline_samples((a, b): (f64, f64), count: usize) -> impl Iterator<Item = f64> {
    (0..=count).map(move |k| a + (b - a) * k as f64 / count as f64)
}

#[test]
fn bspline_split_halves_keep_the_parameters() {
    let mut rng = Rng(12);
    for degree in 0..=5 {
        for n in degree + 1..degree + 6 {
            let c = BSpline::uniform(degree, random_points::<2>(&mut rng, n)).unwrap();
            let (a, b) = c.domain();
            // A knot, a non-knot, near the ends.
            let mut ts = vec![a + 0.37 * (b - a), a + 0.01 * (b - a), a + 0.99 * (b - a)];
            ts.extend(c.knots().iter().copied().filter(|&k| a < k && k < b));
            for t in ts {
                let (l, r) = c.split(t).unwrap();
                assert_eq!(l.domain(), (a, t));
                assert_eq!(r.domain(), (t, b));
                assert_eq!((l.degree(), r.degree()), (degree, degree));
                assert_close(&l.eval(a), &c.eval(a), 1e3 * EPS, "start point");
                assert_close(&r.eval(b), &c.eval(b), 1e3 * EPS, "end point");
                for s in spline_samples((a, b), 60).chain([t]) {
                    // At t the curve takes its limit from the right (a
                    // jump for degree 0), as the right half does.
                    let half = if s < t { &l } else { &r };
                    assert_close(&half.eval(s), &c.eval(s), 1e3 * EPS, "half against curve");
                }
            }
        }
    }
}

#[test]
fn bspline_split_at_a_jump_takes_the_two_limits() {
    // Degree 1 with a double interior knot: a jump at 0.5.
    let c = BSpline::new(
        1,
        vec![0.0, 0.0, 0.5, 0.5, 1.0, 1.0],
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 5.0),
            Point2::new(2.0, 5.0),
        ],
    )
    .unwrap();
    let (l, r) = c.split(0.5).unwrap();
    assert_eq!(l.eval(0.5), Point2::new(1.0, 0.0));
    assert_eq!(r.eval(0.5), Point2::new(1.0, 5.0));
    assert_eq!(l.points().len() + r.points().len(), 4);
}

#[test]
fn nurbs_split_halves_keep_the_parameters() {
    let circle = Nurbs::circle(Point2::new(1.0, -2.0), 3.0).unwrap();
    for &t in &[0.1, 0.25, 0.5, 0.6, 0.999] {
        let (l, r) = circle.split(t).unwrap();
        assert_eq!(l.domain(), (0.0, t));
        assert_eq!(r.domain(), (t, 1.0));
        assert_eq!((l.degree(), r.degree()), (2, 2));
        assert_eq!(l.eval(0.0), circle.eval(0.0));
        assert_eq!(r.eval(1.0), circle.eval(1.0));
        for s in spline_samples((0.0, 1.0), 80) {
            let half = if s <= t { &l } else { &r };
            assert_close(
                &half.eval(s),
                &circle.eval(s),
                64.0 * EPS,
                "half against circle",
            );
            assert!(((half.eval(s) - Point2::new(1.0, -2.0)).norm() - 3.0).abs() < 1e-14);
        }
    }
}

#[test]
fn split_refuses_the_ends_nan_and_outside() {
    let bez = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 1.0)]).unwrap();
    let rat = RationalBezier::new(
        vec![Point2::new(0.0, 0.0), Point2::new(1.0, 1.0)],
        vec![1.0, 2.0],
    )
    .unwrap();
    let spl = BSpline::clamped(2, random_points::<2>(&mut Rng(13), 5)).unwrap();
    let nrb = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    let at_end =
        |r: Result<(), Error>| assert!(matches!(r, Err(Error::SplitAtDomainEnd { .. })), "{r:?}");
    let outside = |r: Result<(), Error>| {
        assert!(
            matches!(r, Err(Error::ParameterOutOfDomain { .. })),
            "{r:?}"
        )
    };
    for t in [0.0, 1.0] {
        at_end(bez.split(t).map(|_| ()));
        at_end(rat.split(t).map(|_| ()));
        at_end(spl.split(t).map(|_| ()));
        at_end(nrb.split(t).map(|_| ()));
    }
    // Within rounding of an end: the knot itself.
    at_end(spl.split(1e-17).map(|_| ()));
    at_end(nrb.split(1.0 - 1e-17).map(|_| ()));
    for t in [f64::NAN, -0.5, 1.5, f64::INFINITY] {
        outside(bez.split(t).map(|_| ()));
        outside(rat.split(t).map(|_| ()));
        outside(spl.split(t).map(|_| ()));
        outside(nrb.split(t).map(|_| ()));
    }
}

// ---------------------------------------------------------------------------
// 3. transformed and transformed_projective
// ---------------------------------------------------------------------------

use revolve::nalgebra::{Affine2, Affine3, Matrix3, Matrix4, Projective2, Projective3};

fn random_affine2(rng: &mut Rng) -> Affine2<f64> {
    let mut m = Matrix3::from_fn(|_, _| rng.uniform(-2.0, 2.0));
    m.set_row(2, &revolve::nalgebra::RowVector3::new(0.0, 0.0, 1.0));
    Affine2::from_matrix_unchecked(m)
}

fn random_affine3(rng: &mut Rng) -> Affine3<f64> {
    let mut m = Matrix4::from_fn(|_, _| rng.uniform(-2.0, 2.0));
    m.set_row(3, &revolve::nalgebra::RowVector4::new(0.0, 0.0, 0.0, 1.0));
    Affine3::from_matrix_unchecked(m)
}

/// `T(C(s))` against `C′(s)` at 41 parameters across the domain; the
/// tolerance covers the rounding of mapping the control points and of
/// evaluating both curves: `1e3·ε` times the size of the values.
fn assert_commutes<const D: usize>(
    original: &impl Curve<D>,
    image: &impl Curve<D>,
    map: impl Fn(&revolve::nalgebra::Point<f64, D>) -> revolve::nalgebra::Point<f64, D>,
    scale: f64,
) {
    assert_eq!(original.domain(), image.domain());
    for s in spline_samples(original.domain(), 40) {
        let want = map(&original.eval(s));
        let got = image.eval(s);
        assert!(
            (want - got).amax() <= 1e3 * EPS * scale,
            "at {s}: {got:?} against {want:?}"
        );
    }
}

#[test]
fn affine_transforms_commute_with_evaluation() {
    let mut rng = Rng(20);
    for _ in 0..20 {
        let t2 = random_affine2(&mut rng);
        let t3 = random_affine3(&mut rng);
        let bez = Bezier::new(random_points::<2>(&mut rng, 5)).unwrap();
        assert_commutes(&bez, &bez.transformed(&t2), |p| t2 * p, 50.0);
        let bez3 = Bezier::new(random_points::<3>(&mut rng, 4)).unwrap();
        assert_commutes(&bez3, &bez3.transformed(&t3), |p| t3 * p, 50.0);
        let weights: Vec<f64> = (0..4).map(|_| rng.uniform(0.3, 3.0)).collect();
        let rat = RationalBezier::new(random_points::<3>(&mut rng, 4), weights.clone()).unwrap();
        let rat_image = rat.transformed(&t3);
        assert_eq!(rat_image.weights(), rat.weights());
        assert_commutes(&rat, &rat_image, |p| t3 * p, 50.0);
        let spl = BSpline::uniform(3, random_points::<3>(&mut rng, 7)).unwrap();
        let spl_image = spl.transformed(&t3);
        assert_eq!(spl_image.knots(), spl.knots());
        assert_commutes(&spl, &spl_image, |p| t3 * p, 50.0);
        let nrb = Nurbs::new(
            3,
            spl.knots().to_vec(),
            spl.points().to_vec(),
            (0..7).map(|_| rng.uniform(0.3, 3.0)).collect(),
        )
        .unwrap();
        let nrb_image = nrb.transformed(&t3);
        assert_eq!(nrb_image.weights(), nrb.weights());
        assert_commutes(&nrb, &nrb_image, |p| t3 * p, 50.0);
        let circle = Nurbs::circle(rng.point2(3.0), 2.0).unwrap();
        assert_commutes(&circle, &circle.transformed(&t2), |p| t2 * p, 50.0);
        // The fallible form gives the same curve.
        assert_eq!(
            circle.try_transformed(&t2).unwrap(),
            circle.transformed(&t2)
        );
    }
}

#[test]
fn projective_transforms_commute_with_evaluation() {
    let mut rng = Rng(21);
    let mut checked = 0;
    for _ in 0..200 {
        // A perspective with a small projective row keeps the curve away
        // from the plane at infinity (most of the time: others are refused).
        let mut m = Matrix4::from_fn(|_, _| rng.uniform(-2.0, 2.0));
        m[(3, 3)] = rng.uniform(2.0, 4.0)
            * if rng.uniform(0.0, 1.0) < 0.5 {
                -1.0
            } else {
                1.0
            };
        for j in 0..3 {
            m[(3, j)] = rng.uniform(-0.2, 0.2);
        }
        let map = Projective3::from_matrix_unchecked(m);
        let weights = (0..6).map(|_| rng.uniform(0.3, 3.0)).collect();
        let nrb = Nurbs::new(
            2,
            vec![0.0, 0.0, 0.0, 0.3, 0.6, 0.8, 1.0, 1.0, 1.0],
            random_points::<3>(&mut rng, 6),
            weights,
        )
        .unwrap();
        // The independent reference: the point mapped in homogeneous form.
        let reference = |p: &Point3<f64>| {
            let h = m * p.to_homogeneous();
            Point3::new(h.x / h.w, h.y / h.w, h.z / h.w)
        };
        match nrb.transformed_projective(&map) {
            Ok(image) => {
                checked += 1;
                assert!(image.weights().iter().all(|&w| w > 0.0));
                assert_commutes(&nrb, &image, reference, 50.0);
            }
            Err(e) => assert!(
                matches!(e, Error::ProjectiveWeightNotPositive { .. }),
                "{e:?}"
            ),
        }
    }
    assert!(checked > 150, "only {checked} projective images checked");
    // 2D: a circle under a perspective is a conic, the images of its points.
    let circle = Nurbs::circle(Point2::new(0.5, 0.0), 1.0).unwrap();
    let m = Matrix3::new(1.0, 0.5, 0.0, 0.0, 1.0, 1.0, 0.3, -0.1, 2.0);
    let image = circle
        .transformed_projective(&Projective2::from_matrix_unchecked(m))
        .unwrap();
    assert_commutes(
        &circle,
        &image,
        |p| Projective2::from_matrix_unchecked(m) * p,
        10.0,
    );
    // An affine matrix as a projective one gives `transformed`'s curve.
    let t = random_affine2(&mut rng);
    let projective = Projective2::from_matrix_unchecked(*t.matrix());
    let (a, b) = (
        circle.transformed(&t),
        circle.transformed_projective(&projective).unwrap(),
    );
    for s in spline_samples((0.0, 1.0), 20) {
        assert_close(&a.eval(s), &b.eval(s), 1e3 * EPS, "affine as projective");
    }
}

#[test]
fn transform_errors_are_named() {
    let bez = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1e99, 2.0)]).unwrap();
    let nan = Affine2::from_matrix_unchecked(Matrix3::new(
        f64::NAN,
        0.0,
        0.0,
        0.0,
        1.0,
        0.0,
        0.0,
        0.0,
        1.0,
    ));
    assert_eq!(bez.try_transformed(&nan), Err(Error::InvalidTransform));
    let grow =
        Affine2::from_matrix_unchecked(Matrix3::new(100.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    assert!(matches!(
        bez.try_transformed(&grow),
        Err(Error::CoordinateTooLarge { index: 1, .. })
    ));
    let overflow =
        Affine2::from_matrix_unchecked(Matrix3::new(1e300, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    assert!(matches!(
        bez.try_transformed(&overflow),
        Err(Error::NonFinitePoint { index: 1 })
    ));
    // The infallible form never gives NaN: saturated points, or the curve itself.
    for t in [nan, grow, overflow] {
        let image = bez.transformed(&t);
        for s in spline_samples((0.0, 1.0), 10) {
            assert!(image.eval(s).iter().all(|x| x.is_finite()));
        }
        let spl = BSpline::clamped(1, bez.points().to_vec())
            .unwrap()
            .transformed(&t);
        assert!(spl.points().iter().all(|p| p.iter().all(|x| x.is_finite())));
    }
    let circle = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    // The line x = 0.5 (the plane at infinity's preimage) cuts the circle.
    let cut = Projective2::from_matrix_unchecked(Matrix3::new(
        1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -0.5,
    ));
    assert!(matches!(
        circle.transformed_projective(&cut),
        Err(Error::ProjectiveWeightNotPositive { .. })
    ));
    let bad = Projective2::from_matrix_unchecked(Matrix3::new(
        1.0,
        0.0,
        0.0,
        0.0,
        f64::INFINITY,
        0.0,
        0.0,
        0.0,
        1.0,
    ));
    assert_eq!(
        circle.transformed_projective(&bad),
        Err(Error::InvalidTransform)
    );
    let rat = RationalBezier::new(
        vec![Point2::new(0.0, 0.0), Point2::new(1.0, 1.0)],
        vec![1.0, 2.0],
    )
    .unwrap();
    assert_eq!(rat.try_transformed(&nan), Err(Error::InvalidTransform));
    assert_eq!(circle.try_transformed(&nan), Err(Error::InvalidTransform));
}

// ---------------------------------------------------------------------------
// 4. parameter_at_length and divide_by_length
// ---------------------------------------------------------------------------

#[test]
fn parameter_at_length_on_a_circle_is_the_angle_times_the_radius() {
    let r = 2.5;
    let circle = Nurbs::circle(Point2::new(1.0, 1.0), r).unwrap();
    let tolerance = 1e-10;
    for k in 0..=20 {
        let s = k as f64 / 20.0 * std::f64::consts::TAU * r * 0.999;
        let t = circle.parameter_at_length(s, tolerance).unwrap();
        let p = circle.eval(t) - Point2::new(1.0, 1.0);
        let mut angle = p.y.atan2(p.x);
        if angle < -1e-9 {
            angle += std::f64::consts::TAU;
        }
        // Closed form: angle = s / r; the arc length error is at most the
        // tolerance, and rounding of the point adds a few ε.
        assert!(
            (angle * r - s).abs() <= tolerance + 1e-13,
            "s = {s}: angle·r = {}",
            angle * r
        );
    }
    assert_eq!(circle.parameter_at_length(0.0, tolerance).unwrap(), 0.0);
    // The whole length: the end, or a parameter within the tolerance of it.
    let t = circle
        .parameter_at_length(std::f64::consts::TAU * r, 1e-9)
        .unwrap();
    assert!((1.0 - t) * std::f64::consts::TAU * r <= 1e-9 + 1e-13, "{t}");
}

#[test]
fn parameter_at_length_on_a_segment_with_non_uniform_speed() {
    // x(t) = 4·(3t² − 2t³) (a cubic Bézier 0, 0, 4, 4 on a line): the length
    // from 0 is x(t) itself, monotone, speed zero at both ends.
    let c = Bezier::new(vec![
        Point2::new(0.0, 0.0),
        Point2::new(0.0, 0.0),
        Point2::new(4.0, 0.0),
        Point2::new(4.0, 0.0),
    ])
    .unwrap();
    // The same in 3D, along a slanted line: length = 5·x/4 … scaled by 5/4.
    let d = Bezier::new(vec![
        Point3::origin(),
        Point3::origin(),
        Point3::new(4.0, 3.0, 0.0),
        Point3::new(4.0, 3.0, 0.0),
    ])
    .unwrap();
    let tolerance = 1e-11;
    for k in 0..=16 {
        let s = 4.0 * k as f64 / 16.0;
        let t = c.parameter_at_length(s, tolerance).unwrap();
        let length = 4.0 * (3.0 * t * t - 2.0 * t * t * t);
        assert!(
            (length - s).abs() <= tolerance + 8.0 * EPS * 4.0,
            "s = {s}, t = {t}"
        );
        let t3 = d.parameter_at_length(1.25 * s, tolerance).unwrap();
        let length3 = 5.0 * (3.0 * t3 * t3 - 2.0 * t3 * t3 * t3);
        assert!((length3 - 1.25 * s).abs() <= tolerance + 8.0 * EPS * 5.0);
    }
    let ts = c.divide_by_length(8, tolerance).unwrap();
    assert_eq!(ts.len(), 9);
    assert_eq!((ts[0], ts[8]), (0.0, 1.0));
    for (i, &t) in ts.iter().enumerate() {
        let length = 4.0 * (3.0 * t * t - 2.0 * t * t * t);
        assert!((length - 0.5 * i as f64).abs() <= tolerance + 32.0 * EPS);
    }
    assert!(ts.windows(2).all(|w| w[0] < w[1]));
}

#[test]
fn length_to_the_parameter_found_is_within_tolerance() {
    let mut rng = Rng(30);
    for _ in 0..12 {
        let degree = 1 + (rng.next_u64() % 4) as usize;
        let n = degree + 1 + (rng.next_u64() % 5) as usize;
        let weights: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 2.0)).collect();
        let base = BSpline::clamped(degree, random_points::<3>(&mut rng, n)).unwrap();
        let curve = Nurbs::new(
            degree,
            base.knots().to_vec(),
            base.points().to_vec(),
            weights,
        )
        .unwrap();
        let total = curve.arc_length(1e-11).unwrap();
        let tolerance = 1e-8;
        for k in 0..=6 {
            let s = total.length * k as f64 / 6.0;
            let t = curve.parameter_at_length(s, tolerance).unwrap();
            // Independent check: the prefix [a, t] measured on its own, as
            // the exact split's left half.
            let measured = match curve.split(t) {
                Ok((left, _)) => left.arc_length(1e-11).unwrap().length,
                // At (or within rounding of) an end.
                Err(Error::SplitAtDomainEnd { .. }) if t < 0.5 => 0.0,
                Err(Error::SplitAtDomainEnd { .. }) => total.length,
                Err(e) => panic!("{e:?}"),
            };
            assert!(
                (measured - s).abs() <= tolerance + 2e-11,
                "s = {s}: L(t) = {measured}"
            );
        }
        let ts = curve.divide_by_length(5, tolerance).unwrap();
        assert!(ts.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!((ts[0], ts[5]), (0.0, 1.0));
    }
}

#[test]
fn length_parameter_errors_are_named() {
    let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(3.0, 4.0)]).unwrap();
    for s in [-1.0, 5.5, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(
                c.parameter_at_length(s, 1e-9),
                Err(Error::LengthOutOfRange { .. })
            ),
            "{s}"
        );
    }
    // Within the tolerance of the end: the end.
    assert_eq!(c.parameter_at_length(5.0 + 1e-10, 1e-9), Ok(1.0));
    for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.parameter_at_length(1.0, tol),
            Err(Error::InvalidTolerance { .. })
        ));
        assert!(matches!(
            c.divide_by_length(2, tol),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    assert_eq!(c.divide_by_length(0, 1e-9), Err(Error::ZeroPieces));
    assert!(matches!(
        c.divide_by_length(usize::MAX, 1e-9),
        Err(Error::TooManySegments { .. })
    ));
    assert!(matches!(
        c.parameter_at_length(1.0, 1e-300),
        Err(Error::ToleranceTooSmall { .. })
    ));
}

/// A user's curve without spans: a unit-speed line, `C(t) = (t, 0)` on [0, 2].
struct Line;

impl Curve<2> for Line {
    fn domain(&self) -> (f64, f64) {
        (0.0, 2.0)
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        Point2::new(t.clamp(0.0, 2.0), 0.0)
    }
    fn derivative(&self, _: f64) -> Vector2<f64> {
        Vector2::new(1.0, 0.0)
    }
}

#[test]
fn length_parameter_on_a_curve_without_spans() {
    let t = Line.parameter_at_length(0.7, 1e-10).unwrap();
    assert!((t - 0.7).abs() <= 1e-10);
    let ts = Line.divide_by_length(4, 1e-10).unwrap();
    for (i, t) in ts.iter().enumerate() {
        assert!((t - 0.5 * i as f64).abs() <= 1e-10);
    }
}

// ---------------------------------------------------------------------------
// 5. Knot removal
// ---------------------------------------------------------------------------

#[test]
fn inserting_then_removing_gives_back_the_control_points() {
    let mut rng = Rng(40);
    for degree in 1..=5 {
        let n = degree + 4;
        let c = BSpline::clamped(degree, random_points::<3>(&mut rng, n)).unwrap();
        for &(u, times) in &[(0.37, 1), (0.61, degree.min(2)), (0.13, degree)] {
            let refined = c.insert_knot(u, times).unwrap();
            let (back, removed) = refined.remove_knot(u, times, 1e-9).unwrap();
            assert_eq!(removed, times, "degree {degree}, u = {u}");
            assert_eq!(back.knots(), c.knots());
            for (a, b) in back.points().iter().zip(c.points()) {
                assert!((a - b).amax() <= 1e-12, "{a:?} against {b:?}");
            }
            // Asking for more removals than the inserted ones stops at them
            // (the original's knots are essential for random points).
            let (_, more) = refined.remove_knot(u, times + 3, 1e-9).unwrap();
            assert_eq!(more, times);
        }
        // NURBS: the same with random weights.
        let weights: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 2.0)).collect();
        let r = Nurbs::new(
            degree,
            c.knots().to_vec(),
            c.points().to_vec(),
            weights.clone(),
        )
        .unwrap();
        let refined = r.insert_knot(0.42, degree).unwrap();
        let (back, removed) = refined.remove_knot(0.42, degree, 1e-9).unwrap();
        assert_eq!(removed, degree);
        assert_eq!(back.knots(), r.knots());
        for ((a, b), (v, w)) in back
            .points()
            .iter()
            .zip(r.points())
            .zip(back.weights().iter().zip(&weights))
        {
            assert!((a - b).amax() <= 1e-11, "{a:?} against {b:?}");
            assert!((v - w).abs() <= 1e-12 * w);
        }
    }
}

#[test]
fn essential_knots_are_not_removed() {
    // A degree-1 polyline with a real corner at its interior knot.
    let corner = BSpline::clamped(
        1,
        vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(2.0, 0.0),
        ],
    )
    .unwrap();
    let (same, removed) = corner.remove_knot(0.5, 1, 0.1).unwrap();
    assert_eq!(removed, 0);
    assert_eq!(same, corner);
    // With a tolerance beyond the corner's distance to the chord (1), it goes:
    // the bound is |P₁ − (P₀ + P₂)/2| = 1.
    let (line, removed) = corner.remove_knot(0.5, 1, 1.0 + 1e-12).unwrap();
    assert_eq!(removed, 1);
    assert_eq!(line.points().len(), 2);
    for s in spline_samples((0.0, 1.0), 20) {
        // The promise: within the tolerance everywhere.
        assert!((line.eval(s) - corner.eval(s)).norm() <= 1.0 + 1e-12);
    }
    // The circle's quarter knots are essential for NURBS too.
    let circle = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    assert_eq!(circle.remove_knot(0.5, 2, 1e-6).unwrap().1, 0);
    // A random cubic's interior knots are essential.
    let c = BSpline::clamped(3, random_points::<2>(&mut Rng(41), 7)).unwrap();
    for &u in &c.knots()[4..7] {
        assert_eq!(c.remove_knot(u, 1, 1e-9).unwrap().1, 0);
    }
}

#[test]
fn removal_within_tolerance_stays_within_it() {
    // Removing a knot from a slightly perturbed refined curve: accepted
    // only when the perturbation's effect is within the tolerance, and then
    // the curves are within the tolerance everywhere (checked densely).
    let c = BSpline::clamped(3, random_points::<2>(&mut Rng(42), 6)).unwrap();
    let refined = c.insert_knot(0.4, 1).unwrap();
    let mut points = refined.points().to_vec();
    points[3].x += 1e-4;
    let bumped = BSpline::new(3, refined.knots().to_vec(), points).unwrap();
    assert_eq!(bumped.remove_knot(0.4, 1, 1e-6).unwrap().1, 0);
    let (smooth, removed) = bumped.remove_knot(0.4, 1, 1e-3).unwrap();
    assert_eq!(removed, 1);
    for s in spline_samples((0.0, 1.0), 400) {
        assert!((smooth.eval(s) - bumped.eval(s)).norm() <= 1e-3);
    }
}

#[test]
fn knot_removal_errors_are_named() {
    let c = BSpline::clamped(2, random_points::<2>(&mut Rng(43), 5)).unwrap();
    for t in [0.0, 1.0, 0.2, f64::NAN, 2.0] {
        assert!(matches!(
            c.remove_knot(t, 1, 1e-9),
            Err(Error::NotAnInteriorKnot { .. })
        ));
    }
    for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.remove_knot(1.0 / 3.0, 1, tol),
            Err(Error::InvalidTolerance { .. })
        ));
    }
    let circle = Nurbs::circle(Point2::origin(), 1.0).unwrap();
    assert!(matches!(
        circle.remove_knot(0.3, 1, 1e-9),
        Err(Error::NotAnInteriorKnot { .. })
    ));
    assert!(matches!(
        circle.remove_knot(0.25, 1, 0.0),
        Err(Error::InvalidTolerance { .. })
    ));
    // Zero removals asked: a copy.
    assert_eq!(c.remove_knot(1.0 / 3.0, 0, 1e-9).unwrap(), (c.clone(), 0));
}

// ---------------------------------------------------------------------------
// 6. 3D arcs and elliptic arcs
// ---------------------------------------------------------------------------

#[test]
fn arcs_in_space_lie_on_their_circle_and_plane() {
    let mut rng = Rng(50);
    for i in 0..100 {
        // Half about the origin (checked to 1e-15·r), half about a far
        // centre (whose coordinates' rounding, 16ε·(|c| + r), is added).
        let center = if i % 2 == 0 {
            Point3::origin()
        } else {
            rng.point3(10.0)
        };
        let normal = rng.point3(1.0).coords;
        let start_dir = rng.point3(1.0).coords;
        let radius = rng.uniform(0.1, 5.0);
        let start = rng.uniform(-7.0, 7.0);
        let sweep = rng.uniform(0.1, std::f64::consts::TAU);
        let arc = Nurbs::arc_3d(center, normal, start_dir, radius, start, start + sweep).unwrap();
        let n = normal.normalize();
        let e1 = (start_dir - n * start_dir.dot(&n)).normalize();
        let e2 = n.cross(&e1);
        for s in spline_samples((0.0, 1.0), 64) {
            let p = arc.eval(s) - center;
            // On the circle to 1e-15·r (plus the centre's rounding, ε·|c|)
            // and in the plane to the same.
            let slack =
                1e-15 * radius + 16.0 * EPS * (center.coords.amax() + radius) * f64::from(i % 2);
            assert!(
                (p.norm() - radius).abs() <= slack,
                "radius {} against {radius}",
                p.norm()
            );
            // The plane: the control points' and the reference normal's
            // rounding, 16ε·r, beside the slack.
            assert!(
                p.dot(&n).abs() <= slack + 16.0 * EPS * radius,
                "off the plane by {}",
                p.dot(&n)
            );
        }
        // The ends at the angles given, counter-clockwise about the normal.
        let at = |theta: f64| center + (e1 * theta.cos() + e2 * theta.sin()) * radius;
        assert!((arc.eval(0.0) - at(start)).norm() <= 1e-14 * (radius + center.coords.amax()));
        assert!(
            (arc.eval(1.0) - at(start + sweep)).norm() <= 1e-14 * (radius + center.coords.amax())
        );
        // Counter-clockwise: (C − c) × C′ points along the normal.
        let d = arc.derivative(0.5);
        assert!((arc.eval(0.5) - center).cross(&d).dot(&n) > 0.0);
    }
}

#[test]
fn elliptic_arcs_satisfy_the_ellipse_equation() {
    let mut rng = Rng(51);
    for _ in 0..50 {
        let center = rng.point2(10.0);
        let (a, b) = (rng.uniform(0.1, 5.0), rng.uniform(0.1, 5.0));
        let start = rng.uniform(-7.0, 7.0);
        let sweep = rng.uniform(0.1, std::f64::consts::TAU);
        let e = Nurbs::ellipse_arc(center, (a, b), start, start + sweep).unwrap();
        for s in spline_samples((0.0, 1.0), 64) {
            let p = e.eval(s) - center;
            let slack = 1e-15 + 8.0 * EPS * center.coords.amax() / a.min(b);
            assert!(((p.x / a).powi(2) + (p.y / b).powi(2) - 1.0).abs() <= slack);
        }
        let at = |t: f64| center + Vector2::new(a * t.cos(), b * t.sin());
        assert!((e.eval(0.0) - at(start)).norm() <= 1e-14 * (a + b + center.coords.amax()));
        assert!((e.eval(1.0) - at(start + sweep)).norm() <= 1e-14 * (a + b + center.coords.amax()));
    }
}

#[test]
fn conic_errors_are_named() {
    let c = Point3::origin();
    let (z, x) = (Vector3::z(), Vector3::x());
    assert!(matches!(
        Nurbs::arc_3d(Point3::new(f64::NAN, 0.0, 0.0), z, x, 1.0, 0.0, 1.0),
        Err(Error::InvalidCenter3 { .. })
    ));
    assert!(matches!(
        Nurbs::arc_3d(Point3::new(1e101, 0.0, 0.0), z, x, 1.0, 0.0, 1.0),
        Err(Error::InvalidCenter3 { .. })
    ));
    for (n, d) in [
        (Vector3::zeros(), x),
        (z, Vector3::zeros()),
        (z, z * -3.0),
        (Vector3::new(f64::NAN, 0.0, 1.0), x),
        (z, Vector3::new(0.0, f64::INFINITY, 0.0)),
    ] {
        assert!(
            matches!(
                Nurbs::arc_3d(c, n, d, 1.0, 0.0, 1.0),
                Err(Error::InvalidArcFrame { .. })
            ),
            "{n:?} {d:?}"
        );
    }
    for r in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e101] {
        assert!(matches!(
            Nurbs::arc_3d(c, z, x, r, 0.0, 1.0),
            Err(Error::InvalidRadius { .. })
        ));
        assert!(matches!(
            Nurbs::ellipse_arc(Point2::origin(), (r, 1.0), 0.0, 1.0),
            Err(Error::InvalidRadius { .. })
        ));
        assert!(matches!(
            Nurbs::ellipse_arc(Point2::origin(), (1.0, r), 0.0, 1.0),
            Err(Error::InvalidRadius { .. })
        ));
    }
    for (s, e) in [(1.0, 1.0), (1.0, 0.0), (0.0, 7.0), (f64::NAN, 1.0)] {
        assert!(matches!(
            Nurbs::arc_3d(c, z, x, 1.0, s, e),
            Err(Error::InvalidSweep { .. })
        ));
        assert!(matches!(
            Nurbs::ellipse_arc(Point2::origin(), (1.0, 2.0), s, e),
            Err(Error::InvalidSweep { .. })
        ));
    }
    assert!(matches!(
        Nurbs::ellipse_arc(Point2::new(0.0, f64::NAN), (1.0, 2.0), 0.0, 1.0),
        Err(Error::InvalidCenter { .. })
    ));
    // A control point beyond the limit: a centre at the limit plus a radius.
    assert!(matches!(
        Nurbs::arc_3d(Point3::new(1e100, 0.0, 0.0), z, x, 1e100, 0.0, 1.0),
        Err(Error::CoordinateTooLarge { .. })
    ));
}

// ---------------------------------------------------------------------------
// 7. Frenet frame
// ---------------------------------------------------------------------------

#[test]
fn frenet_frame_of_a_circle_in_space() {
    let mut rng = Rng(60);
    for _ in 0..20 {
        let center = rng.point3(5.0);
        let normal = rng.point3(1.0).coords;
        let radius = rng.uniform(0.2, 4.0);
        let arc = Nurbs::arc_3d(center, normal, rng.point3(1.0).coords, radius, 0.0, 5.0).unwrap();
        let n = normal.normalize();
        for s in spline_samples((0.0, 1.0), 32) {
            let f = arc.frenet_frame(s).unwrap();
            // Closed form: κ = 1/r, τ = 0, B = n, N toward the centre.
            assert!(
                (f.curvature * radius - 1.0).abs() <= 1e-12,
                "κ·r = {}",
                f.curvature * radius
            );
            assert!(f.torsion.abs() * radius <= 1e-10, "τ = {}", f.torsion);
            assert!((f.binormal.into_inner() - n).norm() <= 1e-12);
            let inward = (center - arc.eval(s)).normalize();
            assert!((f.normal.into_inner() - inward).norm() <= 1e-12);
            assert!((f.tangent.into_inner() - arc.derivative(s).normalize()).norm() <= 1e-14);
            // Orthonormal, right-handed.
            assert!(f.tangent.cross(&f.normal).dot(&f.binormal) > 1.0 - 1e-14);
        }
    }
}

/// Curvature and torsion from central differences of the points: step
/// `h`, errors `O(h²)` in the derivatives and `ε·|C|/h³` from rounding:
/// about 1e-4 relative (τ, large near an inflection, loses more: 1e-3).
fn fd_curvature_torsion(c: &impl Curve<3>, t: f64, h: f64) -> (f64, f64) {
    let p = |k: f64| c.eval(t + k * h).coords;
    let d1 = (p(1.0) - p(-1.0)) / (2.0 * h);
    let d2 = (p(1.0) - 2.0 * p(0.0) + p(-1.0)) / (h * h);
    let d3 = (p(2.0) - 2.0 * p(1.0) + 2.0 * p(-1.0) - p(-2.0)) / (2.0 * h * h * h);
    let cross = d1.cross(&d2);
    (
        cross.norm() / d1.norm().powi(3),
        cross.dot(&d3) / cross.norm_squared(),
    )
}

#[test]
fn frenet_frame_of_random_cubics_against_finite_differences() {
    let mut rng = Rng(61);
    for _ in 0..30 {
        let points = random_points::<3>(&mut rng, 4);
        let bez = Bezier::new(points.clone()).unwrap();
        let spl = BSpline::clamped(3, points.clone()).unwrap();
        let weights: Vec<f64> = (0..4).map(|_| rng.uniform(0.5, 2.0)).collect();
        let rat = RationalBezier::new(points.clone(), weights.clone()).unwrap();
        let nrb = Nurbs::new(3, spl.knots().to_vec(), points, weights).unwrap();
        for &t in &[0.2, 0.5, 0.8] {
            let fb = bez.frenet_frame(t).unwrap();
            let (k, tau) = fd_curvature_torsion(&bez, t, 1e-3);
            assert!(
                (fb.curvature - k).abs() <= 1e-4 * k.max(1.0),
                "κ {} against {k}",
                fb.curvature
            );
            assert!(
                (fb.torsion - tau).abs() <= 1e-3 * tau.abs().max(1.0),
                "τ {} against {tau}",
                fb.torsion
            );
            // The clamped cubic on four points is the Bézier curve.
            let fs = spl.frenet_frame(t).unwrap();
            assert!((fs.curvature - fb.curvature).abs() <= 1e-10 * fb.curvature.max(1.0));
            assert!((fs.torsion - fb.torsion).abs() <= 1e-8 * fb.torsion.abs().max(1.0));
            let fr = rat.frenet_frame(t).unwrap();
            let (k, tau) = fd_curvature_torsion(&rat, t, 1e-3);
            assert!(
                (fr.curvature - k).abs() <= 1e-4 * k.max(1.0),
                "κ {} against {k}",
                fr.curvature
            );
            assert!(
                (fr.torsion - tau).abs() <= 1e-3 * tau.abs().max(1.0),
                "τ {} against {tau}",
                fr.torsion
            );
            let fnr = nrb.frenet_frame(t).unwrap();
            assert!((fnr.curvature - fr.curvature).abs() <= 1e-10 * fr.curvature.max(1.0));
            assert!((fnr.torsion - fr.torsion).abs() <= 1e-8 * fr.torsion.abs().max(1.0));
            assert!((fnr.normal.into_inner() - fr.normal.into_inner()).norm() <= 1e-10);
        }
    }
}

#[test]
fn frenet_frame_is_none_where_undefined() {
    // A straight line: C′ × C″ = 0.
    let line = Bezier::new(vec![
        Point3::origin(),
        Point3::new(1.0, 2.0, 3.0),
        Point3::new(3.0, 6.0, 9.0),
    ])
    .unwrap();
    assert!(line.frenet_frame(0.3).is_none());
    // C′ = 0 at the start (a repeated control point).
    let cusp = Bezier::new(vec![
        Point3::origin(),
        Point3::origin(),
        Point3::new(1.0, 1.0, 0.0),
        Point3::new(2.0, 0.0, 1.0),
    ])
    .unwrap();
    assert!(cusp.frenet_frame(0.0).is_none());
    assert!(cusp.frenet_frame(0.5).is_some());
    // NaN parameters evaluate at the start; never a NaN frame.
    let arc = Nurbs::arc_3d(Point3::origin(), Vector3::z(), Vector3::x(), 1.0, 0.0, 1.0).unwrap();
    let f = arc.frenet_frame(f64::NAN).unwrap();
    assert!(f.curvature.is_finite() && f.torsion.is_finite());
    let spl = BSpline::clamped(1, vec![Point3::origin(), Point3::new(1.0, 0.0, 0.0)]).unwrap();
    assert!(spl.frenet_frame(0.5).is_none());
    let rat = RationalBezier::new(
        vec![Point3::origin(), Point3::new(1.0, 0.0, 0.0)],
        vec![1.0, 3.0],
    )
    .unwrap();
    assert!(rat.frenet_frame(0.5).is_none());
}

#[test]
fn new_errors_name_the_problem() {
    let cases = [
        (
            Error::SplitAtDomainEnd {
                t: 1.0,
                domain: (0.0, 1.0),
            },
            "cannot split at 1",
        ),
        (Error::InvalidTransform, "NaN or infinite entry"),
        (
            Error::ProjectiveWeightNotPositive {
                index: 2,
                weight: -0.5,
            },
            "control point 2 the weight -0.5",
        ),
        (
            Error::LengthOutOfRange {
                s: 7.0,
                length: 5.0,
            },
            "arc length 7 is outside [0, 5]",
        ),
        (Error::ZeroPieces, "zero pieces"),
        (
            Error::NotAnInteriorKnot { t: 0.3 },
            "0.3 is not an interior knot",
        ),
        (
            Error::InvalidCenter3 {
                center: [f64::NAN, 0.0, 0.0],
            },
            "arc center (NaN, 0, 0)",
        ),
        (
            Error::InvalidArcFrame {
                normal: [0.0; 3],
                start_dir: [1.0, 0.0, 0.0],
            },
            "not parallel",
        ),
    ];
    for (error, text) in cases {
        assert!(error.to_string().contains(text), "{error}");
    }
}

// ---------------------------------------------------------------------------
// Property tests: split, transforms and the length parameter on random
// NURBS curves
// ---------------------------------------------------------------------------

mod properties {
    use super::{EPS, Rng, random_affine2, random_points};
    use proptest::prelude::*;
    use revolve::{Curve, Nurbs};

    /// A clamped NURBS of degree `p` on `n` random points with weights in
    /// `[0.2, 5]` and random increasing knots.
    fn random_nurbs(seed: u64, p: usize, n: usize) -> Nurbs<2> {
        let mut rng = Rng(seed);
        let points = random_points::<2>(&mut rng, n);
        let weights = (0..n).map(|_| rng.uniform(0.2, 5.0)).collect();
        let mut inner: Vec<f64> = (0..n - p - 1).map(|_| rng.uniform(0.0, 1.0)).collect();
        inner.sort_by(f64::total_cmp);
        let mut knots = vec![0.0; p + 1];
        knots.extend(inner);
        knots.extend(vec![1.0; p + 1]);
        Nurbs::new(p, knots, points, weights).unwrap()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, ..ProptestConfig::default() })]

        /// The halves of a split are the curve on either side of the cut,
        /// at the same parameters.
        #[test]
        fn split_halves_are_the_curve(
            seed in any::<u64>(), p in 1usize..=5, extra in 0usize..6, cut in 0.01f64..0.99,
        ) {
            let c = random_nurbs(seed, p, p + 1 + extra);
            let (l, r) = c.split(cut).unwrap();
            prop_assert_eq!(l.domain(), (0.0, cut));
            prop_assert_eq!(r.domain(), (cut, 1.0));
            for k in 0..=50 {
                let s = k as f64 / 50.0;
                let half = if s < cut { &l } else { &r };
                prop_assert!((half.eval(s) - c.eval(s)).amax() <= 1e4 * EPS, "at {}", s);
            }
        }

        /// An affine map of the control points is the map of the curve.
        #[test]
        fn affine_maps_commute_with_evaluation(
            seed in any::<u64>(), p in 1usize..=5, extra in 0usize..6,
        ) {
            let c = random_nurbs(seed, p, p + 1 + extra);
            let map = random_affine2(&mut Rng(seed ^ 0x5eed));
            let image = c.transformed(&map);
            for k in 0..=40 {
                let s = k as f64 / 40.0;
                prop_assert!((map * c.eval(s) - image.eval(s)).amax() <= 1e4 * EPS, "at {}", s);
            }
        }

        /// The parameter at a length is where the arc length from the
        /// start reaches it (within the tolerance asked for).
        #[test]
        fn the_parameter_at_a_length_has_that_length(
            seed in any::<u64>(), p in 1usize..=4, extra in 0usize..4, fraction in 0.0f64..=1.0,
        ) {
            let c = random_nurbs(seed, p, p + 1 + extra);
            let total = c.arc_length(1e-10).unwrap().length;
            let tolerance = 1e-8 * total.max(1e-300);
            let u = c.parameter_at_length(fraction * total, tolerance).unwrap();
            prop_assert!((0.0..=1.0).contains(&u));
            let (head, _) = if u > 0.0 && u < 1.0 { c.split(u).unwrap() } else { (c.clone(), c.clone()) };
            let reached = if u <= 0.0 { 0.0 } else if u >= 1.0 { total } else {
                head.arc_length(1e-10).unwrap().length
            };
            prop_assert!((reached - fraction * total).abs() <= tolerance + 1e-9 * total,
                "{} vs {}", reached, fraction * total);
        }
    }
}

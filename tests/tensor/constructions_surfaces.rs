//! Surface constructions: clamped and uniform B-spline surfaces and the flat
//! constructors (against the curves' knots and `new`), ruled surfaces (the
//! hyperbolic paraboloid `z = xy` between two skew lines; curves of
//! different degrees and knots against `(1 − v)A(u) + vB(φ(u))`), extrusions
//! (the cylinder `x² + y² = r²`) and translational sweeps (a circle along a
//! line is a cylinder; a rational profile along a rational path against
//! `P(u) + T(v) − T(v₀)`), isocurves against the surface's points, splits
//! against the surface at the mapped parameters, affine maps commuting with
//! evaluation (`T(S(u, v)) = S'(u, v)`, normals by the inverse transpose),
//! bilinear surfaces against their formula, boundary curves against the
//! surface at the domain's ends, and every error path with its variant. Tolerances are a few ulps of the
//! size (1e-14 relative unless stated).

use revolve_testkit as common;

use common::random_tensors::Xorshift64Star as Rng;
use revolve::nalgebra::{Affine3, Matrix4, Point2, Point3, Vector3};
use revolve::{
    BSpline, BSplineSurface, BezierSurface, Curve, Error, Nurbs, NurbsSurface, ParameterDirection,
    Surface,
};

fn close(a: Point3<f64>, b: Point3<f64>, tol: f64) -> bool {
    (a - b).norm() <= tol
}

/// A 3D NURBS from a 2D one in the plane `z = z0`.
fn lift(c: &Nurbs<2>, z0: f64) -> Nurbs<3> {
    let points = c
        .points()
        .iter()
        .map(|p| Point3::new(p.x, p.y, z0))
        .collect();
    Nurbs::new(c.degree(), c.knots().to_vec(), points, c.weights().to_vec()).unwrap()
}

/// The knots of a clamped curve of `degree` on `n` points.
fn clamped_knots(degree: usize, n: usize) -> Vec<f64> {
    BSpline::clamped(degree, vec![Point2::origin(); n])
        .unwrap()
        .knots()
        .to_vec()
}

fn line(p: Point3<f64>, q: Point3<f64>) -> Nurbs<3> {
    Nurbs::from(BSpline::clamped(1, vec![p, q]).unwrap())
}

fn grid(rng: &mut Rng, rows: usize, cols: usize) -> Vec<Vec<Point3<f64>>> {
    rng.grid(rows, cols)
}

/// `n + 1` parameters spread over `(a, b)`, ends included.
fn params((a, b): (f64, f64), n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |k| a + (b - a) * k as f64 / n as f64)
}

// ---------------------------------------------------------------------------
// Clamped, uniform and flat constructors
// ---------------------------------------------------------------------------

#[test]
fn clamped_and_uniform_take_the_curves_knots() {
    let mut rng = Rng(7);
    for (rows, cols, p, q) in [(4, 3, 2, 1), (5, 5, 3, 3), (2, 6, 1, 4), (3, 3, 0, 2)] {
        let g = grid(&mut rng, rows, cols);
        for clamped in [true, false] {
            let (s, ku, kv) = if clamped {
                let s = BSplineSurface::clamped((p, q), g.clone()).unwrap();
                let ku = BSpline::clamped(p, g.iter().map(|r| r[0]).collect()).unwrap();
                let kv = BSpline::clamped(q, g[0].clone()).unwrap();
                (s, ku.knots().to_vec(), kv.knots().to_vec())
            } else {
                let s = BSplineSurface::uniform((p, q), g.clone()).unwrap();
                let ku = BSpline::uniform(p, g.iter().map(|r| r[0]).collect()).unwrap();
                let kv = BSpline::uniform(q, g[0].clone()).unwrap();
                (s, ku.knots().to_vec(), kv.knots().to_vec())
            };
            assert_eq!(s.knots().0, &ku[..]);
            assert_eq!(s.knots().1, &kv[..]);
            let same = BSplineSurface::new((p, q), (ku, kv), g.clone()).unwrap();
            assert_eq!(s, same);
        }
        // The clamped surface passes through its corners.
        let s = BSplineSurface::clamped((p, q), g.clone()).unwrap();
        assert!(close(s.eval(0.0, 0.0), g[0][0], 1e-14));
        assert!(close(s.eval(1.0, 1.0), g[rows - 1][cols - 1], 1e-14));
    }
}

#[test]
fn clamped_and_uniform_errors_name_the_direction() {
    let g = vec![vec![Point3::origin(); 3]; 2];
    let e = BSplineSurface::clamped((2, 1), g.clone()).unwrap_err();
    assert_eq!(
        e,
        Error::SurfaceKnots {
            direction: ParameterDirection::U,
            error: Box::new(Error::DegreeTooHigh {
                degree: 2,
                points: 2
            })
        }
    );
    let e = BSplineSurface::uniform((1, 3), g.clone()).unwrap_err();
    assert!(
        matches!(e, Error::SurfaceKnots { direction: ParameterDirection::V, ref error }
        if **error == Error::DegreeTooHigh { degree: 3, points: 3 })
    );
    assert_eq!(
        BSplineSurface::clamped((1, 1), vec![]),
        Err(Error::EmptyGrid)
    );
    let ragged = vec![vec![Point3::origin(); 3], vec![Point3::origin(); 2]];
    assert!(matches!(
        BSplineSurface::uniform((1, 1), ragged),
        Err(Error::RaggedGrid {
            row: 1,
            expected: 3,
            found: 2
        })
    ));
    let mut bad = vec![vec![Point3::origin(); 3]; 3];
    bad[2][1].y = f64::NAN;
    assert_eq!(
        BSplineSurface::clamped((1, 1), bad),
        Err(Error::NonFiniteGridPoint { row: 2, column: 1 })
    );
}

#[test]
fn flat_constructors_cut_rows() {
    let mut rng = Rng(11);
    let g = grid(&mut rng, 3, 4);
    let flat: Vec<Point3<f64>> = g.iter().flatten().copied().collect();
    assert_eq!(
        BezierSurface::from_flat(&flat, 3).unwrap(),
        BezierSurface::new(g.clone()).unwrap()
    );
    let knots = (clamped_knots(2, 3), clamped_knots(1, 4));
    assert_eq!(
        BSplineSurface::from_flat((2, 1), knots.clone(), &flat, 3).unwrap(),
        BSplineSurface::new((2, 1), knots.clone(), g.clone()).unwrap()
    );
    let w: Vec<Vec<f64>> = rng.weights(3, 4);
    let wflat: Vec<f64> = w.iter().flatten().copied().collect();
    assert_eq!(
        NurbsSurface::from_flat((2, 1), knots.clone(), &flat, &wflat, 3).unwrap(),
        NurbsSurface::new((2, 1), knots.clone(), g.clone(), w).unwrap()
    );
    // Errors: length not a multiple of rows, zero rows, empty, weights.
    let e = Error::FlatGridLength {
        length: 12,
        rows: 5,
    };
    assert_eq!(BezierSurface::from_flat(&flat, 5), Err(e.clone()));
    assert_eq!(
        BSplineSurface::from_flat((2, 1), knots.clone(), &flat, 5),
        Err(e.clone())
    );
    assert_eq!(
        NurbsSurface::from_flat((2, 1), knots.clone(), &flat, &wflat, 5),
        Err(e)
    );
    assert_eq!(
        BezierSurface::from_flat(&flat, 0),
        Err(Error::FlatGridLength {
            length: 12,
            rows: 0
        })
    );
    assert_eq!(BezierSurface::from_flat(&[], 2), Err(Error::EmptyGrid));
    assert_eq!(
        NurbsSurface::from_flat((2, 1), knots.clone(), &flat, &wflat[..11], 3),
        Err(Error::WeightCount {
            expected: 12,
            found: 11
        })
    );
    let mut bad_w = wflat.clone();
    bad_w[6] = -1.0;
    assert_eq!(
        NurbsSurface::from_flat((2, 1), knots.clone(), &flat, &bad_w, 3),
        Err(Error::InvalidGridWeight {
            row: 1,
            column: 2,
            weight: -1.0
        })
    );
    let mut bad = flat.clone();
    bad[5].x = f64::INFINITY;
    assert_eq!(
        BSplineSurface::from_flat((2, 1), knots, &bad, 3),
        Err(Error::NonFiniteGridPoint { row: 1, column: 1 })
    );
    let e = BezierSurface::from_flat(&flat, 5).unwrap_err().to_string();
    assert!(e.contains("12") && e.contains("5 rows"), "{e}");
}

// ---------------------------------------------------------------------------
// Ruled surfaces
// ---------------------------------------------------------------------------

#[test]
fn ruled_between_two_skew_lines_is_the_hyperbolic_paraboloid() {
    // A(u) = (u, 0, 0), B(u) = (u, 1, u): S = (u, v, uv), so z = x·y.
    let a = line(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0));
    let b = line(Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0));
    let s = NurbsSurface::ruled(&a, &b).unwrap();
    assert_eq!(s.degrees(), (1, 1));
    for u in params((0.0, 1.0), 10) {
        for v in params((0.0, 1.0), 10) {
            let p = s.eval(u, v);
            assert!(close(p, Point3::new(u, v, u * v), 1e-15), "{u} {v}");
            assert!((p.z - p.x * p.y).abs() < 1e-15);
            // The normal of z = xy: ∝ (−y, −x, 1), on the side of +z.
            let n = s.normal(u, v).unwrap();
            let want = Vector3::new(-v, -u, 1.0).normalize();
            assert!((n.into_inner() - want).norm() < 1e-14);
        }
    }
    // The same lines on another domain, traced with a reparametrized b.
    let b2 = Nurbs::new(
        1,
        vec![3.0, 3.0, 7.0, 7.0],
        b.points().to_vec(),
        vec![1.0, 1.0],
    )
    .unwrap();
    let s2 = NurbsSurface::ruled(&a, &b2).unwrap();
    for u in params((0.0, 1.0), 7) {
        for v in params((0.0, 1.0), 7) {
            assert!(close(s2.eval(u, v), Point3::new(u, v, u * v), 1e-15));
        }
    }
}

#[test]
fn ruled_between_curves_of_different_degrees_and_knots() {
    // a: a clamped cubic on [0, 1] with an interior knot; b: a uniform
    // (unclamped) quadratic on its own domain. Both polynomial: the surface
    // is (1 − v)A(u) + vB(φ(u)) with φ linear from a's domain onto b's.
    let mut rng = Rng(3);
    let pa: Vec<Point3<f64>> = (0..5).map(|_| rng.point()).collect();
    let pb: Vec<Point3<f64>> = (0..6).map(|_| rng.point()).collect();
    let a = Nurbs::from(
        BSpline::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0, 1.0],
            pa.clone(),
        )
        .unwrap(),
    );
    let b = Nurbs::from(BSpline::uniform(2, pb.clone()).unwrap());
    let s = NurbsSurface::ruled(&a, &b).unwrap();
    assert_eq!(s.degrees(), (3, 1));
    assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
    let (b0, b1) = b.domain();
    for u in params((0.0, 1.0), 23) {
        let bu = b.eval(b0 + (b1 - b0) * u);
        for v in params((0.0, 1.0), 5) {
            let want = Point3::from(a.eval(u).coords * (1.0 - v) + bu.coords * v);
            assert!(close(s.eval(u, v), want, 1e-14), "{u} {v}");
        }
    }
}

#[test]
fn ruled_between_rational_curves_puts_each_isocurve_on_the_segment() {
    // A circle of radius 1 in z = 0 and one of radius 2 in z = 1: a cone
    // frustum; the weights agree (same circle construction), so the
    // parametrization is linear in v.
    let a = lift(&Nurbs::circle(Point2::origin(), 1.0).unwrap(), 0.0);
    let b = lift(&Nurbs::circle(Point2::origin(), 2.0).unwrap(), 1.0);
    let s = NurbsSurface::ruled(&a, &b).unwrap();
    for u in params((0.0, 1.0), 40) {
        for v in params((0.0, 1.0), 6) {
            let p = s.eval(u, v);
            assert!((p.x.hypot(p.y) - (1.0 + v)).abs() < 1e-14);
            assert!((p.z - v).abs() < 1e-15);
        }
    }
    // Against a quadratic arc with other weights: every point lies on the
    // segment from A(u) to B(u).
    let c = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Point3::new(0.0, 0.0, 2.0),
            Point3::new(1.0, 3.0, 2.0),
            Point3::new(2.0, 0.0, 2.0),
        ],
        vec![1.0, 5.0, 1.0],
    )
    .unwrap();
    let s = NurbsSurface::ruled(&a, &c).unwrap();
    for u in params((0.0, 1.0), 17) {
        let (pa, pc) = (a.eval(u), c.eval(u));
        for v in params((0.0, 1.0), 5) {
            let p = s.eval(u, v);
            let along = (p - pa).cross(&(pc - pa)).norm();
            assert!(along < 1e-13 * (pc - pa).norm_squared().max(1.0), "{u} {v}");
        }
        assert!(close(s.eval(u, 0.0), pa, 1e-14));
        assert!(close(s.eval(u, 1.0), pc, 1e-14));
    }
}

#[test]
fn ruled_errors_come_from_the_compatibility_steps() {
    // Raising a line to a degree beyond the supported one.
    let high = revolve::curve::MAX_ELEVATED_DEGREE + 1;
    let pts: Vec<Point3<f64>> = (0..=high)
        .map(|i| Point3::new(i as f64, 0.0, 0.0))
        .collect();
    let big = Nurbs::from(BSpline::clamped(high, pts).unwrap());
    let low = line(Point3::origin(), Point3::new(0.0, 1.0, 0.0));
    let e = NurbsSurface::ruled(&low, &big).unwrap_err();
    assert!(matches!(e, Error::ElevationTooHigh { .. }), "{e:?}");
    let e = NurbsSurface::ruled(&big, &low).unwrap_err();
    assert!(matches!(e, Error::ElevationTooHigh { .. }), "{e:?}");
}

// ---------------------------------------------------------------------------
// Extrusions and sweeps
// ---------------------------------------------------------------------------

#[test]
fn extruded_circle_is_a_cylinder() {
    let r = 1.5;
    let circle = lift(&Nurbs::circle(Point2::new(1.0, -2.0), r).unwrap(), 0.5);
    let dir = Vector3::new(0.0, 0.0, 4.0);
    let s = NurbsSurface::extrude(&circle, dir).unwrap();
    assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
    for u in params((0.0, 1.0), 64) {
        for v in params((0.0, 1.0), 8) {
            let p = s.eval(u, v);
            assert!(((p.x - 1.0).hypot(p.y + 2.0) - r).abs() < 1e-14);
            assert!((p.z - (0.5 + 4.0 * v)).abs() < 1e-14);
            assert!(close(p, circle.eval(u) + dir * v, 1e-14));
            // The normal is horizontal, along ±(p − axis): C′ × V points
            // outward for a counter-clockwise circle and V = +z.
            let n = s.normal(u, v).unwrap();
            let radial = Vector3::new(p.x - 1.0, p.y + 2.0, 0.0) / r;
            assert!((n.into_inner() - radial).norm() < 1e-13, "{u} {v}");
        }
    }
}

#[test]
fn extrusion_errors() {
    let c = line(Point3::origin(), Point3::new(1.0, 0.0, 0.0));
    for v in [
        Vector3::zeros(),
        Vector3::new(f64::NAN, 0.0, 0.0),
        Vector3::new(0.0, f64::INFINITY, 1.0),
    ] {
        let e = NurbsSurface::extrude(&c, v).unwrap_err();
        assert!(matches!(e, Error::InvalidExtrusion { .. }), "{e:?}");
    }
    let far = Vector3::new(0.0, 0.0, revolve::MAX_COORDINATE);
    let c = line(Point3::new(0.0, 0.0, far.z), Point3::new(1.0, 0.0, 1.0));
    assert!(matches!(
        NurbsSurface::extrude(&c, far),
        Err(Error::GridCoordinateTooLarge {
            row: 0,
            column: 1,
            ..
        })
    ));
}

#[test]
fn swept_circle_along_a_line_is_a_cylinder() {
    let circle = lift(&Nurbs::circle(Point2::origin(), 2.0).unwrap(), 0.0);
    let path = line(Point3::new(3.0, 3.0, 1.0), Point3::new(3.0, 3.0, 6.0));
    let s = NurbsSurface::sweep(&circle, &path).unwrap();
    for u in params((0.0, 1.0), 50) {
        for v in params((0.0, 1.0), 9) {
            let p = s.eval(u, v);
            assert!((p.x.hypot(p.y) - 2.0).abs() < 1e-14);
            assert!((p.z - 5.0 * v).abs() < 1e-14);
        }
    }
}

#[test]
fn sweep_of_rational_curves_is_exactly_the_translational_surface() {
    // A rational profile (an ellipse-like arc with uneven weights) along a
    // rational path with an interior knot and an unclamped start: S equals
    // P(u) + T(v) − T(v₀) at every point.
    let profile = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        vec![
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(1.0, 2.0, 0.5),
            Point3::new(-1.0, 2.0, 0.0),
            Point3::new(-1.0, 0.0, 1.0),
        ],
        vec![1.0, 0.3, 2.0, 1.0],
    )
    .unwrap();
    let path = Nurbs::new(
        3,
        vec![0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0],
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.5, 2.0),
            Point3::new(2.0, -1.0, 3.0),
            Point3::new(3.0, 0.0, 5.0),
            Point3::new(4.0, 1.0, 4.0),
        ],
        vec![1.0, 4.0, 0.5, 2.0, 1.0],
    )
    .unwrap();
    let s = NurbsSurface::sweep(&profile, &path).unwrap();
    let (v0, v1) = path.domain();
    assert_eq!(s.domain(), [(0.0, 1.0), (v0, v1)]);
    let t0 = path.eval(v0);
    for u in params((0.0, 1.0), 21) {
        for v in params((v0, v1), 21) {
            let want = profile.eval(u) + (path.eval(v) - t0);
            assert!(close(s.eval(u, v), want, 1e-13), "{u} {v}");
        }
    }
    // At v₀ the surface is the profile.
    for u in params((0.0, 1.0), 9) {
        assert!(close(s.eval(u, v0), profile.eval(u), 1e-14));
    }
}

#[test]
fn sweep_errors_from_the_grid() {
    let huge = revolve::MAX_COORDINATE;
    let profile = line(Point3::new(huge, 0.0, 0.0), Point3::new(huge, 1.0, 0.0));
    let path = line(Point3::new(0.0, 0.0, 0.0), Point3::new(huge, 0.0, 0.0));
    let e = NurbsSurface::sweep(&profile, &path).unwrap_err();
    assert!(
        matches!(e, Error::GridCoordinateTooLarge { column: 1, .. }),
        "{e:?}"
    );
    // Product weights spanning too wide a range.
    let heavy = |a: f64, b: f64| {
        Nurbs::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Point3::origin(), Point3::new(1.0, 1.0, 1.0)],
            vec![a, b],
        )
        .unwrap()
    };
    let max = revolve::curve::MAX_WEIGHT_RATIO;
    let e = NurbsSurface::sweep(&heavy(1.0, max), &heavy(1.0, max)).unwrap_err();
    assert!(matches!(e, Error::WeightRatioTooLarge { .. }), "{e:?}");
}

// ---------------------------------------------------------------------------
// Isocurves, splits and affine maps
// ---------------------------------------------------------------------------

/// Random surfaces of every kind: a Bézier surface, a clamped B-spline
/// surface with interior (one double) knots, a uniform (unclamped) one, and
/// NURBS on both with random weights, each also reversed.
fn random_splines(seed: u64) -> (Vec<BezierSurface>, Vec<BSplineSurface>, Vec<NurbsSurface>) {
    let mut rng = Rng(seed);
    let mut beziers = Vec::new();
    let mut splines = Vec::new();
    let mut nurbs = Vec::new();
    for (rows, cols, p, q) in [(4, 3, 3, 2), (6, 5, 2, 3), (5, 7, 1, 2), (7, 4, 3, 1)] {
        let g = rng.grid(rows, cols);
        beziers.push(BezierSurface::new(rng.grid(p + 1, q + 1)).unwrap());
        let ku = common::random_tensors::clamped_knots(&mut rng, p, rows);
        let kv = common::random_tensors::clamped_knots(&mut rng, q, cols);
        let clamped = BSplineSurface::new((p, q), (ku.clone(), kv.clone()), g.clone()).unwrap();
        let uniform = BSplineSurface::uniform((p, q), g.clone()).unwrap();
        let w = rng.weights(rows, cols);
        nurbs.push(NurbsSurface::new((p, q), (ku, kv), g.clone(), w.clone()).unwrap());
        nurbs.push(
            NurbsSurface::new(
                (p, q),
                (uniform.knots().0.to_vec(), uniform.knots().1.to_vec()),
                g,
                w,
            )
            .unwrap()
            .reversed(),
        );
        splines.push(clamped);
        splines.push(uniform.reversed());
    }
    (beziers, splines, nurbs)
}

/// The parameters to test in a domain: spread ones, the ends, and the
/// interior knots.
fn test_params(domain: (f64, f64), knots: &[f64]) -> Vec<f64> {
    let mut t: Vec<f64> = params(domain, 13).collect();
    t.extend(
        knots
            .iter()
            .copied()
            .filter(|&k| k > domain.0 && k < domain.1),
    );
    t
}

/// Checks the isocurves of `s` against its points.
fn check_isocurves<S: Surface>(
    s: &S,
    knots: (&[f64], &[f64]),
    iso_u: impl Fn(f64) -> Result<Nurbs<3>, Error>,
    iso_v: impl Fn(f64) -> Result<Nurbs<3>, Error>,
) {
    let [du, dv] = s.domain();
    let size = 10.0;
    for u in test_params(du, knots.0) {
        let c = iso_u(u).unwrap();
        assert_eq!(c.domain(), dv);
        for v in test_params(dv, knots.1) {
            assert!(close(c.eval(v), s.eval(u, v), 1e-14 * size), "{u} {v}");
        }
    }
    for v in test_params(dv, knots.1) {
        let c = iso_v(v).unwrap();
        assert_eq!(c.domain(), du);
        for u in test_params(du, knots.0) {
            assert!(close(c.eval(u), s.eval(u, v), 1e-14 * size), "{u} {v}");
        }
    }
    // Errors name the direction and the domain.
    for bad in [f64::NAN, du.0 - 1.0, du.1 + 1e-9, f64::INFINITY] {
        let e = iso_u(bad).unwrap_err();
        assert!(
            matches!(e, Error::SurfaceParameterOutOfDomain { direction: ParameterDirection::U, domain, .. } if domain == du),
            "{e:?}"
        );
    }
    for bad in [f64::NAN, dv.0 - 1e-9, dv.1 + 2.0, f64::NEG_INFINITY] {
        let e = iso_v(bad).unwrap_err();
        assert!(
            matches!(e, Error::SurfaceParameterOutOfDomain { direction: ParameterDirection::V, domain, .. } if domain == dv),
            "{e:?}"
        );
    }
}

#[test]
fn isocurves_equal_the_surface_at_fixed_parameters() {
    let (beziers, splines, nurbs) = random_splines(5);
    let bk = |n: usize| -> Vec<f64> { [vec![0.0; n + 1], vec![1.0; n + 1]].concat() };
    for s in &beziers {
        let (m, n) = s.degrees();
        check_isocurves(
            s,
            (&bk(m), &bk(n)),
            |u| s.isocurve_u(u),
            |v| s.isocurve_v(v),
        );
    }
    for s in &splines {
        check_isocurves(s, s.knots(), |u| s.isocurve_u(u), |v| s.isocurve_v(v));
        // A polynomial surface's isocurves are polynomial.
        assert!(
            s.isocurve_u(s.domain()[0].0)
                .unwrap()
                .weights()
                .iter()
                .all(|&w| w == 1.0)
        );
    }
    for s in &nurbs {
        check_isocurves(s, s.knots(), |u| s.isocurve_u(u), |v| s.isocurve_v(v));
    }
}

#[test]
fn isocurves_of_a_cylinder_are_circles_and_lines() {
    let circle = lift(&Nurbs::circle(Point2::origin(), 1.0).unwrap(), 0.0);
    let s = NurbsSurface::extrude(&circle, Vector3::new(0.0, 0.0, 2.0)).unwrap();
    let ring = s.isocurve_v(0.25).unwrap();
    for u in params((0.0, 1.0), 40) {
        let p = ring.eval(u);
        assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15 && (p.z - 0.5).abs() < 1e-15);
    }
    let rule = s.isocurve_u(0.3).unwrap();
    assert_eq!(rule.degree(), 1);
    let foot = circle.eval(0.3);
    for v in params((0.0, 1.0), 5) {
        assert!(close(
            rule.eval(v),
            foot + Vector3::new(0.0, 0.0, 2.0 * v),
            1e-15
        ));
    }
}

/// Checks that the halves of a spline surface split at `t` in `axis` are
/// the surface on their parameters, and that the split errors are right.
fn check_split<S: Surface + Clone + std::fmt::Debug>(
    s: &S,
    axis: usize,
    split: impl Fn(f64) -> Result<(S, S), Error>,
) {
    let dom = s.domain();
    let (a, b) = dom[axis];
    for f in [0.13, 0.5, 0.77] {
        let t = a + (b - a) * f;
        let (left, right) = split(t).unwrap();
        let (ld, rd) = (left.domain(), right.domain());
        assert_eq!(
            (ld[axis].0, ld[axis].1, rd[axis].0, rd[axis].1),
            (a, t, t, b)
        );
        assert_eq!(ld[1 - axis], dom[1 - axis]);
        let other = dom[1 - axis];
        for x in params(other, 9) {
            for g in params((0.0, 1.0), 9) {
                let (y_left, y_right) = (a + (t - a) * g, t + (b - t) * g);
                let at = |y: f64| if axis == 0 { (y, x) } else { (x, y) };
                let (u, v) = at(y_left);
                assert!(close(left.eval(u, v), s.eval(u, v), 1e-13), "{u} {v}");
                let (u, v) = at(y_right);
                assert!(close(right.eval(u, v), s.eval(u, v), 1e-13), "{u} {v}");
                // Orientation kept.
                if let (Some(n), Some(m)) = (right.normal(u, v), s.normal(u, v)) {
                    assert!(n.dot(&m) > 0.99, "{u} {v}");
                }
            }
        }
    }
    let direction = if axis == 0 {
        ParameterDirection::U
    } else {
        ParameterDirection::V
    };
    for bad in [a, b, f64::NAN, a - 1.0, b + 1.0, b - 1e-17 * b.abs()] {
        let e = split(bad).unwrap_err();
        assert!(
            matches!(e, Error::SplitOutsideDomain { direction: d, domain, .. } if d == direction && domain == (a, b)),
            "{bad}: {e:?}"
        );
    }
}

#[test]
fn split_halves_equal_the_surface() {
    let (beziers, splines, nurbs) = random_splines(9);
    for s in &splines {
        check_split(s, 0, |t| s.split_u(t));
        check_split(s, 1, |t| s.split_v(t));
        // At an interior knot.
        let ku: Vec<f64> = s.knots().0.to_vec();
        let [du, _] = s.domain();
        if let Some(&k) = ku.iter().find(|&&k| k > du.0 && k < du.1) {
            let (l, r) = s.split_u(k).unwrap();
            assert_eq!(l.domain()[0].1, k);
            assert!(close(l.eval(k, 0.5), r.eval(k, 0.5), 1e-13));
        }
    }
    for s in &nurbs {
        check_split(s, 0, |t| s.split_u(t));
        check_split(s, 1, |t| s.split_v(t));
    }
    for s in &beziers {
        for (axis, f) in [(0, 0.3), (1, 0.6)] {
            let (a, b) = if axis == 0 {
                s.split_u(f).unwrap()
            } else {
                s.split_v(f).unwrap()
            };
            assert_eq!(a.degrees(), s.degrees());
            for x in params((0.0, 1.0), 8) {
                for g in params((0.0, 1.0), 8) {
                    let (ya, yb) = (f * g, f + (1.0 - f) * g);
                    let (sa, sb) = if axis == 0 {
                        (s.eval(ya, x), s.eval(yb, x))
                    } else {
                        (s.eval(x, ya), s.eval(x, yb))
                    };
                    let (ea, eb) = if axis == 0 {
                        (a.eval(g, x), b.eval(g, x))
                    } else {
                        (a.eval(x, g), b.eval(x, g))
                    };
                    assert!(close(ea, sa, 1e-13) && close(eb, sb, 1e-13));
                }
            }
        }
        for bad in [0.0, 1.0, f64::NAN, -0.5, 2.0] {
            assert!(matches!(
                s.split_u(bad),
                Err(Error::SplitOutsideDomain {
                    direction: ParameterDirection::U,
                    ..
                })
            ));
            assert!(matches!(
                s.split_v(bad),
                Err(Error::SplitOutsideDomain {
                    direction: ParameterDirection::V,
                    ..
                })
            ));
        }
    }
}

/// An affine map from its 3×4 matrix.
fn affine(m: [[f64; 4]; 3]) -> Affine3<f64> {
    let mut full = Matrix4::identity();
    for (i, row) in m.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            full[(i, j)] = x;
        }
    }
    Affine3::from_matrix_unchecked(full)
}

/// Checks `T(S(u, v)) = S′(u, v)`, `S′_u = L·S_u`, and `N′ ∝ L⁻ᵀN` with the
/// same orientation.
fn check_transform<S: Surface>(s: &S, t: &S, map: &Affine3<f64>) {
    let l = map.matrix().fixed_view::<3, 3>(0, 0).into_owned();
    let inv_t = l.try_inverse().unwrap().transpose();
    let [du, dv] = s.domain();
    assert_eq!(t.domain(), [du, dv]);
    for u in params(du, 9) {
        for v in params(dv, 9) {
            let p = map * s.eval(u, v);
            assert!(close(t.eval(u, v), p, 1e-13 * (1.0 + p.coords.norm())));
            let (su, sv) = s.partials(u, v);
            let (tu, tv) = t.partials(u, v);
            assert!((tu - l * su).norm() <= 1e-12 * (1.0 + (l * su).norm()));
            assert!((tv - l * sv).norm() <= 1e-12 * (1.0 + (l * sv).norm()));
            if let (Some(n), Some(m)) = (s.normal(u, v), t.normal(u, v)) {
                let want = (inv_t * n.into_inner()).normalize();
                assert!((m.into_inner() - want).norm() < 1e-9, "{u} {v}");
            }
        }
    }
}

#[test]
fn transforms_commute_with_evaluation() {
    let (beziers, splines, nurbs) = random_splines(13);
    let maps = [
        affine([
            [1.0, 0.0, 0.0, 2.0],
            [0.0, 1.0, 0.0, -3.0],
            [0.0, 0.0, 1.0, 0.5],
        ]),
        affine([
            [0.0, -1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 1.0],
            [0.0, 0.0, 1.0, 0.0],
        ]),
        affine([
            [2.0, 0.5, 0.0, 1.0],
            [0.0, 1.5, 0.3, 0.0],
            [0.1, 0.0, 0.7, -2.0],
        ]),
        // A reflection: the orientation flag turns over.
        affine([
            [-1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ]),
    ];
    for map in &maps {
        for s in &beziers {
            check_transform(s, &s.transformed(map), map);
        }
        for s in &splines {
            let t = s.transformed(map);
            assert_eq!(t.knots(), s.knots());
            assert_eq!(t.tolerance(), s.tolerance());
            check_transform(s, &t, map);
        }
        for s in &nurbs {
            let t = s.transformed(map);
            assert_eq!(t.weights(), s.weights());
            check_transform(s, &t, map);
        }
    }
    // The identity changes nothing.
    let id = Affine3::identity();
    assert_eq!(nurbs[0].transformed(&id), nurbs[0]);
    assert_eq!(beziers[0].transformed(&id), beziers[0]);
}

#[test]
fn transform_errors() {
    let (beziers, splines, nurbs) = random_splines(17);
    let nan = affine([
        [1.0, f64::NAN, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);
    let inf = affine([
        [1.0, 0.0, 0.0, f64::INFINITY],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);
    let huge = affine([
        [1e101, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);
    for map in [&nan, &inf] {
        assert_eq!(
            beziers[0].try_transformed(map),
            Err(Error::NonFiniteTransform)
        );
        assert_eq!(
            splines[0].try_transformed(map),
            Err(Error::NonFiniteTransform)
        );
        assert_eq!(
            nurbs[0].try_transformed(map),
            Err(Error::NonFiniteTransform)
        );
        // The infallible form leaves the surface as it was.
        assert_eq!(beziers[0].transformed(map), beziers[0]);
        assert_eq!(splines[0].transformed(map), splines[0]);
        assert_eq!(nurbs[0].transformed(map), nurbs[0]);
    }
    assert!(matches!(
        splines[0].try_transformed(&huge),
        Err(Error::GridCoordinateTooLarge { .. })
    ));
    assert!(matches!(
        nurbs[1].try_transformed(&huge),
        Err(Error::GridCoordinateTooLarge { .. })
    ));
    assert!(matches!(
        beziers[1].try_transformed(&huge),
        Err(Error::GridCoordinateTooLarge { .. })
    ));
    assert_eq!(nurbs[1].transformed(&huge), nurbs[1]);
}

#[test]
fn new_error_messages_name_the_problem() {
    let cases = [
        (
            Error::FlatGridLength { length: 7, rows: 2 },
            "a flat list of 7 control values cannot be cut into 2 rows of equal length: the \
             length must be a non-zero multiple of the rows",
        ),
        (
            Error::SurfaceParameterOutOfDomain {
                direction: ParameterDirection::V,
                t: 1.5,
                domain: (0.0, 1.0),
            },
            "the surface's v parameter 1.5 is outside its domain [0, 1]",
        ),
        (
            Error::SplitOutsideDomain {
                direction: ParameterDirection::U,
                t: 0.0,
                domain: (0.0, 2.0),
            },
            "cannot split the surface in u at 0: the parameter must lie strictly inside the \
             domain (0, 2)",
        ),
        (
            Error::InvalidExtrusion {
                vector: Vector3::zeros(),
            },
            "extrusion vector (0, 0, 0) must be finite and non-zero",
        ),
        (
            Error::NonFiniteTransform,
            "the affine map has a NaN or infinite entry",
        ),
        (
            Error::SpanGap {
                index: 1,
                previous_end: 1.0,
                start: 2.0,
            },
            "the profile's Bézier span 1 starts at 2 but the previous one ends at 1: a spline \
             surface needs spans without gaps",
        ),
    ];
    for (e, want) in cases {
        assert_eq!(e.to_string(), want);
    }
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// On a random rational surface: the isocurves through a random
        /// point pass through it, and the halves of a split at a random
        /// parameter agree with the surface on their sides.
        #[test]
        fn isocurves_and_splits_agree_with_the_surface(
            seed in 1u64..1_000_000,
            fu in 0.0f64..=1.0,
            fv in 0.0f64..=1.0,
            fs in 0.01f64..0.99,
        ) {
            let (_, _, nurbs) = random_splines(seed);
            for s in &nurbs {
                let [du, dv] = s.domain();
                let u = du.0 + (du.1 - du.0) * fu;
                let v = dv.0 + (dv.1 - dv.0) * fv;
                let p = s.eval(u, v);
                prop_assert!(close(s.isocurve_u(u).unwrap().eval(v), p, 1e-13));
                prop_assert!(close(s.isocurve_v(v).unwrap().eval(u), p, 1e-13));
                let cut = du.0 + (du.1 - du.0) * fs;
                let (a, b) = s.split_u(cut).unwrap();
                let half = if u <= cut { a } else { b };
                prop_assert!(close(half.eval(u, v), p, 1e-13));
                let cut = dv.0 + (dv.1 - dv.0) * fs;
                let (a, b) = s.split_v(cut).unwrap();
                let half = if v <= cut { a } else { b };
                prop_assert!(close(half.eval(u, v), p, 1e-13));
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Four-point (bilinear) surfaces and boundary curves
// ---------------------------------------------------------------------------

#[test]
fn bilinear_surfaces_follow_the_closed_form() {
    let mut rng = Rng(0xb111);
    for _ in 0..50 {
        let corners = grid(&mut rng, 2, 2);
        let (p00, p01, p10, p11) = (corners[0][0], corners[0][1], corners[1][0], corners[1][1]);
        let s = NurbsSurface::bilinear(p00, p10, p01, p11).unwrap();
        assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
        for u in params((0.0, 1.0), 7) {
            for v in params((0.0, 1.0), 7) {
                let want = Point3::from(
                    p00.coords * ((1.0 - u) * (1.0 - v))
                        + p10.coords * (u * (1.0 - v))
                        + p01.coords * ((1.0 - u) * v)
                        + p11.coords * (u * v),
                );
                assert!(close(s.eval(u, v), want, 1e-14), "({u}, {v})");
                // ∂S/∂u = (1 − v)(p10 − p00) + v(p11 − p01).
                let su = (p10 - p00) * (1.0 - v) + (p11 - p01) * v;
                assert!((s.partials(u, v).0 - su).norm() < 1e-13);
            }
        }
    }
    let bad = Point3::new(f64::NAN, 0.0, 0.0);
    assert!(
        NurbsSurface::bilinear(bad, Point3::origin(), Point3::origin(), Point3::origin()).is_err()
    );
}

#[test]
fn boundary_curves_are_the_surface_at_the_domain_ends() {
    let mut rng = Rng(0xb0d4);
    let bezier = BezierSurface::new(grid(&mut rng, 4, 3)).unwrap();
    let spline = BSplineSurface::clamped((2, 3), grid(&mut rng, 5, 6)).unwrap();
    let sphere = NurbsSurface::from_revolution(&revolve::Revolution::new(
        Nurbs::arc(
            Point2::origin(),
            1.0,
            -std::f64::consts::FRAC_PI_2,
            std::f64::consts::FRAC_PI_2,
        )
        .unwrap(),
    ))
    .unwrap();
    let surfaces: Vec<(&str, &dyn Surface, [Nurbs<3>; 4])> = vec![
        ("bezier", &bezier, bezier.boundary_curves().unwrap()),
        ("bspline", &spline, spline.boundary_curves().unwrap()),
        ("sphere", &sphere, sphere.boundary_curves().unwrap()),
    ];
    for (name, s, [u0, u1, v0, v1]) in surfaces {
        let [du, dv] = s.domain();
        for t in params(dv, 20) {
            assert!(
                close(u0.eval(t), s.eval(du.0, t), 1e-14),
                "{name}: u0 at {t}"
            );
            assert!(
                close(u1.eval(t), s.eval(du.1, t), 1e-14),
                "{name}: u1 at {t}"
            );
        }
        for t in params(du, 20) {
            assert!(
                close(v0.eval(t), s.eval(t, dv.0), 1e-14),
                "{name}: v0 at {t}"
            );
            assert!(
                close(v1.eval(t), s.eval(t, dv.1), 1e-14),
                "{name}: v1 at {t}"
            );
        }
    }
    // The sphere's u ends are its poles: curves of one point.
    let [south, north, _, _] = sphere.boundary_curves().unwrap();
    for t in params(south.domain(), 8) {
        assert!(close(south.eval(t), Point3::new(0.0, -1.0, 0.0), 1e-15));
        assert!(close(north.eval(t), Point3::new(0.0, 1.0, 0.0), 1e-15));
    }
}

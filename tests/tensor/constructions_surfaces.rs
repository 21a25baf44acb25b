//! Surface constructions: clamped and uniform B-spline surfaces and the flat
//! constructors (against the curves' knots and `new`), ruled surfaces (the
//! hyperbolic paraboloid `z = xy` between two skew lines; curves of
//! different degrees and knots against `(1 − v)A(u) + vB(φ(u))`), extrusions
//! (the cylinder `x² + y² = r²`) and translational sweeps (a circle along a
//! line is a cylinder; a rational profile along a rational path against
//! `P(u) + T(v) − T(v₀)`), isocurves against the surface's points, splits
//! against the surface at the mapped parameters, affine maps commuting with
//! evaluation (`T(S(u, v)) = S'(u, v)`, normals by the inverse transpose),
//! and every error path with its variant. Tolerances are a few ulps of the
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

#[allow(dead_code)]
fn affine(m: [[f64; 4]; 3]) -> Affine3<f64> {
    let mut full = Matrix4::identity();
    for (i, row) in m.iter().enumerate() {
        for (j, &x) in row.iter().enumerate() {
            full[(i, j)] = x;
        }
    }
    Affine3::from_matrix_unchecked(full)
}

//! Surfaces through data: `BSplineSurface::interpolate` (a grid of points)
//! and `NurbsSurface::loft` (a sequence of section curves).
//!
//! References, independent of the library's code:
//! - grid interpolation: the averaged centripetal parameters recomputed here
//!   from their definition (columns, resp. rows, of zero length left out),
//!   and the surface evaluated there: it passes through every grid point to
//!   `1e-12 ×` the grid's size; equally spaced points on a plane give the
//!   bilinear map exactly;
//! - loft, closed forms: circles of equal radius at several heights give a
//!   cylinder (the radius at many `(u, v)` within `1e-12`, and each section
//!   at its parameter, recomputed here from the mean control-point
//!   distances); circles whose radius varies linearly with the height, with
//!   `degree_v = 1`, give a cone (radius `r(z)` by its formula, and the
//!   point as the linear blend of the two neighbouring sections);
//! - loft of incompatible sections (different degrees, knots, domains,
//!   clamped and unclamped, rational and not): each section is an
//!   isoparametric curve of the surface, `S(u, v̄ₖ) = Cₖ(c + (u − a)(d − c)/(b − a))`,
//!   with `v̄ₖ` found by Newton's method on the surface;
//! - every error path, with its exact variant.

use revolve::nalgebra::{Point3, Vector3};
use revolve::{
    BSpline, BSplineSurface, Curve, Error, MAX_COORDINATE, Nurbs, NurbsSurface, ParameterDirection,
    Surface,
};

/// The largest coordinate magnitude of a grid.
fn grid_size(grid: &[Vec<Point3<f64>>]) -> f64 {
    grid.iter()
        .flatten()
        .fold(0.0_f64, |m, p| m.max(p.coords.amax()))
}

/// Centripetal parameters of one line of points, `None` for zero length.
fn centripetal(points: &[Point3<f64>]) -> Option<Vec<f64>> {
    let steps: Vec<f64> = points
        .windows(2)
        .map(|w| (w[1] - w[0]).norm().sqrt())
        .collect();
    let total: f64 = steps.iter().sum();
    if total == 0.0 {
        return None;
    }
    let mut params = vec![0.0];
    let mut sum = 0.0;
    for s in &steps {
        sum += s;
        params.push(sum / total);
    }
    *params.last_mut().unwrap() = 1.0;
    Some(params)
}

/// The mean of the centripetal parameters of the lines that have length.
fn averaged(lines: &[Vec<Point3<f64>>]) -> Vec<f64> {
    let all: Vec<Vec<f64>> = lines.iter().filter_map(|l| centripetal(l)).collect();
    let n = lines[0].len();
    (0..n)
        .map(|k| all.iter().map(|p| p[k]).sum::<f64>() / all.len() as f64)
        .collect()
}

fn columns(grid: &[Vec<Point3<f64>>]) -> Vec<Vec<Point3<f64>>> {
    (0..grid[0].len())
        .map(|j| grid.iter().map(|row| row[j]).collect())
        .collect()
}

/// A deterministic pseudo-random number in `[−1, 1]`.
fn noise(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

fn check_grid_interpolation(degrees: (usize, usize), grid: Vec<Vec<Point3<f64>>>) {
    let s = BSplineSurface::interpolate(degrees, grid.clone()).unwrap();
    assert_eq!(s.degrees(), degrees);
    assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
    assert_eq!(s.points().len(), grid.len());
    assert_eq!(s.points()[0].len(), grid[0].len());
    let u = averaged(&columns(&grid));
    let v = averaged(&grid);
    let tol = 1e-12 * grid_size(&grid);
    for (i, row) in grid.iter().enumerate() {
        for (j, q) in row.iter().enumerate() {
            let miss = (s.eval(u[i], v[j]) - q).norm();
            assert!(
                miss <= tol,
                "{degrees:?}: point ({i}, {j}) missed by {miss:e}"
            );
        }
    }
}

#[test]
fn grid_interpolation_passes_through_every_point() {
    let mut seed = 0x9e37_79b9_7f4a_7c15;
    for p in 1..=4 {
        for q in 1..=4 {
            for (rows, cols) in [(p + 1, q + 1), (p + 3, q + 2), (9, 7)] {
                let grid: Vec<Vec<Point3<f64>>> = (0..rows)
                    .map(|i| {
                        (0..cols)
                            .map(|j| {
                                Point3::new(
                                    i as f64 + 0.3 * noise(&mut seed),
                                    j as f64 + 0.3 * noise(&mut seed),
                                    noise(&mut seed),
                                )
                            })
                            .collect()
                    })
                    .collect();
                check_grid_interpolation((p, q), grid);
            }
        }
    }
}

#[test]
fn grid_interpolation_handles_a_pole() {
    // A hemisphere: row 0 is the pole (one point repeated), rows along the
    // polar angle, columns along the longitude.
    let grid: Vec<Vec<Point3<f64>>> = (0..7)
        .map(|i| {
            let theta = std::f64::consts::FRAC_PI_2 * i as f64 / 6.0;
            (0..9)
                .map(|j| {
                    let phi = std::f64::consts::PI * j as f64 / 8.0;
                    if i == 0 {
                        Point3::new(0.0, 0.0, 1.0)
                    } else {
                        Point3::new(
                            theta.sin() * phi.cos(),
                            theta.sin() * phi.sin(),
                            theta.cos(),
                        )
                    }
                })
                .collect()
        })
        .collect();
    check_grid_interpolation((3, 3), grid.clone());
    check_grid_interpolation((2, 3), grid);
}

#[test]
fn equally_spaced_planar_grid_gives_the_bilinear_map() {
    let (a, b) = (Vector3::new(0.5, 0.1, 0.0), Vector3::new(-0.2, 0.7, 0.3));
    let origin = Point3::new(1.0, 2.0, 3.0);
    for (p, q) in [(1, 1), (2, 3), (3, 2), (4, 4)] {
        let (rows, cols) = (p + 3, q + 2);
        let grid: Vec<Vec<Point3<f64>>> = (0..rows)
            .map(|i| {
                (0..cols)
                    .map(|j| origin + a * i as f64 + b * j as f64)
                    .collect()
            })
            .collect();
        let s = BSplineSurface::interpolate((p, q), grid).unwrap();
        let (ea, eb) = (a * (rows - 1) as f64, b * (cols - 1) as f64);
        for k in 0..=20 {
            for l in 0..=20 {
                let (u, v) = (k as f64 / 20.0, l as f64 / 20.0);
                let expect = origin + ea * u + eb * v;
                assert!(
                    (s.eval(u, v) - expect).norm() < 1e-13,
                    "({p}, {q}) at ({u}, {v})"
                );
                let (su, sv) = s.partials(u, v);
                assert!((su - ea).norm() < 1e-12 && (sv - eb).norm() < 1e-12);
            }
        }
    }
}

#[test]
fn grid_interpolation_errors_name_the_problem() {
    let grid = |rows: usize, cols: usize| -> Vec<Vec<Point3<f64>>> {
        (0..rows)
            .map(|i| {
                (0..cols)
                    .map(|j| Point3::new(i as f64, j as f64, (i * j) as f64))
                    .collect()
            })
            .collect()
    };
    assert_eq!(
        BSplineSurface::interpolate((0, 2), grid(4, 4)),
        Err(Error::ZeroDegree)
    );
    assert_eq!(
        BSplineSurface::interpolate((2, 0), grid(4, 4)),
        Err(Error::ZeroDegree)
    );
    assert_eq!(
        BSplineSurface::interpolate((1, 1), vec![]),
        Err(Error::EmptyGrid)
    );
    assert_eq!(
        BSplineSurface::interpolate((1, 1), vec![vec![], vec![]]),
        Err(Error::EmptyGrid)
    );
    let mut ragged = grid(4, 3);
    ragged[2].pop();
    assert_eq!(
        BSplineSurface::interpolate((1, 1), ragged),
        Err(Error::RaggedGrid {
            row: 2,
            expected: 3,
            found: 2
        })
    );
    let mut nan = grid(4, 3);
    nan[1][2].y = f64::NAN;
    assert_eq!(
        BSplineSurface::interpolate((1, 1), nan),
        Err(Error::NonFiniteGridPoint { row: 1, column: 2 })
    );
    let mut large = grid(4, 3);
    large[3][0].z = -10.0 * MAX_COORDINATE;
    assert_eq!(
        BSplineSurface::interpolate((1, 1), large),
        Err(Error::GridCoordinateTooLarge {
            row: 3,
            column: 0,
            value: -10.0 * MAX_COORDINATE
        })
    );
    assert_eq!(
        BSplineSurface::interpolate((3, 1), grid(3, 5)),
        Err(Error::GridTooSmall {
            direction: ParameterDirection::U,
            found: 3,
            degree: 3
        })
    );
    assert_eq!(
        BSplineSurface::interpolate((2, 5), grid(3, 5)),
        Err(Error::GridTooSmall {
            direction: ParameterDirection::V,
            found: 5,
            degree: 5
        })
    );
    // Row 2 repeats row 1: no parameter separates them.
    let mut rows = grid(5, 4);
    rows[2] = rows[1].clone();
    assert_eq!(
        BSplineSurface::interpolate((2, 2), rows),
        Err(Error::CoincidentGridPoints {
            direction: ParameterDirection::U,
            index: 2
        })
    );
    // Column 3 repeats column 2.
    let mut cols = grid(4, 5);
    for row in &mut cols {
        row[3] = row[2];
    }
    assert_eq!(
        BSplineSurface::interpolate((2, 2), cols),
        Err(Error::CoincidentGridPoints {
            direction: ParameterDirection::V,
            index: 3
        })
    );
    // Every row the same point: no column has any length.
    let flat = vec![vec![Point3::new(1.0, 1.0, 1.0), Point3::new(2.0, 1.0, 1.0)]; 3];
    assert_eq!(
        BSplineSurface::interpolate((1, 1), flat),
        Err(Error::CoincidentGridPoints {
            direction: ParameterDirection::U,
            index: 1
        })
    );
    assert_eq!(
        Error::CoincidentGridPoints {
            direction: ParameterDirection::U,
            index: 2
        }
        .to_string(),
        "along u, the grid's points 1 and 2 coincide in every row or column: their \
         parameters cannot differ"
    );
    assert!(
        Error::GridTooSmall {
            direction: ParameterDirection::V,
            found: 2,
            degree: 3
        }
        .to_string()
        .contains("2 points along v; degree 3 there needs at least 4")
    );
}

// ---------------------------------------------------------------------------
// Lofts
// ---------------------------------------------------------------------------

/// The whole circle of radius `r` about the z axis at height `z`, as nine
/// rational quadratic control points (four quarter arcs), starting at
/// angle `start`.
fn circle(r: f64, z: f64, start: f64) -> Nurbs<3> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for k in 0..9 {
        let angle = start + std::f64::consts::FRAC_PI_4 * k as f64;
        let corner = k % 2 == 1;
        let reach = if corner {
            r * std::f64::consts::SQRT_2
        } else {
            r
        };
        points.push(Point3::new(reach * angle.cos(), reach * angle.sin(), z));
        weights.push(if corner { h } else { 1.0 });
    }
    let knots = vec![
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    Nurbs::new(2, knots, points, weights).unwrap()
}

/// Centripetal parameters across sections from the mean distance of their
/// corresponding control points.
fn section_parameters(sections: &[Nurbs<3>]) -> Vec<f64> {
    let steps: Vec<f64> = sections
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0].points(), w[1].points());
            let mean = a.iter().zip(b).map(|(p, q)| (q - p).norm()).sum::<f64>() / a.len() as f64;
            mean.sqrt()
        })
        .collect();
    let total: f64 = steps.iter().sum();
    let mut params = vec![0.0];
    let mut sum = 0.0;
    for s in &steps {
        sum += s;
        params.push(sum / total);
    }
    *params.last_mut().unwrap() = 1.0;
    params
}

#[test]
fn loft_through_equal_circles_is_a_cylinder() {
    let heights = [0.0, 1.0, 2.5, 4.0, 4.5];
    let sections: Vec<Nurbs<3>> = heights.iter().map(|&z| circle(2.0, z, 0.3)).collect();
    let params = section_parameters(&sections);
    for degree_v in 1..=4 {
        let s = NurbsSurface::loft(&sections, degree_v).unwrap();
        assert_eq!(s.degrees(), (2, degree_v));
        assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
        let mut worst = 0.0_f64;
        for k in 0..=60 {
            for l in 0..=60 {
                let (u, v) = (k as f64 / 60.0, l as f64 / 60.0);
                let p = s.eval(u, v);
                worst = worst.max((p.x.hypot(p.y) - 2.0).abs());
                // The circle's own point at u, lifted to the height.
                let c = sections[0].eval(u);
                assert!((p.x - c.x).abs() < 1e-12 && (p.y - c.y).abs() < 1e-12);
            }
        }
        assert!(
            worst <= 1e-12,
            "degree_v {degree_v}: radius off by {worst:e}"
        );
        println!("loft of circles, degree_v {degree_v}: radius off by at most {worst:e}");
        for (k, (&vk, &z)) in params.iter().zip(&heights).enumerate() {
            for i in 0..=40 {
                let u = i as f64 / 40.0;
                let want = sections[k].eval(u);
                let got = s.eval(u, vk);
                assert!(
                    (got - want).norm() < 1e-12,
                    "degree_v {degree_v}, section {k} at z {z}"
                );
            }
        }
    }
}

#[test]
fn loft_of_degree_one_through_linearly_growing_circles_is_a_cone() {
    // r(z) = 1 + z/2 at heights 0, 1, 3: three sections on one cone.
    let radius = |z: f64| 1.0 + 0.5 * z;
    let heights = [0.0, 1.0, 3.0];
    let sections: Vec<Nurbs<3>> = heights
        .iter()
        .map(|&z| circle(radius(z), z, -1.0))
        .collect();
    let params = section_parameters(&sections);
    let s = NurbsSurface::loft(&sections, 1).unwrap();
    let mut worst = 0.0_f64;
    for k in 0..=80 {
        for l in 0..=80 {
            let (u, v) = (k as f64 / 80.0, l as f64 / 80.0);
            let p = s.eval(u, v);
            worst = worst.max((p.x.hypot(p.y) - radius(p.z)).abs());
            // The linear blend of the neighbouring sections at the same u.
            let seg = if v < params[1] { 0 } else { 1 };
            let t = (v - params[seg]) / (params[seg + 1] - params[seg]);
            let blend =
                sections[seg].eval(u).coords * (1.0 - t) + sections[seg + 1].eval(u).coords * t;
            assert!((p.coords - blend).norm() < 1e-12, "({u}, {v})");
        }
    }
    assert!(worst <= 1e-12, "off the cone by {worst:e}");
    println!("degree-1 loft of growing circles: off the cone by at most {worst:e}");
}

/// The `v` at which the isocurve of `s` through `target` at `u` lies:
/// the best of dense samples, polished by Newton's method on
/// `(S(u, v) − target)·S_v = 0`.
fn section_parameter(s: &NurbsSurface, u: f64, target: Point3<f64>) -> f64 {
    let mut v = (0..=2000)
        .map(|k| k as f64 / 2000.0)
        .min_by(|a, b| {
            let da = (s.eval(u, *a) - target).norm();
            let db = (s.eval(u, *b) - target).norm();
            da.total_cmp(&db)
        })
        .unwrap();
    for _ in 0..50 {
        let (_, sv) = s.partials(u, v);
        let r = s.eval(u, v) - target;
        if sv.norm_squared() == 0.0 {
            break;
        }
        v = (v - r.dot(&sv) / sv.norm_squared()).clamp(0.0, 1.0);
    }
    v
}

#[test]
fn loft_through_incompatible_sections_interpolates_each() {
    // A rational circle on [0, 1]; an unclamped uniform cubic (domain
    // [3/9, 6/9]); a rational quadratic on [0, 2] with uneven knots.
    let first = circle(1.0, 0.0, 0.0);
    let second: Nurbs<3> = BSpline::uniform(
        3,
        (0..6)
            .map(|k| {
                let a = k as f64;
                Point3::new(1.5 * (a * 1.1).cos(), 1.2 * (a * 1.1).sin(), 1.0 + 0.1 * a)
            })
            .collect(),
    )
    .unwrap()
    .into();
    let third = Nurbs::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 1.3, 2.0, 2.0, 2.0],
        vec![
            Point3::new(1.0, 0.0, 2.0),
            Point3::new(1.0, 1.0, 2.2),
            Point3::new(-1.0, 1.5, 2.0),
            Point3::new(-1.0, -1.0, 2.4),
            Point3::new(1.0, -0.5, 2.0),
        ],
        vec![1.0, 1.3, 0.8, 1.0, 1.2],
    )
    .unwrap();
    let fourth = circle(0.5, 3.0, 1.0).elevate_degree(2).unwrap();
    // In this order, and with the unclamped cubic first (its domain
    // [1/3, 2/3] becomes the surface's).
    let orders = [
        [first.clone(), second.clone(), third.clone(), fourth.clone()],
        [second, first, third, fourth],
    ];
    for sections in &orders {
        let (a0, b0) = sections[0].domain();
        for degree_v in 1..=3 {
            let s = NurbsSurface::loft(sections, degree_v).unwrap();
            assert_eq!(s.degrees(), (4, degree_v));
            assert_eq!(s.domain(), [(a0, b0), (0.0, 1.0)]);
            for (k, c) in sections.iter().enumerate() {
                let (a, b) = c.domain();
                // The surface's u, as a fraction of the domain, on the curve.
                let at = |u: f64| c.eval(a + (u - a0) / (b0 - a0) * (b - a));
                let v = match k {
                    0 => 0.0,
                    3 => 1.0,
                    _ => section_parameter(&s, a0 + 0.37 * (b0 - a0), at(a0 + 0.37 * (b0 - a0))),
                };
                let mut worst = 0.0_f64;
                for i in 0..=200 {
                    let u = a0 + (b0 - a0) * i as f64 / 200.0;
                    worst = worst.max((s.eval(u, v) - at(u)).norm());
                }
                assert!(
                    worst < 1e-12,
                    "degree_v {degree_v}, section {k}: off by {worst:e}"
                );
                println!(
                    "loft of incompatible sections, degree_v {degree_v}: section {k} off by {worst:e}"
                );
            }
        }
    }
}

#[test]
fn loft_of_polynomial_sections_has_unit_weights_and_keeps_the_first_domain() {
    let line = |y: f64, z: f64, domain: (f64, f64)| {
        Nurbs::new(
            1,
            vec![domain.0, domain.0, domain.1, domain.1],
            vec![Point3::new(0.0, y, z), Point3::new(2.0, y, z)],
            vec![3.0, 3.0],
        )
        .unwrap()
    };
    let curves = [
        line(0.0, 0.0, (-1.0, 1.0)),
        line(0.5, 1.0, (0.0, 5.0)),
        line(1.0, 3.0, (2.0, 3.0)),
    ];
    let s = NurbsSurface::loft(&curves, 2).unwrap();
    assert_eq!(s.domain(), [(-1.0, 1.0), (0.0, 1.0)]);
    assert!(
        s.weights()
            .iter()
            .flatten()
            .all(|&w| (w - 1.0).abs() < 1e-14)
    );
    for k in 0..=10 {
        let u = -1.0 + 0.2 * k as f64;
        let x = u + 1.0;
        assert!((s.eval(u, 0.0) - Point3::new(x, 0.0, 0.0)).norm() < 1e-15);
        assert!((s.eval(u, 1.0) - Point3::new(x, 1.0, 3.0)).norm() < 1e-15);
    }
}

#[test]
fn loft_errors_name_the_problem() {
    let a = circle(1.0, 0.0, 0.0);
    let b = circle(1.0, 1.0, 0.0);
    let c = circle(1.0, 2.0, 0.0);
    assert_eq!(
        NurbsSurface::loft(&[a.clone(), b.clone()], 0),
        Err(Error::ZeroDegree)
    );
    assert_eq!(
        NurbsSurface::loft(&[], 1),
        Err(Error::TooFewSections {
            sections: 0,
            degree: 1
        })
    );
    assert_eq!(
        NurbsSurface::loft(std::slice::from_ref(&a), 1),
        Err(Error::TooFewSections {
            sections: 1,
            degree: 1
        })
    );
    assert_eq!(
        NurbsSurface::loft(&[a.clone(), b.clone(), c.clone()], 3),
        Err(Error::TooFewSections {
            sections: 3,
            degree: 3
        })
    );
    assert_eq!(
        NurbsSurface::loft(&[a.clone(), b.clone(), b.clone()], 2),
        Err(Error::CoincidentSections { index: 2 })
    );
    // The same circle with a refined knot vector is the same section once
    // the two are made compatible.
    assert_eq!(
        NurbsSurface::loft(&[a.clone(), a.insert_knot(0.1, 1).unwrap()], 1),
        Err(Error::CoincidentSections { index: 1 })
    );
    // A degree beyond what elevation reaches.
    let high = BSpline::clamped(
        65,
        (0..66)
            .map(|k| Point3::new(k as f64 / 65.0, (k % 2) as f64 * 0.1, 1.0))
            .collect(),
    )
    .unwrap();
    assert_eq!(
        NurbsSurface::loft(&[a.clone(), high.into()], 1),
        Err(Error::ElevationTooHigh {
            degree: 2,
            times: 63,
            max: 64
        })
    );
    // Weights that swing across the sections: the interpolated weight of
    // the middle column goes negative.
    let arc = |z: f64, w: f64| {
        Nurbs::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Point3::new(0.0, 0.0, z),
                Point3::new(1.0, 1.0, z),
                Point3::new(2.0, 0.0, z),
            ],
            vec![1.0, w, 1.0],
        )
        .unwrap()
    };
    let swing = NurbsSurface::loft(&[arc(0.0, 1.0), arc(1.0, 1e-3), arc(2.0, 1.0)], 2);
    assert!(
        matches!(
            swing,
            Err(Error::InvalidGridWeight {
                row: 1,
                column: 1,
                weight
            }) if weight < 0.0
        ),
        "{swing:?}"
    );
    assert_eq!(
        Error::TooFewSections {
            sections: 1,
            degree: 1
        }
        .to_string(),
        "a loft of degree 1 across its sections needs at least 2 section curves, got 1"
    );
    assert!(
        Error::CoincidentSections { index: 4 }
            .to_string()
            .contains("section curves 3 and 4")
    );
}

mod hostile {
    //! Any input gives a surface whose points are finite, or an error;
    //! never a panic.

    use super::*;
    use proptest::prelude::*;

    fn wild_coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![
            8 => -10.0f64..10.0,
            1 => Just(f64::NAN),
            1 => Just(f64::NEG_INFINITY),
            1 => Just(2.0 * MAX_COORDINATE),
            1 => Just(1e-300),
            1 => Just(0.0),
        ]
    }

    fn wild_point() -> impl Strategy<Value = Point3<f64>> {
        (wild_coordinate(), wild_coordinate(), wild_coordinate())
            .prop_map(|(x, y, z)| Point3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

        #[test]
        fn grids(
            p in 0usize..5,
            q in 0usize..5,
            rows in proptest::collection::vec(proptest::collection::vec(wild_point(), 0..7), 0..7),
            copy in 0usize..8,
        ) {
            let mut grid = rows;
            // Now and then a repeated row.
            if copy > 0 && copy < grid.len() {
                grid[copy] = grid[copy - 1].clone();
            }
            if let Ok(s) = BSplineSurface::interpolate((p, q), grid) {
                for k in 0..=8 {
                    for l in 0..=8 {
                        let x = s.eval(k as f64 / 8.0, l as f64 / 8.0);
                        prop_assert!(x.coords.iter().all(|c| c.is_finite()));
                    }
                }
            }
        }

        #[test]
        fn lofts(
            degree_v in 0usize..4,
            sections in proptest::collection::vec(
                (1usize..4, proptest::collection::vec(wild_point(), 2..7), 0.1f64..10.0),
                0..5,
            ),
        ) {
            let curves: Vec<Nurbs<3>> = sections
                .into_iter()
                .filter_map(|(p, points, w)| {
                    let n = points.len();
                    let weights = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { w }).collect();
                    let p = p.min(n - 1);
                    let knots = (0..n + p + 1)
                        .map(|i| i.saturating_sub(p).min(n - p) as f64)
                        .collect();
                    Nurbs::new(p, knots, points, weights).ok()
                })
                .collect();
            if let Ok(s) = NurbsSurface::loft(&curves, degree_v) {
                let [(a, b), _] = s.domain();
                for k in 0..=8 {
                    for l in 0..=8 {
                        let x = s.eval(a + (b - a) * k as f64 / 8.0, l as f64 / 8.0);
                        prop_assert!(x.coords.iter().all(|c| c.is_finite()));
                    }
                }
            }
        }
    }
}

//! The constructions of curves and surfaces and the intersections between
//! curves and surfaces, fed the fuzzer's inputs (extreme scales, repeated
//! and NaN points, odd degrees and counts): no panic, no hang, and every
//! result that comes back `Ok` holds finite values and keeps its promise
//! where a cheap check can tell (an interpolating curve passes through its
//! end points, a split half starts where the surface does, an
//! intersection point lies on both curves to within the size).

use super::{Fuzz, control_grid, finite_point, fuzz, parameter};
use revolve::curve::{CurveProjector, intersect_curves, intersect_space_curves};
use revolve::nalgebra::{
    Affine2, Affine3, Matrix4, Point, Point2, Point3, Translation2, Vector2, Vector3,
};
use revolve::{
    Aabb, BSpline, BSplineSurface, Curve, Error, Intersect, Nurbs, NurbsSurface, Revolution,
    Surface,
};

/// Seeds 0..6 000 (a few seconds).
#[test]
fn fuzz_constructions() {
    fuzz("constructions", 0..8_000, |f| match f.below(5) {
        0 => curves_through_points(f),
        1 => surfaces_from_curves(f),
        2 => surface_operations(f),
        3 => curve_operations(f),
        _ => intersections(f),
    });
}

/// A 3D NURBS curve of the fuzzer's points, knots and weights (`None` when
/// the constructor refuses them).
fn nurbs_curve(f: &mut Fuzz) -> Option<Nurbs<3>> {
    let n = 2 + f.below(6);
    let degree = f.below(n.min(4)) + usize::from(f.chance(20));
    let scale = f.scale();
    let points = f.points::<3>(n, scale);
    let knots = if f.chance(3) {
        f.knots(n, degree)
    } else {
        revolve_knots(n, degree)
    };
    let weights = f.weights(n);
    f.call("Nurbs::new", || Nurbs::new(degree, knots, points, weights))?
        .ok()
}

/// Clamped uniform knots on `[0, 1]` for `n` points of degree `degree`.
fn revolve_knots(n: usize, degree: usize) -> Vec<f64> {
    let inner = n.saturating_sub(degree + 1);
    let mut k = vec![0.0; degree + 1];
    k.extend((1..=inner).map(|i| i as f64 / (inner + 1) as f64));
    k.extend(vec![1.0; degree + 1]);
    k
}

/// Interpolation and fitting through the fuzzer's points.
fn curves_through_points(f: &mut Fuzz) {
    let n = f.count().min(200);
    let scale = f.scale();
    let points = f.points::<2>(n, scale);
    let degree = f.below(6);
    if let Some(Ok(c)) = f.call("BSpline::interpolate", || {
        BSpline::interpolate(degree, &points)
    }) {
        let (a, b) = c.domain();
        let (first, last) = (c.eval(a), c.eval(b));
        let size = data_size(&points);
        f.check(
            (first - points[0]).amax() <= 1e-9 * size
                && (last - points[n - 1]).amax() <= 1e-9 * size,
            "BSpline::interpolate",
            || {
                format!(
                    "ends {first:?} {last:?} for {:?} … {:?}",
                    points[0],
                    points[n - 1]
                )
            },
        );
    }
    // Parameters: mostly increasing steps, sometimes any numbers.
    let mut t = f.number();
    let params: Vec<f64> = (0..n + f.below(2))
        .map(|_| {
            if f.chance(8) {
                t = f.number();
            } else {
                t += f.number().abs();
            }
            t
        })
        .collect();
    if let Some(Ok(c)) = f.call("BSpline::interpolate_with_parameters", || {
        BSpline::interpolate_with_parameters(degree, &points, &params)
    }) {
        let k = f.below(n);
        let (p, q) = (c.eval(params[k]), points[k]);
        let size = data_size(&points);
        // Within the data's size times the conditioning a random parameter
        // spacing allows; the check is for NaN and gross misses.
        f.check(
            finite_point(&p) && (p - q).amax() <= 1e-3 * size,
            "BSpline::interpolate_with_parameters",
            || format!("{p:?} at {} for {q:?}", params[k]),
        );
    }
    let control = f.below(n + 3);
    if let Some(Ok(c)) = f.call("BSpline::fit", || BSpline::fit(degree, &points, control)) {
        let t = parameter(f, c.domain());
        let p = c.eval(t);
        f.check(finite_point(&p), "BSpline::fit", || format!("{p:?} at {t}"));
    }
    let rows = 1 + f.below(5);
    let cols = 1 + f.below(5);
    let grid = control_grid(f, rows, cols);
    let degrees = (f.below(4), f.below(4));
    if let Some(Ok(s)) = f.call("BSplineSurface::interpolate", || {
        BSplineSurface::interpolate(degrees, grid.clone())
    }) {
        surface_point_check(f, &s, "BSplineSurface::interpolate");
    }
}

/// Split, transforms, the parameter at an arc length, knot removal, 3D
/// arcs and ellipses, and the Frenet frame.
fn curve_operations(f: &mut Fuzz) {
    let Some(c) = nurbs_curve(f) else {
        return;
    };
    let t = parameter(f, c.domain());
    if let Some(Ok((left, right))) = f.call("Nurbs::split", || c.split(t)) {
        // The halves meet where the curve is cut (unless a jump is there).
        let (at_left, at_right) = (left.eval(left.domain().1), right.eval(right.domain().0));
        f.check(
            finite_point(&at_left) && finite_point(&at_right),
            "Nurbs::split",
            || format!("at {t}: {at_left:?} {at_right:?}"),
        );
    }
    // Degree reduction of a B-spline through the curve's control points
    // (any tolerance): within the tolerance at a few parameters.
    if let Ok(spline) = BSpline::new(c.degree(), c.knots().to_vec(), c.points().to_vec()) {
        let tolerance = if f.chance(4) { f.number() } else { 1e-3 };
        if let Some(Ok(reduced)) =
            f.call("BSpline::reduce_degree", || spline.reduce_degree(tolerance))
        {
            let u = parameter(f, spline.domain());
            let (p, q) = (spline.eval(u), reduced.eval(u));
            let size = p.coords.amax().max(q.coords.amax());
            f.check(
                (p - q).norm() <= tolerance + 1e-12 * size,
                "BSpline::reduce_degree",
                || format!("at {u}: {p:?} vs {q:?}, tolerance {tolerance}"),
            );
        }
    }
    let map = random_affine3(f);
    if let Some(Ok(moved)) = f.call("Nurbs::try_transformed", || c.try_transformed(&map)) {
        let p = moved.eval(t);
        f.check(finite_point(&p), "Nurbs::try_transformed", || {
            format!("{p:?}")
        });
    }
    let length = if f.chance(4) {
        f.number()
    } else {
        f.rng.unit()
    };
    let tolerance = if f.chance(4) { f.number() } else { 1e-6 };
    if let Some(Ok(length_total)) = f.call("Curve::arc_length", || c.arc_length(tolerance)) {
        let s = length * length_total.length;
        if let Some(Ok(u)) = f.call("Curve::parameter_at_length", || {
            c.parameter_at_length(s, tolerance)
        }) {
            let (a, b) = c.domain();
            f.check((a..=b).contains(&u), "Curve::parameter_at_length", || {
                format!("{u} outside ({a}, {b}) for s = {s}")
            });
        }
    }
    let times = f.below(3);
    if let Some(Ok((fewer, removed))) =
        f.call("Nurbs::remove_knot", || c.remove_knot(t, times, tolerance))
    {
        f.check(removed <= times, "Nurbs::remove_knot", || {
            format!("{removed} removed of {times}")
        });
        let p = fewer.eval(parameter(f, fewer.domain()));
        f.check(finite_point(&p), "Nurbs::remove_knot", || format!("{p:?}"));
    }
    if let Some(frame) = f
        .call("Nurbs::frenet_frame", || c.frenet_frame(t))
        .flatten()
    {
        let ok = frame.curvature.is_finite() && frame.torsion.is_finite();
        f.check(ok, "Nurbs::frenet_frame", || format!("{frame:?}"));
    }
    let v = |f: &mut Fuzz| Vector3::new(f.number(), f.number(), f.number());
    let (normal, start_dir) = (v(f), v(f));
    let centre = Point3::from(v(f));
    let (radius, a, b) = (f.number(), f.number(), f.number());
    if let Some(Ok(arc)) = f.call("Nurbs::arc_3d", || {
        Nurbs::arc_3d(centre, normal, start_dir, radius, a, b)
    }) {
        let p = arc.eval(parameter(f, arc.domain()));
        f.check(finite_point(&p), "Nurbs::arc_3d", || format!("{p:?}"));
    }
    let radii = (f.number(), f.number());
    if let Some(Ok(e)) = f.call("Nurbs::ellipse_arc", || {
        Nurbs::ellipse_arc(Point2::new(centre.x, centre.y), radii, a, b)
    }) {
        let p = e.eval(parameter(f, e.domain()));
        f.check(finite_point(&p), "Nurbs::ellipse_arc", || format!("{p:?}"));
    }
}

/// Ruled, extruded, swept and lofted surfaces of the fuzzer's curves.
fn surfaces_from_curves(f: &mut Fuzz) {
    let (Some(a), Some(b)) = (nurbs_curve(f), nurbs_curve(f)) else {
        return;
    };
    if let Some(Ok(s)) = f.call("NurbsSurface::ruled", || NurbsSurface::ruled(&a, &b)) {
        surface_point_check(f, &s, "NurbsSurface::ruled");
    }
    let v = Vector3::new(f.number(), f.number(), f.number());
    if let Some(Ok(s)) = f.call("NurbsSurface::extrude", || NurbsSurface::extrude(&a, v)) {
        surface_point_check(f, &s, "NurbsSurface::extrude");
    }
    if let Some(Ok(s)) = f.call("NurbsSurface::sweep", || NurbsSurface::sweep(&a, &b)) {
        surface_point_check(f, &s, "NurbsSurface::sweep");
    }
    let mut sections = vec![a, b];
    if let Some(c) = nurbs_curve(f) {
        sections.push(c);
    }
    let degree_v = f.below(4);
    if let Some(Ok(s)) = f.call("NurbsSurface::loft", || {
        NurbsSurface::loft(&sections, degree_v)
    }) {
        surface_point_check(f, &s, "NurbsSurface::loft");
    }
}

/// Isocurves, splits and affine maps of a NURBS surface of the fuzzer's
/// grid, and the NURBS form of a revolution.
fn surface_operations(f: &mut Fuzz) {
    let rows = 1 + f.below(4);
    let cols = 1 + f.below(4);
    let grid = control_grid(f, rows, cols);
    let (p, q) = (f.below(rows.max(1)), f.below(cols.max(1)));
    let weights: Vec<Vec<f64>> = grid.iter().map(|row| f.weights(row.len())).collect();
    let knots = (revolve_knots(rows, p), revolve_knots(cols, q));
    let Some(Ok(s)) = f.call("NurbsSurface::new", || {
        NurbsSurface::new((p, q), knots, grid, weights)
    }) else {
        return;
    };
    // One call in eight: the surface against a bilinear patch through its
    // box; every traced point on both surfaces.
    if f.chance(8) {
        let b = s.bounds();
        let corner = |f: &mut Fuzz| {
            Point3::from(
                b.min.coords
                    + b.extent().component_mul(&Vector3::new(
                        f.rng.unit(),
                        f.rng.unit(),
                        f.rng.unit(),
                    )),
            )
        };
        let corners = [corner(f), corner(f), corner(f), corner(f)];
        if let Ok(other) = NurbsSurface::bilinear(corners[0], corners[1], corners[2], corners[3]) {
            let tolerance = if f.chance(4) { f.number() } else { 1e-6 };
            if let Some(Ok(curves)) = f.call("NurbsSurface::intersect_surface", || {
                s.intersect_surface(&other, tolerance)
            }) {
                let size = box_size(&b);
                for p in curves.iter().flat_map(|c| &c.points) {
                    let (on_a, on_b) = (s.eval(p.uv_a.0, p.uv_a.1), other.eval(p.uv_b.0, p.uv_b.1));
                    f.check(
                        (on_a - on_b).norm() <= 1e-9 * size,
                        "NurbsSurface::intersect_surface",
                        || format!("{p:?}: {on_a:?} vs {on_b:?}"),
                    );
                }
            }
        }
    }
    let [du, dv] = s.domain();
    let (u, v) = (parameter(f, du), parameter(f, dv));
    if let Some(Ok(c)) = f.call("NurbsSurface::isocurve_u", || s.isocurve_u(u)) {
        let t = parameter(f, c.domain());
        let (on_curve, on_surface) = (c.eval(t), s.eval(u, t));
        let b = s.bounds();
        let size = box_size(&b);
        f.check(
            (on_curve - on_surface).norm() <= 1e-9 * size,
            "NurbsSurface::isocurve_u",
            || format!("at ({u}, {t}): {on_curve:?} vs {on_surface:?}"),
        );
    }
    if let Some(Ok((low, high))) = f.call("NurbsSurface::split_v", || s.split_v(v)) {
        surface_point_check(f, &low, "NurbsSurface::split_v");
        surface_point_check(f, &high, "NurbsSurface::split_v");
    }
    let map = random_affine3(f);
    if let Some(Ok(t)) = f.call("NurbsSurface::try_transformed", || s.try_transformed(&map)) {
        surface_point_check(f, &t, "NurbsSurface::try_transformed");
    }
    let n = 2 + f.below(5);
    let scale = f.scale();
    let profile_points = f.points::<2>(n, scale);
    if let Ok(profile) = revolve::Bezier::new(profile_points) {
        let r = Revolution::new(profile);
        if let Some(Ok(s)) = f.call("NurbsSurface::from_revolution", || {
            NurbsSurface::from_revolution(&r)
        }) {
            surface_point_check(f, &s, "NurbsSurface::from_revolution");
        }
    }
}

/// Curve–curve and curve–surface intersections: every point reported lies
/// on both within the size (a loose check: the search's own tests hold it
/// to closed forms).
fn intersections(f: &mut Fuzz) {
    let two = |f: &mut Fuzz| -> Option<Nurbs<2>> {
        let n = 2 + f.below(5);
        let degree = f.below(n.min(4));
        let scale = f.scale();
        let points = f.points::<2>(n, scale);
        let weights = f.weights(n);
        f.call("Nurbs::new", || {
            Nurbs::new(degree, revolve_knots(n, degree), points, weights)
        })?
        .ok()
    };
    let (Some(a), Some(b)) = (two(f), two(f)) else {
        return;
    };
    // Sometimes the second curve is the first, moved or refined, so that
    // the overlap proof is exercised.
    let b = match f.below(4) {
        0 => a.reversed(),
        1 => {
            let shift = Vector2::new(f.number(), f.number()) * 1e-12;
            let moved = Affine2::from_matrix_unchecked(Translation2::from(shift).to_homogeneous());
            a.try_transformed(&moved).unwrap_or(b)
        }
        _ => b,
    };
    let tolerance = if f.chance(4) { f.number() } else { 1e-9 };
    let found = f.call("intersect_curves", || intersect_curves(&a, &b, tolerance));
    if let Some(Err(Error::CurvesOverlap { a: ra, b: rb })) = found {
        // The stretch reported runs within the tolerance (and rounding).
        let inside = |r: (f64, f64), (lo, hi): (f64, f64)| lo <= r.0 && r.0 <= r.1 && r.1 <= hi;
        f.check(
            inside(ra, a.domain()) && inside(rb, b.domain()),
            "intersect_curves",
            || format!("overlap {ra:?} / {rb:?} outside the domains"),
        );
        let mid = a.eval(0.5 * (ra.0 + ra.1));
        if let Ok(near) = CurveProjector::new(&b).and_then(|p| p.nearest(&mid)) {
            let size = mid.coords.amax().max(near.point.coords.amax());
            f.check(
                near.distance <= 4.0 * tolerance + 1e-9 * size,
                "intersect_curves",
                || {
                    format!(
                        "overlap {ra:?}: a's middle {mid:?} is {} from b",
                        near.distance
                    )
                },
            );
        }
    }
    if let Some(Ok(found)) = found {
        let size = [a.bounds(), b.bounds()]
            .iter()
            .fold(0.0_f64, |m, (lo, hi)| {
                m.max(lo.coords.amax()).max(hi.coords.amax())
            });
        for x in found.iter().filter(|x| x.certified) {
            let (pa, pb): (Point2<f64>, Point2<f64>) = (a.eval(x.t_a), b.eval(x.t_b));
            f.check(
                (pa - pb).norm() <= 1e-6 * size.max(f64::MIN_POSITIVE),
                "intersect_curves",
                || format!("{x:?}: {pa:?} vs {pb:?}"),
            );
        }
    }
    let Some(c) = nurbs_curve(f) else {
        return;
    };
    if let Some(d) = nurbs_curve(f) {
        // Sometimes the second space curve is the first, reversed.
        let d = if f.chance(4) { c.reversed() } else { d };
        if let Some(Ok(found)) = f.call("intersect_space_curves", || {
            intersect_space_curves(&c, &d, 1e-9)
        }) {
            for x in &found {
                let (pc, pd): (Point3<f64>, Point3<f64>) = (c.eval(x.t_a), d.eval(x.t_b));
                let size = pc.coords.amax().max(pd.coords.amax());
                f.check(
                    (pc - pd).norm() <= 1e-9 + 1e-12 * size,
                    "intersect_space_curves",
                    || format!("{x:?}: {pc:?} vs {pd:?}"),
                );
            }
        }
    }
    let grid = control_grid(f, 3, 3);
    if let Some(Ok(s)) = f.call("BezierSurface::new", || revolve::BezierSurface::new(grid)) {
        if let Some(Ok(found)) = f.call("BezierSurface::intersect_curve", || {
            s.intersect_curve(&c, 1e-9)
        }) {
            let b = s.bounds();
            let size = box_size(&b);
            for x in found.iter().filter(|x| x.certified) {
                let (pc, ps): (Point3<f64>, Point3<f64>) = (c.eval(x.t), s.eval(x.uv.0, x.uv.1));
                f.check(
                    (pc - ps).norm() <= 1e-6 * size.max(pc.coords.amax()),
                    "BezierSurface::intersect_curve",
                    || format!("{x:?}: {pc:?} vs {ps:?}"),
                );
            }
        }
    }
}

/// A constructed surface evaluates to finite points with finite partials.
fn surface_point_check<S: Surface>(f: &mut Fuzz, s: &S, name: &'static str) {
    let [du, dv] = s.domain();
    let (u, v) = (parameter(f, du), parameter(f, dv));
    if let Some((p, (su, sv))) = f.call("Surface::eval", || (s.eval(u, v), s.partials(u, v))) {
        let ok = finite_point(&p) && su.iter().chain(sv.iter()).all(|x| x.is_finite());
        f.check(ok, name, || format!("at ({u}, {v}): {p:?} {su:?} {sv:?}"));
    }
}

/// The largest coordinate of the points (at least the smallest normal).
fn data_size<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.coords.amax()))
        .max(f64::MIN_POSITIVE)
}

/// The largest coordinate of a box's corners (a surface collapsed to a
/// point has no extent, but its points still round at their magnitude).
fn box_size(b: &Aabb) -> f64 {
    b.min
        .coords
        .amax()
        .max(b.max.coords.amax())
        .max(f64::MIN_POSITIVE)
}

/// An affine map of space with entries drawn from the stream (any
/// numbers, singular ones included).
fn random_affine3(f: &mut Fuzz) -> Affine3<f64> {
    let m = Matrix4::from_fn(|i, j| match (i, j) {
        (3, 3) => 1.0,
        (3, _) => 0.0,
        _ => f.number(),
    });
    Affine3::from_matrix_unchecked(m)
}

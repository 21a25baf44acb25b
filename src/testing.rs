//! Test support for downstream crates (feature `testing`): proptest
//! strategies for curves, profiles and rays, and law checkers for your own
//! [`Curve`] and [`Surface`] types.
//!
//! ```
//! use proptest::prelude::*;
//! use revolve::testing::{bspline_curve, check_curve_derivatives};
//!
//! proptest!(|(curve in bspline_curve::<2>(0..=5, 1.0))| {
//!     prop_assert!(check_curve_derivatives(&curve, 16).is_ok());
//! });
//! ```
//!
//! Every strategy and checker is total: bad arguments are clamped as each
//! item documents (a `scale` that is NaN, negative or too large, a degree
//! range that is empty or too high, a huge sample count), never a panic.
//!
//! The checkers compare analytic derivatives with central differences
//! `(f(t + h) − f(t − h))/2h` with `h = √ε·L` (`L` the parameter range). The
//! rounding error `ε|f|/h` is then about `1.5e-8·|f|/L`; the truncation error
//! is `h²|f‴|/6` where `f` is smooth and `h·|Δf″|/4` at a knot where the second
//! derivative jumps (splines of low degree), again about `1e-8` of the scale.
//! The checkers accept `1e-6` of the larger of the derivative's magnitude and
//! `|f|/L`, which a wrong derivative (a wrong factor, a missing term) misses
//! by orders of magnitude while correct ones pass with a wide margin.

use crate::{BSpline, Bezier, Curve, PatchBounds, Ray, Surface};
use nalgebra::{Point, Point2, Point3, SVector, Vector3};
use proptest::prelude::*;
use std::fmt;
use std::ops::RangeInclusive;

/// A law a curve or surface broke, with where and by how much.
#[derive(Debug, Clone, PartialEq)]
pub struct LawViolation {
    /// Which law.
    pub law: &'static str,
    /// The parameters where it failed.
    pub at: Vec<f64>,
    /// The difference found and the limit it exceeded.
    pub error: f64,
    /// The limit.
    pub limit: f64,
}

impl fmt::Display for LawViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} violated at {:?}: error {:e} exceeds {:e}",
            self.law, self.at, self.error, self.limit
        )
    }
}

impl std::error::Error for LawViolation {}

/// The highest degree the curve strategies generate; higher degrees are
/// clamped to it.
pub const MAX_DEGREE: usize = 24;

/// The most samples a checker uses: `samples` of a curve checker are
/// clamped to it, and the grid side `n` of a surface checker to its square
/// root (64).
pub const MAX_SAMPLES: usize = 4096;

/// `scale` moved into `[min, max]`; NaN becomes `min`.
fn clamp_scale(scale: f64, min: f64, max: f64) -> f64 {
    if scale >= min { scale.min(max) } else { min }
}

/// The degree range clamped to `0 ..= MAX_DEGREE`; an empty range means its
/// start.
fn clamp_degrees(degrees: &RangeInclusive<usize>) -> RangeInclusive<usize> {
    let lo = (*degrees.start()).min(MAX_DEGREE);
    let hi = (*degrees.end()).clamp(lo, MAX_DEGREE);
    lo..=hi
}

/// A point with coordinates in `[−scale, scale]`. `scale` is clamped into
/// `[0, MAX_COORDINATE]` (NaN and negative values give 0).
pub fn point<const D: usize>(scale: f64) -> impl Strategy<Value = Point<f64, D>> {
    let scale = clamp_scale(scale, 0.0, crate::MAX_COORDINATE);
    // Drawn in [−1, 1] and scaled: proptest refuses empty float ranges.
    proptest::array::uniform::<_, D>(-1.0..=1.0)
        .prop_map(move |c| Point::from(SVector::from(c) * scale))
}

/// A Bézier curve with a degree in `degrees` and coordinates in
/// `[−scale, scale]`. Degrees are clamped to [`MAX_DEGREE`] (an empty
/// range means its start), `scale` as for [`point`].
pub fn bezier_curve<const D: usize>(
    degrees: RangeInclusive<usize>,
    scale: f64,
) -> impl Strategy<Value = Bezier<D>> {
    clamp_degrees(&degrees)
        .prop_flat_map(move |n| proptest::collection::vec(point::<D>(scale), n + 1))
        .prop_filter_map("a valid Bézier curve", |pts| Bezier::new(pts).ok())
}

/// A B-spline with a degree in `degrees`, `degree + 1 … degree + 8` control
/// points with coordinates in `[−scale, scale]`, and a random valid knot
/// vector: distinct interior knots with random spacing, and ends either
/// clamped (`degree + 1` equal knots) or spaced like the interior (so the
/// curve is smooth on its whole domain and its derivatives can be checked
/// anywhere). Degrees and `scale` are clamped as for [`bezier_curve`].
pub fn bspline_curve<const D: usize>(
    degrees: RangeInclusive<usize>,
    scale: f64,
) -> impl Strategy<Value = BSpline<D>> {
    clamp_degrees(&degrees)
        .prop_flat_map(move |p| {
            (
                Just(p),
                proptest::collection::vec(point::<D>(scale), p + 1..=p + 8),
            )
        })
        .prop_flat_map(|(p, pts)| {
            let n = pts.len();
            let gaps = proptest::collection::vec(0.1..1.0f64, n + p);
            (Just(p), Just(pts), gaps, any::<bool>())
        })
        .prop_map(|(p, pts, gaps, clamped)| {
            let mut knots = Vec::with_capacity(gaps.len() + 1);
            let mut t = 0.0;
            knots.push(t);
            for g in gaps {
                t += g;
                knots.push(t);
            }
            if clamped {
                let n = pts.len();
                let (start, end) = (knots[p], knots[n]);
                knots[..p].fill(start);
                knots[n + 1..].fill(end);
            }
            BSpline::new(p, knots, pts)
        })
        .prop_filter_map("a valid B-spline", Result::ok)
}

/// A profile for a surface of revolution: a uniform B-spline of degree 2 or
/// 3 (so its tangent is continuous) with 4–12 control points,
/// `x ∈ [0.05·scale, scale]`, heights strictly increasing (so the surface is
/// a simple tube). `scale` is clamped into `[1e-100, MAX_COORDINATE/8]`
/// (heights reach `±3·scale`); NaN and non-positive values give `1e-100`.
pub fn profile(scale: f64) -> impl Strategy<Value = BSpline<2>> {
    let scale = clamp_scale(scale, 1e-100, crate::MAX_COORDINATE / 8.0);
    (2usize..=3, 4usize..=12)
        .prop_flat_map(move |(p, n)| {
            (
                Just(p),
                proptest::collection::vec((0.05 * scale..=scale, 0.05 * scale..=0.5 * scale), n),
            )
        })
        .prop_map(|(p, rows)| {
            let mut y = -0.5 * rows.iter().map(|r| r.1).sum::<f64>();
            let pts = rows
                .into_iter()
                .map(|(x, dy)| {
                    y += dy;
                    Point2::new(x, y)
                })
                .collect();
            BSpline::uniform(p, pts)
        })
        .prop_filter_map("a valid profile", Result::ok)
}

/// A ray from a point on a sphere of radius `3·scale` about the origin,
/// aimed at a point in the cube `[−scale, scale]³`. `scale` is clamped into
/// `[1e-100, MAX_COORDINATE]`; NaN and non-positive values give `1e-100`.
pub fn ray(scale: f64) -> impl Strategy<Value = Ray> {
    let scale = clamp_scale(scale, 1e-100, crate::MAX_COORDINATE);
    (
        proptest::array::uniform3(-1.0..=1.0f64),
        proptest::array::uniform3(-scale..=scale),
    )
        .prop_filter_map("direction away from zero", move |(from, to)| {
            let v = Vector3::from(from);
            let n = v.norm();
            (n > 1e-3).then(|| {
                let origin = Point3::from(v / n * 3.0 * scale);
                Ray::new(origin, Point3::from(to) - origin)
            })
        })
}

/// Central difference of `f` at `t` with step `h`.
fn central<const D: usize>(f: impl Fn(f64) -> SVector<f64, D>, t: f64, h: f64) -> SVector<f64, D> {
    (f(t + h) - f(t - h)) / (2.0 * h)
}

/// Whether `error` is above `limit` or NaN (a NaN must fail a check).
fn exceeds(error: f64, limit: f64) -> bool {
    error.is_nan() || error > limit
}

/// Relative limit of the checkers (see the module docs).
const LIMIT: f64 = 1e-6;

/// Checks `Curve::derivative` against central differences of `Curve::eval`
/// at `samples` parameters strictly inside the domain, and
/// `eval_with_derivative` against both.
///
/// The limit is `1e-6 ×` the largest derivative magnitude sampled (plus the
/// same of the point scale over the domain length). Curves whose derivative
/// jumps (knots of high multiplicity) must be checked per smooth piece.
/// `samples` is clamped to [`MAX_SAMPLES`]. A domain that is not finite with
/// `start < end` breaks the [`Curve`] contract and is reported as a
/// violation.
pub fn check_curve_derivatives<const D: usize, C: Curve<D>>(
    curve: &C,
    samples: usize,
) -> Result<(), LawViolation> {
    let samples = samples.min(MAX_SAMPLES);
    let (a, b) = curve.domain();
    check_interval(a, b)?;
    let len = b - a;
    let h = f64::EPSILON.sqrt() * len;
    let ts: Vec<f64> = (0..samples)
        .map(|i| a + len * (i as f64 + 0.5) / samples as f64)
        .filter(|&t| t - h > a && t + h < b)
        .collect();
    let scale = ts.iter().fold(0.0_f64, |m, &t| {
        m.max(curve.derivative(t).amax())
            .max(curve.eval(t).coords.amax() / len)
    });
    let limit = LIMIT * scale.max(f64::MIN_POSITIVE);
    for &t in &ts {
        let fd = central(|s| curve.eval(s).coords, t, h);
        let d = curve.derivative(t);
        let error = (fd - d).amax();
        if exceeds(error, limit) {
            return Err(LawViolation {
                law: "derivative = central difference of eval",
                at: vec![t],
                error,
                limit,
            });
        }
        let (p, d2) = curve.eval_with_derivative(t);
        let error = (p - curve.eval(t)).amax().max((d2 - d).amax());
        if exceeds(error, limit) {
            return Err(LawViolation {
                law: "eval_with_derivative = (eval, derivative)",
                at: vec![t],
                error,
                limit,
            });
        }
    }
    Ok(())
}

/// The law that a parameter interval is finite and not empty.
fn check_interval(a: f64, b: f64) -> Result<(), LawViolation> {
    if a.is_finite() && b.is_finite() && a < b {
        return Ok(());
    }
    Err(LawViolation {
        law: "domain is finite with start < end",
        at: vec![a, b],
        error: if a.is_finite() && b.is_finite() {
            a - b
        } else {
            f64::INFINITY
        },
        limit: 0.0,
    })
}

/// The surface's domain, checked to be finite and non-empty in both
/// parameters.
fn checked_domain<S: Surface>(surface: &S) -> Result<[(f64, f64); 2], LawViolation> {
    let domain = surface.domain();
    for (a, b) in domain {
        check_interval(a, b)?;
    }
    Ok(domain)
}

/// Checks `Surface::partials` against central differences of `Surface::eval`
/// on an `n × n` grid strictly inside the domain (`n` clamped to
/// `1 ..= 64`; a domain that is not finite and non-empty is a violation).
pub fn check_surface_partials<S: Surface>(surface: &S, n: usize) -> Result<(), LawViolation> {
    let [(u0, u1), (v0, v1)] = checked_domain(surface)?;
    let (hu, hv) = (
        f64::EPSILON.sqrt() * (u1 - u0),
        f64::EPSILON.sqrt() * (v1 - v0),
    );
    let grid = grid(surface, n);
    let scale = grid.iter().fold(0.0_f64, |m, &(u, v)| {
        let (su, sv) = surface.partials(u, v);
        let p = surface.eval(u, v).coords.amax();
        m.max(su.amax())
            .max(sv.amax())
            .max(p / (u1 - u0))
            .max(p / (v1 - v0))
    });
    let limit = LIMIT * scale.max(f64::MIN_POSITIVE);
    for &(u, v) in &grid {
        if u - hu <= u0 || u + hu >= u1 || v - hv <= v0 || v + hv >= v1 {
            continue;
        }
        let (su, sv) = surface.partials(u, v);
        let fu = central(|s| surface.eval(s, v).coords, u, hu);
        let fv = central(|s| surface.eval(u, s).coords, v, hv);
        let error = (fu - su).amax().max((fv - sv).amax());
        if exceeds(error, limit) {
            return Err(LawViolation {
                law: "partials = central differences of eval",
                at: vec![u, v],
                error,
                limit,
            });
        }
    }
    Ok(())
}

/// Checks `Surface::normal` on an `n × n` grid: unit length, perpendicular
/// to both partials, and along `∂S/∂u × ∂S/∂v` where that is not tiny, or
/// along its negation at every such point (a surface of reversed
/// orientation; the first such point decides which) (`n` and the domain as
/// for [`check_surface_partials`]).
pub fn check_surface_normals<S: Surface>(surface: &S, n: usize) -> Result<(), LawViolation> {
    checked_domain(surface)?;
    // +1 along ∂S/∂u × ∂S/∂v, −1 against it: set by the first point where
    // the cross product is clear, then held at every other.
    let mut orientation = 0.0_f64;
    for (u, v) in grid(surface, n) {
        let (su, sv) = surface.partials(u, v);
        let cross = su.cross(&sv);
        let Some(normal) = surface.normal(u, v) else {
            if cross.norm() > 1e-8 * su.norm() * sv.norm() {
                return Err(LawViolation {
                    law: "normal exists where the partials span a plane",
                    at: vec![u, v],
                    error: cross.norm(),
                    limit: 1e-8 * su.norm() * sv.norm(),
                });
            }
            continue;
        };
        let checks = [
            ("normal has unit length", (normal.norm() - 1.0).abs(), 1e-12),
            (
                "normal ⟂ ∂S/∂u",
                normal.dot(&su).abs(),
                1e-9 * su.norm().max(1.0),
            ),
            (
                "normal ⟂ ∂S/∂v",
                normal.dot(&sv).abs(),
                1e-9 * sv.norm().max(1.0),
            ),
        ];
        for (law, error, limit) in checks {
            if exceeds(error, limit) {
                return Err(LawViolation {
                    law,
                    at: vec![u, v],
                    error,
                    limit,
                });
            }
        }
        let c = cross.norm();
        if c > 1e-6 * su.norm() * sv.norm() {
            if orientation == 0.0 {
                orientation = if cross.dot(&normal) < 0.0 { -1.0 } else { 1.0 };
            }
            let error = (cross * (orientation / c) - normal.into_inner()).norm();
            if exceeds(error, 1e-9) {
                return Err(LawViolation {
                    law: "normal along ±∂S/∂u × ∂S/∂v, one sign throughout",
                    at: vec![u, v],
                    error,
                    limit: 1e-9,
                });
            }
        }
    }
    Ok(())
}

/// Checks [`PatchBounds::bound_patch`] against samples: for the whole
/// domain and for each of the `4 × 4` and `3 × 5` sub-rectangles of it
/// (edges included, so that patch and knot boundaries are crossed), every
/// point of an `n × n` grid over the rectangle, its corners and edges
/// included, lies in the box (no slack: the box must be conservative).
/// `n` is clamped to `2 ..= 64`; a domain that is not finite and non-empty
/// is a violation.
///
/// ```
/// use revolve::testing::check_surface_bounds;
/// use revolve::BezierSurface;
/// use revolve::nalgebra::Point3;
///
/// let saddle = BezierSurface::new(vec![
///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 1.0)],
///     vec![Point3::new(1.0, 0.0, 1.0), Point3::new(1.0, 1.0, 0.0)],
/// ])?;
/// assert!(check_surface_bounds(&saddle, 9).is_ok());
/// # Ok::<(), revolve::Error>(())
/// ```
pub fn check_surface_bounds<S: PatchBounds>(surface: &S, n: usize) -> Result<(), LawViolation> {
    let [(u0, u1), (v0, v1)] = checked_domain(surface)?;
    let n = n.clamp(2, MAX_SAMPLES.isqrt());
    let at = |lo: f64, hi: f64, i: usize, m: usize| {
        if i == m {
            hi
        } else {
            lo + (hi - lo) * i as f64 / m as f64
        }
    };
    let mut rects = vec![((u0, u1), (v0, v1))];
    for (cu, cv) in [(4, 4), (3, 5)] {
        for i in 0..cu {
            for j in 0..cv {
                rects.push((
                    (at(u0, u1, i, cu), at(u0, u1, i + 1, cu)),
                    (at(v0, v1, j, cv), at(v0, v1, j + 1, cv)),
                ));
            }
        }
    }
    for (u, v) in rects {
        let b = surface.bound_patch(u, v);
        for i in 0..n {
            for j in 0..n {
                let (su, sv) = (at(u.0, u.1, i, n - 1), at(v.0, v.1, j, n - 1));
                let p = surface.eval(su, sv);
                if !b.contains(&p) {
                    // How far outside the box the sample lies.
                    let error =
                        (0..3).fold(0.0_f64, |m, k| m.max(b.min[k] - p[k]).max(p[k] - b.max[k]));
                    return Err(LawViolation {
                        law: "bound_patch contains the sub-patch",
                        at: vec![su, sv, u.0, u.1, v.0, v.1],
                        error: if error.is_nan() { f64::INFINITY } else { error },
                        limit: 0.0,
                    });
                }
            }
        }
    }
    Ok(())
}

/// An `n × n` grid of cell centres of the domain (`n` clamped to
/// `1 ..= √MAX_SAMPLES`).
fn grid<S: Surface>(surface: &S, n: usize) -> Vec<(f64, f64)> {
    let [(u0, u1), (v0, v1)] = surface.domain();
    let n = n.clamp(1, MAX_SAMPLES.isqrt());
    let at = |lo: f64, hi: f64, i: usize| lo + (hi - lo) * (i as f64 + 0.5) / n as f64;
    (0..n)
        .flat_map(|i| (0..n).map(move |j| (at(u0, u1, i), at(v0, v1, j))))
        .collect()
}

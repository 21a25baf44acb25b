//! The intersection curves of two NURBS surfaces
//! ([`NurbsSurface::intersect_surface`]): start points from the certified
//! curve–surface search on a grid of isocurves, each branch then traced by
//! predictor–corrector steps.
//!
//! # Method
//! The common points of `A(u, v)` and `B(s, t)` are the zeros of
//! `F(u, v, s, t) = A(u, v) − B(s, t)`: three equations in four unknowns,
//! curves in general. A branch either reaches the boundary of a domain
//! or closes on itself. Isocurves of each surface (at every knot, the
//! domain's ends included, and at three more parameters inside each knot
//! span, in both directions) are intersected with the other surface by
//! [`NurbsSurface::intersect_curve`], which misses no common point: every
//! branch that reaches a boundary, and every closed branch that crosses
//! one of those isocurves, gets a start point.
//!
//! From a start point not already on a traced branch, the branch is
//! followed both ways along `T = N_A × N_B` (the unit normals' cross
//! product): a predictor step of length `h` in the direction `T` (each
//! surface's parameter step by least squares on its partials), then
//! Newton's method with the minimum-norm step on `F = 0`
//! (`Δx = −Jᵀ(JJᵀ)⁻¹F`, `J` the 3×4 Jacobian). A step is accepted when the
//! corrector converges and the tangent turns by `θ` with `h·θ/8 ≤
//! tolerance` (the chord then stays within about the tolerance of the
//! curve); otherwise `h` is halved. A branch ends at a domain's boundary
//! (a seam of a closed surface, whose two ends are one curve, is crossed),
//! where it meets its own start (closed), or where the surfaces become
//! tangent or a parameterization singular (`|T|` below `10⁻⁸`, as at a
//! pole). Branches that then meet end to end are joined.
//!
//! # What is and is not certified
//! The start points come from a certified search; the traced points lie on
//! both surfaces to about `10⁻¹²` of the size (the corrector's
//! convergence). A closed branch that crosses none of the isocurves (a loop
//! smaller than a knot span's quarter) is missed, and two branches closer
//! together than the tolerance may be traced as one: the tracing itself is
//! not certified.

use super::CurveSurfaceHit;
use crate::{Error, Intersect, NurbsSurface, Surface};
use nalgebra::{Matrix2, Matrix3, Point3, Vector2, Vector3, Vector4};

/// Steps per branch and direction at most.
const MAX_STEPS: usize = 100_000;

/// Newton steps of the corrector at most.
const CORRECTOR_STEPS: usize = 12;

/// Extra isocurves inside each knot span, in each direction.
const INSIDE_SPAN: usize = 3;

/// A point of the intersection of two surfaces, with its parameters on
/// each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceIntersectionPoint {
    /// The point (the midpoint of the two surfaces' points there).
    pub point: Point3<f64>,
    /// Its parameters `(u, v)` on the first surface.
    pub uv_a: (f64, f64),
    /// Its parameters `(u, v)` on the second surface.
    pub uv_b: (f64, f64),
}

/// One branch of the intersection of two surfaces: a polyline whose
/// points lie on both surfaces, each chord within about the tolerance of
/// the branch.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceIntersectionCurve {
    /// The points in order along the branch.
    pub points: Vec<SurfaceIntersectionPoint>,
    /// Whether the branch closes on itself (the last point joins the
    /// first).
    pub closed: bool,
}

/// `(u, v, s, t)`: parameters on both surfaces.
type Params = Vector4<f64>;

impl NurbsSurface {
    /// Every branch of the intersection of this surface with `other`, as
    /// polylines on both surfaces whose chords stay within about
    /// `tolerance` of the branch (the method, and what is certified, are in
    /// the `tensor::surface_intersection` module docs).
    ///
    /// ```
    /// use revolve::{Nurbs, NurbsSurface, Revolution};
    /// use revolve::nalgebra::{Point2, Point3};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // The unit sphere (about the y axis) and the plane y = 0.6: the
    /// // circle of radius 0.8.
    /// let sphere = NurbsSurface::from_revolution(&Revolution::new(
    ///     Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?,
    /// ))?;
    /// let plane = NurbsSurface::bilinear(
    ///     Point3::new(-2.0, 0.6, -2.0), Point3::new(2.0, 0.6, -2.0),
    ///     Point3::new(-2.0, 0.6, 2.0), Point3::new(2.0, 0.6, 2.0),
    /// )?;
    /// let curves = sphere.intersect_surface(&plane, 1e-6)?;
    /// assert_eq!(curves.len(), 1);
    /// assert!(curves[0].closed);
    /// for p in &curves[0].points {
    ///     assert!((p.point.coords.xz().norm() - 0.8).abs() < 1e-12);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; the errors of [`intersect_curve`](Self::intersect_curve)
    /// on the isocurves: [`Error::ToleranceTooSmall`],
    /// [`Error::CurveOnSurface`] when an isocurve of one lies on the other
    /// (the surfaces overlap along it, e.g. two patches sharing an edge).
    pub fn intersect_surface(
        &self,
        other: &NurbsSurface,
        tolerance: f64,
    ) -> Result<Vec<SurfaceIntersectionCurve>, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidTolerance { tolerance });
        }
        let mut seeds: Vec<Params> = Vec::new();
        for (first, second, swap) in [(self, other, false), (other, self, true)] {
            for (axis, knots) in [(0, first.knots().0), (1, first.knots().1)] {
                let domain = first.domain()[axis];
                for x in grid(knots, domain) {
                    let iso = if axis == 0 {
                        first.isocurve_u(x)?
                    } else {
                        first.isocurve_v(x)?
                    };
                    let found: Vec<(f64, (f64, f64))> =
                        match second.intersect_curve(&iso, tolerance) {
                            Ok(hits) => hits
                                .into_iter()
                                .map(|CurveSurfaceHit { t, uv, .. }| (t, uv))
                                .collect(),
                            // The isocurve runs on the other surface: it is
                            // (part of) a branch; its middle is a start.
                            Err(Error::CurveOnSurface { t, u, v }) => {
                                let mid = |(p, q): (f64, f64)| 0.5 * (p + q);
                                vec![(mid(t), (mid(u), mid(v)))]
                            }
                            Err(e) => return Err(e),
                        };
                    for (t, uv) in found {
                        let on_first = if axis == 0 { (x, t) } else { (t, x) };
                        let (ua, ub) = if swap { (uv, on_first) } else { (on_first, uv) };
                        seeds.push(Vector4::new(ua.0, ua.1, ub.0, ub.1));
                    }
                }
            }
        }
        let pair = Pair::new(self, other, tolerance);
        let mut curves: Vec<SurfaceIntersectionCurve> = Vec::new();
        for seed in seeds {
            let Some(x) = pair.correct(seed) else {
                continue;
            };
            let p = pair.point(&x);
            if curves.iter().any(|c| near_polyline(c, &p, 4.0 * tolerance)) {
                continue;
            }
            curves.push(pair.trace(x));
        }
        Ok(joined(curves, 4.0 * tolerance))
    }
}

/// The branches with those that meet end to end (within `within`: a
/// branch through a pole of a surface's parameterization, where the
/// tracing stops, continues on the other side) joined into one, a branch
/// whose ends meet closed, and single points on another branch dropped.
fn joined(mut curves: Vec<SurfaceIntersectionCurve>, within: f64) -> Vec<SurfaceIntersectionCurve> {
    let ends =
        |c: &SurfaceIntersectionCurve| (c.points[0].point, c.points[c.points.len() - 1].point);
    loop {
        let mut merge = None;
        'search: for i in 0..curves.len() {
            for j in i + 1..curves.len() {
                if curves[i].closed || curves[j].closed {
                    continue;
                }
                let ((a0, a1), (b0, b1)) = (ends(&curves[i]), ends(&curves[j]));
                for (k, (p, q)) in [(a1, b0), (a1, b1), (a0, b0), (a0, b1)].iter().enumerate() {
                    if (p - q).norm() <= within {
                        merge = Some((i, j, k));
                        break 'search;
                    }
                }
            }
        }
        let Some((i, j, k)) = merge else {
            break;
        };
        let mut b = curves.remove(j).points;
        let a = &mut curves[i].points;
        // Orient both so that a's end meets b's start.
        if k >= 2 {
            a.reverse();
        }
        if k % 2 == 1 {
            b.reverse();
        }
        a.extend(b.into_iter().skip(1));
    }
    for c in &mut curves {
        let (first, last) = ends(c);
        let long = c.points.len() > 2
            && c.points
                .windows(2)
                .map(|w| (w[1].point - w[0].point).norm())
                .sum::<f64>()
                > 8.0 * within;
        if !c.closed && long && (first - last).norm() <= within {
            c.points.pop();
            c.closed = true;
        }
    }
    let lone: Vec<bool> = (0..curves.len())
        .map(|i| {
            curves[i].points.len() == 1
                && curves.iter().enumerate().any(|(j, c)| {
                    j != i
                        && c.points.len() > 1
                        && near_polyline(c, &curves[i].points[0].point, within)
                })
        })
        .collect();
    let mut k = 0;
    curves.retain(|_| {
        k += 1;
        !lone[k - 1]
    });
    curves
}

/// Every distinct knot inside `domain` (its ends included) and
/// [`INSIDE_SPAN`] evenly spaced parameters inside each knot span.
fn grid(knots: &[f64], (lo, hi): (f64, f64)) -> Vec<f64> {
    let mut breaks: Vec<f64> = knots
        .iter()
        .copied()
        .filter(|&k| (lo..=hi).contains(&k))
        .collect();
    breaks.dedup();
    let mut out = Vec::new();
    for w in breaks.windows(2) {
        out.push(w[0]);
        for k in 1..=INSIDE_SPAN {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / (INSIDE_SPAN + 1) as f64);
        }
    }
    out.extend(breaks.last());
    out
}

/// Whether `p` lies within `within` of a chord of `curve`.
fn near_polyline(curve: &SurfaceIntersectionCurve, p: &Point3<f64>, within: f64) -> bool {
    let pts = &curve.points;
    if pts.len() == 1 {
        return (pts[0].point - p).norm() <= within;
    }
    let mut chords: Vec<(Point3<f64>, Point3<f64>)> =
        pts.windows(2).map(|w| (w[0].point, w[1].point)).collect();
    if curve.closed {
        if let (Some(first), Some(last)) = (pts.first(), pts.last()) {
            chords.push((last.point, first.point));
        }
    }
    chords.iter().any(|(a, b)| {
        let d = b - a;
        let len2 = d.norm_squared();
        let s = if len2 > 0.0 {
            ((p - a).dot(&d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + d * s - p).norm() <= within
    })
}

/// The two surfaces and the tracing's scales.
struct Pair<'a> {
    a: &'a NurbsSurface,
    b: &'a NurbsSurface,
    tolerance: f64,
    /// The corrector's target for `|F|`.
    converged: f64,
    /// The longest step.
    longest: f64,
    domain: [(f64, f64); 4],
    /// Whether each parameter's two domain ends are one curve (a seam).
    wraps: [bool; 4],
}

impl<'a> Pair<'a> {
    fn new(a: &'a NurbsSurface, b: &'a NurbsSurface, tolerance: f64) -> Self {
        let (ba, bb) = (a.bounds(), b.bounds());
        let size = ba.extent().amax().max(bb.extent().amax());
        let magnitude = [ba.min, ba.max, bb.min, bb.max]
            .iter()
            .map(|p| p.coords.amax())
            .fold(size, f64::max);
        let [ua, va] = a.domain();
        let [ub, vb] = b.domain();
        let same = 1e-12 * magnitude.max(f64::MIN_POSITIVE);
        let [wu, wv] = seams(a, same);
        let [ws, wt] = seams(b, same);
        Pair {
            a,
            b,
            tolerance,
            converged: 1e-12 * magnitude.max(f64::MIN_POSITIVE),
            longest: 0.05 * size.max(f64::MIN_POSITIVE),
            domain: [ua, va, ub, vb],
            wraps: [wu, wv, ws, wt],
        }
    }

    /// `x` brought into the domains: across a seam to the other end (the
    /// parameter is periodic there), elsewhere clamped.
    fn clamp(&self, x: Params) -> Params {
        Vector4::from_fn(|i, _| {
            let (lo, hi) = self.domain[i];
            let period = hi - lo;
            match x[i] {
                y if self.wraps[i] && y < lo => (y + period).min(hi),
                y if self.wraps[i] && y > hi => (y - period).max(lo),
                y => y.clamp(lo, hi),
            }
        })
    }

    /// `F = A(u, v) − B(s, t)` and the four partials (columns of `J`).
    fn residual(&self, x: &Params) -> (Vector3<f64>, [Vector3<f64>; 4]) {
        let f = self.a.eval(x[0], x[1]) - self.b.eval(x[2], x[3]);
        let (au, av) = self.a.partials(x[0], x[1]);
        let (bs, bt) = self.b.partials(x[2], x[3]);
        (f, [au, av, -bs, -bt])
    }

    /// Newton's method with minimum-norm steps onto `F = 0`, kept in the
    /// domains; `None` unless `|F|` falls below the target.
    fn correct(&self, mut x: Params) -> Option<Params> {
        for _ in 0..CORRECTOR_STEPS {
            let (f, j) = self.residual(&x);
            if f.norm() <= self.converged {
                return Some(x);
            }
            let jjt = Matrix3::from_fn(|r, c| (0..4).map(|k| j[k][r] * j[k][c]).sum());
            let y = jjt.lu().solve(&(-f))?;
            let step = Vector4::from_fn(|k, _| j[k].dot(&y));
            x = self.clamp(x + step);
        }
        let (f, _) = self.residual(&x);
        (f.norm() <= self.converged).then_some(x)
    }

    fn point(&self, x: &Params) -> Point3<f64> {
        let (p, q) = (self.a.eval(x[0], x[1]), self.b.eval(x[2], x[3]));
        Point3::from((p.coords + q.coords) * 0.5)
    }

    fn record(&self, x: &Params) -> SurfaceIntersectionPoint {
        SurfaceIntersectionPoint {
            point: self.point(x),
            uv_a: (x[0], x[1]),
            uv_b: (x[2], x[3]),
        }
    }

    /// The unit tangent `N_A × N_B` (normalized normals) and the parameter
    /// velocities that follow it on each surface, or `None` where the
    /// surfaces are tangent.
    fn tangent(&self, x: &Params) -> Option<(Vector3<f64>, Params)> {
        let (au, av) = self.a.partials(x[0], x[1]);
        let (bs, bt) = self.b.partials(x[2], x[3]);
        let na = au.cross(&av).try_normalize(0.0)?;
        let nb = bs.cross(&bt).try_normalize(0.0)?;
        let t = na.cross(&nb);
        if t.norm() < 1e-8 {
            return None;
        }
        let t = t.normalize();
        let solve = |p: Vector3<f64>, q: Vector3<f64>| {
            let m = Matrix2::new(p.dot(&p), p.dot(&q), p.dot(&q), q.dot(&q));
            m.lu().solve(&Vector2::new(p.dot(&t), q.dot(&t)))
        };
        let (da, db) = (solve(au, av)?, solve(bs, bt)?);
        Some((t, Vector4::new(da.x, da.y, db.x, db.y)))
    }

    /// The branch through `x`, traced both ways.
    fn trace(&self, x: Params) -> SurfaceIntersectionCurve {
        let (forward, closed) = self.march(x, 1.0);
        if closed {
            return SurfaceIntersectionCurve {
                points: forward.iter().map(|x| self.record(x)).collect(),
                closed,
            };
        }
        // Backward: a branch whose forward march stopped at once (a seam
        // of a closed surface, where the branch leaves the domain) may still
        // close on itself this way.
        let (backward, closed) = self.march(x, -1.0);
        let points = backward
            .iter()
            .rev()
            .chain(forward.iter().skip(1))
            .map(|x| self.record(x))
            .collect();
        SurfaceIntersectionCurve { points, closed }
    }

    /// The points from `start` along `sign·T` to a boundary, a tangency or
    /// back to `start` (then `true`).
    fn march(&self, start: Params, sign: f64) -> (Vec<Params>, bool) {
        let mut out = vec![start];
        let origin = self.point(&start);
        let mut x = start;
        let mut h = 0.1 * self.longest;
        let shortest = 1e-9 * self.longest;
        let mut travelled = 0.0;
        for _ in 0..MAX_STEPS {
            let Some((t0, velocity)) = self.tangent(&x) else {
                break;
            };
            let velocity = velocity * sign;
            // Shorten the step to land on the first boundary it would cross.
            let mut reach = h;
            let mut boundary: Option<(usize, f64)> = None;
            for i in (0..4).filter(|&i| !self.wraps[i]) {
                let (lo, hi) = self.domain[i];
                let target = if velocity[i] > 0.0 {
                    hi
                } else if velocity[i] < 0.0 {
                    lo
                } else {
                    continue;
                };
                let room = (target - x[i]) / velocity[i];
                if room <= reach {
                    reach = room.max(0.0);
                    boundary = Some((i, target));
                }
            }
            // A seam (the domain's two ends one curve) is crossed, not a
            // boundary: its parameter wraps (see `clamp`).
            if reach <= shortest && boundary.is_some() {
                break;
            }
            let Some(next) = self.correct(self.clamp(x + velocity * reach)) else {
                h *= 0.5;
                if h < shortest {
                    break;
                }
                continue;
            };
            let turned = match self.tangent(&next) {
                Some((t1, _)) => t0.dot(&t1).clamp(-1.0, 1.0).acos(),
                None => 0.0,
            };
            let chord = (self.point(&next) - self.point(&x)).norm();
            if chord * turned / 8.0 > self.tolerance && reach > shortest {
                h = 0.5 * reach;
                continue;
            }
            travelled += chord;
            // Back at the start: a closed branch.
            let back = (self.point(&next) - origin).norm();
            if out.len() > 2 && travelled > 2.0 * chord && back <= chord.max(self.tolerance) {
                return (out, true);
            }
            out.push(next);
            x = next;
            // A step cut short by a boundary ends on it: the next round
            // wraps across a seam or ends the branch.
            if boundary.is_none() {
                h = (1.5 * h).min(self.longest);
            }
        }
        (out, false)
    }
}

/// Whether the surface's two `u` ends are one curve, and its two `v` ends
/// (a closed surface's seam): the boundary curves agree at 17 parameters
/// within `same`.
fn seams(s: &NurbsSurface, same: f64) -> [bool; 2] {
    let [du, dv] = s.domain();
    let agree = |first: &dyn Fn(f64) -> Point3<f64>,
                 second: &dyn Fn(f64) -> Point3<f64>,
                 (lo, hi): (f64, f64)| {
        (0..=16).all(|k| {
            let x = lo + (hi - lo) * k as f64 / 16.0;
            (first(x) - second(x)).norm() <= same
        })
    };
    [
        agree(&|v| s.eval(du.0, v), &|v| s.eval(du.1, v), dv),
        agree(&|u| s.eval(u, dv.0), &|u| s.eval(u, dv.1), du),
    ]
}

//! The nearest point of a surface of revolution to a query point, reduced
//! to the nearest point of its profile in the query point's meridian plane.

use super::meridian_newton::meridian_angle;
use super::surface::Revolution;
use super::turn_angle::turn_angle;
use crate::curve::{RationalBezier, RationalBezierSpan, check_query_point, scaled_norm};
use crate::surface_nearest::distance;
use crate::{Curve, CurveProjector, Error, NearestPoint, SurfaceNearest};
use nalgebra::{Point2, Point3, Vector2, Vector3};

impl<C: Curve<2>> Revolution<C> {
    /// The point of the surface nearest to `p`: the least `|S(u, θ) − p|`
    /// over the whole domain (profile ends and poles included).
    ///
    /// # The reduction to the profile
    /// In the local frame (axis `y`) let `p = (pₓ, p_y, p_z)` and
    /// `r = √(pₓ² + p_z²)` its distance from the axis. The circle of the
    /// profile point `(x, y)` is nearest to `p` in `p`'s meridian plane, at
    /// distance `√((|x| − r)² + (y − p_y)²)`, and `(|x| − r)² = min((x − r)²,
    /// (x + r)²)`: the distance from the surface to `p` is the distance from
    /// the profile to `(r, p_y)`, or to `(−r, p_y)` if the profile reaches
    /// `x < 0` (scene files write profiles so; the part at `x < 0` is turned
    /// to `p`'s side by half a turn), whichever is less. That planar query
    /// is [`Curve::nearest_point`]'s (one [`CurveProjector`] for both
    /// points), and the surface point is the profile point turned into
    /// `p`'s meridian: `θ = atan2(−p_z, pₓ)` for `x ≥ 0`, `θ + π` for
    /// `x < 0`, in `[0, 2π]` as [`Hit::uv`](crate::Hit::uv) gives it.
    ///
    /// # Edge rules
    /// On the axis (`r = 0`) every angle is as near: `θ = 0` is returned.
    /// The answer's `uv` is `(u, θ)`, `point` the surface point there and
    /// `distance = |point − p|`; `patch` is 0.
    ///
    /// # What is certified
    /// For a profile with [rational Bézier spans](Curve::rational_bezier_spans)
    /// (Bézier, B-spline, NURBS profiles: spheres, tori, lathed parts) the
    /// profile's answer is certified global (every critical point of the
    /// planar distance isolated, see [`CurveProjector`]), so the distance
    /// returned exceeds the true minimum by rounding only, and `certified`
    /// is `true`. A profile without spans gets the profile's sampled answer
    /// ([`Curve::nearest_point`]), `certified: false`.
    ///
    /// ```
    /// use revolve::{Nurbs, Revolution, Surface};
    /// use revolve::nalgebra::{Point2, Point3};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // A unit sphere: the nearest point of an outside point is on the ray
    /// // from the centre through it.
    /// let sphere = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?);
    /// let p = Point3::new(1.0, 2.0, 2.0);
    /// let near = sphere.nearest_point(&p)?;
    /// assert!(near.certified);
    /// assert!((near.point - p / 3.0).norm() < 1e-15);
    /// assert!((near.distance - 2.0).abs() < 1e-15);
    /// assert!((sphere.eval(near.uv.0, near.uv.1) - near.point).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidQueryPoint`] for a coordinate of `p` that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE); the
    /// [contract error](Self::contract_error) of a surface whose profile or
    /// placement is broken; the profile's errors from
    /// [`Curve::nearest_point`].
    pub fn nearest_point(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        check_query_point(p)?;
        if let Some(e) = &self.broken {
            return Err(e.clone());
        }
        let origin = self.to_world.translation.vector;
        let local = self.rotation.inverse_transform_vector(&(p.coords - origin));
        let r = local.x.hypot(local.z);
        let near = self.profile_nearest(r, local.y)?;
        let x = near.point.x;
        // The meridian's direction, scaled first so that its squares do not
        // underflow for a point within 1e-154 of the axis.
        let m = local.x.abs().max(local.z.abs());
        let direction = if m > 0.0 { local / m } else { local };
        let (sn, cs) = meridian_angle(&direction, x);
        let on_surface = Vector3::new(x * cs, near.point.y, -x * sn);
        let point = Point3::from(self.rotation * on_surface + origin);
        Ok(SurfaceNearest {
            uv: (near.t, turn_angle(sn, cs)),
            point,
            distance: distance(&point, p),
            certified: near.certified,
            patch: 0,
        })
    }

    /// The profile's point nearest to `(r, y)` or, where the profile
    /// reaches `x < 0`, to `(−r, y)` (`r ≥ 0`), whichever is nearer (the
    /// first on a tie). A query point beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE) (a far point turned into
    /// the local frame) is answered with the profile and the point scaled
    /// by ¼ (exactly), the lengths scaled back.
    fn profile_nearest(&self, r: f64, y: f64) -> Result<NearestPoint<2>, Error> {
        let factor = if r.max(y.abs()) > crate::MAX_COORDINATE {
            0.25
        } else {
            1.0
        };
        let (outer, inner) = (Point2::new(r, y) * factor, Point2::new(-r, y) * factor);
        let nearer = |a: NearestPoint<2>, b: NearestPoint<2>| {
            if b.distance < a.distance { b } else { a }
        };
        let near = match self.profile.rational_bezier_spans() {
            Some(mut spans) => {
                if factor != 1.0 {
                    for span in &mut spans {
                        let points = span.curve.points().iter().map(|q| q * factor).collect();
                        let weights = span.curve.weights().to_vec();
                        span.curve = RationalBezier::new(points, weights)?;
                    }
                }
                let negative = spans
                    .iter()
                    .any(|s| s.curve.points().iter().any(|q| q.x < 0.0));
                let projector = CurveProjector::from_spans(spans.clone())?;
                let near = polish(&spans, &outer, projector.nearest(&outer)?);
                if negative && r > 0.0 {
                    nearer(near, polish(&spans, &inner, projector.nearest(&inner)?))
                } else {
                    near
                }
            }
            None if factor != 1.0 => {
                let scaled = Scaled {
                    curve: &self.profile,
                    factor,
                };
                nearer(scaled.nearest_point(&outer)?, scaled.nearest_point(&inner)?)
            }
            None => {
                let near = self.profile.nearest_point(&outer)?;
                if r > 0.0 {
                    nearer(near, self.profile.nearest_point(&inner)?)
                } else {
                    near
                }
            }
        };
        Ok(NearestPoint {
            point: near.point / factor,
            distance: near.distance / factor,
            ..near
        })
    }
}

/// Newton steps of the polish at most.
const POLISH_STEPS: usize = 8;

/// The profile's nearest point `near` to `q` polished by Newton's method on
/// its span, `f(s) = (C(s) − q)·C′(s)` with `f′ = |C′|² + (C − q)·C″` (the
/// span's own derivatives), kept in the span; the polished point replaces
/// `near` unless it is farther beyond rounding (the root isolation places
/// the point to about `10⁻¹⁰`; the distance is flat there, the point is
/// not).
fn polish(
    spans: &[RationalBezierSpan<2>],
    q: &Point2<f64>,
    near: NearestPoint<2>,
) -> NearestPoint<2> {
    let Some(span) = spans
        .iter()
        .find(|s| s.knots.0 <= near.t && near.t <= s.knots.1)
    else {
        return near;
    };
    let (a, b) = span.knots;
    let mut s = ((near.t - a) / (b - a)).clamp(0.0, 1.0);
    let mut d = [Vector2::zeros(); 3];
    let mut last_step = f64::INFINITY;
    for _ in 0..POLISH_STEPS {
        if span.curve.derivatives(s, &mut d).is_err() {
            return near;
        }
        let r = d[0] - q.coords;
        let (f, df) = (r.dot(&d[1]), d[1].norm_squared() + r.dot(&d[2]));
        if !(df > 0.0 && f.is_finite() && df.is_finite()) {
            break;
        }
        let next = (s - f / df).clamp(0.0, 1.0);
        let step = (next - s).abs();
        if step >= last_step || step == 0.0 {
            break;
        }
        (s, last_step) = (next, step);
        if step <= 4.0 * f64::EPSILON {
            break;
        }
    }
    let point = if s <= 0.0 {
        span.curve.points()[0]
    } else if s >= 1.0 {
        span.curve.points()[span.curve.points().len() - 1]
    } else {
        span.curve.eval(s)
    };
    let distance = scaled_norm(point - q);
    let size = point.coords.amax().max(q.coords.amax());
    if distance <= near.distance + 16.0 * f64::EPSILON * size {
        let t = if s <= 0.0 {
            a
        } else if s >= 1.0 {
            b
        } else {
            a + (b - a) * s
        };
        NearestPoint {
            t,
            point,
            distance,
            ..near
        }
    } else {
        near
    }
}

/// A profile scaled by a power of two (for far query points), known by its
/// values and derivatives alone.
struct Scaled<'a, C> {
    curve: &'a C,
    factor: f64,
}

impl<C: Curve<2>> Curve<2> for Scaled<'_, C> {
    fn domain(&self) -> (f64, f64) {
        self.curve.domain()
    }
    fn eval(&self, t: f64) -> Point2<f64> {
        self.curve.eval(t) * self.factor
    }
    fn derivative(&self, t: f64) -> Vector2<f64> {
        self.curve.derivative(t) * self.factor
    }
}

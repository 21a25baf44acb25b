//! Surfaces of revolution as exact NURBS surfaces
//! ([`NurbsSurface::from_revolution`]).
//!
//! This file joins the two surface layers (`revolution/` and `tensor/`,
//! which do not know each other).

use crate::curve::RationalBezierSpan;
use crate::{Curve, Error, NurbsSurface, Revolution};
use nalgebra::{Point3, Vector2};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI, SQRT_2, TAU};

/// The knots of the full circle in `v`: four quarter turns, `v = θ` at
/// each quarter.
fn circle_knots() -> Vec<f64> {
    let q = quarter_starts();
    vec![
        0.0, 0.0, 0.0, q[1], q[1], q[2], q[2], q[3], q[3], TAU, TAU, TAU,
    ]
}

/// Where the four quarters start: `0, π/2, π, 3π/2`.
fn quarter_starts() -> [f64; 4] {
    [0.0, FRAC_PI_2, PI, 3.0 * FRAC_PI_2]
}

/// The unit circle's control points in the local `(x, z)` plane, traced as
/// `(cos θ, −sin θ)`, and their weights: the four quarter arcs of degree 2
/// with the corners weighted `√2/2`.
fn circle_net() -> [(Vector2<f64>, f64); 9] {
    let h = FRAC_1_SQRT_2;
    [
        (Vector2::new(1.0, 0.0), 1.0),
        (Vector2::new(1.0, -1.0), h),
        (Vector2::new(0.0, -1.0), 1.0),
        (Vector2::new(-1.0, -1.0), h),
        (Vector2::new(-1.0, 0.0), 1.0),
        (Vector2::new(-1.0, 1.0), h),
        (Vector2::new(0.0, 1.0), 1.0),
        (Vector2::new(1.0, 1.0), h),
        (Vector2::new(1.0, 0.0), 1.0),
    ]
}

/// The angle within a quarter arc (`[0, π/2]`) at the quarter's own
/// parameter `s ∈ [0, 1]`: `φ = π/4 + 2·atan((√2 − 1)(2s − 1))`.
fn quarter_angle(s: f64) -> f64 {
    FRAC_PI_2 / 2.0 + 2.0 * ((SQRT_2 - 1.0) * (2.0 * s - 1.0)).atan()
}

/// The inverse of [`quarter_angle`]: `s = (tan((φ − π/4)/2)/(√2 − 1) + 1)/2`.
fn quarter_parameter(phi: f64) -> f64 {
    let s = (((phi - FRAC_PI_2 / 2.0) / 2.0).tan() / (SQRT_2 - 1.0) + 1.0) / 2.0;
    s.clamp(0.0, 1.0)
}

/// The profile's rational Bézier spans, checked to follow each other
/// without gaps, all raised to the highest degree.
fn profile_spans<C: Curve<2>>(profile: &C) -> Result<Vec<RationalBezierSpan<2>>, Error> {
    let spans = profile
        .rational_bezier_spans()
        .ok_or(Error::NotPiecewiseRational)?;
    if spans.is_empty() {
        return Err(Error::SpansOutOfOrder { index: 0 });
    }
    for (index, pair) in spans.windows(2).enumerate() {
        let (end, start) = (pair[0].knots.1, pair[1].knots.0);
        if start > end {
            return Err(Error::SpanGap {
                index: index + 1,
                previous_end: end,
                start,
            });
        }
        if start < end || pair[1].knots.1 <= start {
            return Err(Error::SpansOutOfOrder { index: index + 1 });
        }
    }
    let degree = spans.iter().map(|s| s.curve.degree()).max().unwrap_or(0);
    spans
        .into_iter()
        .map(|s| {
            let d = s.curve.degree();
            let curve = if d < degree {
                s.curve.elevate_degree(degree - d)?
            } else {
                s.curve
            };
            Ok(RationalBezierSpan {
                knots: s.knots,
                curve,
            })
        })
        .collect()
}

impl NurbsSurface {
    /// The surface of revolution `r` as a NURBS surface, exactly: the same
    /// points at the same `u`, the same normals, the same hits.
    ///
    /// In `r`'s local frame the revolution is
    /// `S(u, θ) = (x(u) cos θ, y(u), −x(u) sin θ)` (see [`Revolution`]).
    /// The NURBS surface is the tensor product of
    /// - in `u`, the profile's [rational Bézier
    ///   spans](Curve::rational_bezier_spans) (all raised to the highest
    ///   degree `p`), each on its own knot interval with knots of
    ///   multiplicity `p + 1` at every break (so each span keeps its own
    ///   weights and the surface's `u` is the profile's parameter);
    /// - in `v ∈ [0, 2π]`, the unit circle `(cos θ, −sin θ)` in the local
    ///   `xz`-plane as four rational quadratic quarter arcs (weights
    ///   `1, √2/2, 1`, knots `0, π/2, π, 3π/2, 2π` doubled inside).
    ///
    /// The grid is `Pᵢⱼ = (xᵢcⱼ, yᵢ, xᵢsⱼ)` with weights `wᵢωⱼ` (`(xᵢ, yᵢ)`,
    /// `wᵢ` the profile's, `(cⱼ, sⱼ)`, `ωⱼ` the circle's), exact by the
    /// factoring argument of [`sweep`](Self::sweep): the weight function is
    /// `W(u)Ω(v)` and the numerator's coordinates are products of the
    /// profile's and the circle's. Then every control point is mapped by
    /// the revolution's placement [`to_world`](Revolution::to_world)
    /// (affine invariance).
    ///
    /// The parametrization: `u` is the profile's; `v` equals `θ` at every
    /// quarter turn and in between is the quarter arc's rational parameter,
    /// `θ = kπ/2 + π/4 + 2·atan((√2 − 1)(2s − 1))` with `s` the parameter
    /// within quarter `k` ([`revolution_v`](Self::revolution_v) and
    /// [`revolution_angle`](Self::revolution_angle) convert), increasing
    /// with `θ`. So `∂S/∂v` is a positive multiple of `∂S/∂θ` and the
    /// NURBS normal `∂S/∂u × ∂S/∂v` points the way of the revolution's
    /// (no parameter is flipped); a [reversed](Revolution::reversed)
    /// revolution gives a reversed surface. The tolerance is kept. On the
    /// axis (`x = 0`) the row of control points collapses to a point and
    /// the normal is the collapsed edge's limit, as the revolution's is.
    ///
    /// # Errors
    /// The revolution's [`contract_error`](Revolution::contract_error) if
    /// it has one (a broken profile or placement);
    /// [`Error::NotPiecewiseRational`] for a profile without rational Bézier
    /// spans (whose revolution intersects an approximation);
    /// [`Error::SpanGap`] when a span starts after the previous one ends,
    /// [`Error::SpansOutOfOrder`] when it starts before or is empty; the
    /// errors of [`RationalBezier::elevate_degree`](crate::RationalBezier::elevate_degree) and of
    /// [`NurbsSurface::new`] on the grid.
    ///
    /// ```
    /// use revolve::{Intersect, Nurbs, NurbsSurface, Ray, Revolution, Surface};
    /// use revolve::nalgebra::{Point2, Point3, Unit, Vector3};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // A unit sphere placed with its axis along x through (1, 2, 3).
    /// let arc = Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?;
    /// let r = Revolution::new(arc).with_axis(Point3::new(1.0, 2.0, 3.0), Unit::new_normalize(Vector3::x()));
    /// let s = NurbsSurface::from_revolution(&r)?;
    /// for (u, theta) in [(0.2, 0.0), (0.5, 1.0), (0.8, 4.0)] {
    ///     let v = NurbsSurface::revolution_v(theta);
    ///     assert!((s.eval(u, v) - r.eval(u, theta)).norm() < 1e-14);
    ///     let (n, m) = (s.normal(u, v).unwrap(), r.normal(u, theta).unwrap());
    ///     assert!((n.into_inner() - m.into_inner()).norm() < 1e-13);
    /// }
    /// let ray = Ray::new(Point3::new(1.0, 2.0, -3.0), Vector3::z());
    /// let (a, b) = (s.intersect(&ray, 0.0, 99.0).unwrap(), r.intersect(&ray, 0.0, 99.0).unwrap());
    /// assert!((a.t - b.t).abs() < 1e-12);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn from_revolution<C: Curve<2>>(r: &Revolution<C>) -> Result<NurbsSurface, Error> {
        if let Some(e) = r.contract_error() {
            return Err(e.clone());
        }
        let spans = profile_spans(r.profile())?;
        let p = spans[0].curve.degree();
        let mut u_knots = Vec::with_capacity((spans.len() + 1) * (p + 1));
        u_knots.extend(std::iter::repeat_n(spans[0].knots.0, p + 1));
        for span in &spans {
            u_knots.extend(std::iter::repeat_n(span.knots.1, p + 1));
        }
        let circle = circle_net();
        let to_world = r.to_world();
        let mut points = Vec::with_capacity(spans.len() * (p + 1));
        let mut weights = Vec::with_capacity(spans.len() * (p + 1));
        for span in &spans {
            for (q, &w) in span.curve.points().iter().zip(span.curve.weights()) {
                points.push(
                    circle
                        .iter()
                        .map(|(c, _)| to_world * Point3::new(q.x * c.x, q.y, q.x * c.y))
                        .collect(),
                );
                weights.push(circle.iter().map(|&(_, omega)| w * omega).collect());
            }
        }
        let surface = NurbsSurface::new((p, 2), (u_knots, circle_knots()), points, weights)?
            .with_tolerance(*r.tolerance());
        Ok(if r.reversed {
            surface.reversed()
        } else {
            surface
        })
    }

    /// The NURBS parameter `v ∈ [0, 2π]` of
    /// [`from_revolution`](Self::from_revolution)'s surfaces at the
    /// revolution's angle `θ`: `θ` is first brought into `[0, 2π]` (a
    /// multiple of `2π` added; NaN and infinities, which a revolution
    /// evaluates at `θ = 0`, give 0), then in quarter `k` (`θ = kπ/2 + φ`,
    /// `φ ∈ [0, π/2]`) `v = kπ/2 + (π/2)·s` with
    /// `s = (tan((φ − π/4)/2)/(√2 − 1) + 1)/2`. `v = θ` at every quarter
    /// turn; monotone.
    ///
    /// ```
    /// use revolve::NurbsSurface;
    /// use std::f64::consts::{FRAC_PI_2, PI};
    ///
    /// assert_eq!(NurbsSurface::revolution_v(PI), PI);
    /// assert!((NurbsSurface::revolution_v(FRAC_PI_2 / 2.0) - FRAC_PI_2 / 2.0).abs() < 1e-15);
    /// let v = NurbsSurface::revolution_v(0.3);
    /// assert!((NurbsSurface::revolution_angle(v) - 0.3).abs() < 1e-15);
    /// ```
    pub fn revolution_v(theta: f64) -> f64 {
        if !theta.is_finite() {
            return 0.0;
        }
        let theta = if (0.0..=TAU).contains(&theta) {
            theta
        } else {
            theta.rem_euclid(TAU)
        };
        let starts = quarter_starts();
        let k = starts.iter().rposition(|&s| s <= theta).unwrap_or(0);
        let end = if k == 3 { TAU } else { starts[k + 1] };
        if theta >= end || theta <= starts[k] {
            return if theta >= end { end } else { starts[k] };
        }
        let s = quarter_parameter(theta - starts[k]);
        (starts[k] + s * (end - starts[k])).clamp(starts[k], end)
    }

    /// The revolution's angle `θ ∈ [0, 2π]` at the NURBS parameter `v` of
    /// [`from_revolution`](Self::from_revolution)'s surfaces (the inverse
    /// of [`revolution_v`](Self::revolution_v)): `v` clamped into
    /// `[0, 2π]` (NaN to 0), then in quarter `k`, with
    /// `s = (v − kπ/2)/(π/2)`, `θ = kπ/2 + π/4 + 2·atan((√2 − 1)(2s − 1))`.
    ///
    /// ```
    /// use revolve::NurbsSurface;
    /// use std::f64::consts::TAU;
    ///
    /// assert_eq!(NurbsSurface::revolution_angle(TAU), TAU);
    /// assert_eq!(NurbsSurface::revolution_angle(f64::NAN), 0.0);
    /// ```
    pub fn revolution_angle(v: f64) -> f64 {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, TAU) };
        let starts = quarter_starts();
        let k = starts.iter().rposition(|&s| s <= v).unwrap_or(0);
        let end = if k == 3 { TAU } else { starts[k + 1] };
        if v >= end || v <= starts[k] {
            return if v >= end { end } else { starts[k] };
        }
        let s = (v - starts[k]) / (end - starts[k]);
        (starts[k] + quarter_angle(s)).clamp(starts[k], end)
    }
}

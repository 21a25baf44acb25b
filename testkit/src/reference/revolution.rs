//! The exact nearest hit of a ray with a surface of
//! revolution, found in exact rational arithmetic and rounded once.
//!
//! The surface is `{(X, Y, Z) : X² + Z² = x(u)², Y = y(u)}` for a profile
//! `(x(u), y(u))` given as a Bézier curve or a B-spline. Every input `f64`
//! (control points, knots, ray origin and direction, `t_min`, `t_max`) is
//! read as the exact dyadic rational it is, and the answer is the hit of the
//! exact curve those numbers define:
//!
//! 1. Each non-empty knot interval becomes an exact Bézier span (blossoming
//!    with rationals) — [`spans`].
//! 2. For `d_y ≠ 0`, a height `y` is met at `t = (y − o_y)/d_y`, and the ray
//!    meets the surface at parameter `u` iff
//!    `(o_x d_y + (y − o_y) d_x)² + (o_z d_y + (y − o_y) d_z)² − d_y² x² = 0`,
//!    a polynomial of degree `2p` per span whose Bernstein coefficients are
//!    exact integers — [`ray`].
//! 3. Its roots in `[0, 1]` are isolated by Descartes' rule in the Bernstein
//!    basis with exact halving, then bisected until `t`, bounded by the hull
//!    of `y`'s coefficients, is certified — [`search`]. The `t` returned is
//!    the correctly rounded exact `t` when the bounds round alike (always,
//!    bar `t` within `2^-70·(1 + |t|)` of a rounding boundary; then it is
//!    within an ulp).
//!
//! Independence: none of revolve's intersection, root finding, knot
//! insertion or Bézier-span code is used; the only shared input is the
//! profile's numbers. The arithmetic is exact, so the answer carries no
//! floating-point error of its own.
//!
//! Edge rules: a hit needs `t_min < t < t_max` strictly; a root exactly at a
//! span boundary shared by two spans counts once; whatever can't be
//! certified is [`Reference::Ambiguous`] — a tangent (multiple) root or a
//! cluster narrower than `2^-100` in a span's parameter, a root whose `t`
//! can't be separated from `t_min`/`t_max`, two candidate nearest roots
//! whose `t` can't be ordered, a span lying wholly on the ray's cone of
//! circles, and unsupported input: `d_y = 0` (rays perpendicular to the
//! axis; the study sends none), `d = 0`, non-finite numbers, an invalid
//! profile.

pub mod ray;
pub mod search;
pub mod spans;

use super::Certifier;
use revolve::Ray;
use revolve::nalgebra::Point2;

/// A profile converted to exact Bézier spans.
pub struct ExactProfile {
    /// `None` for an invalid profile: every query is ambiguous.
    spans: Option<Vec<spans::Span>>,
}

/// The reference answer for one ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// The nearest hit: `t` rounded to `f64` (within an ulp of the exact
    /// value), and its profile parameter `u` (within `2^-64` of the span's
    /// width, then rounded).
    Hit { t: f64, u: f64 },
    /// No hit in `(t_min, t_max)`.
    Miss,
    /// The exact answer could not be certified (tangent/multiple root, a hit
    /// at `t_min`/`t_max`, `d_y = 0`, `d = 0`, invalid input).
    Ambiguous,
}

impl Certifier for ExactProfile {
    fn certify(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Option<f64>> {
        match self.nearest(ray, t_min, t_max) {
            Reference::Hit { t, .. } => Some(Some(t)),
            Reference::Miss => Some(None),
            Reference::Ambiguous => None,
        }
    }
}

impl ExactProfile {
    /// One Bézier curve (degree ≥ 1), `u ∈ [0, 1]`.
    pub fn from_bezier(points: &[Point2<f64>]) -> Self {
        ExactProfile {
            spans: spans::bezier(points),
        }
    }

    /// A B-spline of degree `degree ≥ 1` with `points.len() + degree + 1`
    /// non-decreasing knots, `u` in its domain `[knots[p], knots[n]]`.
    pub fn from_bspline(degree: usize, knots: &[f64], points: &[Point2<f64>]) -> Self {
        ExactProfile {
            spans: spans::bspline(degree, knots, points),
        }
    }

    /// The exact Bézier spans (`None` for an invalid profile), for tests
    /// that look inside the reference.
    pub fn spans(&self) -> Option<&[spans::Span]> {
        self.spans.as_deref()
    }

    /// The nearest exact hit of `ray` with `t_min < t < t_max`.
    pub fn nearest(&self, ray: &Ray, t_min: f64, t_max: f64) -> Reference {
        let Some(spans) = &self.spans else {
            return Reference::Ambiguous;
        };
        let data = match ray::RayData::new(ray, t_min, t_max) {
            Ok(d) => d,
            Err(ray::Reject::Miss) => return Reference::Miss,
            Err(ray::Reject::Ambiguous) => return Reference::Ambiguous,
        };
        match search::nearest(spans, &data) {
            search::Found::Hit { t, u } => Reference::Hit { t, u },
            search::Found::Miss => Reference::Miss,
            search::Found::Unsure => Reference::Ambiguous,
        }
    }
}

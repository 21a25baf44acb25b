//! The one rule by which every intersector accepts a hit.
//!
//! A candidate point of ray and surface is a hit when its residual (the
//! distance between the ray point and the surface point found for it) is
//! within
//!
//! `distance = max(tolerance · scale, floor · max(scale, |o|∞))`,
//!
//! where `scale` is the object's size and `|o|∞` the ray origin's largest
//! coordinate (the rounding of `o + t·d` grows with it). The certified
//! intersectors (revolutions, patches, profiles refined on the curve) use
//! the rounding floor [`Acceptance::ROUNDING`]: Newton's method from an
//! isolated root reaches a few ulps of the scale, so `1e-12` accepts every
//! hit while a ray that misses a silhouette by more is a miss. The generic
//! Newton intersector, which starts from boxes rather than isolated roots,
//! uses [`Acceptance::NEWTON`] and the object's scale alone.
//!
//! Hits within `distance / |d|` past `t_min` are the ray's own origin (a
//! secondary ray leaving the surface), so the window of accepted ray
//! parameters is `(t_min + distance/|d|, t_max)`: [`Acceptance::t_floor`].

use super::Tolerance;
use nalgebra::Vector3;

/// Residual thresholds of one ray on one object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Acceptance {
    /// The residual within which a hit is accepted.
    pub(crate) distance: f64,
    /// The residual at which Newton's polish may stop: `tolerance · scale`.
    pub(crate) target: f64,
}

impl Acceptance {
    /// The rounding floor of the certified intersectors, relative to the
    /// larger of the object's scale and the origin's distance.
    pub(crate) const ROUNDING: f64 = 1e-12;
    /// The floor of the generic Newton intersector, relative to the
    /// object's scale.
    pub(crate) const NEWTON: f64 = 1e-9;

    /// The certified rule for a ray from `origin` on an object of size
    /// `scale`, at the (clamped) tolerance `tol`.
    #[inline]
    pub(crate) fn certified(tol: &Tolerance, scale: f64, origin: &Vector3<f64>) -> Self {
        Acceptance {
            distance: (tol.relative * scale).max(Self::ROUNDING * scale.max(origin.amax())),
            target: tol.relative * scale,
        }
    }

    /// The generic Newton intersector's rule on an object of size `scale`.
    #[inline]
    pub(crate) fn newton(tol: &Tolerance, scale: f64) -> Self {
        Acceptance {
            distance: tol.relative.max(Self::NEWTON) * scale,
            target: tol.relative * scale,
        }
    }

    /// Whether a candidate with residual `residual` is a hit (NaN is not).
    #[inline]
    pub(crate) fn accepts(&self, residual: f64) -> bool {
        residual <= self.distance
    }

    /// The least ray parameter a hit may have: `t_min` plus the position
    /// uncertainty along a direction of length `dir_norm`.
    #[inline]
    pub(crate) fn t_floor(&self, t_min: f64, dir_norm: f64) -> f64 {
        t_min + self.distance / dir_norm
    }
}

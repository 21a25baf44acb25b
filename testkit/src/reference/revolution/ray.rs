//! A ray as exact integers: the weights of its hit polynomial, its `t(y)`,
//! and its `(t_min, t_max)` window.
//!
//! With `d_y ≠ 0` a point of the ray at height `y` has `t = (y − o_y)/d_y`
//! and `d_y·X = A + B·y`, `d_y·Z = C + D·y` with `A = o_x d_y − o_y d_x`,
//! `B = d_x`, `C = o_z d_y − o_y d_z`, `D = d_z`. It is on the surface iff
//! `f = (A + B y)² + (C + D y)² − d_y² x² = 0`, i.e.
//! `f = K0 + K1·y + K2·y² − K3·x²` with `K0 = A² + C²`, `K1 = 2(AB + CD)`,
//! `K2 = B² + D²`, `K3 = d_y²`. With all six ray numbers written as integers
//! over one power of two, a positive multiple of `f` has integer weights.

use super::spans::Span;
use crate::reference::exact::{Frac, common_exponent, shifted};
use num_bigint::BigInt;
use num_traits::Signed;
use revolve::Ray;

/// Why a ray gets no search.
pub enum Reject {
    /// The window `(t_min, t_max)` is empty.
    Miss,
    /// Unsupported or invalid: `d_y = 0`, `d = 0`, non-finite numbers, NaN bounds.
    Ambiguous,
}

pub struct RayData {
    /// A positive multiple of `f`: `w0 + w1·y + w2·y² − w3·x²`.
    w: [BigInt; 4],
    /// `o_y = oy·2^e`, `d_y = dy·2^e`.
    oy: BigInt,
    dy: BigInt,
    e: i32,
    /// The window; `None` for an infinite bound.
    tmin: Option<Frac>,
    tmax: Option<Frac>,
}

impl RayData {
    pub fn new(ray: &Ray, t_min: f64, t_max: f64) -> Result<RayData, Reject> {
        let (o, d) = (ray.origin, ray.dir);
        let vals = [o.x, o.y, o.z, d.x, d.y, d.z];
        if vals.iter().any(|v| !v.is_finite()) || t_min.is_nan() || t_max.is_nan() {
            return Err(Reject::Ambiguous);
        }
        if d.y == 0.0 {
            return Err(Reject::Ambiguous);
        }
        if t_min >= t_max || t_min == f64::INFINITY || t_max == f64::NEG_INFINITY {
            return Err(Reject::Miss);
        }
        let (m, e) = common_exponent(&vals);
        let [ox, oy, oz, dx, dy, dz] = <[BigInt; 6]>::try_from(m).map_err(|_| Reject::Ambiguous)?;
        let a = &ox * &dy - &oy * &dx;
        let c = &oz * &dy - &oy * &dz;
        let k0 = &a * &a + &c * &c;
        let k1 = (&a * &dx + &c * &dz) << 1u32;
        let k2 = &dx * &dx + &dz * &dz;
        let k3 = &dy * &dy;
        // f·2^(-2e) = k0·2^(2e) + k1·2^e·y + k2·y² − k3·x²; scale to integers.
        let w = if e >= 0 {
            let e = e as u32;
            [k0 << (2 * e), k1 << e, k2, k3]
        } else {
            let e = (-e) as u32;
            [k0, k1 << e, k2 << (2 * e), k3 << (2 * e)]
        };
        let bound = |v: f64| v.is_finite().then(|| Frac::from_f64(v));
        Ok(RayData {
            w,
            oy,
            dy,
            e,
            tmin: bound(t_min),
            tmax: bound(t_max),
        })
    }

    /// The Bernstein coefficients (degree `2p`) of a positive multiple of
    /// `f` on the span.
    pub fn poly(&self, s: &Span) -> Vec<BigInt> {
        let c0 = &self.w[0] * &s.one;
        (0..s.y1.len())
            .map(|k| &c0 + &self.w[1] * &s.y1[k] + &self.w[2] * &s.y2[k] - &self.w[3] * &s.x2[k])
            .collect()
    }

    /// The exact `t` at height `y = yc / (ly·2^shift)`.
    pub fn t_at(&self, yc: &BigInt, ly: &BigInt, shift: u64) -> Frac {
        // t = (yc − oy·ly·2^(shift+e)) / (dy·ly·2^(shift+e))
        let s = shift as i64 + i64::from(self.e);
        let scale = shifted(ly.clone(), s); // ly·2^s as num/den
        // yc/(scale) − oy  over  dy  =  (yc·den − oy·num) / (dy·num)
        Frac::new(
            yc * &scale.den - &self.oy * &scale.num,
            &self.dy * &scale.num,
        )
    }

    /// The `t` interval of heights between the extremes of `yc` (the hull of
    /// a Bernstein polynomial's coefficients bounds its values).
    pub fn t_hull(&self, yc: &[BigInt], ly: &BigInt, shift: u64) -> (Frac, Frac) {
        let lo = yc.iter().min().unwrap_or(&BigInt::ZERO).clone();
        let hi = yc.iter().max().unwrap_or(&BigInt::ZERO).clone();
        let (tl, th) = (self.t_at(&lo, ly, shift), self.t_at(&hi, ly, shift));
        if self.dy.is_positive() {
            (tl, th)
        } else {
            (th, tl)
        }
    }

    /// Every `t ≤ th` is outside the window (`t ≤ t_min`).
    pub fn before(&self, th: &Frac) -> bool {
        self.tmin.as_ref().is_some_and(|m| th <= m)
    }

    /// Every `t ≥ tl` is outside the window (`t ≥ t_max`).
    pub fn after(&self, tl: &Frac) -> bool {
        self.tmax.as_ref().is_some_and(|m| tl >= m)
    }

    /// `[tl, th]` lies strictly inside the window.
    pub fn inside(&self, tl: &Frac, th: &Frac) -> bool {
        self.tmin.as_ref().is_none_or(|m| tl > m) && self.tmax.as_ref().is_none_or(|m| th < m)
    }
}

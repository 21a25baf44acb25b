//! Homogeneous coordinates `(w·P, w)` of a rational curve's control points,
//! and the quotient rule that turns their derivatives into the curve's.
//!
//! A rational curve `C(t) = A(t)/w(t)` with `A = Σ wᵢPᵢ bᵢ(t)` and
//! `w = Σ wᵢ bᵢ(t)` is a polynomial (or spline) curve one dimension up. Every
//! polynomial algorithm (de Casteljau, de Boor, knot insertion, subdivision,
//! degree elevation) runs unchanged on [`Homogeneous`] values; the division
//! comes last.

use nalgebra::{Point, SVector};
use std::ops::{Add, Mul, Sub};

/// A point in homogeneous form: `(w·P, w)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Homogeneous<const D: usize> {
    /// `w·P`.
    pub(crate) wp: SVector<f64, D>,
    /// `w`.
    pub(crate) w: f64,
}

impl<const D: usize> Homogeneous<D> {
    /// `(w·P, w)`.
    #[inline]
    pub(crate) fn new(p: &Point<f64, D>, w: f64) -> Self {
        Homogeneous {
            wp: p.coords * w,
            w,
        }
    }

    /// The zero vector (for derivatives and scratch space).
    #[inline]
    pub(crate) fn zero() -> Self {
        Homogeneous {
            wp: SVector::zeros(),
            w: 0.0,
        }
    }
}

impl<const D: usize> Add for Homogeneous<D> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Homogeneous {
            wp: self.wp + o.wp,
            w: self.w + o.w,
        }
    }
}

impl<const D: usize> Sub for Homogeneous<D> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Homogeneous {
            wp: self.wp - o.wp,
            w: self.w - o.w,
        }
    }
}

impl<const D: usize> Mul<f64> for Homogeneous<D> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: f64) -> Self {
        Homogeneous {
            wp: self.wp * s,
            w: self.w * s,
        }
    }
}

/// The derivatives `C, C′, …, C⁽ᵏ⁾` of `C = A/w` from the homogeneous
/// derivatives `h[j] = (A⁽ʲ⁾, w⁽ʲ⁾)`, `j = 0 … k`, written into `out`
/// (same length as `h`).
///
/// Leibniz's rule on `A = w·C` gives `A⁽ᵏ⁾ = Σⱼ C(k, j) w⁽ʲ⁾ C⁽ᵏ⁻ʲ⁾`, so
/// `C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σ_{j=1}^{k} C(k, j) w⁽ʲ⁾ C⁽ᵏ⁻ʲ⁾) / w` (Piegl & Tiller,
/// *The NURBS Book*, eq. 4.8). `h[0].w` must be positive.
pub(crate) fn quotient_rule<const D: usize>(h: &[Homogeneous<D>], out: &mut [SVector<f64, D>]) {
    let w = h[0].w;
    for k in 0..h.len().min(out.len()) {
        let mut v = h[k].wp;
        // C(k, j) built up along the row.
        let mut binom = 1.0;
        for j in 1..=k {
            binom = binom * (k + 1 - j) as f64 / j as f64;
            v -= out[k - j] * (binom * h[j].w);
        }
        out[k] = v / w;
    }
}

/// The point `A/w` of a homogeneous value (`w > 0`).
#[inline]
pub(crate) fn project<const D: usize>(h: Homogeneous<D>) -> Point<f64, D> {
    Point::from(h.wp / h.w)
}

/// `(C, C′)` from `(A, w)` and `(A′, w′)`: `C = A/w`, `C′ = (A′ − w′C)/w`.
#[inline]
pub(crate) fn project_with_derivative<const D: usize>(
    h: Homogeneous<D>,
    dh: Homogeneous<D>,
) -> (Point<f64, D>, SVector<f64, D>) {
    let c = h.wp / h.w;
    (Point::from(c), (dh.wp - c * dh.w) / h.w)
}

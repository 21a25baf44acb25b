//! Homogeneous coordinates `(w·P, w)` of a rational curve's control points,
//! the scaling of its weights, and the quotient rule that turns the
//! homogeneous derivatives into the curve's.
//!
//! A rational curve `C(t) = A(t)/w(t)` with `A = Σ wᵢPᵢ bᵢ(t)` and
//! `w = Σ wᵢ bᵢ(t)` is a polynomial (or spline) curve one dimension up. Every
//! polynomial algorithm (de Casteljau, de Boor, knot insertion, subdivision,
//! degree elevation) runs unchanged on [`Homogeneous`] values; the division
//! comes last.

use super::clamp_to_box;
use crate::Error;
use crate::scratch::with_scratch;
use nalgebra::{Point, SVector};
use std::ops::{Add, Div, Mul, Sub};

/// The highest derivative order [`Nurbs::derivatives`](crate::Nurbs::derivatives)
/// and [`Nurbs::nth_derivative`](crate::Nurbs::nth_derivative) compute
/// (`1024`). A rational curve's derivatives do not vanish above its degree,
/// and order `k` costs `O(k²)` operations; beyond order ~170 they overflow
/// for most curves anyway (they grow like `k!`).
pub const MAX_DERIVATIVE_ORDER: usize = 1024;

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

    /// The box of homogeneous points (`h` not empty): `(min, max)` of `wP`
    /// per coordinate and of `w`.
    pub(crate) fn bounds(h: &[Self]) -> (Self, Self) {
        h.iter().fold((h[0], h[0]), |(lo, hi), x| {
            (
                Homogeneous {
                    wp: lo.wp.inf(&x.wp),
                    w: lo.w.min(x.w),
                },
                Homogeneous {
                    wp: hi.wp.sup(&x.wp),
                    w: hi.w.max(x.w),
                },
            )
        })
    }

    /// The value moved into the box `(lo, hi)`: for a convex combination of
    /// the points whose box it is, this only removes rounding.
    #[inline]
    pub(crate) fn clamp(self, (lo, hi): (Self, Self)) -> Self {
        Homogeneous {
            wp: self.wp.sup(&lo.wp).inf(&hi.wp),
            w: self.w.clamp(lo.w, hi.w),
        }
    }
}

/// The homogeneous points `(wᵢPᵢ, wᵢ)` of `points` with the weights
/// `weights` (one per point, already scaled as the caller wants).
pub(crate) fn homogeneous_points<const D: usize>(
    points: &[Point<f64, D>],
    weights: impl IntoIterator<Item = f64>,
) -> Vec<Homogeneous<D>> {
    points
        .iter()
        .zip(weights)
        .map(|(p, w)| Homogeneous::new(p, w))
        .collect()
}

/// The largest of the weights (`0` for none).
pub(crate) fn max_weight(weights: impl IntoIterator<Item = f64>) -> f64 {
    weights.into_iter().fold(0.0_f64, |m, w| m.max(w))
}

/// The power of two by which the weights are divided: the largest weight
/// becomes a number in `[1, 2)`, the others are scaled exactly.
pub(crate) fn weight_scale(weights: &[f64]) -> f64 {
    power_of_two_near(max_weight(weights.iter().copied()))
}

/// `2^⌊log₂ x⌋` for a positive finite `x` (subnormal ones too): a power of
/// two within a factor 2 of `x`, by which division is exact. Rounding of the
/// logarithm can only make it `x`'s neighbouring power, still within a
/// factor 2.
pub(crate) fn power_of_two_near(x: f64) -> f64 {
    let e = (x.log2().floor() as i32).clamp(-1074, 1023);
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1_u64 << (e + 1074))
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

impl<const D: usize> Div<f64> for Homogeneous<D> {
    type Output = Self;
    /// Both coordinates divided by `s` (division, not multiplication by
    /// `1/s`, which could overflow for tiny `s`).
    #[inline(always)]
    fn div(self, s: f64) -> Self {
        Homogeneous {
            wp: self.wp / s,
            w: self.w / s,
        }
    }
}

/// Refuses derivative orders beyond [`MAX_DERIVATIVE_ORDER`]
/// ([`Error::DerivativeOrderTooHigh`]).
pub(crate) fn check_derivative_order(order: usize) -> Result<(), Error> {
    if order > MAX_DERIVATIVE_ORDER {
        return Err(Error::DerivativeOrderTooHigh {
            order,
            max: MAX_DERIVATIVE_ORDER,
        });
    }
    Ok(())
}

/// The derivative of order `order` alone, from `derivatives`, which writes
/// the orders `0 ..= order` into the slice it is given (scratch space, no
/// heap allocation for small orders).
///
/// # Errors
/// Those of `derivatives`.
pub(crate) fn one_derivative<const D: usize>(
    order: usize,
    derivatives: impl FnOnce(&mut [SVector<f64, D>]) -> Result<(), Error>,
) -> Result<SVector<f64, D>, Error> {
    with_scratch(order + 1, SVector::zeros(), |out| {
        derivatives(out)?;
        Ok(out[order])
    })
}

/// The last step of a rational curve's derivatives `out` (`C, C′, …`): the
/// point moved into the control points' box `bounds` (which contains the
/// curve), and [`Error::DerivativeOverflow`] with the first order whose value
/// is not finite.
pub(crate) fn finish_derivatives<const D: usize>(
    out: &mut [SVector<f64, D>],
    bounds: (Point<f64, D>, Point<f64, D>),
) -> Result<(), Error> {
    if let Some(first) = out.first_mut() {
        *first = clamp_to_box(*first, bounds);
    }
    match out.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
        Some(order) => Err(Error::DerivativeOverflow { order }),
        None => Ok(()),
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
    let Some(w) = h.first().map(|h0| h0.w) else {
        return;
    };
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

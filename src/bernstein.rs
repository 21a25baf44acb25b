//! The Bernstein basis and the de Casteljau kernels.
//!
//! A polynomial of degree `n` in Bernstein form on `[0, 1]` is
//! `p(t) = Σᵢ cᵢ Bᵢⁿ(t)` with `Bᵢⁿ(t) = C(n, i) tⁱ (1 − t)ⁿ⁻ⁱ`. The coefficients
//! `cᵢ` may be scalars (`f64`) or vectors (`SVector<f64, D>`): anything that is a
//! [`Coefficient`].
//!
//! The kernels here work in place on a caller's slice, so the curve types can
//! run them on stack scratch space without allocating. De Casteljau's algorithm
//! (repeated convex combination) is the evaluator: it is numerically stable
//! because every step is a convex combination for `t ∈ [0, 1]` (Farin, *Curves
//! and Surfaces for CAGD*, ch. 4). [`bernstein_sum`], [`to_power_basis`] and
//! [`horner`] exist as independent references and as speed comparisons for the
//! tests and benches; they are not used by the curve types.
//!
//! ```
//! use revolve::bernstein::{bernstein, de_casteljau};
//! // Partition of unity: the cubic basis sums to one.
//! let sum: f64 = (0..=3).map(|i| bernstein(3, i, 0.3)).sum();
//! assert!((sum - 1.0).abs() < 1e-15);
//! // t² written in the quadratic Bernstein basis has coefficients (0, 0, 1).
//! let mut c = [0.0, 0.0, 1.0];
//! assert!((de_casteljau(&mut c, 0.5).unwrap() - 0.25).abs() < 1e-15);
//! ```

use crate::scratch::with_scratch;
use std::ops::{Add, Mul, Sub};

/// A Bernstein coefficient: a scalar or a vector that can be added, subtracted
/// and scaled by an `f64`. Implemented for `f64` and every nalgebra vector.
pub trait Coefficient:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
}

impl<T> Coefficient for T where T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T> {}

/// `(1 − t)·a + t·b`, the step of de Casteljau's and de Boor's algorithms.
#[inline(always)]
pub fn lerp<T: Coefficient>(a: T, b: T, t: f64) -> T {
    a * (1.0 - t) + b * t
}

/// The binomial coefficient `C(n, k)` as an `f64`; zero when `k > n`.
///
/// Exact (computed in 128-bit integers) while `C(n, k)` fits, which covers every
/// degree a spline uses in practice; beyond that a product of ratios, correct to
/// a few ulps; `+∞` where it exceeds `f64::MAX`. At most about a thousand
/// steps whatever `n` and `k`: with `k ≤ n/2`, `C(n, k) ≥ 2ᵏ`, so `k > 1024`
/// is infinite at once.
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    if k > 1024 {
        return f64::INFINITY;
    }
    let mut exact: u128 = 1;
    for i in 1..=k {
        // exact · (n − k + i) / i is C(n − k + i, i): always an integer.
        match exact.checked_mul((n - k + i) as u128) {
            Some(x) => exact = x / i as u128,
            None => {
                return (1..=k).fold(1.0, |acc, j| acc * (n - k + j) as f64 / j as f64);
            }
        }
    }
    exact as f64
}

/// `ln C(n, k)` for `k ≤ n`, also where `C(n, k)` overflows: there
/// `k ≥ 1025` and `n − k ≥ 1025`, and Stirling's series with its first
/// correction term is within a few ulps, written so that nothing cancels:
/// `k ln(n/k) − (n − k) ln(1 − k/n) + ½ ln(n / (2π k (n − k)))`
/// `+ 1/(12n) − 1/(12k) − 1/(12(n − k))`.
fn ln_binomial(n: usize, k: usize) -> f64 {
    let c = binomial(n, k);
    if c.is_finite() {
        return c.ln();
    }
    let (n, k) = (n as f64, k.min(n - k) as f64);
    let m = n - k;
    k * (n / k).ln() - m * (-k / n).ln_1p()
        + 0.5 * (n / (std::f64::consts::TAU * k * m)).ln()
        + (1.0 / n - 1.0 / k - 1.0 / m) / 12.0
}

/// The row `C(n, 0), …, C(n, n)` of [`binomial`]s (the same values): for
/// loops over products of binomials, which would otherwise recompute each
/// one (`O(n)` apiece).
pub fn binomial_row(n: usize) -> Vec<f64> {
    (0..=n).map(|k| binomial(n, k)).collect()
}

/// The Bernstein basis polynomial `Bᵢⁿ(t) = C(n, i) tⁱ (1 − t)ⁿ⁻ⁱ`; zero when `i > n`.
///
/// Never NaN for a finite `t`. Where the three factors would overflow or
/// underflow on their own (degrees in the thousands and beyond) the value
/// is taken through logarithms, with its sign; it is then `±∞` only where
/// the polynomial itself exceeds `f64::MAX` (far outside `[0, 1]`).
pub fn bernstein(n: usize, i: usize, t: f64) -> f64 {
    if i > n {
        return 0.0;
    }
    if t == 0.0 || t == 1.0 {
        // The ends: 1 for the end's own polynomial, 0 for the others.
        let own = if t == 0.0 { i == 0 } else { i == n };
        return if own { 1.0 } else { 0.0 };
    }
    let (c, a, b) = (binomial(n, i), powi(t, i), powi(1.0 - t, n - i));
    let normal = |x: f64| x.is_normal() || x == 1.0;
    if c.is_finite() && normal(a) && normal(b) {
        let direct = c * a * b;
        if direct.is_finite() && (direct == 0.0 || direct.is_normal()) {
            return direct;
        }
    }
    if t.is_nan() {
        return f64::NAN;
    }
    let odd = |x: f64, e: usize| x < 0.0 && e % 2 == 1;
    let sign = if odd(t, i) != odd(1.0 - t, n - i) {
        -1.0
    } else {
        1.0
    };
    if t.is_infinite() {
        return sign * f64::INFINITY;
    }
    // sign · exp(ln C + i ln|t| + (n − i) ln|1 − t|).
    let ln_rest = if t < 1.0 {
        (-t).ln_1p()
    } else {
        (t - 1.0).ln()
    };
    let exponent = ln_binomial(n, i) + i as f64 * t.abs().ln() + (n - i) as f64 * ln_rest;
    sign * exponent.exp()
}

fn powi(x: f64, n: usize) -> f64 {
    match i32::try_from(n) {
        Ok(n) => x.powi(n),
        Err(_) => x.powf(n as f64),
    }
}

/// Evaluates the Bernstein-form polynomial with coefficients `c` at `t` by de
/// Casteljau's algorithm, overwriting `c` with intermediate values.
///
/// Returns `None` only for an empty slice. Cost: `n(n + 1)/2` linear
/// interpolations for degree `n`; no allocation.
#[inline]
pub fn de_casteljau<T: Coefficient>(c: &mut [T], t: f64) -> Option<T> {
    let n = c.len().checked_sub(1)?;
    for level in 1..=n {
        for j in 0..=(n - level) {
            c[j] = lerp(c[j], c[j + 1], t);
        }
    }
    Some(c[0])
}

/// Evaluates the polynomial and its first derivative at `t` in one de Casteljau
/// pass: the two points of the last-but-one level give `p′(t) = n·(b₁ − b₀)`.
///
/// Overwrites `c`; returns `None` only for an empty slice. A constant (one
/// coefficient) has derivative `c₀ · 0`.
#[inline]
pub fn de_casteljau_with_derivative<T: Coefficient>(c: &mut [T], t: f64) -> Option<(T, T)> {
    let n = c.len().checked_sub(1)?;
    if n == 0 {
        return Some((c[0], c[0] * 0.0));
    }
    for level in 1..n {
        for j in 0..=(n - level) {
            c[j] = lerp(c[j], c[j + 1], t);
        }
    }
    let (b0, b1) = (c[0], c[1]);
    Some((lerp(b0, b1, t), (b1 - b0) * n as f64))
}

/// De Casteljau on a fixed-size array: `N` is known at compile time, so the
/// cascade is unrolled and stays in registers. Runs `levels` levels.
#[inline(always)]
fn cascade<T: Coefficient, const N: usize>(mut c: [T; N], t: f64, levels: usize) -> [T; N] {
    for level in 1..=levels {
        for j in 0..N - level {
            c[j] = lerp(c[j], c[j + 1], t);
        }
    }
    c
}

/// Dispatches a slice of known small length to a fixed-size kernel: lengths
/// 1 to 17 (degree ≤ 16) get an unrolled cascade the compiler can keep in
/// registers.
macro_rules! fixed_sizes {
    ($c:expr, $kernel:ident, $t:expr, [$($n:literal),*]) => {
        match $c.len() {
            $($n => {
                if let Ok(a) = <[T; $n]>::try_from($c) {
                    return Some($kernel(a, $t));
                }
            })*
            _ => {}
        }
    };
}

/// The value at `t` of the Bernstein-form polynomial with coefficients `c`,
/// without modifying `c` (de Casteljau; unrolled for degree ≤ 16, stack
/// scratch up to degree 101, heap beyond). `None` for an empty slice.
#[inline]
pub fn eval<T: Coefficient>(c: &[T], t: f64) -> Option<T> {
    #[inline(always)]
    fn value<T: Coefficient, const N: usize>(a: [T; N], t: f64) -> T {
        cascade(a, t, N - 1)[0]
    }
    fixed_sizes!(
        c,
        value,
        t,
        [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17]
    );
    let first = *c.first()?;
    with_scratch(c.len(), first, |s| {
        s.copy_from_slice(c);
        de_casteljau(s, t)
    })
}

/// The value and first derivative at `t` of the Bernstein-form polynomial
/// with coefficients `c`, without modifying `c` (see
/// [`de_casteljau_with_derivative`]). `None` for an empty slice.
#[inline]
pub fn eval_with_derivative<T: Coefficient>(c: &[T], t: f64) -> Option<(T, T)> {
    fixed_sizes!(
        c,
        both,
        t,
        [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17]
    );
    let first = *c.first()?;
    with_scratch(c.len(), first, |s| {
        s.copy_from_slice(c);
        de_casteljau_with_derivative(s, t)
    })
}

/// The value and derivative from a fixed-size array: the cascade down to the
/// last-but-one level, whose two points give both.
#[inline(always)]
fn both<T: Coefficient, const N: usize>(a: [T; N], t: f64) -> (T, T) {
    if N == 1 {
        return (a[0], a[0] * 0.0);
    }
    let r = cascade(a, t, N.saturating_sub(2));
    (lerp(r[0], r[1], t), (r[1] - r[0]) * (N - 1) as f64)
}

/// Scalar Bernstein coefficients as the root search and the exact
/// intersector evaluate them: a fixed-size array (`[f64; N]`, the cascade
/// unrolled for that `N`) or a slice (dispatched by length at each call).
/// Both give exactly the values of [`eval`] and [`eval_with_derivative`].
pub(crate) trait Polynomial {
    /// The coefficients.
    fn coeffs(&self) -> &[f64];
    /// The value at `t` (0 for no coefficients).
    fn value(&self, t: f64) -> f64;
    /// The value and first derivative at `t` (`None` for no coefficients).
    fn value_and_slope(&self, t: f64) -> Option<(f64, f64)>;
}

impl<const N: usize> Polynomial for [f64; N] {
    #[inline(always)]
    fn coeffs(&self) -> &[f64] {
        self
    }
    #[inline(always)]
    fn value(&self, t: f64) -> f64 {
        if N == 0 {
            return 0.0;
        }
        cascade(*self, t, N - 1)[0]
    }
    #[inline(always)]
    fn value_and_slope(&self, t: f64) -> Option<(f64, f64)> {
        (N > 0).then(|| both(*self, t))
    }
}

impl Polynomial for [f64] {
    #[inline(always)]
    fn coeffs(&self) -> &[f64] {
        self
    }
    #[inline]
    fn value(&self, t: f64) -> f64 {
        eval(self, t).unwrap_or(0.0)
    }
    #[inline]
    fn value_and_slope(&self, t: f64) -> Option<(f64, f64)> {
        eval_with_derivative(self, t)
    }
}

/// Replaces the coefficients of `p` (degree `n = c.len() − 1`) by those of its
/// derivative `p′` (degree `n − 1`, the hodograph: `n·(cᵢ₊₁ − cᵢ)`), in place in
/// `c[..n]`, and returns the new length `n`. An empty slice stays empty.
#[inline]
pub fn differentiate_in_place<T: Coefficient>(c: &mut [T]) -> usize {
    let Some(n) = c.len().checked_sub(1) else {
        return 0;
    };
    let scale = n as f64;
    for j in 0..n {
        c[j] = (c[j + 1] - c[j]) * scale;
    }
    n
}

/// The value at `t` of the `order`-th derivative of the polynomial with
/// coefficients `c`: [`differentiate_in_place`] `order` times, then
/// [`de_casteljau`] on what is left. Overwrites `c`; `None` when `order` is
/// at least `c.len()` (the derivative is then identically zero).
pub(crate) fn nth_derivative_in_place<T: Coefficient>(
    c: &mut [T],
    order: usize,
    t: f64,
) -> Option<T> {
    let mut len = c.len();
    for _ in 0..order {
        len = differentiate_in_place(&mut c[..len]);
    }
    de_casteljau(&mut c[..len], t)
}

/// The Bernstein coefficients of degree `n + times` of the polynomial with
/// coefficients `points` (degree `n`): the same polynomial written with a
/// higher degree (Farin, *Curves and Surfaces for CAGD*, degree elevation
/// repeated `times` times in one formula),
///
/// ```text
/// Qᵢ = Σⱼ C(n, j)·C(times, i − j) / C(n + times, i) · Pⱼ,   i = 0 … n + times,
/// ```
///
/// the sum over `max(0, i − times) ≤ j ≤ min(n, i)`, accumulated in
/// increasing `j`, each weight computed as
/// `(C(n, j)·C(times, i − j))/C(n + times, i)` from [`binomial_row`]s. The
/// weights are positive and sum to one (Vandermonde's identity), so each
/// `Qᵢ` is a convex combination of the `Pⱼ`: the computation is stable,
/// and the new coefficients stay in the old ones' box. `Q₀ = P₀·1` and
/// `Q_{n+times} = Pₙ·1` (exact). Empty for no points; a copy for
/// `times = 0`.
pub(crate) fn elevate_degree<T: Coefficient>(points: &[T], times: usize) -> Vec<T> {
    let Some(n) = points.len().checked_sub(1) else {
        return Vec::new();
    };
    let q = n + times;
    let (row_n, row_k, row_q) = (binomial_row(n), binomial_row(times), binomial_row(q));
    (0..=q)
        .map(|i| {
            let (lo, hi) = (i.saturating_sub(times), i.min(n));
            let weight = |j: usize| row_n[j] * row_k[i - j] / row_q[i];
            (lo + 1..=hi).fold(points[lo] * weight(lo), |acc, j| {
                acc + points[j] * weight(j)
            })
        })
        .collect()
}

/// Splits the polynomial with coefficients `c` at `t` into the coefficients of
/// its restrictions to `[0, t]` (written to `left`) and `[t, 1]` (written to
/// `right`), each reparametrized to `[0, 1]`.
///
/// `left` and `right` must have the length of `c`; returns `false` (and writes
/// nothing) otherwise.
pub fn subdivide<T: Coefficient>(c: &[T], t: f64, left: &mut [T], right: &mut [T]) -> bool {
    if left.len() != c.len() || right.len() != c.len() || c.is_empty() {
        return false;
    }
    let n = c.len() - 1;
    right.copy_from_slice(c);
    for (level, l) in left.iter_mut().enumerate().take(n) {
        *l = right[0];
        for j in 0..(n - level) {
            right[j] = lerp(right[j], right[j + 1], t);
        }
    }
    left[n] = right[0];
    true
}

/// Replaces the Bernstein coefficients `c` on `[0, 1]` by those of the same
/// polynomial on `[a, b] ⊆ [0, 1]` (two de Casteljau subdivisions).
pub(crate) fn restrict<T: Coefficient>(c: &mut [T], (a, b): (f64, f64)) {
    let n = c.len();
    let mut left = c.to_vec();
    let mut right = c.to_vec();
    if b < 1.0 {
        subdivide(c, b, &mut left, &mut right);
        c.copy_from_slice(&left);
    }
    if a > 0.0 && b > 0.0 {
        subdivide(c, (a / b).min(1.0), &mut left, &mut right);
        c.copy_from_slice(&right);
    }
    debug_assert_eq!(c.len(), n);
}
/// Reference evaluator: the Bernstein sum `Σ cᵢ Bᵢⁿ(t)` computed term by term.
///
/// Slower and (near the ends, for high degree) less accurate than de Casteljau;
/// used by tests as an independent second algorithm. `None` for an empty slice.
pub fn bernstein_sum<T: Coefficient>(c: &[T], t: f64) -> Option<T> {
    let n = c.len().checked_sub(1)?;
    let mut acc = c[0] * bernstein(n, 0, t);
    for (i, &ci) in c.iter().enumerate().skip(1) {
        acc = acc + ci * bernstein(n, i, t);
    }
    Some(acc)
}

/// Converts Bernstein coefficients to power-basis (monomial) coefficients
/// `aⱼ = C(n, j) Σᵢ₌₀ʲ (−1)ʲ⁻ⁱ C(j, i) cᵢ`, so that `p(t) = Σ aⱼ tʲ`; the
/// `C(j, i)` rows by Pascal's rule, `O(n²)` operations in all.
///
/// The conversion is ill-conditioned for high degree (the `aⱼ` grow like
/// `2ⁿ` and alternate in sign); it exists to document that and as a speed
/// comparison for [`horner`]. Beyond degree about 1 000 the terms overflow
/// `f64` (infinite, or NaN where two infinities meet): the power basis cannot
/// hold such a polynomial.
pub fn to_power_basis<T: Coefficient>(c: &[T]) -> Vec<T> {
    let n = c.len().saturating_sub(1);
    // Row j of Pascal's triangle, C(j, 0) … C(j, j).
    let mut pascal: Vec<f64> = Vec::with_capacity(c.len());
    let mut a = Vec::with_capacity(c.len());
    for j in 0..c.len() {
        pascal.push(1.0);
        for i in (1..j).rev() {
            pascal[i] += pascal[i - 1];
        }
        let mut acc = c[0] * 0.0;
        for (i, (&ci, &binom)) in c.iter().zip(&pascal).enumerate() {
            let sign = if (j - i) % 2 == 0 { 1.0 } else { -1.0 };
            acc = acc + ci * (sign * binom);
        }
        a.push(acc * binomial(n, j));
    }
    a
}

/// Evaluates the power-basis polynomial `Σ aⱼ tʲ` by Horner's rule.
/// `None` for an empty slice.
pub fn horner<T: Coefficient>(a: &[T], t: f64) -> Option<T> {
    let (&last, rest) = a.split_last()?;
    Some(rest.iter().rev().fold(last, |acc, &aj| acc * t + aj))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binomials_are_exact() {
        assert_eq!(binomial(0, 0), 1.0);
        assert_eq!(binomial(5, 2), 10.0);
        assert_eq!(binomial(5, 6), 0.0);
        assert_eq!(binomial(60, 30), 118_264_581_564_861_424.0);
        // Symmetry and Pascal's rule hold exactly while the values fit.
        for n in 1..50 {
            for k in 1..n {
                assert_eq!(binomial(n, k), binomial(n, n - k));
                assert_eq!(
                    binomial(n, k),
                    binomial(n - 1, k - 1) + binomial(n - 1, k),
                    "n={n} k={k}"
                );
            }
        }
        // Beyond u128 the ratio product is still accurate.
        let big = binomial(200, 100);
        assert!((big / 9.054_851_465_610_328e58 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn de_casteljau_matches_closed_form_cubic() {
        // (1 − t)³·1 + 3t(1 − t)²·2 + 3t²(1 − t)·(−1) + t³·4 at t = 0.25.
        let t: f64 = 0.25;
        let s = 1.0 - t;
        let exact = s.powi(3) + 3.0 * t * s * s * 2.0 - 3.0 * t * t * s + 4.0 * t.powi(3);
        let mut c = [1.0, 2.0, -1.0, 4.0];
        assert!((de_casteljau(&mut c, t).unwrap() - exact).abs() < 1e-15);
        assert_eq!(de_casteljau::<f64>(&mut [], t), None);
    }

    #[test]
    fn derivative_and_hodograph_agree() {
        let coeffs = [1.0, 2.0, -1.0, 4.0, 0.5];
        let mut c = coeffs;
        let (_, d) = de_casteljau_with_derivative(&mut c, 0.3).unwrap();
        let mut h = coeffs;
        let len = differentiate_in_place(&mut h);
        assert_eq!(len, 4);
        let d2 = de_casteljau(&mut h[..len], 0.3).unwrap();
        assert!((d - d2).abs() < 1e-14);
    }

    #[test]
    fn fixed_and_slice_polynomials_are_eval() {
        fn check<const N: usize>(c: [f64; N]) {
            for k in 0..=10 {
                let t = f64::from(k) / 10.0;
                let want = eval_with_derivative(&c[..], t);
                assert_eq!(c.value_and_slope(t), want);
                assert_eq!(c[..].value_and_slope(t), want);
                assert_eq!(c.value(t), eval(&c[..], t).unwrap_or(0.0));
                assert_eq!(c[..].value(t), c.value(t));
            }
            assert_eq!(c.coeffs(), &c[..]);
        }
        check([1.0]);
        check([1.0, 2.0]);
        check([1.0, 2.0, -1.0, 4.0]);
        check([1.0, 2.0, -1.0, 4.0, 0.5, 3.0]);
        // Beyond the unrolled sizes, and no coefficients at all.
        let long: [f64; 20] = std::array::from_fn(|i| (i as f64).sin());
        check(long);
        check([]);
    }

    #[test]
    fn subdivision_reproduces_the_polynomial() {
        let c = [1.0, -2.0, 3.0, 0.5, 2.0];
        let (mut l, mut r) = ([0.0; 5], [0.0; 5]);
        assert!(subdivide(&c, 0.4, &mut l, &mut r));
        for k in 0..=10 {
            let s = k as f64 / 10.0;
            let whole_l = bernstein_sum(&c, 0.4 * s).unwrap();
            let whole_r = bernstein_sum(&c, 0.4 + 0.6 * s).unwrap();
            assert!((bernstein_sum(&l, s).unwrap() - whole_l).abs() < 1e-14);
            assert!((bernstein_sum(&r, s).unwrap() - whole_r).abs() < 1e-14);
        }
        assert!(!subdivide(&c, 0.4, &mut [0.0; 4], &mut r));
    }

    #[test]
    fn power_basis_and_horner_agree_at_low_degree() {
        let c = [1.0, 2.0, -1.0, 4.0];
        let a = to_power_basis(&c);
        for k in 0..=8 {
            let t = k as f64 / 8.0;
            let mut w = c;
            let exact = de_casteljau(&mut w, t).unwrap();
            assert!((horner(&a, t).unwrap() - exact).abs() < 1e-13);
        }
    }
}

//! One profile span in Bézier form, as the exact intersector evaluates it.
//!
//! A span is `(x(s), y(s))`, `s ∈ [0, 1]`, with Bernstein coefficients `xs`
//! and `ys`, and for a rational span positive weights `ws`: then
//! `x = X/W`, `y = Y/W` with `X = Σ wᵢxᵢBᵢ`, `Y = Σ wᵢyᵢBᵢ`, `W = Σ wᵢBᵢ`.
//! Spans of degree ≤ 5 come as fixed-size arrays ([`Fixed`]): the hit
//! polynomial, its root search and every evaluation are then compiled for
//! that size (unrolled, in registers, no dispatch per call). Higher degrees
//! use slices ([`Slices`]). Both compute the same numbers. Polynomial spans
//! carry [`Unweighted`], whose unit weights the compiler folds away.

use super::query::Query;
use crate::bernstein::Polynomial;
use crate::scratch::with_scratch;

/// A span's point `(x, y)` at one parameter and its derivative `(x′, y′)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct ProfilePoint {
    pub(super) x: f64,
    pub(super) y: f64,
    pub(super) dx: f64,
    pub(super) dy: f64,
}

/// A span's weights: none (a polynomial span) or one per coefficient.
pub(super) trait Weights: Copy {
    /// Whether the span is rational.
    const RATIONAL: bool;
    /// Weight `i` (1 for a polynomial span).
    fn at(&self, i: usize) -> f64;
}

/// The weights of a polynomial span: all 1, known at compile time.
#[derive(Debug, Clone, Copy)]
pub(super) struct Unweighted;

impl Weights for Unweighted {
    const RATIONAL: bool = false;
    #[inline(always)]
    fn at(&self, _: usize) -> f64 {
        1.0
    }
}

impl<const W: usize> Weights for &[f64; W] {
    const RATIONAL: bool = true;
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        self[i]
    }
}

impl Weights for &[f64] {
    const RATIONAL: bool = true;
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        self[i]
    }
}

/// A span's Bernstein coefficients and what the intersector evaluates on
/// them.
pub(super) trait SpanForm: Copy {
    /// The coefficients of the hit polynomial `f` (degree `2n`).
    type Poly: Polynomial + ?Sized;

    /// The coefficients of `x(s)`, `y(s)` and `y(s) − h` (degree `n`).
    type Coeffs: Polynomial + ?Sized;

    /// Whether the span is rational.
    const RATIONAL: bool;

    /// The `x` coefficients (the control points' `x`).
    fn xs(&self) -> &Self::Coeffs;

    /// The `y` coefficients (the control points' `y`).
    fn ys(&self) -> &Self::Coeffs;

    /// Hands the homogeneous coefficients `wᵢxᵢ`, `wᵢyᵢ`, `wᵢ` to `then`
    /// (for a polynomial span: `xs`, `ys` and ones).
    fn with_homogeneous<R>(
        &self,
        then: impl FnOnce(&Self::Coeffs, &Self::Coeffs, &Self::Coeffs) -> R,
    ) -> R;

    /// `x`, `y` and their derivatives at `s` (one de Casteljau pass each).
    ///
    /// A rational span is evaluated as `X/W`, `(X′ − xW′)/W`; beyond
    /// `[0, 1]` (where Newton's method may step, and `W` need not stay
    /// positive) it is continued along its end tangent.
    #[inline(always)]
    fn point(&self, s: f64) -> ProfilePoint {
        if !Self::RATIONAL {
            let (x, dx) = self.xs().value_and_slope(s).unwrap_or((0.0, 0.0));
            let (y, dy) = self.ys().value_and_slope(s).unwrap_or((0.0, 0.0));
            return ProfilePoint { x, y, dx, dy };
        }
        let inside = s.clamp(0.0, 1.0);
        let p = self.with_homogeneous(|hx, hy, w| {
            let (x, dx) = hx.value_and_slope(inside).unwrap_or((0.0, 0.0));
            let (y, dy) = hy.value_and_slope(inside).unwrap_or((0.0, 0.0));
            let (w, dw) = w.value_and_slope(inside).unwrap_or((1.0, 0.0));
            let (x, y) = (x / w, y / w);
            ProfilePoint {
                x,
                y,
                dx: (dx - x * dw) / w,
                dy: (dy - y * dw) / w,
            }
        });
        let beyond = s - inside;
        ProfilePoint {
            x: p.x + beyond * p.dx,
            y: p.y + beyond * p.dy,
            ..p
        }
    }

    /// `x(s)`.
    #[inline(always)]
    fn x(&self, s: f64) -> f64 {
        if Self::RATIONAL {
            self.point(s).x
        } else {
            self.xs().value(s)
        }
    }

    /// `y(s)`.
    #[inline(always)]
    fn y(&self, s: f64) -> f64 {
        if Self::RATIONAL {
            self.point(s).y
        } else {
            self.ys().value(s)
        }
    }

    /// Forms the hit polynomial of the ray `q` on this span (see the
    /// intersector's module docs; `weights` are its `C(n,i)C(n,j)/C(2n,i+j)`)
    /// and hands its coefficients and their rounding bound to `then`.
    fn with_hit_polynomial<R>(
        &self,
        q: &Query,
        weights: &[f64],
        then: impl FnOnce(&Self::Poly, f64) -> R,
    ) -> R;

    /// Forms `y(s) − h` (times `W` for a rational span), which vanishes
    /// where a ray perpendicular to the axis at height `h` meets the span's
    /// circles, and hands its coefficients and their rounding bound
    /// (`3ε wᵢ(|yᵢ| + |h|)`) to `then`.
    fn with_height_polynomial<R>(&self, h: f64, then: impl FnOnce(&Self::Coeffs, f64) -> R) -> R;
}

/// `wᵢ(yᵢ − h)` into `g` and its rounding bound.
#[inline(always)]
fn heights(ys: &[f64], ws: impl Weights, h: f64, g: &mut [f64]) -> f64 {
    let mut err = 0.0_f64;
    for (i, (gi, &y)) in g.iter_mut().zip(ys).enumerate() {
        let w = ws.at(i);
        *gi = w * (y - h);
        err = err.max(3.0 * f64::EPSILON * w * (y.abs() + h.abs()));
    }
    err
}

/// A span of `W` coefficients per coordinate (degree `W − 1`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Fixed<'a, const W: usize, R> {
    pub(super) xs: &'a [f64; W],
    pub(super) ys: &'a [f64; W],
    pub(super) ws: R,
}

/// A span of any degree.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slices<'a, R> {
    pub(super) xs: &'a [f64],
    pub(super) ys: &'a [f64],
    pub(super) ws: R,
}

/// `SpanForm` for `Fixed<W>` with a hit polynomial of `F = 2W − 1`
/// coefficients (stable Rust cannot write `2 * W − 1` as an array length).
macro_rules! fixed_span_form {
    ($($w:literal => $f:literal),*) => {$(
        impl<Wt: Weights> SpanForm for Fixed<'_, $w, Wt> {
            type Poly = [f64; $f];
            type Coeffs = [f64; $w];
            const RATIONAL: bool = Wt::RATIONAL;

            #[inline(always)]
            fn with_homogeneous<T>(
                &self,
                then: impl FnOnce(&Self::Coeffs, &Self::Coeffs, &Self::Coeffs) -> T,
            ) -> T {
                let w: [f64; $w] = std::array::from_fn(|i| self.ws.at(i));
                let hx: [f64; $w] = std::array::from_fn(|i| w[i] * self.xs[i]);
                let hy: [f64; $w] = std::array::from_fn(|i| w[i] * self.ys[i]);
                then(&hx, &hy, &w)
            }

            #[inline(always)]
            fn xs(&self) -> &Self::Coeffs {
                self.xs
            }

            #[inline(always)]
            fn ys(&self) -> &Self::Coeffs {
                self.ys
            }

            #[inline(always)]
            fn with_hit_polynomial<R>(
                &self,
                q: &Query,
                weights: &[f64],
                then: impl FnOnce(&Self::Poly, f64) -> R,
            ) -> R {
                let (mut a, mut b, mut c) = ([0.0; $w], [0.0; $w], [0.0; $w]);
                let m = span_terms(self.xs, self.ys, self.ws, q, &mut a, &mut b, &mut c);
                let mut f = [0.0; $f];
                let err = products_into(&a, &b, &c, m, Wt::RATIONAL, &weights[..$w * $w], &mut f);
                then(&f, err)
            }

            #[inline(always)]
            fn with_height_polynomial<R>(
                &self,
                h: f64,
                then: impl FnOnce(&Self::Coeffs, f64) -> R,
            ) -> R {
                let mut g = [0.0; $w];
                let err = heights(self.ys, self.ws, h, &mut g);
                then(&g, err)
            }
        }
    )*};
}

fixed_span_form!(2 => 3, 3 => 5, 4 => 7, 5 => 9, 6 => 11);

impl<Wt: Weights> SpanForm for Slices<'_, Wt> {
    type Poly = [f64];
    type Coeffs = [f64];
    const RATIONAL: bool = Wt::RATIONAL;

    fn with_homogeneous<T>(&self, then: impl FnOnce(&[f64], &[f64], &[f64]) -> T) -> T {
        let w = self.xs.len();
        with_scratch(3 * w, 0.0, |buf| {
            let (hx, rest) = buf.split_at_mut(w);
            let (hy, ws) = rest.split_at_mut(w);
            for i in 0..w {
                ws[i] = self.ws.at(i);
                hx[i] = ws[i] * self.xs[i];
                hy[i] = ws[i] * self.ys[i];
            }
            then(hx, hy, ws)
        })
    }

    fn xs(&self) -> &Self::Coeffs {
        self.xs
    }

    fn ys(&self) -> &Self::Coeffs {
        self.ys
    }

    fn with_hit_polynomial<R>(
        &self,
        q: &Query,
        weights: &[f64],
        then: impl FnOnce(&Self::Poly, f64) -> R,
    ) -> R {
        let w = self.xs.len();
        with_scratch(5 * w, 0.0, |buf| {
            let (a, rest) = buf.split_at_mut(w);
            let (b, rest) = rest.split_at_mut(w);
            let (c, f) = rest.split_at_mut(w);
            let f = &mut f[..(2 * w).saturating_sub(1)];
            let m = span_terms(self.xs, self.ys, self.ws, q, a, b, c);
            let err = products_into(a, b, c, m, Wt::RATIONAL, weights, f);
            then(f, err)
        })
    }

    fn with_height_polynomial<R>(&self, h: f64, then: impl FnOnce(&Self::Coeffs, f64) -> R) -> R {
        with_scratch(self.ys.len(), 0.0, |g| {
            let err = heights(self.ys, self.ws, h, g);
            then(g, err)
        })
    }
}

/// The Bernstein coefficients `aᵢ`, `bᵢ`, `cᵢ` of `A`, `B` and `d_y·x` for
/// one span (see the intersector's module docs), and the largest magnitudes
/// of the terms that form them (`|o_x d_y| + |h d_x|` and so on: with
/// cancellation the rounding error is relative to those, not to the result).
///
/// For a rational span the condition is multiplied by `W²`: `W·A`, `W·B`
/// and `d_y X` have the coefficients `wᵢaᵢ`, `wᵢbᵢ`, `wᵢcᵢ` (one more
/// rounding each, covered by [`products_into`]'s bound), so the hit
/// polynomial keeps degree `2n` and needs no division.
#[inline(always)]
fn span_terms(
    xs: &[f64],
    ys: &[f64],
    ws: impl Weights,
    q: &Query,
    a: &mut [f64],
    b: &mut [f64],
    c: &mut [f64],
) -> [f64; 3] {
    let (o, d) = (q.o, q.d);
    let (oxdy, ozdy) = (o.x * d.y, o.z * d.y);
    let mut m = [0.0_f64; 3];
    for i in 0..xs.len() {
        let w = ws.at(i);
        let h = ys[i] - o.y;
        a[i] = w * (oxdy + h * d.x);
        b[i] = w * (ozdy + h * d.z);
        c[i] = w * (d.y * xs[i]);
        m[0] = m[0].max(w * (oxdy.abs() + (h * d.x).abs()));
        m[1] = m[1].max(w * (ozdy.abs() + (h * d.z).abs()));
        m[2] = m[2].max(c[i].abs());
    }
    m
}

/// `f_k = Σ_{i+j=k} wᵢⱼ (aᵢaⱼ + bᵢbⱼ − cᵢcⱼ)` into `f` (length `2n + 1`)
/// and the bound on its rounding error.
///
/// `Σ_{i+j=k} wᵢⱼ = 1` (Vandermonde), so every coefficient is a weighted mean
/// of terms bounded by `m₀² + m₁² + m₂²` (`m` from [`span_terms`]). The
/// inputs carry up to 3ε error relative to `m`, products and the three
/// terms add 3ε, the `n + 1` sums `(n + 1)ε`: `(n + 8)ε` covers them.
#[inline(always)]
fn products_into(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    [ma, mb, mc]: [f64; 3],
    rational: bool,
    weights: &[f64],
    f: &mut [f64],
) -> f64 {
    let w = a.len();
    f.fill(0.0);
    for i in 0..w {
        f[2 * i] += weights[i * w + i] * (a[i] * a[i] + b[i] * b[i] - c[i] * c[i]);
        for j in i + 1..w {
            f[i + j] += 2.0 * weights[i * w + j] * (a[i] * a[j] + b[i] * b[j] - c[i] * c[j]);
        }
    }
    let slack = if rational { 10 } else { 7 };
    (w + slack) as f64 * f64::EPSILON * (ma * ma + mb * mb + mc * mc)
}

#[cfg(test)]
mod tests {
    use super::super::double_double::Dd;
    use super::*;
    use crate::Tolerance;
    use crate::bernstein::{bernstein_sum, binomial};
    use nalgebra::Vector3;

    /// A small deterministic generator of values in `[−1, 1)`.
    fn values(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    fn weights(w: usize) -> Vec<f64> {
        let n = w - 1;
        (0..w)
            .flat_map(|i| (0..w).map(move |j| (i, j)))
            .map(|(i, j)| binomial(n, i) * binomial(n, j) / binomial(2 * n, i + j))
            .collect()
    }

    /// Fixed-size and slice spans compute the same numbers, to the bit; the
    /// hit polynomial agrees with `A² + B² − (d_y x)²` and the height
    /// polynomial with `y − h`, both formed from the span's own `x(s)`,
    /// `y(s)` (Bernstein sums), within their stated error bounds plus the
    /// rounding of that direct evaluation.
    #[test]
    fn fixed_and_slice_spans_agree_with_the_direct_formula() {
        let mut next = values(11);
        for _ in 0..200 {
            let xs: [f64; 4] = std::array::from_fn(|_| 2.0 * next());
            let ys: [f64; 4] = std::array::from_fn(|_| 3.0 * next());
            let o = Vector3::new(4.0 * next(), 4.0 * next(), 4.0 * next());
            let d = Vector3::new(next(), next(), next());
            let q = Query::new(o, d, &Tolerance::default(), 3.0);
            let w = weights(4);
            let fixed = Fixed {
                xs: &xs,
                ys: &ys,
                ws: Unweighted,
            };
            let slices = Slices {
                xs: &xs,
                ys: &ys,
                ws: Unweighted,
            };
            let (f_fixed, e_fixed) = fixed.with_hit_polynomial(&q, &w, |f, e| (*f, e));
            let (f_slices, e_slices) = slices.with_hit_polynomial(&q, &w, |f, e| (f.to_vec(), e));
            assert_eq!(f_fixed.to_vec(), f_slices);
            assert_eq!(e_fixed, e_slices);
            let h = 3.0 * next();
            let (g_fixed, eg_fixed) = fixed.with_height_polynomial(h, |g, e| (*g, e));
            let (g_slices, eg_slices) = slices.with_height_polynomial(h, |g, e| (g.to_vec(), e));
            assert_eq!(g_fixed.to_vec(), g_slices);
            assert_eq!(eg_fixed, eg_slices);
            for k in 0..=10 {
                let s = f64::from(k) / 10.0;
                assert_eq!(fixed.point(s), slices.point(s));
                assert_eq!((fixed.x(s), fixed.y(s)), (slices.x(s), slices.y(s)));
                let (x, y) = (
                    bernstein_sum(&xs, s).unwrap(),
                    bernstein_sum(&ys, s).unwrap(),
                );
                let (a, b, c) = (
                    o.x * d.y + (y - o.y) * d.x,
                    o.z * d.y + (y - o.y) * d.z,
                    d.y * x,
                );
                let height = bernstein_sum(&g_fixed, s).unwrap();
                assert!((height - (y - h)).abs() <= eg_fixed + 8.0 * f64::EPSILON * 6.0);
                let direct = a * a + b * b - c * c;
                let got = bernstein_sum(&f_fixed, s).unwrap();
                let magnitude = (o.x * d.y).abs() + ((y - o.y) * d.x).abs();
                let rounding = 64.0 * f64::EPSILON * (magnitude + 10.0).powi(2);
                assert!(
                    (got - direct).abs() <= e_fixed + rounding,
                    "f({s}) = {got} but {direct}"
                );
            }
        }
    }

    /// The rounding bound of the hit polynomial holds: its coefficients are
    /// within the bound of the same coefficients in double-double arithmetic
    /// (exact weights to 106 bits, exact products), for random spans of
    /// degree 1 to 5 and random rays, origins up to 1e6 away and rays aimed
    /// at a point of the span (where the coefficients cancel). And the bound
    /// is not vacuous: it stays below `1e-13` of the terms' size, and is no
    /// more than about a thousand times the largest error seen.
    #[test]
    fn hit_polynomial_is_within_its_rounding_bound() {
        check_rounding_bound(29, false);
    }

    /// The same for rational spans, weights from 0.05 to 20: the
    /// coefficients of `W²f` against double-double.
    #[test]
    fn rational_hit_polynomial_is_within_its_rounding_bound() {
        check_rounding_bound(31, true);
    }

    fn check_rounding_bound(seed: u64, rational: bool) {
        let mut next = values(seed);
        let mut worst = 0.0_f64;
        for case in 0..3000 {
            let w = 2 + case % 5;
            let n = w - 1;
            let xs: Vec<f64> = (0..w).map(|_| 2.0 * next()).collect();
            let ys: Vec<f64> = (0..w).map(|_| 3.0 * next()).collect();
            let ws: Vec<f64> = (0..w)
                .map(|_| {
                    if rational {
                        0.05 * 400f64.powf(0.5 + 0.5 * next())
                    } else {
                        1.0
                    }
                })
                .collect();
            let far = [1.0, 1e3, 1e6][case % 3];
            let o = Vector3::new(4.0 * next(), 4.0 * next(), 4.0 * next()) * far;
            let mut d = Vector3::new(next(), next(), next());
            if case % 4 == 0 {
                // Aim at a point of the span's profile circle: f has a root.
                let s = 0.5 + 0.5 * next();
                let hx: Vec<f64> = (0..w).map(|i| ws[i] * xs[i]).collect();
                let hy: Vec<f64> = (0..w).map(|i| ws[i] * ys[i]).collect();
                let weight = bernstein_sum(&ws, s).unwrap();
                let (x, y) = (
                    bernstein_sum(&hx, s).unwrap() / weight,
                    bernstein_sum(&hy, s).unwrap() / weight,
                );
                let angle = 3.0 * next();
                d = Vector3::new(x * angle.cos(), y, -x * angle.sin()) - o;
            }
            let q = Query::new(o, d, &Tolerance::default(), 3.0);
            let (f, err) = if rational {
                let span = Slices {
                    xs: &xs,
                    ys: &ys,
                    ws: &ws[..],
                };
                span.with_hit_polynomial(&q, &weights(w), |f, e| (f.to_vec(), e))
            } else {
                let span = Slices {
                    xs: &xs,
                    ys: &ys,
                    ws: Unweighted,
                };
                span.with_hit_polynomial(&q, &weights(w), |f, e| (f.to_vec(), e))
            };
            let term = |i: usize| {
                let h = Dd::from(ys[i]).add(Dd::from(-o.y));
                let wi = Dd::from(ws[i]);
                (
                    wi.mul(Dd::from(o.x).mul(Dd::from(d.y)).add(h.mul(Dd::from(d.x)))),
                    wi.mul(Dd::from(o.z).mul(Dd::from(d.y)).add(h.mul(Dd::from(d.z)))),
                    wi.mul(Dd::from(d.y).mul(Dd::from(xs[i]))),
                )
            };
            for (k, &fk) in f.iter().enumerate() {
                let mut exact = Dd::from(0.0);
                for i in k.saturating_sub(n)..=k.min(n) {
                    let j = k - i;
                    let ((ai, bi, ci), (aj, bj, cj)) = (term(i), term(j));
                    let weight = Dd::ratio(binomial(n, i) * binomial(n, j), binomial(2 * n, k));
                    let sum = ai.mul(aj).add(bi.mul(bj)).add(ci.mul(cj).neg());
                    exact = exact.add(weight.mul(sum));
                }
                let off = ((fk - exact.0) - exact.1).abs();
                assert!(
                    off <= err,
                    "case {case}, degree {n}: f_{k} = {fk} is {off:e} off, bound {err:e}"
                );
                worst = worst.max(off / err);
            }
            // |aᵢ|, |bᵢ| ≤ wᵢ(|o|·|d|·2 + 3|d|), |cᵢ| ≤ 2wᵢ|d_y|.
            let w_max = ws.iter().fold(0.0_f64, |m, &w| m.max(w));
            let size = w_max.powi(2)
                * ((2.0 * o.amax() * d.amax() + 3.0 * d.amax()).powi(2) + (2.0 * d.y).powi(2));
            assert!(
                err <= 1e-13 * size,
                "bound {err:e} for terms of size {size:e}"
            );
        }
        // The bound is no more than a thousand times the worst error seen
        // (it is a worst case over all roundings; here a quarter is used).
        assert!(worst > 1e-3, "largest error only {worst:e} of the bound");
    }
}

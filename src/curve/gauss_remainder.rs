//! A certified bound on the error of Gauss–Legendre quadrature of the speed
//! of a piece of a rational Bézier span: what makes the arc length's bracket
//! as tight as its estimate.
//!
//! The span is `C = A/w` (homogeneous Bernstein coefficients), with speed
//! `|C′| = √h / w²`, where `h = N·N` and `N = w·A′ − w′·A`; `N` has degree
//! `2n − 2` (the leading terms cancel), `n − 1` for a polynomial span (`w`
//! constant). On the piece `[s₀, s₁]`, in `x ∈ [−1, 1]`, `h` and `w` are
//! polynomials with Chebyshev coefficients `cₖ`, exact from their values at
//! as many Chebyshev points as coefficients. On the Bernstein ellipse
//! `E_ρ` of `[−1, 1]`, `|Tₖ| ≤ (ρᵏ + ρ⁻ᵏ)/2`, so `p` stays within
//! `Δp = Σₖ₌₁ |cₖ|·(ρᵏ + ρ⁻ᵏ)/2` of `c₀`. Where `Δh < c₀(h)` and
//! `Δw < c₀(w)`, `h` keeps to the right half-plane and `w` off zero: the
//! speed continues analytically into `E_ρ` with
//! `|f| ≤ M = √(c₀(h) + Δh)/(c₀(w) − Δw)²`, and the `m`-point Gauss rule on
//! the piece's own `[0, 1]` errs by at most `(64/15)·M·ρ⁻²ᵐ/(ρ² − 1)·½`
//! (Trefethen, *Approximation Theory and Approximation Practice*, Theorem
//! 19.3, on `[−1, 1]` scaled by ½). The Chebyshev basis is the ellipse's
//! own: a polynomial of high degree whose variation is mostly linear gets a
//! bound near `|c₁|·ρ`, not the `Sᵈ` of the Bernstein basis.

use super::homogeneous::Homogeneous;
use crate::bernstein;
use crate::scratch::with_scratch;

/// The ellipse parameters tried, largest (smallest bound) first.
const RHOS: [f64; 8] = [16.0, 10.0, 6.0, 4.0, 2.8, 2.0, 1.6, 1.3];

/// The `m` Chebyshev points `xⱼ = cos(π(j + ½)/m)` of `[−1, 1]`,
/// decreasing (symmetric about 0).
fn nodes(x: &mut [f64]) {
    let m = x.len();
    for j in 0..m.div_ceil(2) {
        let node = (std::f64::consts::PI * (j as f64 + 0.5) / m as f64).cos();
        x[j] = node;
        x[m - 1 - j] = -node;
    }
    if m % 2 == 1 {
        x[m / 2] = 0.0;
    }
}

/// `h` and `w` at the points `x` of the piece `[s₀, s₁]` (in the piece's
/// own parameter) of the span `coeffs`, into `h` and `w`, and bounds on
/// each sample's rounding.
///
/// The bounds are local, so that a part of the span where the weight or the
/// speed is small is not charged the rounding of the span's largest
/// coefficients: de Casteljau's value errs by at most `(n + 1)ε·Σ|cᵢ|Bᵢⁿ(s)`
/// and its derivative by `(n + 1)ε·n·Σ(|cᵢ| + |cᵢ₊₁|)Bᵢⁿ⁻¹(s)` (each level a
/// convex combination, one rounding a step), with `|cᵢ|` the coefficients'
/// norms, evaluated the same way (their own rounding is second order and
/// covered by the factor 4 below); `N = w·A′ − w′·A` adds its products'.
fn sample<const D: usize>(
    coeffs: &[Homogeneous<D>],
    (s0, s1): (f64, f64),
    x: &[f64],
    h: &mut [f64],
    w: &mut [f64],
) -> (f64, f64) {
    let n = coeffs.len() - 1;
    let width = s1 - s0;
    let unit = 4.0 * (n + 1) as f64 * f64::EPSILON;
    let mut h_rounding = 0.0_f64;
    let mut w_rounding = 0.0_f64;
    // The coefficients' magnitudes `(|wᵢPᵢ|, |wᵢ|)` and their neighbours'
    // sums, as homogeneous values so that one evaluation gives both.
    let sizes = |c: &Homogeneous<D>| (c.wp.norm(), c.w.abs());
    with_scratch(2 * n + 1, Homogeneous::<1>::zero(), |buf| {
        let (values, pairs) = buf.split_at_mut(n + 1);
        for (v, c) in values.iter_mut().zip(coeffs) {
            let (p, q) = sizes(c);
            *v = Homogeneous::new(&nalgebra::Point1::new(p), 1.0);
            v.w = q;
        }
        for (i, pair) in pairs.iter_mut().enumerate() {
            let (p0, q0) = sizes(&coeffs[i]);
            let (p1, q1) = sizes(&coeffs[i + 1]);
            *pair = Homogeneous::new(&nalgebra::Point1::new(p0 + p1), 1.0);
            pair.w = q0 + q1;
        }
        for ((&xj, hj), wj) in x.iter().zip(h.iter_mut()).zip(w.iter_mut()) {
            let s = s0 + 0.5 * (1.0 + xj) * width;
            let (value, slope) = bernstein::eval_with_derivative(coeffs, s)
                .unwrap_or((Homogeneous::zero(), Homogeneous::zero()));
            let size = bernstein::eval(values, s).unwrap_or_else(Homogeneous::zero);
            let slope_size = bernstein::eval(pairs, s).unwrap_or_else(Homogeneous::zero);
            // Value and derivative errors of A and w at s.
            let (ea, ew) = (unit * size.wp[0], unit * size.w);
            let (ea1, ew1) = (
                unit * n as f64 * slope_size.wp[0],
                unit * n as f64 * slope_size.w,
            );
            // N in the piece's parameter: the chain rule's factor `width`.
            let big_n = (slope.wp * value.w - value.wp * slope.w) * width;
            let terms = slope.wp.norm() * value.w.abs() + value.wp.norm() * slope.w.abs();
            let n_rounding = (value.w.abs() * ea1
                + (slope.wp.norm() + ea1) * ew
                + slope.w.abs() * ea
                + (value.wp.norm() + ea) * ew1
                + 4.0 * f64::EPSILON * terms)
                * width;
            *hj = big_n.norm_squared();
            *wj = value.w;
            h_rounding = h_rounding
                .max((2.0 * big_n.norm() + n_rounding) * n_rounding + 4.0 * f64::EPSILON * *hj);
            w_rounding = w_rounding.max(ew);
        }
    });
    (h_rounding, w_rounding)
}

/// Into `c`, the Chebyshev coefficients `c₀ … c_deg` (`deg < m`) of the
/// polynomial whose values at the `m` Chebyshev points `x` are `values`:
/// `c₁ …` as magnitudes widened by a bound on their rounding (the samples'
/// `rounding`, the sums' and the recurrence's), `c₀` as a lower bound.
fn chebyshev(x: &[f64], values: &[f64], c: &mut [f64], rounding: f64) {
    let m = values.len();
    let top = values.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let error = 2.0 * rounding + 4.0 * (m * m) as f64 * f64::EPSILON * top;
    c.fill(0.0);
    for (&xj, &v) in x.iter().zip(values) {
        // T₀ … T_deg at xⱼ by the three-term recurrence.
        let (mut previous, mut current) = (1.0, xj);
        c[0] += v;
        for ck in c.iter_mut().skip(1) {
            *ck += v * current;
            let next = 2.0 * xj * current - previous;
            previous = current;
            current = next;
        }
    }
    let scale = 2.0 / m as f64;
    c[0] = 0.5 * scale * c[0] - error;
    for ck in c.iter_mut().skip(1) {
        *ck = (scale * *ck).abs() + error;
    }
}

/// `(c₀, Δ)` on `E_ρ`: the centre (a lower bound) and the radius of a disk
/// holding the polynomial there (infinite where the powers overflow).
fn disk(c: &[f64], rho: f64) -> (f64, f64) {
    let mut radius = 0.0;
    let mut power = 1.0;
    for &ck in &c[1..] {
        power *= rho;
        radius += ck * 0.5 * (power + 1.0 / power);
    }
    (
        c[0],
        if radius.is_finite() {
            radius
        } else {
            f64::INFINITY
        },
    )
}

/// A bound on the error of the `points`-point Gauss–Legendre rule for the
/// length of the piece `[s₀, s₁]` of the span `coeffs` (homogeneous
/// coefficients, weights positive), rounding in the sampled values
/// included; `None` where no ellipse of [`RHOS`] certifies it (a cusp, or a
/// turn sharp for the piece's size: a halving about halves the distance
/// from the speed's nearest complex singularity to the piece, in units of
/// the piece).
pub(super) fn gauss_remainder<const D: usize>(
    coeffs: &[Homogeneous<D>],
    piece: (f64, f64),
    points: usize,
) -> Option<f64> {
    let n = coeffs.len().checked_sub(1)?;
    if n == 0 {
        return Some(0.0);
    }
    let polynomial = coeffs.iter().all(|c| c.w == coeffs[0].w);
    let (h_degree, w_degree) = if polynomial {
        (2 * n - 2, 0)
    } else {
        (4 * n - 4, n)
    };
    let m = h_degree.max(w_degree) + 1;
    with_scratch(5 * m, 0.0, |buf| {
        let (x, rest) = buf.split_at_mut(m);
        let (h_values, rest) = rest.split_at_mut(m);
        let (w_values, rest) = rest.split_at_mut(m);
        let (h, w) = rest.split_at_mut(m);
        let (h, w) = (&mut h[..=h_degree], &mut w[..=w_degree]);
        nodes(x);
        let (h_rounding, w_rounding) = sample(coeffs, piece, x, h_values, w_values);
        chebyshev(x, h_values, h, h_rounding);
        chebyshev(x, w_values, w, w_rounding);
        // The largest ellipse that certifies: the bound falls like ρ⁻²ᵐ,
        // far faster than `M` grows.
        RHOS.iter().find_map(|&rho| {
            let (h0, dh) = disk(h, rho);
            let (w0, dw) = disk(w, rho);
            if !(dh < h0 && dw < w0) {
                return None;
            }
            let bound = (h0 + dh).sqrt() / ((w0 - dw) * (w0 - dw));
            let error =
                64.0 / 15.0 * bound * rho.powi(-2 * points as i32) / (rho * rho - 1.0) * 0.5;
            error.is_finite().then_some(error)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;

    fn span(points: &[(f64, f64)], weights: &[f64]) -> Vec<Homogeneous<2>> {
        points
            .iter()
            .zip(weights)
            .map(|(&(x, y), &w)| Homogeneous::new(&Point2::new(x, y), w))
            .collect()
    }

    /// A straight segment at constant speed: every ellipse certifies, and
    /// the bound is that of the largest (up to the rounding allowance).
    #[test]
    fn a_segment_is_certified_with_the_largest_ellipse() {
        let coeffs = span(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)], &[1.0; 4]);
        let e = gauss_remainder(&coeffs, (0.0, 1.0), 16).unwrap();
        let rho: f64 = RHOS[0];
        let expected = 64.0 / 15.0 * 3.0 * rho.powi(-32) / (rho * rho - 1.0) * 0.5;
        assert!(
            expected <= e && e <= expected * (1.0 + 1e-3),
            "{e:e} vs {expected:e}"
        );
    }

    /// A cusp (speed zero inside) is never certified: the speed is not
    /// analytic there, on the span or on the piece around it.
    #[test]
    fn a_cusp_is_not_certified() {
        let coeffs = span(&[(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)], &[1.0; 4]);
        assert!(gauss_remainder(&coeffs, (0.0, 1.0), 16).is_none());
        assert!(gauss_remainder(&coeffs, (0.49, 0.51), 16).is_none());
    }

    /// The sampled Chebyshev coefficients reproduce `h` and `w` away from
    /// the sample points (so the degrees `2n − 2` of `N` and `n` of `w` are
    /// right): a rational cubic, compared at other parameters with `h`
    /// computed directly.
    #[test]
    fn chebyshev_coefficients_reproduce_the_span() {
        let coeffs = span(
            &[(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0)],
            &[1.0, 0.3, 2.0, 0.7],
        );
        let piece = (0.2, 0.7);
        let mut x = [0.0; 9];
        nodes(&mut x);
        let (mut hs, mut ws) = ([0.0; 9], [0.0; 9]);
        sample(&coeffs, piece, &x, &mut hs, &mut ws);
        let (mut h, mut w) = ([0.0; 9], [0.0; 4]);
        chebyshev(&x, &hs, &mut h, 0.0);
        chebyshev(&x, &ws, &mut w, 0.0);
        // The magnitudes against a sum with `cos` (signs kept), then the
        // signed series against `h` and `w` computed directly.
        let signed = |values: &[f64], deg: usize| -> Vec<f64> {
            let m = values.len();
            (0..=deg)
                .map(|k| {
                    let c: f64 = values
                        .iter()
                        .enumerate()
                        .map(|(j, v)| {
                            v * (k as f64 * std::f64::consts::PI * (j as f64 + 0.5) / m as f64)
                                .cos()
                        })
                        .sum::<f64>()
                        * 2.0
                        / m as f64;
                    if k == 0 { 0.5 * c } else { c }
                })
                .collect()
        };
        let (hc, wc) = (signed(&hs, 8), signed(&ws, 3));
        for (bound, c) in h.iter().zip(&hc).skip(1) {
            assert!((bound - c.abs()).abs() <= 1e-12 * bound.max(1.0));
        }
        assert!((h[0] - hc[0]).abs() <= 1e-12 * h[0]);
        assert!((w[0] - wc[0]).abs() <= 1e-12);
        for x in [-0.93, -0.4, 0.17, 0.66] {
            let s = piece.0 + 0.5 * (1.0 + x) * (piece.1 - piece.0);
            let (value, slope) = bernstein::eval_with_derivative(&coeffs, s).unwrap();
            let big_n = (slope.wp * value.w - value.wp * slope.w) * (piece.1 - piece.0);
            let series = |c: &[f64]| -> f64 {
                c.iter()
                    .enumerate()
                    .map(|(k, ck)| ck * (k as f64 * x.acos()).cos())
                    .sum()
            };
            let direct = big_n.norm_squared();
            assert!((series(&hc) - direct).abs() <= 1e-12 * direct, "x = {x}");
            assert!((series(&wc) - value.w).abs() <= 1e-12, "x = {x}");
        }
    }
}

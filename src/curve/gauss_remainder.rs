//! A certified bound on the error of Gauss–Legendre quadrature of the speed
//! of a rational Bézier piece: what makes the arc length's bracket as tight
//! as its estimate.
//!
//! On its own parameter `u ∈ [0, 1]` the piece is `C = A/w` (homogeneous
//! Bernstein coefficients), with speed `|C′| = √h / w²`, where
//! `h = |N|²` and `N = w·A′ − w′·A`; `h` and `w` are polynomials. For a
//! complex `z`, `Σᵢ |Bᵢᵈ(z)| = (|z| + |1 − z|)ᵈ`, and on the Bernstein
//! ellipse `E_ρ` of `[0, 1]` (foci 0 and 1) `|z| + |1 − z| ≤ S = (ρ + 1/ρ)/2`.
//! So a polynomial `p` of Bernstein coefficients `pᵢ` stays within
//! `Δp = maxᵢ|pᵢ − p₀|·Sᵈ` of `p₀ = p(½)` on `E_ρ`. Where `Δh < h₀` and
//! `Δw < w₀`, `h` keeps off the negative axis and `w` off zero: the speed
//! continues analytically into `E_ρ` with `|f| ≤ M = √(h₀ + Δh)/(w₀ − Δw)²`,
//! and the `m`-point Gauss rule on `[0, 1]` errs by at most
//! `(64/15)·M·ρ⁻²ᵐ/(ρ² − 1)·½` (Trefethen, *Approximation Theory and
//! Approximation Practice*, Theorem 19.3, on `[−1, 1]` scaled by ½).

use super::homogeneous::Homogeneous;
use crate::bernstein::binomial_row;
use nalgebra::SVector;

/// The ellipse parameters tried, largest (smallest bound) first.
const RHOS: [f64; 6] = [8.0, 5.0, 3.5, 2.5, 1.8, 1.4];

/// Relative allowance for the rounding of the coefficients computed here
/// (a few hundred ulps of products of the piece's own coefficients).
const COEFFICIENT_ROUNDING: f64 = 1e-10;

/// The product of two Bernstein polynomials, of degrees `a` and `b`:
/// `(p·q)ₖ = Σᵢ₊ⱼ₌ₖ C(a,i)·C(b,j)/C(a+b,k) · pᵢ·qⱼ`.
fn product<T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>>(
    p: &[f64],
    q: &[T],
    zero: T,
) -> Vec<T> {
    let (a, b) = (p.len() - 1, q.len() - 1);
    let (row_a, row_b, row_ab) = (binomial_row(a), binomial_row(b), binomial_row(a + b));
    (0..=a + b)
        .map(|k| {
            let mut sum = zero;
            for i in k.saturating_sub(b)..=k.min(a) {
                let c = row_a[i] * row_b[k - i] / row_ab[k];
                sum = sum + q[k - i] * (p[i] * c);
            }
            sum
        })
        .collect()
}

/// The value at ½ (de Casteljau) and the largest distance of a coefficient
/// from it.
fn centre_and_spread(c: &[f64]) -> (f64, f64) {
    let mut work = c.to_vec();
    let n = work.len() - 1;
    for level in 1..=n {
        for j in 0..=(n - level) {
            work[j] = 0.5 * (work[j] + work[j + 1]);
        }
    }
    let centre = work[0];
    let spread = c.iter().fold(0.0_f64, |m, &x| m.max((x - centre).abs()));
    (centre, spread)
}

/// A bound on the error of the `points`-point Gauss–Legendre rule for the
/// length of `piece` (homogeneous coefficients on its own `[0, 1]`), in
/// exact arithmetic; where no ellipse of [`RHOS`] certifies it, `Err` with
/// how many times too wide the spreads are for the narrowest ellipse (a
/// halving about halves them), infinite where nothing can be said.
pub(super) fn gauss_remainder<const D: usize>(
    piece: &[Homogeneous<D>],
    points: usize,
) -> Result<f64, f64> {
    let Some(n) = piece.len().checked_sub(1) else {
        return Err(f64::INFINITY);
    };
    if n == 0 {
        return Ok(0.0);
    }
    let mut w: Vec<f64> = piece.iter().map(|h| h.w).collect();
    let a: Vec<SVector<f64, D>> = piece.iter().map(|h| h.wp).collect();
    let da: Vec<SVector<f64, D>> = a.windows(2).map(|x| (x[1] - x[0]) * n as f64).collect();
    let zero = SVector::<f64, D>::zeros();
    let big_n: Vec<SVector<f64, D>> = if w.iter().all(|&x| x == w[0]) {
        // Equal weights: N = w·A′ of degree n − 1, and w a constant (the
        // lowest degrees make the tightest bounds).
        w.truncate(1);
        da.iter().map(|v| v * w[0]).collect()
    } else {
        // N = w·A′ − w′·A, degree 2n − 1.
        let dw: Vec<f64> = w.windows(2).map(|x| (x[1] - x[0]) * n as f64).collect();
        product(&w, &da, zero)
            .iter()
            .zip(product(&dw, &a, zero))
            .map(|(x, y)| x - y)
            .collect()
    };
    // h = |N|², degree 4n − 2, one coordinate at a time.
    let mut h = vec![0.0; 2 * big_n.len() - 1];
    for d in 0..D {
        let coordinate: Vec<f64> = big_n.iter().map(|v| v[d]).collect();
        for (hk, x) in h.iter_mut().zip(product(&coordinate, &coordinate, 0.0)) {
            *hk += x;
        }
    }
    let (h0, h_spread) = centre_and_spread(&h);
    let (w0, w_spread) = centre_and_spread(&w);
    let h_max = h.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let w_max = w.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let h_spread = h_spread + COEFFICIENT_ROUNDING * h_max;
    let w_spread = w_spread + COEFFICIENT_ROUNDING * w_max;
    if !(h0 > 0.0 && w0 > 0.0 && h0.is_finite() && w0.is_finite()) {
        return Err(f64::INFINITY);
    }
    let mut too_wide = f64::INFINITY;
    for &rho in &RHOS {
        let s = 0.5 * (rho + 1.0 / rho);
        let dh = h_spread * s.powi(h.len() as i32 - 1);
        let dw = w_spread * s.powi(w.len() as i32 - 1);
        if dh < h0 && dw < w0 {
            let m = (h0 + dh).sqrt() / ((w0 - dw) * (w0 - dw));
            let error = 64.0 / 15.0 * m * rho.powi(-2 * points as i32) / (rho * rho - 1.0) * 0.5;
            if error.is_finite() {
                return Ok(error);
            }
        }
        too_wide = (dh / h0).max(dw / w0);
    }
    Err(too_wide)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight segment at constant speed: every ellipse certifies, and
    /// the bound is that of the largest (up to the rounding allowance).
    #[test]
    fn a_segment_is_certified_with_the_largest_ellipse() {
        let piece: Vec<Homogeneous<2>> = (0..4)
            .map(|i| Homogeneous::new(&nalgebra::Point2::new(i as f64, 0.0), 1.0))
            .collect();
        let e = gauss_remainder(&piece, 16).unwrap();
        let rho: f64 = 8.0;
        let expected = 64.0 / 15.0 * 3.0 * rho.powi(-32) / (rho * rho - 1.0) * 0.5;
        assert!(
            expected <= e && e <= expected * (1.0 + 1e-3),
            "{e:e} vs {expected:e}"
        );
    }

    /// A cusp (speed zero inside) is never certified: the speed is not
    /// analytic there.
    #[test]
    fn a_cusp_is_not_certified() {
        let points = [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)];
        let piece: Vec<Homogeneous<2>> = points
            .iter()
            .map(|&(x, y)| Homogeneous::new(&nalgebra::Point2::new(x, y), 1.0))
            .collect();
        assert!(gauss_remainder(&piece, 16).is_err());
    }
}

//! A certified lower bound of the squared distance from a point to a piece
//! of a (rational) Bézier patch, from the Bernstein form of that distance.
//!
//! With the query point `P` at the origin (the net translated: `Yᵢⱼ =
//! wᵢⱼ(Pᵢⱼ − P)`, weights `wᵢⱼ > 0`), the piece is `S − P = Y/w` with `Y`
//! and `w` tensor Bernstein polynomials of degrees `(p, q)` on `[0, 1]²`,
//! and `|S − P|² = F/W` with `F = Y·Y` and `W = w²`, both of degrees
//! `(2p, 2q)`. Their Bernstein coefficients are exact sums of products
//! (Farin, *Curves and Surfaces for CAGD*, the product of Bernstein
//! polynomials):
//!
//! ```text
//! F_kl = Σ_{i+i′=k, j+j′=l} C(p,i)C(p,i′)C(q,j)C(q,j′)/(C(2p,k)C(2q,l)) · Yᵢⱼ·Yᵢ′ⱼ′,
//! ```
//!
//! and `W` likewise (`W ≡ 1` for a polynomial patch). Then `|S − P|² ≥ L`
//! on the piece exactly when `Φ = F − L·W ≥ 0` there (`W > 0`), and `Φ` is
//! bounded below two ways, the larger kept:
//!
//! - by its least Bernstein coefficient (the convex hull property);
//! - to second order about a point `c` of the piece: `Φ(c + d) ≥ Φ(c) +
//!   ∇Φ(c)·d + ½·dᵀHd` for a matrix `H` below every Hessian of `Φ` on the
//!   piece, whose entries are bounded by the Bernstein coefficients of
//!   `Φ`'s second derivatives (`2p(2p − 1)·Δ²`, `2p·2q·ΔΔ`): with
//!   `H_ss ≥ a`, `H_tt ≥ c` and `b_lo ≤ H_st ≤ b_hi`, `dᵀHd ≥ a·d_s² +
//!   2b·d_s·d_t + c·d_t²` with `b = b_lo` where `d_s·d_t ≥ 0` and `b = b_hi`
//!   elsewhere, so the bound is the least of four quadratics, each over one
//!   quadrant of the piece about `c` (a rectangle: the interior critical
//!   point if the quadratic is convex, else its sides, one-dimensional
//!   quadratics). Exact for a quadratic `Φ`, however skewed the
//!   parametrization.
//!
//! The second bound is what ends the search near a minimum: about the
//! piece's own nearest point (found by Newton's method), where `∇Φ` is
//! nearly zero or points out of the piece and `H` is positive definite,
//! it is `Φ(c)` less rounding, so the piece is settled whole instead of cut
//! ever finer. It is exact for exact identities too (a sphere's centre:
//! `F = R²W`, every coefficient of `Φ` is `(R² − L)·W_kl`).
//!
//! # Rounding
//! The net's coordinates carry rounding (the translation and the
//! subdivision): the computed `Ỹ`, `w̃` are within `e_Y` (per coordinate)
//! and `e_w` of the exact piece's everywhere (the Bernstein basis sums to
//! one). So `|Y| ≥ |Ỹ| − √3·e_Y` and `ℓ·w ≤ ℓ·w̃ + ℓ·e_w`, and
//! `|S − P| ≥ ℓ` on the exact piece once `|Ỹ| ≥ ℓ′·w̃` with
//! `ℓ′ = ℓ + (ℓ·e_w + √3·e_Y)/(w_min − e_w)`: the computed net is bounded
//! as if exact, against the raised level `L = ℓ′²`. (Moving the net's
//! error into the level, rather than into `F`'s coefficients, keeps it
//! proportional to the distance: near the surface a piece is settled
//! without being cut down to the size of the distance.) The coefficients
//! of `Φ = F(Ỹ) − L·W(w̃)` as computed are within
//! `η = 3γY² + L·γw² + 2u(L·W + F)` of the exact ones (`γ =
//! ((p+1)(q+1) + 12)·u`, `u = ε/2`, `Y`, `w`, `F`, `W` the largest
//! magnitudes), and evaluating the bound from them adds at most
//! `16u·M·(2p + 2q + 2)²` (`M` the largest coefficient magnitude): de
//! Casteljau's value and gradient, the differences and the final sums.

use super::patch::tensor_jet;
use crate::bernstein::binomial_row;
use crate::curve::Homogeneous;
use crate::scratch::with_scratch;
use nalgebra::Vector3;

/// The largest degree in each direction the form is built for: beyond it
/// the binomials of degree `2p` are no longer exact in `f64` (and the form
/// costs `O(p²q²)`), and pieces are bounded by their boxes alone.
pub(super) const MAX_FORM_DEGREE: usize = 24;

/// The unit roundoff.
const U: f64 = f64::EPSILON / 2.0;

/// Below this, an absolute allowance for underflow (the search's nets are
/// scaled so their largest coordinate is about 1).
const UNDERFLOW: f64 = 1e-290;

/// The Bernstein form of the squared distance of pieces of one degree pair,
/// with its work space.
#[derive(Debug, Clone)]
pub(super) struct DistanceForm {
    /// `(p, q)`.
    pub(super) degrees: (usize, usize),
    /// `C(p,i)·C(q,j)`, row-major `(p + 1) × (q + 1)`.
    scales: Vec<f64>,
    /// `1/(C(2p,k)·C(2q,l))`, row-major `(2p + 1) × (2q + 1)`.
    inverses: Vec<f64>,
    /// `i·(2q + 1) + j` for the net's entry `(i, j)`: the index of the
    /// product of entries `a` and `b` in the form is the sum of theirs.
    places: Vec<usize>,
    /// The coefficients of `F`.
    f: Vec<f64>,
    /// The coefficients of `W` (unused for a polynomial piece).
    w: Vec<f64>,
    /// The coefficients of `Φ = F − L·W`.
    phi: Vec<f64>,
    /// Whether `W` is formed (a rational piece).
    rational: bool,
    /// The net's error bounds `(e_Y, e_w)` and least weight.
    net_errors: (f64, f64),
    w_min: f64,
    /// `3γY²`: the rounding of `F`'s coefficients.
    f_error: f64,
    /// `γw²`: the rounding of `W`'s coefficients.
    w_error: f64,
    /// The largest coefficients of `F` and `W`.
    f_max: f64,
    w_max: f64,
    /// `Φ`'s rounding bound, least coefficient and largest magnitude.
    eta: f64,
    least: f64,
    magnitude: f64,
}

impl DistanceForm {
    /// The form for degrees `(p, q)`, each at most [`MAX_FORM_DEGREE`].
    pub(super) fn new((p, q): (usize, usize)) -> Self {
        let (bp, bq) = (binomial_row(p), binomial_row(q));
        let (b2p, b2q) = (binomial_row(2 * p), binomial_row(2 * q));
        let scales = bp
            .iter()
            .flat_map(|a| bq.iter().map(move |b| a * b))
            .collect();
        let inverses = b2p
            .iter()
            .flat_map(|a| b2q.iter().map(move |b| 1.0 / (a * b)))
            .collect();
        let len = (2 * p + 1) * (2 * q + 1);
        let places = (0..=p)
            .flat_map(|i| (0..=q).map(move |j| i * (2 * q + 1) + j))
            .collect();
        DistanceForm {
            degrees: (p, q),
            scales,
            inverses,
            places,
            f: vec![0.0; len],
            w: vec![0.0; len],
            phi: vec![0.0; len],
            rational: false,
            net_errors: (0.0, 0.0),
            w_min: 1.0,
            f_error: 0.0,
            w_error: 0.0,
            f_max: 0.0,
            w_max: 0.0,
            eta: f64::INFINITY,
            least: f64::NEG_INFINITY,
            magnitude: 0.0,
        }
    }

    /// Forms `F` (and `W` when `rational`) of the translated net `net`
    /// (`(Yᵢⱼ, wᵢⱼ)`, row-major), whose entries are within `e_y` (each
    /// coordinate of `Y`) and `e_w` (each weight) of the exact piece's, and
    /// whose exact weights are at least `w_min`.
    pub(super) fn load(
        &mut self,
        net: &[Homogeneous<3>],
        rational: bool,
        (e_y, e_w): (f64, f64),
        w_min: f64,
    ) {
        let (p, q) = self.degrees;
        self.rational = rational;
        self.net_errors = (e_y, e_w);
        self.w_min = w_min;
        self.f.iter_mut().for_each(|x| *x = 0.0);
        if rational {
            self.w.iter_mut().for_each(|x| *x = 0.0);
        }
        let (mut y_max, mut w_max) = (0.0_f64, 0.0_f64);
        let n = net.len();
        with_scratch(n, (Vector3::zeros(), 0.0), |scaled| {
            for ((x, h), &c) in scaled.iter_mut().zip(net).zip(&self.scales) {
                y_max = y_max.max(h.wp.amax());
                w_max = w_max.max(h.w);
                *x = (h.wp * c, h.w * c);
            }
            for a in 0..n {
                let ((ya, wa), pa) = (scaled[a], self.places[a]);
                self.f[2 * pa] += ya.dot(&ya);
                if rational {
                    self.w[2 * pa] += wa * wa;
                }
                let rest = scaled[a + 1..].iter().zip(&self.places[a + 1..]);
                for (&(yb, wb), &pb) in rest {
                    let at = pa + pb;
                    // Doubled exactly: the pair (a, b) and the pair (b, a).
                    self.f[at] += 2.0 * ya.dot(&yb);
                    if rational {
                        self.w[at] += 2.0 * wa * wb;
                    }
                }
            }
        });
        for (x, inv) in self.f.iter_mut().zip(&self.inverses) {
            *x *= inv;
        }
        if rational {
            for (x, inv) in self.w.iter_mut().zip(&self.inverses) {
                *x *= inv;
            }
        }
        let gamma = ((p + 1) as f64 * (q + 1) as f64 + 12.0) * U * 1.01;
        self.f_error = 3.0 * gamma * y_max * y_max;
        self.f_max = self.f.iter().fold(0.0, |m, &x| m.max(x.abs()));
        if rational {
            self.w_error = gamma * w_max * w_max;
            self.w_max = self.w.iter().fold(0.0, |m, &x| m.max(x.abs()));
        } else {
            self.w_error = 0.0;
            self.w_max = 1.0;
        }
    }

    /// Forms `Φ = F̃ − ℓ′²·W̃` for the distance `limit ≥ 0` (see the module
    /// docs) and returns its least coefficient less the rounding bound: a
    /// positive value means `|S − P| > limit` on the whole exact piece.
    pub(super) fn set_limit(&mut self, limit: f64) -> f64 {
        let (e_y, e_w) = self.net_errors;
        let w_low = self.w_min - e_w;
        if w_low <= 0.0 || w_low.is_nan() {
            self.eta = f64::INFINITY;
            return f64::NEG_INFINITY;
        }
        // ℓ′ ≥ ℓ + (ℓ·e_w + √3·e_Y)/w̃: the net's own error moved into the
        // level (rounded up).
        let shifted = (limit + (limit * e_w + 1.7321 * e_y) / w_low) * (1.0 + 4.0 * U);
        let level = shifted * shifted * (1.0 + 2.0 * U);
        if self.rational {
            for ((phi, f), w) in self.phi.iter_mut().zip(&self.f).zip(&self.w) {
                *phi = f - level * w;
            }
        } else {
            for (phi, f) in self.phi.iter_mut().zip(&self.f) {
                *phi = f - level;
            }
        }
        self.eta = self.f_error
            + level * self.w_error
            + 2.0 * U * (level * self.w_max + self.f_max)
            + UNDERFLOW;
        let (least, magnitude) = self
            .phi
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(l, m), &x| {
                (l.min(x), m.max(x.abs()))
            });
        self.least = least;
        self.magnitude = magnitude;
        least - self.eta
    }

    /// A lower bound, rounding included, of `Φ` (as [`set_limit`] formed
    /// it) on the whole piece, the larger of its least coefficient and the
    /// second-order bound about `c ∈ [0, 1]²` (see the module docs):
    /// positive means `|S − P|` exceeds the limit on the whole exact piece.
    ///
    /// [`set_limit`]: Self::set_limit
    pub(super) fn lower_bound(&self, c: (f64, f64)) -> f64 {
        let (p, q) = self.degrees;
        let (big_p, big_q) = (2 * p, 2 * q);
        let cols = big_q + 1;
        let (least, magnitude, eta) = (self.least, self.magnitude, self.eta);
        if least - eta > 0.0 {
            return least - eta;
        }
        let phi = &self.phi;
        let at = |k: usize, l: usize| phi[k * cols + l];
        // Lower bounds of Φ_ss and Φ_tt, and the largest |Φ_st|.
        let mut a = 0.0_f64;
        if big_p >= 2 {
            a = f64::INFINITY;
            for k in 0..=big_p - 2 {
                for l in 0..=big_q {
                    a = a.min(at(k + 2, l) - 2.0 * at(k + 1, l) + at(k, l));
                }
            }
            a *= (big_p * (big_p - 1)) as f64;
        }
        let mut c_tt = 0.0_f64;
        if big_q >= 2 {
            c_tt = f64::INFINITY;
            for k in 0..=big_p {
                for l in 0..=big_q - 2 {
                    c_tt = c_tt.min(at(k, l + 2) - 2.0 * at(k, l + 1) + at(k, l));
                }
            }
            c_tt *= (big_q * (big_q - 1)) as f64;
        }
        let (mut b_lo, mut b_hi) = (0.0_f64, 0.0_f64);
        if big_p >= 1 && big_q >= 1 {
            (b_lo, b_hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..big_p {
                for l in 0..big_q {
                    let mixed = at(k + 1, l + 1) - at(k + 1, l) - at(k, l + 1) + at(k, l);
                    b_lo = b_lo.min(mixed);
                    b_hi = b_hi.max(mixed);
                }
            }
            let factor = (big_p * big_q) as f64;
            (b_lo, b_hi) = (b_lo * factor, b_hi * factor);
        }
        let jet = tensor_jet(phi, cols, c.0, c.1, 1);
        let (value, g) = (jet[0][0], [jet[1][0], jet[0][1]]);
        // The quadratic model's least value on each quadrant about c: where
        // d_s·d_t ≥ 0 the mixed term is at least b_lo·d_s·d_t, elsewhere at
        // least b_hi·d_s·d_t.
        let (s0, s1, t0, t1) = (-c.0, 1.0 - c.0, -c.1, 1.0 - c.1);
        let quadrants = [
            (b_lo, (0.0, s1), (0.0, t1)),
            (b_lo, (s0, 0.0), (t0, 0.0)),
            (b_hi, (0.0, s1), (t0, 0.0)),
            (b_hi, (s0, 0.0), (0.0, t1)),
        ];
        let taylor = value
            + quadrants
                .iter()
                .map(|&(b, ds, dt)| rectangle_min(g, [a, b, c_tt], ds, dt))
                .fold(f64::INFINITY, f64::min);
        let sides = (big_p + big_q + 2) as f64;
        let eval = 16.0 * U * magnitude * sides * sides;
        least.max(taylor) - eta - eval
    }
}

/// The least value of `g·d + ½·dᵀHd`, `H = [h₀ h₁; h₁ h₂]`, for `d` in
/// the rectangle `ds × dt`: at the interior critical point if `H` is
/// positive definite and it lies inside, else on a side (each side a
/// one-dimensional quadratic).
fn rectangle_min(g: [f64; 2], h: [f64; 3], ds: (f64, f64), dt: (f64, f64)) -> f64 {
    let q = |x: f64, y: f64| {
        g[0] * x + g[1] * y + 0.5 * (h[0] * x * x + 2.0 * h[1] * x * y + h[2] * y * y)
    };
    let mut least = f64::INFINITY;
    for x in [ds.0, ds.1] {
        // q(x, y) = const + (g₁ + h₁x)·y + ½h₂y².
        let base = g[0] * x + 0.5 * h[0] * x * x;
        least = least.min(base + quadratic_min(g[1] + h[1] * x, h[2], dt));
    }
    for y in [dt.0, dt.1] {
        let base = g[1] * y + 0.5 * h[2] * y * y;
        least = least.min(base + quadratic_min(g[0] + h[1] * y, h[0], ds));
    }
    let det = h[0] * h[2] - h[1] * h[1];
    if h[0] > 0.0 && det > 0.0 {
        let x = -(h[2] * g[0] - h[1] * g[1]) / det;
        let y = -(h[0] * g[1] - h[1] * g[0]) / det;
        if ds.0 <= x && x <= ds.1 && dt.0 <= y && y <= dt.1 {
            least = least.min(q(x, y));
        }
    }
    least
}

/// The least value of `g·d + ½μ·d²` for `d` in `[lo, hi]`.
fn quadratic_min(g: f64, mu: f64, (lo, hi): (f64, f64)) -> f64 {
    let q = |d: f64| g * d + 0.5 * mu * d * d;
    if mu > 0.0 {
        q((-g / mu).clamp(lo, hi))
    } else {
        q(lo).min(q(hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    /// The formed `F` and `W` agree with `|Y|²` and `w²` evaluated from the
    /// net, and the bound is below the sampled least value of `F − L·W`.
    #[test]
    fn form_matches_the_net_and_bounds_it() {
        let net: Vec<Homogeneous<3>> = (0..12)
            .map(|k| {
                let (i, j) = ((k / 4) as f64, (k % 4) as f64);
                let w = 1.0 + 0.3 * ((k * 7) % 5) as f64;
                Homogeneous::new(&Point3::new(i - 1.0, j * 0.7 - 1.0, (i * j).sin()), w)
            })
            .collect();
        let mut form = DistanceForm::new((2, 3));
        form.load(&net, true, (0.0, 0.0), 1.0);
        let level: f64 = 0.05;
        form.set_limit(level.sqrt());
        let bound = form.lower_bound((0.4, 0.6));
        let mut least = f64::INFINITY;
        for a in 0..=40 {
            for b in 0..=40 {
                let (s, t) = (a as f64 / 40.0, b as f64 / 40.0);
                let h = tensor_jet(&net, 4, s, t, 0)[0][0];
                let f = tensor_jet(&form.f, 7, s, t, 0)[0][0];
                let w = tensor_jet(&form.w, 7, s, t, 0)[0][0];
                assert!((f - h.wp.norm_squared()).abs() < 1e-12 * (1.0 + f));
                assert!((w - h.w * h.w).abs() < 1e-12 * (1.0 + w));
                least = least.min(f - level * w);
            }
        }
        assert!(bound <= least, "{bound} > {least}");
    }

    #[test]
    fn quadratic_min_cases() {
        assert_eq!(quadratic_min(1.0, 2.0, (-1.0, 1.0)), -0.25);
        assert_eq!(quadratic_min(1.0, 2.0, (0.0, 1.0)), 0.0);
        assert_eq!(quadratic_min(1.0, -2.0, (-1.0, 1.0)), -2.0);
    }
}

//! Exact real roots of polynomials with integer coefficients: references
//! computed without rounding, independent of the library.
//!
//! The Sturm sequence `p₀ = p`, `p₁ = p′`, `pᵢ₊₁ = −rem(pᵢ₋₁, pᵢ)` (each
//! remainder a pseudo-remainder scaled by positive factors and divided by
//! its positive content, which keeps the signs) counts the distinct real
//! roots in `(a, b]` as `V(a) − V(b)`, `V(x)` the number of sign changes of
//! `p₀(x), p₁(x), …` with zeros dropped (Sturm's theorem; e.g. Basu,
//! Pollack, Roy, *Algorithms in Real Algebraic Geometry*, §2.2). Its last
//! element is `gcd(p, p′)`; when that is not constant (a multiple root) the
//! sequence is divided by it, so that it is the Sturm sequence of the
//! square-free part. Points are `f64`s and exact midpoints of neighbouring
//! `f64`s, i.e. dyadic rationals `n/2ᵏ`; each sign is the sign of an
//! integer, computed exactly.
//!
//! A root in a window is bracketed by bisection between neighbouring `f64`s
//! and rounded to the nearer one by the sign count at their exact midpoint:
//! the result is the root correctly rounded (a tie may go either way).
//! Inputs given as `f64`s become integers scaled by a common power of two
//! ([`common_integers`]), so the polynomials of the closed forms have
//! integer coefficients and the same roots. The `f64` → dyadic rational
//! conversion and the integer gcd are those of
//! [`reference::exact`](crate::reference::exact), shared with the
//! revolution reference.

use crate::reference::exact::{common_exponent, dyadic, gcd};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// A polynomial with integer coefficients, in ascending powers.
pub type Poly = Vec<BigInt>;

/// The `f64`s as integers `nᵢ` scaled by one power of two (`vᵢ = nᵢ·2ᵉ`
/// exactly, the same `e` for all: [`common_exponent`]); `None` if one is
/// NaN or infinite.
pub fn common_integers(values: &[f64]) -> Option<Vec<BigInt>> {
    if !values.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(common_exponent(values).0)
}

/// `a·b`.
pub fn product(a: &[BigInt], b: &[BigInt]) -> Poly {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// `a + b`.
pub fn sum(a: &[BigInt], b: &[BigInt]) -> Poly {
    let mut out = vec![BigInt::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        out[i] += x;
    }
    for (i, y) in b.iter().enumerate() {
        out[i] += y;
    }
    out
}

/// `c·a`.
pub fn scaled(a: &[BigInt], c: &BigInt) -> Poly {
    a.iter().map(|x| x * c).collect()
}

/// Drops zero leading coefficients (the zero polynomial becomes empty).
fn trimmed<T: Zero>(mut a: Vec<T>) -> Vec<T> {
    while a.last().is_some_and(Zero::is_zero) {
        a.pop();
    }
    a
}

fn derivative(a: &[BigInt]) -> Poly {
    a.iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| c * BigInt::from(i))
        .collect()
}

/// `a` divided by the positive gcd of its coefficients.
fn primitive(a: Poly) -> Poly {
    let g = a.iter().fold(BigInt::zero(), |g, c| gcd(&g, c));
    if g.is_zero() || g.is_one() {
        return a;
    }
    a.into_iter().map(|c| c / &g).collect()
}

/// A positive multiple of the remainder of `a / b` (`b` trimmed, not
/// zero): `r ← |lc(b)|·r − sign(lc(b))·lc(r)·xˢ·b` until `deg r < deg b`.
fn pseudo_remainder(a: &[BigInt], b: &[BigInt]) -> Poly {
    let lead = b.last().expect("a non-zero divisor");
    let (size, sign) = (lead.abs(), lead.signum());
    let mut r = trimmed(a.to_vec());
    while r.len() >= b.len() {
        let shift = r.len() - b.len();
        let factor = r.last().expect("non-empty") * &sign;
        for c in r.iter_mut() {
            *c *= &size;
        }
        for (i, bi) in b.iter().enumerate() {
            r[shift + i] -= &factor * bi;
        }
        r.pop(); // its leading term is now exactly zero
        r = trimmed(r);
    }
    r
}

/// Exact rationals (for the rare division by a non-constant gcd).
type Q = BigRational;

/// The quotient of `a / b` over the rationals, `b` dividing `a`, times a
/// positive integer that clears its denominators.
fn exact_quotient(a: &[BigInt], b: &[BigInt]) -> Poly {
    let mut rem: Vec<Q> = a.iter().map(|c| Q::from_integer(c.clone())).collect();
    let b: Vec<Q> = b.iter().map(|c| Q::from_integer(c.clone())).collect();
    let lead = b.last().expect("a non-zero divisor").clone();
    let mut quot = vec![Q::zero(); (rem.len() + 1).saturating_sub(b.len())];
    while rem.len() >= b.len() {
        let shift = rem.len() - b.len();
        let c = rem.last().expect("non-empty") / &lead;
        for (i, bi) in b.iter().enumerate() {
            rem[shift + i] -= &c * bi;
        }
        quot[shift] = c;
        rem.pop();
        rem = trimmed(rem);
    }
    debug_assert!(rem.is_empty(), "not a divisor");
    // lcm of the denominators: m·(d/gcd(m, d)) is the reduced m/d's denominator times m.
    let mut m = BigInt::one();
    for c in &quot {
        m = &m * Q::new(m.clone(), c.denom().clone()).denom();
    }
    let m = Q::from_integer(m);
    primitive(quot.iter().map(|c| (c * &m).to_integer()).collect())
}

/// A dyadic rational `n / 2ᵏ`.
#[derive(Debug, Clone)]
struct Dyadic {
    n: BigInt,
    k: u64,
}

impl Dyadic {
    /// The exact value of a finite `f64` ([`dyadic`]: `m·2ᵉ`).
    fn of(v: f64) -> Self {
        let (m, e) = dyadic(v);
        if e >= 0 {
            Dyadic { n: m << e, k: 0 }
        } else {
            Dyadic {
                n: m,
                k: u64::from(e.unsigned_abs()),
            }
        }
    }

    /// `(a + b) / 2`, exactly.
    fn midpoint(a: &Dyadic, b: &Dyadic) -> Self {
        let k = a.k.max(b.k);
        Dyadic {
            n: (&a.n << (k - a.k)) + (&b.n << (k - b.k)),
            k: k + 1,
        }
    }
}

/// The sign (−1, 0, 1) of `Σ cᵢ xⁱ` at `x = n/2ᵏ`: that of the integer
/// `2^(k·deg) · p(x)`, by Horner's rule
/// `H ← H·n + cᵢ·2^(k(deg − i))`.
fn sign_at(c: &[BigInt], x: &Dyadic) -> i32 {
    let Some((top, rest)) = c.split_last() else {
        return 0;
    };
    let deg = rest.len() as u64;
    let mut h = top.clone();
    for (i, ci) in rest.iter().enumerate().rev() {
        h = h * &x.n + (ci << (x.k * (deg - i as u64)));
    }
    if h.is_zero() {
        0
    } else if h.is_positive() {
        1
    } else {
        -1
    }
}

/// The real roots of one polynomial: its square-free Sturm sequence.
#[derive(Debug, Clone)]
pub struct RealRoots {
    /// The Sturm sequence of the square-free part, with integer
    /// coefficients (each a positive multiple of the rational one).
    chain: Vec<Vec<BigInt>>,
    /// Every root lies in `(−bound, bound)` (Cauchy's bound, rounded up).
    bound: f64,
}

impl RealRoots {
    /// The roots of `Σ cᵢ tⁱ`; `None` for the zero polynomial (every `t`
    /// is a root).
    pub fn new(coefficients: &[BigInt]) -> Option<Self> {
        let p = primitive(trimmed(coefficients.to_vec()));
        if p.is_empty() {
            return None;
        }
        // Cauchy: every root is below 1 + max|cᵢ|/|c_n| < 1 + 2^(bits(max) − bits(c_n) + 1).
        let lead = p.last().expect("non-empty").bits() as i64;
        let largest = p.iter().map(BigInt::bits).max().expect("non-empty") as i64;
        let bound = 1.0 + 2f64.powi((largest - lead + 1).clamp(0, 1023) as i32);
        let mut chain = vec![p.clone(), primitive(derivative(&p))];
        if chain[1].is_empty() {
            chain.pop(); // a constant: no roots
        }
        while chain.len() >= 2 {
            let n = chain.len();
            let r = pseudo_remainder(&chain[n - 2], &chain[n - 1]);
            if r.is_empty() {
                break;
            }
            chain.push(primitive(r.iter().map(|c| -c).collect()));
        }
        // The last element is gcd(p, p′): divide it out of a multiple root.
        let g = chain.last().expect("non-empty").clone();
        if g.len() > 1 {
            chain = chain.iter().map(|q| exact_quotient(q, &g)).collect();
        }
        Some(RealRoots { chain, bound })
    }

    /// `V(x)`: sign changes along the Sturm sequence at `x`.
    fn variations(&self, x: &Dyadic) -> usize {
        let mut last = 0;
        let mut changes = 0;
        for p in &self.chain {
            let s = sign_at(p, x);
            if s != 0 {
                if last != 0 && s != last {
                    changes += 1;
                }
                last = s;
            }
        }
        changes
    }

    /// Whether `x` is a root.
    fn is_root(&self, x: &Dyadic) -> bool {
        sign_at(&self.chain[0], x) == 0
    }

    /// The number of distinct real roots in `(a, b]`.
    pub fn count(&self, a: f64, b: f64) -> usize {
        // Every root lies within the bound (NaN ends become the bound).
        let (a, b) = (a.max(-self.bound), b.min(self.bound));
        if a >= b {
            return 0;
        }
        self.variations(&Dyadic::of(a))
            .saturating_sub(self.variations(&Dyadic::of(b)))
    }

    /// The smallest root `r` with `t_min < r < t_max`, correctly rounded,
    /// and the neighbouring `f64`s `(lo, hi)` with `lo < r ≤ hi` it was
    /// found between.
    fn first_bracket(&self, t_min: f64, t_max: f64) -> Option<(f64, (f64, f64))> {
        let (mut lo, mut hi) = (t_min.max(-self.bound), t_max.min(self.bound));
        if lo >= hi {
            return None;
        }
        let (dlo, dhi) = (Dyadic::of(lo), Dyadic::of(hi));
        let (mut v_lo, v_hi) = (self.variations(&dlo), self.variations(&dhi));
        // A root at t_max itself is outside the open window.
        let at_end = usize::from(hi == t_max && self.is_root(&dhi));
        if v_lo.saturating_sub(v_hi) <= at_end {
            return None;
        }
        // Invariant: a root in (lo, hi), or at hi when hi < t_max.
        loop {
            let mid = if (hi - lo).is_finite() {
                lo + 0.5 * (hi - lo)
            } else {
                0.5 * lo + 0.5 * hi
            };
            if !(lo < mid && mid < hi) {
                break;
            }
            let v_mid = self.variations(&Dyadic::of(mid));
            if v_lo > v_mid {
                hi = mid;
            } else {
                lo = mid;
                v_lo = v_mid;
            }
        }
        // The smallest root is in (lo, hi]: the nearer end is lo iff it is
        // at or below the exact midpoint.
        let m = Dyadic::midpoint(&Dyadic::of(lo), &Dyadic::of(hi));
        let t = if v_lo > self.variations(&m) { lo } else { hi };
        Some((t, (lo, hi)))
    }

    /// The smallest root in the open window `(t_min, t_max)`, rounded to the
    /// nearest `f64` (which may equal `t_min` or `t_max` when the root is
    /// within half an ulp of them); `None` when there is none.
    pub fn first_in(&self, t_min: f64, t_max: f64) -> Option<f64> {
        self.first_bracket(t_min, t_max).map(|(t, _)| t)
    }

    /// Every distinct root in `(t_min, t_max)`, ascending, each rounded to
    /// the nearest `f64` (roots closer together than an ulp count once).
    pub fn all_in(&self, t_min: f64, t_max: f64) -> Vec<f64> {
        let mut out = Vec::new();
        let mut from = t_min;
        while let Some((t, (_, hi))) = self.first_bracket(from, t_max) {
            out.push(t);
            from = hi;
        }
        out
    }
}

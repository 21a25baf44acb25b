//! The profile as exact Bézier spans, and the per-span polynomials a ray
//! combines into its hit polynomial.
//!
//! A B-spline's span `[t_j, t_{j+1}]` (degree `p`) has the Bézier points
//! `b_i = blossom(t_j, …, t_j, t_{j+1}, …, t_{j+1})` (`p − i` copies of
//! `t_j`, `i` of `t_{j+1}`); the blossom is de Boor's recurrence with one
//! argument per level. Everything here is exact rational arithmetic on the
//! input `f64`s read as the dyadic rationals they are.
//!
//! Products of Bernstein polynomials of degree `p`:
//! `(Σ a_i B_i^p)(Σ b_j B_j^p) = Σ_k B_k^{2p} Σ_{i+j=k} C(p,i)C(p,j)/C(2p,k) a_i b_j`,
//! and with `b ≡ 1` this is degree elevation from `p` to `2p`.

use crate::reference::exact::{Frac, lcm};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use revolve::nalgebra::Point2;

type Q = BigRational;

/// One Bézier span of the profile, with the integer forms the search uses.
pub struct Span {
    /// Global parameter interval: `u = a + (b − a)·s`, `s ∈ [0, 1]`.
    pub a: Frac,
    pub b: Frac,
    /// Bézier control points `(x, y)`, exact.
    pub pts: Vec<(Q, Q)>,
    /// `y = yc[i] / ly`: the degree-`p` Bernstein coefficients of `y`.
    pub yc: Vec<BigInt>,
    pub ly: BigInt,
    /// Degree-`2p` Bernstein coefficients over one denominator `L = one`:
    /// `y1 = L·y`, `y2 = L·y²`, `x2 = L·x²`.
    pub one: BigInt,
    pub y1: Vec<BigInt>,
    pub y2: Vec<BigInt>,
    pub x2: Vec<BigInt>,
}

fn q_of(v: f64) -> Q {
    let f = Frac::from_f64(v);
    Q::new(f.num, f.den)
}

fn binom(n: usize, k: usize) -> BigInt {
    (0..k).fold(BigInt::one(), |c, i| c * (n - i) / (i + 1))
}

/// The product of two degree-`p` Bernstein polynomials, degree `2p`.
fn product(a: &[Q], b: &[Q]) -> Vec<Q> {
    let p = a.len() - 1;
    let bp: Vec<BigInt> = (0..=p).map(|i| binom(p, i)).collect();
    (0..=2 * p)
        .map(|k| {
            let mut sum = Q::zero();
            for i in k.saturating_sub(p)..=k.min(p) {
                let w = Q::from_integer(&bp[i] * &bp[k - i]);
                sum += w * &a[i] * &b[k - i];
            }
            sum / Q::from_integer(binom(2 * p, k))
        })
        .collect()
}

/// `v` over a common denominator: `(L·v_i, L)`.
fn integers(v: &[Q]) -> (Vec<BigInt>, BigInt) {
    let l = lcm(v.iter().map(|q| q.denom()));
    let ints = v.iter().map(|q| q.numer() * (&l / q.denom())).collect();
    (ints, l)
}

impl Span {
    /// The span with Bézier points `pts` (at least two) on `[a, b]`.
    fn new(pts: Vec<(Q, Q)>, a: Frac, b: Frac) -> Span {
        let xs: Vec<Q> = pts.iter().map(|(x, _)| x.clone()).collect();
        let ys: Vec<Q> = pts.iter().map(|(_, y)| y.clone()).collect();
        let ones = vec![Q::one(); pts.len()];
        let (yc, ly) = integers(&ys);
        let mut all = product(&ys, &ones);
        all.extend(product(&ys, &ys));
        all.extend(product(&xs, &xs));
        let (ints, one) = integers(&all);
        let m = 2 * pts.len() - 1; // 2p + 1 coefficients
        Span {
            a,
            b,
            pts,
            yc,
            ly,
            one,
            y1: ints[..m].to_vec(),
            y2: ints[m..2 * m].to_vec(),
            x2: ints[2 * m..].to_vec(),
        }
    }

    /// Whether `next` starts exactly where this span ends (same parameter
    /// and same point), so a root there belongs to one of them only.
    pub fn joins(&self, next: &Span) -> bool {
        self.b == next.a && self.pts.last() == next.pts.first()
    }

    /// The exact point at local parameter `s` (de Casteljau), for tests.
    pub fn eval(&self, s: &Q) -> (Q, Q) {
        let mut c = self.pts.clone();
        let r = Q::one() - s;
        for lvl in 1..c.len() {
            for i in 0..c.len() - lvl {
                c[i] = (
                    &r * &c[i].0 + s * &c[i + 1].0,
                    &r * &c[i].1 + s * &c[i + 1].1,
                );
            }
        }
        c[0].clone()
    }
}

fn finite(points: &[Point2<f64>]) -> bool {
    points.iter().all(|p| p.x.is_finite() && p.y.is_finite())
}

/// The one span of a Bézier profile (degree ≥ 1, finite points), on `[0, 1]`.
pub fn bezier(points: &[Point2<f64>]) -> Option<Vec<Span>> {
    if points.len() < 2 || !finite(points) {
        return None;
    }
    let pts = points.iter().map(|p| (q_of(p.x), q_of(p.y))).collect();
    Some(vec![Span::new(
        pts,
        Frac::from_int(BigInt::zero()),
        Frac::from_int(BigInt::one()),
    )])
}

/// The spans of the B-spline's non-empty knot intervals in its domain
/// `[t_p, t_n]`, or `None` for invalid input (degree 0, too few points,
/// wrong knot count, decreasing or non-finite knots, empty domain).
pub fn bspline(p: usize, knots: &[f64], points: &[Point2<f64>]) -> Option<Vec<Span>> {
    let n = points.len();
    let valid = p >= 1
        && n > p
        && knots.len() == n + p + 1
        && finite(points)
        && knots.iter().all(|k| k.is_finite())
        && knots.windows(2).all(|w| w[0] <= w[1])
        && knots[p] < knots[n];
    if !valid {
        return None;
    }
    let t: Vec<Q> = knots.iter().map(|&k| q_of(k)).collect();
    let pts: Vec<(Q, Q)> = points.iter().map(|p| (q_of(p.x), q_of(p.y))).collect();
    let mut spans = Vec::new();
    for j in p..n {
        if knots[j] == knots[j + 1] {
            continue;
        }
        let bez = (0..=p)
            .map(|i| {
                let args: Vec<&Q> = (0..p)
                    .map(|r| if r < i { &t[j + 1] } else { &t[j] })
                    .collect();
                blossom(p, &t, &pts, j, &args)
            })
            .collect();
        spans.push(Span::new(
            bez,
            Frac::from_f64(knots[j]),
            Frac::from_f64(knots[j + 1]),
        ));
    }
    Some(spans)
}

/// The blossom of the polynomial piece on `[t_j, t_{j+1}]` at `args`
/// (`p` values). The denominators `t_{k+p+1−r} − t_k` are positive because
/// `t_k ≤ t_j < t_{j+1} ≤ t_{k+p+1−r}` for the `k` used.
fn blossom(p: usize, t: &[Q], pts: &[(Q, Q)], j: usize, args: &[&Q]) -> (Q, Q) {
    let mut d: Vec<(Q, Q)> = pts[j - p..=j].to_vec();
    for (r, &x) in (1..=p).zip(args) {
        for k in (j - p + r..=j).rev() {
            let i = k + p - j;
            let alpha = (x - &t[k]) / (&t[k + p + 1 - r] - &t[k]);
            let beta = Q::one() - &alpha;
            d[i] = (
                &beta * &d[i - 1].0 + &alpha * &d[i].0,
                &beta * &d[i - 1].1 + &alpha * &d[i].1,
            );
        }
    }
    d[p].clone()
}

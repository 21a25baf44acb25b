//! The root search on each span's hit polynomial `f(s)`, `s ∈ [0, 1]`, and
//! the choice of the nearest root.
//!
//! - Isolation: Descartes' rule in the Bernstein basis — the number of roots
//!   in the open interval is at most the sign variations `V` of the
//!   coefficients, with the same parity — so `V = 0`: none, `V = 1`: exactly
//!   one, and it is simple. Halving is exact de Casteljau on integers (the
//!   halves' coefficients times `2^n`), so every endpoint is dyadic and a
//!   root exactly at one is seen as a zero coefficient. Pieces whose `t`
//!   range lies outside the window are dropped. A piece still with `V ≥ 2`
//!   at width `2^-100` is a multiple root or a cluster: unsure.
//! - Refinement: bisection by the sign at the midpoint, carrying the
//!   Bernstein coefficients of `y` along so that the hull of them bounds
//!   `y`, hence `t = (y − o_y)/d_y`, over the piece. It stops when the piece
//!   is narrower than `2^-64` (for `u`) and `[t_lo, t_hi]` is inside the
//!   window and either rounds to one `f64` or is narrower than
//!   `2^-70·(1 + |t|)`.

use super::ray::RayData;
use super::spans::Span;
use crate::reference::exact::Frac;
use num_bigint::{BigInt, Sign};
use num_traits::{One, Zero};

/// Isolation gives up on pieces of width `2^-ISOLATION_DEPTH`.
const ISOLATION_DEPTH: u64 = 100;
/// Refinement checks `t` from this depth on (the piece then fixes `u`).
const MIN_DEPTH: u64 = 64;
/// Refinement gives up (unsure) at this depth.
const MAX_DEPTH: u64 = 400;

/// A piece `[k/2^depth, (k+1)/2^depth]` of a span with the Bernstein
/// coefficients of positive multiples of `f` and of `y` on it; `y` is
/// `yc/(ly·2^(p·depth))`.
pub struct Piece {
    f: Vec<BigInt>,
    y: Vec<BigInt>,
    depth: u64,
    k: BigInt,
}

/// A root (or possible root) of the hit polynomial with `t` bounds.
pub enum Cand {
    /// One simple root inside a piece of span `span`, `t ≥ tl`.
    Pending { piece: Piece, span: usize, tl: Frac },
    /// A certified root with `t ∈ [tl, th]` strictly inside the window.
    Hit { tl: Frac, th: Frac, t: f64, u: f64 },
    /// Something at `t ≥ tl` that can't be certified.
    Unsure { tl: Frac },
}

impl Cand {
    fn tl(&self) -> &Frac {
        match self {
            Cand::Pending { tl, .. } | Cand::Hit { tl, .. } | Cand::Unsure { tl } => tl,
        }
    }
}

/// What the search concludes.
pub enum Found {
    Hit { t: f64, u: f64 },
    Miss,
    Unsure,
}

/// Sign variations, zeros skipped.
fn variations(c: &[BigInt]) -> usize {
    let mut last = Sign::NoSign;
    let mut v = 0;
    for s in c.iter().map(BigInt::sign).filter(|&s| s != Sign::NoSign) {
        if last != Sign::NoSign && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// In place: the coefficients of the left half, times `2^n`.
fn left_half(c: &mut [BigInt]) {
    let n = c.len() - 1;
    for r in 1..=n {
        for i in (r..=n).rev() {
            let (lo, hi) = c.split_at_mut(i);
            hi[0] += &lo[i - 1];
        }
    }
    for (i, x) in c.iter_mut().enumerate() {
        *x <<= n - i;
    }
}

/// In place: the coefficients of the right half, times `2^n`.
fn right_half(c: &mut [BigInt]) {
    let n = c.len() - 1;
    for r in 1..=n {
        for i in 0..=n - r {
            let (lo, hi) = c.split_at_mut(i + 1);
            lo[i] += &hi[0];
        }
    }
    for (i, x) in c.iter_mut().enumerate() {
        *x <<= i;
    }
}

/// The global parameter `a + (b − a)·k/2^depth`, rounded.
fn u_at(span: &Span, k: &BigInt, depth: u64) -> f64 {
    let s = Frac::new(k.clone(), BigInt::one() << depth);
    span.a.add(&span.b.sub(&span.a).mul(&s)).to_f64()
}

/// A root exactly at `s = k/2^depth` where `y = yc/(ly·2^shift)`.
fn exact(
    span: &Span,
    ray: &RayData,
    yc: &BigInt,
    shift: u64,
    k: &BigInt,
    depth: u64,
) -> Option<Cand> {
    let t = ray.t_at(yc, &span.ly, shift);
    ray.inside(&t, &t).then(|| Cand::Hit {
        t: t.to_f64(),
        u: u_at(span, k, depth),
        th: t.clone(),
        tl: t,
    })
}

/// Every root of every span's `f` that may lie in the window, isolated.
/// A root at a span's end shared with the next span is the next span's.
pub fn candidates(spans: &[Span], ray: &RayData) -> Vec<Cand> {
    let mut out = Vec::new();
    for (j, span) in spans.iter().enumerate() {
        let p = span.yc.len() as u64 - 1;
        let (tl, th) = ray.t_hull(&span.yc, &span.ly, 0);
        if ray.before(&th) || ray.after(&tl) {
            continue;
        }
        let f = ray.poly(span);
        if f.iter().all(Zero::is_zero) {
            // The whole span lies on the ray's cone of circles.
            out.push(Cand::Unsure { tl });
            continue;
        }
        let n = f.len() - 1;
        if f[0].is_zero() {
            out.extend(exact(span, ray, &span.yc[0], 0, &BigInt::zero(), 0));
        }
        let shared = spans.get(j + 1).is_some_and(|next| span.joins(next));
        if f[n].is_zero() && !shared {
            out.extend(exact(span, ray, &span.yc[p as usize], 0, &BigInt::one(), 0));
        }
        let mut stack = vec![Piece {
            f,
            y: span.yc.clone(),
            depth: 0,
            k: BigInt::zero(),
        }];
        while let Some(pc) = stack.pop() {
            let v = variations(&pc.f);
            if v == 0 {
                continue;
            }
            let (tl, th) = ray.t_hull(&pc.y, &span.ly, p * pc.depth);
            if ray.before(&th) || ray.after(&tl) {
                continue;
            }
            if v == 1 {
                out.push(Cand::Pending {
                    piece: pc,
                    span: j,
                    tl,
                });
                continue;
            }
            if pc.depth >= ISOLATION_DEPTH {
                out.push(Cand::Unsure { tl });
                continue;
            }
            let (mut lf, mut rf) = (pc.f.clone(), pc.f);
            let (mut ly, mut ry) = (pc.y.clone(), pc.y);
            left_half(&mut lf);
            right_half(&mut rf);
            left_half(&mut ly);
            right_half(&mut ry);
            let (depth, k2) = (pc.depth + 1, pc.k << 1u32);
            if rf[0].is_zero() {
                let km = &k2 + 1u32;
                out.extend(exact(span, ray, &ry[0], p * depth, &km, depth));
            }
            stack.push(Piece {
                f: lf,
                y: ly,
                depth,
                k: k2.clone(),
            });
            stack.push(Piece {
                f: rf,
                y: ry,
                depth,
                k: k2 + 1u32,
            });
        }
    }
    out
}

/// `th − tl ≤ 2^-70·(1 + min(|tl|, |th|))`.
fn narrow(tl: &Frac, th: &Frac) -> bool {
    let small = tl.abs().min(th.abs());
    let one = Frac::from_int(BigInt::one());
    th.sub(tl).mul_pow2(70) <= one.add(&small)
}

/// Bisects a piece with exactly one simple root until its `t` is certified
/// (a hit), proven outside the window (`None`), or `MAX_DEPTH` (unsure).
fn refine(span: &Span, ray: &RayData, piece: Piece) -> Option<Cand> {
    let Piece {
        mut f,
        mut y,
        mut depth,
        mut k,
    } = piece;
    let (n, p) = (f.len() - 1, y.len() as u64 - 1);
    // The sign of f just right of the piece's left end: its first nonzero
    // coefficient's. The root is simple and alone, so f has this sign left
    // of it and the opposite sign right of it.
    let left = f.iter().map(BigInt::sign).find(|&s| s != Sign::NoSign)?;
    let mut spare = f.clone();
    loop {
        if depth >= MAX_DEPTH {
            let (tl, _) = ray.t_hull(&y, &span.ly, p * depth);
            return Some(Cand::Unsure { tl });
        }
        for (s, x) in spare.iter_mut().zip(&f) {
            s.clone_from(x);
        }
        left_half(&mut f);
        let mid = f[n].sign();
        depth += 1;
        k <<= 1u32;
        if mid == Sign::NoSign {
            left_half(&mut y);
            k += 1u32;
            return exact(span, ray, &y[p as usize], p * depth, &k, depth);
        }
        if mid == left {
            right_half(&mut spare);
            std::mem::swap(&mut f, &mut spare);
            right_half(&mut y);
            k += 1u32;
        } else {
            left_half(&mut y);
        }
        if depth < MIN_DEPTH {
            continue;
        }
        let (tl, th) = ray.t_hull(&y, &span.ly, p * depth);
        if ray.before(&th) || ray.after(&tl) {
            return None;
        }
        if !ray.inside(&tl, &th) {
            continue; // straddles t_min or t_max: refine further
        }
        let (a, b) = (tl.to_f64(), th.to_f64());
        let t = if a == b {
            a
        } else if narrow(&tl, &th) {
            tl.add(&th)
                .mul(&Frac::new(BigInt::one(), BigInt::from(2)))
                .to_f64()
        } else {
            continue;
        };
        let u = u_at(span, &((&k << 1u32) + 1u32), depth + 1);
        return Some(Cand::Hit { tl, th, t, u });
    }
}

/// The nearest root in the window: refine candidates in order of their
/// lower `t` bound until the first is a certified hit that no other
/// candidate can precede or tie.
pub fn nearest(spans: &[Span], ray: &RayData) -> Found {
    let mut cands = candidates(spans, ray);
    loop {
        let Some(i) = (0..cands.len()).min_by(|&a, &b| cands[a].tl().cmp(cands[b].tl())) else {
            return Found::Miss;
        };
        let j = match &cands[i] {
            Cand::Unsure { .. } => return Found::Unsure,
            Cand::Pending { .. } => i,
            Cand::Hit { th, t, u, .. } => {
                let rival = (0..cands.len()).find(|&j| j != i && cands[j].tl() <= th);
                match rival {
                    None => return Found::Hit { t: *t, u: *u },
                    Some(j) if matches!(cands[j], Cand::Pending { .. }) => j,
                    Some(_) => return Found::Unsure,
                }
            }
        };
        if let Cand::Pending { piece, span, .. } = cands.swap_remove(j) {
            cands.extend(refine(&spans[span], ray, piece));
        }
    }
}

/// Every certified root `(t, u)` in the window, ascending in `t`, for
/// tests; `None` if one is unsure.
pub fn all_roots(spans: &[Span], ray: &RayData) -> Option<Vec<(f64, f64)>> {
    let mut roots = Vec::new();
    for c in candidates(spans, ray) {
        let c = match c {
            Cand::Pending { piece, span, .. } => refine(&spans[span], ray, piece),
            c => Some(c),
        };
        match c {
            Some(Cand::Hit { t, u, .. }) => roots.push((t, u)),
            Some(_) => return None,
            None => {}
        }
    }
    roots.sort_by(|a, b| a.0.total_cmp(&b.0));
    Some(roots)
}

//! Real roots of a Bernstein-form polynomial on `[0, 1]`, none missed.
//!
//! The polynomial `f(u) = Σ cᵢ Bᵢⁿ(u)` is given with an absolute error bound
//! `e` on its coefficients (they usually come out of floating-point
//! arithmetic). The search subdivides `[0, 1]` by de Casteljau and decides each
//! piece with two facts about Bernstein form (Farin, ch. 5; Lane & Riesenfeld
//! 1981):
//!
//! - the graph lies in the convex hull of the control values: if every
//!   coefficient is certainly positive (`cᵢ > e`) or certainly negative, there
//!   is no root;
//! - if the derivative's coefficients `n(cᵢ₊₁ − cᵢ)` are certainly of one sign,
//!   `f` is monotonic: there is one root when the end values certainly differ
//!   in sign, none when they certainly agree, and otherwise (an end value
//!   within the error of zero) a root "within the noise" at that end, which is
//!   reported so that a grazing contact is never lost.
//!
//! Everything else is split at its midpoint. A monotonic piece with a sign
//! change is refined by safeguarded Newton iteration (bisection whenever a
//! Newton step leaves the bracket) to full double precision. Pieces narrower
//! than `2⁻ᴹᴬˣ` that still cannot be decided are reported as roots at their
//! midpoint; where every coefficient is within the error of zero the
//! polynomial vanishes identically on the piece and the whole piece is
//! reported ([`Root::Flat`]).
//!
//! The error bound grows with each subdivision level by the rounding of one
//! convex combination (`2ε·max|cᵢ|`), so the sign tests stay conservative: a
//! root can be reported that exact arithmetic would refute (the caller
//! verifies), but none is missed.

use crate::bernstein::{eval_with_derivative, subdivide};
use crate::scratch::with_scratch;

/// Deepest subdivision: pieces of width `2⁻⁴⁸` (about `3.6e-15`) are not split.
const MAX_DEPTH: u32 = 48;

/// One root (or zero set) found by [`find_roots`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Root {
    /// A root at `u` (isolated and refined to double precision, or a
    /// double/near root within the coefficient error).
    At(f64),
    /// The polynomial is zero within its error bound on all of `[from, to]`.
    Flat {
        /// Start of the interval.
        from: f64,
        /// End of the interval.
        to: f64,
    },
}

/// Finds every root in `[0, 1]` of the polynomial with Bernstein
/// coefficients `coeffs`, each known to within `error` (absolute), and calls
/// `found` with them in increasing order. A root found from both sides of a
/// subdivision point is reported once; touching [`Root::Flat`] intervals are
/// merged.
///
/// No allocation for up to 102 coefficients. An empty slice has no roots.
///
/// ```
/// use revolve::roots::{Root, find_roots};
/// // (u − 0.25)(u − 0.75) in the quadratic Bernstein basis: coefficients
/// // f(0) = 3/16, the control value −5/16 + …, f(1) = 3/16.
/// let c = [0.1875, -0.3125, 0.1875];
/// let mut roots = Vec::new();
/// find_roots(&c, 0.0, |r| roots.push(r));
/// assert_eq!(roots.len(), 2);
/// assert!(matches!(roots[0], Root::At(u) if (u - 0.25).abs() < 1e-15));
/// assert!(matches!(roots[1], Root::At(u) if (u - 0.75).abs() < 1e-15));
/// ```
pub fn find_roots(coeffs: &[f64], error: f64, found: impl FnMut(Root)) {
    find_roots_to(coeffs, error, 0.0, found);
}

/// As [`find_roots`], but pieces narrower than `width` that cannot be decided
/// are reported as [`Root::At`] their midpoint instead of being split further
/// (they hold one root, a cluster of roots, or a near-root within the
/// coefficient error). Callers that polish candidates with Newton's method
/// use this to bound the work near double roots. `width ≤ 2⁻⁴⁸` is the same as
/// [`find_roots`].
pub fn find_roots_to(coeffs: &[f64], error: f64, width: f64, mut found: impl FnMut(Root)) {
    if coeffs.is_empty() {
        return;
    }
    let scale = coeffs.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    let search = Search {
        error: error.max(0.0),
        growth: 2.0 * f64::EPSILON * scale,
        width,
    };
    let mut pending: Option<Root> = None;
    search.piece(coeffs, 0.0, 1.0, 0, &mut |root| {
        pending = match (pending, root) {
            (None, r) => Some(r),
            // The same root seen from both sides of a split point.
            (Some(Root::At(last)), Root::At(u)) if u - last <= 4.0 * f64::EPSILON => pending,
            // Adjacent (or root-touching) zero intervals merge.
            (Some(Root::Flat { from, to }), Root::Flat { from: f2, to: t2 }) if f2 <= to => {
                Some(Root::Flat {
                    from,
                    to: t2.max(to),
                })
            }
            (Some(Root::Flat { from, to }), Root::At(u)) if u <= to => {
                Some(Root::Flat { from, to })
            }
            (Some(Root::At(last)), Root::Flat { from, to }) if from <= last => {
                Some(Root::Flat { from, to })
            }
            (Some(prev), r) => {
                found(prev);
                Some(r)
            }
        };
    });
    if let Some(r) = pending {
        found(r);
    }
}

/// The fixed parameters of one search.
struct Search {
    /// Absolute error of the input coefficients.
    error: f64,
    /// Added to the error at each subdivision level.
    growth: f64,
    /// Undecided pieces narrower than this are reported, not split.
    width: f64,
}

/// How the coefficients sit relative to zero, given their error.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Signs {
    /// All certainly positive, or all certainly negative.
    Definite,
    /// All within the error of zero.
    Zero,
    /// Anything else.
    Mixed,
}

fn classify(c: &[f64], e: f64) -> Signs {
    let (lo, hi) = c
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    if lo > e || hi < -e {
        Signs::Definite
    } else if lo >= -e && hi <= e {
        Signs::Zero
    } else {
        Signs::Mixed
    }
}

/// The sign of `x` if it is certain at error `e`, else 0.
fn certain_sign(x: f64, e: f64) -> i8 {
    if x > e {
        1
    } else if x < -e {
        -1
    } else {
        0
    }
}

impl Search {
    fn piece(&self, c: &[f64], a: f64, b: f64, depth: u32, found: &mut dyn FnMut(Root)) {
        let e = self.error + self.growth * f64::from(depth + 1);
        match classify(c, e) {
            Signs::Definite => return,
            Signs::Zero => return found(Root::Flat { from: a, to: b }),
            Signs::Mixed => {}
        }
        let n = c.len() - 1;
        if self.monotonic(c, e) {
            let (f0, f1) = (c[0], c[n]);
            match (certain_sign(f0, e), certain_sign(f1, e)) {
                (s0, s1) if s0 * s1 < 0 => found(Root::At(refine(c, a, b))),
                (s0, s1) if s0 * s1 > 0 => {}
                // An end value within the noise: the root is there (or the
                // curve only grazes zero); report the end nearer to zero.
                _ => found(Root::At(if f0.abs() <= f1.abs() { a } else { b })),
            }
            return;
        }
        if depth >= MAX_DEPTH || b - a < self.width {
            return found(Root::At(0.5 * (a + b)));
        }
        let mid = 0.5 * (a + b);
        with_scratch(2 * c.len(), 0.0, |buf| {
            let (left, right) = buf.split_at_mut(c.len());
            subdivide(c, 0.5, left, right);
            self.piece(left, a, mid, depth + 1, found);
            self.piece(right, mid, b, depth + 1, found);
        });
    }

    /// Whether the derivative's coefficients `n(cᵢ₊₁ − cᵢ)` certainly share
    /// one sign (each difference is known to within `2e`).
    fn monotonic(&self, c: &[f64], e: f64) -> bool {
        let (lo, hi) = c
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
        let tol = 2.0 * e;
        lo > tol || hi < -tol
    }
}

/// The root of the monotonic polynomial piece `c` on `[a, b]`, whose end
/// values have opposite signs: safeguarded Newton on the local parameter,
/// falling back to bisection whenever a step leaves the bracket or stalls.
fn refine(c: &[f64], a: f64, b: f64) -> f64 {
    let n = c.len() - 1;
    let rising = c[n] > c[0];
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let resolution = 2.0 * f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
    // Start from the chord's zero: exact for a linear piece.
    let mut s = (c[0] / (c[0] - c[n])).clamp(0.0, 1.0);
    for _ in 0..64 {
        let Some((f, df)) = eval_with_derivative(c, s) else {
            break;
        };
        if f == 0.0 {
            lo = s;
            hi = s;
            break;
        }
        if (f > 0.0) == rising {
            hi = s;
        } else {
            lo = s;
        }
        let newton = s - f / df;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        // Done once the step no longer changes the root in the caller's
        // parameter u = a + (b − a)s (a Newton step near the root also
        // bounds the remaining error), or the bracket has collapsed.
        let step = (b - a) * (next - s).abs();
        s = next;
        if step <= resolution || hi - lo <= f64::EPSILON {
            break;
        }
    }
    let s = s.clamp(lo, hi);
    a + (b - a) * s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bernstein coefficients of `Πᵢ (u − rᵢ)` (exactly, by multiplying the
    /// linear factors `(u − r) = −r·B₀¹ + (1 − r)·B₁¹` and degree-raising).
    fn from_roots(roots: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in roots {
            let (l0, l1) = (-r, 1.0 - r);
            let m = c.len() - 1; // current degree
            let mut next = vec![0.0; m + 2];
            // Product of degree m and degree 1 Bernstein forms (degree m + 1):
            // coefficient k = [C(m,k)·C(1,0)·c_k·l0 + C(m,k−1)·C(1,1)·c_{k−1}·l1] / C(m+1,k).
            for (k, slot) in next.iter_mut().enumerate() {
                let bin = |n: usize, i: usize| crate::bernstein::binomial(n, i);
                let mut acc = 0.0;
                if k <= m {
                    acc += bin(m, k) * c[k] * l0;
                }
                if k >= 1 {
                    acc += bin(m, k - 1) * c[k - 1] * l1;
                }
                *slot = acc / bin(m + 1, k);
            }
            c = next;
        }
        c
    }

    fn roots_of(c: &[f64], error: f64) -> Vec<Root> {
        let mut v = Vec::new();
        find_roots(c, error, |r| v.push(r));
        v
    }

    /// The reports as intervals (a root `u` is `[u, u]`).
    fn intervals(r: &[Root]) -> Vec<(f64, f64)> {
        r.iter()
            .map(|r| match *r {
                Root::At(u) => (u, u),
                Root::Flat { from, to } => (from, to),
            })
            .collect()
    }

    /// Every true root lies within `tol` of a report, and every report within
    /// `tol` of a true root.
    fn assert_matches(got: &[(f64, f64)], want: &[f64], tol: f64) {
        let dist = |(lo, hi): (f64, f64), x: f64| (lo - x).max(x - hi).max(0.0);
        for &w in want {
            assert!(
                got.iter().any(|&g| dist(g, w) <= tol),
                "missed {w}: {got:?}"
            );
        }
        for &g in got {
            assert!(want.iter().any(|&w| dist(g, w) <= tol), "false root {g:?}");
        }
    }

    #[test]
    fn finds_simple_roots_to_full_precision() {
        let want = [0.1, 0.37, 0.5, 0.82, 0.99];
        let got = intervals(&roots_of(&from_roots(&want), 1e-16));
        assert_eq!(got.len(), want.len(), "{got:?}");
        assert_matches(&got, &want, 1e-14);
    }

    #[test]
    fn roots_at_the_ends_and_none_outside() {
        let got = intervals(&roots_of(&from_roots(&[0.0, 1.0]), 1e-16));
        assert_matches(&got, &[0.0, 1.0], 1e-15);
        // Roots at −0.5 and 1.5 are outside: none reported.
        assert!(roots_of(&from_roots(&[-0.5, 1.5]), 1e-16).is_empty());
    }

    #[test]
    fn double_root_is_not_missed() {
        // (u − 0.3)² touches zero without a sign change.
        let c = from_roots(&[0.3, 0.3]);
        let got = intervals(&roots_of(&c, 1e-16));
        assert!(!got.is_empty());
        assert_matches(&got, &[0.3], 1e-7);
        // Lifted by 1e-6 it no longer touches: no root.
        let lifted: Vec<f64> = c.iter().map(|x| x + 1e-6).collect();
        assert!(roots_of(&lifted, 1e-16).is_empty());
    }

    #[test]
    fn zero_polynomial_is_flat() {
        assert_eq!(
            roots_of(&[0.0, 1e-18, -1e-18], 1e-16),
            vec![Root::Flat { from: 0.0, to: 1.0 }]
        );
    }

    #[test]
    fn close_roots_of_higher_degree() {
        let want = [0.3, 0.35, 0.4, 0.45, 0.5, 0.9];
        let got = intervals(&roots_of(&from_roots(&want), 0.0));
        assert_eq!(got.len(), want.len(), "{got:?}");
        assert_matches(&got, &want, 1e-12);
    }

    #[test]
    fn roots_on_subdivision_points_are_found_once() {
        // 0.25, 0.5 and 0.75 are exactly where bisection splits.
        let want = [0.05, 0.25, 0.5, 0.6, 0.75, 0.95];
        let got = intervals(&roots_of(&from_roots(&want), 0.0));
        assert_eq!(got.len(), want.len(), "{got:?}");
        assert_matches(&got, &want, 1e-12);
    }
}

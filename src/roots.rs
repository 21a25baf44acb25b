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
//! - if the coefficients certainly change sign exactly once (Descartes' rule
//!   in Bernstein form), there is exactly one root;
//! - a deep piece that is certainly convex or concave has at most two roots,
//!   one either side of its extremum, and none if the extremum's lower bound
//!   is certainly positive (near-tangencies decided at once).
//!
//! Everything else is split at its midpoint. A piece with one root is refined
//! by safeguarded Newton iteration on a certain-sign bracket (bisection
//! whenever a step leaves it or stalls) and confirmed by the signs either
//! side, or earlier by a Taylor bound that puts the Newton point within the
//! requested resolution of the root. Pieces narrower
//! than `2⁻ᴹᴬˣ` that still cannot be decided are reported as roots at their
//! midpoint; where every coefficient is within the error of zero the
//! polynomial vanishes identically on the piece and the whole piece is
//! reported ([`Root::Flat`]).
//!
//! The error bound grows with each subdivision level by the rounding of one
//! convex combination (`2ε·max|cᵢ|`), so the sign tests stay conservative: a
//! root can be reported that exact arithmetic would refute (the caller
//! verifies), but none is missed.

use crate::bernstein::{Polynomial, subdivide};
use crate::scratch::with_scratch;

/// Deepest subdivision: pieces of width `2⁻⁴⁸` (about `3.6e-15`) are not split.
const MAX_DEPTH: u32 = 48;

/// Pieces this deep try the convexity rule ([`Search::convex`]): shallower
/// ones, which hold two well-separated roots more often than a near-double
/// one, are cheaper to halve.
const CONVEX_DEPTH: u32 = 3;

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
    let scale = magnitude(coeffs);
    let search = Search {
        error: error.max(0.0),
        growth: 2.0 * f64::EPSILON * scale,
        width,
    };
    let mut pending: Option<Root> = None;
    let mut merge = |root: Root| {
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
    };
    // Lengths up to 17 (degree ≤ 16) run on exactly sized arrays.
    macro_rules! fixed {
        ($($n:literal),*) => {
            match coeffs.len() {
                $($n => {
                    if let Ok(c) = <&[f64; $n]>::try_from(coeffs) {
                        search.piece_fixed(c, 0.0, 1.0, 0, &mut merge);
                    }
                })*
                _ => search.piece(coeffs, 0.0, 1.0, 0, &mut merge),
            }
        };
    }
    fixed!(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17);
    if let Some(r) = pending {
        found(r);
    }
}

/// The roots in `[0, 1]` when the search's first, cheapest rules decide
/// them, exactly as [`find_roots_to`] would report them: every coefficient
/// certainly of one sign ([`QuickRoots::None`]), or one certain sign change
/// and its root confirmed ([`QuickRoots::One`]). Anything else is
/// [`QuickRoots::Search`]: call [`find_roots_to`].
///
/// For callers on a hot path: with coefficients in a fixed-size array the
/// whole decision and refinement run unrolled, without the search's
/// recursion and callbacks.
#[inline(always)]
pub(crate) fn quick_roots<P: Polynomial + ?Sized>(c: &P, error: f64, width: f64) -> QuickRoots {
    let coeffs = c.coeffs();
    if coeffs.is_empty() {
        return QuickRoots::None;
    }
    // The error of the search's first level (depth 0).
    let e = error.max(0.0) + 2.0 * f64::EPSILON * magnitude(coeffs);
    match first_look(c, 0.0, 1.0, e, width) {
        Look::NoRoot => QuickRoots::None,
        Look::One(u) => QuickRoots::One(u),
        Look::Flat | Look::Undecided => QuickRoots::Search,
    }
}

/// What [`quick_roots`] decided.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum QuickRoots {
    /// No root in `[0, 1]`.
    None,
    /// Exactly one root, refined.
    One(f64),
    /// Not decided by the first rules.
    Search,
}

/// What the cheap rules say about one piece.
enum Look {
    /// Every coefficient certainly of one sign: no root.
    NoRoot,
    /// Every coefficient within the error of zero.
    Flat,
    /// One certain sign change: exactly one root, here (confirmed).
    One(f64),
    /// None of these.
    Undecided,
}

/// The cheap rules on the piece `c` of `[a, b]` at coefficient error `e`:
/// the convex-hull test and, for one certain sign change (Descartes' rule),
/// the refined root ([`refine`] to `width`; a root it cannot confirm leaves
/// the piece undecided).
#[inline(always)]
fn first_look<P: Polynomial + ?Sized>(c: &P, a: f64, b: f64, e: f64, width: f64) -> Look {
    let coeffs = c.coeffs();
    match sign_pattern(coeffs, e) {
        Signs::Definite => Look::NoRoot,
        Signs::Zero => Look::Flat,
        Signs::OneChange => refine(c, a, b, width).map_or(Look::Undecided, Look::One),
        Signs::Mixed => Look::Undecided,
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
    /// Exactly one certain sign change: the ends certainly of opposite
    /// signs, a run certainly of the first sign, at most one coefficient
    /// within the noise, then a run certainly of the last sign. Every
    /// polynomial whose coefficients lie within the error of these has one
    /// sign change, so by the Bernstein form of Descartes' rule of signs
    /// (Lane & Riesenfeld 1981) exactly one root in `(0, 1)`, a simple one.
    OneChange,
    /// Anything else.
    Mixed,
}

/// The [`Signs`] of `c` at error `e`, in one pass over the certain signs
/// `sᵢ ∈ {−1, 0, 1}`: one change means `s₀ ≠ 0`, `sₙ = −s₀`, at most one
/// `sᵢ = 0` and total variation `Σ|sᵢ₊₁ − sᵢ| = 2` (a sequence from `s₀` to
/// `−s₀` with no step back).
#[inline]
fn sign_pattern(c: &[f64], e: f64) -> Signs {
    let Some((&first, rest)) = c.split_first() else {
        return Signs::Zero;
    };
    let code = |x: f64| i32::from(x > e) - i32::from(x < -e);
    let s0 = code(first);
    let (mut positive, mut negative) = (i32::from(s0 > 0), i32::from(s0 < 0));
    let (mut variation, mut last) = (0, s0);
    for &x in rest {
        let s = code(x);
        positive += i32::from(s > 0);
        negative += i32::from(s < 0);
        variation += (s - last).abs();
        last = s;
    }
    let n = c.len() as i32;
    let zeros = n - positive - negative;
    if positive == n || negative == n {
        Signs::Definite
    } else if zeros == n {
        Signs::Zero
    } else if s0 != 0 && last == -s0 && variation == 2 && zeros <= 1 {
        Signs::OneChange
    } else {
        Signs::Mixed
    }
}

/// The least and the greatest of `values` (infinities for none), by plain
/// comparisons: NaNs are passed over as `f64::min` and `f64::max` pass them,
/// without their NaN handling per element (this runs for every piece).
#[inline]
fn extremes(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in values {
        if x < lo {
            lo = x;
        }
        if x > hi {
            hi = x;
        }
    }
    (lo, hi)
}

/// The largest magnitude `max|cᵢ|` (0 for none), as [`extremes`] finds it.
#[inline]
fn magnitude(c: &[f64]) -> f64 {
    let mut m = 0.0;
    for x in c {
        if x.abs() > m {
            m = x.abs();
        }
    }
    m
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
    /// Decides the piece `c` on `[a, b]` (reporting what it holds), or
    /// returns `true` when it must be split.
    ///
    /// Generic over the coefficients' storage: pieces of a fixed size run
    /// every rule and refinement compiled for that size.
    fn settle<P: Polynomial + ?Sized>(
        &self,
        poly: &P,
        a: f64,
        b: f64,
        depth: u32,
        found: &mut dyn FnMut(Root),
    ) -> bool {
        let c = poly.coeffs();
        let e = self.error + self.growth * f64::from(depth + 1);
        match first_look(poly, a, b, e, self.width) {
            Look::NoRoot => return false,
            Look::Flat => {
                found(Root::Flat { from: a, to: b });
                return false;
            }
            Look::One(u) => {
                found(Root::At(u));
                return false;
            }
            Look::Undecided => {}
        }
        let n = c.len() - 1;
        if self.monotonic(c, e) {
            let (f0, f1) = (c[0], c[n]);
            match (certain_sign(f0, e), certain_sign(f1, e)) {
                // Monotonic: the estimate is the root even when rounding
                // hides the signs around it.
                (s0, s1) if s0 * s1 < 0 => found(Root::At(
                    refine(poly, a, b, self.width).unwrap_or_else(|u| u),
                )),
                (s0, s1) if s0 * s1 > 0 => {}
                // An end value within the noise: the root is there (or the
                // curve only grazes zero); report the end nearer to zero.
                _ => found(Root::At(if f0.abs() <= f1.abs() { a } else { b })),
            }
            return false;
        }
        if depth >= CONVEX_DEPTH && self.convex(poly, a, b, e, found) {
            return false;
        }
        if depth >= MAX_DEPTH || b - a < self.width {
            found(Root::At(0.5 * (a + b)));
            return false;
        }
        true
    }

    /// The search on a piece of any length (halves in stack scratch).
    fn piece(&self, c: &[f64], a: f64, b: f64, depth: u32, found: &mut dyn FnMut(Root)) {
        if !self.settle(c, a, b, depth, found) {
            return;
        }
        let mid = 0.5 * (a + b);
        with_scratch(2 * c.len(), 0.0, |buf| {
            let (left, right) = buf.split_at_mut(c.len());
            subdivide(c, 0.5, left, right);
            self.piece(left, a, mid, depth + 1, found);
            self.piece(right, mid, b, depth + 1, found);
        });
    }

    /// The search on a piece of `N` coefficients: the halves are arrays the
    /// compiler sizes exactly (no scratch buckets, no slice bounds).
    fn piece_fixed<const N: usize>(
        &self,
        c: &[f64; N],
        a: f64,
        b: f64,
        depth: u32,
        found: &mut dyn FnMut(Root),
    ) {
        if !self.settle(c, a, b, depth, found) {
            return;
        }
        let mid = 0.5 * (a + b);
        let (mut left, mut right) = ([0.0; N], [0.0; N]);
        subdivide(c, 0.5, &mut left, &mut right);
        self.piece_fixed(&left, a, mid, depth + 1, found);
        self.piece_fixed(&right, mid, b, depth + 1, found);
    }

    /// Decides a piece that is certainly convex or concave (second
    /// differences `cᵢ₊₂ − 2cᵢ₊₁ + cᵢ`, known to within `4e`, of one sign),
    /// reporting its roots; `false` when it is not such a piece or its
    /// critical point cannot be isolated.
    ///
    /// With `g = ±f` convex, `g′` rises through one critical point `s*`
    /// (refined from the derivative's coefficients) and `g` has at most two
    /// roots, one on each side of its minimum. The minimum is at least
    /// `g(ŝ) − |g′(ŝ)|` at the computed `ŝ` (a convex function lies above its
    /// tangents, and `|s − ŝ| ≤ 1`), less the errors:
    /// - that bound certainly positive: no root (a ray that passes a
    ///   silhouette closely, decided at once instead of by thirty halvings);
    /// - `g(ŝ)` certainly negative: one root on each side whose end value is
    ///   certainly positive (refined on that monotonic side), a root within
    ///   the noise at an end whose value is uncertain;
    /// - otherwise the minimum is within the noise of zero: one (near-)double
    ///   root at `ŝ`, the grazing contact.
    fn convex<P: Polynomial + ?Sized>(
        &self,
        poly: &P,
        a: f64,
        b: f64,
        e: f64,
        found: &mut dyn FnMut(Root),
    ) -> bool {
        let c = poly.coeffs();
        let n = c.len() - 1;
        if n < 2 {
            return false;
        }
        let (lo2, hi2) = extremes(c.windows(3).map(|w| w[2] - 2.0 * w[1] + w[0]));
        let sigma = if lo2 > 4.0 * e {
            1.0
        } else if hi2 < -4.0 * e {
            -1.0
        } else {
            return false;
        };
        let scale = magnitude(c);
        let noise = 4.0 * n as f64 * f64::EPSILON * scale;
        // The critical point: the one root of the rising g′ (its ends must
        // certainly differ in sign, else the piece is monotonic or unclear).
        let critical = with_scratch(n, 0.0, |d| {
            for (di, w) in d.iter_mut().zip(c.windows(2)) {
                *di = sigma * n as f64 * (w[1] - w[0]);
            }
            let de = 2.0 * n as f64 * e + noise;
            if !(d[0] < -de && d[n - 1] > de) {
                return None;
            }
            Some(refine(d, 0.0, 1.0, 0.0).unwrap_or_else(|s| s))
        });
        let Some(s_star) = critical else {
            return false;
        };
        let Some((m, dm)) = poly.value_and_slope(s_star) else {
            return false;
        };
        let (gm, slope) = (sigma * m, dm.abs() + 2.0 * n as f64 * (e + noise));
        let value_error = e + noise;
        if gm - slope - value_error > 0.0 {
            return true;
        }
        let to_u = |s: f64| a + (b - a) * s;
        if gm < -value_error {
            let (g0, g1) = (sigma * c[0], sigma * c[n]);
            // Left of the minimum g falls, right of it g rises.
            match certain_sign(g0, e) {
                1 => {
                    let start = s_star * g0 / (g0 - gm);
                    let root =
                        refine_within(poly, a, b, self.width, (0.0, s_star), sigma < 0.0, start);
                    found(Root::At(root.unwrap_or_else(|u| u)));
                }
                0 => found(Root::At(a)),
                _ => {}
            }
            match certain_sign(g1, e) {
                1 => {
                    let start = s_star + (1.0 - s_star) * (-gm) / (g1 - gm);
                    let root =
                        refine_within(poly, a, b, self.width, (s_star, 1.0), sigma > 0.0, start);
                    found(Root::At(root.unwrap_or_else(|u| u)));
                }
                0 => found(Root::At(b)),
                _ => {}
            }
            return true;
        }
        found(Root::At(to_u(s_star)));
        true
    }

    /// Whether the derivative's coefficients `n(cᵢ₊₁ − cᵢ)` certainly share
    /// one sign (each difference is known to within `2e`).
    fn monotonic(&self, c: &[f64], e: f64) -> bool {
        let (lo, hi) = extremes(c.windows(2).map(|w| w[1] - w[0]));
        let tol = 2.0 * e;
        lo > tol || hi < -tol
    }
}

/// The root of the polynomial piece `c` on `[a, b]` that has exactly one
/// root there (end values certainly of opposite signs), by safeguarded
/// Newton iteration on the local parameter `s`.
///
/// Values within the evaluation's rounding bound (`4nε·max|cᵢ|` for de
/// Casteljau) carry no sign. The bracket `[lo, hi]` moves only on certain
/// signs, so it always holds the root; Newton steps that leave it, or eight
/// iterations that fail to halve it (linear convergence towards a near-touch
/// of zero), are replaced by bisection. Once a Newton step no longer moves
/// the root in the caller's parameter `u = a + (b − a)s` (or moves it less
/// than `done`: a caller that polishes the root itself; the Newton point
/// after such a step is already accurate to about its square), or the value
/// is within the noise, the root is confirmed by certain, opposite signs a
/// little way either side.
///
/// Most roots end one evaluation earlier and without those probes: once a
/// step is below the square root of the resolution, the Newton point is
/// about as accurate as the resolution, and [`Taylor::newton_error`] proves
/// it (from the values already computed and a bound on `|f″|` over the
/// piece). A root so proven is returned as `Ok` too.
///
/// `Ok(u)` is a confirmed root. `Err(u)` is the best estimate where the
/// signs could not be confirmed: near a touch of zero within the rounding
/// bound, the one root cannot be told from the noise (the caller then
/// subdivides instead).
#[inline]
fn refine<P: Polynomial + ?Sized>(c: &P, a: f64, b: f64, done: f64) -> Result<f64, f64> {
    refine_from(c, a, b, done, polygon_crossing(c.coeffs()))
}

/// [`refine`] from the local start `s` (in `[0, 1]`).
#[inline]
fn refine_from<P: Polynomial + ?Sized>(
    c: &P,
    a: f64,
    b: f64,
    done: f64,
    s: f64,
) -> Result<f64, f64> {
    let coeffs = c.coeffs();
    let rising = coeffs[coeffs.len() - 1] > coeffs[0];
    refine_within(c, a, b, done, (0.0, 1.0), rising, s)
}

/// [`refine`] on the local bracket `bracket` (whose ends certainly have
/// opposite signs, rising or falling through the one root) from `s`.
#[inline]
fn refine_within<P: Polynomial + ?Sized>(
    c: &P,
    a: f64,
    b: f64,
    done: f64,
    bracket: (f64, f64),
    rising: bool,
    mut s: f64,
) -> Result<f64, f64> {
    let n = c.coeffs().len() - 1;
    let to_u = |s: f64| a + (b - a) * s;
    // f·sign rises through the root.
    let sign = if rising { 1.0 } else { -1.0 };
    let scale = magnitude(c.coeffs());
    let noise = 4.0 * n.max(1) as f64 * f64::EPSILON * scale;
    // Which side of the root `x` certainly is: −1 before, 1 after, 0 unknown.
    let side = |f: f64| {
        if f * sign > noise {
            1
        } else if f * sign < -noise {
            -1
        } else {
            0
        }
    };
    // The rounding of f′: twice that of the two values it is the
    // difference of, times n.
    let derivative_noise = 2.0 * n as f64 * noise;
    let (mut lo, mut hi) = bracket;
    let resolution = (2.0 * f64::EPSILON * a.abs().max(b.abs()).max(f64::MIN_POSITIVE) / (b - a))
        .max(done / (b - a));
    let mut checkpoint = hi - lo;
    for i in 1..=128 {
        let Some((f, df)) = c.value_and_slope(s) else {
            break;
        };
        match side(f) {
            1 => hi = s,
            -1 => lo = s,
            _ => {}
        }
        let newton = s - f / df;
        let step = (newton - s).abs();
        if step * step <= resolution {
            let taylor = Taylor {
                value: f,
                slope: df,
                noise,
                derivative_noise,
                curvature: curvature_bound(c.coeffs(), scale),
            };
            if taylor
                .newton_error(s, step, (lo, hi))
                .is_some_and(|e| e <= resolution)
            {
                return Ok(to_u(newton.clamp(lo, hi)));
            }
        }
        let small_step = step <= resolution.max(f64::EPSILON * s);
        if small_step || side(f) == 0 {
            // Confirm by certain signs either side, at a distance the noise
            // cannot flip (at most 2⁻²⁰: farther is no confirmation).
            let noise_width = 2.0 * noise / df.abs();
            let trust_newton = small_step || step <= noise_width;
            let center = if trust_newton { newton } else { s }.clamp(lo, hi);
            let d = noise_width
                .max(4.0 * if trust_newton { step } else { 0.0 })
                .max(4.0 * f64::EPSILON)
                .min(1.0 / (1u32 << 20) as f64);
            let (l, r) = ((center - d).max(lo), (center + d).min(hi));
            let at = |x: f64, end: f64, known: i32| {
                if x == end { known } else { side(c.value(x)) }
            };
            match (at(l, lo, -1), at(r, hi, 1)) {
                (-1, 1) => return Ok(to_u(center)),
                (1, _) => hi = l,
                (_, -1) => lo = r,
                // A sign lost in the noise on a piece that is not monotonic:
                // the root cannot be told from a near-touch here.
                _ => return Err(to_u(center)),
            }
            s = 0.5 * (lo + hi);
        } else {
            let stalled = i % 8 == 0 && hi - lo > 0.5 * checkpoint;
            if i % 8 == 0 {
                checkpoint = hi - lo;
            }
            s = if newton >= lo && newton <= hi && !stalled {
                newton
            } else {
                0.5 * (lo + hi)
            };
        }
        if hi - lo <= 2.0 * f64::EPSILON {
            // Certain signs at both ends of a collapsed bracket.
            return Ok(to_u(0.5 * (lo + hi)));
        }
    }
    Err(to_u(s.clamp(lo, hi)))
}

/// A polynomial's value and slope at one point `s` as computed, with bounds
/// on their rounding and on the second derivative near `s`.
struct Taylor {
    /// `f(s)`, within `noise` of the exact value.
    value: f64,
    /// `f′(s)`, within `derivative_noise` of the exact value.
    slope: f64,
    noise: f64,
    derivative_noise: f64,
    /// `|f″| ≤ curvature` on the piece (`[0, 1]`).
    curvature: f64,
}

impl Taylor {
    /// A bound on `|r − N|` for the Newton point `N = s − f(s)/f′(s)` (as
    /// computed; `step = |N − s|`) and the one root `r` of the bracket
    /// `[lo, hi] ⊆ [0, 1]`; `None` when the bound does not apply.
    ///
    /// With `|f(s)| ≤ F` and `|f′(s)| ≥ D > 0` (the computed values widened
    /// by their rounding) and `|f″| ≤ L`, Taylor's theorem gives
    /// `f(s ± δ) = f(s) ± f′(s)δ + ½f″(ξ)δ²`. With `D² > 2LF` and
    /// `δ₋ = 2F / (D + √(D² − 2LF))`, the smaller root of `½Lδ² − Dδ + F`,
    /// `f` therefore takes (weakly) opposite signs at `s ± δ₋`, and at the
    /// one towards the Newton point the sign opposite to `f(s)`'s. So a root
    /// lies between `s` and `s ± δ₋` on the Newton side when the sign of
    /// `f(s)` is certain, else within `δ₋` of `s`; if that interval lies in
    /// the bracket, it is the bracket's root. (Otherwise the tangent may
    /// point at a root beyond the bracket while the bracket's own is far;
    /// near a touch of zero `D² ≤ 2LF`.) With `δ = |r − s| ≤ δ₋`, Taylor's
    /// theorem at `r` gives `r − N = f̃/f̃′ − f/f′ − ½f″(ξ)δ²/f′(s)`: the
    /// rounding of the quotient, at most `(noise + F·noise′/D)/D`, the
    /// curvature term, at most `Lδ₋²/(2D)`, and the rounding of `N` itself,
    /// `2ε(|s| + step)`.
    fn newton_error(&self, s: f64, step: f64, (lo, hi): (f64, f64)) -> Option<f64> {
        let d = self.slope.abs() - self.derivative_noise;
        let big_f = self.value.abs() + self.noise;
        let l = self.curvature;
        let disc = d * d - 2.0 * l * big_f;
        if !(d > 0.0 && disc > 0.0) {
            return None;
        }
        let near = 2.0 * big_f / (d + disc.sqrt());
        // Where a root certainly is: on the Newton side of s, or on either
        // side when f(s) is within its rounding of zero.
        let (from, to) = if self.value.abs() > self.noise {
            let newton_side = if (self.value > 0.0) == (self.slope > 0.0) {
                -near
            } else {
                near
            };
            (s.min(s + newton_side), s.max(s + newton_side))
        } else {
            (s - near, s + near)
        };
        if from < lo || to > hi {
            return None;
        }
        let curve = 0.5 * l * near * near / d;
        let quotient = (self.noise + big_f * self.derivative_noise / d) / d;
        Some(curve + quotient + 2.0 * f64::EPSILON * (s.abs() + step))
    }
}

/// A bound on `|f″|` over `[0, 1]` for the polynomial with Bernstein
/// coefficients `c` of degree `n`: the second derivative's coefficients
/// `n(n − 1)(cᵢ₊₂ − 2cᵢ₊₁ + cᵢ)` bound it (convex hull), and each second
/// difference is computed to within `16ε·max|cᵢ|` (`scale`). Zero below
/// degree 2.
fn curvature_bound(c: &[f64], scale: f64) -> f64 {
    let n = c.len().saturating_sub(1) as f64;
    let mut second = 0.0;
    for w in c.windows(3) {
        let d = (w[2] - 2.0 * w[1] + w[0]).abs();
        if d > second {
            second = d;
        }
    }
    n * (n - 1.0).max(0.0) * (second + 16.0 * f64::EPSILON * scale)
}

/// Where the control polygon `(i/n, cᵢ)` first crosses zero (0 if it does
/// not).
#[inline]
fn polygon_crossing(c: &[f64]) -> f64 {
    let n = (c.len() - 1) as f64;
    for (i, w) in c.windows(2).enumerate() {
        if (w[0] > 0.0) != (w[1] > 0.0) {
            let step = w[0] / (w[0] - w[1]);
            return ((i as f64 + if step.is_finite() { step } else { 0.0 }) / n).clamp(0.0, 1.0);
        }
    }
    0.0
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

    #[test]
    fn one_sign_change_allows_one_uncertain_coefficient_only() {
        let e = 0.1;
        let one = |c: &[f64]| sign_pattern(c, e) == Signs::OneChange;
        assert!(one(&[1.0, 1.0, 0.05, -1.0]));
        assert!(one(&[-1.0, 1.0, 1.0]));
        assert!(one(&[1.0, -1.0]));
        // Two coefficients in the noise could be +, − between the runs.
        assert!(!one(&[1.0, 0.05, -0.05, -1.0]));
        assert!(!one(&[1.0, -1.0, 1.0, -1.0]));
        // A step back within the noise: +, 0, +, − could change sign thrice.
        assert!(!one(&[1.0, 0.05, 1.0, -1.0]));
        // An end in the noise is never certain.
        assert!(!one(&[0.05, -1.0, -1.0]));
        assert!(!one(&[1.0, 1.0]));
        assert_eq!(sign_pattern(&[1.0, 1.0], e), Signs::Definite);
        assert_eq!(sign_pattern(&[-1.0, -0.2], e), Signs::Definite);
        assert_eq!(sign_pattern(&[0.05, -0.1, 0.0], e), Signs::Zero);
        assert_eq!(sign_pattern(&[0.05, 1.0, 0.0], e), Signs::Mixed);
    }

    #[test]
    fn a_near_touch_is_not_taken_for_the_root() {
        // (u − 0.2)·((u − 0.7)² + δ): one root at 0.2, and near 0.7 the
        // polynomial almost touches zero, where Newton's steps are tiny.
        for delta in [1e-6, 1e-12, 1e-20, 1e-28] {
            let mut c = from_roots(&[0.7, 0.7]);
            // Adding δ to every coefficient adds δ (partition of unity).
            c.iter_mut().for_each(|x| *x += delta);
            let lin = from_roots(&[0.2]);
            // Product of a quadratic and a linear Bernstein form (degree 3).
            let bin = crate::bernstein::binomial;
            let mut p = vec![0.0; 4];
            for (i, ci) in c.iter().enumerate() {
                for (j, lj) in lin.iter().enumerate() {
                    p[i + j] += bin(2, i) * bin(1, j) / bin(3, i + j) * ci * lj;
                }
            }
            // (Below rounding, δ leaves a numerical double root at 0.7 that
            // the search rightly reports too.)
            if delta >= 1e-12 {
                let got = intervals(&roots_of(&p, 0.0));
                assert_matches(&got, &[0.2], 1e-12);
            }
            // And the refinement alone, from anywhere, gives the root.
            for k in 0..=1000 {
                let s0 = 0.69 + 0.02 * f64::from(k) / 1000.0;
                // Confirmed at 0.2, or (only where δ is below the rounding
                // of evaluation) declined so that the caller subdivides.
                match refine_from(p.as_slice(), 0.0, 1.0, 0.0, s0) {
                    Ok(u) => assert!((u - 0.2).abs() < 1e-12, "δ = {delta}, from {s0}: {u}"),
                    Err(u) => assert!(delta < 1e-15, "δ = {delta}, from {s0}: declined at {u}"),
                }
            }
        }
    }

    /// The Taylor bound of a point: its Newton point and the bound.
    fn taylor_at(c: &[f64], s: f64, bracket: (f64, f64)) -> (f64, Option<f64>) {
        let scale = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let n = (c.len() - 1) as f64;
        let noise = 4.0 * n * f64::EPSILON * scale;
        let (f, df) = crate::bernstein::eval_with_derivative(c, s).unwrap();
        let newton = s - f / df;
        let taylor = Taylor {
            value: f,
            slope: df,
            noise,
            derivative_noise: 2.0 * n * noise,
            curvature: curvature_bound(c, scale),
        };
        (newton, taylor.newton_error(s, (newton - s).abs(), bracket))
    }

    #[test]
    fn taylor_bound_holds_near_simple_roots() {
        let want = [0.1, 0.37, 0.5, 0.82, 0.99];
        let c = from_roots(&want);
        for (i, &r) in want.iter().enumerate() {
            // The isolating interval: halfway to the neighbours.
            let lo = if i == 0 { 0.0 } else { 0.5 * (want[i - 1] + r) };
            let hi = want.get(i + 1).map_or(1.0, |&w| 0.5 * (w + r));
            for offset in [1e-2, 1e-3, 1e-5, 1e-7, 1e-9, -1e-9, -1e-5, -1e-2] {
                let s = (r + offset).clamp(lo, hi);
                let (newton, bound) = taylor_at(&c, s, (lo, hi));
                if let Some(e) = bound {
                    assert!(
                        (newton - r).abs() <= e,
                        "root {r}, from {s}: {newton} ± {e}"
                    );
                }
                // Close to a simple root the bound applies, and it is about
                // the square of the distance.
                if offset.abs() <= 1e-5 {
                    assert!(
                        bound.is_some_and(|e| e < 1e-6),
                        "root {r}, from {s}: {bound:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn taylor_bound_declines_when_the_tangent_points_past_the_bracket() {
        // (u + 0.01)(u − 0.9): the bracket [0.02, 1] holds the root 0.9, but
        // at 0.02 the tangent points at −0.01, just outside it. A bound
        // around the Newton point there would certify a root that the
        // bracket does not hold.
        let c = from_roots(&[-0.01, 0.9]);
        let (newton, bound) = taylor_at(&c, 0.02, (0.02, 1.0));
        assert!((newton + 0.01).abs() < 2e-3, "{newton}");
        assert_eq!(bound, None);
        // On a bracket that holds the near root it applies.
        let (newton, bound) = taylor_at(&c, 0.02, (-0.05, 0.4));
        assert!(bound.is_some_and(|e| (newton + 0.01).abs() <= e));
        // At a touch of zero (a double root) it never applies.
        let touch = from_roots(&[0.5, 0.5]);
        for s in [0.49, 0.4999, 0.5 + 1e-7] {
            assert_eq!(taylor_at(&touch, s, (0.0, 1.0)).1, None, "{s}");
        }
        // Rising through zero beside a near-touch: the piece's one root is
        // found, not the near-touch, from any start.
        let mut p = from_roots(&[0.2, 0.7, 0.7]);
        p.iter_mut().for_each(|x| *x += 1e-9);
        for k in 0..=100 {
            let s0 = 0.65 + 0.1 * f64::from(k) / 100.0;
            // (Lifted by 1e-9, the root moves by 1e-9 / f′(0.2) = 4e-9.)
            let u = refine_from(p.as_slice(), 0.0, 1.0, 0.0, s0).expect("confirmed");
            assert!((u - 0.2).abs() < 1e-8, "from {s0}: {u}");
        }
    }

    #[test]
    fn close_roots_are_all_found_to_the_candidate_width() {
        let width = 1.0 / f64::from(1u32 << 30);
        // (Closer roots are ill-conditioned: the coefficients' rounding
        // moves them by more than the width.)
        let want = [0.2, 0.5, 0.51, 0.53, 0.75];
        let mut got = Vec::new();
        find_roots_to(&from_roots(&want), 0.0, width, |r| got.push(r));
        let got = intervals(&got);
        assert_eq!(got.len(), want.len(), "{got:?}");
        assert_matches(&got, &want, width);
    }

    #[test]
    fn convex_and_concave_pieces() {
        for (r0, r1) in [
            (0.3, 0.35),
            (0.1, 0.9),
            (0.5, 0.5 + 1e-6),
            (0.0, 0.4),
            (0.6, 1.0),
        ] {
            for sign in [1.0, -1.0] {
                let c: Vec<f64> = from_roots(&[r0, r1]).iter().map(|x| sign * x).collect();
                let got = intervals(&roots_of(&c, 0.0));
                assert_eq!(got.len(), 2, "{r0}, {r1}: {got:?}");
                // The roots are conditioned by the slope |r₁ − r₀| there:
                // evaluation noise 4nε·max|cᵢ| moves them by that over it.
                let noise = 8.0 * f64::EPSILON * c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                assert_matches(&got, &[r0, r1], (noise / (r1 - r0)).max(1e-14));
            }
        }
        // A quartic with no root in [0, 1] beyond a close approach from above.
        for lift in [1e-4, 1e-8, 1e-12] {
            let mut c = from_roots(&[0.3, 0.3, -2.0, 3.0]);
            let scale = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            // The quartic is negative on [0, 1]: flip it and lift it.
            c.iter_mut().for_each(|x| *x = -*x + lift * scale);
            assert!(roots_of(&c, 0.0).is_empty(), "lift {lift}");
            // Dropped by as much, it crosses twice near 0.3.
            c.iter_mut().for_each(|x| *x -= 2.0 * lift * scale);
            let got = intervals(&roots_of(&c, 0.0));
            assert_eq!(got.len(), 2, "lift {lift}: {got:?}");
            assert!(
                got.iter()
                    .all(|&(lo, hi)| (lo - 0.3).abs() < 1e-2 && (hi - 0.3).abs() < 1e-2)
            );
        }
    }

    /// `quick_roots` decides only what the full search reports, and reports
    /// the same root to the bit, on fixed-size arrays and on slices alike;
    /// it decides most one-root and no-root sextics (else the fast path
    /// would be dead code).
    #[test]
    fn quick_roots_agrees_with_the_search() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let mut unit = || crate::test_unit::unit(&mut state);
        let (mut none, mut one, mut search) = (0, 0, 0);
        for case in 0..3000 {
            // Six roots, zero to three of them in [0, 1]; a scale; for some
            // cases an error bound on the coefficients.
            let inside = case % 4;
            let roots: Vec<f64> = (0..6)
                .map(|i| {
                    if i < inside {
                        unit()
                    } else if unit() < 0.5 {
                        -0.05 - 2.0 * unit()
                    } else {
                        1.05 + 2.0 * unit()
                    }
                })
                .collect();
            let scale = 10f64.powf(6.0 * unit() - 3.0);
            let c: Vec<f64> = from_roots(&roots).iter().map(|x| x * scale).collect();
            let error = if case % 3 == 0 { 1e-12 * scale } else { 0.0 };
            let arr: [f64; 7] = c.clone().try_into().expect("seven coefficients");
            let quick = quick_roots(&arr, error, 0.0);
            assert_eq!(quick, quick_roots(c.as_slice(), error, 0.0), "{c:?}");
            let full = roots_of(&c, error);
            match quick {
                QuickRoots::None => {
                    assert!(full.is_empty(), "{c:?}: {full:?}");
                    none += 1;
                }
                QuickRoots::One(u) => {
                    assert_eq!(full, vec![Root::At(u)], "{c:?}");
                    one += 1;
                }
                QuickRoots::Search => search += 1,
            }
        }
        assert!(
            none > 500 && one > 500,
            "{none} none, {one} one, {search} searched"
        );
    }
}

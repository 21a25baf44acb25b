//! Knot vectors and the kernels on them that every B-spline shares:
//! polynomial ([`BSpline`](crate::BSpline)) and rational
//! ([`Nurbs`](crate::Nurbs)) curves, and the tensor-product surfaces.
//!
//! Notation (Piegl & Tiller, *The NURBS Book*, ch. 2–5): degree `p`, control
//! values `P₀ … P_{n−1}`, knots `t₀ ≤ … ≤ t_{n+p}`, domain `[t_p, t_n]`. The
//! kernels are generic over the control values (a [`Coefficient`]): vectors
//! for a polynomial spline, homogeneous points `(wP, w)` for a rational one.
//!
//! - the knot vectors: [`validate_knots`], the [`domain`], the non-empty
//!   spans ([`nonempty_spans`]), the uniform and clamped knots;
//! - de Boor's algorithm ([`de_boor`]) and blossoms ([`blossom`]),
//!   which give each span's Bézier points ([`span_bezier_points`]);
//! - the derivative splines' control values ([`derivative_control_step`],
//!   [`check_derivative_points`]);
//! - knot insertion ([`knot_to_insert`], [`boehm_insert`], [`insert_knot`]).

use super::check_in_domain;
use crate::Error;
use crate::bernstein::{Coefficient, lerp};
use crate::limits::{MAX_COORDINATE, MAX_DERIVATIVE};
use crate::scratch::with_scratch;
use nalgebra::{Point, SVector};
use std::ops::Div;

/// The parameter domain `[t_p, t_n]` of a spline of degree `degree` with
/// `n` control points on `knots`.
#[inline]
pub(crate) fn domain(knots: &[f64], degree: usize, n: usize) -> (f64, f64) {
    (knots[degree], knots[n])
}

/// The indices `i` of the non-empty knot spans `[tᵢ, tᵢ₊₁)` of the domain
/// (`degree ≤ i < n`), in order: one polynomial piece each.
pub(crate) fn nonempty_spans(
    knots: &[f64],
    degree: usize,
    n: usize,
) -> impl Iterator<Item = usize> + '_ {
    (degree..n).filter(|&i| knots[i] < knots[i + 1])
}

/// The smallest gap between distinct knots that rounding can tell apart,
/// `4ε ×` the knot range (see [`Error::KnotGapTooSmall`]).
#[inline]
pub(crate) fn min_knot_gap(knots: &[f64]) -> f64 {
    4.0 * f64::EPSILON * (knots[knots.len() - 1] - knots[0])
}

/// The course framework's uniform knots `tᵢ = i/(n + p)`, `i = 0 … n + p`,
/// for `n` control points and degree `p` (`p < n`).
pub(crate) fn uniform_knots(degree: usize, n: usize) -> Vec<f64> {
    let last = (n + degree) as f64;
    (0..=n + degree).map(|i| i as f64 / last).collect()
}

/// Clamped (open uniform) knots on `[0, 1]`: `degree + 1` knots at 0 and at
/// 1 and uniform interior knots, for `n` control points (`degree < n`).
pub(crate) fn clamped_knots(degree: usize, n: usize) -> Vec<f64> {
    let spans = n - degree;
    (0..=n + degree)
        .map(|i| match i {
            i if i <= degree => 0.0,
            i if i >= n => 1.0,
            i => (i - degree) as f64 / spans as f64,
        })
        .collect()
}

/// [`Error::DegreeTooHigh`] unless there are more than `degree` control
/// points.
pub(crate) fn check_degree(degree: usize, points: usize) -> Result<(), Error> {
    if degree >= points {
        Err(Error::DegreeTooHigh { degree, points })
    } else {
        Ok(())
    }
}

/// Checks a knot vector for `n` control points of degree `degree`: the
/// checks of [`BSpline::new`](crate::BSpline::new) after the points', in
/// its order ([`Error::DegreeTooHigh`], [`Error::KnotCount`],
/// [`Error::NonFiniteKnot`], [`Error::KnotTooLarge`],
/// [`Error::DecreasingKnots`], [`Error::KnotGapTooSmall`],
/// [`Error::KnotMultiplicity`], [`Error::EmptyDomain`]).
pub(crate) fn validate_knots(degree: usize, knots: &[f64], n: usize) -> Result<(), Error> {
    check_degree(degree, n)?;
    let expected = n + degree + 1;
    if knots.len() != expected {
        return Err(Error::KnotCount {
            expected,
            found: knots.len(),
        });
    }
    for (index, &value) in knots.iter().enumerate() {
        if !value.is_finite() {
            return Err(Error::NonFiniteKnot { index });
        }
        if value.abs() > MAX_COORDINATE {
            return Err(Error::KnotTooLarge { index, value });
        }
    }
    if let Some(index) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
        return Err(Error::DecreasingKnots { index });
    }
    let min = min_knot_gap(knots);
    for index in 1..knots.len() {
        let gap = knots[index] - knots[index - 1];
        if gap > 0.0 && gap < min {
            return Err(Error::KnotGapTooSmall { index, gap, min });
        }
    }
    for run in knots.chunk_by(|a, b| a == b) {
        if run.len() > degree + 1 {
            return Err(Error::KnotMultiplicity {
                knot: run[0],
                multiplicity: run.len(),
                max: degree + 1,
            });
        }
    }
    let (start, end) = domain(knots, degree, n);
    if start >= end {
        return Err(Error::EmptyDomain { start, end });
    }
    Ok(())
}

/// The knot vector of the same spline traced backward, `C(a + b − t)` on
/// the same domain `[a, b]`: each knot mirrored, `t ↦ a + b − t`, in reverse
/// order (the control values are reversed with them).
///
/// # Edge rules
/// - The domain's ends map onto each other exactly (`a ↦ b`, `b ↦ a`), and
///   a knot inside the domain stays inside it (rounding is clamped there).
/// - `a + b − t` is rounded, which keeps the order but can bring two
///   distinct knots together (a knot an ulp from its neighbour, where the
///   mirrored values fall in a coarser binade) or within the gap rule of
///   [`validate_knots`]. Such a knot is moved apart from its neighbour to
///   the rule's gap (a few ulps), never onto it: multiplicities are kept,
///   and the result is always a valid knot vector.
/// - An outer knot whose mirror image would exceed
///   [`MAX_COORDINATE`] is clamped to it (only for knot vectors spanning
///   more than about `10¹⁰⁰`).
pub(crate) fn reflected_knots(knots: &[f64], degree: usize, n: usize) -> Vec<f64> {
    let (a, b) = domain(knots, degree, n);
    let sum = a + b;
    let mirror = |k: f64| {
        let r = sum - k;
        let r = if k == a {
            b
        } else if k == b {
            a
        } else if k < a {
            r.max(b)
        } else if k > b {
            r.min(a)
        } else {
            r.clamp(a, b)
        };
        r.clamp(-MAX_COORDINATE, MAX_COORDINATE)
    };
    // One entry per run of equal knots, last run first: the mirrored value,
    // the multiplicity, and whether it is an end of the domain (kept).
    let mut runs: Vec<(f64, usize, bool)> = knots
        .chunk_by(|x, y| x == y)
        .rev()
        .map(|run| (mirror(run[0]), run.len(), run[0] == a || run[0] == b))
        .collect();
    separate_runs(&mut runs);
    runs.iter()
        .flat_map(|&(value, count, _)| std::iter::repeat_n(value, count))
        .collect()
}

/// Moves the values of `runs` (non-decreasing, each `(value, multiplicity,
/// fixed)`) that are not `fixed` so that consecutive values differ by at
/// least the gap rule of [`validate_knots`] (with a margin of `2⁻¹⁰`, so
/// that the ends' own moves cannot make it bite): first up from below, then
/// down from above. Each move is a few ulps, and a valid knot vector has
/// room for them many times over (the passes could run out of room only
/// with about `1/(8ε)` distinct knots), so the values stay increasing and
/// the fixed ones in place.
fn separate_runs(runs: &mut [(f64, usize, bool)]) {
    let last = runs.len() - 1;
    let gap = 4.0 * f64::EPSILON * (runs[last].0 - runs[0].0) * (1.0 + 1.0 / 1024.0);
    let apart = |lo: f64, hi: f64| hi - lo >= gap;
    for j in 1..=last {
        let lo = runs[j - 1].0;
        let (hi, _, fixed) = runs[j];
        if !fixed && !apart(lo, hi) {
            let mut x = hi.max(lo + gap);
            for _ in 0..64 {
                if apart(lo, x) {
                    break;
                }
                x = next_float(x, 1.0);
            }
            runs[j].0 = x.min(MAX_COORDINATE);
        }
    }
    for j in (0..last).rev() {
        let hi = runs[j + 1].0;
        let (lo, _, fixed) = runs[j];
        if !fixed && !apart(lo, hi) {
            let mut x = lo.min(hi - gap);
            for _ in 0..64 {
                if apart(x, hi) {
                    break;
                }
                x = next_float(x, -1.0);
            }
            runs[j].0 = x.max(-MAX_COORDINATE);
        }
    }
}

/// The next float after the finite `x` toward `+∞` (`direction > 0`) or
/// `−∞` (`f64::next_up` needs a newer Rust than the crate's minimum).
fn next_float(x: f64, direction: f64) -> f64 {
    if x == 0.0 {
        return f64::from_bits(1).copysign(direction);
    }
    let bits = x.to_bits();
    f64::from_bits(if (x > 0.0) == (direction > 0.0) {
        bits + 1
    } else {
        bits - 1
    })
}

/// The blossom `f(a, …, a, b, …, b)` (`count_a` copies of `a`, the rest `b`)
/// of the polynomial on knot span `span`, whose `p + 1` control values
/// (global indices `span − p … span`) are `control`: de Boor's algorithm with
/// argument `a` at the first `count_a` levels and `b` after. The values are
/// vectors for a polynomial spline, homogeneous points for a rational one.
pub(crate) fn blossom<T: Coefficient>(
    knots: &[f64],
    control: &[T],
    p: usize,
    span: usize,
    count_a: usize,
    a: f64,
    b: f64,
) -> T {
    with_scratch(p + 1, control[0], |s| {
        s.copy_from_slice(control);
        blossom_in_place(knots, p, span, s, count_a, a, b)
    })
}

/// [`blossom`] on control values already in `s` (overwritten).
fn blossom_in_place<T: Coefficient>(
    knots: &[f64],
    p: usize,
    span: usize,
    s: &mut [T],
    count_a: usize,
    a: f64,
    b: f64,
) -> T {
    for level in 1..=p {
        let u = if level <= count_a { a } else { b };
        de_boor_level(knots, p, span, s, u, level);
    }
    s[p]
}

/// The Bézier control values of the polynomial on the non-empty knot span
/// `span`, whose `p + 1` control values (global indices `span − p … span`)
/// are `control`, written to `out[..=p]`: the blossoms
/// `bᵣ = f(a, …, a, b, …, b)` (`p − r` times `a`, `r` times `b`) on
/// `[a, b] = [t_span, t_{span+1}]` (Ramshaw's blossoming principle).
pub(crate) fn span_bezier_points<T: Coefficient>(
    knots: &[f64],
    p: usize,
    span: usize,
    control: &[T],
    out: &mut [T],
) {
    let (a, b) = (knots[span], knots[span + 1]);
    for (r, dst) in out.iter_mut().enumerate().take(p + 1) {
        *dst = blossom(knots, control, p, span, p - r, a, b);
    }
}

/// Replaces the control values of the `(r − 1)`-th derivative spline that act
/// on `span`, in `s[..=p − r + 1]`, by those of the `r`-th, in `s[..=p − r]`:
/// `Q⁽ʳ⁾ⱼ = (Q⁽ʳ⁻¹⁾ⱼ₊₁ − Q⁽ʳ⁻¹⁾ⱼ)/(t_{j+p+1} − t_{j+r})·(p − r + 1)` (Piegl &
/// Tiller eq. 3.8; the knot difference contains the non-empty span, so it is
/// positive). Generic: vectors for a polynomial spline, homogeneous points
/// for a rational one.
#[inline(always)]
pub(crate) fn derivative_control_step<T>(
    knots: &[f64],
    p: usize,
    span: usize,
    s: &mut [T],
    r: usize,
) where
    T: Coefficient + Div<f64, Output = T>,
{
    for j in 0..=(p - r) {
        // Control value span − p + j of the r-th derivative spline.
        let gap = derivative_gap(knots, p, span - p + j, r);
        s[j] = derivative_control(s[j], s[j + 1], gap, p, r);
    }
}

/// De Boor's algorithm at `t` for degree `q` on `s[0..=q]`, which holds the
/// coefficients with global indices `span − q … span` (overwritten): the
/// value of the spline at `t`.
#[inline(always)]
pub(crate) fn de_boor<T: Coefficient>(
    knots: &[f64],
    q: usize,
    span: usize,
    s: &mut [T],
    t: f64,
) -> T {
    for level in 1..=q {
        de_boor_level(knots, q, span, s, t, level);
    }
    s[q]
}

/// Level `level` of de Boor's algorithm at argument `u`: for local index
/// `j = q … level` (global `l = span − q + j`),
/// `sⱼ ← lerp(sⱼ₋₁, sⱼ, (u − t_l)/(t_{l+q+1−level} − t_l))`. The knot interval
/// always contains the non-empty span, so the division is safe.
#[inline(always)]
fn de_boor_level<T: Coefficient>(
    knots: &[f64],
    q: usize,
    span: usize,
    s: &mut [T],
    u: f64,
    level: usize,
) {
    for j in (level..=q).rev() {
        let l = span - q + j;
        let lo = knots[l];
        let hi = knots[l + q + 1 - level];
        s[j] = lerp(s[j - 1], s[j], (u - lo) / (hi - lo));
    }
}

/// The knot difference `t_{i+p+1} − t_{i+r}` that divides the control value
/// `i` of the order-`r` derivative spline (Piegl & Tiller eq. 3.8); zero
/// where that value's basis function vanishes identically.
#[inline(always)]
pub(crate) fn derivative_gap(knots: &[f64], p: usize, i: usize, r: usize) -> f64 {
    knots[i + p + 1] - knots[i + r]
}

/// A control value of the order-`r` derivative spline from two neighbouring
/// ones of order `r − 1`: `(b − a)/gap·(p − r + 1)`, with `gap` from
/// [`derivative_gap`] (positive).
#[inline(always)]
pub(crate) fn derivative_control<T>(a: T, b: T, gap: f64, p: usize, r: usize) -> T
where
    T: Coefficient + Div<f64, Output = T>,
{
    (b - a) / gap * (p - r + 1) as f64
}

/// Checks the control points of the derivative splines of orders
/// `1 ..= degree`, computed as [`BSpline::nth_derivative`](crate::BSpline::nth_derivative) computes them,
/// `Q⁽ʳ⁾ᵢ = (Q⁽ʳ⁻¹⁾ᵢ₊₁ − Q⁽ʳ⁻¹⁾ᵢ)/(tᵢ₊ₚ₊₁ − tᵢ₊ᵣ)·(p − r + 1)`: each must be
/// within [`MAX_DERIVATIVE`]. Points whose knot difference is zero (their basis
/// function vanishes; no non-empty span uses them) are skipped, and so is
/// everything computed from them.
pub(crate) fn check_derivative_points<const D: usize>(
    degree: usize,
    knots: &[f64],
    points: &[Point<f64, D>],
) -> Result<(), Error> {
    let mut q: Vec<Option<SVector<f64, D>>> = points.iter().map(|p| Some(p.coords)).collect();
    for order in 1..=degree {
        for i in 0..q.len() - 1 {
            let gap = derivative_gap(knots, degree, i, order);
            q[i] = match (q[i], q[i + 1]) {
                (Some(a), Some(b)) if gap > 0.0 => {
                    let d = derivative_control(a, b, gap, degree, order);
                    if !d.iter().all(|x| x.abs() <= MAX_DERIVATIVE) {
                        return Err(Error::DerivativeOverflow { order });
                    }
                    Some(d)
                }
                _ => None,
            };
        }
        q.pop();
    }
    Ok(())
}

/// The knot that inserting `t` `times` times into `knots` (degree `degree`,
/// domain `domain`) inserts: `t` itself, or an existing knot within rounding
/// (`4ε ×` the knot range) of it, so that the result satisfies the rules of
/// [`BSpline::new`](crate::BSpline::new).
///
/// # Errors
/// [`Error::ParameterOutOfDomain`] if `t` is NaN or outside the domain;
/// [`Error::KnotMultiplicity`] if the knot would then occur more than
/// `degree + 1` times.
pub(crate) fn knot_to_insert(
    knots: &[f64],
    degree: usize,
    domain: (f64, f64),
    t: f64,
    times: usize,
) -> Result<f64, Error> {
    check_in_domain(t, domain)?;
    // A parameter closer to an existing knot than rounding can resolve
    // (see `Error::KnotGapTooSmall`) is that knot.
    let min_gap = min_knot_gap(knots);
    let t = knots
        .iter()
        .copied()
        .find(|&k| (k - t).abs() < min_gap)
        .unwrap_or(t);
    let existing = knots.iter().filter(|&&k| k == t).count();
    let multiplicity = existing.saturating_add(times);
    if multiplicity > degree + 1 {
        return Err(Error::KnotMultiplicity {
            knot: t,
            multiplicity,
            max: degree + 1,
        });
    }
    Ok(t)
}

/// One Boehm insertion of the knot `t` into knot span `k`
/// (`t_k ≤ t ≤ t_{k+1}`, a non-empty span): the new control values are
/// `Qⱼ = combine(Pⱼ₋₁, Pⱼ, αⱼ)`, meant as `(1 − αⱼ)Pⱼ₋₁ + αⱼPⱼ` with
/// `αⱼ = (t − tⱼ)/(tⱼ₊ₚ − tⱼ)`, for `k − p < j ≤ k`; the others are kept
/// (Piegl & Tiller, eq. 5.15). Returns the new knots and control values.
/// Generic over the control values: points of a polynomial spline, points
/// with weights of a rational one.
pub(crate) fn boehm_insert<T: Copy>(
    knots: &[f64],
    p: usize,
    k: usize,
    t: f64,
    control: &[T],
    combine: impl Fn(T, T, f64) -> T,
) -> (Vec<f64>, Vec<T>) {
    let mut values = Vec::with_capacity(control.len() + 1);
    values.extend_from_slice(&control[..=k - p]);
    for j in (k - p + 1)..=k {
        let alpha = (t - knots[j]) / (knots[j + p] - knots[j]);
        values.push(combine(control[j - 1], control[j], alpha));
    }
    values.extend_from_slice(&control[k..]);
    let mut new_knots = Vec::with_capacity(knots.len() + 1);
    new_knots.extend_from_slice(&knots[..=k]);
    new_knots.push(t);
    new_knots.extend_from_slice(&knots[k + 1..]);
    (new_knots, values)
}

/// `curve` with the knot `t` inserted `times` times: `t` made a valid knot
/// to insert by [`knot_to_insert`] (for the curve's `knots`, `degree` and
/// `domain`), then `insert_once` (a Boehm insertion, [`boehm_insert`])
/// `times` times.
///
/// # Errors
/// Those of [`knot_to_insert`] and of `insert_once`.
pub(crate) fn insert_knot<C: Clone>(
    curve: &C,
    (knots, degree, domain): (&[f64], usize, (f64, f64)),
    t: f64,
    times: usize,
    insert_once: impl Fn(&C, f64) -> Result<C, Error>,
) -> Result<C, Error> {
    let t = knot_to_insert(knots, degree, domain, t, times)?;
    let mut curve = curve.clone();
    for _ in 0..times {
        curve = insert_once(&curve, t)?;
    }
    Ok(curve)
}

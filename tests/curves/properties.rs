//! Property tests of the curve layer (proptest).
//!
//! Every property is a generic function over the dimension `D` and runs for
//! `D = 1, 2, 3` (see the `properties!` table at the end). The strategies
//! generate Bézier curves of degree 0–12 and B-splines of degree 0–12 with
//! random valid knot vectors (repeated knots up to full multiplicity, also in
//! the interior), plus the `uniform` and `clamped` constructors, with control
//! points in about `[-10, 10]` (now and then repeating their predecessor
//! exactly or up to a tiny offset).
//!
//! Properties (one module each, tests `dim_1`, `dim_2`, `dim_3`):
//! derivatives of orders 1–3 against central differences (Bézier, B-spline);
//! de Casteljau against the Bernstein sum; B-spline basis functions (partition
//! of unity, non-negativity, local support against a textbook Cox–de Boor
//! recursion, `Σ Nᵢ Pᵢ = eval`, basis derivatives against `nth_derivative`);
//! a B-spline against its Bézier spans; knot insertion; Bézier subdivision;
//! the full-degree clamped B-spline against the Bézier curve; the
//! `uniform`/`clamped` knot vectors; derivative splines and hodographs;
//! flattening; uniform discretization; evaluation outside the domain. Two
//! plain tests pin down the smallest failing cases found for library bugs.
//!
//! # Tolerances
//! No tolerance is a bare magic number: each one is a bound on the rounding
//! error (or truncation error) of the computation being compared, derived from
//! the control points of the polynomial piece involved; see [`Magnitudes`]
//! and [`fd_tolerance`].

use proptest::collection::{SizeRange, vec};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::TestCaseError;
use revolve::bernstein::bernstein_sum;
use revolve::nalgebra::{Point, SVector};
use revolve::{BSpline, Bezier, Curve, CurveSample, Error, Flattening};

const EPS: f64 = f64::EPSILON;

/// Largest degree generated.
const MAX_DEGREE: usize = 12;

/// Test configuration: `cases` cases, no regression files written.
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

// ---------------------------------------------------------------------------
// Strategies
// ---------------------------------------------------------------------------

/// `count` control points with coordinates in `[-10, 10]`. One point in ten
/// repeats its predecessor exactly and one in ten repeats it up to an offset of
/// size `1e-13 … 0.1` (degenerate control polygons, tiny jumps at knots of
/// full multiplicity).
fn control_points<const D: usize>(
    count: impl Into<SizeRange>,
) -> impl Strategy<Value = Vec<Point<f64, D>>> {
    let raw = (
        proptest::array::uniform::<_, D>(-10.0..=10.0f64),
        0u8..10,
        -14i32..=-2,
    );
    vec(raw, count).prop_map(|raw| {
        let mut points: Vec<Point<f64, D>> = Vec::with_capacity(raw.len());
        for (coords, kind, exponent) in raw {
            let fresh = Point::from(coords);
            let point = match (points.last(), kind) {
                (Some(&prev), 0) => prev,
                (Some(&prev), 1) => prev + fresh.coords * 10f64.powi(exponent),
                _ => fresh,
            };
            points.push(point);
        }
        points
    })
}

/// A valid knot vector for degree `p` and `n` control points: `n + p + 1`
/// non-decreasing knots starting in `[-3, 3]` with gaps in `[0.05, 1]` or zero
/// (three in ten), multiplicities capped at `p + 1`, in four cases of ten one
/// forced run of full multiplicity `p + 1` (in the interior of the domain when
/// there is room for it, `n ≥ 2p + 2`, in half of those), and a non-empty
/// domain `[t_p, t_n]`.
fn knot_vector(p: usize, n: usize) -> impl Strategy<Value = Vec<f64>> {
    let len = n + p + 1;
    (
        -3.0..3.0f64,
        vec((0u8..10, 0.05..=1.0f64), len - 1),
        proptest::option::weighted(0.4, (any::<bool>(), any::<Index>())),
    )
        .prop_map(move |(offset, steps, full_run)| {
            // gaps[i] = t_{i+1} − t_i.
            let mut gaps: Vec<f64> = steps
                .iter()
                .map(|&(zero, gap)| if zero < 3 { 0.0 } else { gap })
                .collect();
            // The run t_s = … = t_{s+p} lies inside (t_p, t_n) iff p < s < n − p.
            let full_run = full_run.map(|(interior, at)| {
                if interior && n >= 2 * p + 2 {
                    p + 1 + at.index(n - 2 * p - 1)
                } else {
                    at.index(len - p)
                }
            });
            if let Some(start) = full_run {
                // Knots t_start … t_{start+p} equal, their neighbours distinct.
                gaps[start..start + p].fill(0.0);
                if start > 0 {
                    gaps[start - 1] = steps[start - 1].1;
                }
                if start + p < gaps.len() {
                    gaps[start + p] = steps[start + p].1;
                }
            }
            // Cap every run of equal knots at p + 1.
            let mut run = 1;
            for (gap, &(_, fallback)) in gaps.iter_mut().zip(&steps) {
                if *gap == 0.0 {
                    run += 1;
                    if run > p + 1 {
                        *gap = fallback;
                        run = 1;
                    }
                } else {
                    run = 1;
                }
            }
            // Non-empty domain: some gap between t_p and t_n is positive.
            if gaps[p..n].iter().all(|&g| g == 0.0) {
                gaps[p] = steps[p].1;
            }
            let mut knots = Vec::with_capacity(len);
            knots.push(offset);
            for gap in gaps {
                knots.push(knots[knots.len() - 1] + gap);
            }
            knots
        })
}

/// A B-spline of degree `p` = 0–12 with `p + 1 … 2p + 9` control points: six
/// in ten from `BSpline::new` with a random knot vector, two in ten `uniform`,
/// two in ten `clamped`. Where the curve may jump (an interior knot of full
/// multiplicity), in one case of three the jump is made small (`1e-10 … 0.17`,
/// the range of flattening tolerances).
fn spline<const D: usize>() -> impl Strategy<Value = BSpline<D>> {
    (0..=MAX_DEGREE, 0u8..10)
        .prop_flat_map(|(p, kind)| (Just(p), Just(kind), 0..=p + 8))
        .prop_flat_map(|(p, kind, extra)| {
            let n = p + 1 + extra;
            let small_jump = (
                0u8..3,
                -10i32..=-1,
                proptest::array::uniform::<_, D>(-1.0..=1.0f64),
            );
            (
                Just(p),
                Just(kind),
                control_points::<D>(n),
                knot_vector(p, n),
                small_jump,
            )
        })
        .prop_map(|(p, kind, mut points, knots, (jump, exponent, offset))| {
            match kind {
                0 | 1 => BSpline::uniform(p, points),
                2 | 3 => BSpline::clamped(p, points),
                _ => {
                    if jump == 0 {
                        if let Some(s) = interior_jump(&knots, p, points.len()) {
                            // The curve jumps from P_{s−1} to P_s there.
                            let offset = SVector::from(offset) * 10f64.powi(exponent);
                            points[s] = points[s - 1] + offset;
                        }
                    }
                    BSpline::new(p, knots, points)
                }
            }
            .expect("the strategy generates valid B-splines")
        })
}

/// The first index `s` of the first run `t_s = … = t_{s+p}` of full
/// multiplicity strictly inside the domain `(t_p, t_n)`, if any: there the
/// curve may jump, from `P_{s−1}` (left limit) to `P_s` (value).
fn interior_jump(knots: &[f64], p: usize, n: usize) -> Option<usize> {
    let (a, b) = (knots[p], knots[n]);
    (1..knots.len()).find(|&s| {
        let k = knots[s];
        a < k
            && k < b
            && knots[s - 1] < k
            && knots[s..].iter().take_while(|&&x| x == k).count() == p + 1
    })
}

/// A Bézier curve of degree 0–12.
fn bezier<const D: usize>() -> impl Strategy<Value = Bezier<D>> {
    control_points::<D>(1..=MAX_DEGREE + 1)
        .prop_map(|points| Bezier::new(points).expect("the strategy generates valid points"))
}

/// A B-spline with eight (span choice, relative position) pairs.
fn spline_and_params<const D: usize>() -> impl Strategy<Value = (BSpline<D>, Vec<(Index, f64)>)> {
    (spline::<D>(), vec((any::<Index>(), 0.0..1.0f64), 8))
}

/// A Bézier curve with eight parameters in `[0, 1)`.
fn bezier_and_params<const D: usize>() -> impl Strategy<Value = (Bezier<D>, Vec<f64>)> {
    (bezier::<D>(), vec(0.0..1.0f64, 8))
}

// ---------------------------------------------------------------------------
// Reference mathematics and error bounds
// ---------------------------------------------------------------------------

/// Size bounds for one polynomial piece (a B-spline on one knot span, or a
/// Bézier curve, which is the span `[0, 1]` of clamped knots), computed from
/// its control points. Every tolerance in this file is built from them.
///
/// Let `Q⁽ʳ⁾` be the control points of the `r`-th derivative spline acting on
/// the span, `Q⁽ʳ⁾ⱼ = (p − r + 1)(Q⁽ʳ⁻¹⁾ⱼ₊₁ − Q⁽ʳ⁻¹⁾ⱼ)/(t_{j+p+1} − t_{j+r})`
/// (every denominator is at least the span width `w`; for a Bézier curve
/// these are the hodographs).
///
/// - `bound(r) = maxⱼ |Q⁽ʳ⁾ⱼ|` bounds `|f⁽ʳ⁾(t)|` on the span: the basis
///   functions are non-negative and sum to one (convex hull property).
/// - `size(j) = max_{r ≤ j} bound(r) · Π_{s=r+1..j} 2(p − s + 1)/w` bounds
///   every intermediate value of a `j`-th derivative evaluation *and* how
///   much a relative perturbation of the level-`r` values grows by the time it
///   reaches level `j` (each differencing step multiplies by at most
///   `2(p − s + 1)/w`).
/// - `rounding(j) = 16 ε (p + j + 1) size(j)` bounds the rounding error of one
///   evaluation of `f⁽ʲ⁾` by the library's algorithms. Each step (a level of
///   convex combinations `(1 − α)a + αb` with `α = (u − tₗ)/(t_h − tₗ)`
///   computed to a small *relative* error, or a differencing step) adds at
///   most 9 unit roundoffs, `4.5 ε size(j)`; earlier errors are carried along
///   by convex combinations (no growth) or grow by the differences, as
///   accounted for in `size`. An evaluation takes at most `2p + 1` steps
///   (blossoming the span into Bézier form, then de Casteljau; or
///   differencing, then de Boor), and the rounding of `u = (t − a)/w` (at most
///   `2ε` relative) moves `t` by at most `2εw`, hence `f⁽ʲ⁾` by at most
///   `2εw · bound(j + 1) ≤ 4pε size(j)`. In all at most
///   `ε (13p + 4.5j + 4.5) size(j) ≤ rounding(j)`: a relative tolerance of
///   about `1e-13` of the magnitudes involved.
#[derive(Debug, Clone)]
struct Magnitudes {
    degree: usize,
    bound: Vec<f64>,
    size: Vec<f64>,
}

impl Magnitudes {
    /// Bounds for the polynomial of the B-spline (`knots`, `points`, degree
    /// `p`) on the non-empty span `[t_span, t_{span+1})`.
    fn of_span<const D: usize>(
        knots: &[f64],
        points: &[Point<f64, D>],
        p: usize,
        span: usize,
    ) -> Self {
        let w = knots[span + 1] - knots[span];
        assert!(w > 0.0, "span {span} is empty");
        let mut level: Vec<SVector<f64, D>> =
            points[span - p..=span].iter().map(|q| q.coords).collect();
        let mut bound = vec![max_norm(&level)];
        for r in 1..=p {
            level = (0..=p - r)
                .map(|j| {
                    let g = span - p + j;
                    let den = knots[g + p + 1] - knots[g + r];
                    (level[j + 1] - level[j]) * ((p - r + 1) as f64 / den)
                })
                .collect();
            bound.push(max_norm(&level));
        }
        let size = (0..=p)
            .map(|j| {
                (0..=j)
                    .map(|r| {
                        let growth: f64 =
                            (r + 1..=j).map(|s| 2.0 * (p - s + 1) as f64 / w).product();
                        bound[r] * growth
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        Self {
            degree: p,
            bound,
            size,
        }
    }

    /// Bounds for a Bézier curve on `[0, 1]`.
    fn of_bezier<const D: usize>(points: &[Point<f64, D>]) -> Self {
        let p = points.len() - 1;
        let knots: Vec<f64> = (0..2 * (p + 1))
            .map(|i| if i <= p { 0.0 } else { 1.0 })
            .collect();
        Self::of_span(&knots, points, p, p)
    }

    /// Bounds valid on every span of a B-spline (the maximum over spans).
    fn of_spline<const D: usize>(spline: &BSpline<D>) -> Self {
        let p = spline.degree();
        nonempty_spans(spline)
            .into_iter()
            .map(|span| Self::of_span(spline.knots(), spline.points(), p, span))
            .reduce(|a, b| Self {
                degree: p,
                bound: a
                    .bound
                    .iter()
                    .zip(&b.bound)
                    .map(|(x, y)| x.max(*y))
                    .collect(),
                size: a.size.iter().zip(&b.size).map(|(x, y)| x.max(*y)).collect(),
            })
            .expect("a B-spline has a non-empty span")
    }

    /// Bound on `|f⁽ʳ⁾|` over the piece (zero above the degree).
    fn bound(&self, r: usize) -> f64 {
        self.bound.get(r).copied().unwrap_or(0.0)
    }

    /// Bound on the intermediates of an order-`j` evaluation (zero above the
    /// degree, where the derivative is returned as an exact zero).
    fn size(&self, j: usize) -> f64 {
        self.size.get(j).copied().unwrap_or(0.0)
    }

    /// Bound on the rounding error of one evaluation of `f⁽ʲ⁾`.
    fn rounding(&self, j: usize) -> f64 {
        16.0 * EPS * (self.degree + j + 1) as f64 * self.size(j)
    }
}

/// Allowed `|D_h f⁽ᵏ⁻¹⁾(t) − f⁽ᵏ⁾(t)|` for the central difference
/// `D_h g(t) = (g(t + h) − g(t − h)) / ((t + h) − (t − h))`, where `f⁽ᵏ⁻¹⁾` and
/// `f⁽ᵏ⁾` are evaluated analytically (so errors do not compound over orders),
/// `t ± h` lie in one polynomial piece, and `|t| ≤ t_max`.
///
/// - Truncation: Taylor's theorem gives `h²/6 · max|f⁽ᵏ⁺²⁾|`.
/// - Rounding of the two evaluations of `f⁽ᵏ⁻¹⁾`, divided by the step `2h`:
///   `rounding(k − 1)/h`.
/// - Rounding of `t ± h` (up to `ε|t|/2` each) moves the midpoint of the
///   stencil off `t`: `ε t_max · max|f⁽ᵏ⁺¹⁾|`. (The step is the computed
///   difference `(t + h) − (t − h)`, exact or within `ε` relative; the latter
///   is covered by the next term.)
/// - Rounding of the analytic value itself: `rounding(k)`.
///
/// With `h ≈ cbrt(ε)·w ≈ 1e-5·w` for a piece of width `w` (derivatives scale
/// like `w⁻ʲ`) the truncation term (`∝ h²`) and the rounding term (`∝ ε/h`)
/// are roughly balanced, and the tolerance is at most about `1e-8 × size(k)`
/// (truncation: `h²/6 · (2p/w)² ≈ 1e-8` for `p = 12`; rounding: about
/// `16 ε (p + k) / (1e-5 · 2(p − k + 1)) ≈ 1e-9`): an error in a derivative
/// formula (a wrong factor, knot difference or span) is larger by orders of
/// magnitude.
fn fd_tolerance(m: &Magnitudes, k: usize, h: f64, t_max: f64) -> f64 {
    h * h / 6.0 * m.bound(k + 2)
        + m.rounding(k - 1) / h
        + EPS * t_max * m.bound(k + 1)
        + m.rounding(k)
}

/// The largest Euclidean norm in `v` (zero for an empty slice).
fn max_norm<const D: usize>(v: &[SVector<f64, D>]) -> f64 {
    v.iter().map(|x| x.norm()).fold(0.0, f64::max)
}

/// The largest absolute coordinate of the points (the scale the flattening
/// and the Bernstein comparison are relative to).
fn coordinate_scale<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points.iter().map(|p| p.coords.amax()).fold(0.0, f64::max)
}

/// Indices `i` (`p ≤ i < n`) of the non-empty knot spans `[tᵢ, tᵢ₊₁)` of the
/// domain.
fn nonempty_spans<const D: usize>(spline: &BSpline<D>) -> Vec<usize> {
    let knots = spline.knots();
    (spline.degree()..spline.points().len())
        .filter(|&i| knots[i] < knots[i + 1])
        .collect()
}

/// All `knots.len() − p − 1` B-spline basis functions `N_{i,p}(t)` by the
/// textbook Cox–de Boor recursion (tabulated bottom-up): `N_{i,0}(t) = 1` on
/// `[tᵢ, tᵢ₊₁)` and 0 elsewhere, and
/// `N_{i,q} = (t − tᵢ)/(t_{i+q} − tᵢ) N_{i,q−1} + (t_{i+q+1} − t)/(t_{i+q+1} − t_{i+1}) N_{i+1,q−1}`
/// with a term taken as 0 where its denominator is 0.
fn cox_de_boor(knots: &[f64], p: usize, t: f64) -> Vec<f64> {
    let ratio = |num: f64, den: f64| if den == 0.0 { 0.0 } else { num / den };
    let m = knots.len() - 1;
    let mut n: Vec<f64> = (0..m)
        .map(|i| {
            if knots[i] <= t && t < knots[i + 1] {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    for q in 1..=p {
        n = (0..m - q)
            .map(|i| {
                ratio(t - knots[i], knots[i + q] - knots[i]) * n[i]
                    + ratio(knots[i + q + 1] - t, knots[i + q + 1] - knots[i + 1]) * n[i + 1]
            })
            .collect();
    }
    n
}

/// The distance from `x` to the segment `[a, b]`.
fn distance_to_segment<const D: usize>(
    x: Point<f64, D>,
    a: Point<f64, D>,
    b: Point<f64, D>,
) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let s = if len2 > 0.0 {
        ((x - a).dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - (a + ab * s)).norm()
}

/// `count + 1` uniformly spaced parameters covering `[a, b]`, ends exact.
fn uniform_params(a: f64, b: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..=count).map(move |i| {
        if i == count {
            b
        } else {
            a + (b - a) * (i as f64 / count as f64)
        }
    })
}

/// Parameters for dense comparisons over a B-spline's domain: 100 uniform
/// intervals plus every knot inside the domain.
fn dense_params<const D: usize>(spline: &BSpline<D>) -> Vec<f64> {
    let (a, b) = spline.domain();
    uniform_params(a, b, 100)
        .chain(spline.knots().iter().copied().filter(|&k| a <= k && k <= b))
        .collect()
}

/// Asserts `|got − want| ≤ tolerance`.
fn assert_close<const D: usize>(
    got: SVector<f64, D>,
    want: SVector<f64, D>,
    tolerance: f64,
    what: &str,
) -> Result<(), TestCaseError> {
    let err = (got - want).norm();
    prop_assert!(
        err <= tolerance,
        "{what}: |got − want| = {err:e} > {tolerance:e}\n got  = {got:?}\n want = {want:?}"
    );
    Ok(())
}

/// Checks that `BSpline::new` accepts the parts (degree, knots, points) of a
/// B-spline an operation returned: the operation kept the invariants the
/// constructor establishes.
fn check_valid_parts<const D: usize>(spline: &BSpline<D>, what: &str) -> Result<(), TestCaseError> {
    let rebuilt = BSpline::new(
        spline.degree(),
        spline.knots().to_vec(),
        spline.points().to_vec(),
    );
    prop_assert!(
        rebuilt.is_ok(),
        "{} returned a B-spline that BSpline::new rejects: {:?}\n knots = {:?}",
        what,
        rebuilt.err(),
        spline.knots()
    );
    Ok(())
}

/// Checks one central difference: `lower` is `f⁽ᵏ⁻¹⁾`, `exact` is `f⁽ᵏ⁾(t)`.
fn check_central_difference<const D: usize>(
    lower: impl Fn(f64) -> SVector<f64, D>,
    exact: SVector<f64, D>,
    t: f64,
    h: f64,
    tolerance: f64,
    what: &str,
) -> Result<(), TestCaseError> {
    let (tp, tm) = (t + h, t - h);
    let difference = (lower(tp) - lower(tm)) / (tp - tm);
    assert_close(
        exact,
        difference,
        tolerance,
        &format!("{what} vs central difference at t = {t} (h = {h:e})"),
    )
}

// ---------------------------------------------------------------------------
// 1. Derivatives against central differences
// ---------------------------------------------------------------------------

/// Bézier: `derivative`, `nth_derivative` of orders 1–3 against central
/// differences of the next lower order, for `t ∈ [0.05, 0.95]` and
/// `h = 1e-5` (the domain has length 1). Orders above the degree are zero.
fn bezier_derivatives_match_central_differences<const D: usize>(
    (curve, params): (Bezier<D>, Vec<f64>),
) -> Result<(), TestCaseError> {
    let m = Magnitudes::of_bezier(curve.points());
    let h = 1e-5;
    for u in params {
        let t = 0.05 + 0.9 * u;
        let tol = |k| fd_tolerance(&m, k, h, 1.0);
        let value = |s: f64| curve.eval(s).coords;
        // Two evaluations of the point, each within rounding(0).
        assert_close(
            curve.nth_derivative(t, 0).unwrap(),
            value(t),
            2.0 * m.rounding(0),
            "nth(0) vs eval",
        )?;
        check_central_difference(value, curve.derivative(t), t, h, tol(1), "derivative")?;
        check_central_difference(
            value,
            curve.nth_derivative(t, 1).unwrap(),
            t,
            h,
            tol(1),
            "nth(1)",
        )?;
        let first = |s: f64| curve.derivative(s);
        check_central_difference(
            first,
            curve.nth_derivative(t, 2).unwrap(),
            t,
            h,
            tol(2),
            "nth(2)",
        )?;
        let second = |s: f64| curve.nth_derivative(s, 2).unwrap();
        check_central_difference(
            second,
            curve.nth_derivative(t, 3).unwrap(),
            t,
            h,
            tol(3),
            "nth(3)",
        )?;
        let above = curve.degree() + 1;
        prop_assert_eq!(
            curve.nth_derivative(t, above).unwrap(),
            SVector::<f64, D>::zeros()
        );
    }
    Ok(())
}

/// B-spline: the same, at `t = a + w(0.05 + 0.9u)` in a random non-empty span
/// `[a, b)` of width `w` with `h = 1e-5·w`, so `t ± h` stay inside the span
/// (the derivatives may jump at knots).
fn spline_derivatives_match_central_differences<const D: usize>(
    (spline, params): (BSpline<D>, Vec<(Index, f64)>),
) -> Result<(), TestCaseError> {
    let spans = nonempty_spans(&spline);
    let knots = spline.knots();
    for (index, u) in params {
        let span = spans[index.index(spans.len())];
        let (a, b) = (knots[span], knots[span + 1]);
        let w = b - a;
        let t = a + w * (0.05 + 0.9 * u);
        let h = 1e-5 * w;
        let m = Magnitudes::of_span(knots, spline.points(), spline.degree(), span);
        let tol = |k| fd_tolerance(&m, k, h, a.abs().max(b.abs()));
        let value = |s: f64| spline.eval(s).coords;
        // de Boor on the control points vs the span's Bézier form: each within
        // rounding(0) of the curve.
        assert_close(
            spline.nth_derivative(t, 0).unwrap(),
            value(t),
            2.0 * m.rounding(0),
            "nth(0) vs eval",
        )?;
        check_central_difference(value, spline.derivative(t), t, h, tol(1), "derivative")?;
        check_central_difference(
            value,
            spline.nth_derivative(t, 1).unwrap(),
            t,
            h,
            tol(1),
            "nth(1)",
        )?;
        let first = |s: f64| spline.derivative(s);
        check_central_difference(
            first,
            spline.nth_derivative(t, 2).unwrap(),
            t,
            h,
            tol(2),
            "nth(2)",
        )?;
        let second = |s: f64| spline.nth_derivative(s, 2).unwrap();
        check_central_difference(
            second,
            spline.nth_derivative(t, 3).unwrap(),
            t,
            h,
            tol(3),
            "nth(3)",
        )?;
        let above = spline.degree() + 1;
        prop_assert_eq!(
            spline.nth_derivative(t, above).unwrap(),
            SVector::<f64, D>::zeros()
        );
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 2. de Casteljau against the Bernstein sum
// ---------------------------------------------------------------------------

/// `Bezier::eval` (de Casteljau) equals `bernstein_sum` on each coordinate to
/// `1e-12 ×` the control-point scale, at random parameters and at 0, ½, 1.
/// (The Bernstein sum is accurate to about `(2n + 4) ε ×` the scale.)
fn de_casteljau_matches_bernstein_sum<const D: usize>(
    (curve, params): (Bezier<D>, Vec<f64>),
) -> Result<(), TestCaseError> {
    let scale = coordinate_scale(curve.points());
    let coords: Vec<Vec<f64>> = (0..D)
        .map(|d| curve.points().iter().map(|p| p[d]).collect())
        .collect();
    for t in params.into_iter().chain([0.0, 0.5, 1.0]) {
        let point = curve.eval(t);
        for (d, c) in coords.iter().enumerate() {
            let reference = bernstein_sum(c, t).expect("non-empty");
            let err = (point[d] - reference).abs();
            prop_assert!(
                err <= 1e-12 * scale,
                "coordinate {d} at t = {t}: de Casteljau {} vs Bernstein sum {reference} (error {err:e})",
                point[d]
            );
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 3. Basis functions
// ---------------------------------------------------------------------------

/// `basis_functions` at `t` in a random non-empty span `[tᵢ, tᵢ₊₁)` (its left
/// end included, where the half-open rule decides): the returned first index
/// is `i − p`; the values are non-negative, sum to 1 within `1e-13`, and match
/// the textbook recursion over all `n` functions, which is exactly zero
/// outside `i − p … i` (local support). `Σ Nⱼ Pⱼ` equals `eval(t)`;
/// `basis_derivatives` of order 0 equals the values and of order `k ≤ 3`
/// gives `Σ Nⱼ⁽ᵏ⁾ Pⱼ = nth_derivative(t, k)`; orders above `p` are zero.
///
/// Both basis evaluations make a relative error of at most about `5 ε` per
/// level of the recursion (two subtractions or a sum, a division, a
/// product, a sum of non-negative terms), so they agree within `16 (p + 1) ε`.
fn basis_functions_are_a_local_partition_of_unity<const D: usize>(
    (spline, params): (BSpline<D>, Vec<(Index, f64)>),
) -> Result<(), TestCaseError> {
    let p = spline.degree();
    let knots = spline.knots();
    let points = spline.points();
    let spans = nonempty_spans(&spline);
    let basis_tol = 16.0 * (p + 1) as f64 * EPS;
    let mut values = vec![0.0; p + 1];
    let mut derivatives = vec![0.0; 4 * (p + 1)];
    let result = spline.basis_functions(0.0, &mut values[..p]);
    prop_assert!(
        matches!(result, Err(Error::BufferLength { .. })),
        "spline.basis_functions: expected Error::BufferLength, got {:?}",
        result
    );
    for (k, (index, u)) in params.into_iter().enumerate() {
        let span = spans[index.index(spans.len())];
        let (a, b) = (knots[span], knots[span + 1]);
        // The first sample sits on the knot itself; the others strictly inside.
        let t = if k == 0 {
            a
        } else {
            a + (b - a) * (0.001 + 0.998 * u)
        };
        prop_assert!(a <= t && t < b);

        let first = spline.basis_functions(t, &mut values)?;
        prop_assert_eq!(first + p, span, "first index at t = {}", t);
        prop_assert_eq!(spline.span(t), span, "span at t = {}", t);
        prop_assert!(values.iter().all(|&v| v >= 0.0), "negative: {:?}", values);
        let sum: f64 = values.iter().sum();
        prop_assert!((sum - 1.0).abs() <= 1e-13, "sum {} at t = {}", sum, t);

        let reference = cox_de_boor(knots, p, t);
        prop_assert_eq!(reference.len(), points.len());
        for (j, &r) in reference.iter().enumerate() {
            if (first..=first + p).contains(&j) {
                let v = values[j - first];
                prop_assert!(
                    (v - r).abs() <= basis_tol,
                    "N_{}({}) = {} but Cox–de Boor gives {}",
                    j,
                    t,
                    v,
                    r
                );
            } else {
                prop_assert_eq!(r, 0.0, "N_{} is outside the support but nonzero", j);
            }
        }

        let m = Magnitudes::of_span(knots, points, p, span);
        let combination: SVector<f64, D> = values
            .iter()
            .zip(&points[first..=first + p])
            .map(|(&n, q)| q.coords * n)
            .sum();
        let tol = 2.0 * m.rounding(0) + (p + 1) as f64 * EPS * m.bound(0);
        assert_close(combination, spline.eval(t).coords, tol, "Σ Nⱼ Pⱼ vs eval")?;

        let first_d = spline.basis_derivatives(t, 3, &mut derivatives)?;
        prop_assert_eq!(first_d, first);
        for (d, v) in derivatives[..=p].iter().zip(&values) {
            prop_assert!((d - v).abs() <= basis_tol, "order-0 row {} vs {}", d, v);
        }
        for order in 1..=3 {
            let row = &derivatives[order * (p + 1)..(order + 1) * (p + 1)];
            if order > p {
                prop_assert!(
                    row.iter().all(|&x| x == 0.0),
                    "order {} row {:?}",
                    order,
                    row
                );
                continue;
            }
            let combination: SVector<f64, D> = row
                .iter()
                .zip(&points[first..=first + p])
                .map(|(&n, q)| q.coords * n)
                .sum();
            // Σ |Nⱼ⁽ᵏ⁾| |Pⱼ| ≤ (p + 1) size(k): p + 2 rounding budgets in all.
            let tol = (p + 2) as f64 * m.rounding(order);
            assert_close(
                combination,
                spline.nth_derivative(t, order).unwrap(),
                tol,
                &format!("Σ Nⱼ⁽{order}⁾ Pⱼ vs nth_derivative at t = {t}"),
            )?;
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 4. Bézier spans
// ---------------------------------------------------------------------------

/// `to_bezier_spans` returns one piece per non-empty span, contiguous and
/// covering the domain; on `[a, b)` the spline equals
/// `curve((t − a)/(b − a))` and its `k`-th derivative equals the piece's
/// divided by `(b − a)ᵏ`. The rounding of `s = (t − a)/(b − a)` (relative
/// `2ε`, so `t` moves by at most `2εw`) adds `4εw · max|f⁽ᵏ⁺¹⁾|`.
fn bspline_equals_its_bezier_spans<const D: usize>(
    (spline, params): (BSpline<D>, Vec<(Index, f64)>),
) -> Result<(), TestCaseError> {
    let p = spline.degree();
    let spans = spline.to_bezier_spans();
    let indices = nonempty_spans(&spline);
    prop_assert_eq!(spans.len(), indices.len());
    let (start, end) = spline.domain();
    prop_assert_eq!(spans[0].knots.0, start);
    prop_assert_eq!(spans[spans.len() - 1].knots.1, end);
    for pair in spans.windows(2) {
        prop_assert_eq!(pair[0].knots.1, pair[1].knots.0);
    }
    for (piece, &span) in spans.iter().zip(&indices) {
        let (a, b) = piece.knots;
        prop_assert_eq!((a, b), (spline.knots()[span], spline.knots()[span + 1]));
        prop_assert_eq!(piece.curve.degree(), p);
        let w = b - a;
        let m = Magnitudes::of_span(spline.knots(), spline.points(), p, span);
        let last = span == indices[indices.len() - 1];
        let relative = params
            .iter()
            .map(|&(_, u)| 0.999 * u)
            .chain([0.0])
            .chain(last.then_some(1.0));
        for u in relative {
            let t = if u == 1.0 { b } else { a + w * u };
            let s = (t - a) / w;
            let tol = |k: usize| 2.0 * m.rounding(k) + 4.0 * EPS * w * m.bound(k + 1);
            let what = format!("span [{a}, {b}] at t = {t}");
            assert_close(
                spline.eval(t).coords,
                piece.curve.eval(s).coords,
                tol(0),
                &what,
            )?;
            assert_close(
                spline.derivative(t),
                piece.curve.derivative(s) / w,
                tol(1),
                &what,
            )?;
            for k in 2..=3 {
                assert_close(
                    spline.nth_derivative(t, k).unwrap(),
                    piece.curve.nth_derivative(s, k).unwrap() / w.powi(k as i32),
                    tol(k),
                    &format!("{what}, order {k}"),
                )?;
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 5. Knot insertion
// ---------------------------------------------------------------------------

/// A B-spline, where to insert (0: an existing knot of the domain, 1: a
/// random parameter, 2: a parameter 1–3 ulps from an existing knot), the
/// knot choice, a relative position, and the insertion count.
type InsertionCase<const D: usize> = (BSpline<D>, u8, Index, f64, Index);

/// Inputs for [`knot_insertion_keeps_the_curve`].
fn insertion_case<const D: usize>() -> impl Strategy<Value = InsertionCase<D>> {
    (
        spline::<D>(),
        0u8..3,
        any::<Index>(),
        0.0..=1.0f64,
        any::<Index>(),
    )
}

/// `insert_knot(t, times)` keeps the curve (values and first derivatives,
/// compared on 101 parameters and every knot) and the domain, adds `times`
/// knots equal to `t` (or to the existing knot within `4ε ×` the knot range
/// of `t`, as documented) and `times` control points, returns a B-spline that
/// `BSpline::new` accepts, and fails exactly when the multiplicity of that
/// knot would exceed `p + 1`, or `t` is outside the domain.
///
/// Each insertion replaces points by convex combinations with weights of
/// relative error ~3ε: at most `9ε max|P|` per point and insertion.
fn knot_insertion_keeps_the_curve<const D: usize>(
    (spline, place, which, u, how_many): InsertionCase<D>,
) -> Result<(), TestCaseError> {
    let p = spline.degree();
    let (a, b) = spline.domain();
    let inside: Vec<f64> = spline
        .knots()
        .iter()
        .copied()
        .filter(|&k| a <= k && k <= b)
        .collect();
    let knot = inside[which.index(inside.len())];
    let t = match place {
        0 => knot,
        1 => (a + (b - a) * u).clamp(a, b),
        _ => {
            // 1–3 ulps to either side, inside the domain.
            let ulps = (u * 6.0).floor() - 3.0;
            let ulps = if ulps >= 0.0 { ulps + 1.0 } else { ulps };
            (knot + ulps * EPS * knot.abs().max(f64::MIN_POSITIVE)).clamp(a, b)
        }
    };
    // Documented: a `t` within `4ε ×` the knot range of an existing knot
    // (closer than `BSpline::new` allows distinct knots to be) inserts that
    // knot.
    let knots = spline.knots();
    let min_gap = 4.0 * EPS * (knots[knots.len() - 1] - knots[0]);
    let t = knots
        .iter()
        .copied()
        .find(|&k| (k - t).abs() < min_gap)
        .unwrap_or(t);
    let multiplicity = knots.iter().filter(|&&k| k == t).count();
    let room = p + 1 - multiplicity;
    let too_many = spline.insert_knot(t, room + 1);
    prop_assert!(
        matches!(too_many, Err(Error::KnotMultiplicity { multiplicity: m, max, .. }) if m == p + 2 && max == p + 1),
        "inserting {} {} times (multiplicity {}) gave {:?}",
        t,
        room + 1,
        multiplicity,
        too_many
    );
    for outside in [a - 1.0, b + 0.5, f64::NAN, f64::INFINITY] {
        let result = spline.insert_knot(outside, 1);
        prop_assert!(
            matches!(result, Err(Error::ParameterOutOfDomain { .. })),
            "spline.insert_knot: expected Error::ParameterOutOfDomain, got {:?}",
            result
        );
    }
    if room == 0 {
        return Ok(());
    }
    let times = 1 + how_many.index(room);
    let refined = spline.insert_knot(t, times)?;

    prop_assert_eq!(refined.degree(), p);
    prop_assert_eq!(refined.domain(), (a, b));
    prop_assert_eq!(refined.points().len(), spline.points().len() + times);
    let mut expected_knots = spline.knots().to_vec();
    expected_knots.extend(std::iter::repeat_n(t, times));
    expected_knots.sort_by(f64::total_cmp);
    prop_assert_eq!(refined.knots(), &expected_knots[..]);
    check_valid_parts(&refined, &format!("insert_knot({t}, {times})"))?;

    let m = Magnitudes::of_spline(&spline);
    let m_refined = Magnitudes::of_spline(&refined);
    let inserted = 9.0 * times as f64 * EPS;
    let tol0 = m.rounding(0) + m_refined.rounding(0) + inserted * m.bound(0);
    let tol1 = m.rounding(1) + m_refined.rounding(1) + inserted * m_refined.size(1);
    for x in dense_params(&spline) {
        let what = format!("after inserting {t} ×{times}, at {x}");
        assert_close(refined.eval(x).coords, spline.eval(x).coords, tol0, &what)?;
        assert_close(refined.derivative(x), spline.derivative(x), tol1, &what)?;
    }
    Ok(())
}

/// Regression (the smallest failing case the property above found, fixed in
/// the library since): inserting a knot one ulp from an existing knot
/// returned a B-spline with a knot gap of `1.1e-16`, which `BSpline::new`
/// rejects (`KnotGapTooSmall`: rounding cannot resolve it), and on which the
/// derivative was wrong: `(8, 0)` instead of `(5.714…, 0)` at `t = 0.5`.
/// Now documented: a parameter that close to a knot inserts the knot.
#[test]
fn knot_insertion_next_to_a_knot_keeps_the_invariants() {
    let points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0], [5.0, 1.0]].map(Point::from);
    let knots = vec![0.0, 0.0, 0.0, 0.5, 0.7, 1.0, 1.0, 1.0];
    let spline = BSpline::<2>::new(2, knots, points.to_vec()).expect("valid spline");
    let t = 0.5 + 0.5 * EPS; // the next double after 0.5
    let refined = spline.insert_knot(t, 1).expect("t is in the domain");
    if let Err(failure) = check_valid_parts(&refined, &format!("insert_knot({t}, 1)")) {
        panic!("{failure}");
    }
    // Documented: a parameter within rounding of a knot inserts that knot.
    assert_eq!(Ok(refined), spline.insert_knot(0.5, 1));
}

// ---------------------------------------------------------------------------
// 6. Bézier subdivision
// ---------------------------------------------------------------------------

/// `subdivide(t)` gives pieces of the same degree with
/// `left(s) = P(s·t)` and `right(s) = P(t + s(1 − t))`; the parameter
/// rounding (≤ 2ε) adds `4ε max|P′|`, the subdivision itself one rounding
/// budget. Parameters outside `[0, 1]` and NaN are errors.
fn subdivision_keeps_the_curve<const D: usize>(
    (curve, split, params): (Bezier<D>, f64, Vec<f64>),
) -> Result<(), TestCaseError> {
    let m = Magnitudes::of_bezier(curve.points());
    let tol = 3.0 * m.rounding(0) + 4.0 * EPS * m.bound(1);
    let (left, right) = curve.subdivide(split)?;
    prop_assert_eq!(left.degree(), curve.degree());
    prop_assert_eq!(right.degree(), curve.degree());
    for s in params.into_iter().chain([0.0, 1.0]) {
        let what = format!("split at {split}, s = {s}");
        let whole = curve.eval(s * split).coords;
        assert_close(left.eval(s).coords, whole, tol, &format!("left, {what}"))?;
        let whole = curve.eval(split + s * (1.0 - split)).coords;
        assert_close(right.eval(s).coords, whole, tol, &format!("right, {what}"))?;
    }
    for bad in [-0.25, 1.5, f64::NAN, f64::NEG_INFINITY] {
        let result = curve.subdivide(bad);
        prop_assert!(
            matches!(result, Err(Error::ParameterOutOfDomain { .. })),
            "curve.subdivide: expected Error::ParameterOutOfDomain, got {:?}",
            result
        );
    }
    Ok(())
}

/// A Bézier curve, a split parameter (one in five exactly 0, ½ or 1) and
/// eight parameters in `[0, 1]`.
fn subdivision_case<const D: usize>() -> impl Strategy<Value = (Bezier<D>, f64, Vec<f64>)> {
    let split = prop_oneof![
        4 => 0.0..=1.0f64,
        1 => prop::sample::select(vec![0.0, 0.5, 1.0]),
    ];
    (bezier::<D>(), split, vec(0.0..=1.0f64, 8))
}

// ---------------------------------------------------------------------------
// 7. Clamped B-spline of full degree = Bézier
// ---------------------------------------------------------------------------

/// `BSpline::clamped(n − 1, P)` on `n` points has knots `0ⁿ 1ⁿ` and equals
/// `Bezier::new(P)` in value and derivatives of orders 1–3.
fn full_degree_clamped_spline_is_the_bezier<const D: usize>(
    (curve, params): (Bezier<D>, Vec<f64>),
) -> Result<(), TestCaseError> {
    let points = curve.points().to_vec();
    let n = points.len();
    let spline = BSpline::clamped(n - 1, points)?;
    let knots: Vec<f64> = (0..2 * n).map(|i| if i < n { 0.0 } else { 1.0 }).collect();
    prop_assert_eq!(spline.knots(), &knots[..]);
    prop_assert_eq!(spline.domain(), (0.0, 1.0));
    let m = Magnitudes::of_bezier(curve.points());
    for t in params.into_iter().chain([0.0, 1.0]) {
        let what = format!("t = {t}");
        assert_close(
            spline.eval(t).coords,
            curve.eval(t).coords,
            2.0 * m.rounding(0),
            &what,
        )?;
        assert_close(
            spline.derivative(t),
            curve.derivative(t),
            2.0 * m.rounding(1),
            &what,
        )?;
        for k in 1..=3 {
            assert_close(
                spline.nth_derivative(t, k).unwrap(),
                curve.nth_derivative(t, k).unwrap(),
                2.0 * m.rounding(k),
                &format!("{what}, order {k}"),
            )?;
        }
    }
    Ok(())
}

/// `BSpline::uniform(p, P)` has the knots `i/(n + p)`, `i = 0 … n + p`, and
/// the domain `[t_p, t_n]`; `BSpline::clamped(p, P)` has `p + 1` knots 0,
/// `p + 1` knots 1 and the interior knots `(i − p)/(n − p)`, and starts at
/// `P₀` and ends at `P_{n−1}`. Each knot is one correctly rounded division
/// (within `ε ×` its value). A degree `≥ n` is an error for both.
fn constructors_make_the_documented_knots<const D: usize>(
    (p, points): (usize, Vec<Point<f64, D>>),
) -> Result<(), TestCaseError> {
    let n = points.len();
    let uniform = BSpline::uniform(p, points.clone())?;
    let knots = uniform.knots();
    prop_assert_eq!(knots.len(), n + p + 1);
    for (i, &k) in knots.iter().enumerate() {
        let want = i as f64 / (n + p) as f64;
        prop_assert!((k - want).abs() <= EPS * want, "uniform knot {} = {}", i, k);
    }
    prop_assert_eq!(uniform.domain(), (knots[p], knots[n]));

    let clamped = BSpline::clamped(p, points.clone())?;
    let knots = clamped.knots();
    prop_assert_eq!(knots.len(), n + p + 1);
    prop_assert!(knots[..=p].iter().all(|&k| k == 0.0), "{:?}", knots);
    prop_assert!(knots[n..].iter().all(|&k| k == 1.0), "{:?}", knots);
    for (i, &k) in knots.iter().enumerate().take(n).skip(p + 1) {
        let want = (i - p) as f64 / (n - p) as f64;
        prop_assert!((k - want).abs() <= EPS * want, "clamped knot {} = {}", i, k);
    }
    prop_assert_eq!(clamped.domain(), (0.0, 1.0));
    let m = Magnitudes::of_spline(&clamped);
    let ends = [(0.0, points[0]), (1.0, points[n - 1])];
    for (t, point) in ends {
        let what = format!("clamped end at t = {t}");
        assert_close(clamped.eval(t).coords, point.coords, m.rounding(0), &what)?;
    }

    for degree in [n, n + 3] {
        let too_high = (
            BSpline::uniform(degree, points.clone()),
            BSpline::clamped(degree, points.clone()),
        );
        prop_assert!(
            matches!(
                too_high,
                (
                    Err(Error::DegreeTooHigh { .. }),
                    Err(Error::DegreeTooHigh { .. })
                )
            ),
            "degree {} on {} points: {:?}",
            degree,
            n,
            too_high
        );
    }
    Ok(())
}

/// A degree 0–12 and `p + 1 … 2p + 9` control points.
fn degree_and_points<const D: usize>() -> impl Strategy<Value = (usize, Vec<Point<f64, D>>)> {
    (0..=MAX_DEGREE).prop_flat_map(|p| (Just(p), control_points::<D>(p + 1..=2 * p + 9)))
}

// ---------------------------------------------------------------------------
// 8. Derivative curves
// ---------------------------------------------------------------------------

/// `derivative_spline()` has degree `p − 1` (0 for `p = 0`), the same domain,
/// and evaluates to `derivative(t)`; `nth_derivative_spline(k)` evaluates to
/// `nth_derivative(t, k)`, `k ≤ 3`. Checked on 101 parameters and every knot.
fn derivative_spline_evaluates_to_the_derivative<const D: usize>(
    spline: BSpline<D>,
) -> Result<(), TestCaseError> {
    let p = spline.degree();
    let derivative = spline.derivative_spline();
    prop_assert_eq!(derivative.degree(), p.saturating_sub(1));
    prop_assert_eq!(derivative.domain(), spline.domain());
    check_valid_parts(&derivative, "derivative_spline()")?;
    let m = Magnitudes::of_spline(&spline);
    let higher: Vec<BSpline<D>> = (0..=3).map(|k| spline.nth_derivative_spline(k)).collect();
    for (k, curve) in higher.iter().enumerate() {
        prop_assert_eq!(curve.domain(), spline.domain());
        check_valid_parts(curve, &format!("nth_derivative_spline({k})"))?;
    }
    for t in dense_params(&spline) {
        let what = format!("t = {t}");
        assert_close(
            derivative.eval(t).coords,
            spline.derivative(t),
            2.0 * m.rounding(1),
            &what,
        )?;
        for (k, curve) in higher.iter().enumerate() {
            assert_close(
                curve.eval(t).coords,
                spline.nth_derivative(t, k).unwrap(),
                2.0 * m.rounding(k),
                &format!("{what}, order {k}"),
            )?;
        }
    }
    Ok(())
}

/// `hodograph()` has degree `n − 1` (0 for `n = 0`) and evaluates to
/// `derivative(t)`.
fn hodograph_evaluates_to_the_derivative<const D: usize>(
    (curve, params): (Bezier<D>, Vec<f64>),
) -> Result<(), TestCaseError> {
    let hodograph = curve.hodograph();
    prop_assert_eq!(hodograph.degree(), curve.degree().saturating_sub(1));
    let m = Magnitudes::of_bezier(curve.points());
    for t in params.into_iter().chain([0.0, 1.0]) {
        assert_close(
            hodograph.eval(t).coords,
            curve.derivative(t),
            2.0 * m.rounding(1),
            &format!("t = {t}"),
        )?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// 9. Flattening
// ---------------------------------------------------------------------------

/// Checks a flattening of `curve` to `tolerance`: `0 ≤ bound ≤ tolerance`;
/// parameters non-decreasing from the domain start to the domain end; each
/// sample equals `eval(t)` and `derivative(t)` except the first of two
/// samples with equal `t`, which must be the left limit there
/// (`left_limit(t)` where the curve jumps, else `eval(t)`); and every curve point at 63 parameters strictly between
/// two consecutive samples lies within `bound` of the segment joining them
/// (plus `1e-12 ×` the coordinate scale for the rounding of the test's own
/// evaluation and distance).
fn check_flattening<const D: usize>(
    curve: &impl Curve<D>,
    flat: &Flattening<D>,
    tolerance: f64,
    m: &Magnitudes,
    scale: f64,
    left_limit: impl Fn(f64) -> Option<Point<f64, D>>,
) -> Result<(), TestCaseError> {
    prop_assert!(
        0.0 <= flat.bound && flat.bound <= tolerance,
        "bound {} for tolerance {}",
        flat.bound,
        tolerance
    );
    let samples: &[CurveSample<D>] = &flat.samples;
    prop_assert!(samples.len() >= 2);
    let (a, b) = curve.domain();
    prop_assert_eq!(samples[0].t, a);
    prop_assert_eq!(samples[samples.len() - 1].t, b);
    for (i, sample) in samples.iter().enumerate() {
        let jump = samples.get(i + 1).is_some_and(|next| next.t == sample.t);
        if jump {
            // Where the curve is continuous the left limit is the value.
            let limit = left_limit(sample.t).unwrap_or_else(|| curve.eval(sample.t));
            assert_close(
                sample.point.coords,
                limit.coords,
                m.rounding(0),
                &format!("left-limit sample {i} at t = {}", sample.t),
            )?;
        } else {
            let what = format!("sample {i} at t = {}", sample.t);
            assert_close(
                sample.point.coords,
                curve.eval(sample.t).coords,
                m.rounding(0),
                &what,
            )?;
            assert_close(
                sample.derivative,
                curve.derivative(sample.t),
                m.rounding(1),
                &what,
            )?;
        }
    }
    let allowed = flat.bound + 1e-12 * scale;
    for pair in samples.windows(2) {
        let (s0, s1) = (&pair[0], &pair[1]);
        prop_assert!(s0.t <= s1.t, "parameters decrease: {} then {}", s0.t, s1.t);
        if s0.t == s1.t {
            continue;
        }
        for j in 1..64 {
            let t = s0.t + (s1.t - s0.t) * (j as f64 / 64.0);
            let distance = distance_to_segment(curve.eval(t), s0.point, s1.point);
            prop_assert!(
                distance <= allowed,
                "curve point at t = {} is {:e} from the segment between t = {} and t = {} \
                 (bound {:e}, tolerance {:e})",
                t,
                distance,
                s0.t,
                s1.t,
                flat.bound,
                tolerance
            );
        }
    }
    Ok(())
}

/// A tolerance `10^x`, `x ∈ [−6, −1]`.
fn flatten_tolerance() -> impl Strategy<Value = f64> {
    (-6.0..=-1.0f64).prop_map(|x| 10f64.powf(x))
}

/// `Bezier::flatten` meets its contract (see [`check_flattening`]); invalid
/// tolerances are errors.
fn bezier_flattening_is_within_its_bound<const D: usize>(
    (curve, tolerance): (Bezier<D>, f64),
) -> Result<(), TestCaseError> {
    let flat = curve.flatten(tolerance)?;
    let m = Magnitudes::of_bezier(curve.points());
    let scale = coordinate_scale(curve.points());
    check_flattening(&curve, &flat, tolerance, &m, scale, |_| None)?;
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let result = curve.flatten(bad);
        prop_assert!(
            matches!(result, Err(Error::InvalidTolerance { .. })),
            "curve.flatten: expected Error::InvalidTolerance, got {:?}",
            result
        );
    }
    Ok(())
}

/// Flattens `spline` to `tolerance` and checks the result (see
/// [`check_flattening`]). At an interior knot of full multiplicity `p + 1`,
/// `t_s = … = t_{s+p}`, the curve may jump; its left limit there is `P_{s−1}`.
fn check_spline_flattening<const D: usize>(
    spline: &BSpline<D>,
    tolerance: f64,
) -> Result<(), TestCaseError> {
    let flat = spline.flatten(tolerance)?;
    let p = spline.degree();
    let (a, b) = spline.domain();
    let knots = spline.knots();
    let left_limit = |t: f64| {
        let s = knots.iter().position(|&k| k == t)?;
        let full = knots.iter().filter(|&&k| k == t).count() == p + 1;
        (a < t && t < b && full).then(|| spline.points()[s - 1])
    };
    let m = Magnitudes::of_spline(spline);
    let scale = coordinate_scale(spline.points());
    check_flattening(spline, &flat, tolerance, &m, scale, left_limit)
}

/// `BSpline::flatten` meets its contract (see [`check_spline_flattening`]);
/// invalid tolerances are errors.
fn bspline_flattening_is_within_its_bound<const D: usize>(
    (spline, tolerance): (BSpline<D>, f64),
) -> Result<(), TestCaseError> {
    check_spline_flattening(&spline, tolerance)?;
    for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let result = spline.flatten(bad);
        prop_assert!(
            matches!(result, Err(Error::InvalidTolerance { .. })),
            "spline.flatten: expected Error::InvalidTolerance, got {:?}",
            result
        );
    }
    Ok(())
}

/// Regression (the smallest failing case the property above found, fixed in
/// the library since): a jump smaller than the tolerance (0.001 < 0.01) at an
/// interior knot of full multiplicity got no left-limit sample, so the
/// polyline ran from `(0, 0)` straight to the right limit `(1, 1.001)` while
/// the curve arrives at `(1, 1)`: just left of `t = 1` the curve was `7.1e-4`
/// from the polyline, with a reported `bound` of about `2e-15`.
#[test]
fn bspline_flattening_is_within_its_bound_across_a_small_jump() {
    let points = [[0.0, 0.0], [1.0, 1.0], [1.0, 1.001], [2.0, 0.0]].map(Point::from);
    let knots = vec![0.0, 0.0, 1.0, 1.0, 2.0, 2.0];
    let spline = BSpline::<2>::new(1, knots, points.to_vec()).expect("valid spline");
    if let Err(failure) = check_spline_flattening(&spline, 1e-2) {
        panic!("{failure}");
    }
}

// ---------------------------------------------------------------------------
// 10. Uniform discretization
// ---------------------------------------------------------------------------

/// `discretize(segments)` returns `segments + 1` samples at
/// `tᵢ = a + (b − a) i/segments` (the ends exact; inside within
/// `4ε (|a| + |b|)`: any way of computing `tᵢ`, as a convex combination or
/// as here, is within `2ε (|a| + |b|)` of the exact value)
/// with `point = eval(t)` and `derivative = derivative(t)`; `discretize(0)`
/// returns the two end samples.
fn check_discretization<const D: usize>(
    curve: &impl Curve<D>,
    segments: usize,
    m: &Magnitudes,
) -> Result<(), TestCaseError> {
    let (a, b) = curve.domain();
    let samples = curve.discretize(segments);
    prop_assert_eq!(samples.len(), segments + 1);
    prop_assert_eq!(samples[0].t, a);
    prop_assert_eq!(samples[segments].t, b);
    let spacing_tol = 4.0 * EPS * (a.abs() + b.abs());
    for (i, sample) in samples.iter().enumerate() {
        let ideal = a + (b - a) * (i as f64 / segments as f64);
        prop_assert!(
            (sample.t - ideal).abs() <= spacing_tol,
            "sample {} at t = {}, expected {}",
            i,
            sample.t,
            ideal
        );
        let what = format!("sample {i} at t = {}", sample.t);
        assert_close(
            sample.point.coords,
            curve.eval(sample.t).coords,
            m.rounding(0),
            &what,
        )?;
        assert_close(
            sample.derivative,
            curve.derivative(sample.t),
            m.rounding(1),
            &what,
        )?;
    }
    let ends = curve.discretize(0);
    prop_assert_eq!(ends.len(), 2);
    prop_assert_eq!((ends[0].t, ends[1].t), (a, b));
    Ok(())
}

/// [`check_discretization`] for a Bézier curve.
fn bezier_discretization_is_uniform<const D: usize>(
    (curve, segments): (Bezier<D>, usize),
) -> Result<(), TestCaseError> {
    check_discretization(&curve, segments, &Magnitudes::of_bezier(curve.points()))
}

/// [`check_discretization`] for a B-spline.
fn bspline_discretization_is_uniform<const D: usize>(
    (spline, segments): (BSpline<D>, usize),
) -> Result<(), TestCaseError> {
    check_discretization(&spline, segments, &Magnitudes::of_spline(&spline))
}

// ---------------------------------------------------------------------------
// 11. Evaluation outside the domain
// ---------------------------------------------------------------------------

/// Parameters outside the domain `[a, b]` (finite, infinite, NaN), and which
/// end each must be moved to: `false` = start (also for NaN), `true` = end.
fn outside_params(a: f64, b: f64, far: f64) -> [(f64, bool); 8] {
    [
        (f64::NAN, false),
        (-f64::NAN, false),
        (f64::NEG_INFINITY, false),
        (f64::INFINITY, true),
        (f64::MIN, false),
        (f64::MAX, true),
        (a - far, false),
        (b + far, true),
    ]
}

/// Outside its domain a Bézier curve evaluates (point, derivatives of orders
/// 0–3, point with derivative) exactly as at the nearest end, NaN as at 0,
/// and never returns NaN.
fn bezier_evaluation_clamps<const D: usize>(
    (curve, far): (Bezier<D>, f64),
) -> Result<(), TestCaseError> {
    for (t, to_end) in outside_params(0.0, 1.0, far) {
        let end = if to_end { 1.0 } else { 0.0 };
        let point = curve.eval(t);
        prop_assert!(
            point.coords.iter().all(|c| c.is_finite()),
            "eval({}) = {:?}",
            t,
            point
        );
        prop_assert_eq!(point, curve.eval(end), "eval({})", t);
        prop_assert_eq!(
            curve.derivative(t),
            curve.derivative(end),
            "derivative({})",
            t
        );
        prop_assert_eq!(
            curve.eval_with_derivative(t),
            curve.eval_with_derivative(end)
        );
        for k in 0..=3 {
            let d = curve.nth_derivative(t, k).unwrap();
            prop_assert!(
                d.iter().all(|c| c.is_finite()),
                "nth({}, {}) = {:?}",
                t,
                k,
                d
            );
            prop_assert_eq!(
                d,
                curve.nth_derivative(end, k).unwrap(),
                "nth({}, {})",
                t,
                k
            );
        }
    }
    Ok(())
}

/// The same for B-splines, plus `span`, `basis_functions` and
/// `basis_derivatives`.
fn bspline_evaluation_clamps<const D: usize>(
    (spline, far): (BSpline<D>, f64),
) -> Result<(), TestCaseError> {
    let (a, b) = spline.domain();
    let p = spline.degree();
    let (mut basis, mut basis_end) = (vec![0.0; p + 1], vec![0.0; p + 1]);
    let (mut ders, mut ders_end) = (vec![0.0; 4 * (p + 1)], vec![0.0; 4 * (p + 1)]);
    for (t, to_end) in outside_params(a, b, far) {
        let end = if to_end { b } else { a };
        let point = spline.eval(t);
        prop_assert!(
            point.coords.iter().all(|c| c.is_finite()),
            "eval({}) = {:?}",
            t,
            point
        );
        prop_assert_eq!(point, spline.eval(end), "eval({})", t);
        prop_assert_eq!(
            spline.derivative(t),
            spline.derivative(end),
            "derivative({})",
            t
        );
        prop_assert_eq!(
            spline.eval_with_derivative(t),
            spline.eval_with_derivative(end)
        );
        for k in 0..=3 {
            let d = spline.nth_derivative(t, k).unwrap();
            prop_assert!(
                d.iter().all(|c| c.is_finite()),
                "nth({}, {}) = {:?}",
                t,
                k,
                d
            );
            prop_assert_eq!(
                d,
                spline.nth_derivative(end, k).unwrap(),
                "nth({}, {})",
                t,
                k
            );
        }
        prop_assert_eq!(spline.span(t), spline.span(end));
        let first = spline.basis_functions(t, &mut basis)?;
        prop_assert_eq!(first, spline.basis_functions(end, &mut basis_end)?);
        prop_assert_eq!(&basis, &basis_end);
        let first = spline.basis_derivatives(t, 3, &mut ders)?;
        prop_assert_eq!(first, spline.basis_derivatives(end, 3, &mut ders_end)?);
        prop_assert_eq!(&ders, &ders_end);
        prop_assert!(
            ders.iter().all(|x| x.is_finite()),
            "basis derivatives {:?}",
            ders
        );
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Instantiation for D = 1, 2, 3
// ---------------------------------------------------------------------------

/// A Bézier curve and a flattening tolerance.
fn bezier_and_tolerance<const D: usize>() -> impl Strategy<Value = (Bezier<D>, f64)> {
    (bezier::<D>(), flatten_tolerance())
}

/// A B-spline and a flattening tolerance.
fn spline_and_tolerance<const D: usize>() -> impl Strategy<Value = (BSpline<D>, f64)> {
    (spline::<D>(), flatten_tolerance())
}

/// A Bézier curve and a segment count 1–300.
fn bezier_and_segments<const D: usize>() -> impl Strategy<Value = (Bezier<D>, usize)> {
    (bezier::<D>(), 1usize..=300)
}

/// A B-spline and a segment count 1–300.
fn spline_and_segments<const D: usize>() -> impl Strategy<Value = (BSpline<D>, usize)> {
    (spline::<D>(), 1usize..=300)
}

/// A Bézier curve and a distance `1e-9 … 1e6` outside its domain.
fn bezier_and_distance<const D: usize>() -> impl Strategy<Value = (Bezier<D>, f64)> {
    (bezier::<D>(), 1e-9..1e6f64)
}

/// A B-spline and a distance `1e-9 … 1e6` outside its domain.
fn spline_and_distance<const D: usize>() -> impl Strategy<Value = (BSpline<D>, f64)> {
    (spline::<D>(), 1e-9..1e6f64)
}

/// For each `name: cases, strategy => check;` a module `name` with the tests
/// `dim_1`, `dim_2`, `dim_3` that run `check::<D>` on `cases` inputs from
/// `strategy::<D>()`.
macro_rules! properties {
    ($($name:ident: $cases:expr, $strategy:ident => $check:ident;)*) => {
        $(
            mod $name {
                use super::*;
                proptest! {
                    #![proptest_config(config($cases))]
                    #[test]
                    fn dim_1(input in $strategy::<1>()) {
                        $check::<1>(input)?;
                    }
                    #[test]
                    fn dim_2(input in $strategy::<2>()) {
                        $check::<2>(input)?;
                    }
                    #[test]
                    fn dim_3(input in $strategy::<3>()) {
                        $check::<3>(input)?;
                    }
                }
            }
        )*
    };
}

properties! {
    bezier_derivatives: 1024, bezier_and_params => bezier_derivatives_match_central_differences;
    bspline_derivatives: 1024, spline_and_params => spline_derivatives_match_central_differences;
    de_casteljau_vs_bernstein: 1024, bezier_and_params => de_casteljau_matches_bernstein_sum;
    basis_functions: 1024, spline_and_params => basis_functions_are_a_local_partition_of_unity;
    bezier_spans: 1024, spline_and_params => bspline_equals_its_bezier_spans;
    knot_insertion: 1024, insertion_case => knot_insertion_keeps_the_curve;
    subdivision: 1024, subdivision_case => subdivision_keeps_the_curve;
    clamped_is_bezier: 1024, bezier_and_params => full_degree_clamped_spline_is_the_bezier;
    constructors: 1024, degree_and_points => constructors_make_the_documented_knots;
    derivative_spline: 512, spline => derivative_spline_evaluates_to_the_derivative;
    hodograph: 1024, bezier_and_params => hodograph_evaluates_to_the_derivative;
    bezier_flatten: 256, bezier_and_tolerance => bezier_flattening_is_within_its_bound;
    bspline_flatten: 256, spline_and_tolerance => bspline_flattening_is_within_its_bound;
    bezier_discretize: 512, bezier_and_segments => bezier_discretization_is_uniform;
    bspline_discretize: 512, spline_and_segments => bspline_discretization_is_uniform;
    bezier_outside_domain: 1024, bezier_and_distance => bezier_evaluation_clamps;
    bspline_outside_domain: 1024, spline_and_distance => bspline_evaluation_clamps;
}

//! The curve part of the study: what a given deviation from the curve costs
//! in samples and time, for adaptive flattening and uniform discretization.
//!
//! Two profiles: the vase (one cubic Bézier) and the wine glass (the course's
//! uniform cubic B-spline on 25 points). Two sweeps each:
//!
//! - adaptive: `flatten(tol)` for `tol = 10⁻¹, 10⁻², …` down to the smallest
//!   tolerance the library accepts for the curve (`10⁻¹⁰ ×` its largest
//!   control-point coordinate, so `10⁻⁹` for both profiles);
//! - uniform: `Curve::discretize(n)` for `n = 4, 8, …, 4096` *segments*
//!   (`n + 1` samples, see the trait's documentation).
//!
//! For every point we report the number of samples, the time (median over
//! repeated runs), the bound the library certifies (adaptive only) and the
//! deviation we *measure*: the largest distance from a curve point with
//! parameter in `[sᵢ.t, sᵢ₊₁.t]` to the segment `[sᵢ, sᵢ₊₁]`, found by dense
//! sampling plus a golden-section refinement in every segment. The curve
//! points for that measurement come from a second evaluator that shares no
//! code with the one under test ([`Reference`]): the Bernstein sum with
//! explicit binomials and powers for the Bézier, the Cox–de Boor basis times
//! the control points for the B-spline. The measurement is a lower estimate
//! of the true deviation (a maximum found by search), and tight: the search
//! brackets the worst point to far below the sampling step.

use crate::common::{vase, wine_glass};
use revolve::nalgebra::Point2;
use revolve::{BSpline, Bezier, Curve, CurveSample, Error, Flattening};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// One point of the curve study (one row of the curve table).
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePoint {
    /// `"vase"` or `"wine glass"`.
    pub curve: &'static str,
    /// `"adaptive"` (flattening to a tolerance) or `"uniform"` (`discretize(n)`).
    pub method: &'static str,
    /// The setting: `"tol 1e-4"` or `"n = 64"`.
    pub knob: String,
    /// Samples produced (for uniform discretization `n + 1`).
    pub samples: usize,
    /// Seconds per call, the median of repeated runs on one thread.
    pub seconds: f64,
    /// The deviation bound the library certifies (adaptive only).
    pub certified: Option<f64>,
    /// The largest deviation of the curve from the polyline, as measured.
    pub measured: f64,
}

/// Tolerances tried, from coarse to fine; a sweep stops at the first one the
/// library rejects as too small.
const TOLERANCE_EXPONENTS: std::ops::RangeInclusive<i32> = 1..=14;

/// Uniform segment counts: `4, 8, …, 4096`.
const SEGMENTS: [usize; 11] = [4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096];

/// Interior parameters sampled per segment before refinement.
const DENSE: usize = 32;

/// Golden-section iterations (the bracket shrinks by `0.618` per iteration).
const GOLDEN_ITERATIONS: usize = 60;

/// A curve under study, with its independent reference evaluator.
pub struct Subject {
    /// The name in tables and plots.
    pub name: &'static str,
    /// The curve as the library represents it.
    pub curve: Profile,
    /// The second evaluator.
    pub reference: Reference,
}

/// The two curve types of the study.
pub enum Profile {
    /// A Bézier curve.
    Bezier(Bezier<2>),
    /// A B-spline curve.
    BSpline(BSpline<2>),
}

impl Profile {
    fn flatten(&self, tolerance: f64) -> Result<Flattening<2>, Error> {
        match self {
            Profile::Bezier(c) => c.flatten(tolerance),
            Profile::BSpline(c) => c.flatten(tolerance),
        }
    }

    fn discretize(&self, segments: usize) -> Vec<CurveSample<2>> {
        match self {
            Profile::Bezier(c) => c.discretize(segments),
            Profile::BSpline(c) => c.discretize(segments),
        }
    }

    /// `Curve::eval` of the library (the code under test).
    #[cfg(test)]
    fn eval(&self, t: f64) -> Point2<f64> {
        match self {
            Profile::Bezier(c) => c.eval(t),
            Profile::BSpline(c) => c.eval(t),
        }
    }

    /// The parameter domain.
    #[cfg(test)]
    fn domain(&self) -> (f64, f64) {
        match self {
            Profile::Bezier(c) => c.domain(),
            Profile::BSpline(c) => c.domain(),
        }
    }
}

/// A second way to evaluate a curve, independent of de Casteljau, de Boor
/// and the flattening code.
pub enum Reference {
    /// `Σ C(n, i) tⁱ (1 − t)ⁿ⁻ⁱ Pᵢ` with binomials from Pascal's triangle and
    /// explicit powers.
    Bernstein {
        /// The control points.
        points: Vec<Point2<f64>>,
        /// `C(n, i)`, `i = 0 … n`.
        binomials: Vec<f64>,
    },
    /// `Σ Nᵢ,ₚ(t) Pᵢ` with the basis from `BSpline::basis_functions`
    /// (Cox–de Boor's recurrence).
    CoxDeBoor(BSpline<2>),
}

impl Reference {
    /// The reference evaluator of a Bézier curve.
    pub fn bernstein(curve: &Bezier<2>) -> Self {
        let points = curve.points().to_vec();
        let n = points.len() - 1;
        let mut binomials = vec![1.0; n + 1];
        // Row n of Pascal's triangle, built in place from the right.
        for row in 1..=n {
            for k in (1..row).rev() {
                binomials[k] += binomials[k - 1];
            }
        }
        Reference::Bernstein { points, binomials }
    }

    /// The point at `t`.
    pub fn eval(&self, t: f64) -> Point2<f64> {
        match self {
            Reference::Bernstein { points, binomials } => {
                let n = points.len() - 1;
                let mut sum = Point2::origin().coords;
                for (i, (p, c)) in points.iter().zip(binomials).enumerate() {
                    let w = c * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32);
                    sum += p.coords * w;
                }
                Point2::from(sum)
            }
            Reference::CoxDeBoor(spline) => {
                let mut basis = [0.0; 17];
                let p = spline.degree();
                let first = spline
                    .basis_functions(t, &mut basis[..=p])
                    .expect("degree at most 16");
                let mut sum = Point2::origin().coords;
                for (r, n) in basis[..=p].iter().enumerate() {
                    sum += spline.points()[first + r].coords * *n;
                }
                Point2::from(sum)
            }
        }
    }
}

/// The two profiles of the study.
pub fn subjects() -> Vec<Subject> {
    let v = vase();
    let g = wine_glass();
    vec![
        Subject {
            name: "vase",
            reference: Reference::bernstein(&v),
            curve: Profile::Bezier(v),
        },
        Subject {
            name: "wine glass",
            reference: Reference::CoxDeBoor(g.clone()),
            curve: Profile::BSpline(g),
        },
    ]
}

/// The distance from `q` to the segment `[a, b]`.
pub fn distance_to_segment(q: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let ab = b - a;
    let aq = q - a;
    let len2 = ab.norm_squared();
    let s = if len2 > 0.0 {
        (aq.dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (aq - ab * s).norm()
}

/// The largest distance from the curve (evaluated by `eval`) to the polyline
/// through `samples`, taken segment by segment over the parameter interval
/// each segment covers.
///
/// In every segment: the two ends and [`DENSE`] interior parameters, then a
/// golden-section search for a maximum in the bracket around the worst of
/// them. A lower estimate of the true maximum, tight in practice.
pub fn measured_deviation(eval: impl Fn(f64) -> Point2<f64>, samples: &[CurveSample<2>]) -> f64 {
    let mut worst: f64 = 0.0;
    for pair in samples.windows(2) {
        let (s0, s1) = (&pair[0], &pair[1]);
        let (a, b) = (s0.point, s1.point);
        let dist = |t: f64| distance_to_segment(eval(t), a, b);
        let (t0, t1) = (s0.t, s1.t);
        if t1 <= t0 {
            // A jump (two samples at one parameter): the segment is the jump.
            worst = worst.max(dist(t0));
            continue;
        }
        let param = |k: usize| {
            if k == DENSE + 1 {
                t1
            } else {
                t0 + (t1 - t0) * k as f64 / (DENSE + 1) as f64
            }
        };
        let (mut best_k, mut best) = (0, f64::NEG_INFINITY);
        for k in 0..=DENSE + 1 {
            let d = dist(param(k));
            if d > best {
                (best_k, best) = (k, d);
            }
        }
        let lo = param(best_k.saturating_sub(1));
        let hi = param((best_k + 1).min(DENSE + 1));
        best = best.max(golden_max(&dist, lo, hi));
        worst = worst.max(best);
    }
    worst
}

/// The largest value of `f` that a golden-section search for a maximum on
/// `[lo, hi]` visits.
fn golden_max(f: &impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    let mut best = f1.max(f2);
    for _ in 0..GOLDEN_ITERATIONS {
        if f1 >= f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
            best = best.max(f1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
            best = best.max(f2);
        }
        if hi - lo <= f64::EPSILON * (lo.abs() + hi.abs()) {
            break;
        }
    }
    best
}

/// How long to time one configuration.
struct Budget {
    /// Target duration of one timed batch.
    batch: Duration,
    /// Target total duration.
    total: Duration,
    /// Fewest batches.
    min_batches: usize,
}

impl Budget {
    fn new(quick: bool) -> Self {
        if quick {
            Budget {
                batch: Duration::from_micros(200),
                total: Duration::from_millis(2),
                min_batches: 3,
            }
        } else {
            Budget {
                batch: Duration::from_millis(1),
                total: Duration::from_millis(20),
                min_batches: 7,
            }
        }
    }
}

/// Seconds per call of `f`: the median over batches of the mean time per
/// call in a batch. Batches repeat `f` enough times to last about
/// `budget.batch` (so the clock's resolution does not matter); there are
/// enough batches to last `budget.total` in all.
fn median_seconds<R>(budget: &Budget, mut f: impl FnMut() -> R) -> f64 {
    let start = Instant::now();
    black_box(f());
    let once = start.elapsed().max(Duration::from_nanos(20));
    let per_batch = (budget.batch.as_secs_f64() / once.as_secs_f64()).ceil() as usize;
    let per_batch = per_batch.clamp(1, 1 << 20);
    let batch_time = once.as_secs_f64() * per_batch as f64;
    let batches =
        ((budget.total.as_secs_f64() / batch_time).ceil() as usize).clamp(budget.min_batches, 1000);
    let mut times: Vec<f64> = (0..batches)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..per_batch {
                black_box(f());
            }
            start.elapsed().as_secs_f64() / per_batch as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    crate::study::median_sorted(&times)
}

/// The tolerances the library accepts for this curve, coarse to fine.
pub fn tolerances(subject: &Subject) -> Vec<(i32, f64)> {
    TOLERANCE_EXPONENTS
        .map(|e| (e, 10f64.powi(-e)))
        .take_while(|&(_, tol)| {
            !matches!(
                subject.curve.flatten(tol),
                Err(Error::ToleranceTooSmall { .. })
            )
        })
        .collect()
}

/// The adaptive point at `10^-exponent`.
fn adaptive_point(subject: &Subject, exponent: i32, tol: f64, budget: &Budget) -> CurvePoint {
    let flat = subject.curve.flatten(tol).expect("accepted tolerance");
    let seconds = median_seconds(budget, || subject.curve.flatten(tol));
    CurvePoint {
        curve: subject.name,
        method: "adaptive",
        knob: format!("tol 1e-{exponent}"),
        samples: flat.samples.len(),
        seconds,
        certified: Some(flat.bound),
        measured: measured_deviation(|t| subject.reference.eval(t), &flat.samples),
    }
}

/// The uniform point with `segments` segments.
fn uniform_point(subject: &Subject, segments: usize, budget: &Budget) -> CurvePoint {
    let samples = subject.curve.discretize(segments);
    let seconds = median_seconds(budget, || subject.curve.discretize(segments));
    CurvePoint {
        curve: subject.name,
        method: "uniform",
        knob: format!("n = {segments}"),
        samples: samples.len(),
        seconds,
        certified: None,
        measured: measured_deviation(|t| subject.reference.eval(t), &samples),
    }
}

/// Runs the whole curve study: both curves, both sweeps, in the order
/// vase adaptive, vase uniform, wine glass adaptive, wine glass uniform.
///
/// `progress(done, total)` is called once before the first point (with
/// `done = 0`) and after every point. `quick` times each point for about
/// 2 ms instead of 20 ms; the measurements are the same.
pub fn study(quick: bool, progress: &mut dyn FnMut(usize, usize)) -> Vec<CurvePoint> {
    let budget = Budget::new(quick);
    let subjects = subjects();
    let plans: Vec<Vec<(i32, f64)>> = subjects.iter().map(tolerances).collect();
    let total: usize = plans.iter().map(|p| p.len() + SEGMENTS.len()).sum();
    let mut out = Vec::with_capacity(total);
    progress(0, total);
    for (subject, plan) in subjects.iter().zip(&plans) {
        for &(exponent, tol) in plan {
            out.push(adaptive_point(subject, exponent, tol, &budget));
            progress(out.len(), total);
        }
        for segments in SEGMENTS {
            out.push(uniform_point(subject, segments, &budget));
            progress(out.len(), total);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_evaluators_agree_with_eval() {
        for subject in subjects() {
            let (a, b) = subject.curve.domain();
            for i in 0..=1000 {
                let t = a + (b - a) * i as f64 / 1000.0;
                let got = subject.reference.eval(t);
                let want = subject.curve.eval(t);
                assert!(
                    (got - want).norm() <= 1e-14,
                    "{} at t = {t}: reference {got:?}, eval {want:?}",
                    subject.name
                );
            }
        }
    }

    #[test]
    fn bernstein_binomials_are_pascal() {
        let curve = Bezier::new(vec![Point2::origin(); 7]).unwrap();
        let Reference::Bernstein { binomials, .. } = Reference::bernstein(&curve) else {
            unreachable!()
        };
        assert_eq!(binomials, vec![1.0, 6.0, 15.0, 20.0, 15.0, 6.0, 1.0]);
    }

    /// The certified bound holds for the measured deviation, and the
    /// measurement finds a deviation of the bound's order (a measurement
    /// that missed the worst points would fall far below it).
    #[test]
    fn measured_deviation_within_certified_bound() {
        for subject in subjects() {
            let plan = tolerances(&subject);
            assert_eq!(plan.last().map(|p| p.0), Some(9), "{}", subject.name);
            for (_, tol) in plan {
                let flat = subject.curve.flatten(tol).unwrap();
                let measured = measured_deviation(|t| subject.reference.eval(t), &flat.samples);
                assert!(
                    measured <= flat.bound,
                    "{} tol {tol:e}: measured {measured:e} > bound {:e}",
                    subject.name,
                    flat.bound
                );
                assert!(
                    measured >= 0.2 * flat.bound,
                    "{} tol {tol:e}: measured {measured:e} ≪ bound {:e}",
                    subject.name,
                    flat.bound
                );
            }
        }
    }

    /// `P(t) = (2t, 4t(1 − t))`, i.e. `y = 2x − x²`. On a parameter interval
    /// of width `h` the chord spans `2h` in `x`, and the curve's vertical
    /// offset from the chord peaks at the midpoint at `|y''|/2 · (2h)²/4 =
    /// h²`; the perpendicular distance is that times `cos θ = 1/√(1 + m²)`,
    /// `m` the chord's slope `2 − 2x_mid`. The flattest chord, around the
    /// apex, has `|m| = 2h` (n even), so the deviation is `h²/√(1 + 4h²)`.
    #[test]
    fn parabola_uniform_deviation_matches_closed_form() {
        let parabola = Bezier::new(vec![
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 2.0),
            Point2::new(2.0, 0.0),
        ])
        .unwrap();
        let reference = Reference::bernstein(&parabola);
        for n in [4, 8, 16, 64, 256, 1024] {
            let samples = parabola.discretize(n);
            let measured = measured_deviation(|t| reference.eval(t), &samples);
            let h = 1.0 / n as f64;
            let exact = h * h / (1.0 + 4.0 * h * h).sqrt();
            assert!(
                (measured - exact).abs() <= 1e-12,
                "n = {n}: measured {measured:e}, closed form {exact:e}"
            );
        }
    }

    #[test]
    fn uniform_error_quarters_when_n_doubles() {
        let vase = &subjects()[0];
        let errors: Vec<f64> = SEGMENTS
            .iter()
            .map(|&n| measured_deviation(|t| vase.reference.eval(t), &vase.curve.discretize(n)))
            .collect();
        for (pair, n) in errors.windows(2).zip(SEGMENTS) {
            let ratio = pair[0] / pair[1];
            assert!(
                (3.0..=5.0).contains(&ratio),
                "n = {n} → {}: error {:e} → {:e}, ratio {ratio}",
                2 * n,
                pair[0],
                pair[1]
            );
        }
    }

    #[test]
    fn distance_to_segment_cases() {
        let (a, b) = (Point2::new(0.0, 0.0), Point2::new(2.0, 0.0));
        assert_eq!(distance_to_segment(Point2::new(1.0, 3.0), a, b), 3.0);
        assert_eq!(distance_to_segment(Point2::new(5.0, 4.0), a, b), 5.0);
        assert_eq!(distance_to_segment(Point2::new(-3.0, -4.0), a, b), 5.0);
        assert_eq!(distance_to_segment(Point2::new(3.0, 4.0), a, a), 5.0);
    }

    #[test]
    fn quick_study_is_complete() {
        let mut calls = Vec::new();
        let points = study(true, &mut |done, total| calls.push((done, total)));
        let total = points.len();
        assert_eq!(calls.first(), Some(&(0, total)));
        assert_eq!(calls.last(), Some(&(total, total)));
        for curve in ["vase", "wine glass"] {
            let uniform: Vec<_> = points
                .iter()
                .filter(|p| p.curve == curve && p.method == "uniform")
                .collect();
            assert_eq!(uniform.len(), SEGMENTS.len());
            assert_eq!(uniform[4].knob, "n = 64");
            assert_eq!(uniform[4].samples, 65);
            let adaptive = points
                .iter()
                .filter(|p| p.curve == curve && p.method == "adaptive");
            assert_eq!(adaptive.count(), 9);
        }
        for p in &points {
            assert!(p.seconds > 0.0 && p.seconds.is_finite(), "{p:?}");
            assert!(p.measured > 0.0, "{p:?}");
            if let Some(bound) = p.certified {
                assert!(p.measured <= bound, "{p:?}");
            }
        }
    }
}

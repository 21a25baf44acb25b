//! A fuzz target over the public API: constructors, evaluators and
//! intersectors fed random and extreme values (NaN, ±∞, ±0, subnormals,
//! `1e-300` … `f64::MAX`, huge degrees and counts, directions of length
//! `1e-200` and `1e200`, NaN, reversed and infinite `t` ranges) and users'
//! own curve types that break the [`Curve`] contract.
//!
//! Seeded and deterministic: case `seed` draws everything from SplitMix64
//! (`common::Rng`) started at `seed`, so a failure names the call and the
//! seed that reproduce it. Bounded in time: each target runs a fixed number of
//! seeds on a worker thread while the test thread watches; a call that does
//! not return within [`CALL_LIMIT`] fails the target with its name and seed
//! (the worker is left behind; the test binary ends it when it exits).
//!
//! Asserted for every call: no panic (each call runs under `catch_unwind`),
//! no hang, and no NaN in anything returned: points, derivatives, tangents,
//! samples, Bézier spans, hits (`t`, point, normal, `uv`), the bounds of
//! non-empty boxes, meshes. Values of the crate's own curves must be finite
//! (their derivatives are bounded at construction); values a user's curve
//! returns itself (a NaN point of a curve that evaluates to NaN) are not
//! judged, only what the library computes from them.

use revolve_testkit as common;

mod constructions;

use common::Rng;
use revolve::nalgebra::{Isometry3, Point, Point2, Point3, SVector, Unit, Vector2, Vector3};
use revolve::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierPatches, BezierSpan, BezierSurface, Curve, Error,
    Hit, Intersect, MAX_COORDINATE, MAX_SEGMENTS, Mesh, NewtonIntersector, Nurbs, NurbsSurface,
    PatchBounds, RationalBezier, RationalBezierSpan, Ray, Revolution, Surface, SurfaceNearest,
    Tolerance,
};
use std::any::Any;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, Once};
use std::thread;
use std::time::{Duration, Instant};

/// A single call that runs longer than this is a hang.
const CALL_LIMIT: Duration = Duration::from_secs(5);

/// Failures listed in full, in all and per call (the rest are counted).
const LISTED_FAILURES: usize = 40;
const LISTED_PER_CALL: u64 = 6;

// ---------------------------------------------------------------------------
// The harness: worker, watchdog, per-call catch_unwind
// ---------------------------------------------------------------------------

/// What the worker is doing, for the watchdog.
struct Progress {
    calls: AtomicU64,
    seed: AtomicU64,
    call: Mutex<&'static str>,
}

/// A fuzz case's state: its random numbers and what failed.
struct Fuzz {
    rng: Rng,
    seed: u64,
    progress: Arc<Progress>,
    failures: Vec<String>,
    failed: u64,
    /// Failures per call.
    tally: BTreeMap<&'static str, u64>,
    /// Hits the intersectors returned (so that a target that never hits
    /// shows).
    hits: u64,
    /// Aimed rays judged by the intersection contract (`aimed_case`).
    aimed: u64,
}

thread_local! {
    /// Where the last panic on this thread happened (the hook records it,
    /// the failure message reports it).
    static PANIC_AT: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Panics on fuzz worker threads are caught and reported as failures; the
/// hook keeps them off stderr and records their location.
fn quiet_fuzz_panics() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let default = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            let fuzzing = thread::current()
                .name()
                .is_some_and(|n| n.starts_with("fuzz-"));
            if fuzzing {
                let at = info.location().map(|l| l.to_string()).unwrap_or_default();
                PANIC_AT.with(|p| *p.borrow_mut() = at);
            } else {
                default(info);
            }
        }));
    });
}

fn panic_message(payload: &(dyn Any + Send)) -> String {
    let text = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(non-text panic)".into());
    let at = PANIC_AT.with(|p| p.borrow().clone());
    format!("panicked at {at}: {text}")
}

impl Fuzz {
    /// Runs one call of the API: counted, watched, a panic recorded as a
    /// failure (`None`).
    fn call<R>(&mut self, name: &'static str, f: impl FnOnce() -> R) -> Option<R> {
        *self.progress.call.lock().unwrap() = name;
        self.progress.calls.fetch_add(1, Ordering::Relaxed);
        match panic::catch_unwind(AssertUnwindSafe(f)) {
            Ok(r) => Some(r),
            Err(payload) => {
                self.fail(name, panic_message(&*payload));
                None
            }
        }
    }

    /// Records a failure of `name` unless `ok`.
    fn check(&mut self, ok: bool, name: &'static str, what: impl FnOnce() -> String) {
        if !ok {
            self.fail(name, what());
        }
    }

    fn fail(&mut self, name: &'static str, what: String) {
        self.failed += 1;
        let tally = self.tally.entry(name).or_default();
        *tally += 1;
        if *tally <= LISTED_PER_CALL && self.failures.len() < LISTED_FAILURES {
            self.failures
                .push(format!("{name} (seed {}): {what}", self.seed));
        }
    }
}

/// The seeds to run: `seeds`, or only `FUZZ_SEED` when that is set (to
/// reproduce a failure; none when it lies outside `seeds`).
fn seed_range(seeds: std::ops::Range<u64>) -> std::ops::Range<u64> {
    match std::env::var("FUZZ_SEED").ok().and_then(|s| s.parse().ok()) {
        Some(seed) if seeds.contains(&seed) => seed..seed + 1,
        Some(_) => 0..0,
        None => seeds,
    }
}

/// Runs `case` for each seed of `seeds` on a worker thread and watches it.
/// A long target is split into tests over parts of one seed range, so the
/// test harness runs the parts side by side.
fn fuzz(name: &'static str, seeds: std::ops::Range<u64>, case: fn(&mut Fuzz)) {
    quiet_fuzz_panics();
    let seeds = seed_range(seeds);
    let progress = Arc::new(Progress {
        calls: AtomicU64::new(0),
        seed: AtomicU64::new(0),
        call: Mutex::new("(start)"),
    });
    let shared = Arc::clone(&progress);
    let start = Instant::now();
    let range = seeds.clone();
    let worker = thread::Builder::new()
        .name(format!("fuzz-{name}"))
        .spawn(move || {
            let mut fuzz = Fuzz {
                rng: Rng(0),
                seed: 0,
                progress: shared,
                failures: Vec::new(),
                failed: 0,
                tally: BTreeMap::new(),
                hits: 0,
                aimed: 0,
            };
            for seed in range {
                fuzz.seed = seed;
                fuzz.rng = Rng(seed);
                fuzz.progress.seed.store(seed, Ordering::Relaxed);
                // A panic of the case's own code (not of a watched call).
                if let Err(payload) = panic::catch_unwind(AssertUnwindSafe(|| case(&mut fuzz))) {
                    fuzz.fail("(the fuzz case)", panic_message(&*payload));
                }
            }
            (
                fuzz.failures,
                fuzz.failed,
                fuzz.tally,
                fuzz.hits,
                fuzz.aimed,
            )
        })
        .expect("spawn the fuzz worker");
    let (mut last, mut since) = (u64::MAX, Instant::now());
    while !worker.is_finished() {
        thread::sleep(Duration::from_millis(20));
        let calls = progress.calls.load(Ordering::Relaxed);
        if calls != last {
            (last, since) = (calls, Instant::now());
        } else if since.elapsed() > CALL_LIMIT {
            panic!(
                "{name}: `{}` with seed {} has not returned after {CALL_LIMIT:?}: a hang \
                 (target aborted after {calls} calls)",
                progress.call.lock().unwrap(),
                progress.seed.load(Ordering::Relaxed),
            );
        }
    }
    let (failures, failed, tally, hits, aimed) = worker.join().unwrap_or_else(|payload| {
        panic!(
            "{name}: the fuzz case itself failed at seed {} (after `{}`): {}",
            progress.seed.load(Ordering::Relaxed),
            progress.call.lock().unwrap(),
            panic_message(&*payload)
        )
    });
    let calls = progress.calls.load(Ordering::Relaxed);
    println!(
        "fuzz {name}: {calls} calls, seeds {seeds:?}, {:.1} s, {hits} hits, {aimed} aimed rays \
         judged, {failed} failures",
        start.elapsed().as_secs_f64()
    );
    assert!(
        failed == 0,
        "fuzz {name}: {failed} failing calls of {calls} ({tally:?}); the first:\n{}",
        failures.join("\n")
    );
}

// ---------------------------------------------------------------------------
// Values
// ---------------------------------------------------------------------------

const EXTREMES: [f64; 30] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    f64::MIN_POSITIVE,
    1e-300,
    -1e-300,
    1e-200,
    1e-154,
    1e-16,
    f64::EPSILON,
    0.5,
    1.0,
    -1.0,
    2.0,
    1e16,
    1e100,
    -1e100,
    1e154,
    1e200,
    1e300,
    -1e300,
    f64::MAX,
    -f64::MAX,
    MAX_COORDINATE,
    -MAX_COORDINATE,
    1.0 + f64::EPSILON,
];

impl Fuzz {
    fn below(&mut self, n: usize) -> usize {
        self.rng.below(n)
    }

    fn chance(&mut self, one_in: usize) -> bool {
        self.rng.below(one_in) == 0
    }

    fn extreme(&mut self) -> f64 {
        EXTREMES[self.below(EXTREMES.len())]
    }

    /// `±10^e`, `e` uniform in `[lo, hi]`.
    fn magnitude(&mut self, lo: f64, hi: f64) -> f64 {
        let sign = if self.chance(2) { -1.0 } else { 1.0 };
        sign * 10f64.powf(self.rng.range(lo, hi))
    }

    /// Any number: extremes, random bit patterns, all magnitudes, and
    /// ordinary values.
    fn number(&mut self) -> f64 {
        match self.below(8) {
            0 | 1 => self.extreme(),
            2 => f64::from_bits(self.rng.next_u64()),
            3 => self.magnitude(-320.0, 308.0),
            _ => self.rng.range(-10.0, 10.0),
        }
    }

    /// A coordinate: mostly ordinary, sometimes at the limits of what
    /// constructors accept, sometimes beyond.
    fn coordinate(&mut self, scale: f64) -> f64 {
        match self.below(40) {
            0 => self.extreme(),
            1 => self.number(),
            2 => {
                let s = if self.chance(2) { -1.0 } else { 1.0 };
                s * MAX_COORDINATE * (1.0 - self.rng.unit() * 1e-15)
            }
            _ => scale * self.rng.range(-1.0, 1.0),
        }
    }

    /// A scale for a curve's coordinates.
    fn scale(&mut self) -> f64 {
        match self.below(6) {
            0 => self.magnitude(-300.0, 100.0).abs(),
            1 => MAX_COORDINATE,
            _ => 10f64.powf(self.rng.range(-3.0, 3.0)),
        }
    }

    /// A count: mostly small, sometimes large.
    fn count(&mut self) -> usize {
        match self.below(30) {
            0 => 20 + self.below(40),
            1 => 100 + self.below(120),
            _ => self.below(9),
        }
    }

    fn points<const D: usize>(&mut self, n: usize, scale: f64) -> Vec<Point<f64, D>> {
        let mut points = Vec::with_capacity(n);
        for _ in 0..n {
            let c: [f64; D] = std::array::from_fn(|_| 0.0);
            let mut p = Point::from(SVector::from(c));
            for k in 0..D {
                p[k] = self.coordinate(scale);
            }
            // Some repeated control points (poles, flat spans).
            if !points.is_empty() && self.chance(8) {
                p = points[points.len() - 1];
            }
            points.push(p);
        }
        points
    }

    /// A degree for `n` points: mostly valid, sometimes too high or huge.
    fn degree(&mut self, n: usize) -> usize {
        match self.below(20) {
            0 => usize::MAX,
            1 => n,
            2 => n.saturating_sub(1),
            3 => 1000,
            _ => self.below(6).min(n.saturating_sub(1)),
        }
    }

    /// A knot vector for `n` points of degree `p`: valid kinds (uniform,
    /// clamped, repeated, scaled to tiny or huge ranges) and broken ones.
    fn knots(&mut self, n: usize, p: usize) -> Vec<f64> {
        let len = match n.checked_add(p).and_then(|m| m.checked_add(1)) {
            Some(len) if len <= 1000 => len,
            _ => self.below(12),
        };
        let len = match self.below(25) {
            0 => len + 1,
            1 => len.saturating_sub(1),
            _ => len,
        };
        let mut knots: Vec<f64> = (0..len).map(|_| self.rng.unit()).collect();
        knots.sort_by(f64::total_cmp);
        match self.below(8) {
            0 => {
                // Clamped ends.
                let m = len.saturating_sub(p.saturating_add(1));
                for (i, k) in knots.iter_mut().enumerate() {
                    if i <= p {
                        *k = 0.0;
                    } else if i >= m {
                        *k = 1.0;
                    }
                }
            }
            1 => {
                // Repeated interior knots.
                for i in 1..len {
                    if self.chance(3) {
                        knots[i] = knots[i - 1];
                    }
                }
            }
            2 => {
                // A tiny or huge knot range, or a shift.
                let factor = self.magnitude(-300.0, 100.0).abs();
                let shift = if self.chance(2) { self.number() } else { 0.0 };
                for k in &mut knots {
                    *k = *k * factor + shift;
                }
            }
            3 => {
                // Extreme values anywhere (mostly invalid).
                for k in &mut knots {
                    if self.chance(4) {
                        *k = self.extreme();
                    }
                }
            }
            4 => {
                // Short spans next to long ones.
                for i in 1..len {
                    if self.chance(3) {
                        knots[i] = knots[i - 1] + knots[i - 1].abs() * 1e-15 * self.rng.unit();
                    }
                }
                knots.sort_by(f64::total_cmp);
            }
            _ => {}
        }
        knots
    }

    /// A parameter: inside the domain mostly, anything sometimes.
    fn parameter(&mut self, (a, b): (f64, f64)) -> f64 {
        match self.below(6) {
            0 => self.number(),
            1 => {
                if self.chance(2) {
                    a
                } else {
                    b
                }
            }
            _ => a + (b - a) * self.rng.unit(),
        }
    }

    /// A `(t_min, t_max)` range: the usual `(0, ∞)` mostly, and NaN,
    /// reversed, empty and infinite ones.
    fn t_range(&mut self) -> (f64, f64) {
        match self.below(10) {
            0 => (self.number(), self.number()),
            1 => (f64::NAN, f64::INFINITY),
            2 => (0.0, f64::NAN),
            3 => (f64::NEG_INFINITY, f64::INFINITY),
            4 => {
                let t = self.rng.range(0.0, 10.0);
                (t, t * self.rng.unit())
            }
            _ => (0.0, f64::INFINITY),
        }
    }

    /// A direction: random, with lengths across the whole range, and
    /// degenerate ones.
    fn direction(&mut self) -> Vector3<f64> {
        let unit = self.rng.direction();
        match self.below(12) {
            0 => Vector3::zeros(),
            1 => Vector3::new(self.number(), self.number(), self.number()),
            2 => unit * 1e-200,
            3 => unit * 1e200,
            4 => unit * self.magnitude(-300.0, 300.0).abs(),
            5 => Vector3::new(0.0, self.number(), 0.0),
            _ => unit,
        }
    }
}

// ---------------------------------------------------------------------------
// Checks
// ---------------------------------------------------------------------------

fn finite<const D: usize>(v: &SVector<f64, D>) -> bool {
    v.iter().all(|c| c.is_finite())
}

fn finite_point<const D: usize>(p: &Point<f64, D>) -> bool {
    finite(&p.coords)
}

fn unit_vector<const D: usize>(u: &Unit<SVector<f64, D>>) -> bool {
    finite(u) && (u.norm() - 1.0).abs() <= 1e-12
}

/// A non-empty box has no NaN coordinate.
fn sane_box(b: &Aabb) -> bool {
    b.is_empty() || b.min.iter().chain(b.max.iter()).all(|c| !c.is_nan())
}

/// How far `eval(uv)` can lie from a hit's point by the rounding of `uv`
/// alone: each parameter is within an ulp or
/// two of the point's exact parameters, and the partials carry that onto
/// the surface (negligible unless a knot span is a few ulps of its
/// magnitude wide, as the knot rule allows).
fn parameter_rounding<S: Surface>(s: &S, (u, v): (f64, f64)) -> f64 {
    let (su, sv) = s.partials(u, v);
    4.0 * f64::EPSILON * (u.abs() * su.norm() + v.abs() * sv.norm())
}

fn sane_hit(hit: &Hit, t_min: f64, t_max: f64) -> bool {
    hit.t.is_finite()
        && hit.t > t_min
        && hit.t < t_max
        && finite_point(&hit.point)
        && unit_vector(&hit.normal)
        && hit.uv.0.is_finite()
        && hit.uv.1.is_finite()
}

impl Fuzz {
    /// The trait's evaluators on one of the crate's curves: every value
    /// finite, tangents of unit length.
    fn own_curve<const D: usize, C: Curve<D>>(
        &mut self,
        kind: &'static str,
        c: &C,
        nth: impl Fn(&C, f64, usize) -> SVector<f64, D>,
    ) {
        let Some(domain) = self.call("Curve::domain", || c.domain()) else {
            return;
        };
        self.check(
            domain.0.is_finite() && domain.1.is_finite() && domain.0 < domain.1,
            "Curve::domain",
            || format!("{kind}: domain {domain:?}"),
        );
        for _ in 0..4 {
            let t = self.parameter(domain);
            if let Some(p) = self.call("Curve::eval", || c.eval(t)) {
                self.check(finite_point(&p), "Curve::eval", || {
                    format!("{kind} at {t:e}: {p:?}")
                });
            }
            if let Some(d) = self.call("Curve::derivative", || c.derivative(t)) {
                self.check(finite(&d), "Curve::derivative", || {
                    format!("{kind} at {t:e}: {d:?}")
                });
            }
            if let Some((p, d)) =
                self.call("Curve::eval_with_derivative", || c.eval_with_derivative(t))
            {
                self.check(
                    finite_point(&p) && finite(&d),
                    "Curve::eval_with_derivative",
                    || format!("{kind} at {t:e}: {p:?} {d:?}"),
                );
            }
            if let Some(Some(u)) = self.call("Curve::tangent", || c.tangent(t)) {
                self.check(unit_vector(&u), "Curve::tangent", || {
                    format!("{kind} at {t:e}: {u:?}, norm {}", u.norm())
                });
            }
            let order = match self.below(6) {
                0 => usize::MAX,
                1 => self.below(300),
                _ => self.below(5),
            };
            if let Some(d) = self.call("nth_derivative", || nth(c, t, order)) {
                self.check(finite(&d), "nth_derivative", || {
                    format!("{kind} at {t:e}, order {order}: {d:?}")
                });
            }
        }
        let segments = self.below(12);
        if let Some(samples) = self.call("Curve::discretize", || c.discretize(segments)) {
            let ok = samples.len() == segments.max(1) + 1
                && samples[0].t == domain.0
                && samples[samples.len() - 1].t == domain.1
                && samples
                    .iter()
                    .all(|s| s.t.is_finite() && finite_point(&s.point) && finite(&s.derivative));
            self.check(ok, "Curve::discretize", || {
                format!("{kind}: {segments} segments, {} samples", samples.len())
            });
        }
        let huge = MAX_SEGMENTS + 1 + self.below(usize::MAX / 2);
        if let Some(r) = self.call("Curve::try_discretize", || {
            c.try_discretize(huge).map(|v| v.len())
        }) {
            self.check(
                r == Err(Error::TooManySegments {
                    segments: huge,
                    max: MAX_SEGMENTS,
                }),
                "Curve::try_discretize",
                || format!("{kind}: {huge} segments gave {r:?}"),
            );
        }
        if let Some(spans) = self.call("Curve::rational_bezier_spans", || c.rational_bezier_spans())
        {
            let spans = spans.unwrap_or_default();
            self.check(!spans.is_empty(), "Curve::rational_bezier_spans", || {
                format!("{kind}: no spans")
            });
            self.spans_are_sane(kind, &spans, domain);
        }
        // Polynomial spans, where the curve has them, are the same pieces.
        if let Some(Some(spans)) = self.call("Curve::bezier_spans", || c.bezier_spans()) {
            let spans: Vec<RationalBezierSpan<D>> =
                spans.into_iter().map(RationalBezierSpan::from).collect();
            self.spans_are_sane(kind, &spans, domain);
        }
    }

    /// Spans in order, covering the domain, with control points within
    /// `MAX_COORDINATE` that `Bezier::new` accepts again.
    fn spans_are_sane<const D: usize>(
        &mut self,
        kind: &'static str,
        spans: &[RationalBezierSpan<D>],
        domain: (f64, f64),
    ) {
        let mut end = domain.0;
        for (i, s) in spans.iter().enumerate() {
            let (points, weights) = (s.curve.points().to_vec(), s.curve.weights().to_vec());
            let ok = s.knots.0 == end
                && s.knots.0 < s.knots.1
                && s.curve
                    .points()
                    .iter()
                    .all(|p| p.coords.iter().all(|c| c.abs() <= MAX_COORDINATE))
                && RationalBezier::new(points, weights).is_ok();
            self.check(ok, "Curve::bezier_spans", || {
                format!("{kind}: span {i} of {}: {:?}", spans.len(), s.knots)
            });
            end = s.knots.1;
        }
        self.check(end == domain.1, "Curve::bezier_spans", || {
            format!("{kind}: spans end at {end:e}, domain at {:e}", domain.1)
        });
    }

    fn flatten_check<const D: usize>(
        &mut self,
        kind: &'static str,
        result: Result<revolve::Flattening<D>, Error>,
        tolerance: f64,
    ) {
        if let Ok(flat) = result {
            let ok = flat.bound <= tolerance
                && flat.samples.len() >= 2
                && flat
                    .samples
                    .iter()
                    .all(|s| s.t.is_finite() && finite_point(&s.point) && finite(&s.derivative));
            self.check(ok, "flatten", || {
                format!("{kind}: tolerance {tolerance:e}, bound {:e}", flat.bound)
            });
        }
    }

    /// A tolerance for flattening: relative to the curve's scale mostly.
    fn flatten_tolerance(&mut self, scale: f64) -> f64 {
        match self.below(4) {
            0 => self.number(),
            _ => scale * 10f64.powf(self.rng.range(-6.0, 0.0)),
        }
    }
}

// ---------------------------------------------------------------------------
// Users' curve types, contract-abiding and not
// ---------------------------------------------------------------------------

/// How a user's curve behaves.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// A half circle of radius `r` written with cos/sin: the sphere.
    Sphere,
    /// An off-axis circle: a torus.
    Torus,
    /// Domain `(1, 0)`.
    Reversed,
    /// Domain `(NaN, 1)`.
    NanDomain,
    /// Domain `(−∞, ∞)`.
    InfiniteDomain,
    /// Domain `(−f64::MAX, f64::MAX)`.
    HugeDomain,
    /// NaN points and derivatives.
    NanEval,
    /// Infinite points.
    InfiniteEval,
    /// Bézier spans in reverse order.
    SpansOutOfOrder,
    /// No Bézier spans (an empty list).
    EmptySpans,
    /// One span on `(−∞, ∞)`.
    InfiniteSpans,
    /// A span on `(NaN, 1)`.
    NanSpanKnot,
    /// Spans of different degrees.
    MixedDegrees,
}

const KINDS: [Kind; 13] = [
    Kind::Sphere,
    Kind::Torus,
    Kind::Reversed,
    Kind::NanDomain,
    Kind::InfiniteDomain,
    Kind::HugeDomain,
    Kind::NanEval,
    Kind::InfiniteEval,
    Kind::SpansOutOfOrder,
    Kind::EmptySpans,
    Kind::InfiniteSpans,
    Kind::NanSpanKnot,
    Kind::MixedDegrees,
];

fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Sphere => "user Sphere",
        Kind::Torus => "user Torus",
        Kind::Reversed => "user Reversed",
        Kind::NanDomain => "user NanDomain",
        Kind::InfiniteDomain => "user InfiniteDomain",
        Kind::HugeDomain => "user HugeDomain",
        Kind::NanEval => "user NanEval",
        Kind::InfiniteEval => "user InfiniteEval",
        Kind::SpansOutOfOrder => "user SpansOutOfOrder",
        Kind::EmptySpans => "user EmptySpans",
        Kind::InfiniteSpans => "user InfiniteSpans",
        Kind::NanSpanKnot => "user NanSpanKnot",
        Kind::MixedDegrees => "user MixedDegrees",
    }
}

/// A user's curve: `kind` says how it breaks (or keeps) the contract.
#[derive(Debug, Clone, Copy)]
struct UserCurve {
    kind: Kind,
    r: f64,
}

impl UserCurve {
    /// The contract-abiding kinds move `t` into the domain as the crate's
    /// curves do (NaN to the start); the others use it as it is.
    fn inside(&self, t: f64) -> f64 {
        if !matches!(self.kind, Kind::Sphere | Kind::Torus) {
            return t;
        }
        let (a, b) = self.domain();
        if t >= a { t.min(b) } else { a }
    }

    fn line(a: (f64, f64), b: (f64, f64)) -> Bezier<2> {
        Bezier::new(vec![Point2::new(a.0, a.1), Point2::new(b.0, b.1)]).unwrap()
    }
}

impl Curve<2> for UserCurve {
    fn domain(&self) -> (f64, f64) {
        match self.kind {
            Kind::Reversed => (1.0, 0.0),
            Kind::NanDomain => (f64::NAN, 1.0),
            Kind::InfiniteDomain => (f64::NEG_INFINITY, f64::INFINITY),
            Kind::HugeDomain => (-f64::MAX, f64::MAX),
            Kind::Torus => (0.0, std::f64::consts::TAU),
            _ => (0.0, std::f64::consts::PI),
        }
    }

    fn eval(&self, t: f64) -> Point2<f64> {
        let r = self.r;
        let t = self.inside(t);
        match self.kind {
            Kind::NanEval => Point2::new(f64::NAN, t),
            Kind::InfiniteEval => Point2::new(f64::INFINITY, t),
            Kind::Torus => Point2::new(2.0 * r + r * t.cos(), r * t.sin()),
            _ => Point2::new(r * t.sin(), -r * t.cos()),
        }
    }

    fn derivative(&self, t: f64) -> Vector2<f64> {
        let r = self.r;
        let t = self.inside(t);
        match self.kind {
            Kind::NanEval => Vector2::new(f64::NAN, f64::NAN),
            Kind::InfiniteEval => Vector2::new(0.0, 1.0),
            Kind::Torus => Vector2::new(-r * t.sin(), r * t.cos()),
            _ => Vector2::new(r * t.cos(), r * t.sin()),
        }
    }

    fn bezier_spans(&self) -> Option<Vec<BezierSpan<2>>> {
        // Spans whose points Bezier::new accepts.
        let r = if self.r.abs() <= MAX_COORDINATE / 2.0 {
            self.r
        } else {
            1.0
        };
        let span = |knots, curve| BezierSpan { knots, curve };
        match self.kind {
            Kind::SpansOutOfOrder => Some(vec![
                span((1.0, 2.0), Self::line((r, 0.0), (r, r))),
                span((0.0, 1.0), Self::line((0.0, 0.0), (r, 0.0))),
            ]),
            Kind::EmptySpans => Some(Vec::new()),
            Kind::InfiniteSpans => Some(vec![span(
                (f64::NEG_INFINITY, f64::INFINITY),
                Self::line((r, 0.0), (r, r)),
            )]),
            Kind::NanSpanKnot => Some(vec![span((f64::NAN, 1.0), Self::line((r, 0.0), (r, r)))]),
            Kind::MixedDegrees => Some(vec![
                span((0.0, 1.0), Self::line((0.0, 0.0), (r, 0.0))),
                span(
                    (1.0, 2.0),
                    Bezier::new(vec![
                        Point2::new(r, 0.0),
                        Point2::new(2.0 * r, r),
                        Point2::new(r, 2.0 * r),
                    ])
                    .unwrap(),
                ),
            ]),
            _ => None,
        }
    }
}

// ---------------------------------------------------------------------------
// Targets
// ---------------------------------------------------------------------------

/// Curve constructors and evaluators: Bezier, BSpline (new, uniform,
/// clamped, insert_knot, derivative splines, flatten), in 1, 2 and 3
/// dimensions; seeds 0..100 000 in four parts.
fn fuzz_curves(seeds: std::ops::Range<u64>) {
    fuzz("curves", seeds, |f| match f.below(4) {
        0 => curve_case::<1>(f),
        1 => curve_case::<3>(f),
        _ => curve_case::<2>(f),
    });
}

#[test]
fn fuzz_curves_part_1() {
    fuzz_curves(0..25_000);
}

#[test]
fn fuzz_curves_part_2() {
    fuzz_curves(25_000..50_000);
}

#[test]
fn fuzz_curves_part_3() {
    fuzz_curves(50_000..75_000);
}

#[test]
fn fuzz_curves_part_4() {
    fuzz_curves(75_000..100_000);
}

fn curve_case<const D: usize>(f: &mut Fuzz) {
    let n = f.count();
    let scale = f.scale();
    let points: Vec<Point<f64, D>> = f.points(n, scale);

    // Bézier.
    let copy = points.clone();
    if let Some(Ok(c)) = f.call("Bezier::new", || Bezier::new(copy)) {
        f.own_curve("Bezier", &c, |c, t, k| c.nth_derivative(t, k).unwrap());
        let t = f.number();
        if let Some(Ok((left, right))) = f.call("Bezier::subdivide", || c.subdivide(t)) {
            for half in [left, right] {
                let ok = half
                    .points()
                    .iter()
                    .all(|p| p.coords.iter().all(|x| x.abs() <= MAX_COORDINATE));
                f.check(ok, "Bezier::subdivide", || {
                    format!("at {t:e}: beyond the limit")
                });
                let u = f.parameter((0.0, 1.0));
                if let Some(d) = f.call("Bezier::nth_derivative", || {
                    half.nth_derivative(u, 1 + (n % 4)).unwrap()
                }) {
                    f.check(finite(&d), "Bezier::subdivide", || {
                        format!("derivative {d:?}")
                    });
                }
            }
        }
        if let Some(h) = f.call("Bezier::hodograph", || c.hodograph()) {
            let u = f.parameter((0.0, 1.0));
            if let Some((p, d)) =
                f.call("Curve::eval_with_derivative", || h.eval_with_derivative(u))
            {
                f.check(finite_point(&p) && finite(&d), "Bezier::hodograph", || {
                    format!("at {u:e}: {p:?} {d:?}")
                });
            }
        }
        if n <= 30 {
            let tolerance = f.flatten_tolerance(scale);
            if let Some(r) = f.call("Bezier::flatten", || c.flatten(tolerance)) {
                f.flatten_check("Bezier", r, tolerance);
            }
        }
    }

    // B-splines.
    let degree = f.degree(n);
    let knots = f.knots(n, degree);
    let copy = points.clone();
    let spline = match f.below(4) {
        0 => f.call("BSpline::uniform", || BSpline::uniform(degree, copy)),
        1 => f.call("BSpline::clamped", || BSpline::clamped(degree, copy)),
        _ => f.call("BSpline::new", || BSpline::new(degree, knots, copy)),
    };
    let Some(Ok(s)) = spline else {
        return;
    };
    f.own_curve("BSpline", &s, |c, t, k| c.nth_derivative(t, k).unwrap());
    let t = f.parameter(s.domain());
    let times = match f.below(6) {
        0 => usize::MAX,
        1 => s.degree() + 1,
        _ => f.below(3),
    };
    if let Some(Ok(inserted)) = f.call("BSpline::insert_knot", || s.insert_knot(t, times)) {
        f.own_curve("BSpline after insert_knot", &inserted, |c, t, k| {
            c.nth_derivative(t, k).unwrap()
        });
    }
    let order = if f.chance(4) { usize::MAX } else { f.below(4) };
    if let Some(d) = f.call("BSpline::nth_derivative_spline", || {
        s.nth_derivative_spline(order)
    }) {
        let u = f.parameter(d.domain());
        if let Some((p, v)) = f.call("Curve::eval_with_derivative", || d.eval_with_derivative(u)) {
            f.check(
                finite_point(&p) && finite(&v),
                "BSpline::nth_derivative_spline",
                || format!("order {order} at {u:e}: {p:?} {v:?}"),
            );
        }
    }
    if n <= 30 {
        let tolerance = f.flatten_tolerance(scale);
        if let Some(r) = f.call("BSpline::flatten", || s.flatten(tolerance)) {
            f.flatten_check("BSpline", r, tolerance);
        }
    }
    f.queries("BSpline", &s);
    let times = if f.chance(8) { usize::MAX } else { f.below(3) };
    if let Some(Ok(up)) = f.call("BSpline::elevate_degree", || s.elevate_degree(times)) {
        f.own_curve("BSpline after elevate_degree", &up, |c, t, k| {
            c.nth_derivative(t, k).unwrap()
        });
    }

    // Rational curves: the same points with random (sometimes bad) weights.
    let weights = f.weights(n);
    let copy = points.clone();
    let w = weights.clone();
    if let Some(Ok(c)) = f.call("RationalBezier::new", || RationalBezier::new(copy, w)) {
        f.own_curve("RationalBezier", &c, |c, t, k| {
            c.nth_derivative(t, k).unwrap_or_else(|_| SVector::zeros())
        });
        f.queries("RationalBezier", &c);
    }
    let copy = points.clone();
    let knots = s.knots().to_vec();
    let degree = s.degree();
    let Some(Ok(r)) = f.call("Nurbs::new", || Nurbs::new(degree, knots, copy, weights)) else {
        return;
    };
    f.own_curve("Nurbs", &r, |c, t, k| {
        c.nth_derivative(t, k).unwrap_or_else(|_| SVector::zeros())
    });
    let t = f.parameter(r.domain());
    let times = f.below(3);
    if let Some(Ok(inserted)) = f.call("Nurbs::insert_knot", || r.insert_knot(t, times)) {
        f.own_curve("Nurbs after insert_knot", &inserted, |c, t, k| {
            c.nth_derivative(t, k).unwrap_or_else(|_| SVector::zeros())
        });
    }
    let times = if f.chance(8) { usize::MAX } else { f.below(3) };
    if let Some(Ok(up)) = f.call("Nurbs::elevate_degree", || r.elevate_degree(times)) {
        f.own_curve("Nurbs after elevate_degree", &up, |c, t, k| {
            c.nth_derivative(t, k).unwrap_or_else(|_| SVector::zeros())
        });
    }
    if n <= 30 {
        let tolerance = f.flatten_tolerance(scale);
        if let Some(r) = f.call("Nurbs::flatten", || r.flatten(tolerance)) {
            f.flatten_check("Nurbs", r, tolerance);
        }
    }
    f.queries("Nurbs", &r);
}

impl Fuzz {
    /// `n` weights: mostly in `[0.05, 20]`, sometimes extreme or invalid
    /// (zero, negative, NaN, infinite), sometimes one too few.
    fn weights(&mut self, n: usize) -> Vec<f64> {
        let mut w: Vec<f64> = (0..n)
            .map(|_| {
                if self.chance(40) {
                    self.extreme()
                } else {
                    0.05 * 400f64.powf(self.below(1001) as f64 / 1000.0)
                }
            })
            .collect();
        if self.chance(50) {
            w.pop();
        }
        w
    }

    /// The nearest point to a random (sometimes invalid) point, and the arc
    /// length at a random (sometimes invalid) tolerance: a finite answer
    /// or an error, never a panic or NaN.
    fn queries<const D: usize, C: Curve<D>>(&mut self, kind: &'static str, c: &C) {
        // One curve in eight: a query costs far more than an evaluation.
        if !self.chance(8) {
            return;
        }
        let scale = self.scale();
        let p: Point<f64, D> = Point::from(SVector::from_fn(|_, _| self.coordinate(scale)));
        if let Some(Ok(near)) = self.call("Curve::nearest_point", || c.nearest_point(&p)) {
            self.check(
                near.distance.is_finite() && finite_point(&near.point) && near.t.is_finite(),
                "Curve::nearest_point",
                || format!("{kind}: {near:?}"),
            );
        }
        let tolerance = if self.chance(4) {
            self.number()
        } else {
            1e-6 * scale
        };
        if let Some(Ok(length)) = self.call("Curve::arc_length", || c.arc_length(tolerance)) {
            self.check(
                length.length.is_finite() && length.lower <= length.upper,
                "Curve::arc_length",
                || format!("{kind}: {length:?}"),
            );
        }
    }
}

/// Users' curves that break the contract (and two that keep it) through
/// the trait's default methods: no panic, no hang.
#[test]
fn fuzz_user_curves() {
    fuzz("user curves", 0..400_000, |f| {
        let kind = KINDS[f.below(KINDS.len())];
        let r = if f.chance(4) { f.number() } else { f.scale() };
        let c = UserCurve { kind, r };
        let t = f.parameter(c.domain());
        let _ = f.call("Curve::eval_with_derivative", || c.eval_with_derivative(t));
        if let Some(Some(u)) = f.call("Curve::tangent", || c.tangent(t)) {
            f.check(unit_vector(&u), "Curve::tangent", || {
                format!("{kind:?} at {t:e}: {u:?}")
            });
        }
        let segments = f.below(9);
        if let Some(samples) = f.call("Curve::discretize", || c.discretize(segments)) {
            f.check(
                samples.len() == segments.max(1) + 1,
                "Curve::discretize",
                || format!("{kind:?}: {} samples", samples.len()),
            );
        }
        let segments = if f.chance(2) {
            usize::MAX
        } else {
            MAX_SEGMENTS + 1
        };
        if let Some(r) = f.call("Curve::try_discretize", || {
            c.try_discretize(segments).map(|v| v.len())
        }) {
            f.check(r.is_err(), "Curve::try_discretize", || {
                format!("{kind:?}: {r:?}")
            });
        }
        #[cfg(feature = "testing")]
        if let Some(r) = f.call("testing::check_curve_derivatives", || {
            revolve::testing::check_curve_derivatives(&c, 8)
        }) {
            let broken_domain = matches!(
                kind,
                Kind::Reversed | Kind::NanDomain | Kind::InfiniteDomain
            );
            if broken_domain {
                f.check(r.is_err(), "testing::check_curve_derivatives", || {
                    format!("{kind:?}: a broken domain passed")
                });
            }
        }
    });
}

/// Boxes: empty, infinite, NaN and ordinary ones through every method.
#[test]
fn fuzz_boxes() {
    fuzz("boxes", 0..500_000, |f| {
        let b = match f.below(6) {
            0 => Aabb::EMPTY,
            1 => Aabb {
                min: Point3::new(f.number(), f.number(), f.number()),
                max: Point3::new(f.number(), f.number(), f.number()),
            },
            2 => Aabb::new(
                Point3::new(f.extreme(), f.extreme(), f.extreme()),
                Point3::new(f.extreme(), f.extreme(), f.extreme()),
            ),
            _ => Aabb::from_points(&[
                Point3::new(f.number(), f.number(), f.number()),
                Point3::new(f.number(), f.number(), f.number()),
            ]),
        };
        if let Some(c) = f.call("Aabb::center", || b.center()) {
            f.check(c.iter().all(|x| !x.is_nan()), "Aabb::center", || {
                format!("{b:?}: {c:?}")
            });
            f.check(
                !b.is_empty() || c == Point3::origin(),
                "Aabb::center",
                || format!("empty {b:?}: {c:?}"),
            );
        }
        if let Some(e) = f.call("Aabb::extent", || b.extent()) {
            f.check(e.iter().all(|x| !x.is_nan()), "Aabb::extent", || {
                format!("{b:?}: {e:?}")
            });
        }
        if let Some(s) = f.call("Aabb::scale", || b.scale()) {
            f.check(!s.is_nan(), "Aabb::scale", || format!("{b:?}: {s}"));
        }
        let margin = f.number();
        if let Some(e) = f.call("Aabb::expand", || b.expand(margin)) {
            f.check(sane_box(&e), "Aabb::expand", || {
                format!("{b:?} by {margin}: {e:?}")
            });
        }
        let axis = Vector3::new(f.number(), f.number(), f.number());
        let shift = Vector3::new(f.coordinate(10.0), f.coordinate(10.0), f.coordinate(10.0));
        if let Some(m) = f.call("Isometry3::new", || Isometry3::new(shift, axis)) {
            if let Some(t) = f.call("Aabb::transformed", || b.transformed(&m)) {
                f.check(sane_box(&t), "Aabb::transformed", || {
                    format!("{b:?}: {t:?}")
                });
            }
        }
        let ray = Ray::new(
            Point3::new(f.coordinate(10.0), f.coordinate(10.0), f.coordinate(10.0)),
            f.direction(),
        );
        let (lo, hi) = f.t_range();
        if let Some(Some((a, z))) = f.call("Aabb::clip", || b.clip(&ray, lo, hi)) {
            f.check(!a.is_nan() && !z.is_nan() && a <= z, "Aabb::clip", || {
                format!("{b:?}, {ray:?}, ({lo}, {hi}): ({a}, {z})")
            });
        }
    });
}

/// Builds a profile for the surface targets: one of the crate's curves or
/// a user's.
enum Profile {
    Bezier(Bezier<2>),
    BSpline(BSpline<2>),
    Nurbs(Nurbs<2>),
    User(UserCurve),
}

fn profile(f: &mut Fuzz) -> Option<Profile> {
    let scale = f.scale();
    match f.below(5) {
        4 => {
            let n = 1 + f.below(10);
            let points = f.points::<2>(n, scale);
            let degree = f.below(4).min(n - 1);
            let knots = f.knots(n, degree);
            let weights = f.weights(n);
            f.call("Nurbs::new", || Nurbs::new(degree, knots, points, weights))?
                .ok()
                .map(Profile::Nurbs)
        }
        0 => {
            let n = 1 + f.below(6);
            let points = f.points::<2>(n, scale);
            f.call("Bezier::new", || Bezier::new(points))?
                .ok()
                .map(Profile::Bezier)
        }
        1 => {
            let n = 1 + f.below(12);
            let points = f.points::<2>(n, scale);
            let degree = f.below(4).min(n - 1);
            let knots = f.knots(n, degree);
            f.call("BSpline::new", || BSpline::new(degree, knots, points))?
                .ok()
                .map(Profile::BSpline)
        }
        2 => {
            let n = 2 + f.below(10);
            let points = f.points::<2>(n, scale);
            let degree = 1 + f.below(3).min(n - 2);
            f.call("BSpline::uniform", || BSpline::uniform(degree, points))?
                .ok()
                .map(Profile::BSpline)
        }
        _ => {
            let kind = KINDS[f.below(KINDS.len())];
            Some(Profile::User(UserCurve { kind, r: scale }))
        }
    }
}

/// Revolutions of the crate's and users' profiles: constructors
/// (`Revolution::new`, `with_axis`, `with_tolerance`, `Tolerance::relative`),
/// the surface's evaluators and patch bounds, `Intersect` (the exact
/// intersector), and tessellation.
#[test]
fn fuzz_revolutions() {
    fuzz("revolutions", 0..20_000, |f| match profile(f) {
        Some(Profile::Bezier(c)) => revolution_case(f, c, "Bezier", true),
        Some(Profile::BSpline(c)) => revolution_case(f, c, "BSpline", true),
        Some(Profile::Nurbs(c)) => revolution_case(f, c, "Nurbs", true),
        Some(Profile::User(c)) => {
            let keeps_contract = matches!(c.kind, Kind::Sphere | Kind::Torus);
            revolution_case(f, c, kind_name(c.kind), keeps_contract)
        }
        None => {}
    });
}

/// A placed revolution with a random tolerance and how it was placed, or
/// `None` if a call panicked.
fn revolution<C: Curve<2>>(f: &mut Fuzz, c: C) -> Option<(Revolution<C>, String)> {
    let mut s = f.call("Revolution::new", || Revolution::new(c))?;
    let mut how = String::new();
    if f.chance(2) {
        let origin = Point3::new(f.coordinate(10.0), f.coordinate(10.0), f.coordinate(10.0));
        let axis = Vector3::new(f.number(), f.number(), f.number());
        if let Some(axis) = Unit::try_new(axis, 0.0) {
            s = f.call("Revolution::with_axis", || s.with_axis(origin, axis))?;
            how += &format!(", axis through {origin:?} along {axis:?}");
        }
    }
    if f.chance(3) {
        let relative = f.number();
        let tolerance = f.call("Tolerance::relative", || Tolerance::relative(relative))?;
        s = f.call("Revolution::with_tolerance", || s.with_tolerance(tolerance))?;
        how += &format!(", tolerance {relative:e}");
    }
    Some((s, how))
}

/// A ray aimed at the box `b` (from outside, inside or far away), or an
/// extreme one.
fn ray_at(f: &mut Fuzz, b: &Aabb) -> Ray {
    let dir = f.direction();
    if b.is_empty() || f.chance(5) {
        let o = Point3::new(f.number(), f.number(), f.number());
        return Ray::new(o, dir);
    }
    let c = b.center();
    let size = b.extent().amax().min(f64::MAX / 8.0);
    let target = c + Vector3::new(
        f.rng.range(-0.5, 0.5),
        f.rng.range(-0.5, 0.5),
        f.rng.range(-0.5, 0.5),
    ) * size;
    let away = f.rng.direction() * size * 10f64.powf(f.rng.range(-1.0, 3.0));
    let origin = target + away;
    let len = dir.norm();
    let aim = if len > 0.0 && len.is_finite() && f.chance(2) {
        -away.normalize() * len
    } else {
        dir
    };
    Ray::new(origin, aim)
}

/// The surface targets on `c` (`profile` names it in failures). Points
/// and partials are judged only for profiles that keep the contract: a
/// user's curve that returns NaN makes its surface's points NaN.
fn revolution_case<C: Curve<2>>(f: &mut Fuzz, c: C, profile: &'static str, judged: bool) {
    let Some((s, how)) = revolution(f, c) else {
        return;
    };
    let profile = format!("{profile}{how}");
    let profile = profile.as_str();
    let Some(bounds) = f.call("Intersect::bounds", || s.bounds()) else {
        return;
    };
    f.check(sane_box(&bounds), "Intersect::bounds", || {
        format!("{profile}: {bounds:?}")
    });
    let [du, dv] = s.domain();
    for _ in 0..3 {
        let (u, v) = (f.parameter(du), f.parameter(dv));
        if let Some(p) = f.call("Surface::eval", || s.eval(u, v)) {
            f.check(!judged || finite_point(&p), "Surface::eval", || {
                format!("{profile} at ({u:e}, {v:e}): {p:?}")
            });
        }
        if let Some((a, b)) = f.call("Surface::partials", || s.partials(u, v)) {
            f.check(
                !judged || (finite(&a) && finite(&b)),
                "Surface::partials",
                || format!("{profile} at ({u:e}, {v:e}): {a:?} {b:?}"),
            );
        }
        if let Some(Some(n)) = f.call("Surface::normal", || s.normal(u, v)) {
            f.check(unit_vector(&n), "Surface::normal", || {
                format!("{profile} at ({u:e}, {v:e}): {n:?}")
            });
        }
        let (u1, v1) = (f.parameter(du), f.parameter(dv));
        if let Some(b) = f.call("PatchBounds::bound_patch", || {
            s.bound_patch((u.min(u1), u.max(u1)), (v.min(v1), v.max(v1)))
        }) {
            f.check(sane_box(&b), "PatchBounds::bound_patch", || {
                format!("{profile}: {b:?}")
            });
        }
    }
    for _ in 0..6 {
        let ray = ray_at(f, &bounds);
        let (lo, hi) = f.t_range();
        if let Some(Some(hit)) = f.call("Revolution::intersect", || s.intersect(&ray, lo, hi)) {
            f.hits += 1;
            f.check(sane_hit(&hit, lo, hi), "Revolution::intersect", || {
                format!("{profile}: {ray:?} in ({lo:e}, {hi:e}): {hit:?}")
            });
        }
    }
    batch_case(f, &s, &bounds, profile);
    if judged {
        aimed_case(f, &s, &bounds, s.tolerance(), profile);
    }
    queries_case(f, &s, &bounds, profile);
    if f.chance(8) {
        let scale = bounds.scale();
        let tolerance = match f.below(3) {
            0 => f.number(),
            _ => scale * 10f64.powf(f.rng.range(-2.5, 0.0)),
        };
        if let Some(Ok(mesh)) = f.call("Revolution::tessellate", || s.tessellate(tolerance)) {
            f.mesh_is_sane(profile, &mesh, tolerance);
        }
    }
    let sample = |f: &mut Fuzz| surface_sample(f, &s);
    nearest_case(f, (&bounds, judged), profile, &sample, &|p| {
        s.nearest_point(p)
    });
}

impl Fuzz {
    fn mesh_is_sane(&mut self, profile: &str, mesh: &Mesh, tolerance: f64) {
        let n = mesh.positions.len();
        let ok = n <= Mesh::MAX_VERTICES
            && mesh.normals.len() == n
            && mesh.uvs.len() == n
            && mesh.bound <= tolerance
            && mesh.positions.iter().all(finite_point)
            && mesh.normals.iter().all(unit_vector)
            && mesh.uvs.iter().all(|(u, v)| u.is_finite() && v.is_finite())
            && mesh.triangles.iter().flatten().all(|&i| (i as usize) < n);
        self.check(ok, "Revolution::tessellate", || {
            format!(
                "{profile}, tolerance {tolerance:e}: {n} vertices, bound {:e}",
                mesh.bound
            )
        });
        self.mesh_outputs(profile, mesh);
    }

    /// `Mesh::welded` (no more vertices, every index valid) and the OBJ and
    /// STL writers (into memory, without error).
    fn mesh_outputs(&mut self, kind: &str, mesh: &Mesh) {
        if !self.chance(4) {
            return;
        }
        if let Some(welded) = self.call("Mesh::welded", || mesh.welded()) {
            let n = welded.positions.len();
            let ok = n <= mesh.positions.len()
                && welded.normals.len() == n
                && welded.triangles.iter().flatten().all(|&i| (i as usize) < n);
            self.check(ok, "Mesh::welded", || format!("{kind}: {n} vertices"));
        }
        let mut out = Vec::new();
        if let Some(written) = self.call("Mesh::write_obj", || mesh.write_obj(&mut out)) {
            self.check(written.is_ok(), "Mesh::write_obj", || {
                format!("{kind}: {written:?}")
            });
        }
        out.clear();
        if let Some(written) = self.call("Mesh::write_stl", || mesh.write_stl(&mut out)) {
            self.check(written.is_ok(), "Mesh::write_stl", || {
                format!("{kind}: {written:?}")
            });
        }
    }
}

/// The generic Newton intersector on revolutions of the crate's and users'
/// profiles: construction (depths up to 5, clamped beyond), odd
/// tolerances, extreme rays and ranges, and its one-run entry point.
#[test]
fn fuzz_newton() {
    fuzz("newton", 0..3_000, |f| match profile(f) {
        Some(Profile::Bezier(c)) => newton_case(f, c),
        Some(Profile::BSpline(c)) => newton_case(f, c),
        Some(Profile::Nurbs(c)) => newton_case(f, c),
        Some(Profile::User(c)) => newton_case(f, c),
        None => {}
    });
}

fn newton_case<C: Curve<2>>(f: &mut Fuzz, c: C) {
    let Some((s, _)) = revolution(f, c) else {
        return;
    };
    // A huge depth is clamped to MAX_DEPTH (2¹⁶ leaves, 65536 patch
    // bounds): tried once in a while only.
    let depth = if f.chance(300) {
        u32::MAX
    } else {
        f.below(6) as u32
    };
    let Some(mut newton) = f.call("NewtonIntersector::new", || {
        NewtonIntersector::new(&s, depth)
    }) else {
        return;
    };
    if f.chance(3) {
        let tolerance = Tolerance {
            relative: f.number(),
            max_iterations: match f.below(4) {
                0 => 0,
                1 => u32::MAX,
                _ => 1 + f.below(64) as u32,
            },
        };
        newton = match f.call("NewtonIntersector::with_tolerance", || {
            newton.with_tolerance(tolerance)
        }) {
            Some(n) => n,
            None => return,
        };
    }
    let Some(bounds) = f.call("NewtonIntersector::bounds", || newton.bounds()) else {
        return;
    };
    f.check(sane_box(&bounds), "NewtonIntersector::bounds", || {
        format!("{bounds:?}")
    });
    for _ in 0..6 {
        let ray = ray_at(f, &bounds);
        let (lo, hi) = f.t_range();
        if let Some(Some(hit)) = f.call("NewtonIntersector::intersect", || {
            newton.intersect(&ray, lo, hi)
        }) {
            f.hits += 1;
            f.check(
                sane_hit(&hit, lo, hi),
                "NewtonIntersector::intersect",
                || format!("{ray:?} in ({lo:e}, {hi:e}): {hit:?}"),
            );
        }
    }
    let ray = ray_at(f, &bounds);
    let (t, u, v) = (f.number(), f.number(), f.number());
    if let Some(run) = f.call("NewtonIntersector::newton", || newton.newton(&ray, t, u, v)) {
        f.check(
            !run.converged || (run.t.is_finite() && run.uv.0.is_finite() && run.uv.1.is_finite()),
            "NewtonIntersector::newton",
            || format!("{ray:?} from ({t:e}, {u:e}, {v:e}): {run:?}"),
        );
    }
}

/// The `testing` feature's strategies and checkers with bad arguments:
/// every strategy yields a valid value, every checker returns.
#[cfg(feature = "testing")]
#[test]
fn fuzz_testing_support() {
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::TestRunner;
    use revolve::testing;

    fn one<S: Strategy>(strategy: S, seed: u64) -> Option<S::Value> {
        let mut bytes = [0u8; 32];
        bytes[..8].copy_from_slice(&seed.to_le_bytes());
        let config = proptest::test_runner::Config::default();
        let rng = proptest::test_runner::TestRng::from_seed(
            proptest::test_runner::RngAlgorithm::ChaCha,
            &bytes,
        );
        let mut runner = TestRunner::new_with_rng(config, rng);
        strategy.new_tree(&mut runner).ok().map(|t| t.current())
    }

    fuzz("testing support", 0..1_000, |f| {
        let scale = f.number();
        let (a, b) = (f.count() * f.below(3), f.count());
        let degrees = if f.chance(8) {
            usize::MAX..=usize::MAX
        } else {
            a..=b
        };
        let seed = f.rng.next_u64();
        if let Some(Some(p)) = f.call("testing::point", || one(testing::point::<3>(scale), seed)) {
            f.check(finite_point(&p), "testing::point", || {
                format!("scale {scale}: {p:?}")
            });
        }
        let d = degrees.clone();
        if let Some(c) = f.call("testing::bezier_curve", || {
            one(testing::bezier_curve::<2>(d, scale), seed)
        }) {
            f.check(
                c.as_ref().is_none_or(|c| c.degree() <= testing::MAX_DEGREE),
                "testing::bezier_curve",
                || format!("{degrees:?}, scale {scale}"),
            );
        }
        let d = degrees.clone();
        if let Some(Some(c)) = f.call("testing::bspline_curve", || {
            one(testing::bspline_curve::<2>(d, scale), seed)
        }) {
            let samples = if f.chance(4) { usize::MAX } else { f.below(40) };
            let _ = f.call("testing::check_curve_derivatives", || {
                testing::check_curve_derivatives(&c, samples)
            });
        }
        if let Some(Some(p)) = f.call("testing::profile", || one(testing::profile(scale), seed)) {
            let s = Revolution::new(p);
            let n = if f.chance(4) { usize::MAX } else { f.below(12) };
            let _ = f.call("testing::check_surface_partials", || {
                testing::check_surface_partials(&s, n)
            });
            let _ = f.call("testing::check_surface_normals", || {
                testing::check_surface_normals(&s, n)
            });
        }
        if let Some(Some(r)) = f.call("testing::ray", || one(testing::ray(scale), seed)) {
            f.check(
                finite_point(&r.origin) && finite(&r.dir) && r.dir != Vector3::zeros(),
                "testing::ray",
                || format!("scale {scale}: {r:?}"),
            );
        }
        let kind = KINDS[f.below(KINDS.len())];
        let s = Revolution::new(UserCurve { kind, r: 1.0 });
        let n = f.below(6);
        let _ = f.call("testing::check_surface_partials", || {
            testing::check_surface_partials(&s, n)
        });
    });
}

// ---------------------------------------------------------------------------
// Tensor-product surfaces
// ---------------------------------------------------------------------------

#[test]
fn fuzz_tensor_surfaces() {
    fuzz("tensor surfaces", 0..30_000, |f| {
        let (rows, cols) = (1 + f.below(5), 1 + f.below(5));
        let grid = control_grid(f, rows, cols);
        match f.below(3) {
            0 => {
                if let Some(Ok(s)) = f.call("BezierSurface::new", || BezierSurface::new(grid)) {
                    tensor_case(f, &s, "BezierSurface");
                    // Beside a copy of itself, or beside another patch of
                    // any shape and size (degenerate ones included: one
                    // row, one column, all points within 1e-9 of one).
                    let other = if f.chance(2) {
                        Some(s.clone())
                    } else {
                        let (rows, cols) = (1 + f.below(5), 1 + f.below(5));
                        let mut grid = control_grid(f, rows, cols);
                        if f.chance(3) {
                            let centre = grid.first().and_then(|r| r.first()).copied();
                            for p in grid.iter_mut().flatten() {
                                if let Some(c) = centre {
                                    *p = c + (*p - c) * 1e-9;
                                }
                            }
                        }
                        f.call("BezierSurface::new", || BezierSurface::new(grid))
                            .and_then(Result::ok)
                    };
                    if let Some(other) = other {
                        if let Some(Ok(m)) = f.call("BezierPatches::new", || {
                            BezierPatches::new(vec![s.clone(), other])
                        }) {
                            patches_case(f, &m);
                        }
                    }
                }
            }
            1 => {
                let degrees = (f.below(rows + 1), f.below(cols + 1));
                let knots = (f.knots(rows, degrees.0), f.knots(cols, degrees.1));
                if let Some(Ok(s)) = f.call("BSplineSurface::new", || {
                    BSplineSurface::new(degrees, knots, grid)
                }) {
                    tensor_case(f, &s, "BSplineSurface");
                    surface_constructions(f, &s);
                }
            }
            _ => {
                let degrees = (f.below(rows + 1), f.below(cols + 1));
                let knots = (f.knots(rows, degrees.0), f.knots(cols, degrees.1));
                let weights: Vec<Vec<f64>> = (0..rows).map(|_| f.weights(cols)).collect();
                if let Some(Ok(s)) = f.call("NurbsSurface::new", || {
                    NurbsSurface::new(degrees, knots, grid, weights)
                }) {
                    tensor_case(f, &s, "NurbsSurface");
                    surface_constructions(f, &s);
                }
            }
        }
    });
}

/// A grid of control points of `rows × cols` at a random scale, with now
/// and then a collapsed row (a pole, as on the teapot's lid), a ragged row
/// or no rows at all.
fn control_grid(f: &mut Fuzz, rows: usize, cols: usize) -> Vec<Vec<Point3<f64>>> {
    let scale = f.scale();
    let mut grid: Vec<Vec<Point3<f64>>> = (0..rows)
        .map(|_| {
            let mut row: Vec<Point3<f64>> = (0..cols)
                .map(|_| {
                    let c = [
                        f.coordinate(scale),
                        f.coordinate(scale),
                        f.coordinate(scale),
                    ];
                    Point3::new(c[0], c[1], c[2])
                })
                .collect();
            if f.chance(6) && !row.is_empty() {
                let first = row[0];
                row.iter_mut().for_each(|p| *p = first);
            }
            row
        })
        .collect();
    if f.chance(40) {
        grid[0].pop();
    }
    if f.chance(60) {
        grid.clear();
    }
    grid
}

/// A parameter: mostly inside the domain, sometimes extreme.
fn parameter(f: &mut Fuzz, (lo, hi): (f64, f64)) -> f64 {
    if f.chance(8) {
        f.number()
    } else {
        lo + (hi - lo) * f.rng.unit()
    }
}

/// Evaluation, bounds, intersection and meshing of a constructed tensor
/// surface: no panic, no NaN, every hit on its ray and on the surface.
fn tensor_case<S: Surface + Intersect + TensorMesh>(f: &mut Fuzz, s: &S, kind: &'static str) {
    let [du, dv] = s.domain();
    for _ in 0..4 {
        let (u, v) = (parameter(f, du), parameter(f, dv));
        if let Some(p) = f.call("Surface::eval", || s.eval(u, v)) {
            f.check(finite_point(&p), "Surface::eval", || {
                format!("{kind} ({u}, {v}): {p:?}")
            });
        }
        if let Some((a, b)) = f.call("Surface::partials", || s.partials(u, v)) {
            f.check(finite(&a) && finite(&b), "Surface::partials", || {
                format!("{kind} ({u}, {v}): {a:?} {b:?}")
            });
        }
        if let Some(Some(n)) = f.call("Surface::normal", || s.normal(u, v)) {
            f.check(unit_vector(&n), "Surface::normal", || {
                format!("{kind}: {n:?}")
            });
        }
    }
    let Some(bounds) = f.call("Intersect::bounds", || s.bounds()) else {
        return;
    };
    f.check(sane_box(&bounds), "Intersect::bounds", || {
        format!("{kind}: {bounds:?}")
    });
    for _ in 0..6 {
        let ray = ray_at(f, &bounds);
        let (t_min, t_max) = if f.chance(6) {
            (f.number(), f.number())
        } else {
            (0.0, f64::INFINITY)
        };
        if let Some(Some(hit)) = f.call("Intersect::intersect", || s.intersect(&ray, t_min, t_max))
        {
            f.hits += 1;
            f.check(sane_hit(&hit, t_min, t_max), "Intersect::intersect", || {
                format!("{kind}: {ray:?} ({t_min}, {t_max}): {hit:?}")
            });
            let on = s.eval(hit.uv.0, hit.uv.1);
            let size = bounds.extent().amax().max(ray.origin.coords.amax());
            f.check(
                (on - hit.point).norm() <= 1e-6 * size + parameter_rounding(s, hit.uv),
                "Intersect::intersect",
                || format!("{kind}: hit {hit:?} not on the surface ({on:?})"),
            );
        }
    }
    batch_case(f, s, &bounds, kind);
    aimed_case(f, s, &bounds, s.tolerance(), kind);
    queries_case(f, s, &bounds, kind);
    if f.chance(10) {
        let tolerance = if f.chance(3) {
            f.number()
        } else {
            bounds.extent().amax() * 10f64.powf(f.rng.range(-3.0, -1.0))
        };
        if let Some(Ok(mesh)) = f.call("tessellate", || s.mesh(tolerance)) {
            f.check(sane_mesh(&mesh), "tessellate", || {
                format!("{kind}: a NaN in the mesh")
            });
            f.mesh_outputs(kind, &mesh);
        }
    }
    let sample = |f: &mut Fuzz| surface_sample(f, s);
    nearest_case(f, (&bounds, true), kind, &sample, &|p| s.nearest(p));
}

/// `intersect_batch` over random rays and ranges (slices of unequal
/// lengths too): each answer is `intersect`'s for its ray and range.
fn batch_case<S: Intersect + ?Sized>(f: &mut Fuzz, s: &S, bounds: &Aabb, kind: &str) {
    let n = f.below(6);
    let rays: Vec<Ray> = (0..n).map(|_| ray_at(f, bounds)).collect();
    let ranges: Vec<(f64, f64)> = (0..n + f.below(2))
        .map(|_| {
            if f.chance(5) {
                (f.number(), f.number())
            } else {
                (0.0, f64::INFINITY)
            }
        })
        .collect();
    let mut hits = vec![None; n.saturating_sub(f.below(2))];
    if f.call("Intersect::intersect_batch", || {
        s.intersect_batch(&rays, &ranges, &mut hits)
    })
    .is_none()
    {
        return;
    }
    for ((ray, &(t_min, t_max)), hit) in rays.iter().zip(&ranges).zip(&hits) {
        let single = s.intersect(ray, t_min, t_max);
        f.check(
            single.map(|h| h.t.to_bits()) == hit.map(|h| h.t.to_bits()),
            "Intersect::intersect_batch",
            || format!("{kind}: {ray:?} ({t_min}, {t_max}): batch {hit:?}, single {single:?}"),
        );
    }
}

/// `intersect_all` and `occluded` on random rays and ranges: every hit in
/// the range, `t` increasing, the first `intersect`'s; `occluded` exactly
/// whether `intersect` hits.
fn queries_case<S: Intersect + ?Sized>(f: &mut Fuzz, s: &S, bounds: &Aabb, kind: &str) {
    let mut hits = Vec::new();
    for _ in 0..2 {
        let ray = ray_at(f, bounds);
        let (t_min, t_max) = if f.chance(5) {
            (f.number(), f.number())
        } else {
            (0.0, f64::INFINITY)
        };
        let Some(occluded) = f.call("Intersect::occluded", || s.occluded(&ray, t_min, t_max))
        else {
            continue;
        };
        if f.call("Intersect::intersect_all", || {
            s.intersect_all(&ray, t_min, t_max, &mut hits)
        })
        .is_none()
        {
            continue;
        }
        let single = s.intersect(&ray, t_min, t_max);
        f.check(occluded == single.is_some(), "Intersect::occluded", || {
            format!("{kind}: {ray:?} ({t_min}, {t_max}): {occluded}, intersect {single:?}")
        });
        let ordered = hits.windows(2).all(|w| w[0].t < w[1].t);
        let inside = hits.iter().all(|h| h.t > t_min && h.t < t_max);
        let first = hits.first().map(|h| h.t.to_bits()) == single.map(|h| h.t.to_bits());
        f.check(
            ordered && inside && first,
            "Intersect::intersect_all",
            || format!("{kind}: {ray:?} ({t_min}, {t_max}): {hits:?}, intersect {single:?}"),
        );
    }
}

/// The intersection contract on aimed rays: a ray through a surface point
/// `S(u, v)` (interior of the domain, a normal there, crossing at more than
/// about 6° from the tangent plane) hits, not beyond that point and on the
/// ray. Judged for surfaces of size 1e-150 … 1e100 (the documented range and
/// well above the underflow of squared sizes), rays from up to 1e6 sizes
/// away with directions of length 1e-100 … 1e100. The accuracy owed is the
/// surface's `tolerance` (relative to its box's scale), at best 1e-9.
fn aimed_case<S: Surface + Intersect>(
    f: &mut Fuzz,
    s: &S,
    bounds: &Aabb,
    tolerance: &Tolerance,
    kind: &str,
) {
    let size = bounds.extent().amax();
    if !(1e-150..=1e100).contains(&size) {
        return;
    }
    let [du, dv] = s.domain();
    let (u, v) = (
        du.0 + (du.1 - du.0) * f.rng.range(0.05, 0.95),
        dv.0 + (dv.1 - dv.0) * f.rng.range(0.05, 0.95),
    );
    let (target, Some(normal)) = (s.eval(u, v), s.normal(u, v)) else {
        return;
    };
    let unit = f.rng.direction();
    if unit.dot(&normal).abs() < 0.1 {
        return;
    }
    let dir = unit * 10f64.powf(f.rng.range(-100.0, 100.0));
    let back = size * 10f64.powf(f.rng.range(0.0, 6.0)) / dir.norm();
    let ray = Ray::new(target - dir * back, dir);
    // The rounded origin puts the line `miss` from the target; the surface
    // must reach well beyond that around it (its parameters do by 0.05 of
    // the domain at least: judged where the partials carry that far) for a
    // hit to be owed.
    // (The difference loses the target below the origin's rounding.)
    let miss = (target - ray.origin).cross(&unit).norm()
        + 4.0 * f64::EPSILON * (ray.origin.coords.norm() + target.coords.norm());
    let (su, sv) = s.partials(u, v);
    let (du_len, dv_len) = (0.05 * (du.1 - du.0), 0.05 * (dv.1 - dv.0));
    // The parameter rectangle's image is at least as wide as the smaller
    // singular value of (S_u du, S_v dv) (not just the shorter partial: a
    // needle-like piece has long, nearly parallel partials).
    let (a, b) = (su * du_len, sv * dv_len);
    // (Unit vectors in the cross product: its norm would overflow at 1e100.)
    let reach_around = a.normalize().cross(&b.normalize()).norm() * a.norm().min(b.norm());
    let owed = miss <= 1e-3 * reach_around;
    if !owed {
        return;
    }
    let Some(hit) = f.call("Intersect::intersect (aimed)", || {
        s.intersect(&ray, 0.0, f64::INFINITY)
    }) else {
        return;
    };
    f.check(hit.is_some(), "Intersect::intersect (aimed)", || {
        format!("{kind} of size {size:e}: {ray:?} aimed at ({u}, {v}) = {target:?} missed")
    });
    f.aimed += 1;
    if let Some(hit) = hit {
        let reach = size + hit.t * dir.norm();
        let off = (ray.origin + ray.dir * hit.t - hit.point).norm();
        // Beyond the aimed point by the miss and the tolerance at a 6°
        // crossing at most.
        let accuracy = tolerance.clamped().relative * bounds.scale();
        let late = back * 1e-9 + 10.0 * (miss + accuracy) / dir.norm();
        f.check(
            hit.t <= back + late && off <= 1e-9 * reach + 10.0 * accuracy,
            "Intersect::intersect (aimed)",
            || format!("{kind} of size {size:e}: {ray:?} aimed at t = {back}: {hit:?}, {off:e} off the ray"),
        );
    }
}

/// `nearest_point` from query points near the surface, on it (a surface
/// point nudged), and anywhere (any coordinates, NaN included): an answer
/// whose distance is `|point − P|`; certified, no surface sample `eval(uv)`
/// (from `sample`, 32 random draws) is nearer beyond `1e-9` of the size; an
/// `InvalidQueryPoint` error only for a query point beyond the limits.
/// Surfaces whose profile breaks the curve contract (its spans another
/// curve than its `eval`) are not `judged` against the samples.
fn nearest_case(
    f: &mut Fuzz,
    (bounds, judged): (&Aabb, bool),
    kind: &str,
    sample: &dyn Fn(&mut Fuzz) -> Option<Point3<f64>>,
    nearest: &dyn Fn(&Point3<f64>) -> Result<SurfaceNearest, Error>,
) {
    let p = match f.below(3) {
        0 if !bounds.is_empty() => {
            let size = bounds.extent().amax().min(f64::MAX / 8.0);
            bounds.center() + f.rng.direction() * size * 10f64.powf(f.rng.range(-3.0, 1.0))
        }
        1 => match sample(f) {
            Some(q) => {
                q + f.rng.direction() * q.coords.amax() * 10f64.powf(f.rng.range(-16.0, -2.0))
            }
            None => return,
        },
        _ => Point3::new(f.number(), f.number(), f.number()),
    };
    let Some(answer) = f.call("nearest_point", || nearest(&p)) else {
        return;
    };
    let valid = p.coords.iter().all(|c| c.abs() <= MAX_COORDINATE);
    let near = match answer {
        Ok(near) => near,
        Err(e) => {
            let refused = matches!(e, Error::InvalidQueryPoint { .. });
            f.check(!refused || !valid, "nearest_point", || {
                format!("{kind}: {p:?} refused: {e:?}")
            });
            return;
        }
    };
    let size = bounds.scale().max(p.coords.amax());
    // Lengths scaled before squaring: tiny surfaces' squares underflow.
    let length = |v: Vector3<f64>| {
        let m = v.amax();
        if m > 0.0 { m * (v / m).norm() } else { 0.0 }
    };
    let computed = length(near.point - p);
    f.check(
        finite_point(&near.point)
            && near.distance.is_finite()
            && (computed - near.distance).abs() <= 1e-9 * size,
        "nearest_point",
        || format!("{kind}: {p:?}: {near:?} (|point − P| = {computed:e})"),
    );
    if near.certified && judged {
        for _ in 0..32 {
            let Some(q) = sample(f) else {
                continue;
            };
            let d = length(q - p);
            f.check(d >= near.distance - 1e-9 * size, "nearest_point", || {
                format!("{kind} of scale {size:e}: {p:?}: {near:?}, but {q:?} is at {d:e}")
            });
        }
    }
}

/// A random point `S(u, v)` of a surface's domain.
fn surface_sample<S: Surface>(f: &mut Fuzz, s: &S) -> Option<Point3<f64>> {
    let [du, dv] = s.domain();
    let (u, v) = (
        du.0 + (du.1 - du.0) * f.rng.unit(),
        dv.0 + (dv.1 - dv.0) * f.rng.unit(),
    );
    let q = s.eval(u, v);
    finite_point(&q).then_some(q)
}

/// A model of patches: intersection without panic or NaN.
fn patches_case(f: &mut Fuzz, m: &BezierPatches) {
    let b = m.bounds();
    batch_case(f, m, &b, "BezierPatches");
    queries_case(f, m, &b, "BezierPatches");
    for _ in 0..3 {
        let ray = ray_at(f, &b);
        if let Some(Some((k, hit))) = f.call("BezierPatches::intersect_patch", || {
            m.intersect_patch(&ray, 0.0, f64::INFINITY)
        }) {
            f.check(
                k < m.len() && sane_hit(&hit, 0.0, f64::INFINITY),
                "BezierPatches",
                || format!("{ray:?}: {k} {hit:?}"),
            );
        }
    }
    let sample = |f: &mut Fuzz| {
        let k = f.below(m.len());
        surface_sample(f, &m.patches()[k])
    };
    nearest_case(f, (&b, true), "BezierPatches", &sample, &|p| {
        m.nearest_point(p)
    });
}

/// The tensor surfaces' `tessellate`, `tolerance` and `nearest_point`,
/// behind one name.
trait TensorMesh {
    fn mesh(&self, tolerance: f64) -> Result<Mesh, Error>;
    fn tolerance(&self) -> &Tolerance;
    fn nearest(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error>;
}

impl TensorMesh for BezierSurface {
    fn mesh(&self, tolerance: f64) -> Result<Mesh, Error> {
        self.tessellate(tolerance)
    }
    fn tolerance(&self) -> &Tolerance {
        BezierSurface::tolerance(self)
    }
    fn nearest(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.nearest_point(p)
    }
}

impl TensorMesh for BSplineSurface {
    fn mesh(&self, tolerance: f64) -> Result<Mesh, Error> {
        self.tessellate(tolerance)
    }
    fn tolerance(&self) -> &Tolerance {
        BSplineSurface::tolerance(self)
    }
    fn nearest(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.nearest_point(p)
    }
}

impl TensorMesh for NurbsSurface {
    fn mesh(&self, tolerance: f64) -> Result<Mesh, Error> {
        self.tessellate(tolerance)
    }
    fn tolerance(&self) -> &Tolerance {
        NurbsSurface::tolerance(self)
    }
    fn nearest(&self, p: &Point3<f64>) -> Result<SurfaceNearest, Error> {
        self.nearest_point(p)
    }
}

/// No NaN anywhere in a mesh.
fn sane_mesh(m: &Mesh) -> bool {
    m.positions.iter().all(finite_point)
        && m.normals.iter().all(unit_vector)
        && m.uvs.iter().all(|(u, v)| u.is_finite() && v.is_finite())
        && m.bound.is_finite()
}

// ---------------------------------------------------------------------------
// Serde input
// ---------------------------------------------------------------------------

/// What a mutated number becomes: extremes, out-of-range values and other
/// JSON kinds.
#[cfg(feature = "serde")]
const JSON_REPLACEMENTS: [&str; 16] = [
    "1e308",
    "-1e308",
    "5e-324",
    "0",
    "-0",
    "1e101",
    "-1e101",
    "1e-320",
    "1e400",
    "123456789012345678901234567890",
    "null",
    "true",
    "\"x\"",
    "[]",
    "{}",
    "18446744073709551615",
];

/// Mutates a JSON text: a number replaced, a span deleted, an array element
/// repeated, or the text cut short.
#[cfg(feature = "serde")]
fn mutate_json(f: &mut Fuzz, json: &str) -> String {
    let bytes = json.as_bytes();
    let at = |f: &mut Fuzz| f.below(bytes.len().max(1));
    match f.below(5) {
        0 | 1 => {
            // The number that starts at or after a random position.
            let start = (at(f)..bytes.len())
                .find(|&i| {
                    (bytes[i].is_ascii_digit() || bytes[i] == b'-')
                        && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric())
                })
                .unwrap_or(0);
            let end = (start + 1..bytes.len())
                .find(|&i| !matches!(bytes[i], b'0'..=b'9' | b'.' | b'e' | b'E' | b'-' | b'+'))
                .unwrap_or(bytes.len());
            let with = JSON_REPLACEMENTS[f.below(JSON_REPLACEMENTS.len())];
            format!("{}{with}{}", &json[..start], &json[end.min(json.len())..])
        }
        2 => {
            let start = at(f);
            let end = (start + 1 + f.below(8)).min(json.len());
            format!("{}{}", &json[..start], &json[end..])
        }
        3 => {
            // Repeat the bracketed element that starts at a random '['.
            let start = (at(f)..bytes.len())
                .find(|&i| bytes[i] == b'[')
                .unwrap_or(0);
            let mut depth = 0;
            let end = (start..bytes.len())
                .find(|&i| {
                    match bytes[i] {
                        b'[' => depth += 1,
                        b']' => depth -= 1,
                        _ => {}
                    }
                    depth == 0
                })
                .map_or(bytes.len(), |i| i + 1);
            let element = &json[start..end];
            format!("{}{element},{element}{}", &json[..start], &json[end..])
        }
        _ => json[..at(f)].to_string(),
    }
}

/// Serializes `value`, mutates the text and reads it back as a `T`: no
/// panic, no hang; what is accepted is usable (`usable`) and serializes.
#[cfg(feature = "serde")]
fn serde_case<T: serde::Serialize + serde::de::DeserializeOwned>(
    f: &mut Fuzz,
    value: &T,
    kind: &'static str,
    usable: fn(&T) -> bool,
) {
    let Ok(json) = serde_json::to_string(value) else {
        f.fail("serde: serialize", format!("{kind} does not serialize"));
        return;
    };
    for _ in 0..4 {
        let mutated = mutate_json(f, &json);
        if let Some(Ok(back)) = f.call("serde: deserialize", || serde_json::from_str::<T>(&mutated))
        {
            let ok = usable(&back) && serde_json::to_string(&back).is_ok();
            f.check(ok, "serde: deserialize", || {
                format!("{kind} accepted but not usable: {mutated}")
            });
        }
    }
}

/// Serde input for every serializable type: valid objects of random shape,
/// their JSON mutated (numbers replaced by extremes and other kinds, spans
/// deleted, elements repeated, text cut short), read back.
#[cfg(feature = "serde")]
#[test]
fn fuzz_serde_input() {
    fn curve_ok<const D: usize, C: Curve<D>>(c: &C) -> bool {
        let (a, b) = c.domain();
        finite_point(&c.eval(a)) && finite_point(&c.eval(0.5 * (a + b)))
    }
    fn surface_ok<S: Surface + Intersect>(s: &S) -> bool {
        let [u, v] = s.domain();
        let b = s.bounds();
        finite_point(&s.eval(0.5 * (u.0 + u.1), 0.5 * (v.0 + v.1)))
            && sane_box(&b)
            && s.intersect(
                &Ray::new(Point3::new(0.3, 0.2, -1e3), Vector3::z()),
                0.0,
                f64::INFINITY,
            )
            .is_none_or(|h| sane_hit(&h, 0.0, f64::INFINITY))
    }
    fuzz("serde input", 0..20_000, |f| {
        let scale = 10f64.powf(f.rng.range(-3.0, 3.0));
        let n = 2 + f.below(5);
        let points2: Vec<Point2<f64>> = (0..n)
            .map(|_| {
                Point2::new(
                    f.rng.range(0.1, 1.0) * scale,
                    f.rng.range(-1.0, 1.0) * scale,
                )
            })
            .collect();
        let degree = 1 + f.below(n - 1);
        let clamped: Vec<f64> = (0..n + degree + 1)
            .map(|i| (i.saturating_sub(degree)).min(n - degree) as f64)
            .collect();
        let weights: Vec<f64> = (0..n).map(|_| f.rng.range(0.2, 5.0)).collect();
        let (rows, cols) = (2 + f.below(3), 2 + f.below(3));
        let grid: Vec<Vec<Point3<f64>>> = (0..rows)
            .map(|i| {
                (0..cols)
                    .map(|j| Point3::new(i as f64, j as f64, f.rng.range(-1.0, 1.0)) * scale)
                    .collect()
            })
            .collect();
        let grid_weights: Vec<Vec<f64>> = (0..rows)
            .map(|_| (0..cols).map(|_| f.rng.range(0.2, 5.0)).collect())
            .collect();
        match f.below(10) {
            0 => serde_case(
                f,
                &Bezier::new(points2).unwrap(),
                "Bezier",
                curve_ok::<2, _>,
            ),
            1 => serde_case(
                f,
                &BSpline::new(degree, clamped, points2).unwrap(),
                "BSpline",
                curve_ok::<2, _>,
            ),
            2 => serde_case(
                f,
                &Nurbs::new(degree, clamped, points2, weights).unwrap(),
                "Nurbs",
                curve_ok::<2, _>,
            ),
            3 => serde_case(
                f,
                &RationalBezier::new(points2, weights).unwrap(),
                "RationalBezier",
                curve_ok::<2, _>,
            ),
            4 => serde_case(
                f,
                &Revolution::new(Nurbs::new(degree, clamped, points2, weights).unwrap()),
                "Revolution",
                surface_ok,
            ),
            5 => serde_case(
                f,
                &BezierSurface::new(grid).unwrap(),
                "BezierSurface",
                surface_ok,
            ),
            6 => serde_case(
                f,
                &BSplineSurface::new(
                    (rows - 1, cols - 1),
                    (bezier_knots(rows), bezier_knots(cols)),
                    grid,
                )
                .unwrap(),
                "BSplineSurface",
                surface_ok,
            ),
            7 => serde_case(
                f,
                &NurbsSurface::new(
                    (rows - 1, cols - 1),
                    (bezier_knots(rows), bezier_knots(cols)),
                    grid,
                    grid_weights,
                )
                .unwrap(),
                "NurbsSurface",
                surface_ok,
            ),
            8 => {
                let patch = BezierSurface::new(grid).unwrap();
                let model = BezierPatches::new(vec![patch.clone(), patch]).unwrap();
                serde_case(f, &model, "BezierPatches", surface_ok_patches);
            }
            _ => {
                serde_case(f, &Tolerance::relative(1e-9), "Tolerance", |t| {
                    t.relative.is_finite()
                });
                let ray = Ray::new(Point3::new(1.0, 2.0, 3.0), Vector3::new(0.0, 0.0, -1.0));
                serde_case(f, &ray, "Ray", |_| true);
                let aabb = Aabb::new(Point3::origin(), Point3::new(1.0, 2.0, 3.0));
                serde_case(f, &aabb, "Aabb", |_| true);
            }
        }
    });
}

/// A model read back: its bounds and a ray are sane.
#[cfg(feature = "serde")]
fn surface_ok_patches(m: &BezierPatches) -> bool {
    sane_box(&m.bounds())
        && m.intersect(
            &Ray::new(Point3::new(0.3, 0.2, -1e3), Vector3::z()),
            0.0,
            f64::INFINITY,
        )
        .is_none_or(|h| sane_hit(&h, 0.0, f64::INFINITY))
}

// ---------------------------------------------------------------------------
// Constructions on tensor surfaces, Bernstein kernels
// ---------------------------------------------------------------------------

/// Clamped Bézier knots `0…0 1…1` of `m` each.
fn bezier_knots(m: usize) -> Vec<f64> {
    [vec![0.0; m], vec![1.0; m]].concat()
}

/// What the construction checks need of a spline surface kind.
trait SplineSurface: Surface + Intersect + Sized {
    const NAME: &'static str;
    fn second(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>);
    fn insert(&self, along_u: bool, t: f64, times: usize) -> Result<Self, Error>;
    /// Each Bézier piece read back by its kind's constructor.
    fn pieces_back(&self) -> Vec<Result<(), Error>>;
}

/// The members the spline surface kinds share (their inherent methods have
/// the same names).
macro_rules! spline_surface_members {
    ($name:literal) => {
        const NAME: &'static str = $name;
        fn second(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
            self.second_partials(u, v)
        }
        fn insert(&self, along_u: bool, t: f64, times: usize) -> Result<Self, Error> {
            if along_u {
                self.insert_knot_u(t, times)
            } else {
                self.insert_knot_v(t, times)
            }
        }
    };
}

impl SplineSurface for BSplineSurface {
    spline_surface_members!("BSplineSurface");
    fn pieces_back(&self) -> Vec<Result<(), Error>> {
        self.to_bezier_patches()
            .into_iter()
            .map(|piece| BezierSurface::new(piece.surface.points().to_vec()).map(|_| ()))
            .collect()
    }
}

impl SplineSurface for NurbsSurface {
    spline_surface_members!("NurbsSurface");
    fn pieces_back(&self) -> Vec<Result<(), Error>> {
        let (p, q) = self.degrees();
        let knots = || (bezier_knots(p + 1), bezier_knots(q + 1));
        self.to_bezier_patches()
            .into_iter()
            .map(|piece| {
                NurbsSurface::new((p, q), knots(), piece.points, piece.weights).map(|_| ())
            })
            .collect()
    }
}

/// A spline surface's second partials (finite), its Bézier pieces (each
/// accepted back by its kind's constructor) and knot insertion (the same
/// surface, or an error for a bad knot).
fn surface_constructions<S: SplineSurface>(f: &mut Fuzz, s: &S) {
    let kind = S::NAME;
    let [du, dv] = s.domain();
    let (u, v) = (parameter(f, du), parameter(f, dv));
    if let Some((a, b, c)) = f.call("second_partials", || s.second(u, v)) {
        f.check(
            finite(&a) && finite(&b) && finite(&c),
            "second_partials",
            || format!("{kind} ({u}, {v}): {a:?} {b:?} {c:?}"),
        );
    }
    if f.chance(4) {
        if let Some(back) = f.call("to_bezier_patches", || s.pieces_back()) {
            for piece in back {
                f.check(piece.is_ok(), "to_bezier_patches", || {
                    format!("{kind}: a piece is refused: {piece:?}")
                });
            }
        }
    }
    let along_u = f.chance(2);
    let (t, times) = (parameter(f, if along_u { du } else { dv }), 1 + f.below(3));
    if let Some(Ok(refined)) = f.call("insert_knot", || s.insert(along_u, t, times)) {
        let scale = s.bounds().scale();
        let (a, b) = (s.eval(u, v), refined.eval(u, v));
        f.check((a - b).norm() <= 1e-9 * scale, "insert_knot", || {
            format!("{kind}, t {t} ×{times}: {a:?} became {b:?}")
        });
    }
}

/// The Bernstein kernels at any degree and parameter: `binomial` is never
/// NaN, `bernstein` never NaN for a finite `t`, de Casteljau and subdivision
/// of finite coefficients finite for `t` in `[0, 1]`, the power basis of
/// low degree agreeing with de Casteljau.
#[test]
fn fuzz_bernstein_kernels() {
    use revolve::bernstein::{
        bernstein, binomial, de_casteljau, horner, subdivide, to_power_basis,
    };
    fuzz("bernstein kernels", 0..100_000, |f| {
        let n = match f.below(4) {
            0 => f.rng.next_u64() as usize,
            1 => f.below(5000),
            _ => f.below(30),
        };
        let i = if f.chance(2) {
            f.below(n.saturating_add(2).min(1 << 20))
        } else {
            f.rng.next_u64() as usize
        };
        if let Some(c) = f.call("bernstein::binomial", || binomial(n, i)) {
            f.check(!c.is_nan() && c >= 0.0, "bernstein::binomial", || {
                format!("C({n}, {i}) = {c}")
            });
        }
        let t = if f.chance(3) {
            f.number()
        } else {
            f.rng.unit()
        };
        if let Some(b) = f.call("bernstein::bernstein", || bernstein(n, i, t)) {
            f.check(
                !t.is_finite() || !b.is_nan(),
                "bernstein::bernstein",
                || format!("B({n}, {i}, {t}) = {b}"),
            );
        }
        let m = 1 + f.below(40);
        let c: Vec<f64> = (0..m)
            .map(|_| f.rng.range(-1.0, 1.0) * 10f64.powf(f.rng.range(-100.0, 100.0)))
            .collect();
        let t = f.rng.unit();
        let mut work = c.clone();
        if let Some(Some(v)) = f.call("bernstein::de_casteljau", || de_casteljau(&mut work, t)) {
            f.check(v.is_finite(), "bernstein::de_casteljau", || {
                format!("{c:?} at {t}: {v}")
            });
            if m <= 12 {
                let power = to_power_basis(&c);
                let scale = c.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
                let h = horner(&power, t).unwrap_or(f64::NAN);
                f.check(
                    (h - v).abs() <= 1e-9 * scale,
                    "bernstein::to_power_basis",
                    || format!("{c:?} at {t}: Horner {h} vs de Casteljau {v}"),
                );
            }
        }
        let (mut left, mut right) = (vec![0.0; m], vec![0.0; m]);
        if let Some(true) = f.call("bernstein::subdivide", || {
            subdivide(&c, t, &mut left, &mut right)
        }) {
            f.check(
                left.iter().chain(&right).all(|x| x.is_finite()),
                "bernstein::subdivide",
                || format!("{c:?} at {t}"),
            );
        }
    });
}

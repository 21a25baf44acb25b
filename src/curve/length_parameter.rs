//! The parameter at a given arc length, and the division of a curve into
//! pieces of equal length ([`Curve::parameter_at_length`],
//! [`Curve::divide_by_length`]).
//!
//! # Method
//! The curve's [rational Bézier spans](Curve::rational_bezier_spans) are
//! measured once with [`Curve::arc_length`] (each to its share of a quarter
//! of the tolerance, in proportion to its control polygon's length), giving
//! cumulative lengths with rigorous brackets. The span where the length `s`
//! is reached is found from them; inside it, `t` solves `L(u) = s − L₀`
//! (`L₀` the spans before, `L(u)` the length of the span's piece `[0, u]`,
//! measured on its exact de Casteljau half to a quarter of the tolerance)
//! by Newton's method with `L′(u) = |C′(u)|`, kept in a shrinking bracket
//! and replaced by bisection when a step leaves it or the speed vanishes,
//! until the estimate is within a quarter of the tolerance. The answer is
//! then checked against the rigorous brackets: `lower ≤ L(a, t) ≤ upper`
//! with `max(upper − s, s − lower) ≤ tolerance`; if the brackets are too
//! wide the whole is done again with an eighth of the budget, and if that
//! fails too the error says so. So for curves with spans the answer is
//! certified. A curve without spans gets the same Newton iteration on its
//! whole domain with the sampled quadrature, whose upper bound is infinite:
//! its answer rests on the error estimate only.

use super::{ArcLength, Curve, MAX_SEGMENTS, RationalBezierSpan, clamp_to_domain, scaled_norm};
use crate::{Error, RationalBezier};
use nalgebra::{Point, SVector};

/// Most Newton or bisection steps in one span (bisection alone halves the
/// bracket to below an ulp in 64 steps).
const MAX_STEPS: usize = 200;

/// How the curve's lengths are measured: by spans, or on the whole domain.
enum Source<'a, C: ?Sized, const D: usize> {
    /// The spans, each with its length measured.
    Spans {
        spans: Vec<RationalBezierSpan<D>>,
        lengths: Vec<ArcLength>,
    },
    /// A curve without spans.
    Whole(&'a C),
}

/// A curve's lengths, measured once, for many length queries.
struct LengthTable<'a, C: ?Sized, const D: usize> {
    source: Source<'a, C, D>,
    /// The whole length's estimate and bracket.
    total: ArcLength,
    tolerance: f64,
}

/// The length of a control polygon.
fn polygon_length<const D: usize>(points: &[Point<f64, D>]) -> f64 {
    points.windows(2).map(|w| scaled_norm(w[1] - w[0])).sum()
}

/// The restriction of a curve to `[a, end]` (for curves without spans):
/// evaluation forwarded, clamped to that interval.
struct Restricted<'a, C: ?Sized> {
    curve: &'a C,
    domain: (f64, f64),
}

impl<C: Curve<D> + ?Sized, const D: usize> Curve<D> for Restricted<'_, C> {
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
    fn eval(&self, t: f64) -> Point<f64, D> {
        self.curve.eval(clamp_to_domain(t, self.domain))
    }
    fn derivative(&self, t: f64) -> SVector<f64, D> {
        self.curve.derivative(clamp_to_domain(t, self.domain))
    }
}

/// `x + y` for two brackets, estimates and error estimates.
fn add(x: ArcLength, y: ArcLength) -> ArcLength {
    ArcLength {
        length: x.length + y.length,
        error_bound: x.error_bound + y.error_bound,
        lower: x.lower + y.lower,
        upper: x.upper + y.upper,
        pieces: x.pieces + y.pieces,
    }
}

/// The length zero, exactly.
const ZERO: ArcLength = ArcLength {
    length: 0.0,
    error_bound: 0.0,
    lower: 0.0,
    upper: 0.0,
    pieces: 0,
};

impl<'a, C: Curve<D> + ?Sized, const D: usize> LengthTable<'a, C, D> {
    /// Measures the curve; `budget` is the share of the tolerance each
    /// stage may use (a quarter, then an eighth of that).
    fn new(curve: &'a C, tolerance: f64, budget: f64) -> Result<Self, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidTolerance { tolerance });
        }
        let share = tolerance * budget;
        match curve.rational_bezier_spans() {
            Some(spans) => {
                let polygon: f64 = spans.iter().map(|s| polygon_length(s.curve.points())).sum();
                let mut lengths = Vec::with_capacity(spans.len());
                let mut total = ZERO;
                for span in &spans {
                    let own = polygon_length(span.curve.points());
                    let length = if own > 0.0 {
                        span.curve.arc_length(share * (own / polygon))?
                    } else {
                        ZERO
                    };
                    total = add(total, length);
                    lengths.push(length);
                }
                Ok(LengthTable {
                    source: Source::Spans { spans, lengths },
                    total,
                    tolerance,
                })
            }
            None => {
                let total = curve.arc_length(share)?;
                Ok(LengthTable {
                    source: Source::Whole(curve),
                    total,
                    tolerance,
                })
            }
        }
    }

    /// The parameter where the length from the start reaches `s`, with
    /// the bracket of `L(a, t)` (`s` in `[0, total.length]`).
    fn parameter(&self, s: f64, budget: f64) -> Result<(f64, ArcLength), Error> {
        let share = self.tolerance * budget;
        match &self.source {
            Source::Spans { spans, lengths, .. } => {
                // The span where the cumulative estimate reaches s.
                let mut before = ZERO;
                let mut index = spans.len() - 1;
                for (j, l) in lengths.iter().enumerate() {
                    if before.length + l.length >= s || j + 1 == spans.len() {
                        index = j;
                        break;
                    }
                    before = add(before, *l);
                }
                let span = &spans[index];
                let whole = lengths[index];
                let target = s - before.length;
                let partial = |u: f64| piece_length(&span.curve, u, share, whole);
                let speed = |u: f64| scaled_norm(span.curve.derivative(u));
                let guess = if whole.length > 0.0 {
                    target / whole.length
                } else {
                    0.5
                };
                let (u, part) = solve(target, (0.0, 1.0), guess, share, partial, speed)?;
                let (k0, k1) = span.knots;
                let t = if u <= 0.0 {
                    k0
                } else if u >= 1.0 {
                    k1
                } else {
                    (k0 + (k1 - k0) * u).clamp(k0, k1)
                };
                Ok((t, add(before, part)))
            }
            Source::Whole(curve) => {
                let (a, b) = curve.domain();
                let partial = |t: f64| {
                    if t <= a {
                        return Ok(ZERO);
                    }
                    Restricted {
                        curve: *curve,
                        domain: (a, t.min(b)),
                    }
                    .arc_length(share)
                };
                let speed = |t: f64| scaled_norm(curve.derivative(t));
                let guess = if self.total.length > 0.0 {
                    a + (b - a) * (s / self.total.length)
                } else {
                    a
                };
                solve(s, (a, b), guess, share, partial, speed)
            }
        }
    }
}

/// The length of the piece `[0, u]` of a span (its exact de Casteljau left
/// half) to `share`; the whole span's measure at `u = 1`, zero at `u = 0`.
fn piece_length<const D: usize>(
    span: &RationalBezier<D>,
    u: f64,
    share: f64,
    whole: ArcLength,
) -> Result<ArcLength, Error> {
    if u <= 0.0 {
        return Ok(ZERO);
    }
    if u >= 1.0 {
        return Ok(whole);
    }
    let (left, _) = span.split(u)?;
    if polygon_length(left.points()) == 0.0 {
        return Ok(ZERO);
    }
    left.arc_length(share)
}

/// Safeguarded Newton on `L(x) − target` over `bracket`, from `guess`,
/// until the estimate is within `share`: the root and the length there.
fn solve(
    target: f64,
    (mut lo, mut hi): (f64, f64),
    guess: f64,
    share: f64,
    length: impl Fn(f64) -> Result<ArcLength, Error>,
    speed: impl Fn(f64) -> f64,
) -> Result<(f64, ArcLength), Error> {
    let mut x = guess.clamp(lo, hi);
    let mut best = (x, length(x)?);
    for _ in 0..MAX_STEPS {
        let l = best.1;
        let residual = l.length - target;
        if residual.abs() <= share {
            return Ok(best);
        }
        if residual > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        if lo.is_nan() || hi.is_nan() || lo >= hi {
            break;
        }
        let v = speed(x);
        let newton = x - residual / v;
        let mid = lo + 0.5 * (hi - lo);
        x = if v > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            mid
        };
        if x <= lo || x >= hi {
            // The bracket is down to adjacent floats.
            break;
        }
        best = (x, length(x)?);
    }
    Ok(best)
}

/// Checks `s` against the whole length: `[0, length + tolerance]`.
fn check_length(s: f64, total: &ArcLength, tolerance: f64) -> Result<(), Error> {
    if s >= 0.0 && s <= total.length + tolerance {
        Ok(())
    } else {
        Err(Error::LengthOutOfRange {
            s,
            length: total.length,
        })
    }
}

/// Whether the bracket of `L(a, t)` certifies `|L(a, t) − s| ≤ tolerance`
/// (or, for curves without spans, the estimate does).
fn certified(length: &ArcLength, s: f64, tolerance: f64) -> bool {
    if length.upper.is_finite() {
        (length.upper - s).max(s - length.lower) <= tolerance
    } else {
        (length.length - s).abs() + length.error_bound <= tolerance
    }
}

/// The parameters at the lengths `targets` (each in `[0, total]`), with a
/// retry at an eighth of the budget when a bracket is too wide.
fn parameters<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    tolerance: f64,
    targets: impl Fn(&ArcLength) -> Result<Vec<f64>, Error>,
) -> Result<Vec<f64>, Error> {
    let mut last = None;
    for budget in [0.25, 0.25 / 8.0] {
        let table = LengthTable::new(curve, tolerance, budget)?;
        let (a, b) = curve.domain();
        let wanted = targets(&table.total)?;
        let mut out = Vec::with_capacity(wanted.len());
        let mut all_certified = true;
        for &s in &wanted {
            if s <= 0.0 {
                out.push(a);
                continue;
            }
            if s >= table.total.length {
                // The end: certified when the whole length's bracket is.
                all_certified &= certified(&table.total, s, tolerance);
                out.push(b);
                continue;
            }
            let (t, length) = table.parameter(s, budget)?;
            all_certified &= certified(&length, s, tolerance);
            last = Some(length);
            out.push(t);
        }
        if all_certified {
            return Ok(out);
        }
    }
    let achieved = last.map_or(tolerance, |l| l.upper - l.lower);
    Err(Error::ToleranceTooSmall {
        tolerance,
        min: achieved,
    })
}

/// [`Curve::parameter_at_length`].
pub(crate) fn parameter_at_length<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    s: f64,
    tolerance: f64,
) -> Result<f64, Error> {
    let out = parameters(curve, tolerance, |total| {
        check_length(s, total, tolerance)?;
        Ok(vec![s])
    })?;
    Ok(out[0])
}

/// [`Curve::divide_by_length`].
pub(crate) fn divide_by_length<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    pieces: usize,
    tolerance: f64,
) -> Result<Vec<f64>, Error> {
    if pieces == 0 {
        return Err(Error::ZeroPieces);
    }
    if pieces > MAX_SEGMENTS {
        return Err(Error::TooManySegments {
            segments: pieces,
            max: MAX_SEGMENTS,
        });
    }
    parameters(curve, tolerance, |total| {
        let mut targets = crate::allocation::try_with_capacity(pieces + 1)?;
        targets.extend((0..=pieces).map(|i| {
            if i == pieces {
                total.length
            } else {
                total.length * (i as f64 / pieces as f64)
            }
        }));
        Ok(targets)
    })
}

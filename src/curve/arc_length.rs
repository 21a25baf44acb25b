//! Arc length `L = ∫ |C′(t)| dt` to a requested tolerance, with a rigorous
//! bracket and an error estimate.
//!
//! # Method
//! Each rational Bézier span is integrated in its own parameter `s ∈ [0, 1]`
//! (the length does not depend on the parametrization) by adaptive
//! Gauss–Legendre quadrature: on a piece `[s₀, s₁]` the rules of 8 and 16
//! points give `G₈` and `G₁₆`; the piece is accepted when `|G₁₆ − G₈|` is
//! within its share of the tolerance and `G₁₆` lies in the piece's rigorous
//! bracket (below), and halved otherwise (at most 40 levels deep, at most
//! 2¹⁸ pieces in all). `length` is the sum of the `G₁₆`. The speed `|C′(s)|`
//! is evaluated from the span's own homogeneous coefficients (de Casteljau
//! and the quotient rule), so its rounding does not grow with the depth.
//!
//! # What is rigorous and what is estimated
//! - **Rigorous** (up to a rounding margin that is added): `lower ≤ L ≤
//!   upper`. For a piece of a rational Bézier curve with positive weights,
//!   the chord is at most the arc length, which is at most the length of
//!   the piece's control polygon: de Casteljau subdivision (on homogeneous
//!   points, each projected point lies on the segment between the two it
//!   combines) never lengthens the polygon, and the polygons converge to the
//!   curve (Farin, *Curves and Surfaces for CAGD*, §4.4 and ch. 13). `lower`
//!   and `upper` are the sums over the final pieces.
//! - **Estimated**: `error_bound` is `Σ |G₁₆ − G₈|` over the pieces (the
//!   error of the lower-order rule, which for a smooth integrand greatly
//!   exceeds that of the reported higher-order one) plus a bound on the
//!   rounding of the evaluation, capped by the rigorous
//!   `max(length − lower, upper − length)`. It is at most the requested
//!   tolerance unless the depth or piece limit was reached. An integrand
//!   that fools both rules at once on a piece (a feature narrower than the
//!   nodes' spacing) also lies outside the piece's bracket only if it is
//!   large, so the estimate is trustworthy for curves whose spans are not
//!   pathologically wiggly; the bracket always holds.
//!
//! Curves without spans (a user's own [`Curve`]) get the same adaptive
//! quadrature on their domain, starting from 16 equal pieces, with
//! `derivative` as the integrand: `lower` (the sum of chords) is rigorous
//! up to the curve's own evaluation, `upper` is infinite, and
//! `error_bound` is the estimate alone.

use super::homogeneous::{Homogeneous, project, project_with_derivative};
use super::query::validate_spans;
use super::RationalBezierSpan;
use crate::bernstein::{self, subdivide};
use crate::scratch::with_scratch;
use crate::{Curve, Error};
use nalgebra::Point;

/// The low and high orders of the Gauss–Legendre pair.
const LOW_ORDER: usize = 8;
const HIGH_ORDER: usize = 16;

/// Deepest halving of a piece.
const MAX_DEPTH: u32 = 40;

/// Most pieces in all; beyond, remaining pieces are accepted as they are.
const MAX_PIECES: usize = 1 << 18;

/// Tolerances below this multiple of the length scale (the control
/// polygon's length, or the sampled chords') are refused: the sums' own
/// rounding is a few `1e-15` of the length.
const MIN_RELATIVE_TOLERANCE: f64 = 1e-13;

/// Pieces a curve without spans starts from.
const FALLBACK_PIECES: usize = 16;

/// The arc length of a curve and how well it is known; see
/// [`Curve::arc_length`] and the [module docs](self) for what is rigorous
/// (`lower`, `upper`) and what is estimated (`error_bound`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcLength {
    /// The length: the sum of 16-point Gauss–Legendre values over the
    /// adaptive pieces.
    pub length: f64,
    /// The estimated bound on `|length − L|`: the sum of the differences of
    /// the 8- and 16-point rules, plus a rounding bound, at most the
    /// rigorous `max(length − lower, upper − length)`. At most the
    /// requested tolerance unless the piece limits were reached.
    pub error_bound: f64,
    /// A rigorous lower bound on `L`: the sum of the pieces' chords.
    pub lower: f64,
    /// A rigorous upper bound on `L`: the sum of the pieces' control-polygon
    /// lengths; infinite for curves without rational spans.
    pub upper: f64,
    /// The number of pieces integrated.
    pub pieces: usize,
}

/// The nodes and weights of one Gauss–Legendre rule on `[0, 1]`.
struct Rule {
    nodes: [f64; HIGH_ORDER],
    weights: [f64; HIGH_ORDER],
    len: usize,
}

impl Rule {
    /// The `n`-point rule (`n ≤ HIGH_ORDER`): the roots `xᵢ` of the
    /// Legendre polynomial `Pₙ` by Newton's method from
    /// `cos(π(i − ¼)/(n + ½))`, weights `2/((1 − xᵢ²)Pₙ′(xᵢ)²)` (Abramowitz
    /// & Stegun 25.4.29), mapped from `[−1, 1]` to `[0, 1]`.
    fn new(n: usize) -> Self {
        let mut rule = Rule {
            nodes: [0.0; HIGH_ORDER],
            weights: [0.0; HIGH_ORDER],
            len: n,
        };
        for i in 0..n {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut slope = 1.0;
            for _ in 0..100 {
                // P₀ … Pₙ at x by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                slope = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / slope;
                x -= step;
                if step.abs() <= 1e-16 {
                    break;
                }
            }
            rule.nodes[i] = 0.5 * (1.0 - x);
            rule.weights[i] = 1.0 / ((1.0 - x * x) * slope * slope);
        }
        rule
    }

    /// `∫_{s₀}^{s₁} f` by this rule.
    fn integrate(
        &self,
        (s0, s1): (f64, f64),
        mut f: impl FnMut(f64) -> Result<f64, Error>,
    ) -> Result<f64, Error> {
        let h = s1 - s0;
        let mut sum = 0.0;
        for i in 0..self.len {
            sum += self.weights[i] * f(s0 + h * self.nodes[i])?;
        }
        Ok(h * sum)
    }
}

/// What the adaptive quadrature needs of a curve on a parameter interval.
trait Source<const D: usize> {
    /// The speed `|dC/ds|`.
    fn speed(&self, s: f64) -> Result<f64, Error>;
    /// The point `C(s)`.
    fn point(&self, s: f64) -> Result<Point<f64, D>, Error>;
    /// A rigorous upper bound on the length of `[s₀, s₁]` (infinite if none).
    fn polygon(&self, s0: f64, s1: f64) -> f64;
}

/// One rational Bézier span, its homogeneous coefficients (weights scaled
/// so the largest is 1).
struct SpanSource<const D: usize> {
    coeffs: Vec<Homogeneous<D>>,
}

impl<const D: usize> SpanSource<D> {
    fn new(span: &RationalBezierSpan<D>) -> Self {
        let weights = span.curve.weights();
        let top = weights.iter().fold(0.0_f64, |m, &w| m.max(w));
        let coeffs = span
            .curve
            .points()
            .iter()
            .zip(weights)
            .map(|(p, &w)| Homogeneous::new(p, w / top))
            .collect();
        SpanSource { coeffs }
    }

    /// A bound on the rounding of the speed per unit of parameter: the
    /// hodograph's coefficients `n·Δ(wP)` carry `2ε` of `2n·max|wP|`, de
    /// Casteljau adds `nε` of that, the quotient rule divides by `w ≥ w_min`:
    /// `4(n + 1)²ε·max|P|·(w_max/w_min)`.
    fn rounding(span: &RationalBezierSpan<D>) -> f64 {
        let n = span.curve.degree() as f64;
        let scale = span
            .curve
            .points()
            .iter()
            .fold(0.0_f64, |m, p| m.max(p.coords.amax()));
        let w = span.curve.weights();
        let (lo, hi) = w.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        4.0 * (n + 1.0) * (n + 1.0) * f64::EPSILON * scale * (hi / lo)
    }
}

impl<const D: usize> Source<D> for SpanSource<D> {
    fn speed(&self, s: f64) -> Result<f64, Error> {
        let (h, dh) = bernstein::eval_with_derivative(&self.coeffs, s)
            .unwrap_or((Homogeneous::zero(), Homogeneous::zero()));
        Ok(project_with_derivative(h, dh).1.norm())
    }

    fn point(&self, s: f64) -> Result<Point<f64, D>, Error> {
        Ok(project(
            bernstein::eval(&self.coeffs, s).unwrap_or_else(Homogeneous::zero),
        ))
    }

    /// The control polygon of the piece `[s₀, s₁]`, from two de Casteljau
    /// subdivisions of the span.
    fn polygon(&self, s0: f64, s1: f64) -> f64 {
        let len = self.coeffs.len();
        with_scratch(3 * len, Homogeneous::zero(), |buf| {
            let (piece, rest) = buf.split_at_mut(len);
            let (left, right) = rest.split_at_mut(len);
            piece.copy_from_slice(&self.coeffs);
            if s0 > 0.0 {
                subdivide(piece, s0, left, right);
                piece.copy_from_slice(right);
            }
            if s1 < 1.0 {
                subdivide(piece, (s1 - s0) / (1.0 - s0), left, right);
                piece.copy_from_slice(left);
            }
            piece
                .windows(2)
                .map(|w| (project(w[1]) - project(w[0])).norm())
                .sum()
        })
    }
}

/// A user's curve on its own parameter.
struct CurveSource<'a, C: ?Sized> {
    curve: &'a C,
}

impl<C: Curve<D> + ?Sized, const D: usize> Source<D> for CurveSource<'_, C> {
    fn speed(&self, t: f64) -> Result<f64, Error> {
        let v = self.curve.derivative(t).norm();
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Error::CurveNotFinite { t })
        }
    }

    fn point(&self, t: f64) -> Result<Point<f64, D>, Error> {
        let c = self.curve.eval(t);
        if c.coords.iter().all(|x| x.abs() <= crate::MAX_COORDINATE) {
            Ok(c)
        } else {
            Err(Error::CurveNotFinite { t })
        }
    }

    fn polygon(&self, _: f64, _: f64) -> f64 {
        f64::INFINITY
    }
}

/// The running sums of the accepted pieces.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    length: f64,
    estimate: f64,
    lower: f64,
    upper: f64,
    pieces: usize,
}

/// The adaptive quadrature: the fixed inputs.
struct Adaptive<'a, S> {
    source: &'a S,
    low: &'a Rule,
    high: &'a Rule,
    /// The error allowed on a piece, from its parameter width and polygon.
    allowed: &'a dyn Fn(f64, f64) -> f64,
}

impl<S> Adaptive<'_, S> {
    /// Integrates `[s₀, s₁]` (end points `p0`, `p1`) into `tally`, halving
    /// until the piece is accepted.
    fn run<const D: usize>(
        &self,
        (s0, s1): (f64, f64),
        (p0, p1): (Point<f64, D>, Point<f64, D>),
        depth: u32,
        tally: &mut Tally,
    ) -> Result<(), Error>
    where
        S: Source<D>,
    {
        let chord = (p1 - p0).norm();
        let polygon = self.source.polygon(s0, s1);
        let speed = |s: f64| self.source.speed(s);
        let low = self.low.integrate((s0, s1), speed)?;
        let high = self.high.integrate((s0, s1), speed)?;
        let difference = (high - low).abs();
        let slack = 1e-12 * polygon.min(high.abs() + chord) + f64::MIN_POSITIVE;
        let bracketed = high >= chord - slack && high <= polygon + slack;
        let converged = difference <= (self.allowed)(s1 - s0, polygon) && bracketed;
        let mid = 0.5 * (s0 + s1);
        if converged || depth >= MAX_DEPTH || tally.pieces >= MAX_PIECES || mid <= s0 || mid >= s1
        {
            tally.length += high;
            tally.estimate += difference;
            tally.lower += chord;
            tally.upper += polygon;
            tally.pieces += 1;
            return Ok(());
        }
        let pm = self.source.point(mid)?;
        self.run((s0, mid), (p0, pm), depth + 1, tally)?;
        self.run((mid, s1), (pm, p1), depth + 1, tally)
    }
}

/// [`Error::InvalidTolerance`] unless finite and positive.
fn check_tolerance(tolerance: f64) -> Result<(), Error> {
    if tolerance.is_finite() && tolerance > 0.0 {
        Ok(())
    } else {
        Err(Error::InvalidTolerance { tolerance })
    }
}

/// [`Error::ToleranceTooSmall`] below `min`.
fn check_minimum(tolerance: f64, min: f64) -> Result<(), Error> {
    if tolerance < min {
        Err(Error::ToleranceTooSmall { tolerance, min })
    } else {
        Ok(())
    }
}

/// [`Curve::arc_length`].
pub(crate) fn arc_length<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    tolerance: f64,
) -> Result<ArcLength, Error> {
    check_tolerance(tolerance)?;
    let (low, high) = (Rule::new(LOW_ORDER), Rule::new(HIGH_ORDER));
    match curve.rational_bezier_spans() {
        Some(spans) => spans_length(&spans, tolerance, &low, &high),
        None => sampled_length(curve, tolerance, &low, &high),
    }
}

/// The arc length of rational Bézier spans.
fn spans_length<const D: usize>(
    spans: &[RationalBezierSpan<D>],
    tolerance: f64,
    low: &Rule,
    high: &Rule,
) -> Result<ArcLength, Error> {
    validate_spans(spans)?;
    let sources: Vec<SpanSource<D>> = spans.iter().map(SpanSource::new).collect();
    let polygons: Vec<f64> = sources.iter().map(|s| s.polygon(0.0, 1.0)).collect();
    let total: f64 = polygons.iter().sum();
    let rounding: f64 = spans.iter().map(SpanSource::rounding).sum();
    check_minimum(
        tolerance,
        (MIN_RELATIVE_TOLERANCE * total).max(4.0 * rounding),
    )?;
    if total == 0.0 {
        return Ok(ArcLength {
            length: 0.0,
            error_bound: 0.0,
            lower: 0.0,
            upper: 0.0,
            pieces: spans.len(),
        });
    }
    // Half the tolerance shared by the pieces' polygons (a piece's polygon
    // bounds its length), half by parameter width: the sums over the final
    // pieces are at most the tolerance.
    let count = spans.len() as f64;
    let allowed = |width: f64, polygon: f64| {
        tolerance * (0.5 * polygon / total + 0.5 * width / count).min(1.0)
    };
    let mut tally = Tally::default();
    for source in &sources {
        let adaptive = Adaptive {
            source,
            low,
            high,
            allowed: &allowed,
        };
        let ends = (source.point(0.0)?, source.point(1.0)?);
        adaptive.run((0.0, 1.0), ends, 0, &mut tally)?;
    }
    // Rounding: the speeds' (rounding per unit parameter, one unit per
    // span), the sums', and the polygons' and chords' vertices.
    let sums = 2.0 * (HIGH_ORDER as f64 + tally.pieces as f64) * f64::EPSILON;
    let evaluation = rounding + sums * tally.length;
    let margin = rounding * (1.0 + tally.pieces as f64) + sums * tally.upper;
    Ok(finish(tally, evaluation, margin))
}

/// The estimate, the bracket widened by `margin`, and the error bound
/// capped by the bracket.
fn finish(tally: Tally, evaluation: f64, margin: f64) -> ArcLength {
    let lower = (tally.lower - margin).max(0.0);
    let upper = tally.upper + margin;
    let length = tally.length.clamp(lower, upper);
    let rigorous = (length - lower).max(upper - length);
    ArcLength {
        length,
        error_bound: (tally.estimate + evaluation).min(rigorous),
        lower,
        upper,
        pieces: tally.pieces,
    }
}

/// The arc length of a curve known only by `eval` and `derivative`.
fn sampled_length<C: Curve<D> + ?Sized, const D: usize>(
    curve: &C,
    tolerance: f64,
    low: &Rule,
    high: &Rule,
) -> Result<ArcLength, Error> {
    let (a, b) = curve.domain();
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(Error::InvalidDomain { start: a, end: b });
    }
    let source = CurveSource { curve };
    let at = |i: usize| match i {
        0 => a,
        i if i == FALLBACK_PIECES => b,
        i => {
            let s = i as f64 / FALLBACK_PIECES as f64;
            a * (1.0 - s) + b * s
        }
    };
    let mut ends = Vec::with_capacity(FALLBACK_PIECES + 1);
    for i in 0..=FALLBACK_PIECES {
        ends.push(source.point(at(i))?);
    }
    let chords: f64 = ends.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    check_minimum(tolerance, MIN_RELATIVE_TOLERANCE * chords)?;
    let width = b - a;
    let allowed = |w: f64, _: f64| tolerance * (w / width).min(1.0);
    let adaptive = Adaptive {
        source: &source,
        low,
        high,
        allowed: &allowed,
    };
    let mut tally = Tally::default();
    for i in 0..FALLBACK_PIECES {
        adaptive.run((at(i), at(i + 1)), (ends[i], ends[i + 1]), 0, &mut tally)?;
    }
    let sums = 2.0 * (HIGH_ORDER as f64 + tally.pieces as f64) * f64::EPSILON;
    let (evaluation, margin) = (sums * tally.length, sums * tally.lower);
    Ok(finish(tally, evaluation, margin))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rules integrate polynomials of degree `2n − 1` exactly (checked
    /// on `xᵏ`, whose integral over `[0, 1]` is `1/(k + 1)`), and their
    /// weights sum to one.
    #[test]
    fn gauss_legendre_rules_are_exact_to_degree_2n_minus_1() {
        for n in [1, 2, 5, LOW_ORDER, HIGH_ORDER] {
            let rule = Rule::new(n);
            let total: f64 = rule.weights[..n].iter().sum();
            assert!((total - 1.0).abs() < 1e-15, "n={n}: {total}");
            for k in 0..2 * n {
                let got = rule
                    .integrate((0.0, 1.0), |x| Ok(x.powi(k as i32)))
                    .unwrap();
                let want = 1.0 / (k + 1) as f64;
                assert!((got - want).abs() < 1e-15, "n={n}, x^{k}: {got} vs {want}");
            }
            // Not exact one degree higher (the rule has exactly n points;
            // beyond n = 8 that error is below double precision).
            if n <= LOW_ORDER {
                let k = 2 * n as i32;
                let got = rule.integrate((0.0, 1.0), |x| Ok(x.powi(k))).unwrap();
                assert!((got - 1.0 / (k + 1) as f64).abs() > 1e-12, "n={n}");
            }
        }
    }
}

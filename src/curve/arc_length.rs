//! Arc length `L = ∫ |C′(t)| dt` to a requested tolerance, with a rigorous
//! bracket and an error estimate: the method and what is rigorous are in the
//! docs of [`ArcLength`].

use super::gauss_remainder::gauss_remainder;
use super::homogeneous::{
    Homogeneous, homogeneous_points, max_weight, project, project_with_derivative,
};
use super::query::{scaled_span, spans_magnitude, validate_spans};
use super::unit_scale::UnitScale;
use super::{RationalBezierSpan, check_tolerance, max_abs_coordinate};
use crate::bernstein::{self, subdivide};
use crate::scratch::with_scratch;
use crate::{Curve, Error};
use nalgebra::Point;

/// Points of the Gauss–Legendre rule.
const ORDER: usize = 16;

/// Deepest halving of a piece.
const MAX_DEPTH: u32 = 40;

/// Most pieces in all; beyond, remaining pieces are accepted as they are
/// (and the reported `error_bound` says so). Each piece costs 33 rational
/// evaluations and two subdivisions, so this bounds a call's time: about
/// 0.1 s for a degree-28 rational curve with wild weights.
const MAX_PIECES: usize = 1 << 13;

/// Most halvings of one span's pieces made only to tighten a bracket (the
/// estimate having converged). Pieces whose bracket a halving cannot
/// tighten, as where the rounding of a high-degree span's coefficients
/// outweighs the quadrature's remainder, are then accepted as they are
/// instead of being halved up to the piece limit.
const MAX_TIGHTENINGS: usize = 1024;

/// The work allowed for one span's certificates, in evaluations of a
/// coefficient (a certificate of a degree-`n` span samples it at up to
/// `4n − 3` points, each `(n + 1)²` such evaluations): about 10 ms. Later
/// pieces keep their chords and polygons. Only wild spans (high degree, a
/// speed that nearly vanishes, thousands of pieces) reach it.
const MAX_CERTIFICATE_WORK: usize = 1 << 24;

/// Tolerances below this multiple of the length scale (the control
/// polygon's length, or the sampled chords') are refused: the sums' own
/// rounding is a few `1e-15` of the length.
const MIN_RELATIVE_TOLERANCE: f64 = 1e-13;

/// The relative rounding of the sums: the 16-point sums (`18ε`, positive
/// weights and terms), the nodes' positions (`4ε`), the compensated total
/// (`2ε`).
const SUM_ROUNDING: f64 = 24.0 * f64::EPSILON;

/// Pieces a curve without spans starts from.
const FALLBACK_PIECES: usize = 16;

/// The arc length of a curve and how well it is known ([`Curve::arc_length`]):
/// `lower` and `upper` are rigorous, `error_bound` is an estimate.
///
/// # Method
/// Each rational Bézier span is integrated in its own parameter `s ∈ [0, 1]`
/// (the length does not depend on the parametrization) by adaptive
/// Gauss–Legendre quadrature: a piece `[s₀, s₁]` whose 16-point value is
/// `G` is split in halves with values `G_l`, `G_r`; the piece is accepted,
/// contributing `G_l + G_r`, when `|G_l + G_r − G|` is within its share of
/// the tolerance, `G_l + G_r` lies between the piece's chord and polygon,
/// and the piece's rigorous bracket (below) is within twice that share;
/// otherwise each half is treated the same way (at most 40 levels deep, at
/// most 2¹³ pieces in all, at most 1 024 halvings a span made for the bracket
/// alone, and certificates worth about 10 ms a span). The speed `|C′(s)|` is evaluated from the span's
/// own homogeneous coefficients (de Casteljau and the quotient rule), so
/// its rounding does not grow with the depth. Comparing a rule with itself
/// on the halves (rather than with a lower-order rule at nearly the same
/// nodes) samples the integrand at new points, so a peak of the speed that
/// one set of nodes misses shows up as a difference.
///
/// # What is rigorous and what is estimated
/// - **Rigorous** (up to a rounding margin that is added): `lower ≤ L ≤
///   upper`. For a piece of a rational Bézier curve with positive weights,
///   the chord is at most the arc length, which is at most the length of
///   the piece's control polygon: de Casteljau subdivision (on homogeneous
///   points, each projected point lies on the segment between the two it
///   combines) never lengthens the polygon (triangle inequality), and the
///   polygons converge to the curve. Where the speed on both halves is
///   certified analytic in a Bernstein ellipse (see
///   `curve/gauss_remainder.rs`), their values plus and minus
///   Gauss–Legendre's remainder bound and the evaluation's rounding bracket
///   the piece far more tightly, and the tighter of the two brackets is
///   taken. `lower` and `upper` are the sums over the final pieces. Pieces
///   near a cusp, where the speed is not analytic, are halved until their
///   chord and polygon are close enough. So `upper − lower` is about the
///   tolerance or less (unless the piece limits were reached).
/// - **Estimated**: `error_bound` is `Σ |G_l + G_r − G|` over the pieces
///   (the error of the whole-piece value, which for a smooth integrand
///   greatly exceeds that of the reported two-halves one) plus a bound on the
///   rounding of the evaluation, capped by the rigorous
///   `max(length − lower, upper − length)`. It is at most the requested
///   tolerance unless the depth or piece limit was reached. A feature of
///   the speed narrower than the nodes' spacing on both the piece and its
///   halves goes unseen unless it pushes the value out of the piece's
///   bracket, so the estimate is trustworthy for curves whose spans are not
///   pathologically wiggly; the bracket always holds.
///
/// Curves without spans (a user's own [`Curve`]) get the same adaptive
/// quadrature on their domain, starting from 16 equal pieces, with
/// `derivative` as the integrand: `lower` (the sum of chords) is rigorous
/// up to the curve's own evaluation, `upper` is infinite, and
/// `error_bound` is the estimate alone.
///
/// ```
/// use revolve::Curve;
/// use revolve::curve::RationalBezier;
/// use revolve::nalgebra::Point2;
///
/// // A quarter of the circle of radius 3 is 3π/2 long.
/// let h = std::f64::consts::FRAC_1_SQRT_2;
/// let quarter = RationalBezier::new(
///     vec![Point2::new(3.0, 0.0), Point2::new(3.0, 3.0), Point2::new(0.0, 3.0)],
///     vec![1.0, h, 1.0],
/// )?;
/// let arc = quarter.arc_length(1e-10)?;
/// let exact = 1.5 * std::f64::consts::PI;
/// assert!((arc.length - exact).abs() <= arc.error_bound && arc.error_bound <= 1e-10);
/// // The bracket: chords below, control polygons above.
/// assert!(arc.lower <= exact && exact <= arc.upper && arc.upper <= 6.0 + 1e-12);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcLength {
    /// The length: the sum of 16-point Gauss–Legendre values over the
    /// halves of the adaptive pieces.
    pub length: f64,
    /// The estimated bound on `|length − L|`: the sum over the pieces of the
    /// difference between the rule on the piece and on its halves, plus a
    /// rounding bound, at most the
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
    nodes: [f64; ORDER],
    weights: [f64; ORDER],
    len: usize,
}

impl Rule {
    /// The `n`-point rule (`n ≤ ORDER`): the roots `xᵢ` of the
    /// Legendre polynomial `Pₙ` by Newton's method from
    /// `cos(π(i − ¼)/(n + ½))`, weights `2/((1 − xᵢ²)Pₙ′(xᵢ)²)` (Abramowitz
    /// & Stegun 25.4.29), mapped from `[−1, 1]` to `[0, 1]`.
    fn new(n: usize) -> Self {
        let mut rule = Rule {
            nodes: [0.0; ORDER],
            weights: [0.0; ORDER],
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
    /// A bound on the rounding of a piece's chord and of its polygon.
    fn vertex_rounding(&self) -> f64 {
        0.0
    }
    /// The work of one [`Source::bracket`] of two parts (see
    /// [`MAX_CERTIFICATE_WORK`]); zero for a source that certifies nothing.
    /// Where it can certify, a piece is accepted only once its bracket is
    /// within its share of the tolerance.
    fn certificate_work(&self) -> usize {
        0
    }

    /// A rigorous bracket of the total length of `parts` (each a parameter
    /// interval and the rule's value on it), where the speed is certified
    /// analytic on every part.
    fn bracket(&self, _parts: &[((f64, f64), f64)]) -> Option<Certified> {
        None
    }
}

/// A certified bracket of a piece's length.
#[derive(Debug, Clone, Copy)]
struct Certified {
    lower: f64,
    upper: f64,
    /// The quadrature's part of its half-width, the rest being rounding.
    quadrature: f64,
}

/// One rational Bézier span, its homogeneous coefficients (weights scaled
/// so the largest is 1).
struct SpanSource<const D: usize> {
    coeffs: Vec<Homogeneous<D>>,
    /// [`SpanSource::rounding`] of the span.
    rounding: f64,
}

impl<const D: usize> SpanSource<D> {
    fn new(span: &RationalBezierSpan<D>) -> Self {
        let weights = span.curve.weights();
        let top = max_weight(weights.iter().copied());
        let coeffs = homogeneous_points(span.curve.points(), weights.iter().map(|&w| w / top));
        SpanSource {
            coeffs,
            rounding: Self::rounding(span),
        }
    }

    /// A bound on the rounding of the speed per unit of parameter: the
    /// hodograph's coefficients `n·Δ(wP)` carry `2ε` of `2n·max|wP|`, de
    /// Casteljau adds `nε` of that, the quotient rule divides by `w ≥ w_min`:
    /// `4(n + 1)²ε·max|P|·(w_max/w_min)`.
    fn rounding(span: &RationalBezierSpan<D>) -> f64 {
        let n = span.curve.degree() as f64;
        let scale = max_abs_coordinate(span.curve.points());
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

    /// Each vertex (an evaluation, or two subdivisions) is within the
    /// speed's rounding bound of its exact place.
    fn vertex_rounding(&self) -> f64 {
        2.0 * self.rounding
    }

    fn certificate_work(&self) -> usize {
        let n = self.coeffs.len();
        2 * 4 * n * n * n
    }

    /// Each part's value within its certified Gauss–Legendre remainder
    /// ([`gauss_remainder`]), the speeds' rounding (`rounding` per unit of
    /// parameter) and the weighted sum's (`SUM_ROUNDING` of the value).
    fn bracket(&self, parts: &[((f64, f64), f64)]) -> Option<Certified> {
        let mut bracket = Certified {
            lower: 0.0,
            upper: 0.0,
            quadrature: 0.0,
        };
        for &((s0, s1), value) in parts {
            let error = gauss_remainder(&self.coeffs, (s0, s1), ORDER)?;
            let slack = error + self.rounding * (s1 - s0) + SUM_ROUNDING * value.abs();
            bracket.lower += (value - slack).max(0.0);
            bracket.upper += value + slack;
            bracket.quadrature += error;
        }
        Some(bracket)
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

/// The running sums of the accepted pieces; the length by Neumaier's
/// compensated summation (error `2ε·length` whatever the number of pieces).
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    length: f64,
    compensation: f64,
    estimate: f64,
    lower: f64,
    upper: f64,
    pieces: usize,
    /// Halvings made to tighten a bracket on the current span.
    tightenings: usize,
    /// The work of the brackets certified on the current span (see
    /// [`MAX_CERTIFICATE_WORK`]).
    certificate_work: usize,
}

impl Tally {
    fn add_length(&mut self, x: f64) {
        let sum = self.length + x;
        self.compensation += if self.length.abs() >= x.abs() {
            (self.length - sum) + x
        } else {
            (x - sum) + self.length
        };
        self.length = sum;
    }

    /// Adds an accepted piece.
    fn accept(&mut self, length: f64, difference: f64, chord: f64, polygon: f64) {
        self.add_length(length);
        self.estimate += difference;
        self.lower += chord;
        self.upper += polygon;
        self.pieces += 1;
    }

    /// The compensated length.
    fn length(&self) -> f64 {
        self.length + self.compensation
    }
}

/// The adaptive quadrature: the fixed inputs.
struct Adaptive<'a, S> {
    source: &'a S,
    rule: &'a Rule,
    /// The error allowed on a piece, from its parameter width and polygon.
    allowed: &'a dyn Fn(f64, f64) -> f64,
}

impl<S> Adaptive<'_, S> {
    /// The rule's value on the piece `[s₀, s₁]`.
    fn value<const D: usize>(&self, piece: (f64, f64)) -> Result<f64, Error>
    where
        S: Source<D>,
    {
        self.rule.integrate(piece, |s| self.source.speed(s))
    }

    /// Integrates `[s₀, s₁]` (end points `p0`, `p1`, the rule's value on
    /// it `whole`) into `tally`, halving until the piece is accepted.
    fn run<const D: usize>(
        &self,
        (s0, s1): (f64, f64),
        (p0, p1): (Point<f64, D>, Point<f64, D>),
        whole: f64,
        depth: u32,
        tally: &mut Tally,
    ) -> Result<(), Error>
    where
        S: Source<D>,
    {
        let mid = 0.5 * (s0 + s1);
        let chord = (p1 - p0).norm();
        let polygon = self.source.polygon(s0, s1);
        let allowed = (self.allowed)(s1 - s0, polygon);
        // The piece's bracket: chord and polygon, tightened where the
        // quadrature's error is certified; tight when within the piece's
        // share of the tolerance (or when nothing can be certified).
        let bracket = |parts: &[((f64, f64), f64)], certify: bool| {
            let certified = if certify {
                self.source.bracket(parts)
            } else {
                None
            };
            let tight = self.source.certificate_work() == 0
                || polygon - chord <= 2.0 * allowed
                || certified.is_some_and(|c| c.quadrature <= allowed);
            // Chord and polygon widened by their vertices' rounding.
            let margin = self.source.vertex_rounding();
            let (chord, polygon) = ((chord - margin).max(0.0), polygon + margin);
            let (lo, hi) = match certified {
                Some(c) if c.lower.max(chord) <= c.upper.min(polygon) => {
                    (c.lower.max(chord), c.upper.min(polygon))
                }
                _ => (chord, polygon),
            };
            (lo, hi, tight)
        };
        if mid <= s0 || mid >= s1 {
            // Too narrow to halve: accept the piece as it is.
            let (lo, hi, _) = bracket(&[((s0, s1), whole)], true);
            tally.accept(whole, 0.0, lo, hi);
            return Ok(());
        }
        let (left, right) = (self.value((s0, mid))?, self.value((mid, s1))?);
        let halves = left + right;
        let difference = (halves - whole).abs();
        let slack = 1e-12 * polygon.min(halves.abs() + chord) + f64::MIN_POSITIVE;
        let bracketed = halves >= chord - slack && halves <= polygon + slack;
        let converged = difference <= allowed && bracketed;
        let exhausted = depth >= MAX_DEPTH || tally.pieces >= MAX_PIECES;
        if converged || exhausted {
            // Past the piece limits a certificate is not worth its cost
            // (the bound is already out of reach).
            let certify =
                tally.pieces < MAX_PIECES && tally.certificate_work < MAX_CERTIFICATE_WORK;
            if certify {
                tally.certificate_work += self.source.certificate_work();
            }
            let (lo, hi, tight) = bracket(&[((s0, mid), left), ((mid, s1), right)], certify);
            if tight || exhausted || tally.tightenings >= MAX_TIGHTENINGS {
                tally.accept(halves, difference, lo, hi);
                return Ok(());
            }
            tally.tightenings += 1;
        }
        let pm = self.source.point(mid)?;
        self.run((s0, mid), (p0, pm), left, depth + 1, tally)?;
        self.run((mid, s1), (pm, p1), right, depth + 1, tally)
    }

    /// Integrates `[s₀, s₁]` from scratch.
    fn start<const D: usize>(
        &self,
        piece: (f64, f64),
        ends: (Point<f64, D>, Point<f64, D>),
        tally: &mut Tally,
    ) -> Result<(), Error>
    where
        S: Source<D>,
    {
        let whole = self.value(piece)?;
        self.run(piece, ends, whole, 0, tally)
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
    let rule = Rule::new(ORDER);
    match curve.rational_bezier_spans() {
        Some(spans) => spans_length(&spans, tolerance, &rule),
        None => sampled_length(curve, tolerance, &rule),
    }
}

/// The arc length of rational Bézier spans; tiny ones (see [`UnitScale`])
/// measured rescaled exactly, with the tolerance, and scaled back.
fn spans_length<const D: usize>(
    spans: &[RationalBezierSpan<D>],
    tolerance: f64,
    rule: &Rule,
) -> Result<ArcLength, Error> {
    validate_spans(spans)?;
    let Some(unit) = UnitScale::for_magnitude(spans_magnitude(spans)) else {
        return spans_length_at_scale(spans, tolerance, rule);
    };
    let scaled: Vec<RationalBezierSpan<D>> = spans.iter().map(|s| scaled_span(&unit, s)).collect();
    // A tolerance that overflows when scaled is far above the curve's size.
    let up = unit.up(tolerance).min(f64::MAX);
    match spans_length_at_scale(&scaled, up, rule) {
        Ok(arc) => Ok(ArcLength {
            length: unit.down(arc.length),
            error_bound: unit.down(arc.error_bound),
            lower: unit.down(arc.lower),
            upper: unit.down(arc.upper),
            pieces: arc.pieces,
        }),
        Err(Error::ToleranceTooSmall { min, .. }) => Err(Error::ToleranceTooSmall {
            tolerance,
            min: unit.down(min),
        }),
        Err(e) => Err(e),
    }
}

/// [`spans_length`] for spans that are not tiny.
fn spans_length_at_scale<const D: usize>(
    spans: &[RationalBezierSpan<D>],
    tolerance: f64,
    rule: &Rule,
) -> Result<ArcLength, Error> {
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
    // Half the tolerance for the quadrature, shared half by the pieces'
    // polygons (a piece's polygon bounds its length) and half by parameter
    // width: the sums over the final pieces are at most tolerance / 2. The
    // other half covers the rounding (at most a quarter, by the minimum
    // tolerance) and the sums' (below).
    let count = spans.len() as f64;
    let allowed = |width: f64, polygon: f64| {
        0.5 * tolerance * (0.5 * polygon / total + 0.5 * width / count).min(1.0)
    };
    let mut tally = Tally::default();
    for source in &sources {
        let adaptive = Adaptive {
            source,
            rule,
            allowed: &allowed,
        };
        let ends = (source.point(0.0)?, source.point(1.0)?);
        (tally.tightenings, tally.certificate_work) = (0, 0);
        adaptive.start((0.0, 1.0), ends, &mut tally)?;
    }
    let evaluation = rounding + SUM_ROUNDING * tally.length();
    Ok(finish(tally, evaluation, SUM_ROUNDING * tally.upper))
}

/// The estimate, the bracket widened by `margin`, and the error bound
/// capped by the bracket.
fn finish(tally: Tally, evaluation: f64, margin: f64) -> ArcLength {
    let lo = (tally.lower - margin).max(0.0);
    let hi = tally.upper + margin;
    // Rounding can only cross them for curves so small (below about 1e-150)
    // that the norms' squares are subnormal: keep the bracket ordered.
    let (lower, upper) = if lo <= hi {
        (lo, hi)
    } else {
        (hi.max(0.0), lo)
    };
    let length = tally.length().max(lower).min(upper);
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
    rule: &Rule,
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
    let allowed = |w: f64, _: f64| 0.5 * tolerance * (w / width).min(1.0);
    let adaptive = Adaptive {
        source: &source,
        rule,
        allowed: &allowed,
    };
    let mut tally = Tally::default();
    for i in 0..FALLBACK_PIECES {
        adaptive.start((at(i), at(i + 1)), (ends[i], ends[i + 1]), &mut tally)?;
    }
    if !tally.length().is_finite() {
        // Speeds near the largest f64 summed beyond it.
        return Err(Error::CurveNotFinite { t: a });
    }
    let (evaluation, margin) = (SUM_ROUNDING * tally.length(), SUM_ROUNDING * tally.lower);
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
        for n in [1, 2, 5, 8, ORDER] {
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
            if n <= 8 {
                let k = 2 * n as i32;
                let got = rule.integrate((0.0, 1.0), |x| Ok(x.powi(k))).unwrap();
                assert!((got - 1.0 / (k + 1) as f64).abs() > 1e-12, "n={n}");
            }
        }
    }
}

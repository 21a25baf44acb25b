//! Adaptive flattening with a guaranteed deviation bound.
//!
//! A curve is cut into Bézier pieces by de Casteljau subdivision at parameter
//! midpoints until each piece is certified flat. The certificate comes from
//! the control polygon: a Bézier piece lies in the convex hull of its control
//! points, and the distance to the chord `[P₀, Pₙ]` is a convex function, so
//! its maximum over the hull is attained at a control point. Hence
//!
//! `dist(P(t), chord) ≤ maxᵢ dist(Pᵢ, [P₀, Pₙ])` for every `t` in the piece.
//!
//! A piece that fails this test but whose second derivative is small enough
//! is cut into at most a dozen equal parameter parts at once, each certified
//! by `|C(s) − chord| ≤ w²/8 · max|C″|` for a part of width `w` (tight for
//! parabolas, where the hull bound is twice the deviation); pieces needing
//! more parts are halved first, so parts are short only where the curvature
//! is high.
//!
//! The bound we compare against the tolerance is that maximum plus an allowance
//! for the rounding of the subdivided control points
//! (`2ε · scale · (n + 1) · (depth + 1)`), so it holds for the exact curve, not
//! only for its floating-point subdivision.
//!
//! Rational pieces (`Σ wᵢPᵢBᵢ / Σ wᵢBᵢ`, weights `wᵢ > 0`) are subdivided on
//! their homogeneous points `(wᵢPᵢ, wᵢ)`. With positive weights the piece is,
//! at every parameter, a convex combination of its control points (weights
//! `wᵢBᵢ(t)/Σ wⱼBⱼ(t) ≥ 0`), so it lies in their convex hull (Farin, *Curves
//! and Surfaces for CAGD*, §13.2; Piegl & Tiller, *The NURBS Book*, §4.2,
//! property P4.9), and the same bound holds with the projected control
//! points `Pᵢ`: `dist(C(t), [P₀, Pₙ]) ≤ maxᵢ dist(Pᵢ, [P₀, Pₙ])`. The
//! second-derivative shortcut is not used for them (their `C″` is not a
//! hodograph of the control points). Their rounding allowance is twice the
//! polynomial one: the homogeneous coordinates `wP` and `w` are each rounded
//! like polynomial control points, relative to `w·scale` and `w` (the weights
//! are positive, so `w` is computed without cancellation), and the projection
//! `wP/w` adds both relative errors.

use super::CurveSample;
use super::homogeneous::{Homogeneous, project, project_with_derivative};
use super::unit_scale::UnitScale;
use crate::bernstein::{Coefficient, subdivide};
use crate::scratch::with_scratch;
use crate::{Curve, Error};
use nalgebra::{Point, SVector};

/// Deepest subdivision: pieces narrower than `2⁻⁵⁰` of a span are not split.
const MAX_DEPTH: u32 = 50;

/// Spans whose end points differ by at most this multiple of the scale are
/// joined continuously (the difference is rounding of their Bézier forms);
/// larger differences are jumps and get a left-limit sample.
const JOIN_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// Tolerances below this multiple of the largest control-point coordinate are
/// rejected: rounding (about `1e-16` of the scale) would dominate the bound and
/// the number of pieces would explode.
pub(crate) const MIN_RELATIVE_TOLERANCE: f64 = 1e-10;

/// The result of adaptive flattening: samples and the deviation bound achieved.
///
/// The samples are in parameter order. For consecutive samples `sᵢ`, `sᵢ₊₁`,
/// every point of the curve with parameter in `[sᵢ.t, sᵢ₊₁.t]` lies within
/// `bound` of the segment `[sᵢ.point, sᵢ₊₁.point]`; `bound ≤ tolerance`.
///
/// Where a B-spline or NURBS jumps (an interior knot of full multiplicity), the sample
/// list holds two samples with the same `t`: the limit from the left, then the
/// value (right limit). The segment between them is the jump itself.
#[derive(Debug, Clone, PartialEq)]
pub struct Flattening<const D: usize> {
    /// The samples, with points and derivatives, in parameter order.
    pub samples: Vec<CurveSample<D>>,
    /// The guaranteed deviation bound (≤ the requested tolerance).
    pub bound: f64,
}

/// A control value of a Bézier piece as flattening uses it: a point of a
/// polynomial piece, or a homogeneous point of a rational one.
pub(crate) trait FlatControl<const D: usize>: Coefficient {
    /// The multiple of the polynomial rounding allowance that covers the
    /// rounding of subdivided values of this kind.
    const ROUNDING_FACTOR: f64;

    /// The point in space this value stands for.
    fn position(self) -> SVector<f64, D>;

    /// The value whose position is this one's times `factor` (a weight
    /// stays as it is).
    fn scaled(self, factor: f64) -> Self;

    /// A bound on `max |C″(s)|` over the piece `c` in its own parameter
    /// `s ∈ [0, 1]`, where one is known.
    fn second_derivative_bound(c: &[Self]) -> Option<f64>;

    /// The end point of the piece `c` on a parameter interval of width
    /// `width`, and its derivative there (limit from the left).
    fn end_sample(c: &[Self], width: f64) -> (Point<f64, D>, SVector<f64, D>);
}

impl<const D: usize> FlatControl<D> for SVector<f64, D> {
    const ROUNDING_FACTOR: f64 = 1.0;

    #[inline]
    fn position(self) -> SVector<f64, D> {
        self
    }

    fn scaled(self, factor: f64) -> Self {
        self * factor
    }

    fn second_derivative_bound(c: &[Self]) -> Option<f64> {
        Some(second_derivative_bound(c))
    }

    fn end_sample(c: &[Self], width: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let n = c.len();
        let end = c[n - 1];
        let derivative = match n {
            1 => SVector::zeros(),
            _ => (end - c[n - 2]) * ((n - 1) as f64 / width),
        };
        (Point::from(end), derivative)
    }
}

impl<const D: usize> FlatControl<D> for Homogeneous<D> {
    const ROUNDING_FACTOR: f64 = 2.0;

    #[inline]
    fn position(self) -> SVector<f64, D> {
        project(self).coords
    }

    fn scaled(self, factor: f64) -> Self {
        Homogeneous {
            wp: self.wp * factor,
            w: self.w,
        }
    }

    fn second_derivative_bound(_: &[Self]) -> Option<f64> {
        None
    }

    /// `C = A/w` and `C′ = (A′ − w′C)/w` from the last homogeneous point and
    /// the last leg of the homogeneous hodograph, `(n − 1)(hₙ₋₁ − hₙ₋₂)/width`.
    fn end_sample(c: &[Self], width: f64) -> (Point<f64, D>, SVector<f64, D>) {
        let n = c.len();
        let end = c[n - 1];
        let leg = match n {
            1 => Homogeneous::zero(),
            _ => (end - c[n - 2]) * (n - 1) as f64,
        };
        project_with_derivative(end, leg / width)
    }
}

/// What one refinement pass accumulates.
struct Accumulator<'c, C, const D: usize> {
    curve: &'c C,
    tolerance: f64,
    scale: f64,
    bound: f64,
    samples: Vec<CurveSample<D>>,
}

impl<C: Curve<D>, const D: usize> Accumulator<'_, C, D> {
    /// Appends the curve's sample at `t` (point and derivative).
    fn sample(&mut self, t: f64) {
        let (point, derivative) = self.curve.eval_with_derivative(t);
        self.samples.push(CurveSample {
            t,
            point,
            derivative,
        });
    }
}

/// Flattens `curve`, given as a sequence of Bézier pieces (control points and
/// the parameter interval each covers), to `tolerance`.
pub(crate) fn flatten_pieces<'a, C: Curve<D>, const D: usize>(
    curve: &C,
    pieces: impl IntoIterator<Item = (&'a [Point<f64, D>], (f64, f64))>,
    tolerance: f64,
) -> Result<Flattening<D>, Error> {
    flatten_controls(curve, pieces, |p| p.coords, tolerance)
}

/// Flattens `curve`, given as a sequence of Bézier pieces (control values
/// `S`, loaded as the [`FlatControl`] values `load(s)`, and the parameter
/// interval each covers), to `tolerance`: polynomial pieces from their
/// points, rational pieces from their homogeneous points.
pub(crate) fn flatten_controls<'a, C: Curve<D>, S: 'a, T: FlatControl<D>, const D: usize>(
    curve: &C,
    pieces: impl IntoIterator<Item = (&'a [S], (f64, f64))>,
    load: impl Fn(&S) -> T,
    tolerance: f64,
) -> Result<Flattening<D>, Error> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidTolerance { tolerance });
    }
    let pieces: Vec<_> = pieces.into_iter().collect();
    let scale = pieces
        .iter()
        .flat_map(|(values, _)| values.iter())
        .map(|s| load(s).position().amax())
        .fold(0.0, f64::max);
    let min = MIN_RELATIVE_TOLERANCE * scale;
    if tolerance < min {
        return Err(Error::ToleranceTooSmall { tolerance, min });
    }
    // Tiny geometry is certified rescaled exactly (see `UnitScale`): the
    // controls' positions, the tolerance and the scale times 2ᵏ, the bound
    // and the jump samples' points times 2⁻ᵏ (the other samples are the
    // curve's own evaluations).
    match UnitScale::for_magnitude(scale) {
        None => certify(curve, &pieces, load, tolerance, scale, None),
        Some(unit) => {
            let (f1, f2) = unit.up_factors();
            let up = |s: &S| load(s).scaled(f1).scaled(f2);
            let scaled_tolerance = unit.up(tolerance).min(f64::MAX);
            let flat = certify(
                curve,
                &pieces,
                up,
                scaled_tolerance,
                unit.up(scale),
                Some(unit),
            )?;
            Ok(Flattening {
                samples: flat.samples,
                bound: unit.down(flat.bound),
            })
        }
    }
}

/// [`flatten_controls`] at the scale given: `unit` scales the jump
/// samples, which come from the controls, back to the curve's.
fn certify<'a, C: Curve<D>, S: 'a, T: FlatControl<D>, const D: usize>(
    curve: &C,
    pieces: &[(&'a [S], (f64, f64))],
    load: impl Fn(&S) -> T,
    tolerance: f64,
    scale: f64,
    unit: Option<UnitScale>,
) -> Result<Flattening<D>, Error> {
    let mut acc = Accumulator {
        curve,
        tolerance,
        scale,
        bound: 0.0,
        samples: Vec::new(),
    };
    for (k, &(values, (a, b))) in pieces.iter().enumerate() {
        let n = values.len();
        let (end, derivative) = with_scratch(n, load(&values[0]), |c| {
            for (dst, s) in c.iter_mut().zip(values) {
                *dst = load(s);
            }
            refine(&mut acc, c, a, b, 0)?;
            Ok::<_, Error>(T::end_sample(c, b - a))
        })?;
        let next_start = pieces.get(k + 1).map(|(s, _)| load(&s[0]).position());
        if next_start.is_some_and(|s| (s - end.coords).norm() > JOIN_ROUNDING * acc.scale) {
            // A jump (of any size beyond rounding): close this piece with its
            // limit from the left, so the polyline follows the jump.
            let back = |v: SVector<f64, D>| unit.map_or(v, |u| u.down_vector(v));
            acc.samples.push(CurveSample {
                t: b,
                point: Point::from(back(end.coords)),
                derivative: back(derivative),
            });
        }
    }
    acc.sample(curve.domain().1);
    Ok(Flattening {
        samples: acc.samples,
        bound: acc.bound,
    })
}

/// Certifies the piece `c` (covering `[a, b]`) or splits it at its midpoint.
/// Pushes the start sample of every certified piece.
fn refine<C: Curve<D>, T: FlatControl<D>, const D: usize>(
    acc: &mut Accumulator<'_, C, D>,
    c: &[T],
    a: f64,
    b: f64,
    depth: u32,
) -> Result<(), Error> {
    let n = c.len();
    // Rounding of the subdivided control points, plus the rounding gap a
    // continuous join may show between two spans' end points (the polyline
    // runs to the next span's start).
    let rounding =
        T::ROUNDING_FACTOR * 2.0 * f64::EPSILON * acc.scale * n as f64 * f64::from(depth + 1)
            + JOIN_ROUNDING * acc.scale;
    let bound = hull_to_chord_distance(c) + rounding;
    if bound <= acc.tolerance {
        acc.bound = acc.bound.max(bound);
        acc.sample(a);
        return Ok(());
    }
    if let Some((parts, deviation)) = uniform_parts(c, acc.tolerance - rounding) {
        // Equal parts, each certified by the second-derivative bound.
        for k in 0..parts {
            acc.sample(a + (b - a) * (k as f64 / parts as f64));
        }
        acc.bound = acc.bound.max(deviation + rounding);
        return Ok(());
    }
    if depth >= MAX_DEPTH {
        return Err(Error::ToleranceTooSmall {
            tolerance: acc.tolerance,
            min: bound,
        });
    }
    let mid = 0.5 * (a + b);
    with_scratch(n, c[0], |left| {
        with_scratch(n, c[0], |right| {
            subdivide(c, 0.5, left, right);
            refine(acc, left, a, mid, depth + 1)?;
            refine(acc, right, mid, b, depth + 1)
        })
    })
}

/// Pieces are cut into at most this many equal parts at once; a piece that
/// needs more is halved first, so that parts stay short only where the
/// curvature is high.
const MAX_UNIFORM_PARTS: usize = 12;

/// How many equal parameter parts of the piece `c` certainly deviate from
/// their chords by at most `tolerance`, if at most [`MAX_UNIFORM_PARTS`],
/// and the deviation bound they achieve.
///
/// On a part of width `w` (in the piece's parameter `s ∈ [0, 1]`) the curve
/// minus its chord's linear interpolant is `e(s) = −∫ G(s, σ) C″(σ) dσ` with
/// the Green's function `G ≥ 0`, `∫ G = (s − s₀)(s₁ − s)/2 ≤ w²/8`, so
/// `|e| ≤ w²/8 · max|C″|` ([`second_derivative_bound`]); the chord point
/// `L(s)` is on the segment, so this bounds the distance to it too.
fn uniform_parts<T: FlatControl<D>, const D: usize>(
    c: &[T],
    tolerance: f64,
) -> Option<(usize, f64)> {
    if c.len() < 3 || tolerance.is_nan() || tolerance <= 0.0 {
        return None;
    }
    let second = T::second_derivative_bound(c)?;
    let parts = (second / (8.0 * tolerance)).sqrt().ceil();
    if !(parts.is_finite() && parts >= 1.0 && parts <= MAX_UNIFORM_PARTS as f64) {
        return None;
    }
    Some((parts as usize, second / (8.0 * parts * parts)))
}

/// `max |C″(s)|` over the piece `c` (parameter `s ∈ [0, 1]`), bounded by
/// the largest control point of the second hodograph,
/// `n(n − 1)·maxᵢ |cᵢ₊₂ − 2cᵢ₊₁ + cᵢ|` (convex hull; the norm is convex),
/// each difference enlarged by its rounding, `4ε(|cᵢ₊₂| + 2|cᵢ₊₁| + |cᵢ|)`.
fn second_derivative_bound<const D: usize>(c: &[SVector<f64, D>]) -> f64 {
    let n = c.len().saturating_sub(1) as f64;
    let max = c
        .windows(3)
        .map(|w| {
            let size = w[2].norm() + 2.0 * w[1].norm() + w[0].norm();
            (w[2] - w[1] * 2.0 + w[0]).norm() + 4.0 * f64::EPSILON * size
        })
        .fold(
            0.0,
            |m: f64, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        );
    n * (n - 1.0) * max
}

/// `maxᵢ dist(cᵢ, [c₀, cₙ])`: how far the control polygon strays from the
/// chord (with the control points' [positions](FlatControl::position)).
fn hull_to_chord_distance<T: FlatControl<D>, const D: usize>(c: &[T]) -> f64 {
    let (Some(&first), Some(&last)) = (c.first(), c.last()) else {
        return 0.0;
    };
    let (first, last) = (first.position(), last.position());
    let chord = last - first;
    let len2 = chord.norm_squared();
    c.iter()
        .map(|&p| {
            let w = p.position() - first;
            let s = if len2 > 0.0 {
                (w.dot(&chord) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (w - chord * s).norm()
        })
        // A NaN distance (impossible for accepted coordinates) must not be
        // dropped by `max`: it makes the piece uncertifiable.
        .fold(
            0.0,
            |m, d| if d.is_nan() { f64::INFINITY } else { m.max(d) },
        )
}

//! Cubic Bézier spans standing in for a profile that has none of its own.
//!
//! A user's [`Curve<2>`](crate::Curve) need only give points and first
//! derivatives. To intersect its surface of revolution the crate replaces it
//! by the piecewise cubic Hermite interpolant of its points and derivatives,
//! `C¹` and exact at the breakpoints: on `[u₀, u₁]`, `h = u₁ − u₀`, the
//! Bézier control points `C(u₀)`, `C(u₀) + h C′(u₀)/3`, `C(u₁) − h C′(u₁)/3`,
//! `C(u₁)`. A piece is split in half until, at `s = ¼, ½, ¾` of it, the
//! interpolant's point is within the tolerance of the curve's and its
//! derivative (times `h/4`) is too. The error of cubic Hermite
//! interpolation is `h⁴ |C⁗| / 384` (de Boor, *A Practical Guide to
//! Splines*, ch. IV), so a smooth curve needs few pieces: about 40 for a
//! half circle at `1e-7` of its radius.
//!
//! No bound from samples can be certified for a curve known only through
//! its values: a feature narrower than the sample spacing can hide between
//! samples. The approximation is what the intersector searches, and every
//! hit it finds is refined on the curve itself, so what it can lose is
//! confined to rays that graze the surface within the measured deviation.

use crate::curve::BezierSpan;
use crate::{Bezier, Curve, Error};
use nalgebra::{Point2, Vector2};

/// The deviation target, relative to the profile's size.
pub(crate) const RELATIVE_DEVIATION: f64 = 1e-7;

/// The most pieces an approximation may have.
pub(crate) const MAX_PIECES: usize = 4096;

/// Pieces the domain is cut into before any test.
const START_PIECES: usize = 8;

/// A profile's stand-in: its cubic spans and the largest deviation from the
/// curve measured at the test points.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Approximation {
    pub(crate) spans: Vec<BezierSpan<2>>,
    pub(crate) deviation: f64,
}

/// The point and derivative of `curve` at `t`, checked finite and within
/// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
fn sample<C: Curve<2>>(curve: &C, t: f64) -> Result<(Point2<f64>, Vector2<f64>), Error> {
    let (p, d) = curve.eval_with_derivative(t);
    let ok = p
        .coords
        .iter()
        .chain(d.iter())
        .all(|v| v.is_finite() && v.abs() <= crate::MAX_COORDINATE);
    if ok {
        Ok((p, d))
    } else {
        Err(Error::CurveNotFinite { t })
    }
}

/// The cubic Hermite approximation of `curve` over its domain `(a, b)`
/// (checked by the caller: finite, `a < b`).
///
/// # Errors
/// [`Error::CurveNotFinite`] where the curve gives a non-finite or too large
/// value; [`Error::ProfileTooRough`] if [`MAX_PIECES`] pieces do not reach
/// the deviation target (a curve with a jump or a kink in its value, or
/// oscillating faster than the pieces can follow).
pub(crate) fn approximate<C: Curve<2>>(
    curve: &C,
    (a, b): (f64, f64),
) -> Result<Approximation, Error> {
    let at = |k: usize, n: usize| {
        if k == n {
            b
        } else {
            a + (b - a) * (k as f64 / n as f64)
        }
    };
    // The size from a first look at the curve.
    let mut size = 0.0_f64;
    for k in 0..=4 * START_PIECES {
        let (p, _) = sample(curve, at(k, 4 * START_PIECES))?;
        size = size.max(p.x.abs()).max(p.y.abs());
    }
    let tolerance = RELATIVE_DEVIATION * size.max(f64::MIN_POSITIVE);
    // Pieces still to test, last on top; finished ones come out in order.
    let mut todo: Vec<(f64, f64)> = (0..START_PIECES)
        .rev()
        .map(|k| (at(k, START_PIECES), at(k + 1, START_PIECES)))
        .collect();
    let mut spans = Vec::new();
    let mut deviation = 0.0_f64;
    while let Some((u0, u1)) = todo.pop() {
        if spans.len() + todo.len() >= MAX_PIECES {
            return Err(Error::ProfileTooRough { pieces: MAX_PIECES });
        }
        let (p0, d0) = sample(curve, u0)?;
        let (p3, d3) = sample(curve, u1)?;
        let h = u1 - u0;
        let points = vec![p0, p0 + d0 * (h / 3.0), p3 - d3 * (h / 3.0), p3];
        let piece = Bezier::new(points).map_err(|_| Error::CurveNotFinite { t: u0 })?;
        let mut worst = 0.0_f64;
        for s in [0.25, 0.5, 0.75] {
            let (p, d) = sample(curve, u0 + h * s)?;
            let off = (piece.eval(s) - p).norm();
            let slope = (piece.derivative(s) / h - d).norm() * h * 0.25;
            worst = worst.max(off).max(slope);
        }
        let mid = u0 + 0.5 * h;
        if worst <= tolerance || !(u0 < mid && mid < u1) {
            if worst > tolerance {
                return Err(Error::ProfileTooRough {
                    pieces: spans.len() + todo.len() + 1,
                });
            }
            deviation = deviation.max(worst);
            spans.push(BezierSpan {
                knots: (u0, u1),
                curve: piece,
            });
        } else {
            todo.push((mid, u1));
            todo.push((u0, mid));
        }
    }
    Ok(Approximation { spans, deviation })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The unit half circle from the south pole to the north pole, by
    /// cosine and sine.
    struct HalfCircle;

    impl Curve<2> for HalfCircle {
        fn domain(&self) -> (f64, f64) {
            (-PI / 2.0, PI / 2.0)
        }
        fn eval(&self, t: f64) -> Point2<f64> {
            Point2::new(t.cos(), t.sin())
        }
        fn derivative(&self, t: f64) -> Vector2<f64> {
            Vector2::new(-t.sin(), t.cos())
        }
    }

    /// The spans stay within the tolerance of the circle at dense points
    /// (the test points are only three per piece), join without gaps, and
    /// number about what the `h⁴/384` error predicts.
    #[test]
    fn half_circle_is_followed_within_the_tolerance() {
        let approx = approximate(&HalfCircle, HalfCircle.domain()).unwrap();
        let n = approx.spans.len();
        assert!((16..=128).contains(&n), "{n} pieces");
        for w in approx.spans.windows(2) {
            assert_eq!(w[0].knots.1, w[1].knots.0);
            assert_eq!(w[0].curve.points()[3], w[1].curve.points()[0]);
        }
        let mut worst = 0.0_f64;
        for span in &approx.spans {
            for k in 0..=64 {
                let p = span.curve.eval(k as f64 / 64.0);
                worst = worst.max((p.coords.norm() - 1.0).abs());
            }
        }
        assert!(
            worst <= 1.5 * RELATIVE_DEVIATION,
            "worst radius error {worst:e}"
        );
        assert!(approx.deviation <= RELATIVE_DEVIATION);
    }

    /// A curve with a jump cannot be followed: an error, not a hang.
    #[test]
    fn a_jump_is_too_rough() {
        struct Step;
        impl Curve<2> for Step {
            fn domain(&self) -> (f64, f64) {
                (0.0, 1.0)
            }
            fn eval(&self, t: f64) -> Point2<f64> {
                Point2::new(1.0, if t < 0.3 { 0.0 } else { 1.0 })
            }
            fn derivative(&self, _: f64) -> Vector2<f64> {
                Vector2::zeros()
            }
        }
        assert!(matches!(
            approximate(&Step, (0.0, 1.0)),
            Err(Error::ProfileTooRough { .. })
        ));
    }

    /// A NaN inside the domain is reported with its parameter.
    #[test]
    fn nan_values_are_named() {
        struct Hole;
        impl Curve<2> for Hole {
            fn domain(&self) -> (f64, f64) {
                (0.0, 1.0)
            }
            fn eval(&self, t: f64) -> Point2<f64> {
                Point2::new(if t > 0.5 { f64::NAN } else { 1.0 }, t)
            }
            fn derivative(&self, _: f64) -> Vector2<f64> {
                Vector2::new(0.0, 1.0)
            }
        }
        let err = approximate(&Hole, (0.0, 1.0)).unwrap_err();
        assert!(
            matches!(err, Error::CurveNotFinite { t } if t > 0.5),
            "{err:?}"
        );
    }
}

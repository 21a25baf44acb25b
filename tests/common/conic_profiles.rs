//! Exact conic profiles for rational revolutions: the half circle of a
//! sphere and the full circle of a torus, made of quarter arcs (rational
//! quadratic Bézier pieces with weights `1, √2/2, 1`, control points exact
//! on the axes).

use revolve::nalgebra::{Point2, Unit, Vector2};
use revolve::{Curve, RationalBezier, RationalBezierSpan};
use std::f64::consts::FRAC_1_SQRT_2;

/// Quarter arcs in order, piece `i` on the parameter interval `[i, i + 1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct QuarterArcs {
    pieces: Vec<RationalBezier<2>>,
}

/// The unit direction of angle `k·π/2`, exactly.
fn axis_direction(k: usize) -> Vector2<f64> {
    [
        Vector2::new(1.0, 0.0),
        Vector2::new(0.0, 1.0),
        Vector2::new(-1.0, 0.0),
        Vector2::new(0.0, -1.0),
    ][k % 4]
}

impl QuarterArcs {
    /// The quarter arcs of the circle about `center` of radius `radius`
    /// from angle `first·π/2`, `count` of them, counter-clockwise.
    pub fn new(center: Point2<f64>, radius: f64, first: usize, count: usize) -> Self {
        let pieces = (first..first + count)
            .map(|k| {
                let (a, b) = (axis_direction(k), axis_direction(k + 1));
                RationalBezier::new(
                    vec![
                        center + a * radius,
                        center + (a + b) * radius,
                        center + b * radius,
                    ],
                    vec![1.0, FRAC_1_SQRT_2, 1.0],
                )
                .expect("a valid quarter arc")
            })
            .collect();
        QuarterArcs { pieces }
    }

    /// The piece containing `t` (clamped into the domain, NaN at its start)
    /// and the local parameter; a join belongs to the piece it starts.
    fn locate(&self, t: f64) -> (&RationalBezier<2>, f64) {
        let n = self.pieces.len();
        let t = if t.is_nan() {
            0.0
        } else {
            t.clamp(0.0, n as f64)
        };
        let i = (t.floor() as usize).min(n - 1);
        (&self.pieces[i], t - i as f64)
    }
}

impl Curve<2> for QuarterArcs {
    fn domain(&self) -> (f64, f64) {
        (0.0, self.pieces.len() as f64)
    }

    fn eval(&self, t: f64) -> Point2<f64> {
        let (piece, s) = self.locate(t);
        piece.eval(s)
    }

    fn derivative(&self, t: f64) -> Vector2<f64> {
        let (piece, s) = self.locate(t);
        piece.derivative(s)
    }

    fn eval_with_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>) {
        let (piece, s) = self.locate(t);
        piece.eval_with_derivative(s)
    }

    fn tangent(&self, t: f64) -> Option<Unit<Vector2<f64>>> {
        let (piece, s) = self.locate(t);
        piece.tangent(s)
    }

    fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<2>>> {
        Some(
            self.pieces
                .iter()
                .enumerate()
                .map(|(i, piece)| RationalBezierSpan {
                    knots: (i as f64, i as f64 + 1.0),
                    curve: piece.clone(),
                })
                .collect(),
        )
    }
}

/// The sphere's profile: the half circle of radius `radius` about the
/// origin from the south pole `(0, −R)` to the north pole `(0, R)` through
/// `(R, 0)`, as two quarter arcs (their join is the equator).
pub fn sphere_profile(radius: f64) -> QuarterArcs {
    QuarterArcs::new(Point2::origin(), radius, 3, 2)
}

/// The torus's profile: the circle of radius `minor` about `(major, 0)`,
/// counter-clockwise from `(major + minor, 0)`, as four quarter arcs (joins
/// on the outer and inner equators and on the top and bottom circles).
pub fn torus_profile(major: f64, minor: f64) -> QuarterArcs {
    QuarterArcs::new(Point2::new(major, 0.0), minor, 0, 4)
}

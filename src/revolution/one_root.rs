//! The one-root decision: on a span where every line of the ray's class has
//! a strictly monotonic hit function, the function's values at the span's
//! end points decide between no root and exactly one, and safeguarded
//! Newton finds that one without forming the polynomial.

use super::query::Query;
use super::select::select;
use super::span_form::SpanForm;
use super::span_table::SpanTable;
use crate::bernstein::Polynomial;
use nalgebra::Vector3;

/// Safeguarded Newton on a one-root span stops once a step is this small
/// (in the span's parameter): the point it reaches is then accurate to
/// about its square, and the polish finishes it.
const NEWTON_DONE: f64 = 1e-6;
/// What a span's end values say about the roots of a hit function that
/// is strictly monotonic on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum EndRoots {
    /// Certainly of one sign: no root.
    None,
    /// Certainly of opposite signs: exactly one root, strictly inside.
    One,
    /// An end within the rounding of zero.
    Unknown,
}
/// The hit function `f = A² + B² − (d_y x)²` of one ray (see the module
/// docs) at profile points.
#[derive(Debug, Clone, Copy)]
struct HitFunction {
    o: Vector3<f64>,
    d: Vector3<f64>,
    /// `o_x d_y` and `o_z d_y`.
    oxdy: f64,
    ozdy: f64,
}
impl HitFunction {
    #[inline(always)]
    fn new(q: &Query) -> Self {
        let (o, d) = (q.o, q.d);
        HitFunction {
            o,
            d,
            oxdy: o.x * d.y,
            ozdy: o.z * d.y,
        }
    }

    /// `f` at the profile point `(x, y)`, with `A` and `B` there.
    #[inline(always)]
    fn parts(&self, x: f64, y: f64) -> (f64, f64, f64) {
        let h = y - self.o.y;
        let a = self.oxdy + h * self.d.x;
        let b = self.ozdy + h * self.d.z;
        let c = self.d.y * x;
        (a * a + b * b - c * c, a, b)
    }
}
/// The hit function of one ray (`d_y ≠ 0`) at control points, with a bound
/// on its rounding there.
#[derive(Debug, Clone, Copy)]
pub(super) struct EndValues {
    f: HitFunction,
    pub(super) err: f64,
}
impl EndValues {
    /// For the ray `q` on the profile of `table`. With `m_A = |o_x d_y| +
    /// (|y|_max + |o_y|)|d_x|`, likewise `m_B`, and `m_C = |d_y| |x|_max`,
    /// each of `A`, `B`, `d_y x` is computed to within `3ε` of its `m`,
    /// their squares to within `7ε m²` and `f` to within `9ε Σ m²`; the
    /// bound takes `16ε Σ m²`.
    #[inline(always)]
    pub(super) fn new(q: &Query, table: &SpanTable) -> Self {
        let f = HitFunction::new(q);
        let (o, d) = (f.o, f.d);
        let reach = table.y_range.0.abs().max(table.y_range.1.abs()) + o.y.abs();
        let ma = f.oxdy.abs() + reach * d.x.abs();
        let mb = f.ozdy.abs() + reach * d.z.abs();
        let mc = d.y.abs() * table.r_max;
        EndValues {
            f,
            err: 16.0 * f64::EPSILON * (ma * ma + mb * mb + mc * mc),
        }
    }

    /// `f` at the profile point `(x, y)`.
    #[inline(always)]
    pub(super) fn value(&self, (x, y): (f64, f64)) -> f64 {
        self.f.parts(x, y).0
    }

    /// What the end values at the span's end points `ends` say.
    #[inline(always)]
    pub(super) fn roots(&self, ends: [(f64, f64); 2]) -> EndRoots {
        let (f0, f1) = (self.value(ends[0]), self.value(ends[1]));
        let e = self.err;
        let sign = |f: f64| i32::from(f > e) - i32::from(f < -e);
        match sign(f0) * sign(f1) {
            1 => EndRoots::None,
            -1 => EndRoots::One,
            _ => EndRoots::Unknown,
        }
    }
}
/// The one root in `(0, 1)` of the hit function `f` of `span` for the ray
/// `q` (`d_y ≠ 0`), where `f` is strictly monotonic with certainly
/// opposite end values ([`EndRoots::One`]): Newton's method on `f`
/// evaluated from the span's point and derivative, from the chord's
/// crossing, kept in the bracket its signs maintain (bisection when a
/// step leaves it), until a step is below [`NEWTON_DONE`].
#[inline(always)]
pub(super) fn monotone_root<P: SpanForm>(span: P, q: &Query) -> f64 {
    let hit = HitFunction::new(q);
    let (d, dy2) = (q.d, q.d.y * q.d.y);
    let value = |x: f64, y: f64| hit.parts(x, y);
    let (xs, ys) = (span.xs().coeffs(), span.ys().coeffs());
    let n = xs.len() - 1;
    let (f0, _, _) = value(xs[0], ys[0]);
    let (f1, _, _) = value(xs[n], ys[n]);
    let rising = f1 > f0;
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut s = (f0 / (f0 - f1)).clamp(0.0, 1.0);
    for _ in 0..64 {
        let p = span.point(s);
        let (f, a, b) = value(p.x, p.y);
        if f == 0.0 {
            return s;
        }
        // Selects, not branches: which side s is on follows no pattern.
        let past = (f > 0.0) == rising;
        hi = select(past, s, hi);
        lo = select(past, lo, s);
        let slope = 2.0 * ((a * d.x + b * d.z) * p.dy - dy2 * p.x * p.dx);
        let newton = s - f / slope;
        let next = select(newton > lo && newton < hi, newton, 0.5 * (lo + hi));
        let step = (next - s).abs();
        s = next;
        if step <= NEWTON_DONE {
            break;
        }
    }
    s
}

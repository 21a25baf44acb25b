//! The polynomial pieces of a B-spline in Bézier form, precomputed once, and
//! the search for the piece that contains a parameter.
//!
//! A B-spline of degree `p` is a polynomial of degree `p` on each non-empty
//! knot span `[tᵢ, tᵢ₊₁)` of its domain. [`PieceTable`] stores, for each such
//! span in order, its break points and its Bézier control points (`p + 1`
//! vectors, from blossoming at construction). Evaluating then needs only the
//! piece search and one de Casteljau cascade on `u = (t − a)/(b − a)`, which is
//! exact at both ends (`u = 0` and `u = 1` give the end control points).
//!
//! The piece search is a binary search over the break points, or, when the
//! break points are (to rounding) equally spaced, as for the course
//! framework's uniform knots and for clamped knots, a direct guess
//! `⌊(t − b₀)·m/(b_m − b₀)⌋` corrected by comparing with the neighbouring
//! break points: constant time whatever the number of control points.

use super::knots::{nonempty_spans, span_bezier_points};
use crate::bernstein::{self, Coefficient};
use crate::{Bezier, BezierSpan, Error};
use nalgebra::{Point, SVector};
use std::ops::Div;

/// The Bézier pieces of a B-spline and how to find them. The control values
/// `T` are vectors for a polynomial spline and homogeneous points for a
/// rational one.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PieceTable<T> {
    /// `b₀ < b₁ < … < b_m`: the distinct knot values of the domain.
    breaks: Vec<f64>,
    /// For piece `j`, the index `i` of its knot span `[tᵢ, tᵢ₊₁)`.
    spans: Vec<usize>,
    /// `p + 1` Bézier control points per piece, piece after piece.
    coeffs: Vec<T>,
    /// `m/(b_m − b₀)` when the break points are equally spaced to rounding.
    uniform_scale: Option<f64>,
    /// Control points per piece: `p + 1`.
    width: usize,
}

impl<T: Copy> PieceTable<T> {
    /// Builds the table for the non-empty spans `i` in `p..n` of `knots`,
    /// taking each span's Bézier control points from `bezier_points(i, out)`
    /// (`out` is filled with `zero` before).
    pub(crate) fn new(
        degree: usize,
        knots: &[f64],
        n: usize,
        zero: T,
        mut bezier_points: impl FnMut(usize, &mut [T]),
    ) -> Self {
        let spans: Vec<usize> = nonempty_spans(knots, degree, n).collect();
        let mut breaks: Vec<f64> = spans.iter().map(|&i| knots[i]).collect();
        breaks.push(knots[n]);
        let mut coeffs = vec![zero; spans.len() * (degree + 1)];
        for (&i, chunk) in spans.iter().zip(coeffs.chunks_exact_mut(degree + 1)) {
            bezier_points(i, chunk);
        }
        let m = spans.len();
        let (first, last) = (breaks[0], breaks[m]);
        let h = (last - first) / m as f64;
        let equally_spaced = breaks
            .iter()
            .enumerate()
            .all(|(j, &b)| (b - (first + h * j as f64)).abs() <= 1e-9 * h);
        Self {
            breaks,
            spans,
            coeffs,
            uniform_scale: equally_spaced.then(|| m as f64 / (last - first)),
            width: degree + 1,
        }
    }

    /// The number of pieces.
    pub(crate) fn len(&self) -> usize {
        self.spans.len()
    }

    /// The piece containing `t`, which must lie in the domain `[b₀, b_m]`:
    /// the `j` with `b_j ≤ t < b_{j+1}`, or the last piece at `t = b_m`.
    #[inline]
    pub(crate) fn locate(&self, t: f64) -> usize {
        let m = self.spans.len();
        match self.uniform_scale {
            Some(scale) => {
                // The guess is exact up to rounding; the comparisons with the
                // real break points make the answer exact.
                let guess = ((t - self.breaks[0]) * scale) as usize;
                let mut j = guess.min(m - 1);
                while j > 0 && t < self.breaks[j] {
                    j -= 1;
                }
                while j + 1 < m && t >= self.breaks[j + 1] {
                    j += 1;
                }
                j
            }
            None => self.breaks[1..m].partition_point(|&b| b <= t),
        }
    }

    /// The knot span index `i` of piece `j`.
    #[inline]
    pub(crate) fn span(&self, j: usize) -> usize {
        self.spans[j]
    }

    /// The parameter interval `(a, b)` of piece `j`.
    #[inline]
    pub(crate) fn interval(&self, j: usize) -> (f64, f64) {
        (self.breaks[j], self.breaks[j + 1])
    }

    /// The Bézier control points of piece `j`.
    #[inline]
    pub(crate) fn coeffs(&self, j: usize) -> &[T] {
        &self.coeffs[j * self.width..(j + 1) * self.width]
    }

    /// The piece containing `t` (in the domain): its index and interval
    /// `(a, b)`.
    #[inline]
    fn piece_at(&self, t: f64) -> (usize, (f64, f64)) {
        let j = self.locate(t);
        (j, self.interval(j))
    }

    /// The knot span index `i` of the piece containing `t` (in the domain).
    #[inline]
    pub(crate) fn span_at(&self, t: f64) -> usize {
        self.span(self.locate(t))
    }

    /// The parameter width `b − a` of the piece containing `t` (in the
    /// domain).
    #[inline]
    pub(crate) fn width_at(&self, t: f64) -> f64 {
        let (_, (a, b)) = self.piece_at(t);
        b - a
    }

    /// Calls `check(coeffs, 1.0)` and `check(coeffs, b − a)` for every
    /// piece in order (the hodographs in the piece's own parameter and in
    /// `t`), stopping at the first error.
    pub(crate) fn check_each(
        &self,
        check: impl Fn(&[T], f64) -> Result<(), Error>,
    ) -> Result<(), Error> {
        for j in 0..self.len() {
            let (a, b) = self.interval(j);
            let c = self.coeffs(j);
            check(c, 1.0)?;
            check(c, b - a)?;
        }
        Ok(())
    }

    /// The pieces as [`BezierSpan`]s, each control value mapped to a point
    /// by `point`.
    pub(crate) fn bezier_spans<const D: usize>(
        &self,
        point: impl Fn(&T) -> SVector<f64, D>,
    ) -> Vec<BezierSpan<D>> {
        (0..self.len())
            .map(|j| BezierSpan {
                knots: self.interval(j),
                curve: Bezier::from_valid_points(
                    self.coeffs(j)
                        .iter()
                        .map(|c| Point::from(point(c)))
                        .collect(),
                ),
            })
            .collect()
    }
}

impl<T: Coefficient> PieceTable<T> {
    /// The table of a spline of degree `degree` on `knots` with control
    /// values `control`: each non-empty span's Bézier points are the
    /// blossoms of [`span_bezier_points`], then passed to
    /// `finish(span, points)` (to keep them in the span's hull, scale them).
    pub(crate) fn blossomed(
        degree: usize,
        knots: &[f64],
        control: &[T],
        zero: T,
        mut finish: impl FnMut(usize, &mut [T]),
    ) -> Self {
        Self::new(degree, knots, control.len(), zero, |span, out| {
            span_bezier_points(knots, degree, span, &control[span - degree..=span], out);
            finish(span, out);
        })
    }

    /// The value at `t` (in the domain): de Casteljau on the piece
    /// containing it at `u = (t − a)/(b − a)`.
    #[inline]
    pub(crate) fn eval(&self, t: f64) -> Option<T> {
        let (j, (a, b)) = self.piece_at(t);
        bernstein::eval(self.coeffs(j), (t - a) / (b - a))
    }

    /// The value and the derivative in `t` at `t` (in the domain): one de
    /// Casteljau pass on the piece at `u = (t − a)/w`, `w = b − a`, the
    /// derivative in `u` divided by `w`.
    #[inline]
    pub(crate) fn eval_with_derivative(&self, t: f64) -> Option<(T, T)>
    where
        T: Div<f64, Output = T>,
    {
        let (j, (a, b)) = self.piece_at(t);
        let w = b - a;
        let (value, derivative) = bernstein::eval_with_derivative(self.coeffs(j), (t - a) / w)?;
        Some((value, derivative / w))
    }
}

//! The candidate hits of one span: the ray parameters a root of the span's
//! polynomial gives (from the height, or from the radius for shallow rays),
//! kept sorted on the stack, and the refinements of a root on the height
//! and on the axis.

use super::query::Query;
use super::span_culling::circle_times;
use super::span_form::SpanForm;
use crate::roots::Root;

/// Root pieces narrower than this (in a span's parameter) are handed to
/// Newton's method as candidates instead of being split further: from there
/// Newton on the unsquared system converges, and near-tangent rays (double
/// roots) do not drive the subdivision to the bottom.
pub(super) const CANDIDATE_WIDTH: f64 = 1.0 / (1u64 << 30) as f64;
/// Candidates stored per span before sorting; more are polished unsorted.
const MAX_CANDIDATES: usize = 16;
/// The candidate hits `(t, s)` of one span, on the stack.
pub(super) struct Candidates {
    items: [(f64, f64); MAX_CANDIDATES],
    len: usize,
    /// Candidates beyond the capacity, kept in order of discovery.
    spill: Vec<(f64, f64)>,
}
impl Default for Candidates {
    fn default() -> Self {
        Candidates {
            items: [(0.0, 0.0); MAX_CANDIDATES],
            len: 0,
            spill: Vec::new(),
        }
    }
}
impl Candidates {
    pub(super) fn push(&mut self, t: f64, s: f64) {
        if !t.is_finite() {
            return;
        }
        if self.len < MAX_CANDIDATES {
            self.items[self.len] = (t, s);
            self.len += 1;
        } else {
            self.spill.push((t, s));
        }
    }

    /// Sorts by `t` (insertion sort: there are few).
    pub(super) fn sort(&mut self) {
        if !self.spill.is_empty() {
            // Rare: many roots. Merge everything on the heap.
            let mut all: Vec<_> = self.items[..self.len].to_vec();
            all.append(&mut self.spill);
            all.sort_by(|a, b| a.0.total_cmp(&b.0));
            self.spill = all;
            self.len = 0;
            return;
        }
        let items = &mut self.items[..self.len];
        for i in 1..items.len() {
            let mut j = i;
            while j > 0 && items[j - 1].0 > items[j].0 {
                items.swap(j - 1, j);
                j -= 1;
            }
        }
    }

    pub(super) fn as_slice(&self) -> &[(f64, f64)] {
        if self.len == 0 {
            &self.spill
        } else {
            &self.items[..self.len]
        }
    }
}
/// Ray parameters to try for the root `s` of `span`: from the height when
/// the ray is steep, else from the radius (both crossings), nearest the
/// height's answer first.
#[inline(always)]
pub(super) fn candidate_times<P: SpanForm>(span: P, q: &Query, s: f64) -> [Option<f64>; 2] {
    let y = span.y(s);
    let t_height = (y - q.o.y) / q.d.y;
    // |d_y| ≥ |d_xz|, compared squared (|d| is finite, so the squares
    // are too).
    if q.d.y * q.d.y >= q.radius.0 {
        [Some(t_height), None]
    } else {
        let [a, b] = circle_times(q, span.x(s));
        // Keep the radius solution that agrees with the height.
        match (a, b) {
            (Some(a), Some(b)) => {
                if (a - t_height).abs() <= (b - t_height).abs() {
                    [Some(a), Some(b)]
                } else {
                    [Some(b), Some(a)]
                }
            }
            _ => [Some(t_height), None],
        }
    }
}
/// The root `s0` of `y(s) = h` (as isolated, to [`CANDIDATE_WIDTH`])
/// refined by Newton's method on the span: at most four steps, each kept
/// only if it brings `y` closer to `h` and stays within the isolating
/// width of `s0` and in `[0, 1]`.
#[inline(always)]
pub(super) fn height_root<P: SpanForm>(span: P, h: f64, s0: f64) -> f64 {
    let (lo, hi) = (
        (s0 - CANDIDATE_WIDTH).max(0.0),
        (s0 + CANDIDATE_WIDTH).min(1.0),
    );
    let mut s = s0;
    let mut p = span.point(s);
    for _ in 0..4 {
        let g = p.y - h;
        if g == 0.0 || p.dy == 0.0 {
            break;
        }
        let next = s - g / p.dy;
        if !(next >= lo && next <= hi) {
            break;
        }
        let q = span.point(next);
        if (q.y - h).abs() >= g.abs() {
            break;
        }
        (s, p) = (next, q);
    }
    s
}
/// The parameters to try for one root report: the root itself, or the ends
/// and middle of an interval on which the polynomial vanishes.
pub(super) fn root_samples(root: Root) -> impl Iterator<Item = f64> {
    let v = match root {
        Root::At(s) => [Some(s), None, None],
        Root::Flat { from, to } => [Some(from), Some(0.5 * (from + to)), Some(to)],
    };
    v.into_iter().flatten()
}

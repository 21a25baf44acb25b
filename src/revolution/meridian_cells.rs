//! Span culling decided once per surface: a table from a ray's three
//! rotation-invariant numbers to the spans it can meet.
//!
//! Up to rotation about the axis, a line is fixed by three numbers: the
//! squared distance `ρ₀²` of its closest approach to the axis, the height
//! `y_c` of that closest point, and `c = |d_y| / |d|`, the cosine of its
//! angle with the axis. With `g = √(1 − c²) / c` (the line's run per unit of
//! rise), its points in the meridian plane satisfy
//!
//! `ρ² = ρ₀² + g² (y − y_c)²`,
//!
//! so over a span's height range `[y₀, y₁]` the line's distance from the
//! axis is least where `|y − y_c|` is least and greatest where it is
//! greatest. The table cuts `(c, y_c, ρ₀)` into cells and keeps, per cell,
//! the spans whose padded height–radius box some line of the (slightly
//! enlarged) cell meets: the line comes within the box's outer radius in
//! its height range, and does not stay inside its inner radius. A ray then
//! runs the per-span test ([`span_entry`](super::revolution)) on those spans
//! only, instead of on every span of every group it enters.
//!
//! The number of cells is fixed ([`SLOPE_CELLS`] × [`HEIGHT_CELLS`] ×
//! [`RHO_CELLS`], or [`RHO_CELLS_MANY`] radius cells for profiles of more
//! than [`MANY_SPANS`] spans, where finer cells save more tests) and each
//! holds one bit per span, rounded up to whole bytes, so the table's size
//! is proportional to the number of spans: with the monotonicity table
//! below, `512 · (4 + 1) · ⌈n/8⌉` bytes for `n ≤ 16` spans (2.5 KiB for
//! 8), `512 · (5 + 1) · ⌈n/8⌉` beyond (9 KiB for 22). It is built by runs:
//! for one slope cell, radius cell and span, the height cells whose lines
//! meet the box are one run, less a middle run where every line stays
//! inside the inner radius, both found in closed form.
//!
//! The table is a superset of the per-span test, never a replacement: it
//! passes every span that test would pass, so the spans entered, and hence
//! the hits, are the same as without it. Rays it cannot vouch for (nearly
//! along the axis, an origin far out, a tolerance looser than its padding)
//! get [`Cell::Outside`] and the full test. A ray whose closest approach is
//! farther from the axis than any span, or whose closest point is so far
//! above or below that its slope cannot bring it back, is a certain miss.
//!
//! A second table, over slope and height cells only, marks the spans on
//! which the hit function of every line of the cell is strictly monotonic
//! ([`Monotone`]; monotonicity does not depend on `ρ₀`), also by runs of
//! height cells found in closed form. The intersector decides those spans
//! from their end values.

use super::monotone_spans::{Monotone, SpanCurves};
use crate::bernstein::binomial_row;
use nalgebra::Vector3;

/// Cells along `c`, uniform in `[0, C_MAX]`.
const SLOPE_CELLS: usize = 16;
/// Cells along `y_c`, uniform over the heights from which a line of the
/// `c` cell can still reach the profile.
const HEIGHT_CELLS: usize = 32;
/// Cells along `ρ₀` (not its square: the cells near the axis, where thin
/// parts such as a stem are, are as wide as those far out), uniform in
/// `[0, R]` (`R` the padded outer radius, with the margin).
const RHO_CELLS: usize = 4;
/// Cells along `ρ₀` for profiles of more than [`MANY_SPANS`] spans.
const RHO_CELLS_MANY: usize = 5;
/// The number of spans beyond which the table takes [`RHO_CELLS_MANY`]
/// radius cells.
const MANY_SPANS: usize = 16;
/// Lines closer than this to the axis direction (`c > C_MAX`, within about
/// 8°) are outside the table: their closest point is ill-conditioned and
/// can be far from the profile.
const C_MAX: f64 = 0.99;

/// How far, relative to the object's scale, the table pads every span box.
/// Rays whose position tolerance exceeds it are outside the table.
const PAD: f64 = 1e-6;
/// The margin by which every cell is enlarged (relative to the scale, and
/// to its square for `ρ₀²`): it covers the rounding of a ray's three numbers
/// for origins up to [`ORIGIN_LIMIT`] times the scale (about `60 ε |o|`
/// for `y_c` and `ρ₀`, see [`MeridianCells::classify`]).
const MARGIN: f64 = 1e-7;
/// Rays whose origin is farther out than this many times the scale are
/// outside the table.
const ORIGIN_LIMIT: f64 = 1e5;
/// The margin of a cell's `c` range (rounding of `|d_y| / |d|`: a few ulps).
const SLOPE_MARGIN: f64 = 1e-12;
/// Slope cells per unit of `c`: `SLOPE_CELLS / C_MAX` less a relative
/// `2⁻⁴⁴`, so that `c = C_MAX` falls in the last cell.
const SLOPE_SCALE: f64 = SLOPE_CELLS as f64 / C_MAX * (1.0 - 1.0 / (1u64 << 44) as f64);
/// Slack, in cells, when a run's ends are rounded to whole cells: it covers
/// the rounding of their arithmetic, so that a run never leaves out a cell
/// the cell test passes.
const RUN_SLACK: f64 = 1e-9;

/// Where the table puts a ray.
pub(super) enum Cell<'a> {
    /// No span can be hit.
    Miss,
    /// Only the spans [`Listed`] yields can be hit.
    Spans(Listed<'a>),
    /// The table cannot say; test every span.
    Outside,
}

/// The spans of a ray's cell, 64 to a word: the `w`-th item is `(listed,
/// monotone)`, bit `k` of `listed` set when span `64 w + k` can be hit, and
/// of `monotone` when the span's hit function is strictly monotonic for
/// every line of the cell (see [`Monotone`]; a bit that may be set for a
/// span not listed).
pub(super) struct Listed<'a> {
    cells: &'a MeridianCells,
    /// The cell's first byte in [`MeridianCells::masks`], and its slope and
    /// height cell's in [`MeridianCells::monotone`].
    listed: usize,
    monotone: usize,
    /// The first span of the next word.
    next: usize,
}

impl Iterator for Listed<'_> {
    type Item = (u64, u64);

    #[inline]
    fn next(&mut self) -> Option<(u64, u64)> {
        let (cells, first) = (self.cells, self.next);
        if first >= cells.spans {
            return None;
        }
        self.next += 64;
        // The cell's bytes for spans first.. (past the last span its bits
        // are clear; `keep` drops the next cells' bytes).
        let word = |bytes: &[u8], at: usize| read_word(bytes, at + first / 8) & cells.keep;
        Some((
            word(&cells.masks, self.listed),
            word(&cells.monotone, self.monotone),
        ))
    }
}

/// The 8 bytes of `bytes` from byte `at`, little-endian.
#[inline(always)]
fn read_word(bytes: &[u8], at: usize) -> u64 {
    // (Never short: the tables keep 7 bytes to spare.)
    bytes
        .get(at..)
        .and_then(<[u8]>::first_chunk)
        .map_or(0, |word| u64::from_le_bytes(*word))
}

/// The culling table of one surface.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct MeridianCells {
    /// `ρ₀²` at and beyond which nothing can be hit (with the margin).
    rho2_max: f64,
    /// The number of radius cells, and that divided by `√rho2_max` less a
    /// relative `2⁻⁴⁴`: radius cells per unit of `ρ₀`, such that a `ρ₀²`
    /// below `rho2_max` is in a cell.
    rho_cells: usize,
    rho_scale: f64,
    /// Per `c` cell: the lowest `y_c` of its height cells and
    /// `HEIGHT_CELLS` divided by their total height.
    heights: [(f64, f64); SLOPE_CELLS],
    /// Largest position tolerance (`accept`) the padding covers.
    pad: f64,
    /// Largest `|o|` coordinate whose rounding the margins cover.
    origin_limit: f64,
    /// The margin by which cells are enlarged ([`MARGIN`] times the scale).
    margin: f64,
    /// The number of spans.
    spans: usize,
    /// The bytes a cell holds in each table: one bit per span, in whole
    /// bytes up to 64 spans (a cell is then read as one word), in whole
    /// words beyond; and the mask of a word's bits that belong to the cell
    /// (all of them for whole words).
    width: usize,
    keep: u64,
    /// The span masks, bit `s` for span `s` (little-endian): cell `(k, j,
    /// i)` (slope, height, radius) from byte `((k · HEIGHT_CELLS + j) ·
    /// rho_cells + i) · width`, and 7 bytes to spare (a cell is read as
    /// words).
    masks: Vec<u8>,
    /// The spans on which every line of slope and height cell `(k, j)` has
    /// a strictly monotonic hit function, from byte `(k · HEIGHT_CELLS + j)
    /// · width`, and 7 bytes to spare.
    monotone: Vec<u8>,
}

/// One span's box as the table sees it: heights `y` and distances from
/// the axis `r`, as the span's control points bound them (the table adds
/// its own padding).
#[derive(Debug, Clone, Copy)]
pub(super) struct SpanBox {
    pub(super) y: (f64, f64),
    pub(super) r: (f64, f64),
}

/// `C(n,i)·C(n,j)/C(2n,i+j)` for `i, j ∈ 0..=n`, row-major `(n + 1) ×
/// (n + 1)`: the weights of the product of two degree-`n` polynomials in
/// the Bernstein basis of degree `2n`.
pub(super) fn product_weights(n: usize) -> Vec<f64> {
    // Rows of binomials: O(n²) rather than O(n) per product.
    let (row, row2) = (binomial_row(n), binomial_row(2 * n));
    (0..=n)
        .flat_map(|i| {
            let (row, row2) = (&row, &row2);
            (0..=n).map(move |j| row[i] * row[j] / row2[i + j])
        })
        .collect()
}

/// `g² = (1 − c²) / c²` for `c` in `(0, 1]`, `∞` at `c ≤ 0`.
fn run_per_rise_squared(c: f64) -> f64 {
    if c <= 0.0 {
        f64::INFINITY
    } else {
        let c = c.min(1.0);
        (1.0 - c * c) / (c * c)
    }
}

/// The range of `c` of slope cell `k`, with its margin.
fn slope_range(k: usize) -> (f64, f64) {
    let c_cell = C_MAX / SLOPE_CELLS as f64;
    (
        (k as f64 * c_cell - SLOPE_MARGIN).max(0.0),
        ((k + 1) as f64 * c_cell + SLOPE_MARGIN).min(1.0),
    )
}

/// `x` clamped into `[−1, HEIGHT_CELLS]` (`x` real or infinite, not NaN):
/// the height cells' range and one beyond either end.
fn clamp_cells(x: f64) -> f64 {
    let top = HEIGHT_CELLS as f64;
    if x < -1.0 {
        -1.0
    } else if x > top {
        top
    } else {
        x
    }
}

/// `⌊x⌋` for `x` clamped as by [`clamp_cells`]: a truncating conversion of
/// `x + 1 ≥ 0` (no call to `floor`).
fn floor_cell(x: f64) -> isize {
    (clamp_cells(x) + 1.0) as i32 as isize - 1
}

/// `⌈x⌉` for `x` clamped as by [`clamp_cells`].
fn ceil_cell(x: f64) -> isize {
    let floor = floor_cell(x);
    floor + isize::from(clamp_cells(x) > floor as f64)
}

/// Sets bits `at + j · stride` of `bytes` (bit `b` is bit `b % 8` of byte
/// `b / 8`) for the height cells `j` of `first..=last` within
/// `0..HEIGHT_CELLS`.
fn set_run(bytes: &mut [u8], (first, last): (isize, isize), at: usize, stride: usize) {
    let first = first.max(0) as usize;
    let end = (last + 1).clamp(0, HEIGHT_CELLS as isize) as usize;
    let mut bit = at + first * stride;
    for _ in first..end {
        bytes[bit / 8] |= 1 << (bit % 8);
        bit += stride;
    }
}

impl MeridianCells {
    /// The table for spans with boxes `boxes` on an object of size `scale`,
    /// with no span certified monotonic (see [`Self::certify_monotone`]).
    pub(super) fn new(boxes: &[SpanBox], scale: f64) -> Self {
        let pad = PAD * scale;
        let margin = MARGIN * scale;
        let rho2_margin = margin * scale;
        let spans = boxes.len();
        let boxes: Vec<SpanBox> = boxes
            .iter()
            .map(|b| SpanBox {
                y: (b.y.0 - pad, b.y.1 + pad),
                r: (b.r.0 - pad, b.r.1 + pad),
            })
            .collect();
        let r_max = boxes.iter().fold(0.0_f64, |m, b| m.max(b.r.1));
        let (y_min, y_max) = boxes
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.y.0), hi.max(b.y.1))
            });
        let rho_cells = if spans > MANY_SPANS {
            RHO_CELLS_MANY
        } else {
            RHO_CELLS
        };
        let rho2_max = r_max * r_max + rho2_margin;
        let rho_scale = rho_cells as f64 / rho2_max.sqrt() * (1.0 - 1.0 / (1u64 << 44) as f64);
        let rho_cell = 1.0 / rho_scale;
        let width = if spans <= 64 {
            spans.div_ceil(8)
        } else {
            8 * spans.div_ceil(64)
        };
        let mut masks = vec![0_u8; SLOPE_CELLS * HEIGHT_CELLS * rho_cells * width + 7];
        // Per radius cell i and span s, at i · spans + s: √(r₁² − a0), the
        // room within the outer radius at the cell's least ρ₀² (NaN when
        // there is none), and √(r₀² − a1), the depth inside the inner radius
        // at its greatest (NaN when there is none).
        let mut room = Vec::with_capacity(rho_cells * spans);
        let mut depth = Vec::with_capacity(rho_cells * spans);
        for i in 0..rho_cells {
            let a0 = ((i as f64 * rho_cell).powi(2) - rho2_margin).max(0.0);
            let a1 = ((i + 1) as f64 * rho_cell).powi(2) + rho2_margin;
            for b in &boxes {
                room.push((b.r.1 * b.r.1 - a0).sqrt());
                depth.push(if b.r.0 > 0.0 {
                    (b.r.0 * b.r.0 - a1).sqrt()
                } else {
                    f64::NAN
                });
            }
        }
        let mut heights = [(0.0, 0.0); SLOPE_CELLS];
        for (k, height) in heights.iter_mut().enumerate() {
            let (c0, c1) = slope_range(k);
            // g over the cell: least at its greatest c.
            let (g0, g1) = (
                run_per_rise_squared(c1).sqrt(),
                run_per_rise_squared(c0).sqrt(),
            );
            // A line of this cell meets heights within R/g of y_c only.
            let reach = if g0 > 0.0 { r_max / g0 } else { f64::INFINITY };
            let (lo, hi) = (y_min - reach - margin, y_max + reach + margin);
            let per = HEIGHT_CELLS as f64 / (hi - lo);
            *height = (lo, per);
            // Height cell j spans [lo + j/per − margin, lo + (j + 1)/per +
            // margin]; `at(y)` is y's place in cells.
            let at = |y: f64| (y - lo) * per;
            for i in 0..rho_cells {
                // The bit of span s in cell (k, j, i) is row + j · stride + s.
                let stride = 8 * rho_cells * width;
                let row = (k * HEIGHT_CELLS * rho_cells + i) * 8 * width;
                for (s, b) in boxes.iter().enumerate() {
                    // Comes within the outer radius, a0 + g0² near² ≤ r₁²:
                    // the cell's heights come within h of the box's.
                    let h = room[i * spans + s] / g0;
                    if h.is_nan() {
                        continue;
                    }
                    let first = ceil_cell(at(b.y.0 - h - margin) - 1.0 - RUN_SLACK);
                    let last = floor_cell(at(b.y.1 + h + margin) + RUN_SLACK);
                    // Gets out of the inner radius, a1 + g1² far² ≥ r₀², fails
                    // only where the cell's heights stay within h of both
                    // ends of the box: cells strictly between these two.
                    let h = depth[i * spans + s] / g1;
                    let (stay_from, stay_to) = if h > 0.0 {
                        (
                            floor_cell(at(b.y.1 - h + margin) + RUN_SLACK) + 1,
                            ceil_cell(at(b.y.0 + h - margin) - 1.0 - RUN_SLACK) - 1,
                        )
                    } else {
                        (1, 0)
                    };
                    if stay_from <= stay_to {
                        set_run(
                            &mut masks,
                            (first, last.min(stay_from - 1)),
                            row + s,
                            stride,
                        );
                        set_run(&mut masks, (first.max(stay_to + 1), last), row + s, stride);
                    } else {
                        set_run(&mut masks, (first, last), row + s, stride);
                    }
                }
            }
        }
        MeridianCells {
            rho2_max,
            rho_cells,
            rho_scale,
            heights,
            pad,
            origin_limit: ORIGIN_LIMIT * scale,
            margin,
            spans,
            width,
            keep: u64::MAX >> (64 - 8 * width.min(8)),
            masks,
            monotone: vec![0; SLOPE_CELLS * HEIGHT_CELLS * width + 7],
        }
    }

    /// The bytes the table holds on the heap.
    pub(super) fn heap_bytes(&self) -> usize {
        self.masks.capacity() + self.monotone.capacity()
    }

    /// Certifies no span monotonic (all take the full solve).
    #[cfg(test)]
    pub(super) fn forget_monotone(&mut self) {
        self.monotone.fill(0);
    }

    /// Marks, per slope and height cell, the spans (Bernstein coefficients
    /// `curves`, in the order of the boxes) on which every line of the
    /// cell, enlarged by the margins, has a strictly monotonic hit
    /// function: the height cells within the heights [`Monotone::heights`]
    /// certifies for the cell's slopes (the ends of its range of `u = c² /
    /// (1 − c²)`).
    pub(super) fn certify_monotone(&mut self, curves: SpanCurves<'_>) {
        let certificates = Monotone::new(curves);
        let margin = self.margin;
        for (k, &(lo, per)) in self.heights.iter().enumerate() {
            let (c0, c1) = slope_range(k);
            let u = |c: f64| c * c / (1.0 - c * c);
            for s in 0..self.spans {
                for (y0, y1) in certificates.heights(s, (u(c0), u(c1))) {
                    // Cell j spans [lo + j/per − margin, lo + (j + 1)/per +
                    // margin]: within [y0, y1] from j ≥ (y0 + margin − lo)·per
                    // to j ≤ (y1 − margin − lo)·per − 1 (no slack: a cell
                    // must lie inside).
                    let first = ceil_cell((y0 + margin - lo) * per);
                    let last = floor_cell((y1 - margin - lo) * per) - 1;
                    let row = k * HEIGHT_CELLS * 8 * self.width;
                    set_run(&mut self.monotone, (first, last), row + s, 8 * self.width);
                }
            }
        }
    }

    /// The cell of the ray `o + t·d` (`|d| = dn > 0`, all finite) at
    /// position tolerance `accept`.
    ///
    /// Rounding: with `c ≤ C_MAX`, `|d_xz|² ≥ (1 − C_MAX²)|d|²`, so the
    /// closest point's `t_c = −(o_xz·d_xz)/|d_xz|²` is off by at most
    /// `6ε|o|/|d_xz|`, `y_c = o_y + t_c d_y` by about `60 ε |o|` (as
    /// `|d_y|/|d_xz| ≤ 7`) and `ρ₀²` by about `30 ε |o| R`: for
    /// `|o| ≤ ORIGIN_LIMIT · scale` that is far inside [`MARGIN`] (for `ρ₀`
    /// itself, the margin of `ρ₀²` is at least `MARGIN · scale² / 2R`).
    // Inlined by force into both instantiations of the span search (left
    // out of line, a ray took 2.5 % more instructions).
    #[inline(always)]
    pub(super) fn classify(
        &self,
        o: Vector3<f64>,
        d: Vector3<f64>,
        dn: f64,
        accept: f64,
    ) -> Cell<'_> {
        let c = d.y.abs() / dn;
        // (Plain comparisons rather than `max` and `||`: no NaN reaches
        // here, and one branch serves the three tests.)
        let (x, y) = (o.x.abs(), o.y.abs());
        let far = if x > y { x } else { y };
        let far = if far > o.z.abs() { far } else { o.z.abs() };
        if (c > C_MAX) | (accept > self.pad) | (far > self.origin_limit) {
            return Cell::Outside;
        }
        let a = d.x * d.x + d.z * d.z;
        if a < f64::MIN_POSITIVE {
            // Squares in the subnormal range have lost their precision.
            return Cell::Outside;
        }
        let t_c = -(o.x * d.x + o.z * d.z) / a;
        let (px, pz) = (o.x + t_c * d.x, o.z + t_c * d.z);
        let rho2 = px * px + pz * pz;
        // Cells as i32 (the values are small and not negative). With c ≤
        // C_MAX, k < SLOPE_CELLS: the factor is a hair under SLOPE_CELLS /
        // C_MAX (which moves the cells' ends by far less than their margin).
        let k = (c * SLOPE_SCALE) as i32 as usize;
        let (lo, per) = self.heights[k];
        let y = (o.y + t_c * d.y - lo) * per;
        if !(rho2.is_finite() && y.is_finite()) {
            return Cell::Outside;
        }
        if rho2 >= self.rho2_max || y < 0.0 || y >= HEIGHT_CELLS as f64 {
            return Cell::Miss;
        }
        let row = k * HEIGHT_CELLS + y as i32 as usize;
        // rho2 < rho2_max: i < rho_cells (see rho_scale).
        let i = (rho2.sqrt() * self.rho_scale) as i32 as usize;
        Cell::Spans(Listed {
            cells: self,
            listed: (row * self.rho_cells + i) * self.width,
            monotone: row * self.width,
            next: 0,
        })
    }
}

#[cfg(test)]
mod tests;

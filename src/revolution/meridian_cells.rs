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

/// The spans' Bernstein coefficients, `w` per span (degree `w − 1`), for
/// [`MeridianCells::certify_monotone`], with the weights of products,
/// [`product_weights`] of degree `w − 1`.
#[derive(Debug, Clone, Copy)]
pub(super) struct SpanCurves<'a> {
    pub(super) xs: &'a [f64],
    pub(super) ys: &'a [f64],
    pub(super) w: usize,
    pub(super) weights: &'a [f64],
}

/// The certificates of monotonicity of a profile's spans, for boxes of
/// line classes.
///
/// For a line with numbers `ρ₀²`, `y_c` and `c`, the hits on a span are
/// the roots of `F(s) = x(s)² − ρ₀² − g² (y(s) − y_c)²` (the intersector's
/// `f` is `−d_y² F`), so
///
/// `c² F′ = c² (x²)′ − (1 − c²) ((y − y_c)²)′`,
///
/// which does not depend on `ρ₀²`. Its Bernstein coefficients (degree
/// `2n − 1`) are `vᵢ = c² pᵢ − (1 − c²)(qᵢ − 2 y_c rᵢ)` with `p = (x²)′`,
/// `q = (y²)′`, `r = y′` (raised to degree `2n − 1`): bilinear in `c²` and
/// `y_c`, so over a box of `(c², y_c)` they are extreme at its corners. If
/// they are all certainly of one sign there (beyond [`Monotone::TOL`] of
/// their terms' size, which covers the rounding here and in the
/// coefficients), `F′` keeps that sign on the whole span for every line of
/// the box, and `F` has at most one root there, a simple one.
///
/// For a fixed `c` each condition `σ vᵢ > TOL · sizeᵢ` (`σ = ±1`) holds on
/// a half-line of `y_c` ([`Monotone::heights`]), so the heights certified
/// for a range of slopes are one interval per sign.
#[derive(Debug, Clone, PartialEq)]
struct Monotone {
    /// The coefficients of every span, `per_span` (`2n`) a span.
    terms: Vec<Term>,
    per_span: usize,
}

/// One coefficient of `c² F′` (see [`Monotone`]): `p`, `q`, `r`, and for
/// [`Monotone::heights`] with `T = 2 · TOL`: `T |p|`, `T |q|` and `1 / (2r
/// (1 ± T))` (infinite for `r = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Term {
    p: f64,
    q: f64,
    r: f64,
    tp: f64,
    tq: f64,
    up: f64,
    down: f64,
}

impl Monotone {
    /// The relative margin by which the coefficients must be of one sign.
    const TOL: f64 = 1e-9;
    /// The margin [`Self::heights`] asks, twice [`Self::TOL`]: the rounding
    /// of its roots (a few ulps of the terms) then still leaves every
    /// height it returns certain by `TOL`.
    const T: f64 = 2.0 * Self::TOL;

    /// The certificates of the spans `curves`.
    fn new(curves: SpanCurves<'_>) -> Self {
        let w = curves.w;
        let per_span = 2 * (w - 1);
        let m = per_span as f64;
        let spans = curves.xs.len() / w;
        let mut terms = Vec::with_capacity(spans * per_span);
        // x², y² and y (raised): degree 2n, reused for every span.
        let mut products = vec![[0.0; 3]; 2 * w - 1];
        for (xs, ys) in curves.xs.chunks_exact(w).zip(curves.ys.chunks_exact(w)) {
            products.fill([0.0; 3]);
            // Σ_{i+j=k} C(n,i)C(n,j)/C(2n,k) aᵢbⱼ: the product of two
            // degree-n polynomials in the Bernstein basis of degree 2n
            // (y times 1 = Σ Bⱼ raises y).
            for i in 0..w {
                for j in 0..w {
                    let weight = curves.weights[i * w + j];
                    let out = &mut products[i + j];
                    out[0] += weight * xs[i] * xs[j];
                    out[1] += weight * ys[i] * ys[j];
                    out[2] += weight * ys[i];
                }
            }
            terms.extend(products.windows(2).map(|pair| {
                let [p, q, r] = std::array::from_fn(|k| m * (pair[1][k] - pair[0][k]));
                Term {
                    p,
                    q,
                    r,
                    tp: Self::T * p.abs(),
                    tq: Self::T * q.abs(),
                    up: 1.0 / (2.0 * r * (1.0 + Self::T)),
                    down: 1.0 / (2.0 * r * (1.0 - Self::T)),
                }
            }));
        }
        Monotone { terms, per_span }
    }

    /// Span `s`'s coefficients.
    fn span(&self, s: usize) -> &[Term] {
        &self.terms[s * self.per_span..(s + 1) * self.per_span]
    }

    /// The heights `y_c` at which span `s`'s `c² F′` is certainly
    /// positive, and those at which it is certainly negative, for every
    /// `c` with `u = c² / (1 − c²)` in `[u0, u1]`: open intervals, `(∞,
    /// −∞)` when empty.
    ///
    /// Divided by `1 − c²`, the condition on one coefficient is
    /// `σ(u p − q + 2 r y) > T (u |p| + |q| + 2 |r| |y|)`, that is
    /// `a + b y − T |b| |y| > 0` with `a = σ(u p − q) − T (u |p| + |q|)` and
    /// `b = 2σr`: monotonic in `y` with the sign of `b`, it holds on one
    /// side of its root `−a / (b (1 ± T))` (`+` for `a ≥ 0`), everywhere or
    /// nowhere for `b = 0`. Over `[u0, u1]` it is linear in `u`, so its two
    /// ends decide.
    fn heights(&self, s: usize, (u0, u1): (f64, f64)) -> [(f64, f64); 2] {
        let (mut rising, mut falling) = (
            (f64::NEG_INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::INFINITY),
        );
        for u in [u0, u1] {
            for t in self.span(s) {
                let v = u * t.p - t.q;
                let size = u * t.tp + t.tq;
                let (a_rising, a_falling) = (v - size, -v - size);
                // The roots for b = 2r and b = −2r.
                let root_rising = -a_rising * if a_rising >= 0.0 { t.up } else { t.down };
                let root_falling = a_falling * if a_falling >= 0.0 { t.up } else { t.down };
                // (Plain comparisons: no NaN reaches here.)
                let (larger, smaller) = (
                    |a: f64, b: f64| if a > b { a } else { b },
                    |a: f64, b: f64| if a < b { a } else { b },
                );
                if t.r > 0.0 {
                    rising.0 = larger(rising.0, root_rising);
                    falling.1 = smaller(falling.1, root_falling);
                } else if t.r < 0.0 {
                    rising.1 = smaller(rising.1, root_rising);
                    falling.0 = larger(falling.0, root_falling);
                } else {
                    // b = 0: certain for every y or for none.
                    let (rises, falls) = (a_rising > 0.0, a_falling > 0.0);
                    if !rises {
                        rising = (f64::INFINITY, f64::NEG_INFINITY);
                    }
                    if !falls {
                        falling = (f64::INFINITY, f64::NEG_INFINITY);
                    }
                }
            }
        }
        [rising, falling]
    }

    /// Whether span `s`'s `c² F′` is certainly of one sign for every `c ∈
    /// [c0, c1]` and `y_c ∈ [y0, y1]`, by its coefficients at the box's
    /// four corners (the reference for [`Self::heights`]).
    #[cfg(test)]
    fn holds(&self, s: usize, (c0, c1): (f64, f64), (y0, y1): (f64, f64)) -> bool {
        let mut sign = 0.0;
        for &c2 in &[c0 * c0, c1 * c1] {
            for &yc in &[y0, y1] {
                for t in self.span(s) {
                    let (dx2, dy2, dy) = (t.p, t.q, t.r);
                    let q = dy2 - 2.0 * yc * dy;
                    let v = c2 * dx2 - (1.0 - c2) * q;
                    let size = c2 * dx2.abs() + (1.0 - c2) * (dy2.abs() + 2.0 * (yc * dy).abs());
                    let certain = if v > Self::TOL * size {
                        1.0
                    } else if v < -Self::TOL * size {
                        -1.0
                    } else {
                        return false;
                    };
                    if sign == 0.0 {
                        sign = certain;
                    } else if sign != certain {
                        return false;
                    }
                }
            }
        }
        true
    }
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
    #[inline]
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
mod tests {
    use super::*;

    use crate::revolution::test_unit::unit;

    /// Random boxes in `[0, scale] × [−scale, scale]` (radius × height),
    /// some touching the axis, some of zero height or zero radial width.
    fn boxes(state: &mut u64, count: usize, scale: f64) -> Vec<SpanBox> {
        (0..count)
            .map(|i| {
                let (y0, r0) = (unit(state) * 2.0 - 1.0, unit(state) * 0.9);
                let dy = if i % 7 == 3 { 0.0 } else { 0.3 * unit(state) };
                let dr = if i % 5 == 2 { 0.0 } else { 0.3 * unit(state) };
                let r0 = if i % 4 == 1 { 0.0 } else { r0 };
                SpanBox {
                    y: (y0 * scale, (y0 + dy) * scale),
                    r: (r0 * scale, (r0 + dr).min(1.0) * scale),
                }
            })
            .collect()
    }

    /// The boxes the ray `o + t·d` certainly enters, by sampling: a dense
    /// grid of `t` over its passage by the boxes, plus, for every box, the
    /// closest approach to the axis and the parameters where the ray
    /// crosses the box's heights and radii (so that touching contacts are
    /// sampled where they happen). Independent of the table's cell
    /// arithmetic.
    fn entered(boxes: &[SpanBox], o: Vector3<f64>, d: Vector3<f64>, scale: f64) -> Vec<bool> {
        let a = d.x * d.x + d.z * d.z;
        let t_c = if a > 0.0 {
            -(o.x * d.x + o.z * d.z) / a
        } else {
            0.0
        };
        let mut ts = vec![t_c];
        let reach = 8.0 * (scale + o.amax()) / d.norm();
        ts.extend((0..=20_000).map(|i| t_c - reach + 2.0 * reach * i as f64 / 20_000.0));
        for b in boxes {
            if d.y != 0.0 {
                ts.extend([(b.y.0 - o.y) / d.y, (b.y.1 - o.y) / d.y]);
            }
            for r in [b.r.0, b.r.1] {
                let (bb, cc) = (o.x * d.x + o.z * d.z, o.x * o.x + o.z * o.z - r * r);
                let disc = bb * bb - a * cc;
                if a > 0.0 && disc >= 0.0 {
                    ts.extend([(-bb - disc.sqrt()) / a, (-bb + disc.sqrt()) / a]);
                }
            }
        }
        boxes
            .iter()
            .map(|b| {
                ts.iter().any(|&t| {
                    let p = o + d * t;
                    let rho = (p.x * p.x + p.z * p.z).sqrt();
                    (b.y.0..=b.y.1).contains(&p.y) && (b.r.0..=b.r.1).contains(&rho)
                })
            })
            .collect()
    }

    /// Checks one ray: a box the ray enters is in its cell's mask, and a
    /// certain miss enters none. Returns what the table said, with the
    /// mask's size.
    fn check(
        cells: &MeridianCells,
        boxes: &[SpanBox],
        o: Vector3<f64>,
        d: Vector3<f64>,
        scale: f64,
    ) -> Option<usize> {
        let truth = entered(boxes, o, d, scale);
        let accept = 1e-12 * scale;
        match cells.classify(o, d, d.norm(), accept) {
            Cell::Outside => None,
            Cell::Miss => {
                assert!(
                    !truth.contains(&true),
                    "a miss that enters {truth:?}: o {o:?} d {d:?}"
                );
                Some(0)
            }
            Cell::Spans(words) => {
                let mask: Vec<u64> = words.map(|(listed, _)| listed).collect();
                assert_eq!(mask.len(), boxes.len().div_ceil(64));
                for (s, &inside) in truth.iter().enumerate() {
                    let listed = mask[s / 64] >> (s % 64) & 1 == 1;
                    assert!(
                        !inside || listed,
                        "box {s} entered but not listed: o {o:?} d {d:?}"
                    );
                }
                Some(mask.iter().map(|w| w.count_ones() as usize).sum())
            }
        }
    }

    /// Random rays through and around random boxes, at three scales: every
    /// entered box is listed, and the table decides most rays with masks
    /// well short of every box (else it would cull nothing).
    #[test]
    fn lists_every_box_a_ray_enters() {
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        for scale in [1e-6, 1.0, 1e6] {
            let boxes = boxes(&mut state, 70, scale);
            let cells = MeridianCells::new(&boxes, scale);
            let (mut decided, mut listed, mut rays) = (0, 0, 0);
            for case in 0..600 {
                let target = Vector3::new(
                    unit(&mut state) * 2.0 - 1.0,
                    unit(&mut state) * 2.2 - 1.1,
                    unit(&mut state) * 2.0 - 1.0,
                ) * scale;
                let mut d = Vector3::new(
                    unit(&mut state) - 0.5,
                    unit(&mut state) - 0.5,
                    unit(&mut state) - 0.5,
                );
                match case % 6 {
                    // Perpendicular to the axis.
                    0 => d.y = 0.0,
                    // Through the axis.
                    1 => {
                        d.x = -target.x / scale;
                        d.z = -target.z / scale;
                    }
                    _ => {}
                }
                if d.norm() == 0.0 {
                    continue;
                }
                let back = if case % 10 == 9 { 1e4 } else { 3.0 };
                let o = target - d.normalize() * back * scale;
                rays += 1;
                if let Some(n) = check(&cells, &boxes, o, d, scale) {
                    decided += 1;
                    listed += n;
                }
            }
            assert!(decided > rays * 9 / 10, "{decided} of {rays} decided");
            assert!(
                listed < decided * 70 / 3,
                "{listed} listed for {decided} rays"
            );
        }
    }

    /// Rays whose three numbers sit exactly on cell boundaries (and a
    /// rounding either side): the cells' margins keep them listed.
    #[test]
    fn rays_on_cell_boundaries() {
        let mut state = 0x2545_F491_4F6C_DD1D_u64;
        let scale = 1.0;
        let boxes = boxes(&mut state, 40, scale);
        let cells = MeridianCells::new(&boxes, scale);
        let mut decided = 0;
        for k in 0..SLOPE_CELLS {
            let c = k as f64 * C_MAX / SLOPE_CELLS as f64;
            let (lo, per) = cells.heights[k];
            for j in 0..=HEIGHT_CELLS {
                let y_c = lo + j as f64 / per;
                for i in 0..cells.rho_cells {
                    let rho = i as f64 / cells.rho_scale;
                    for nudge in [-1e-15, 0.0, 1e-15] {
                        // Closest point (ρ₀, y_c, 0), direction across the
                        // radius there at cosine c with the axis.
                        let closest = Vector3::new(rho + nudge, y_c + nudge, 0.0);
                        let d = Vector3::new(0.0, c, (1.0 - c * c).sqrt());
                        let o = closest - d * 4.0;
                        if check(&cells, &boxes, o, d, scale).is_some() {
                            decided += 1;
                        }
                    }
                }
            }
        }
        assert!(decided > 0);
    }

    /// A chain of `spans` cubic spans, as a profile's (`x` and `y`
    /// coefficients, 4 a span): each control point a small random step from
    /// the last, rising on the whole, radii in `[0, scale]`.
    fn chain(state: &mut u64, spans: usize, scale: f64) -> (Vec<f64>, Vec<f64>) {
        let (mut xs, mut ys) = (Vec::new(), Vec::new());
        let (mut x, mut y) = (0.5 * scale, -scale);
        for i in 0..spans * 4 {
            if i % 4 != 0 || i == 0 {
                x = (x + 0.1 * scale * (2.0 * unit(state) - 1.0)).clamp(0.0, scale);
                y += 0.05 * scale * (2.0 * unit(state) - 0.4);
            }
            xs.push(x);
            ys.push(y);
        }
        (xs, ys)
    }

    /// The boxes of [`chain`]'s spans, by their control points.
    fn chain_boxes(xs: &[f64], ys: &[f64]) -> Vec<SpanBox> {
        xs.chunks(4)
            .zip(ys.chunks(4))
            .map(|(x, y)| SpanBox {
                y: (
                    y.iter().copied().fold(f64::INFINITY, f64::min),
                    y.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                ),
                r: (0.0, x.iter().copied().fold(0.0, f64::max)),
            })
            .collect()
    }

    /// Every span the table certifies monotonic for a ray's cell has, for
    /// that ray, a hit function whose slope keeps one sign along the whole
    /// span: `f′ = 2[(A d_x + B d_z) y′ − d_y² x x′]` from the span's own
    /// point and derivative (de Casteljau) at 401 parameters, independent of
    /// the certificate's coefficients and corners. Random cubic spans at
    /// three scales, random rays at every slope the table covers; the table
    /// must certify over ten thousand listed spans and leave some.
    #[test]
    fn certified_spans_are_monotonic() {
        use crate::bernstein::eval_with_derivative;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let (mut certified, mut uncertain) = (0, 0);
        for scale in [1e-6, 1.0, 1e6] {
            for _ in 0..6 {
                let spans = 12;
                let (xs, ys) = chain(&mut state, spans, scale);
                let mut cells = MeridianCells::new(&chain_boxes(&xs, &ys), scale);
                cells.certify_monotone(SpanCurves {
                    xs: &xs,
                    ys: &ys,
                    w: 4,
                    weights: &product_weights(3),
                });
                for _ in 0..20_000 {
                    let o = Vector3::new(
                        4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                        4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                        4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                    );
                    let d = Vector3::new(
                        2.0 * unit(&mut state) - 1.0,
                        (2.0 * unit(&mut state) - 1.0) * [0.05, 1.0, 4.0][certified % 3],
                        2.0 * unit(&mut state) - 1.0,
                    );
                    let Cell::Spans(mut words) = cells.classify(o, d, d.norm(), 1e-12 * scale)
                    else {
                        continue;
                    };
                    let (listed, monotone) = words.next().expect("one word");
                    assert!(words.next().is_none());
                    for k in 0..spans {
                        if listed >> k & 1 == 0 {
                            continue;
                        }
                        if monotone >> k & 1 == 0 {
                            uncertain += 1;
                            continue;
                        }
                        certified += 1;
                        let (sx, sy) = (&xs[4 * k..4 * k + 4], &ys[4 * k..4 * k + 4]);
                        let mut signs = (0, 0);
                        for i in 0..=400 {
                            let s = f64::from(i) / 400.0;
                            let (x, dx) = eval_with_derivative(sx, s).unwrap();
                            let (y, dy) = eval_with_derivative(sy, s).unwrap();
                            let h = y - o.y;
                            let (a, b) = (o.x * d.y + h * d.x, o.z * d.y + h * d.z);
                            let slope = (a * d.x + b * d.z) * dy - d.y * d.y * x * dx;
                            if slope > 0.0 {
                                signs.0 += 1;
                            } else if slope < 0.0 {
                                signs.1 += 1;
                            }
                        }
                        assert!(
                            signs.0 == 401 || signs.1 == 401,
                            "span {k} certified but f′ has signs {signs:?}: o {o:?} d {d:?}"
                        );
                    }
                }
            }
        }
        assert!(
            certified > 10_000 && uncertain > 1000,
            "{certified} certified, {uncertain} not"
        );
    }

    /// The cell test the table's runs stand for: whether some line of cell
    /// `(k, j, i)`, enlarged by the margins, meets the padded box `b`, by
    /// the box's nearest and farthest heights from the cell's.
    fn cell_meets(cells: &MeridianCells, (k, j, i): (usize, usize, usize), b: &SpanBox) -> bool {
        let (c0, c1) = slope_range(k);
        let (g0, g1) = (run_per_rise_squared(c1), run_per_rise_squared(c0));
        let (lo, per) = cells.heights[k];
        let m = cells.margin;
        let (y0, y1) = (lo + j as f64 / per - m, lo + (j + 1) as f64 / per + m);
        let rho_cell = 1.0 / cells.rho_scale;
        let rho2_margin = m * m / MARGIN;
        let a0 = ((i as f64 * rho_cell).powi(2) - rho2_margin).max(0.0);
        let a1 = ((i + 1) as f64 * rho_cell).powi(2) + rho2_margin;
        let pad = PAD / MARGIN * m;
        let (by, br) = ((b.y.0 - pad, b.y.1 + pad), (b.r.0 - pad, b.r.1 + pad));
        let near = (by.0 - y1).max(y0 - by.1).max(0.0);
        let far = (by.1 - y0).max(y1 - by.0);
        let within = a0 + g0 * near * near <= br.1 * br.1;
        let out = br.0 <= 0.0 || g1.is_infinite() || a1 + g1 * far * far >= br.0 * br.0;
        within && out
    }

    /// The runs of height cells the table is built from give the cells the
    /// cell test passes: every one of them (the table is a superset), and
    /// beyond them only cells at a run's end within its rounding slack
    /// (none in practice). Random boxes at three scales.
    #[test]
    fn runs_are_the_cells_the_cell_test_passes() {
        let mut state = 0x1234_5678_9ABC_DEF1_u64;
        for scale in [1e-6, 1.0, 1e6] {
            let boxes = boxes(&mut state, 70, scale);
            let cells = MeridianCells::new(&boxes, scale);
            let (mut passed, mut extra) = (0, 0);
            for k in 0..SLOPE_CELLS {
                for j in 0..HEIGHT_CELLS {
                    for i in 0..cells.rho_cells {
                        let at = ((k * HEIGHT_CELLS + j) * cells.rho_cells + i) * cells.width;
                        for (s, b) in boxes.iter().enumerate() {
                            let set = cells.masks[at + s / 8] >> (s % 8) & 1 == 1;
                            let meets = cell_meets(&cells, (k, j, i), b);
                            assert!(set || !meets, "cell {:?} box {s} left out", (k, j, i));
                            passed += usize::from(meets);
                            extra += usize::from(set && !meets);
                        }
                    }
                }
            }
            assert!(passed > 10_000, "{passed} cells passed");
            assert!(extra <= passed / 1000, "{extra} cells beyond {passed}");
        }
    }

    /// The height cells certified monotonic per slope cell and span (from
    /// the closed-form heights) pass the corner test [`Monotone::holds`] on
    /// the cell enlarged by the margins, and miss few of the cells that
    /// test passes (the closed form asks twice its tolerance). Random cubic
    /// chains at three scales.
    #[test]
    fn certified_cells_pass_the_corner_test() {
        let mut state = 0x0F1E_2D3C_4B5A_6978_u64;
        let (mut certified, mut missed) = (0, 0);
        for scale in [1e-6, 1.0, 1e6] {
            let (xs, ys) = chain(&mut state, 12, scale);
            let mut cells = MeridianCells::new(&chain_boxes(&xs, &ys), scale);
            let weights = product_weights(3);
            cells.certify_monotone(SpanCurves {
                xs: &xs,
                ys: &ys,
                w: 4,
                weights: &weights,
            });
            let certificates = Monotone::new(SpanCurves {
                xs: &xs,
                ys: &ys,
                w: 4,
                weights: &weights,
            });
            for k in 0..SLOPE_CELLS {
                let (lo, per) = cells.heights[k];
                let m = cells.margin;
                for j in 0..HEIGHT_CELLS {
                    let y = (lo + j as f64 / per - m, lo + (j + 1) as f64 / per + m);
                    for s in 0..12 {
                        let at = (k * HEIGHT_CELLS + j) * cells.width;
                        let set = cells.monotone[at + s / 8] >> (s % 8) & 1 == 1;
                        let holds = certificates.holds(s, slope_range(k), y);
                        assert!(holds || !set, "slope {k} height {j} span {s}: certified");
                        certified += usize::from(set);
                        missed += usize::from(holds && !set);
                    }
                }
            }
        }
        assert!(certified > 2000, "{certified} certified");
        assert!(missed <= certified / 100, "{missed} missed of {certified}");
    }

    /// Lines steeper than `C_MAX`, far origins and loose tolerances are
    /// left to the full test; a line that stays outside every box's radius
    /// is a certain miss.
    #[test]
    fn outside_and_certain_misses() {
        let boxes = [SpanBox {
            y: (0.0, 1.0),
            r: (0.2, 0.5),
        }];
        let cells = MeridianCells::new(&boxes, 1.0);
        let o = Vector3::new(0.1, -2.0, 0.0);
        let steep = Vector3::new(0.0, 1.0, 0.01);
        assert!(matches!(
            cells.classify(o, steep, steep.norm(), 1e-12),
            Cell::Outside
        ));
        let d = Vector3::new(0.0, 0.5, 1.0);
        assert!(matches!(
            cells.classify(o, d, d.norm(), 1e-3),
            Cell::Outside
        ));
        let far = Vector3::new(2e5, 0.5, 0.0);
        assert!(matches!(
            cells.classify(far, d, d.norm(), 1e-12),
            Cell::Outside
        ));
        let wide = Vector3::new(0.6, 0.5, -3.0);
        let along_z = Vector3::new(0.0, 0.0, 1.0);
        assert!(matches!(
            cells.classify(wide, along_z, 1.0, 1e-12),
            Cell::Miss
        ));
        let near = Vector3::new(0.4, 0.5, -3.0);
        let Cell::Spans(words) = cells.classify(near, along_z, 1.0, 1e-12) else {
            panic!("a line through the box is not listed");
        };
        assert_eq!(words.map(|(listed, _)| listed).collect::<Vec<_>>(), [1]);
    }
}

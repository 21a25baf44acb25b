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
//! greatest. The table cuts `(ρ₀², y_c, c)` into cells and keeps, per cell,
//! the spans whose padded height–radius box some line of the (slightly
//! enlarged) cell meets: the line comes within the box's outer radius in
//! its height range, and does not stay inside its inner radius. A ray then
//! runs the per-span test ([`span_entry`](super::revolution)) on those spans
//! only, instead of on every span of every group it enters.
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
//! ([`MeridianCells::certify_monotone`]; monotonicity does not depend on
//! `ρ₀²`). The intersector decides those spans from their end values.

use crate::bernstein::binomial;
use nalgebra::Vector3;

/// Cells along `ρ₀²`, uniform in `[0, R²]` (`R` the padded outer radius).
const RHO_CELLS: usize = 16;
/// Cells along `y_c`, uniform over the heights from which a line of the
/// `c` cell can still reach the profile.
const HEIGHT_CELLS: usize = 32;
/// Cells along `c`, uniform in `[0, C_MAX]`.
const SLOPE_CELLS: usize = 16;
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

/// Where the table puts a ray.
pub(super) enum Cell<'a> {
    /// No span can be hit.
    Miss,
    /// Only the spans in `listed` can be hit (bit `k % 64` of word
    /// `k / 64`); on those in `monotone` the hit function is strictly
    /// monotonic for every line of the cell (see [`Monotone`]).
    Spans {
        listed: &'a [u64],
        monotone: &'a [u64],
    },
    /// The table cannot say; test every span.
    Outside,
}

/// The culling table of one surface.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct MeridianCells {
    /// `ρ₀²` at and beyond which nothing can be hit (with the margin).
    rho2_max: f64,
    /// `RHO_CELLS / rho2_max`.
    rho2_scale: f64,
    /// Per `c` cell: the lowest `y_c` of its height cells and
    /// `HEIGHT_CELLS` divided by their total height.
    heights: [(f64, f64); SLOPE_CELLS],
    /// Largest position tolerance (`accept`) the padding covers.
    pad: f64,
    /// Largest `|o|` coordinate whose rounding the margins cover.
    origin_limit: f64,
    /// The margin by which cells are enlarged ([`MARGIN`] times the scale).
    margin: f64,
    /// Words per cell's span mask.
    words: usize,
    /// The masks, cell `(k, j, i)` (slope, height, radius) at
    /// `((k · HEIGHT_CELLS + j) · RHO_CELLS + i) · words`.
    masks: Vec<u64>,
    /// The spans on which every line of slope and height cell `(k, j)` has
    /// a strictly monotonic hit function, at `(k · HEIGHT_CELLS + j) · words`.
    monotone: Vec<u64>,
}

/// The spans' Bernstein coefficients, `w` per span (degree `w − 1`), for
/// [`MeridianCells::new`]'s monotonicity table.
#[derive(Debug, Clone, Copy)]
pub(super) struct SpanCurves<'a> {
    pub(super) xs: &'a [f64],
    pub(super) ys: &'a [f64],
    pub(super) w: usize,
}

/// The certificate of monotonicity for one span and a box of line classes.
///
/// For a line with numbers `ρ₀²`, `y_c` and `c`, the hits on a span are
/// the roots of `F(s) = x(s)² − ρ₀² − g² (y(s) − y_c)²` (the intersector's
/// `f` is `−d_y² F`), so
///
/// `c² F′ = c² (x²)′ − (1 − c²) ((y − y_c)²)′`,
///
/// which does not depend on `ρ₀²` and is linear in `c²` and in `y_c`
/// (`((y − y_c)²)′ = (y²)′ − 2 y_c y′`). Its Bernstein coefficients (degree
/// `2n − 1`) are therefore extreme at the four corners of a box of
/// `(c², y_c)`: if they are all certainly of one sign there, `F′` keeps
/// that sign on the whole span for every line of the box, and `F` has at
/// most one root there, a simple one.
struct Monotone {
    /// `(x²)′`, degree `2n − 1`.
    square_x: Vec<f64>,
    /// `(y²)′` and `y′`, both degree `2n − 1`.
    square_y: Vec<f64>,
    slope_y: Vec<f64>,
}

impl Monotone {
    fn new(xs: &[f64], ys: &[f64]) -> Self {
        let n = xs.len() - 1;
        let derivative = |z: Vec<f64>| -> Vec<f64> {
            let m = (z.len() - 1) as f64;
            z.windows(2).map(|w| m * (w[1] - w[0])).collect()
        };
        // y of degree n raised to degree 2n (so that y′ has degree 2n − 1).
        let raised: Vec<f64> = (0..=2 * n)
            .map(|k| {
                (k.saturating_sub(n)..=k.min(n))
                    .map(|i| binomial(n, i) * binomial(n, k - i) / binomial(2 * n, k) * ys[i])
                    .sum()
            })
            .collect();
        Monotone {
            square_x: derivative(square(xs)),
            square_y: derivative(square(ys)),
            slope_y: derivative(raised),
        }
    }

    /// Whether `c² F′` is certainly of one sign for every `c ∈ [c0, c1]`
    /// and `y_c ∈ [y0, y1]` (see the type's docs; `tol` relative to the
    /// terms' size covers the rounding here and in the coefficients).
    fn holds(&self, (c0, c1): (f64, f64), (y0, y1): (f64, f64)) -> bool {
        const TOL: f64 = 1e-9;
        let mut sign = 0.0;
        for &c2 in &[c0 * c0, c1 * c1] {
            for &yc in &[y0, y1] {
                for ((&dx2, &dy2), &dy) in
                    self.square_x.iter().zip(&self.square_y).zip(&self.slope_y)
                {
                    let q = dy2 - 2.0 * yc * dy;
                    let v = c2 * dx2 - (1.0 - c2) * q;
                    let size = c2 * dx2.abs() + (1.0 - c2) * (dy2.abs() + 2.0 * (yc * dy).abs());
                    let certain = if v > TOL * size {
                        1.0
                    } else if v < -TOL * size {
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

/// The Bernstein coefficients of `z(s)²` (degree `2n`) for `z` of degree
/// `n` with coefficients `zs`.
fn square(zs: &[f64]) -> Vec<f64> {
    let n = zs.len() - 1;
    let mut out = vec![0.0; 2 * n + 1];
    for (i, &a) in zs.iter().enumerate() {
        for (j, &b) in zs.iter().enumerate() {
            out[i + j] += binomial(n, i) * binomial(n, j) * a * b;
        }
    }
    for (k, v) in out.iter_mut().enumerate() {
        *v /= binomial(2 * n, k);
    }
    out
}

/// One span's box as the table sees it: heights `y` and distances from
/// the axis `r`, as the span's control points bound them (the table adds
/// its own padding).
#[derive(Debug, Clone, Copy)]
pub(super) struct SpanBox {
    pub(super) y: (f64, f64),
    pub(super) r: (f64, f64),
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

impl MeridianCells {
    /// The table for spans with boxes `boxes` on an object of size `scale`,
    /// with no span certified monotonic (see [`Self::certify_monotone`]).
    pub(super) fn new(boxes: &[SpanBox], scale: f64) -> Self {
        let pad = PAD * scale;
        let margin = MARGIN * scale;
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
        let rho2_max = r_max * r_max + margin * scale;
        let rho2_cell = rho2_max / RHO_CELLS as f64;
        let words = boxes.len().div_ceil(64);
        let mut masks = vec![0_u64; SLOPE_CELLS * HEIGHT_CELLS * RHO_CELLS * words];
        let monotone = vec![0_u64; SLOPE_CELLS * HEIGHT_CELLS * words];
        let mut heights = [(0.0, 0.0); SLOPE_CELLS];
        let c_cell = C_MAX / SLOPE_CELLS as f64;
        for (k, height) in heights.iter_mut().enumerate() {
            let c0 = (k as f64 * c_cell - SLOPE_MARGIN).max(0.0);
            let c1 = ((k + 1) as f64 * c_cell + SLOPE_MARGIN).min(1.0);
            // g² over the cell: largest at its least c.
            let (g0, g1) = (run_per_rise_squared(c1), run_per_rise_squared(c0));
            // A line of this cell meets heights within R/g of y_c only.
            let reach = if g0 > 0.0 {
                r_max / g0.sqrt()
            } else {
                f64::INFINITY
            };
            let (lo, hi) = (y_min - reach - margin, y_max + reach + margin);
            let y_cell = (hi - lo) / HEIGHT_CELLS as f64;
            *height = (lo, HEIGHT_CELLS as f64 / (hi - lo));
            for j in 0..HEIGHT_CELLS {
                let b0 = lo + j as f64 * y_cell - margin;
                let b1 = lo + (j + 1) as f64 * y_cell + margin;
                for i in 0..RHO_CELLS {
                    let a0 = (i as f64 * rho2_cell - margin * scale).max(0.0);
                    let a1 = (i + 1) as f64 * rho2_cell + margin * scale;
                    let cell = ((k * HEIGHT_CELLS + j) * RHO_CELLS + i) * words;
                    for (s, b) in boxes.iter().enumerate() {
                        // Nearest and farthest height differences between
                        // the cell's y_c and the box.
                        let near = (b.y.0 - b1).max(b0 - b.y.1).max(0.0);
                        let far = (b.y.1 - b0).max(b1 - b.y.0);
                        let comes_within = a0 + g0 * near * near <= b.r.1 * b.r.1;
                        let gets_out = b.r.0 <= 0.0
                            || g1.is_infinite()
                            || a1 + g1 * far * far >= b.r.0 * b.r.0;
                        if comes_within && gets_out {
                            masks[cell + s / 64] |= 1 << (s % 64);
                        }
                    }
                }
            }
        }
        MeridianCells {
            rho2_max,
            rho2_scale: RHO_CELLS as f64 / rho2_max,
            heights,
            pad,
            origin_limit: ORIGIN_LIMIT * scale,
            margin,
            words,
            masks,
            monotone,
        }
    }

    /// Certifies no span monotonic (all take the full solve).
    #[cfg(test)]
    pub(super) fn forget_monotone(&mut self) {
        self.monotone.fill(0);
    }

    /// Marks, per slope and height cell, the spans (Bernstein coefficients
    /// `curves`, in the order of the boxes) on which every line of the
    /// cell, enlarged by the margins, has a strictly monotonic hit
    /// function ([`Monotone`]).
    pub(super) fn certify_monotone(&mut self, curves: SpanCurves<'_>) {
        let certificates: Vec<Monotone> = curves
            .xs
            .chunks_exact(curves.w)
            .zip(curves.ys.chunks_exact(curves.w))
            .map(|(xs, ys)| Monotone::new(xs, ys))
            .collect();
        let c_cell = C_MAX / SLOPE_CELLS as f64;
        for (k, &(lo, per)) in self.heights.iter().enumerate() {
            let c0 = (k as f64 * c_cell - SLOPE_MARGIN).max(0.0);
            let c1 = ((k + 1) as f64 * c_cell + SLOPE_MARGIN).min(1.0);
            for j in 0..HEIGHT_CELLS {
                let b0 = lo + j as f64 / per - self.margin;
                let b1 = lo + (j + 1) as f64 / per + self.margin;
                let at = (k * HEIGHT_CELLS + j) * self.words;
                for (s, certificate) in certificates.iter().enumerate() {
                    if certificate.holds((c0, c1), (b0, b1)) {
                        self.monotone[at + s / 64] |= 1 << (s % 64);
                    }
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
    /// `|o| ≤ ORIGIN_LIMIT · scale` that is far inside [`MARGIN`].
    #[inline]
    pub(super) fn classify(
        &self,
        o: Vector3<f64>,
        d: Vector3<f64>,
        dn: f64,
        accept: f64,
    ) -> Cell<'_> {
        let c = d.y.abs() / dn;
        if c > C_MAX || accept > self.pad || o.amax() > self.origin_limit {
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
        let k = ((c * (SLOPE_CELLS as f64 / C_MAX)) as usize).min(SLOPE_CELLS - 1);
        let (lo, per) = self.heights[k];
        let y = (o.y + t_c * d.y - lo) * per;
        if !(rho2.is_finite() && y.is_finite()) {
            return Cell::Outside;
        }
        if rho2 >= self.rho2_max || y < 0.0 || y >= HEIGHT_CELLS as f64 {
            return Cell::Miss;
        }
        let j = y as usize;
        let i = ((rho2 * self.rho2_scale) as usize).min(RHO_CELLS - 1);
        let at = ((k * HEIGHT_CELLS + j) * RHO_CELLS + i) * self.words;
        let mono = (k * HEIGHT_CELLS + j) * self.words;
        Cell::Spans {
            listed: &self.masks[at..at + self.words],
            monotone: &self.monotone[mono..mono + self.words],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::ray::test_unit::unit;

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
            Cell::Spans { listed: mask, .. } => {
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
            assert_eq!(cells.words, 2);
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
            for j in (0..=HEIGHT_CELLS).step_by(3) {
                let y_c = lo + j as f64 / per;
                for i in (0..RHO_CELLS).step_by(2) {
                    let rho = (i as f64 * cells.rho2_max / RHO_CELLS as f64).sqrt();
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

    /// Lines steeper than `C_MAX`, far origins and loose tolerances are
    /// left to the full test; a line that stays outside every box's radius
    /// is a certain miss.
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
                // A chain of spans, as a profile's: each control point a
                // small random step from the last, rising on the whole.
                let (mut xs, mut ys) = (Vec::new(), Vec::new());
                let (mut x, mut y) = (0.5 * scale, -scale);
                for i in 0..spans * 4 {
                    if i % 4 != 0 || i == 0 {
                        x = (x + 0.1 * scale * (2.0 * unit(&mut state) - 1.0)).clamp(0.0, scale);
                        y += 0.05 * scale * (2.0 * unit(&mut state) - 0.4);
                    }
                    xs.push(x);
                    ys.push(y);
                }
                let boxes: Vec<SpanBox> = xs
                    .chunks(4)
                    .zip(ys.chunks(4))
                    .map(|(x, y)| SpanBox {
                        y: (
                            y.iter().copied().fold(f64::INFINITY, f64::min),
                            y.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                        ),
                        r: (0.0, x.iter().copied().fold(0.0, f64::max)),
                    })
                    .collect();
                let mut cells = MeridianCells::new(&boxes, scale);
                cells.certify_monotone(SpanCurves {
                    xs: &xs,
                    ys: &ys,
                    w: 4,
                });
                for _ in 0..20000 {
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
                    let Cell::Spans { listed, monotone } =
                        cells.classify(o, d, d.norm(), 1e-12 * scale)
                    else {
                        continue;
                    };
                    for k in 0..spans {
                        let bit = |mask: &[u64]| mask[k / 64] >> (k % 64) & 1 == 1;
                        if !bit(listed) {
                            continue;
                        }
                        if !bit(monotone) {
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
        assert!(matches!(
            cells.classify(near, along_z, 1.0, 1e-12),
            Cell::Spans { listed: [1], .. }
        ));
    }
}

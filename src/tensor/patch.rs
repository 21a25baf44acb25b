//! One Bézier patch of a tensor-product surface in homogeneous form, and
//! its jets: the point and partial derivatives up to second order by tensor
//! de Casteljau.
//!
//! A patch of degrees `(p, q)` is `S(s, t) = A(s, t)/w(s, t)` with
//! `A = Σᵢⱼ wᵢⱼPᵢⱼ Bᵢᵖ(s) Bⱼ^q(t)` and `w = Σᵢⱼ wᵢⱼ Bᵢᵖ(s) Bⱼ^q(t)` on
//! `[0, 1]²` (unit weights for the polynomial surfaces, so that the division
//! is exact). Evaluation runs de Casteljau along every row (in `t`), then
//! along the column of results (in `s`) (Farin, *Curves and Surfaces for
//! CAGD*, ch. 16–17), on stack scratch space.

use crate::bernstein::{self, Coefficient, lerp};
use crate::curve::Homogeneous;
use crate::curve::unit_direction;
use crate::scratch::with_scratch;
use crate::{Aabb, Hit, Ray};
use nalgebra::{Point3, Unit, Vector3};

/// One Bézier patch of a tensor-product surface, on the parameter rectangle
/// `u × v`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Patch {
    /// The parameter interval in `u` the patch covers, `u.0 < u.1`.
    pub(crate) u: (f64, f64),
    /// The parameter interval in `v`, `v.0 < v.1`.
    pub(crate) v: (f64, f64),
    /// `(wᵢⱼPᵢⱼ, wᵢⱼ)`, row-major: `net[i·(q + 1) + j]`.
    pub(crate) net: Vec<Homogeneous<3>>,
}
impl Patch {
    /// The box of the projected control net, which holds the patch (convex
    /// hull property, weights positive); not padded.
    pub(crate) fn net_box(&self) -> Aabb {
        self.net
            .iter()
            .fold(Aabb::EMPTY, |b, h| b.include(&Point3::from(h.wp / h.w)))
    }
}
/// How far a box around control points of largest coordinate `scale` is
/// padded for rounding (of the points' projection and of the search's
/// arithmetic on them).
pub(crate) fn rounding_pad(scale: f64) -> f64 {
    64.0 * f64::EPSILON * scale
}
/// Value and derivatives up to order 2 (`d[a][b] = ∂ᵃ⁺ᵇ/∂uᵃ∂vᵇ`, `a + b ≤ 2`).
pub(crate) type Jet<T> = [[T; 3]; 3];
/// The derivatives `0 ..= order` (`order ≤ 2`) at `t` of the Bernstein
/// polynomial with coefficients `c` (non-empty), into `out[..=order]`.
/// De Casteljau down to `order + 1` points; the `k`-th derivative is
/// `n!/(n − k)!` times the `k`-th forward difference of those.
#[inline]
fn bernstein_jet<T: Coefficient>(c: &[T], t: f64, order: usize, out: &mut [T; 3]) {
    let n = c.len() - 1;
    let zero = c[0] * 0.0;
    *out = [zero; 3];
    // Orders 0 and 1: the kernels unrolled for degree ≤ 16.
    match order {
        0 => {
            if let Some(x) = bernstein::eval(c, t) {
                out[0] = x;
                return;
            }
        }
        1 => {
            if let Some((x, dx)) = bernstein::eval_with_derivative(c, t) {
                out[0] = x;
                out[1] = dx;
                return;
            }
        }
        _ => {}
    }
    let k = order.min(n);
    with_scratch(c.len(), c[0], |s| {
        s.copy_from_slice(c);
        for level in 1..=(n - k) {
            for j in 0..=(n - level) {
                s[j] = lerp(s[j], s[j + 1], t);
            }
        }
        let nf = n as f64;
        match k {
            0 => out[0] = s[0],
            1 => {
                out[0] = lerp(s[0], s[1], t);
                out[1] = (s[1] - s[0]) * nf;
            }
            _ => {
                let a = lerp(s[0], s[1], t);
                let b = lerp(s[1], s[2], t);
                out[0] = lerp(a, b, t);
                out[1] = (b - a) * nf;
                out[2] = (s[2] - s[1] * 2.0 + s[0]) * (nf * (nf - 1.0));
            }
        }
    });
}
/// The jet (orders `a + b ≤ order ≤ 2`) at `(s, t) ∈ [0, 1]²` of the tensor
/// Bernstein polynomial with row-major coefficients `net` of `rows × cols`.
pub(crate) fn tensor_jet<T: Coefficient>(
    net: &[T],
    cols: usize,
    s: f64,
    t: f64,
    order: usize,
) -> Jet<T> {
    let rows = net.len() / cols;
    let zero = net[0] * 0.0;
    let mut jet = [[zero; 3]; 3];
    with_scratch((order + 1) * rows, zero, |buf| {
        let mut row_jet = [zero; 3];
        for i in 0..rows {
            bernstein_jet(&net[i * cols..(i + 1) * cols], t, order, &mut row_jet);
            for b in 0..=order {
                buf[b * rows + i] = row_jet[b];
            }
        }
        let mut col_jet = [zero; 3];
        for b in 0..=order {
            bernstein_jet(&buf[b * rows..(b + 1) * rows], s, order - b, &mut col_jet);
            for a in 0..=(order - b) {
                jet[a][b] = col_jet[a];
            }
        }
    });
    jet
}
/// The point and derivatives (orders `≤ order ≤ 2`) of `S = A/w` from the
/// homogeneous jet, by the quotient rule (Leibniz on `A = w·S`).
pub(crate) fn project_jet(h: &Jet<Homogeneous<3>>, order: usize) -> Jet<Vector3<f64>> {
    let w = h[0][0].w;
    let mut d = [[Vector3::zeros(); 3]; 3];
    d[0][0] = h[0][0].wp / w;
    if order >= 1 {
        d[1][0] = (h[1][0].wp - d[0][0] * h[1][0].w) / w;
        d[0][1] = (h[0][1].wp - d[0][0] * h[0][1].w) / w;
    }
    if order >= 2 {
        let s = d[0][0];
        d[2][0] = (h[2][0].wp - d[1][0] * (2.0 * h[1][0].w) - s * h[2][0].w) / w;
        d[0][2] = (h[0][2].wp - d[0][1] * (2.0 * h[0][1].w) - s * h[0][2].w) / w;
        d[1][1] = (h[1][1].wp - d[0][1] * h[1][0].w - d[1][0] * h[0][1].w - s * h[1][1].w) / w;
    }
    d
}

/// A hit in a surface's own parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PatchHit {
    /// Index of the patch hit.
    pub(crate) patch: usize,
    pub(crate) t: f64,
    pub(crate) u: f64,
    pub(crate) v: f64,
    /// The hit's parameters `(s, t)` on piece `patch`, each in `[0, 1]`:
    /// `(u, v)` is their image, rounded.
    pub(crate) st: (f64, f64),
    /// Newton's method ended past the patch's side (by at most its
    /// slack) and `(u, v)` was moved onto it: the root may lie on the
    /// neighbouring patch, where it can be found without that move.
    pub(crate) past_side: bool,
}

impl PatchHit {
    /// The crate's hit for `ray`, with the surface's `point` and `normal`
    /// at `(u, v)`; where the surface has no tangent plane the normal faces
    /// the ray.
    pub(crate) fn to_hit(
        self,
        ray: &Ray,
        point: Point3<f64>,
        normal: Option<Unit<Vector3<f64>>>,
    ) -> Option<Hit> {
        let normal = normal.or_else(|| unit_direction(-ray.dir))?;
        Some(Hit {
            t: self.t,
            point,
            normal,
            uv: (self.u, self.v),
        })
    }
}

/// The most control points per side [`first_jet`] takes (degree 7).
const JET_SIDE: usize = 8;

/// The Bernstein bases of degrees `n < JET_SIDE` and `n − 1` at `t`:
/// `Bⱼⁿ(t)` and `Bⱼⁿ⁻¹(t)` (the second empty for `n = 0`), by the
/// recurrence `Bⱼᵏ = (1 − t)·Bⱼᵏ⁻¹ + t·Bⱼ₋₁ᵏ⁻¹`.
#[inline(always)]
fn bases(n: usize, t: f64) -> ([f64; JET_SIDE], [f64; JET_SIDE]) {
    let mut b = [0.0; JET_SIDE];
    b[0] = 1.0;
    let u = 1.0 - t;
    let mut lower = b;
    for k in 1..=n {
        lower = b;
        for j in (1..=k).rev() {
            b[j] = u * b[j] + t * b[j - 1];
        }
        b[0] *= u;
    }
    (b, lower)
}

/// The homogeneous point and first partials `(A, ∂A/∂s, ∂A/∂t)` (with
/// their weights) at `(s, t)` of the net `net` of `rows × cols` points,
/// degrees below [`JET_SIDE`] (`None` beyond): `A = Σᵢ Bᵢ(s)·Rᵢ` over the
/// rows' values `Rᵢ = Σⱼ Bⱼ(t)·Pᵢⱼ`, `∂A/∂s = p·Σᵢ Bᵢᵖ⁻¹(s)·(Rᵢ₊₁ − Rᵢ)`
/// and `∂A/∂t = q·Σᵢ Bᵢ(s)·Σⱼ Bⱼ^{q−1}(t)·(Pᵢⱼ₊₁ − Pᵢⱼ)`. The derivatives are
/// sums of differences, so they vanish exactly where the points they
/// difference coincide (a collapsed edge), as de Casteljau's do. Any
/// `(s, t)` is taken (outside `[0, 1]²` the polynomial is extended).
#[inline]
pub(crate) fn first_jet(
    net: &[Homogeneous<3>],
    cols: usize,
    s: f64,
    t: f64,
) -> Option<[Homogeneous<3>; 3]> {
    let jet = jet_sums(net, cols, s, t, |h| [h.wp.x, h.wp.y, h.wp.z, h.w])?;
    Some(jet.map(|a| Homogeneous {
        wp: Vector3::new(a[0], a[1], a[2]),
        w: a[3],
    }))
}

/// The point and first partials `(S, ∂S/∂s, ∂S/∂t)` of a polynomial net
/// (unit weights): [`first_jet`] without the weights.
#[inline]
pub(crate) fn polynomial_jet(
    net: &[Homogeneous<3>],
    cols: usize,
    s: f64,
    t: f64,
) -> Option<[Vector3<f64>; 3]> {
    let jet = jet_sums(net, cols, s, t, |h| [h.wp.x, h.wp.y, h.wp.z])?;
    Some(jet.map(|a| Vector3::new(a[0], a[1], a[2])))
}

/// The sums of [`first_jet`] over the `K` coordinates `coords` gives of
/// each point: unrolled for bicubic, biquadratic and bilinear nets, by
/// the sized loops up to [`JET_SIDE`] a side, `None` beyond.
#[inline(always)]
fn jet_sums<const K: usize>(
    net: &[Homogeneous<3>],
    cols: usize,
    s: f64,
    t: f64,
    coords: impl Fn(&Homogeneous<3>) -> [f64; K],
) -> Option<[[f64; K]; 3]> {
    Some(match (net.len(), cols) {
        // Constant sizes, so that the inlined loops are unrolled.
        (16, 4) => sum_jet_sized(net, 4, 4, s, t, coords),
        (9, 3) => sum_jet_sized(net, 3, 3, s, t, coords),
        (4, 2) => sum_jet_sized(net, 2, 2, s, t, coords),
        _ => {
            let rows = net.len().checked_div(cols)?;
            if rows == 0 || rows > JET_SIDE || cols > JET_SIDE || rows * cols != net.len() {
                return None;
            }
            sum_jet_sized::<K>(net, rows, cols, s, t, coords)
        }
    })
}

/// The sums of [`first_jet`] over the `K` coordinates `coords` gives of
/// each point of a net of `rows × cols ≤ JET_SIDE²` points.
#[inline(always)]
fn sum_jet_sized<const K: usize>(
    net: &[Homogeneous<3>],
    rows: usize,
    cols: usize,
    s: f64,
    t: f64,
    coords: impl Fn(&Homogeneous<3>) -> [f64; K],
) -> [[f64; K]; 3] {
    let (p, q) = (rows - 1, cols - 1);
    let (bs, ls) = bases(p, s);
    let (bt, lt) = bases(q, t);
    let mut point = [0.0_f64; K];
    let mut along_t = [0.0_f64; K];
    let mut along_s = [0.0_f64; K];
    let mut previous = [0.0_f64; K];
    for i in 0..rows {
        let row = &net[i * cols..(i + 1) * cols];
        let (mut value, mut slope) = ([0.0_f64; K], [0.0_f64; K]);
        let mut last = coords(&row[0]);
        for c in 0..K {
            value[c] = bt[0] * last[c];
        }
        for j in 1..cols {
            let x = coords(&row[j]);
            for c in 0..K {
                value[c] += bt[j] * x[c];
                slope[c] += lt[j - 1] * (x[c] - last[c]);
            }
            last = x;
        }
        for c in 0..K {
            point[c] += bs[i] * value[c];
            along_t[c] += bs[i] * slope[c];
            if i > 0 {
                along_s[c] += ls[i - 1] * (value[c] - previous[c]);
            }
        }
        previous = value;
    }
    let (pf, qf) = (p as f64, q as f64);
    [point, along_s.map(|x| x * pf), along_t.map(|x| x * qf)]
}

//! An independent reference for ray ∩ (rational) Bézier patch that finds
//! every root, written without the library's patch search.
//!
//! The ray `o + t·d` is the intersection of two planes with normals `e₁`,
//! `e₂ ⟂ d`. On a patch `S = A/W` (`A = Σ wᵢⱼPᵢⱼBᵢ(u)Bⱼ(v)`, `W = Σ wᵢⱼBᵢBⱼ`)
//! the ray meets the surface where `fₖ = eₖ·(A − W·o)`, `k = 1, 2`, both
//! vanish. Unlike the library (Bernstein coefficients and de Casteljau
//! subdivision), the reference
//! - converts each `fₖ` to the **power (monomial) basis** with interval
//!   coefficients ([`Interval`]: every operation rounded outward by one ulp,
//!   so the true value of every real-number operation is enclosed);
//! - encloses `fₖ` on a parameter box `[u₀, u₀ + h] × [v₀, v₀ + k]` by the
//!   Taylor shift to the box's corner, `fₖ(u₀ + s, v₀ + r) = Σ gₐᵦ sᵃ rᵝ`,
//!   and the range `g₀₀ + Σ gₐᵦ·[0, hᵃkᵝ]`: a box whose enclosure of `f₁`
//!   or of `f₂` excludes zero holds no root (rigorously);
//! - subdivides the other boxes down to [`LEAF`], then runs Newton's method
//!   on `(e₁·(S − o), e₂·(S − o))` from the leaf's centre with its own
//!   evaluation of `S` (the explicit Bernstein sums `C(n, i)xⁱ(1 − x)ⁿ⁻ⁱ`,
//!   not de Casteljau). A leaf is resolved when Newton lands on a root inside
//!   it (widened by a tenth of its size); an unresolved leaf is halved again,
//!   down to [`FLOOR`]; a leaf still unresolved there (a grazing ray or a
//!   non-isolated root) makes the answer [`RefHits::doubtful`];
//! - merges roots closer than `1e-10` of the scene's size along the ray.
//!
//! The search covers `[−η, 1 + η]²` (`η = 1e-6`), so roots just outside a
//! patch are seen and flagged ([`RefHit::edge`]).

use super::Rng;
/// The interval type of the enclosures (one for all of testkit's references).
pub use crate::interval::Interval;
use revolve::nalgebra::{Point3, Vector3};
use revolve::{BSplineSurface, BezierSurface, Hit, Intersect, NurbsSurface, Ray, Surface};

/// Boxes at most this wide (both sides) try Newton's method.
pub const LEAF: f64 = 1.0 / 2048.0;

/// Unresolved boxes are halved down to this width.
pub const FLOOR: f64 = 1.0 / (1u64 << 26) as f64;

/// Boxes a search may visit before it gives up (and is doubtful).
pub const MAX_BOXES: usize = 200_000;

/// How far outside `[0, 1]²` the search looks.
pub const ETA: f64 = 1e-6;

/// Largest degree the reference handles (stack arrays).
const MAX_DEGREE: usize = 23;

/// One rational Bézier patch of a surface, on the parameter rectangle
/// `u × v` of the surface (local parameters `[0, 1]²`).
#[derive(Debug, Clone)]
pub struct RefPatch {
    pub points: Vec<Vec<Point3<f64>>>,
    pub weights: Vec<Vec<f64>>,
    pub u: (f64, f64),
    pub v: (f64, f64),
}

impl RefPatch {
    /// A polynomial patch (unit weights) on `[0, 1]²`.
    pub fn polynomial(points: Vec<Vec<Point3<f64>>>) -> Self {
        let weights = points.iter().map(|r| vec![1.0; r.len()]).collect();
        RefPatch {
            points,
            weights,
            u: (0.0, 1.0),
            v: (0.0, 1.0),
        }
    }

    fn degrees(&self) -> (usize, usize) {
        (self.points.len() - 1, self.points[0].len() - 1)
    }

    /// `(S, S_u, S_v)` at local `(s, t)` by the explicit Bernstein sums.
    pub fn jet(&self, s: f64, t: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let (p, q) = self.degrees();
        let (bu, du) = basis(p, s);
        let (bv, dv) = basis(q, t);
        let (mut a, mut a_s, mut a_t) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
        let (mut w, mut w_s, mut w_t) = (0.0, 0.0, 0.0);
        for i in 0..=p {
            for j in 0..=q {
                let wij = self.weights[i][j];
                let hp = self.points[i][j].coords * wij;
                let (b, bs, bt) = (bu[i] * bv[j], du[i] * bv[j], bu[i] * dv[j]);
                a += hp * b;
                a_s += hp * bs;
                a_t += hp * bt;
                w += wij * b;
                w_s += wij * bs;
                w_t += wij * bt;
            }
        }
        let x = a / w;
        (x, (a_s - x * w_s) / w, (a_t - x * w_t) / w)
    }

    /// The largest absolute control-point coordinate.
    pub fn size(&self) -> f64 {
        self.points
            .iter()
            .flatten()
            .fold(0.0_f64, |m, p| m.max(p.coords.amax()))
    }
}

/// The Bernstein basis of degree `n` at `x` and its derivatives:
/// `Bᵢ = C(n, i)xⁱ(1 − x)ⁿ⁻ⁱ`, `Bᵢ' = n(Bᵢ₋₁ⁿ⁻¹ − Bᵢⁿ⁻¹)`.
fn basis(n: usize, x: f64) -> ([f64; MAX_DEGREE + 1], [f64; MAX_DEGREE + 1]) {
    assert!(n <= MAX_DEGREE, "degree {n} beyond the reference's");
    let direct = |m: usize, i: usize| -> f64 {
        binomial(m, i) * x.powi(i as i32) * (1.0 - x).powi((m - i) as i32)
    };
    let mut b = [0.0; MAX_DEGREE + 1];
    let mut d = [0.0; MAX_DEGREE + 1];
    for i in 0..=n {
        b[i] = direct(n, i);
        if n > 0 {
            let left = if i > 0 { direct(n - 1, i - 1) } else { 0.0 };
            let right = if i < n { direct(n - 1, i) } else { 0.0 };
            d[i] = n as f64 * (left - right);
        }
    }
    (b, d)
}

/// `C(n, k)`, exact for the degrees used here.
fn binomial(n: usize, k: usize) -> f64 {
    let mut c = 1.0;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c.round()
}

/// One root of the ray on a surface.
#[derive(Debug, Clone, Copy)]
pub struct RefHit {
    /// Ray parameter (units of `|d|`).
    pub t: f64,
    /// Surface parameters.
    pub u: f64,
    pub v: f64,
    /// The surface point.
    pub point: Point3<f64>,
    /// `|d̂·n̂|` (`n = S_u × S_v`), the Jacobian's determinant relative to its
    /// largest value: 0 at tangency (and at collapsed edges).
    pub cos: f64,
    /// Distance in local parameters from the patch's boundary (negative
    /// outside it).
    pub edge: f64,
}

/// All roots along the whole line, nearest first.
#[derive(Debug, Clone, Default)]
pub struct RefHits {
    pub hits: Vec<RefHit>,
    /// Some box could not be resolved (grazing ray, non-isolated root or
    /// the box budget spent): roots may be missing there.
    pub doubtful: bool,
    /// Boxes visited.
    pub boxes: usize,
}

impl RefHits {
    /// The roots with `t_min < t < t_max`.
    pub fn within(&self, t_min: f64, t_max: f64) -> Vec<RefHit> {
        self.hits
            .iter()
            .copied()
            .filter(|h| h.t > t_min && h.t < t_max)
            .collect()
    }

    /// Whether the roots in `(t_min, t_max)` can be compared with an
    /// intersector: the answer is not doubtful, every root there is
    /// transversal (`cos ≥ min_cos`) and clear of the patch boundaries by
    /// `1e-7`, roots are more than `gap` apart in `t` and none is within
    /// `gap` of the window's ends.
    pub fn clear(&self, t_min: f64, t_max: f64, min_cos: f64, gap: f64) -> bool {
        if self.doubtful {
            return false;
        }
        let near = |a: f64, b: f64| (a - b).abs() <= gap;
        let mut last = t_min;
        for h in &self.hits {
            if near(h.t, t_min) || near(h.t, t_max) {
                return false;
            }
            if h.t > t_min && h.t < t_max {
                if h.cos < min_cos || h.edge.abs() < 1e-7 || near(h.t, last) {
                    return false;
                }
                last = h.t;
            }
        }
        true
    }
}

/// The reference's roots of `ray` on the Bézier surface.
pub fn bezier_hits(s: &BezierSurface, ray: &Ray) -> RefHits {
    hits_on(&[RefPatch::polynomial(s.points().to_vec())], ray)
}

/// The reference's roots on a B-spline surface (its Bézier pieces, from
/// the library's `to_bezier_patches`, which `tests/tensor/tensor_surfaces.rs`
/// checks against an independent evaluator; the root finding here is the
/// reference's own).
pub fn bspline_hits(s: &BSplineSurface, ray: &Ray) -> RefHits {
    let patches: Vec<RefPatch> = s
        .to_bezier_patches()
        .into_iter()
        .map(|b| RefPatch {
            u: b.u,
            v: b.v,
            ..RefPatch::polynomial(b.surface.points().to_vec())
        })
        .collect();
    hits_on(&patches, ray)
}

/// The reference's roots on a NURBS surface (its rational Bézier pieces).
pub fn nurbs_hits(s: &NurbsSurface, ray: &Ray) -> RefHits {
    let patches: Vec<RefPatch> = s
        .to_bezier_patches()
        .into_iter()
        .map(|b| RefPatch {
            points: b.points,
            weights: b.weights,
            u: b.u,
            v: b.v,
        })
        .collect();
    hits_on(&patches, ray)
}

/// Every root of `ray` on the patches, merged and sorted by `t`.
pub fn hits_on(patches: &[RefPatch], ray: &Ray) -> RefHits {
    let size = patches
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.size()))
        .max(f64::MIN_POSITIVE);
    let dn = ray.dir.norm();
    let mut out = RefHits::default();
    let mut all = Vec::new();
    for patch in patches {
        let found = patch_hits(patch, ray);
        out.doubtful |= found.doubtful;
        out.boxes += found.boxes;
        all.extend(found.hits);
    }
    all.sort_by(|a, b| a.t.total_cmp(&b.t));
    // Merge roots closer than 1e-10·size along the ray (one root seen by
    // neighbouring leaves, patches or a collapsed edge), keeping the one
    // deepest inside its patch.
    let mut merged: Vec<RefHit> = Vec::new();
    for h in all {
        match merged.last_mut() {
            Some(last) if (h.t - last.t).abs() * dn <= 1e-10 * size => {
                if h.edge > last.edge {
                    *last = h;
                }
            }
            _ => merged.push(h),
        }
    }
    out.hits = merged;
    out
}

/// The two plane normals of the ray (unit, perpendicular to `d` and to each
/// other).
fn planes(d: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let dh = d.normalize();
    // The coordinate axis least aligned with d.
    let a = dh.abs();
    let helper = if a.x <= a.y && a.x <= a.z {
        Vector3::x()
    } else if a.y <= a.z {
        Vector3::y()
    } else {
        Vector3::z()
    };
    let e1 = helper.cross(&dh).normalize();
    let e2 = dh.cross(&e1).normalize();
    (dh, e1, e2)
}

/// The power-basis coefficients of `f = e·(A − W·o)` as intervals,
/// `m[a][b]` of `uᵃvᵇ`.
fn power_form(patch: &RefPatch, o: &Point3<f64>, e: &Vector3<f64>) -> Vec<Vec<Interval>> {
    let (p, q) = patch.degrees();
    // Bernstein coefficients e·w(P − o), enclosed.
    let mut c: Vec<Vec<Interval>> = (0..=p)
        .map(|i| {
            (0..=q)
                .map(|j| {
                    let w = Interval::point(patch.weights[i][j]);
                    let mut sum = Interval::ZERO;
                    for k in 0..3 {
                        let rel = Interval::point(patch.points[i][j][k]).sub(Interval::point(o[k]));
                        sum = sum.add(Interval::point(e[k]).mul(w.mul(rel)));
                    }
                    sum
                })
                .collect()
        })
        .collect();
    // Bernstein → power along u (each column), then along v (each row):
    // mₐ = Σᵢ≤ₐ bᵢ C(n, i) C(n − i, a − i) (−1)^(a − i).
    let convert = |b: &[Interval]| -> Vec<Interval> {
        let n = b.len() - 1;
        (0..=n)
            .map(|a| {
                let mut sum = Interval::ZERO;
                for (i, bi) in b.iter().enumerate().take(a + 1) {
                    let k = binomial(n, i) * binomial(n - i, a - i);
                    let k = if (a - i) % 2 == 1 { -k } else { k };
                    sum = sum.add(bi.mul(Interval::point(k)));
                }
                sum
            })
            .collect()
    };
    for j in 0..=q {
        let col: Vec<Interval> = c.iter().map(|row| row[j]).collect();
        for (row, x) in c.iter_mut().zip(convert(&col)) {
            row[j] = x;
        }
    }
    for row in c.iter_mut() {
        *row = convert(row);
    }
    c
}

/// The range of the power-form polynomial `m` over
/// `[u₀, u₀ + h] × [v₀, v₀ + k]`, enclosed: Taylor shift to the corner, then
/// `g₀₀ + Σ gₐᵦ·[0, hᵃkᵝ]`. `scratch` receives the shifted coefficients.
fn enclose(
    m: &[Vec<Interval>],
    u0: f64,
    v0: f64,
    h: f64,
    k: f64,
    scratch: &mut [[Interval; MAX_DEGREE + 1]; MAX_DEGREE + 1],
) -> Interval {
    let p = m.len() - 1;
    let q = m[0].len() - 1;
    for (row, src) in scratch.iter_mut().zip(m) {
        row[..=q].copy_from_slice(src);
    }
    let (x0, y0) = (Interval::point(u0), Interval::point(v0));
    // Shift in u: each column j, the polynomial Σₐ g[a][j] uᵃ.
    if u0 != 0.0 {
        #[allow(clippy::needless_range_loop)] // the shift runs down each column
        for j in 0..=q {
            for i in 0..p {
                for a in (i..p).rev() {
                    scratch[a][j] = scratch[a][j].add(x0.mul(scratch[a + 1][j]));
                }
            }
        }
    }
    if v0 != 0.0 {
        for row in scratch.iter_mut().take(p + 1) {
            for i in 0..q {
                for b in (i..q).rev() {
                    row[b] = row[b].add(y0.mul(row[b + 1]));
                }
            }
        }
    }
    let mut range = scratch[0][0];
    // hᵃ (upper end), then hᵃkᵇ.
    let mut hu = Interval::point(1.0);
    for (a, row) in scratch.iter().take(p + 1).enumerate() {
        let mut hv = hu;
        for (b, g) in row.iter().take(q + 1).enumerate() {
            if a + b > 0 {
                range = range.add(g.mul(Interval::new(0.0, hv.hi)));
            }
            hv = hv.mul(Interval::point(k));
        }
        hu = hu.mul(Interval::point(h));
    }
    range
}

/// A box of the search in local parameters.
#[derive(Debug, Clone, Copy)]
struct Cell {
    u0: f64,
    v0: f64,
    h: f64,
    k: f64,
}

/// Every root of the ray on one patch.
fn patch_hits(patch: &RefPatch, ray: &Ray) -> RefHits {
    let (dh, e1, e2) = planes(&ray.dir);
    let o = ray.origin;
    let m1 = power_form(patch, &o, &e1);
    let m2 = power_form(patch, &o, &e2);
    let size = patch.size().max(o.coords.amax()).max(f64::MIN_POSITIVE);
    let mut scratch = [[Interval::ZERO; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    let mut out = RefHits::default();
    let mut roots: Vec<(f64, f64)> = Vec::new();
    let mut stack = vec![Cell {
        u0: -ETA,
        v0: -ETA,
        h: 1.0 + 2.0 * ETA,
        k: 1.0 + 2.0 * ETA,
    }];
    while let Some(c) = stack.pop() {
        out.boxes += 1;
        if out.boxes > MAX_BOXES {
            out.doubtful = true;
            break;
        }
        if !enclose(&m1, c.u0, c.v0, c.h, c.k, &mut scratch).contains_zero()
            || !enclose(&m2, c.u0, c.v0, c.h, c.k, &mut scratch).contains_zero()
        {
            continue;
        }
        if c.h <= LEAF && c.k <= LEAF {
            if let Some((s, t)) = newton(patch, &o, &e1, &e2, c, size) {
                let (mu, mv) = (0.1 * c.h, 0.1 * c.k);
                let inside = s >= c.u0 - mu
                    && s <= c.u0 + c.h + mu
                    && t >= c.v0 - mv
                    && t <= c.v0 + c.k + mv;
                if !roots
                    .iter()
                    .any(|r| (r.0 - s).abs() <= 1e-12 && (r.1 - t).abs() <= 1e-12)
                {
                    roots.push((s, t));
                }
                if inside {
                    continue;
                }
            }
            if c.h <= FLOOR && c.k <= FLOOR {
                // Unresolved at the floor: unless a root found lies right
                // here, roots may be missed.
                let close = roots.iter().any(|r| {
                    (r.0 - (c.u0 + 0.5 * c.h)).abs() <= 4.0 * LEAF
                        && (r.1 - (c.v0 + 0.5 * c.k)).abs() <= 4.0 * LEAF
                });
                out.doubtful |= !close;
                continue;
            }
        }
        // Halve the wider side.
        if c.h >= c.k {
            let h = 0.5 * c.h;
            stack.push(Cell { h, ..c });
            stack.push(Cell {
                u0: c.u0 + h,
                h,
                ..c
            });
        } else {
            let k = 0.5 * c.k;
            stack.push(Cell { k, ..c });
            stack.push(Cell {
                v0: c.v0 + k,
                k,
                ..c
            });
        }
    }
    let dn = ray.dir.norm();
    out.hits = roots
        .into_iter()
        .filter(|&(s, t)| (-ETA..=1.0 + ETA).contains(&s) && (-ETA..=1.0 + ETA).contains(&t))
        .map(|(s, t)| {
            let (x, xs, xt) = patch.jet(s, t);
            let n = xs.cross(&xt);
            let cos = if n.norm() > 0.0 {
                n.normalize().dot(&dh).abs()
            } else {
                0.0
            };
            RefHit {
                t: dh.dot(&(x - o.coords)) / dn,
                u: patch.u.0 + (patch.u.1 - patch.u.0) * s,
                v: patch.v.0 + (patch.v.1 - patch.v.0) * t,
                point: Point3::from(x),
                cos,
                edge: s.min(t).min(1.0 - s).min(1.0 - t),
            }
        })
        .collect();
    out
}

/// Newton's method on `(e₁·(S − o), e₂·(S − o))` from the centre of `c`:
/// the local parameters of a root (residual within `1e-11·size`), or `None`.
fn newton(
    patch: &RefPatch,
    o: &Point3<f64>,
    e1: &Vector3<f64>,
    e2: &Vector3<f64>,
    c: Cell,
    size: f64,
) -> Option<(f64, f64)> {
    let (mut s, mut t) = (c.u0 + 0.5 * c.h, c.v0 + 0.5 * c.k);
    let mut residual = f64::INFINITY;
    for _ in 0..60 {
        let (x, xs, xt) = patch.jet(s, t);
        let r = x - o.coords;
        let (fa, fb) = (e1.dot(&r), e2.dot(&r));
        residual = fa.hypot(fb);
        if residual <= 1e-15 * size {
            break;
        }
        let (j00, j01, j10, j11) = (e1.dot(&xs), e1.dot(&xt), e2.dot(&xs), e2.dot(&xt));
        let det = j00 * j11 - j01 * j10;
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let ds = (fa * j11 - fb * j01) / det;
        let dt = (fb * j00 - fa * j10) / det;
        s -= ds;
        t -= dt;
        if !(s.is_finite() && t.is_finite()) || s.abs() > 3.0 || t.abs() > 3.0 {
            return None;
        }
        if ds.abs() <= 1e-16 && dt.abs() <= 1e-16 {
            let (x, _, _) = patch.jet(s, t);
            let r = x - o.coords;
            residual = e1.dot(&r).hypot(e2.dot(&r));
            break;
        }
    }
    (residual <= 1e-11 * size).then_some((s, t))
}

/// Every hit of an intersector in `(t_min, t_max)`, nearest first: the
/// nearest, then the nearest beyond it (`t_min` = the previous hit's `t`),
/// and so on; at most `cap` (a secondary ray that re-finds its own start
/// would loop).
pub fn walk_hits<S: Intersect>(s: &S, ray: &Ray, t_min: f64, t_max: f64, cap: usize) -> Vec<Hit> {
    let mut out: Vec<Hit> = Vec::new();
    let mut from = t_min;
    while out.len() < cap {
        match s.intersect(ray, from, t_max) {
            Some(h) => {
                from = h.t;
                out.push(h);
            }
            None => break,
        }
    }
    out
}

/// [`check_hit`](super::check_hit) at the scale of the surface and the
/// ray's origin (the intersector's own scale of acceptance).
pub fn check_patch_hit<S: Surface + Intersect>(s: &S, ray: &Ray, h: &Hit, t_min: f64, t_max: f64) {
    let scale = s.bounds().scale().max(ray.origin.coords.amax());
    super::check_hit(s, ray, h, t_min, t_max, scale);
}

/// A ray from a random point at distance `4·size` toward a random point of
/// the box `[lo, hi]³`, its length scaled by a random factor.
pub fn random_ray(rng: &mut Rng, size: f64, lo: f64, hi: f64) -> Ray {
    let origin = Point3::from(rng.direction() * 4.0 * size);
    let target = rng.point([lo; 3], [hi; 3]);
    Ray::new(origin, (target - origin) * rng.range(0.3, 3.0))
}

/// Random bicubic control nets of three kinds, all folded so that rays meet
/// them several times: `0` every point uniform in `[−1, 1]³`; `1` a height
/// field over `[−1, 1]²` with heights in `[−1.5, 1.5]`; `2` an S-fold (the
/// rows' `x` runs −1, 1, −1, 1 plus noise, so lines along `x` cross it up to
/// three times).
pub fn folded_net(rng: &mut Rng, kind: usize) -> Vec<Vec<Point3<f64>>> {
    (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (a, b) = (i as f64 / 3.0 * 2.0 - 1.0, j as f64 / 3.0 * 2.0 - 1.0);
                    match kind {
                        0 => rng.point([-1.0; 3], [1.0; 3]),
                        1 => Point3::new(a, b, rng.range(-1.5, 1.5)),
                        _ => {
                            let x = if i % 2 == 0 { -1.0 } else { 1.0 };
                            Point3::new(
                                x + rng.range(-0.2, 0.2),
                                b + rng.range(-0.2, 0.2),
                                a + rng.range(-0.3, 0.3),
                            )
                        }
                    }
                })
                .collect()
        })
        .collect()
}

/// Tallies of a comparison run.
#[derive(Debug, Default)]
pub struct Tally {
    pub rays: usize,
    pub excluded: usize,
    /// Rays by their number of hits (4 = four or more).
    pub by_count: [usize; 5],
}

/// Compares the intersector with the reference on one ray: unless the
/// reference flags the ray (doubtful, a root within `1e-4` of tangency or
/// `1e-7` of a patch edge, two roots within `1e-7·size`), `intersect_all`
/// finds exactly the reference's roots in `(0, ∞)`, in order,
/// `t` within `1e-9·size/|d|` and `(u, v)` within `1e-6`.
pub fn compare<S: Surface + Intersect>(
    s: &S,
    want: &RefHits,
    ray: &Ray,
    size: f64,
    tally: &mut Tally,
) {
    tally.rays += 1;
    let dn = ray.dir.norm();
    if !want.clear(0.0, f64::INFINITY, 1e-4, 1e-7 * size / dn) {
        tally.excluded += 1;
        return;
    }
    let want = want.within(0.0, f64::INFINITY);
    let mut got = Vec::new();
    s.intersect_all(ray, 0.0, f64::INFINITY, &mut got);
    assert_eq!(
        got.first().copied(),
        s.intersect(ray, 0.0, f64::INFINITY),
        "intersect_all's first hit is not intersect's for {ray:?}"
    );
    assert_eq!(s.occluded(ray, 0.0, f64::INFINITY), !got.is_empty());
    let ts = |v: Vec<f64>| format!("{v:?}");
    assert_eq!(
        got.len(),
        want.len(),
        "hits at t = {} but the reference has {} for {ray:?}",
        ts(got.iter().map(|h| h.t).collect()),
        ts(want.iter().map(|h| h.t).collect()),
    );
    for (g, w) in got.iter().zip(&want) {
        check_patch_hit(s, ray, g, 0.0, f64::INFINITY);
        assert!(
            (g.t - w.t).abs() * dn <= 1e-9 * size,
            "t {} vs reference {} for {ray:?}",
            g.t,
            w.t
        );
        assert!(
            (g.uv.0 - w.u).abs() <= 1e-6 && (g.uv.1 - w.v).abs() <= 1e-6,
            "uv {:?} vs reference ({}, {}) for {ray:?}",
            g.uv,
            w.u,
            w.v
        );
    }
    tally.by_count[want.len().min(4)] += 1;
}

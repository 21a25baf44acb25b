//! The certified search for the common points of a rational Bézier curve
//! piece and another rational Bézier piece one dimension lower than the
//! space (a curve in the plane, a patch in space): subdivision with
//! separating-direction tests, Krawczyk's uniqueness test, Newton's polish.
//!
//! # The system
//! The curve piece is `A(s) = X(s)/W(s)` (homogeneous numerator `X`, weight
//! `W > 0`, degree `n`), the other piece `B(y) = Y(y)/V(y)` with
//! `y ∈ [0, 1]^{D−1}` (degrees `d₁ … d_{D−1}`). Their common points are the
//! roots of `F(s, y) = A(s) − B(y)`, `D` equations in `D` unknowns, and,
//! the weights being positive, exactly the roots of the polynomial
//!
//! ```text
//! G(s, y) = X(s)·V(y) − Y(y)·W(s),   gᵢⱼ = Xᵢ·Vⱼ − Yⱼ·Wᵢ
//! ```
//!
//! whose tensor-product Bernstein coefficients on any box are the products
//! of the two pieces' homogeneous control points restricted to that box
//! (a product of polynomials in separate variables).
//!
//! # The search
//! Boxes `[s₀, s₁] × [y₀, y₁]` are examined from a stack, starting with
//! `[0, 1]^D`:
//! 1. **Exclusion.** Both pieces are restricted to the box (de Casteljau);
//!    by the convex hull property each lies in the hull of its projected
//!    control points. If, along one of a few directions (the axes, the
//!    normal of the curve piece's chord in the plane, the normal of the
//!    other piece's chord or of its diagonals), the two sets of projections
//!    are separated by more than their rounding bounds, the box holds no
//!    root.
//! 2. **Uniqueness.** Krawczyk's operator `K = c − Y·G(c) + (I − Y·J)(E − c)`
//!    is formed for the box `E` widened by an eighth of its width on every
//!    side (so that a root on a side of the box, at a span join or at a
//!    subdivision point, lies inside it), with `J` the interval hull of the
//!    derivative nets of `G` and every coefficient widened by its rounding
//!    bound. If `K` lies strictly inside `E`, `E` holds exactly one root of
//!    `G` (Krawczyk 1969; Moore, Kearfott & Cloud, *Introduction to Interval
//!    Analysis*, §8.2), and it lies in `K`: the box is done, and the root is
//!    polished by Newton's method on `F` inside `K`.
//! 3. **Subdivision.** Otherwise each piece whose control points span more
//!    than the tolerance is halved in every parameter (at most
//!    [`MAX_DEPTH`] times), and the children are pushed. A box whose pieces
//!    are both within the tolerance (or at the depth cap) is a *leaf*: the
//!    two pieces come within about the tolerance of each other without a
//!    proven single crossing (a tangency, a near miss, an overlap).
//!
//! Leaves that touch form clusters; each cluster is one uncertified
//! result, at its leaf whose pieces' centres are nearest. More than
//! [`MAX_LEAVES`] leaves or [`MAX_BOXES`] boxes for one pair of pieces is
//! an overlap: the pieces run within the tolerance of each other along a
//! stretch (the hull of the leaves found is reported). A caller may give
//! a smaller budget of boxes, past which the search stops unfinished (the
//! planar search then tries a direct proof that the pieces are one arc).
//!
//! # Rounding
//! The control points are scaled by a power of two (exact) so that the
//! largest coordinate is near one, the weights so that the largest is near
//! one. A restriction to `[a, b]` (two de Casteljau subdivisions, possibly
//! extrapolating for the widened boxes) errs by at most
//! `(1 + 8·Σ(dₖ + 1))·ε·M·Λ`, with `M` the largest coefficient of the piece
//! and `Λ = Π(|1 − t| + |t|)^d` over the subdivision parameters `t` (one for
//! parameters in `[0, 1]`). Projected points carry that error divided by
//! the least weight, plus the division's rounding and a margin for the
//! rounded ratio `a/b` of the second subdivision (the piece then covers its
//! interval up to `ε` relative: the margin is `ε` times a bound on the
//! derivative). The coefficients of `G` carry the products' error terms.
//! All of these only widen the tests, so no root is excluded by rounding.

use super::Homogeneous;
use crate::bernstein::subdivide;
use nalgebra::SVector;

/// Deepest subdivision of a piece: parameter intervals of width `2⁻⁴⁸`
/// (relative to the span or patch) are not split.
pub(crate) const MAX_DEPTH: u32 = 48;

/// Most boxes examined for one pair of pieces; more is reported as an
/// overlap.
pub(crate) const MAX_BOXES: usize = 1 << 18;

/// Most leaves (boxes whose pieces are both within the tolerance, without
/// a certified root) for one pair of pieces; more is reported as an
/// overlap.
pub(crate) const MAX_LEAVES: usize = 1 << 13;

/// Most coefficients of the system `G` (the product of the pieces' control
/// net sizes): beyond it the search is refused.
pub(crate) const MAX_SYSTEM: usize = 1 << 14;

/// How far Krawczyk's enclosure must stay inside the widened box (in its
/// own parameters).
const MARGIN: f64 = 1e-9;

/// Newton steps of the polish at most.
const POLISH_STEPS: usize = 24;

/// A rational Bézier piece with `axes` parameters (1: a curve, 2: a patch):
/// homogeneous control points, flat with the first parameter slowest.
#[derive(Debug, Clone)]
pub(crate) struct Net<const D: usize> {
    /// `(w·P, w)`, scaled (see the module docs).
    pub(crate) coefs: Vec<Homogeneous<D>>,
    /// The degree in each parameter.
    pub(crate) degrees: Vec<usize>,
}

impl<const D: usize> Net<D> {
    /// The largest absolute `wP` coordinate and the largest weight.
    fn magnitudes(&self) -> (f64, f64) {
        self.coefs.iter().fold((0.0_f64, 0.0_f64), |(x, w), h| {
            (x.max(h.wp.amax()), w.max(h.w.abs()))
        })
    }

    /// The coefficients restricted to `bx` (one interval per parameter, any
    /// `a < b`, extrapolating outside `[0, 1]`), with the amplification `Λ`.
    fn restricted(&self, bx: &[(f64, f64)]) -> (Vec<Homogeneous<D>>, f64) {
        let mut c = self.coefs.clone();
        let mut amplification = 1.0;
        let total = c.len();
        for (axis, &(a, b)) in bx.iter().enumerate() {
            let d = self.degrees[axis];
            if d == 0 {
                continue;
            }
            let stride: usize = self.degrees[axis + 1..].iter().map(|d| d + 1).product();
            let outer = total / ((d + 1) * stride);
            let mut line = vec![Homogeneous::zero(); d + 1];
            let mut left = line.clone();
            let mut right = line.clone();
            let mut lambda = 1.0;
            for o in 0..outer {
                for r in 0..stride {
                    let base = o * (d + 1) * stride + r;
                    for (k, x) in line.iter_mut().enumerate() {
                        *x = c[base + k * stride];
                    }
                    lambda = restrict_line(&mut line, a, b, &mut left, &mut right);
                    for (k, x) in line.iter().enumerate() {
                        c[base + k * stride] = *x;
                    }
                }
            }
            amplification *= lambda;
        }
        (c, amplification)
    }

    /// The projected point and its first partial derivatives at `x` (one
    /// entry per parameter; one or two parameters), by de Casteljau and the
    /// quotient rule. `None` for a weight that is not positive.
    pub(crate) fn jet(&self, x: &[f64]) -> Option<(SVector<f64, D>, Vec<SVector<f64, D>>)> {
        let (h, dh) = match self.degrees.len() {
            1 => {
                let (h, d) = eval_derivative(&self.coefs, x[0]);
                (h, vec![d])
            }
            2 => {
                let cols = self.degrees[1] + 1;
                let rows = self.degrees[0] + 1;
                let mut values = Vec::with_capacity(rows);
                let mut slopes = Vec::with_capacity(rows);
                for i in 0..rows {
                    let (h, d) = eval_derivative(&self.coefs[i * cols..(i + 1) * cols], x[1]);
                    values.push(h);
                    slopes.push(d);
                }
                let (h, du) = eval_derivative(&values, x[0]);
                let (dv, _) = eval_derivative(&slopes, x[0]);
                (h, vec![du, dv])
            }
            _ => return None,
        };
        if h.w.is_nan() || h.w <= 0.0 {
            return None;
        }
        let p = h.wp / h.w;
        let partials = dh.iter().map(|d| (d.wp - p * d.w) / h.w).collect();
        Some((p, partials))
    }
}

/// The value and the derivative at `t` of the Bernstein polynomial `c`
/// (de Casteljau; zero derivative for degree 0).
fn eval_derivative<const D: usize>(
    c: &[Homogeneous<D>],
    t: f64,
) -> (Homogeneous<D>, Homogeneous<D>) {
    let mut w = c.to_vec();
    let n = w.len() - 1;
    if n == 0 {
        return (w[0], Homogeneous::zero());
    }
    for level in 1..n {
        for j in 0..=(n - level) {
            w[j] = w[j] * (1.0 - t) + w[j + 1] * t;
        }
    }
    let value = w[0] * (1.0 - t) + w[1] * t;
    (value, (w[1] - w[0]) * n as f64)
}

/// `|1 − t| + |t|`: how much one de Casteljau step at `t` can grow values.
fn growth(t: f64) -> f64 {
    (1.0 - t).abs() + t.abs()
}

/// Restricts the Bernstein coefficients `c` on `[0, 1]` to `[a, b]`
/// (`a < b`, `b > 0`), returning the amplification `Λ`.
fn restrict_line<const D: usize>(
    c: &mut [Homogeneous<D>],
    a: f64,
    b: f64,
    left: &mut [Homogeneous<D>],
    right: &mut [Homogeneous<D>],
) -> f64 {
    let n = c.len() as i32 - 1;
    let mut lambda = 1.0;
    if b != 1.0 {
        subdivide(c, b, left, right);
        c.copy_from_slice(left);
        lambda *= growth(b).powi(n);
    }
    if a != 0.0 {
        let t = a / b;
        subdivide(c, t, left, right);
        c.copy_from_slice(right);
        lambda *= growth(t).powi(n);
    }
    lambda
}

/// A restricted piece: projected control points, their rounding bound,
/// the homogeneous coefficients and their error bounds.
struct Piece<const D: usize> {
    coefs: Vec<Homogeneous<D>>,
    points: Vec<SVector<f64, D>>,
    /// Bound on the error of each projected point (max norm); infinite
    /// where a weight could not be bounded away from zero.
    pad: f64,
    /// Bounds on the errors of the `wP` coordinates and of the weights.
    err: (f64, f64),
    /// Largest absolute `wP` coordinate and weight.
    max: (f64, f64),
}

impl<const D: usize> Piece<D> {
    fn new(net: &Net<D>, bx: &[(f64, f64)], magnitudes: (f64, f64)) -> Self {
        let (coefs, lambda) = net.restricted(bx);
        let sum: usize = net.degrees.iter().map(|d| d + 1).sum();
        let factor = (1.0 + 8.0 * sum as f64) * f64::EPSILON * lambda;
        let err = (factor * magnitudes.0, factor * magnitudes.1);
        let mut w_min = f64::INFINITY;
        let mut max = (0.0_f64, 0.0_f64);
        let mut p_max = 0.0_f64;
        let points: Vec<SVector<f64, D>> = coefs
            .iter()
            .map(|h| {
                w_min = w_min.min(h.w);
                max = (max.0.max(h.wp.amax()), max.1.max(h.w.abs()));
                let p = h.wp / h.w;
                p_max = p_max.max(p.amax());
                p
            })
            .collect();
        let w_low = w_min - err.1;
        let degree_sum: usize = net.degrees.iter().sum();
        let pad = if w_low > 0.0 && p_max.is_finite() {
            (err.0 + p_max * err.1) / w_low
                + 4.0 * f64::EPSILON * p_max
                + 8.0 * f64::EPSILON * degree_sum as f64 * magnitudes.0 * lambda / w_low
        } else {
            f64::INFINITY
        };
        Piece {
            coefs,
            points,
            pad,
            err,
            max,
        }
    }

    /// The largest extent of the projected control points' box (plus pad).
    fn diameter(&self) -> f64 {
        let (lo, hi) = bounds(&self.points);
        (hi - lo).amax() + 2.0 * self.pad
    }
}

/// The box of `points` (non-empty).
fn bounds<const D: usize>(points: &[SVector<f64, D>]) -> (SVector<f64, D>, SVector<f64, D>) {
    points
        .iter()
        .fold((points[0], points[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)))
}

/// A normal of the piece: for a curve in the plane the normal of its chord,
/// for a patch in space the cross product of its diagonals; `None` in
/// other cases or where it vanishes.
fn normal<const D: usize>(
    points: &[SVector<f64, D>],
    degrees: &[usize],
) -> Option<SVector<f64, D>> {
    let last = points.len() - 1;
    let n = match (D, degrees.len()) {
        (2, 1) => {
            let c = points[last] - points[0];
            let mut n = SVector::<f64, D>::zeros();
            n[0] = -c[1];
            n[1] = c[0];
            n
        }
        (3, 1) => return None,
        (3, 2) => {
            let cols = degrees[1] + 1;
            let d1 = points[last] - points[0];
            let d2 = points[cols - 1] - points[last + 1 - cols];
            let mut n = SVector::<f64, D>::zeros();
            n[0] = d1[1] * d2[2] - d1[2] * d2[1];
            n[1] = d1[2] * d2[0] - d1[0] * d2[2];
            n[2] = d1[0] * d2[1] - d1[1] * d2[0];
            n
        }
        _ => return None,
    };
    let m = n.amax();
    (m > 0.0 && m.is_finite()).then(|| n / m)
}

/// Whether the projections of the two pieces' points on `dir` are
/// certainly apart.
fn separated_along<const D: usize>(a: &Piece<D>, b: &Piece<D>, dir: &SVector<f64, D>) -> bool {
    let range = |p: &Piece<D>| {
        p.points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                let v = dir.dot(x);
                (lo.min(v), hi.max(v))
            })
    };
    let (a_lo, a_hi) = range(a);
    let (b_lo, b_hi) = range(b);
    let norm1 = dir.abs().sum();
    let size = a_lo.abs().max(a_hi.abs()).max(b_lo.abs()).max(b_hi.abs());
    let rounding = 2.0 * (D as f64 + 1.0) * f64::EPSILON * size;
    let pad = (a.pad + b.pad) * norm1 + 2.0 * rounding;
    a_hi + pad < b_lo || b_hi + pad < a_lo
}

/// A root found in local parameters (the curve's `s`, then the other
/// piece's), each in `[0, 1]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LocalRoot<const D: usize> {
    pub(crate) x: [f64; D],
    pub(crate) certified: bool,
    /// For an uncertified root, the hull of its cluster of leaves (where
    /// the pieces come within the tolerance); `x` itself for a certified one.
    pub(crate) hull: [(f64, f64); D],
}

/// What the search of one pair of pieces found.
pub(crate) enum PairOutcome<const D: usize> {
    /// Every root: certified ones and one per cluster of leaves.
    Roots(Vec<LocalRoot<D>>),
    /// The pieces run together: the hull (local parameters) of the leaves
    /// found before the caps were reached.
    Overlap([(f64, f64); D]),
    /// The search examined more boxes than its budget (below the caps).
    Unfinished,
}

/// A box waiting to be examined, with the depth of each piece.
#[derive(Clone, Copy)]
struct Item<const D: usize> {
    bx: [(f64, f64); D],
    depth: (u32, u32),
}

/// Every common point of the curve piece `a` (one parameter) and the piece
/// `b` (`D − 1` parameters), both scaled as the module docs say;
/// `tolerance` in the scaled units. Past `budget` boxes (at most
/// [`MAX_BOXES`]) the search stops [unfinished](PairOutcome::Unfinished).
pub(crate) fn search_pair<const D: usize>(
    a: &Net<D>,
    b: &Net<D>,
    tolerance: f64,
    budget: usize,
) -> PairOutcome<D> {
    let (ma, mb) = (a.magnitudes(), b.magnitudes());
    let mut stack = vec![Item {
        bx: [(0.0, 1.0); D],
        depth: (0, 0),
    }];
    let mut roots = Vec::new();
    let mut leaves: Vec<[(f64, f64); D]> = Vec::new();
    let mut boxes = 0usize;
    while let Some(item) = stack.pop() {
        boxes += 1;
        if boxes > MAX_BOXES || leaves.len() > MAX_LEAVES {
            leaves.push(item.bx);
            return PairOutcome::Overlap(hull(&leaves));
        }
        if boxes > budget {
            return PairOutcome::Unfinished;
        }
        let pa = Piece::new(a, &item.bx[..1], ma);
        let pb = Piece::new(b, &item.bx[1..], mb);
        if excluded(&pa, &pb, &b.degrees) {
            continue;
        }
        if let Some(found) = certify(a, b, &item.bx, ma, mb) {
            roots.extend(found);
            continue;
        }
        let split_a = pa.diameter() > tolerance && item.depth.0 < MAX_DEPTH && a.degrees[0] > 0;
        let split_b = pb.diameter() > tolerance && item.depth.1 < MAX_DEPTH;
        if !split_a && !split_b {
            leaves.push(item.bx);
            continue;
        }
        let halves = |(lo, hi): (f64, f64), split: bool| {
            let mid = 0.5 * (lo + hi);
            if split {
                [(lo, mid), (mid, hi)]
            } else {
                [(lo, hi), (f64::NAN, f64::NAN)]
            }
        };
        let count = 1usize << (D - 1);
        for ha in halves(item.bx[0], split_a) {
            if ha.0.is_nan() {
                continue;
            }
            for mask in 0..count {
                if !split_b && mask > 0 {
                    continue;
                }
                let mut bx = item.bx;
                bx[0] = ha;
                for k in 1..D {
                    let h = halves(item.bx[k], split_b);
                    bx[k] = h[(mask >> (k - 1)) & 1];
                }
                stack.push(Item {
                    bx,
                    depth: (
                        item.depth.0 + u32::from(split_a),
                        item.depth.1 + u32::from(split_b),
                    ),
                });
            }
        }
    }
    for cluster in clusters(&leaves) {
        roots.push(representative(a, b, &cluster));
    }
    PairOutcome::Roots(roots)
}

/// Whether a separating direction proves the box holds no root.
fn excluded<const D: usize>(pa: &Piece<D>, pb: &Piece<D>, b_degrees: &[usize]) -> bool {
    if !(pa.pad.is_finite() && pb.pad.is_finite()) {
        return false;
    }
    for k in 0..D {
        let mut e = SVector::<f64, D>::zeros();
        e[k] = 1.0;
        if separated_along(pa, pb, &e) {
            return true;
        }
    }
    [
        normal(&pa.points, &[pa.points.len() - 1]),
        normal(&pb.points, b_degrees),
    ]
    .iter()
    .flatten()
    .any(|n| separated_along(pa, pb, n))
}

/// The hull of boxes (non-empty).
fn hull<const D: usize>(boxes: &[[(f64, f64); D]]) -> [(f64, f64); D] {
    let mut h = [(f64::INFINITY, f64::NEG_INFINITY); D];
    for bx in boxes {
        for k in 0..D {
            h[k] = (h[k].0.min(bx[k].0), h[k].1.max(bx[k].1));
        }
    }
    h
}

/// The leaves grouped into clusters of boxes that touch (closed boxes
/// sharing a point), by union–find.
fn clusters<const D: usize>(leaves: &[[(f64, f64); D]]) -> Vec<Vec<[(f64, f64); D]>> {
    let mut parent: Vec<usize> = (0..leaves.len()).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in 0..leaves.len() {
        for j in 0..i {
            let touch = (0..D)
                .all(|k| leaves[i][k].0 <= leaves[j][k].1 && leaves[j][k].0 <= leaves[i][k].1);
            if touch {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    type Group<const D: usize> = (usize, Vec<[(f64, f64); D]>);
    let mut groups: Vec<Group<D>> = Vec::new();
    for (i, leaf) in leaves.iter().enumerate() {
        let r = find(&mut parent, i);
        match groups.iter_mut().find(|(root, _)| *root == r) {
            Some((_, g)) => g.push(*leaf),
            None => groups.push((r, vec![*leaf])),
        }
    }
    groups.into_iter().map(|(_, g)| g).collect()
}

/// One uncertified root for a cluster of leaves: the centre of the leaf
/// whose pieces' points there are nearest.
fn representative<const D: usize>(
    a: &Net<D>,
    b: &Net<D>,
    cluster: &[[(f64, f64); D]],
) -> LocalRoot<D> {
    let centre =
        |bx: &[(f64, f64); D]| -> [f64; D] { std::array::from_fn(|k| 0.5 * (bx[k].0 + bx[k].1)) };
    let mut best = (f64::INFINITY, centre(&cluster[0]));
    for bx in cluster {
        let x = centre(bx);
        let gap = residual(a, b, &x).map_or(f64::INFINITY, |r| r.0.norm());
        if gap < best.0 {
            best = (gap, x);
        }
    }
    LocalRoot {
        x: best.1,
        certified: false,
        hull: hull(cluster),
    }
}

/// `F(x) = A(s) − B(y)` and its Jacobian's columns.
fn residual<const D: usize>(
    a: &Net<D>,
    b: &Net<D>,
    x: &[f64; D],
) -> Option<(SVector<f64, D>, [SVector<f64, D>; D])> {
    let (pa, da) = a.jet(&x[..1])?;
    let (pb, db) = b.jet(&x[1..])?;
    let mut jac = [SVector::<f64, D>::zeros(); D];
    jac[0] = da[0];
    for k in 1..D {
        jac[k] = -db[k - 1];
    }
    Some((pa - pb, jac))
}

/// Solves `Σₖ cols[k]·xₖ = rhs` by Gaussian elimination with partial
/// pivoting; `None` for a singular (or non-finite) matrix.
#[allow(clippy::needless_range_loop)]
fn solve<const D: usize>(cols: &[SVector<f64, D>; D], rhs: SVector<f64, D>) -> Option<[f64; D]> {
    let mut m = [[0.0_f64; D]; D];
    let mut r = [0.0_f64; D];
    for i in 0..D {
        for k in 0..D {
            m[i][k] = cols[k][i];
        }
        r[i] = rhs[i];
    }
    for c in 0..D {
        let p = (c..D).max_by(|&i, &j| m[i][c].abs().total_cmp(&m[j][c].abs()))?;
        if !(m[p][c] != 0.0 && m[p][c].is_finite()) {
            return None;
        }
        m.swap(c, p);
        r.swap(c, p);
        for i in c + 1..D {
            let f = m[i][c] / m[c][c];
            for k in c..D {
                m[i][k] -= f * m[c][k];
            }
            r[i] -= f * r[c];
        }
    }
    let mut x = [0.0_f64; D];
    for c in (0..D).rev() {
        let mut s = r[c];
        for k in c + 1..D {
            s -= m[c][k] * x[k];
        }
        x[c] = s / m[c][c];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The inverse of the `D × D` matrix `m` (rows), `None` if singular.
fn inverse<const D: usize>(m: &[[f64; D]; D]) -> Option<[[f64; D]; D]> {
    let mut inv = [[0.0_f64; D]; D];
    let cols: [SVector<f64, D>; D] = std::array::from_fn(|k| SVector::from_fn(|i, _| m[i][k]));
    for j in 0..D {
        let mut e = SVector::<f64, D>::zeros();
        e[j] = 1.0;
        let x = solve(&cols, e)?;
        for i in 0..D {
            inv[i][j] = x[i];
        }
    }
    Some(inv)
}

/// Krawczyk's test on the box `bx` widened by an eighth on every side:
/// `None` when it fails; for a certified box the polished root, or
/// `Some(None)` when the widened box's one root lies outside `[0, 1]^D`
/// by more than rounding (the box then holds none).
fn certify<const D: usize>(
    a: &Net<D>,
    b: &Net<D>,
    bx: &[(f64, f64); D],
    ma: (f64, f64),
    mb: (f64, f64),
) -> Option<Option<LocalRoot<D>>> {
    let wide: [(f64, f64); D] = std::array::from_fn(|k| {
        let (lo, hi) = bx[k];
        let w = 0.125 * (hi - lo);
        (lo - w, hi + w)
    });
    let pa = Piece::new(a, &wide[..1], ma);
    let pb = Piece::new(b, &wide[1..], mb);
    let mut degrees = [0usize; D];
    degrees[0] = a.degrees[0];
    degrees[1..].copy_from_slice(&b.degrees);
    if degrees.contains(&0) {
        return None;
    }
    // G's coefficients and their error bound.
    let m = pb.coefs.len();
    let mut g = Vec::with_capacity(pa.coefs.len() * m);
    for ha in &pa.coefs {
        for hb in &pb.coefs {
            g.push(ha.wp * hb.w - hb.wp * ha.w);
        }
    }
    let err = pa.err.0 * (pb.max.1 + pb.err.1)
        + (pa.max.0 + pa.err.0) * pb.err.1
        + pb.err.0 * (pa.max.1 + pa.err.1)
        + (pb.max.0 + pb.err.0) * pa.err.1
        + 3.0 * f64::EPSILON * (pa.max.0 * pb.max.1 + pb.max.0 * pa.max.1);
    let enclosure = krawczyk(&g, &degrees, err)?;
    // The enclosure in the span's parameters.
    let k: [(f64, f64); D] = std::array::from_fn(|i| {
        let (lo, hi) = wide[i];
        (
            lo + (hi - lo) * enclosure[i].0,
            lo + (hi - lo) * enclosure[i].1,
        )
    });
    let x = polish(a, b, &k, &wide);
    let slack = 1e-12;
    let inside = |v: f64| (-slack..=1.0 + slack).contains(&v);
    if !x.iter().all(|&v| inside(v)) {
        // The one root of the widened box lies in `K`: if `K` misses the
        // pieces' parameters the box holds none (the root belongs to a
        // neighbouring span, or to none); else the polish did not settle
        // where it is, and smaller boxes decide.
        let misses = k.iter().any(|&(lo, hi)| hi < -slack || lo > 1.0 + slack);
        return misses.then_some(None);
    }
    let x = x.map(|v| v.clamp(0.0, 1.0));
    Some(Some(LocalRoot {
        x,
        certified: true,
        hull: x.map(|v| (v, v)),
    }))
}

/// Newton's method on `F` from the middle of the enclosure `k`, kept in the
/// widened box; the result if it stays in `k` (which holds the root), else
/// the middle of `k`.
fn polish<const D: usize>(
    a: &Net<D>,
    b: &Net<D>,
    k: &[(f64, f64); D],
    wide: &[(f64, f64); D],
) -> [f64; D] {
    let middle: [f64; D] = std::array::from_fn(|i| 0.5 * (k[i].0 + k[i].1));
    let mut x = middle;
    let mut last = f64::INFINITY;
    for _ in 0..POLISH_STEPS {
        let Some((f, jac)) = residual(a, b, &x) else {
            break;
        };
        let Some(step) = solve(&jac, -f) else {
            break;
        };
        let size = step.iter().fold(0.0_f64, |m, s| m.max(s.abs()));
        if size.is_nan() || size >= last {
            break;
        }
        for i in 0..D {
            x[i] = (x[i] + step[i]).clamp(wide[i].0, wide[i].1);
        }
        last = size;
        if size <= 4.0 * f64::EPSILON {
            break;
        }
    }
    let inside = (0..D).all(|i| {
        let pad = 1e-3 * (k[i].1 - k[i].0) + 4.0 * f64::EPSILON;
        x[i] >= k[i].0 - pad && x[i] <= k[i].1 + pad
    });
    if inside { x } else { middle }
}

/// Krawczyk's test for the tensor Bernstein polynomial `g` (components `D`,
/// degrees `degrees`, each coefficient within `err` of the exact one) on
/// `[0, 1]^D`: the enclosure `K` if it lies strictly inside, which proves
/// exactly one root there (in `K`).
#[allow(clippy::needless_range_loop)]
fn krawczyk<const D: usize>(
    g: &[SVector<f64, D>],
    degrees: &[usize; D],
    err: f64,
) -> Option<[(f64, f64); D]> {
    let eps = f64::EPSILON;
    let mut strides = [1usize; D];
    for k in (0..D - 1).rev() {
        strides[k] = strides[k + 1] * (degrees[k + 1] + 1);
    }
    // Interval Jacobian J[f][k] over the box.
    let mut jac = [[(f64::INFINITY, f64::NEG_INFINITY); D]; D];
    let mut largest = 0.0_f64;
    let mut centre = SVector::<f64, D>::zeros();
    for (idx, c) in g.iter().enumerate() {
        largest = largest.max(c.amax());
        // The Bernstein weight of this coefficient at the centre.
        let mut weight = 1.0;
        for k in 0..D {
            let i = (idx / strides[k]) % (degrees[k] + 1);
            weight *= crate::bernstein::binomial(degrees[k], i) * 0.5_f64.powi(degrees[k] as i32);
            if i < degrees[k] {
                let next = g[idx + strides[k]];
                for f in 0..D {
                    let v = degrees[k] as f64 * (next[f] - c[f]);
                    jac[f][k] = (jac[f][k].0.min(v), jac[f][k].1.max(v));
                }
            }
        }
        centre += c * weight;
    }
    if !largest.is_finite() {
        return None;
    }
    for f in 0..D {
        for k in 0..D {
            let r = jac[f][k];
            let pad = 2.0 * degrees[k] as f64 * err + 2.0 * eps * r.0.abs().max(r.1.abs());
            jac[f][k] = (r.0 - pad, r.1 + pad);
        }
    }
    let f_bound = err + (g.len() + degrees.iter().sum::<usize>() + 4) as f64 * eps * largest;
    let mid: [[f64; D]; D] =
        std::array::from_fn(|f| std::array::from_fn(|k| 0.5 * (jac[f][k].0 + jac[f][k].1)));
    let y = inverse(&mid)?;
    let mut enclosure = [(0.0, 0.0); D];
    for i in 0..D {
        let mut yf = 0.0;
        let mut radius = 0.0;
        let mut terms = 0.5;
        for j in 0..D {
            yf += y[i][j] * centre[j];
            radius += y[i][j].abs() * f_bound;
            terms += (y[i][j] * centre[j]).abs();
        }
        for k in 0..D {
            let identity = if i == k { 1.0 } else { 0.0 };
            let (mut lo, mut hi) = (0.0, 0.0);
            for j in 0..D {
                let (p, q) = (y[i][j] * jac[j][k].0, y[i][j] * jac[j][k].1);
                lo += p.min(q);
                hi += p.max(q);
                terms += p.abs().max(q.abs());
            }
            let magnitude = (identity - lo).abs().max((identity - hi).abs());
            radius += 0.5 * magnitude;
            terms += magnitude;
        }
        radius += 4.0 * (D as f64 + 2.0) * eps * (terms + radius);
        let c = 0.5 - yf;
        if !(c - radius > MARGIN && c + radius < 1.0 - MARGIN) {
            return None;
        }
        enclosure[i] = (c - radius, c + radius);
    }
    Some(enclosure)
}

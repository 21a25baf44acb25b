//! The shared core of the tensor-product surfaces: a table of rational
//! Bézier patches on a grid of breakpoints, with evaluation, the limit
//! normal at collapsed edges, convex-hull bounds of sub-rectangles and the
//! ray search (its pieces built by the first ray).

use super::patch::{Jet, Patch, first_jet, project_jet, rounding_pad, tensor_jet};
use super::search::{PatchSet, intersect, occluded};
use super::search_pieces::SearchPieces;
use crate::bernstein::{eval_with_derivative, restrict};
use crate::curve::{Homogeneous, power_of_two_near, unit_direction};
use crate::surface::oriented;
use crate::{Aabb, Error, Hit, Ray, Tolerance};
use nalgebra::{Point3, Unit, Vector3};
use std::sync::OnceLock;

/// The Bézier patches of a surface, one per non-empty knot rectangle, on a
/// grid of breakpoints.
#[derive(Debug, Clone)]
pub(crate) struct PatchTable {
    /// Degrees `(p, q)`.
    pub(crate) degrees: (usize, usize),
    /// The distinct breakpoints in `u`, increasing, at least two.
    pub(crate) u_breaks: Vec<f64>,
    /// The distinct breakpoints in `v`.
    pub(crate) v_breaks: Vec<f64>,
    /// Patch `(a, b)` (the `a`-th u-span, `b`-th v-span) at
    /// `a·(v_breaks.len() − 1) + b`.
    pub(crate) patches: Vec<Patch>,
    /// The largest extent of the box of the projected control points
    /// (the scale of the normal's degeneracy test), computed once.
    extent: f64,
    /// A box around the control points, padded for rounding as the
    /// search's own boxes are.
    bounds: Aabb,
    /// The patches cut into pieces, with the hierarchy over them, for ray
    /// intersection: built by the first ray, so that a surface that is
    /// never intersected (or only as part of a [`BezierPatches`] model,
    /// which has its own) does not hold them.
    ///
    /// [`BezierPatches`]: crate::BezierPatches
    search: OnceLock<SearchPieces>,
    /// The intersection accuracy.
    pub(crate) tolerance: Tolerance,
    /// The orientation is reversed (the surface kinds' `reversed()`): the
    /// normals are negated, nothing else changes.
    pub(crate) reversed: bool,
}
/// The index `k` of the span `[breaks[k], breaks[k + 1])` holding `x`
/// (clamped into the breakpoints; the last breakpoint belongs to the last
/// span).
fn locate(breaks: &[f64], x: f64) -> usize {
    let last = breaks.len() - 2;
    // Number of breakpoints ≤ x, minus one.
    let k = breaks.partition_point(|&b| b <= x);
    k.saturating_sub(1).min(last)
}
/// Equal when the surfaces are: the cached search pieces do not count.
impl PartialEq for PatchTable {
    fn eq(&self, other: &Self) -> bool {
        self.degrees == other.degrees
            && self.u_breaks == other.u_breaks
            && self.v_breaks == other.v_breaks
            && self.patches == other.patches
            && self.tolerance == other.tolerance
            && self.reversed == other.reversed
    }
}
impl PatchTable {
    /// The table of `patches` on the breakpoint grid (see the fields).
    pub(crate) fn new(
        degrees: (usize, usize),
        u_breaks: Vec<f64>,
        v_breaks: Vec<f64>,
        patches: Vec<Patch>,
    ) -> Self {
        let b = patches
            .iter()
            .fold(Aabb::EMPTY, |b, p| b.union(&p.net_box()));
        let scale = b.min.coords.amax().max(b.max.coords.amax());
        PatchTable {
            degrees,
            u_breaks,
            v_breaks,
            patches,
            extent: b.extent().amax(),
            bounds: b.expand(rounding_pad(scale)),
            search: OnceLock::new(),
            tolerance: Tolerance::default(),
            reversed: false,
        }
    }

    /// The parameter rectangle.
    pub(crate) fn domain(&self) -> [(f64, f64); 2] {
        [
            (self.u_breaks[0], self.u_breaks[self.u_breaks.len() - 1]),
            (self.v_breaks[0], self.v_breaks[self.v_breaks.len() - 1]),
        ]
    }

    /// `(u, v)` clamped into the domain, NaN to its start.
    pub(crate) fn clamp(&self, u: f64, v: f64) -> (f64, f64) {
        let [du, dv] = self.domain();
        (
            crate::curve::clamp_to_domain(u, du),
            crate::curve::clamp_to_domain(v, dv),
        )
    }

    /// The jet of the surface at `(u, v)` (clamped), orders `≤ order ≤ 2`,
    /// with respect to the surface's own parameters.
    pub(crate) fn jet(&self, u: f64, v: f64, order: usize) -> Jet<Vector3<f64>> {
        let (patch, st) = self.locate(u, v);
        self.jet_on(patch, st, order)
    }

    /// The patch holding `(u, v)` (clamped) and the point's parameters
    /// `(s, t)` on it, each in `[0, 1]`.
    fn locate(&self, u: f64, v: f64) -> (&Patch, (f64, f64)) {
        let (u, v) = self.clamp(u, v);
        let (a, b) = (locate(&self.u_breaks, u), locate(&self.v_breaks, v));
        let patch = &self.patches[a * (self.v_breaks.len() - 1) + b];
        let s = ((u - patch.u.0) / (patch.u.1 - patch.u.0)).clamp(0.0, 1.0);
        let t = ((v - patch.v.0) / (patch.v.1 - patch.v.0)).clamp(0.0, 1.0);
        (patch, (s, t))
    }

    /// The point at `(s, t)` (clamped into `[0, 1]²`) of `patch` (one of
    /// the table's).
    pub(crate) fn point_on(&self, patch: &Patch, (s, t): (f64, f64)) -> Point3<f64> {
        let st = (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
        Point3::from(self.jet_on(patch, st, 0)[0][0])
    }

    /// The jet at `(s, t)` of `patch` (one of the table's), with respect
    /// to the surface's own parameters.
    fn jet_on(&self, patch: &Patch, (s, t): (f64, f64), order: usize) -> Jet<Vector3<f64>> {
        let (wu, wv) = (patch.u.1 - patch.u.0, patch.v.1 - patch.v.0);
        let cols = self.degrees.1 + 1;
        // Orders up to one by the Bernstein bases, higher by de Casteljau.
        let h = match first_jet(&patch.net, cols, s, t).filter(|_| order <= 1) {
            Some([h, hs, ht]) => {
                let zero = Homogeneous::zero();
                [[h, ht, zero], [hs, zero, zero], [zero; 3]]
            }
            None => tensor_jet(&patch.net, cols, s, t, order),
        };
        let mut d = project_jet(&h, order);
        // Chain rule for s = (u − u₀)/wu, t = (v − v₀)/wv: one division per
        // order (a power of a tiny width would underflow to zero; the
        // quotients stay within the derivative bound checked at construction).
        for (a, row) in d.iter_mut().enumerate() {
            for (b, x) in row.iter_mut().enumerate() {
                if a + b >= 1 && a + b <= order {
                    for _ in 0..a {
                        *x /= wu;
                    }
                    for _ in 0..b {
                        *x /= wv;
                    }
                }
            }
        }
        d
    }

    /// The nearest hit of `ray` with `t_min < t < t_max` (see
    /// [`crate::ray::patch`]): the point is `S(u, v)`, the normal follows
    /// `∂S/∂u × ∂S/∂v` (its limit where that vanishes; negated when
    /// `reversed`; facing the ray where no tangent plane exists).
    pub(crate) fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        let search = self.search_pieces();
        let found = intersect(search.set(), ray, t_min, t_max, &self.tolerance)?;
        let (owner, st) = search.on_owner(found.patch, found.st);
        let (point, normal) =
            self.point_and_normal_on(&self.patches[owner], st, (found.u, found.v));
        found.to_hit(ray, point, normal)
    }

    /// The point and normal at `(s, t)` of `patch` (one of the table's),
    /// whose surface parameters are `(u, v)`: evaluated at `(s, t)`, which
    /// resolve the point even where `(u, v)` cannot (a domain a few ulps
    /// wide at a large parameter value: `u` takes only a few values there;
    /// see [`Hit::uv`]).
    pub(crate) fn point_and_normal_on(
        &self,
        patch: &Patch,
        st: (f64, f64),
        (u, v): (f64, f64),
    ) -> (Point3<f64>, Option<Unit<Vector3<f64>>>) {
        let (u, v) = self.clamp(u, v);
        let first = self.jet_on(patch, st, 1);
        let normal = self.normal_from(u, v, first[1][0], first[0][1]);
        let normal = normal.map(|n| oriented(n, self.reversed));
        (Point3::from(first[0][0]), normal)
    }

    /// Whether the ray hits the surface in `(t_min, t_max)`: exactly
    /// `hit(…).is_some()`, stopping at the first piece with a hit.
    pub(crate) fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        occluded(self.search_set(), ray, t_min, t_max, &self.tolerance)
    }

    /// What the ray–patch search runs over.
    pub(crate) fn search_set(&self) -> PatchSet<'_> {
        self.search_pieces().set()
    }

    /// The search's pieces, built by the first call.
    fn search_pieces(&self) -> &SearchPieces {
        self.search
            .get_or_init(|| SearchPieces::new(&self.patches, self.degrees))
    }

    /// A box around the surface (its control points, padded for rounding).
    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// `S(u, v)`.
    pub(crate) fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        Point3::from(self.jet(u, v, 0)[0][0])
    }

    /// `(∂S/∂u, ∂S/∂v)`.
    pub(crate) fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        let d = self.jet(u, v, 1);
        (d[1][0], d[0][1])
    }

    /// The unit normal along `∂S/∂u × ∂S/∂v`, with the limit where that
    /// vanishes (see [`BezierSurface`](crate::BezierSurface)'s docs for the
    /// rule); negated when `reversed`.
    pub(crate) fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        let (u, v) = self.clamp(u, v);
        let first = self.jet(u, v, 1);
        self.normal_from(u, v, first[1][0], first[0][1])
            .map(|n| oriented(n, self.reversed))
    }

    /// [`normal`](Self::normal) at `(u, v)` (in the domain) given the
    /// partials `su`, `sv` there.
    fn normal_from(
        &self,
        u: f64,
        v: f64,
        su: Vector3<f64>,
        sv: Vector3<f64>,
    ) -> Option<Unit<Vector3<f64>>> {
        // The typical size of a first derivative: net extent over the
        // parameter widths, times the degree.
        let [du, dv] = self.domain();
        let extent = self.extent.max(f64::MIN_POSITIVE);
        let typical = extent * (self.degrees.0.max(self.degrees.1).max(1) as f64)
            / (du.1 - du.0).min(dv.1 - dv.0);
        // Derivatives in units of a power of two near the typical size
        // (exact), so that products neither underflow on tiny surfaces
        // (below about 1e-154 the cross product would be zero) nor
        // overflow on huge ones.
        let unit = power_of_two_near(typical);
        let (su, sv, typical) = (su / unit, sv / unit, typical / unit);
        let n = su.cross(&sv);
        let negligible = (1e-7 * typical) * (1e-7 * typical);
        if n.norm() > negligible {
            return unit_direction(n);
        }
        let d = self.jet(u, v, 2).map(|row| row.map(|x| x / unit));
        // N(u + h·du, v + h·dv) = N + h·N₁ + O(h²) toward the domain's
        // centre, N₁ = du(S_uu×S_v + S_u×S_uv) + dv(S_uv×S_v + S_u×S_vv).
        let dir_u = (0.5 * (du.0 + du.1) - u) / (du.1 - du.0);
        let dir_v = (0.5 * (dv.0 + dv.1) - v) / (dv.1 - dv.0);
        let wide = (du.1 - du.0).max(dv.1 - dv.0);
        if let Some(limit) = corner_limit(
            [u == du.0 || u == du.1, v == dv.0 || v == dv.1],
            [su, sv],
            [d[2][0], d[1][1], d[0][2]],
            [dir_u.signum(), dir_v.signum()],
            negligible / wide,
        ) {
            return limit;
        }
        let n1 = (d[2][0].cross(&sv) + su.cross(&d[1][1])) * dir_u
            + (d[1][1].cross(&sv) + su.cross(&d[0][2])) * dir_v;
        if n1.norm() * wide > negligible {
            let n1 = unit_direction(n1)?;
            // At a collapsed edge the limit is a tangent plane only if every
            // direction leaving the edge lies in it (else a cone point).
            return self.edge_is_flat(u, v, su, sv, &n1).then_some(n1);
        }
        // Both orders vanish. On a collapsed edge whose next rows of
        // control points collapse onto the same point (a pole on a tripled
        // control point), the limit comes from the first row that leaves.
        if let Some(limit) = self.collapsed_edge_limit(u, v) {
            return limit;
        }
        // Otherwise (a corner where two edges collapse, or an edge whose
        // limit that row does not resolve): the normals at steps h = 10⁻³ …
        // 10⁻⁸ (of the domain, in half decades) inside along the direction,
        // while the cross product is clearly resolved (sine of the angle
        // between the partials ≥ 10⁻⁶, each partial 10³ times its rounding:
        // near a pole the partial along the collapsing edge shrinks as h³
        // and would soon be rounding alone); the last of them if they
        // converge (successive ones within 10⁻³), else no tangent plane.
        let b = self.bounds;
        let coordinates = b.min.coords.amax().max(b.max.coords.amax());
        let rounding = 4.0 * f64::EPSILON * coordinates * self.degrees.0.max(self.degrees.1) as f64
            / (du.1 - du.0).min(dv.1 - dv.0)
            / unit;
        let mut last: Option<Unit<Vector3<f64>>> = None;
        let mut converged = false;
        for k in 6..=16 {
            let h = 10f64.powf(-0.5 * k as f64);
            let (su, sv) =
                self.partials(u + h * dir_u * (du.1 - du.0), v + h * dir_v * (dv.1 - dv.0));
            let (su, sv) = (su / unit, sv / unit);
            let n = su.cross(&sv);
            let resolved = n.norm() > 1e-6 * su.norm() * sv.norm()
                && su.norm().min(sv.norm()) > 1e3 * rounding;
            if !resolved {
                break;
            }
            let Some(n) = unit_direction(n) else {
                break;
            };
            if let Some(previous) = last {
                converged = (n.into_inner() - previous.into_inner()).norm() < 1e-3;
            }
            last = Some(n);
        }
        if converged { last } else { None }
    }

    /// The normal's limit at `(u, v)` on an edge of the domain that
    /// collapses to one point `P`, where the rows of control points after
    /// it collapse onto `P` too, up to row `k` (the first that leaves `P`;
    /// across the edge, rows numbered from it). With `s` the patch
    /// parameter across the edge and `t` along it, numerator and weight
    /// give `S − P = C(p, k)·sᵏ·F(t)/W₀(t) + O(sᵏ⁺¹)` with
    /// `F(t) = Σⱼ Bⱼ(t)·wₖⱼ·(Pₖⱼ − P)`, so that
    /// `S_s × S_t ∝ s²ᵏ⁻¹·F × F′` and the limit is along `±F(t) × F′(t)`
    /// (the sign from the edge's side and parameter). It is a tangent
    /// plane only if every `wₖⱼ(Pₖⱼ − P)` of every patch along the edge is
    /// perpendicular to it (within `10⁻⁷`): `Some(None)` otherwise (a
    /// cone point). `None` (not decided here) off a collapsed edge, when
    /// no row leaves `P`, or when `F × F′` is not resolved at `t`.
    fn collapsed_edge_limit(&self, u: f64, v: f64) -> Option<Option<Unit<Vector3<f64>>>> {
        let [du, dv] = self.domain();
        let (p, q) = self.degrees;
        let cols = q + 1;
        let (nu, nv) = (self.u_breaks.len() - 1, self.v_breaks.len() - 1);
        let (patch, (s, t)) = self.locate(u, v);
        let (a, b) = (locate(&self.u_breaks, u), locate(&self.v_breaks, v));
        let same = 1e-12 * self.extent.max(f64::MIN_POSITIVE);
        let point = |h: &Homogeneous<3>| h.wp / h.w;
        // (edge across u?, at the domain's start?)
        let edges = [
            (true, u == du.0, u == du.0 || u == du.1),
            (false, v == dv.0, v == dv.0 || v == dv.1),
        ];
        for (across_u, at_start, on_edge) in edges {
            if !on_edge {
                continue;
            }
            let (across, along) = if across_u { (p, q) } else { (q, p) };
            // The control point `(i, j)`: `i` rows from the edge, `j` along it.
            let at = |net: &[Homogeneous<3>], i: usize, j: usize| {
                let i = if at_start { i } else { across - i };
                if across_u {
                    net[i * cols + j]
                } else {
                    net[j * cols + i]
                }
            };
            let net = &patch.net;
            let pole = point(&at(net, 0, 0));
            let off = |net: &[Homogeneous<3>], i: usize| {
                (0..=along).any(|j| (point(&at(net, i, j)) - pole).amax() > same)
            };
            if off(net, 0) {
                continue;
            }
            let Some(k) = (1..=across).find(|&i| off(net, i)) else {
                continue;
            };
            let row: Vec<Vector3<f64>> = (0..=along)
                .map(|j| {
                    let h = at(net, k, j);
                    h.wp - pole * h.w
                })
                .collect();
            let along_t = if across_u { t } else { s };
            let (f, df) = eval_with_derivative(&row, along_t)?;
            let n = f.cross(&df);
            let resolved = n.norm() > 1e-7 * f.norm() * df.norm();
            if !resolved {
                continue;
            }
            // S_u × S_v: + at u's start, − at u's end; the other way on v.
            let sign = if across_u == at_start { 1.0 } else { -1.0 };
            let n = unit_direction(n * sign)?;
            // Every patch along the edge: its row k (when rows before it
            // collapse too) perpendicular to n.
            let mut flat = true;
            let others: Vec<&Patch> = if across_u {
                (0..nv).map(|bb| &self.patches[a * nv + bb]).collect()
            } else {
                (0..nu).map(|aa| &self.patches[aa * nv + b]).collect()
            };
            for other in others {
                for i in 1..=k {
                    for j in 0..=along {
                        let h = at(&other.net, i, j);
                        let d = h.wp - pole * h.w;
                        flat &= n.dot(&d).abs() <= 1e-7 * d.norm();
                    }
                }
            }
            return Some(flat.then_some(n));
        }
        None
    }

    /// At a point `(u, v)` on an edge of the domain where that edge is
    /// collapsed (the partial along it vanishes), whether the first
    /// differences of the control net leaving the edge (they span the
    /// directions `∂S/∂n` along the whole edge, with positive factors) are
    /// all perpendicular to `n` within `10⁻⁷` relative: the edge point then
    /// has the tangent plane `⟂ n`; otherwise it is a cone point. `true`
    /// off the edges and on edges that do not collapse.
    fn edge_is_flat(
        &self,
        u: f64,
        v: f64,
        su: Vector3<f64>,
        sv: Vector3<f64>,
        n: &Unit<Vector3<f64>>,
    ) -> bool {
        let [du, dv] = self.domain();
        let (p, q) = self.degrees;
        let cols = q + 1;
        let (nu, nv) = (self.u_breaks.len() - 1, self.v_breaks.len() - 1);
        let point = |h: &Homogeneous<3>| h.wp / h.w;
        let tiny = |x: Vector3<f64>, y: Vector3<f64>| x.norm() <= 1e-7 * y.norm();
        let flat = |d: Vector3<f64>| n.dot(&d).abs() <= 1e-7 * d.norm();
        let mut ok = true;
        if (u == du.0 || u == du.1) && tiny(sv, su) && p >= 1 {
            let (a, i0, i1) = if u == du.0 {
                (0, 0, 1)
            } else {
                (nu - 1, p, p - 1)
            };
            for b in 0..nv {
                let net = &self.patches[a * nv + b].net;
                for j in 0..cols {
                    ok &= flat(point(&net[i1 * cols + j]) - point(&net[i0 * cols + j]));
                }
            }
        }
        if (v == dv.0 || v == dv.1) && tiny(su, sv) && q >= 1 {
            let (b, j0, j1) = if v == dv.0 {
                (0, 0, 1)
            } else {
                (nv - 1, q, q - 1)
            };
            for a in 0..nu {
                let net = &self.patches[a * nv + b].net;
                for i in 0..=p {
                    ok &= flat(point(&net[i * cols + j1]) - point(&net[i * cols + j0]));
                }
            }
        }
        ok
    }

    /// A box containing `S([u₀, u₁] × [v₀, v₁])`: the union over the patches
    /// the rectangle meets of the box of the sub-patch's projected control
    /// net (de Casteljau subdivision in homogeneous coordinates; the convex
    /// hull property with positive weights), padded for rounding.
    pub(crate) fn bound(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        let (u0, v0) = self.clamp(u.0.min(u.1), v.0.min(v.1));
        let (u1, v1) = self.clamp(u.0.max(u.1), v.0.max(v.1));
        let (a0, a1) = (locate(&self.u_breaks, u0), locate(&self.v_breaks, v0));
        let (b0, b1) = (locate(&self.u_breaks, u1), locate(&self.v_breaks, v1));
        let (p, q) = self.degrees;
        let cols = q + 1;
        let mut boxed = Aabb::EMPTY;
        let mut magnitude = 0.0_f64;
        for a in a0..=b0 {
            for b in a1..=b1 {
                let patch = &self.patches[a * (self.v_breaks.len() - 1) + b];
                let local = |x: f64, (lo, hi): (f64, f64)| ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
                let s = (local(u0, patch.u), local(u1, patch.u));
                let t = (local(v0, patch.v), local(v1, patch.v));
                let mut net = patch.net.clone();
                // Rows (in t), then columns (in s).
                let mut line = Vec::with_capacity(p.max(q) + 1);
                for i in 0..=p {
                    line.clear();
                    line.extend_from_slice(&net[i * cols..(i + 1) * cols]);
                    restrict(&mut line, t);
                    net[i * cols..(i + 1) * cols].copy_from_slice(&line);
                }
                for j in 0..cols {
                    line.clear();
                    line.extend((0..=p).map(|i| net[i * cols + j]));
                    restrict(&mut line, s);
                    for i in 0..=p {
                        net[i * cols + j] = line[i];
                    }
                }
                for h in &net {
                    let x = Point3::from(h.wp / h.w);
                    magnitude = magnitude.max(x.coords.amax());
                    boxed = boxed.include(&x);
                }
            }
        }
        let pad = 16.0 * (p + q + 2) as f64 * f64::EPSILON * magnitude;
        boxed.expand(pad)
    }
}

/// The normal at a corner of the domain where one first partial vanishes
/// but the edges do not collapse (a corner control point doubled, `P₁₀ =
/// P₀₀`): approaching along the inward direction `(a, b)` (signs `inward`),
/// with `S_u = 0` the normal is `N ≈ r·(a S_uu + b S_uv) × S_v`, a
/// combination of `A = S_uu × S_v` (along the edge `v` fixed) and
/// `B = S_uv × S_v` (along the edge `u` fixed); with `S_v = 0`,
/// `A = S_u × S_uv`, `B = S_u × S_vv`. The limit is independent of the
/// direction exactly when `A` and `B` point the same way: it is then
/// `Some(that direction)`; `Some(None)` when they do not (a cone point).
/// `None` (not decided here) off the corners, when neither or both
/// partials vanish, or when `A` or `B` vanishes too (a collapsed edge,
/// which [`PatchTable::edge_is_flat`] decides).
fn corner_limit(
    [on_u_end, on_v_end]: [bool; 2],
    [su, sv]: [Vector3<f64>; 2],
    [suu, suv, svv]: [Vector3<f64>; 3],
    [inward_u, inward_v]: [f64; 2],
    negligible: f64,
) -> Option<Option<Unit<Vector3<f64>>>> {
    let tiny = |x: Vector3<f64>, y: Vector3<f64>| x.norm() <= 1e-7 * y.norm();
    if !(on_u_end && on_v_end) || tiny(su, sv) == tiny(sv, su) {
        return None;
    }
    let (a, b) = if tiny(su, sv) {
        (suu.cross(&sv) * inward_u, suv.cross(&sv) * inward_v)
    } else {
        (su.cross(&suv) * inward_u, su.cross(&svv) * inward_v)
    };
    if a.norm() <= negligible || b.norm() <= negligible {
        return None;
    }
    let same_way = a.dot(&b) > 0.0 && a.cross(&b).norm() <= 1e-7 * a.norm() * b.norm();
    Some(if same_way {
        unit_direction(a / a.norm() + b / b.norm())
    } else {
        None
    })
}

/// Checks that the first and second partials of every rational patch stay
/// within [`MAX_DERIVATIVE`](crate::MAX_DERIVATIVE), as the rational curves
/// check their pieces. With `S = A/w` (homogeneous `(A, w)`) the quotient
/// rule gives, direction by direction,
/// `|S′| ≤ (|A′| + |w′|·|S|)/w`, `|S″| ≤ (|A″| + 2|w′|·|S′| + |w″|·|S|)/w`
/// and `|S_uv| ≤ (|A_uv| + |w_u|·|S_v| + |w_v|·|S_u| + |w_uv|·|S|)/w`, with
/// `w ≥ min w` and the derivatives of `A` and `w` bounded by the nets'
/// differences times `degree / width` per order (convex hull property).
///
/// # Errors
/// [`Error::DerivativeOverflow`] (order 1 or 2).
pub(crate) fn check_rational_partials(table: &PatchTable) -> Result<(), Error> {
    let (p, q) = table.degrees;
    let cols = q + 1;
    let within = |bound: f64| bound <= crate::MAX_DERIVATIVE;
    for patch in &table.patches {
        let net = &patch.net;
        let at = |i: usize, j: usize| net[i * cols + j];
        let w_min = net.iter().fold(f64::INFINITY, |m, h| m.min(h.w));
        let p_max = net.iter().fold(0.0_f64, |m, h| m.max(h.wp.amax() / h.w));
        // Largest |Δ^k A| and |Δ^k w| of order k along a direction, and
        // the mixed first difference.
        let (mut d1, mut d2) = ([[0.0_f64; 2]; 2], [[0.0_f64; 2]; 2]);
        let mut mixed = [0.0_f64; 2];
        let record = |slot: &mut [f64; 2], a: Homogeneous<3>| {
            slot[0] = slot[0].max(a.wp.amax());
            slot[1] = slot[1].max(a.w.abs());
        };
        for i in 0..=p {
            for j in 0..=q {
                let h = at(i, j);
                if i < p {
                    record(&mut d1[0], at(i + 1, j) - h);
                    if j < q {
                        record(
                            &mut mixed,
                            at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + h,
                        );
                    }
                }
                if i + 2 <= p {
                    record(&mut d2[0], at(i + 2, j) - at(i + 1, j) * 2.0 + h);
                }
                if j < q {
                    record(&mut d1[1], at(i, j + 1) - h);
                }
                if j + 2 <= q {
                    record(&mut d2[1], at(i, j + 2) - at(i, j + 1) * 2.0 + h);
                }
            }
        }
        // degree / width and (degree − 1) / width per direction (the
        // factors apart: a squared tiny width would underflow).
        let factor = [
            (
                p as f64 / (patch.u.1 - patch.u.0),
                p.saturating_sub(1) as f64 / (patch.u.1 - patch.u.0),
            ),
            (
                q as f64 / (patch.v.1 - patch.v.0),
                q.saturating_sub(1) as f64 / (patch.v.1 - patch.v.0),
            ),
        ];
        let mut first = [0.0_f64; 2];
        for k in 0..2 {
            let (f1, f2) = factor[k];
            let (a1, w1) = (d1[k][0] * f1, d1[k][1] * f1);
            first[k] = (a1 + w1 * p_max) / w_min;
            if !within(first[k]) {
                return Err(Error::DerivativeOverflow { order: 1 });
            }
            let (a2, w2) = (d2[k][0] * f1 * f2, d2[k][1] * f1 * f2);
            let second = (a2 + 2.0 * w1 * first[k] + w2 * p_max) / w_min;
            if !within(second) {
                return Err(Error::DerivativeOverflow { order: 2 });
            }
        }
        let (fu, fv) = (factor[0].0, factor[1].0);
        let (w_u, w_v) = (d1[0][1] * fu, d1[1][1] * fv);
        let cross =
            (mixed[0] * fu * fv + w_u * first[1] + w_v * first[0] + mixed[1] * fu * fv * p_max)
                / w_min;
        if !within(cross) {
            return Err(Error::DerivativeOverflow { order: 2 });
        }
    }
    Ok(())
}

//! Triangle meshes of tensor-product (Bézier, B-spline, NURBS) surfaces and
//! of lists of Bézier patches, with a certified deviation bound; watertight
//! where patches share an edge.
//!
//! # The grid
//! Each (rational) Bézier patch `S(s, t) = A(s, t)/w(s, t)`, `(s, t) ∈ [0, 1]²`,
//! of degrees `(p, q)` is cut into `n_s × n_t` equal cells of size
//! `h × k = 1/n_s × 1/n_t`; each cell `A = (s, t)`, `B = (s + h, t)`,
//! `C = (s, t + k)`, `D = (s + h, t + k)` becomes the triangles `ABC` and `BDC`
//! (both follow `∂S/∂s × ∂S/∂t`), with the surface's points as vertices.
//!
//! # The bound
//! Let `M_ss`, `M_st`, `M_tt` bound `|S_ss|`, `|S_st|`, `|S_tt|` on the patch.
//! For a point `x` of a triangle with vertices `xᵢ` and barycentric
//! coordinates `λᵢ`, Taylor's formula with integral remainder at `x` gives
//! `S(xᵢ) = S(x) + DS(x)(xᵢ − x) + Rᵢ` with
//! `|Rᵢ| ≤ ½ Q(xᵢ − x)`, `Q(d) = M_ss d_s² + 2M_st |d_s d_t| + M_tt d_t²`
//! (the segment from `x` to `xᵢ` stays in the triangle). As `Σλᵢ(xᵢ − x) = 0`,
//! the linear interpolant `L(x) = Σλᵢ S(xᵢ)`, a point of the mesh triangle,
//! satisfies `|S(x) − L(x)| = |Σλᵢ Rᵢ| ≤ ½ Σλᵢ Q(xᵢ − x)`. On the triangle
//! `ABC`, with `x = A + (a·h, b·k)`, `a, b ≥ 0`, `a + b ≤ 1`:
//! `Σλᵢ d_s² = a(1 − a)h² ≤ h²/4`, `Σλᵢ d_t² = b(1 − b)k² ≤ k²/4` and
//! `Σλᵢ |d_s d_t| = ab(3 − 2a − 2b)·hk ≤ hk/4` (its only critical point is
//! `a = b = ½`, on the edge `a + b = 1`, where `ab ≤ ¼`); `BDC` is the same
//! triangle turned by a half turn, which keeps `|d_s d_t|`. Hence every point
//! of the patch lies within
//!
//! `(h²M_ss + 2hk·M_st + k²M_tt) / 8`
//!
//! of its two triangles: the bound of Filip, Magedson & Markot ("Surface
//! algorithms using bounds on derivatives", CAGD 3, 1986) for the bilinear
//! interpolant, shown here for the triangles directly.
//!
//! The second-partial bounds come from the net (convex hull property of
//! the hodographs; Farin, *Curves and Surfaces for CAGD*, ch. 16): with the
//! net translated to the centre `c` of its box, `aᵢⱼ = wᵢⱼ(Pᵢⱼ − c)`,
//! `R = max|Pᵢⱼ − c|` (so `|S − c| ≤ R`: positive weights make `S` a convex
//! combination of the `Pᵢⱼ`) and `w ≥ w_min = min wᵢⱼ`, the hodographs give
//! `|A_s| ≤ p·max|Δ_s a|`, `|A_ss| ≤ p(p−1)·max|Δ²_s a|`,
//! `|A_st| ≤ pq·max|Δ_sΔ_t a|` (likewise `W_s`, `W_ss`, `W_st` for `w`), and the
//! quotient rule (`A = wS` differentiated; Piegl & Tiller, *The NURBS Book*,
//! §4.5)
//!
//! `|S_s| ≤ (|A_s| + W_s R)/w_min`,
//! `|S_ss| ≤ (|A_ss| + 2W_s|S_s| + W_ss R)/w_min`,
//! `|S_st| ≤ (|A_st| + W_s|S_t| + W_t|S_s| + W_st R)/w_min`.
//!
//! For a polynomial patch (equal weights) the `W` terms vanish and these are
//! the classic `p(p−1)·max|Δ²_s P|` etc. They are taken on each of the
//! patch's `4 × 4` equal sub-patches (de Casteljau subdivision) and the
//! largest, times `4²` for the change of parameter, bounds the whole patch:
//! closer to the true maxima, above all for rational patches (smaller `R`
//! and weight variation per piece). The counts are chosen per patch as
//! `n_s = ⌈√((M_ss + M_st)/(4τ))⌉`, `n_t = ⌈√((M_tt + M_st)/(4τ))⌉`, which
//! gives a bound `≤ τ` (as `2hk ≤ h² + k²`), then raised to agree across
//! shared edges (below).
//!
//! A triangle that collapses (two equal vertices, at a collapsed edge as on
//! the teapot's lid and bottom) is left out when the cell's other triangle
//! does not collapse: its interpolant then lies on an edge of that other
//! triangle (checked case by case: `A = B` or `A = C` leave the segment `BC`
//! or `AB`, both edges of `BDC`; `B = D` or `C = D` leave `BC`, an edge of
//! `ABC`). Where both collapse (a cell whose image is a curve) both stay, so
//! the bound keeps holding.
//!
//! The reported [`Mesh::bound`] adds a rounding allowance for the vertices
//! (`16(p + q + 2)ε · scale · w_max/w_min`, with `scale` the largest control
//! coordinate); the differences of the net are enlarged by their own rounding.
//!
//! # Watertight edges
//! Two patches that share an edge with the same control points (in the same
//! or the reverse order; a B-spline's neighbouring patches, the teapot's)
//! get the same number of segments there: the counts along a patch's two
//! directions are unified (union–find) over all such matched edges, each
//! class taking the largest count any member needs. The vertices of a
//! boundary edge come from the edge curve alone, evaluated in a canonical
//! direction (the lexicographically smaller of the control sequence and its
//! reverse, compared bit by bit), so both sides compute bit-identical points;
//! edge vertices with equal positions are then welded into one vertex (a
//! patch's interior vertices are its own). Edges collapsed to a
//! point are not matched (every one of their vertices is that point).

use super::patch::{Patch, tensor_jet};
use super::patch_table::PatchTable;
use crate::Error;
use crate::Mesh;
use crate::allocation::try_with_capacity;
use crate::bernstein::{self, Coefficient};
use crate::curve::{Homogeneous, MIN_RELATIVE_TOLERANCE};
use nalgebra::{Point3, Unit, Vector3};
use std::collections::HashMap;

/// Bounds on the second partials of a patch in its local `(s, t)`.
#[derive(Debug, Clone, Copy)]
struct Curvature {
    ss: f64,
    st: f64,
    tt: f64,
}

/// One edge of a patch: which direction node its segment count belongs to,
/// and its control points in the patch's own order.
struct Edge {
    node: usize,
    controls: Vec<Homogeneous<3>>,
}

/// A triangle mesh of the rational Bézier `patches` (degrees `degrees`,
/// each with its parameter rectangle) within `tolerance` (see the module
/// docs); normals from the surface (the limit at collapsed edges; the mean
/// of the adjacent faces' normals where the surface has none), `uv` in the
/// patches' rectangles. The patches `k` with `reversed(k)` have their
/// normals negated and their triangles wound the other way (a vertex shared
/// by several patches keeps the orientation of the first that has it).
///
/// # Errors
/// [`Error::InvalidTolerance`] (not finite and positive);
/// [`Error::ToleranceTooSmall`] below `10⁻¹⁰` of the largest control
/// coordinate or below the rounding allowance; [`Error::MeshTooLarge`]
/// where the mesh would exceed [`Mesh::MAX_VERTICES`] (its `min` fits);
/// [`Error::AllocationFailed`].
pub(crate) fn tessellate_patches(
    degrees: (usize, usize),
    patches: &[Patch],
    tolerance: f64,
    reversed: impl Fn(usize) -> bool,
) -> Result<Mesh, Error> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidTolerance { tolerance });
    }
    let (p, q) = degrees;
    let point = |h: &Homogeneous<3>| Point3::from(h.wp / h.w);
    let controls = || patches.iter().flat_map(|patch| patch.net.iter());
    let scale = controls().fold(0.0_f64, |m, h| m.max(point(h).coords.amax()));
    let w_min = controls().fold(f64::INFINITY, |m, h| m.min(h.w));
    let w_max = controls().fold(0.0_f64, |m, h| m.max(h.w));
    let rounding = 16.0 * (p + q + 2) as f64 * f64::EPSILON * scale * (w_max / w_min);
    let min = (MIN_RELATIVE_TOLERANCE * scale).max(2.0 * rounding);
    if patches.is_empty() {
        return if tolerance < min {
            Err(Error::ToleranceTooSmall { tolerance, min })
        } else {
            Ok(empty_mesh())
        };
    }
    // Below the precision floor the mesh is planned at the floor, so that
    // the error names the vertex cap where even the floor exceeds it.
    let effective = tolerance.max(min);
    let target = effective - rounding;
    let curvatures: Vec<Curvature> = patches.iter().map(|x| curvature(&x.net, p, q)).collect();
    // Direction nodes: 2k is patch k's s direction, 2k + 1 its t direction.
    let mut need: Vec<f64> = curvatures
        .iter()
        .flat_map(|c| {
            let count = |m: f64| (m / (4.0 * target)).sqrt().ceil().max(1.0);
            [count(c.ss + c.st), count(c.tt + c.st)]
        })
        .collect();
    let edges: Vec<[Edge; 4]> = patches
        .iter()
        .enumerate()
        .map(|(k, patch)| patch_edges(k, &patch.net, p, q))
        .collect();
    let mut classes = UnionFind::new(need.len());
    let mut seen: HashMap<Vec<u64>, usize> = HashMap::new();
    for edge in edges.iter().flatten() {
        if collapsed(&edge.controls) {
            continue;
        }
        let (key, _) = canonical(&edge.controls);
        let first = *seen.entry(key).or_insert(edge.node);
        classes.union(first, edge.node);
    }
    let mut class_need = vec![1.0_f64; need.len()];
    for (node, &n) in need.iter().enumerate() {
        let root = classes.find(node);
        class_need[root] = class_need[root].max(n);
    }
    for (node, n) in need.iter_mut().enumerate() {
        *n = class_need[classes.find(node)];
    }
    let vertices: f64 = need.chunks(2).map(|c| (c[0] + 1.0) * (c[1] + 1.0)).sum();
    if vertices.is_nan() || vertices > Mesh::MAX_VERTICES as f64 {
        let ratio = if vertices.is_finite() {
            vertices / Mesh::MAX_VERTICES as f64
        } else {
            f64::MAX
        };
        return Err(Error::MeshTooLarge {
            tolerance,
            vertices,
            max: Mesh::MAX_VERTICES,
            min: (effective * ratio * 1.25).max(min),
        });
    }
    if tolerance < min {
        return Err(Error::ToleranceTooSmall { tolerance, min });
    }
    let counts: Vec<(usize, usize)> = need
        .chunks(2)
        .map(|c| (c[0] as usize, c[1] as usize))
        .collect();
    let bound = curvatures
        .iter()
        .zip(&counts)
        .map(|(c, &(ns, nt))| {
            let (h, k) = (1.0 / ns as f64, 1.0 / nt as f64);
            // (1 + 16ε): the grid parameters i/n are rounded.
            (h * h * c.ss + 2.0 * h * k * c.st + k * k * c.tt) / 8.0 * (1.0 + 16.0 * f64::EPSILON)
        })
        .fold(0.0_f64, f64::max)
        + rounding;
    let vertices = vertices as usize;
    build(degrees, patches, &edges, &counts, bound, vertices, reversed)
}

/// A mesh with nothing in it.
fn empty_mesh() -> Mesh {
    Mesh {
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        triangles: Vec::new(),
        bound: 0.0,
    }
}

/// The vertices (welded) and triangles for the chosen counts, turned the
/// other way round on the patches `k` with `reversed(k)`.
fn build(
    (p, q): (usize, usize),
    patches: &[Patch],
    edges: &[[Edge; 4]],
    counts: &[(usize, usize)],
    bound: f64,
    vertices: usize,
    reversed: impl Fn(usize) -> bool,
) -> Result<Mesh, Error> {
    let cells: usize = counts.iter().map(|&(a, b)| a * b).sum();
    let mut mesh = Mesh {
        positions: try_with_capacity(vertices)?,
        normals: Vec::new(),
        uvs: try_with_capacity(vertices)?,
        triangles: try_with_capacity(2 * cells)?,
        bound,
    };
    let mut normals: Vec<Option<Unit<Vector3<f64>>>> = try_with_capacity(vertices)?;
    let mut welded: HashMap<[u64; 3], u32> = HashMap::new();
    let cols = q + 1;
    // Each patch's new vertices and its triangles, to orient afterwards.
    let mut ranges = Vec::with_capacity(patches.len());
    for ((patch, patch_edges), &(ns, nt)) in patches.iter().zip(edges).zip(counts) {
        let first = (mesh.positions.len(), mesh.triangles.len());
        // A one-patch table gives the patch's normals (with their limits).
        let table = PatchTable::new(
            (p, q),
            vec![patch.u.0, patch.u.1],
            vec![patch.v.0, patch.v.1],
            vec![patch.clone()],
        );
        // Boundary points from the edge curves: s = 0, s = 1 (along t),
        // t = 0, t = 1 (along s).
        let rim: Vec<Vec<Point3<f64>>> = patch_edges
            .iter()
            .enumerate()
            .map(|(e, edge)| edge_points(&edge.controls, if e < 2 { nt } else { ns }))
            .collect();
        let param = |i: usize, n: usize, (a, b): (f64, f64)| {
            if i == n {
                (1.0, b)
            } else {
                let x = i as f64 / n as f64;
                (x, a + (b - a) * x)
            }
        };
        let mut index = try_with_capacity::<u32>((ns + 1) * (nt + 1))?;
        for i in 0..=ns {
            let (s, u) = param(i, ns, patch.u);
            for j in 0..=nt {
                let (t, v) = param(j, nt, patch.v);
                let on_rim = i == 0 || i == ns || j == 0 || j == nt;
                let position = if i == 0 {
                    rim[0][j]
                } else if i == ns {
                    rim[1][j]
                } else if j == 0 {
                    rim[2][i]
                } else if j == nt {
                    rim[3][i]
                } else {
                    let h = tensor_jet(&patch.net, cols, s, t, 0)[0][0];
                    Point3::from(h.wp / h.w)
                };
                let next = mesh.positions.len() as u32;
                // Only edge vertices can be shared (with other patches, or
                // along a collapsed edge): they are welded by their bits.
                let id = if on_rim {
                    let key = position.coords.map(f64::to_bits);
                    *welded.entry([key.x, key.y, key.z]).or_insert(next)
                } else {
                    next
                };
                if id == next {
                    mesh.positions.push(position);
                    mesh.uvs.push((u, v));
                    normals.push(table.normal(u, v));
                }
                index.push(id);
            }
        }
        let at = |i: usize, j: usize| index[i * (nt + 1) + j];
        for i in 0..ns {
            for j in 0..nt {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
                let first = [a, b, c];
                let second = [b, d, c];
                let (keep_first, keep_second) = match (degenerate(first), degenerate(second)) {
                    (true, false) => (false, true),
                    (false, true) => (true, false),
                    _ => (true, true),
                };
                if keep_first {
                    mesh.triangles.push(first);
                }
                if keep_second {
                    mesh.triangles.push(second);
                }
            }
        }
        ranges.push((first.0..mesh.positions.len(), first.1..mesh.triangles.len()));
    }
    mesh.normals = fill_normals(&mesh.positions, &mesh.triangles, &normals)?;
    for (k, (vertices, triangles)) in ranges.into_iter().enumerate() {
        if reversed(k) {
            mesh.reverse_orientation(vertices, triangles);
        }
    }
    Ok(mesh)
}

/// Whether a triangle has two equal vertex indices.
fn degenerate([a, b, c]: [u32; 3]) -> bool {
    a == b || b == c || a == c
}

/// The vertex normals: the surface's where it has one, else the normalized
/// sum of the adjacent triangles' area vectors, else `+z` (a vertex of
/// collapsed triangles only).
fn fill_normals(
    positions: &[Point3<f64>],
    triangles: &[[u32; 3]],
    surface: &[Option<Unit<Vector3<f64>>>],
) -> Result<Vec<Unit<Vector3<f64>>>, Error> {
    let mut sums: HashMap<u32, Vector3<f64>> = HashMap::new();
    if surface.iter().any(Option::is_none) {
        for t in triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let area = (b - a).cross(&(c - a));
            for &i in t {
                if surface[i as usize].is_none() {
                    *sums.entry(i).or_insert_with(Vector3::zeros) += area;
                }
            }
        }
    }
    let mut out = try_with_capacity(surface.len())?;
    for (i, n) in surface.iter().enumerate() {
        out.push(n.unwrap_or_else(|| {
            sums.get(&(i as u32))
                .and_then(|s| crate::curve::unit_direction(*s))
                .unwrap_or_else(Vector3::z_axis)
        }));
    }
    Ok(out)
}

/// The four edges of patch `k` (net row-major, degrees `(p, q)`): `s = 0`
/// and `s = 1` (curves in `t`, counted by the `t` node `2k + 1`), then
/// `t = 0` and `t = 1` (curves in `s`, node `2k`).
fn patch_edges(k: usize, net: &[Homogeneous<3>], p: usize, q: usize) -> [Edge; 4] {
    let cols = q + 1;
    let row = |i: usize| net[i * cols..(i + 1) * cols].to_vec();
    let column = |j: usize| (0..=p).map(|i| net[i * cols + j]).collect();
    [
        Edge {
            node: 2 * k + 1,
            controls: row(0),
        },
        Edge {
            node: 2 * k + 1,
            controls: row(p),
        },
        Edge {
            node: 2 * k,
            controls: column(0),
        },
        Edge {
            node: 2 * k,
            controls: column(q),
        },
    ]
}

/// Whether all control points of an edge project to the same point.
fn collapsed(controls: &[Homogeneous<3>]) -> bool {
    let first = controls[0].wp / controls[0].w;
    controls.iter().all(|h| h.wp / h.w == first)
}

/// The edge's control sequence in its canonical direction (bits of the
/// lexicographically smaller of it and its reverse) and whether that is the
/// reverse.
fn canonical(controls: &[Homogeneous<3>]) -> (Vec<u64>, bool) {
    let bits = |h: &Homogeneous<3>| [h.wp.x, h.wp.y, h.wp.z, h.w].map(f64::to_bits);
    let forward: Vec<u64> = controls.iter().flat_map(bits).collect();
    let backward: Vec<u64> = controls.iter().rev().flat_map(bits).collect();
    if backward < forward {
        (backward, true)
    } else {
        (forward, false)
    }
}

/// The `n + 1` points of the edge curve at parameters `k/n`, in the edge's
/// own direction, computed in its canonical direction (so that both patches
/// along an edge get the same bits); the end points are the end controls
/// projected, and a collapsed edge is its point throughout.
fn edge_points(controls: &[Homogeneous<3>], n: usize) -> Vec<Point3<f64>> {
    let point = |h: &Homogeneous<3>| Point3::from(h.wp / h.w);
    if collapsed(controls) {
        return vec![point(&controls[0]); n + 1];
    }
    let (_, reversed) = canonical(controls);
    let ordered: Vec<Homogeneous<3>> = if reversed {
        controls.iter().rev().copied().collect()
    } else {
        controls.to_vec()
    };
    let last = ordered.len() - 1;
    let mut points: Vec<Point3<f64>> = (0..=n)
        .map(|k| match k {
            0 => point(&ordered[0]),
            k if k == n => point(&ordered[last]),
            k => {
                let h = bernstein::eval(&ordered, k as f64 / n as f64).unwrap_or(ordered[0]);
                point(&h)
            }
        })
        .collect();
    if reversed {
        points.reverse();
    }
    points
}

/// Each patch's second-partial bounds are the largest over its
/// `SUBPATCHES × SUBPATCHES` equal sub-patches (de Casteljau subdivision),
/// scaled back to the patch's parameters: closer to the true maxima than
/// the whole net's differences, above all for rational patches (smaller
/// `R` and weight variation).
const SUBPATCHES: usize = 4;

/// The pieces of the Bézier coefficients `c` on the `m` equal parts of
/// `[0, 1]`, each on its own `[0, 1]`.
fn split<T: Coefficient>(c: &[T], m: usize) -> Vec<Vec<T>> {
    let mut rest = c.to_vec();
    let mut left = c.to_vec();
    let mut right = c.to_vec();
    let mut pieces = Vec::with_capacity(m);
    for k in 0..m - 1 {
        bernstein::subdivide(&rest, 1.0 / (m - k) as f64, &mut left, &mut right);
        pieces.push(left.clone());
        rest.copy_from_slice(&right);
    }
    pieces.push(rest);
    pieces
}

/// Bounds on `|S_ss|`, `|S_st|`, `|S_tt|` over the patch in its `(s, t)`:
/// the largest of the sub-patches' bounds ([`net_curvature`]) times `m²`
/// (a sub-patch's parameter is `m` times the patch's).
fn curvature(net: &[Homogeneous<3>], p: usize, q: usize) -> Curvature {
    let m = SUBPATCHES;
    let cols = q + 1;
    // Rows (in t) split into m pieces: strips[b][i] is row i on piece b.
    let strips: Vec<Vec<Vec<Homogeneous<3>>>> = {
        let rows: Vec<Vec<Vec<Homogeneous<3>>>> = net.chunks(cols).map(|r| split(r, m)).collect();
        (0..m)
            .map(|b| rows.iter().map(|pieces| pieces[b].clone()).collect())
            .collect()
    };
    let mut worst = Curvature {
        ss: 0.0,
        st: 0.0,
        tt: 0.0,
    };
    let scale = (m * m) as f64;
    for strip in &strips {
        // Columns (in s) of this strip, split into m pieces.
        let columns: Vec<Vec<Vec<Homogeneous<3>>>> = (0..cols)
            .map(|j| split(&strip.iter().map(|row| row[j]).collect::<Vec<_>>(), m))
            .collect();
        for a in 0..m {
            let mut sub = Vec::with_capacity(net.len());
            for i in 0..=p {
                sub.extend(columns.iter().map(|pieces| pieces[a][i]));
            }
            let c = net_curvature(&sub, p, q);
            worst.ss = worst.ss.max(c.ss * scale);
            worst.st = worst.st.max(c.st * scale);
            worst.tt = worst.tt.max(c.tt * scale);
        }
    }
    worst
}

/// Bounds on `|S_ss|`, `|S_st|`, `|S_tt|` over the (sub-)patch of `net`
/// (see the module docs), each difference enlarged by the rounding of the
/// subdivided net and its own.
fn net_curvature(net: &[Homogeneous<3>], p: usize, q: usize) -> Curvature {
    let cols = q + 1;
    let points: Vec<Vector3<f64>> = net.iter().map(|h| h.wp / h.w).collect();
    let (lo, hi) = points.iter().fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), x| (lo.inf(x), hi.sup(x)),
    );
    let centre = (lo + hi) * 0.5;
    let radius = points
        .iter()
        .fold(0.0_f64, |m, x| m.max((x - centre).norm()));
    // (w(P − c), w) per control point.
    // The third entry is the size the rounding of `w(P − c)` is relative to
    // (the untranslated magnitude: subdivision rounds before translating).
    let a: Vec<(Vector3<f64>, f64, f64)> = net
        .iter()
        .map(|h| (h.wp - centre * h.w, h.w, h.wp.norm() + h.w * centre.norm()))
        .collect();
    let w_min = net.iter().fold(f64::INFINITY, |m, h| m.min(h.w));
    let at = |i: usize, j: usize| a[i * cols + j];
    // Largest |Σ cₖ xₖ| (vector and weight parts) over the stencil
    // `(di, dj, c)` placed at every (i, j) where it fits, plus rounding.
    let stencil = |shape: &[(usize, usize, f64)], rows: usize, columns: usize| {
        let mut best = (0.0_f64, 0.0_f64);
        for i in 0..rows {
            for j in 0..columns {
                let (mut x, mut w, mut size, mut wsize) = (Vector3::zeros(), 0.0, 0.0, 0.0);
                for &(di, dj, c) in shape {
                    let (v, vw, magnitude) = at(i + di, j + dj);
                    x += v * c;
                    w += vw * c;
                    size += magnitude * c.abs();
                    wsize += vw * c.abs();
                }
                let slack = 8.0 * (p + q + 2) as f64 * f64::EPSILON;
                best.0 = best.0.max(x.norm() + slack * size);
                best.1 = best.1.max(w.abs() + slack * wsize);
            }
        }
        best
    };
    let (pf, qf) = (p as f64, q as f64);
    let first_s = stencil(&[(0, 0, -1.0), (1, 0, 1.0)], p, cols);
    let first_t = stencil(&[(0, 0, -1.0), (0, 1, 1.0)], p + 1, q);
    let second_s = stencil(
        &[(0, 0, 1.0), (1, 0, -2.0), (2, 0, 1.0)],
        p.saturating_sub(1),
        cols,
    );
    let second_t = stencil(
        &[(0, 0, 1.0), (0, 1, -2.0), (0, 2, 1.0)],
        p + 1,
        q.saturating_sub(1),
    );
    let twist = stencil(
        &[(0, 0, 1.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, 1.0)],
        p,
        q,
    );
    let (a_s, w_s) = (pf * first_s.0, pf * first_s.1);
    let (a_t, w_t) = (qf * first_t.0, qf * first_t.1);
    let (a_ss, w_ss) = (
        pf * (pf - 1.0).max(0.0) * second_s.0,
        pf * (pf - 1.0).max(0.0) * second_s.1,
    );
    let (a_tt, w_tt) = (
        qf * (qf - 1.0).max(0.0) * second_t.0,
        qf * (qf - 1.0).max(0.0) * second_t.1,
    );
    let (a_st, w_st) = (pf * qf * twist.0, pf * qf * twist.1);
    let s_s = (a_s + w_s * radius) / w_min;
    let s_t = (a_t + w_t * radius) / w_min;
    let sane = |x: f64| if x.is_nan() { f64::INFINITY } else { x };
    Curvature {
        ss: sane((a_ss + 2.0 * w_s * s_s + w_ss * radius) / w_min),
        st: sane((a_st + w_s * s_t + w_t * s_s + w_st * radius) / w_min),
        tt: sane((a_tt + 2.0 * w_t * s_t + w_tt * radius) / w_min),
    }
}

/// Disjoint sets of direction nodes (path halving, union by index).
struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}

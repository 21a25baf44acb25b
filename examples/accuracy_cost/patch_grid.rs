//! A uniform triangulation of Bézier patches with a deviation bound: what
//! the triangle-mesh baseline ray-casts for patches.
//!
//! Each patch's parameter square is cut into `n_u × n_v` equal cells, each
//! split into two triangles through grid points of the surface. For linear
//! interpolation on a triangle, at a point `x` with barycentric weights
//! `λᵢ` of the corners `xᵢ`, Taylor's theorem about `x` gives
//! `S(x) − L(x) = −½ Σ λᵢ D²S(ξᵢ)[xᵢ − x, xᵢ − x]`, and with
//! `|D²S[w, w]| ≤ M_uu w_u² + 2M_uv|w_u w_v| + M_vv w_v²`,
//! `Σλᵢ(uᵢ − u)² ≤ Δu²/4` (the variance of a two-point law) and
//! Cauchy–Schwarz for the mixed term, every surface point is within
//!
//! `bound = (M_uu Δu² + 2 M_uv Δu Δv + M_vv Δv²) / 8`
//!
//! of the mesh, where `M_uu = m(m − 1)·max|Δ²_u P|`,
//! `M_uv = m n·max|Δ_u Δ_v P|`, `M_vv = n(n − 1)·max|Δ²_v P|` bound the
//! second partials' lengths (convex hull of their Bézier nets). The grid of
//! each patch is the smallest found (growing the side whose term dominates
//! by steps of 20 %) whose bound is within the tolerance.

use revolve::nalgebra::Point3;
use revolve::{BezierSurface, Surface};

/// The bounds `(M_uu, M_uv, M_vv)` of a patch's second partials.
pub fn second_partial_bounds(patch: &BezierSurface) -> (f64, f64, f64) {
    let p = patch.points();
    let (m, n) = patch.degrees();
    let mut b = (0.0_f64, 0.0_f64, 0.0_f64);
    for i in 0..=m {
        for j in 0..=n {
            if i + 2 <= m {
                let d = p[i + 2][j] - 2.0 * p[i + 1][j].coords + p[i][j].coords;
                b.0 = b.0.max(d.coords.norm());
            }
            if i < m && j < n {
                let d = p[i + 1][j + 1] - p[i + 1][j] - (p[i][j + 1] - p[i][j]);
                b.1 = b.1.max(d.norm());
            }
            if j + 2 <= n {
                let d = p[i][j + 2] - 2.0 * p[i][j + 1].coords + p[i][j].coords;
                b.2 = b.2.max(d.coords.norm());
            }
        }
    }
    let (m, n) = (m as f64, n as f64);
    (m * (m - 1.0) * b.0, m * n * b.1, n * (n - 1.0) * b.2)
}

/// The deviation bound of an `n_u × n_v` grid for second-partial bounds `m`.
pub fn grid_bound(m: (f64, f64, f64), n_u: usize, n_v: usize) -> f64 {
    let (du, dv) = (1.0 / n_u as f64, 1.0 / n_v as f64);
    (m.0 * du * du + 2.0 * m.1 * du * dv + m.2 * dv * dv) / 8.0
}

/// The grid `(n_u, n_v)` of one patch for `tolerance`, with its bound, or
/// `None` if it would need more than `max_cells` cells.
pub fn grid_for(
    patch: &BezierSurface,
    tolerance: f64,
    max_cells: usize,
) -> Option<(usize, usize, f64)> {
    let m = second_partial_bounds(patch);
    let (mut n_u, mut n_v) = (1usize, 1usize);
    loop {
        let bound = grid_bound(m, n_u, n_v);
        if bound <= tolerance {
            return Some((n_u, n_v, bound));
        }
        let mixed = m.1 / (n_u * n_v) as f64;
        let term_u = m.0 / (n_u * n_u) as f64 + mixed;
        let term_v = m.2 / (n_v * n_v) as f64 + mixed;
        let grow = |n: usize| (n + 1).max((n as f64 * 1.2).ceil() as usize);
        if term_u >= term_v {
            n_u = grow(n_u);
        } else {
            n_v = grow(n_v);
        }
        if n_u.saturating_mul(n_v) > max_cells {
            return None;
        }
    }
}

/// A triangle mesh and its deviation bound.
pub struct GridMesh {
    pub positions: Vec<Point3<f64>>,
    pub triangles: Vec<[u32; 3]>,
    /// Every surface point is within `bound` of the mesh.
    pub bound: f64,
}

/// A uniform mesh of `patches` within `tolerance`: positions, triangles
/// (triangles with two equal corners, on collapsed edges, left out) and the
/// largest bound over the patches. `None` if it would exceed
/// `max_triangles`.
pub fn grid_mesh(
    patches: &[BezierSurface],
    tolerance: f64,
    max_triangles: usize,
) -> Option<GridMesh> {
    let grids: Vec<(usize, usize, f64)> = patches
        .iter()
        .map(|p| grid_for(p, tolerance, max_triangles / 2))
        .collect::<Option<_>>()?;
    let cells: usize = grids.iter().map(|g| g.0 * g.1).sum();
    if 2 * cells > max_triangles {
        return None;
    }
    let mut positions = Vec::new();
    let mut triangles = Vec::with_capacity(2 * cells);
    let mut bound = 0.0_f64;
    for (patch, &(n_u, n_v, b)) in patches.iter().zip(&grids) {
        bound = bound.max(b);
        let base = positions.len();
        for i in 0..=n_u {
            for j in 0..=n_v {
                positions.push(patch.eval(i as f64 / n_u as f64, j as f64 / n_v as f64));
            }
        }
        let index = |i: usize, j: usize| (base + i * (n_v + 1) + j) as u32;
        for i in 0..n_u {
            for j in 0..n_v {
                let (a, b, c, d) = (
                    index(i, j),
                    index(i + 1, j),
                    index(i + 1, j + 1),
                    index(i, j + 1),
                );
                for tri in [[a, b, c], [a, c, d]] {
                    let p = |k: usize| positions[tri[k] as usize];
                    if p(0) != p(1) && p(1) != p(2) && p(2) != p(0) {
                        triangles.push(tri);
                    }
                }
            }
        }
    }
    Some(GridMesh {
        positions,
        triangles,
        bound,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::Rng;

    /// The bound holds: random surface points are within it of the
    /// triangle over their cell (closest point on the two triangles,
    /// computed by brute force over a fine barycentric grid bounds the
    /// distance from above; the parametric bound must exceed the true one).
    #[test]
    fn the_grid_bound_holds_and_shrinks_with_the_tolerance() {
        let patch = crate::common::tensor_shapes::folded_bicubic();
        let (n_u, n_v, bound) = grid_for(&patch, 1e-2, 1 << 20).unwrap();
        assert!(bound <= 1e-2);
        let mut rng = Rng(3);
        let mut worst = 0.0_f64;
        for _ in 0..2000 {
            let (u, v) = (rng.unit(), rng.unit());
            let (fu, fv) = (u * n_u as f64, v * n_v as f64);
            let (i, j) = ((fu as usize).min(n_u - 1), (fv as usize).min(n_v - 1));
            let (s, r) = (fu - i as f64, fv - j as f64);
            let corner = |a: usize, b: usize| {
                patch.eval((i + a) as f64 / n_u as f64, (j + b) as f64 / n_v as f64)
            };
            // The point of the mesh at the same parameters (a, b, c or a, c, d).
            let l = if s >= r {
                corner(0, 0) + (corner(1, 0) - corner(0, 0)) * s + (corner(1, 1) - corner(1, 0)) * r
            } else {
                corner(0, 0) + (corner(0, 1) - corner(0, 0)) * r + (corner(1, 1) - corner(0, 1)) * s
            };
            worst = worst.max((patch.eval(u, v) - l).norm());
        }
        assert!(worst <= bound, "measured {worst:e} > bound {bound:e}");
        assert!(worst > bound / 20.0, "bound {bound:e} far from {worst:e}");
        let (fine_u, fine_v, fine) = grid_for(&patch, 1e-4, 1 << 20).unwrap();
        assert!(fine <= 1e-4 && fine_u * fine_v > n_u * n_v);
        assert_eq!(grid_for(&patch, 1e-12, 1000), None);
    }

    #[test]
    fn collapsed_edges_leave_no_degenerate_triangles() {
        let pot = crate::common::teapot::patches();
        let mesh = grid_mesh(&pot, 1e-2, 1 << 22).unwrap();
        assert!(mesh.bound <= 1e-2);
        for t in &mesh.triangles {
            let p = |k: usize| mesh.positions[t[k] as usize];
            assert!((p(1) - p(0)).cross(&(p(2) - p(0))).norm() > 0.0);
        }
        assert!(grid_mesh(&pot, 1e-2, 100).is_none());
    }
}

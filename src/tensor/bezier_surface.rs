//! Tensor-product Bézier surfaces.

use super::control_net::{flatten_points, rows_and_columns};
use super::patch::Patch;
use super::patch_table::PatchTable;
use super::tessellate::tessellate_patches;
use crate::Mesh;
use crate::curve::{Homogeneous, check_derivatives};
use crate::{Aabb, Error, Hit, Intersect, PatchBounds, Ray, Surface, Tolerance};
use nalgebra::{Point3, Unit, Vector3};

/// A tensor-product Bézier surface
/// `S(u, v) = Σᵢ Σⱼ Pᵢⱼ Bᵢᵐ(u) Bⱼⁿ(v)` on `[0, 1]²`, of degrees
/// `(m, n) = (rows − 1, cols − 1)`; `points[i][j]`, `i` along `u`.
///
/// Evaluation is tensor de Casteljau (each row in `v`, then the column of
/// results in `u`; Farin, *Curves and Surfaces for CAGD*, ch. 16), without a
/// heap allocation up to degree 16 × 16; the partials `∂S/∂u`, `∂S/∂v` come
/// from the last de Casteljau levels, analytically.
///
/// # Edge rules
/// - Parameters outside `[0, 1]` evaluate at the nearest edge; NaN at 0.
/// - [`normal`](crate::Surface::normal) is `∂S/∂u × ∂S/∂v` normalized
///   (negated on a [reversed](BezierSurface::reversed) surface). Where that
///   cross product is negligible (below `(10⁻⁷·D)²` for the typical first
///   derivative `D` = net extent × degree / parameter width; a *collapsed
///   edge*, all points of a row equal, as on the teapot's lid), the normal is
///   the limit from inside the domain: with the inward direction `d` toward
///   the domain's centre, `N(x + h·d) = h·N₁ + O(h²)` with
///   `N₁ = d_u(S_uu×S_v + S_u×S_uv) + d_v(S_uv×S_v + S_u×S_vv)` (second
///   partials, analytic), so the limit is `N₁/|N₁|`. At a *collapsed
///   corner* (one partial vanishes there but neither edge collapses, as
///   where `P₁₀ = P₀₀`) the normal along the inward direction `(a, b)` is
///   `∝ a·A + b·B` (with `S_u = 0`: `A = S_uu×S_v`, `B = S_uv×S_v`; with
///   `S_v = 0`: `A = S_u×S_uv`, `B = S_u×S_vv`, each `A`, `B` signed by
///   the inward side): the normal is their common direction when they point
///   the same way (within `10⁻⁷`), and `None` (a cone point) when not. On a collapsed edge
///   of the domain that limit is the tangent plane only if every direction
///   leaving the edge lies in it (the net's first differences off the edge
///   are all perpendicular to it, within `10⁻⁷`, as on the teapot's lid,
///   whose second row is level with its apex); otherwise the edge point is a
///   cone point and the normal is `None`. Where `N₁` vanishes too on a
///   collapsed edge whose next rows collapse onto the same point `P` (a
///   pole on a tripled control point), the first row `k` that leaves `P`
///   gives the limit exactly: `S − P ∝ sᵏ·F(t)` with
///   `F(t) = Σⱼ Bⱼ(t)·wₖⱼ(Pₖⱼ − P)`, so the normal is along `±F × F′`; it
///   is the tangent plane only if every `wₖⱼ(Pₖⱼ − P)` along the edge is
///   perpendicular to it (else a cone point, `None`). Otherwise (two
///   collapsed edges meeting at a corner), the normals at steps
///   `h = 10⁻³, 10⁻³·⁵, …, 10⁻⁸` of the domain inside along `d` are
///   computed while the partials' cross product is resolved (sine of their
///   angle `≥ 10⁻⁶`, each partial above its rounding); if successive ones
///   converge (within `10⁻³`) the last is the normal. `None` where none of
///   these gives a normal: no tangent plane.
/// - [`bound_patch`](crate::PatchBounds::bound_patch) is the box of the
///   sub-patch's control net (de Casteljau subdivision; convex hull
///   property), padded for rounding.
///
/// ```
/// use revolve::{BezierSurface, Surface};
/// use revolve::nalgebra::Point3;
///
/// // A bilinear patch: S(u, v) = (u, v, u·v).
/// let s = BezierSurface::new(vec![
///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
/// ])?;
/// let p = s.eval(0.5, 0.25);
/// assert!((p - Point3::new(0.5, 0.25, 0.125)).norm() < 1e-15);
/// let (su, sv) = s.partials(0.5, 0.25);
/// assert!((su.z - 0.25).abs() < 1e-15 && (sv.z - 0.5).abs() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSurface {
    points: Vec<Vec<Point3<f64>>>,
    table: PatchTable,
}

impl BezierSurface {
    /// The same surface with the given intersection accuracy (the default
    /// is full double precision), [clamped](Tolerance::clamped) into the
    /// valid range: a point of the surface within `tolerance.relative` of
    /// its size (at least `10⁻¹²`) off the ray counts as a hit (so a ray
    /// passing that close to a silhouette touches it), and boxes whose image
    /// is that small are decided at once. The search is certified and every
    /// hit polished to full precision at every tolerance.
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.table.tolerance = tolerance.clamped();
        self
    }

    /// The intersection accuracy.
    pub fn tolerance(&self) -> &Tolerance {
        &self.table.tolerance
    }

    /// The Bézier surface of the control grid `points[i][j]` (`i` along
    /// `u`), of degrees `(rows − 1, cols − 1)`, on `[0, 1]²`.
    ///
    /// # Errors
    /// [`Error::EmptyGrid`] (no rows, or empty rows),
    /// [`Error::RaggedGrid`] (rows of different lengths),
    /// [`Error::NonFiniteGridPoint`] / [`Error::GridCoordinateTooLarge`] with
    /// the row and column, [`Error::DerivativeOverflow`] when a
    /// hodograph of a row or a column could exceed
    /// [`MAX_DERIVATIVE`](crate::MAX_DERIVATIVE).
    pub fn new(points: Vec<Vec<Point3<f64>>>) -> Result<Self, Error> {
        let (flat, cols) = flatten_points(&points)?;
        let coords: Vec<Vector3<f64>> = flat.iter().map(|p| p.coords).collect();
        let (rows, columns) = rows_and_columns(&coords, cols);
        for line in rows.iter().chain(&columns) {
            check_derivatives(line, 1.0)?;
        }
        Ok(Self::from_valid_parts(points))
    }

    /// Wraps a grid the crate knows to be valid.
    pub(crate) fn from_valid_parts(points: Vec<Vec<Point3<f64>>>) -> Self {
        let rows = points.len();
        let cols = points[0].len();
        let net = points
            .iter()
            .flatten()
            .map(|p| Homogeneous::new(p, 1.0))
            .collect();
        let table = PatchTable::new(
            (rows - 1, cols - 1),
            vec![0.0, 1.0],
            vec![0.0, 1.0],
            vec![Patch {
                u: (0.0, 1.0),
                v: (0.0, 1.0),
                net,
            }],
        );
        BezierSurface { points, table }
    }

    /// The control grid, `points[i][j]` with `i` along `u`.
    pub fn points(&self) -> &[Vec<Point3<f64>>] {
        &self.points
    }

    /// The same surface with the opposite orientation: the unit normal
    /// becomes `−(∂S/∂u × ∂S/∂v)/|∂S/∂u × ∂S/∂v|` (its limits at collapsed
    /// edges negated too), while the control grid, the points, the
    /// [`partials`](Surface::partials) (unchanged, so no longer crossing to
    /// the normal), the parameters and the hits' `t`, `point` and `uv` are
    /// exactly the original's. Every normal is negated: [`Surface::normal`],
    /// each [`Hit`]'s from [`Intersect`], and [`tessellate`](Self::tessellate)'s
    /// vertex normals, whose triangles are wound the other way to match.
    /// Where no tangent plane exists a hit's normal faces the ray as before.
    /// `reversed().reversed()` is the original.
    ///
    /// ```
    /// use revolve::{BezierSurface, Intersect, Ray, Surface};
    /// use revolve::nalgebra::{Point3, Vector3};
    ///
    /// // The unit square in z = 0, its normal +z.
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0)],
    /// ])?;
    /// let r = s.reversed();
    /// assert_eq!(s.normal(0.5, 0.5).unwrap().into_inner(), Vector3::z());
    /// assert_eq!(r.normal(0.5, 0.5).unwrap().into_inner(), -Vector3::z());
    /// assert_eq!(r.partials(0.5, 0.5), s.partials(0.5, 0.5));
    /// let ray = Ray::new(Point3::new(0.25, 0.5, 1.0), -Vector3::z());
    /// let (a, b) = (s.intersect(&ray, 0.0, 9.0).unwrap(), r.intersect(&ray, 0.0, 9.0).unwrap());
    /// assert_eq!((a.t, a.point, a.uv, -a.normal), (b.t, b.point, b.uv, b.normal));
    /// assert_eq!(r.reversed(), s);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn reversed(&self) -> Self {
        let mut surface = self.clone();
        surface.table.reversed = !surface.table.reversed;
        surface
    }

    /// Whether the orientation is [reversed](Self::reversed).
    pub(crate) fn is_reversed(&self) -> bool {
        self.table.reversed
    }

    /// The degrees `(m, n) = (rows − 1, cols − 1)`.
    pub fn degrees(&self) -> (usize, usize) {
        self.table.degrees
    }

    /// The patch table (for the nearest-point search).
    pub(crate) fn table(&self) -> &PatchTable {
        &self.table
    }

    /// The second partial derivatives `(S_uu, S_uv, S_vv)` at `(u, v)`
    /// (clamped into the domain), analytic.
    pub fn second_partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let d = self.table.jet(u, v, 2);
        (d[2][0], d[1][1], d[0][2])
    }

    /// A triangle mesh within `tolerance` of the surface: the patch cut
    /// into a grid of equal cells, two triangles each, so fine that the
    /// second-derivative bound `(h²M_uu + 2hk·M_uv + k²M_vv)/8` (Filip,
    /// Magedson & Markot 1986; `M` from the net's second differences) is
    /// below the tolerance; see [`Mesh`] and the bound it reports in
    /// [`Mesh::bound`]. Normals are the surface's (the limit at collapsed
    /// edges, where zero-area triangles are left out; negated, with the
    /// triangles wound the other way, on a [reversed](Self::reversed)
    /// surface), `uvs` are `(u, v)`.
    ///
    /// ```
    /// use revolve::BezierSurface;
    /// use revolve::nalgebra::Point3;
    ///
    /// // A saddle: S(u, v) = (u, v, u·v).
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let mesh = s.tessellate(1e-3)?;
    /// assert!(mesh.bound <= 1e-3);
    /// // The vertices lie on the surface; their uvs are its parameters.
    /// for (x, &(u, v)) in mesh.positions.iter().zip(&mesh.uvs) {
    ///     assert!((x - Point3::new(u, v, u * v)).norm() < 1e-15);
    /// }
    /// let mut obj = Vec::new();
    /// mesh.write_obj(&mut obj).unwrap();
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] (not finite and positive);
    /// [`Error::ToleranceTooSmall`] below `10⁻¹⁰` of the largest control
    /// coordinate; [`Error::MeshTooLarge`] where the mesh would exceed
    /// [`Mesh::MAX_VERTICES`] (its `min` is a tolerance that fits);
    /// [`Error::AllocationFailed`].
    pub fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        let reversed = self.table.reversed;
        tessellate_patches(self.table.degrees, &self.table.patches, tolerance, |_| {
            reversed
        })
    }
}

impl Surface for BezierSurface {
    fn domain(&self) -> [(f64, f64); 2] {
        self.table.domain()
    }

    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        self.table.eval(u, v)
    }

    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        self.table.partials(u, v)
    }

    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        self.table.normal(u, v)
    }
}

impl PatchBounds for BezierSurface {
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        self.table.bound(u, v)
    }
}

/// Ray intersection by Bézier clipping and subdivision of the ray's two
/// plane distances on each Bézier patch (the patches cut once into up to 256
/// nearly bilinear pieces, visited through a hierarchy over their boxes): a
/// box is dropped or shrunk only where a certain sign rules a hit out; a box
/// that Krawczyk's test proves to hold one root, or one below `2⁻¹⁴` a side,
/// is finished by Newton's method, and only points on the surface to the
/// surface's tolerance (`with_tolerance`) are hits. `Hit::uv` is `(u, v)` in
/// the surface's parameters; the normal follows `∂S/∂u × ∂S/∂v` (the limit
/// at collapsed edges).
impl Intersect for BezierSurface {
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.table.hit(ray, t_min, t_max)
    }

    /// Stops at the first patch piece with a hit.
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.table.occluded(ray, t_min, t_max)
    }

    fn bounds(&self) -> Aabb {
        self.table.bounds()
    }
}

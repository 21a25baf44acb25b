//! Tensor-product B-spline surfaces, and the spline core they share with the
//! rational ones (knot refinement into Bézier patches, knot insertion).

use super::BezierSurface;
use super::control_net::{flatten_points, flatten_weights, rows_and_columns, weight_scale};
use super::patch::Patch;
use super::patch_table::{PatchTable, check_rational_partials};
use super::tessellate::tessellate_patches;
use crate::Mesh;
use crate::bernstein::{Coefficient, lerp};
use crate::curve::{
    Homogeneous, boehm_insert, check_derivative_points, knot_to_insert, validate_knots,
};
use crate::limits::MAX_COORDINATE;
use crate::{
    Aabb, Error, Hit, Intersect, ParameterDirection, PatchBounds, Ray, Surface, Tolerance,
};
use nalgebra::{Point1, Point3, Unit, Vector3};

/// A tensor-product B-spline surface
/// `S(u, v) = Σᵢ Σⱼ Pᵢⱼ Nᵢ,ₚ(u) Nⱼ,q(v)` of degrees `(p, q)`, knot vectors
/// `(U, V)` and control grid `points[i][j]` (`i` along `u`): each knot vector
/// follows the rules of [`BSpline::new`](crate::BSpline::new) for its
/// direction (`rows + p + 1` knots in `u`, `cols + q + 1` in `v`), and the
/// domain is `[U_p, U_rows] × [V_q, V_cols]`.
///
/// At construction the surface is cut into its Bézier patches (Boehm knot
/// insertion of every domain knot up to multiplicity `p`, resp. `q`, per
/// column and per row; Piegl & Tiller, *The NURBS Book*, §5.4); evaluation
/// locates the patch by binary search and runs tensor de Casteljau on it
/// (see [`BezierSurface`]), without heap allocation up to degree 16 × 16.
///
/// # Edge rules
/// - Knot rectangles are half-open like a B-spline curve's spans: at an
///   interior knot the value is the limit from above; the domain's end
///   belongs to the last patch.
/// - Parameters outside the domain evaluate at the nearest edge; NaN at the
///   start.
/// - Normals and bounds as for [`BezierSurface`] (the limit at collapsed
///   edges; the box of the sub-patches' control nets).
///
/// ```
/// use revolve::{BSplineSurface, Surface};
/// use revolve::nalgebra::Point3;
///
/// // A biquadratic plane z = 0 over a 3 × 3 grid, two spans in u.
/// let grid: Vec<Vec<Point3<f64>>> = (0..3)
///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, 0.0)).collect())
///     .collect();
/// let s = BSplineSurface::new(
///     (1, 2),
///     (vec![0.0, 0.0, 0.5, 1.0, 1.0], vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
///     grid,
/// )?;
/// assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
/// assert!((s.eval(0.75, 0.5) - Point3::new(1.5, 1.0, 0.0)).norm() < 1e-15);
/// assert_eq!(s.to_bezier_patches().len(), 2);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineSurface {
    core: TensorSpline,
}

/// One polynomial piece of a [`BSplineSurface`]: on the knot rectangle
/// `u × v` the spline equals `surface((u − u₀)/(u₁ − u₀), (v − v₀)/(v₁ − v₀))`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatch {
    /// The knot interval `(u₀, u₁)` in `u`, `u₀ < u₁`.
    pub u: (f64, f64),
    /// The knot interval `(v₀, v₁)` in `v`, `v₀ < v₁`.
    pub v: (f64, f64),
    /// The piece over `[0, 1]²`, of the spline's degrees.
    pub surface: BezierSurface,
}

impl BSplineSurface {
    /// The same surface with the given intersection accuracy (the default
    /// is full double precision), [clamped](Tolerance::clamped) into the
    /// valid range: a point of the surface within `tolerance.relative` of
    /// its size (at least `10⁻¹²`) off the ray counts as a hit (so a ray
    /// passing that close to a silhouette touches it), and boxes whose image
    /// is that small are decided at once. The search is certified and every
    /// hit polished to full precision at every tolerance.
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.core.table.tolerance = tolerance.clamped();
        self
    }

    /// The intersection accuracy.
    pub fn tolerance(&self) -> &Tolerance {
        &self.core.table.tolerance
    }

    /// A B-spline surface of degrees `(p, q)`, knot vectors `(U, V)` and
    /// control grid `points[i][j]`.
    ///
    /// # Errors
    /// The grid's ([`Error::EmptyGrid`], [`Error::RaggedGrid`],
    /// [`Error::NonFiniteGridPoint`] / [`Error::GridCoordinateTooLarge`] with
    /// the row and column), then the knot checks of
    /// [`BSpline::new`](crate::BSpline::new) for `U` (against the rows), then
    /// for `V` (against the columns), each wrapped in
    /// [`Error::SurfaceKnots`] with its direction: [`Error::DegreeTooHigh`],
    /// [`Error::KnotCount`], [`Error::NonFiniteKnot`], [`Error::KnotTooLarge`],
    /// [`Error::DecreasingKnots`], [`Error::KnotGapTooSmall`],
    /// [`Error::KnotMultiplicity`], [`Error::EmptyDomain`]; then
    /// [`Error::DerivativeOverflow`] when a derivative spline of a row or a
    /// column could exceed [`MAX_DERIVATIVE`](crate::MAX_DERIVATIVE).
    pub fn new(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: Vec<Vec<Point3<f64>>>,
    ) -> Result<Self, Error> {
        Ok(BSplineSurface {
            core: TensorSpline::new(degrees, knots, points, None)?,
        })
    }

    /// The degrees `(p, q)`.
    pub fn degrees(&self) -> (usize, usize) {
        self.core.degrees
    }

    /// The knot vectors `(U, V)`.
    pub fn knots(&self) -> (&[f64], &[f64]) {
        (&self.core.knots.0, &self.core.knots.1)
    }

    /// The control grid, `points[i][j]` with `i` along `u`.
    pub fn points(&self) -> &[Vec<Point3<f64>>] {
        &self.core.points
    }

    /// The same surface with the opposite orientation: the unit normal
    /// becomes `−(∂S/∂u × ∂S/∂v)/|∂S/∂u × ∂S/∂v|`, while the grid, knots,
    /// points, [`partials`](Surface::partials) (unchanged), parameters and
    /// hits' `t`, `point` and `uv` are exactly the original's; every normal
    /// is negated as for [`BezierSurface::reversed`] (the tessellation's
    /// triangles wound the other way), and [`to_bezier_patches`](Self::to_bezier_patches)
    /// and knot insertion keep the orientation. `reversed().reversed()` is
    /// the original.
    pub fn reversed(&self) -> Self {
        Self {
            core: self.core.reversed(),
        }
    }

    /// Whether the orientation is [reversed](Self::reversed).
    #[cfg(feature = "serde")]
    pub(crate) fn is_reversed(&self) -> bool {
        self.core.table.reversed
    }

    /// The second partial derivatives `(S_uu, S_uv, S_vv)` at `(u, v)`
    /// (clamped into the domain), analytic.
    pub fn second_partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let d = self.core.table.jet(u, v, 2);
        (d[2][0], d[1][1], d[0][2])
    }

    /// A triangle mesh within `tolerance` of the surface, each Bézier patch
    /// cut as in [`BezierSurface::tessellate`]; neighbouring patches get the
    /// same vertices along their common edge (welded), so the mesh is
    /// watertight across the knot lines.
    ///
    /// # Errors
    /// As [`BezierSurface::tessellate`].
    pub fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        self.core.tessellate(tolerance)
    }

    /// The Bézier patches, one per non-empty knot rectangle of the domain,
    /// `u`-span major (all `v`-spans of the first `u`-span first).
    pub fn to_bezier_patches(&self) -> Vec<BezierPatch> {
        self.core
            .table
            .patches
            .iter()
            .map(|patch| {
                let (points, _) = self.core.patch_grid(patch);
                let surface = BezierSurface::from_valid_parts(points);
                BezierPatch {
                    u: patch.u,
                    v: patch.v,
                    surface: if self.core.table.reversed {
                        surface.reversed()
                    } else {
                        surface
                    },
                }
            })
            .collect()
    }

    /// The same surface with the knot `t` inserted `times` times into `U`
    /// (Boehm's algorithm on every column of the grid; Piegl & Tiller eq.
    /// 5.15). A `t` within rounding of an existing knot inserts that knot.
    ///
    /// # Errors
    /// [`Error::SurfaceKnots`] in `u` wrapping
    /// [`Error::ParameterOutOfDomain`] (NaN or outside the `u` domain) or
    /// [`Error::KnotMultiplicity`] (beyond `p + 1`); the checks of
    /// [`new`](Self::new) on the result.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..3)
    ///     .map(|i| (0..2).map(|j| Point3::new(i as f64, j as f64, (i * i) as f64)).collect())
    ///     .collect();
    /// let k = (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = BSplineSurface::new((2, 1), k, grid)?;
    /// let refined = s.insert_knot_u(0.25, 2)?;
    /// assert_eq!(refined.points().len(), 5);
    /// assert_eq!(refined.to_bezier_patches().len(), 2);
    /// for (u, v) in [(0.1, 0.2), (0.25, 0.5), (0.9, 1.0)] {
    ///     assert!((refined.eval(u, v) - s.eval(u, v)).norm() < 1e-15);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn insert_knot_u(&self, t: f64, times: usize) -> Result<Self, Error> {
        Ok(BSplineSurface {
            core: self.core.insert_knot(0, t, times)?,
        })
    }

    /// The same surface with the knot `t` inserted `times` times into `V`
    /// (Boehm's algorithm on every row).
    ///
    /// # Errors
    /// As [`insert_knot_u`](Self::insert_knot_u), for `v`.
    pub fn insert_knot_v(&self, t: f64, times: usize) -> Result<Self, Error> {
        Ok(BSplineSurface {
            core: self.core.insert_knot(1, t, times)?,
        })
    }

    /// The shared core (for the rational surface's conversion).
    pub(crate) fn core(&self) -> &TensorSpline {
        &self.core
    }

    /// The surface of a core the crate built.
    pub(super) fn from_core(core: TensorSpline) -> Self {
        BSplineSurface { core }
    }
}

impl Surface for BSplineSurface {
    fn domain(&self) -> [(f64, f64); 2] {
        self.core.table.domain()
    }

    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        self.core.table.eval(u, v)
    }

    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        self.core.table.partials(u, v)
    }

    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        self.core.table.normal(u, v)
    }
}

impl PatchBounds for BSplineSurface {
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        self.core.table.bound(u, v)
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
impl Intersect for BSplineSurface {
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.core.table.hit(ray, t_min, t_max)
    }

    /// Stops at the first patch piece with a hit.
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.core.table.occluded(ray, t_min, t_max)
    }

    fn bounds(&self) -> Aabb {
        self.core.table.bounds()
    }
}

/// A (rational or polynomial) tensor-product spline: the data and the
/// Bézier patch table shared by [`BSplineSurface`] and
/// [`NurbsSurface`](crate::NurbsSurface).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TensorSpline {
    pub(crate) degrees: (usize, usize),
    pub(crate) knots: (Vec<f64>, Vec<f64>),
    pub(crate) points: Vec<Vec<Point3<f64>>>,
    /// All ones for a polynomial spline.
    pub(crate) weights: Vec<Vec<f64>>,
    pub(crate) rational: bool,
    /// The power of two the weights are divided by in the patches.
    scale: f64,
    pub(crate) table: PatchTable,
}

/// Wraps a curve's knot error as the surface's in `direction`.
fn in_direction(direction: ParameterDirection) -> impl Fn(Error) -> Error {
    move |error| Error::SurfaceKnots {
        direction,
        error: Box::new(error),
    }
}

impl TensorSpline {
    /// The same spline with the opposite orientation (the surface kinds'
    /// `reversed`): only the table's flag changes.
    pub(crate) fn reversed(&self) -> Self {
        let mut spline = self.clone();
        spline.table.reversed = !spline.table.reversed;
        spline
    }

    /// Validates and builds (`weights: None` for a polynomial spline).
    pub(crate) fn new(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: Vec<Vec<Point3<f64>>>,
        weights: Option<Vec<Vec<f64>>>,
    ) -> Result<Self, Error> {
        let (_, cols) = flatten_points(&points)?;
        let rows = points.len();
        validate_knots(degrees.0, &knots.0, rows).map_err(in_direction(ParameterDirection::U))?;
        validate_knots(degrees.1, &knots.1, cols).map_err(in_direction(ParameterDirection::V))?;
        let rational = weights.is_some();
        let weights = match weights {
            Some(w) => flatten_weights(&w, rows, cols)?
                .chunks(cols)
                .map(<[f64]>::to_vec)
                .collect(),
            None => vec![vec![1.0; cols]; rows],
        };
        Self::from_checked_parts(degrees, knots, points, weights, rational)
    }

    /// Builds from valid grids and knots, checking the derivative splines of
    /// every row and column (in homogeneous coordinates when rational).
    fn from_checked_parts(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: Vec<Vec<Point3<f64>>>,
        weights: Vec<Vec<f64>>,
        rational: bool,
    ) -> Result<Self, Error> {
        let cols = points[0].len();
        let flat_w: Vec<f64> = weights.iter().flatten().copied().collect();
        let scale = if rational { weight_scale(&flat_w) } else { 1.0 };
        let homogeneous: Vec<Homogeneous<3>> = points
            .iter()
            .flatten()
            .zip(&flat_w)
            .map(|(p, &w)| Homogeneous::new(p, w / scale))
            .collect();
        let wp: Vec<Point3<f64>> = homogeneous.iter().map(|h| Point3::from(h.wp)).collect();
        let (wp_rows, wp_cols) = rows_and_columns(&wp, cols);
        for row in &wp_rows {
            check_derivative_points(degrees.1, &knots.1, row)?;
        }
        for col in &wp_cols {
            check_derivative_points(degrees.0, &knots.0, col)?;
        }
        if rational {
            let w: Vec<Point1<f64>> = homogeneous.iter().map(|h| Point1::new(h.w)).collect();
            let (w_rows, w_cols) = rows_and_columns(&w, cols);
            for row in &w_rows {
                check_derivative_points(degrees.1, &knots.1, row)?;
            }
            for col in &w_cols {
                check_derivative_points(degrees.0, &knots.0, col)?;
            }
        }
        let table = patch_table(degrees, &knots, &homogeneous, cols);
        if rational {
            check_rational_partials(&table)?;
        }
        Ok(TensorSpline {
            degrees,
            knots,
            points,
            weights,
            rational,
            scale,
            table,
        })
    }

    /// The points and weights of a patch's net (weights as given, not
    /// scaled).
    pub(crate) fn patch_grid(&self, patch: &Patch) -> (Vec<Vec<Point3<f64>>>, Vec<Vec<f64>>) {
        let cols = self.degrees.1 + 1;
        // The net's points are convex combinations of the grid's, whose
        // coordinates are within MAX_COORDINATE: so are theirs, up to the
        // rounding the clamp takes back (so the nets pass the constructors).
        let within = |p: Point3<f64>| p.map(|c| c.clamp(-MAX_COORDINATE, MAX_COORDINATE));
        let mut points = Vec::with_capacity(self.degrees.0 + 1);
        let mut weights = Vec::with_capacity(self.degrees.0 + 1);
        for row in patch.net.chunks(cols) {
            if self.rational {
                points.push(
                    row.iter()
                        .map(|h| within(Point3::from(h.wp / h.w)))
                        .collect(),
                );
                weights.push(row.iter().map(|h| h.w * self.scale).collect());
            } else {
                points.push(row.iter().map(|h| within(Point3::from(h.wp))).collect());
                weights.push(vec![1.0; cols]);
            }
        }
        (points, weights)
    }

    /// The spline with `t` inserted `times` times into the knots of
    /// direction `axis` (0: `u`, per column; 1: `v`, per row).
    pub(crate) fn insert_knot(&self, axis: usize, t: f64, times: usize) -> Result<Self, Error> {
        let p = if axis == 0 {
            self.degrees.0
        } else {
            self.degrees.1
        };
        let knots = if axis == 0 {
            &self.knots.0
        } else {
            &self.knots.1
        };
        let domain = self.table.domain()[axis];
        let direction = if axis == 0 {
            ParameterDirection::U
        } else {
            ParameterDirection::V
        };
        let t = knot_to_insert(knots, p, domain, t, times).map_err(in_direction(direction))?;
        // The lines along the axis: columns for u, rows for v.
        let cols = self.points[0].len();
        let pairs: Vec<(Point3<f64>, f64)> = self
            .points
            .iter()
            .flatten()
            .copied()
            .zip(self.weights.iter().flatten().copied())
            .collect();
        let (rows, columns) = rows_and_columns(&pairs, cols);
        let mut lines = if axis == 0 { columns } else { rows };
        let mut knots = knots.clone();
        let rational = self.rational;
        let combine = |a: (Point3<f64>, f64), b: (Point3<f64>, f64), alpha: f64| {
            if rational {
                let h = lerp(
                    Homogeneous::new(&a.0, a.1),
                    Homogeneous::new(&b.0, b.1),
                    alpha,
                );
                (Point3::from(h.wp / h.w), h.w)
            } else {
                (Point3::from(lerp(a.0.coords, b.0.coords, alpha)), 1.0)
            }
        };
        for _ in 0..times {
            let k = insertion_span(&knots, p, lines[0].len(), t);
            let mut new_knots = Vec::new();
            for line in &mut lines {
                let (kn, values) = boehm_insert(&knots, p, k, t, line, combine);
                *line = values;
                new_knots = kn;
            }
            knots = new_knots;
        }
        // Back to the row-major grid.
        let (points, weights): (Vec<Vec<Point3<f64>>>, Vec<Vec<f64>>) = if axis == 0 {
            let n = lines[0].len();
            (0..n).map(|i| lines.iter().map(|l| l[i]).unzip()).unzip()
        } else {
            lines.into_iter().map(|l| l.into_iter().unzip()).unzip()
        };
        let all_knots = if axis == 0 {
            (knots, self.knots.1.clone())
        } else {
            (self.knots.0.clone(), knots)
        };
        let mut spline =
            Self::from_checked_parts(self.degrees, all_knots, points, weights, rational)?;
        spline.table.reversed = self.table.reversed;
        Ok(spline)
    }

    /// The surface's mesh (see [`BSplineSurface::tessellate`]), turned the
    /// other way round when the orientation is reversed.
    pub(crate) fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        let reversed = self.table.reversed;
        tessellate_patches(self.table.degrees, &self.table.patches, tolerance, |_| {
            reversed
        })
    }
}

/// The non-empty span `k` (`t_k ≤ t ≤ t_{k+1}`, `p ≤ k < n`) to insert `t`
/// (inside the domain `[t_p, t_n]`) into: the span holding `t`, or for
/// `t = t_n` the last non-empty one.
pub(super) fn insertion_span(knots: &[f64], p: usize, n: usize, t: f64) -> usize {
    if t >= knots[n] {
        (p..n).rev().find(|&k| knots[k] < knots[n]).unwrap_or(p)
    } else {
        knots
            .partition_point(|&x| x <= t)
            .saturating_sub(1)
            .clamp(p, n - 1)
    }
}

/// Refines `lines` (control values along one direction, sharing `knots` of
/// degree `p`) until every knot of the domain `[t_p, t_n]` has multiplicity
/// at least `p`; returns the new knots. Each non-empty span `k` then has the
/// Bézier control values `k − p ..= k`.
fn refine_to_bezier<T: Coefficient>(knots: &[f64], p: usize, lines: &mut [Vec<T>]) -> Vec<f64> {
    let mut knots = knots.to_vec();
    let n = lines[0].len();
    let (start, end) = (knots[p], knots[n]);
    let mut values: Vec<f64> = knots
        .iter()
        .copied()
        .filter(|&x| x >= start && x <= end)
        .collect();
    values.dedup();
    for x in values {
        let multiplicity = knots.iter().filter(|&&k| k == x).count();
        for _ in multiplicity..p {
            let n = lines[0].len();
            let k = insertion_span(&knots, p, n, x);
            let mut new_knots = Vec::new();
            for line in lines.iter_mut() {
                let (kn, vals) = boehm_insert(&knots, p, k, x, line, lerp);
                *line = vals;
                new_knots = kn;
            }
            knots = new_knots;
        }
    }
    knots
}

/// The non-empty spans `k` of refined knots, with their intervals.
fn spans(knots: &[f64], p: usize, n: usize) -> Vec<(usize, (f64, f64))> {
    (p..n)
        .filter(|&k| knots[k] < knots[k + 1])
        .map(|k| (k, (knots[k], knots[k + 1])))
        .collect()
}

/// The Bézier patch table of a spline with the row-major homogeneous net.
fn patch_table(
    degrees: (usize, usize),
    knots: &(Vec<f64>, Vec<f64>),
    net: &[Homogeneous<3>],
    cols: usize,
) -> PatchTable {
    let (p, q) = degrees;
    let (_, mut columns) = rows_and_columns(net, cols);
    let ku = refine_to_bezier(&knots.0, p, &mut columns);
    let rows_n = columns[0].len();
    let mut rows: Vec<Vec<Homogeneous<3>>> = (0..rows_n)
        .map(|i| columns.iter().map(|c| c[i]).collect())
        .collect();
    let kv = refine_to_bezier(&knots.1, q, &mut rows);
    let cols_n = rows[0].len();
    let u_spans = spans(&ku, p, rows_n);
    let v_spans = spans(&kv, q, cols_n);
    let mut patches = Vec::with_capacity(u_spans.len() * v_spans.len());
    for &(a, u) in &u_spans {
        for &(b, v) in &v_spans {
            let mut patch_net = Vec::with_capacity((p + 1) * (q + 1));
            for row in &rows[a - p..=a] {
                patch_net.extend_from_slice(&row[b - q..=b]);
            }
            patches.push(Patch {
                u,
                v,
                net: patch_net,
            });
        }
    }
    let breaks = |s: &[(usize, (f64, f64))]| {
        let mut b: Vec<f64> = s.iter().map(|x| x.1.0).collect();
        b.push(s[s.len() - 1].1.1);
        b
    };
    PatchTable::new(degrees, breaks(&u_spans), breaks(&v_spans), patches)
}

//! Tensor-product rational B-spline (NURBS) surfaces.

use super::bspline_surface::TensorSpline;
use super::{BSplineSurface, BezierSurface};
use crate::Mesh;
use crate::{Aabb, Error, Hit, Intersect, PatchBounds, Ray, Surface, Tolerance};
use nalgebra::{Point3, Unit, Vector3};

/// A NURBS surface
/// `S(u, v) = Σᵢⱼ wᵢⱼPᵢⱼ Nᵢ,ₚ(u)Nⱼ,q(v) / Σᵢⱼ wᵢⱼ Nᵢ,ₚ(u)Nⱼ,q(v)` with
/// positive weights: the knot and grid rules of [`BSplineSurface`], one
/// weight per control point.
///
/// The surface is a polynomial spline one dimension up in homogeneous
/// coordinates `(wP, w)`: knot refinement into Bézier patches, de Casteljau
/// and subdivision run on those, and the division comes last; the partials
/// follow by the quotient rule `S_u = (A_u − w_u S)/w` (Piegl & Tiller,
/// *The NURBS Book*, §4.5). Equal weights give the [`BSplineSurface`] of the
/// same grid.
///
/// # Edge rules
/// As [`BSplineSurface`]: half-open knot rectangles, clamping into the
/// domain (NaN to its start), the limit normal at collapsed edges (see
/// [`BezierSurface`](crate::BezierSurface)), and bounds from the projected
/// control net of the sub-patch (the convex hull property holds for positive
/// weights).
///
/// ```
/// use revolve::{NurbsSurface, Surface};
/// use revolve::nalgebra::Point3;
///
/// // A quarter cylinder of radius 1: a quarter circle in u, a line in v.
/// let h = std::f64::consts::FRAC_1_SQRT_2;
/// let arc = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
/// let points = arc.iter()
///     .map(|&(x, y)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, 2.0)])
///     .collect();
/// let s = NurbsSurface::new(
///     (2, 1),
///     (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
///     points,
///     vec![vec![1.0, 1.0], vec![h, h], vec![1.0, 1.0]],
/// )?;
/// let p = s.eval(0.3, 0.6);
/// assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15);
/// assert!((p.z - 1.2).abs() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    core: TensorSpline,
}

/// One rational piece of a [`NurbsSurface`]: on the knot rectangle `u × v`
/// the surface equals the rational Bézier patch of `points` and `weights`
/// (degrees `(rows − 1, cols − 1)`) at
/// `((u − u₀)/(u₁ − u₀), (v − v₀)/(v₁ − v₀))`.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBezierPatch {
    /// The knot interval `(u₀, u₁)` in `u`, `u₀ < u₁`.
    pub u: (f64, f64),
    /// The knot interval `(v₀, v₁)` in `v`, `v₀ < v₁`.
    pub v: (f64, f64),
    /// The control grid, `points[i][j]` with `i` along `u`.
    pub points: Vec<Vec<Point3<f64>>>,
    /// The weights, positive, one per point.
    pub weights: Vec<Vec<f64>>,
}

impl NurbsSurface {
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

    /// A NURBS surface of degrees `(p, q)`, knot vectors `(U, V)`, control
    /// grid `points[i][j]` and weights `weights[i][j]`.
    ///
    /// # Errors
    /// The checks of [`BSplineSurface::new`] for the points and knots; then
    /// [`Error::WeightCount`] (not one row of weights per row of points),
    /// [`Error::RaggedGrid`] (a row of weights of another length than the
    /// points' rows), [`Error::InvalidGridWeight`] (zero, negative, NaN or
    /// infinite; its row and column),
    /// [`Error::WeightRatioTooLarge`]; [`Error::DerivativeOverflow`] as for
    /// the B-spline, in homogeneous coordinates.
    pub fn new(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: Vec<Vec<Point3<f64>>>,
        weights: Vec<Vec<f64>>,
    ) -> Result<Self, Error> {
        Ok(NurbsSurface {
            core: TensorSpline::new(degrees, knots, points, Some(weights))?,
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
    /// becomes `−(∂S/∂u × ∂S/∂v)/|∂S/∂u × ∂S/∂v|`, while the grid, weights,
    /// knots, points, [`partials`](Surface::partials) (unchanged), parameters
    /// and hits' `t`, `point` and `uv` are exactly the original's; every
    /// normal is negated as for
    /// [`BezierSurface::reversed`](crate::BezierSurface::reversed) (the
    /// tessellation's triangles wound the other way), and knot insertion
    /// keeps the orientation (the plain data of
    /// [`to_bezier_patches`](Self::to_bezier_patches) has none).
    /// `reversed().reversed()` is the original.
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

    /// The weights, as given (all ones for a converted [`BSplineSurface`]);
    /// weights that all lie below `2⁻⁵⁰⁰` or above `2⁵⁰⁰` are scaled by one
    /// power of two at construction (exactly, the surface unchanged) so that
    /// the largest is in `[1, 2)`.
    pub fn weights(&self) -> &[Vec<f64>] {
        &self.core.weights
    }

    /// The shared core (for the nearest-point search).
    pub(crate) fn core(&self) -> &TensorSpline {
        &self.core
    }

    /// The surface of a core the crate built.
    pub(super) fn from_core(core: TensorSpline) -> Self {
        NurbsSurface { core }
    }

    /// The second partial derivatives `(S_uu, S_uv, S_vv)` at `(u, v)`
    /// (clamped into the domain), by the quotient rule.
    pub fn second_partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let d = self.core.table.jet(u, v, 2);
        (d[2][0], d[1][1], d[0][2])
    }

    /// The rational Bézier patches, one per non-empty knot rectangle of the
    /// domain, `u`-span major.
    pub fn to_bezier_patches(&self) -> Vec<RationalBezierPatch> {
        self.core
            .table
            .patches
            .iter()
            .map(|patch| {
                let (points, weights) = self.core.patch_grid(patch);
                RationalBezierPatch {
                    u: patch.u,
                    v: patch.v,
                    points,
                    weights,
                }
            })
            .collect()
    }

    /// A triangle mesh within `tolerance` of the surface, as
    /// [`BSplineSurface::tessellate`], with the second-derivative bounds of
    /// the rational patches from their homogeneous nets by the quotient rule
    /// (see [`Mesh`]).
    ///
    /// # Errors
    /// As [`BezierSurface::tessellate`](crate::BezierSurface::tessellate).
    pub fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        self.core.tessellate(tolerance)
    }

    /// The same surface with the knot `t` inserted `times` times into `U`
    /// (Boehm's algorithm on every column, in homogeneous coordinates).
    ///
    /// # Errors
    /// As [`BSplineSurface::insert_knot_u`].
    pub fn insert_knot_u(&self, t: f64, times: usize) -> Result<Self, Error> {
        Ok(NurbsSurface {
            core: self.core.insert_knot(0, t, times)?,
        })
    }

    /// The same surface with the knot `t` inserted `times` times into `V`.
    ///
    /// # Errors
    /// As [`BSplineSurface::insert_knot_v`].
    pub fn insert_knot_v(&self, t: f64, times: usize) -> Result<Self, Error> {
        Ok(NurbsSurface {
            core: self.core.insert_knot(1, t, times)?,
        })
    }
}

impl From<BSplineSurface> for NurbsSurface {
    /// The same surface with unit weights.
    fn from(s: BSplineSurface) -> Self {
        // Unit weights change no homogeneous value: the polynomial core is
        // already the rational surface (its weights read as ones).
        NurbsSurface {
            core: s.core().clone(),
        }
    }
}

impl TryFrom<&BezierSurface> for NurbsSurface {
    type Error = Error;

    /// The same surface as one NURBS patch with unit weights, on `[0, 1]²`
    /// (clamped knots `0 … 0 1 … 1`), e.g. to intersect it with another
    /// surface ([`NurbsSurface::intersect_surface`]).
    ///
    /// ```
    /// use revolve::{BezierSurface, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let b = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let n = NurbsSurface::try_from(&b)?;
    /// assert!((n.eval(0.3, 0.6) - b.eval(0.3, 0.6)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// The checks of [`NurbsSurface::new`] (none fail for a valid Bézier
    /// surface in practice).
    fn try_from(s: &BezierSurface) -> Result<Self, Error> {
        Ok(NurbsSurface { core: s.spline()? })
    }
}

impl Surface for NurbsSurface {
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

impl PatchBounds for NurbsSurface {
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
impl Intersect for NurbsSurface {
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

//! Isoparametric curves of the tensor-product surfaces: the curve
//! `v ↦ S(u₀, v)` or `u ↦ S(u, v₀)`, exactly, as a [`Nurbs`].

use super::bspline_surface::{TensorSpline, insertion_span};
use super::{BSplineSurface, BezierSurface, NurbsSurface};
use crate::bernstein::lerp;
use crate::curve::Homogeneous;
use crate::limits::MAX_COORDINATE;
use crate::{Error, Nurbs, ParameterDirection, Surface};
use nalgebra::Point3;

/// The value at `t` of the spline of degree `p` on `knots` with the control
/// values `line` (de Boor's algorithm on the `p + 1` values of the span
/// holding `t`; Piegl & Tiller, *The NURBS Book*, A3.1 in homogeneous
/// form). `t` lies in the domain `[t_p, t_n]`.
fn de_boor_at(knots: &[f64], p: usize, line: &[Homogeneous<3>], t: f64) -> Homogeneous<3> {
    let k = insertion_span(knots, p, line.len(), t);
    let mut d: Vec<Homogeneous<3>> = line[k - p..=k].to_vec();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let lo = knots[j + k - p];
            let hi = knots[j + 1 + k - r];
            d[j] = lerp(d[j - 1], d[j], (t - lo) / (hi - lo));
        }
    }
    d[p]
}

impl TensorSpline {
    /// The isocurve at `t` fixed in direction `axis` (0: `u` fixed, a
    /// curve along `v`; 1: `v` fixed, a curve along `u`).
    pub(crate) fn isocurve(&self, axis: usize, t: f64) -> Result<Nurbs<3>, Error> {
        let (direction, p, knots, other_p, other_knots) = if axis == 0 {
            (
                ParameterDirection::U,
                self.degrees.0,
                &self.knots.0,
                self.degrees.1,
                &self.knots.1,
            )
        } else {
            (
                ParameterDirection::V,
                self.degrees.1,
                &self.knots.1,
                self.degrees.0,
                &self.knots.0,
            )
        };
        let domain = self.table.domain()[axis];
        if !(t >= domain.0 && t <= domain.1) {
            return Err(Error::SurfaceParameterOutOfDomain {
                direction,
                t,
                domain,
            });
        }
        let (rows, cols) = (self.points.len(), self.points[0].len());
        let h = |i: usize, j: usize| Homogeneous::new(&self.points[i][j], self.weights[i][j]);
        // The lines running along the fixed direction: columns for u
        // fixed, rows for v fixed; one control value of the isocurve each.
        let lines: Vec<Vec<Homogeneous<3>>> = if axis == 0 {
            (0..cols)
                .map(|j| (0..rows).map(|i| h(i, j)).collect())
                .collect()
        } else {
            (0..rows)
                .map(|i| (0..cols).map(|j| h(i, j)).collect())
                .collect()
        };
        let within = |x: f64| x.clamp(-MAX_COORDINATE, MAX_COORDINATE);
        let (points, weights): (Vec<Point3<f64>>, Vec<f64>) = lines
            .iter()
            .map(|line| {
                let q = de_boor_at(knots, p, line, t);
                if self.rational {
                    (Point3::from((q.wp / q.w).map(within)), q.w)
                } else {
                    (Point3::from(q.wp.map(within)), 1.0)
                }
            })
            .unzip();
        Nurbs::new(other_p, other_knots.clone(), points, weights)
    }
}

/// The knots of a Bézier surface's direction of degree `p`: `p + 1` zeros
/// and `p + 1` ones.
pub(super) fn bezier_knots(p: usize) -> Vec<f64> {
    let mut k = vec![0.0; p + 1];
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

impl BezierSurface {
    /// The spline form of this surface (clamped knots `[0, …, 0, 1, …, 1]`).
    pub(super) fn spline(&self) -> Result<TensorSpline, Error> {
        let (m, n) = self.degrees();
        TensorSpline::new(
            (m, n),
            (bezier_knots(m), bezier_knots(n)),
            self.points().to_vec(),
            None,
        )
    }

    /// The isocurve `v ↦ S(u, v)` at fixed `u ∈ [0, 1]`, exactly: a
    /// polynomial [`Nurbs`] (all weights 1) of degree `n` on the knots
    /// `[0, …, 0, 1, …, 1]` whose control points are the columns' de
    /// Casteljau values at `u`, `Qⱼ = Σᵢ PᵢⱼBᵢᵐ(u)`.
    ///
    /// # Errors
    /// [`Error::SurfaceParameterOutOfDomain`] in `u` for a NaN `u` or one
    /// outside `[0, 1]`.
    ///
    /// ```
    /// use revolve::{BezierSurface, Curve, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let c = s.isocurve_u(0.5)?;
    /// assert!((c.eval(0.25) - s.eval(0.5, 0.25)).norm() < 1e-15);
    /// assert!(s.isocurve_u(1.5).is_err());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_u(&self, u: f64) -> Result<Nurbs<3>, Error> {
        self.spline()?.isocurve(0, u)
    }

    /// The isocurve `u ↦ S(u, v)` at fixed `v ∈ [0, 1]`, exactly (as
    /// [`isocurve_u`](Self::isocurve_u), on the rows).
    ///
    /// # Errors
    /// [`Error::SurfaceParameterOutOfDomain`] in `v`.
    ///
    /// ```
    /// use revolve::{BezierSurface, Curve, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let c = s.isocurve_v(0.25)?;
    /// assert!((c.eval(0.5) - s.eval(0.5, 0.25)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_v(&self, v: f64) -> Result<Nurbs<3>, Error> {
        self.spline()?.isocurve(1, v)
    }

    /// The four boundary curves, exactly: `[S(0, ·), S(1, ·), S(·, 0),
    /// S(·, 1)]` (the isocurves at the ends of the domain; a collapsed edge
    /// gives a curve of one point).
    ///
    /// # Errors
    /// None in practice (the isocurves' own errors).
    ///
    /// ```
    /// use revolve::{BezierSurface, Curve, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let [u0, _u1, _v0, v1] = s.boundary_curves()?;
    /// assert!((u0.eval(0.5) - s.eval(0.0, 0.5)).norm() < 1e-15);
    /// assert!((v1.eval(0.5) - s.eval(0.5, 1.0)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn boundary_curves(&self) -> Result<[Nurbs<3>; 4], Error> {
        let spline = self.spline()?;
        boundaries(self.domain(), |axis, x| spline.isocurve(axis, x))
    }
}

impl BSplineSurface {
    /// The isocurve `v ↦ S(u, v)` at fixed `u`, exactly: the polynomial
    /// [`Nurbs`] (all weights 1) of degree `q` on the knots `V`, whose
    /// control points are the values at `u` of the grid's columns, each a
    /// B-spline of degree `p` on `U` (de Boor's algorithm), since
    /// `S(u, v) = Σⱼ (Σᵢ PᵢⱼNᵢ(u)) Mⱼ(v)`. At an interior knot of `U` the
    /// columns take their limit from above, as the surface does.
    ///
    /// # Errors
    /// [`Error::SurfaceParameterOutOfDomain`] in `u` for a NaN `u` or one
    /// outside the `u` domain `[U_p, U_rows]`.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Curve, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..4)
    ///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, (i * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((2, 2), grid)?;
    /// let c = s.isocurve_u(0.3)?;
    /// for v in [0.0, 0.4, 1.0] {
    ///     assert!((c.eval(v) - s.eval(0.3, v)).norm() < 1e-14);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_u(&self, u: f64) -> Result<Nurbs<3>, Error> {
        self.core().isocurve(0, u)
    }

    /// The isocurve `u ↦ S(u, v)` at fixed `v`, exactly (as
    /// [`isocurve_u`](Self::isocurve_u), on the rows, degree `p` on `U`).
    ///
    /// # Errors
    /// [`Error::SurfaceParameterOutOfDomain`] in `v`.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Curve, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..4)
    ///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, (i * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((2, 2), grid)?;
    /// let c = s.isocurve_v(0.7)?;
    /// assert!((c.eval(0.2) - s.eval(0.2, 0.7)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_v(&self, v: f64) -> Result<Nurbs<3>, Error> {
        self.core().isocurve(1, v)
    }

    /// The four boundary curves, exactly: the isocurves at the ends of the
    /// domain, `[S(u₀, ·), S(u₁, ·), S(·, v₀), S(·, v₁)]` (a collapsed edge
    /// gives a curve of one point).
    ///
    /// # Errors
    /// The isocurves' errors (only at the weight-ratio bound for NURBS).
    pub fn boundary_curves(&self) -> Result<[Nurbs<3>; 4], Error> {
        boundaries(self.domain(), |axis, x| self.core().isocurve(axis, x))
    }
}

impl NurbsSurface {
    /// The isocurve `v ↦ S(u, v)` at fixed `u`, exactly: with the
    /// homogeneous grid `(wᵢⱼPᵢⱼ, wᵢⱼ)`, each column's homogeneous value at
    /// `u` (de Boor's algorithm), `(Aⱼ, Wⱼ) = Σᵢ (wᵢⱼPᵢⱼ, wᵢⱼ)Nᵢ(u)`, gives
    /// the control point `Aⱼ/Wⱼ` with weight `Wⱼ > 0` of a [`Nurbs`] of
    /// degree `q` on `V`: `S(u, v) = Σⱼ AⱼMⱼ(v) / Σⱼ WⱼMⱼ(v)`.
    ///
    /// # Errors
    /// [`Error::SurfaceParameterOutOfDomain`] in `u` for a NaN `u` or one
    /// outside the `u` domain; the errors of [`Nurbs::new`] should the
    /// curve's weights span more than
    /// [`MAX_WEIGHT_RATIO`](crate::curve::MAX_WEIGHT_RATIO) (they are
    /// combinations of the surface's, so only at that bound).
    ///
    /// ```
    /// use revolve::{Curve, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A quarter cylinder: its isocurves at fixed u are vertical lines,
    /// // at fixed v quarter circles.
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let points = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].iter()
    ///     .map(|&(x, y)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, 2.0)])
    ///     .collect();
    /// let s = NurbsSurface::new(
    ///     (2, 1),
    ///     (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
    ///     points,
    ///     vec![vec![1.0, 1.0], vec![h, h], vec![1.0, 1.0]],
    /// )?;
    /// let arc = s.isocurve_v(0.5)?;
    /// let p = arc.eval(0.3);
    /// assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15 && (p.z - 1.0).abs() < 1e-15);
    /// assert!((s.isocurve_u(0.3)?.eval(0.5) - s.eval(0.3, 0.5)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_u(&self, u: f64) -> Result<Nurbs<3>, Error> {
        self.core().isocurve(0, u)
    }

    /// The isocurve `u ↦ S(u, v)` at fixed `v`, exactly (as
    /// [`isocurve_u`](Self::isocurve_u), on the rows, degree `p` on `U`).
    ///
    /// # Errors
    /// As [`isocurve_u`](Self::isocurve_u), in `v`.
    ///
    /// ```
    /// use revolve::{Curve, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let points = vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ];
    /// let k = (vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = NurbsSurface::new((1, 1), k, points, vec![vec![1.0, 2.0], vec![3.0, 1.0]])?;
    /// let c = s.isocurve_v(0.6)?;
    /// assert!((c.eval(0.2) - s.eval(0.2, 0.6)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn isocurve_v(&self, v: f64) -> Result<Nurbs<3>, Error> {
        self.core().isocurve(1, v)
    }

    /// The four boundary curves, exactly: the isocurves at the ends of the
    /// domain, `[S(u₀, ·), S(u₁, ·), S(·, v₀), S(·, v₁)]` (a collapsed edge
    /// gives a curve of one point).
    ///
    /// # Errors
    /// The isocurves' errors (only at the weight-ratio bound for NURBS).
    pub fn boundary_curves(&self) -> Result<[Nurbs<3>; 4], Error> {
        boundaries(self.domain(), |axis, x| self.core().isocurve(axis, x))
    }
}

/// The isocurves at the ends of `domain`: `u` first, then `v`.
fn boundaries(
    [du, dv]: [(f64, f64); 2],
    isocurve: impl Fn(usize, f64) -> Result<Nurbs<3>, Error>,
) -> Result<[Nurbs<3>; 4], Error> {
    Ok([
        isocurve(0, du.0)?,
        isocurve(0, du.1)?,
        isocurve(1, dv.0)?,
        isocurve(1, dv.1)?,
    ])
}

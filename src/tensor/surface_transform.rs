//! The tensor-product surfaces under affine maps: the control points
//! mapped, which maps the surface exactly (affine invariance).

use super::bspline_surface::TensorSpline;
use super::{BSplineSurface, BezierSurface, NurbsSurface};
use crate::Error;
use nalgebra::{Affine3, Point3};

/// Checks the map's entries and says whether it turns the orientation
/// over (the determinant of its linear part is negative).
fn check_map(map: &Affine3<f64>) -> Result<bool, Error> {
    let m = map.matrix();
    if !m.iter().all(|x| x.is_finite()) {
        return Err(Error::NonFiniteTransform);
    }
    Ok(m.fixed_view::<3, 3>(0, 0).determinant() < 0.0)
}

/// The grid mapped point by point.
fn mapped(map: &Affine3<f64>, points: &[Vec<Point3<f64>>]) -> Vec<Vec<Point3<f64>>> {
    points
        .iter()
        .map(|row| row.iter().map(|p| map * p).collect())
        .collect()
}

impl TensorSpline {
    /// The spline under `map` (see [`NurbsSurface::try_transformed`]).
    fn transformed(&self, map: &Affine3<f64>) -> Result<Self, Error> {
        let flips = check_map(map)?;
        let weights = self.rational.then(|| self.weights.clone());
        let mut spline = TensorSpline::new(
            self.degrees,
            self.knots.clone(),
            mapped(map, &self.points),
            weights,
        )?;
        spline.table.reversed = self.table.reversed != flips;
        spline.table.tolerance = self.table.tolerance;
        Ok(spline)
    }
}

impl BezierSurface {
    /// The surface under the affine map `T(x) = Lx + c`, exactly: the
    /// control points mapped (a Bézier surface is an affine combination of
    /// its control points, so `T(S(u, v)) = S′(u, v)` at every parameter).
    /// The partials map by `L`; the normal by the inverse transpose,
    /// `N′ = L⁻ᵀN/|L⁻ᵀN|`: where `det L < 0` (a reflection) the
    /// orientation flag of [`reversed`](Self::reversed) is turned over to
    /// keep that rule (`S′_u × S′_v = det L·L⁻ᵀ(S_u × S_v)`). A singular `L`
    /// gives a flat surface without normals. The tolerance is kept.
    ///
    /// A map that cannot be applied (a NaN or infinite entry, or one taking
    /// a control point beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE) or
    /// a derivative beyond [`MAX_DERIVATIVE`](crate::MAX_DERIVATIVE))
    /// leaves the surface unchanged, so that this never fails;
    /// [`try_transformed`](Self::try_transformed) reports it instead.
    ///
    /// ```
    /// use revolve::{BezierSurface, Surface};
    /// use revolve::nalgebra::{Affine3, Matrix4, Point3};
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ])?;
    /// let map = Affine3::from_matrix_unchecked(Matrix4::new(
    ///     2.0, 1.0, 0.0, 5.0,
    ///     0.0, 1.0, 0.0, -1.0,
    ///     0.0, 0.0, 3.0, 0.0,
    ///     0.0, 0.0, 0.0, 1.0,
    /// ));
    /// let t = s.transformed(&map);
    /// assert!((t.eval(0.3, 0.6) - map * s.eval(0.3, 0.6)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, map: &Affine3<f64>) -> Self {
        self.try_transformed(map).unwrap_or_else(|_| self.clone())
    }

    /// As [`transformed`](Self::transformed), with a map that cannot be
    /// applied an error.
    ///
    /// # Errors
    /// [`Error::NonFiniteTransform`] for a NaN or infinite entry; the
    /// errors of [`new`](Self::new) on the mapped grid
    /// ([`Error::GridCoordinateTooLarge`] with the row and column,
    /// [`Error::DerivativeOverflow`]).
    ///
    /// ```
    /// use revolve::{BezierSurface, Error};
    /// use revolve::nalgebra::{Affine3, Matrix4, Point3};
    ///
    /// let s = BezierSurface::new(vec![vec![Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)]])?;
    /// let bad = Affine3::from_matrix_unchecked(Matrix4::new_scaling(f64::NAN));
    /// assert_eq!(s.try_transformed(&bad), Err(Error::NonFiniteTransform));
    /// assert_eq!(s.transformed(&bad), s);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn try_transformed(&self, map: &Affine3<f64>) -> Result<Self, Error> {
        let flips = check_map(map)?;
        let surface =
            BezierSurface::new(mapped(map, self.points()))?.with_tolerance(*self.tolerance());
        Ok(if self.is_reversed() != flips {
            surface.reversed()
        } else {
            surface
        })
    }
}

impl BSplineSurface {
    /// The surface under the affine map `T(x) = Lx + c`, exactly: the
    /// control points mapped, the knots kept (B-splines sum to one, so
    /// `T(S(u, v)) = S′(u, v)`). Partials, normals, orientation and the
    /// fallback for a map that cannot be applied as for
    /// [`BezierSurface::transformed`].
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::{Affine3, Point3, Rotation3, Vector3};
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..4)
    ///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, (i * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((2, 2), grid)?;
    /// let map = Affine3::from_matrix_unchecked(
    ///     Rotation3::from_axis_angle(&Vector3::z_axis(), 0.7).to_homogeneous(),
    /// );
    /// let t = s.transformed(&map);
    /// assert!((t.eval(0.4, 0.9) - map * s.eval(0.4, 0.9)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, map: &Affine3<f64>) -> Self {
        self.try_transformed(map).unwrap_or_else(|_| self.clone())
    }

    /// As [`transformed`](Self::transformed), with a map that cannot be
    /// applied an error.
    ///
    /// # Errors
    /// As [`BezierSurface::try_transformed`].
    ///
    /// ```
    /// use revolve::{BSplineSurface, Error};
    /// use revolve::nalgebra::{Affine3, Matrix4, Point3};
    ///
    /// let grid = vec![vec![Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)]; 2];
    /// let s = BSplineSurface::clamped((1, 1), grid)?;
    /// let huge = Affine3::from_matrix_unchecked(Matrix4::new_nonuniform_scaling(
    ///     &revolve::nalgebra::Vector3::new(1e101, 1.0, 1.0),
    /// ));
    /// assert!(matches!(s.try_transformed(&huge), Err(Error::GridCoordinateTooLarge { .. })));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn try_transformed(&self, map: &Affine3<f64>) -> Result<Self, Error> {
        Ok(Self::from_core(self.core().transformed(map)?))
    }
}

impl NurbsSurface {
    /// The surface under the affine map `T(x) = Lx + c`, exactly: the
    /// control points mapped, the weights and knots kept (the rational
    /// basis functions sum to one, so `T(S(u, v)) = S′(u, v)`). Partials,
    /// normals, orientation and the fallback for a map that cannot be
    /// applied as for [`BezierSurface::transformed`].
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::{Affine3, Matrix4, Point3};
    ///
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
    /// // Stretched in x: the quarter cylinder becomes a quarter elliptic one.
    /// let map = Affine3::from_matrix_unchecked(Matrix4::new_nonuniform_scaling(
    ///     &revolve::nalgebra::Vector3::new(3.0, 1.0, 1.0),
    /// ));
    /// let p = s.transformed(&map).eval(0.4, 0.5);
    /// assert!(((p.x / 3.0).hypot(p.y) - 1.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, map: &Affine3<f64>) -> Self {
        self.try_transformed(map).unwrap_or_else(|_| self.clone())
    }

    /// As [`transformed`](Self::transformed), with a map that cannot be
    /// applied an error.
    ///
    /// # Errors
    /// As [`BezierSurface::try_transformed`].
    ///
    /// ```
    /// use revolve::{Error, NurbsSurface};
    /// use revolve::nalgebra::{Affine3, Matrix4, Point3};
    ///
    /// let points = vec![vec![Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)]; 2];
    /// let k = (vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = NurbsSurface::new((1, 1), k, points, vec![vec![1.0, 2.0]; 2])?;
    /// let bad = Affine3::from_matrix_unchecked(Matrix4::new_scaling(f64::INFINITY));
    /// assert_eq!(s.try_transformed(&bad), Err(Error::NonFiniteTransform));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn try_transformed(&self, map: &Affine3<f64>) -> Result<Self, Error> {
        Ok(Self::from_core(self.core().transformed(map)?))
    }
}

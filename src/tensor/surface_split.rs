//! Splitting the tensor-product surfaces in two along an isoparametric
//! line, exactly, by knot insertion.

use super::bspline_surface::TensorSpline;
use super::{BSplineSurface, BezierSurface, NurbsSurface};
use crate::curve::knot_to_insert;
use crate::{Error, ParameterDirection};
use nalgebra::Point3;

/// Cuts a row-major grid along `axis` (0: rows, i.e. `u`; 1: columns)
/// into the part before index `end_left` (exclusive) and the part from
/// `start_right`.
fn cut<T: Clone>(
    grid: &[Vec<T>],
    axis: usize,
    end_left: usize,
    start_right: usize,
) -> (Vec<Vec<T>>, Vec<Vec<T>>) {
    if axis == 0 {
        (grid[..end_left].to_vec(), grid[start_right..].to_vec())
    } else {
        (
            grid.iter().map(|r| r[..end_left].to_vec()).collect(),
            grid.iter().map(|r| r[start_right..].to_vec()).collect(),
        )
    }
}

impl TensorSpline {
    /// The two halves of the spline cut at `t` in direction `axis` (0:
    /// `u`): `t` (or the knot within rounding of it) inserted up to
    /// multiplicity `p` (`1` for degree 0), the grid cut at the repeated
    /// knot, each half's knot vector ending (starting) with `t` repeated
    /// `p + 1` times. The halves keep the orientation and the tolerance.
    pub(crate) fn split(&self, axis: usize, t: f64) -> Result<(Self, Self), Error> {
        let (direction, p, knots) = if axis == 0 {
            (ParameterDirection::U, self.degrees.0, &self.knots.0)
        } else {
            (ParameterDirection::V, self.degrees.1, &self.knots.1)
        };
        let domain = self.table.domain()[axis];
        let outside = Error::SplitOutsideDomain {
            direction,
            t,
            domain,
        };
        let x = knot_to_insert(knots, p, domain, t, 0).map_err(|_| outside.clone())?;
        if !(x > domain.0 && x < domain.1) {
            return Err(outside);
        }
        let have = knots.iter().filter(|&&k| k == x).count();
        let target = p.max(1);
        let refined = if have < target {
            self.insert_knot(axis, x, target - have)?
        } else {
            self.clone()
        };
        let k = if axis == 0 {
            &refined.knots.0
        } else {
            &refined.knots.1
        };
        // x occupies k[r .. r + m], m ≥ max(p, 1).
        let r = k.iter().position(|&v| v == x).unwrap_or(0);
        let m = k.iter().filter(|&&v| v == x).count();
        let start_right = (r + m).saturating_sub(p + 1);
        let mut left_knots = k[..r].to_vec();
        left_knots.extend(std::iter::repeat_n(x, p + 1));
        let mut right_knots = vec![x; p + 1];
        right_knots.extend_from_slice(&k[r + m..]);
        let (left_points, right_points) = cut(&refined.points, axis, r, start_right);
        let (left_weights, right_weights) = cut(&refined.weights, axis, r, start_right);
        let half = |knots: Vec<f64>,
                    points: Vec<Vec<Point3<f64>>>,
                    weights: Vec<Vec<f64>>|
         -> Result<Self, Error> {
            let all = if axis == 0 {
                (knots, self.knots.1.clone())
            } else {
                (self.knots.0.clone(), knots)
            };
            let weights = self.rational.then_some(weights);
            let mut spline = TensorSpline::new(self.degrees, all, points, weights)?;
            spline.table.reversed = self.table.reversed;
            spline.table.tolerance = self.table.tolerance;
            Ok(spline)
        };
        Ok((
            half(left_knots, left_points, left_weights)?,
            half(right_knots, right_points, right_weights)?,
        ))
    }
}

impl BSplineSurface {
    /// The surface cut in two at `u`: the halves on `[U_p, u] × V` and
    /// `[u, U_rows] × V`, each equal to the surface at the same
    /// parameters (no reparametrization), exactly. `u` is inserted into
    /// `U` up to multiplicity `p` (Boehm's algorithm on every column), so
    /// that the row of control points at the repeated knot is the
    /// isocurve at `u`, shared by both halves; the halves' knot vectors
    /// end and start with `u` repeated `p + 1` times (Piegl & Tiller,
    /// *The NURBS Book*, §5.3). A `u` within rounding of an existing knot
    /// splits at that knot. The halves keep the orientation and tolerance.
    ///
    /// # Errors
    /// [`Error::SplitOutsideDomain`] in `u` unless `u` lies strictly inside
    /// the `u` domain (NaN, outside, at an end or within rounding of one);
    /// the errors of [`new`](Self::new) on a half.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..4)
    ///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, (i * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((2, 2), grid)?;
    /// let (a, b) = s.split_u(0.3)?;
    /// assert_eq!(a.domain()[0], (0.0, 0.3));
    /// assert_eq!(b.domain()[0], (0.3, 1.0));
    /// assert!((a.eval(0.1, 0.5) - s.eval(0.1, 0.5)).norm() < 1e-14);
    /// assert!((b.eval(0.8, 0.5) - s.eval(0.8, 0.5)).norm() < 1e-14);
    /// assert!(s.split_u(1.0).is_err());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_u(&self, u: f64) -> Result<(Self, Self), Error> {
        let (a, b) = self.core().split(0, u)?;
        Ok((Self::from_core(a), Self::from_core(b)))
    }

    /// The surface cut in two at `v` (as [`split_u`](Self::split_u), on
    /// the rows): halves on `U × [V_q, v]` and `U × [v, V_cols]`.
    ///
    /// # Errors
    /// [`Error::SplitOutsideDomain`] in `v`; the errors of
    /// [`new`](Self::new) on a half.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..3)
    ///     .map(|i| (0..4).map(|j| Point3::new(i as f64, j as f64, (i + j * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((1, 3), grid)?;
    /// let (a, b) = s.split_v(0.5)?;
    /// assert!((a.eval(0.2, 0.25) - s.eval(0.2, 0.25)).norm() < 1e-14);
    /// assert!((b.eval(0.2, 0.75) - s.eval(0.2, 0.75)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_v(&self, v: f64) -> Result<(Self, Self), Error> {
        let (a, b) = self.core().split(1, v)?;
        Ok((Self::from_core(a), Self::from_core(b)))
    }
}

impl NurbsSurface {
    /// The surface cut in two at `u`, exactly: as
    /// [`BSplineSurface::split_u`], with the insertion on the homogeneous
    /// points `(wP, w)` (the weights go with the points).
    ///
    /// # Errors
    /// As [`BSplineSurface::split_u`].
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
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
    /// let (a, b) = s.split_u(0.5)?;
    /// assert!((a.eval(0.2, 0.3) - s.eval(0.2, 0.3)).norm() < 1e-15);
    /// assert!((b.eval(0.9, 0.3) - s.eval(0.9, 0.3)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_u(&self, u: f64) -> Result<(Self, Self), Error> {
        let (a, b) = self.core().split(0, u)?;
        Ok((Self::from_core(a), Self::from_core(b)))
    }

    /// The surface cut in two at `v`, exactly (as
    /// [`split_u`](Self::split_u), on the rows).
    ///
    /// # Errors
    /// As [`BSplineSurface::split_v`].
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let points = vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    /// ];
    /// let k = (vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = NurbsSurface::new((1, 1), k, points, vec![vec![1.0, 2.0], vec![3.0, 1.0]])?;
    /// let (a, b) = s.split_v(0.4)?;
    /// assert!((a.eval(0.7, 0.1) - s.eval(0.7, 0.1)).norm() < 1e-15);
    /// assert!((b.eval(0.7, 0.9) - s.eval(0.7, 0.9)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_v(&self, v: f64) -> Result<(Self, Self), Error> {
        let (a, b) = self.core().split(1, v)?;
        Ok((Self::from_core(a), Self::from_core(b)))
    }
}

impl BezierSurface {
    /// The two halves of the surface cut at `u ∈ (0, 1)`, each a Bézier
    /// surface on `[0, 1]²` of the same degrees: the first is
    /// `S(u·s, t)`, the second `S(u + (1 − u)s, t)` (de Casteljau
    /// subdivision of every column, as knot insertion of `u` `m` times).
    ///
    /// # Errors
    /// [`Error::SplitOutsideDomain`] in `u` unless `0 < u < 1` (beyond
    /// rounding of the ends).
    ///
    /// ```
    /// use revolve::{BezierSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 1.0), Point3::new(1.0, 1.0, 0.0)],
    ///     vec![Point3::new(2.0, 0.0, 0.0), Point3::new(2.0, 1.0, 2.0)],
    /// ])?;
    /// let (a, b) = s.split_u(0.25)?;
    /// // The first half at s is the surface at 0.25·s.
    /// assert!((a.eval(0.5, 0.3) - s.eval(0.125, 0.3)).norm() < 1e-15);
    /// assert!((b.eval(0.0, 0.3) - s.eval(0.25, 0.3)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_u(&self, u: f64) -> Result<(Self, Self), Error> {
        self.split(0, u)
    }

    /// The two halves cut at `v ∈ (0, 1)`: `S(s, v·t)` and
    /// `S(s, v + (1 − v)t)` (as [`split_u`](Self::split_u), on the rows).
    ///
    /// # Errors
    /// [`Error::SplitOutsideDomain`] in `v` unless `0 < v < 1`.
    ///
    /// ```
    /// use revolve::{BezierSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = BezierSurface::new(vec![
    ///     vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 3.0), Point3::new(0.0, 2.0, 0.0)],
    ///     vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0), Point3::new(1.0, 2.0, 0.0)],
    /// ])?;
    /// let (a, b) = s.split_v(0.5)?;
    /// assert!((a.eval(0.3, 1.0) - s.eval(0.3, 0.5)).norm() < 1e-15);
    /// assert!((b.eval(0.3, 0.5) - s.eval(0.3, 0.75)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn split_v(&self, v: f64) -> Result<(Self, Self), Error> {
        self.split(1, v)
    }

    /// The halves at `t` in direction `axis`, as Bézier surfaces.
    fn split(&self, axis: usize, t: f64) -> Result<(Self, Self), Error> {
        let (a, b) = self.spline()?.split(axis, t)?;
        let reversed = self.is_reversed();
        let half = |s: TensorSpline| -> Result<Self, Error> {
            let surface = BezierSurface::new(s.points)?.with_tolerance(*self.tolerance());
            Ok(if reversed {
                surface.reversed()
            } else {
                surface
            })
        };
        Ok((half(a)?, half(b)?))
    }
}

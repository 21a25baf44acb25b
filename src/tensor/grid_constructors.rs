//! Convenience constructors of the tensor-product surfaces: B-spline
//! surfaces with the curves' clamped and uniform knots in both directions,
//! and every kind from a flat, row-major list of control points.

use super::{BSplineSurface, BezierSurface, NurbsSurface};
use crate::{BSpline, Error, ParameterDirection};
use nalgebra::{Point1, Point3};

/// The knots that [`BSpline::clamped`] (`clamped`) or [`BSpline::uniform`]
/// gives a curve of `degree` with `n` control points, or its error wrapped
/// as the surface's in `direction`.
fn curve_knots(
    direction: ParameterDirection,
    degree: usize,
    n: usize,
    clamped: bool,
) -> Result<Vec<f64>, Error> {
    let points = vec![Point1::origin(); n];
    let curve = if clamped {
        BSpline::clamped(degree, points)
    } else {
        BSpline::uniform(degree, points)
    };
    curve
        .map(|c| c.knots().to_vec())
        .map_err(|error| Error::SurfaceKnots {
            direction,
            error: Box::new(error),
        })
}

/// The B-spline surface of `points` with the knots of `clamped` (or
/// uniform) curves in both directions.
fn with_curve_knots(
    degrees: (usize, usize),
    points: Vec<Vec<Point3<f64>>>,
    clamped: bool,
) -> Result<BSplineSurface, Error> {
    // The grid's own errors (empty, ragged, not finite) come first, as in
    // `new`.
    let (_, cols) = super::control_net::flatten_points(&points)?;
    let ku = curve_knots(ParameterDirection::U, degrees.0, points.len(), clamped)?;
    let kv = curve_knots(ParameterDirection::V, degrees.1, cols, clamped)?;
    BSplineSurface::new(degrees, (ku, kv), points)
}

/// The rows of a flat row-major list: `rows` rows of `values.len() / rows`.
///
/// # Errors
/// [`Error::EmptyGrid`] for an empty list; [`Error::FlatGridLength`] when
/// `rows` is zero or does not divide the length.
fn cut_rows<T: Copy>(values: &[T], rows: usize) -> Result<Vec<Vec<T>>, Error> {
    if values.is_empty() {
        return Err(Error::EmptyGrid);
    }
    if rows == 0 || values.len() % rows != 0 {
        return Err(Error::FlatGridLength {
            length: values.len(),
            rows,
        });
    }
    Ok(values
        .chunks(values.len() / rows)
        .map(<[T]>::to_vec)
        .collect())
}

impl BSplineSurface {
    /// The clamped B-spline surface of degrees `(p, q)` on the grid
    /// `points[i][j]` (`i` along `u`): in each direction the knots of
    /// [`BSpline::clamped`] for that many control points (`p + 1` knots at 0
    /// and at 1, uniform interior knots), so the domain is `[0, 1]²` and the
    /// surface interpolates the four corner points and its edges are the
    /// clamped curves of the edge rows and columns.
    ///
    /// # Errors
    /// The grid's errors as for [`new`](Self::new) ([`Error::EmptyGrid`],
    /// [`Error::RaggedGrid`], [`Error::NonFiniteGridPoint`],
    /// [`Error::GridCoordinateTooLarge`] with the row and column); then
    /// [`Error::SurfaceKnots`] in `u` or `v` wrapping
    /// [`Error::DegreeTooHigh`] when a degree is not below the number of
    /// control points in its direction; then the checks of `new`.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..4)
    ///     .map(|i| (0..3).map(|j| Point3::new(i as f64, j as f64, (i * j) as f64)).collect())
    ///     .collect();
    /// let s = BSplineSurface::clamped((2, 1), grid)?;
    /// assert_eq!(s.knots().0, &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]);
    /// assert_eq!(s.knots().1, &[0.0, 0.0, 0.5, 1.0, 1.0]);
    /// // The corners are interpolated.
    /// assert_eq!(s.eval(1.0, 1.0), Point3::new(3.0, 2.0, 6.0));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn clamped(degrees: (usize, usize), points: Vec<Vec<Point3<f64>>>) -> Result<Self, Error> {
        with_curve_knots(degrees, points, true)
    }

    /// The uniform B-spline surface of degrees `(p, q)` on the grid
    /// `points[i][j]`: in each direction the knots of [`BSpline::uniform`]
    /// (`tₖ = k/(n + p)`, the course framework's), so the domain is
    /// `[U_p, U_rows] × [V_q, V_cols]` and the surface does not in general
    /// pass through the corner points.
    ///
    /// # Errors
    /// As [`clamped`](Self::clamped).
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let grid: Vec<Vec<Point3<f64>>> = (0..3)
    ///     .map(|i| (0..2).map(|j| Point3::new(i as f64, j as f64, 0.0)).collect())
    ///     .collect();
    /// let s = BSplineSurface::uniform((2, 1), grid)?;
    /// assert_eq!(s.knots().0, &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
    /// assert_eq!(s.domain(), [(0.4, 0.6), (1.0 / 3.0, 2.0 / 3.0)]);
    /// // A quadratic on equally spaced points: the middle of the rows.
    /// assert!((s.eval(0.5, 0.5) - Point3::new(1.0, 0.5, 0.0)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn uniform(degrees: (usize, usize), points: Vec<Vec<Point3<f64>>>) -> Result<Self, Error> {
        with_curve_knots(degrees, points, false)
    }

    /// [`new`](Self::new) on a flat, row-major list of control points:
    /// `points[i·cols + j]` is `Pᵢⱼ` (`i` along `u`), cut into `rows` rows
    /// of `cols = points.len() / rows`.
    ///
    /// # Errors
    /// [`Error::EmptyGrid`] for an empty list; [`Error::FlatGridLength`]
    /// (naming the length and the rows) when `rows` is zero or does not
    /// divide the length; then the errors of [`new`](Self::new).
    ///
    /// ```
    /// use revolve::{BSplineSurface, Error, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let flat: Vec<Point3<f64>> = (0..6)
    ///     .map(|k| Point3::new((k / 2) as f64, (k % 2) as f64, 0.0))
    ///     .collect();
    /// let k = (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = BSplineSurface::from_flat((2, 1), k.clone(), &flat, 3)?;
    /// assert_eq!(s.points()[2][1], Point3::new(2.0, 1.0, 0.0));
    /// let e = BSplineSurface::from_flat((2, 1), k, &flat, 4).unwrap_err();
    /// assert_eq!(e, Error::FlatGridLength { length: 6, rows: 4 });
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn from_flat(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: &[Point3<f64>],
        rows: usize,
    ) -> Result<Self, Error> {
        Self::new(degrees, knots, cut_rows(points, rows)?)
    }
}

impl BezierSurface {
    /// [`new`](Self::new) on a flat, row-major list of control points:
    /// `points[i·cols + j]` is `Pᵢⱼ`, cut into `rows` rows of
    /// `cols = points.len() / rows`; degrees `(rows − 1, cols − 1)`.
    ///
    /// # Errors
    /// [`Error::EmptyGrid`] for an empty list; [`Error::FlatGridLength`]
    /// when `rows` is zero or does not divide the length; then the errors
    /// of [`new`](Self::new).
    ///
    /// ```
    /// use revolve::{BezierSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let flat = [
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0),
    ///     Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0),
    /// ];
    /// let s = BezierSurface::from_flat(&flat, 2)?;
    /// assert_eq!(s.degrees(), (1, 1));
    /// assert!((s.eval(0.5, 0.5) - Point3::new(0.5, 0.5, 0.25)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn from_flat(points: &[Point3<f64>], rows: usize) -> Result<Self, Error> {
        Self::new(cut_rows(points, rows)?)
    }
}

impl NurbsSurface {
    /// [`new`](Self::new) on flat, row-major lists of control points and
    /// weights: `points[i·cols + j]` is `Pᵢⱼ` with weight
    /// `weights[i·cols + j]`, cut into `rows` rows of
    /// `cols = points.len() / rows`.
    ///
    /// # Errors
    /// [`Error::EmptyGrid`] for no points; [`Error::FlatGridLength`] when
    /// `rows` is zero or does not divide the number of points;
    /// [`Error::WeightCount`] unless there is one weight per point; then
    /// the errors of [`new`](Self::new) (a bad weight as
    /// [`Error::InvalidGridWeight`] with its row and column).
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A quarter cylinder: a quarter circle in u, a line in v.
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let flat = [
    ///     Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 0.0, 1.0),
    ///     Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 1.0, 1.0),
    /// ];
    /// let k = (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let s = NurbsSurface::from_flat((2, 1), k, &flat, &[1.0, 1.0, h, h, 1.0, 1.0], 3)?;
    /// let p = s.eval(0.3, 0.5);
    /// assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn from_flat(
        degrees: (usize, usize),
        knots: (Vec<f64>, Vec<f64>),
        points: &[Point3<f64>],
        weights: &[f64],
        rows: usize,
    ) -> Result<Self, Error> {
        let grid = cut_rows(points, rows)?;
        if weights.len() != points.len() {
            return Err(Error::WeightCount {
                expected: points.len(),
                found: weights.len(),
            });
        }
        let w = cut_rows(weights, rows)?;
        Self::new(degrees, knots, grid, w)
    }
}

//! Interpolation of a grid of points by a tensor-product B-spline surface
//! (Piegl & Tiller, *The NURBS Book*, §9.2.5): parameters averaged over the
//! grid's rows and columns, then curve interpolation along every row and
//! along every column of the result, with the curve layer's machinery.

use super::BSplineSurface;
use super::control_net::flatten_points;
use crate::curve::{Interpolation, averaged_parameters};
use crate::{Error, ParameterDirection};
use nalgebra::{Point3, Vector3};

impl BSplineSurface {
    /// The B-spline surface of degrees `(p, q)` through every point of
    /// `grid` (`grid[i][j]`, `i` along `u`, `j` along `v`):
    /// `S(ūᵢ, v̄ⱼ) = grid[i][j]`, on the domain `[0, 1]²`.
    ///
    /// # Method
    /// - Parameters in `u`: each column `j` (the points `grid[0][j] …
    ///   grid[rows−1][j]`) gets its centripetal parameters, as in
    ///   [`BSpline::interpolate`](crate::BSpline::interpolate), and `ūᵢ` is
    ///   their mean over the columns; columns of zero length (a collapsed
    ///   edge, a pole) are left out of the mean. Likewise `v̄ⱼ` over the
    ///   rows.
    /// - Knots by averaging (Piegl & Tiller eq. 9.8) in each direction:
    ///   `p + 1` (resp. `q + 1`) knots at 0 and at 1, means of `p`
    ///   consecutive parameters inside.
    /// - Each row is interpolated along `v` at the `v̄ⱼ`, giving
    ///   intermediate points `Rᵢⱼ`; then each column of `R` is interpolated
    ///   along `u` at the `ūᵢ`, giving the control points. The two banded
    ///   collocation systems are factored once each.
    ///
    /// The corners are the grid's corners exactly; a grid of collinear,
    /// equally spaced points in each direction gives the bilinear map.
    ///
    /// ```
    /// use revolve::{BSplineSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // 5 × 4 points on the paraboloid z = x² + y².
    /// let grid: Vec<Vec<Point3<f64>>> = (0..5)
    ///     .map(|i| {
    ///         (0..4)
    ///             .map(|j| {
    ///                 let (x, y) = (i as f64 / 4.0, j as f64 / 3.0);
    ///                 Point3::new(x, y, x * x + y * y)
    ///             })
    ///             .collect()
    ///     })
    ///     .collect();
    /// let s = BSplineSurface::interpolate((3, 2), grid.clone())?;
    /// assert_eq!(s.degrees(), (3, 2));
    /// assert_eq!(s.domain(), [(0.0, 1.0), (0.0, 1.0)]);
    /// assert_eq!(s.eval(0.0, 0.0), grid[0][0]);
    /// assert_eq!(s.eval(1.0, 1.0), grid[4][3]);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// In the order checked: [`Error::ZeroDegree`] (either degree 0); the
    /// grid's errors as for [`new`](Self::new): [`Error::EmptyGrid`],
    /// [`Error::RaggedGrid`], [`Error::NonFiniteGridPoint`],
    /// [`Error::GridCoordinateTooLarge`]; [`Error::GridTooSmall`] (fewer
    /// than `p + 1` rows, then fewer than `q + 1` columns);
    /// [`Error::CoincidentGridPoints`] (two consecutive rows, then columns,
    /// equal wherever the grid has length in that direction);
    /// [`Error::SingularSystem`] (rounding only); then the errors of
    /// [`new`](Self::new) for the result (e.g.
    /// [`Error::GridCoordinateTooLarge`] when the surface swings beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE)).
    pub fn interpolate(
        degrees: (usize, usize),
        grid: Vec<Vec<Point3<f64>>>,
    ) -> Result<BSplineSurface, Error> {
        let (p, q) = degrees;
        if p == 0 || q == 0 {
            return Err(Error::ZeroDegree);
        }
        let (_, cols) = flatten_points(&grid)?;
        let rows = grid.len();
        for (direction, found, degree) in [
            (ParameterDirection::U, rows, p),
            (ParameterDirection::V, cols, q),
        ] {
            if found <= degree {
                return Err(Error::GridTooSmall {
                    direction,
                    found,
                    degree,
                });
            }
        }
        let columns: Vec<Vec<Point3<f64>>> = (0..cols)
            .map(|j| grid.iter().map(|row| row[j]).collect())
            .collect();
        let u = averaged_parameters(rows, columns.iter().map(Vec::as_slice)).map_err(|index| {
            Error::CoincidentGridPoints {
                direction: ParameterDirection::U,
                index,
            }
        })?;
        let v = averaged_parameters(cols, grid.iter().map(Vec::as_slice)).map_err(|index| {
            Error::CoincidentGridPoints {
                direction: ParameterDirection::V,
                index,
            }
        })?;
        let along_u = Interpolation::new(p, &u)?;
        let along_v = Interpolation::new(q, &v)?;
        // Along v, row by row: R[i][j].
        let r: Vec<Vec<Vector3<f64>>> = grid
            .iter()
            .map(|row| {
                let values: Vec<Vector3<f64>> = row.iter().map(|p| p.coords).collect();
                along_v.solve(&values)
            })
            .collect();
        // Along u, column by column of R: the control points.
        let mut points = vec![vec![Point3::origin(); cols]; rows];
        for j in 0..cols {
            let column: Vec<Vector3<f64>> = r.iter().map(|row| row[j]).collect();
            for (i, x) in along_u.solve(&column).into_iter().enumerate() {
                points[i][j] = Point3::from(x);
            }
        }
        let knots = (along_u.knots().to_vec(), along_v.knots().to_vec());
        BSplineSurface::new(degrees, knots, points)
    }
}

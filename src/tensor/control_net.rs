//! Grids of control points and weights as the constructors take them
//! (`points[i][j]`, rows along `u`): checked and flattened row-major, and
//! back.

use crate::Error;
use crate::curve::{normalized_weights, validate_points, validate_weights};
use nalgebra::Point3;

/// Checks a grid of control points and flattens it row-major.
///
/// # Errors
/// [`Error::EmptyGrid`] for no rows or an empty first row,
/// [`Error::RaggedGrid`] for a row of another length than the first, then
/// [`Error::NonFiniteGridPoint`] / [`Error::GridCoordinateTooLarge`] with the
/// row and column of the point.
pub(crate) fn flatten_points(
    points: &[Vec<Point3<f64>>],
) -> Result<(Vec<Point3<f64>>, usize), Error> {
    let cols = points.first().map_or(0, Vec::len);
    if cols == 0 {
        return Err(Error::EmptyGrid);
    }
    if let Some(row) = points.iter().position(|r| r.len() != cols) {
        return Err(Error::RaggedGrid {
            row,
            expected: cols,
            found: points[row].len(),
        });
    }
    let flat: Vec<Point3<f64>> = points.iter().flatten().copied().collect();
    validate_points(&flat).map_err(|e| match e {
        Error::NonFinitePoint { index } => Error::NonFiniteGridPoint {
            row: index / cols,
            column: index % cols,
        },
        Error::CoordinateTooLarge { index, value } => Error::GridCoordinateTooLarge {
            row: index / cols,
            column: index % cols,
            value,
        },
        other => other,
    })?;
    Ok((flat, cols))
}
/// Checks a grid of weights for `rows × cols` points and flattens it.
///
/// # Errors
/// [`Error::WeightCount`] (expected `rows·cols`) when the number of rows
/// differs, [`Error::RaggedGrid`] for a row of other than `cols` weights, then
/// the curve checks (`validate_weights`) on the flat list:
/// [`Error::InvalidGridWeight`] (its row and column),
/// [`Error::WeightRatioTooLarge`].
pub(crate) fn flatten_weights(
    weights: &[Vec<f64>],
    rows: usize,
    cols: usize,
) -> Result<Vec<f64>, Error> {
    if weights.len() != rows {
        return Err(Error::WeightCount {
            expected: rows * cols,
            found: weights.iter().map(Vec::len).sum(),
        });
    }
    if let Some(row) = weights.iter().position(|r| r.len() != cols) {
        return Err(Error::RaggedGrid {
            row,
            expected: cols,
            found: weights[row].len(),
        });
    }
    let flat: Vec<f64> = weights.iter().flatten().copied().collect();
    validate_weights(&flat, rows * cols).map_err(|e| match e {
        Error::InvalidWeight { index, weight } => Error::InvalidGridWeight {
            row: index / cols,
            column: index % cols,
            weight,
        },
        other => other,
    })?;
    Ok(normalized_weights(flat))
}
/// A power of two near the largest weight: dividing by it is exact and keeps
/// `w·P` in range.
pub(crate) fn weight_scale(weights: &[f64]) -> f64 {
    let max = weights.iter().fold(0.0_f64, |m, &w| m.max(w));
    if max > 0.0 && max.is_finite() {
        2.0_f64.powi(max.log2().round() as i32)
    } else {
        1.0
    }
}
/// The rows and the columns of a row-major `rows × cols` grid, as lists.
pub(crate) fn rows_and_columns<T: Copy>(flat: &[T], cols: usize) -> (Vec<Vec<T>>, Vec<Vec<T>>) {
    let rows: Vec<Vec<T>> = flat.chunks(cols).map(<[T]>::to_vec).collect();
    let columns = (0..cols)
        .map(|j| rows.iter().map(|r| r[j]).collect())
        .collect();
    (rows, columns)
}

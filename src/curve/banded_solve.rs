//! Banded linear systems: LU factorization with partial pivoting, for the
//! collocation matrices of spline interpolation and the normal equations of
//! least-squares fitting.
//!
//! A square matrix `A` of order `n` with `kl` sub-diagonals and `ku`
//! super-diagonals (`aᵢⱼ = 0` unless `−kl ≤ j − i ≤ ku`) is stored row by
//! row, each row holding the columns `i − kl … i + kl + ku`: the band, plus
//! `kl` more on the right for the fill-in that row interchanges bring
//! (after pivoting, `U` has `kl + ku` super-diagonals). Elimination costs
//! `O(n·kl·(kl + ku))`, a solve `O(n·(2kl + ku))` per right-hand side.
//!
//! Spline collocation matrices are totally positive, so Gaussian
//! elimination without pivoting is stable on them (de Boor & Pinkus, 1977);
//! pivoting costs little and keeps the solver safe for the normal
//! equations and for any rounding.

use crate::Error;
use crate::allocation::try_with_capacity;
use nalgebra::SVector;

/// A banded matrix, then its LU factors (after [`factor`](Self::factor)).
#[derive(Debug, Clone)]
pub(crate) struct BandedMatrix {
    n: usize,
    kl: usize,
    ku: usize,
    /// Entries per stored row: `2·kl + ku + 1`.
    width: usize,
    /// Row `i`, column `j` at `i·width + (j + kl − i)`.
    data: Vec<f64>,
    /// The row swapped with row `k` at step `k` of the elimination.
    pivots: Vec<usize>,
    /// The largest magnitude of an entry of the matrix as given.
    scale: f64,
}

impl BandedMatrix {
    /// The zero matrix of order `n` with `kl` sub- and `ku` super-diagonals.
    ///
    /// # Errors
    /// [`Error::AllocationFailed`] when the band cannot be allocated.
    pub(crate) fn zeros(n: usize, kl: usize, ku: usize) -> Result<Self, Error> {
        let width = kl
            .checked_mul(2)
            .and_then(|w| w.checked_add(ku))
            .and_then(|w| w.checked_add(1))
            .ok_or(Error::AllocationFailed { bytes: usize::MAX })?;
        let len = n
            .checked_mul(width)
            .ok_or(Error::AllocationFailed { bytes: usize::MAX })?;
        let mut data = try_with_capacity(len)?;
        data.resize(len, 0.0);
        Ok(Self {
            n,
            kl,
            ku,
            width,
            data,
            pivots: try_with_capacity(n)?,
            scale: 0.0,
        })
    }

    /// Index of entry `(i, j)` in `data`, if it lies in the stored band.
    #[inline]
    fn index(&self, i: usize, j: usize) -> Option<usize> {
        let offset = (j + self.kl).checked_sub(i)?;
        (i < self.n && j < self.n && offset < self.width).then(|| i * self.width + offset)
    }

    /// Adds `value` to entry `(i, j)`, which must lie in the band
    /// (`−kl ≤ j − i ≤ ku`); returns `false` (and changes nothing) when
    /// it does not.
    pub(crate) fn add(&mut self, i: usize, j: usize, value: f64) -> bool {
        let in_band = j + self.kl >= i && j <= i + self.ku;
        match self.index(i, j) {
            Some(at) if in_band => {
                self.data[at] += value;
                true
            }
            _ => false,
        }
    }

    /// Entry `(i, j)` of the stored band (zero outside it).
    #[cfg(test)]
    fn get(&self, i: usize, j: usize) -> f64 {
        self.index(i, j).map_or(0.0, |at| self.data[at])
    }

    /// Factors the matrix in place into `P·A = L·U` by Gaussian elimination
    /// with partial pivoting (the largest magnitude in the column among the
    /// `kl` rows below the diagonal).
    ///
    /// # Errors
    /// [`Error::SingularSystem`] with the column when no candidate pivot
    /// exceeds `ε ×` the largest magnitude of an entry of `A` (or it is not
    /// finite): the matrix is singular to working precision. A matrix with
    /// a NaN or infinite entry, or the zero matrix, fails at column 0.
    pub(crate) fn factor(&mut self) -> Result<(), Error> {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        self.scale = self.data.iter().fold(0.0_f64, |m, &x| m.max(x.abs()));
        if !self.scale.is_finite() || self.data.iter().any(|x| x.is_nan()) {
            return Err(Error::SingularSystem { column: 0 });
        }
        let tiny = f64::EPSILON * self.scale;
        self.pivots.clear();
        for k in 0..n {
            let last_row = (k + kl).min(n - 1);
            let last_col = (k + kl + ku).min(n - 1);
            // The pivot: the largest magnitude in column k, rows k ..= k + kl.
            let mut best = k;
            let mut best_abs = -1.0;
            for r in k..=last_row {
                let a = self.entry(r, k).abs();
                if a > best_abs {
                    best = r;
                    best_abs = a;
                }
            }
            if best_abs <= tiny || !best_abs.is_finite() {
                return Err(Error::SingularSystem { column: k });
            }
            self.pivots.push(best);
            if best != k {
                for j in k..=last_col {
                    let (a, b) = (self.slot(k, j), self.slot(best, j));
                    self.data.swap(a, b);
                }
            }
            let pivot = self.entry(k, k);
            for i in k + 1..=last_row {
                let at = self.slot(i, k);
                let l = self.data[at] / pivot;
                self.data[at] = l;
                if l != 0.0 {
                    for j in k + 1..=last_col {
                        let u = self.entry(k, j);
                        let at = self.slot(i, j);
                        self.data[at] -= l * u;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves `A·x = b` for every right-hand side (`rhs[i]` is row `i` of
    /// `b`, one column per component), in place, with the factors of
    /// [`factor`](Self::factor), which must have succeeded.
    pub(crate) fn solve<const K: usize>(&self, rhs: &mut [SVector<f64, K>]) {
        let (n, kl, ku) = (self.n, self.kl, self.ku);
        if rhs.len() != n || self.pivots.len() != n {
            return;
        }
        // Forward: the row interchanges and L (unit diagonal).
        for k in 0..n {
            rhs.swap(k, self.pivots[k]);
            let xk = rhs[k];
            let last = (k + kl).min(n - 1);
            for (i, r) in rhs.iter_mut().enumerate().take(last + 1).skip(k + 1) {
                let l = self.entry(i, k);
                if l != 0.0 {
                    *r -= xk * l;
                }
            }
        }
        // Backward: U, with kl + ku super-diagonals.
        for i in (0..n).rev() {
            let mut x = rhs[i];
            let last = (i + kl + ku).min(n - 1);
            for (j, r) in rhs.iter().enumerate().take(last + 1).skip(i + 1) {
                x -= *r * self.entry(i, j);
            }
            rhs[i] = x / self.entry(i, i);
        }
    }

    /// Index of `(i, j)`, known to lie in the stored band.
    #[inline(always)]
    fn slot(&self, i: usize, j: usize) -> usize {
        i * self.width + (j + self.kl - i)
    }

    /// Entry `(i, j)`, known to lie in the stored band.
    #[inline(always)]
    fn entry(&self, i: usize, j: usize) -> f64 {
        self.data[self.slot(i, j)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, Vector1};

    /// A banded matrix from a dense one (entries outside the band must be
    /// zero).
    fn banded(dense: &DMatrix<f64>, kl: usize, ku: usize) -> BandedMatrix {
        let n = dense.nrows();
        let mut m = BandedMatrix::zeros(n, kl, ku).unwrap();
        for i in 0..n {
            for j in 0..n {
                if dense[(i, j)] != 0.0 {
                    assert!(m.add(i, j, dense[(i, j)]), "({i}, {j}) outside the band");
                }
            }
        }
        m
    }

    #[test]
    fn solves_a_system_that_needs_pivoting() {
        // Zero on the diagonal at the first step: elimination without row
        // interchanges would divide by zero.
        let dense = DMatrix::from_row_slice(
            4,
            4,
            &[
                0.0, 2.0, 1.0, 0.0, //
                3.0, 1.0, 0.0, 1.0, //
                0.0, 4.0, 1.0, 2.0, //
                0.0, 0.0, 5.0, 1.0,
            ],
        );
        let x = [1.0, -2.0, 0.5, 3.0];
        let b = &dense * nalgebra::DVector::from_row_slice(&x);
        let mut m = banded(&dense, 1, 2);
        m.factor().unwrap();
        let mut rhs: Vec<Vector1<f64>> = b.iter().map(|&v| Vector1::new(v)).collect();
        m.solve(&mut rhs);
        for (got, want) in rhs.iter().zip(x) {
            assert!((got.x - want).abs() < 1e-14, "{rhs:?}");
        }
    }

    #[test]
    fn band_limits_are_enforced() {
        let mut m = BandedMatrix::zeros(5, 1, 2).unwrap();
        assert!(m.add(3, 2, 1.0));
        assert!(m.add(2, 4, 1.0));
        assert!(!m.add(3, 1, 1.0));
        assert!(!m.add(0, 3, 1.0));
        assert!(!m.add(5, 5, 1.0));
        assert_eq!(m.get(3, 2), 1.0);
        assert_eq!(m.get(3, 1), 0.0);
    }

    #[test]
    fn singular_matrices_are_an_error_naming_the_column() {
        // Column 1 equals twice column 0 in the rows that reach it.
        let dense = DMatrix::from_row_slice(3, 3, &[1.0, 2.0, 0.0, 2.0, 4.0, 0.0, 0.0, 0.0, 1.0]);
        let mut m = banded(&dense, 1, 1);
        assert_eq!(m.factor(), Err(Error::SingularSystem { column: 1 }));
        let mut zero = BandedMatrix::zeros(2, 1, 1).unwrap();
        assert_eq!(zero.factor(), Err(Error::SingularSystem { column: 0 }));
        let mut nan = BandedMatrix::zeros(2, 1, 1).unwrap();
        nan.add(0, 0, f64::NAN);
        assert_eq!(nan.factor(), Err(Error::SingularSystem { column: 0 }));
    }

    #[test]
    fn absurd_sizes_are_an_allocation_error() {
        assert!(matches!(
            BandedMatrix::zeros(usize::MAX / 2, 1, 1),
            Err(Error::AllocationFailed { .. })
        ));
        assert!(matches!(
            BandedMatrix::zeros(3, usize::MAX / 2, 1),
            Err(Error::AllocationFailed { .. })
        ));
    }
}

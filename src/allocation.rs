//! Fallible allocation: a result too large for memory is an error value,
//! not an abort.

use crate::Error;

/// An empty vector with room for `len` elements, or
/// [`Error::AllocationFailed`] when the memory cannot be had (instead of
/// the process aborting).
pub(crate) fn try_with_capacity<T>(len: usize) -> Result<Vec<T>, Error> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| Error::AllocationFailed {
            bytes: len.saturating_mul(std::mem::size_of::<T>()),
        })?;
    Ok(v)
}

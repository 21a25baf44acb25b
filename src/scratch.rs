//! Stack scratch space for the allocation-free hot paths.
//!
//! Evaluation needs a working copy of `degree + 1` coefficients. Up to
//! `6 × 17` entries live in a stack array sized to the next bucket (4, 8, 17
//! or 102, so a cubic does not initialise space it never uses); beyond that a
//! heap buffer is used.

/// Entries for one coefficient row on the stack: enough for degree 16.
pub(crate) const STACK_LEN: usize = 17;

/// Entries for a few rows at once (basis derivatives use five rows).
const TABLE_LEN: usize = 6 * STACK_LEN;

/// Runs `f` on a scratch slice of `len` copies of `fill`.
///
/// No heap allocation happens for `len <= 6 × STACK_LEN`.
#[inline(always)]
pub(crate) fn with_scratch<T: Copy, R>(len: usize, fill: T, f: impl FnOnce(&mut [T]) -> R) -> R {
    if len <= 4 {
        let mut buf = [fill; 4];
        f(&mut buf[..len])
    } else if len <= 8 {
        let mut buf = [fill; 8];
        f(&mut buf[..len])
    } else if len <= STACK_LEN {
        let mut buf = [fill; STACK_LEN];
        f(&mut buf[..len])
    } else if len <= TABLE_LEN {
        let mut buf = [fill; TABLE_LEN];
        f(&mut buf[..len])
    } else {
        let mut buf = vec![fill; len];
        f(&mut buf)
    }
}

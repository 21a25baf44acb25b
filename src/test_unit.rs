//! Test-only: a tiny deterministic generator for the crate's unit tests
//! (xorshift64), so that each test's random cases are reproducible.

/// xorshift64: the next value of `state`, as a uniform number in `[0, 1)`.
pub(crate) fn unit(state: &mut u64) -> f64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

//! A choice between two computed values without a branch.
//!
//! Where the condition follows no pattern from one ray to the next (which
//! side of a root an iterate fell on, which octant a hit lies in), a branch
//! is mispredicted about half the time; the compiler does not always turn
//! `if c { a } else { b }` into a conditional move, so these spell it out.

/// `if pick { a } else { b }`, by a mask rather than a branch.
#[inline(always)]
pub(super) fn select(pick: bool, a: f64, b: f64) -> f64 {
    let mask = u64::from(pick).wrapping_neg();
    f64::from_bits((a.to_bits() & mask) | (b.to_bits() & !mask))
}

#[cfg(test)]
mod tests {
    use super::select;

    #[test]
    fn picks_either_value_bit_for_bit() {
        for (a, b) in [(1.5, -2.0), (-0.0, 0.0), (f64::NAN, f64::INFINITY)] {
            assert_eq!(select(true, a, b).to_bits(), a.to_bits());
            assert_eq!(select(false, a, b).to_bits(), b.to_bits());
        }
    }
}

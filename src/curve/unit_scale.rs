//! Exact rescaling of tiny geometry: coordinates all below `2⁻²⁵⁶` are
//! multiplied by a power of two that brings the largest to `[1, 2)`, a
//! query runs there, and its lengths are scaled back.
//!
//! Below about `1e-154` squared distances underflow, so distances, chord
//! deviations and speeds computed from them come out as zero: nearest
//! points at distance 0, arc lengths of 0, flattenings "certified" with one
//! chord. A product of a float and a power of two is exact unless it
//! overflows or underflows, so the rescaled problem is the same problem,
//! and results scaled back are exact wherever they are normal numbers.

use nalgebra::SVector;

/// Geometry whose largest coordinate is below this is rescaled.
const TINY: f64 = f64::from_bits((1023 - 256) << 52);

/// A power of two `2ᵏ` and its inverse, each as two factors (`2¹⁰⁷⁴` and
/// `2⁻¹⁰⁷⁴` are out of range as one `f64`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct UnitScale {
    up: (f64, f64),
    down: (f64, f64),
}

impl UnitScale {
    /// The scale for geometry of largest coordinate `magnitude`, if it is
    /// tiny (positive and below `2⁻²⁵⁶`); `None` otherwise.
    pub(crate) fn for_magnitude(magnitude: f64) -> Option<UnitScale> {
        if !(magnitude > 0.0 && magnitude < TINY) {
            return None;
        }
        // magnitude·2ᵏ in [1, 2): k = −⌊log₂ magnitude⌋, at most 1074.
        let k = -(magnitude.log2().floor() as i32);
        let (a, b) = (k / 2, k - k / 2);
        Some(UnitScale {
            up: (2f64.powi(a), 2f64.powi(b)),
            down: (2f64.powi(-a), 2f64.powi(-b)),
        })
    }

    /// The two factors whose product is `2ᵏ`.
    pub(crate) fn up_factors(&self) -> (f64, f64) {
        self.up
    }

    /// `x·2ᵏ`.
    pub(crate) fn up(&self, x: f64) -> f64 {
        x * self.up.0 * self.up.1
    }

    /// `x·2⁻ᵏ`.
    pub(crate) fn down(&self, x: f64) -> f64 {
        x * self.down.0 * self.down.1
    }

    /// A point or vector times `2ᵏ`.
    pub(crate) fn up_vector<const D: usize>(&self, v: SVector<f64, D>) -> SVector<f64, D> {
        v * self.up.0 * self.up.1
    }

    /// A point or vector times `2⁻ᵏ`.
    pub(crate) fn down_vector<const D: usize>(&self, v: SVector<f64, D>) -> SVector<f64, D> {
        v * self.down.0 * self.down.1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scales_are_exact_powers_of_two_that_bring_the_largest_to_one() {
        assert!(UnitScale::for_magnitude(1e-70).is_none());
        assert!(UnitScale::for_magnitude(0.0).is_none());
        for m in [1e-78, 1e-154, 1e-200, 1e-300, f64::MIN_POSITIVE, 5e-324] {
            let unit = UnitScale::for_magnitude(m).unwrap();
            let scaled = unit.up(m);
            assert!((1.0..2.0).contains(&scaled), "{m:e} → {scaled}");
            assert_eq!(unit.down(scaled), m);
        }
    }
}

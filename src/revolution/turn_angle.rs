//! The angle of a direction in `[0, 2π]`, a few times cheaper than `atan2`.
//!
//! Every hit's `v` is the angle of the ray point about the axis, so this is
//! on every ray's path (the C library's `atan2` costs about 180
//! instructions). Here, with `a = |sin|`, `b = |cos|` and `z = min(a, b) /
//! max(a, b) ∈ [0, 1]`:
//!
//! - `atan z = atan cᵢ + atan w` with `cᵢ = i/8` the nearest eighth and
//!   `w = (z − cᵢ)/(1 + z cᵢ)`, so `|w| ≤ 1/16`; `atan cᵢ` is tabulated as a
//!   sum of two doubles;
//! - `atan w = w − w³/3 + … + w¹³/13`, whose first omitted term is below
//!   `2⁻⁵⁸ |w|`;
//! - the octant is restored from `π/2 − ·` (when `a > b`), `π − ·` (when
//!   `cos < 0`) and `2π − ·` (when `sin < 0`).
//!
//! `z − cᵢ` is exact (Sterbenz: `z` is within a factor of two of `cᵢ` for
//! `i ≥ 1`), so the error is the few roundings of `z`, `w` and the octant
//! steps: within two units in the last place of `atan2`'s result (the
//! tests check this on ten million directions).

use super::select::select;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// `atan(i/8)` for `i = 0, …, 8`, as `(hi, lo)` with `hi` the double nearest
/// and `lo` the remainder.
const ATAN_EIGHTHS: [(f64, f64); 9] = [
    (0.0, 0.0),
    (0.12435499454676144, -3.1253241424539383e-18),
    (0.24497866312686414, 1.0698755618734451e-17),
    (0.35877067027057225, -2.4623815582638635e-17),
    (0.4636476090008061, 2.2698777452961687e-17),
    (0.5585993153435624, -5.4556305485916264e-18),
    (0.6435011087932844, 1.5834785051444286e-17),
    (0.7188299996216245, -2.1478388444456983e-17),
    (FRAC_PI_4, 3.061616997868383e-17),
];

/// The remainders `π/2 − FRAC_PI_2` and `π − PI`.
const FRAC_PI_2_LO: f64 = 6.123233995736766e-17;
const PI_LO: f64 = 1.2246467991473532e-16;

/// `atan2(sin, cos)` brought into `[0, 2π]` by one turn on the negative
/// half (the result may round up to `2π` itself for a direction just below
/// the positive `cos` axis, as `rem_euclid` may); never `−0`. The two
/// numbers need not be normalized; both zero gives `0`.
#[inline]
pub(super) fn turn_angle(sin: f64, cos: f64) -> f64 {
    let (a, b) = (sin.abs(), cos.abs());
    let steep = a > b;
    let (num, den) = if steep { (b, a) } else { (a, b) };
    if den == 0.0 {
        return 0.0;
    }
    let z = num / den;
    // The nearest eighth (z ≤ 1, so i ≤ 8; a NaN would give 0).
    let i = ((z * 8.0 + 0.5) as usize).min(8);
    let c = i as f64 * 0.125;
    let w = (z - c) / (1.0 + z * c);
    let w2 = w * w;
    let tail = w2
        * (-1.0 / 3.0
            + w2 * (1.0 / 5.0
                + w2 * (-1.0 / 7.0 + w2 * (1.0 / 9.0 + w2 * (-1.0 / 11.0 + w2 / 13.0)))));
    let (hi, lo) = ATAN_EIGHTHS[i];
    let r = hi + (lo + (w + w * tail));
    // The octant by selects: the signs are as good as random from one hit
    // to the next, so a branch on them would be mispredicted half the time.
    let r = select(steep, (FRAC_PI_2 - r) + FRAC_PI_2_LO, r);
    let r = select(cos < 0.0, (PI - r) + PI_LO, r);
    // A `sin` of −0 counts as on the axis (θ = 0 or π), as `+ 0.0` turns a
    // −0 into 0.
    select(sin < 0.0, TAU - r, r + 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spacing of doubles at `x` (`x` finite, nonzero).
    fn ulp(x: f64) -> f64 {
        let x = x.abs();
        f64::from_bits(x.to_bits() + 1) - x
    }

    /// The reference: `atan2` with one turn added on the negative half.
    fn reference(sin: f64, cos: f64) -> f64 {
        let angle = sin.atan2(cos);
        if angle < 0.0 {
            angle + TAU
        } else {
            angle + 0.0
        }
    }

    use crate::test_unit::unit;

    #[test]
    fn agrees_with_atan2_within_two_ulps() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut worst = 0.0_f64;
        for n in 0..10_000_000_u64 {
            // Directions all round the circle, some crowded near the axes
            // and the diagonals (where the octant and the eighths switch),
            // some not of unit length.
            let angle = match n % 4 {
                0 => unit(&mut state) * TAU,
                1 => ((n / 4) % 8) as f64 * (PI / 4.0) + (unit(&mut state) - 0.5) * 1e-6,
                2 => ((n / 4) % 16) as f64 * (PI / 8.0) + (unit(&mut state) - 0.5) * 1e-12,
                _ => ((n / 4) % 4) as f64 * (PI / 2.0) + (unit(&mut state) - 0.5) * 1e-200,
            };
            let length = if n % 3 == 0 {
                1.0
            } else {
                (unit(&mut state) * 40.0 - 20.0).exp2()
            };
            let (sin, cos) = (length * angle.sin(), length * angle.cos());
            let (got, want) = (turn_angle(sin, cos), reference(sin, cos));
            assert!((0.0..=TAU).contains(&got), "{got} for ({sin}, {cos})");
            if want == 0.0 {
                assert_eq!(got.to_bits(), 0, "({sin}, {cos})");
                continue;
            }
            let error = (got - want).abs() / ulp(want);
            worst = worst.max(error);
            assert!(
                error <= 2.0,
                "({sin:e}, {cos:e}): {got} against {want}, {error} ulps"
            );
        }
        // The bound is not idle: the worst case uses part of it.
        assert!(worst > 0.0, "no direction differed from atan2 at all");
    }

    #[test]
    fn axes_zeros_and_signed_zeros() {
        let cases = [
            ((0.0, 1.0), 0.0),
            ((-0.0, 1.0), 0.0),
            ((1.0, 0.0), FRAC_PI_2),
            ((1.0, -0.0), FRAC_PI_2),
            ((0.0, -1.0), PI),
            ((-0.0, -1.0), PI),
            ((-1.0, 0.0), 3.0 * FRAC_PI_2),
            ((0.0, 0.0), 0.0),
            ((-0.0, -0.0), 0.0),
            ((1.0, 1.0), PI / 4.0),
            ((-1.0, -1.0), 5.0 * PI / 4.0),
            ((1e-300, 1.0), 1e-300),
            ((f64::MIN_POSITIVE, f64::MAX), 0.0),
        ];
        for ((sin, cos), want) in cases {
            let got = turn_angle(sin, cos);
            assert!(
                (got - want).abs() <= 2.0 * ulp(want.max(f64::MIN_POSITIVE)),
                "({sin}, {cos}): {got} against {want}"
            );
            assert!(got.is_sign_positive(), "({sin}, {cos}) gave −0");
        }
    }
}

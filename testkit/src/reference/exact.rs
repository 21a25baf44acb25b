//! Exact numbers: every finite `f64` as the dyadic rational `m·2^e` it is,
//! unreduced fractions of big integers, and correct rounding back to `f64`.

use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;

/// A finite `v` as `m·2^e` exactly, `m` odd or zero. Non-finite input gives
/// `(0, 0)`; callers reject it first.
pub fn dyadic(v: f64) -> (BigInt, i32) {
    if !v.is_finite() || v == 0.0 {
        return (BigInt::zero(), 0);
    }
    let bits = v.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (m, e) = if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    };
    let tz = m.trailing_zeros();
    let m = BigInt::from(m >> tz);
    (if v < 0.0 { -m } else { m }, e + tz as i32)
}

/// Finite values as integers over one power of two: `vals[i] = out[i]·2^e`.
pub fn common_exponent(vals: &[f64]) -> (Vec<BigInt>, i32) {
    let parts: Vec<(BigInt, i32)> = vals.iter().map(|&v| dyadic(v)).collect();
    let e = parts
        .iter()
        .filter(|(m, _)| !m.is_zero())
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0);
    let ints = parts
        .into_iter()
        .map(|(m, ei)| if m.is_zero() { m } else { m << (ei - e) as u32 })
        .collect();
    (ints, e)
}

/// `a·2^s` for a signed shift `s`, as a fraction.
pub fn shifted(a: BigInt, s: i64) -> Frac {
    if s >= 0 {
        Frac::from_int(a << s as u64)
    } else {
        Frac {
            num: a,
            den: BigInt::one() << (-s) as u64,
        }
    }
}

/// An exact rational `num/den`, `den > 0`, not reduced (comparisons
/// cross-multiply, so reduction would only cost time).
#[derive(Clone, Debug)]
pub struct Frac {
    pub num: BigInt,
    pub den: BigInt,
}

impl Frac {
    /// `num/den`; `den ≠ 0` is the caller's invariant (a zero `den` gives 0/1
    /// rather than a panic).
    pub fn new(num: BigInt, den: BigInt) -> Self {
        if den.is_zero() {
            return Frac::from_int(BigInt::zero());
        }
        if den.is_negative() {
            Frac {
                num: -num,
                den: -den,
            }
        } else {
            Frac { num, den }
        }
    }

    pub fn from_int(num: BigInt) -> Self {
        Frac {
            num,
            den: BigInt::one(),
        }
    }

    /// The finite `v` exactly.
    pub fn from_f64(v: f64) -> Self {
        let (m, e) = dyadic(v);
        shifted(m, i64::from(e))
    }

    /// Correctly rounded (to nearest, ties to even).
    pub fn to_f64(&self) -> f64 {
        round_ratio(&self.num, &self.den)
    }

    pub fn add(&self, o: &Frac) -> Frac {
        if self.den == o.den {
            return Frac {
                num: &self.num + &o.num,
                den: self.den.clone(),
            };
        }
        Frac {
            num: &self.num * &o.den + &o.num * &self.den,
            den: &self.den * &o.den,
        }
    }

    pub fn sub(&self, o: &Frac) -> Frac {
        self.add(&o.neg())
    }

    pub fn mul(&self, o: &Frac) -> Frac {
        Frac {
            num: &self.num * &o.num,
            den: &self.den * &o.den,
        }
    }

    pub fn neg(&self) -> Frac {
        Frac {
            num: -&self.num,
            den: self.den.clone(),
        }
    }

    pub fn abs(&self) -> Frac {
        Frac {
            num: self.num.abs(),
            den: self.den.clone(),
        }
    }

    /// `self·2^k`.
    pub fn mul_pow2(&self, k: u64) -> Frac {
        Frac {
            num: &self.num << k,
            den: self.den.clone(),
        }
    }
}

impl PartialEq for Frac {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Frac {}
impl PartialOrd for Frac {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Frac {
    fn cmp(&self, o: &Self) -> Ordering {
        if self.den == o.den {
            return self.num.cmp(&o.num);
        }
        (&self.num * &o.den).cmp(&(&o.num * &self.den))
    }
}

/// `2^x` for `-1074 ≤ x ≤ 1023`, exactly.
fn pow2(x: i64) -> f64 {
    if x >= -1022 {
        f64::from_bits(((x + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (x + 1074))
    }
}

/// `num/den` (`den > 0`) correctly rounded to `f64`: to nearest, ties to
/// even, with subnormals, and `±∞` beyond the range.
pub fn round_ratio(num: &BigInt, den: &BigInt) -> f64 {
    if num.is_zero() || den.is_zero() {
        return 0.0;
    }
    let neg = num.is_negative() != den.is_negative();
    let (a, b): (&BigUint, &BigUint) = (num.magnitude(), den.magnitude());
    // q = ⌊a·2^s / b⌋ has 55 or 56 bits; `sticky` records a nonzero remainder.
    let s = 55 - (a.bits() as i64 - b.bits() as i64);
    let (na, nb) = if s >= 0 {
        (a << s as u64, b.clone())
    } else {
        (a.clone(), b << (-s) as u64)
    };
    let q = &na / &nb;
    let sticky = !(&na - &q * &nb).is_zero();
    // Invariant: 2^54 ≤ q < 2^56, so it fits a u64.
    let q = q.to_u64().unwrap_or(u64::MAX >> 8);
    let qb = 64 - i64::from(q.leading_zeros());
    let exp = qb - 1 - s; // value in [2^exp, 2^(exp+1))
    // Bits of q to drop: down to 53 significant bits, or to the 2^-1074 grid.
    let k = if exp >= -1022 { qb - 53 } else { s - 1074 };
    let mag = if k > qb {
        0.0 // below half the smallest subnormal
    } else {
        let mut m = q >> k;
        let rem = q & ((1u64 << k) - 1);
        let half = 1u64 << (k - 1);
        if rem > half || (rem == half && (sticky || m & 1 == 1)) {
            m += 1;
        }
        let x = k - s; // value = m·2^x, m ≤ 2^53
        if m == 0 {
            0.0
        } else if x > 1023 {
            f64::INFINITY
        } else {
            // Exact: the product is representable or overflows to ∞.
            m as f64 * pow2(x)
        }
    };
    if neg { -mag } else { mag }
}

/// Greatest common divisor (Euclid); `gcd(0, 0) = 0`.
pub fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    let (mut a, mut b) = (a.abs(), b.abs());
    while !b.is_zero() {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

/// Least common multiple of positive integers (1 for none).
pub fn lcm<'a>(vals: impl IntoIterator<Item = &'a BigInt>) -> BigInt {
    vals.into_iter().fold(BigInt::one(), |l, v| {
        let g = gcd(&l, v);
        if g.is_zero() { l } else { &l / g * v }
    })
}

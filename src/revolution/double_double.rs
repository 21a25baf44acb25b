//! Double-double arithmetic for tests: a number `hi + lo` of about 106
//! bits, the reference against which rounding bounds are checked.

/// `hi + lo` with `|lo| ≤ ulp(hi)/2`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Dd(pub(super) f64, pub(super) f64);

impl Dd {
    pub(super) fn from(x: f64) -> Self {
        Dd(x, 0.0)
    }

    pub(super) fn add(self, o: Dd) -> Dd {
        // Knuth's two-sum on the high parts, then the low parts.
        let s = self.0 + o.0;
        let v = s - self.0;
        let e = (self.0 - (s - v)) + (o.0 - v) + self.1 + o.1;
        let hi = s + e;
        Dd(hi, e - (hi - s))
    }

    pub(super) fn neg(self) -> Dd {
        Dd(-self.0, -self.1)
    }

    pub(super) fn mul(self, o: Dd) -> Dd {
        // The exact product of the high parts by a fused multiply-add.
        let p = self.0 * o.0;
        let e = self.0.mul_add(o.0, -p) + self.0 * o.1 + self.1 * o.0;
        let hi = p + e;
        Dd(hi, e - (hi - p))
    }

    /// `n / m` for small integers (exact in `f64`), to double-double.
    pub(super) fn ratio(n: f64, m: f64) -> Dd {
        let q = n / m;
        let r = (-q).mul_add(m, n); // exact remainder
        Dd(q, r / m)
    }

    /// The value rounded to the nearest `f64` (about).
    pub(super) fn value(self) -> f64 {
        self.0 + self.1
    }
}

//! Closed intervals of reals with `f64` ends, rounded outward: every
//! operation's exact result on any members lies in the interval it returns
//! (round to nearest errs by at most half an ulp; each end is then moved one
//! ulp outward).
//!
//! The one interval type of testkit's references: the power-form patch
//! enclosure ([`patch_reference`](crate::patch_reference)) and the certified
//! nearest patch hit ([`reference::patch`](crate::reference::patch)). It is
//! written here, not taken from the library, so that the references share no
//! rounding-bound code with the solvers they check. `f64::next_up` needs
//! Rust 1.86, above the crate's MSRV: [`up`] and [`down`] step the bits.

/// The closed interval `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// The next `f64` above `x` (`x` itself for NaN and `+∞`).
pub fn up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next `f64` below `x`.
pub fn down(x: f64) -> f64 {
    -up(-x)
}

// `add`, `sub`, `mul` round outward: named methods, not the operator traits.
#[allow(clippy::should_implement_trait)]
impl Interval {
    /// `[0, 0]`.
    pub const ZERO: Interval = Interval { lo: 0.0, hi: 0.0 };

    /// The single real `x` (an `f64` is exact).
    pub fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }

    /// `[lo, hi]` (the ends ordered).
    pub fn new(a: f64, b: f64) -> Interval {
        Interval {
            lo: a.min(b),
            hi: a.max(b),
        }
    }

    /// Whether `0 ∈ [lo, hi]`.
    pub fn contains_zero(self) -> bool {
        self.lo <= 0.0 && self.hi >= 0.0
    }

    /// The sum.
    pub fn add(self, o: Interval) -> Interval {
        Interval {
            lo: down(self.lo + o.lo),
            hi: up(self.hi + o.hi),
        }
    }

    /// The difference.
    pub fn sub(self, o: Interval) -> Interval {
        Interval {
            lo: down(self.lo - o.hi),
            hi: up(self.hi - o.lo),
        }
    }

    /// The product (the four end products, outward).
    pub fn mul(self, o: Interval) -> Interval {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        Interval {
            lo: down(p.iter().copied().fold(f64::INFINITY, f64::min)),
            hi: up(p.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        }
    }

    /// `self / k` for a nonzero `f64` `k`.
    pub fn div_point(self, k: f64) -> Interval {
        let (a, b) = (self.lo / k, self.hi / k);
        Interval {
            lo: down(a.min(b)),
            hi: up(a.max(b)),
        }
    }

    /// `(1 − τ)a + τb` for the exact `τ ∈ [0, 1]` (in this form, not
    /// `a + τ(b − a)`, so that the widths of `a` and `b` are averaged, not
    /// added up again at each de Casteljau level).
    pub fn lerp(a: Interval, b: Interval, tau: f64) -> Interval {
        let rest = 1.0 - tau;
        // 1 − τ is exact for τ ∈ [½, 1] (Sterbenz) and whenever it rounds
        // back; otherwise bracket it.
        let rest = if 1.0 - rest == tau {
            Interval::point(rest)
        } else {
            Interval::point(1.0).sub(Interval::point(tau))
        };
        rest.mul(a).add(Interval::point(tau).mul(b))
    }

    /// The smallest interval containing both.
    pub fn hull(self, o: Interval) -> Interval {
        Interval {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    /// The largest `|x|` of a member.
    pub fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// The midpoint (rounded).
    pub fn mid(self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }

    /// Every member is `> 0`.
    pub fn positive(self) -> bool {
        self.lo > 0.0
    }

    /// Every member is `< 0`.
    pub fn negative(self) -> bool {
        self.hi < 0.0
    }
}

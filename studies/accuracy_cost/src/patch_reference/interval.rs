//! Closed intervals of reals with `f64` ends, rounded outward: every
//! operation's exact result on any members lies in the interval it returns
//! (round to nearest errs by at most half an ulp; each end is then moved one
//! ulp outward).

/// The closed interval `[lo, hi]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iv {
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

impl Iv {
    /// The single real `x` (an `f64` is exact).
    pub fn point(x: f64) -> Iv {
        Iv { lo: x, hi: x }
    }

    pub fn add(self, o: Iv) -> Iv {
        Iv {
            lo: down(self.lo + o.lo),
            hi: up(self.hi + o.hi),
        }
    }

    pub fn sub(self, o: Iv) -> Iv {
        Iv {
            lo: down(self.lo - o.hi),
            hi: up(self.hi - o.lo),
        }
    }

    pub fn mul(self, o: Iv) -> Iv {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        Iv {
            lo: down(p.iter().copied().fold(f64::INFINITY, f64::min)),
            hi: up(p.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        }
    }

    /// `self / k` for a nonzero `f64` `k`.
    pub fn div_point(self, k: f64) -> Iv {
        let (a, b) = (self.lo / k, self.hi / k);
        Iv {
            lo: down(a.min(b)),
            hi: up(a.max(b)),
        }
    }

    /// `(1 − τ)a + τb` for the exact `τ ∈ [0, 1]` (in this form, not
    /// `a + τ(b − a)`, so that the widths of `a` and `b` are averaged, not
    /// added up again at each de Casteljau level).
    pub fn lerp(a: Iv, b: Iv, tau: f64) -> Iv {
        let rest = 1.0 - tau;
        // 1 − τ is exact for τ ∈ [½, 1] (Sterbenz) and whenever it rounds
        // back; otherwise bracket it.
        let rest = if 1.0 - rest == tau {
            Iv::point(rest)
        } else {
            Iv::point(1.0).sub(Iv::point(tau))
        };
        rest.mul(a).add(Iv::point(tau).mul(b))
    }

    /// The smallest interval containing both.
    pub fn hull(self, o: Iv) -> Iv {
        Iv {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    /// The largest `|x|` of a member.
    pub fn magnitude(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_enclose_the_exact_results() {
        // 0.1 + 0.2 is not 0.3 in binary; the exact sum of the two doubles
        // lies strictly inside the rounded-outward interval.
        let s = Iv::point(0.1).add(Iv::point(0.2));
        assert!(s.lo < 0.1 + 0.2 && 0.1 + 0.2 < s.hi);
        assert!(s.hi - s.lo <= 4.0 * f64::EPSILON);
        let p = Iv { lo: -2.0, hi: 3.0 }.mul(Iv { lo: -5.0, hi: 1.0 });
        assert!(p.lo <= -15.0 && p.hi >= 10.0 && p.lo > -15.0 - 1e-13);
        let q = Iv { lo: 1.0, hi: 2.0 }.div_point(-4.0);
        assert!(q.lo <= -0.5 && q.hi >= -0.25);
        assert_eq!(up(0.0), f64::from_bits(1));
        assert_eq!(down(0.0), -f64::from_bits(1));
        assert_eq!(up(-1.0), -1.0 + f64::EPSILON / 2.0);
        assert_eq!(down(1.0), 1.0 - f64::EPSILON / 2.0);
        let l = Iv::lerp(Iv::point(1.0), Iv::point(3.0), 0.25);
        assert!(l.lo <= 1.5 && 1.5 <= l.hi);
        assert!(
            Iv {
                lo: 1e-300,
                hi: 1.0
            }
            .positive()
        );
        assert!(!Iv { lo: 0.0, hi: 1.0 }.positive());
    }
}

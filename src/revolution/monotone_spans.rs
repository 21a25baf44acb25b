//! Certificates that a span's hit function is strictly monotonic for every
//! line of a range of slopes and heights of closest approach: the second
//! table of [`MeridianCells`](super::meridian_cells::MeridianCells).

/// The spans' Bernstein coefficients, `w` per span (degree `w − 1`), for
/// [`MeridianCells::certify_monotone`](super::meridian_cells::MeridianCells::certify_monotone), with the weights of products,
/// [`product_weights`](super::meridian_cells::product_weights) of degree `w − 1`.
#[derive(Debug, Clone, Copy)]
pub(super) struct SpanCurves<'a> {
    pub(super) xs: &'a [f64],
    pub(super) ys: &'a [f64],
    pub(super) w: usize,
    pub(super) weights: &'a [f64],
}

/// The certificates of monotonicity of a profile's spans, for boxes of
/// line classes.
///
/// For a line with numbers `ρ₀²`, `y_c` and `c`, the hits on a span are
/// the roots of `F(s) = x(s)² − ρ₀² − g² (y(s) − y_c)²` (the intersector's
/// `f` is `−d_y² F`), so
///
/// `c² F′ = c² (x²)′ − (1 − c²) ((y − y_c)²)′`,
///
/// which does not depend on `ρ₀²`. Its Bernstein coefficients (degree
/// `2n − 1`) are `vᵢ = c² pᵢ − (1 − c²)(qᵢ − 2 y_c rᵢ)` with `p = (x²)′`,
/// `q = (y²)′`, `r = y′` (raised to degree `2n − 1`): bilinear in `c²` and
/// `y_c`, so over a box of `(c², y_c)` they are extreme at its corners. If
/// they are all certainly of one sign there (beyond [`Monotone::TOL`] of
/// their terms' size, which covers the rounding here and in the
/// coefficients), `F′` keeps that sign on the whole span for every line of
/// the box, and `F` has at most one root there, a simple one.
///
/// For a fixed `c` each condition `σ vᵢ > TOL · sizeᵢ` (`σ = ±1`) holds on
/// a half-line of `y_c` ([`Monotone::heights`]), so the heights certified
/// for a range of slopes are one interval per sign.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Monotone {
    /// The coefficients of every span, `per_span` (`2n`) a span.
    terms: Vec<Term>,
    per_span: usize,
}
/// One coefficient of `c² F′` (see [`Monotone`]): `p`, `q`, `r`, and for
/// [`Monotone::heights`] with `T = 2 · TOL`: `T |p|`, `T |q|` and `1 / (2r
/// (1 ± T))` (infinite for `r = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Term {
    p: f64,
    q: f64,
    r: f64,
    tp: f64,
    tq: f64,
    up: f64,
    down: f64,
}
impl Monotone {
    /// The relative margin by which the coefficients must be of one sign.
    const TOL: f64 = 1e-9;
    /// The margin [`Self::heights`] asks, twice [`Self::TOL`]: the rounding
    /// of its roots (a few ulps of the terms) then still leaves every
    /// height it returns certain by `TOL`.
    const T: f64 = 2.0 * Self::TOL;

    /// The certificates of the spans `curves`.
    pub(super) fn new(curves: SpanCurves<'_>) -> Self {
        let w = curves.w;
        let per_span = 2 * (w - 1);
        let m = per_span as f64;
        let spans = curves.xs.len() / w;
        let mut terms = Vec::with_capacity(spans * per_span);
        // x², y² and y (raised): degree 2n, reused for every span.
        let mut products = vec![[0.0; 3]; 2 * w - 1];
        for (xs, ys) in curves.xs.chunks_exact(w).zip(curves.ys.chunks_exact(w)) {
            products.fill([0.0; 3]);
            // Σ_{i+j=k} C(n,i)C(n,j)/C(2n,k) aᵢbⱼ: the product of two
            // degree-n polynomials in the Bernstein basis of degree 2n
            // (y times 1 = Σ Bⱼ raises y).
            for i in 0..w {
                for j in 0..w {
                    let weight = curves.weights[i * w + j];
                    let out = &mut products[i + j];
                    out[0] += weight * xs[i] * xs[j];
                    out[1] += weight * ys[i] * ys[j];
                    out[2] += weight * ys[i];
                }
            }
            terms.extend(products.windows(2).map(|pair| {
                let [p, q, r] = std::array::from_fn(|k| m * (pair[1][k] - pair[0][k]));
                Term {
                    p,
                    q,
                    r,
                    tp: Self::T * p.abs(),
                    tq: Self::T * q.abs(),
                    up: 1.0 / (2.0 * r * (1.0 + Self::T)),
                    down: 1.0 / (2.0 * r * (1.0 - Self::T)),
                }
            }));
        }
        Monotone { terms, per_span }
    }

    /// Span `s`'s coefficients.
    fn span(&self, s: usize) -> &[Term] {
        &self.terms[s * self.per_span..(s + 1) * self.per_span]
    }

    /// The heights `y_c` at which span `s`'s `c² F′` is certainly
    /// positive, and those at which it is certainly negative, for every
    /// `c` with `u = c² / (1 − c²)` in `[u0, u1]`: open intervals, `(∞,
    /// −∞)` when empty.
    ///
    /// Divided by `1 − c²`, the condition on one coefficient is
    /// `σ(u p − q + 2 r y) > T (u |p| + |q| + 2 |r| |y|)`, that is
    /// `a + b y − T |b| |y| > 0` with `a = σ(u p − q) − T (u |p| + |q|)` and
    /// `b = 2σr`: monotonic in `y` with the sign of `b`, it holds on one
    /// side of its root `−a / (b (1 ± T))` (`+` for `a ≥ 0`), everywhere or
    /// nowhere for `b = 0`. Over `[u0, u1]` it is linear in `u`, so its two
    /// ends decide.
    pub(super) fn heights(&self, s: usize, (u0, u1): (f64, f64)) -> [(f64, f64); 2] {
        let (mut rising, mut falling) = (
            (f64::NEG_INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::INFINITY),
        );
        for u in [u0, u1] {
            for t in self.span(s) {
                let v = u * t.p - t.q;
                let size = u * t.tp + t.tq;
                let (a_rising, a_falling) = (v - size, -v - size);
                // The roots for b = 2r and b = −2r.
                let root_rising = -a_rising * if a_rising >= 0.0 { t.up } else { t.down };
                let root_falling = a_falling * if a_falling >= 0.0 { t.up } else { t.down };
                // (Plain comparisons: no NaN reaches here.)
                let (larger, smaller) = (
                    |a: f64, b: f64| if a > b { a } else { b },
                    |a: f64, b: f64| if a < b { a } else { b },
                );
                if t.r > 0.0 {
                    rising.0 = larger(rising.0, root_rising);
                    falling.1 = smaller(falling.1, root_falling);
                } else if t.r < 0.0 {
                    rising.1 = smaller(rising.1, root_rising);
                    falling.0 = larger(falling.0, root_falling);
                } else {
                    // b = 0: certain for every y or for none.
                    let (rises, falls) = (a_rising > 0.0, a_falling > 0.0);
                    if !rises {
                        rising = (f64::INFINITY, f64::NEG_INFINITY);
                    }
                    if !falls {
                        falling = (f64::INFINITY, f64::NEG_INFINITY);
                    }
                }
            }
        }
        [rising, falling]
    }

    /// Whether span `s`'s `c² F′` is certainly of one sign for every `c ∈
    /// [c0, c1]` and `y_c ∈ [y0, y1]`, by its coefficients at the box's
    /// four corners (the reference for [`Self::heights`]).
    #[cfg(test)]
    pub(super) fn holds(&self, s: usize, (c0, c1): (f64, f64), (y0, y1): (f64, f64)) -> bool {
        let mut sign = 0.0;
        for &c2 in &[c0 * c0, c1 * c1] {
            for &yc in &[y0, y1] {
                for t in self.span(s) {
                    let (dx2, dy2, dy) = (t.p, t.q, t.r);
                    let q = dy2 - 2.0 * yc * dy;
                    let v = c2 * dx2 - (1.0 - c2) * q;
                    let size = c2 * dx2.abs() + (1.0 - c2) * (dy2.abs() + 2.0 * (yc * dy).abs());
                    let certain = if v > Self::TOL * size {
                        1.0
                    } else if v < -Self::TOL * size {
                        -1.0
                    } else {
                        return false;
                    };
                    if sign == 0.0 {
                        sign = certain;
                    } else if sign != certain {
                        return false;
                    }
                }
            }
        }
        true
    }
}

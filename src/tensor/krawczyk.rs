//! Krawczyk's test: whether a box of the patch search holds exactly one
//! root of the ray's two plane distances.

/// Boxes at most this wide (in both parameters) try the uniqueness test.
pub(super) const TRY_UNIQUE: f64 = 1.0 / 8.0;
/// Krawczyk's test on the box's coefficients (in the box's own parameters
/// `x ∈ [0, 1]²`): with `c` the centre, `J` an interval enclosure of the
/// Jacobian of `F = (α, β)` over the box (from the derivative nets: `p` times
/// the range of the differences in the first parameter, `q` times in the
/// second) and `Y` the inverse of its midpoint,
/// `K = c − Y·F(c) + (I − Y·J)·([0, 1]² − c)`. If `K` lies strictly inside
/// the box, the box holds exactly one root of `F` (Krawczyk 1969; Moore,
/// Kearfott & Cloud, *Introduction to Interval Analysis*, §8.2); `Y` may
/// be any matrix, so its own rounding does not matter. The enclosures are
/// widened for every rounding on the way: each coefficient carries `bound`
/// (so `F(c)` gains `bound` and `J` `2·degree·bound`), the differences of
/// `J` and the averages of `F(c)` (`p + q` levels) their own rounding, and
/// `K`'s sums and products `4ε` times the sum of their terms' magnitudes
/// (Higham, *Accuracy and Stability of Numerical Algorithms*, §3.1).
/// Beyond that, `K` must clear the box's sides by `1e-6`.
// Index loops mirror the matrix formulas.
#[allow(clippy::needless_range_loop)]
pub(super) fn unique_root(coef: &[[f64; 4]], p: usize, q: usize, bound: [f64; 2]) -> bool {
    let cols = q + 1;
    // Interval Jacobian: rows α, β; columns ∂/∂x₀ (rows of the net), ∂/∂x₁.
    let mut jac = [[(f64::INFINITY, f64::NEG_INFINITY); 2]; 2];
    let widen = |r: &mut (f64, f64), x: f64| {
        r.0 = r.0.min(x);
        r.1 = r.1.max(x);
    };
    for i in 0..=p {
        for j in 0..=q {
            let c = coef[i * cols + j];
            for f in 0..2 {
                if i < p {
                    widen(
                        &mut jac[f][0],
                        p as f64 * (coef[(i + 1) * cols + j][f] - c[f]),
                    );
                }
                if j < q {
                    widen(
                        &mut jac[f][1],
                        q as f64 * (coef[i * cols + j + 1][f] - c[f]),
                    );
                }
            }
        }
    }
    for (f, row) in jac.iter_mut().enumerate() {
        for (k, r) in row.iter_mut().enumerate() {
            let degree = if k == 0 { p } else { q };
            if degree == 0 {
                *r = (0.0, 0.0);
            }
            let pad = 2.0 * degree as f64 * bound[f];
            let own = 2.0 * f64::EPSILON * r.0.abs().max(r.1.abs());
            *r = (r.0 - pad - own, r.1 + pad + own);
        }
    }
    // F at the centre: de Casteljau at ½ in both parameters.
    if p + 1 > 32 || cols > 32 {
        return false;
    }
    let mut centre = [0.0_f64; 2];
    // Averages round by at most ε/2 of the largest coefficient each.
    let f_bound: [f64; 2] = std::array::from_fn(|f| {
        let largest = coef.iter().fold(0.0_f64, |m, c| m.max(c[f].abs()));
        bound[f] + 0.5 * (p + q) as f64 * f64::EPSILON * largest
    });
    for (f, value) in centre.iter_mut().enumerate() {
        let mut row_values = [0.0_f64; 32];
        for (i, slot) in row_values.iter_mut().enumerate().take(p + 1) {
            let mut w = [0.0_f64; 32];
            for j in 0..cols {
                w[j] = coef[i * cols + j][f];
            }
            *slot = half_value(&mut w[..cols]);
        }
        *value = half_value(&mut row_values[..p + 1]);
    }
    let mid = |r: (f64, f64)| 0.5 * (r.0 + r.1);
    let m = [
        [mid(jac[0][0]), mid(jac[0][1])],
        [mid(jac[1][0]), mid(jac[1][1])],
    ];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    if det == 0.0 || !det.is_finite() {
        return false;
    }
    let y = [
        [m[1][1] / det, -m[0][1] / det],
        [-m[1][0] / det, m[0][0] / det],
    ];
    for i in 0..2 {
        // c − Y F(c), with F(c) ± f_bound.
        let yf = y[i][0] * centre[0] + y[i][1] * centre[1];
        let mut radius = y[i][0].abs() * f_bound[0] + y[i][1].abs() * f_bound[1];
        // Magnitudes of the terms summed, for their rounding.
        let mut terms = (y[i][0] * centre[0]).abs() + (y[i][1] * centre[1]).abs() + 0.5;
        // (I − Y J)(x − c), x − c ∈ [−½, ½]².
        for k in 0..2 {
            let identity = if i == k { 1.0 } else { 0.0 };
            // (Y J)_{ik} = Σ_j Y_ij J_jk: an interval.
            let (mut lo, mut hi) = (0.0, 0.0);
            for j in 0..2 {
                let (a, b) = (y[i][j] * jac[j][k].0, y[i][j] * jac[j][k].1);
                lo += a.min(b);
                hi += a.max(b);
                terms += a.abs().max(b.abs());
            }
            let magnitude = (identity - lo).abs().max((identity - hi).abs());
            radius += 0.5 * magnitude;
            terms += magnitude;
        }
        radius += 4.0 * f64::EPSILON * (terms + radius);
        let centre_i = 0.5 - yf;
        if !(centre_i - radius > 1e-6 && centre_i + radius < 1.0 - 1e-6) {
            return false;
        }
    }
    true
}
/// The value at ½ of the Bernstein polynomial with coefficients `w`
/// (overwritten).
fn half_value(w: &mut [f64]) -> f64 {
    let n = w.len();
    for level in 1..n {
        for k in 0..n - level {
            w[k] = 0.5 * (w[k] + w[k + 1]);
        }
    }
    w[0]
}

//! Bézier clipping of a box's two plane distances, and the restriction of
//! a box's coefficient lines to a sub-range (de Casteljau, in place).
//!
//! In each parameter, the convex hull of a distance function's control
//! points bounds the range where it can vanish (Nishita, Sederberg &
//! Nakajima, "Ray tracing trimmed rational surface patches", SIGGRAPH 1990).

/// A clipped box is clipped again (rather than halved) while it keeps at
/// most this fraction of its area.
pub(super) const CLIP_ENOUGH: f64 = 0.64;

/// Bézier clipping (Nishita, Sederberg & Nakajima 1990) of a box's
/// coefficients: the ranges `(s, t)` (of the box's own `[0, 1]²`) outside
/// which the box holds no root of `(α, β)`, or `None` if it holds none.
///
/// For `s`, `d = n·(α, β)` with `n` perpendicular to the net's mean
/// direction along `t` (so that `d` varies mostly with `s`); its
/// coefficients `dᵢⱼ`, widened by their rounding, give points
/// `(i/p, dᵢⱼ)` whose convex hull contains the graph of `d` over each line
/// of constant `t` (the convex hull property in `s`, for every `t` at once:
/// the `dᵢ(t)` are convex combinations of the `dᵢⱼ`). Where the hull misses
/// `d = 0` there is no root. The same with the roles of `s` and `t`
/// exchanged. The ends are widened by `8ε` for the rounding of the hull's
/// crossings.
pub(super) fn clip(
    coef: &[[f64; 4]],
    (p, q): (usize, usize),
    bound: [f64; 2],
) -> Option<((f64, f64), (f64, f64))> {
    let cols = q + 1;
    let at = |i: usize, j: usize| coef[i * cols + j];
    // Mean direction of the net along t (last column minus first) and
    // along s (last row minus first).
    let (mut vt, mut vs) = ([0.0_f64; 2], [0.0_f64; 2]);
    for i in 0..=p {
        let (a, b) = (at(i, 0), at(i, q));
        vt[0] += b[0] - a[0];
        vt[1] += b[1] - a[1];
    }
    for j in 0..=q {
        let (a, b) = (at(0, j), at(p, j));
        vs[0] += b[0] - a[0];
        vs[1] += b[1] - a[1];
    }
    let mut s_range = if p == 0 {
        (0.0, 1.0)
    } else {
        clip_line(coef, p, q, true, normal_to(vt), bound)?
    };
    let mut t_range = if q == 0 {
        (0.0, 1.0)
    } else {
        clip_line(coef, p, q, false, normal_to(vs), bound)?
    };
    let kept = (s_range.1 - s_range.0) * (t_range.1 - t_range.0);
    if kept > CLIP_ENOUGH {
        // Where the image's directions along s and t are nearly parallel
        // (near a collapsed corner, or a fold) the lines across them say
        // little; the lines along them may say more. Both ranges hold
        // every root, so their intersection does.
        let meet = |a: (f64, f64), b: (f64, f64)| {
            let r = (a.0.max(b.0), a.1.min(b.1));
            (r.0 <= r.1).then_some(r)
        };
        if p > 0 {
            let along = normal_to(normal_to(vt));
            s_range = meet(s_range, clip_line(coef, p, q, true, along, bound)?)?;
        }
        if q > 0 {
            let along = normal_to(normal_to(vs));
            t_range = meet(t_range, clip_line(coef, p, q, false, along, bound)?)?;
        }
    }
    Some((s_range, t_range))
}
/// A unit vector perpendicular to `v` (`(1, 0)` if `v` vanishes).
fn normal_to(v: [f64; 2]) -> [f64; 2] {
    let norm = v[0].hypot(v[1]);
    if norm > 0.0 && norm.is_finite() {
        [-v[1] / norm, v[0] / norm]
    } else {
        [1.0, 0.0]
    }
}
/// The range in `s` (`along_s`) or in `t` where the hull of the points
/// `(index/degree, n·(α, β))` meets zero (see [`clip`]); `None` if nowhere.
fn clip_line(
    coef: &[[f64; 4]],
    p: usize,
    q: usize,
    along_s: bool,
    n: [f64; 2],
    bound: [f64; 2],
) -> Option<(f64, f64)> {
    let cols = q + 1;
    let (degree, other) = if along_s { (p, q) } else { (q, p) };
    // Per abscissa, the least and greatest ordinate, widened by the
    // coefficients' rounding and the projection's.
    let pad = n[0].abs() * bound[0] + n[1].abs() * bound[1];
    let mut low = [0.0_f64; 33];
    let mut high = [0.0_f64; 33];
    if degree >= low.len() {
        return Some((0.0, 1.0));
    }
    for i in 0..=degree {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for j in 0..=other {
            let c = if along_s {
                coef[i * cols + j]
            } else {
                coef[j * cols + i]
            };
            let d = n[0] * c[0] + n[1] * c[1];
            lo = lo.min(d);
            hi = hi.max(d);
        }
        let slop = pad + 2.0 * f64::EPSILON * lo.abs().max(hi.abs());
        low[i] = lo - slop;
        high[i] = hi + slop;
    }
    // The hull is bounded below by the lower hull of the lows and above by
    // the upper hull of the highs; it meets zero where the first is ≤ 0
    // and the second ≥ 0.
    let below = non_positive_range(&low[..=degree])?;
    for h in high[..=degree].iter_mut() {
        *h = -*h;
    }
    let above = non_positive_range(&high[..=degree])?;
    let (from, to) = (below.0.max(above.0), below.1.min(above.1));
    if from > to {
        return None;
    }
    let widen = 8.0 * f64::EPSILON;
    Some(((from - widen).max(0.0), (to + widen).min(1.0)))
}
/// The range of `x ∈ [0, 1]` where the lower convex hull `L` of the points
/// `(i/n, ys[i])` (`n = ys.len() − 1 ≥ 1`) is `≤ 0`, or `None` if `L > 0`
/// throughout. `L` is convex, so the range is an interval, and `L` is least
/// at a vertex.
fn non_positive_range(ys: &[f64]) -> Option<(f64, f64)> {
    let n = ys.len() - 1;
    let x = |i: usize| i as f64 / n as f64;
    // Monotone chain (Andrew 1979): the lower hull's vertices, left to right.
    let mut hull = [0_usize; 33];
    let mut len = 0;
    for i in 0..=n {
        while len >= 2 {
            let (a, b) = (hull[len - 2], hull[len - 1]);
            let cross = (x(b) - x(a)) * (ys[i] - ys[a]) - (ys[b] - ys[a]) * (x(i) - x(a));
            if cross <= 0.0 {
                len -= 1;
            } else {
                break;
            }
        }
        hull[len] = i;
        len += 1;
    }
    let hull = &hull[..len];
    let first = hull.iter().position(|&i| ys[i] <= 0.0)?;
    let last = hull.iter().rposition(|&i| ys[i] <= 0.0)?;
    let crossing = |a: usize, b: usize| x(a) + (x(b) - x(a)) * (ys[a] / (ys[a] - ys[b]));
    let from = if first == 0 {
        0.0
    } else {
        crossing(hull[first - 1], hull[first])
    };
    let to = if last == len - 1 {
        1.0
    } else {
        crossing(hull[last], hull[last + 1])
    };
    Some((from, to))
}
/// Replaces the box coefficients by those of the sub-box `r` (of
/// `[0, 1]`) in `s` (`along_s`) or in `t`: each line of coefficients is
/// split at `r.1` (keeping the left part), then at `r.0/r.1` (keeping the
/// right part).
pub(super) fn restrict_lines(
    coef: &mut [[f64; 4]],
    p: usize,
    q: usize,
    along_s: bool,
    r: (f64, f64),
) {
    let cols = q + 1;
    let (count, len, stride, step): (usize, usize, usize, usize) = if along_s {
        (cols, p + 1, 1, cols)
    } else {
        (p + 1, cols, cols, 1)
    };
    let mut work = [[0.0_f64; 4]; 33];
    if len > work.len() {
        return restrict_long_lines(coef, count, len, stride, step, r);
    }
    for line in 0..count {
        let at = |k: usize| line * stride + k * step;
        let w = &mut work[..len];
        for (k, slot) in w.iter_mut().enumerate() {
            *slot = coef[at(k)];
        }
        if r.1 < 1.0 {
            split_keep(w, r.1, true);
        }
        if r.0 > 0.0 {
            split_keep(w, r.0 / r.1, false);
        }
        for (k, slot) in w.iter().enumerate() {
            coef[at(k)] = *slot;
        }
    }
}
/// [`restrict_lines`] for lines longer than its stack buffer.
fn restrict_long_lines(
    coef: &mut [[f64; 4]],
    count: usize,
    len: usize,
    stride: usize,
    step: usize,
    r: (f64, f64),
) {
    let mut w = vec![[0.0_f64; 4]; len];
    for line in 0..count {
        for (k, slot) in w.iter_mut().enumerate() {
            *slot = coef[line * stride + k * step];
        }
        if r.1 < 1.0 {
            split_keep(&mut w, r.1, true);
        }
        if r.0 > 0.0 {
            split_keep(&mut w, r.0 / r.1, false);
        }
        for (k, slot) in w.iter().enumerate() {
            coef[line * stride + k * step] = *slot;
        }
    }
}
/// De Casteljau at `x` on the Bernstein coefficients `w` (in place): `w`
/// becomes the coefficients on `[0, x]` (`left`) or on `[x, 1]`.
fn split_keep(w: &mut [[f64; 4]], x: f64, left: bool) {
    let n = w.len();
    if left {
        // Level by level from the right: w[k] holds the k-th left
        // coefficient once level k is done.
        for level in 1..n {
            for k in (level..n).rev() {
                let (a, b) = (w[k - 1], w[k]);
                for c in 0..4 {
                    w[k][c] = a[c] + x * (b[c] - a[c]);
                }
            }
        }
    } else {
        for level in 1..n {
            for k in 0..n - level {
                let (a, b) = (w[k], w[k + 1]);
                for c in 0..4 {
                    w[k][c] = a[c] + x * (b[c] - a[c]);
                }
            }
        }
    }
}

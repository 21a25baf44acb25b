//! Newton's method on the squared distance from a point to a piece of a
//! (rational) Bézier patch, kept in the piece's parameter square: the
//! nearest-point search's candidates and the points its second-order bound
//! is taken about.

use super::patch::{project_jet, tensor_jet};
use crate::curve::Homogeneous;

/// Newton's method on `f = |S − P|²` over the piece of net `net` (`P` the
/// origin), in its parameters `[0, 1]²` from `start`, kept in the square:
/// a coordinate on a side where the gradient points out is held there and
/// the other solved alone; where the Hessian is not positive definite the
/// Gauss–Newton matrix `JᵀJ` (damped) takes its place; a step that does
/// not descend (beyond rounding) is halved; it stops after `steps` steps
/// or at a step below `shortest`. Returns the nearest point evaluated
/// (the later of two within rounding) and its distance.
pub(super) fn newton(
    net: &[Homogeneous<3>],
    cols: usize,
    start: (f64, f64),
    (steps, shortest): (usize, f64),
) -> ((f64, f64), f64) {
    // The rounding of a computed |S − P|² (`reach` bounds |S − P|):
    // differences below it are noise, and the later point is kept.
    let reach = net.iter().fold(0.0_f64, |m, h| m.max(h.wp.amax() / h.w));
    let noise = |f: f64| 16.0 * f64::EPSILON * (f + 4.0 * f.sqrt() * reach);
    let mut x = start;
    let mut best = (x, f64::INFINITY);
    let mut previous: Option<((f64, f64), f64)> = None;
    let mut halvings = 0;
    for _ in 0..steps {
        let d = project_jet(&tensor_jet(net, cols, x.0, x.1, 2), 2);
        let (r, su, sv) = (d[0][0], d[1][0], d[0][1]);
        let f = r.norm_squared();
        if !f.is_finite() {
            break;
        }
        if f <= best.1 + noise(best.1) {
            best = (x, f);
        }
        if let Some((from, f_from)) = previous {
            if f > f_from + noise(f_from) && halvings < 4 {
                // No descent: back toward where the step started.
                halvings += 1;
                x = ((from.0 + x.0) * 0.5, (from.1 + x.1) * 0.5);
                continue;
            }
        }
        let g = [r.dot(&su), r.dot(&sv)];
        let gauss = [su.dot(&su), su.dot(&sv), sv.dot(&sv)];
        let h = [
            gauss[0] + r.dot(&d[2][0]),
            gauss[1] + r.dot(&d[1][1]),
            gauss[2] + r.dot(&d[0][2]),
        ];
        let at = [x.0, x.1];
        // Held: on a side, with the gradient pointing out of the square.
        let held = [0, 1].map(|i| (at[i] <= 0.0 && g[i] > 0.0) || (at[i] >= 1.0 && g[i] < 0.0));
        let step = match held {
            [true, true] => break,
            [false, false] => solve(h, g).or_else(|| solve(damped(gauss), g)),
            [false, true] => single(h[0], gauss[0], g[0]).map(|s| [s, 0.0]),
            [true, false] => single(h[2], gauss[2], g[1]).map(|s| [0.0, s]),
        };
        let Some(step) = step else { break };
        let next = (
            (x.0 + step[0]).clamp(0.0, 1.0),
            (x.1 + step[1]).clamp(0.0, 1.0),
        );
        if (next.0 - x.0).abs().max((next.1 - x.1).abs()) <= shortest {
            break;
        }
        previous = Some((x, f));
        halvings = 0;
        x = next;
    }
    if best.1.is_finite() {
        (best.0, best.1.sqrt())
    } else {
        let r = tensor_jet(net, cols, start.0, start.1, 0)[0][0];
        (start, (r.wp / r.w).norm())
    }
}

/// The Newton step `−H⁻¹g` for the symmetric `H = [h₀ h₁; h₁ h₂]`, if `H`
/// is positive definite.
fn solve(h: [f64; 3], g: [f64; 2]) -> Option<[f64; 2]> {
    let det = h[0] * h[2] - h[1] * h[1];
    if !(h[0] > 0.0 && h[2] > 0.0 && det > 1e-12 * h[0] * h[2]) {
        return None;
    }
    let step = [
        -(h[2] * g[0] - h[1] * g[1]) / det,
        -(h[0] * g[1] - h[1] * g[0]) / det,
    ];
    step.iter().all(|s| s.is_finite()).then_some(step)
}

/// `JᵀJ` damped by a millionth of its trace.
fn damped(g: [f64; 3]) -> [f64; 3] {
    let mu = 1e-6 * (g[0] + g[2]) + f64::MIN_POSITIVE;
    [g[0] + mu, g[1], g[2] + mu]
}

/// The one-coordinate step `−g/h`, with `JᵀJ`'s entry where `h ≤ 0`.
fn single(h: f64, gauss: f64, g: f64) -> Option<f64> {
    let h = if h > 0.0 { h } else { gauss };
    let step = -g / h;
    (h > 0.0 && step.is_finite()).then_some(step)
}

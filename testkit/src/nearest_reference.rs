//! An independent reference for nearest-point queries on surfaces: dense
//! samples of `Surface::eval` over the domain, the best local minima of the
//! samples refined by damped Gauss–Newton steps (Levenberg–Marquardt, on
//! `Surface::eval` and `Surface::partials` only, kept in the domain). Its
//! distance is an upper bound of the true least distance (it is the
//! distance of a surface point), and near it for smooth surfaces.

use revolve::Surface;
use revolve::nalgebra::{Matrix2, Point3, Vector2};

/// The reference: the nearest point found, its parameters and distance.
#[derive(Debug, Clone, Copy)]
pub struct Reference {
    pub uv: (f64, f64),
    pub point: Point3<f64>,
    pub distance: f64,
}

/// How many of the samples' local minima are refined.
const REFINED: usize = 16;

/// Levenberg–Marquardt steps per refined minimum.
const STEPS: usize = 60;

/// The nearest of `side × side` samples (uniform over the domain, edges
/// included) to `p`, with the best local minima of the samples refined.
pub fn sampled_nearest<S: Surface + ?Sized>(s: &S, p: &Point3<f64>, side: usize) -> Reference {
    let [du, dv] = s.domain();
    let at = |k: usize, (a, b): (f64, f64)| {
        if k + 1 == side {
            b
        } else {
            a + (b - a) * (k as f64 / (side - 1) as f64)
        }
    };
    let mut d = vec![0.0; side * side];
    for i in 0..side {
        for j in 0..side {
            d[i * side + j] = (s.eval(at(i, du), at(j, dv)) - p).norm();
        }
    }
    // Local minima of the grid (8 neighbours, the edges included).
    let mut minima: Vec<usize> = (0..side * side)
        .filter(|&k| {
            let (i, j) = ((k / side) as isize, (k % side) as isize);
            (-1..=1).all(|a| {
                (-1..=1).all(|b| {
                    let (x, y) = (i + a, j + b);
                    let inside = x >= 0 && y >= 0 && (x as usize) < side && (y as usize) < side;
                    !inside || d[x as usize * side + y as usize] >= d[k]
                })
            })
        })
        .collect();
    minima.sort_by(|&a, &b| d[a].total_cmp(&d[b]));
    minima.truncate(REFINED);
    let mut best = Reference {
        uv: (at(0, du), at(0, dv)),
        point: s.eval(at(0, du), at(0, dv)),
        distance: d[0],
    };
    for k in minima {
        let start = (at(k / side, du), at(k % side, dv));
        let r = refine(s, p, start, (du, dv));
        if r.distance < best.distance {
            best = r;
        }
    }
    best
}

/// Levenberg–Marquardt on `|S(u, v) − p|²` from `start`, clamped into the
/// domain.
pub fn refine<S: Surface + ?Sized>(
    s: &S,
    p: &Point3<f64>,
    start: (f64, f64),
    (du, dv): ((f64, f64), (f64, f64)),
) -> Reference {
    let eval = |uv: (f64, f64)| {
        let q = s.eval(uv.0, uv.1);
        (q, (q - p).norm())
    };
    let (mut uv, (mut q, mut f)) = (start, eval(start));
    let mut lambda = 1e-9;
    for _ in 0..STEPS {
        let (su, sv) = s.partials(uv.0, uv.1);
        let r = q - p;
        let jtj = Matrix2::new(su.dot(&su), su.dot(&sv), su.dot(&sv), sv.dot(&sv));
        let g = Vector2::new(su.dot(&r), sv.dot(&r));
        let damped = jtj + Matrix2::identity() * (lambda * (jtj[(0, 0)] + jtj[(1, 1)]) + 1e-300);
        let Some(step) = damped.try_inverse().map(|m| -(m * g)) else {
            break;
        };
        let next = (
            (uv.0 + step.x).clamp(du.0, du.1),
            (uv.1 + step.y).clamp(dv.0, dv.1),
        );
        let (nq, nf) = eval(next);
        if nf < f {
            (uv, q, f) = (next, nq, nf);
            lambda = (lambda * 0.1).max(1e-15);
        } else {
            lambda *= 10.0;
            if lambda > 1e12 {
                break;
            }
        }
    }
    Reference {
        uv,
        point: q,
        distance: f,
    }
}

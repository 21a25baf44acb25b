//! Random valid NURBS data and the parameters to test them at (shared by the
//! NURBS tests and the allocation tests).

use crate::Rng;
use revolve::nalgebra::Point2;
use revolve::{Curve, Nurbs};

/// A random valid NURBS: degree `p`, `n ≥ p + 1` points in `[−10, 10]²`,
/// weights log-uniform in `[w_lo, w_hi]`, and a knot vector with repeated
/// knots (any multiplicity up to `p + 1`, also inside) and gaps in
/// `[0.05, 1]`.
pub struct Random {
    pub degree: usize,
    pub knots: Vec<f64>,
    pub points: Vec<Point2<f64>>,
    pub weights: Vec<f64>,
}

/// The parts of a random valid NURBS of degree `degree` with weights in
/// `[w_lo, w_hi]` (see [`Random`]).
pub fn random_parts(rng: &mut Rng, degree: usize, w_lo: f64, w_hi: f64) -> Random {
    loop {
        let n = degree + 1 + rng.below(6);
        let count = n + degree + 1;
        let mut knots = Vec::with_capacity(count);
        let mut value = rng.range(-2.0, 2.0);
        while knots.len() < count {
            // Mostly simple knots, sometimes repeated up to full multiplicity.
            let multiplicity = match rng.below(4) {
                0 => 1 + rng.below(degree + 1),
                _ => 1,
            };
            for _ in 0..multiplicity.min(count - knots.len()) {
                knots.push(value);
            }
            value += rng.range(0.05, 1.0);
        }
        let points = (0..n)
            .map(|_| Point2::new(rng.range(-10.0, 10.0), rng.range(-10.0, 10.0)))
            .collect();
        let weights = (0..n)
            .map(|_| w_lo * (w_hi / w_lo).powf(rng.unit()))
            .collect();
        let parts = Random {
            degree,
            knots,
            points,
            weights,
        };
        // An empty domain (t_p = t_n) is possible with heavy repetition.
        if parts.knots[degree] < parts.knots[n] {
            return parts;
        }
    }
}

impl Random {
    /// The NURBS of these parts.
    pub fn nurbs(&self) -> Nurbs<2> {
        Nurbs::new(
            self.degree,
            self.knots.clone(),
            self.points.clone(),
            self.weights.clone(),
        )
        .expect("valid random NURBS")
    }
}

/// Parameters to test: the domain ends, every knot in the domain, random
/// ones, and NaN/outside values (which must act as the nearest end).
pub fn parameters(rng: &mut Rng, c: &Nurbs<2>, random: usize) -> Vec<f64> {
    let (a, b) = c.domain();
    let mut ts = vec![a, b];
    ts.extend(c.knots().iter().copied().filter(|&k| a <= k && k <= b));
    ts.extend((0..random).map(|_| rng.range(a, b)));
    ts
}

//! Random tensor-product surface data: a small xorshift64* generator with
//! control nets and weights, and clamped knot vectors (shared by the
//! tensor-surface tests and the allocation tests).

use revolve::nalgebra::Point3;

/// A small deterministic generator (xorshift64*), uniform in `[0, 1)`.
pub struct Xorshift64Star(pub u64);

// `next` is the next number in `[0, 1)`, not an iterator's `Option`.
#[allow(clippy::should_implement_trait)]
impl Xorshift64Star {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }

    pub fn point(&mut self) -> Point3<f64> {
        Point3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
    }

    pub fn grid(&mut self, rows: usize, cols: usize) -> Vec<Vec<Point3<f64>>> {
        (0..rows)
            .map(|_| (0..cols).map(|_| self.point()).collect())
            .collect()
    }

    pub fn weights(&mut self, rows: usize, cols: usize) -> Vec<Vec<f64>> {
        (0..rows)
            .map(|_| (0..cols).map(|_| self.range(0.3, 3.0)).collect())
            .collect()
    }
}

/// A clamped knot vector of degree `p` for `n` points with sorted random
/// interior knots on `[0, 1]` (one of them doubled when there is room).
pub fn clamped_knots(rng: &mut Xorshift64Star, p: usize, n: usize) -> Vec<f64> {
    let mut interior: Vec<f64> = (0..n - p - 1).map(|_| rng.range(0.1, 0.9)).collect();
    if interior.len() >= 2 {
        interior[1] = interior[0];
    }
    interior.sort_by(f64::total_cmp);
    let mut k = vec![0.0; p + 1];
    k.extend(interior);
    k.extend(vec![1.0; p + 1]);
    k
}

//! Random numbers and the sample patterns built from them.
//!
//! Every pixel owns a generator seeded from `(seed, x, y)` alone, so a render
//! is reproducible bit for bit whatever the number of threads or the order in
//! which tiles finish.
//!
//! - [`Rng`] is SplitMix64 (Steele, Lea and Flood, "Fast splittable
//!   pseudorandom number generators", 2014): a 64-bit Weyl sequence pushed
//!   through a bijective mixer. It passes BigCrush, needs one `u64` of state
//!   and costs a few multiplications per draw.
//! - [`stratum`] splits `[0, 1)²` into a grid of cells, one per sample, and
//!   [`cosine_hemisphere`] maps `[0, 1)²` to directions with density
//!   `cos θ / π` (Malley's method: uniform on the disk, lifted to the sphere).

use revolve::nalgebra::Vector3;

/// SplitMix64: the state advances by the golden-ratio increment and each
/// output is the mixed state.
#[derive(Debug, Clone)]
pub struct Rng {
    state: u64,
}

const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// The SplitMix64 output function: a bijection of `u64` with full avalanche.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

impl Rng {
    /// A generator whose stream depends only on `seed`.
    pub fn new(seed: u64) -> Rng {
        Rng { state: mix(seed) }
    }

    /// The generator of pixel `(x, y)` for the render seed `seed`: the three
    /// numbers are mixed one after another, so neighbouring pixels get
    /// unrelated streams.
    pub fn for_pixel(seed: u64, x: u32, y: u32) -> Rng {
        let h = mix(seed ^ GOLDEN);
        let h = mix(h ^ u64::from(x).wrapping_mul(GOLDEN));
        Rng::new(h ^ u64::from(y).wrapping_mul(0xd1b5_4a32_d192_ed03))
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN);
        mix(self.state)
    }

    /// A uniform number in `[0, 1)`: the top 53 bits scaled by `2⁻⁵³`, so
    /// every value is exact and 1 is never returned.
    #[inline]
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform point of `[0, 1)²`.
    #[inline]
    pub fn next_2d(&mut self) -> (f64, f64) {
        let a = self.next_f64();
        (a, self.next_f64())
    }
}

/// The grid used to stratify `n` samples: `columns = ⌈√n⌉` and
/// `rows = ⌈n / columns⌉`, so a square count gives a square grid and any
/// other count leaves the last row partly empty.
pub fn grid(n: u32) -> (u32, u32) {
    let n = n.max(1);
    let mut columns = (f64::from(n)).sqrt().ceil() as u32;
    // Guard against the square root rounding up past an exact square.
    while columns > 1 && (columns - 1) * (columns - 1) >= n {
        columns -= 1;
    }
    (columns, n.div_ceil(columns))
}

/// Sample `i` of `n` stratified over `[0, 1)²`: the cell `(i mod columns,
/// i div columns)` of [`grid`]`(n)`, jittered uniformly inside it by `jitter`
/// (a uniform point of `[0, 1)²`).
pub fn stratum(i: u32, n: u32, jitter: (f64, f64)) -> (f64, f64) {
    let (columns, rows) = grid(n);
    let (cx, cy) = (i % columns, i / columns);
    (
        (f64::from(cx) + jitter.0) / f64::from(columns),
        (f64::from(cy) + jitter.1) / f64::from(rows),
    )
}

/// A direction about the unit vector `n` with density `cos θ / π` over the
/// hemisphere `n · ω > 0`, from the uniform point `(a, b)` of `[0, 1)²`:
/// radius `√a` and angle `2πb` on the unit disk, lifted by
/// `z = √(1 − a)` (Malley's method). The result is unit length.
pub fn cosine_hemisphere(n: &Vector3<f64>, (a, b): (f64, f64)) -> Vector3<f64> {
    let (t, s) = orthonormal_basis(n);
    let r = a.sqrt();
    let phi = 2.0 * std::f64::consts::PI * b;
    let z = (1.0 - a).max(0.0).sqrt();
    (t * (r * phi.cos()) + s * (r * phi.sin()) + n * z).normalize()
}

/// Two unit vectors `(t, s)` that make `(t, s, n)` a right-handed
/// orthonormal frame for the unit vector `n`, without branches on the
/// direction except its sign (Duff et al., "Building an orthonormal basis,
/// revisited", JCGT 2017).
pub fn orthonormal_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vector3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vector3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_numbers_stay_in_the_unit_interval_and_average_a_half() {
        let mut rng = Rng::new(7);
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = rng.next_f64();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        assert!((sum / f64::from(n) - 0.5).abs() < 0.005);
    }

    #[test]
    fn pixel_streams_are_reproducible_and_distinct() {
        let a = Rng::for_pixel(1, 3, 4).next_u64();
        assert_eq!(a, Rng::for_pixel(1, 3, 4).next_u64());
        assert_ne!(a, Rng::for_pixel(1, 4, 3).next_u64());
        assert_ne!(a, Rng::for_pixel(2, 3, 4).next_u64());
    }

    #[test]
    fn grids_cover_the_sample_count() {
        for n in 1..200 {
            let (c, r) = grid(n);
            assert!(c * r >= n && c * (r - 1) < n, "n = {n}: {c}×{r}");
        }
        assert_eq!(grid(16), (4, 4));
        assert_eq!(grid(1), (1, 1));
    }

    #[test]
    fn strata_fall_in_their_own_cells() {
        let (sx, sy) = stratum(5, 9, (0.5, 0.5));
        assert!((sx - 2.5 / 3.0).abs() < 1e-15 && (sy - 1.5 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn bases_are_orthonormal_and_right_handed() {
        let mut rng = Rng::new(3);
        for _ in 0..1000 {
            let n = Vector3::new(
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
            )
            .normalize();
            let (t, s) = orthonormal_basis(&n);
            assert!((t.norm() - 1.0).abs() < 1e-12 && (s.norm() - 1.0).abs() < 1e-12);
            assert!(t.dot(&s).abs() < 1e-12 && t.dot(&n).abs() < 1e-12);
            assert!((t.cross(&s) - n).norm() < 1e-12);
        }
    }

    #[test]
    fn cosine_samples_have_mean_cosine_two_thirds() {
        // E[cos θ] under the density cos θ / π is 2/3.
        let n = Vector3::new(0.3, -0.5, 0.8).normalize();
        let mut rng = Rng::new(11);
        let count = 200_000;
        let mut sum = 0.0;
        for _ in 0..count {
            let w = cosine_hemisphere(&n, rng.next_2d());
            let c = w.dot(&n);
            assert!(c >= 0.0);
            sum += c;
        }
        assert!((sum / f64::from(count) - 2.0 / 3.0).abs() < 0.005);
    }
}

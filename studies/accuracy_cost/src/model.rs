//! What the study measures: the method interface and the figures of one row.

use revolve::Ray;

/// A way to find the nearest ray–surface hit, as the study drives it.
///
/// `nearest` takes `&mut self` so that randomized methods (the course
/// method's random starts) can keep their generator.
pub trait Method {
    /// The series this method belongs to in the plot (e.g. `"exact"`).
    fn series(&self) -> String;
    /// Its setting, for the table (e.g. `"tol 1e-6"`).
    fn knob(&self) -> String;
    /// The `t` of the nearest hit with `t_min < t < t_max`, or `None`.
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64>;
    /// [`nearest`](Self::nearest) for every ray: `answers[i]` for
    /// `rays[i]` (the common prefix of the two slices). How the study casts
    /// a ray set, both for the answers and timed; the default casts one ray
    /// at a time, a batch method overrides it.
    fn nearest_all(&mut self, rays: &[Ray], t_min: f64, t_max: f64, answers: &mut [Option<f64>]) {
        for (ray, answer) in rays.iter().zip(answers) {
            *answer = self.nearest(ray, t_min, t_max);
        }
    }
    /// For a method that casts through `Intersect::intersect_batch`: how
    /// many of `rays` get a hit that differs in any bit (`t`, point, normal,
    /// `u`, `v`, or hit against miss) from the single-ray `intersect` of the
    /// same object. `None` for every other method.
    fn batch_mismatches(&self, _rays: &[Ray], _t_min: f64, _t_max: f64) -> Option<usize> {
        None
    }
}

/// Error figures of one method on one ray set, against the reference.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorStats {
    /// Rays traced (those with a certain reference answer).
    pub rays: usize,
    /// Rays the reference hits.
    pub reference_hits: usize,
    /// Median of `|t − t_ref| / scale` over rays both hit.
    pub median: f64,
    /// Maximum of `|t − t_ref| / scale` over rays both hit.
    pub max: f64,
    /// Fraction of the reference's hits the method missed.
    pub miss_rate: f64,
    /// Fraction of the reference's misses the method hit.
    pub false_hit_rate: f64,
    /// Fraction of the reference's hits answered with a far hit
    /// (`|t − t_ref| > FAR_HIT · scale`): another root, a near miss accepted
    /// within a loose tolerance, or a grazing hit on a coarse mesh.
    pub far_hit_rate: f64,
}

/// Relative `t` error above which a hit counts as far from the exact one.
pub const FAR_HIT: f64 = 1e-3;

/// One row of the intersection table and one point of the plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The shape: `"vase"`, `"wine glass"`, `"NURBS sphere"`, `"NURBS torus"`.
    pub shape: &'static str,
    /// The plot series.
    pub series: String,
    /// The setting.
    pub knob: String,
    /// Errors against the reference.
    pub errors: ErrorStats,
    /// Rays per second on one thread, the median of repeated runs.
    pub rays_per_second: f64,
    /// Heap bytes the method's per-surface data holds.
    pub memory_bytes: usize,
    /// Seconds to build the per-surface data.
    pub build_seconds: f64,
    /// For a batch row: rays whose batch hit differs from the single
    /// path's in any bit ([`Method::batch_mismatches`]); `None` otherwise.
    pub batch_mismatches: Option<usize>,
}

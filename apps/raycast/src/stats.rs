//! What a render cost: rays by kind and the time in revolve's intersector.
//!
//! Each worker counts into its own [`Stats`] (no sharing in the hot path);
//! the renderer merges them when the image is done and adds the wall time
//! and the number of threads, from which [`Stats::revolution_share`] is
//! computed.

use std::time::Duration;

use crate::geometry::IntersectStats;

/// Rays traced, by kind.
///
/// - `primary`: camera rays, one per pixel sample;
/// - `shadow`: visibility tests towards a light sample, plus one for each
///   transparent surface a shadow ray is continued past;
/// - `reflection`: mirror rays (including the Fresnel-reflected part of a
///   dielectric);
/// - `refraction`: rays transmitted through a dielectric surface;
/// - `indirect`: diffuse bounces of the path tracer.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    pub primary: u64,
    pub shadow: u64,
    pub reflection: u64,
    pub refraction: u64,
    pub indirect: u64,
}

impl RayCounts {
    /// All rays.
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflection + self.refraction + self.indirect
    }

    fn add(&mut self, o: &RayCounts) {
        self.primary += o.primary;
        self.shadow += o.shadow;
        self.reflection += o.reflection;
        self.refraction += o.refraction;
        self.indirect += o.indirect;
    }
}

/// The counters of one worker, or of the whole render once merged.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    pub rays: RayCounts,
    /// Revolution intersection calls and the nanoseconds spent in them,
    /// summed over the threads that made them.
    pub intersect: IntersectStats,
    /// Wall-clock time of the render (set by the renderer after merging).
    pub wall: Duration,
    /// Worker threads the render ran on (set by the renderer).
    pub threads: usize,
    /// Time to build the world (bounding volume hierarchy) before tracing.
    pub build: Duration,
    /// Camera samples whose value was not finite (NaN or infinite in some
    /// channel), counted as black instead of poisoning their pixel.
    pub non_finite_samples: u64,
}

impl Stats {
    /// Adds another worker's counters (wall time, threads and build
    /// time are not summed: they describe the whole render).
    pub fn merge(&mut self, other: &Stats) {
        self.rays.add(&other.rays);
        self.intersect.revolution_calls += other.intersect.revolution_calls;
        self.intersect.revolution_nanos += other.intersect.revolution_nanos;
        self.non_finite_samples += other.non_finite_samples;
    }

    /// The share of the render's thread time spent inside revolve's exact
    /// intersector: `Σ revolution_nanos` over all threads divided by
    /// `wall time × threads` (the thread time available). 0 when nothing was
    /// timed.
    pub fn revolution_share(&self) -> f64 {
        let available = self.wall.as_nanos() as f64 * self.threads.max(1) as f64;
        if available > 0.0 {
            self.intersect.revolution_nanos as f64 / available
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_adds_counts_and_the_share_divides_by_thread_time() {
        let mut a = Stats::default();
        a.rays.primary = 3;
        a.intersect.revolution_nanos = 500;
        let mut b = Stats::default();
        b.rays.shadow = 2;
        b.rays.indirect = 1;
        b.intersect.revolution_calls = 4;
        b.intersect.revolution_nanos = 1500;
        a.merge(&b);
        assert_eq!(a.rays.total(), 6);
        assert_eq!(a.intersect.revolution_calls, 4);
        a.wall = Duration::from_nanos(1000);
        a.threads = 4;
        assert!((a.revolution_share() - 0.5).abs() < 1e-15);
    }
}

//! The nearest hits of several rays at once ([`World::intersect_batch`]).
//!
//! Every ray (lane) walks the world's BVH on its own ([`Walk`]), exactly as
//! [`World::intersect`] would, but the walks advance in step: each round,
//! every lane still walking names the next object it must test, and each
//! object named is tested once for all the lanes that named it, through
//! [`Placed::intersect_batch`] (revolve's `Intersect::intersect_batch` for
//! revolution bodies). A lane's objects are thus tested in the same order,
//! over the same ranges `(t_min, nearest so far)`, as by the single-ray
//! query: the hits, their ties and the statistics are the same, bit for bit.
//! Coherent rays (neighbouring camera rays) name the same objects in the
//! same rounds, so the batches are full.

use super::LANES;
use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use super::bvh::{BoxRay, Walk};
use super::object::Placed;
use super::shapes::LocalHit;
use super::{IntersectStats, SurfaceHit, World};

impl World {
    /// For every `rays[i]`, the nearest hit with `t_min < t`, as
    /// [`World::intersect`]`(rays[i], t_min, ∞)` gives it, into `hits[i]`
    /// (the common prefix of the two slices is processed).
    pub fn intersect_batch(
        &self,
        rays: &[Ray],
        t_min: f64,
        hits: &mut [Option<SurfaceHit>],
        stats: &mut IntersectStats,
    ) {
        for (rays, hits) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
            self.intersect_lanes(rays, t_min, hits, stats);
        }
    }

    /// [`Self::intersect_batch`] for at most [`LANES`] rays.
    fn intersect_lanes(
        &self,
        rays: &[Ray],
        t_min: f64,
        hits: &mut [Option<SurfaceHit>],
        stats: &mut IntersectStats,
    ) {
        let n = rays.len().min(hits.len());
        if n == 0 {
            return;
        }
        let mut best: [Option<(&Placed, LocalHit)>; LANES] = [None; LANES];
        let mut ranges = [(t_min, f64::INFINITY); LANES];
        let mut found: [Option<LocalHit>; LANES] = [None; LANES];
        for p in &self.unbounded {
            p.intersect_batch(&rays[..n], &ranges[..n], &mut found[..n], stats);
            for i in 0..n {
                if let Some(h) = found[i] {
                    ranges[i].1 = h.t;
                    best[i] = Some((p, h));
                }
            }
        }

        let boxes: [BoxRay; LANES] = std::array::from_fn(|i| BoxRay::new(&rays[i.min(n - 1)]));
        let mut walks: [Walk; LANES] =
            std::array::from_fn(|i| Walk::new(&self.bvh, &boxes[i], t_min, ranges[i].1));
        let mut group = [Ray::new(Point3::origin(), Vector3::zeros()); LANES];
        let mut group_ranges = [(0.0, 0.0); LANES];
        let mut lanes = [0usize; LANES];
        loop {
            let mut next: [Option<usize>; LANES] = [None; LANES];
            for i in 0..n {
                next[i] = walks[i].next(&self.bvh, &boxes[i], t_min, ranges[i].1);
            }
            if next[..n].iter().all(Option::is_none) {
                break;
            }
            // Each object named this round, tested for the lanes naming it.
            while let Some(k) = next[..n].iter().find_map(|k| *k) {
                let mut m = 0;
                for i in 0..n {
                    if next[i] == Some(k) {
                        next[i] = None;
                        (group[m], group_ranges[m], lanes[m]) = (rays[i], ranges[i], i);
                        m += 1;
                    }
                }
                let p = &self.bounded[k];
                p.intersect_batch(&group[..m], &group_ranges[..m], &mut found[..m], stats);
                for j in 0..m {
                    if let Some(h) = found[j] {
                        let i = lanes[j];
                        ranges[i].1 = h.t;
                        best[i] = Some((p, h));
                    }
                }
            }
        }
        for i in 0..n {
            hits[i] = best[i].and_then(|(p, h)| super::surface_hit(&rays[i], p, h));
        }
    }
}

//! The batch path: an exact (certified) intersector called through
//! `Intersect::intersect_batch` on [`BATCH`] consecutive rays of the ray set
//! at a time (the last batch of a set may be shorter), and the check that
//! its hits are the single path's bit for bit.
//!
//! A batch row is measured exactly as its single-ray row
//! ([`crate::study::measured_row`]): only the way the ray set is cast
//! ([`Method::nearest_all`]) differs.

use crate::memory::built;
use crate::model::Method;
use revolve::{Hit, Intersect, Ray};

/// Rays per call of `intersect_batch`.
pub const BATCH: usize = 8;

/// A single-ray method that is one object's `Intersect::intersect`.
pub trait Single: Method {
    /// The object intersected.
    type Model: Intersect;
    /// The object, for the batch path.
    fn model(&self) -> &Self::Model;
}

/// `S`'s object cast through `intersect_batch`, [`BATCH`] consecutive rays
/// a call; the series is `S`'s with `", batches of 8"`, the setting `S`'s.
pub struct Batched<S>(pub S);

impl<S: Single> Method for Batched<S> {
    fn series(&self) -> String {
        format!("{}, batches of {BATCH}", self.0.series())
    }
    fn knob(&self) -> String {
        self.0.knob()
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let mut answer = [None];
        self.nearest_all(std::slice::from_ref(ray), t_min, t_max, &mut answer);
        answer[0]
    }
    fn nearest_all(&mut self, rays: &[Ray], t_min: f64, t_max: f64, answers: &mut [Option<f64>]) {
        let rays = &rays[..rays.len().min(answers.len())];
        batch_hits(self.0.model(), rays, t_min, t_max, |i, _, hit| {
            answers[i] = hit.map(|h| h.t);
        });
    }
    fn batch_mismatches(&self, rays: &[Ray], t_min: f64, t_max: f64) -> Option<usize> {
        let model = self.0.model();
        let mut differ = 0;
        batch_hits(model, rays, t_min, t_max, |_, ray, hit| {
            if !same_bits(hit, model.intersect(ray, t_min, t_max)) {
                differ += 1;
            }
        });
        Some(differ)
    }
}

/// Casts `rays` through `model.intersect_batch`, [`BATCH`] consecutive rays
/// a call, each in `(t_min, t_max)`; `each(i, &rays[i], hit)` in order.
fn batch_hits<M: Intersect>(
    model: &M,
    rays: &[Ray],
    t_min: f64,
    t_max: f64,
    mut each: impl FnMut(usize, &Ray, Option<Hit>),
) {
    let ranges = [(t_min, t_max); BATCH];
    let mut hits = [None; BATCH];
    for (k, batch) in rays.chunks(BATCH).enumerate() {
        model.intersect_batch(batch, &ranges, &mut hits);
        for (j, (ray, hit)) in batch.iter().zip(&hits).enumerate() {
            each(k * BATCH + j, ray, *hit);
        }
    }
}

/// Whether two answers are the same in every bit: both misses, or hits
/// whose `t`, point, normal, `u` and `v` have equal bit patterns (so `0.0`
/// and `-0.0` differ).
pub fn same_bits(a: Option<Hit>, b: Option<Hit>) -> bool {
    let bits = |h: Hit| {
        [
            h.t, h.point.x, h.point.y, h.point.z, h.normal.x, h.normal.y, h.normal.z, h.uv.0,
            h.uv.1,
        ]
        .map(f64::to_bits)
    };
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => bits(a) == bits(b),
        _ => false,
    }
}

/// Builds `make()` and records its row, then builds and records the same
/// method through the batch path ([`Batched`]); each is built, timed and
/// counted on its own.
pub fn record_single_and_batched<S: Single>(
    make: impl Fn() -> S,
    record: &mut dyn FnMut(&mut dyn Method, f64, usize),
) {
    let (mut single, seconds, bytes) = built(&make);
    record(&mut single, seconds, bytes);
    let (mut batched, seconds, bytes) = built(|| Batched(make()));
    record(&mut batched, seconds, bytes);
}

#[cfg(test)]
mod tests {
    use super::*;
    use revolve::Aabb;
    use revolve::nalgebra::{Point3, Unit, Vector3};
    use std::cell::RefCell;

    /// The unit square of the plane `z = 0`, hit from either side; its
    /// `intersect_batch` records each batch's length and, if `corrupt`,
    /// writes `-0.0` for the normal's `x` (equal to `0.0` as a number, not
    /// in its bits) in lane 5 of each batch.
    struct Square {
        corrupt: bool,
        batches: RefCell<Vec<usize>>,
    }

    impl Intersect for Square {
        fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
            let t = -ray.origin.z / ray.dir.z;
            let point = ray.at(t);
            let inside = point.x.abs() <= 1.0 && point.y.abs() <= 1.0;
            (t > t_min && t < t_max && inside).then(|| Hit {
                t,
                point,
                normal: Vector3::z_axis(),
                uv: (point.x, point.y),
            })
        }
        fn bounds(&self) -> Aabb {
            Aabb::new(Point3::new(-1.0, -1.0, 0.0), Point3::new(1.0, 1.0, 0.0))
        }
        fn intersect_batch(&self, rays: &[Ray], ranges: &[(f64, f64)], hits: &mut [Option<Hit>]) {
            self.batches.borrow_mut().push(rays.len());
            for (lane, ((ray, &(lo, hi)), hit)) in rays.iter().zip(ranges).zip(hits).enumerate() {
                *hit = self.intersect(ray, lo, hi);
                if let (true, 5, Some(h)) = (self.corrupt, lane, hit.as_mut()) {
                    h.normal = Unit::new_unchecked(Vector3::new(-0.0, 0.0, 1.0));
                }
            }
        }
    }

    struct OnSquare(Square);

    impl Method for OnSquare {
        fn series(&self) -> String {
            "square".into()
        }
        fn knob(&self) -> String {
            "none".into()
        }
        fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
            self.0.intersect(ray, t_min, t_max).map(|h| h.t)
        }
    }

    impl Single for OnSquare {
        type Model = Square;
        fn model(&self) -> &Square {
            &self.0
        }
    }

    fn batched(corrupt: bool) -> Batched<OnSquare> {
        Batched(OnSquare(Square {
            corrupt,
            batches: RefCell::new(Vec::new()),
        }))
    }

    /// 20 rays straight down at `x = −1.5 + 0.15·i`: those with `|x| ≤ 1`
    /// hit at `t = 2`.
    fn rays() -> Vec<Ray> {
        (0..20)
            .map(|i| {
                let x = -1.5 + 0.15 * i as f64;
                Ray::new(Point3::new(x, 0.25, 2.0), -Vector3::z())
            })
            .collect()
    }

    #[test]
    fn batches_are_eight_consecutive_rays_and_give_the_single_answers() {
        let rays = rays();
        let mut m = batched(false);
        assert_eq!(m.series(), "square, batches of 8");
        assert_eq!(m.knob(), "none");
        let mut answers = vec![Some(-1.0); rays.len()];
        m.nearest_all(&rays, 0.0, 10.0, &mut answers);
        assert_eq!(*m.0.0.batches.borrow(), vec![8, 8, 4]);
        for (i, answer) in answers.iter().enumerate() {
            let x = -1.5 + 0.15 * i as f64;
            let want = (x.abs() <= 1.0).then_some(2.0);
            assert_eq!(*answer, want, "ray {i} at x = {x}");
        }
        assert_eq!(m.nearest(&rays[10], 0.0, 10.0), Some(2.0));
        assert_eq!(m.nearest(&rays[10], 0.0, 1.5), None);
        assert_eq!(m.batch_mismatches(&rays, 0.0, 10.0), Some(0));
        // Fewer answer slots than rays: the common prefix, in one batch.
        m.0.0.batches.borrow_mut().clear();
        let mut three = [None; 3];
        m.nearest_all(&rays[8..], 0.0, 10.0, &mut three);
        assert_eq!(three, [Some(2.0); 3]);
        assert_eq!(*m.0.0.batches.borrow(), vec![3]);
    }

    /// A difference in one bit of a normal is counted, on every batch whose
    /// lane 5 hits (rays 5 and 13 of the 20).
    #[test]
    fn a_single_bit_of_difference_is_counted() {
        let rays = rays();
        let m = batched(true);
        assert!(m.0.0.intersect(&rays[5], 0.0, 10.0).is_some());
        assert!(m.0.0.intersect(&rays[13], 0.0, 10.0).is_some());
        assert_eq!(m.batch_mismatches(&rays, 0.0, 10.0), Some(2));
        // Lane 5 of the second batch only: ray 13.
        assert_eq!(m.batch_mismatches(&rays[8..], 0.0, 10.0), Some(1));
    }

    #[test]
    fn same_bits_compares_every_field_bitwise() {
        let surface = revolve::Revolution::new(crate::common::vase());
        let ray = Ray::new(Point3::new(-5.0, 0.5, 0.1), Vector3::x());
        let h = surface.intersect(&ray, 0.0, 100.0).expect("the vase");
        assert!(same_bits(Some(h), Some(h)));
        assert!(same_bits(None, None));
        assert!(!same_bits(Some(h), None) && !same_bits(None, Some(h)));
        let next = |x: f64| f64::from_bits(x.to_bits() + 1);
        let mut changed = [h; 5];
        changed[0].t = next(h.t);
        changed[1].point.z = next(h.point.z);
        changed[2].normal = Unit::new_unchecked(-h.normal.into_inner());
        changed[3].uv.0 = next(h.uv.0);
        changed[4].uv.1 = next(h.uv.1);
        for c in changed {
            assert!(!same_bits(Some(h), Some(c)), "{c:?}");
        }
        let zero = Hit { t: 0.0, ..h };
        let negative_zero = Hit { t: -0.0, ..h };
        assert_eq!(zero, negative_zero);
        assert!(!same_bits(Some(zero), Some(negative_zero)));
    }
}

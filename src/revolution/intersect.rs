//! Ray intersection for a surface of revolution: the ray taken into the
//! profile's local frame, the span table's hit (or, for a profile without
//! spans, the approximation's hit refined on the profile), and the hit
//! taken back to the world with its normal.

use super::profile_refine::refine_on_profile;
use super::query::LocalHit;
use super::span_search::ExactReport;
use super::span_table::SpanTable;
use super::surface::profile_normal;
use crate::ray::acceptance::Acceptance;
use crate::surface::oriented;
use crate::{Aabb, Curve, Hit, Intersect, Ray, Revolution};
use nalgebra::{Point3, Unit, Vector3};

/// How many hits of a profile's approximation are tried, nearest first,
/// before a ray is called a miss (each that does not refine onto the
/// profile, as near a silhouette, moves the search past it).
const REFINE_TRIES: usize = 8;

impl<C: Curve<2>> Revolution<C> {
    /// As [`Intersect::intersect`], with a report of how the exact
    /// intersector finished (spans entered and solved, roots, candidates,
    /// Newton iterations, the hit's residual). The fast path
    /// (`Intersect::intersect`) computes the same hit.
    pub fn intersect_with_report(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
    ) -> (Option<Hit>, ExactReport) {
        let mut report = ExactReport::default();
        let hit = self.intersect_reporting(ray, t_min, t_max, &mut report);
        if hit.is_none() {
            report.residual = None;
        }
        (hit, report)
    }

    fn intersect_reporting(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        report: &mut ExactReport,
    ) -> Option<Hit> {
        let exact = self.exact.as_ref()?;
        let (o, d) = self.to_local(ray);
        let local = match self.approximation {
            None => exact.intersect::<false>(o, d, t_min, t_max, &self.tolerance, report)?,
            Some(_) => self.refined_hit(exact, o, d, t_min, t_max, report)?,
        };
        report.residual = Some(local.residual);
        let at_end = local.u >= self.profile.domain().1;
        let finite = |n: &Unit<Vector3<f64>>| n.iter().all(|c| c.is_finite());
        let normal_local = match local.tangent {
            Some(t) => profile_normal(local.x, t, at_end, local.sin_cos)
                .map(|n| oriented(n, self.reversed)),
            None => self.normal_local(local.u, local.theta),
        }
        .filter(finite)
        // No tangent plane (a cone's apex): face the ray.
        .or_else(|| Unit::try_new(-d / d.amax(), 0.0))?;
        let origin = &self.to_world.translation.vector;
        let point = Point3::from(self.rotation * local.point.coords + origin);
        if !point.coords.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Hit {
            t: local.t,
            point,
            normal: Unit::new_unchecked(self.rotation * normal_local.into_inner()),
            uv: (local.u, local.theta),
        })
    }

    /// The ray's origin and direction in the profile's local frame.
    fn to_local(&self, ray: &Ray) -> (Point3<f64>, Vector3<f64>) {
        let origin = &self.to_world.translation.vector;
        let o = Point3::from(
            self.rotation
                .inverse_transform_vector(&(ray.origin.coords - origin)),
        );
        (o, self.rotation.inverse_transform_vector(&ray.dir))
    }

    /// The nearest hit for a profile without Bézier spans: the hits of its
    /// approximation, nearest first, refined by Newton's method on the
    /// profile itself; one that does not refine (a ray grazing the
    /// approximation where the profile is missed) moves the search past it.
    fn refined_hit(
        &self,
        table: &SpanTable,
        o: Point3<f64>,
        d: Vector3<f64>,
        t_min: f64,
        t_max: f64,
        report: &mut ExactReport,
    ) -> Option<LocalHit> {
        let (r_max, y_range) = table.local_bounds();
        let scale = r_max.max(y_range.0.abs()).max(y_range.1.abs());
        // As in the exact intersector, a hit within the position
        // uncertainty of the origin is the origin itself (a secondary ray
        // leaving the surface): the floor is `accept/|d|` past `t_min`.
        let m = d.amax();
        let dn = m * (d / m).norm();
        let t_floor = Acceptance::certified(&self.tolerance, scale, &o.coords).t_floor(t_min, dn);
        let mut from = t_min;
        for _ in 0..REFINE_TRIES {
            let guess = table.intersect::<false>(o, d, from, t_max, &self.tolerance, report)?;
            let refined = refine_on_profile(
                &self.profile,
                self.profile.domain(),
                &o.coords,
                &d,
                (guess.u, guess.t),
                scale,
                &self.tolerance,
                &mut report.iterations,
            );
            if let Some(hit) = refined.filter(|h| h.t > t_floor && h.t < t_max) {
                return Some(hit);
            }
            from = guess.t;
        }
        None
    }
}

impl<C: Curve<2>> Intersect for Revolution<C> {
    /// The nearest hit with `t_min < t < t_max`, or `None`: the exact
    /// intersector for profiles with Bézier spans, the refined
    /// approximation for others (see [`Revolution`]'s docs for what each
    /// guarantees; [`Revolution::has_exact_intersector`] tells which
    /// applies). `t_min` or `t_max` NaN, or `t_min ≥ t_max`, is a miss; so
    /// is a zero, NaN or infinite direction.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.intersect_reporting(ray, t_min, t_max, &mut ExactReport::default())
    }

    /// For profiles with Bézier spans, the span search stops at the first
    /// span with a hit instead of going on for a nearer one.
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        match (&self.exact, self.approximation) {
            (Some(exact), None) => {
                let (o, d) = self.to_local(ray);
                let mut report = ExactReport::default();
                exact
                    .intersect::<true>(o, d, t_min, t_max, &self.tolerance, &mut report)
                    .is_some()
            }
            _ => self.intersect(ray, t_min, t_max).is_some(),
        }
    }

    fn bounds(&self) -> Aabb {
        match &self.exact {
            // The cylinder around the profile's radius and height ranges
            // (of its approximation, widened by twice its deviation).
            Some(e) => {
                let (r, (y0, y1)) = e.local_bounds();
                let pad = 2.0 * self.approximation.unwrap_or(0.0);
                Aabb::new(
                    Point3::new(-r - pad, y0 - pad, -r - pad),
                    Point3::new(r + pad, y1 + pad, r + pad),
                )
                .transformed(&self.to_world)
            }
            None => Aabb::EMPTY,
        }
    }
}

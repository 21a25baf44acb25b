//! A `RevSurface`: revolve's exact intersector, with the body's normal
//! oriented outward once at build time, and every call timed.
//!
//! # Orientation
//! revolve's normal is `∂S/∂u × ∂S/∂θ`; whether that points out of the body
//! depends on the direction the profile is written in. It is decided
//! numerically, once:
//!
//! 1. The profile is sampled at 513 uniform parameters; at the sample of
//!    largest `|x|` (the widest point of the body) the outside of a closed
//!    body lies away from the axis. The surface normal there (revolve's
//!    `Surface::normal(u, 0)`) is compared with the direction from the axis
//!    to the point; if it points toward the axis, every hit normal of the body
//!    is flipped.
//! 2. If the normal there is (nearly) parallel to the axis — the widest point
//!    is a flat rim, say — the sign of the profile's area in the `(|x|, y)`
//!    half-plane decides instead (shoelace over the samples, closed along the
//!    axis): revolve's normal is the tangent turned a quarter counter-clockwise
//!    in that half-plane, so for a counter-clockwise (positive) profile it
//!    points into the enclosed region and is flipped.
//!
//! 3. If the area vanishes too (a flat disk), the normal is made to point
//!    along `+y`, the axis direction: a lid faces up.
//!
//! For an open profile "outward" means "away from the axis at the widest
//! point", which is what a vase or a cup needs.
//!
//! UV: `((u − u₀)/(u₁ − u₀), θ/2π)` with `[u₀, u₁]` the profile's domain and
//! `(u, θ)` revolve's `Hit::uv`.

use std::f64::consts::TAU;
use std::sync::Arc;
use std::time::Instant;

use revolve::nalgebra::{Point3, Vector3};
use revolve::{Aabb, Curve, Hit, Intersect, Ray, Revolution, Surface};

use super::IntersectStats;
use super::LANES;
use super::shapes::LocalHit;
use crate::scene::RevolutionBody;

/// Profile samples for the orientation test (plus one).
const SAMPLES: usize = 512;

/// A revolution body ready for ray queries.
#[derive(Debug, Clone)]
pub struct RevolutionShape {
    body: Arc<RevolutionBody>,
    /// Negate revolve's normals (see the module docs).
    flip: bool,
    domain: (f64, f64),
    bounds: Aabb,
}

impl RevolutionShape {
    /// `None` when the body has no exact intersector (empty bounds: revolve
    /// would never report a hit).
    pub fn new(body: Arc<RevolutionBody>) -> Option<RevolutionShape> {
        let (flip, domain, bounds) = match &*body {
            RevolutionBody::Bezier(r) => (needs_flip(r), r.profile().domain(), r.bounds()),
            RevolutionBody::BSpline(r) => (needs_flip(r), r.profile().domain(), r.bounds()),
            RevolutionBody::Nurbs(r) => (needs_flip(r), r.profile().domain(), r.bounds()),
        };
        if bounds.is_empty() || domain.1 <= domain.0 {
            return None;
        }
        Some(RevolutionShape {
            body,
            flip,
            domain,
            bounds,
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Whether hit normals are negated (for tests).
    #[cfg(test)]
    pub fn flipped(&self) -> bool {
        self.flip
    }

    /// `query` (a call on revolve's surface), counted and timed into
    /// `stats` as one call.
    #[inline]
    fn timed<R>(stats: &mut IntersectStats, query: impl FnOnce() -> R) -> R {
        let start = Instant::now();
        let answer = query();
        stats.revolution_calls += 1;
        stats.revolution_nanos += start.elapsed().as_nanos() as u64;
        answer
    }

    /// revolve's exact intersector, timed into `stats`.
    #[inline]
    fn hit(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut IntersectStats) -> Option<Hit> {
        Self::timed(stats, || match &*self.body {
            RevolutionBody::Bezier(r) => r.intersect(ray, t_min, t_max),
            RevolutionBody::BSpline(r) => r.intersect(ray, t_min, t_max),
            RevolutionBody::Nurbs(r) => r.intersect(ray, t_min, t_max),
        })
    }

    pub fn intersect(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut IntersectStats,
    ) -> Option<LocalHit> {
        self.hit(ray, t_min, t_max, stats).map(|h| self.local(&h))
    }

    /// revolve's [`Intersect::occluded`] (the search stops at the first
    /// span with a hit), timed into `stats` as a call.
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut IntersectStats) -> bool {
        Self::timed(stats, || match &*self.body {
            RevolutionBody::Bezier(r) => r.occluded(ray, t_min, t_max),
            RevolutionBody::BSpline(r) => r.occluded(ray, t_min, t_max),
            RevolutionBody::Nurbs(r) => r.occluded(ray, t_min, t_max),
        })
    }

    /// revolve's [`Intersect::intersect_batch`] over the lanes (at most
    /// [`LANES`]): `out[i]` is what [`Self::intersect`] gives for `rays[i]`
    /// in `ranges[i]`; counts one call per lane and times the batch.
    pub fn intersect_batch(
        &self,
        rays: &[Ray],
        ranges: &[(f64, f64)],
        out: &mut [Option<LocalHit>],
        stats: &mut IntersectStats,
    ) {
        let n = rays.len().min(ranges.len()).min(out.len()).min(LANES);
        let mut hits = [None; LANES];
        let start = Instant::now();
        let (rays, ranges, hits) = (&rays[..n], &ranges[..n], &mut hits[..n]);
        match &*self.body {
            RevolutionBody::Bezier(r) => r.intersect_batch(rays, ranges, hits),
            RevolutionBody::BSpline(r) => r.intersect_batch(rays, ranges, hits),
            RevolutionBody::Nurbs(r) => r.intersect_batch(rays, ranges, hits),
        }
        stats.revolution_calls += n as u64;
        stats.revolution_nanos += start.elapsed().as_nanos() as u64;
        for (o, h) in out.iter_mut().zip(hits.iter()) {
            *o = h.as_ref().map(|h| self.local(h));
        }
    }

    /// revolve's hit with the normal oriented and the UV scaled to `[0, 1]²`.
    fn local(&self, h: &Hit) -> LocalHit {
        let n = h.normal.into_inner();
        let (u0, u1) = self.domain;
        LocalHit {
            t: h.t,
            point: h.point,
            normal: if self.flip { -n } else { n },
            uv: (
                ((h.uv.0 - u0) / (u1 - u0)).clamp(0.0, 1.0),
                (h.uv.1.rem_euclid(TAU) / TAU).clamp(0.0, 1.0),
            ),
        }
    }
}

/// Whether revolve's normal points into the body (see the module docs).
fn needs_flip<C: Curve<2>>(rev: &Revolution<C>) -> bool {
    let profile = rev.profile();
    let (u0, u1) = profile.domain();
    let at = |i: usize| {
        let s = i as f64 / SAMPLES as f64;
        if i == SAMPLES {
            u1
        } else {
            u0 * (1.0 - s) + u1 * s
        }
    };
    // Widest sample, and twice the signed area of (|x|, y) closed along the
    // axis: ... → (|x_n|, y_n) → (0, y_n) → (0, y_0) → (|x_0|, y_0).
    let (mut widest, mut u_widest) = (-1.0, u0);
    let mut area2 = 0.0;
    let first = profile.eval(u0);
    let mut prev = (first.x.abs(), first.y);
    for i in 0..=SAMPLES {
        let u = at(i);
        let p = profile.eval(u);
        let q = (p.x.abs(), p.y);
        if q.0 > widest {
            (widest, u_widest) = (q.0, u);
        }
        area2 += prev.0 * q.1 - q.0 * prev.1;
        prev = q;
    }
    let closing = [(0.0, prev.1), (0.0, first.y), (first.x.abs(), first.y)];
    for q in closing {
        area2 += prev.0 * q.1 - q.0 * prev.1;
        prev = q;
    }

    let frame = rev.to_world();
    let axis = frame.rotation * Vector3::y();
    let origin = Point3::from(frame.translation.vector);
    let Some(n) = rev.normal(u_widest, 0.0) else {
        return area2 > 0.0;
    };
    let w = rev.eval(u_widest, 0.0) - origin;
    let radial = w - axis * w.dot(&axis);
    let len = radial.norm();
    if len > 0.0 {
        let c = n.dot(&radial) / len;
        if c.abs() > 1e-6 {
            return c < 0.0;
        }
    }
    if area2.abs() > 1e-12 * widest * widest {
        area2 > 0.0
    } else {
        n.dot(&axis) < 0.0
    }
}

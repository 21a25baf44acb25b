//! The course method: Newton's method on `(t, u, v)` from random starts.
//!
//! Reproduced as a baseline for the study; the library does not use it (its
//! exact intersector and [`revolve::NewtonIntersector`] are what it offers).

use crate::common::Rng;
use crate::model::Method;
use revolve::nalgebra::{Isometry3, Matrix3, Vector3};
use revolve::{Aabb, BezierSurface, Curve, Intersect, PatchBounds, Ray, Revolution, Surface};
use std::f64::consts::TAU;

/// The margin `ε` of the acceptance test: a hit needs `t > ε` and both
/// normalized parameters in `(ε, 1 − ε)`. The report does not give its
/// value; `10⁻⁶` is assumed.
pub const EPS: f64 = 1e-6;

/// How far an iterate may stray before the attempt is abandoned: `t < −0.3`,
/// or `u` or `v` outside `[−0.3, 1.3]` (the report's pruning, in its units).
pub const STRAY: f64 = 0.3;

/// The default acceptance threshold on the residual, relative to the
/// object's scale (the largest absolute coordinate of its bounding box). The
/// report does not give its `NEWTON_DELTA`; `10⁻⁶` is assumed.
pub const RELATIVE_DELTA: f64 = 1e-6;

/// What the course method needs besides the [`Surface`]: a bounding box,
/// and for a surface turned about an axis that axis (to start the angle at
/// the box entry point's).
pub trait Seeded: Surface {
    /// For a surface of revolution, the rigid motion from the local frame
    /// (axis = local `y`, angle `θ = atan2(−z, x)`) to the world; `None`
    /// for a surface without an axis (a patch: `v₀` is uniform).
    fn axis_frame(&self) -> Option<Isometry3<f64>>;
    /// A box containing the surface.
    fn bounding_box(&self) -> Aabb;
}

impl<C: Curve<2>> Seeded for Revolution<C> {
    fn axis_frame(&self) -> Option<Isometry3<f64>> {
        Some(*self.to_world())
    }

    fn bounding_box(&self) -> Aabb {
        let b = Intersect::bounds(self);
        if b.is_empty() {
            // No exact intersector (profile without Bézier spans): the
            // conservative box of the whole parameter rectangle.
            let [u, v] = self.domain();
            self.bound_patch(u, v)
        } else {
            b
        }
    }
}

/// A Bézier patch: no axis; its box is that of its control net (the convex
/// hull's box, as the course accelerates the search).
impl Seeded for BezierSurface {
    fn axis_frame(&self) -> Option<Isometry3<f64>> {
        None
    }

    fn bounding_box(&self) -> Aabb {
        Intersect::bounds(self)
    }
}

impl<T: Seeded + ?Sized> Seeded for &T {
    fn axis_frame(&self) -> Option<Isometry3<f64>> {
        (**self).axis_frame()
    }

    fn bounding_box(&self) -> Aabb {
        (**self).bounding_box()
    }
}

/// The ray–surface intersection taught in the course, as a student report
/// describes it (§3.5.2): Newton's method directly on `X = (t, u, v)`.
///
/// # The method
/// With `u ∈ [0, 1]` the profile parameter and `v = θ/2π ∈ [0, 1]` the angle
/// as a fraction of a turn (mapped linearly onto the surface's
/// [domain](Surface::domain); the partials are the analytic ones times the
/// interval widths), it solves
///
/// `F(t, u, v) = P(u, v) − (o + t·d) = 0`
///
/// by steps `J·ΔX = −F`, `J = [−d | ∂P/∂u | ∂P/∂v]` (an LU solve; the report
/// used Gaussian elimination). Only a ray that hits the surface's bounding
/// box is tried. Then `s` attempts ([`new`](Self::new)'s `attempts`, the
/// report's `NEWTON_ATTEMPT`) each start from
///
/// - `t₀`: where the ray enters the box ([`Aabb::clip`] within
///   `(t_min, t_max)`),
/// - `u₀`: uniform in `[0, 1]`,
/// - `v₀`: the angle of the box entry point about the axis (in turns) plus a
///   uniform offset in `[−0.1, 0.1]`, wrapped into `(0, 1]`; on a surface
///   without an axis (a Bézier patch, [`Seeded::axis_frame`] `None`),
///   uniform in `[0, 1]` like `u₀`,
///
/// and take at most `i` steps (`iterations`, the report's `NEWTON_ITER`).
/// After each step `X ← X + ΔX` the attempt is abandoned if `t < −0.3` or
/// `u` or `v` leaves `[−0.3, 1.3]` ([`STRAY`]), and it succeeds when
/// `t_min < t < t_max`, `t > ε`, `u, v ∈ (ε, 1 − ε)` ([`EPS`]) and the
/// max-norm of `F` *at the iterate before the step* (as the report measures
/// it) is below `delta` ([`with_delta`](Self::with_delta); default
/// [`RELATIVE_DELTA`] × the object's scale). The answer is the smallest
/// accepted `t` over all attempts. A singular `J` or a non-finite step ends
/// the attempt. The report ran `s = 15`, `i = 10`.
///
/// Random numbers come from a SplitMix64 [`Rng`] seeded in the constructor:
/// the answers depend on the sequence of rays traced.
///
/// # Known properties (kept, since it is reproduced as is)
/// - Hits near the seam `θ = 0` (`v` within `ε` of 0 or 1) and near the
///   profile's ends are never accepted; an attempt converging to `v`
///   slightly below 0 is not wrapped.
/// - Starting `t` at the box entry and `u` at random, an attempt may converge
///   to a farther hit; the nearest is found only if some attempt leads to it.
/// - Outside `[0, 1]` the crate's curves evaluate at the nearest end (the
///   course's polynomial evaluators extrapolate), so iterates that stray
///   there behave differently from the report's code.
pub struct CourseNewton<S> {
    surface: S,
    attempts: u32,
    iterations: u32,
    delta: f64,
    rng: Rng,
    bounds: Aabb,
    to_local: Option<Isometry3<f64>>,
    domain: [(f64, f64); 2],
    steps: u64,
}

impl<S: Seeded> CourseNewton<S> {
    /// The method on `surface` with `attempts` random starts of at most
    /// `iterations` steps each, random numbers seeded by `seed`, and the
    /// default `delta` ([`RELATIVE_DELTA`] × the object's scale).
    pub fn new(surface: S, attempts: u32, iterations: u32, seed: u64) -> Self {
        let bounds = surface.bounding_box();
        let scale = if bounds.is_empty() {
            1.0
        } else {
            bounds.scale()
        };
        CourseNewton {
            to_local: surface.axis_frame().map(|f| f.inverse()),
            domain: surface.domain(),
            surface,
            attempts,
            iterations,
            delta: RELATIVE_DELTA * scale,
            rng: Rng(seed),
            bounds,
            steps: 0,
        }
    }

    /// The same method accepting a hit when the max-norm of the residual is
    /// below `delta` (absolute, in the surface's length units).
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn with_delta(mut self, delta: f64) -> Self {
        self.delta = delta;
        self
    }

    /// The acceptance threshold on the residual.
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn delta(&self) -> f64 {
        self.delta
    }

    /// Newton steps taken so far, over all rays.
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// One attempt from `(t0, u0, v0)`: the accepted `t`, or `None`.
    fn attempt(&mut self, ray: &Ray, start: Vector3<f64>, t_min: f64, t_max: f64) -> Option<f64> {
        let [(u_lo, u_hi), (v_lo, v_hi)] = self.domain;
        let (u_width, v_width) = (u_hi - u_lo, v_hi - v_lo);
        let mut x = start;
        for _ in 0..self.iterations {
            self.steps += 1;
            let (u, v) = (u_lo + u_width * x.y, v_lo + v_width * x.z);
            let p = self.surface.eval(u, v);
            let (su, sv) = self.surface.partials(u, v);
            // −F = o + t·d − P; J = ∂F/∂(t, u, v) = [−d | ∂P/∂u | ∂P/∂v].
            let minus_f = ray.at(x.x) - p;
            let j = Matrix3::from_columns(&[-ray.dir, su * u_width, sv * v_width]);
            let step = j.lu().solve(&minus_f)?;
            if !step.iter().all(|s| s.is_finite()) {
                return None;
            }
            let residual = minus_f.amax();
            x += step;
            let (t, u, v) = (x.x, x.y, x.z);
            let near = -STRAY..=1.0 + STRAY;
            if !(t >= -STRAY && near.contains(&u) && near.contains(&v)) {
                return None;
            }
            let inside = |s: f64| s > EPS && s < 1.0 - EPS;
            if t > EPS && t > t_min && t < t_max && inside(u) && inside(v) && residual < self.delta
            {
                return Some(t);
            }
        }
        None
    }
}

/// `s` wrapped into `(0, 1]`.
fn wrap_turn(s: f64) -> f64 {
    let w = s.rem_euclid(1.0);
    if w > 0.0 { w } else { 1.0 }
}

impl<S: Seeded> Method for CourseNewton<S> {
    fn series(&self) -> String {
        "course Newton".to_string()
    }

    fn knob(&self) -> String {
        format!("s={}, i={}", self.attempts, self.iterations)
    }

    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let (t0, _) = self.bounds.clip(ray, t_min, t_max)?;
        let turn = self.to_local.map(|frame| {
            let entry = frame * ray.at(t0);
            (-entry.z).atan2(entry.x) / TAU
        });
        let mut best: Option<f64> = None;
        for _ in 0..self.attempts {
            let u0 = self.rng.unit();
            let v0 = match turn {
                Some(turn) => wrap_turn(turn + self.rng.range(-0.1, 0.1)),
                None => self.rng.unit(),
            };
            let found = self.attempt(ray, Vector3::new(t0, u0, v0), t_min, t_max);
            if let Some(t) = found.filter(|&t| best.is_none_or(|b| t < b)) {
                best = Some(t);
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use revolve::Bezier;
    use revolve::nalgebra::{Point2, Point3, Vector3};

    /// The tube `x² + z² = 1`, `−1 ≤ y ≤ 1`.
    fn cylinder() -> Revolution<Bezier<2>> {
        Revolution::new(Bezier::new(vec![Point2::new(1.0, -1.0), Point2::new(1.0, 1.0)]).unwrap())
    }

    /// The nearest `t > t_min` where the ray meets the tube, in closed form.
    fn cylinder_t(ray: &Ray, t_min: f64) -> Option<f64> {
        let (o, d) = (ray.origin, ray.dir);
        let a = d.x * d.x + d.z * d.z;
        let b = 2.0 * (o.x * d.x + o.z * d.z);
        let c = o.x * o.x + o.z * o.z - 1.0;
        let disc = b * b - 4.0 * a * c;
        if a == 0.0 || disc < 0.0 {
            return None;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        let mut roots = [q / a, c / q];
        roots.sort_by(f64::total_cmp);
        roots
            .into_iter()
            .find(|&t| t > t_min && (ray.at(t).y).abs() <= 1.0)
    }

    /// A ray from outside, through the axis at height `y`, in the direction
    /// of angle `theta`, tilted by `slope` (vertical over horizontal).
    fn through_axis(theta: f64, y: f64, slope: f64) -> Ray {
        let out = Vector3::new(theta.cos(), 0.0, -theta.sin());
        let dir = (-out + Vector3::new(0.0, slope, 0.0)).normalize();
        let target = Point3::new(0.0, y, 0.0);
        Ray::new(target - dir * 3.0, dir)
    }

    fn random_rays(n: usize, seed: u64) -> Vec<Ray> {
        let mut rng = Rng(seed);
        (0..n)
            .map(|_| {
                // Away from the seam θ = 0, which the method cannot accept.
                let theta = rng.range(0.2, TAU - 0.2);
                through_axis(theta, rng.range(-0.6, 0.6), rng.range(-0.3, 0.3))
            })
            .collect()
    }

    #[test]
    fn converges_to_the_closed_form_on_a_cylinder() {
        let mut m = CourseNewton::new(cylinder(), 15, 10, 7);
        assert_eq!(m.series(), "course Newton");
        assert_eq!(m.knob(), "s=15, i=10");
        assert_eq!(m.delta(), 1e-6);
        let mut worst: f64 = 0.0;
        for ray in random_rays(50, 1) {
            let want = cylinder_t(&ray, 0.0).unwrap();
            let got = m.nearest(&ray, 0.0, f64::INFINITY);
            let got = got.unwrap_or_else(|| panic!("missed {ray:?}"));
            worst = worst.max((got - want).abs());
        }
        assert!(worst < 1e-6, "worst |t − t_exact| = {worst:e}");
        // A plain ray through the axis: enters at t = 2.
        let ray = through_axis(1.0, 0.25, 0.0);
        let t = m.nearest(&ray, 0.0, f64::INFINITY).unwrap();
        assert!((t - 2.0).abs() < 1e-6, "t = {t}");
        // The window is respected: past the entry the exit (t = 4) is next
        // (from t_min = 3.2 the box entry is on the exit's side of the axis,
        // where the starting angle leads Newton to it).
        let t = m.nearest(&ray, 3.2, f64::INFINITY).unwrap();
        assert!((t - 4.0).abs() < 1e-6, "t = {t}");
        assert_eq!(m.nearest(&ray, 0.0, 1.9), None);
    }

    #[test]
    fn a_ray_missing_the_box_does_not_iterate() {
        let mut m = CourseNewton::new(cylinder(), 15, 10, 7);
        // Passes above the box (y = 1.5 > 1).
        let ray = Ray::new(Point3::new(-3.0, 1.5, 0.0), Vector3::x());
        assert_eq!(m.nearest(&ray, 0.0, f64::INFINITY), None);
        assert_eq!(m.steps(), 0);
        // The same generator state as a fresh one: no random numbers drawn.
        let mut fresh = CourseNewton::new(cylinder(), 15, 10, 7);
        let hit = through_axis(1.0, 0.0, 0.0);
        assert_eq!(
            m.nearest(&hit, 0.0, f64::INFINITY),
            fresh.nearest(&hit, 0.0, f64::INFINITY)
        );
        assert!(m.steps() > 0);
    }

    #[test]
    fn the_same_seed_gives_the_same_answers() {
        let rays = random_rays(40, 2);
        let run = |seed| {
            let mut m = CourseNewton::new(cylinder(), 3, 4, seed);
            rays.iter()
                .map(|r| m.nearest(r, 0.0, f64::INFINITY).map(f64::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(run(11), run(11));
        // With few attempts the seed matters (some answer or miss differs).
        assert_ne!(run(11), run(12));
    }

    #[test]
    fn the_knobs_matter() {
        let rays = random_rays(100, 3);
        let hits = |s, i| {
            let mut m = CourseNewton::new(cylinder(), s, i, 5);
            rays.iter()
                .filter(|r| m.nearest(r, 0.0, f64::INFINITY).is_some())
                .count()
        };
        let (few, many) = (hits(1, 1), hits(15, 10));
        assert!(many >= 95, "s=15, i=10 found {many}/100");
        assert!(few <= 10, "s=1, i=1 found {few}/100");
    }

    #[test]
    fn delta_is_a_knob() {
        let ray = through_axis(2.0, 0.1, 0.2);
        let want = cylinder_t(&ray, 0.0).unwrap();
        // A loose delta accepts after fewer steps, with a larger error.
        let mut loose = CourseNewton::new(cylinder(), 15, 10, 9).with_delta(0.5);
        let mut tight = CourseNewton::new(cylinder(), 15, 10, 9).with_delta(1e-9);
        let a = loose.nearest(&ray, 0.0, f64::INFINITY).unwrap();
        let b = tight.nearest(&ray, 0.0, f64::INFINITY).unwrap();
        assert!(
            (b - want).abs() < 1e-12,
            "tight error {:e}",
            (b - want).abs()
        );
        assert!(loose.steps() < tight.steps());
        assert!((a - want).abs() < 0.5);
    }

    /// On a patch (no axis) both starting parameters are uniform: the
    /// bilinear patch `S(u, v) = (u, v, uv)` met by vertical rays down
    /// through `(x, y)` at height `xy`, `t = 2 − xy` from `z = 2`.
    #[test]
    fn converges_on_a_patch_without_an_axis() {
        let patch = BezierSurface::new(vec![
            vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
            vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
        ])
        .unwrap();
        assert!(patch.axis_frame().is_none());
        let mut m = CourseNewton::new(patch, 15, 10, 3);
        let mut rng = Rng(8);
        for _ in 0..50 {
            let (x, y) = (rng.range(0.05, 0.95), rng.range(0.05, 0.95));
            let ray = Ray::new(Point3::new(x, y, 2.0), -Vector3::z());
            let t = m.nearest(&ray, 0.0, f64::INFINITY).expect("a hit");
            assert!((t - (2.0 - x * y)).abs() < 1e-9, "t = {t} at ({x}, {y})");
        }
        // Beside the patch's box: no iteration.
        let before = m.steps();
        let beside = Ray::new(Point3::new(1.5, 0.5, 2.0), -Vector3::z());
        assert_eq!(m.nearest(&beside, 0.0, f64::INFINITY), None);
        assert_eq!(m.steps(), before);
    }

    #[test]
    fn wraps_turns_into_the_half_open_unit_interval() {
        assert_eq!(wrap_turn(0.0), 1.0);
        assert_eq!(wrap_turn(1.0), 1.0);
        assert!((wrap_turn(-0.05) - 0.95).abs() < 1e-15);
        assert!((wrap_turn(1.05) - 0.05).abs() < 1e-12);
    }
}

//! Generic Newton intersection for any [`PatchBounds`], seeded from a tree
//! of conservatively bounded parameter patches, with diagnostics.
//!
//! # The method
//! A ray `R(t) = o + t·d` meets a parametric surface `S(u, v)` where
//!
//! `F(t, u, v) = o + t·d − S(u, v) = 0`,
//!
//! three equations in three unknowns. Newton's method solves `J·δ = −F` with
//! the analytic Jacobian `J = [d, −∂S/∂u, −∂S/∂v]` (columns; a 3×3 LU solve)
//! and steps `(t, u, v) += δ`. It converges quadratically near a transversal
//! hit (where `J` is invertible: the ray is not tangent to the surface) and
//! only linearly, or not at all, near tangency; and it finds the root its
//! starting point leads to, not necessarily the nearest one. This is the
//! method of the course notes; the exact solver for surfaces of revolution
//! ([`Revolution`](crate::Revolution)'s [`Intersect`]) is the robust
//! reference it is compared with.
//!
//! # Starting points: the patch tree
//! [`NewtonIntersector::new`] builds, once, a complete binary tree of
//! parameter rectangles of the given depth: each rectangle is halved in the
//! parameter whose image is longer (estimated from the partial derivative at
//! its centre times its width, and the chord across it). Each leaf gets a
//! *conservative* box from [`PatchBounds::bound_patch`]; each inner node
//! the union of its children's boxes, which is conservative too.
//!
//! Per ray the tree is traversed depth first, nearer child first (by the
//! slab test [`Aabb::clip`]), pruning every box the ray enters at or beyond
//! the nearest hit found so far. At each leaf whose box the ray enters, one
//! Newton run starts from the leaf's centre `(u_c, v_c)` and from `t` at the
//! projection of `S(u_c, v_c)` on the ray, clamped to where the ray is inside
//! the box. (`F` is linear in `t`, so Newton's first step does not depend on
//! the starting `t`; the projection only makes the first residual a fair
//! measure of the start.) Deeper trees give more, closer starting points:
//! fewer missed hits, more work per ray.
//!
//! # Stopping and acceptance (edge rules)
//! With `scale` the largest absolute coordinate of the surface's bounding box
//! and `τ` the [`Tolerance`]'s relative target, a run stops ([`NewtonFinish`])
//! when
//! - the residual `|F|` is at most `τ·scale` (`ResidualSmall`);
//! - the step moves the ray point and the surface point by at most `τ·scale`
//!   together (`|δt|·|d| + |δu|·|S_u| + |δv|·|S_v|`, `StepSmall`);
//! - the residual is already acceptable (below) and stops decreasing: rounding
//!   allows no more progress (`RoundingFloor`);
//! - the iteration cap [`Tolerance::max_iterations`] is reached
//!   (`IterationCap`);
//! - `J` is exactly singular (`SingularJacobian`), the iterate is not finite
//!   (`Diverged`), or a non-periodic parameter sits on the edge of its domain
//!   and the step pushes it out again (`LeftDomain`).
//!
//! A non-periodic parameter that steps out of its interval is clamped to it
//! (the crate's curves evaluate outside points at the nearest end, so this is
//! a projected Newton step); a periodic one ([`PatchBounds::periodic`],
//! the angle of a [`Revolution`](crate::Revolution)) is taken modulo its
//! period. The run's answer is its iterate with the smallest residual; it is
//! *converged* when that residual is at most `max(τ, 10⁻⁹)·scale` (the exact
//! solver's acceptance) and the run did not stop at the iteration cap (there
//! it was still improving, so its answer is provisional; every other finish
//! means the run can do no better: a singular Jacobian at a pole, or the
//! domain's edge at a rim, can still hold an exact hit). So `(u, v)` is always
//! inside the domain and the ray passes within that distance of the surface.
//! A converged run is a hit when `t_min + accept/|d| < t < t_max` (hits within
//! the position uncertainty of the origin are the origin itself: a secondary
//! ray leaving the surface does not hit it again) and it is the nearest so far.
//!
//! The hit's `point` is `S(u, v)` (on the surface to rounding; within the
//! acceptance of `o + t·d`), its `normal` is [`Surface::normal`] or, where the
//! surface has no tangent plane (a cone's apex), the unit vector facing the
//! ray (`−d/|d|`). No hit ever holds NaN: non-finite rays and non-finite
//! results are misses.
//!
//! # Edge rules of the query
//! - The search runs on the unit direction `d/|d|` (found without overflow
//!   from `d`'s largest component), so any finite non-zero `d` works, of
//!   length `1e-300` as well as `1e300`; `t` is converted back to units of
//!   `|d|`. A hit whose `t` is then not finite, or no longer strictly inside
//!   `(t_min, t_max)` after the conversion's rounding, is a miss.
//! - A NaN or infinite origin, a zero, NaN or infinite direction, a NaN
//!   `t_min` or `t_max`, or `t_min ≥ t_max` is a miss.
//! - The [`Tolerance`] is used clamped: `relative` into `[ε, 10⁻³]` (NaN
//!   means the default `4ε`), `max_iterations` into `1 ..= 1000`, so no
//!   setting can make a query run without end.
//!
//! # Cost
//! Building evaluates [`bound_patch`](PatchBounds::bound_patch) once per
//! leaf (`2^depth` leaves, `depth ≤` [`MAX_DEPTH`]). A query allocates
//! nothing: the traversal stack is a fixed array of `MAX_DEPTH + 1` entries
//! (a depth-first walk that pushes both children holds at most one pending
//! sibling per level plus the current node).
//!
//! ```
//! use revolve::nalgebra::{Point2, Point3, Vector3};
//! use revolve::ray::newton::{NewtonFinish, NewtonIntersector};
//! use revolve::{Bezier, Intersect, Ray, Revolution};
//!
//! // A cylinder of radius 1 and height 2 about the y axis.
//! let cylinder = Revolution::new(Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)])?);
//! // Borrow the surface (own it by passing it by value instead).
//! let newton = NewtonIntersector::new(&cylinder, 6);
//!
//! let ray = Ray::new(Point3::new(-5.0, 1.0, 0.5), Vector3::new(1.0, 0.0, 0.0));
//! let hit = newton.intersect(&ray, 0.0, f64::INFINITY).unwrap();
//! // Closed form: x² + z² = 1 at z = 0.5 gives x = −√0.75, t = 5 − √0.75.
//! assert!((hit.t - (5.0 - 0.75_f64.sqrt())).abs() < 1e-12);
//! // The exact solver agrees.
//! let exact = cylinder.intersect(&ray, 0.0, f64::INFINITY).unwrap();
//! assert!((hit.t - exact.t).abs() < 1e-12);
//!
//! // The diagnostic path tells how the search went.
//! let (same, report) = newton.intersect_with_report(&ray, 0.0, f64::INFINITY);
//! assert_eq!(same, Some(hit));
//! assert!(report.converged() && report.leaves_tried >= 1);
//! assert!(report.residual() < 1e-12);
//! let run = report.hit.unwrap();
//! assert!(run.iterations > 0);
//! assert!(matches!(
//!     run.finish,
//!     NewtonFinish::ResidualSmall | NewtonFinish::StepSmall | NewtonFinish::RoundingFloor
//! ));
//!
//! // A ray above the cylinder misses, and no run converges.
//! let above = Ray::new(Point3::new(-5.0, 3.0, 0.0), Vector3::new(1.0, 0.0, 0.0));
//! let (miss, report) = newton.intersect_with_report(&above, 0.0, f64::INFINITY);
//! assert!(miss.is_none() && !report.converged() && report.converged_runs == 0);
//! # Ok::<(), revolve::Error>(())
//! ```

use super::acceptance::Acceptance;
use super::{SplitDirection, walk_hits};
use crate::surface::PatchBounds;
use crate::{Aabb, Error, Hit, Intersect, Ray, Surface, Tolerance};
use nalgebra::{Matrix3, Unit};

/// The deepest patch tree [`NewtonIntersector::new`] builds: `2¹⁶` leaves
/// (about 10 MB of boxes). Larger depths are clamped to it.
pub const MAX_DEPTH: u32 = 16;

/// Entries of the traversal stack: at most one pending sibling per level plus
/// the node being expanded.
const TRAVERSAL_STACK: usize = MAX_DEPTH as usize + 1;

/// One node of the parameter tree: a parameter rectangle and a conservative
/// box of its image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParameterBox {
    /// The first parameter interval `(u₀, u₁)`.
    pub u: (f64, f64),
    /// The second parameter interval `(v₀, v₁)`.
    pub v: (f64, f64),
    /// A box containing `S([u₀, u₁] × [v₀, v₁])`.
    pub bounds: Aabb,
}

/// How one Newton run ended (see the [module docs](self) for the exact
/// rules). Whether its answer is accepted is [`NewtonRun::converged`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NewtonFinish {
    /// The residual `|F|` reached the tolerance target.
    ResidualSmall,
    /// The step became smaller than the tolerance target (converged if the
    /// residual is acceptable, else a stall at a near miss).
    StepSmall,
    /// The residual was acceptable and stopped decreasing: rounding allows no
    /// more progress.
    RoundingFloor,
    /// The iteration cap was reached.
    IterationCap,
    /// The Jacobian `[d, −S_u, −S_v]` was exactly singular.
    SingularJacobian,
    /// An iterate or step was not finite.
    Diverged,
    /// A non-periodic parameter was on the edge of its domain and the step
    /// pushed it out again.
    LeftDomain,
}

/// The result of one Newton run on `F(t, u, v) = o + t·d − S(u, v)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonRun {
    /// Ray parameter of the answer (the iterate with the smallest residual).
    pub t: f64,
    /// Surface parameters of the answer, inside the domain (periodic ones
    /// reduced to their interval).
    pub uv: (f64, f64),
    /// `|F(t, u, v)|` at the answer: the distance between the ray point and
    /// the surface point.
    pub residual: f64,
    /// Newton steps taken.
    pub iterations: u32,
    /// Why the run stopped.
    pub finish: NewtonFinish,
    /// Whether the answer is accepted as a point of both ray and surface:
    /// `residual ≤ max(τ, 10⁻⁹)·scale` and the run did not stop at the
    /// iteration cap.
    pub converged: bool,
}

/// How many runs of a query ended each way, one field per [`NewtonFinish`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FinishCounts {
    /// Runs that ended [`NewtonFinish::ResidualSmall`].
    pub residual_small: u32,
    /// Runs that ended [`NewtonFinish::StepSmall`].
    pub step_small: u32,
    /// Runs that ended [`NewtonFinish::RoundingFloor`].
    pub rounding_floor: u32,
    /// Runs that ended [`NewtonFinish::IterationCap`].
    pub iteration_cap: u32,
    /// Runs that ended [`NewtonFinish::SingularJacobian`].
    pub singular_jacobian: u32,
    /// Runs that ended [`NewtonFinish::Diverged`].
    pub diverged: u32,
    /// Runs that ended [`NewtonFinish::LeftDomain`].
    pub left_domain: u32,
}

impl FinishCounts {
    /// The count for one way of finishing.
    pub fn get(&self, finish: NewtonFinish) -> u32 {
        *self.slot(finish)
    }

    fn slot(&self, finish: NewtonFinish) -> &u32 {
        match finish {
            NewtonFinish::ResidualSmall => &self.residual_small,
            NewtonFinish::StepSmall => &self.step_small,
            NewtonFinish::RoundingFloor => &self.rounding_floor,
            NewtonFinish::IterationCap => &self.iteration_cap,
            NewtonFinish::SingularJacobian => &self.singular_jacobian,
            NewtonFinish::Diverged => &self.diverged,
            NewtonFinish::LeftDomain => &self.left_domain,
        }
    }

    fn bump(&mut self, finish: NewtonFinish) {
        let slot = match finish {
            NewtonFinish::ResidualSmall => &mut self.residual_small,
            NewtonFinish::StepSmall => &mut self.step_small,
            NewtonFinish::RoundingFloor => &mut self.rounding_floor,
            NewtonFinish::IterationCap => &mut self.iteration_cap,
            NewtonFinish::SingularJacobian => &mut self.singular_jacobian,
            NewtonFinish::Diverged => &mut self.diverged,
            NewtonFinish::LeftDomain => &mut self.left_domain,
        };
        *slot += 1;
    }
}

/// How one query of [`NewtonIntersector::intersect_with_report`] went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonReport {
    /// Slab tests made: boxes of tree nodes tested against the ray (the
    /// root, and both children of every inner node the ray entered before
    /// the nearest hit).
    pub boxes_tested: u32,
    /// Leaves whose box the ray entered before the nearest hit; each got
    /// exactly one Newton run.
    pub leaves_tried: u32,
    /// Newton steps over all runs.
    pub iterations: u32,
    /// Runs whose answer was accepted as a point of ray and surface
    /// (including those then rejected for `t`).
    pub converged_runs: u32,
    /// Converged runs rejected because `t` was outside `(t_min, t_max)` or
    /// not nearer than the best hit.
    pub rejected_t: u32,
    /// How the runs ended.
    pub finishes: FinishCounts,
    /// The run that produced the returned hit.
    pub hit: Option<NewtonRun>,
    /// Of the runs that did not produce the returned hit, the one with the
    /// smallest residual: for a miss, how close Newton came.
    pub closest: Option<NewtonRun>,
}

impl NewtonReport {
    /// Whether the query found a hit.
    pub fn converged(&self) -> bool {
        self.hit.is_some()
    }

    /// The final residual of the deciding run (the hit's, else the closest
    /// miss's); infinite when no run was made.
    pub fn residual(&self) -> f64 {
        self.deciding().map_or(f64::INFINITY, |r| r.residual)
    }

    /// How the deciding run (the hit's, else the closest miss's) finished;
    /// `None` when no run was made (the ray missed every box).
    pub fn finish(&self) -> Option<NewtonFinish> {
        self.deciding().map(|r| r.finish)
    }

    /// Newton runs made: one per leaf tried.
    pub fn runs(&self) -> u32 {
        self.leaves_tried
    }

    fn deciding(&self) -> Option<&NewtonRun> {
        self.hit.as_ref().or(self.closest.as_ref())
    }

    fn keep_closest(&mut self, run: NewtonRun) {
        if self.closest.is_none_or(|m| run.residual < m.residual) {
            self.closest = Some(run);
        }
    }
}

/// Newton intersection of rays with any [`PatchBounds`], seeded from a
/// patch tree built once (see the [module docs](self) for the method and its
/// rules).
///
/// The intersector owns its surface `S`. Because `&T` is a
/// [`PatchBounds`] whenever `T` is, pass `&surface` to borrow instead (the
/// usual choice when the same surface also serves the exact solver, as in the
/// example); pass the surface by value to keep one self-contained object in a
/// scene.
#[derive(Debug, Clone)]
pub struct NewtonIntersector<S> {
    surface: S,
    /// Complete binary tree in heap order: the children of node `i` are
    /// `2i + 1` and `2i + 2`; the last `2^depth` nodes are the leaves.
    nodes: Vec<ParameterBox>,
    depth: u32,
    tolerance: Tolerance,
    domain: [(f64, f64); 2],
    periodic: [bool; 2],
    /// Largest absolute coordinate of the root box: the scale of tolerances.
    scale: f64,
}

/// Thresholds of one query, from the tolerance and the surface's scale.
#[derive(Debug, Clone, Copy)]
struct Limits {
    /// A run is converged when its residual is within
    /// `acceptance.distance` ([`Acceptance::newton`]).
    acceptance: Acceptance,
    max_iterations: u32,
}

impl<S: PatchBounds> NewtonIntersector<S> {
    /// The intersector for `surface` with a patch tree of `depth` levels
    /// below the root (`2^depth` leaves; clamped to [`MAX_DEPTH`]), and the
    /// default [`Tolerance`] (full double precision, 32 iterations).
    ///
    /// Depth 0 is a single patch: one Newton run per ray from the centre of
    /// the domain, the plain method of the course notes. Building costs one
    /// [`bound_patch`](PatchBounds::bound_patch) per leaf: at
    /// [`MAX_DEPTH`] 65 536 of them (about half a second on a 70-point
    /// profile). [`try_new`](Self::try_new) refuses a depth beyond the cap
    /// instead of clamping it.
    pub fn new(surface: S, depth: u32) -> Self {
        let depth = depth.min(MAX_DEPTH);
        let domain = surface.domain();
        let periodic = surface.periodic();
        let count = (1usize << (depth + 1)) - 1;
        let first_leaf = (1usize << depth) - 1;
        let empty = ParameterBox {
            u: domain[0],
            v: domain[1],
            bounds: Aabb::EMPTY,
        };
        let mut nodes = vec![empty; count];
        for i in 0..first_leaf {
            let ParameterBox { u, v, .. } = nodes[i];
            let (left, right) = if split_u(&surface, u, v) {
                let m = 0.5 * (u.0 + u.1);
                (((u.0, m), v), ((m, u.1), v))
            } else {
                let m = 0.5 * (v.0 + v.1);
                ((u, (v.0, m)), (u, (m, v.1)))
            };
            nodes[2 * i + 1] = ParameterBox {
                u: left.0,
                v: left.1,
                bounds: Aabb::EMPTY,
            };
            nodes[2 * i + 2] = ParameterBox {
                u: right.0,
                v: right.1,
                bounds: Aabb::EMPTY,
            };
        }
        for node in &mut nodes[first_leaf..] {
            node.bounds = surface.bound_patch(node.u, node.v);
        }
        for i in (0..first_leaf).rev() {
            nodes[i].bounds = nodes[2 * i + 1].bounds.union(&nodes[2 * i + 2].bounds);
        }
        let scale = nodes[0].bounds.scale();
        let scale = if scale.is_finite() && scale > 0.0 {
            scale
        } else {
            f64::MIN_POSITIVE
        };
        NewtonIntersector {
            surface,
            nodes,
            depth,
            tolerance: Tolerance::default(),
            domain,
            periodic,
            scale,
        }
    }

    /// As [`new`](Self::new), but a `depth` beyond [`MAX_DEPTH`] is an error
    /// rather than clamped.
    ///
    /// ```
    /// use revolve::{Error, NewtonIntersector, Revolution, Nurbs};
    /// use revolve::nalgebra::Point2;
    ///
    /// let sphere = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -1.5707963267948966, 1.5707963267948966)?);
    /// assert!(NewtonIntersector::try_new(&sphere, 8).is_ok());
    /// assert_eq!(
    ///     NewtonIntersector::try_new(&sphere, 1000).err(),
    ///     Some(Error::DepthTooLarge { depth: 1000, max: 16 })
    /// );
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::DepthTooLarge`] for `depth > MAX_DEPTH`.
    pub fn try_new(surface: S, depth: u32) -> Result<Self, Error> {
        if depth > MAX_DEPTH {
            return Err(Error::DepthTooLarge {
                depth,
                max: MAX_DEPTH,
            });
        }
        Ok(Self::new(surface, depth))
    }

    /// The same intersector with the given accuracy: the residual and step
    /// target relative to the surface's scale, and the iteration cap per run.
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// The accuracy setting.
    pub fn tolerance(&self) -> &Tolerance {
        &self.tolerance
    }

    /// The surface.
    pub fn surface(&self) -> &S {
        &self.surface
    }

    /// The depth of the patch tree (after clamping to [`MAX_DEPTH`]).
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// The largest absolute coordinate of the surface's bounding box: the
    /// scale that relative tolerances refer to.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The leaves of the patch tree (left to right in the tree): their
    /// rectangles and conservative boxes.
    pub fn leaves(&self) -> &[ParameterBox] {
        &self.nodes[(1usize << self.depth) - 1..]
    }

    /// The nearest hit with `t_min < t < t_max`, and how the search went.
    ///
    /// Same answer as [`Intersect::intersect`], which skips the bookkeeping.
    pub fn intersect_with_report(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
    ) -> (Option<Hit>, NewtonReport) {
        let mut report = NewtonReport::default();
        let hit = self.search(ray, t_min, t_max, &mut report);
        (hit, report)
    }

    /// One Newton run from the given start `(t, u, v)`, with this
    /// intersector's tolerance and scale (the building block of the search,
    /// for studies of the method itself). Parameters outside the domain are
    /// first clamped (or reduced, if periodic).
    ///
    /// The run works on the unit direction like the search (`t` converted
    /// both ways). A ray without a finite origin and a finite non-zero
    /// direction gives a run that `Diverged` at its start, not converged.
    pub fn newton(&self, ray: &Ray, t: f64, u: f64, v: f64) -> NewtonRun {
        match UnitRay::new(ray) {
            Some(units) => {
                let run = self.run(&units.ray, units.length_of(t), (u, v), &self.limits());
                units.run_from_unit(run)
            }
            None => NewtonRun {
                t,
                uv: (u, v),
                residual: f64::INFINITY,
                iterations: 0,
                finish: NewtonFinish::Diverged,
                converged: false,
            },
        }
    }

    fn limits(&self) -> Limits {
        let tolerance = self.tolerance.clamped();
        Limits {
            acceptance: Acceptance::newton(&tolerance, self.scale),
            max_iterations: tolerance.max_iterations,
        }
    }

    /// The traversal on the ray with unit direction, with optional
    /// bookkeeping; `t` of the hit and of the recorded runs in the caller's
    /// units.
    #[inline]
    fn search<R: Recorder>(&self, ray: &Ray, t_min: f64, t_max: f64, rec: &mut R) -> Option<Hit> {
        let units = UnitRay::new(ray)?;
        if t_min >= t_max || t_min.is_nan() || t_max.is_nan() {
            return None;
        }
        let hit = self.search_unit(&units, units.length_of(t_min), units.length_of(t_max), rec)?;
        let t = units.parameter_of(hit.t);
        if t.is_finite() && t > t_min && t < t_max {
            Some(Hit { t, ..hit })
        } else {
            rec.discard_hit();
            None
        }
    }

    /// [`search`](Self::search) with `t`, `t_min`, `t_max` as lengths along
    /// the unit direction `units.ray.dir`.
    #[inline]
    fn search_unit<R: Recorder>(
        &self,
        units: &UnitRay,
        t_min: f64,
        t_max: f64,
        rec: &mut R,
    ) -> Option<Hit> {
        let ray = &units.ray;
        let limits = self.limits();
        let t_floor = t_min + limits.acceptance.distance;
        let mut t_best = t_max;
        let mut best: Option<NewtonRun> = None;
        let first_leaf = (1usize << self.depth) - 1;

        // (node, entry, exit); see TRAVERSAL_STACK for the size bound.
        let mut stack = [(0_u32, 0.0_f64, 0.0_f64); TRAVERSAL_STACK];
        let mut len = 0;
        rec.visit();
        if let Some((lo, hi)) = self.nodes[0].bounds.clip(ray, t_floor, t_best) {
            stack[0] = (0, lo, hi);
            len = 1;
        }
        while len > 0 {
            len -= 1;
            let (i, enter, exit) = stack[len];
            if enter >= t_best {
                continue;
            }
            let i = i as usize;
            if i >= first_leaf {
                let patch = &self.nodes[i];
                let centre = (0.5 * (patch.u.0 + patch.u.1), 0.5 * (patch.v.0 + patch.v.1));
                let c = self.surface.eval(centre.0, centre.1);
                let t0 = (c - ray.origin).dot(&ray.dir);
                // `max` then `min`: a NaN projection starts at the entry.
                let t0 = t0.max(enter).min(exit.min(t_best));
                let run = self.run(ray, t0, centre, &limits);
                let accepted = run.converged && run.t > t_floor && run.t < t_best;
                rec.run(&units.run_from_unit(run), accepted);
                if accepted {
                    t_best = run.t;
                    best = Some(run);
                }
                continue;
            }
            let mut children = [None, None];
            for (k, child) in [2 * i + 1, 2 * i + 2].into_iter().enumerate() {
                rec.visit();
                children[k] = self.nodes[child]
                    .bounds
                    .clip(ray, t_floor, t_best)
                    .map(|(lo, hi)| (child as u32, lo, hi));
            }
            // Push the farther child first so the nearer one is expanded
            // first.
            if let (Some(a), Some(b)) = (children[0], children[1]) {
                if b.1 < a.1 {
                    children = [Some(a), Some(b)];
                } else {
                    children = [Some(b), Some(a)];
                }
            }
            for c in children.into_iter().flatten() {
                stack[len] = c;
                len += 1;
            }
        }
        let run = best?;
        let (u, v) = run.uv;
        let point = self.surface.eval(u, v);
        if !(point.coords.iter().all(|c| c.is_finite()) && u.is_finite() && v.is_finite()) {
            rec.discard_hit();
            return None;
        }
        let normal = self
            .surface
            .normal(u, v)
            .filter(|n| n.iter().all(|c| c.is_finite()))
            .unwrap_or_else(|| Unit::new_unchecked(-ray.dir));
        Some(Hit {
            t: run.t,
            point,
            normal,
            uv: run.uv,
        })
    }

    /// Moves parameter `k` into its domain: modulo the period if periodic,
    /// else clamped. Returns the new value and whether it was clamped. A NaN
    /// parameter, or a domain that is not an interval (a surface that breaks
    /// its contract), gives the domain's start; never a panic.
    #[inline]
    fn confine(&self, k: usize, x: f64) -> (f64, bool) {
        let (a, b) = self.domain[k];
        if x >= a && x <= b {
            return (x, false);
        }
        if self.periodic[k] && b > a && x.is_finite() {
            let w = a + (x - a).rem_euclid(b - a);
            // rem_euclid may round up to the period itself.
            return (if w > b { a } else { w }, false);
        }
        (if x > b && a <= b { b } else { a }, true)
    }

    /// Newton's method on `F(t, u, v) = o + t·d − S(u, v)` from `(t, uv)`,
    /// for a unit direction `d`.
    fn run(&self, ray: &Ray, t: f64, uv: (f64, f64), limits: &Limits) -> NewtonRun {
        let (o, d) = (ray.origin, ray.dir);
        let residual = |t: f64, u: f64, v: f64| o + d * t - self.surface.eval(u, v).coords;
        let (mut u, _) = self.confine(0, uv.0);
        let (mut v, _) = self.confine(1, uv.1);
        let mut t = t;
        let mut f = residual(t, u, v).coords;
        let mut r = f.norm();
        let mut best = (r, t, u, v);
        let mut iterations = 0;
        let finish = loop {
            if !(r.is_finite() && t.is_finite()) {
                break NewtonFinish::Diverged;
            }
            if r <= limits.acceptance.target {
                break NewtonFinish::ResidualSmall;
            }
            if iterations >= limits.max_iterations {
                break NewtonFinish::IterationCap;
            }
            let (su, sv) = self.surface.partials(u, v);
            let j = Matrix3::from_columns(&[d, -su, -sv]);
            let Some(step) = j.lu().solve(&(-f)) else {
                break NewtonFinish::SingularJacobian;
            };
            if !step.iter().all(|s| s.is_finite()) {
                break NewtonFinish::Diverged;
            }
            iterations += 1;
            let moved = step.x.abs() + step.y.abs() * su.norm() + step.z.abs() * sv.norm();
            let (u_new, u_clamped) = self.confine(0, u + step.y);
            let (v_new, v_clamped) = self.confine(1, v + step.z);
            // On the edge already and pushed out again: the root is outside.
            if (u_clamped && u_new == u) || (v_clamped && v_new == v) {
                break NewtonFinish::LeftDomain;
            }
            t += step.x;
            u = u_new;
            v = v_new;
            f = residual(t, u, v).coords;
            let r_new = f.norm();
            if r_new < best.0 {
                best = (r_new, t, u, v);
            }
            if moved <= limits.acceptance.target {
                break NewtonFinish::StepSmall;
            }
            if limits.acceptance.accepts(r) && (r_new >= r || r_new.is_nan()) {
                break NewtonFinish::RoundingFloor;
            }
            r = r_new;
        };
        let (residual, t, u, v) = best;
        NewtonRun {
            t,
            uv: (u, v),
            residual,
            iterations,
            finish,
            // A run stopped by the cap was still making progress: its answer
            // is provisional. Any other finish means this run can do no
            // better, and its best iterate stands on its residual.
            converged: finish != NewtonFinish::IterationCap
                && limits.acceptance.accepts(residual)
                && t.is_finite(),
        }
    }
}

/// A ray with its direction scaled to unit length, and the conversion of
/// `t` between the caller's units (`|dir|`) and lengths.
#[derive(Debug, Clone, Copy)]
struct UnitRay {
    /// The same origin, direction `dir/|dir|`.
    ray: Ray,
    /// The largest absolute component `m` of the caller's direction.
    largest: f64,
    /// `|dir/m|`, in `[1, √3]`: `|dir| = m·|dir/m|`, kept as two factors so
    /// that no direction of finite components overflows or underflows.
    norm_of_scaled: f64,
}

impl UnitRay {
    /// `None` for a NaN or infinite origin, or a direction that is zero or
    /// not finite.
    fn new(ray: &Ray) -> Option<Self> {
        if !ray.origin.iter().all(|c| c.is_finite()) {
            return None;
        }
        let split = SplitDirection::new(&ray.dir)?;
        Some(UnitRay {
            ray: Ray::new(ray.origin, split.unit),
            largest: split.largest,
            norm_of_scaled: split.norm_of_scaled,
        })
    }

    /// A ray parameter in the caller's units as a length.
    fn length_of(&self, t: f64) -> f64 {
        t * self.largest * self.norm_of_scaled
    }

    /// A length along the ray as a ray parameter in the caller's units.
    fn parameter_of(&self, length: f64) -> f64 {
        length / self.norm_of_scaled / self.largest
    }

    /// The run with its `t` in the caller's units (not converged if that
    /// `t` is not finite).
    fn run_from_unit(&self, run: NewtonRun) -> NewtonRun {
        let t = self.parameter_of(run.t);
        NewtonRun {
            t,
            converged: run.converged && t.is_finite(),
            ..run
        }
    }
}

/// Whether to halve the rectangle in `u` (else in `v`): the parameter whose
/// image is longer. The length along each parameter is estimated on the
/// rectangle's middle lines as the larger of the polyline through
/// [`LENGTH_SAMPLES`]` + 1` points (which sees folds, where the profile turns
/// back, and whole turns of a periodic parameter) and the partial
/// derivative at the centre times the width.
fn split_u<S: Surface>(surface: &S, u: (f64, f64), v: (f64, f64)) -> bool {
    let (um, vm) = (0.5 * (u.0 + u.1), 0.5 * (v.0 + v.1));
    let (su, sv) = surface.partials(um, vm);
    let polyline = |f: &dyn Fn(f64) -> nalgebra::Point3<f64>, (a, b): (f64, f64)| {
        let mut length = 0.0;
        let mut prev = f(a);
        for k in 1..=LENGTH_SAMPLES {
            let s = if k == LENGTH_SAMPLES {
                b
            } else {
                a + (b - a) * k as f64 / LENGTH_SAMPLES as f64
            };
            let p = f(s);
            length += (p - prev).norm();
            prev = p;
        }
        length
    };
    let length_u = (su.norm() * (u.1 - u.0)).max(polyline(&|s| surface.eval(s, vm), u));
    let length_v = (sv.norm() * (v.1 - v.0)).max(polyline(&|s| surface.eval(um, s), v));
    length_u >= length_v
}

/// Segments of the polylines that estimate a patch's extent when choosing
/// the split direction.
const LENGTH_SAMPLES: usize = 8;

impl<S: PatchBounds> Intersect for NewtonIntersector<S> {
    /// The nearest hit Newton finds from the patch tree's starting points
    /// (see the [module docs](self)): every hit is a true intersection to the
    /// acceptance, but near tangency, or with two hits in one leaf, the
    /// nearest hit can be missed.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.search(ray, t_min, t_max, &mut NoRecord)
    }

    /// The walk of [`Intersect::intersect_all`], with this intersector's own
    /// acceptance (looser than the certified intersectors'). Like
    /// [`intersect`](Self::intersect), it can miss a hit near tangency or
    /// one of two hits in one leaf.
    fn intersect_all(&self, ray: &Ray, t_min: f64, t_max: f64, hits: &mut Vec<Hit>) {
        let accept = self.limits().acceptance.distance;
        walk_hits(
            |from| self.intersect(ray, from, t_max),
            ray,
            t_min,
            accept,
            hits,
        );
    }

    /// The root box of the patch tree: conservative, so it contains every
    /// hit.
    fn bounds(&self) -> Aabb {
        self.nodes[0].bounds
    }
}

/// Bookkeeping hooks of the traversal; the fast path's are empty.
trait Recorder {
    fn visit(&mut self);
    /// A leaf's run; `accepted` when it became the best hit so far.
    fn run(&mut self, run: &NewtonRun, accepted: bool);
    /// The best hit was not returned after all (its point was not finite).
    fn discard_hit(&mut self);
}

struct NoRecord;

impl Recorder for NoRecord {
    #[inline(always)]
    fn visit(&mut self) {}
    #[inline(always)]
    fn run(&mut self, _: &NewtonRun, _: bool) {}
    #[inline(always)]
    fn discard_hit(&mut self) {}
}

impl Recorder for NewtonReport {
    fn visit(&mut self) {
        self.boxes_tested += 1;
    }

    fn run(&mut self, run: &NewtonRun, accepted: bool) {
        self.leaves_tried += 1;
        self.iterations += run.iterations;
        self.finishes.bump(run.finish);
        if run.converged {
            self.converged_runs += 1;
            if !accepted {
                self.rejected_t += 1;
            }
        }
        // A superseded hit run becomes a candidate for the closest miss.
        let candidate = if accepted {
            self.hit.replace(*run)
        } else {
            Some(*run)
        };
        if let Some(c) = candidate {
            self.keep_closest(c);
        }
    }

    fn discard_hit(&mut self) {
        if let Some(h) = self.hit.take() {
            self.keep_closest(h);
        }
    }
}

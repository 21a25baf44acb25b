//! The intersection study: shapes, rays, reference answers, and the
//! measurement of every method and setting against them.
//!
//! For each shape, random rays run from a sphere around the bounding box
//! through a random point of the box (hits and misses mixed, as in
//! rendering). The exact reference ([`ExactProfile`]) answers each ray in
//! rational arithmetic, and for the rational shapes (a NURBS sphere and
//! torus) the closed forms solved exactly ([`ClosedForm`]); rays a
//! reference cannot certify (tangent contacts) are left out and counted. Every method then traces the same rays twice: once for
//! its answers (errors against the reference), then `repeats` timed passes on
//! one thread, of which the median rate is reported. The exact intersector
//! has two rows per tolerance: one ray a call, and the same object through
//! `intersect_batch`, 8 consecutive rays a call ([`crate::batch`]), whose
//! hits are checked against the single calls' bit for bit.

use crate::batch::{Single, record_single_and_batched};
use crate::closed_form::ClosedForm;
use crate::course::CourseNewton;
use crate::memory::built;
use crate::mesh_baseline::MeshBaseline;
use crate::model::{ErrorStats, FAR_HIT, Method, Row};
use crate::reference::{Certifier, ExactProfile};
use revolve::{
    Aabb, BSpline, Bezier, Curve, Intersect, NewtonIntersector, Nurbs, PatchBounds, Ray,
    Revolution, Tolerance,
};
use std::hint::black_box;
use std::time::Instant;

use crate::common::Rng;
use rayon::prelude::*;

/// Rays start this far along `dir` (unit) from the target point, times the
/// box diagonal; every method searches `(0, T_MAX)`.
const START: f64 = 2.0;
pub const T_MAX: f64 = 100.0;

/// How big a run is.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// Rays per shape.
    pub rays: usize,
    /// Timed passes per method (the median rate is reported).
    pub repeats: usize,
    /// Relative tolerances of the exact intersector (and of the same
    /// profile given as an own curve, without Bézier spans).
    pub exact_tolerances: Vec<f64>,
    /// Patch-tree depths and tolerances of the generic Newton intersector.
    pub newton_depths: Vec<u32>,
    pub newton_tolerances: Vec<f64>,
    /// `(attempts, iterations)` of the course method.
    pub course: Vec<(u32, u32)>,
    /// Tessellation tolerances of the triangle-mesh baseline.
    pub mesh_tolerances: Vec<f64>,
}

impl Plan {
    /// The full study (a few minutes on 2 cores).
    pub fn full() -> Self {
        Plan {
            rays: 2000,
            repeats: 5,
            exact_tolerances: vec![1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14],
            newton_depths: vec![4, 6, 8, 10],
            newton_tolerances: vec![1e-4, 1e-8, 1e-12],
            course: vec![(1, 10), (5, 10), (15, 5), (15, 10), (15, 20), (40, 20)],
            mesh_tolerances: vec![1e-2, 1e-3, 1e-4, 1e-5],
        }
    }

    /// Every code path at a tiny size (CI, tests).
    pub fn quick() -> Self {
        Plan {
            rays: 48,
            repeats: 1,
            exact_tolerances: vec![1e-3, 1e-14],
            newton_depths: vec![4],
            newton_tolerances: vec![1e-8],
            course: vec![(15, 10)],
            mesh_tolerances: vec![1e-2],
        }
    }

    /// Rows one patch shape produces: the certified intersector at each
    /// exact tolerance, single rays and in batches, then as for a revolution
    /// without the own-curve sweep ([`crate::patch_study`]).
    pub fn patch_rows(&self) -> usize {
        2 * self.exact_tolerances.len()
            + self.newton_depths.len() * self.newton_tolerances.len()
            + self.course.len()
            + self.mesh_tolerances.len()
    }

    /// Rows one shape of revolution produces (for the progress bar): the
    /// exact intersector in single rays and in batches, and the own curve,
    /// at each exact tolerance; then Newton, the course method, the meshes.
    pub fn rows(&self) -> usize {
        3 * self.exact_tolerances.len()
            + self.newton_depths.len() * self.newton_tolerances.len()
            + self.course.len()
            + self.mesh_tolerances.len()
    }
}

/// A shape of the study: its profile, revolved, and the reference that
/// certifies its rays.
pub struct Shape<C> {
    pub name: &'static str,
    pub profile: C,
    pub reference: Box<dyn Certifier>,
}

/// The vase: one cubic Bézier.
pub fn vase() -> Shape<Bezier<2>> {
    let profile = crate::common::vase();
    let exact = ExactProfile::from_bezier(profile.points());
    Shape {
        name: "vase",
        profile,
        reference: Box::new(exact),
    }
}

/// The wine glass: a 25-point uniform cubic B-spline.
pub fn wine_glass() -> Shape<BSpline<2>> {
    let profile = crate::common::wine_glass();
    let exact = ExactProfile::from_bspline(profile.degree(), profile.knots(), profile.points());
    Shape {
        name: "wine glass",
        profile,
        reference: Box::new(exact),
    }
}

/// The sphere's radius.
pub const SPHERE_RADIUS: f64 = 1.0;

/// The torus's radii: the tube's centre circle and the tube.
pub const TORUS_RADII: (f64, f64) = (1.0, 0.375);

/// A sphere as a rational revolution: the NURBS half circle from pole to
/// pole (`Nurbs::arc`, two quarter arcs) about the axis.
pub fn sphere() -> Shape<Nurbs<2>> {
    Shape {
        name: "NURBS sphere",
        profile: crate::common::conic_profiles::sphere_profile(SPHERE_RADIUS),
        reference: Box::new(ClosedForm::Sphere {
            radius: SPHERE_RADIUS,
        }),
    }
}

/// A torus as a rational revolution: the NURBS circle off the axis
/// (`Nurbs::circle`, four quarter arcs) about it.
pub fn torus() -> Shape<Nurbs<2>> {
    let (major, minor) = TORUS_RADII;
    Shape {
        name: "NURBS torus",
        profile: crate::common::conic_profiles::torus_profile(major, minor),
        reference: Box::new(ClosedForm::Torus { major, minor }),
    }
}

/// A ray and its certified nearest hit (`None`: a certain miss).
#[derive(Debug, Clone, Copy)]
pub struct Case {
    pub ray: Ray,
    pub t: Option<f64>,
}

/// The rays of one shape with their reference answers.
pub struct Cases {
    pub cases: Vec<Case>,
    /// Rays the reference could not certify (left out).
    pub ambiguous: usize,
    /// The object's scale: errors are `|t − t_ref| / scale`.
    pub scale: f64,
}

impl Cases {
    /// The rays, in order.
    pub fn rays(&self) -> Vec<Ray> {
        self.cases.iter().map(|c| c.ray).collect()
    }
}

/// `count` random rays through `bounds` (unit directions, `d_y ≠ 0`),
/// deterministic for `seed`.
pub fn random_rays(bounds: &Aabb, count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let radius = START * bounds.extent().norm();
    let mut rays = Vec::with_capacity(count);
    while rays.len() < count {
        let target = rng.point_in(bounds);
        let dir = rng.direction();
        if dir.y == 0.0 {
            continue; // the reference handles d_y ≠ 0 only
        }
        rays.push(Ray::new(target - dir * radius, dir));
    }
    rays
}

/// The reference answers for `rays` (in parallel: the exact arithmetic is
/// the slow part of a run).
pub fn reference_cases(reference: &dyn Certifier, rays: &[Ray], scale: f64) -> Cases {
    let answers: Vec<Option<Option<f64>>> = rays
        .par_iter()
        .map(|r| reference.certify(r, 0.0, T_MAX))
        .collect();
    let mut cases = Vec::with_capacity(rays.len());
    let mut ambiguous = 0;
    for (ray, answer) in rays.iter().zip(answers) {
        match answer {
            Some(t) => cases.push(Case { ray: *ray, t }),
            None => ambiguous += 1,
        }
    }
    Cases {
        cases,
        ambiguous,
        scale,
    }
}

/// The errors of `answers` (one per case, in order) against the reference.
pub fn error_stats(cases: &Cases, answers: &[Option<f64>]) -> ErrorStats {
    let mut errors = Vec::new();
    let (mut hits, mut misses, mut false_hits, mut wrong, mut ref_misses) = (0, 0, 0, 0, 0);
    for (case, answer) in cases.cases.iter().zip(answers) {
        match (case.t, *answer) {
            (Some(t_ref), Some(t)) => {
                hits += 1;
                let e = (t - t_ref).abs() / cases.scale;
                if e > FAR_HIT {
                    wrong += 1;
                }
                errors.push(e);
            }
            (Some(_), None) => {
                hits += 1;
                misses += 1;
            }
            (None, Some(_)) => {
                ref_misses += 1;
                false_hits += 1;
            }
            (None, None) => ref_misses += 1,
        }
    }
    errors.sort_by(f64::total_cmp);
    let rate = |k: usize, of: usize| if of == 0 { 0.0 } else { k as f64 / of as f64 };
    ErrorStats {
        rays: cases.cases.len(),
        reference_hits: hits,
        median: median_sorted(&errors),
        max: errors.last().copied().unwrap_or(0.0),
        miss_rate: rate(misses, hits),
        false_hit_rate: rate(false_hits, ref_misses),
        far_hit_rate: rate(wrong, hits),
    }
}

/// The median of sorted values (0 for none).
pub fn median_sorted(v: &[f64]) -> f64 {
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// Casts every case's ray once for the answers, then `repeats` timed
/// passes, each through the method's [`Method::nearest_all`]: the error
/// figures and the median rays per second.
pub fn measure(method: &mut dyn Method, cases: &Cases, repeats: usize) -> (ErrorStats, f64) {
    let rays = cases.rays();
    let mut answers = vec![None; rays.len()];
    method.nearest_all(&rays, 0.0, T_MAX, &mut answers);
    let stats = error_stats(cases, &answers);
    let mut rates: Vec<f64> = (0..repeats.max(1))
        .map(|_| {
            let start = Instant::now();
            method.nearest_all(black_box(&rays), 0.0, T_MAX, &mut answers);
            black_box(&answers);
            rays.len() as f64 / start.elapsed().as_secs_f64().max(1e-12)
        })
        .collect();
    rates.sort_by(f64::total_cmp);
    (stats, median_sorted(&rates))
}

/// The exact intersector at one tolerance.
struct Exact<C> {
    surface: Revolution<C>,
    tolerance: f64,
}

impl<C: Curve<2>> Method for Exact<C> {
    fn series(&self) -> String {
        "revolve exact".to_string()
    }
    fn knob(&self) -> String {
        format!("tol {:.0e}", self.tolerance)
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.surface.intersect(ray, t_min, t_max).map(|h| h.t)
    }
}

impl<C: Curve<2>> Single for Exact<C> {
    type Model = Revolution<C>;
    fn model(&self) -> &Revolution<C> {
        &self.surface
    }
}

/// A profile seen only through the three required [`Curve`] methods, as a
/// user's own curve type is: no Bézier spans, so its revolution is
/// intersected through its approximation refined on the curve.
#[derive(Clone)]
struct OwnCurve<C>(C);

impl<C: Curve<2>> Curve<2> for OwnCurve<C> {
    fn domain(&self) -> (f64, f64) {
        self.0.domain()
    }
    fn eval(&self, t: f64) -> revolve::nalgebra::Point2<f64> {
        self.0.eval(t)
    }
    fn derivative(&self, t: f64) -> revolve::nalgebra::Vector2<f64> {
        self.0.derivative(t)
    }
}

/// The same shape's profile as an own curve, at one tolerance.
struct Approximated<C> {
    surface: Revolution<OwnCurve<C>>,
    tolerance: f64,
}

impl<C: Curve<2>> Method for Approximated<C> {
    fn series(&self) -> String {
        "revolve own curve (approximation + Newton)".to_string()
    }
    fn knob(&self) -> String {
        format!("tol {:.0e}", self.tolerance)
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.surface.intersect(ray, t_min, t_max).map(|h| h.t)
    }
}

/// The generic Newton intersector at one depth and tolerance.
pub struct Newton<S> {
    pub solver: NewtonIntersector<S>,
    pub tolerance: f64,
}

impl<S: PatchBounds> Method for Newton<S> {
    fn series(&self) -> String {
        format!("revolve Newton, depth {}", self.solver.depth())
    }
    fn knob(&self) -> String {
        format!("depth {}, tol {:.0e}", self.solver.depth(), self.tolerance)
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.solver.intersect(ray, t_min, t_max).map(|h| h.t)
    }
}

/// The row of `method` on `shape`'s `cases`, measured `repeats` times;
/// `(seconds, bytes)` is what it took to build. A batch method's hits are
/// also compared with its single path's ([`Method::batch_mismatches`]).
pub fn measured_row(
    shape: &'static str,
    method: &mut dyn Method,
    cases: &Cases,
    repeats: usize,
    (seconds, bytes): (f64, usize),
) -> Row {
    let (errors, rate) = measure(method, cases, repeats);
    let batch_mismatches = method.batch_mismatches(&cases.rays(), 0.0, T_MAX);
    Row {
        shape,
        series: method.series(),
        knob: method.knob(),
        errors,
        rays_per_second: rate,
        memory_bytes: bytes,
        build_seconds: seconds,
        batch_mismatches,
    }
}

/// Every method and setting of `plan` on one shape; `tick` after each row.
pub fn run_shape<C: Curve<2> + Clone>(
    shape: &Shape<C>,
    cases: &Cases,
    plan: &Plan,
    tick: &mut dyn FnMut(&Row),
) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut record = |method: &mut dyn Method, seconds: f64, bytes: usize| {
        let row = measured_row(shape.name, method, cases, plan.repeats, (seconds, bytes));
        tick(&row);
        rows.push(row);
    };
    for &tolerance in &plan.exact_tolerances {
        let exact = || Exact {
            surface: Revolution::new(shape.profile.clone())
                .with_tolerance(Tolerance::relative(tolerance)),
            tolerance,
        };
        record_single_and_batched(exact, &mut record);
    }
    for &tolerance in &plan.exact_tolerances {
        let (mut m, s, b) = built(|| Approximated {
            surface: Revolution::new(OwnCurve(shape.profile.clone()))
                .with_tolerance(Tolerance::relative(tolerance)),
            tolerance,
        });
        record(&mut m, s, b);
    }
    for &depth in &plan.newton_depths {
        for &tolerance in &plan.newton_tolerances {
            let (mut m, s, b) = built(|| Newton {
                solver: NewtonIntersector::new(Revolution::new(shape.profile.clone()), depth)
                    .with_tolerance(Tolerance::relative(tolerance)),
                tolerance,
            });
            record(&mut m, s, b);
        }
    }
    for &(attempts, iterations) in &plan.course {
        let (mut m, s, b) = built(|| {
            CourseNewton::new(
                Revolution::new(shape.profile.clone()),
                attempts,
                iterations,
                0x5EED,
            )
        });
        record(&mut m, s, b);
    }
    for &tolerance in &plan.mesh_tolerances {
        // A tolerance the tessellator rejects is skipped, not fatal.
        if let Ok((mut m, build)) =
            MeshBaseline::build(&Revolution::new(shape.profile.clone()), tolerance)
        {
            record(&mut m, build.seconds, build.bytes);
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use revolve::nalgebra::{Point3, Vector3};

    fn case(t: Option<f64>) -> Case {
        Case {
            ray: Ray::new(Point3::origin(), Vector3::y()),
            t,
        }
    }

    #[test]
    fn error_figures_count_each_kind_of_answer() {
        let cases = Cases {
            cases: vec![
                case(Some(1.0)),
                case(Some(2.0)),
                case(Some(3.0)),
                case(Some(4.0)),
                case(None),
                case(None),
            ],
            ambiguous: 0,
            scale: 2.0,
        };
        // Exact, off by 2e-6, another root (off by 1), missed; one false hit.
        let answers = [
            Some(1.0),
            Some(2.0 + 2e-6),
            Some(4.0),
            None,
            Some(5.0),
            None,
        ];
        let e = error_stats(&cases, &answers);
        assert_eq!((e.rays, e.reference_hits), (6, 4));
        assert!(
            (e.median - 1e-6).abs() < 1e-15,
            "median of 0, 1e-6 and 0.5: {}",
            e.median
        );
        assert_eq!(e.max, 0.5);
        assert_eq!(e.miss_rate, 0.25);
        assert_eq!(e.false_hit_rate, 0.5);
        assert_eq!(e.far_hit_rate, 0.25);
    }

    #[test]
    fn rays_are_deterministic_and_aimed_at_the_box() {
        let b = Aabb::new(Point3::new(-1.0, -1.0, -1.0), Point3::new(1.0, 2.0, 1.0));
        let rays = random_rays(&b, 100, 7);
        assert_eq!(rays, random_rays(&b, 100, 7));
        for r in &rays {
            assert!(r.dir.y != 0.0 && (r.dir.norm() - 1.0).abs() < 1e-12);
            let clip = b.clip(r, 0.0, T_MAX);
            assert!(clip.is_some(), "{r:?} misses the box it was aimed at");
        }
    }

    /// The claim the study rests on: on certified rays, the exact
    /// intersector at full precision agrees with the rational reference
    /// (no miss, no false hit, errors at rounding level).
    #[test]
    fn exact_intersector_matches_the_reference() {
        let glass = wine_glass();
        let surface = Revolution::new(glass.profile.clone());
        let b = surface.bounds();
        let cases = reference_cases(
            glass.reference.as_ref(),
            &random_rays(&b, 200, 11),
            b.scale(),
        );
        assert!(cases.ambiguous <= 2, "{} ambiguous", cases.ambiguous);
        let hits = cases.cases.iter().filter(|c| c.t.is_some()).count();
        assert!(hits > 50, "only {hits} hits");
        let mut m = Exact {
            surface,
            tolerance: 4.0 * f64::EPSILON,
        };
        let (e, rate) = measure(&mut m, &cases, 1);
        assert_eq!(e.miss_rate, 0.0);
        assert_eq!(e.false_hit_rate, 0.0);
        assert!(e.max < 1e-12, "max error {:e}", e.max);
        assert!(rate > 0.0);
    }

    /// The same claim for the rational shapes against their closed forms:
    /// the NURBS sphere and torus get the exact intersector, which misses
    /// nothing and hits nothing false on certified rays, at rounding level.
    #[test]
    fn rational_shapes_match_their_closed_forms() {
        for shape in [sphere(), torus()] {
            let surface = Revolution::new(shape.profile.clone());
            assert!(surface.has_exact_intersector(), "{}", shape.name);
            let b = surface.bounds();
            let rays = random_rays(&b, 300, 17);
            let cases = reference_cases(shape.reference.as_ref(), &rays, b.scale());
            assert_eq!(cases.ambiguous, 0, "{}", shape.name);
            let hits = cases.cases.iter().filter(|c| c.t.is_some()).count();
            assert!(hits > 100, "{}: only {hits} hits", shape.name);
            let mut m = Exact {
                surface,
                tolerance: 4.0 * f64::EPSILON,
            };
            let (e, _) = measure(&mut m, &cases, 1);
            assert_eq!(e.miss_rate, 0.0, "{}", shape.name);
            assert_eq!(e.false_hit_rate, 0.0, "{}", shape.name);
            assert!(e.max < 1e-12, "{}: max error {:e}", shape.name, e.max);
        }
    }

    /// The glass's profile given as an own curve (no Bézier spans): its
    /// approximation refined on the curve agrees with the rational
    /// reference on certified rays as the exact intersector does.
    #[test]
    fn own_curve_profile_matches_the_reference() {
        let glass = wine_glass();
        let surface = Revolution::new(OwnCurve(glass.profile.clone()));
        assert!(!surface.has_exact_intersector());
        let b = Revolution::new(glass.profile.clone()).bounds();
        let cases = reference_cases(
            glass.reference.as_ref(),
            &random_rays(&b, 400, 13),
            b.scale(),
        );
        let hits = cases.cases.iter().filter(|c| c.t.is_some()).count();
        assert!(hits > 100, "only {hits} hits");
        let mut m = Approximated {
            surface,
            tolerance: 4.0 * f64::EPSILON,
        };
        let (e, _) = measure(&mut m, &cases, 1);
        assert_eq!(e.miss_rate, 0.0);
        assert_eq!(e.false_hit_rate, 0.0);
        assert!(e.max < 1e-12, "max error {:e}", e.max);
    }
}

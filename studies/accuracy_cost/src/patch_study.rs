//! The intersection study on tensor-product Bézier patches: a gently curved
//! bicubic, a folded bicubic and Newell's teapot (32 bicubic patches), each
//! against the certified interval reference ([`PatchReference`]).
//!
//! Methods, on the same rays as for the revolutions:
//! - revolve's certified patch intersector (`Intersect` on
//!   [`BezierSurface`]) at the plan's exact tolerances (`with_tolerance`),
//!   one ray a call and in batches of 8 (`intersect_batch`,
//!   [`crate::batch`]);
//! - [`NewtonIntersector`] at the plan's depths and tolerances;
//! - the course method ([`CourseNewton`]) with `u₀`, `v₀` uniform;
//! - the patches tessellated by revolve (`tessellate`, certified deviation,
//!   welded along shared edges) and ray-cast as one parry `TriMesh`, at the
//!   plan's mesh tolerances (absolute; meshes predicted to exceed
//!   [`MAX_TRIANGLES`] are skipped).
//!
//! The certified intersector ray-casts the teapot as a [`BezierPatches`]
//! (a hierarchy over the patches' boxes); Newton and the course method as a
//! loop over its patches, each behind a test of its box ([`PatchLoop`]);
//! the meshes are one `TriMesh` of all patches.

use crate::batch::{Single, record_single_and_batched};
use crate::course::CourseNewton;
use crate::memory::built;
use crate::mesh_baseline::MeshBaseline;
use crate::model::{Method, Row};
use crate::patch_shapes;
use crate::reference::PatchReference;
use crate::study::{Cases, Newton, Plan, measured_row};
use revolve::nalgebra::Vector3;
use revolve::{Aabb, BezierPatches, BezierSurface, Intersect, NewtonIntersector, Ray, Tolerance};

/// Meshes predicted to have more triangles are not built (memory on a
/// shared machine).
pub const MAX_TRIANGLES: usize = 2_500_000;

/// A shape made of Bézier patches.
pub struct PatchShape {
    pub name: &'static str,
    pub patches: Vec<BezierSurface>,
}

impl PatchShape {
    /// The union of the patches' boxes.
    pub fn bounds(&self) -> Aabb {
        self.patches
            .iter()
            .fold(Aabb::EMPTY, |b, p| b.union(&p.bounds()))
    }

    /// The certified reference for its rays.
    pub fn reference(&self) -> PatchReference {
        PatchReference::new(&self.patches)
    }
}

/// The gently curved bicubic patch.
pub fn bicubic_patch() -> PatchShape {
    PatchShape {
        name: "bicubic patch",
        patches: vec![patch_shapes::gentle_bicubic()],
    }
}

/// The folded bicubic patch.
pub fn folded_patch() -> PatchShape {
    PatchShape {
        name: "folded patch",
        patches: vec![crate::common::tensor_shapes::folded_bicubic()],
    }
}

/// Newell's teapot (`scenes/data/teapot.txt`).
pub fn teapot() -> PatchShape {
    PatchShape {
        name: "teapot",
        patches: crate::common::teapot::patches(),
    }
}

/// revolve's certified intersector on a patch ([`BezierSurface`]) or a model
/// of many ([`BezierPatches`], through its hierarchy).
pub struct Certified<M> {
    model: M,
    knob: String,
}

impl<M: Intersect> Method for Certified<M> {
    fn series(&self) -> String {
        "revolve certified".to_string()
    }
    fn knob(&self) -> String {
        self.knob.clone()
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        self.model.intersect(ray, t_min, t_max).map(|h| h.t)
    }
}

impl<M: Intersect> Single for Certified<M> {
    type Model = M;
    fn model(&self) -> &M {
        &self.model
    }
}

/// One method per patch, each tried where the ray meets that patch's box
/// (searching only up to the nearest hit so far); the nearest hit wins. With
/// one patch, the method alone.
pub struct PatchLoop<M> {
    parts: Vec<(Aabb, M)>,
}

impl<M: Method> PatchLoop<M> {
    pub fn new(patches: &[BezierSurface], make: impl Fn(&BezierSurface) -> M) -> Self {
        PatchLoop {
            parts: patches.iter().map(|p| (p.bounds(), make(p))).collect(),
        }
    }
}

impl<M: Method> Method for PatchLoop<M> {
    fn series(&self) -> String {
        self.parts[0].1.series()
    }
    fn knob(&self) -> String {
        let knob = self.parts[0].1.knob();
        match self.parts.len() {
            1 => knob,
            n => format!("{knob}, loop over {n} boxes"),
        }
    }
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        if let [(_, only)] = self.parts.as_mut_slice() {
            return only.nearest(ray, t_min, t_max);
        }
        let mut best = None;
        let mut reach = t_max;
        for (bounds, method) in &mut self.parts {
            if bounds.clip(ray, t_min, reach).is_none() {
                continue;
            }
            if let Some(t) = method.nearest(ray, t_min, reach) {
                best = Some(t);
                reach = t;
            }
        }
        best
    }
}

/// `surface` after one ray: a surface cuts its patches into the search's
/// pieces on its first ray, so that this counts in its build time and the
/// memory it holds, as it would in use.
fn searched(surface: BezierSurface) -> BezierSurface {
    let centre = surface.bounds().center();
    let ray = Ray::new(
        centre - Vector3::new(0.3, 0.2, 1.0) * 10.0,
        Vector3::new(0.3, 0.2, 1.0),
    );
    let _ = surface.intersect(&ray, 0.0, f64::INFINITY);
    surface
}

/// Every method and setting of `plan` on one patch shape; `tick` after each
/// row.
pub fn run_patch_shape(
    shape: &PatchShape,
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
    let patches = &shape.patches;
    for &tolerance in &plan.exact_tolerances {
        let tol = Tolerance::relative(tolerance);
        let knob = format!("tol {tolerance:.0e}");
        if let [patch] = patches.as_slice() {
            let certified = || Certified {
                model: searched(patch.clone().with_tolerance(tol)),
                knob: knob.clone(),
            };
            record_single_and_batched(certified, &mut record);
        } else {
            let certified = || Certified {
                model: BezierPatches::new(patches.clone())
                    .expect("a non-empty model")
                    .with_tolerance(tol),
                knob: format!("{knob}, BVH over {} patches", patches.len()),
            };
            record_single_and_batched(certified, &mut record);
        }
    }
    for &depth in &plan.newton_depths {
        for &tolerance in &plan.newton_tolerances {
            let (mut m, s, b) = built(|| {
                PatchLoop::new(patches, |p| Newton {
                    solver: NewtonIntersector::new(p.clone(), depth)
                        .with_tolerance(Tolerance::relative(tolerance)),
                    tolerance,
                })
            });
            record(&mut m, s, b);
        }
    }
    for &(attempts, iterations) in &plan.course {
        let (mut m, s, b) = built(|| {
            PatchLoop::new(patches, |p| {
                CourseNewton::new(p.clone(), attempts, iterations, 0x5EED)
            })
        });
        record(&mut m, s, b);
    }
    // Triangles grow about as 1/tolerance (the grid's cells as
    // 1/√tolerance a side): a mesh predicted from the previous one to
    // exceed MAX_TRIANGLES is skipped, as is one the tessellator refuses.
    let mut previous: Option<(f64, usize)> = None;
    for &tolerance in &plan.mesh_tolerances {
        let predicted = previous.map_or(0.0, |(tol, tris)| tris as f64 * tol / tolerance);
        if predicted > MAX_TRIANGLES as f64 {
            continue;
        }
        if let Ok((mut m, build)) = MeshBaseline::from_patches(patches, tolerance) {
            previous = Some((tolerance, build.triangles));
            record(&mut m, build.seconds, build.bytes);
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::interval::Interval;
    use crate::common::reference::patch::Answer;
    use crate::common::{kappa, t_tolerance};
    use crate::study::{random_rays, reference_cases};
    use revolve::Surface;
    use revolve::nalgebra::{Point3, Vector3};

    /// The bilinear patch `S(u, v) = (u, v, u·v)` and a ray: the closed form
    /// `t` of their nearest hit (a quadratic in `t`), or `None`.
    fn bilinear_t(ray: &Ray) -> Option<f64> {
        let (o, d) = (ray.origin, ray.dir);
        // z = x·y along the ray: (o_x + t d_x)(o_y + t d_y) − (o_z + t d_z) = 0.
        let a = d.x * d.y;
        let b = o.x * d.y + o.y * d.x - d.z;
        let c = o.x * o.y - o.z;
        let mut roots = if a == 0.0 {
            vec![-c / b]
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                return None;
            }
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            vec![q / a, c / q]
        };
        roots.sort_by(f64::total_cmp);
        roots.into_iter().find(|&t| {
            let p = ray.at(t);
            t > 0.0 && (0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)
        })
    }

    #[test]
    fn the_reference_matches_the_bilinear_closed_form() {
        let patch = BezierSurface::new(vec![
            vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
            vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
        ])
        .unwrap();
        let reference = PatchReference::new(std::slice::from_ref(&patch));
        let rays = random_rays(&patch.bounds(), 400, 21);
        let (mut hits, mut certain) = (0, 0);
        for ray in &rays {
            let want = bilinear_t(ray);
            match reference.nearest(ray, 0.0, 100.0) {
                Answer::Hit(t) => {
                    certain += 1;
                    hits += 1;
                    let w = want.unwrap_or_else(|| panic!("closed form misses {ray:?}"));
                    assert!(t.lo <= w + 1e-14 && w - 1e-14 <= t.hi, "{t:?} vs {w}");
                    assert!(t.hi - t.lo < 1e-12, "{t:?} too wide");
                }
                Answer::Miss => {
                    certain += 1;
                    assert_eq!(want, None, "{ray:?}");
                }
                Answer::Ambiguous => {}
            }
        }
        assert!(certain >= 396, "only {certain} of 400 certain");
        assert!(hits > 100, "only {hits} hits");
    }

    /// Whether revolve's hit `h` is the reference's: its `t` within the
    /// reference interval widened by the hit's allowed error (the backward
    /// error `1e-12` of the scale amplified by its condition).
    fn agrees(h: &revolve::Hit, ray: &Ray, want: Interval, scale: f64) -> bool {
        let slack = t_tolerance(scale, kappa(&ray.dir, &h.normal), &ray.dir);
        want.lo - slack <= h.t && h.t <= want.hi + slack
    }

    /// Each ray's certified answer agrees with revolve's certified
    /// intersector (a second, independently written method) on the three
    /// shapes, and on the fold the window is respected: from just past the
    /// first hit, the next one. The reference's intervals are narrow.
    #[test]
    fn the_reference_agrees_with_the_certified_intersector() {
        for shape in [bicubic_patch(), folded_patch(), teapot()] {
            let reference = shape.reference();
            let b = shape.bounds();
            let scale = b.scale();
            let (mut second, mut hits, mut widest) = (0, 0, 0.0_f64);
            for ray in random_rays(&b, 300, 5) {
                let nearest = |t_min: f64| {
                    shape
                        .patches
                        .iter()
                        .filter_map(|p| p.intersect(&ray, t_min, 100.0))
                        .min_by(|x, y| x.t.total_cmp(&y.t))
                };
                match (reference.nearest(&ray, 0.0, 100.0), nearest(0.0)) {
                    (Answer::Hit(want), Some(h)) => {
                        hits += 1;
                        widest = widest.max((want.hi - want.lo) / scale);
                        assert!(agrees(&h, &ray, want, scale), "{h:?} vs {want:?}");
                        let past = want.hi + 1e-9;
                        if let Answer::Hit(next) = reference.nearest(&ray, past, 100.0) {
                            second += 1;
                            let h2 = nearest(past).expect("the second hit");
                            assert!(agrees(&h2, &ray, next, scale), "{h2:?} vs {next:?}");
                        }
                    }
                    (Answer::Miss, None) | (Answer::Ambiguous, _) => {}
                    (want, got) => panic!("{}: reference {want:?}, certified {got:?}", shape.name),
                }
            }
            assert!(hits > 100, "{}: only {hits} hits", shape.name);
            assert!(widest < 1e-12, "{}: reference {widest:e} wide", shape.name);
            if shape.name == "folded patch" {
                assert!(second >= 3, "only {second} rays cross the fold twice");
            }
        }
    }

    /// Every row kind runs on the teapot at the quick size, and the
    /// certified intersector misses nothing against the reference.
    #[test]
    fn teapot_rows_at_the_quick_size() {
        let shape = teapot();
        assert_eq!(shape.patches.len(), 32);
        let b = shape.bounds();
        let plan = Plan::quick();
        let cases = reference_cases(&shape.reference(), &random_rays(&b, 60, 9), b.scale());
        let rows = run_patch_shape(&shape, &cases, &plan, &mut |_| {});
        assert_eq!(rows.len(), plan.patch_rows());
        let newton = 2 * plan.exact_tolerances.len();
        assert!(rows[newton].knob.contains("loop over 32 boxes"));
        for pair in rows[..newton].chunks(2) {
            let (single, batched) = (&pair[0], &pair[1]);
            assert_eq!(single.series, "revolve certified");
            assert_eq!(batched.series, "revolve certified, batches of 8");
            assert_eq!(single.batch_mismatches, None);
            assert_eq!(batched.batch_mismatches, Some(0));
            // The same answers, so the same error figures.
            assert_eq!(batched.errors, single.errors);
            assert_eq!(batched.knob, single.knob);
            for certified in pair {
                assert!(certified.knob.contains("BVH over 32 patches"));
                assert_eq!(certified.errors.miss_rate, 0.0);
                assert_eq!(certified.errors.false_hit_rate, 0.0);
                assert_eq!(certified.errors.far_hit_rate, 0.0);
            }
        }
        let mesh = rows.last().unwrap();
        assert_eq!(mesh.series, "parry TriMesh");
        assert!(mesh.knob.starts_with("tess 1e-2"));
    }

    #[test]
    fn a_ray_along_no_box_meets_nothing() {
        let shape = teapot();
        let mut m = PatchLoop::new(&shape.patches, |p| Certified {
            model: p.clone(),
            knob: String::new(),
        });
        let away = Ray::new(Point3::new(0.0, 0.0, 50.0), Vector3::z());
        assert_eq!(m.nearest(&away, 0.0, 100.0), None);
        let down = Ray::new(Point3::new(0.1, 0.05, 50.0), -Vector3::z());
        let t = m.nearest(&down, 0.0, 100.0).expect("the lid");
        assert!(t > 45.0 && t < 48.0, "{t}");
    }

    #[test]
    fn the_teapot_has_32_bicubic_patches_that_join() {
        let pot = teapot().patches;
        assert_eq!(pot.len(), 32);
        assert!(pot.iter().all(|p| p.degrees() == (3, 3)));
        // The rim's first patch ends (v = 1) where its neighbour starts.
        let (a, b) = (&pot[0], &pot[1]);
        for u in [0.0, 0.3, 1.0] {
            assert!((a.eval(u, 1.0) - b.eval(u, 0.0)).norm() < 1e-12);
        }
    }
}

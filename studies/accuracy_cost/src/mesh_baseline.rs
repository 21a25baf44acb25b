//! What a user would otherwise do: tessellate, then ray-cast the triangles.

use crate::memory;
use crate::model::Method;
use parry3d_f64::math::Vector as PVector;
use parry3d_f64::query::{Ray as PRay, RayCast};
use parry3d_f64::shape::TriMesh;
use revolve::nalgebra::Point3;
use revolve::{BezierPatches, BezierSurface, Curve, Error, Ray, Revolution};
use std::time::Instant;

/// A surface of revolution tessellated with [`Revolution::tessellate`], or
/// Bézier patches with their `tessellate` (whose
/// [`Mesh::bound`](revolve::Mesh::bound) certifies the deviation), and
/// ray-cast as a parry [`TriMesh`] (f64, with its BVH), two-sided: the first
/// triangle crossing (`solid = false`).
pub struct MeshBaseline {
    /// `None` when the tessellation has no triangles (a profile on the
    /// axis): nothing to hit.
    mesh: Option<TriMesh>,
    bound: f64,
    tolerance: f64,
}

/// The cost of building a [`MeshBaseline`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshBuild {
    /// Wall-clock seconds: tessellation plus the `TriMesh` and its BVH.
    pub seconds: f64,
    /// Heap bytes the built baseline holds (see [`memory::held_by`]).
    pub bytes: usize,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// The mesh's certified deviation bound.
    pub bound: f64,
}

impl MeshBaseline {
    /// Tessellate `surface` to `tolerance` and build the TriMesh; report build
    /// time (tessellation + TriMesh with its BVH, wall clock) and heap bytes
    /// held (measured with [`memory::held_by`]: the tessellation's vertex
    /// normals and uvs are dropped, the positions are converted to parry's
    /// vectors and the index buffer moves into the `TriMesh`).
    ///
    /// # Errors
    /// Those of [`Revolution::tessellate`].
    pub fn build<C: Curve<2>>(
        surface: &Revolution<C>,
        tolerance: f64,
    ) -> Result<(Self, MeshBuild), Error> {
        Self::timed(|| {
            let mesh = surface.tessellate(tolerance)?;
            Ok(Self::assemble(
                &mesh.positions,
                mesh.triangles,
                mesh.bound,
                tolerance,
            ))
        })
    }

    /// Bézier patches tessellated to `tolerance`
    /// ([`BezierSurface::tessellate`], or [`BezierPatches::tessellate`] for
    /// several: welded along shared edges) as one `TriMesh`; build time and
    /// heap as for [`build`](Self::build).
    ///
    /// # Errors
    /// Those of the tessellation (and of [`BezierPatches::new`]).
    pub fn from_patches(
        patches: &[BezierSurface],
        tolerance: f64,
    ) -> Result<(Self, MeshBuild), Error> {
        Self::timed(|| {
            let mesh = match patches {
                [one] => one.tessellate(tolerance)?,
                many => BezierPatches::new(many.to_vec())?.tessellate(tolerance)?,
            };
            Ok(Self::assemble(
                &mesh.positions,
                mesh.triangles,
                mesh.bound,
                tolerance,
            ))
        })
    }

    /// The baseline of a mesh: positions converted to parry's vectors, the
    /// index buffer moved into the `TriMesh`.
    fn assemble(
        positions: &[Point3<f64>],
        triangles: Vec<[u32; 3]>,
        bound: f64,
        tolerance: f64,
    ) -> Self {
        let vertices: Vec<PVector> = positions
            .iter()
            .map(|p| PVector::new(p.x, p.y, p.z))
            .collect();
        // `TriMesh::new` fails only on an empty index buffer.
        let mesh = TriMesh::new(vertices, triangles).ok();
        MeshBaseline {
            mesh,
            bound,
            tolerance,
        }
    }

    /// Runs `make`, timing it and counting the heap the result holds.
    fn timed<E>(make: impl FnOnce() -> Result<Self, E>) -> Result<(Self, MeshBuild), E> {
        let start = Instant::now();
        let (built, bytes) = memory::held_by(make);
        let seconds = start.elapsed().as_secs_f64();
        let built = built?;
        let stats = MeshBuild {
            seconds,
            bytes,
            triangles: built.triangles(),
            bound: built.bound,
        };
        Ok((built, stats))
    }

    /// Triangles in the `TriMesh`.
    pub fn triangles(&self) -> usize {
        self.mesh.as_ref().map_or(0, TriMesh::num_triangles)
    }

    /// The mesh's certified deviation bound.
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn bound(&self) -> f64 {
        self.bound
    }
}

impl Method for MeshBaseline {
    fn series(&self) -> String {
        "parry TriMesh".to_string()
    }

    fn knob(&self) -> String {
        format!("tess {:.0e}, {} tris", self.tolerance, self.triangles())
    }

    /// The first triangle crossing with `t_min < t < t_max`, `t` along `dir`
    /// as given (parry's time of impact for the same direction vector). parry
    /// casts from its origin, so the ray starts at `origin + t_min·dir` when
    /// `t_min` is finite (at `origin` otherwise).
    fn nearest(&mut self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let mesh = self.mesh.as_ref()?;
        let base = if t_min.is_finite() { t_min } else { 0.0 };
        let o = ray.at(base);
        let d = ray.dir;
        let cast = PRay::new(PVector::new(o.x, o.y, o.z), PVector::new(d.x, d.y, d.z));
        let reach = (t_max - base).min(f64::MAX);
        let toi = mesh.cast_local_ray(&cast, reach, false)?;
        let t = base + toi;
        // Also rejects everything for an empty or NaN window.
        (t > t_min && t < t_max).then_some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::Rng;
    use revolve::Bezier;
    use revolve::nalgebra::{Point2, Point3, Vector3};
    use std::f64::consts::TAU;

    fn cylinder() -> Revolution<Bezier<2>> {
        Revolution::new(Bezier::new(vec![Point2::new(1.0, -1.0), Point2::new(1.0, 1.0)]).unwrap())
    }

    /// A horizontal ray from outside through the axis at angle `theta` and
    /// height `y`: it meets the tube at t = 2 and t = 4.
    fn through_axis(theta: f64, y: f64) -> Ray {
        let out = Vector3::new(theta.cos(), 0.0, -theta.sin());
        Ray::new(Point3::new(0.0, y, 0.0) + out * 3.0, -out)
    }

    #[test]
    fn hits_within_the_mesh_bound() {
        let (mut m, build) = MeshBaseline::build(&cylinder(), 1e-3).unwrap();
        assert!(build.bound <= 1e-3 && build.bound > 0.0);
        assert_eq!(m.series(), "parry TriMesh");
        assert_eq!(m.knob(), format!("tess 1e-3, {} tris", build.triangles));
        let mut rng = Rng(4);
        let mut worst: f64 = 0.0;
        for _ in 0..500 {
            let ray = through_axis(rng.range(0.0, TAU), rng.range(-0.95, 0.95));
            let t = m.nearest(&ray, 0.0, f64::INFINITY).expect("a hit");
            // The chords lie inside the tube: the hit is at or after t = 2.
            assert!(t >= 2.0 - 1e-12, "t = {t}");
            worst = worst.max((t - 2.0).abs());
        }
        assert!(
            worst <= build.bound * (1.0 + 1e-9) + 1e-12,
            "worst {worst:e} > bound {:e}",
            build.bound
        );
        // A non-unit direction: t is in units of |dir|.
        let r = through_axis(0.7, 0.3);
        let doubled = Ray::new(r.origin, r.dir * 2.0);
        let (a, b) = (
            m.nearest(&r, 0.0, f64::INFINITY).unwrap(),
            m.nearest(&doubled, 0.0, f64::INFINITY).unwrap(),
        );
        assert!((a - 2.0 * b).abs() < 1e-12, "{a} vs 2·{b}");
        // Above the tube: a miss.
        let above = Ray::new(Point3::new(-3.0, 1.5, 0.0), Vector3::x());
        assert_eq!(m.nearest(&above, 0.0, f64::INFINITY), None);
    }

    #[test]
    fn triangle_count_matches_the_tessellation() {
        let surface = cylinder();
        let (m, build) = MeshBaseline::build(&surface, 1e-3).unwrap();
        let mesh = surface.tessellate(1e-3).unwrap();
        assert_eq!(m.triangles(), mesh.triangles.len());
        assert_eq!(build.triangles, mesh.triangles.len());
        assert_eq!(build.bound, mesh.bound);
        assert_eq!(m.bound(), mesh.bound);
    }

    #[test]
    fn the_window_is_respected() {
        let (mut m, build) = MeshBaseline::build(&cylinder(), 1e-3).unwrap();
        let slack = 2.0 * build.bound + 1e-12;
        let ray = through_axis(1.3, 0.2);
        // Past the entry, the exit near t = 4.
        let t = m.nearest(&ray, 2.5, f64::INFINITY).unwrap();
        assert!((t - 4.0).abs() <= slack, "t = {t}");
        // Ending before the entry: nothing.
        assert_eq!(m.nearest(&ray, 0.0, 1.9), None);
        // Starting inside the tube, the next crossing; a negative t_min sees
        // the entry behind the origin.
        let inside = Ray::new(ray.at(3.0), ray.dir);
        let t = m.nearest(&inside, 0.0, f64::INFINITY).unwrap();
        assert!((t - 1.0).abs() <= slack, "t = {t}");
        let t = m.nearest(&inside, -5.0, f64::INFINITY).unwrap();
        assert!((t + 1.0).abs() <= slack, "t = {t}");
        assert_eq!(m.nearest(&ray, 3.0, 3.0), None);
    }

    #[test]
    fn memory_is_counted_and_grows_with_finer_tolerance() {
        assert!(
            memory::installed(),
            "HeapCounter is not the global allocator"
        );
        let surface = cylinder();
        let (_, coarse) = MeshBaseline::build(&surface, 1e-2).unwrap();
        let (_, fine) = MeshBaseline::build(&surface, 1e-4).unwrap();
        assert!(fine.triangles > coarse.triangles);
        assert!(coarse.bytes > 0);
        assert!(
            fine.bytes > coarse.bytes,
            "{} vs {}",
            fine.bytes,
            coarse.bytes
        );
        // At least the vertices (24 bytes) and indices (12 per triangle).
        assert!(fine.bytes >= 12 * fine.triangles, "{}", fine.bytes);
        assert!(fine.seconds > 0.0);
    }
}

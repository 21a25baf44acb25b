//! Triangle meshes with per-vertex normals and parameters, a certified
//! deviation bound, welding, and OBJ and STL output; shared by every
//! surface kind (`revolution/tessellate.rs`, `tensor/tessellate.rs` make
//! them).

use nalgebra::{Point3, Unit, Vector3};
use std::collections::HashMap;
use std::io::{self, Write};
use std::ops::Range;

/// A triangle mesh with per-vertex normals and surface parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Unit normals per vertex (the surface's orientation). A ring has one
    /// normal per vertex, the surface's (right-limit) normal; where the
    /// profile has a crease the triangles below it share those normals
    /// (known limitation: no split normals at creases).
    pub normals: Vec<Unit<Vector3<f64>>>,
    /// Surface parameters `(u, v)` per vertex.
    pub uvs: Vec<(f64, f64)>,
    /// Triangles as vertex indices `[a, b, c]`, ordered so that
    /// `(b − a) × (c − a)` points along the surface normal.
    pub triangles: Vec<[u32; 3]>,
    /// Every point of the surface lies within `bound` of the mesh.
    pub bound: f64,
}

impl Mesh {
    /// The most vertices [`Revolution::tessellate`](crate::Revolution::tessellate) and the tensor surfaces'
    /// `tessellate` make (`2²⁴`; with
    /// normals, parameters and about two triangles per vertex, about 1.4 GB);
    /// tolerances that would need more are refused.
    pub const MAX_VERTICES: usize = 1 << 24;

    /// Writes the mesh as Wavefront OBJ (`v`, `vt`, `vn` and `f v/vt/vn`
    /// lines; indices are 1-based). `vt` holds the surface parameters
    /// `(u, v)` as they are (not normalized to `[0, 1]`).
    pub fn write_obj(&self, out: &mut impl Write) -> io::Result<()> {
        writeln!(
            out,
            "# revolve mesh: {} vertices, {} triangles",
            self.positions.len(),
            self.triangles.len()
        )?;
        writeln!(out, "# deviation bound {:e}", self.bound)?;
        for p in &self.positions {
            writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
        }
        for (u, v) in &self.uvs {
            writeln!(out, "vt {u} {v}")?;
        }
        for n in &self.normals {
            writeln!(out, "vn {} {} {}", n.x, n.y, n.z)?;
        }
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| i + 1);
            writeln!(out, "f {a}/{a}/{a} {b}/{b}/{b} {c}/{c}/{c}")?;
        }
        Ok(())
    }

    /// The same mesh with the vertices of equal position merged into one
    /// (the first of them keeps its normal and parameters), and the
    /// triangles that merging collapses (two corners the same vertex) left
    /// out. A closed surface's mesh is then watertight: a revolution's seam
    /// `θ = 0 ≡ 2π` and its poles, whose vertices
    /// [`Revolution::tessellate`](crate::Revolution::tessellate) keeps apart
    /// so that `(u, θ)` stay continuous, become one vertex each. The bound
    /// is unchanged (no position moves).
    ///
    /// ```
    /// use revolve::nalgebra::Point2;
    /// use revolve::{Nurbs, Revolution};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// let sphere = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?);
    /// let mesh = sphere.tessellate(1e-2)?;
    /// let welded = mesh.welded();
    /// assert!(welded.positions.len() < mesh.positions.len());
    /// // Euler's formula for a closed mesh of genus 0: V − E + F = 2, E = 3F/2.
    /// let (v, f) = (welded.positions.len() as i64, welded.triangles.len() as i64);
    /// assert_eq!(2 * v - f, 4);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn welded(&self) -> Mesh {
        // Bit patterns of the coordinates, with −0 taken as +0.
        let key = |p: &Point3<f64>| p.coords.map(|c| (c + 0.0).to_bits());
        let mut first: HashMap<_, u32> = HashMap::with_capacity(self.positions.len());
        let mut keep = Vec::with_capacity(self.positions.len());
        let mut remap = Vec::with_capacity(self.positions.len());
        for (i, p) in self.positions.iter().enumerate() {
            let next = keep.len() as u32;
            let index = *first.entry(key(p)).or_insert(next);
            if index == next {
                keep.push(i);
            }
            remap.push(index);
        }
        Mesh {
            positions: keep.iter().map(|&i| self.positions[i]).collect(),
            normals: keep.iter().map(|&i| self.normals[i]).collect(),
            uvs: keep.iter().map(|&i| self.uvs[i]).collect(),
            triangles: self
                .triangles
                .iter()
                .map(|t| t.map(|i| remap[i as usize]))
                .filter(|[a, b, c]| a != b && b != c && a != c)
                .collect(),
            bound: self.bound,
        }
    }

    /// Turns the vertices `vertices` and the triangles `triangles` the other
    /// way round: their normals negated, each triangle `[a, b, c]` wound as
    /// `[a, c, b]` (so `(b − a) × (c − a)` follows the new normals). What a
    /// reversed surface's `tessellate` does to its mesh.
    pub(crate) fn reverse_orientation(&mut self, vertices: Range<usize>, triangles: Range<usize>) {
        for n in &mut self.normals[vertices] {
            *n = -*n;
        }
        for t in &mut self.triangles[triangles] {
            t.swap(1, 2);
        }
    }

    /// Writes the mesh as ASCII STL: one `facet` a triangle, its normal the
    /// unit `(b − a) × (c − a)` (zero for a triangle without area), then its
    /// three corners. STL has no shared vertices, normals per vertex or
    /// parameters; weld first ([`welded`](Self::welded)) for a watertight
    /// solid.
    pub fn write_stl(&self, out: &mut impl Write) -> io::Result<()> {
        writeln!(out, "solid revolve")?;
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.positions[i as usize]);
            let n = (b - a).cross(&(c - a));
            let n = n.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
            writeln!(out, "  facet normal {} {} {}", n.x, n.y, n.z)?;
            writeln!(out, "    outer loop")?;
            for p in [a, b, c] {
                writeln!(out, "      vertex {} {} {}", p.x, p.y, p.z)?;
            }
            writeln!(out, "    endloop")?;
            writeln!(out, "  endfacet")?;
        }
        writeln!(out, "endsolid revolve")
    }
}

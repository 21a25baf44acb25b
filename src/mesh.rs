//! Triangle meshes with per-vertex normals and parameters, a certified
//! deviation bound, and OBJ output; shared by every surface kind
//! (`revolution/tessellate.rs`, `tensor/tessellate.rs` make them).

use nalgebra::{Point3, Unit, Vector3};
use std::io::{self, Write};

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
}

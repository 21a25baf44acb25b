//! Emissive objects sampled uniformly by world area, for next-event
//! estimation.
//!
//! Under an affine map `p ↦ L·p + c` areas on a plane scale by a constant,
//! `|L·e1 × L·e2|` for an orthonormal pair `(e1, e2)` spanning it, so a
//! uniform sample of a flat piece in the object frame maps to a uniform
//! sample of its image, and the world area of a parallelogram or triangle is
//! that of its mapped edge vectors (exact for any non-singular `L`).
//!
//! - Rectangle: one parallelogram. Box: its six faces, chosen with
//!   probability proportional to their world areas. Triangle and mesh: their
//!   (valid) triangles, chosen likewise. Within a triangle
//!   `p = v0 + √a(1 − b)·e1 + √a·b·e2` (uniform by area).
//! - Disk and ring: polar sampling `ρ = √(r_in² + a(r_out² − r_in²))`,
//!   `φ = 2πb`, mapped to the world (the image of a disk under `L` is an
//!   ellipse; the map keeps uniformity).
//! - Sphere: `z = 1 − 2a`, `φ = 2πb` on the unit sphere (Archimedes: uniform
//!   by area). Only when the transform is a similarity (`L = s·R`): the image
//!   of a sphere under a general `L` is an ellipsoid, whose area has no closed
//!   form and which the map would not sample uniformly, so such a sphere is
//!   **not** an emitter (it still glows where rays hit it).
//! - Plane (infinite), revolution bodies and tubes are not sampled either.
//!
//! Choosing a piece by `a` reuses `a`: the position of `a·total` inside the
//! chosen piece's share of the cumulative areas, rescaled to `[0, 1]`, is
//! again uniform. Normals are oriented as `SurfaceHit::normal` (outward for
//! spheres and boxes, the winding or given normal for flat shapes: object
//! normals mapped by `L⁻ᵀ`, so a reflecting `L` keeps their orientation).

use std::f64::consts::{PI, TAU};

use revolve::nalgebra::{Point3, Unit, Vector3};

use super::shapes::{Triangle, basis};
use super::transform::Frame;
use crate::scene::Shape;

/// An object whose material emits light, sampled uniformly by area for
/// next-event estimation (rectangles, disks, rings, spheres, triangles,
/// meshes and boxes; see the module docs for the rules). Other emissive
/// shapes only light what their rays happen to hit.
#[derive(Debug, Clone)]
pub struct Emitter {
    /// Index into `Scene::objects`.
    pub object: usize,
    area: f64,
    kind: Kind,
}

#[derive(Debug, Clone)]
enum Kind {
    /// Parallelograms and triangles, with the cumulative world areas.
    Flat {
        pieces: Vec<Flat>,
        cdf: Vec<f64>,
    },
    /// A disk or ring mapped to the world: `center + ρ(cos φ·w1 + sin φ·w2)`.
    Annulus {
        center: Point3<f64>,
        w1: Vector3<f64>,
        w2: Vector3<f64>,
        inner: f64,
        outer: f64,
        normal: Unit<Vector3<f64>>,
    },
    Sphere {
        center: Point3<f64>,
        radius: f64,
    },
}

/// A world parallelogram `origin + a·e1 + b·e2` or triangle.
#[derive(Debug, Clone)]
struct Flat {
    origin: Point3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    normal: Unit<Vector3<f64>>,
    triangle: bool,
}

impl Flat {
    /// The object-frame piece `origin, e1, e2` with normal `n`, in the
    /// world; `None` if it has no area there.
    fn new(
        frame: Option<&Frame>,
        origin: Point3<f64>,
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        n: Vector3<f64>,
        triangle: bool,
    ) -> Option<Flat> {
        let (origin, e1, e2, n) = match frame {
            Some(f) => (f.point(&origin), f.vector(&e1), f.vector(&e2), f.normal(&n)),
            None => (origin, e1, e2, n),
        };
        let flat = Flat {
            origin,
            e1,
            e2,
            normal: Unit::try_new(n, 0.0)?,
            triangle,
        };
        let area = flat.area();
        (area > 0.0 && area.is_finite()).then_some(flat)
    }

    fn area(&self) -> f64 {
        let a = self.e1.cross(&self.e2).norm();
        if self.triangle { 0.5 * a } else { a }
    }

    fn sample(&self, a: f64, b: f64) -> Point3<f64> {
        if self.triangle {
            let s = a.sqrt();
            self.origin + self.e1 * (s * (1.0 - b)) + self.e2 * (s * b)
        } else {
            self.origin + self.e1 * a + self.e2 * b
        }
    }
}

impl Emitter {
    /// The emitter for `shape` placed by `frame`; `None` for shapes that are
    /// not sampled or have no area.
    pub(super) fn new(object: usize, shape: &Shape, frame: Option<&Frame>) -> Option<Emitter> {
        let kind = match shape {
            Shape::Rectangle {
                corner,
                edge1,
                edge2,
            } => flat(vec![Flat::new(
                frame,
                *corner,
                *edge1,
                *edge2,
                edge1.cross(edge2),
                false,
            )?])?,
            Shape::Box { min, max } => {
                let (lo, hi) = (min.inf(max), min.sup(max));
                let ext = hi - lo;
                let mut faces = Vec::with_capacity(6);
                for k in 0..3 {
                    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                    let mut ei = Vector3::zeros();
                    ei[i] = ext[i];
                    let mut ej = Vector3::zeros();
                    ej[j] = ext[j];
                    let mut n = Vector3::zeros();
                    n[k] = 1.0;
                    let mut top = lo;
                    top[k] = hi[k];
                    faces.extend(Flat::new(frame, lo, ei, ej, -n, false));
                    faces.extend(Flat::new(frame, top, ei, ej, n, false));
                }
                flat(faces)?
            }
            Shape::Triangle { vertices } => flat(triangle(frame, vertices).into_iter().collect())?,
            Shape::Mesh(mesh) => flat(
                mesh.triangles
                    .iter()
                    .filter_map(|t| {
                        let v = |k: usize| mesh.vertices.get(t[k] as usize).copied();
                        triangle(frame, &[v(0)?, v(1)?, v(2)?])
                    })
                    .collect(),
            )?,
            Shape::Disk {
                center,
                normal,
                radius,
            } => annulus(frame, center, normal, 0.0, *radius)?,
            Shape::Ring {
                center,
                normal,
                inner,
                outer,
            } => annulus(frame, center, normal, *inner, *outer)?,
            Shape::Sphere { center, radius } => {
                let (center, scale) = match frame {
                    Some(f) => (f.point(center), f.similarity_scale()?),
                    None => (*center, 1.0),
                };
                let radius = radius * scale;
                if !(radius > 0.0 && radius.is_finite()) {
                    return None;
                }
                Kind::Sphere { center, radius }
            }
            Shape::Plane { .. } | Shape::Revolution(_) | Shape::Tube(_) | Shape::Surface(_) => {
                return None;
            }
        };
        let area = match &kind {
            Kind::Flat { cdf, .. } => *cdf.last()?,
            Kind::Annulus {
                w1,
                w2,
                inner,
                outer,
                ..
            } => PI * (outer * outer - inner * inner) * w1.cross(w2).norm(),
            Kind::Sphere { radius, .. } => 4.0 * PI * radius * radius,
        };
        (area > 0.0 && area.is_finite()).then_some(Emitter { object, area, kind })
    }

    /// World-space area.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The point for `(a, b) ∈ [0, 1)²` (uniform by area) and its unit
    /// normal there (oriented as `SurfaceHit::normal`).
    pub fn sample(&self, a: f64, b: f64) -> (Point3<f64>, Unit<Vector3<f64>>) {
        let (a, b) = (a.clamp(0.0, 1.0), b.clamp(0.0, 1.0));
        match &self.kind {
            Kind::Flat { pieces, cdf } => {
                let target = a * self.area;
                let k = cdf.partition_point(|&c| c <= target).min(pieces.len() - 1);
                let lo = if k == 0 { 0.0 } else { cdf[k - 1] };
                let a = ((target - lo) / (cdf[k] - lo)).clamp(0.0, 1.0);
                (pieces[k].sample(a, b), pieces[k].normal)
            }
            Kind::Annulus {
                center,
                w1,
                w2,
                inner,
                outer,
                normal,
            } => {
                let rho = (inner * inner + a * (outer * outer - inner * inner)).sqrt();
                let (s, c) = (TAU * b).sin_cos();
                (center + (w1 * c + w2 * s) * rho, *normal)
            }
            Kind::Sphere { center, radius } => {
                let z = 1.0 - 2.0 * a;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (s, c) = (TAU * b).sin_cos();
                let n = Vector3::new(r * c, r * s, z);
                (center + n * *radius, Unit::new_unchecked(n))
            }
        }
    }
}

/// The flat kind with its cumulative areas; `None` for no pieces.
fn flat(pieces: Vec<Flat>) -> Option<Kind> {
    if pieces.is_empty() {
        return None;
    }
    let cdf = pieces
        .iter()
        .scan(0.0, |acc, p| {
            *acc += p.area();
            Some(*acc)
        })
        .collect();
    Some(Kind::Flat { pieces, cdf })
}

/// A valid triangle in the world.
fn triangle(frame: Option<&Frame>, v: &[Point3<f64>; 3]) -> Option<Flat> {
    let t = Triangle::new(*v)?;
    let (v0, e1, e2) = t.parts();
    Flat::new(frame, v0, e1, e2, t.normal(), true)
}

/// A disk or ring in the world (same validity rules as the shape).
fn annulus(
    frame: Option<&Frame>,
    center: &Point3<f64>,
    normal: &Vector3<f64>,
    inner: f64,
    outer: f64,
) -> Option<Kind> {
    let (inner, outer) = (inner.min(outer).max(0.0), inner.max(outer));
    let n = normal.try_normalize(0.0)?;
    if !(outer > 0.0 && outer.is_finite()) {
        return None;
    }
    let (e1, e2) = basis(&n);
    let (center, w1, w2, n) = match frame {
        Some(f) => (f.point(center), f.vector(&e1), f.vector(&e2), f.normal(&n)),
        None => (*center, e1, e2, n),
    };
    Some(Kind::Annulus {
        center,
        w1,
        w2,
        inner,
        outer,
        normal: Unit::try_new(n, 0.0)?,
    })
}

//! Triangle meshes of a surface of revolution with a certified deviation
//! bound.
//!
//! The profile is flattened adaptively ([`Flattening`](crate::Flattening)) so
//! that each profile piece lies within `ε_p` of its chord, and the angle is cut
//! into `N` equal steps so that a circle of the largest radius `R` lies within
//! its sagitta `R(1 − cos(π/N)) = 2R sin²(π/2N)` of its chords. Between two profile samples and
//! two angles the surface patch lies within `ε_p` of the patch swept by the
//! chord (a piece of a cone), and that piece of cone lies within the sagitta
//! of the planar isosceles trapezoid through its four corners, which the mesh
//! covers with two triangles. So every surface point is within
//!
//! `bound = ε_p + R(1 − cos(π/N))`
//!
//! of the mesh; the tolerance is split evenly between the two terms.

use super::surface::profile_normal;
use crate::allocation::try_with_capacity;
use crate::curve::{Homogeneous, MIN_RELATIVE_TOLERANCE, flatten_controls, flatten_pieces};
use crate::{Curve, Error, Mesh, Revolution};
use nalgebra::{Point3, Unit, Vector3};
use std::f64::consts::{PI, TAU};

/// What [`Revolution::tessellate`] decided: the profile rings, the angular
/// steps and the sagitta they leave.
struct Plan {
    flat: crate::Flattening<2>,
    steps: usize,
    sagitta: f64,
}

impl<C: Curve<2>> Revolution<C> {
    /// A triangle mesh within `tolerance` of the surface (see the module
    /// docs for the bound, which the mesh reports in [`Mesh::bound`]). On a
    /// [reversed](Self::reversed) surface the same mesh with its normals
    /// negated and its triangles wound the other way.
    ///
    /// Vertices on the axis (poles) are shared by their ring; triangles that
    /// collapse there are left out. The seam `θ = 0 ≡ 2π` has duplicate
    /// vertices so that `(u, v)` stay continuous; [`Mesh::welded`] merges
    /// them and each pole's ring into one vertex, for a watertight mesh.
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`]; [`Error::ToleranceTooSmall`] below what
    /// flattening certifies (for half the tolerance);
    /// [`Error::MeshTooLarge`] where the mesh would
    /// exceed 2²⁴ vertices (its `min` is a tolerance that fits, see
    /// [`Mesh::MAX_VERTICES`]);
    /// [`Error::NotPiecewisePolynomial`] for a profile without usable
    /// [(rational) Bézier spans](Curve::rational_bezier_spans) (none, so no certified bound is
    /// possible, or spans that give samples with a NaN or infinite value);
    /// [`Error::AllocationFailed`] if the memory for the mesh cannot be had.
    pub fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        let Plan {
            flat,
            steps,
            sagitta,
        } = match self.plan(tolerance) {
            Ok(plan) => plan,
            Err(Error::ToleranceTooSmall { min, .. }) => {
                // Where even the precision floor gives too many vertices, the
                // vertex cap is what the caller must respect.
                let usable = self.usable_minimum(min)?;
                return Err(match self.plan(min) {
                    Err(Error::MeshTooLarge { vertices, max, .. }) => Error::MeshTooLarge {
                        tolerance,
                        vertices,
                        max,
                        min: usable,
                    },
                    _ => Error::ToleranceTooSmall {
                        tolerance,
                        min: usable,
                    },
                });
            }
            Err(Error::MeshTooLarge {
                vertices, max, min, ..
            }) => {
                return Err(Error::MeshTooLarge {
                    tolerance,
                    vertices,
                    max,
                    min: self.usable_minimum(min)?,
                });
            }
            Err(e) => return Err(e),
        };
        let columns = steps + 1;
        let rings = flat.samples.len();
        let vertices = rings * columns;
        let mut mesh = Mesh {
            positions: try_with_capacity(vertices)?,
            normals: try_with_capacity(vertices)?,
            uvs: try_with_capacity(vertices)?,
            triangles: try_with_capacity(2 * rings.saturating_sub(1) * steps)?,
            bound: flat.bound + sagitta,
        };
        let up = Unit::new_unchecked(self.to_world().rotation * Vector3::y());
        for (i, sample) in flat.samples.iter().enumerate() {
            // The ring comes from the sample itself, so a jump's left-limit
            // sample makes its own ring (evaluating at its t would give the
            // right limit).
            let (x, y) = (sample.point.x, sample.point.y);
            let tangent =
                Unit::try_new(sample.derivative, 0.0).or_else(|| self.profile().tangent(sample.t));
            let arriving = flat
                .samples
                .get(i + 1)
                .is_none_or(|next| next.t == sample.t);
            let first = mesh.positions.len();
            for j in 0..steps {
                let theta = TAU * j as f64 / steps as f64;
                let (sn, cs) = theta.sin_cos();
                mesh.positions
                    .push(self.to_world() * Point3::new(x * cs, y, -x * sn));
                let n = tangent
                    .and_then(|t| profile_normal(x, t, arriving, (sn, cs)))
                    .map(|n| Unit::new_unchecked(self.to_world().rotation * n.into_inner()))
                    // No tangent plane (an apex): the axis direction is the
                    // best vertex normal there.
                    .unwrap_or(up);
                mesh.normals.push(n);
                mesh.uvs.push((sample.t, theta));
            }
            // The seam: θ = 2π repeats θ = 0 exactly.
            mesh.positions.push(mesh.positions[first]);
            mesh.normals.push(mesh.normals[first]);
            mesh.uvs.push((sample.t, TAU));
        }
        let index = |i: usize, j: usize| (i * columns + j) as u32;
        for i in 0..rings - 1 {
            let lower_on_axis = flat.samples[i].point.x == 0.0;
            let upper_on_axis = flat.samples[i + 1].point.x == 0.0;
            for j in 0..steps {
                let (a, b) = (index(i, j), index(i, j + 1));
                let (c, d) = (index(i + 1, j), index(i + 1, j + 1));
                // Orientation: (∂S/∂u) × (∂S/∂θ) is the normal, so a triangle
                // (u, θ) → (u + du, θ) → (u, θ + dθ) follows it.
                if !lower_on_axis {
                    mesh.triangles.push([a, c, b]);
                }
                if !upper_on_axis {
                    mesh.triangles.push([b, c, d]);
                }
            }
        }
        if self.reversed {
            mesh.reverse_orientation(0..mesh.normals.len(), 0..mesh.triangles.len());
        }
        Ok(mesh)
    }
    /// The profile samples and angular steps for `tolerance`, with the
    /// bound; `ToleranceTooSmall` or `MeshTooLarge` (with a `min` for this
    /// check) if a limit is exceeded.
    fn plan(&self, tolerance: f64) -> Result<Plan, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidTolerance { tolerance });
        }
        if let Some(broken) = self.contract_error() {
            return Err(broken.clone());
        }
        let spans = self
            .profile()
            .rational_bezier_spans()
            .ok_or(Error::NotPiecewisePolynomial)?;
        let scale = spans
            .iter()
            .flat_map(|s| s.curve.points())
            .fold(0.0_f64, |m, p| m.max(p.coords.amax()));
        let r_max = spans
            .iter()
            .flat_map(|s| s.curve.points())
            .fold(0.0_f64, |m, p| m.max(p.x.abs()));
        // Flattening's floor (for half the tolerance); the angular steps
        // have none of their own, only the vertex cap below.
        let min = 2.0 * MIN_RELATIVE_TOLERANCE * scale;
        if tolerance < min {
            return Err(Error::ToleranceTooSmall { tolerance, min });
        }
        let flat = if spans.iter().all(|s| s.curve.is_polynomial()) {
            flatten_pieces(
                self.profile(),
                spans.iter().map(|s| (s.curve.points(), s.knots)),
                0.5 * tolerance,
            )?
        } else {
            // Rational pieces are flattened from their homogeneous points,
            // with the bound that holds for them (see `Flattening`).
            let homogeneous: Vec<Vec<Homogeneous<2>>> = spans
                .iter()
                .map(|s| {
                    let c = &s.curve;
                    c.points()
                        .iter()
                        .zip(c.weights())
                        .map(|(p, &w)| Homogeneous::new(p, w))
                        .collect()
                })
                .collect();
            flatten_controls(
                self.profile(),
                homogeneous
                    .iter()
                    .zip(&spans)
                    .map(|(h, s)| (&h[..], s.knots)),
                |h| *h,
                0.5 * tolerance,
            )?
        };
        // Spans that pass the contract check but still sample to non-finite
        // values must not become NaN vertices.
        let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
        let usable = flat.samples.iter().all(|s| {
            s.t.is_finite() && finite(s.point.coords.as_slice()) && finite(s.derivative.as_slice())
        });
        if !usable {
            return Err(Error::NotPiecewisePolynomial);
        }
        // Smallest N with 2R sin²(π/2N) ≤ tolerance/2 (no cancellation, so
        // also for the tiniest tolerances).
        let steps = if r_max == 0.0 {
            3.0
        } else {
            let half = 2.0 * (0.25 * tolerance / r_max).sqrt().min(1.0).asin();
            (PI / half).ceil().max(3.0)
        };
        let rings = flat.samples.len();
        // The vertex count grows like 1/tolerance; refuse meshes beyond the
        // budget with the tolerance that would fit it.
        let vertices = rings as f64 * (steps + 1.0);
        if vertices > Mesh::MAX_VERTICES as f64 {
            return Err(Error::MeshTooLarge {
                tolerance,
                vertices,
                max: Mesh::MAX_VERTICES,
                min: tolerance * vertices / Mesh::MAX_VERTICES as f64 * 1.25,
            });
        }
        let steps = steps as usize;
        let sagitta = 2.0 * r_max * (0.5 * PI / steps as f64).sin().powi(2);
        Ok(Plan {
            flat,
            steps,
            sagitta,
        })
    }

    /// A tolerance that passes every check, starting from the `min` one
    /// check reported (each check's minimum can trip the next one).
    fn usable_minimum(&self, mut min: f64) -> Result<f64, Error> {
        for _ in 0..4 {
            match self.plan(min) {
                Ok(_) => return Ok(min),
                Err(
                    Error::ToleranceTooSmall { min: next, .. }
                    | Error::MeshTooLarge { min: next, .. },
                ) => min = next.max(1.5 * min),
                Err(e) => return Err(e),
            }
        }
        Ok(min)
    }
}

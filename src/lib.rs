//! # revolve
//!
//! Spline curves and surfaces — surfaces of revolution and tensor-product
//! Bézier, B-spline and NURBS surfaces — with certified ray intersection.
//!
//! The curve layer:
//!
//! - [`Bezier`] curves of any degree and dimension, evaluated by de Casteljau's
//!   algorithm, with derivatives of any order, subdivision and bounds;
//! - [`BSpline`] curves of any degree and dimension (de Boor evaluation,
//!   Cox–de Boor basis values and derivatives, derivative splines, knot
//!   insertion, conversion to Bézier spans), with uniform knots `i/(n + k)`
//!   (the convention of the classic course ray-tracing framework, whose
//!   assignments discretize Bézier and B-spline curves into surfaces of
//!   revolution and whose scene files the ray caster reads) and clamped
//!   knots;
//! - [`Nurbs`] rational B-splines (evaluation in homogeneous coordinates,
//!   derivatives of any order by the quotient rule, knot insertion,
//!   rational Bézier spans), with exact circles and arcs
//!   ([`Nurbs::circle`], [`Nurbs::arc`]);
//! - the [`Curve`] trait they share, usable for your own curve types, with
//!   uniform sampling ([`Curve::discretize`]) and adaptive flattening to a
//!   guaranteed tolerance ([`Bezier::flatten`], [`BSpline::flatten`]);
//! - the Bernstein-basis kernels in [`bernstein`] and root isolation in
//!   [`roots`].
//!
//! Surfaces and rays:
//!
//! - the [`Surface`] trait (point, analytic partials, normal) and
//!   [`PatchBounds`] (a box around any parameter rectangle);
//! - [`Revolution`]: a 2D profile turned about an axis placed anywhere, with
//!   limit normals on the axis, tessellated with a certified bound
//!   ([`Mesh`]); any [`Curve`] can be the profile ([`Revolution::try_new`]
//!   checks the trait's contract);
//! - tensor-product surfaces: [`BezierSurface`], [`BSplineSurface`] and
//!   [`NurbsSurface`] (conversion to Bézier patches, knot insertion, limit
//!   normals at collapsed edges), and [`BezierPatches`], a model made of
//!   many Bézier patches (Newell's teapot) behind a bounding-volume
//!   hierarchy;
//! - [`Intersect`]: the nearest hit of a [`Ray`], one ray or many
//!   ([`Intersect::intersect_batch`]). Certified for revolutions with
//!   polynomial or rational Bézier spans (the angle eliminated, one
//!   polynomial per span, every root isolated; exact spheres and tori from
//!   NURBS arcs) and for the tensor surfaces (Bézier clipping with
//!   Krawczyk's uniqueness test, finished by Newton's method): no
//!   transversal hit missed, none false. Profiles without spans use a cubic
//!   approximation refined on the profile; [`NewtonIntersector`] runs
//!   Newton's method on `(t, u, v)` for any [`PatchBounds`] surface.
//!   Accuracy is a [`Tolerance`];
//! - nearest points: `nearest_point` on every surface kind
//!   ([`Revolution::nearest_point`], [`BezierSurface::nearest_point`],
//!   [`BSplineSurface::nearest_point`], [`NurbsSurface::nearest_point`],
//!   [`BezierPatches::nearest_point`]) gives a [`SurfaceNearest`], the
//!   global minimum of the distance over the whole domain, certified where
//!   the surface has polynomial or rational pieces (a revolution through its
//!   profile's certified nearest point, the tensor kinds by a branch and
//!   bound over Bézier pieces with a second-order bound);
//! - intersections of curves: [`curve::intersect_curves`] (two planar
//!   curves) and `intersect_curve` on the tensor kinds
//!   ([`BezierSurface::intersect_curve`] and the others: a space curve and a
//!   surface), every common point by subdivision with separating-direction
//!   tests and Krawczyk's test, polished by Newton's method: none missed,
//!   transversal crossings certified, tangencies reported once as
//!   uncertified, overlaps an error;
//! - [`Bvh`]: a bounding-volume hierarchy over boxed items (binned surface
//!   area heuristic, nearest-first traversal, [`Walk`] for rays side by
//!   side), the one the patch search uses and the ray caster builds its
//!   world, meshes and tubes on.
//!
//! Where the code is: [`curve`] (one file per curve type), [`bernstein`] and
//! [`roots`] (the kernels), [`ray`] (what every intersector shares: rays,
//! hits, the acceptance rule, the hierarchy, generic Newton), [`revolution`]
//! and [`tensor`] (each surface kind with its intersector and
//! tessellation).
//!
//! Features:
//!
//! - `testing`: proptest strategies and law checkers for your own curves
//!   and surfaces;
//! - `serde`: `Serialize` and `Deserialize` for the curves, the surfaces,
//!   [`Ray`], [`Tolerance`] and [`Aabb`], written as their defining data
//!   (intersector tables are rebuilt when read) and read back through the
//!   public constructors, so that bad data is an error with the crate's
//!   [`Error`] message and a deserialized value is as valid as a
//!   constructed one.
//!
//! Bad input is an [`Error`] value, never a panic; evaluation never returns
//! NaN (parameters are moved into the domain, see [`Curve`]). Evaluation does
//! not allocate for degrees up to 16.
//!
//! ```
//! use revolve::{BSpline, Bezier, Curve};
//! use revolve::nalgebra::{Point2, Vector2};
//!
//! // A cubic Bézier and the clamped cubic B-spline on the same points are the same curve.
//! let pts = vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0)];
//! let bezier = Bezier::new(pts.clone())?;
//! let spline = BSpline::clamped(3, pts)?;
//! for s in spline.discretize(8) {
//!     assert!((s.point - bezier.eval(s.t)).norm() < 1e-14);
//!     assert!((s.derivative - bezier.derivative(s.t)).norm() < 1e-13);
//! }
//! // Derivatives at the ends follow the control polygon: 3·(P1 − P0).
//! assert_eq!(bezier.derivative(0.0), Vector2::new(3.0, 6.0));
//!
//! // Flattening certifies its deviation from the curve.
//! let flat = bezier.flatten(1e-4)?;
//! assert!(flat.bound <= 1e-4);
//!
//! // Bad input is an error that names the problem.
//! let err = BSpline::<2>::uniform(4, vec![Point2::origin(); 3]).unwrap_err();
//! assert_eq!(err.to_string(), "degree 4 needs at least 5 control points, got 3");
//! # Ok::<(), revolve::Error>(())
//! ```

#![deny(missing_docs)]
#![forbid(unsafe_code)]
#![warn(clippy::all, rust_2018_idioms)]

pub use nalgebra;

mod aabb;
mod allocation;
pub mod bernstein;
pub mod curve;
mod error;
mod limits;
mod mesh;
pub mod prelude;
pub mod ray;
pub mod revolution;
mod revolution_to_nurbs;
pub mod roots;
mod scratch;
#[cfg(feature = "serde")]
mod serde_impls;
mod surface;
mod surface_nearest;
pub mod tensor;
#[cfg(test)]
mod test_unit;
#[cfg(feature = "testing")]
pub mod testing;

pub use aabb::Aabb;
pub use curve::{
    ArcLength, BSpline, Bezier, BezierSpan, Curve, CurveProjector, CurveSample, Flattening,
    FrenetFrame, MAX_DERIVATIVE, MAX_SEGMENTS, NearestPoint, Nurbs, RationalBezier,
    RationalBezierSpan,
};
pub use error::{Error, ParameterDirection};
pub use limits::MAX_COORDINATE;
pub use mesh::Mesh;
pub use ray::bvh::{BoxRay, Bvh, Walk};
pub use ray::newton::{NewtonFinish, NewtonIntersector, NewtonReport, NewtonRun};
pub use ray::{Hit, Intersect, Ray, Tolerance};
pub use revolution::{ExactReport, Revolution};
pub use surface::{PatchBounds, Surface};
pub use surface_nearest::SurfaceNearest;
pub use tensor::{
    BSplineSurface, BezierPatch, BezierPatches, BezierSurface, NurbsSurface, RationalBezierPatch,
};

/// The former name of [`PatchBounds`], kept so that code written against it
/// still compiles.
pub use surface::PatchBounds as BoundedSurface;

/// The README's code blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

//! # revolve
//!
//! Spline curves and surfaces of revolution with exact, robust ray
//! intersection.
//!
//! The curve layer:
//!
//! - [`Bezier`] curves of any degree and dimension, evaluated by de Casteljau's
//!   algorithm, with derivatives of any order, subdivision and bounds;
//! - [`BSpline`] curves of any degree and dimension (de Boor evaluation,
//!   Cox–de Boor basis values and derivatives, derivative splines, knot
//!   insertion, conversion to Bézier spans), including the course framework's
//!   uniform knots and clamped knots;
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
//! - [`Revolution`]: a profile turned about an axis ([`Surface`], with
//!   analytic partials and limit normals on the axis), placeable anywhere,
//!   tessellated with a certified bound ([`Mesh`]); any [`Curve`] can be the
//!   profile ([`Revolution::try_new`] checks the trait's contract);
//! - [`Intersect`] for revolutions: the exact intersector (the angle
//!   eliminated, one polynomial per profile span, every root isolated) for
//!   profiles with polynomial or rational Bézier spans (exact spheres and
//!   tori from NURBS arcs), the same on a cubic approximation refined
//!   by Newton's method for other profiles, and [`NewtonIntersector`] for
//!   any [`PatchBounds`]; accuracy is a [`Tolerance`];
//! - feature `testing`: proptest strategies and law checkers for your own
//!   curves and surfaces;
//! - feature `serde`: `Serialize` and `Deserialize` for the curves, the
//!   surfaces, [`Ray`], [`Tolerance`] and [`Aabb`], written as their
//!   defining data (a revolution's intersector tables are rebuilt when it is
//!   read) and read back through the public constructors, so that bad data
//!   is an error with the crate's [`Error`] message and a deserialized value
//!   is as valid as a constructed one.
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
pub mod ray;
pub mod revolution;
pub mod roots;
mod scratch;
#[cfg(feature = "serde")]
mod serde_impls;
mod surface;
pub mod tensor;
#[cfg(feature = "testing")]
pub mod testing;

pub use aabb::Aabb;
pub use curve::{
    ArcLength, BSpline, Bezier, BezierSpan, Curve, CurveProjector, CurveSample, Flattening,
    MAX_DERIVATIVE, MAX_SEGMENTS, NearestPoint, Nurbs, RationalBezier, RationalBezierSpan,
};
pub use error::Error;
pub use limits::MAX_COORDINATE;
pub use mesh::Mesh;
pub use ray::newton::{NewtonFinish, NewtonIntersector, NewtonReport, NewtonRun};
pub use ray::{Hit, Intersect, Ray, Tolerance};
pub use revolution::{ExactReport, Revolution};
pub use surface::{PatchBounds, Surface};
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

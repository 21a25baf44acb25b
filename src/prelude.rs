//! The traits and types most programs use, in one import:
//! `use revolve::prelude::*;`.
//!
//! The traits ([`Curve`], [`Surface`], [`Intersect`], [`PatchBounds`]) are
//! what make the methods callable (`bounds`, `intersect`, `eval` on a
//! surface); the curve and surface kinds, rays, hits, meshes and errors come
//! with them, and nalgebra's point and vector types the constructors take.
//!
//! ```
//! use revolve::prelude::*;
//!
//! let sphere = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -1.5707963267948966, 1.5707963267948966)?);
//! let hit = sphere
//!     .intersect(&Ray::new(Point3::new(0.0, 0.0, 5.0), -Vector3::z()), 0.0, f64::INFINITY)
//!     .expect("the ray is aimed at the sphere");
//! assert!((hit.t - 4.0).abs() < 1e-12);
//! assert_eq!(sphere.bounds().max, Point3::new(1.0, 1.0, 1.0));
//! # Ok::<(), Error>(())
//! ```

pub use crate::nalgebra::{Point2, Point3, Unit, Vector2, Vector3};
pub use crate::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierPatches, BezierSurface, Curve, Error, Hit,
    Intersect, Mesh, NewtonIntersector, Nurbs, NurbsSurface, PatchBounds, RationalBezier, Ray,
    Revolution, Surface, SurfaceNearest, Tolerance,
};

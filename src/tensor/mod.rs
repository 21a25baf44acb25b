//! Tensor-product surfaces: [`BezierSurface`], [`BSplineSurface`],
//! [`NurbsSurface`] and models made of many Bézier patches
//! ([`BezierPatches`]), with the certified patch search and their
//! tessellation.
//!
//! Every kind is held as a table of homogeneous Bézier patches
//! (`patch_table.rs`); evaluation, bounds, the ray search (`search.rs`)
//! and tessellation all work on that table.

mod bezier_patches;
mod bezier_surface;
mod bspline_surface;
mod clip;
mod control_net;
mod curve_intersection;
mod distance_bound;
mod grid_constructors;
mod interpolate_surface;
mod isocurve;
mod krawczyk;
mod loft;
mod nearest;
mod nearest_newton;
mod newton_polish;
mod nurbs_surface;
mod patch;
mod patch_table;
mod projection_certificate;
mod ruled;
mod search;
mod search_pieces;
mod surface_intersection;
mod surface_split;
mod surface_transform;
mod sweep;
mod tessellate;

pub use bezier_patches::BezierPatches;
pub use bezier_surface::BezierSurface;
pub use bspline_surface::{BSplineSurface, BezierPatch};
pub use curve_intersection::CurveSurfaceHit;
pub use nurbs_surface::{NurbsSurface, RationalBezierPatch};
pub use surface_intersection::{SurfaceIntersectionCurve, SurfaceIntersectionPoint};

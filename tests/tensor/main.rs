//! Integration tests of tensor-product surfaces (Bézier, B-spline and NURBS
//! surfaces, `BezierPatches` models): evaluation against closed forms and an
//! independent evaluator, the certified ray–patch intersector against closed
//! forms and an independent reference (`revolve_testkit::patch_reference`),
//! its hard cases, nearest points (against closed forms and refined dense
//! samples), and tessellation.
//!
//! One module per subject; each module's docs state its references and
//! tolerances.

mod bezier_patches;
mod constructions;
mod constructions_surfaces;
mod curve_surface;
mod nearest;
mod patch_hard_cases;
mod patch_intersect;
mod patch_mesh;
mod patch_reference;
mod surface_intersection;
mod tensor_surfaces;

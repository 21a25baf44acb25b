//! Integration tests of surfaces of revolution (`revolve::Revolution`):
//! partials, normals and intersections against independent references, the
//! hard cases of DESIGN.md §5, rational profiles against exact closed forms,
//! users' own profile types, batches of rays, the generic Newton intersector
//! on revolutions, nearest points, and tessellation.
//!
//! One module per subject; each module's docs state its references and
//! tolerances.

mod batch;
mod hard_cases;
mod mesh;
mod nearest;
mod newton;
mod own_profiles;
mod queries;
mod rational_revolution;
mod revolution;
mod rigid_motion;
mod to_nurbs;

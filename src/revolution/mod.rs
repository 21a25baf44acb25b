//! Surfaces of revolution: the surface ([`Revolution`]), its certified
//! intersector, the profile approximation for curves without Bézier spans,
//! and its tessellation.
//!
//! A ray meets `S(u, θ)` where the ray point at height `y(u)` lies at
//! distance `|x(u)|` from the axis: the angle is eliminated and each Bézier
//! span of the profile gives one polynomial in `u` whose roots are all
//! isolated (`span_table.rs`, `span_search.rs`). Profiles without spans are approximated by
//! cubic pieces within a certified deviation and the hits refined on the
//! profile itself (`profile_approximation.rs`, `profile_refine.rs`).

mod bounds;
mod candidates;
#[cfg(test)]
mod double_double;
mod intersect;
mod meridian_cells;
mod meridian_newton;
mod monotone_spans;
mod nearest;
mod one_root;
mod profile_approximation;
mod profile_refine;
mod query;
mod rigid_motion;
mod select;
mod span_culling;
mod span_form;
mod span_search;
mod span_table;
mod surface;
mod tessellate;
mod turn_angle;

pub use span_search::ExactReport;
pub use surface::Revolution;

//! Integration tests of the curve layer (`revolve::curve`, `revolve::bernstein`):
//! Bézier, B-spline, rational Bézier and NURBS curves against closed forms
//! and exact arithmetic, degree elevation, the nearest-point and arc-length
//! queries, high-degree stability, and property tests of the curve laws.
//!
//! One module per subject; each module's docs state its references and
//! tolerances.

mod bezier;
mod bspline;
mod constructions;
mod elevate;
mod intersections;
mod nurbs;
mod operations;
mod properties;
mod queries;
mod rational_bezier;
mod reduce;
mod space_intersections;
mod stability;

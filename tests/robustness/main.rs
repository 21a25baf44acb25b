//! Robustness of the whole public API: every bad input is a named `Error`,
//! never a panic; extreme sizes, directions and ranges give the closed-form
//! answer or a miss; users' curves that break the `Curve` contract are
//! handled; and a seeded, time-bounded fuzz target over constructors,
//! evaluators and intersectors.

mod errors;
mod extremes;
mod findings;
mod fuzz;
mod robustness;

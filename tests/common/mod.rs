//! A bridge for `examples/accuracy_cost`, which still includes this file by
//! `#[path]`: the shared helpers are the `revolve-testkit` dev crate
//! (`testkit/`) now. Goes away when the study uses the crate directly.

pub use revolve_testkit::*;

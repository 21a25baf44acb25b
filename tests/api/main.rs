//! The optional features' contracts: `serde` (round trips bit for bit, bad
//! data as the constructors' errors) and `testing` (the proptest strategies
//! and law checkers offered to downstream crates); and orientation
//! (`reversed()` on every curve and surface kind, its serde and law parts
//! with those features).
//!
//! `serde` and `testing` compile only with their feature (`cargo test
//! --all-features`).

mod orientation;
mod serde;
mod testing;

//! The optional features' contracts: `serde` (round trips bit for bit, bad
//! data as the constructors' errors) and `testing` (the proptest strategies
//! and law checkers offered to downstream crates).
//!
//! Each module compiles only with its feature (`cargo test --all-features`).

mod serde;
mod testing;

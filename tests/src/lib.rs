//! Shared helpers for sightline's cross-crate tests, benchmarks and
//! workloads.

pub mod obj;

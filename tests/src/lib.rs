//! Shared helpers for sightline's cross-crate tests and benchmarks, and
//! the W1/W2 raster workloads (`src/bin/workload.rs`).

pub mod fill;
pub mod obj;
pub mod workload;

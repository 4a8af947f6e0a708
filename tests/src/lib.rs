//! Shared helpers for sightline's cross-crate tests, benchmarks and
//! workloads: the OBJ reader, the W1/W2 raster workloads, the ray-cast
//! workloads and the fill-rate modes (`src/bin/workload.rs`).

pub mod fill;
pub mod obj;
pub mod ray_workload;
pub mod workload;

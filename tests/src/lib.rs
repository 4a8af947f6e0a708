//! Shared helpers for sightline's cross-crate tests and benchmarks.

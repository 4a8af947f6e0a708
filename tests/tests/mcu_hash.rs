//! Host half of the host/MCU bit-identity check.
//!
//! `tests/mcu/src/kernels.rs` is compiled here and into the Cortex-M
//! firmware. The firmware's `hash` command prints FNV-1a of its I16F16 and
//! f32 results and `tests/mcu/run` requires them to equal
//! `FX_HASH_EXPECTED` and `F32_HASH_EXPECTED`; this test requires the host
//! to produce the same values, so results are bit-identical on x86-64,
//! ARMv6-M and ARMv7E-M.

#[allow(dead_code)]
#[path = "../mcu/src/kernels.rs"]
mod kernels;

use sightline::scalar::I16F16;

#[test]
fn fixed_point_results_hash_as_on_the_mcu() {
    let h = kernels::hash_results::<I16F16>();
    assert_eq!(
        h,
        kernels::FX_HASH_EXPECTED,
        "host I16F16 hash {h:#018x} differs from the expected (MCU) value {:#018x}",
        kernels::FX_HASH_EXPECTED
    );
}

/// f32 results are bit-identical across targets too (see
/// `kernels::F32_HASH_EXPECTED`): the firmware's `hash f32` line must give
/// the same value on both Cortex-M targets.
#[test]
fn f32_results_hash_as_on_the_mcu() {
    let h = kernels::hash_results::<f32>();
    assert_eq!(
        h,
        kernels::F32_HASH_EXPECTED,
        "host f32 hash {h:#018x} differs from the expected (MCU) value {:#018x}",
        kernels::F32_HASH_EXPECTED
    );
}

#[test]
fn every_solve3x3_system_succeeds() {
    // The hash covers errors too, but the kernel is meant to measure a
    // successful, well-conditioned solve.
    assert!(kernels::all_systems_solve::<I16F16>());
    assert!(kernels::all_systems_solve::<f32>());
}

//! The micro-kernels measured on Cortex-M, and a hash of their results.
//!
//! This file is shared: the firmware (`tests/mcu/src/main.rs`) and the host
//! test `tests/tests/mcu_hash.rs` both include it, so the host and every
//! target hash exactly the same computation. It depends only on `core` and
//! `sightline`.
//!
//! Every kernel cycles through a table of [`INPUTS`] inputs, so a figure per
//! operation is an average over those inputs (fixed-point `sin_cos` and
//! `sqrt` take data-dependent paths).

use core::hint::black_box;
use sightline::math::{Affine3, Vec3};
use sightline::scalar::{I16F16, Scalar};
use sightline::solve::{SolveError, solve};
use sightline::transform::Euler;

/// FNV-1a (64-bit) over the I16F16 results of [`hash_results`]: the value
/// the host computes and every target must print.
pub const FX_HASH_EXPECTED: u64 = 0xe777_78aa_0efd_9aa0;

/// FNV-1a (64-bit) over the f32 results of [`hash_results`]. The kernels
/// use only IEEE-754 basic operations (correctly rounded on every target:
/// SSE on x86-64, the FPU on Cortex-M4F, compiler-builtins' soft float on
/// Cortex-M0) and libm's pure-Rust functions, and Rust never contracts
/// `a * b + c` into a fused multiply-add, so f32 results are bit-identical
/// too: the host and every target must give this value.
pub const F32_HASH_EXPECTED: u64 = 0xc9a2_094e_ef04_662c;

/// Inputs per kernel table; iteration `i` uses input `i % INPUTS`.
pub const INPUTS: usize = 8;

/// The kernels, by the names used on the firmware command line and in
/// `docs/mcu/kernels.md`.
pub const KERNELS: [&str; 6] = [
    "empty",
    "sin_cos",
    "sqrt",
    "transform_point3",
    "to_mat3",
    "solve3x3",
];

/// A scalar whose results can be hashed bit for bit.
pub trait Bits: Scalar {
    /// The raw 32-bit representation.
    fn bits(self) -> u32;
}
impl Bits for f32 {
    fn bits(self) -> u32 {
        self.to_bits()
    }
}
impl Bits for I16F16 {
    fn bits(self) -> u32 {
        self.to_bits() as u32
    }
}

/// FNV-1a, 64-bit.
#[derive(Clone, Copy, Debug)]
pub struct Fnv(pub u64);
impl Fnv {
    /// The offset basis.
    pub const fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    /// Hashes the four little-endian bytes of `v`.
    pub fn u32(&mut self, v: u32) {
        for b in v.to_le_bytes() {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    /// Hashes a scalar's bits.
    pub fn s<S: Bits>(&mut self, v: S) {
        self.u32(v.bits());
    }
}
impl Default for Fnv {
    fn default() -> Self {
        Self::new()
    }
}

// ---------------------------------------------------------------- inputs

const ANGLES: [f64; INPUTS] = [0.1, -0.7, 1.3, -2.2, 2.9, -3.1, 0.785, 4.5];
const RADICANDS: [f64; INPUTS] = [0.0123, 0.5, 1.0, 2.0, 3.75, 100.25, 1234.5, 30000.0];
const POINTS: [[f64; 3]; INPUTS] = [
    [1.0, 2.0, 3.0],
    [-4.5, 0.25, 7.0],
    [0.0, 0.0, 0.0],
    [10.0, -20.0, 30.0],
    [-0.125, 0.5, -1.0],
    [100.0, 50.0, -75.0],
    [3.3, -2.2, 1.1],
    [-9.0, 8.0, -7.0],
];
const EULERS: [[f64; 3]; INPUTS] = [
    [0.0, 0.0, 0.0],
    [0.1, 0.2, 0.3],
    [-0.5, 1.0, -1.5],
    [3.0, -1.2, 2.0],
    [1.57, 0.4, -3.0],
    [-2.5, -0.9, 0.7],
    [0.33, 1.5, 2.9],
    [-3.1, 0.05, -0.05],
];
const POSE_ANGLES: [f64; 3] = [0.3, -0.6, 1.1];
const POSE_ORIGIN: [f64; 3] = [1.5, -2.0, 10.0];

/// System `k` (0..INPUTS): a diagonally dominant, well-conditioned `A`
/// and three right-hand sides.
fn system<S: Scalar>(k: usize) -> ([[S; 3]; 3], [[S; 3]; 3]) {
    const A: [[f64; 3]; 3] = [[4.0, 1.0, -0.5], [1.0, 5.0, 1.5], [-0.5, 0.75, 3.0]];
    const P: [[f64; 3]; 3] = [[1.0, -1.0, 0.5], [0.5, 1.0, -1.0], [-1.0, 0.5, 1.0]];
    const B: [[f64; 3]; 3] = [[1.0, 0.5, -2.0], [2.0, -1.0, 0.25], [-0.75, 3.0, 1.0]];
    let t = 0.0625 * k as f64;
    let a = core::array::from_fn(|r| core::array::from_fn(|c| S::from_f64(A[r][c] + t * P[r][c])));
    let b = core::array::from_fn(|r| core::array::from_fn(|c| S::from_f64(B[r][c] + 4.0 * t)));
    (a, b)
}

fn v3<S: Scalar>(p: [f64; 3]) -> Vec3<S> {
    Vec3::new(S::from_f64(p[0]), S::from_f64(p[1]), S::from_f64(p[2]))
}
fn euler<S: Scalar>(e: [f64; 3]) -> Euler<S> {
    Euler::new(S::from_f64(e[0]), S::from_f64(e[1]), S::from_f64(e[2]))
}
fn pose<S: Scalar>() -> Affine3<S> {
    Affine3::new(euler::<S>(POSE_ANGLES).to_mat3(), v3(POSE_ORIGIN))
}

// ---------------------------------------------------------------- timed loops
//
// Each loop converts its inputs first (the same work for any `n`, so it
// cancels in the N-vs-0 difference), then runs `n` operations. Inputs and
// results pass through `black_box`, so nothing is hoisted or removed.

/// Runs `n` operations of kernel `name` for scalar `S`; `false` for an
/// unknown name.
pub fn run<S: Scalar>(name: &str, n: u32) -> bool {
    match name {
        "empty" => bench_empty::<S>(n),
        "sin_cos" => bench_sin_cos::<S>(n),
        "sqrt" => bench_sqrt::<S>(n),
        "transform_point3" => bench_transform_point3::<S>(n),
        "to_mat3" => bench_to_mat3::<S>(n),
        "solve3x3" => bench_solve3x3::<S>(n),
        _ => return false,
    }
    true
}

/// The loop and `black_box` overhead alone: one scalar in, one out.
#[inline(never)]
pub fn bench_empty<S: Scalar>(n: u32) {
    let xs = ANGLES.map(S::from_f64);
    for i in 0..n as usize {
        black_box(black_box(xs[i % INPUTS]));
    }
}

/// `sin_cos` of an angle.
#[inline(never)]
pub fn bench_sin_cos<S: Scalar>(n: u32) {
    let xs = ANGLES.map(S::from_f64);
    for i in 0..n as usize {
        black_box(black_box(xs[i % INPUTS]).sin_cos());
    }
}

/// `sqrt`.
#[inline(never)]
pub fn bench_sqrt<S: Scalar>(n: u32) {
    let xs = RADICANDS.map(S::from_f64);
    for i in 0..n as usize {
        black_box(black_box(xs[i % INPUTS]).sqrt());
    }
}

/// One `Affine3::transform_point3` (the matrix is reloaded every time).
#[inline(never)]
pub fn bench_transform_point3<S: Scalar>(n: u32) {
    let m = pose::<S>();
    let ps = POINTS.map(v3::<S>);
    for i in 0..n as usize {
        black_box(black_box(&m).transform_point3(black_box(ps[i % INPUTS])));
    }
}

/// `Euler::to_mat3` (three `sin_cos` and the products).
#[inline(never)]
pub fn bench_to_mat3<S: Scalar>(n: u32) {
    let es = EULERS.map(euler::<S>);
    for i in 0..n as usize {
        black_box(black_box(&es[i % INPUTS]).to_mat3());
    }
}

/// `solve::solve` of a 3×3 system with 3 right-hand sides, diagnostics
/// (growth, rcond) included.
#[inline(never)]
pub fn bench_solve3x3<S: Scalar>(n: u32) {
    let systems: [_; INPUTS] = core::array::from_fn(system::<S>);
    for i in 0..n as usize {
        let (a, b) = black_box(&systems[i % INPUTS]);
        let _ = black_box(solve(a, b));
    }
}

// ---------------------------------------------------------------- hash

fn hash_err(h: &mut Fnv, e: SolveError) {
    h.u32(0xdead_0000);
    h.u32(match e {
        SolveError::Singular { column } => 0x100 + column as u32,
        SolveError::IllConditioned { rcond } => 0x200 ^ rcond.to_bits(),
        SolveError::Overflow => 0x300,
        SolveError::NonFinite => 0x400,
        // `SolveError` is `#[non_exhaustive]`; `Inaccurate` and later variants.
        _ => 0x500,
    });
}

/// FNV-1a over the bits of every kernel's result on every input, in a
/// fixed order: sin_cos, sqrt, transform_point3, to_mat3, solve3x3 (x, then
/// growth, rcond and ‖A‖₁).
pub fn hash_results<S: Bits>() -> u64 {
    let mut h = Fnv::new();
    for x in ANGLES.map(S::from_f64) {
        let (s, c) = black_box(x).sin_cos();
        h.s(s);
        h.s(c);
    }
    for x in RADICANDS.map(S::from_f64) {
        h.s(black_box(x).sqrt());
    }
    let m = pose::<S>();
    for p in POINTS.map(v3::<S>) {
        for v in black_box(&m).transform_point3(p).to_array() {
            h.s(v);
        }
    }
    for e in EULERS.map(euler::<S>) {
        for v in black_box(&e).to_mat3().m.into_iter().flatten() {
            h.s(v);
        }
    }
    for k in 0..INPUTS {
        let (a, b) = system::<S>(k);
        match solve(black_box(&a), &b) {
            Ok(sol) => {
                for v in sol.x.into_iter().flatten() {
                    h.s(v);
                }
                h.s(sol.diagnostics.growth);
                h.s(sol.diagnostics.rcond);
                h.s(sol.diagnostics.norm1);
            }
            Err(e) => hash_err(&mut h, e),
        }
    }
    h.0
}

/// Whether every system of the `solve3x3` kernel solves without error (the
/// kernel is meant to measure the successful path).
pub fn all_systems_solve<S: Scalar>() -> bool {
    (0..INPUTS).all(|k| {
        let (a, b) = system::<S>(k);
        solve(&a, &b).is_ok()
    })
}

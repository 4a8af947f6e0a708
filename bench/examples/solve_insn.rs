//! The 3×3 (3 right-hand sides) solve variants of `benches/solve.rs`, for
//! two measurements that hold up on a shared, noisy machine:
//!
//! - `solve_insn VARIANT N` runs one variant N times, for callgrind
//!   instruction counts: `count(N) − count(0)` over N is instructions per
//!   solve.
//! - `solve_insn time` interleaves all variants in 41 rounds of 20 000
//!   solves each and prints each variant's median ns per solve and its
//!   ratio to nalgebra, so load changes hit every variant alike.
//!
//! ```text
//! cargo build --release --manifest-path bench/Cargo.toml --example solve_insn
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!   bench/target/release/examples/solve_insn sightline_f32 100000
//! bench/target/release/examples/solve_insn time
//! ```

use sightline::scalar::{I16F16, Scalar};
use sightline::solve::{Lu, solve};
use std::hint::black_box;

const A: [[f64; 3]; 3] = [[4.0, -2.0, 1.0], [3.0, 6.0, -4.0], [2.0, 1.0, 8.0]];
const B: [[f64; 3]; 3] = [[12.0, -1.0, 0.5], [-25.0, 3.0, 2.0], [32.0, 0.25, -7.0]];

fn cast<T: Scalar>(m: &[[f64; 3]; 3]) -> [[T; 3]; 3] {
    m.map(|r| r.map(T::from_f64))
}

const VARIANTS: [&str; 4] = [
    "sightline_f32",
    "sightline_f32_no_rcond",
    "sightline_i16f16",
    "nalgebra_lu_f32",
];

fn run(variant: &str, n: u64) -> f64 {
    let (a32, b32) = (cast::<f32>(&A), cast::<f32>(&B));
    let (afx, bfx) = (cast::<I16F16>(&A), cast::<I16F16>(&B));
    let na = nalgebra::Matrix3::<f32>::from_fn(|i, j| A[i][j] as f32);
    let nb = nalgebra::Matrix3::<f32>::from_fn(|i, j| B[i][j] as f32);
    let mut sink = 0.0f64;
    for _ in 0..n {
        sink += match variant {
            "sightline_f32" => {
                solve(black_box(&a32), black_box(&b32)).map_or(0.0, |s| s.x[0][0] as f64)
            }
            "sightline_f32_no_rcond" => Lu::factor(black_box(&a32))
                .and_then(|lu| lu.solve(black_box(&b32)))
                .map_or(0.0, |x| x[0][0] as f64),
            "sightline_i16f16" => {
                solve(black_box(&afx), black_box(&bfx)).map_or(0.0, |s| s.x[0][0].to_f64())
            }
            "nalgebra_lu_f32" => black_box(na)
                .lu()
                .solve(&black_box(nb))
                .map_or(0.0, |x| x[(0, 0)] as f64),
            other => panic!("unknown variant {other}"),
        };
    }
    sink
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let variant = args.get(1).map(String::as_str).unwrap_or("sightline_f32");
    if variant == "time" {
        const BATCH: u64 = 20_000;
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); VARIANTS.len()];
        for _round in 0..41 {
            for (k, v) in VARIANTS.iter().enumerate() {
                let t = std::time::Instant::now();
                black_box(run(v, BATCH));
                times[k].push(t.elapsed().as_nanos() as f64 / BATCH as f64);
            }
        }
        let medians: Vec<f64> = times
            .iter_mut()
            .map(|t| {
                t.sort_by(f64::total_cmp);
                t[t.len() / 2]
            })
            .collect();
        let base = medians[VARIANTS.len() - 1];
        for (v, m) in VARIANTS.iter().zip(&medians) {
            println!("{v:<24} {m:8.1} ns/solve  {:.2}x nalgebra", m / base);
        }
        return;
    }
    let n: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0);
    let sink = run(variant, n);
    println!("{variant} {n} {sink}");
}

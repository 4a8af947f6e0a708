//! 3×3 solve with 3 right-hand sides: sightline's GEPP (with growth and the
//! rcond estimate) in f32 and I16F16, against nalgebra's LU on the same
//! system.
//!
//! Run: `cargo bench --manifest-path bench/Cargo.toml --bench solve`

use criterion::{Criterion, criterion_group, criterion_main};
use sightline::scalar::{I16F16, Scalar};
use sightline::solve::{Lu, solve};
use std::hint::black_box;

const A: [[f64; 3]; 3] = [[4.0, -2.0, 1.0], [3.0, 6.0, -4.0], [2.0, 1.0, 8.0]];
const B: [[f64; 3]; 3] = [[12.0, -1.0, 0.5], [-25.0, 3.0, 2.0], [32.0, 0.25, -7.0]];

fn cast<T: Scalar>(m: &[[f64; 3]; 3]) -> [[T; 3]; 3] {
    m.map(|r| r.map(T::from_f64))
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("solve3x3_rhs3");
    let (a32, b32) = (cast::<f32>(&A), cast::<f32>(&B));
    g.bench_function("sightline_f32", |bch| {
        bch.iter(|| solve(black_box(&a32), black_box(&b32)).map(|s| s.x))
    });
    g.bench_function("sightline_f32_no_rcond", |bch| {
        bch.iter(|| Lu::factor(black_box(&a32)).and_then(|lu| lu.solve(black_box(&b32))))
    });
    let (afx, bfx) = (cast::<I16F16>(&A), cast::<I16F16>(&B));
    g.bench_function("sightline_i16f16", |bch| {
        bch.iter(|| solve(black_box(&afx), black_box(&bfx)).map(|s| s.x))
    });
    let na = nalgebra::Matrix3::<f32>::from_fn(|i, j| A[i][j] as f32);
    let nb = nalgebra::Matrix3::<f32>::from_fn(|i, j| B[i][j] as f32);
    g.bench_function("nalgebra_lu_f32", |bch| {
        bch.iter(|| black_box(na).lu().solve(&black_box(nb)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

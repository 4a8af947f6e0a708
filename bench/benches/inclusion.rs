//! Cost per point-in-polygon test of each inclusion method against the
//! polygon's vertex count, and precomputed per-polygon data (plane,
//! dominant axis, 2D edge equations) against computing it per ray.
//!
//! Polygons are regular n-gons (convex, so all four methods apply) of
//! radius 1 in a tilted plane; the query points are 1024 random points
//! of the projected polygon's bounding square (about 79 % inside for
//! large n). The slab index is built once per polygon in caller storage.
//!
//! Run: `cargo bench --manifest-path bench/Cargo.toml --bench inclusion`

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use sightline::math::{Vec2, Vec3};
use sightline::ray::{InclusionTest, Polygon, Ray, SlabIndex};
use std::hint::black_box;
use std::time::Duration;

const SIZES: [usize; 10] = [3, 4, 6, 8, 12, 16, 32, 64, 128, 256];
const CAP: usize = 256;

/// SplitMix64, for reproducible points.
fn rng(seed: &mut u64) -> f32 {
    *seed = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *seed;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
}

/// The point (x, y) of the polygons' plane: through (0, 0, −5), tilted
/// 0.4 rad about x.
fn on_plane(x: f32, y: f32) -> Vec3<f32> {
    let (s, c) = 0.4f32.sin_cos();
    Vec3::new(x, y * c, -5.0 + y * s)
}

/// A regular n-gon of radius 1 in that plane.
fn ngon(n: usize) -> Vec<Vec3<f32>> {
    (0..n)
        .map(|k| {
            let a = std::f32::consts::TAU * k as f32 / n as f32 + 0.1;
            on_plane(a.cos(), a.sin())
        })
        .collect()
}

/// Precomputed against per-ray polygon set-up for an n-gon, with the
/// capacity equal to n so that neither side copies unused storage.
fn precompute_case<const N: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    rays: &[Ray<f32>],
) {
    let verts = ngon(N);
    let poly = Polygon::<f32, N>::new(&verts)
        .expect("n-gon")
        .with_test(InclusionTest::HalfPlane);
    g.bench_with_input(BenchmarkId::new("precomputed", N), &N, |b, _| {
        b.iter(|| {
            rays.iter()
                .filter(|r| poly.intersect(black_box(r), 0.0).is_some())
                .count()
        })
    });
    g.bench_with_input(BenchmarkId::new("per_ray", N), &N, |b, _| {
        b.iter(|| {
            rays.iter()
                .filter(|r| {
                    Polygon::<f32, N>::new(black_box(&verts))
                        .ok()
                        .and_then(|p| p.with_test(InclusionTest::HalfPlane).intersect(r, 0.0))
                        .is_some()
                })
                .count()
        })
    });
}

fn bench(c: &mut Criterion) {
    let mut seed = 7u64;
    let points: Vec<(f32, f32)> = (0..1024)
        .map(|_| (rng(&mut seed) * 2.2 - 1.1, rng(&mut seed) * 2.2 - 1.1))
        .collect();
    let mut g = c.benchmark_group("inclusion");
    g.throughput(Throughput::Elements(points.len() as u64));
    g.sample_size(20);
    g.warm_up_time(Duration::from_millis(200));
    g.measurement_time(Duration::from_millis(800));
    for n in SIZES {
        let poly = Polygon::<f32, CAP>::new(&ngon(n)).expect("regular n-gon");
        assert!(poly.is_convex());
        // Query points on the polygon's plane, projected as it projects.
        let pts: Vec<Vec2<f32>> = points
            .iter()
            .map(|&(a, b)| poly.project(on_plane(a, b)))
            .collect();
        for (name, test) in [
            ("crossing", InclusionTest::Crossing),
            ("half_plane", InclusionTest::HalfPlane),
            ("fan", InclusionTest::Fan),
        ] {
            g.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| {
                    pts.iter()
                        .filter(|&&p| poly.contains(black_box(p), test))
                        .count()
                })
            });
        }
        let mut ys = vec![0f32; n];
        let mut starts = vec![0u32; n + 1];
        let mut edges = vec![0u32; n * n];
        let slab = SlabIndex::build(&poly, &mut ys, &mut starts, &mut edges).expect("sized");
        g.bench_with_input(BenchmarkId::new("slab", n), &n, |b, _| {
            b.iter(|| pts.iter().filter(|&&p| slab.contains(black_box(p))).count())
        });
        // All four agree on these points (none lies on an edge).
        let counts: Vec<usize> = [
            InclusionTest::Crossing,
            InclusionTest::HalfPlane,
            InclusionTest::Fan,
        ]
        .iter()
        .map(|&t| pts.iter().filter(|&&p| poly.contains(p, t)).count())
        .chain([pts.iter().filter(|&&p| slab.contains(p)).count()])
        .collect();
        assert!(
            counts.windows(2).all(|w| w[0] == w[1]),
            "n = {n}: {counts:?}"
        );
    }
    g.finish();

    // Ray–polygon intersection: the precomputed polygon, against building
    // it (Newell normal, dominant axis, orientation, convexity, edge
    // equations) for every ray, both with the half-plane test.
    let mut g = c.benchmark_group("precompute");
    g.throughput(Throughput::Elements(points.len() as u64));
    g.sample_size(20);
    g.warm_up_time(Duration::from_millis(200));
    g.measurement_time(Duration::from_millis(800));
    let rays: Vec<Ray<f32>> = points
        .iter()
        .map(|&(a, b)| Ray::new(Vec3::ZERO, Vec3::new(a / 5.0, b / 5.0, -1.0)).expect("finite"))
        .collect();
    precompute_case::<3>(&mut g, &rays);
    precompute_case::<4>(&mut g, &rays);
    precompute_case::<8>(&mut g, &rays);
    precompute_case::<16>(&mut g, &rays);
    precompute_case::<64>(&mut g, &rays);
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Rays per second on the bunny posed as W1 frame 0: brute force, per-object
//! bounding boxes and the uniform grid (`sightline_tests::ray_workload`),
//! and parry3d's `TriMesh` ray cast (its own BVH) on the same rays.
//!
//! The rays are every 97th pixel of the 320×240 frame (792 primary rays,
//! spread over the whole image: about a quarter hit the bunny, as in the
//! full frame), so that brute force fits the shared machine's time budget.
//! Throughput is reported per ray.
//!
//! Run: `cargo bench --manifest-path bench/Cargo.toml --bench ray`

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use parry3d::math::{Point, Vector};
use parry3d::query::{Ray as PRay, RayCast};
use parry3d::shape::TriMesh;
use sightline::ray::{Mailbox, Ray};
use sightline_tests::ray_workload::{RayMode, RayWorkload};
use sightline_tests::workload::{HEIGHT, Model, WIDTH};
use std::hint::black_box;
use std::time::Duration;

const STRIDE: usize = 97;

fn rays(w: &RayWorkload<f32>) -> Vec<Ray<f32>> {
    (0..WIDTH as usize * HEIGHT as usize)
        .step_by(STRIDE)
        .filter_map(|k| w.pixel_ray((k % WIDTH as usize) as u16, (k / WIDTH as usize) as u16))
        .collect()
}

fn bench(c: &mut Criterion) {
    let model = Model::<f32>::bunny();
    let modes =
        [RayMode::Brute, RayMode::Bounds, RayMode::Grid].map(|m| RayWorkload::new(&model, m));
    let rays = rays(&modes[0]);
    let mut g = c.benchmark_group("bunny_primary_rays");
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(3));
    let mut hits = Vec::new();
    for w in &modes {
        let mut stamps = w.stamps();
        let mut mb = Mailbox::new(&mut stamps);
        hits.push(
            rays.iter()
                .filter(|r| w.nearest(r, &mut mb).is_some())
                .count(),
        );
        g.bench_function(w.mode().name(), |b| {
            b.iter(|| {
                let mut n = 0;
                for r in &rays {
                    n += usize::from(w.nearest(black_box(r), &mut mb).is_some());
                }
                n
            })
        });
    }
    // parry3d on the same world-space triangles and rays.
    let mesh = modes[0].mesh();
    let mut verts = Vec::new();
    let mut idx = Vec::new();
    for i in 0..mesh.len() {
        let t = mesh.triangle(i).expect("in range");
        let k = verts.len() as u32;
        for v in t.v {
            verts.push(Point::new(v.x, v.y, v.z));
        }
        idx.push([k, k + 1, k + 2]);
    }
    let tm = TriMesh::new(verts, idx).expect("bunny trimesh");
    let prays: Vec<PRay> = rays
        .iter()
        .map(|r| {
            let (o, d) = (r.origin(), r.dir());
            PRay::new(Point::new(o.x, o.y, o.z), Vector::new(d.x, d.y, d.z))
        })
        .collect();
    let parry_hits = prays
        .iter()
        .filter(|r| tm.cast_local_ray(r, f32::MAX, true).is_some())
        .count();
    eprintln!(
        "{} rays; hits: brute {}, bounds {}, grid {}, parry3d {parry_hits}",
        rays.len(),
        hits[0],
        hits[1],
        hits[2]
    );
    g.bench_function("parry3d_trimesh", |b| {
        b.iter(|| {
            let mut n = 0;
            for r in &prays {
                n += usize::from(tm.cast_local_ray(black_box(r), f32::MAX, true).is_some());
            }
            n
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

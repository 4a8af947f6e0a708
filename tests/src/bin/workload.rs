//! Benchmark workloads on the bunny: W1 (flat) and W2 (Gouraud) through the
//! raster pipeline, fill rate per shader, and (when built) the ray-cast
//! variants.
//!
//! ```text
//! cargo run --release -p sightline-tests --bin workload -- w1 200
//! cargo run --release -p sightline-tests --bin workload -- w2 200 --scalar fixed
//! cargo run --release -p sightline-tests --bin workload -- w1 200 --passes 5
//! cargo run --release -p sightline-tests --bin workload -- fill gouraud-depth 100
//! cargo run --release -p sightline-tests --bin workload -- ray-grid 20
//! ```
//!
//! `w1|w2 N` renders frames k = 0..N−1 of N (yaw 2πk/N) exactly once and
//! prints the median ns over those N frames as its last line,
//! `ns_per_frame: <n>`. With N = 0 it does only the set-up, so callgrind's
//! count for N = 20 minus N = 0, divided by 20, is instructions per frame.
//!
//! `--passes P` times as `WORKLOADS.md` does instead: one warm-up pass,
//! then P passes of the N frames; `ns_per_frame` is then the median of the
//! passes' averages. `--scalar f32` (default) or `--scalar fixed` (I16F16)
//! picks the pipeline's scalar type.
//!
//! `ray-brute|ray-bounds|ray-grid N [--scalar f32|fixed] [--passes P]`
//! casts N frames of 320×240 primary rays at the bunny posed as W1 frame
//! 0 and shades them by the W1 flat rule (`sightline_tests::ray_workload`);
//! N = 0 does only the set-up, including the grid build.
//!
//! `fill MODE N [--passes P]` fills one 320×240-covering polygon per frame
//! with one shader (MODE: flat, flat-depth, gouraud-depth, affine, persp,
//! persp16) and also prints pixels per second; see
//! `docs/raster-workloads.md`.

use sightline::scalar::{I16F16, Scalar};
use sightline_tests::fill::{FillBench, FillMode};
use sightline_tests::ray_workload::{RayMode, RayWorkload};
use sightline_tests::workload::{Frame, Model, Shading, Workload};
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "usage: workload w1|w2 N [--scalar f32|fixed] [--passes P]\n       workload ray-brute|ray-bounds|ray-grid N [--scalar f32|fixed] [--passes P]\n       workload fill flat|flat-depth|gouraud-depth|affine|persp|persp16 N [--passes P]";

/// Median ns per frame: of the individual frames (one pass), or of the
/// per-pass averages after a warm-up pass.
fn time_frames(n: u32, passes: Option<u32>, mut frame: impl FnMut(u32)) -> u64 {
    if n == 0 {
        return 0;
    }
    let mut samples = Vec::new();
    match passes {
        None => {
            for k in 0..n {
                let t = Instant::now();
                frame(k);
                samples.push(t.elapsed().as_nanos() as u64);
            }
        }
        Some(p) => {
            for pass in 0..=p {
                let t = Instant::now();
                for k in 0..n {
                    frame(k);
                }
                if pass > 0 {
                    samples.push(t.elapsed().as_nanos() as u64 / n as u64);
                }
            }
        }
    }
    samples.sort_unstable();
    samples[samples.len() / 2]
}

fn fill(mode: FillMode, n: u32, passes: Option<u32>) {
    let mut b = FillBench::new(mode);
    let mut px = 0u64;
    let med = time_frames(n, passes, |_| {
        px = b.frame() as u64;
        black_box(&b.color);
    });
    println!("fill {} N={n} pixels_per_frame={px}", mode.name());
    println!("Mpixels_per_s: {:.1}", px as f64 / med.max(1) as f64 * 1e3);
    println!("ns_per_frame: {med}");
}

fn run<S: Scalar>(shading: Shading, n: u32, passes: Option<u32>) {
    let model = Model::bunny();
    let mut w = Workload::<S>::new(&model, shading);
    let mut frame = Frame::default();
    let mut tris = 0u64;
    let med = time_frames(n, passes, |k| {
        tris += w.render(k, n, &mut frame) as u64;
        black_box(&frame.color);
    });
    let frames = n as u64 * passes.map_or(1, |p| p as u64 + 1);
    println!(
        "{} {} N={n} passes={} triangles_drawn_per_frame={:.1}",
        match shading {
            Shading::Flat => "w1",
            Shading::Gouraud => "w2",
        },
        S::NAME,
        passes.map_or("1 (per-frame median)".to_string(), |p| p.to_string()),
        tris as f64 / frames.max(1) as f64
    );
    println!("ns_per_frame: {med}");
}

fn ray<S: Scalar>(mode: RayMode, n: u32, passes: Option<u32>) {
    let mut w = RayWorkload::<S>::new(&Model::bunny(), mode);
    let mut frame = Frame::default();
    let mut hits = 0;
    let med = time_frames(n, passes, |_| {
        hits = w.render(&mut frame.color).hits;
        black_box(&frame.color);
    });
    let rays =
        u32::from(sightline_tests::workload::WIDTH) * u32::from(sightline_tests::workload::HEIGHT);
    println!(
        "{} {} N={n} passes={} rays_per_frame={rays} hits_per_frame={hits} grid_res={:?} objects={}",
        mode.name(),
        S::NAME,
        passes.map_or("1 (per-frame median)".to_string(), |p| p.to_string()),
        w.grid_res(),
        w.objects(),
    );
    if n > 0 {
        println!("Mrays_per_s: {:.3}", rays as f64 / med.max(1) as f64 * 1e3);
    }
    println!("ns_per_frame: {med}");
}

/// Parses `[--scalar f32|fixed] [--passes P]`; `None` on anything else.
fn options(rest: &[String]) -> Option<(bool, Option<u32>)> {
    let mut fixed = false;
    let mut passes = None;
    let mut it = rest.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--scalar" => match it.next().map(String::as_str) {
                Some("f32") => fixed = false,
                Some("fixed") => fixed = true,
                _ => return None,
            },
            "--passes" => passes = Some(it.next()?.parse::<u32>().ok().filter(|&p| p > 0)?),
            _ => return None,
        }
    }
    Some((fixed, passes))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = || {
        eprintln!("{USAGE}");
        ExitCode::FAILURE
    };
    match args.first().map(String::as_str) {
        Some("fill") => {
            let mode = args.get(1).and_then(|m| FillMode::from_name(m));
            let n = args.get(2).and_then(|s| s.parse::<u32>().ok());
            let (Some(mode), Some(n), Some((false, passes))) =
                (mode, n, options(args.get(3..).unwrap_or(&[])))
            else {
                return usage();
            };
            fill(mode, n, passes);
        }
        Some(w @ ("w1" | "w2")) => {
            let shading = if w == "w1" {
                Shading::Flat
            } else {
                Shading::Gouraud
            };
            let n = args.get(1).and_then(|s| s.parse::<u32>().ok());
            let (Some(n), Some((fixed, passes))) = (n, options(args.get(2..).unwrap_or(&[])))
            else {
                return usage();
            };
            if fixed {
                run::<I16F16>(shading, n, passes);
            } else {
                run::<f32>(shading, n, passes);
            }
        }
        Some(m) if RayMode::from_name(m).is_some() => {
            let mode = RayMode::from_name(m).unwrap_or(RayMode::Brute);
            let n = args.get(1).and_then(|s| s.parse::<u32>().ok());
            let (Some(n), Some((fixed, passes))) = (n, options(args.get(2..).unwrap_or(&[])))
            else {
                return usage();
            };
            if fixed {
                ray::<I16F16>(mode, n, passes);
            } else {
                ray::<f32>(mode, n, passes);
            }
        }
        _ => return usage(),
    }
    ExitCode::SUCCESS
}

//! Runs benchmark workload W1 (flat) or W2 (Gouraud) on the bunny.
//!
//! ```text
//! cargo run --release -p sightline-tests --bin workload -- w1 200
//! cargo run --release -p sightline-tests --bin workload -- w2 200 --scalar fixed
//! ```
//!
//! Renders frames k = 0..N−1 of N (yaw 2πk/N). Timing: one warm-up pass,
//! then 5 timed passes of N frames; the last line is the median
//! `ns_per_frame: <n>`. With `--once` it renders the N frames exactly once
//! (for callgrind: count(N) − count(0), over N, is instructions per
//! frame). With N = 0 it does only the set-up.
//!
//! `--scalar f32` (default) or `--scalar fixed` (I16F16) picks the
//! pipeline's scalar type.
//!
//! `workload fill MODE N [--once]` instead fills one 320×240-covering
//! polygon per frame with one shader (MODE: flat, flat-depth,
//! gouraud-depth, affine, persp, persp16) and also prints pixels per
//! second; see `docs/raster-workloads.md`.

use sightline::scalar::{I16F16, Scalar};
use sightline_tests::fill::{FillBench, FillMode};
use sightline_tests::workload::{Frame, Model, Shading, Workload};
use std::hint::black_box;
use std::process::ExitCode;
use std::time::Instant;

const USAGE: &str = "usage: workload w1|w2 N [--scalar f32|fixed] [--once]\n       workload fill flat|flat-depth|gouraud-depth|affine|persp|persp16 N [--once]";

fn fill(mode: FillMode, n: u32, once: bool) {
    let mut b = FillBench::new(mode);
    if n == 0 {
        println!("ns_per_frame: 0");
        return;
    }
    let mut pass = || {
        let t = Instant::now();
        let mut px = 0u64;
        for _ in 0..n {
            px += b.frame() as u64;
            black_box(&b.color);
        }
        (t.elapsed().as_nanos() as u64, px)
    };
    if !once {
        pass();
    }
    let mut times = Vec::new();
    let mut px = 0;
    for _ in 0..if once { 1 } else { 5 } {
        let (ns, p) = pass();
        times.push(ns / n as u64);
        px = p / n as u64;
    }
    times.sort_unstable();
    let med = times[times.len() / 2];
    println!("fill {} N={n} pixels_per_frame={px}", mode.name());
    println!("Mpixels_per_s: {:.1}", px as f64 / med.max(1) as f64 * 1e3);
    println!("ns_per_frame: {med}");
}

fn run<S: Scalar>(shading: Shading, n: u32, once: bool) {
    let mut w = Workload::<S>::new(Model::bunny(), shading);
    let mut frame = Frame::default();
    let pass = |w: &mut Workload<S>, frame: &mut Frame| {
        let t = Instant::now();
        let mut tris = 0u64;
        for k in 0..n {
            tris += w.render(k, n, frame) as u64;
            black_box(&frame.color);
        }
        (t.elapsed().as_nanos() as u64, tris)
    };
    if n == 0 {
        println!("ns_per_frame: 0");
        return;
    }
    let passes = if once { 1 } else { 5 };
    if !once {
        pass(&mut w, &mut frame);
    }
    let mut times = Vec::new();
    let mut tris = 0;
    for _ in 0..passes {
        let (ns, t) = pass(&mut w, &mut frame);
        times.push(ns / n as u64);
        tris = t;
    }
    times.sort_unstable();
    println!(
        "{} {} N={n} passes={passes} triangles_drawn_per_frame={:.1}",
        match shading {
            Shading::Flat => "w1",
            Shading::Gouraud => "w2",
        },
        S::NAME,
        tris as f64 / n as f64
    );
    println!("pass_ns_per_frame: {times:?}");
    println!("ns_per_frame: {}", times[times.len() / 2]);
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("fill") {
        let mode = args.get(1).and_then(|m| FillMode::from_name(m));
        let n = args.get(2).and_then(|s| s.parse::<u32>().ok());
        let once = match args.get(3).map(String::as_str) {
            None => false,
            Some("--once") => true,
            Some(_) => {
                eprintln!("{USAGE}");
                return ExitCode::FAILURE;
            }
        };
        let (Some(mode), Some(n)) = (mode, n) else {
            eprintln!("{USAGE}");
            return ExitCode::FAILURE;
        };
        fill(mode, n, once);
        return ExitCode::SUCCESS;
    }
    let shading = match args.first().map(String::as_str) {
        Some("w1") => Shading::Flat,
        Some("w2") => Shading::Gouraud,
        _ => {
            eprintln!("{USAGE}");
            return ExitCode::FAILURE;
        }
    };
    let Some(n) = args.get(1).and_then(|s| s.parse::<u32>().ok()) else {
        eprintln!("{USAGE}");
        return ExitCode::FAILURE;
    };
    let mut fixed = false;
    let mut once = false;
    let mut rest = args[2..].iter();
    while let Some(a) = rest.next() {
        match a.as_str() {
            "--once" => once = true,
            "--scalar" => match rest.next().map(String::as_str) {
                Some("f32") => fixed = false,
                Some("fixed") => fixed = true,
                _ => {
                    eprintln!("{USAGE}");
                    return ExitCode::FAILURE;
                }
            },
            _ => {
                eprintln!("{USAGE}");
                return ExitCode::FAILURE;
            }
        }
    }
    if fixed {
        run::<I16F16>(shading, n, once);
    } else {
        run::<f32>(shading, n, once);
    }
    ExitCode::SUCCESS
}

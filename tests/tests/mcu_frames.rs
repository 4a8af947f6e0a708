//! Host half of the host/MCU frame comparison.
//!
//! `tests/mcu/src/frames.rs` is compiled here and into the Cortex-M
//! firmware. Without `MCU_FRAMES_DIR` these tests check the shared code on
//! its own (strips equal a whole frame, the fill-rate quads cover exactly
//! the pixels the instructions-per-pixel figures divide by, W1 covers the
//! bunny's documented pixel range). `tests/mcu/run` sets `MCU_FRAMES_DIR`
//! to a directory of firmware `frames` outputs (`TRIPLE.txt`); then
//! `frames_match_the_mcu` requires every I16F16 frame hash (the scenes'
//! and the fill-rate quads', `fill-MODE`) to equal the host's and prints,
//! for every f32 frame, how many pixels differ from the host's and by how
//! much:
//!
//! ```text
//! fxhash SCENE TRIPLE 0x… equal
//! fdiff SCENE TRIPLE pixels=N max=D
//! ```
//!
//! `max` is the largest difference of one RGB565 channel, in that
//! channel's steps (5/6/5 bits).

#[allow(dead_code)]
#[path = "../mcu/src/frames.rs"]
mod frames;

use embedded_graphics::pixelcolor::{IntoStorage, Rgb565, RgbColor};
use frames::{FRAME_PIXELS, Fnv, HEIGHT, WIDTH};
use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::raster::DepthBuffer;
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::{self, Color, PreparedObject, Renderer, builtin};
use sightline::target::Framebuffer;

/// Renders `name` through the shared strip code; returns the hash and all
/// pixels.
fn strips<S: Scalar>(name: &str) -> (u64, Vec<u16>) {
    let mut color = vec![Color::BLACK; frames::BAND_PIXELS];
    let mut depth = vec![0u16; frames::BAND_PIXELS];
    let mut px = Vec::with_capacity(FRAME_PIXELS);
    let mut vec3s = vec![Vec3::<S>::ZERO; frames::STORAGE.vec3s];
    let mut scratch = vec![MeshVertex::default(); frames::STORAGE.vertices];
    let h = frames::render_scene::<S>(
        name,
        &mut vec3s,
        &mut scratch,
        &mut color,
        &mut depth,
        |y, row| {
            assert_eq!(
                px.len(),
                y as usize * WIDTH as usize,
                "rows arrive in order"
            );
            px.extend(row.iter().map(|c| c.into_storage()));
        },
    )
    .expect("built-in scenes render");
    assert_eq!(px.len(), FRAME_PIXELS);
    (h, px)
}

/// The raster path of `scene` into one whole-frame target.
fn whole_frame<S: Scalar>(
    scene: &scene::Scene<'_>,
    fb: &mut Framebuffer<'_, Color>,
    z: &mut DepthBuffer<'_>,
) {
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = scene.prepare(&mut vec3s, &mut objects).unwrap();
    let renderer = Renderer::<S>::new(scene, WIDTH, HEIGHT).unwrap();
    let mut scratch = vec![MeshVertex::default(); need.vertices];
    let frame = renderer.project(objects, &mut scratch).unwrap();
    frame.draw(fb, z);
}

#[test]
fn strips_equal_a_whole_frame() {
    for name in ["cube", "bunny", "corridor"] {
        for fx in [true, false] {
            let (h, px) = if fx {
                strips::<I16F16>(name)
            } else {
                strips::<f32>(name)
            };
            // Oracle: the same scene in one whole-frame buffer.
            let scene = builtin::by_name(name).unwrap();
            let mut color = vec![Color::BLACK; FRAME_PIXELS];
            let mut depth = vec![0u16; FRAME_PIXELS];
            let w = WIDTH as usize;
            {
                let mut fb = Framebuffer::new(&mut color, WIDTH, HEIGHT, w).unwrap();
                let mut z = DepthBuffer::new(&mut depth, WIDTH, HEIGHT, w, 0).unwrap();
                z.clear();
                if fx {
                    whole_frame::<I16F16>(scene, &mut fb, &mut z);
                } else {
                    whole_frame::<f32>(scene, &mut fb, &mut z);
                }
            }
            let whole: Vec<u16> = color.iter().map(|c| c.into_storage()).collect();
            assert!(whole == px, "{name}: strips differ from the whole frame");
            let mut f = Fnv::new();
            f.pixels(&color);
            assert_eq!(f.0, h, "{name}: hash of the strips");
            let bg = scene.background.into_storage();
            let drawn = whole.iter().filter(|&&c| c != bg).count();
            assert!(
                drawn > FRAME_PIXELS / 10,
                "{name}: only {drawn} pixels drawn"
            );
        }
    }
}

/// The host's hash of every fill-rate mode's full-width frame.
fn fill_hashes() -> Vec<(&'static str, u64)> {
    let mut color = vec![Color::BLACK; FRAME_PIXELS];
    let mut depth = vec![0u16; FRAME_PIXELS];
    frames::FILL_MODES
        .iter()
        .map(|&mode| {
            let h = frames::fill_hash(mode, &mut color, &mut depth).expect("a known mode");
            (mode, h)
        })
        .collect()
}

#[test]
fn fill_quads_cover_the_counted_pixels() {
    let mut color = vec![Color::BLACK; FRAME_PIXELS];
    let mut depth = vec![0u16; FRAME_PIXELS];
    for mode in frames::FILL_MODES {
        for (halve, want) in [(false, 76_800), (true, 38_400)] {
            let got = frames::fill(mode, halve, &mut color, &mut depth).unwrap();
            assert_eq!(got, want, "{mode} halve={halve}");
            // Every row is covered: the per-row cost cancels in the
            // difference of the two runs.
            for y in 0..HEIGHT as usize {
                let row = &color[y * WIDTH as usize..(y + 1) * WIDTH as usize];
                let n = row.iter().filter(|&&c| c != Rgb565::BLACK).count();
                assert_eq!(n, want as usize / HEIGHT as usize, "{mode} row {y}");
            }
        }
    }
    assert!(frames::fill("nope", false, &mut color, &mut depth).is_none());
}

#[test]
fn workload_frames_cover_the_documented_range() {
    // WORKLOADS.md: the bunny covers 11.0k-18.2k pixels per frame inside
    // x 66..254, y 8..223.
    let mut color = vec![Color::BLACK; FRAME_PIXELS];
    let mut depth = vec![0u16; FRAME_PIXELS];
    let mut scratch = vec![MeshVertex::default(); frames::BUNNY_VERTS];
    for gouraud in [false, true] {
        let mut storage = vec![Vec3::<f32>::ZERO; frames::WORKLOAD_VEC3S];
        let mut wl = frames::Workload::<f32>::new(gouraud, &mut storage).unwrap();
        for k in [0, 50, 100, 150] {
            let drawn = wl.frame(k, &mut color, &mut depth, &mut scratch);
            assert!(drawn > 1000, "frame {k}: {drawn} triangles");
            let bg = frames::gray565(0);
            let mut n = 0;
            for (i, &c) in color.iter().enumerate() {
                if c != bg {
                    n += 1;
                    let (x, y) = (i % WIDTH as usize, i / WIDTH as usize);
                    assert!(
                        (60..260).contains(&x) && (4..228).contains(&y),
                        "({x}, {y})"
                    );
                }
            }
            assert!((10_500..=18_700).contains(&n), "frame {k}: {n} pixels");
        }
    }
}

/// Parses a firmware `frames` output: `frame` hashes and f32 rows.
struct McuFrames {
    hashes: Vec<(String, String, u64)>,
    rows: std::collections::HashMap<String, Vec<u16>>,
}

fn parse(text: &str) -> McuFrames {
    let mut hashes = Vec::new();
    let mut rows: std::collections::HashMap<String, Vec<u16>> = Default::default();
    for line in text.lines() {
        let f: Vec<&str> = line.split_ascii_whitespace().collect();
        match f.as_slice() {
            ["frame", scene, scalar, h] => {
                let h = u64::from_str_radix(h.trim_start_matches("0x"), 16).expect("hex hash");
                hashes.push((scene.to_string(), scalar.to_string(), h));
            }
            ["row", scene, "f32", y, hex] => {
                let y: usize = y.parse().expect("row number");
                let px = rows
                    .entry(scene.to_string())
                    .or_insert_with(|| vec![0; FRAME_PIXELS]);
                assert_eq!(hex.len(), 4 * WIDTH as usize, "row {y} of {scene}");
                for x in 0..WIDTH as usize {
                    px[y * WIDTH as usize + x] =
                        u16::from_str_radix(&hex[4 * x..4 * x + 4], 16).expect("hex pixel");
                }
            }
            _ => {}
        }
    }
    McuFrames { hashes, rows }
}

/// Prints the `fxhash` line of frame `name` on `triple` (the firmware's
/// hash `got`, the host's `want`); returns 1 if they differ, else 0.
fn compare_fx(name: &str, triple: &str, got: Option<u64>, want: u64) -> u32 {
    match got {
        Some(h) if h == want => {
            println!("fxhash {name} {triple} {h:#018x} equal");
            0
        }
        other => {
            println!("fxhash {name} {triple} {other:x?} DIFFERS from host {want:#018x}");
            1
        }
    }
}

#[test]
fn frames_match_the_mcu() {
    let Ok(dir) = std::env::var("MCU_FRAMES_DIR") else {
        for name in frames::SCENES {
            println!("frame {name} I16F16 {:#018x}", strips::<I16F16>(name).0);
            println!("frame {name} f32 {:#018x}", strips::<f32>(name).0);
        }
        for (mode, h) in fill_hashes() {
            println!("frame fill-{mode} I16F16 {h:#018x}");
        }
        return;
    };
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("MCU_FRAMES_DIR exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "txt"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no TRIPLE.txt in {dir}");
    let host: Vec<_> = frames::SCENES
        .iter()
        .map(|&n| (n, strips::<I16F16>(n).0, strips::<f32>(n)))
        .collect();
    let fills = fill_hashes();
    let mut mismatches = 0;
    for file in files {
        let triple = file.file_stem().unwrap().to_string_lossy().to_string();
        let mcu = parse(&std::fs::read_to_string(&file).unwrap());
        // The fill-rate frames: I16F16 only, compared like the scenes'.
        for (mode, fx) in &fills {
            let name = format!("fill-{mode}");
            let got = mcu
                .hashes
                .iter()
                .find(|(n, sc, _)| *n == name && sc == "I16F16");
            mismatches += compare_fx(&name, &triple, got.map(|h| h.2), *fx);
        }
        for (name, fx, (fl_hash, fl_px)) in &host {
            let get = |s: &str| {
                mcu.hashes
                    .iter()
                    .find(|(n, sc, _)| n == name && sc == s)
                    .map(|h| h.2)
            };
            mismatches += compare_fx(name, &triple, get("I16F16"), *fx);
            let Some(px) = mcu.rows.get(*name) else {
                println!("fdiff {name} {triple} missing");
                mismatches += 1;
                continue;
            };
            let (mut n, mut max) = (0, 0);
            for (&a, &b) in px.iter().zip(fl_px) {
                if a != b {
                    n += 1;
                    let (ca, cb) = (
                        Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(a)),
                        Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(b)),
                    );
                    let d = [
                        ca.r().abs_diff(cb.r()),
                        ca.g().abs_diff(cb.g()),
                        ca.b().abs_diff(cb.b()),
                    ];
                    max = max.max(d.into_iter().max().unwrap());
                }
            }
            // The dump must be the frame the firmware hashed.
            let mut f = Fnv::new();
            for &p in px {
                f.u16(p);
            }
            if Some(f.0) != get("f32") {
                println!("fdiff {name} {triple} dump does not match its hash");
                mismatches += 1;
            }
            let same = if f.0 == *fl_hash { " (hash equal)" } else { "" };
            println!("fdiff {name} {triple} pixels={n} max={max}{same}");
        }
    }
    assert_eq!(
        mismatches, 0,
        "MCU frames differ from the host's (see above)"
    );
}

//! Measures sightline micro-kernels on Cortex-M under QEMU.
//!
//! The command line comes from semihosting (`SYS_GET_CMDLINE`; QEMU's
//! `-semihosting-config ...,arg=A,arg=B`):
//!
//! - `run KERNEL SCALAR N`: runs `N` operations of `KERNEL` (see
//!   [`kernels::KERNELS`]) for `SCALAR` (`I16F16` or `f32`) and exits. Run it
//!   with N and with 0 under the qemu-insn plugin: the difference in guest
//!   instructions over N is the cost per operation. Give N with a fixed
//!   number of digits (e.g. `000256` and `000000`) so that parsing costs the
//!   same in both runs.
//! - `hash`: prints FNV-1a of the I16F16 and f32 results
//!   (`hash I16F16 0x…`, `hash f32 0x…`) and fails if either differs from
//!   [`kernels::FX_HASH_EXPECTED`] / [`kernels::F32_HASH_EXPECTED`], which
//!   the host test checks too, or if a `solve3x3` system fails to solve.
//!
//! - `frames`: renders every scene of [`frames::SCENES`] in I16F16 and f32
//!   at 320×240 through bands and prints `frame SCENE SCALAR 0x…` (FNV-1a
//!   of the frame); f32 frames are also dumped row by row as
//!   `row SCENE f32 Y HEX…` (four hex digits per RGB565 pixel) so that the
//!   host can count differing pixels. Then, for every fill-rate mode
//!   ([`frames::FILL_MODES`]), `frame fill-MODE I16F16 0x…`: the hash of
//!   its full-width fill frame ([`frames::fill_hash`]).
//! - `fill MODE full|half`: fills the fill-rate quad of span shader `MODE`
//!   ([`frames::FILL_MODES`]) [`frames::FILL_REPEAT`] times at full or half
//!   width. The difference in guest instructions over the difference in
//!   pixels is the cost per pixel.
//! - `wl w1|w2 SCALAR NN`: sets up W1 or W2 and renders `NN` of its frames
//!   (every 10th of a turn of 200). Run with 20 and 00: the difference over
//!   20 is the cost per frame.
//!
//! Exit status (semihosting): 0 on success, 1 on a bad command line,
//! mismatch or panic.

#![no_std]
#![no_main]

mod frames;
mod kernels;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hio, hprintln, nr, syscall1};
use panic_semihosting as _;
use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::scalar::I16F16;
use sightline::scalar::Scalar;
use sightline::scene::Color;

/// The semihosting command line (QEMU joins its `arg=` values with spaces).
fn cmdline(buf: &mut [u8]) -> &str {
    let mut block = [buf.as_mut_ptr() as usize, buf.len()];
    // SAFETY: SYS_GET_CMDLINE writes at most `block[1]` bytes into `buf`
    // and the length back into `block[1]`.
    let rc = unsafe { syscall1(nr::GET_CMDLINE, block.as_mut_ptr() as usize) };
    if rc != 0 {
        return "";
    }
    let len = block[1].min(buf.len());
    core::str::from_utf8(&buf[..len]).unwrap_or("")
}

fn parse_u32(s: &str) -> Option<u32> {
    let mut v: u32 = 0;
    if s.is_empty() {
        return None;
    }
    for c in s.bytes() {
        if !c.is_ascii_digit() {
            return None;
        }
        v = v.checked_mul(10)?.checked_add((c - b'0') as u32)?;
    }
    Some(v)
}

fn exit(ok: bool) -> ! {
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    #[allow(clippy::empty_loop)]
    loop {}
}

fn usage(cmd: &str) -> ! {
    hprintln!(
        "bad command line {:?}; expected `run KERNEL SCALAR N`, `hash`, `frames`, `fill MODE full|half`, `wl w1|w2 SCALAR NN` or `sf SCENE SCALAR N`",
        cmd
    );
    hprintln!("kernels: {:?}; scalars: I16F16, f32", kernels::KERNELS);
    hprintln!("fill modes: {:?}", frames::FILL_MODES);
    exit(false)
}

/// The three arguments `WORD SCALAR N` of the `run`, `sf` and `wl`
/// commands (N decimal), or the usage message.
fn word_scalar_count<'a>(
    args: &mut impl Iterator<Item = &'a str>,
    cmd: &str,
) -> (&'a str, &'a str, u32) {
    match (
        args.next(),
        args.next(),
        args.next().and_then(parse_u32),
        args.next(),
    ) {
        (Some(word), Some(scalar), Some(n), None) => (word, scalar, n),
        _ => usage(cmd),
    }
}

#[entry]
fn main() -> ! {
    let mut buf = [0u8; 128];
    let cmd = cmdline(&mut buf);
    let mut args = cmd.split_ascii_whitespace();
    match args.next() {
        Some("run") => {
            let (kernel, scalar, n) = word_scalar_count(&mut args, cmd);
            let ok = match scalar {
                "I16F16" => kernels::run::<I16F16>(kernel, n),
                "f32" => kernels::run::<f32>(kernel, n),
                _ => false,
            };
            if !ok {
                usage(cmd)
            }
            exit(true)
        }
        Some("hash") => {
            let fx = kernels::hash_results::<I16F16>();
            let fl = kernels::hash_results::<f32>();
            hprintln!("hash I16F16 {:#018x}", fx);
            hprintln!("hash f32 {:#018x}", fl);
            let mut ok = true;
            if fx != kernels::FX_HASH_EXPECTED {
                hprintln!(
                    "I16F16 hash mismatch: expected {:#018x}",
                    kernels::FX_HASH_EXPECTED
                );
                ok = false;
            }
            if fl != kernels::F32_HASH_EXPECTED {
                hprintln!(
                    "f32 hash mismatch: expected {:#018x}",
                    kernels::F32_HASH_EXPECTED
                );
                ok = false;
            }
            if !kernels::all_systems_solve::<I16F16>() || !kernels::all_systems_solve::<f32>() {
                hprintln!("a solve3x3 system failed to solve");
                ok = false;
            }
            exit(ok)
        }
        Some("frames") => {
            let ok = all_frames();
            exit(ok)
        }
        Some("fill") => {
            let (Some(mode), Some(width), None) = (args.next(), args.next(), args.next()) else {
                usage(cmd)
            };
            let halve = match width {
                "full" => false,
                "half" => true,
                _ => usage(cmd),
            };
            let (color, depth) = frame_buffers();
            match frames::fill(mode, halve, color, depth) {
                Some(px) => {
                    hprintln!("fill {} {} pixels {}", mode, width, px);
                    exit(true)
                }
                None => usage(cmd),
            }
        }
        Some("sf") => {
            // sf SCENE SCALAR N: N frames of a built-in scene through the
            // scene API (prepared once); N is written with a fixed number
            // of digits by tests/mcu/run so both runs parse alike.
            let (name, scalar, n) = word_scalar_count(&mut args, cmd);
            let (color, depth) = frame_buffers();
            let (fx3, f3, scratch) = scene_buffers();
            let r = match scalar {
                "I16F16" => {
                    frames::scene_frames::<I16F16>(name, n, fx3, scratch, color, depth, |_, _| {})
                }
                "f32" => frames::scene_frames::<f32>(name, n, f3, scratch, color, depth, |_, _| {}),
                _ => usage(cmd),
            };
            match r {
                Ok(()) => {
                    hprintln!("sf {} {} frames {}", name, scalar, n);
                    exit(true)
                }
                Err(e) => {
                    hprintln!("sf {} {} error {:?}", name, scalar, e);
                    exit(false)
                }
            }
        }
        Some("wl") => {
            let (which, scalar, n) = word_scalar_count(&mut args, cmd);
            let gouraud = match which {
                "w1" => false,
                "w2" => true,
                _ => usage(cmd),
            };
            let drawn = match scalar {
                "I16F16" => workload::<I16F16>(gouraud, n, |b| b.0),
                "f32" => workload::<f32>(gouraud, n, |b| b.1),
                _ => usage(cmd),
            };
            match drawn {
                Some(d) => {
                    hprintln!("wl {} {} frames {} triangles {}", which, scalar, n, d);
                    exit(true)
                }
                None => exit(false),
            }
        }
        _ => usage(cmd),
    }
}

const FRAME: usize = frames::FRAME_PIXELS;
static mut COLOR: [Color; FRAME] = [Color::new(0, 0, 0); FRAME];
static mut DEPTH: [u16; FRAME] = [0; FRAME];
/// Prepared-scene storage: the largest of the built-in scenes and W1/W2.
const VEC3S: usize = if frames::STORAGE.vec3s > frames::WORKLOAD_VEC3S {
    frames::STORAGE.vec3s
} else {
    frames::WORKLOAD_VEC3S
};
const VERTICES: usize = if frames::STORAGE.vertices > frames::BUNNY_VERTS {
    frames::STORAGE.vertices
} else {
    frames::BUNNY_VERTS
};
static mut VEC3_FX: [Vec3<I16F16>; VEC3S] = [Vec3::ZERO; VEC3S];
static mut VEC3_F32: [Vec3<f32>; VEC3S] = [Vec3::ZERO; VEC3S];
static mut SCRATCH: [MeshVertex<1>; VERTICES] = [MeshVertex {
    outcode: 0,
    screen: sightline::raster::ScreenVertex::new(0, 0, 0, [0]),
}; VERTICES];

/// The whole-frame color and depth buffers (in .bss, not on the stack).
fn frame_buffers() -> (&'static mut [Color], &'static mut [u16]) {
    // SAFETY: called once per run (each command takes them at most once),
    // single-threaded, no interrupts touch them.
    unsafe {
        (
            &mut *core::ptr::addr_of_mut!(COLOR),
            &mut *core::ptr::addr_of_mut!(DEPTH),
        )
    }
}

type SceneBuffers = (
    &'static mut [Vec3<I16F16>],
    &'static mut [Vec3<f32>],
    &'static mut [MeshVertex<1>],
);

/// Prepared-scene storage in both scalars and the frame scratch (in .bss).
fn scene_buffers() -> SceneBuffers {
    // SAFETY: as `frame_buffers`: taken once per run, single-threaded.
    unsafe {
        (
            &mut *core::ptr::addr_of_mut!(VEC3_FX),
            &mut *core::ptr::addr_of_mut!(VEC3_F32),
            &mut *core::ptr::addr_of_mut!(SCRATCH),
        )
    }
}

/// Renders every scene in both scalars; prints hashes and the f32 rows.
fn all_frames() -> bool {
    let (color, depth) = frame_buffers();
    let (fx3, f3, scratch) = scene_buffers();
    let mut out = hio::hstdout().ok();
    let mut ok = true;
    for name in frames::SCENES {
        for fx in [true, false] {
            let scalar = if fx { "I16F16" } else { "f32" };
            let mut line = [0u8; 64 + 4 * frames::WIDTH as usize];
            let dump = |y: u16, px: &[Color]| {
                if fx {
                    return;
                }
                let n = row_line(&mut line, name, y, px);
                if let Some(o) = out.as_mut() {
                    let _ = o.write_all(&line[..n]);
                }
            };
            let r = if fx {
                frames::render_scene::<I16F16>(name, fx3, scratch, color, depth, dump)
            } else {
                frames::render_scene::<f32>(name, f3, scratch, color, depth, dump)
            };
            match r {
                Ok(h) => hprintln!("frame {} {} {:#018x}", name, scalar, h),
                Err(e) => {
                    hprintln!("frame {} {} error {:?}", name, scalar, e);
                    ok = false;
                }
            }
        }
    }
    for mode in frames::FILL_MODES {
        match frames::fill_hash(mode, color, depth) {
            Some(h) => hprintln!("frame fill-{} I16F16 {:#018x}", mode, h),
            None => {
                hprintln!("frame fill-{} I16F16 error", mode);
                ok = false;
            }
        }
    }
    ok
}

/// Formats `row NAME f32 Y HEX…\n` into `line`; returns its length.
fn row_line(line: &mut [u8], name: &str, y: u16, px: &[Color]) -> usize {
    use embedded_graphics::pixelcolor::IntoStorage;
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let mut n = 0;
    let mut put = |b: u8| {
        if n < line.len() {
            line[n] = b;
            n += 1;
        }
    };
    for &b in b"row " {
        put(b);
    }
    for &b in name.as_bytes() {
        put(b);
    }
    for &b in b" f32 " {
        put(b);
    }
    for d in [y / 100, y / 10 % 10, y % 10] {
        put(b'0' + d as u8);
    }
    put(b' ');
    for &c in px {
        let v = c.into_storage();
        for s in [12, 8, 4, 0] {
            put(HEX[((v >> s) & 15) as usize]);
        }
    }
    put(b'\n');
    n
}

/// Runs `n` frames of W1 or W2 (frames 0, 10, 20, … of a turn of 200),
/// with the storage `pick` chooses for scalar `S`.
fn workload<S: Scalar>(
    gouraud: bool,
    n: u32,
    pick: impl FnOnce(SceneBuffers) -> &'static mut [Vec3<S>],
) -> Option<u32> {
    let buffers = scene_buffers();
    let scratch = buffers.2;
    let mut wl = frames::Workload::<S>::new(gouraud, pick((buffers.0, buffers.1, &mut [])))?;
    let (color, depth) = frame_buffers();
    let mut drawn = 0;
    for i in 0..n {
        drawn = wl.frame(i * frames::WORKLOAD_STEP, color, depth, scratch);
    }
    Some(drawn)
}

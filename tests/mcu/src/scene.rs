//! Size and RAM firmware: renders the built-in scenes its cargo features
//! select, at 320×240 in I16F16 through strips of [`ROWS`] rows with a
//! band-sized u16 depth buffer, and nothing else. `tests/mcu/run` builds it
//! once per scene set and target to measure .text/.rodata/.data/.bss, and
//! runs the ARM builds under QEMU to measure the stack high-water mark.
//!
//! | firmware feature | scenes | sightline features |
//! |---|---|---|
//! | `scene-flat` | cube (flat shading, depth) | `depth` |
//! | `scene-gouraud` | bunny (Gouraud + flat floor, depth) | `gouraud`, `depth` |
//! | `scene-texture` | corridor (perspective texture, depth) | `texture`, `perspective`, `depth` |
//! | `scene-all` | every built-in scene; spheres through the ray path | `full` |
//!
//! No `core::fmt`: the output (semihosting on ARM) is formatted by hand and
//! the panic handler exits without a message, so the figures are the
//! renderer's and not the formatter's. On ARM it prints
//! `scene hash 0x… stack N` and exits 0; on RISC-V (built for size only,
//! never run) it loops after rendering.

#![no_std]
#![no_main]

use core::hint::black_box;
#[cfg(feature = "scene-all")]
use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::raster::DepthBuffer;
use sightline::scalar::I16F16;
#[cfg(feature = "scene-all")]
use sightline::scene::{self, PreparedObject, Renderer, Scene, Storage, builtin};
use sightline::scene::{Color, Frame};
use sightline::target::Band;

#[cfg(not(any(
    feature = "scene-flat",
    feature = "scene-gouraud",
    feature = "scene-texture",
    feature = "scene-all"
)))]
compile_error!("select the scenes with one scene-* feature");
#[cfg(any(
    all(feature = "scene-flat", feature = "scene-gouraud"),
    all(feature = "scene-flat", feature = "scene-texture"),
    all(feature = "scene-flat", feature = "scene-all"),
    all(feature = "scene-gouraud", feature = "scene-texture"),
    all(feature = "scene-gouraud", feature = "scene-all"),
    all(feature = "scene-texture", feature = "scene-all"),
))]
compile_error!("select one scene-* feature only (build with --no-default-features)");

/// The flat, Gouraud and textured firmwares draw one scene each, prepared
/// on the host by build.rs (`sightline::scene::export`) into const I16F16
/// data: no f32 arithmetic, normalization or camera solving runs here
/// (`tests/mcu/run` checks that they link no solver and no floating point).
#[cfg(feature = "scene-flat")]
mod prepared {
    include!(concat!(env!("OUT_DIR"), "/cube.rs"));
}
#[cfg(feature = "scene-gouraud")]
mod prepared {
    include!(concat!(env!("OUT_DIR"), "/bunny.rs"));
}
#[cfg(feature = "scene-texture")]
mod prepared {
    include!(concat!(env!("OUT_DIR"), "/corridor.rs"));
}

/// The full firmware prepares every built-in scene at run time, from its
/// f32 description, as a host does.
#[cfg(feature = "scene-all")]
static SCENES: [&Scene<'static>; 5] = builtin::ALL;

const WIDTH: u16 = 320;
const HEIGHT: u16 = 240;
/// Rows per strip: 320·15·(2 + 2) = 19 200 bytes of buffers, 16 strips a
/// frame. (16 rows, 20 480 bytes, put the textured corridor's RAM 856
/// bytes over the 24 KiB goal.) `tests/mcu/run` reads this line.
const ROWS: u16 = 15;
const BAND: usize = WIDTH as usize * ROWS as usize;

static mut COLOR: [Color; BAND] = [Color::new(0, 0, 0); BAND];
static mut DEPTH: [u16; BAND] = [0; BAND];

/// Scratch vertices a frame needs.
#[cfg(not(feature = "scene-all"))]
const VERTICES: usize = {
    assert!(prepared::WIDTH == WIDTH && prepared::HEIGHT == HEIGHT);
    prepared::VERTICES
};
/// The largest storage any scene of [`SCENES`] needs.
#[cfg(feature = "scene-all")]
const STORAGE: Storage = Storage::for_any(&SCENES);
#[cfg(feature = "scene-all")]
const VERTICES: usize = STORAGE.vertices;
#[cfg(feature = "scene-all")]
static mut VEC3S: [Vec3<I16F16>; STORAGE.vec3s] = [Vec3::ZERO; STORAGE.vec3s];
static mut SCRATCH: [MeshVertex<1>; VERTICES] = [MeshVertex {
    outcode: 0,
    screen: sightline::raster::ScreenVertex::new(0, 0, 0, [0]),
}; VERTICES];

/// Draws `frame` strip by strip into the band buffers, hashing each.
fn draw_strips(frame: &Frame<'_, '_, I16F16>, h: &mut u64) -> Result<(), ()> {
    // SAFETY: the only references to the band buffers, taken once per
    // call and dropped at its end; `render` calls this from one thread.
    let (color, depth) = unsafe {
        (
            &mut *core::ptr::addr_of_mut!(COLOR),
            &mut *core::ptr::addr_of_mut!(DEPTH),
        )
    };
    for y0 in (0..HEIGHT).step_by(ROWS as usize) {
        let w = WIDTH as usize;
        let mut band = Band::new(&mut color[..], WIDTH, ROWS, w, y0 as i32).map_err(|_| ())?;
        let mut z = DepthBuffer::new(&mut depth[..], WIDTH, ROWS, w, y0 as i32).map_err(|_| ())?;
        z.clear();
        // The cube scene stays in front of the near plane and within 1024
        // pixels of the viewport (its floor too): it draws without the
        // clipper, and the firmware links none. The bunny's floor reaches
        // further and the corridor's textured walls are clipped at the
        // sides: those firmwares draw with `Frame::draw`.
        #[cfg(feature = "scene-flat")]
        frame.draw_unclipped(&mut band, &mut z).map_err(|_| ())?;
        #[cfg(not(feature = "scene-flat"))]
        frame.draw(&mut band, &mut z);
        hash_pixels(h, &color[..]);
    }
    Ok(())
}

/// FNV-1a over every pixel of the scene, row by row (0 on any error).
#[cfg(not(feature = "scene-all"))]
fn render() -> u64 {
    // SAFETY: the only reference to the scratch, taken once.
    let scratch = unsafe { &mut *core::ptr::addr_of_mut!(SCRATCH) };
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let (Ok(mut objects), Ok(renderer)) = (prepared::objects(), prepared::renderer()) else {
        return 0;
    };
    let Ok(frame) = renderer.project(black_box(&mut objects[..]), &mut scratch[..]) else {
        return 0;
    };
    match draw_strips(&frame, &mut h) {
        Ok(()) => h,
        Err(()) => 0,
    }
}

/// FNV-1a over every pixel of every scene, row by row (0 on any error).
#[cfg(feature = "scene-all")]
fn render() -> u64 {
    // SAFETY: the only references to these buffers, taken once.
    let (color, vec3s, scratch) = unsafe {
        (
            &mut *core::ptr::addr_of_mut!(COLOR),
            &mut *core::ptr::addr_of_mut!(VEC3S),
            &mut *core::ptr::addr_of_mut!(SCRATCH),
        )
    };
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for scene in black_box(&SCENES).iter() {
        if !scene.spheres.is_empty() {
            let Ok(view) = scene.view::<I16F16>(WIDTH, HEIGHT) else {
                return 0;
            };
            let Ok(ray) = scene::RayScene::new(scene, &view) else {
                return 0;
            };
            for y0 in (0..HEIGHT).step_by(ROWS as usize) {
                let w = WIDTH as usize;
                let Ok(mut band) = Band::new(&mut color[..], WIDTH, ROWS, w, y0 as i32) else {
                    return 0;
                };
                ray.render(&mut band);
                hash_pixels(&mut h, &color[..]);
            }
            continue;
        }
        // Prepared once, projected once per frame, drawn per strip.
        let mut objects = [PreparedObject::EMPTY; STORAGE.objects];
        let Ok(objects) = scene.prepare(&mut vec3s[..], &mut objects) else {
            return 0;
        };
        let Ok(renderer) = Renderer::new(scene, WIDTH, HEIGHT) else {
            return 0;
        };
        let Ok(frame) = renderer.project(objects, &mut scratch[..]) else {
            return 0;
        };
        if draw_strips(&frame, &mut h).is_err() {
            return 0;
        }
    }
    h
}

fn hash_pixels(h: &mut u64, px: &[Color]) {
    use embedded_graphics::pixelcolor::IntoStorage;
    for &c in px {
        for b in c.into_storage().to_le_bytes() {
            *h ^= b as u64;
            *h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

#[cfg(target_arch = "arm")]
mod arm {
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hio};

    const PAINT: u32 = 0xa5a5_a5a5;
    /// Bytes below the stack pointer painted at start-up.
    const PAINT_BYTES: usize = 64 * 1024;

    unsafe extern "C" {
        static _stack_start: u32;
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        debug::exit(debug::EXIT_FAILURE);
        loop {
            core::hint::spin_loop();
        }
    }

    /// Paints [sp − PAINT_BYTES, sp − 256) with [`PAINT`]; returns the
    /// lowest painted address.
    #[inline(never)]
    fn paint() -> usize {
        let sp = cortex_m::register::msp::read() as usize;
        let lo = sp - PAINT_BYTES;
        let mut p = lo;
        while p < sp - 256 {
            // SAFETY: RAM below the live stack (QEMU's mps2 RAM is 4 MiB,
            // the statics sit at its bottom), not in use yet.
            unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
            p += 4;
        }
        lo
    }

    /// Bytes of stack used: from the top of RAM down to the lowest word
    /// that no longer holds the paint.
    fn high_water(lo: usize) -> usize {
        let top = core::ptr::addr_of!(_stack_start) as usize;
        let mut p = lo;
        // SAFETY: reads of the painted region.
        while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
            p += 4;
        }
        top - p
    }

    fn hex(out: &mut [u8], mut n: usize, v: u64, digits: u32) -> usize {
        for i in (0..digits).rev() {
            out[n] = b"0123456789abcdef"[((v >> (4 * i)) & 15) as usize];
            n += 1;
        }
        n
    }

    #[entry]
    fn main() -> ! {
        let lo = paint();
        let h = super::render();
        let used = high_water(lo);
        let mut line = [0u8; 64];
        let mut n = 0;
        for &b in b"scene hash 0x" {
            line[n] = b;
            n += 1;
        }
        n = hex(&mut line, n, h, 16);
        for &b in b" stack 0x" {
            line[n] = b;
            n += 1;
        }
        n = hex(&mut line, n, used as u64, 8);
        line[n] = b'\n';
        n += 1;
        if let Ok(mut o) = hio::hstdout() {
            let _ = o.write_all(&line[..n]);
        }
        debug::exit(if h != 0 {
            debug::EXIT_SUCCESS
        } else {
            debug::EXIT_FAILURE
        });
        loop {
            core::hint::spin_loop();
        }
    }
}

#[cfg(target_arch = "riscv32")]
mod riscv {
    // Minimal start-up for a size build (never run): stack pointer from
    // the linker script `riscv.x`, then `rmain`. .data is not copied and
    // .bss is not zeroed, which a real runtime (riscv-rt) would do.
    core::arch::global_asm!(
        ".section .text.start, \"ax\"",
        ".globl _start",
        "_start:",
        "la sp, _stack_start",
        "call rmain",
        "1: j 1b",
    );

    #[unsafe(no_mangle)]
    extern "C" fn rmain() -> ! {
        let h = super::render();
        // SAFETY: a write to a static the linker keeps (the result must
        // not be optimized away).
        unsafe { core::ptr::write_volatile(core::ptr::addr_of_mut!(RESULT), h) };
        loop {
            core::hint::spin_loop();
        }
    }

    static mut RESULT: u64 = 0;

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        loop {
            core::hint::spin_loop();
        }
    }
}

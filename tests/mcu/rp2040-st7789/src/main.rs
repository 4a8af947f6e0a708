//! sightline on an RP2040 with an ST7789 240×240 SPI display.
//!
//! Renders the built-in Gouraud-lit bunny ([`sightline::scene::builtin::BUNNY`])
//! in I16F16 fixed point (the RP2040's Cortex-M0+ has no FPU), turning it a
//! little every frame. The scene is prepared on the host by build.rs
//! (`sightline::scene::export`) into const data in flash, so the firmware
//! does no floating point. The frame is drawn in strips of [`BAND_ROWS`] rows:
//! each strip is rendered into a small color band and a matching depth
//! band, then pushed to the display's window for those rows. RAM for the
//! picture is 240·16·(2 + 2) bytes = 15 KiB instead of 225 KiB for a whole
//! frame with depth.
//!
//! Wiring (see README.md): SPI0, SCK = GPIO18, MOSI = GPIO19, CS = GPIO17,
//! DC = GPIO16, RST = GPIO20, backlight = GPIO21; 62.5 MHz SPI mode 3.

#![no_std]
#![no_main]

use core::panic::PanicInfo;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::MODE_3;
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::Builder;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use rp2040_hal::{self as hal, Clock, fugit::RateExtU32, pac};
use sightline::pipeline::MeshVertex;
use sightline::raster::DepthBuffer;
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::Color;
use sightline::target::Band;

/// The built-in bunny prepared for this display (build.rs).
mod bunny {
    include!(concat!(env!("OUT_DIR"), "/bunny.rs"));
}

/// The second-stage bootloader for the W25Q080 flash of the Pico (and
/// most RP2040 boards); it goes in the `.boot2` section (`memory.x`).
#[unsafe(link_section = ".boot2")]
#[used]
pub static BOOT2: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The board's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;
/// Display side in pixels.
const SIDE: u16 = 240;
/// Rows per strip.
const BAND_ROWS: u16 = 16;
const BAND_PIXELS: usize = SIDE as usize * BAND_ROWS as usize;
const _: () = assert!(bunny::WIDTH == SIDE && bunny::HEIGHT == SIDE);
/// 1/64 of a turn, 2π/64 rad, in 16.16 (0.098175 · 65536 = 6433.98).
const STEP: I16F16 = I16F16::from_bits(6434);

/// On a panic, stop: a board without a debugger shows the last frame.
#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .unwrap();
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // SPI0 on GPIO18 (SCK) and GPIO19 (MOSI); the ST7789 never talks back.
    let sck = pins.gpio18.into_function::<hal::gpio::FunctionSpi>();
    let mosi = pins.gpio19.into_function::<hal::gpio::FunctionSpi>();
    let spi = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI0, (mosi, sck)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_3,
    );
    let cs = pins.gpio17.into_push_pull_output();
    let dc = pins.gpio16.into_push_pull_output();
    let rst = pins.gpio20.into_push_pull_output();
    let mut backlight = pins.gpio21.into_push_pull_output();
    let spi = ExclusiveDevice::new_no_delay(spi, cs).unwrap();
    let mut spi_buffer = [0u8; 512];
    let di = SpiInterface::new(spi, dc, &mut spi_buffer);
    let mut display = Builder::new(ST7789, di)
        .display_size(SIDE, SIDE)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer)
        .unwrap();
    backlight.set_high().unwrap();

    let mut color = [Color::new(0, 0, 0); BAND_PIXELS];
    let mut depth = [0u16; BAND_PIXELS];
    // Prepared on the host by build.rs: the objects borrow positions and
    // normals in flash; the renderer holds camera, projection, clip volume
    // and light.
    let mut objects = bunny::objects().unwrap();
    let renderer = bunny::renderer().unwrap();
    let mut scratch = [MeshVertex::default(); bunny::VERTICES];
    let yaw0 = objects[1].pose.angles.yaw;
    let mut frame: i32 = 0;
    loop {
        // Turn the bunny 1/64 of a turn per frame: each vertex is
        // transformed and projected once per frame, then drawn per strip.
        objects[1].pose.angles.yaw = yaw0 + STEP * I16F16::from_i32(frame % 64);
        let Ok(projected) = renderer.project(&mut objects, &mut scratch) else {
            continue;
        };
        for y0 in (0..SIDE).step_by(BAND_ROWS as usize) {
            let rows = BAND_ROWS.min(SIDE - y0);
            let n = SIDE as usize * rows as usize;
            let mut band =
                Band::new(&mut color[..n], SIDE, rows, SIDE as usize, y0 as i32).unwrap();
            let mut zb =
                DepthBuffer::new(&mut depth[..n], SIDE, rows, SIDE as usize, y0 as i32).unwrap();
            zb.clear();
            projected.draw(&mut band, &mut zb);
            // Push the strip to rows y0..y0+rows of the display.
            let _ = display.set_pixels(0, y0, SIDE - 1, y0 + rows - 1, color[..n].iter().copied());
        }
        frame = frame.wrapping_add(1);
    }
}

//! Images in the scene color (Rgb565), PNG output and comparison.

use sightline::scene::Color;
use std::path::Path;

use embedded_graphics::pixelcolor::RgbColor;

/// A `width`×`height` image, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: u16,
    /// Height in pixels.
    pub height: u16,
    /// The pixels, row-major.
    pub pixels: Vec<Color>,
}

/// Rgb565 → 8-bit RGB by bit replication (0 → 0, full → 255).
#[must_use]
pub fn to_rgb8(c: Color) -> [u8; 3] {
    let (r, g, b) = (c.r(), c.g(), c.b());
    [
        (r << 3) | (r >> 2),
        (g << 2) | (g >> 4),
        (b << 3) | (b >> 2),
    ]
}

impl Image {
    /// An image filled with `c`.
    #[must_use]
    pub fn new(width: u16, height: u16, c: Color) -> Self {
        Self {
            width,
            height,
            pixels: vec![c; width as usize * height as usize],
        }
    }

    /// The pixels as 8-bit RGB bytes.
    #[must_use]
    pub fn rgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|&c| to_rgb8(c)).collect()
    }

    /// Writes the image as an 8-bit RGB PNG.
    ///
    /// # Errors
    /// I/O or encoder errors, as text.
    pub fn write_png(&self, path: &Path) -> Result<(), String> {
        write_rgb8_png(path, self.width, self.height, &self.rgb8())
    }
}

/// Writes 8-bit RGB bytes as a PNG.
///
/// # Errors
/// I/O or encoder errors, as text naming the file.
pub fn write_rgb8_png(path: &Path, width: u16, height: u16, rgb: &[u8]) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: cannot write PNG: {e}", path.display());
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), width as u32, height as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().map_err(|e| err(&e))?;
    w.write_image_data(rgb).map_err(|e| err(&e))?;
    w.finish().map_err(|e| err(&e))?;
    Ok(())
}

/// A decoded PNG as 8-bit RGB.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgb8Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGB bytes, row-major.
    pub rgb: Vec<u8>,
}

/// Reads any 8-bit-convertible PNG as RGB (gray is expanded, alpha
/// dropped).
///
/// # Errors
/// I/O or decoder errors, as text naming the file.
pub fn read_png_rgb8(path: &Path) -> Result<Rgb8Image, String> {
    read_png_rgb8_limited(path, u32::MAX)
}

/// As [`read_png_rgb8`], but refuses a PNG wider or taller than
/// `max_side` pixels after reading only its header (before any pixel data
/// is decoded or memory for it is allocated).
///
/// # Errors
/// As [`read_png_rgb8`]; a too large image names the file and its size.
pub fn read_png_rgb8_limited(path: &Path, max_side: u32) -> Result<Rgb8Image, String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: cannot read PNG: {e}", path.display());
    let file = std::fs::File::open(path).map_err(|e| err(&e))?;
    let mut dec = png::Decoder::new(std::io::BufReader::new(file));
    dec.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = dec.read_info().map_err(|e| err(&e))?;
    let (w, h) = (reader.info().width, reader.info().height);
    if w > max_side || h > max_side {
        return Err(format!(
            "{} is {w}x{h} pixels: expected at most {max_side}x{max_side}",
            path.display()
        ));
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| err(&"image too large"))?;
    let mut buf = vec![0; size];
    let info = reader.next_frame(&mut buf).map_err(|e| err(&e))?;
    buf.truncate(info.buffer_size());
    let n = info.width as usize * info.height as usize;
    let rgb: Vec<u8> = match info.color_type {
        png::ColorType::Rgb => buf,
        png::ColorType::Rgba => buf
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect(),
        png::ColorType::Grayscale => buf.iter().flat_map(|&g| [g, g, g]).collect(),
        png::ColorType::GrayscaleAlpha => buf
            .chunks_exact(2)
            .flat_map(|p| [p[0], p[0], p[0]])
            .collect(),
        png::ColorType::Indexed => return Err(err(&"indexed color was not expanded")),
    };
    if rgb.len() != n * 3 {
        return Err(err(&"unexpected buffer size"));
    }
    Ok(Rgb8Image {
        width: info.width,
        height: info.height,
        rgb,
    })
}

/// How two images of the same scene agree.
///
/// `equal`: pixels with identical Rgb565 values. `within`: pixels whose
/// channels differ by at most one step of Rgb565 in red and blue and two in
/// green (one intensity quantum of the material model moves a channel by
/// at most that much) — equal pixels included.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Agreement {
    /// Pixels compared.
    pub total: usize,
    /// Pixels exactly equal.
    pub equal: usize,
    /// Pixels within tolerance (including equal ones).
    pub within: usize,
}

impl Agreement {
    /// Percent of pixels exactly equal.
    #[must_use]
    pub fn equal_percent(&self) -> f64 {
        100.0 * self.equal as f64 / self.total.max(1) as f64
    }

    /// Percent of pixels within tolerance.
    #[must_use]
    pub fn within_percent(&self) -> f64 {
        100.0 * self.within as f64 / self.total.max(1) as f64
    }
}

fn within_tolerance(a: Color, b: Color) -> bool {
    a.r().abs_diff(b.r()) <= 1 && a.g().abs_diff(b.g()) <= 2 && a.b().abs_diff(b.b()) <= 1
}

/// Compares two images pixel by pixel (sizes must match).
///
/// # Panics
/// If the sizes differ.
#[must_use]
pub fn agreement(a: &Image, b: &Image) -> Agreement {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "image sizes differ"
    );
    let mut r = Agreement {
        total: a.pixels.len(),
        equal: 0,
        within: 0,
    };
    for (&p, &q) in a.pixels.iter().zip(&b.pixels) {
        r.equal += usize::from(p == q);
        r.within += usize::from(within_tolerance(p, q));
    }
    r
}

/// A diff image: equal pixels as a dimmed gray of `a`, pixels within
/// tolerance yellow, others red.
#[must_use]
pub fn diff_rgb8(a: &Image, b: &Image) -> Vec<u8> {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(&p, &q)| {
            if p == q {
                let [r, g, bl] = to_rgb8(p);
                let y = ((r as u16 + g as u16 + bl as u16) / 9) as u8;
                [y, y, y]
            } else if within_tolerance(p, q) {
                [255, 220, 0]
            } else {
                [255, 0, 0]
            }
        })
        .collect()
}

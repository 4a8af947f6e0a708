//! Helpers shared by the unit tests (compiled only for `cfg(test)`): a
//! seeded PRNG, test-only targets, and the exact coverage oracle shared by
//! the raster and pipeline tests.

use crate::raster::ScreenVertex;
use crate::target::{Rect, Target};
use std::string::String;
use std::vec;
use std::vec::Vec;

/// SplitMix64: a tiny, seeded, portable PRNG so tests are reproducible
/// without a dependency.
#[derive(Debug, Clone)]
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `lo..=hi`.
    pub(crate) fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % ((hi - lo + 1) as u64)) as i64
    }
    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Approximately standard normal (sum of 12 uniforms − 6).
    pub(crate) fn normal(&mut self) -> f64 {
        (0..12).map(|_| self.unit()).sum::<f64>() - 6.0
    }
}

/// A character framebuffer that panics on a write outside its rectangle
/// and (unless allowed) on writing a pixel twice: the fill rule's test
/// (embedded-graphics' `MockDisplay` idea).
#[derive(Debug)]
pub struct MockTarget {
    pub w: i32,
    pub h: i32,
    pub px: Vec<char>,
    pub allow_overdraw: bool,
    pub writes: Vec<u32>,
}

impl MockTarget {
    pub fn new(w: i32, h: i32) -> Self {
        Self {
            w,
            h,
            px: vec!['.'; (w * h) as usize],
            allow_overdraw: false,
            writes: vec![0; (w * h) as usize],
        }
    }

    fn put(&mut self, x: i32, y: i32, c: char) {
        assert!(
            x >= 0 && x < self.w && y >= 0 && y < self.h,
            "out-of-bounds write at ({x}, {y})"
        );
        let i = (y * self.w + x) as usize;
        assert!(
            self.allow_overdraw || self.writes[i] == 0,
            "overdraw at ({x}, {y})"
        );
        self.writes[i] += 1;
        self.px[i] = c;
    }

    pub fn rows(&self) -> Vec<String> {
        self.px
            .chunks(self.w as usize)
            .map(|r| r.iter().collect())
            .collect()
    }

    #[track_caller]
    pub fn assert_pattern(&self, pattern: &[&str]) {
        let rows = self.rows();
        let got: Vec<&str> = rows.iter().map(String::as_str).collect();
        assert_eq!(got, pattern, "\ngot:\n{}\n", rows.join("\n"));
    }
}

impl Target for MockTarget {
    type Color = char;
    fn clip_rect(&self) -> Rect {
        Rect::new(0, 0, self.w, self.h)
    }
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: char) {
        for i in 0..len as i32 {
            self.put(x + i, y, color);
        }
    }
    fn fill_with<F: FnMut() -> char>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        for i in 0..len as i32 {
            let c = colors();
            self.put(x + i, y, c);
        }
    }
}

/// Pixel (i, j) is covered by the convex polygon under the top-left rule,
/// computed from exact i128 edge functions at the center (16i+8, 16j+8).
/// Independent of the scan converter: no stepping, no chains.
pub fn oracle_covers<const VARYINGS: usize>(
    poly: &[ScreenVertex<VARYINGS>],
    i: i64,
    j: i64,
) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let p: Vec<(i128, i128)> = poly.iter().map(|v| (v.x as i128, v.y as i128)).collect();
    let mut area: i128 = 0;
    for k in 0..n {
        let (a, b) = (p[k], p[(k + 1) % n]);
        area += a.0 * b.1 - a.1 * b.0;
    }
    if area == 0 {
        return false;
    }
    let (cx, cy) = (16 * i as i128 + 8, 16 * j as i128 + 8);
    for k in 0..n {
        // Orient so that the interior is where cross(b − a, p − a) > 0.
        let (a, b) = if area > 0 {
            (p[k], p[(k + 1) % n])
        } else {
            (p[(k + 1) % n], p[k])
        };
        let d = (b.0 - a.0, b.1 - a.1);
        if d == (0, 0) {
            continue;
        }
        let e = d.0 * (cy - a.1) - d.1 * (cx - a.0);
        // y down: with this orientation a top edge runs to +x with the
        // interior below; a left edge runs up (−y).
        let top_left = (d.1 == 0 && d.0 > 0) || d.1 < 0;
        if e < 0 || (e == 0 && !top_left) {
            return false;
        }
    }
    true
}

/// 28.4 from pixels.
pub fn sp(v: f64) -> i32 {
    (v * 16.0).round() as i32
}

pub fn sv(x: f64, y: f64) -> ScreenVertex<0> {
    ScreenVertex::new(sp(x), sp(y), 0, [])
}

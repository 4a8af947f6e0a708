//! `raster`: the scan converter (`raster::fill_polygon`) and the whole
//! pipeline (`Pipeline::draw_polygon`, f32) on random polygons, including
//! huge, out-of-limit, sliver, self-intersecting and (through the
//! pipeline) NaN ones, drawn into a *guarded* buffer: a band of W×H pixels
//! (stride W + pad, frame rows y0..y0+H) cut out of the middle of a larger
//! array, with a depth buffer guarded the same way.
//!
//! Oracle:
//! - nothing outside the band's pixels changes in either array (guard rows
//!   above and below, the stride padding, guard columns);
//! - through a recording target: every span lies inside the clip
//!   rectangle, at most one span per row;
//! - triangles with in-range vertices: the set of pixels drawn equals the
//!   exact coverage at pixel centers, computed with i64 edge functions and
//!   the documented top-left rule (left and horizontal top edges closed,
//!   right and bottom edges open); so two triangles sharing an edge
//!   (ABC, CBD with A and D on opposite sides) never both write a pixel,
//!   which is asserted directly as well.
#![no_main]

mod common;

use arbitrary::Arbitrary;
use common::Num;
use libfuzzer_sys::fuzz_target;
use sightline::camera::Projection;
use sightline::math::Vec3;
use sightline::pipeline::{Intensity, Pipeline, Vertex};
use sightline::raster::{
    COORD_LIMIT, DepthBuffer, Flat, Gouraud, NoDepth, ScreenVertex, fill_polygon,
};
use sightline::target::{Band, Rect, Target};

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Coord {
    /// Pixel k plus a subpixel offset (28.4), near the target.
    Near(i8, u8),
    /// Any 28.4 value within the limit.
    Limit(i32),
    /// Any i32 (may exceed the limit: rejected).
    Any(i32),
}

impl Coord {
    fn v(self) -> i32 {
        match self {
            Coord::Near(k, s) => k as i32 * 16 + (s % 16) as i32,
            Coord::Limit(x) => x % (COORD_LIMIT + 1),
            Coord::Any(x) => x,
        }
    }
}

#[derive(Arbitrary, Debug)]
enum Mode {
    Poly(Vec<(Coord, Coord, u16, i32)>),
    Shared([(i8, u8, i8, u8); 4]),
    Pipe {
        focus: u8,
        verts: Vec<([Num; 3], Num)>,
    },
}

#[derive(Arbitrary, Debug)]
struct Input {
    w: u8,
    h: u8,
    pad: u8,
    y0: i8,
    depth: bool,
    gouraud: bool,
    mode: Mode,
}

const G: usize = 3; // guard rows and columns
const SENTINEL: u8 = 0xA5;
const KEY_SENTINEL: u16 = 0xA5A5;

struct Guarded {
    w: usize,
    h: usize,
    stride: usize,
    y0: i32,
    px: Vec<u8>,
    keys: Vec<u16>,
}

impl Guarded {
    fn new(w: usize, h: usize, pad: usize, y0: i32) -> Self {
        let stride = w + pad;
        let total = (h + 2 * G) * stride + 2 * G;
        let mut g = Guarded {
            w,
            h,
            stride,
            y0,
            px: vec![SENTINEL; total],
            keys: vec![KEY_SENTINEL; total],
        };
        for r in 0..h {
            for c in 0..w {
                let i = g.index(r, c);
                g.px[i] = 0;
                g.keys[i] = u16::MAX;
            }
        }
        g
    }
    fn start(&self) -> usize {
        G * self.stride + G
    }
    fn index(&self, r: usize, c: usize) -> usize {
        self.start() + r * self.stride + c
    }
    fn len(&self) -> usize {
        self.stride * (self.h - 1) + self.w
    }
    /// Asserts the guard is intact; returns the drawn pixels (frame
    /// coordinates).
    fn check(&self) -> Vec<(i32, i32)> {
        let mut drawn = Vec::new();
        let mut inside = vec![false; self.px.len()];
        for r in 0..self.h {
            for c in 0..self.w {
                let i = self.index(r, c);
                inside[i] = true;
                if self.px[i] != 0 {
                    drawn.push((c as i32, r as i32 + self.y0));
                }
            }
        }
        for (i, (&p, &k)) in self.px.iter().zip(&self.keys).enumerate() {
            if !inside[i] {
                assert_eq!(p, SENTINEL, "pixel write outside the band at element {i}");
                assert_eq!(
                    k, KEY_SENTINEL,
                    "depth write outside the band at element {i}"
                );
            }
        }
        drawn
    }
}

/// Records spans; asserts they are inside the clip rectangle and at most
/// one per row per polygon.
struct Recorder {
    clip: Rect,
    rows: Vec<(i32, i32, u32)>,
}

impl Recorder {
    fn span(&mut self, y: i32, x: i32, len: u32) {
        let c = self.clip;
        assert!(
            len > 0 && y >= c.y0 && y < c.y1 && x >= c.x0 && (x as i64 + len as i64) <= c.x1 as i64,
            "span ({x}, {y}) len {len} outside {c:?}"
        );
        assert!(self.rows.iter().all(|r| r.1 != y), "two spans on row {y}");
        self.rows.push((x, y, len));
    }
}

impl Target for Recorder {
    type Color = u8;
    fn clip_rect(&self) -> Rect {
        self.clip
    }
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, _c: u8) {
        self.span(y, x, len);
    }
    fn fill_with<F: FnMut() -> u8>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        for _ in 0..len {
            let _ = colors();
        }
        self.span(y, x, len);
    }
}

fn ramp() -> [u8; 256] {
    core::array::from_fn(|i| (i as u8).max(1))
}

/// Draws `verts` into a fresh guarded band (and a recorder); returns the
/// drawn pixels.
fn draw(input: &Input, verts: &[ScreenVertex<1>]) -> Vec<(i32, i32)> {
    let (w, h) = (input.w as usize % 24 + 1, input.h as usize % 16 + 1);
    let y0 = input.y0 as i32 % 8;
    let mut g = Guarded::new(w, h, input.pad as usize % 4, y0);
    let (start, len, stride) = (g.start(), g.len(), g.stride);
    let ramp = ramp();
    {
        let (px, keys) = (&mut g.px, &mut g.keys);
        let mut band = Band::new(&mut px[start..start + len], w as u16, h as u16, stride, y0)
            .expect("valid band");
        let mut depth = DepthBuffer::<u16>::new(
            &mut keys[start..start + len],
            w as u16,
            h as u16,
            stride,
            y0,
        )
        .expect("valid");
        match (input.depth, input.gouraud) {
            (false, false) => fill_polygon(&mut band, &mut NoDepth, &Flat(7u8), verts),
            (false, true) => fill_polygon(&mut band, &mut NoDepth, &Gouraud::new(&ramp), verts),
            (true, false) => fill_polygon(&mut band, &mut depth, &Flat(7u8), verts),
            (true, true) => fill_polygon(&mut band, &mut depth, &Gouraud::new(&ramp), verts),
        };
    }
    let mut rec = Recorder {
        clip: Rect::new(0, y0, w as i32, y0 + h as i32),
        rows: Vec::new(),
    };
    fill_polygon(&mut rec, &mut NoDepth, &Flat(7u8), verts);
    let drawn = g.check();
    if !input.depth {
        // Without a depth test the band shows exactly the recorded spans.
        let mut spans: Vec<(i32, i32)> = rec
            .rows
            .iter()
            .flat_map(|&(x, y, l)| (x..x + l as i32).map(move |i| (i, y)))
            .collect();
        spans.sort_by_key(|&(x, y)| (y, x));
        let mut d = drawn.clone();
        d.sort_by_key(|&(x, y)| (y, x));
        assert_eq!(d, spans, "band vs recorded spans");
    }
    drawn
}

/// Exact top-left-rule coverage of a triangle (28.4 vertices) at pixel
/// centers inside the band.
fn coverage(input: &Input, t: [(i64, i64); 3]) -> Vec<(i32, i32)> {
    let (w, h) = (input.w as i64 % 24 + 1, input.h as i64 % 16 + 1);
    let y0 = input.y0 as i64 % 8;
    let [a, mut b, mut c] = t;
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area == 0 {
        return Vec::new();
    }
    if area < 0 {
        core::mem::swap(&mut b, &mut c);
    }
    let edges = [(a, b), (b, c), (c, a)];
    let mut out = Vec::new();
    for j in y0..y0 + h {
        for i in 0..w {
            let p = (16 * i + 8, 16 * j + 8);
            let inside = edges.iter().all(|&(s, e)| {
                let (dx, dy) = (e.0 - s.0, e.1 - s.1);
                let v = dx * (p.1 - s.1) - dy * (p.0 - s.0);
                v > 0 || (v == 0 && (dy < 0 || (dy == 0 && dx > 0)))
            });
            if inside {
                out.push((i as i32, j as i32));
            }
        }
    }
    out
}

fuzz_target!(|input: Input| {
    match &input.mode {
        Mode::Poly(vs) => {
            let verts: Vec<ScreenVertex<1>> = vs
                .iter()
                .take(16)
                .map(|&(x, y, z, v)| ScreenVertex::new(x.v(), y.v(), z, [v]))
                .collect();
            let mut drawn = draw(&input, &verts);
            if verts.len() == 3
                && verts.iter().all(|v| {
                    v.x.unsigned_abs() <= COORD_LIMIT as u32
                        && v.y.unsigned_abs() <= COORD_LIMIT as u32
                })
                && (!input.depth || verts.iter().all(|v| v.z < 60000))
            {
                let t = [0, 1, 2].map(|i| (verts[i].x as i64, verts[i].y as i64));
                let mut want = coverage(&input, t);
                drawn.sort();
                want.sort();
                assert_eq!(drawn, want, "triangle {t:?}: drawn vs exact coverage");
            }
        }
        Mode::Shared(p) => {
            let v: Vec<ScreenVertex<1>> = p
                .iter()
                .map(|&(x, xs, y, ys)| {
                    ScreenVertex::new(
                        x as i32 % 32 * 16 + (xs % 16) as i32,
                        y as i32 % 24 * 16 + (ys % 16) as i32,
                        100,
                        [0],
                    )
                })
                .collect();
            let (a, b, c, d) = (v[0], v[1], v[2], v[3]);
            let side = |q: ScreenVertex<1>| {
                ((c.x - b.x) as i64 * (q.y - b.y) as i64 - (c.y - b.y) as i64 * (q.x - b.x) as i64)
                    .signum()
            };
            let mut d1 = draw(&input, &[a, b, c]);
            let mut d2 = draw(&input, &[c, b, d]);
            let mut w1 = coverage(&input, [a, b, c].map(|q| (q.x as i64, q.y as i64)));
            let mut w2 = coverage(&input, [c, b, d].map(|q| (q.x as i64, q.y as i64)));
            d1.sort();
            d2.sort();
            w1.sort();
            w2.sort();
            assert_eq!(d1, w1, "first triangle vs exact coverage");
            assert_eq!(d2, w2, "second triangle vs exact coverage");
            if side(a) * side(d) == -1 {
                assert!(
                    d1.iter().all(|p| d2.binary_search(p).is_err()),
                    "triangles sharing an edge both wrote a pixel"
                );
            }
        }
        Mode::Pipe { focus, verts } => {
            let (w, h) = (input.w as u16 % 24 + 1, input.h as u16 % 16 + 1);
            let Ok(pipe) = Pipeline::new(
                Projection::perspective(*focus as f32 + 1.0, w, h),
                w,
                h,
                0.25f32,
                100.0,
                8.0,
            ) else {
                return;
            };
            let vs: Vec<Vertex<f32, Intensity<f32>>> = verts
                .iter()
                .take(10)
                .map(|(p, i)| {
                    Vertex::new(common::v3::<f32>(*p), Intensity(common::conv(i.value())))
                })
                .collect();
            let y0 = input.y0 as i32 % 8;
            let mut g = Guarded::new(w as usize, h as usize, input.pad as usize % 4, y0);
            let (start, len, stride) = (g.start(), g.len(), g.stride);
            let ramp = ramp();
            {
                let (px, keys) = (&mut g.px, &mut g.keys);
                let mut band =
                    Band::new(&mut px[start..start + len], w, h, stride, y0).expect("valid band");
                let mut depth =
                    DepthBuffer::<u16>::new(&mut keys[start..start + len], w, h, stride, y0)
                        .expect("valid");
                let _ = pipe.draw_polygon(&mut band, &mut depth, &Gouraud::new(&ramp), &vs);
            }
            g.check();
            let _ = Vec3::<f32>::ZERO;
        }
    }
});

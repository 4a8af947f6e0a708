//! Integer scan conversion of convex polygons into spans.
//!
//! Input is a convex polygon (any number of vertices, either winding) in
//! screen space with 28.4 fixed-point coordinates ([`SUBPIXEL_BITS`] = 4),
//! pixel (i, j) having its center at (i + ½, j + ½). Coverage follows the
//! **top-left rule** of the D3D rasterization rules: a pixel is drawn when
//! its center is strictly inside, or on a left edge, or on a horizontal top
//! edge. So polygons that share edges in a mesh cover every pixel exactly
//! once: no gaps, no double writes.
//!
//! The walk is the chapter's: find the top vertex, walk the two chains of
//! edges down to the bottom vertex one scanline at a time with exact
//! integer steppers (see the `edge` module), and emit `[left, right)` per
//! row, scissored to the target's [`clip_rect`](crate::target::Target::clip_rect).
//! A triangle (most of a mesh) walks its long edge against its two short
//! edges instead, which gives the same spans without chain bookkeeping.
//! Rows and columns are half-open at the same rule: row j is drawn when
//! `y_top ≤ j + ½ < y_bottom`, pixel i when `x_left ≤ i + ½ < x_right`.
//!
//! Interpolated quantities (the depth key and the shader's varyings) are
//! planes fitted once per polygon and evaluated once per span (see the
//! `gradient` module); per pixel there is one add per quantity. On targets
//! that expose their memory ([`Target::span_mut`]) the depth test and the
//! write are fused into one loop per span.
//!
//! | piece | choices (all compile-time) |
//! |---|---|
//! | shader ([`SpanShader`]) | [`Flat`], [`Gouraud`] (color ramp), [`AffineTexture`], [`LitAffineTexture`] (texture × intensity), [`PerspectiveTexture`] (exact, or runs of N) |
//! | texels | a [`Texture`](crate::texture::Texture) (the crate's one texel store), wrapped by a [`Wrap`](crate::texture::Wrap) type: [`Repeat`](crate::texture::Repeat), [`RepeatPow2`](crate::texture::RepeatPow2), [`Clamp`](crate::texture::Clamp) |
//! | depth ([`DepthTest`]) | [`NoDepth`] (free), [`DepthBuffer`] (u16 keys, or u32 24.8 depths; less-than) |
//! | target | anything implementing [`Target`] |
//!
//! # Limits
//!
//! - Vertex coordinates must lie within ±[`COORD_LIMIT`] (2^28 in 28.4,
//!   i.e. ±16 777 216 pixels); a polygon with any vertex outside is
//!   [rejected](FillOutcome::Rejected), never wrapped. Within that range all
//!   edge arithmetic fits in i64 (derivation in `edge`).
//! - Targets are at most 65535×65535 pixels (`u16` sizes), far inside the
//!   coordinate range, so any viewport plus a guard band of 16 million
//!   pixels on each side is exact.
//! - **32-bit set-up.** A triangle whose vertices all lie within ±2^14
//!   (28.4, i.e. ±1024 pixels: any viewport up to 992 pixels wide with the
//!   pipeline's 16-pixel guard band) walks its edges entirely in `i32`: the
//!   edge numerator is then below 1.62·10^9 < 2^31 (derivation at
//!   `EdgeStepper32` in `edge`). Larger triangles, and every other
//!   polygon, walk their left and right vertex chains with `i64` edges.
//!   The choice is made per triangle from its coordinates and both walks
//!   compute the same exact quotients, so it never changes a pixel.
//!   Products of two 32-bit values (edge vectors, areas, gradient
//!   numerators) are 32×32→64 multiplies, never 64×64 ones.
//!
//! # Robustness
//!
//! Whatever the input (non-convex, self-intersecting, repeated vertices,
//! zero area, extreme coordinates) [`fill_polygon`] does not panic, and
//! writes only inside the target's clip rectangle, at most one span per
//! row. Only convex input is guaranteed to be covered correctly.

mod depth;
mod edge;
mod gradient;
#[cfg(feature = "perspective")]
pub(crate) mod persp_div;
mod shader;
#[cfg(feature = "texture")]
mod texture;

#[cfg(feature = "depth")]
pub use depth::DepthBuffer;
pub use depth::{DEPTH_FRAC_BITS, DepthKey, DepthTest, NoDepth, StoredDepth};
#[cfg(feature = "gouraud")]
pub use shader::Gouraud;
pub use shader::{Flat, ScalableColor, SpanShader, VARYING_FRAC_BITS};
#[cfg(feature = "perspective")]
pub use texture::PerspectiveTexture;
#[cfg(feature = "texture")]
pub use texture::{AffineTexture, LitAffineTexture};

/// Fractional bits of the perspective varying `q = near/z ∈ (0, 1]`.
pub const PERSPECTIVE_Q_BITS: u32 = 24;

use crate::target::Target;
pub(crate) use edge::SMALL_COORD_LIMIT;
use edge::{EdgeStepper, EdgeStepper32, first_center};
use gradient::{AreaRecip, Basis, Gradient};

/// Fractional bits of screen coordinates (28.4 fixed point).
pub const SUBPIXEL_BITS: u32 = 4;

/// Largest accepted `|x|` or `|y|` of a vertex, in 28.4 units (2^24 pixels).
pub const COORD_LIMIT: i32 = 1 << 28;

/// A polygon vertex in screen space.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ScreenVertex<const VARYINGS: usize> {
    /// x in 28.4 fixed point (pixels × 16).
    pub x: i32,
    /// y in 28.4 fixed point (pixels × 16), down the screen.
    pub y: i32,
    /// Depth key, 0 nearest; used only with a [`DepthBuffer`].
    pub z: DepthKey,
    /// The shader's varyings, 16.16 fixed point.
    pub v: [i32; VARYINGS],
}

impl<const VARYINGS: usize> ScreenVertex<VARYINGS> {
    /// A vertex at 28.4 coordinates (pixels × 16) with a depth key and
    /// varyings.
    #[must_use]
    pub const fn new(x: i32, y: i32, z: DepthKey, v: [i32; VARYINGS]) -> Self {
        Self { x, y, z, v }
    }
}

/// What [`fill_polygon`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FillOutcome {
    /// Spans were emitted (some may still have failed the depth test).
    Drawn,
    /// Nothing to draw: fewer than three vertices, zero area, or no pixel
    /// center inside the clip rectangle.
    Empty,
    /// A vertex lies outside ±[`COORD_LIMIT`]; nothing was drawn.
    Rejected,
}

/// One chain of edges from the top vertex to the bottom vertex.
struct Chain<'v, const VARYINGS: usize> {
    verts: &'v [ScreenVertex<VARYINGS>],
    /// End vertex of the current edge.
    pos: usize,
    bottom: usize,
    forward: bool,
    /// First row below the current edge.
    end_row: i32,
    edge: EdgeStepper,
}

impl<'v, const VARYINGS: usize> Chain<'v, VARYINGS> {
    fn new(verts: &'v [ScreenVertex<VARYINGS>], top: usize, bottom: usize, forward: bool) -> Self {
        Self {
            verts,
            pos: top,
            bottom,
            forward,
            end_row: i32::MIN,
            edge: EdgeStepper::NONE,
        }
    }

    /// Makes the current edge the one that covers row `j`; `false` when the
    /// chain has ended. Each call moves `pos` only towards `bottom`, so the
    /// total work per polygon is bounded by the vertex count.
    #[inline]
    fn seek(&mut self, j: i32) -> bool {
        while self.end_row <= j {
            if self.pos == self.bottom {
                return false;
            }
            let n = self.verts.len();
            let a = self.pos;
            let b = if self.forward {
                if a + 1 == n { 0 } else { a + 1 }
            } else if a == 0 {
                n - 1
            } else {
                a - 1
            };
            self.pos = b;
            let (Some(va), Some(vb)) = (self.verts.get(a), self.verts.get(b)) else {
                return false;
            };
            self.end_row = first_center(vb.y);
            if self.end_row > j {
                self.edge = EdgeStepper::new(va.x, va.y, vb.x, vb.y, j);
            }
        }
        true
    }
}

/// The two chains' columns on row `y`, then a step down; `None` when a
/// chain has ended. Out of line, so that the triangles' row walk in
/// [`fill_polygon`] keeps its registers (W2 on ARMv6-M: 7.61 M
/// instructions per frame with the chains inlined, 7.51 M without).
#[cold]
#[inline(never)]
fn chain_row<const VARYINGS: usize>(
    chains: &mut (Chain<'_, VARYINGS>, Chain<'_, VARYINGS>),
    y: i32,
) -> Option<(i32, i32)> {
    let (a, b) = chains;
    if !(a.seek(y) && b.seek(y)) {
        return None;
    }
    let xs = (a.edge.x as i32, b.edge.x as i32);
    a.edge.step();
    b.edge.step();
    Some(xs)
}

/// Twice the signed area of the triangle `v0, a, b` (28.4 units).
/// Coordinates within ±2^28 keep edge components below 2^29, so each
/// product is a 32×32→64 multiply; with `small` (every coordinate within
/// ±[`SMALL_COORD_LIMIT`](edge::SMALL_COORD_LIMIT)) the components are
/// within ±2^15 and each product within ±2^30: two 32-bit multiplies.
#[inline(always)]
fn area2<const VARYINGS: usize>(
    v0: &ScreenVertex<VARYINGS>,
    a: &ScreenVertex<VARYINGS>,
    b: &ScreenVertex<VARYINGS>,
    small: bool,
) -> i64 {
    let (e1x, e1y) = (a.x - v0.x, a.y - v0.y);
    let (e2x, e2y) = (b.x - v0.x, b.y - v0.y);
    if small {
        (e1x * e2y) as i64 - (e1y * e2x) as i64
    } else {
        crate::scalar::widening_mul(e1x, e2y) - crate::scalar::widening_mul(e1y, e2x)
    }
}

/// Scan-converts a convex polygon into `target`, coloring with `shader`
/// and testing against `depth`.
///
/// See the [module docs](self) for the fill rule, limits and robustness.
/// Varyings and depth are planes through three of the vertices (the fan
/// triangle from vertex 0 with the largest area); for a triangle, and for
/// any polygon whose values are affine over it (e.g. a clipped triangle),
/// that is exact interpolation.
///
/// # Examples
///
/// ```
/// use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
/// use sightline::raster::{FillOutcome, Flat, NoDepth, ScreenVertex, fill_polygon};
/// use sightline::target::Framebuffer;
///
/// let mut pixels = [Rgb565::BLACK; 8 * 4];
/// let mut fb = Framebuffer::new(&mut pixels, 8, 4, 8).unwrap();
/// // Pixels × 16: a 4×4 square from (2, 0) to (6, 4).
/// let v = |x: i32, y: i32| ScreenVertex::new(x * 16, y * 16, 0, []);
/// let square = [v(2, 0), v(6, 0), v(6, 4), v(2, 4)];
/// let out = fill_polygon(&mut fb, &mut NoDepth, &Flat(Rgb565::RED), &square);
/// assert_eq!(out, FillOutcome::Drawn);
/// assert_eq!(fb.pixel(2, 0), Some(Rgb565::RED));
/// assert_eq!(fb.pixel(6, 0), Some(Rgb565::BLACK)); // right edge excluded
/// ```
///
/// # Panics
///
/// Never.
pub fn fill_polygon<T, Z, Sh, const VARYINGS: usize>(
    target: &mut T,
    depth: &mut Z,
    shader: &Sh,
    verts: &[ScreenVertex<VARYINGS>],
) -> FillOutcome
where
    T: Target,
    Z: DepthTest,
    Sh: SpanShader<VARYINGS, Color = T::Color>,
{
    fill::<T, Z, Sh, VARYINGS, true>(target, depth, shader, verts)
}

/// [`fill_polygon`] for a triangle whose vertices all lie within
/// ±[`SMALL_COORD_LIMIT`](edge::SMALL_COORD_LIMIT) (2^14 in 28.4, ±1024
/// pixels), which the 32-bit walk covers: the same pixels, without the
/// 64-bit chain walk that polygons and larger triangles take, so a
/// firmware that draws only such triangles does not link it, and the
/// function is shorter (W1/W2 on ARMv6-M through
/// `Frame::draw_unclipped`: 5.40 M / 6.37 M instructions per frame with
/// `fill_polygon`, 5.29 M / 6.27 M with this). Any other triangle is
/// [`Rejected`](FillOutcome::Rejected) and nothing is drawn.
/// [`Frame::draw_unclipped`](crate::scene::Frame::draw_unclipped) calls
/// it for the triangles that need no clipping, whose vertices lie in a
/// guard band within that bound.
pub(crate) fn fill_small_triangle<T, Z, Sh, const VARYINGS: usize>(
    target: &mut T,
    depth: &mut Z,
    shader: &Sh,
    verts: &[ScreenVertex<VARYINGS>; 3],
) -> FillOutcome
where
    T: Target,
    Z: DepthTest,
    Sh: SpanShader<VARYINGS, Color = T::Color>,
{
    fill::<T, Z, Sh, VARYINGS, false>(target, depth, shader, verts)
}

/// [`fill_polygon`]'s body. Without `POLYGONS` only triangles within
/// ±[`SMALL_COORD_LIMIT`](edge::SMALL_COORD_LIMIT) are drawn (the 32-bit
/// walk) and anything else is rejected before any pixel is written, so
/// the chain walk and its 64-bit edges are left out.
#[inline(always)]
fn fill<T, Z, Sh, const VARYINGS: usize, const POLYGONS: bool>(
    target: &mut T,
    depth: &mut Z,
    shader: &Sh,
    verts: &[ScreenVertex<VARYINGS>],
) -> FillOutcome
where
    T: Target,
    Z: DepthTest,
    Sh: SpanShader<VARYINGS, Color = T::Color>,
{
    let n = verts.len();
    if n < 3 {
        return FillOutcome::Empty;
    }
    if !POLYGONS && n != 3 {
        return FillOutcome::Rejected;
    }
    // A triangle (most of a mesh) is sorted top to bottom once, by
    // reference (swapping the vertices themselves moved their varyings
    // too): its walk below takes the order, and its extreme rows come
    // from it. Any other polygon finds its extreme rows in one pass. Both
    // also take the largest coordinate magnitude (for the range checks
    // here and for the 32-bit walk).
    let magnitude = |v: &ScreenVertex<VARYINGS>| v.x.unsigned_abs().max(v.y.unsigned_abs());
    let (sorted, top_y, bottom_y, reach) = if let [a, b, c] = verts {
        let (mut t, mut m, mut b) = (a, b, c);
        if m.y < t.y {
            core::mem::swap(&mut t, &mut m);
        }
        if b.y < m.y {
            core::mem::swap(&mut m, &mut b);
        }
        if m.y < t.y {
            core::mem::swap(&mut t, &mut m);
        }
        let reach = magnitude(t).max(magnitude(m)).max(magnitude(b));
        (Some([t, m, b]), t.y, b.y, reach)
    } else {
        let (mut top_y, mut bottom_y, mut reach) = (verts[0].y, verts[0].y, 0u32);
        for v in verts {
            top_y = top_y.min(v.y);
            bottom_y = bottom_y.max(v.y);
            reach = reach.max(magnitude(v));
        }
        (None, top_y, bottom_y, reach)
    };
    if reach > COORD_LIMIT as u32 || (!POLYGONS && reach > edge::SMALL_COORD_LIMIT as u32) {
        return FillOutcome::Rejected;
    }
    let mut clip = target.clip_rect();
    if let Some(r) = depth.clip_rect() {
        clip = clip.intersect(&r);
    }
    let row0 = first_center(top_y).max(clip.y0);
    let row1 = first_center(bottom_y).min(clip.y1);
    if row0 >= row1 || clip.x0 >= clip.x1 {
        return FillOutcome::Empty;
    }

    // The basis for the planes: the fan triangle of largest |area|. With
    // coordinates within ±2^28 each cross product is below 2^60.
    // (By index: copying the vertices at each better candidate cost about
    // a hundred instructions per triangle on ARMv6-M.) The search, which
    // a triangle skips, took 1.5 % of W1 on ARMv6-M (5.90 M -> 5.81 M).
    let v0 = &verts[0];
    let small = reach <= edge::SMALL_COORD_LIMIT as u32;
    // A triangle is its own basis: one fan triangle, no search.
    let bv = if let [_, a, b] = verts {
        [v0, a, b]
    } else {
        let (mut best, mut best_area) = (1, 0u64);
        for (k, w) in verts[1..].windows(2).enumerate() {
            let area = area2(v0, &w[0], &w[1], small).unsigned_abs();
            if area > best_area {
                (best, best_area) = (k + 1, area);
            }
        }
        match (verts.get(best), verts.get(best + 1)) {
            (Some(a), Some(b)) => [v0, a, b],
            _ => return FillOutcome::Empty,
        }
    };
    let best_area = area2(v0, bv[1], bv[2], small);
    if best_area == 0 {
        // Every vertex is on one line through vertex 0: no interior.
        return FillOutcome::Empty;
    }
    let solid = shader.solid();
    let basis = Basis {
        p: bv.map(|v| (v.x, v.y)),
        area2: best_area,
        short: reach <= edge::SMALL_COORD_LIMIT as u32,
        // One reciprocal for every plane's two quotients, each then one
        // 32×32→64 multiply (see `AreaRecip`): W1 on ARMv6-M,
        // depth alone, 6.65 M instructions per frame with two library
        // divisions per plane, 6.30 M with it. Only where a 64-bit
        // division is a library call: on 64-bit hosts it is one
        // instruction (x86-64 W2: 4.42 M instructions without the
        // reciprocal, 4.74 M with it). The quotients are the same (the
        // host/MCU frame checks compare the two routes bit for bit).
        recip: if !cfg!(target_pointer_width = "64")
            && (Z::ENABLED || (solid.is_none() && VARYINGS > 0))
        {
            AreaRecip::new(best_area)
        } else {
            None
        },
    };
    let zgrad = if Z::ENABLED {
        let z = |v: &ScreenVertex<VARYINGS>| (v.z as i32) << DEPTH_FRAC_BITS;
        Gradient::new(&basis, [z(bv[0]), z(bv[1]), z(bv[2])])
    } else {
        Gradient::default()
    };
    let mut vgrad = [Gradient::default(); VARYINGS];
    if solid.is_none() {
        for (k, g) in vgrad.iter_mut().enumerate() {
            *g = Gradient::new(&basis, [bv[0].v[k], bv[1].v[k], bv[2].v[k]]);
        }
    }
    let zmax = ((DepthKey::MAX as i32) << DEPTH_FRAC_BITS) | ((1 << DEPTH_FRAC_BITS) - 1);
    let (lo, hi) = Sh::RANGE;

    // Triangles (most of a mesh) whose coordinates allow 32-bit edges (see
    // `EdgeStepper32`): the long edge top→bottom against the short edges
    // top→mid and mid→bottom, no chain walking. These are the edges the
    // chains would take, set up with the same rows, and an edge's value on
    // a row does not depend on where its walk started (see `edge`), so the
    // spans are identical. Everything else (polygons, and triangles beyond
    // ±`SMALL_COORD_LIMIT`, which no viewport below 992 pixels produces)
    // walks the chains with 64-bit edges.
    let small_triangle = sorted.filter(|_| reach <= edge::SMALL_COORD_LIMIT as u32);
    // Every plane by the 32-bit route ([`Gradient::span_tiny`]) when each
    // fits this triangle's extent around the basis origin (vertex 0): the
    // same values as the general route, decided once per triangle. On
    // every target: on x86-64 too, where a 64-bit product is one
    // instruction, it is the shorter span set-up (W1/W2 callgrind Ir per
    // frame 3.42 M / 4.15 M with the general route only, 3.34 M / 4.06 M
    // with this one).
    //
    // The extent is measured from the basis origin `bv[0]`, from which
    // the spans' pixel centers are measured (`px`, `py` below), not from
    // the top vertex: measured from the top vertex (as it once was), a
    // triangle whose vertex 0 lies elsewhere could pass with pixel
    // centers up to twice the extent from the origin, and the 32-bit
    // start overflowed (found by the proptest
    // `fused_depth_write_matches_runs`; its case is kept in
    // `proptest-regressions`).
    //
    // Polygons (the clipper's) take it too: their pixel centers lie in the
    // bounding box of all their vertices, so the extent is measured over
    // all of them. Scene frames (`bash tests/mcu/run`), before -> after:
    // ARMv6-M I16F16 corridor 6 824 282 -> 6 432 161 instructions,
    // corridor-affine 3 351 535 -> 3 072 183, bunny (whose floor is
    // clipped) 9 017 119 -> 9 022 970; Cortex-M4 f32 corridor 4 867 241 ->
    // 4 761 149, corridor-affine 2 373 892 -> 2 286 918, bunny 6 118 390
    // -> 6 064 489. W1/W2 clip nothing and are unchanged. The thumbv6m
    // Gouraud and texture firmwares grew by 228 and 424 bytes of .text.
    let ext = if !small {
        u32::MAX
    } else {
        let o = bv[0];
        if small_triangle.is_some() {
            distance_from(bv[1], o).max(distance_from(bv[2], o))
        } else {
            polygon_extent(verts, o)
        }
    };
    let tiny = small
        && !general_spans_forced()
        && (!Z::ENABLED || zgrad.fits::<false>(ext))
        && (solid.is_some() || vgrad.iter().all(|g| g.fits::<true>(ext)));
    #[cfg(test)]
    if tiny {
        TINY_FILLS.with(|t| t.set(t.get() + 1));
    }

    // One span: `[min(xa, xb), max(xa, xb))` of row `y`, scissored. The
    // same ceil formula serves left and right edges (first center at or
    // right of the edge), so for convex input min/max is exactly
    // [left, right) whatever the winding; for garbage it still yields one
    // bounded span. Evaluates to whether anything was inside the clip. A
    // macro rather than a closure: expanded once, in the row walk below.
    // Columns are within ±2^24 + 1 (coordinates within ±2^28 in 28.4), so
    // the edges' columns fit in i32.
    macro_rules! span {
        ($y:expr, $xa:expr, $xb:expr) => {{
            let (y, xa, xb): (i32, i32, i32) = ($y, $xa, $xb);
            let inside = 'span: {
                let x0 = xa.min(xb).max(clip.x0);
                let x1 = xa.max(xb).min(clip.x1);
                if x0 >= x1 {
                    break 'span false;
                }
                let (x, len) = (x0, (x1 - x0) as u32);
                // Depth, and the varyings at the span's first pixel with
                // their steps: one set-up for the fused write and the runs.
                let (mut z, mut dz) = (0, 0);
                let mut start = [0i32; VARYINGS];
                let mut step = [0i32; VARYINGS];
                if tiny {
                    // The first pixel center relative to the basis origin,
                    // shared by every plane.
                    let px = x * 16 + 8 - basis.p[0].0;
                    let py = y * 16 + 8 - basis.p[0].1;
                    let n = len as i32 - 1;
                    // The bound `fits` was checked against (the last
                    // pixel's center too).
                    debug_assert!(
                        px.unsigned_abs() <= ext
                            && py.unsigned_abs() <= ext
                            && (px + n * 16).unsigned_abs() <= ext,
                        "a span's pixel centers lie outside the polygon's extent"
                    );
                    if Z::ENABLED {
                        (z, dz) = zgrad.span_tiny::<false>(px, py, n, 0, zmax);
                    }
                    if solid.is_none() {
                        for k in 0..VARYINGS {
                            (start[k], step[k]) = vgrad[k].span_tiny::<true>(px, py, n, lo, hi);
                        }
                    }
                } else {
                    if Z::ENABLED {
                        (z, dz) = zgrad.span(x, y, len, 0, zmax);
                    }
                    if solid.is_none() {
                        for k in 0..VARYINGS {
                            (start[k], step[k]) = vgrad[k].span(x, y, len, lo, hi);
                        }
                    }
                }
                // What the shader sees (see `shifted`).
                if Sh::SHIFT != 0 && solid.is_none() {
                    for k in 0..VARYINGS {
                        (start[k], step[k]) =
                            shifted::<Sh, VARYINGS>((start[k], step[k]), len as i32 - 1);
                    }
                }
                // The varyings `i` pixels into the span.
                let at = |i: u32| {
                    let mut v = start;
                    for k in 0..VARYINGS {
                        v[k] = v[k].wrapping_add(step[k].wrapping_mul(i as i32));
                    }
                    v
                };
                if Z::ENABLED && Sh::PER_PIXEL {
                    if let Some(pixels) = target.span_mut(y, x, len) {
                        // Depth test and write fused in one loop; on
                        // ARMv6-M a long span of a varying shader falls
                        // through to the keys first and then `shade_run`
                        // per passing run (see `shades_runs`).
                        if let Some(c) = solid {
                            depth.test_fill(y, x, z, dz, pixels, c);
                            break 'span true;
                        }
                        if !depth::shades_runs(pixels.len()) {
                            depth.test_write(y, x, z, dz, pixels, |i| shader.color(&at(i)));
                            break 'span true;
                        }
                    }
                }
                if let Some(c) = solid {
                    depth.test_span(y, x, len, z, dz, |off, run| {
                        target.fill_solid(y, x + off as i32, run, c);
                    });
                } else {
                    depth.test_span(y, x, len, z, dz, |off, run| {
                        shader.shade_run(target, y, x + off as i32, run, at(off), step);
                    });
                }
                true
            };
            inside
        }};
    }

    // One row walk for both kinds, so the span code above is expanded once
    // per shader: a triangle steps its long edge against the short edge of
    // the half it is in, anything else its two chains (out of line and
    // cold: polygons are the clipper's few). A walk per kind, each with its
    // own span code, was 1.1 KB more in the flat cube firmware and 2.7 KB
    // more in the Gouraud one on thumbv6m, for 1 % fewer instructions per
    // W1 and W2 frame.
    let mut tri = small_triangle.map(|[t, m, b]| {
        let split = first_center(m.y).clamp(row0, row1);
        let long = EdgeStepper32::new(t.x, t.y, b.x, b.y, row0);
        // The upper short edge from `row0`, and the lower one from `split`
        // (at `row1`, past the last row, when the upper half is empty).
        let (short, lower_at) = if row0 < split {
            (EdgeStepper32::new(t.x, t.y, m.x, m.y, row0), split)
        } else {
            (EdgeStepper32::new(m.x, m.y, b.x, b.y, row0), row1)
        };
        (long, short, lower_at, [m.x, m.y, b.x, b.y])
    });
    let mut chains = if POLYGONS && tri.is_none() {
        // The first vertex on the top row and the first on the bottom row.
        let first_at = |y: i32| verts.iter().position(|v| v.y == y).unwrap_or(0);
        let (top, bottom) = (first_at(top_y), first_at(bottom_y));
        Some((
            Chain::new(verts, top, bottom, true),
            Chain::new(verts, top, bottom, false),
        ))
    } else {
        None
    };
    let mut drawn = false;
    for y in row0..row1 {
        let (xa, xb) = if let Some((long, short, lower_at, mb)) = &mut tri {
            if y == *lower_at {
                *short = EdgeStepper32::new(mb[0], mb[1], mb[2], mb[3], y);
            }
            let xs = (long.x, short.x);
            long.step();
            short.step();
            xs
        } else {
            match chains.as_mut().and_then(|c| chain_row(c, y)) {
                Some(xs) => xs,
                None => break,
            }
        };
        drawn |= span!(y, xa, xb);
    }
    if drawn {
        FillOutcome::Drawn
    } else {
        FillOutcome::Empty
    }
}

/// The largest coordinate distance (28.4) of any vertex from `o`: the
/// extent [`fill`] checks the 32-bit span route against for a polygon.
/// Out of line: inlined, the banded bunny scene frame on the Cortex-M4
/// (f32), which draws every triangle through `fill_polygon`, took
/// 6 164 218 instructions instead of 6 064 489.
#[inline(never)]
fn polygon_extent<const VARYINGS: usize>(
    verts: &[ScreenVertex<VARYINGS>],
    o: &ScreenVertex<VARYINGS>,
) -> u32 {
    verts.iter().map(|p| distance_from(p, o)).max().unwrap_or(0)
}

/// The larger of `p`'s coordinate distances (28.4) from `o`.
#[inline(always)]
fn distance_from<const VARYINGS: usize>(
    p: &ScreenVertex<VARYINGS>,
    o: &ScreenVertex<VARYINGS>,
) -> u32 {
    (p.x - o.x).unsigned_abs().max((p.y - o.y).unsigned_abs())
}

#[cfg(test)]
std::thread_local! {
    /// Tests set this to draw every plane by the general route, to compare
    /// it with the 32-bit one ([`Gradient::span_tiny`]) on whole polygons.
    pub(crate) static GENERAL_SPANS: core::cell::Cell<bool> = const { core::cell::Cell::new(false) };
    /// Counts the fills that took the 32-bit route (tests read it to know
    /// that a comparison compared something).
    pub(crate) static TINY_FILLS: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
}

/// Whether a test asked for the general span route only ([`GENERAL_SPANS`]);
/// `false` outside tests, where it compiles away.
#[inline(always)]
fn general_spans_forced() -> bool {
    #[cfg(test)]
    {
        GENERAL_SPANS.with(|g| g.get())
    }
    #[cfg(not(test))]
    {
        false
    }
}

/// A varying's span start and step `(v, dv)` as shader `Sh` sees them:
/// shifted left by [`SpanShader::SHIFT`] (wrapping; stepping commutes with
/// the shift modulo 2^32). Shifted once a span, before the fused loop's
/// closure captures them: shifted in the closure's per-pixel value
/// instead, LLVM folds the shift back into the mask it was to remove.
/// Debug builds first check that the span's first and last (`n` steps on)
/// values lie in the shader's range: a set-up fault that let one wrap
/// would be hidden by the shift. Called only for shaders with a shift.
#[inline(always)]
fn shifted<Sh: SpanShader<VARYINGS>, const VARYINGS: usize>(
    (v, dv): (i32, i32),
    n: i32,
) -> (i32, i32) {
    let (lo, hi) = Sh::RANGE;
    debug_assert!(
        (lo..=hi).contains(&v) && (lo..=hi).contains(&v.wrapping_add(dv.wrapping_mul(n))),
        "a varying left the shader's range: span set-up did not clamp"
    );
    (v.wrapping_shl(Sh::SHIFT), dv.wrapping_shl(Sh::SHIFT))
}

// Each test is gated on the stages it needs.
#[cfg(test)]
mod tests;

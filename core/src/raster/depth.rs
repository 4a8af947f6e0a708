//! Optional depth testing, chosen at compile time.
//!
//! The scan converter is generic over [`DepthTest`]: with [`NoDepth`] the
//! test, the depth plane set-up and the run splitting all compile away
//! (`ENABLED` is a constant), so a scene without a depth buffer pays
//! nothing for the feature.

use crate::target::Rect;
#[cfg(feature = "depth")]
use crate::target::{Band, BufferError};

/// Depth keys: 0 is nearest, 65535 farthest. The pipeline maps the near
/// plane to 0 and the far plane to 65535 (see
/// [`pipeline`](crate::pipeline)).
pub type DepthKey = u16;

/// Fractional bits of the interpolated depth key (24.8 in an `i32`): the
/// step error over a span of 256 pixels stays below one key unit.
pub const DEPTH_FRAC_BITS: u32 = 8;

/// A per-span depth test that splits a span into the runs that pass.
pub trait DepthTest {
    /// `false` only for [`NoDepth`]: lets the scan converter skip the depth
    /// plane set-up at compile time.
    const ENABLED: bool;

    /// The pixels this buffer holds, or `None` when it imposes no limit.
    fn clip_rect(&self) -> Option<Rect>;

    /// Tests the span `x..x+len` of row `y`, where pixel `x+i` has depth
    /// `z + i·dz` (24.8; the 16-bit key is `>> DEPTH_FRAC_BITS`). Stores
    /// the keys that pass (strictly
    /// less than the stored key) and calls `pass(offset, run)` for each
    /// maximal run of passing pixels, left to right. Pixels outside the
    /// buffer fail.
    fn test_span<F: FnMut(u32, u32)>(&mut self, y: i32, x: i32, len: u32, z: i32, dz: i32, pass: F);

    /// As [`Self::test_span`] for a span whose pixels the caller holds in
    /// `pixels` (pixel `x+i` is `pixels[i]`, `len = pixels.len()`): writes
    /// `color(i)` into each pixel `i` that passes, in one loop. `color` is
    /// called once per passing pixel, left to right.
    #[inline]
    fn test_write<C, F: FnMut(u32) -> C>(
        &mut self,
        y: i32,
        x: i32,
        z: i32,
        dz: i32,
        pixels: &mut [C],
        mut color: F,
    ) {
        let len = u32::try_from(pixels.len()).unwrap_or(u32::MAX);
        self.test_span(y, x, len, z, dz, |off, run| {
            let (a, b) = (off as usize, off as usize + run as usize);
            if let Some(px) = pixels.get_mut(a..b) {
                for (i, p) in (off..).zip(px) {
                    *p = color(i);
                }
            }
        });
    }

    /// As [`Self::test_write`] with one `color` for every pixel that
    /// passes (a flat-shaded span).
    #[inline]
    fn test_fill<C: Copy>(&mut self, y: i32, x: i32, z: i32, dz: i32, pixels: &mut [C], color: C) {
        self.test_write(y, x, z, dz, pixels, |_| color);
    }
}

/// No depth buffer: every pixel passes.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoDepth;

impl DepthTest for NoDepth {
    const ENABLED: bool = false;

    fn clip_rect(&self) -> Option<Rect> {
        None
    }

    #[inline]
    fn test_span<F: FnMut(u32, u32)>(
        &mut self,
        _y: i32,
        _x: i32,
        len: u32,
        _z: i32,
        _dz: i32,
        mut pass: F,
    ) {
        pass(0, len);
    }
}

/// What a [`DepthBuffer`] stores per pixel: `u16` (the 16-bit key, half
/// the memory) or `u32` (the interpolated key with its 8 fractional bits,
/// 24.8).
pub trait StoredDepth: Copy + Ord + core::fmt::Debug + private::Sealed {
    /// The farthest value: what [`DepthBuffer::clear`] writes.
    const FAR: Self;
    /// The stored value for an interpolated depth `z` in 24.8 (within
    /// `0..=65535·256+255`, as the span set-up guarantees).
    fn from_z(z: i32) -> Self;
    /// `Some(from_z(z))` when depth `z` passes against `stored`
    /// (`from_z(z) < stored`, less-than), for `z` in the same range.
    fn passes(z: i32, stored: Self) -> Option<Self>;
}

impl StoredDepth for u16 {
    const FAR: Self = u16::MAX;
    #[inline]
    fn from_z(z: i32) -> Self {
        (z >> DEPTH_FRAC_BITS) as u16
    }
    /// On ARMv6-M compared in u32: for `z` in `0..2^24` the shifted value
    /// is the key itself, so no zero extension of it is needed, and the
    /// register it took stays free in the per-pixel loops, which have
    /// seven low registers there (ipp flat + depth 14.25 -> 12.25,
    /// Gouraud + depth 25.25 -> 20.25). Elsewhere the key is truncated
    /// first: on the Cortex-M4 the u32 form gained W1 0.6 % but cost the
    /// textured, depth-tested corridor-affine frame 9 % (the fused loop
    /// with the texel fetch shuffled registers at every pixel).
    #[inline]
    fn passes(z: i32, stored: Self) -> Option<Self> {
        if crate::scalar::ARMV6M {
            passes16_wide(z, stored)
        } else {
            passes16_narrow(z, stored)
        }
    }
}

/// [`StoredDepth::passes`] for 16-bit keys, compared in u32 (ARMv6-M).
#[inline(always)]
fn passes16_wide(z: i32, stored: u16) -> Option<u16> {
    let key = z as u32 >> DEPTH_FRAC_BITS;
    (key < u32::from(stored)).then_some(key as u16)
}

/// [`StoredDepth::passes`] for 16-bit keys, truncated first.
#[inline(always)]
fn passes16_narrow(z: i32, stored: u16) -> Option<u16> {
    let key = (z >> DEPTH_FRAC_BITS) as u16;
    (key < stored).then_some(key)
}

/// Keeps the 8 fractional bits the scan converter interpolates: pixels of
/// two polygons whose 16-bit keys tie are still ordered by their exact
/// planes (to 1/256 of a key). Vertex keys themselves stay 16-bit (see
/// [`pipeline`](crate::pipeline)), so this refines the ordering between
/// vertices, not the precision of the projection.
impl StoredDepth for u32 {
    const FAR: Self = u32::MAX;
    #[inline]
    fn from_z(z: i32) -> Self {
        z as u32
    }
    #[inline]
    fn passes(z: i32, stored: Self) -> Option<Self> {
        ((z as u32) < stored).then_some(z as u32)
    }
}

/// `keys.fill(K::FAR)` by [`fill_words`] over the keys' 4-byte-aligned
/// middle: every key type's far value is all ones, so each word is two
/// far u16 keys or one far u32 key.
#[cfg(feature = "depth")]
fn fill_far_words<K: StoredDepth>(keys: &mut [K]) {
    let (head, words, tail) = bytemuck::pod_align_to_mut::<K, u32>(keys);
    head.fill(K::FAR);
    fill_words(words, u32::MAX);
    tail.fill(K::FAR);
}

/// `words.fill(w)` by the solid fills' unrolled store loop (32 stores per
/// iteration). The key fill
/// before, `slice::fill` of 16-bit keys, became the library's `memset`,
/// which on ARMv6-M stores one word per four instructions: with this loop
/// (and one fill for a gapless buffer instead of one per row) W1/W2 per
/// frame went from 5.29 M / 6.27 M to 5.20 M / 6.19 M instructions on
/// ARMv6-M and from 3.53 M / 4.10 M to 3.43 M / 4.00 M on the Cortex-M4,
/// for 100 bytes more in the flat firmware (`bash tests/mcu/run`). 64-bit
/// hosts keep `slice::fill`: their `memset` is vectorized (x86-64 W1
/// callgrind counts were 0.4 % higher with this loop). (Sixteen stores
/// per iteration at first; 32 took ARMv6-M W2 from 6.046 M to 6.043 M,
/// 32 bytes.)
#[cfg(feature = "depth")]
#[inline(never)]
fn fill_words(words: &mut [u32], w: u32) {
    // Opaque to the optimizer: with the constant far value in view, LLVM
    // turned the stores back into a `memset` call.
    let w = core::hint::black_box(w);
    crate::target::fill_run(words, w);
}

mod private {
    /// `Pod` lets [`super::DepthBuffer::clear`] store two 16-bit keys at
    /// once through a `u32` view of the keys (`bytemuck`'s checked cast:
    /// no `unsafe` of sightline's own).
    pub trait Sealed: bytemuck::Pod {}
    impl Sealed for u16 {}
    impl Sealed for u32 {}
}

/// A depth buffer over a caller-supplied slice of 16-bit keys (`K = u16`,
/// the default) or 24.8 depths (`K = u32`, see [`StoredDepth`]), with the
/// same shape rules as [`Framebuffer`](crate::target::Framebuffer) and an
/// optional first row, so a band-sized depth buffer can follow a
/// [`Band`](crate::target::Band).
///
/// # Guarantees
///
/// Validated once by [`DepthBuffer::new`]; afterwards no method panics or
/// writes outside the slice.
#[cfg(feature = "depth")]
#[derive(Debug)]
pub struct DepthBuffer<'a, K: StoredDepth = DepthKey> {
    // A band of keys: one shape check and one clipping rule for color
    // and depth.
    keys: Band<'a, K>,
}

#[cfg(feature = "depth")]
impl<'a, K: StoredDepth> DepthBuffer<'a, K> {
    /// Wraps `buf` as `rows` rows of `width` keys, `stride` apart, for
    /// frame rows `y0..y0+rows`.
    ///
    /// # Errors
    /// As [`Band::new`](crate::target::Band::new).
    pub fn new(
        buf: &'a mut [K],
        width: u16,
        rows: u16,
        stride: usize,
        y0: i32,
    ) -> Result<Self, BufferError> {
        Band::new(buf, width, rows, stride, y0).map(|keys| Self { keys })
    }

    /// Sets every key to the farthest value ([`StoredDepth::FAR`]: 65535
    /// for `u16`).
    pub fn clear(&mut self) {
        self.keys.for_each_run(|run| {
            if cfg!(target_pointer_width = "64") {
                run.fill(K::FAR);
            } else {
                fill_far_words(run);
            }
        });
    }

    /// Moves the buffer to frame rows `y0..y0+rows` (contents kept).
    ///
    /// # Errors
    /// [`BufferError::Overflow`] if `y0 + rows` overflows `i32`.
    pub fn move_to(&mut self, y0: i32) -> Result<(), BufferError> {
        self.keys.move_to(y0)
    }

    /// The key at frame position (x, y), or `None` outside.
    #[must_use]
    pub fn key(&self, x: i32, y: i32) -> Option<K> {
        self.keys.pixel(x, y)
    }
}

#[cfg(feature = "depth")]
impl<K: StoredDepth> DepthTest for DepthBuffer<'_, K> {
    const ENABLED: bool = true;

    fn clip_rect(&self) -> Option<Rect> {
        Some(self.keys.layout.rect())
    }

    #[inline]
    fn test_span<F: FnMut(u32, u32)>(
        &mut self,
        y: i32,
        x: i32,
        len: u32,
        z: i32,
        dz: i32,
        mut pass: F,
    ) {
        let Some((skip, r)) = self.keys.layout.span(y, x, len) else {
            return;
        };
        let Some(row) = self.keys.buf.get_mut(r) else {
            return;
        };
        let z = z.wrapping_add(dz.wrapping_mul(skip as i32));
        // i + passed ≤ row.len() ≤ len, so these fit in u32.
        passing_runs(row, z, dz, |i, passed| pass(skip + i as u32, passed as u32));
    }

    // Always inlined, as the targets' `span_mut`: the scan converter calls
    // it once per span, and x86-64 left it out of line once the span code
    // had one call site (W1 there: 3.97 M instructions per frame out of
    // line, 3.62 M inlined; ARMv6-M inlined it either way).
    #[inline(always)]
    fn test_write<C, F: FnMut(u32) -> C>(
        &mut self,
        y: i32,
        x: i32,
        z: i32,
        dz: i32,
        pixels: &mut [C],
        color: F,
    ) {
        self.write_passing(y, x, z, dz, pixels, color);
    }

    #[inline(always)]
    fn test_fill<C: Copy>(&mut self, y: i32, x: i32, z: i32, dz: i32, pixels: &mut [C], color: C) {
        if let Some(keys) = self.exact_keys(y, x, pixels.len()) {
            fused_fill(keys, pixels, z, dz, color);
        } else {
            self.write_passing(y, x, z, dz, pixels, |_| color);
        }
    }
}

/// The fused per-pixel loop: test `keys` against the depths `z + i·dz`,
/// and where one passes store it and the pixel `color(i)`.
///
/// Out of line on purpose: inlined into the scan converter, which keeps
/// its edge, plane and clip state live across the span, the loop spilled
/// its depth, step and color to the stack on ARMv6-M (8 low registers):
/// 18 instructions per pixel for flat + depth instead of 11.
#[cfg(feature = "depth")]
#[inline(never)]
fn fused_run<K: StoredDepth, C, F: FnMut(u32) -> C>(
    keys: &mut [K],
    pixels: &mut [C],
    mut z: i32,
    dz: i32,
    mut color: F,
) {
    for ((d, p), i) in keys.iter_mut().zip(pixels).zip(0..) {
        if let Some(key) = K::passes(z, *d) {
            *d = key;
            *p = color(i);
        }
        z = z.wrapping_add(dz);
    }
}

/// [`fused_run`] with one color ([`DepthTest::test_fill`]): an odd first
/// pixel alone, then two pixels per iteration, which on ARMv6-M keeps the
/// color, the depth and its step in registers. Flat + depth 12.25 -> 10.25
/// instructions per pixel (`ipp flat-depth`, `bash tests/mcu/run`; 12.00 ->
/// 10.00 on the Cortex-M4), the flat cube scene frame 1.40 M -> 1.28 M,
/// W1 5.63 M -> 5.58 M, 44 bytes more in the flat firmware. The varying
/// shaders keep [`fused_run`]'s one-pixel loop: paired, the per-span
/// set-up of their indexed color closure cost W2 0.5 % (its spans
/// average 2.5 pixels). On 32-bit Arm a span of 64 pixels or more takes
/// [`split_fill`] instead.
#[cfg(feature = "depth")]
#[inline(never)]
fn fused_fill<K: StoredDepth, C: Copy>(
    keys: &mut [K],
    pixels: &mut [C],
    mut z: i32,
    dz: i32,
    color: C,
) {
    let pixel = |d: &mut K, p: &mut C, z: i32| {
        if let Some(key) = K::passes(z, *d) {
            *d = key;
            *p = color;
        }
    };
    // The same length for both (the callers' spans are), so that the
    // pairs line up.
    let n = keys.len().min(pixels.len());
    let (Some(mut keys), Some(mut pixels)) = (keys.get_mut(..n), pixels.get_mut(..n)) else {
        return;
    };
    if takes_split_route(n) {
        split_fill(keys, pixels, z, dz, color);
        return;
    }
    if n % 2 == 1 {
        let (k, p) = (core::mem::take(&mut keys), core::mem::take(&mut pixels));
        if let (Some((d, k)), Some((p, px))) = (k.split_first_mut(), p.split_first_mut()) {
            pixel(d, p, z);
            z = z.wrapping_add(dz);
            (keys, pixels) = (k, px);
        }
    }
    for (k, p) in keys.chunks_exact_mut(2).zip(pixels.chunks_exact_mut(2)) {
        if let ([k0, k1], [p0, p1]) = (k, p) {
            pixel(k0, p0, z);
            z = z.wrapping_add(dz);
            pixel(k1, p1, z);
            z = z.wrapping_add(dz);
        }
    }
}

/// [`fused_fill`] for a span of 64 pixels or more: the keys first
/// ([`passing_runs`], two a loop iteration), then each run of passing
/// pixels filled by the targets' solid fill (on 2-byte pixels two a
/// store). On ARMv6-M (`bash tests/mcu/run`) flat + depth went from 10.26
/// to 8.76 instructions per pixel (`ipp flat-depth`), the cube scene frame
/// from 857 173 to 851 184 and the banded bunny's from 9 118 591 to
/// 9 095 533; W1, whose spans are a few pixels, from 5 040 966 to
/// 5 060 469 (the length test per span), for 208 bytes in the flat
/// firmware. With the split from 16 pixels on, the cube frame was 868 740
/// instead: on its spans, the three calls per run cost more than the
/// pairs save. (Unrolled by four, the key loop spilled: LLVM's loop
/// strength reduction kept `dz`, `2dz` and `3dz` apart, and the loop took
/// 34 instructions per four keys; [`store_passing`] now hides the
/// recurrence from it.)
///
/// The Cortex-M4 took this route too once [`store_passing`] stored eight
/// keys an iteration (before, with two, its cube frame rose from 775 163
/// to 790 617). `bash tests/mcu/run`, Cortex-M4, fused -> split for both
/// flat and varying spans ([`split_write`]): ipp flat + depth 10.00 ->
/// 7.76, Gouraud + depth 15.00 -> 13.50; scene frames f32 cube 773 198 ->
/// 710 510, corridor-affine 2 678 503 -> 2 539 330, bunny 6 223 483 ->
/// 6 191 371 (I16F16 cube 775 163 -> 712 539); but W1 / W2, whose spans
/// are a few pixels, pay the length tests: f32 3 252 991 / 3 755 565 ->
/// 3 264 948 / 3 771 952 (0.4 %). 152 bytes more in the thumbv7em flat
/// firmware, 512 in the Gouraud one. x86-64 keeps the fused loops (its
/// `memset` and registers serve them).
#[cfg(feature = "depth")]
#[inline(never)]
fn split_fill<K: StoredDepth, C: Copy>(
    keys: &mut [K],
    pixels: &mut [C],
    z: i32,
    dz: i32,
    color: C,
) {
    passing_runs(keys, z, dz, |i, passed| {
        if let Some(run) = pixels.get_mut(i..i + passed) {
            crate::target::fill_unrolled(run, color);
        }
    });
}

/// Whether a depth-tested span of `n` pixels takes the split loops
/// ([`split_fill`], [`split_write`]) instead of the fused ones: spans of
/// 64 pixels or more, on 32-bit Arm only (the figures are at those two).
#[cfg(feature = "depth")]
#[inline(always)]
fn takes_split_route(n: usize) -> bool {
    cfg!(target_arch = "arm") && n >= LONG_SPAN
}

/// The span length from which depth-tested spans test their keys first
/// ([`split_fill`], [`split_write`], [`shades_runs`]).
const LONG_SPAN: usize = 64;

/// [`fused_run`] for a span of 64 pixels or more on 32-bit Arm (as
/// [`split_fill`] for one color): the keys first ([`passing_runs`]), then
/// each run of passing pixels written by a loop of its own, four pixels
/// an iteration. Fused, the loop keeps the depth, the varyings, their
/// steps, the keys, the pixels and the shader's table live together, more
/// than ARMv6-M's seven low registers, and spilled three of them (18
/// instructions per pixel for Gouraud + depth). Split, each loop has
/// registers to spare.
///
/// `bash tests/mcu/run`, ARMv6-M, fused -> split (both with the
/// eight-key [`store_passing`]): ipp Gouraud + depth 18.26 -> 13.63
/// (14.88 with a one-pixel color loop, 140 bytes less in the Gouraud
/// firmware); the textured, depth-tested corridor-affine scene frame
/// 3 951 557 -> 3 622 225; W2 6 001 835 -> 5 973 787. The banded bunny,
/// none of whose spans is this long, pays the length test per span:
/// 9 028 943 -> 9 069 577 (0.45 %). 344 bytes more in the Gouraud
/// firmware, 636 in the texture one (an instance per shader). Short spans
/// keep the fused loop: a run costs two calls and the loop's set-up. The
/// Cortex-M4's figures are at [`split_fill`]. On ARMv6-M the scan
/// converter now hands such spans to the shader's own run loop instead
/// ([`shades_runs`]); this stays the route of [`DepthTest::test_write`]
/// there, and the scan converter's on the Cortex-M4.
#[cfg(feature = "depth")]
#[inline(never)]
fn split_write<K: StoredDepth, C, F: FnMut(u32) -> C>(
    keys: &mut [K],
    pixels: &mut [C],
    z: i32,
    dz: i32,
    mut color: F,
) {
    let n = keys.len().min(pixels.len());
    let keys = keys.get_mut(..n).unwrap_or(&mut []);
    passing_runs(keys, z, dz, |i, passed| {
        if let Some(run) = pixels.get_mut(i..i + passed) {
            let mut j = i as u32;
            let mut quads = run.chunks_exact_mut(4);
            for quad in &mut quads {
                if let [a, b, c, d] = quad {
                    *a = color(j);
                    *b = color(j + 1);
                    *c = color(j + 2);
                    *d = color(j + 3);
                }
                j += 4;
            }
            for p in quads.into_remainder() {
                *p = color(j);
                j += 1;
            }
        }
    });
}

/// Whether the scan converter tests the keys of a depth-tested span of
/// `n` pixels first and then shades each passing run by the shader's
/// [`SpanShader::shade_run`](crate::raster::SpanShader::shade_run),
/// for a shader whose colors it would otherwise write per pixel in
/// [`DepthTest::test_write`]'s fused loop: spans of 64 pixels or more,
/// on ARMv6-M only. [`Gouraud`](crate::raster::Gouraud)'s `shade_run`
/// writes a run in a loop of its own with registers to spare, where the
/// fused loop spills on ARMv6-M's seven low registers.
///
/// ARMv6-M, the [`split_write`] route -> this one: ipp Gouraud + depth,
/// the shader alone, 13.38 -> 11.96; the banded bunny scene frame (none
/// of whose spans is this long) 9 064 719 -> 9 008 246, but W2
/// 5 975 200 -> 6 019 773 (0.75 %: the scan converter's registers). On
/// the Cortex-M4 the same route took W2 (f32) from 3 771 954 to
/// 3 821 421 and the bunny frame from 6 118 897 to 6 221 999, for
/// Gouraud + depth 13.50 -> 11.69, so it keeps [`split_write`]. (The
/// figures after the change are `bash tests/mcu/run`'s; the Cortex-M4's
/// and the 13.38 came from `../shared/tools/qemu-prof` over the same
/// firmware's `fill`, `wl` and `sf` runs.)
#[inline(always)]
pub(super) fn shades_runs(n: usize) -> bool {
    crate::scalar::ARMV6M && n >= LONG_SPAN
}

/// Tests and stores the keys of `row` against the depths `z + i·dz`, and
/// calls `pass(i, n)` for each maximal run of `n` passing keys from `i`,
/// left to right. Two tight loops (skip failing pixels, then store passing
/// ones) instead of one loop with run state, each out of line so that on
/// Cortex-M0 its few registers are not taken by the caller's state.
#[cfg(feature = "depth")]
#[inline(always)]
fn passing_runs<K: StoredDepth>(
    row: &mut [K],
    mut z: i32,
    dz: i32,
    mut pass: impl FnMut(usize, usize),
) {
    let n = row.len();
    let mut i = 0;
    while i < n {
        let (failed, z1) = skip_failing(row.get(i..).unwrap_or(&[]), z, dz);
        i += failed;
        let (passed, z2) = store_passing(row.get_mut(i..).unwrap_or(&mut []), z1, dz);
        z = z2;
        if passed > 0 {
            pass(i, passed);
        }
        i += passed;
    }
}

#[cfg(feature = "depth")]
impl<K: StoredDepth> DepthBuffer<'_, K> {
    /// The keys of span `x..x+len` of row `y` when all of it is inside.
    #[inline(always)]
    fn exact_keys(&mut self, y: i32, x: i32, len: usize) -> Option<&mut [K]> {
        let len = u32::try_from(len).unwrap_or(u32::MAX);
        let band = &mut self.keys;
        band.buf.get_mut(band.layout.span_exact(y, x, len)?)
    }

    /// The fused loop of [`DepthTest::test_write`]: one pass over the
    /// keys and the pixels together.
    #[inline(always)]
    fn write_passing<C, F: FnMut(u32) -> C>(
        &mut self,
        y: i32,
        x: i32,
        z: i32,
        dz: i32,
        pixels: &mut [C],
        mut color: F,
    ) {
        if let Some(keys) = self.exact_keys(y, x, pixels.len()) {
            // The whole span is inside (the scan converter's case).
            if takes_split_route(pixels.len()) {
                split_write(keys, pixels, z, dz, color);
            } else {
                fused_run(keys, pixels, z, dz, color);
            }
            return;
        }
        let len = u32::try_from(pixels.len()).unwrap_or(u32::MAX);
        let band = &mut self.keys;
        let Some((skip, r)) = band.layout.span(y, x, len) else {
            return;
        };
        let (Some(keys), Some(pixels)) = (band.buf.get_mut(r), pixels.get_mut(skip as usize..))
        else {
            return;
        };
        let mut z = z.wrapping_add(dz.wrapping_mul(skip as i32));
        for ((d, p), i) in keys.iter_mut().zip(pixels).zip(skip..) {
            // The span set-up keeps z within 0..=65535·256+255, so the
            // conversion is exact.
            if let Some(key) = K::passes(z, *d) {
                *d = key;
                *p = color(i);
            }
            z = z.wrapping_add(dz);
        }
    }
}

/// Counts leading pixels that fail (key ≥ stored); returns the count and
/// the z after them. The span set-up keeps z within
/// 0..=65535·256+255, so the shift gives the key exactly.
#[cfg(feature = "depth")]
#[inline(never)]
fn skip_failing<K: StoredDepth>(row: &[K], mut z: i32, dz: i32) -> (usize, i32) {
    let mut n = 0;
    for &d in row {
        if K::passes(z, d).is_some() {
            break;
        }
        z = z.wrapping_add(dz);
        n += 1;
    }
    (n, z)
}

/// Stores leading keys that pass (key < stored); returns the count and
/// the z after them (after the last key of `row`, the z past it is
/// returned only up to bit 30, see below; the callers do not use it).
///
/// Sixteen keys a loop iteration, each six instructions on ARMv6-M (shift,
/// load, compare, branch, store, step). The z carried from one iteration
/// to the next is passed through `(z << 1) >> 1`, which keeps every depth
/// the span set-up makes (`0..=65535·256+255`) and costs two instructions
/// an iteration: without it, LLVM's loop strength reduction rewrote the
/// keys' depths as `z + k·dz` from the iteration's first, and kept the
/// multiples `2dz`, `3dz`, … on the stack (34 instructions for four keys).
/// The sign-extending shift hides the recurrence from it, and the steps
/// stay one add each. The loop itself walks one pointer; the count is
/// recovered from the address of the key that fails.
///
/// `bash tests/mcu/run`, two keys an iteration before -> eight now, on
/// ARMv6-M: ipp flat + depth 8.76 -> 7.38 (`split_fill`), persp16 + depth
/// 50.56 -> 49.18; the flat cube scene frame 851 184 -> 779 198, the
/// corridor's 7 752 712 -> 7 667 609; on the Cortex-M4 persp16 + depth
/// 35.00 -> 33.50. W1/W2 do not run it (their spans take the fused
/// loops). 140 bytes more in the flat firmware.
///
/// Eight -> sixteen keys an iteration (`bash tests/mcu/run`, ipp with the
/// shader alone): ARMv6-M flat + depth 7.13 -> 6.82, Gouraud + depth
/// 11.96 -> 11.65, persp16 + depth 40.56 -> 40.25; scene frames I16F16
/// cube 779 343 -> 766 758, bunny 9 008 246 -> 8 997 019, corridor
/// 5 858 400 -> 5 847 478; Cortex-M4 flat + depth 7.76 -> 7.51, f32 cube
/// 709 750 -> 699 308; W1/W2 unchanged. 176 bytes more in each ARMv6-M
/// firmware (the flat one 16 496 -> 16 672).
#[cfg(feature = "depth")]
#[inline(never)]
fn store_passing<K: StoredDepth>(row: &mut [K], mut z: i32, dz: i32) -> (usize, i32) {
    let (base, len) = (row.as_ptr() as usize, row.len());
    // The index of key `k` in `row` (`K` is u16 or u32, never zero-sized).
    let at = |k: &mut K| (core::ptr::from_mut(k) as usize - base) / core::mem::size_of::<K>();
    // Stores key `$d`'s depth `z` if it passes and steps z; else returns
    // the key's index.
    macro_rules! key {
        ($d:ident, $index:expr) => {
            let Some(key) = K::passes(z, *$d) else {
                return ($index, z);
            };
            *$d = key;
            z = z.wrapping_add(dz);
        };
    }
    // `key!` for each of the keys after `$k0;`, the n-th at index
    // `at($k0) + n`.
    macro_rules! keys {
        ($k0:ident; $n:expr;) => {};
        ($k0:ident; $n:expr; $d:ident $($rest:ident)*) => {
            key!($d, at($k0) + $n);
            keys!($k0; $n + 1; $($rest)*);
        };
    }
    let mut blocks = row.chunks_exact_mut(16);
    for block in &mut blocks {
        if let [a, b, c, d, e, f, g, h, i, j, k, l, m, n, o, p] = block {
            keys!(a; 0; a b c d e f g h i j k l m n o p);
            z = (z << 1) >> 1;
        }
    }
    for d in blocks.into_remainder() {
        key!(d, at(d));
    }
    (len, z)
}

#[cfg(all(test, feature = "depth"))]
mod tests {
    use super::*;
    use std::vec;
    use std::vec::Vec;

    /// Both forms of the 16-bit test agree for every depth the span set-up
    /// makes (`0..=65535·256+255`) against a spread of stored keys, and the
    /// key they store is the truncated depth.
    #[test]
    fn both_16_bit_depth_tests_agree() {
        let stored = [0u16, 1, 2, 255, 256, 4096, 32767, 32768, 65534, 65535];
        for z in (0..=(65535 << DEPTH_FRAC_BITS) | 255)
            .step_by(37)
            .chain([0, 255, 256])
        {
            for &d in &stored {
                let want = ((z >> DEPTH_FRAC_BITS) < i32::from(d))
                    .then_some((z >> DEPTH_FRAC_BITS) as u16);
                assert_eq!(passes16_wide(z, d), want, "z {z}, stored {d}");
                assert_eq!(passes16_narrow(z, d), want, "z {z}, stored {d}");
            }
        }
    }

    /// The paired one-color loop against the rule stated per pixel (key
    /// `(z + i·dz) >> 8` stored, and the color written, where it is below
    /// the stored key), for every length up to 11 (odd and even, so both
    /// the lone first pixel and the pairs), and lengths around and above
    /// the 64 pixels from which [`split_fill`] takes over on 32-bit Arm (it
    /// is also checked on its own, and so is [`split_write`], the route of
    /// the varying shaders' long spans there, with a color per pixel
    /// index), stored keys
    /// that make runs pass and fail (random keys, and mostly far keys for
    /// long passing runs), both key widths, 1- and 2-byte pixels (the
    /// latter filled two a store), and slices of unequal length (only the
    /// common prefix is touched).
    #[test]
    fn fused_fill_is_the_per_pixel_rule() {
        fn check<K: StoredDepth, P>(rng: &mut crate::test_util::Rng)
        where
            P: Copy + From<u8> + PartialEq + core::fmt::Debug,
        {
            for len in (0..12usize).chain([15, 16, 17, 24, 63, 64, 65, 66, 71, 100, 131]) {
                // Out of 8, how many stored keys are far (pass surely).
                let far = [0, 4, 7, 8][rng.int(0, 3) as usize];
                for extra in [0usize, 0, 0, 1, 3] {
                    // Near depths, or the far end of the range (keys
                    // above 2^15, depths above 2^23).
                    let top = [0, 65000 << DEPTH_FRAC_BITS][rng.int(0, 1) as usize];
                    let z0 = top + rng.int(0, 200 << DEPTH_FRAC_BITS) as i32;
                    let dz = rng.int(-600, 600) as i32;
                    // Within the set-up's range at every pixel
                    // (0..=65535·256+255: at most 65000·256 + 51 200 +
                    // 600·134 here).
                    let z0 = z0.max(-dz * (len as i32 + 3)).max(0);
                    let stored: Vec<K> = (0..len + extra)
                        .map(|_| {
                            if rng.int(0, 7) < far {
                                K::FAR
                            } else {
                                K::from_z(top + rng.int(0, 260 << DEPTH_FRAC_BITS) as i32)
                            }
                        })
                        .collect();
                    let (klen, plen) = if rng.int(0, 1) == 0 {
                        (len + extra, len)
                    } else {
                        (len, len + extra)
                    };
                    let mut keys = stored[..klen.min(stored.len())].to_vec();
                    keys.resize(klen, K::FAR);
                    let mut want_keys = keys.clone();
                    let mut want_px = vec![P::from(0); plen];
                    for i in 0..klen.min(plen) {
                        let z = z0 + dz * i as i32;
                        let key = K::from_z(z);
                        if key < want_keys[i] {
                            want_keys[i] = key;
                            want_px[i] = P::from(7);
                        }
                    }
                    let mut px = vec![P::from(0); plen];
                    // The split route directly too (only 32-bit Arm takes it
                    // from `fused_fill`), on the common prefix.
                    let n = klen.min(plen);
                    let (mut keys2, mut px2) = (keys[..n].to_vec(), px[..n].to_vec());
                    split_fill(&mut keys2, &mut px2, z0, dz, P::from(7));
                    assert_eq!(keys2, want_keys[..n], "split: len {len} z {z0} dz {dz}");
                    assert_eq!(px2, want_px[..n], "split: len {len} z {z0} dz {dz}");
                    // And `split_write`, with a color per index.
                    let (mut keys3, mut px3) = (keys[..n].to_vec(), px[..n].to_vec());
                    let shade = |i: u32| P::from((i % 250) as u8 + 1);
                    split_write(&mut keys3, &mut px3, z0, dz, shade);
                    let want3: Vec<P> = (0..n)
                        .map(|i| {
                            let passed = want_px[i] == P::from(7);
                            if passed { shade(i as u32) } else { P::from(0) }
                        })
                        .collect();
                    assert_eq!(
                        keys3,
                        want_keys[..n],
                        "split write: len {len} z {z0} dz {dz}"
                    );
                    assert_eq!(px3, want3, "split write: len {len} z {z0} dz {dz}");
                    fused_fill(&mut keys, &mut px, z0, dz, P::from(7));
                    assert_eq!(keys, want_keys, "len {len} z {z0} dz {dz}");
                    assert_eq!(px, want_px, "len {len} z {z0} dz {dz}");
                }
            }
        }
        let mut rng = crate::test_util::Rng::new(11);
        for _ in 0..300 {
            check::<u16, u8>(&mut rng);
            check::<u32, u8>(&mut rng);
            check::<u16, u16>(&mut rng);
            check::<u32, u16>(&mut rng);
        }
    }

    /// The word-wide clear (32-bit targets' route, run here directly)
    /// sets exactly the keys it is given to far, at every start alignment
    /// and for lengths around the 16-word loop's multiples, and leaves
    /// the keys on both sides alone.
    #[test]
    fn word_clear_sets_exactly_its_keys_to_far() {
        fn check<K: StoredDepth>(seven: K) {
            for start in 0..4 {
                for len in (0..80).chain([255, 256, 257, 320, 321]) {
                    let mut keys = vec![seven; start + len + 3];
                    fill_far_words(&mut keys[start..start + len]);
                    for (i, &k) in keys.iter().enumerate() {
                        let inside = (start..start + len).contains(&i);
                        let want = if inside { K::FAR } else { seven };
                        assert_eq!(k, want, "start {start} len {len} key {i}");
                    }
                }
            }
        }
        check::<u16>(7);
        check::<u32>(7);
    }

    /// `clear` fills each row of a strided buffer and nothing between
    /// rows, and a gapless buffer whole.
    #[test]
    fn clear_fills_rows_only() {
        for stride in [5usize, 7] {
            let mut keys = vec![3u16; stride * 3 + 2];
            let mut z = DepthBuffer::new(&mut keys, 5, 3, stride, 0).unwrap();
            z.clear();
            for (i, &k) in keys.iter().enumerate() {
                let inside = i < stride * 3 && i % stride < 5;
                assert_eq!(
                    k,
                    if inside { u16::MAX } else { 3 },
                    "stride {stride} key {i}"
                );
            }
        }
    }
}

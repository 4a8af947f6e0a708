//! Texture-mapping span shaders: nearest-texel sampling of a
//! [`Texture`] through [`Texture::sample`] (the crate's one texel store
//! and sampler, in [`crate::texture`]), affine or perspective-correct.
//! The wrap mode is a type parameter ([`Wrap`]): no per-pixel branch on
//! it, and [`RepeatPow2`](crate::texture::RepeatPow2) is one AND per axis.
//!
//! - [`AffineTexture`] interpolates (u, v) linearly in screen space: exact
//!   for parallel projection and for polygons parallel to the screen,
//!   distorted (swimming) for steep polygons under perspective.
//! - [`PerspectiveTexture`] interpolates (u/z, v/z, 1/z), which *are*
//!   linear in screen space, and divides. With `N = 1` (exact mode) every
//!   pixel gets the texel of its own exact quotient: on a slice target a
//!   division every 64 pixels, and an exact integer step of each texel
//!   coordinate between them. With `N = 8`, `16` or `32` it
//!   computes (u, v) at every N-th pixel of a span (and at its last pixel)
//!   and steps linearly between them (the classic subdivided affine
//!   compromise). Each division is division-free
//!   ([`persp_div`](super::persp_div)): a reciprocal estimate, products,
//!   and a correction by the exact remainder, in 32-bit arithmetic where
//!   the quotients are small (exact mode's texels everywhere, the run
//!   ends on ARMv6-M). The step over a full run is a shift. The
//!   instructions per pixel of exact mode and of 16-pixel runs on ARMv6-M
//!   and ARMv7E-M are in the generated `docs/mcu/tables.md`
//!   (`ipp persp`, `ipp persp16`).

#[cfg(feature = "perspective")]
use super::PERSPECTIVE_Q_BITS;
#[cfg(feature = "perspective")]
use super::persp_div::{divide, divide_small, divide_small_wide, texels};
#[cfg(feature = "perspective")]
use super::shader::shade_per_pixel;
use super::shader::{ScalableColor, SpanShader, VARYING_FRAC_BITS};
use crate::target::Target;
use crate::texture::{MaskedTexels, Texture, Wrap};
#[cfg(feature = "perspective")]
use crate::texture::{PAIRS, sample_coords};
use core::marker::PhantomData;

/// Affine texture mapping: varyings (u, v) in texels, 16.16.
///
/// Per pixel: two adds, two shifts, the wrap, one multiply-add for the
/// index and one load. On slice targets, a [`RepeatPow2`](crate::texture::RepeatPow2)
/// texture whose stride is a power of two and whose `stride·height` is at
/// most 2^16 texels is sampled through masks instead (no multiply, no
/// bounds check per pixel), with the same texels.
#[derive(Clone, Copy, Debug)]
pub struct AffineTexture<'a, C, W> {
    tex: Texture<'a, C>,
    /// The texture's masks, where it has them (decided once, here).
    masked: Option<MaskedTexels<'a, C>>,
    wrap: PhantomData<W>,
}

impl<'a, C: Copy, W: Wrap> AffineTexture<'a, C, W> {
    /// An affine texture shader; `None` if `W` does not accept the
    /// texture's size ([`RepeatPow2`](crate::texture::RepeatPow2) needs powers of two).
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        tex.accepts::<W>().then_some(Self {
            tex,
            masked: tex.masked::<W>(),
            wrap: PhantomData,
        })
    }
}

impl<C: Copy, W: Wrap> SpanShader<2> for AffineTexture<'_, C, W> {
    type Color = C;
    // `shade_run` gives `color` at every pixel, so either route draws the
    // same pixels; with a depth buffer, testing the keys first and then
    // shading the passing runs in `shade_run`'s loop costs less than
    // `color` per pixel inside the depth loop (corridor-affine frame,
    // I16F16 on ARMv6-M: 3 069 376 instructions with `PER_PIXEL`, 2 868 398
    // without; the tests/mcu firmware's `sf corridor-affine I16F16 1|0`
    // under QEMU, counted by `../shared/tools/qemu-prof`; the second is
    // the figure `bash tests/mcu/run` published).
    const PER_PIXEL: bool = false;

    #[inline]
    fn color(&self, v: &[i32; 2]) -> C {
        self.tex
            .sample::<W>(v[0] >> VARYING_FRAC_BITS, v[1] >> VARYING_FRAC_BITS)
    }

    /// [`Self::color`] at every pixel: on a slice target, for a
    /// [`RepeatPow2`](crate::texture::RepeatPow2) texture of at most 2^16
    /// texels with a power-of-two stride, through masks instead of a
    /// multiply and a bounds check per pixel (the same texels: `bash
    /// tests/mcu/run`, ipp affine, ARMv6-M 24.26 -> 19.76, Cortex-M4
    /// 15.00 -> 9.00).
    #[inline]
    fn shade_run<T: Target<Color = C>>(
        &self,
        target: &mut T,
        y: i32,
        x: i32,
        len: u32,
        start: [i32; 2],
        step: [i32; 2],
    ) {
        if let Some(m) = &self.masked
            && let Some(pixels) = target.span_mut(y, x, len)
        {
            m.fill_run(pixels, (start[0], start[1]), (step[0], step[1]));
            return;
        }
        // Not `shade_per_pixel`: with it here, the corridor-affine frame
        // (f32, Cortex-M4) took 2 033 058 instructions against 1 943 019,
        // though this loop does the same (tests/mcu firmware, `sf
        // corridor-affine f32 1|0` under `../shared/tools/qemu-prof`).
        let mut v = start;
        target.fill_with(y, x, len, || {
            let c = self.color(&v);
            v[0] = v[0].wrapping_add(step[0]);
            v[1] = v[1].wrapping_add(step[1]);
            c
        });
    }
}

/// Affine texture mapping modulated by Gouraud intensity: varyings
/// (intensity 0..=255, u, v), all 16.16, as
/// [`IntensityUv`](crate::pipeline::IntensityUv) vertices produce. Each
/// pixel is its texel scaled by the interpolated intensity
/// ([`ScalableColor::scale`]), so full intensity (255) gives exactly
/// [`AffineTexture`]'s color.
///
/// Per pixel: the affine texture's work plus one scale per channel.
#[derive(Clone, Copy, Debug)]
pub struct LitAffineTexture<'a, C, W> {
    tex: Texture<'a, C>,
    wrap: PhantomData<W>,
}

impl<'a, C: ScalableColor, W: Wrap> LitAffineTexture<'a, C, W> {
    /// A lit affine texture shader; `None` if `W` does not accept the
    /// texture's size.
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        tex.accepts::<W>().then_some(Self {
            tex,
            wrap: PhantomData,
        })
    }
}

impl<C: ScalableColor, W: Wrap> SpanShader<3> for LitAffineTexture<'_, C, W> {
    type Color = C;

    #[inline]
    fn color(&self, v: &[i32; 3]) -> C {
        // The intensity varying shares the default range with u and v, so
        // clamp it into 0..=255 here.
        let i = (v[0] >> VARYING_FRAC_BITS).clamp(0, 255) as u8;
        self.tex
            .sample::<W>(v[1] >> VARYING_FRAC_BITS, v[2] >> VARYING_FRAC_BITS)
            .scale(i)
    }
}

/// Perspective-correct texture mapping from the varyings
/// (u·q, v·q, q) with `q = near/z`: (u, v) = (u·q / q, v·q / q).
///
/// `N` is the run length: 1 for exact mode (the texel of every pixel's
/// own quotient; see [`SpanShader::color`], stepped exactly between
/// divisions 64 pixels apart on slice targets), 8, 16 or 32 for
/// subdivided affine runs (any `N ≥ 1` works; a power of two makes the
/// step a shift). Every division below 2^13 texels is a division-free
/// reciprocal with a remainder check, and gives the exact truncated
/// quotient. Beyond that (rare), `N = 1` divides exactly with the crate's
/// 64-bit division, and the ends of longer runs keep the reciprocal,
/// above the quotient by at most `4·T/2^31 + 1` units of 2^−16 for a
/// quotient of `T` units. With `N > 1`, (u, v) at every N-th pixel and at
/// the span's last pixel come from it, and the pixels between are stepped
/// linearly, in 32-bit arithmetic when every run end is below 2^13
/// texels. In both modes, on slice targets, a [`RepeatPow2`](crate::texture::RepeatPow2)
/// texture of at most 2^16 texels with a power-of-two stride is sampled
/// through masks instead of a multiply and a bounds check per pixel.
/// Feed it [`UvPerspective`](crate::pipeline::UvPerspective) vertices.
#[cfg(feature = "perspective")]
#[derive(Clone, Copy, Debug)]
pub struct PerspectiveTexture<'a, C, W, const N: u32> {
    tex: Texture<'a, C>,
    /// The texture's masks, where it has them (decided once, here).
    masked: Option<MaskedTexels<'a, C>>,
    wrap: PhantomData<W>,
}

#[cfg(feature = "perspective")]
impl<'a, C: Copy, W: Wrap, const N: u32> PerspectiveTexture<'a, C, W, N> {
    /// A perspective texture shader; `None` if `W` does not accept the
    /// texture's size.
    #[must_use]
    pub fn new(tex: Texture<'a, C>) -> Option<Self> {
        tex.accepts::<W>().then_some(Self {
            tex,
            masked: tex.masked::<W>(),
            wrap: PhantomData,
        })
    }
}

#[cfg(feature = "perspective")]
impl<C: Copy, W: Wrap, const N: u32> PerspectiveTexture<'_, C, W, N> {
    /// Pixels of one run of the general slice path from (u, v) = `a`
    /// stepping by `d` (16.16), in i64. Only spans with a run end beyond
    /// [`Self::small_runs`]' range (2^13 texels) get here, so it keeps no
    /// i32 loop of its own.
    #[inline]
    fn fill_run(&self, run: &mut [C], a: (i64, i64), d: (i64, i64)) {
        let mut cur = a;
        for p in run {
            *p = self.tex.sample::<W>(texel_coord(cur.0), texel_coord(cur.1));
            cur.0 += d.0;
            cur.1 += d.1;
        }
    }

    /// The slice path when every run end is small: each (u, v) from
    /// [`divide_small`] (|u|, |v| below 2^13 texels, where the divide is
    /// exact), so the steps and every pixel's value are i32 and the run
    /// set-up has no 64-bit arithmetic. The same pixels as the general
    /// path, whose run ends and steps are the same values in i64; `false`
    /// (having written some pixels, all of which the general path then
    /// overwrites with the same values) as soon as a run end is not
    /// small.
    #[inline]
    fn small_runs(&self, pixels: &mut [C], start: [i32; 3], step: [i32; 3]) -> bool {
        let n = N.max(1) as usize;
        // One run ahead: `start + step·(i + N)` as `start + step·i + step·N`
        // (equal modulo 2^32).
        let ahead = step.map(|s| s.wrapping_mul(n as i32));
        let mut v = start;
        let Some(mut a) = divide_small(&v) else {
            return false;
        };
        // A copy: read from `self` in `fill_small`, ARMv6-M ipp persp16
        // was 34.69 against 34.19.
        let masked = self.masked;
        let mut rest = pixels;
        while rest.len() > n {
            let (run, tail) = rest.split_at_mut(n);
            // Written out: at opt-level "s" the three-element loop stayed
            // a loop, through the stack (`bash tests/mcu/run`, ipp
            // persp16 33.94 -> 33.13 on ARMv6-M, 22.50 -> 21.94 on the
            // Cortex-M4).
            v = [
                v[0].wrapping_add(ahead[0]),
                v[1].wrapping_add(ahead[1]),
                v[2].wrapping_add(ahead[2]),
            ];
            let Some(b) = divide_small(&v) else {
                return false;
            };
            // |a|, |b| < 2^29: no overflow. As the general path: a shift
            // for a power of two, else a truncating division.
            let d = if N.is_power_of_two() {
                let k = N.trailing_zeros();
                ((b.0 - a.0) >> k, (b.1 - a.1) >> k)
            } else {
                ((b.0 - a.0) / n as i32, (b.1 - a.1) / n as i32)
            };
            self.fill_small(masked, run, a, d);
            a = b;
            rest = tail;
        }
        // The last run (1 to N pixels) steps towards the span's last pixel.
        let seg = rest.len() as i32;
        if seg > 1 {
            let i = (rest.len() - 1) as i32;
            let last = [0, 1, 2].map(|k| v[k].wrapping_add(step[k].wrapping_mul(i)));
            let Some(b) = divide_small(&last) else {
                return false;
            };
            let d = ((b.0 - a.0) / (seg - 1), (b.1 - a.1) / (seg - 1));
            self.fill_small(masked, rest, a, d);
        } else {
            self.fill_small(masked, rest, a, (0, 0));
        }
        true
    }

    /// The texel exact mode samples for varyings `v`: each coordinate is
    /// `T >> 16` for the truncated quotient `T = trunc(x·2^24 / q)` (16.16)
    /// of `x = u·q` by `q` (q ≤ 0 taken as 1), clamped to i32.
    #[inline]
    fn texel(&self, v: &[i32; 3]) -> (i32, i32) {
        // The same values every way: at texel precision where it can,
        // else the small divide by 64-bit products, else the 64-bit
        // division.
        if let Some(t) = texels(v) {
            return t;
        }
        match divide_small_wide(v) {
            Some((u, t)) => (u >> VARYING_FRAC_BITS, t >> VARYING_FRAC_BITS),
            None => Self::texel_wide(v),
        }
    }

    /// [`Self::texel`] beyond the small divide's range (|u| or |v| of
    /// 2^13 texels or more): rare, so out of line, and the exact truncated
    /// quotients by the crate's 64-bit division.
    #[cold]
    #[inline(never)]
    fn texel_wide(v: &[i32; 3]) -> (i32, i32) {
        let q = v[2].max(1) as i64;
        let t = |x: i32| crate::scalar::div_rem_i64((x as i64) << PERSPECTIVE_Q_BITS, q).0;
        (texel_coord(t(v[0])), texel_coord(t(v[1])))
    }

    /// Exact mode on a slice: [`SpanShader::color`]'s texel at every pixel,
    /// with a division only every [`EXACT_RUN`] pixels.
    ///
    /// Along a span, x = u·q and q are linear in the pixel index, so
    /// u = x/q is monotonic wherever q > 0. A run's pixels take texels
    /// between the exact ones at its first pixel and at its far end (the
    /// next run's first pixel, or the span's last), and each pixel's
    /// floor `F = ⌊x·2^8 / q⌋` is stepped from the previous pixel's, with
    /// `E = x·2^8 − F·q` brought into `[0, q)` by adding or subtracting `q`,
    /// one unit of F at a time. `E` is exact in wrapping i32 arithmetic:
    /// with the ends' texels `d` apart and neither clamped, F lies within
    /// `d + 2` of its previous value, so `|E| < (d + 3)·q`, and the run
    /// checks `(d + 3)·q < 2^31` for q up to the larger end's, and q in
    /// `[1, 2^24]` at both ends (hence between them). That admits about
    /// 120 texels per run at q = 2^24 (z at the near plane), more further
    /// away. The texel is then F, or F + 1 for x < 0 when truncating `T`
    /// toward zero crosses a texel (`E > q − ⌈q/2^16⌉`), stored as i16
    /// (the ends' texels are checked to lie within ±32766). A run outside
    /// those bounds, or whose varyings would wrap, takes `color` at every
    /// pixel (the same texels, a division each).
    fn exact_runs(&self, pixels: &mut [C], start: [i32; 3], step: [i32; 3]) {
        let len = pixels.len();
        let mut v = start;
        let mut ta = self.texel(&v);
        let mut rest = pixels;
        let mut i = 0usize;
        // Each run's texel coordinates, before sampling.
        let (mut tu, mut tv) = ([0i16; EXACT_RUN], [0i16; EXACT_RUN]);
        while !rest.is_empty() {
            let n = rest.len().min(EXACT_RUN);
            let (run, tail) = rest.split_at_mut(n);
            let far = if i + n < len { n } else { n - 1 };
            let vb: [i32; 3] =
                core::array::from_fn(|k| v[k].wrapping_add(step[k].wrapping_mul(far as i32)));
            let tb = self.texel(&vb);
            if !self.exact_run(run, (v, ta), (vb, tb), step, (&mut tu, &mut tv)) {
                let mut w = v;
                for p in run.iter_mut() {
                    *p = self.color(&w);
                    for (wk, sk) in w.iter_mut().zip(&step) {
                        *wk = wk.wrapping_add(*sk);
                    }
                }
            }
            // The far end is the next run's first pixel (or past the last
            // run).
            v = vb;
            ta = tb;
            i += n;
            rest = tail;
        }
    }

    /// One run of [`Self::exact_runs`] from varyings `v` (texels `ta`) to
    /// its far end `vb` (texels `tb`); `false`, having written nothing, if
    /// the run is outside the stepping's bounds.
    #[inline]
    fn exact_run(
        &self,
        run: &mut [C],
        (v, ta): ([i32; 3], (i32, i32)),
        (vb, tb): ([i32; 3], (i32, i32)),
        step: [i32; 3],
        scratch: (&mut [i16; EXACT_RUN], &mut [i16; EXACT_RUN]),
    ) -> bool {
        const Q_MAX: i32 = 1 << PERSPECTIVE_Q_BITS;
        // Linear between the ends, with no wrap: a step below 2^30 / run
        // length moves a varying by less than 2^30 over a run, and the far
        // end is then the true sum exactly when it did not overflow.
        let m = run.len() as i32;
        let linear = (0..3).all(|k| {
            step[k].unsigned_abs() < (1 << 30) / EXACT_RUN as u32
                && v[k].checked_add(step[k] * m).is_some()
        });
        let q_ok = |q: i32| (1..=Q_MAX).contains(&q);
        if !(linear && q_ok(v[2]) && q_ok(vb[2])) {
            return false;
        }
        // Texels within ±32766 (unclamped, so F is within one of each,
        // and every texel between, one beyond at most, fits i16), few
        // enough apart that (d + 3)·q < 2^31 for q up to the larger end's:
        // checked as (d + 3)·(⌊q/2^12⌋ + 1) < 2^19, within u32 for d < 2^12.
        let q_units = (v[2].max(vb[2]) >> 12) as u32 + 1;
        let near = |a: i32, b: i32| {
            let d = a.abs_diff(b);
            d < 1 << 12
                && (d + 3) * q_units < 1 << 19
                && a.unsigned_abs().max(b.unsigned_abs()) < i16::MAX as u32
        };
        if !(near(ta.0, tb.0) && near(ta.1, tb.1)) {
            return false;
        }
        // One coordinate at a time (fewer live values than both at once:
        // ARMv6-M has eight low registers), then the texels.
        let (tu, tv) = scratch;
        // Where both ends' texels are at least 1, F ≥ 0 (x ≥ 0) throughout
        // and the loop needs no sign test; F is then the texel, so the
        // ends' texels give the way F moves (see `floor_run`).
        for (out, x, dx, a, b) in [
            (&mut *tu, v[0], step[0], ta.0, tb.0),
            (&mut *tv, v[1], step[1], ta.1, tb.1),
        ] {
            let out = &mut out[..run.len()];
            if a.min(b) < 1 {
                floor_run::<true, true, true>(out, x, dx, v[2], step[2], a);
            } else if a <= b {
                floor_run::<false, true, false>(out, x, dx, v[2], step[2], a);
            } else {
                floor_run::<false, false, true>(out, x, dx, v[2], step[2], a);
            }
        }
        self.sample_run(run, &tu[..], &tv[..]);
        true
    }

    /// `run[j]` = the texel at `(u[j], v[j])`, through the texture's masks
    /// where it has them (`bash tests/mcu/run`: ARMv6-M ipp persp 55.43 ->
    /// 52.38, Cortex-M4 40.93 -> 37.93). Out of line: inlined into the run
    /// loop of [`Self::exact_runs`], it spilled.
    #[inline(never)]
    fn sample_run(&self, run: &mut [C], u: &[i16], v: &[i16]) {
        if let Some(m) = &self.masked {
            m.sample_run(run, u, v);
        } else {
            self.sample_by::<{ PAIRS }>(run, u, v);
        }
    }

    /// [`Self::sample_run`] without masks, two pixels an iteration with
    /// `P` (ARMv6-M's route: the texture's masks, stride and size, which it
    /// reloads from the stack, then serve both). `bash tests/mcu/run`: ipp
    /// persp 60.59 -> 58.34, corridor frame 7 414 592 -> 7 289 505, for
    /// 168 bytes. On the Cortex-M4 the pairs cost more (ipp 43.76 ->
    /// 44.58, f32 corridor frame +1.5 %), and x86-64 was even (`workload
    /// fill persp`, callgrind 51.29 -> 51.25 instructions per pixel).
    /// (Those figures predate the masked route, which the built-in scenes
    /// now take.)
    #[inline(always)]
    pub(super) fn sample_by<const P: bool>(&self, run: &mut [C], u: &[i16], v: &[i16]) {
        sample_coords::<_, P>(run, u, v, |x, y| {
            Some(self.tex.sample::<W>(x.into(), y.into()))
        });
    }

    /// One run from (u, v) = `a` by `d`, every value within i32 (see
    /// [`Self::small_runs`]).
    #[inline]
    fn fill_small(
        &self,
        masked: Option<MaskedTexels<'_, C>>,
        run: &mut [C],
        a: (i32, i32),
        d: (i32, i32),
    ) {
        if let Some(m) = masked {
            m.fill_run(run, a, d);
            return;
        }
        let (mut u, mut v) = a;
        for p in run {
            *p = self
                .tex
                .sample::<W>(u >> VARYING_FRAC_BITS, v >> VARYING_FRAC_BITS);
            u = u.wrapping_add(d.0);
            v = v.wrapping_add(d.1);
        }
    }
}

/// Pixels per run of exact mode's stepping: one division per run, and
/// two arrays of this length on the stack. On ARMv6-M (`ipp persp`), with
/// i32 arrays: 97.99 instructions per pixel with 16, 79.64 with 32, 68.67
/// with 64; with i16 arrays (texels within ±32766, else the run divides
/// per pixel) 64 costs 70.95 and the stack of 32 i32 entries, 256 bytes.
#[cfg(feature = "perspective")]
const EXACT_RUN: usize = 64;

/// Exact mode's texel coordinate at each pixel of a run (see
/// `exact_runs`): x and q step by `dx` and `dq`, q stays in `[1, 2^24]`,
/// and `f`, starting from the first pixel's texel, stays close enough to
/// `F = ⌊x·2^8 / q⌋` that `|x·2^8 − f·q| < 2^31`. Each pixel steps `f` to
/// F with `E = x·2^8 − F·q` in `[0, q)`, then writes F, or F + 1 when
/// x < 0 (exactly when F < 0) and `E > q − ⌈q/2^16⌉`. Without `SIGNED`
/// the caller has shown F ≥ 0 throughout, and the sign test is left out
/// (ARMv6-M `ipp persp` 70.95 → 65.31, corridor frame −4.9 %, 200 bytes).
/// The step of E, `dx·2^8 − f·dq`, is kept up to date as f moves (one
/// add per texel crossed) instead of multiplied at each pixel: ARMv6-M
/// `ipp persp` 65.31 → 60.59, corridor frame 7 667 609 → 7 414 592;
/// Cortex-M4 45.72 → 43.76, f32 corridor frame 5 234 445 → 5 219 269;
/// 12 bytes (`bash tests/mcu/run`).
///
/// `UP` and `DOWN` say which way f may have to move: both, or only one
/// when the caller knows the direction. Along a run where q > 0, `x/q`
/// is monotonic (the sign of its slope is that of `dx·q − x·dq`, the
/// same at every pixel), so F moves one way only; with f starting at F
/// (no `SIGNED`), E then leaves `[0, q)` on one side only, and one test
/// per pixel is left out: ARMv6-M `ipp persp` 58.34 → 55.43, corridor
/// frame 7 289 505 → 7 107 806; Cortex-M4 43.76 → 40.93, f32 corridor
/// frame 5 219 269 → 5 032 631; x86-64 `workload fill persp` 51.25 →
/// 46.52 (callgrind); 104 bytes.
#[cfg(feature = "perspective")]
#[inline(never)]
fn floor_run<const SIGNED: bool, const UP: bool, const DOWN: bool>(
    out: &mut [i16],
    x: i32,
    dx: i32,
    mut q: i32,
    dq: i32,
    mut f: i32,
) {
    // E from the previous pixel's: x·2^8 − f·q moves by h = dx·2^8 − f·dq
    // (wrapping, as E itself: only its true value is bounded), and h
    // moves by ∓dq as f steps by ±1.
    let mut e = (x << 8).wrapping_sub(f.wrapping_mul(q));
    let mut h = (dx << 8).wrapping_sub(f.wrapping_mul(dq));
    for t in out {
        while DOWN && e < 0 {
            f -= 1;
            e += q;
            h = h.wrapping_add(dq);
        }
        while UP && e >= q {
            f += 1;
            e -= q;
            h = h.wrapping_sub(dq);
        }
        // F < 0 exactly when x < 0 (never without `SIGNED`).
        *t = (if SIGNED && f < 0 && e > q - ((q + 0xffff) >> 16) {
            f + 1
        } else {
            f
        }) as i16;
        e = e.wrapping_add(h);
        q = q.wrapping_add(dq);
    }
}

#[cfg(feature = "perspective")]
#[inline]
fn texel_coord(u: i64) -> i32 {
    (u >> VARYING_FRAC_BITS).clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

#[cfg(feature = "perspective")]
impl<C: Copy, W: Wrap, const N: u32> SpanShader<3> for PerspectiveTexture<'_, C, W, N> {
    type Color = C;
    // Runs of N > 1 step between exact divisions, which `color` alone
    // cannot reproduce. Exact mode (N = 1) gives `color`'s values, but
    // its own run (a division every 64 pixels, stepped exactly between)
    // is far cheaper than `color` at every pixel, so the depth test hands
    // it runs too.
    const PER_PIXEL: bool = false;

    #[inline]
    fn color(&self, v: &[i32; 3]) -> C {
        let (u, t) = self.texel(v);
        self.tex.sample::<W>(u, t)
    }

    fn shade_run<T: Target<Color = C>>(
        &self,
        target: &mut T,
        y: i32,
        x: i32,
        len: u32,
        start: [i32; 3],
        step: [i32; 3],
    ) {
        if N <= 1 {
            if let Some(pixels) = target.span_mut(y, x, len) {
                self.exact_runs(pixels, start, step);
                return;
            }
            shade_per_pixel(self, target, (y, x, len), start, step);
            return;
        }
        // (u, v) from a reciprocal at the first pixel of every run of N
        // and at the span's last pixel; linear steps between. Run k covers
        // pixels kN..kN+N and steps from its start towards the next run's
        // start, so every endpoint serves two runs (one reciprocal per N
        // pixels) and, N being a power of two, the step is a shift. The
        // last run steps towards the span's last pixel, so no endpoint
        // lies outside the span, where q may leave the polygon's range.
        let at = |i: u32| -> (i64, i64) {
            let i = i as i32;
            divide(&[
                start[0].wrapping_add(step[0].wrapping_mul(i)),
                start[1].wrapping_add(step[1].wrapping_mul(i)),
                start[2].wrapping_add(step[2].wrapping_mul(i)),
            ])
        };
        // The step of one run of `seg` pixels starting at `i` with (u, v)
        // `a`, and the next run's start.
        let run_step = |i: u32, seg: u32, a: (i64, i64)| -> ((i64, i64), (i64, i64)) {
            if i.saturating_add(seg) < len {
                let b = at(i + seg);
                let d = if seg == N && N.is_power_of_two() {
                    let k = N.trailing_zeros();
                    ((b.0 - a.0) >> k, (b.1 - a.1) >> k)
                } else {
                    // `checked_div`: seg ≥ 1 here, but this keeps the
                    // division's panic path out of the binary.
                    let n = seg as i64;
                    (
                        (b.0 - a.0).checked_div(n).unwrap_or(0),
                        (b.1 - a.1).checked_div(n).unwrap_or(0),
                    )
                };
                (d, b)
            } else if seg > 1 {
                let b = at(len - 1);
                let n = seg as i64 - 1;
                (
                    (
                        (b.0 - a.0).checked_div(n).unwrap_or(0),
                        (b.1 - a.1).checked_div(n).unwrap_or(0),
                    ),
                    b,
                )
            } else {
                ((0, 0), a)
            }
        };
        if let Some(pixels) = target.span_mut(y, x, len) {
            if self.small_runs(pixels, start, step) {
                return;
            }
            // Slice target: the same values as the general path below, one
            // run of N at a time in a tight loop.
            let mut i = 0u32;
            let mut a = at(0);
            for run in pixels.chunks_mut(N as usize) {
                let seg = run.len() as u32;
                let (d, next) = run_step(i, seg, a);
                self.fill_run(run, a, d);
                a = next;
                i += seg;
            }
            return;
        }
        let mut i = 0u32;
        let mut cur = at(0);
        let (mut d, mut next) = ((0i64, 0i64), cur);
        let mut left = 0u32;
        target.fill_with(y, x, len, || {
            if left == 0 {
                // `max(1)`: robust even if a target called this more than `len`
                // times, which the `Target` contract rules out.
                let seg = N.min(len.saturating_sub(i)).max(1);
                cur = next;
                (d, next) = run_step(i, seg, cur);
                left = seg;
            }
            let c = self.tex.sample::<W>(texel_coord(cur.0), texel_coord(cur.1));
            left -= 1;
            i += 1;
            cur.0 += d.0;
            cur.1 += d.1;
            c
        });
    }
}

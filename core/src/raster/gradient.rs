//! Plane equations for interpolated quantities (depth, intensity, texel
//! coordinates), set up once per polygon and evaluated once per span.
//!
//! A quantity `a` given at three vertices is the plane
//! `a(X, Y) = a₀ + g_x·(X − x₀) + g_y·(Y − y₀)` over 28.4 screen
//! coordinates, with `g_x = (Δa₁·e₂y − Δa₂·e₁y) / A`,
//! `g_y = (Δa₂·e₁x − Δa₁·e₂x) / A` and `A = e₁ × e₂` (twice the signed
//! area). Evaluating the plane at each span's first pixel center, instead
//! of stepping values down the edges, keeps every span independent of the
//! rows before it (bands render bit-identically) and costs one
//! multiply-add per quantity per span.

use crate::scalar::{div_rem_i64, div_rem_u64, normalize_shift, recip62_floor, widening_mul_u32};

/// Extra fractional bits kept in the gradients beyond the values' own.
const EXTRA: u32 = 8;

/// A plane over the screen for one quantity.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Gradient {
    /// `a₀ << EXTRA`.
    base: i64,
    /// Change per 28.4 unit in x and y, with [`EXTRA`] extra bits.
    gx: i64,
    gy: i64,
    x0: i32,
    y0: i32,
    /// The per-pixel step `gx·16 >> EXTRA`, rounded.
    step: i64,
    /// `|gx|, |gy| < 2^32`: then, for any pixel within ±2^16 and an
    /// origin within ±2^28 (28.4), `|gx·px|, |gy·py| < 2^61` and
    /// `|base| < 2^61` (values below 2^52 in 24.8 or 16.16), so the plane
    /// needs no saturation.
    small: bool,
    /// `|gx|, |gy| < 2^31` (and so `|step| < 2^27`): on the `small` path
    /// every product is then a 32×32→64 multiply.
    narrow: bool,
    /// `a₀` when it is within ±2^28.
    a0: i32,
    /// `⌊max(|gx|, |gy|) / 2^16⌋ + 1` (at least the magnitude of either
    /// gradient's high 16-bit half) when the plane is `narrow` and
    /// `|a₀| < 2^28`, else 2^15: what [`Self::fits`] weighs against a
    /// polygon's extent.
    reach: u32,
}

/// The three vertices the planes are fitted through: positions (28.4),
/// the doubled signed area `A ≠ 0`, and its reciprocal when `|A| < 2^31`
/// (any triangle within ±1024 pixels: edges below 2^15 in 28.4, each
/// product below 2^30) and the set-up shares it (see [`AreaRecip`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Basis {
    pub(super) p: [(i32, i32); 3],
    pub(super) area2: i64,
    pub(super) recip: Option<AreaRecip>,
    /// Every vertex within ±[`SMALL_COORD_LIMIT`](super::edge::SMALL_COORD_LIMIT)
    /// (2^14 in 28.4): edge components within ±2^15, so a product of one
    /// with an i32 difference takes two 32-bit multiplies ([`mul_short`]).
    pub(super) short: bool,
}

/// `|A|` (in `[8, 2^31)`) with `r ≈ 2^62/d'`, `d' = |A|·2^s` normalized
/// into `[2^30, 2^31)`: one reciprocal shared by every gradient of a
/// polygon, so each quotient is one 32×32→64 multiply and a 32-bit check
/// instead of a 64-bit library division (about 320 instructions a
/// quotient on ARMv6-M, `u64_div_rem` and the `u32_div_rem` it calls).
///
/// `r` is [`recip62_floor`]`(d')`, capped below 2^32:
/// `R − 4 ≤ r ≤ R` for `R = 2^62/d'` (for every divisor:
/// `recip62_exhaustive`). The dividend `u < 2^(32+t)`, `t = 27 − s`, is
/// first cut to 32 bits, `u' = ⌊u/2^t⌋`, and the estimate is
/// `e = ⌊u'·r / 2^35⌋`. Since `u/|A| = u·R/2^(62−s)`, that is
/// `u'·2^t·R/2^(62−s)` less at most `4u'/2^35 < 1/2` (from `r`), and
/// `u'·2^t` is `u` less at most `2^t − 1`, a quotient error below
/// `2^t/|A| ≤ 1/8` (`|A| ≥ 2^(30−s)`): `e` lies in
/// `(u/|A| − 5/8, u/|A|]`, so it is `⌊u/|A|⌋` or one less, and whether
/// `u − e·|A|` (in `[0, 2|A|)`, below 2^32: its low 32 bits) reaches `|A|`
/// tells which. The quotient is then below 2^29, and every quotient below
/// 2^28 is in range (`u < 2^28·2|A| ≤ 2^(32+t)`). (W2 on ARMv6-M: the
/// previous form, `r` above `R` and the full `u·r` in two widening
/// multiplies whenever `u ≥ 2^32`, cost 6.83 M instructions per frame.)
#[derive(Clone, Copy, Debug)]
pub(super) struct AreaRecip {
    d: u32,
    /// `27 − s`, in `[0, 27]`: the bits cut from the dividend.
    t: u32,
    /// In `(2^31 − 4, 2^32)`.
    r: u32,
}

impl Basis {
    /// `(v·2^EXTRA) / A`, rounded to nearest (ties away from zero) and
    /// saturated: by the shared reciprocal when there is one and the
    /// quotient is in its range ([`Self::quotient_recip`]), else
    /// [`Self::quotient_divided`]. One copy for both set-up routes.
    #[inline(never)]
    pub(super) fn quotient(&self, v: i64) -> i64 {
        match self.quotient_recip(v) {
            Some(q) => q as i64,
            None => self.quotient_divided(v),
        }
    }

    /// [`Self::quotient`] by the shared reciprocal, when there is one and
    /// the quotient is in its range (then it is below 2^29 in
    /// magnitude), else `None`. Inlined into each plane's set-up: out of
    /// line it cost ARMv6-M W1/W2 5.12 M / 6.10 M instructions per frame,
    /// inlined 5.09 M / 6.05 M, for 64 bytes more in the flat firmware
    /// and 280 in the Gouraud one (`bash tests/mcu/run`).
    #[inline]
    pub(super) fn quotient_recip(&self, v: i64) -> Option<i32> {
        let m = v.unsigned_abs();
        if m >= 1 << (62 - EXTRA) {
            return None;
        }
        // On the magnitude, as `div_round` (|v·2^EXTRA| = m·2^EXTRA).
        let q = self.recip?.div_round_magnitude(m << EXTRA)? as i32;
        Some(if (v < 0) != (self.area2 < 0) { -q } else { q })
    }

    /// [`Self::quotient`] without the reciprocal: one i64 division while
    /// the shifted numerator stays below 2^62, else bit by bit
    /// ([`div_round_shifted`]).
    #[inline(never)]
    pub(super) fn quotient_divided(&self, v: i64) -> i64 {
        if v.unsigned_abs() >= 1 << (62 - EXTRA) {
            return div_round_shifted(v, self.area2);
        }
        div_round(v << EXTRA, self.area2)
    }
}

impl AreaRecip {
    /// The reciprocal of `|area2|`, if it is in `[8, 2^31)` (slivers of
    /// smaller area divide).
    pub(super) fn new(area2: i64) -> Option<Self> {
        let d = area2.unsigned_abs();
        if !(8..1 << 31).contains(&d) {
            return None;
        }
        let d = d as u32;
        // s ≤ 27 for d ≥ 8.
        let s = normalize_shift(d);
        Some(Self {
            d,
            t: 27 - s,
            // At or below R, at most 4 below it; only d' = 2^30 (R = 2^32)
            // can reach 2^32, and one unit less is still within 4 of R.
            r: recip62_floor(d << s).min(u32::MAX as u64) as u32,
        })
    }

    /// [`Self::new`] with the reciprocal `⌊2^62/d'⌋ − below` instead of
    /// [`recip62_floor`]'s (which is one of those with `below ≤ 3`): for
    /// tests that put the estimate at either end of its error bound.
    #[cfg(test)]
    pub(super) fn with_floor_less(area2: i64, below: u32) -> Option<Self> {
        let mut r = Self::new(area2)?;
        let dn = (r.d as u64) << (27 - r.t);
        r.r = ((1u64 << 62) / dn).min(u32::MAX as u64) as u32 - below;
        Some(r)
    }

    /// `⌊u / |A|⌋` when `u < 2^(32+t)` (then below 2^29), else `None`.
    #[inline]
    fn div_floor(&self, u: u64) -> Option<u64> {
        // Shifts of 32-bit halves only: a variable 64-bit shift is a
        // library call on ARMv6-M.
        let (ul, uh) = (u as u32, (u >> 32) as u32);
        let t = self.t;
        if uh >> t != 0 {
            return None; // u ≥ 2^(32+t)
        }
        // u' = ⌊u / 2^t⌋ < 2^32 (`<< 1 << (31 − t)`: no shift by 32 at t = 0,
        // where uh = 0).
        let u1 = (ul >> t) | ((uh << 1) << (31 - t));
        let e = (widening_mul_u32(u1, self.r) >> 35) as u32;
        // e = ⌊u/|A|⌋ or one less: u − e·|A| in [0, 2|A|), exact in the
        // low 32 bits.
        let short = ul.wrapping_sub(e.wrapping_mul(self.d)) >= self.d;
        Some(u64::from(e + u32::from(short)))
    }

    /// The magnitude of [`div_round`]`(num, den)` for `den = ±|A|` and
    /// `m = |num| < 2^62`, `⌊(m + ⌊|A|/2⌋) / |A|⌋`, when the quotient is in
    /// range of [`Self::div_floor`]; `None` then the caller divides. (On
    /// the magnitude, so that the caller forms it once: W2 on ARMv6-M
    /// 6.91 M -> 6.88 M instructions per frame.)
    #[inline]
    pub(super) fn div_round_magnitude(&self, m: u64) -> Option<u64> {
        self.div_floor(m + (self.d / 2) as u64)
    }
}

impl Gradient {
    /// Fits the plane through values `a` (depth keys or varyings) at the
    /// basis vertices.
    ///
    /// Nearly every triangle takes the short route: the basis is `short`
    /// (every coordinate within ±2^14, so edges within ±2^15) and both
    /// differences `Δa` fit i32. Each numerator `Δa₁·e₂ − Δa₂·e₁` is then
    /// four two-multiply products ([`mul_short`]), below
    /// `2·2^31·2^15 = 2^47`. Everything else takes [`Self::general`], which
    /// gives the same plane for every input (`short_route_is_general`).
    /// (W1/W2 on ARMv6-M: 6.20 M / 7.51 M instructions per frame with
    /// one route for both, whose 64-bit edge vectors and range tests
    /// spilled; 6.09 M / 7.26 M, and 760 bytes less in the Gouraud
    /// firmware.) No route links i128 arithmetic (on Cortex-M0 an i128
    /// division is a kilobyte of library code).
    #[inline]
    pub(super) fn new(b: &Basis, a: [i32; 3]) -> Self {
        let (x0, y0) = b.p[0];
        let (Some(d1), Some(d2), true) = (a[1].checked_sub(a[0]), a[2].checked_sub(a[0]), b.short)
        else {
            return Self::general(b, a);
        };
        let (e1x, e1y) = (b.p[1].0 - x0, b.p[1].1 - y0);
        let (e2x, e2y) = (b.p[2].0 - x0, b.p[2].1 - y0);
        let nx = mul_short(d1, e2y) - mul_short(d2, e1y);
        let ny = mul_short(d2, e1x) - mul_short(d1, e2x);
        // The scan converter makes the shared reciprocal only where
        // pointers are narrower than 64 bits (see `fill_polygon`), so a
        // 64-bit host divides at once: asking the reciprocal first cost
        // x86-64 W1/W2 1.8 % / 2.9 %, one call per quotient that always
        // says no. (Both give the same quotients.)
        if cfg!(target_pointer_width = "64") {
            let q = |v| b.quotient_divided(v);
            return Self::from_quotients(a[0], q(nx), q(ny), x0, y0);
        }
        match (b.quotient_recip(nx), b.quotient_recip(ny)) {
            (Some(gx), Some(gy)) => Self::from_small_quotients(a[0], gx, gy, x0, y0),
            (gx, gy) => {
                let q = |g: Option<i32>, v| g.map_or_else(|| b.quotient_divided(v), i64::from);
                Self::from_quotients(a[0], q(gx, nx), q(gy, ny), x0, y0)
            }
        }
    }

    /// [`Self::new`] for any basis within ±[`COORD_LIMIT`](super::COORD_LIMIT),
    /// which the scan converter checks first: edge components within
    /// ±2^29 and value differences within ±2^32, so each product is
    /// below 2^61 and the numerators, below 2^62, are exact in i64. Shifted
    /// by [`EXTRA`] they may not be: [`Basis::quotient`] then divides
    /// bit by bit.
    #[cold]
    #[inline(never)]
    pub(super) fn general(b: &Basis, a: [i32; 3]) -> Self {
        let (x0, y0) = b.p[0];
        let e = |k: usize| (b.p[k].0 as i64 - x0 as i64, b.p[k].1 as i64 - y0 as i64);
        let (e1, e2) = (e(1), e(2));
        let da1 = a[1] as i64 - a[0] as i64;
        let da2 = a[2] as i64 - a[0] as i64;
        let nx = da1 * e2.1 - da2 * e1.1;
        let ny = da2 * e1.0 - da1 * e2.0;
        Self::from_quotients(a[0], b.quotient(nx), b.quotient(ny), x0, y0)
    }

    /// The gradients `(gx, gy)`, with [`EXTRA`] extra bits (tests only).
    #[cfg(test)]
    pub(super) fn gradients(&self) -> (i64, i64) {
        (self.gx, self.gy)
    }

    /// [`Self::from_quotients`] for gradients below 2^29 in magnitude
    /// (what [`Basis::quotient_recip`] gives): the same plane, with 32-bit
    /// arithmetic where that one needs 64-bit (no saturation, and the
    /// plane is `small` and `narrow`). W1/W2 instructions per frame with
    /// it: ARMv6-M 5.58 M / 6.64 M -> 5.51 M / 6.50 M, ARMv7E-M (f32)
    /// 3.69 M / 4.35 M -> 3.65 M / 4.27 M; 240 bytes more in the flat
    /// firmware (`bash tests/mcu/run`).
    #[inline(always)]
    pub(super) fn from_small_quotients(a0: i32, gx: i32, gy: i32, x0: i32, y0: i32) -> Self {
        Self {
            base: (a0 as i64) << EXTRA,
            gx: gx as i64,
            gy: gy as i64,
            x0,
            y0,
            // |gx| < 2^29: the rounding add cannot overflow.
            step: ((gx + (1 << (EXTRA - 5))) >> (EXTRA - 4)) as i64,
            small: true,
            narrow: true,
            a0,
            reach: if a0.unsigned_abs() < 1 << 28 {
                (gx.unsigned_abs().max(gy.unsigned_abs()) >> 16) + 1
            } else {
                1 << 15
            },
        }
    }

    /// The plane with value `a0` at `(x0, y0)` and gradients `gx`, `gy`
    /// (with [`EXTRA`] extra bits).
    #[inline(always)]
    pub(super) fn from_quotients(a0: i32, gx: i64, gy: i64, x0: i32, y0: i32) -> Self {
        let a0 = a0 as i64;
        let lim = 1i64 << 32;
        let narrow = gx.unsigned_abs() < 1 << 31 && gy.unsigned_abs() < 1 << 31;
        Self {
            base: a0 << EXTRA,
            gx,
            gy,
            x0,
            y0,
            step: gx.saturating_add(1 << (EXTRA - 5)) >> (EXTRA - 4),
            // `unsigned_abs`: a saturated gradient is i64::MIN, whose `abs`
            // overflows (a panic with debug assertions, and a wrapped
            // negative value that wrongly chose the fast path otherwise;
            // found by the `raster` fuzz target).
            // (`a0` is an i32, so `|base| < 2^40`.)
            small: gx.unsigned_abs() < lim as u64 && gy.unsigned_abs() < lim as u64,
            narrow,
            a0: a0 as i32,
            reach: if narrow && a0.unsigned_abs() < 1 << 28 {
                (gx.unsigned_abs().max(gy.unsigned_abs()) >> 16) as u32 + 1
            } else {
                1 << 15
            },
        }
    }

    /// Start value and per-pixel step for the span of `len` pixels whose
    /// first pixel is column `x` on row `y`, with every value of the span
    /// inside `[lo, hi]`.
    ///
    /// The plane's values at both ends are clamped into `[lo, hi]`; when
    /// clamping changed anything (rounding at a vertex, a polygon that is
    /// not planar in this quantity, or saturated arithmetic on a degenerate
    /// sliver) the step is recomputed from the clamped ends, so the
    /// per-pixel loop never leaves the range and needs no clamp of its own.
    /// `hi − lo` must be below 2^31 so that the step fits in i32.
    #[inline(always)]
    pub(super) fn span(&self, x: i32, y: i32, len: u32, lo: i32, hi: i32) -> (i32, i32) {
        let n = len.saturating_sub(1) as i64;
        // One pixel is 16 units of 28.4: step = gx·16 >> EXTRA, rounded.
        let step = if n == 0 { 0 } else { self.step };
        let pixel_range = 1 << 16;
        let (start, end) = if self.small
            && self.narrow
            && x.abs() < pixel_range
            && y.abs() < pixel_range
            && len < 1 << 16
        {
            // See `small` and `narrow`: |x·16|, |y·16| < 2^20 and the
            // origin is within ±2^28, so |px|, |py| < 2^29 (in i32, no
            // 64-bit arithmetic), |step| < 2^27 and n < 2^16 (the span is
            // clipped to the target): every product is a 32×32→64 multiply.
            let px = x * 16 + 8 - self.x0;
            let py = y * 16 + 8 - self.y0;
            let mul = crate::scalar::widening_mul;
            let v = self.base + mul(self.gx as i32, px) + mul(self.gy as i32, py);
            let start = (v + (1 << (EXTRA - 1))) >> EXTRA;
            (start, start + mul(step as i32, n as i32))
        } else {
            self.wide_ends(x, y, len, step, n)
        };
        let (lo64, hi64) = (lo as i64, hi as i64);
        if start >= lo64 && start <= hi64 && end >= lo64 && end <= hi64 {
            // In range at both ends, hence everywhere between; |step| ≤ hi − lo.
            return (start as i32, step as i32);
        }
        clamped(start, end, n, lo64, hi64)
    }

    /// Whether [`Self::span_tiny`] gives this plane's spans for a polygon
    /// whose every vertex lies within `ext` (28.4, per coordinate) of the
    /// basis origin: `ext < 2^14` and `reach·ext` below 2^20 when `SPLIT`,
    /// below 2^14 otherwise (`reach` bounds the gradient's high halves,
    /// see `span_tiny`; with `ext < 2^14` the product cannot overflow).
    /// `ext` is nonzero for a polygon of nonzero area, the only kind
    /// scanned (at `ext = 0` a plane that is not `narrow` would pass).
    #[inline(always)]
    pub(super) fn fits<const SPLIT: bool>(&self, ext: u32) -> bool {
        ext < 1 << 14 && self.reach * ext < if SPLIT { 1 << 20 } else { 1 << 14 }
    }

    /// [`Self::span`] in 32-bit arithmetic, for a plane that [`fits`] the
    /// polygon: `(px, py)` is the span's first pixel center relative to
    /// the origin (`x·16 + 8 − x₀`, likewise for y; the same for every
    /// plane of the polygon) and `n` its length less one.
    ///
    /// Pixel centers inside the polygon lie within its bounding box, so
    /// `|px|, |py| ≤ ext` and `n ≤ 2·ext/16`. Each gradient splits into
    /// 16-bit halves, `g = gₕ·2^16 + gₗ` (`gₗ` unsigned, `|gₕ| ≤ reach`),
    /// so `gx·px + gy·py = sₕ·2^16 + sₗ` with
    /// `sₗ = gxₗ·px + gyₗ·py` (below `2·2^16·2^14`: with the rounding
    /// term `2^7` it fits i32) and `sₕ = gxₕ·px + gyₕ·py`
    /// (`|sₕ| ≤ 2·reach·ext < 2^21`). Since `base = a₀·2^EXTRA` and
    /// `2^16` is a multiple of `2^EXTRA`, the general route's
    /// `⌊(base + sₕ·2^16 + sₗ + 2^7)/2^EXTRA⌋` is
    /// `a₀ + sₕ·2^8 + ⌊(sₗ + 2^7)/2^EXTRA⌋`: the same start, below
    /// `2^28 + 2^29 + 2^23` in magnitude. `|step| ≤ m/16 + 1` for
    /// `m = max(|gx|, |gy|) < reach·2^16`, so `|step·n| < 2^29 + 2^11`
    /// and the end stays within i32. ARMv6-M: five 32-bit multiplies and
    /// 32-bit compares per plane instead of two four-multiply widening
    /// products and 64-bit compares.
    ///
    /// Without `SPLIT` (`reach·ext < 2^14`, so `m·ext < 2^30`), the whole
    /// gradients: `|gx·px| + |gy·py| + 2^7 < 2^31`, the start is
    /// `a₀ + ⌊(gx·px + gy·py + 2^7)/2^EXTRA⌋`, and `|step·n| < 2^24`: three
    /// multiplies. Depths take it (their gradients are small); the
    /// varyings, 8.16 colors whose gradients exceed 2^16 on most small
    /// triangles, split (W2 on ARMv6-M: 7.79 M instructions per frame
    /// with neither split, 7.63 M with the varyings split, 7.69 M with
    /// every plane split, which cost W1 1.9 %: 6.30 M -> 6.42 M).
    ///
    /// [`fits`]: Self::fits
    #[inline(always)]
    pub(super) fn span_tiny<const SPLIT: bool>(
        &self,
        px: i32,
        py: i32,
        n: i32,
        lo: i32,
        hi: i32,
    ) -> (i32, i32) {
        let step = if n == 0 { 0 } else { self.step as i32 };
        let (gx, gy) = (self.gx as i32, self.gy as i32);
        let round = 1 << (EXTRA - 1);
        let start = if SPLIT {
            let high = (gx >> 16) * px + (gy >> 16) * py;
            let low = (gx & 0xffff) * px + (gy & 0xffff) * py + round;
            self.a0 + (high << (16 - EXTRA)) + (low >> EXTRA)
        } else {
            self.a0 + ((gx * px + gy * py + round) >> EXTRA)
        };
        let end = start + step * n;
        // `lo ≤ v ≤ hi` as one unsigned compare (`hi − lo < 2^31`).
        let width = hi.wrapping_sub(lo) as u32;
        if start.wrapping_sub(lo) as u32 <= width && end.wrapping_sub(lo) as u32 <= width {
            return (start, step);
        }
        clamped(start as i64, end as i64, n as i64, lo as i64, hi as i64)
    }
}

/// The span's ends clamped into `[lo, hi]` and the step between them.
///
/// Out of line on purpose: inlined, LLVM evaluated the 64-bit division on
/// every span of more than one pixel (it may speculate a division by a
/// divisor known to be positive) and selected the unclamped step
/// afterwards: one library division per span on ARMv6-M.
#[inline(never)]
fn clamped(start: i64, end: i64, n: i64, lo: i64, hi: i64) -> (i32, i32) {
    let s = start.clamp(lo, hi);
    let e = end.clamp(lo, hi);
    let step = if n > 0 { div_rem_i64(e - s, n).0 } else { 0 };
    (s as i32, step as i32)
}

impl Gradient {
    /// [`Self::span`]'s start and end values outside the narrow case: 64×64
    /// products, saturated when the plane is not `small`.
    ///
    /// Out of line on purpose: inlined, LLVM computed these products on
    /// every span and selected the narrow result afterwards (if-conversion:
    /// both arms are free of side effects), which on ARMv6-M cost four
    /// 64-bit library multiplies per span.
    #[inline(never)]
    fn wide_ends(&self, x: i32, y: i32, len: u32, step: i64, n: i64) -> (i64, i64) {
        let px = (x as i64) * 16 + 8 - self.x0 as i64;
        let py = (y as i64) * 16 + 8 - self.y0 as i64;
        let pixel_range = 1 << 16;
        if self.small && x.abs() < pixel_range && y.abs() < pixel_range && len < 1 << 16 {
            // See `small`; n < 2^16 and |step·n| < 2^44.
            let v = self.base + self.gx * px + self.gy * py;
            let start = (v + (1 << (EXTRA - 1))) >> EXTRA;
            (start, start + step * n)
        } else {
            let v = self
                .base
                .saturating_add(self.gx.saturating_mul(px))
                .saturating_add(self.gy.saturating_mul(py));
            let start = v.saturating_add(1 << (EXTRA - 1)) >> EXTRA;
            (start, start.saturating_add(step.saturating_mul(n)))
        }
    }
}

/// `d·e` for `|e| ≤ 2^15`, exact: with `d = dₕ·2^16 + dₗ` (`dₗ` in
/// `[0, 2^16)`), `|dₕ·e| ≤ 2^30` and `|dₗ·e| < 2^31` are 32-bit products.
/// Two multiplies where a 32×32→64 product is four on ARMv6-M.
#[inline(always)]
pub(super) fn mul_short(d: i32, e: i32) -> i64 {
    (((d >> 16) * e) as i64) * (1 << 16) + ((d & 0xffff) * e) as i64
}

/// `(v·2^EXTRA) / den` rounded to nearest, ties away from zero, saturated
/// to i64; `den ≠ 0` (a zero `den` gives the saturated value of `v`'s
/// sign). Exact for every `v` and `den`, in u64: `|v| = q₀·|den| + r₀`,
/// then each of the `EXTRA` shifted-in bits doubles the remainder (below
/// 2^64 as `r < |den| ≤ 2^63`) and takes one more quotient bit.
#[inline(never)]
pub(super) fn div_round_shifted(v: i64, den: i64) -> i64 {
    let (u, d) = (v.unsigned_abs(), den.unsigned_abs());
    let negative = (v < 0) != (den < 0);
    let q = match (d != 0).then(|| div_rem_u64(u, d)) {
        None => u64::MAX, // den = 0
        Some((mut q, mut r)) => {
            for _ in 0..EXTRA {
                // r < d: 2r < 2^64, and 2r − d < d.
                let r2 = r << 1;
                q = q.saturating_mul(2);
                if r2 >= d {
                    r = r2 - d;
                    q = q.saturating_add(1);
                } else {
                    r = r2;
                }
            }
            // Ties away from zero: round up when 2r ≥ d (r < d ≤ 2^63).
            if r >= d - r { q.saturating_add(1) } else { q }
        }
    };
    if negative {
        if q >= 1 << 63 { i64::MIN } else { -(q as i64) }
    } else {
        i64::try_from(q).unwrap_or(i64::MAX)
    }
}

/// `num / den` rounded to nearest, ties away from zero; `den ≠ 0`,
/// `|num| < 2^62`.
#[inline(never)]
pub(super) fn div_round(num: i64, den: i64) -> i64 {
    // Ties away from zero: sign(num/den)·⌊(|num| + ⌊|den|/2⌋) / |den|⌋.
    // The sum is below 2^62 + 2^62, so it and the quotient fit. On
    // magnitudes: an unsigned division skips the signed wrapper
    // (`__divmoddi4`, about 50 instructions a call on ARMv6-M). Out of
    // line: inlined into the set-up, W1 gained a little more but W2 lost
    // 0.5 % on ARMv6-M.
    let d = den.unsigned_abs();
    let q = div_rem_u64(num.unsigned_abs() + d / 2, d).0 as i64;
    if (num < 0) != (den < 0) { -q } else { q }
}

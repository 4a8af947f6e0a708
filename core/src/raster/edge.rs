//! Exact integer edge steppers for the scan converter.
//!
//! Coordinates are 28.4 fixed point (see [`SUBPIXEL_BITS`](super::SUBPIXEL_BITS)).
//! For scanline j the pixel-center line is `y_c = 16j + 8`, and the first
//! pixel whose center lies at or right of the edge is
//! `i = ceil((x(y_c) − 8) / 16)`. Writing `x(y_c)` as the exact rational
//! `x₀ + (y_c − y₀)·dx/dy`, that is `ceil(N / D)` with
//! `N = (x₀ − 8)·dy + (y_c − y₀)·dx` and `D = 16·dy`. Stepping one row adds
//! `16·dx` to N, so the quotient and remainder advance by a constant
//! (Bresenham's DDA): no drift, and the value on row j is the same whichever
//! row the walk started at, which is what makes band rendering
//! bit-identical to full-frame rendering.

/// `ceil(n / d)` and the remainder `r = q·d − n ∈ [0, d)`, for `d > 0`.
#[inline]
pub(super) fn ceil_div(n: i64, d: i64) -> (i64, i64) {
    // One truncating division: n = q·d + r with |r| < d and r of n's
    // sign. r > 0: the ceiling is q + 1 with remainder d − r; r ≤ 0: it
    // is q with remainder −r. (No overflow: d > 0 and |n| < 2^63.)
    let (q, r) = crate::scalar::div_rem_i64(n, d);
    if r > 0 { (q + 1, d - r) } else { (q, -r) }
}

/// The first pixel row (or column) whose center is at or after the 28.4
/// coordinate `v`: `ceil((v − 8) / 16)`.
#[inline]
pub(super) fn first_center(v: i32) -> i32 {
    // No overflow: |v| ≤ COORD_LIMIT = 2^28 is checked before use.
    (v - 8 + 15) >> 4
}

/// One edge being walked down, one scanline per [`EdgeStepper::step`].
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeStepper {
    /// First pixel column at or right of the edge on the current row.
    pub(super) x: i64,
    /// `x·D − N`, in `[0, D)`.
    r: i64,
    d: i64,
    q_step: i64,
    r_step: i64,
}

impl EdgeStepper {
    /// A placeholder (vertical at column 0) before the first edge is set.
    pub(super) const NONE: Self = Self {
        x: 0,
        r: 0,
        d: 1,
        q_step: 0,
        r_step: 0,
    };

    /// Sets up the edge (x₀, y₀)→(x₁, y₁) (28.4) on scanline `row`.
    ///
    /// Magnitudes: with all coordinates within ±2^28 and `row`'s center
    /// within the polygon's extent, `|N| < 2^59` and `D ≤ 2^34`, so i64
    /// holds every intermediate.
    ///
    /// An edge that does not go down (`y₁ ≤ y₀`) can only be reached with
    /// non-convex input; it is treated as vertical at x₀ so that nothing
    /// divides by zero.
    pub(super) fn new(x0: i32, y0: i32, x1: i32, y1: i32, row: i32) -> Self {
        let dy = y1 as i64 - y0 as i64;
        if dy <= 0 {
            return Self {
                x: first_center(x0) as i64,
                r: 0,
                d: 1,
                q_step: 0,
                r_step: 0,
            };
        }
        let dx = x1 as i64 - x0 as i64;
        let yc = row as i64 * 16 + 8;
        let n = (x0 as i64 - 8) * dy + (yc - y0 as i64) * dx;
        let d = 16 * dy;
        let (x, r) = ceil_div(n, d);
        let (q_step, r_step) = ceil_div(16 * dx, d);
        Self {
            x,
            r,
            d,
            q_step,
            r_step,
        }
    }

    /// Advances to the next scanline: N grows by `16·dx = q_step·D − r_step`.
    #[inline]
    pub(super) fn step(&mut self) {
        self.x += self.q_step;
        self.r += self.r_step;
        if self.r >= self.d {
            self.x -= 1;
            self.r -= self.d;
        }
    }
}

/// The exact `i32` twin of [`EdgeStepper`], for triangles whose 28.4
/// coordinates all lie within ±[`SMALL_COORD_LIMIT`].
///
/// Bound: with `|x|, |y| ≤ 2^14`, `0 < dy ≤ 2^15`, `|dx| ≤ 2^15` and the
/// row's center within the edge's extent (`0 ≤ y_c − y₀ ≤ dy + 8`),
/// `|N| ≤ (2^14 + 8)·2^15 + (2^15 + 8)·2^15 < 1.62·10^9 < 2^31`, and
/// `D = 16·dy ≤ 2^19`: every intermediate fits in `i32`, so the set-up is
/// two 32-bit divisions (no 64-bit library calls on ARMv6-M) and the walk
/// keeps its state in four 32-bit registers. The values are identical to
/// [`EdgeStepper`]'s: both compute the same exact quotients.
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeStepper32 {
    pub(super) x: i32,
    r: i32,
    d: i32,
    q_step: i32,
    r_step: i32,
}

/// Largest `|x|`, `|y|` (28.4) for [`EdgeStepper32`]: 2^14, i.e. ±1024
/// pixels, which covers any viewport up to 992 pixels plus the 16-pixel
/// guard band.
pub const SMALL_COORD_LIMIT: i32 = 1 << 14;

/// `n / d` and `n % d` for `d > 0`.
///
/// Where the core divides in hardware (ARMv7-M's `udiv`, RISC-V's M
/// extension, every host) that is one instruction; on ARMv6-M, which has
/// none, it is [`udiv_small`]. (W1 in f32 on a Cortex-M4F: 4 011 631
/// instructions per frame with the shift-and-subtract loop, 3 953 917
/// with `udiv`.)
#[inline(always)]
fn udiv32(n: u32, d: u32) -> (u32, u32) {
    if cfg!(any(
        all(target_arch = "arm", not(target_has_atomic = "ptr")),
        all(
            any(target_arch = "riscv32", target_arch = "riscv64"),
            not(target_feature = "m")
        )
    )) {
        udiv_small(n, d)
    } else {
        // `d > 0` by contract; the fallback divisor keeps a broken
        // contract from becoming a panic.
        let d = core::num::NonZeroU32::new(d).unwrap_or(core::num::NonZeroU32::MIN);
        (n / d, n % d)
    }
}

/// `n / d` and `n % d` for `d > 0`, by shift and subtract, in as many
/// steps as the quotient has bits.
///
/// ARMv6-M has no divide instruction. The library's 32-bit division
/// normalizes both operands first and cost about 210 instructions per
/// call in the W1 frame; the edge set-up's quotients are small (a slope,
/// and a column offset of about one slope, see [`EdgeStepper32::new`]),
/// so this loop usually ends after a few steps. (A fixed 16-step loop was
/// tried before and cost W1 10 % more than the library.)
#[inline]
fn udiv_small(mut n: u32, d: u32) -> (u32, u32) {
    let (mut s, mut bit) = (d, 1u32);
    // `s ≤ n/2` keeps `2s ≤ n`: no overflow.
    while s <= n >> 1 {
        s <<= 1;
        bit <<= 1;
    }
    let mut q = 0;
    loop {
        if n >= s {
            n -= s;
            q |= bit;
        }
        if bit == 1 {
            return (q, n);
        }
        s >>= 1;
        bit >>= 1;
    }
}

/// `ceil(n / d)` and its remainder `q·d − n` in `[0, d)`, for `d > 0`, in
/// `i32`.
#[inline]
fn ceil_div32(n: i32, d: i32) -> (i32, i32) {
    // d > 0, so `d as u32` is d; |n| ≤ 2^31 fits in u32, and the quotient
    // of |n| by d ≥ 1 fits in i32 unless n = i32::MIN and d = 1, where
    // `-q` wraps to the right value.
    let (q, r) = udiv32(n.unsigned_abs(), d as u32);
    let (q, r) = (q as i32, r as i32);
    if n >= 0 {
        // n = q·d + r.
        if r > 0 { (q + 1, d - r) } else { (q, 0) }
    } else {
        // n = −(q·d + r): the ceiling is −q, with remainder r.
        (q.wrapping_neg(), r)
    }
}

impl EdgeStepper32 {
    /// As [`EdgeStepper::new`]; every coordinate within
    /// ±[`SMALL_COORD_LIMIT`] and `row`'s center within the edge's rows.
    pub(super) fn new(x0: i32, y0: i32, x1: i32, y1: i32, row: i32) -> Self {
        let dy = y1 - y0;
        if dy <= 0 {
            return Self {
                x: first_center(x0),
                r: 0,
                d: 1,
                q_step: 0,
                r_step: 0,
            };
        }
        let dx = x1 - x0;
        let yc = row * 16 + 8;
        // N = 16·c·dy + m with c = first_center(x₀), so the first column is
        // c + ceil(m / D) with the same remainder. As (x₀ − 8) − 16c lies
        // in (−16, 0], |m| < 16·dy + (y_c − y₀)·|dx|: when the walk starts
        // on the vertex's own row (y_c − y₀ < 16), m's quotient is about
        // one slope, not a whole column number, and the division is short.
        // |m| < 2^19 + (2^15 + 8)·2^15 < 2^31.
        let c = first_center(x0);
        let m = ((x0 - 8) - 16 * c) * dy + (yc - y0) * dx;
        let d = 16 * dy;
        let (x, r) = ceil_div32(m, d);
        let x = c + x;
        let (q_step, r_step) = ceil_div32(16 * dx, d);
        Self {
            x,
            r,
            d,
            q_step,
            r_step,
        }
    }

    /// As [`EdgeStepper::step`].
    #[inline]
    pub(super) fn step(&mut self) {
        self.x += self.q_step;
        self.r += self.r_step;
        if self.r >= self.d {
            self.x -= 1;
            self.r -= self.d;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact i64 reference for `ceil_div32`.
    fn ceil_ref(n: i32, d: i32) -> (i32, i32) {
        let (n, d) = (n as i64, d as i64);
        let q = n.div_euclid(d) + i64::from(n.rem_euclid(d) != 0);
        (q as i32, (q * d - n) as i32)
    }

    #[test]
    fn ceil_div32_matches_exact_division() {
        let ns = [
            0,
            1,
            -1,
            15,
            16,
            17,
            -16,
            -17,
            1 << 30,
            (1 << 30) + 12345,
            -(1 << 30),
            i32::MAX,
            i32::MIN + 1,
            1_619_999_999,
            -1_619_999_999,
        ];
        let ds = [1, 2, 3, 16, 17, 48, 1000, (1 << 19) - 1, 1 << 19, i32::MAX];
        for &n in &ns {
            for &d in &ds {
                assert_eq!(ceil_div32(n, d), ceil_ref(n, d), "n = {n}, d = {d}");
            }
        }
        // A deterministic sweep (xorshift) over the set-up's ranges.
        let mut x = 0x2545_f491_u32;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let n = x as i32;
            let d = ((x.rotate_left(11) >> (x & 15)) | 1) as i32 & 0x7fff_ffff;
            let d = d.max(1);
            assert_eq!(ceil_div32(n, d), ceil_ref(n, d), "n = {n}, d = {d}");
        }
    }

    /// The shift-and-subtract division (ARMv6-M's route; hosts divide in
    /// hardware) against the hardware quotient and remainder.
    #[test]
    fn udiv_small_matches_division() {
        let ns = [
            0u32,
            1,
            15,
            16,
            17,
            1 << 30,
            (1 << 31) - 1,
            1 << 31,
            1_619_999_999,
        ];
        let ds = [
            1u32,
            2,
            3,
            16,
            17,
            48,
            1000,
            (1 << 19) - 1,
            1 << 19,
            i32::MAX as u32,
        ];
        for &n in &ns {
            for &d in &ds {
                assert_eq!(udiv_small(n, d), (n / d, n % d), "n = {n}, d = {d}");
            }
        }
        let mut x = 0x2545_f491_u32;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let n = x.rotate_left(7) >> (x & 31) | u32::from(x & 1 == 0) << 31;
            let d = ((x.rotate_left(11) >> (x & 15)) & 0x7fff_ffff).max(1);
            assert_eq!(udiv_small(n, d), (n / d, n % d), "n = {n}, d = {d}");
        }
    }

    /// The 32-bit stepper gives the same columns and remainders as the
    /// 64-bit one on every row, for edges anywhere in its range and walks
    /// started on any row.
    #[test]
    fn stepper32_matches_stepper64() {
        let lim = SMALL_COORD_LIMIT;
        let mut x = 0x9e37_79b9_u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        };
        let coord = |r: u32, scale: u32| ((r % (2 * scale + 1)) as i32) - scale as i32;
        for case in 0..20_000 {
            // Small triangles near the origin, and edges across the range.
            let scale = if case % 2 == 0 { 400 } else { lim as u32 };
            let (x0, y0) = (coord(next(), scale), coord(next(), scale));
            let (x1, y1) = (coord(next(), scale), coord(next(), scale));
            let (first, last) = (first_center(y0), first_center(y1));
            if first >= last {
                continue;
            }
            let start = first + (next() % (last - first) as u32) as i32;
            let mut a = EdgeStepper::new(x0, y0, x1, y1, start);
            let mut b = EdgeStepper32::new(x0, y0, x1, y1, start);
            for row in start..last.min(start + 64) {
                assert_eq!(
                    (a.x, a.r),
                    (b.x as i64, b.r as i64),
                    "edge ({x0}, {y0}) -> ({x1}, {y1}), row {row}, from {start}"
                );
                a.step();
                b.step();
            }
        }
    }
}

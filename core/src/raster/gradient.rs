//! Plane equations for interpolated quantities (depth, intensity, texel
//! coordinates), set up once per polygon and evaluated once per span.
//!
//! A quantity `a` given at three vertices is the plane
//! `a(X, Y) = a₀ + g_x·(X − x₀) + g_y·(Y − y₀)` over 28.4 screen
//! coordinates, with `g_x = (Δa₁·e₂y − Δa₂·e₁y) / A`,
//! `g_y = (Δa₂·e₁x − Δa₁·e₂x) / A` and `A = e₁ × e₂` (twice the signed
//! area). Evaluating the plane at each span's first pixel centre, instead
//! of stepping values down the edges, keeps every span independent of the
//! rows before it (bands render bit-identically) and costs one
//! multiply-add per quantity per span.

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
}

/// The three vertices the planes are fitted through: positions (28.4) and
/// the doubled signed area `A ≠ 0`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Basis {
    pub(super) p: [(i32, i32); 3],
    pub(super) area2: i64,
}

impl Gradient {
    /// Fits the plane through values `a` at the basis vertices.
    ///
    /// Uses i128 for the numerators: `Δa` (< 2^33) times an edge component
    /// (< 2^30) times 2^EXTRA reaches 2^71. The quotient saturates to i64.
    pub(super) fn new(b: &Basis, a: [i64; 3]) -> Self {
        let (x0, y0) = b.p[0];
        let e1 = (b.p[1].0 as i128 - x0 as i128, b.p[1].1 as i128 - y0 as i128);
        let e2 = (b.p[2].0 as i128 - x0 as i128, b.p[2].1 as i128 - y0 as i128);
        let da1 = (a[1] - a[0]) as i128;
        let da2 = (a[2] - a[0]) as i128;
        let area = b.area2 as i128;
        let div = |num: i128| -> i64 {
            // Round to nearest: add half the divisor with the quotient's sign.
            let num = num << EXTRA;
            let half = area.abs() / 2;
            let q = if (num < 0) == (area < 0) {
                (num + num.signum() * half) / area
            } else {
                (num - num.signum() * half) / area
            };
            q.clamp(i64::MIN as i128, i64::MAX as i128) as i64
        };
        Self {
            base: a[0] << EXTRA,
            gx: div(da1 * e2.1 - da2 * e1.1),
            gy: div(da2 * e1.0 - da1 * e2.0),
            x0,
            y0,
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
    #[inline]
    pub(super) fn span(&self, x: i32, y: i32, len: u32, lo: i32, hi: i32) -> (i32, i32) {
        let px = (x as i64) * 16 + 8 - self.x0 as i64;
        let py = (y as i64) * 16 + 8 - self.y0 as i64;
        let v = self
            .base
            .saturating_add(self.gx.saturating_mul(px))
            .saturating_add(self.gy.saturating_mul(py));
        let start = v.saturating_add(1 << (EXTRA - 1)) >> EXTRA;
        // One pixel is 16 units of 28.4: step = gx·16 >> EXTRA, rounded.
        let n = len.saturating_sub(1) as i64;
        let step = if n == 0 {
            0
        } else {
            self.gx.saturating_add(1 << (EXTRA - 5)) >> (EXTRA - 4)
        };
        let end = start.saturating_add(step.saturating_mul(n));
        let (lo64, hi64) = (lo as i64, hi as i64);
        if start >= lo64 && start <= hi64 && end >= lo64 && end <= hi64 {
            // In range at both ends, hence everywhere between; |step| ≤ hi − lo.
            return (start as i32, step as i32);
        }
        let s = start.clamp(lo64, hi64);
        let e = end.clamp(lo64, hi64);
        let step = if n > 0 { (e - s) / n } else { 0 };
        (s as i32, step as i32)
    }
}

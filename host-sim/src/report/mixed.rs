//! The mixed fixed-point transform: rotation coefficients in Q2.30,
//! points and translation in Q16.16, products accumulated exactly in
//! `i64` and rounded once. A rotation's coefficients lie in [−1, 1], so
//! Q2.30 holds them with 2⁻³⁰ resolution instead of I16F16's 2⁻¹⁶, while
//! the points keep I16F16's ±32768 range.
//!
//! This is a report-local kernel (not in core): it measures whether the
//! scheme is worth adding.

/// An object→view transform with Q2.30 matrix and Q16.16 translation.
#[derive(Clone, Copy, Debug)]
pub struct MixedAffine {
    /// Rotation rows, Q2.30.
    pub m: [[i32; 3]; 3],
    /// Translation, Q16.16.
    pub t: [i32; 3],
}

fn quantize(x: f64, frac: u32) -> i32 {
    (x * f64::from(1u32 << frac))
        .round()
        .clamp(i32::MIN as f64, i32::MAX as f64) as i32
}

/// `x` to Q16.16, rounded and saturated.
pub fn q16(x: f64) -> i32 {
    quantize(x, 16)
}

/// Q16.16 to `f64`.
pub fn from_q16(x: i32) -> f64 {
    f64::from(x) / 65536.0
}

impl MixedAffine {
    /// Rounds an `f64` matrix (coefficients within (−2, 2)) and
    /// translation.
    pub fn from_f64(m: [[f64; 3]; 3], t: [f64; 3]) -> Self {
        Self {
            m: m.map(|r| r.map(|c| quantize(c, 30))),
            t: t.map(q16),
        }
    }

    /// `M·p + t` in Q16.16. Each product is below 2⁶¹ in magnitude
    /// (|m| < 2³¹, |p| < 2³¹ but |m| ≤ 2³⁰ for a rotation), so the sum of
    /// three plus the shifted translation fits `i64`; the result
    /// saturates to `i32`.
    #[inline]
    pub fn transform(&self, p: [i32; 3]) -> [i32; 3] {
        let mut out = [0i32; 3];
        for (o, (row, &t)) in out.iter_mut().zip(self.m.iter().zip(&self.t)) {
            let acc = i64::from(row[0]) * i64::from(p[0])
                + i64::from(row[1]) * i64::from(p[1])
                + i64::from(row[2]) * i64::from(p[2])
                + (i64::from(t) << 30);
            // Q2.30 × Q16.16 = Q.46; back to Q16.16 with round-half-up.
            let r = (acc + (1 << 29)) >> 30;
            *o = r.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_about_z_is_exact_to_a_grid_step() {
        let (s, c) = (0.3f64.sin(), 0.3f64.cos());
        let m = MixedAffine::from_f64(
            [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
            [1.0, 2.0, 3.0],
        );
        let p = [12.5, -7.25, 100.0];
        let r = m.transform(p.map(q16));
        let want = [
            c * p[0] - s * p[1] + 1.0,
            s * p[0] + c * p[1] + 2.0,
            p[2] + 3.0,
        ];
        for k in 0..3 {
            assert!((from_q16(r[k]) - want[k]).abs() <= 1.0 / 65536.0, "{k}");
        }
    }
}

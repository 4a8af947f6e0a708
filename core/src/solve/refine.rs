//! Residuals in a wider precision and iterative refinement.
//!
//! The scheme is the classical mixed-precision one that LAPACK's
//! `xGERFS` applies after `xGETRS` (Higham, *Accuracy and Stability of
//! Numerical Algorithms*, 2nd ed., ch. 12): form `r = b − A x̂` more
//! accurately than the working precision, solve `A d = r` with the factors
//! already computed, and take `x̂ + d`. It converges as long as the factors
//! are a fair approximation of `A` (roughly ρ·n·u·κ < 1), so it repairs the
//! large backward errors that high pivot growth leaves behind. This is an
//! independent implementation of that scheme, not a port.
//!
//! Residual precision, per scalar:
//! - **f32**: in f64. A product of two f32 values is exact in f64 (24 + 24
//!   significant bits ≤ 53), and the n-term sum adds a relative error of at
//!   most n·2⁻⁵³ of Σ|aᵢₖ xₖ|, far below f32's u = 2⁻²⁴.
//! - **f64 and fixed point**: in double-double: each product split exactly
//!   by a fused multiply-add (`fma(a, x, −a·x)` is the rounding error of
//!   `a·x`), summed with Knuth's TwoSum. The result is accurate to about
//!   n·2⁻¹⁰⁶ of Σ|aᵢₖ xₖ| (Ogita, Rump and Oishi, "Accurate sum and dot
//!   product", SIAM J. Sci. Comput. 26 (2005), the compensated dot product).
//!   Fixed-point values are exact in f64 but their products (up to 62 bits)
//!   are not, hence the compensation.
//!
//! Everything is computed on `A` and `x̂` scaled by powers of two so that
//! their largest entries lie in [1, 2): the products and sums can then
//! neither overflow nor lose accuracy to underflow (an entry that scales
//! into the subnormal range is at most 2⁻¹⁰²² of the largest, an absolute
//! error far below the ratios' denominators, which are at least 1).

// `!(a <= b)` on purpose: a NaN ratio must stop refinement.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use super::Lu;
use crate::scalar::Scalar;

/// At most this many correction steps, as `xGERFS` (`ITMAX = 5`).
pub const MAX_REFINEMENT_STEPS: u8 = 5;

/// The residual ratio above which a step of refinement is taken. Below it
/// the solution is already backward stable to a small multiple of u and a
/// correction would change at most its last bits.
pub const REFINE_ABOVE_RATIO: f64 = 1.0;

/// The residual ratio a returned float solution stays below: LAPACK's test
/// threshold (`THRESH = 30` in `TESTING/LIN`).
pub const RESIDUAL_RATIO_MAX: f64 = 30.0;

/// `x̂` and what its residual says about it.
pub(super) struct Checked<S, const N: usize, const M: usize> {
    pub x: [[S; M]; N],
    /// max over columns of ‖r‖₁ / (‖A‖₁ ‖x̂‖₁ n u), see [`super`].
    pub ratio: f64,
    /// max over columns of ‖r‖₁ / (‖A‖₁ ‖x̂‖₁), the normwise backward error.
    pub backward: f64,
    pub steps: u8,
}

/// The unit roundoff u of `S`: half an ulp of 1 for floats (LAPACK's
/// `xLAMCH('E')`), one grid step for fixed point (absolute rounding by up
/// to half a step, but truncating steps occur in the fixed-point division).
pub(super) fn unit_roundoff<S: Scalar>() -> f64 {
    S::EPSILON.to_f64() * if S::IS_FLOAT { 0.5 } else { 1.0 }
}

/// 2⁻ᵉ with e the binary exponent of `m > 0` (so `m·2⁻ᵉ ∈ [1, 2)`), with e
/// clamped to f64's normal range; 1 for `m = 0`.
fn pow2_scale(m: f64) -> f64 {
    if m == 0.0 || !m.is_finite() {
        return 1.0;
    }
    let e = ((m.to_bits() >> 52) & 0x7ff) as i64 - 1023;
    let e = e.clamp(-1021, 1021);
    f64::from_bits(((1023 - e) as u64) << 52)
}

/// `s + p` as an unevaluated sum (Knuth's TwoSum, no branch).
#[inline]
fn two_sum(s: f64, p: f64) -> (f64, f64) {
    let t = s + p;
    let z = t - s;
    (t, (s - (t - z)) + (p - z))
}

/// Residuals `R = B − A X` of the stored values, scaled (see the module
/// docs), with the per-column ratio figures. Returns `(R, ratio,
/// backward)`; `R` is unscaled again (it may be ±∞ for f64 near its
/// range, which stops refinement).
pub(super) fn residual<S: Scalar, const N: usize, const M: usize>(
    a: &[[S; N]; N],
    b: &[[S; M]; N],
    x: &[[S; M]; N],
) -> ([[f64; M]; N], f64, f64) {
    // f32 products are exact in f64; everything else gets the compensated
    // dot product.
    let compensated = !(S::IS_FLOAT && S::EPSILON.to_f64() > 1e-10);
    let u = unit_roundoff::<S>();
    let mut max_a = 0.0f64;
    for row in a {
        for v in row {
            max_a = max_a.max(v.to_f64().abs());
        }
    }
    let sa = pow2_scale(max_a);
    let mut norm_a = 0.0f64;
    for j in 0..N {
        let mut col = 0.0;
        for row in a {
            col += (row[j].to_f64() * sa).abs();
        }
        norm_a = norm_a.max(col);
    }
    let mut r = [[0.0f64; M]; N];
    let (mut ratio, mut backward) = (0.0f64, 0.0f64);
    for c in 0..M {
        let mut max_x = 0.0f64;
        for row in x {
            max_x = max_x.max(row[c].to_f64().abs());
        }
        let sx = pow2_scale(max_x);
        // Scale b by the smaller factor first so the intermediate cannot
        // overflow unless the scaled value itself does.
        let (s1, s2) = if sa < sx { (sa, sx) } else { (sx, sa) };
        let mut rn = 0.0f64;
        let mut xn = 0.0f64;
        for i in 0..N {
            let mut s = b[i][c].to_f64() * s1 * s2;
            let mut err = 0.0f64;
            for k in 0..N {
                let ak = a[i][k].to_f64() * sa;
                let xk = x[k][c].to_f64() * sx;
                let p = ak * xk;
                if compensated {
                    let pe = libm::fma(ak, xk, -p);
                    let (t, e) = two_sum(s, -p);
                    s = t;
                    err += e - pe;
                } else {
                    s -= p;
                }
            }
            let ri = s + err;
            rn += ri.abs();
            xn += (x[i][c].to_f64() * sx).abs();
            r[i][c] = ri / sa / sx;
        }
        let (col_ratio, col_backward) = if rn == 0.0 {
            (0.0, 0.0)
        } else if xn == 0.0 || norm_a == 0.0 {
            (f64::INFINITY, f64::INFINITY)
        } else {
            let eta = rn / (norm_a * xn);
            (eta / (N as f64 * u), eta)
        };
        // NaN (from an overflowed scaled b) counts as infinitely bad.
        ratio = if col_ratio.is_nan() {
            f64::INFINITY
        } else {
            ratio.max(col_ratio)
        };
        backward = if col_backward.is_nan() {
            f64::INFINITY
        } else {
            backward.max(col_backward)
        };
    }
    (r, ratio, backward)
}

/// Whether pivot growth alone calls for a correction step: the a priori
/// backward error ρ·n·u is no longer small (above 2⁻¹⁰), even if the
/// residual of this right-hand side happens to be.
pub(super) fn growth_calls_for_refinement<S: Scalar>(n: usize, growth: f64) -> bool {
    growth * n as f64 * unit_roundoff::<S>() > 1.0 / 1024.0
}

/// Refines `x0` (see the module docs) and returns the best iterate by
/// residual ratio. A correction that overflows stops the iteration and
/// keeps the previous iterate; the caller judges the returned ratio.
pub(super) fn refine<S: Scalar, const N: usize, const M: usize>(
    a: &[[S; N]; N],
    b: &[[S; M]; N],
    lu: &Lu<S, N>,
    x0: [[S; M]; N],
) -> Checked<S, N, M> {
    let force = growth_calls_for_refinement::<S>(N, lu.growth().to_f64());
    let (mut r, mut ratio, mut backward) = residual(a, b, &x0);
    let mut best = Checked {
        x: x0,
        ratio,
        backward,
        steps: 0,
    };
    let mut steps = 0u8;
    'refine: while steps < MAX_REFINEMENT_STEPS
        && (ratio > REFINE_ABOVE_RATIO || (force && steps == 0))
    {
        steps += 1;
        let mut rs = [[S::ZERO; M]; N];
        let mut any = false;
        for (dst, src) in rs.iter_mut().zip(r.iter()) {
            for (d, s) in dst.iter_mut().zip(src.iter()) {
                match S::try_from_f64(*s) {
                    Some(v) => *d = v,
                    None => break 'refine,
                }
                any |= *d != S::ZERO;
            }
        }
        if !any {
            // The residual is below the grid (fixed point) or zero: no
            // correction can be represented.
            break;
        }
        let Ok(d) = lu.solve(&rs) else { break };
        let mut x = best.x;
        for (xr, dr) in x.iter_mut().zip(d.iter()) {
            for (xv, dv) in xr.iter_mut().zip(dr.iter()) {
                match xv.checked_add(*dv) {
                    Some(v) => *xv = v,
                    None => break 'refine,
                }
            }
        }
        let prev = ratio;
        (r, ratio, backward) = residual(a, b, &x);
        if ratio < best.ratio {
            best = Checked {
                x,
                ratio,
                backward,
                steps,
            };
        }
        // Stagnation, as xGERFS: go on only while each step at least
        // halves the backward error.
        if !(2.0 * ratio <= prev) {
            break;
        }
    }
    best.steps = steps;
    best
}

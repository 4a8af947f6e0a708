//! Overflow-checked small kernels and the higher-precision fallbacks the
//! ray module needs, in one place (`checked`: the kernels return `None`
//! where a value would overflow or not be finite).
//!
//! - `*_checked` return `None` where [`Scalar`]'s checked path would report
//!   overflow or a non-finite value, so callers can turn it into "no hit".
//! - [`diff_of_products_wide`] evaluates a difference of products `a·b − c·d` in more
//!   precision than `S`: exactly in `f64` for `f32` inputs (two 24-bit
//!   significands multiply exactly into 53 bits), in double-`f64`
//!   arithmetic (Dekker's product, no fused multiply-add and no `libm`) for
//!   `f64` inputs. Fixed point uses [`fixed_bits`] and exact `i128` instead.

use crate::math::{Vec2, Vec3};
use crate::scalar::Scalar;

/// `a − b` componentwise, `None` on overflow or a non-finite result.
pub(crate) fn sub3<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Option<Vec3<S>> {
    Some(Vec3::new(
        a.x.checked_sub(b.x)?,
        a.y.checked_sub(b.y)?,
        a.z.checked_sub(b.z)?,
    ))
}

/// `a − b` componentwise, `None` on overflow or a non-finite result.
pub(crate) fn sub2<S: Scalar>(a: Vec2<S>, b: Vec2<S>) -> Option<Vec2<S>> {
    Some(Vec2::new(a.x.checked_sub(b.x)?, a.y.checked_sub(b.y)?))
}

/// `a·b`, each product exact with one rounding per term for fixed point
/// (via [`Scalar::sub_mul_noting_overflow`]); `None` on overflow or a non-finite
/// result.
pub(crate) fn dot3_checked<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Option<S> {
    let mut of = false;
    let acc = S::ZERO
        .sub_mul_noting_overflow(-a.x, b.x, &mut of)
        .sub_mul_noting_overflow(-a.y, b.y, &mut of)
        .sub_mul_noting_overflow(-a.z, b.z, &mut of);
    (!of && acc.is_finite()).then_some(acc)
}

/// `q + t·d`, `None` on overflow or a non-finite result.
pub(crate) fn point_at<S: Scalar>(q: Vec3<S>, d: Vec3<S>, t: S) -> Option<Vec3<S>> {
    let mut of = false;
    let p = Vec3::new(
        q.x.sub_mul_noting_overflow(-d.x, t, &mut of),
        q.y.sub_mul_noting_overflow(-d.y, t, &mut of),
        q.z.sub_mul_noting_overflow(-d.z, t, &mut of),
    );
    (!of && p.is_finite()).then_some(p)
}

/// The raw integer of a fixed-point value (`x / EPSILON`, exact because
/// `EPSILON` is a power of two and `to_f64` is exact for fixed point).
/// Only meaningful when `!S::IS_FLOAT`.
pub(crate) fn fixed_bits<S: Scalar>(x: S) -> i64 {
    (x.to_f64() / S::EPSILON.to_f64()) as i64
}

/// The fixed-point value with raw integer `r`; `None` beyond `i32`.
pub(crate) fn from_fixed_bits<S: Scalar>(r: i128) -> Option<S> {
    let r = i32::try_from(r).ok()?;
    Some(S::from_f64(r as f64 * S::EPSILON.to_f64()))
}

/// Whether the float type `S` is `f32` (its epsilon is 2⁻²³).
fn is_single<S: Scalar>() -> bool {
    S::IS_FLOAT && S::EPSILON.to_f64() > 1e-10
}

/// `a·b − c·d` in more precision than `S` (see the module docs); the
/// sign of the result is that of the exact value for `f32`, and for `f64`
/// except when the exact value is below about 2⁻¹⁰⁰ of the products.
pub(crate) fn diff_of_products_wide<S: Scalar>(a: S, b: S, c: S, d: S) -> f64 {
    let (a, b, c, d) = (a.to_f64(), b.to_f64(), c.to_f64(), d.to_f64());
    if is_single::<S>() {
        // Both products are exact in f64; one rounding in the difference
        // cannot change the sign.
        return a * b - c * d;
    }
    let (p1, e1) = two_prod(a, b);
    let (p2, e2) = two_prod(c, d);
    let (s, es) = two_sum(p1, -p2);
    s + (es + (e1 - e2))
}

/// Dekker/Veltkamp splitting: `a = hi + lo` with 26-bit halves.
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2²⁷ + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a·b = p + e` exactly (Dekker's product; no FMA needed).
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    (p, e)
}

/// `a + b = s + e` exactly (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diff_of_products_wide_recovers_cancelled_sign() {
        // (1 + 2⁻³⁰)² − (1 + 2⁻²⁹) = 2⁻⁶⁰, lost entirely in plain f64.
        let a = 1.0 + 2f64.powi(-30);
        let c = 1.0 + 2f64.powi(-29);
        assert_eq!(a * a - c * 1.0, 0.0);
        let w = diff_of_products_wide(a, a, c, 1.0);
        assert_eq!(w, 2f64.powi(-60));
        let a32 = 1.0f32 + 2f32.powi(-12);
        let c32 = 1.0f32 + 2f32.powi(-11);
        assert_eq!(a32 * a32 - c32, 0.0);
        assert_eq!(diff_of_products_wide(a32, a32, c32, 1.0), 2f64.powi(-24));
    }
}

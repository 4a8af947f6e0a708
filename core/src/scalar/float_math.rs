//! The one place where the no_std build calls into `libm`.
//!
//! Every transcendental or root function used by the float implementations of
//! [`Scalar`](super::Scalar) is routed through here, so a reader can see at a
//! glance what a Cortex-M build links from `libm`.

#[inline]
pub(crate) fn sqrtf(x: f32) -> f32 {
    libm::sqrtf(x)
}
#[inline]
pub(crate) fn sqrt(x: f64) -> f64 {
    libm::sqrt(x)
}
#[inline]
pub(crate) fn sincosf(x: f32) -> (f32, f32) {
    libm::sincosf(x)
}
#[inline]
pub(crate) fn sincos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}
#[inline]
pub(crate) fn atan2f(y: f32, x: f32) -> f32 {
    libm::atan2f(y, x)
}
#[inline]
pub(crate) fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}
#[inline]
pub(crate) fn asinf(x: f32) -> f32 {
    libm::asinf(x)
}
#[inline]
pub(crate) fn asin(x: f64) -> f64 {
    libm::asin(x)
}

//! Tests for the ray module, written once as generic functions and
//! instantiated per scalar with [`per_scalar!`]; tolerances derive from each
//! type's `EPSILON`.

mod basics;
mod grid;
mod inclusion;
mod nearest;
mod sphere;
mod watertight;

use crate::math::Vec3;
use crate::scalar::Scalar;

/// Instantiates generic test functions `fn name<S: Scalar>()` for f32, f64
/// and I16F16 (glam's `impl_*_tests!` pattern).
macro_rules! per_scalar {
    ($($name:ident),* $(,)?) => {
        mod f32_suite {
            $( #[test] fn $name() { super::$name::<f32>() } )*
        }
        mod f64_suite {
            $( #[test] fn $name() { super::$name::<f64>() } )*
        }
        mod i16f16_suite {
            $( #[test] fn $name() { super::$name::<crate::scalar::I16F16>() } )*
        }
    };
}
pub(crate) use per_scalar;

/// A small seeded PRNG (SplitMix64), so failures reproduce exactly.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `lo..=hi`.
    pub(crate) fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % ((hi - lo + 1) as u64)) as i64
    }
    /// Uniform in `[0, 1)`.
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `[lo, hi)`.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Which family a scalar belongs to, for choosing exact ranges.
pub(crate) fn is_f64<S: Scalar>() -> bool {
    S::IS_FLOAT && S::EPSILON.to_f64() < 1e-10
}

pub(crate) fn v3<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
}

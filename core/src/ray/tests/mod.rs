//! Tests for the ray module, written once as generic functions and
//! instantiated per scalar with [`per_scalar!`]; tolerances derive from each
//! type's `EPSILON`.

mod basics;
mod bounding_sphere;
// Its maze is the demo scenes' `COLUMN_MAP`.
#[cfg(all(feature = "column", feature = "demo"))]
mod column;
#[cfg(feature = "grid")]
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

pub(crate) use crate::test_util::Rng;

/// Which family a scalar belongs to, for choosing exact ranges.
pub(crate) fn is_f64<S: Scalar>() -> bool {
    S::IS_FLOAT && S::EPSILON.to_f64() < 1e-10
}

pub(crate) fn v3<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::new(S::from_f64(x), S::from_f64(y), S::from_f64(z))
}

//! Vectors and matrices over any [`Scalar`](crate::scalar::Scalar).
//!
//! Names follow glam: `transform_point3` (w = 1), `transform_vector3`
//! (w = 0), `project_point3` (with the divide), `try_inverse`,
//! `normalize` / `try_normalize` / `normalize_or_zero`.

mod mat;
mod vec;

pub use mat::{Affine3, Mat3, Mat4, PointTransform};
pub use vec::{Vec2, Vec3, Vec4};

#[cfg(test)]
mod tests;

//! # sightline
//!
//! A `no_std`, allocation-free geometry and raster core for microcontroller
//! displays, following a textbook chapter on *viewing processes*: object and
//! camera transforms, parallel and perspective projection, and a diagnosable
//! Gaussian-elimination solver, generic over `f32`, `f64` and saturating
//! fixed point.
//!
//! ## Layers (bottom to top)
//!
//! | module | what it holds |
//! |---|---|
//! | [`scalar`] | the [`Scalar`](scalar::Scalar) trait for `f32`, `f64` and [`Fx`](scalar::Fx) fixed point; overflow policy |
//! | [`math`] | `Vec2/3/4`, `Mat3`, `Affine3` (3×4), `Mat4` |
//! | [`solve`] | Gaussian elimination with partial pivoting, N×N with M right-hand sides, with pivot growth and the reciprocal condition number |
//! | [`transform`] | object→world from roll, pitch, yaw and an origin |
//! | [`camera`] | cameras from angles, orthonormal vectors or general vectors (via [`solve`]); projections |
//! | [`pipeline`] | vertex formats chosen at compile time (xyz, +intensity, +uv, +both, perspective uv); Sutherland–Hodgman clipping in view space (near, far, four side planes with a guard band); projection to 28.4 sub-pixel coordinates and depth keys |
//! | [`raster`] | integer scan conversion of convex polygons (28.4 sub-pixel, top-left rule) into spans; span shaders (flat, Gouraud, affine and perspective-correct textures, exact or subdivided); optional depth buffer |
//! | [`texture`] | texture-mapping vectors (axis-edge fast path, any polygon via [`solve`]), the per-pixel perspective mapping, and the affine/perspective choice from a distortion bound |
//! | [`target`] | span sinks: slice framebuffer with stride, bands for strip rendering, embedded-graphics `DrawTarget` adapter |
//! | [`ray`] | screen→world: rays from a ray-casting camera, planes, polygons with four inclusion tests, spheres, watertight triangles, nearest hit, bounding boxes and a uniform grid |
//! | [`scene`] | one borrowed scene description (meshes, poses, materials, light, camera) rendered by both paths with one material model; built-in demo scenes as static data |
//!
//! ## Coordinate conventions
//!
//! These hold everywhere in the crate.
//!
//! - **World** space is right-handed with **+Y up** (as OBJ and glTF files
//!   are). Angles are in radians and follow the right-hand rule:
//!   **roll** about +Z, **pitch** about +X, **yaw** about +Y, applied in
//!   that order: `object→world = T(O)·Ry(yaw)·Rx(pitch)·Rz(roll)`.
//! - **View** space is right-handed with the eye at the origin, **+Z the
//!   direction of view**, **+X to the right** of the screen and **+Y down**
//!   the screen. A camera with zero angles looks along world −Z with world
//!   +Y up on the screen.
//! - **Screen** space is in pixels: x to the right, y down, origin at the
//!   top-left corner of the top-left pixel, so pixel (i, j) has its centre
//!   at (i + ½, j + ½). Perspective projection is `x_s = cx + f·x/z`,
//!   `y_s = cy + f·y/z`, with the focus distance `f` in pixels and
//!   (cx, cy) usually the viewport centre.
//!
//! ## Numeric representations
//!
//! Kernels are written once, generic over [`Scalar`](scalar::Scalar). On a
//! core without an FPU (Cortex-M0/M0+, RP2040) use [`I16F16`](scalar::I16F16);
//! on Cortex-M4F/M7 `f32` is hardware arithmetic. `f64` is the reference
//! used by tests. Fixed point saturates and never wraps; see
//! [`scalar`] for the exact policy.
//!
//! ## Crate features
//!
//! None yet: everything above is always compiled, and generic code costs
//! nothing until it is instantiated.

#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs, missing_debug_implementations)]

#[cfg(test)]
extern crate std;

pub mod camera;
pub mod math;
pub mod pipeline;
pub mod raster;
pub mod ray;
pub mod scalar;
pub mod scene;
pub mod solve;
pub mod target;
pub mod texture;
pub mod transform;

#[cfg(test)]
mod test_util;

//! # sightline
//!
//! A `no_std`, allocation-free geometry and raster core for microcontroller
//! displays, following a textbook chapter on *viewing processes*: object and
//! camera transforms, parallel and perspective projection, and a diagnosable
//! Gaussian-elimination solver, generic over `f32`, `f64` and saturating
//! fixed point.
//!
//! ## A first render
//!
//! A Gouraud-lit cube turning in a 240×240 RGB565 frame with a depth
//! buffer, in I16F16 (for a Cortex-M0), without allocation (features
//! `gouraud` and `depth`; the cube comes from the demo scenes, feature
//! `demo`):
//!
//! ```
//! # #[cfg(all(feature = "gouraud", feature = "depth", feature = "demo"))] {
//! use sightline::math::Vec3;
//! use sightline::pipeline::MeshVertex;
//! use sightline::raster::DepthBuffer;
//! use sightline::scalar::{I16F16, Scalar};
//! use sightline::scene::{builtin, Color, Material, PreparedObject, Renderer, Scene, SceneObject};
//! use sightline::target::Framebuffer;
//! use sightline::transform::Pose;
//!
//! // The description: the built-in cube mesh, Gouraud-lit, seen by the
//! // built-in cube scene's camera and light.
//! let cube = [SceneObject {
//!     mesh: &builtin::CUBE_MESH,
//!     pose: Pose::default(),
//!     material: Material::Gouraud(Color::new(31, 40, 10)),
//! }];
//! let scene = Scene { objects: &cube, ..builtin::CUBE };
//!
//! // Once: positions and vertex normals in I16F16 (the cube has none, so
//! // they are prepared from its faces), then camera, projection and light.
//! let need = scene.storage();
//! assert_eq!((need.vec3s, need.objects, need.vertices), (16, 1, 8));
//! let mut vec3s = [Vec3::<I16F16>::ZERO; 16];
//! let mut objects = [PreparedObject::EMPTY; 1];
//! let objects = scene.prepare(&mut vec3s, &mut objects).unwrap();
//! let renderer = Renderer::<I16F16>::new(&scene, 240, 240).unwrap();
//!
//! // Per frame: turn the cube, project each vertex once, draw.
//! let mut pixels = [Color::new(0, 0, 0); 240 * 240];
//! let mut keys = [u16::MAX; 240 * 240];
//! let mut scratch = [MeshVertex::default(); 8];
//! for frame in 0..3 {
//!     objects[0].pose.angles.yaw = I16F16::from_f32(0.3) * I16F16::from_i32(frame);
//!     let projected = renderer.project(objects, &mut scratch).unwrap();
//!     let mut fb = Framebuffer::new(&mut pixels, 240, 240, 240).unwrap();
//!     let mut depth = DepthBuffer::new(&mut keys, 240, 240, 240, 0).unwrap();
//!     depth.clear();
//!     let stats = projected.draw(&mut fb, &mut depth);
//!     // A closed cube: its back faces are culled before any set-up.
//!     assert!(stats.drawn >= 2 && stats.culled >= 4, "{stats:?}");
//! }
//! assert!(pixels.iter().any(|&p| p != scene.background));
//! # }
//! ```
//!
//! For a small RAM, draw the same projected frame band by band into a
//! [`target::Band`] with a band-sized depth buffer; every caller (the host
//! simulator, the tests, the firmware) renders this way.
//!
//! ## Layers (bottom to top)
//!
//! Every module uses only modules above it in this table (its *uses*
//! column, which the unit test `layer_tests` checks against the source
//! text: a module that names another outside its list, or one listed
//! below itself, fails the build's tests).
//!
//! | module | what it holds | uses |
//! |---|---|---|
//! | [`scalar`] | the [`Scalar`](scalar::Scalar) trait for `f32`, `f64` and [`Fx`](scalar::Fx) fixed point; overflow policy | — |
//! | [`math`] | `Vec2/3/4`, `Mat3` (with a direct adjugate inverse), `Affine3` (3×4), `Mat4` | `scalar` |
//! | [`solve`] | Gaussian elimination with partial pivoting, N×N with M right-hand sides, with pivot growth and the reciprocal condition number; inverses with those diagnostics | `scalar`, `math` |
//! | [`texture`] | the one texel store and nearest-texel sampler ([`Texture`](texture::Texture), wrap modes) shared by raster, ray and scene; texture-mapping vectors (axis-edge fast path, any polygon via [`solve`]), the per-pixel perspective mapping, and the affine/perspective choice from a distortion bound | `scalar`, `math`, `solve` |
//! | [`transform`] | object→world from roll, pitch, yaw and an origin | `scalar`, `math` |
//! | [`camera`] | cameras from angles, orthonormal vectors or general vectors (via [`solve`]); projections | `scalar`, `math`, `solve`, `transform` |
//! | [`target`] | span sinks: slice framebuffer with stride, bands for strip rendering, embedded-graphics `DrawTarget` adapter | — |
//! | [`raster`] | integer scan conversion of convex polygons (28.4 sub-pixel, top-left rule) into spans; span shaders (flat, Gouraud, affine and perspective-correct textures, exact or subdivided); optional depth buffer | `scalar`, `texture`, `target` |
//! | [`pipeline`] | vertex formats chosen at compile time (xyz, +intensity, +uv, +both, perspective uv); Sutherland–Hodgman clipping in view space (near, far, four side planes with a guard band); projection to 28.4 sub-pixel coordinates and depth keys, handed to [`raster`] | `scalar`, `math`, `camera`, `target`, `raster` |
//! | [`ray`] | screen→world: rays from a ray-casting camera, planes, polygons with four inclusion tests, spheres, watertight triangles, nearest hit, bounding boxes and spheres, a uniform grid, and a column caster over 2D grid maps | `scalar`, `math`, `solve`, `texture`, `camera`, `target` |
//! | [`scene`] | in rooms: the borrowed description (meshes, poses, materials, light, camera), hand-made descriptions, the prepared scene in the render scalar, the raster renderer and the ray renderer over it, the one material model they share, and the demo scenes as static data (feature `demo`) | `scalar`, `math`, `solve`, `texture`, `transform`, `camera`, `target`, `raster`, `pipeline`, `ray` |
//!
//! The pipeline sits above the raster: the scan converter knows nothing
//! of vertices or clipping, and the pipeline hands it projected polygons.
//!
//! ## Naming
//!
//! - American spelling (`center`, `color`, `normalize`, `quantize`), as
//!   the Rust ecosystem writes it.
//! - `try_*` (`try_normalize`, `try_inverse`, `try_orthonormalize`)
//!   returns `Option`: `None` is the one way it can fail. A validating
//!   constructor (`new`, `from_*`, `look_at`) returns `Result` with an
//!   error that says what was wrong.
//! - `checked_*` returns `None` on overflow or a non-finite result;
//!   `*_noting_overflow` saturates and sets a caller's flag instead, for
//!   loops that check once at the end.
//! - The const generic `VARYINGS` is the number of interpolated values a
//!   vertex carries to the scan converter.
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
//!   top-left corner of the top-left pixel, so pixel (i, j) has its center
//!   at (i + ½, j + ½). Perspective projection is `x_s = cx + f·x/z`,
//!   `y_s = cy + f·y/z`, with the focus distance `f` in pixels and
//!   (cx, cy) usually the viewport center.
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
//! Whole stages are cargo features, so that a firmware links only what its
//! scenes use. The default is the minimal flat-shaded raster path
//! (scalars, math, solver, cameras, pipeline with near and side clipping,
//! the scan converter with [`Flat`](raster::Flat) and
//! [`NoDepth`](raster::NoDepth), targets, scene descriptions). Generic code
//! costs nothing until it is instantiated; the features remove what
//! the scene renderer ([`scene::Renderer`]) would otherwise link for every
//! material.
//!
//! | feature | adds | needs |
//! |---|---|---|
//! | `depth` | `raster::DepthBuffer` | |
//! | `gouraud` | `raster::Gouraud`; Gouraud materials in [`scene::Renderer`] | |
//! | `texture` | the mapping half of [`texture`] (vectors, screen mapping, `choose_mapping`; its texel store is always there, as scene descriptions name it), the affine texture shaders; affine texture materials | |
//! | `perspective` | `raster::PerspectiveTexture`; perspective and `Auto` texture materials | `texture` |
//! | `clip-far` | clipping at the far plane when asked ([`Pipeline::with_far_clip`](pipeline::Pipeline::with_far_clip), [`Renderer::with_far_clip`](scene::Renderer::with_far_clip)); without it geometry beyond `far` is drawn, its depth key saturated at the far value | |
//! | `raycast` | `ray`, `scene::RayScene` | |
//! | `sphere` | `ray::Sphere`; spheres in `scene::RayScene` | `raycast` |
//! | `grid` | `ray::Grid` | `raycast` |
//! | `column` | the column (grid-map) caster `ray::column` | `raycast`, `texture` |
//! | `demo` | the built-in demo scenes `scene::builtin` (const data; the bunny's is generated by the build script from `data/bunny.obj`) | |
//! | `full` | all of the above (the host simulator, tests and fuzzers use it) | |
//! | `serde` | `serde::Deserialize` for the description types a scene file spells the same way ([`scene::CameraSpec`], [`scene::Light`], [`scene::TextureMode`]), checking numbers as they are read; no_std, no alloc; not part of `full` | |
//! | `export` | `scene::export`: a prepared scene written as Rust source, for a firmware's `build.rs` to turn into `const` data (the device then does no `f32` arithmetic and no camera solving); a host tool, not part of `full` | |
//!
//! What the stages cost, measured by `bash tests/mcu/run` on firmware that
//! renders built-in scenes at 320×240 in I16F16 through 15-row strips
//! (thumbv6m, `opt-level = "s"`, LTO; bytes; the table is generated by that
//! run, full tables in `docs/mcu/tables.md`). *By inline chain* counts
//! every byte whose inlining chain passes through sightline's source (what
//! the library costs a firmware); *by innermost line* charges a byte to the
//! innermost source line, so sightline's arithmetic inlined from Rust's
//! core library does not count there:
//!
#![doc = include_str!("../doc/sizes.md")]
//!
//! The differences include each scene's own use of the stage (e.g. vertex
//! normals for the bunny); `depth`, `clip-far`, `grid` and `column` were not
//! measured on their own.
//!
//! Features are additive: each adds code and API and never changes what
//! existing calls do; a behavior is chosen by an argument (e.g. far-plane
//! clipping by [`Pipeline::with_far_clip`](pipeline::Pipeline::with_far_clip)).
//! A feature that needs another turns it on (`perspective` turns on
//! `texture`; `sphere`, `grid` and `column` turn on `raycast`; `column`
//! turns on `texture` too). A scene whose material
//! needs a stage that is left out is refused at run time with
//! [`SceneError::FeatureDisabled`](scene::SceneError::FeatureDisabled),
//! before anything is drawn.

#![no_std]
// One module allows `unsafe` (`target::pairs`: two 2-byte pixels per
// 32-bit store in solid fills; tested under Miri in CI).
#![deny(unsafe_code)]
// docs.rs (nightly, `--cfg docsrs`) marks each item with the features it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]
#![deny(missing_docs, missing_debug_implementations)]

#[cfg(test)]
extern crate std;

pub mod camera;
pub mod math;
pub mod pipeline;
pub mod raster;
#[cfg(feature = "raycast")]
pub mod ray;
pub mod scalar;
pub mod scene;
pub mod solve;
pub mod target;
pub mod texture;
pub mod transform;

// Checks the layer table above against the source text.
#[cfg(test)]
mod layer_tests;

// Shared by the test modules; a build with fewer stages runs fewer of them.
#[cfg(test)]
mod test_util;

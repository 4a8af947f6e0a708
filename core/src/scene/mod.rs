//! One borrowed, allocation-free scene description that both viewing
//! paths render: the raster path (world→screen through the
//! [`pipeline`](crate::pipeline)) over its prepared form, and the ray path
//! ([`RayScene`], screen→world per pixel or per row).
//!
//! The layer is split into rooms, one per concept; every public item is
//! re-exported here, so its path is `sightline::scene::X` whichever room
//! holds it.
//!
//! | room | what it holds |
//! |---|---|
//! | `description.rs` | the description, borrowed and in `f32`: [`MeshData`], [`Material`], [`SceneObject`], [`SceneSphere`], [`Light`], [`CameraSpec`], [`ProjectionSpec`], [`Scene`]; checking it ([`Scene::validate`]) and its [`View`] for one image size |
//! | `error.rs` | [`SceneError`], shared by every room |
//! | `build.rs` | hand-made descriptions: [`Scene::new`] with defaults, [`quantize_positions`] and [`quantize_normals`] at compile time |
//! | `prepared.rs` | the prepared scene, made once: [`PreparedMesh`] (positions and normals in the render scalar), [`PreparedObject`], [`Scene::prepare`] into caller storage |
//! | `render.rs` | the raster renderer, per frame: [`Renderer::project`] (each vertex once) and [`Frame::draw`] (per band) |
//! | `ray/` | the ray renderer (feature `raycast`): `RayScene`, per-pixel and per-row ray casting, shaded at the hit; with `grid`, a uniform grid per object in caller storage |
//! | `material.rs` | the material model both renderers use, and [`PreparedLight`] |
//! | `export.rs` | a prepared scene written as Rust source, for `const` data in firmware (feature `export`) |
//! | `builtin/` | the demo scenes as `const` data, shared by firmware and the host simulator (feature `demo`) |
//!
//! With feature `serde`, the description types that a scene file spells
//! the same way ([`CameraSpec`], [`Light`], [`TextureMode`]) implement
//! `serde::Deserialize`.
//!
//! # Prepare once, draw per frame
//!
//! ```text
//! Scene (f32, quantized meshes) ──Scene::prepare──► [PreparedObject<S>]   once, into caller storage
//! Scene ──Renderer::new──► Renderer<S> (camera, projection, clip volume, light)
//! per frame: set poses ──Renderer::project──► Frame (every vertex once, into caller scratch)
//! per band:  Frame::draw(target, depth)   (cull, light, set up, scan-convert)
//! ```
//!
//! The [`Renderer`] docs show a whole first render.
//!
//! A firmware can do the first two steps on the host instead: the
//! `export` module (feature `export`) writes the prepared objects and the
//! renderer as Rust source, which the firmware includes as `const` data;
//! it then builds them with [`PreparedMesh::new`],
//! [`PreparedObject::new`], [`Camera::from_world_to_view`](crate::camera::Camera::from_world_to_view),
//! [`PreparedLight::from_unit`] and [`Renderer::from_prepared`], which do
//! no arithmetic, so no `f32` code runs on the device.
//!
//! # Data forms
//!
//! Scene-level numbers (camera, poses, light, spheres) are `f32` so that
//! scenes can be `const`; they are converted to the rendering scalar `S`
//! once, by [`Scene::prepare`] and [`Renderer::new`] (a general camera is
//! solved in `f32` for a fixed-point `S`, then rounded). Mesh positions are quantized `i16` with one `f32`
//! scale per mesh (world units per step), normals are `i16` in units of
//! 1/32767, texture coordinates are `i16` texels: small in flash and exact
//! in I16F16.
//!
//! # Material model
//!
//! Light is one directional light with an ambient and a diffuse term:
//! `I = ambient + diffuse·max(0, n·L)`, clamped to [0, 1] and quantized to
//! `q = ⌊255·I⌋`; the pixel is the base color scaled by `q/255`
//! ([`ScalableColor::scale`](crate::raster::ScalableColor::scale)).
//!
//! - [`Material::Flat`]: `n` is the triangle's face normal, the same exact
//!   integer direction of the quantized vertices on both paths. The raster
//!   path normalizes it once when the mesh is prepared and lights it in
//!   object space (the light turned by the pose); the ray path turns and
//!   normalizes it per hit and lights it in world space. The two round
//!   differently, so a triangle's color can differ by one intensity step
//!   where `255·I` falls within rounding of an integer.
//! - [`Material::Gouraud`]: `I` is evaluated at the vertices (vertex
//!   normals; for a mesh without them the raster path prepares
//!   area-weighted ones, the ray path uses the face normal). The raster
//!   path interpolates it linearly in screen space (16.16 varyings); the
//!   ray path takes the hit's barycentric weights, `I = u·I_A + v·I_B +
//!   w·I_C`, which is linear in object space (perspective-correct). Both
//!   then quantize and scale the color the same way.
//! - [`Material::Texture`]: unlit nearest-texel sampling, repeating a
//!   power-of-two texture. The ray path interpolates the vertices'
//!   texture coordinates with the hit's barycentric weights (for a planar
//!   triangle, the texture-mapping vectors' value at the hit point), so it
//!   is always perspective-correct; the raster path follows
//!   [`TextureMode`]. Both fetch with the one sampler,
//!   [`Texture::sample`](crate::texture::Texture::sample).
//! - Spheres ([`SceneSphere`]) are drawn by the ray path only, lit per hit
//!   with the sphere normal.
//!
//! Both paths sample at pixel centers (i + ½, j + ½) and use the nearest
//! surface, so their images can be compared pixel by pixel.

mod build;
#[cfg(feature = "serde")]
pub mod de;
mod description;
mod error;
#[cfg(feature = "export")]
pub mod export;
mod material;
mod prepared;
#[cfg(feature = "raycast")]
mod ray;
mod render;

#[cfg(feature = "demo")]
pub mod builtin;

pub use build::{QuantizedPositions, quantize_normals, quantize_positions};
pub use description::{
    AUTO_AFFINE_MAX_ERROR, CameraSpec, Color, Light, MAX_RAY_OBJECTS, Material, MeshData,
    ProjectionSpec, Scene, SceneObject, SceneSphere, TextureMode, View, vec3,
};
pub use error::SceneError;
pub use material::{PreparedLight, quantize_intensity};
pub use prepared::{
    MeshError, Normals, PreparedMesh, PreparedObject, Storage, storage_len, triangle_hash,
};
#[cfg(feature = "grid")]
pub use ray::{RayBuffers, RayStorage, RayTriangle};
#[cfg(feature = "raycast")]
pub use ray::{RaySample, RayScene};
pub use render::{Frame, RasterStats, Renderer};

use description::light_is_finite;

// The scene tests compare both paths with every material.
#[cfg(all(
    test,
    feature = "gouraud",
    feature = "texture",
    feature = "perspective",
    feature = "depth",
    feature = "raycast",
    feature = "sphere",
    feature = "demo"
))]
mod tests;
// What a build with fewer stages does; runs with any feature set that
// has the demo scenes.
#[cfg(all(test, feature = "demo"))]
mod feature_tests;

//! One borrowed, allocation-free scene description that both viewing
//! paths render: the raster path (world→screen through the
//! [`pipeline`](crate::pipeline)) over its prepared form, and the ray path
//! ([`RayScene`], screen→world per pixel or per row).
//!
//! | file | what it holds |
//! |---|---|
//! | `mod.rs` | the description: [`MeshData`], [`Material`], [`SceneObject`], [`SceneSphere`], [`Light`], [`CameraSpec`], [`ProjectionSpec`], [`Scene`]; [`SceneError`] |
//! | `build.rs` | building descriptions by hand: [`Scene::new`] with defaults, [`quantize_positions`] and [`quantize_normals`] at compile time |
//! | `prepared.rs` | the prepared form, made once: [`PreparedMesh`] (positions and normals in the render scalar), [`PreparedObject`], [`Scene::prepare`] into caller storage |
//! | `render.rs` | the raster path per frame: [`Renderer::project`] (each vertex once) and [`Frame::draw`] (per band) |
//! | `shade.rs` | the one material model both paths use |
//! | `ray/` | [`RayScene`]: per-pixel and per-row ray casting, shaded at the hit; with `grid`, a uniform grid per object in caller storage |
//! | `builtin/` | demo scenes as `const` data, shared by firmware and the host simulator |
//!
//! # Prepare once, draw per frame
//!
//! ```text
//! Scene (f32, quantised meshes) ──Scene::prepare──► [PreparedObject<S>]   once, into caller storage
//! Scene ──Renderer::new──► Renderer<S> (camera, projection, clip volume, light)
//! per frame: set poses ──Renderer::project──► Frame (every vertex once, into caller scratch)
//! per band:  Frame::draw(target, depth)   (cull, light, set up, scan-convert)
//! ```
//!
//! The [`Renderer`] docs show a whole first render.
//!
//! # Data forms
//!
//! Scene-level numbers (camera, poses, light, spheres) are `f32` so that
//! scenes can be `const`; they are converted to the rendering scalar `S`
//! once, by [`Scene::prepare`] and [`Renderer::new`] (a general camera is
//! solved in `f32` for a fixed-point `S`, then rounded). Mesh positions are quantised `i16` with one `f32`
//! scale per mesh (world units per step), normals are `i16` in units of
//! 1/32767, texture coordinates are `i16` texels: small in flash and exact
//! in I16F16.
//!
//! # Material model
//!
//! Light is one directional light with an ambient and a diffuse term:
//! `I = ambient + diffuse·max(0, n·L)`, clamped to [0, 1] and quantised to
//! `q = ⌊255·I⌋`; the pixel is the base colour scaled by `q/255`
//! ([`Shade::scale`](crate::raster::Shade::scale)).
//!
//! - [`Material::Flat`]: `n` is the triangle's face normal, the same exact
//!   integer direction of the quantised vertices on both paths. The raster
//!   path normalises it once when the mesh is prepared and lights it in
//!   object space (the light turned by the pose); the ray path turns and
//!   normalises it per hit and lights it in world space. The two round
//!   differently, so a triangle's colour can differ by one intensity step
//!   where `255·I` falls within rounding of an integer.
//! - [`Material::Gouraud`]: `I` is evaluated at the vertices (vertex
//!   normals; for a mesh without them the raster path prepares
//!   area-weighted ones, the ray path uses the face normal). The raster
//!   path interpolates it linearly in screen space (16.16 varyings); the
//!   ray path takes the hit's barycentric weights, `I = u·I_A + v·I_B +
//!   w·I_C`, which is linear in object space (perspective-correct). Both
//!   then quantise and scale the colour the same way.
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
//! Both paths sample at pixel centres (i + ½, j + ½) and use the nearest
//! surface, so their images can be compared pixel by pixel.

mod build;
mod prepared;
#[cfg(feature = "raycast")]
mod ray;
mod render;
mod shade;

pub mod builtin;

pub use build::{QuantizedPositions, quantize_normals, quantize_positions};
pub use prepared::{MeshError, Normals, PreparedMesh, PreparedObject, Storage, storage_len};
#[cfg(feature = "grid")]
pub use ray::{RayBuffers, RayStorage, RayTriangle};
#[cfg(feature = "raycast")]
pub use ray::{RaySample, RayScene};
pub use render::{Frame, RasterStats, Renderer};

/// How many objects, and how many spheres, the ray path holds (its
/// per-object state lives in fixed-capacity vectors: no allocation).
pub const MAX_RAY_OBJECTS: usize = 32;
pub use shade::quantise_intensity;

use crate::camera::{Camera, CameraError, Projection};
use crate::math::Vec3;
use crate::pipeline::PipelineError;
#[cfg(feature = "raycast")]
use crate::ray::RayCameraError;
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};
use core::fmt;
use embedded_graphics::pixelcolor::Rgb565;

/// The colour type of scenes and of their images.
pub type Color = Rgb565;

/// An indexed triangle mesh over borrowed slices, quantised: the
/// description a file or `const` data gives. [`MeshData::prepare`] turns it
/// into the render scalar.
///
/// Triangles are counter-clockwise seen from outside (the OBJ
/// convention). A mesh marked [`closed`](Self::closed) has its back faces
/// culled; an open one is drawn from both sides.
#[derive(Clone, Copy, Debug)]
pub struct MeshData<'a> {
    /// Whether every edge is shared by exactly two triangles with opposite
    /// winding (a closed, consistently oriented surface, whose back faces
    /// can never be seen from outside).
    pub closed: bool,
    /// Quantised object-space positions: position `k` is
    /// `positions[k] · scale`.
    pub positions: &'a [[i16; 3]],
    /// World units per position step.
    pub scale: f32,
    /// Vertex indices of each triangle.
    pub triangles: &'a [[u16; 3]],
    /// Optional unit vertex normals in units of 1/32767 (for Gouraud).
    pub normals: Option<&'a [[i16; 3]]>,
    /// Optional texture coordinates in texels (for textures).
    pub uvs: Option<&'a [[i16; 2]]>,
}

/// How the raster path maps a texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureMode {
    /// Linear in screen space: cheap, distorted on steep polygons.
    Affine,
    /// Perspective-correct, one (reciprocal) division per pixel.
    Perspective,
    /// Per triangle, by [`choose_mapping`](crate::texture::choose_mapping):
    /// affine where the bound on affine mapping's error
    /// ([`affine_error_bound`](crate::texture::affine_error_bound), from
    /// the vertices' depths and texture coordinates) is at most
    /// [`AUTO_AFFINE_MAX_ERROR`] texels, perspective elsewhere and for
    /// every triangle that needs clipping.
    Auto,
}

/// The largest affine error, in texels per axis, that
/// [`TextureMode::Auto`] accepts before it maps a triangle perspectively:
/// half a texel, so that with the rounding of both paths an affinely
/// mapped pixel stays within one texel of the perspective-correct one.
pub const AUTO_AFFINE_MAX_ERROR: f32 = 0.5;

/// A surface's appearance.
#[derive(Clone, Copy, Debug)]
pub enum Material<'a> {
    /// One colour per triangle, lit with the face normal.
    Flat(Color),
    /// Lit at the vertices and interpolated.
    Gouraud(Color),
    /// An unlit texture.
    Texture {
        /// The texels; both sides must be powers of two (the renderers
        /// tile with [`RepeatPow2`](crate::texture::RepeatPow2)).
        texture: crate::texture::Texture<'a, Color>,
        /// Affine, perspective or chosen per triangle.
        mode: TextureMode,
    },
}

/// A mesh placed in the world with a material.
#[derive(Clone, Copy, Debug)]
pub struct SceneObject<'a> {
    /// The shape.
    pub mesh: &'a MeshData<'a>,
    /// Where it is: origin and roll/pitch/yaw (radians).
    pub pose: Pose<f32>,
    /// How it looks.
    pub material: Material<'a>,
}

/// A sphere, drawn by the ray path only.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneSphere {
    /// Centre in world coordinates.
    pub centre: [f32; 3],
    /// Radius.
    pub radius: f32,
    /// Base colour, lit per hit.
    pub color: Color,
}

/// A directional light with an ambient term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Direction *towards* the light (world; need not be unit length).
    pub direction: [f32; 3],
    /// Ambient intensity.
    pub ambient: f32,
    /// Diffuse intensity.
    pub diffuse: f32,
}

/// The camera, in any of the forms of [`Camera`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSpec {
    /// [`Camera::from_angles`].
    Angles {
        /// Eye position.
        position: [f32; 3],
        /// Roll, pitch, yaw in radians.
        angles: [f32; 3],
    },
    /// [`Camera::from_orthonormal`].
    Orthonormal {
        /// Eye position.
        position: [f32; 3],
        /// Screen right.
        right: [f32; 3],
        /// Screen down.
        down: [f32; 3],
        /// Direction of view.
        forward: [f32; 3],
    },
    /// [`Camera::from_vectors`] (general vectors, solved).
    Vectors {
        /// Eye position.
        position: [f32; 3],
        /// World vector of view x.
        u: [f32; 3],
        /// World vector of view y.
        v: [f32; 3],
        /// World vector of view z.
        w: [f32; 3],
    },
    /// [`Camera::look_at`].
    LookAt {
        /// Eye position.
        eye: [f32; 3],
        /// Point looked at.
        target: [f32; 3],
        /// Screen up.
        up: [f32; 3],
    },
}

/// The projection, independent of the image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProjectionSpec {
    /// Perspective with a horizontal field of view in radians.
    Perspective {
        /// Horizontal field of view, radians, in (0, π).
        fov_x: f32,
    },
    /// Parallel projection showing `width` world units across the image
    /// (raster path only).
    Parallel {
        /// World units across the image.
        width: f32,
    },
}

/// A whole scene.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'a> {
    /// Short name (for file names and listings).
    pub name: &'a str,
    /// One line describing it.
    pub description: &'a str,
    /// The camera.
    pub camera: CameraSpec,
    /// The projection.
    pub projection: ProjectionSpec,
    /// Near clip distance (view z).
    pub near: f32,
    /// Far distance (view z): the end of the depth range. Geometry beyond
    /// it is drawn with the farthest depth key, unless the renderer clips
    /// there ([`Renderer::with_far_clip`], feature `clip-far`).
    pub far: f32,
    /// The light.
    pub light: Light,
    /// Colour where nothing is hit.
    pub background: Color,
    /// Meshes (both paths).
    pub objects: &'a [SceneObject<'a>],
    /// Spheres (ray path only).
    pub spheres: &'a [SceneSphere],
}

/// Why a scene cannot be rendered.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SceneError {
    /// A number of the scene is NaN or ±∞: `what` names it (`camera`,
    /// `projection`, `light`, `near`, `far`).
    NonFinite {
        /// Which part of the scene.
        what: &'static str,
    },
    /// A mesh could not be prepared.
    Mesh {
        /// Object index in the scene.
        object: usize,
        /// Why.
        error: MeshError,
    },
    /// A flat material without face normals, or a Gouraud one without
    /// vertex normals, in a [`PreparedMesh`].
    MissingNormals {
        /// Object index in the scene.
        object: usize,
    },
    /// The storage given to [`Scene::prepare`] is shorter than
    /// [`Scene::storage`] says.
    Storage,
    /// The frame scratch given to [`Renderer::project`] is too short.
    ScratchTooSmall {
        /// Vertices needed (all objects together).
        needed: usize,
        /// Vertices given.
        given: usize,
    },
    /// The camera could not be built.
    Camera(CameraError),
    /// The field of view is not in (0, π), or the image size is zero.
    BadProjection,
    /// The pipeline rejected the projection or depth range.
    Pipeline(PipelineError),
    /// The ray camera could not be built (e.g. a parallel projection).
    #[cfg(feature = "raycast")]
    RayCamera(RayCameraError),
    /// The scene needs a stage this build of the crate leaves out: the
    /// named cargo feature (e.g. a Gouraud material without `gouraud` on
    /// the raster path, spheres without `sphere` on the ray path).
    FeatureDisabled {
        /// The cargo feature to enable.
        feature: &'static str,
    },
    /// A triangle index is beyond the mesh's positions.
    IndexOutOfRange {
        /// Object index in the scene.
        object: usize,
        /// Triangle index in the mesh.
        triangle: usize,
    },
    /// Normals or texture coordinates are not one per position.
    AttributeCount {
        /// Object index in the scene.
        object: usize,
    },
    /// A texture side is not a power of two.
    TextureNotPowerOfTwo {
        /// Width in texels.
        width: u16,
        /// Height in texels.
        height: u16,
    },
    /// A texture's texel count differs from width × height.
    TextureSize,
    /// A textured mesh has no texture coordinates.
    MissingUv {
        /// Object index in the scene.
        object: usize,
    },
    /// A slice of the ray path's grid storage is shorter than
    /// `Scene::ray_storage` says (feature `grid`).
    RayStorage {
        /// Which slice: `triangles`, `cells` or `items`.
        what: &'static str,
        /// Elements needed.
        needed: usize,
        /// Elements given.
        given: usize,
    },
    /// More objects than the ray path's capacity [`MAX_RAY_OBJECTS`].
    TooManyObjects,
    /// A pose cannot be inverted (ray path), or a value is not finite.
    BadPose {
        /// Object index in the scene.
        object: usize,
    },
    /// A sphere has a non-positive or non-finite radius or centre.
    BadSphere {
        /// Sphere index in the scene.
        sphere: usize,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite { what } => write!(f, "{what}: a value is NaN or infinite"),
            Self::Mesh { object, error } => write!(f, "object {object}: {error}"),
            Self::MissingNormals { object } => write!(
                f,
                "object {object}: the material needs normals the prepared mesh lacks"
            ),
            Self::Storage => f.write_str("storage is shorter than Scene::storage says"),
            Self::ScratchTooSmall { needed, given } => write!(
                f,
                "frame scratch holds {given} vertices, the objects have {needed}"
            ),
            Self::Camera(e) => write!(f, "camera: {e}"),
            Self::BadProjection => {
                f.write_str("projection: need 0 < fov_x < pi (or width > 0) and a non-empty image")
            }
            Self::Pipeline(e) => write!(f, "pipeline: {e}"),
            #[cfg(feature = "raycast")]
            Self::RayCamera(e) => write!(f, "ray camera: {e}"),
            Self::FeatureDisabled { feature } => {
                write!(f, "the scene needs the `{feature}` feature of sightline")
            }
            Self::IndexOutOfRange { object, triangle } => write!(
                f,
                "object {object}: triangle {triangle} has a vertex index beyond the positions"
            ),
            Self::AttributeCount { object } => write!(
                f,
                "object {object}: normals or uvs must have one entry per position"
            ),
            Self::TextureNotPowerOfTwo { width, height } => write!(
                f,
                "texture is {width}x{height}: both sides must be powers of two"
            ),
            Self::TextureSize => f.write_str("texture texel count differs from width x height"),
            Self::MissingUv { object } => {
                write!(
                    f,
                    "object {object}: textured mesh has no texture coordinates"
                )
            }
            Self::RayStorage {
                what,
                needed,
                given,
            } => write!(
                f,
                "ray storage: {what} holds {given} entries, the scene needs {needed}"
            ),
            Self::TooManyObjects => {
                write!(f, "more than {MAX_RAY_OBJECTS} objects for the ray path")
            }
            Self::BadPose { object } => {
                write!(
                    f,
                    "object {object}: pose is NaN, infinite or not invertible"
                )
            }
            Self::BadSphere { sphere } => write!(f, "sphere {sphere}: bad centre or radius"),
        }
    }
}

impl core::error::Error for SceneError {}

impl SceneError {
    /// The same error with its object index set to `object` (for errors
    /// that name an object).
    #[must_use]
    pub fn at_object(self, object: usize) -> Self {
        match self {
            Self::Mesh { error, .. } => Self::Mesh { object, error },
            Self::MissingNormals { .. } => Self::MissingNormals { object },
            Self::MissingUv { .. } => Self::MissingUv { object },
            Self::BadPose { .. } => Self::BadPose { object },
            Self::AttributeCount { .. } => Self::AttributeCount { object },
            Self::IndexOutOfRange { triangle, .. } => Self::IndexOutOfRange { object, triangle },
            e => e,
        }
    }
}

fn finite3(v: &[f32; 3]) -> bool {
    v.iter().all(|c| c.is_finite())
}

fn light_is_finite(l: &Light) -> bool {
    finite3(&l.direction) && l.ambient.is_finite() && l.diffuse.is_finite()
}

/// `[f32; 3]` → `Vec3<S>`.
#[must_use]
pub fn vec3<S: Scalar>(v: [f32; 3]) -> Vec3<S> {
    Vec3::new(S::from_f32(v[0]), S::from_f32(v[1]), S::from_f32(v[2]))
}

/// A scene's camera and projection for one image size, in scalar `S`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View<S> {
    /// The camera.
    pub camera: Camera<S>,
    /// The projection about the image centre.
    pub projection: Projection<S>,
    /// Image width in pixels.
    pub width: u16,
    /// Image height in pixels.
    pub height: u16,
}

impl CameraSpec {
    /// Builds the camera in scalar `S`.
    ///
    /// # Errors
    /// The camera constructor's [`CameraError`].
    pub fn build<S: Scalar>(&self) -> Result<Camera<S>, CameraError> {
        match *self {
            Self::Angles { position, angles } => Ok(Camera::from_angles(
                vec3(position),
                Euler::new(
                    S::from_f32(angles[0]),
                    S::from_f32(angles[1]),
                    S::from_f32(angles[2]),
                ),
            )),
            Self::Orthonormal {
                position,
                right,
                down,
                forward,
            } => Camera::from_orthonormal(vec3(position), vec3(right), vec3(down), vec3(forward)),
            // Solved in f32 for fixed point and rounded: a camera solved in
            // I16F16 is ~370x less accurate (docs/report/accuracy.md).
            Self::Vectors { position, u, v, w } if !S::IS_FLOAT => {
                Camera::<f32>::from_vectors(vec3(position), vec3(u), vec3(v), vec3(w))
                    .map(|(c, _)| c.cast())
            }
            Self::Vectors { position, u, v, w } => {
                Camera::from_vectors(vec3(position), vec3(u), vec3(v), vec3(w)).map(|(c, _)| c)
            }
            Self::LookAt { eye, target, up } => Camera::look_at(vec3(eye), vec3(target), vec3(up)),
        }
    }
}

impl Scene<'_> {
    /// The camera and projection for a `width`×`height` image.
    ///
    /// # Errors
    /// [`SceneError::Camera`], [`SceneError::BadProjection`].
    pub fn view<S: Scalar>(&self, width: u16, height: u16) -> Result<View<S>, SceneError> {
        if width == 0 || height == 0 {
            return Err(SceneError::BadProjection);
        }
        let camera = self.camera.build::<S>().map_err(SceneError::Camera)?;
        let projection = match self.projection {
            ProjectionSpec::Perspective { fov_x } => {
                Projection::perspective_fov(S::from_f32(fov_x), width, height)
                    .ok_or(SceneError::BadProjection)?
            }
            ProjectionSpec::Parallel { width: w } => {
                if !(w > 0.0 && w.is_finite()) {
                    return Err(SceneError::BadProjection);
                }
                Projection::parallel(S::from_f32(width as f32 / w), width, height)
            }
        };
        Ok(View {
            camera,
            projection,
            width,
            height,
        })
    }

    /// Checks that every number of the camera, projection, light and depth
    /// range is finite.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] naming the part.
    pub fn validate_view(&self) -> Result<(), SceneError> {
        let camera_ok = match &self.camera {
            CameraSpec::Angles { position, angles } => finite3(position) && finite3(angles),
            CameraSpec::Orthonormal {
                position,
                right,
                down,
                forward,
            } => finite3(position) && finite3(right) && finite3(down) && finite3(forward),
            CameraSpec::Vectors { position, u, v, w } => {
                finite3(position) && finite3(u) && finite3(v) && finite3(w)
            }
            CameraSpec::LookAt { eye, target, up } => {
                finite3(eye) && finite3(target) && finite3(up)
            }
        };
        let projection_ok = match self.projection {
            ProjectionSpec::Perspective { fov_x } => fov_x.is_finite(),
            ProjectionSpec::Parallel { width } => width.is_finite(),
        };
        let checks = [
            (camera_ok, "camera"),
            (projection_ok, "projection"),
            (light_is_finite(&self.light), "light"),
            (self.near.is_finite(), "near"),
            (self.far.is_finite(), "far"),
        ];
        match checks.iter().find(|(ok, _)| !ok) {
            Some(&(_, what)) => Err(SceneError::NonFinite { what }),
            None => Ok(()),
        }
    }

    /// Checks every mesh and material: indices in range, one normal and uv
    /// per position, uvs present for textures, textures power-of-two.
    ///
    /// # Errors
    /// The first problem found.
    pub fn validate(&self) -> Result<(), SceneError> {
        for (o, obj) in self.objects.iter().enumerate() {
            let m = obj.mesh;
            let n = m.positions.len();
            for (t, tri) in m.triangles.iter().enumerate() {
                if tri.iter().any(|&k| k as usize >= n) {
                    return Err(SceneError::IndexOutOfRange {
                        object: o,
                        triangle: t,
                    });
                }
            }
            if m.normals.is_some_and(|v| v.len() != n) || m.uvs.is_some_and(|v| v.len() != n) {
                return Err(SceneError::AttributeCount { object: o });
            }
            if let Material::Texture { texture, .. } = obj.material {
                if !texture.accepts::<crate::texture::RepeatPow2>() {
                    return Err(SceneError::TextureNotPowerOfTwo {
                        width: texture.width(),
                        height: texture.height(),
                    });
                }
                if m.uvs.is_none() {
                    return Err(SceneError::MissingUv { object: o });
                }
            }
            let p = &obj.pose;
            let finite = [
                p.origin.x,
                p.origin.y,
                p.origin.z,
                p.angles.roll,
                p.angles.pitch,
            ]
            .iter()
            .chain([p.angles.yaw, m.scale].iter())
            .all(|v| v.is_finite());
            if !finite || m.scale == 0.0 {
                return Err(SceneError::BadPose { object: o });
            }
        }
        for (k, s) in self.spheres.iter().enumerate() {
            if !(s.radius > 0.0 && s.radius.is_finite() && s.centre.iter().all(|c| c.is_finite())) {
                return Err(SceneError::BadSphere { sphere: k });
            }
        }
        Ok(())
    }
}

// The scene tests compare both paths with every material.
#[cfg(all(
    test,
    feature = "gouraud",
    feature = "texture",
    feature = "perspective",
    feature = "depth",
    feature = "raycast",
    feature = "sphere"
))]
mod tests;
// What a build with fewer stages does; runs with any feature set.
#[cfg(test)]
mod feature_tests;

//! [`SceneError`]: why a scene cannot be prepared or rendered, shared by
//! every room of the scene layer.

use super::MAX_RAY_OBJECTS;
use super::prepared::MeshError;
use crate::camera::CameraError;
use crate::pipeline::PipelineError;
#[cfg(feature = "raycast")]
use crate::ray::RayCameraError;
use core::fmt;

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
    /// vertex normals, in a [`PreparedMesh`](super::PreparedMesh).
    MissingNormals {
        /// Object index in the scene.
        object: usize,
    },
    /// The storage given to [`Scene::prepare`](super::Scene::prepare) is shorter than
    /// [`Scene::storage`](super::Scene::storage) says.
    Storage,
    /// The frame scratch given to [`Renderer::project`](super::Renderer::project) is too short.
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
    /// A sphere has a non-positive or non-finite radius or center.
    BadSphere {
        /// Sphere index in the scene.
        sphere: usize,
    },
    /// [`Frame::draw_unclipped`](super::Frame::draw_unclipped) was given
    /// a frame in which a triangle of this object crosses a plane of the
    /// view volume (the side planes at the object's guard band, see
    /// [`Renderer::project`](super::Renderer::project)) or uses a vertex
    /// that cannot be projected: it needs the clipper of
    /// [`Frame::draw`](super::Frame::draw).
    NeedsClipping {
        /// Object index in the scene (the first such object).
        object: usize,
    },
    /// [`Frame::draw_unclipped`](super::Frame::draw_unclipped) covers
    /// guard bands within ±1024 pixels (its 32-bit triangle walk): a
    /// viewport up to 1007 pixels a side with the pipeline's 16-pixel
    /// band. This viewport's is wider; draw it with
    /// [`Frame::draw`](super::Frame::draw).
    ViewportTooLarge,
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
            Self::BadSphere { sphere } => write!(f, "sphere {sphere}: bad center or radius"),
            Self::NeedsClipping { object } => write!(
                f,
                "object {object}: a triangle crosses the view volume's boundary; draw the frame with Frame::draw, which clips"
            ),
            Self::ViewportTooLarge => f.write_str(
                "the viewport's guard band reaches beyond 1024 pixels: draw the frame with Frame::draw"
            ),
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
            Self::NeedsClipping { .. } => Self::NeedsClipping { object },
            e => e,
        }
    }
}

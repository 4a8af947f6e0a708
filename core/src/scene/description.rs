//! The description: what a scene file or `const` data says, borrowed and
//! in `f32` (meshes quantized to `i16`). Nothing here allocates or depends
//! on the render scalar until [`Scene::view`] or [`CameraSpec::build`]
//! turns the camera into one.

use super::SceneError;
use crate::camera::{Camera, CameraError, Projection};
use crate::math::Vec3;
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};
use embedded_graphics::pixelcolor::Rgb565;

/// The color type of scenes and of their images.
pub type Color = Rgb565;

/// An indexed triangle mesh over borrowed slices, quantized: the
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
    /// Quantized object-space positions: position `k` is
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
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize),
    serde(rename = "mode", deny_unknown_fields)
)]
pub enum TextureMode {
    /// Linear in screen space: cheap, distorted on steep polygons.
    Affine,
    /// Perspective-correct and exact: every pixel reads the texel of its
    /// own (u·q)/q (`raster::PerspectiveTexture` with `N = 1`).
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
    /// One color per triangle, lit with the face normal.
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
    /// Center in world coordinates.
    pub center: [f32; 3],
    /// Radius.
    pub radius: f32,
    /// Base color, lit per hit.
    pub color: Color,
}

/// A directional light with an ambient term.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize),
    serde(rename = "light", deny_unknown_fields)
)]
pub struct Light {
    /// Direction *towards* the light (world; need not be unit length).
    #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
    pub direction: [f32; 3],
    /// Ambient intensity (read from a file: 0 unless given).
    #[cfg_attr(
        feature = "serde",
        serde(default, deserialize_with = "super::de::finite")
    )]
    pub ambient: f32,
    /// Diffuse intensity (read from a file: 1 unless given).
    #[cfg_attr(
        feature = "serde",
        serde(default = "super::de::one", deserialize_with = "super::de::finite")
    )]
    pub diffuse: f32,
}

/// The camera, in any of the forms of [`Camera`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize),
    serde(rename = "camera", deny_unknown_fields)
)]
pub enum CameraSpec {
    /// [`Camera::from_angles`].
    Angles {
        /// Eye position.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        position: [f32; 3],
        /// Roll, pitch, yaw in radians.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        angles: [f32; 3],
    },
    /// [`Camera::from_orthonormal`].
    Orthonormal {
        /// Eye position.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        position: [f32; 3],
        /// Screen right.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        right: [f32; 3],
        /// Screen down.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        down: [f32; 3],
        /// Direction of view.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        forward: [f32; 3],
    },
    /// [`Camera::from_vectors`] (general vectors, solved).
    Vectors {
        /// Eye position.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        position: [f32; 3],
        /// World vector of view x.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        u: [f32; 3],
        /// World vector of view y.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        v: [f32; 3],
        /// World vector of view z.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        w: [f32; 3],
    },
    /// [`Camera::look_at`].
    LookAt {
        /// Eye position.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        eye: [f32; 3],
        /// Point looked at.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
        target: [f32; 3],
        /// Screen up.
        #[cfg_attr(feature = "serde", serde(deserialize_with = "super::de::finite3"))]
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
    /// there ([`Renderer::with_far_clip`](super::Renderer::with_far_clip), feature `clip-far`).
    pub far: f32,
    /// The light.
    pub light: Light,
    /// Color where nothing is hit.
    pub background: Color,
    /// Meshes (both paths).
    pub objects: &'a [SceneObject<'a>],
    /// Spheres (ray path only).
    pub spheres: &'a [SceneSphere],
}

/// How many objects, and how many spheres, the ray path holds (its
/// per-object state lives in fixed-capacity vectors: no allocation).
pub const MAX_RAY_OBJECTS: usize = 32;

fn finite3(v: &[f32; 3]) -> bool {
    v.iter().all(|c| c.is_finite())
}

pub(super) fn light_is_finite(l: &Light) -> bool {
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
    /// The projection about the image center.
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
        self.view_with(camera, width, height)
    }

    /// The scene's projection for a `width`×`height` image, seen through
    /// a `camera` you built yourself instead of [`Scene::camera`].
    ///
    /// [`CameraSpec::build`] matches every camera form at run time, so a
    /// firmware that calls [`Scene::view`] or [`Renderer::new`](super::Renderer::new)
    /// links the general-vector solver even if its scenes never use it.
    /// Build the camera with the one constructor your scenes need
    /// ([`Camera::look_at`], [`Camera::from_angles`],
    /// [`Camera::from_orthonormal`]) and pass it here (or to
    /// [`Renderer::with_camera`](super::Renderer::with_camera)): the
    /// camera form is then chosen at compile time and no solver code is
    /// linked (`tests/mcu/run` checks this for the flat cube firmware).
    ///
    /// # Errors
    /// [`SceneError::NonFinite`] for a camera with a NaN or infinite
    /// entry; [`SceneError::BadProjection`].
    pub fn view_with<S: Scalar>(
        &self,
        camera: Camera<S>,
        width: u16,
        height: u16,
    ) -> Result<View<S>, SceneError> {
        if width == 0 || height == 0 {
            return Err(SceneError::BadProjection);
        }
        let m = camera.world_to_view();
        if !(m.matrix.m.iter().flatten().all(|v| v.is_finite()) && m.translation.is_finite()) {
            return Err(SceneError::NonFinite { what: "camera" });
        }
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
        if !self.camera_is_finite() {
            return Err(SceneError::NonFinite { what: "camera" });
        }
        self.validate_view_except_camera()
    }

    fn camera_is_finite(&self) -> bool {
        match &self.camera {
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
        }
    }

    /// [`Scene::validate_view`] without the camera (for a renderer given
    /// its own camera).
    pub(super) fn validate_view_except_camera(&self) -> Result<(), SceneError> {
        let projection_ok = match self.projection {
            ProjectionSpec::Perspective { fov_x } => fov_x.is_finite(),
            ProjectionSpec::Parallel { width } => width.is_finite(),
        };
        let checks = [
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
            if !(s.radius > 0.0 && s.radius.is_finite() && s.center.iter().all(|c| c.is_finite())) {
                return Err(SceneError::BadSphere { sphere: k });
            }
        }
        Ok(())
    }
}

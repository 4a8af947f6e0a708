//! The material model shared by both paths (see the module docs): the
//! light, the intensity quantization and the exact face directions of the
//! quantized meshes. Interpolation is each path's own: the raster path's
//! varyings live in `pipeline::vertex`, the ray path shades at the hit.

// The per-vertex and per-hit helpers below that only the ray path calls
// (it shades at the hit, see the module docs) exist with `raycast`.
#[cfg(feature = "raycast")]
use super::MeshData;
use super::{Light, vec3};
use crate::math::{Mat3, Vec3};
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};

/// `I` (any real) → `⌊255·clamp(I, 0, 1)⌋` as the raster path's intensity
/// varying does it: 255·I in 16.16 fixed point, then the integer part.
#[must_use]
pub fn quantize_intensity<S: Scalar>(i: S) -> u8 {
    let v = (i.clamp_to(S::ZERO, S::ONE) * S::from_i32(255))
        .to_subpixel(16)
        .unwrap_or(0);
    (v >> 16).clamp(0, 255) as u8
}

/// The light in the render scalar `S`: a unit direction towards the light,
/// and the ambient and diffuse terms of the material model (see the
/// module docs). [`Renderer`](super::Renderer) holds one; build it from a
/// scene's [`Light`] with [`PreparedLight::from_light`], or from values in
/// `S` with [`PreparedLight::from_unit`] (for example `const` data written
/// by `scene::export`, feature `export`, so that no `f32` code runs on the
/// device).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreparedLight<S> {
    dir: Vec3<S>,
    ambient: S,
    diffuse: S,
}

impl<S: Scalar> PreparedLight<S> {
    /// The light of a description, its direction normalized in `S` (a zero
    /// direction leaves only the ambient term). The caller has checked that
    /// every number is finite.
    pub(crate) fn new(light: &Light) -> Self {
        Self {
            dir: vec3::<S>(light.direction)
                .try_normalize()
                .unwrap_or(Vec3::ZERO),
            ambient: S::from_f32(light.ambient),
            diffuse: S::from_f32(light.diffuse),
        }
    }

    /// The light of a description: its direction normalized in `S` (a
    /// zero direction leaves only the ambient term), its terms rounded to
    /// `S`.
    ///
    /// # Errors
    /// [`SceneError::NonFinite`](super::SceneError::NonFinite) (naming the
    /// light) when a number is NaN or infinite.
    pub fn from_light(light: &Light) -> Result<Self, super::SceneError> {
        if super::light_is_finite(light) {
            Ok(Self::new(light))
        } else {
            Err(super::SceneError::NonFinite { what: "light" })
        }
    }

    /// A light from its parts in `S`, used as given: `direction` points
    /// towards the light and should have unit length (a longer one
    /// brightens the diffuse term in proportion; zero leaves only
    /// `ambient`).
    #[must_use]
    pub const fn from_unit(direction: Vec3<S>, ambient: S, diffuse: S) -> Self {
        Self {
            dir: direction,
            ambient,
            diffuse,
        }
    }

    /// Whether every part is finite (always, in fixed point).
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.dir.is_finite() && self.ambient.is_finite() && self.diffuse.is_finite()
    }

    /// The direction towards the light.
    #[must_use]
    pub fn direction(&self) -> Vec3<S> {
        self.dir
    }

    /// The ambient term.
    #[must_use]
    pub fn ambient(&self) -> S {
        self.ambient
    }

    /// The diffuse term.
    #[must_use]
    pub fn diffuse(&self) -> S {
        self.diffuse
    }

    /// The same light seen from an object turned by the rotation `rot`
    /// (object→world): `n_world·L = (rot·n)·L = n·(rotᵀ·L)`, so object-space
    /// normals can be lit as they are.
    pub(crate) fn in_object(&self, rot: &Mat3<S>) -> Self {
        Self {
            dir: rot.transpose().mul_vec3(self.dir),
            ..*self
        }
    }

    /// This light prepared for the intensities of many normals.
    pub(crate) fn for_normals(&self) -> NormalLight<S> {
        NormalLight {
            light: *self,
            dir: S::dot3_prepare(self.dir.to_array()),
        }
    }

    /// `ambient + diffuse·max(0, n·L)` for a world-space unit normal.
    #[cfg(feature = "raycast")]
    pub(crate) fn intensity(&self, n: Vec3<S>) -> S {
        self.shade(n.dot(self.dir))
    }

    /// `ambient + diffuse·max(0, d)` for `d = n·L`.
    #[inline]
    fn shade(&self, d: S) -> S {
        self.ambient + self.diffuse * d.max_of(S::ZERO)
    }
}

/// A light prepared for many normals of one object
/// ([`PreparedLight::for_normals`]): the same intensities.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NormalLight<S> {
    light: PreparedLight<S>,
    /// The direction prepared for dot products, where `S` has a route.
    dir: Option<[[i32; 3]; 3]>,
}

impl<S: Scalar> NormalLight<S> {
    /// `ambient + diffuse·max(0, n·L)` for a unit normal in the light's
    /// space: the light's own intensity for `n`.
    #[inline]
    pub(crate) fn intensity(&self, n: Vec3<S>) -> S {
        let fast = match &self.dir {
            Some(d) => S::dot3_prepared(d, n.to_array()),
            None => None,
        };
        self.light
            .shade(fast.unwrap_or_else(|| n.dot(self.light.dir)))
    }
}

/// A pose in scalar `S`.
pub(crate) fn pose<S: Scalar>(p: &Pose<f32>) -> Pose<S> {
    Pose::new(
        Vec3::new(
            S::from_f32(p.origin.x),
            S::from_f32(p.origin.y),
            S::from_f32(p.origin.z),
        ),
        Euler::new(
            S::from_f32(p.angles.roll),
            S::from_f32(p.angles.pitch),
            S::from_f32(p.angles.yaw),
        ),
    )
}

/// Object-space position of vertex `k` (zero if out of range; validated
/// scenes never are).
#[inline]
#[cfg(feature = "raycast")]
pub(crate) fn position<S: Scalar>(mesh: &MeshData<'_>, scale: S, k: u16) -> Vec3<S> {
    let p = mesh.positions.get(k as usize).copied().unwrap_or([0; 3]);
    Vec3::new(
        S::from_i32(p[0] as i32) * scale,
        S::from_i32(p[1] as i32) * scale,
        S::from_i32(p[2] as i32) * scale,
    )
}

/// 1/16384, the unit of [`face_direction`].
const INV_2_14: f32 = 1.0 / 16384.0;

/// The exact cross product `(b − a) × (c − a)` of triangle `tri` of
/// quantized positions, in i64 (components below 2^17 each, so below
/// 2^35); a missing index reads as the origin.
pub(crate) fn face_cross(positions: &[[i16; 3]], tri: [u16; 3]) -> [i64; 3] {
    let p = |k: u16| {
        let v = positions.get(k as usize).copied().unwrap_or([0; 3]);
        [v[0] as i64, v[1] as i64, v[2] as i64]
    };
    let (a, b, c) = (p(tri[0]), p(tri[1]), p(tri[2]));
    let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ]
}

/// The face direction of `tri`, [`face_cross`] scaled so its largest
/// component is ±2^14 and flipped for a mirrored (negative-scale) mesh, in
/// `S` (units of 2^14, so the result does not depend on the scalar type's
/// range: I16F16 would lose small triangles' normals to underflow
/// otherwise). `None` for a degenerate triangle.
pub(crate) fn face_direction<S: Scalar>(
    positions: &[[i16; 3]],
    tri: [u16; 3],
    flip: bool,
) -> Option<Vec3<S>> {
    let n = face_cross(positions, tri);
    let m = n.iter().map(|v| v.abs()).max().unwrap_or(0);
    if m == 0 {
        return None;
    }
    let sign = if flip { -1 } else { 1 };
    let unit = S::from_f32(INV_2_14);
    let c = |v: i64| S::from_i32(crate::scalar::div_rem_i64(sign * (v << 14), m).0 as i32) * unit;
    Some(Vec3::new(c(n[0]), c(n[1]), c(n[2])))
}

/// The world-space unit face normal of triangle `tri` under rotation
/// `rot` ([`face_direction`], turned, normalized). `None` for a
/// degenerate triangle.
#[cfg(feature = "raycast")]
pub(crate) fn face_normal<S: Scalar>(
    mesh: &MeshData<'_>,
    rot: &Mat3<S>,
    tri: [u16; 3],
) -> Option<Vec3<S>> {
    let d = face_direction::<S>(mesh.positions, tri, mesh.scale < 0.0)?;
    rot.mul_vec3(d).try_normalize()
}

/// The world-space unit normal at vertex `k`: the mesh's vertex normal if
/// it has them, else `face`.
#[cfg(feature = "raycast")]
pub(crate) fn vertex_normal<S: Scalar>(
    mesh: &MeshData<'_>,
    rot: &Mat3<S>,
    k: u16,
    face: Option<Vec3<S>>,
) -> Option<Vec3<S>> {
    match mesh.normals.and_then(|n| n.get(k as usize)) {
        Some(n) => {
            let unit = S::from_f32(1.0 / 32767.0);
            let v = Vec3::new(
                S::from_i32(n[0] as i32) * unit,
                S::from_i32(n[1] as i32) * unit,
                S::from_i32(n[2] as i32) * unit,
            );
            rot.mul_vec3(v).try_normalize()
        }
        None => face,
    }
}

/// The intensities at the three vertices of a Gouraud triangle.
#[cfg(feature = "raycast")]
pub(crate) fn vertex_intensities<S: Scalar>(
    mesh: &MeshData<'_>,
    rot: &Mat3<S>,
    light: &PreparedLight<S>,
    tri: [u16; 3],
) -> [S; 3] {
    let face = face_normal(mesh, rot, tri);
    tri.map(|k| vertex_normal(mesh, rot, k, face).map_or(S::ZERO, |n| light.intensity(n)))
}

/// The texture coordinates of vertex `k` in texels.
#[cfg(feature = "raycast")]
pub(crate) fn uv<S: Scalar>(mesh: &MeshData<'_>, k: u16) -> (S, S) {
    let t = mesh
        .uvs
        .and_then(|u| u.get(k as usize))
        .copied()
        .unwrap_or([0; 2]);
    (S::from_i32(t[0] as i32), S::from_i32(t[1] as i32))
}

/// A texel coordinate → integer texel: 16.16, then the integer part
/// (floor), as the texture stage's coordinates are read.
#[cfg(feature = "raycast")]
pub(crate) fn texel<S: Scalar>(u: S) -> i32 {
    match u.to_subpixel(16) {
        Some(v) => v >> 16,
        None => 0,
    }
}

//! The prepared form of a scene: meshes in the render scalar, with their
//! normals computed once, placed as objects with a material and a cull
//! mode. Everything here is done once, not per frame; the per-frame work
//! is in [`Renderer`](super::Renderer).
//!
//! All storage is the caller's: [`MeshData::prepare`] writes into slices
//! the caller owns (a `Vec` on a host, a `static` array on a firmware), and
//! [`PreparedMesh::new`] borrows slices that may just as well be `const`
//! data in flash.

use super::material::{NormalLight, face_cross, face_direction};
use super::{Color, Material, MeshData, Scene, SceneError};
use crate::math::{Affine3, Vec3};
use crate::pipeline::Cull;
use crate::scalar::Scalar;
use crate::transform::{Euler, Pose};
use core::fmt;

/// Why a mesh cannot be prepared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// A triangle names a vertex beyond the positions.
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
    },
    /// Normals or texture coordinates are not one per position, or face
    /// normals not one per triangle.
    AttributeCount,
    /// A position or normal is NaN or ±∞, or the mesh scale is zero or not
    /// finite.
    NonFinite {
        /// The vertex (or, for a bad scale, 0).
        vertex: usize,
    },
    /// A storage slice is shorter than the mesh needs.
    Storage {
        /// Elements needed.
        needed: usize,
        /// Elements given.
        given: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IndexOutOfRange { triangle } => {
                write!(
                    f,
                    "triangle {triangle} has a vertex index beyond the positions"
                )
            }
            Self::AttributeCount => f.write_str(
                "normals or uvs must have one entry per position (face normals one per triangle)",
            ),
            Self::NonFinite { vertex } => {
                write!(
                    f,
                    "vertex {vertex} (or the mesh scale) is NaN, infinite or zero"
                )
            }
            Self::Storage { needed, given } => {
                write!(f, "storage holds {given} entries, the mesh needs {needed}")
            }
        }
    }
}

impl core::error::Error for MeshError {}

/// A triangle mesh in the render scalar `S`: object-space positions, unit
/// face normals (for flat shading), unit vertex normals (for Gouraud) and
/// texture coordinates in texels, all borrowed.
///
/// Build one with [`MeshData::prepare`] from quantized data, or with
/// [`PreparedMesh::new`] from positions and normals you computed (for
/// example `const` data for a firmware, so that no `f32` code runs on an
/// FPU-less core).
///
/// # Guarantees
/// A `PreparedMesh` has passed [`PreparedMesh::new`]'s checks: every index
/// is in range and every attribute slice is either empty or of the right
/// length. The renderers rely on that and never panic on it.
#[derive(Clone, Copy, Debug)]
pub struct PreparedMesh<'a, S> {
    positions: &'a [Vec3<S>],
    triangles: &'a [[u16; 3]],
    face_normals: &'a [Vec3<S>],
    vertex_normals: &'a [Vec3<S>],
    uvs: &'a [[i16; 2]],
    closed: bool,
}

impl<S: Scalar> PreparedMesh<'_, S> {
    /// An empty mesh (draws nothing), to initialize object storage.
    pub const EMPTY: Self = PreparedMesh {
        positions: &[],
        triangles: &[],
        face_normals: &[],
        vertex_normals: &[],
        uvs: &[],
        closed: false,
    };
}

impl<'a, S: Scalar> PreparedMesh<'a, S> {
    /// A mesh from its parts. `face_normals` is empty or one per triangle,
    /// `vertex_normals` and `uvs` empty or one per position. `closed`
    /// says that every edge is shared by two triangles of opposite
    /// winding (a closed, consistently oriented surface): objects of such
    /// a mesh cull back faces by default.
    ///
    /// # Errors
    /// [`MeshError::IndexOutOfRange`], [`MeshError::AttributeCount`],
    /// [`MeshError::NonFinite`].
    pub fn new(
        positions: &'a [Vec3<S>],
        triangles: &'a [[u16; 3]],
        face_normals: &'a [Vec3<S>],
        vertex_normals: &'a [Vec3<S>],
        uvs: &'a [[i16; 2]],
        closed: bool,
    ) -> Result<Self, MeshError> {
        let n = positions.len();
        check_indices(triangles, n)?;
        let count_ok = |len: usize, want: usize| len == 0 || len == want;
        if !(count_ok(face_normals.len(), triangles.len())
            && count_ok(vertex_normals.len(), n)
            && count_ok(uvs.len(), n))
        {
            return Err(MeshError::AttributeCount);
        }
        for (k, p) in positions.iter().enumerate() {
            let normal_ok = vertex_normals.get(k).is_none_or(|v| v.is_finite());
            if !(p.is_finite() && normal_ok) {
                return Err(MeshError::NonFinite { vertex: k });
            }
        }
        if let Some(t) = face_normals.iter().position(|v| !v.is_finite()) {
            let vertex = triangles.get(t).map_or(0, |tri| tri[0] as usize);
            return Err(MeshError::NonFinite { vertex });
        }
        Ok(Self {
            positions,
            triangles,
            face_normals,
            vertex_normals,
            uvs,
            closed,
        })
    }

    /// Object-space positions.
    #[must_use]
    pub fn positions(&self) -> &'a [Vec3<S>] {
        self.positions
    }
    /// Vertex indices of each triangle (counter-clockwise seen from the
    /// front).
    #[must_use]
    pub fn triangles(&self) -> &'a [[u16; 3]] {
        self.triangles
    }
    /// Unit face normals, one per triangle, or empty.
    #[must_use]
    pub fn face_normals(&self) -> &'a [Vec3<S>] {
        self.face_normals
    }
    /// Unit vertex normals, one per position, or empty.
    #[must_use]
    pub fn vertex_normals(&self) -> &'a [Vec3<S>] {
        self.vertex_normals
    }
    /// Texture coordinates in texels, one per position, or empty.
    #[must_use]
    pub fn uvs(&self) -> &'a [[i16; 2]] {
        self.uvs
    }
    /// Whether the mesh is a closed, consistently oriented surface.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }
}

/// FNV-1a over a mesh's vertex indices (each `u16` little-endian, in
/// order): a fingerprint of its triangles. `const`, so code generated by
/// `scene::export` (feature `export`) compares it at compile time with the
/// scene it reads the triangles from; evaluated there, it costs the
/// firmware no code.
#[must_use]
pub const fn triangle_hash(triangles: &[[u16; 3]]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut t = 0;
    while t < triangles.len() {
        let mut k = 0;
        while k < 3 {
            let [lo, hi] = triangles[t][k].to_le_bytes();
            h = (h ^ lo as u64).wrapping_mul(0x0000_0100_0000_01b3);
            h = (h ^ hi as u64).wrapping_mul(0x0000_0100_0000_01b3);
            k += 1;
        }
        t += 1;
    }
    h
}

fn check_indices(triangles: &[[u16; 3]], n: usize) -> Result<(), MeshError> {
    match triangles
        .iter()
        .position(|t| t.iter().any(|&k| k as usize >= n))
    {
        Some(triangle) => Err(MeshError::IndexOutOfRange { triangle }),
        None => Ok(()),
    }
}

/// What [`MeshData::prepare`] computes: which normals the material needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Normals {
    /// None (textures).
    None,
    /// Face normals (flat shading).
    Face,
    /// Vertex normals (Gouraud): the mesh's own, or else the normalized
    /// area-weighted sum of the face normals at each vertex.
    Vertex,
}

impl Normals {
    /// What `material` needs.
    #[must_use]
    pub fn for_material(material: &Material<'_>) -> Self {
        match material {
            Material::Flat(_) => Self::Face,
            Material::Gouraud(_) => Self::Vertex,
            Material::Texture { .. } => Self::None,
        }
    }
}

/// Storage [`MeshData::prepare`] needs, in `Vec3` elements.
#[must_use]
pub const fn storage_len(mesh: &MeshData<'_>, normals: Normals) -> usize {
    let n = mesh.positions.len();
    n + match normals {
        Normals::None => 0,
        Normals::Face => mesh.triangles.len(),
        Normals::Vertex => n,
    }
}

impl MeshData<'_> {
    /// Prepares the mesh into `storage` (at least [`storage_len`] long):
    /// positions `positions[k]·scale` in `S`, then the normals `normals`
    /// asks for. A mirrored mesh (negative scale) is prepared as open, so
    /// it is drawn from both sides. Face normals come from the exact integer cross product of
    /// the quantized positions (so small triangles keep their normal in
    /// fixed point); a negative scale flips them. Degenerate triangles get
    /// a zero normal (they are lit by the ambient term only and cover no
    /// pixel).
    ///
    /// # Errors
    /// [`MeshError::Storage`] if `storage` is too short; the checks of
    /// [`PreparedMesh::new`].
    pub fn prepare<'s, S: Scalar>(
        &'s self,
        normals: Normals,
        storage: &'s mut [Vec3<S>],
    ) -> Result<PreparedMesh<'s, S>, MeshError> {
        let n = self.positions.len();
        let t = self.triangles.len();
        let needed = storage_len(self, normals);
        if storage.len() < needed {
            return Err(MeshError::Storage {
                needed,
                given: storage.len(),
            });
        }
        if !(self.scale.is_finite() && self.scale != 0.0) {
            return Err(MeshError::NonFinite { vertex: 0 });
        }
        check_indices(self.triangles, n)?;
        if self.normals.is_some_and(|v| v.len() != n) || self.uvs.is_some_and(|v| v.len() != n) {
            return Err(MeshError::AttributeCount);
        }
        let (pos, rest) = storage.split_at_mut(n);
        let scale = S::from_f32(self.scale);
        for (out, p) in pos.iter_mut().zip(self.positions) {
            *out = Vec3::new(
                S::from_i32(p[0] as i32) * scale,
                S::from_i32(p[1] as i32) * scale,
                S::from_i32(p[2] as i32) * scale,
            );
        }
        let flip = self.scale < 0.0;
        let (faces, verts): (&[Vec3<S>], &[Vec3<S>]) = match normals {
            Normals::None => (&[], &[]),
            Normals::Face => {
                let faces = &mut rest[..t];
                self.face_normals_into(faces);
                (&*faces, &[])
            }
            Normals::Vertex => {
                let verts = &mut rest[..n];
                match self.normals {
                    Some(src) => {
                        let unit = S::from_f32(1.0 / 32767.0);
                        for (out, v) in verts.iter_mut().zip(src) {
                            *out = Vec3::new(
                                S::from_i32(v[0] as i32) * unit,
                                S::from_i32(v[1] as i32) * unit,
                                S::from_i32(v[2] as i32) * unit,
                            )
                            .try_normalize()
                            .unwrap_or(Vec3::ZERO);
                        }
                    }
                    None => self.area_weighted_normals(verts, flip),
                }
                (&[], &*verts)
            }
        };
        PreparedMesh::new(
            pos,
            self.triangles,
            faces,
            verts,
            self.uvs.unwrap_or(&[]),
            // A negative scale mirrors the mesh and flips its winding on
            // screen: culling its "back" faces would drop the front ones.
            self.closed && !flip,
        )
    }

    /// Unit face normals in `S`, one per triangle, into `out` (pairwise;
    /// extra entries of `out` are left alone): the exact integer cross
    /// product of the quantized positions, normalized, flipped for a
    /// negative scale, zero for a degenerate triangle.
    pub fn face_normals_into<S: Scalar>(&self, out: &mut [Vec3<S>]) {
        let flip = self.scale < 0.0;
        for (o, &tri) in out.iter_mut().zip(self.triangles) {
            *o = face_direction::<S>(self.positions, tri, flip)
                .and_then(Vec3::try_normalize)
                .unwrap_or(Vec3::ZERO);
        }
    }

    /// Vertex normals as the normalized sum of the exact face cross
    /// products at each vertex (area weighting), accumulated in `S` after
    /// scaling every cross product by the largest one, so the sum cannot
    /// overflow a fixed-point format while each vertex has fewer than
    /// 2^14 triangles.
    fn area_weighted_normals<S: Scalar>(&self, out: &mut [Vec3<S>], flip: bool) {
        for v in out.iter_mut() {
            *v = Vec3::ZERO;
        }
        let cross = |tri: [u16; 3]| face_cross(self.positions, tri);
        let m = self
            .triangles
            .iter()
            .flat_map(|&t| cross(t))
            .map(i64::abs)
            .max()
            .unwrap_or(0);
        if m == 0 {
            return;
        }
        let sign = if flip { -1 } else { 1 };
        let unit = S::from_f32(1.0 / 16384.0);
        for &tri in self.triangles {
            let c = cross(tri).map(|v| {
                S::from_i32(crate::scalar::div_rem_i64(sign * (v << 14), m).0 as i32) * unit
            });
            let d = Vec3::new(c[0], c[1], c[2]);
            for &k in &tri {
                if let Some(v) = out.get_mut(k as usize) {
                    *v += d;
                }
            }
        }
        for v in out.iter_mut() {
            *v = v.try_normalize().unwrap_or(Vec3::ZERO);
        }
    }
}

/// Per-frame state of an object, written by
/// [`Renderer::project`](super::Renderer::project).
#[derive(Clone, Copy, Debug)]
pub(super) struct ObjectFrame<S> {
    /// Object→view.
    pub(super) to_view: Affine3<S>,
    /// The light with its direction turned into object space (so the
    /// prepared object-space normals are used as they are).
    pub(super) light: NormalLight<S>,
    /// Index of the object's first vertex in the frame's scratch.
    pub(super) first: usize,
}

/// A prepared mesh placed in the world with a material: what the renderer
/// draws. The pose may change every frame.
#[derive(Clone, Copy, Debug)]
pub struct PreparedObject<'a, S> {
    /// The shape.
    pub mesh: PreparedMesh<'a, S>,
    /// Where it is (object→world); change it between frames.
    pub pose: Pose<S>,
    /// How it looks.
    pub material: Material<'a>,
    /// Which faces are dropped before any set-up: [`Cull::Back`] by
    /// default for closed meshes, [`Cull::None`] otherwise.
    pub cull: Cull,
    pub(super) frame: Option<ObjectFrame<S>>,
}

impl<S: Scalar> PreparedObject<'_, S> {
    /// An object that draws nothing, to initialize object storage.
    pub const EMPTY: Self = PreparedObject {
        mesh: PreparedMesh::EMPTY,
        pose: Pose::new(Vec3::ZERO, Euler::ZERO),
        material: Material::Flat(Color::new(0, 0, 0)),
        cull: Cull::None,
        frame: None,
    };
}

impl<'a, S: Scalar> PreparedObject<'a, S> {
    /// `mesh` at `pose` with `material`, culling back faces if the mesh is
    /// closed.
    ///
    /// # Errors
    /// [`SceneError::MissingNormals`] when a flat material has no face
    /// normals or a Gouraud one no vertex normals;
    /// [`SceneError::MissingUv`] for a texture without texture
    /// coordinates; [`SceneError::FeatureDisabled`] when the material's
    /// stage is compiled out; [`SceneError::BadPose`] for a non-finite
    /// pose. The object index in the errors is 0: [`Scene::prepare`] fills
    /// in the real one.
    pub fn new(
        mesh: PreparedMesh<'a, S>,
        pose: Pose<S>,
        material: Material<'a>,
    ) -> Result<Self, SceneError> {
        check_material(&mesh, &material, 0)?;
        let p = &pose;
        let finite = p.origin.is_finite()
            && p.angles.roll.is_finite()
            && p.angles.pitch.is_finite()
            && p.angles.yaw.is_finite();
        if !finite {
            return Err(SceneError::BadPose { object: 0 });
        }
        Ok(Self {
            mesh,
            pose,
            material,
            cull: if mesh.closed { Cull::Back } else { Cull::None },
            frame: None,
        })
    }
}

/// The stage a material needs, if this build leaves it out.
pub(super) fn missing_feature(material: &Material<'_>) -> Option<&'static str> {
    match material {
        Material::Flat(_) => None,
        Material::Gouraud(_) => (!cfg!(feature = "gouraud")).then_some("gouraud"),
        Material::Texture { mode, .. } => {
            if !cfg!(feature = "texture") {
                Some("texture")
            } else if !cfg!(feature = "perspective") && *mode != super::TextureMode::Affine {
                Some("perspective")
            } else {
                None
            }
        }
    }
}

fn check_material<S: Scalar>(
    mesh: &PreparedMesh<'_, S>,
    material: &Material<'_>,
    object: usize,
) -> Result<(), SceneError> {
    if let Some(feature) = missing_feature(material) {
        return Err(SceneError::FeatureDisabled { feature });
    }
    let has_faces = mesh.triangles.is_empty() || !mesh.face_normals.is_empty();
    let has_verts = mesh.positions.is_empty() || !mesh.vertex_normals.is_empty();
    match material {
        Material::Flat(_) if !has_faces => Err(SceneError::MissingNormals { object }),
        Material::Gouraud(_) if !has_verts => Err(SceneError::MissingNormals { object }),
        Material::Texture { .. } if mesh.uvs.is_empty() && !mesh.positions.is_empty() => {
            Err(SceneError::MissingUv { object })
        }
        _ => Ok(()),
    }
}

/// How much storage [`Scene::prepare`] needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Storage {
    /// `Vec3` elements for positions and normals.
    pub vec3s: usize,
    /// Objects.
    pub objects: usize,
    /// Scratch vertices for one frame
    /// ([`Renderer::project`](super::Renderer::project)).
    pub vertices: usize,
}

impl Storage {
    /// Field by field, the larger of the two: storage that fits either.
    #[must_use]
    pub const fn max(self, other: Self) -> Self {
        const fn m(a: usize, b: usize) -> usize {
            if a > b { a } else { b }
        }
        Self {
            vec3s: m(self.vec3s, other.vec3s),
            objects: m(self.objects, other.objects),
            vertices: m(self.vertices, other.vertices),
        }
    }

    /// Storage that fits any one of `scenes` (prepared one at a time into
    /// the same buffers), for sizing `static` arrays at compile time.
    #[must_use]
    pub const fn for_any(scenes: &[&Scene<'_>]) -> Self {
        let mut s = Self {
            vec3s: 0,
            objects: 0,
            vertices: 0,
        };
        let mut i = 0;
        while i < scenes.len() {
            s = s.max(scenes[i].storage());
            i += 1;
        }
        s
    }
}

impl Scene<'_> {
    /// The storage [`Self::prepare`] and a frame of this scene need.
    #[must_use]
    pub const fn storage(&self) -> Storage {
        let mut s = Storage {
            vec3s: 0,
            objects: self.objects.len(),
            vertices: 0,
        };
        let mut i = 0;
        while i < self.objects.len() {
            let o = &self.objects[i];
            let normals = match o.material {
                Material::Flat(_) => Normals::Face,
                Material::Gouraud(_) => Normals::Vertex,
                Material::Texture { .. } => Normals::None,
            };
            s.vec3s += storage_len(o.mesh, normals);
            s.vertices += o.mesh.positions.len();
            i += 1;
        }
        s
    }

    /// Prepares every object of the scene into caller storage: meshes into
    /// `vec3s` (with the normals each material needs), objects into
    /// `objects`, both at least as long as [`Self::storage`] says. Returns
    /// the prepared objects (a prefix of `objects`).
    ///
    /// # Errors
    /// [`SceneError::Storage`] if a slice is too short; any error of
    /// [`MeshData::prepare`] (as [`SceneError::Mesh`]) or
    /// [`PreparedObject::new`], naming the object.
    pub fn prepare<'s, S: Scalar>(
        &'s self,
        vec3s: &'s mut [Vec3<S>],
        objects: &'s mut [PreparedObject<'s, S>],
    ) -> Result<&'s mut [PreparedObject<'s, S>], SceneError> {
        self.validate()?;
        let need = self.storage();
        if vec3s.len() < need.vec3s || objects.len() < need.objects {
            return Err(SceneError::Storage);
        }
        let mut rest = vec3s;
        for (o, (src, out)) in self.objects.iter().zip(objects.iter_mut()).enumerate() {
            let normals = Normals::for_material(&src.material);
            let (mine, tail) = rest.split_at_mut(storage_len(src.mesh, normals));
            rest = tail;
            let mesh = src
                .mesh
                .prepare(normals, mine)
                .map_err(|error| SceneError::Mesh { object: o, error })?;
            let pose = super::material::pose::<S>(&src.pose);
            *out = PreparedObject::new(mesh, pose, src.material).map_err(|e| e.at_object(o))?;
        }
        Ok(&mut objects[..need.objects])
    }
}

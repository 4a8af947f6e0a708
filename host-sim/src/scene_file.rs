//! Scene files (RON): meshes from OBJ files, PNG textures, a camera in any
//! form, objects with poses and materials, a light and spheres.
//!
//! Errors carry the file, line and column they refer to and what was
//! expected; see `docs/sim.md` for the format.

use crate::image::read_png_rgb8;
use serde::Deserialize;
use sightline::math::Vec3;
use sightline::scene::{
    self, CameraSpec, Color, Light, Material, MeshData, ProjectionSpec, Scene, SceneObject,
    SceneSphere, TextureData, TextureMode,
};
use sightline::transform::{Euler, Pose};
use std::fmt;
use std::path::{Path, PathBuf};

/// An error in a scene file or a file it references, with its location.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    /// The file the error is in.
    pub file: PathBuf,
    /// 1-based line (0 when unknown).
    pub line: usize,
    /// 1-based column (0 when unknown).
    pub col: usize,
    /// What is wrong and what was expected.
    pub message: String,
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file.display(),
            self.line,
            self.col,
            self.message
        )
    }
}

impl std::error::Error for FileError {}

/// `[r, g, b]` in 0..=255.
type Rgb = [u8; 3];

fn color(c: Rgb) -> Color {
    Color::new(c[0] >> 3, c[1] >> 2, c[2] >> 3)
}

/// The camera forms of a scene file.
#[derive(Clone, Debug, Deserialize)]
pub enum CameraDef {
    /// Position and roll, pitch, yaw (radians).
    Angles {
        /// Eye position.
        position: [f32; 3],
        /// (roll, pitch, yaw) in radians.
        angles: [f32; 3],
    },
    /// Orthonormal right, down, forward.
    Orthonormal {
        /// Eye position.
        position: [f32; 3],
        /// Screen right.
        right: [f32; 3],
        /// Screen down.
        down: [f32; 3],
        /// View direction.
        forward: [f32; 3],
    },
    /// General vectors, solved by Gaussian elimination.
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
    /// Eye, target, up.
    LookAt {
        /// Eye.
        eye: [f32; 3],
        /// Target.
        target: [f32; 3],
        /// Up.
        up: [f32; 3],
    },
}

/// A projection.
#[derive(Clone, Debug, Deserialize)]
pub enum ProjectionDef {
    /// Horizontal field of view in degrees.
    Perspective {
        /// Degrees.
        fov_x_degrees: f32,
    },
    /// World units across the image (raster only).
    Parallel {
        /// World units across.
        width: f32,
    },
}

/// Raster texture mapping mode.
#[derive(Clone, Copy, Debug, Deserialize)]
pub enum ModeDef {
    /// Linear in screen space.
    Affine,
    /// Perspective-correct.
    Perspective,
    /// Chosen per triangle.
    Auto,
}

/// A material.
#[derive(Clone, Debug, Deserialize)]
pub enum MaterialDef {
    /// Flat colour.
    Flat(Rgb),
    /// Gouraud colour.
    Gouraud(Rgb),
    /// A PNG texture (sides powers of two) and a mode.
    Texture {
        /// PNG file, relative to the scene file.
        file: String,
        /// Mapping mode.
        #[serde(default = "default_mode")]
        mode: ModeDef,
    },
}

fn default_mode() -> ModeDef {
    ModeDef::Perspective
}

/// An object.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDef {
    /// OBJ file relative to the scene file, or `builtin:cube`,
    /// `builtin:floor`, `builtin:bunny`.
    pub mesh: String,
    /// Origin in world coordinates.
    #[serde(default)]
    pub position: [f32; 3],
    /// (roll, pitch, yaw) in radians.
    #[serde(default)]
    pub angles: [f32; 3],
    /// Uniform scale applied to the OBJ coordinates.
    #[serde(default = "one")]
    pub scale: f32,
    /// Appearance.
    pub material: MaterialDef,
}

fn one() -> f32 {
    1.0
}

/// The light.
#[derive(Clone, Debug, Deserialize)]
pub struct LightDef {
    /// Direction towards the light.
    pub direction: [f32; 3],
    /// Ambient intensity.
    #[serde(default)]
    pub ambient: f32,
    /// Diffuse intensity.
    #[serde(default = "one")]
    pub diffuse: f32,
}

/// A sphere.
#[derive(Clone, Debug, Deserialize)]
pub struct SphereDef {
    /// Centre.
    pub centre: [f32; 3],
    /// Radius.
    pub radius: f32,
    /// Colour.
    pub color: Rgb,
}

/// A whole scene file.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "Scene", deny_unknown_fields)]
pub struct SceneDef {
    /// Name.
    pub name: String,
    /// Description.
    #[serde(default)]
    pub description: String,
    /// Camera.
    pub camera: CameraDef,
    /// Projection.
    pub projection: ProjectionDef,
    /// Near distance.
    #[serde(default = "default_near")]
    pub near: f32,
    /// Far distance.
    #[serde(default = "default_far")]
    pub far: f32,
    /// Light.
    pub light: LightDef,
    /// Background colour.
    #[serde(default)]
    pub background: Rgb,
    /// Objects.
    #[serde(default)]
    pub objects: Vec<ObjectDef>,
    /// Spheres.
    #[serde(default)]
    pub spheres: Vec<SphereDef>,
}

fn default_near() -> f32 {
    0.1
}
fn default_far() -> f32 {
    100.0
}

/// An owned mesh in core's quantised form.
#[derive(Clone, Debug, Default)]
pub struct OwnedMesh {
    /// Quantised positions.
    pub positions: Vec<[i16; 3]>,
    /// World units per step.
    pub scale: f32,
    /// Triangles.
    pub triangles: Vec<[u16; 3]>,
    /// Vertex normals (1/32767).
    pub normals: Option<Vec<[i16; 3]>>,
    /// Texture coordinates in [0, 1] (OBJ convention, v up), converted to
    /// texels once the texture size is known.
    pub texcoords: Option<Vec<[f32; 2]>>,
    /// Every edge is used once in each direction: a closed, consistently
    /// oriented surface (its back faces are culled).
    pub closed: bool,
}

/// Whether every directed edge `(a, b)` of `tris` appears exactly once and
/// its reverse `(b, a)` too: the mesh is closed and consistently wound.
#[must_use]
pub fn is_closed(tris: &[[u16; 3]]) -> bool {
    let mut edges = std::collections::HashMap::with_capacity(tris.len() * 3);
    for t in tris {
        for i in 0..3 {
            let e = (t[i], t[(i + 1) % 3]);
            if e.0 == e.1 || edges.insert(e, ()).is_some() {
                return false;
            }
        }
    }
    !tris.is_empty() && edges.keys().all(|&(a, b)| edges.contains_key(&(b, a)))
}

enum MeshSource {
    Builtin(&'static MeshData<'static>),
    Owned(OwnedMesh),
}

struct LoadedObject {
    mesh: MeshSource,
    uvs: Option<Vec<[i16; 2]>>,
    texture: Option<(Vec<Color>, u16, u16, TextureMode)>,
    def: ObjectDef,
}

/// A scene file loaded with everything it references.
pub struct LoadedScene {
    def: SceneDef,
    objects: Vec<LoadedObject>,
    /// The scene file.
    pub path: PathBuf,
}

impl fmt::Debug for LoadedScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("LoadedScene")
            .field("path", &self.path)
            .field("name", &self.def.name)
            .finish()
    }
}

/// 1-based (line, column) of byte offset `at` in `text`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Where `needle` first occurs in `text` (1-based), or (0, 0).
fn locate(text: &str, needle: &str) -> (usize, usize) {
    text.find(needle).map_or((0, 0), |at| line_col(text, at))
}

/// Loads a scene file and everything it references.
///
/// # Errors
/// [`FileError`] naming the scene file (syntax, unknown fields, a missing
/// mesh or texture file, a non-power-of-two texture, a singular camera)
/// or the referenced file (a bad OBJ index).
pub fn load(path: &Path) -> Result<LoadedScene, FileError> {
    let text = std::fs::read_to_string(path).map_err(|e| FileError {
        file: path.to_path_buf(),
        line: 0,
        col: 0,
        message: format!("cannot read scene file: {e}"),
    })?;
    parse(&text, path)
}

/// Parses scene-file `text` as if read from `path` (which names the file
/// in errors, and whose directory holds the referenced mesh and texture
/// files), loading everything it references.
///
/// # Errors
/// As [`load`], apart from reading the scene file itself. Never panics,
/// whatever the text (checked by the `scene_file` fuzz target).
pub fn parse(text: &str, path: &Path) -> Result<LoadedScene, FileError> {
    let def: SceneDef = ron::from_str(text).map_err(|e| FileError {
        file: path.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: format!("{} (expected a scene as described in docs/sim.md)", e.code),
    })?;
    let here = |needle: &str, message: String| {
        let (line, col) = locate(text, needle);
        FileError {
            file: path.to_path_buf(),
            line,
            col,
            message,
        }
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let mut objects = Vec::new();
    for o in &def.objects {
        let quoted = format!("\"{}\"", o.mesh);
        let mesh = match o.mesh.as_str() {
            "builtin:cube" => MeshSource::Builtin(&scene::builtin::CUBE_MESH),
            "builtin:floor" => MeshSource::Builtin(&scene::builtin::FLOOR_MESH),
            "builtin:bunny" => MeshSource::Builtin(&scene::builtin::BUNNY_MESH),
            name if name.starts_with("builtin:") => {
                return Err(here(
                    &quoted,
                    format!(
                        "unknown built-in mesh {name:?}: expected builtin:cube, builtin:floor or builtin:bunny"
                    ),
                ));
            }
            file => {
                let p = dir.join(file);
                if !p.is_file() {
                    return Err(here(
                        &quoted,
                        format!(
                            "mesh file {} not found (expected an OBJ file, relative to the scene file)",
                            p.display()
                        ),
                    ));
                }
                MeshSource::Owned(load_obj(&p, o.scale)?)
            }
        };
        let mut texture = None;
        let mut uvs = None;
        if let MaterialDef::Texture { file, mode } = &o.material {
            let quoted_t = format!("\"{file}\"");
            let p = dir.join(file);
            if !p.is_file() {
                return Err(here(
                    &quoted_t,
                    format!("texture file {} not found (expected a PNG)", p.display()),
                ));
            }
            let img = read_png_rgb8(&p).map_err(|m| here(&quoted_t, m))?;
            let (w, h) = (img.width, img.height);
            if !(w.is_power_of_two() && h.is_power_of_two() && w <= 32768 && h <= 32768) {
                return Err(here(
                    &quoted_t,
                    format!(
                        "texture {} is {w}x{h}: expected both sides to be powers of two (e.g. 64x64)",
                        p.display()
                    ),
                ));
            }
            let texels = img
                .rgb
                .chunks_exact(3)
                .map(|c| color([c[0], c[1], c[2]]))
                .collect();
            let tc = match &mesh {
                MeshSource::Owned(m) => m.texcoords.clone(),
                MeshSource::Builtin(_) => None,
            };
            let Some(tc) = tc else {
                return Err(here(
                    &quoted,
                    "a textured mesh needs texture coordinates (`vt` lines in the OBJ file)"
                        .to_string(),
                ));
            };
            uvs = Some(
                tc.iter()
                    .map(|t| {
                        let u = (t[0] * w as f32).round().clamp(-32768.0, 32767.0) as i16;
                        let v = ((1.0 - t[1]) * h as f32).round().clamp(-32768.0, 32767.0) as i16;
                        [u, v]
                    })
                    .collect(),
            );
            let mode = match mode {
                ModeDef::Affine => TextureMode::Affine,
                ModeDef::Perspective => TextureMode::Perspective,
                ModeDef::Auto => TextureMode::Auto,
            };
            texture = Some((texels, w as u16, h as u16, mode));
        }
        objects.push(LoadedObject {
            mesh,
            uvs,
            texture,
            def: o.clone(),
        });
    }
    let loaded = LoadedScene {
        def,
        objects,
        path: path.to_path_buf(),
    };
    // Check the camera now, so that a singular camera is reported with
    // its place in the file.
    let spec = loaded.camera_spec();
    if let Err(e) = spec.build::<f32>() {
        let token = match loaded.def.camera {
            CameraDef::Angles { .. } => "Angles",
            CameraDef::Orthonormal { .. } => "Orthonormal",
            CameraDef::Vectors { .. } => "Vectors",
            CameraDef::LookAt { .. } => "LookAt",
        };
        let expected = match loaded.def.camera {
            CameraDef::Vectors { .. } => "expected three linearly independent vectors u, v, w",
            CameraDef::Orthonormal { .. } => {
                "expected unit, mutually perpendicular, right-handed right/down/forward"
            }
            _ => "expected eye != target and up not parallel to the view",
        };
        return Err(here(token, format!("camera: {e}; {expected}")));
    }
    Ok(loaded)
}

/// Checks the face indices of an OBJ text, so that a bad index is reported
/// with its line and column (tobj reports neither).
fn check_obj_indices(path: &Path, text: &str) -> Result<(), FileError> {
    let (mut nv, mut nt, mut nn) = (0i64, 0i64, 0i64);
    for (ln, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => nv += 1,
            Some("vt") => nt += 1,
            Some("vn") => nn += 1,
            Some("f") => {
                let mut offset = line.find('f').unwrap_or(0) + 1;
                for w in line[offset..].split_whitespace() {
                    let col = line[offset..].find(w).map_or(offset, |p| offset + p);
                    offset = col + w.len();
                    for (k, part) in w.split('/').enumerate() {
                        if part.is_empty() {
                            continue;
                        }
                        let count = [nv, nt, nn][k.min(2)];
                        let kind = ["vertex", "texture coordinate", "normal"][k.min(2)];
                        let ok = part
                            .parse::<i64>()
                            .is_ok_and(|i| (i > 0 && i <= count) || (i < 0 && -i <= count));
                        if !ok {
                            return Err(FileError {
                                file: path.to_path_buf(),
                                line: ln + 1,
                                col: col + 1,
                                message: format!(
                                    "bad face index {part:?}: expected a {kind} index in 1..={count} (or -1..=-{count})"
                                ),
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Loads an OBJ file into core's quantised form, with `scale` applied.
///
/// # Errors
/// [`FileError`] naming the OBJ file.
pub fn load_obj(path: &Path, scale: f32) -> Result<OwnedMesh, FileError> {
    let err = |line, col, message: String| FileError {
        file: path.to_path_buf(),
        line,
        col,
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| err(0, 0, format!("cannot read: {e}")))?;
    check_obj_indices(path, &text)?;
    let opts = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ..Default::default()
    };
    let (models, _materials) =
        tobj::load_obj(path, &opts).map_err(|e| err(0, 0, format!("not a valid OBJ file: {e}")))?;
    let mut pos: Vec<[f32; 3]> = Vec::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut tcs: Vec<[f32; 2]> = Vec::new();
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let all_normals = models.iter().all(|m| !m.mesh.normals.is_empty());
    let all_tc = models.iter().all(|m| !m.mesh.texcoords.is_empty());
    for m in &models {
        let base = pos.len() as u32;
        let mesh = &m.mesh;
        pos.extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if all_normals {
            normals.extend(mesh.normals.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        }
        if all_tc {
            tcs.extend(mesh.texcoords.chunks_exact(2).map(|p| [p[0], p[1]]));
        }
        tris.extend(
            mesh.indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    if pos.is_empty() || tris.is_empty() {
        return Err(err(0, 0, "expected at least one face".to_string()));
    }
    if pos.len() > 65536 {
        return Err(err(
            0,
            0,
            format!(
                "{} vertices: expected at most 65536 (u16 indices)",
                pos.len()
            ),
        ));
    }
    let m = pos
        .iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0f32, f32::max);
    if !(m.is_finite() && m > 0.0 && scale.is_finite() && scale != 0.0) {
        return Err(err(
            0,
            0,
            "expected finite, non-zero coordinates and scale".into(),
        ));
    }
    // 30 000 steps for the largest coordinate: inside i16, exact in I16F16.
    let step = m / 30000.0;
    let positions: Vec<[i16; 3]> = pos
        .iter()
        .map(|p| p.map(|c| (c / step).round() as i16))
        .collect();
    let triangles: Vec<[u16; 3]> = tris.iter().map(|t| t.map(|k| k as u16)).collect();
    let normals = if all_normals && normals.len() == pos.len() {
        normals
    } else {
        area_weighted_normals(&positions, &triangles)
    };
    let normals = normals
        .iter()
        .map(|n| {
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let l = if l > 0.0 { l } else { 1.0 };
            n.map(|c| (c / l * 32767.0).round() as i16)
        })
        .collect();
    Ok(OwnedMesh {
        positions,
        scale: step * scale,
        closed: is_closed(&triangles),
        triangles,
        normals: Some(normals),
        texcoords: (all_tc && tcs.len() == pos.len()).then_some(tcs),
    })
}

fn area_weighted_normals(p: &[[i16; 3]], tris: &[[u16; 3]]) -> Vec<[f32; 3]> {
    let mut n = vec![[0f32; 3]; p.len()];
    for t in tris {
        let v = t.map(|k| p[k as usize].map(f32::from));
        let e1 = [v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]];
        let e2 = [v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]];
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        for &k in t {
            for i in 0..3 {
                n[k as usize][i] += c[i];
            }
        }
    }
    n
}

impl LoadedScene {
    /// The scene's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.def.name
    }

    fn camera_spec(&self) -> CameraSpec {
        match self.def.camera.clone() {
            CameraDef::Angles { position, angles } => CameraSpec::Angles { position, angles },
            CameraDef::Orthonormal {
                position,
                right,
                down,
                forward,
            } => CameraSpec::Orthonormal {
                position,
                right,
                down,
                forward,
            },
            CameraDef::Vectors { position, u, v, w } => CameraSpec::Vectors { position, u, v, w },
            CameraDef::LookAt { eye, target, up } => CameraSpec::LookAt { eye, target, up },
        }
    }

    /// Calls `f` with the core scene borrowing this data.
    pub fn with_scene<R>(&self, f: impl FnOnce(&Scene<'_>) -> R) -> R {
        let meshes: Vec<MeshData<'_>> = self
            .objects
            .iter()
            .map(|o| {
                let base = match &o.mesh {
                    MeshSource::Builtin(m) => **m,
                    MeshSource::Owned(m) => MeshData {
                        closed: m.closed,
                        positions: &m.positions,
                        scale: m.scale,
                        triangles: &m.triangles,
                        normals: m.normals.as_deref(),
                        uvs: None,
                    },
                };
                MeshData {
                    uvs: o.uvs.as_deref().or(base.uvs),
                    ..base
                }
            })
            .collect();
        let objects: Vec<SceneObject<'_>> = self
            .objects
            .iter()
            .zip(&meshes)
            .map(|(o, mesh)| {
                let material = match (&o.def.material, &o.texture) {
                    (MaterialDef::Flat(c), _) => Material::Flat(color(*c)),
                    (MaterialDef::Gouraud(c), _) => Material::Gouraud(color(*c)),
                    (MaterialDef::Texture { .. }, Some((texels, w, h, mode))) => {
                        match TextureData::new(texels, *w, *h) {
                            Ok(texture) => Material::Texture {
                                texture,
                                mode: *mode,
                            },
                            Err(_) => Material::Flat(Color::new(31, 0, 31)),
                        }
                    }
                    (MaterialDef::Texture { .. }, None) => Material::Flat(Color::new(31, 0, 31)),
                };
                let [x, y, z] = o.def.position;
                let [roll, pitch, yaw] = o.def.angles;
                SceneObject {
                    mesh,
                    pose: Pose::new(Vec3::new(x, y, z), Euler::new(roll, pitch, yaw)),
                    material,
                }
            })
            .collect();
        let spheres: Vec<SceneSphere> = self
            .def
            .spheres
            .iter()
            .map(|s| SceneSphere {
                centre: s.centre,
                radius: s.radius,
                color: color(s.color),
            })
            .collect();
        let d = &self.def;
        let scene = Scene {
            name: &d.name,
            description: &d.description,
            camera: self.camera_spec(),
            projection: match d.projection {
                ProjectionDef::Perspective { fov_x_degrees } => ProjectionSpec::Perspective {
                    fov_x: fov_x_degrees.to_radians(),
                },
                ProjectionDef::Parallel { width } => ProjectionSpec::Parallel { width },
            },
            near: d.near,
            far: d.far,
            light: Light {
                direction: d.light.direction,
                ambient: d.light.ambient,
                diffuse: d.light.diffuse,
            },
            background: color(d.background),
            objects: &objects,
            spheres: &spheres,
        };
        f(&scene)
    }
}

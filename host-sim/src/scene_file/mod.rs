//! Scene files (RON): meshes from OBJ files, PNG textures, a camera in any
//! form, objects with poses and materials, a light and spheres.
//!
//! Errors carry the file, line and column they refer to and what was
//! expected; see `docs/sim.md` for the format.

mod defs;
mod obj;

pub use defs::{MaterialDef, ObjectDef, ProjectionDef, Rgb, SceneDef, SphereDef};
pub use obj::{OwnedMesh, is_closed, load_obj};

use crate::image::read_png_rgb8_limited;
use sightline::camera::CameraError;
use sightline::math::Vec3;
use sightline::scene::{
    self, CameraSpec, Color, Material, MeshData, ProjectionSpec, Scene, SceneObject, SceneSphere,
    TextureMode,
};
use sightline::texture::Texture;
use sightline::transform::{Euler, Pose};
use std::fmt;
use std::path::{Path, PathBuf};

/// An error in a scene file or a file it references, with its location.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FileError {
    /// The file the error is in.
    pub file: PathBuf,
    /// 1-based line (0 when unknown; then neither line nor column is
    /// shown).
    pub line: usize,
    /// 1-based column (0 when unknown; then only the line is shown).
    pub col: usize,
    /// What is wrong and what was expected.
    pub message: String,
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let file = self.file.display();
        match (self.line, self.col) {
            (0, _) => write!(f, "{file}: {}", self.message),
            (line, 0) => write!(f, "{file}:{line}: {}", self.message),
            (line, col) => write!(f, "{file}:{line}:{col}: {}", self.message),
        }
    }
}

impl std::error::Error for FileError {}

fn color(c: Rgb) -> Color {
    Color::new(c[0] >> 3, c[1] >> 2, c[2] >> 3)
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

/// Byte offset of the first field `name:` (a whole identifier followed by
/// a colon) at or after byte `from` in `text`.
fn find_field(text: &str, from: usize, name: &str) -> Option<usize> {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut at = from.min(text.len());
    while let Some(p) = text[at..].find(name) {
        let start = at + p;
        let end = start + name.len();
        let before_ok = !text[..start].chars().next_back().is_some_and(ident);
        let after_ok = text[end..].trim_start().starts_with(':');
        if before_ok && after_ok {
            return Some(start);
        }
        at = end;
    }
    None
}

/// The largest texture side accepted (see docs/sim.md): bigger PNGs are
/// refused after reading their header, before decoding.
pub const MAX_TEXTURE_SIDE: u32 = 4096;

/// The byte order mark some editors put at the start of a UTF-8 file.
const BOM: char = '\u{feff}';

/// Loads a scene file and everything it references.
///
/// # Errors
/// [`FileError`] naming the scene file (syntax, unknown fields, NaN or
/// infinite numbers, a missing mesh or texture file, a bad texture, a
/// singular camera) or the referenced file (a bad OBJ line).
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
/// files), loading everything it references. A leading byte order mark
/// is skipped.
///
/// # Errors
/// As [`load`], apart from reading the scene file itself. Never panics,
/// whatever the text (checked by the `scene_file` fuzz target).
pub fn parse(text: &str, path: &Path) -> Result<LoadedScene, FileError> {
    let text = text.strip_prefix(BOM).unwrap_or(text);
    let def: SceneDef = ron::from_str(text).map_err(|e| FileError {
        file: path.to_path_buf(),
        line: e.span.start.line,
        col: e.span.start.col,
        message: match e.code {
            // Our own checks of a value say what they expected.
            ron::Error::Message(m) => m,
            c => format!("{c} (expected a scene as described in docs/sim.md)"),
        },
    })?;
    let at = |offset: Option<usize>, message: String| {
        let (line, col) = offset.map_or((0, 0), |o| line_col(text, o));
        FileError {
            file: path.to_path_buf(),
            line,
            col,
            message,
        }
    };
    let here = |needle: &str, message: String| at(text.find(needle), message);
    if def.far <= def.near {
        return Err(at(
            find_field(text, 0, "far").or_else(|| find_field(text, 0, "near")),
            format!(
                "far is {} and near {}: expected near < far",
                def.far, def.near
            ),
        ));
    }
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
                // An OBJ error without a line is placed at the `mesh:`
                // field, naming the OBJ file in the message.
                let mesh = load_obj(&p, o.scale).map_err(|e| {
                    if e.line == 0 {
                        here(&quoted, format!("{}: {}", p.display(), e.message))
                    } else {
                        e
                    }
                })?;
                MeshSource::Owned(mesh)
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
            let img = read_png_rgb8_limited(&p, MAX_TEXTURE_SIDE)
                .map_err(|m| here(&quoted_t, format!("texture {m}")))?;
            let (w, h) = (img.width, img.height);
            if !(w.is_power_of_two() && h.is_power_of_two()) {
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
            texture = Some((texels, w as u16, h as u16, *mode));
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
    if let Err(e) = loaded.def.camera.build::<f32>() {
        return Err(camera_error(&loaded.def.camera, e, text, path));
    }
    Ok(loaded)
}

/// The error for a camera that core cannot build, placed at the camera
/// (or at the field to blame) and saying what was expected.
fn camera_error(camera: &CameraSpec, e: CameraError, text: &str, path: &Path) -> FileError {
    let token = match camera {
        CameraSpec::Angles { .. } => "Angles",
        CameraSpec::Orthonormal { .. } => "Orthonormal",
        CameraSpec::Vectors { .. } => "Vectors",
        CameraSpec::LookAt { .. } => "LookAt",
    };
    let start = find_field(text, 0, "camera").unwrap_or(0);
    let cam = text[start..].find(token).map(|p| start + p);
    let field = |name| cam.and_then(|c| find_field(text, c, name)).or(cam);
    let (offset, message) = match (camera, e) {
        (CameraSpec::LookAt { up, .. }, _) if up.iter().all(|&c| c == 0.0) => (
            field("up"),
            "camera: the up vector is zero: expected a non-zero up, not parallel to the view"
                .to_string(),
        ),
        (CameraSpec::LookAt { eye, target, .. }, _) if eye == target => (
            field("target"),
            "camera: eye and target are the same point: expected a target away from the eye"
                .to_string(),
        ),
        (CameraSpec::LookAt { .. }, CameraError::UpParallelToView) => (
            field("up"),
            "camera: the up vector is parallel to the direction of view: expected an up vector not parallel to target - eye"
                .to_string(),
        ),
        (CameraSpec::Vectors { .. }, e) => (
            cam,
            format!("camera: {e}; expected three linearly independent vectors u, v, w"),
        ),
        (CameraSpec::Orthonormal { .. }, e) => (
            cam,
            format!(
                "camera: {e}; expected unit, mutually perpendicular, right-handed right/down/forward"
            ),
        ),
        (_, e) => (
            cam,
            format!("camera: {e}; expected eye != target and up not parallel to the view"),
        ),
    };
    let (line, col) = offset.map_or((0, 0), |o| line_col(text, o));
    FileError {
        file: path.to_path_buf(),
        line,
        col,
        message,
    }
}

impl LoadedScene {
    /// The scene's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.def.name
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
                        match Texture::new(texels, *w, *h, *w as usize) {
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
                center: s.center,
                radius: s.radius,
                color: color(s.color),
            })
            .collect();
        let d = &self.def;
        let scene = Scene {
            name: &d.name,
            description: &d.description,
            camera: d.camera,
            projection: match d.projection {
                ProjectionDef::Perspective { fov_x_degrees } => ProjectionSpec::Perspective {
                    fov_x: fov_x_degrees.to_radians(),
                },
                ProjectionDef::Parallel { width } => ProjectionSpec::Parallel { width },
            },
            near: d.near,
            far: d.far,
            light: d.light,
            background: color(d.background),
            objects: &objects,
            spheres: &spheres,
        };
        f(&scene)
    }
}

//! A prepared scene written out as Rust source (feature `export`), so that
//! a firmware holds it as `const` data in flash and does no `f32`
//! arithmetic, no normalization and no camera solving at run time.
//!
//! Run [`write_scene`] on the host, typically in the firmware's
//! `build.rs` (with `sightline` as a build dependency that has `export`),
//! and `include!` the file it writes into a module of its own:
//!
//! ```text
//! // build.rs
//! let scene = &sightline::scene::builtin::CUBE;
//! let mut vec3s = vec![Vec3::<I16F16>::ZERO; scene.storage().vec3s];
//! let mut objects = vec![PreparedObject::EMPTY; scene.storage().objects];
//! let mut code = String::new();
//! write_scene(&mut code, "::sightline::scene::builtin::CUBE", scene, 320, 240, &mut vec3s, &mut objects)?;
//! std::fs::write(out_dir.join("cube.rs"), code)?;
//!
//! // firmware
//! mod cube { include!(concat!(env!("OUT_DIR"), "/cube.rs")); }
//! let mut objects = cube::objects()?;       // PreparedMesh::new's checks, no arithmetic
//! let renderer = cube::renderer()?;         // Renderer::from_prepared
//! let frame = renderer.project(&mut objects, &mut scratch)?;
//! ```
//!
//! The values are the host's, bit for bit: the same code prepared them
//! (`tests/tests/prepared_export.rs` renders both and compares every
//! pixel). The scene's triangles, texture coordinates and materials are
//! not copied: the generated code reads them from the scene named by
//! `scene_path` at compile time, and checks at compile time that their
//! counts and a hash of the triangles match what was prepared.
//!
//! # What the generated module holds
//!
//! - `type S` (the scalar), `WIDTH`, `HEIGHT`, `OBJECTS` (object count) and
//!   `VERTICES` (the scratch length [`Renderer::project`] needs);
//! - per object `k`: `POSITIONS_k`, `FACE_NORMALS_k`, `VERTEX_NORMALS_k`
//!   (statics, empty where the material needs none), `POSE_k`;
//! - `fn objects() -> Result<[PreparedObject<'static, S>; OBJECTS], SceneError>`
//!   (poses and culling as prepared; change poses per frame as usual);
//! - `fn renderer() -> Result<Renderer<S>, SceneError>`: camera (by its
//!   world→view transform, [`Camera::from_world_to_view`]), projection,
//!   depth range, light and background, and far clipping if it was on.

use super::{PreparedObject, Renderer, Scene, SceneError, triangle_hash};
#[cfg(doc)]
use crate::camera::Camera;
use crate::camera::ProjectionKind;
use crate::math::Vec3;
use crate::pipeline::Cull;
use crate::scalar::{Fx, Scalar};
use core::fmt::{self, Write};
use embedded_graphics::pixelcolor::RgbColor;

/// A scalar type whose values [`write_prepared`] can write as exact Rust
/// literals: its raw bits.
pub trait ScalarLiteral: Scalar {
    /// The type's path in generated code.
    const PATH: &'static str;
    /// The type of its raw bits (`i32` for fixed point, `u32`/`u64` for
    /// floats).
    const BITS: &'static str;
    /// Writes the raw bits of `self`.
    ///
    /// # Errors
    /// The writer's.
    fn write_bits(self, out: &mut dyn Write) -> fmt::Result;
}

macro_rules! fixed_literal {
    ($($frac:ident $name:literal),*) => {$(
        impl ScalarLiteral for Fx<fixed::types::extra::$frac> {
            const PATH: &'static str = concat!("::sightline::scalar::", $name);
            const BITS: &'static str = "i32";
            fn write_bits(self, out: &mut dyn Write) -> fmt::Result {
                write!(out, "{}", self.to_bits())
            }
        }
    )*};
}
fixed_literal!(U16 "I16F16", U12 "I20F12", U8 "I24F8", U30 "I2F30");

impl ScalarLiteral for f32 {
    const PATH: &'static str = "f32";
    const BITS: &'static str = "u32";
    fn write_bits(self, out: &mut dyn Write) -> fmt::Result {
        write!(out, "{:#x}", self.to_bits())
    }
}

impl ScalarLiteral for f64 {
    const PATH: &'static str = "f64";
    const BITS: &'static str = "u64";
    fn write_bits(self, out: &mut dyn Write) -> fmt::Result {
        write!(out, "{:#x}", self.to_bits())
    }
}

fn s<S: ScalarLiteral>(out: &mut dyn Write, x: S) -> fmt::Result {
    out.write_str("s(")?;
    x.write_bits(out)?;
    out.write_str(")")
}

fn v<S: ScalarLiteral>(out: &mut dyn Write, p: Vec3<S>) -> fmt::Result {
    out.write_str("v(")?;
    p.x.write_bits(out)?;
    out.write_str(", ")?;
    p.y.write_bits(out)?;
    out.write_str(", ")?;
    p.z.write_bits(out)?;
    out.write_str(")")
}

fn vec3s<S: ScalarLiteral>(
    out: &mut dyn Write,
    name: &str,
    k: usize,
    data: &[Vec3<S>],
) -> fmt::Result {
    write!(
        out,
        "pub static {name}_{k}: [::sightline::math::Vec3<S>; {}] = [",
        data.len()
    )?;
    for (i, p) in data.iter().enumerate() {
        out.write_str(if i % 4 == 0 { "\n    " } else { " " })?;
        v(out, *p)?;
        out.write_str(",")?;
    }
    out.write_str("\n];\n")
}

/// Why [`write_scene`] wrote nothing usable.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum ExportError {
    /// The scene could not be prepared or its renderer built (the
    /// storage is too short, a number is not finite, a camera is
    /// degenerate, …).
    Scene(SceneError),
    /// The writer failed.
    Write,
}

impl fmt::Display for ExportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Scene(e) => write!(f, "preparing the scene: {e}"),
            Self::Write => f.write_str("the writer failed"),
        }
    }
}

impl core::error::Error for ExportError {}

/// Prepares `scene` into `vec3s` and `objects` (at least as long as
/// [`Scene::storage`] says), builds its renderer for a `width`×`height`
/// image ([`Renderer::new`]) and writes both with [`write_prepared`]: the
/// whole of a firmware's `build.rs` step.
///
/// # Errors
/// [`ExportError::Scene`] from [`Scene::prepare`] or [`Renderer::new`];
/// [`ExportError::Write`]. On [`ExportError::Scene`] nothing has been
/// written; what a failing writer took is not a usable module.
pub fn write_scene<'s, S: ScalarLiteral>(
    out: &mut dyn Write,
    scene_path: &str,
    scene: &'s Scene<'s>,
    width: u16,
    height: u16,
    vec3s: &'s mut [Vec3<S>],
    objects: &'s mut [PreparedObject<'s, S>],
) -> Result<(), ExportError> {
    let renderer = Renderer::<S>::new(scene, width, height).map_err(ExportError::Scene)?;
    let objects = scene.prepare(vec3s, objects).map_err(ExportError::Scene)?;
    write_prepared(out, scene_path, objects, &renderer).map_err(|_| ExportError::Write)
}

/// Writes `objects` and `renderer` as a Rust module body (see the module
/// docs): `objects` as [`Scene::prepare`] returned
/// them for the scene that the Rust path `scene_path` names (a `static`
/// or `const` [`Scene`], for example
/// `"::sightline::scene::builtin::CUBE"`), with any poses or culling you
/// changed since; `renderer` built for that scene.
///
/// The generated code needs `sightline` with the features the materials
/// use, and the scene at `scene_path`. It fails to compile, naming the
/// object, if that scene's object count, triangle or position counts or
/// triangles differ from what was prepared.
///
/// # Errors
/// The writer's.
pub fn write_prepared<S: ScalarLiteral>(
    out: &mut dyn Write,
    scene_path: &str,
    objects: &[PreparedObject<'_, S>],
    renderer: &Renderer<S>,
) -> fmt::Result {
    let view = renderer.view();
    let vertices: usize = objects.iter().map(|o| o.mesh.positions().len()).sum();
    write!(
        out,
        "// Generated by sightline::scene::export::write_prepared from `{scene_path}`\n\
         // ({} objects, {vertices} vertices, {}x{} pixels). Do not edit.\n\
         use ::sightline::scene::Material;\n\
         /// The render scalar.\n\
         pub type S = {};\n\
         #[allow(dead_code)]\n\
         const fn s(bits: {}) -> S {{ S::from_bits(bits) }}\n\
         #[allow(dead_code)]\n\
         const fn v(x: {bits}, y: {bits}, z: {bits}) -> ::sightline::math::Vec3<S> {{\n    \
             ::sightline::math::Vec3::new(s(x), s(y), s(z))\n}}\n\
         /// Image width the renderer was built for.\n\
         pub const WIDTH: u16 = {};\n\
         /// Image height the renderer was built for.\n\
         pub const HEIGHT: u16 = {};\n\
         /// Objects of the scene.\n\
         pub const OBJECTS: usize = {};\n\
         /// Scratch vertices a frame needs.\n\
         pub const VERTICES: usize = {vertices};\n\
         const SCENE: &::sightline::scene::Scene<'static> = &{scene_path};\n\
         const _: () = assert!(SCENE.objects.len() == OBJECTS, \"the scene's object count differs from the prepared one\");\n\
",
        objects.len(),
        view.width,
        view.height,
        S::PATH,
        S::BITS,
        view.width,
        view.height,
        objects.len(),
        bits = S::BITS,
    )?;
    for (k, o) in objects.iter().enumerate() {
        let m = &o.mesh;
        writeln!(out, "\n// Object {k}.")?;
        vec3s(out, "POSITIONS", k, m.positions())?;
        vec3s(out, "FACE_NORMALS", k, m.face_normals())?;
        vec3s(out, "VERTEX_NORMALS", k, m.vertex_normals())?;
        let ang = o.pose.angles;
        write!(
            out,
            "/// Object {k}'s pose as prepared.\npub const POSE_{k}: ::sightline::transform::Pose<S> = ::sightline::transform::Pose::new("
        )?;
        v(out, o.pose.origin)?;
        out.write_str(", ::sightline::transform::Euler::new(")?;
        s(out, ang.roll)?;
        out.write_str(", ")?;
        s(out, ang.pitch)?;
        out.write_str(", ")?;
        s(out, ang.yaw)?;
        out.write_str("));\n")?;
        write!(
            out,
            "const _: () = {{\n    \
                 let m = SCENE.objects[{k}].mesh;\n    \
                 assert!(m.positions.len() == {n} && m.triangles.len() == {t}, \"object {k}: the scene's mesh has other counts than the prepared one\");\n    \
                 assert!(::sightline::scene::triangle_hash(m.triangles) == {h:#x}, \"object {k}: the scene's triangles differ from the prepared ones\");\n\
             }};\n\
             const TRIANGLES_{k}: &[[u16; 3]] = SCENE.objects[{k}].mesh.triangles;\n\
             const UVS_{k}: &[[i16; 2]] = match SCENE.objects[{k}].mesh.uvs {{ Some(u) => u, None => &[] }};\n\
             const MATERIAL_{k}: Material<'static> = SCENE.objects[{k}].material;\n",
            n = m.positions().len(),
            t = m.triangles().len(),
            h = triangle_hash(m.triangles()),
        )?;
    }
    out.write_str(
        "\n/// The prepared objects: each mesh through `PreparedMesh::new`'s checks, no arithmetic.\n\
         ///\n/// # Errors\n/// What `PreparedMesh::new` and `PreparedObject::new` refuse (a material\n\
         /// whose stage this build leaves out).\n\
         pub fn objects() -> Result<[::sightline::scene::PreparedObject<'static, S>; OBJECTS], ::sightline::scene::SceneError> {\n    \
         Ok([",
    )?;
    for (k, o) in objects.iter().enumerate() {
        let cull = match o.cull {
            Cull::None => "None",
            Cull::Back => "Back",
            Cull::Front => "Front",
        };
        write!(
            out,
            "\n        object({k}, &POSITIONS_{k}, TRIANGLES_{k}, &FACE_NORMALS_{k}, &VERTEX_NORMALS_{k}, UVS_{k}, {closed}, POSE_{k}, MATERIAL_{k}, ::sightline::pipeline::Cull::{cull})?,",
            closed = o.mesh.is_closed(),
        )?;
    }
    out.write_str(
        "\n    ])\n}\n\n\
         #[allow(clippy::too_many_arguments)]\n\
         fn object(\n    k: usize,\n    positions: &'static [::sightline::math::Vec3<S>],\n    \
         triangles: &'static [[u16; 3]],\n    \
         faces: &'static [::sightline::math::Vec3<S>],\n    verts: &'static [::sightline::math::Vec3<S>],\n    \
         uvs: &'static [[i16; 2]],\n    \
         closed: bool,\n    pose: ::sightline::transform::Pose<S>,\n    material: Material<'static>,\n    \
         cull: ::sightline::pipeline::Cull,\n\
         ) -> Result<::sightline::scene::PreparedObject<'static, S>, ::sightline::scene::SceneError> {\n    \
             let mesh = ::sightline::scene::PreparedMesh::new(positions, triangles, faces, verts, uvs, closed)\n        \
                 .map_err(|error| ::sightline::scene::SceneError::Mesh { object: k, error })?;\n    \
             let mut o = ::sightline::scene::PreparedObject::new(mesh, pose, material).map_err(|e| e.at_object(k))?;\n    \
             o.cull = cull;\n    \
             Ok(o)\n}\n",
    )?;
    let w2v = view.camera.world_to_view();
    let (r0, r1, r2) = view.camera.view_axes();
    out.write_str(
        "\n/// Camera, projection, depth range, light and background, from values.\n\
         ///\n/// # Errors\n/// What `Renderer::from_prepared` refuses.\n\
         pub fn renderer() -> Result<::sightline::scene::Renderer<S>, ::sightline::scene::SceneError> {\n    \
         let camera = ::sightline::camera::Camera::from_world_to_view(\n        ",
    )?;
    v(out, view.camera.position())?;
    out.write_str(",\n        ::sightline::math::Affine3::new(\n            ::sightline::math::Mat3::from_rows(")?;
    v(out, r0)?;
    out.write_str(", ")?;
    v(out, r1)?;
    out.write_str(", ")?;
    v(out, r2)?;
    out.write_str("),\n            ")?;
    v(out, w2v.translation)?;
    out.write_str(
        ",\n        ),\n    )\n    .map_err(::sightline::scene::SceneError::Camera)?;\n    \
         let projection = ::sightline::camera::Projection {\n        kind: ::sightline::camera::ProjectionKind::",
    )?;
    let (kind, param) = match view.projection.kind {
        ProjectionKind::Perspective { focus } => ("Perspective { focus: ", focus),
        ProjectionKind::Parallel { scale } => ("Parallel { scale: ", scale),
    };
    out.write_str(kind)?;
    s(out, param)?;
    out.write_str(" },\n        center: ::sightline::math::Vec2::new(")?;
    s(out, view.projection.center.x)?;
    out.write_str(", ")?;
    s(out, view.projection.center.y)?;
    out.write_str(
        "),\n    };\n    \
         let view = ::sightline::scene::View { camera, projection, width: WIDTH, height: HEIGHT };\n    \
         let light = ::sightline::scene::PreparedLight::from_unit(",
    )?;
    let light = renderer.light();
    v(out, light.direction())?;
    out.write_str(", ")?;
    s(out, light.ambient())?;
    out.write_str(", ")?;
    s(out, light.diffuse())?;
    let (near, far) = renderer.depth_range();
    let bg = renderer.background();
    out.write_str(");\n    ::sightline::scene::Renderer::from_prepared(view, ")?;
    s(out, near)?;
    out.write_str(", ")?;
    s(out, far)?;
    write!(
        out,
        ", light, ::sightline::scene::Color::new({}, {}, {}))",
        bg.r(),
        bg.g(),
        bg.b()
    )?;
    if renderer.clips_far() {
        // `with_far_clip` exists with `clip-far`, which the renderer had.
        out.write_str("\n        .map(|r| r.with_far_clip(true))")?;
    }
    out.write_str("\n}\n")
}

#[cfg(all(test, feature = "demo"))]
mod tests {
    use super::*;
    use crate::scalar::I16F16;
    use crate::scene::builtin::CUBE;
    use std::string::String;
    use std::vec;

    /// Too little storage or a bad scene is refused before anything is
    /// written; a good one writes the module (whose values
    /// `tests/tests/prepared_export.rs` compiles and checks).
    #[test]
    fn write_scene_refuses_before_writing() {
        let need = CUBE.storage();
        let storage = |v: usize| {
            (
                vec![Vec3::<I16F16>::ZERO; v],
                vec![PreparedObject::EMPTY; need.objects],
            )
        };
        let mut code = String::new();
        let (mut vec3s, mut objects) = storage(need.vec3s - 1);
        let r = write_scene(&mut code, "CUBE", &CUBE, 320, 240, &mut vec3s, &mut objects);
        assert_eq!(r, Err(ExportError::Scene(SceneError::Storage)));
        assert!(code.is_empty());

        let mut bad = CUBE;
        bad.near = f32::NAN;
        let (mut vec3s, mut objects) = storage(need.vec3s);
        let r = write_scene(&mut code, "CUBE", &bad, 320, 240, &mut vec3s, &mut objects);
        assert!(
            matches!(r, Err(ExportError::Scene(SceneError::NonFinite { .. }))),
            "{r:?}"
        );
        assert!(code.is_empty());

        let (mut vec3s, mut objects) = storage(need.vec3s);
        let r = write_scene(&mut code, "CUBE", &CUBE, 320, 240, &mut vec3s, &mut objects);
        assert_eq!(r, Ok(()));
        assert!(code.contains("pub const VERTICES: usize = 12;"), "{code}");
        assert!(code.contains("pub fn renderer()"));
    }
}

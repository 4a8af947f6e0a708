//! The serde types of a scene file.
//!
//! Every struct and enum denies unknown fields, so a typo is an error
//! with its place. The serde names are the names users write (`camera`,
//! `object`, `mode`, …), so RON's messages never show a Rust type name.
//! Numbers are checked while they are read (finite; a field of view in
//! (0°, 180°); positive widths, radii and scales), so RON reports the
//! line and column of the offending value.
//!
//! The camera ([`CameraSpec`]), the light ([`Light`]) and the texture
//! mode ([`TextureMode`]) are core's own description types, read through
//! core's `serde` feature with the same names and checks; the rest differ
//! from core's types in shape (degrees, `[r, g, b]` bytes, file names)
//! and are converted in `scene_file`.

use serde::Deserialize;
use serde::de::{Deserializer, Error as _};
use sightline::scene::{CameraSpec, Light, TextureMode};

/// `[r, g, b]` in 0..=255.
pub type Rgb = [u8; 3];

// Finite numbers are checked by core's own serde helpers, so the error
// stands at the number in the file.
use sightline::scene::de::{finite, finite3};

fn positive<'de, D: Deserializer<'de>>(d: D, what: &str) -> Result<f32, D::Error> {
    let x = finite(d)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(D::Error::custom(format!("{what} is {x}: expected > 0")))
    }
}

fn positive_width<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    positive(d, "width")
}

fn positive_radius<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    positive(d, "radius")
}

fn positive_scale<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    positive(d, "scale")
}

fn positive_near<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    positive(d, "near")
}

fn positive_far<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    positive(d, "far")
}

fn fov_degrees<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    let x = finite(d)?;
    if x > 0.0 && x < 180.0 {
        Ok(x)
    } else {
        Err(D::Error::custom(format!(
            "fov_x_degrees is {x}: expected a field of view in degrees, 0 < fov_x_degrees < 180"
        )))
    }
}

/// A projection.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "projection", deny_unknown_fields)]
pub enum ProjectionDef {
    /// Horizontal field of view in degrees.
    Perspective {
        /// Degrees, in (0, 180).
        #[serde(deserialize_with = "fov_degrees")]
        fov_x_degrees: f32,
    },
    /// World units across the image (raster only).
    Parallel {
        /// World units across, > 0.
        #[serde(deserialize_with = "positive_width")]
        width: f32,
    },
}

/// A material.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "material", deny_unknown_fields)]
pub enum MaterialDef {
    /// Flat color.
    Flat(Rgb),
    /// Gouraud color.
    Gouraud(Rgb),
    /// A PNG texture (sides powers of two) and a mode.
    Texture {
        /// PNG file, relative to the scene file.
        file: String,
        /// Mapping mode.
        #[serde(default = "default_mode")]
        mode: TextureMode,
    },
}

fn default_mode() -> TextureMode {
    TextureMode::Perspective
}

/// An object.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "object", deny_unknown_fields)]
pub struct ObjectDef {
    /// OBJ file relative to the scene file, or `builtin:cube`,
    /// `builtin:floor`, `builtin:bunny`.
    pub mesh: String,
    /// Origin in world coordinates.
    #[serde(default, deserialize_with = "finite3")]
    pub position: [f32; 3],
    /// (roll, pitch, yaw) in radians.
    #[serde(default, deserialize_with = "finite3")]
    pub angles: [f32; 3],
    /// Uniform scale applied to the OBJ coordinates, > 0.
    #[serde(default = "one", deserialize_with = "positive_scale")]
    pub scale: f32,
    /// Appearance.
    pub material: MaterialDef,
}

fn one() -> f32 {
    1.0
}

/// A sphere.
#[derive(Clone, Debug, Deserialize)]
#[serde(rename = "sphere", deny_unknown_fields)]
pub struct SphereDef {
    /// Center (files written before the American spelling say `centre`,
    /// which is still read).
    #[serde(alias = "centre", deserialize_with = "finite3")]
    pub center: [f32; 3],
    /// Radius, > 0.
    #[serde(deserialize_with = "positive_radius")]
    pub radius: f32,
    /// Color.
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
    /// Camera (core's own type, read through its `serde` feature).
    pub camera: CameraSpec,
    /// Projection.
    pub projection: ProjectionDef,
    /// Near distance, > 0.
    #[serde(default = "default_near", deserialize_with = "positive_near")]
    pub near: f32,
    /// Far distance, > 0 (and > near).
    #[serde(default = "default_far", deserialize_with = "positive_far")]
    pub far: f32,
    /// Light (core's own type, read through its `serde` feature).
    pub light: Light,
    /// Background color.
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

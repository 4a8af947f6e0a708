//! Checks that the `serde` derives of the description run while a value
//! is read (feature `serde`), so that a format with positions (RON, JSON)
//! reports the offending number where it stands. No allocation: messages
//! are formatted into the deserializer's own error.
//!
//! [`finite`] and [`finite3`] are public for a reader's own types
//! (`#[serde(deserialize_with = "sightline::scene::de::finite")]`), as the
//! simulator's scene files use them.

use serde::de::{Deserialize, Deserializer, Error};

/// A number that must be finite.
struct Finite(f32);

impl<'de> Deserialize<'de> for Finite {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let x = f32::deserialize(d)?;
        if x.is_finite() {
            Ok(Self(x))
        } else {
            Err(D::Error::custom(format_args!(
                "expected a finite number, found {x}"
            )))
        }
    }
}

/// A finite `f32`; NaN and ±∞ are an error at the number.
///
/// # Errors
/// The deserializer's error, or a custom one for a non-finite number.
pub fn finite<'de, D: Deserializer<'de>>(d: D) -> Result<f32, D::Error> {
    Finite::deserialize(d).map(|f| f.0)
}

/// Three finite `f32`s; an error stands at the first bad one.
///
/// # Errors
/// As [`finite`].
pub fn finite3<'de, D: Deserializer<'de>>(d: D) -> Result<[f32; 3], D::Error> {
    <[Finite; 3]>::deserialize(d).map(|a| a.map(|f| f.0))
}

/// The default diffuse intensity of a light read from a file.
pub(super) fn one() -> f32 {
    1.0
}

//! Everything about textures below the renderers: the one texel store
//! and sampler, the texture-mapping vectors, the per-pixel perspective
//! mapping they give, and the choice between affine and perspective
//! mapping per polygon.
//!
//! # Texels
//!
//! [`Texture`] is a validated, read-only view of a caller's texel slice
//! (row-major, with a stride), and [`Texture::sample`] the one
//! nearest-texel fetch, with the wrap mode as a type parameter
//! ([`Repeat`], [`RepeatPow2`], [`Clamp`]). The raster's texture shaders,
//! the column caster ([`ray::column`](crate::ray::column)) and both paths of the
//! scene (its [`Material::Texture`](crate::scene::Material::Texture))
//! read texels only through it, so the two viewing paths fetch the same
//! texel for the same (u, v). The store depends on nothing else in the
//! crate and is present without any feature (scene descriptions name it);
//! the mapping below needs the `texture` feature.
//!
//! # Mapping
//!
//! A texture lies on a planar polygon as `X = P + u·U + v·V` (view space):
//! the point of texture coordinates (u, v) is the origin P plus u times
//! the vector U plus v times the vector V ([`TextureVectors`]). They are
//! recovered from the polygon's vertices and texture coordinates:
//!
//! | constructor | for | how |
//! |---|---|---|
//! | [`TextureVectors::from_axis_edges`] | rectangles and triangles whose edges from one vertex run along u and along v | U and V are those edges divided by their texel lengths: no arithmetic beyond that |
//! | [`TextureVectors::from_polygon`] | any planar polygon with affine (u, v) | the reverse-mapping equations `Xᵢ − X_k = (uᵢ − u_k)·U + (vᵢ − v_k)·V`, based on a vertex k of the polygon, solved by [`crate::solve`] (2×2, three right-hand sides) |
//!
//! Basing the equations on a vertex instead of the texture origin keeps
//! the coefficients small (texel differences across the polygon) however
//! far away the origin (u, v) = (0, 0) lies, so the system is as well
//! conditioned as the polygon's texture layout.
//!
//! [`TextureVectors::screen_mapping`] turns the vectors into the
//! per-pixel perspective mapping: with the view ray `D = ((x_s − c_x)/f,
//! (y_s − c_y)/f, 1)` through screen point (x_s, y_s),
//!
//! ```text
//! u = D·(V×P) / D·(U×V),   v = D·(P×U) / D·(U×V)
//! ```
//!
//! (Cramer's rule on `t·D = P + u·U + v·V`): ratios of functions linear in
//! x_s and y_s ([`ScreenMapping`]). A·D and B·D are the classic "magic
//! vectors" of perspective texture mapping.
//!
//! Finally [`choose_mapping`] decides per triangle whether affine
//! interpolation is good enough, from a bound on its error in texels
//! ([`affine_error_bound`]).

mod texel;
#[cfg(feature = "texture")]
pub(crate) use texel::MaskedTexels;
pub use texel::{Clamp, Repeat, RepeatPow2, Texture, TextureError, Wrap};
#[cfg(feature = "perspective")]
pub(crate) use texel::{PAIRS, sample_coords};

#[cfg(feature = "texture")]
mod mapping;
#[cfg(feature = "texture")]
pub use mapping::{
    Mapping, MappingError, ScreenMapping, TextureVectors, affine_error_bound, choose_mapping,
};

#[cfg(all(test, feature = "perspective", feature = "depth"))]
mod tests;

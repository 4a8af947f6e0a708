//! Vertex formats that carry only what a scene needs.
//!
//! A [`Vertex`] is a view-space position plus an attribute set `A` chosen
//! at compile time: `()` (position only), [`Intensity`], [`Uv`] or
//! [`IntensityUv`]. The clipper interpolates the attributes with
//! [`Attributes::lerp`] using the same parameter as the coordinates, so a
//! flat-shaded scene clips and pushes only x, y, z.

use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt::Debug;

/// Per-vertex quantities interpolated linearly along clipped edges.
pub trait Attributes<S: Scalar>: Copy + Debug {
    /// `self + (other − self)·t`, componentwise.
    #[must_use]
    fn lerp(self, other: Self, t: S) -> Self;

    /// `false` if any component is NaN or ±∞.
    fn is_finite(&self) -> bool;
}

/// Attributes that map to the scan converter's `VARYINGS` varyings (16.16 fixed
/// point, see [`SpanShader`](crate::raster::SpanShader)).
pub trait Varyings<S: Scalar, const VARYINGS: usize>: Attributes<S> {
    /// The varyings for this vertex. `q` is `near/z` for perspective
    /// projection (in (0, 1] after clipping) and 1 for parallel; only
    /// perspective-correct formats use it. Values that do not convert
    /// (NaN, out of range) become 0 or saturate; the scan converter clamps
    /// to the shader's range.
    fn to_varyings(&self, q: S) -> [i32; VARYINGS];
}

/// A view-space vertex: position (x right, y down, z forward) and
/// attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex<S, A = ()> {
    /// Position in view space.
    pub pos: Vec3<S>,
    /// Interpolated attributes.
    pub attr: A,
}

impl<S: Scalar, A> Vertex<S, A> {
    /// A vertex from a position and attributes.
    #[must_use]
    pub const fn new(pos: Vec3<S>, attr: A) -> Self {
        Self { pos, attr }
    }
}

/// Position only: for flat shading.
pub type VertexXyz<S> = Vertex<S, ()>;
/// Position and intensity: for Gouraud shading.
pub type VertexXyzI<S> = Vertex<S, Intensity<S>>;
/// Position and texture coordinates.
pub type VertexXyzUv<S> = Vertex<S, Uv<S>>;
/// Position, intensity and texture coordinates.
pub type VertexXyzIUv<S> = Vertex<S, IntensityUv<S>>;
/// Position and texture coordinates for perspective-correct mapping.
pub type VertexXyzUvP<S> = Vertex<S, UvPerspective<S>>;

/// Light intensity in `[0, 1]`, mapped to the varying 0..=255 (16.16).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Intensity<S>(pub S);

/// Texture coordinates in texels, mapped to 16.16 varyings.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Uv<S> {
    /// Horizontal texel coordinate.
    pub u: S,
    /// Vertical texel coordinate.
    pub v: S,
}

/// Texture coordinates in texels for perspective-correct mapping with
/// [`PerspectiveTexture`](crate::raster::PerspectiveTexture): the varyings
/// are `u·q`, `v·q` (16.16) and `q = near/z` (8.24), which are linear in
/// screen space.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct UvPerspective<S> {
    /// Horizontal texel coordinate.
    pub u: S,
    /// Vertical texel coordinate.
    pub v: S,
}

/// Intensity and texture coordinates (varyings: intensity, u, v).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct IntensityUv<S> {
    /// Light intensity in `[0, 1]`.
    pub i: S,
    /// Horizontal texel coordinate.
    pub u: S,
    /// Vertical texel coordinate.
    pub v: S,
}

/// `a + (b − a)·t` for `t` in `[0, 1]`, never beyond `a` and `b` (to a
/// step). Out of line: only clipped polygons interpolate, and inlined for
/// each coordinate and attribute it cost the flat cube firmware 264 bytes
/// of .text once the saturation fallback was added.
#[inline(never)]
fn lerp<S: Scalar>(a: S, b: S, t: S) -> S {
    if let Some(d) = b.checked_sub(a) {
        let r = a + d * t;
        if r.is_finite() {
            return r;
        }
    }
    lerp_far_apart(a, b, t)
}

/// At the ends of the range b − a overflows: to ±∞ in floats (and ∞·0 is
/// NaN), or it saturates in fixed point, although the exact value lies
/// between a and b (found by the `clip` fuzz target; for floats the
/// rounding of a + (b − a)·t can overflow too). Each product here is at
/// most |a| or |b|, and their sum lies between (to a step). Cold.
#[cold]
#[inline(never)]
fn lerp_far_apart<S: Scalar>(a: S, b: S, t: S) -> S {
    a * (S::ONE - t) + b * t
}

/// Intensity `[0, 1]` → 0..=255 in 16.16.
fn intensity_varying<S: Scalar>(i: S) -> i32 {
    (i.clamp_to(S::ZERO, S::ONE) * S::from_i32(255))
        .to_subpixel(16)
        .unwrap_or(0)
}

/// Texels → 16.16, saturated to the default shader range (±2^29).
fn texel_varying<S: Scalar>(u: S) -> i32 {
    let lim = 1 << 29;
    match u.to_subpixel(16) {
        Some(v) => v.clamp(-lim, lim - 1),
        None if u > S::ZERO => lim - 1,
        None if u < S::ZERO => -lim,
        None => 0,
    }
}

impl<S: Scalar> Attributes<S> for () {
    #[inline]
    fn lerp(self, _other: Self, _t: S) -> Self {}
    fn is_finite(&self) -> bool {
        true
    }
}

impl<S: Scalar> Varyings<S, 0> for () {
    fn to_varyings(&self, _q: S) -> [i32; 0] {
        []
    }
}

impl<S: Scalar> Attributes<S> for Intensity<S> {
    #[inline]
    fn lerp(self, other: Self, t: S) -> Self {
        Self(lerp(self.0, other.0, t))
    }
    fn is_finite(&self) -> bool {
        self.0.is_finite()
    }
}

impl<S: Scalar> Varyings<S, 1> for Intensity<S> {
    fn to_varyings(&self, _q: S) -> [i32; 1] {
        [intensity_varying(self.0)]
    }
}

/// Formats whose fields are all interpolated scalars: each field lerps and
/// is checked on its own. (`Uv` and `UvPerspective` interpolate alike and
/// differ only in their varyings.)
macro_rules! field_attributes {
    ($($T:ident { $($f:ident),+ }),+ $(,)?) => {$(
        impl<S: Scalar> Attributes<S> for $T<S> {
            #[inline]
            fn lerp(self, other: Self, t: S) -> Self {
                Self {
                    $($f: lerp(self.$f, other.$f, t)),+
                }
            }
            fn is_finite(&self) -> bool {
                $(self.$f.is_finite())&&+
            }
        }
    )+};
}
field_attributes!(Uv { u, v }, UvPerspective { u, v }, IntensityUv { i, u, v });

impl<S: Scalar> Varyings<S, 2> for Uv<S> {
    fn to_varyings(&self, _q: S) -> [i32; 2] {
        [texel_varying(self.u), texel_varying(self.v)]
    }
}

impl<S: Scalar> Varyings<S, 3> for UvPerspective<S> {
    fn to_varyings(&self, q: S) -> [i32; 3] {
        let q = q.clamp_to(S::ZERO, S::ONE);
        let qv = q
            .to_subpixel(crate::raster::PERSPECTIVE_Q_BITS)
            .unwrap_or(1)
            .max(1);
        [texel_varying(self.u * q), texel_varying(self.v * q), qv]
    }
}

impl<S: Scalar> Varyings<S, 3> for IntensityUv<S> {
    fn to_varyings(&self, _q: S) -> [i32; 3] {
        [
            intensity_varying(self.i),
            texel_varying(self.u),
            texel_varying(self.v),
        ]
    }
}

/// Whether every coordinate and attribute is finite (always true for fixed
/// point).
pub(super) fn vertex_is_finite<S: Scalar, A: Attributes<S>>(v: &Vertex<S, A>) -> bool {
    v.pos.is_finite() && v.attr.is_finite()
}

/// Linear interpolation of position and attributes with one parameter.
#[inline]
pub(super) fn lerp_vertex<S: Scalar, A: Attributes<S>>(
    a: &Vertex<S, A>,
    b: &Vertex<S, A>,
    t: S,
) -> Vertex<S, A> {
    Vertex {
        pos: Vec3::new(
            lerp(a.pos.x, b.pos.x, t),
            lerp(a.pos.y, b.pos.y, t),
            lerp(a.pos.z, b.pos.z, t),
        ),
        attr: a.attr.lerp(b.attr, t),
    }
}

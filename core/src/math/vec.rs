//! Small fixed-size vectors over any [`Scalar`].

use crate::scalar::Scalar;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A 2D vector or point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec2<S> {
    /// x component.
    pub x: S,
    /// y component.
    pub y: S,
}

/// A 3D vector or point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<S> {
    /// x component.
    pub x: S,
    /// y component.
    pub y: S,
    /// z component.
    pub z: S,
}

/// A 4D (homogeneous) vector.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec4<S> {
    /// x component.
    pub x: S,
    /// y component.
    pub y: S,
    /// z component.
    pub z: S,
    /// w component.
    pub w: S,
}

macro_rules! vec_common {
    ($V:ident { $($f:ident),+ }, $n:literal) => {
        impl<S: Scalar> $V<S> {
            /// All components zero.
            pub const ZERO: Self = Self { $($f: S::ZERO),+ };

            /// Creates a vector from its components.
            #[must_use]
            pub const fn new($($f: S),+) -> Self {
                Self { $($f),+ }
            }
            /// The same value in every component.
            #[must_use]
            pub const fn splat(v: S) -> Self {
                Self { $($f: v),+ }
            }
            /// Converts from an array of components.
            #[must_use]
            pub const fn from_array(a: [S; $n]) -> Self {
                let [$($f),+] = a;
                Self { $($f),+ }
            }
            /// The components as an array.
            #[must_use]
            pub const fn to_array(self) -> [S; $n] {
                [$(self.$f),+]
            }
            /// Dot product.
            #[must_use]
            pub fn dot(self, rhs: Self) -> S {
                if let Some(v) = S::dot_fast([$(self.$f),+], [$(rhs.$f),+]) {
                    return v;
                }
                let mut acc = S::ZERO;
                $(acc += self.$f * rhs.$f;)+
                acc
            }
            /// Squared Euclidean length (may overflow or saturate for large
            /// vectors; prefer [`Self::length`]).
            #[must_use]
            pub fn length_squared(self) -> S {
                self.dot(self)
            }
            /// Largest absolute component (the ∞-norm).
            #[must_use]
            pub fn max_abs(self) -> S {
                let mut m = S::ZERO;
                $(m = m.max_of(self.$f.abs());)+
                m
            }
            /// Euclidean length, computed as `m·‖v/m‖` with `m` the largest
            /// absolute component, so it neither overflows nor underflows
            /// while the result is representable (fixed point: saturates
            /// beyond `MAX`).
            #[must_use]
            pub fn length(self) -> S {
                let m = self.max_abs();
                if m == S::ZERO {
                    return S::ZERO;
                }
                m * (self / m).length_squared().sqrt()
            }
            /// Unit vector in the same direction, or `None` when the vector
            /// is zero or has a non-finite component.
            ///
            /// The scaling by the largest component first keeps it accurate
            /// for tiny and huge vectors in every representation.
            #[must_use]
            pub fn try_normalize(self) -> Option<Self> {
                let m = self.max_abs();
                if m == S::ZERO || !m.is_finite() {
                    return None;
                }
                let s = self / m;
                let len = s.length_squared().sqrt();
                let r = s / len;
                if r.is_finite() { Some(r) } else { None }
            }
            /// Unit vector in the same direction, or zero when
            /// [`Self::try_normalize`] fails.
            #[must_use]
            pub fn normalize_or_zero(self) -> Self {
                self.try_normalize().unwrap_or(Self::ZERO)
            }
            /// Unit vector in the same direction.
            ///
            /// # Panics
            /// Never. A zero or non-finite vector gives the zero vector, as
            /// [`Self::normalize_or_zero`]; use [`Self::try_normalize`] to
            /// detect that case.
            #[must_use]
            pub fn normalize(self) -> Self {
                self.normalize_or_zero()
            }
            /// `true` when every component is finite.
            #[must_use]
            pub fn is_finite(self) -> bool {
                true $(&& self.$f.is_finite())+
            }
            /// Linear interpolation `self + (rhs - self)·t`.
            #[must_use]
            pub fn lerp(self, rhs: Self, t: S) -> Self {
                self + (rhs - self) * t
            }
            /// Converts every component to another scalar type (through f64,
            /// with that type's rounding and saturation).
            #[must_use]
            pub fn cast<T: Scalar>(self) -> $V<T> {
                $V { $($f: T::from_f64(self.$f.to_f64())),+ }
            }
        }
        impl<S: Scalar> Add for $V<S> {
            type Output = Self;
            #[inline]
            fn add(self, rhs: Self) -> Self {
                Self { $($f: self.$f + rhs.$f),+ }
            }
        }
        impl<S: Scalar> Sub for $V<S> {
            type Output = Self;
            #[inline]
            fn sub(self, rhs: Self) -> Self {
                Self { $($f: self.$f - rhs.$f),+ }
            }
        }
        impl<S: Scalar> AddAssign for $V<S> {
            #[inline]
            fn add_assign(&mut self, rhs: Self) {
                *self = *self + rhs;
            }
        }
        impl<S: Scalar> SubAssign for $V<S> {
            #[inline]
            fn sub_assign(&mut self, rhs: Self) {
                *self = *self - rhs;
            }
        }
        impl<S: Scalar> Mul<S> for $V<S> {
            type Output = Self;
            #[inline]
            fn mul(self, rhs: S) -> Self {
                Self { $($f: self.$f * rhs),+ }
            }
        }
        impl<S: Scalar> Div<S> for $V<S> {
            type Output = Self;
            #[inline]
            fn div(self, rhs: S) -> Self {
                Self { $($f: self.$f / rhs),+ }
            }
        }
        impl<S: Scalar> Neg for $V<S> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                Self { $($f: -self.$f),+ }
            }
        }
    };
}

vec_common!(Vec2 { x, y }, 2);
vec_common!(Vec3 { x, y, z }, 3);
vec_common!(Vec4 { x, y, z, w }, 4);

impl<S: Scalar> Vec2<S> {
    /// The z component of the 3D cross product, `x·ry − y·rx`: twice the
    /// signed area of the triangle (0, self, rhs), positive when `rhs` is
    /// counter-clockwise from `self` in a y-up frame.
    #[must_use]
    pub fn perp_dot(self, rhs: Self) -> S {
        self.x * rhs.y - self.y * rhs.x
    }
}

impl<S: Scalar> Vec3<S> {
    /// Unit x.
    pub const X: Self = Self::new(S::ONE, S::ZERO, S::ZERO);
    /// Unit y.
    pub const Y: Self = Self::new(S::ZERO, S::ONE, S::ZERO);
    /// Unit z.
    pub const Z: Self = Self::new(S::ZERO, S::ZERO, S::ONE);

    /// Cross product (right-handed: `X.cross(Y) == Z`).
    #[must_use]
    pub fn cross(self, rhs: Self) -> Self {
        Self {
            x: self.y * rhs.z - self.z * rhs.y,
            y: self.z * rhs.x - self.x * rhs.z,
            z: self.x * rhs.y - self.y * rhs.x,
        }
    }
    /// Extends with `w`.
    #[must_use]
    pub fn extend(self, w: S) -> Vec4<S> {
        Vec4::new(self.x, self.y, self.z, w)
    }
}

impl<S: Scalar> Vec4<S> {
    /// Drops `w`.
    #[must_use]
    pub fn truncate(self) -> Vec3<S> {
        Vec3::new(self.x, self.y, self.z)
    }
}

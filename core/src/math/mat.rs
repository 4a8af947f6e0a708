//! 3×3, affine 3×4 and 4×4 matrices over any [`Scalar`].
//!
//! Storage is row-major (`m[row][col]`), matching the chapter's matrix
//! equations, and vectors are columns: `p' = M·p`. Composition `a * b`
//! applies `b` first.

use super::vec::{Vec3, Vec4};
use crate::scalar::Scalar;
use core::ops::Mul;

/// A 3×3 matrix (rotation, scale, shear).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3<S> {
    /// Rows.
    pub m: [[S; 3]; 3],
}

/// An affine transform `p ↦ M·p + t`: a 3×4 matrix `[M | t]` with an
/// implicit last row (0, 0, 0, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine3<S> {
    /// The linear part.
    pub matrix: Mat3<S>,
    /// The translation.
    pub translation: Vec3<S>,
}

/// An [`Affine3`] prepared for transforming many points
/// ([`Affine3::for_points`]).
#[derive(Clone, Copy, Debug)]
pub struct PointTransform<S> {
    affine: Affine3<S>,
    prepared: Option<[[[i32; 3]; 3]; 3]>,
}

impl<S: Scalar> PointTransform<S> {
    /// `M·p + t`: the transform's [`Affine3::transform_point3`].
    #[must_use]
    #[inline]
    pub fn apply(&self, p: Vec3<S>) -> Vec3<S> {
        let fast = match &self.prepared {
            Some(m) => S::mat3_vec3_prepared(m, p.to_array()),
            None => None,
        };
        let mp = match fast {
            Some(r) => Vec3::from_array(r),
            None => self.affine.matrix.mul_vec3(p),
        };
        mp + self.affine.translation
    }

    /// The transform.
    #[must_use]
    pub fn affine(&self) -> &Affine3<S> {
        &self.affine
    }
}

/// A 4×4 matrix, for projections (homogeneous w ≠ 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat4<S> {
    /// Rows.
    pub m: [[S; 4]; 4],
}

impl<S: Scalar> Mat3<S> {
    /// The identity.
    pub const IDENTITY: Self = Self {
        m: [
            [S::ONE, S::ZERO, S::ZERO],
            [S::ZERO, S::ONE, S::ZERO],
            [S::ZERO, S::ZERO, S::ONE],
        ],
    };

    /// From three rows.
    #[must_use]
    pub const fn from_rows(r0: Vec3<S>, r1: Vec3<S>, r2: Vec3<S>) -> Self {
        Self {
            m: [r0.to_array(), r1.to_array(), r2.to_array()],
        }
    }
    /// From three columns.
    #[must_use]
    pub fn from_cols(c0: Vec3<S>, c1: Vec3<S>, c2: Vec3<S>) -> Self {
        Self::from_rows(c0, c1, c2).transpose()
    }
    /// Row `i` (0..3).
    #[must_use]
    pub fn row(&self, i: usize) -> Vec3<S> {
        Vec3::from_array(self.m[i])
    }
    /// Column `j` (0..3).
    #[must_use]
    pub fn col(&self, j: usize) -> Vec3<S> {
        Vec3::new(self.m[0][j], self.m[1][j], self.m[2][j])
    }
    /// The transpose.
    #[must_use]
    pub fn transpose(&self) -> Self {
        let m = &self.m;
        Self {
            m: [
                [m[0][0], m[1][0], m[2][0]],
                [m[0][1], m[1][1], m[2][1]],
                [m[0][2], m[1][2], m[2][2]],
            ],
        }
    }
    /// `M·v`.
    #[must_use]
    pub fn mul_vec3(&self, v: Vec3<S>) -> Vec3<S> {
        if let Some(r) = S::mat3_vec3_fast(&self.m, v.to_array()) {
            return Vec3::from_array(r);
        }
        Vec3::new(self.row(0).dot(v), self.row(1).dot(v), self.row(2).dot(v))
    }
    /// `self · rhs`.
    #[must_use]
    pub fn mul_mat3(&self, rhs: &Self) -> Self {
        let mut out = Self::IDENTITY;
        for i in 0..3 {
            for j in 0..3 {
                out.m[i][j] = self.row(i).dot(rhs.col(j));
            }
        }
        out
    }
    /// The determinant (cofactor expansion along the first row).
    #[must_use]
    pub fn determinant(&self) -> S {
        self.row(0).dot(self.row(1).cross(self.row(2)))
    }
    /// The inverse from the adjugate, `M⁻¹ = adj(M)/det(M)`, or `None`
    /// when `M` is singular to working precision, not finite, or its
    /// inverse overflows the representation.
    ///
    /// Each row is first divided by its largest |entry| (`N = D⁻¹M`, so
    /// `M⁻¹ = N⁻¹D⁻¹`): the cofactors of N lie in [−2, 2] and its
    /// determinant in [−3√3, 3√3] (Hadamard), whatever the scale of `M`,
    /// so fixed point neither saturates nor loses its resolution there.
    /// `None` when `|det N| ≤ 32·ε`: the computed determinant of a matrix
    /// that is exactly singular (with exactly stored rows) is at most
    /// about 24·ε for floats (the rounding of N and of the triple product)
    /// and 27 grid steps for fixed point, so every such matrix is refused.
    ///
    /// No solver is involved: this is three cross products, a dot product
    /// and nine divisions. [`crate::solve::invert`] is the pivoting solver's
    /// inverse with its diagnostics (growth, condition number) and a
    /// reason when it fails.
    #[must_use]
    pub fn try_inverse(&self) -> Option<Self> {
        let mut n = [Vec3::ZERO; 3];
        let mut s = [S::ZERO; 3];
        for i in 0..3 {
            let r = self.row(i);
            let si = r.max_abs();
            if si == S::ZERO || !r.is_finite() || !si.is_finite() {
                return None;
            }
            s[i] = si;
            n[i] = div3(r, si)?;
        }
        // Columns of adj(N): N·(n₁×n₂) = (det, 0, 0) and so on.
        let c = [n[1].cross(n[2]), n[2].cross(n[0]), n[0].cross(n[1])];
        let det = n[0].dot(c[0]);
        let tiny = S::EPSILON * S::from_i32(32);
        if det.abs().partial_cmp(&tiny) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        let col = |j: usize| div3(div3(c[j], det)?, s[j]);
        Some(Self::from_cols(col(0)?, col(1)?, col(2)?))
    }
    /// Rotation by `angle` radians about +X (right-handed: Y turns toward Z).
    #[must_use]
    pub fn rotation_x(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        let (o, z) = (S::ONE, S::ZERO);
        Self {
            m: [[o, z, z], [z, c, -s], [z, s, c]],
        }
    }
    /// Rotation by `angle` radians about +Y (right-handed: Z turns toward X).
    #[must_use]
    pub fn rotation_y(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        let (o, z) = (S::ONE, S::ZERO);
        Self {
            m: [[c, z, s], [z, o, z], [-s, z, c]],
        }
    }
    /// Rotation by `angle` radians about +Z (right-handed: X turns toward Y).
    #[must_use]
    pub fn rotation_z(angle: S) -> Self {
        let (s, c) = angle.sin_cos();
        let (o, z) = (S::ONE, S::ZERO);
        Self {
            m: [[c, -s, z], [s, c, z], [z, z, o]],
        }
    }
    /// A diagonal scale.
    #[must_use]
    pub fn from_diagonal(d: Vec3<S>) -> Self {
        let z = S::ZERO;
        Self {
            m: [[d.x, z, z], [z, d.y, z], [z, z, d.z]],
        }
    }
    /// The nearest-in-spirit rotation to a drifted one: Gram–Schmidt on the
    /// rows (row 0 normalized, row 1 made orthogonal to it and normalized,
    /// row 2 = row 0 × row 1). Use it to re-orthonormalize a rotation that
    /// accumulates many small incremental products.
    ///
    /// Returns `None` when the first two rows are zero, parallel or not
    /// finite; "parallel" means that row 1's component orthogonal to row 0
    /// is within 64·ε of row 1's size, where its direction would be
    /// rounding noise.
    #[must_use]
    pub fn try_orthonormalize(&self) -> Option<Self> {
        let r0 = self.row(0).try_normalize()?;
        let r1 = self.row(1);
        let rest = r1 - r0 * r0.dot(r1);
        if rest.max_abs() <= r1.max_abs() * S::EPSILON * S::from_i32(64) {
            return None;
        }
        let r1 = rest.try_normalize()?;
        Some(Self::from_rows(r0, r1, r0.cross(r1)))
    }
    /// Converts every entry to another scalar type.
    #[must_use]
    pub fn cast<T: Scalar>(&self) -> Mat3<T> {
        Mat3::from_rows(self.row(0).cast(), self.row(1).cast(), self.row(2).cast())
    }
}

impl<S: Scalar> Mul for Mat3<S> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        self.mul_mat3(&rhs)
    }
}

impl<S: Scalar> Affine3<S> {
    /// The identity.
    pub const IDENTITY: Self = Self {
        matrix: Mat3::IDENTITY,
        translation: Vec3::ZERO,
    };

    /// From a linear part and a translation.
    #[must_use]
    pub const fn new(matrix: Mat3<S>, translation: Vec3<S>) -> Self {
        Self {
            matrix,
            translation,
        }
    }
    /// A pure translation.
    #[must_use]
    pub fn from_translation(t: Vec3<S>) -> Self {
        Self::new(Mat3::IDENTITY, t)
    }
    /// A pure linear map.
    #[must_use]
    pub fn from_mat3(m: Mat3<S>) -> Self {
        Self::new(m, Vec3::ZERO)
    }
    /// Transforms a point (w = 1): `M·p + t`.
    #[must_use]
    pub fn transform_point3(&self, p: Vec3<S>) -> Vec3<S> {
        self.matrix.mul_vec3(p) + self.translation
    }
    /// Transforms a direction (w = 0): `M·v`.
    #[must_use]
    pub fn transform_vector3(&self, v: Vec3<S>) -> Vec3<S> {
        self.matrix.mul_vec3(v)
    }
    /// This transform prepared for many points: [`PointTransform::apply`]
    /// gives [`Self::transform_point3`]'s values, with the work that
    /// depends only on the matrix done here, once (16.16 fixed point on
    /// ARMv6-M: its range test and the halves of its entries).
    #[must_use]
    pub fn for_points(&self) -> PointTransform<S> {
        PointTransform {
            affine: *self,
            prepared: S::mat3_prepare(&self.matrix.m),
        }
    }
    /// `self · rhs`: the composition that applies `rhs` first.
    #[must_use]
    pub fn mul_affine(&self, rhs: &Self) -> Self {
        Self::new(
            self.matrix.mul_mat3(&rhs.matrix),
            self.matrix.mul_vec3(rhs.translation) + self.translation,
        )
    }
    /// The inverse transform `p ↦ M⁻¹(p − t)`.
    ///
    /// `None` as [`Mat3::try_inverse`], or when the new translation is
    /// not finite.
    #[must_use]
    pub fn try_inverse(&self) -> Option<Self> {
        let inv = self.matrix.try_inverse()?;
        let t = -inv.mul_vec3(self.translation);
        t.is_finite().then(|| Self::new(inv, t))
    }
    /// As a 4×4 matrix with last row (0, 0, 0, 1).
    #[must_use]
    pub fn to_mat4(&self) -> Mat4<S> {
        let m = &self.matrix.m;
        let t = self.translation;
        let (z, o) = (S::ZERO, S::ONE);
        Mat4 {
            m: [
                [m[0][0], m[0][1], m[0][2], t.x],
                [m[1][0], m[1][1], m[1][2], t.y],
                [m[2][0], m[2][1], m[2][2], t.z],
                [z, z, z, o],
            ],
        }
    }
    /// Converts every entry to another scalar type.
    #[must_use]
    pub fn cast<T: Scalar>(&self) -> Affine3<T> {
        Affine3::new(self.matrix.cast(), self.translation.cast())
    }
}

impl<S: Scalar> Mul for Affine3<S> {
    type Output = Self;
    /// `a * b` applies `b` first.
    fn mul(self, rhs: Self) -> Self {
        self.mul_affine(&rhs)
    }
}

impl<S: Scalar> Mat4<S> {
    /// The identity.
    pub const IDENTITY: Self = Self {
        m: [
            [S::ONE, S::ZERO, S::ZERO, S::ZERO],
            [S::ZERO, S::ONE, S::ZERO, S::ZERO],
            [S::ZERO, S::ZERO, S::ONE, S::ZERO],
            [S::ZERO, S::ZERO, S::ZERO, S::ONE],
        ],
    };

    /// `M·v`.
    #[must_use]
    pub fn mul_vec4(&self, v: Vec4<S>) -> Vec4<S> {
        let r = |i: usize| Vec4::from_array(self.m[i]).dot(v);
        Vec4::new(r(0), r(1), r(2), r(3))
    }
    /// `self · rhs`.
    #[must_use]
    pub fn mul_mat4(&self, rhs: &Self) -> Self {
        let mut out = Self::IDENTITY;
        for i in 0..4 {
            for j in 0..4 {
                let mut acc = S::ZERO;
                for k in 0..4 {
                    acc += self.m[i][k] * rhs.m[k][j];
                }
                out.m[i][j] = acc;
            }
        }
        out
    }
    /// Transforms a point with w = 1 and returns x, y, z **without** the
    /// divide (correct for affine matrices; see [`Self::project_point3`]).
    #[must_use]
    pub fn transform_point3(&self, p: Vec3<S>) -> Vec3<S> {
        self.mul_vec4(p.extend(S::ONE)).truncate()
    }
    /// Transforms a direction with w = 0, without the divide.
    #[must_use]
    pub fn transform_vector3(&self, v: Vec3<S>) -> Vec3<S> {
        self.mul_vec4(v.extend(S::ZERO)).truncate()
    }
    /// Transforms a point with w = 1 and divides by the resulting w.
    ///
    /// Returns `None` when w is zero or the result is not finite (a point
    /// in the eye plane of a perspective matrix): callers clip first.
    #[must_use]
    pub fn project_point3(&self, p: Vec3<S>) -> Option<Vec3<S>> {
        let h = self.mul_vec4(p.extend(S::ONE));
        if h.w == S::ZERO {
            return None;
        }
        let mut overflow = false;
        let r = Vec3::new(
            h.x.div_noting_overflow(h.w, &mut overflow),
            h.y.div_noting_overflow(h.w, &mut overflow),
            h.z.div_noting_overflow(h.w, &mut overflow),
        );
        (!overflow && r.is_finite()).then_some(r)
    }
}

impl<S: Scalar> Mul for Mat4<S> {
    type Output = Self;
    fn mul(self, rhs: Self) -> Self {
        self.mul_mat4(&rhs)
    }
}

impl<S: Scalar> From<Affine3<S>> for Mat4<S> {
    fn from(a: Affine3<S>) -> Self {
        a.to_mat4()
    }
}

/// `v / d` per component, or `None` on overflow or a non-finite result.
fn div3<S: Scalar>(v: Vec3<S>, d: S) -> Option<Vec3<S>> {
    let r = Vec3::new(
        v.x.checked_div(d)?,
        v.y.checked_div(d)?,
        v.z.checked_div(d)?,
    );
    r.is_finite().then_some(r)
}

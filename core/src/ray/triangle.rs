//! Triangles and triangle meshes, with the watertight ray/triangle test of
//! Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT
//! 2(1), 2013.
//!
//! The test works in the ray's own frame ([`ShearedRay`]): the axes are
//! permuted so the ray's dominant axis is z (x and y swapped when `d_z < 0`
//! to keep the winding), and the vertices, relative to the origin, are
//! sheared so that the ray becomes the +z axis through (0, 0). The 2D edge
//! functions of the sheared vertices,
//!
//! ```text
//! U = Cx·By − Cy·Bx,  V = Ax·Cy − Ay·Cx,  W = Bx·Ay − By·Ax,
//! ```
//!
//! are the signed areas seen along the ray. The ray hits when U, V, W are
//! all ≥ 0 or all ≤ 0 (either winding; no culling), with `det = U+V+W ≠ 0`.
//!
//! Why this is watertight: the sheared coordinates of a vertex depend only
//! on the vertex and the ray, so two triangles sharing an edge compute the
//! edge function from bit-identical inputs, and `x_P·y_Q − y_P·x_Q` is
//! exactly the negation of `x_Q·y_P − y_Q·x_P` under IEEE rounding. A
//! point on the edge gives 0 for both triangles, and both report the hit.
//! Only a *rounded* 0 could be wrong, so when any of U, V, W is exactly 0
//! they are recomputed in more precision (paper, §3, "fallback to double"):
//! - `f32`: in `f64`, where the products are exact, so the sign is exact;
//! - `f64`: with Dekker's exact products (double-`f64`);
//! - fixed point: always in exact `i128` integer arithmetic on the raw bits
//!   (the sheared coordinates are exact fixed-point values), including
//!   `det`, `T` and the division for `t`.
//!
//! Edge hits are therefore reported by every triangle touching the point;
//! a nearest-hit query then takes the lowest index on equal `t`.
//!
//! Fixed point: a vertex whose sheared coordinates overflow, or a
//! direction whose dominant component is so small that `1/d_z` overflows,
//! gives no hit.

use super::Ray;
use super::checked::{diff_of_products_wide, fixed_bits, from_fixed_bits, sub3};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// A triangle (either winding; two-sided).
///
/// No validation is needed: a non-finite triangle, or one with a repeated
/// vertex, is never hit. A triangle with three distinct collinear
/// vertices can be hit by a ray whose line meets their line, in every
/// scalar type: the sheared vertices are rounded (in fixed point too, the
/// shear factors are), which can leave it a tiny area (found by the
/// `ray_triangle` fuzz target). The hit then lies on the segment to
/// rounding, where its neighbors in a mesh are hit as well, so such a
/// sliver never opens or closes a gap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle<S> {
    /// The vertices A, B, C.
    pub v: [Vec3<S>; 3],
}

/// A watertight hit: `t` and the barycentric weights of A, B, C
/// (`u + v + w = 1` to rounding; the point is `u·A + v·B + w·C`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit<S> {
    /// Ray parameter.
    pub t: S,
    /// Weight of vertex A.
    pub u: S,
    /// Weight of vertex B.
    pub v: S,
    /// Weight of vertex C.
    pub w: S,
}

/// A ray prepared for the watertight test: axis permutation and shear,
/// computed once and reused for every triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearedRay<S> {
    origin: Vec3<S>,
    k: [usize; 3],
    shear: [S; 3],
}

impl<S: Scalar> ShearedRay<S> {
    /// Prepares `ray`. `None` when the shear overflows (fixed point only:
    /// `1/d_z` beyond the range).
    #[must_use]
    pub fn new(ray: &Ray<S>) -> Option<Self> {
        let d = ray.dir().to_array();
        let mut kz = 0;
        for k in 1..3 {
            if d[k].abs() > d[kz].abs() {
                kz = k;
            }
        }
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Swap to keep the winding (paper, fig. 1).
        if d[kz] < S::ZERO {
            core::mem::swap(&mut kx, &mut ky);
        }
        let sx = d[kx].checked_div(d[kz])?;
        let sy = d[ky].checked_div(d[kz])?;
        let sz = S::ONE.checked_div(d[kz])?;
        Some(Self {
            origin: ray.origin(),
            k: [kx, ky, kz],
            shear: [sx, sy, sz],
        })
    }

    /// The sheared coordinates (x, y, z) of a vertex; `None` on overflow.
    fn transform(&self, v: Vec3<S>) -> Option<[S; 3]> {
        let a = sub3(v, self.origin)?.to_array();
        let [kx, ky, kz] = self.k;
        let [sx, sy, sz] = self.shear;
        let mut of = false;
        let x = a[kx].sub_mul_noting_overflow(sx, a[kz], &mut of);
        let y = a[ky].sub_mul_noting_overflow(sy, a[kz], &mut of);
        let z = a[kz].checked_mul(sz)?;
        (!of && x.is_finite() && y.is_finite()).then_some([x, y, z])
    }
}

impl<S: Scalar> Triangle<S> {
    /// The triangle A, B, C.
    #[must_use]
    pub const fn new(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> Self {
        Self { v: [a, b, c] }
    }

    /// The unit normal `(B − A) × (C − A)`, normalized; `None` when
    /// degenerate.
    #[must_use]
    pub fn normal(&self) -> Option<Vec3<S>> {
        let e1 = sub3(self.v[1], self.v[0])?;
        let e2 = sub3(self.v[2], self.v[0])?;
        let (s1, s2) = (e1.max_abs(), e2.max_abs());
        if s1 == S::ZERO || s2 == S::ZERO {
            return None;
        }
        (e1 / s1).cross(e2 / s2).try_normalize()
    }

    /// Watertight intersection (see the [module docs](self)) with `t > t_min`.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<TriangleHit<S>> {
        self.intersect_sheared(&ShearedRay::new(ray)?, t_min)
    }

    /// As [`Self::intersect`], with the ray prepared once.
    #[must_use]
    pub fn intersect_sheared(&self, r: &ShearedRay<S>, t_min: S) -> Option<TriangleHit<S>> {
        let a = r.transform(self.v[0])?;
        let b = r.transform(self.v[1])?;
        let c = r.transform(self.v[2])?;
        let hit = if S::IS_FLOAT {
            float_hit(a, b, c)?
        } else {
            fixed_hit(a, b, c)?
        };
        (hit.t > t_min).then_some(hit)
    }
}

fn float_hit<S: Scalar>(a: [S; 3], b: [S; 3], c: [S; 3]) -> Option<TriangleHit<S>> {
    let u = c[0] * b[1] - c[1] * b[0];
    let v = a[0] * c[1] - a[1] * c[0];
    let w = b[0] * a[1] - b[1] * a[0];
    let zero = S::ZERO;
    let suspect = |e: S| e == zero || !e.is_finite();
    if suspect(u) || suspect(v) || suspect(w) {
        // Fallback to higher precision (Woop et al. 2013, §3).
        let u = diff_of_products_wide(c[0], b[1], c[1], b[0]);
        let v = diff_of_products_wide(a[0], c[1], a[1], c[0]);
        let w = diff_of_products_wide(b[0], a[1], b[1], a[0]);
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let t = (u * a[2].to_f64() + v * b[2].to_f64() + w * c[2].to_f64()) / det;
        let conv = |x: f64| S::try_from_f64(x);
        return Some(TriangleHit {
            t: conv(t)?,
            u: conv(u / det)?,
            v: conv(v / det)?,
            w: conv(w / det)?,
        });
    }
    if (u < zero || v < zero || w < zero) && (u > zero || v > zero || w > zero) {
        return None;
    }
    let det = u + v + w;
    if det == zero {
        return None;
    }
    let t = (u * a[2] + v * b[2] + w * c[2]).checked_div(det)?;
    Some(TriangleHit {
        t,
        u: u.checked_div(det)?,
        v: v.checked_div(det)?,
        w: w.checked_div(det)?,
    })
}

fn fixed_hit<S: Scalar>(a: [S; 3], b: [S; 3], c: [S; 3]) -> Option<TriangleHit<S>> {
    let r = |p: [S; 3]| {
        [
            fixed_bits(p[0]) as i128,
            fixed_bits(p[1]) as i128,
            fixed_bits(p[2]) as i128,
        ]
    };
    let (a, b, c) = (r(a), r(b), r(c));
    // Exact: |raw| < 2³¹, so each product is below 2⁶² and U, V, W, det
    // below 2⁶⁵; T below 2⁹⁸. Raw U has 2F fraction bits, T 3F.
    let u = c[0] * b[1] - c[1] * b[0];
    let v = a[0] * c[1] - a[1] * c[0];
    let w = b[0] * a[1] - b[1] * a[0];
    if (u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0) {
        return None;
    }
    let det = u + v + w;
    if det == 0 {
        return None;
    }
    let t = (u * a[2] + v * b[2] + w * c[2]) / det;
    let one = fixed_bits(S::ONE) as i128;
    Some(TriangleHit {
        t: from_fixed_bits(t)?,
        u: from_fixed_bits(u * one / det)?,
        v: from_fixed_bits(v * one / det)?,
        w: from_fixed_bits(w * one / det)?,
    })
}

/// Why a [`Mesh`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum MeshError {
    /// Triangle `triangle` refers to a vertex index beyond the vertex slice.
    IndexOutOfRange {
        /// The offending triangle.
        triangle: usize,
    },
    /// A vertex is NaN or ±∞.
    NonFinite,
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IndexOutOfRange { triangle } => {
                write!(
                    f,
                    "mesh triangle {triangle} has a vertex index out of range"
                )
            }
            Self::NonFinite => f.write_str("mesh vertex contains NaN or infinity"),
        }
    }
}

impl core::error::Error for MeshError {}

/// An indexed triangle mesh over borrowed vertex and index slices. Shared
/// vertices are stored once, which is what makes watertight testing
/// meaningful: both triangles of an edge see the same coordinates.
///
/// # Guarantees
/// After [`Self::new`] succeeds every index is in range, so no query panics.
#[derive(Clone, Copy, Debug)]
pub struct Mesh<'a, S> {
    vertices: &'a [Vec3<S>],
    indices: &'a [[u32; 3]],
}

impl<'a, S: Scalar> Mesh<'a, S> {
    /// Validates and wraps the slices.
    ///
    /// # Errors
    /// [`MeshError`].
    pub fn new(vertices: &'a [Vec3<S>], indices: &'a [[u32; 3]]) -> Result<Self, MeshError> {
        if vertices.iter().any(|v| !v.is_finite()) {
            return Err(MeshError::NonFinite);
        }
        for (i, t) in indices.iter().enumerate() {
            if t.iter().any(|&k| k as usize >= vertices.len()) {
                return Err(MeshError::IndexOutOfRange { triangle: i });
            }
        }
        Ok(Self { vertices, indices })
    }

    /// Number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.indices.len()
    }

    /// Whether there are no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// Triangle `i`; `None` beyond [`Self::len`].
    #[must_use]
    pub fn triangle(&self, i: usize) -> Option<Triangle<S>> {
        let t = self.indices.get(i)?;
        Some(Triangle::new(
            self.vertices[t[0] as usize],
            self.vertices[t[1] as usize],
            self.vertices[t[2] as usize],
        ))
    }

    /// The nearest watertight hit with `t > t_min`: (triangle index, hit).
    /// On equal `t` the lower index wins.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<(usize, TriangleHit<S>)> {
        let r = ShearedRay::new(ray)?;
        let mut best: Option<(usize, TriangleHit<S>)> = None;
        for i in 0..self.len() {
            let Some(tri) = self.triangle(i) else {
                continue;
            };
            if let Some(h) = tri.intersect_sheared(&r, t_min) {
                if best.is_none_or(|(_, b)| h.t < b.t) {
                    best = Some((i, h));
                }
            }
        }
        best
    }
}

//! Planes and line–plane intersection.

use super::Ray;
use super::checked::{dot3_checked, fixed_bits, sub3};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::cmp::Ordering;
use core::fmt;

/// Why a [`Plane`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PlaneError {
    /// An input is NaN or ±∞.
    NonFinite,
    /// The normal is the zero vector.
    ZeroNormal,
    /// The three points are collinear (or coincide): the cross product of
    /// the edge vectors is zero.
    Collinear,
}

impl fmt::Display for PlaneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("plane input contains NaN or infinity"),
            Self::ZeroNormal => f.write_str("plane normal is the zero vector"),
            Self::Collinear => f.write_str("plane points are collinear"),
        }
    }
}

impl core::error::Error for PlaneError {}

/// A plane through `point` with unit `normal`: the points X with
/// `normal·(X − point) = 0`.
///
/// The normal as given (before normalizing) is kept too: whether a ray is
/// parallel to the plane is decided exactly on it (see
/// [`Self::intersect`]).
///
/// # Guarantees
/// The point is finite and the normal is finite and unit length (to the
/// rounding of `S`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S> {
    point: Vec3<S>,
    normal: Vec3<S>,
    given: Vec3<S>,
}

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with the given (not necessarily unit)
    /// normal; the normal is normalized.
    ///
    /// # Errors
    /// [`PlaneError::NonFinite`], [`PlaneError::ZeroNormal`].
    pub fn new(point: Vec3<S>, normal: Vec3<S>) -> Result<Self, PlaneError> {
        if !(point.is_finite() && normal.is_finite()) {
            return Err(PlaneError::NonFinite);
        }
        let given = normal;
        let normal = normal.try_normalize().ok_or(PlaneError::ZeroNormal)?;
        Ok(Self {
            point,
            normal,
            given,
        })
    }

    /// The plane through three points, normal `(b − a) × (c − a)`
    /// (counter-clockwise points seen from the side the normal points to).
    ///
    /// # Errors
    /// [`PlaneError::NonFinite`]; [`PlaneError::Collinear`] when the cross
    /// product is zero or (fixed point) the edge vectors overflow.
    pub fn from_points(a: Vec3<S>, b: Vec3<S>, c: Vec3<S>) -> Result<Self, PlaneError> {
        if !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return Err(PlaneError::NonFinite);
        }
        let e1 = sub3(b, a).ok_or(PlaneError::Collinear)?;
        let e2 = sub3(c, a).ok_or(PlaneError::Collinear)?;
        // Scale both edges to at most 1 first so the cross product cannot
        // overflow fixed point; the direction is unchanged.
        let s1 = e1.max_abs();
        let s2 = e2.max_abs();
        if s1 == S::ZERO || s2 == S::ZERO {
            return Err(PlaneError::Collinear);
        }
        let n = (e1 / s1).cross(e2 / s2);
        Self::new(a, n).map_err(|_| PlaneError::Collinear)
    }

    /// A point on the plane.
    #[must_use]
    pub fn point(&self) -> Vec3<S> {
        self.point
    }

    /// The unit normal.
    #[must_use]
    pub fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// Signed distance `normal·(p − point)`; `None` on overflow.
    #[must_use]
    pub fn signed_distance(&self, p: Vec3<S>) -> Option<S> {
        dot3_checked(self.normal, sub3(p, self.point)?)
    }

    /// The parameter `t > t_min` at which the ray meets the plane:
    /// `t = n·(P − Q) / n·d`.
    ///
    /// Returns `None` when the ray is parallel to the plane or lies in it,
    /// decided exactly: `m·d = 0` in exact arithmetic for the normal `m` as
    /// given to [`Self::new`] (for [`Self::from_points`], the computed cross
    /// product) and the ray direction `d` as stored. The unit normal is
    /// rounded, so its `n·d` is usually not 0 for such a ray, and is not
    /// used for this decision. Also `None` when the rounded `n·d` is 0
    /// anyway (a direction within rounding of parallel), when the hit is at
    /// `t ≤ t_min`, or when the quotient overflows or is not finite (a
    /// nearly parallel ray whose hit is beyond the representable range).
    /// Every other ray gets `t` from the unit normal.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<S> {
        if dot_sign(self.given, ray.dir())? == Ordering::Equal {
            return None;
        }
        let denom = dot3_checked(self.normal, ray.dir())?;
        if denom == S::ZERO {
            return None;
        }
        let num = dot3_checked(self.normal, sub3(self.point, ray.origin())?)?;
        let t = num.checked_div(denom)?;
        (t > t_min).then_some(t)
    }
}

/// The exact sign of `a·b`; `None` for a non-finite input.
///
/// Fixed point: exact in `i128` on the raw bits. Floats: a filter in `S`
/// and, when it cannot decide, the exact big-integer sum of the three
/// products (`crate::scalar::predicates`). The filter's bound: with unit
/// roundoff u and half the smallest subnormal η, the computed sum of three
/// products differs from the exact one by at most `γ₃·Σ|aᵢbᵢ| + 3η`
/// (γ₃ = 3u/(1 − 3u)), which with `m~ = fl(Σ|fl(aᵢbᵢ)|)` is below
/// `3.01·u·m~ + 4η`; the accepted margin `fl(fl(4u·m~) + 16η)` exceeds
/// that even after its own two roundings. Overflow makes `m~` infinite or
/// NaN, so the filter declines and the exact stage decides.
fn dot_sign<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> Option<Ordering> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    if !S::IS_FLOAT {
        let w = |x: S| fixed_bits(x) as i128;
        let s = w(a.x) * w(b.x) + w(a.y) * w(b.y) + w(a.z) * w(b.z);
        return Some(s.cmp(&0));
    }
    let (p, q, r) = (a.x * b.x, a.y * b.y, a.z * b.z);
    let sum = p + q + r;
    let mag = p.abs() + q.abs() + r.abs();
    // 16η: 2⁻¹⁴⁶ for f32, 2⁻¹⁰⁷¹ for f64 (both exact in their type).
    let single = S::EPSILON.to_f64() > 1e-10;
    let k = S::from_f64(if single {
        f32::from_bits(1 << 3) as f64
    } else {
        f64::from_bits(1 << 3)
    });
    let four_u = S::TWO * S::EPSILON;
    let bound = four_u * mag + k;
    if sum > bound {
        return Some(Ordering::Greater);
    }
    if -sum > bound {
        return Some(Ordering::Less);
    }
    let f = |x: S| x.to_f64();
    Some(crate::scalar::predicates::exact_sign_of_products(&[
        (f(a.x), f(b.x), false),
        (f(a.y), f(b.y), false),
        (f(a.z), f(b.z), false),
    ]))
}

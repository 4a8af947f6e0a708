//! Spheres, with the numerically stable ray/sphere quadratic of Haines,
//! Günther and Akenine-Möller, "Precision Improvements for Ray/Sphere
//! Intersection", *Ray Tracing Gems*, ch. 7 (2019).
//!
//! With `f = Q − C`, the line meets the sphere at the roots of
//! `a·t² + 2b·t + c = 0`, `a = d·d`, `b = f·d`, `c = f·f − r²`.
//!
//! - The discriminant `b² − a·c` cancels catastrophically for small or
//!   distant spheres. It equals `a·(r² − |l|²)` with
//!   `l = f − (b/a)·d` the vector from the closest point of the line to
//!   the center, which does not (ch. 7, eq. 7.5). We go one step further
//!   and take the square root as `√a·√(r − |l|)·√(r + |l|)`, so nothing
//!   small is squared: in fixed point a distant small sphere would
//!   otherwise underflow to nothing.
//! - The roots are `t₀ = c/q`, `t₁ = q/a` with `q = −(b + sign(b)·√Δ)`, the
//!   form that never subtracts nearly equal numbers (ch. 7, eq. 7.7;
//!   Numerical Recipes §5.6). `c` is evaluated as `(|f| − r)·(|f| + r)`.
//! - Before all that, the direction is made unit length and `f` and `r`
//!   are divided by `s = max(‖f‖_∞, r)`, so every intermediate is at most
//!   a few units: nothing overflows fixed point or `f32` even for huge
//!   spheres, and the roots are scaled back by `s / |d|` at the end.
//!
//! # Accuracy
//!
//! With ε = `S::EPSILON`, scaled radius `r_s = r/s` and scaled half-chord
//! `h_s` (half the length of the chord, over s), each root is within
//!
//! ```text
//! (s/|d|)·32ε·(1 + |t|·|d|/s + r_s/h_s)  +  (1 + |t|)·f/|d|  +  f
//! ```
//!
//! of the exact root of the stored inputs, where f is one absolute
//! rounding of `S`: the smallest subnormal for floats, the step 2⁻¹⁶ for
//! I16F16 (where |d| and the product `t·s` are rounded to that step before
//! the division by |d|, hence the `(1 + |t|)·f/|d|` term: keep
//! fixed-point directions well above 2⁻¹⁶). The `r_s/h_s` factor is
//! the conditioning of the roots near tangency; hit and miss may differ
//! from the exact answer only where the line passes within about 32ε·s of
//! tangency. The `ray_sphere` fuzz target checks this bound against a
//! double-double reference.

use super::Ray;
use super::checked::sub3;
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::fmt;

/// Why a [`Sphere`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SphereError {
    /// The center or radius is NaN or ±∞.
    NonFinite,
    /// The radius is zero or negative.
    NonPositiveRadius,
}

impl fmt::Display for SphereError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("sphere center or radius contains NaN or infinity"),
            Self::NonPositiveRadius => f.write_str("sphere radius is not positive"),
        }
    }
}

impl core::error::Error for SphereError {}

/// The real roots of the ray/sphere quadratic (any sign of `t`), ascending.
///
/// A root whose value is beyond the range of `S` is reported as `S::MAX`
/// (or `S::MIN`), so the other root of a huge sphere is still usable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Roots<S> {
    /// The line misses the sphere (or the computation overflowed).
    None,
    /// The line is tangent: one double root.
    One(S),
    /// Two roots `t₀ ≤ t₁`.
    Two(S, S),
}

/// A sphere with a finite center and a positive finite radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere<S> {
    center: Vec3<S>,
    radius: S,
}

impl<S: Scalar> Sphere<S> {
    /// The sphere with the given center and radius.
    ///
    /// # Errors
    /// [`SphereError::NonFinite`], [`SphereError::NonPositiveRadius`].
    pub fn new(center: Vec3<S>, radius: S) -> Result<Self, SphereError> {
        if !(center.is_finite() && radius.is_finite()) {
            return Err(SphereError::NonFinite);
        }
        if radius.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) {
            return Err(SphereError::NonPositiveRadius);
        }
        Ok(Self { center, radius })
    }

    /// The center.
    #[must_use]
    pub fn center(&self) -> Vec3<S> {
        self.center
    }

    /// The radius.
    #[must_use]
    pub fn radius(&self) -> S {
        self.radius
    }

    /// The outward unit normal at a point of the surface.
    #[must_use]
    pub fn normal_at(&self, p: Vec3<S>) -> Vec3<S> {
        sub3(p, self.center)
            .and_then(Vec3::try_normalize)
            .unwrap_or(Vec3::Z)
    }

    /// All real roots of the line `Q + t·d` with the sphere, ascending. An
    /// origin inside gives one negative and one positive root; an origin on
    /// the surface a root at (or within rounding of) zero.
    ///
    /// Returns [`Roots::None`] on a miss and whenever an intermediate
    /// overflows or is not finite.
    #[must_use]
    pub fn roots(&self, ray: &Ray<S>) -> Roots<S> {
        self.roots_opt(ray).unwrap_or(Roots::None)
    }

    fn roots_opt(&self, ray: &Ray<S>) -> Option<Roots<S>> {
        let d = ray.dir();
        let len = d.length();
        if !(len > S::ZERO && len.is_finite()) {
            return None;
        }
        let dn = d / len;
        let f = sub3(ray.origin(), self.center)?;
        let s = f.max_abs().max_of(self.radius);
        let fs = f / s;
        let r = self.radius / s;
        let a = dn.dot(dn);
        let b = fs.dot(dn);
        let l = fs - dn * (b / a);
        let l_len = l.length();
        if l_len > r {
            return Some(Roots::None);
        }
        // √Δ = √a·√(r − |l|)·√(r + |l|): stable discriminant, RTG ch. 7.
        let sq = a.sqrt() * (r - l_len).sqrt() * (r + l_len).sqrt();
        let f_len = fs.length();
        let c = (f_len - r) * (f_len + r);
        let q = if b >= S::ZERO { -(b + sq) } else { -(b - sq) };
        // Back to the caller's units; a root beyond the range saturates
        // (so the near root of a huge sphere survives its far root). When
        // `t·s` overflows but `t·s/|d|` does not (a long direction), scale
        // by `s/|d|` instead (then s is large, so the ratio keeps its
        // precision even in fixed point): found by the `ray_sphere` fuzz
        // target.
        let back = |t: S| {
            let sat = if t > S::ZERO { S::MAX } else { S::MIN };
            Some(
                t.checked_mul(s)
                    .and_then(|x| x.checked_div(len))
                    .or_else(|| s.checked_div(len).and_then(|k| t.checked_mul(k)))
                    .unwrap_or(sat),
            )
        };
        if q == S::ZERO {
            // b = 0 and Δ = 0: the origin is the tangent point.
            return Some(Roots::One(S::ZERO));
        }
        let t1 = back(q.checked_div(a)?)?;
        if sq == S::ZERO {
            return Some(Roots::One(t1));
        }
        let t0 = back(c.checked_div(q)?)?;
        Some(if t0 <= t1 {
            Roots::Two(t0, t1)
        } else {
            Roots::Two(t1, t0)
        })
    }

    /// The least root `t > t_min`, if any. A root beyond the range of `S`
    /// (reported as `S::MAX` by [`Self::roots`]) is not a hit, as for the
    /// other shapes, whose overflowing hits are misses: otherwise a ray
    /// with a tiny direction "hit" at `t = S::MAX`, which the grid, whose
    /// box test overflows there, could not find (found by the `grid` fuzz
    /// target).
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<S> {
        let hit = |t: S| t > t_min && t < S::MAX;
        match self.roots(ray) {
            Roots::None => None,
            Roots::One(t) => hit(t).then_some(t),
            Roots::Two(t0, t1) => {
                if hit(t0) {
                    Some(t0)
                } else if hit(t1) {
                    Some(t1)
                } else {
                    None
                }
            }
        }
    }
}

//! Object→world transforms from roll, pitch and yaw plus a translation.
//!
//! See the crate docs for the axis conventions. In short: world is
//! right-handed with +Y up; roll turns about +Z, pitch about +X, yaw about
//! +Y, each by the right-hand rule; roll is applied first, then pitch, then
//! yaw, then the translation to the object's origin:
//!
//! ```text
//! object→world = T(O) · Ry(yaw) · Rx(pitch) · Rz(roll)
//! ```

use crate::math::{Affine3, Mat3, Vec3};
use crate::scalar::Scalar;

/// Roll, pitch and yaw in radians (Tait–Bryan angles, applied in that order).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Euler<S> {
    /// Rotation about +Z, applied first.
    pub roll: S,
    /// Rotation about +X, applied second.
    pub pitch: S,
    /// Rotation about +Y, applied last.
    pub yaw: S,
}

impl<S: Scalar> Euler<S> {
    /// All angles zero.
    pub const ZERO: Self = Self {
        roll: S::ZERO,
        pitch: S::ZERO,
        yaw: S::ZERO,
    };

    /// Creates the angles.
    #[must_use]
    pub const fn new(roll: S, pitch: S, yaw: S) -> Self {
        Self { roll, pitch, yaw }
    }

    /// The rotation `Ry(yaw) · Rx(pitch) · Rz(roll)`, built in closed form
    /// (one `sin_cos` per angle, 14 multiplications).
    #[must_use]
    pub fn to_mat3(&self) -> Mat3<S> {
        let (sr, cr) = self.roll.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        let (sy, cy) = self.yaw.sin_cos();
        // Every product through one out-of-line multiply: this runs once
        // per object and frame, and in fixed point each inlined `*` (its
        // fast path, wide path and saturation) cost about a hundred bytes
        // of flash on ARMv6-M; the values are the same.
        let mul = product::<S>;
        let (ysp, csp) = (mul(sy, sp), mul(cy, sp));
        Mat3 {
            m: [
                [
                    mul(cy, cr) + mul(ysp, sr),
                    mul(ysp, cr) - mul(cy, sr),
                    mul(sy, cp),
                ],
                [mul(cp, sr), mul(cp, cr), -sp],
                [
                    mul(csp, sr) - mul(sy, cr),
                    mul(sy, sr) + mul(csp, cr),
                    mul(cy, cp),
                ],
            ],
        }
    }

    /// Recovers the angles from a rotation built by [`Self::to_mat3`].
    ///
    /// Pitch is returned in [−π/2, π/2], roll and yaw in (−π, π]. At gimbal
    /// lock (|pitch| = π/2, detected as cos(pitch) below 16·ε) only
    /// yaw ± roll is determined; roll is then reported as 0.
    #[must_use]
    pub fn from_mat3(r: &Mat3<S>) -> Self {
        let m = &r.m;
        // m[1] = (cp·sr, cp·cr, −sp): atan2 of −sp over cp is better
        // conditioned than asin near ±π/2.
        let cp = Vec3::new(m[1][0], m[1][1], S::ZERO).length();
        let pitch = (-m[1][2]).atan2(cp);
        let tiny = S::EPSILON * S::from_i32(16);
        if cp > tiny {
            Self {
                roll: m[1][0].atan2(m[1][1]),
                pitch,
                yaw: m[0][2].atan2(m[2][2]),
            }
        } else {
            Self {
                roll: S::ZERO,
                pitch,
                yaw: (-m[2][0]).atan2(m[0][0]),
            }
        }
    }
}

/// `a·b`, kept out of line (see [`Euler::to_mat3`]).
#[inline(never)]
fn product<S: Scalar>(a: S, b: S) -> S {
    a * b
}

/// Where an object is: its origin in world coordinates and its orientation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pose<S> {
    /// The object's origin O in world coordinates.
    pub origin: Vec3<S>,
    /// Its orientation.
    pub angles: Euler<S>,
}

impl<S: Scalar> Pose<S> {
    /// Creates a pose.
    #[must_use]
    pub const fn new(origin: Vec3<S>, angles: Euler<S>) -> Self {
        Self { origin, angles }
    }

    /// The object→world matrix `T(O) · Ry(yaw) · Rx(pitch) · Rz(roll)`,
    /// concatenated into one affine transform.
    #[must_use]
    pub fn object_to_world(&self) -> Affine3<S> {
        Affine3::new(self.angles.to_mat3(), self.origin)
    }
}

//! Cameras (world→view transforms) in the three forms of the viewing-process
//! chapter, and parallel and perspective projection.
//!
//! View space is right-handed with the eye at the origin, **+Z the
//! direction of view**, +X to the right of the screen and +Y **down** the
//! screen, so that projected coordinates grow the way pixel indices do (see
//! the crate docs).
//!
//! | constructor | input | how the matrix is obtained |
//! |---|---|---|
//! | [`Camera::from_angles`] | position V, yaw/pitch/roll | `T(−V)`, then the inverse rotations in yaw, pitch, roll order |
//! | [`Camera::from_orthonormal`] | V, right, down, forward (orthonormal) | rows taken directly from the vectors' components |
//! | [`Camera::from_vectors`] | V, any three independent vectors | solving `[u v w]·X = I` by Gaussian elimination |
//! | [`Camera::look_at`] | eye, target, up | builds orthonormal vectors, then as `from_orthonormal` |

use crate::math::{Affine3, Mat3, Mat4, Vec2, Vec3};
use crate::scalar::Scalar;
use crate::solve::{self, Diagnostics, SolveConfig, SolveError};
use crate::transform::{Euler, Pose};
use core::fmt;

/// Why a camera could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum CameraError {
    /// An input is NaN or ±∞.
    NonFinite,
    /// A direction vector is zero (or the eye coincides with the target).
    ZeroVector,
    /// `look_at`'s up vector is parallel to the direction of view.
    UpParallelToView,
    /// The vectors given to [`Camera::from_orthonormal`] are not unit length
    /// and mutually perpendicular within the documented tolerance.
    NotOrthonormal,
    /// The vectors are orthonormal but left-handed (right × down = −forward):
    /// the image would be mirrored. Pass the screen's *down* vector.
    LeftHanded,
    /// The general vectors are parallel or nearly parallel: the system for
    /// the view matrix is singular or its reciprocal condition number is
    /// below √ε. Carries the solver's error.
    Degenerate(SolveError),
}

impl fmt::Display for CameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("camera input contains NaN or infinity"),
            Self::ZeroVector => f.write_str("camera direction vector has zero length"),
            Self::UpParallelToView => {
                f.write_str("look_at: the up vector is parallel to the direction of view")
            }
            Self::NotOrthonormal => {
                f.write_str("camera vectors are not orthonormal within tolerance")
            }
            Self::LeftHanded => f.write_str(
                "camera vectors are left-handed (right x down = -forward); pass the screen's down vector",
            ),
            Self::Degenerate(e) => {
                write!(f, "camera vectors are parallel or nearly parallel: {e}")
            }
        }
    }
}

impl core::error::Error for CameraError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Degenerate(e) => Some(e),
            _ => None,
        }
    }
}

/// A camera: the world→view transform plus the eye position.
///
/// Four ways to build one, all giving the same view here: an eye at
/// (0, 0, 5) looking down −Z with +Y up. View space has x right, y down
/// and z forward, so the world origin lands 5 in front of the eye.
///
/// ```
/// use sightline::camera::Camera;
/// use sightline::math::Vec3;
/// use sightline::transform::Euler;
///
/// let eye = Vec3::new(0.0f32, 0.0, 5.0);
/// let angles = Camera::from_angles(eye, Euler::new(0.0, 0.0, 0.0));
/// let look = Camera::look_at(eye, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)).unwrap();
/// let (right, down, fwd) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 0.0, -1.0));
/// let ortho = Camera::from_orthonormal(eye, right, down, fwd).unwrap();
/// // General vectors (here a scaled, sheared frame) are inverted by the
/// // solver, which reports its diagnostics too.
/// let (general, diag) = Camera::from_vectors(eye, right * 2.0, down + right, fwd).unwrap();
/// assert!(diag.rcond > 0.1);
///
/// let p = Vec3::new(0.0, 1.0, 0.0); // one unit above the origin
/// for cam in [angles, look, ortho] {
///     let v = cam.world_to_view().transform_point3(p);
///     assert!((v - Vec3::new(0.0, -1.0, 5.0)).length() < 1e-6, "{v:?}");
/// }
/// // With u = 2·right, v = down + right: p − eye = x·u + y·v + z·w.
/// let v = general.world_to_view().transform_point3(p);
/// assert!((v - Vec3::new(0.5, -1.0, 5.0)).length() < 1e-6, "{v:?}");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<S> {
    world_to_view: Affine3<S>,
    position: Vec3<S>,
}

/// `diag(1, −1, −1)`: from the y-up, looking-down-−Z frame that the angles
/// describe to view space (y down, looking down +Z). A rotation by π about X.
fn flip_to_view<S: Scalar>() -> Mat3<S> {
    Mat3::from_diagonal(Vec3::new(S::ONE, -S::ONE, -S::ONE))
}

impl<S: Scalar> Camera<S> {
    /// Camera at `position` V turned by `angles`.
    ///
    /// With all angles zero the camera looks along world −Z with +Y up on
    /// the screen (the OpenGL default). Positive yaw turns it to the left
    /// (about +Y), positive pitch tilts it up (about +X), positive roll
    /// turns the image clockwise (about the view axis, +Z of the world
    /// before yaw and pitch).
    ///
    /// The world→view matrix is `F · Rz(−roll) · Rx(−pitch) · Ry(−yaw) ·
    /// T(−V)`: translate by −V, then undo yaw, pitch and roll in that order,
    /// where `F = diag(1, −1, −1)` turns to view axes.
    #[must_use]
    pub fn from_angles(position: Vec3<S>, angles: Euler<S>) -> Self {
        // The inverse of a rotation is its transpose.
        let r = flip_to_view().mul_mat3(&angles.to_mat3().transpose());
        Self::from_rotation(position, r)
    }

    fn from_rotation(position: Vec3<S>, r: Mat3<S>) -> Self {
        Self {
            world_to_view: Affine3::new(r, -r.mul_vec3(position)),
            position,
        }
    }

    /// Camera from three orthonormal world vectors: the screen's `right`
    /// and `down` axes and the direction of view `forward`. The rotation's
    /// rows are the vectors' components; no arithmetic is needed.
    ///
    /// # Errors
    /// [`CameraError::NonFinite`]; [`CameraError::NotOrthonormal`] when a
    /// length differs from 1, or a dot product from 0, by more than 64·ε of
    /// the scalar type (≈ 10⁻³ for I16F16, 7.6·10⁻⁶ for f32);
    /// [`CameraError::LeftHanded`] when `right × down` points opposite to
    /// `forward`.
    pub fn from_orthonormal(
        position: Vec3<S>,
        right: Vec3<S>,
        down: Vec3<S>,
        forward: Vec3<S>,
    ) -> Result<Self, CameraError> {
        if !(position.is_finite() && right.is_finite() && down.is_finite() && forward.is_finite()) {
            return Err(CameraError::NonFinite);
        }
        let tol = S::EPSILON * S::from_i32(64);
        let near = |v: S, target: S| (v - target).abs() <= tol;
        let unit = |v: Vec3<S>| v.max_abs() <= S::TWO && near(v.length_squared(), S::ONE);
        if !(unit(right)
            && unit(down)
            && unit(forward)
            && near(right.dot(down), S::ZERO)
            && near(right.dot(forward), S::ZERO)
            && near(down.dot(forward), S::ZERO))
        {
            return Err(CameraError::NotOrthonormal);
        }
        if right.cross(down).dot(forward) < S::ZERO {
            return Err(CameraError::LeftHanded);
        }
        Ok(Self::from_rotation(
            position,
            Mat3::from_rows(right, down, forward),
        ))
    }

    /// Camera from three general (independent, not necessarily orthogonal
    /// or unit) world vectors `u`, `v`, `w`: a world point P has view
    /// coordinates (x, y, z) with `P − V = x·u + y·v + z·w`. The world→view
    /// matrix is `[u v w]⁻¹`, obtained by solving `[u v w]·X = I` with
    /// Gaussian elimination and partial pivoting ([`crate::solve`]); the
    /// solver's diagnostics are returned with the camera.
    ///
    /// With orthonormal, right-handed `u, v, w` this equals
    /// [`Self::from_orthonormal`] to rounding.
    ///
    /// # Errors
    /// [`CameraError::NonFinite`], or [`CameraError::Degenerate`] when the
    /// vectors are parallel, coplanar, or so nearly so that the estimated
    /// reciprocal condition number falls below √ε (≈ 3.5·10⁻⁴ for f32,
    /// 3.9·10⁻³ for I16F16, 1.5·10⁻⁸ for f64).
    pub fn from_vectors(
        position: Vec3<S>,
        u: Vec3<S>,
        v: Vec3<S>,
        w: Vec3<S>,
    ) -> Result<(Self, Diagnostics<S>), CameraError> {
        if !(position.is_finite() && u.is_finite() && v.is_finite() && w.is_finite()) {
            return Err(CameraError::NonFinite);
        }
        let a = Mat3::from_cols(u, v, w);
        let config = SolveConfig {
            rcond_min: S::EPSILON.sqrt(),
            ..SolveConfig::default()
        };
        let sol = solve::solve_with(&a.m, &Mat3::<S>::IDENTITY.m, &config)
            .map_err(CameraError::Degenerate)?;
        Ok((
            Self::from_rotation(position, Mat3 { m: sol.x }),
            sol.diagnostics,
        ))
    }

    /// Camera at `eye` looking at `target`, with `up` giving the screen's
    /// upward direction (it need not be perpendicular to the view).
    ///
    /// # Errors
    /// [`CameraError::NonFinite`]; [`CameraError::ZeroVector`] when `eye ==
    /// target` or `up` is zero; [`CameraError::UpParallelToView`] when `up`
    /// is parallel to the direction of view.
    pub fn look_at(eye: Vec3<S>, target: Vec3<S>, up: Vec3<S>) -> Result<Self, CameraError> {
        if !(eye.is_finite() && target.is_finite() && up.is_finite()) {
            return Err(CameraError::NonFinite);
        }
        let forward = (target - eye)
            .try_normalize()
            .ok_or(CameraError::ZeroVector)?;
        let up = up.try_normalize().ok_or(CameraError::ZeroVector)?;
        // right = forward × up; parallel vectors give a (near) zero cross.
        let right_raw = forward.cross(up);
        if right_raw.max_abs() <= S::EPSILON * S::from_i32(64) {
            return Err(CameraError::UpParallelToView);
        }
        let right = right_raw
            .try_normalize()
            .ok_or(CameraError::UpParallelToView)?;
        let down = forward.cross(right);
        Ok(Self::from_rotation(
            eye,
            Mat3::from_rows(right, down, forward),
        ))
    }

    /// The camera whose world→view transform is `world_to_view`, with its
    /// eye at `position`, both used as given (no arithmetic): for a camera
    /// computed ahead of time, for example by `scene::export` (feature
    /// `export`) from any of the other
    /// forms, so that a firmware links neither the solver nor the
    /// normalization. The renderers expect `world_to_view` to map
    /// `position` to the origin, as every other constructor makes it.
    ///
    /// # Errors
    /// [`CameraError::NonFinite`].
    pub fn from_world_to_view(
        position: Vec3<S>,
        world_to_view: Affine3<S>,
    ) -> Result<Self, CameraError> {
        let m = &world_to_view.matrix;
        let finite = position.is_finite()
            && world_to_view.translation.is_finite()
            && m.row(0).is_finite()
            && m.row(1).is_finite()
            && m.row(2).is_finite();
        if !finite {
            return Err(CameraError::NonFinite);
        }
        Ok(Self {
            world_to_view,
            position,
        })
    }

    /// The same camera in scalar `T`, each coefficient rounded: solve a
    /// general camera in `f32` or `f64`, then render in fixed point.
    #[must_use]
    pub fn cast<T: Scalar>(&self) -> Camera<T> {
        Camera {
            world_to_view: self.world_to_view.cast(),
            position: self.position.cast(),
        }
    }

    /// The world→view transform.
    #[must_use]
    pub fn world_to_view(&self) -> &Affine3<S> {
        &self.world_to_view
    }

    /// The eye position V in world coordinates.
    #[must_use]
    pub fn position(&self) -> Vec3<S> {
        self.position
    }

    /// The one concatenated object→view matrix for an object at `pose`:
    /// `world→view · object→world`.
    #[must_use]
    pub fn object_to_view(&self, pose: &Pose<S>) -> Affine3<S> {
        self.world_to_view.mul_affine(&pose.object_to_world())
    }

    /// The world-space axes of the view frame: (right, down, forward). For
    /// a general camera these are the rows of its matrix, i.e. the dual
    /// basis of `u, v, w`.
    #[must_use]
    pub fn view_axes(&self) -> (Vec3<S>, Vec3<S>, Vec3<S>) {
        let m = &self.world_to_view.matrix;
        (m.row(0), m.row(1), m.row(2))
    }
}

/// Parallel or perspective projection from view space to screen space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProjectionKind<S> {
    /// Orthographic: `x_s = cx + scale·x`, `y_s = cy + scale·y`.
    Parallel {
        /// Pixels per world unit.
        scale: S,
    },
    /// Central projection onto the screen at focus distance `focus` (in
    /// pixels) in front of the eye: `x_s = cx + focus·x/z`,
    /// `y_s = cy + focus·y/z`.
    Perspective {
        /// Distance from the eye to the screen, in pixels.
        focus: S,
    },
}

/// A projection and the screen center it projects about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection<S> {
    /// Parallel or perspective, with its parameter.
    pub kind: ProjectionKind<S>,
    /// Screen position of the view axis, in pixels (usually the viewport
    /// center (w/2, h/2)).
    pub center: Vec2<S>,
}

impl<S: Scalar> Projection<S> {
    /// Perspective projection with the given focus distance (pixels),
    /// centered on a `width`×`height` viewport.
    #[must_use]
    pub fn perspective(focus: S, width: u16, height: u16) -> Self {
        Self {
            kind: ProjectionKind::Perspective { focus },
            center: center(width, height),
        }
    }

    /// Parallel projection with `scale` pixels per world unit, centered on a
    /// `width`×`height` viewport.
    #[must_use]
    pub fn parallel(scale: S, width: u16, height: u16) -> Self {
        Self {
            kind: ProjectionKind::Parallel { scale },
            center: center(width, height),
        }
    }

    /// Perspective projection whose horizontal field of view is `fov_x`
    /// radians: focus = (width/2) / tan(fov_x/2). Returns `None` unless
    /// 0 < `fov_x` < π (the focus would be infinite or negative).
    #[must_use]
    pub fn perspective_fov(fov_x: S, width: u16, height: u16) -> Option<Self> {
        if !(fov_x > S::ZERO && fov_x < S::PI) {
            return None;
        }
        let (s, c) = (fov_x * S::HALF).sin_cos();
        let half_w = S::from_i32(width as i32) * S::HALF;
        let focus = half_w.checked_mul(c)?.checked_div(s)?;
        (focus > S::ZERO).then(|| Self::perspective(focus, width, height))
    }

    /// Changes the focus distance (perspective) or scale (parallel) at run
    /// time.
    pub fn set_focus(&mut self, focus: S) {
        match &mut self.kind {
            ProjectionKind::Perspective { focus: f } => *f = focus,
            ProjectionKind::Parallel { scale } => *scale = focus,
        }
    }

    /// Projects a view-space point to screen coordinates (pixels, x right,
    /// y down) and returns a depth: `1/z` for perspective (larger is
    /// nearer; what is linear in screen space), `z` for parallel.
    ///
    /// Returns `None` for perspective when `z ≤ 0` (at or behind the eye;
    /// callers clip against a near plane first) and whenever the result
    /// overflows or is not finite. When `x·focus` alone would overflow
    /// (e.g. I16F16 with |x|·focus ≥ 32768), `x/z` is formed first, so a
    /// far point with an on-screen pixel still projects (to within about
    /// `focus·2⁻¹⁶` px in I16F16) instead of failing or saturating.
    #[must_use]
    pub fn project(&self, p: Vec3<S>) -> Option<(Vec2<S>, S)> {
        let mut overflow = false;
        let out = match self.kind {
            ProjectionKind::Parallel { scale } => {
                let sx = p.x.checked_mul(scale)?;
                let sy = p.y.checked_mul(scale)?;
                (
                    Vec2::new(
                        self.center.x.checked_add(sx)?,
                        self.center.y.checked_add(sy)?,
                    ),
                    p.z,
                )
            }
            ProjectionKind::Perspective { focus } => {
                if p.z <= S::ZERO || !p.z.is_finite() {
                    return None;
                }
                // The same values by a faster route (16.16: one reciprocal
                // and no division), where the scalar has one.
                if let Some((sx, sy, inv_z)) = S::perspective_fast(p.x, p.y, p.z, focus) {
                    let sx = self.center.x.checked_add(sx)?;
                    let sy = self.center.y.checked_add(sy)?;
                    return Some((Vec2::new(sx, sy), inv_z));
                }
                // One division for both coordinates: r = f/z, then x·r and
                // y·r (a division costs ~300 instructions on ARMv6-M in
                // fixed point, a multiply ~30). In I16F16 r is within 2⁻¹⁷
                // of f/z, so x·r is within (|x| + 1)·2⁻¹⁷ px of x·f/z:
                // below 10⁻³ px while |x|, |y| ≤ 128 view units. Beyond
                // that, or where r or a product overflows, `focus_ratio`
                // divides each coordinate (within 2⁻¹⁶ px). 1/z and f/z
                // share one reciprocal of z in fixed point (the same
                // values as two divisions).
                let near_axis = |v: S| v.abs() <= S::from_i32(128);
                let (inv_z, ratio) = if !(near_axis(p.x) && near_axis(p.y)) {
                    (S::ONE.div_noting_overflow(p.z, &mut overflow), None)
                } else if S::IS_FLOAT {
                    // Two divisions: the shared form measured 1.5 % more
                    // instructions per W1 frame on a Cortex-M4F (this
                    // function: 160 K -> 232 K, qemu-prof).
                    (
                        S::ONE.div_noting_overflow(p.z, &mut overflow),
                        focus.checked_div(p.z),
                    )
                } else {
                    let [inv_z, ratio] = S::checked_quotients([S::ONE, focus], p.z);
                    (inv_z?, ratio)
                };
                let pair = ratio.and_then(|r| Some((p.x.checked_mul(r)?, p.y.checked_mul(r)?)));
                let (sx, sy) = match pair {
                    Some(xy) => xy,
                    None => (
                        focus_ratio(p.x, focus, p.z, &mut overflow),
                        focus_ratio(p.y, focus, p.z, &mut overflow),
                    ),
                };
                (
                    Vec2::new(
                        self.center.x.checked_add(sx)?,
                        self.center.y.checked_add(sy)?,
                    ),
                    inv_z,
                )
            }
        };
        (!overflow && out.0.is_finite() && out.1.is_finite()).then_some(out)
    }

    /// The projection as a 4×4 matrix acting on (x, y, z, 1):
    /// [`Mat4::project_point3`] of a view point gives (x_s, y_s, depth) with
    /// the same depth convention as [`Self::project`].
    #[must_use]
    pub fn to_mat4(&self) -> Mat4<S> {
        let (z, o) = (S::ZERO, S::ONE);
        let (cx, cy) = (self.center.x, self.center.y);
        match self.kind {
            ProjectionKind::Parallel { scale } => Mat4 {
                m: [
                    [scale, z, z, cx],
                    [z, scale, z, cy],
                    [z, z, o, z],
                    [z, z, z, o],
                ],
            },
            ProjectionKind::Perspective { focus } => Mat4 {
                m: [
                    [focus, z, cx, z],
                    [z, focus, cy, z],
                    [z, z, z, o],
                    [z, z, o, z],
                ],
            },
        }
    }
}

/// `focus·x/z`: the product first (the more precise order), or, when
/// `x·focus` overflows (fixed point beyond its range, float beyond
/// ±MAX), the quotient `x/z` first, which stays small for any point
/// inside the view volume. Before this fallback a saturated product gave
/// a wrong pixel without any error (stability suite,
/// `tests/tests/stability_geometry.rs`).
fn focus_ratio<S: Scalar>(x: S, focus: S, z: S, overflow: &mut bool) -> S {
    match x.checked_mul(focus) {
        Some(xf) => xf.div_noting_overflow(z, overflow),
        None => {
            let r = x.div_noting_overflow(z, overflow);
            r.checked_mul(focus).unwrap_or_else(|| {
                *overflow = true;
                S::ZERO
            })
        }
    }
}

fn center<S: Scalar>(width: u16, height: u16) -> Vec2<S> {
    Vec2::new(
        S::from_i32(width as i32) * S::HALF,
        S::from_i32(height as i32) * S::HALF,
    )
}

#[cfg(test)]
mod tests;

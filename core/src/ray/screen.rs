//! The ray-casting camera of the viewing-process chapter: screen center O,
//! per-pixel screen vectors u (right) and v (down), viewer V.
//!
//! The screen point of pixel (i, j) is the chapter's
//! `R = O + (i − w/2)·u + (j − h/2)·v`, taken at the pixel's **center**,
//! `R = O + (i + ½ − c_x)·u + (j + ½ − c_y)·v` with `(c_x, c_y)` the
//! projection center (w/2, h/2 by default), matching the crate's screen
//! convention that pixel (i, j) covers `[i, i+1) × [j, j+1)`. The ray runs
//! from V through R, `d = R − V`, so `t = 1` is on the screen.
//!
//! [`RayCamera::from_camera`] derives (O, u, v, V) from the same
//! [`Camera`] and perspective [`Projection`] the raster path uses: a world
//! point the raster path projects to screen position (x_s, y_s) lies on the
//! ray through (x_s, y_s).

use super::Ray;
use crate::camera::{Camera, Projection, ProjectionKind};
use crate::math::{Mat3, Vec2, Vec3};
use crate::scalar::Scalar;
use crate::solve::{self, SolveError};
use core::fmt;

/// Why a [`RayCamera`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum RayCameraError {
    /// An input is NaN or ±∞.
    NonFinite,
    /// `u` or `v` is zero, or the focus distance is not positive.
    ZeroVector,
    /// The projection is parallel; ray casting here needs a viewer point.
    NotPerspective,
    /// The camera's world→view matrix cannot be inverted.
    Singular(SolveError),
}

impl fmt::Display for RayCameraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("ray camera input contains NaN or infinity"),
            Self::ZeroVector => {
                f.write_str("ray camera screen vector is zero or focus is not positive")
            }
            Self::NotPerspective => f.write_str("ray camera needs a perspective projection"),
            Self::Singular(e) => write!(f, "camera matrix cannot be inverted: {e}"),
        }
    }
}

impl core::error::Error for RayCameraError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Singular(e) => Some(e),
            _ => None,
        }
    }
}

/// A ray-casting camera (O, u, v, V) for a `width`×`height` screen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayCamera<S> {
    /// Screen center O (world), the point at screen position `center`.
    pub screen_center: Vec3<S>,
    /// World vector from one pixel to the next to the right.
    pub u: Vec3<S>,
    /// World vector from one pixel to the next downward.
    pub v: Vec3<S>,
    /// The viewer V (world).
    pub viewer: Vec3<S>,
    /// Screen position of O in pixels (the projection center).
    pub center: Vec2<S>,
    /// Screen width in pixels.
    pub width: u16,
    /// Screen height in pixels.
    pub height: u16,
}

impl<S: Scalar> RayCamera<S> {
    /// The chapter's camera, with O at the screen position (w/2, h/2).
    ///
    /// # Errors
    /// [`RayCameraError::NonFinite`], [`RayCameraError::ZeroVector`].
    pub fn new(
        screen_center: Vec3<S>,
        u: Vec3<S>,
        v: Vec3<S>,
        viewer: Vec3<S>,
        width: u16,
        height: u16,
    ) -> Result<Self, RayCameraError> {
        if !(screen_center.is_finite() && u.is_finite() && v.is_finite() && viewer.is_finite()) {
            return Err(RayCameraError::NonFinite);
        }
        if u.max_abs() == S::ZERO || v.max_abs() == S::ZERO {
            return Err(RayCameraError::ZeroVector);
        }
        let half = |n: u16| S::from_i32(n as i32) * S::HALF;
        Ok(Self {
            screen_center,
            u,
            v,
            viewer,
            center: Vec2::new(half(width), half(height)),
            width,
            height,
        })
    }

    /// The camera that casts through the pixels the raster path fills for
    /// `camera` and a perspective `projection` with focus f: V is the
    /// camera position; with (u_w, v_w, w_w) the world images of the view
    /// axes (the columns of the inverse world→view matrix), `u = u_w`,
    /// `v = v_w` and `O = V + f·w_w` at screen position `projection.center`.
    /// The screen thus sits f world units along the view axis, one unit per
    /// pixel.
    ///
    /// # Errors
    /// [`RayCameraError::NotPerspective`] for a parallel projection;
    /// [`RayCameraError::ZeroVector`] when the focus is not positive;
    /// [`RayCameraError::Singular`] when the camera matrix is singular;
    /// [`RayCameraError::NonFinite`].
    pub fn from_camera(
        camera: &Camera<S>,
        projection: &Projection<S>,
        width: u16,
        height: u16,
    ) -> Result<Self, RayCameraError> {
        let ProjectionKind::Perspective { focus } = projection.kind else {
            return Err(RayCameraError::NotPerspective);
        };
        if focus.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) || !focus.is_finite() {
            return Err(RayCameraError::ZeroVector);
        }
        let inv = Mat3 {
            m: solve::invert(&camera.world_to_view().matrix.m)
                .map_err(RayCameraError::Singular)?
                .x,
        };
        let (u, v, w) = (inv.col(0), inv.col(1), inv.col(2));
        let viewer = camera.position();
        let mut cam = Self::new(viewer + w * focus, u, v, viewer, width, height)?;
        if !projection.center.is_finite() {
            return Err(RayCameraError::NonFinite);
        }
        cam.center = projection.center;
        Ok(cam)
    }

    /// The world point at screen position (x_s, y_s) in pixels:
    /// `O + (x_s − c_x)·u + (y_s − c_y)·v`.
    #[must_use]
    pub fn screen_point(&self, x_s: S, y_s: S) -> Vec3<S> {
        self.screen_center + self.u * (x_s - self.center.x) + self.v * (y_s - self.center.y)
    }

    /// The ray from V through screen position (x_s, y_s); `None` when V
    /// lies there or the arithmetic overflows.
    #[must_use]
    pub fn ray_through(&self, x_s: S, y_s: S) -> Option<Ray<S>> {
        Ray::through(self.viewer, self.screen_point(x_s, y_s)).ok()
    }

    /// The ray through the center (i + ½, j + ½) of pixel (i, j). Pixels
    /// outside the screen are allowed (the formula extends).
    #[must_use]
    pub fn pixel_ray(&self, i: u16, j: u16) -> Option<Ray<S>> {
        let c = |k: u16| S::from_i32(k as i32) + S::HALF;
        self.ray_through(c(i), c(j))
    }

    /// The ray for column i of a column caster: through (i + ½, c_y), the
    /// column's center on the horizon row of the projection center.
    #[must_use]
    pub fn column_ray(&self, i: u16) -> Option<Ray<S>> {
        self.ray_through(S::from_i32(i as i32) + S::HALF, self.center.y)
    }

    /// The column rays `(i, column_ray(i))` for `i in 0..width`.
    pub fn column_rays(&self) -> impl Iterator<Item = (u16, Option<Ray<S>>)> + '_ {
        (0..self.width).map(|i| (i, self.column_ray(i)))
    }
}

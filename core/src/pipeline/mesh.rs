//! Indexed meshes: project each shared vertex once, then assemble
//! triangles.
//!
//! [`Pipeline::project_polygon`] clips and projects every polygon on its
//! own, so a closed mesh projects each vertex about six times and runs the
//! six-plane clipper on triangles that are nowhere near a plane. Here each
//! vertex is classified against the planes (an *outcode*, one bit per
//! plane outside) and projected once into caller-supplied scratch
//! ([`MeshVertex`]); then per triangle:
//!
//! - all three outcodes zero (the common case): the three projected
//!   vertices are used directly;
//! - one plane has all three vertices outside: nothing is visible;
//! - otherwise the triangle goes through [`Pipeline::project_polygon`].
//!
//! Clipping a polygon whose vertices are all inside returns it unchanged,
//! and projection is per vertex, so the result equals
//! [`Pipeline::project_polygon`]'s. The one exception: the side planes are
//! tested on the projected vertex against the guard-band rectangle, the
//! clipper tests them in view space, and the two can disagree for a vertex
//! within rounding of a side plane, 16 pixels off screen. Then one path
//! draws the triangle whole and the other cuts a sliver off screen: the
//! vertices differ, the pixels do not (tested).

use super::{Cull, DrawError, Pipeline, ScreenPolygon, Varyings, Vertex};
use crate::raster::ScreenVertex;
use crate::scalar::Scalar;

/// A mesh vertex after [`Pipeline::project_vertex`]: the planes it lies
/// outside of, and its projection when it lies inside all of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshVertex<const VARYINGS: usize> {
    /// Bit `i` set: outside plane `i` of the frustum. Bit 7 set: not
    /// finite, or the projection overflowed.
    pub outcode: u8,
    /// The projected vertex; meaningful only when `outcode == 0`.
    pub screen: ScreenVertex<VARYINGS>,
}

/// The outcode bit for a vertex that cannot be used directly (not
/// finite, or its projection failed): triangles using it always take the
/// clipping path, which reports the error as
/// [`Pipeline::project_polygon`] does.
pub const OUTCODE_UNUSABLE: u8 = 0x80;
const UNUSABLE: u8 = OUTCODE_UNUSABLE;

impl<const VARYINGS: usize> Default for MeshVertex<VARYINGS> {
    fn default() -> Self {
        Self {
            outcode: UNUSABLE,
            screen: ScreenVertex::new(0, 0, 0, [0; VARYINGS]),
        }
    }
}

/// A triangle ready for [`fill_polygon`](crate::raster::fill_polygon).
#[derive(Clone, Debug)]
pub enum MeshTriangle<const VARYINGS: usize> {
    /// Entirely inside the volume: the three projected vertices.
    Inside([ScreenVertex<VARYINGS>; 3]),
    /// Crossed a plane: the clipped, projected polygon.
    Clipped(ScreenPolygon<VARYINGS>),
}

impl<const VARYINGS: usize> MeshTriangle<VARYINGS> {
    /// The vertices.
    #[must_use]
    pub fn as_slice(&self) -> &[ScreenVertex<VARYINGS>] {
        match self {
            Self::Inside(v) => v,
            Self::Clipped(p) => p,
        }
    }
}

impl<S: Scalar> Pipeline<S> {
    /// Classifies a view-space vertex against the frustum and, when it is
    /// inside every plane, projects it (see the [`mesh`](self) module).
    /// A vertex that is not finite or cannot be projected (overflow) is
    /// marked unusable, so triangles using it take the clipping path,
    /// which reports the error.
    #[must_use]
    pub fn project_vertex<A: Varyings<S, VARYINGS>, const VARYINGS: usize>(
        &self,
        v: &Vertex<S, A>,
    ) -> MeshVertex<VARYINGS> {
        if !(v.pos.is_finite() && v.attr.is_finite()) {
            return MeshVertex::default();
        }
        // The depth planes (near, and far with `with_far_clip`) are tested in
        // view space; the four side planes, for a vertex in front of them,
        // on its projection against the guard-band rectangle: one compare
        // each instead of a dot product. The two tests can disagree only
        // for a vertex within rounding of a side plane, 16 pixels off
        // screen: it is then either drawn as it is (the scan converter
        // scissors it) or sent to the clipper, which keeps it whole; the
        // visible pixels are the same.
        //
        // The depth planes are `z − near ≥ 0` and `far − z ≥ 0` (see
        // `Pipeline::new`): their distance `0·x + 0·y + 1·z + d` is negative
        // exactly when `z < near` (or `z > far`), in fixed point (the zero
        // and unit products are exact and a saturated sum keeps its sign)
        // and in floats (`a − b` rounds to zero only when `a = b`), so the
        // compare gives the same outcode as the dot product, without its
        // three multiplies.
        let depth_planes = self.frustum.planes().len().saturating_sub(4);
        let mut outcode = u8::from(v.pos.z < self.near);
        #[cfg(feature = "clip-far")]
        if depth_planes == 2 && v.pos.z > self.far_plane.d {
            outcode |= 2;
        }
        if outcode != 0 {
            return MeshVertex {
                outcode,
                ..MeshVertex::default()
            };
        }
        let Some(screen) = self.project(v) else {
            return MeshVertex::default();
        };
        let [x0, x1, y0, y1] = self.guard_rect;
        // Bits for x < x0, x > x1, y < y0, y > y1 above the depth planes'
        // (built without branches: a loop over the four cost about 50
        // instructions per vertex on ARMv6-M).
        let side = u8::from(screen.x < x0)
            | (u8::from(screen.x > x1) << 1)
            | (u8::from(screen.y < y0) << 2)
            | (u8::from(screen.y > y1) << 3);
        outcode |= side << depth_planes;
        MeshVertex { outcode, screen }
    }

    /// The outcode bits a vertex's projection cannot be used with: the
    /// depth planes' (near, and far with `with_far_clip`) and
    /// [`OUTCODE_UNUSABLE`]. A vertex with only side-plane bits set (off
    /// the viewport's guard band, in front of the eye) still has its
    /// exact projection in [`MeshVertex::screen`].
    pub(crate) fn unprojected_outcodes(&self) -> u8 {
        let depth_planes = self.frustum.planes().len().saturating_sub(4);
        ((1u8 << depth_planes) - 1) | UNUSABLE
    }

    /// Projects every vertex of `verts` into `out` (pairwise; extra
    /// entries of either slice are left alone).
    pub fn project_vertices<A: Varyings<S, VARYINGS>, const VARYINGS: usize>(
        &self,
        verts: &[Vertex<S, A>],
        out: &mut [MeshVertex<VARYINGS>],
    ) {
        for (o, v) in out.iter_mut().zip(verts) {
            *o = self.project_vertex(v);
        }
    }

    /// Triangle `tri` (indices into `verts` and `projected`, which
    /// [`Self::project_vertices`] filled from `verts`) ready to fill, with
    /// face culling applied: `Ok(None)` if culled or entirely outside.
    /// The same pixels as [`Self::project_polygon`] of the three vertices
    /// (see the [`mesh`](self) module).
    ///
    /// # Errors
    /// As [`Self::project_polygon`]; an index out of range is reported as
    /// [`DrawError::Projection`].
    #[inline]
    pub fn mesh_triangle<A, const VARYINGS: usize>(
        &self,
        verts: &[Vertex<S, A>],
        projected: &[MeshVertex<VARYINGS>],
        tri: [u32; 3],
    ) -> Result<Option<MeshTriangle<VARYINGS>>, DrawError>
    where
        A: Varyings<S, VARYINGS>,
    {
        let get = |i: u32| projected.get(i as usize).ok_or(DrawError::Projection);
        let (a, b, c) = (get(tri[0])?, get(tri[1])?, get(tri[2])?);
        if a.outcode | b.outcode | c.outcode == 0 {
            let s = [a.screen, b.screen, c.screen];
            return Ok(self.keep(&s).then_some(MeshTriangle::Inside(s)));
        }
        if a.outcode & b.outcode & c.outcode & !UNUSABLE != 0 {
            // All three outside one plane: clipping would leave nothing.
            return Ok(None);
        }
        let vget = |i: u32| verts.get(i as usize).copied().ok_or(DrawError::Projection);
        let poly = [vget(tri[0])?, vget(tri[1])?, vget(tri[2])?];
        Ok(self.project_polygon(&poly)?.map(MeshTriangle::Clipped))
    }

    /// Whether face culling keeps a projected polygon (the rule of
    /// [`Self::project_polygon`]).
    #[inline]
    #[must_use]
    pub fn keep<const VARYINGS: usize>(&self, screen: &[ScreenVertex<VARYINGS>]) -> bool {
        if self.cull == Cull::None {
            return true;
        }
        let Some(&last) = screen.last() else {
            return true;
        };
        let lim = crate::raster::COORD_LIMIT.unsigned_abs();
        let front = if let ([a, b, c], true) = (
            screen,
            screen
                .iter()
                .all(|v| v.x.unsigned_abs() <= lim && v.y.unsigned_abs() <= lim),
        ) {
            // A triangle within ±2^28: edge vectors below 2^29 (i32),
            // products below 2^58, so the i64 difference is exact (and
            // equals the shoelace sum); 32×32→64 multiplies.
            let mul = crate::scalar::widening_mul;
            let (e1x, e1y) = (b.x - a.x, b.y - a.y);
            let (e2x, e2y) = (c.x - a.x, c.y - a.y);
            mul(e1x, e2y) - mul(e1y, e2x) < 0
        } else {
            shoelace_front(screen, last)
        };
        !((self.cull == Cull::Back && !front) || (self.cull == Cull::Front && front))
    }
}

impl<S: Scalar> Pipeline<S> {
    /// [`Self::keep`] for a triangle whose three vertices are all inside
    /// the volume (outcode 0), given by their 28.4 screen positions.
    ///
    /// With a viewport whose guard-band rectangle lies within ±2^14 (any
    /// viewport up to 990 pixels with the 16-pixel guard band), the edge
    /// vectors are below 2^15, each product below 2^30 and their
    /// difference below 2^31: an exact `i32` cross product, two 32-bit
    /// multiplies. Larger viewports take [`Self::keep`]. (Always inlined:
    /// ARMv6-M had left this per-triangle test out of line, and inlined
    /// it took W1 from 5.74 M to 5.69 M instructions per frame, with the
    /// same .text.)
    #[inline(always)]
    #[must_use]
    pub(crate) fn keep_inside(&self, a: (i32, i32), b: (i32, i32), c: (i32, i32)) -> bool {
        if self.cull == Cull::None {
            return true;
        }
        if !self.guard_small {
            let v = |p: (i32, i32)| ScreenVertex::new(p.0, p.1, 0, []);
            return self.keep(&[v(a), v(b), v(c)]);
        }
        let (e1x, e1y) = (b.0 - a.0, b.1 - a.1);
        let (e2x, e2y) = (c.0 - a.0, c.1 - a.1);
        let front = e1x * e2y - e1y * e2x < 0;
        !((self.cull == Cull::Back && !front) || (self.cull == Cull::Front && front))
    }
}

/// Front-facing (negative shoelace area, y down) for any polygon.
///
/// Exact for any `i32` coordinates without i128 arithmetic: each product
/// is at most 2^62 in magnitude (exact in i64) and is added to a two-part
/// accumulator `hi·2^32 + lo` with `lo` kept in `[0, 2^32)`, so nothing
/// overflows for fewer than 2^29 vertices.
pub(super) fn shoelace_front<const VARYINGS: usize>(
    screen: &[ScreenVertex<VARYINGS>],
    last: ScreenVertex<VARYINGS>,
) -> bool {
    let (mut hi, mut lo) = (0i64, 0i64);
    let mut add = |p: i64| {
        // |lo + p| < 2^32 + 2^62; hi changes by at most 2^30 + 1 per call.
        let t = lo + p;
        hi += t >> 32;
        lo = t & 0xffff_ffff;
    };
    let mut prev = last;
    for &v in screen {
        add(crate::scalar::widening_mul(prev.x, v.y));
        add(-crate::scalar::widening_mul(prev.y, v.x));
        prev = v;
    }
    // The area is hi·2^32 + lo with 0 ≤ lo < 2^32: negative exactly when hi is.
    hi < 0
}

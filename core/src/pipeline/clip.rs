//! Sutherland–Hodgman clipping in view space.
//!
//! A polygon is clipped against each [`Plane`] of a [`Frustum`] in turn;
//! the part with `n·p + d ≥ 0` is kept. Intersections interpolate every
//! attribute with the same parameter as the coordinates.
//!
//! # Shared edges clip identically
//!
//! Two polygons that share an edge traverse it in opposite directions.
//! The intersection parameter is therefore always computed from the
//! edge's endpoints in a canonical order (lexicographic by x, y, z), so
//! both polygons get bit-identical intersection points, their projected
//! edges coincide exactly, and the top-left rule leaves no gap or overlap.

use super::vertex::{Attributes, Vertex, lerp_vertex, vertex_is_finite};
use crate::math::Vec3;
use crate::scalar::Scalar;
use core::cmp::Ordering;
use core::fmt;

/// Most vertices accepted in one input polygon.
pub const MAX_INPUT_VERTICES: usize = 8;

/// Most planes in a [`Frustum`]: near, far, left, right, top, bottom.
pub const MAX_PLANES: usize = 6;

/// Capacity of a clipped polygon.
///
/// Clipping a **convex** polygon against one plane replaces the run of
/// vertices outside by at most two intersection points, removing at least
/// one vertex whenever it adds two; so each plane adds at most one vertex,
/// and after [`MAX_PLANES`] planes a polygon of at most
/// [`MAX_INPUT_VERTICES`] has at most `8 + 6 = 14` vertices. Non-convex
/// input can exceed this; it is reported as
/// [`ClipError::TooManyVertices`], never truncated silently.
pub const MAX_CLIPPED_VERTICES: usize = MAX_INPUT_VERTICES + MAX_PLANES;

/// A clipped polygon: at most [`MAX_CLIPPED_VERTICES`] vertices.
pub type ClippedPolygon<S, A> = heapless::Vec<Vertex<S, A>, MAX_CLIPPED_VERTICES>;

/// Why a polygon could not be clipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ClipError {
    /// A coordinate or attribute is NaN or ±∞.
    NonFinite,
    /// More than [`MAX_INPUT_VERTICES`] input vertices, or (non-convex
    /// input only) more than [`MAX_CLIPPED_VERTICES`] after a plane.
    TooManyVertices,
}

impl fmt::Display for ClipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("polygon has a NaN or infinite coordinate or attribute"),
            Self::TooManyVertices => f.write_str("polygon has too many vertices to clip"),
        }
    }
}

impl core::error::Error for ClipError {}

/// A half-space `n·p + d ≥ 0` in view space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S> {
    /// Normal (need not be unit length).
    pub n: Vec3<S>,
    /// Offset.
    pub d: S,
}

impl<S: Scalar> Plane<S> {
    /// The plane `n·p + d ≥ 0`.
    #[must_use]
    pub const fn new(n: Vec3<S>, d: S) -> Self {
        Self { n, d }
    }

    /// Signed distance (scaled by |n|): ≥ 0 inside.
    #[must_use]
    #[inline]
    pub fn distance(&self, p: Vec3<S>) -> S {
        self.n.x * p.x + self.n.y * p.y + self.n.z * p.z + self.d
    }
}

/// A set of up to [`MAX_PLANES`] clip planes; the kept part of a polygon
/// is where every `n·p + d ≥ 0`.
///
/// # Shared edges clip identically
///
/// Intersection points are computed from each edge's endpoints in a
/// canonical order (lexicographic by x, y, z), not in traversal order, so
/// two polygons sharing an edge get bit-identical points on it and their
/// rasterized edges meet without gap or overlap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frustum<S> {
    planes: [Plane<S>; MAX_PLANES],
    count: usize,
}

impl<S: Scalar> Frustum<S> {
    /// A frustum from explicit planes (at most [`MAX_PLANES`]; extra
    /// planes are ignored).
    #[must_use]
    pub fn from_planes(planes: &[Plane<S>]) -> Self {
        let mut out = [Plane::new(Vec3::ZERO, S::ZERO); MAX_PLANES];
        let count = planes.len().min(MAX_PLANES);
        out[..count].copy_from_slice(&planes[..count]);
        Self { planes: out, count }
    }

    /// The planes.
    #[must_use]
    pub fn planes(&self) -> &[Plane<S>] {
        &self.planes[..self.count.min(MAX_PLANES)]
    }

    /// Clips a polygon against every plane in turn (Sutherland–Hodgman).
    ///
    /// A vertex exactly on a plane is kept as is (no duplicate is made);
    /// a polygon lying in a plane is kept whole. The result may have fewer
    /// than three vertices (nothing visible).
    ///
    /// # Errors
    /// [`ClipError::NonFinite`] for NaN or ±∞ input (floats);
    /// [`ClipError::TooManyVertices`] as documented there.
    pub fn clip<A: Attributes<S>>(
        &self,
        poly: &[Vertex<S, A>],
    ) -> Result<ClippedPolygon<S, A>, ClipError> {
        if poly.len() > MAX_INPUT_VERTICES {
            return Err(ClipError::TooManyVertices);
        }
        if !poly.iter().all(vertex_is_finite) {
            return Err(ClipError::NonFinite);
        }
        let mut cur = ClippedPolygon::new();
        for v in poly {
            cur.push(*v).map_err(|_| ClipError::TooManyVertices)?;
        }
        // Fixed point: a bound on every coordinate of every polygon below.
        // Intersection points lie between their edge's endpoints (the
        // fallback in `lerp` within a step of them), so the input's
        // largest magnitude plus one bounds them all.
        let m = if S::IS_FLOAT {
            S::ZERO
        } else {
            max_magnitude(poly) + S::ONE
        };
        // Ping-pong between two buffers by reference; a plane that cuts
        // nothing leaves the polygon where it is. Swapping the buffers
        // themselves after every plane moved 4 to 5 KB per clipped
        // triangle (three copies of two 14-vertex buffers, six planes).
        // Scene frames (`bash tests/mcu/run`), before -> after: ARMv6-M
        // I16F16 corridor 7 107 806 -> 6 824 282 instructions,
        // corridor-affine 3 622 225 -> 3 351 535, bunny 9 069 577 ->
        // 9 017 119; Cortex-M4 f32 corridor 5 032 631 -> 4 867 241,
        // corridor-affine 2 539 330 -> 2 373 892, bunny 6 191 371 ->
        // 6 118 390. The stack, which held the swap's copies, is 416 bytes
        // smaller in the Gouraud firmware on thumbv6m and 560 in the
        // texture one; .text is 224 and 284 bytes larger.
        let mut other = ClippedPolygon::new();
        let mut in_cur = true;
        for plane in self.planes() {
            let (src, dst) = if in_cur {
                (&mut cur, &mut other)
            } else {
                (&mut other, &mut cur)
            };
            if src.len() < 3 {
                src.clear();
                break;
            }
            if clip_one(plane, m, src, dst)? {
                in_cur = !in_cur;
            }
        }
        let mut out = if in_cur { cur } else { other };
        if out.len() < 3 {
            out.clear();
        }
        Ok(out)
    }
}

/// The largest |coordinate| of the polygon's vertices (0 if empty).
fn max_magnitude<S: Scalar, A: Attributes<S>>(poly: &[Vertex<S, A>]) -> S {
    poly.iter().fold(S::ZERO, |m, v| {
        m.max_of(v.pos.x.abs())
            .max_of(v.pos.y.abs())
            .max_of(v.pos.z.abs())
    })
}

/// Lexicographic order on positions; only used on finite values.
fn canonical_first<S: Scalar>(a: Vec3<S>, b: Vec3<S>) -> bool {
    let key = |v: Vec3<S>| [v.x, v.y, v.z];
    for (x, y) in key(a).into_iter().zip(key(b)) {
        match x.partial_cmp(&y) {
            Some(Ordering::Less) => return true,
            Some(Ordering::Greater) => return false,
            _ => {}
        }
    }
    true
}

/// The point where edge a–b crosses the plane, with `da`, `db` of strictly
/// opposite signs, computed from the canonically first endpoint.
fn intersect<S: Scalar, A: Attributes<S>>(
    a: &Vertex<S, A>,
    da: S,
    b: &Vertex<S, A>,
    db: S,
) -> Vertex<S, A> {
    let (p, dp, q, dq) = if canonical_first(a.pos, b.pos) {
        (a, da, b, db)
    } else {
        (b, db, a, da)
    };
    // dp and dq have opposite signs, so |dp − dq| ≥ |dp| and t ∈ [0, 1]
    // up to rounding; clamp for fixed point, whose division saturates.
    //
    // Floats with huge (finite) coordinates: n·p + d or dp − dq can
    // overflow to ±∞, and `dp / (dp − dq)` becomes 0 or NaN, which picked
    // the vertex *outside* the plane (found by the `clip` fuzz target).
    // Halve both when only the difference overflows, and use the limit
    // when a distance itself is infinite.
    let den = dp - dq;
    let t = if den.is_finite() {
        dp / den
    } else {
        (dp * S::HALF) / (dp * S::HALF - dq * S::HALF)
    };
    let t = if t.is_finite() {
        t.clamp_to(S::ZERO, S::ONE)
    } else if dp.is_finite() {
        // |dq| = ∞: the crossing tends to p.
        S::ZERO
    } else if dq.is_finite() {
        S::ONE
    } else if dp > S::ZERO {
        // Both infinite: keep the endpoint inside.
        S::ZERO
    } else {
        S::ONE
    };
    lerp_vertex(p, q, t)
}

/// The same half-space with its largest coefficient scaled into
/// `[1/8, 1/4)` by a power of two (floats only). Scaling by a power of two
/// is exact, so signs and the ratios `dp / (dp − dq)` are unchanged, but
/// `n·p + d` can no longer overflow for finite `p`: a huge coefficient
/// (e.g. `−f32::MAX`) made every distance ±∞ and picked intersection
/// points outside the plane (found by the `clip` fuzz target). Fixed
/// point is returned unchanged (see `fitted`).
fn scaled<S: Scalar>(plane: &Plane<S>) -> Plane<S> {
    if !S::IS_FLOAT {
        return *plane;
    }
    let n = plane.n;
    let m =
        n.x.abs()
            .max_of(n.y.abs())
            .max_of(n.z.abs())
            .max_of(plane.d.abs())
            .to_f64();
    if !(m > 0.0 && m.is_finite()) {
        return *plane;
    }
    // 2^e ≤ m < 2^(e+1) (subnormal m: e = −1023, good enough), k = 2^−(e+3).
    let e = ((m.to_bits() >> 52) & 0x7ff) as i64 - 1023;
    let ke = -(e + 3);
    let kf = if ke >= -1022 {
        f64::from_bits(((ke + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (ke + 1074))
    };
    let k = S::from_f64(kf);
    if k.to_f64() != kf {
        // Not a power of two in S (beyond f32's range): leave it.
        return *plane;
    }
    Plane::new(n * k, plane.d * k)
}

/// Fixed point: the plane halved (a power of two, exact up to the last
/// bit of each coefficient, so the kept side is the same) until
/// `Σ|n_k|·m + |d| ≤ MAX/2`, where `m` bounds every coordinate of the
/// polygon: then no distance `n·p + d` saturates, nor the difference of
/// two. Saturated distances moved intersection points off the plane, up
/// to 146 units outside a side plane `x ≤ 282.5 z` (found by the `clip`
/// fuzz target). The bound is taken with the saturating operators (all
/// terms are ≥ 0, so saturation only overestimates it). A plane that
/// already fits, which is every plane of a scene within
/// `±MAX/(2·Σ|n|)`, is returned unchanged.
fn fitted<S: Scalar>(plane: &Plane<S>, m: S) -> Plane<S> {
    let half_max = S::MAX * S::HALF;
    let bound = |pl: &Plane<S>| (pl.n.x.abs() + pl.n.y.abs() + pl.n.z.abs()) * m + pl.d.abs();
    let mut pl = *plane;
    // 32 halvings take any I16F16 coefficient to zero.
    for _ in 0..32 {
        if bound(&pl) <= half_max {
            break;
        }
        pl = Plane::new(pl.n * S::HALF, pl.d * S::HALF);
    }
    pl
}

/// Clips `input` against one plane into `out`. Returns `false`, with
/// `out` untouched, when every vertex lies inside or on the plane: the
/// clipped polygon is `input` itself then (a crossing needs a vertex
/// outside).
fn clip_one<S: Scalar, A: Attributes<S>>(
    plane: &Plane<S>,
    m: S,
    input: &ClippedPolygon<S, A>,
    out: &mut ClippedPolygon<S, A>,
) -> Result<bool, ClipError> {
    let plane = &if S::IS_FLOAT {
        scaled(plane)
    } else {
        fitted(plane, m)
    };
    // Every distance once, in order. "Outside" is "not `>= 0`", as the
    // loop below reads it: a NaN distance (which finite input and the
    // fitted plane should not give) takes the loop, which drops it.
    let mut dist = [S::ZERO; MAX_CLIPPED_VERTICES];
    let mut outside = false;
    for (d, v) in dist.iter_mut().zip(input.iter()) {
        *d = plane.distance(v.pos);
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        {
            outside |= !(*d >= S::ZERO);
        }
    }
    if !outside {
        return Ok(false);
    }
    out.clear();
    let n = input.len();
    let (Some(last), Some(&d_last)) = (input.last(), dist.get(n.wrapping_sub(1))) else {
        return Ok(true);
    };
    let mut s = last;
    let mut ds = d_last;
    let full = |_| ClipError::TooManyVertices;
    for (e, &de) in input.iter().zip(dist.iter()) {
        if de >= S::ZERO {
            // A crossing needs strictly opposite signs: a vertex exactly on
            // the plane is itself the crossing point.
            if ds < S::ZERO && de > S::ZERO {
                out.push(intersect(s, ds, e, de)).map_err(full)?;
            }
            out.push(*e).map_err(full)?;
        } else if ds > S::ZERO {
            out.push(intersect(s, ds, e, de)).map_err(full)?;
        }
        s = e;
        ds = de;
    }
    Ok(true)
}

//! Planar polygons (convex or simple concave) with precomputed plane,
//! dominant axis and 2D edge equations, and three of the four inclusion
//! tests (the fourth, slabs, is in [`SlabIndex`](super::SlabIndex)).
//!
//! # Reference plane
//!
//! The normal's dominant axis k (largest |n_k|, the lowest index on a tie)
//! is dropped: a point (p₀, p₁, p₂) projects to `(p_{k+1}, p_{k+2})`
//! (indices mod 3). The cyclic order keeps the frame right-handed, so the
//! projected polygon is counter-clockwise exactly when `n_k > 0`. All 2D
//! statements below ("x", "y", "left", "up") refer to this frame, with y
//! up.
//!
//! # Edge equations
//!
//! Edge i runs from vertex `a = v_i` to `v_{i+1}` with `d = v_{i+1} − v_i`.
//! Its equation is `E(p) = A·x + B·y + C` with `A = −d.y`, `B = d.x`,
//! `C = d.y·a.x − d.x·a.y`, evaluated as `d.x·(p.y − a.y) − d.y·(p.x − a.x)`
//! (relative to `a`, which keeps the terms small near the polygon). E is
//! twice the signed area of (a, b, p) for the end vertex `b = v_{i+1}`:
//! positive when p is left of the edge. The inclusion tests need only its
//! sign ([`Edge2::sign`]), and that sign is **exact** in every scalar type:
//! it is [`Scalar::orient2d`] of the edge's two original vertices `a`, `b`
//! and p (never of the rounded `d` or of rounded coefficients), exact in
//! `i128` for fixed point and by a filtered exact predicate for floats
//! (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
//! Robust Geometric Predicates", 1997). The projection only drops a
//! coordinate, so it is exact too. [`Edge2::value`] returns the number
//! itself, rounded (fixed point: each product exact with one rounding,
//! [`Scalar::sub_mul_noting_overflow`]; `None` on overflow).
//!
//! # Boundary policy
//!
//! A point p is inside exactly when the point `p' = p + (δ, δ·η)` is inside,
//! for infinitesimals `0 < η ≪ δ`: p is nudged right, and then (only
//! relevant on horizontal edges) up. `p'` never lies on a line through two
//! distinct vertices, so for each edge it is strictly left or right:
//!
//! ```text
//! owns(edge, p) = E(p) > 0  or  (E(p) = 0 and (d.y < 0 or (d.y = 0 and d.x > 0)))
//! ```
//!
//! (for a counter-clockwise polygon; a clockwise one uses its negation).
//! Geometrically, in either orientation: a point on an edge belongs to the
//! polygon when the polygon lies on the edge's +x side, or, for a
//! horizontal edge, on its +y side. Left and bottom edges are closed,
//! right and top edges open, like the top-left fill rule mirrored for
//! y-up. For a vertex, the neighborhood just to its right (and then just
//! above) decides. Consequences:
//! - Two polygons that share an edge with opposite directions (as in any
//!   consistently oriented partition of the plane) never both claim a
//!   point on it, and for a point inside the shared edge exactly one does.
//! - A tiling of a region claims every point of its interior exactly once.
//! - All four tests compute the same predicate from exact signs, so for
//!   every finite query they agree with each other and with the exact
//!   answer for the vertices as given, in every scalar type: off the
//!   boundary by the point's true position, on it by this rule (a point
//!   one unit in the last place off an edge is classified by the side it
//!   is on, however long the edge).
//!
//! The crossing test (1) in this form counts an edge when exactly one end
//! has `y ≤ p.y` (the half-open rule: a vertex at the ray's height counts
//! as below) and `p` is strictly left of the edge directed upward.

use super::Ray;
use super::checked::{point_at, sub2};
use super::plane::Plane;
use crate::math::{Vec2, Vec3};
use crate::scalar::Scalar;
use core::cmp::Ordering;
use core::fmt;

/// Why a [`Polygon`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum PolygonError {
    /// A vertex is NaN or ±∞.
    NonFinite,
    /// Fewer than three distinct consecutive vertices, or zero area (all
    /// vertices collinear).
    Degenerate,
    /// More distinct vertices than the capacity `N`.
    TooManyVertices {
        /// The capacity `N`.
        capacity: usize,
    },
    /// A fixed-point edge vector overflows.
    Overflow,
    /// A vertex is farther from the best-fit plane than 64·ε·(1 + the
    /// largest coordinate magnitude).
    NotPlanar,
}

impl fmt::Display for PolygonError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NonFinite => f.write_str("polygon vertex contains NaN or infinity"),
            Self::Degenerate => f.write_str("polygon has fewer than 3 vertices or zero area"),
            Self::TooManyVertices { capacity } => {
                write!(f, "polygon has more than {capacity} vertices")
            }
            Self::Overflow => f.write_str("polygon edge vector overflows the scalar type"),
            Self::NotPlanar => f.write_str("polygon vertices are not coplanar"),
        }
    }
}

impl core::error::Error for PolygonError {}

/// One directed 2D edge: start `a`, end `b` (the next vertex) and the
/// vector `d` between them. See the [module docs](self) for the equation
/// and the boundary policy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge2<S> {
    /// Start vertex.
    pub a: Vec2<S>,
    /// End vertex (the next vertex of the polygon, as given).
    pub b: Vec2<S>,
    /// `b − a`: rounded to `S` for floats (its component signs are still
    /// exact), exact for fixed point. The predicates use `a` and `b`.
    pub d: Vec2<S>,
}

impl<S: Scalar> Edge2<S> {
    /// The coefficients (A, B, C) of `E(p) = A·x + B·y + C`; `None` if C
    /// overflows. [`Self::value`] evaluates the same function relative to
    /// `a` instead.
    #[must_use]
    pub fn coefficients(&self) -> Option<(S, S, S)> {
        let mut of = false;
        let c = S::ZERO
            .sub_mul_noting_overflow(-self.d.y, self.a.x, &mut of)
            .sub_mul_noting_overflow(self.d.x, self.a.y, &mut of);
        (!of && c.is_finite()).then_some((-self.d.y, self.d.x, c))
    }

    /// `E(p) = d.x·(p.y − a.y) − d.y·(p.x − a.x)`: positive left of the
    /// edge. `None` on overflow or a non-finite value.
    #[must_use]
    pub fn value(&self, p: Vec2<S>) -> Option<S> {
        let r = sub2(p, self.a)?;
        let mut of = false;
        let e = S::ZERO
            .sub_mul_noting_overflow(self.d.y, r.x, &mut of)
            .sub_mul_noting_overflow(-self.d.x, r.y, &mut of);
        (!of && e.is_finite()).then_some(e)
    }

    /// The exact sign of `E(p)`, from `a`, `b` and `p`
    /// ([`Scalar::orient2d`]); `None` only when `p` is not finite.
    #[must_use]
    pub fn sign(&self, p: Vec2<S>) -> Option<Ordering> {
        S::orient2d(arr(self.a), arr(self.b), arr(p))
    }

    /// Whether the nudged point `p'` is left of the edge (the boundary
    /// policy in the [module docs](self)). `None` when [`Self::sign`] is.
    #[must_use]
    pub fn owns(&self, p: Vec2<S>) -> Option<bool> {
        owns_segment(self.a, self.b, p)
    }
}

/// The boundary policy for the directed segment a→b, exactly.
fn owns_segment<S: Scalar>(a: Vec2<S>, b: Vec2<S>, p: Vec2<S>) -> Option<bool> {
    Some(owns_from(
        S::orient2d(arr(a), arr(b), arr(p))?,
        b.y.partial_cmp(&a.y)?,
        b.x.partial_cmp(&a.x)?,
    ))
}

fn arr<S: Scalar>(v: Vec2<S>) -> [S; 2] {
    [v.x, v.y]
}

/// The boundary policy from the signs of `E(p)`, `d.y` and `d.x`.
fn owns_from(e: Ordering, dy: Ordering, dx: Ordering) -> bool {
    e == Ordering::Greater
        || (e == Ordering::Equal
            && (dy == Ordering::Less || (dy == Ordering::Equal && dx == Ordering::Greater)))
}

/// Which inclusion test [`Polygon::contains`] runs.
///
/// The fourth test, slab subdivision, needs caller storage and lives in
/// [`SlabIndex`](super::SlabIndex).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum InclusionTest {
    /// (1) Odd crossings of a ray towards +x (Jordan curve theorem); any
    /// simple polygon. O(n).
    #[default]
    Crossing,
    /// (2) Inside every edge's half-plane; convex polygons. O(n).
    HalfPlane,
    /// (3) Binary search over the triangle fan from vertex 0, then one edge
    /// test; convex polygons. O(log n).
    Fan,
}

/// A planar polygon with up to `N` vertices, with its plane, the dominant
/// axis of its normal and its 2D edges precomputed.
///
/// The polygon must be simple (edges meet only at shared vertices;
/// this O(n²) property is not checked) and its vertices coplanar (checked
/// to a tolerance, [`PolygonError::NotPlanar`]): the plane is the Newell
/// normal through vertex 0, and inclusion is decided in the projection. Consecutive duplicate vertices are dropped.
/// Convex and concave polygons are both accepted; for a polygon that is not
/// convex ([`Self::is_convex`] is false), [`InclusionTest::HalfPlane`] and
/// [`InclusionTest::Fan`] fall back to [`InclusionTest::Crossing`].
///
/// Construction does its one-off bookkeeping (Newell normal, orientation)
/// in `f64`; queries use only `S` and the exact [`Scalar::orient2d`].
#[derive(Clone, Debug)]
pub struct Polygon<S, const N: usize> {
    plane: Plane<S>,
    axis: usize,
    ccw: bool,
    convex: bool,
    test: InclusionTest,
    edges: heapless::Vec<Edge2<S>, N>,
}

impl<S: Scalar, const N: usize> Polygon<S, N> {
    /// Builds the polygon from its vertices in order (either orientation),
    /// with [`InclusionTest::Crossing`] selected.
    ///
    /// # Errors
    /// See [`PolygonError`].
    pub fn new(vertices: &[Vec3<S>]) -> Result<Self, PolygonError> {
        if vertices.iter().any(|v| !v.is_finite()) {
            return Err(PolygonError::NonFinite);
        }
        if vertices.len() < 3 {
            return Err(PolygonError::Degenerate);
        }
        let f = |v: Vec3<S>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
        let v0 = f(vertices[0]);
        // Newell's normal, relative to v0: twice the vector area.
        let mut n = [0.0f64; 3];
        for i in 1..vertices.len() - 1 {
            let p = f(vertices[i]);
            let q = f(vertices[i + 1]);
            let a = [p[0] - v0[0], p[1] - v0[1], p[2] - v0[2]];
            let b = [q[0] - v0[0], q[1] - v0[1], q[2] - v0[2]];
            n[0] += a[1] * b[2] - a[2] * b[1];
            n[1] += a[2] * b[0] - a[0] * b[2];
            n[2] += a[0] * b[1] - a[1] * b[0];
        }
        let mut axis = 0;
        for k in 1..3 {
            if n[k].abs() > n[axis].abs() {
                axis = k;
            }
        }
        if !(n[axis].is_finite() && n[axis] != 0.0) {
            return Err(PolygonError::Degenerate);
        }
        // Coplanarity, against the unit Newell normal through v0.
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let mut biggest = 0.0f64;
        let mut off = 0.0f64;
        for &v in vertices {
            let p = f(v);
            biggest = biggest.max(p[0].abs()).max(p[1].abs()).max(p[2].abs());
            let r = [p[0] - v0[0], p[1] - v0[1], p[2] - v0[2]];
            off = off.max(((r[0] * n[0] + r[1] * n[1] + r[2] * n[2]) / len).abs());
        }
        if off > 64.0 * S::EPSILON.to_f64() * (1.0 + biggest) {
            return Err(PolygonError::NotPlanar);
        }
        let m = n[axis].abs();
        let normal = Vec3::new(
            S::from_f64(n[0] / m),
            S::from_f64(n[1] / m),
            S::from_f64(n[2] / m),
        );
        let plane = Plane::new(vertices[0], normal).map_err(|_| PolygonError::Degenerate)?;

        let mut pts: heapless::Vec<Vec2<S>, N> = heapless::Vec::new();
        for &v in vertices {
            let p = project(axis, v);
            if pts.last() == Some(&p) {
                continue;
            }
            pts.push(p)
                .map_err(|_| PolygonError::TooManyVertices { capacity: N })?;
        }
        while pts.len() > 1 && pts.last() == pts.first() {
            pts.pop();
        }
        if pts.len() < 3 {
            return Err(PolygonError::Degenerate);
        }
        let mut edges = heapless::Vec::new();
        for i in 0..pts.len() {
            let a = pts[i];
            let b = pts[(i + 1) % pts.len()];
            let d = sub2(b, a).ok_or(PolygonError::Overflow)?;
            // Cannot fail: edges and pts have the same capacity.
            let _ = edges.push(Edge2 { a, b, d });
        }
        let ccw = n[axis] > 0.0;
        let convex = is_convex(&edges, ccw);
        Ok(Self {
            plane,
            axis,
            ccw,
            convex,
            test: InclusionTest::Crossing,
            edges,
        })
    }

    /// The same polygon with `test` selected for [`Self::intersect`].
    #[must_use]
    pub fn with_test(mut self, test: InclusionTest) -> Self {
        self.test = test;
        self
    }

    /// The selected inclusion test.
    #[must_use]
    pub fn test(&self) -> InclusionTest {
        self.test
    }

    /// The polygon's plane (through vertex 0, unit Newell normal: the
    /// vertices run counter-clockwise seen from the side it points to).
    #[must_use]
    pub fn plane(&self) -> &Plane<S> {
        &self.plane
    }

    /// The dropped axis k (0, 1 or 2) of the reference plane.
    #[must_use]
    pub fn dominant_axis(&self) -> usize {
        self.axis
    }

    /// Whether the projected polygon is counter-clockwise (y up).
    #[must_use]
    pub fn is_ccw(&self) -> bool {
        self.ccw
    }

    /// Whether the projected polygon is convex (collinear vertices
    /// allowed). Decided exactly at construction.
    #[must_use]
    pub fn is_convex(&self) -> bool {
        self.convex
    }

    /// The projected edges, in vertex order.
    #[must_use]
    pub fn edges(&self) -> &[Edge2<S>] {
        &self.edges
    }

    /// Projects a 3D point to the reference plane (drops the dominant axis).
    #[must_use]
    pub fn project(&self, p: Vec3<S>) -> Vec2<S> {
        project(self.axis, p)
    }

    /// Whether the projected point `p` is inside, by the given test and the
    /// boundary policy of the [module docs](self). Overflow means outside.
    #[must_use]
    pub fn contains(&self, p: Vec2<S>, test: InclusionTest) -> bool {
        match test {
            InclusionTest::Crossing => self.contains_crossing(p),
            InclusionTest::HalfPlane => self.contains_half_plane(p),
            InclusionTest::Fan => self.contains_fan(p),
        }
    }

    /// Test (1): odd-crossing rule; any simple polygon.
    #[must_use]
    pub fn contains_crossing(&self, p: Vec2<S>) -> bool {
        let mut inside = false;
        for e in self.edges.iter() {
            let b = e.b;
            // Half-open in y: a vertex at the ray's height counts as below.
            if (e.a.y <= p.y) == (b.y <= p.y) {
                continue;
            }
            let Some(v) = e.sign(p) else {
                return false;
            };
            // Strictly left of the edge directed upward.
            let left_of_upward = if e.d.y > S::ZERO {
                v == Ordering::Greater
            } else {
                v == Ordering::Less
            };
            inside ^= left_of_upward;
        }
        inside
    }

    /// Test (2): the half-plane test; convex polygons (falls back to test
    /// (1) otherwise).
    #[must_use]
    pub fn contains_half_plane(&self, p: Vec2<S>) -> bool {
        if !self.convex {
            return self.contains_crossing(p);
        }
        self.edges.iter().all(|e| e.owns(p) == Some(self.ccw))
    }

    /// Test (3): binary search over the fan of triangles (v₀, vᵢ, vᵢ₊₁),
    /// then one edge test; convex polygons (falls back to test (1)
    /// otherwise). O(log n).
    #[must_use]
    pub fn contains_fan(&self, p: Vec2<S>) -> bool {
        if !self.convex {
            return self.contains_crossing(p);
        }
        self.fan(p).unwrap_or(false)
    }

    fn fan(&self, p: Vec2<S>) -> Option<bool> {
        let e = &self.edges;
        let n = e.len();
        let v0 = e[0].a;
        // "Inward": left for a counter-clockwise polygon, right otherwise
        // (the mirror image of the same nudged-point predicate).
        let inward = |edge: &Edge2<S>| edge.owns(p).map(|l| l == self.ccw);
        if !(inward(&e[0])? && inward(&e[n - 1])?) {
            return Some(false);
        }
        // Invariant: p' is inward of the diagonal v0→v_lo and not of
        // v0→v_hi. The diagonals turn monotonically for a convex polygon
        // and p' lies within their cone, so the predicate is monotone.
        let (mut lo, mut hi) = (1, n - 1);
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            // Exact, from the two vertices (no rounded or overflowing
            // v_mid − v0).
            let diag_inward = owns_segment(v0, e[mid].a, p)? == self.ccw;
            if diag_inward {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        inward(&e[lo])
    }

    /// The nearest `t > t_min` at which the ray meets the polygon, using the
    /// selected test: plane hit, then inclusion of the projected hit point.
    #[must_use]
    pub fn intersect(&self, ray: &Ray<S>, t_min: S) -> Option<S> {
        let t = self.plane.intersect(ray, t_min)?;
        let x = point_at(ray.origin(), ray.dir(), t)?;
        self.contains(self.project(x), self.test).then_some(t)
    }
}

/// Drops axis `k`: `(p_{k+1}, p_{k+2})`.
pub(crate) fn project<S: Scalar>(k: usize, p: Vec3<S>) -> Vec2<S> {
    let c = p.to_array();
    Vec2::new(c[(k + 1) % 3], c[(k + 2) % 3])
}

/// Convexity: every turn (exact, [`Scalar::orient2d`]) has the polygon's
/// orientation or is straight ahead, and the edge directions go round once
/// (the sign of d.x changes exactly twice, which rules out star polygons).
fn is_convex<S: Scalar>(edges: &[Edge2<S>], ccw: bool) -> bool {
    let n = edges.len();
    let dir = |e: &Edge2<S>| (e.d.x.to_f64(), e.d.y.to_f64());
    let mut changes = 0;
    let mut last_sign = 0i8;
    let mut first_sign = 0i8;
    for i in 0..n {
        let (ax, ay) = dir(&edges[i]);
        let (bx, by) = dir(&edges[(i + 1) % n]);
        let next = &edges[(i + 1) % n];
        let Some(turn) = S::orient2d(arr(edges[i].a), arr(edges[i].b), arr(next.b)) else {
            return false;
        };
        if turn != Ordering::Equal && (turn == Ordering::Greater) != ccw {
            return false;
        }
        // Exactly collinear: the rounded directions are parallel too, and
        // their dot product has the exact sign.
        if turn == Ordering::Equal && ax * bx + ay * by < 0.0 {
            return false;
        }
        let s = if ax > 0.0 {
            1
        } else if ax < 0.0 {
            -1
        } else {
            0
        };
        if s != 0 {
            if first_sign == 0 {
                first_sign = s;
            } else if s != last_sign {
                changes += 1;
            }
            last_sign = s;
        }
    }
    if last_sign != first_sign {
        changes += 1;
    }
    changes <= 2
}

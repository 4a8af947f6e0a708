//! Inclusion test (4): slab subdivision with binary search, for simple
//! (concave or convex) polygons, stored in caller-supplied slices.
//!
//! The distinct vertex y values cut the reference plane into horizontal
//! slabs `[y_k, y_{k+1})`. No vertex lies strictly inside a slab, so the
//! non-horizontal edges that cross slab k cross all of it and, the polygon
//! being simple, never cross each other there: they are totally ordered
//! left to right. A query finds its slab by binary search over the y
//! values and counts the edges right of the point by a second binary
//! search; the point is inside when that count is odd. Both searches use
//! the same nudged-point predicate as the other tests (see
//! [`polygon`](super::Polygon)'s boundary policy), so the answers agree.
//!
//! # Storage
//!
//! [`SlabIndex::build`] takes three slices from the caller:
//! - `ys`: at least n entries (n = [`Polygon::edges`]`().len()`), for the
//!   sorted distinct y values;
//! - `starts`: at least n entries, slab k's edges are
//!   `edges[starts[k]..starts[k + 1]]`;
//! - `edges`: the total number of (slab, edge) pairs: at most n·(n − 1),
//!   since each of the ≤ n − 1 slabs is crossed by at most n edges (usually
//!   far fewer). When the slice is
//!   too short [`SlabError::EdgeStorage`] reports the exact number needed,
//!   so a caller can size it with one failed call.
//!
//! Building is O(n²) time (plus a sort per slab) and is done once per
//! polygon; a query is O(log n).

use super::Polygon;
use super::polygon::Edge2;
use crate::math::Vec2;
use crate::scalar::Scalar;
use core::cmp::Ordering;
use core::fmt;

/// Why a [`SlabIndex`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum SlabError {
    /// `ys` or `starts` is shorter than the polygon's vertex count.
    VertexStorage {
        /// Entries needed in each of `ys` and `starts`.
        needed: usize,
    },
    /// `edges` is too short.
    EdgeStorage {
        /// Entries needed.
        needed: usize,
    },
    /// More than `u32::MAX` (slab, edge) pairs.
    TooLarge,
}

impl fmt::Display for SlabError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::VertexStorage { needed } => {
                write!(f, "slab index needs {needed} entries for ys and starts")
            }
            Self::EdgeStorage { needed } => write!(f, "slab index needs {needed} edge entries"),
            Self::TooLarge => f.write_str("slab index has more than u32::MAX entries"),
        }
    }
}

impl core::error::Error for SlabError {}

/// The slab subdivision of one [`Polygon`], borrowing it and the caller's
/// storage.
///
/// # Guarantees
/// After [`Self::build`] succeeds, [`Self::contains`] never panics and
/// never indexes out of bounds.
#[derive(Debug)]
pub struct SlabIndex<'a, S, const N: usize> {
    poly: &'a Polygon<S, N>,
    ys: &'a [S],
    starts: &'a [u32],
    edges: &'a [u32],
}

impl<'a, S: Scalar, const N: usize> SlabIndex<'a, S, N> {
    /// Builds the index for `poly` in the given storage (see the
    /// [module docs](self) for the sizes).
    ///
    /// # Errors
    /// [`SlabError`] when a slice is too short (with the size needed).
    pub fn build(
        poly: &'a Polygon<S, N>,
        ys: &'a mut [S],
        starts: &'a mut [u32],
        edges: &'a mut [u32],
    ) -> Result<Self, SlabError> {
        let pe = poly.edges();
        let n = pe.len();
        if ys.len() < n || starts.len() < n {
            return Err(SlabError::VertexStorage { needed: n });
        }
        for (y, e) in ys.iter_mut().zip(pe) {
            *y = e.a.y;
        }
        let (ys, _) = ys.split_at_mut(n);
        // Vertices are finite (checked by Polygon::new): the order is total.
        ys.sort_unstable_by(|a, b| a.partial_cmp(b).unwrap_or(core::cmp::Ordering::Equal));
        let mut m = 0;
        for i in 0..n {
            if i == 0 || ys[i] != ys[m - 1] {
                ys[m] = ys[i];
                m += 1;
            }
        }
        let ys: &'a [S] = &ys[..m];
        let slabs = m - 1;

        // Count first, so a short `edges` slice is reported exactly.
        let mut needed = 0usize;
        for i in 0..n {
            let (lo, hi) = span(pe, i);
            if lo < hi {
                let first = ys.partition_point(|&y| y < lo);
                let last = ys.partition_point(|&y| y < hi);
                needed += last - first;
            }
        }
        if needed > u32::MAX as usize {
            return Err(SlabError::TooLarge);
        }
        if edges.len() < needed {
            return Err(SlabError::EdgeStorage { needed });
        }
        let mut count = 0usize;
        for k in 0..slabs {
            starts[k] = count as u32;
            let (y0, y1) = (ys[k], ys[k + 1]);
            for i in 0..n {
                let (lo, hi) = span(pe, i);
                if lo <= y0 && hi >= y1 && lo < hi {
                    edges[count] = i as u32;
                    count += 1;
                }
            }
            // Order left to right inside the slab, exactly (see
            // `left_to_right`).
            let start = starts[k] as usize;
            edges[start..count]
                .sort_unstable_by(|&a, &b| left_to_right(&pe[a as usize], &pe[b as usize]));
        }
        starts[slabs] = count as u32;
        Ok(Self {
            poly,
            ys,
            starts: &starts[..=slabs],
            edges: &edges[..count],
        })
    }

    /// The polygon this index was built for.
    #[must_use]
    pub fn polygon(&self) -> &'a Polygon<S, N> {
        self.poly
    }

    /// Number of slabs.
    #[must_use]
    pub fn slab_count(&self) -> usize {
        self.starts.len() - 1
    }

    /// Test (4): whether the projected point `p` is inside, with the
    /// boundary policy of [`Polygon`]. Overflow means outside.
    #[must_use]
    pub fn contains(&self, p: Vec2<S>) -> bool {
        // The nudged point is just above p.y: slab k has y_k ≤ p.y < y_{k+1}.
        let idx = self.ys.partition_point(|&y| y <= p.y);
        if idx == 0 || idx >= self.ys.len() {
            return false;
        }
        let k = idx - 1;
        let (s, e) = (self.starts[k] as usize, self.starts[k + 1] as usize);
        let list = &self.edges[s..e];
        let pe = self.poly.edges();
        let mut overflow = false;
        // Edges left of p' first, then edges right of it; p' is right of
        // the upward-directed edge unless strictly left (same predicate as
        // the crossing test).
        let left_count = list.partition_point(|&i| {
            let edge = &pe[i as usize];
            match edge.sign(p) {
                Some(v) => {
                    !(if edge.d.y > S::ZERO {
                        v == core::cmp::Ordering::Greater
                    } else {
                        v == core::cmp::Ordering::Less
                    })
                }
                None => {
                    overflow = true;
                    false
                }
            }
        });
        !overflow && (list.len() - left_count) % 2 == 1
    }
}

/// The order of two edges that both cross one slab, left to right, from
/// exact orientations of their original vertices only.
///
/// Edges of a simple polygon meet only at shared vertices. Direct both
/// upward, `i = p₀→p₁`, `j = q₀→q₁`. If `q₀.y ≥ p₀.y`, then q₀ lies within
/// i's height range, and if it is strictly right of i so is all of j up to
/// the lower top (the segments cannot cross), in particular inside the
/// slab; if q₀ is on the line of i it is the shared vertex p₀, and the
/// lower of the two tops decides the same way. Otherwise p₀ lies within
/// j's range and decides, mirrored.
fn left_to_right<S: Scalar>(i: &Edge2<S>, j: &Edge2<S>) -> Ordering {
    let up = |e: &Edge2<S>| {
        if e.a.y <= e.b.y {
            ([e.a.x, e.a.y], [e.b.x, e.b.y])
        } else {
            ([e.b.x, e.b.y], [e.a.x, e.a.y])
        }
    };
    let (p0, p1) = up(i);
    let (q0, q1) = up(j);
    // Finite vertices: never `None`.
    let o = |a, b, c| S::orient2d(a, b, c).unwrap_or(Ordering::Equal);
    // `Less` means i comes first: a point of j right of i (orientation
    // `Less`), or a point of i left of j (orientation `Greater`).
    let by_i = |c| o(p0, p1, c);
    let by_j = |c| o(q0, q1, c).reverse();
    if q0[1] >= p0[1] {
        let s = by_i(q0);
        if s != Ordering::Equal {
            return s;
        }
        if q1[1] <= p1[1] { by_i(q1) } else { by_j(p1) }
    } else {
        by_j(p0)
    }
}

/// The y range `(min, max)` of edge `i` (from its two vertices, not from
/// `a + d`, which may round).
fn span<S: Scalar>(pe: &[Edge2<S>], i: usize) -> (S, S) {
    let a = pe[i].a.y;
    let b = pe[(i + 1) % pe.len()].a.y;
    if a <= b { (a, b) } else { (b, a) }
}

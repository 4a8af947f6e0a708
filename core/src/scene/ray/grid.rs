//! The ray path's acceleration: each object's triangles, in the object's
//! own space, binned into a uniform [`Grid`] over the object's box (3D
//! DDA, early exit; see [`crate::ray::grid`]), in caller storage.
//!
//! One grid per object, not one over the world: a ray is still carried
//! into each object's space and tested against the object's box first,
//! exactly as without a grid, so the grid only replaces the loop over the
//! object's triangles. That keeps a small object's cells small next to a
//! large floor (one world grid over the bunny scene's 32-unit floor would
//! give the bunny about 13 times fewer cells), and it keeps the result
//! bit for bit that of the loop: the same triangles, in the same space,
//! with the same ties (lowest index).
//!
//! # Storage
//!
//! [`Scene::ray_storage`] (a `const fn`, so firmware can size `static`
//! arrays) gives the lengths of the three slices of [`RayBuffers`], for
//! `n_o` triangles in object `o`:
//! - `triangles`: `Σ n_o`, one [`RayTriangle`] per triangle;
//! - `cells`: `Σ (CELLS_PER_TRIANGLE·n_o + 1)` cell starts;
//! - `items`: `Σ ITEMS_PER_TRIANGLE·n_o` (triangle, cell) entries.
//!
//! An object's grid has at most `CELLS_PER_TRIANGLE·n_o` cells (the usual
//! λ of uniform grids), split over the axes in proportion to its box. An
//! object whose triangles overlap more cells than its item budget (large
//! triangles in a fine grid, e.g. a cube's faces) gets a coarser grid:
//! each axis's resolution is cut to ¾ until the items fit, at worst one
//! cell, which needs one item per triangle. Slower then, never wrong.

use super::RayScene;
use crate::math::Vec3;
use crate::ray::{
    Aabb, Grid, GridError, Intersect, Mailbox, Ray, SurfaceHit, Triangle, TriangleHit,
};
use crate::scalar::Scalar;
use crate::scene::material;
use crate::scene::{Scene, SceneError, View};

/// Grid cells per triangle (λ; 2–4 is common for uniform grids).
pub const CELLS_PER_TRIANGLE: usize = 2;

/// (Triangle, cell) entries per triangle in [`RayStorage::items`]. The
/// bunny at λ = 2 needs about 4.5 per triangle.
pub const ITEMS_PER_TRIANGLE: usize = 8;

/// A world-space triangle of a [`RayScene`] built
/// [`with_grid`](RayScene::with_grid): storage element of
/// [`RayBuffers::triangles`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayTriangle<S> {
    triangle: Triangle<S>,
}

impl<S: Scalar> RayTriangle<S> {
    /// A placeholder, to initialize storage.
    pub const EMPTY: Self = Self {
        triangle: Triangle::new(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO),
    };

    /// The triangle in world space.
    #[must_use]
    pub fn triangle(&self) -> &Triangle<S> {
        &self.triangle
    }
}

impl<S: Scalar> Intersect<S> for RayTriangle<S> {
    // Only t decides the nearest hit; the weights are recomputed for the
    // winner alone.
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let h = self.triangle.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t: h.t,
            normal: Vec3::ZERO,
            part: 0,
        })
    }
}

/// How much storage [`RayScene::with_grid`] needs (element counts).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RayStorage {
    /// [`RayTriangle`]s: every triangle of the scene.
    pub triangles: usize,
    /// Cell starts of the grid.
    pub cells: usize,
    /// (Triangle, cell) entries of the grid.
    pub items: usize,
}

/// Caller storage for [`RayScene::with_grid`], each slice at least as long
/// as [`Scene::ray_storage`] says (a `Vec` on a host, `static` arrays on a
/// firmware).
#[derive(Debug)]
pub struct RayBuffers<'a, S> {
    /// World-space triangles.
    pub triangles: &'a mut [RayTriangle<S>],
    /// Grid cell starts.
    pub cells: &'a mut [u32],
    /// Grid entries.
    pub items: &'a mut [u32],
}

impl Scene<'_> {
    /// The storage [`RayScene::with_grid`] needs for this scene.
    #[must_use]
    pub const fn ray_storage(&self) -> RayStorage {
        let mut s = RayStorage {
            triangles: 0,
            cells: 0,
            items: 0,
        };
        let mut i = 0;
        while i < self.objects.len() {
            let n = self.objects[i].mesh.triangles.len();
            s.triangles += n;
            s.cells += object_cells(n);
            s.items += ITEMS_PER_TRIANGLE * n;
            i += 1;
        }
        s
    }
}

/// Cell starts for an object of `n` triangles (none without triangles).
const fn object_cells(n: usize) -> usize {
    if n == 0 {
        0
    } else {
        CELLS_PER_TRIANGLE * n + 1
    }
}

/// One object's grid and the object-space triangles it indexes.
#[derive(Clone, Debug)]
pub(super) struct ObjectGrid<'a, S> {
    grid: Grid<'a, S>,
    tris: &'a [RayTriangle<S>],
}

impl<S: Scalar> ObjectGrid<'_, S> {
    /// The nearest triangle hit by the object-space ray (its index in the
    /// mesh, ties to the lower index) with its barycentric weights.
    pub(super) fn nearest(&self, ray: &Ray<S>) -> Option<(usize, TriangleHit<S>)> {
        // No mailbox: queries stay `&self` (a triangle in several cells may
        // be tested more than once per ray; the result is the same).
        let mut mailbox = Mailbox::new(&mut []);
        let (i, _) = self.grid.nearest(ray, S::ZERO, self.tris, &mut mailbox)?;
        let h = self.tris.get(i)?.triangle.intersect(ray, S::ZERO)?;
        Some((i, h))
    }

    /// Cells per axis.
    pub(super) fn resolution(&self) -> [usize; 3] {
        self.grid.resolution()
    }
}

impl<'a, S: Scalar> RayScene<'a, S> {
    /// As [`Self::new`], and each object's triangles binned into a uniform
    /// grid in `buffers` (see the module docs), which its queries then
    /// walk instead of every triangle. The image is the same as
    /// [`Self::new`]'s, bit for bit.
    ///
    /// # Errors
    /// [`Self::new`]'s errors; [`SceneError::RayStorage`] if a slice of
    /// `buffers` is shorter than [`Scene::ray_storage`] says.
    pub fn with_grid(
        scene: &Scene<'a>,
        view: &View<S>,
        buffers: RayBuffers<'a, S>,
    ) -> Result<Self, SceneError> {
        let mut rs = Self::new(scene, view)?;
        let need = scene.ray_storage();
        let short = |what, needed, given: usize| {
            (given < needed).then_some(SceneError::RayStorage {
                what,
                needed,
                given,
            })
        };
        if let Some(e) = short("triangles", need.triangles, buffers.triangles.len())
            .or(short("cells", need.cells, buffers.cells.len()))
            .or(short("items", need.items, buffers.items.len()))
        {
            return Err(e);
        }
        let (mut tris, mut cells, mut items) = (buffers.triangles, buffers.cells, buffers.items);
        for (obj, desc) in rs.objects.iter().zip(scene.objects) {
            let mesh = desc.mesh;
            let n = mesh.triangles.len();
            let (t, rest) = core::mem::take(&mut tris).split_at_mut(n);
            tris = rest;
            let (c, rest) = core::mem::take(&mut cells).split_at_mut(object_cells(n));
            cells = rest;
            let (i, rest) = core::mem::take(&mut items).split_at_mut(ITEMS_PER_TRIANGLE * n);
            items = rest;
            for (slot, &tri) in t.iter_mut().zip(mesh.triangles) {
                let p = tri.map(|k| material::position(mesh, obj.scale, k));
                slot.triangle = Triangle::new(p[0], p[1], p[2]);
            }
            let grid = match &obj.bounds {
                Some(b) if n > 0 => Some(object_grid(t, b, c, i)?),
                _ => None,
            };
            // One entry per object (capacity as objects): cannot fail.
            rs.grids
                .push(grid)
                .map_err(|_| SceneError::TooManyObjects)?;
        }
        Ok(rs)
    }

    /// Each object's grid cells per axis (`None` for an object without
    /// a grid: no triangles, or built with [`Self::new`]).
    pub fn grid_resolutions(&self) -> impl Iterator<Item = Option<[usize; 3]>> + '_ {
        (0..self.objects.len()).map(|o| {
            self.grids
                .get(o)
                .and_then(|g| g.as_ref().map(ObjectGrid::resolution))
        })
    }
}

/// The grid over one object's triangles `tris` inside its box `bounds`.
fn object_grid<'a, S: Scalar>(
    tris: &'a [RayTriangle<S>],
    bounds: &Aabb<S>,
    cells: &'a mut [u32],
    items: &'a mut [u32],
) -> Result<ObjectGrid<'a, S>, SceneError> {
    let n = tris.len();
    // A triangle of finite positions always has a box; the object's box
    // (which holds every vertex) stands in for one that did not.
    let box_of = |i: usize| {
        tris.get(i)
            .and_then(|t| Aabb::from_points(&t.triangle.v).ok())
            .or(Some(*bounds))
    };
    let given = (cells.len(), items.len());
    let mut res = resolution(bounds, CELLS_PER_TRIANGLE * n);
    // Coarsen until the items fit (one cell always does: n ≤ items).
    loop {
        match Grid::build_with(n, box_of, res, &mut *cells, &mut []) {
            Err(GridError::ItemStorage { needed }) if needed > given.1 && res != [1; 3] => {
                res = res.map(|r| (r * 3 / 4).max(1));
            }
            Ok(_) | Err(GridError::ItemStorage { .. }) => break,
            Err(e) => return Err(grid_error(e, given)),
        }
    }
    let grid = Grid::build_with(n, box_of, res, cells, items).map_err(|e| grid_error(e, given))?;
    Ok(ObjectGrid { grid, tris })
}

/// A grid that cannot be built in the given (cells, items) storage.
fn grid_error(e: GridError, given: (usize, usize)) -> SceneError {
    let (what, needed, given) = match e {
        GridError::CellStorage { needed } => ("cells", needed, given.0),
        GridError::ItemStorage { needed } => ("items", needed, given.1),
        // Not for an object with triangles and at most 2^24 cells;
        // reported rather than assumed.
        GridError::Empty | GridError::TooLarge => ("cells", usize::MAX, given.0),
    };
    SceneError::RayStorage {
        what,
        needed,
        given,
    }
}

/// At most `budget` cells over `bounds`, cubic cells as far as the
/// extent allows: side `h = ∛(volume / budget)`, an axis of extent `e`
/// gets `round(e / h)` cells (at least 1; a flat axis counts as 1/64 of
/// the longest for the volume), then the largest count is cut until the
/// product fits.
fn resolution<S: Scalar>(bounds: &Aabb<S>, budget: usize) -> [u16; 3] {
    let (lo, hi) = (bounds.min().to_array(), bounds.max().to_array());
    let ext = [0, 1, 2].map(|k| (hi[k].to_f64() - lo[k].to_f64()).max(0.0));
    let longest = ext.iter().copied().fold(0.0, f64::max);
    let budget = budget.clamp(1, 1 << 24);
    if !(longest > 0.0 && longest.is_finite()) {
        return [1; 3];
    }
    let e = ext.map(|x| x.max(longest / 64.0));
    let h = libm::cbrt(e[0] * e[1] * e[2] / budget as f64);
    if !(h > 0.0 && h.is_finite()) {
        return [1; 3];
    }
    let mut r = ext.map(|x| libm::round(x / h).clamp(1.0, 1024.0) as usize);
    while r[0] * r[1] * r[2] > budget {
        let k = (0..3).fold(0, |m, k| if r[k] > r[m] { k } else { m });
        r[k] -= 1;
    }
    r.map(|x| x as u16)
}

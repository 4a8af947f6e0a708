//! Ray-cast workloads on the bunny: 320×240 primary rays at the bunny
//! posed as W1 frame 0 (`../shared/WORKLOADS.md`, [`crate::workload`]),
//! shaded by the W1 flat rule, through one of three searches:
//!
//! - [`RayMode::Brute`]: every ray against all 3674 triangles
//!   ([`Mesh::intersect`], which prepares the ray's shear once per ray, the
//!   best a brute-force loop can do);
//! - [`RayMode::Bounds`]: the bunny split into up to 64 objects (triangles
//!   binned by centroid into a 4×4×4 lattice over the bunny's box), each
//!   with its [`Aabb`]; an object's triangles are tested only when the ray
//!   meets its box before the best hit so far;
//! - [`RayMode::Grid`]: a uniform [`Grid`] over the triangles' boxes,
//!   about [`GRID_CELLS_PER_TRIANGLE`] cells per triangle, traversed with
//!   the 3D DDA and mailboxing.
//!
//! All three use the watertight triangle test and the same tie rule
//! (least t, then lowest triangle index), so their images are identical.
//!
//! The camera is W1's: at the origin, zero angles, focus 200 px, screen
//! 320×240 ([`RayCamera::from_camera`], so the ray of pixel (i, j) passes
//! through the point the raster path projects to (i + ½, j + ½)).

use crate::workload::{HEIGHT, Model, WIDTH, Workload, gray565, intensity_byte};
use embedded_graphics::pixelcolor::Rgb565;
use sightline::camera::{Camera, Projection};
use sightline::math::Vec3;
use sightline::ray::{
    Aabb, Grid, Intersect, Mailbox, Mesh, Ray, RayCamera, ShearedRay, SurfaceHit, Triangle,
};
use sightline::scalar::Scalar;
use sightline::transform::Euler;

/// Grid cells per triangle (the usual λ of uniform grids; 2–4 is common).
pub const GRID_CELLS_PER_TRIANGLE: f64 = 2.0;

/// Which search the rays use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayMode {
    /// All triangles per ray.
    Brute,
    /// Per-object bounding boxes first.
    Bounds,
    /// Uniform grid with 3D DDA.
    Grid,
}

impl RayMode {
    /// The workload bin's name: `ray-brute`, `ray-bounds`, `ray-grid`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Brute => "ray-brute",
            Self::Bounds => "ray-bounds",
            Self::Grid => "ray-grid",
        }
    }

    /// The mode called `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        [Self::Brute, Self::Bounds, Self::Grid]
            .into_iter()
            .find(|m| m.name() == name)
    }
}

/// A triangle for the grid: only `t` is used, so the hit carries no
/// normal (shading looks the face color up by index).
#[derive(Clone, Copy, Debug)]
struct Tri<S>(Triangle<S>);

impl<S: Scalar> Intersect<S> for Tri<S> {
    #[inline]
    fn intersect_ray(&self, ray: &Ray<S>, t_min: S) -> Option<SurfaceHit<S>> {
        let h = self.0.intersect(ray, t_min)?;
        Some(SurfaceHit {
            t: h.t,
            normal: Vec3::ZERO,
            part: 0,
        })
    }
}

/// One object of the bounds mode: a box and its triangles' indices.
#[derive(Clone, Debug)]
struct Cluster<S> {
    bounds: Aabb<S>,
    tris: Vec<u32>,
}

/// Everything set up once: world-space bunny, per-triangle colors, the
/// ray camera, the clusters and the grid (storage leaked once, so the grid
/// can borrow it for the program's life).
#[derive(Debug)]
pub struct RayWorkload<S: Scalar + 'static> {
    mode: RayMode,
    camera: RayCamera<S>,
    mesh: Mesh<'static, S>,
    tris: Vec<Tri<S>>,
    colors: Vec<Rgb565>,
    clusters: Vec<Cluster<S>>,
    grid: Option<Grid<'static, S>>,
    stamps: Vec<u32>,
}

/// The result of one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayStats {
    /// Pixels whose ray hit the bunny.
    pub hits: u32,
}

impl<S: Scalar + 'static> RayWorkload<S> {
    /// Sets up `mode` for `model` posed as W1 frame 0.
    ///
    /// # Panics
    /// If the camera, mesh or grid cannot be built (not for the bunny:
    /// tested).
    #[must_use]
    pub fn new(model: &Model<S>, mode: RayMode) -> Self {
        let camera = Camera::from_angles(Vec3::ZERO, Euler::ZERO);
        let projection =
            Projection::perspective(S::from_f64(crate::workload::FOCUS), WIDTH, HEIGHT);
        let ray_camera =
            RayCamera::from_camera(&camera, &projection, WIDTH, HEIGHT).expect("W1 camera");
        let pose = Workload::<S>::pose(0, 1);
        let to_world = pose.object_to_world();
        let vertices: Vec<Vec3<S>> = model
            .positions
            .iter()
            .map(|&p| to_world.transform_point3(p))
            .collect();
        let indices: &'static [[u32; 3]] = Box::leak(
            model
                .triangles
                .iter()
                .map(|t| t.map(u32::from))
                .collect::<Vec<_>>()
                .into_boxed_slice(),
        );
        // The W1 rule exactly as the raster workload evaluates it.
        let m = camera.object_to_view(&pose);
        let k3 = S::from_f64(1.0 / 3f64.sqrt());
        let l = m.matrix.transpose().mul_vec3(Vec3::new(k3, -k3, -k3));
        let (ambient, diffuse) = (S::from_f64(0.2), S::from_f64(0.8));
        let colors = model
            .face_normals
            .iter()
            .map(|&n| gray565(intensity_byte(ambient + diffuse * n.dot(l).max_of(S::ZERO))))
            .collect();
        let tris: Vec<Tri<S>> = indices
            .iter()
            .map(|t| {
                Tri(Triangle::new(
                    vertices[t[0] as usize],
                    vertices[t[1] as usize],
                    vertices[t[2] as usize],
                ))
            })
            .collect();
        let boxes: Vec<Aabb<S>> = tris
            .iter()
            .map(|t| Aabb::from_points(&t.0.v).expect("finite bunny"))
            .collect();
        let mut w = Self {
            mode,
            camera: ray_camera,
            mesh: Mesh::new(Box::leak(vertices.into_boxed_slice()), indices).expect("bunny mesh"),
            stamps: vec![0; tris.len()],
            tris,
            colors,
            clusters: Vec::new(),
            grid: None,
        };
        match mode {
            RayMode::Brute => {}
            RayMode::Bounds => w.clusters = clusters(&boxes),
            RayMode::Grid => w.grid = Some(grid(&boxes)),
        }
        w
    }

    /// The mode.
    #[must_use]
    pub fn mode(&self) -> RayMode {
        self.mode
    }

    /// The grid's cells per axis, or `None` outside grid mode.
    #[must_use]
    pub fn grid_res(&self) -> Option<[u16; 3]> {
        self.grid.as_ref().map(|_| grid_res(self.tris.len()))
    }

    /// The ray of pixel (i, j) (W1's camera); `None` only for a
    /// degenerate camera.
    #[must_use]
    pub fn pixel_ray(&self, i: u16, j: u16) -> Option<Ray<S>> {
        self.camera.pixel_ray(i, j)
    }

    /// The bunny in world space: vertices and triangles.
    #[must_use]
    pub fn mesh(&self) -> &Mesh<'static, S> {
        &self.mesh
    }

    /// A fresh mailbox storage (one stamp per triangle) for [`Self::nearest`].
    #[must_use]
    pub fn stamps(&self) -> Vec<u32> {
        vec![0; self.tris.len()]
    }

    /// The number of objects (bounding boxes) in bounds mode, else 0.
    #[must_use]
    pub fn objects(&self) -> usize {
        self.clusters.len()
    }

    /// The nearest triangle the ray hits: (triangle index, t).
    #[must_use]
    pub fn nearest(&self, ray: &Ray<S>, mailbox: &mut Mailbox<'_>) -> Option<(usize, S)> {
        match self.mode {
            RayMode::Brute => self.mesh.intersect(ray, S::ZERO).map(|(i, h)| (i, h.t)),
            RayMode::Bounds => {
                let r = ShearedRay::new(ray)?;
                let mut best: Option<(usize, S)> = None;
                for c in &self.clusters {
                    let t_max = best.map_or(S::MAX, |(_, t)| t);
                    if c.bounds.intersect_range(ray, S::ZERO, t_max).is_none() {
                        continue;
                    }
                    for &i in &c.tris {
                        let i = i as usize;
                        if let Some(h) = self.tris[i].0.intersect_sheared(&r, S::ZERO) {
                            let better = match best {
                                None => true,
                                Some((bi, bt)) => h.t < bt || (h.t == bt && i < bi),
                            };
                            if better {
                                best = Some((i, h.t));
                            }
                        }
                    }
                }
                best
            }
            RayMode::Grid => {
                let g = self.grid.as_ref()?;
                g.nearest(ray, S::ZERO, &self.tris, mailbox)
                    .map(|(i, h)| (i, h.t))
            }
        }
    }

    /// Casts one frame into `color` (320×240, cleared to black first) and
    /// returns its statistics. `stamps` of the mailbox are per workload.
    pub fn render(&mut self, color: &mut [Rgb565]) -> RayStats {
        let bg = gray565(0);
        color.fill(bg);
        let mut stamps = core::mem::take(&mut self.stamps);
        let mut mailbox = Mailbox::new(&mut stamps);
        let mut hits = 0;
        for j in 0..HEIGHT {
            for i in 0..WIDTH {
                let Some(ray) = self.camera.pixel_ray(i, j) else {
                    continue;
                };
                if let Some((tri, _)) = self.nearest(&ray, &mut mailbox) {
                    if let Some(px) = color.get_mut(j as usize * WIDTH as usize + i as usize) {
                        *px = self.colors[tri];
                        hits += 1;
                    }
                }
            }
        }
        self.stamps = stamps;
        RayStats { hits }
    }
}

/// Cells per axis for `n` triangles: λ·n cells split evenly over the
/// bunny's box, whose sides are close enough to equal (the normalization
/// makes the largest 2, the others 1.55 and 1.94) that a cube grid is
/// used.
fn grid_res(n: usize) -> [u16; 3] {
    let r = (GRID_CELLS_PER_TRIANGLE * n as f64).cbrt().round().max(1.0) as u16;
    [r; 3]
}

fn grid<S: Scalar>(boxes: &[Aabb<S>]) -> Grid<'static, S> {
    let res = grid_res(boxes.len());
    let cells: usize = res.iter().map(|&r| r as usize).product();
    let cell_start: &'static mut [u32] = Box::leak(vec![0u32; cells + 1].into_boxed_slice());
    // Ask for the item count first with an empty slice.
    let needed = match Grid::build(boxes, res, &mut vec![0u32; cells + 1], &mut []) {
        Err(sightline::ray::GridError::ItemStorage { needed }) => needed,
        Ok(_) => 0,
        Err(e) => panic!("grid: {e}"),
    };
    let items: &'static mut [u32] = Box::leak(vec![0u32; needed].into_boxed_slice());
    Grid::build(boxes, res, cell_start, items).expect("grid storage sized")
}

/// Bins triangles by the center of their box into a 4×4×4 lattice over
/// the union box; each non-empty bin is an object with the union of its
/// triangles' boxes. Triangles keep ascending index order within a bin.
fn clusters<S: Scalar>(boxes: &[Aabb<S>]) -> Vec<Cluster<S>> {
    const B: usize = 4;
    let all = boxes.iter().skip(1).fold(boxes[0], |a, b| a.union(b));
    let (lo, hi) = (all.min().to_array(), all.max().to_array());
    let mut bins: Vec<Option<Cluster<S>>> = vec![None; B * B * B];
    for (i, b) in boxes.iter().enumerate() {
        let (mn, mx) = (b.min().to_array(), b.max().to_array());
        let mut idx = 0;
        for k in 0..3 {
            let c = (mn[k].to_f64() + mx[k].to_f64()) / 2.0;
            let f = (c - lo[k].to_f64()) / (hi[k].to_f64() - lo[k].to_f64()).max(1e-9);
            idx = idx * B + ((f * B as f64) as usize).min(B - 1);
        }
        match &mut bins[idx] {
            Some(c) => {
                c.bounds = c.bounds.union(b);
                c.tris.push(i as u32);
            }
            slot @ None => {
                *slot = Some(Cluster {
                    bounds: *b,
                    tris: vec![i as u32],
                });
            }
        }
    }
    bins.into_iter().flatten().collect()
}

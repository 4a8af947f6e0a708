//! Rendering a core scene into an [`Image`] with either path.

use crate::image::Image;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::raster::DepthBuffer;
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::{
    Color, PreparedObject, RayBuffers, RayScene, RayTriangle, Renderer, Scene, SceneError,
};
use sightline::target::Framebuffer;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Which path renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// World→screen: the pipeline and scan converter.
    Raster,
    /// Screen→world: one ray per pixel center.
    Ray,
    /// Both (two images).
    Both,
}

/// Which scalar the core computes in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ScalarKind {
    /// `f32`.
    F32,
    /// I16F16 fixed point.
    Fixed,
}

impl ScalarKind {
    /// Short name for file names and reports.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::Fixed => "fixed",
        }
    }
}

/// Renders `scene` with the raster path.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn raster<S: Scalar>(scene: &Scene<'_>, width: u16, height: u16) -> Result<Image, SceneError> {
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = scene.prepare(&mut vec3s, &mut objects)?;
    let renderer = Renderer::<S>::new(scene, width, height)?;
    let mut scratch = vec![MeshVertex::default(); need.vertices];
    let frame = renderer.project(objects, &mut scratch)?;

    let mut img = Image::new(width, height, scene.background);
    let mut keys = vec![u16::MAX; img.pixels.len()];
    let w = width as usize;
    let mut fb = Framebuffer::new(&mut img.pixels, width, height, w)
        .map_err(|_| SceneError::BadProjection)?;
    let mut depth =
        DepthBuffer::new(&mut keys, width, height, w, 0).map_err(|_| SceneError::BadProjection)?;
    frame.draw(&mut fb, &mut depth);
    Ok(img)
}

/// How a ray render reports its progress on stderr.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// Silent.
    Off,
    /// An indicatif bar (for a terminal).
    Bar,
    /// Plain lines, `ray: 30% (72/240 rows, 1.4 s)`, at each 10 % of the
    /// rows once the render has run for [`LINES_AFTER`] (so short renders
    /// stay quiet): for logs and pipes, where a bar shows nothing.
    Lines,
}

/// How long a ray render runs before [`Progress::Lines`] prints.
pub const LINES_AFTER: Duration = Duration::from_secs(1);

/// Counts finished rows and prints a line at each new tenth of them.
struct LineReport<'a> {
    total: usize,
    done: AtomicUsize,
    last_tenth: Mutex<usize>,
    start: Instant,
    after: Duration,
    sink: &'a (dyn Fn(&str) + Sync),
}

impl LineReport<'_> {
    fn row_done(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        let tenth = done * 10 / self.total.max(1);
        let Ok(mut last) = self.last_tenth.lock() else {
            return;
        };
        if tenth > *last {
            *last = tenth;
            let t = self.start.elapsed();
            if t >= self.after {
                (self.sink)(&format!(
                    "ray: {}% ({done}/{} rows, {:.1} s)",
                    tenth * 10,
                    self.total,
                    t.as_secs_f64()
                ));
            }
        }
    }
}

/// Renders `scene` with the ray path, rows in parallel with rayon
/// (`parallel = false`: one thread, rows in order). Both give the same
/// image bit for bit: every pixel is a pure function of the scene.
/// `progress`: an indicatif bar on stderr.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn ray<S: Scalar + Send + Sync>(
    scene: &Scene<'_>,
    width: u16,
    height: u16,
    parallel: bool,
    progress: bool,
) -> Result<Image, SceneError> {
    let p = if progress {
        Progress::Bar
    } else {
        Progress::Off
    };
    ray_with::<S>(scene, width, height, parallel, p)
}

/// [`ray`] with the progress report chosen.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn ray_with<S: Scalar + Send + Sync>(
    scene: &Scene<'_>,
    width: u16,
    height: u16,
    parallel: bool,
    progress: Progress,
) -> Result<Image, SceneError> {
    let stderr = |l: &str| eprintln!("{l}");
    ray_report::<S>(
        scene,
        width,
        height,
        parallel,
        progress,
        LINES_AFTER,
        &stderr,
    )
}

/// Builds the scene's ray path for a `width`×`height` image, with its
/// uniform grid in storage allocated here (the sizes of
/// [`Scene::ray_storage`]), and hands it to `f`.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn with_ray_scene<S: Scalar, R>(
    scene: &Scene<'_>,
    width: u16,
    height: u16,
    f: impl FnOnce(&RayScene<'_, S>) -> R,
) -> Result<R, SceneError> {
    let view = scene.view::<S>(width, height)?;
    let need = scene.ray_storage();
    let mut triangles = vec![RayTriangle::EMPTY; need.triangles];
    let mut cells = vec![0u32; need.cells];
    let mut items = vec![0u32; need.items];
    let buffers = RayBuffers {
        triangles: &mut triangles,
        cells: &mut cells,
        items: &mut items,
    };
    let rs = RayScene::with_grid(scene, &view, buffers)?;
    Ok(f(&rs))
}

/// [`ray_with`], with [`Progress::Lines`] going to `sink` once `after` has
/// passed.
fn ray_report<S: Scalar + Send + Sync>(
    scene: &Scene<'_>,
    width: u16,
    height: u16,
    parallel: bool,
    progress: Progress,
    after: Duration,
    sink: &(dyn Fn(&str) + Sync),
) -> Result<Image, SceneError> {
    with_ray_scene::<S, _>(scene, width, height, |rs| {
        ray_rows(rs, scene, parallel, progress, after, sink)
    })
}

/// Renders every row of `rs` (see [`ray_report`]).
fn ray_rows<S: Scalar + Send + Sync>(
    rs: &RayScene<'_, S>,
    scene: &Scene<'_>,
    parallel: bool,
    progress: Progress,
    after: Duration,
    sink: &(dyn Fn(&str) + Sync),
) -> Image {
    let (width, height) = (rs.width(), rs.height());
    let mut img = Image::new(width, height, scene.background);
    let bar = if progress == Progress::Bar {
        let b = ProgressBar::new(height as u64);
        b.set_style(
            ProgressStyle::with_template("ray {bar:40} {pos}/{len} rows {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b
    } else {
        ProgressBar::hidden()
    };
    let lines = (progress == Progress::Lines).then(|| LineReport {
        total: height as usize,
        done: AtomicUsize::new(0),
        last_tenth: Mutex::new(0),
        start: Instant::now(),
        after,
        sink,
    });
    let row_done = || {
        bar.inc(1);
        if let Some(l) = &lines {
            l.row_done();
        }
    };
    let w = width as usize;
    if parallel {
        img.pixels
            .par_chunks_mut(w)
            .enumerate()
            .for_each(|(j, row)| {
                rs.render_row(j as u16, row);
                row_done();
            });
    } else {
        for (j, row) in img.pixels.chunks_mut(w).enumerate() {
            rs.render_row(j as u16, row);
            row_done();
        }
    }
    bar.finish_and_clear();
    img
}

/// Renders with the chosen scalar and path (`Method::Both` is not a
/// single image: pass `Raster` or `Ray`); `progress`: a bar for the ray
/// path.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn render(
    scene: &Scene<'_>,
    method: Method,
    scalar: ScalarKind,
    width: u16,
    height: u16,
    progress: bool,
) -> Result<Image, SceneError> {
    let p = if progress {
        Progress::Bar
    } else {
        Progress::Off
    };
    render_with(scene, method, scalar, width, height, p)
}

/// [`render`] with the ray path's progress report chosen.
///
/// # Errors
/// The scene's [`SceneError`].
pub fn render_with(
    scene: &Scene<'_>,
    method: Method,
    scalar: ScalarKind,
    width: u16,
    height: u16,
    progress: Progress,
) -> Result<Image, SceneError> {
    match (method, scalar) {
        (Method::Ray, ScalarKind::F32) => ray_with::<f32>(scene, width, height, true, progress),
        (Method::Ray, ScalarKind::Fixed) => {
            ray_with::<I16F16>(scene, width, height, true, progress)
        }
        (_, ScalarKind::F32) => raster::<f32>(scene, width, height),
        (_, ScalarKind::Fixed) => raster::<I16F16>(scene, width, height),
    }
}

/// The name of the column-caster scene (not a [`Scene`]: a grid map).
pub const MAZE: &str = "maze";

/// One-line description of [`MAZE`] for `list`.
pub const MAZE_DESCRIPTION: &str =
    "column caster over the built-in 16x12 grid map (textured walls, y sides darker)";

/// Horizontal field of view of the maze view, radians (66°, as in
/// Wolfenstein-style casters).
const MAZE_FOV: f64 = 66.0 * std::f64::consts::PI / 180.0;

/// A 16×16 brick texture (light bricks, dark mortar) and the same at half
/// brightness for walls hit on a y side.
fn brick_textures() -> (Vec<Color>, Vec<Color>) {
    use embedded_graphics::pixelcolor::RgbColor;
    let mut x = Vec::with_capacity(256);
    for j in 0..16u8 {
        for i in 0..16u8 {
            let offset = if j < 8 { 0 } else { 8 };
            let mortar = j % 8 == 7 || (i + offset) % 16 == 0;
            x.push(if mortar {
                Color::new(10, 20, 10)
            } else {
                // A little shading per brick row so the v mapping shows.
                Color::new(22 + (j % 8) / 2, 20 + j % 8, 6)
            });
        }
    }
    let y = x
        .iter()
        .map(|c| Color::new(c.r() / 2, c.g() / 2, c.b() / 2))
        .collect();
    (x, y)
}

/// Renders the built-in grid map ([`sightline::scene::builtin::COLUMN_MAP`])
/// with the column caster in scalar `S`, from the map's start position.
///
/// # Errors
/// The caster's error, as text (not for the built-in map).
pub fn maze<S: Scalar>(width: u16, height: u16) -> Result<Image, String> {
    use sightline::ray::column::{Column, ColumnCamera, ColumnStyle, render_columns};
    use sightline::texture::Texture;
    let map = &sightline::scene::builtin::COLUMN_MAP;
    let focus = S::from_f64(width as f64 / 2.0 / (MAZE_FOV / 2.0).tan());
    let cam = ColumnCamera::<S>::at_start(map, focus, width, height).map_err(|e| e.to_string())?;
    let (xt, yt) = brick_textures();
    let style = ColumnStyle {
        x_side: Texture::new(&xt, 16, 16, 16).map_err(|e| e.to_string())?,
        y_side: Texture::new(&yt, 16, 16, 16).map_err(|e| e.to_string())?,
        ceiling: Color::new(6, 12, 10),
        floor: Color::new(10, 18, 8),
    };
    let mut img = Image::new(width, height, style.ceiling);
    let mut cols = vec![Column::EMPTY; width as usize];
    let mut fb = Framebuffer::new(&mut img.pixels, width, height, width as usize)
        .map_err(|e| e.to_string())?;
    render_columns(map, &cam, &style, &mut cols, &mut fb).map_err(|e| e.to_string())?;
    Ok(img)
}

/// [`maze`] in the chosen scalar.
///
/// # Errors
/// As [`maze`].
pub fn render_maze(scalar: ScalarKind, width: u16, height: u16) -> Result<Image, String> {
    match scalar {
        ScalarKind::F32 => maze::<f32>(width, height),
        ScalarKind::Fixed => maze::<I16F16>(width, height),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sightline::scene::builtin;

    fn lines(progress: Progress, after: Duration) -> Vec<String> {
        let got = Mutex::new(Vec::new());
        let sink = |l: &str| got.lock().unwrap().push(l.to_string());
        ray_report::<f32>(&builtin::CUBE, 16, 20, true, progress, after, &sink).unwrap();
        got.into_inner().unwrap()
    }

    #[test]
    fn progress_lines_report_each_tenth_of_the_rows_once() {
        let got = lines(Progress::Lines, Duration::ZERO);
        assert_eq!(got.len(), 10, "{got:?}");
        for (i, l) in got.iter().enumerate() {
            assert!(l.starts_with(&format!("ray: {}% (", (i + 1) * 10)), "{l}");
        }
        assert!(got[9].contains("(20/20 rows, "), "{got:?}");
    }

    #[test]
    fn progress_lines_are_quiet_for_short_renders_and_when_off() {
        assert!(lines(Progress::Lines, Duration::from_secs(3600)).is_empty());
        assert!(lines(Progress::Off, Duration::ZERO).is_empty());
        assert!(lines(Progress::Bar, Duration::ZERO).is_empty());
    }
}

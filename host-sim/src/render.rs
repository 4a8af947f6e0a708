//! Rendering a core scene into an [`Image`] with either path.

use crate::image::Image;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use sightline::raster::DepthBuffer;
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::{RayScene, Scene, SceneError, render_raster};
use sightline::target::Framebuffer;

/// Which path renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// World→screen: the pipeline and scan converter.
    Raster,
    /// Screen→world: one ray per pixel centre.
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
    let view = scene.view::<S>(width, height)?;
    let mut img = Image::new(width, height, scene.background);
    let mut keys = vec![u16::MAX; img.pixels.len()];
    let w = width as usize;
    let mut fb = Framebuffer::new(&mut img.pixels, width, height, w)
        .map_err(|_| SceneError::BadProjection)?;
    let mut depth =
        DepthBuffer::new(&mut keys, width, height, w, 0).map_err(|_| SceneError::BadProjection)?;
    render_raster(scene, &view, &mut fb, &mut depth)?;
    Ok(img)
}

/// Renders `scene` with the ray path, rows in parallel with rayon
/// (`parallel = false`: one thread, rows in order). Both give the same
/// image bit for bit: every pixel is a pure function of the scene.
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
    let view = scene.view::<S>(width, height)?;
    let rs = RayScene::new(scene, &view)?;
    let mut img = Image::new(width, height, scene.background);
    let bar = if progress {
        let b = ProgressBar::new(height as u64);
        b.set_style(
            ProgressStyle::with_template("ray {bar:40} {pos}/{len} rows {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b
    } else {
        ProgressBar::hidden()
    };
    let w = width as usize;
    if parallel {
        img.pixels
            .par_chunks_mut(w)
            .enumerate()
            .for_each(|(j, row)| {
                rs.render_row(j as u16, row);
                bar.inc(1);
            });
    } else {
        for (j, row) in img.pixels.chunks_mut(w).enumerate() {
            rs.render_row(j as u16, row);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    Ok(img)
}

/// Renders with the chosen scalar and path (`Method::Both` is not a
/// single image: pass `Raster` or `Ray`).
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
    match (method, scalar) {
        (Method::Ray, ScalarKind::F32) => ray::<f32>(scene, width, height, true, progress),
        (Method::Ray, ScalarKind::Fixed) => ray::<I16F16>(scene, width, height, true, progress),
        (_, ScalarKind::F32) => raster::<f32>(scene, width, height),
        (_, ScalarKind::Fixed) => raster::<I16F16>(scene, width, height),
    }
}

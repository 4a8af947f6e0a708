//! Animated turntables: a scene turned once about the world up axis over
//! N frames, written as an animated PNG (APNG).
//!
//! # What turns
//!
//! The objects and spheres turn; the camera and the light stay where the
//! scene puts them, as on a real turntable. Frame `k` of `N` turns every
//! object and sphere by `θ_k = 2π·k/N` about the vertical line (world +Y)
//! through the scene's center ([`center`]): an object's origin `O` moves
//! to `C + Ry(θ)·(O − C)` and its yaw grows by `θ`. Since a pose is
//! `T(O)·Ry(yaw)·Rx(pitch)·Rz(roll)` (yaw outermost, about world +Y), this
//! turns every point of the object by exactly `Ry(θ)` about the axis,
//! whatever its roll and pitch, so it works for every built-in scene and
//! every scene file with no camera form to special-case. Frame 0 is the
//! scene exactly as given, i.e. the still render; the last frame stops one
//! step short of a full turn, so the animation loops without a repeated
//! frame.
//!
//! Every frame renders through the same functions as a still
//! ([`render::render_with`]), with either path.
//!
//! # Memory
//!
//! All frames are rendered before anything is written (so `--method both`
//! leaves nothing behind when one path fails). The frames together may
//! hold at most [`MAX_PIXELS`] pixels — as many as one 4096×4096 image,
//! the largest still size — that is 32 MiB per path in Rgb565.

use crate::cli::line;
use crate::image::Image;
use crate::render::{self, LINES_AFTER, Method, Progress, ScalarKind};
use indicatif::{ProgressBar, ProgressStyle};
use sightline::math::Vec3;
use sightline::scene::{Scene, SceneObject, SceneSphere};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The most pixels all frames of one turntable may hold together
/// (frames × width × height): one 4096×4096 image.
pub const MAX_PIXELS: u64 = 4096 * 4096;

/// Frames per second when `--fps` is not given.
pub const DEFAULT_FPS: u16 = 25;

/// The highest `--fps` (browsers slow down faster APNGs anyway).
pub const MAX_FPS: u16 = 100;

/// Parses `--frames`: a whole number of at least 1 (1: a still PNG).
///
/// # Errors
/// A message saying what was expected.
pub fn parse_frames(s: &str) -> Result<u32, String> {
    match s.trim().parse::<u32>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "expected a whole number of frames, at least 1 (1: a still PNG, 2 or more: \
             an animated turntable); got {s:?}"
        )),
    }
}

/// Parses `--fps`: a whole number in `1..=`[`MAX_FPS`].
///
/// # Errors
/// A message saying what was expected.
pub fn parse_fps(s: &str) -> Result<u16, String> {
    match s.trim().parse::<u16>() {
        Ok(n) if (1..=MAX_FPS).contains(&n) => Ok(n),
        _ => Err(format!(
            "expected frames per second as a whole number in 1..={MAX_FPS}; got {s:?}"
        )),
    }
}

/// Checks that `frames` frames of `width`×`height` fit [`MAX_PIXELS`].
///
/// # Errors
/// A message with the numbers and what to change.
pub fn check_size(frames: u32, width: u16, height: u16) -> Result<(), String> {
    let pixels = u64::from(frames) * u64::from(width) * u64::from(height);
    if pixels > MAX_PIXELS {
        return Err(format!(
            "a turntable of {frames} frames at {width}x{height} holds {pixels} pixels: at most \
             {MAX_PIXELS} (one 4096x4096 image) fit in memory; use fewer --frames or a smaller \
             --size"
        ));
    }
    Ok(())
}

/// The axis of the turn: `(x, z)` of the center of the world-space
/// bounding box of every mesh vertex (through its pose) and every sphere.
/// `(0, 0)` for a scene with neither.
#[must_use]
pub fn center(scene: &Scene<'_>) -> (f64, f64) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut add = |x: f64, z: f64, r: f64| {
        lo = [lo[0].min(x - r), lo[1].min(z - r)];
        hi = [hi[0].max(x + r), hi[1].max(z + r)];
    };
    for o in scene.objects {
        let m = o.pose.object_to_world();
        let s = o.mesh.scale;
        for p in o.mesh.positions {
            let [x, y, z] = p.map(|c| f32::from(c) * s);
            let w = m.transform_point3(Vec3::new(x, y, z));
            add(f64::from(w.x), f64::from(w.z), 0.0);
        }
    }
    for s in scene.spheres {
        add(
            f64::from(s.center[0]),
            f64::from(s.center[2]),
            f64::from(s.radius),
        );
    }
    if lo[0].is_finite() && hi[0].is_finite() && lo[1].is_finite() && hi[1].is_finite() {
        ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0)
    } else {
        (0.0, 0.0)
    }
}

/// `(x, z)` turned by `angle` about `center`, by the right-hand rule about
/// +Y (as `Ry` of [`sightline::transform::Euler::to_mat3`]), in f64.
fn turn_xz(x: f32, z: f32, (cx, cz): (f64, f64), angle: f64) -> (f32, f32) {
    let (s, c) = angle.sin_cos();
    let (dx, dz) = (f64::from(x) - cx, f64::from(z) - cz);
    ((cx + c * dx + s * dz) as f32, (cz - s * dx + c * dz) as f32)
}

/// The objects and spheres of `scene` turned by `angle` radians about the
/// vertical axis through `center` (see the module docs).
#[must_use]
pub fn turned<'a>(
    scene: &Scene<'a>,
    center: (f64, f64),
    angle: f64,
) -> (Vec<SceneObject<'a>>, Vec<SceneSphere>) {
    let objects = scene
        .objects
        .iter()
        .map(|o| {
            let mut o = *o;
            let (x, z) = turn_xz(o.pose.origin.x, o.pose.origin.z, center, angle);
            o.pose.origin.x = x;
            o.pose.origin.z = z;
            o.pose.angles.yaw = (f64::from(o.pose.angles.yaw) + angle) as f32;
            o
        })
        .collect();
    let spheres = scene
        .spheres
        .iter()
        .map(|s| {
            let mut s = *s;
            let (x, z) = turn_xz(s.center[0], s.center[2], center, angle);
            s.center[0] = x;
            s.center[2] = z;
            s
        })
        .collect();
    (objects, spheres)
}

/// The angle of frame `k` of `frames`: `2π·k/frames`.
#[must_use]
pub fn frame_angle(k: u32, frames: u32) -> f64 {
    std::f64::consts::TAU * f64::from(k) / f64::from(frames.max(1))
}

/// Reports finished frames: a bar, plain lines or nothing.
struct FrameProgress {
    bar: ProgressBar,
    lines: bool,
    total: u32,
    last_tenth: u32,
    start: Instant,
    label: &'static str,
}

impl FrameProgress {
    fn new(progress: Progress, total: u32, label: &'static str) -> Self {
        let bar = if progress == Progress::Bar {
            let b = ProgressBar::new(u64::from(total));
            let template =
                format!("turntable {label} {{bar:40}} {{pos}}/{{len}} frames {{elapsed}}");
            b.set_style(
                ProgressStyle::with_template(&template)
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b
        } else {
            ProgressBar::hidden()
        };
        Self {
            bar,
            lines: progress == Progress::Lines,
            total,
            last_tenth: 0,
            start: Instant::now(),
            label,
        }
    }

    fn frame_done(&mut self, done: u32) {
        self.bar.inc(1);
        let tenth = done * 10 / self.total.max(1);
        if self.lines && tenth > self.last_tenth {
            self.last_tenth = tenth;
            let t = self.start.elapsed();
            if t >= LINES_AFTER {
                eprintln!(
                    "turntable {}: {}% ({done}/{} frames, {:.1} s)",
                    self.label,
                    tenth * 10,
                    self.total,
                    t.as_secs_f64()
                );
            }
        }
    }
}

impl Drop for FrameProgress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Renders the `frames` frames of the turntable of `scene` with one path
/// (`Raster` or `Ray`; `Both` renders as `Raster`), through
/// [`render::render_with`]. Frame 0 is `scene` itself.
///
/// # Errors
/// The first frame's error, as text naming the scene and the path; a size
/// beyond [`MAX_PIXELS`] before anything is rendered.
pub fn render_frames(
    scene: &Scene<'_>,
    method: Method,
    scalar: ScalarKind,
    (width, height): (u16, u16),
    frames: u32,
    progress: Progress,
) -> Result<Vec<Image>, String> {
    check_size(frames, width, height)?;
    let what = if method == Method::Ray {
        "ray"
    } else {
        "raster"
    };
    let fail = |k: u32, e: &dyn std::fmt::Display| {
        format!("scene {} ({what}, turntable frame {k}): {e}", scene.name)
    };
    let c = center(scene);
    let mut report = FrameProgress::new(progress, frames, what);
    let mut out = Vec::with_capacity(frames as usize);
    for k in 0..frames {
        let img = if k == 0 {
            render::render_with(scene, method, scalar, width, height, Progress::Off)
        } else {
            let (objects, spheres) = turned(scene, c, frame_angle(k, frames));
            let s = Scene {
                objects: &objects,
                spheres: &spheres,
                ..*scene
            };
            render::render_with(&s, method, scalar, width, height, Progress::Off)
        }
        .map_err(|e| fail(k, &e))?;
        out.push(img);
        report.frame_done(k + 1);
    }
    Ok(out)
}

/// Writes `frames` (all of one size, at least one) as an animated 8-bit
/// RGB PNG that loops forever at `fps` frames per second. Every frame is a
/// whole image (no offsets, no blending), so a viewer without APNG
/// support shows frame 0, the still.
///
/// # Errors
/// No frames, frames of differing sizes, or I/O and encoder errors, as
/// text naming the file.
pub fn write_apng(path: &Path, frames: &[Image], fps: u16) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: cannot write PNG: {e}", path.display());
    let first = frames.first().ok_or_else(|| err(&"no frames"))?;
    let (w, h) = (first.width, first.height);
    if frames.iter().any(|f| (f.width, f.height) != (w, h)) {
        return Err(err(&"frames differ in size"));
    }
    let n = u32::try_from(frames.len()).map_err(|_| err(&"too many frames"))?;
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), w.into(), h.into());
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::High);
    enc.set_animated(n, 0).map_err(|e| err(&e))?;
    enc.set_frame_delay(1, fps.max(1)).map_err(|e| err(&e))?;
    let mut wr = enc.write_header().map_err(|e| err(&e))?;
    for f in frames {
        wr.write_image_data(&f.rgb8()).map_err(|e| err(&e))?;
    }
    wr.finish().map_err(|e| err(&e))?;
    Ok(())
}

/// `render SCENE --frames N` for N ≥ 2: renders every frame of every path
/// `method` asks for, then writes one APNG per path (`out_file`, or
/// `SCENE-METHOD-turntable.png`; with `both`, -raster/-ray added) and a
/// line per file to `out`.
///
/// # Errors
/// As [`render_frames`] (nothing is written then) and [`write_apng`].
#[allow(clippy::too_many_arguments)]
pub fn turntable_cmd(
    scene: &Scene<'_>,
    method: Method,
    scalar: ScalarKind,
    (w, h): (u16, u16),
    frames: u32,
    fps: u16,
    out_file: Option<PathBuf>,
    out: &mut dyn Write,
) -> Result<(), String> {
    check_size(frames, w, h)?;
    let progress = if std::io::stderr().is_terminal() {
        Progress::Bar
    } else {
        Progress::Lines
    };
    let default = |what: &str| PathBuf::from(format!("{}-{what}-turntable.png", scene.name));
    let jobs: Vec<(Method, PathBuf)> = match method {
        Method::Both => {
            let base =
                out_file.unwrap_or_else(|| PathBuf::from(format!("{}-turntable.png", scene.name)));
            vec![
                (Method::Raster, crate::with_suffix(&base, "raster")),
                (Method::Ray, crate::with_suffix(&base, "ray")),
            ]
        }
        Method::Ray => vec![(Method::Ray, out_file.unwrap_or_else(|| default("ray")))],
        Method::Raster => vec![(
            Method::Raster,
            out_file.unwrap_or_else(|| default("raster")),
        )],
    };
    // Every frame of every path before any file, as for a still: a path
    // that cannot render the scene leaves no partial result.
    let mut done = Vec::with_capacity(jobs.len());
    for (m, file) in jobs {
        let images = render_frames(scene, m, scalar, (w, h), frames, progress)?;
        done.push((m, file, images));
    }
    for (m, file, images) in done {
        write_apng(&file, &images, fps)?;
        let what = if m == Method::Ray { "ray" } else { "raster" };
        line(
            out,
            &format!(
                "wrote {} ({}, {w}x{h}, {what}, {}, turntable of {frames} frames at {fps} fps)",
                file.display(),
                scene.name,
                scalar.name()
            ),
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use sightline::scene::builtin;

    /// Every vertex of a turned object lands where turning its original
    /// world position about the axis puts it (f64 reference, computed
    /// independently of the pose arithmetic).
    #[test]
    fn turning_moves_every_vertex_by_ry_about_the_axis() {
        let scene = &builtin::CUBE;
        let c = (0.7, -1.3);
        for angle in [0.4, 2.0, -1.1] {
            let (objects, _) = turned(scene, c, angle);
            for (o, t) in scene.objects.iter().zip(&objects) {
                let (m0, m1) = (o.pose.object_to_world(), t.pose.object_to_world());
                for p in o.mesh.positions {
                    let [x, y, z] = p.map(|v| f32::from(v) * o.mesh.scale);
                    let a = m0.transform_point3(Vec3::new(x, y, z));
                    let b = m1.transform_point3(Vec3::new(x, y, z));
                    let (s, co) = f64::sin_cos(angle);
                    let (dx, dz) = (f64::from(a.x) - c.0, f64::from(a.z) - c.1);
                    let want = [
                        c.0 + co * dx + s * dz,
                        f64::from(a.y),
                        c.1 - s * dx + co * dz,
                    ];
                    let got = [b.x, b.y, b.z].map(f64::from);
                    for (g, w) in got.iter().zip(want) {
                        assert!((g - w).abs() < 1e-5, "{got:?} vs {want:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn spheres_turn_about_the_axis_and_keep_height_and_radius() {
        let scene = &builtin::SPHERES;
        let (_, spheres) = turned(scene, (0.0, 0.0), std::f64::consts::FRAC_PI_2);
        for (s, t) in scene.spheres.iter().zip(&spheres) {
            // A quarter turn by the right-hand rule about +Y: (x, z) → (z, −x).
            assert!((t.center[0] - s.center[2]).abs() < 1e-6, "{t:?}");
            assert!((t.center[2] + s.center[0]).abs() < 1e-6, "{t:?}");
            assert_eq!((t.center[1], t.radius), (s.center[1], s.radius));
        }
    }

    #[test]
    fn center_is_the_middle_of_the_world_bounding_box() {
        // Corridor: x ∈ [−2, 2], z ∈ [−24, 0].
        assert_eq!(center(&builtin::CORRIDOR), (0.0, -12.0));
    }

    #[test]
    fn sizes_beyond_the_cap_are_refused() {
        assert!(check_size(1, 4096, 4096).is_ok());
        let e = check_size(2, 4096, 4096).unwrap_err();
        assert!(
            e.contains("33554432 pixels") && e.contains("--frames"),
            "{e}"
        );
    }
}

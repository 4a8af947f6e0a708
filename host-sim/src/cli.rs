//! The command line: `sightline-sim [render|list|compare|report|help]`.

use crate::image::{self, Image, agreement, diff_rgb8, write_rgb8_png};
use crate::render::{self, Method, Progress, ScalarKind};
use crate::{report, scene_file, turntable};
use clap::{Parser, Subcommand};
use sightline::scene::{self, Scene};
use std::ffi::OsString;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

/// Default image size.
pub const DEFAULT_SIZE: (u16, u16) = (320, 240);

/// sightline host simulator: render the built-in scenes and scene files
/// with the raster and the ray path.
///
/// Without a subcommand, renders the default built-in scene (the bunny)
/// with the raster path to a PNG in the current directory.
#[derive(Debug, Parser)]
#[command(name = "sightline-sim", version, disable_help_subcommand = true)]
pub struct Cli {
    /// What to do (default: render the default scene).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a built-in scene (by name) or a scene file (.ron) to PNG.
    Render {
        /// Built-in scene name (see `list`) or path to a .ron scene file.
        scene: String,
        /// Which path renders; `both` writes two files.
        #[arg(long, value_enum, default_value = "raster")]
        method: Method,
        /// Which scalar the core computes in.
        #[arg(long, value_enum, default_value = "f32")]
        scalar: ScalarKind,
        /// Image size, WxH.
        #[arg(long, default_value = "320x240", value_parser = parse_size)]
        size: (u16, u16),
        /// Output file (default: SCENE-METHOD.png in the current
        /// directory, SCENE-METHOD-turntable.png with --frames; with
        /// `both`, -raster/-ray is added before .png).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write an animated PNG (APNG) of N frames that turns the objects
        /// once about the world up axis through the scene center (camera
        /// and light stay); 1 writes the still PNG.
        #[arg(long, value_name = "N", value_parser = turntable::parse_frames)]
        frames: Option<u32>,
        /// Frames per second of the animated PNG (1..=100; default 25).
        #[arg(long, requires = "frames", value_parser = turntable::parse_fps)]
        fps: Option<u16>,
    },
    /// List the built-in scenes.
    List,
    /// Render a scene with both paths, report the agreement and write a
    /// diff PNG (gray: equal, yellow: within tolerance, red: different).
    Compare {
        /// Built-in scene name or path to a .ron scene file.
        scene: String,
        /// Which scalar the core computes in.
        #[arg(long, value_enum, default_value = "f32")]
        scalar: ScalarKind,
        /// Image size, WxH.
        #[arg(long, default_value = "320x240", value_parser = parse_size)]
        size: (u16, u16),
        /// Diff image file (default: SCENE-diff.png).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Measure error against run time for every numeric representation
    /// and write DIR/accuracy.md plus one Pareto plot (PNG) per routine.
    Report {
        /// Output directory.
        #[arg(long, default_value = "report")]
        out: PathBuf,
        /// Smoke-test size (a fraction of a second; figures are not
        /// meaningful).
        #[arg(long)]
        tiny: bool,
    },
    /// Print this message or the help of the given subcommand.
    Help {
        /// The subcommand whose help to print.
        command: Vec<String>,
    },
}

/// Parses `WxH`.
///
/// # Errors
/// A message saying what was expected.
pub fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let bad = || format!("expected WxH with 1..=4096 pixels per side, e.g. 320x240; got {s:?}");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u16 = w.trim().parse().map_err(|_| bad())?;
    let h: u16 = h.trim().parse().map_err(|_| bad())?;
    if !(1..=4096).contains(&w) || !(1..=4096).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// A built-in scene or a loaded scene file.
enum SceneSource {
    Builtin(&'static Scene<'static>),
    File(Box<scene_file::LoadedScene>),
}

impl SceneSource {
    fn open(arg: &str) -> Result<Self, String> {
        if let Some(s) = scene::builtin::by_name(arg) {
            return Ok(Self::Builtin(s));
        }
        let p = Path::new(arg);
        if p.extension().is_some_and(|e| e == "ron") || p.is_file() {
            return scene_file::load(p)
                .map(|l| Self::File(Box::new(l)))
                .map_err(|e| e.to_string());
        }
        let mut names: Vec<&str> = scene::builtin::ALL.iter().map(|s| s.name).collect();
        names.push(render::MAZE);
        Err(format!(
            "unknown scene {arg:?}: expected a built-in scene ({}) or a .ron scene file",
            names.join(", ")
        ))
    }

    fn with<R>(&self, f: impl FnOnce(&Scene<'_>) -> R) -> R {
        match self {
            Self::Builtin(s) => f(s),
            Self::File(l) => l.with_scene(f),
        }
    }
}

pub(crate) fn with_suffix(path: &Path, suffix: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "out".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}-{suffix}.png"))
}

fn render_cmd(
    src: &SceneSource,
    method: Method,
    scalar: ScalarKind,
    (w, h): (u16, u16),
    out_file: Option<PathBuf>,
    out: &mut dyn Write,
) -> Result<(), String> {
    // A bar on a terminal; plain lines on stderr for logs and pipes.
    let progress = if std::io::stdout().is_terminal() {
        Progress::Bar
    } else {
        Progress::Lines
    };
    src.with(|scene| {
        let jobs: Vec<(Method, PathBuf)> = match method {
            Method::Both => {
                let base = out_file
                    .clone()
                    .unwrap_or_else(|| PathBuf::from(format!("{}.png", scene.name)));
                vec![
                    (Method::Raster, with_suffix(&base, "raster")),
                    (Method::Ray, with_suffix(&base, "ray")),
                ]
            }
            m => {
                let name = if m == Method::Raster { "raster" } else { "ray" };
                let file = out_file
                    .clone()
                    .unwrap_or_else(|| PathBuf::from(format!("{}-{name}.png", scene.name)));
                vec![(m, file)]
            }
        };
        // Render every image before writing any, so that a path that
        // cannot render this scene (e.g. the ray path and a parallel
        // projection) leaves no partial result behind.
        let mut images = Vec::with_capacity(jobs.len());
        for (m, file) in jobs {
            let what = if m == Method::Raster { "raster" } else { "ray" };
            let img = render::render_with(scene, m, scalar, w, h, progress)
                .map_err(|e| format!("scene {} ({what}): {e}", scene.name))?;
            images.push((img, file, what));
        }
        for (img, file, what) in images {
            img.write_png(&file)?;
            line(
                out,
                &format!(
                    "wrote {} ({}, {w}x{h}, {what}, {})",
                    file.display(),
                    scene.name,
                    scalar.name()
                ),
            );
        }
        Ok(())
    })
}

/// Renders the column-caster scene [`render::MAZE`]. It has one path (the
/// column caster, a ray method), so `--method` only chooses the file name.
fn maze_cmd(
    method: Method,
    scalar: ScalarKind,
    (w, h): (u16, u16),
    out_file: Option<PathBuf>,
    out: &mut dyn Write,
) -> Result<(), String> {
    if method == Method::Raster {
        line(
            out,
            "note: maze has no raster path; rendering with the column caster",
        );
    }
    let file = out_file.unwrap_or_else(|| PathBuf::from(format!("{}-column.png", render::MAZE)));
    let img = render::render_maze(scalar, w, h).map_err(|e| format!("scene maze: {e}"))?;
    img.write_png(&file)?;
    line(
        out,
        &format!(
            "wrote {} (maze, {w}x{h}, column caster, {})",
            file.display(),
            scalar.name()
        ),
    );
    Ok(())
}

/// The agreement of the two paths on one scene, plus both images.
///
/// # Errors
/// The scene's error, as text.
pub fn compare_images(
    scene: &Scene<'_>,
    scalar: ScalarKind,
    (w, h): (u16, u16),
) -> Result<(Image, Image, image::Agreement), String> {
    let a = render::render(scene, Method::Raster, scalar, w, h, false)
        .map_err(|e| format!("scene {} (raster): {e}", scene.name))?;
    let b = render::render(scene, Method::Ray, scalar, w, h, false)
        .map_err(|e| format!("scene {} (ray): {e}", scene.name))?;
    let ag = agreement(&a, &b);
    Ok((a, b, ag))
}

fn compare_cmd(
    src: &SceneSource,
    scalar: ScalarKind,
    size: (u16, u16),
    out_file: Option<PathBuf>,
    out: &mut dyn Write,
) -> Result<(), String> {
    src.with(|scene| {
        let (a, b, ag) = compare_images(scene, scalar, size)?;
        let file = out_file.unwrap_or_else(|| PathBuf::from(format!("{}-diff.png", scene.name)));
        write_rgb8_png(&file, a.width, a.height, &diff_rgb8(&a, &b))?;
        line(
            out,
            &format!(
                "scene: {} ({}x{}, {})",
                scene.name,
                size.0,
                size.1,
                scalar.name()
            ),
        );
        if !scene.spheres.is_empty() {
            line(out, "note: spheres are drawn by the ray path only");
        }
        line(out, &format!("pixels: {}", ag.total));
        line(
            out,
            &format!("equal: {} ({:.2}%)", ag.equal, ag.equal_percent()),
        );
        line(
            out,
            &format!(
                "within tolerance (|dR|,|dB| <= 1, |dG| <= 2 in Rgb565): {} ({:.2}%)",
                ag.within,
                ag.within_percent()
            ),
        );
        line(out, &format!("diff image: {}", file.display()));
        line(out, &format!("agreement: {:.2}%", ag.equal_percent()));
        Ok(())
    })
}

fn report_cmd(dir: &Path, tiny: bool, out: &mut dyn Write) -> Result<(), String> {
    let (size, tiny_flag) = if tiny {
        (report::Size::TINY, " --tiny")
    } else {
        (report::Size::FULL, "")
    };
    let cmd = format!(
        "cargo run --release -p sightline-sim -- report --out {}{tiny_flag}",
        dir.display()
    );
    let w = report::generate(dir, size, &cmd)?;
    line(
        out,
        &format!(
            "wrote {} and {} plots in {:.1} s",
            w.markdown.display(),
            w.plots.len(),
            w.seconds
        ),
    );
    Ok(())
}

/// Runs the command line `args` (including the program name), writing
/// normal output to `out`.
///
/// # Errors
/// A message for the user (clap's usage errors included); `main` prints it
/// and exits with status 1 (2 for usage errors).
pub fn run<I, T>(args: I, out: &mut dyn Write) -> Result<(), RunError>
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    let cli = Cli::try_parse_from(&args).map_err(RunError::Usage)?;
    let r = match cli.command {
        None => {
            let scene = scene::builtin::DEFAULT;
            let file = PathBuf::from(format!("sightline-{}.png", scene.name));
            render_cmd(
                &SceneSource::Builtin(scene),
                Method::Raster,
                ScalarKind::F32,
                DEFAULT_SIZE,
                Some(file),
                out,
            )
        }
        Some(Command::Render { scene, frames, .. })
            if scene == render::MAZE && frames.is_some_and(|n| n >= 2) =>
        {
            Err(format!(
                "scene {}: --frames needs a scene with objects to turn; the column caster's grid \
             map has none",
                render::MAZE
            ))
        }
        Some(Command::Render {
            scene,
            method,
            scalar,
            size,
            out: file,
            ..
        }) if scene == render::MAZE => maze_cmd(method, scalar, size, file, out),
        Some(Command::Render {
            scene,
            method,
            scalar,
            size,
            out: file,
            frames: Some(n),
            fps,
        }) if n >= 2 => SceneSource::open(&scene).and_then(|src| {
            let fps = fps.unwrap_or(turntable::DEFAULT_FPS);
            src.with(|s| turntable::turntable_cmd(s, method, scalar, size, n, fps, file, out))
        }),
        Some(Command::Render {
            scene,
            method,
            scalar,
            size,
            out: file,
            ..
        }) => SceneSource::open(&scene)
            .and_then(|src| render_cmd(&src, method, scalar, size, file, out)),
        Some(Command::List) => {
            line(out, "built-in scenes:");
            for s in scene::builtin::ALL {
                line(out, &format!("  {:<16} {}", s.name, s.description));
            }
            line(
                out,
                &format!("  {:<16} {}", render::MAZE, render::MAZE_DESCRIPTION),
            );
            line(out, "scene files: see host-sim/scenes/*.ron");
            Ok(())
        }
        Some(Command::Compare { scene, .. }) if scene == render::MAZE => Err(format!(
            "scene {}: only the column caster renders it; use `render {0}`",
            render::MAZE
        )),
        Some(Command::Compare {
            scene,
            scalar,
            size,
            out: file,
        }) => SceneSource::open(&scene).and_then(|src| compare_cmd(&src, scalar, size, file, out)),
        Some(Command::Report { out: dir, tiny }) => report_cmd(&dir, tiny, out),
        Some(Command::Help { command }) => {
            // `help X Y` is `X Y --help`: clap prints the help (a `Usage`
            // "error" that `main` prints to stdout with status 0), or
            // reports an unknown subcommand.
            let bin = args
                .first()
                .cloned()
                .unwrap_or_else(|| "sightline-sim".into());
            let again = std::iter::once(bin)
                .chain(command.into_iter().map(OsString::from))
                .chain(["--help".into()]);
            return match Cli::try_parse_from(again) {
                Err(e) => Err(RunError::Usage(e)),
                Ok(_) => Err(RunError::Failed("help: no help to print".into())),
            };
        }
    };
    r.map_err(RunError::Failed)
}

/// Why [`run`] failed.
#[derive(Debug)]
pub enum RunError {
    /// Bad command line (or `--help` / `--version`, which clap reports
    /// this way).
    Usage(clap::Error),
    /// The command failed; the message says why.
    Failed(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Usage(e) => write!(f, "{e}"),
            Self::Failed(m) => write!(f, "error: {m}"),
        }
    }
}

impl std::error::Error for RunError {}

/// Writes `text` then a newline, ignoring errors on a closed pipe.
pub(crate) fn line(out: &mut dyn Write, text: &str) {
    let _ = writeln!(out, "{text}");
}

//! The built-in scenes across both paths: raster vs ray agreement, and
//! golden images.
//!
//! # Agreement metric
//!
//! Both paths sample each pixel at its centre (i + ½, j + ½) and shade
//! with the same material model (see `sightline::scene`). A pixel
//! *agrees* when the two Rgb565 values are equal; it is *within
//! tolerance* when red and blue differ by at most 1 and green by at most 2
//! (one intensity quantum). The thresholds below sit just under the
//! measured figures (docs/sim.md), so a regression in either path (a
//! half-pixel shift, a wrong normal, a fill-rule change) fails them.
//!
//! # Golden images
//!
//! `tests/images/<scene>/<method>-<scalar>.png`, 96×72, compared exactly.
//! To bless after a deliberate change:
//!
//! ```text
//! SIGHTLINE_BLESS=1 cargo test -p sightline-tests --test scenes golden
//! ```
//!
//! Without the variable a mismatch writes `<name>.png.new` beside the
//! golden image (ignored by git) and fails; goldens are never rewritten
//! automatically.

use sightline::scene::builtin;
use sightline_sim::compare_images;
use sightline_sim::image::{Image, read_png_rgb8, write_rgb8_png};
use sightline_sim::render::{self, Method, ScalarKind};
use std::path::PathBuf;

/// (scene, scalar, minimum % equal, minimum % within tolerance) at 160×120.
const AGREEMENT: &[(&str, ScalarKind, f64, f64)] = &[
    ("cube", ScalarKind::F32, 99.8, 99.8),
    ("cube", ScalarKind::Fixed, 99.8, 99.8),
    ("bunny", ScalarKind::F32, 99.8, 99.8),
    ("bunny", ScalarKind::Fixed, 99.8, 99.8),
    ("corridor", ScalarKind::F32, 99.4, 99.4),
    ("corridor", ScalarKind::Fixed, 99.4, 99.4),
    // Raster draws the floor only; the spheres differ.
    ("spheres", ScalarKind::F32, 82.5, 82.5),
];

#[test]
fn raster_and_ray_agree_on_builtin_scenes() {
    let mut failures = Vec::new();
    for &(name, scalar, equal, within) in AGREEMENT {
        let scene = builtin::by_name(name).unwrap();
        let (_, _, ag) = compare_images(scene, scalar, (160, 120)).unwrap();
        println!(
            "{name:<16} {:<5} equal {:6.2}%  within {:6.2}%",
            scalar.name(),
            ag.equal_percent(),
            ag.within_percent()
        );
        if ag.equal_percent() < equal || ag.within_percent() < within {
            failures.push(format!(
                "{name} {}: equal {:.2}% (min {equal}), within {:.2}% (min {within})",
                scalar.name(),
                ag.equal_percent(),
                ag.within_percent()
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn affine_corridor_visibly_differs_from_the_exact_image() {
    // Affine mapping on the steep floor and walls is what the perspective
    // corridor avoids: about half the pixels get another texel.
    let scene = builtin::by_name("corridor-affine").unwrap();
    let (_, _, ag) = compare_images(scene, ScalarKind::F32, (160, 120)).unwrap();
    assert!(ag.equal_percent() < 70.0, "{ag:?}");
}

/// Compares `img` with the golden PNG at `path` (96×72), or writes it
/// there when blessing. A difference leaves the new image beside the old
/// one as `.png.new` and is recorded in `failures`.
fn check_golden(path: &std::path::Path, img: &Image, bless: bool, failures: &mut Vec<String>) {
    let rgb = img.rgb8();
    let dir = path.parent().unwrap();
    if bless {
        std::fs::create_dir_all(dir).unwrap();
        write_rgb8_png(path, img.width, img.height, &rgb).unwrap();
        return;
    }
    let same = read_png_rgb8(path).is_ok_and(|g| (g.width, g.height) == (96, 72) && g.rgb == rgb);
    if !same {
        let new = path.with_extension("png.new");
        std::fs::create_dir_all(dir).unwrap();
        write_rgb8_png(&new, img.width, img.height, &rgb).unwrap();
        failures.push(format!(
            "{} differs (see {})",
            path.display(),
            new.display()
        ));
    }
}

fn blessing() -> bool {
    std::env::var_os("SIGHTLINE_BLESS").is_some_and(|v| v == "1")
}

fn assert_no_failures(failures: &[String]) {
    assert!(
        failures.is_empty(),
        "golden images differ; check the .png.new files and bless with \
         SIGHTLINE_BLESS=1 if the change is deliberate:\n{failures:#?}"
    );
}

#[test]
fn golden_images() {
    let bless = blessing();
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("images");
    let mut failures = Vec::new();
    for scene in builtin::ALL {
        for method in [Method::Raster, Method::Ray] {
            for scalar in [ScalarKind::F32, ScalarKind::Fixed] {
                let m = if method == Method::Raster {
                    "raster"
                } else {
                    "ray"
                };
                let path = root
                    .join(scene.name)
                    .join(format!("{m}-{}.png", scalar.name()));
                let img = render::render(scene, method, scalar, 96, 72, false).unwrap();
                check_golden(&path, &img, bless, &mut failures);
            }
        }
    }
    assert_no_failures(&failures);
}

/// The column caster's scene `maze` (not a `Scene`: a grid map), golden
/// at 96×72 in f32 and I16F16 as `tests/images/maze/column-<scalar>.png`,
/// blessed the same way as the other golden images.
#[test]
fn golden_maze() {
    let bless = blessing();
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("images")
        .join(render::MAZE);
    let mut failures = Vec::new();
    for scalar in [ScalarKind::F32, ScalarKind::Fixed] {
        let path = dir.join(format!("column-{}.png", scalar.name()));
        let img = render::render_maze(scalar, 96, 72).unwrap();
        check_golden(&path, &img, bless, &mut failures);
    }
    assert_no_failures(&failures);
}

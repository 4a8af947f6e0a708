//! The scene file reads core's own description types (`CameraSpec`,
//! `Light`, `TextureMode`, through core's `serde` feature): every camera
//! form, the light's defaults and every texture mode come out as the
//! values written, checked against literal core values.

use sightline::scene::{CameraSpec, Light, Material, TextureMode};
use sightline_sim::image::write_rgb8_png;
use sightline_sim::scene_file::parse;
use std::path::PathBuf;

fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sightline-sim-sf-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A scene file with `camera` and `light`, one textured quad in `mode`
/// (or the default mode when `mode` is empty).
fn scene(camera: &str, light: &str, mode: &str) -> String {
    format!(
        "Scene(\n    name: \"t\",\n    camera: {camera},\n    projection: Perspective(fov_x_degrees: 60.0),\n    light: {light},\n    objects: [(mesh: \"q.obj\", material: Texture(file: \"t.png\"{mode}))],\n)\n"
    )
}

/// Parses `text` next to a quad OBJ with texture coordinates and a 2x2
/// PNG; returns the scene's camera, light and texture mode.
fn read(tag: &str, text: &str) -> (CameraSpec, Light, TextureMode) {
    let d = temp_dir(tag);
    std::fs::write(
        d.join("q.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    write_rgb8_png(&d.join("t.png"), 2, 2, &[9; 12]).unwrap();
    let p = d.join("scene.ron");
    let loaded = parse(text, &p).unwrap_or_else(|e| panic!("{e}"));
    loaded.with_scene(|s| {
        let Material::Texture { mode, .. } = s.objects[0].material else {
            panic!("not textured: {:?}", s.objects[0].material);
        };
        (s.camera, s.light, mode)
    })
}

const LIGHT: &str = "(direction: (0.0, 1.0, 0.0), ambient: 0.25, diffuse: 0.5)";
const LOOK_AT: &str = "LookAt(eye: (0.0, 0.0, 5.0), target: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0))";

#[test]
fn every_camera_form_is_read_as_written() {
    let cases = [
        (
            "Angles(position: (1.0, 2.0, 3.0), angles: (0.5, -0.25, 0.125))",
            CameraSpec::Angles {
                position: [1.0, 2.0, 3.0],
                angles: [0.5, -0.25, 0.125],
            },
        ),
        (
            "Orthonormal(position: (0.0, 0.0, 5.0), right: (1.0, 0.0, 0.0), down: (0.0, -1.0, 0.0), forward: (0.0, 0.0, -1.0))",
            CameraSpec::Orthonormal {
                position: [0.0, 0.0, 5.0],
                right: [1.0, 0.0, 0.0],
                down: [0.0, -1.0, 0.0],
                forward: [0.0, 0.0, -1.0],
            },
        ),
        (
            "Vectors(position: (0.0, 0.0, 5.0), u: (2.0, 0.0, 0.0), v: (0.0, -2.0, 0.0), w: (0.0, 0.0, -1.5))",
            CameraSpec::Vectors {
                position: [0.0, 0.0, 5.0],
                u: [2.0, 0.0, 0.0],
                v: [0.0, -2.0, 0.0],
                w: [0.0, 0.0, -1.5],
            },
        ),
        (
            LOOK_AT,
            CameraSpec::LookAt {
                eye: [0.0, 0.0, 5.0],
                target: [0.0, 0.0, 0.0],
                up: [0.0, 1.0, 0.0],
            },
        ),
    ];
    for (k, (text, want)) in cases.into_iter().enumerate() {
        let (camera, ..) = read(&format!("cam{k}"), &scene(text, LIGHT, ""));
        assert_eq!(camera, want, "{text}");
    }
}

#[test]
fn light_fields_and_defaults() {
    let (_, light, _) = read("light", &scene(LOOK_AT, LIGHT, ""));
    assert_eq!(
        light,
        Light {
            direction: [0.0, 1.0, 0.0],
            ambient: 0.25,
            diffuse: 0.5
        }
    );
    // A file that gives only the direction: no ambient, full diffuse.
    let (_, light, _) = read(
        "light-default",
        &scene(LOOK_AT, "(direction: (0.5, 1.0, -2.0))", ""),
    );
    assert_eq!(
        light,
        Light {
            direction: [0.5, 1.0, -2.0],
            ambient: 0.0,
            diffuse: 1.0
        }
    );
}

#[test]
fn texture_modes_and_default() {
    for (text, want) in [
        ("", TextureMode::Perspective),
        (", mode: Affine", TextureMode::Affine),
        (", mode: Perspective", TextureMode::Perspective),
        (", mode: Auto", TextureMode::Auto),
    ] {
        let (.., mode) = read("mode", &scene(LOOK_AT, LIGHT, text));
        assert_eq!(mode, want, "{text:?}");
    }
}

/// The bunny core's build script generates its data from is the one the
/// host workloads and scene files load.
#[test]
fn core_bunny_source_is_the_test_data_bunny() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let core = std::fs::read(root.join("core/data/bunny.obj")).unwrap();
    let tests = std::fs::read(root.join("tests/data/bunny.obj")).unwrap();
    assert!(
        core == tests,
        "core/data/bunny.obj differs from tests/data/bunny.obj"
    );
}

/// A sphere's `center` is read under its American name and, for files
/// written before the rename, as `centre`; both give the same value.
#[test]
fn sphere_center_reads_both_spellings() {
    let d = temp_dir("center");
    let p = d.join("scene.ron");
    for key in ["center", "centre"] {
        let text = format!(
            "Scene(\n    name: \"s\",\n    camera: Angles(position: (0.0, 0.0, 5.0), angles: (0.0, 0.0, 0.0)),\n    projection: Perspective(fov_x_degrees: 60.0),\n    light: (direction: (0.0, 0.0, -1.0)),\n    objects: [],\n    spheres: [({key}: (1.5, -2.0, 0.25), radius: 0.5, color: (1, 2, 3))],\n)\n"
        );
        let loaded = parse(&text, &p).unwrap_or_else(|e| panic!("{key}: {e}"));
        loaded.with_scene(|s| assert_eq!(s.spheres[0].center, [1.5, -2.0, 0.25], "{key}"));
    }
    let bad = "Scene(\n    name: \"s\",\n    camera: Angles(position: (0.0, 0.0, 5.0), angles: (0.0, 0.0, 0.0)),\n    projection: Perspective(fov_x_degrees: 60.0),\n    light: (direction: (0.0, 0.0, -1.0)),\n    objects: [],\n    spheres: [(middle: (1.5, -2.0, 0.25), radius: 0.5, color: (1, 2, 3))],\n)\n";
    assert!(parse(bad, &p).is_err());
}

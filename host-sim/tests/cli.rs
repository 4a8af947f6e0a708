//! Every subcommand through `run`, the binary's default run, bad scene
//! files, and the parallel ray path against the single-threaded one.

use sightline::scalar::I16F16;
use sightline::scene::builtin;
use sightline_sim::image::{read_png_rgb8, write_rgb8_png};
use sightline_sim::{RunError, render, run};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// A fresh empty directory under the target dir.
fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicU32 = AtomicU32::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("sightline-sim-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run_ok(args: &[&str]) -> String {
    let mut out = Vec::new();
    let mut full = vec!["sightline-sim"];
    full.extend_from_slice(args);
    if let Err(e) = run(full, &mut out) {
        panic!("{args:?} failed: {e}");
    }
    String::from_utf8(out).unwrap()
}

fn run_err(args: &[&str]) -> String {
    let mut out = Vec::new();
    let mut full = vec!["sightline-sim"];
    full.extend_from_slice(args);
    match run(full, &mut out) {
        Ok(()) => panic!("{args:?} should fail"),
        Err(e) => e.to_string(),
    }
}

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

#[test]
fn list_names_every_builtin_scene() {
    let out = run_ok(&["list"]);
    for s in builtin::ALL {
        assert!(out.contains(s.name), "{out}");
    }
}

#[test]
fn render_builtin_writes_png_of_requested_size() {
    let d = temp_dir("render");
    let file = d.join("cube.png");
    let out = run_ok(&[
        "render",
        "cube",
        "--size",
        "40x30",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(out.contains("wrote"), "{out}");
    let img = read_png_rgb8(&file).unwrap();
    assert_eq!((img.width, img.height), (40, 30));
    // Not a blank image: the cube and floor are visible.
    let first = &img.rgb[..3];
    assert!(img.rgb.chunks(3).any(|p| p != first));
}

#[test]
fn render_both_fixed_writes_two_files() {
    let d = temp_dir("both");
    let base = d.join("c.png");
    run_ok(&[
        "render",
        "cube",
        "--method",
        "both",
        "--scalar",
        "fixed",
        "--size",
        "32x24",
        "--out",
        base.to_str().unwrap(),
    ]);
    assert!(d.join("c-raster.png").is_file());
    assert!(d.join("c-ray.png").is_file());
}

#[test]
fn compare_last_line_is_agreement() {
    let d = temp_dir("compare");
    let diff = d.join("diff.png");
    let out = run_ok(&[
        "compare",
        "cube",
        "--size",
        "64x48",
        "--out",
        diff.to_str().unwrap(),
    ]);
    let last = out.lines().last().unwrap();
    assert!(
        last.starts_with("agreement: ") && last.ends_with('%'),
        "{out}"
    );
    let pct: f64 = last["agreement: ".len()..last.len() - 1].parse().unwrap();
    assert!(pct >= 99.0, "{out}");
    assert!(diff.is_file());
}

#[test]
fn scene_files_render() {
    let d = temp_dir("files");
    for f in ["cube.ron", "textured.ron", "bunny.ron"] {
        let p = scenes_dir().join(f);
        let out = d.join(f.replace(".ron", ".png"));
        run_ok(&[
            "render",
            p.to_str().unwrap(),
            "--method",
            "both",
            "--size",
            "32x24",
            "--out",
            out.to_str().unwrap(),
        ]);
    }
}

#[test]
fn usage_errors() {
    assert!(matches!(
        run(
            ["sightline-sim", "render", "cube", "--size", "0x10"],
            &mut Vec::new()
        ),
        Err(RunError::Usage(_))
    ));
    assert!(matches!(
        run(["sightline-sim", "frobnicate"], &mut Vec::new()),
        Err(RunError::Usage(_))
    ));
    let e = run_err(&["render", "no-such-scene"]);
    assert!(e.contains("unknown scene") && e.contains("cube"), "{e}");
    // The ray path needs perspective.
    let d = temp_dir("parallel");
    let p = d.join("p.ron");
    std::fs::write(
        &p,
        r#"Scene(name: "p", camera: Angles(position: (0.0, 0.0, 5.0), angles: (0.0, 0.0, 0.0)),
        projection: Parallel(width: 4.0), light: (direction: (0.0, 1.0, 0.0)),
        objects: [(mesh: "builtin:cube", material: Flat((255, 0, 0)))])"#,
    )
    .unwrap();
    let out = d.join("p.png");
    run_ok(&[
        "render",
        p.to_str().unwrap(),
        "--size",
        "16x16",
        "--out",
        out.to_str().unwrap(),
    ]);
    let e = run_err(&[
        "render",
        p.to_str().unwrap(),
        "--method",
        "ray",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(e.contains("perspective"), "{e}");
}

/// Writes `text` as a scene file in a fresh directory (with the given
/// extra files) and returns the error message of rendering it.
fn scene_error(tag: &str, text: &str, files: &[(&str, &[u8])]) -> String {
    let d = temp_dir(tag);
    for (name, data) in files {
        std::fs::write(d.join(name), data).unwrap();
    }
    let p = d.join("scene.ron");
    std::fs::write(&p, text).unwrap();
    let out = d.join("o.png");
    run_err(&[
        "render",
        p.to_str().unwrap(),
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ])
}

const HEAD: &str = r#"Scene(
    name: "t",
    camera: LookAt(eye: (0.0, 0.0, 5.0), target: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0)),
    projection: Perspective(fov_x_degrees: 60.0),
    light: (direction: (0.0, 1.0, 0.0)),
"#;

#[test]
fn missing_mesh_file_names_file_line_and_column() {
    let text =
        format!("{HEAD}    objects: [(mesh: \"nope.obj\", material: Flat((1, 2, 3)))],\n)\n");
    let e = scene_error("missing", &text, &[]);
    assert!(e.contains("scene.ron:6:22:"), "{e}");
    assert!(e.contains("nope.obj") && e.contains("not found"), "{e}");
}

#[test]
fn bad_obj_index_names_obj_line_and_column() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\n";
    let text = format!("{HEAD}    objects: [(mesh: \"m.obj\", material: Flat((1, 2, 3)))],\n)\n");
    let e = scene_error("badindex", &text, &[("m.obj", obj)]);
    assert!(e.contains("m.obj:5:7:"), "{e}");
    assert!(e.contains("\"7\"") && e.contains("1..=3"), "{e}");
}

#[test]
fn non_power_of_two_texture_is_rejected_with_its_place() {
    let d = temp_dir("tex");
    let png = d.join("t.png");
    write_rgb8_png(&png, 24, 16, &vec![128; 24 * 16 * 3]).unwrap();
    let png_bytes = std::fs::read(&png).unwrap();
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    let text = format!(
        "{HEAD}    objects: [(mesh: \"m.obj\",\n        material: Texture(file: \"t.png\", mode: Auto))],\n)\n"
    );
    let e = scene_error("tex", &text, &[("m.obj", obj), ("t.png", &png_bytes)]);
    assert!(e.contains("scene.ron:7:33:"), "{e}");
    assert!(e.contains("24x16") && e.contains("powers of two"), "{e}");
}

#[test]
fn singular_general_camera_is_reported() {
    let text = r#"Scene(
    name: "t",
    camera: Vectors(position: (0.0, 0.0, 5.0), u: (1.0, 0.0, 0.0), v: (2.0, 0.0, 0.0), w: (0.0, 0.0, -1.0)),
    projection: Perspective(fov_x_degrees: 60.0),
    light: (direction: (0.0, 1.0, 0.0)),
)
"#;
    let e = scene_error("singular", text, &[]);
    assert!(e.contains("scene.ron:3:13:"), "{e}");
    assert!(e.contains("linearly independent"), "{e}");
}

#[test]
fn syntax_error_names_line_and_column() {
    let text = format!("{HEAD}    objects: [(mesh: 3)],\n)\n");
    let e = scene_error("syntax", &text, &[]);
    assert!(e.contains("scene.ron:6:"), "{e}");
}

#[test]
fn parallel_ray_path_is_bit_identical_to_single_threaded() {
    for scene in [&builtin::BUNNY, &builtin::SPHERES, &builtin::CORRIDOR] {
        let a = render::ray::<f32>(scene, 48, 36, true, false).unwrap();
        let b = render::ray::<f32>(scene, 48, 36, false, false).unwrap();
        assert_eq!(a, b, "{}", scene.name);
        let a = render::ray::<I16F16>(scene, 24, 18, true, false).unwrap();
        let b = render::ray::<I16F16>(scene, 24, 18, false, false).unwrap();
        assert_eq!(a, b, "{} fixed", scene.name);
    }
}

#[test]
fn default_run_writes_png_in_current_directory() {
    let d = temp_dir("default");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sightline-sim"))
        .current_dir(&d)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(stdout.contains("wrote sightline-bunny.png"), "{stdout}");
    let img = read_png_rgb8(&d.join("sightline-bunny.png")).unwrap();
    assert_eq!((img.width, img.height), (320, 240));
}

#[test]
fn maze_renders_with_the_column_caster() {
    assert!(run_ok(&["list"]).contains("maze"));
    let d = temp_dir("maze");
    let file = d.join("m.png");
    let text = run_ok(&[
        "render",
        "maze",
        "--method",
        "ray",
        "--scalar",
        "fixed",
        "--size",
        "64x48",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(text.contains("column caster"), "{text}");
    let img = read_png_rgb8(&file).unwrap();
    assert_eq!((img.width, img.height), (64, 48));
    // Walls, ceiling and floor: more than three colours.
    let mut colours: Vec<&[u8]> = img.rgb.chunks(3).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 3, "{} colours", colours.len());
    assert!(run_err(&["compare", "maze"]).contains("column caster"));
}

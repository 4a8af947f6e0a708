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
    // Walls, ceiling and floor: more than three colors.
    let mut colors: Vec<&[u8]> = img.rgb.chunks(3).collect();
    colors.sort_unstable();
    colors.dedup();
    assert!(colors.len() > 3, "{} colors", colors.len());
    assert!(run_err(&["compare", "maze"]).contains("column caster"));
}

/// A scene with one object using mesh `m.obj` and `material`.
fn obj_scene(material: &str) -> String {
    format!("{HEAD}    objects: [(mesh: \"m.obj\", material: {material})],\n)\n")
}

#[test]
fn nan_or_infinite_obj_numbers_name_the_obj_line() {
    let flat = obj_scene("Flat((1, 2, 3))");
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n";
    let e = scene_error("nanv", &flat, &[("m.obj", obj)]);
    assert!(
        e.contains("m.obj:3:5: vertex coordinate is NaN or infinite"),
        "{e}"
    );
    // 1e39 is infinite in f32.
    let obj = b"v 0 0 0\nv 1 0 0\n# c\n\nv 0 1e39 0\nf 1 2 3\n";
    let e = scene_error("infv", &flat, &[("m.obj", obj)]);
    assert!(
        e.contains("m.obj:5:5: vertex coordinate is NaN or infinite"),
        "{e}"
    );
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt -inf 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    let e = scene_error("infvt", &flat, &[("m.obj", obj)]);
    assert!(
        e.contains("m.obj:5:4: texture coordinate is NaN or infinite"),
        "{e}"
    );
}

#[test]
fn nan_or_infinite_scene_numbers_name_the_field() {
    let obj = "    objects: [(mesh: \"builtin:cube\", material: Flat((1, 2, 3)))],\n";
    // (what to replace in HEAD + obj, with what, where the error is)
    let cases = [
        ("eye: (0.0, 0.0, 5.0)", "eye: (0.0, NaN, 5.0)", "3:31"),
        ("fov_x_degrees: 60.0", "fov_x_degrees: inf", "4:44"),
        (
            "direction: (0.0, 1.0, 0.0)",
            "direction: (0.0, 1.0, -inf)",
            "5:35",
        ),
        (
            "direction: (0.0, 1.0, 0.0)",
            "direction: (0.0, 1.0, 0.0), ambient: NaN",
            "5:50",
        ),
        (
            "\"builtin:cube\"",
            "\"builtin:cube\", angles: (NaN, 0.0, 0.0)",
            "6:47",
        ),
        ("\"builtin:cube\"", "\"builtin:cube\", scale: inf", "6:45"),
        ("name: \"t\",", "name: \"t\", near: NaN,", "2:22"),
        ("name: \"t\",", "name: \"t\", far: inf,", "2:21"),
    ];
    for (from, to, place) in cases {
        let text = format!("{HEAD}{obj})\n").replace(from, to);
        let e = scene_error("nanscene", &text, &[]);
        assert!(
            e.contains(&format!("scene.ron:{place}: expected a finite number")),
            "{to}: {e}"
        );
    }
    let text = format!(
        "{HEAD}    spheres: [(center: (0.0, 0.0, 0.0), radius: NaN, color: (1, 2, 3))],\n)\n"
    );
    let e = scene_error("nansphere", &text, &[]);
    assert!(
        e.contains("scene.ron:6:49: expected a finite number, found NaN"),
        "{e}"
    );
}

#[test]
fn a_stray_vertex_that_collapses_triangles_is_refused() {
    // A cube (side 2) with one vertex at 1e6: the step is 33.3, so every
    // vertex but that one quantizes to 0 and all 12 triangles collapse.
    let cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1000000\n\
        f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    let e = scene_error(
        "collapse",
        &obj_scene("Flat((1, 2, 3))"),
        &[("m.obj", cube.as_bytes())],
    );
    assert!(e.contains("scene.ron:6:22: "), "{e}");
    assert!(e.contains("m.obj: "), "{e}");
    assert!(
        e.contains("12 of 12 triangles collapse when quantized: the largest coordinate 1000000 forces a step of 33.3"),
        "{e}"
    );
    // A large triangle and a small one: only the small one collapses.
    let two = b"v 0 0 0\nv 100000 0 0\nv 0 100000 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 4 5\n";
    let e = scene_error(
        "collapse2",
        &obj_scene("Flat((1, 2, 3))"),
        &[("m.obj", two)],
    );
    assert!(
        e.contains("1 of 2 triangles collapse when quantized: the largest coordinate 100000 forces a step of 3.33"),
        "{e}"
    );
    // The same cube without the stray vertex loads.
    let ok = cube.replace("1000000", "1");
    let d = temp_dir("nocollapse");
    std::fs::write(d.join("m.obj"), ok).unwrap();
    let p = d.join("scene.ron");
    std::fs::write(&p, obj_scene("Flat((1, 2, 3))")).unwrap();
    let out = d.join("o.png");
    run_ok(&[
        "render",
        p.to_str().unwrap(),
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ]);
}

#[test]
fn obj_errors_without_a_line_are_placed_at_the_mesh_field() {
    // Only a line element: no faces.
    let e = scene_error(
        "nofaces",
        &obj_scene("Flat((1, 2, 3))"),
        &[("m.obj", b"v 0 0 0\nv 1 0 0\nl 1 2\n")],
    );
    assert!(e.contains("scene.ron:6:22: "), "{e}");
    assert!(e.contains("m.obj: no faces"), "{e}");
    assert!(!e.contains(":0:0"), "{e}");
    // A `v` line with two numbers has its line.
    let e = scene_error(
        "twonum",
        &obj_scene("Flat((1, 2, 3))"),
        &[("m.obj", b"v 0 0 0\nv 1 0\n")],
    );
    assert!(
        e.contains("m.obj:2:1: `v` with 2 numbers: expected x y z"),
        "{e}"
    );
}

#[test]
fn messages_say_what_users_write() {
    let cube = "    objects: [(mesh: \"builtin:cube\", material: Flat((1, 2, 3)))],\n";
    let scene = |from: &str, to: &str| format!("{HEAD}{cube})\n").replace(from, to);
    // The field of view is in degrees.
    let e = scene_error(
        "fov",
        &scene("fov_x_degrees: 60.0", "fov_x_degrees: 180.0"),
        &[],
    );
    assert!(
        e.contains("scene.ron:4:44: ") && e.contains("degrees") && e.contains("180"),
        "{e}"
    );
    assert!(!e.contains("pi"), "{e}");
    // A zero up vector is named as such, at `up`.
    let e = scene_error(
        "up",
        &scene("up: (0.0, 1.0, 0.0)", "up: (0.0, 0.0, 0.0)"),
        &[],
    );
    assert!(
        e.contains("scene.ron:3:67: camera: the up vector is zero"),
        "{e}"
    );
    assert!(!e.contains("direction"), "{e}");
    // A bad scale is the scene's, not the OBJ file's.
    let e = scene_error(
        "scale",
        &obj_scene("Flat((1, 2, 3))").replace("\"m.obj\",", "\"m.obj\", scale: 0.0,"),
        &[("m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")],
    );
    assert!(
        e.contains("scene.ron:6:38: scale is 0: expected > 0"),
        "{e}"
    );
    // A face using texture coordinates before any `vt`.
    let e = scene_error(
        "novt",
        &obj_scene("Flat((1, 2, 3))"),
        &[("m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n")],
    );
    assert!(
        e.contains("m.obj:4:3: ") && e.contains("there are no texture coordinates"),
        "{e}"
    );
    assert!(!e.contains("1..=0"), "{e}");
    // RON's messages use the scene file's names, not Rust type names.
    for (from, to, name) in [
        ("Flat((1, 2, 3))", "Flat((1, 2, 3)), color: 1", "`object`"),
        ("LookAt(", "LookAtt(", "enum `camera`"),
        (
            "Flat((1, 2, 3))",
            "Texture(file: \"t.png\", mode: Fast)",
            "enum `mode`",
        ),
    ] {
        let e = scene_error("names", &scene(from, to), &[]);
        assert!(e.contains(name), "{e}");
        assert!(!e.contains("Def`"), "{e}");
    }
}

#[test]
fn unknown_fields_are_errors_everywhere() {
    let cube = "    objects: [(mesh: \"builtin:cube\", material: Flat((1, 2, 3)))],\n";
    let spheres = "    spheres: [(center: (0.0, 0.0, 0.0), radius: 1.0, color: (1, 2, 3))],\n";
    let base = format!("{HEAD}{cube}{spheres})\n");
    for (from, to, place) in [
        (
            "direction: (0.0, 1.0, 0.0)",
            "direction: (0.0, 1.0, 0.0), ambinet: 0.2",
            "5:41",
        ),
        // `colour`: the British spelling is not a field (the field is `color`).
        ("radius: 1.0", "radius: 1.0, colour: 1", "7:54"),
        (
            "up: (0.0, 1.0, 0.0)",
            "up: (0.0, 1.0, 0.0), roll: 1.0",
            "3:88",
        ),
        (
            "fov_x_degrees: 60.0",
            "fov_x_degrees: 60.0, fov_y: 1.0",
            "4:50",
        ),
        (
            "Flat((1, 2, 3))",
            "Texture(file: \"t.png\", mdoe: Auto)",
            "6:71",
        ),
    ] {
        let e = scene_error("unknown", &base.replace(from, to), &[]);
        assert!(
            e.contains(&format!("scene.ron:{place}: Unexpected field named")),
            "{to}: {e}"
        );
    }
    // Camera variants other than LookAt.
    let text = base.replace(
        "LookAt(eye: (0.0, 0.0, 5.0), target: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0))",
        "Angles(position: (0.0, 0.0, 5.0), angles: (0.0, 0.0, 0.0), fov: 1.0)",
    );
    let e = scene_error("unknown", &text, &[]);
    assert!(
        e.contains("scene.ron:3:72: Unexpected field named `fov`"),
        "{e}"
    );
}

/// CRC-32 (IEEE) of `data`, for hand-made PNG chunks.
fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A PNG that only has a header claiming `w`x`h` pixels (and a truncated
/// data chunk): decoding it fails, reading its size does not.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], data: &[u8]| {
        png.extend((data.len() as u32).to_be_bytes());
        let mut body = kind.to_vec();
        body.extend(data);
        png.extend(&body);
        png.extend(crc32(&body).to_be_bytes());
    };
    let mut ihdr = w.to_be_bytes().to_vec();
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]); // 8-bit RGB
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c]);
    png
}

#[test]
fn huge_textures_are_refused_from_their_header() {
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    let text = obj_scene("Texture(file: \"t.png\")");
    let e = scene_error(
        "huge",
        &text,
        &[("m.obj", obj), ("t.png", &png_header_only(8192, 8192))],
    );
    assert!(e.contains("scene.ron:6:55: texture "), "{e}");
    assert!(
        e.contains("t.png is 8192x8192 pixels: expected at most 4096x4096"),
        "{e}"
    );
    // Within the limit, the same broken file fails when decoded.
    let e = scene_error(
        "huge",
        &text,
        &[("m.obj", obj), ("t.png", &png_header_only(64, 64))],
    );
    assert!(e.contains("cannot read PNG"), "{e}");
}

/// Renders scene `text` with `--method both` and returns the error and
/// the files in the directory afterwards.
fn both_error(tag: &str, text: &str) -> (String, Vec<String>) {
    let d = temp_dir(tag);
    let p = d.join("scene.ron");
    std::fs::write(&p, text).unwrap();
    let out = d.join("o.png");
    let e = run_err(&[
        "render",
        p.to_str().unwrap(),
        "--method",
        "both",
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ]);
    let mut files: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|f| f.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    (e, files)
}

#[test]
fn method_both_writes_nothing_when_a_path_fails() {
    let cube = "(mesh: \"builtin:cube\", material: Flat((1, 2, 3)))";
    let parallel = format!("{HEAD}    objects: [{cube}],\n)\n")
        .replace("Perspective(fov_x_degrees: 60.0)", "Parallel(width: 4.0)");
    let (e, files) = both_error("both-parallel", &parallel);
    assert!(e.contains("(ray)") && e.contains("perspective"), "{e}");
    assert_eq!(files, ["scene.ron"]);
    let many = vec![cube; 33].join(", ");
    let (e, files) = both_error("both-many", &format!("{HEAD}    objects: [{many}],\n)\n"));
    assert!(e.contains("more than 32 objects"), "{e}");
    assert_eq!(files, ["scene.ron"]);
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let d = temp_dir("bom");
    let p = d.join("scene.ron");
    let text = format!(
        "\u{feff}{HEAD}    objects: [(mesh: \"builtin:cube\", material: Flat((1, 2, 3)))],\n)\n"
    );
    std::fs::write(&p, text).unwrap();
    let out = d.join("o.png");
    run_ok(&[
        "render",
        p.to_str().unwrap(),
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(out.is_file());
}

#[test]
fn help_subcommand_takes_help() {
    for args in [&["help", "--help"][..], &["help"], &["help", "render"]] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_sightline-sim"))
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success(), "{args:?}: {out:?}");
        let stdout = String::from_utf8(out.stdout).unwrap();
        assert!(
            stdout.contains("Usage: sightline-sim"),
            "{args:?}: {stdout}"
        );
        if args.len() == 2 {
            assert!(
                stdout.contains(&format!(
                    "sightline-sim {}",
                    args[1].trim_start_matches('-')
                )) || args[1] == "--help",
                "{stdout}"
            );
        }
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sightline-sim"))
        .args(["help", "render"])
        .output()
        .unwrap();
    assert!(String::from_utf8(out.stdout).unwrap().contains("--method"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sightline-sim"))
        .args(["help", "frobnicate"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
}

#[test]
fn unknown_scene_lists_every_scene_the_cli_accepts() {
    let e = run_err(&["render", "no-such-scene"]);
    for s in builtin::ALL {
        assert!(e.contains(s.name), "{e}");
    }
    assert!(e.contains("maze"), "{e}");
}

#[test]
fn bad_faces_are_refused_with_their_line() {
    let flat = obj_scene("Flat((1, 2, 3))");
    // An L-shaped hexagon: not convex, a fan from vertex 1 is wrong.
    let obj = b"v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n\nf 1 2 3 4 5 6\n";
    let e = scene_error("concave", &flat, &[("m.obj", obj)]);
    assert!(
        e.contains("m.obj:8:1: face with 6 vertices is not convex"),
        "{e}"
    );
    // A convex quad is fine.
    let d = temp_dir("convex");
    std::fs::write(
        d.join("m.obj"),
        b"v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4\n",
    )
    .unwrap();
    std::fs::write(d.join("scene.ron"), &flat).unwrap();
    let (p, out) = (d.join("scene.ron"), d.join("o.png"));
    run_ok(&[
        "render",
        p.to_str().unwrap(),
        "--size",
        "8x8",
        "--out",
        out.to_str().unwrap(),
    ]);
    // Faces with two vertices.
    let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2\n";
    let e = scene_error("twoverts", &flat, &[("m.obj", obj)]);
    assert!(
        e.contains("m.obj:5:1: face with 2 vertices: expected at least 3"),
        "{e}"
    );
}

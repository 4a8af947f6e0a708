//! `render SCENE --frames N`: the animated PNG decodes as N whole frames,
//! frame 0 is the still, the scene really turns, and bad options fail
//! with a clear message and no file.

use sightline_sim::image::read_png_rgb8;
use sightline_sim::{RunError, run};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicU32 = AtomicU32::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("sightline-sim-tt-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run_args(args: &[&str]) -> Result<String, RunError> {
    let mut out = Vec::new();
    let mut full = vec!["sightline-sim"];
    full.extend_from_slice(args);
    run(full, &mut out).map(|()| String::from_utf8(out).unwrap())
}

fn run_ok(args: &[&str]) -> String {
    run_args(args).unwrap_or_else(|e| panic!("{args:?} failed: {e}"))
}

fn files_in(d: &Path) -> Vec<String> {
    let mut f: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|f| f.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    f.sort();
    f
}

/// A decoded APNG: the acTL frame and play counts, and each frame's
/// control chunk and RGB bytes.
struct Apng {
    num_frames: u32,
    num_plays: u32,
    frames: Vec<(png::FrameControl, Vec<u8>)>,
}

fn decode_apng(path: &Path) -> Apng {
    let file = std::fs::File::open(path).unwrap();
    let dec = png::Decoder::new(std::io::BufReader::new(file));
    let mut reader = dec.read_info().unwrap();
    let info = reader.info();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let actl = info.animation_control.expect("an animated PNG (acTL)");
    let mut frames = Vec::new();
    for _ in 0..actl.num_frames {
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let out = reader.next_frame(&mut buf).unwrap();
        buf.truncate(out.buffer_size());
        let fctl = *reader.info().frame_control().expect("fcTL per frame");
        frames.push((fctl, buf));
    }
    Apng {
        num_frames: actl.num_frames,
        num_plays: actl.num_plays,
        frames,
    }
}

/// Frames of `WxH` whose control chunks cover the whole image, in order.
fn check_frames(a: &Apng, n: u32, (w, h): (u32, u32), fps: u16) {
    assert_eq!(a.num_frames, n);
    assert_eq!(a.num_plays, 0, "loops forever");
    assert_eq!(a.frames.len(), n as usize);
    for (k, (f, rgb)) in a.frames.iter().enumerate() {
        assert_eq!(
            (f.width, f.height, f.x_offset, f.y_offset),
            (w, h, 0, 0),
            "frame {k}"
        );
        assert_eq!((f.delay_num, f.delay_den), (1, fps), "frame {k}");
        assert_eq!(rgb.len(), (w * h * 3) as usize, "frame {k}");
    }
}

/// Every frame differs from every other: the scene turns, and no angle
/// repeats within one turn (for frame counts whose steps avoid the
/// scenes' symmetries).
fn check_all_differ(a: &Apng, scene: &str) {
    for i in 0..a.frames.len() {
        for j in i + 1..a.frames.len() {
            assert_ne!(
                a.frames[i].1, a.frames[j].1,
                "{scene}: frames {i} and {j} are equal"
            );
        }
    }
}

fn turntable(
    scene: &str,
    method: &str,
    frames: u32,
    size: &str,
    fps: Option<&str>,
) -> (PathBuf, PathBuf) {
    let d = temp_dir(scene);
    let anim = d.join("anim.png");
    let still = d.join("still.png");
    let n = frames.to_string();
    let mut args = vec![
        "render",
        scene,
        "--method",
        method,
        "--size",
        size,
        "--frames",
        &n,
        "--out",
        anim.to_str().unwrap(),
    ];
    if let Some(f) = fps {
        args.extend(["--fps", f]);
    }
    let out = run_ok(&args);
    assert!(out.contains("turntable of"), "{out}");
    run_ok(&[
        "render",
        scene,
        "--method",
        method,
        "--size",
        size,
        "--out",
        still.to_str().unwrap(),
    ]);
    (anim, still)
}

#[test]
fn raster_turntables_of_every_builtin_scene_decode_start_at_the_still_and_turn() {
    for scene in ["cube", "bunny", "corridor", "spheres"] {
        // 5 frames: steps of 72°, so no two frames are a quarter or half
        // turn apart (the cube and the square floors look the same then).
        let (anim, still) = turntable(scene, "raster", 5, "48x36", None);
        let a = decode_apng(&anim);
        check_frames(&a, 5, (48, 36), 25);
        let s = read_png_rgb8(&still).unwrap();
        assert_eq!(
            a.frames[0].1, s.rgb,
            "{scene}: frame 0 is the still, pixel for pixel"
        );
        check_all_differ(&a, scene);
    }
}

#[test]
fn ray_turntable_with_fps_and_a_scene_file() {
    let (anim, still) = turntable("spheres", "ray", 5, "40x30", Some("10"));
    let a = decode_apng(&anim);
    check_frames(&a, 5, (40, 30), 10);
    assert_eq!(a.frames[0].1, read_png_rgb8(&still).unwrap().rgb);
    check_all_differ(&a, "spheres (ray)");

    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cube.ron");
    let (anim, still) = turntable(file.to_str().unwrap(), "raster", 3, "40x30", None);
    let a = decode_apng(&anim);
    check_frames(&a, 3, (40, 30), 25);
    assert_eq!(a.frames[0].1, read_png_rgb8(&still).unwrap().rgb);
    check_all_differ(&a, "cube.ron");
}

#[test]
fn method_both_writes_two_turntables() {
    let d = temp_dir("both");
    let base = d.join("t.png");
    run_ok(&[
        "render",
        "cube",
        "--method",
        "both",
        "--size",
        "24x18",
        "--frames",
        "3",
        "--out",
        base.to_str().unwrap(),
    ]);
    assert_eq!(files_in(&d), ["t-raster.png", "t-ray.png"]);
    for f in ["t-raster.png", "t-ray.png"] {
        check_frames(&decode_apng(&d.join(f)), 3, (24, 18), 25);
    }
}

#[test]
fn one_frame_is_the_still_png() {
    let d = temp_dir("one");
    let f = d.join("one.png");
    run_ok(&[
        "render",
        "cube",
        "--size",
        "16x12",
        "--frames",
        "1",
        "--out",
        f.to_str().unwrap(),
    ]);
    let dec = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&f).unwrap()));
    assert!(dec.read_info().unwrap().info().animation_control.is_none());
}

/// Usage errors (exit status 2) with the message clap prints.
fn usage_error(args: &[&str]) -> String {
    match run_args(args) {
        Err(RunError::Usage(e)) => {
            assert!(e.use_stderr(), "{args:?}: {e}");
            e.to_string()
        }
        Ok(_) => panic!("{args:?} should fail"),
        Err(e) => panic!("{args:?}: expected a usage error, got {e}"),
    }
}

#[test]
fn bad_frames_and_fps_are_usage_errors_that_say_what_is_expected() {
    for bad in ["0", "-1", "two", "1.5", "", "4294967296"] {
        let arg = format!("--frames={bad}");
        let e = usage_error(&["render", "cube", &arg]);
        assert!(
            e.contains("--frames") && e.contains("at least 1"),
            "{bad:?}: {e}"
        );
    }
    for bad in ["0", "101", "x"] {
        let e = usage_error(&["render", "cube", "--frames", "4", "--fps", bad]);
        assert!(e.contains("--fps") && e.contains("1..=100"), "{bad:?}: {e}");
    }
    let e = usage_error(&["render", "cube", "--fps", "10"]);
    assert!(e.contains("--frames"), "{e}");
}

#[test]
fn too_many_pixels_and_the_maze_fail_before_rendering_and_write_nothing() {
    let d = temp_dir("cap");
    let f = d.join("x.png");
    let f = f.to_str().unwrap();
    let t = std::time::Instant::now();
    let e = run_args(&[
        "render",
        "bunny",
        "--size",
        "4096x4096",
        "--frames",
        "2",
        "--out",
        f,
    ])
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("2 frames at 4096x4096 holds 33554432 pixels") && e.contains("at most 16777216"),
        "{e}"
    );
    let e = run_args(&[
        "render", "cube", "--size", "320x240", "--frames", "1000", "--out", f,
    ])
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("76800000 pixels") && e.contains("fewer --frames"),
        "{e}"
    );
    // Refused from the numbers alone, not after rendering.
    assert!(t.elapsed().as_secs() < 5, "{:?}", t.elapsed());
    let e = run_args(&["render", "maze", "--frames", "3", "--out", f])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("maze") && e.contains("--frames"), "{e}");
    assert!(files_in(&d).is_empty(), "{:?}", files_in(&d));
}

#[test]
fn method_both_turntable_writes_nothing_when_the_ray_path_fails() {
    let d = temp_dir("both-fail");
    let p = d.join("scene.ron");
    std::fs::write(
        &p,
        r#"Scene(
    name: "t",
    camera: LookAt(eye: (0.0, 0.0, 5.0), target: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0)),
    projection: Parallel(width: 4.0),
    light: (direction: (0.0, 1.0, 0.0)),
    objects: [(mesh: "builtin:cube", material: Flat((1, 2, 3)))],
)
"#,
    )
    .unwrap();
    let out = d.join("o.png");
    let e = run_args(&[
        "render",
        p.to_str().unwrap(),
        "--method",
        "both",
        "--size",
        "8x8",
        "--frames",
        "3",
        "--out",
        out.to_str().unwrap(),
    ])
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("(ray, turntable frame 0)") && e.contains("perspective"),
        "{e}"
    );
    assert_eq!(files_in(&d), ["scene.ron"]);
}

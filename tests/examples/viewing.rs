//! The viewing pipeline's foundation end to end: one camera built three
//! ways, a cube projected in f64, f32 and I16F16, and the solver's verdict
//! on good and degenerate general cameras.
//!
//! `cargo run --release -p sightline-tests --example viewing`

use sightline::camera::{Camera, Projection};
use sightline::math::Vec3;
use sightline::scalar::{I16F16, Scalar};
use sightline::transform::{Euler, Pose};

const W: u16 = 240;
const H: u16 = 240;

fn cube() -> [Vec3<f64>; 8] {
    core::array::from_fn(|i| {
        let s = |b: usize| if i & b != 0 { 1.0 } else { -1.0 };
        Vec3::new(s(1), s(2), s(4))
    })
}

/// Projects the cube with the camera and object pose given in f64,
/// converted to `T`; returns screen positions in f64.
fn project<T: Scalar>(eye: Vec3<f64>, cam: Euler<f64>, pose: Pose<f64>) -> Vec<Option<(f64, f64)>> {
    let e = |a: Euler<f64>| {
        Euler::new(
            T::from_f64(a.roll),
            T::from_f64(a.pitch),
            T::from_f64(a.yaw),
        )
    };
    let camera = Camera::from_angles(eye.cast::<T>(), e(cam));
    let pose = Pose::new(pose.origin.cast::<T>(), e(pose.angles));
    let m = camera.object_to_view(&pose);
    let proj = Projection::perspective(T::from_i32(200), W, H);
    cube()
        .iter()
        .map(|p| {
            proj.project(m.transform_point3(p.cast::<T>()))
                .map(|(s, _)| (s.x.to_f64(), s.y.to_f64()))
        })
        .collect()
}

fn main() {
    let eye = Vec3::new(0.0, 1.5, 6.0);
    let cam = Euler::new(0.0, -0.2, 0.0);
    let pose = Pose::new(Vec3::new(0.0, 0.0, 0.0), Euler::new(0.1, 0.3, 0.6));

    println!(
        "sightline: a cube seen by a camera at {eye:?}, pitched down 0.2 rad, on a {W}x{H} screen (focus 200 px)\n"
    );
    let reference = project::<f64>(eye, cam, pose);
    println!(
        "{:>6} {:>22} {:>12} {:>12}",
        "vertex", "f64 screen (px)", "f32 err px", "I16F16 err px"
    );
    let f32s = project::<f32>(eye, cam, pose);
    let fxs = project::<I16F16>(eye, cam, pose);
    let err = |a: Option<(f64, f64)>, b: Option<(f64, f64)>| match (a, b) {
        (Some(a), Some(b)) => format!("{:.2e}", (a.0 - b.0).abs().max((a.1 - b.1).abs())),
        _ => "clipped".to_string(),
    };
    for (i, r) in reference.iter().enumerate() {
        let at = r.map_or("behind the eye".to_string(), |(x, y)| {
            format!("({x:8.3}, {y:8.3})")
        });
        println!(
            "{i:>6} {at:>22} {:>12} {:>12}",
            err(*r, f32s[i]),
            err(*r, fxs[i])
        );
    }

    // The same camera from its orthonormal axes and from the general
    // (solver) form: identical world→view maps up to rounding.
    let a = Camera::from_angles(eye, cam);
    let (right, down, forward) = a.view_axes();
    let b = Camera::from_orthonormal(eye, right, down, forward).expect("axes of a rotation");
    let (c, diag) = Camera::from_vectors(eye, right, down, forward).expect("orthonormal");
    let p = Vec3::new(0.3, -0.7, 0.2);
    let pa = a.world_to_view().transform_point3(p);
    let d = |q: Vec3<f64>| (q - pa).max_abs();
    println!(
        "\nthree camera forms on one point: orthonormal differs by {:.1e}, general (solver) by {:.1e}; solver growth {:.3}, rcond {:.3}",
        d(b.world_to_view().transform_point3(p)),
        d(c.world_to_view().transform_point3(p)),
        diag.growth,
        diag.rcond
    );

    // A sheared general camera, and two that the solver refuses.
    let sheared = Camera::from_vectors(
        eye,
        Vec3::new(1.0, 0.2, 0.0),
        Vec3::new(0.0, -1.0, 0.1),
        Vec3::new(0.1, 0.0, -1.0),
    );
    match sheared {
        Ok((_, d)) => println!(
            "sheared general camera: accepted, growth {:.3}, rcond {:.3}",
            d.growth, d.rcond
        ),
        Err(e) => println!("sheared general camera: {e}"),
    }
    let x = Vec3::new(1.0f32, 0.0, 0.0);
    for (what, v) in [
        ("parallel", x * 2.0),
        ("nearly parallel (1e-4 rad)", Vec3::new(1.0, 1e-4, 0.0)),
    ] {
        match Camera::from_vectors(Vec3::ZERO, x, v, Vec3::new(0.0, 0.0, 1.0)) {
            Ok(_) => println!("{what} vectors in f32: accepted"),
            Err(e) => println!("{what} vectors in f32: error: {e}"),
        }
    }
}

//! Writes the built-in scenes, prepared on this host, as Rust source with
//! `sightline::scene::export::write_scene` (as the size/RAM firmware's
//! build.rs does), so `tests/tests/prepared_export.rs` can compile them and
//! compare them with preparation at run time.
use sightline::math::Vec3;
use sightline::scalar::I16F16;
use sightline::scene::export::{ScalarLiteral, write_scene};
use sightline::scene::{PreparedObject, Scene, builtin};
use std::{env, fs, path::PathBuf};

fn export<S: ScalarLiteral>(scene: &Scene<'static>, path: &str, file: &str) {
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let mut code = String::new();
    write_scene(&mut code, path, scene, 320, 240, &mut vec3s, &mut objects)
        .unwrap_or_else(|e| panic!("{path}: {e}"));
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    fs::write(out.join(file), code).unwrap_or_else(|e| panic!("{file}: {e}"));
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let b = "::sightline::scene::builtin::";
    export::<I16F16>(&builtin::CUBE, &format!("{b}CUBE"), "cube_i16f16.rs");
    export::<I16F16>(&builtin::BUNNY, &format!("{b}BUNNY"), "bunny_i16f16.rs");
    export::<I16F16>(
        &builtin::CORRIDOR,
        &format!("{b}CORRIDOR"),
        "corridor_i16f16.rs",
    );
    export::<I16F16>(
        &builtin::CORRIDOR_AFFINE,
        &format!("{b}CORRIDOR_AFFINE"),
        "corridor_affine_i16f16.rs",
    );
    export::<f32>(&builtin::BUNNY, &format!("{b}BUNNY"), "bunny_f32.rs");
}

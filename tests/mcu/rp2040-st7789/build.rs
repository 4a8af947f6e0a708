//! Puts `memory.x` on the linker search path for cortex-m-rt's `link.x`,
//! and writes the built-in bunny, prepared here on the host for a 240×240
//! display in I16F16, as const data (`sightline::scene::export`): the
//! firmware then does no f32 arithmetic, normalization or camera set-up,
//! and the prepared positions and normals sit in flash, not RAM.
use sightline::math::Vec3;
use sightline::scalar::I16F16;
use sightline::scene::export::write_scene;
use sightline::scene::{PreparedObject, builtin};
use std::{env, fs, path::PathBuf};

/// Display side in pixels (`SIDE` in src/main.rs checks it).
const SIDE: u16 = 240;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("write memory.x");

    let scene = &builtin::BUNNY;
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let mut code = String::new();
    let path = "::sightline::scene::builtin::BUNNY";
    write_scene(&mut code, path, scene, SIDE, SIDE, &mut vec3s, &mut objects)
        .unwrap_or_else(|e| panic!("the bunny: {e}"));
    fs::write(out.join("bunny.rs"), code).expect("write bunny.rs");

    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
}

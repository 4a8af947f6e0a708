//! Puts `memory.x` (ARM) and `riscv.x` (RISC-V size builds) on the linker
//! search path for cortex-m-rt's `link.x`, and writes the built-in scenes
//! the size/RAM firmware draws as prepared I16F16 const data
//! (`sightline::scene::export`): prepared here, on the host, so the
//! firmware does no f32 arithmetic, normalization or camera solving.
use sightline::math::Vec3;
use sightline::scalar::I16F16;
use sightline::scene::export::write_scene;
use sightline::scene::{PreparedObject, Scene, builtin};
use std::{env, fs, path::Path, path::PathBuf};

/// The firmware's image size (`WIDTH`/`HEIGHT` in src/scene.rs).
const WIDTH: u16 = 320;
const HEIGHT: u16 = 240;

fn export(out: &Path, scene: &Scene<'static>, name: &str) {
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let mut code = String::new();
    let path = format!("::sightline::scene::builtin::{name}");
    write_scene(
        &mut code,
        &path,
        scene,
        WIDTH,
        HEIGHT,
        &mut vec3s,
        &mut objects,
    )
    .unwrap_or_else(|e| panic!("{name}: {e}"));
    let file = out.join(format!("{}.rs", name.to_lowercase()));
    fs::write(&file, code).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
}

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR"));
    fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("write memory.x");
    fs::write(out.join("riscv.x"), include_bytes!("riscv.x")).expect("write riscv.x");
    export(&out, &builtin::CUBE, "CUBE");
    export(&out, &builtin::BUNNY, "BUNNY");
    export(&out, &builtin::CORRIDOR, "CORRIDOR");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=riscv.x");
    println!("cargo:rerun-if-changed=build.rs");
}

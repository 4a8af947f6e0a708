//! `scene::export` against preparation at run time: `tests/build.rs`
//! prepares built-in scenes on the host and writes them as Rust source
//! with `write_prepared` (as the size/RAM firmware's build.rs does); here
//! that source is compiled, and its objects, renderer and a rendered frame
//! must equal what `Scene::prepare` and `Renderer::new` give, bit for bit.

use sightline::math::Vec3;
use sightline::pipeline::MeshVertex;
use sightline::raster::DepthBuffer;
use sightline::scalar::{I16F16, Scalar};
use sightline::scene::{Color, PreparedObject, Renderer, Scene, builtin};
use sightline::target::Framebuffer;

mod cube {
    include!(concat!(env!("OUT_DIR"), "/cube_i16f16.rs"));
}
mod bunny {
    include!(concat!(env!("OUT_DIR"), "/bunny_i16f16.rs"));
}
mod bunny_f32 {
    include!(concat!(env!("OUT_DIR"), "/bunny_f32.rs"));
}
mod corridor {
    include!(concat!(env!("OUT_DIR"), "/corridor_i16f16.rs"));
}
mod corridor_affine {
    include!(concat!(env!("OUT_DIR"), "/corridor_affine_i16f16.rs"));
}

const W: u16 = 320;
const H: u16 = 240;

/// Every pixel of one frame, drawn with a depth buffer.
fn render<S: Scalar>(renderer: &Renderer<S>, objects: &mut [PreparedObject<'_, S>]) -> Vec<Color> {
    let vertices: usize = objects.iter().map(|o| o.mesh.positions().len()).sum();
    let mut scratch = vec![MeshVertex::default(); vertices];
    let frame = renderer
        .project(objects, &mut scratch)
        .expect("scratch fits");
    let mut color = vec![Color::new(0, 0, 0); usize::from(W) * usize::from(H)];
    let mut depth = vec![0u16; color.len()];
    let mut fb = Framebuffer::new(&mut color, W, H, usize::from(W)).unwrap();
    let mut z = DepthBuffer::new(&mut depth, W, H, usize::from(W), 0).unwrap();
    let stats = frame.draw(&mut fb, &mut z);
    assert!(stats.drawn > 0, "{stats:?}");
    color
}

fn same_as_run_time<S: Scalar, const N: usize>(
    name: &str,
    scene: &Scene<'static>,
    exported: [PreparedObject<'static, S>; N],
    exported_renderer: Renderer<S>,
    vertices: usize,
) {
    let need = scene.storage();
    assert_eq!(need.vertices, vertices, "{name}: VERTICES");
    let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = scene.prepare(&mut vec3s, &mut objects).unwrap();
    assert_eq!(objects.len(), N, "{name}: object count");
    for (k, (a, b)) in objects.iter().zip(&exported).enumerate() {
        let (ma, mb) = (&a.mesh, &b.mesh);
        assert!(
            ma.positions() == mb.positions(),
            "{name} object {k}: positions"
        );
        assert!(
            ma.face_normals() == mb.face_normals(),
            "{name} object {k}: face normals"
        );
        assert!(
            ma.vertex_normals() == mb.vertex_normals(),
            "{name} object {k}: vertex normals"
        );
        assert_eq!(
            ma.triangles(),
            mb.triangles(),
            "{name} object {k}: triangles"
        );
        assert_eq!(ma.uvs(), mb.uvs(), "{name} object {k}: uvs");
        assert_eq!(ma.is_closed(), mb.is_closed(), "{name} object {k}: closed");
        assert!(a.pose == b.pose, "{name} object {k}: pose");
        assert_eq!(a.cull, b.cull, "{name} object {k}: cull");
    }
    let renderer = Renderer::<S>::new(scene, W, H).unwrap();
    let (va, vb) = (renderer.view(), exported_renderer.view());
    assert!(va.camera == vb.camera, "{name}: camera");
    assert!(va.projection == vb.projection, "{name}: projection");
    assert_eq!((va.width, va.height), (vb.width, vb.height), "{name}: size");
    assert!(
        renderer.light() == exported_renderer.light(),
        "{name}: light"
    );
    assert!(
        renderer.depth_range() == exported_renderer.depth_range(),
        "{name}: depth range"
    );
    assert_eq!(
        renderer.background(),
        exported_renderer.background(),
        "{name}: background"
    );
    assert_eq!(
        renderer.clips_far(),
        exported_renderer.clips_far(),
        "{name}: far clip"
    );
    let mut exported = exported;
    let a = render(&renderer, objects);
    let b = render(&exported_renderer, &mut exported);
    let differ = a.iter().zip(&b).filter(|(p, q)| p != q).count();
    assert_eq!(differ, 0, "{name}: {differ} pixels differ");
}

/// `same_as_run_time` for the exported module `$m` of built-in scene `$scene`.
macro_rules! check {
    ($m:ident, $name:expr, $scene:expr, $S:ty, $N:literal) => {
        same_as_run_time::<$S, $N>(
            $name,
            &$scene,
            $m::objects().unwrap(),
            $m::renderer().unwrap(),
            $m::VERTICES,
        )
    };
}

#[test]
fn exported_cube_equals_run_time_preparation() {
    check!(cube, "cube", builtin::CUBE, I16F16, 2);
}

#[test]
fn exported_bunny_equals_run_time_preparation() {
    check!(bunny, "bunny", builtin::BUNNY, I16F16, 2);
    check!(bunny_f32, "bunny f32", builtin::BUNNY, f32, 2);
}

#[test]
fn exported_corridors_equal_run_time_preparation() {
    check!(corridor, "corridor", builtin::CORRIDOR, I16F16, 1);
    check!(
        corridor_affine,
        "corridor-affine",
        builtin::CORRIDOR_AFFINE,
        I16F16,
        1
    );
}

/// The generated constants name the module's shape.
#[test]
fn exported_sizes() {
    assert_eq!((cube::WIDTH, cube::HEIGHT, cube::OBJECTS), (W, H, 2));
    assert_eq!(
        bunny::POSITIONS_1.len(),
        builtin::BUNNY.objects[1].mesh.positions.len()
    );
    assert_eq!(cube::FACE_NORMALS_1.len(), 12);
    assert!(cube::VERTEX_NORMALS_1.is_empty());
}

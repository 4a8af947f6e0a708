//! What a build with fewer stages does, for whatever features are on:
//! a material whose stage is left out is refused with
//! [`SceneError::FeatureDisabled`] before anything is drawn, flat scenes
//! render with any feature set, and the far plane clips only when the
//! caller asks (`with_far_clip`, feature `clip-far`).

use super::builtin::{BUNNY, CORRIDOR, CORRIDOR_AFFINE, CUBE};
use super::*;
use crate::camera::Projection;
use crate::math::Vec3;
use crate::pipeline::DrawOutcome;
use crate::pipeline::{Pipeline, Vertex};
use crate::raster::{FillOutcome, Flat, NoDepth};
use crate::scalar::{I16F16, Scalar};
use crate::target::Framebuffer;
use crate::transform::{Euler, Pose};
use std::vec;

const SENTINEL: Color = Color::new(1, 2, 3);

/// Prepares `scene` in `S` (storage from `Vec`s), projects one frame at
/// `w`×`h` and hands it to `draw`: what a host caller writes.
pub(super) fn with_frame<S: Scalar, R>(
    scene: &Scene<'_>,
    w: u16,
    h: u16,
    draw: impl FnOnce(&Frame<'_, '_, S>) -> R,
) -> Result<R, SceneError> {
    let need = scene.storage();
    let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = scene.prepare(&mut vec3s, &mut objects)?;
    let renderer = Renderer::<S>::new(scene, w, h)?;
    let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices];
    let frame = renderer.project(objects, &mut scratch)?;
    Ok(draw(&frame))
}

/// Renders `scene` at 64×48 without a depth buffer; returns the result
/// and the pixels.
fn render(scene: &Scene<'_>) -> (Result<RasterStats, SceneError>, std::vec::Vec<Color>) {
    let (w, h) = (64u16, 48u16);
    let mut px = vec![SENTINEL; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
    let r = with_frame::<I16F16, _>(scene, w, h, |f| f.draw(&mut fb, &mut NoDepth));
    (r, px)
}

fn expect(scene: &Scene<'_>, missing: Option<&'static str>) {
    let (r, px) = render(scene);
    match missing {
        Some(feature) => {
            assert_eq!(
                r,
                Err(SceneError::FeatureDisabled { feature }),
                "{}",
                scene.name
            );
            assert!(
                px.iter().all(|&c| c == SENTINEL),
                "{}: drew before refusing",
                scene.name
            );
        }
        None => {
            let stats = r.unwrap();
            assert!(stats.drawn > 0, "{}: {stats:?}", scene.name);
            let bg = px.iter().filter(|&&c| c == scene.background).count();
            assert!(bg < px.len(), "{}: only background", scene.name);
            assert!(
                !px.contains(&SENTINEL),
                "{}: background not filled",
                scene.name
            );
        }
    }
}

#[test]
fn flat_scenes_render_with_any_features() {
    expect(&CUBE, None);
}

#[test]
fn left_out_materials_are_refused_before_drawing() {
    expect(&BUNNY, (!cfg!(feature = "gouraud")).then_some("gouraud"));
    let texture = if !cfg!(feature = "texture") {
        Some("texture")
    } else if !cfg!(feature = "perspective") {
        Some("perspective")
    } else {
        None
    };
    expect(&CORRIDOR, texture);
    let affine = (!cfg!(feature = "texture")).then_some("texture");
    expect(&CORRIDOR_AFFINE, affine);
}

#[test]
fn the_far_plane_clips_only_when_asked() {
    let base = Pipeline::new(
        Projection::perspective(100.0f32, 64, 48),
        64,
        48,
        0.5,
        10.0,
        16.0,
    )
    .unwrap();
    // A triangle at z = 20, beyond far = 10, covering the screen center.
    let tri = [(-5.0, -5.0), (5.0, -5.0), (0.0, 5.0)]
        .map(|(x, y)| Vertex::new(Vec3::new(x, y, 20.0f32), ()));
    let draw = |pipe: &Pipeline<f32>| {
        let mut px = vec![SENTINEL; 64 * 48];
        let mut fb = Framebuffer::new(&mut px, 64, 48, 64).unwrap();
        let r = pipe.draw_polygon(&mut fb, &mut NoDepth, &Flat(Color::new(31, 0, 0)), &tri);
        (r, px.iter().filter(|&&c| c == Color::new(31, 0, 0)).count())
    };
    // Whatever the features, a new pipeline draws it (features never
    // change behavior).
    assert!(!base.clips_far());
    let (r, drawn) = draw(&base);
    assert_eq!(r, Ok(DrawOutcome::Filled(FillOutcome::Drawn)));
    assert!(drawn > 100, "{drawn}");
    #[cfg(feature = "clip-far")]
    {
        let clipped = base.with_far_clip(true);
        assert!(clipped.clips_far());
        let (r, drawn) = draw(&clipped);
        assert_ne!(r, Ok(DrawOutcome::Filled(FillOutcome::Drawn)));
        assert_eq!(drawn, 0);
        // And back.
        assert_eq!(draw(&clipped.with_far_clip(false)), draw(&base));
    }
}

#[test]
fn builtin_closed_flags_match_the_edges() {
    // `closed` is data: check it against the definition (every directed
    // edge once, and its reverse too).
    use std::collections::HashSet;
    for mesh in [
        &super::builtin::CUBE_MESH,
        &super::builtin::FLOOR_MESH,
        &super::builtin::BUNNY_MESH,
    ] {
        let mut edges = HashSet::new();
        let mut unique = true;
        for t in mesh.triangles {
            for i in 0..3 {
                unique &= edges.insert((t[i], t[(i + 1) % 3]));
            }
        }
        let closed = unique && edges.iter().all(|&(a, b)| edges.contains(&(b, a)));
        assert_eq!(mesh.closed, closed, "{} triangles", mesh.triangles.len());
    }
}

#[test]
fn too_small_storage_and_scratch_are_errors_before_drawing() {
    let need = CUBE.storage();
    let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s - 1];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    assert_eq!(
        CUBE.prepare(&mut vec3s, &mut objects).err(),
        Some(SceneError::Storage)
    );
    // (A failed `prepare` keeps its storage borrowed: fresh storage.)
    let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = CUBE.prepare(&mut vec3s, &mut objects).unwrap();
    let renderer = Renderer::<I16F16>::new(&CUBE, 16, 16).unwrap();
    let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices - 1];
    assert_eq!(
        renderer.project(objects, &mut scratch).err(),
        Some(SceneError::ScratchTooSmall {
            needed: need.vertices,
            given: need.vertices - 1
        })
    );
}

#[test]
fn non_finite_scene_numbers_are_refused_by_name() {
    let light = Light {
        ambient: f32::NAN,
        ..CUBE.light
    };
    let far = Scene {
        far: f32::INFINITY,
        ..CUBE
    };
    let lit = Scene { light, ..CUBE };
    let eye = Scene {
        camera: CameraSpec::LookAt {
            eye: [f32::NAN, 0.0, 0.0],
            target: [0.0; 3],
            up: [0.0, 1.0, 0.0],
        },
        ..CUBE
    };
    for (scene, what) in [(&far, "far"), (&lit, "light"), (&eye, "camera")] {
        assert_eq!(
            Renderer::<f32>::new(scene, 16, 16).err(),
            Some(SceneError::NonFinite { what })
        );
    }
    let mut r = Renderer::<f32>::new(&CUBE, 16, 16).unwrap();
    assert_eq!(
        r.set_light(&light),
        Err(SceneError::NonFinite { what: "light" })
    );
}

#[test]
fn closed_meshes_cull_back_faces_without_a_depth_buffer() {
    // The cube drawn without depth: with culling only its front faces
    // reach the image, so it equals the depth-tested image; drawn with
    // `Cull::None` the back faces paint over some front pixels.
    let (w, h) = (48u16, 36u16);
    let draw = |cull: Option<crate::pipeline::Cull>, with_depth: bool| {
        let need = CUBE.storage();
        let mut vec3s = vec![Vec3::<f32>::ZERO; need.vec3s];
        let mut objects = vec![PreparedObject::EMPTY; need.objects];
        let objects = CUBE.prepare(&mut vec3s, &mut objects).unwrap();
        if let Some(c) = cull {
            for o in objects.iter_mut() {
                o.cull = c;
            }
        }
        let renderer = Renderer::<f32>::new(&CUBE, w, h).unwrap();
        let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices];
        let frame = renderer.project(objects, &mut scratch).unwrap();
        let mut px = vec![SENTINEL; w as usize * h as usize];
        let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
        let stats = if with_depth {
            #[cfg(feature = "depth")]
            {
                let mut keys = vec![u16::MAX; px_len(w, h)];
                let mut z =
                    crate::raster::DepthBuffer::new(&mut keys, w, h, w as usize, 0).unwrap();
                frame.draw(&mut fb, &mut z)
            }
            #[cfg(not(feature = "depth"))]
            frame.draw(&mut fb, &mut NoDepth)
        } else {
            frame.draw(&mut fb, &mut NoDepth)
        };
        (px, stats)
    };
    let (culled, stats) = draw(None, false);
    assert!(stats.culled >= 5, "{stats:?}");
    let (all, _) = draw(Some(crate::pipeline::Cull::None), false);
    assert_ne!(
        culled, all,
        "back faces drawn over front faces without culling"
    );
    if cfg!(feature = "depth") {
        let (depth_tested, _) = draw(None, true);
        assert_eq!(culled, depth_tested);
    }
}

#[cfg(feature = "depth")]
fn px_len(w: u16, h: u16) -> usize {
    w as usize * h as usize
}

#[test]
fn storage_for_any_fits_each_scene() {
    let all = Storage::for_any(&[&CUBE, &BUNNY, &CORRIDOR]);
    for s in [&CUBE, &BUNNY, &CORRIDOR] {
        let n = s.storage();
        assert!(n.vec3s <= all.vec3s && n.objects <= all.objects && n.vertices <= all.vertices);
    }
    // The bunny has the most of everything but objects (cube and bunny
    // both have two).
    assert_eq!(all, BUNNY.storage());
}

#[cfg(feature = "gouraud")]
#[test]
fn a_material_changed_after_preparing_draws_without_panicking() {
    // The objects' fields are public: a flat-prepared cube (no vertex
    // normals) switched to Gouraud is lit by the ambient term, not a panic.
    let need = CUBE.storage();
    let mut vec3s = vec![Vec3::<f32>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = CUBE.prepare(&mut vec3s, &mut objects).unwrap();
    for o in objects.iter_mut() {
        o.material = Material::Gouraud(Color::new(31, 63, 31));
    }
    let renderer = Renderer::<f32>::new(&CUBE, 32, 24).unwrap();
    let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices];
    let frame = renderer.project(objects, &mut scratch).unwrap();
    let mut px = vec![SENTINEL; 32 * 24];
    let mut fb = Framebuffer::new(&mut px, 32, 24, 32).unwrap();
    assert!(frame.draw(&mut fb, &mut NoDepth).drawn > 0);
}

/// A renderer rebuilt from its own parts (`from_prepared`, what exported
/// const data does) draws the same pixels; a non-finite light is refused
/// by `PreparedLight::from_light`.
#[test]
fn renderer_from_prepared_parts_draws_the_same() {
    let (w, h) = (64u16, 48u16);
    let a = Renderer::<I16F16>::new(&CUBE, w, h).unwrap();
    let view = *a.view();
    let camera = crate::camera::Camera::from_world_to_view(
        view.camera.position(),
        *view.camera.world_to_view(),
    )
    .unwrap();
    let (near, far) = a.depth_range();
    let light = PreparedLight::from_unit(
        a.light().direction(),
        a.light().ambient(),
        a.light().diffuse(),
    );
    let b =
        Renderer::from_prepared(View { camera, ..view }, near, far, light, a.background()).unwrap();
    let need = CUBE.storage();
    let mut vec3s = vec![Vec3::<I16F16>::ZERO; need.vec3s];
    let mut objects = vec![PreparedObject::EMPTY; need.objects];
    let objects = CUBE.prepare(&mut vec3s, &mut objects).unwrap();
    let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices];
    let mut px = [
        vec![SENTINEL; usize::from(w) * usize::from(h)],
        vec![SENTINEL; usize::from(w) * usize::from(h)],
    ];
    for (r, buf) in [&a, &b].into_iter().zip(px.iter_mut()) {
        let frame = r.project(objects, &mut scratch).unwrap();
        let mut fb = Framebuffer::new(buf, w, h, usize::from(w)).unwrap();
        assert!(frame.draw(&mut fb, &mut NoDepth).drawn > 0);
    }
    assert!(px[0] == px[1]);
    let mut bad = CUBE.light;
    bad.diffuse = f32::NAN;
    assert_eq!(
        PreparedLight::<I16F16>::from_light(&bad),
        Err(SceneError::NonFinite { what: "light" })
    );
    assert!(PreparedLight::<I16F16>::from_light(&CUBE.light).unwrap() == a.light());
    // A float light from parts is checked by the renderer.
    let f = Renderer::<f32>::new(&CUBE, w, h).unwrap();
    let (near, far) = f.depth_range();
    let nan = PreparedLight::from_unit(Vec3::new(0.0, f32::NAN, 1.0), 0.2, 0.8);
    assert!(!nan.is_finite() && f.light().is_finite());
    assert!(matches!(
        Renderer::from_prepared(*f.view(), near, far, nan, f.background()),
        Err(SceneError::NonFinite { what: "light" })
    ));
    let inf = PreparedLight::from_unit(Vec3::new(0.0, 0.0, 1.0), f32::INFINITY, 0.8);
    assert!(Renderer::from_prepared(*f.view(), near, far, inf, f.background()).is_err());
}

/// `triangle_hash` is FNV-1a over the indices' little-endian bytes: the
/// same as hashing the byte string, and it tells apart a swapped index.
#[test]
fn triangle_hash_is_fnv1a_of_the_index_bytes() {
    let tris = CUBE.objects[1].mesh.triangles;
    let bytes: std::vec::Vec<u8> = tris
        .iter()
        .flatten()
        .flat_map(|k| k.to_le_bytes())
        .collect();
    let fnv = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    assert_eq!(triangle_hash(tris), fnv);
    assert_eq!(triangle_hash(&[]), 0xcbf2_9ce4_8422_2325);
    let mut swapped = tris.to_vec();
    swapped[0].swap(0, 1);
    assert_ne!(triangle_hash(&swapped), fnv);
}

/// Renders `scene` at `w`×`h` without a depth buffer with [`Frame::draw`]
/// (`unclipped` false) or [`Frame::draw_unclipped`], over a sentinel;
/// returns the draw's result, whether the frame needed clipping, and the
/// pixels.
#[allow(clippy::type_complexity)]
fn draw_either(
    scene: &Scene<'_>,
    w: u16,
    h: u16,
    unclipped: bool,
) -> (Result<RasterStats, SceneError>, bool, std::vec::Vec<Color>) {
    let mut px = vec![SENTINEL; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
    let (r, needs) = with_frame::<I16F16, _>(scene, w, h, |f| {
        let r = if unclipped {
            f.draw_unclipped(&mut fb, &mut NoDepth)
        } else {
            Ok(f.draw(&mut fb, &mut NoDepth))
        };
        (r, f.needs_clipping())
    })
    .unwrap();
    (r, needs, px)
}

/// The cube scene (its flat floor reaches a little past the view's sides:
/// within the widened guard band, drawn as it is), the cube alone, and
/// the cube with a second one behind the camera (every vertex outside the
/// near plane: dropped without the clipper): no frame needs clipping, and
/// `draw_unclipped` draws what `draw` does.
#[test]
fn draw_unclipped_draws_what_draw_does() {
    let cube = CUBE.objects[1];
    // The eye is at (3, 2.5, 5) looking at the origin: (9, 7.5, 15) is
    // far behind it.
    let behind = SceneObject {
        pose: Pose::new(Vec3::new(9.0, 7.5, 15.0), Euler::new(0.0, 0.0, 0.0)),
        ..cube
    };
    let alone = [cube];
    let with_behind = [cube, behind];
    // (The floor reaches beyond 1024 pixels at 1007×700: the next test.)
    type Case<'s> = (&'s [SceneObject<'s>], &'s [(u16, u16)]);
    let cases: [Case<'_>; 3] = [
        (CUBE.objects, &[(64, 48), (320, 240)]),
        (&alone, &[(64, 48), (320, 240), (1007, 700)]),
        (&with_behind, &[(64, 48), (320, 240), (1007, 700)]),
    ];
    for (objects, sizes) in cases {
        let scene = Scene { objects, ..CUBE };
        for &(w, h) in sizes {
            let (want, needs, want_px) = draw_either(&scene, w, h, false);
            let (got, needs_u, got_px) = draw_either(&scene, w, h, true);
            assert!(!needs && !needs_u, "{w}x{h}: the cube stays in view");
            let want = want.unwrap();
            assert!(want.drawn > 0 && want.clipped == 0, "{want:?}");
            assert_eq!(got, Ok(want), "{w}x{h}");
            assert!(got_px == want_px, "{w}x{h}: pixels differ");
        }
    }
}

/// A frame with a triangle across a plane is refused whole: the error
/// names the first such object, and not one pixel (not even the
/// background) is written. So is a viewport beyond the 32-bit walk.
#[test]
fn draw_unclipped_refuses_what_needs_the_clipper() {
    // At 1007×700 the cube scene's floor (object 0) reaches beyond 1024
    // pixels, past the widened guard band.
    let (r, needs, px) = draw_either(&CUBE, 1007, 700, true);
    assert!(needs);
    assert_eq!(r, Err(SceneError::NeedsClipping { object: 0 }));
    assert!(px.iter().all(|&c| c == SENTINEL));
    let (drawn, _, _) = draw_either(&CUBE, 1007, 700, false);
    assert!(drawn.unwrap().clipped > 0, "draw clips the floor");

    // A second cube around the eye crosses the near plane.
    let cube = CUBE.objects[1];
    let at_eye = SceneObject {
        pose: Pose::new(Vec3::new(3.0, 2.5, 5.0), Euler::new(0.0, 0.0, 0.0)),
        ..cube
    };
    let objects = [cube, at_eye];
    let scene = Scene {
        objects: &objects,
        ..CUBE
    };
    let (r, needs, px) = draw_either(&scene, 64, 48, true);
    assert!(needs);
    assert_eq!(r, Err(SceneError::NeedsClipping { object: 1 }));
    assert!(px.iter().all(|&c| c == SENTINEL));

    // 1008 pixels and the 16-pixel guard band: 1024 pixels, 2^14 in 28.4.
    let alone = [cube];
    let scene = Scene {
        objects: &alone,
        ..CUBE
    };
    let (r, needs, px) = draw_either(&scene, 1008, 700, true);
    assert!(!needs);
    assert_eq!(r, Err(SceneError::ViewportTooLarge));
    assert!(px.iter().all(|&c| c == SENTINEL));
}

/// Textured objects keep the 16-pixel guard band (see
/// `widen_guard_band`): the corridor's walls, past the sides, are clipped.
#[cfg(feature = "texture")]
#[test]
fn textured_sides_are_clipped() {
    let (r, needs, px) = draw_either(&CORRIDOR_AFFINE, 64, 48, true);
    assert!(needs);
    assert_eq!(r, Err(SceneError::NeedsClipping { object: 0 }));
    assert!(px.iter().all(|&c| c == SENTINEL));
    let (drawn, _, _) = draw_either(&CORRIDOR_AFFINE, 64, 48, false);
    assert!(drawn.unwrap().clipped > 0);
}

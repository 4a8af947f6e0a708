use super::builtin::{self, CUBE, CUBE_MESH};
use super::*;
use crate::math::Vec3;
use crate::raster::{DepthBuffer, ScalableColor};
use crate::scalar::{I16F16, Scalar};
use crate::target::Framebuffer;
use crate::texture::{Texture, TextureError};
use crate::transform::Pose;
use embedded_graphics::pixelcolor::IntoStorage;
use std::vec;

fn raster_image<S: Scalar>(scene: &Scene<'_>, w: u16, h: u16) -> std::vec::Vec<Color> {
    let mut px = vec![Color::new(0, 0, 0); w as usize * h as usize];
    let mut keys = vec![u16::MAX; px.len()];
    let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
    let mut depth = DepthBuffer::new(&mut keys, w, h, w as usize, 0).unwrap();
    let stats =
        super::feature_tests::with_frame::<S, _>(scene, w, h, |f| f.draw(&mut fb, &mut depth))
            .unwrap();
    assert_eq!(stats.errors, 0);
    px
}

fn ray_image<S: Scalar>(scene: &Scene<'_>, w: u16, h: u16) -> std::vec::Vec<Color> {
    let view = scene.view::<S>(w, h).unwrap();
    let rs = RayScene::new(scene, &view).unwrap();
    let mut px = vec![Color::new(0, 0, 0); w as usize * h as usize];
    for (j, row) in px.chunks_mut(w as usize).enumerate() {
        rs.render_row(j as u16, row);
    }
    px
}

#[test]
fn builtin_scenes_validate() {
    for s in builtin::ALL {
        s.validate().unwrap();
        assert_eq!(builtin::by_name(s.name).map(|f| f.name), Some(s.name));
    }
    #[cfg(feature = "column")]
    assert_eq!(
        builtin::COLUMN_MAP.cells.len(),
        builtin::COLUMN_MAP.width as usize * builtin::COLUMN_MAP.height as usize
    );
}

#[test]
fn quantize_matches_floor_of_255_i() {
    assert_eq!(quantize_intensity(0.0f32), 0);
    assert_eq!(quantize_intensity(1.0f32), 255);
    assert_eq!(quantize_intensity(2.0f32), 255);
    assert_eq!(quantize_intensity(-1.0f32), 0);
    assert_eq!(quantize_intensity(0.5f32), 127);
    assert_eq!(quantize_intensity(I16F16::from_f32(0.5)), 127);
}

#[test]
fn flat_cube_agrees_between_paths_in_f32_and_fixed() {
    fn check<S: Scalar>() {
        let a = raster_image::<S>(&CUBE, 64, 48);
        let b = ray_image::<S>(&CUBE, 64, 48);
        let equal = a.iter().zip(&b).filter(|(p, q)| p == q).count();
        assert!(equal * 100 >= a.len() * 99, "{equal} of {}", a.len());
        // The cube's faces are lit differently: several colors appear.
        let mut colors: std::vec::Vec<_> = a.iter().map(|c| c.into_storage()).collect();
        colors.sort_unstable();
        colors.dedup();
        assert!(colors.len() >= 4, "{colors:?}");
    }
    check::<f32>();
    check::<I16F16>();
}

#[test]
fn flat_color_is_base_scaled_by_quantized_intensity() {
    // Looking straight down at the top face of an unrotated cube: n = +Y.
    let objects = [SceneObject {
        mesh: &CUBE_MESH,
        pose: Pose::default(),
        material: Material::Flat(Color::new(31, 63, 31)),
    }];
    let scene = Scene {
        camera: CameraSpec::LookAt {
            eye: [0.0, 5.0, 0.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 0.0, -1.0],
        },
        light: Light {
            direction: [0.0, 1.0, 0.0],
            ambient: 0.1,
            diffuse: 0.4,
        },
        objects: &objects,
        spheres: &[],
        ..CUBE
    };
    let want = Color::new(31, 63, 31).scale(quantize_intensity(0.5f32));
    assert_eq!(raster_image::<f32>(&scene, 8, 8)[4 * 8 + 4], want);
    assert_eq!(ray_image::<f32>(&scene, 8, 8)[4 * 8 + 4], want);
}

#[test]
fn validate_reports_bad_meshes_and_textures() {
    let bad = MeshData {
        triangles: &[[0, 1, 8]],
        ..CUBE_MESH
    };
    let objects = [SceneObject {
        mesh: &bad,
        pose: Pose::default(),
        material: Material::Flat(Color::new(1, 1, 1)),
    }];
    let scene = Scene {
        objects: &objects,
        ..CUBE
    };
    assert_eq!(
        scene.validate(),
        Err(SceneError::IndexOutOfRange {
            object: 0,
            triangle: 0
        })
    );
    let texels = [Color::new(0, 0, 0); 12];
    assert_eq!(
        Texture::new(&texels, 4, 4, 4).err(),
        Some(TextureError::TooShort {
            needed: 16,
            len: 12
        })
    );
    let textured = |texture| {
        [SceneObject {
            mesh: &CUBE_MESH,
            pose: Pose::default(),
            material: Material::Texture {
                texture,
                mode: TextureMode::Auto,
            },
        }]
    };
    // A 4×3 texture is a valid store, but the scene tiles by powers of two.
    let objects = textured(Texture::new(&texels, 4, 3, 4).unwrap());
    let scene = Scene {
        objects: &objects,
        ..CUBE
    };
    assert_eq!(
        scene.validate(),
        Err(SceneError::TextureNotPowerOfTwo {
            width: 4,
            height: 3
        })
    );
    let objects = textured(Texture::new(&texels[..8], 4, 2, 4).unwrap());
    let scene = Scene {
        objects: &objects,
        ..CUBE
    };
    assert_eq!(scene.validate(), Err(SceneError::MissingUv { object: 0 }));
}

#[test]
fn singular_general_camera_and_parallel_ray_are_errors() {
    let scene = Scene {
        camera: CameraSpec::Vectors {
            position: [0.0; 3],
            u: [1.0, 0.0, 0.0],
            v: [2.0, 0.0, 0.0],
            w: [0.0, 0.0, 1.0],
        },
        ..CUBE
    };
    assert!(matches!(
        scene.view::<f32>(8, 8),
        Err(SceneError::Camera(crate::camera::CameraError::Degenerate(
            _
        )))
    ));
    let scene = Scene {
        projection: ProjectionSpec::Parallel { width: 4.0 },
        ..CUBE
    };
    let view = scene.view::<f32>(8, 8).unwrap();
    assert!(matches!(
        RayScene::new(&scene, &view),
        Err(SceneError::RayCamera(_))
    ));
}

#[test]
fn strip_rendering_with_bands_equals_the_whole_frame() {
    use crate::target::Band;
    let (w, h, rows) = (48u16, 36u16, 8u16);
    for scene in [&builtin::BUNNY, &builtin::CORRIDOR] {
        let whole = raster_image::<f32>(scene, w, h);
        let mut strip = vec![Color::new(0, 0, 0); w as usize * rows as usize];
        let mut keys = vec![u16::MAX; strip.len()];
        // One projected frame, drawn band by band.
        super::feature_tests::with_frame::<f32, _>(scene, w, h, |frame| {
            let mut y0 = 0;
            while y0 < h as i32 {
                keys.fill(u16::MAX);
                let mut band = Band::new(&mut strip, w, rows, w as usize, y0).unwrap();
                let mut depth = DepthBuffer::new(&mut keys, w, rows, w as usize, y0).unwrap();
                frame.draw(&mut band, &mut depth);
                for y in y0..(y0 + rows as i32).min(h as i32) {
                    for x in 0..w as i32 {
                        assert_eq!(
                            band.pixel(x, y),
                            Some(whole[y as usize * w as usize + x as usize]),
                            "{} ({x}, {y})",
                            scene.name
                        );
                    }
                }
                y0 += rows as i32;
            }
        })
        .unwrap();
    }
}

fn grid_ray_image<S: Scalar>(scene: &Scene<'_>, w: u16, h: u16) -> std::vec::Vec<Color> {
    let view = scene.view::<S>(w, h).unwrap();
    let need = scene.ray_storage();
    let mut tris = vec![RayTriangle::EMPTY; need.triangles];
    let (mut cells, mut items) = (vec![0u32; need.cells], vec![0u32; need.items]);
    let buffers = RayBuffers {
        triangles: &mut tris,
        cells: &mut cells,
        items: &mut items,
    };
    let rs = RayScene::with_grid(scene, &view, buffers).unwrap();
    for (o, r) in rs.grid_resolutions().enumerate() {
        let n = scene.objects[o].mesh.triangles.len();
        let r = r.expect("every object with triangles has a grid");
        let cells = r.iter().product::<usize>();
        assert!(
            cells >= 1 && cells <= 2 * n,
            "{} object {o}: {r:?}",
            scene.name
        );
    }
    let mut px = vec![Color::new(0, 0, 0); w as usize * h as usize];
    for (j, row) in px.chunks_mut(w as usize).enumerate() {
        rs.render_row(j as u16, row);
    }
    px
}

#[test]
fn grid_gives_the_object_loops_image_bit_for_bit() {
    // The grid only replaces the loop over an object's triangles (same
    // space, same test, same ties), so the images must be identical.
    fn check<S: Scalar>() {
        for scene in builtin::ALL {
            let a = ray_image::<S>(scene, 48, 36);
            let b = grid_ray_image::<S>(scene, 48, 36);
            let diff = a.iter().zip(&b).filter(|(p, q)| p != q).count();
            assert_eq!(diff, 0, "{}: {diff} pixels differ", scene.name);
        }
    }
    check::<f32>();
    check::<I16F16>();
}

#[test]
fn bunny_grid_is_fine_and_storage_is_const() {
    const NEED: RayStorage = builtin::BUNNY.ray_storage();
    assert_eq!(NEED.triangles, 2 + builtin::BUNNY_MESH.triangles.len());
    let view = builtin::BUNNY.view::<f32>(32, 24).unwrap();
    let mut tris = [RayTriangle::EMPTY; NEED.triangles];
    let (mut cells, mut items) = ([0u32; NEED.cells], vec![0u32; NEED.items]);
    let rs = RayScene::with_grid(
        &builtin::BUNNY,
        &view,
        RayBuffers {
            triangles: &mut tris,
            cells: &mut cells,
            items: &mut items,
        },
    )
    .unwrap();
    let r: std::vec::Vec<_> = rs.grid_resolutions().collect();
    // The bunny's own grid, not one coarsened to a few cells.
    let bunny = r[1].unwrap();
    assert!(bunny.iter().product::<usize>() > 3000, "{r:?}");
}

#[test]
fn short_ray_storage_is_a_clear_error() {
    let scene = &builtin::BUNNY;
    let view = scene.view::<f32>(8, 8).unwrap();
    let need = scene.ray_storage();
    for (k, what) in ["triangles", "cells", "items"].into_iter().enumerate() {
        let less = |j: usize, n: usize| if j == k { n - 1 } else { n };
        let mut tris = vec![RayTriangle::EMPTY; less(0, need.triangles)];
        let mut cells = vec![0u32; less(1, need.cells)];
        let mut items = vec![0u32; less(2, need.items)];
        let needed = [need.triangles, need.cells, need.items][k];
        let got = RayScene::with_grid(
            scene,
            &view,
            RayBuffers {
                triangles: &mut tris,
                cells: &mut cells,
                items: &mut items,
            },
        );
        assert_eq!(
            got.err(),
            Some(SceneError::RayStorage {
                what,
                needed,
                given: needed - 1
            })
        );
    }
}

/// `Renderer::with_camera` with the cube's look-at camera built directly
/// draws the frame `Renderer::new` draws from the scene's `CameraSpec`,
/// pixel for pixel; a non-finite camera is refused whatever the spec says.
#[test]
fn renderer_with_a_direct_camera_equals_the_scene_camera() {
    fn check<S: Scalar>() {
        let (w, h) = (96u16, 64u16);
        let expected = raster_image::<S>(&CUBE, w, h);
        let CameraSpec::LookAt { eye, target, up } = CUBE.camera else {
            panic!("the cube's camera is look_at");
        };
        let camera = crate::camera::Camera::look_at(vec3(eye), vec3(target), vec3(up)).unwrap();
        let need = CUBE.storage();
        let mut vec3s = vec![Vec3::<S>::ZERO; need.vec3s];
        let mut objects = vec![PreparedObject::EMPTY; need.objects];
        let objects = CUBE.prepare(&mut vec3s, &mut objects).unwrap();
        let renderer = Renderer::<S>::with_camera(&CUBE, camera, w, h).unwrap();
        let mut scratch = vec![crate::pipeline::MeshVertex::default(); need.vertices];
        let frame = renderer.project(objects, &mut scratch).unwrap();
        let mut px = vec![Color::new(0, 0, 0); w as usize * h as usize];
        let mut keys = vec![u16::MAX; px.len()];
        let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
        let mut depth = DepthBuffer::new(&mut keys, w, h, w as usize, 0).unwrap();
        frame.draw(&mut fb, &mut depth);
        assert!(px == expected, "{}: with_camera differs from new", S::NAME);
    }
    check::<I16F16>();
    check::<f32>();
    let nan = crate::camera::Camera::<f32>::from_angles(
        Vec3::new(f32::NAN, 0.0, 0.0),
        crate::transform::Euler::new(0.0, 0.0, 0.0),
    );
    assert!(matches!(
        Renderer::with_camera(&CUBE, nan, 8, 8),
        Err(SceneError::NonFinite { what: "camera" })
    ));
    // The scene's own camera spec is not consulted: a NaN there is fine.
    let mut bad = CUBE;
    bad.camera = CameraSpec::LookAt {
        eye: [f32::NAN; 3],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
    };
    let good = crate::camera::Camera::<f32>::from_angles(
        Vec3::new(0.0, 0.0, 5.0),
        crate::transform::Euler::new(0.0, 0.0, 0.0),
    );
    assert!(Renderer::with_camera(&bad, good, 8, 8).is_ok());
    assert!(matches!(
        Renderer::<f32>::new(&bad, 8, 8),
        Err(SceneError::NonFinite { what: "camera" })
    ));
}

/// `TextureMode::Auto` draws each triangle exactly as `Affine` or as
/// `Perspective` does, as `choose_mapping`'s bound decides: affine iff
/// `Δuv·(z_max − z_min)/(4·z_min) ≤ AUTO_AFFINE_MAX_ERROR`, the oracle
/// computed here in f64 from the quantized positions (view z = −world z
/// for the camera at the origin with zero angles). Triangles within 2 %
/// of the threshold are skipped (the rule sees the depths as 8.24
/// perspective varyings shifted to 12 bits). Cases where the old
/// depth-ratio rule (`z_max/z_min ≤ 1.1`) decided otherwise are included,
/// and only cases where Affine and Perspective draw different images
/// count as evidence.
#[test]
fn auto_mapping_follows_the_affine_error_bound() {
    const SIDE: usize = 32;
    let texels: [Color; SIDE * SIDE] = core::array::from_fn(|k| {
        let (x, y) = ((k % SIDE) as u8, (k / SIDE) as u8);
        Color::new(x, y * 2, (x ^ y) & 31)
    });
    let tex = Texture::new(&texels, SIDE as u16, SIDE as u16, SIDE).unwrap();
    let threshold = f64::from(AUTO_AFFINE_MAX_ERROR);
    // (z of A and C, z of B in 1/256 units, texel extent D).
    let cases: [(i16, i16, i16); 10] = [
        (512, 512, 64), // parallel to the screen: bound 0
        (512, 538, 16), // bound 0.20
        (512, 560, 16), // 0.375
        (512, 563, 16), // 0.40, the old rule's limit ratio
        (512, 576, 16), // 0.5 + 0: skipped (at the threshold)
        (512, 590, 16), // 0.61
        (512, 538, 64), // 0.81: old rule affine (ratio 1.05), new perspective
        (512, 640, 4),  // 0.25: old rule perspective (ratio 1.25), new affine
        (512, 614, 8),  // 0.40: old rule perspective (ratio 1.2), new affine
        (512, 768, 16), // 2.0
    ];
    let mut evidence = [0; 2];
    for (za, zb, d) in cases {
        let positions = [[-128, -128, -za], [128, -128, -zb], [-128, 128, -za]];
        let uvs = [[0, 0], [d, 0], [0, d]];
        let mesh = MeshData {
            closed: false,
            positions: &positions,
            scale: 1.0 / 256.0,
            triangles: &[[0, 1, 2]],
            normals: None,
            uvs: Some(&uvs),
        };
        let image = |mode| {
            let objects = [SceneObject {
                mesh: &mesh,
                pose: Pose::default(),
                material: Material::Texture { texture: tex, mode },
            }];
            let scene = Scene {
                camera: CameraSpec::Angles {
                    position: [0.0; 3],
                    angles: [0.0; 3],
                },
                projection: ProjectionSpec::Perspective { fov_x: 1.0 },
                objects: &objects,
                spheres: &[],
                ..CUBE
            };
            raster_image::<I16F16>(&scene, 128, 128)
        };
        let (z0, z1) = (f64::from(za), f64::from(zb));
        let bound = f64::from(d) * (z1 - z0) / (4.0 * z0);
        if (bound - threshold).abs() < 0.02 * threshold {
            continue;
        }
        let affine = bound <= threshold;
        let auto = image(TextureMode::Auto);
        let (a, p) = (image(TextureMode::Affine), image(TextureMode::Perspective));
        let want = if affine { &a } else { &p };
        assert!(
            auto == *want,
            "({za}, {zb}, {d}): bound {bound:.3}, Auto should be {}",
            if affine { "affine" } else { "perspective" }
        );
        if a != p {
            evidence[usize::from(affine)] += 1;
        }
    }
    assert!(
        evidence[0] >= 3 && evidence[1] >= 2,
        "too few cases where affine and perspective differ: {evidence:?}"
    );
}

/// The bunny alone (the built-in scene without its floor) stays in view:
/// with a depth buffer, in both scalars, whole and in bands,
/// `draw_unclipped` draws what `draw` does.
#[test]
fn bunny_draws_the_same_unclipped() {
    fn check<S: Scalar>() {
        let scene = Scene {
            objects: &builtin::BUNNY.objects[1..],
            ..builtin::BUNNY
        };
        let (w, h) = (320u16, 240u16);
        let draw = |unclipped: bool, rows: u16| {
            let mut px = vec![Color::new(1, 2, 3); w as usize * h as usize];
            let mut keys = vec![0u16; w as usize * rows as usize];
            let stats = super::feature_tests::with_frame::<S, _>(&scene, w, h, |f| {
                assert!(!f.needs_clipping());
                let mut sum = RasterStats::default();
                for (k, band) in px.chunks_mut(w as usize * rows as usize).enumerate() {
                    let y0 = k as i32 * rows as i32;
                    let n = (band.len() / w as usize) as u16;
                    let mut t = crate::target::Band::new(band, w, n, w as usize, y0).unwrap();
                    let mut z = DepthBuffer::new(&mut keys, w, n, w as usize, y0).unwrap();
                    z.clear();
                    let s = if unclipped {
                        f.draw_unclipped(&mut t, &mut z).unwrap()
                    } else {
                        f.draw(&mut t, &mut z)
                    };
                    sum.drawn += s.drawn;
                    sum.culled += s.culled;
                    sum.clipped += s.clipped;
                    sum.errors += s.errors;
                }
                sum
            })
            .unwrap();
            (stats, px)
        };
        for rows in [240, 15] {
            let (want, want_px) = draw(false, rows);
            let (got, got_px) = draw(true, rows);
            assert!(
                want.drawn > 1000 && want.clipped == 0 && want.errors == 0,
                "{want:?}"
            );
            assert_eq!(got, want);
            assert!(got_px == want_px, "{rows}-row bands: pixels differ");
        }
    }
    check::<I16F16>();
    check::<f32>();
}

//! What a build with fewer stages does, for whatever features are on:
//! a material whose stage is left out is refused with
//! [`SceneError::FeatureDisabled`] before anything is drawn, flat scenes
//! render with any feature set, and the far plane clips only with
//! `clip-far`.

use super::builtin::{BUNNY, CORRIDOR, CORRIDOR_AFFINE, CUBE};
use super::*;
use crate::camera::Projection;
use crate::math::Vec3;
use crate::pipeline::{Pipeline, Vertex};
use crate::raster::{FillOutcome, Flat, NoDepth};
use crate::scalar::I16F16;
use crate::target::Framebuffer;
use std::vec;

const SENTINEL: Color = Color::new(1, 2, 3);

/// Renders `scene` at 64×48 without a depth buffer; returns the result
/// and the pixels.
fn render(scene: &Scene<'_>) -> (Result<RasterStats, SceneError>, std::vec::Vec<Color>) {
    let (w, h) = (64u16, 48u16);
    let mut px = vec![SENTINEL; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
    let view = scene.view::<I16F16>(w, h).unwrap();
    let r = render_raster(scene, &view, &mut fb, &mut NoDepth);
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
fn the_far_plane_clips_only_with_clip_far() {
    let pipe = Pipeline::new(
        Projection::perspective(100.0f32, 64, 48),
        64,
        48,
        0.5,
        10.0,
        16.0,
    )
    .unwrap();
    // A triangle at z = 20, beyond far = 10, covering the screen centre.
    let tri = [(-5.0, -5.0), (5.0, -5.0), (0.0, 5.0)]
        .map(|(x, y)| Vertex::new(Vec3::new(x, y, 20.0f32), ()));
    let mut px = vec![SENTINEL; 64 * 48];
    let mut fb = Framebuffer::new(&mut px, 64, 48, 64).unwrap();
    let r = pipe.draw_polygon(&mut fb, &mut NoDepth, &Flat(Color::new(31, 0, 0)), &tri);
    let drawn = px.iter().filter(|&&c| c == Color::new(31, 0, 0)).count();
    if cfg!(feature = "clip-far") {
        assert_ne!(r, Ok(FillOutcome::Drawn));
        assert_eq!(drawn, 0);
    } else {
        assert_eq!(r, Ok(FillOutcome::Drawn));
        assert!(drawn > 100, "{drawn}");
    }
}

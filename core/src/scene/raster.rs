//! The raster path: every triangle of every object through the
//! [`Pipeline`] (clip, project, scan-convert) with the scene's material.

use super::shade::{self, Lighting};
#[cfg(feature = "perspective")]
use super::{AUTO_AFFINE_MAX_DEPTH_RATIO, TextureMode};
use super::{Color, Material, Scene, SceneError, View};
#[cfg(feature = "gouraud")]
use crate::pipeline::Intensity;
#[cfg(feature = "texture")]
use crate::pipeline::Uv;
#[cfg(feature = "perspective")]
use crate::pipeline::UvPerspective;
use crate::pipeline::{Pipeline, Vertex};
#[cfg(feature = "gouraud")]
use crate::raster::Gouraud;
#[cfg(feature = "perspective")]
use crate::raster::PerspectiveTexture;
#[cfg(feature = "texture")]
use crate::raster::{AffineTexture, RepeatPow2, Texture};
use crate::raster::{DepthTest, FillOutcome, Flat, Shade};
use crate::scalar::Scalar;
use crate::target::Target;

/// What [`render_raster`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles submitted.
    pub triangles: u32,
    /// Triangles that emitted spans.
    pub drawn: u32,
    /// Triangles the pipeline could not draw (clip or projection
    /// overflow, e.g. saturated fixed point); the rest of the scene is
    /// still drawn.
    pub errors: u32,
}

impl RasterStats {
    fn count(&mut self, r: Result<FillOutcome, crate::pipeline::DrawError>) {
        self.triangles += 1;
        match r {
            Ok(FillOutcome::Drawn) => self.drawn += 1,
            Ok(_) => {}
            Err(_) => self.errors += 1,
        }
    }
}

/// Guard band of the clip volume, in pixels.
const GUARD: i32 = 16;

/// Renders `scene` into `target` through the pipeline: fills the target's
/// clip rectangle with the background, then draws every triangle (both
/// sides) with `depth` deciding visibility. Spheres are not drawn (the
/// ray path's).
///
/// Works with any [`Target`], so a [`Band`](crate::target::Band) plus a
/// band-sized depth buffer renders a strip (call once per band).
///
/// Only the stages compiled in are linked: a flat-only build (no
/// `gouraud`, `texture` or `perspective` feature) contains no Gouraud or
/// texture code.
///
/// # Errors
/// [`SceneError`] from [`Scene::validate`] or the pipeline;
/// [`SceneError::FeatureDisabled`] for a material whose stage this build
/// leaves out (`Gouraud` needs `gouraud`; `Texture` needs `texture`, and
/// its `Perspective` and `Auto` modes need `perspective` too). Nothing is
/// drawn then.
pub fn render_raster<S, T, Z>(
    scene: &Scene<'_>,
    view: &View<S>,
    target: &mut T,
    depth: &mut Z,
) -> Result<RasterStats, SceneError>
where
    S: Scalar,
    T: Target<Color = Color>,
    Z: DepthTest,
{
    scene.validate()?;
    for obj in scene.objects {
        let missing = match obj.material {
            Material::Flat(_) => None,
            Material::Gouraud(_) => (!cfg!(feature = "gouraud")).then_some("gouraud"),
            Material::Texture { mode, .. } => {
                if !cfg!(feature = "texture") {
                    Some("texture")
                } else if !cfg!(feature = "perspective") && mode != super::TextureMode::Affine {
                    Some("perspective")
                } else {
                    None
                }
            }
        };
        if let Some(feature) = missing {
            return Err(SceneError::FeatureDisabled { feature });
        }
    }
    let pipe = Pipeline::new(
        view.projection,
        view.width,
        view.height,
        S::from_f32(scene.near),
        S::from_f32(scene.far),
        S::from_i32(GUARD),
    )
    .map_err(SceneError::Pipeline)?;
    let r = target.clip_rect();
    if !r.is_empty() {
        for y in r.y0..r.y1 {
            target.fill_solid(y, r.x0, (r.x1 - r.x0) as u32, scene.background);
        }
    }
    let light = Lighting::<S>::new(&scene.light);
    let mut stats = RasterStats::default();
    for obj in scene.objects {
        let pose = shade::pose::<S>(&obj.pose);
        let rot = pose.angles.to_mat3();
        let to_view = view.camera.object_to_view(&pose);
        let mesh = obj.mesh;
        let scale = S::from_f32(mesh.scale);
        let view_pos = |k: u16| to_view.transform_point3(shade::position(mesh, scale, k));
        match obj.material {
            Material::Flat(color) => {
                for &tri in mesh.triangles {
                    let q = shade::face_normal(mesh, &rot, tri)
                        .map_or(0, |n| shade::quantise_intensity(light.intensity(n)));
                    let verts = tri.map(|k| Vertex::new(view_pos(k), ()));
                    stats.count(pipe.draw_polygon(target, depth, &Flat(color.scale(q)), &verts));
                }
            }
            #[cfg(feature = "gouraud")]
            Material::Gouraud(color) => {
                let ramp = color.ramp();
                let shader = Gouraud::new(&ramp);
                for &tri in mesh.triangles {
                    let i = shade::vertex_intensities(mesh, &rot, &light, tri);
                    let verts = [0, 1, 2].map(|c| Vertex::new(view_pos(tri[c]), Intensity(i[c])));
                    stats.count(pipe.draw_polygon(target, depth, &shader, &verts));
                }
            }
            #[cfg(feature = "texture")]
            Material::Texture { texture, mode } => {
                let w = texture.width();
                let tex = Texture::new(texture.texels(), w, texture.height(), w as usize)
                    .map_err(|_| SceneError::TextureSize)?;
                let not_pow2 = SceneError::TextureNotPowerOfTwo {
                    width: w,
                    height: texture.height(),
                };
                let affine = AffineTexture::<_, RepeatPow2>::new(tex).ok_or(not_pow2)?;
                #[cfg(feature = "perspective")]
                let exact = PerspectiveTexture::<_, RepeatPow2, 1>::new(tex).ok_or(not_pow2)?;
                #[cfg(feature = "perspective")]
                let ratio = S::from_f32(AUTO_AFFINE_MAX_DEPTH_RATIO);
                #[cfg(not(feature = "perspective"))]
                let _ = mode; // Affine (checked above)
                for &tri in mesh.triangles {
                    let pos = tri.map(view_pos);
                    let uvs = tri.map(|k| shade::uv::<S>(mesh, k));
                    #[cfg(feature = "perspective")]
                    let use_affine = match mode {
                        TextureMode::Affine => true,
                        TextureMode::Perspective => false,
                        TextureMode::Auto => {
                            let zmin = pos[0].z.min_of(pos[1].z).min_of(pos[2].z);
                            let zmax = pos[0].z.max_of(pos[1].z).max_of(pos[2].z);
                            zmin > S::ZERO && zmax <= zmin * ratio
                        }
                    };
                    #[cfg(feature = "perspective")]
                    if !use_affine {
                        let verts = [0, 1, 2].map(|c| {
                            Vertex::new(
                                pos[c],
                                UvPerspective {
                                    u: uvs[c].0,
                                    v: uvs[c].1,
                                },
                            )
                        });
                        stats.count(pipe.draw_polygon(target, depth, &exact, &verts));
                        continue;
                    }
                    let verts = [0, 1, 2].map(|c| {
                        Vertex::new(
                            pos[c],
                            Uv {
                                u: uvs[c].0,
                                v: uvs[c].1,
                            },
                        )
                    });
                    stats.count(pipe.draw_polygon(target, depth, &affine, &verts));
                }
            }
            // Refused before drawing (see above).
            #[allow(unreachable_patterns)]
            _ => {}
        }
    }
    Ok(stats)
}

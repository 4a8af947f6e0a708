//! The ray-cast workloads (`workload ray-brute|ray-bounds|ray-grid`): one
//! frame each. The three searches must give identical images, and their
//! coverage must equal the raster W1 frame 0's except on its silhouette.

use embedded_graphics::pixelcolor::Rgb565;
use sightline_tests::ray_workload::{RayMode, RayWorkload};
use sightline_tests::workload::{Frame, HEIGHT, Model, Shading, WIDTH, Workload, gray565};

fn ray_frame(model: &Model<f32>, mode: RayMode) -> (Vec<Rgb565>, u32) {
    let mut w = RayWorkload::new(model, mode);
    assert_eq!(w.mode(), mode);
    let mut px = vec![gray565(7); WIDTH as usize * HEIGHT as usize];
    let hits = w.render(&mut px).hits;
    (px, hits)
}

#[test]
fn three_searches_identical_and_coverage_matches_raster() {
    let model = Model::<f32>::bunny();
    let (grid, grid_hits) = ray_frame(&model, RayMode::Grid);
    let (bounds, bounds_hits) = ray_frame(&model, RayMode::Bounds);
    let (brute, brute_hits) = ray_frame(&model, RayMode::Brute);
    assert_eq!(grid_hits, brute_hits);
    assert_eq!(bounds_hits, brute_hits);
    let diff = |a: &[Rgb565], b: &[Rgb565]| a.iter().zip(b).filter(|(x, y)| x != y).count();
    assert_eq!(diff(&grid, &brute), 0, "grid vs brute force");
    assert_eq!(diff(&bounds, &brute), 0, "bounds vs brute force");

    // Raster W1 frame 0.
    let mut raster = Workload::<f32>::new(&model, Shading::Flat);
    let mut frame = Frame::default();
    raster.render(0, 1, &mut frame);
    let bg = gray565(0);
    let (w, h) = (WIDTH as i32, HEIGHT as i32);
    let covered = |px: &[Rgb565], x: i32, y: i32| {
        x >= 0 && y >= 0 && x < w && y < h && px[(y * w + x) as usize] != bg
    };
    let raster_px = frame.color.clone();
    let raster_cov = frame.coverage().pixels;
    let (mut only_ray, mut only_raster, mut color) = (0, 0, 0);
    for y in 0..h {
        for x in 0..w {
            let (r, s) = (covered(&brute, x, y), covered(&raster_px, x, y));
            if r == s {
                if r && brute[(y * w + x) as usize] != raster_px[(y * w + x) as usize] {
                    color += 1;
                }
                continue;
            }
            // A disagreement must sit on the raster silhouette: one of the
            // 4-neighbors has the state the ray path gave this pixel.
            let on_silhouette = [(1, 0), (-1, 0), (0, 1), (0, -1)]
                .iter()
                .any(|(dx, dy)| covered(&raster_px, x + dx, y + dy) == r);
            assert!(
                on_silhouette,
                "({x}, {y}): ray {r}, raster {s}, off the silhouette"
            );
            if r {
                only_ray += 1;
            } else {
                only_raster += 1;
            }
        }
    }
    // Silhouette pixels of the raster image: covered, with an uncovered
    // 4-neighbor.
    let mut silhouette = 0;
    for y in 0..h {
        for x in 0..w {
            if covered(&raster_px, x, y)
                && [(1, 0), (-1, 0), (0, 1), (0, -1)]
                    .iter()
                    .any(|(dx, dy)| !covered(&raster_px, x + dx, y + dy))
            {
                silhouette += 1;
            }
        }
    }
    println!(
        "ray coverage {brute_hits}, raster {raster_cov}: {only_ray} only ray, {only_raster} only raster \
         ({silhouette} silhouette pixels), {color} covered by both with another color"
    );
    assert_eq!(brute_hits - only_ray + only_raster, raster_cov);
    // The raster path snaps vertices to 1/16 px, so an edge moves by at
    // most 1/32 px; a silhouette pixel changes only when its center lies
    // in that band, about 1/16 of the silhouette pixels for edges at
    // random angles. Allow twice that.
    assert!(
        (only_ray + only_raster) * 8 <= silhouette,
        "{} differing pixels for {silhouette} silhouette pixels",
        only_ray + only_raster
    );
}

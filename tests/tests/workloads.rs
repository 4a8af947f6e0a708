//! W1/W2 as defined in docs/raster-workloads.md: the bunny lands where
//! the peers' renderers put it, and the mesh path draws exactly what the
//! per-polygon path draws.

use sightline::scalar::I16F16;
use sightline_tests::obj;
use sightline_tests::workload::{BUNNY_OBJ, Frame, Model, Shading, Workload};

#[test]
fn bunny_obj_has_the_documented_size() {
    let m = obj::parse(BUNNY_OBJ).unwrap();
    assert_eq!(m.positions.len(), 1839);
    assert_eq!(m.triangles.len(), 3674);
}

/// Average coverage over all N = 200 frames and the union bounding box.
fn coverage_stats(shading: Shading) -> (f64, u32, u32, (u16, u16, u16, u16)) {
    let n = 200;
    let model = Model::bunny();
    let mut w = Workload::<f32>::new(&model, shading);
    let mut frame = Frame::default();
    let (mut sum, mut lo, mut hi) = (0u64, u32::MAX, 0u32);
    let mut bb = (u16::MAX, u16::MAX, 0, 0);
    for k in 0..n {
        w.render(k, n, &mut frame);
        let c = frame.coverage();
        sum += c.pixels as u64;
        lo = lo.min(c.pixels);
        hi = hi.max(c.pixels);
        let (a, b, cc, d) = c.bbox.unwrap();
        bb = (bb.0.min(a), bb.1.min(b), bb.2.max(cc), bb.3.max(d));
    }
    (sum as f64 / n as f64, lo, hi, bb)
}

#[test]
fn w1_and_w2_cover_the_documented_pixels() {
    for shading in [Shading::Flat, Shading::Gouraud] {
        let (avg, lo, hi, (x0, y0, x1, y1)) = coverage_stats(shading);
        println!(
            "{shading:?}: avg {avg:.0} px (min {lo}, max {hi}), bbox x {x0}..{x1} y {y0}..{y1}"
        );
        // The definition: about 14.6k–15.0k on average (11.0k–18.2k per
        // frame, rounded, across the peers), half-open bbox y 8..223,
        // x 66..254.
        assert!((14_600.0..=15_000.0).contains(&avg), "average {avg}");
        assert!((10_800..=11_400).contains(&lo), "min {lo}");
        assert!((17_900..=18_400).contains(&hi), "max {hi}");
        assert_eq!((x0, y0, x1 + 1, y1 + 1), (66, 8, 254, 223));
    }
}

#[test]
fn fixed_point_pipeline_renders_nearly_the_same_bunny() {
    let n = 20;
    let (ma, mb) = (Model::bunny(), Model::bunny());
    let mut a = Workload::<f32>::new(&ma, Shading::Flat);
    let mut b = Workload::<I16F16>::new(&mb, Shading::Flat);
    let (mut fa, mut fb) = (Frame::default(), Frame::default());
    for k in 0..n {
        a.render(k, n, &mut fa);
        b.render(k, n, &mut fb);
        let (ca, cb) = (fa.coverage(), fb.coverage());
        let rel = (ca.pixels as f64 - cb.pixels as f64).abs() / ca.pixels as f64;
        assert!(rel < 0.01, "frame {k}: {} vs {} px", ca.pixels, cb.pixels);
        let differ = fa
            .color
            .iter()
            .zip(&fb.color)
            .filter(|(p, q)| p != q)
            .count();
        assert!(
            differ * 20 < ca.pixels as usize,
            "frame {k}: {differ} pixels differ"
        );
    }
}

#[test]
fn fill_modes_cover_the_whole_viewport() {
    use sightline_tests::fill::{FillBench, FillMode};
    for mode in FillMode::ALL {
        let mut b = FillBench::new(mode);
        for _ in 0..3 {
            assert_eq!(b.frame(), 320 * 240);
            // Every pixel is written every frame (depth modes move nearer).
            assert_eq!(b.covered(), 320 * 240, "{mode:?}");
        }
    }
}

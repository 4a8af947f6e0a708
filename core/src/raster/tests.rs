use super::*;
#[cfg(all(feature = "gouraud", feature = "depth"))]
use crate::target::Band;
#[cfg(any(feature = "depth", feature = "texture"))]
use crate::target::Framebuffer;
#[cfg(any(feature = "gouraud", feature = "depth", feature = "texture"))]
use crate::test_util::sp;
use crate::test_util::{MockTarget, oracle_covers, sv};
#[cfg(feature = "perspective")]
use crate::texture::Repeat;
#[cfg(feature = "texture")]
use crate::texture::{Clamp, RepeatPow2, Texture};
use proptest::prelude::*;
use std::vec;
use std::vec::Vec;

fn flat(t: &mut MockTarget, c: char, poly: &[ScreenVertex<0>]) -> FillOutcome {
    fill_polygon(t, &mut NoDepth, &Flat(c), poly)
}

#[test]
fn flat_triangle_pattern() {
    let mut t = MockTarget::new(8, 6);
    // Left edge on x = 1 (pixel centers 0.5 and 1.5 either side), the
    // hypotenuse crosses row 4's center line at x = 6.4.
    let out = flat(&mut t, '#', &[sv(1.0, 0.0), sv(7.0, 5.0), sv(1.0, 5.0)]);
    assert_eq!(out, FillOutcome::Drawn);
    t.assert_pattern(&[
        ".#......", //
        ".##.....", //
        ".###....", //
        ".####...", //
        ".#####..", //
        "........", //
    ]);
}

#[test]
fn edges_through_pixel_centers_follow_top_left_rule() {
    // A square whose edges pass exactly through pixel centers 1.5 and 4.5:
    // the left and top edges are drawn, the right and bottom are not.
    let mut t = MockTarget::new(7, 7);
    let sq = [sv(1.5, 1.5), sv(4.5, 1.5), sv(4.5, 4.5), sv(1.5, 4.5)];
    flat(&mut t, '#', &sq);
    t.assert_pattern(&[
        ".......", //
        ".###...", //
        ".###...", //
        ".###...", //
        ".......", //
        ".......", //
        ".......", //
    ]);
    // Either winding gives the same pixels.
    let mut u = MockTarget::new(7, 7);
    let mut rev = sq;
    rev.reverse();
    flat(&mut u, '#', &rev);
    assert_eq!(t.px, u.px);
}

#[test]
fn shared_diagonal_is_covered_exactly_once() {
    // Two triangles split a quad along a diagonal through pixel centers;
    // MockTarget panics on any pixel written twice.
    let mut t = MockTarget::new(6, 6);
    let (a, b, c, d) = (sv(0.5, 0.5), sv(5.5, 0.5), sv(5.5, 5.5), sv(0.5, 5.5));
    flat(&mut t, 'a', &[a, b, c]);
    flat(&mut t, 'b', &[a, c, d]);
    t.assert_pattern(&[
        "aaaaa.", //
        "baaaa.", //
        "bbaaa.", //
        "bbbaa.", //
        "bbbba.", //
        "......", //
    ]);
}

#[test]
fn pentagon_and_clip_to_target() {
    // A convex pentagon partly outside the target on the left and top.
    let mut t = MockTarget::new(6, 5);
    let p = [
        sv(-2.0, 2.0),
        sv(2.0, -3.0),
        sv(6.0, 1.0),
        sv(5.0, 5.0),
        sv(0.0, 5.0),
    ];
    flat(&mut t, '#', &p);
    t.assert_pattern(&[
        "#####.", //
        "######", //
        "######", //
        "#####.", //
        "#####.", //
    ]);
}

#[cfg(feature = "gouraud")]
#[test]
fn gouraud_pattern() {
    // Intensity 0 on the left edge, 255 on the right, ramp to digits 0..9.
    let mut ramp = ['?'; 256];
    for (i, c) in ramp.iter_mut().enumerate() {
        *c = char::from(b'0' + (i * 10 / 256) as u8);
    }
    let v = |x: f64, y: f64, i: i32| ScreenVertex::new(sp(x), sp(y), 0, [i << 16]);
    let mut t = MockTarget::new(10, 3);
    let quad = [
        v(0.0, 0.0, 0),
        v(10.0, 0.0, 255),
        v(10.0, 3.0, 255),
        v(0.0, 3.0, 0),
    ];
    fill_polygon(&mut t, &mut NoDepth, &Gouraud::new(&ramp), &quad);
    t.assert_pattern(&[
        "0123456789", //
        "0123456789", //
        "0123456789", //
    ]);
}

#[cfg(feature = "gouraud")]
#[test]
fn gouraud_values_never_leave_the_ramp() {
    // Out-of-range varyings (intensity beyond 255 and below 0) are clamped
    // per span; the ramp lookup cannot index outside 256 entries anyway,
    // but colors must be the clamped ones.
    let mut ramp = ['m'; 256];
    ramp[0] = 'L';
    ramp[255] = 'H';
    let v = |x: f64, y: f64, i: i32| ScreenVertex::new(sp(x), sp(y), 0, [i]);
    let mut t = MockTarget::new(4, 2);
    let quad = [
        v(0.0, 0.0, i32::MIN),
        v(4.0, 0.0, i32::MAX),
        v(4.0, 2.0, i32::MAX),
        v(0.0, 2.0, i32::MIN),
    ];
    fill_polygon(&mut t, &mut NoDepth, &Gouraud::new(&ramp), &quad);
    for c in &t.px {
        assert!(['L', 'm', 'H'].contains(c));
    }
    assert_eq!(t.px[0], 'L');
    assert_eq!(t.px[3], 'H');
}

#[cfg(feature = "depth")]
#[test]
fn depth_test_is_order_independent() {
    let q = |x0: f64, y0: f64, x1: f64, y1: f64, z: u16| {
        [
            ScreenVertex::new(sp(x0), sp(y0), z, []),
            ScreenVertex::new(sp(x1), sp(y0), z, []),
            ScreenVertex::new(sp(x1), sp(y1), z, []),
            ScreenVertex::new(sp(x0), sp(y1), z, []),
        ]
    };
    let near = q(2.0, 1.0, 6.0, 4.0, 100);
    let far = q(0.0, 0.0, 5.0, 3.0, 200);
    let expected = [
        "fffff...", //
        "ffnnnn..", //
        "ffnnnn..", //
        "..nnnn..", //
        "........", //
    ];
    for near_first in [true, false] {
        let mut t = MockTarget::new(8, 5);
        // Drawing near-then-far never overdraws; far-then-near must.
        t.allow_overdraw = !near_first;
        let mut zb = [u16::MAX; 40];
        let mut depth = DepthBuffer::new(&mut zb, 8, 5, 8, 0).unwrap();
        let order = if near_first {
            [(near, 'n'), (far, 'f')]
        } else {
            [(far, 'f'), (near, 'n')]
        };
        for (poly, c) in order {
            fill_polygon(&mut t, &mut depth, &Flat(c), &poly);
        }
        t.assert_pattern(&expected);
        assert_eq!(depth.key(3, 2), Some(100));
        assert_eq!(depth.key(0, 0), Some(200));
        assert_eq!(depth.key(7, 4), Some(u16::MAX));
    }
}

#[cfg(feature = "depth")]
#[test]
fn depth_interpolates_across_a_tilted_polygon() {
    // z from 0 at x = 0 to 65535 at x = 16 along the span; a flat polygon
    // at key 32768 wins on the far half only.
    let mut zb = [u16::MAX; 16];
    let mut depth = DepthBuffer::new(&mut zb, 16, 1, 16, 0).unwrap();
    let mut t = MockTarget::new(16, 1);
    t.allow_overdraw = true;
    let tilt = [
        ScreenVertex::new(0, 0, 0, []),
        ScreenVertex::new(sp(16.0), 0, 65535, []),
        ScreenVertex::new(sp(16.0), sp(1.0), 65535, []),
        ScreenVertex::new(0, sp(1.0), 0, []),
    ];
    fill_polygon(&mut t, &mut depth, &Flat('t'), &tilt);
    let mut wall = tilt;
    for v in &mut wall {
        v.z = 32768;
    }
    fill_polygon(&mut t, &mut depth, &Flat('w'), &wall);
    t.assert_pattern(&["ttttttttwwwwwwww"]);
}

#[test]
fn degenerate_and_extreme_input() {
    let mut t = MockTarget::new(8, 8);
    assert_eq!(flat(&mut t, '#', &[]), FillOutcome::Empty);
    assert_eq!(
        flat(&mut t, '#', &[sv(1.0, 1.0), sv(5.0, 5.0)]),
        FillOutcome::Empty
    );
    // Collinear and repeated vertices: zero area.
    let line = [sv(0.0, 0.0), sv(4.0, 4.0), sv(8.0, 8.0), sv(4.0, 4.0)];
    assert_eq!(flat(&mut t, '#', &line), FillOutcome::Empty);
    let same = [sv(3.0, 3.0); 5];
    assert_eq!(flat(&mut t, '#', &same), FillOutcome::Empty);
    // Beyond the coordinate limit: rejected, nothing drawn.
    let huge = [
        ScreenVertex::new(i32::MIN, 0, 0, []),
        ScreenVertex::new(i32::MAX, i32::MAX, 0, []),
        ScreenVertex::new(0, i32::MAX, 0, []),
    ];
    assert_eq!(flat(&mut t, '#', &huge), FillOutcome::Rejected);
    assert!(t.px.iter().all(|&c| c == '.'));
    // At the limit: a triangle covering the whole target, exactly once.
    let l = COORD_LIMIT;
    let big = [
        ScreenVertex::new(-l, -l, 0, []),
        ScreenVertex::new(l, 0, 0, []),
        ScreenVertex::new(0, l, 0, []),
    ];
    assert_eq!(flat(&mut t, '#', &big), FillOutcome::Drawn);
    assert!(t.px.iter().all(|&c| c == '#'));
}

#[cfg(feature = "gouraud")]
#[test]
fn sliver_with_extreme_varyings_stays_in_range() {
    // A near-degenerate, very long sliver: gradients are huge and the
    // per-span evaluation saturates; values must still be clamped.
    let mut ramp = ['x'; 256];
    ramp[0] = 'a';
    ramp[255] = 'b';
    let mut t = MockTarget::new(32, 32);
    let l = COORD_LIMIT;
    let poly = [
        ScreenVertex::new(-l, -l, 0, [0]),
        ScreenVertex::new(l, l, 0, [i32::MAX]),
        ScreenVertex::new(l, l - 1, 0, [i32::MIN]),
    ];
    let out = fill_polygon(&mut t, &mut NoDepth, &Gouraud::new(&ramp), &poly);
    // `Gouraud::color` debug-asserts that every intensity it looks up lies
    // in 0..=255, so an unclamped, wrapped value fails this test above;
    // here the sliver must have drawn pixels, every one from the ramp's
    // clamped ends or its middle.
    assert_eq!(out, FillOutcome::Drawn);
    let drawn: Vec<char> = t.px.iter().copied().filter(|&c| c != '.').collect();
    assert!(!drawn.is_empty(), "the sliver drew nothing");
    assert!(
        drawn.iter().all(|c| ['a', 'x', 'b'].contains(c)),
        "{drawn:?}"
    );

    // A thin (two-pixel) sliver whose intensity plane runs four ramps
    // beyond both ends inside it: the span set-up must clamp, so both ends
    // of the ramp appear and nothing else wraps in.
    let mut t = MockTarget::new(32, 32);
    let big = 4 * (255 << VARYING_FRAC_BITS);
    let poly = [
        ScreenVertex::new(sp(0.0), sp(0.0), 0, [0]),
        ScreenVertex::new(sp(32.0), sp(32.0), 0, [big]),
        ScreenVertex::new(sp(32.0), sp(30.0), 0, [-big]),
    ];
    let out = fill_polygon(&mut t, &mut NoDepth, &Gouraud::new(&ramp), &poly);
    assert_eq!(out, FillOutcome::Drawn);
    let drawn: Vec<char> = t.px.iter().copied().filter(|&c| c != '.').collect();
    assert!(drawn.contains(&'a') && drawn.contains(&'b'), "{drawn:?}");
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
fn render_frame(w: u16, h: u16, polys: &[Vec<ScreenVertex<1>>], ramp: &[u8; 256]) -> Vec<u8> {
    let mut buf = vec![0u8; w as usize * h as usize];
    let mut zb = vec![u16::MAX; w as usize * h as usize];
    let mut fb = Framebuffer::new(&mut buf, w, h, w as usize).unwrap();
    let mut depth = DepthBuffer::new(&mut zb, w, h, w as usize, 0).unwrap();
    for p in polys {
        fill_polygon(&mut fb, &mut depth, &Gouraud::new(ramp), p);
    }
    buf
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
fn render_bands(
    w: u16,
    h: u16,
    rows: u16,
    polys: &[Vec<ScreenVertex<1>>],
    ramp: &[u8; 256],
) -> Vec<u8> {
    let mut out = Vec::new();
    let mut buf = vec![0u8; w as usize * rows as usize];
    let mut zb = vec![0u16; w as usize * rows as usize];
    let mut band = Band::new(&mut buf, w, rows, w as usize, 0).unwrap();
    let mut depth = DepthBuffer::new(&mut zb, w, rows, w as usize, 0).unwrap();
    let mut y0 = 0;
    while y0 < h as i32 {
        band.move_to(y0).unwrap();
        depth.move_to(y0).unwrap();
        band.clear(0);
        depth.clear();
        for p in polys {
            fill_polygon(&mut band, &mut depth, &Gouraud::new(ramp), p);
        }
        let n = (h as i32 - y0).min(rows as i32) as usize * w as usize;
        out.extend_from_slice(&band.as_slice()[..n]);
        y0 += rows as i32;
    }
    out
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
fn ramp_u8() -> [u8; 256] {
    core::array::from_fn(|i| i as u8)
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
#[test]
fn bands_match_full_frame() {
    let v = |x: f64, y: f64, z: u16, i: i32| ScreenVertex::new(sp(x), sp(y), z, [i << 16]);
    let polys = vec![
        vec![
            v(-3.0, 2.3, 500, 10),
            v(30.7, 5.1, 9000, 250),
            v(12.2, 37.9, 100, 128),
        ],
        vec![
            v(5.0, 5.0, 50, 0),
            v(25.0, 7.0, 60000, 255),
            v(27.0, 30.0, 3000, 90),
            v(3.0, 28.0, 20, 200),
        ],
    ];
    let full = render_frame(32, 30, &polys, &ramp_u8());
    for rows in [1, 3, 7, 16] {
        assert_eq!(
            full,
            render_bands(32, 30, rows, &polys, &ramp_u8()),
            "band height {rows}"
        );
    }
    assert!(full.iter().any(|&p| p != 0));
}

/// Convex hull (Andrew's monotone chain, collinear points dropped) of
/// points on an ellipse, rounded to 28.4: rounding alone can make the
/// polygon slightly non-convex, which the fill rule does not cover.
fn ellipse_poly(cx: i32, cy: i32, rx: i32, ry: i32, angles: &[f64]) -> Vec<ScreenVertex<0>> {
    let mut pts: Vec<(i64, i64)> = angles
        .iter()
        .map(|t| {
            (
                cx as i64 + (rx as f64 * t.cos()).round() as i64,
                cy as i64 + (ry as f64 * t.sin()).round() as i64,
            )
        })
        .collect();
    convex_hull(&mut pts)
        .into_iter()
        .map(|(x, y)| ScreenVertex::new(x as i32, y as i32, 0, []))
        .collect()
}

fn convex_hull(pts: &mut Vec<(i64, i64)>) -> Vec<(i64, i64)> {
    pts.sort();
    pts.dedup();
    if pts.len() < 3 {
        return pts.clone();
    }
    let cross = |o: (i64, i64), a: (i64, i64), b: (i64, i64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut h: Vec<(i64, i64)> = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let it: Vec<(i64, i64)> = if pass == 0 {
            pts.clone()
        } else {
            pts.iter().rev().copied().collect()
        };
        for p in it {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Renders `polys` into a `w`×`h` target that counts writes (and panics
/// out of bounds) and compares every pixel's count with the oracle's.
fn check_against_oracle(w: i32, h: i32, polys: &[Vec<ScreenVertex<0>>]) {
    let mut t = MockTarget::new(w, h);
    t.allow_overdraw = true;
    for p in polys {
        fill_polygon(&mut t, &mut NoDepth, &Flat('#'), p);
    }
    for j in 0..h {
        for i in 0..w {
            let want: u32 = polys
                .iter()
                .map(|p| oracle_covers(p, i as i64, j as i64) as u32)
                .sum();
            let got = t.writes[(j * w + i) as usize];
            assert_eq!(got, want, "pixel ({i}, {j})");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_convex_polygons_match_oracle(
        cx in -200i32..600, cy in -200i32..600,
        rx in 0i32..900, ry in 0i32..900,
        angles in proptest::collection::vec(0.0f64..core::f64::consts::TAU, 3..9),
    ) {
        let p = ellipse_poly(cx, cy, rx, ry, &angles);
        check_against_oracle(24, 20, &[p]);
    }
}

/// A jittered grid of `nx`×`ny` cells, each split into two triangles along
/// alternating diagonals; the jitter (below a quarter cell) keeps every
/// triangle positively oriented, so the mesh tiles its area.
fn grid_mesh(
    ox: i32,
    oy: i32,
    cell: i32,
    nx: usize,
    ny: usize,
    jitter: &[(i32, i32)],
) -> Vec<Vec<ScreenVertex<0>>> {
    let vid = |i: usize, j: usize| {
        let (jx, jy) = jitter[(j * (nx + 1) + i) % jitter.len()];
        let jx = jx.rem_euclid(cell / 4 + 1) - cell / 8;
        let jy = jy.rem_euclid(cell / 4 + 1) - cell / 8;
        ScreenVertex::new(ox + i as i32 * cell + jx, oy + j as i32 * cell + jy, 0, [])
    };
    let mut tris = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1));
            if (i + j) % 2 == 0 {
                tris.push(vec![a, b, c]);
                tris.push(vec![a, c, d]);
            } else {
                tris.push(vec![a, b, d]);
                tris.push(vec![b, c, d]);
            }
        }
    }
    tris
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn grid_meshes_cover_each_pixel_once(
        ox in -300i32..100, oy in -300i32..100,
        cell in 4i32..200,
        nx in 1usize..8, ny in 1usize..8,
        jitter in proptest::collection::vec((0i32..1000, 0i32..1000), 1..40),
    ) {
        let mesh = grid_mesh(ox, oy, cell, nx, ny, &jitter);
        check_against_oracle(24, 20, &mesh);
        // The oracle itself says the mesh is disjoint; the check above
        // compared per-pixel counts, so the raster's are at most one too.
        let mut t = MockTarget::new(24, 20);
        for p in &mesh {
            fill_polygon(&mut t, &mut NoDepth, &Flat('#'), p);
        }
    }

    #[test]
    fn fans_cover_each_pixel_once(
        cx in -100i32..500, cy in -100i32..400,
        r in 1i32..2000,
        steps in proptest::collection::vec(1u32..100, 3..12),
    ) {
        // Angles strictly increasing over one turn, each step < π.
        let total: u32 = steps.iter().sum();
        let mut acc = 0u32;
        let mut ring = Vec::new();
        for s in &steps {
            if *s as f64 / total as f64 >= 0.5 {
                return Ok(());
            }
            let t = core::f64::consts::TAU * acc as f64 / total as f64;
            ring.push(ScreenVertex::<0>::new(
                cx + (r as f64 * t.cos()).round() as i32,
                cy + (r as f64 * t.sin()).round() as i32,
                0,
                [],
            ));
            acc += s;
        }
        let c = ScreenVertex::new(cx, cy, 0, []);
        let fan: Vec<Vec<ScreenVertex<0>>> = (0..ring.len())
            .map(|k| vec![c, ring[k], ring[(k + 1) % ring.len()]])
            .collect();
        check_against_oracle(30, 26, &fan);
        let mut t = MockTarget::new(30, 26);
        for p in &fan {
            // Panics on overdraw.
            fill_polygon(&mut t, &mut NoDepth, &Flat('#'), p);
        }
    }

    #[test]
    fn huge_triangles_match_oracle(
        a in (-(1i32 << 27)..(1 << 27), -(1i32 << 27)..(1 << 27)),
        b in (-(1i32 << 27)..(1 << 27), -(1i32 << 27)..(1 << 27)),
        c in (-400i32..800, -400i32..800),
    ) {
        let tri = vec![
            ScreenVertex::new(a.0, a.1, 0, []),
            ScreenVertex::new(b.0, b.1, 0, []),
            ScreenVertex::new(c.0, c.1, 0, []),
        ];
        check_against_oracle(32, 32, &[tri]);
    }

    #[test]
    fn tiny_triangles_match_oracle(
        x in 0i32..200, y in 0i32..200,
        d in proptest::collection::vec((-20i32..20, -20i32..20), 2),
    ) {
        let tri = vec![
            ScreenVertex::new(x, y, 0, []),
            ScreenVertex::new(x + d[0].0, y + d[0].1, 0, []),
            ScreenVertex::new(x + d[1].0, y + d[1].1, 0, []),
        ];
        check_against_oracle(14, 14, &[tri]);
    }

    #[cfg(all(feature = "gouraud", feature = "depth"))]
    #[test]
    fn garbage_polygons_never_panic_or_escape(
        pts in proptest::collection::vec((any::<i32>(), any::<i32>(), any::<u16>(), any::<i32>()), 0..12),
        small in proptest::collection::vec((-600i32..600, -600i32..600), 0..12),
    ) {
        let mut ramp = ['g'; 256];
        ramp[7] = 'h';
        let mut zb = [u16::MAX; 20 * 16];
        let mut depth = DepthBuffer::new(&mut zb, 20, 16, 20, 0).unwrap();
        let mut t = MockTarget::new(20, 16);
        t.allow_overdraw = true;
        let big: Vec<ScreenVertex<1>> = pts
            .iter()
            .map(|&(x, y, z, v)| ScreenVertex::new(x >> (x as u32 % 8), y >> (y as u32 % 8), z, [v]))
            .collect();
        fill_polygon(&mut t, &mut depth, &Gouraud::new(&ramp), &big);
        // Non-convex, self-intersecting small polygons: at most one span
        // per row, inside the target (MockTarget panics otherwise).
        let mut u = MockTarget::new(20, 16);
        let sm: Vec<ScreenVertex<0>> = small.iter().map(|&(x, y)| ScreenVertex::new(x, y, 0, [])).collect();
        fill_polygon(&mut u, &mut NoDepth, &Flat('#'), &sm);
    }
}

#[test]
fn rounded_division_ties_away_from_zero() {
    use super::gradient::div_round;
    assert_eq!(div_round(5, 2), 3);
    assert_eq!(div_round(-5, 2), -3);
    assert_eq!(div_round(5, -2), -3);
    assert_eq!(div_round(-5, -2), 3);
    assert_eq!(div_round(7, 3), 2);
    assert_eq!(div_round(-7, 3), -2);
    assert_eq!(div_round(0, -3), 0);
}

/// The exact reference: `round(num / den)`, ties away from zero,
/// saturated to i64, in i128 (the oracle only; the crate links no i128).
fn div_round_i128(num: i128, den: i128) -> i64 {
    let half = (den / 2).abs();
    let q = (num + num.signum() * half) / den;
    q.clamp(i64::MIN as i128, i64::MAX as i128) as i64
}

proptest! {
    #[test]
    fn rounded_division_matches_i128(num in -(1i64 << 61)..(1i64 << 61), den in any::<i64>()) {
        use super::gradient::div_round;
        let den = if den == 0 { 1 } else { den >> 3 | 1 };
        prop_assert_eq!(div_round(num, den), div_round_i128(num as i128, den as i128));
        // Against exact rational rounding.
        let q = div_round(num, den) as i128;
        let (n, d) = (num as i128, den as i128);
        // |n/d − q| ≤ ½  ⇔  |n − q·d| ≤ |d|/2
        prop_assert!(2 * (n - q * d).abs() <= d.abs());
    }

    /// `div_round_shifted` (the set-up's i64-only path for numerators
    /// that overflow once shifted) equals the i128 quotient of `v·2^8`
    /// for every `v` and non-zero `den`, saturated included.
    #[test]
    fn shifted_division_matches_i128(v in any::<i64>(), den in any::<i64>(), shift in 0u32..64) {
        use super::gradient::div_round_shifted;
        // Denominators of every magnitude, small ones included.
        let den = den >> shift;
        let den = if den == 0 { 1 } else { den };
        prop_assert_eq!(div_round_shifted(v, den), div_round_i128((v as i128) << 8, den as i128));
    }
}

#[test]
fn shifted_division_edges() {
    use super::gradient::div_round_shifted;
    for v in [
        0,
        1,
        -1,
        127,
        128,
        -128,
        i64::MAX,
        i64::MIN,
        i64::MIN + 1,
        1 << 54,
        -(1 << 54),
    ] {
        for den in [
            1,
            -1,
            2,
            -2,
            3,
            255,
            256,
            257,
            511,
            512,
            i64::MAX,
            i64::MIN,
            1 << 59,
            -(1 << 59) + 1,
        ] {
            assert_eq!(
                div_round_shifted(v, den),
                div_round_i128((v as i128) << 8, den as i128),
                "v = {v}, den = {den}"
            );
        }
    }
}

/// The shared area reciprocal (`AreaRecip`, the set-up's division for
/// polygons with two planes or more) against the exact i128 quotient:
/// whenever it answers it gives `div_round`'s value, and it answers for
/// every quotient below 2^28 in magnitude (the claim that one correction
/// step suffices there) and every divisor in `[8, 2^31)`.
fn check_area_recip(num: i64, den: i64) {
    check_area_recip_with(num, den, None);
}

/// [`check_area_recip`] with the reciprocal `⌊2^62/d'⌋ − below` when
/// `below` is given (`AreaRecip::with_floor_less`), else the set-up's.
fn check_area_recip_with(num: i64, den: i64, below: Option<u32>) {
    use super::gradient::AreaRecip;
    let r = match below {
        Some(b) => AreaRecip::with_floor_less(den, b),
        None => AreaRecip::new(den),
    };
    let Some(r) = r else {
        assert!(
            den.unsigned_abs() < 8 || den.unsigned_abs() >= 1 << 31,
            "den = {den}"
        );
        return;
    };
    let want = div_round_i128(num as i128, den as i128);
    // The set-up applies the sign of num/den to the magnitude.
    match r.div_round_magnitude(num.unsigned_abs()) {
        Some(q) => assert_eq!(q, want.unsigned_abs(), "num = {num}, den = {den}"),
        None => assert!(
            want.unsigned_abs() >= 1 << 28,
            "num = {num}, den = {den}: no answer for {want}"
        ),
    }
}

#[test]
fn mul_short_is_the_exact_product() {
    use super::gradient::mul_short;
    let mut ds = vec![
        0i32,
        1,
        -1,
        i32::MAX,
        i32::MIN,
        0xffff,
        0x10000,
        -0x10000,
        -0xffff,
    ];
    let mut x = 0x2545_f491_u32;
    for _ in 0..400 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        ds.push(x as i32 >> (x % 31));
    }
    for &d in &ds {
        for e in (-(1 << 15)..=1 << 15)
            .step_by(7)
            .chain([-(1 << 15), 1 << 15, -1, 1])
        {
            assert_eq!(mul_short(d, e), d as i64 * e as i64, "d = {d}, e = {e}");
        }
    }
}

/// The route `Gradient::new` takes on 32-bit targets when the shared
/// reciprocal answers both quotients (64-bit hosts skip it, so it is
/// checked here directly): `quotient_recip` gives the divided quotient
/// (`quotient_divided`) whenever it answers, and `from_small_quotients` builds the plane
/// `from_quotients` builds, every field, for gradients below 2^29. The
/// bases are short triangles of every size and the numerators of every
/// magnitude the short route makes (below 2^47); the reciprocal must
/// answer most of them, or the check would say little.
#[test]
fn small_quotients_are_the_general_route() {
    use super::gradient::{AreaRecip, Basis, Gradient};
    let mut rng = crate::test_util::Rng::new(5);
    let (mut asked, mut answered) = (0u32, 0u32);
    for _ in 0..20_000 {
        let size = rng.int(1, 14) as u32;
        let c = |rng: &mut crate::test_util::Rng| rng.int(-(1 << size), 1 << size) as i32;
        let p = [
            (c(&mut rng), c(&mut rng)),
            (c(&mut rng), c(&mut rng)),
            (c(&mut rng), c(&mut rng)),
        ];
        let area2 = (p[1].0 - p[0].0) as i64 * (p[2].1 - p[0].1) as i64
            - (p[1].1 - p[0].1) as i64 * (p[2].0 - p[0].0) as i64;
        let Some(recip) = AreaRecip::new(area2) else {
            continue;
        };
        let basis = Basis {
            p,
            area2,
            recip: Some(recip),
            short: true,
        };
        for _ in 0..4 {
            let bits = rng.int(0, 47) as u32;
            let v = rng.int(-(1 << bits), 1 << bits);
            asked += 1;
            if let Some(q) = basis.quotient_recip(v) {
                answered += 1;
                assert_eq!(q as i64, basis.quotient_divided(v), "v {v}, area2 {area2}");
                assert!(q.unsigned_abs() < 1 << 29, "v {v}, area2 {area2}: {q}");
            }
        }
        let g = |rng: &mut crate::test_util::Rng| rng.int(-(1 << 29) + 1, (1 << 29) - 1) as i32;
        let (a0, gx, gy) = (
            rng.int(i32::MIN as i64, i32::MAX as i64) as i32,
            g(&mut rng),
            g(&mut rng),
        );
        let (gx, gy) = (gx >> rng.int(0, 29), gy >> rng.int(0, 29));
        let small = Gradient::from_small_quotients(a0, gx, gy, p[0].0, p[0].1);
        let general = Gradient::from_quotients(a0, gx as i64, gy as i64, p[0].0, p[0].1);
        assert_eq!(std::format!("{small:?}"), std::format!("{general:?}"));
    }
    assert!(
        answered > asked / 2,
        "the reciprocal answered {answered} of {asked}"
    );
}

proptest! {
    /// The set-up's short route (two-multiply products for short edges,
    /// with or without the shared area reciprocal) gives the same plane
    /// as the general route, for values of every magnitude, including
    /// differences beyond i32 (which leave the short route).
    #[test]
    fn short_route_is_general(
        p in proptest::array::uniform6(-(1i32 << 14)..=1 << 14),
        a in proptest::array::uniform3(any::<i32>()),
        shift in 0u32..32,
        with_recip in any::<bool>(),
    ) {
        use super::gradient::{AreaRecip, Basis, Gradient};
        let p = [(p[0], p[1]), (p[2], p[3]), (p[4], p[5])];
        let area2 = crate::scalar::widening_mul(p[1].0 - p[0].0, p[2].1 - p[0].1)
            - crate::scalar::widening_mul(p[1].1 - p[0].1, p[2].0 - p[0].0);
        prop_assume!(area2 != 0);
        let a = a.map(|v| v >> shift);
        let recip = if with_recip { AreaRecip::new(area2) } else { None };
        let basis = Basis { p, area2, recip, short: true };
        let fast = Gradient::new(&basis, a);
        let general = Gradient::general(&basis, a);
        prop_assert_eq!(std::format!("{fast:?}"), std::format!("{general:?}"));
    }

    /// Both set-up routes against the exact plane: `g = (Δa × e) · 2^8 / A`
    /// in i128, rounded to nearest with ties away from zero and saturated,
    /// for bases anywhere within ±COORD_LIMIT (short and not) and values
    /// of every magnitude.
    #[test]
    fn gradients_match_i128(
        p in proptest::array::uniform6(-(1i32 << 28)..=1 << 28),
        pshift in 0u32..28,
        a in proptest::array::uniform3(any::<i32>()),
        shift in 0u32..32,
        with_recip in any::<bool>(),
    ) {
        use super::gradient::{AreaRecip, Basis, Gradient};
        let p = p.map(|v| v >> pshift);
        let p = [(p[0], p[1]), (p[2], p[3]), (p[4], p[5])];
        let e = |k: usize| ((p[k].0 - p[0].0) as i128, (p[k].1 - p[0].1) as i128);
        let (e1, e2) = (e(1), e(2));
        let area2 = e1.0 * e2.1 - e1.1 * e2.0;
        prop_assume!(area2 != 0);
        let a = a.map(|v| v >> shift);
        let d1 = a[1] as i128 - a[0] as i128;
        let d2 = a[2] as i128 - a[0] as i128;
        let want = (
            div_round_i128((d1 * e2.1 - d2 * e1.1) << 8, area2),
            div_round_i128((d2 * e1.0 - d1 * e2.0) << 8, area2),
        );
        let area2 = area2 as i64;
        let short = p.iter().all(|q| q.0.abs() <= 1 << 14 && q.1.abs() <= 1 << 14);
        let recip = if with_recip { AreaRecip::new(area2) } else { None };
        let basis = Basis { p, area2, recip, short };
        prop_assert_eq!(Gradient::new(&basis, a).gradients(), want);
        prop_assert_eq!(Gradient::general(&basis, a).gradients(), want);
    }

    /// A plane's span values by the 32-bit route equal the general
    /// route's, clamping included, for every span of a triangle that the
    /// plane fits: first pixel centers within the triangle's extent
    /// around the origin, lengths up to twice that extent. (With overflow
    /// checks on, as in `cargo test`, a bound too loose in `fits` panics
    /// in `span_tiny`.)
    #[test]
    fn tiny_spans_match_general(
        p in proptest::array::uniform6(-(1i32 << 11)..=1 << 11),
        a in proptest::array::uniform3(any::<i32>()),
        shift in 0u32..32,
        kx in any::<u32>(), ky in any::<u32>(), kn in any::<u32>(),
        lo in -(1i32 << 29)..1 << 29, width in 0i32..1 << 30,
    ) {
        use super::gradient::{Basis, Gradient};
        let p = [(p[0], p[1]), (p[2], p[3]), (p[4], p[5])];
        let area2 = crate::scalar::widening_mul(p[1].0 - p[0].0, p[2].1 - p[0].1)
            - crate::scalar::widening_mul(p[1].1 - p[0].1, p[2].0 - p[0].0);
        prop_assume!(area2 != 0);
        let a = a.map(|v| v >> shift);
        let g = Gradient::new(&Basis { p, area2, recip: None, short: true }, a);
        let (x0, y0) = p[0];
        let d = |q: (i32, i32)| (q.0 - x0).unsigned_abs().max((q.1 - y0).unsigned_abs());
        let ext = d(p[1]).max(d(p[2]));
        prop_assume!(g.fits::<true>(ext));
        // A pixel column whose center is within ±ext of the origin.
        let e = ext as i32;
        let pick = |o: i32, k: u32| {
            let (first, last) = ((o - 8 - e).div_euclid(16) + 1, (o - 8 + e).div_euclid(16));
            (first <= last).then(|| first + (k % (last - first + 1) as u32) as i32)
        };
        let (Some(x), Some(y)) = (pick(x0, kx), pick(y0, ky)) else {
            return Ok(());
        };
        let n = (kn % (2 * ext / 16 + 1)) as i32;
        let hi = lo + width;
        let (px, py) = (x * 16 + 8 - x0, y * 16 + 8 - y0);
        prop_assert!(px.abs() <= e && py.abs() <= e);
        let general = g.span(x, y, n as u32 + 1, lo, hi);
        prop_assert_eq!(g.span_tiny::<true>(px, py, n, lo, hi), general);
        if g.fits::<false>(ext) {
            prop_assert_eq!(g.span_tiny::<false>(px, py, n, lo, hi), general);
        }
    }

    #[test]
    fn area_recip_matches_i128(
        num in any::<i64>(), nshift in 2u32..64, den in any::<i32>(), dshift in 0u32..32,
    ) {
        // Numerators below 2^62 of every magnitude, denominators of every
        // magnitude below 2^31 (the set-up's range) and both signs.
        check_area_recip(num >> nshift, (den >> dshift) as i64);
    }
}

#[test]
fn area_recip_edges() {
    let mut dens = vec![
        1i64,
        2,
        3,
        (1 << 31) - 1,
        1 << 30,
        (1 << 30) + 1,
        (1 << 30) - 1,
        1 << 31,
    ];
    for k in 0..31 {
        // Powers of two (the reciprocal is exactly 2^32) and their neighbours.
        dens.extend([1i64 << k, (1 << k) + 1, (1i64 << k).max(2) - 1]);
    }
    for &d in &dens.clone() {
        dens.push(-d);
    }
    for &den in &dens {
        let d = den.unsigned_abs() as i64;
        // Quotients at and around 2^28 to 2^32, ties, zero, the largest
        // numerators.
        let mut nums = vec![
            0i64,
            1,
            -1,
            d / 2,
            d / 2 + 1,
            d - 1,
            d,
            (1 << 62) - 1,
            -(1 << 62) + 1,
        ];
        for q in [
            1i64 << 28,
            (1 << 28) - 1,
            1 << 29,
            (1 << 29) - 1,
            1 << 30,
            (1 << 30) - 1,
            1 << 31,
            (1 << 31) - 1,
            1 << 32,
            (1 << 32) - 1,
            12345,
        ] {
            let n = (q as i128 * d as i128).min((1 << 62) - 1) as i64;
            nums.extend([n, n - 1, n + 1, n + d / 2, n - d / 2, -n, -(n - 1)]);
        }
        for num in nums {
            if num.unsigned_abs() < 1 << 62 {
                check_area_recip(num, den);
            }
        }
    }
}

/// The area reciprocal at its worst: `u = q·|A|` exactly (the quotient's
/// fraction is 0, so any shortfall of the estimate floors it one lower),
/// with the low `c` bits of `u` all ones and `q` as large as `u < 2^(32+c)`
/// allows, for odd divisors of every magnitude (the reciprocal's own
/// shortfall below `2^62/d'` differs with each), at the range's top
/// (`c = t = 27 − s`) and one bit beyond it, where the reciprocal must
/// answer correctly or not at all (the quotients there reach 2^28). A
/// variant that cuts one bit more (`t = 28 − s`, error bounds 1/4 and 1
/// instead of 1/8 and 1/2) fails here. Each case runs with the set-up's
/// reciprocal and with the two ends of the range `recip62_floor` is
/// documented (and exhaustively checked) to stay in: `⌊2^62/d'⌋` and 3
/// units below it.
#[test]
fn area_recip_worst_cases() {
    let mut x = 0x9e37_79b9_u32;
    for i in 0..20_000u32 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        // Odd, in [8, 2^31), every bit length from 4 to 31.
        let d = ((x >> (i % 28 + 1)) | 9) & 0x7fff_ffff;
        let s = d.leading_zeros() - 1;
        // d⁻¹ mod 2^64 by Newton's iteration (d is odd).
        let mut inv = 1u64;
        for _ in 0..6 {
            inv = inv.wrapping_mul(2u64.wrapping_sub((d as u64).wrapping_mul(inv)));
        }
        for c in [27 - s, 28 - s] {
            // q ≡ −d⁻¹ (mod 2^c) makes q·d ≡ −1: its low c bits all ones.
            let m = (1u64 << c) - 1;
            let q0 = inv.wrapping_neg() & m;
            let top = ((1u64 << (32 + c)) - 1) / d as u64;
            if top < q0 {
                continue;
            }
            let q = q0 + ((top - q0) >> c << c);
            let u = q * d as u64;
            assert_eq!(u & m, m, "d = {d}");
            // div_round_magnitude(u − ⌊d/2⌋) divides u: the rounding of
            // (u − ⌊d/2⌋)/d, q exactly.
            let num = (u - (d / 2) as u64) as i64;
            for below in [None, Some(0), Some(3)] {
                check_area_recip_with(num, d as i64, below);
                check_area_recip_with(num + 1, d as i64, below);
                check_area_recip_with(-num, -(d as i64), below);
            }
        }
    }
}

#[cfg(feature = "texture")]
fn checker() -> [char; 16] {
    // 4×4 texels: row j, column i is a letter from "abcd" + row offset.
    core::array::from_fn(|k| char::from(b'a' + (k % 4) as u8 + 4 * (k / 4) as u8))
}

#[cfg(feature = "texture")]
#[test]
fn affine_texture_pattern() {
    // u, v from 0 to 8 over an 8×8 square: the 4×4 texture tiles twice,
    // each texel 1×1 pixel; with Clamp the second tile repeats the edge.
    let tex_data = checker();
    let tex = Texture::new(&tex_data, 4, 4, 4).unwrap();
    let v = |x: f64, y: f64| ScreenVertex::new(sp(x), sp(y), 0, [sp(x) << 12, sp(y) << 12]);
    let sq = [v(0.0, 0.0), v(8.0, 0.0), v(8.0, 8.0), v(0.0, 8.0)];
    let mut t = MockTarget::new(8, 8);
    let sh = AffineTexture::<char, RepeatPow2>::new(tex).unwrap();
    fill_polygon(&mut t, &mut NoDepth, &sh, &sq);
    t.assert_pattern(&[
        "abcdabcd", //
        "efghefgh", //
        "ijklijkl", //
        "mnopmnop", //
        "abcdabcd", //
        "efghefgh", //
        "ijklijkl", //
        "mnopmnop", //
    ]);
    let mut t = MockTarget::new(8, 8);
    let sh = AffineTexture::<char, Clamp>::new(tex).unwrap();
    fill_polygon(&mut t, &mut NoDepth, &sh, &sq);
    t.assert_pattern(&[
        "abcddddd", //
        "efghhhhh", //
        "ijklllll", //
        "mnoppppp", //
        "mnoppppp", //
        "mnoppppp", //
        "mnoppppp", //
        "mnoppppp", //
    ]);
}

#[cfg(feature = "perspective")]
#[test]
fn perspective_texture_with_constant_depth_equals_affine() {
    // q constant (½): (u·q, v·q, q) must give the same texels as (u, v).
    let tex_data = checker();
    let tex = Texture::new(&tex_data, 4, 4, 4).unwrap();
    let q = 1 << (PERSPECTIVE_Q_BITS - 1);
    let v = |x: f64, y: f64| ScreenVertex::new(sp(x), sp(y), 0, [sp(x) << 11, sp(y) << 11, q]);
    let sq = [v(0.0, 0.0), v(8.0, 0.0), v(8.0, 8.0), v(0.0, 8.0)];
    let mut exact = MockTarget::new(8, 8);
    let sh = PerspectiveTexture::<char, RepeatPow2, 1>::new(tex).unwrap();
    fill_polygon(&mut exact, &mut NoDepth, &sh, &sq);
    let mut sub = MockTarget::new(8, 8);
    let sh = PerspectiveTexture::<char, RepeatPow2, 3>::new(tex).unwrap();
    fill_polygon(&mut sub, &mut NoDepth, &sh, &sq);
    for t in [&exact, &sub] {
        t.assert_pattern(&[
            "abcdabcd", //
            "efghefgh", //
            "ijklijkl", //
            "mnopmnop", //
            "abcdabcd", //
            "efghefgh", //
            "ijklijkl", //
            "mnopmnop", //
        ]);
    }
}

#[cfg(feature = "depth")]
proptest! {
    #[test]
    fn depth_runs_match_per_pixel_reference(
        stored in proptest::collection::vec(any::<u16>(), 1..40),
        x in -10i32..50, len in 0u32..60,
        z in 0i32..(65536 << 8), dz in -(1i32 << 16)..(1 << 16),
    ) {
        let w = stored.len();
        let mut buf = stored.clone();
        let mut d = DepthBuffer::new(&mut buf, w as u16, 1, w, 0).unwrap();
        let mut runs = Vec::new();
        d.test_span(0, x, len, z, dz, |off, n| runs.push((off, n)));
        // Per pixel: pixel x+i has key (z + i·dz) >> 8 and passes if less
        // than the stored key; inside the buffer only.
        let mut want = stored.clone();
        let mut pass = vec![false; len as usize];
        for i in 0..len as i64 {
            let col = x as i64 + i;
            if col < 0 || col >= w as i64 {
                continue;
            }
            let key = ((z as i64 + i * dz as i64) >> 8) as u16;
            let c = col as usize;
            if key < want[c] {
                want[c] = key;
                pass[i as usize] = true;
            }
        }
        let mut got_pass = vec![false; len as usize];
        let mut last_end = None;
        for &(off, n) in &runs {
            prop_assert!(n > 0);
            // Maximal, ordered runs.
            if let Some(e) = last_end {
                prop_assert!(off > e);
            }
            for k in off..off + n {
                got_pass[k as usize] = true;
            }
            last_end = Some(off + n);
        }
        prop_assert_eq!(got_pass, pass);
        prop_assert_eq!(buf, want);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Vertices on the half-pixel lattice (multiples of 8 in 28.4), so
    /// that edges and vertices often pass exactly through pixel centers:
    /// the ties the top-left rule decides. Fans around a lattice point
    /// also check that the ties partition.
    #[test]
    fn lattice_polygons_match_oracle(
        pts in proptest::collection::vec((-4i32..40, -4i32..40), 3..7),
    ) {
        let mut p: Vec<(i64, i64)> = pts.iter().map(|&(x, y)| (8 * x as i64, 8 * y as i64)).collect();
        let hull: Vec<ScreenVertex<0>> = convex_hull(&mut p)
            .into_iter()
            .map(|(x, y)| ScreenVertex::new(x as i32, y as i32, 0, []))
            .collect();
        check_against_oracle(18, 18, core::slice::from_ref(&hull));
        // Split the hull into a fan from its first vertex: every pixel
        // of the hull exactly once.
        if hull.len() >= 3 {
            let fan: Vec<Vec<ScreenVertex<0>>> = (1..hull.len() - 1)
                .map(|k| vec![hull[0], hull[k], hull[k + 1]])
                .collect();
            check_against_oracle(18, 18, &fan);
            let mut whole = MockTarget::new(18, 18);
            fill_polygon(&mut whole, &mut NoDepth, &Flat('#'), &hull);
            let mut parts = MockTarget::new(18, 18);
            for t in &fan {
                fill_polygon(&mut parts, &mut NoDepth, &Flat('#'), t);
            }
            prop_assert_eq!(whole.px, parts.px);
        }
    }
}

/// A framebuffer that hides [`Target::span_mut`], forcing the run-splitting
/// path of the depth test.
#[cfg(any(all(feature = "gouraud", feature = "depth"), feature = "texture"))]
struct Unfused<'a>(Framebuffer<'a, u8>);

#[cfg(any(all(feature = "gouraud", feature = "depth"), feature = "texture"))]
impl Target for Unfused<'_> {
    type Color = u8;
    fn clip_rect(&self) -> crate::target::Rect {
        self.0.clip_rect()
    }
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, color: u8) {
        self.0.fill_solid(y, x, len, color);
    }
    fn fill_with<F: FnMut() -> u8>(&mut self, y: i32, x: i32, len: u32, colors: F) {
        self.0.fill_with(y, x, len, colors);
    }
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
proptest! {
    /// The fused depth-test-and-write loop (slice targets) gives exactly
    /// the pixels and keys of the run-splitting path, flat and Gouraud.
    #[test]
    fn fused_depth_write_matches_runs(
        tris in proptest::collection::vec(
            ((-40i32..360, -40i32..300, 0u16..=u16::MAX, 0i32..256),
             (-40i32..360, -40i32..300, 0u16..=u16::MAX, 0i32..256),
             (-40i32..360, -40i32..300, 0u16..=u16::MAX, 0i32..256)), 1..12),
        gouraud in any::<bool>(),
    ) {
        let ramp = ramp_u8();
        let [fused, runs] = fused_and_unfused(|fa, da, fb, db| {
            for (k, &(a, b, c)) in tris.iter().enumerate() {
                let v = |p: (i32, i32, u16, i32)| {
                    ScreenVertex::new(p.0 * 2, p.1 * 2, p.2, [p.3 << 16])
                };
                let poly = [v(a), v(b), v(c)];
                if gouraud {
                    let g = Gouraud::new(&ramp);
                    fill_polygon(fa, da, &g, &poly);
                    fill_polygon(fb, db, &g, &poly);
                } else {
                    fill_polygon(fa, da, &Flat(k as u8 + 1), &poly);
                    fill_polygon(fb, db, &Flat(k as u8 + 1), &poly);
                }
            }
        });
        prop_assert_eq!(fused, runs);
    }
}

/// Colors and keys of a 40×30 slice framebuffer and of an [`Unfused`] one,
/// each with its own depth buffer, after `draw` has drawn into both.
#[cfg(all(feature = "depth", any(feature = "gouraud", feature = "texture")))]
fn fused_and_unfused(
    draw: impl FnOnce(
        &mut Framebuffer<'_, u8>,
        &mut DepthBuffer<'_>,
        &mut Unfused<'_>,
        &mut DepthBuffer<'_>,
    ),
) -> [(Vec<u8>, Vec<u16>); 2] {
    let (w, h) = (40u16, 30u16);
    let n = w as usize * h as usize;
    let (mut ca, mut za) = (vec![0u8; n], vec![u16::MAX; n]);
    let (mut cb, mut zb) = (vec![0u8; n], vec![u16::MAX; n]);
    {
        let mut fa = Framebuffer::new(&mut ca, w, h, w as usize).unwrap();
        let mut da = DepthBuffer::new(&mut za, w, h, w as usize, 0).unwrap();
        let mut fb = Unfused(Framebuffer::new(&mut cb, w, h, w as usize).unwrap());
        let mut db = DepthBuffer::new(&mut zb, w, h, w as usize, 0).unwrap();
        draw(&mut fa, &mut da, &mut fb, &mut db);
    }
    [(ca, za), (cb, zb)]
}

#[cfg(feature = "texture")]
proptest! {
    /// Affine texturing of a masked (power-of-two) texture writes the same
    /// pixels into a slice target (the masked run loop) as through
    /// `fill_with` (`color` per pixel), for texture coordinates up to
    /// ±30 000 texels (steps that wrap the texture many times per pixel),
    /// with row padding; and with a depth buffer (runs of passing pixels)
    /// the same pixels and keys.
    #[test]
    fn affine_slice_path_matches(
        tris in proptest::collection::vec(
            ((-40i32..360, -40i32..300, -30_000i32..30_000, -30_000i32..30_000, 0u16..=u16::MAX),
             (-40i32..360, -40i32..300, -30_000i32..30_000, -30_000i32..30_000, 0u16..=u16::MAX),
             (-40i32..360, -40i32..300, -30_000i32..30_000, -30_000i32..30_000, 0u16..=u16::MAX)), 1..8),
        small in any::<bool>(),
    ) {
        // 8×4 texels in rows of 16, so the stride is not the width.
        let texels: Vec<u8> = (0..64u32).map(|i| (i * 37 % 251) as u8).collect();
        let tex = Texture::new(&texels, 8, 4, 16).unwrap();
        let sh = AffineTexture::<_, RepeatPow2>::new(tex).unwrap();
        let (w, h) = (40u16, 30u16);
        let n = w as usize * h as usize;
        let v = |p: (i32, i32, i32, i32, u16)| {
            // `small`: within a few texels, where neighbouring pixels
            // share texels.
            let (u, t) = if small { (p.2 % 16, p.3 % 16) } else { (p.2, p.3) };
            ScreenVertex::new(p.0 * 2, p.1 * 2, p.4, [u << 16, t << 16])
        };
        let (mut ca, mut cb) = (vec![0u8; n], vec![0u8; n]);
        {
            let mut fa = Framebuffer::new(&mut ca, w, h, w as usize).unwrap();
            let mut fb = Unfused(Framebuffer::new(&mut cb, w, h, w as usize).unwrap());
            for &(a, b, c) in &tris {
                let poly = [v(a), v(b), v(c)];
                fill_polygon(&mut fa, &mut NoDepth, &sh, &poly);
                fill_polygon(&mut fb, &mut NoDepth, &sh, &poly);
            }
        }
        prop_assert_eq!(&ca, &cb);
        #[cfg(feature = "depth")]
        {
            let [fused, runs] = fused_and_unfused(|fa, da, fb, db| {
                for &(a, b, c) in &tris {
                    let poly = [v(a), v(b), v(c)];
                    fill_polygon(fa, da, &sh, &poly);
                    fill_polygon(fb, db, &sh, &poly);
                }
            });
            prop_assert_eq!(fused, runs);
        }
    }
}

#[cfg(feature = "perspective")]
proptest! {
    /// Subdivided perspective texturing writes the same pixels into a
    /// slice target (run loop) as through `fill_with` (per-pixel closure).
    #[test]
    fn subdivided_perspective_slice_path_matches(
        tris in proptest::collection::vec(
            ((-40i32..360, -40i32..300, -600i32..600, -600i32..600, 1i32..(1 << 24)),
             (-40i32..360, -40i32..300, -600i32..600, -600i32..600, 1i32..(1 << 24)),
             (-40i32..360, -40i32..300, -600i32..600, -600i32..600, 1i32..(1 << 24))), 1..8),
    ) {
        let texels: Vec<u8> = (0..64u32).map(|i| (i * 37 % 251) as u8).collect();
        let tex = Texture::new(&texels, 8, 8, 8).unwrap();
        let sh = PerspectiveTexture::<_, RepeatPow2, 16>::new(tex).unwrap();
        let (w, h) = (40u16, 30u16);
        let n = w as usize * h as usize;
        let (mut ca, mut cb) = (vec![0u8; n], vec![0u8; n]);
        {
            let mut fa = Framebuffer::new(&mut ca, w, h, w as usize).unwrap();
            let mut fb = Unfused(Framebuffer::new(&mut cb, w, h, w as usize).unwrap());
            for &(a, b, c) in &tris {
                // Varyings u·q, v·q (16.16) and q (8.24) as the pipeline
                // makes them.
                let v = |p: (i32, i32, i32, i32, i32)| {
                    let uq = ((p.2 as i64 * p.4 as i64) >> 8) as i32;
                    let vq = ((p.3 as i64 * p.4 as i64) >> 8) as i32;
                    ScreenVertex::new(p.0 * 2, p.1 * 2, 0, [uq, vq, p.4])
                };
                let poly = [v(a), v(b), v(c)];
                fill_polygon(&mut fa, &mut NoDepth, &sh, &poly);
                fill_polygon(&mut fb, &mut NoDepth, &sh, &poly);
            }
        }
        prop_assert_eq!(ca, cb);
    }
}

#[cfg(feature = "texture")]
#[test]
fn lit_affine_texture_scales_texels() {
    use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    let texels: Vec<Rgb565> = (0..16u8)
        .map(|i| Rgb565::new(i * 2, 63 - i * 3, 31 - i))
        .collect();
    let tex = Texture::new(&texels, 4, 4, 4).unwrap();
    let plain = AffineTexture::<_, RepeatPow2>::new(tex).unwrap();
    let lit = LitAffineTexture::<_, RepeatPow2>::new(tex).unwrap();
    let (w, h) = (12u16, 10u16);
    let n = w as usize * h as usize;
    for i in [0u8, 1, 77, 128, 254, 255] {
        let (mut a, mut b) = (vec![Rgb565::BLACK; n], vec![Rgb565::BLACK; n]);
        {
            let mut fa = Framebuffer::new(&mut a, w, h, w as usize).unwrap();
            let mut fb = Framebuffer::new(&mut b, w, h, w as usize).unwrap();
            let iv = (i as i32) << 16;
            let uv = |x: i32, y: i32, u: i32, v: i32| (x * 16, y * 16, u << 16, v << 16);
            let quad = [
                uv(0, 0, 0, 0),
                uv(12, 1, 9, 0),
                uv(11, 10, 9, 7),
                uv(1, 9, 0, 7),
            ];
            let pa: Vec<ScreenVertex<2>> = quad
                .iter()
                .map(|&(x, y, u, v)| ScreenVertex::new(x, y, 0, [u, v]))
                .collect();
            let pb: Vec<ScreenVertex<3>> = quad
                .iter()
                .map(|&(x, y, u, v)| ScreenVertex::new(x, y, 0, [iv, u, v]))
                .collect();
            fill_polygon(&mut fa, &mut NoDepth, &plain, &pa);
            fill_polygon(&mut fb, &mut NoDepth, &lit, &pb);
        }
        for (p, q) in a.iter().zip(&b) {
            assert_eq!(p.scale(i), *q, "intensity {i}");
        }
    }
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
proptest! {
    /// The triangle walker gives exactly the chain walker's pixels and
    /// keys: the same triangle with a repeated vertex goes through the
    /// general path.
    #[test]
    fn triangle_path_matches_general_path(
        tri in proptest::array::uniform3((-300i32..900, -300i32..700, 0u16..=u16::MAX, 0i32..256)),
        clip_x in 0u16..30, clip_y in 0u16..20,
    ) {
        let (w, h) = (40u16, 30u16);
        let n = w as usize * h as usize;
        let ramp = ramp_u8();
        let v = |p: (i32, i32, u16, i32)| ScreenVertex::new(p.0, p.1, p.2, [p.3 << 16]);
        let t3 = [v(tri[0]), v(tri[1]), v(tri[2])];
        let t4 = [t3[0], t3[1], t3[2], t3[2]];
        let mut out = Vec::new();
        for poly in [&t3[..], &t4[..]] {
            let (mut c, mut z) = (vec![0u8; n], vec![u16::MAX; n]);
            let o = {
                let mut band = Band::new(&mut c, w, h - clip_y, w as usize, clip_y as i32).unwrap();
                let mut d = DepthBuffer::new(&mut z, w - clip_x, h, w as usize, 0).unwrap();
                fill_polygon(&mut band, &mut d, &Gouraud::new(&ramp), poly)
            };
            out.push((o, c, z));
        }
        prop_assert_eq!(&out[0], &out[1]);
    }
}

#[cfg(all(feature = "gouraud", feature = "depth"))]
proptest! {
    /// Polygons (as the clipper makes them) whose planes fit their extent
    /// take the 32-bit span route: every pixel and key as the general
    /// route gives them. The extent is that of all the vertices, not only
    /// the basis triangle's (a span outside it fails a debug assertion in
    /// `fill`); radii up to 600 pixels reach past the 32-bit route's
    /// bounds, where the general route must be taken.
    #[test]
    fn polygon_spans_match_general_route(
        cx in -100i32..500, cy in -100i32..400,
        rx in 1i32..9_600, ry in 1i32..9_600,
        angles in proptest::collection::vec(0.0f64..core::f64::consts::TAU, 4..9),
        zs in proptest::collection::vec(0u16..=u16::MAX, 8),
        vs in proptest::collection::vec(0i32..256, 8),
        clip_x in 0u16..30, clip_y in 0u16..20,
    ) {
        let (w, h) = (48u16, 36u16);
        let n = w as usize * h as usize;
        let ramp = ramp_u8();
        let poly: Vec<ScreenVertex<1>> = ellipse_poly(cx * 16, cy * 16, rx, ry, &angles)
            .iter()
            .enumerate()
            .map(|(k, p)| ScreenVertex::new(p.x, p.y, zs[k % 8], [vs[k % 8] << 16]))
            .collect();
        let mut out = Vec::new();
        for general in [false, true] {
            super::GENERAL_SPANS.with(|g| g.set(general));
            let (mut c, mut z) = (vec![0u8; n], vec![u16::MAX; n]);
            let o = {
                let mut band = Band::new(&mut c, w, h - clip_y, w as usize, clip_y as i32).unwrap();
                let mut d = DepthBuffer::new(&mut z, w - clip_x, h, w as usize, 0).unwrap();
                fill_polygon(&mut band, &mut d, &Gouraud::new(&ramp), &poly)
            };
            super::GENERAL_SPANS.with(|g| g.set(false));
            out.push((o, c, z));
        }
        prop_assert_eq!(&out[0], &out[1]);
    }
}

/// The comparison above compares something: a pentagon some 40 pixels
/// across with Gouraud and depth planes takes the 32-bit route.
#[cfg(all(feature = "gouraud", feature = "depth"))]
#[test]
fn polygons_take_the_32_bit_route() {
    let ramp = ramp_u8();
    let (w, h) = (48u16, 36u16);
    let n = w as usize * h as usize;
    let (mut c, mut z) = (vec![0u8; n], vec![u16::MAX; n]);
    let mut fb = Framebuffer::new(&mut c, w, h, w as usize).unwrap();
    let mut d = DepthBuffer::new(&mut z, w, h, w as usize, 0).unwrap();
    let v = |x: i32, y: i32, z: u16, i: i32| ScreenVertex::new(x * 16, y * 16, z, [i << 16]);
    let pentagon = [
        v(4, 2, 100, 10),
        v(40, 4, 3000, 200),
        v(44, 20, 9000, 90),
        v(20, 34, 500, 30),
        v(2, 18, 1200, 250),
    ];
    let before = super::TINY_FILLS.with(|t| t.get());
    assert_eq!(
        fill_polygon(&mut fb, &mut d, &Gouraud::new(&ramp), &pentagon),
        FillOutcome::Drawn
    );
    assert_eq!(super::TINY_FILLS.with(|t| t.get()), before + 1);
}

/// Draws two triangles covering the same 32×32 square in both orders with
/// a `K` depth buffer; returns how many pixels differ between the orders.
#[cfg(feature = "depth")]
fn crossing_planes_order_dependence<K: StoredDepth>(far: K) -> usize {
    let (w, h) = (32u16, 32u16);
    let n = w as usize * h as usize;
    // Two planes that cross along the diagonal and differ by at most 1.5
    // keys over the square: with 16-bit keys most pixels tie.
    let a = |c| {
        let v = |x: i32, y: i32, z: u16| ScreenVertex::new(x * 16, y * 16, z, [0; 0]);
        (c, [v(-40, -40, 1000), v(80, -40, 1001), v(-40, 80, 1001)])
    };
    let b = |c| {
        let v = |x: i32, y: i32, z: u16| ScreenVertex::new(x * 16, y * 16, z, [0; 0]);
        (c, [v(-40, -40, 1001), v(80, -40, 1000), v(-40, 80, 1000)])
    };
    let mut out = Vec::new();
    for order in [[a(1u8), b(2u8)], [b(2u8), a(1u8)]] {
        let (mut c, mut z) = (vec![0u8; n], vec![far; n]);
        {
            let mut fb = Framebuffer::new(&mut c, w, h, w as usize).unwrap();
            let mut d = DepthBuffer::new(&mut z, w, h, w as usize, 0).unwrap();
            for (col, tri) in &order {
                fill_polygon(&mut fb, &mut d, &Flat(*col), tri);
            }
        }
        out.push(c);
    }
    out[0].iter().zip(&out[1]).filter(|(p, q)| p != q).count()
}

#[cfg(feature = "depth")]
#[test]
fn u32_depth_keeps_the_interpolated_fraction() {
    // u16: pixels whose keys tie keep whichever triangle came first.
    let d16 = crossing_planes_order_dependence::<u16>(u16::MAX);
    // u32 (24.8): the planes decide everywhere but on the crossing line.
    let d32 = crossing_planes_order_dependence::<u32>(u32::MAX);
    std::println!("order-dependent pixels: u16 {d16}, u32 {d32}");
    assert!(d16 > 300, "u16: {d16} pixels depend on the order");
    assert!(d32 <= 32, "u32: {d32} pixels depend on the order");
}

#[cfg(feature = "depth")]
proptest! {
    /// With well separated depths (whole keys apart at every pixel) the
    /// u32 buffer draws exactly what the u16 buffer draws.
    #[test]
    fn u32_depth_matches_u16_when_keys_differ(
        zs in proptest::collection::vec(0u16..60, 2..6),
    ) {
        let (w, h) = (24u16, 20u16);
        let n = w as usize * h as usize;
        let tris: Vec<[ScreenVertex<0>; 3]> = zs.iter().enumerate().map(|(k, &z)| {
            let z = z * 1000; // constant depth per triangle
            let o = k as i32 * 32;
            [ScreenVertex::new(o, 0, z, []), ScreenVertex::new(o + 300, 40, z, []),
             ScreenVertex::new(o + 20, 320, z, [])]
        }).collect();
        let (mut c16, mut z16) = (vec![0u8; n], vec![u16::MAX; n]);
        let (mut c32, mut z32) = (vec![0u8; n], vec![u32::MAX; n]);
        {
            let mut f16 = Framebuffer::new(&mut c16, w, h, w as usize).unwrap();
            let mut d16 = DepthBuffer::new(&mut z16, w, h, w as usize, 0).unwrap();
            let mut f32_ = Framebuffer::new(&mut c32, w, h, w as usize).unwrap();
            let mut d32 = DepthBuffer::new(&mut z32, w, h, w as usize, 0).unwrap();
            for (k, t) in tris.iter().enumerate() {
                fill_polygon(&mut f16, &mut d16, &Flat(k as u8 + 1), t);
                fill_polygon(&mut f32_, &mut d32, &Flat(k as u8 + 1), t);
            }
        }
        prop_assert_eq!(c16, c32);
        for (a, b) in z16.iter().zip(&z32) {
            prop_assert_eq!(*a as u32, if *b == u32::MAX { u16::MAX as u32 } else { *b >> 8 });
        }
    }
}

/// Fuzz regression (`raster`): a sliver 9.8 million pixels tall with large
/// varyings saturates a gradient to `i64::MIN`, whose `abs()` overflowed
/// while choosing the plane's fast path (a panic with debug assertions).
/// It must draw without panicking and only inside the band.
#[cfg(all(feature = "gouraud", feature = "depth"))]
#[test]
fn saturated_gradient_does_not_overflow() {
    let ramp: [u8; 256] = core::array::from_fn(|i| (i as u8).max(1));
    let (w, h, stride, y0) = (13u16, 16u16, 16usize, -5);
    let len = stride * (h as usize - 1) + w as usize;
    let mut px = std::vec![0u8; len];
    let mut keys = std::vec![u16::MAX; len];
    let mut band = crate::target::Band::new(&mut px, w, h, stride, y0).unwrap();
    let mut depth = DepthBuffer::<u16>::new(&mut keys, w, h, stride, y0).unwrap();
    let verts = [
        ScreenVertex::new(-1, 156_850_543, 65369, [185_273_329]),
        ScreenVertex::new(0, -1, 65535, [872_415_231]),
        ScreenVertex::new(0, 0, 0, [0]),
    ];
    let _ = fill_polygon(&mut band, &mut depth, &Gouraud::new(&ramp), &verts);
    for (i, &p) in px.iter().enumerate() {
        if i % stride >= w as usize {
            assert_eq!(p, 0, "stride padding written at {i}");
        }
    }
}

#[cfg(feature = "perspective")]
proptest! {
    /// The perspective divide against the exact quotient in i128: the
    /// truncated quotient itself below `EXACT_BELOW` units, and beyond it
    /// never below it and above it by at most 4·T/2^31 + 1 units.
    #[test]
    fn perspective_divide_is_the_exact_quotient(
        x in prop_oneof![any::<i32>(), -(1i32 << 12)..(1 << 12)],
        q in prop_oneof![1i32..64, 1i32..(1 << 24), any::<i32>()],
    ) {
        use super::persp_div::{EXACT_BELOW, divide};
        let (got, _) = divide(&[x, 0, q]);
        let qq = q.max(1) as i128;
        let num = (x.unsigned_abs() as i128) << PERSPECTIVE_Q_BITS;
        let trunc = num / qq;
        let m = got.unsigned_abs() as i128;
        prop_assert!(got == 0 || (got < 0) == (x < 0));
        if trunc < EXACT_BELOW as i128 {
            prop_assert_eq!(m, trunc);
        } else {
            prop_assert!(m >= trunc, "{m} < {trunc}");
            prop_assert!(m - trunc <= 4 * trunc / (1 << 31) + 1, "{m} vs {trunc}");
        }
    }
}

#[cfg(feature = "perspective")]
proptest! {
    /// The small divide is the divide wherever it answers, and answers
    /// wherever both quotients are below `EXACT_BELOW − 1` units.
    #[test]
    fn small_divide_is_the_divide(
        u in prop_oneof![any::<i32>(), -(1i32 << 12)..(1 << 12)],
        v in prop_oneof![any::<i32>(), -(1i32 << 20)..(1 << 20)],
        q in prop_oneof![1i32..64, 1i32..(1 << 24), any::<i32>()],
    ) {
        use super::persp_div::{EXACT_BELOW, divide, divide_small};
        let (a, b) = divide(&[u, v, q]);
        match divide_small(&[u, v, q]) {
            Some((x, y)) => prop_assert_eq!((x as i64, y as i64), (a, b)),
            None => prop_assert!(a.unsigned_abs().max(b.unsigned_abs()) >= EXACT_BELOW - 1),
        }
    }

    /// Exact mode samples the texel at the exact truncated quotients
    /// (i128 oracle), on both sides of the small divide's range.
    #[test]
    fn exact_mode_samples_the_exact_quotient(
        u in prop_oneof![any::<i32>(), -(1i32 << 20)..(1 << 20)],
        v in prop_oneof![any::<i32>(), -(1i32 << 12)..(1 << 12)],
        q in prop_oneof![1i32..64, 1i32..(1 << 24), any::<i32>()],
    ) {
        let texels: Vec<u16> = (0..64 * 32u32).map(|i| (i * 40503 % 65521) as u16).collect();
        let tex = Texture::new(&texels, 64, 32, 64).unwrap();
        let sh = PerspectiveTexture::<_, RepeatPow2, 1>::new(tex).unwrap();
        let qq = q.max(1) as i128;
        let texel = |x: i32| {
            let t = ((x as i128) << PERSPECTIVE_Q_BITS) / qq;
            (t >> 16).clamp(i32::MIN as i128, i32::MAX as i128) as i32
        };
        prop_assert_eq!(sh.color(&[u, v, q]), tex.sample::<RepeatPow2>(texel(u), texel(v)));
    }

    /// Quotients just below an integer, where the reciprocal's estimate
    /// is one too high and only the remainder's sign corrects it.
    #[test]
    fn small_divide_corrects_its_estimate(
        q in (1i64 << 25)..(1 << 26),
        t in (1i64 << 26)..(1 << 29),
        neg in any::<bool>(),
    ) {
        use super::persp_div::{divide, divide_small};
        // u·2^24 just below (t + 1)·q: the quotient is t, its fraction
        // above 1 − 2^24/q.
        let u = (((t + 1) * q - 1) >> PERSPECTIVE_Q_BITS) as i32;
        let u = if neg { -u } else { u };
        let exact = ((u.unsigned_abs() as i64) << PERSPECTIVE_Q_BITS) / q;
        let want = if neg { -exact } else { exact };
        prop_assert_eq!(divide(&[u, 0, q as i32]).0, want);
        if let Some((x, _)) = divide_small(&[u, 0, q as i32]) {
            prop_assert_eq!(x as i64, want);
        }
    }
}

/// `persp_div::texels` against the exact texels (i128), and that it
/// answers wherever `q` is in `[2^8, 2^24]` and both texels lie within
/// `±(2^15 − 8)`.
#[cfg(feature = "perspective")]
fn check_texels(x: i32, y: i32, q: i32) -> Result<(), proptest::test_runner::TestCaseError> {
    let texel = |x: i32| ((((x as i128) << PERSPECTIVE_Q_BITS) / q as i128) >> 16) as i64;
    let want = (texel(x), texel(y));
    match super::persp_div::texels(&[x, y, q]) {
        Some((u, v)) => prop_assert_eq!((u as i64, v as i64), want, "x {} y {} q {}", x, y, q),
        None => prop_assert!(
            !(1 << 8..=1 << 24).contains(&q)
                || want.0.abs() >= (1 << 15) - 8
                || want.1.abs() >= (1 << 15) - 8,
            "no answer for x {} y {} q {}",
            x,
            y,
            q
        ),
    }
    Ok(())
}

/// Divisors q for the 32-bit divides: below, across and above their range
/// `[2^8, 2^24]`, its ends and 2^16, and any i32.
#[cfg(feature = "perspective")]
fn short_divisors() -> impl Strategy<Value = i32> {
    prop_oneof![
        1i32..(1 << 9),
        (1i32 << 8)..=(1 << 24),
        ((1i32 << 16) - 16)..((1 << 16) + 16),
        ((1i32 << 24) - 64)..((1 << 24) + 64),
        any::<i32>(),
    ]
}

/// `persp_div::quotients` against the exact truncated quotients (i128),
/// and that it answers wherever `q` is in `[2^8, 2^24]` and both lie
/// within `±(2^29 − 2^17)`, and never beyond `±(2^29 − 2^16)` (where
/// `divide` is exact too).
#[cfg(feature = "perspective")]
fn check_quotients(x: i32, y: i32, q: i32) -> Result<(), proptest::test_runner::TestCaseError> {
    use super::persp_div::quotients;
    let exact = |x: i32| (((x as i128) << PERSPECTIVE_Q_BITS) / q as i128) as i64;
    let want = (exact(x), exact(y));
    let limit = (1i64 << 29) - (1 << 17);
    match quotients(&[x, y, q]) {
        Some((u, v)) => {
            prop_assert_eq!((u as i64, v as i64), want, "x {} y {} q {}", x, y, q);
            let most = (1i64 << 29) - (1 << 16);
            prop_assert!(
                want.0.abs() < most && want.1.abs() < most,
                "x {} y {} q {}",
                x,
                y,
                q
            );
        }
        None => prop_assert!(
            !(1 << 8..=1 << 24).contains(&q) || want.0.abs() >= limit || want.1.abs() >= limit,
            "no answer for x {} y {} q {}",
            x,
            y,
            q
        ),
    }
    Ok(())
}

#[cfg(feature = "perspective")]
proptest! {
    /// The 32-bit divide gives the exact truncated quotients (i128
    /// oracle): q across its range and beyond it, quotients from a
    /// fraction of a texel to beyond 2^13 texels, fractions anywhere.
    #[test]
    fn quotients_are_the_exact_quotients(
        x in prop_oneof![any::<i32>(), -(1i32 << 21)..(1 << 21), -4096i32..4096, -8i32..8],
        y in prop_oneof![any::<i32>(), -(1i32 << 13)..(1 << 13)],
        q in short_divisors(),
    ) {
        check_quotients(x, y, q)?;
    }

    /// The same where the fraction is just below a unit: `x·2^24 mod q`
    /// in the last 2^k of q, found from the inverse of 2^24 modulo an odd
    /// q, and quotients near the 2^29 − 2^16 limit.
    #[test]
    fn quotients_near_a_unit(
        q in ((1i64 << 8) + 1..(1 << 24)).prop_map(|q| q | 1),
        back in 1i64..1024, t in 0i64..(1 << 29),
    ) {
        // 2^24·a ≡ q − back (mod q): the fraction's remainder is one
        // `back` short of a unit.
        let r = (q - back % q).rem_euclid(q);
        let inv2 = (q + 1) / 2;
        let inv = (0..24).fold(1, |acc, _| acc * inv2 % q);
        let a0 = (r * inv) % q;
        // Near the quotient t: a ≈ t·q/2^24, moved to the residue a0.
        let a = ((t * q) >> 24) / q * q + a0;
        prop_assume!(a < 1 << 31);
        prop_assert_eq!((a << 24).rem_euclid(q), r);
        check_quotients(a as i32, -(a as i32), q as i32)?;
    }

    /// The same at the edge of its range: quotients within 2^17 units of
    /// `2^29 − 2^16`, either sign.
    #[test]
    fn quotients_at_their_limit(
        q in (1i64 << 8)..=(1 << 24), k in -(1i64 << 17)..(1 << 17), neg in any::<bool>(),
    ) {
        let a = (((1i64 << 29) - (1 << 16) + k) * q) >> 24;
        prop_assume!(a < 1 << 31);
        let x = if neg { -a } else { a } as i32;
        check_quotients(x, 0, q as i32)?;
    }
}

#[cfg(feature = "perspective")]
proptest! {
    /// Exact mode's texel divide gives the exact texels (i128 oracle):
    /// q across its range and beyond it, texels from a few to beyond
    /// 2^15.
    #[test]
    fn texels_are_the_exact_quotients(
        x in prop_oneof![any::<i32>(), -(1i32 << 23)..(1 << 23), -4096i32..4096],
        y in prop_oneof![any::<i32>(), -(1i32 << 16)..(1 << 16)],
        q in short_divisors(),
    ) {
        check_texels(x, y, q)?;
    }

    /// The same where the sign rule decides: x < 0 with
    /// `E = x·2^8 mod q` at or next to `⌈q/2^16⌉` (and at 0 and q − 1),
    /// built with the inverse of 256 modulo an odd q.
    #[test]
    fn texels_at_the_sign_rule(
        q in prop_oneof![
            ((1i64 << 8) + 1..(1 << 24)).prop_map(|q| q | 1),
            (1i64..256).prop_map(|k| (k << 16) + 1),
        ],
        pick in 0usize..6, g in 0i64..(1 << 15),
    ) {
        let ceil = (q + 0xffff) >> 16;
        let e = [0, 1, ceil - 1, ceil, ceil + 1, q - 1][pick].clamp(0, q - 1);
        // a·256 ≡ e (mod q) with G = ⌊a·256/q⌋ close to g.
        let inv = (0..8).fold(1, |acc, _| acc * ((q + 1) / 2) % q);
        let a0 = (e * inv) % q;
        let a = a0 + (g * q / 256) / q * q;
        prop_assume!(a < 1 << 31);
        prop_assert_eq!((a * 256).rem_euclid(q), e);
        check_texels(-(a as i32), a as i32, q as i32)?;
        check_texels(a as i32, -(a as i32), q as i32)?;
    }
}

#[cfg(feature = "perspective")]
proptest! {
    /// Exact mode's stepped runs sample `color`'s texel at every pixel:
    /// spans where the stepping applies (q up to 2^24, a few texels a
    /// pixel, u either sign and crossing zero, small q where truncation
    /// toward zero often crosses a texel) and spans where it must fall
    /// back (large steps, q leaving its range, wrapping varyings).
    #[test]
    fn exact_runs_are_color(
        x0 in prop_oneof![-(1i32 << 28)..(1 << 28), -(1i32 << 16)..(1 << 16), any::<i32>()],
        dx in prop_oneof![-(1i32 << 18)..(1 << 18), -300i32..300, -(1i32 << 25)..(1 << 25), any::<i32>()],
        y0 in -(1i32 << 24)..(1 << 24),
        dy in -(1i32 << 12)..(1 << 12),
        q0 in prop_oneof![1i32..64, 1i32..(1 << 16), 1i32..=(1 << 24), (1i32 << 24)..(1 << 30), any::<i32>()],
        dq in prop_oneof![-64i32..64, -(1i32 << 14)..(1 << 14), any::<i32>()],
        len in 1u32..240,
    ) {
        exact_runs_match_color([x0, y0, q0], [dx, dy, dq], len)?;
    }

    /// The same near zero: F = ⌊x·2^8/q⌋ = −2, where the truncation puts
    /// the texel at −1 and the run's ends' texels may all be ≥ −1 (the
    /// sign test must not be skipped there). The x are found by scanning
    /// F = −2's interval for residues in the window.
    #[test]
    fn exact_runs_truncate_toward_zero_near_zero(
        q in ((1i64 << 16) + 1..(1 << 22)).prop_map(|q| q | 1),
        dx in -3i32..=3, len in 1u32..70,
    ) {
        let window = (q + 0xffff) >> 16;
        let xs: Vec<i64> = (-(2 * q) / 256 - 1..=-q / 256)
            .filter(|&x| (x * 256).div_euclid(q) == -2 && (x * 256).rem_euclid(q) > q - window)
            .collect();
        // About one q in four has such an x (the residues step by 256
        // through a window narrower than that); the others check nothing.
        for x in xs {
            exact_runs_match_color([x as i32, 0, q as i32], [dx, 0, 0], len)?;
        }
    }

    /// Exact mode where both ends' texels are clamped to i32 (u of 2^31
    /// texels or more): the stepping must not start from them.
    #[test]
    fn exact_runs_with_clamped_texels(
        x0 in (1i32 << 27)..(1 << 28), q0 in 1i32..8, dx in -64i32..64, len in 1u32..40,
    ) {
        exact_runs_match_color([x0, -x0, q0], [dx, dx, 0], len)?;
    }

    /// Exact mode's unmasked sampling pass, one and two pixels an iteration
    /// (the second is ARMv6-M's), writes what sampling each pixel gives,
    /// for runs of every length up to 70 (odd ones end
    /// with a lone pixel), coordinates anywhere in i16 (wrapped or
    /// clamped), and coordinate slices longer than the run.
    #[test]
    fn paired_sampling_is_per_pixel(
        uv in proptest::collection::vec(any::<(i16, i16)>(), 0..70),
        extra in 0usize..3,
    ) {
        let texels: Vec<u16> = (0..64 * 32u32).map(|i| (i * 40503 % 65521) as u16).collect();
        let (u, v): (Vec<i16>, Vec<i16>) = uv.iter().copied().unzip();
        let n = u.len().saturating_sub(extra);
        let tex = Texture::new(&texels, 64, 32, 64).unwrap();
        unmasked_sampling_is_per_pixel::<RepeatPow2>(tex, &u, &v, n)?;
        let tex = Texture::new(&texels, 5, 3, 7).unwrap();
        unmasked_sampling_is_per_pixel::<Clamp>(tex, &u, &v, n)?;
    }

    /// Exact mode where every pixel's u is a whole texel (E = 0 exactly:
    /// the stepping must land on F, not one below).
    #[test]
    fn exact_runs_on_whole_texels(
        a in 1i32..(1 << 16), k in -100i32..100, j in -3i32..=3, len in 1u32..240,
    ) {
        // q = 256·a and x = a·(k + j·i): u = x·2^8/q = k + j·i exactly.
        exact_runs_match_color([a * k, a * k, 256 * a], [a * j, -a * j, 0], len)?;
    }

    /// Exact mode where truncating T toward zero crosses a texel: x < 0
    /// and `x·2^8 mod q` within `⌈q/2^16⌉` below q (q > 2^16), built with
    /// the inverse of 256 modulo an odd q.
    #[test]
    fn exact_runs_truncate_toward_zero(
        q in prop_oneof![
            ((1i64 << 16) + 1..(1 << 24)).prop_map(|q| q | 1),
            // ⌈q/2^16⌉ is one more than ⌊q/2^16⌋ by a single unit.
            (1i64..256).prop_map(|k| (k << 16) + 1),
        ],
        back in 1i64..256, m in 1i64..100, dx in -2000i32..2000, len in 1u32..40,
    ) {
        let window = (q + 0xffff) >> 16;
        let r = q - 1 - (back % (window - 1).max(1));
        // 2^−1 = (q + 1)/2 modulo odd q, so 256^−1 is its eighth power.
        let inv = (0..8).fold(1, |acc, _| acc * ((q + 1) / 2) % q);
        let x = (r * inv) % q - m * q;
        prop_assert_eq!((x * 256).rem_euclid(q), r);
        exact_runs_match_color([x as i32, 0, q as i32], [dx, 0, 0], len)?;
    }
}

/// `PerspectiveTexture::sample_by` (exact mode's unmasked sampling
/// pass), one and two pixels an iteration, against `sample` at each of
/// the first `n` pixels.
#[cfg(feature = "perspective")]
fn unmasked_sampling_is_per_pixel<W: crate::texture::Wrap>(
    tex: Texture<'_, u16>,
    u: &[i16],
    v: &[i16],
    n: usize,
) -> Result<(), proptest::test_runner::TestCaseError> {
    let sh = PerspectiveTexture::<_, W, 1>::new(tex).unwrap();
    for pairs in [false, true] {
        let mut run = vec![0u16; n];
        if pairs {
            sh.sample_by::<true>(&mut run, u, v);
        } else {
            sh.sample_by::<false>(&mut run, u, v);
        }
        for (j, &got) in run.iter().enumerate() {
            let want = tex.sample::<W>(u[j].into(), v[j].into());
            prop_assert_eq!(got, want, "pixel {} pairs {}", j, pairs);
        }
    }
    Ok(())
}

/// `PerspectiveTexture<_, _, 1>::shade_run` on a slice against `color` at
/// every pixel, and nothing written past the run.
#[cfg(feature = "perspective")]
fn exact_runs_match_color(
    start: [i32; 3],
    step: [i32; 3],
    len: u32,
) -> Result<(), proptest::test_runner::TestCaseError> {
    let texels: Vec<u8> = (0..64 * 32u32).map(|i| (i * 37 % 251) as u8).collect();
    let tex = Texture::new(&texels, 64, 32, 64).unwrap();
    check_exact_runs(
        &PerspectiveTexture::<_, RepeatPow2, 1>::new(tex).unwrap(),
        start,
        step,
        len,
    )?;
    // Clamp on a 5×3 texture: every bit of a texel coordinate matters, not
    // only the low ones a power-of-two repeat keeps.
    let tex = Texture::new(&texels[..15], 5, 3, 5).unwrap();
    check_exact_runs(
        &PerspectiveTexture::<_, crate::texture::Clamp, 1>::new(tex).unwrap(),
        start,
        step,
        len,
    )
}

#[cfg(feature = "perspective")]
fn check_exact_runs<Sh: SpanShader<3, Color = u8>>(
    sh: &Sh,
    start: [i32; 3],
    step: [i32; 3],
    len: u32,
) -> Result<(), proptest::test_runner::TestCaseError> {
    let w = 240u16;
    let mut got = vec![0u8; w as usize];
    {
        let mut fb = Framebuffer::new(&mut got, w, 1, w as usize).unwrap();
        sh.shade_run(&mut fb, 0, 0, len, start, step);
    }
    for i in 0..len as i32 {
        let v: [i32; 3] = core::array::from_fn(|k| start[k].wrapping_add(step[k].wrapping_mul(i)));
        prop_assert_eq!(got[i as usize], sh.color(&v), "pixel {} of {}", i, len);
    }
    prop_assert!(got[len as usize..].iter().all(|&p| p == 0));
    Ok(())
}

#[cfg(feature = "perspective")]
proptest! {
    /// Subdivided runs with any varyings, including ones the pipeline never
    /// makes (q ≤ 0, u·q at the ends of i32, steps that wrap): no panic
    /// (debug builds check every operation), and the slice path writes the
    /// same pixels as the per-pixel `fill_with` path.
    #[test]
    fn subdivided_runs_with_extreme_varyings_agree(
        start in any::<[i32; 3]>(),
        step in any::<[i32; 3]>(),
        x in 0i32..40,
        len in 1u32..200,
        small_steps in any::<bool>(),
    ) {
        let step = if small_steps { step.map(|s| s >> 16) } else { step };
        let texels: Vec<u8> = (0..64u32).map(|i| (i * 37 % 251) as u8).collect();
        let tex = Texture::new(&texels, 8, 8, 8).unwrap();
        let sh8 = PerspectiveTexture::<_, RepeatPow2, 8>::new(tex).unwrap();
        let sh5 = PerspectiveTexture::<_, Repeat, 5>::new(tex).unwrap();
        let w = 240u16;
        let (mut ca, mut cb) = (vec![0u8; w as usize], vec![0u8; w as usize]);
        let len = len.min(w as u32 - x as u32);
        {
            let mut fa = Framebuffer::new(&mut ca, w, 1, w as usize).unwrap();
            let mut fb = Unfused(Framebuffer::new(&mut cb, w, 1, w as usize).unwrap());
            sh8.shade_run(&mut fa, 0, x, len, start, step);
            sh8.shade_run(&mut fb, 0, x, len, start, step);
            prop_assert_eq!(&ca, &cb);
            let mut fa = Framebuffer::new(&mut ca, w, 1, w as usize).unwrap();
            let mut fb = Unfused(Framebuffer::new(&mut cb, w, 1, w as usize).unwrap());
            sh5.shade_run(&mut fa, 0, x, len, start, step);
            sh5.shade_run(&mut fb, 0, x, len, start, step);
        }
        prop_assert_eq!(ca, cb);
    }
}

proptest! {
    /// The triangle-only entry draws what `fill_polygon` draws for a
    /// triangle within ±2^14 (28.4) and rejects any other before writing
    /// a pixel (its documented bound, not the code's constant).
    #[test]
    fn small_triangle_fill_is_fill_polygon(
        wide in proptest::collection::vec((-(1i32 << 14) - 40..(1 << 14) + 40, -(1i32 << 14) - 40..(1 << 14) + 40), 3),
        near in proptest::collection::vec((-100i32..700, -100i32..700), 3),
        pick_near in any::<bool>(),
    ) {
        let pts = if pick_near { &near } else { &wide };
        let tri: [ScreenVertex<0>; 3] =
            core::array::from_fn(|k| ScreenVertex::new(pts[k].0, pts[k].1, 0, []));
        let (mut want_t, mut got_t) = (MockTarget::new(32, 32), MockTarget::new(32, 32));
        let want = fill_polygon(&mut want_t, &mut NoDepth, &Flat('#'), &tri);
        let got = fill_small_triangle(&mut got_t, &mut NoDepth, &Flat('#'), &tri);
        let bound = 1u32 << 14;
        if tri.iter().all(|v| v.x.unsigned_abs() <= bound && v.y.unsigned_abs() <= bound) {
            prop_assert_eq!(got, want);
            prop_assert_eq!(&got_t.px, &want_t.px);
        } else {
            prop_assert_eq!(got, FillOutcome::Rejected);
            prop_assert!(got_t.px.iter().all(|&c| c == '.'));
        }
    }
}

/// `fill_small_triangle`'s bound, at the bound: a vertex at 2^14 (28.4)
/// is drawn as `fill_polygon` draws it, one unit beyond is rejected.
#[test]
fn small_triangle_bound_is_inclusive() {
    let limit = 1 << 14;
    let v = |x: i32, y: i32| ScreenVertex::<0>::new(x, y, 0, []);
    for (reach, inside) in [
        (limit, true),
        (limit + 1, false),
        (-limit, true),
        (-limit - 1, false),
    ] {
        for tri in [
            [v(0, 0), v(reach, 0), v(0, 32 * 16)],
            [v(0, 0), v(0, reach), v(32 * 16, 0)],
        ] {
            let (mut want_t, mut got_t) = (MockTarget::new(32, 32), MockTarget::new(32, 32));
            let want = fill_polygon(&mut want_t, &mut NoDepth, &Flat('#'), &tri);
            let got = fill_small_triangle(&mut got_t, &mut NoDepth, &Flat('#'), &tri);
            if inside {
                assert_eq!((got, &got_t.px), (want, &want_t.px), "{reach}");
            } else {
                assert_eq!(got, FillOutcome::Rejected, "{reach}");
                assert!(got_t.px.iter().all(|&c| c == '.'));
            }
        }
    }
}

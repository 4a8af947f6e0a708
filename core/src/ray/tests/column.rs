//! The column caster: an ASCII-art frame derived by hand, perpendicular
//! distances against an f64 brute-force oracle, no fisheye, strips equal
//! to the whole frame, bad input, and a property test that every pixel of
//! the target is written exactly once and nothing outside it.

use super::{Rng, per_scalar};
use crate::math::Vec2;
use crate::ray::column::{
    Column, ColumnCamera, ColumnError, ColumnStyle, GridMap, Side, cast_columns, draw_columns,
    render_columns,
};
use crate::scalar::Scalar;
use crate::scene::builtin::COLUMN_MAP;
use crate::target::{Band, Framebuffer, Rect, Target};
use crate::texture::Texture;

extern crate std;
use std::string::String;
use std::vec;
use std::vec::Vec;

/// x-side walls: texels `A B` over `C D`; y-side walls the lower case.
const X_TEX: [u8; 4] = *b"ABCD";
const Y_TEX: [u8; 4] = *b"abcd";

fn style() -> ColumnStyle<'static, u8> {
    ColumnStyle {
        x_side: Texture::new(&X_TEX, 2, 2, 2).unwrap(),
        y_side: Texture::new(&Y_TEX, 2, 2, 2).unwrap(),
        ceiling: b' ',
        floor: b'.',
    }
}

const ROOM: GridMap<'static> = GridMap {
    width: 5,
    height: 5,
    cells: b"#####\
             #...#\
             #...#\
             #...#\
             #####",
    start: [1.5, 2.5],
    heading: 0.0,
};

fn render<S: Scalar>(map: &GridMap<'_>, cam: &ColumnCamera<S>) -> Vec<u8> {
    let (w, h) = (cam.width, cam.height);
    let mut px = vec![b'?'; w as usize * h as usize];
    let mut cols = vec![Column::EMPTY; w as usize];
    let mut fb = Framebuffer::new(&mut px, w, h, w as usize).unwrap();
    render_columns(map, cam, &style(), &mut cols, &mut fb).unwrap();
    px
}

fn art(px: &[u8], w: usize) -> String {
    px.chunks(w)
        .map(|r| std::format!("{}//\n", String::from_utf8_lossy(r)))
        .collect()
}

/// Camera at (1.5, 2.5) facing +x in a 3×3 room, 16×12 screen, f = 8
/// (90°). Column i looks along (1, s), s = (2i − 15)/16. Derivation:
/// - |s| > 0.6 (columns 0–2, 13–15) meet the row-0/row-4 walls first, a
///   y side, at t = 1.5/|s| = 1.6, 1.846, 2.182; the others the x = 4
///   wall, an x side, at t = 2.5 for all of them (no fisheye).
/// - Half heights f/(2t) = 2.5, 2.167, 1.833, 1.6 around c_y = 6: rows
///   whose centers lie in [6 − h, 6 + h) are wall: rows 3–7 for columns 0
///   and 15 (the top 3.5 is included), rows 4–7 for the others.
/// - u: the fraction along the face (y on the x = 4 wall; x on the row-0
///   wall; 1 − x on the row-4 wall, seen from its front), ×2 texels:
///   e.g. column 5 meets x = 4 at y = 2.5 − 2.5·0.3125 = 1.72 → u = 1.
/// - v: (row center − top)/(bottom − top), ×2 texels: the top two wall
///   rows of every column use texture row 0, the bottom two row 1.
fn ascii_frame<S: Scalar>() {
    let cam = ColumnCamera::<S>::at_start(&ROOM, S::from_i32(8), 16, 12).unwrap();
    let expected = "                //
                //
                //
a              b//
aabAABAABBABBabb//
aabAABAABBABBabb//
ccdCCDCCDDCDDcdd//
ccdCCDCCDDCDDcdd//
................//
................//
................//
................//
";
    assert_eq!(art(&render(&ROOM, &cam), 16), expected, "{}", S::NAME);
    // The records behind it.
    let mut cols = vec![Column::EMPTY; 16];
    cast_columns(&ROOM, &cam, &mut cols).unwrap();
    for (i, c) in cols.iter().enumerate() {
        let hit = c.hit.unwrap();
        let x_side = (3..=12).contains(&i);
        assert_eq!(hit.side == Side::X, x_side, "column {i}");
        // x side: the x = 4 wall; y side: x = 3 on the row-0 (left
        // columns) or row-4 (right columns) wall.
        let cell = if x_side { 4 } else { 3 };
        let row = if x_side {
            hit.cell[1]
        } else if i < 8 {
            0
        } else {
            4
        };
        assert_eq!(hit.cell, [cell, row], "column {i}");
    }
}

/// The f64 oracle: the least t > 0 at which the ray from `p` along `d`
/// crosses a grid line into a wall cell, over all grid lines (no DDA).
/// Also returns whether the hit is ambiguous: another wall crossing lies
/// within `margin` of it (a ray through a corner).
fn oracle(map: &GridMap<'_>, p: [f64; 2], d: [f64; 2], margin: f64) -> Option<(f64, bool)> {
    let mut hits: Vec<f64> = Vec::new();
    for axis in 0..2 {
        if d[axis] == 0.0 {
            continue;
        }
        let n = if axis == 0 { map.width } else { map.height } as i32;
        for k in 0..=n {
            let t = (k as f64 - p[axis]) / d[axis];
            if t <= 0.0 {
                continue;
            }
            let o = 1 - axis;
            let other = p[o] + t * d[o];
            // The cell entered: k on a positive step, k − 1 on a negative.
            let c = if d[axis] > 0.0 { k } else { k - 1 };
            let oc = other.floor() as i32;
            let (x, y) = if axis == 0 { (c, oc) } else { (oc, c) };
            if map.is_wall(x, y) == Some(true) {
                hits.push(t);
            }
        }
    }
    hits.sort_by(f64::total_cmp);
    let &t = hits.first()?;
    // Ambiguous when another candidate is close, or the hit point is
    // close to a grid corner.
    let q = [p[0] + t * d[0], p[1] + t * d[1]];
    let near_corner = q.iter().all(|v| (v - v.round()).abs() < margin);
    Some((
        t,
        near_corner || hits.get(1).is_some_and(|&u| u - t < margin),
    ))
}

/// Perpendicular distance of every column against the f64 oracle, from
/// random free positions and headings in the built-in maze.
///
/// Error budget (derived, then checked): the caster's t is
/// `gap·δ + k·δ` with δ = 1/|d_axis| and k ≤ 28 grid lines crossed. For
/// floats each of the ≤ 30 roundings adds ≤ ½ ulp(t), and the direction
/// itself carries a relative error of a few ε, which moves t by t·ε·(1 + δ):
/// |Δt| ≤ 64·ε·t·(1 + δ). For fixed point δ is rounded once (≤ 1 step,
/// 2⁻¹⁶, times δ² for the rounding of d) and then added k times exactly,
/// so |Δt| ≤ (k + 2)·(1 + δ²)·2⁻¹⁶ + the direction's error as above.
fn perpendicular_distance_vs_f64<S: Scalar>() {
    let map = &COLUMN_MAP;
    let mut rng = Rng::new(41);
    let (w, h) = (64u16, 48u16);
    let f = 40.0;
    let mut cols = vec![Column::EMPTY; w as usize];
    let (mut checked, mut skipped) = (0u32, 0u32);
    let mut worst = 0.0f64;
    while checked < 5000 {
        let p = [rng.range(0.0, 16.0), rng.range(0.0, 12.0)];
        if map.is_wall(p[0] as i32, p[1] as i32) != Some(false) {
            continue;
        }
        let heading = rng.range(-3.2, 3.2);
        let cam = ColumnCamera::<S>::new(
            Vec2::new(S::from_f64(p[0]), S::from_f64(p[1])),
            S::from_f64(heading),
            S::from_f64(f),
            w,
            h,
        )
        .unwrap();
        cast_columns(map, &cam, &mut cols).unwrap();
        // The reference sees the camera the scalar actually holds.
        let pos = [cam.position.x.to_f64(), cam.position.y.to_f64()];
        let (s, c) = heading.sin_cos();
        for (i, col) in cols.iter().enumerate() {
            let k = (i as f64 + 0.5 - w as f64 / 2.0) / f;
            let d = [c - s * k, s + c * k];
            let Some((t_ref, ambiguous)) = oracle(map, pos, d, 1e-3) else {
                panic!("the maze is enclosed, column {i} must hit");
            };
            if ambiguous {
                skipped += 1;
                continue;
            }
            let t = col.hit.expect("enclosed map").distance.to_f64();
            let delta = 1.0 / d[0].abs().min(d[1].abs()).max(1e-9);
            let eps = S::EPSILON.to_f64();
            let tol = if S::IS_FLOAT {
                64.0 * eps * t_ref * (1.0 + delta)
            } else {
                30.0 * (1.0 + delta * delta) * eps + 64.0 * eps * t_ref * (1.0 + delta)
            };
            worst = worst.max((t - t_ref).abs() / tol);
            assert!(
                (t - t_ref).abs() <= tol,
                "{}: column {i} t = {t}, f64 {t_ref}, tol {tol}, pos {pos:?} heading {heading}",
                S::NAME
            );
            checked += 1;
        }
    }
    assert!(skipped * 50 < checked, "{skipped} ambiguous of {checked}");
    std::println!(
        "column caster {}: {checked} columns, worst error {:.3} of the tolerance, {skipped} corner rays skipped",
        S::NAME,
        worst
    );
}

/// Facing a long wall head-on from a fractional position: every column
/// that meets it gets the same distance and the same screen extent.
/// With the Euclidean distance (fisheye), the edge columns would be
/// 1/cos(45°) ≈ 1.41× further and visibly shorter.
fn no_fisheye<S: Scalar>() {
    let map = GridMap {
        width: 12,
        height: 4,
        cells: b"############\
                 #..........#\
                 #..........#\
                 ############",
        start: [0.0; 2],
        heading: 0.0,
    };
    // Facing +y (down the rows) at y = 1.3: the row-3 wall is 1.7 ahead.
    let cam = ColumnCamera::<S>::new(
        Vec2::new(S::from_f64(5.7), S::from_f64(1.3)),
        S::from_f64(core::f64::consts::FRAC_PI_2),
        S::from_i32(32),
        64,
        48,
    )
    .unwrap();
    let mut cols = vec![Column::EMPTY; 64];
    cast_columns(&map, &cam, &mut cols).unwrap();
    let center = cols[32];
    let tol = S::EPSILON.to_f64() * 256.0;
    for (i, c) in cols.iter().enumerate() {
        let hit = c.hit.unwrap();
        assert_eq!(hit.side, Side::Y, "column {i}");
        assert_eq!(hit.cell[1], 3, "column {i}");
        assert!(
            (hit.distance.to_f64() - 1.7).abs() <= tol,
            "{} column {i}: {}",
            S::NAME,
            hit.distance.to_f64()
        );
        // Equal extents to within one 24.8 step (the distance's rounding).
        assert!((c.top - center.top).abs() <= 1, "column {i}");
        assert!((c.bottom - center.bottom).abs() <= 1, "column {i}");
    }
    // And the extent is f/(2t) = 32/3.4 rows on each side of the center.
    let half = (center.bottom - center.top) as f64 / 512.0;
    assert!((half - 32.0 / 3.4).abs() < 2.0 / 256.0, "half {half}");
}

/// Bands of 7 rows (not dividing 48) equal the whole frame, bit for bit.
fn strips_equal_whole_frame<S: Scalar>() {
    let (w, h) = (64u16, 48u16);
    for (k, heading) in [0.3, 1.9, -2.4, 3.0].into_iter().enumerate() {
        let pos = [[1.5, 1.5], [5.2, 5.5], [13.5, 9.1], [9.4, 7.6]][k];
        let cam = ColumnCamera::<S>::new(
            Vec2::new(S::from_f64(pos[0]), S::from_f64(pos[1])),
            S::from_f64(heading),
            S::from_i32(40),
            w,
            h,
        )
        .unwrap();
        let whole = render(&COLUMN_MAP, &cam);
        let mut cols = vec![Column::EMPTY; w as usize];
        cast_columns(&COLUMN_MAP, &cam, &mut cols).unwrap();
        let rows = 7u16;
        let mut strip = vec![b'?'; w as usize * rows as usize];
        let mut banded = Vec::new();
        let mut band = Band::new(&mut strip, w, rows, w as usize, 0).unwrap();
        let mut y0 = 0;
        while y0 < h as i32 {
            band.move_to(y0).unwrap();
            draw_columns(&cols, h, &style(), &mut band);
            let n = (h as i32 - y0).min(rows as i32) as usize;
            banded.extend_from_slice(&band.as_slice()[..n * w as usize]);
            y0 += rows as i32;
        }
        assert_eq!(
            art(&banded, w as usize),
            art(&whole, w as usize),
            "{}",
            S::NAME
        );
        // The frame shows both wall orientations, ceiling and floor.
        for set in [&b"ABCD"[..], b"abcd", b" ", b"."] {
            assert!(whole.iter().any(|c| set.contains(c)), "{k}: {set:?}");
        }
    }
}

/// Every documented error, no panic, and a defined (empty) frame.
fn bad_input<S: Scalar>() {
    let s = S::from_f64;
    let cam = |x: f64, y: f64| {
        ColumnCamera::<S>::new(Vec2::new(s(x), s(y)), S::ZERO, s(4.0), 8, 6).unwrap()
    };
    let mut cols = vec![Column::EMPTY; 8];
    let empty_frame = |cols: &[Column<S>]| {
        let mut px = vec![b'?'; 48];
        let mut fb = Framebuffer::new(&mut px, 8, 6, 8).unwrap();
        draw_columns(cols, 6, &style(), &mut fb);
        px
    };
    let expect_empty = {
        let mut e = vec![b' '; 24];
        e.extend_from_slice(&[b'.'; 24]);
        e
    };

    // Map size mismatch, empty map.
    let short = GridMap {
        cells: &ROOM.cells[..24],
        ..ROOM
    };
    assert_eq!(
        cast_columns(&short, &cam(1.5, 2.5), &mut cols),
        Err(ColumnError::MapSize {
            cells: 24,
            expected: 25
        })
    );
    assert_eq!(empty_frame(&cols), expect_empty);
    let empty = GridMap {
        width: 0,
        height: 0,
        cells: &[],
        ..ROOM
    };
    assert_eq!(
        cast_columns(&empty, &cam(1.5, 2.5), &mut cols),
        Err(ColumnError::EmptyMap)
    );
    // Inside a wall; outside the map (both sides).
    cast_columns(&ROOM, &cam(1.5, 2.5), &mut cols).unwrap();
    assert_eq!(
        cast_columns(&ROOM, &cam(0.5, 2.5), &mut cols),
        Err(ColumnError::InsideWall)
    );
    assert_eq!(empty_frame(&cols), expect_empty);
    assert_eq!(
        cast_columns(&ROOM, &cam(-0.5, 2.5), &mut cols),
        Err(ColumnError::OutsideMap)
    );
    assert_eq!(
        cast_columns(&ROOM, &cam(2.5, 5.0), &mut cols),
        Err(ColumnError::OutsideMap)
    );
    // Too few column records.
    assert_eq!(
        cast_columns(&ROOM, &cam(1.5, 2.5), &mut cols[..5]),
        Err(ColumnError::ColumnsTooShort { len: 5, width: 8 })
    );
    // Bad cameras.
    assert_eq!(
        ColumnCamera::<S>::new(Vec2::new(S::ZERO, S::ZERO), S::ZERO, S::ZERO, 8, 6),
        Err(ColumnError::BadCamera)
    );
    assert_eq!(
        ColumnCamera::<S>::new(Vec2::new(S::ONE, S::ONE), S::ZERO, S::ONE, 0, 6),
        Err(ColumnError::BadCamera)
    );
    if S::IS_FLOAT {
        // from_f64 maps NaN to 0; the float sqrt of −1 is NaN.
        let nan = (-S::ONE).sqrt();
        assert!(ColumnCamera::<S>::new(Vec2::new(nan, S::ONE), S::ZERO, S::ONE, 8, 6).is_err());
        assert!(ColumnCamera::<S>::new(Vec2::new(S::ONE, S::ONE), nan, S::ONE, 8, 6).is_err());
        // A hand-built camera with NaN inside is caught by the cast.
        let mut c = cam(1.5, 2.5);
        c.position.x = nan;
        assert_eq!(
            cast_columns(&ROOM, &c, &mut cols),
            Err(ColumnError::BadCamera)
        );
        let mut c = cam(1.5, 2.5);
        c.forward = Vec2::new(nan, nan);
        assert_eq!(
            cast_columns(&ROOM, &c, &mut cols),
            Err(ColumnError::BadCamera)
        );
        assert_eq!(empty_frame(&cols), expect_empty);
    }
    // A map that is not enclosed: rays that leave it meet no wall.
    let open = GridMap {
        width: 3,
        height: 1,
        cells: b"..#",
        ..ROOM
    };
    let c = ColumnCamera::<S>::new(Vec2::new(s(0.5), s(0.5)), S::PI, s(4.0), 8, 6).unwrap();
    cast_columns(&open, &c, &mut cols).unwrap();
    assert!(cols.iter().all(|c| c.hit.is_none()));
    assert_eq!(empty_frame(&cols), expect_empty);
    let c = ColumnCamera::<S>::new(Vec2::new(s(0.5), s(0.5)), S::ZERO, s(4.0), 8, 6).unwrap();
    cast_columns(&open, &c, &mut cols).unwrap();
    assert!(
        cols[3].hit.is_some() && cols[4].hit.is_some(),
        "the wall ahead"
    );
    // Pressed against a wall: huge columns, clamped, no overflow.
    let c = ColumnCamera::<S>::new(Vec2::new(s(3.999), s(2.5)), S::ZERO, s(4.0), 8, 6).unwrap();
    let _ = render(&ROOM, &c);
    // Extreme focus values.
    let c = ColumnCamera::<S>::new(Vec2::new(s(1.5), s(2.5)), s(0.7), S::MAX, 8, 6).unwrap();
    let _ = render(&ROOM, &c);
    let c = ColumnCamera::<S>::new(Vec2::new(s(1.5), s(2.5)), s(0.7), S::EPSILON, 8, 6).unwrap();
    let _ = render(&ROOM, &c);
}

/// A target that records every write and fails on one outside its clip
/// rectangle; pixels written twice are counted.
struct Checked {
    clip: Rect,
    frame_w: i32,
    writes: Vec<u8>,
}

impl Checked {
    fn new(clip: Rect, frame_w: i32, frame_h: i32) -> Self {
        Self {
            clip,
            frame_w,
            writes: vec![0; (frame_w * frame_h) as usize],
        }
    }
    fn mark(&mut self, y: i32, x: i32) {
        assert!(
            self.clip.contains(x, y),
            "write at ({x}, {y}) outside {:?}",
            self.clip
        );
        self.writes[(y * self.frame_w + x) as usize] += 1;
    }
}

impl Target for Checked {
    type Color = u8;
    fn clip_rect(&self) -> Rect {
        self.clip
    }
    fn fill_solid(&mut self, y: i32, x: i32, len: u32, _: u8) {
        for k in 0..len as i32 {
            self.mark(y, x + k);
        }
    }
    fn fill_with<F: FnMut() -> u8>(&mut self, y: i32, x: i32, len: u32, mut colors: F) {
        for k in 0..len as i32 {
            colors();
            self.mark(y, x + k);
        }
    }
}

/// Random maps (enclosed or not, right or wrong size), cameras (including
/// extreme and out-of-map ones), screens and clip rectangles: every pixel
/// of the clip rectangle within the drawn columns is written exactly once,
/// nothing outside it is, and real framebuffers and bands never panic.
fn no_write_out_of_bounds<S: Scalar>() {
    let mut rng = Rng::new(77);
    let mut cells = Vec::new();
    for case in 0..400 {
        let (mw, mh) = (rng.int(0, 9) as u16, rng.int(0, 9) as u16);
        cells.clear();
        let n = mw as usize * mh as usize;
        let len = if case % 10 == 0 {
            rng.int(0, n as i64 + 2) as usize
        } else {
            n
        };
        for _ in 0..len {
            cells.push(if rng.unit() < 0.3 { b'#' } else { b'.' });
        }
        let map = GridMap {
            width: mw,
            height: mh,
            cells: &cells,
            start: [0.0; 2],
            heading: 0.0,
        };
        let (w, h) = (rng.int(1, 40) as u16, rng.int(1, 40) as u16);
        let pick = |rng: &mut Rng| match rng.int(0, 5) {
            0 => S::MAX,
            1 => S::MIN,
            2 => S::from_f64(rng.range(-2.0, 2.0)),
            _ => S::from_f64(rng.range(0.0, 9.0)),
        };
        let pos = Vec2::new(pick(&mut rng), pick(&mut rng));
        let focus = if rng.unit() < 0.2 {
            S::MAX
        } else {
            S::from_f64(rng.range(0.01, 100.0))
        };
        let Ok(cam) = ColumnCamera::<S>::new(pos, S::from_f64(rng.range(-7.0, 7.0)), focus, w, h)
        else {
            continue;
        };
        let ncols = rng.int(0, w as i64 + 3) as usize;
        let mut cols = vec![Column::EMPTY; ncols];
        let _ = cast_columns(&map, &cam, &mut cols);
        // A clip rectangle partly outside the frame, as a band may be.
        let clip = Rect::new(
            rng.int(-3, w as i64) as i32,
            rng.int(-3, h as i64) as i32,
            rng.int(0, w as i64 + 3) as i32,
            rng.int(0, h as i64 + 3) as i32,
        );
        let fw = w as i32 + 6;
        let mut t = Checked::new(
            clip.intersect(&Rect::new(0, 0, fw, h as i32 + 6)),
            fw,
            h as i32 + 6,
        );
        draw_columns(&cols, h, &style(), &mut t);
        for y in 0..h as i32 + 6 {
            for x in 0..fw {
                let expect = u8::from(t.clip.contains(x, y) && (x as usize) < ncols);
                assert_eq!(
                    t.writes[(y * fw + x) as usize],
                    expect,
                    "case {case} ({x}, {y})"
                );
            }
        }
        // Real targets: a framebuffer with stride padding and a band.
        let mut px = vec![b'?'; (w as usize + 2) * h as usize];
        let mut fb = Framebuffer::new(&mut px, w, h, w as usize + 2).unwrap();
        let _ = render_columns(&map, &cam, &style(), &mut cols, &mut fb);
        for row in px.chunks(w as usize + 2) {
            assert_eq!(&row[w as usize..], b"??", "padding untouched");
        }
        let mut strip = vec![b'?'; w as usize * 3];
        let y0 = rng.int(-5, h as i64 + 2) as i32;
        let mut band = Band::new(&mut strip, w, 3, w as usize, y0).unwrap();
        draw_columns(&cols, h, &style(), &mut band);
    }
}

per_scalar!(
    ascii_frame,
    perpendicular_distance_vs_f64,
    no_fisheye,
    strips_equal_whole_frame,
    bad_input,
    no_write_out_of_bounds,
);

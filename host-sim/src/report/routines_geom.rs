//! Point transform, projection, the solver and the general camera.

use super::mcu::{self, McuCell, NO_KERNEL};
use super::mixed::{MixedAffine, from_q16, q16};
use super::{ErrStats, Pending, Rng, Row, Size, Table, Timing, cases, finish};
use sightline::camera::{Camera, Projection};
use sightline::math::{Affine3, Vec3};
use sightline::scalar::{I16F16, I20F12, Scalar};
use sightline::solve::solve;
use sightline::transform::{Euler, Pose};

/// Runs `$f::<S>(args)` for f64, f32, I16F16 and I20F12, collecting rows.
macro_rules! per_scalar {
    ($f:ident ( $($a:expr),* )) => {
        vec![
            $f::<f64>($($a),*),
            $f::<f32>($($a),*),
            $f::<sightline::scalar::I16F16>($($a),*),
            $f::<sightline::scalar::I20F12>($($a),*),
        ]
    };
}
pub(super) use per_scalar;

pub(super) fn v3<S: Scalar>(v: Vec3<f64>) -> Vec3<S> {
    v.cast()
}

pub(super) fn dist(a: Vec3<f64>, b: Vec3<f64>) -> f64 {
    (a - b).length()
}

pub(super) fn rand_vec(rng: &mut Rng, r: f64) -> Vec3<f64> {
    Vec3::new(rng.range(-r, r), rng.range(-r, r), rng.range(-r, r))
}

/// The text of a fraction as a count, e.g. "3/256 rejected".
pub(super) fn count_note(n: usize, of: usize, what: &str) -> String {
    if n == 0 {
        String::new()
    } else {
        format!("{n}/{of} {what}")
    }
}

pub(super) fn find<'a>(rows: &'a [Row], repr: &str) -> Option<&'a Row> {
    rows.iter().find(|r| r.repr == repr)
}

/// The row of representation `S` whose note counts the `rejected` of
/// `of` inputs as `what` (no note when none was).
pub(super) fn scalar_row<S: Scalar>(
    errs: &[f64],
    mcu: McuCell,
    rejected: usize,
    of: usize,
    what: &str,
) -> Row {
    Row::new(S::NAME, errs, mcu, count_note(rejected, of, what))
}

fn err_of(rows: &[Row], repr: &str, pick: fn(ErrStats) -> f64) -> f64 {
    find(rows, repr).and_then(|r| r.err).map_or(f64::NAN, pick)
}

/// The maximum error of the row `repr` (NaN without one).
pub(super) fn max_err(rows: &[Row], repr: &str) -> f64 {
    err_of(rows, repr, |e| e.max)
}

/// The mean error of the row `repr` (NaN without one).
pub(super) fn mean_err(rows: &[Row], repr: &str) -> f64 {
    err_of(rows, repr, |e| e.mean)
}

pub(super) fn ns(rows: &[Row], repr: &str) -> f64 {
    find(rows, repr).map_or(f64::NAN, |r| r.time.median)
}

/// `x` with 3 significant digits, for recommendation text.
pub(super) fn g(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if !(1e-3..1e4).contains(&x.abs()) {
        format!("{x:.2e}")
    } else if x.abs() >= 100.0 {
        format!("{x:.0}")
    } else {
        let s = if x.abs() >= 10.0 {
            format!("{x:.1}")
        } else {
            format!("{x:.3}")
        };
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    }
}

// ---------------------------------------------------------------- transform

struct TransformCase {
    mats: Vec<Affine3<f64>>,
    /// (matrix index, object-space point).
    pts: Vec<(usize, Vec3<f64>)>,
}

const FOCUS: f64 = 120.0;
const VIEW: u16 = 240;

fn transform_case(size: Size) -> TransformCase {
    let mut rng = Rng::new(1);
    let n_mats = (size.samples / 64).max(2);
    let mats = (0..n_mats)
        .map(|_| {
            let ang = |r: &mut Rng| {
                Euler::new(r.range(-3.1, 3.1), r.range(-1.5, 1.5), r.range(-3.1, 3.1))
            };
            let cam = Camera::from_angles(rand_vec(&mut rng, 50.0), ang(&mut rng));
            let pose = Pose::new(rand_vec(&mut rng, 50.0), ang(&mut rng));
            cam.object_to_view(&pose)
        })
        .collect();
    let pts = (0..size.samples)
        .map(|i| (i % n_mats, rand_vec(&mut rng, 10.0)))
        .collect();
    TransformCase { mats, pts }
}

fn transform_row<S: Scalar>(size: Size, c: &TransformCase) -> Pending<'static> {
    let mats: Vec<Affine3<S>> = c.mats.iter().map(|m| m.cast()).collect();
    let pts: Vec<(usize, Vec3<S>)> = c.pts.iter().map(|&(i, p)| (i, v3(p))).collect();
    let errs: Vec<f64> = c
        .pts
        .iter()
        .zip(&pts)
        .map(|(&(i, p), &(_, ps))| {
            dist(
                mats[i].transform_point3(ps).cast(),
                c.mats[i].transform_point3(p),
            )
        })
        .collect();
    let mcu = mcu::lookup("transform_point3", S::NAME);
    Row::new(S::NAME, &errs, mcu, "").timed(size, pts, move |&(i, p)| mats[i].transform_point3(p))
}

fn transform_mixed_row(size: Size, c: &TransformCase) -> Pending<'static> {
    let mats: Vec<MixedAffine> = c
        .mats
        .iter()
        .map(|m| {
            let t = m.translation;
            MixedAffine::from_f64(m.matrix.m, [t.x, t.y, t.z])
        })
        .collect();
    let pts: Vec<(usize, [i32; 3])> = c
        .pts
        .iter()
        .map(|&(i, p)| (i, [q16(p.x), q16(p.y), q16(p.z)]))
        .collect();
    let errs: Vec<f64> = c
        .pts
        .iter()
        .zip(&pts)
        .map(|(&(i, p), &(_, pq))| {
            let r = mats[i].transform(pq);
            let got = Vec3::new(from_q16(r[0]), from_q16(r[1]), from_q16(r[2]));
            dist(got, c.mats[i].transform_point3(p))
        })
        .collect();
    let note = "report-local kernel, i64 accumulation";
    Row::new("Q2.30×Q16.16", &errs, NO_KERNEL, note)
        .timed(size, pts, move |&(i, p)| mats[i].transform(p))
}

/// Object→view point transform (`Affine3::transform_point3`).
pub fn transform(size: Size) -> Table {
    let c = transform_case(size);
    let mut pending = per_scalar!(transform_row(size, &c));
    pending.push(transform_mixed_row(size, &c));
    let rows = finish(size, pending);
    let px = |repr: &str| max_err(&rows, repr) * FOCUS;
    // Depth from which the error is below the rasterizer's 1/16 px step.
    let z16 = |repr: &str| px(repr) * 16.0;
    let depth_text = |repr: &str| {
        if z16(repr) <= 1.0 {
            "at every depth z ≥ 1".to_owned()
        } else {
            format!("from z ≈ {} on", g(z16(repr)))
        }
    };
    let recommendation = format!(
        "A view-space error e moves a vertex by at most 120·e/z px in a 240×240 view with \
         focus 120 px. I16F16 transforms stay within {} units, i.e. {} px at z = 1 and below \
         the rasterizer's 1/16 px sub-pixel step {}; that costs {} instructions/vertex on \
         Cortex-M0 class cores (thumbv6m), where soft-float f32 costs {} ({}× more). On a \
         Cortex-M4F, f32 is both the more accurate (error {}) and the cheaper ({} against {} \
         instructions for I16F16). The mixed Q2.30×Q16.16 scheme cuts the I16F16 error \
         {}× (to {} units), because the rotation coefficients keep 30 fraction bits, and on \
         the host it runs at {} ns against {} ns for I16F16; it has no Cortex-M figure yet. I20F12 trades precision for \
         range (error {} units, {} px at z = 1) and only pays off for scenes beyond I16F16's \
         ±32768. Host times (f32 {} ns, I16F16 {} ns) reflect the host's FPU and say nothing \
         about a Cortex-M0.",
        g(max_err(&rows, "I16F16")),
        g(px("I16F16")),
        depth_text("I16F16"),
        mcu_v6m(&rows, "I16F16"),
        mcu_v6m(&rows, "f32"),
        g(mcu_ratio(&rows, "f32", "I16F16")),
        g(max_err(&rows, "f32")),
        mcu_v7em(&rows, "f32"),
        mcu_v7em(&rows, "I16F16"),
        g(max_err(&rows, "I16F16") / max_err(&rows, "Q2.30×Q16.16")),
        g(max_err(&rows, "Q2.30×Q16.16")),
        g(ns(&rows, "Q2.30×Q16.16")),
        g(ns(&rows, "I16F16")),
        g(max_err(&rows, "I20F12")),
        g(px("I20F12")),
        g(ns(&rows, "f32")),
        g(ns(&rows, "I16F16")),
    );
    Table {
        id: "transform",
        title: "Point transform (object→view)",
        op: "one `Affine3::transform_point3`",
        unit: "view-space units (Euclidean distance)",
        unit_short: "view units",
        setup: format!(
            "{} object→view matrices (random camera and pose angles, positions within ±50) \
             composed in f64 and rounded once into each representation; {} object points \
             within ±10 (view coordinates up to about ±150). Reference: the f64 transform.",
            c.mats.len(),
            c.pts.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

fn mcu_ratio(rows: &[Row], a: &str, b: &str) -> f64 {
    match (find(rows, a).map(|r| &r.mcu), find(rows, b).map(|r| &r.mcu)) {
        (Some(McuCell::Measured { v6m: x, .. }), Some(McuCell::Measured { v6m: y, .. })) => x / y,
        _ => f64::NAN,
    }
}

pub(super) fn mcu_v6m(rows: &[Row], repr: &str) -> String {
    match find(rows, repr).map(|r| &r.mcu) {
        Some(McuCell::Measured { v6m, .. }) => format!("{v6m:.0}"),
        _ => "(not measured)".into(),
    }
}

pub(super) fn mcu_v7em(rows: &[Row], repr: &str) -> String {
    match find(rows, repr).map(|r| &r.mcu) {
        Some(McuCell::Measured { v7em, .. }) => format!("{v7em:.0}"),
        _ => "(not measured)".into(),
    }
}

// --------------------------------------------------------------- projection

fn projection_points(size: Size) -> Vec<Vec3<f64>> {
    cases(size, 2, |rng| {
        let z = rng.log_range(1.0, 100.0);
        let sx = rng.range(0.0, f64::from(VIEW)) - f64::from(VIEW) / 2.0;
        let sy = rng.range(0.0, f64::from(VIEW)) - f64::from(VIEW) / 2.0;
        Vec3::new(sx * z / FOCUS, sy * z / FOCUS, z)
    })
}

fn projection_row<S: Scalar>(size: Size, pts: &[Vec3<f64>]) -> Pending<'static> {
    let proj = Projection::<S>::perspective(S::from_f64(FOCUS), VIEW, VIEW);
    let reference = Projection::<f64>::perspective(FOCUS, VIEW, VIEW);
    let ps: Vec<Vec3<S>> = pts.iter().map(|&p| v3(p)).collect();
    let mut failed = 0;
    let mut errs = Vec::new();
    for (&p, &q) in pts.iter().zip(&ps) {
        let (r, _) = reference.project(p).expect("reference points are in front");
        match proj.project(q) {
            Some((s, _)) => errs.push((s.cast::<f64>() - r).length()),
            None => failed += 1,
        }
    }
    scalar_row::<S>(&errs, NO_KERNEL, failed, pts.len(), "not projected").timed(
        size,
        ps,
        move |&p| proj.project(p),
    )
}

/// Perspective projection to pixels (`Projection::project`).
pub fn projection(size: Size) -> Table {
    let pts = projection_points(size);
    let rows = finish(size, per_scalar!(projection_row(size, &pts)));
    let recommendation = format!(
        "Projection divides by z, so fixed point loses relative precision for near, \
         off-center points: I16F16 is within {} px of f64 (mean {} px), I20F12 within {} px, \
         f32 within {} px. All four are below the rasterizer's 1/16 px sub-pixel step \
         ({}), so for a 240×240 display the projection does not decide the scalar; the \
         transform and camera set-up before it do.",
        g(max_err(&rows, "I16F16")),
        g(mean_err(&rows, "I16F16")),
        g(max_err(&rows, "I20F12")),
        g(max_err(&rows, "f32")),
        if rows
            .iter()
            .all(|r| r.err.is_some_and(|e| e.max < 1.0 / 16.0))
        {
            "true for every row here"
        } else {
            "not true for every row here: see the table"
        },
    );
    Table {
        id: "projection",
        title: "Perspective projection (view → pixels)",
        op: "one `Projection::project`",
        unit: "pixels (Euclidean distance on screen)",
        unit_short: "px",
        setup: format!(
            "{} view-space points spread uniformly over a 240×240 viewport (focus 120 px, 90° \
             field of view) at depths log-uniform in [1, 100]. Reference: f64 projection of the \
             same f64 points.",
            pts.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

// ------------------------------------------------------------------- solver

/// A random orthogonal matrix (Gram–Schmidt on random rows).
pub(super) fn orthogonal<const N: usize>(rng: &mut Rng) -> [[f64; N]; N] {
    let mut q = [[0.0; N]; N];
    for i in 0..N {
        loop {
            let mut r = [0.0; N];
            for x in &mut r {
                *x = rng.range(-1.0, 1.0);
            }
            for qj in q.iter().take(i) {
                let d: f64 = r.iter().zip(qj).map(|(a, b)| a * b).sum();
                for (x, y) in r.iter_mut().zip(qj) {
                    *x -= d * y;
                }
            }
            let n = r.iter().map(|x| x * x).sum::<f64>().sqrt();
            if n > 0.1 {
                q[i] = r.map(|x| x / n);
                break;
            }
        }
    }
    q
}

struct System<const N: usize> {
    a: [[f64; N]; N],
    b: [[f64; 1]; N],
}

fn systems<const N: usize>(rng: &mut Rng, kappa: f64, count: usize) -> Vec<System<N>> {
    (0..count)
        .map(|_| {
            let (q1, q2) = (orthogonal::<N>(rng), orthogonal::<N>(rng));
            let sigma: [f64; N] =
                core::array::from_fn(|i| kappa.powf(-(i as f64) / (N as f64 - 1.0)));
            let mut a = [[0.0; N]; N];
            for (i, row) in a.iter_mut().enumerate() {
                for (j, x) in row.iter_mut().enumerate() {
                    *x = (0..N).map(|k| q1[i][k] * sigma[k] * q2[j][k]).sum();
                }
            }
            let x: [f64; N] = core::array::from_fn(|_| rng.range(-1.0, 1.0));
            let b = core::array::from_fn(|i| [(0..N).map(|j| a[i][j] * x[j]).sum()]);
            System { a, b }
        })
        .collect()
}

fn solver_row<S: Scalar, const N: usize>(
    size: Size,
    kappa: f64,
    sys: &[System<N>],
) -> Pending<'static> {
    let cast = |s: &System<N>| {
        (
            s.a.map(|r| r.map(S::from_f64)),
            s.b.map(|r| r.map(S::from_f64)),
        )
    };
    let inputs: Vec<_> = sys.iter().map(cast).collect();
    let mut errs = Vec::new();
    let mut rejected = 0;
    let mut why = String::new();
    for (s, (a, b)) in sys.iter().zip(&inputs) {
        let Ok(r) = solve(&s.a, &s.b) else {
            continue; // the f64 reference rejected it too: not counted
        };
        match solve(a, b) {
            Ok(x) => {
                let norm = r.x.iter().fold(0.0f64, |m, v| m.max(v[0].abs()));
                let e =
                    r.x.iter()
                        .zip(&x.x)
                        .fold(0.0f64, |m, (u, v)| m.max((u[0] - v[0].to_f64()).abs()));
                errs.push(e / norm);
            }
            Err(e) => {
                rejected += 1;
                if why.is_empty() {
                    why = format!("{e:?}");
                    why.truncate(why.find(['{', '(']).unwrap_or(why.len()));
                }
            }
        }
    }
    let mut note = count_note(rejected, sys.len(), "rejected");
    if !why.is_empty() {
        note.push_str(&format!(" ({})", why.trim()));
    }
    let row = Row {
        repr: format!("{}, κ≈{kappa:.0e}", S::NAME),
        err: ErrStats::of(&errs),
        time: Timing::PENDING,
        mcu: if N == 3 {
            mcu::lookup("solve3x3", S::NAME)
        } else {
            NO_KERNEL
        },
        note,
    };
    row.timed(size, inputs, |(a, b)| solve(a, b).is_ok())
}

const KAPPAS: [f64; 3] = [1e1, 1e3, 1e5];

/// Gaussian elimination with partial pivoting, N×N, one right-hand side,
/// by condition number.
pub fn solver<const N: usize>(size: Size) -> Table {
    let mut rng = Rng::new(3 + N as u64);
    let count = (size.samples / 16).max(8);
    let mut pending = Vec::new();
    for kappa in KAPPAS {
        let sys = systems::<N>(&mut rng, kappa, count);
        pending.push(solver_row::<f64, N>(size, kappa, &sys));
        pending.push(solver_row::<f32, N>(size, kappa, &sys));
        pending.push(solver_row::<I16F16, N>(size, kappa, &sys));
        pending.push(solver_row::<I20F12, N>(size, kappa, &sys));
    }
    let rows = finish(size, pending);
    let e = |s: &str, k: f64| max_err(&rows, &format!("{s}, κ≈{k:.0e}"));
    let note = |s: &str, k: f64| {
        find(&rows, &format!("{s}, κ≈{k:.0e}"))
            .map(|r| {
                if r.note.is_empty() {
                    "none rejected".to_owned()
                } else {
                    r.note.clone()
                }
            })
            .unwrap_or_default()
    };
    let recommendation = format!(
        "The relative error grows roughly in proportion to κ·ε, as backward-stable elimination predicts: \
         f32 reaches {} at κ≈1e1, {} at κ≈1e3 and {} at κ≈1e5; I16F16 {} / {} / {} \
         (κ≈1e5: {}). With the default threshold (rcond ≥ ε) the solver rejects most systems \
         a representation cannot solve, but the ones it accepts near the threshold carry \
         errors up to κ·ε ≈ 1 (the I16F16 κ≈1e5 maximum above): callers that need accuracy \
         from fixed point should pass `SolveConfig {{ rcond_min: ε.sqrt() }}`, as the camera \
         and texture set-up do. For the well-conditioned systems of camera and \
         texture setup (κ ≲ 1e2), I16F16 is accurate to about {} relative; for anything \
         worse use f32 (or f64 on the host). {}",
        g(e("f32", 1e1)),
        g(e("f32", 1e3)),
        g(e("f32", 1e5)),
        g(e("I16F16", 1e1)),
        g(e("I16F16", 1e3)),
        g(e("I16F16", 1e5)),
        note("I16F16", 1e5),
        g(e("I16F16", 1e1)),
        if N == 3 {
            format!(
                "On Cortex-M0 the 3×3 solve (kernel `solve3x3`, 3 right-hand sides) costs {} \
                 instructions in I16F16 against {} in soft f32; on Cortex-M4F f32 costs {}.",
                mcu_v6m(&rows, "I16F16, κ≈1e1"),
                mcu_v6m(&rows, "f32, κ≈1e1"),
                mcu_v7em(&rows, "f32, κ≈1e1"),
            )
        } else {
            String::new()
        }
    );
    Table {
        id: if N == 3 { "solver3" } else { "solver4" },
        title: if N == 3 {
            "Solver, 3×3 systems by condition number"
        } else {
            "Solver, 4×4 systems by condition number"
        },
        op: "one `solve::solve` (factor, condition estimate, one right-hand side)",
        unit: "relative forward error ‖x − x_f64‖∞ / ‖x_f64‖∞",
        unit_short: "relative",
        setup: format!(
            "For each κ, {count} systems A = Q₁·diag(σ)·Q₂ᵀ with random orthogonal Q₁, Q₂ and \
             singular values from 1 down to 1/κ (geometric), x uniform in [−1, 1], b = A·x in \
             f64; rounded into each representation. Reference: the f64 solution. The Cortex-M \
             figure is the harness's `solve3x3` kernel (a well-conditioned 3×3 system with \
             three right-hand sides), the same code path."
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

// ------------------------------------------------------------------- camera

struct CameraCase {
    pos: Vec3<f64>,
    u: Vec3<f64>,
    v: Vec3<f64>,
    w: Vec3<f64>,
    pts: [Vec3<f64>; 8],
}

fn camera_cases(size: Size) -> Vec<CameraCase> {
    let mut rng = Rng::new(5);
    (0..(size.samples / 8).max(8))
        .map(|_| {
            let q = orthogonal::<3>(&mut rng);
            let mut axis = |i: usize| {
                let s = rng.range(0.5, 2.0);
                Vec3::new(q[i][0], q[i][1], q[i][2]) * s + rand_vec(&mut rng, 0.3)
            };
            let (u, v, w) = (axis(0), axis(1), axis(2));
            let pos = rand_vec(&mut rng, 50.0);
            let pts = core::array::from_fn(|_| rand_vec(&mut rng, 100.0));
            CameraCase { pos, u, v, w, pts }
        })
        .collect()
}

fn camera_row<S: Scalar>(size: Size, cases: &[CameraCase]) -> Pending<'static> {
    type In<S> = (Vec3<S>, Vec3<S>, Vec3<S>, Vec3<S>);
    let inputs: Vec<In<S>> = cases
        .iter()
        .map(|c| (v3(c.pos), v3(c.u), v3(c.v), v3(c.w)))
        .collect();
    let mut errs = Vec::new();
    let mut rejected = 0;
    for (c, &(p, u, v, w)) in cases.iter().zip(&inputs) {
        let (r, _) = Camera::from_vectors(c.pos, c.u, c.v, c.w).expect("f64 camera");
        match Camera::from_vectors(p, u, v, w) {
            Ok((cam, _)) => {
                for &x in &c.pts {
                    let got: Vec3<f64> = cam.world_to_view().transform_point3(v3(x)).cast();
                    errs.push(dist(got, r.world_to_view().transform_point3(x)));
                }
            }
            Err(_) => rejected += 1,
        }
    }
    scalar_row::<S>(&errs, NO_KERNEL, rejected, cases.len(), "rejected").timed(
        size,
        inputs,
        |&(p, u, v, w)| Camera::from_vectors(p, u, v, w).is_ok(),
    )
}

/// The general camera from three vectors, via the solver.
pub fn camera(size: Size, transform_i16f16_err: f64) -> Table {
    let cases = camera_cases(size);
    let rows = finish(size, per_scalar!(camera_row(size, &cases)));
    let recommendation = format!(
        "Building the camera costs one 3×3 solve with three right-hand sides (host: I16F16 \
         {} ns, f32 {} ns) and runs once per frame or less, so its cost hardly matters; its \
         accuracy does, because every vertex inherits it: world points within ±100 land \
         within {} view units of f64 with an I16F16 camera (I20F12: {}; f32: {}). That is {}× \
         the error of the I16F16 point transform itself ({} units, transform table), so on \
         an FPU-less core build the camera in f32 (or better) once per frame and round the \
         final matrix into the fixed-point transform.",
        g(ns(&rows, "I16F16")),
        g(ns(&rows, "f32")),
        g(max_err(&rows, "I16F16")),
        g(max_err(&rows, "I20F12")),
        g(max_err(&rows, "f32")),
        g(max_err(&rows, "I16F16") / transform_i16f16_err),
        g(transform_i16f16_err),
    );
    Table {
        id: "camera",
        title: "General camera from the solver",
        op: "one `Camera::from_vectors` (3×3 solve, three right-hand sides)",
        unit: "view-space units: |world→view of a point − f64|",
        unit_short: "view units",
        setup: format!(
            "{} cameras from general vectors u, v, w: a random orthonormal frame, each axis \
             scaled by [0.5, 2] and sheared by up to ±0.3 per component; positions within \
             ±50. Error over 8 world points within ±100 per camera. Reference: the f64 camera.",
            cases.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

//! `sightline-sim report`: error against run time for every numeric
//! representation of the core's kernels, as `accuracy.md` plus one Pareto
//! plot (PNG) per routine.
//!
//! Each routine runs the same deterministic inputs in every representation
//! it supports. Errors are measured against an `f64` reference (or an exact
//! construction, where the routine has one; each table says which), host
//! time is the median of repeated timed passes in this process, and the
//! Cortex-M column is read from `docs/mcu/kernels.md` (compiled in), which
//! `tests/mcu/run` generates. See [`METHOD`] for the text that heads the
//! report.

mod markdown;
mod mcu;
mod mixed;
mod plot;
mod routines_geom;
mod routines_ray;
mod routines_tex;
mod stats;

pub use markdown::{ParsedRow, parse_tables};
pub use stats::{ErrStats, Timing};

use std::path::{Path, PathBuf};
use std::time::Instant;

/// How much work the report does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Size {
    /// Inputs per routine and representation (points, rays, systems: the
    /// routines scale their own counts from it).
    pub samples: usize,
    /// Timed passes per row; the median and spread are over these.
    pub reps: usize,
    /// Minimum duration of one timed pass in microseconds (short passes
    /// are repeated until they last this long).
    pub min_pass_us: u64,
}

impl Size {
    /// The size of the committed report (about 10 s in release on the
    /// project machine).
    pub const FULL: Self = Self {
        samples: 16384,
        reps: 101,
        min_pass_us: 200,
    };
    /// A smoke-test size for `cargo test` (well under a second of work).
    pub const TINY: Self = Self {
        samples: 64,
        reps: 3,
        min_pass_us: 0,
    };
}

/// One representation's measurements for one routine.
#[derive(Clone, Debug)]
pub struct Row {
    /// The representation (and variant), e.g. `"I16F16"` or
    /// `"f32, exact"`.
    pub repr: String,
    /// Error statistics; `None` when every input was rejected.
    pub err: Option<ErrStats>,
    /// Host time per operation.
    pub time: Timing,
    /// Guest instructions per operation on (thumbv6m, thumbv7em-hf), or
    /// why there is no figure.
    pub mcu: mcu::McuCell,
    /// Rejections, misses and other remarks.
    pub note: String,
}

impl Row {
    /// A row measured from per-input errors, its time still to come from
    /// the round-robin timing ([`Timing::PENDING`]).
    pub fn new(
        repr: impl Into<String>,
        errs: &[f64],
        mcu: mcu::McuCell,
        note: impl Into<String>,
    ) -> Self {
        Self {
            repr: repr.into(),
            err: ErrStats::of(errs),
            time: Timing::PENDING,
            mcu,
            note: note.into(),
        }
    }
}

impl Row {
    /// This row paired with its benchmark: `f` over `inputs`, one
    /// operation per input (the tail every per-representation routine
    /// shares).
    pub fn timed<'a, I: 'a, R, F: FnMut(&I) -> R + 'a>(
        self,
        size: Size,
        inputs: Vec<I>,
        f: F,
    ) -> Pending<'a> {
        (self, bench(size, inputs, 1.0, f))
    }
}

/// `size.samples` cases drawn by `draw` from a generator seeded with
/// `seed` (each routine has its own seed, so tables do not share inputs).
pub fn cases<C>(size: Size, seed: u64, mut draw: impl FnMut(&mut Rng) -> C) -> Vec<C> {
    let mut rng = Rng::new(seed);
    (0..size.samples).map(|_| draw(&mut rng)).collect()
}

/// One routine's table, plot and recommendation.
#[derive(Clone, Debug)]
pub struct Table {
    /// File-name stem of the plot, e.g. `"transform"`.
    pub id: &'static str,
    /// Heading.
    pub title: &'static str,
    /// What one timed operation is.
    pub op: &'static str,
    /// The error's unit and what it measures.
    pub unit: &'static str,
    /// Short unit for the plot axis.
    pub unit_short: &'static str,
    /// How the inputs are made and what the reference is.
    pub setup: String,
    /// One row per representation.
    pub rows: Vec<Row>,
    /// Plot the mean error instead of the maximum (where the maximum is
    /// one quantized worst case shared by most rows).
    pub plot_mean: bool,
    /// What the data supports, written from the rows.
    pub recommendation: String,
}

/// The text at the top of `accuracy.md`.
pub const METHOD: &str = "\
## Method

- **Inputs.** Every routine draws its inputs from a fixed-seed generator (SplitMix64), \
so two runs measure the same cases. The inputs are made in `f64` and rounded once into \
each representation (`Scalar::from_f64`, round to nearest, saturating); the rounding of \
the inputs is part of a representation's error.
- **Reference.** The `f64` result of the same kernel, unless a table says it uses an \
exact construction instead (texture coordinates chosen first and geometry built from them; \
polygon targets placed on a known side of an edge). `f64` rows therefore show 0 where `f64` \
is the reference.
- **Error.** Per input, the distance between the result (converted to `f64`) and the \
reference in the table's unit; the table gives the maximum and the mean over all inputs \
that the representation did not reject. Rejections (a solver error, a `None` from a \
projection, a miss where the reference hits) are counted in *notes*, never averaged in.
- **Host time.** One timed pass runs the kernel behind `std::hint::black_box` for about the \
minimum pass time: over a chunk of the inputs (successive passes take successive chunks, so \
the passes cover all inputs) or over all inputs repeated; ns/op is the pass time divided by \
the operations. The rows of a table are timed round-robin (one pass of each row \
per round; in the line–polygon and texture-mapping tables, within each representation), so load from other processes spreads over all rows of the table alike. The \
table gives the median of the passes and the interquartile range (IQR, 25th–75th \
percentile) and min–max as spread. Release build, one thread, on a shared 2-core machine \
that other engineers were building on: compare rows within one table rather than figures \
across tables or runs.
- **Cortex-M.** Guest instructions per operation from `docs/mcu/kernels.md` \
(generated by `bash tests/mcu/run`, QEMU instruction-count plugin), for the kernels that \
harness has: thumbv6m (Cortex-M0-class, soft float) and thumbv7em-hf (Cortex-M4F). Where \
it has no kernel the cell says so. Instructions are not cycles.
- **Plots.** One PNG per routine: maximum error (mean error where the table says so) against median host ns/op, both axes \
logarithmic, one labelled point per row. A row with zero error is drawn at the bottom \
edge of the plot and its label ends in `(0)`. The gray line joins the Pareto front \
(rows that no other row beats on both error and time).
";

/// A deterministic SplitMix64 generator.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// Log-uniform in [lo, hi) (both positive).
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.unit()).exp()
    }
}

/// One timed pass of a kernel over its inputs, in ns per operation.
pub trait Pass {
    /// Runs the pass and returns ns per operation.
    fn pass(&mut self) -> f64;
}

struct Bench<I, F> {
    inputs: Vec<I>,
    f: F,
    /// Inputs per pass (a pass cycles through the inputs chunk by chunk
    /// when the whole slice takes longer than the minimum pass).
    chunk: usize,
    /// Where the next pass starts.
    cursor: usize,
    /// Repetitions of the chunk per pass (when it is shorter than the
    /// minimum pass).
    loops: usize,
    ops_per_input: f64,
}

impl<I, R, F: FnMut(&I) -> R> Pass for Bench<I, F> {
    fn pass(&mut self) -> f64 {
        let end = (self.cursor + self.chunk).min(self.inputs.len());
        let part = &self.inputs[self.cursor..end];
        self.cursor = if end >= self.inputs.len() { 0 } else { end };
        let t = Instant::now();
        for _ in 0..self.loops {
            for x in part {
                std::hint::black_box((self.f)(std::hint::black_box(x)));
            }
        }
        let ops = part.len().max(1) as f64 * self.ops_per_input * self.loops as f64;
        t.elapsed().as_nanos() as f64 / ops
    }
}

/// A row whose timing is still to be run, and its benchmark.
pub type Pending<'a> = (Row, Box<dyn Pass + 'a>);

/// A benchmark of `f` over `inputs` (`ops_per_input` operations each). A
/// warm-up pass over all inputs sizes the passes to about
/// `size.min_pass_us`: a chunk of the inputs (successive passes take
/// successive chunks) or the inputs repeated. Short passes keep most of
/// them clear of preemption on a loaded machine, and the median discards
/// the rest.
pub fn bench<'a, I: 'a, R, F: FnMut(&I) -> R + 'a>(
    size: Size,
    inputs: Vec<I>,
    ops_per_input: f64,
    f: F,
) -> Box<dyn Pass + 'a> {
    let n = inputs.len().max(1);
    let mut b = Bench {
        inputs,
        f,
        chunk: n,
        cursor: 0,
        loops: 1,
        ops_per_input,
    };
    let per_input_ns = b.pass().max(1e-3) * ops_per_input;
    let target_ns = size.min_pass_us as f64 * 1000.0;
    let inputs_per_pass = (target_ns / per_input_ns).ceil().max(1.0) as usize;
    if inputs_per_pass < n {
        b.chunk = inputs_per_pass;
    } else {
        b.loops = inputs_per_pass.div_ceil(n);
    }
    Box::new(b)
}

/// Runs the benchmarks of one table's rows round-robin (`size.reps`
/// rounds, one pass of every row per round), so that load from other
/// processes spreads over all rows instead of hitting a few, and stores
/// each row's median and spread.
pub fn finish(size: Size, pending: Vec<Pending<'_>>) -> Vec<Row> {
    let (mut rows, mut benches): (Vec<Row>, Vec<Box<dyn Pass + '_>>) = pending.into_iter().unzip();
    let mut samples = vec![Vec::with_capacity(size.reps); rows.len()];
    for _ in 0..size.reps.max(1) {
        for (b, s) in benches.iter_mut().zip(&mut samples) {
            s.push(b.pass());
        }
    }
    for (r, s) in rows.iter_mut().zip(samples) {
        r.time = Timing::from_samples(s);
    }
    rows
}

/// Runs every routine at `size` and returns the tables (no files).
pub fn tables(size: Size) -> Vec<Table> {
    let transform = routines_geom::transform(size);
    let fx_transform_err = transform
        .rows
        .iter()
        .find(|r| r.repr == "I16F16")
        .and_then(|r| r.err)
        .map_or(f64::NAN, |e| e.max);
    vec![
        transform,
        routines_geom::projection(size),
        routines_geom::solver::<3>(size),
        routines_geom::solver::<4>(size),
        routines_geom::camera(size, fx_transform_err),
        routines_tex::texture_vectors(size),
        routines_ray::line_plane(size),
        routines_ray::line_polygon(size),
        routines_ray::line_sphere(size),
        routines_tex::texture_mapping(size),
    ]
}

/// What [`generate`] wrote.
#[derive(Debug)]
pub struct Written {
    /// `DIR/accuracy.md`.
    pub markdown: PathBuf,
    /// One PNG per routine.
    pub plots: Vec<PathBuf>,
    /// The tables, as measured.
    pub tables: Vec<Table>,
    /// Wall time of the whole run in seconds.
    pub seconds: f64,
}

/// Runs the report at `size` and writes `dir/accuracy.md` and
/// `dir/<routine>.png`; `command` is the command line quoted in the
/// report.
///
/// # Errors
/// A message when the directory or a file cannot be written.
pub fn generate(dir: &Path, size: Size, command: &str) -> Result<Written, String> {
    let start = Instant::now();
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let tables = tables(size);
    let mut plots = Vec::new();
    for t in &tables {
        let file = dir.join(format!("{}.png", t.id));
        plot::pareto(&file, t)?;
        plots.push(file);
    }
    let seconds = start.elapsed().as_secs_f64();
    let md = markdown::render(&tables, size, command, seconds);
    let markdown = dir.join("accuracy.md");
    std::fs::write(&markdown, md)
        .map_err(|e| format!("cannot write {}: {e}", markdown.display()))?;
    Ok(Written {
        markdown,
        plots,
        tables,
        seconds,
    })
}

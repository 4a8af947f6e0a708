//! Ray intersections: line–plane, line–polygon (per inclusion test) and
//! line–sphere.

use super::mcu::NO_KERNEL;
use super::routines_geom::{
    count_note, dist, find, g, max_err, mean_err, ns, per_scalar, rand_vec, v3,
};
use super::{ErrStats, Pending, Rng, Row, Size, Table, Timing, bench, cases, finish};
use sightline::math::Vec3;
use sightline::ray::{InclusionTest, Plane, Polygon, Ray, SlabIndex, Sphere};
use sightline::scalar::Scalar;

/// The 99th percentile of `e` (0 for none).
fn p99(e: &[f64]) -> f64 {
    let mut v = e.to_vec();
    v.sort_by(f64::total_cmp);
    v.get((v.len() * 99) / 100).copied().unwrap_or(0.0)
}

/// The 99th percentile recorded in a row's note ("p99 X; …").
fn p99_of(rows: &[Row], repr: &str) -> f64 {
    find(rows, repr)
        .and_then(|r| r.note.strip_prefix("p99 ")?.split(';').next()?.parse().ok())
        .unwrap_or(f64::NAN)
}

/// The hit point of an `S` ray at `t`, formed in f64 from the stored
/// values (so only the representation's rounding of the inputs and of t
/// counts).
fn hit_f64<S: Scalar>(ray: &Ray<S>, t: S) -> Vec3<f64> {
    ray.origin().cast::<f64>() + ray.dir().cast::<f64>() * t.to_f64()
}

/// A primitive a ray can hit at a parameter t > 0.
trait Hit<S> {
    fn hit(&self, ray: &Ray<S>) -> Option<S>;
}

impl<S: Scalar> Hit<S> for Plane<S> {
    fn hit(&self, ray: &Ray<S>) -> Option<S> {
        self.intersect(ray, S::ZERO)
    }
}

impl<S: Scalar> Hit<S> for Sphere<S> {
    fn hit(&self, ray: &Ray<S>) -> Option<S> {
        self.intersect(ray, S::ZERO)
    }
}

/// A ray from `origin` along the unit `dir`.
#[derive(Clone, Copy)]
struct Aim {
    origin: Vec3<f64>,
    dir: Vec3<f64>,
}

impl Aim {
    /// The ray from `origin` towards `target`.
    fn at(origin: Vec3<f64>, target: Vec3<f64>) -> Self {
        Self {
            origin,
            dir: (target - origin).normalize(),
        }
    }
}

/// One ray case: a primitive, and a ray aimed at it, built in any
/// representation.
trait RayCase {
    type Prim<S: Scalar>: Hit<S> + 'static;
    fn prim<S: Scalar>(&self) -> Option<Self::Prim<S>>;
    fn aim(&self) -> Aim;
    /// What the note says about the case with the largest error.
    fn worst_note(&self) -> Option<String> {
        None
    }
}

/// The row of representation `S` for a line–primitive table: hit points
/// against the f64 hits, the 99th percentile and misses in the note.
fn ray_row<S: Scalar>(size: Size, cases: &[impl RayCase]) -> Pending<'static> {
    let inputs: Vec<_> = cases
        .iter()
        .filter_map(|c| {
            let a = c.aim();
            Some((c.prim::<S>()?, Ray::new(v3::<S>(a.origin), v3(a.dir)).ok()?))
        })
        .collect();
    let mut errs = Vec::new();
    let mut missed = cases.len() - inputs.len();
    let mut worst = (0.0, None);
    for (c, (pr, ray)) in cases.iter().zip(&inputs) {
        let rp = c.prim::<f64>().expect("f64 primitive");
        let a = c.aim();
        let rr = Ray::new(a.origin, a.dir).expect("f64 ray");
        let Some(tr) = rp.hit(&rr) else {
            continue;
        };
        match pr.hit(ray) {
            Some(t) => {
                let e = dist(hit_f64(ray, t), rr.at(tr));
                if e > worst.0 {
                    worst = (e, Some(c));
                }
                errs.push(e);
            }
            None => missed += 1,
        }
    }
    let mut note = format!("p99 {}", super::markdown::num(p99(&errs)));
    if let Some(w) = worst.1.and_then(RayCase::worst_note) {
        note.push_str(&w);
    }
    if missed > 0 {
        note.push_str(&format!("; {}", count_note(missed, cases.len(), "missed")));
    }
    Row::new(S::NAME, &errs, NO_KERNEL, note).timed(size, inputs, |(pr, ray)| pr.hit(ray))
}

// -------------------------------------------------------------- line–plane

struct PlaneCase {
    point: Vec3<f64>,
    normal: Vec3<f64>,
    aim: Aim,
}

impl RayCase for PlaneCase {
    type Prim<S: Scalar> = Plane<S>;
    fn prim<S: Scalar>(&self) -> Option<Plane<S>> {
        Plane::new(v3(self.point), v3(self.normal)).ok()
    }
    fn aim(&self) -> Aim {
        self.aim
    }
    fn worst_note(&self) -> Option<String> {
        let sin = self.aim.dir.dot(self.normal.normalize()).abs();
        Some(format!(
            "; worst case {:.2}° from grazing",
            sin.asin().to_degrees()
        ))
    }
}

fn plane_cases(size: Size) -> Vec<PlaneCase> {
    cases(size, 11, |rng| {
        let point = rand_vec(rng, 50.0);
        let normal = rand_vec(rng, 1.0);
        let origin = rand_vec(rng, 10.0);
        // A target on the plane: the point plus an in-plane offset.
        let off = rand_vec(rng, 40.0);
        let nn = normal.normalize();
        let target = point + off - nn * off.dot(nn);
        PlaneCase {
            point,
            normal,
            aim: Aim::at(origin, target),
        }
    })
}

/// Line–plane intersection (`ray::Plane::intersect`).
pub fn line_plane(size: Size) -> Table {
    let cases = plane_cases(size);
    let rows = finish(size, per_scalar!(ray_row(size, &cases)));
    let mean = |s: &str| mean_err(&rows, s);
    let recommendation = format!(
        "The maxima come from rays that meet the plane at a grazing angle (see notes), where \
         the hit point moves by the direction's rounding divided by the angle's sine; the \
         means are what a typical ray sees: f32 {} units (max {}), I16F16 {} (max {}), \
         I20F12 {} (max {}). I16F16 ({} ns/op on the host against {} for f32) is good for \
         picking and floor/wall hits that are not grazing; where grazing rays matter (long \
         floors towards the horizon), use f32, whose worst case stays at {} units.",
        g(mean("f32")),
        g(max_err(&rows, "f32")),
        g(mean("I16F16")),
        g(max_err(&rows, "I16F16")),
        g(mean("I20F12")),
        g(max_err(&rows, "I20F12")),
        g(ns(&rows, "I16F16")),
        g(ns(&rows, "f32")),
        g(max_err(&rows, "f32")),
    );
    Table {
        id: "line_plane",
        title: "Line–plane intersection",
        op: "one `Plane::intersect`",
        unit: "world units: |hit point − f64 hit point|",
        unit_short: "world units",
        setup: format!(
            "{} random planes through points within ±50 with random normals, rays from \
             within ±10 towards a point of the plane up to 40 units off its anchor (unit \
             direction). Reference: the f64 hit.",
            cases.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

// ------------------------------------------------------------ line–polygon

const POLY_N: usize = 8;

struct PolyScene {
    verts: Vec<Vec3<f64>>,
    eye: Vec3<f64>,
    /// Targets on the polygon's plane, whether they are inside by
    /// construction, and their distance from the edge.
    targets: Vec<(Vec3<f64>, bool, f64)>,
}

fn poly_scene(size: Size) -> PolyScene {
    // A convex hexagon of radius 20, tilted, around (5, −3, −60).
    let center = Vec3::new(5.0, -3.0, -60.0);
    let e1 = Vec3::new(1.0, 0.2, 0.3).normalize();
    let e2 = e1.cross(Vec3::new(0.1, 0.4, 1.0)).normalize();
    let verts: Vec<Vec3<f64>> = (0..6)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 6.0 + 0.1;
            center + e1 * (20.0 * a.cos()) + e2 * (20.0 * a.sin())
        })
        .collect();
    let mut rng = Rng::new(12);
    let n = e1.cross(e2);
    let targets = (0..size.samples)
        .map(|_| {
            let k = (rng.next_u64() % 6) as usize;
            let (a, b) = (verts[k], verts[(k + 1) % 6]);
            let along = a + (b - a) * rng.range(0.1, 0.9);
            // Inward normal of edge k within the plane.
            let inward = n.cross(b - a).normalize();
            let inward = if inward.dot(center - along) > 0.0 {
                inward
            } else {
                -inward
            };
            let d = rng.log_range(1e-6, 1e-1);
            let inside = rng.next_u64() & 1 == 0;
            let p = along + inward * if inside { d } else { -d };
            (p, inside, d)
        })
        .collect();
    PolyScene {
        verts,
        eye: Vec3::new(0.0, 0.0, 0.0),
        targets,
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Method {
    Test(InclusionTest),
    Slab,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Self::Test(InclusionTest::Crossing) => "crossing",
            Self::Test(InclusionTest::HalfPlane) => "half-plane",
            Self::Test(InclusionTest::Fan) => "fan",
            Self::Slab => "slab",
        }
    }
}

const METHODS: [Method; 4] = [
    Method::Test(InclusionTest::Crossing),
    Method::Test(InclusionTest::HalfPlane),
    Method::Test(InclusionTest::Fan),
    Method::Slab,
];

fn poly_rows<S: Scalar>(size: Size, sc: &PolyScene) -> Vec<Row> {
    let verts: Vec<Vec3<S>> = sc.verts.iter().map(|&v| v3(v)).collect();
    let Ok(poly) = Polygon::<S, POLY_N>::new(&verts) else {
        return Vec::new();
    };
    let eye = v3::<S>(sc.eye);
    let rays: Vec<Option<Ray<S>>> = sc
        .targets
        .iter()
        .map(|&(p, _, _)| Ray::through(eye, v3(p)).ok())
        .collect();
    let mut ys = [S::ZERO; POLY_N];
    let mut starts = [0u32; POLY_N];
    let mut edges = [0u32; POLY_N * POLY_N];
    let slab = SlabIndex::build(&poly, &mut ys, &mut starts, &mut edges).ok();
    let valid: Vec<Ray<S>> = rays.iter().flatten().copied().collect();
    let polys: Vec<(Method, Polygon<S, POLY_N>)> = METHODS
        .iter()
        .map(|&m| match m {
            Method::Test(t) => (m, poly.clone().with_test(t)),
            Method::Slab => (m, poly.clone()),
        })
        .collect();
    let slab = slab.as_ref();
    let pending: Vec<Pending<'_>> = polys
        .iter()
        .map(|(m, p)| {
            let m = *m;
            let hit = move |ray: &Ray<S>| -> bool {
                match m {
                    Method::Test(_) => p.intersect(ray, S::ZERO).is_some(),
                    Method::Slab => {
                        let Some(t) = p.plane().intersect(ray, S::ZERO) else {
                            return false;
                        };
                        let x = ray.at(t);
                        slab.is_some_and(|s| s.contains(p.project(x)))
                    }
                }
            };
            let mut wrong = 0usize;
            // The largest distance from the edge among misclassified targets.
            let mut widest = 0.0f64;
            for (ray, &(_, inside, d)) in rays.iter().zip(&sc.targets) {
                let got = ray.as_ref().is_some_and(hit);
                if got != inside {
                    wrong += 1;
                    widest = widest.max(d);
                }
            }
            let rate = wrong as f64 / sc.targets.len() as f64;
            let b = bench(size, valid.clone(), 1.0, hit);
            let row = Row {
                repr: format!("{}, {}", S::NAME, m.name()),
                // One figure per row: the rate is both max and mean.
                err: Some(ErrStats {
                    max: rate,
                    mean: rate,
                    count: sc.targets.len(),
                }),
                time: Timing::PENDING,
                mcu: NO_KERNEL,
                note: if wrong == 0 {
                    format!("0/{} misclassified", sc.targets.len())
                } else {
                    format!(
                        "{wrong}/{} misclassified, all within {} of the edge",
                        sc.targets.len(),
                        super::markdown::num(widest)
                    )
                },
            };
            (row, b)
        })
        .collect();
    // Round-robin over the four tests of this representation.
    finish(size, pending)
}

/// Line–polygon intersection per inclusion test, near the edges.
pub fn line_polygon(size: Size) -> Table {
    let sc = poly_scene(size);
    let rows: Vec<Row> = per_scalar!(poly_rows(size, &sc))
        .into_iter()
        .flatten()
        .collect();
    let rate = |s: &str| max_err(&rows, s);
    let fastest = |s: &str| {
        rows.iter()
            .filter(|r| r.repr.starts_with(&format!("{s},")))
            .min_by(|a, b| a.time.median.total_cmp(&b.time.median))
            .map(|r| (r.repr.clone(), r.time.median))
            .unwrap_or_default()
    };
    // Do the four tests agree within each representation?
    let same = ["f64", "f32", "I16F16", "I20F12"].iter().all(|s| {
        let notes: Vec<&str> = rows
            .iter()
            .filter(|r| r.repr.starts_with(&format!("{s},")))
            .map(|r| r.note.as_str())
            .collect();
        notes.windows(2).all(|w| w[0] == w[1])
    });
    let same_text = if same {
        "The four tests misclassify the same number of rays within each representation, as \
         their shared boundary predicate predicts."
    } else {
        "The four tests do not misclassify the same number of rays in every representation \
         (see the notes column)."
    };
    let (f32_fast, f32_ns) = fastest("f32");
    let (fx_fast, fx_ns) = fastest("I16F16");
    let recommendation = format!(
        "Targets lie 10⁻⁶ to 10⁻¹ units (log-uniform) inside or outside an edge of a hexagon \
         of radius 20, 60 units away, so this is the hardest case for classification. {} Rates: \
         f64 {}, f32 {}, I16F16 {}, I20F12 {}. Every misclassified target lies \
         within a small distance of its edge (notes column: the largest such distance per \
         row), the scale of the representation's rounding of the hit point, so the \
         representation and not the test decides robustness near edges. Pick the test for \
         speed: for this hexagon the fastest is {} at {} ns and {} at {} ns.",
        same_text,
        g(rate("f64, crossing")),
        g(rate("f32, crossing")),
        g(rate("I16F16, crossing")),
        g(rate("I20F12, crossing")),
        f32_fast,
        g(f32_ns),
        fx_fast,
        g(fx_ns),
    );
    Table {
        id: "line_polygon",
        title: "Line–polygon intersection by inclusion test (near edges)",
        op: "one intersection: plane hit, projection, inclusion test",
        unit: "misclassification rate (fraction of rays classified against the construction)",
        unit_short: "wrong-classification rate",
        setup: format!(
            "A tilted convex hexagon (radius 20) centered 60 units from the eye; {} rays from the \
             eye through targets on its plane, each at a log-uniform distance in [10⁻⁶, 10⁻¹] \
             inside or outside a random edge (away from the vertices). Reference: the side \
             chosen by construction (exact), not f64. Slab uses `SlabIndex` over the same \
             polygon.",
            sc.targets.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

// ------------------------------------------------------------- line–sphere

struct SphereCase {
    center: Vec3<f64>,
    radius: f64,
    aim: Aim,
}

impl RayCase for SphereCase {
    type Prim<S: Scalar> = Sphere<S>;
    fn prim<S: Scalar>(&self) -> Option<Sphere<S>> {
        Sphere::new(v3(self.center), S::from_f64(self.radius)).ok()
    }
    fn aim(&self) -> Aim {
        self.aim
    }
}

fn sphere_cases(size: Size) -> Vec<SphereCase> {
    cases(size, 13, |rng| {
        let radius = rng.log_range(1.0, 20.0);
        let center = rand_vec(rng, 60.0) + Vec3::new(0.0, 0.0, -80.0);
        let origin = rand_vec(rng, 5.0);
        // Aim at a point of the silhouette disc, up to 0.999 of the
        // radius off center (near-grazing rays included).
        let to_c = (center - origin).normalize();
        let side = to_c.cross(Vec3::new(0.3, 1.0, 0.2)).normalize();
        let up = to_c.cross(side);
        let r = radius * rng.range(0.0, 0.999).sqrt();
        let a = rng.range(0.0, std::f64::consts::TAU);
        let target = center + side * (r * a.cos()) + up * (r * a.sin());
        SphereCase {
            center,
            radius,
            aim: Aim::at(origin, target),
        }
    })
}

/// Line–sphere intersection (`ray::Sphere::intersect`).
pub fn line_sphere(size: Size) -> Table {
    let cases = sphere_cases(size);
    let rows = finish(size, per_scalar!(ray_row(size, &cases)));
    let recommendation = format!(
        "Rays aimed anywhere on the silhouette, up to 0.999 of the radius off center, where \
         the hit point is most sensitive to the direction: f32 is within {} units, I16F16 \
         within {} and I20F12 within {} of the f64 hit ({} / {} / {} ns/op on the host). The near-grazing rays set the \
         maxima: 99% of I16F16 hits are within {} units (f32: {}), enough for shading a \
         sphere tens of pixels across; use f32 where silhouettes must be exact.",
        g(max_err(&rows, "f32")),
        g(max_err(&rows, "I16F16")),
        g(max_err(&rows, "I20F12")),
        g(ns(&rows, "f32")),
        g(ns(&rows, "I16F16")),
        g(ns(&rows, "I20F12")),
        g(p99_of(&rows, "I16F16")),
        g(p99_of(&rows, "f32")),
    );
    Table {
        id: "line_sphere",
        title: "Line–sphere intersection",
        op: "one `Sphere::intersect`",
        unit: "world units: |hit point − f64 hit point|",
        unit_short: "world units",
        setup: format!(
            "{} spheres of radius log-uniform in [1, 20] centered within ±60 of (0, 0, −80); \
             rays from within ±5 of the origin (unit direction) aimed at a uniform point of \
             the sphere's silhouette disc out to 0.999 of its radius. Reference: the f64 hit.",
            cases.len()
        ),
        rows,
        plot_mean: false,
        recommendation,
    }
}

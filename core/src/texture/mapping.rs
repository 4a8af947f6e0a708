//! Texture-mapping vectors, the screen mapping they give, and the
//! affine/perspective choice (see the [module docs](super)).

use crate::math::{Vec2, Vec3};
use crate::scalar::Scalar;
use crate::solve::{self, Diagnostics, SolveConfig, SolveError};
use core::fmt;

/// Why texture-mapping vectors could not be recovered.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum MappingError {
    /// Fewer than three vertices, or position and texture-coordinate
    /// slices of different lengths.
    TooFewVertices,
    /// A coordinate is NaN or ±∞.
    NonFinite,
    /// The positions have no area: repeated or collinear vertices.
    DegeneratePolygon,
    /// The texture coordinates have no area (repeated or collinear (u, v)),
    /// or an axis edge has zero texel length: no mapping exists.
    DegenerateUv,
    /// [`TextureVectors::from_axis_edges`]: the edge to `b` changes v or
    /// the edge to `c` changes u.
    NotAxisAligned,
    /// The vertices do not fit one affine mapping: a vertex lies off the
    /// plane of the others or its (u, v) disagrees with theirs by more
    /// than the tolerance (see [`TextureVectors::from_polygon`]).
    Inconsistent,
    /// The solver rejected the system (singular or ill-conditioned to
    /// working precision, or overflow).
    Solve(SolveError),
}

impl fmt::Display for MappingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooFewVertices => {
                f.write_str("need at least three vertices, each with texture coordinates")
            }
            Self::NonFinite => f.write_str("a position or texture coordinate is NaN or infinite"),
            Self::DegeneratePolygon => {
                f.write_str("polygon has no area (repeated or collinear vertices)")
            }
            Self::DegenerateUv => {
                f.write_str("texture coordinates have no area (repeated or collinear)")
            }
            Self::NotAxisAligned => {
                f.write_str("edges from the base vertex do not run along u and v")
            }
            Self::Inconsistent => {
                f.write_str("vertices and texture coordinates do not fit one planar affine mapping")
            }
            Self::Solve(e) => write!(f, "texture-vector system not solvable: {e}"),
        }
    }
}

impl core::error::Error for MappingError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Solve(e) => Some(e),
            _ => None,
        }
    }
}

/// Texture-mapping vectors: the texture point (u, v) lies at
/// `origin + u·u_axis + v·v_axis` in view space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureVectors<S> {
    /// P: where texture coordinates (0, 0) lie (possibly off the polygon).
    pub origin: Vec3<S>,
    /// U: the view-space step for one texel in u.
    pub u_axis: Vec3<S>,
    /// V: the view-space step for one texel in v.
    pub v_axis: Vec3<S>,
}

/// The per-pixel perspective mapping of a [`TextureVectors`] plane:
/// with the view ray `D(x, y) = ((x − c_x)/f, (y − c_y)/f, 1)` through
/// screen point (x, y) (pixels, x right, y down; pixel (i, j) has its
/// center at (i + ½, j + ½)),
///
/// ```text
/// u = k · D·a / D·n,   v = k · D·b / D·n
/// ```
///
/// Each dot product is linear in x and y, so u and v are ratios of linear
/// functions of the screen coordinates. `a` and `b` share one scale and
/// `n` has its own (each normalized so its largest component is 1), and
/// `k` restores their ratio: that keeps the relative precision of fixed
/// point in numerator and denominator alike.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenMapping<S> {
    /// Numerator vector for u (`V×P`, scaled).
    pub a: Vec3<S>,
    /// Numerator vector for v (`P×U`, same scale as `a`).
    pub b: Vec3<S>,
    /// Denominator vector (`U×V`, the plane's normal, scaled).
    pub n: Vec3<S>,
    /// The ratio of the two scales.
    pub k: S,
    /// Screen center (c_x, c_y).
    pub center: Vec2<S>,
    /// Focus distance f in pixels.
    pub focus: S,
}

impl<S: Scalar> ScreenMapping<S> {
    /// The view ray through screen point (x, y), or `None` on overflow.
    fn ray(&self, x: S, y: S) -> Option<Vec3<S>> {
        Some(Vec3::new(
            x.checked_sub(self.center.x)?.checked_div(self.focus)?,
            y.checked_sub(self.center.y)?.checked_div(self.focus)?,
            S::ONE,
        ))
    }

    /// (u, v) at screen point (x, y), or `None` where the view ray is
    /// parallel to the plane (the denominator is zero) or the arithmetic
    /// overflows.
    #[must_use]
    pub fn uv(&self, x: S, y: S) -> Option<(S, S)> {
        let d = self.ray(x, y)?;
        let den = d.dot(self.n);
        let u = d.dot(self.a).checked_div(den)?.checked_mul(self.k)?;
        let v = d.dot(self.b).checked_div(den)?.checked_mul(self.k)?;
        Some((u, v))
    }
}

impl<S: Scalar> TextureVectors<S> {
    /// The view-space point of texture coordinates (u, v).
    #[must_use]
    pub fn point(&self, u: S, v: S) -> Vec3<S> {
        self.origin + self.u_axis * u + self.v_axis * v
    }

    /// The fast path for rectangles and right triangles laid out along
    /// the texture axes: from vertex `a`, the edge to `b` runs along u
    /// only (same v) and the edge to `c` along v only (same u). Then
    /// `U = (b − a)/(u_b − u_a)`, `V = (c − a)/(v_c − v_a)` and
    /// `P = a − u_a·U − v_a·V`: two divisions per axis, no system to solve.
    ///
    /// # Errors
    /// [`MappingError::NonFinite`]; [`MappingError::NotAxisAligned`] when
    /// `uv_b.y ≠ uv_a.y` or `uv_c.x ≠ uv_a.x`; [`MappingError::DegenerateUv`]
    /// for a zero texel length; [`MappingError::DegeneratePolygon`] when
    /// the edges are parallel or zero.
    pub fn from_axis_edges(
        a: Vec3<S>,
        b: Vec3<S>,
        c: Vec3<S>,
        uv_a: Vec2<S>,
        uv_b: Vec2<S>,
        uv_c: Vec2<S>,
    ) -> Result<Self, MappingError> {
        let finite = |v: Vec2<S>| v.x.is_finite() && v.y.is_finite();
        if !(a.is_finite()
            && b.is_finite()
            && c.is_finite()
            && finite(uv_a)
            && finite(uv_b)
            && finite(uv_c))
        {
            return Err(MappingError::NonFinite);
        }
        if uv_b.y != uv_a.y || uv_c.x != uv_a.x {
            return Err(MappingError::NotAxisAligned);
        }
        let du = uv_b.x - uv_a.x;
        let dv = uv_c.y - uv_a.y;
        if du == S::ZERO || dv == S::ZERO {
            return Err(MappingError::DegenerateUv);
        }
        let (eu, ev) = (b - a, c - a);
        check_area(eu, ev)?;
        let overflow = MappingError::Solve(SolveError::Overflow);
        let div = |e: Vec3<S>, d: S| -> Result<Vec3<S>, MappingError> {
            Ok(Vec3::new(
                e.x.checked_div(d).ok_or(overflow)?,
                e.y.checked_div(d).ok_or(overflow)?,
                e.z.checked_div(d).ok_or(overflow)?,
            ))
        };
        let u_axis = div(eu, du)?;
        let v_axis = div(ev, dv)?;
        Ok(Self {
            origin: a - u_axis * uv_a.x - v_axis * uv_a.y,
            u_axis,
            v_axis,
        })
    }

    /// Texture-mapping vectors of any planar polygon whose texture
    /// coordinates are affine over it, by the reverse-mapping equations
    /// based on vertex 0:
    ///
    /// ```text
    /// Xᵢ − X₀ = (uᵢ − u₀)·U + (vᵢ − v₀)·V
    /// ```
    ///
    /// Two of these (the vertex pair i, j whose texel differences span the
    /// largest area) form the 2×2 system
    /// `[[Δuᵢ, Δvᵢ], [Δuⱼ, Δvⱼ]]·[U; V] = [Xᵢ − X₀; Xⱼ − X₀]` with the x, y
    /// and z components as three right-hand sides, solved with
    /// [`crate::solve`] (partial pivoting, with its diagnostics returned).
    /// Then `P = X₀ − u₀·U − v₀·V`. Every other vertex is checked against
    /// the result.
    ///
    /// # Errors
    /// - [`MappingError::TooFewVertices`] for fewer than three vertices or
    ///   slices of different lengths;
    /// - [`MappingError::NonFinite`];
    /// - [`MappingError::DegeneratePolygon`] when the positions span no
    ///   area (relative to the polygon's size, below 64·ε of the scalar);
    /// - [`MappingError::DegenerateUv`] likewise for the texture
    ///   coordinates;
    /// - [`MappingError::Solve`] when the solver rejects the system
    ///   (reciprocal condition number below √ε);
    /// - [`MappingError::Inconsistent`] when a vertex misses the mapping
    ///   by more than `√ε·16` times the polygon's extent (non-planar
    ///   polygon, or texture coordinates that are not affine over it).
    pub fn from_polygon(
        positions: &[Vec3<S>],
        uvs: &[Vec2<S>],
    ) -> Result<(Self, Diagnostics<S>), MappingError> {
        let n = positions.len();
        if n < 3 || uvs.len() != n {
            return Err(MappingError::TooFewVertices);
        }
        if !(positions.iter().all(|p| p.is_finite())
            && uvs.iter().all(|t| t.x.is_finite() && t.y.is_finite()))
        {
            return Err(MappingError::NonFinite);
        }
        let (x0, t0) = (positions[0], uvs[0]);
        // The polygon's area vector (Newell's method) against its extent.
        let mut area = Vec3::ZERO;
        for i in 1..n - 1 {
            area += (positions[i] - x0).cross(positions[i + 1] - x0);
        }
        let size = positions
            .iter()
            .fold(S::ZERO, |m, p| m.max_of((*p - x0).max_abs()));
        let tiny = S::EPSILON * S::from_i32(64);
        if size == S::ZERO || area.max_abs() <= tiny * size * size {
            return Err(MappingError::DegeneratePolygon);
        }
        // The best-conditioned pair: the largest |Δuᵢ·Δvⱼ − Δvᵢ·Δuⱼ|.
        let d = |i: usize| uvs[i] - t0;
        let uv_size = uvs.iter().fold(S::ZERO, |m, t| {
            m.max_of((*t - t0).x.abs()).max_of((*t - t0).y.abs())
        });
        let mut best = (1, 2, S::ZERO);
        for i in 1..n {
            for j in i + 1..n {
                let det = d(i).perp_dot(d(j)).abs();
                if det > best.2 {
                    best = (i, j, det);
                }
            }
        }
        let (i, j, det) = best;
        if uv_size == S::ZERO || det <= tiny * uv_size * uv_size {
            return Err(MappingError::DegenerateUv);
        }
        let (di, dj) = (d(i), d(j));
        let (ei, ej) = (positions[i] - x0, positions[j] - x0);
        let a = [[di.x, di.y], [dj.x, dj.y]];
        let b = [[ei.x, ei.y, ei.z], [ej.x, ej.y, ej.z]];
        let config = SolveConfig {
            rcond_min: S::EPSILON.sqrt(),
            ..SolveConfig::default()
        };
        let sol = solve::solve_with(&a, &b, &config).map_err(MappingError::Solve)?;
        let [ur, vr] = sol.x;
        let u_axis = Vec3::new(ur[0], ur[1], ur[2]);
        let v_axis = Vec3::new(vr[0], vr[1], vr[2]);
        let m = Self {
            origin: x0 - u_axis * t0.x - v_axis * t0.y,
            u_axis,
            v_axis,
        };
        // Every vertex must lie where the mapping puts its (u, v); compared
        // relative to X₀ so that a far texture origin does not cost
        // precision.
        let tol = S::EPSILON.sqrt() * S::from_i32(16) * size;
        for (&pk, &tk) in positions.iter().zip(uvs).skip(1) {
            let dk = tk - t0;
            let predicted = u_axis * dk.x + v_axis * dk.y;
            if (predicted - (pk - x0)).max_abs() > tol {
                return Err(MappingError::Inconsistent);
            }
        }
        Ok((m, sol.diagnostics))
    }

    /// The per-pixel perspective mapping ([`ScreenMapping`]) for a
    /// perspective projection with focus distance `focus` (pixels) about
    /// screen point `center` (see [`Projection`](crate::camera::Projection)):
    /// with `N = U×V`, `A = V×P`, `B = P×U` and the view ray `D`,
    /// `u = D·A / D·N` and `v = D·B / D·N`.
    ///
    /// U, V and P are first divided by the larger of |U|, |V| (the scale
    /// cancels in the ratios), so that fixed point does not form the
    /// cross product of texel-sized vectors, a few grid steps each.
    ///
    /// Returns `None` if U and V are zero or parallel, a value overflows
    /// (fixed point) or `focus` is not positive.
    #[must_use]
    pub fn screen_mapping(&self, focus: S, center: Vec2<S>) -> Option<ScreenMapping<S>> {
        if focus.partial_cmp(&S::ZERO) != Some(core::cmp::Ordering::Greater) {
            return None;
        }
        let div = |w: Vec3<S>, d: S| -> Option<Vec3<S>> {
            Some(Vec3::new(
                w.x.checked_div(d)?,
                w.y.checked_div(d)?,
                w.z.checked_div(d)?,
            ))
        };
        let s = self.u_axis.max_abs().max_of(self.v_axis.max_abs());
        if s == S::ZERO {
            return None;
        }
        let (p, u, v) = (
            div(self.origin, s)?,
            div(self.u_axis, s)?,
            div(self.v_axis, s)?,
        );
        let (n, a, b) = (u.cross(v), v.cross(p), p.cross(u));
        let m1 = a.max_abs().max_of(b.max_abs());
        let m2 = n.max_abs();
        if m2 == S::ZERO || !m1.is_finite() || !m2.is_finite() {
            return None;
        }
        let (a, b, k) = if m1 == S::ZERO {
            // P = 0 (the plane passes through the eye): u = v = 0.
            (a, b, S::ZERO)
        } else {
            (div(a, m1)?, div(b, m1)?, m1.checked_div(m2)?)
        };
        Some(ScreenMapping {
            a,
            b,
            n: div(n, m2)?,
            k,
            center,
            focus,
        })
    }
}

/// `DegeneratePolygon` unless the two edges span an area.
fn check_area<S: Scalar>(e1: Vec3<S>, e2: Vec3<S>) -> Result<(), MappingError> {
    let size = e1.max_abs().max_of(e2.max_abs());
    let tiny = S::EPSILON * S::from_i32(64);
    if size == S::ZERO || e1.cross(e2).max_abs() <= tiny * size * size {
        Err(MappingError::DegeneratePolygon)
    } else {
        Ok(())
    }
}

/// Affine or perspective texture mapping for one polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mapping {
    /// Interpolate (u, v) linearly in screen space
    /// ([`AffineTexture`](crate::raster::AffineTexture)).
    Affine,
    /// Interpolate (u/z, v/z, 1/z) and divide
    /// ([`PerspectiveTexture`](crate::raster::PerspectiveTexture)).
    Perspective,
}

/// An upper bound, in texels per axis, on how far affine interpolation of
/// (u, v) over a triangle strays from the perspective-correct values,
/// given the vertices' view depths `z` (all positive) and texture
/// coordinates.
///
/// Derivation: with screen-space barycentric weights λᵢ ≥ 0 and
/// qᵢ = 1/zᵢ (which *is* linear in screen space), the exact value is
/// `u = Σλᵢqᵢuᵢ / q̄` with `q̄ = Σλᵢqᵢ`, and affine gives `Σλᵢuᵢ`. Their
/// difference is `Σλᵢ(uᵢ − c)(qᵢ − q̄)/q̄` for any constant c (the terms
/// `Σλᵢ(qᵢ − q̄)` vanish). Taking c mid-range, `|uᵢ − c| ≤ Δu/2`; the
/// mean absolute deviation `Σλᵢ|qᵢ − q̄|` of values in
/// `[q_min, q_max]` is at most `(q_max − q_min)/2`; and `q̄ ≥ q_min`. So
///
/// ```text
/// |u_affine − u_exact| ≤ Δu · (q_max − q_min) / (4·q_min) = Δu · (z_max − z_min) / (4·z_min)
/// ```
///
/// and the same for v with Δv. The bound is the larger of the two. It
/// holds at every point of the triangle (not outside it, where the
/// weights can be negative), so decide per triangle. For parallel
/// projection pass equal depths: the bound is 0.
///
/// Returns `None` for a non-positive or non-finite depth, or overflow.
#[must_use]
pub fn affine_error_bound<S: Scalar>(z: [S; 3], uv: [Vec2<S>; 3]) -> Option<S> {
    if !z.iter().all(|&d| d > S::ZERO && d.is_finite()) {
        return None;
    }
    let zmin = z[0].min_of(z[1]).min_of(z[2]);
    let zmax = z[0].max_of(z[1]).max_of(z[2]);
    let range = |f: fn(&Vec2<S>) -> S| {
        let (a, b, c) = (f(&uv[0]), f(&uv[1]), f(&uv[2]));
        a.max_of(b).max_of(c).checked_sub(a.min_of(b).min_of(c))
    };
    let du = range(|t| t.x)?;
    let dv = range(|t| t.y)?;
    let spread = (zmax - zmin).checked_div(zmin.checked_mul(S::from_i32(4))?)?;
    let b = du.max_of(dv).checked_mul(spread)?;
    b.is_finite().then_some(b)
}

/// Chooses affine mapping for a triangle when its error cannot exceed
/// `threshold` texels per axis ([`affine_error_bound`]), perspective
/// otherwise ("use perspective texture mapping only where the distortion
/// cannot be neglected"). Undecidable input (non-positive depth,
/// overflow) gets [`Mapping::Perspective`], which is always correct.
#[must_use]
pub fn choose_mapping<S: Scalar>(z: [S; 3], uv: [Vec2<S>; 3], threshold: S) -> Mapping {
    match affine_error_bound(z, uv) {
        Some(b) if b <= threshold => Mapping::Affine,
        _ => Mapping::Perspective,
    }
}

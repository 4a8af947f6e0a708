//! Gaussian elimination with partial pivoting for `A X = B`, with `A` of
//! size N×N and `B` of M columns (const generics, no allocation), returning
//! the solution together with the diagnostics a caller needs to trust it.
//!
//! This generalizes the viewing-process chapter's routine, which solves
//! `A X = B` for an `m`-column `B`, and follows LAPACK's expert driver
//! `xGESVX` in what it reports:
//!
//! - **pivot growth** ρ = maxₖ maxᵢⱼ |aᵢⱼ⁽ᵏ⁾| / maxᵢⱼ |aᵢⱼ|, the growth factor
//!   of Higham, *Accuracy and Stability of Numerical Algorithms* (2nd ed.),
//!   §9.3. Backward error is bounded by a small multiple of ρ·n·ε; partial
//!   pivoting allows ρ up to 2ⁿ⁻¹ (Wilkinson's matrix reaches it).
//! - **reciprocal condition number** `rcond` = 1 / (‖A‖₁ · ‖A⁻¹‖₁). For
//!   N ≤ [`EXACT_INVERSE_NORM_MAX_N`] the norm of the inverse is computed
//!   exactly from N solves with the factors (cheaper than estimating at that
//!   size); above it, ‖A⁻¹‖₁ is estimated by Hager's method as refined by
//!   Higham (the algorithm of LAPACK `xLACN2`, Higham ch. 15). That estimate
//!   is a lower bound, usually within a factor of 3, so `rcond` is then an
//!   upper bound of the true 1-norm reciprocal condition number.
//!
//! # Accuracy
//!
//! Gaussian elimination with partial pivoting is normwise backward stable
//! up to the growth factor. With u the unit roundoff (half an ulp of 1)
//! and ρ the reported growth, a returned float solution satisfies
//! (Higham, Theorem 9.4 and Lemma 9.6, one extra rounding for the
//! reciprocal pivots included in the constant):
//!
//! ```text
//! ‖b − A x̂‖₁ ≤ residual_bound(n, ρ) · u · ‖A‖₁ · ‖x̂‖₁,
//! residual_bound(n, ρ) = (3n + 1)(1 + 2n²ρ)
//! ```
//!
//! which [`residual_bound`] computes. It is a worst case; random systems
//! stay below 2 (LAPACK's test threshold is 30).
//!
//! Fixed point rounds every operation to the absolute grid step δ = 2⁻ᶠ
//! (u = δ/2) instead of relatively. A returned solution then satisfies
//! ‖b − A x̂‖∞ ≤ [`fixed_residual_bound`] (same n and ρ, with ‖A‖ the
//! largest |aᵢⱼ|), derived the same way with an absolute error per
//! operation.
//!
//!
//! # Refinement and the residual ratio
//!
//! A float solution is checked, and if need be improved, by its **residual
//! ratio**, LAPACK's normwise test ratio with the order n in the
//! denominator:
//!
//! ```text
//! ratio = max over columns j of ‖b_j − A x̂_j‖₁ / (‖A‖₁ · ‖x̂_j‖₁ · n · u)
//! ```
//!
//! with the residual of the stored values formed in a wider precision
//! (f64 for f32, a compensated double-double dot product for f64; see the
//! private `refine` module) and u the unit roundoff (half an ulp of 1,
//! LAPACK's `xLAMCH('E')`). When the ratio exceeds
//! [`REFINE_ABOVE_RATIO`], or the growth makes ρ·n·u exceed 2⁻¹⁰, the
//! solver takes steps of iterative refinement as LAPACK's `xGERFS` does
//! (residual in the wider precision, correction solved with the same
//! factors; at most [`MAX_REFINEMENT_STEPS`], stopping when a step no
//! longer halves the ratio). A well-conditioned system with modest growth
//! takes no step: its only extra cost is the one residual.
//! [`Diagnostics::refinement_steps`] says how many were taken. If the best
//! iterate's ratio is still not below [`RESIDUAL_RATIO_MAX`] = 30 (LAPACK's
//! test threshold), the solve fails with [`SolveError::Inaccurate`]. So a
//! returned float solution has ratio < 30 (as computed by the solver in
//! the wider precision).
//!
//! # Condition threshold: at least one correct digit
//!
//! With κ̂₁ = 1/`rcond` and η = ‖b − A x̂‖₁ / (‖A‖₁ ‖x̂‖₁) the backward
//! error of the returned x̂, its relative forward error against the system
//! the caller meant (the stored entries being the caller's values rounded
//! once, a relative perturbation of u) is bounded, to first order, by
//!
//! ```text
//! ‖x − x̂‖₁ / ‖x̂‖₁ ≤ ferr = κ̂₁ · (η + u)
//! ```
//!
//! (Higham, Theorem 7.2; LAPACK's `FERR` has the same form). A float
//! solution is returned only when ferr ≤ [`SolveConfig::max_forward_error`],
//! by default 1/10: at least one correct decimal digit. Otherwise the
//! result is [`SolveError::IllConditioned`]. Since η ≥ 0, this requires
//! rcond ≥ 10·u = 5ε at the least; the check on u/rcond alone is made
//! before the solve. κ̂₁ is exact for N ≤ [`EXACT_INVERSE_NORM_MAX_N`] (up
//! to rounding) and an estimate from below above it, so there ferr is an
//! estimate (as LAPACK's), usually within a factor of 3.
//!
//! # Fixed point
//!
//! Fixed point is refined the same way (residual exact to 2⁻¹⁰⁶ in
//! double-double, correction on the grid, u = one step); a correction
//! below the grid ends refinement. Because rounding is absolute, a
//! relative residual ratio or forward-error bound is not a meaningful
//! guarantee for small solutions; fixed point therefore keeps only the
//! [`SolveConfig::rcond_min`] threshold and the absolute bound
//! [`fixed_residual_bound`], and never reports [`SolveError::Inaccurate`].
//! This is a stated limit, not a guarantee of a ratio below 30.
//!
//! # Errors
//!
//! See [`SolveError`]. In short: an exactly zero pivot is
//! [`SolveError::Singular`] with the column where elimination failed;
//! `rcond` below [`SolveConfig::rcond_min`] (by default the scalar's
//! [`EPSILON`](Scalar::EPSILON), as `xGESVX` warns when `RCOND < ε`), or
//! a forward-error bound above [`SolveConfig::max_forward_error`], is
//! [`SolveError::IllConditioned`]; a residual ratio that refinement cannot
//! bring below 30 is [`SolveError::Inaccurate`]; an overflowing or
//! non-finite intermediate (fixed-point saturation, float ±∞) is
//! [`SolveError::Overflow`]; NaN or ±∞ in the input is
//! [`SolveError::NonFinite`]. A returned solution never contains NaN, ±∞
//! or a saturated value.

// Index loops mirror the textbook's elimination and substitution formulas.
#![allow(clippy::needless_range_loop)]
// `!(a <= b)` on purpose: a NaN figure must fail the check.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::scalar::Scalar;
use core::fmt;

mod refine;
pub use refine::{MAX_REFINEMENT_STEPS, REFINE_ABOVE_RATIO, RESIDUAL_RATIO_MAX};
mod condition;
pub use condition::EXACT_INVERSE_NORM_MAX_N;
mod inverse;
pub use inverse::{invert, invert_affine};

/// Why a system could not be solved.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum SolveError {
    /// Elimination met an exactly zero pivot column: no row at or below the
    /// diagonal of `column` (0-based) has a non-zero entry. The matrix is
    /// singular in exact arithmetic on the stored values.
    Singular {
        /// The 0-based column where elimination failed.
        column: usize,
    },
    /// The estimated reciprocal condition number is below
    /// [`SolveConfig::rcond_min`], or the forward-error bound κ̂₁·(η + u) of
    /// the module docs exceeds [`SolveConfig::max_forward_error`] (floats):
    /// the matrix is singular to working precision, and a solution would
    /// not carry the requested correct digits.
    IllConditioned {
        /// The estimate (upper bound) of 1 / κ₁(A), rounded to f32.
        rcond: f32,
    },
    /// An intermediate or the solution overflowed the representation: a
    /// fixed-point product or quotient that would have saturated, or a float
    /// that became ±∞ (for both, including ‖A‖₁, the largest column sum of
    /// |A|).
    Overflow,
    /// The input contains NaN or ±∞.
    NonFinite,
    /// Floats only: even after iterative refinement, the residual ratio
    /// ‖b − A x̂‖₁ / (‖A‖₁ ‖x̂‖₁ n u) of the best iterate (module docs) is
    /// not below [`RESIDUAL_RATIO_MAX`] = 30. The factorization is too
    /// inaccurate (pivot growth near 1/u) for refinement to converge, so no
    /// solution backward stable to LAPACK's standard exists from it.
    Inaccurate {
        /// The residual ratio of the best iterate, rounded to f32 (∞ if it
        /// could not be formed in range).
        ratio: f32,
    },
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Singular { column } => {
                write!(f, "matrix is singular: zero pivot in column {column}")
            }
            Self::IllConditioned { rcond } => write!(
                f,
                "matrix is singular to working precision (reciprocal condition number {rcond:e})"
            ),
            Self::Overflow => f.write_str("arithmetic overflow during elimination"),
            Self::NonFinite => f.write_str("input contains NaN or infinity"),
            Self::Inaccurate { ratio } => write!(
                f,
                "solution inaccurate after refinement (residual ratio {ratio:e}, limit 30)"
            ),
        }
    }
}

impl core::error::Error for SolveError {}

/// What the solver measured about the system it solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnostics<S> {
    /// Pivot growth factor ρ ≥ 1 (Higham §9.3); 2ⁿ⁻¹ at worst with partial
    /// pivoting.
    pub growth: S,
    /// Estimated reciprocal condition number in the 1-norm, in (0, 1].
    pub rcond: S,
    /// ‖A‖₁, the maximum absolute column sum.
    pub norm1: S,
    /// Steps of iterative refinement taken (0 when the first solution's
    /// residual ratio was at most [`REFINE_ABOVE_RATIO`] and growth was
    /// modest), at most [`MAX_REFINEMENT_STEPS`].
    pub refinement_steps: u8,
    /// The residual ratio of the returned solution (module docs), rounded
    /// to f32; below 30 for floats.
    pub residual_ratio: f32,
    /// The forward-error bound κ̂₁·(η + u) of the module docs, rounded to
    /// f32 (for fixed point computed the same way, with u one step, and
    /// informative only).
    pub forward_error: f32,
}

/// A solution with its diagnostics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<S, const N: usize, const M: usize> {
    /// `X`, N rows by M columns.
    pub x: [[S; M]; N],
    /// Growth and condition estimates.
    pub diagnostics: Diagnostics<S>,
}

/// Thresholds for [`solve_with`]. Build it with struct update syntax,
/// e.g. `SolveConfig { rcond_min: x, ..SolveConfig::default() }`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveConfig<S> {
    /// Systems whose `rcond` estimate is below this are rejected with
    /// [`SolveError::IllConditioned`]. Zero disables this check.
    pub rcond_min: S,
    /// Float solutions whose forward-error bound κ̂₁·(η + u) (module docs)
    /// exceeds this are rejected with [`SolveError::IllConditioned`]. The
    /// default 1/10 guarantees one correct digit; `f32::INFINITY` disables
    /// the check. Ignored for fixed point.
    pub max_forward_error: f32,
}

impl<S: Scalar> Default for SolveConfig<S> {
    fn default() -> Self {
        Self {
            rcond_min: S::EPSILON,
            max_forward_error: 0.1,
        }
    }
}

impl<S: Scalar> SolveConfig<S> {
    /// No condition check at all: any system that factors without a zero
    /// pivot or overflow is solved (the residual-ratio check,
    /// [`SolveError::Inaccurate`], still applies).
    #[must_use]
    pub fn unchecked() -> Self {
        Self {
            rcond_min: S::ZERO,
            max_forward_error: f32::INFINITY,
        }
    }
}

/// An LU factorization `P A = L U` with unit lower-triangular `L`, kept in
/// one array as LAPACK does, plus the permutation and the growth factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lu<S, const N: usize> {
    lu: [[S; N]; N],
    /// Row `i` of `P A` is row `perm[i]` of `A`.
    perm: [usize; N],
    /// `1/uᵢᵢ` for floats; unused (ones) for fixed point.
    inv_diag: [S; N],
    /// Largest |entry| met during elimination, and of A: ρ is their ratio.
    max_seen: S,
    max_a: S,
    norm1: S,
}

/// Solves `A X = B` with the default [`SolveConfig`].
///
/// # Errors
/// See the [module docs](self) and [`SolveError`].
///
/// # Examples
/// ```
/// use sightline::solve::solve;
/// let a = [[2.0f64, 1.0], [1.0, 3.0]];
/// let b = [[3.0], [5.0]];
/// let s = solve(&a, &b).unwrap();
/// assert!((s.x[0][0] - 0.8).abs() < 1e-15 && (s.x[1][0] - 1.4).abs() < 1e-15);
/// ```
pub fn solve<S: Scalar, const N: usize, const M: usize>(
    a: &[[S; N]; N],
    b: &[[S; M]; N],
) -> Result<Solution<S, N, M>, SolveError> {
    solve_with(a, b, &SolveConfig::default())
}

/// Solves `A X = B` with explicit thresholds.
///
/// # Errors
/// See the [module docs](self) and [`SolveError`].
pub fn solve_with<S: Scalar, const N: usize, const M: usize>(
    a: &[[S; N]; N],
    b: &[[S; M]; N],
    config: &SolveConfig<S>,
) -> Result<Solution<S, N, M>, SolveError> {
    if !all_finite(b) {
        return Err(SolveError::NonFinite);
    }
    let lu = Lu::factor(a)?;
    let rcond = lu.rcond();
    let ill = SolveError::IllConditioned {
        rcond: rcond.to_f32(),
    };
    if rcond < config.rcond_min {
        return Err(ill);
    }
    let u = refine::unit_roundoff::<S>();
    let max_ferr = f64::from(config.max_forward_error);
    // ferr ≥ u/rcond whatever the residual: reject before solving.
    if S::IS_FLOAT && !(u / rcond.to_f64() <= max_ferr) {
        return Err(ill);
    }
    let x = lu.solve_finite(b)?;
    let checked = refine::refine(a, b, &lu, x);
    if S::IS_FLOAT && !(checked.ratio < RESIDUAL_RATIO_MAX) {
        return Err(SolveError::Inaccurate {
            ratio: checked.ratio as f32,
        });
    }
    let ferr = (checked.backward + u) / rcond.to_f64();
    if S::IS_FLOAT && !(ferr <= max_ferr) {
        return Err(ill);
    }
    Ok(Solution {
        x: checked.x,
        diagnostics: Diagnostics {
            growth: lu.growth(),
            rcond,
            norm1: lu.norm1,
            refinement_steps: checked.steps,
            residual_ratio: checked.ratio as f32,
            forward_error: ferr as f32,
        },
    })
}

impl<S: Scalar, const N: usize> Lu<S, N> {
    /// Factors `A` by Gaussian elimination with partial pivoting (the first
    /// row of largest magnitude in the column is chosen, so ties resolve
    /// deterministically).
    ///
    /// # Errors
    /// [`SolveError::NonFinite`] for NaN/±∞ input, [`SolveError::Singular`]
    /// for a zero pivot column, [`SolveError::Overflow`] when an update
    /// overflows.
    #[inline(always)]
    pub fn factor(a: &[[S; N]; N]) -> Result<Self, SolveError> {
        let mut lu = *a;
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        if !all_finite(a) {
            return Err(SolveError::NonFinite);
        }
        let mut max_a = S::ZERO;
        let mut norm1 = S::ZERO;
        for j in 0..N {
            let mut col = S::ZERO;
            for row in a {
                let v = row[j].abs();
                max_a = max_a.max_of(v);
                col += v;
            }
            norm1 = norm1.max_of(col);
        }
        // Fixed point: a column sum of |A| beyond the range saturates, and
        // then no condition number can be formed; report it rather than
        // return diagnostics computed from a clipped norm.
        // Floats: likewise when it overflows to ∞ (entries near the range),
        // which would otherwise make rcond 0 and misreport a
        // well-conditioned matrix as ill-conditioned.
        if (!S::IS_FLOAT && norm1 == S::MAX) || !norm1.is_finite() {
            return Err(SolveError::Overflow);
        }
        let mut max_seen = max_a;
        let mut overflow = false;
        let mut inv_diag = [S::ONE; N];
        for k in 0..N {
            // Partial pivoting: the largest |a_ik| for i ≥ k.
            let mut p = k;
            let mut best = lu[k][k].abs();
            for (i, row) in lu.iter().enumerate().skip(k + 1) {
                let v = row[k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best == S::ZERO {
                return Err(SolveError::Singular { column: k });
            }
            if p != k {
                lu.swap(p, k);
                perm.swap(p, k);
            }
            let (top, bottom) = lu.split_at_mut(k + 1);
            let pivot_row = &top[k];
            let pivot = pivot_row[k];
            // Floats: one division per column, then multiplications (the
            // reciprocal is kept for the substitutions). Fixed point divides
            // per entry: 1/pivot can overflow where each quotient cannot.
            if S::IS_FLOAT {
                inv_diag[k] = S::ONE / pivot;
            }
            for row in bottom.iter_mut() {
                // |l| ≤ 1 (within an ulp) by the pivot choice, so this never
                // overflows.
                let l = if S::IS_FLOAT {
                    row[k] * inv_diag[k]
                } else {
                    row[k] / pivot
                };
                row[k] = l;
                for j in k + 1..N {
                    let v = row[j].sub_mul_noting_overflow(l, pivot_row[j], &mut overflow);
                    row[j] = v;
                    max_seen = max_seen.max_of(v.abs());
                }
            }
        }
        if overflow || !max_seen.is_finite() {
            return Err(SolveError::Overflow);
        }
        Ok(Self {
            lu,
            perm,
            inv_diag,
            max_seen,
            max_a,
            norm1,
        })
    }

    /// The pivot growth factor ρ = max|a⁽ᵏ⁾| / max|a| of the factorization
    /// (computed on request; `max|a| > 0` since a zero matrix is singular).
    #[must_use]
    pub fn growth(&self) -> S {
        self.max_seen / self.max_a
    }

    /// ‖A‖₁ of the factored matrix.
    #[must_use]
    pub fn norm1(&self) -> S {
        self.norm1
    }

    /// Solves `A X = B` with the factors.
    ///
    /// # Errors
    /// [`SolveError::NonFinite`] for NaN/±∞ in `B`, [`SolveError::Overflow`]
    /// if a value of the solution overflows.
    pub fn solve<const M: usize>(&self, b: &[[S; M]; N]) -> Result<[[S; M]; N], SolveError> {
        if !all_finite(b) {
            return Err(SolveError::NonFinite);
        }
        self.solve_finite(b)
    }

    /// [`Self::solve`] for a `B` already known to be finite.
    fn solve_finite<const M: usize>(&self, b: &[[S; M]; N]) -> Result<[[S; M]; N], SolveError> {
        let mut x = [[S::ZERO; M]; N];
        for (xi, &pi) in x.iter_mut().zip(self.perm.iter()) {
            *xi = b[pi];
        }
        let mut overflow = false;
        self.substitute(&mut x, &mut overflow);
        if overflow || !all_finite(&x) {
            return Err(SolveError::Overflow);
        }
        Ok(x)
    }

    /// Forward substitution with unit `L`, then back substitution with `U`,
    /// in place on an already permuted right-hand side.
    fn substitute<const M: usize>(&self, x: &mut [[S; M]; N], overflow: &mut bool) {
        for i in 1..N {
            let (done, rest) = x.split_at_mut(i);
            let xi = &mut rest[0];
            for (j, xj) in done.iter().enumerate() {
                let l = self.lu[i][j];
                for c in 0..M {
                    xi[c] = xi[c].sub_mul_noting_overflow(l, xj[c], overflow);
                }
            }
        }
        for i in (0..N).rev() {
            let (head, tail) = x.split_at_mut(i + 1);
            let xi = &mut head[i];
            for (j, xj) in tail.iter().enumerate() {
                let u = self.lu[i][i + 1 + j];
                for c in 0..M {
                    xi[c] = xi[c].sub_mul_noting_overflow(u, xj[c], overflow);
                }
            }
            for v in xi.iter_mut() {
                *v = self.divide_by_pivot(*v, i, overflow);
            }
        }
    }

    /// `v / uᵢᵢ`. Floats multiply by the reciprocal computed once per
    /// pivot (one division instead of M; a second rounding that leaves the
    /// backward error bound of the same order, and keeps power-of-two
    /// scaling exact). Fixed point divides, so a tiny pivot cannot overflow
    /// a reciprocal that the quotient itself would not.
    #[inline]
    fn divide_by_pivot(&self, v: S, i: usize, overflow: &mut bool) -> S {
        if S::IS_FLOAT {
            v * self.inv_diag[i]
        } else {
            v.div_noting_overflow(self.lu[i][i], overflow)
        }
    }
}

/// The normwise backward-error constant of the module docs:
/// `(3n + 1)(1 + 2n²ρ)`. A float solution satisfies `‖b − Ax̂‖₁ ≤
/// residual_bound(n, ρ) · u · ‖A‖₁ · ‖x̂‖₁` with u half an ulp of 1.
#[must_use]
pub fn residual_bound(n: usize, growth: f64) -> f64 {
    let n = n as f64;
    (3.0 * n + 1.0) * (1.0 + 2.0 * n * n * growth)
}

/// The absolute residual bound for fixed point (see the module docs): a
/// solution of an n×n system with growth ρ, largest entry `max_a` and
/// largest solution entry `max_x`, on a grid of step `delta`, satisfies
/// `‖b − Ax̂‖∞ ≤ (3n + 1)(1 + 2n·ρ·max_a)(1 + n·max_x)·delta`: each of the
/// O(n) roundings met by an entry of L·U or of the substitutions is at
/// most δ/2 absolute, and is multiplied by at most ρ·max_a (an entry of U)
/// or by a solution entry.
#[must_use]
pub fn fixed_residual_bound(n: usize, growth: f64, max_a: f64, max_x: f64, delta: f64) -> f64 {
    let n = n as f64;
    (3.0 * n + 1.0) * (1.0 + 2.0 * n * growth * max_a) * (1.0 + n * max_x) * delta
}

/// Whether every entry is finite, without a branch per entry: `0·x` is 0
/// for finite x and NaN for ±∞ and NaN, and the sum of those is NaN exactly
/// when one of them is (it cannot overflow). Fixed point is always finite.
#[inline]
fn all_finite<S: Scalar, const R: usize, const C: usize>(m: &[[S; C]; R]) -> bool {
    if !S::IS_FLOAT {
        return true;
    }
    let mut acc = S::ZERO;
    for row in m {
        for &v in row {
            acc += v * S::ZERO;
        }
    }
    acc == S::ZERO
}

fn sum_abs<S: Scalar, const N: usize>(v: &[S; N]) -> Option<S> {
    let mut s = S::ZERO;
    for x in v {
        s = s.checked_add(x.abs())?;
    }
    Some(s)
}

#[cfg(test)]
mod tests;

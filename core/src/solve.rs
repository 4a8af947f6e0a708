//! Gaussian elimination with partial pivoting for `A X = B`, with `A` of
//! size N×N and `B` of M columns (const generics, no allocation), returning
//! the solution together with the diagnostics a caller needs to trust it.
//!
//! This generalises the viewing-process chapter's routine, which solves
//! `A X = B` for an `m`-column `B`, and follows LAPACK's expert driver
//! `xGESVX` in what it reports:
//!
//! - **pivot growth** ρ = maxₖ maxᵢⱼ |aᵢⱼ⁽ᵏ⁾| / maxᵢⱼ |aᵢⱼ|, the growth factor
//!   of Higham, *Accuracy and Stability of Numerical Algorithms* (2nd ed.),
//!   §9.3. Backward error is bounded by a small multiple of ρ·n·ε; partial
//!   pivoting allows ρ up to 2ⁿ⁻¹ (Wilkinson's matrix reaches it).
//! - **reciprocal condition number** `rcond` = 1 / (‖A‖₁ · est‖A⁻¹‖₁), with
//!   ‖A⁻¹‖₁ estimated by Hager's method as refined by Higham (the algorithm
//!   of LAPACK `xLACN2`, Higham ch. 15). The estimate of ‖A⁻¹‖₁ is a lower
//!   bound, usually within a factor of 3, so `rcond` is an upper bound of
//!   the true 1-norm reciprocal condition number.
//!
//! # Errors
//!
//! See [`SolveError`]. In short: an exactly zero pivot is
//! [`SolveError::Singular`] with the column where elimination failed;
//! `rcond` below the threshold (by default the scalar's
//! [`EPSILON`](Scalar::EPSILON), as `xGESVX` warns when `RCOND < ε`) is
//! [`SolveError::IllConditioned`]; an overflowing or non-finite intermediate
//! (fixed-point saturation, float ±∞) is [`SolveError::Overflow`]; NaN or ±∞
//! in the input is [`SolveError::NonFinite`]. A returned solution never
//! contains NaN, ±∞ or a saturated value.

use crate::scalar::Scalar;
use core::fmt;

/// Why a system could not be solved.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolveError {
    /// Elimination met an exactly zero pivot column: no row at or below the
    /// diagonal of `column` (0-based) has a non-zero entry. The matrix is
    /// singular in exact arithmetic on the stored values.
    Singular {
        /// The 0-based column where elimination failed.
        column: usize,
    },
    /// The estimated reciprocal condition number is below the threshold: the
    /// matrix is singular to working precision, and a solution would carry
    /// no correct digits.
    IllConditioned {
        /// The estimate (upper bound) of 1 / κ₁(A), rounded to f32.
        rcond: f32,
    },
    /// An intermediate or the solution overflowed the representation: a
    /// fixed-point product or quotient that would have saturated, or a float
    /// that became ±∞.
    Overflow,
    /// The input contains NaN or ±∞.
    NonFinite,
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Singular { column } => {
                write!(f, "matrix is singular: zero pivot in column {column}")
            }
            Self::IllConditioned { rcond } => write!(
                f,
                "matrix is singular to working precision (reciprocal condition estimate {rcond:e})"
            ),
            Self::Overflow => f.write_str("arithmetic overflow during elimination"),
            Self::NonFinite => f.write_str("input contains NaN or infinity"),
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
}

/// A solution with its diagnostics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<S, const N: usize, const M: usize> {
    /// `X`, N rows by M columns.
    pub x: [[S; M]; N],
    /// Growth and condition estimates.
    pub diagnostics: Diagnostics<S>,
}

/// Thresholds for [`solve_with`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveConfig<S> {
    /// Systems whose `rcond` estimate is below this are rejected with
    /// [`SolveError::IllConditioned`]. Zero disables the check.
    pub rcond_min: S,
}

impl<S: Scalar> Default for SolveConfig<S> {
    fn default() -> Self {
        Self {
            rcond_min: S::EPSILON,
        }
    }
}

/// An LU factorisation `P A = L U` with unit lower-triangular `L`, kept in
/// one array as LAPACK does, plus the permutation and the growth factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lu<S, const N: usize> {
    lu: [[S; N]; N],
    /// Row `i` of `P A` is row `perm[i]` of `A`.
    perm: [usize; N],
    growth: S,
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
    if !b.iter().flatten().all(|v| v.is_finite()) {
        return Err(SolveError::NonFinite);
    }
    let lu = Lu::factor(a)?;
    let rcond = lu.rcond();
    if rcond < config.rcond_min {
        return Err(SolveError::IllConditioned {
            rcond: rcond.to_f32(),
        });
    }
    let x = lu.solve(b)?;
    Ok(Solution {
        x,
        diagnostics: Diagnostics {
            growth: lu.growth,
            rcond,
            norm1: lu.norm1,
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
    pub fn factor(a: &[[S; N]; N]) -> Result<Self, SolveError> {
        let mut lu = *a;
        let mut perm = [0usize; N];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let mut max_a = S::ZERO;
        for row in a {
            for &v in row {
                if !v.is_finite() {
                    return Err(SolveError::NonFinite);
                }
                max_a = max_a.max_of(v.abs());
            }
        }
        let norm1 = norm1(a);
        let mut max_seen = max_a;
        let mut overflow = false;
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
            for row in bottom.iter_mut() {
                // |l| ≤ 1 by the pivot choice, so this never overflows.
                let l = row[k] / pivot;
                row[k] = l;
                if l == S::ZERO {
                    continue;
                }
                for j in k + 1..N {
                    let v = row[j].sub_mul_flag(l, pivot_row[j], &mut overflow);
                    row[j] = v;
                    max_seen = max_seen.max_of(v.abs());
                }
            }
        }
        if overflow || !max_seen.is_finite() {
            return Err(SolveError::Overflow);
        }
        // ρ = max|a⁽ᵏ⁾| / max|a|; max_a > 0 here (else column 0 was zero).
        let growth = max_seen / max_a;
        Ok(Self {
            lu,
            perm,
            growth,
            norm1,
        })
    }

    /// The pivot growth factor ρ of the factorisation.
    #[must_use]
    pub fn growth(&self) -> S {
        self.growth
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
        let mut x = [[S::ZERO; M]; N];
        for (xi, &pi) in x.iter_mut().zip(self.perm.iter()) {
            *xi = b[pi];
            if !xi.iter().all(|v| v.is_finite()) {
                return Err(SolveError::NonFinite);
            }
        }
        let mut overflow = false;
        // Forward substitution with unit L.
        for i in 1..N {
            let (done, rest) = x.split_at_mut(i);
            let xi = &mut rest[0];
            for (j, xj) in done.iter().enumerate() {
                let l = self.lu[i][j];
                if l == S::ZERO {
                    continue;
                }
                for c in 0..M {
                    xi[c] = xi[c].sub_mul_flag(l, xj[c], &mut overflow);
                }
            }
        }
        // Back substitution with U.
        for i in (0..N).rev() {
            let (head, tail) = x.split_at_mut(i + 1);
            let xi = &mut head[i];
            for (j, xj) in tail.iter().enumerate() {
                let u = self.lu[i][i + 1 + j];
                if u == S::ZERO {
                    continue;
                }
                for c in 0..M {
                    xi[c] = xi[c].sub_mul_flag(u, xj[c], &mut overflow);
                }
            }
            let d = self.lu[i][i];
            for v in xi.iter_mut() {
                *v = v.div_flag(d, &mut overflow);
            }
        }
        if overflow || !x.iter().flatten().all(|v| v.is_finite()) {
            return Err(SolveError::Overflow);
        }
        Ok(x)
    }

    /// Solves `Aᵀ z = c` with the same factors: `Uᵀ w = c`, `Lᵀ v = w`,
    /// `z = Pᵀ v`. Returns `None` on overflow.
    #[allow(clippy::needless_range_loop)] // index form mirrors the LU algebra
    fn solve_transposed(&self, c: &[S; N]) -> Option<[S; N]> {
        let mut overflow = false;
        let mut w = *c;
        for i in 0..N {
            let mut acc = w[i];
            for j in 0..i {
                acc = acc.sub_mul_flag(self.lu[j][i], w[j], &mut overflow);
            }
            w[i] = acc.div_flag(self.lu[i][i], &mut overflow);
        }
        for i in (0..N).rev() {
            let mut acc = w[i];
            for j in i + 1..N {
                acc = acc.sub_mul_flag(self.lu[j][i], w[j], &mut overflow);
            }
            w[i] = acc;
        }
        let mut z = [S::ZERO; N];
        for (i, &p) in self.perm.iter().enumerate() {
            z[p] = w[i];
        }
        (!overflow && z.iter().all(|v| v.is_finite())).then_some(z)
    }

    fn solve_vec(&self, b: &[S; N]) -> Option<[S; N]> {
        let mut bb = [[S::ZERO; 1]; N];
        for (d, s) in bb.iter_mut().zip(b.iter()) {
            d[0] = *s;
        }
        let x = self.solve(&bb).ok()?;
        let mut out = [S::ZERO; N];
        for (d, s) in out.iter_mut().zip(x.iter()) {
            *d = s[0];
        }
        Some(out)
    }

    /// Estimate of ‖A⁻¹‖₁ by Hager's method with Higham's refinements
    /// (LAPACK `xLACN2`): at most 5 iterations of the sign-vector ascent,
    /// then the alternative vector xᵢ = (−1)ⁱ(1 + i/(n−1)) guards against
    /// the ascent's known counter-examples. Returns `None` if a solve
    /// overflows (the matrix is then singular to working precision).
    fn inverse_norm1_estimate(&self) -> Option<S> {
        if N == 0 {
            return Some(S::ZERO);
        }
        let n = S::from_i32(N as i32);
        let mut x = [S::ONE / n; N];
        let mut est = S::ZERO;
        let mut xi_prev = [S::ZERO; N];
        for iter in 0..5 {
            let y = self.solve_vec(&x)?;
            est = sum_abs(&y)?;
            let mut xi = [S::ONE; N];
            for (s, v) in xi.iter_mut().zip(y.iter()) {
                if *v < S::ZERO {
                    *s = -S::ONE;
                }
            }
            if iter > 0 && xi == xi_prev {
                break;
            }
            xi_prev = xi;
            let z = self.solve_transposed(&xi)?;
            let mut j = 0;
            let mut zmax = z[0].abs();
            for (i, v) in z.iter().enumerate().skip(1) {
                if v.abs() > zmax {
                    zmax = v.abs();
                    j = i;
                }
            }
            if iter > 0 {
                let mut ztx = S::ZERO;
                for (a, b) in z.iter().zip(x.iter()) {
                    ztx += *a * *b;
                }
                if zmax <= ztx {
                    break;
                }
            }
            x = [S::ZERO; N];
            x[j] = S::ONE;
        }
        // Higham's alternative estimate, 2‖A⁻¹ x‖₁ / (3n).
        let mut alt = [S::ZERO; N];
        let denom = S::from_i32((N as i32 - 1).max(1));
        for (i, v) in alt.iter_mut().enumerate() {
            let mag = S::ONE + S::from_i32(i as i32) / denom;
            *v = if i % 2 == 0 { mag } else { -mag };
        }
        let y = self.solve_vec(&alt)?;
        let alt_est = S::TWO * sum_abs(&y)? / (S::from_i32(3) * n);
        Some(est.max_of(alt_est))
    }

    /// Estimated reciprocal condition number 1 / (‖A‖₁ · est‖A⁻¹‖₁) in
    /// [0, 1]. Zero when the estimate overflows the representation.
    #[must_use]
    pub fn rcond(&self) -> S {
        let Some(inv) = self.inverse_norm1_estimate() else {
            return S::ZERO;
        };
        if inv == S::ZERO || self.norm1 == S::ZERO {
            return S::ZERO;
        }
        // Divide twice rather than multiply the norms: the product may
        // overflow (fixed point) where the quotient is representable.
        match S::ONE
            .checked_div(self.norm1)
            .and_then(|r| r.checked_div(inv))
        {
            Some(r) => r.min_of(S::ONE),
            None => S::ZERO,
        }
    }
}

/// ‖A‖₁: maximum absolute column sum (saturating for fixed point).
fn norm1<S: Scalar, const N: usize>(a: &[[S; N]; N]) -> S {
    let mut best = S::ZERO;
    for j in 0..N {
        let mut s = S::ZERO;
        for row in a {
            s += row[j].abs();
        }
        best = best.max_of(s);
    }
    best
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

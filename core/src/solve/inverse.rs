//! Matrix inverses through the pivoting solver, with its diagnostics.
//!
//! [`Mat3::try_inverse`] (in [`crate::math`], which sits below this
//! module and uses no solver) is the cheap adjugate inverse that says only
//! *whether* it succeeded; these say *why not* ([`SolveError`]) and how
//! well conditioned the matrix was ([`Diagnostics`](super::Diagnostics)).

use super::{Solution, SolveError, solve};
use crate::math::{Affine3, Mat3};
use crate::scalar::Scalar;

/// `A⁻¹` by Gaussian elimination with partial pivoting on `A X = I`,
/// with the solver's diagnostics.
///
/// # Errors
/// Whatever [`solve`] reports: singular, ill-conditioned to working
/// precision, overflow or non-finite input.
///
/// # Examples
/// ```
/// use sightline::solve::invert;
/// let a = [[4.0f64, 0.0], [0.0, 0.5]];
/// assert_eq!(invert(&a).unwrap().x, [[0.25, 0.0], [0.0, 2.0]]);
/// ```
pub fn invert<S: Scalar, const N: usize>(a: &[[S; N]; N]) -> Result<Solution<S, N, N>, SolveError> {
    let mut id = [[S::ZERO; N]; N];
    for (i, row) in id.iter_mut().enumerate() {
        row[i] = S::ONE;
    }
    solve(a, &id)
}

/// The inverse transform `p ↦ M⁻¹(p − t)`, with `M⁻¹` from [`invert`].
///
/// # Errors
/// As [`invert`]; [`SolveError::Overflow`] when the new translation is
/// not finite.
pub fn invert_affine<S: Scalar>(a: &Affine3<S>) -> Result<Affine3<S>, SolveError> {
    let inv = Mat3 {
        m: invert(&a.matrix.m)?.x,
    };
    let t = -inv.mul_vec3(a.translation);
    if t.is_finite() {
        Ok(Affine3::new(inv, t))
    } else {
        Err(SolveError::Overflow)
    }
}

//! The arithmetic of a Dormand–Prince step, written once over [`Real`]: one trajectory
//! (`f64`, as [`Dopri54`](super::Dopri54) steps) or four lanes side by side
//! ([`F64x4`](crate::lanes::F64x4), as the batch engine steps), lane by lane the same IEEE
//! operations in the same order.
//! The stage times and the step-size controller's factors are here too, for the same reason.
//! `k1` is the derivative at the step's start and `k` the stages k2..k7 (k7 at the 5th-order
//! solution, FSAL).

use super::{
    A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64, A65, A71, A73, A74, A75,
    A76, C2, C3, C4, C5, D1, D3, D4, D5, D6, D7, E1, E3, E4, E5, E6, E7,
};
use crate::lanes::{exp, Real};

/// The step-size controller's growth after an accepted attempt, before its safety factor
/// and clamps: `err_prev^β / err^α` (α = 0.2 − 0.75 β), from the two error norms' logarithms;
/// on lanes, so that the batch computes four attempts' at once, by the same operations.
#[inline(always)]
pub fn growth<S: Real>(beta: S, ln_err_prev: S, ln_err: S) -> S {
    exp(beta * ln_err_prev - alpha(beta) * ln_err)
}

/// The controller's shrinkage after a rejected attempt, before its safety factor: `err^α`.
#[inline(always)]
pub fn shrinkage<S: Real>(beta: S, ln_err: S) -> S {
    exp(alpha(beta) * ln_err)
}

/// The controller's exponent of the error, `α = 0.2 − 0.75 β` (β: of the previous error).
#[inline(always)]
fn alpha<S: Real>(beta: S) -> S {
    S::splat(0.2) - S::splat(0.75) * beta
}

/// Time of stage `stage` (0..6 for k2..k7) of attempts from `t` of step `h` ending at
/// `t_end`, on lanes: the single flight's stepper and the batch's four attempts side by side
/// compute it here.
#[inline(always)]
pub fn stage_time<S: Real>(stage: usize, t: S, h: S, t_end: S) -> S {
    let c = match stage {
        0 => C2,
        1 => C3,
        2 => C4,
        3 => C5,
        _ => return t_end,
    };
    t + S::splat(c) * h
}

/// The state of stage `stage` (0..6 for k2..k7) from the stages before it.
#[inline(always)]
pub fn stage_state<S: Real, const N: usize>(
    stage: usize,
    h: S,
    y: &[S; N],
    k1: &[S; N],
    k: &[[S; N]; 6],
    ys: &mut [S; N],
) {
    let c = S::splat;
    match stage {
        0 => {
            for i in 0..N {
                ys[i] = y[i] + h * c(A21) * k1[i];
            }
        }
        1 => {
            for i in 0..N {
                ys[i] = y[i] + h * (c(A31) * k1[i] + c(A32) * k[0][i]);
            }
        }
        2 => {
            for i in 0..N {
                ys[i] = y[i] + h * (c(A41) * k1[i] + c(A42) * k[0][i] + c(A43) * k[1][i]);
            }
        }
        3 => {
            for i in 0..N {
                ys[i] = y[i]
                    + h * (c(A51) * k1[i] + c(A52) * k[0][i] + c(A53) * k[1][i] + c(A54) * k[2][i]);
            }
        }
        4 => {
            for i in 0..N {
                ys[i] = y[i]
                    + h * (c(A61) * k1[i]
                        + c(A62) * k[0][i]
                        + c(A63) * k[1][i]
                        + c(A64) * k[2][i]
                        + c(A65) * k[3][i]);
            }
        }
        _ => {
            for i in 0..N {
                ys[i] = y[i]
                    + h * (c(A71) * k1[i]
                        + c(A73) * k[1][i]
                        + c(A74) * k[2][i]
                        + c(A75) * k[3][i]
                        + c(A76) * k[4][i]);
            }
        }
    }
}

/// The sum over the components of `(e_i / (atol_i + rtol·max(|y_i|, |y_new_i|)))²`, `e`
/// the difference of the 5th- and 4th-order solutions (the error norm is
/// `sqrt(sum / N)`).
#[inline(always)]
pub fn error_sum<S: Real, const N: usize>(
    h: S,
    y: &[S; N],
    y_new: &[S; N],
    k1: &[S; N],
    k: &[[S; N]; 6],
    atol: &[S; N],
    rtol: S,
) -> S {
    let c = S::splat;
    let [_, k3, k4, k5, k6, k7] = k;
    let mut sum = c(0.0);
    for i in 0..N {
        let e = h
            * (c(E1) * k1[i]
                + c(E3) * k3[i]
                + c(E4) * k4[i]
                + c(E5) * k5[i]
                + c(E6) * k6[i]
                + c(E7) * k7[i]);
        let sk = atol[i] + rtol * y[i].abs().max(y_new[i].abs());
        let q = e / sk;
        sum = sum + q * q;
    }
    sum
}

/// The dense-output coefficients of an accepted step from `y` to `y_new`.
#[inline(always)]
pub fn dense_coefficients<S: Real, const N: usize>(
    h: S,
    y: &[S; N],
    y_new: &[S; N],
    k1: &[S; N],
    k: &[[S; N]; 6],
    cont: &mut [[S; N]; 4],
) {
    let c = S::splat;
    let [_, k3, k4, k5, k6, k7] = k;
    for i in 0..N {
        let ydiff = y_new[i] - y[i];
        let bspl = h * k1[i] - ydiff;
        cont[0][i] = ydiff;
        cont[1][i] = bspl;
        cont[2][i] = ydiff - h * k7[i] - bspl;
        cont[3][i] = h
            * (c(D1) * k1[i]
                + c(D3) * k3[i]
                + c(D4) * k4[i]
                + c(D5) * k5[i]
                + c(D6) * k6[i]
                + c(D7) * k7[i]);
    }
}

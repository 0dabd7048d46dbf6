//! Least-squares fits of a polynomial basis at a patch's points, as
//! linear operators on the fitted values: the pseudo-inverse `A⁺` through
//! the eigenvalues of `AᵀA` (those below `1e-12` of the largest dropped:
//! degenerate patches), the fit `V A⁺` at other points and its residual
//! `I − A A⁺` ([`super::spr`], [`super::free_faces`]).

use faer::Mat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd;

/// `A⁺`, the least-squares operator (`n × m`, row-major) of a basis
/// evaluated at `m` points (`a`, rows of `n`).
fn pseudo_inverse(a: &[f64], n: usize) -> Vec<f64> {
    let m = a.len() / n;
    // (AᵀA)⁺ = Q Λ⁺ Qᵀ
    let mut gram_pinv = vec![0.0; n * n];
    if let Some((q, lambda)) = gram_eigen(a, n) {
        let largest = lambda.iter().copied().fold(0.0f64, f64::max);
        for l in (0..n).filter(|&l| lambda[l] > 1e-12 * largest) {
            for i in 0..n {
                for j in 0..n {
                    gram_pinv[i * n + j] += q[(i, l)] * q[(j, l)] / lambda[l];
                }
            }
        }
    }
    // A⁺ = (AᵀA)⁺ Aᵀ
    let mut out = vec![0.0; n * m];
    for i in 0..n {
        for p in 0..m {
            out[i * m + p] = (0..n).map(|j| gram_pinv[i * n + j] * a[p * n + j]).sum();
        }
    }
    out
}

/// The eigenvalues `Λ` and eigenvectors `Q` (columns) of `AᵀA` for a
/// basis evaluated at points (`a`, rows of `n`); `None` if the solver
/// fails.
pub(super) fn gram_eigen(a: &[f64], n: usize) -> Option<(Mat<f64>, Vec<f64>)> {
    let m = a.len() / n;
    let gram = Mat::<f64>::from_fn(n, n, |i, j| (0..m).map(|r| a[r * n + i] * a[r * n + j]).sum());
    let mut q = Mat::<f64>::zeros(n, n);
    let mut lambda = faer::Col::<f64>::zeros(n);
    let (par, params) = (faer::Par::Seq, Default::default());
    let mut mem = MemBuffer::new(evd::self_adjoint_evd_scratch::<f64>(n, evd::ComputeEigenvectors::Yes, par, params));
    let stack = MemStack::new(&mut mem);
    evd::self_adjoint_evd(gram.as_ref(), lambda.as_diagonal_mut(), Some(q.as_mut()), par, stack, params).ok()?;
    Some((q, (0..n).map(|i| lambda[i]).collect()))
}

/// `V A⁺` for a basis evaluated at the patch's points (`a`, rows) and at the
/// element's own (`v`, rows), both row-major with `n` columns.
pub(super) fn fit_operator(a: &[f64], v: &[f64], n: usize) -> Vec<f64> {
    let (m, k) = (a.len() / n, v.len() / n);
    let pinv = pseudo_inverse(a, n);
    let mut r = vec![0.0; k * m];
    for g in 0..k {
        for p in 0..m {
            r[g * m + p] = (0..n).map(|j| v[g * n + j] * pinv[j * m + p]).sum();
        }
    }
    r
}

/// `I − A A⁺` (`m × m`, row-major): the residual of the fit.
pub(super) fn residual_operator(a: &[f64], n: usize) -> Vec<f64> {
    let m = a.len() / n;
    let mut r = fit_operator(a, a, n);
    for (i, x) in r.iter_mut().enumerate() {
        *x = if i / m == i % m { 1.0 } else { 0.0 } - *x;
    }
    r
}

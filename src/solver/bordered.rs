//! The bordered system of force-controlled indenters and impactors,
//!
//! ```text
//! A = [ K   B ]     K the structure's tangent (n × n, symmetric),
//!     [ Bᵀ  C ]     B its m border columns, C the m × m diagonal corner,
//! ```
//!
//! solved by conjugate gradients preconditioned with the bordered
//! factorization of an earlier tangent: with `L Lᵀ ≈ K₀` and the border
//! `B₀, C₀` of the evaluation it was made at, `X₀ = K₀⁻¹ B₀` and the Schur
//! complement `S₀ = C₀ − B₀ᵀ X₀` (m × m), the preconditioner is `A₀⁻¹`
//! applied by Keller's block elimination:
//!
//! ```text
//! y = K₀⁻¹ r_u,   z_a = S₀⁻¹ (r_a − B₀ᵀ y),   z_u = y − X₀ z_a.
//! ```
//!
//! `A` is the Hessian of the potential of the structure and its rigid
//! indenters (symmetric positive definite while an impactor's mass or a
//! touching indenter's contact holds it), so conjugate gradients apply and
//! converge in a few iterations while `A₀⁻¹ A` stays close to the identity,
//! as for the reuse of a factorization without a border (`solver::reuse`).
//! With the present tangent's own double-precision factor and border,
//! `A₀ = A` and one iteration solves it. Keller's elimination alone with
//! an inexact `K⁻¹` would not do: `S = C − Bᵀ K⁻¹ B` is a difference of
//! nearly equal terms where a penalty contact holds the indenter, and an
//! error of `K⁻¹ B` of relative size η becomes a much larger one of `S`;
//! here every residual is that of `A` itself, formed in double precision.

use super::krylov::{self, Krylov};
use super::linear::{Cholesky, LinearError, LowerCsc};

/// The border of a bordered system: the columns `B` (equation space) and
/// the diagonal corner `C`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Border<'a> {
    /// `B`'s columns, one per indenter.
    pub cols: &'a [&'a [f64]],
    /// `C`'s diagonal.
    pub corner: &'a [f64],
}

/// The border of the evaluation a factorization was made at, eliminated
/// with that factor (module docs): `B₀`, `X₀ = K₀⁻¹ B₀` and `S₀`.
#[derive(Debug, Default)]
pub(crate) struct FactorBorder {
    b: Vec<Vec<f64>>,
    x: Vec<Vec<f64>>,
    s: Vec<Vec<f64>>,
}

impl FactorBorder {
    /// Eliminates `border` with the factor `chol` of the tangent it was
    /// evaluated with.
    pub fn new(chol: &mut Cholesky, border: &Border<'_>) -> Result<Self, LinearError> {
        let m = border.cols.len();
        let b: Vec<Vec<f64>> = border.cols.iter().map(|c| c.to_vec()).collect();
        let mut x = b.clone();
        for col in &mut x {
            if col.iter().any(|v| *v != 0.0) {
                chol.solve_in_place(col)?;
            }
        }
        let mut s = vec![vec![0.0; m]; m];
        for i in 0..m {
            for j in 0..m {
                s[i][j] = -dot(&b[i], &x[j]);
            }
            s[i][i] += border.corner[i];
        }
        Ok(Self { b, x, s })
    }

    /// Number of border columns.
    pub fn len(&self) -> usize {
        self.b.len()
    }

    /// `z = A₀⁻¹ r` (module docs); `z_u` holds `r_u` on entry.
    fn apply(&self, chol: &mut Cholesky, z_u: &mut [f64], r_a: &[f64], z_a: &mut [f64]) -> Result<(), LinearError> {
        chol.solve_in_place(z_u)?;
        let rhs: Vec<f64> = (0..self.len()).map(|i| r_a[i] - dot(&self.b[i], z_u)).collect();
        let za = solve_dense(self.s.clone(), rhs).ok_or(LinearError::Singular)?;
        for (x, v) in self.x.iter().zip(&za) {
            for (z, xi) in z_u.iter_mut().zip(x) {
                *z -= v * xi;
            }
        }
        z_a.copy_from_slice(&za);
        Ok(())
    }
}

/// Storage of [`pcg_bordered`] kept between solves: the stacked vectors
/// `[·_u; ·_a]` of conjugate gradients and the right-hand side.
#[derive(Debug, Default)]
pub(crate) struct BorderedWork {
    u: [Vec<f64>; 5],
    rhs: Vec<f64>,
}

/// Conjugate gradients for the bordered system `A [x_u; x_a] = [b_u; b_a]`
/// (module docs), preconditioned by `chol` and `factor`, from zero, to
/// `‖b − A x‖ ≤ tol ‖b‖` within `max_iterations` ([`krylov::Stop`]): [`krylov::pcg_with`] on
/// the stacked vector `[x_u; x_a]`. `rhs_u` and `rhs_a` hold `b` on entry
/// and, on convergence, `x` (otherwise `b` unchanged). Stops early on a
/// breakdown (`pᵀ A p ≤ 0`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn pcg_bordered(
    (pattern, values): (&LowerCsc, &[f64]),
    border: &Border<'_>,
    (chol, factor): (&mut Cholesky, &FactorBorder),
    rhs_u: &mut [f64],
    rhs_a: &mut [f64],
    stop: krylov::Stop,
    max_iterations: usize,
    work: &mut BorderedWork,
) -> Result<Krylov, LinearError> {
    let n = rhs_u.len();
    let BorderedWork { u, rhs } = work;
    rhs.clear();
    rhs.extend_from_slice(rhs_u);
    rhs.extend_from_slice(rhs_a);
    // q = A p
    let operator = |p: &[f64], q: &mut [f64]| {
        let (p_u, p_a) = p.split_at(n);
        let (q_u, q_a) = q.split_at_mut(n);
        pattern.mul_symmetric(values, p_u, q_u);
        for (i, col) in border.cols.iter().enumerate() {
            for (qv, c) in q_u.iter_mut().zip(col.iter()) {
                *qv += c * p_a[i];
            }
            q_a[i] = dot(col, p_u) + border.corner[i] * p_a[i];
        }
    };
    // z ← A₀⁻¹ z
    let precond = |z: &mut [f64]| {
        let (z_u, z_a) = z.split_at_mut(n);
        let r_a = z_a.to_vec();
        factor.apply(chol, z_u, &r_a, z_a)
    };
    let outcome = krylov::pcg_with(operator, precond, rhs, stop, max_iterations, u)?;
    if let Krylov::Converged(_) = outcome {
        rhs_u.copy_from_slice(&rhs[..n]);
        rhs_a.copy_from_slice(&rhs[n..]);
    }
    Ok(outcome)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Keller's block elimination of the bordered system `[K B; Bᵀ' C] [x; a]
/// = [r; r_a]` once `K⁻¹` has been applied (module docs): `x` holds `x₁ =
/// K⁻¹ r` on entry and `x₁ − X Δa` on return, `cols` are `X = K⁻¹ B`,
/// `row(i, v)` is the border row `bᵢ' · v` (`bᵢ' = bᵢ` for a symmetric
/// border), `corner` is `C`'s diagonal. Returns `Δa` solving the Schur
/// complement `(C − B'ᵀ X) Δa = r_a − B'ᵀ x₁`.
pub(crate) fn eliminate(
    x: &mut [f64],
    cols: &[Vec<f64>],
    row: impl Fn(usize, &[f64]) -> f64,
    corner: &[f64],
    r_a: &[f64],
) -> Result<Vec<f64>, LinearError> {
    let m = cols.len();
    let mut s = vec![vec![0.0; m]; m];
    let mut rhs = vec![0.0; m];
    for i in 0..m {
        for j in 0..m {
            s[i][j] = -row(i, &cols[j]);
        }
        s[i][i] += corner[i];
        rhs[i] = r_a[i] - row(i, x);
    }
    let da = solve_dense(s, rhs).ok_or(LinearError::Singular)?;
    for (col, d) in cols.iter().zip(&da) {
        for (v, c) in x.iter_mut().zip(col) {
            *v -= c * d;
        }
    }
    Ok(da)
}

/// Gaussian elimination with partial pivoting of the small dense system
/// `a x = b` (the `m × m` Schur complement); `None` if singular.
pub(crate) fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for col in 0..n {
        let p = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if !(a[p][col].abs() > 0.0) {
            return None;
        }
        a.swap(col, p);
        b.swap(col, p);
        for row in col + 1..n {
            let f = a[row][col] / a[col][col];
            for k in col..n {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|k| a[i][k] * x[k]).sum();
        x[i] = (b[i] - s) / a[i][i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::super::krylov::tests::tridiagonal;
    use super::super::reuse::{ReuseSettings, ReusingSolver, SolveKind};
    use super::*;

    /// A rigid impactor on a chain of springs: `K` the chain's tridiagonal
    /// tangent (`diagonal`) plus the penalty `eps` at the touching nodes
    /// `contact`, the border `B = −eps` there, the corner `C = eps · |contact|
    /// + mass` (the Hessian of `½ uᵀK₀u + ½ eps Σ (u_s − a)² + ½ mass a²`,
    /// `src/analysis/structure/force.rs`).
    fn impactor(diagonal: &[f64], contact: &[usize], eps: f64, mass: f64) -> (LowerCsc, Vec<f64>, Vec<f64>, f64) {
        let mut d = diagonal.to_vec();
        let mut b = vec![0.0; d.len()];
        for &s in contact {
            d[s] += eps;
            b[s] = -eps;
        }
        let (pattern, values) = tridiagonal(&d);
        (pattern, values, b, eps * contact.len() as f64 + mass)
    }

    /// The same system dense, solved by Gaussian elimination: the
    /// independent reference.
    fn dense_solution(pattern: &LowerCsc, values: &[f64], b: &[f64], c: f64, rhs: &[f64], rhs_a: f64) -> Vec<f64> {
        let n = b.len();
        let mut a = vec![vec![0.0; n + 1]; n + 1];
        for col in 0..n {
            for k in pattern.col_ptr[col]..pattern.col_ptr[col + 1] {
                let row = pattern.row_idx[k] as usize;
                a[row][col] = values[k];
                a[col][row] = values[k];
            }
            a[col][n] = b[col];
            a[n][col] = b[col];
        }
        a[n][n] = c;
        let mut f = rhs.to_vec();
        f.push(rhs_a);
        solve_dense(a, f).unwrap()
    }

    fn largest_difference(x: &[f64], a: f64, reference: &[f64]) -> f64 {
        let size = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        x.iter().chain([&a]).zip(reference).fold(0.0_f64, |m, (p, q)| m.max((p - q).abs())) / size
    }

    /// With a penalty a million times the chain's stiffness, `S = C − Bᵀ
    /// K⁻¹ B` is a difference of nearly equal terms; the bordered PCG with
    /// the present tangent's double factor solves the system in one
    /// iteration to round-off, and after the contact set and the chain's
    /// stiffness change (a node more in contact, three softened rows) with
    /// the old factor to the requested tolerance, without a factorization.
    #[test]
    fn the_bordered_system_is_solved_with_its_own_and_with_an_earlier_factor() {
        let n = 200;
        let (eps, mass) = (1e6, 0.5);
        let settings = ReuseSettings { min_iterations: 20, single_precision: false, ..Default::default() };
        let (pattern, values, b, c) = impactor(&vec![2.5; n], &[99, 100], eps, mass);
        let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin()).collect();
        let reference = dense_solution(&pattern, &values, &b, c, &rhs, 3.0);
        let (mut x, mut a) = (rhs.clone(), [3.0]);
        let border = Border { cols: &[&b], corner: &[c] };
        let kind = solver.solve_bordered((&pattern, &values), &border, &mut x, &mut a, 1e-12).unwrap();
        assert_eq!(kind, SolveKind::Factorized);
        assert!(solver.stats().krylov_iterations <= 2, "{:?}", solver.stats());
        let error = largest_difference(&x, a[0], &reference);
        assert!(error < 1e-9, "own factor: {error:e}");

        let mut diagonal = vec![2.5; n];
        for d in &mut diagonal[40..43] {
            *d = 2.1;
        }
        let (_, values1, b1, c1) = impactor(&diagonal, &[99, 100, 101], eps, mass);
        let reference = dense_solution(&pattern, &values1, &b1, c1, &rhs, 3.0);
        let (mut x, mut a) = (rhs.clone(), [3.0]);
        let border = Border { cols: &[&b1], corner: &[c1] };
        let kind = solver.solve_bordered((&pattern, &values1), &border, &mut x, &mut a, 1e-10).unwrap();
        let SolveKind::Reused(k) = kind else { panic!("expected reuse, got {kind:?}") };
        assert!(k <= 8, "{k} iterations");
        assert_eq!(solver.stats().factorizations, 1);
        let error = largest_difference(&x, a[0], &reference);
        assert!(error < 1e-6, "earlier factor: {error:e}");
    }
}

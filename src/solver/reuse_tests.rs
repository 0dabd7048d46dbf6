//! Tests of `solver::reuse` (a file of their own: the module is near the
//! length limit).

use super::unsymmetric::EXACT;
use super::*;
use crate::solver::nonsymmetric::NonSymmetric;

use super::super::krylov::tests::{residual as residual_unsymmetric, tridiagonal};

/// `‖A x − b‖` for the symmetric `A` (lower `v` on `p`).
fn residual(p: &LowerCsc, v: &[f64], x: &[f64], b: &[f64]) -> f64 {
    residual_unsymmetric(p, v, &NonSymmetric::default(), x, b)
}

/// A local change of the matrix (a "plastic zone" of 3 rows of 200) is
/// solved by PCG with the old factor in a few iterations (at most one per
/// changed row plus one, in exact arithmetic) to the requested tolerance.
#[test]
fn local_change_is_solved_by_the_old_factor_in_a_few_iterations() {
    let n = 200;
    let d0 = vec![2.5; n];
    let (pattern, v0) = tridiagonal(&d0);
    // a tridiagonal factorization costs less than two PCG iterations, so
    // the cost rule alone would allow only the minimum: raise it
    let settings = ReuseSettings { min_iterations: 10, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
    let mut x = b.clone();
    assert_eq!(solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap(), SolveKind::Factorized);
    // soften three rows (as plastic flow would)
    let mut d1 = d0.clone();
    for d in &mut d1[100..103] {
        *d = 2.1;
    }
    let (_, v1) = tridiagonal(&d1);
    let mut x = b.clone();
    let kind = solver.solve(&pattern, &v1, &mut x, 1e-8, false).unwrap();
    let SolveKind::Reused(k) = kind else { panic!("expected reuse, got {kind:?}") };
    assert!(k <= 4, "{k} iterations");
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(residual(&pattern, &v1, &x, &b) <= 1e-8 * bn);
    assert_eq!(solver.stats().factorizations, 1);
}

/// A matrix far from the factored one (every diagonal changed by a
/// factor 50: no low-rank structure) defeats PCG within its allowance:
/// the solver must fall back to a factorization and still solve exactly.
#[test]
fn a_factor_that_no_longer_preconditions_is_replaced() {
    let n = 400;
    let (pattern, v0) = tridiagonal(&vec![2.0001; n]);
    // double precision: the factorization after the fallback solves exactly
    let settings =
        ReuseSettings { min_iterations: 5, max_iterations: 5, single_precision: false, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let b: Vec<f64> = (0..n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
    let mut x = b.clone();
    solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap();
    let d1: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 100.0 } else { 2.0001 }).collect();
    let (_, v1) = tridiagonal(&d1);
    let mut x = b.clone();
    let kind = solver.solve(&pattern, &v1, &mut x, 1e-8, false).unwrap();
    assert_eq!(kind, SolveKind::FellBack(5));
    assert_eq!(solver.stats().factorizations, 2);
    assert_eq!(solver.stats().fallbacks, 1);
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(residual(&pattern, &v1, &x, &b) <= 1e-12 * bn);
}

/// 2×2 blocks `[[1 + δ, −1], [−1, 1 + δ]]` (eigenvalues `δ` and `2 + δ`):
/// lower pattern and values.
fn pairs(deltas: &[f64]) -> (LowerCsc, Vec<f64>) {
    let columns: Vec<Vec<usize>> = (0..deltas.len()).flat_map(|i| [vec![2 * i, 2 * i + 1], vec![2 * i + 1]]).collect();
    let values: Vec<f64> = deltas.iter().flat_map(|d| [1.0 + d, -1.0, 1.0 + d]).collect();
    (LowerCsc::from_columns(2 * deltas.len(), &columns), values)
}

/// Mixed precision: the `f32` factor of the present matrix alone solves
/// it with a relative error of about `κ · 6e-8` only (κ = 4e4 here:
/// measured residual 3.0e-4 of ‖b‖, printed by the assertion message if
/// it ever reaches 1e-9); the PCG refinement in `f64` must bring the
/// residual to `η`.
#[test]
fn a_single_precision_factor_is_refined_to_the_requested_tolerance() {
    let n = 200;
    let (pattern, v) = tridiagonal(&vec![2.0001; n]);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut alone = Cholesky::analyze(&pattern).unwrap();
    alone.factorize_with(&v, true).unwrap();
    assert!(alone.is_single());
    let mut y = b.clone();
    alone.solve_in_place(&mut y).unwrap();
    let unrefined = residual(&pattern, &v, &y, &b) / bn;
    assert!(unrefined > 1e-9, "the f32 solve alone reached {unrefined:e}: the test proves nothing");

    let settings = ReuseSettings { min_iterations: 10, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let mut x = b.clone();
    assert_eq!(solver.solve(&pattern, &v, &mut x, 1e-11, false).unwrap(), SolveKind::Factorized);
    assert!(residual(&pattern, &v, &x, &b) <= 1e-11 * bn, "{unrefined:e}");
    let st = solver.stats();
    assert_eq!((st.factorizations, st.single_factorizations, st.precision_fallbacks), (1, 1, 0));
    assert!(st.krylov_iterations >= 1);
}

/// A matrix too ill-conditioned for `f32`: 2×2 blocks whose small
/// eigenvalues `δ ∈ [3e-7, 1e-6]` are of the size of the rounding of
/// `1 + δ` (1.2e-7), so the `f32` factor (which still exists) gets each
/// of them wrong by up to ~20 %, differently per block; PCG needs more
/// than the 5 iterations allowed. The solver must fall back to an `f64`
/// factor, solve exactly, and stay in `f64`.
#[test]
fn a_single_precision_factor_that_does_not_precondition_falls_back_to_double() {
    let deltas: Vec<f64> = (0..100).map(|i| 3e-7 + 7e-7 * ((i * 37) % 100) as f64 / 100.0).collect();
    let (pattern, v) = pairs(&deltas);
    let settings = ReuseSettings { min_iterations: 5, max_iterations: 5, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let b: Vec<f64> = (0..pattern.n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut x = b.clone();
    assert_eq!(solver.solve(&pattern, &v, &mut x, 1e-10, false).unwrap(), SolveKind::Factorized);
    let st = *solver.stats();
    assert_eq!((st.factorizations, st.single_factorizations, st.precision_fallbacks), (2, 1, 1), "{st:?}");
    // a backward-stable f64 solve leaves ε ‖A‖ ‖x‖ ≈ 1e-16 · 2 · ‖b‖ / 3e-7
    // ≈ 7e-10 ‖b‖ (measured 2.2e-10; the f32 factor alone leaves 0.12)
    let r = residual(&pattern, &v, &x, &b) / bn;
    let mut alone = Cholesky::analyze(&pattern).unwrap();
    alone.factorize_with(&v, true).unwrap();
    let mut y = b.clone();
    alone.solve_in_place(&mut y).unwrap();
    eprintln!("residual {r:e}, f32 alone {:e}", residual(&pattern, &v, &y, &b) / bn);
    assert!(r <= 1e-8, "{r:e}");
    // the next factorization is in f64 (a matrix changed everywhere)
    let (_, v2) = pairs(&deltas.iter().map(|d| 2.0 * d).collect::<Vec<_>>());
    let mut x = b.clone();
    solver.solve(&pattern, &v2, &mut x, 1e-10, false).unwrap();
    assert_eq!(solver.stats().single_factorizations, 1);
    assert!(residual(&pattern, &v2, &x, &b) <= 1e-8 * bn);
}

/// Disabled reuse factorizes every time.
#[test]
fn disabled_reuse_factorizes_every_solve() {
    let (pattern, v0) = tridiagonal(&[3.0; 10]);
    let settings = ReuseSettings { enabled: false, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    for _ in 0..3 {
        let mut x = vec![1.0; 10];
        assert_eq!(solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap(), SolveKind::Factorized);
    }
    assert_eq!((solver.stats().factorizations, solver.stats().reused), (3, 0));
}

/// Friction couplings `σ t nᵀ` (outer products) at pairs of neighbouring
/// unknowns.
fn couplings(points: &[usize], sigma: f64) -> NonSymmetric {
    let mut s = NonSymmetric::default();
    for &i in points {
        s.push_outer([(i, sigma)], [(i + 1, 1.0)]);
    }
    s
}

/// The unsymmetric path: the first solve factorizes the symmetric part and
/// GMRES brings `(A + S) x = b` to the forcing term; a second system whose
/// symmetric part changed in a few rows (a spreading plastic zone) and
/// whose couplings moved is solved with the same factor (`Reused`), no new
/// factorization; each solution satisfies its own unsymmetric system (a
/// solver that ignored `S`, or applied it with the wrong sign, leaves a
/// residual of order ‖S x‖ ≈ 0.1 ‖b‖, checked to be far above η).
#[test]
fn the_unsymmetric_path_reuses_the_symmetric_factor() {
    let n = 300;
    let (pattern, v0) = tridiagonal(&vec![2.5; n]);
    let s0 = couplings(&[20, 90, 150, 151, 240], 0.7);
    let settings = ReuseSettings { min_iterations: 10, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.2).cos() + 0.3).collect();
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let eta = 1e-9;
    let mut x = b.clone();
    assert_eq!(solver.solve_unsymmetric(&pattern, &v0, &s0, &mut x, eta, false).unwrap(), SolveKind::Factorized);
    assert!(residual_unsymmetric(&pattern, &v0, &s0, &x, &b) <= eta * bn);
    assert!(residual(&pattern, &v0, &x, &b) > 1e-3 * bn, "the couplings change the solution");
    let mut d1 = vec![2.5; n];
    for d in &mut d1[100..104] {
        *d = 2.2;
    }
    let (_, v1) = tridiagonal(&d1);
    let s1 = couplings(&[20, 91, 150, 151, 241], 0.7);
    let mut x = b.clone();
    let kind = solver.solve_unsymmetric(&pattern, &v1, &s1, &mut x, eta, false).unwrap();
    assert!(matches!(kind, SolveKind::Reused(_)), "{kind:?}");
    assert!(residual_unsymmetric(&pattern, &v1, &s1, &x, &b) <= eta * bn);
    assert_eq!(solver.stats().factorizations, 1);
    // without couplings the symmetric path (PCG) serves, with the same factor
    let mut x = b.clone();
    let kind = solver.solve_unsymmetric(&pattern, &v1, &NonSymmetric::default(), &mut x, eta, false).unwrap();
    assert!(matches!(kind, SolveKind::Reused(_)), "{kind:?}");
    assert!(residual(&pattern, &v1, &x, &b) <= eta * bn);
}

/// The bordered solves of force control (`must_factor`): a fresh factor in
/// double precision and every right-hand side solved to [`EXACT`], not to
/// the forcing term the caller passed (0.1 here).
#[test]
fn must_factor_solves_the_unsymmetric_system_exactly() {
    let n = 120;
    let (pattern, v) = tridiagonal(&vec![2.2; n]);
    let s = couplings(&[5, 60, 61, 100], 0.9);
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), ReuseSettings::default());
    let b: Vec<f64> = (0..n).map(|i| ((i * 31) % 7) as f64 - 3.0).collect();
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut x = b.clone();
    solver.solve_unsymmetric(&pattern, &v, &s, &mut x, 0.1, true).unwrap();
    assert!(residual_unsymmetric(&pattern, &v, &s, &x, &b) <= EXACT * bn);
    let b2: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
    let mut y = b2.clone();
    solver.solve_again_unsymmetric(&pattern, &v, &s, &mut y).unwrap();
    let b2n = b2.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(residual_unsymmetric(&pattern, &v, &s, &y, &b2) <= EXACT * b2n);
    assert_eq!((solver.stats().factorizations, solver.stats().single_factorizations), (1, 0));
}

/// A matrix whose rounding to `f32` is singular (2×2 blocks of eigenvalues
/// `δ = 1e-9` and 2: `1 + δ` rounds to 1): the single-precision `LLᵀ`
/// breaks down and the factor is made in double. Single precision is then
/// tried again only after 1, 3, 7, 15 … factorizations in double — before,
/// every factorization tried (and failed) in single precision first, which
/// cost the 999,108-DOF I-beam 90 s of 400 (docs/performance.md, "At
/// scale"); and it is tried again, so that a passing breakdown does not
/// end single precision for the run.
#[test]
fn breakdowns_in_single_precision_back_off_exponentially() {
    let (pattern, v) = pairs(&[1e-9; 50]);
    let mut alone = Cholesky::analyze(&pattern).unwrap();
    alone.factorize_with(&v, true).unwrap();
    assert!(!alone.is_single(), "the f32 LLᵀ of a singular rounding succeeded: the test proves nothing");
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), ReuseSettings::default());
    assert!(solver.single, "single precision is the default");
    let b: Vec<f64> = (0..pattern.n).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
    let mut x = b.clone();
    assert_eq!(solver.solve(&pattern, &v, &mut x, 1e-10, false).unwrap(), SolveKind::Factorized);
    assert!(residual(&pattern, &v, &x, &b) <= 1e-8 * b.iter().map(|v| v * v).sum::<f64>().sqrt());
    // 19 more factorizations: attempts at the 3rd, 7th and 15th (1 + 2, 4, 8 in double between)
    for _ in 1..20 {
        solver.factorize(&v, solver.single).unwrap();
    }
    let st = *solver.stats();
    assert_eq!((st.factorizations, st.single_factorizations, st.single_breakdowns), (20, 0, 4), "{st:?}");
    // a matrix that factors in single precision resets the count once tried
    let (pattern2, good) = pairs(&[0.5; 50]);
    assert_eq!(pattern2.n, pattern.n);
    for _ in 0..16 {
        solver.factorize(&good, solver.single).unwrap();
    }
    assert!(solver.chol.is_single() && solver.breakdowns == 0, "single precision never came back");
}

/// A finishing request (`finish_next`) on the local change above: PCG with
/// the old factor goes on from `η = 1e-2` to `1e-11` within half its
/// allowance (the changed rows make the preconditioned operator of low
/// rank), reports the request met, and counts no factorization more; the
/// next solve, not asked, stops at its own `η` again.
#[test]
fn a_finishing_request_goes_on_within_the_unworn_iterations() {
    let n = 200;
    let (pattern, v0) = tridiagonal(&vec![2.5; n]);
    let settings = ReuseSettings { min_iterations: 10, single_precision: false, ..Default::default() };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
    let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut x = b.clone();
    solver.solve(&pattern, &v0, &mut x, 1e-8, false).unwrap();
    let mut d1 = vec![2.5; n];
    for d in &mut d1[100..103] {
        *d = 2.1;
    }
    let (_, v1) = tridiagonal(&d1);
    let plain = |solver: &mut ReusingSolver| {
        let mut x = b.clone();
        let kind = solver.solve(&pattern, &v1, &mut x, 1e-2, false).unwrap();
        (kind, residual(&pattern, &v1, &x, &b) / bn)
    };
    let (kind, r) = plain(&mut solver);
    assert!(matches!(kind, SolveKind::Reused(_)) && r <= 1e-2 && r > 1e-11, "{kind:?} {r:e}");
    solver.finish_next(1e-11);
    let mut x = b.clone();
    let kind = solver.solve(&pattern, &v1, &mut x, 1e-2, false).unwrap();
    let SolveKind::Reused(k) = kind else { panic!("{kind:?}") };
    assert!(k <= 5 && solver.finished(), "{k}");
    assert!(residual(&pattern, &v1, &x, &b) <= 1e-11 * bn);
    let (again, r_again) = plain(&mut solver);
    assert!(matches!(again, SolveKind::Reused(_)) && r_again > 1e-11, "{again:?} {r_again:e}");
    assert_eq!(solver.stats().factorizations, 1);
}

/// A factor worn by a tight solve (more than half its allowance) is
/// replaced before the next tight solve, but tried for a loose one its
/// contraction reaches within half the allowance (module docs): the first
/// correction of an increment after the last, tight one of the increment
/// before. Eight scattered rows softened (rank 8: CG needs up to nine
/// iterations with the old factor) wear it at `1e-10`; then `0.1` is
/// solved with it and `1e-10` is not.
#[test]
fn a_worn_factor_still_serves_a_looser_solve() {
    let n = 200;
    let (pattern, v0) = tridiagonal(&vec![2.5; n]);
    let settings =
        ReuseSettings { min_iterations: 12, max_iterations: 12, single_precision: false, ..Default::default() };
    let solve = |solver: &mut ReusingSolver, v: &[f64], forcing: f64| {
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin() + 1.0).collect();
        let mut x = b.clone();
        let kind = solver.solve(&pattern, v, &mut x, forcing, false).unwrap();
        let bn = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(residual(&pattern, v, &x, &b) <= forcing * bn, "{kind:?}");
        kind
    };
    let mut d1 = vec![2.5; n];
    for k in 0..8 {
        d1[10 + 23 * k] = 1.2 + 0.3 * k as f64;
    }
    let (_, v1) = tridiagonal(&d1);
    // a model whose materials soften refactors after a worn solve, as before
    let off = ReuseSettings { worn_for_loose: false, ..settings };
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), off);
    assert_eq!(solve(&mut solver, &v0, 1e-10), SolveKind::Factorized);
    assert!(matches!(solve(&mut solver, &v1, 1e-10), SolveKind::Reused(7..=12)));
    assert_eq!(solve(&mut solver, &v1, 0.1), SolveKind::Factorized);
    let mut solver = ReusingSolver::new(Cholesky::analyze(&pattern).unwrap(), settings);
    assert_eq!(solve(&mut solver, &v0, 1e-10), SolveKind::Factorized);
    let worn = solve(&mut solver, &v1, 1e-10);
    assert!(matches!(worn, SolveKind::Reused(7..=12)), "{worn:?}: the factor is not worn");
    let loose = solve(&mut solver, &v1, 0.1);
    assert!(matches!(loose, SolveKind::Reused(1..=6)), "{loose:?}");
    assert_eq!(solver.stats().factorizations, 1);
    // a loose solve leaves the factor unworn: wear it again, then a tight
    // solve refactors
    assert!(matches!(solve(&mut solver, &v1, 1e-10), SolveKind::Reused(7..=12)));
    assert_eq!(solve(&mut solver, &v1, 1e-10), SolveKind::Factorized);
    // a loose solve that Newton asks to finish tight (`finish_next`) is
    // judged by the residual it is to reach: the worn factor is not tried
    // (else PCG stops short of the finish and a linear step, which a
    // direct solve ends to round-off, ends at Newton's tolerance)
    assert!(matches!(solve(&mut solver, &v0, 1e-10), SolveKind::Reused(7..=12)), "not worn again");
    solver.finish_next(1e-10);
    assert_eq!(solve(&mut solver, &v0, 0.1), SolveKind::Factorized);
    assert!(solver.finished());
}

//! The unsymmetric path of the reusing solver (a model with friction,
//! `solver::krylov`): GMRES preconditioned by the factor of a symmetric
//! part, with the reuse policy of the symmetric solves (`solver::reuse`).

use std::time::Instant;

use super::super::krylov::{self, Krylov};
use super::super::linear::{LinearError, LowerCsc};
use super::super::nonsymmetric::NonSymmetric;
use super::{ReusingSolver, SolveKind};

/// GMRES restart length (a model with friction): the basis holds this many
/// vectors of the equations' size (counted in the memory estimate).
pub(crate) const GMRES_RESTART: usize = 30;

/// Most GMRES iterations with the factor of the present symmetric part
/// before the solve is reported as failed (`LinearError::KrylovStalled`;
/// Newton then cuts the increment back).
pub(crate) const GMRES_MAX_FRESH: usize = 200;

/// Relative residual of the GMRES solves that stand in for exact ones (the
/// bordered solves of force control).
pub(crate) const EXACT: f64 = 1e-12;

/// Largest forcing term of a GMRES solve (a model whose points slide with
/// friction): below the symmetric path's `η_max`. Sliding makes the
/// residual only piecewise smooth, and steps solved to 0.1 or 1e-2 cost
/// Newton iterations that cost more (an assembly each, with surface
/// contact) than the GMRES iterations they save: measured (`cufem run`, one
/// run each) on examples/cantilevers_contact_nonmatching_friction.toml 90
/// Newton iterations with no cap below η_max, 76 with 1e-2, 66 with 1e-3
/// (the frictionless twin: 72), and 67 → 63 on
/// examples/cantilevers_contact_friction.toml, at equal or lower time.
pub(crate) const UNSYMMETRIC_FORCING: f64 = 1e-3;

impl ReusingSolver {
    /// Solves `(A + S) x = b` for the symmetric `A` (lower-triangle
    /// `values` on `pattern`) plus the unsymmetric entries `skew` (a model
    /// with friction, `solver::krylov`): GMRES preconditioned by the factor
    /// of a symmetric part, with the reuse policy of [`Self::solve`]. A
    /// solve with the last factor may take the iterations its fresh factor
    /// needed plus the cost of a factorization; if it does not converge, the
    /// present `A` is factorized and GMRES runs with it (at most
    /// [`GMRES_MAX_FRESH`] iterations; a single-precision factor that fails
    /// is replaced by a double one). Without skew entries this is
    /// [`Self::solve`]. With `must_factor` the factor is of the present `A`
    /// in double precision, for [`Self::solve_again_unsymmetric`].
    pub(crate) fn solve_unsymmetric(
        &mut self,
        pattern: &LowerCsc,
        values: &[f64],
        skew: &NonSymmetric,
        rhs: &mut [f64],
        forcing: f64,
        must_factor: bool,
    ) -> Result<SolveKind, LinearError> {
        if skew.is_empty() {
            return self.solve(pattern, values, rhs, forcing, must_factor);
        }
        let try_reuse = self.settings.enabled && self.has_factor && !self.worn && !self.skip && !must_factor;
        self.skip = false;
        self.finish = None;
        self.finished = false;
        // the bordering (`must_factor`) combines this solution with further
        // ones of the same matrix: all of them as exact as the direct solves
        // of the symmetric path
        let eta = if must_factor { EXACT } else { self.stop(forcing).min(UNSYMMETRIC_FORCING) };
        let mut kind = SolveKind::Factorized;
        if try_reuse {
            let allowed = self.allowed_iterations(pattern);
            let budget = allowed + self.fresh_iterations;
            let outcome = self.gmres(pattern, values, skew, rhs, eta, budget)?;
            kind = self.reused(outcome, self.fresh_iterations + allowed / 2);
            // GMRES's iterations do not predict PCG's (`Self::serves`)
            self.contraction = None;
            if let SolveKind::Reused(_) = kind {
                return Ok(kind);
            }
        }
        self.skip = matches!(kind, SolveKind::FellBack(_));
        self.factorize(values, self.single && !must_factor)?;
        loop {
            match self.gmres(pattern, values, skew, rhs, eta, GMRES_MAX_FRESH)? {
                Krylov::Converged(k) => {
                    self.fresh_iterations = k;
                    return Ok(kind);
                }
                Krylov::NotConverged(_) if self.chol.is_single() => {
                    self.stats.precision_fallbacks += 1;
                    self.single = false;
                    self.factorize(values, false)?;
                }
                Krylov::NotConverged(k) => return Err(LinearError::KrylovStalled(k)),
            }
        }
    }

    /// After [`Self::solve_unsymmetric`] with `must_factor`: solves a further
    /// right-hand side of the same system to [`EXACT`] (relative).
    pub(crate) fn solve_again_unsymmetric(
        &mut self,
        pattern: &LowerCsc,
        values: &[f64],
        skew: &NonSymmetric,
        rhs: &mut [f64],
    ) -> Result<(), LinearError> {
        if skew.is_empty() {
            return self.solve_again(rhs);
        }
        match self.gmres(pattern, values, skew, rhs, EXACT, GMRES_MAX_FRESH)? {
            Krylov::Converged(_) => Ok(()),
            Krylov::NotConverged(k) => Err(LinearError::KrylovStalled(k)),
        }
    }

    /// One GMRES solve with the present factor, counted and timed.
    fn gmres(
        &mut self,
        pattern: &LowerCsc,
        values: &[f64],
        skew: &NonSymmetric,
        rhs: &mut [f64],
        eta: f64,
        max_iterations: usize,
    ) -> Result<Krylov, LinearError> {
        let t = Instant::now();
        let outcome = krylov::gmres(
            pattern,
            values,
            skew,
            &mut self.chol,
            rhs,
            eta,
            max_iterations,
            GMRES_RESTART,
            &mut self.gmres,
        )?;
        self.stats.solve_time += t.elapsed();
        self.stats.krylov_iterations += outcome.iterations();
        Ok(outcome)
    }
}

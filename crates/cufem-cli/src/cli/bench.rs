//! `cufem bench`: phase timings over repeated runs, medians reported.
//!
//! Default: one linear solve at the full load (setup split into ordering,
//! pattern and symbolic analysis; then assembly, numeric factorization and
//! solve). With `--full`: the whole analysis, with per-iteration averages.

use std::time::Duration;

use anyhow::Result;
use cufem::analysis::{self, Silent, Structure};
use cufem::setup::Model;
use cufem::solver::newton::NonlinearProblem;
use cufem::solver::stepping::Incremental;

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn ms(d: Duration) -> String {
    format!("{:9.1} ms", d.as_secs_f64() * 1e3)
}

/// Runs the benchmark and prints medians.
pub fn run(model: &Model, repeat: usize, full: bool) -> Result<()> {
    println!("{} — {} DOF, {} run(s), {} thread(s)", model.title, model.n_dofs(), repeat, rayon::current_num_threads());
    if full {
        let mut walls = Vec::new();
        let mut rows: Vec<[Duration; 7]> = Vec::new();
        let mut last = None;
        for _ in 0..repeat {
            let sol = analysis::run(model, &analysis::RunOptions::default(), &mut Silent)?;
            let t = sol.timings;
            walls.push(sol.wall_time);
            rows.push([
                t.assembly,
                t.contact,
                t.solver.factorization_time,
                t.solver.solve_time,
                t.stress_pass,
                t.element_tangents,
                t.eigen,
            ]);
            last = Some(sol);
        }
        let sol = last.expect("at least one run");
        let t = sol.timings;
        let iters: usize = sol.increments.iter().map(|i| i.newton.iterations).sum();
        let col = |k: usize| median(rows.iter().map(|r| r[k]).collect());
        println!(
            "  increments {}, Newton iterations {}, evaluations {} ({} without element tangents, {} repeated \
             with them), cutbacks {}",
            sol.increments.len(),
            iters,
            t.evaluations,
            t.residual_only,
            t.reevaluations,
            sol.cutbacks.len()
        );
        let solves = (t.solver.factorizations + t.solver.reused).max(1);
        println!(
            "  factorizations {}, solves reusing a factorization {} ({:.0} %), Krylov (PCG/GMRES) iterations {}, \
             fallbacks {}",
            t.solver.factorizations,
            t.solver.reused,
            100.0 * t.solver.reused as f64 / solves as f64,
            t.solver.krylov_iterations,
            t.solver.fallbacks
        );
        println!(
            "  single-precision factorizations {}, precision fallbacks {}",
            t.solver.single_factorizations, t.solver.precision_fallbacks
        );
        println!("  wall time (median)         {}", ms(median(walls)));
        let per_eval = |d: Duration| d / t.evaluations.max(1) as u32;
        let per_fact = |d: Duration| d / t.solver.factorizations.max(1) as u32;
        println!("  element loop + return map  {}   per evaluation {}", ms(col(0)), ms(per_eval(col(0))));
        println!("    kernel: stress pass      {}   per evaluation {}", ms(col(4)), ms(per_eval(col(4))));
        println!("    kernel: element tangents {}   per evaluation {}", ms(col(5)), ms(per_eval(col(5))));
        println!("  contact                    {}   per evaluation {}", ms(col(1)), ms(per_eval(col(1))));
        println!("  numeric factorization      {}   per factor.    {}", ms(col(2)), ms(per_fact(col(2))));
        let per_solve = |d: Duration| d / solves as u32;
        println!("  solves (triangular + PCG)  {}   per solve      {}", ms(col(3)), ms(per_solve(col(3))));
        if sol.modal.is_some() || sol.buckling.is_some() {
            // its own factorizations and solves are not in the counts above
            println!("  eigenproblem (Lanczos)     {}", ms(col(6)));
        }
        if let Some(peak) = cufem::size::peak_memory() {
            let estimate = sol.memory.total();
            println!(
                "  peak resident memory       {:>9.1} MiB (estimate {:.1} MiB)",
                peak as f64 / 1048576.0,
                estimate as f64 / 1048576.0
            );
        }
        return Ok(());
    }
    let mut rows: Vec<[Duration; 8]> = Vec::new();
    let mut nnz = (0, 0, 0);
    for _ in 0..repeat {
        let mut s = Structure::of_model(model, None)?;
        s.set_load_factor(1.0);
        s.evaluate()?;
        s.correct()?;
        let t = *s.timings();
        nnz = (s.n_equations(), s.pattern().nnz(), s.factor_nnz());
        rows.push([
            t.ordering,
            t.pattern,
            t.symbolic,
            t.element_cache,
            t.assembly + t.contact,
            t.solver.factorization_time,
            t.solver.solve_time,
            t.setup + t.assembly + t.contact + t.solver.factorization_time + t.solver.solve_time,
        ]);
    }
    let col = |k: usize| median(rows.iter().map(|r| r[k]).collect());
    println!("  equations {}, nnz(K lower) {}, nnz(L) {}", nnz.0, nnz.1, nnz.2);
    println!("  ordering (graph + METIS)   {}", ms(col(0)));
    println!("  pattern + scatter maps     {}", ms(col(1)));
    println!("  symbolic factorization     {}", ms(col(2)));
    println!("  elastic element matrices   {}   (once; full element loop with nuclei)", ms(col(3)));
    println!("  assembly (element loop)    {}   (forces + cached elastic matrices)", ms(col(4)));
    println!("  numeric factorization      {}", ms(col(5)));
    println!("  solve                      {}", ms(col(6)));
    println!("  total                      {}", ms(col(7)));
    Ok(())
}

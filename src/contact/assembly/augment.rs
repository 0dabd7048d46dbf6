//! Augmented-Lagrangian contact (Uzawa updates between Newton solves;
//! Simo & Laursen, Computers & Structures 42, 1992): for every indenter or
//! pair contact with a `penetration_tolerance`, once Newton has converged,
//! if its largest penetration exceeds the tolerance each point's multiplier
//! takes the point's current force, `λ ← λ − ε g` (≥ 0), and Newton runs
//! again. At convergence the contact forces are the multipliers and the
//! penetration is below the tolerance, whatever the penalty `ε`: the
//! penalty sets how many augmentations it takes, not the answer.

use super::Contacts;

impl Contacts<'_> {
    /// One Uzawa update of every augmented contact whose penetration exceeds
    /// its tolerance; true if any multiplier changed (another Newton solve
    /// is needed).
    pub(crate) fn augment(&mut self) -> bool {
        let (indenters, pairs) = (self.indenters, self.pairs);
        let tolerances =
            indenters.iter().map(|i| i.penetration_tolerance).chain(pairs.iter().map(|c| c.penetration_tolerance));
        let penalties = |k: usize, j: usize| -> f64 {
            let ni = indenters.len();
            if k < ni { indenters[k].nodes[j].penalty } else { pairs[k - ni].point_penalty(j) }
        };
        let mut changed = false;
        for (k, tol) in tolerances.enumerate() {
            let Some(tol) = tol else { continue };
            let range = self.ranges[k].clone();
            let worst = self.points[range.clone()].iter().filter(|p| p.active).map(|p| -p.gap).fold(0.0, f64::max);
            if worst <= tol {
                continue;
            }
            for (j, p) in self.points[range].iter_mut().enumerate() {
                let next = (p.multiplier - penalties(k, j) * p.gap).max(0.0);
                changed |= next != p.multiplier;
                p.multiplier = next;
            }
        }
        changed
    }
}

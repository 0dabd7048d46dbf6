//! The internal forces of linear elastic elements as one product with the
//! elastic stiffness assembled at setup, `f = K₀ u`, instead of the element
//! loop over the Gauss points.
//!
//! In small strain, with materials that neither yield nor damage, the
//! elements' internal force is linear in the displacements and equals the
//! product of the elastic tangent the assembler caches
//! ([`Assembler::cache_elastic`]) with them: over the equations by the
//! symmetric product of that lower triangle, and at the DOFs fixed at zero
//! (which have no equation: the reactions) by their rows of `K₀`, coupling
//! them to the free DOFs, assembled here once. A DOF without an equation is
//! fixed at zero (`setup::constraints`), so it adds nothing to the product.
//! The product costs a pass over the matrix, a few times less than the
//! Gauss loop (`analysis::structure::elements`, which leaves the stresses to
//! be formed when they are read).

use super::{Assembler, Inputs, NO_EQ};
use crate::elements::{self, PointData, TangentMode, Workspace};
use crate::materials::PointState;

/// `K₀` as an operator on displacements: the assembler's cached elastic
/// tangent over the equations, and the rows of the fixed DOFs.
#[derive(Debug, Clone)]
pub(crate) struct ElasticProduct {
    /// The DOF of each equation.
    dof_of_eq: Vec<usize>,
    /// The fixed DOFs that couple to a free one, each with a row of
    /// `cols`/`values`.
    fixed: Vec<usize>,
    /// Start of each fixed DOF's row in `cols`/`values` (`fixed.len() + 1`).
    row_ptr: Vec<usize>,
    /// Equation of each entry.
    cols: Vec<u32>,
    /// `K₀[fixed, equation]`.
    values: Vec<f64>,
    /// Displacements and forces per equation (scratch).
    u_eq: Vec<f64>,
    f_eq: Vec<f64>,
}

impl ElasticProduct {
    /// The product of `assembler`'s elastic tangent (cached), with the
    /// fixed DOFs' rows from every element touching one at `input` (zero
    /// displacements and virgin states).
    ///
    /// # Panics
    /// If the assembler has no elastic tangent cached (a caller's bug).
    pub(crate) fn new(assembler: &Assembler, input: &Inputs<'_>) -> Self {
        assert!(!assembler.elastic_global.is_empty(), "the elastic tangent is cached first");
        let eq = &assembler.dofs.eq;
        let mut dof_of_eq = vec![0; assembler.dofs.n_eq];
        for (d, &e) in eq.iter().enumerate() {
            if e != NO_EQ {
                dof_of_eq[e] = d;
            }
        }
        // (fixed DOF, equation, value) of every element touching a fixed DOF
        let mut entries: Vec<(usize, u32, f64)> = Vec::new();
        let mut ws = Workspace::default();
        let mut nodes = Vec::new();
        for r in &assembler.scatter.elements {
            let body = &input.mesh.bodies[r.body];
            body.element_nodes(r.element, &mut nodes);
            let dofs: Vec<usize> = nodes.iter().flat_map(|&n| (0..3).map(move |c| 3 * n + c)).collect();
            if dofs.iter().all(|&d| eq[d] != NO_EQ) {
                continue;
            }
            let geom = &input.geometry[r.body];
            let ngp = geom.gp_per_element();
            let g0 = input.gp_offsets[r.body] + r.element * ngp;
            let (mut trial, mut stress) = (vec![PointState::default(); ngp], vec![[0.0; 6]; ngp]);
            let points = PointData {
                committed: &input.states[g0..g0 + ngp],
                trial: &mut trial,
                stress: &mut stress,
                predictor: input.predictor,
                kinematics: input.kinematics,
                initial: None,
                step: None,
                damage: None,
            };
            let zeros = vec![0.0; dofs.len()];
            let material = &input.materials[body.material_of(body.split_element(r.element).0)];
            let section_elements = body.section.n_elements();
            elements::element_response(
                geom,
                r.element,
                section_elements,
                &zeros,
                material,
                points,
                TangentMode::Always,
                &mut ws,
            );
            // the kernel fills the upper triangle (p ≤ q) of the element matrix
            let n = dofs.len();
            for (p, &dp) in dofs.iter().enumerate() {
                if eq[dp] != NO_EQ {
                    continue;
                }
                for (q, &dq) in dofs.iter().enumerate() {
                    let e = eq[dq];
                    if e != NO_EQ {
                        let k = ws.tangent[p.min(q) * n + p.max(q)];
                        entries.push((dp, u32::try_from(e).expect("equations are 32-bit"), k));
                    }
                }
            }
        }
        // summed over the elements, in rows of fixed DOFs
        entries.sort_unstable_by_key(|&(d, e, _)| (d, e));
        let mut merged: Vec<(usize, u32, f64)> = Vec::with_capacity(entries.len());
        for (d, e, k) in entries {
            match merged.last_mut() {
                Some(last) if (last.0, last.1) == (d, e) => last.2 += k,
                _ => merged.push((d, e, k)),
            }
        }
        let (mut fixed, mut row_ptr) = (Vec::new(), Vec::new());
        for (i, &(d, _, _)) in merged.iter().enumerate() {
            if fixed.last() != Some(&d) {
                fixed.push(d);
                row_ptr.push(i);
            }
        }
        row_ptr.push(merged.len());
        let (cols, values) = merged.iter().map(|&(_, e, k)| (e, k)).unzip();
        let n_eq = dof_of_eq.len();
        Self { dof_of_eq, fixed, row_ptr, cols, values, u_eq: vec![0.0; n_eq], f_eq: vec![0.0; n_eq] }
    }

    /// The internal forces `f = K₀ u` (per DOF, overwritten) of the
    /// displacements `u` (per DOF, zero where fixed).
    pub(crate) fn force(&mut self, assembler: &Assembler, u: &[f64], f: &mut [f64]) {
        for (x, &d) in self.u_eq.iter_mut().zip(&self.dof_of_eq) {
            *x = u[d];
        }
        assembler.pattern.mul_symmetric(&assembler.elastic_global, &self.u_eq, &mut self.f_eq);
        f.fill(0.0);
        for (&y, &d) in self.f_eq.iter().zip(&self.dof_of_eq) {
            f[d] = y;
        }
        for (k, &d) in self.fixed.iter().enumerate() {
            let range = self.row_ptr[k]..self.row_ptr[k + 1];
            f[d] =
                self.cols[range.clone()].iter().zip(&self.values[range]).map(|(&e, v)| v * self.u_eq[e as usize]).sum();
        }
    }
}

impl Assembler {
    /// Overwrites `values` (pattern order) with the cached elastic tangent:
    /// the elements' whole tangent when none of them yields or damages.
    pub(crate) fn elastic_tangent_into(&self, values: &mut [f64]) {
        values.copy_from_slice(&self.elastic_global);
    }
}

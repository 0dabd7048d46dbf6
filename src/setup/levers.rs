//! `[[levers]]`: rigid levers, linear multi-point constraints with a
//! prescribed value (`bc::Lever`). Point `k` of a lever selects nodes of a
//! body and names a component and a coefficient `c_k`; the lever's
//! displacement is `δ = Σ_k c_k ū_k`, `ū_k` the mean of that component
//! over the point's nodes, so each node's DOF enters with `c_k / n_k`. The
//! analysis prescribes `δ = value · factor(λ)` through one extra unknown,
//! the lever's force `P`, which pushes each node by `P c_k / n_k` along the
//! component (`analysis/structure/levers.rs`).
//!
//! A lever ties free DOFs only: a point whose component a `[[constraints]]`
//! entry fixes or prescribes is refused (its value is already set; the
//! bordered solve works on the free equations). What the levers are not
//! written for is refused by key: symmetry planes (a lever across a plane
//! has no mirror image here), force-controlled indenters and impactors
//! (their bordering and the lever's would have to be one system), path
//! following, transient, eigenvalue analyses and adaptive refinement.

use std::collections::BTreeMap;

use super::constraints::ConstraintHandler;
use super::preprocess::{body_index, model_coords, selection};
use crate::bc::Lever;
use crate::contact::Indenter;
use crate::input::schema::{LeverFile, ModelFile};
use crate::input::validate::describe_selection;
use crate::input::{ModelError, invalid};
use crate::mesh::Mesh;

/// The model's `[[levers]]`, their DOFs checked free under `handler`,
/// refused beside force-controlled `indenters`.
pub(super) fn levers(
    file: &[LeverFile],
    mesh: &Mesh,
    handler: &ConstraintHandler,
    indenters: &[Indenter],
) -> Result<Vec<Lever>, ModelError> {
    if let Some(i) = indenters.iter().find(|i| !file.is_empty() && (i.force.is_some() || i.impactor.is_some())) {
        return Err(invalid(
            "levers",
            format!("given with the force-controlled indenter {:?}", i.name),
            "no [[levers]] with force-controlled indenters or impactors (indenters moved by `displacement` are fine)",
        ));
    }
    file.iter().enumerate().map(|(i, l)| lever(&format!("levers[{i}]"), l, mesh, handler)).collect()
}

fn lever(key: &str, l: &LeverFile, mesh: &Mesh, handler: &ConstraintHandler) -> Result<Lever, ModelError> {
    if !l.value.is_finite() {
        return Err(invalid(format!("{key}.value"), l.value, "a finite displacement in m"));
    }
    if l.points.is_empty() {
        return Err(invalid(
            format!("{key}.points"),
            "[]",
            "at least one point { body, where, component, coefficient }",
        ));
    }
    let mut terms: BTreeMap<usize, f64> = BTreeMap::new();
    for (k, p) in l.points.iter().enumerate() {
        let pk = format!("{key}.points[{k}]");
        if !(p.coefficient.is_finite() && p.coefficient != 0.0) {
            return Err(invalid(format!("{pk}.coefficient"), p.coefficient, "a finite, non-zero number"));
        }
        let b = body_index(mesh, format!("{pk}.body"), &p.body)?;
        let body = &mesh.bodies[b];
        let nodes = selection(&format!("{pk}.where"), &p.selection, body)?.nodes(body);
        if nodes.is_empty() {
            return Err(invalid(
                format!("{pk}.where"),
                describe_selection(&p.selection),
                format!("a selection that contains nodes of body {:?}", body.name),
            ));
        }
        let c = p.component.index();
        let share = p.coefficient / nodes.len() as f64;
        for n in nodes {
            let node = n + body.node_offset;
            let dof = 3 * node + c;
            if let Some(held) = handler.prescribed(dof) {
                return Err(invalid(
                    format!("{pk}.where"),
                    describe_selection(&p.selection),
                    format!(
                        "nodes whose u_{} no constraint fixes or prescribes (constraints[{}] holds the node at {:?}: \
                         a lever ties free displacements)",
                        ["x", "y", "z"][c],
                        held.constraint,
                        model_coords(body, node)
                    ),
                ));
            }
            *terms.entry(dof).or_insert(0.0) += share;
        }
    }
    let size = terms.values().map(|v| v.abs()).fold(0.0, f64::max);
    let terms: Vec<(usize, f64)> = terms.into_iter().filter(|(_, v)| v.abs() > 1e-12 * size).collect();
    if terms.is_empty() {
        return Err(invalid(
            format!("{key}.points"),
            "coefficients that cancel on every node",
            "points whose coefficients leave some DOF with a non-zero one (two points on the same nodes add up)",
        ));
    }
    Ok(Lever { name: l.name.clone(), value: l.value, terms })
}

/// Refuses levers where the analysis does not carry them (module docs;
/// force-controlled indenters: [`levers`]).
pub(super) fn combinations(file: &ModelFile) -> Result<(), ModelError> {
    if file.levers.is_empty() {
        return Ok(());
    }
    let why = |what: &str| format!("no [[levers]] with {what}");
    if let Some(s) = file.symmetry.first() {
        return Err(invalid("levers", format!("given with symmetry plane {:?}", s.name), why("[[symmetry]] planes")));
    }
    if file.solver.control == Some(crate::input::schema::Control::ArcLength) {
        return Err(invalid(
            "levers",
            "given with solver.control = \"arc_length\"",
            why("path following: the lever's displacement control already passes limit points"),
        ));
    }
    if let Some(kind) = file.analysis.kind.filter(|k| *k != crate::input::schema::AnalysisType::Static) {
        return Err(invalid(
            "levers",
            format!("given with analysis.type = \"{}\"", format!("{kind:?}").to_lowercase()),
            why("another analysis than \"static\" (the transient energy ledger and the eigenproblems leave them out)"),
        ));
    }
    if file.adapt.is_some() {
        return Err(with_adapt("[adapt]"));
    }
    Ok(())
}

/// The refusal of levers in an adaptive run, asked for by `given`
/// (`[adapt]`, or the command line's `--adapt`: `Model::check_adaptive`).
pub(super) fn with_adapt(given: &str) -> ModelError {
    invalid("levers", format!("given with {given}"), "no [[levers]] with adaptive refinement")
}

#[cfg(test)]
mod tests {
    use crate::setup::{Limits, Model};

    const BASE: &str = r#"
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3

[[bodies]]
name = "beam"
material = "steel"
section = { shape = "rectangle", element = "L4", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.0, to = 0.04, elements = 1 } }
axis = { element = "B2", from = 0.0, to = 0.5, elements = 4 }

[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]
"#;

    /// The error of the base cantilever with a lever of `points` (and `more`).
    fn refused(points: &str, more: &str) -> String {
        let text = format!("{BASE}\n[[levers]]\nname = \"lever\"\nvalue = 1e-3\npoints = [{points}]\n{more}");
        match Model::parse_with(&text, Limits::none()) {
            Ok(_) => panic!("accepted: {points} {more}"),
            Err(e) => e.to_string(),
        }
    }

    const TIP: &str = r#"{ body = "beam", where = { y = 0.5 }, component = "z", coefficient = 1.0 }"#;

    /// Each mistake is refused by its key, with what is allowed.
    #[test]
    fn levers_are_refused_by_key() {
        let cases = [
            (String::new(), String::new(), "levers[0].points", "at least one point"),
            (TIP.replace("beam\"", "bean\""), String::new(), "levers[0].points[0].body", "one of the bodies"),
            (TIP.replace("y = 0.5", "y = 0.7"), String::new(), "levers[0].points[0].where", "contains nodes"),
            (TIP.replace("1.0 }", "0.0 }"), String::new(), "levers[0].points[0].coefficient", "non-zero"),
            (TIP.replace("y = 0.5", "y = 0.0"), String::new(), "levers[0].points[0].where", "no constraint fixes"),
            (format!("{TIP}, {}", TIP.replace("1.0 }", "-1.0 }")), String::new(), "levers[0].points", "cancel"),
            (TIP.into(), "[solver]\ncontrol = \"arc_length\"".into(), "levers", "path following"),
            (TIP.into(), "[analysis]\ntype = \"modal\"\nmodes = 2".into(), "levers", "\"modal\""),
            (TIP.into(), "[[symmetry]]\nname = \"mid\"\nplane = { x = 0.0 }".into(), "levers", "[[symmetry]] planes"),
        ];
        for (points, more, key, why) in cases {
            let e = refused(&points, &more);
            assert!(e.contains(&format!("{key} =")) && e.contains(why), "{points} {more}: {e}");
        }
    }

    /// A lever's DOFs with their coefficient over the point's node count,
    /// two points on the same nodes adding up.
    #[test]
    fn lever_terms_share_a_point_over_its_nodes() {
        let text = format!(
            "{BASE}\n[[levers]]\nname = \"lever\"\nvalue = 1e-3\npoints = [{TIP}, {}]",
            TIP.replace("1.0 }", "2.0 }").replace("\"z\"", "\"x\"")
        );
        let model = Model::parse_with(&text, Limits::none()).unwrap();
        let l = &model.levers[0];
        // the tip section of an L4 section: 4 nodes, u_z and u_x each
        assert_eq!(l.terms.len(), 8);
        assert!(l.terms.iter().all(|&(d, a)| if d % 3 == 2 { a == 0.25 } else { d % 3 == 0 && a == 0.5 }));
    }
}

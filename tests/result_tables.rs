//! The probe table (`analysis::tables::probes`) and what serialises it:
//! summary.json's `probes` and the Python package's `probe` row.

use std::path::Path;

use cufem::analysis::{self, Silent, tables};
use cufem::post::Quantity;
use cufem::setup::Model;

/// `examples/cantilever_timoshenko.toml` (aluminium, 0.1 × 0.1 m, 1 m,
/// tip force 1 kN down) with strengths, so the failure indices are
/// tabulated, and a probe on the top fibre at mid-span.
fn cantilever_with_strengths() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/cantilever_timoshenko.toml");
    std::fs::read_to_string(path)
        .unwrap()
        .replace(
            "poisson_ratio = 0.3\n",
            "poisson_ratio = 0.3\nstrengths = { xt = 300e6, xc = 300e6, yt = 200e6, yc = 250e6, s12 = 150e6, s23 = 150e6 }\n",
        )
        .replace("[[probes]]\n", "[[probes]]\nname = \"top_mid\"\npoint = [0.05, 0.5, 0.1]\n\n[[probes]]\n")
}

/// Each probe's entry in summary.json is its row of the probe table, and
/// both are the fields sampled at the probe directly
/// (`FieldView::sample_probe`): displacement, stress, von Mises, peeq and
/// each failure index by its name. Beam theory fixes the one stress that
/// matters: σ_yy = M c / I at the top fibre at mid-span, M = 1 kN · 0.5 m,
/// c = 0.05 m, I = 0.1 · 0.1³ / 12 m⁴: 3.0 MPa in tension. A summary that
/// took the strains for the stresses, shuffled the criteria or the
/// probes, or a table that left a probe out would fail.
#[test]
fn summary_probes_are_the_probe_table_rows() {
    let model = Model::parse(&cantilever_with_strengths()).unwrap();
    let sol = analysis::run(&model, &Default::default(), &mut Silent).unwrap();
    let view = sol.fields(&model);
    let table = tables::probes(&model, &view);
    let summary = cufem::io::summary(&model, &sol);
    assert_eq!(table.rows(), 2);
    assert_eq!(table.text("probe").unwrap(), ["top_mid", "tip"]);
    assert_eq!(summary.probes.len(), 2);
    for (i, (p, s)) in model.probes.iter().zip(&summary.probes).enumerate() {
        let direct = view.sample_probe(p).unwrap();
        assert_eq!((s.name.as_str(), s.point), (p.name.as_str(), p.point));
        assert_eq!((s.u, s.stress), (direct.u, direct.stress), "{}", p.name);
        assert_eq!((s.von_mises, s.peeq), (direct.von_mises, direct.peeq), "{}", p.name);
        let indices = s.failure_indices.as_ref().unwrap();
        for (k, name) in cufem::post::failure::CRITERIA.iter().enumerate() {
            assert_eq!(indices[name], direct.failure[k], "{} {name}", p.name);
        }
        // the row Python's `probe` returns: x, y, z, then every quantity
        let row = table.row(i);
        assert_eq!(row.0.len(), 3 + model.quantities().len());
        assert_eq!([row.get("x"), row.get("y"), row.get("z")], p.point.map(Some));
        for q in model.quantities() {
            assert_eq!(row.get(&q.name()), Some(direct.get(q)), "{} {}", p.name, q.name());
        }
    }
    let s_yy = summary.probes[0].stress[1];
    eprintln!("top fibre at mid-span: σ_yy = {s_yy:.6e} Pa, M c / I = 3.0e6 Pa");
    assert!((s_yy / 3.0e6 - 1.0).abs() < 0.02, "σ_yy {s_yy:e} Pa against M c / I = 3.0e6 Pa");
    assert!(table.real(&Quantity::Failure(1).name()).unwrap()[0] > 0.0);
}

"""Findings of a new-user review of the package (each test fails without its
fix): a study's variants and outputs, warnings that a quiet run and an
adaptive model owe the user, errors in the package's own words, and the ply
damage as cell data."""

import json
import math
import warnings

import pytest

import cufem
from cufem import study
from conftest import EXAMPLES

TIMOSHENKO = EXAMPLES / "cantilever_timoshenko.toml"

# an elastic–perfectly-plastic cantilever under three times its collapse
# load: Newton fails in the first increments (the review's model)
OVERLOAD = """
title = "EPP cantilever, tip force above the limit load"
[solver]
increments = 5
[[materials]]
name = "steel"
young_modulus = 200e9
poisson_ratio = 0.3
plasticity = { yield_stress = 250e6, hardening = "perfect" }
[[bodies]]
name = "beam"
material = "steel"
section = { shape = "rectangle", element = "L9", x = { from = 0.0, to = 0.02, elements = 1 }, z = { from = 0.0, to = 0.02, elements = 2 } }
axis = { element = "B4", from = 0.0, to = 0.8, elements = 8 }
[[constraints]]
name = "root"
body = "beam"
where = { y = 0.0 }
fix = ["x", "y", "z"]
[[loads]]
name = "tip"
body = "beam"
where = { y = 0.8 }
total_force = [0.0, 0.0, -3000.0]
"""


def test_a_single_value_is_one_variant():
    # was split into the characters "L" and "4", and a float raised a bare TypeError
    assert study.grid({"bodies.0.section.element": "L4"}) == [{"bodies.0.section.element": "L4"}]
    assert study.grid({"materials.0.young_modulus": 70e9, "a": [1, 2]}) == [
        {"materials.0.young_modulus": 70e9, "a": 1},
        {"materials.0.young_modulus": 70e9, "a": 2},
    ]


def test_a_bad_output_is_refused_before_anything_is_solved():
    # (solved first, each row then failed: the KeyError below would not be raised)
    with pytest.raises(KeyError, match="probe.tip.u_q.*expected a probe quantity"):
        study.run(TIMOSHENKO, {"materials.0.young_modulus": [70e9, 80e9]}, ["probe.tip.u_z", "probe.tip.u_q"], max_workers=0)
    with pytest.raises(KeyError, match="reaction.root.m_x"):
        study.run(TIMOSHENKO, [{}], ["reaction.root.m_x"], max_workers=0)


def test_a_probes_strain_is_an_output():
    # summary.json holds no strains: they come from Results.probe (were refused)
    df = study.run(TIMOSHENKO, [{}], ["probe.tip.e_yy"], max_workers=0)
    single = cufem.Model.from_file(TIMOSHENKO).run(quiet=True, threads=1).probe("tip")["e_yy"]
    assert df["error"].isna().all() and df.iloc[0]["probe.tip.e_yy"] == single


def test_an_output_a_run_lacks_blanks_that_output_only():
    df = study.run(TIMOSHENKO, [{}], ["probe.tip.u_z", "probe.nowhere.u_z", "reaction.root.f_z"], max_workers=0)
    row = df.iloc[0]
    assert "no probe 'nowhere'" in row["error"]
    assert math.isnan(row["probe.nowhere.u_z"])
    # the converged run's other outputs are kept (were NaN after the bad one)
    assert row["probe.tip.u_z"] < 0.0 and abs(row["reaction.root.f_z"]) > 0.0


def test_the_report_takes_a_vector_valued_parameter(tmp_path):
    d = cufem.Model.from_file(TIMOSHENKO).to_dict()
    force = d["loads"][0]["total_force"]
    twice = [2.0 * f for f in force]
    df = study.run(TIMOSHENKO, {"materials.0.young_modulus": [70e9, 80e9], "loads.0.total_force": [force, twice]},
                   ["probe.tip.u_z"], max_workers=0)
    assert df["error"].isna().all()
    page = open(study.report(df, tmp_path / "study.html"), encoding="utf-8").read()
    assert page.count("<figure") == 1 and "total_force" in page


def test_a_quiet_run_that_stops_says_so(tmp_path):
    model = cufem.Model.from_toml(OVERLOAD)
    with pytest.warns(UserWarning, match="the run ended not_converged"):
        r = model.run(quiet=True, threads=1)
    assert r.status == "not_converged"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert cufem.Model.from_file(TIMOSHENKO).run(quiet=True, threads=1).status == "converged"


def test_an_adaptive_model_runs_its_cycles_as_the_cli_does(cli, tmp_path):
    # the same file gave 1,200 DOF and 6.60 % here, 2,565 DOF and 4.14 % from the CLI (a new-user review)
    path = tmp_path / "adaptive.toml"
    path.write_text(open(TIMOSHENKO, encoding="utf-8").read() + "\n[adapt]\ntolerance = 0.05\n", encoding="utf-8")
    cli("run", path, "--out", tmp_path / "cli", "--threads", "1", "--quiet")
    with open(tmp_path / "cli" / "summary.json", encoding="utf-8") as f:
        expected = json.load(f)
    ours = cufem.Model.from_file(path).run(quiet=True, threads=1).summary
    assert len(expected["adapt"]) >= 2 and [c["dof"] for c in ours["adapt"]] == [c["dof"] for c in expected["adapt"]]
    assert ours["dof"] == expected["dof"] > ours["adapt"][0]["dof"]
    assert ours["probes"][0]["u"] == pytest.approx(expected["probes"][0]["u"], rel=1e-9, abs=1e-15)


def test_errors_speak_the_packages_words(tmp_path):
    model = cufem.Model.from_file(TIMOSHENKO)
    with pytest.raises(ValueError, match="threads = -1: expected an integer from 1 to 1024"):
        model.run(threads=-1)
    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    r = model.run(quiet=True, threads=1)
    with pytest.raises(OSError) as e:
        r.write(foreign)
    text = str(e.value)
    assert text.startswith("out = ") and "pass force=True" in text and "--" not in text, text
    assert "OSError" not in text, text


def test_the_ply_damage_is_cell_data(memory_runs):
    r = memory_runs("notched_strip_coarse")
    names = r.cell_field_names
    assert names[:2] == ["body", "element"] and set(names[2:]) == {"d_ft", "d_fc", "d_mt", "d_mc"}, names
    # the strip breaks: its fibres fail in tension (summary.json's damage)
    assert r.cell_field("d_ft").max() == pytest.approx(r.summary["damage"]["largest"]["fibre_tension"], abs=1e-12)
    mesh = r.to_meshio()
    assert "d_ft" in mesh.cell_data and len(mesh.cell_data["d_ft"][0]) == len(r.cell_field("body"))
    with pytest.raises(KeyError, match="cell field 'd_xx'"):
        r.cell_field("d_xx")


def test_a_dict_models_error_names_its_key_path():
    d = cufem.Model.from_file(EXAMPLES / "block_indentation_unload.toml").to_dict()
    cases = [
        ("materials.0.youngs_modulus", 1e9, "materials.0.youngs_modulus: unknown field `youngs_modulus`"),
        ("materials.0.plasticity.yield_strength", 1e8, "materials.0.plasticity.yield_strength: unknown field"),
        ("bodies.0.section.x.segments.1.ratios", 2.0, "bodies.0.section.x.segments.1.ratios: unknown field"),
        ("steps.1.increments", "many", "steps.1.increments: invalid type"),
    ]
    for path, value, expected in cases:
        with pytest.raises(cufem.ModelError) as e:
            cufem.Model.from_dict(cufem.model.set_path(d, path, value))
        # was "model file: TOML parse error at line 61, column 1" and a caret under text the user never saw
        assert str(e.value).startswith(expected) and "line" not in str(e.value), str(e.value)


def test_a_plot_shows_what_the_report_shows(memory_runs):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = memory_runs("bending_compact_4L9")
    try:
        ax = r.plot_line("top")
        drawn = [l.get_label() for l in ax.get_lines() if l.get_visible()]
        # the coordinates and the displacements (a millionth of the stresses) start hidden, as in report.html
        assert drawn and not {"x", "y", "z", "u_z"} & set(drawn) and all(c.startswith("s_") or c == "von_mises" for c in drawn), drawn
        assert ax.get_ylabel() == "[Pa]"
        ax = r.plot_history("load", columns=["f_z", "max_penetration"])
        assert all(l.get_visible() for l in ax.get_lines()) and ax.get_ylabel() == "several units: see the legend"
    finally:
        plt.close("all")


def test_frames_steps_and_mode_shapes_are_reachable(memory_runs, cli_runs):
    import meshio
    import numpy as np

    modes = memory_runs("cantilever_modes")
    assert modes.kept["modes"] >= 2
    # the shape as mode_1.vtu holds it: the same points and displacement
    vtu = meshio.read(cli_runs("cantilever_modes") / "mode_1.vtu")
    shape = modes.mode(0)
    u = shape.field("displacement")
    assert np.abs(u).max() == pytest.approx(1.0, abs=1e-12)
    np.testing.assert_allclose(shape.points, vtu.points, atol=1e-12)
    np.testing.assert_allclose(u, vtu.point_data["displacement"], rtol=1e-9, atol=1e-12)
    # the unloaded run's own state is zero everywhere: the shapes were all it had to show
    assert np.abs(modes.field("displacement")).max() == 0.0
    with pytest.raises(KeyError, match=r"mode 99: this run kept"):
        modes.mode(99)
    rod = memory_runs("rod_impact")
    n = rod.kept["frames"]
    assert n >= 2
    vtu = meshio.read(cli_runs("rod_impact") / "frame_0001.vtu")
    np.testing.assert_allclose(rod.frame(0).field("displacement"), vtu.point_data["displacement"], rtol=1e-9, atol=1e-15)
    assert not np.allclose(rod.frame(0).field("displacement"), rod.frame(n - 1).field("displacement"))


def test_step_ends_are_reachable_where_kept(memory_runs, cli_runs):
    import meshio
    import numpy as np

    two = memory_runs("block_indentation_unload")
    assert two.kept["steps"] == 2
    vtu = meshio.read(cli_runs("block_indentation_unload") / "result_1_load.vtu")
    np.testing.assert_allclose(two.step(0).field("displacement"), vtu.point_data["displacement"], rtol=1e-9, atol=1e-15)
    # a history of one step keeps none: its end is the final state (kept counted it, step(0) refused it)
    one = memory_runs("cantilever_timoshenko")
    assert one.kept["steps"] == 0
    for call in (lambda: one.step(0), lambda: two.frame(-1), lambda: two.step(-1)):
        with pytest.raises(KeyError):
            call()


def test_a_range_of_values_is_a_list_of_variants():
    # a range or a generator was taken as one value, and every row failed
    assert study.grid({"a": range(4, 13, 4)}) == [{"a": 4}, {"a": 8}, {"a": 12}]
    assert study.grid({"a": (v for v in [1, 2])}) == [{"a": 1}, {"a": 2}]


def test_a_dict_error_past_a_multi_line_description_names_its_key():
    d = cufem.Model.from_file(EXAMPLES / "block_indentation_unload.toml").to_dict()
    d["description"] = "Indentation.\n[1] Johnson 1985.\n[[materials]]\nname = 'x'\n"
    with pytest.raises(cufem.ModelError) as e:
        cufem.Model.from_dict(cufem.model.set_path(d, "materials.0.youngs_modulus", 1e9))
    assert str(e.value).startswith("materials.0.youngs_modulus: unknown field"), str(e.value)

"""Python results against the CLI's files, to the last digit."""

import numpy as np
import pandas as pd
import pytest

import cufem
from conftest import EXAMPLES, load_summary

# timings, memory and wall time differ from run to run
VOLATILE = ("wall_time_s", "timings", "memory")
# the quarter model: its histories' full-structure columns (symmetry planes)
EXAMPLES_COMPARED = ["cantilever_timoshenko", "bending_compact_4L9", "bending_compact_4L9_quarter"]


def stable(summary, files=True):
    s = {k: v for k, v in summary.items() if k not in VOLATILE}
    if not files:
        s.pop("files")
    return s


@pytest.fixture(scope="module")
def py_runs(tmp_path_factory):
    cache = {}

    def get(name):
        if name not in cache:
            out = tmp_path_factory.mktemp("py") / name
            model = cufem.Model.from_file(EXAMPLES / f"{name}.toml")
            cache[name] = (model.run(out=out, threads=1, quiet=True), out)
        return cache[name]

    return get


@pytest.mark.parametrize("name", EXAMPLES_COMPARED)
def test_summary_equals_the_cli_summary_json(name, cli_runs, py_runs):
    cli = load_summary(cli_runs(name))
    results, out = py_runs(name)
    # every number parsed from both JSON texts is the same f64: equal to the last digit
    assert stable(results.summary) == stable(cli)
    assert stable(load_summary(out)) == stable(cli)
    assert results.summary["status"] == "converged"
    # in memory, without writing: the same content, no file list
    mem = cufem.Model.from_file(EXAMPLES / f"{name}.toml").run(threads=1, quiet=True)
    assert stable(mem.summary, files=False) == stable(cli, files=False)
    assert mem.summary["files"] == [] and mem.files is None


@pytest.mark.parametrize("name", EXAMPLES_COMPARED)
def test_results_do_not_depend_on_the_thread_count(name, cli_runs):
    cli = load_summary(cli_runs(name))
    two = cufem.Model.from_file(EXAMPLES / f"{name}.toml").run(threads=2, quiet=True)
    assert stable(two.summary, files=False) == stable(cli, files=False)


@pytest.mark.parametrize("name", EXAMPLES_COMPARED)
def test_same_files_as_the_cli(name, cli_runs, py_runs, tmp_path):
    cli_dir = cli_runs(name)
    results, out = py_runs(name)
    cli_files = sorted(p.name for p in cli_dir.iterdir())
    assert sorted(p.name for p in out.iterdir()) == cli_files
    written = results.write(tmp_path / "again")
    assert sorted(written) == cli_files
    assert stable(load_summary(tmp_path / "again")) == stable(load_summary(cli_dir))
    # CSV files are byte-identical (VTU too: same fields, same writer)
    for f in cli_files:
        if f.endswith(".csv") or f.endswith(".vtu"):
            assert (out / f).read_bytes() == (cli_dir / f).read_bytes(), f


@pytest.mark.parametrize("name", EXAMPLES_COMPARED)
def test_probe_line_history_equal_the_cli_csv(name, cli_runs, py_runs):
    cli_dir = cli_runs(name)
    results, _ = py_runs(name)
    cli = load_summary(cli_dir)
    for p in cli["probes"]:
        probe = results.probe(p["name"])
        assert [probe["u_x"], probe["u_y"], probe["u_z"]] == p["u"]
        assert [probe[f"s_{c}"] for c in ("xx", "yy", "zz", "xy", "xz", "yz")] == p["stress"]
        assert probe["von_mises"] == p["von_mises"] and probe["peeq"] == p["peeq"]
    model = cufem.Model.from_file(EXAMPLES / f"{name}.toml")
    for line in model.check()["lines"]:
        ours = results.line(line)
        theirs = pd.read_csv(cli_dir / f"line_{line}.csv")
        pd.testing.assert_frame_equal(ours, theirs, check_exact=True, check_dtype=False)
    for csv in cli_dir.glob("history_*.csv"):
        ours = results.history(csv.stem[len("history_"):])
        theirs = pd.read_csv(csv)
        pd.testing.assert_frame_equal(ours, theirs, check_exact=True, check_dtype=False)


@pytest.mark.parametrize("name", EXAMPLES_COMPARED)
def test_meshio_reads_the_cli_vtu_and_to_meshio_agrees(name, cli, py_runs, tmp_path):
    meshio = pytest.importorskip("meshio")
    # the linear sub-cells: meshio refuses the Lagrange cells' VTU version
    # (test_lagrange_vtu.py); the points and fields are the same in both
    d = cufem.Model.from_file(EXAMPLES / f"{name}.toml").to_dict()
    d.setdefault("output", {})["vtu_cells"] = "linear"
    model = EXAMPLES / f"{name}.toml"
    linear = tmp_path / model.name
    linear.write_text(cufem.Model.from_dict(d, base=EXAMPLES).to_toml())
    cli("run", linear, "--out", tmp_path / "out", "--threads", "1", "--quiet")
    theirs = meshio.read(tmp_path / "out" / "result.vtu")
    results, _ = py_runs(name)
    ours = results.to_meshio()
    np.testing.assert_array_equal(ours.points, theirs.points)
    assert [c.type for c in ours.cells] == [c.type for c in theirs.cells] == ["hexahedron"]
    np.testing.assert_array_equal(ours.cells[0].data, theirs.cells[0].data)
    assert sorted(ours.point_data) == sorted(theirs.point_data)
    for k, v in theirs.point_data.items():
        np.testing.assert_array_equal(ours.point_data[k], v, err_msg=k)
        np.testing.assert_array_equal(results.field(k).reshape(v.shape), v, err_msg=k)
    assert sorted(ours.cell_data) == sorted(theirs.cell_data)
    for k, v in theirs.cell_data.items():
        np.testing.assert_array_equal(ours.cell_data[k][0], v[0], err_msg=k)
    # the fields without a written folder: the same arrays, from memory
    mem = cufem.Model.from_file(EXAMPLES / f"{name}.toml").run(threads=1, quiet=True)
    np.testing.assert_array_equal(mem.field("s_yy"), theirs.point_data["s_yy"][:, 0])
    np.testing.assert_array_equal(mem.points, theirs.points)


def test_check_counts(cli):
    c = cufem.Model.from_file(EXAMPLES / "cantilever_timoshenko.toml").check()
    # 5 B4 × 2×2 L9: section 5 × 5 nodes, axis 16 nodes
    assert c["bodies"][0]["elements"] == 20
    assert c["nodes"] == 25 * 16 and c["dof"] == 3 * 400
    assert c["equations"] == 3 * 400 - 3 * 25
    out = cli("check", EXAMPLES / "cantilever_timoshenko.toml").stdout
    assert "20 elements, 400 nodes, 1,200 DOF" in out


def test_history_and_line_shapes():
    r = cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml").run(threads=1, quiet=True)
    h = r.history("load")
    assert list(h.columns[:3]) == ["increment", "lambda", "iterations"]
    assert len(h) == r.summary["increments"]
    assert h["f_z"].iloc[-1] == pytest.approx(next(c for c in r.summary["contact"] if c["name"] == "load")["force"][2])
    with pytest.raises(KeyError, match="expected one of"):
        r.line("nowhere")


@pytest.mark.parametrize("name,table", [("cantilever_modes", "modes"), ("column_buckling", "buckling")])
def test_modes_equal_the_cli_csv_and_summary(name, table, cli_runs):
    cli_dir = cli_runs(name)
    results = cufem.Model.from_file(EXAMPLES / f"{name}.toml").run(threads=1, quiet=True)
    ours = getattr(results, table)()
    theirs = pd.read_csv(cli_dir / f"{table}.csv")
    pd.testing.assert_frame_equal(ours, theirs, check_exact=True, check_dtype=False)
    assert list(ours["mode"]) == list(range(1, len(ours) + 1))
    s = load_summary(cli_dir)
    if table == "modes":
        assert list(ours["frequency_hz"]) == s["modal"]["frequencies_hz"]
        assert ours[["effective_mass_x", "effective_mass_y", "effective_mass_z"]].values.tolist() == s["modal"]["effective_masses"]
    else:
        assert list(ours["load_factor"]) == s["buckling"]["factors"]
    # the other table: not computed by this analysis
    with pytest.raises(KeyError, match="analysis.type"):
        getattr(results, "buckling" if table == "modes" else "modes")()

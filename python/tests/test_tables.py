"""Every table of a run as a pandas DataFrame, against the CSV file the CLI
(`cufem run`) wrote for the same model: the same column names (with the
units in them where the file has them), dtypes, row order and values to the
last digit (conftest.read_csv)."""

import math

import pytest

from conftest import assert_same_as_csv as assert_same, load_summary, read_csv

# each kind of table: lines, histories of constraints (a free component is
# an empty field), contacts and probes, history.csv, contact points
# (bending_compact_4L9, its quarter with full-structure columns), energy.csv
# of a transient run (rod_impact), modes.csv and buckling.csv
EXAMPLES_TABLED = [
    "bending_compact_4L9",
    "bending_compact_4L9_quarter",
    "rod_impact",
    "cantilever_modes",
    "column_buckling",
]




@pytest.mark.parametrize("name", EXAMPLES_TABLED)
def test_every_table_equals_the_cli_csv(name, cli_runs, memory_runs):
    cli_dir = cli_runs(name)
    results = memory_runs(name)
    csvs = sorted(p.stem for p in cli_dir.glob("*.csv"))
    # the CLI's summary lists its files in the order it wrote them
    written = [f[: -len(".csv")] for f in load_summary(cli_dir)["files"] if f.endswith(".csv")]
    assert results.table_names() == written
    assert sorted(results.table_names()) == csvs
    for stem, table in results.tables().items():
        assert_same(table, cli_dir / f"{stem}.csv")


@pytest.mark.parametrize("name", EXAMPLES_TABLED)
def test_named_accessors_equal_the_cli_csv(name, cli_runs, memory_runs):
    cli_dir = cli_runs(name)
    results = memory_runs(name)
    s = load_summary(cli_dir)
    files = set(s["files"])
    if "history.csv" in files:
        h = results.history()
        assert_same(h, cli_dir / "history.csv")
        # a transient run's history has the time of each step after lambda
        time = ["time"] if "energy.csv" in files else []
        assert list(h.columns) == ["increment", "lambda", *time, "iterations", "plastic_points", "negative_pivots"]
        assert len(h) == s["increments"]
    for c in s["contact"]:
        points = results.contact_points(c["name"])
        assert_same(points, cli_dir / f"contact_{c['name']}.csv")
        # the points' forces add up to the contact's resultant in summary.json
        for k, axis in enumerate("xyz"):
            assert points[f"f_{axis}"].sum() == pytest.approx(c["force"][k], rel=1e-9, abs=1e-9 * max(map(abs, c["force"])))
    if "energy.csv" in files:
        e = results.energy()
        assert_same(e, cli_dir / "energy.csv")
        assert list(e.columns[:2]) == ["time_s", "kinetic_J"]
        # summary.json's energy: the last row, by bare column name
        last = {k[: k.rindex("_")]: v for k, v in e.iloc[-1].items()}
        assert last == s["energy"]
    else:
        with pytest.raises(KeyError, match='analysis.type = "transient"'):
            results.energy()


@pytest.mark.parametrize("name", EXAMPLES_TABLED)
def test_probes_equal_the_summary(name, cli_runs, memory_runs):
    s = load_summary(cli_runs(name))
    p = memory_runs(name).probes()
    assert list(p["probe"]) == [q["name"] for q in s["probes"]]
    for i, q in enumerate(s["probes"]):
        row = p.iloc[i]
        assert [row["x"], row["y"], row["z"]] == q["point"]
        assert [row["u_x"], row["u_y"], row["u_z"]] == q["u"]
        assert [row[f"s_{c}"] for c in ("xx", "yy", "zz", "xy", "xz", "yz")] == q["stress"]
        assert row["von_mises"] == q["von_mises"] and row["peeq"] == q["peeq"]
        # the dict of one probe: the same row
        one = memory_runs(name).probe(q["name"])
        assert all(one[k] == row[k] or (math.isnan(one[k]) and math.isnan(row[k])) for k in one)
        assert sorted(one) == sorted(k for k in p.columns if k != "probe")


def test_unknown_tables_name_the_ones_there(memory_runs):
    r = memory_runs("bending_compact_4L9")
    with pytest.raises(KeyError, match=r"contact 'nowhere': .*'support_left', 'support_right', 'load'"):
        r.contact_points("nowhere")
    with pytest.raises(KeyError, match=r'this run writes no energy.csv; expected one of \["line_top", "history_symmetry_y"'):
        r.table("energy")


# (Results method, its argument, the table it charts, x column, series)
# the series as report.html charts them: every measured column but the
# increment, the counts only in history.csv (the energy: every J column)
PLOTS = [
    ("bending_compact_4L9", "plot_history", ("load",), "history_load", "lambda",
     ["d_x", "d_y", "d_z", "f_x", "f_y", "f_z", "max_penetration", "f_n", "f_t"]),
    ("bending_compact_4L9", "plot_history", (), "history", "lambda", ["iterations", "plastic_points", "negative_pivots"]),
    ("bending_compact_4L9", "plot_line", ("top",), "line_top", "s", None),
    ("rod_impact", "plot_energy", (), "energy", "time_s", None),
    ("cantilever_modes", "plot_modes", (), "modes", "mode",
     ["frequency_hz", "effective_mass_x", "effective_mass_y", "effective_mass_z", "frequency_error", "mode_error"]),
    ("column_buckling", "plot_modes", (), "buckling", "mode", None),
]


@pytest.mark.parametrize("name, method, args, stem, x, series", PLOTS, ids=[f"{p[0]}-{p[3]}" for p in PLOTS])
def test_plots_draw_the_table(name, method, args, stem, x, series, cli_runs, memory_runs):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    table = read_csv(cli_runs(name) / f"{stem}.csv")
    if series is None:  # every column but x (and the increment)
        series = [c for c in table.columns if c not in (x, "increment")]
    ax = getattr(memory_runs(name), method)(*args)
    try:
        assert ax.get_xlabel() == x
        assert [l.get_label() for l in ax.get_lines()] == series
        for line, c in zip(ax.get_lines(), series):
            # the CSV's numbers, not rescaled (a unit change would show here)
            assert list(line.get_xdata()) == list(table[x]), c
            ours, theirs = line.get_ydata(), table[c].to_numpy()
            assert all(a == b or (math.isnan(a) and math.isnan(b)) for a, b in zip(ours, theirs)) and len(ours) == len(theirs), c
        # one column, into a given Axes
        fig, given = plt.subplots()
        assert getattr(memory_runs(name), method)(*args, columns=[series[-1]], ax=given) is given
        assert [l.get_label() for l in given.get_lines()] == [series[-1]]
        with pytest.raises(KeyError, match="not charted"):
            getattr(memory_runs(name), method)(*args, columns=["increment"], ax=given)
    finally:
        plt.close("all")


def test_plots_without_matplotlib_name_the_extra(memory_runs, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(ImportError) as e:
        memory_runs("bending_compact_4L9").plot_line("top")
    assert str(e.value).startswith("Results.plot_table('line_top') needs matplotlib, which is not installed"), e.value
    assert 'pip install "./python[plot]"' in str(e.value)


def test_plots_of_tables_the_run_has_not(memory_runs):
    r = memory_runs("bending_compact_4L9")
    with pytest.raises(KeyError, match='analysis.type = "transient"'):
        r.plot_energy()
    with pytest.raises(KeyError, match='analysis.type = "modal" or "buckling"'):
        r.plot_modes()
    with pytest.raises(ValueError, match="no chart"):
        r.plot_table("contact_load")

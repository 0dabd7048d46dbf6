"""The notebook example (examples/python/bending_compact_notebook.ipynb)
executes as a reader runs it — a Jupyter kernel (nbclient, ipykernel)
started in the notebook's folder — and every DataFrame it shows equals the
CSV file the CLI wrote for the same model; its cells display the report
inline and the plots as images."""

import os
import shutil
from html import escape
from pathlib import Path

import nbclient
import nbformat
import pandas as pd
import pytest

from conftest import EXAMPLES, assert_same_as_csv, load_summary

NOTEBOOK = EXAMPLES / "python" / "bending_compact_notebook.ipynb"
MODEL = "bending_compact_4L9"
# the notebook's variables and the CSV file each shows
FRAMES = {"load": "history_load", "top": "line_top", "contact": "contact_load"}


def dump_cell(folder):
    """A cell appended to the notebook: it pickles the notebook's DataFrames
    into `folder` and names its output folder there."""
    return nbformat.v4.new_code_cell(
        f"""_dump = Path({str(folder)!r})
for _name in {sorted([*FRAMES, "probes"])!r}:
    globals()[_name].to_pickle(_dump / f"{{_name}}.pkl")
for _stem, _table in tables.items():
    _table.to_pickle(_dump / f"table_{{_stem}}.pkl")
(_dump / "out.txt").write_text(str(out))
(_dump / "status.txt").write_text(results.status)"""
    )


@pytest.fixture(scope="module")
def executed(tmp_path_factory):
    """The notebook, executed with the dump cell; the dump's folder."""
    nb = nbformat.read(NOTEBOOK, as_version=4)
    folder = tmp_path_factory.mktemp("notebook")
    nb.cells.append(dump_cell(folder))
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(NOTEBOOK.parent)}})
    # the kernel's own matplotlib backend (inline), as in Jupyter, whatever
    # MPLBACKEND the tests run with
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    client.execute(env=env)
    out = Path((folder / "out.txt").read_text())
    yield nb, folder, out
    # the notebook's temporary output folder
    shutil.rmtree(out.parent, ignore_errors=True)


def test_the_notebook_is_committed_without_outputs():
    nb = nbformat.read(NOTEBOOK, as_version=4)
    nbformat.validate(nb)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert code and all(not c.outputs and c.execution_count is None for c in code)
    # documented: markdown between the code
    assert sum(c.cell_type == "markdown" for c in nb.cells) >= 4


def test_the_notebooks_dataframes_equal_the_csv_files(executed, cli_runs):
    _, folder, out = executed
    assert (folder / "status.txt").read_text() == "converged"
    cli_dir = cli_runs(MODEL)
    for name, stem in FRAMES.items():
        frame = pd.read_pickle(folder / f"{name}.pkl")
        assert_same_as_csv(frame, cli_dir / f"{stem}.csv")
        assert_same_as_csv(frame, out / f"{stem}.csv")
    # tables(): every CSV the run wrote, each equal to it
    stems = sorted(p.name[len("table_"): -len(".pkl")] for p in folder.glob("table_*.pkl"))
    assert stems == sorted(p.stem for p in cli_dir.glob("*.csv")) == sorted(p.stem for p in out.glob("*.csv"))
    for stem in stems:
        assert_same_as_csv(pd.read_pickle(folder / f"table_{stem}.pkl"), cli_dir / f"{stem}.csv")
    # probes(): summary.json's probes
    probes = pd.read_pickle(folder / "probes.pkl")
    summary = load_summary(cli_dir)
    assert list(probes["probe"]) == [p["name"] for p in summary["probes"]]
    for i, p in enumerate(summary["probes"]):
        assert [probes[f"u_{a}"].iloc[i] for a in "xyz"] == p["u"]
        assert probes["peeq"].iloc[i] == p["peeq"]


def test_the_notebook_shows_the_report_and_the_plots(executed):
    nb, _, out = executed
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    html = [o.data["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    # the report inline: the page the run wrote, escaped into an iframe
    report = [h for h in html if h.startswith("<iframe srcdoc=")]
    assert len(report) == 1
    page = (out / "report.html").read_text(encoding="utf-8")
    assert escape(page, quote=True) in report[0]
    # the DataFrames as tables, the two plots as images
    assert sum(h.lstrip().startswith("<div>") for h in html) >= 3
    assert sum("image/png" in o.get("data", {}) for o in outputs) == 2

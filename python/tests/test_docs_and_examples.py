"""The Python the documentation shows runs as written (issue 52): every
```python block of README.md and docs/python.md, and every script in
examples/python/, in a fresh folder holding a link to examples/ (the
snippets' paths are relative to the repository, as a reader runs them).

A snippet whose comment promises a pandas DataFrame (``name = …  # … pandas
DataFrame``) must bind one: a ``pip install`` without pandas gave a dict.
Each example must accept ``--out FOLDER`` and write its files there; what
they hold is checked against what the physics says of them."""

import csv
import re
import subprocess
import sys

import pandas as pd
import pytest

from conftest import EXAMPLES, ROOT

DOCS = [ROOT / "README.md", ROOT / "docs" / "python.md"]
SCRIPTS = sorted((EXAMPLES / "python").glob("*.py"))
BLOCK = re.compile(r"^```python\n(.*?)^```$", re.S | re.M)
DATAFRAME = re.compile(r"^(\w+)\s*=.*#.*pandas DataFrame", re.M)


def python_blocks(path):
    return BLOCK.findall(path.read_text(encoding="utf-8"))


def in_a_fresh_folder(tmp_path):
    """A folder like a checkout's root to run in: examples/ is a link."""
    (tmp_path / "examples").symlink_to(EXAMPLES, target_is_directory=True)
    return tmp_path


def test_the_docs_have_python_snippets():
    """The README shows the package in a ```python block (the test below
    runs every one; a README without one would pass it by running none)."""
    assert python_blocks(ROOT / "README.md"), "README.md: no ```python block"
    assert python_blocks(ROOT / "docs" / "python.md"), "docs/python.md: no ```python block"


@pytest.mark.parametrize(
    "doc, k",
    [(doc, k) for doc in DOCS for k in range(len(python_blocks(doc)))],
    ids=lambda v: v.name if hasattr(v, "name") else str(v),
)
def test_a_python_snippet_of_the_docs_runs(doc, k, tmp_path, monkeypatch):
    code = python_blocks(doc)[k]
    monkeypatch.chdir(in_a_fresh_folder(tmp_path))
    namespace = {"__name__": "__main__"}
    exec(compile(code, f"{doc.name} ```python block {k + 1}", "exec"), namespace)
    promised = DATAFRAME.findall(code)
    for name in promised:
        assert isinstance(namespace[name], pd.DataFrame), f"{doc.name}: {name} is {type(namespace[name])}"
    if doc.name == "README.md" and k == 0:
        assert promised, "README.md: the snippet no longer shows a DataFrame (this test checks one)"


def run_example(script, tmp_path):
    out = tmp_path / "out"
    p = subprocess.run(
        [sys.executable, str(script), "--out", str(out)],
        cwd=in_a_fresh_folder(tmp_path),
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert p.returncode == 0, f"{script.name} exited {p.returncode}:\n{p.stdout}\n{p.stderr}"
    return out, p.stdout


def png(path):
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"


def check_block_sweep(out, stdout):
    """The punch force and the plastic strain at the punch edge grow with
    the depth (a deeper punch into a hardening block); the edge yields
    before the centre (the stress concentrates at the punch's corner)."""
    png(out / "block_indentation_sweep.png")
    rows = re.findall(r"depth ([\d.]+) mm: force ([\d.]+) MN, peeq edge ([\d.]+), centre ([\d.]+) \(converged", stdout)
    assert len(rows) == 4, stdout
    depth, force, edge, centre = (list(map(float, c)) for c in zip(*rows))
    assert depth == sorted(depth) and force == sorted(force) and edge == sorted(edge), rows
    assert all(e > c for e, c in zip(edge, centre)), rows


def check_tube_dask(out, stdout):
    """Three converged variants, run by Dask; a thicker wall takes a larger
    roller force at the same displacement (stiffer section)."""
    png(out / "tube_wall_thickness.png")
    with open(out / "tube_wall_thickness.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [r["status"] for r in rows] == ["converged"] * 3, rows
    assert all(r["error"] == "" for r in rows), rows
    force = [float(r["roller force [kN]"]) for r in rows]
    thickness = [float(r["bodies.0.section.thickness"]) for r in rows]
    assert thickness == sorted(thickness) and force == sorted(force) and force[0] > 0, rows


CHECKS = {
    "block_indentation_sweep.py": check_block_sweep,
    "tube_wall_thickness_dask.py": check_tube_dask,
}


def test_every_example_has_a_check():
    assert SCRIPTS, "examples/python/ holds no script"
    assert sorted(s.name for s in SCRIPTS) == sorted(CHECKS), "add a check for a new example here"


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda s: s.name)
def test_a_python_example_runs_as_written(script, tmp_path):
    out, stdout = run_example(script, tmp_path)
    CHECKS[script.name](out, stdout)

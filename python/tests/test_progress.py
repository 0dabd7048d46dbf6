"""`Model.run` prints what `cufem run` prints (issue 52, item 9), from the
same library functions (`cufem::io::report`): the header and the final
report on stdout, the set-up line, a line per increment (residuals, plastic
points, penetration) and per cutback on stderr, the stop message of a run
that stopped early; `quiet=True` prints nothing but the warnings.

The reference is the CLI's own output for the same model and threads: the
two must agree line for line, but for the wall time in the table and the
output folder's name."""

import re

import cufem
from conftest import EXAMPLES

# a line that leaves the bar past its end (y = 0.25 m): a model warning
WARNING_PROBE = """
[[lines]]
name = "past_the_end"
from = [0.005, 0.2, 0.01]
to = [0.005, 0.3, 0.01]
points = 11
"""

# the table's row: "cufem 1D (…)  DOF  time  increments  iterations"
TIME = re.compile(r"^(cufem 1D \(.*\)\s+[\d,]+\s+)\d+\.\d+(\s+\d+\s+\d+)$")


def normalized(text, folder):
    """The printed text with the wall time and the output folder replaced."""
    lines = []
    for line in text.replace(str(folder), "<out>").splitlines():
        lines.append(TIME.sub(r"\1<time>\2", line))
    return lines


def run_both(cli, capsys, tmp_path, model_path, cli_code=0):
    """The CLI's and Python's stdout and stderr for one model (threads 1)."""
    p = cli("run", model_path, "--out", tmp_path / "cli", "--threads", "1", check=False)
    assert p.returncode == cli_code, p.stderr
    capsys.readouterr()
    results = cufem.Model.from_file(model_path).run(out=tmp_path / "py", threads=1)
    py = capsys.readouterr()
    return (
        (normalized(p.stdout, tmp_path / "cli"), normalized(p.stderr, tmp_path / "cli")),
        (normalized(py.out, tmp_path / "py"), normalized(py.err, tmp_path / "py")),
        results,
    )


def test_a_run_prints_the_clis_header_progress_and_report(cli, capsys, tmp_path):
    (cli_out, cli_err), (py_out, py_err), results = run_both(
        cli, capsys, tmp_path, EXAMPLES / "bending_compact_4L9.toml"
    )
    assert py_out == cli_out
    assert py_err == cli_err
    # what the lines hold, so that two empty outputs could not agree
    n = results.summary["increments"]
    assert py_out[0] == results.summary["title"]
    assert any(l.startswith("cufem 1D (bar 10B4 - 4L9)") and "<time>" in l for l in py_out), py_out
    assert any(l.startswith("contact_centre [0.005, 0.125, 0.01]") for l in py_out), py_out
    assert py_out[-1] == f"wrote {len(results.files)} files to <out>"
    assert py_err[0].startswith("solving 2145 equations, nnz(L) = ")
    increments = [l for l in py_err if l.startswith("increment ")]
    assert len(increments) == n == 15
    assert all("residuals [" in l and "plastic points" in l for l in increments), increments


def test_cutbacks_and_an_early_stop_print_as_the_cli_prints_them(cli, capsys, tmp_path):
    """At most 3 Newton iterations and Δλ ≥ 0.15 from 0.2: the third
    increment fails at 0.2 and its cutback to 0.1 is below the minimum, so
    the run stops at λ = 0.4 (CLI exit code 2) after printing a cutback."""
    text = (EXAMPLES / "bending_compact_4L9.toml").read_text()
    assert "\n[solver]\nincrements = 15\n" in text
    text = text.replace(
        "\n[solver]\nincrements = 15\n", "\n[solver]\nincrements = 5\nmax_iterations = 3\nmin_increment = 0.15\n"
    )
    path = tmp_path / "stops.toml"
    path.write_text(text)
    (cli_out, cli_err), (py_out, py_err), results = run_both(cli, capsys, tmp_path, path, cli_code=2)
    assert results.status == "not_converged"
    assert py_out == cli_out
    assert py_err == cli_err
    assert any(l.startswith("  cutback: increment 3 (λ = 0.6000") for l in py_err), py_err
    assert "the analysis stopped early: " in "\n".join(py_err)
    assert py_err[-1] == "results of the last converged increment (load factor 0.4000) are in <out>", py_err


def test_quiet_prints_nothing(capsys):
    capsys.readouterr()
    results = cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml").run(threads=1, quiet=True)
    printed = capsys.readouterr()
    assert (printed.out, printed.err) == ("", "")
    assert results.summary["increments"] == 15


def test_warnings_are_printed_also_when_quiet(capsys):
    """A warning goes to stderr as the CLI prints it, `quiet` or not (and
    to summary["warnings"])."""
    text = (EXAMPLES / "bending_compact_4L9.toml").read_text()
    model = cufem.Model.from_toml(text + WARNING_PROBE, base=EXAMPLES)
    assert model.check()["warnings"], "the added probe must give a warning"
    capsys.readouterr()
    results = model.run(threads=1, quiet=True)
    printed = capsys.readouterr()
    assert printed.out == ""
    lines = printed.err.splitlines()
    assert lines and all(l.startswith("warning: ") for l in lines), lines
    assert [l[len("warning: ") :] for l in lines] == results.summary["warnings"]

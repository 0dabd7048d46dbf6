"""SIGINT to a Python process running a long model keeps the last converged increment."""

import json
import signal
import subprocess
import sys
import time

from conftest import EXAMPLES

# Python's own Ctrl-C handler, as in a terminal: a process started in the
# background of a non-interactive shell (CI) inherits SIGINT ignored, and
# Python then leaves it ignored
SCRIPT = """
import signal, sys, cufem
signal.signal(signal.SIGINT, signal.default_int_handler)
r = cufem.Model.from_file(sys.argv[1]).run(out=sys.argv[2], threads=1)
print("status", r.summary["status"], r.summary["increments"], flush=True)
"""


def test_sigint_stops_the_run_and_keeps_the_last_increment(tmp_path):
    out = tmp_path / "out"
    p = subprocess.Popen(
        [sys.executable, "-c", SCRIPT, str(EXAMPLES / "bending_tube_20L9.toml"), str(out)],
        stderr=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    lines = []
    deadline = time.time() + 120
    # wait for two converged increments, then Ctrl-C
    while time.time() < deadline:
        line = p.stderr.readline()
        if not line:
            break
        lines.append(line)
        if line.startswith("increment   2"):
            p.send_signal(signal.SIGINT)
            break
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 0, "".join(lines) + stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "interrupted"
    assert 2 <= summary["increments"] < 15
    assert 0 < summary["load_factor"] < 1
    # the script's own line comes last, after the CLI's report
    assert stdout.splitlines()[-1].split() == ["status", "interrupted", str(summary["increments"])], stdout
    assert "interrupted: stopping at the next safe point" in stderr
    assert "result.vtu" in summary["files"]


SCRIPT_OUT = """
import signal, sys, cufem
signal.signal(signal.SIGINT, signal.default_int_handler)
r = cufem.Model.from_file(sys.argv[1]).run(out=sys.argv[2], threads=1)
print("out", r.out, r.summary["status"], flush=True)
"""


def test_sigint_never_replaces_a_converged_set(tmp_path):
    """Issue 24 item 3: an interrupted run into a folder holding a converged
    set used to replace it with the partial one; now the converged set stays
    byte for byte and the partial one goes to ``out.partial``."""
    import cufem

    out = tmp_path / "out"
    cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml").run(out=out, threads=1, quiet=True)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    p = subprocess.Popen(
        [sys.executable, "-c", SCRIPT_OUT, str(EXAMPLES / "bending_tube_20L9.toml"), str(out)],
        stderr=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    deadline = time.time() + 120
    while time.time() < deadline:
        line = p.stderr.readline()
        if not line or line.startswith("increment   2"):
            p.send_signal(signal.SIGINT)
            break
    stdout, stderr = p.communicate(timeout=120)
    assert p.returncode == 0, stderr
    assert {q.name: q.read_bytes() for q in out.iterdir()} == before
    partial = tmp_path / "out.partial"
    assert stdout.splitlines()[-1].split() == ["out", str(partial), "interrupted"], stdout + stderr
    assert json.loads((partial / "summary.json").read_text())["status"] == "interrupted"
    assert f"the converged results already in {out} were kept as they were" in stderr, stderr

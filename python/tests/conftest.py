"""Shared fixtures: the repository, the CLI binary, CLI runs."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def cli_binary() -> Path:
    """`target/release/cufem` of this checkout (built if missing)."""
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    exe = target / "release" / "cufem"
    if not exe.exists():
        subprocess.run(["cargo", "build", "--release", "--bin", "cufem"], cwd=ROOT, check=True)
    return exe


@pytest.fixture(scope="session")
def cli():
    exe = cli_binary()

    def run(*args, check=True):
        p = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"cufem {' '.join(map(str, args))} exited {p.returncode}: {p.stderr}")
        return p

    return run


@pytest.fixture(scope="session")
def cli_runs(cli, tmp_path_factory):
    """The CLI's output folder of an example (run once per session, threads=1)."""
    cache = {}

    def get(name):
        if name not in cache:
            out = tmp_path_factory.mktemp("cli") / name
            cli("run", EXAMPLES / f"{name}.toml", "--out", out, "--threads", "1", "--quiet")
            cache[name] = out
        return cache[name]

    return get


@pytest.fixture(scope="session")
def memory_runs():
    """`cufem.Results` of an example run in memory (no files written; run
    once per session, threads=1)."""
    import cufem

    cache = {}

    def get(name):
        if name not in cache:
            cache[name] = cufem.Model.from_file(EXAMPLES / f"{name}.toml").run(threads=1, quiet=True)
        return cache[name]

    return get


def load_summary(folder) -> dict:
    with open(Path(folder) / "summary.json") as f:
        return json.load(f)


def read_csv(path):
    """A CSV file of a run as pandas reads it, each number the f64 its text
    spells: Rust's shortest round-trip `{:e}` is parsed back exactly by
    pandas 3's default parser, by an older one with `float_precision =
    "round_trip"` (which pandas 3 deprecates)."""
    import pandas as pd

    exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
    return pd.read_csv(path, **exact)


def assert_same_as_csv(frame, path):
    """`frame` equals the CSV file at `path`: column names, dtypes, row
    order and every value to the last digit."""
    import pandas as pd

    pd.testing.assert_frame_equal(frame, read_csv(path), check_exact=True, check_dtype=True, obj=Path(path).name)

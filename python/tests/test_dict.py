"""from_dict round-trips from_file."""

import numpy as np
import pytest

import cufem
from conftest import EXAMPLES

ALL = sorted(p.stem for p in EXAMPLES.glob("*.toml"))


@pytest.mark.parametrize("name", ALL)
def test_from_dict_round_trips_from_file(name):
    m = cufem.Model.from_file(EXAMPLES / f"{name}.toml")
    d = m.to_dict()
    again = cufem.Model.from_dict(d, base=m.base)
    assert again.check() == m.check()
    assert again.to_dict() == d


def test_from_dict_runs_to_the_same_results():
    m = cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml")
    a = m.run(threads=1, quiet=True).summary
    b = cufem.Model.from_dict(m.to_dict()).run(threads=1, quiet=True).summary
    for k in ("probes", "reactions", "contact", "max_peeq", "increments", "status"):
        assert a[k] == b[k]


def test_numpy_values_are_accepted():
    d = cufem.Model.from_file(EXAMPLES / "cantilever_timoshenko.toml").to_dict()
    d["loads"][0]["total_force"] = np.array([0.0, 0.0, -1000.0])
    d["bodies"][0]["axis"]["elements"] = np.int64(5)
    d["materials"][0]["young_modulus"] = np.float64(70e9)
    assert cufem.Model.from_dict(d).check()["dof"] == 1200

"""Every model error surfaces as cufem.ModelError with the CLI's message."""

import pytest
import tomli_w

import cufem
from cufem.model import set_path
from conftest import EXAMPLES

BASE = EXAMPLES / "cantilever_timoshenko.toml"

# (dotted path, value): each one makes the cantilever invalid
MUTATIONS = [
    ("materials.0.young_modulus", -70e9),
    ("materials.0.young_modulus", 1e-300),
    ("materials.0.poisson_ratio", 0.5),
    ("bodies.0.material", "steel"),
    ("bodies.0.section.element", "L7"),
    ("bodies.0.section.x.elements", 0),
    ("bodies.0.axis.to", -1.0),
    ("constraints.0.body", "nobody"),
    ("constraints.0.fix", ["q"]),
    ("loads.0.total_force", [0.0, 1e300, 0.0]),
    ("loads.0.total_force", [0.0, 0.0]),
    ("probes.0.point", [5.0, 5.0, 5.0]),
    ("lines.0.points", 1),
    ("lines.0.plot", ["nothing"]),
    ("references.0.quantity", "s_qq"),
    ("solver", {"increments": 0}),
    ("bodies.0.colour", "red"),
    ("constraints", []),
]


def mutated(path, value):
    return set_path(cufem.Model.from_file(BASE).to_dict(), path, value)


@pytest.mark.parametrize("path,value", MUTATIONS, ids=[f"{p}={v}" for p, v in MUTATIONS])
def test_model_errors_carry_the_cli_message(path, value, cli, tmp_path):
    d = mutated(path, value)
    file = tmp_path / "bad.toml"
    file.write_text(tomli_w.dumps(d))
    p = cli("check", file, check=False)
    assert p.returncode == 1, p.stderr
    with pytest.raises(cufem.ModelError) as e:
        cufem.Model.from_file(file)
    message = str(e.value)
    assert isinstance(e.value, ValueError)
    # the CLI prints "error: invalid model FILE: MESSAGE"
    assert f"error: invalid model {file}: {message}" in p.stderr
    # the same text and the same dict give the same message
    with pytest.raises(cufem.ModelError) as t:
        cufem.Model.from_toml(file.read_text())
    assert str(t.value) == message
    with pytest.raises(cufem.ModelError) as m:
        cufem.Model.from_dict(d)
    if "line" not in message:  # parser messages quote lines of the text, which differs
        assert str(m.value) == message


def test_toml_syntax_error(cli, tmp_path):
    file = tmp_path / "bad.toml"
    file.write_text(BASE.read_text().replace('name = "beam"', 'name = "beam'))
    p = cli("check", file, check=False)
    with pytest.raises(cufem.ModelError) as e:
        cufem.Model.from_file(file)
    assert str(e.value).startswith("model file: TOML parse error")
    assert f"error: invalid model {file}: {e.value}" in p.stderr


def test_dict_values_toml_cannot_hold():
    d = cufem.Model.from_file(BASE).to_dict()
    with pytest.raises(cufem.ModelError, match=r"loads\.0\.total_force\.1 = None"):
        cufem.Model.from_dict(set_path(d, "loads.0.total_force", [0.0, None, 1.0]))
    with pytest.raises(cufem.ModelError, match="expected a number, string"):
        cufem.Model.from_dict(set_path(d, "title", object()))


def test_missing_file_is_an_os_error():
    with pytest.raises(OSError, match="cannot read model file"):
        cufem.Model.from_file(EXAMPLES / "no_such_model.toml")

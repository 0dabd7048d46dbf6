"""One install brings what the docs and examples use (issue 52, item 6 and
8): the installed package's metadata (python/pyproject.toml) lists pandas
as a dependency and, in the `all` extra, every other third-party module
that examples/python/ imports; without an extra's package the function
that needs it says which extra to install."""

import ast
import importlib.metadata
import re
import sys

import pytest

import cufem
from conftest import EXAMPLES

# import name → the requirement that brings it
REQUIREMENT = {"matplotlib": "matplotlib", "dask": "dask[distributed]", "pandas": "pandas", "numpy": "numpy",
               "meshio": "meshio"}


def requirements():
    """{extra or "": set of requirement strings} of the installed cufem."""
    out = {}
    for r in importlib.metadata.requires("cufem") or []:
        m = re.match(r"^\s*([^;]+?)\s*(?:;\s*extra\s*==\s*['\"](\w+)['\"])?\s*$", r)
        assert m, r
        out.setdefault(m.group(2) or "", set()).add(m.group(1).replace(" ", ""))
    return out


def third_party_imports(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            names.add(node.module.split(".")[0])
    return {n for n in names if n not in sys.stdlib_module_names and n != "cufem"}


def test_pandas_is_a_dependency_and_all_brings_what_the_examples_import():
    req = requirements()
    assert {"numpy", "pandas"} <= req[""], req
    assert {"meshio", "dask[distributed]", "matplotlib"} <= req["all"], req
    scripts = sorted((EXAMPLES / "python").glob("*.py"))
    assert scripts
    for script in scripts:
        for module in third_party_imports(script):
            assert module in REQUIREMENT, f"{script.name} imports {module}: add it to the `all` extra and here"
            assert REQUIREMENT[module] in req["all"] | req[""], f"{script.name}: {module} not in [all]"


@pytest.fixture(scope="module")
def results():
    return cufem.Model.from_file(EXAMPLES / "bending_compact_4L9.toml").run(threads=1, quiet=True)


def test_without_meshio_to_meshio_names_the_extra(results, monkeypatch):
    monkeypatch.setitem(sys.modules, "meshio", None)  # `import meshio` raises ImportError
    with pytest.raises(ImportError) as e:
        results.to_meshio()
    assert str(e.value).startswith("Results.to_meshio() needs meshio, which is not installed"), e.value
    assert 'pip install "./python[meshio]"' in str(e.value), e.value


def test_without_pandas_a_table_names_the_dependency(results, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match=r"needs pandas, which is not installed: pip install pandas"):
        results.line("top")

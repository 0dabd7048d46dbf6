"""Imports of the packages some functions need, with an error that says
what to install (python/pyproject.toml: pandas is a dependency, the others
are extras; ``pip install "./python[all]"`` brings every one)."""

from __future__ import annotations

import importlib

# the module → (what pip installs, the extra that brings it; None: a dependency)
_PACKAGES = {
    "pandas": ("pandas", None),
    "meshio": ("meshio", "meshio"),
    "dask.distributed": ("dask[distributed]", "dask"),
    "matplotlib": ("matplotlib", "plot"),
    "matplotlib.pyplot": ("matplotlib", "plot"),
}


def require(module: str, what: str):
    """`module`, imported; if it is missing, an ImportError naming `what`
    needs it and the command that installs it."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        package, extra = _PACKAGES[module]
        if extra is None:
            how = f'pip install {package} (a dependency of cufem: a plain `pip install ./python` brings it)'
        else:
            how = f'pip install "{package}", or cufem with its extra: pip install "./python[{extra}]" (or "./python[all]")'
        raise ImportError(f"{what} needs {package}, which is not installed: {how}") from e

"""cufem from Python: build, run and post-process refined 1D CUF models.

>>> import cufem
>>> model = cufem.Model.from_file("examples/bending_compact_4L9.toml")
>>> results = model.run(out="out/compact")
>>> results.summary["probes"][0]["peeq"]

The model is read by the CLI's own parser (``cufem run``), so the schema and
every validation message are the CLI's; an invalid model raises
:class:`ModelError` (a ``ValueError``). ``cufem.study`` runs parameter
variants of a model in a process pool or on a Dask cluster.
"""

from ._native import ModelError
from .model import Model
from .results import Results

__all__ = ["Model", "Results", "ModelError", "study"]
__version__ = "0.1.0"


def __getattr__(name):
    # `cufem.study` without importing concurrent.futures at `import cufem`
    if name == "study":
        import importlib

        return importlib.import_module(".study", __name__)
    raise AttributeError(name)

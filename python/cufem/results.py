"""`cufem.Results`: the solution of a run, read by name."""

from __future__ import annotations

import json
import os
from typing import Dict, Optional

import numpy as np

from ._extras import require


def _table(columns):
    """The columns as a pandas DataFrame (integer counts as integers)."""
    pd = require("pandas", "a table of results (Results.line, Results.history)")
    data = {name: np.asarray(values, dtype=float) for name, values in columns}
    for k in ("increment", "iterations", "plastic_points", "mode"):
        if k in data and np.all(np.isfinite(data[k])):
            data[k] = data[k].astype(np.int64)
    return pd.DataFrame(data)


class Results:
    """The results of :meth:`cufem.Model.run` (the last converged increment
    if the analysis stopped early: see ``summary["status"]``)."""

    def __init__(self, native, out: Optional[str] = None):
        self._native = native
        #: the folder the CLI's files were written to, if any
        self.out = out
        self._summary = None
        self._vtu = None

    @property
    def summary(self) -> dict:
        """The content of ``summary.json`` (``files``: those written by
        ``run(out=…)``, else empty)."""
        if self._summary is None:
            self._summary = json.loads(self._native.summary_json())
        return self._summary

    @property
    def status(self) -> str:
        """``"converged"``, ``"not_converged"`` or ``"interrupted"``."""
        return self.summary["status"]

    @property
    def files(self):
        """The files written by ``run(out=…)`` (None if nothing was written)."""
        return self._native.files

    def probe(self, name: str) -> Dict[str, float]:
        """Every quantity at probe `name`: ``x, y, z`` (the point), ``u_x`` …
        ``u_z``, ``s_xx`` … ``s_yz``, ``von_mises``, ``peeq``, ``e_xx`` …
        (the values of summary.json, strains included)."""
        return dict(self._native.probe(name))

    def line(self, name: str):
        """The samples of ``[[lines]]`` entry `name` as ``line_<name>.csv``
        has them (columns ``s, x, y, z, u_x, …, peeq, e_xx, …``), as a
        pandas DataFrame."""
        return _table(self._native.line(name))

    def history(self, name: str):
        """Per converged increment, as ``history_<name>.csv``: for a
        constraint set the prescribed displacement ``u_*`` and reaction
        ``r_*``; for an indenter or contact its displacement ``d_*``, force
        ``f_*``, ``max_penetration``, ``plastic_points``, ``f_n`` and ``f_t``;
        in a model cut by symmetry planes, also the full structure's
        ``full_r_*`` or ``full_f_*`` (not for a plane's own reaction);
        for ``"probes"`` (``history_probes.csv``) every probe's displacement
        ``<probe>.u_*``. A pandas DataFrame."""
        return _table(self._native.history(name))

    def modes(self):
        """The vibration modes of a modal analysis, as ``modes.csv`` has
        them: ``mode`` (from 1), ``frequency_hz`` and the effective masses
        ``effective_mass_x``, ``_y``, ``_z`` (kg), a pandas DataFrame;
        KeyError without a modal analysis."""
        return _table(self._native.modes(False))

    def buckling(self):
        """The buckling modes, as ``buckling.csv`` has them: ``mode``,
        ``load_factor``, the critical load ``critical_load_*`` (N) and, cut
        by symmetry planes, the full structure's ``full_critical_load_*``;
        a pandas DataFrame, KeyError without a buckling analysis."""
        return _table(self._native.modes(True))

    def _vtu_data(self) -> dict:
        # the arrays result.vtu holds, computed by the native module
        if self._vtu is None:
            self._vtu = self._native.fields()
        return self._vtu

    @property
    def points(self) -> np.ndarray:
        """The points of ``result.vtu`` (n, 3), m."""
        return self._vtu_data()["points"]

    def field(self, name: str) -> np.ndarray:
        """Point field `name` of ``result.vtu`` at :attr:`points`:
        ``displacement`` (n, 3), ``s_yy``, ``von_mises``, ``peeq``,
        ``contact_force`` …"""
        data = self._vtu_data()["point_data"]
        if name not in data:
            raise KeyError(f"field {name!r}: expected one of {sorted(data)}")
        return data[name]

    @property
    def field_names(self):
        """The point fields of ``result.vtu``."""
        return list(self._vtu_data()["point_data"])

    def to_meshio(self):
        """The fields of ``result.vtu`` as a ``meshio.Mesh``: the linear
        hexahedra of ``output.vtu_cells = "linear"`` (meshio reads the
        Lagrange cells of ``result.vtu`` but knows no Lagrange shape), the
        point data and the ``body``/``element`` cell data, each (n,
        components) like ``meshio.read`` gives them. Needs meshio (the
        ``meshio`` extra)."""
        meshio = require("meshio", "Results.to_meshio()")

        d = self._vtu_data()

        # as meshio.read gives them: (n, components), also for one component
        def column(v):
            return v.reshape(len(v), -1)

        return meshio.Mesh(
            d["points"],
            [("hexahedron", d["connectivity"])],
            point_data={k: column(v) for k, v in d["point_data"].items()},
            cell_data={k: [column(v)] for k, v in d["cell_data"].items()},
        )

    def write(self, dir, force: bool = False):
        """Writes the CLI's files (summary.json, result.vtu, CSV, PNG) into
        `dir` as ``cufem run --out dir`` does; returns their names."""
        return self._native.write(os.fspath(dir), force)

    def __repr__(self) -> str:
        s = self.summary
        return f"<cufem.Results {s['title']!r}: {s['status']}, load factor {s['load_factor']:.4g}, {s['increments']} increments>"

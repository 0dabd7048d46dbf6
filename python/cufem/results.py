"""`cufem.Results`: the solution of a run, read by name."""

from __future__ import annotations

import html
import json
import os
import tempfile
from pathlib import Path
from typing import Dict, Optional

import numpy as np

from ._extras import require


def _column(kind, values):
    """One column with the dtype ``pandas.read_csv`` gives its CSV column:
    real numbers as float64 (an absent value NaN), counts as int64 (as
    float64 with NaN where some are absent), text as text."""
    if kind == "count":
        return np.asarray(values, dtype=np.int64)
    if kind == "text":
        return list(values)
    values = np.asarray(values, dtype=float)
    if kind == "optional_count" and np.all(np.isfinite(values)):
        return values.astype(np.int64)
    return values


def _table(columns):
    """Typed columns ``(CSV header, kind, values, unit)`` of the native
    module as a pandas DataFrame, equal to ``pandas.read_csv`` of the CSV
    file."""
    pd = require("pandas", "a table of results (Results.line, Results.history, Results.table)")
    return pd.DataFrame({name: _column(kind, values) for name, kind, values, _ in columns})


class Results:
    """The results of :meth:`cufem.Model.run` (the last converged increment
    if the analysis stopped early: see ``summary["status"]``)."""

    def __init__(self, native, out: Optional[str] = None):
        self._native = native
        #: the folder the CLI's files were written to, if any
        self.out = out
        self._summary = None
        self._vtu = None
        self._report = None

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
        and, in a laminate, the failure indices (summary.json's probes hold
        the displacement, stress, von Mises and peeq; the strains and
        indices are the same evaluation's, given only here and by
        :meth:`probes`)."""
        return dict(self._native.probe(name))

    def line(self, name: str):
        """The samples of ``[[lines]]`` entry `name` as ``line_<name>.csv``
        has them (columns ``s, x, y, z, u_x, …, peeq, e_xx, …``), as a
        pandas DataFrame."""
        return _table(self._native.line(name))

    def history(self, name: Optional[str] = None):
        """Per converged increment, as ``history_<name>.csv``; without a
        name, ``history.csv``: ``increment``, ``lambda``, ``iterations``,
        ``plastic_points`` and ``negative_pivots`` (NaN where not known).
        For a constraint set the prescribed displacement ``u_*`` and reaction
        ``r_*``; for an indenter or contact its displacement ``d_*``, force
        ``f_*``, ``max_penetration``, ``plastic_points``, ``f_n`` and ``f_t``;
        in a model cut by symmetry planes, also the full structure's
        ``full_r_*`` or ``full_f_*`` (not for a plane's own reaction);
        for ``"probes"`` (``history_probes.csv``) every probe's displacement
        ``<probe>.u_*``. A pandas DataFrame."""
        if name is None:
            return self.table("history")
        return _table(self._native.history(name))

    def probes(self):
        """Every probe at the end, one row per probe (in the model's order),
        ``probe`` (its name), the point ``x, y, z`` (m), ``u_x`` … (m),
        ``s_xx`` … ``von_mises`` (Pa), ``peeq`` (as summary.json's
        ``probes``), then ``e_xx`` … and the failure indices of a laminate
        (not in summary.json); a pandas DataFrame (:meth:`probe` gives one
        row as a dict)."""
        return _table(self._native.probes())

    def contact_points(self, name: str):
        """The final state of every point of contact `name` (an indenter or
        a contact pair), as ``contact_<name>.csv``: ``node``, ``x, y, z``
        (m), ``gap`` (m), ``f_x`` … (N), ``area`` (m²), ``pressure`` and
        ``traction`` (Pa), ``active``, ``slip`` (m) and ``sliding`` (0 or
        1); a pandas DataFrame, KeyError naming the contacts for another
        name."""
        stem = f"contact_{name}"
        names = self.table_names()
        if stem not in names:
            contacts = [n[len("contact_") :] for n in names if n.startswith("contact_")]
            raise KeyError(f"contact {name!r}: expected an indenter or contact of this run, one of {contacts}")
        return self.table(stem)

    def energy(self):
        """The energy balance of a transient run per converged time step, as
        ``energy.csv``: ``time_s`` and the energies in J (``kinetic_J``,
        ``internal_J``, ``elastic_J``, ``plastic_J``, ``damping_J``,
        ``external_J``, ``contact_J``, ``supports_J``, ``balance_J``,
        ``impactors_J``; ``interfaces_J``, ``delamination_J`` and
        ``damage_*_J`` in models that have them); a pandas DataFrame,
        KeyError without a transient analysis."""
        if "energy" not in self.table_names():
            raise KeyError('energy.csv: this run has no transient analysis (analysis.type = "transient" computes one)')
        return self.table("energy")

    def table_names(self):
        """The stem of every CSV file the run writes (``line_<name>``,
        ``history_<name>``, ``history``, ``contact_<name>``, ``modes``,
        ``buckling``, ``energy``), in the order ``cufem run`` writes them."""
        return list(self._native.table_names())

    def table(self, stem: str):
        """The content of ``<stem>.csv`` (one of :meth:`table_names`) as a
        pandas DataFrame: the same column names (units in them as the file
        has them), row order and values as ``pandas.read_csv`` of the file
        ``cufem run`` writes; KeyError listing the tables for another stem."""
        return _table(self._native.table(stem))

    def tables(self):
        """Every table of :meth:`table_names`, a dict stem → DataFrame."""
        return {stem: self.table(stem) for stem in self.table_names()}

    def modes(self):
        """The vibration modes of a modal analysis, as ``modes.csv`` has
        them: ``mode`` (from 1), ``frequency_hz``, the effective masses
        ``effective_mass_x``, ``_y``, ``_z`` (kg), the estimated relative
        error of the frequency ``frequency_error`` and of the mode shape
        in the energy norm ``mode_error``; a pandas DataFrame, KeyError
        without a modal analysis."""
        return _table(self._native.modes(False))

    def buckling(self):
        """The buckling modes, as ``buckling.csv`` has them: ``mode``,
        ``load_factor``, the critical load ``critical_load_*`` (N), cut by
        symmetry planes the full structure's ``full_critical_load_*``, then
        the estimated relative error of the factor ``factor_error`` and of
        the mode shape ``mode_error``; a pandas DataFrame, KeyError without
        a buckling analysis."""
        return _table(self._native.modes(True))

    def plot_table(self, stem: str, columns=None, ax=None):
        """The chart ``report.html`` draws of table `stem` (one of
        :meth:`table_names` but ``contact_*``) with matplotlib: histories
        against ``lambda`` (``time`` in a transient run), lines against ``s``, the energy against
        ``time_s``, modes against ``mode``; every measured column a line
        labelled by its CSV name, or only `columns`. Drawn into `ax`, or a
        new figure's; returns the Axes. Needs matplotlib (the ``plot``
        extra)."""
        from . import plots

        typed = self._native.table(stem)
        units = {name: unit for name, _, _, unit in typed}
        return plots.plot_table(stem, _table(typed), columns, ax, f"Results.plot_table({stem!r})", units)

    def plot_history(self, name: Optional[str] = None, columns=None, ax=None):
        """:meth:`plot_table` of ``history_<name>`` (reactions, contact
        forces, probe displacements against ``lambda``, or ``time`` in a
        transient run) or, without a name,
        of ``history`` (iterations, plastic points, negative pivots)."""
        return self.plot_table("history" if name is None else f"history_{name}", columns, ax)

    def plot_line(self, name: str, columns=None, ax=None):
        """:meth:`plot_table` of ``line_<name>``: the quantities along the
        line against ``s`` (m); ``columns=["s_yy"]`` for one."""
        return self.plot_table(f"line_{name}", columns, ax)

    def plot_energy(self, columns=None, ax=None):
        """:meth:`plot_table` of ``energy``: the energy balance of a
        transient run against ``time_s``."""
        self.energy()  # KeyError naming analysis.type without one
        return self.plot_table("energy", columns, ax)

    def plot_modes(self, columns=None, ax=None):
        """:meth:`plot_table` of ``modes`` (frequencies, effective masses)
        or ``buckling`` (load factors, critical loads) against ``mode``;
        KeyError without either analysis."""
        names = self.table_names()
        stem = next((n for n in ("modes", "buckling") if n in names), None)
        if stem is None:
            raise KeyError('modes.csv, buckling.csv: this run has no modal or buckling analysis (analysis.type = "modal" or "buckling")')
        return self.plot_table(stem, columns, ax)

    @property
    def kept(self) -> Dict[str, int]:
        """How many states beside the final one the run kept: ``frames`` (a
        transient run's, every ``analysis.output_interval``), ``steps``
        (the step ends of a history of several steps) and ``modes`` (the
        mode shapes of a modal or buckling analysis)."""
        frames, steps, modes = self._native.kept()
        return {"frames": frames, "steps": steps, "modes": modes}

    def frame(self, k: int) -> "Results":
        """Frame `k` (from 0) of a transient run as a :class:`Results`: its
        :attr:`points`, :meth:`field`, :meth:`cell_field` and
        :meth:`to_meshio` are those of the (k+1)-th ``frame_<n>.vtu``
        (``frame_0001.vtu`` for k = 0); KeyError past the frames kept."""
        return self._kept_state("frame", k)

    def step(self, k: int) -> "Results":
        """The end of load step `k` (from 0) as a :class:`Results`, its
        fields those of ``result_<k+1>_<name>.vtu``; KeyError for a step that
        kept none (a history of one step keeps none: the final state is its
        end)."""
        return self._kept_state("step", k)

    def mode(self, k: int) -> "Results":
        """Mode shape `k` (from 0) of a modal or buckling analysis as a
        :class:`Results`, its fields those of ``mode_<k+1>.vtu``: the shape
        as ``displacement`` (largest component 1) with the strains and
        stresses of the shape at that scale; KeyError past the modes."""
        return self._kept_state("mode", k)

    def _kept_state(self, kind: str, k: int) -> "Results":
        if k < 0:
            raise KeyError(f"{kind} {k}: numbered from 0")
        return Results(self._native.state(kind, k))

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

    def cell_field(self, name: str) -> np.ndarray:
        """Cell field `name` of ``result.vtu``, one value per linear
        hexahedron of :meth:`to_meshio`: ``body`` and ``element`` (their
        indices) and, in a model with ply damage, ``d_ft``, ``d_fc``,
        ``d_mt``, ``d_mc`` (each mode's largest damage over the element's
        Gauss points, as ``result.vtu`` has them)."""
        data = self._vtu_data()["cell_data"]
        if name not in data:
            raise KeyError(f"cell field {name!r}: expected one of {list(data)}")
        return data[name]

    @property
    def cell_field_names(self):
        """The cell fields of ``result.vtu`` (:meth:`cell_field`)."""
        return list(self._vtu_data()["cell_data"])

    def to_meshio(self):
        """The fields of ``result.vtu`` as a ``meshio.Mesh``: the linear
        hexahedra of ``output.vtu_cells = "linear"`` (meshio reads the
        Lagrange cells of ``result.vtu`` but knows no Lagrange shape), the
        point data and the cell data (``body``, ``element`` and the ply
        damage ``d_*`` of :meth:`cell_field`), each (n, components) like
        ``meshio.read`` gives them. Needs meshio (the
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

    def report_html(self) -> Optional[str]:
        """The text of the run's ``report.html`` (the self-contained page:
        the model, the convergence log, the tables, the charts, the
        warnings and the 3D view), as :meth:`write` writes it; None with
        ``output.report = false``. Written once into a temporary folder
        (with the run's other files) and kept."""
        if self._report is None:
            with tempfile.TemporaryDirectory(prefix="cufem-report-") as tmp:
                page = Path(tmp) / "results" / "report.html"
                self.write(page.parent)
                self._report = page.read_text(encoding="utf-8") if page.exists() else ""
        return self._report or None

    def report_iframe(self, height: int = 720) -> str:
        """``report.html`` inline: an ``<iframe>`` whose ``srcdoc`` is the
        page (HTML-escaped), `height` pixels high, its scripts allowed and
        sandboxed from the notebook; what Jupyter shows for a
        :class:`Results` (``IPython.display.HTML(results.report_iframe(900))``
        for another height). Without a report (``output.report = false``)
        the summary line of :meth:`__repr__`."""
        page = self.report_html()
        if page is None:
            return f"<pre>{html.escape(repr(self))} (no report: output.report = false)</pre>"
        return (
            f'<iframe srcdoc="{html.escape(page, quote=True)}" sandbox="allow-scripts" '
            f'style="width: 100%; height: {int(height)}px; border: 1px solid #ccc"></iframe>'
        )

    def _repr_html_(self) -> str:
        # Jupyter's rich display of a Results: the report inline
        return self.report_iframe()

    def __repr__(self) -> str:
        s = self.summary
        return f"<cufem.Results {s['title']!r}: {s['status']}, load factor {s['load_factor']:.4g}, {s['increments']} increments>"

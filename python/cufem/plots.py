"""Matplotlib charts of a run's tables: the charts ``report.html`` draws
(histories against the load factor, lines along their distance, the
energy balance against time, the modes by number), one Axes each. Needs
matplotlib (the ``plot`` extra); :class:`cufem.Results` calls these through
its ``plot_*`` methods."""

from __future__ import annotations

from typing import Dict, Optional, Sequence, Tuple

import numpy as np

from ._extras import require

# columns that count rather than measure: charted only in history.csv's chart
COUNTS = ("iterations", "plastic_points", "negative_pivots")


def chart_columns(stem: str, table) -> Tuple[str, list]:
    """The x column and the series of the chart of table `stem`, as
    ``report.html`` chooses them: ``energy`` against ``time_s``, ``modes``
    and ``buckling`` against ``mode``, ``line_*`` against ``s``,
    ``history*`` and ``error_history`` against ``time`` in a transient run
    and ``lambda`` otherwise; every other numeric column a series but
    ``increment``, ``lambda`` when against ``time`` (and the counts, but in
    ``history``). ValueError for a table without a chart (``contact_*``)."""
    if stem == "energy":
        x = "time_s"
    elif stem in ("modes", "buckling"):
        x = "mode"
    elif stem.startswith("line_"):
        x = "s"
    elif stem.startswith("history") or stem == "error_history":
        x = "time" if "time" in table.columns else "lambda"
    else:
        raise ValueError(
            f"table {stem!r}: no chart (charted are history*, line_*, energy, modes, buckling, error_history)"
        )
    series = [
        c
        for c in table.columns
        if c not in (x, "increment")
        and not (x == "time" and c == "lambda")
        and table[c].dtype.kind in "iuf"
        and (stem == "history" or c not in COUNTS)
    ]
    return x, series


def shown(stem: str, table, series: Sequence[str]) -> list:
    """Which series ``report.html`` draws at first: not a line's coordinates
    ``x, y, z``, and not a curve below a thousandth of the largest shown
    (another unit's, or round-off)."""
    coordinate = [stem.startswith("line_") and c in ("x", "y", "z") for c in series]
    size = [0.0 if k else float(np.nanmax(np.abs(table[c].to_numpy(dtype=float)), initial=0.0)) for c, k in zip(series, coordinate)]
    top = max(size, default=0.0)
    return [not k and v >= 1e-3 * top for k, v in zip(coordinate, size)]


def _title(stem: str) -> str:
    if stem == "energy":
        return "energy balance"
    if stem.startswith("line_"):
        return f"line {stem[len('line_'):]}"
    return stem


def plot_table(
    stem: str,
    table,
    columns: Optional[Sequence[str]] = None,
    ax=None,
    what: str = "a plot",
    units: Optional[Dict[str, str]] = None,
):
    """Draws the chart of table `stem` (a DataFrame of it) into `ax` (a new
    figure's Axes without one): the series of :func:`chart_columns`, or
    only `columns`, against its x column, each a line labelled by its
    column name; without `columns` the lines ``report.html`` hides at
    first (:func:`shown`) are drawn hidden (``line.set_visible(True)``
    shows one). The y axis carries the unit of the lines shown (`units`:
    column → SI unit, as the native tables give them), or says that they
    have several. Returns the Axes."""
    require("matplotlib", what)
    x, series = chart_columns(stem, table)
    if columns is not None:
        unknown = [c for c in columns if c not in series]
        if unknown:
            raise KeyError(f"{stem}: columns {unknown} are not charted; expected some of {series}")
        series = list(columns)
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    visible = shown(stem, table, series) if columns is None else [True] * len(series)
    for c, v in zip(series, visible):
        (line,) = ax.plot(table[x].to_numpy(), table[c].to_numpy(), marker="o" if len(table) <= 60 else None, label=c)
        line.set_visible(v)
    given = units or {}
    units = {given.get(c, "") for c, v in zip(series, visible) if v}
    if len(units) == 1:
        only = units.pop()
        ax.set_ylabel(f"[{only}]" if only else "")
    elif units:
        ax.set_ylabel("several units: see the legend")
    ax.set_xlabel(x)
    ax.set_title(_title(stem))
    if series:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax

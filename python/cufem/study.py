"""Parameter studies: many variants of one model, locally or on Dask.

>>> from cufem import study
>>> df = study.run("examples/block_indentation.toml",
...                {"indenters.0.displacement.2": [-0.5e-3, -1e-3]},
...                outputs=["probe.edge.peeq", "contact.punch.f_z"])

A variant is a dict of dotted key paths into the model dict
(``"indenters.0.displacement.2"``: list indices are numbers) and values.
``variants`` is a list of such dicts, or one dict of value lists: their
product grid (:func:`grid`; a single value that is not a list is one
value). Each variant is built with
:meth:`cufem.Model.from_dict` (the CLI's validation) and solved; the result
is a pandas DataFrame with a row per variant: the variant's values, an
``error`` column (None, or the message of the variant that failed: an
invalid model, a missing key, an output the run does not have) and the
requested outputs (NaN where it failed). The outputs' forms and quantities
are checked before anything is solved. A variant that does not converge is not an error: its ``status``
says so and its values are those of the last converged increment.

Outputs are read from the summary (summary.json):

* ``probe.<name>.<quantity>``: ``u_x`` … ``u_z``, ``s_xx`` … ``s_yz``,
  ``von_mises``, ``peeq``, the strains ``e_xx`` … ``e_yz`` and, in a
  laminate, the failure indices ``fi_*`` (those of ``Results.probe``);
* ``reaction.<name>.f_x|f_y|f_z``, ``contact.<name>.f_x|f_y|f_z`` or
  ``contact.<name>.max_penetration``;
* any scalar of the summary: ``status``, ``load_factor``, ``max_peeq``,
  ``increments``, ``newton_iterations``, ``plastic_points``, ``dof`` …
"""

from __future__ import annotations

import itertools
import math
import os
import warnings
from typing import Any, Dict, Iterable, List, Optional, Sequence, Union

from . import _native
from ._extras import require
from .model import Model, set_path

_QUANTITIES = {"u_x": ("u", 0), "u_y": ("u", 1), "u_z": ("u", 2)}
_QUANTITIES.update({f"s_{c}": ("stress", k) for k, c in enumerate(["xx", "yy", "zz", "xy", "xz", "yz"])})
_QUANTITIES.update({"von_mises": ("von_mises", None), "peeq": ("peeq", None)})
_FORCE = {"f_x": 0, "f_y": 1, "f_z": 2}
# a probe's strains (and a laminate's failure indices, fi_*): Results.probe's, not summary.json's
_STRAINS = tuple(f"e_{c}" for c in ["xx", "yy", "zz", "xy", "xz", "yz"])

DEFAULT_OUTPUTS = ("status", "load_factor", "max_peeq")


def grid(variants: Dict[str, Sequence[Any]]) -> List[Dict[str, Any]]:
    """The product grid of value lists: ``{"a": [1, 2], "b": [3, 4]}`` →
    four variants, the last key varying fastest. A value that is not a list
    or other iterable (a number, a string, a table) is one value: ``{"a": "L4"}`` is
    one variant, not ``"L"`` and ``"4"``; a list-valued key (a vector) is
    given as a list of lists."""
    keys = list(variants)

    def values(k):
        v = variants[k]
        if isinstance(v, (str, bytes, dict)) or getattr(v, "ndim", None) == 0:
            return [v]  # one value (a numpy scalar included)
        if hasattr(v, "tolist"):  # a numpy array of values
            return v.tolist()
        try:
            return list(v)  # a list, tuple, range, generator, set …
        except TypeError:
            return [v]  # a number

    return [dict(zip(keys, combination)) for combination in itertools.product(*(values(k) for k in keys))]


def check_output(spec: str) -> None:
    """Refuses an output `spec` whose form or quantity is not one of the
    module docs', before anything is solved (a typo there cost a whole
    study, every row then failed; a new-user review). Names of probes,
    constraints and contacts are checked against each run's summary."""
    parts = spec.split(".") if isinstance(spec, str) else []
    if parts and parts[0] in ("probe", "reaction", "contact") and len(parts) == 3:
        kind, _, what = parts
        allowed = sorted(_QUANTITIES) + list(_STRAINS) + ["fi_*"] if kind == "probe" else list(_FORCE) + (["max_penetration"] if kind == "contact" else [])
        if what not in allowed and not (kind == "probe" and what.startswith("fi_")):
            raise KeyError(f"output {spec!r}: expected a {kind} quantity of {allowed}")
        return
    if len(parts) == 1 and parts[0]:
        return  # a scalar of the summary: known only from a run's summary
    raise KeyError(
        f"output {spec!r}: expected probe.<name>.<quantity>, reaction.<name>.f_x|f_y|f_z, "
        "contact.<name>.f_x|f_y|f_z|max_penetration or a scalar of the summary (status, load_factor, max_peeq, …)"
    )


def output_value(summary: dict, spec: str, probe=None) -> Any:
    """The value of output `spec` (module docs) in a summary dict; a probe's
    strain or failure index from `probe` (``Results.probe``)."""
    parts = spec.split(".")
    if parts[0] in ("probe", "reaction", "contact") and len(parts) == 3:
        kind, name, what = parts
        table = {"probe": "probes", "reaction": "reactions", "contact": "contact"}[kind]
        entry = next((e for e in summary[table] if e["name"] == name), None)
        if entry is None:
            names = [e["name"] for e in summary[table]]
            raise KeyError(f"output {spec!r}: no {kind} {name!r} (the model has {names})")
        if kind == "probe":
            if what not in _QUANTITIES and probe is not None:
                values = probe(name)
                if what not in values:
                    raise KeyError(f"output {spec!r}: expected a quantity of {sorted(values)}")
                return values[what]
            if what not in _QUANTITIES:
                raise KeyError(f"output {spec!r}: expected a quantity of {sorted(_QUANTITIES)}")
            key, k = _QUANTITIES[what]
            return entry[key] if k is None else entry[key][k]
        if what in _FORCE:
            return entry["force"][_FORCE[what]]
        if what == "max_penetration" and kind == "contact":
            return entry["max_penetration"]
        raise KeyError(f"output {spec!r}: expected f_x, f_y, f_z" + (" or max_penetration" if kind == "contact" else ""))
    if len(parts) == 1 and parts[0] in summary and not isinstance(summary[parts[0]], (list, dict)):
        return summary[parts[0]]
    raise KeyError(
        f"output {spec!r}: expected probe.<name>.<quantity>, reaction.<name>.f_x|f_y|f_z, "
        "contact.<name>.f_x|f_y|f_z|max_penetration or a scalar of the summary (status, load_factor, max_peeq, …)"
    )


def run_variant(model: dict, base: str, variant: Dict[str, Any], outputs: Sequence[str], threads: Optional[int]) -> dict:
    """Builds and solves one variant; never raises: a failure is the row's
    ``error``. (The task that the process pool or Dask runs.)"""
    row: Dict[str, Any] = dict(variant)
    row["error"] = None
    for spec in outputs:
        row[spec] = math.nan
    try:
        d = model
        for path, value in variant.items():
            d = set_path(d, path, value)
        with warnings.catch_warnings():
            # a stop is the row's status
            warnings.simplefilter("ignore", UserWarning)
            results = Model.from_dict(d, base=base).run(threads=threads, quiet=True)
    except Exception as e:  # a failed variant is a row, not a crashed study
        row["error"] = _message(e)
        return row
    # each output on its own: a name one run lacks blanks that output only
    failed = []
    for spec in outputs:
        try:
            row[spec] = output_value(results.summary, spec, results.probe)
        except Exception as e:
            failed.append(_message(e))
    if failed:
        row["error"] = "; ".join(failed)
    return row


def _message(e: Exception) -> str:
    """A model error's own message (the CLI's), a bad key path's text, else `Type: message`."""
    if isinstance(e, _native.ModelError):
        return str(e)
    if isinstance(e, KeyError) and e.args:
        return str(e.args[0])
    return f"{type(e).__name__}: {e}"


def _model_dict(model) -> tuple:
    if isinstance(model, Model):
        return model.to_dict(), model.base
    if isinstance(model, dict):
        return model, os.getcwd()
    m = Model.from_file(model)
    return m.to_dict(), m.base


def run(
    model: Union[Model, dict, str, os.PathLike],
    variants: Union[Iterable[Dict[str, Any]], Dict[str, Sequence[Any]]],
    outputs: Sequence[str] = DEFAULT_OUTPUTS,
    *,
    client=None,
    max_workers: Optional[int] = None,
    threads: Optional[int] = 1,
    mp_context: Optional[str] = None,
):
    """Runs every variant of `model` and returns a pandas DataFrame, one row
    per variant in the given order (module docs).

    model: a :class:`cufem.Model`, a model dict or a model file path.
    variants: a list of ``{dotted path: value}`` dicts, or one dict of value
    lists (their product grid).
    client: a ``dask.distributed.Client``: the variants run as Dask tasks on
    its cluster; otherwise in a local process pool of `max_workers`
    processes (default: the CPU count) started with `mp_context` (default
    ``"forkserver"`` where available: scripts need the usual
    ``if __name__ == "__main__":`` guard).
    threads: solver threads per variant (default 1: the parallelism is
    across variants).
    """
    pd = require("pandas", "cufem.study.run")

    base_dict, base = _model_dict(model)
    variants = grid(variants) if isinstance(variants, dict) else [dict(v) for v in variants]
    outputs = [outputs] if isinstance(outputs, str) else list(outputs)
    for spec in outputs:
        check_output(spec)
    tasks = [(base_dict, base, v, outputs, threads) for v in variants]
    if client is not None:
        futures = [client.submit(run_variant, *t, pure=False) for t in tasks]
        rows = client.gather(futures)
    elif max_workers == 0 or len(tasks) <= 1:
        rows = [run_variant(*t) for t in tasks]
    else:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        if mp_context is None:
            mp_context = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
        ctx = multiprocessing.get_context(mp_context)
        workers = min(max_workers or os.cpu_count() or 1, len(tasks))
        with ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
            rows = list(pool.map(run_variant, *zip(*tasks)))
    columns = list(dict.fromkeys(k for v in variants for k in v)) + ["error"] + outputs
    return pd.DataFrame(rows, columns=columns)


def report(df, path: Union[str, os.PathLike], title: str = "cufem parameter study") -> str:
    """Writes the study's ``report.html`` to `path` and returns its path: one
    self-contained page (nothing loaded at view time) with the table of the
    variants (``df`` as :func:`run` returns it, failed variants with their
    ``error``) and, for every numeric output, a vector chart (inline SVG) of
    it against each varied parameter that takes two or more numeric values
    (the other parameters' combinations as separate lines). Needs matplotlib
    (the ``plot`` extra)."""
    import html
    import io

    plt = require("matplotlib.pyplot", "cufem.study.report")
    pd = require("pandas", "cufem.study.report")

    def numeric(column) -> bool:
        return pd.api.types.is_numeric_dtype(df[column]) and not pd.api.types.is_bool_dtype(df[column])

    # a vector-valued parameter (``loads.0.total_force``) groups by its text: lists are not hashable
    df = df.copy()
    for c in df.columns:
        if df[c].map(lambda v: isinstance(v, (list, dict))).any():
            df[c] = df[c].map(repr)
    varied = list(df.columns[: list(df.columns).index("error")])
    outputs = [c for c in df.columns[list(df.columns).index("error") + 1 :] if numeric(c)]
    parameters = [p for p in varied if numeric(p) and df[p].nunique() >= 2]
    charts = []
    for out in outputs:
        for p in parameters:
            others = [q for q in varied if q != p]
            fig, ax = plt.subplots(figsize=(6.0, 3.6))
            groups = df.groupby(others, dropna=False, sort=False) if others else [((), df)]
            for key, g in groups:
                g = g.sort_values(p)
                label = ", ".join(f"{q} = {v}" for q, v in zip(others, key if isinstance(key, tuple) else (key,)))
                ax.plot(g[p], g[out], marker="o", label=label or None)
            ax.set_xlabel(p)
            ax.set_ylabel(out)
            if others:
                ax.legend(fontsize="small")
            ax.grid(True, alpha=0.3)
            svg = io.StringIO()
            fig.savefig(svg, format="svg", bbox_inches="tight")
            plt.close(fig)
            body = svg.getvalue()
            charts.append(f'<figure data-output="{html.escape(out)}" data-parameter="{html.escape(p)}">'
                          f"{body[body.index('<svg'):]}</figure>")
    page = (
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
        f"<title>{html.escape(title)}</title>"
        "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
        "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}figure{display:inline-block}</style>"
        f"</head><body><h1>{html.escape(title)}</h1>"
        f"<p>{len(df)} variants, {int(df['error'].notna().sum())} failed.</p>"
        f"{df.to_html(index=False, na_rep='', escape=True)}"
        + "".join(charts)
        + "</body></html>\n"
    )
    path = os.fspath(path)
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)
    return path

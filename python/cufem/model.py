"""`cufem.Model`: a validated model, from a file, TOML text or a dict."""

from __future__ import annotations

import copy
import os
import re
import warnings
from typing import Any, Optional

from . import _native
from .results import Results


class Model:
    """A validated cufem model (docs/model-format.md).

    Build it with :meth:`from_file`, :meth:`from_toml` or :meth:`from_dict`;
    all three go through the CLI's parser and validation, so an invalid
    model raises :class:`cufem.ModelError` with the CLI's message (key,
    value, what is allowed).
    """

    def __init__(self, native, text: str, base: str, path: Optional[str] = None):
        self._native = native
        self._text = text
        self._base = base
        #: the model file, when read from one
        self.path = path

    @classmethod
    def from_file(cls, path, max_memory: Optional[int] = None) -> "Model":
        """Reads a model file; relative paths in it (gmsh sections) start at its folder."""
        path = os.fspath(path)
        native = _native.parse_file(path, max_memory)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        base = os.path.dirname(os.path.abspath(path))
        return cls(native, text, base, path)

    @classmethod
    def from_toml(cls, text: str, base=None, max_memory: Optional[int] = None) -> "Model":
        """Parses model-file text; relative paths start at `base` (default: the current folder)."""
        base = os.path.abspath(os.fspath(base) if base is not None else os.getcwd())
        return cls(_native.parse_toml(text, base, max_memory), text, base)

    @classmethod
    def from_dict(cls, d: dict, base=None, max_memory: Optional[int] = None) -> "Model":
        """A model from nested dicts and lists with the model file's keys
        (``{"materials": [{"name": "steel", ...}], "bodies": [...]}``):
        written as TOML text and parsed like a file. numpy numbers and arrays
        are accepted; ``None`` is refused (TOML has no null). An error of
        the text is named by the dict's dotted key path
        (``materials.0.youngs_modulus: unknown field …``), not by a line of
        the generated text."""
        text = _native.object_to_toml(d)
        try:
            return cls.from_toml(text, base, max_memory)
        except _native.ModelError as e:
            message = _dict_error(str(e), text, d)
            if message is None:
                raise
        raise _native.ModelError(message)

    def to_dict(self) -> dict:
        """The model file's keys as nested dicts and lists (a deep copy:
        change it and pass it to :meth:`from_dict`)."""
        return _native.toml_to_object(self._text)

    def to_toml(self) -> str:
        """The model-file text this model was read from."""
        return self._text

    @property
    def base(self) -> str:
        """The folder relative paths in the model start at."""
        return self._base

    def check(self) -> dict:
        """Sizes: ``bodies`` (per body: elements, nodes, dof, section and
        axis elements), total ``elements``, ``nodes``, ``dof``, the
        ``equations`` after the symbolic factorization, and the warnings."""
        return self._native.check()

    def run(self, out=None, threads: Optional[int] = None, quiet: bool = False, force: bool = False) -> Results:
        """Solves the model and returns its :class:`Results`, printing what
        ``cufem run`` prints, from the same library functions: the title and
        the discretization, a line when the analysis is set up and one per
        increment (λ, iterations, residuals, plastic points, penetration)
        and per cutback, the final table (DOF, time, increments, Newton
        iterations; probes, references, reactions and contact forces) and
        the files written. Header, table and files go to ``sys.stdout``,
        progress and warnings to ``sys.stderr`` (as the CLI's streams).

        quiet: print nothing but the warnings (also in
        ``summary["warnings"]``). ``cufem run --quiet`` still prints the
        final table; ``quiet=True`` does not, so that a loop of runs stays
        silent, but a run that ends otherwise than converged issues a
        Python ``UserWarning`` saying how and where its files went.

        A model with an ``[adapt]`` table runs its adaptive cycles as
        ``cufem run`` does (a line per cycle on stderr unless `quiet`); the
        results are the last finished cycle's, ``summary["adapt"]`` lists
        the cycles.

        The GIL is released during the solve. Ctrl-C (SIGINT) stops the
        analysis at the next safe point: the results of the last converged
        increment are returned (``summary["status"] == "interrupted"``) and,
        with `out`, written; a second Ctrl-C raises ``KeyboardInterrupt``.

        out: a folder to write the CLI's files into (``cufem run --out``:
        locked, replaced atomically; `force` as ``--force``). A run that
        stops early never replaces a converged result set there: it writes
        to ``<out>.partial`` instead (``Results.out`` says where).
        threads: worker threads (default: the model's ``solver.threads``,
        else all cores).
        """
        out = os.fspath(out) if out is not None else None
        if isinstance(threads, int) and threads < 1:
            # as the native check words it for 0 (a negative count raised a bare OverflowError)
            raise ValueError(f"threads = {threads}: expected an integer from 1 to 1024")
        # the text and folder let a model with an [adapt] table run its cycles
        # (it solved its own mesh alone: the same file gave other results than
        # from the CLI; a new-user review)
        native = self._native.run(out, force, threads, quiet, self._text, self._base)
        # a run that stopped early beside a converged set writes to out.partial
        results = Results(native, native.written_to or out)
        if quiet and results.status != "converged":
            # quiet prints nothing: the stop would pass unseen
            where = f"; its files are in {results.out}" if out is not None and results.out != out else ""
            warnings.warn(f"the run ended {results.status} at load factor {results.summary['load_factor']:.4g}{where}",
                          UserWarning, stacklevel=2)
        return results

    def __repr__(self) -> str:
        c = self._native.check()
        return f"<cufem.Model {self.path or c['title']!r}: {len(c['bodies'])} bodies, {c['dof']} DOF>"


def _dict_error(message: str, text: str, d: Any) -> Optional[str]:
    """A parse error of the TOML text written from a dict ("TOML parse error
    at line 61, column 1" and the line with a caret under it), as the dict's
    dotted key path and the reason; None for another error (a validation
    error already names its key)."""
    m = re.search(r"TOML parse error at line (\d+), column \d+", message)
    if m is None:
        return None
    lines = text.splitlines()
    at = int(m.group(1))
    arrays: dict = {}

    def resolve(parts):
        # a header's path with the index of every array of tables it passes
        path = []
        for p in parts:
            path.append(p)
            key = ".".join(path)
            if key in arrays:
                path.append(str(arrays[key]))
        return path

    table: list = []
    inside = False  # within a multi-line string (a description): its lines are text
    # through the error's own line: an error in a table's keys points at its header
    for line in lines[:at]:
        stripped = line.strip()
        quotes = line.count('"""') + line.count("'''")
        if inside or quotes % 2 == 1:
            inside = inside != (quotes % 2 == 1)
            continue
        if stripped.startswith("[["):
            parts = [p.strip().strip('"') for p in stripped[2:-2].split(".")]
            parent = resolve(parts[:-1])
            key = ".".join(parent + [parts[-1]])
            arrays[key] = arrays.get(key, -1) + 1
            table = parent + [parts[-1], str(arrays[key])]
        elif stripped.startswith("["):
            table = resolve([p.strip().strip('"') for p in stripped[1:-1].split(".")])
    line = lines[at - 1] if 0 < at <= len(lines) else ""
    key = line.split("=", 1)[0].strip().strip('"') if "=" in line and not line.lstrip().startswith("[") else ""
    body = message.splitlines()
    caret = max((i for i, l in enumerate(body) if l.lstrip(" |").startswith("^")), default=len(body) - 1)
    reason = " ".join(l.strip() for l in body[caret + 1 :]) or body[-1]
    # the reader names the key itself (`bodies[0].axis.elements: …`): as the dict's dotted path
    named = re.match(r"([A-Za-z_]\w*(?:\[\d+\]|\.[A-Za-z_]\w*)*): (.*)$", reason)
    if named:
        dotted = re.sub(r"\[(\d+)\]", r".\1", named.group(1))
        return f"{dotted}: {named.group(2)}"
    unknown = re.match(r"unknown field `([^`]+)`", reason)
    if not key and unknown:
        # the parser points at the header of the table it was reading (a
        # section's, for a key of a segment inside it): the key's one place
        # under that table in the dict, if it has one
        places = list(_find_key(_at(d, table), unknown.group(1), table))
        table, key = (places[0], "") if len(places) == 1 else (table, unknown.group(1))
    path = ".".join(table + ([key] if key else [])) or "(the model)"
    return f"{path}: {reason}"


def _at(d: Any, path: list) -> Any:
    for k in path:
        try:
            d = d[int(k)] if isinstance(d, list) else d[k]
        except (KeyError, IndexError, ValueError, TypeError):
            return None
    return d


def _find_key(node: Any, key: str, path: list):
    """Every path under `node` (at `path`) whose last key is `key`."""
    if isinstance(node, dict):
        for k, v in node.items():
            if k == key:
                yield path + [k]
            yield from _find_key(v, key, path + [k])
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _find_key(v, key, path + [str(i)])


def set_path(d: dict, path: str, value: Any) -> dict:
    """A copy of model dict `d` with the dotted key path set to `value`
    (``"indenters.0.displacement.2"``: list indices are numbers). The last
    key may be new; every key before it must exist."""
    d = copy.deepcopy(d)
    keys = path.split(".")
    node: Any = d
    for i, k in enumerate(keys):
        last = i == len(keys) - 1
        where = ".".join(keys[: i + 1])
        if isinstance(node, list):
            try:
                idx = int(k)
            except ValueError:
                raise KeyError(f"{path}: {where} is a list index, expected an integer") from None
            if not -len(node) <= idx < len(node):
                raise KeyError(f"{path}: {where} is past the end of a list of {len(node)}")
            if last:
                node[idx] = value
            else:
                node = node[idx]
        elif isinstance(node, dict):
            if last:
                node[k] = value
            elif k not in node:
                raise KeyError(f"{path}: the model has no key {where}")
            else:
                node = node[k]
        else:
            raise KeyError(f"{path}: {'.'.join(keys[:i])} is a value, not a table or list")
    return d

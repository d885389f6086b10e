"""Reading another simulator's run: CSV or JSON, columns named as in :mod:`.geometry`.

* CSV: one header line naming the columns, then one row per output time; lines starting
  with ``#`` are comments.  Values are numbers (Python's float syntax).
* JSON: one object whose keys are the column names and whose values are equal-length lists
  of numbers or decimal strings.

A mapping of column name to sequence (in Python) is read the same way as the JSON object.
"""
from __future__ import annotations

import csv
import json
import math
from decimal import Decimal
from pathlib import Path

import numpy as np

from ..contact_geometry import FORMS, detect


#: The first line of the suite's own run files (verify.series.columns.FORMAT, written out: scoring stays light).
_SUITE_FORMAT = "rolling-verify run 1"


_FORM_COLUMNS = {c for form in FORMS.values() for c in form}


class InvalidRun(ValueError):
    """A run that cannot be scored (bad file, wrong columns, a start not the case's, a violated constraint)."""


def read_run(run) -> tuple:
    """(form name, dict of float arrays) of a CSV/JSON file or a mapping of columns."""
    if isinstance(run, (str, Path)):
        path = Path(run)
        try:
            text = path.read_text()
        except (OSError, UnicodeDecodeError) as err:  # missing, a folder, unreadable, not text
            raise InvalidRun(f"cannot read the run {path}: {err}") from None
        columns = _json(text, path) if path.suffix.lower() == ".json" else _csv(text, path)
        if _SUITE_FORMAT in text[:200]:  # the suite's own run file: its state columns (invariants etc. are derived)
            columns = {n: v for n, v in columns.items() if n in _FORM_COLUMNS}
    else:
        columns = dict(run)
    try:
        form = detect(columns)
    except ValueError as err:
        raise InvalidRun(str(err)) from None
    out, length = {}, None
    for name, values in columns.items():
        arr = np.empty(len(np.ravel(values)))
        for row, v in enumerate(np.ravel(values)):
            try:
                arr[row] = float(v)
            except (TypeError, ValueError):
                raise InvalidRun(f"column {name!r} at row {row} holds {str(v)[:40]!r}, not a number; allowed: "
                                 "decimal numbers") from None
        if not np.all(np.isfinite(arr)):
            bad = int(np.flatnonzero(~np.isfinite(arr))[0])
            raise InvalidRun(f"column {name!r} is not finite at row {bad} ({arr[bad]})")
        if length is not None and len(arr) != length:
            raise InvalidRun(f"column {name!r} has {len(arr)} values, the others {length}")
        length = len(arr)
        out[name] = arr
    if length < 2:
        raise InvalidRun(f"the run has {length} output time(s); at least 2 are needed")
    t = out["t"]
    if np.any(np.diff(t) <= 0):
        j = int(np.flatnonzero(np.diff(t) <= 0)[0])
        raise InvalidRun(f"the times are not strictly increasing: t[{j}] = {t[j]!r}, t[{j + 1}] = {t[j + 1]!r}")
    return form, out


def _csv(text: str, path: Path) -> dict:
    rows = [r for r in csv.reader(line for line in text.splitlines() if line.strip() and not line.lstrip().startswith("#"))]
    if not rows:
        raise InvalidRun(f"{path} has no header line")
    header = [_without_unit(h) for h in rows[0]]
    if len(set(header)) != len(header):
        raise InvalidRun(f"{path}: a column is named twice in {header}")
    cols = {h: [] for h in header}
    for k, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise InvalidRun(f"{path}: data row {k - 1} has {len(row)} fields, the header {len(header)}")
        for h, v in zip(header, row):
            cols[h].append(v.strip())
    return cols


def _without_unit(heading: str) -> str:
    """``theta [rad]`` -> ``theta``: the headings of the suite's own run files (verify.series) carry units."""
    name, bracket, unit = heading.strip().partition(" [")
    return name.strip() if bracket and unit.endswith("]") else heading.strip()


def _json(text: str, path: Path) -> dict:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise InvalidRun(f"{path} is not valid JSON ({err})") from None
    if isinstance(data, dict) and isinstance(data.get("columns"), dict) and "units" in data:
        data = data["columns"]  # a run file of the suite (python -m verify trajectory --output run.json)
    if not isinstance(data, dict) or not all(isinstance(v, list) for v in data.values()):
        raise InvalidRun(f"{path}: expected one object of columns (name: list of numbers)")
    return data


def exact_decimal(t: float) -> str:
    """The exact decimal value of a double (so that a quad run is evaluated at that very time)."""
    if not math.isfinite(t):
        raise ValueError(t)
    return format(Decimal(t), "f")

"""A run's columns in a file people keep: CSV, JSON or NumPy ``.npz``, chosen by the extension.

CSV
    Comment lines ``# key: <JSON value>`` (the format, model, parameters, precision, start,
    outcome, the suite's version), then one header line ``t [s],theta [rad],...,energy [m R^2/s^2]``
    and one row per output time.  Numbers carry every digit: the shortest decimal that reads back to
    the same double (Python's ``repr``), and in long, quad and MPFR the decimal that identifies the
    number at that precision (:meth:`verify.precision.Precision.to_text`).  NaN (mu_req where N <= 0,
    the slip direction while rolling) is written ``nan``.
JSON
    ``{"format", "meta": {...}, "units": {name: unit}, "columns": {name: [values]}}``; numbers in
    double, decimal strings carrying every digit in the other precisions, NaN as null.
NPZ
    One array per column (float64 in double, ``numpy.longdouble`` in long, decimal strings in quad
    and MPFR, strings for labels), ``__units__`` and ``__meta__`` as JSON text.

Every file is written atomically (:func:`verify.provenance.write_atomic`): a reader sees the old
file or the whole new one, never half of it.  :func:`read_run` reads any of the three back into a
:class:`~.columns.RunColumns` (float64 in double; decimal strings otherwise).
"""
from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np

from .columns import FORMAT, RunColumns

EXTENSIONS = (".csv", ".json", ".npz")


class RunFileError(ValueError):
    """A file name or a file's content that cannot be a run (bad input: one line naming it)."""


def output_path(text: str, option: str = "--output", extensions: tuple = EXTENSIONS) -> Path:
    """The checked output file: a known extension, an existing folder, not itself a folder.

    Checked before the run so that nothing is computed for a file that cannot be written; the
    pictures (:func:`verify.series.plot.picture_path`) and animations are checked by the same rule.
    """
    path = Path(str(text))
    allowed = f"allowed a file name ending in {', '.join(extensions)}"
    if not str(text).strip():
        raise RunFileError(f"{option} '': {allowed}")
    if path.is_dir():
        raise RunFileError(f"{option} {str(text)!r} is a folder; {allowed}")
    if path.suffix.lower() not in extensions:
        raise RunFileError(f"{option} {str(text)!r}: unknown extension {path.suffix or '(none)'!r}; "
                           f"allowed {', '.join(extensions)}")
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise RunFileError(f"{option} {str(text)!r}: the folder {str(folder)!r} does not exist; create it first")
    return path


def write_run(columns: RunColumns, path) -> Path:
    """Write ``columns`` to ``path`` in the format its extension names; returns the path."""
    from ..provenance import write_atomic  # lazy: 30 ms, only to write a run

    path = Path(path)
    kind = path.suffix.lower()
    if kind == ".csv":
        data = to_csv_text(columns).encode()
    elif kind == ".json":
        data = to_json_text(columns).encode()
    elif kind == ".npz":
        data = _npz_bytes(columns)
    else:
        raise RunFileError(f"{str(path)!r}: unknown extension {kind or '(none)'!r}; allowed {', '.join(EXTENSIONS)}")
    write_atomic(path, data)
    return path


def _text(value) -> str:
    """Every digit of one value (its type says its precision)."""
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (float, np.float64)):
        return repr(float(value))
    if isinstance(value, np.longdouble):
        return "nan" if np.isnan(value) else np.format_float_scientific(value, unique=True)
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    text = str(value)  # heyoka's real128 and real print every digit
    return "nan" if text.lower() in ("nan", "-nan") else text


def _json_value(value):
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (float, np.float64)):
        if math.isinf(value):  # JSON has no infinity: the string, which the reader turns back into one
            return "inf" if value > 0 else "-inf"
        return float(value) if math.isfinite(value) else None
    text = _text(value)
    return None if text == "nan" else text


def to_csv_text(columns: RunColumns) -> str:
    out = io.StringIO()
    out.write(f"# format: {json.dumps(FORMAT)}\n")
    for key, value in columns.meta.items():
        if key != "format":
            out.write(f"# {key}: {json.dumps(value, allow_nan=False)}\n")
    writer = csv.writer(out, lineterminator="\n")
    names = columns.names
    writer.writerow([columns.header(n) for n in names])
    for row in zip(*(columns.values[n] for n in names)):
        writer.writerow([_text(v) for v in row])
    return out.getvalue()


def to_json_text(columns: RunColumns) -> str:
    doc = {"format": FORMAT, "meta": {k: v for k, v in columns.meta.items() if k != "format"},
           "units": dict(columns.units),
           "columns": {n: [_json_value(v) for v in columns.values[n]] for n in columns.names}}
    return json.dumps(doc, indent=1, allow_nan=False) + "\n"


def _npz_bytes(columns: RunColumns) -> bytes:
    arrays = {}
    for name in columns.names:
        v = np.asarray(columns.values[name])
        if v.dtype not in (np.float64, np.longdouble) and v.dtype.kind != "U":  # quad, MPFR: every digit as text
            v = np.array([_text(x) for x in columns.values[name]], dtype=str)
        arrays[name] = v
    arrays["__units__"] = np.array(json.dumps(columns.units))
    arrays["__meta__"] = np.array(json.dumps(columns.meta, allow_nan=False))
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)
    return buffer.getvalue()


# --- reading ------------------------------------------------------------------------------------

def read_run(path) -> RunColumns:
    """A run file written by :func:`write_run` (CSV, JSON or NPZ) as :class:`RunColumns`.

    Double runs come back as float64 arrays with the same bits; other precisions as arrays of the
    decimal strings written (the same strings), labels as strings.

    Raises
    ------
    RunFileError
        If the file is missing, has an unknown extension, or is not a run file of this format.
    """
    path = Path(path)
    if not path.is_file():
        raise RunFileError(f"no run file {str(path)!r}; allowed a .csv, .json or .npz written by "
                           "'python -m verify trajectory ... --output FILE'")
    kind = path.suffix.lower()
    try:
        if kind == ".csv":
            return _read_csv(path)
        if kind == ".json":
            return _read_json(path)
        if kind == ".npz":
            return _read_npz(path)
    except (OSError, ValueError, KeyError, TypeError, json.JSONDecodeError, UnicodeDecodeError) as err:
        if isinstance(err, RunFileError):
            raise
        raise RunFileError(f"{str(path)!r} is not a run file of this suite ({type(err).__name__}: "
                           f"{' '.join(str(err).split())[:120]})") from None
    raise RunFileError(f"{str(path)!r}: unknown extension {kind or '(none)'!r}; allowed {', '.join(EXTENSIONS)}")


def _typed(values: list, double: bool, label: bool) -> np.ndarray:
    if label:
        return np.array(values, dtype=str)
    if double:
        return np.array([math.nan if v is None else float(v) for v in values], dtype=float)
    return np.array(["nan" if v is None else str(v) for v in values], dtype=str)


def _check_format(found) -> None:
    if found != FORMAT:
        raise RunFileError(f"format {found!r}; this suite reads {FORMAT!r}")


def _read_csv(path: Path) -> RunColumns:
    meta, lines = {}, path.read_text(encoding="utf-8").splitlines()
    i = 0
    while i < len(lines) and lines[i].startswith("# "):
        key, sep, value = lines[i][2:].partition(": ")
        if not sep:
            raise RunFileError(f"{str(path)!r} line {i + 1}: a comment line is '# key: value'")
        meta[key] = json.loads(value)
        i += 1
    _check_format(meta.pop("format", None))
    rows = list(csv.reader(lines[i:]))
    if not rows:
        raise RunFileError(f"{str(path)!r} has no header line")
    names, units = [], {}
    for heading in rows[0]:
        name, _, unit = heading.partition(" [")
        if not unit.endswith("]"):
            raise RunFileError(f"{str(path)!r}: the heading {heading!r} is not 'name [unit]'")
        names.append(name)
        units[name] = unit[:-1]
    body = rows[1:]
    if any(len(r) != len(names) for r in body):
        raise RunFileError(f"{str(path)!r}: a row has not {len(names)} values")
    double = meta.get("precision") == "double"
    values = {n: _typed([r[j] for r in body], double, units[n] == "-") for j, n in enumerate(names)}
    return RunColumns(values, units, {"format": FORMAT, **meta})


def _read_json(path: Path) -> RunColumns:
    doc = json.loads(path.read_text(encoding="utf-8"))
    _check_format(doc.get("format"))
    meta, units = doc["meta"], doc["units"]
    double = meta.get("precision") == "double"
    values = {n: _typed(v, double, units[n] == "-") for n, v in doc["columns"].items()}
    return RunColumns(values, units, {"format": FORMAT, **meta})


def _read_npz(path: Path) -> RunColumns:
    with np.load(path, allow_pickle=False) as data:
        meta = json.loads(str(data["__meta__"]))
        units = json.loads(str(data["__units__"]))
        _check_format(meta.get("format"))
        values = {n: data[n] for n in units}
    return RunColumns(values, units, meta)

"""Every reference case in plain files, in the suite's Euler form and in a rotation-matrix form.

``python -m verify reference --export DIR --format csv|json`` writes, per case,

* ``<case>.euler.csv``: ``t, theta, phi, psi, thetadot, phidot, psidot, x, y`` (form (a));
* ``<case>.matrix.csv``: ``t, R11..R33, qw, qx, qy, qz, x, y, z, vx, vy, vz, wx, wy, wz``
  (form (b), :mod:`verify.frames`; bodies on the plane only);

or one ``<case>.json`` holding both (columns as lists of decimal strings) with the case's
initial state, parameters and conventions; and ``README.md`` spelling out every case's start,
parameters and the conventions.  Form (a) is the stored decimals (agreeing digits) as they are; form
(b) is computed from them at 50 digits and written with 30 significant digits (every stored
value has 31 agreeing digits or more at t_end, fewer only where it passes near 0, where
its absolute error bound, ``abs_error`` in the case file, is still below 1e-30).  Everything
is computed before anything is written; each file is replaced atomically.
"""
from __future__ import annotations

import json
from pathlib import Path

import mpmath

from models.catalogue import entry
from models.symbols import STATE_NAMES

from ..provenance import writable_folder, write_atomic
from ..series.columns import RunColumns, state_units
from ..series.files import to_csv_text
from ..frames import CONTACT, MOTION, MATRIX_ENTRIES, QUATERNION, euler_to_b
from .store import CONVENTIONS, DIRECTORY, load_set

EXPORT_FORMATS = ("csv", "json")
DIGITS_B = 30
B_COLUMNS = ("t",) + MATRIX_ENTRIES + QUATERNION + MOTION


def form_b_columns(record: dict) -> dict:
    """Form (b) of a case's stored grid as decimal strings (``DIGITS_B`` significant digits), or {}."""
    model = record["model"]["name"]
    if model not in CONTACT:
        return {}
    with mpmath.workdps(50):
        params = {k: mpmath.mpf(v["exact"].split("/")[0]) / (mpmath.mpf(v["exact"].split("/")[1])
                                                              if "/" in v["exact"] else 1)
                  for k, v in record["model"]["parameters"].items()}
        cols = {c: [] for c in B_COLUMNS}
        cols["t"] = list(record["grid"])
        for j in range(len(record["grid"])):
            state = {n: mpmath.mpf(record["state"][n]["value"][j]) for n in STATE_NAMES}
            b = euler_to_b(model, state, params, module="mpmath")
            if "friction" in record:  # C's own velocity: the no-slip one of euler_to_b plus the slip
                b["vx"], b["vy"] = (mpmath.mpf(record["columns"][c]["value"][j]) for c in ("velocity_x", "velocity_y"))
            for c in B_COLUMNS[1:]:
                cols[c].append(_decimal(b[c]))
    return cols


def _decimal(v) -> str:
    v = mpmath.mpf(v)
    return "0" if v == 0 else mpmath.nstr(v, DIGITS_B, strip_zeros=False, min_fixed=-4, max_fixed=6)


def euler_columns(record: dict) -> dict:
    return {"t": list(record["grid"]), **{n: list(record["state"][n]["value"]) for n in STATE_NAMES}}


def column_units(record: dict, names) -> dict:
    """The unit of each exported column (:mod:`verify.series.columns`' units, form (b)'s added)."""
    length = entry(record["model"]["name"]).length_unit
    units = state_units(length)
    units.update({n: "1" for n in MATRIX_ENTRIES + QUATERNION})
    units.update({"x": length, "y": length, "z": length, "vx": f"{length}/s", "vy": f"{length}/s",
                  "vz": f"{length}/s", "wx": "1/s", "wy": "1/s", "wz": "1/s"})
    return {n: units[n] for n in names}


def _csv(columns: dict, record: dict, form: str) -> str:
    """One form of a case in the suite's CSV (:func:`verify.series.files.to_csv_text`: ``# key: value``
    metadata, ``name [unit]`` headings, the stored decimals as they are)."""
    meta = {"reference_case": record["name"], "form": form, **case_setup(record), "conventions": CONVENTIONS}
    return to_csv_text(RunColumns(columns, column_units(record, columns), meta))


def case_setup(record: dict) -> dict:
    """What a user needs to set the case up in another tool."""
    return {"name": record["name"], "description": record["description"], "source": record["source"],
            "model": record["model"]["name"], "title": record["model"]["title"], "t_end": record["t_end"],
            "initial_state": record["initial_state"],
            "parameters": {k: {"exact": v["exact"], "decimal": v["decimal"], "description": v["description"]}
                           for k, v in record["model"]["parameters"].items()},
            **({"friction": {**record["friction"], "switches": [{"kind": k, "t": t} for k, t in zip(
                record["switches"]["kinds"], record["switches"]["times"]["value"])]}} if "friction" in record else {})}


def export_set(directory: Path, fmt: str, source: Path = DIRECTORY) -> list:
    """Write every case of the set at ``source`` to ``directory`` in ``fmt``; returns the paths written."""
    if fmt not in EXPORT_FORMATS:
        raise ValueError(f"--format {fmt!r}; allowed: {', '.join(EXPORT_FORMATS)}")
    directory = Path(directory)
    if directory.exists() and not directory.is_dir():
        raise ValueError(f"--export {str(directory)!r} exists and is not a folder")
    _refuse_overwriting(directory, Path(source))
    writable_folder(directory)
    files = {}
    setups = []
    for record in load_set(source):
        euler, matrix = euler_columns(record), form_b_columns(record)
        setup = case_setup(record)
        setups.append((setup, bool(matrix)))
        if fmt == "csv":
            files[f"{record['name']}.euler.csv"] = _csv(euler, record, "euler")
            if matrix:
                files[f"{record['name']}.matrix.csv"] = _csv(matrix, record, "matrix+quaternion")
        else:
            files[f"{record['name']}.json"] = json.dumps(
                {"format": "rolling-verify reference case, export 1", **setup, "conventions": CONVENTIONS,
                 "forms": _forms_text(), "units": column_units(record, list(euler) + list(matrix)),
                 "euler": euler, "matrix": matrix or None}, indent=1) + "\n"
    files["README.md"] = readme(setups, fmt, source)
    for name, text in files.items():
        write_atomic(directory / name, text)
    return [directory / n for n in files]


def _forms_text() -> dict:
    return {"euler": "t, " + ", ".join(STATE_NAMES) + ": the stored decimals (agreeing digits) (form (a))",
            "matrix": ", ".join(B_COLUMNS) + f": form (b), from form (a) at 50 digits, {DIGITS_B} significant digits; "
                      "R = Rz(phi) Rx(theta) Rz(psi) body to inertial (column 3 the symmetry axis e3), q = "
                      "qz(phi) qx(theta) qz(psi) scalar first, (x, y, z) and (vx, vy, vz) the centre of mass, "
                      "(wx, wy, wz) the angular velocity in inertial components; Z up, the plane at z = 0"}


def readme(setups: list, fmt: str, source: Path = DIRECTORY) -> str:
    def files(name, has_b):
        if fmt == "json":
            return f"`{name}.json`"
        return f"`{name}.euler.csv`" + (f", `{name}.matrix.csv`" if has_b else "")

    blocks = []
    for s, has_b in setups:
        start = ", ".join(f"{n} = {v}" for n, v in s["initial_state"].items())
        params = ", ".join(f"{k} = {v['exact']}" for k, v in s["parameters"].items())
        blocks.append(f"### `{s['name']}`\n\n{s['description']} ({s['source']}). Model `{s['model']}` ({s['title']}); "
                      f"t from 0 to {s['t_end']} s. Files: {files(s['name'], has_b)}.\n\n"
                      f"* initial state: {start}\n* parameters (exact): {params}\n")
    conventions = "\n".join(f"* **{k}**: {v}" for k, v in CONVENTIONS.items())
    return f"""# The reference cases, exported

Written by `python -m verify reference --export DIR --format {fmt}` from `{_shown_source(source)}` (see its
README for how far the values are agreed). Score your own run of a case with
`python -m verify score RUN --case NAME` (RUN a CSV or JSON file in either form below).

Each CSV is the suite's run-file format (the one `python -m verify trajectory ... --output run.csv`
writes): lines `# key: <JSON value>` with the case's setup and conventions, then one heading line
`name [unit]` (lengths in the body's unit, time in s, rates in 1/s), then the values.  The JSON files
give the same units in `units`.  `score` reads headings with or without units.

## Forms

* **(a) Euler** (`*.euler.csv`, key `euler`): `t, {', '.join(STATE_NAMES)}`, the stored (agreeing-digit)
  decimals unchanged.
* **(b) matrix** (`*.matrix.csv`, key `matrix`): `{', '.join(B_COLUMNS)}`.
  R maps body to inertial components, R = Rz(phi) Rx(theta) Rz(psi), so its third column is the
  symmetry axis e3 and Rij is row i, column j; q = qz(phi) qx(theta) qz(psi) (scalar first) is the same
  rotation; (x, y, z) is the centre of mass C (Z up, the plane at z = 0), (vx, vy, vz) its velocity,
  (wx, wy, wz) the angular velocity in inertial components. Computed from (a) at 50 digits and
  written with {DIGITS_B} significant digits. `score` reads a run with the nine Rij, the four q, or
  both (then R is used and q must be the same rotation at t = 0), with the other nine columns.
  Defined for the bodies on the plane (disk, ring, hurricane balls, smooth-plane disk); the
  gyroscope (fixed pivot) and the effective model (psi = phi imposed) are given in form (a) only.

Back from (b) to (a): theta = atan2(hypot(R13, R23), R33), phi = atan2(R13, -R23),
psi = atan2(R31, R32), thetadot = w . e1, phidot = (w . e2) / sin theta,
psidot = w . e3 - phidot cos theta (phi, psi modulo 2 pi).

## Conventions

{conventions}

## Cases

{chr(10).join(blocks)}"""


def _refuse_overwriting(directory: Path, source: Path) -> None:
    """The export goes to a new or empty folder, or over an earlier export; never over the set it reads
    (its case files share names with the export's JSON files) or over any other folder's files."""
    if directory.resolve() == source.resolve() or (directory / "index.json").exists():
        raise ValueError(f"--export {str(directory)!r} holds a reference set (index.json): the export would "
                         "overwrite its case files; allowed: a new or empty folder, or an earlier export")
    if directory.is_dir():
        present = [p for p in directory.iterdir() if not p.name.startswith(".")]
        earlier = (directory / "README.md").exists() and "export" in (directory / "README.md").read_text()[:400]
        if present and not earlier:
            raise ValueError(f"--export {str(directory)!r} is a folder with other files in it; allowed: a new or "
                             "empty folder, or an earlier export")


def _shown_source(source: Path) -> str:
    """The set's folder as the README names it: relative to the project where it lies inside it."""
    try:
        return str(Path(source).resolve().relative_to(DIRECTORY.resolve().parents[1])) + "/"
    except ValueError:
        return str(source) + "/"

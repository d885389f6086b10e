"""The reference set on disk: one JSON file per case, an index, and a README.

The format is plain JSON (readable without this package): every number that carries
agreeing digits is a decimal string; a double-precision copy sits beside it for
convenience.  ``FORMAT`` names the layout; a reader should refuse any other.

A case file holds: the model (name, title, the source of its equations, a fingerprint of
the equations, parameters as exact rationals and as decimals), the conventions, the exact
initial state, the output grid, the two precisions and their step counts, and for every
state component and every invariant the columns ``value`` (decimal strings rounded to their
agreeing digits), ``digits`` (significant digits on which the two runs agree; null for a value
that is 0 in both runs), ``abs_error`` (the agreement's estimate of a bound on |value - exact|) and ``double``; then the conditioning
(:func:`verify.reference.make.conditioning`) and the provenance (versions, sources' commit).

Format 1 keeps the key names it was published with (``precisions.certified``, the index's
``min_certified_digits_final`` and ``median_certified_digits_final``): readers outside this
package, the committed files (pinned by their sha256) and the report's stored results use them.
What they hold is agreement, not proof, and the record's own description says so.
"""
from __future__ import annotations

import hashlib
import json
import math
from pathlib import Path

import sympy as sp

from models import get_model
from models.symbols import STATE_NAMES

from ..provenance import source_commit, versions, write_atomic
from .cases import ReferenceCase
from .coulomb_runs import check_same_switches
from .make import HIGH, LOW, Run, agreed_columns, conditioning, equations_fingerprint, predicted_digits

# the readers (and the set's place and formats) are json only, shared with the scorer (verify.scoring.casefiles)
from ..scoring.casefiles import (DIRECTORY, FORMAT, INDEX_FORMAT, file_sha256, load_set, read_case,  # noqa: F401
                                 read_index, read_json)

CONVENTIONS = {
    "angles": "3-1-3 Euler angles (phi, theta, psi), paper Fig. 1: e1 = (cos phi, sin phi, 0) the line of nodes, "
              "e3 = (sin phi sin theta, -cos phi sin theta, cos theta) the symmetry axis; theta = pi/2 is upright",
    "state": "theta, phi, psi, thetadot, phidot, psidot, x, y; (x, y) the horizontal position of the centre of mass "
             "(of the pivot's body for the gyroscope and the effective model: x = y = 0); phi and psi continuous, "
             "never reduced modulo 2 pi",
    "angular_velocity": "omega = (thetadot, phidot sin theta, phidot cos theta + psidot) in (e1, e2, e3)",
    "units": "time in seconds; lengths in units of R (disk, ring) or a (hurricane balls); g is g/R (or g/a) in s^-2; "
             "energies per m R^2 (disk, ring, smooth-plane disk) or per 2 m a^2 (hurricane balls, gyroscope, effective), "
             "potential zero on the plane",
    "parameters": "read once, correctly rounded, at the run's precision from their exact values",
    "initial_state": "decimal strings, read once, correctly rounded, at the run's precision",
}


def case_record(c: ReferenceCase, low: Run, high: Run, low_bits: int, high_bits: int) -> dict:
    """The JSON object of one case file."""
    model = get_model(c.model)
    params = {}
    for p in model.parameters:
        exact = sp.Rational(c.params[p.name]) if p.name in c.params else sp.nsimplify(p.default)
        params[p.name] = {"exact": str(exact), "decimal": str(sp.N(exact, 40)), "description": p.description}
    state = agreed_columns(low.state, high.state, low_bits, high_bits)
    invariants = agreed_columns(low.invariants, high.invariants, low_bits, high_bits)
    record = {
        "format": FORMAT,
        "name": c.name,
        "description": c.description,
        "source": c.source,
        "kind": c.kind,
        "model": {"name": c.model, "title": model.title, "equations": "derived", "equations_source": model.source,
                  "equations_sha256": equations_fingerprint(c.model),
                  "equations_sha256_method": "sha256 of the accelerations, the velocity of C, the closed-form "
                                             "invariants and N/(Mg), evaluated at three fixed states with the default "
                                             "parameters at 50 digits and printed to 40 (verify.reference.make)",
                  "parameters": params, "invariants": list(invariants)},
        "conventions": CONVENTIONS,
        "initial_state": {n: c.state.get(n, "0") for n in STATE_NAMES},
        "t_end": c.t_end,
        "grid": c.grid(),
        "precisions": {"low": low.precision, "high": high.precision, "tolerance": "each precision's epsilon",
                       "steps": {low.precision: low.steps, high.precision: high.steps},
                       "certified": "agreeing digits, not proved (the key keeps its format-1 name): value = the high run "
                                    "rounded to the digits on which it and the low run agree; abs_error = one unit in "
                                    "the last agreeing digit, the agreement's estimate of a bound on |value - exact|"},
        "state": state,
        "invariants": invariants,
        "conditioning": conditioning(c),
        "provenance": {"versions": versions(), "source_commit": source_commit()["commit"]},
    }
    if c.hybrid:
        record.update(coulomb_blocks(c, low, high, low_bits, high_bits))
        record["model"]["equations_sha256"] = equations_fingerprint(c.run_model)
    return record


def coulomb_blocks(c: ReferenceCase, low, high, low_bits: int, high_bits: int) -> dict:
    """The keys a Coulomb case adds: ``friction`` (the law, mu, the start's CM velocity), ``phases`` (rolling
    or sliding at each grid time) and ``switches`` (their kinds, and their times agreed like any value)."""
    check_same_switches(low, high)
    times = agreed_columns({"t": low.switch_times}, {"t": high.switch_times}, low_bits, high_bits)["t"]
    return {
        "friction": {"law": "Coulomb, static = kinetic: |F_h| <= mu N while rolling, F_h = -mu N u/|u| while "
                            "sliding (u the contact point's slip velocity)",
                     "mu": c.friction, "model": c.run_model,
                     "initial_velocity_xy": list(c.velocity) if c.velocity else None,
                     "initial_velocity_is": "the centre of mass's (v_x, v_y) at t = 0: the contact slides from the start"
                                            if c.velocity else "null: the start rolls (v_C the no-slip velocity)",
                     "invariants_are": "E + W (E the energy, W = int mu N s dt the work done by friction): conserved",
                     "columns_are": "energy E, work W, slip speed s = |u| (0 while rolling), velocity_x and velocity_y "
                                    "the centre of mass's horizontal velocity (the no-slip one plus the slip u)"},
        "columns": agreed_columns(low.columns, high.columns, low_bits, high_bits),
        "phases": high.phases,
        "switches": {"kinds": high.switch_kinds, "times": times},
    }


def final_summary(record: dict) -> dict:
    """Agreeing digits at the final time and what the conditioning predicts for them."""
    low_bits = int(record["precisions"]["low"].split(":")[1])
    steps = record["precisions"]["steps"][record["precisions"]["low"]]
    scale = reduced_scale(record)
    rows = {}
    for n in STATE_NAMES:
        col = record["state"][n]
        rows[n] = {"digits": col["digits"][-1],
                   "predicted": round(predicted_digits(steps, record["conditioning"]["state_row_sum"][n][-1], scale,
                                                       col["double"][-1], low_bits), 1),
                   "row_sum": record["conditioning"]["state_row_sum"][n][-1]}
    # a component whose exact value is 0 (thetadot of a steady motion) has no significant digits:
    # what the runs agree on is that it is 0 to within abs_error; such values are listed apart
    zeros = {n: record["state"][n]["abs_error"][-1] for n in STATE_NAMES
             if rows[n]["digits"] is None or (rows[n]["digits"] == 0 and abs(record["state"][n]["double"][-1])
                                              <= float(record["state"][n]["abs_error"][-1]))}
    agreed = [r["digits"] for n, r in rows.items() if n not in zeros]
    weakest = min((n for n in rows if n not in zeros), key=lambda n: rows[n]["digits"], default=None)
    return {"min_digits_final": min(agreed) if agreed else None,
            "weakest_component": weakest, "predicted_digits_weakest": rows[weakest]["predicted"] if weakest else None,
            "median_digits_final": sorted(agreed)[len(agreed) // 2] if agreed else None,
            "zero_within_final": zeros,
            "max_row_sum_final": max(r["row_sum"] for r in rows.values()), "components": rows}


def reduced_scale(record: dict) -> float:
    """Y: the largest magnitude the integrator's error control sees (rates, theta, reduced angles 4 pi)."""
    biggest = 4 * math.pi
    for n in ("theta", "thetadot", "phidot", "psidot"):
        biggest = max(biggest, max(abs(v) for v in record["state"][n]["double"]))
    return biggest


def _zeros(entry: dict) -> str:
    zeros = entry.get("zero_within_final") or {}
    return ", ".join(f"{n} ({e})" for n, e in zeros.items()) or "-"


def dumps(record: dict) -> str:
    return json.dumps(record, indent=1) + "\n"


def index_record(records: list) -> dict:
    entries = []
    for r in records:
        s = final_summary(r)
        friction = r.get("friction")
        entries.append({"name": r["name"], "file": f"{r['name']}.json",
                        "model": friction["model"] if friction else r["model"]["name"], "kind": r["kind"],
                        "source": r["source"], "t_end": r["t_end"], "grid_points": len(r["grid"]),
                        "steps": r["precisions"]["steps"], "min_certified_digits_final": s["min_digits_final"],
                        "median_certified_digits_final": s["median_digits_final"],
                        "zero_within_final": s["zero_within_final"],
                        "weakest_component": s["weakest_component"],
                        "predicted_digits_weakest": s["predicted_digits_weakest"],
                        "max_row_sum_final": s["max_row_sum_final"],
                        **({"mu": friction["mu"], "switches": [
                            {"kind": k, "t": t, "digits": d} for k, t, d in zip(
                                r["switches"]["kinds"], r["switches"]["times"]["value"],
                                r["switches"]["times"]["digits"])]} if friction else {}),
                        "sha256": hashlib.sha256(dumps(r).encode()).hexdigest()})
    used = {(r["precisions"]["low"], r["precisions"]["high"]) for r in records}
    low, high = sorted(used)[0] if len(used) == 1 else (LOW, HIGH)
    if len(used) > 1:
        raise ValueError(f"the cases of one set must share their precisions; found {sorted(used)}")
    return {"format": INDEX_FORMAT, "precisions": {"low": low, "high": high}, "cases": entries}


def write_set(records: list, directory: Path = DIRECTORY) -> None:
    """Write every case file, the index and the README (each atomically; nothing before all are computed)."""
    directory = Path(directory)
    for r in records:
        write_atomic(directory / f"{r['name']}.json", dumps(r))
    index = index_record(records)
    write_atomic(directory / "index.json", json.dumps(index, indent=1) + "\n")
    write_atomic(directory / "README.md", readme(index))


def write_case(record: dict, directory: Path = DIRECTORY) -> None:
    """Replace one case file and refresh the index and README from the files on disk."""
    directory = Path(directory)
    write_atomic(directory / f"{record['name']}.json", dumps(record))
    names = [e["name"] for e in read_index(directory)["cases"]] if (directory / "index.json").exists() else []
    if record["name"] not in names:
        names.append(record["name"])
    refresh_index(directory, names)


def refresh_index(directory: Path = DIRECTORY, names=None) -> None:
    """Rewrite index.json and README.md from the case files on disk (all those of the index by default)."""
    directory = Path(directory)
    names = names or [e["name"] for e in read_index(directory)["cases"]]
    index = index_record([read_case(directory / f"{n}.json") for n in names])
    write_atomic(directory / "index.json", json.dumps(index, indent=1) + "\n")
    write_atomic(directory / "README.md", readme(index))


def readme(index: dict) -> str:
    rows = "\n".join(
        f"| `{e['name']}` | {e['model']} | {e['kind']} | {e['source']} | {e['t_end']} | {e['grid_points']} | "
        f"{e['min_certified_digits_final']} | {e['median_certified_digits_final']} | {_zeros(e)} | "
        f"{e['max_row_sum_final']:.2g} |" for e in index["cases"])
    return f"""# Reference trajectories

Generated by `python -m verify reference --make` (do not edit by hand: `index.json` holds each file's
sha256). Each case is integrated by heyoka's Taylor method on the equations derived from the vectors
(`models/rolling.py`) twice, in MPFR at {index['precisions']['low'][3:]} and {index['precisions']['high'][3:]} bits, each at its own epsilon. A stored
value is the {index['precisions']['high'][3:]}-bit result rounded to the significant digits on which the two runs agree;
`abs_error` is one unit in its last agreeing digit. These are *agreeing digits*, not proved ones: two
runs of the same method can share an error, and `abs_error` is the agreement's estimate of a bound, not
a proof. (Format 1 keeps its published key names, `precisions.certified` and the index's
`min_certified_digits_final`: they hold agreeing digits. Proved enclosures are in `proved/`, written by `python -m verify reference --prove`.)

| case | model | kind | source | t_end (s) | grid points | agreeing digits at t_end: min | median | exactly 0, agreed to | max row sum of the transition matrix at t_end |
|---|---|---|---|---:|---:|---:|---:|---|---:|
{rows}

Agreeing digits fall with the conditioning of the flow: a run at epsilon keeps about
-log10(eps sqrt(N) R Y / |y|) digits of a component y, with N the steps, R the row sum of the
state-transition matrix (the `conditioning` block of each file, from heyoka's variational
equations) and Y the largest rate. These flows are integrable, so R grows about linearly with
time: runs of 10 s keep 30 digits or more, runs of 100 s lose one or two more; a value that
happens to pass near zero keeps fewer *significant* digits for the same absolute error, and a
component whose exact value is 0 (thetadot of a steady motion) has none: what the runs agree on
is that it is 0 to within its abs_error (the column 'exactly 0').

## Reading a case without this package

```python
import json
from decimal import Decimal

case = json.load(open("reports/reference/disk-fig3-lhs.json"))
assert case["format"] == "{FORMAT}"
t = [Decimal(s) for s in case["grid"]]                          # exact output times
theta = [Decimal(s) for s in case["state"]["theta"]["value"]]   # agreeing decimals
bound = [Decimal(s) for s in case["state"]["theta"]["abs_error"]]
start = case["initial_state"]                                   # exact decimal strings
params = {{k: v["exact"] for k, v in case["model"]["parameters"].items()}}  # exact rationals
# your integrator's theta at t[-1] should differ from theta[-1] by at most
# bound[-1] + your own error; case["state"]["theta"]["double"] has the values as floats.
```

With mpmath, `mpmath.mpf(s)` after `mpmath.mp.dps = 50`. Every file also carries the model's
parameters (exact rationals and 40-digit decimals), the conventions (Euler angles, state order,
units), the invariants at every grid point (agreed the same way), the conditioning
(`state_row_sum`, `parameter_term`), the step counts, and the versions and commit that made it.

## Checking an integrator

`python -m verify reference --check [--precision double|long|quad]` re-integrates every case at
that precision and prints, per case, the largest error against the agreed values in units of
the bound eps (sqrt(N) R* Y + P + |y|) + abs_error, with R* the largest row sum up to that time and P the
parameter term (`verify/reference/check.py` argues it): a ratio above 1 fails.
"""

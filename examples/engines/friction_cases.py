"""The Coulomb reference cases as the engine adapters run them: the case, its start, and the run's slip.

Shared by ``examples/engines/*_adapter.py`` (each puts this folder on ``sys.path``; the leaderboard loads
only ``*_adapter.py``, so this module is not taken for an engine).  A Coulomb case
(:attr:`verify.reference.cases.ReferenceCase.friction` set: ``coin-coulomb-slip-1``, ``coin-coulomb-skid-1``)
is the coin with Coulomb friction, static = kinetic = mu; it may start rolling (``velocity`` None: the
centre of mass moves as rolling sets it) or sliding (``velocity`` = the centre of mass's horizontal velocity
at t = 0, a skid).

* :func:`load_case` -- the case record the adapters read: ``reports/reference/<case>.json`` when the
  reference set has it, else (a Coulomb case before its file exists) the same keys built from
  :mod:`verify.reference.cases`; the adapters' copy gets ``coulomb``: None for a rolling case, else
  ``{"mu": mu, "velocity": None or (vx, vy)}`` as decimal strings, taken from the case itself.
* :func:`start_b` -- the start in form (b) (:func:`verify.frames.euler_to_b`), with the skid's centre of
  mass velocity in place of the rolling one (its vertical part stays the one the orientation's rates
  set, 0 on both cases: theta' = 0 at t = 0).
* :func:`slip_speed`, :func:`slip_summary` -- the contact point's horizontal velocity
  u = v_C + omega x r_P along a run in form (b) (r_P = -e2 - h e3, the coin's rim edge; the
  scorer's own geometry, :mod:`verify.contact_geometry`), and where the run slides: every interval
  where |u| exceeds :data:`SLIP_THRESHOLD`, its end taken as the stick.
* :func:`reference_switches` -- where the reference slips and sticks (the reference file's switch times
  when it has them, else this suite's hybrid run of the case in double).

Why a threshold of 0.1 R/s.  Every engine here regularises friction or softens the contact, so a
"rolling" contact creeps: at their best settings on the rolling cases the contact point's speed stays
below 0.05 R/s (MuJoCo 0.044, Drake 0.017, PyBullet 7.6e-3, on disk-standard-1 to 1 s), and on the Coulomb
cases, where the reference rolls (10 ms or more from its switches: :func:`creep`), below 3.1e-3 R/s (all
four engines at "best", both cases), far below the slip phases' speeds (up to 3.0 R/s on
coin-coulomb-slip-1, 36 R/s at the start of the skid).  Near a
stick the reference's slip speed falls linearly at 260 R/s^2 (skid) to 480 R/s^2 (slip-1): the
threshold then moves a stick time by at most 0.1/260 = 0.4 ms, below the engines' own errors and
the output spacing of their default settings.  The onset of slip from rolling is slow (s grows like
sigma t^2 / 2 from mu_req = mu), so the threshold shows the slip's start late by about 1.4 ms on
slip-1: the reference's own crossing times at the same threshold (``reference_switches(...,
threshold=...)``: 0.0793 and 0.0964 on slip-1, 0.0761 on the skid) compare like with like.
"""
from __future__ import annotations

import json
from functools import lru_cache

import numpy as np
import sympy as sp

from models import get_model
from models.symbols import STATE_NAMES
from verify.engine.hybrid import solve
from verify.frames import euler_to_b
from verify.reference.cases import case
from verify.reference.store import DIRECTORY
from verify.contact_geometry import b_to_euler, contact_vector

#: Contact slip speed (R/s, length unit per second) above which a run is said to slide (see the module).
SLIP_THRESHOLD = 0.1


def _case(name: str):
    """The :class:`~verify.reference.cases.ReferenceCase` called ``name``, or None when there is none."""
    try:
        return case(name)
    except ValueError:
        return None


def record_from_case(c) -> dict:
    """The keys of a reference file the adapters read (name, model and its parameters, initial_state,
    t_end, grid), built from the case itself: for a Coulomb case whose file is not made yet."""
    model = get_model(c.model)
    params = {}
    for p in model.parameters:
        exact = sp.Rational(c.params[p.name]) if p.name in c.params else sp.nsimplify(p.default)
        params[p.name] = {"exact": str(exact), "decimal": str(sp.N(exact, 40))}
    return {"name": c.name, "model": {"name": c.model, "parameters": params},
            "initial_state": {n: c.state.get(n, "0") for n in STATE_NAMES}, "t_end": c.t_end, "grid": c.grid(),
            "built_from": "verify.reference.cases (no reference file yet)"}


def load_case(name: str) -> dict:
    """The case record (the reference file, or built from the case), with ``coulomb``.

    ``coulomb`` is None for a rolling case (the adapters then roll without slipping, as before), else
    ``{"mu": mu, "velocity": None or the skid's [vx, vy]}`` as decimal strings.
    """
    path = DIRECTORY / f"{name}.json"
    c = _case(name)
    if path.exists():
        record = json.loads(path.read_text())
    elif c is not None:
        record = record_from_case(c)
    else:
        raise FileNotFoundError(f"no reference case {name!r}: neither {path} nor a case of verify.reference.cases")
    hybrid = c is not None and c.friction is not None
    record["coulomb"] = ({"mu": c.friction, "velocity": None if c.velocity is None else list(c.velocity)}
                         if hybrid else None)
    return record


def friction_of(record: dict):
    """mu as a float, or None for a case that rolls without slipping."""
    coulomb = record.get("coulomb")
    return None if coulomb is None else float(coulomb["mu"])


def start_b(record: dict, model: str, params: dict) -> dict:
    """The case's start in form (b) as floats, for ``model`` with ``params`` (as the adapter simulates it),
    with a skid's centre of mass velocity (``record['coulomb']['velocity']``) in place of the rolling one."""
    start = {n: np.array([float(record["initial_state"][n])]) for n in STATE_NAMES}
    b0 = {c: float(v[0]) for c, v in euler_to_b(model, start, params).items()}
    velocity = (record.get("coulomb") or {}).get("velocity")
    if velocity is not None:
        b0["vx"], b0["vy"] = (float(v) for v in velocity)
    return b0


def slip_speed(columns: dict, record: dict) -> np.ndarray:
    """|horizontal velocity of the contact point| along a run in form (b) (matrix or quaternion columns).

    u = v_C + omega x r_P with r_P = -e2 - h e3 (the coin; h = 0 for the disk), the scorer's geometry
    (:func:`verify.contact_geometry.contact_vector`); its vertical part is the height constraint's, not slip.
    """
    cols = {k: np.asarray(v, float) for k, v in columns.items()}
    state, _, w = b_to_euler(cols)
    params = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    r_p = contact_vector(record["model"]["name"], state["theta"], state["phi"], params)
    v = np.array([cols["vx"], cols["vy"], cols["vz"]]) + np.cross(w, r_p, axis=0)
    return np.hypot(v[0], v[1])


def slide_intervals(t, s, threshold: float = SLIP_THRESHOLD) -> list:
    """[(start, end), ...]: where ``s`` exceeds ``threshold``, the crossings interpolated linearly between
    outputs; a slide under way at the first output starts there, one under way at the last ends None."""
    t, s = np.asarray(t, float), np.asarray(s, float)
    above = s > threshold
    out, start = [], (float(t[0]) if above[0] else None)
    for j in range(1, len(t)):
        if above[j] == above[j - 1]:
            continue
        a, b = s[j - 1], s[j]
        cross = float(t[j - 1] + (threshold - a) / (b - a) * (t[j] - t[j - 1]))
        if above[j]:
            start = cross
        else:
            out.append((start, cross))
            start = None
    if start is not None:
        out.append((start, None))
    return out


def slip_summary(columns: dict, record: dict, threshold: float = SLIP_THRESHOLD) -> dict:
    """Where a run slides and sticks, from its own slip speed (JSON-ready).

    Keys: ``threshold``; ``slides`` (intervals as :func:`slide_intervals`, at most 20 listed, ``n_slides``
    counts them); ``slips_at`` (the first slide's start after t = 0, None if it slides from the start or
    never); ``sticks_at`` (the end of the first slide; None if it never slides or never stops);
    ``max_slip`` and where; ``output_spacing`` (the largest step between outputs, the resolution of the
    times above).
    """
    t = np.asarray(columns["t"], float)
    s = slip_speed(columns, record)
    slides = slide_intervals(t, s, threshold)
    j = int(np.argmax(s))
    first = slides[0] if slides else None
    return {"threshold": threshold, "n_slides": len(slides),
            "slides": [[_short(a), _short(b)] for a, b in slides[:20]],
            "slips_at": _short(first[0]) if first and first[0] > t[0] else None,
            "sticks_at": _short(first[1]) if first else None,
            "max_slip": _short(float(s[j])), "max_slip_at": _short(float(t[j])),
            "output_spacing": _short(float(np.max(np.diff(t)))) if len(t) > 1 else None}


def _short(x):
    return None if x is None else float(f"{x:.6g}")


def creep(columns: dict, record: dict, ref: dict, margin: float = 0.01):
    """The largest slip speed of the run where the reference rolls, ``margin`` (s) or more from its
    switches: how far from rolling the engine's contact is while the exact motion rolls (None if no
    output time qualifies)."""
    t = np.asarray(columns["t"], float)
    s = slip_speed(columns, record)
    bounds = [0.0] + list(ref["switch_times"]) + [np.inf]
    rolling = np.zeros_like(t, bool)
    for kind, a, b in zip(ref["phases"], bounds, bounds[1:]):
        if kind == "rolling":
            rolling |= (t >= a + (margin if a > 0 else 0)) & (t <= b - margin)
    return _short(float(np.max(s[rolling]))) if np.any(rolling) else None


@lru_cache(maxsize=None)
def _hybrid_run(name: str, n_eval: int):
    c = _case(name)
    return solve(c.run_model, c.t_end, c.state, c.exact_params, friction=c.friction, velocity=c.velocity,
                 precision="double", n_eval=n_eval)


def reference_switches(record: dict, threshold: float | None = None) -> dict:
    """Where the reference of a Coulomb case slips and sticks: ``{'phases': ['rolling', 'sliding', ...],
    'n_slides', 'switch_times': [...], 'slips_at', 'sticks_at', 'source'}`` (the first slip from rolling after
    t = 0 and the first stick; None where there is none).

    From the reference file's ``switches`` (the hybrid runs' event-located switch times, agreed to 37 digits)
    when the record has them, else from this suite's hybrid run of the case in double
    (:func:`verify.engine.hybrid.solve`: the same times to about 1e-16 s).  With ``threshold``, also where the
    reference's own slip speed crosses it (``slips_at_threshold``, ``sticks_at_threshold``; the hybrid in double
    on 2^12 outputs plus the switch times, some seconds): the times an engine's run is measured by.
    """
    switches = record.get("switches")
    if switches and threshold is None:
        kinds = [switches["kinds"][0].split(" -> ")[0]] + [k.split(" -> ")[1] for k in switches["kinds"]]
        times = [float(t) for t in switches["times"]["value"]]
        source = "the reference file's switches (agreed event-located times)"
    else:
        sol = _hybrid_run(record["name"], 33 if threshold is None else 4097)
        kinds = [ph.kind for ph in sol.phases]
        times = [float(x) for x in sol.switch_times]
        source = "verify.engine.hybrid.solve in double (event-located switches)"
    first_slip = next((t for t, k in zip(times, kinds[1:]) if k == "sliding"), None)
    first_stick = next((t for t, k, j in zip(times, kinds[1:], kinds) if k == "rolling" and j == "sliding"), None)
    out = {"phases": kinds, "n_slides": kinds.count("sliding"), "switch_times": [_short(x) for x in times],
           "slips_at": _short(first_slip), "sticks_at": _short(first_stick), "source": source}
    if threshold is not None:
        slides = slide_intervals([float(x) for x in sol.t], [float(x) for x in sol.slip_speed], threshold)
        if slides:
            a, b = slides[0]
            out["slips_at_threshold"] = _short(a) if a > 0 else None
            out["sticks_at_threshold"] = _short(b)
    return out


def friction_record(columns: dict, record: dict) -> dict:
    """The record's ``friction`` block for a Coulomb case (JSON-ready), or None for a rolling case: ``mu``,
    ``velocity`` (the skid's), ``run`` (:func:`slip_summary` and its ``creep``, :func:`creep`) and
    ``reference`` (:func:`reference_switches`)."""
    if friction_of(record) is None:
        return None
    run = slip_summary(columns, record)
    try:
        ref = reference_switches(record)
        run["creep"] = creep(columns, record, ref)
    except Exception as err:  # noqa: BLE001 -- the run's own numbers stand without the reference's
        ref = {"error": f"{type(err).__name__}: {err}"}
    return {"mu": record["coulomb"]["mu"], "velocity": record["coulomb"]["velocity"], "run": run, "reference": ref}

"""A body's run with friction as a record and as columns: what ``trajectory --body ... --friction MU`` prints and keeps.

Two laws (:mod:`verify.engine.hybrid`, exact Coulomb friction: rolling and sliding phases; :mod:`verify.engine.smooth`,
the smooth law -mu N u/sqrt(|u|^2 + eps^2): no phases).  Their columns (:class:`verify.series.columns.RunColumns`, the
files of :mod:`verify.series.files` and the picture of :mod:`verify.series.plot`) are a rolling run's t and eight
states, then

* Coulomb: ``phase``, ``slip_speed`` [L/s], ``slip_direction`` [rad], ``energy``, ``work``, ``energy_plus_work``
  (:func:`verify.series.columns.run_columns`), and C's horizontal velocity ``xdot``, ``ydot`` [L/s]; the phases and
  the switch times in the metadata;
* smooth: ``slip_e1``, ``slip_h`` (the slip u along e1 and h) and ``slip_speed`` |u| [L/s], ``energy``, ``work``,
  ``energy_plus_work`` [M L^2/s^2], ``normal_force`` [M g], ``height`` z_C [L], ``jellett`` (a sphere's L . r_P),
  ``xdot``, ``ydot`` [L/s].

C's velocity is the sliding equations' own x', y' (paper Eqs. 5-7: u minus the horizontal part of omega x r_P,
:func:`models.coulomb.derive_sliding`, :func:`models.smooth_friction.derive_smooth`) evaluated by a heyoka cfunc at
the run's precision, so the column carries the run's digits; in a rolling phase u = 0 and it is the rolling
constraint's v_C (the tests compare it with the rolling model's ``velocity_xy``).  The body itself is kept in the
metadata (:func:`body_meta`: name, model name, fingerprint, the file's exact text) so that ``plot`` redraws the run and
the body file can be written back to re-run it.
"""
from __future__ import annotations

import numpy as np

from models import coulomb, smooth_friction as sf
from models.smooth_friction import STATE_NAMES as SMOOTH_NAMES

from ..engine.row_functions import evaluate_rows
from ..series import run_columns
from ..series.columns import FORMAT, RunColumns, invariant_unit, state_units, suite_version

#: the columns of C's horizontal velocity, in L/s
VELOCITY_COLUMNS = ("xdot", "ydot")


def body_meta(body, given_as) -> dict:
    """What a run's file records of its body (``given_as``: the --body value as typed)."""
    from models.bodies import fingerprint, model_name, to_toml  # lazy: models.bodies only for a body, not disk+coulomb

    return {"name": body.name, "model": model_name(body), "fingerprint": fingerprint(body), "given_as": str(given_as),
            "toml": to_toml(body)}


def cm_velocity(sol) -> tuple:
    """(xdot, ydot) of C at every output of a Coulomb (``HybridSolution``) or smooth-law run, in the run's precision."""
    p = sol.precision
    smooth = not hasattr(sol, "phases")
    if smooth:
        rolling, equations, params = sf.body(sol.model.removeprefix("body:"))
        extra = (sf.slip_e1, sf.slip_h, sf.work)
        states = sol.y
    else:
        rolling, equations, params = coulomb.body(sol.model)
        extra = (coulomb.slip_speed, coulomb.slip_direction, coulomb.work)
        # rolling outputs: s = 0 and the direction undefined (NaN); s cos(alpha - phi) is then 0 at any alpha
        direction = [p.zero() if np.isnan(float(a)) else a for a in sol.slip_direction]
        states = np.vstack([sol.y, p.array(list(sol.slip_speed))[None, :], p.array(direction)[None, :],
                            p.array(list(sol.work))[None, :]])
    # mu does not enter v_C: only the parameters the expressions read reach the cfunc
    out = evaluate_rows(rolling, extra, params, equations.cm_velocity_xy, states, sol.params, p)
    return out[0], out[1]


def friction_columns(sol, meta: dict) -> RunColumns:
    """The columns of a body's run with friction (module docstring); ``meta`` is added to the metadata."""
    vx, vy = cm_velocity(sol)
    if hasattr(sol, "phases"):
        columns = run_columns(sol, {**meta, "switch_times": [sol.precision.to_text(t) for t in sol.switch_times
                                                             if t is not None]})
        length = columns.units["x"]
        values, units = dict(columns.values), dict(columns.units)
        for name, v in zip(VELOCITY_COLUMNS, (vx, vy)):
            values[name], units[name] = v, f"{length}/s"
        return RunColumns(values, units, columns.meta)
    return _smooth_columns(sol, vx, vy, meta)


def _smooth_columns(sol, vx, vy, meta: dict) -> RunColumns:
    p = sol.precision
    length, inertia = "L", "M L^2"  # a body file's units (models.catalogue.entry of body:NAME)
    values, units = {"t": sol.t}, state_units(length)
    for i, name in enumerate(SMOOTH_NAMES[:8]):
        values[name] = sol.y[i]
    for i, name in ((8, "slip_e1"), (9, "slip_h")):
        values[name], units[name] = sol.y[i], f"{length}/s"
    values["slip_speed"], units["slip_speed"] = np.array([np.hypot(float(a), float(b)) for a, b in
                                                          zip(sol.y[8], sol.y[9])]), f"{length}/s"
    values["energy"], values["work"] = sol.energy, sol.work
    values["energy_plus_work"] = np.array([e + w for e, w in zip(sol.energy, sol.work)], dtype=sol.energy.dtype)
    for name in ("energy", "work", "energy_plus_work"):
        units[name] = invariant_unit(name, inertia, length)
    values["normal_force"], units["normal_force"] = sol.normal_force, "M g"
    values["height"], units["height"] = sol.height, length
    if sol.jellett is not None:
        values["jellett"], units["jellett"] = sol.jellett, invariant_unit("jellett", inertia, length)
    for name, v in zip(VELOCITY_COLUMNS, (vx, vy)):
        values[name], units[name] = v, f"{length}/s"
    info = {
        "format": FORMAT, "model": sol.model + "+smooth", "title": f"the body {meta.get('body', {}).get('name', '')} "
        "under the smooth friction law", "equations": "derived", "precision": p.name,
        "params": {k: p.to_text(v) for k, v in sol.params.items()}, "t_end": p.to_text(sol.t[-1]),
        "start": {n: p.to_text(sol.y[i, 0]) for i, n in enumerate(SMOOTH_NAMES[:8])},
        "start_time": p.to_text(sol.t[0]), "outcome": sol.outcome, "message": str(sol.message), "steps": int(sol.steps),
        "energy_plus_work_drift_in_eps": sol.energy_plus_work_drift_in_eps,
        "jellett_drift_in_eps": sol.jellett_drift_in_eps,
        "units_note": (f"time s, angles rad, lengths in L (the body's scale), g/L = params.g in s^-2; moments of inertia "
                       f"in {inertia}; N in units of M g; slip_speed in double (a reading of slip_e1, slip_h)"),
        "version": suite_version(),
    }
    info.update(meta)
    return RunColumns(values, units, info)


def smooth_record(sol) -> dict:
    """The JSON object of a smooth-law run: the end state, E + W and Jellett's drift, the slip."""
    p = sol.precision
    return {"model": sol.model + "+smooth", "precision": p.name, "params": {k: p.to_json(v) for k, v in sol.params.items()},
            "outcome": sol.outcome, "message": sol.message, "steps": sol.steps, "t": p.to_json(sol.t[-1]),
            "state": {n: p.to_json(sol.y[i, -1]) for i, n in enumerate(SMOOTH_NAMES)},
            "max_theta": float(max(float(v) for v in sol["theta"])), "height": p.to_json(sol.height[-1]),
            "energy_plus_work_drift_in_eps": sol.energy_plus_work_drift_in_eps,
            "jellett_drift_in_eps": sol.jellett_drift_in_eps}


def smooth_text(record: dict) -> str:
    lines = [f"{record['model']} ({record['precision']}), mu = {record['params']['mu']}, eps = {record['params']['eps']}: "
             f"{record['outcome']} at t = {record['t']} s"]
    lines += [f"  {n:<9} {v}" for n, v in record["state"].items()]
    lines.append(f"  max theta {record['max_theta']:.6g} rad, z_C at the end {record['height']} L")
    jellett = record["jellett_drift_in_eps"]
    lines.append(f"  E + W drift: {record['energy_plus_work_drift_in_eps']:.3g} eps of E's term scale"
                 + ("" if jellett is None else f"; Jellett's lambda: {jellett:.3g} eps of its term scale")
                 + f"; {record['steps']} Taylor steps")
    return "\n".join(lines)

"""A run as named columns with units: what ``trajectory --output`` writes and ``plot`` reads.

:func:`run_columns` turns a :class:`~verify.engine.trajectory.Trajectory` (a rolling run) or a
:class:`~verify.engine.hybrid.HybridSolution` (a Coulomb run that rolls and slides) into a
:class:`RunColumns`: ``t`` and the eight state components, then every invariant the model tracks,
N/(Mg) and mu_req where the model has a rolling contact, and for a Coulomb run its phase, slip
speed and direction, energy, work and E + W.  Values stay in the run's precision (floats in
double, ``numpy.longdouble`` in long, heyoka's real128 or real in quad and MPFR); the files of
:mod:`.files` write every digit.

Units (:mod:`models.catalogue`): time in s, angles in rad, rates in 1/s, lengths in the body's
unit L (R, or the ball radius a of the hurricane balls), energies in the model's inertia unit per
s^2 (m R^2/s^2, or 2 m a^2/s^2 for the two balls), N in units of M g.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from models.catalogue import STATE_NAMES, entry

#: Format name and version written into every file (readers check it).
FORMAT = "rolling-verify run 1"


def state_units(length: str) -> dict:
    """Units of ``t`` and the eight state components."""
    rate = "1/s"
    return {"t": "s", "theta": "rad", "phi": "rad", "psi": "rad", "thetadot": rate, "phidot": rate,
            "psidot": rate, "x": length, "y": length}


def invariant_unit(name: str, inertia: str, length: str) -> str:
    """The unit of an invariant the models track (``models.catalogue`` names them)."""
    if name in ("energy", "work", "energy_plus_work"):
        return f"{inertia}/s^2"
    if name in ("chaplygin_1", "chaplygin_2"):
        return "1/s"  # omega2 and omega3 transported to theta_ref (verify.engine.chaplygin)
    if name in ("p_phi", "p_psi", "routh"):
        return f"{inertia}/s"  # angular momenta; Routh's omega3 times a moment of inertia
    if name == "jellett":
        return f"{inertia[:-2]}^3/s" if inertia.endswith("^2") else f"{inertia} {length}/s"  # L . r_P
    raise KeyError(f"no unit for the invariant {name!r}")


@dataclass(frozen=True)
class RunColumns:
    """A run's columns, units and description.

    Attributes
    ----------
    values : dict of name -> ndarray
        Every column on the run's output grid, in order: ``t``, the state, the rest.
    units : dict of name -> str
        The unit of each column ("1" for a pure number, "-" for a label such as ``phase``).
    meta : dict
        JSON-ready: ``format``, ``model``, ``equations``, ``precision``, ``params`` (decimal strings
        carrying every digit), ``t_end``, ``start`` (the state at t = 0), ``outcome``, ``message``,
        ``steps``, ``version`` (the suite's version and sources' commit), and whatever the caller adds
        (``start_name``, ``given``: how the start was typed).
    """

    values: dict
    units: dict
    meta: dict = field(default_factory=dict)

    @property
    def names(self) -> tuple:
        return tuple(self.values)

    def header(self, name: str) -> str:
        """``name [unit]``, the CSV column heading."""
        return f"{name} [{self.units[name]}]"

    def as_float(self, name: str) -> np.ndarray:
        """A column as float64 (for plotting; NaN where a value is undefined)."""
        return np.array([float(v) for v in self.values[name]], dtype=float)


def run_columns(sol, extra_meta: dict | None = None) -> RunColumns:
    """The columns of a :class:`Trajectory` or a :class:`HybridSolution` (see the module docstring)."""
    hybrid = hasattr(sol, "phases")
    info = entry(sol.model)
    length, inertia = info.length_unit, info.inertia_unit
    p = sol.precision
    values = {"t": sol.t}
    units = state_units(length)
    for i, name in enumerate(STATE_NAMES):
        values[name] = sol.y[i]
    if hybrid:
        phase_kind = np.array([sol.phases[i].kind for i in sol.phase_index], dtype=str)
        values["phase"] = phase_kind
        units["phase"] = "-"
        values["slip_speed"], units["slip_speed"] = sol.slip_speed, f"{length}/s"
        values["slip_direction"], units["slip_direction"] = sol.slip_direction, "rad"
        values["energy"] = sol.energy
        values["work"] = sol.work
        values["energy_plus_work"] = np.array([e + w for e, w in zip(sol.energy, sol.work)], dtype=sol.energy.dtype)
        for name in ("energy", "work", "energy_plus_work"):
            units[name] = invariant_unit(name, inertia, length)
    else:
        for name, trace in sol.invariants.items():
            values[name] = trace.values
            units[name] = invariant_unit(name, inertia, length)
        if sol.normal_force is not None:
            values["normal_force"], units["normal_force"] = sol.normal_force, "M g"
        if sol.friction_required is not None:
            values["mu_req"], units["mu_req"] = sol.friction_required, "1"
    meta = {
        "format": FORMAT,
        "model": sol.model,
        "title": info.title,
        "equations": getattr(sol, "equations", "derived"),
        "precision": p.name,
        "params": {k: p.to_text(v) for k, v in sol.params.items()},
        "t_end": p.to_text(sol.t_end) if hasattr(sol, "t_end") else (p.to_text(sol.t[-1]) if len(sol.t) else None),
        "start": {n: p.to_text(sol.y[i, 0]) for i, n in enumerate(STATE_NAMES)} if len(sol.t) else {},
        "start_time": p.to_text(sol.t[0]) if len(sol.t) else None,
        "outcome": sol.outcome,
        "message": str(sol.message),
        "steps": int(sol.steps),
        "units_note": ("time s, angles rad, lengths in L (R, or the ball radius a), g/L = params.g in s^-2; "
                       f"moments of inertia in {inertia}; N in units of M g, M the body's whole mass"),
        "version": suite_version(),
    }
    if hybrid:
        meta["phases"] = [{"kind": ph.kind, "t_start": p.to_text(ph.t_start),
                           "t_end": None if ph.t_end is None else p.to_text(ph.t_end), "ended": ph.ended}
                          for ph in sol.phases]
        meta["energy_plus_work_drift_in_eps"] = sol.energy_plus_work_drift_in_eps
    if getattr(sol, "friction", None) is not None:
        meta["friction"] = p.to_text(sol.friction)
    meta.update(extra_meta or {})
    return RunColumns(values, units, meta)


def suite_version() -> dict:
    """The suite's version and the commit of its sources (``verify.provenance``)."""
    from importlib.metadata import PackageNotFoundError, version  # lazy: 30 ms, only to write a run

    from ..provenance import source_commit  # lazy: 46 ms, only to write a run

    try:
        package = version("rolling-verify")
    except PackageNotFoundError:
        package = None
    return {"package": package, **source_commit()}

"""The units of a sweep's axes and recorded quantities: what its map's labels say (:mod:`verify.sweep.plot`).

The state's units are a run file's (:func:`verify.series.columns.state_units`: angles in rad, rates in
1/s, positions in the model's length unit); ``tilt`` is an angle added to theta; a parameter's unit is
its model's (:mod:`models.catalogue`: moments of inertia in the model's inertia unit, lengths in its
length unit, ``g`` as g/L in 1/s^2, ``k`` = I1/(m R^2) and a friction coefficient pure numbers, a
dissipative couple's coefficient ``c`` in 1/s (the air drag's a pure number) -- a body file's ``c`` is a
semi-axis, a length).
A recorded quantity's unit follows from what it measures (:mod:`verify.sweep.engine`,
:func:`verify.studies.orbits.senses`).  A name with no known unit raises ``KeyError``:
tests/test_sweep_units.py asks for every parameter of every model and every quantity a spec can record.

Labels are written as the run's pictures write them (:mod:`verify.series.plot`): ``name / unit``,
``name / (unit)`` for a compound unit, ``name (ratio)`` for a pure number, ``name (count)`` and
``name (sign)`` for counts and signs.
"""
from __future__ import annotations

from models.catalogue import BODY_PREFIX, entry
from models.symbols import STATE_NAMES

from ..series.columns import state_units
from .spec import FRICTION, SENSE_KEYS, YES_NO

#: A pure number (a ratio of like quantities, a coefficient of friction).
RATIO = "ratio"
#: Dimensionless labels written in parentheses after the name, not as "/ unit".
_WORDS = (RATIO, "count", "sign", "turns", "yes/no")
#: Parameters that are lengths (in the model's length unit): the ring's h and w, a body file's semi-axes
#: and heights.
_LENGTHS = ("h", "w", "a", "c", "half_thickness", "centre_height")
#: The unit of a dissipative model's coefficient ``c`` where it is not 1/s: the couples are per m R^2 (in
#: 1/s^2), so a couple -c omega_perp (rolling friction, Moffatt's, the contact rate's) has c in 1/s, and the
#: air drag's -c A(w) |omega_perp| omega_perp a pure number.
_DISSIPATION = {"ring+air-drag": RATIO}
#: What the senses of an orbit record (verify.studies.orbits.senses): signs (-1, 0, 1), counts, turns.
_COUNTS = ("windows", "windows_undecided", "points_per_nutation")
_TURNS = ("strobe_last", "mean_last")


def parameter_unit(model: str, name: str) -> str:
    """The unit of the parameter ``name`` of ``model`` (module docstring); ``KeyError`` if none is known."""
    catalogue = entry(model)
    if name in ("I1", "I3"):
        return catalogue.inertia_unit
    if name in ("k", FRICTION):
        return RATIO
    if name == "g":
        return "1/s^2"
    if name == "c" and not catalogue.name.startswith(BODY_PREFIX):
        return _DISSIPATION.get(catalogue.name, "1/s")
    if name in _LENGTHS:
        return catalogue.length_unit
    raise KeyError(f"no unit known for the parameter {name!r} of {model!r}")


def axis_unit(model: str, name: str) -> str:
    """The unit of a sweep axis: a state variable, ``tilt`` or a parameter of ``model``."""
    states = state_units(entry(model).length_unit)
    if name in states:
        return states[name]
    if name == "tilt":
        return "rad"
    return parameter_unit(model, name)


def quantity_unit(model: str, name: str) -> str:
    """The unit of a recorded quantity (``verify.sweep.spec.QUANTITIES`` and ``ALWAYS``)."""
    if name in ("max_theta", "min_theta", "final_theta", "max_theta_deviation", "theta_at_slip"):
        return "rad"
    if name.startswith("final_") and name[len("final_"):] in STATE_NAMES:
        return state_units(entry(model).length_unit)[name[len("final_"):]]
    if name in ("growth", "energy_drift_vs_terms", "max_friction_required_on_grid"):
        return RATIO  # max_theta_deviation / tilt; a drift over the energy's term scale; |F_h| / N
    if name in YES_NO:
        return "yes/no"
    if name.startswith("t_"):
        return "s"  # t_stop, t_slip and the senses' times of a window's start
    if name in _COUNTS:
        return "count"
    if name in _TURNS:
        return "turns"
    if name in SENSE_KEYS:
        return "sign"
    raise KeyError(f"no unit known for the quantity {name!r}")


def label(name: str, unit: str) -> str:
    """``name / unit`` (``name / (unit)`` for a compound unit), or ``name (ratio)`` and the like for a word."""
    if unit in _WORDS:
        return f"{name} ({unit})"
    return f"{name} / ({unit})" if any(c in unit for c in " /^") else f"{name} / {unit}"

"""A sweep described by a small TOML file: model, fixed values, axes, run length, what to record.

Example (``verify/sweep/specs/disk-diameter-spin.toml`` ships with the package)::

    [sweep]
    name = "disk-diameter-spin"
    model = "disk"               # python -m verify models lists them (dissipative ones too)
    t_end = 10                   # seconds
    samples = 401                # dense-output samples per run, uniform in [0, t_end]
    chunk = 500                  # trajectories per chunk: the unit of storage and of resuming
    store = "sweeps/disk-diameter-spin.sqlite"   # relative to the working directory

    [params]                     # fixed parameters (numbers or decimal strings)
    k = 0.25

    [start]                      # the start every run shares...
    steady = "diameter-spin"     # ...here the steady motion at the rate axis (models.steady)

    [[axis]]
    name = "phidot"              # a state variable, a parameter, "tilt" (added to theta), or
    from = 14.0                  # "w" with geometry = "annulus" (see below)
    to = 42.0
    count = 100
    scale = "linear"             # or "log"

    [[axis]]
    name = "tilt"
    from = 1e-6
    to = 1e-1
    count = 100
    scale = "log"

    [record]
    quantities = ["max_theta_deviation", "growth", "max_theta", "min_theta"]

    [stop]
    theta_below = 0.05           # optional: a terminal event when theta falls below this

    [plot]
    x = "phidot"
    y = "tilt"
    quantity = "growth"
    log = true

``[geometry] kind = "annulus"`` (ring models) makes I1 and I3 follow from the half-thickness
``h`` and the wall ``w`` (units of R) of an annular cylinder at every point
(:func:`models.ring_dissipation.annulus_inertia`); ``w`` may then be an axis or a fixed value.

A model that rolls may take a friction coefficient, ``[params] friction = MU`` or an axis
``name = "friction"`` (positive ends): every run then also stops at the terminal event ``slips`` of
``solve(..., friction=MU)`` and may record ``slipped``, ``t_slip``, ``theta_at_slip``;
``max_friction_required_on_grid`` needs only a rolling model (:mod:`verify.sweep.engine`).  A
yes/no quantity (:data:`YES_NO`) or ``outcome`` as ``[plot] quantity`` is drawn as categories,
one run a cell, so every axis with more than one value must be ``x``, ``y`` or ``panels``.

Every run records ``outcome`` (``ok``, the terminal event, or ``failed:<reason>`` -- see
:mod:`verify.sweep.engine`), ``t_stop`` (the event's time, or t_end) and ``energy_drift_vs_terms``
(max |E + W - E(0)| over the samples, relative to the largest sum of the magnitudes of the energy's
terms; W is the work of a dissipative term, 0 otherwise).

Validation
----------
Parsing checks the spec's layout, names and each fixed value (a ``[params]`` value, each end of a
parameter axis) against the model's ranges, by :mod:`verify.engine.validation`, the module ``solve``
uses.  The axes are intervals and the ranges are intervals, so an axis whose two ends are in
range has every value in range.  Every point of the grid is then checked as a whole start (the
parameters together, theta in the domain, N > 0) by :func:`verify.sweep.engine.validate_points`
before a store is created; see there why an invalid point refuses the sweep instead of being
stored.  Axis values are computed on demand (:class:`verify.sweep.axes.AxisValues`), never as a list, so a
spec with a typo in a count costs nothing until :mod:`verify.sweep.runner` refuses it by its size.
"""
from __future__ import annotations

import hashlib
import math
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional

import numpy as np

from models import ALL_NAMES, BODY_PREFIX
from models.steady import MOTIONS
from models.symbols import STATE_NAMES

from ..engine.ensemble import resolve
from ..engine.validation import InvalidStart, check_parameter_value
from .axes import Axis, AxisValues

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

#: The orbit/spin senses of a run, read by a study (verify.studies.orbits.senses documents each).
SENSE_KEYS = ("orbit_start", "orbit_end", "orbit_last", "t_orbit_start", "t_orbit_end", "orbit_reversal",
              "t_orbit_reversal", "spin_start", "spin_end", "retrograde_turn", "retrograde_by_last_read",
              "retrograde_end", "t_retrograde", "windows", "windows_undecided", "strobe_last", "mean_last",
              "points_per_nutation", "node_turn_start", "node_turn_end", "node_retrograde_turn", "path_start",
              "path_end", "path_reversal", "roll_start", "roll_end", "roll_reversal", "t_roll_reversal")
#: The friction coefficient of a sweep: ``[params] friction`` or ``[[axis]] name = "friction"`` (a model that rolls).
FRICTION = "friction"
#: What a run records about its friction (verify.sweep.engine documents each); the first three need a coefficient.
FRICTION_KEYS = ("slipped", "t_slip", "theta_at_slip", "max_friction_required_on_grid")
#: Quantities a run can record beyond outcome, t_stop and energy_drift_vs_terms (see verify.sweep.engine).
QUANTITIES = ("max_theta", "min_theta", "final_theta", "max_theta_deviation", "growth") + SENSE_KEYS \
    + tuple(f"final_{n}" for n in STATE_NAMES) + FRICTION_KEYS
ALWAYS = ("t_stop", "energy_drift_vs_terms")
#: Quantities that are 1 (yes), 0 (no) or NaN (not read): drawn as categories, never on a colour bar.
YES_NO = ("slipped", "orbit_reversal", "retrograde_turn", "retrograde_by_last_read", "retrograde_end",
          "node_retrograde_turn", "path_reversal", "roll_reversal")
#: The one categorical column: how each run ended (drawn as one category per outcome).
OUTCOME = "outcome"
GEOMETRIES = ("annulus",)
#: The axis that sets the rate of each steady motion (sleeping: psidot is the spin, phidot = 0).
RATE_AXIS = {"diameter-spin": "phidot", "straight-line": "psidot", "precession": "phidot", "sleeping": "psidot"}
SECTIONS = {"sweep", "params", "start", "axis", "record", "stop", "plot", "geometry"}


class SpecError(ValueError):
    """A sweep specification that cannot be run; the message names the bad value and what is allowed."""


class InvalidPoint(SpecError):
    """A point of the grid that is not a valid start (``verify.engine.validation``): the sweep is refused.

    ``index`` is the first such point, ``point`` its axis values, ``reason`` one of
    ``verify.engine.validation.REASONS``, ``no_steady`` (``[start] steady`` has no such motion at that
    rate) or ``below_stop`` (theta at or below ``[stop] theta_below``: the run would never stop).
    """

    def __init__(self, message: str, index: int, point: dict, reason: str):
        super().__init__(message)
        self.index, self.point, self.reason = index, point, reason


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep (see the module docstring for the TOML layout)."""

    name: str
    model: str
    t_end: float
    samples: int
    chunk: int
    store: Path
    params: dict
    start: dict
    steady: Optional[str]
    axes: tuple
    record: tuple
    theta_stop: Optional[float]
    geometry: Optional[str]
    plot: dict
    text: str = field(repr=False)
    friction: Optional[float] = None  # [params] friction: the fixed coefficient (an axis is in ``axes``)

    @property
    def slips(self) -> bool:
        """Whether the runs have a friction coefficient, fixed or an axis (the terminal event ``slips``)."""
        return self.friction is not None or any(a.name == FRICTION for a in self.axes)

    @property
    def sha256(self) -> str:
        """The spec's identity: a store made by another spec is refused."""
        return hashlib.sha256(self.text.encode()).hexdigest()

    @property
    def n_points(self) -> int:
        return math.prod(len(a.values) for a in self.axes)

    @property
    def n_chunks(self) -> int:
        return -(-self.n_points // self.chunk)

    def point(self, index: int) -> dict:
        """Axis values of point ``index`` (row-major: the last axis varies fastest)."""
        out = {}
        for axis in reversed(self.axes):
            index, j = divmod(index, len(axis.values))
            out[axis.name] = axis.values[j]
        return {a.name: out[a.name] for a in self.axes}

    def columns(self, indices) -> dict:
        """Axis name -> float array of its values at the points ``indices`` (as :meth:`point`)."""
        rest = np.asarray(indices, dtype=np.int64)
        out = {}
        for axis in reversed(self.axes):
            rest, j = np.divmod(rest, len(axis.values))
            out[axis.name] = axis.values.take(j)
        return {a.name: out[a.name] for a in self.axes}

    def chunk_points(self, chunk: int) -> range:
        return range(chunk * self.chunk, min((chunk + 1) * self.chunk, self.n_points))


#: The shipped specs' folder (``verify.sweep.SPECS``).
SHIPPED = Path(__file__).resolve().parent / "specs"


def shipped() -> tuple:
    """The names of the shipped specs (``disk-diameter-spin``, ...)."""
    return tuple(sorted(p.stem for p in SHIPPED.glob("*.toml")))


def load(path, store: Optional[str] = None) -> SweepSpec:
    """Read and validate a spec file, or a shipped spec by its name (``disk-diameter-spin``, with or without
    ``.toml``) where no such file is in the working folder; ``store`` overrides its store path."""
    path = Path(path)
    if not path.exists() and path.parent == Path(".") and path.with_suffix(".toml").stem in shipped():
        path = SHIPPED / f"{path.with_suffix('.toml').stem}.toml"
    try:
        text = path.read_text()
    except FileNotFoundError:
        raise SpecError(f"no sweep spec {path}; allowed: a TOML file, or a shipped spec by name: "
                        f"{', '.join(shipped())}") from None
    except OSError as err:
        raise SpecError(f"cannot read the sweep spec {path}: {err}") from None
    return parse(text, str(path), store)


def parse(text: str, where: str = "<spec>", store: Optional[str] = None) -> SweepSpec:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise SpecError(f"{where} is not valid TOML: {err}") from None
    _only(data, SECTIONS, where)
    sweep = _table(data, "sweep", where, required=True)
    _only(sweep, {"name", "model", "t_end", "samples", "chunk", "store"}, f"{where} [sweep]")
    name = _text(sweep, "name", where)
    model_name = _text(sweep, "model", where)
    if model_name not in ALL_NAMES and not model_name.startswith(BODY_PREFIX):
        raise SpecError(f"{where}: [sweep] model = {model_name!r} is unknown; allowed: {', '.join(ALL_NAMES)}, or a "
                        f"shipped body {BODY_PREFIX}NAME (python -m verify models)")
    try:
        model = resolve(model_name)  # a body file's model is derived once and kept on disk
    except ValueError as err:  # an unknown body
        raise SpecError(f"{where}: [sweep] model = {model_name!r}: {err}") from None
    t_end = _positive(sweep.get("t_end"), "[sweep] t_end", where)
    samples = _count(sweep.get("samples", 401), "[sweep] samples", where, minimum=2)
    chunk = _count(sweep.get("chunk", 512), "[sweep] chunk", where, minimum=1)
    store_path = Path(store if store is not None else _text(sweep, "store", where))

    geometry_table = _table(data, "geometry", where)
    _only(geometry_table, {"kind"}, f"{where} [geometry]")
    geometry = geometry_table.get("kind")
    if geometry is not None and geometry not in GEOMETRIES:
        raise SpecError(f"{where}: [geometry] kind = {geometry!r}; allowed: {', '.join(GEOMETRIES)}")
    if geometry == "annulus" and not {"I1", "I3", "h"} <= set(model.parameter_names):
        raise SpecError(f"{where}: [geometry] kind = 'annulus' needs a ring model (I1, I3, h); {model_name!r} has "
                        f"{', '.join(model.parameter_names)}")
    settable = set(model.parameter_names)
    if geometry == "annulus":
        settable = (settable - {"I1", "I3"}) | {"w"}
    rolls = model.horizontal_acceleration is not None and model.normal_force is not None  # as slip_event_function
    if rolls:
        settable |= {FRICTION}

    params = {}
    for key, value in _table(data, "params", where).items():
        if key == FRICTION and not rolls:
            raise SpecError(f"{where}: [params] friction: {model_name!r} has no rolling contact, so no friction to "
                            "run out of; allowed: friction with a model that rolls (python -m verify models)")
        if key not in settable:
            raise SpecError(f"{where}: [params] {key} is not a parameter of {model_name!r}; allowed: "
                            f"{', '.join(sorted(settable))}")
        params[key] = _number(value, f"[params] {key}", where)
        if key == FRICTION:
            _positive(value, "[params] friction (a coefficient)", where)
        _in_range(model, key, params[key], value, f"[params] {key} = {value!r}", where)
    friction = params.pop(FRICTION, None)

    start_table = dict(_table(data, "start", where))
    steady = start_table.pop("steady", None)
    if steady is not None:
        allowed = MOTIONS.get(model_name, ())
        if steady not in allowed:
            raise SpecError(f"{where}: [start] steady = {steady!r} for {model_name!r}; allowed: "
                            f"{', '.join(allowed) or 'none (this model has no steady-motion study)'}")
    start = {}
    for key, value in start_table.items():
        if key not in STATE_NAMES:
            raise SpecError(f"{where}: [start] {key} is not a state variable; allowed: {', '.join(STATE_NAMES)}, steady")
        start[key] = _number(value, f"[start] {key}", where)

    axes = []
    for i, ax in enumerate(data.get("axis", []) or []):
        if not isinstance(ax, dict):
            raise SpecError(f"{where}: [[axis]] number {i + 1} is not a table")
        _only(ax, {"name", "from", "to", "count", "scale"}, f"{where} [[axis]] {i + 1}")
        axes.append(_axis(ax, i, settable, steady, model_name, where))
    if not axes:
        raise SpecError(f"{where}: no [[axis]]; a sweep needs at least one")
    names = [a.name for a in axes]
    if len(set(names)) != len(names):
        raise SpecError(f"{where}: an axis is given twice: {names}")
    clash = set(names) & (set(params) | set(start) | ({FRICTION} if friction is not None else set()))
    if clash:
        raise SpecError(f"{where}: {sorted(clash)[0]} is both an axis and a fixed value")
    if geometry == "annulus":
        missing = {"h", "w"} - set(names) - set(params)
        if missing:
            raise SpecError(f"{where}: [geometry] annulus needs h and w (as axes or [params]); missing "
                            f"{', '.join(sorted(missing))}")
    if steady is not None and RATE_AXIS[steady] not in names:
        raise SpecError(f"{where}: [start] steady = {steady!r} needs an axis named {RATE_AXIS[steady]!r} (its rate)")
    if "tilt" in names and steady is None and "theta" not in start:
        raise SpecError(f"{where}: the axis 'tilt' is added to theta: give [start] theta or [start] steady")

    record_table = _table(data, "record", where)
    _only(record_table, {"quantities"}, f"{where} [record]")
    record = tuple(record_table.get("quantities", ()))
    for q in record:
        if q not in QUANTITIES:
            raise SpecError(f"{where}: [record] quantity {q!r} is unknown; allowed: {', '.join(QUANTITIES)}")
    if "growth" in record and "tilt" not in names:
        raise SpecError(f"{where}: [record] growth is max_theta_deviation / tilt: it needs an axis named 'tilt'")
    slips = friction is not None or FRICTION in names
    for q in FRICTION_KEYS:
        if q in record and not rolls:
            raise SpecError(f"{where}: [record] {q}: {model_name!r} has no rolling contact; allowed with a model that "
                            "rolls")
        if q in record and q != "max_friction_required_on_grid" and not slips:
            raise SpecError(f"{where}: [record] {q} needs a friction coefficient: [params] friction = MU or an "
                            "[[axis]] named 'friction'")

    stop = _table(data, "stop", where)
    _only(stop, {"theta_below"}, f"{where} [stop]")
    theta_stop = None
    if "theta_below" in stop:
        theta_stop = _positive(stop["theta_below"], "[stop] theta_below", where)

    plot = dict(_table(data, "plot", where))
    _only(plot, {"x", "y", "panels", "quantity", "log", "title"}, f"{where} [plot]")
    for key in ("x", "y", "panels"):
        if key in plot and plot[key] not in names:
            raise SpecError(f"{where}: [plot] {key} = {plot[key]!r} is not an axis; allowed: {', '.join(names)}")
    if "quantity" in plot and plot["quantity"] not in QUANTITIES + ALWAYS + (OUTCOME,):
        raise SpecError(f"{where}: [plot] quantity = {plot['quantity']!r}; allowed: recorded quantities or outcome")
    shown = plot.get("quantity", record[0] if record else ALWAYS[0])
    if shown in YES_NO + (OUTCOME,):
        drawn = {plot.get("x", names[0]), plot.get("y", names[min(1, len(names) - 1)]), plot.get("panels")}
        hidden = [a.name for a in axes if a.name not in drawn and len(a.values) > 1]
        if hidden:
            raise SpecError(f"{where}: [plot] quantity = {shown!r} is drawn as categories, one run a cell, and cannot "
                            f"be averaged over the axis {hidden[0]!r}; allowed: that axis as [plot] x, y or panels")
    return SweepSpec(name, model_name, t_end, samples, chunk, store_path, params, start, steady, tuple(axes), record,
                     theta_stop, geometry, plot, text, friction)


def _axis(ax: dict, i: int, settable: set, steady, model_name: str, where: str) -> Axis:
    name = ax.get("name")
    allowed = set(STATE_NAMES) | settable | {"tilt"}
    if name == FRICTION and FRICTION not in settable:
        raise SpecError(f"{where}: [[axis]] {i + 1} name = 'friction': {model_name!r} has no rolling contact, so no "
                        "friction to run out of; allowed: friction with a model that rolls (python -m verify models)")
    if name not in allowed:
        raise SpecError(f"{where}: [[axis]] {i + 1} name = {name!r}; allowed: state variables "
                        f"({', '.join(STATE_NAMES)}), parameters of {model_name!r} ({', '.join(sorted(settable))}) "
                        "or 'tilt'")
    lo = _number(ax.get("from"), f"[[axis]] {name} from", where)
    hi = _number(ax.get("to"), f"[[axis]] {name} to", where)
    count = _count(ax.get("count"), f"[[axis]] {name} count", where, minimum=1)
    scale = ax.get("scale", "linear")
    if scale not in ("linear", "log"):
        raise SpecError(f"{where}: [[axis]] {name} scale = {scale!r}; allowed: linear, log")
    if scale == "log" and not (lo > 0 and hi > 0):
        raise SpecError(f"{where}: [[axis]] {name}: a log axis needs positive ends; got from = {lo}, to = {hi}")
    if name == FRICTION and not (lo > 0 and hi > 0):
        raise SpecError(f"{where}: [[axis]] friction: a friction coefficient must be positive; got from = {lo}, "
                        f"to = {hi}")
    model = resolve(model_name)
    for end, raw in (("from", ax.get("from")), ("to", ax.get("to"))):  # monotone axis: its ends bound it
        _in_range(model, name, lo if end == "from" else hi, raw, f"[[axis]] {name} {end} = {raw!r}", where)
    # geometric axes keep their ends exactly as written (AxisValues.value)
    return Axis(name, AxisValues(lo, hi, count, scale), scale)


def _in_range(model, name: str, value: float, raw, what: str, where: str) -> None:
    """A fixed value or an axis end of a model parameter against its range (verify.engine.validation)."""
    if name not in model.parameter_names:
        return
    try:
        check_parameter_value(model, name, value, shown=raw)
    except InvalidStart as err:
        raise SpecError(f"{where}: {what}: {err}") from None


def _only(table: dict, allowed: set, where: str) -> None:
    extra = sorted(set(table) - allowed)
    if extra:
        raise SpecError(f"{where}: unknown key {extra[0]!r}; allowed: {', '.join(sorted(allowed))}")


def _table(data: dict, key: str, where: str, required: bool = False) -> dict:
    value = data.get(key)
    if value is None:
        if required:
            raise SpecError(f"{where}: the [{key}] table is missing")
        return {}
    if not isinstance(value, dict):
        raise SpecError(f"{where}: [{key}] must be a table")
    return value


def _text(table: dict, key: str, where: str) -> str:
    value = table.get(key)
    if not isinstance(value, str) or not value:
        raise SpecError(f"{where}: {key} must be a non-empty string; got {value!r}")
    return value


def _number(value, what: str, where: str) -> float:
    if isinstance(value, bool):
        raise SpecError(f"{where}: {what} = {value!r} is not a number")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise SpecError(f"{where}: {what} = {value!r} is not a number") from None
    if not math.isfinite(v):
        raise SpecError(f"{where}: {what} = {value!r} is not finite")
    return v


def _positive(value, what: str, where: str) -> float:
    v = _number(value, what, where)
    if not v > 0:
        raise SpecError(f"{where}: {what} = {value!r} must be positive")
    return v


def _count(value, what: str, where: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise SpecError(f"{where}: {what} = {value!r} must be an integer >= {minimum}")
    if value < minimum:
        raise SpecError(f"{where}: {what} = {value} must be at least {minimum}")
    return value

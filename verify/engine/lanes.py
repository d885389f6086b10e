"""The lanes of batch runs: the SIMD width, and a model's lane system compiled once (:func:`compile_lanes`).

heyoka's batch mode runs ``batch_size`` trajectories in the lanes of SIMD registers.  The
width it recommends depends on the CPU (4 doubles with AVX2, 8 with AVX-512), and results
of batch runs differ at round-off between widths, so the width is an explicit setting:

* ``VERIFY_SIMD_WIDTH=N`` in the environment fixes it (e.g. to reproduce on an AVX2 machine
  what an AVX-512 machine computes, or to run the batch-dependent tests at both widths);
* otherwise :func:`heyoka.recommended_simd_size` decides.

Nothing in the suite may assume a particular width.

A lane system (:class:`LaneSystem`) is a model's equations as a ``taylor_adaptive_batch`` template
with freezing terminal events (:mod:`.batch`): every right-hand side multiplied by the lane's
``alive`` parameter, and each per-lane parameter -- the model's, the bookkeeping records
(``alive``, ``reason``, ``t_stop``, and in the ``full`` form the state at the stop, ``theta_at_stop``, ...) and the lane's settings (``theta_max``,
``theta_stop``, ``theta_lower``, ``theta_upper``, ``friction``) -- at a position found by its
name in :class:`LaneLayout`, never by offset arithmetic.  Two forms (paper Eqs. 18, 50, 67, 87
and the dissipative variants, as the model derives them):

* ``full``: the eight states (theta, phi, psi, their rates, x, y) and the work W of a dissipative
  term (the sweeps); events: the domain's ends, ``theta_stop`` (a spec's ``[stop]``), the loss of
  contact, ``slips`` (a friction coefficient);
* ``reduced``: theta, thetadot, phidot, psidot only (the stability maps: phi, psi, x, y appear on
  no right-hand side of these four); events: theta at the lane's lower and upper bound, the loss
  of contact.

heyoka sizes a system's parameters by the highest ``par[i]`` its expressions read, so the records
(written by the events' callbacks, read by no expression) sit below a parameter that is read.
"""
from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import numpy as np
import sympy as sp

from models.base import Model
from models.symbols import ACCELERATIONS, STATE, STATE_NAMES, phidot, psidot, theta, thetadot

from . import batch
from .compile import FRICTION, contact_event, slip_event_function, to_heyoka

ENV = "VERIFY_SIMD_WIDTH"
#: The forms of a lane system (module docstring).
FORMS = ("full", "reduced")
#: The ``full`` form's records of the state where a terminal event froze a lane (``theta_at_stop``, ...):
#: what a sweep's ``final_*`` of a stopped run reads (its samples end at the last grid time before the stop).
AT_STOP = tuple(f"{name}_at_stop" for name in STATE_NAMES)
#: Bookkeeping records and the value a lane starts with: alive (1, or 0 once frozen), the code of the
#: event that froze it (0: none), when, and (``full`` form) the state there.
RECORDS = {"alive": 1.0, "reason": 0.0, "t_stop": math.nan, **dict.fromkeys(AT_STOP, math.nan)}
REDUCED_STATES = ("theta", "thetadot", "phidot", "psidot")


def simd_width() -> int:
    """Lanes of one SIMD register for double precision (``VERIFY_SIMD_WIDTH`` or heyoka's choice)."""
    text = os.environ.get(ENV, "").strip()
    if not text:
        return int(hy.recommended_simd_size())
    try:
        width = int(text)
    except ValueError:
        width = 0
    if width < 1 or width > 64:
        raise ValueError(f"{ENV}={text!r}: allowed a whole number of lanes from 1 to 64 (e.g. 4 or 8)")
    return width


@dataclass(frozen=True)
class LaneLayout:
    """Every per-lane parameter by name: ``par[i]`` of the lane system is ``names[i]``."""

    names: tuple

    def __getitem__(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise KeyError(f"{name!r} is not a lane parameter; allowed: {', '.join(self.names)}") from None

    def __contains__(self, name) -> bool:
        return name in self.names

    def __len__(self) -> int:
        return len(self.names)

    def columns(self, n: int, values: Mapping) -> np.ndarray:
        """The (len(names), n) array of the lanes' parameters from ``values`` (name -> a number or n numbers).

        Every name must be given, except the records of :data:`RECORDS`, which start at their values
        there; a name that is not a lane parameter is refused.  The order of ``values`` plays no part.
        """
        unknown = [k for k in values if k not in self.names]
        if unknown:
            raise KeyError(f"{unknown[0]!r} is not a lane parameter; allowed: {', '.join(self.names)}")
        out = np.empty((len(self.names), n))
        for i, name in enumerate(self.names):
            if name in values:
                out[i] = values[name]
            elif name in RECORDS:
                out[i] = RECORDS[name]
            else:
                raise KeyError(f"no value for the lane parameter {name!r}; given: {', '.join(values) or 'none'}")
        return out


@dataclass(frozen=True, eq=False)
class LaneSystem:
    """A model's batch template with freezing events (:func:`compile_lanes`).

    ``states`` names the integrated states in order, ``events`` the terminal events (the code
    recorded in ``reason`` is the index + 1), ``layout`` the per-lane parameters.
    """

    model: Model
    form: str
    states: tuple
    events: tuple
    layout: LaneLayout
    template: object  # taylor_adaptive_batch, copied by every ensemble run, never integrated itself
    cooldown: float

    @property
    def batch_size(self) -> int:
        return int(self.template.batch_size)

    @property
    def records(self) -> batch.Lanes:
        return batch.Lanes(self.layout["alive"], self.layout["reason"], self.layout["t_stop"])

    def row(self, name: str) -> int:
        """The state row called ``name``."""
        return self.states.index(name)


@lru_cache(maxsize=None)
def compile_lanes(model: Model, form: str, batch_size: int, cooldown: float, stop: bool = False,
                  friction: bool = False, bare: bool = False, events: tuple = None) -> LaneSystem:
    """The lane system of ``model`` (compiled once per process and settings; heyoka caches the code on disk).

    Parameters
    ----------
    model : Model
    form : str
        ``"full"`` or ``"reduced"`` (module docstring).
    batch_size : int
        Lanes per batch.
    cooldown : float
        Longer than any run: an event fires at most once in a lane.
    stop : bool
        ``full`` only: the event ``theta_stop`` where theta falls through the lane's ``theta_stop``
        (compiled only when asked for: an event costs on every step).
    friction : bool
        ``full`` only: the event ``slips`` where the friction the rolling needs reaches the lane's
        ``friction`` (:func:`verify.engine.compile.slip_event_function`, as ``solve(friction=...)``).
    """
    if form not in FORMS:
        raise ValueError(f"form={form!r}; allowed: {', '.join(FORMS)}")
    if form == "reduced" and (stop or friction):
        raise ValueError("the reduced lane system has no theta_stop or slips event; allowed: form='full'")
    build = _full if form == "full" else _reduced
    states, system, compiled, names, park, between, record, rest = build(model, stop, friction, bare)
    if events is not None:
        if not bare:
            raise ValueError("a choice of events is for a bare baseline: every guard runs on the suite's lanes")
        compiled = [e for e in compiled if e[0] in events]
    events = compiled
    if bare:  # heyoka wants exactly as many parameters as the highest par[i] read: the records may go unread
        exprs = [rhs for _, rhs in system] + [ex for _, ex, _ in events]
        names = names[: 1 + max([int(str(p)[1:]) for p in hy.get_params(exprs)], default=-1)]
        park, between, record = (), None, ()  # nothing frozen, nothing parked
    layout = LaneLayout(names)
    where = batch.Lanes(*(layout.names.index(k) if k in layout else -1 for k in ("alive", "reason", "t_stop")))
    park_rows = tuple((states.index(k), v) for k, v in park)
    between_rows = None if between is None else (states.index(between[0]), layout[between[1]], layout[between[2]])
    record_rows = tuple((states.index(k), layout[p]) for k, p in record)
    template = batch.batch_system(system, events, where, len(names), batch_size, cooldown, rest,
                                  [float(sp.N(p.default)) for p in model.parameters], park=park_rows,
                                  park_between=between_rows, record=record_rows, freezing=not bare)
    return LaneSystem(model, form, states, tuple(e[0] for e in events), layout, template, cooldown)


def _full(model: Model, stop: bool, friction: bool, bare: bool):
    """The eight states (and W), each right-hand side times ``alive``; the sweeps' events."""
    variables = list(hy.make_vars(*STATE_NAMES))
    mapping = dict(zip(STATE, variables))
    last_name = "theta_stop" if stop else "theta_max"  # the one the last event reads
    # the state at an event (records, read by no expression) below the parameter the last event reads
    names = tuple(model.parameter_names) + ("alive", "reason", "t_stop") + AT_STOP + (last_name,)
    if friction:
        names += ("friction",)
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    alive, last = hy.par[names.index("alive")], hy.par[names.index(last_name)]
    unscaled = [to_heyoka(r, mapping, compact=True) for _, r in model.rhs()]
    system = [(v, r if bare else r * alive) for v, r in zip(variables, unscaled)]
    states = STATE_NAMES
    if model.dissipation is not None:
        W = hy.make_vars("W")
        work = to_heyoka(model.dissipation, mapping, compact=True)
        system.append((W, work if bare else work * alive))
        variables.append(W)
        states = STATE_NAMES + ("W",)
    th = variables[0]
    dom = model.domain
    lo, hi = float(dom.theta_min), float(dom.theta_max)
    if stop:
        events = [(dom.below, th - lo, hy.event_direction.negative), (dom.above, th - hi, hy.event_direction.positive),
                  ("theta_stop", th - last, hy.event_direction.negative)]
    else:  # the upper end read from the lane's theta_max: the records must sit below a parameter that is read
        events = [(dom.below, th - lo, hy.event_direction.negative), (dom.above, th - last, hy.event_direction.positive)]
    rates = [unscaled[STATE_NAMES.index(s)] for s in ("thetadot", "phidot", "psidot")]
    if model.normal_force is not None:
        # the event reads the system's own accelerations so that heyoka's decomposition computes them once
        events.append(("contact_lost", contact_event(model, mapping, rates), hy.event_direction.negative))
    record = tuple(zip(STATE_NAMES, AT_STOP))
    if friction:
        f = slip_event_function(model)
        if f is None:
            raise ValueError(f"model {model.name!r} has no rolling contact, so no friction to run out of; allowed: "
                             "a friction coefficient with a model that rolls")
        # last, so the other events keep their codes
        slip_map = {**mapping, FRICTION: hy.par[names.index("friction")], **dict(zip(ACCELERATIONS, rates))}
        events.append(("slips", to_heyoka(f, slip_map, compact=True), hy.event_direction.positive))
    safe = 0.5 * (lo + hi)
    # a frozen lane is parked mid-domain with phidot = 1, not 0: |omega_perp| terms (sqrt) have no
    # Taylor series at 0
    park = (("theta", safe), ("thetadot", 0.0), ("psidot", 0.0), ("phidot", 1.0))
    rest = np.zeros(len(variables))
    rest[0] = safe
    return states, system, events, names, park, None, record, rest


def _reduced(model: Model, stop: bool, friction: bool, bare: bool):
    """theta, thetadot, phidot, psidot, each right-hand side times ``alive``; bounds per lane."""
    variables = hy.make_vars(*REDUCED_STATES)
    mapping = dict(zip((theta, thetadot, phidot, psidot), variables))
    names = tuple(model.parameter_names) + ("alive", "reason", "t_stop", "theta_lower", "theta_upper")
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    alive, lower, upper = (hy.par[names.index(k)] for k in ("alive", "theta_lower", "theta_upper"))
    rhs = [thetadot] + list(model.accelerations)
    allowed = set(mapping)
    for expr in rhs + ([model.normal_force] if model.normal_force is not None else []):
        extra = expr.free_symbols - allowed
        if extra:
            raise ValueError(f"model {model.name!r}: the reduced system depends on {sorted(map(str, extra))}")
    unscaled = [to_heyoka(r, mapping, compact=True) for r in rhs]
    system = [(v, r if bare else r * alive) for v, r in zip(variables, unscaled)]
    th = variables[0]
    events = [("below", th - lower, hy.event_direction.negative), ("above", th - upper, hy.event_direction.positive)]
    if model.normal_force is not None:
        events.append(("contact_lost", contact_event(model, mapping, unscaled[1:]), hy.event_direction.negative))
    # a frozen lane is parked in the middle of its bounds with thetadot = 0: never on a singular end
    return REDUCED_STATES, system, events, names, (("thetadot", 0.0),), ("theta", "theta_lower", "theta_upper"), \
        (), np.ones(4)

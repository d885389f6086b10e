"""Integrate a model by Taylor's method at any precision and return a named record.

Shaped like scipy's ``solve_ivp``: ``solve`` returns a :class:`Trajectory` with ``t``,
``y`` (one row per state component), ``status``, ``message``, the events that stopped it,
and the invariants with their drift; a failed integration raises
:class:`IntegrationError` instead of returning a short array.

Cyclic coordinates and error control
------------------------------------
heyoka's step-size control is relative to the largest state component, so a phi, psi,
x or y that grows without bound loosens the control of theta and the rates, and the
energy error grows like t instead of Brouwer's sqrt(t) (HEYOKA.md).  None of phi, psi,
x, y feeds back into the dynamics (psi, x, y appear nowhere on the right-hand side, phi
only through x', y'), so the run is cut into fixed segments and between segments they
are moved into offsets kept outside the integrator: phi and psi by whole turns (exact multiples of the precision's
2 pi, so sin and cos of phi are unchanged), x and y entirely.  The returned phi, psi,
x, y are the offsets plus the reduced values: continuous, never reduced modulo 2 pi.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import heyoka as hy
import mpmath
import numpy as np

from models import get_model
from models.base import Model
from models.symbols import STATE_NAMES

from . import invariants as inv
from .compile import compile_model
from .invariants import InvariantTrace
from .precision import Precision, parse_precision

_CYCLIC = (1, 2, 6, 7)  # phi, psi, x, y
_ANGLES = (1, 2)


class IntegrationError(RuntimeError):
    """The integrator failed (non-finite state, step limit): no partial result is returned."""


@dataclass(frozen=True)
class Trajectory:
    """A run: grid times, states, outcome, invariants.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times reached on the grid, plus the event time if a terminal event stopped the run.
    y : ndarray, shape (8, n)
        States, rows in the order of ``state_names``; phi, psi continuous.
    status : int
        0 when ``t_end`` was reached, 1 when a terminal event stopped the run.
    outcome : str
        ``"ok"`` or ``"event:<name>"`` (``lies_flat``, ``rim_switch``, ``contact_lost``, ...).
    steps : int
        Taylor steps taken.
    invariants : dict of name -> InvariantTrace
        Energy first, then the model's other conserved quantities; each with its values and
        ``max_abs_drift``, ``max_rel_drift`` (over |I(0)|) and ``max_drift_vs_terms`` (over
        the magnitudes of I's terms), see :class:`verify.invariants.InvariantTrace`.
    normal_force : ndarray or None
        N / (M g) on the grid (contact holds while it is positive).
    """

    model: str
    equations: str
    precision: Precision
    params: dict
    t_end: object
    t: np.ndarray
    y: np.ndarray
    status: int
    message: str
    outcome: str
    t_events: dict
    steps: int
    tol: object
    invariants: dict = field(repr=False)
    normal_force: object = field(default=None, repr=False)
    state_names: tuple = STATE_NAMES

    @property
    def success(self) -> bool:
        return self.status >= 0

    def __getitem__(self, name: str) -> np.ndarray:
        return self.y[STATE_NAMES.index(name)]

    @property
    def final_state(self) -> dict:
        return {n: self.y[i, -1] for i, n in enumerate(STATE_NAMES)}


def resolve_parameters(model: Model, values, precision: Precision) -> dict:
    """Every parameter of the model at ``precision``: defaults overridden by ``values``."""
    values = dict(values or {})
    unknown = sorted(set(values) - set(model.parameter_names))
    if unknown:
        raise ValueError(
            f"unknown parameter {unknown[0]!r} for model {model.name!r}; allowed: {', '.join(model.parameter_names)}"
        )
    out = {}
    for p in model.parameters:
        raw = values.get(p.name, p.default)
        try:
            val = precision.number(raw)
        except (ValueError, TypeError) as err:
            raise ValueError(f"parameter {p.name}={raw!r}: {err}") from None
        p.check(val, shown=raw)
        out[p.name] = val
    model.check_relations(out)
    return out


def resolve_state(model: Model, values, precision: Precision) -> np.ndarray:
    """The eight-component initial state; unset components are 0."""
    values = dict(values or {})
    unknown = sorted(set(values) - set(STATE_NAMES))
    if unknown:
        raise ValueError(f"unknown state variable {unknown[0]!r}; allowed: {', '.join(STATE_NAMES)}")
    state = []
    for name in STATE_NAMES:
        raw = values.get(name, 0)
        try:
            state.append(precision.number(raw))
        except (ValueError, TypeError) as err:
            raise ValueError(f"state {name}={raw!r}: {err}") from None
    dom = model.domain
    th = state[0]
    if not dom.contains(th):
        raise ValueError(
            f"state theta={values.get('theta', 0)} is outside the domain of {model.name!r}: "
            f"{float(dom.theta_min):.17g} < theta < {float(dom.theta_max):.17g} "
            f"(at the lower end: {dom.below}; at the upper end: {dom.above})"
        )
    return precision.array(state)


def _check_constraints(model: Model, state, params, precision: Precision) -> None:
    from models.symbols import STATE as SYMS

    for name, expr, text in model.constraints:
        subs = {s: precision.to_mpf(v) for s, v in zip(SYMS, state)}
        with mpmath.workprec(precision.bits + 16):
            val = expr.subs(subs)
        if val != 0:
            raise ValueError(f"state violates the constraint {name} = 0 ({text}); it is {float(val):g}")


def _parse_positive(name: str, value, precision: Precision):
    try:
        v = precision.number(value)
    except (ValueError, TypeError) as err:
        raise ValueError(f"{name}={value!r}: {err}") from None
    if not float(v) > 0:
        raise ValueError(f"{name}={value} must be a positive finite number")
    return v


class _Offsets:
    """phi, psi, x, y moved out of the integrator (module docstring)."""

    def __init__(self, precision: Precision):
        self.fp = precision.number
        with mpmath.workprec(precision.bits + 32):
            self.two_pi = precision.number(2 * mpmath.pi)
        self.limit = {1: float(self.two_pi), 2: float(self.two_pi), 6: 1.0, 7: 1.0}
        self.value = {i: precision.zero() for i in _CYCLIC}

    def rebase(self, st) -> None:
        """Move whole turns of phi, psi and all of x, y from the state into the offsets."""
        for i in _CYCLIC:
            v = st[i]
            if abs(float(v)) <= self.limit[i]:
                continue
            turns = self.fp(round(float(v) / float(self.two_pi))) * self.two_pi if i in _ANGLES else v
            st[i] = v - turns
            self.value[i] = self.value[i] + turns

    def restore(self, row) -> np.ndarray:
        row = np.array(row)
        for i in _CYCLIC:
            row[i] = row[i] + self.value[i]
        return row


def _propagate(ta, grid, t_end, h_max, prec: Precision):
    """Integrate over fixed segments of 2 pi h_max, rebasing between them.

    Each segment is one ``propagate_grid`` call (heyoka's C++ loop, dense output at the
    grid points inside it), so the Python cost is per segment, not per step; a segment
    holds at least 2 pi steps (h <= h_max) and typically hundreds.  Segment ends depend
    on t_end and the initial rates only, so the steps, and the bits of the result, do
    not depend on the output grid.  Returns (outcome, steps, times, states).
    """
    offsets = _Offsets(prec)
    seg = prec.number(2 * math.pi) * h_max
    times, states, steps, k = [grid[0]], [np.array(ta.state)], 0, 1
    j = 1  # next output grid index
    outcome = hy.taylor_outcome.time_limit
    while True:
        end = prec.number(k) * seg
        if not end < t_end:
            end = t_end
        inside = []
        while j < len(grid) and grid[j] < end:
            inside.append(grid[j])
            j += 1
        res = ta.propagate_grid(prec.array([ta.time] + inside + [end]), max_delta_t=h_max)
        outcome, steps = res[0], steps + int(res[3])
        rows = res[-1][1:]
        for t, row in zip(inside, rows):
            times.append(t)
            states.append(offsets.restore(row))
        if outcome != hy.taylor_outcome.time_limit:  # an event (or a failure) inside the segment
            times.append(ta.time)
            states.append(offsets.restore(ta.state))
            return outcome, steps, times, states
        if j < len(grid) and not grid[j] > end:  # the segment end is itself an output point
            times.append(end)
            states.append(offsets.restore(ta.state))
            j += 1
        if not end < t_end:
            return outcome, steps, times, states
        offsets.rebase(ta.state)
        k += 1


def solve(
    model,
    t_end,
    state=None,
    params=None,
    *,
    precision="double",
    equations: str = "derived",
    tol=None,
    t_eval=None,
    n_eval: int = 101,
    events: bool = True,
    high_accuracy: bool = False,
) -> Trajectory:
    """Integrate ``model`` from ``state`` at time 0 to ``t_end``.

    Parameters
    ----------
    model : str or Model
        A model name (``python -m verify models`` lists them) or a Model object.
    t_end : number or decimal string
        Final time in seconds, > 0.
    state, params : dict, optional
        Initial values by name (unset state components are 0; unset parameters take the
        model's defaults).  Strings are read at ``precision``.
    precision : {"double", "long", "quad", "mp:BITS"}
    equations : {"derived", "paper"}
        The derived equations or the paper's as printed (ignored for a Model object).
    tol : number, optional
        Taylor tolerance; defaults to the precision's epsilon.
    t_eval : sequence, optional
        Output times in [0, t_end], increasing; default ``n_eval`` equally spaced points.
    events : bool
        Stop at the domain's ends and at loss of contact (default True).
    high_accuracy : bool
        heyoka's high-accuracy mode (compensated summation of the Taylor series), for long runs
        where the energy error should follow Brouwer's law (``python -m verify bench`` measures it).

    Raises
    ------
    ValueError
        For bad input (unknown names, non-finite values, out-of-range parameters, states
        outside the domain, non-positive tolerance, unknown precision).
    IntegrationError
        If the integrator fails.
    """
    prec = parse_precision(precision)
    if isinstance(model, str):
        model = get_model(model, equations)
    pars = resolve_parameters(model, params, prec)
    y0 = resolve_state(model, state, prec)
    _check_constraints(model, y0, pars, prec)
    t_end = _parse_positive("t_end", t_end, prec)
    tol_value = prec.zero() if tol is None else _parse_positive("tol", tol, prec)
    grid = _grid(t_end, t_eval, n_eval, prec)

    compiled = compile_model(model, prec)
    values0, normal0 = inv.evaluate(compiled, y0[:, None].copy(), pars)
    if normal0 is not None and not float(normal0[0]) > 0:
        raise ValueError(
            f"the initial state of {model.name!r} has normal force N/(Mg) = {float(normal0[0]):.6g} <= 0: "
            "the body would leave the plane; allowed: states with N > 0"
        )

    ta = hy.taylor_adaptive(
        list(compiled.system), y0, pars=compiled.system_pars(prec.array(pars.values())), tol=tol_value,
        t_events=compiled.t_events() if events else [], high_accuracy=high_accuracy, **prec.integrator_kwargs(),
    )
    outcome, steps, times, states = _propagate(ta, grid, t_end, max_step(y0, pars, prec), prec)
    status, label, message, t_events = _interpret(outcome, compiled, ta)
    t = prec.array(times)
    y = np.ascontiguousarray(np.array(states).T)

    values, normal = inv.evaluate(compiled, y, pars)
    traces = inv.traces(compiled, values, y, pars)
    return Trajectory(
        model=model.name, equations=model.equations, precision=prec, params=pars, t_end=t_end, t=t, y=y,
        status=status, message=message, outcome=label, t_events=t_events, steps=steps, tol=ta.tol,
        invariants=traces, normal_force=normal,
    )


def max_step(y0, pars: dict, prec: Precision):
    """The largest step: one radian of the fastest initial rate (or of sqrt(g)).

    heyoka's step-size rule assumes that Taylor coefficients decay geometrically.  On
    an exactly steady motion (the Eq. 45 spin-down, a steady precession) every
    coefficient of theta and the rates vanishes, phi and psi are linear in t, and only
    x, y keep round-off-sized coefficients that grow like Omega^n/n! before decaying;
    the rule then takes steps with Omega h of tens or hundreds of radians and sums a
    truncated series far outside its range (seen: x = -1.2e4 instead of 0 after 1 s of
    the Eq. 45 state at theta = 0.1 in quad).  Capping Omega h at 1 keeps the truncated
    terms below 1/p!.  On ordinary motions the cap does not bind (typical Omega h ~ 0.03).
    """
    rates = [abs(float(y0[i])) for i in (3, 4, 5)] + [float(pars.get("g", 1)) ** 0.5]
    return prec.number(1) / prec.number(max(rates))


def _grid(t_end, t_eval, n_eval, prec: Precision) -> np.ndarray:
    if t_eval is None:
        if int(n_eval) < 2:
            raise ValueError(f"n_eval={n_eval} must be at least 2")
        n = int(n_eval) - 1
        pts = [t_end * prec.number(i) / prec.number(n) for i in range(n)] + [t_end]
        return prec.array([prec.zero()] + pts[1:])
    pts = [prec.number(v) if not isinstance(v, type(t_end)) else v for v in t_eval]
    for a, b in zip(pts, pts[1:]):
        if not b > a:
            raise ValueError(f"t_eval must be strictly increasing; {b} follows {a}")
    if pts and (pts[0] < 0 or pts[-1] > t_end):
        raise ValueError(f"t_eval must lie in [0, t_end={t_end}]")
    if not pts or pts[0] > 0:
        pts = [prec.zero()] + pts
    return prec.array(pts)


def _interpret(outcome, compiled, ta):
    code = int(outcome)
    names = [name for name, _, _ in compiled.events]
    if outcome == hy.taylor_outcome.time_limit:
        return 0, "ok", "reached t_end", {}
    if -len(names) <= code < 0:
        name = names[-code - 1]
        return 1, f"event:{name}", f"stopped by the terminal event {name} at t = {ta.time}", {name: ta.time}
    raise IntegrationError(
        f"the integration of {compiled.model.name!r} failed at t = {ta.time} with outcome {outcome} "
        f"(state {list(ta.state)})"
    )

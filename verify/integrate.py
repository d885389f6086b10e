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
only through x', y'), so after every step a callback moves them into offsets kept
outside the integrator: phi and psi by whole turns (exact multiples of the precision's
2 pi, so sin and cos of phi are unchanged), x and y entirely.  The returned phi, psi,
x, y are the offsets plus the reduced values: continuous, never reduced modulo 2 pi.
"""
from __future__ import annotations

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
        Energy first, then the model's other conserved quantities.
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


class _Rebaser:
    """Step callback: keep phi, psi, x, y small inside the integrator (module docstring)."""

    def __init__(self, precision: Precision):
        zero = precision.zero()
        self.fp = precision.number
        with mpmath.workprec(precision.bits + 32):
            self.two_pi = precision.number(2 * mpmath.pi)
        self.limit = {1: float(self.two_pi), 2: float(self.two_pi), 6: 1.0, 7: 1.0}
        self.offset = {i: zero for i in _CYCLIC}
        self.change_times = []  # time at the end of the step after which offsets changed
        self.change_offsets = []  # the offsets in effect up to that time

    def __call__(self, ta) -> bool:
        st = ta.state
        if any(abs(float(st[i])) > self.limit[i] for i in _CYCLIC):
            self.change_times.append(ta.time)
            self.change_offsets.append(dict(self.offset))
            for i in _CYCLIC:
                v = st[i]
                if abs(float(v)) <= self.limit[i]:
                    continue
                if i in _ANGLES:
                    turns = self.fp(round(float(v) / float(self.two_pi))) * self.two_pi
                else:
                    turns = v
                st[i] = v - turns
                self.offset[i] = self.offset[i] + turns
        return True

    def offsets_at(self, times) -> list:
        """The offsets in effect at each (sorted) output time."""
        out, p = [], 0
        for t in times:
            while p < len(self.change_times) and self.change_times[p] < t:
                p += 1
            out.append(self.change_offsets[p] if p < len(self.change_times) else self.offset)
        return out


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
        t_events=compiled.t_events() if events else [], **prec.integrator_kwargs(),
    )
    rebaser = _Rebaser(prec)
    res = ta.propagate_grid(grid, callback=rebaser, max_delta_t=max_step(y0, pars, prec))
    outcome, steps, rows = res[0], int(res[3]), res[-1]
    status, label, message, t_events = _interpret(outcome, compiled, ta)

    times = list(grid[: len(rows)])
    states = [np.array(r) for r in rows]
    offsets = rebaser.offsets_at(times)
    if status == 1 and (not times or ta.time != times[-1]):
        times.append(ta.time)
        states.append(np.array(ta.state))
        offsets.append(rebaser.offset)
    for row, off in zip(states, offsets):
        for i in _CYCLIC:
            row[i] = row[i] + off[i]
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

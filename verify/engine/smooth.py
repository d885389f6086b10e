"""A body of revolution under the smooth friction law, integrated by heyoka: the tippe top's engine.

The equations are :mod:`models.smooth_friction`'s (F_h = -mu N u / sqrt(|u|^2 + eps^2), paper Eqs. 5-7;
state: the eight, the slip's components in (e1, h), the work W).  They do not fit a
:class:`models.base.Model`, whose right-hand side is three accelerations and the no-slip velocity of C
(:meth:`models.base.Model.rhs`): the slip is three more states.  Rather than widen the Model and every
place that reads it (the compiler, the validation, the runs, the scorers) this module builds its own small
heyoka system from the sympy rows, as :mod:`verify.engine.hybrid` does for Coulomb's sliding phase, and
reuses the engine's pieces around it: the symbol map and the refusal of double-rounded constants
(:mod:`.compile`), the integrator pool (:mod:`.integrators`), the run in segments with phi and psi moved
back by whole turns (:func:`verify.engine.auxiliary.propagate_in_turns`'s loop), the step cap
(:func:`verify.engine.problem.max_step`), the start's checks against the rolling model
(:mod:`.validation`).

Events (terminal): the domain's ends (a sphere's ``axis_vertical`` at theta = 0 and pi, where the
Euler angles are singular), ``contact_lost`` (N/(Mg) = 0), ``painleve_margin`` (the rows jam; cannot
happen below the body's critical friction, :func:`models.coulomb.critical_friction`), and an optional
``theta_stop`` where theta rises through a given angle.

Checks carried by every run (:class:`SmoothSolution`): E + W against E(0) in units of epsilon times E's
term scale up to each output (:func:`verify.engine.hybrid_guards.balance_drift_in_eps`, the Coulomb runs'
measure), and for a sphere Jellett's lambda = L_C . r_P against lambda(0) in epsilon of its own term scale.
Both are held to the Coulomb runs' bound, 4 eps a step (:func:`~verify.engine.hybrid_guards.balance_bound_in_eps`
with no switch: each step commits at most the tolerance and about as much again in the polynomial's
evaluation, carried by the flow, of which both are invariants); a run beyond it raises
:class:`IntegrationError` ('failed:energy_balance' or 'failed:jellett') with the run up to there.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import heyoka as hy
import numpy as np
import sympy as sp

from models import smooth_friction as sf
from models.base import Model
from models.coulomb import mu as MU
from models.symbols import phi

from . import heyoka_log, integrators
from .auxiliary import _in_turns
from .compile import symbol_map, to_heyoka
from .hybrid_guards import balance_bound_in_eps, balance_drift_in_eps
from .problem import max_step
from .trajectory import IntegrationError
from .validation import InvalidStart, first_problem, parameters as resolve_parameters, positive_number
from .validation import state as resolve_state
from ..precision import Precision, parse_precision

JAM_EVENT = "painleve_margin"
THETA_STOP = "theta_stop"
_SLIP1, _SLIP2, _WORK = 8, 9, 10


@dataclass(frozen=True)
class SmoothSolution:
    """A smooth-law run, shaped like the engine's other records.

    Attributes
    ----------
    t : ndarray (n,)
        Output times reached (plus the time of a terminal event that stopped the run).
    y : ndarray (11, n)
        :data:`models.smooth_friction.STATE_NAMES`: the eight (phi, psi continuous), slip_e1, slip_h, work.
    energy, work, normal_force, height, jellett : ndarray (n,)
        E per unit mass, W (the state's ``work`` is W / g), N/(Mg), z_C, and Jellett's lambda (None for a body that is not a sphere).
    energy_plus_work_drift_in_eps : float
        max over the outputs of |E + W - E(0)| / (eps E's term scale up to that output).
    jellett_drift_in_eps : float or None
        max |lambda - lambda(0)| / (eps lambda's term scale up to that output).
    outcome : str
        ``"ok"`` (t_end reached) or ``"event:<name>"``.
    """

    model: str
    precision: Precision
    params: dict
    t: np.ndarray
    y: np.ndarray
    energy: np.ndarray
    work: np.ndarray
    normal_force: np.ndarray
    height: np.ndarray
    jellett: np.ndarray | None
    energy_plus_work_drift_in_eps: float
    jellett_drift_in_eps: float | None
    outcome: str
    steps: int
    message: str = ""
    extra: dict = field(default_factory=dict)

    def __getitem__(self, name):
        return self.y[sf.STATE_NAMES.index(name)]

    @property
    def slip_speed(self) -> np.ndarray:
        return np.hypot(self.y[_SLIP1].astype(float), self.y[_SLIP2].astype(float))

    def __repr__(self) -> str:
        return (f"SmoothSolution(model={self.model!r}, precision={self.precision.name!r}, outcome={self.outcome!r}, "
                f"t = 0 to {float(self.t[-1]):g} s, {len(self.t)} outputs, steps={self.steps}, "
                f"E+W within {self.energy_plus_work_drift_in_eps:.3g} eps)")


@dataclass(frozen=True)
class _Compiled:
    rolling: Model
    precision: Precision
    system: tuple
    events: tuple  # (name, expression, direction)
    outputs: object  # cfunc: 11 states -> [E, N/(Mg), z_C, lambda?, E's terms..., lambda's terms...]
    n_energy_terms: int
    n_jellett_terms: int
    contact_velocity: object  # cfunc: 8 states -> (c1, c2), omega x r_P along (e1, h)
    n_pars: int


def _jellett(rolling: Model):
    for inv in rolling.invariants:
        if inv.name == "jellett":
            return inv.expr
    return None


def _terms(expr):
    return sp.Add.make_args(sp.expand(expr))


@lru_cache(maxsize=None)
def compiled(body, precision: Precision) -> _Compiled:
    """The smooth-law system of ``body`` (a shipped body's name or a :class:`models.bodies.Body`) at
    ``precision``: ``par[i]`` the rolling model's parameters, then mu, eps, then theta_stop."""
    if isinstance(body, str):
        rolling, sm, params = sf.body(body)
    else:
        rolling, sm, params = sf.body_model(body)
    variables = tuple(hy.make_vars(*sf.STATE_NAMES))
    mapping = symbol_map(rolling, variables[:8])
    n = len(rolling.parameters)
    mapping.update({sf.slip_e1: variables[_SLIP1], sf.slip_h: variables[_SLIP2], sf.work: variables[_WORK],
                    MU: hy.par[n], sf.eps: hy.par[n + 1]})
    system = tuple((v, to_heyoka(rhs, mapping, compact=True)) for v, rhs in zip(variables, sm.rhs))
    theta = variables[0]
    dom = rolling.domain
    events = (
        (dom.below, theta - to_heyoka(dom.theta_min, mapping, compact=True), hy.event_direction.negative),
        (dom.above, theta - to_heyoka(dom.theta_max, mapping, compact=True), hy.event_direction.positive),
        ("contact_lost", to_heyoka(sm.normal_force, mapping, compact=True), hy.event_direction.negative),
        (JAM_EVENT, to_heyoka(sm.painleve_margin, mapping, compact=True), hy.event_direction.negative),
        (THETA_STOP, theta - hy.par[n + 2], hy.event_direction.positive),
    )
    jellett = _jellett(rolling)
    e_terms = _terms(sm.energy)
    j_terms = _terms(jellett) if jellett is not None else ()
    outs = [sm.energy, sm.normal_force, sm.height] + ([jellett] if jellett is not None else []) + list(e_terms) + list(j_terms)
    kw = precision.integrator_kwargs()
    outputs = hy.cfunc([to_heyoka(e, mapping) for e in outs], list(variables), **kw)
    c = [-e.subs({sf.slip_e1: 0, sf.slip_h: 0}) for e in _nodal_velocity(sm)]
    contact_velocity = hy.cfunc([to_heyoka(e, mapping) for e in c], list(variables[:8]), **kw)
    return _Compiled(rolling, precision, system, events, outputs, len(e_terms), len(j_terms), contact_velocity, n + 3)


def _nodal_velocity(sm):
    """C's horizontal velocity along (e1, h), read back from (x', y'): (v1, v2) = R(-phi) (x', y')."""
    xdot, ydot = sm.cm_velocity_xy
    return (sp.simplify(xdot * sp.cos(phi) + ydot * sp.sin(phi)), sp.simplify(-xdot * sp.sin(phi) + ydot * sp.cos(phi)))


def _build(c: _Compiled):
    prec = c.precision
    events = [hy.t_event(ex, direction=d, fp_type=prec.fp_type) for _, ex, d in c.events]
    # compact mode at every precision: the sphere's rows are ~3000 operations (the hybrid's choice, HEYOKA.md)
    kw = {**prec.integrator_kwargs(), "compact_mode": True}
    return hy.taylor_adaptive(list(c.system), prec.array([0] * len(c.system)), pars=prec.array([0] * c.n_pars),
                              tol=prec.zero(), t_events=events, **kw)


def _evaluate(function, states: np.ndarray, pars: np.ndarray) -> np.ndarray:
    pars = pars[: function.nparams]
    if states.ndim == 2:
        pars = np.repeat(pars[:, None], states.shape[1], axis=1)
    return function(np.ascontiguousarray(states), pars=np.ascontiguousarray(pars))


def start_slip(c: _Compiled, y8, velocity, par_vector, prec: Precision):
    """(slip_e1, slip_h) of a start whose C moves horizontally at ``velocity`` (inertial (v_x, v_y));
    None: the no-slip velocity (u = 0)."""
    if velocity is None:
        return prec.zero(), prec.zero()
    vx, vy = (prec.number(v) for v in velocity)
    phi = y8[1]
    cos, sin = (np.cos(phi), np.sin(phi)) if prec.name in ("double", "long") else (hy.cos(phi), hy.sin(phi))
    c1, c2 = _evaluate(c.contact_velocity, np.asarray(y8), par_vector)
    return vx * cos + vy * sin + c1, -vx * sin + vy * cos + c2


def solve(body, t_end, state=None, params=None, *, friction, slip_scale, velocity=None, precision="double",
          n_eval: int = 101, t_eval=None, theta_stop=None) -> SmoothSolution:
    """Integrate ``body`` under the smooth friction law from time 0 to ``t_end``.

    Parameters
    ----------
    body : str or models.bodies.Body
        A shipped body file (``"tippe-top"`` or ``"body:tippe-top"``) or a loaded body.
    t_end : number or decimal string, > 0
    state : mapping or sequence
        The eight components as for :func:`verify.engine.single.solve` (theta in the body's domain).
    params : mapping, optional
        The rolling model's parameters (a sphere: I1, I3, centre_height, g).
    friction, slip_scale : number or decimal string
        mu >= 0 and eps > 0 of F_h = -mu N u / sqrt(|u|^2 + eps^2).
    velocity : pair, optional
        C's horizontal velocity (v_x, v_y) at t = 0; None: the no-slip velocity (u = 0 at the start).
    precision : {"double", "long", "quad", "mp:BITS"}
    n_eval, t_eval
        Equally spaced output times, or the output times themselves (from 0 to t_end).
    theta_stop : number or decimal string, optional
        End the run (outcome ``event:theta_stop``) where theta rises through this angle.

    Raises
    ------
    ValueError
        Bad input; :class:`~verify.engine.validation.InvalidStart` for a start outside the domain.
    IntegrationError
        heyoka failed (a non-finite state).
    """
    prec = parse_precision(precision)
    c = compiled(body if not isinstance(body, str) else body.removeprefix("body:"), prec)
    rolling = c.rolling
    t_end = positive_number("t_end", t_end, prec)
    mu = _number("friction", friction, prec, "the friction coefficient mu >= 0", lambda v: v >= 0)
    eps = _number("slip_scale", slip_scale, prec, "the slip scale eps > 0", lambda v: v > 0)
    stop = prec.number(10) if theta_stop is None else _number("theta_stop", theta_stop, prec, "an angle",
                                                              lambda v: math.isfinite(v))
    pars = resolve_parameters(rolling, params, prec)
    y0 = resolve_state(rolling, state, prec)
    problem = first_problem(rolling, y0[:, None], None, [dict(state)] if isinstance(state, dict) else None)
    if problem is not None:
        raise InvalidStart(problem[2], problem[1])
    par_vector = prec.array([pars[p.name] for p in rolling.parameters] + [mu, eps, stop])
    u1, u2 = start_slip(c, y0, velocity, par_vector, prec)
    start = prec.array(list(y0) + [u1, u2, prec.zero()])
    normal0 = float(_evaluate(c.outputs, start, par_vector)[1])
    if not normal0 > 0:
        raise InvalidStart(f"N/(Mg) = {normal0:.6g} <= 0 at the start: the body leaves the plane", "contact_lost")
    grid = _grid(t_end, n_eval, t_eval, prec)
    key = ("smooth", body if not isinstance(body, str) else body.removeprefix("body:"), prec)
    names = [name for name, _, _ in c.events]
    with integrators.borrowed(key, lambda: _build(c), prec.zero(), start, par_vector) as ta:
        with heyoka_log.collect():
            outcome, steps, times, rows = _in_turns(ta, grid[1:], max_step(y0, pars, prec), prec, 32 * math.pi)
    if outcome == hy.taylor_outcome.time_limit:
        label = "ok"
    elif -len(names) <= int(outcome) < 0:
        label = f"event:{names[-int(outcome) - 1]}"
    else:
        raise IntegrationError(f"the smooth-law run of {rolling.name!r} failed at t = {times[-1]} with outcome "
                               f"{outcome}", "failed:" + str(outcome).rsplit(".", 1)[-1], times[-1], rows[-1])
    y = np.ascontiguousarray(np.array(rows).T)
    return _record(c, prec, {**pars, "mu": mu, "eps": eps}, par_vector, prec.array(times), y, label, steps)


def _record(c: _Compiled, prec, pars, par_vector, t, y, label, steps) -> SmoothSolution:
    out = _evaluate(c.outputs, y, par_vector)
    has_j = c.n_jellett_terms > 0
    first = 4 if has_j else 3
    energy, normal, height = out[0], out[1], out[2]
    work = y[_WORK] * pars["g"]  # the state holds W / g (models.smooth_friction)
    e_scale = np.sum(np.abs(out[first:first + c.n_energy_terms]), axis=0)
    drift = balance_drift_in_eps(energy, work, e_scale, prec.eps)
    jellett = j_drift = None
    if has_j:
        jellett = out[3]
        j_scale = np.sum(np.abs(out[first + c.n_energy_terms:]), axis=0)
        j_drift = float(np.max(balance_drift_in_eps(jellett, [prec.zero()] * len(t), j_scale, prec.eps)))
    sol = SmoothSolution(c.rolling.name, prec, pars, t, y, energy, work, normal, height, jellett,
                         float(np.max(drift)), j_drift, label, steps,
                         message="t_end reached" if label == "ok" else f"stopped at {label}")
    bound = balance_bound_in_eps(steps, 0)
    for what, value, outcome in (("E + W", sol.energy_plus_work_drift_in_eps, "failed:energy_balance"),
                                 ("Jellett's integral", j_drift, "failed:jellett")):
        if value is not None and not value <= bound:  # NaN fails too
            raise IntegrationError(f"the smooth-law run of {c.rolling.name!r} broke its own guard: {what} drifted "
                                   f"{value:.3g} eps of its term scale, more than the {bound:g} eps its {steps} steps "
                                   "allow; the run is not reliable", outcome, t[-1], y[:, -1], trajectory=sol)
    return sol


def _number(what, value, prec, allowed, ok):
    try:
        v = prec.number(value)
    except (ValueError, TypeError) as err:
        raise ValueError(f"{what}={value!r}: {err}; allowed: {allowed}") from None
    if not ok(float(v)):
        raise ValueError(f"{what}={value!r}; allowed: {allowed}")
    return v


def _grid(t_end, n_eval, t_eval, prec):
    if t_eval is not None:
        grid = [prec.number(v) for v in t_eval]
        if len(grid) < 2 or grid[0] != 0 or grid[-1] != t_end or any(not b > a for a, b in zip(grid, grid[1:])):
            raise ValueError(f"t_eval must increase from 0 to t_end = {float(t_end):.9g} (at least 2 times)")
        return grid
    n = int(n_eval) - 1
    if n < 1:
        raise ValueError(f"n_eval={n_eval} must be at least 2")
    return [prec.zero()] + [t_end * prec.number(i) / prec.number(n) for i in range(1, n)] + [t_end]


__all__ = ["SmoothSolution", "compiled", "solve", "start_slip"]

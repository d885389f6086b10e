"""Rolling and sliding with Coulomb friction, event-driven: ``disk+coulomb``, ``ring+coulomb``.

A run is a sequence of phases, each integrated by heyoka's Taylor method at the run's precision:

* **rolling**: the rolling model (``disk``, ``ring``; paper Eqs. 5-8) run by the engine,
  :func:`verify.engine.single.solve` with ``friction=mu``, whose terminal event ``slips`` fires
  where the required friction mu_req = |F_h| / N reaches mu;
* **sliding**: the equations of :mod:`models.coulomb` (F_h = -mu N u/|u|, slip speed and
  direction as state, the work W = int mu N s dt as a quadrature), integrated here with the
  terminal event ``sticks`` on the slip speed s (direction negative: Coulomb friction brings s to
  zero at a finite rate, so s changes sign there and heyoka locates the root to epsilon).

Switches and their maps:

* launch: a start with a centre-of-mass velocity ``velocity`` slides if the contact's slip
  u = v_C + omega x r_P is not zero (s = |u|, alpha = atan2(u_y, u_x)); without ``velocity``,
  or with u = 0 exactly, it rolls (v_C is then the rolling model's ``velocity_xy``);
* sliding -> rolling at ``sticks`` (s = 0): the eight components are handed over as they are
  (at s = 0 the CM velocity of the sliding state *is* the no-slip velocity), the slip state is
  dropped, W is kept.  If the rolling equations there need mu_req > mu the slip would go on
  from s = 0 in the direction of -F_req: that is the onset below;
* rolling -> sliding at ``slips``: the exact map is s = 0, alpha the direction of -F_req (with
  |F_req| = mu N the only consistent choice, since the contact's response to a horizontal force
  is invertible).  **Not integrated**: from s = 0 the direction equation
  d(alpha)/dt = (e_perp . du/dt)/s is 0/0 (s grows like t^2), heyoka cannot take a first step,
  and near the onset the direction dynamics is stiff (it relaxes at a rate ~ mu N / s).  A run
  that reaches it raises :class:`UnsupportedTransition` naming the time, with the run up to there.

Error budget: each phase's Taylor integration at tolerance epsilon; each switch time located by
heyoka's event root finding to a few epsilon of t; the maps are exact (no rounding but the
handing over of the same numbers).  E + W is checked over the whole run (:attr:`HybridSolution.
energy_plus_work_drift_in_eps`).  The sliding phases are not cut into segments with phi, psi moved
out (as :mod:`verify.engine.segments` does for long rolling runs): a sliding phase lasts until
the slip dies out, a fraction of a second at the rates the suite uses; its steps are capped at one
radian of the fastest initial rate as every run's are (:func:`verify.engine.problem.max_step`).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import numpy as np
import sympy as sp

from models import coulomb
from models.symbols import STATE_NAMES

from . import heyoka_log
from .compile import friction_function, symbol_map, to_heyoka
from .problem import max_step
from .single import solve as solve_rolling
from .trajectory import IntegrationError
from .validation import InvalidStart, parameters as resolve_parameters, state as resolve_state
from ..precision import Precision, parse_precision

#: Sliding-phase state (models.coulomb): the eight, the slip speed and direction, the work.
SLIDING_STATE_NAMES = coulomb.SLIDING_STATE_NAMES
_SLIP, _DIRECTION, _WORK = 8, 9, 10


class UnsupportedTransition(IntegrationError):
    """The run reached a switch this driver does not integrate (the onset of slip from s = 0)."""


@dataclass(frozen=True)
class Phase:
    """One phase of a run: ``kind`` 'rolling' or 'sliding', its times and how it ended
    ('ok' at t_end, 'sticks', 'slips', or the rolling model's events: 'event:lies_flat', ...)."""

    kind: str
    t_start: object
    t_end: object
    ended: str


@dataclass(frozen=True)
class HybridSolution:
    """A run of a body that rolls or slides, shaped like scipy's ``solve_ivp`` result.

    Attributes
    ----------
    t : ndarray (n,)
        Output times: the grid points of every phase, and every switch time (once per phase it
        ends or starts, so a switch time appears twice: the end of one phase, the start of the next).
    y : ndarray (8, n)
        The eight components of ``STATE_NAMES``.
    slip_speed, slip_direction : ndarray (n,)
        s = |u| and alpha (inertial) where sliding; 0 and NaN where rolling.
    phase_index : ndarray (n,)
        The index in ``phases`` each output belongs to.
    energy, work : ndarray (n,)
        E per m R^2, and W = int mu N s dt (constant in rolling phases).
    energy_scale : float
        The largest term scale of E on the run (sum of the absolute values of its terms).
    energy_plus_work_drift_in_eps : float
        max |E + W - E(0)| / (energy_scale eps): the energy balance at the precision.
    switch_times : tuple
        Times where a phase ended and the next began.
    outcome, status, message
        'ok' (status 0) or the last phase's terminal event (status 1).
    """

    model: str
    precision: Precision
    params: dict
    t: np.ndarray
    y: np.ndarray
    slip_speed: np.ndarray
    slip_direction: np.ndarray
    phase_index: np.ndarray
    phases: tuple
    energy: np.ndarray
    work: np.ndarray
    energy_scale: float
    energy_plus_work_drift_in_eps: float
    switch_times: tuple
    outcome: str
    status: int
    message: str
    rolling_runs: tuple  # the engine's Trajectory of each rolling phase

    def __getitem__(self, name):
        return self.y[STATE_NAMES.index(name)]


@dataclass(frozen=True)
class _Compiled:
    precision: Precision
    system: tuple
    events: tuple  # (name, expression, direction)
    sliding_function: object  # cfunc: 11 states -> [E, N/(Mg), E's terms...]
    rolling_function: object  # cfunc: 8 states -> [E, N/(Mg), F_x/(Mg), F_y/(Mg), E's terms...]
    launch_function: object  # cfunc: 8 states + (vx, vy) -> [s, alpha]
    rhs_function: object  # cfunc: 11 states -> their time derivatives
    n_pars: int


@lru_cache(maxsize=None)
def compiled(name: str, precision: Precision) -> _Compiled:
    """The sliding system of ``name`` and its functions at ``precision`` (parameters: the rolling
    model's as ``par[i]``, then mu)."""
    rolling, sliding, params = coulomb.body(name)
    variables = tuple(hy.make_vars(*SLIDING_STATE_NAMES))
    mapping = symbol_map(rolling, variables[:8])
    mapping.update({coulomb.slip_speed: variables[_SLIP], coulomb.slip_direction: variables[_DIRECTION],
                    coulomb.work: variables[_WORK], coulomb.mu: hy.par[len(rolling.parameters)]})
    system = tuple((v, to_heyoka(rhs, mapping)) for v, rhs in zip(variables, sliding.rhs))
    theta = variables[0]
    dom = rolling.domain
    events = (
        ("sticks", variables[_SLIP], hy.event_direction.negative),
        (dom.below, theta - to_heyoka(dom.theta_min, mapping), hy.event_direction.negative),
        (dom.above, theta - to_heyoka(dom.theta_max, mapping), hy.event_direction.positive),
        ("contact_lost", to_heyoka(sliding.normal_force, mapping), hy.event_direction.negative),
    )
    kw = precision.integrator_kwargs()
    sliding_function = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.energy, sliding.normal_force,
                                                                 *_terms(sliding.energy))], list(variables), **kw)
    energy = rolling.energy
    force = rolling.horizontal_force
    rolling_function = hy.cfunc([to_heyoka(e, mapping) for e in (energy, rolling.normal_force, *force,
                                                                 *_terms(energy))], list(variables[:8]), **kw)
    vx, vy = hy.make_vars("vx", "vy")
    cm_x, cm_y = (to_heyoka(e.subs(coulomb.slip_speed, 0), mapping) for e in sliding.cm_velocity_xy)
    ux, uy = vx - cm_x, vy - cm_y  # u = v_C + omega x r_P, and omega x r_P = -(v_C at s = 0)
    launch_function = hy.cfunc([hy.sqrt(ux * ux + uy * uy), hy.atan2(uy, ux)], list(variables[:8]) + [vx, vy], **kw)
    rhs_function = hy.cfunc([rhs for _, rhs in system], list(variables), **kw)
    return _Compiled(precision, system, events, sliding_function, rolling_function, launch_function, rhs_function,
                     len(rolling.parameters) + 1)


def _terms(expr):
    """The terms of ``expr`` expanded: the sum of their absolute values is the scale its drift is judged by
    (as :func:`models.build.additive_scale`, evaluated term by term: heyoka has no Abs)."""
    return sp.Add.make_args(sp.expand(expr))


def _term_scale(values, first):
    return sum(abs(v) for v in values[first:])


def _evaluate(function, states: np.ndarray, pars: np.ndarray) -> np.ndarray:
    states = np.ascontiguousarray(states)
    pars = pars[: function.nparams]
    if states.ndim == 2:  # one column per state: the parameters once per column
        pars = np.repeat(pars[:, None], states.shape[1], axis=1)
    return function(states, pars=np.ascontiguousarray(pars))


@lru_cache(maxsize=None)
def _sliding_template(name: str, precision: Precision):
    c = compiled(name, precision)
    events = [hy.t_event(ex, direction=d, fp_type=precision.fp_type) for _, ex, d in c.events]
    # compact mode at every precision: the ring's sliding rows are ~3500 operations, whose full JIT in
    # double took 490 s (measured once, cold cache); compact mode costs ~1.6x per step (HEYOKA.md)
    kw = {**precision.integrator_kwargs(), "compact_mode": True}
    return hy.taylor_adaptive(list(c.system), precision.array([0] * len(c.system)),
                              pars=precision.array([0] * c.n_pars), tol=precision.zero(), t_events=events, **kw)


def solve(
    name: str,
    t_end,
    state=None,
    params=None,
    *,
    friction,
    velocity=None,
    precision="double",
    n_eval: int = 101,
) -> HybridSolution:
    """Integrate ``disk+coulomb`` or ``ring+coulomb`` from time 0 to ``t_end``.

    Parameters
    ----------
    name : {"disk+coulomb", "ring+coulomb"}
    t_end : number or decimal string, > 0
    state : mapping or sequence
        The eight components as for :func:`verify.engine.single.solve`.
    params : mapping, optional
        The rolling model's parameters (``disk``: k, g; ``ring``: I1, I3, h, g).
    friction : number or decimal string >= 0
        The Coulomb coefficient mu (static = kinetic).
    velocity : pair, optional
        The centre of mass's horizontal velocity (v_x, v_y) at t = 0; None: rolling (no slip).
    precision : {"double", "long", "quad", "mp:BITS"}
    n_eval : int
        Equally spaced output times from 0 to t_end (plus the switch times).

    Raises
    ------
    ValueError
        Bad input; :class:`~verify.engine.validation.InvalidStart` for a start outside the domain
        or with N <= 0.
    UnsupportedTransition
        The run reached the onset of slip from s = 0 (from rolling, or at a stick where rolling
        needs mu_req > mu); ``t`` is its time, ``trajectory`` the :class:`HybridSolution` up to it.
    IntegrationError
        A sliding phase failed (non-finite state, event detection).
    """
    prec = parse_precision(precision)
    rolling, sliding, all_params = coulomb.body(name)
    t_end = prec.number(t_end)
    if not float(t_end) > 0:
        raise ValueError(f"t_end={t_end} must be > 0")
    mu = prec.number(friction)
    if not float(mu) >= 0:
        raise ValueError(f"friction={friction!r} must be >= 0 (the Coulomb coefficient)")
    pars = resolve_parameters(rolling, params, prec)
    y0 = resolve_state(rolling, state, prec)
    c = compiled(name, prec)
    par_vector = prec.array([pars[p.name] for p in rolling.parameters] + [mu])
    n = int(n_eval) - 1
    if n < 1:
        raise ValueError(f"n_eval={n_eval} must be at least 2")
    grid = [t_end * prec.number(i) / prec.number(n) for i in range(n)] + [t_end]

    run = _Run(name, prec, c, pars, par_vector, mu, grid, t_end)
    if velocity is None:
        run.rolling(prec.zero(), y0)
    else:
        s, alpha = launch_slip(c, y0, [prec.number(v) for v in velocity], par_vector)
        if s == 0:
            run.rolling(prec.zero(), y0)
        else:
            run.sliding(prec.zero(), prec.array(list(y0) + [s, alpha, prec.zero()]))
    return run.result()


class _CollapseWatch:
    """propagate_grid's callback: stop when a step falls below 16 eps max(|t|, cap).

    Where a sliding phase ends the direction equation alpha' = (e_perp . du/dt) / s relaxes at a rate
    ~ mu N / s, which grows without bound as s -> 0: heyoka's steps then shrink in proportion to the
    time left to the stick (measured: by 0.6 a step) and never cross it.  Below 16 eps max(|t|, cap)
    the time left is a few ulps of t, and :meth:`_Run._finish_stick` takes it in one step.
    """

    def __init__(self, prec: Precision, cap):
        self.eps, self.cap = prec.eps, float(cap)
        self.last = None

    def __call__(self, ta) -> bool:
        t = ta.time
        stop = self.last is not None and abs(float(t - self.last)) < 16 * self.eps * max(abs(float(t)), self.cap)
        self.last = t  # at the run's precision: a difference of doubles would vanish long before a quad step
        return not stop


def launch_slip(c: _Compiled, y0, velocity, par_vector):
    """(s, alpha) of a start with CM velocity ``velocity``: u = v_C + omega x r_P (the launch map)."""
    return tuple(_evaluate(c.launch_function, c.precision.array(list(y0) + list(velocity)), par_vector))


class _Run:
    """The phases of one run, integrated in turn (see the module docstring)."""

    def __init__(self, name, prec, c, pars, par_vector, mu, grid, t_end):
        self.name, self.prec, self.c, self.pars, self.par_vector, self.mu = name, prec, c, pars, par_vector, mu
        self.grid, self.t_end = grid, t_end
        self.t, self.y, self.slip, self.direction, self.index, self.energy, self.work, self.scale = ([] for _ in range(8))
        self.phases, self.rolling_runs = [], []
        self.outcome, self.message = "ok", "t_end reached"
        self.work_so_far = prec.zero()

    def _grid_after(self, t0):
        return [g for g in self.grid if g > t0]

    def _record(self, kind, times, states, energy, scale, slip, direction, work):
        k = len(self.phases) - 1
        self.t += list(times)
        self.y += [np.asarray(s[:8]) for s in states]
        self.energy += list(energy)
        self.scale += list(scale)
        self.slip += list(slip)
        self.direction += list(direction)
        self.work += list(work)
        self.index += [k] * len(times)

    # --- sliding ---------------------------------------------------------------------------------
    def sliding(self, t0, y0):
        prec, c = self.prec, self.c
        ta = _copy(_sliding_template(self.name, prec))
        ta.time = t0
        ta.state[:] = y0
        ta.state[_WORK] = self.work_so_far
        ta.pars[:] = self.par_vector
        ta.reset_cooldowns()
        self.phases.append(Phase("sliding", t0, None, "running"))
        grid = prec.array([t0] + self._grid_after(t0))
        cap = max_step(y0[:8], self.pars, prec)
        collapse = _CollapseWatch(prec, cap)
        with heyoka_log.collect() as messages:
            result = ta.propagate_grid(grid, max_delta_t=cap, callback=collapse)
        outcome, out = result[0], np.asarray(result[-1])
        times = list(grid[: len(out)])
        states = [np.array(r) for r in out]
        if outcome == hy.taylor_outcome.time_limit:
            ended = "ok"
        elif outcome == hy.taylor_outcome.cb_stop:
            ended = "sticks"
            t_stick, y_stick = self._finish_stick(ta)
            times.append(t_stick)
            states.append(y_stick)
        elif 0 <= -int(outcome) - 1 < len(c.events):  # terminal event i ends with outcome -i - 1
            ended = c.events[-int(outcome) - 1][0]
            times.append(ta.time)
            states.append(np.array(ta.state))
        else:
            label = "failed:non_finite" if outcome == hy.taylor_outcome.err_nf_state else "failed:sliding"
            raise IntegrationError(f"sliding phase of {self.name} stopped at t = {ta.time}: heyoka outcome {outcome}"
                                   + (f" ({'; '.join(messages)})" if messages else ""), label, ta.time,
                                   list(ta.state), self.result())
        if messages:
            raise IntegrationError(f"sliding phase of {self.name}: heyoka warned: {'; '.join(messages)}",
                                   "failed:event_detection", ta.time, list(ta.state), None)
        values = _evaluate(c.sliding_function, prec.array(np.concatenate(states)).reshape(len(states), -1).T,
                           self.par_vector)
        if not all(np.isfinite(np.asarray(s, dtype=float)).all() for s in states):
            raise IntegrationError(f"sliding phase of {self.name}: non-finite state by t = {ta.time}",
                                   "failed:non_finite", ta.time, list(ta.state), None)
        self._record("sliding", times, states, values[0], _term_scale(values, 2), [s[_SLIP] for s in states],
                     [s[_DIRECTION] for s in states], [s[_WORK] for s in states])
        t1 = times[-1]
        self.phases[-1] = Phase("sliding", t0, t1, ended)
        self.work_so_far = states[-1][_WORK]
        if ended == "sticks":
            y8 = prec.array(list(states[-1][:8]))
            return self._after_stick(t1, y8)
        if ended != "ok":
            self.outcome, self.message = f"event:{ended}", f"the sliding phase ended at {ended}"

    def _finish_stick(self, ta):
        """The last ulps before a stick whose steps collapsed (:class:`_CollapseWatch`): one Euler step.

        There s falls at a finite rate s' < 0 and the remaining time is tau = -s / s', a few ulps of t;
        the state moves by tau y' (error tau^2 |y''| / 2, far below eps: tau |y'| is itself about the
        rounding of y).  alpha is dropped at the stick and the work gains mu N s tau.
        """
        prec, y = self.prec, np.array(ta.state)
        rate = _evaluate(self.c.rhs_function, y, self.par_vector)
        if not rate[_SLIP] < 0:
            raise IntegrationError(f"sliding phase of {self.name}: the steps collapsed at t = {ta.time} with the slip "
                                   f"speed {y[_SLIP]} not falling", "failed:step_size_collapse", ta.time, list(y),
                                   self.result())
        tau = -y[_SLIP] / rate[_SLIP]
        y_stick = y + tau * rate
        y_stick[_SLIP] = prec.zero()
        return ta.time + tau, y_stick

    def _after_stick(self, t, y8):
        """Sliding -> rolling at s = 0: the eight components as they are, if rolling holds there."""
        normal, mu_req = (float(v) for v in _evaluate(friction_function(_rolling(self.name), self.prec).function, y8,
                                                       self.par_vector[:-1]))
        if not mu_req <= float(self.mu):
            raise self._unsupported(t, f"the slip stops at t = {t} but rolling there needs mu_req = {mu_req:.6g} > "
                                       f"mu = {float(self.mu):.6g}: the slip restarts from s = 0, not integrated")
        return self.rolling(t, y8)

    # --- rolling ---------------------------------------------------------------------------------
    def rolling(self, t0, y8):
        prec = self.prec
        rolling = _rolling(self.name)
        after = self._grid_after(t0)
        relative = [g - t0 for g in after]
        self.phases.append(Phase("rolling", t0, None, "running"))
        try:
            sol = solve_rolling(rolling, self.t_end - t0, y8, self.pars, precision=prec,
                                t_eval=[prec.zero()] + [r for r in relative if r > 0], friction=self.mu)
        except InvalidStart as err:
            if err.reason == "slips":
                raise self._unsupported(t0, f"rolling from t = {t0} needs more friction than mu: {err}") from None
            raise
        self.rolling_runs.append(sol)
        states = [np.array(sol.y[:, j]) for j in range(sol.y.shape[1])]
        times = [t0 + tau for tau in sol.t]
        values = _evaluate(self.c.rolling_function, np.ascontiguousarray(sol.y), self.par_vector[:-1])
        nan = np.longdouble("nan") if prec.name == "long" else float("nan")
        self._record("rolling", times, states, values[0], _term_scale(values, 4), [prec.zero()] * len(times),
                     [nan] * len(times), [self.work_so_far] * len(times))
        ended = "ok" if sol.status == 0 else (sol.outcome[6:] if sol.outcome.startswith("event:") else sol.outcome)
        self.phases[-1] = Phase("rolling", t0, times[-1], ended)
        if ended == "slips":
            y_slip = np.ascontiguousarray(sol.y[:, -1])
            raise self._unsupported(times[-1], f"the contact slips at t = {times[-1]} (mu_req reached mu = "
                                               f"{float(self.mu):.6g}): the onset of sliding from s = 0 is not "
                                               f"integrated; slip direction there: {self.slip_direction(y_slip)}")
        if ended != "ok":
            self.outcome, self.message = f"event:{ended}", sol.message

    def slip_direction(self, y8):
        """alpha of the slip at an onset: the direction of -F_req (module docstring)."""
        values = _evaluate(self.c.rolling_function, y8, self.par_vector[:-1])
        return float(np.arctan2(-float(values[3]), -float(values[2])))

    def _unsupported(self, t, message):
        self.outcome, self.message = "unsupported:slip_onset", message
        return UnsupportedTransition(message, "unsupported:slip_onset", t, None, self.result())

    # --- the record ------------------------------------------------------------------------------
    def result(self) -> HybridSolution:
        prec = self.prec
        y = np.array(self.y).T if self.y else np.zeros((8, 0))
        energy, work = np.array(self.energy), np.array(self.work)
        scale = max(float(s) for s in self.scale) if self.scale else float("nan")
        balance = energy + work
        drift = max(abs(float(b - balance[0])) for b in balance) / (scale * prec.eps) if len(balance) else float("nan")
        switches = tuple(p.t_end for p in self.phases[:-1])
        status = 0 if self.outcome == "ok" else 1
        return HybridSolution(
            model=self.name, precision=prec, params={**self.pars, "mu": self.mu}, t=np.array(self.t), y=y,
            slip_speed=np.array(self.slip), slip_direction=np.array(self.direction, dtype=_dtype(prec)),
            phase_index=np.array(self.index), phases=tuple(self.phases), energy=energy, work=work,
            energy_scale=scale, energy_plus_work_drift_in_eps=drift, switch_times=switches,
            outcome=self.outcome, status=status, message=self.message, rolling_runs=tuple(self.rolling_runs),
        )


def _dtype(prec: Precision):
    return {"double": float, "long": np.longdouble}.get(prec.name, object)


def _rolling(name):
    from models import get_model

    return get_model(coulomb.ROLLING[name])


def _copy(ta):
    import copy

    return copy.copy(ta)


def sliding_expressions(name: str) -> dict:
    """The sliding phase's right-hand sides by state name (sympy), for inspection and tests."""
    _, sliding, _ = coulomb.body(name)
    return {n: sp.sympify(e) for n, e in zip(SLIDING_STATE_NAMES, sliding.rhs)}

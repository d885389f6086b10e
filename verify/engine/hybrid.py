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
* sliding from s = 0 where rolling needs mu_req > mu (a start, or a stick where rolling cannot
  hold): the slip starts at a finite rate lambda in the one direction alpha0 along which it then
  accelerates (:func:`onset_directions`); d(alpha)/dt = (e_perp . du/dt)/s is 0/0 there, a regular
  singular point whose one regular solution is started by a second-order Taylor polynomial over
  2^-ceil(bits/3) of the step cap (:meth:`_Run.onset`), then heyoka takes over;
* rolling -> sliding at ``slips`` (mu_req reaches mu exactly): s = 0, alpha0 the direction of -F_req,
  but there lambda = 0: s grows like sigma t^2 / 2 and d(alpha)/dt = B/s has an irregular singular point
  (deviations from the slow solution die like exp(-A_s / t), A_s = 2 |B_alpha| / sigma), which an explicit
  Taylor method started at a small t pays for with ~ A_s / t steps.  The slow solution is carried from
  the event to t1 (the step cap, or 2^-j of it) by its power series in t, built order by order in ball
  arithmetic at the precision plus guard bits and summed where its terms are below eps / 16 of each
  component's largest (:mod:`verify.engine.slip_onset`, :meth:`_Run.slip_onset`); heyoka takes over at
  t1, where the pull-back's rate A_s / t1^2 is a few hundred per second on the examples.  A series that
  does not reach eps at any t1 tried (or a direction slope B_alpha that does not restore) raises
  :class:`UnsupportedTransition` naming the time, with the run up to there.

Guards: every phase and switch checks itself (:mod:`verify.engine.hybrid_guards`: the domain, E + W, each
switch's constraint, Painleve's jam, a run that stops short of t_end), and a run that breaks one raises
:class:`IntegrationError` with its named outcome and the run up to there.  Output times that fall between an
onset at s = 0 and heyoka's start take their states from the onset's own series or Taylor polynomial.

Error budget: each phase's Taylor integration at tolerance epsilon; each switch time located by
heyoka's event root finding to a few epsilon of t; the maps are exact (no rounding but the
handing over of the same numbers).  E + W is checked after every phase (:func:`~verify.engine.hybrid_guards.check_balance`) and reported
(:attr:`HybridSolution.energy_plus_work_drift_in_eps`).  The sliding phases are not cut into segments with phi, psi moved
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

from . import heyoka_log, hybrid_guards as guards, slip_onset
from .compile import friction_function, symbol_map, to_heyoka
from .problem import max_step
from .single import solve as solve_rolling
from .trajectory import IntegrationError, Trajectory
from .validation import InvalidStart, first_problem, parameters as resolve_parameters, positive_number
from .validation import state as resolve_state
from ..precision import Precision, parse_precision

#: The sliding phase's event where Painleve's margin reaches 0 (:func:`models.coulomb.painleve_margin`).
JAM_EVENT = "painleve_margin"
#: Sliding-phase state (models.coulomb): the eight, the slip speed and direction, the work.
SLIDING_STATE_NAMES = coulomb.SLIDING_STATE_NAMES
_SLIP, _DIRECTION, _WORK = 8, 9, 10


class UnsupportedTransition(IntegrationError):
    """The run reached a switch this driver does not integrate (a slip onset whose direction is not unique,
    or whose series at mu_req = mu does not settle)."""


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
        max over the outputs of |E + W - E(0)| / (eps times the largest term scale of E up to that output):
        the energy balance at the precision (:func:`verify.engine.hybrid_guards.balance_drift_in_eps`); a
        run is handed out only if it is within :func:`~verify.engine.hybrid_guards.balance_bound_in_eps`.
    switch_times : tuple
        Times where a phase ended and the next began.
    steps : int
        heyoka's Taylor steps over every phase.
    outcome, status, message
        'ok' (status 0), the last phase's terminal event ('event:lies_flat', 'event:contact_lost', status 1),
        or, on the partial run an :class:`IntegrationError` carries, its named failure
        (:mod:`verify.engine.hybrid_guards`: 'failed:outside_domain', 'failed:energy_balance',
        'failed:switch_constraint', 'painleve:jam'; 'unsupported:slip_onset'; heyoka's 'failed:...').
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
    steps: int = 0  # Taylor steps of every phase

    def __getitem__(self, name):
        return self.y[STATE_NAMES.index(name)]

    def __repr__(self) -> str:  # the arrays are for reading, not for printing
        span = f"t = {float(self.t[0]):g} to {float(self.t[-1]):g} s, {len(self.t)} outputs" if len(self.t) else "no outputs"
        kinds = [ph.kind for ph in self.phases]
        return (f"HybridSolution(model={self.model!r}, precision={self.precision.name!r}, outcome={self.outcome!r}, "
                f"{span}, {len(kinds)} phases ({kinds.count('rolling')} rolling, {kinds.count('sliding')} sliding), "
                f"steps={self.steps})")

    # the same time-series methods as a rolling run's
    columns, save, to_csv, to_json, plot, animate, _save_as = (
        Trajectory.columns, Trajectory.save, Trajectory.to_csv, Trajectory.to_json, Trajectory.plot, Trajectory.animate,
        Trajectory._save_as)


@dataclass(frozen=True)
class _Compiled:
    precision: Precision
    system: tuple
    events: tuple  # (name, expression, direction)
    sliding_function: object  # cfunc: 11 states -> [E, N/(Mg), E's terms...]
    rolling_function: object  # cfunc: 8 states -> [E, N/(Mg), F_x/(Mg), F_y/(Mg), E's terms...]
    launch_function: object  # cfunc: 8 states + (vx, vy) -> [s, alpha]
    rhs_function: object  # cfunc: 11 states -> their time derivatives
    slip_rates: object  # cfunc: 8 states + alpha -> [e . du/dt, e_perp . du/dt] (no s in either)
    n_pars: int
    check_function: object  # cfunc: 11 states -> [P, sliding v_C (x, y), rolling v_C (x, y)]


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
        (JAM_EVENT, to_heyoka(sliding.painleve_margin, mapping), hy.event_direction.negative),
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
    slip_rates = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.slip_rate_along, sliding.slip_rate_across)],
                          list(variables[:8]) + [variables[_DIRECTION]], **kw)
    # the guards' quantities: Painleve's margin, and v_C two ways (the sliding phase's, with its slip, and the
    # rolling model's no-slip one from models.rolling): at a stick they must agree
    check_function = hy.cfunc([to_heyoka(e, mapping) for e in (sliding.painleve_margin, *sliding.cm_velocity_xy,
                                                                 *rolling.velocity_xy)], list(variables), **kw)
    return _Compiled(precision, system, events, sliding_function, rolling_function, launch_function, rhs_function,
                     slip_rates, len(rolling.parameters) + 1, check_function)


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
    t_eval=None,
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
    t_eval : sequence, optional
        The output times instead (plus the switch times): increasing, from 0 to t_end, each read at
        ``precision`` (decimal strings exactly as written).

    Raises
    ------
    ValueError
        Bad input; :class:`~verify.engine.validation.InvalidStart` for a start outside the domain
        or with N <= 0.
    UnsupportedTransition
        The run reached the onset of slip from rolling where mu_req = mu (the ``slips`` event) and the
        onset's series does not settle, or a slip from s = 0 whose direction is not unique; ``t`` is
        its time, ``trajectory`` the
        :class:`HybridSolution` up to it.
    IntegrationError
        A sliding phase failed (non-finite state, event detection).
    """
    prec = parse_precision(precision)
    rolling, sliding, all_params = coulomb.body(name)
    t_end = positive_number("t_end", t_end, prec)
    try:
        mu = prec.number(friction)
    except (ValueError, TypeError) as err:
        raise ValueError(f"friction={friction!r}: {err}; allowed: a Coulomb coefficient >= 0") from None
    if not float(mu) >= 0:
        raise ValueError(f"friction={friction!r} must be >= 0 (the Coulomb coefficient)")
    pars = resolve_parameters(rolling, params, prec)
    y0 = resolve_state(rolling, state, prec)
    problem = first_problem(rolling, y0[:, None], None, [dict(state)] if isinstance(state, dict) else None)
    if problem is not None:  # the body's domain and constraints, as solve checks them (N waits for the phase)
        raise InvalidStart(problem[2], problem[1])
    c = compiled(name, prec)
    par_vector = prec.array([pars[p.name] for p in rolling.parameters] + [mu])
    if t_eval is not None:
        grid = [prec.number(v) for v in t_eval]
        if len(grid) < 2 or grid[0] != 0 or grid[-1] != t_end or any(not b > a for a, b in zip(grid, grid[1:])):
            raise ValueError(f"t_eval must increase from 0 to t_end = {float(t_end):.9g} (at least 2 times); "
                             f"got {len(grid)} times from {float(grid[0]) if grid else None!r}")
    else:
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
    if run.outcome == "ok" and not (run.t and run.t[-1] == t_end):  # 'ok' means t_end was reached: say so
        raise guards.fail(run, guards.SHORT_RUN, f"{name}: the run ended ok at t = {float(run.t[-1]) if run.t else 0:.9g}"
                                                 f" before t_end = {float(t_end):.9g} (a bug of the driver)", None, None)
    return run.result()


class _CollapseWatch:
    """propagate_grid's callback: stop when a step falls below 16 eps max(|t|, cap).

    Where a sliding phase ends the direction equation alpha' = (e_perp . du/dt) / s relaxes at a rate
    ~ mu N / s, which grows without bound as s -> 0: heyoka's steps then shrink in proportion to the
    time left to the stick (measured: by 0.6 to 0.85 a step) and never cross it.  Below 16 eps
    max(|t|, cap) the time left is a few ulps of t, and :meth:`_Run._finish_stick` takes it in one
    step.  The watch also keeps the last state it saw: the shrinking steps may end in a non-finite
    state before they are that small (measured once: steps of 1e-16 s, 130 ulps of t before the stick,
    then NaN), and :meth:`_Run.sliding` then finishes from there if the time left is below
    :data:`FINISH_ULPS` ulps.
    """

    def __init__(self, prec: Precision, cap):
        self.eps, self.cap = prec.eps, float(cap)
        self.last = None
        self.last_state = None

    def __call__(self, ta) -> bool:
        t = ta.time
        stop = self.last is not None and abs(float(t - self.last)) < 16 * self.eps * max(abs(float(t)), self.cap)
        self.last = t  # at the run's precision: a difference of doubles would vanish long before a quad step
        self.last_state = np.array(ta.state)
        return not stop


#: How close to a stick (in units of eps max(|t|, step cap)) a sliding phase whose steps collapsed (or
#: ended in a non-finite state) may be finished by one Euler step from its last finite state.  Near a
#: stick alpha converges to its limit only like (time left)^kappa, with kappa < 1 on the examples, so its
#: error is of order (time left)^(1 + kappa); but alpha is dropped at the stick, and the eight and W are
#: smooth there: their error is (time left)^2 |y''| / 2, below eps of the state for time left up to
#: ~sqrt(eps) / rate, far above this (2^16 ulps of t: (1.5e-11 t)^2 times rates^2).  The stick's own
#: guards (the no-slip velocity, E + W) check the result.  Measured: the steps stall 130 to 1160 ulps
#: before the stick (2^10 was too few for the steady circle at 0.99 of its mu_req).
FINISH_ULPS = 2 ** 16
#: Painleve's margin below which a collapse of the steps is the jam's: N and the accelerations are ~1 / P
#: times their frictionless size (a thousandfold here), which only mu above the body's critical value
#: reaches (P >= 1 - mu / mu_c otherwise).  Measured on random skids at mu = 1.4 to 1.9 (disk, mu_c = 1.118):
#: the steps stall at P = 4e-5 to 2.5e-7 with N / (M g) = 9e3 to 1.6e6.
JAM_MARGIN = 2 ** -10


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
        self.steps = 0  # Taylor steps of every phase so far (the energy balance's bound grows with them)
        dom = _rolling(name).domain
        self.domain_events = (dom.below, dom.above)
        self.theta_bounds = tuple(_domain_end(e, prec) for e in (dom.theta_min, dom.theta_max))

    def _grid_after(self, t0):
        return [g for g in self.grid if g > t0]

    def truncate(self, n: int) -> None:
        """Keep the first ``n`` outputs (a guard that failed keeps the run through the output it failed at)."""
        for rows in (self.t, self.y, self.energy, self.scale, self.slip, self.direction, self.work, self.index):
            del rows[n:]

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
    def sliding(self, t0, y0, onset=None):
        """A sliding phase from (t0, y0); ``onset``: (time, state) where it began at s = 0 (:meth:`onset`), if so."""
        prec, c = self.prec, self.c
        begun = t0 if onset is None else onset[0]
        self._check_sliding_start(t0, y0, onset)
        inside = [] if onset is None else onset[2]  # output times between the onset and t0 (_outputs_before)
        if inside and inside[-1][0] >= self.t_end:  # the run ends before heyoka would start
            self.phases.append(Phase("sliding", begun, None, "running"))
            return self._end_phase_in_onset(begun, onset, inside)
        ta = _copy(_sliding_template(self.name, prec))
        ta.time = t0
        ta.state[:] = y0
        ta.pars[:] = self.par_vector
        ta.reset_cooldowns()
        self.phases.append(Phase("sliding", begun, None, "running"))
        grid = prec.array([t0] + self._grid_after(t0))
        cap = max_step(y0[:8], self.pars, prec)
        collapse = _CollapseWatch(prec, cap)
        with heyoka_log.collect() as messages:
            result = ta.propagate_grid(grid, max_delta_t=cap, callback=collapse)
        outcome, out = result[0], np.asarray(result[-1])
        self.steps += int(result[3])
        times = list(grid[: len(out)])
        states = [np.array(r) for r in out]
        if onset is not None:  # the phase's first output is where it began, s = 0, not the Euler step's end
            times[0], states[0] = onset[0], np.array(onset[1])
            times[1:1], states[1:1] = [g for g, _ in inside], [np.array(v) for _, v in inside]
        if outcome == hy.taylor_outcome.time_limit:
            ended = "ok"
        elif outcome == hy.taylor_outcome.cb_stop or (outcome == hy.taylor_outcome.err_nf_state
                                                      and collapse.last_state is not None):
            # the steps collapsed (or ended non-finite just after): at a stick, at the domain's end, or a failure
            ta.time, ta.state[:] = collapse.last, collapse.last_state
            ended, t_last, y_last = self._after_collapse(ta, collapse, outcome)
            if all(np.isfinite(np.asarray(y_last, dtype=float))):
                times.append(t_last)
                states.append(y_last)
        elif 0 <= -int(outcome) - 1 < len(c.events):  # terminal event i ends with outcome -i - 1
            ended = c.events[-int(outcome) - 1][0]
            times.append(ta.time)
            states.append(np.array(ta.state))
        else:
            label = "failed:non_finite" if outcome == hy.taylor_outcome.err_nf_state else "failed:sliding"
            raise IntegrationError(f"sliding phase of {self.name} stopped at t = {ta.time}: heyoka outcome {outcome}"
                                   + (f" ({'; '.join(m.text for m in messages)})" if messages else ""), label, ta.time,
                                   list(ta.state), self.result())
        stick_raw = None
        if ended == "sticks":  # the state handed over has s = 0; the guard reads the slip it had (_check_stick)
            stick_raw = states[-1].copy()
            states[-1][_SLIP] = prec.zero()
        if messages:
            raise IntegrationError(f"sliding phase of {self.name}: heyoka warned: {'; '.join(m.text for m in messages)}",
                                   "failed:event_detection", ta.time, list(ta.state), None)
        values = _evaluate(c.sliding_function, prec.array(np.concatenate(states)).reshape(len(states), -1).T,
                           self.par_vector)
        if not all(np.isfinite(np.asarray(s, dtype=float)).all() for s in states):
            raise IntegrationError(f"sliding phase of {self.name}: non-finite state by t = {ta.time}",
                                   "failed:non_finite", ta.time, list(ta.state), None)
        self._record("sliding", times, states, values[0], _term_scale(values, 2), [s[_SLIP] for s in states],
                     [s[_DIRECTION] for s in states], [s[_WORK] for s in states])
        t1 = times[-1]
        self.phases[-1] = Phase("sliding", begun, t1, ended)
        self.work_so_far = states[-1][_WORK]
        if ended.startswith("failed:") or ended == guards.PAINLEVE_JAM:  # the steps collapsed: the run up to there
            raise guards.fail(self, ended, self.collapse_message, t1, states[-1])
        self._check_phase("sliding", times, [s[0] for s in states], [s[3] for s in states], ended, states[-1])
        if ended == JAM_EVENT:
            raise guards.fail(self, guards.PAINLEVE_JAM, self._jam_message(t1, states[-1], "reaches", 0), t1, states[-1])
        if ended == "sticks":
            self._check_stick(t1, stick_raw, max(abs(float(s[_SLIP])) for s in states))
            y8 = prec.array(list(states[-1][:8]))
            return self._after_stick(t1, y8)
        if ended != "ok":
            self.outcome, self.message = f"event:{ended}", f"the sliding phase ended at {ended}"

    def _end_phase_in_onset(self, begun, onset, inside):
        """A sliding phase whose t_end falls between its onset and heyoka's start: its outputs are the onset's
        own solution's (series or Taylor polynomial), and the run ends ok there."""
        times = [onset[0]] + [g for g, _ in inside]
        states = [np.array(onset[1])] + [np.array(v) for _, v in inside]
        values = _evaluate(self.c.sliding_function, self.prec.array(np.concatenate(states)).reshape(len(states), -1).T,
                           self.par_vector)
        self._record("sliding", times, states, values[0], _term_scale(values, 2), [s[_SLIP] for s in states],
                     [s[_DIRECTION] for s in states], [s[_WORK] for s in states])
        self.phases[-1] = Phase("sliding", begun, times[-1], "ok")
        self.work_so_far = states[-1][_WORK]
        self._check_phase("sliding", times, [s[0] for s in states], [s[3] for s in states], "ok", states[-1])

    def _after_collapse(self, ta, watch, outcome):
        """(ended, t, state) where a sliding phase's steps collapsed (:class:`_CollapseWatch`) at ``ta``'s state.

        * within :data:`FINISH_ULPS` of a stick (s falling): the stick, by :meth:`_finish_stick`;
        * with theta within the terminal event's allowance of a domain end and moving towards it
          (:data:`~verify.engine.hybrid_guards.EVENT_ULPS`): that end's event (``lies_flat``).  Near
          theta = 0 the Euler angles' rates blow up like 1 / sin(theta) (phi' = omega2 / sin(theta)), so a
          slip whose sideways rate is a rounding away from 0 stalls the steps within ulps of the end,
          before the event's root (measured: theta = 9.5e-14, 1.5e-13 allowed);
        * with Painleve's margin P below :data:`JAM_MARGIN`: ``painleve:jam`` (N and the accelerations grow
          like 1 / P, so the steps stall before P's event can fire);
        * otherwise ``failed:step_size_collapse`` (or ``failed:non_finite`` for a state that became so).
        """
        y = np.array(ta.state)
        t = ta.time
        finite = all(np.isfinite(np.asarray(y, dtype=float)))
        with np.errstate(divide="ignore", invalid="ignore"):
            rate = _evaluate(self.c.rhs_function, y, self.par_vector) if finite else None
        if finite and rate[_SLIP] < 0:
            left = float(-y[_SLIP] / rate[_SLIP])
            if left <= FINISH_ULPS * self.prec.eps * max(abs(float(t)), watch.cap):
                t_stick, y_stick = self._finish_stick(ta)
                return "sticks", t_stick, y_stick
        if finite:
            margin = _evaluate(self.c.check_function, y, self.par_vector)[0]
            if margin <= JAM_MARGIN:
                self.collapse_message = self._jam_message(t, y, "reaches", margin)
                return guards.PAINLEVE_JAM, t, y
            lo, hi = self.theta_bounds
            allowance = guards.EVENT_ULPS * self.prec.eps * (abs(float(y[3])) * max(abs(float(t)), 1.0) + 1.0)
            for edge, name, towards in ((lo, self.domain_events[0], y[3] < 0), (hi, self.domain_events[1], y[3] > 0)):
                if towards and abs(float(y[0] - edge)) <= allowance:
                    return name, t, y
        self.collapse_message = (f"the sliding phase of {self.name}: the steps collapsed at t = {float(t):.9g} (theta"
                                 f" = {float(y[0]):.6g}, slip speed {float(y[_SLIP]):.3g}) away from a stick and "
                                 "from the domain's ends")
        return ("failed:non_finite" if outcome == hy.taylor_outcome.err_nf_state or not finite
                else "failed:step_size_collapse"), t, y

    def _finish_stick(self, ta):
        """The last ulps before a stick whose steps collapsed (:class:`_CollapseWatch`): one Euler step.

        There s falls at a finite rate s' < 0 and the remaining time is tau = -s / s', a few ulps of t
        (at most :data:`FINISH_ULPS`); the state moves by tau y' (error of order tau^(1 + kappa),
        :data:`FINISH_ULPS`).  alpha is dropped at the stick and the work gains mu N s tau.
        """
        prec, y = self.prec, np.array(ta.state)
        with np.errstate(divide="ignore", invalid="ignore"):  # alpha' is 0/0 if s is 0 already; alpha is dropped
            rate = _evaluate(self.c.rhs_function, y, self.par_vector)
        rate[_DIRECTION] = prec.zero()
        tau = -y[_SLIP] / rate[_SLIP]
        return ta.time + tau, y + tau * rate  # s there is 0 to the rounding of y + tau y' (_check_stick)

    def _after_stick(self, t, y8):
        """Sliding -> rolling at s = 0: the eight components as they are, if rolling holds there."""
        normal, mu_req = (float(v) for v in _evaluate(friction_function(_rolling(self.name), self.prec).function, y8,
                                                       self.par_vector[:-1]))
        if not mu_req <= float(self.mu):
            return self.onset(t, y8, f"the slip stops at t = {t} but rolling there needs mu_req = {mu_req:.6g} > "
                                     f"mu = {float(self.mu):.6g}")
        return self.rolling(t, y8)

    # --- sliding from s = 0 where rolling needs more than mu -----------------------------------
    def onset(self, t, y8, why):
        """Sliding from s = 0 where rolling would need mu_req > mu: the slip starts at a finite rate.

        With |F_req| > mu N the slip's acceleration at s = 0 is finite, du/dt = lambda e(alpha0) with
        lambda > 0, for the one direction alpha0 in which the friction -mu N e(alpha0) leaves the
        contact accelerating along e(alpha0) (:func:`onset_directions`: the root of B(alpha) = e_perp .
        du/dt with e . du/dt > 0; unique, since the contact's response to a horizontal force is
        positive definite).  There d(alpha)/dt = B/s is 0/0, a regular singular point: with
        s = lambda t + O(t^2) (t from the onset), alpha = alpha0 + alpha1 t + O(t^2) with
        alpha1 = B_t / (lambda - B_alpha) (B_t the rate of B along the motion at fixed alpha, B_alpha
        < 0 its restoring slope), the one solution that stays regular; the others leave it like
        t^(B_alpha / lambda) and die out.

        heyoka cannot start at s = 0, so the phase starts at tau = 2^-ceil(bits/3) of the step cap
        (:func:`onset_step`) from this second-order Taylor start: y(tau) = y + tau y' + tau^2 y''/2
        for the eight and s (y'' by a second-order one-sided difference along the first-order path
        over tau and 2 tau), alpha(tau) = alpha0 + alpha1 tau (B_alpha, B_t by central differences),
        W(tau) by Simpson's rule on mu g N s along that start.  The truncation, tau^3 times the third derivative over 6, is
        of order eps of the state; alpha's error, O(tau^2), is a displacement off the regular
        solution, pulled back at the rate lambda / s and moving the state by far less.

        Where mu_req = mu exactly (the ``slips`` event of a rolling phase) lambda = 0: s grows like
        t^2, alpha's pull-back is stiff like 1/t^2, and that onset is :meth:`slip_onset`'s.
        """
        prec, c = self.prec, self.c
        roots = onset_directions(c, y8, self.par_vector)
        if len(roots) != 1:
            raise self._unsupported(t, f"{why}; the slip's direction there is not unique ({len(roots)} directions "
                                       "with the slip accelerating along itself): not integrated")
        alpha0, lam = roots[0]
        y = prec.array(list(y8) + [prec.zero(), alpha0, self.work_so_far])
        tau = onset_step(prec, y8, self.pars)
        start = _second_order_start(c, y, lam, tau, self.par_vector)
        inside = self._outputs_before(t, t + tau, lambda dt: _second_order_start(c, y, lam, dt, self.par_vector))
        return self.sliding(t + tau, start, onset=(t, y, inside))

    # --- rolling ---------------------------------------------------------------------------------
    def rolling(self, t0, y8):
        prec = self.prec
        rolling = _rolling(self.name)
        after = [g for g in self._grid_after(t0) if g - t0 > 0]
        relative = [g - t0 for g in after]
        self.phases.append(Phase("rolling", t0, None, "running"))
        try:
            sol = solve_rolling(rolling, self.t_end - t0, y8, self.pars, precision=prec,
                                t_eval=[prec.zero()] + relative, friction=self.mu)
        except InvalidStart as err:
            if err.reason == "slips":
                self.phases.pop()
                return self.onset(t0, y8, f"rolling from t = {t0} needs more friction than mu: {err}")
            # a state the run reached, not one the user gave: a failed run, not bad input
            self.phases.pop()
            outcome = guards.OUTSIDE_DOMAIN if err.reason == "outside_domain" else guards.SWITCH_CONSTRAINT
            raise guards.fail(self, outcome, f"the rolling phase of {self.name} from t = {float(t0):.9g} cannot "
                                             f"start: {err}", t0, y8) from None
        self.rolling_runs.append(sol)
        self.steps += int(sol.steps)
        states = [np.array(sol.y[:, j]) for j in range(sol.y.shape[1])]
        # a grid output is reported at the grid's own time: t0 + (g - t0) need not round back to g (it is g to
        # an ulp, and the state was integrated to it); the event that ends the phase is at t0 + its own time
        times = [t0] + [after[k] if k < len(relative) and tau == relative[k] else t0 + tau
                        for k, tau in enumerate(sol.t[1:])]
        values = _evaluate(self.c.rolling_function, np.ascontiguousarray(sol.y), self.par_vector[:-1])
        nan = np.longdouble("nan") if prec.name == "long" else float("nan")
        self._record("rolling", times, states, values[0], _term_scale(values, 4), [prec.zero()] * len(times),
                     [nan] * len(times), [self.work_so_far] * len(times))
        ended = "ok" if sol.status == 0 else (sol.outcome[6:] if sol.outcome.startswith("event:") else sol.outcome)
        self.phases[-1] = Phase("rolling", t0, times[-1], ended)
        self._check_phase("rolling", times, sol.y[0], sol.y[3], ended, sol.y[:, -1])
        if ended == "slips":
            self._check_slips(times[-1], np.ascontiguousarray(sol.y[:, -1]))
            return self.slip_onset(times[-1], np.ascontiguousarray(sol.y[:, -1]))
        if ended != "ok":
            self.outcome, self.message = f"event:{ended}", sol.message

    def slip_onset(self, t, y8):
        """Rolling -> sliding where mu_req reaches mu (the ``slips`` event): s = 0, alpha0 the direction of
        -F_req, lambda = 0; the slow solution's power series (:mod:`.slip_onset`) carries the state to t1,
        where heyoka takes over."""
        prec = self.prec
        try:
            t1, start, series, order = slip_onset.series_start(self.name, prec, y8, self.slip_direction(y8),
                                                           self.work_so_far, self.par_vector,
                                                           max_step(y8, self.pars, prec))
        except slip_onset.SeriesDoesNotSettle as err:
            raise self._unsupported(t, f"the contact slips at t = {t} (mu_req reached mu = {float(self.mu):.6g}): "
                                       f"the onset's series does not settle: {err}") from None
        alpha0 = slip_onset.from_arb(prec, series.alpha[0])
        y = prec.array(list(y8) + [prec.zero(), alpha0, self.work_so_far])
        inside = self._outputs_before(t, t + t1,
                                      lambda tau: prec.array(slip_onset.series_state(series, prec, tau, order,
                                                                                     self.work_so_far)))
        return self.sliding(t + t1, prec.array(start), onset=(t, y, inside))

    def _outputs_before(self, t, t0, state_at):
        """[(g, state)] for the output times g in (t, t0], between an onset at t and its start at t0, from the
        onset's own solution ``state_at(g - t)`` (its series or Taylor polynomial, exact there to the same
        order: g - t <= t0 - t).  Without them a run whose t_end falls there would end at the onset."""
        return [(g, state_at(g - t)) for g in self.grid if t < g <= t0]

    def slip_direction(self, y8):
        """alpha of the slip at an onset: the direction of -F_req (module docstring)."""
        values = _evaluate(self.c.rolling_function, y8, self.par_vector[:-1])
        return float(np.arctan2(-float(values[3]), -float(values[2])))

    def _unsupported(self, t, message):
        self.outcome, self.message = "unsupported:slip_onset", message
        return UnsupportedTransition(message, "unsupported:slip_onset", t, None, self.result())

    # --- the guards (verify.engine.hybrid_guards) --------------------------------------------------
    def _check_phase(self, kind, times, thetas, thetadots, ended, last):
        """Domain at every output, N = 0 where the phase ended at contact_lost, then E + W so far (``last``:
        the phase's last state, the eight or the sliding eleven)."""
        guards.check_domain(self, kind, times, thetas, *self.theta_bounds, ended, thetadots)
        if ended == "contact_lost":
            last = self.prec.array(list(last))
            if kind == "sliding":
                def normal(y):
                    return _evaluate(self.c.sliding_function, y, self.par_vector)[1:2]
            else:
                friction = friction_function(_rolling(self.name), self.prec).function

                def normal(y):
                    return _evaluate(friction, y, self.par_vector[:-1])[:1]
            self._check_constraint("contact_lost event", normal, last, times[-1], "N / (M g)")
        guards.check_balance(self)

    def _rates(self, y):
        """d/dt of a state: the sliding rows' (the eight's rates at s = 0 with alpha the slip's direction are the
        rolling ones where mu_req = mu; alpha' is 0/0 there and not read)."""
        full = self.prec.array(list(y) + [self.prec.zero(), self.prec.zero(), self.work_so_far]) if len(y) == 8 else y
        with np.errstate(divide="ignore", invalid="ignore"):
            rates = _evaluate(self.c.rhs_function, full, self.par_vector)
        rates[_DIRECTION] = self.prec.zero()
        return rates[: len(y)]

    def _check_constraint(self, name, function, y, t, what, rates=None):
        """|function(y)| within SWITCH_ULPS of what one ulp moves it (:func:`~.hybrid_guards.one_ulp_sensitivity`)."""
        rates = self._rates(y) if rates is None else rates
        cap = max_step(y[:8], self.pars, self.prec)
        bound = guards.SWITCH_ULPS * guards.one_ulp_sensitivity(function, y, rates, t, cap, self.prec)
        value = np.asarray(function(y))
        guards.check_switch(self, name, float(np.max(np.abs(value))), bound, t, y, what)

    def _check_sliding_start(self, t0, y0, onset):
        """A sliding phase starts inside the domain, with s >= 0, with Painleve's margin P > 0, and, where it
        began at s = 0 (``onset``: time, state), with the E + W of its onset (series or Taylor start)."""
        begun = t0 if onset is None else onset[0]
        guards.check_domain(self, "sliding", [t0], [y0[0]], *self.theta_bounds, None, recorded=False)
        if onset is not None:
            before, after = (_evaluate(self.c.sliding_function, self.prec.array(list(y)), self.par_vector)
                             for y in (onset[1], y0))
            scale = max(_term_scale(before, 2), _term_scale(after, 2))
            gap = (after[0] + y0[_WORK]) - (before[0] + onset[1][_WORK])
            guards.check_switch(self, "onset of slip", gap, guards.BALANCE_PER_SWITCH * self.prec.eps * scale, begun,
                                y0, f"E + W at t = {float(t0):.9g} (its start) minus E + W at the onset")
        if not y0[_SLIP] >= 0:
            where = "sliding phase" if onset is None else "onset of slip"
            raise guards.fail(self, guards.SWITCH_CONSTRAINT, f"{self.name}: the {where} from t = {float(begun):.9g}"
                                                              f" starts with a slip speed {float(y0[_SLIP]):.3g} < 0",
                              t0, y0)
        margin = _evaluate(self.c.check_function, y0, self.par_vector)[0]
        if not margin > 0:
            raise guards.fail(self, guards.PAINLEVE_JAM, self._jam_message(begun, y0, "starts at", margin), begun, y0)

    def _jam_message(self, t, y, where, margin):
        from models.coulomb import critical_friction

        critical = critical_friction(self.name, {k: str(v) for k, v in self.pars.items()})
        return (f"{self.name}: the sliding phase {where} Painleve's jam at t = {float(t):.9g} (margin P = "
                f"{float(margin):.3g} at theta = {float(y[0]):.6g}; N and the accelerations grow like 1 / P): with "
                f"Coulomb friction mu = {float(self.mu):.6g}, above this body's critical {critical:.6g}, the rigid "
                "body has no unique smooth motion from there")

    def _check_stick(self, t, raw, slip_max):
        """At a stick the sliding state's v_C (its slip s still in it) is the rolling model's no-slip v_C."""
        def slip(y):  # v_C of the sliding state minus the rolling model's no-slip v_C: the contact's slip
            values = _evaluate(self.c.check_function, y, self.par_vector)
            return [values[1] - values[3], values[2] - values[4]]

        with np.errstate(divide="ignore", invalid="ignore"):
            rates = _evaluate(self.c.rhs_function, raw, self.par_vector)
        if raw[_SLIP] == 0:  # alpha' is 0/0; alpha does not enter v_C at s = 0
            rates[_DIRECTION] = self.prec.zero()
        self._check_constraint("stick", slip, raw, t, "v_C - v_C(no slip) (the contact's slip, R/s)", rates)

    def _check_slips(self, t, y8):
        """At a slips event the rolling motion needs mu_req = mu."""
        friction = friction_function(_rolling(self.name), self.prec).function

        def excess(y):
            return _evaluate(friction, y, self.par_vector[:-1])[1:] - self.mu

        y8 = self.prec.array(list(y8))
        rates = self._rates_at_slip(y8)
        self._check_constraint("slips event", excess, y8, t, "mu_req - mu", rates)

    def _rates_at_slip(self, y8):
        """The eight's rates where mu_req = mu: the sliding rows' at s = 0 with alpha the direction of -F_req
        (the friction is then the one rolling needs, so the accelerations are the rolling ones)."""
        alpha = self.prec.number(self.slip_direction(y8))
        full = self.prec.array(list(y8) + [self.prec.zero(), alpha, self.work_so_far])
        with np.errstate(divide="ignore", invalid="ignore"):
            rates = _evaluate(self.c.rhs_function, full, self.par_vector)
        return rates[:8]

    # --- the record ------------------------------------------------------------------------------
    def result(self) -> HybridSolution:
        prec = self.prec
        y = np.array(self.y).T if self.y else np.zeros((8, 0))
        energy, work = np.array(self.energy), np.array(self.work)
        scale = max(float(s) for s in self.scale) if self.scale else float("nan")
        drift = float(np.max(guards.balance_drift_in_eps(energy, work, self.scale, prec.eps))) if len(energy) else float("nan")
        switches = tuple(p.t_end for p in self.phases[:-1])
        status = 0 if self.outcome == "ok" else 1
        return HybridSolution(
            model=self.name, precision=prec, params={**self.pars, "mu": self.mu}, t=np.array(self.t), y=y,
            slip_speed=np.array(self.slip), slip_direction=np.array(self.direction, dtype=_dtype(prec)),
            phase_index=np.array(self.index), phases=tuple(self.phases), energy=energy, work=work,
            energy_scale=scale, energy_plus_work_drift_in_eps=drift, switch_times=switches,
            outcome=self.outcome, status=status, message=self.message, rolling_runs=tuple(self.rolling_runs),
            steps=self.steps,
        )


def onset_directions(c: _Compiled, y8, par_vector, samples: int = 256) -> list:
    """[(alpha0, lambda)]: the directions in which a slip from s = 0 accelerates along itself, du/dt = lambda e.

    The roots in alpha of e_perp(alpha) . du/dt (the slip's acceleration with friction -mu N e(alpha),
    ``models.coulomb``'s ``slip_rate_across``) with lambda = e . du/dt > 0: bracketed on ``samples``
    directions, then bisected at the precision until the bracket stops shrinking.
    """
    prec = c.precision
    two_pi = 2 * _pi(prec)
    alphas = [two_pi * prec.number(i) / prec.number(samples) - two_pi / 2 for i in range(samples + 1)]

    def rates(alpha):
        return _evaluate(c.slip_rates, prec.array(list(y8) + [alpha]), par_vector)

    values = [rates(a) for a in alphas]
    found = []
    for (a, fa), (b, fb) in zip(zip(alphas, values), zip(alphas[1:], values[1:])):
        if (fa[1] > 0) == (fb[1] > 0) or not (fa[0] > 0 or fb[0] > 0):
            continue
        lo, hi, up = a, b, fa[1] < 0
        while True:
            mid = (lo + hi) / 2
            if not lo < mid < hi:
                break
            if (rates(mid)[1] < 0) == up:
                lo = mid
            else:
                hi = mid
        along = rates(lo)[0]
        if along > 0:
            found.append((lo, along))
    return found


def onset_step(prec: Precision, y8, pars):
    """How far the Taylor start of a slip from s = 0 reaches: 2^-ceil(bits/3) of the step cap (one radian
    of the fastest rate), so that its truncation, tau^3 times the third derivative, is of order eps
    (:meth:`_Run.onset`)."""
    return prec.number(2) ** -((_bits(prec) + 2) // 3) * max_step(y8, pars, prec)


def _second_order_start(c: _Compiled, y, lam, tau, par_vector):
    """The state a time ``tau`` after a slip's onset ``y`` (s = 0, alpha0, W): see :meth:`_Run.onset`.

    The eight, s and alpha from their second-order Taylor polynomials, and the work W by Simpson's rule
    on the rate mu g N s along them (exact to O(tau^5) for them).
    """
    prec = c.precision
    y8, alpha0 = y[:8], y[_DIRECTION]
    with np.errstate(divide="ignore", invalid="ignore"):  # d(alpha)/dt is 0/0 at s = 0 and is not read
        rate0 = _evaluate(c.rhs_function, y, par_vector)

    def across(state8, alpha):
        return _evaluate(c.slip_rates, prec.array(list(state8) + [alpha]), par_vector)[1]

    h = tau
    b_alpha = (across(y8, alpha0 + h) - across(y8, alpha0 - h)) / (2 * h)
    b_t = (across(y8 + h * rate0[:8], alpha0) - across(y8 - h * rate0[:8], alpha0)) / (2 * h)
    alpha1 = b_t / (lam - b_alpha)

    def along_path(dt):  # the rates on the first-order path, for the second derivatives
        p = y.copy()
        p[:8] = y8 + dt * rate0[:8]
        p[_SLIP], p[_DIRECTION] = lam * dt, alpha0 + alpha1 * dt
        return _evaluate(c.rhs_function, p, par_vector)

    r1, r2 = along_path(h), along_path(2 * h)
    moving = list(range(8)) + [_SLIP]
    second = {i: (-3 * rate0[i] + 4 * r1[i] - r2[i]) / (2 * h) for i in moving}

    def at(dt, alpha2):
        p = y.copy()
        for i in moving:
            p[i] = y[i] + dt * rate0[i] + dt * dt * second[i] / 2
        p[_DIRECTION] = alpha0 + alpha1 * dt + alpha2 * dt * dt / 2
        return p

    def mismatch(alpha2):  # alpha's rate on the path at h against the path's own, alpha1 + alpha2 h
        return _evaluate(c.rhs_function, at(h, alpha2), par_vector)[_DIRECTION] - (alpha1 + alpha2 * h)

    # alpha2 puts the start on the regular solution to second order too: the rate is affine in alpha2
    # to far below eps there (alpha2 h^2 / 2 is a displacement of order h^2), so one secant step solves it
    m0, m1 = mismatch(prec.zero()), mismatch(prec.number(1))
    alpha2 = -m0 / (m1 - m0)
    start, middle = at(tau, alpha2), at(tau / 2, alpha2)
    work_rate = [_evaluate(c.rhs_function, p, par_vector)[_WORK] for p in (middle, start)]
    start[_WORK] = y[_WORK] + tau * (4 * work_rate[0] + work_rate[1]) / 6  # the rate is 0 at s = 0
    return start


def _pi(prec: Precision):
    import mpmath

    with mpmath.workprec(_bits(prec) + 16):
        return prec.number(mpmath.nstr(mpmath.pi, int(_bits(prec) * 0.302) + 6))


def _bits(prec: Precision) -> int:
    return int(round(1 - np.log2(prec.eps)))


def _domain_end(end, prec: Precision):
    """A domain end (sympy: 0, pi, pi/2) as a number of the run's precision (the start check's own rounding,
    :func:`verify.engine.validation._domain_end`)."""
    from .validation import _domain_end as rounded_like

    return rounded_like(end, prec.zero())


def _dtype(prec: Precision):
    return {"double": float, "long": np.longdouble}.get(prec.name, object)


def _rolling(name):
    from models import get_model

    return get_model(coulomb.rolling_name(name))


def _copy(ta):
    import copy

    return copy.copy(ta)


def sliding_expressions(name: str) -> dict:
    """The sliding phase's right-hand sides by state name (sympy), for inspection and tests."""
    _, sliding, _ = coulomb.body(name)
    return {n: sp.sympify(e) for n, e in zip(SLIDING_STATE_NAMES, sliding.rhs)}

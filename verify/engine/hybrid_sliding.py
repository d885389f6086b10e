"""The sliding phase of a rolling-and-sliding run (:mod:`verify.engine.hybrid`), integrated by heyoka.

The equations of :mod:`models.coulomb` (paper Eqs. 5-8 with F_h = -mu N u/|u|, the slip speed s and direction
alpha as state, the work W = int mu N s dt as a quadrature; :mod:`verify.engine.hybrid_system`) run from a
start (t0, y0) with the terminal event ``sticks`` on s (direction negative: Coulomb friction brings s to zero at
a finite rate, so s changes sign there and heyoka locates the root to epsilon), the domain's ends,
``contact_lost`` and Painleve's margin.

Near a stick the direction's equation grows stiff and heyoka's steps may collapse before the event
(:class:`CollapseWatch`); :func:`after_collapse` says what the run reached there (the stick, a domain end,
Painleve's jam, or a named failure) and :func:`finish_stick` takes the last ulps to the stick in one step.

The phase's steps are capped at one radian of the fastest initial rate as every run's are
(:func:`verify.engine.problem.max_step`); it is not cut into segments (:mod:`verify.engine.segments`): a
sliding phase lasts until the slip dies out, a fraction of a second at the rates the suite uses.
"""
from __future__ import annotations

import heyoka as hy
import numpy as np

from . import heyoka_log, hybrid_guards as guards
from .hybrid_run import Phase
from .hybrid_system import DIRECTION, JAM_EVENT, SLIP, WORK, evaluate, new_sliding_integrator, term_scale
from .problem import max_step
from .trajectory import IntegrationError

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


class CollapseWatch:
    """propagate_grid's callback: stop when a step falls below 16 eps max(|t|, cap).

    Where a sliding phase ends the direction equation alpha' = (e_perp . du/dt) / s relaxes at a rate
    ~ mu N / s, which grows without bound as s -> 0: heyoka's steps then shrink in proportion to the
    time left to the stick (measured: by 0.6 to 0.85 a step) and never cross it.  Below 16 eps
    max(|t|, cap) the time left is a few ulps of t, and :func:`finish_stick` takes it in one
    step.  The watch also keeps the last state it saw: the shrinking steps may end in a non-finite
    state before they are that small (measured once: steps of 1e-16 s, 130 ulps of t before the stick,
    then NaN), and :func:`sliding_phase` then finishes from there if the time left is below
    :data:`FINISH_ULPS` ulps.
    """

    def __init__(self, prec, cap):
        self.eps, self.cap = prec.eps, float(cap)
        self.last = None
        self.last_state = None

    def __call__(self, ta) -> bool:
        t = ta.time
        stop = self.last is not None and abs(float(t - self.last)) < 16 * self.eps * max(abs(float(t)), self.cap)
        self.last = t  # at the run's precision: a difference of doubles would vanish long before a quad step
        self.last_state = np.array(ta.state)
        return not stop


def sliding_phase(run, t0, y0, onset=None):
    """A sliding phase of ``run`` from (t0, y0), its outputs recorded and checked.

    Parameters
    ----------
    run : verify.engine.hybrid_run.Run
    t0 : number
        Where heyoka starts.
    y0 : ndarray (11,)
        The sliding state there (:data:`verify.engine.hybrid_system.SLIDING_STATE_NAMES`).
    onset : tuple, optional
        (time, state, outputs) where the phase began at s = 0 (:mod:`verify.engine.hybrid_switches`), and
        the outputs between that time and t0 from the onset's own solution.

    Returns
    -------
    tuple or None
        ``("sticks", t, y8)`` where the slip stopped (the switch is the caller's), or None where the run
        ended (at t_end, or at a terminal event: the run's outcome says which).
    """
    prec, c = run.prec, run.c
    begun = t0 if onset is None else onset[0]
    guards.check_sliding_start(run, t0, y0, onset)
    inside = [] if onset is None else onset[2]  # output times between the onset and t0 (Run.outputs_before)
    if inside and inside[-1][0] >= run.t_end:  # the run ends before heyoka would start
        run.phases.append(Phase("sliding", begun, None, "running"))
        return end_phase_in_onset(run, begun, onset, inside)
    ta = new_sliding_integrator(run.name, prec)
    ta.time = t0
    ta.state[:] = y0
    ta.pars[:] = run.par_vector
    ta.reset_cooldowns()
    run.phases.append(Phase("sliding", begun, None, "running"))
    grid = prec.array([t0] + run.grid_after(t0))
    cap = max_step(y0[:8], run.pars, prec)
    collapse = CollapseWatch(prec, cap)
    with heyoka_log.collect() as messages:
        result = ta.propagate_grid(grid, max_delta_t=cap, callback=collapse)
    outcome, out = result[0], np.asarray(result[-1])
    run.steps += int(result[3])
    times = list(grid[: len(out)])
    states = [np.array(r) for r in out]
    if onset is not None:  # the phase's first output is where it began, s = 0, not the Euler step's end
        times[0], states[0] = onset[0], np.array(onset[1])
        times[1:1], states[1:1] = [g for g, _ in inside], [np.array(v) for _, v in inside]
    collapse_message = None
    if outcome == hy.taylor_outcome.time_limit:
        ended = "ok"
    elif outcome == hy.taylor_outcome.cb_stop or (outcome == hy.taylor_outcome.err_nf_state
                                                  and collapse.last_state is not None):
        # the steps collapsed (or ended non-finite just after): at a stick, at the domain's end, or a failure
        ta.time, ta.state[:] = collapse.last, collapse.last_state
        ended, t_last, y_last, collapse_message = after_collapse(run, ta, collapse, outcome)
        if all(np.isfinite(np.asarray(y_last, dtype=float))):
            times.append(t_last)
            states.append(y_last)
    elif 0 <= -int(outcome) - 1 < len(c.events):  # terminal event i ends with outcome -i - 1
        ended = c.events[-int(outcome) - 1][0]
        times.append(ta.time)
        states.append(np.array(ta.state))
    else:
        label = "failed:non_finite" if outcome == hy.taylor_outcome.err_nf_state else "failed:sliding"
        raise IntegrationError(f"sliding phase of {run.name} stopped at t = {ta.time}: heyoka outcome {outcome}"
                               + (f" ({'; '.join(m.text for m in messages)})" if messages else ""), label, ta.time,
                               list(ta.state), run.result())
    stick_raw = None
    if ended == "sticks":  # the state handed over has s = 0; the guard reads the slip it had (check_stick)
        stick_raw = states[-1].copy()
        states[-1][SLIP] = prec.zero()
    if messages:
        raise IntegrationError(f"sliding phase of {run.name}: heyoka warned: {'; '.join(m.text for m in messages)}",
                               "failed:event_detection", ta.time, list(ta.state), None)
    values = evaluate(c.sliding_function, prec.array(np.concatenate(states)).reshape(len(states), -1).T,
                      run.par_vector)
    if not all(np.isfinite(np.asarray(s, dtype=float)).all() for s in states):
        raise IntegrationError(f"sliding phase of {run.name}: non-finite state by t = {ta.time}",
                               "failed:non_finite", ta.time, list(ta.state), None)
    run.record(times, states, values[0], term_scale(values, 2), [s[SLIP] for s in states],
               [s[DIRECTION] for s in states], [s[WORK] for s in states])
    t1 = times[-1]
    run.phases[-1] = Phase("sliding", begun, t1, ended)
    run.work_so_far = states[-1][WORK]
    if ended.startswith("failed:") or ended == guards.PAINLEVE_JAM:  # the steps collapsed: the run up to there
        raise guards.fail(run, ended, collapse_message, t1, states[-1])
    guards.check_phase(run, "sliding", times, [s[0] for s in states], [s[3] for s in states], ended, states[-1])
    if ended == JAM_EVENT:
        raise guards.fail(run, guards.PAINLEVE_JAM, guards.jam_message(run, t1, states[-1], "reaches", 0), t1,
                          states[-1])
    if ended == "sticks":
        guards.check_stick(run, t1, stick_raw)
        return "sticks", t1, prec.array(list(states[-1][:8]))
    if ended != "ok":
        run.outcome, run.message = f"event:{ended}", f"the sliding phase ended at {ended}"
    return None


def end_phase_in_onset(run, begun, onset, inside):
    """A sliding phase whose t_end falls between its onset and heyoka's start: its outputs are the onset's
    own solution's (series or Taylor polynomial), and the run ends ok there (returns None)."""
    times = [onset[0]] + [g for g, _ in inside]
    states = [np.array(onset[1])] + [np.array(v) for _, v in inside]
    values = evaluate(run.c.sliding_function, run.prec.array(np.concatenate(states)).reshape(len(states), -1).T,
                      run.par_vector)
    run.record(times, states, values[0], term_scale(values, 2), [s[SLIP] for s in states],
               [s[DIRECTION] for s in states], [s[WORK] for s in states])
    run.phases[-1] = Phase("sliding", begun, times[-1], "ok")
    run.work_so_far = states[-1][WORK]
    guards.check_phase(run, "sliding", times, [s[0] for s in states], [s[3] for s in states], "ok", states[-1])
    return None


def after_collapse(run, ta, watch, outcome):
    """(ended, t, state, message) where a sliding phase's steps collapsed (:class:`CollapseWatch`) at ``ta``'s
    state; ``message`` says why for a failure or Painleve's jam (None otherwise).

    * within :data:`FINISH_ULPS` of a stick (s falling): the stick, by :func:`finish_stick`;
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
        rate = evaluate(run.c.rhs_function, y, run.par_vector) if finite else None
    if finite and rate[SLIP] < 0:
        left = float(-y[SLIP] / rate[SLIP])
        if left <= FINISH_ULPS * run.prec.eps * max(abs(float(t)), watch.cap):
            t_stick, y_stick = finish_stick(run, ta)
            return "sticks", t_stick, y_stick, None
    if finite:
        margin = evaluate(run.c.check_function, y, run.par_vector)[0]
        if margin <= JAM_MARGIN:
            return guards.PAINLEVE_JAM, t, y, guards.jam_message(run, t, y, "reaches", margin)
        lo, hi = run.theta_bounds
        allowance = guards.EVENT_ULPS * run.prec.eps * (abs(float(y[3])) * max(abs(float(t)), 1.0) + 1.0)
        for edge, name, towards in ((lo, run.domain_events[0], y[3] < 0), (hi, run.domain_events[1], y[3] > 0)):
            if towards and abs(float(y[0] - edge)) <= allowance:
                return name, t, y, None
    message = (f"the sliding phase of {run.name}: the steps collapsed at t = {float(t):.9g} (theta"
               f" = {float(y[0]):.6g}, slip speed {float(y[SLIP]):.3g}) away from a stick and "
               "from the domain's ends")
    return ("failed:non_finite" if outcome == hy.taylor_outcome.err_nf_state or not finite
            else "failed:step_size_collapse"), t, y, message


def finish_stick(run, ta):
    """The last ulps before a stick whose steps collapsed (:class:`CollapseWatch`): one Euler step.

    There s falls at a finite rate s' < 0 and the remaining time is tau = -s / s', a few ulps of t
    (at most :data:`FINISH_ULPS`); the state moves by tau y' (error of order tau^(1 + kappa),
    :data:`FINISH_ULPS`).  alpha is dropped at the stick and the work gains mu N s tau.
    """
    prec, y = run.prec, np.array(ta.state)
    with np.errstate(divide="ignore", invalid="ignore"):  # alpha' is 0/0 if s is 0 already; alpha is dropped
        rate = evaluate(run.c.rhs_function, y, run.par_vector)
    rate[DIRECTION] = prec.zero()
    tau = -y[SLIP] / rate[SLIP]
    return ta.time + tau, y + tau * rate  # s there is 0 to the rounding of y + tau y' (check_stick)

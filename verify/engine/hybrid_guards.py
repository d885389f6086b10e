"""What a rolling <-> sliding run checks of itself (:mod:`verify.engine.hybrid`): its named failures.

A run of ``disk+coulomb`` or ``ring+coulomb`` is handed out only if every phase and every switch
passed its guard; otherwise it ends with one of these outcomes (status 1, the command exits 1), and
:class:`~verify.engine.trajectory.IntegrationError` carries the run up to there:

* ``failed:outside_domain`` -- a state of any phase (an output, a switch state, the start a series
  or a Taylor start hands to heyoka) has theta outside the model's open domain (the disk's
  0 < theta < pi, the ring's 0 < theta < pi/2), other than the end of the terminal event that
  reached the domain's end, which may lie :data:`EVENT_ULPS` off it;
* ``failed:energy_balance`` -- |E + W - E(0)| exceeds :func:`balance_bound_in_eps` (eps of E's term
  scale, grown with the Taylor steps and the switches taken);
* ``failed:switch_constraint`` -- a switch does not hold its own constraint: a stick whose slip speed
  before it is set to 0 is not within eps of 0, or whose contact does not move with the rolling
  model's no-slip velocity; a ``slips`` event whose mu_req is not mu; a ``contact_lost`` event whose
  N is not 0 (:func:`check_switch`);
* ``failed:short_run`` -- a run whose phases all ended ``ok`` did not reach t_end (measured once: a
  slip onset whose series reached past t_end handed out the onset's state as the end);
* ``painleve:jam`` -- a sliding phase reaches, or starts at, Painleve's margin P <= 0
  (:func:`models.coulomb.painleve_margin`): the rigid body with Coulomb friction has no unique motion
  from there; possible only for mu above :func:`models.coulomb.critical_friction`.

The energy balance holds whatever the motion's conditioning: E + W is conserved by the exact flow of
every phase, so an error committed in one step moves it once and is carried, not amplified; the
bound grows only with the number of places an error is committed (steps and switches).
"""
from __future__ import annotations

import numpy as np

from .trajectory import IntegrationError

OUTSIDE_DOMAIN = "failed:outside_domain"
ENERGY_BALANCE = "failed:energy_balance"
SWITCH_CONSTRAINT = "failed:switch_constraint"
PAINLEVE_JAM = "painleve:jam"
SHORT_RUN = "failed:short_run"
#: Every outcome of a run that is not handed out as a result (status 1, exit 1), with heyoka's own.
FAILED_OUTCOMES = (OUTSIDE_DOMAIN, ENERGY_BALANCE, SWITCH_CONSTRAINT, PAINLEVE_JAM, SHORT_RUN)

#: eps of E's term scale one Taylor step may move E + W by.  heyoka's step at tolerance eps keeps the
#: local error of each component within eps of the state's size; E is a sum of terms of degree <= 2
#: in the rates (times bounded trigonometric factors), so a relative error eps in each component moves
#: E by at most 2 eps of its term scale; and the evaluation of the step's Taylor polynomial adds about as
#: much again.  Errors of successive steps are carried by the flow (E + W is its invariant), not
#: amplified, and added: the bound is linear in the steps (measured: a random walk, far below it).
BALANCE_PER_STEP = 4
#: eps of E's term scale one switch may move E + W by: the eight are handed over as they are (E is then
#: evaluated on the other phase's formula: a few eps), the stick's last ulps are one Euler step (measured
#: under 1 eps), the onset's series is summed to eps / 16 of each component and its start by a
#: second-order Taylor polynomial to order eps of the state.  64 covers the formula change and the
#: start's components with margin.
BALANCE_PER_SWITCH = 64
#: How far (in ulps of the quantity's scale, times the event time) the end of a terminal event may lie
#: off its root: heyoka locates the root of the event's Taylor polynomial to a few ulps of t, and the
#: quantity moves at its rate over that time; 1024 covers rates up to the thousands per unit of the
#: step's time scale.
EVENT_ULPS = 1024
#: A switch's constraint (mu_req = mu at a slip, N = 0 where contact is lost, v_C = its no-slip value at a
#: stick) holds to this many times what one ulp moves it (:func:`one_ulp_sensitivity`): heyoka locates an
#: event's root to a few ulps of t, the state is then exact to the integration's few ulps, and the maps
#: hand the numbers over as they are.
SWITCH_ULPS = 64


def balance_bound_in_eps(steps: int, switches: int) -> float:
    """The bound on max |E + W - E(0)| in eps of E's term scale after ``steps`` Taylor steps and ``switches``
    phase switches (module docstring)."""
    return BALANCE_PER_STEP * max(int(steps), 1) + BALANCE_PER_SWITCH * (int(switches) + 1)


def balance_drift_in_eps(energy, work, scale, eps) -> np.ndarray:
    """|E + W - E(0) - W(0)| at each output over eps times the largest term scale of E *up to* that output.

    Not the largest of the whole run: where a run ends near the disk's flat position its rates grow a
    millionfold, with terms of E that cancel, and that scale would make every earlier drift look nil
    (measured: 1e-17 eps).  An error committed at one output was committed at the scales before it."""
    balance = np.array([float(e + w - energy[0] - work[0]) for e, w in zip(energy, work)])
    running = np.maximum.accumulate(np.array([float(s) for s in scale]))
    return np.abs(balance) / (running * eps)


def one_ulp_sensitivity(function, y, rates, t, cap, prec) -> float:
    """How much one ulp moves ``function(y)``: the sum over components i of |f(y + d_i e_i) - f(y)| (summed
    over f's outputs), with d_i = eps (|y_i| + |y_i'| (|t| + cap)): one ulp of the component, and one ulp
    of the time (|t| + the step cap: heyoka's root is relative to the step) along the motion's rate."""
    base = np.asarray(function(y))
    eps = prec.number(prec.eps)
    total = 0.0
    for i in range(len(y)):
        d = eps * (abs(y[i]) + abs(rates[i]) * (abs(t) + cap))
        if not d > 0:
            continue
        z = y.copy()
        z[i] = z[i] + d
        total += float(np.sum(np.abs(np.asarray(function(z)) - base)))
    return total


def fail(run, outcome: str, message: str, t, state):
    """The :class:`IntegrationError` of a failed guard, with the run up to there; ``run`` is the hybrid
    driver (its outcome and message are set first, so the partial record says how it ended)."""
    run.outcome, run.message = outcome, message
    return IntegrationError(message, outcome, t, None if state is None else list(state), run.result())


def check_domain(run, kind: str, times, thetas, lo, hi, end_event: str | None, rates=None, recorded=True) -> None:
    """Every theta of a phase strictly inside (lo, hi); the last one may be on an end the phase's terminal
    event ``end_event`` reached (``rates``: thetadot there, for the event's allowance).  ``recorded``: the
    thetas are the run's last outputs (a failure keeps the run through the first one outside)."""
    inside = [bool(lo < th < hi) for th in thetas]  # at the run's precision: lo, hi are its numbers
    if end_event in run.domain_events and len(thetas):
        t_last = abs(float(times[-1]))
        allowance = EVENT_ULPS * run.prec.eps * (abs(float(rates[-1])) * max(t_last, 1.0) + 1.0)
        edge = lo if end_event == run.domain_events[0] else hi
        inside[-1] = inside[-1] or abs(float(thetas[-1] - edge)) <= allowance
    if not all(inside):
        k = inside.index(False)
        if recorded:  # the run up to there: through the first output outside, not the rest of the phase
            run.truncate(len(run.t) - len(thetas) + k + 1)
        raise fail(run, OUTSIDE_DOMAIN, f"the {kind} phase of {run.name} left its domain {float(lo):.6g} < theta < "
                                        f"{float(hi):.6g}: theta = {float(thetas[k]):.6g} at t = {float(times[k]):.9g}",
                   times[k], None)


def check_balance(run) -> None:
    """max |E + W - E(0)| over the run so far within :func:`balance_bound_in_eps` of its steps and switches."""
    drift = balance_drift_in_eps(run.energy, run.work, run.scale, run.prec.eps)
    bound = balance_bound_in_eps(run.steps, len(run.phases) - 1)
    if not drift.max() <= bound:  # NaN fails too
        k = int(np.nanargmax(drift)) if np.isfinite(drift).any() else 0
        raise fail(run, ENERGY_BALANCE, f"{run.name}: E + W drifted by {drift[k]:.3g} eps of E's term scale at "
                                         f"t = {float(run.t[k]):.9g}, past its bound of {bound:.3g} eps "
                                         f"({run.steps} Taylor steps, {len(run.phases) - 1} switches)",
                   run.t[k], run.y[k])


def check_switch(run, name: str, value, bound, t, state, what: str) -> None:
    """A switch's constraint: |value| <= bound, else ``failed:switch_constraint`` naming ``what``."""
    if not abs(float(value)) <= float(bound):
        raise fail(run, SWITCH_CONSTRAINT, f"{run.name}: the {name} at t = {float(t):.9g} does not hold its "
                                            f"constraint: {what} = {float(value):.3g}, allowed |.| <= "
                                            f"{float(bound):.3g}", t, state)

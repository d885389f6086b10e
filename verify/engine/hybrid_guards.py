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

The checks of a phase and of each switch (:func:`check_phase`, :func:`check_sliding_start`,
:func:`check_stick`, :func:`check_slips`) read the run's compiled functions
(:mod:`verify.engine.hybrid_system`) and raise through :func:`fail`.

The energy balance holds whatever the motion's conditioning: E + W is conserved by the exact flow of
every phase, so an error committed in one step moves it once and is carried, not amplified; the
bound grows only with the number of places an error is committed (steps and switches).
"""
from __future__ import annotations

import numpy as np

from models import coulomb

from .compile import friction_function
from .hybrid_system import DIRECTION, SLIP, WORK, evaluate, rolling_model, slip_direction, term_scale
from .problem import max_step
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


# --- the checks of a run's phases and switches ----------------------------------------------------------------

def check_phase(run, kind, times, thetas, thetadots, ended, last) -> None:
    """Domain at every output, N = 0 where the phase ended at contact_lost, then E + W so far (``last``:
    the phase's last state, the eight or the sliding eleven)."""
    check_domain(run, kind, times, thetas, *run.theta_bounds, ended, thetadots)
    if ended == "contact_lost":
        last = run.prec.array(list(last))
        if kind == "sliding":
            def normal(y):
                return evaluate(run.c.sliding_function, y, run.par_vector)[1:2]
        else:
            friction = friction_function(rolling_model(run.name), run.prec).function

            def normal(y):
                return evaluate(friction, y, run.par_vector[:-1])[:1]
        check_constraint(run, "contact_lost event", normal, last, times[-1], "N / (M g)")
    check_balance(run)


def state_rates(run, y):
    """d/dt of a state: the sliding rows' (the eight's rates at s = 0 with alpha the slip's direction are the
    rolling ones where mu_req = mu; alpha' is 0/0 there and not read)."""
    prec = run.prec
    full = prec.array(list(y) + [prec.zero(), prec.zero(), run.work_so_far]) if len(y) == 8 else y
    with np.errstate(divide="ignore", invalid="ignore"):
        rates = evaluate(run.c.rhs_function, full, run.par_vector)
    rates[DIRECTION] = prec.zero()
    return rates[: len(y)]


def check_constraint(run, name, function, y, t, what, rates=None) -> None:
    """|function(y)| within :data:`SWITCH_ULPS` of what one ulp moves it (:func:`one_ulp_sensitivity`)."""
    rates = state_rates(run, y) if rates is None else rates
    cap = max_step(y[:8], run.pars, run.prec)
    bound = SWITCH_ULPS * one_ulp_sensitivity(function, y, rates, t, cap, run.prec)
    value = np.asarray(function(y))
    check_switch(run, name, float(np.max(np.abs(value))), bound, t, y, what)


def check_sliding_start(run, t0, y0, onset) -> None:
    """A sliding phase starts inside the domain, with s >= 0, with Painleve's margin P > 0, and, where it
    began at s = 0 (``onset``: time, state), with the E + W of its onset (series or Taylor start)."""
    prec, c = run.prec, run.c
    begun = t0 if onset is None else onset[0]
    check_domain(run, "sliding", [t0], [y0[0]], *run.theta_bounds, None, recorded=False)
    if onset is not None:
        before, after = (evaluate(c.sliding_function, prec.array(list(y)), run.par_vector) for y in (onset[1], y0))
        scale = max(term_scale(before, 2), term_scale(after, 2))
        gap = (after[0] + y0[WORK]) - (before[0] + onset[1][WORK])
        check_switch(run, "onset of slip", gap, BALANCE_PER_SWITCH * prec.eps * scale, begun, y0,
                     f"E + W at t = {float(t0):.9g} (its start) minus E + W at the onset")
    if not y0[SLIP] >= 0:
        where = "sliding phase" if onset is None else "onset of slip"
        raise fail(run, SWITCH_CONSTRAINT, f"{run.name}: the {where} from t = {float(begun):.9g} starts with a slip "
                                           f"speed {float(y0[SLIP]):.3g} < 0", t0, y0)
    margin = evaluate(c.check_function, y0, run.par_vector)[0]
    if not margin > 0:
        raise fail(run, PAINLEVE_JAM, jam_message(run, begun, y0, "starts at", margin), begun, y0)


def jam_message(run, t, y, where, margin) -> str:
    """What a sliding phase that ``where`` ('reaches', 'starts at') Painleve's jam at (t, y) says."""
    critical = coulomb.critical_friction(run.name, {k: str(v) for k, v in run.pars.items()})
    return (f"{run.name}: the sliding phase {where} Painleve's jam at t = {float(t):.9g} (margin P = "
            f"{float(margin):.3g} at theta = {float(y[0]):.6g}; N and the accelerations grow like 1 / P): with "
            f"Coulomb friction mu = {float(run.mu):.6g}, above this body's critical {critical:.6g}, the rigid "
            "body has no unique smooth motion from there")


def check_stick(run, t, raw) -> None:
    """At a stick the sliding state's v_C (its slip s still in it, ``raw``) is the rolling model's no-slip v_C."""
    def slip(y):  # v_C of the sliding state minus the rolling model's no-slip v_C: the contact's slip
        values = evaluate(run.c.check_function, y, run.par_vector)
        return [values[1] - values[3], values[2] - values[4]]

    with np.errstate(divide="ignore", invalid="ignore"):
        rates = evaluate(run.c.rhs_function, raw, run.par_vector)
    if raw[SLIP] == 0:  # alpha' is 0/0; alpha does not enter v_C at s = 0
        rates[DIRECTION] = run.prec.zero()
    check_constraint(run, "stick", slip, raw, t, "v_C - v_C(no slip) (the contact's slip, R/s)", rates)


def check_slips(run, t, y8) -> None:
    """At a slips event the rolling motion needs mu_req = mu."""
    friction = friction_function(rolling_model(run.name), run.prec).function

    def excess(y):
        return evaluate(friction, y, run.par_vector[:-1])[1:] - run.mu

    y8 = run.prec.array(list(y8))
    check_constraint(run, "slips event", excess, y8, t, "mu_req - mu", rates_at_slip(run, y8))


def rates_at_slip(run, y8):
    """The eight's rates where mu_req = mu: the sliding rows' at s = 0 with alpha the direction of -F_req
    (the friction is then the one rolling needs, so the accelerations are the rolling ones)."""
    prec = run.prec
    alpha = prec.number(slip_direction(run.c, y8, run.par_vector))
    full = prec.array(list(y8) + [prec.zero(), alpha, run.work_so_far])
    with np.errstate(divide="ignore", invalid="ignore"):
        rates = evaluate(run.c.rhs_function, full, run.par_vector)
    return rates[:8]

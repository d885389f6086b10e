"""The switches of a rolling-and-sliding run (:mod:`verify.engine.hybrid`) that start a slip from s = 0.

* sliding -> rolling at ``sticks`` (:func:`after_stick`): the eight components are handed over as they are
  (at s = 0 the CM velocity of the sliding state *is* the no-slip velocity), the slip state is dropped, W is
  kept, if the rolling equations there need mu_req <= mu; otherwise the slip goes on from s = 0;
* sliding from s = 0 where rolling needs mu_req > mu (a start, or a stick where rolling cannot hold;
  :func:`onset`): the slip starts at a finite rate lambda in the one direction alpha0 along which it then
  accelerates (:func:`onset_directions`); d(alpha)/dt = (e_perp . du/dt)/s is 0/0 there, a regular
  singular point whose one regular solution is started by a second-order Taylor polynomial over
  2^-ceil(bits/3) of the step cap (:func:`second_order_start`), then heyoka takes over;
* rolling -> sliding at ``slips`` (mu_req reaches mu exactly; :func:`slip_onset`): s = 0, alpha0 the
  direction of -F_req, but lambda = 0: the slow solution is carried from the event by its power series in
  t (:mod:`verify.engine.slip_onset`) to where heyoka takes over.

Each returns the sliding phase's start, ``("sliding", t0, y0, onset)``, or the rolling phase's,
``("rolling", t, y8)``; :class:`~verify.engine.hybrid_run.UnsupportedTransition` where the slip's direction
is not unique or the series does not settle.
"""
from __future__ import annotations

import mpmath
import numpy as np

from . import slip_onset as onset_series
from .compile import friction_function
from .hybrid_system import DIRECTION, SLIP, WORK, SlidingSystem, evaluate, rolling_model, slip_direction
from .problem import max_step
from ..precision import Precision


def after_stick(run, t, y8):
    """Sliding -> rolling at s = 0: the eight components as they are, if rolling holds there."""
    normal, mu_req = (float(v) for v in evaluate(friction_function(rolling_model(run.name), run.prec).function, y8,
                                                  run.par_vector[:-1]))
    if not mu_req <= float(run.mu):
        return onset(run, t, y8, f"the slip stops at t = {t} but rolling there needs mu_req = {mu_req:.6g} > "
                                 f"mu = {float(run.mu):.6g}")
    return "rolling", t, y8


def onset(run, t, y8, why):
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
    t^2, alpha's pull-back is stiff like 1/t^2, and that onset is :func:`slip_onset`'s.

    Returns ``("sliding", t + tau, start, (t, y, outputs))``.
    """
    prec, c = run.prec, run.c
    roots = onset_directions(c, y8, run.par_vector)
    if len(roots) != 1:
        raise run.unsupported(t, f"{why}; the slip's direction there is not unique ({len(roots)} directions "
                                 "with the slip accelerating along itself): not integrated")
    alpha0, lam = roots[0]
    y = prec.array(list(y8) + [prec.zero(), alpha0, run.work_so_far])
    tau = onset_step(prec, y8, run.pars)
    start = second_order_start(c, y, lam, tau, run.par_vector)
    inside = run.outputs_before(t, t + tau, lambda dt: second_order_start(c, y, lam, dt, run.par_vector))
    return "sliding", t + tau, start, (t, y, inside)


def slip_onset(run, t, y8):
    """Rolling -> sliding where mu_req reaches mu (the ``slips`` event): s = 0, alpha0 the direction of
    -F_req, lambda = 0; the slow solution's power series (:mod:`verify.engine.slip_onset`) carries the state
    to t1, where heyoka takes over.  Returns ``("sliding", t + t1, start, (t, y, outputs))``."""
    prec = run.prec
    try:
        t1, start, series, order = onset_series.series_start(run.name, prec, y8,
                                                             slip_direction(run.c, y8, run.par_vector),
                                                             run.work_so_far, run.par_vector,
                                                             max_step(y8, run.pars, prec))
    except onset_series.SeriesDoesNotSettle as err:
        raise run.unsupported(t, f"the contact slips at t = {t} (mu_req reached mu = {float(run.mu):.6g}): "
                                 f"the onset's series does not settle: {err}") from None
    alpha0 = onset_series.from_arb(prec, series.alpha[0])
    y = prec.array(list(y8) + [prec.zero(), alpha0, run.work_so_far])
    inside = run.outputs_before(t, t + t1, lambda tau: prec.array(onset_series.series_state(series, prec, tau, order,
                                                                                             run.work_so_far)))
    return "sliding", t + t1, prec.array(start), (t, y, inside)


def onset_directions(c: SlidingSystem, y8, par_vector, samples: int = 256) -> list:
    """[(alpha0, lambda)]: the directions in which a slip from s = 0 accelerates along itself, du/dt = lambda e.

    The roots in alpha of e_perp(alpha) . du/dt (the slip's acceleration with friction -mu N e(alpha),
    ``models.coulomb``'s ``slip_rate_across``) with lambda = e . du/dt > 0: bracketed on ``samples``
    directions, then bisected at the precision until the bracket stops shrinking.
    """
    prec = c.precision
    two_pi = 2 * pi_at(prec)
    alphas = [two_pi * prec.number(i) / prec.number(samples) - two_pi / 2 for i in range(samples + 1)]

    def rates(alpha):
        return evaluate(c.slip_rates, prec.array(list(y8) + [alpha]), par_vector)

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
    (:func:`onset`)."""
    return prec.number(2) ** -((bits(prec) + 2) // 3) * max_step(y8, pars, prec)


def second_order_start(c: SlidingSystem, y, lam, tau, par_vector):
    """The state a time ``tau`` after a slip's onset ``y`` (s = 0, alpha0, W): see :func:`onset`.

    The eight, s and alpha from their second-order Taylor polynomials, and the work W by Simpson's rule
    on the rate mu g N s along them (exact to O(tau^5) for them).
    """
    prec = c.precision
    y8, alpha0 = y[:8], y[DIRECTION]
    with np.errstate(divide="ignore", invalid="ignore"):  # d(alpha)/dt is 0/0 at s = 0 and is not read
        rate0 = evaluate(c.rhs_function, y, par_vector)

    def across(state8, alpha):
        return evaluate(c.slip_rates, prec.array(list(state8) + [alpha]), par_vector)[1]

    h = tau
    b_alpha = (across(y8, alpha0 + h) - across(y8, alpha0 - h)) / (2 * h)
    b_t = (across(y8 + h * rate0[:8], alpha0) - across(y8 - h * rate0[:8], alpha0)) / (2 * h)
    alpha1 = b_t / (lam - b_alpha)

    def along_path(dt):  # the rates on the first-order path, for the second derivatives
        p = y.copy()
        p[:8] = y8 + dt * rate0[:8]
        p[SLIP], p[DIRECTION] = lam * dt, alpha0 + alpha1 * dt
        return evaluate(c.rhs_function, p, par_vector)

    r1, r2 = along_path(h), along_path(2 * h)
    moving = list(range(8)) + [SLIP]
    second = {i: (-3 * rate0[i] + 4 * r1[i] - r2[i]) / (2 * h) for i in moving}

    def at(dt, alpha2):
        p = y.copy()
        for i in moving:
            p[i] = y[i] + dt * rate0[i] + dt * dt * second[i] / 2
        p[DIRECTION] = alpha0 + alpha1 * dt + alpha2 * dt * dt / 2
        return p

    def mismatch(alpha2):  # alpha's rate on the path at h against the path's own, alpha1 + alpha2 h
        return evaluate(c.rhs_function, at(h, alpha2), par_vector)[DIRECTION] - (alpha1 + alpha2 * h)

    # alpha2 puts the start on the regular solution to second order too: the rate is affine in alpha2
    # to far below eps there (alpha2 h^2 / 2 is a displacement of order h^2), so one secant step solves it
    m0, m1 = mismatch(prec.zero()), mismatch(prec.number(1))
    alpha2 = -m0 / (m1 - m0)
    start, middle = at(tau, alpha2), at(tau / 2, alpha2)
    work_rate = [evaluate(c.rhs_function, p, par_vector)[WORK] for p in (middle, start)]
    start[WORK] = y[WORK] + tau * (4 * work_rate[0] + work_rate[1]) / 6  # the rate is 0 at s = 0
    return start


def pi_at(prec: Precision):
    """pi as a number of ``prec``, read from a decimal string of enough digits."""
    with mpmath.workprec(bits(prec) + 16):
        return prec.number(mpmath.nstr(mpmath.pi, int(bits(prec) * 0.302) + 6))


def bits(prec: Precision) -> int:
    """The significand's bits of ``prec`` (from its epsilon)."""
    return int(round(1 - np.log2(prec.eps)))

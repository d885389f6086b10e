"""How a run of :func:`verify.engine.single.solve` ended: ``ok``, a terminal event, or a named failure.

A run either ends ``ok`` (at t_end) or at a terminal event, with every state it returns
inside the model's domain and, where the model has a contact and events are on, with a
positive normal force; or :class:`~verify.engine.trajectory.IntegrationError` is raised with
``outcome`` one of :data:`FAILURES`.  (With ``events=False`` nothing stops the run at the domain's
ends or at N = 0, by request -- the claims read how far theta goes past pi/2 that way --, and a run
whose theta left the domain is returned with ``outcome = "outside_domain"``, ``status = 2``: never
``ok``.)

* ``failed:non_finite`` -- heyoka stopped on a non-finite state (``taylor_outcome.err_nf_state``),
  or a returned state is not finite;
* ``failed:event_detection`` -- heyoka warned that its event detection failed (root finding gave
  up, or was skipped), or a state left the domain, or the normal force fell to N <= 0, without
  the terminal event that should have stopped the run there (heyoka's warnings are collected by
  :mod:`verify.engine.heyoka_log`, never printed);
* ``failed:step_size_collapse`` -- a segment of 2 pi radians of the fastest initial rate took
  more than 2 pi :data:`~verify.engine.segments.COLLAPSE_FACTOR` steps (2e5; a segment typically
  takes ~200): the steps averaged less than 2^-15 of the step cap
  (:func:`~verify.engine.problem.max_step`), a thousandth of the typical step (omega h ~ 0.03),
  i.e. the motion's rates grew a thousandfold over the fastest initial one (the largest growth in
  the suite's runs is ~25-fold, the standard disk dipping to theta = 0.25) -- a singularity of the
  equations, which a bounded-energy rolling body meets only at its domain's ends.  heyoka has no
  outcome for this (its step size shrinks without bound and the run never returns), so each
  segment is given this step budget (:mod:`verify.engine.segments`).

The error carries ``t`` (where the failure was seen), ``state`` and ``trajectory``: the run up
to its last valid output, with that outcome and ``status = -1``.
"""
from __future__ import annotations

import math

import heyoka as hy
import numpy as np

from models.base import Model
from models.symbols import STATE_NAMES

from . import invariants as inv
from . import validation
from .segments import COLLAPSE_FACTOR
from .trajectory import End, IntegrationError, Trajectory

#: Outcomes of a failed run (``IntegrationError.outcome``; the module docstring says when).
FAILURES = ("failed:non_finite", "failed:event_detection", "failed:step_size_collapse")

def as_float(values) -> np.ndarray:
    """Values of any precision's dtype as doubles (vectorised where numpy can cast the dtype)."""
    try:
        return np.asarray(values).astype(float)
    except (TypeError, ValueError):
        return np.array([float(v) for v in np.ravel(values)]).reshape(np.shape(values))


#: How far (in units of the precision's epsilon, times max(1, mu)) a returned state's mu_req may exceed the
#: friction coefficient before it counts as a missed ``slips`` event: far above the rounding of the
#: friction cfunc (some forty operations, each to half an ulp; its conditioning is of order 1 while
#: N/(Mg) is, and N <= 0 is caught before), far below what a missed event leaves behind, where mu_req
#: grows past mu at its own rate over the spacing of the outputs.
SLIP_SLACK_EPS = 2 ** 10


def failure(model: Model, compiled, run, t, y, pars, events: bool, messages, friction=None):
    """((outcome, number of valid leading outputs, message) of a failed run or None, normal force).

    The guard of the module docstring: heyoka's own failures first, then every returned state
    against the domain, (events on) the normal force and (with ``friction``) the friction it needs
    (:data:`SLIP_SLACK_EPS`); the normal force is returned for the record (None
    with events off or without a contact).  At a terminal event's own output the event's function
    is ~0 with either sign, so that one condition is not applied there.  Runs on every output of
    every run, so it works on whole arrays, converted to double as the checks always were.
    """
    name = model.name
    yf = as_float(y)
    finite = np.isfinite(yf).all(axis=0)
    if run.outcome == hy.taylor_outcome.err_nf_state or not finite.all():
        k = int(np.argmin(finite)) if not finite.all() else len(finite) - 1
        last = float(t[max(k - 1, 0)])
        return ("failed:non_finite", k, f"the integration of {name!r} failed after t = {last:.9g}: heyoka "
                f"reached a non-finite state ({_first_bad(y[:, k])}); the run is not reliable past t = {last:.9g}"), None
    if run.collapsed:
        k = len(t) - 1
        return ("failed:step_size_collapse", k, f"the integration of {name!r} failed at t = {float(t[k]):.9g}: the "
                f"step size collapsed (a segment of 2 pi / the fastest initial rate took more than "
                f"{int(2 * math.pi * COLLAPSE_FACTOR)} steps; the last was {float(run.last_h):.3g} s) -- the motion "
                f"runs into a singularity of the equations (state {_state_text(y[:, k])})"), None
    ev = _event_name(run.outcome, compiled)
    dom = model.domain
    lo, hi = validation.domain_ends(dom)
    th = yf[0]
    inside = (lo < th) & (th < hi)
    if ev in (dom.below, dom.above):
        inside[-1] = True
    detection = [m.text for m in messages if m.event_detection or m.level in ("error", "critical")]
    normal = validation.normal_force(compiled, y, pars) if events else None
    positive = np.ones(len(th), bool) if normal is None else as_float(normal) > 0
    if ev == "contact_lost":
        positive[-1] = True
    if not inside.all() and events:
        k = int(np.argmin(inside))
        why = f"without its terminal event ({dom.below if th[k] <= lo else dom.above}): heyoka's event detection failed"
        if detection:
            why += f" (heyoka: {detection[0]})"
        return ("failed:event_detection", k, f"the integration of {name!r} failed: at t = {float(t[k]):.9g} theta = "
                f"{th[k]:.9g} is outside its domain {lo:.9g} < theta < {hi:.9g}, {why}; the run is not reliable from there"), normal
    if not positive.all():
        k = int(np.argmin(positive))
        extra = f" (heyoka: {detection[0]})" if detection else ""
        return ("failed:event_detection", k, f"the integration of {name!r} failed: at t = {float(t[k]):.9g} the normal "
                f"force N/(Mg) = {float(normal[k]):.6g} <= 0 without the terminal event contact_lost: heyoka's event "
                f"detection failed{extra}; the run is not reliable from there"), normal
    if friction is not None:
        need = inv.friction_required(compiled, y, pars)
        eps = compiled.precision.eps
        within = need <= friction + SLIP_SLACK_EPS * eps * max(1, friction)
        if ev == "slips":
            within[-1] = True
        if not within.all():
            k = int(np.argmin(within))
            return ("failed:event_detection", k, f"the integration of {name!r} failed: at t = {float(t[k]):.9g} the "
                    f"rolling motion needs mu_req = {float(need[k]):.9g} > friction = {friction} without the terminal "
                    f"event slips: heyoka's event detection failed; the run is not reliable from there"), normal
    if detection:
        return ("failed:event_detection", len(t) - 1, f"the integration of {name!r} failed: heyoka's event detection "
                f"failed during the run ({detection[0]}); an event may have been missed"), normal
    return None, normal


def unstopped(model: Model, t, y, status, label, message):
    """events=False: a run whose theta left the domain is returned, labelled ``outside_domain``."""
    dom = model.domain
    lo, hi = validation.domain_ends(dom)
    th = as_float(y[0])
    outside = np.flatnonzero(~((lo < th) & (th < hi)))
    if not len(outside):
        return status, label, message
    k = int(outside[0])
    return 2, "outside_domain", (f"theta left the domain {lo:.9g} < theta < {hi:.9g} at t = {float(t[k]):.9g} "
                                 f"(theta = {th[k]:.9g}) and the run went on past it, as events=False asks; {message}")


def _event_name(outcome, compiled):
    code = int(outcome)
    names = [name for name, _, _ in compiled.events]
    if outcome != hy.taylor_outcome.time_limit and -len(names) <= code < 0:
        return names[-code - 1]
    return None


def _first_bad(col) -> str:
    for name, v in zip(STATE_NAMES, col):
        if not math.isfinite(float(v)):
            return f"{name} = {v}"
    return "?"


def _state_text(col) -> str:
    return ", ".join(f"{n} = {float(v):.6g}" for n, v in zip(STATE_NAMES, col))


def partial(model, compiled, prec, pars, t_end, t, y, good, label, message, steps, tol):
    """The run up to its last valid output, as a Trajectory with the failure's outcome (or None)."""
    keep = max(int(good), 1)
    t, y = t[:keep], np.ascontiguousarray(y[:, :keep])
    evaluation = inv.OnDemand(compiled, y, pars, drop_start=False)
    try:
        evaluation.traces  # evaluated now: a record that cannot be evaluated is not returned
    except Exception:  # noqa: BLE001 - a best-effort record of a failed run
        return None
    return Trajectory(
        model=model.name, equations=model.equations, precision=prec, params=pars, t_end=t_end, t=t, y=y,
        status=-1, message=message, outcome=label, t_events={}, steps=steps, tol=tol, evaluation=evaluation,
    )



def interpret(outcome, compiled, end: End):
    code = int(outcome)
    names = [name for name, _, _ in compiled.events]
    if outcome == hy.taylor_outcome.time_limit:
        return 0, "ok", "reached t_end", {}
    if -len(names) <= code < 0:
        name = names[-code - 1]
        return 1, f"event:{name}", f"stopped by the terminal event {name} at t = {end.time}", {name: end.time}
    raise IntegrationError(
        f"the integration of {compiled.model.name!r} failed at t = {end.time} with outcome {outcome} "
        f"(state {end.state})", "failed:" + str(outcome).rsplit(".", 1)[-1], end.time, end.state
    )



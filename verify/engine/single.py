"""Integrate a model by Taylor's method at any precision and return a named record.

Shaped like scipy's ``solve_ivp``: ``solve`` returns a :class:`Trajectory` with ``t``,
``y`` (one row per state component), ``status``, ``message``, the events that stopped it,
and the invariants with their drift; a failed integration raises
:class:`IntegrationError` instead of returning a short array.

The run is integrated in fixed segments between which phi, psi, x, y are moved out of the
integrator, so heyoka's error control does not loosen as they grow (:mod:`verify.engine.segments`);
how a run ends, and the failures it can raise (:data:`FAILURES`), are in
:mod:`verify.engine.failures`; the runs with more states and the auxiliary systems of the
studies in :mod:`verify.engine.auxiliary`.  Their public names are importable from here too.
"""
from __future__ import annotations

import math
import numbers

import numpy as np

from models.base import Model

from . import heyoka_log, integrators
from . import invariants as inv
from . import validation
from .auxiliary import ExtendedRun, GridRun, propagate_in_turns, through_grid  # noqa: F401 - public here too
from .failures import FAILURES, failure, interpret, partial, unstopped  # noqa: F401
from .invariants import InvariantTrace  # noqa: F401
from .problem import Problem, max_step, resolve_model  # noqa: F401
from .segments import COLLAPSE_FACTOR, PROGRESS_SECONDS, propagate_segments  # noqa: F401
from .trajectory import End, IntegrationError, Trajectory
from ..precision import Precision, parse_precision

#: The default number of output points when neither t_eval nor n_eval is given.
N_EVAL_DEFAULT = 101


def resolve_parameters(model: Model, values, precision: Precision) -> dict:
    """Every parameter of the model at ``precision``: defaults overridden by ``values``
    (:func:`verify.engine.validation.parameters`)."""
    return validation.parameters(model, values, precision)


def resolve_state(model: Model, values, precision: Precision) -> np.ndarray:
    """The eight-component initial state (a mapping, or eight values in state order); unset
    components are 0; theta must lie in the model's domain (:mod:`verify.engine.validation`)."""
    y0 = validation.state(model, values, precision)
    shown = [dict(values)] if isinstance(values, dict) else None
    problem = validation.first_problem(model, y0[:, None], None, shown)
    if problem is not None and problem[1] == "outside_domain":
        raise validation.InvalidStart(problem[2], problem[1])
    return y0


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
    n_eval=None,
    events: bool = True,
    high_accuracy: bool = False,
    progress=None,
    friction=None,
) -> Trajectory:
    """Integrate ``model`` from ``state`` at time 0 to ``t_end``.

    Parameters
    ----------
    model : str or Model
        A model name (``python -m verify models`` lists them) or a Model object.
    t_end : number or decimal string
        Final time in seconds, > 0.
    state : mapping or sequence, optional
        Initial values by name (unset components are 0), or all eight in the model's state
        order ``theta, phi, psi, thetadot, phidot, psidot, x, y`` (a list, tuple or 1-D array).
        Strings are read at ``precision``.
    params : mapping, optional
        Parameters by name; unset ones take the model's defaults.
    precision : {"double", "long", "quad", "mp:BITS"}
        BITS at least :data:`verify.precision.MIN_MPFR_BITS` (53).
    equations : {"derived", "paper"}
        The derived equations or the paper's as printed (ignored for a Model object).
    tol : number, optional
        Taylor tolerance; defaults to the precision's epsilon.
    t_eval : sequence, optional
        Output times in [0, t_end], strictly increasing; exactly these are returned (plus the
        time of a terminal event that stops the run before the last of them).
    n_eval : int, optional
        Else ``n_eval`` >= 2 equally spaced output times from 0 to t_end (default 101).  Give
        ``t_eval`` or ``n_eval``, not both.
    events : bool
        Stop at the domain's ends and at loss of contact (default True).  Without events
        neither is enforced (the integrator then has no events compiled at all); a run whose
        theta leaves the domain then ends ``outside_domain``.  What they cost, measured on the
        disk's standard start by ``benchmarks/event_costs.py`` (bare heyoka, t_end 10 / 100 s, 2
        shared cores): the domain's two ends +18 % / +8 %, ``contact_lost`` +53 % / +38 % (its
        function is the normal force, whose Taylor coefficients heyoka computes every step),
        all three +56 % / +42 %.
    high_accuracy : bool
        heyoka's high-accuracy mode (compensated summation of the Taylor series), for long runs
        where the energy error should follow Brouwer's law (``python -m verify bench`` measures it).
    progress : callable(t, steps), optional
        Called during the integration at most every 0.5 s of wall time with the time reached
        (a float, seconds) and the Taylor steps taken so far; not necessarily at the end.  It runs
        in the integrating thread; an exception it raises ends the run.  None (the default)
        costs nothing.
    friction : number or decimal string, optional
        A friction coefficient mu > 0 for a model that rolls: the run also stops at the terminal
        event ``slips`` (outcome ``event:slips``), where the friction the rolling motion needs,
        mu_req = |F_h|/N (``sol.friction_required``), reaches mu -- where a body on a table with that
        coefficient starts to slip.  Needs ``events=True``.  A start with mu_req >= mu is refused
        (:class:`~verify.engine.validation.InvalidStart`, reason ``slips``).  None (the default):
        unlimited friction, no such event.

    Raises
    ------
    ValueError
        For bad input (unknown names, non-finite values, out-of-range parameters, states
        outside the domain or with N <= 0 -- :class:`verify.engine.validation.InvalidStart` --,
        non-positive tolerance, bad grids, unknown precision).
    IntegrationError
        If the integration fails; ``outcome`` is one of :data:`FAILURES` (:mod:`verify.engine.failures`).
    """
    prec = parse_precision(precision)
    model = resolve_model(model, equations)
    t_end = validation.positive_number("t_end", t_end, prec)
    tol_value = validation.tolerance(tol, prec)
    grid, with_start = _grid(t_end, t_eval, n_eval, prec)
    events = validation.flag("events", events)
    high_accuracy = validation.flag("high_accuracy", high_accuracy)
    if progress is not None and not callable(progress):
        raise ValueError(f"progress={progress!r} is not callable; allowed: None or a function progress(t, steps)")
    friction = validation.friction(model, friction, events, prec)
    y0, pars = validation.validate(model, state, params, prec, friction=friction)  # compiles the model to check N
    return propagate(Problem(model, prec, pars, y0, tol_value, events, high_accuracy, friction), t_end, grid,
                     with_start, progress)


def propagate(problem: Problem, t_end, grid, with_start: bool = True, progress=None) -> Trajectory:
    """Run a validated :class:`~verify.engine.problem.Problem` through ``grid`` (from t = 0) to ``t_end``.

    ``grid`` is an array at the problem's precision starting at 0 (:func:`solve` makes it from
    ``t_eval`` / ``n_eval``); ``with_start`` says whether t = 0 is an output.  The integrator is
    borrowed from :mod:`verify.engine.integrators`; the invariants are evaluated when first read
    (:class:`verify.engine.invariants.OnDemand`), on every output of the run.
    """
    model, prec, pars, y0 = problem.model, problem.precision, problem.params, problem.y0
    compiled = problem.compiled
    key, build = integrators.for_model(compiled, problem.tol, events=problem.events,
                                       high_accuracy=problem.high_accuracy)
    with integrators.borrowed(key, build, prec.zero(), y0, problem.par_vector) as ta:
        with heyoka_log.collect() as messages:
            run = propagate_segments(ta, grid, t_end, problem.max_step, prec, progress)
        end = End(ta.time, list(ta.state), ta.tol)
    t, y = run.t, np.ascontiguousarray(run.y.T)
    fail, normal = failure(model, compiled, run, t, y, pars, problem.events, messages, problem.friction)
    if fail is not None:
        label, good, message = fail
        record = partial(model, compiled, prec, pars, t_end, t, y, good, label, message, run.steps, end.tol)
        raise IntegrationError(message, label, end.time, end.state, record)
    status, label, message, t_events = interpret(run.outcome, compiled, end)
    if not problem.events:
        status, label, message = unstopped(model, t, y, status, label, message)
    lazy = inv.OnDemand(compiled, y, pars, drop_start=not with_start, normal=normal)
    if not with_start:  # t = 0 was integrated from, not asked for
        t, y = t[1:], np.ascontiguousarray(y[:, 1:])
    return Trajectory(
        model=model.name, equations=model.equations, precision=prec, params=pars, t_end=t_end, t=t, y=y,
        status=status, message=message, outcome=label, t_events=t_events, steps=run.steps, tol=end.tol,
        evaluation=lazy, friction=problem.friction,
    )


def _grid(t_end, t_eval, n_eval, prec: Precision):
    """(integration grid from t = 0, whether t = 0 is an output) for ``t_eval`` or ``n_eval``."""
    if t_eval is not None and n_eval is not None:
        raise ValueError(f"t_eval and n_eval={n_eval!r} are both given; allowed: one of them (t_eval: the output "
                         "times; n_eval: that many equally spaced ones)")
    if t_eval is None:
        n_eval = N_EVAL_DEFAULT if n_eval is None else n_eval
        if isinstance(n_eval, bool) or not isinstance(n_eval, numbers.Integral):
            raise ValueError(f"n_eval={n_eval!r} is not an integer; allowed: an integer >= 2 (the start and t_end)")
        if n_eval < 2:
            raise ValueError(f"n_eval={n_eval} must be at least 2 (the start and t_end)")
        n = int(n_eval) - 1
        if prec.name in ("double", "long") and n < 2 ** 53:  # the same roundings, one array operation
            inner = (t_end * np.arange(1, n, dtype=prec.fp_type)) / prec.fp_type(n)
            pts = np.concatenate([[prec.fp_type(0)], inner, [t_end]]).astype(prec.fp_type)
        else:
            pts = prec.array([prec.zero()] + [t_end * prec.number(i) / prec.number(n) for i in range(1, n)] + [t_end])
        rising = pts[1:] > pts[:-1]
        if not np.all(rising):
            i = int(np.argmin(rising))
            a, b = pts[i], pts[i + 1]
            raise ValueError(f"n_eval={n_eval}: the grid k t_end / {n} is not strictly increasing in {prec.name} "
                             f"(t_{i} = {a}, t_{i + 1} = {b}); allowed: fewer points, a longer t_end or more bits")
        return pts, True
    if isinstance(t_eval, (str, bytes)) or not hasattr(t_eval, "__iter__"):
        raise ValueError(f"t_eval={t_eval!r}: allowed: a sequence of times in [0, t_end], strictly increasing")
    pts = []
    for v in t_eval:
        try:
            p = v if isinstance(v, type(t_end)) else prec.number(v)
        except (ValueError, TypeError) as err:
            raise ValueError(f"t_eval value {v!r}: {err}") from None
        if not math.isfinite(float(p)):
            raise ValueError(f"t_eval value {v!r} is not a finite number")
        pts.append(p)
    if not pts:
        raise ValueError("t_eval is empty; allowed: one or more times in [0, t_end], strictly increasing")
    for a, b in zip(pts, pts[1:]):
        if not b > a:
            raise ValueError(f"t_eval must be strictly increasing; {b} follows {a}")
    if pts[0] < 0 or pts[-1] > t_end:
        raise ValueError(f"t_eval must lie in [0, t_end={t_end}]; it runs from {pts[0]} to {pts[-1]}")
    with_start = not pts[0] > 0
    if with_start:
        pts[0] = prec.zero()
    else:
        pts = [prec.zero()] + pts
    return prec.array(pts), with_start



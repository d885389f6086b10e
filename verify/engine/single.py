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
only through x', y'), so the run is cut into fixed segments and between segments they
are moved into offsets kept outside the integrator: phi and psi by whole turns (exact multiples of the precision's
2 pi, so sin and cos of phi are unchanged), x and y entirely.  The returned phi, psi,
x, y are the offsets plus the reduced values: continuous, never reduced modulo 2 pi.

Failures
--------
A run either ends ``ok`` (at t_end) or at a terminal event, with every state it returns
inside the model's domain and, where the model has a contact and events are on, with a
positive normal force; or :class:`IntegrationError` is raised with ``outcome`` one of
:data:`FAILURES`.  (With ``events=False`` nothing stops the run at the domain's ends or at N = 0,
by request -- the claims read how far theta goes past pi/2 that way --, and a run whose theta
left the domain is returned with ``outcome = "outside_domain"``, ``status = 2``: never ``ok``.)

* ``failed:non_finite`` -- heyoka stopped on a non-finite state (``taylor_outcome.err_nf_state``),
  or a returned state is not finite;
* ``failed:event_detection`` -- heyoka warned that its event detection failed (root finding gave
  up, or was skipped), or a state left the domain, or the normal force fell to N <= 0, without
  the terminal event that should have stopped the run there (heyoka's warnings are collected by
  :mod:`verify.engine.heyoka_log`, never printed);
* ``failed:step_size_collapse`` -- a segment of 2 pi radians of the fastest initial rate took
  more than 2 pi :data:`COLLAPSE_FACTOR` steps (2e5; a segment typically takes ~200): the steps
  averaged less than 2^-15 of the step cap (:func:`max_step`), a thousandth of the typical step
  (omega h ~ 0.03), i.e. the motion's rates grew a thousandfold over the fastest initial one (the
  largest growth in the suite's runs is ~25-fold, the standard disk dipping to theta = 0.25) -- a
  singularity of the equations, which a bounded-energy rolling body meets only at its domain's
  ends.  heyoka has no outcome for this (its step size shrinks without bound and the run never
  returns), so each segment is given this step budget.

The error carries ``t`` (where the failure was seen), ``state`` and ``trajectory``: the run up
to its last valid output, with that outcome and ``status = -1``.
"""
from __future__ import annotations

import math
import numbers
import time
from dataclasses import dataclass, field

import heyoka as hy
import mpmath
import numpy as np

from models.base import Model
from models.symbols import STATE_NAMES

from . import heyoka_log, integrators
from . import invariants as inv
from . import validation
from .invariants import InvariantTrace
from .problem import Problem, max_step, resolve_model
from ..precision import Precision, parse_precision

_CYCLIC = (1, 2, 6, 7)  # phi, psi, x, y
_ANGLES = (1, 2)

#: Outcomes of a failed run (``IntegrationError.outcome``; the module docstring says when).
FAILURES = ("failed:non_finite", "failed:event_detection", "failed:step_size_collapse")
#: A segment (2 pi radians of the fastest initial rate) may take 2 pi COLLAPSE_FACTOR steps.
COLLAPSE_FACTOR = 2 ** 15
#: The progress hook is called at most this often (seconds of wall time).
PROGRESS_SECONDS = 0.5
#: The default number of output points when neither t_eval nor n_eval is given.
N_EVAL_DEFAULT = 101


class IntegrationError(RuntimeError):
    """The integration failed; ``outcome`` says how (one of :data:`FAILURES`).

    ``t`` and ``state`` are where the failure was seen; ``trajectory`` is the run up to its last
    valid output (a :class:`Trajectory` with that outcome and ``status = -1``), or None.
    """

    def __init__(self, message: str, outcome: str = "failed", t=None, state=None, trajectory=None):
        super().__init__(message)
        self.outcome, self.t, self.state, self.trajectory = outcome, t, state, trajectory


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
        0 when ``t_end`` was reached, 1 when a terminal event stopped the run, 2 when a run
        without events reached t_end after its theta left the domain (-1 only on the partial
        record an :class:`IntegrationError` carries).
    outcome : str
        ``"ok"`` or ``"event:<name>"`` (``lies_flat``, ``rim_switch``, ``contact_lost``, ...);
        ``"outside_domain"`` (status 2, ``events=False`` only); ``"failed:<reason>"`` only on an
        :class:`IntegrationError`'s partial record.
    steps : int
        Taylor steps taken.
    invariants : dict of name -> InvariantTrace (property)
        Energy first, then the model's other conserved quantities; each with its values and
        ``max_abs_drift``, ``max_rel_drift`` (over |I(0)|) and ``max_drift_vs_terms`` (over
        the magnitudes of I's terms), see :class:`verify.engine.invariants.InvariantTrace`.
        Evaluated when first read (Chaplygin's closed form costs milliseconds a point), then
        kept; the drifts cover every output of the run.
    normal_force : ndarray or None (property)
        N / (M g) on the grid (contact holds while it is positive); None without a contact.
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
    evaluation: inv.OnDemand = field(repr=False, compare=False)
    state_names: tuple = STATE_NAMES

    @property
    def invariants(self) -> dict:
        return self.evaluation.traces

    @property
    def normal_force(self):
        return self.evaluation.normal_force

    @property
    def success(self) -> bool:
        return self.status >= 0

    def __getitem__(self, name: str) -> np.ndarray:
        return self.y[STATE_NAMES.index(name)]

    @property
    def final_state(self) -> dict:
        return {n: self.y[i, -1] for i, n in enumerate(STATE_NAMES)}


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


def _integer_reader(precision: Precision):
    """n -> the integer n at ``precision``, as ``precision.number`` reads it (exactly: |n| < 2^53 here),
    without its general path (a Fraction per call) where the type takes an int exactly itself."""
    if precision.name in ("double", "long"):
        return precision.fp_type
    return precision.number


class _Offsets:
    """phi, psi, x, y moved out of the integrator (module docstring)."""

    def __init__(self, precision: Precision):
        self.fp = _integer_reader(precision)
        with mpmath.workprec(precision.bits + 32):
            self.two_pi = precision.number(2 * mpmath.pi)
        self.limit = {1: float(self.two_pi), 2: float(self.two_pi), 6: 1.0, 7: 1.0}
        self.value = {i: precision.zero() for i in _CYCLIC}

    def rebase(self, st) -> None:
        """Move whole turns of phi, psi and all of x, y from the state into the offsets."""
        for i in _CYCLIC:
            v = st[i]
            if abs(float(v)) <= self.limit[i]:
                continue
            turns = self.fp(round(float(v) / float(self.two_pi))) * self.two_pi if i in _ANGLES else v
            st[i] = v - turns
            self.value[i] = self.value[i] + turns

    def restore_rows(self, rows) -> list:
        """:meth:`restore` of every row of a 2-D block, one array addition per cyclic column."""
        rows = np.array(rows)
        for i in _CYCLIC:
            rows[:, i] = rows[:, i] + self.value[i]
        return list(rows)

    def restore(self, row) -> np.ndarray:
        row = np.array(row)
        for i in _CYCLIC:
            row[i] = row[i] + self.value[i]
        return row


class _Clock:
    """Calls a progress hook at most every PROGRESS_SECONDS of wall time.

    It is asked after every segment (cheap: a clock read).  Where one segment takes longer than
    PROGRESS_SECONDS (slow precisions: MPFR at hundreds of bits), it is also asked after every
    step through heyoka's step callback, whose cost (~1 us) is then negligible beside the step's.
    Neither changes a step: the callback only reads the time.
    """

    def __init__(self, hook):
        self.hook = hook
        self.last = self.mark = time.monotonic()
        self.per_step = False
        self.steps_before = 0  # steps of the finished segments

    def check(self, t, steps: int) -> None:
        now = time.monotonic()
        if now - self.last >= PROGRESS_SECONDS:
            self.last = now
            self.hook(float(t), int(steps))

    def segment_done(self, t, steps: int) -> None:
        now = time.monotonic()
        if now - self.mark > PROGRESS_SECONDS:
            self.per_step = True
        self.mark = now
        self.steps_before = steps
        self.check(t, steps)

    def callback(self):
        if not self.per_step:
            return None
        base = self.steps_before

        class _Step:
            n = 0

            def __call__(inner, ta):  # noqa: N805 - heyoka calls it with the integrator
                inner.n += 1
                self.check(ta.time, base + inner.n)
                return True

        return _Step()


@dataclass
class _Run:
    outcome: object
    steps: int
    times: list
    states: list
    collapsed: bool = False
    last_h: object = None


def _propagate(ta, grid, t_end, h_max, prec: Precision, progress=None) -> _Run:
    """Integrate over fixed segments of 2 pi h_max, rebasing between them.

    A segment is one ``propagate_grid`` call (heyoka's C++ loop, dense output at the grid
    points inside it), so the Python cost is per segment, not per step; a segment holds at
    least 2 pi steps (h <= h_max) and typically hundreds.  Segment ends depend on t_end and
    the initial rates only, so the steps, and the bits of the result, do not depend on the
    output grid.  A segment may take at most 2 pi COLLAPSE_FACTOR steps (``max_steps``; beyond
    that the step size has collapsed, see the module docstring).  The ``progress`` hook is
    called between segments, or from heyoka's step callback where segments are slow
    (:class:`_Clock`); segments are never split for it (a new ``propagate_grid`` call from
    inside a segment would start with a tiny step to the double-rounded time and change the
    bits), so the result is the same with or without it (tests/test_api.py).
    """
    offsets = _Offsets(prec)
    integer = _integer_reader(prec)
    seg = prec.number(2 * math.pi) * h_max
    budget = int(2 * math.pi * COLLAPSE_FACTOR)
    clock = _Clock(progress) if progress is not None else None
    run = _Run(hy.taylor_outcome.time_limit, 0, [grid[0]], [np.array(ta.state)])
    j, k = 1, 1  # next output grid index, segment number
    while True:
        end = integer(k) * seg
        if not end < t_end:
            end = t_end
        inside = []
        while j < len(grid) and grid[j] < end:
            inside.append(grid[j])
            j += 1
        kwargs = {"max_delta_t": h_max, "max_steps": budget}
        if clock is not None and clock.per_step:
            kwargs["callback"] = clock.callback()
        res = ta.propagate_grid(prec.array([ta.time] + inside + [end]), **kwargs)
        outcome, run.steps = res[0], run.steps + int(res[3])
        rows = res[-1][1:]
        if len(rows):
            kept = rows[: len(inside)]
            run.times.extend(inside[: len(kept)])
            run.states.extend(offsets.restore_rows(kept))
        finished = len(rows) == len(inside) + 1  # (heyoka says step_limit when the budget ends on t_end)
        if outcome == hy.taylor_outcome.step_limit and not finished:  # the step size collapsed
            run.outcome, run.collapsed, run.last_h = outcome, True, ta.last_h
            run.times.append(ta.time)
            run.states.append(offsets.restore(ta.state))
            return run
        if outcome not in (hy.taylor_outcome.time_limit, hy.taylor_outcome.step_limit):  # an event or a failure
            run.outcome = outcome
            run.times.append(ta.time)
            run.states.append(offsets.restore(ta.state))
            return run
        run.outcome = hy.taylor_outcome.time_limit
        if j < len(grid) and not grid[j] > end:  # the segment end is itself an output point
            run.times.append(end)
            run.states.append(offsets.restore(ta.state))
            j += 1
        if clock is not None:
            clock.segment_done(ta.time, run.steps)
        if not end < t_end:
            return run
        offsets.rebase(ta.state)
        k += 1


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

    Raises
    ------
    ValueError
        For bad input (unknown names, non-finite values, out-of-range parameters, states
        outside the domain or with N <= 0 -- :class:`verify.engine.validation.InvalidStart` --,
        non-positive tolerance, bad grids, unknown precision).
    IntegrationError
        If the integration fails; ``outcome`` is one of :data:`FAILURES` (module docstring).
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
    y0, pars = validation.validate(model, state, params, prec)  # compiles the model only to check N
    return propagate(Problem(model, prec, pars, y0, tol_value, events, high_accuracy), t_end, grid, with_start,
                     progress)


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
            run = _propagate(ta, grid, t_end, problem.max_step, prec, progress)
        end = _End(ta.time, list(ta.state), ta.tol)
    t = prec.array(run.times)
    y = np.ascontiguousarray(np.array(run.states).T)
    fail, normal = _failure(model, compiled, run, t, y, pars, problem.events, messages)
    if fail is not None:
        label, good, message = fail
        partial = _partial(model, compiled, prec, pars, t_end, t, y, good, label, message, run.steps, end.tol)
        raise IntegrationError(message, label, end.time, end.state, partial)
    status, label, message, t_events = _interpret(run.outcome, compiled, end)
    if not problem.events:
        status, label, message = _unstopped(model, t, y, status, label, message)
    lazy = inv.OnDemand(compiled, y, pars, drop_start=not with_start, normal=normal)
    if not with_start:  # t = 0 was integrated from, not asked for
        t, y = t[1:], np.ascontiguousarray(y[:, 1:])
    return Trajectory(
        model=model.name, equations=model.equations, precision=prec, params=pars, t_end=t_end, t=t, y=y,
        status=status, message=message, outcome=label, t_events=t_events, steps=run.steps, tol=end.tol,
        evaluation=lazy,
    )


@dataclass(frozen=True)
class _End:
    """Where the integrator stopped (read before it is given back to the pool)."""

    time: object
    state: list
    tol: object


def _as_float(values) -> np.ndarray:
    """Values of any precision's dtype as doubles (vectorised where numpy can cast the dtype)."""
    try:
        return np.asarray(values).astype(float)
    except (TypeError, ValueError):
        return np.array([float(v) for v in np.ravel(values)]).reshape(np.shape(values))


def _failure(model: Model, compiled, run: _Run, t, y, pars, events: bool, messages):
    """((outcome, number of valid leading outputs, message) of a failed run or None, normal force).

    The guard of the module docstring: heyoka's own failures first, then every returned state
    against the domain and (events on) the normal force, which is returned for the record (None
    with events off or without a contact).  At a terminal event's own output the event's function
    is ~0 with either sign, so that one condition is not applied there.  Runs on every output of
    every run, so it works on whole arrays, converted to double as the checks always were.
    """
    name = model.name
    yf = _as_float(y)
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
    lo, hi = float(dom.theta_min), float(dom.theta_max)
    th = yf[0]
    inside = (lo < th) & (th < hi)
    if ev in (dom.below, dom.above):
        inside[-1] = True
    detection = [m.text for m in messages if m.event_detection or m.level in ("error", "critical")]
    normal = validation.normal_force(compiled, y, pars) if events else None
    positive = np.ones(len(th), bool) if normal is None else _as_float(normal) > 0
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
    if detection:
        return ("failed:event_detection", len(t) - 1, f"the integration of {name!r} failed: heyoka's event detection "
                f"failed during the run ({detection[0]}); an event may have been missed"), normal
    return None, normal


def _unstopped(model: Model, t, y, status, label, message):
    """events=False: a run whose theta left the domain is returned, labelled ``outside_domain``."""
    dom = model.domain
    lo, hi = float(dom.theta_min), float(dom.theta_max)
    th = np.array([float(v) for v in y[0]])
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


def _partial(model, compiled, prec, pars, t_end, t, y, good, label, message, steps, tol):
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


def _interpret(outcome, compiled, end: _End):
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


# --- runs with more states: segments of a number of radians of the current fastest rate -----------

@dataclass(frozen=True)
class ExtendedRun:
    """A run of a model's equations with more states (:func:`propagate_in_turns`).

    ``t`` the start and the output times reached (plus the time of a terminal event that stopped
    the run); ``y`` one row per state (the eight of STATE_NAMES, phi and psi continuous, then the
    extra states in their order); ``outcome`` ``"ok"`` or ``"event:<name>"``; ``steps`` Taylor steps.
    """

    t: np.ndarray
    y: np.ndarray
    outcome: str
    steps: int


def propagate_in_turns(problem: Problem, t_eval, extra_states: tuple = (), extra_start=(), theta_stop=None,
                       segment_radians: float = 32 * math.pi) -> ExtendedRun:
    """Integrate ``problem`` with ``extra_states`` alongside, to the last of ``t_eval`` or a terminal event.

    ``extra_states`` are (name, sympy right-hand side) pairs (e.g. the work a dissipative couple
    has done), started at ``extra_start``; ``theta_stop`` (a number at the problem's precision)
    adds a terminal event ``theta_stop`` where theta falls through it.  Tolerance epsilon, the
    model's terminal events on, steps at most ``problem.max_step``.

    The run goes output time by output time, each in segments of ``segment_radians`` of the
    fastest rate at the segment's start (one ``propagate_until`` each); after a segment, phi
    and psi are moved back by whole turns when they exceed ``segment_radians``, the turns are
    counted and added back (exactly: the precision's 2 pi times the count) in the returned
    rows, so they are continuous.  Unlike :func:`solve`'s fixed segments, the segment ends
    depend on the run's own rates, so the bits of a run depend on its output times.
    """
    prec, compiled = problem.precision, problem.compiled
    key, build = integrators.for_extended(compiled, tuple(extra_states), theta_stop is not None)
    names = [name for name, _, _ in compiled.events] + (["theta_stop"] if theta_stop is not None else [])
    pars = compiled.parameter_vector(problem.params, every=True)
    if theta_stop is not None:
        pars = prec.array(list(pars) + [theta_stop])
    start = prec.array(list(problem.y0) + list(extra_start))
    with integrators.borrowed(key, build, prec.zero(), start, pars) as ta:
        outcome, steps, times, rows = _in_turns(ta, t_eval, problem.max_step, prec, segment_radians)
        end = _End(ta.time, list(ta.state), ta.tol)
    if outcome == hy.taylor_outcome.time_limit:
        label = "ok"
    elif -len(names) <= int(outcome) < 0:
        label = f"event:{names[-int(outcome) - 1]}"
    else:
        raise IntegrationError(f"the run of {compiled.model.name!r} failed at t = {end.time} with outcome {outcome}",
                               "failed:" + str(outcome).rsplit(".", 1)[-1], end.time, end.state)
    return ExtendedRun(prec.array(times), np.ascontiguousarray(np.array(rows).T), label, steps)


def _in_turns(ta, grid, h_max, prec: Precision, segment_radians: float):
    """(outcome, steps, times, rows) of :func:`propagate_in_turns`; if an event stopped the run its
    state is the last row."""
    with mpmath.workprec(prec.bits + 32):
        two_pi = prec.number(2 * mpmath.pi)
    turns = {1: 0, 2: 0}
    times, rows, steps = [ta.time], [np.array(ta.state)], 0
    for target in grid:
        while ta.time < target:
            rate = max(abs(float(ta.state[i])) for i in (3, 4, 5)) + 1.0
            end = min(target, ta.time + prec.number(segment_radians / rate))
            res = ta.propagate_until(end, max_delta_t=h_max)
            outcome, steps = res[0], steps + int(res[3])
            if outcome != hy.taylor_outcome.time_limit:
                times.append(ta.time)
                rows.append(_with_turns(ta.state, turns, two_pi, prec))
                return outcome, steps, times, rows
            for i in turns:
                n = round(float(ta.state[i]) / float(two_pi))
                if abs(float(ta.state[i])) > segment_radians:
                    ta.state[i] = ta.state[i] - prec.number(n) * two_pi
                    turns[i] += n
        times.append(ta.time)
        rows.append(_with_turns(ta.state, turns, two_pi, prec))
    return hy.taylor_outcome.time_limit, steps, times, rows


def _with_turns(state, turns, two_pi, prec):
    row = np.array(state)
    for i, n in turns.items():
        row[i] = row[i] + prec.number(n) * two_pi
    return row


# --- any small system through a grid (auxiliary ODEs of the studies) --------------------------------

@dataclass(frozen=True)
class GridRun:
    """A run of :func:`through_grid`: ``reached`` whether every grid point was reached, ``outcome``
    heyoka's outcome as text, ``rows`` the states at the grid points reached (one row each)."""

    reached: bool
    outcome: str
    rows: np.ndarray


def through_grid(key, system, start, pars, grid, precision="double") -> GridRun:
    """Integrate a heyoka ``system`` ((variable, expression) pairs) from ``start`` at ``grid[0]``
    through ``grid`` (tolerance epsilon of ``precision``; no events).

    ``key`` names the system for the integrator pool (:mod:`verify.engine.integrators`): the same
    key must always mean the same system.  For auxiliary equations of the studies, such as a drift
    integrated with theta as the independent variable.
    """
    prec = parse_precision(precision)

    def build():
        return hy.taylor_adaptive(list(system), prec.array([0] * len(system)), pars=prec.array([0] * len(pars)),
                                  tol=prec.zero(), **prec.integrator_kwargs())

    grid = prec.array(grid)
    with integrators.borrowed(("system", key, prec), build, grid[0], prec.array(start), prec.array(pars)) as ta:
        res = ta.propagate_grid(grid)
    rows = res[-1]
    return GridRun(len(rows) == len(grid), str(res[0]), rows)

"""Runs for the studies beside :func:`verify.engine.single.solve`: the model's equations with more
states (:func:`propagate_in_turns`), and any small system through a grid (:func:`through_grid`)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import heyoka as hy
import numpy as np

from . import integrators, segments
from .compile import to_heyoka
from .problem import Problem
from .trajectory import End, IntegrationError
from ..precision import Precision, parse_precision

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
        end = End(ta.time, list(ta.state), ta.tol)
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
    two_pi = segments.two_pi(prec)
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


def sympy_system(states, time=None, parameters=()) -> list:
    """A small system for :func:`through_grid` from sympy: ``states`` (name, symbol or None, right-hand side).

    Each state's symbol (None: it appears on no right-hand side) becomes its variable, ``time`` (a
    symbol, e.g. theta for a drift integrated with theta as the independent variable) heyoka's time,
    and ``parameters[i]`` ``par[i]``; constants are refused as :func:`verify.engine.compile.to_heyoka`
    refuses them.  The studies describe their auxiliary equations this way and never build heyoka
    expressions themselves.
    """
    names = [name for name, _, _ in states]
    variables = hy.make_vars(*names) if len(names) > 1 else [hy.make_vars(*names)]
    mapping = {sym: var for (_, sym, _), var in zip(states, variables) if sym is not None}
    if time is not None:
        mapping[time] = hy.time
    mapping.update({p: hy.par[i] for i, p in enumerate(parameters)})
    return [(var, to_heyoka(rhs, mapping, compact=True)) for var, (_, _, rhs) in zip(variables, states)]


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

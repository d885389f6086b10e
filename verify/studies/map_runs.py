"""The runs of a stability map: the reduced system compiled for heyoka's batch mode, every lane's
start and parameters, and the ensemble propagation reduced to each run's largest deviation
(:mod:`verify.studies.maps` describes the protocol, how it runs and why it is deterministic).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Optional

import heyoka as hy
import mpmath
import numpy as np

from models import get_model
from models.symbols import phidot, psidot, theta, thetadot

from . import thresholds
from ..engine import batch

SAMPLES_PER_RADIAN = 4  # dense-output samples per radian of the fastest rate (see sample_times)
CHUNK = 64  # batches per ensemble call: bounds the memory of the dense output held at once
_EXTRA = ("alive", "reason", "t_left", "lower", "upper")  # per-lane parameters after the model's


@lru_cache(maxsize=None)
def reduced_system(name: str):
    """heyoka form of the reduced system of model ``name``, with the freezing factor.

    Returns ``(variables, system, events, n_model_pars)``: ``events`` are
    ``(name, expression, direction)`` -- theta at the lower and upper bound (runtime
    parameters), and the normal force where the model has a contact.
    """
    from verify.engine.compile import contact_event, to_heyoka

    model = get_model(name)
    variables = hy.make_vars("theta", "thetadot", "phidot", "psidot")
    mapping = dict(zip((theta, thetadot, phidot, psidot), variables))
    n = len(model.parameters)
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    alive, lower, upper = hy.par[n], hy.par[n + 3], hy.par[n + 4]
    rhs = [thetadot] + list(model.accelerations)
    allowed = set(mapping)
    for expr in rhs + ([model.normal_force] if model.normal_force is not None else []):
        extra = expr.free_symbols - allowed
        if extra:
            raise RuntimeError(f"model {name!r}: the reduced system depends on {sorted(map(str, extra))}")
    unscaled = [to_heyoka(r, mapping) for r in rhs]
    system = [(v, r * alive) for v, r in zip(variables, unscaled)]
    th = variables[0]
    events = [("below", th - lower, hy.event_direction.negative),
              ("above", th - upper, hy.event_direction.positive)]
    if model.normal_force is not None:
        # on the system's own accelerations, so that heyoka computes them once (compile.contact_event)
        events.append(("contact_lost", contact_event(model, mapping, unscaled[1:]), hy.event_direction.negative))
    return tuple(variables), tuple(system), tuple(events), n


@lru_cache(maxsize=None)
def template(name: str, batch_size: int, cooldown: float):
    """A batch integrator of the reduced system (compiled once; copied by every ensemble iteration).

    A frozen lane is parked in the middle of its bounds with thetadot = 0, so that it never sits
    on a singular end of the domain.
    """
    variables, system, events, n = reduced_system(name)
    model = get_model(name)
    return batch.batch_system(system, events, batch.Lanes(n, n + 1, n + 2), n + len(_EXTRA), batch_size, cooldown, np.ones(4),
                              [float(p.default) for p in model.parameters], park=((1, 0.0),),
                              park_between=(0, n + 3, n + 4))


# --- the grid of runs ------------------------------------------------------------------------

def sample_times(t_end: float, fastest: float) -> np.ndarray:
    """The dense-output times: uniform, SAMPLES_PER_RADIAN samples per radian of ``fastest``.

    The nutation frequency of the models here is at most ~1.6 times the fastest rate, so a
    nutation period holds >= 15 samples and the sampled maximum of an oscillation is low by
    at most 1 - cos(pi/15) ~ 2%.

    Parameters
    ----------
    t_end : float
        Length of the run (s).
    fastest : float
        The fastest rate of the map, or sqrt(g) if larger (rad/s).

    Returns
    -------
    ndarray
        ``ceil(t_end * fastest * SAMPLES_PER_RADIAN) + 1`` times from 0 to ``t_end``.
    """
    n = max(2, int(math.ceil(t_end * fastest * SAMPLES_PER_RADIAN)) + 1)
    return np.linspace(0.0, t_end, n)


def _steady(name, motion, rate, params, tmin, tmax) -> dict:
    """thresholds.steady_state at ``rate``, or ValueError when no such steady motion exists there."""
    s = thresholds.steady_state(name, motion, repr(rate), params)
    try:
        th = float(mpmath.mpf(s["theta"]))
    except (TypeError, ValueError):
        th = math.nan
    if not tmin <= th <= tmax:
        raise ValueError(f"rate {rate!r} has no steady {motion} of {name!r} (theta = {s['theta']}); allowed: rates "
                         f"at which the steady motion exists with {tmin:.6g} <= theta <= {tmax:.6g}")
    return s


def _initial_conditions(name, motion, rates, tilts, params, cap):
    """Per-point initial state, bounds and steady angle, in map order (tilt-major)."""
    model = get_model(name)
    dom = model.domain
    tmin, tmax = float(dom.theta_min), float(dom.theta_max)
    steady = [_steady(name, motion, float(r), params, tmin, tmax) for r in rates]
    ths = np.array([float(mpmath.mpf(s["theta"])) for s in steady])
    n = len(tilts) * len(rates)
    y0 = np.zeros((4, n))
    bounds = np.zeros((2, n))
    with mpmath.workdps(40):
        for i, tilt in enumerate(tilts):
            for j, s in enumerate(steady):
                k = i * len(rates) + j
                th0 = mpmath.mpf(s["theta"])
                lo, hi = max(float(th0 - cap), tmin), min(float(th0 + cap), tmax)
                start = float(th0 + mpmath.mpf(float(tilt)))
                if not lo < start < hi:
                    raise ValueError(f"tilt {float(tilt)!r} at rate {float(rates[j])!r} starts theta at {start!r}, "
                                     f"outside ({lo!r}, {hi!r}); allowed: tilts below the cap {cap} that keep "
                                     f"theta inside the domain of {name!r}")
                y0[:, k] = (start, 0.0, float(mpmath.mpf(s["phidot"])), float(mpmath.mpf(s["psidot"])))
                bounds[:, k] = (lo, hi)
    return y0, bounds, ths


def _lane_arrays(y0, bounds, pars, batch_size):
    """States and parameters for every lane, padded to whole batches by repeating the last point."""
    n = y0.shape[1]
    padded = -(-n // batch_size) * batch_size
    idx = np.minimum(np.arange(padded), n - 1)
    states = np.ascontiguousarray(y0[:, idx])
    p = np.zeros((len(pars) + len(_EXTRA), padded))
    p[: len(pars)] = np.array(pars)[:, None]
    m = len(pars)
    p[m] = 1.0  # alive
    p[m + 2] = np.nan  # t_left
    p[m + 3: m + 5] = bounds[:, idx]
    return states, p


@dataclass(frozen=True, eq=False)
class Runs:
    """Every lane of a map, ready for the integrators (see :func:`prepare_runs`).

    ``states`` (4, n_lanes) and ``pars`` (n_model_pars + 5, n_lanes) are lane-major, n_lanes a
    multiple of ``batch_size`` (the last point repeated as padding); the first ``n`` lanes are
    the map's points in tilt-major order.  ``ref`` is each lane's steady angle.
    """

    model: str
    states: np.ndarray
    pars: np.ndarray
    ref: np.ndarray
    grid: np.ndarray
    step_cap: Optional[float]
    n: int
    n_model_pars: int
    batch_size: int
    theta_steady: np.ndarray  # per rate
    model_pars: tuple  # the model's parameters in double, model order

    @property
    def cooldown(self) -> float:
        return 2.0 * float(self.grid[-1]) + 1.0


def prepare_runs(model: str, motion: str, rates, tilts, t_end: float, params: dict, cap: float,
                 step_cap: bool, batch_size: int) -> Runs:
    """Initial states, per-lane parameters, sample times and step cap of a map (inputs validated)."""
    from verify.engine.single import resolve_parameters
    from verify.precision import parse_precision

    from verify.engine import validation

    mdl = get_model(model)
    pars = [float(v) for v in resolve_parameters(mdl, params, parse_precision("double")).values()]
    y0, bounds, ths = _initial_conditions(model, motion, rates, tilts, params, cap)
    full = np.zeros((8, y0.shape[1]))  # every start checked as solve and the sweeps check theirs
    full[[0, 3, 4, 5]] = y0
    normal = validation.normal_force_columns(model, full, np.repeat(np.array(pars)[:, None], y0.shape[1], axis=1))
    problem = validation.first_problem(mdl, full, normal)
    if problem is not None:
        k = problem[0]
        raise validation.InvalidStart(f"map point rate = {float(rates[k % len(rates)])!r}, tilt = "
                                      f"{float(tilts[k // len(rates)])!r}: {problem[2]}", problem[1])
    rates, g = y0[2:].ravel(), dict(zip(mdl.parameter_names, pars)).get("g", 1.0)
    states, lane_pars = _lane_arrays(y0, bounds, pars, batch_size)
    n = y0.shape[1]
    ref = np.tile(ths, len(tilts))
    ref = np.concatenate([ref, np.full(states.shape[1] - n, ref[-1])])
    return Runs(model, states, lane_pars, ref, sample_times(t_end, batch.fastest_rate(rates, g)),
                batch.step_cap(rates, g) if step_cap else None,
                n, len(pars), batch_size, ths, tuple(pars))


def propagate(name, states, pars, ref, grid, batch_size, threads, step_cap, chunk=CHUNK):
    """Run every lane by ensemble propagation of batches; reduce each batch's dense output at once.

    ``states`` (4, n_lanes) and ``pars`` (n_pars, n_lanes) hold every lane's initial state and
    parameters, n_lanes a multiple of ``batch_size``; ``ref`` (n_lanes) is the angle the
    deviation is measured from.  The ensemble runs ``chunk`` batches per call, so that only
    their dense output is held at once.  Returns (max |theta - ref| over ``grid`` per lane,
    the lanes' final parameters -- alive, reason, t_left --, batch steps taken in all).
    """
    ta = template(name, batch_size, 2.0 * float(grid[-1]) + 1.0)  # the cooldown of Runs.cooldown
    deviation = np.empty(states.shape[1])
    final_pars = np.empty_like(pars)
    steps = 0
    for batches, _ in batch.propagate_grid(ta, states, pars, grid, threads, chunk, max_delta_t=step_cap):
        for b in batches:
            if not b.complete(len(grid)):
                local = b.local
                raise RuntimeError(f"batch {b.index} of the {name!r} map stopped with "
                                   f"{[r[0] for r in local.propagate_res]} at t = {list(local.time)} "
                                   f"(state {local.state.tolist()})")
            cols = b.columns
            deviation[cols] = np.max(np.abs(b.output[:, 0, :] - ref[None, cols]), axis=0)
            final_pars[:, cols] = b.local.pars
            steps += b.steps
    return deviation, final_pars, steps

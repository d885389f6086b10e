"""The runs of a stability map on the batch road: the map's :class:`verify.engine.ensemble.Ensemble` (the
reduced lane system), every lane's start and parameters laid out by name, and the ensemble propagation
reduced to each run's largest deviation (:mod:`verify.studies.maps` describes the protocol, how it runs
and why it is deterministic).  No heyoka here: the engine room builds and runs the integrators.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import mpmath
import numpy as np

from . import thresholds
from ..engine import batch, validation
from ..engine.ensemble import Ensemble, ensemble
from ..engine.single import resolve_parameters
from ..precision import parse_precision

SAMPLES_PER_RADIAN = 4  # dense-output samples per radian of the fastest rate (see sample_times)
CHUNK = 64  # batches per ensemble call: bounds the memory of the dense output held at once


def map_ensemble(name: str, batch_size: int, cooldown: float) -> Ensemble:
    """The map's :class:`verify.engine.ensemble.Ensemble`: the reduced lane system of model ``name``
    (theta, thetadot, phidot, psidot; events: theta at the lane's ``theta_lower`` and ``theta_upper``,
    the loss of contact where the model has a contact), one per process and settings.  A frozen
    lane is parked in the middle of its bounds with thetadot = 0, never on a singular end of the domain."""
    return ensemble(name, "reduced", batch_size, cooldown)


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


def _initial_conditions(model, motion, rates, tilts, params, cap):
    """Per-point initial state, bounds and steady angle, in map order (tilt-major)."""
    name = model.name
    dom = model.domain
    tmin, tmax = float(dom.theta_min), float(dom.theta_max)
    steady = [_steady(name, motion, float(r), params, tmin, tmax) for r in rates]
    ths = np.array([float(mpmath.mpf(s["theta"])) for s in steady])
    n = len(tilts) * len(rates)
    y0 = np.zeros((4, n))
    bounds = np.zeros((2, n))
    with mpmath.workdps(40):
        # per rate once: the steady angle (40 digits), the bounds and the rates in double
        th0s = [mpmath.mpf(s["theta"]) for s in steady]
        ends = [(max(float(th0 - cap), tmin), min(float(th0 + cap), tmax)) for th0 in th0s]
        rates_of = [(float(mpmath.mpf(s["phidot"])), float(mpmath.mpf(s["psidot"]))) for s in steady]
        for i, tilt in enumerate(tilts):
            dt = mpmath.mpf(float(tilt))
            for j, th0 in enumerate(th0s):
                k = i * len(rates) + j
                lo, hi = ends[j]
                start = float(th0 + dt)  # the steady angle (40 digits) plus the tilt, rounded once
                if not lo < start < hi:
                    raise ValueError(f"tilt {float(tilt)!r} at rate {float(rates[j])!r} starts theta at {start!r}, "
                                     f"outside ({lo!r}, {hi!r}); allowed: tilts below the cap {cap} that keep "
                                     f"theta inside the domain of {name!r}")
                y0[:, k] = (start, 0.0, *rates_of[j])
                bounds[:, k] = (lo, hi)
    return y0, bounds, ths


@dataclass(frozen=True, eq=False)
class Runs:
    """Every lane of a map, ready for the integrators (see :func:`prepare_runs`).

    ``states`` (4, n_lanes) and ``pars`` (the lane parameters of ``ensemble``, by name, n_lanes)
    hold every lane, n_lanes a multiple of ``batch_size`` (the last point repeated as padding); the
    first ``n`` lanes are the map's points in tilt-major order.  ``ref`` is each lane's steady angle.
    """

    ensemble: Ensemble
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
    ens = map_ensemble(model, batch_size, 2.0 * float(t_end) + 1.0)  # the cooldown of Runs.cooldown
    mdl = ens.model
    resolved = resolve_parameters(mdl, params, parse_precision("double"))
    values = {name: float(resolved[name]) for name in mdl.parameter_names}  # by name, whatever the mapping's order
    y0, bounds, ths = _initial_conditions(mdl, motion, rates, tilts, params, cap)
    n = y0.shape[1]
    full = np.zeros((8, n))  # every start checked as solve and the sweeps check theirs
    full[[0, 3, 4, 5]] = y0
    normal = ens.normal_force_columns(full, ens.model_columns(values, n))
    problem = validation.first_problem(mdl, full, normal)
    if problem is not None:
        k = problem[0]
        raise validation.InvalidStart(f"map point rate = {float(rates[k % len(rates)])!r}, tilt = "
                                      f"{float(tilts[k // len(rates)])!r}: {problem[2]}", problem[1])
    idx = batch.pad_lanes(n, batch_size)
    states = np.ascontiguousarray(y0[:, idx])
    lane_pars = ens.parameters(len(idx), {**values, "theta_lower": bounds[0, idx], "theta_upper": bounds[1, idx]})
    ref = np.tile(ths, len(tilts))[idx]
    rates_all, g = y0[2:].ravel(), values["g"]  # the model's own g (every model has one: sqrt(g) is a rate)
    return Runs(ens, model, states, lane_pars, ref, sample_times(t_end, ens.fastest_rate(rates_all, g)),
                ens.step_cap(rates_all, g) if step_cap else None, n, len(values), batch_size, ths,
                tuple(values.values()))


def propagate(runs: Runs, threads: int, chunk: int = CHUNK):
    """Run every lane by ensemble propagation of batches; reduce each batch's dense output at once.

    The ensemble runs ``chunk`` batches per call, so that only their dense output is held at once.
    Returns (max |theta - ref| over the grid per lane, the lanes' final parameters -- alive,
    reason, t_stop --, batch steps taken in all).  A batch that did not reach the end of the grid
    (a lane heyoka stopped) raises RuntimeError naming it: a map has no row for a failed run.
    """
    ens, grid = runs.ensemble, runs.grid
    th = ens.lanes.row("theta")
    deviation = np.empty(runs.states.shape[1])
    final_pars = np.empty_like(runs.pars)
    steps = 0
    for batches, _ in ens.propagate(runs.states, runs.pars, grid, threads, chunk, max_delta_t=runs.step_cap):
        for b in batches:
            if not b.complete(len(grid)):
                local = b.local
                raise RuntimeError(f"batch {b.index} of the {runs.model!r} map stopped with "
                                   f"{[r[0] for r in local.propagate_res]} at t = {list(local.time)} "
                                   f"(state {local.state.tolist()})")
            cols = b.columns
            deviation[cols] = np.max(np.abs(b.output[:, th, :] - runs.ref[None, cols]), axis=0)
            final_pars[:, cols] = b.local.pars
            steps += b.steps
    return deviation, final_pars, steps

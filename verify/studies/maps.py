"""Stability maps: spin rate x initial tilt, by heyoka's batch mode and ensemble propagation.

Protocol (the one of :func:`verify.studies.thresholds.grows`): start on the steady motion at
the rate, perturb theta alone by +tilt and keep the rates, so the body moves onto a
neighbouring member of the two-parameter family of steady motions; the map records the
largest deviation |theta - theta_steady| from the *unperturbed* steady angle within
``t_end``.  A stable point oscillates about the neighbouring member (deviation of the order
of the tilt, times a factor that grows like 1/w2 near the threshold); an unstable one grows
until the nonlinear terms saturate it, or it leaves.

Only theta, thetadot, phidot, psidot feed back into the dynamics (phi, psi, x, y appear on no
right-hand side of these four), so the map integrates the reduced 4-dimensional system.

How it runs
-----------
(:mod:`verify.studies.map_runs`)

* The reduced system is compiled once per model in double (:func:`verify.engine.lanes.compile_lanes`,
  through the map's :class:`verify.engine.ensemble.Ensemble`)
  (batch size twice :func:`verify.engine.lanes.simd_width`: two SIMD registers a lane group; measured on
  a 2-core AVX2 machine, 10^4 disk runs take 7.2 s with 8 lanes and 9.0 s with 4, bit for bit the
  same results), parameters as runtime ``par[i]``: the model's parameters in model order, then
  five per-lane parameters laid out by name (alive, reason, t_stop, theta_lower, theta_upper).
* The grid of (tilt, rate) points is cut into batches and run on threads by
  :func:`verify.engine.batch.propagate_grid`; each batch's dense output on a fixed time grid is
  reduced to its maximum deviation as soon as its chunk returns.
* A run *leaves* when theta reaches theta_steady -+ ``cap`` or an end of the model's domain
  (whichever is nearer), or when the normal force vanishes (models with a contact).  heyoka 7.13
  stops a whole batch on one lane's terminal event, so the events freeze their own lane instead
  (:class:`verify.engine.batch.Freeze`): it is parked in the middle of its bounds with
  thetadot = 0, so that a frozen lane never sits on a singular end of the domain, and the whole
  batch runs to ``t_end`` in one ``propagate_grid`` call.

Determinism
-----------
Every batch starts from a copy of the same template with its lanes filled from fixed columns of
precomputed arrays, so the result of a point does not depend on thread scheduling, and the
reductions are plain numpy on fixed-order arrays: two runs give identical bytes.  Lanes of a
batch do not interact either (each has its own step size and events): measured, a point gives
the same bytes with other batch partners (rates reversed) and with batch size 4 instead of 8.
"""
from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from typing import Optional

import numpy as np

from models import BODY_PREFIX

from . import thresholds
from ..engine.ensemble import resolve
from ..engine.lanes import simd_width
from ..engine.single import resolve_parameters
from ..precision import parse_precision
# the runs (re-exported: tests and benchmarks/ reach them as maps.Runs, maps.prepare_runs, ...)
from .map_runs import CHUNK, SAMPLES_PER_RADIAN, Runs, map_ensemble, prepare_runs, propagate, sample_times  # noqa: F401

MOTIONS = thresholds.MOTIONS
GROWTH = thresholds.GROWTH
CAP = 1.0  # rad: a run that moves this far from the steady angle has left
REASONS = ("stayed", "below", "above", "contact_lost")  # codes 0..3 of StabilityMap.reason


@dataclass(frozen=True, eq=False)
class StabilityMap:
    """A stability map of one steady motion.

    Attributes
    ----------
    model, motion : str
    params : dict
        Every parameter of the model as a decimal string (defaults filled in).
    rates : ndarray, shape (n_rates,)
        Spin rates (the rate that names the motion: phidot0, psidot0, ...).
    tilts : ndarray, shape (n_tilts,)
        Initial perturbations of theta (rad, > 0).
    theta_steady : ndarray, shape (n_rates,)
        The steady angle at each rate (double nearest the 36-digit value).
    max_deviation : ndarray, shape (n_tilts, n_rates)
        max |theta - theta_steady| over the sample times, or ``cap`` when the run left.
    left : ndarray of bool, shape (n_tilts, n_rates)
        The run reached the cap, an end of the domain, or lost contact.
    reason : ndarray of int8, shape (n_tilts, n_rates)
        Index into ``REASONS``: why the run left (0 when it stayed).
    t_left : ndarray, shape (n_tilts, n_rates)
        When it left (NaN when it stayed).
    linear_threshold : float or None
        The exact linear threshold of :func:`thresholds.threshold` (None: there is none).
    t_end, cap : float
    n_samples : int
        Dense-output samples per run (uniform in [0, t_end]).
    n_trajectories, batch_size, threads, n_steps : int
        Runs (excluding padding lanes), lanes per batch, threads, batch steps taken in all.
    step_cap : float or None
        The ``max_delta_t`` every batch ran with (None: uncapped).
    wall_seconds : float
        Wall time of the propagation (the only field that changes from run to run).
    """

    model: str
    motion: str
    params: dict
    rates: np.ndarray
    tilts: np.ndarray
    theta_steady: np.ndarray
    max_deviation: np.ndarray
    left: np.ndarray
    reason: np.ndarray
    t_left: np.ndarray
    linear_threshold: Optional[float]
    t_end: float
    cap: float
    n_samples: int
    n_trajectories: int
    batch_size: int
    threads: int
    n_steps: int
    step_cap: Optional[float]
    wall_seconds: float

    @property
    def growth(self) -> np.ndarray:
        """max_deviation / tilt, shape (n_tilts, n_rates)."""
        return self.max_deviation / self.tilts[:, None]

    @property
    def grows(self) -> np.ndarray:
        """Growth: the run left, or grew by more than GROWTH x the tilt.

        :func:`thresholds.grows` counts only the domain's ends and loss of contact as leaving;
        here reaching the cap counts too, so for tilts above cap / GROWTH (1e-3) the map calls
        growth what stays below GROWTH x the tilt yet moves more than ``cap``.
        """
        return self.left | (self.growth > GROWTH)


# --- input -------------------------------------------------------------------------------

def _check_motion(model: str, motion: str) -> None:
    if model.startswith(BODY_PREFIX):
        raise ValueError(f"model {model!r}: a stability map starts on a steady motion, and a body file has no "
                         f"steady-motion study (models.steady.MOTIONS); allowed: {', '.join(MOTIONS)} (a body file "
                         "sweeps with explicit starts: python -m verify sweep)")
    if model not in MOTIONS:
        raise ValueError(f"unknown model {model!r} for a stability map; allowed: {', '.join(MOTIONS)}")
    if motion not in MOTIONS[model]:
        raise ValueError(f"unknown motion {motion!r} for model {model!r}; allowed: {', '.join(MOTIONS[model])}")


def _positive_vector(name: str, values) -> np.ndarray:
    """A non-empty 1-D array of positive finite floats, or ValueError naming the bad value."""
    try:
        arr = np.array(values, dtype=float)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{name}={values!r} must be a sequence of positive numbers ({err})") from None
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D sequence of positive numbers; got shape {arr.shape}")
    bad = [v for v in arr if not (math.isfinite(v) and v > 0)]
    if bad:
        raise ValueError(f"{name} contains {float(bad[0])!r}; allowed: positive finite numbers")
    return arr


def _positive(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} must be a positive finite number") from None
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name}={value!r} must be a positive finite number")
    return v


# --- the map ----------------------------------------------------------------------------------

def stability_map(model: str = "disk", motion: str = "diameter-spin", rates=None, tilts=None,
                  t_end: float = 10.0, params: Optional[dict] = None, threads: Optional[int] = None,
                  cap: float = CAP, step_cap: bool = False, batch_size: Optional[int] = None) -> StabilityMap:
    """The stability map of a steady motion over spin rates x initial tilts.

    Each point starts on the steady motion at the rate (:func:`thresholds.steady_state`)
    with theta perturbed by +tilt and the rates unchanged -- the perturbation moves the body
    onto a neighbouring member of the family of steady motions -- and the map measures the
    deviation from the *unperturbed* steady angle: max |theta - theta_steady| over
    :func:`sample_times` within ``t_end``, or ``cap`` when the run left (reached
    theta_steady -+ cap or an end of the domain, or lost contact).

    Parameters
    ----------
    model, motion : str
        A model and one of its steady motions (``MOTIONS``), e.g. ``"disk"``,
        ``"diameter-spin"`` or ``"straight-line"``; ``"sliding-disk"``, ``"diameter-spin"``.
    rates, tilts : sequence of float
        Positive spin rates (default: 20 rates from 0.5 to 2 times the linear threshold) and
        positive tilts in rad (default: 1e-6 ... 1e-1, 6 points, log-spaced).
    t_end : float
        Length of every run (s).
    params : dict, optional
        Model parameters as decimal strings (e.g. ``{"k": "0.5"}`` for the hoop).
    threads : int, optional
        Ensemble threads (default: the machine's cores).
    cap : float
        Deviation (rad) at which a run counts as left.
    step_cap : bool
        Cap the step at 1 / max(fastest rate of the map, sqrt(g)), like
        :func:`verify.engine.single.max_step`.  Off by default: measured on the 100 x 100 disk
        map it changes no classification, moves max deviations of non-growing runs by at
        most 3e-9 (relative; round-off carried by the flow's conditioning) and takes 44%
        more steps (10-30% more wall time).  The cap guards against steps fooled by the
        vanishing Taylor coefficients of an exactly steady state, which in solve's
        8-dimensional system bite through x and y; the reduced system has no such component,
        and every run here starts perturbed (tilt > 0).
    batch_size : int, optional
        Lanes per batch (default ``2 * verify.engine.lanes.simd_width()``, see the module docstring).

    Returns
    -------
    StabilityMap
        Arrays of shape (len(tilts), len(rates)); ``wall_seconds`` is the propagation alone
        (compilation, steady states and the sympy threshold excluded).

    Raises
    ------
    ValueError
        Unknown model, motion or parameter; empty or non-positive rates or tilts; a tilt
        that would start outside the cap or the domain; non-positive t_end, cap or threads.
    """
    _check_motion(model, motion)
    params = dict(params or {})
    resolve_parameters(resolve(model), params, parse_precision("double"))  # names and ranges, before sympy
    t_end = _positive("t_end", t_end)
    cap = _positive("cap", cap)
    tilts = _positive_vector("tilts", np.logspace(-6, -1, 6) if tilts is None else tilts)
    if rates is not None:
        rates = _positive_vector("rates", rates)
    threads = (os.cpu_count() or 1) if threads is None else int(_positive("threads", threads))
    batch_size = 2 * simd_width() if batch_size is None else int(_positive("batch_size", batch_size))
    runs = None if rates is None else prepare_runs(model, motion, rates, tilts, t_end, params, cap, step_cap,
                                                   batch_size)
    thr = thresholds.threshold(model, motion, params)
    lin = None if thr.value is None else float(thr.value)
    if runs is None:
        if lin is None:
            raise ValueError(f"{model} {motion} has no linear threshold: give the rates explicitly")
        rates = np.linspace(0.5 * lin, 2.0 * lin, 20)
        runs = prepare_runs(model, motion, rates, tilts, t_end, params, cap, step_cap, batch_size)
    runs.ensemble.lanes  # compile (or load from heyoka's cache) outside the timing
    start = time.perf_counter()
    dev, final, steps = propagate(runs, threads)
    wall = time.perf_counter() - start

    n, record = runs.n, runs.ensemble.record
    shape = (len(tilts), len(rates))
    alive = record(final, "alive")[:n] != 0.0
    dev = np.where(alive, dev[:n], cap)
    return StabilityMap(
        model=model, motion=motion, params=dict(thr.params), rates=_frozen(rates), tilts=_frozen(tilts),
        theta_steady=_frozen(runs.theta_steady), max_deviation=_frozen(dev.reshape(shape)),
        left=_frozen(~alive.reshape(shape)), reason=_frozen(record(final, "reason")[:n].astype(np.int8).reshape(shape)),
        t_left=_frozen(record(final, "t_stop")[:n].reshape(shape)), linear_threshold=lin, t_end=t_end, cap=cap,
        n_samples=len(runs.grid), n_trajectories=n, batch_size=batch_size, threads=threads, n_steps=steps,
        step_cap=runs.step_cap, wall_seconds=wall,
    )


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a)
    a.setflags(write=False)
    return a


# --- reading a map ------------------------------------------------------------------------

def switch_bracket(smap: StabilityMap, tilt_index: int = 0) -> Optional[tuple]:
    """The rates between which the classification switches from growth to no growth.

    Parameters
    ----------
    smap : StabilityMap
    tilt_index : int
        The row (tilt) to read; 0 is the first tilt given.

    Returns
    -------
    (float, float) or None
        Along the row, rates ascending: if every point below some rate grows
        (``StabilityMap.grows``) and every point from it on does not, the last growing rate
        and the first stable one; otherwise (no switch, several, or the wrong way round) None.
    """
    order = np.argsort(smap.rates)
    row = smap.grows[tilt_index][order]
    rates = smap.rates[order]
    k = int(np.argmin(row)) if not row.all() else len(row)
    if k == 0 or k == len(row) or not row[:k].all() or row[k:].any():
        return None
    return float(rates[k - 1]), float(rates[k])


def consistent_with_threshold(smap: StabilityMap, value: float, tilt_index: int = 0) -> bool:
    """Whether a threshold rate is consistent with the map.

    Parameters
    ----------
    smap : StabilityMap
    value : float
        A threshold rate (e.g. the exact linear one, or a wrong one in a negative control).
    tilt_index : int
        The row (tilt) to read; use the smallest tilt, where the linearisation holds.

    Returns
    -------
    bool
        True when the row switches once from growth to no growth (:func:`switch_bracket`)
        and the switch brackets ``value`` strictly.
    """
    br = switch_bracket(smap, tilt_index)
    return br is not None and br[0] < float(value) < br[1]

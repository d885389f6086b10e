"""Many trajectories at once: heyoka batch integrators (SIMD lanes) in ensembles on threads.

The one batch propagator of the suite; the sweeps (:mod:`verify.sweep.engine`) and the stability
maps (:mod:`verify.studies.maps`) are its users.

* :func:`batch_system` compiles a system with per-lane bookkeeping parameters and the terminal
  events asked for (an event nobody asked for is not compiled: each costs on every step);
* :func:`propagate_grid` runs every lane on a common output grid, ``chunk`` batches at a time (the
  next chunk integrating while the caller reads the last), and yields each chunk's results as
  :class:`Batch` objects with heyoka's log messages; each worker thread enters heyoka along the
  call path it timed fastest (:mod:`.call_paths`);
* :func:`lane_failures` and :func:`alone` detect and isolate the lanes that failed;
* :func:`per_lane` evaluates a compiled function over the samples of many runs at once with the
  bits of one call per run;
* :func:`fastest_rate` and :func:`step_cap` (from :mod:`.problem`): the step cap, one radian of the fastest rate.

Terminal events in batch mode
-----------------------------
heyoka 7.13 stops the whole batch when a terminal event fires in one lane: the lane sits at its
event time, the others at the end of their own last step, and ``propagate_grid`` fills the
remaining rows of *every* lane with NaN.  So the events here return True (go on) and
:class:`Freeze` freezes its own lane instead: it zeroes the lane's ``alive`` parameter, which
multiplies every right-hand side (x * 1.0 = x exactly, so a live lane integrates the plain
equations), records the event's code and time in two more parameters (:class:`Lanes`), and
parks the lane on a state where the equations are regular.  A cooldown longer than the run
keeps the event from firing again in that lane.  heyoka sizes a system's parameters by the
highest ``par[i]`` its expressions read, so the two records must sit below a parameter that is
read (``alive``, or one an event reads).

Determinism
-----------
Each worker copies the same template once and fills its lanes, batch after batch, from fixed
columns of precomputed arrays; lanes do not interact (each has its own step size and events).  A
lane's result depends on its own inputs and the batch width only, whatever its partners, the
threads, the order the workers take the batches in, the call path or the chunking.
"""
from __future__ import annotations

import copy
import threading
from concurrent.futures import ThreadPoolExecutor
from contextlib import ExitStack
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Iterator, Optional

import heyoka as hy
import numpy as np

from . import call_paths, heyoka_log
from .problem import fastest_rate, step_cap  # noqa: F401 - the step cap, as solve() caps its steps


@dataclass(frozen=True)
class Lanes:
    """Where a lane's bookkeeping sits among its parameters: the ``alive`` factor (1, or 0 once
    frozen), the code of the event that froze it (0: none) and the time it did."""

    alive: int
    reason: int
    t_stop: int


class Freeze:
    """Terminal-event callback: freeze this lane, record why and when, park it, let the batch run on.

    Parameters
    ----------
    lanes : Lanes
        Where the lane's bookkeeping parameters are.
    code : int
        The event's code recorded in ``reason`` (its index + 1).
    park : sequence of (row, value)
        State rows set to fixed values when the lane freezes.
    park_between : (row, par_a, par_b), optional
        A state row set to the mean of two of the lane's parameters.
    record : sequence of (row, par)
        State rows copied into parameters before the lane is parked: the state at the event
        (heyoka calls a terminal event's callback with the lane at its event time).
    """

    def __init__(self, lanes: Lanes, code: int, park=(), park_between=None, record=()):
        self.lanes, self.code = lanes, float(code)
        self.park, self.between, self.record = tuple(park), park_between, tuple(record)

    def __call__(self, ta, d_sgn, lane):
        where, pars, state = self.lanes, ta.pars, ta.state
        if pars[where.alive, lane] == 0.0:  # already frozen: two events in one step
            return True
        pars[where.alive, lane] = 0.0
        pars[where.reason, lane] = self.code
        pars[where.t_stop, lane] = ta.time[lane]
        for row, par in self.record:
            pars[par, lane] = state[row, lane]
        if self.between is not None:
            row, a, b = self.between
            state[row, lane] = 0.5 * (pars[a, lane] + pars[b, lane])
        for row, value in self.park:
            state[row, lane] = value
        return True


def go_on(ta, d_sgn, lane) -> bool:
    """Terminal-event callback of a bare baseline (verify.bench): nothing recorded, the batch runs on."""
    return True


def batch_system(system, events, lanes: Lanes, n_pars: int, batch_size: int, cooldown: float,
                 state, default_pars, park=(), park_between=None, record=(), freezing: bool = True):
    """A ``taylor_adaptive_batch`` template of ``system`` with freezing terminal events.

    Parameters
    ----------
    system : list of (variable, expression)
        The right-hand sides, each already multiplied by ``par[lanes.alive]``.
    events : sequence of (name, expression, direction)
        Only the events wanted; event i records code i + 1.
    lanes : Lanes
        Where the bookkeeping parameters are.
    n_pars : int
        All per-lane parameters (the model's first, in model order).
    batch_size : int
        Lanes per batch.
    cooldown : float
        Longer than any run: an event fires at most once in a lane.
    state : sequence of float
        A regular state for the template's lanes (overwritten by every ensemble iteration).
    default_pars : sequence of float
        The model's parameters for the template's lanes (the first parameters).
    park, park_between, record
        Where a frozen lane is parked, and what of its state at the event is kept (:class:`Freeze`);
        a record's parameter must sit below one that is read, as ``reason`` and ``t_stop`` do.
    freezing : bool
        False: the events' callback is :func:`go_on` (a bare baseline's: the same events, nothing frozen).
    """
    t_events = [hy.t_event_batch(ex, direction=d, cooldown=cooldown,
                                 callback=Freeze(lanes, i + 1, park, park_between, record) if freezing else go_on)
                for i, (_, ex, d) in enumerate(events)]
    lanes_state = np.repeat(np.asarray(state, float)[:, None], batch_size, axis=1)
    pars = np.zeros((n_pars, batch_size))
    pars[: len(default_pars)] = np.asarray(default_pars, float)[:, None]
    if freezing:
        pars[lanes.alive] = 1.0
    return hy.taylor_adaptive_batch(list(system), lanes_state, pars=pars, t_events=t_events)


def pad_lanes(n: int, batch_size: int) -> np.ndarray:
    """Column of the input that fills each lane: whole batches, the last point repeated as padding."""
    return np.minimum(np.arange(-(-n // batch_size) * batch_size), n - 1)


@dataclass(frozen=True)
class Batch:
    """One batch's result: ``index`` of the batch, its integrator after the run (``local``:
    time, state, parameters, ``propagate_res``) and its output on the grid, shape
    (n_grid, n_states, batch_size) -- fewer rows when the batch stopped early."""

    index: int
    local: object
    output: np.ndarray

    @property
    def columns(self) -> slice:
        bs = self.local.batch_size
        return slice(self.index * bs, (self.index + 1) * bs)

    @property
    def steps(self) -> int:
        """Steps of the batch (the most any lane took)."""
        return max(int(r[3]) for r in self.local.propagate_res)

    def complete(self, n_grid: int) -> bool:
        """Every lane ran to the end of the grid (no heyoka stop, no missing rows)."""
        return (all(r[0] == hy.taylor_outcome.time_limit for r in self.local.propagate_res)
                and self.output.shape[0] == n_grid)


def propagate_grid(template, states, pars, grid, threads: int, chunk: Optional[int] = None,
                   max_delta_t: Optional[float] = None, max_steps: Optional[int] = None) -> Iterator[tuple]:
    """Run every lane on ``grid``, batches on threads; yield (batches, heyoka's messages) per chunk.

    ``states`` (n_states, n_lanes) and ``pars`` (n_pars, n_lanes) hold every lane's start and
    parameters, n_lanes a multiple of the template's batch size (:func:`pad_lanes`).  ``chunk``
    batches run per call (None: all at once), so that only their output is held at once.

    Each thread copies the template once and reuses its copy for the batches it takes from a
    shared queue, in index order (time, state, parameters and event cooldowns reset for each):
    heyoka's ``ensemble_propagate_grid_batch`` copies the template for every batch, holding the
    GIL (~1 ms for an integrator with Python event callbacks), which serialises the threads; a
    queue keeps both threads busy when batches cost unequal times (fixed shares left one idle).
    Each thread calls heyoka along the path it found fastest (:mod:`.call_paths`).  A batch's
    result depends on its own lanes only, so neither the sharing nor the path changes a bit.  The
    next chunk is started before a chunk is yielded: it runs while the caller reduces this one.
    """
    bs = template.batch_size
    n_batches = states.shape[1] // bs
    chunk = n_batches if chunk is None else chunk
    grid_lanes = np.ascontiguousarray(np.repeat(np.asarray(grid, float)[:, None], bs, axis=1))
    workers = max(1, int(threads))
    copies = [copy.deepcopy(template) for _ in range(workers)]
    choosers: dict = {}  # per thread: which path is fast depends on the thread's stack (:mod:`.call_paths`)
    failed = threading.Event()  # a worker that raised: the others stop taking batches

    def one(ta, chooser, b: int) -> Batch:
        cols = slice(b * bs, (b + 1) * bs)
        ta.set_time(0.0)
        if ta.with_events:
            ta.reset_cooldowns()
        ta.state[:] = states[:, cols]
        ta.pars[:] = pars[:, cols]
        output = call_paths.timed_propagate_grid(chooser, ta, grid_lanes, max_delta_t, max_steps)[-1]
        local = SimpleNamespace(time=ta.time.copy(), state=ta.state.copy(), pars=ta.pars.copy(),
                                propagate_res=list(ta.propagate_res), batch_size=bs)
        return Batch(b, local, output)

    def share(worker: int, queue, lock) -> list:
        out = []
        chooser = choosers.setdefault(threading.get_ident(), call_paths.PathChooser())
        while not failed.is_set():
            with lock:
                b = next(queue, None)
            if b is None:
                return out
            try:
                out.append(one(copies[worker], chooser, b))
            except BaseException:
                failed.set()
                raise
        return out

    def launch(pool, first: int, stack: ExitStack):
        """Start the chunk from batch ``first`` on every worker; heyoka's messages collected until it ends."""
        messages = stack.enter_context(heyoka_log.collect())
        queue, lock = iter(range(first, min(first + chunk, n_batches))), threading.Lock()
        return [pool.submit(share, worker, queue, lock) for worker in range(workers)], messages

    with ThreadPoolExecutor(max_workers=workers) as pool:
        firsts = list(range(0, n_batches, chunk))
        stack, running = ExitStack(), None
        try:
            running = launch(pool, firsts[0], stack) if firsts else None
            for k in range(len(firsts)):
                futures, messages = running
                parts = [f.result() for f in futures]
                stack.close()  # this chunk's messages are complete
                stack = ExitStack()
                # the next chunk runs while the caller reduces this one
                running = launch(pool, firsts[k + 1], stack) if k + 1 < len(firsts) else None
                yield sorted((b for part in parts for b in part), key=lambda b: b.index), list(messages)
        finally:  # a caller that stops early: the chunk under way ends inside its collection
            for future in (running[0] if running else ()):
                future.exception()
            stack.close()


def alone(template, grid, state_col, pars_col, max_delta_t=None, max_steps=None) -> tuple:
    """One lane integrated alone, in a batch of copies of itself: (:class:`Batch`, heyoka's messages).

    Lanes are independent, so a lane gets the same bits alone as in a mixed batch; alone, a
    failed lane is told apart from its neighbours.
    """
    bs = template.batch_size
    states = np.repeat(np.asarray(state_col)[:, None], bs, axis=1)
    pars = np.repeat(np.asarray(pars_col)[:, None], bs, axis=1)
    (batches, messages), = propagate_grid(template, states, pars, grid, 1, None, max_delta_t, max_steps)
    return batches[0], messages


def lane_failure(batch: Batch, lane: int, lanes: Lanes, warned) -> Optional[tuple]:
    """(outcome, time) when heyoka failed the lane, else None.

    ``failed:non_finite``: heyoka stopped the lane on a non-finite state;
    ``failed:step_size_collapse``: it stopped for any other reason (the step budget ran out);
    ``failed:event_detection``: heyoka warned (``warned``, the lane's messages) that event
    detection failed, or logged an error -- at the lane's stop time when an event froze it.
    """
    local = batch.local
    outcome = local.propagate_res[lane][0]
    t_fail = float(local.time[lane])
    if outcome == hy.taylor_outcome.err_nf_state:
        return "failed:non_finite", t_fail
    if outcome != hy.taylor_outcome.time_limit:
        return "failed:step_size_collapse", t_fail
    if any(m.event_detection or m.level in ("error", "critical") for m in warned):
        reason = int(local.pars[lanes.reason, lane])
        return "failed:event_detection", float(local.pars[lanes.t_stop, lane]) if reason else t_fail
    return None


@dataclass(frozen=True)
class ScalarTwin:
    """A compiled function and its scalar build: evaluated by :func:`per_lane`."""

    simd: object
    scalar: object

    @classmethod
    def of(cls, outputs, variables) -> "ScalarTwin":
        return cls(hy.cfunc(outputs, variables), hy.cfunc(outputs, variables, batch_size=1))


def per_lane(fn: ScalarTwin, points: np.ndarray, pars: Optional[np.ndarray], lengths) -> np.ndarray:
    """``fn`` at the samples of many runs, bit for bit as one call per run would give them.

    ``points`` (n_inputs, lanes, n_samples) holds lane l's samples in order, its run the first
    ``lengths[l]``; ``pars`` (n_pars, lanes) its parameters (or None).  heyoka's compiled
    functions evaluate whole SIMD groups of points vectorised and the points left over one by one
    with scalar code, whose transcendental functions can differ in the last bit; and a SIMD group's
    values can depend on the whole group (the vector sine and cosine reduce their arguments another
    way when one of the group is NaN, infinite or beyond ~1e15).  So each lane's samples are padded
    to whole groups (its last sample repeated), no group holds two lanes, and every point is evaluated
    by the SIMD build in one call: a run's whole groups are then the groups of a call on that run
    alone, and its leftover points -- its last ``length % width``, which such a call gives to scalar
    code -- are evaluated again by the scalar build.

    Returns (n_outputs, lanes, n_samples); the values past a run's length belong to no run.
    """
    n_in, lanes, n_samples = points.shape
    lengths = np.asarray(lengths, dtype=np.int64)
    width = int(fn.simd.batch_size)
    row = n_samples + (-n_samples) % width  # a lane's samples in whole groups
    if row == n_samples and points.flags.c_contiguous:
        flat = points.reshape(n_in, lanes * row)  # no copy
    else:
        lanes_padded = np.empty((n_in, lanes, row))
        lanes_padded[:, :, :n_samples] = points
        lanes_padded[:, :, n_samples:] = points[:, :, n_samples - 1:]
        flat = lanes_padded.reshape(n_in, lanes * row)
    kwargs = {}
    if pars is not None and fn.simd.nparams:
        kwargs = {"pars": np.repeat(np.ascontiguousarray(pars[: fn.simd.nparams], dtype=float), row, axis=1)}
    out = fn.simd(flat, **kwargs)
    tails = lengths % width
    tail = np.repeat(np.arange(lanes) * row + lengths - tails, tails) + (
        np.arange(int(tails.sum())) - np.repeat(np.cumsum(tails) - tails, tails))
    if tail.size:
        scalar = {"pars": np.ascontiguousarray(kwargs["pars"][: fn.scalar.nparams, tail])} if kwargs else {}
        out[:, tail] = fn.scalar(np.ascontiguousarray(flat[:, tail]), **scalar)
    return out.reshape(out.shape[0], lanes, row)[:, :, :n_samples]

"""How a batch integrator is called: the same bits along every path, up to 1.4 times the speed along some.

What was measured
-----------------
heyoka's JIT-compiled Taylor step of a batch integrator runs about 1.0 or about 1.4 (x) as long
for the same integrator, batches and steps, depending only on how Python reaches
``propagate_grid``: with keywords written out or as a mapping (``**options``), directly or one C
frame deeper (``next(map(...))``).  Which path is fast differs between threads and, for the main
thread, between processes, which points at the alignment of the C stack when the JIT code runs
(its AVX-512 temporaries across 64-byte boundaries); a path changes how much C stack CPython and
pybind11 use before heyoka is entered.  Measured with AVX-512, batch 8, on the disk's lanes; see
``python -m verify bench`` ("Call paths").  The arithmetic is the same: the results are bit for bit
equal along every path (tests/test_call_paths.py).

What is done about it
---------------------
:class:`PathChooser`: a worker runs its first batches along each path of :data:`PATHS` in turn, times
them per step, and runs the rest along the fastest.  The choice moves time, never bits: a loaded
machine that misjudges it costs speed only.
"""
from __future__ import annotations

import time
from typing import Optional

#: The ways of calling ``propagate_grid`` tried by each worker: (keywords written out or a mapping,
#: extra C frames).
PATHS = (("keywords", 0), ("keywords", 1), ("mapping", 0), ("mapping", 1))
#: A calibration batch counts only with at least this many steps: below it the call's own
#: overhead, not the step, sets its time per step.
MIN_STEPS = 64
NO_CAP = float("inf")  # heyoka's max_delta_t when there is no cap
NO_LIMIT = 0  # heyoka's max_steps when there is no limit


def propagate_grid(ta, grid, path, max_delta_t: Optional[float] = None, max_steps: Optional[int] = None):
    """``ta.propagate_grid(grid, max_delta_t=..., max_steps=...)`` along ``path`` (an item of :data:`PATHS`)."""
    form, depth = path
    cap = NO_CAP if max_delta_t is None else float(max_delta_t)
    limit = NO_LIMIT if max_steps is None else int(max_steps)
    call = _keywords if form == "keywords" else _mapping
    return at_depth(lambda: call(ta, grid, cap, limit), depth)


def _keywords(ta, grid, cap, limit):
    return ta.propagate_grid(grid, max_delta_t=cap, max_steps=limit)


def _mapping(ta, grid, cap, limit):
    options = {"max_delta_t": cap, "max_steps": limit}
    return ta.propagate_grid(grid, **options)


def at_depth(fn, depth: int):
    """``fn()`` called ``depth`` C frames deeper than a direct call (each a ``next(map(...))`` round trip)."""
    if depth <= 0:
        return fn()
    return next(map(_deeper, ((fn, depth - 1),)))


def _deeper(args):
    return at_depth(*args)


class PathChooser:
    """One worker's choice of path: each of :data:`PATHS` in turn on batches of at least
    :data:`MIN_STEPS` steps, then the fastest per step.  ``path()`` before a batch, ``record()`` after."""

    def __init__(self, paths=PATHS, min_steps: int = MIN_STEPS):
        self.paths, self.min_steps = tuple(paths), int(min_steps)
        self.per_step: dict = {}
        self.chosen = None if len(self.paths) > 1 else self.paths[0]

    def path(self):
        if self.chosen is not None:
            return self.chosen
        return next(p for p in self.paths if p not in self.per_step)

    def record(self, path, seconds: float, steps: int) -> None:
        if self.chosen is not None or steps < self.min_steps:
            return
        self.per_step[path] = seconds / steps
        if len(self.per_step) == len(self.paths):
            self.chosen = min(self.paths, key=self.per_step.__getitem__)


def timed_propagate_grid(chooser: PathChooser, ta, grid, max_delta_t=None, max_steps=None):
    """:func:`propagate_grid` along ``chooser``'s path, its time per step (the most any lane took) recorded."""
    path = chooser.path()
    start = time.perf_counter()
    out = propagate_grid(ta, grid, path, max_delta_t, max_steps)
    chooser.record(path, time.perf_counter() - start, max(int(r[3]) for r in ta.propagate_res))
    return out

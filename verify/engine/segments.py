"""The segment scheme of :func:`verify.engine.single.solve`: fixed segments, cyclic coordinates kept small.

heyoka's step-size control is relative to the largest state component, so a phi, psi, x or y that
grows without bound loosens the control of theta and the rates, and the energy error grows like t
instead of Brouwer's sqrt(t) (HEYOKA.md).  None of phi, psi, x, y feeds back into the dynamics
(psi, x, y appear nowhere on the right-hand side, phi only through x', y'), so the run is cut into
fixed segments and between segments they are moved into offsets kept outside the integrator: phi
and psi by whole turns (exact multiples of the precision's 2 pi, so sin and cos of phi are
unchanged), x and y entirely.  The returned phi, psi, x, y are the offsets plus the reduced values:
continuous, never reduced modulo 2 pi.

What it costs against one bare ``propagate_until`` (disk, double, 100 s; ``reports/BENCHMARKS.md``):
the reduced state keeps the error control tight, ~20 % more steps than bare heyoka takes with
angles grown to 10^3; each segment also truncates one step at its end and, being one
``propagate_grid`` call, starts with heyoka's step to the double-rounded start time.
"""
from __future__ import annotations

import bisect
import math
import time
from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import mpmath
import numpy as np

from ..precision import Precision

_CYCLIC = (1, 2, 6, 7)  # phi, psi, x, y
_ANGLES = (1, 2)

#: A segment (2 pi radians of the fastest initial rate) may take 2 pi COLLAPSE_FACTOR steps.
COLLAPSE_FACTOR = 2 ** 15
#: The progress hook is called at most this often (seconds of wall time).
PROGRESS_SECONDS = 0.5

_TIME_LIMIT = hy.taylor_outcome.time_limit
_STEP_LIMIT = hy.taylor_outcome.step_limit


def integer_reader(precision: Precision):
    """n -> the integer n at ``precision``, as ``precision.number`` reads it (exactly: |n| < 2^53 here),
    without its general path (a Fraction per call) where the type takes an int exactly itself."""
    if precision.name in ("double", "long"):
        return precision.fp_type
    return precision.number


@lru_cache(maxsize=None)
def two_pi(precision: Precision):
    """2 pi rounded once to ``precision`` (the turn the angles are moved by)."""
    with mpmath.workprec(precision.bits + 32):
        return precision.number(2 * mpmath.pi)


class Offsets:
    """phi, psi, x, y moved out of the integrator (module docstring)."""

    def __init__(self, precision: Precision):
        self.fp = integer_reader(precision)
        self.two_pi = two_pi(precision)
        turn = float(self.two_pi)
        self.limits = ((1, turn, True), (2, turn, True), (6, 1.0, False), (7, 1.0, False))
        self.columns = list(_CYCLIC)
        self.vector_limits = np.array([turn, turn, 1.0, 1.0]) if precision.name in ("double", "long") else None
        zero = precision.zero()
        self.value = {i: zero for i in _CYCLIC}

    def rebase(self, st) -> None:
        """Move whole turns of phi, psi and all of x, y from the state into the offsets."""
        turn = self.limits[0][1]
        # the comparisons in Python floats (one tolist where the dtype allows: ~1 us, a numpy test of four
        # values costs ~4 us a segment); the values moved keep the state's own precision
        floats = st.tolist() if self.vector_limits is not None else None
        for i, limit, angle in self.limits:
            f = floats[i] if floats is not None else float(st[i])
            if abs(f) <= limit:
                continue
            v = st[i]
            moved = self.fp(round(f / turn)) * self.two_pi if angle else v
            st[i] = v - moved
            self.value[i] = self.value[i] + moved

    def restore_rows(self, rows) -> np.ndarray:
        """The rows (one state each) with the offsets added back, one array addition per cyclic column."""
        rows = np.array(rows)
        for i in _CYCLIC:
            rows[:, i] = rows[:, i] + self.value[i]
        return rows


class Clock:
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
class Run:
    """What :func:`propagate_segments` reached: heyoka's last outcome, the steps, the output times
    ``t`` and states ``y`` (one row per output, phi, psi, x, y with their offsets added back);
    ``collapsed`` when a segment ran out of its step budget (then ``last_h`` is heyoka's last step)."""

    outcome: object
    steps: int
    t: np.ndarray
    y: np.ndarray
    collapsed: bool = False
    last_h: object = None


class _Blocks:
    """Output times and rows collected segment by segment and joined once at the end."""

    def __init__(self, grid, ta):
        self.dtype = grid.dtype
        self.times, self.rows = [grid[:1]], [np.array(ta.state)[None, :]]

    def add(self, times, rows) -> None:
        self.times.append(times)
        self.rows.append(rows)

    def add_state(self, ta, offsets: Offsets) -> None:
        """The integrator's own time and state (a segment end, an event, a failure)."""
        self.add(self.scalar(ta.time), offsets.restore_rows(np.array(ta.state)[None, :]))

    def scalar(self, value) -> np.ndarray:
        out = np.empty(1, dtype=self.dtype)
        out[0] = value
        return out

    def run(self, outcome, steps, collapsed=False, last_h=None) -> Run:
        return Run(outcome, steps, np.concatenate(self.times), np.concatenate(self.rows), collapsed, last_h)


def _segment_grid(prec: Precision, start, inside: np.ndarray, end) -> np.ndarray:
    """[start, *inside, end] at the run's precision, as ``propagate_grid`` takes it."""
    if prec.name in ("double", "long"):
        out = np.empty(len(inside) + 2, dtype=inside.dtype)
        out[0], out[1:-1], out[-1] = start, inside, end
        return out
    return prec.array([start] + list(inside) + [end])


def propagate_segments(ta, grid, t_end, h_max, prec: Precision, progress=None) -> Run:
    """Integrate over fixed segments of 2 pi h_max, rebasing between them.

    A segment is one ``propagate_grid`` call (heyoka's C++ loop, dense output at the grid
    points inside it), so the Python cost is per segment, not per step; a segment holds at
    least 2 pi steps (h <= h_max) and typically hundreds.  Segment ends depend on t_end and
    the initial rates only, so the steps, and the bits of the result, do not depend on the
    output grid.  A segment may take at most 2 pi COLLAPSE_FACTOR steps (``max_steps``; beyond
    that the step size has collapsed, see :mod:`verify.engine.single`).  The ``progress`` hook is
    called between segments, or from heyoka's step callback where segments are slow
    (:class:`Clock`); segments are never split for it (a new ``propagate_grid`` call from
    inside a segment would start with a tiny step to the double-rounded time and change the
    bits), so the result is the same with or without it (tests/test_api.py).
    """
    offsets = Offsets(prec)
    integer = integer_reader(prec)
    seg = prec.number(2 * math.pi) * h_max
    kwargs = {"max_delta_t": h_max, "max_steps": int(2 * math.pi * COLLAPSE_FACTOR)}
    clock = Clock(progress) if progress is not None else None
    out = _Blocks(grid, ta)
    steps = 0
    n_grid = len(grid)
    j, k = 1, 1  # next output grid index, segment number
    while True:
        end = integer(k) * seg
        if not end < t_end:
            end = t_end
        stop = bisect.bisect_left(grid, end, j)  # grid[j:stop] lies inside the segment
        inside = grid[j:stop]
        j = stop
        if clock is not None and clock.per_step:
            kwargs["callback"] = clock.callback()
        res = ta.propagate_grid(_segment_grid(prec, ta.time, inside, end), **kwargs)
        outcome, steps = res[0], steps + int(res[3])
        rows = res[-1][1:]
        kept = rows[: len(inside)]
        if len(kept):
            out.add(inside[: len(kept)], offsets.restore_rows(kept))
        finished = len(rows) == len(inside) + 1  # (heyoka says step_limit when the budget ends on t_end)
        if outcome == _STEP_LIMIT and not finished:  # the step size collapsed
            out.add_state(ta, offsets)
            return out.run(outcome, steps, True, ta.last_h)
        if outcome != _TIME_LIMIT and outcome != _STEP_LIMIT:  # an event or a failure
            out.add_state(ta, offsets)
            return out.run(outcome, steps)
        if j < n_grid and not grid[j] > end:  # the segment end is itself an output point
            out.add(out.scalar(end), offsets.restore_rows(np.array(ta.state)[None, :]))
            j += 1
        if clock is not None:
            clock.segment_done(ta.time, steps)
        if not end < t_end:
            return out.run(_TIME_LIMIT, steps)
        offsets.rebase(ta.state)
        k += 1

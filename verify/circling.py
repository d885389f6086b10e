"""The sense in which a centre-of-mass path circles over many nutation loops.

A rolling body that nutates draws fast loops (one per nutation) on top of a slow drift of
the loops' centres.  The captions' words ("clockwise CM motion", "a generally clockwise
orbit", "the CM spirals outward") are about the slow drift, not about the loops: the total
turning of the raw path counts every loop and so reports the sense of the loops.  Here the
slow path is extracted twice, by two filters that share nothing but the run:

* **stroboscopic**: the CM sampled once per nutation, at the successive maxima of theta
  (located by a parabola through the three output points around each maximum), and the
  sense read as the winding angle of those samples about their centroid;
* **running mean**: the CM averaged over one nutation period (the median spacing of those
  maxima) by differences of the cumulative trapezoidal integral, and the sense read as the
  signed area the averaged path sweeps about its centroid, expressed as turns of a circle of
  the same mean radius.

Both are in turns (> 0 counter-clockwise seen from above, z up).  The stroboscopic samples
resolve a slow path only if they advance by less than :data:`RESOLVED_STEP` of a turn from
one to the next (median); otherwise they alias the motion (a circle traversed at 0.57 turn a
sample looks like one traversed backwards at 0.43) and that measure gives no sense.  The
running mean needs at least :data:`MIN_POINTS_PER_NUTATION` output points a nutation.  Neither
filter can tell a slow drift from loops that are not locked to the nutation (their attenuated
remainder also sweeps area): where the scales do not separate the two measures disagree, and
the sense is left undecided -- which is the point of having two.  One median period serves
the whole path, so a run whose nutation period changes much should be cut into windows of a
few nutations first (the sweep engine does: ``verify.sweep.engine.orbit_windows``).  A measure decides only
when its slow path turns by at least :data:`DECISIVE_TURNS`; two measures agree when both
decide and have the same sign.  With no nutation (theta constant to round-off) the path
itself is the slow path, and the same two reductions (winding and area) are applied to it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

DECISIVE_TURNS = 0.5  # half a turn of the slow path: less is a drift, not a circling
RESOLVED_STEP = 0.25  # turns between stroboscopic samples: more, and the samples alias the motion
MIN_POINTS_PER_NUTATION = 16  # the running mean (second order in the grid) is off by up to 20% at 5
MIN_NUTATIONS = 4  # fewer maxima of theta than this: too short a run to filter


@dataclass(frozen=True)
class Sense:
    """One measure of the circling sense: signed turns and whether they decide."""

    name: str
    turns: float  # > 0 counter-clockwise seen from above

    @property
    def decides(self) -> bool:
        return math.isfinite(self.turns) and abs(self.turns) >= DECISIVE_TURNS

    @property
    def sign(self) -> int:
        return int(np.sign(self.turns)) if self.decides else 0

    def value(self) -> str:
        if not math.isfinite(self.turns):
            return "no slow path"
        word = {1: "counter-clockwise", -1: "clockwise", 0: "undecided"}[self.sign]
        return f"{self.turns:+.2f} turns ({word})"

    def text(self) -> str:
        return f"{self.name}: {self.value()}"


@dataclass(frozen=True)
class Circling:
    """The two measures of one path, and the nutation they filtered out."""

    strobe: Sense
    mean: Sense
    nutation_period: float  # s; NaN when there is no nutation
    n_nutations: int

    @property
    def agree(self) -> bool:
        return self.strobe.sign != 0 and self.strobe.sign == self.mean.sign

    @property
    def sign(self) -> int:
        """+1 counter-clockwise, -1 clockwise, 0 when the measures do not both decide alike."""
        return self.strobe.sign if self.agree else 0

    def word(self) -> str:
        return {1: "counter-clockwise", -1: "clockwise", 0: "undecided"}[self.sign]

    def measures(self) -> tuple:
        """(name, text) pairs for an Evaluation."""
        return ((self.strobe.name, self.strobe.value()), (self.mean.name, self.mean.value()))


def theta_maxima(t: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Times of the strict local maxima of theta, refined by a parabola through three points."""
    th = np.asarray(theta, dtype=float)
    i = np.nonzero((th[1:-1] > th[:-2]) & (th[1:-1] >= th[2:]))[0] + 1
    if len(i) == 0:
        return np.array([])
    a, b, c = th[i - 1], th[i], th[i + 1]
    den = a - 2 * b + c
    shift = np.where(den != 0, 0.5 * (a - c) / np.where(den != 0, den, 1.0), 0.0)
    dt = np.asarray(t, dtype=float)[i + 1] - np.asarray(t, dtype=float)[i]
    return np.asarray(t, dtype=float)[i] + np.clip(shift, -0.5, 0.5) * dt


def winding_turns(x: np.ndarray, y: np.ndarray) -> float:
    """Signed turns the points sweep about their centroid (> 0 counter-clockwise)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if len(x) < 3:
        return math.nan
    ang = np.unwrap(np.arctan2(y - y.mean(), x - x.mean()))
    return float(ang[-1] - ang[0]) / (2 * math.pi)


def area_turns(x: np.ndarray, y: np.ndarray) -> float:
    """Signed area swept about the centroid, in turns of a circle of the path's rms radius."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if len(x) < 3:
        return math.nan
    xs, ys = x - x.mean(), y - y.mean()
    swept = 0.5 * float(np.sum(xs[:-1] * np.diff(ys) - ys[:-1] * np.diff(xs)))
    r2 = float(np.mean(xs**2 + ys**2))
    return swept / (math.pi * r2) if r2 > 0 else math.nan


def running_mean(t: np.ndarray, values: np.ndarray, window: float):
    """Mean of ``values`` over [t - window/2, t + window/2] (trapezoid rule), where the window fits."""
    t, v = np.asarray(t, float), np.asarray(values, float)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    centre = t[(t >= t[0] + window / 2) & (t <= t[-1] - window / 2)]
    hi = np.interp(centre + window / 2, t, cum)
    lo = np.interp(centre - window / 2, t, cum)
    return centre, (hi - lo) / window


def circling(t, x, y, theta, nutation_floor: float = 1e-9, whole_path: bool = False) -> Circling:
    """The circling sense of the CM path (x, y)(t) over the nutation of theta(t), two ways.

    ``t`` must be a fine uniform grid (several points per nutation).  ``nutation_floor``:
    a theta spread below it (rad) counts as no nutation.

    ``whole_path``: when the CM circles faster than a quarter turn a nutation there is no
    slow path for the once-per-nutation samples to resolve.  For a whole run (a figure's
    path) the first measure is then the winding of the raw path about its own centroid --
    how often the CM goes round the centre of everything it drew, which counts a guide
    circle and not loops that do not enclose that centre.  Windows cut out of a decaying run
    (the sweep engine) keep the default, undecided there: a window's centroid is not the
    centre of an orbit.
    """
    t, x, y, theta = (np.asarray(v, dtype=float) for v in (t, x, y, theta))
    if np.ptp(theta) < nutation_floor:
        return Circling(Sense("path winding (no nutation)", winding_turns(x, y)),
                        Sense("path area (no nutation)", area_turns(x, y)), math.nan, 0)
    marks = theta_maxima(t, theta)
    if len(marks) < MIN_NUTATIONS:
        nan = math.nan
        return Circling(Sense("CM once per nutation, winding", nan), Sense("CM mean over a nutation, area", nan),
                        nan, len(marks))
    period = float(np.median(np.diff(marks)))
    sx, sy = np.interp(marks, t, x), np.interp(marks, t, y)
    _, mx = running_mean(t, x, period)
    _, my = running_mean(t, y, period)
    strobe = winding_turns(sx, sy)
    mean = area_turns(mx, my) if period / float(np.median(np.diff(t))) >= MIN_POINTS_PER_NUTATION else math.nan
    if np.median(np.abs(np.diff(np.unwrap(np.arctan2(sy - sy.mean(), sx - sx.mean()))))) / (2 * math.pi) > RESOLVED_STEP:
        if whole_path:  # no slow path to sample: the orbit is the path's own circling
            return Circling(Sense("CM path winding about its centroid (no separate slow path)", winding_turns(x, y)),
                            Sense("CM mean over a nutation, area", mean), period, len(marks))
        strobe = math.nan  # the CM circles too fast to be sampled once per nutation: no slow path there
    return Circling(Sense("CM once per nutation, winding", strobe),
                    Sense("CM mean over a nutation, area", mean), period, len(marks))


def epicycle(t, guide_rate: float, loop_rate: float, guide_radius: float = 1.0, loop_radius: float = 0.3,
             wobble_rate: float = None):
    """A synthetic path for negative controls: loops at ``loop_rate`` on a guide circle at ``guide_rate``.

    Returns (x, y, theta) with theta nutating once per loop (maxima where the loop phase is 0).
    """
    t = np.asarray(t, float)
    x = guide_radius * np.cos(guide_rate * t) + loop_radius * np.cos(loop_rate * t)
    y = guide_radius * np.sin(guide_rate * t) + loop_radius * np.sin(loop_rate * t)
    theta = 0.1 + 0.01 * np.cos(abs(loop_rate if wobble_rate is None else wobble_rate) * t)
    return x, y, theta

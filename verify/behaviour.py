"""Qualitative statements about theta(t), each decided by two measures computed differently.

A caption's words -- "wobbles above and below pi/2", "oscillates on one side of
equilibrium", "theta oscillates", "theta quickly exceeds the limit" -- become a verdict here
only when two measures that share nothing but the run agree; when they disagree the
statement is undecided (:attr:`Reading.holds` is None) and both numbers are shown.

* sides of a level: the number of sign changes of theta - level on the output grid, and the
  fractions of the run's *time* spent on each side (trapezoid weights, so a crossing between
  two output points still counts its share);
* oscillation: the turning points of theta (maxima refined by a parabola), and the envelope
  (the second half of the run stays within the first half's range, widened by half of it:
  bounded motion neither grows nor drifts);
* leaving a domain: heyoka's terminal event (root-finding of the event function inside a
  step) in one run, and the output grid of a second run with the events switched off.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .circling import theta_maxima

SIDE_FRACTION = 0.05  # "above and below" needs at least 5 % of the time on each side
MIN_TURNING_POINTS = 3  # "oscillates" needs at least three maxima of theta
ENVELOPE_GROWTH = 2.0  # bounded: the second half's range at most twice the first half's


@dataclass(frozen=True)
class Reading:
    """A statement read from a run by two measures."""

    statement: str
    first: tuple  # (name, value text, verdict: bool)
    second: tuple

    def __post_init__(self):
        for key in ("first", "second"):
            name, value, verdict = getattr(self, key)
            object.__setattr__(self, key, (name, value, bool(verdict)))  # numpy bools become Python bools

    @property
    def holds(self) -> Optional[bool]:
        """True or False when the measures agree, None when they disagree."""
        return self.first[2] if self.first[2] == self.second[2] else None

    def measures(self) -> tuple:
        return ((self.first[0], f"{self.first[1]} -> {'yes' if self.first[2] else 'no'}"),
                (self.second[0], f"{self.second[1]} -> {'yes' if self.second[2] else 'no'}"))

    def text(self) -> str:
        word = {True: "yes", False: "no", None: "undecided (the measures disagree)"}[self.holds]
        return (f"{self.statement}: {word} [{self.first[0]}: {self.first[1]}; "
                f"{self.second[0]}: {self.second[1]}]")


def side_fractions(t, values, level) -> tuple:
    """Fractions of the run's time with values below and above ``level`` (linear between points)."""
    t, v = np.asarray(t, float), np.asarray(values, float) - level
    below = above = 0.0
    for a, b, dt in zip(v[:-1], v[1:], np.diff(t)):
        if a >= 0 and b >= 0:
            above += dt
        elif a <= 0 and b <= 0:
            below += dt
        else:  # crosses inside the interval
            f = a / (a - b)
            first, second = f * dt, (1 - f) * dt
            if a > 0:
                above, below = above + first, below + second
            else:
                below, above = below + first, above + second
    total = float(t[-1] - t[0])
    return below / total, above / total


def crossings(values, level) -> int:
    s = np.sign(np.asarray(values, float) - level)
    s = s[s != 0]
    return int(np.count_nonzero(s[1:] != s[:-1]))


def both_sides(t, theta, level, name="both sides of the level") -> Reading:
    """Does theta spend time on both sides of ``level`` (wobble above and below)?"""
    n = crossings(theta, level)
    lo, hi = side_fractions(t, theta, level)
    return Reading(name, ("sign changes of theta - level", str(n), n >= 2),
                   ("time below / above", f"{lo:.3f} / {hi:.3f}", min(lo, hi) >= SIDE_FRACTION))


def one_side(t, theta, level, name="one side of the level") -> Reading:
    """Does theta stay on one side of ``level`` for the whole run?"""
    n = crossings(theta, level)
    lo, hi = side_fractions(t, theta, level)
    return Reading(name, ("sign changes of theta - level", str(n), n == 0),
                   ("time below / above", f"{lo:.4f} / {hi:.4f}", min(lo, hi) == 0.0))


def oscillates(t, theta, completed: bool, name="theta oscillates") -> Reading:
    """Does theta oscillate (turn back repeatedly) and stay bounded over a completed run?

    The envelope measure: the second half of the run stays within the first half's range
    widened by half of it on each side (ENVELOPE_GROWTH = 2: an oscillation whose amplitude at
    most doubles, with no drift of its centre beyond that).
    """
    t, th = np.asarray(t, float), np.asarray(theta, float)
    n = len(theta_maxima(t, th))
    half = len(th) // 2
    lo, hi = th[: half + 1].min(), th[: half + 1].max()
    margin = (ENVELOPE_GROWTH - 1) / 2 * (hi - lo)
    late = th[half:]
    excess = max(lo - late.min(), late.max() - hi, 0.0) / (hi - lo) if hi > lo else math.inf
    return Reading(name, ("maxima of theta", f"{n}{'' if completed else ' (run stopped early)'}",
                          completed and n >= MIN_TURNING_POINTS),
                   ("2nd half beyond the 1st half's range, / that range",
                    f"{excess:.3g}{'' if completed else ' (run stopped early)'}",
                    completed and excess <= margin / (hi - lo) if hi > lo else False))


def leaves(event_outcome: str, event_name: str, event_time: float, t_free, theta_free, limit: float,
           above: bool = True, name="theta leaves the domain") -> Reading:
    """Does theta reach ``limit``?  By the run's terminal event and by a run without events."""
    th = np.asarray(theta_free, float)
    hit = np.nonzero(th >= limit if above else th <= limit)[0]
    t_grid = float(np.asarray(t_free, float)[hit[0]]) if len(hit) else math.nan
    by_event = event_outcome == f"event:{event_name}"
    return Reading(name, (f"terminal event {event_name}", f"{event_outcome} at t = {event_time:.4g} s", by_event),
                   ("output grid of a run without events",
                    f"theta first past {limit:.6g} at t = {t_grid:.4g} s" if len(hit) else
                    f"theta stays within {limit:.6g} (extreme {th.max() if above else th.min():.6g})", bool(len(hit))))


def spirals_out(t, x, y, theta=None, name="the CM spirals outward") -> Reading:
    """Does the CM spiral away from where it started (up to its farthest point)?

    Two measures: how far the CM gets (its largest distance from the start against the
    largest over the first tenth of the run: at least 3 for 'out'); and the spiral itself,
    read in polar coordinates about the start up to the farthest point: the distance sampled
    once per turn of the polar angle must grow from turn to turn (in at least 80 % of at
    least two turns).  A path that goes out in a straight line, or circles without receding,
    fails the second.
    """
    t, x, y = (np.asarray(v, float) for v in (t, x, y))
    r = np.hypot(x - x[0], y - y[0])
    n = len(t)
    early = float(r[: max(n // 10, 2)].max())
    far = int(np.argmax(r))
    ratio = float(r[far]) / early if early > 0 else math.inf
    keep = slice(max(n // 100, 1), far + 1)  # skip the first points, where the polar angle about the start is noise
    ang = np.unwrap(np.arctan2(y[keep] - y[0], x[keep] - x[0]))
    turns, growing = 0, 0.0
    if len(ang) > 2 and np.ptp(ang) > 0:
        swept = np.abs(ang - ang[0])
        marks = np.arange(2 * math.pi, swept.max(), 2 * math.pi)
        first = np.searchsorted(np.maximum.accumulate(swept), marks)
        per_turn = r[keep][first] if len(first) else np.array([])
        turns = len(per_turn)
        growing = float(np.mean(np.diff(np.concatenate([[r[keep][0]], per_turn])) > 0)) if turns else 0.0
    return Reading(name, ("farthest distance from the start / farthest over the first tenth", f"{ratio:.3g}", ratio >= 3),
                   ("distance once per turn about the start, growing turn to turn",
                    f"{growing:.0%} of {turns} turns", turns >= 2 and growing >= 0.8))

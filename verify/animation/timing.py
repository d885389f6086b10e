"""The animation's clock: the speed factor, the frame times, and the states at those times.

Speed rule (simulated seconds per second of animation)
-------------------------------------------------------
The fastest thing to follow is the body turning: the mark on the rim (or on a ball) goes
round at the body's angular speed |omega|, with omega = (thetadot, phidot sin(theta),
phidot cos(theta) + psidot) in (e1, e2, e3) (paper Eq. 16).  The default speed is the one at
which the largest |omega| of the run is one turn per second of animation,

    speed = min(1, 2 pi / max |omega|), rounded down to two significant digits,

never faster than real time when the body is slow.  A run whose animation would then last
longer than ``max_seconds`` is sped up to fit: ``speed = duration / max_seconds``, rounded up
likewise; the
record says so (``raised``) and the clock text shows the factor used.  The rates come from
the run's grid (``numpy.gradient`` of the continuous angles), so a run needs no rates.

Frames and interpolation
------------------------
Frame k is at animation time k / fps, i.e. simulated time t0 + k speed / fps; the last frame
is the run's last state (held if the step does not land on it).  States between grid points
are linear interpolations of theta, phi, psi, x, y: phi and psi are continuous, so this is
exact to first order.  It is faithful only where the body turns little between grid points;
a grid on which the body turns by more than :data:`MAX_GRID_TURN` radians in one step
(the angle of the rotation between the two orientations) is refused (``AnimationError``), whatever the frame rate, because then the frames
show chords of the motion, not the motion (a grid with fewer points than frames but small
steps is fine: its frames are interpolated).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import AnimationError
from .geometry import rotation

#: Largest turn of the body (radians) between two grid points that linear interpolation draws
#: faithfully: 0.5 rad keeps the chord's sag at 1 - cos(0.25) = 3 % of the radius.
MAX_GRID_TURN = 0.5
#: One turn per second of animation for the fastest turning (see the module docstring).
TURNS_PER_SECOND = 1.0


@dataclass(frozen=True)
class Clock:
    """The animation's time base: ``speed`` (sim s per animation s), frame times ``times``
    (sim s), whether ``speed`` was raised to fit ``max_seconds``, and the rule that set it."""

    speed: float
    times: np.ndarray
    raised: bool
    rule: str


def angular_speed(arrays: dict) -> np.ndarray:
    """|omega| on the run's grid from the gradients of theta, phi, psi (paper Eq. 16)."""
    t, th = arrays["t"], arrays["theta"]
    thd, phd, psd = (np.gradient(arrays[n], t) for n in ("theta", "phi", "psi"))
    return np.sqrt(thd ** 2 + (phd * np.sin(th)) ** 2 + (phd * np.cos(th) + psd) ** 2)


def grid_turn(arrays: dict) -> np.ndarray:
    """The angle (radians) the body turns between consecutive grid points: the angle of the
    rotation R_i^T R_(i+1), exact and free of the Euler angles' singularity at theta = 0 (where
    phi and psi can each jump while phi + psi, and so the body, barely moves)."""
    r = rotation(arrays["theta"], arrays["phi"], arrays["psi"])
    trace = np.einsum("nij,nij->n", r[:-1], r[1:])  # trace(R_i^T R_(i+1))
    return np.arccos(np.clip((trace - 1) / 2, -1.0, 1.0))


def check_grid(label: str, arrays: dict) -> None:
    """Refuse a grid too coarse to interpolate (module docstring); one-line ``AnimationError``."""
    turn = grid_turn(arrays)
    worst = int(np.argmax(turn))
    if turn[worst] > MAX_GRID_TURN:
        t = arrays["t"]
        raise AnimationError(
            f"run {label!r}: the body turns {turn[worst]:.3g} rad between grid points t = {t[worst]:.6g} and "
            f"{t[worst + 1]:.6g} s; allowed: at most {MAX_GRID_TURN} rad per step (rerun with more output points, "
            f"e.g. n_eval >= {int(np.ceil(len(t) * turn[worst] / MAX_GRID_TURN)) + 1})")


def clock(runs_arrays: list, fps: float, speed, max_seconds: float) -> Clock:
    """The shared clock of several runs (all panels show the same simulated time).

    Parameters
    ----------
    runs_arrays : list of dict
        Each run's checked arrays (``t``, ``theta``, ``phi``, ``psi``, ...).
    fps : float
        Frames per second of animation.
    speed : float or None
        Simulated seconds per animation second; None: the default rule (module docstring).
    max_seconds : float
        Longest animation; with ``speed`` None a longer one is sped up to fit, with a
        given ``speed`` it is refused.

    Returns
    -------
    Clock
    """
    t0 = min(a["t"][0] for a in runs_arrays)
    t1 = max(a["t"][-1] for a in runs_arrays)
    duration = t1 - t0
    raised = False
    if speed is None:
        fastest = max(float(np.max(angular_speed(a))) for a in runs_arrays)
        speed = nice(min(1.0, 2 * np.pi * TURNS_PER_SECOND / fastest), down=True) if fastest > 0 else 1.0
        rule = f"fastest turn {fastest:.3g} rad/s shown at <= {TURNS_PER_SECOND:g} turn/s"
        if duration / speed > max_seconds:
            speed, raised = nice(duration / max_seconds, down=False), True
            rule += f"; raised to fit {max_seconds:g} s"
    else:
        rule = "given"
        if duration / speed > max_seconds * (1 + 1e-12):
            raise AnimationError(f"speed={speed!r} makes a {duration / speed:.4g} s animation; allowed: at most "
                                 f"max_seconds={max_seconds!r} (raise speed or max_seconds)")
    step = speed / fps
    n = int(np.ceil(duration / step - 1e-9)) + 1
    times = np.minimum(t0 + step * np.arange(n), t1)
    return Clock(float(speed), times, raised, rule)


def nice(value: float, down: bool) -> float:
    """``value`` rounded down (or up) to two significant digits, so the stated factor reads simply
    (0.19x rather than 0.1973x) and moves the rule by at most 10 %."""
    scale = 10.0 ** (np.floor(np.log10(value)) - 1)
    units = value / scale
    return float((np.floor(units * (1 + 1e-12)) if down else np.ceil(units * (1 - 1e-12))) * scale)


def states_at(arrays: dict, times: np.ndarray) -> dict:
    """theta, phi, psi, x, y at ``times`` by linear interpolation; before a run's start its
    first state, after its end its last (the run stopped: held still)."""
    return {n: np.interp(times, arrays["t"], arrays[n]) for n in ("theta", "phi", "psi", "x", "y")}


def speed_text(speed: float) -> str:
    """'shown at 0.25x real time (slow motion)', 'in real time', 'shown at 3x real time (sped up)'."""
    if abs(speed - 1) < 1e-9:
        return "in real time"
    return f"shown at {speed:.3g}x real time ({'slow motion' if speed < 1 else 'sped up'})"

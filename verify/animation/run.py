"""One run to animate: the body, its parameters and its state on the run's output grid (and, for a run
with friction, the contact's slip and phase)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import AnimationError

#: The angles and positions an animation reads, in the order of the dataclass.
STATE_FIELDS = ("theta", "phi", "psi", "x", "y")


@dataclass(frozen=True, eq=False)  # eq on arrays is ambiguous: runs compare by identity
class AnimationRun:
    """A run of one body on its output grid, ready to be drawn.

    Parameters
    ----------
    label : str
        The panel's title (e.g. ``"stable: phidot = 30"``).
    model : str
        A name of :data:`models.ALL_NAMES` or ``"disk+coulomb"``, ``"ring+coulomb"``
        (which bodies can be drawn: :data:`verify.animation.bodies.DRAWN_MODELS`).
    params : dict of str to float
        The body's parameters by name: ``k`` for the disks (``k = 1/2`` is drawn as a hoop),
        ``h`` (and optionally the wall ``w``) for the rings; ``I1``, ``I3``, ``g`` may be given
        and are not read.
    t, theta, phi, psi, x, y : numpy.ndarray
        The state on the run's grid (1-D float arrays of one length, at least 2 points):
        times non-decreasing (a repeated time, as a terminal event or a phase switch leaves,
        is dropped when the run is read, keeping the later state), the Euler angles of
        :mod:`models.symbols` with phi and psi continuous (not reduced mod 2 pi), and (x, y)
        the centre of mass.
    body : models.bodies.Body, optional
        The body of revolution of a ``body:NAME`` model (drawn from its profile,
        :mod:`verify.animation.revolution`); None: a shipped body's file is read by its name.
    slip_x, slip_y : numpy.ndarray, optional
        The contact point's slip velocity u (inertial x, y; body lengths per second) on the grid,
        0 where the body rolls: drawn as an arrow at the contact.
    phase : numpy.ndarray of str, optional
        What the contact does at each grid point ('rolling', 'sliding', ...), shown as text.
    """

    label: str
    model: str
    params: dict
    t: np.ndarray
    theta: np.ndarray
    phi: np.ndarray
    psi: np.ndarray
    x: np.ndarray
    y: np.ndarray
    body: object = None
    slip_x: np.ndarray | None = None
    slip_y: np.ndarray | None = None
    phase: np.ndarray | None = None

    @classmethod
    def from_solution(cls, label: str, model: str, solution, params=None, **extra) -> "AnimationRun":
        """An :class:`AnimationRun` of a :class:`verify.engine.trajectory.Trajectory` (or any
        object with ``t`` and ``solution[name]``); ``params`` as floats by name; ``extra``: the
        optional fields (``body``, ``slip_x``, ``slip_y``, ``phase``)."""
        arrays = {name: np.asarray(solution[name], float) for name in STATE_FIELDS}
        return cls(label=label, model=model, params={k: float(v) for k, v in dict(params or {}).items()},
                   t=np.asarray(solution.t, float), **arrays, **extra)


def checked_arrays(run: AnimationRun) -> dict:
    """The run's arrays as float arrays on a strictly increasing grid.

    Raises
    ------
    AnimationError
        An array is missing, of another length, not finite, or the times decrease or
        (but for repeated times, which are dropped keeping the last state) have fewer than
        two distinct values.
    """
    names = ("t",) + STATE_FIELDS
    out = {}
    optional = [n for n in ("slip_x", "slip_y") if getattr(run, n) is not None]
    if len(optional) == 1:
        raise AnimationError(f"run {run.label!r}: {optional[0]} without its partner; allowed: both slip_x and slip_y "
                             "or neither")
    for name in names + tuple(optional):
        value = getattr(run, name)
        if value is None:
            raise AnimationError(f"run {run.label!r}: {name} is missing; give 1-D float arrays {', '.join(names)}")
        array = np.asarray(value, dtype=float)
        if array.ndim != 1:
            raise AnimationError(f"run {run.label!r}: {name} has shape {array.shape}; allowed: one 1-D array per field")
        if not np.all(np.isfinite(array)):
            raise AnimationError(f"run {run.label!r}: {name} has a non-finite value; allowed: finite floats")
        out[name] = array
    if run.phase is not None:
        out["phase"] = np.asarray(run.phase, dtype=str)
        if out["phase"].ndim != 1:
            raise AnimationError(f"run {run.label!r}: phase has shape {out['phase'].shape}; allowed: one 1-D array")
    lengths = {name: len(a) for name, a in out.items()}
    if len(set(lengths.values())) != 1:
        raise AnimationError(f"run {run.label!r}: arrays of different lengths {lengths}; allowed: one length")
    t = out["t"]
    if np.any(np.diff(t) < 0):
        raise AnimationError(f"run {run.label!r}: times decrease at t = {t[np.argmax(np.diff(t) < 0)]!r}; "
                             "allowed: a non-decreasing grid")
    keep = np.append(np.diff(t) > 0, True)  # of repeated times keep the last (a terminal event's state)
    out = {name: a[keep] for name, a in out.items()}
    if len(out["t"]) < 2:
        raise AnimationError(f"run {run.label!r}: {len(out['t'])} distinct time(s); allowed: at least 2")
    return out

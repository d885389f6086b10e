"""What a run's samples say about its orbit: the sense in which the centre of mass circles, and of the spin.

The paper's circular motions (the disk's, Eqs. 19-21; the ring's, Eqs. 51-58, Fig. 8) turn the
line of nodes e1 and the centre of mass C together at the rate phidot about the vertical, so on
them the sense of the orbit is the sign of phidot.  Off them -- a ring whose dissipation drives
theta down, the "terminal retrograde turn" the paper cites (Borisov, Kilin and Karavaev,
arXiv:1611.02957) -- C draws nutation loops on a slower drift, and the sense of the orbit is the
sense of that slow path, read window by window (:func:`orbit_windows`) by two measures of
:mod:`verify.circling` that share nothing but the run; the spin is omega . Z = phidot + psidot
cos(theta), Z the vertical, from omega of Eq. 16 (omega . Z = omega_2 sin(theta) + omega_3 cos(theta)).

These are the sweeps' readings of the orbit: :func:`verify.sweep.engine.run_chunk` calls
:func:`senses` on each run's samples when its spec records one of
:data:`verify.sweep.spec.SENSE_KEYS` (``run_chunk(..., senses=senses)``; ``python -m verify sweep``
and :mod:`verify.studies.retrograde` pass it).  The sweep engine does not import this module: the
science sits above the machinery that runs it.
"""
from __future__ import annotations

import math

import numpy as np

from models.catalogue import STATE_NAMES

from ..circling import circling, theta_maxima
from ..sweep.spec import SENSE_KEYS

WINDOWS = 20  # a run without nutation is read over 20 equal windows
NUTATIONS_PER_WINDOW = 12  # otherwise over windows of 12 nutations (see orbit_windows)
NUTATION_FLOOR = 1e-9  # rad: a theta spread below this is no nutation
#: Columns of a run's samples ``y`` (samples x states, the states in STATE_NAMES order).
TH, PH, X, Y = (STATE_NAMES.index(n) for n in ("theta", "phi", "x", "y"))


def orbit_windows(t, theta) -> list:
    """Index slices of the windows a run's senses are read over.

    A run that nutates is cut half-way between successive maxima of theta into windows of
    :data:`NUTATIONS_PER_WINDOW` nutations (the remainder spread evenly, so each window holds
    N to 2N - 1), less than a nutation and a half at either end left out.  Counting nutations
    rather than seconds keeps the filters of :mod:`verify.circling` the same in every window
    although the nutation period of a decaying ring shrinks fourfold (0.2-0.3 s at the start,
    0.05 s at theta = 0.1) and the period within one window stays nearly constant (the
    running mean uses one period per window).  A run whose theta does not move (no nutation)
    is cut into :data:`WINDOWS` equal windows instead.  Fewer than two windows: [].
    """
    t, theta = np.asarray(t, float), np.asarray(theta, float)
    if len(t) < 2:
        return []
    if np.ptp(theta) < NUTATION_FLOOR:
        if len(t) < 2 * WINDOWS:
            return []
        edges = np.linspace(0, len(t) - 1, WINDOWS + 1).round().astype(int)
        return [slice(a, b + 1) for a, b in zip(edges[:-1], edges[1:])]
    marks = theta_maxima(t, theta)
    cuts = 0.5 * (marks[:-1] + marks[1:])  # len(marks) - 1 cuts hold len(marks) - 2 whole nutations
    k = (len(cuts) - 1) // NUTATIONS_PER_WINDOW
    if k < 2:
        return []
    at = np.searchsorted(t, cuts[np.linspace(0, len(cuts) - 1, k + 1).round().astype(int)])
    return [slice(a, b + 1) for a, b in zip(at[:-1], at[1:])]


def senses(t, y, omega_z) -> dict:
    """The sense of the orbit (the slow path of the centre of mass) and of the spin, window by window.

    ``orbit`` is the sense in which the CM's *slow path* circles -- the path left when the
    nutation loops are filtered out -- read by :func:`verify.circling.circling` in each window of
    :func:`orbit_windows` by two measures that share nothing but the run (the CM once per
    nutation, its winding; the CM averaged over a nutation, its swept area).  A window's orbit
    sense is +1/-1 only where both measures decide (half a turn or more) with the same sign, and
    0 (undecided) otherwise: neither measure is preferred.  The nutation loops themselves -- and
    with them the turning of the line of nodes e1 -- do not enter.

    ``spin`` is the sign of the mean of omega . Z = phidot + psidot cos(theta) over a window.
    A decided window is prograde when its orbit goes with its own spin, retrograde when against.

    * ``orbit_start``/``orbit_end``: orbit sense in the first/last window that decides (NaN: none
      does); ``t_orbit_start``/``t_orbit_end`` where those windows begin/end; ``orbit_last`` the
      sense in the run's last window (0: the end state is not read);
    * ``orbit_reversal`` = 1 when a later decided window has the sense opposite to the first one
      (``t_orbit_reversal``: the start of the first such window), 0 when none has, NaN when fewer
      than two windows decide;
    * ``spin_start``/``spin_end``: the spin in the run's first/last window;
    * ``retrograde_turn``: the run ends against its spin after starting with it.  1 when the run's
      last window decides and is retrograde and the first window that decides is prograde; 0 when
      the last window decides and is prograde, or it and the run's first window are both
      retrograde; NaN otherwise (the end state, or the start before it, is not read);
    * ``retrograde_by_last_read``: the same with the last window that decides standing for the
      end (what the slow path shows as far as it can be read; NaN when fewer than two decide);
      ``retrograde_end``: that window is retrograde; ``t_retrograde``: start of the first
      retrograde decided window after a prograde first one;
    * ``windows``, ``windows_undecided``; ``strobe_last``/``mean_last``: the two measures (turns)
      in the run's last window, to show how they disagree when they do; ``points_per_nutation``:
      the output grid's resolution of the shortest nutation period in the run;
    * ``node_turn_*``: the former reading, the sign of phi(end) - phi(start) in the first/last window
      (it counts the turning of e1, i.e. the loops), and ``node_retrograde_turn`` the retrograde
      turn by that reading -- kept for comparison, not used for the verdict;
    * ``path_*``: the sign of the area the raw sampled path sweeps (loops included);
      ``roll_*``: the sign of the CM's displacement along e1, the direction it rolls (when it
      reverses so does the centripetal friction force).

    Every value is NaN for a run with fewer than two windows (too few nutations to read).
    """
    wins = orbit_windows(t, y[:, TH])
    if not wins:
        return dict.fromkeys(SENSE_KEYS, math.nan)
    t = np.asarray(t, float)
    phi, x, yy, th = y[:, PH], y[:, X], y[:, Y], y[:, TH]
    orbit, spin, node, path, roll, reads = [], [], [], [], [], []
    for s in wins:
        c = circling(t[s], x[s], yy[s], th[s], nutation_floor=NUTATION_FLOOR)
        reads.append(c)
        orbit.append(c.sign)
        spin.append(int(np.sign(np.mean(omega_z[s]))))
        p = phi[s]
        node.append(int(np.sign(p[-1] - p[0])))
        xs, ys = x[s] - x[s].mean(), yy[s] - yy[s].mean()
        path.append(int(np.sign(np.sum(xs[:-1] * np.diff(ys) - ys[:-1] * np.diff(xs)))))
        roll.append(int(np.sign(np.sum(np.diff(x[s]) * np.cos(p[:-1]) + np.diff(yy[s]) * np.sin(p[:-1])))))
    start = [float(t[s][0]) for s in wins]
    decided = [i for i, o in enumerate(orbit) if o != 0]
    pro = {i: spin[i] != 0 and orbit[i] == spin[i] for i in decided}
    retro = {i: spin[i] != 0 and orbit[i] == -spin[i] for i in decided}
    nan = math.nan
    out = {"windows": float(len(wins)), "windows_undecided": float(len(wins) - len(decided)),
           "orbit_last": float(orbit[-1]), "spin_start": float(spin[0]), "spin_end": float(spin[-1]),
           "strobe_last": reads[-1].strobe.turns, "mean_last": reads[-1].mean.turns,
           "points_per_nutation": _points_per_nutation(t, reads),
           "orbit_start": nan, "orbit_end": nan, "t_orbit_start": nan, "t_orbit_end": nan,
           "orbit_reversal": nan, "t_orbit_reversal": nan, "retrograde_end": nan, "retrograde_turn": nan,
           "retrograde_by_last_read": nan, "t_retrograde": nan}
    if decided:
        first, last = decided[0], decided[-1]
        flip = next((i for i in decided if orbit[i] == -orbit[first]), None)
        turned = next((i for i in decided if retro[i]), None) if pro[first] else None
        out.update(orbit_start=float(orbit[first]), orbit_end=float(orbit[last]), t_orbit_start=start[first],
                   t_orbit_end=float(t[wins[last]][-1]), retrograde_end=float(retro[last]),
                   t_retrograde=start[turned] if turned is not None else nan)
        if len(decided) >= 2:
            out.update(orbit_reversal=float(flip is not None), t_orbit_reversal=start[flip] if flip is not None else nan,
                       retrograde_by_last_read=float(pro[first] and retro[last]))
        end = len(wins) - 1
        if end in decided and len(decided) >= 2:
            if pro[end]:
                out["retrograde_turn"] = 0.0
            elif retro[end] and pro[first]:
                out["retrograde_turn"] = 1.0
            elif retro[end] and first == 0 and retro[0]:
                out["retrograde_turn"] = 0.0  # retrograde from its first window on: no turn
    node_retro = node[0] == spin[0] and node[-1] == -spin[-1] and spin[-1] != 0
    flip_roll = next((i for i, r in enumerate(roll) if r != roll[0]), None)
    out.update(node_turn_start=float(node[0]), node_turn_end=float(node[-1]), node_retrograde_turn=float(node_retro),
               path_start=float(path[0]), path_end=float(path[-1]), path_reversal=float(path[-1] != path[0]),
               roll_start=float(roll[0]), roll_end=float(roll[-1]), roll_reversal=float(roll[-1] != roll[0]),
               t_roll_reversal=start[flip_roll] if flip_roll is not None else nan)
    return out


def _points_per_nutation(t, reads) -> float:
    """Output points in the shortest nutation period of the run's windows (NaN: no nutation)."""
    periods = [c.nutation_period for c in reads if math.isfinite(c.nutation_period)]
    return min(periods) / float(t[1] - t[0]) if periods else math.nan

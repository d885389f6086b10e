"""The figure runs and their reading: one run of a caption's start, the verdict from its readings."""
from __future__ import annotations

import dataclasses
import math
from functools import lru_cache

import numpy as np

from models import get_model
from models.common import PAPER_G
from models.ring import parameter_set
from verify.circling import circling
from verify.engine.single import solve

from ..base import Evaluation, RunData, decide, undecided

G = float(PAPER_G)
SQRT_G = math.sqrt(G)
K = 0.25
DENSE = 20001  # output points of a run read by the measures: >= 40 a nutation on every run here
# the paper's printed ring (text before Fig. 9): the figure runs use the paper's own numbers
RING_PRINTED = dict(parameter_set("printed"))


@lru_cache(maxsize=None)
def _without_chaplygin(name: str):
    """The model without its Chaplygin integrals: the figure runs read the path on a dense grid,
    and the figure checks read no Chaplygin integral (they were left out when each point cost ~2 ms
    of mpmath 2F1; the transport in theta is now cheap, but adding them would only add work); energy
    is still tracked at every point."""
    model = get_model(name)
    return dataclasses.replace(model, chaplygin=None) if model.chaplygin is not None else model


def run(model, state, t_end, label, n_eval=DENSE, **kw):
    """(Trajectory, RunData) of ``model`` from ``state`` (floats or decimal strings) for ``t_end`` s."""
    sol = solve(_without_chaplygin(model), str(t_end),
                {k: (v if isinstance(v, str) else repr(float(v))) for k, v in state.items()}, n_eval=n_eval, **kw)
    f = lambda a: tuple(float(v) for v in a)
    th, ph, ps, phd, psd = (np.array(f(sol[n])) for n in ("theta", "phi", "psi", "phidot", "psidot"))
    om3 = phd * np.cos(th) + psd
    data = RunData(label, f(sol.t), tuple(th), tuple(ph), tuple(om3), f(sol["x"]), f(sol["y"]),
                   sol.invariants["energy"].max_rel_drift, sol.outcome)
    return sol, data


def _arrays(d: RunData):
    return tuple(np.array(v) for v in (d.t, d.theta, d.x, d.y, d.phi, d.omega3))


def _completed(d: RunData) -> bool:
    return d.outcome == "ok"


def _bisect(leaves_at, lo: float, hi: float, halvings: int = 14) -> tuple:
    """Bracket [lo, hi] of the smallest value at which ``leaves_at`` turns True (monotone assumed)."""
    for _ in range(halvings):
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if leaves_at(mid) else (mid, hi)
    return lo, hi


def _leaves_quietly(model, state, t_end, params=None) -> bool:
    sol = solve(model, str(t_end), {k: repr(float(v)) for k, v in state.items()}, params=params, n_eval=2)
    return sol.outcome != "ok"


def _verdict(readings, want, expected, observed, detail, correction=None, figures=()) -> Evaluation:
    """Confirmed when every reading agrees with what the caption says, erratum when one reading
    (with its two measures agreeing) contradicts it, not checkable when a reading's measures disagree."""
    measures = tuple(m for r in readings for m in r.measures())
    if any(r.holds is None for r in readings):
        return undecided(expected, observed, detail + " The measures disagree: " +
                         "; ".join(r.text() for r in readings if r.holds is None), figures, measures)
    ok = all(r.holds == w for r, w in zip(readings, want))
    return decide(ok, "; ".join(r.text() for r in readings), observed, detail, correction, figures, measures)


def circle_centre(x, y):
    """Least-squares centre of points on a circle (Kasa's algebraic fit)."""
    A = np.column_stack([x, y, np.ones_like(x)])
    sol = np.linalg.lstsq(A, x**2 + y**2, rcond=None)[0]
    return sol[0] / 2, sol[1] / 2


def _sense(d: RunData):
    t, th, x, y, _, _ = _arrays(d)
    return circling(t, x, y, th, whole_path=True)

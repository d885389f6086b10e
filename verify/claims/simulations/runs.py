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
from verify.figure_starts import start

from verify.studies.finite_offset import finite_offset_verdict

from ..base import ERRATUM, QUALIFIED, Evaluation, RunData, decide, qualify, undecided

G = float(PAPER_G)
SQRT_G = math.sqrt(G)
K = 0.25
DENSE = 20001  # output points of a run read by the measures: >= 40 a nutation on every run here
# the paper's printed ring (text before Fig. 9): the figure runs use the paper's own numbers
RING_PRINTED = dict(parameter_set("printed"))
#: How every text names the ring's parameter set (the annular one: verify.claims.ring.RING).
PRINTED_SET = "the printed ring set (I1 = 0.4993, I3 = 0.8727, h = 0.4344, text before Fig. 9)"


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


def run_start(name: str, label: str, **kw):
    """(Trajectory, RunData) of the figure start ``name`` (:mod:`verify.figure_starts`): the one
    source of each panel's start, so the report's run is the run a reader gets by that name.
    The RunData carries the start's panel side."""
    s = start(name)
    params = dict(s.params) or None
    kw.setdefault("n_eval", s.n_eval)
    if not s.events:
        kw.setdefault("events", False)
    sol, data = run(s.model, dict(s.state), s.t_end, label, params=params, **kw)
    return sol, dataclasses.replace(data, side=s.side)


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


def all_hold(readings) -> "bool | None":
    """True when every reading holds, False when none does, None when one is undecided or they differ."""
    held = [r.holds for r in readings]
    if any(h is None for h in held) or len(set(held)) != 1:
        return None
    return held[0]


def finite_offset(readings, linearly_stable: bool, start_offset: float, bracket: tuple, expected: str, detail: str,
                  qualification: str, correction: str, figures=()):
    """The rule of :mod:`verify.studies.finite_offset` as an evaluation, or None when the rate is linearly
    unstable (not this situation: the caller decides by the run).  ``readings`` are those of the run
    from the caption's start (all of them must hold for 'leaves'); ``qualification`` is given when it
    leaves, ``correction`` when it stays."""
    verdict = finite_offset_verdict(linearly_stable, all_hold(readings), start_offset, bracket)
    if verdict is None:
        return None
    measures = tuple(m for r in readings for m in r.measures())
    said = "; ".join(r.text() for r in readings)
    if verdict == QUALIFIED:
        return qualify(said, expected, detail, qualification, figures=figures, measures=measures)
    if verdict == ERRATUM:
        return decide(False, said, expected, detail, correction=correction, figures=figures, measures=measures)
    lo, hi = bracket
    return undecided(said, expected, detail + f" The run from the start (offset {start_offset:.3g}) and the bisection "
                     f"(stays at {lo:.3g}, leaves at {hi:.3g}) disagree, or the run's measures do", figures, measures)

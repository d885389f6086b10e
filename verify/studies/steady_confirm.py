"""The thresholds of :mod:`verify.studies.steady_bodies` against the full nonlinear equations.

A threshold says that a small tilt off the steady motion stays small on one side of the critical rate and
grows on the other.  :func:`confirm` runs the body's model (:func:`verify.engine.single.solve`, double
precision, heyoka's Taylor method at machine tolerance) from the steady motion at the rate (1 - margin)
and (1 + margin) times the threshold, with theta perturbed alone by ``tilt`` (the rates kept: the body
moves onto a neighbouring member of the family, as in :func:`verify.studies.thresholds.grows`), and reads
"grows" as it does: theta leaves its steady value by more than GROWTH = 1000 times the tilt within t_end,
or the run ends at the edge of the domain.  Sleeping at theta0 = 0 starts at theta = tilt, at theta0 = pi
at pi - tilt, with phidot = 0 and psidot the rate (omega3 up to its sign).

Why these numbers: the linear solution oscillates about a neighbouring member of the family displaced by
d* = -(c e + d f) tilt / w2 (:func:`verify.studies.thresholds.linear_deviation`), so on the stable side the
deviation stays within a few times the tilt unless w2 is tiny, and 10 % from a threshold w2 is about a
fifth of its scale; on the unstable side it grows like exp(sqrt(-w2) t), and 1000 is 7 e-foldings, which
take well under a second at the rates here (sqrt(-w2) of order 10 s^-1).  A tilt of 1e-4 keeps the
nonlinear terms (order tilt^2) far below the linear ones.

The negative control (tests) hands :func:`confirm` a wrong threshold: both runs then land on one side of
the true one, and the confirmation says they disagree.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Optional

import mpmath
import sympy as sp

from models.steady_bodies import DPS, domain, parameter_values, steady_state, turned_over
from models.symbols import phidot, psidot, theta
from verify.engine.single import solve

from .steady_bodies import Record, _model, sleeping_form, stability_form
from .thresholds import GROWTH, OMEGA3


@dataclass(frozen=True)
class Run:
    """One nonlinear run from a perturbed steady motion."""

    rate: str
    outcome: str  # "ok" or the event that ended it
    deviation: float  # max |theta - theta_steady| on the grid
    grows: bool
    linear: Optional[float]  # the linearisation's bound on that deviation (None where it grows)


@dataclass(frozen=True)
class Confirmation:
    """The runs below and above a threshold and whether they say what the record says."""

    record: Record
    tilt: str
    t_end: str
    below: Run
    above: Run

    @property
    def agrees(self) -> bool:
        """The side the record calls stable stays within GROWTH x tilt, the other grows."""
        if self.record.stable == "above":
            return self.below.grows and not self.above.grows
        if self.record.stable == "below":
            return self.above.grows and not self.below.grows
        raise ValueError(f"record without a threshold (stable: {self.record.stable})")


def start(model, record: Record, rate, tilt, params: Optional[dict] = None) -> tuple:
    """(initial state as decimal strings, theta of the unperturbed steady motion) of a run at ``rate``."""
    subs = parameter_values(model, params)
    values = {p.name: subs[p.symbol] for p in model.parameters}
    with mpmath.workdps(DPS):
        tilt = mpmath.mpf(tilt)
        if record.motion == "sleeping":
            th0 = mpmath.mpf(record.theta0)
            state = {"theta": th0, "phidot": mpmath.mpf(0), "psidot": mpmath.mpf(rate)}
        else:
            on_branch = record.motion == "diameter-spin" and record.theta0_exact is None
            s = steady_state(model, record.motion, rate, record.theta0, values, branch=on_branch)
            state = {k: mpmath.mpf(v) for k, v in s.items()}
            th0 = state["theta"]
        lo, hi = domain(model, subs)
        state["theta"] = th0 + tilt if th0 + tilt < hi else th0 - tilt
        return {k: mpmath.nstr(v, 36) for k, v in state.items()}, th0


def run(model, record: Record, rate, tilt="1e-4", params: Optional[dict] = None, t_end="10") -> Run:
    """The run at ``rate`` from the steady motion with theta perturbed by ``tilt`` (module docstring)."""
    model = _model(model)
    state, th0 = start(model, record, rate, tilt, params)
    sol = solve(model, t_end, state, params, n_eval=401)
    dev = max(abs(float(v) - float(th0)) for v in sol["theta"])
    bound = linear_bound(model, record, rate, tilt, params)
    rate = mpmath.nstr(mpmath.mpf(rate), 15)
    return Run(rate, sol.outcome, dev, sol.outcome != "ok" or dev > GROWTH * float(tilt), bound)


def linear_bound(model, record: Record, rate, tilt="1e-4", params: Optional[dict] = None) -> Optional[float]:
    """max |theta - theta_steady| over all times by the linearised equations, from the start of :func:`run`.

    With the rates kept, d theta'' = -w2 d theta - s tilt, so d theta = d* + (tilt - d*) cos(sqrt(w2) t),
    d* = -s tilt / w2, at most |d*| + |tilt - d*| (:func:`verify.studies.thresholds.linear_deviation`).
    Sleeping: u'' = A u + i B u' with u(0) = tilt, u'(0) = 0 is c1 exp(i s1 t) + c2 exp(i s2 t), s1,2 the
    roots of s^2 - B s + A, at most tilt (|s1| + |s2|) / |s1 - s2|.  None where the motion is unstable.
    """
    model = _model(model)
    subs = parameter_values(model, params)
    with mpmath.workdps(DPS):
        tilt = mpmath.mpf(tilt)
        if record.motion == "sleeping":
            body = model if record.theta0_exact == "0" else turned_over(model)
            A, B = (mpmath.mpf(sp.N(x.subs(subs).subs(OMEGA3, sp.Float(mpmath.nstr(mpmath.mpf(rate), 40), 40)), 40))
                    for x in sleeping_form(body))
            disc = B**2 - 4 * A
            if disc <= 0:
                return None
            s1, s2 = (B + mpmath.sqrt(disc)) / 2, (B - mpmath.sqrt(disc)) / 2
            return float(tilt * (abs(s1) + abs(s2)) / abs(s1 - s2))
        state, _ = start(model, record, rate, 0, params)
        form = stability_form(model)
        x = [mpmath.mpf(state[k]) for k in ("theta", "phidot", "psidot")]
        w2, s = (sp.lambdify((theta, phidot, psidot), e.subs(subs), "mpmath")(*x) for e in (form.w2, form.s))
        if w2 <= 0:
            return None
        shift = -s * tilt / w2
        return float(abs(shift) + abs(tilt - shift))


def confirm(model, record: Record, params: Optional[dict] = None, margin="0.1", tilt="1e-4", t_end="10",
            value: Optional[str] = None) -> Confirmation:
    """Runs at (1 -+ margin) x the threshold (``value`` in place of the record's: the negative control)."""
    if record.value is None and value is None:
        raise ValueError(f"{record.body} {record.motion}: no threshold to confirm (stable: {record.stable})")
    model = _model(model)
    tested = record if value is None else replace(record, value=value)
    with mpmath.workdps(DPS):
        v, m = mpmath.mpf(tested.value), mpmath.mpf(margin)
        rates = [v * (1 - m), v * (1 + m)]
    below, above = (run(model, tested, r, tilt, params, t_end) for r in rates)
    return Confirmation(tested, str(tilt), str(t_end), below, above)


def confirm_every_rate(model, record: Record, rates=("1", "30", "300"), params: Optional[dict] = None, tilt="1e-4",
                       t_end="10") -> tuple:
    """Runs at each of ``rates`` for a record without a threshold: under "every rate" none may grow, under
    "no rate" each must (the caller asserts it; returns the :class:`Run` of each rate)."""
    if record.value is not None or record.theta0 == "-":
        raise ValueError(f"{record.body} {record.motion}: confirm_every_rate is for a motion at a fixed theta0 "
                         f"without a threshold (this one: {record.value or record.branch})")
    return tuple(run(model, record, r, tilt, params, t_end) for r in rates)


__all__ = ["Confirmation", "Run", "confirm", "confirm_every_rate", "run", "start"]

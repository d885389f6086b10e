"""Rolling and sliding with Coulomb friction: the report's examples (``disk+coulomb``).

Three runs of :func:`verify.engine.hybrid.solve`, each in double and quad:

* **a skid**: the wobbling disk launched with a centre-of-mass velocity that is not the no-slip one
  (the contact slips at t = 0 with s > 0), mu = 1: it slides, sticks and rolls on;
* **a steady circle below its friction**: the stationary circular rolling of ``tests/test_coulomb.py``
  (Le Saux, Leine & Glocker's g/r = 196.2 s^-2, 5 deg; our reading of their rho) with mu = 0.9 of what
  the circle needs: the contact cannot hold at t = 0, the slip starts from s = 0, then sticks;
* **a perturbed circle**: that circle tilted by 0.01 rad more, whose mu_req oscillates, with mu halfway
  between its extremes: it rolls until mu_req reaches mu, slides from there (the onset's power series,
  :mod:`verify.engine.slip_onset`), sticks and rolls on.

For each: the phases and how they end, the energy balance E + W in eps of E's term scale, and how far
the switch times of the two precisions lie apart.
"""
from __future__ import annotations

import sympy as sp

from models import get_model
from models.symbols import phidot, psidot, theta, thetadot

from ..engine import hybrid
from ..engine.single import solve

PRECISIONS = ("double", "quad")
SKID = {"state": {"theta": "1.2", "phidot": "3", "psidot": "25"}, "velocity": ("3", "1"), "friction": "1",
        "t_end": "0.5", "params": None}


def steady_circle():
    """(state, params) of the disk's stationary circle at g = 196.2 s^-2, theta = 5 deg, psidot = phidot (1/10 - cos theta).

    thetaddot = 0 at thetadot = 0 fixes phidot (the faster root); the state is written to 45 digits.
    """
    m = get_model("disk")
    k, g, tilt, rho = sp.Rational(1, 4), sp.Rational(1962, 10), 5 * sp.pi / 180, sp.Rational(1, 10)
    p = sp.Symbol("p", positive=True)
    acc = m.accelerations[0].subs({thetadot: 0, m.parameter("k").symbol: k, m.parameter("g").symbol: g})
    rates = sp.solve(acc.subs(psidot, p * (rho - sp.cos(theta))).subs({phidot: p, theta: tilt}), p)
    rate = max(rates, key=lambda v: float(v))
    state = {"theta": str(sp.N(tilt, 45)), "phidot": str(sp.N(rate, 45)), "psidot": str(sp.N(rate * (rho - sp.cos(tilt)), 45))}
    return state, {"k": "0.25", "g": "196.2"}


def _circle_case():
    state, params = steady_circle()
    need = solve("disk", "0.2", state, params, precision="quad", n_eval=2).friction_required[0]
    mu = sp.N(sp.Rational(9, 10) * sp.Float(str(need), 40), 30)
    return {"state": state, "velocity": None, "friction": str(mu), "t_end": "0.2", "params": params,
            "need": f"{float(need):.6g}"}


def perturbed_circle():
    """(state, params, mu) of the steady circle tilted by 0.01 rad, mu halfway between the extremes of its
    mu_req over 0.2 s (the rolling run without the slip event, double, 2001 outputs)."""
    state, params = steady_circle()
    state = dict(state, theta=str(float(state["theta"]) + 0.01))
    need = [float(v) for v in solve("disk", "0.2", state, params, n_eval=2001).friction_required]
    return state, params, str(0.5 * (min(need) + max(need)))


def _perturbed_case():
    state, params, mu = perturbed_circle()
    return {"state": state, "velocity": None, "friction": mu, "t_end": "0.2", "params": params}


def examples() -> list:
    """One record per example: the phases per precision, E + W, and the switch times' agreement."""
    out = []
    for name, case in (("skid", SKID), ("circle below its friction", _circle_case()),
                       ("perturbed circle, mu between its extremes", _perturbed_case())):
        runs = {p: hybrid.solve("disk+coulomb", case["t_end"], case["state"], case["params"], friction=case["friction"],
                                velocity=case["velocity"], precision=p, n_eval=11) for p in PRECISIONS}
        double, quad = runs["double"], runs["quad"]
        switch_gap = [abs(float(a - quad.precision.number(str(b)))) / (float(b) * double.precision.eps)
                      for a, b in zip(quad.switch_times, double.switch_times)]
        out.append({
            "example": name, "friction": case["friction"][:8], "t_end": case["t_end"], "need": case.get("need"),
            "phases": [{"kind": ph.kind, "t_start": f"{float(ph.t_start):.12g}", "t_end": f"{float(ph.t_end):.12g}",
                        "ended": ph.ended} for ph in double.phases],
            "same_phases": [ph.kind for ph in double.phases] == [ph.kind for ph in quad.phases],
            "energy_plus_work_in_eps": {p: f"{r.energy_plus_work_drift_in_eps:.2g}" for p, r in runs.items()},
            "switch_gap_in_double_eps": f"{max(switch_gap):.3g}" if switch_gap else None,
        })
    return out

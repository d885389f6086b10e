"""The shipped bodies of revolution (``models/bodies/*.toml``) as report rows: what each is, the paper's bodies
reproduced from their profiles, and a run of each keeping its invariants.

For the paper's bodies the derived accelerations from the profile are compared with the built-in model's as
sympy identities (the disk's I1 = k, I3 = 2 k; the ring's half_thickness = h), and the same start is run by both:
the same bits where the expressions are the same (the hurricane balls), else the largest difference relative to
1 + |y| (other roundings of the same equations).  Every body is then run for 1 s in double from its default
start (the middle of its domain, phidot = 1, psidot = 10) with each invariant's drift in units of eps times its
term scale.
"""
from __future__ import annotations

import numpy as np
import sympy as sp

from models import get_model
from models.bodies import default_start, load, model_of, shipped

from ..engine.single import solve

#: The paper's bodies among the shipped files: the built-in model and how its parameters map to the file's.
PAPER_BODIES = {"disk": "disk", "hoop": "disk", "ring": "ring", "hurricane": "hurricane"}
#: Starts of the identity runs, per built-in model (rates in 1/s), and their parameters.
_IDENTITY_RUNS = {"disk": ({"theta": "1.2", "phidot": "1", "psidot": "10"}, {"k": "1/4"}),
                  "ring": ({"theta": "1.0", "phidot": "-3", "psidot": "20"}, {}),
                  "hurricane": ({"theta": "1.21", "phidot": "70", "psidot": "70"}, {})}


def rows() -> list:
    """One JSON-ready row per shipped body (:func:`models.bodies.shipped`)."""
    out = []
    for name in shipped():
        body = load(name)
        model = model_of(body)
        row = {"name": name, "description": body.description, "kind": body.kind,
               "profile": {k: str(v) for k, v in body.profile}, "I1": str(body.I1), "I3": str(body.I3),
               "domain": [str(model.domain.theta_min), str(model.domain.theta_max), model.domain.below,
                          model.domain.above],
               "parameters": [p.name for p in model.parameters],
               "invariants": [i.name for i in model.invariants] + (["chaplygin_1", "chaplygin_2"] if model.chaplygin
                                                                  else []),
               "run": default_run(model, body)}
        if name in PAPER_BODIES and name != "hoop":
            row["paper"] = paper_identity(name, model)
        out.append(row)
    return out


def default_run(model, body) -> dict:
    """A 1-s double run from the body's default start (:func:`models.bodies.default_start`): outcome, steps, each
    invariant's drift / (eps x term scale)."""
    start, _ = default_start(body)
    sol = solve(model, "1", start, n_eval=33)
    return {"start": {k: str(v) for k, v in start.items()}, "outcome": sol.outcome,
            "t_last": float(sol.t[-1]), "steps": int(sol.steps),
            "drift_in_eps": {n: round(float(tr.max_drift_vs_terms) / 2.0 ** -52, 2) for n, tr in sol.invariants.items()}}


def paper_identity(name: str, model) -> dict:
    """The body file's equations against the built-in model's: identity and a run of each."""
    builtin = get_model(PAPER_BODIES[name])
    subs = {}
    if PAPER_BODIES[name] == "disk":
        k = builtin.parameter("k").symbol
        subs = {model.parameter("I1").symbol: k, model.parameter("I3").symbol: 2 * k}
    elif PAPER_BODIES[name] == "ring":
        subs = {model.parameter("half_thickness").symbol: builtin.parameter("h").symbol}
    same_terms = model.accelerations == builtin.accelerations
    identity = same_terms or all(sp.simplify(a.subs(subs) - b) == 0
                                 for a, b in zip(model.accelerations, builtin.accelerations))
    start, params = _IDENTITY_RUNS[PAPER_BODIES[name]]
    a = solve(builtin, "1", start, {k: sp.Rational(v) for k, v in params.items()}, n_eval=9)
    b = solve(model, "1", start, n_eval=9)
    diff = float(np.max(np.abs(a.y - b.y) / (1 + np.abs(a.y))))
    return {"model": PAPER_BODIES[name], "identity": bool(identity), "same_expressions": bool(same_terms),
            "same_bits": bool(np.array_equal(a.y, b.y)), "max_rel_difference": float(f"{diff:.3e}"),
            "start": start}


__all__ = ["PAPER_BODIES", "default_run", "paper_identity", "rows"]

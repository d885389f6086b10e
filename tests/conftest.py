"""Shared helpers for the tests."""
from __future__ import annotations

import os
import random

import mpmath
import pytest
import sympy as sp

os.environ.setdefault("MPLBACKEND", "Agg")

from models.symbols import STATE  # noqa: E402


def random_states(n: int, seed: int, theta_range=(0.2, 1.4)):
    """Reproducible random states (theta, rates) as exact decimal strings."""
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        out.append({
            "theta": f"{rng.uniform(*theta_range):.15f}",
            "phi": f"{rng.uniform(-3, 3):.15f}",
            "psi": f"{rng.uniform(-3, 3):.15f}",
            "thetadot": f"{rng.uniform(-5, 5):.15f}",
            "phidot": f"{rng.uniform(-20, 20):.15f}",
            "psidot": f"{rng.uniform(-20, 20):.15f}",
        })
    return out


def mp_evaluator(exprs, model):
    """exprs(state dict of strings, params) evaluated by mpmath at the current precision."""
    syms = list(STATE) + [p.symbol for p in model.parameters]
    f = sp.lambdify(syms, list(exprs), modules="mpmath")

    def evaluate(state: dict, params: dict | None = None):
        params = params or {}
        values = [mpmath.mpf(state.get(str(s), 0)) for s in STATE]
        values += [mpmath.mpf(sp.N(params.get(p.name, p.default), 60)) for p in model.parameters]
        return [mpmath.mpf(v) for v in f(*values)]

    return evaluate


@pytest.fixture
def mp50():
    with mpmath.workdps(50):
        yield

"""Compute a reference case: two MPFR runs, their agreeing digits, invariants, conditioning.

``python -m verify reference --make`` runs every case of :mod:`verify.reference.cases` at
``LOW`` and ``HIGH`` bits (processes in parallel, one case-precision per task), keeps the
agreeing digits of each value of the state and of every invariant on the output grid
(:mod:`verify.reference.agreement`), measures the conditioning of the flow with the
variational equations (:func:`verify.engine.conditioning.sensitivities`), and writes one JSON file
per case with :mod:`verify.reference.store`.
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from functools import lru_cache

import mpmath
import sympy as sp

from models import coulomb, get_model
from models.symbols import STATE, STATE_NAMES

from ..engine.conditioning import sensitivities
from ..engine.single import solve
from ..precision import parse_precision
from .cases import ReferenceCase, case
from .agreement import agree
from .coulomb_runs import conditioning as hybrid_conditioning, run_case as run_hybrid

LOW, HIGH = "mp:128", "mp:256"
FINGERPRINT_STATES = (
    {"theta": "0.3", "phi": "0.4", "psi": "-1.1", "thetadot": "0.3", "phidot": "1.7", "psidot": "-2.9"},
    {"theta": "0.7", "phi": "-2.2", "psi": "0.5", "thetadot": "-1.3", "phidot": "-4.1", "psidot": "7.3"},
    {"theta": "1.1", "phi": "1.9", "psi": "3.0", "thetadot": "2.1", "phidot": "0.6", "psidot": "12.5"},
)


@dataclass(frozen=True)
class Run:
    """One case at one precision, as decimal strings carrying every digit of the run."""

    case: str
    precision: str
    steps: int
    outcome: str
    state: dict  # name -> [text per grid time]
    invariants: dict  # name -> [text per grid time]


def run_case(name: str, precision: str) -> Run:
    """Integrate case ``name`` at ``precision`` on its grid (derived equations); raise unless it reaches t_end.

    A Coulomb case is the hybrid's run (:func:`verify.reference.coulomb_runs.run_case`, a ``HybridRun``)."""
    c = case(name)
    if c.hybrid:
        return run_hybrid(c, precision)
    p = parse_precision(precision)
    sol = solve(c.model, c.t_end, c.state, c.exact_params, precision=p, t_eval=c.grid())
    if sol.outcome != "ok" or len(sol.t) != c.intervals + 1:
        raise RuntimeError(f"reference case {name} at {precision}: {sol.outcome} at t = {sol.t[-1]} "
                           f"({len(sol.t)} of {c.intervals + 1} grid points); a reference run must reach t_end")
    state = {n: [p.to_text(v) for v in sol.y[i]] for i, n in enumerate(STATE_NAMES)}
    invariants = {n: [p.to_text(v) for v in tr.values] for n, tr in sol.invariants.items()}
    return Run(name, p.name, sol.steps, sol.outcome, state, invariants)


def agreed_columns(low: dict, high: dict, low_bits: int, high_bits: int) -> dict:
    """name -> {"value", "digits", "abs_error", "double"} columns from two runs' columns."""
    out = {}
    for name in high:
        cells = [agree(_mp(a, high_bits), _mp(b, high_bits), low_bits, high_bits)
                 for a, b in zip(low[name], high[name])]
        out[name] = {"value": [c.text for c in cells], "digits": [c.digits for c in cells],
                     "abs_error": [c.abs_error for c in cells],
                     "double": [float(_mp(c.text, high_bits)) for c in cells]}
    return out


def _mp(text: str, bits: int):
    with mpmath.workprec(bits + 32):
        return mpmath.mpf(text)


def equations_fingerprint(model_name: str) -> str:
    """sha256 of the derived equations evaluated at three fixed states (defaults, 50 digits, printed to 40).

    Accelerations, the velocity of C, every closed-form invariant and the normal force: a
    fingerprint of the equations as functions, independent of how sympy writes them.  A
    reference file whose fingerprint differs from the current model's is stale.  For a body with
    Coulomb friction (``ring+coulomb``) the rolling model's fingerprint is followed by the sliding
    phase's right-hand sides, energy and N/(Mg) at the same states with a slip s = 1/2, direction 1/3,
    work 0 and mu = 1/2.
    """
    return _fingerprint(model_name)


@lru_cache(maxsize=None)
def _fingerprint(model_name: str) -> str:
    if model_name.endswith("+coulomb"):
        return _coulomb_fingerprint(model_name)
    model = get_model(model_name)
    exprs = list(model.accelerations) + list(model.velocity_xy) + [i.expr for i in model.invariants]
    if model.normal_force is not None:
        exprs.append(model.normal_force)
    syms = list(STATE) + [p.symbol for p in model.parameters]
    f = sp.lambdify(syms, exprs, "mpmath")
    h = hashlib.sha256()
    with mpmath.workdps(50):
        pars = [mpmath.mpf(sp.N(p.default, 60)) for p in model.parameters]
        for st in FINGERPRINT_STATES:
            values = [mpmath.mpf(st.get(n, "0")) for n in STATE_NAMES] + pars
            for v in f(*values):
                h.update(mpmath.nstr(mpmath.mpf(v), 40).encode() + b";")
    return h.hexdigest()


def _coulomb_fingerprint(model_name: str) -> str:
    rolling, sliding, params = coulomb.body(model_name)
    exprs = list(sliding.rhs) + [sliding.energy, sliding.normal_force]
    f = sp.lambdify(list(coulomb.SLIDING_STATE) + [p.symbol for p in params], exprs, "mpmath")
    h = hashlib.sha256(_fingerprint(rolling.name).encode())
    with mpmath.workdps(50):
        pars = [mpmath.mpf(sp.N(p.default, 60)) for p in params[:-1]] + [mpmath.mpf(1) / 2]
        for st in FINGERPRINT_STATES:
            values = [mpmath.mpf(st.get(n, "0")) for n in STATE_NAMES] + [mpmath.mpf(1) / 2, mpmath.mpf(1) / 3, 0]
            for v in f(*values, *pars):
                h.update(mpmath.nstr(mpmath.mpf(v), 40).encode() + b";")
    return h.hexdigest()


def conditioning(c: ReferenceCase) -> dict:
    """Row sums of |Phi(t, 0)| and the parameter terms on the grid (t > 0), per component."""
    if c.hybrid:
        return hybrid_conditioning(c)
    times = [float(t) for t in c.grid()[1:]]
    R, P = sensitivities(c.model, times, c.state, c.exact_params)
    fmt = lambda x: float(f"{x:.3e}")  # noqa: E731 -- magnitudes: 4 digits are plenty, and stable
    return {
        "method": "heyoka variational equations of order 1 in the state and the runtime parameters, double "
                  "precision, compact mode; state_row_sum[i] = sum_j |dy_i(t)/dy_j(0)|, "
                  "parameter_term[i] = sum_k |dy_i(t)/dp_k| |p_k|; the first grid time (t = 0) has "
                  "state_row_sum 1 and parameter_term 0",
        "state_row_sum": {n: [1.0] + [fmt(r[i]) for r in R] for i, n in enumerate(STATE_NAMES)},
        "parameter_term": {n: [0.0] + [fmt(r[i]) for r in P] for i, n in enumerate(STATE_NAMES)},
    }


def predicted_digits(steps: int, row_sum: float, scale: float, value: float, bits: int) -> float:
    """Digits a run at ``bits`` should keep of a value: -log10(eps sqrt(N) R Y / |value|)."""
    if value == 0:
        return 0.0
    return -math.log10(math.ldexp(1.0, 1 - bits) * math.sqrt(max(steps, 1)) * max(row_sum, 1.0) * scale / abs(value))

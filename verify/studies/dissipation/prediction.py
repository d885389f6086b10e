"""Predicted numbers for one law, coefficient and start: the family law's closed forms and the drift
with omega3 transported (item 2 of the package docstring)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import mpmath
import numpy as np
import sympy as sp

from models import disk
from models.dissipative import c as C_SYMBOL, dissipative_disk, work_rate
from models.rolling import derive
from models.common import PAPER_G
from models.symbols import g, phidot, psidot, theta, thetadot

from ...engine.auxiliary import sympy_system
from ...engine.single import resolve_parameters, through_grid
from ...precision import parse_precision
from .family import family_law, theta0
from .protocol import LEVELS_PER_DECADE, THETA0, THETA_STOP


@dataclass(frozen=True)
class Prediction:
    """Predicted numbers for one law, coefficient and start.

    ``t0_family``, ``turns_family`` are the family law's closed forms (mpmath);
    ``*_transported`` and the level arrays come from the transported drift (module
    docstring, item 2), integrated by heyoka in double: the time and phi at which the drift
    passes each of ``levels`` (theta0 10^(-j/LEVELS_PER_DECADE), decreasing).
    """

    law: str
    c: mpmath.mpf
    theta0: mpmath.mpf
    params: dict  # k, g, c as mpmath numbers
    p: sp.Rational
    q: sp.Rational
    t0_family: mpmath.mpf
    turns_family: mpmath.mpf
    t0_transported: float
    turns_transported: float
    omega3_final: float  # omega3 as theta -> 0 on the transported drift
    levels: np.ndarray
    t_levels: np.ndarray
    phi_levels: np.ndarray

    def adiabatic_parameter(self, th):
        """a(theta) = |dtheta/dt| / (theta phidot) on the family (drift rate over the rate of turning)."""
        return _adiabatic_function(self.law)(th, *self._pars())

    def family_remainder(self, th):
        """(time, turns) from theta down to theta = 0 along the family law (closed forms)."""
        fl = family_law(self.law)
        with mpmath.workdps(30):
            vals = {theta0: sp.Float(mpmath.nstr(mpmath.mpf(th), 30), 30), disk.k: self.params["k"], g: self.params["g"],
                    C_SYMBOL: self.params["c"]}
            return (mpmath.mpf(sp.N(fl.time_to_singularity.subs(vals), 30)),
                    mpmath.mpf(sp.N(fl.turns_to_singularity.subs(vals), 30)))

    def secant_table(self):
        """(theta_mid, |dtheta/dt|, phidot) between consecutive levels, as :func:`secants` for a run."""
        return _secants(self.t_levels, self.levels, self.phi_levels)

    def _pars(self):
        return tuple(float(self.params[n]) for n in ("k", "g", "c"))


@lru_cache(maxsize=None)
def _adiabatic_function(name: str):
    """a(theta, k, g, c) = |dtheta/dt| / (theta phidot) on the family, for numpy."""
    fl = family_law(name)
    expr = -fl.rate / (theta * sp.sqrt(fl.phidot_squared))
    return sp.lambdify([theta, disk.k, g, C_SYMBOL], sp.simplify(expr), "numpy")


def predict(name: str, c=None, theta_start: str = THETA0, theta_stop: str = THETA_STOP, params=None) -> Prediction:
    """The family law's numbers and the transported drift for a run from ``theta_start``.

    ``c`` defaults to the law's default; ``params`` may set k and g.  Bad values raise
    ``ValueError`` naming them and the allowed range.
    """
    fl = family_law(name)
    pv = _parameter_values(name, c, params)
    if pv["c"] == 0:
        raise ValueError(f"c={c} gives no spin-down to predict; allowed for a prediction: c > 0")
    with mpmath.workdps(30):
        th0 = mpmath.mpf(theta_start)
        vals = {theta0: sp.Float(theta_start, 30), disk.k: pv["k"], g: pv["g"], C_SYMBOL: pv["c"]}
        t0 = mpmath.mpf(sp.N(fl.time_to_singularity.subs(vals), 30))
        turns = mpmath.mpf(sp.N(fl.turns_to_singularity.subs(vals), 30))
    levels = level_grid(float(th0), float(theta_stop))
    t_lv, phi_lv, w3, t0_tr, turns_tr = _transport(name, pv, float(th0), levels)
    return Prediction(name, pv["c"], th0, pv, fl.p, fl.q, t0, turns, t0_tr, turns_tr, w3, levels, t_lv, phi_lv)


def level_grid(theta_start: float, theta_stop: float) -> np.ndarray:
    """theta_start 10^(-j/LEVELS_PER_DECADE), j = 1, 2, ..., the last one replaced by theta_stop."""
    if not 0 < theta_stop < theta_start:
        raise ValueError(f"theta_stop={theta_stop} must lie in (0, theta0 = {theta_start})")
    n = max(1, math.ceil(LEVELS_PER_DECADE * math.log10(theta_start / theta_stop) - 1e-9))
    levels = theta_start * 10.0 ** (-np.arange(1, n + 1) / LEVELS_PER_DECADE)
    levels[-1] = theta_stop
    return levels


def _parameter_values(name: str, c, params) -> dict:
    """k, g, c as 30-digit mpmath numbers, checked by the model (names, ranges, c >= 0)."""
    model = dissipative_disk(name)
    values = dict(params or {})
    if c is not None:
        values["c"] = c
    resolve_parameters(model, values, parse_precision("double"))
    out = {}
    with mpmath.workdps(30):
        for p in model.parameters:
            raw = values.get(p.name, p.default)
            exact = sp.Rational(raw) if isinstance(raw, str) else sp.nsimplify(raw) if isinstance(raw, (int, float)) else raw
            out[p.name] = mpmath.mpf(sp.N(exact, 30))
    return out


@lru_cache(maxsize=None)
def transport_system(name: str):
    """The drift along steady motions with omega3 transported: d(omega3, t, phi)/d(theta).

    At (theta, omega3) the steady phidot is the root of row 1 (thetaddot = 0 at thetadot = 0,
    psidot = omega3 - phidot cos theta) that continues the family's; omega3 follows row 3 of the
    Chaplygin matrix, d(omega3)/d(theta) = A21 omega2 + A22 omega3 (unchanged by the couple:
    tests/test_dissipation.py); dt/dtheta = -(dE/dtheta) / P with E the model's energy and P
    the couple's work rate on that steady motion.  heyoka integrates it with theta as time.
    """
    model = dissipative_disk(name)
    w3 = sp.Symbol("omega3", real=True)
    sub = {thetadot: 0, psidot: w3 - phidot * sp.cos(theta)}
    row = sp.numer(sp.together(model.accelerations[0].subs(sub)))
    family_rate = sp.sqrt(family_law(name).phidot_squared)
    probe = {theta: sp.Rational(1, 10), disk.k: sp.Rational(1, 4), g: PAPER_G, w3: 0}
    roots = [r for r in sp.solve(row, phidot) if abs(sp.N((r - family_rate).subs(probe), 30)) < 1e-20]
    if len(roots) != 1:
        raise RuntimeError("no unique steady phidot continuing the cm-at-rest family")
    rate = roots[0]
    A = derive(disk.k, 2 * disk.k, disk.R2, disk.R3, "rolling").chaplygin_matrix
    dw3 = A[1, 0] * rate * sp.sin(theta) + A[1, 1] * w3
    energy = model.energy.subs(sub).subs(phidot, rate)
    dE = sp.diff(energy, theta) + sp.diff(energy, w3) * dw3
    dt = -dE / work_rate(name).subs(sub).subs(phidot, rate)
    return sympy_system([("omega3", w3, dw3), ("t", None, dt), ("phi", None, rate * dt)], time=theta,
                        parameters=(disk.k, g, C_SYMBOL))


def _transport(name: str, pv: dict, th0: float, levels: np.ndarray):
    """Integrate the transported drift from th0 down through the levels and on to 1e-6 of the
    last one; the rest to theta = 0 (a (1e-10)^n fraction of t0) from the family law."""
    pars = [float(pv["k"]), float(pv["g"]), float(pv["c"])]  # par[0], par[1], par[2] of transport_system
    tiny = float(levels[-1]) * 1e-6
    run = through_grid(("dissipation transport", name), transport_system(name), [0.0, 0.0, 0.0], pars,
                       np.concatenate([[th0], levels, [tiny]]))
    rows = run.rows
    if not run.reached:
        raise RuntimeError(f"the transported drift stopped early ({run.outcome})")
    fl = family_law(name)
    vals = {theta0: sp.Float(repr(tiny), 30), disk.k: pv["k"], g: pv["g"], C_SYMBOL: pv["c"]}
    rest_t = float(sp.N(fl.time_to_singularity.subs(vals)))
    rest_turns = float(sp.N(fl.turns_to_singularity.subs(vals)))
    w3_end, t_end, phi_end = (float(v) for v in rows[-1])
    return rows[1:-1, 1].copy(), rows[1:-1, 2].copy(), w3_end, t_end + rest_t, phi_end / (2 * math.pi) + rest_turns


def _secants(t, th, ph):
    t, th, ph = (np.asarray(v, float) for v in (t, th, ph))
    dt = np.diff(t)
    ok = (dt > 0) & (th[1:] > 0) & (th[:-1] > 0)
    dt = np.where(ok, dt, 1.0)
    mid = np.sqrt(np.abs(th[1:] * th[:-1]))
    return mid[ok], (np.abs(np.diff(th)) / dt)[ok], (np.diff(ph) / dt)[ok]

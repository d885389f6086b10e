"""The dissipative spin-down of the disk towards theta -> 0: laws, runs, fitted exponents.

The disk of :mod:`models.dissipative` loses energy through a couple
``tau = -c sin^-n(theta) omega_perp`` (``moffatt``: n = 3, ``contact-rate``: n = 2).  This study

1. **predicts** with sympy, from the model's own expressions, what the couple does on the
   centre-of-mass-at-rest family (v_C = 0, omega3 = 0: the family on which the paper's Eq. 45,
   phidot^2 = g/(k sin theta), is exact): the family's energy E(theta), the dissipated power,
   hence ``dtheta/dt = -P / (dE/dtheta)``, its leading power ``-A theta^m`` at small theta, the
   exponents ``p = 1/(1 - m)`` of ``theta ~ (t0 - t)^p`` and ``q = p r`` of ``phidot ~ (t0 - t)^q``
   (``phidot ~ theta^r`` on the family), and the time and the number of turns of phi from a
   start theta0 to the singularity (:func:`family_law`, :func:`predict`);
2. refines that prediction: the drift does not stay on the family.  Row 3 of the rolling
   equations, ``(2k+1) d(omega3)/d(theta) = omega2`` (Chaplygin's, see :mod:`models.disk`), holds
   unchanged with the couple (it has no e3 component), so as theta falls omega3 grows from 0
   to ``-(1/(2k+1)) int omega2 dtheta`` (about -0.87 s^-1 from theta0 = 0.1) and the centre of
   mass starts to circle.  The *transported* prediction follows the steady motions with that
   omega3 (heyoka, theta as the independent variable); the exponents are the same (the
   omega3 terms are O(theta^1/2) relative), t0 and the turns move by ~1%;
3. **integrates** the model with heyoka from the exact steady state at theta0 (from
   :func:`verify.studies.spindown.spindown`), the work of the couple
   ``W(t) = int c sin^-n |omega_perp|^2 dt`` carried as a ninth variable, and checks the energy
   balance ``E(t) + W(t) = E(0)`` (:func:`integrate_with_work`);
4. **fits** the exponents without knowing t0: the slope s of log|dtheta/dt| against log theta
   gives ``p = 1/(1 - s)``, the slope of log phidot against log theta times p gives q; then t0
   and the turns to the singularity (:func:`fit_exponents`).

Where the run is trustworthy
----------------------------
The law is a statement about slow drift along steady motions: it holds while the drift rate
|dtheta/dt|/theta is small against the nutation frequency (sqrt(3/5) phidot at small theta
for k = 1/4, from the linearised equations).  Their ratio, the adiabatic parameter
``a(theta) = |dtheta/dt| / (theta phidot)``, grows like theta^-5/2 (Moffatt) and theta^-3/2
(contact-rate) as theta falls, so *every* run leaves the law before theta = 0, whatever c:
measured, the local slopes agree with the transported drift to ~1e-5 while a < 1e-4,
depart by ~1e-4 at a = 1e-3 (growing like a^2) and by ~1% at a = 1e-2; by a ~ 0.05-0.2 the
disk stops going round (phidot drops to 0 within a few nutations, nearly all the energy goes
into W) and then creeps flat, overdamped.  That is the model's physics, not round-off:
double keeps E + W = E(0) to ~600 epsilon of E(0) over 2.5e6 steps down to theta = 1e-4
(0.4-0.5 eps sqrt(N)).  A smaller c moves the breakdown down only slowly (the turns to the
singularity grow like 1/c, the breakdown angle only like c^(2/5) and c^(2/3)), so the runs
use the smallest c the time budget allows (:data:`STUDY_C`) and the fit window ends where
the predicted a(theta) reaches :data:`A_MAX`.  With the study's c the Moffatt run breaks
down at theta = 3.5e-4, above theta_stop; the contact-rate run reaches theta_stop = 1e-4 at
a = 7e-3, still on the law to 1e-3 in the local slopes.

Sampling
--------
The run is sampled where the transported prediction puts the levels
``theta0 * 10^(-j/LEVELS_PER_DECADE)``; between samples dtheta/dt and phidot are the secant
slopes ``dtheta/dt``, ``dphi/dt``, which average over the nutation (its period is ~140 a
times the time between samples).  The start, exactly on the family (thetadot = 0), excites a
nutation of relative size ~a(theta0) < 1e-6, damped by the couple.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache

import heyoka as hy
import mpmath
import numpy as np
import sympy as sp

from models import disk
from models.dissipative import LAW_NAMES, c as C_SYMBOL, dissipative_disk, law as get_law, work_rate
from models.rolling import derive
from models.common import PAPER_G
from models.symbols import STATE_NAMES, g, phidot, psidot, theta, thetadot

from ..engine import invariants as inv
from ..engine import validation
from ..engine.compile import compile_model, to_heyoka
from ..engine.problem import Problem
from ..engine.single import propagate_in_turns, resolve_parameters, through_grid
from ..precision import parse_precision
from .spindown import spindown

#: Start of every run: the exact steady centre-of-mass-at-rest state at this tilt.
THETA0 = "0.1"
#: Terminal event of every run.
THETA_STOP = "1e-4"
#: The study's coefficients (s^-1): the smallest the ~60 s budget of ``make report`` allows.
#: Moffatt 1e-8: 4.7e5 turns of phi to the singularity, 2.5e6 Taylor steps (~13 s), breakdown
#: at theta = 3.5e-4; contact-rate 2e-7: 3.9e5 turns, 1.9e6 steps (~9 s), no breakdown above
#: theta_stop = 1e-4.  Both are far below physical values (Moffatt's default, air under a
#: 5-g, 1-cm coin, is 5.7e-5); the exponents do not depend on c, only the window does.
STUDY_C = {"moffatt": "1e-8", "contact-rate": "2e-7"}
#: The fit window ends where the predicted adiabatic parameter a(theta) reaches this.
A_MAX = 1e-3
#: ... and starts here: above it the drift's local slopes stray by more than ~3e-3 from the
#: leading powers (O(theta^2) terms of the family law, O(theta^1/2 .. theta^3/2) ones of omega3).
FIT_TOP = 0.05
LEVELS_PER_DECADE = 40
#: Segments of this many radians of the fastest rate; phi, psi rebased by whole turns beyond it
#: (keeps them below the rates, so they never loosen heyoka's step-size control; see
#: verify.engine.single.propagate_in_turns).
_SEGMENT_RADIANS = 32 * math.pi


# --- 1. the laws on the family (sympy) ---------------------------------------------------------

theta0 = sp.Symbol("theta0", positive=True)


@dataclass(frozen=True)
class FamilyLaw:
    """What the couple does on the disk's centre-of-mass-at-rest family, in closed form.

    Every expression is derived from the model (the energy and row 1 of the derived
    equations, the velocity of C, the couple's work rate); nothing is typed in.
    """

    law: str
    exponent: int  # n of the couple
    phidot_squared: sp.Expr  # phidot^2 on the family (paper Eq. 45)
    energy: sp.Expr  # E(theta) on the family, per m R^2
    power: sp.Expr  # dissipated power on the family, >= 0
    rate: sp.Expr  # dtheta/dt = -power / (dE/dtheta)
    rate_coefficient: sp.Expr  # A in dtheta/dt ~ -A theta^m
    rate_exponent: sp.Rational  # m
    phidot_exponent: sp.Rational  # r in phidot ~ theta^r
    p: sp.Rational  # theta ~ (t0 - t)^p
    q: sp.Rational  # phidot ~ (t0 - t)^q
    time_to_singularity: sp.Expr  # t0 from theta0 (symbol theta0)
    turns_to_singularity: sp.Expr  # turns of phi from theta0 to theta = 0

    @property
    def finite_time(self) -> bool:
        return _finite(self.time_to_singularity)

    @property
    def finite_turns(self) -> bool:
        return _finite(self.turns_to_singularity)


def _finite(expr: sp.Expr) -> bool:
    return not expr.has(sp.oo, -sp.oo, sp.zoo, sp.nan, sp.Integral)


def _family_substitution():
    """psidot on the cm-at-rest family: v_C = 0 at thetadot = 0, solved from the derived v_C."""
    d = derive(disk.k, 2 * disk.k, disk.R2, disk.R3, "rolling")
    eqs = [e for e in d.velocity_cm.subs(thetadot, 0) if e != 0]
    sol = sp.solve(eqs, psidot, dict=True)
    if len(sol) != 1:
        raise RuntimeError("v_C = 0 does not fix psidot uniquely")
    return {thetadot: 0, psidot: sol[0][psidot]}


@lru_cache(maxsize=None)
def family_law(name: str) -> FamilyLaw:
    """Closed-form laws of the ``name`` couple on the cm-at-rest family (module docstring, item 1)."""
    lw = get_law(name)
    model = dissipative_disk(name)
    fam = _family_substitution()
    P2 = sp.Symbol("P2", positive=True)
    row = sp.numer(sp.together(model.accelerations[0].subs(fam)))  # thetaddot = 0 on a steady motion
    roots = sp.solve(sp.expand(row).subs(phidot, sp.sqrt(P2)), P2)
    if len(roots) != 1:
        raise RuntimeError(f"row 1 on the family gives {len(roots)} values of phidot^2")
    phidot2 = sp.simplify(roots[0])
    on = lambda e: sp.simplify(e.subs(fam).subs(phidot, sp.sqrt(phidot2)))
    energy, power = on(model.energy), on(work_rate(name))
    rate = sp.simplify(-power / sp.diff(energy, theta))
    A, m = _leading(-rate)
    _, r = _leading(sp.sqrt(phidot2))
    p = 1 / (1 - m)
    per_dtheta = 1 / (-rate)  # dt per unit fall of theta
    t0 = _integral_from_zero(per_dtheta)
    turns = sp.simplify(_integral_from_zero(sp.sqrt(phidot2) * per_dtheta) / (2 * sp.pi))
    return FamilyLaw(name, lw.exponent, phidot2, energy, power, rate, A, m, r, p, p * r, t0, turns)


def _integral_from_zero(expr) -> sp.Expr:
    """int_0^theta0 expr d(theta), through u = sin(theta) (0 < theta < pi/2; sympy's own
    route through heurisch takes tens of seconds on these integrands)."""
    u = sp.Symbol("u", positive=True)
    integrand = sp.expand_trig(sp.simplify(expr / sp.cos(theta)))
    integrand = sp.simplify(integrand.subs(sp.cos(theta), sp.sqrt(1 - u ** 2)).subs(sp.sin(theta), u))
    if integrand.has(theta):
        raise RuntimeError(f"cannot write {expr} d(theta) in u = sin(theta)")
    return sp.simplify(sp.integrate(integrand, (u, 0, sp.sin(theta0))))


def _leading(expr):
    """(A, m) with expr ~ A theta^m as theta -> 0+: m = lim theta d(log expr)/d(theta), A = lim expr / theta^m."""
    m = sp.limit(sp.simplify(theta * sp.diff(sp.log(expr), theta)), theta, 0, "+")
    A = sp.simplify(sp.limit(sp.simplify(expr / theta ** m), theta, 0, "+"))
    if not m.is_Rational or A.has(theta) or not _finite(A) or A == 0:
        raise RuntimeError(f"no leading power of theta in {expr}")
    return A, m


# --- 2. predictions for one start and coefficient ------------------------------------------------

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
def _transport_system(name: str):
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
    W3, T, PHI = hy.make_vars("omega3", "t", "phi")
    mapping = {w3: W3, theta: hy.time, disk.k: hy.par[0], g: hy.par[1], C_SYMBOL: hy.par[2]}
    return [(W3, to_heyoka(dw3, mapping)), (T, to_heyoka(dt, mapping)), (PHI, to_heyoka(rate * dt, mapping))]


def _transport(name: str, pv: dict, th0: float, levels: np.ndarray):
    """Integrate the transported drift from th0 down through the levels and on to 1e-6 of the
    last one; the rest to theta = 0 (a (1e-10)^n fraction of t0) from the family law."""
    pars = [float(pv["k"]), float(pv["g"]), float(pv["c"])]  # par[0], par[1], par[2] of _transport_system
    tiny = float(levels[-1]) * 1e-6
    run = through_grid(("dissipation transport", name), _transport_system(name), [0.0, 0.0, 0.0], pars,
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


# --- 3. the run with the work as a ninth variable ------------------------------------------------

@dataclass(frozen=True)
class WorkRun:
    """One run of the dissipative disk with W(t), the work of the couple, alongside.

    ``y`` has nine rows: the eight states of ``STATE_NAMES`` (phi, psi continuous) and W
    (``run["W"]``).  ``balance`` is max |E(t) + W(t) - E(0)| / E(0) over the samples.
    """

    law: str
    c: float
    params: dict  # as decimal strings
    precision: str
    work_exponent: int
    t: np.ndarray
    y: np.ndarray
    energy: np.ndarray
    normal_force: np.ndarray
    outcome: str
    steps: int
    balance: float
    eps: float
    wall_seconds: float

    def __getitem__(self, name: str) -> np.ndarray:
        return self.y[8] if name == "W" else self.y[STATE_NAMES.index(name)]

    @property
    def balance_in_eps(self) -> float:
        return self.balance / self.eps

    @property
    def balance_bound_in_eps(self) -> float:
        """10 sqrt(N), N Taylor steps: the bound ``balance`` is held to, in epsilon.

        heyoka keeps each step's local error at epsilon relative to the state's magnitude,
        and round-off adds epsilon-sized errors to E and to W each step; their signs are
        independent, so E + W - E(0) random-walks to ~ eps sqrt(N) E(0).  The suite allows
        10 eps sqrt(N) for every conserved quantity (README, Accuracy; measured there <=
        5.1).  Measured here: 0.4-0.5 eps sqrt(N) on the study's runs of 2e6 steps.
        """
        return 10.0 * math.sqrt(max(self.steps, 1))

    @property
    def balance_ok(self) -> bool:
        return self.balance_in_eps <= self.balance_bound_in_eps


def integrate_with_work(name: str, t_eval, c=None, state=None, *, params=None, theta_stop: str = THETA_STOP,
                        precision: str = "double", work_exponent=None) -> WorkRun:
    """Integrate the ``name`` disk and the work W of its couple until the last of ``t_eval``.

    Parameters
    ----------
    name : {"moffatt", "contact-rate"}
    t_eval : sequence of strictly increasing times > 0
        Output times; the run ends at the last one or at a terminal event (``theta_stop``,
        ``lies_flat``, ``contact_lost``), whose state is then the last sample.
    c : number or decimal string, optional
        The coefficient in s^-1 (default: the law's); must be finite and >= 0.
    state : dict, optional
        Initial state by name; default the exact steady cm-at-rest state at THETA0 (paper
        Eq. 45 holds exactly on it).
    params : dict, optional
        k, g (defaults as for the disk).
    theta_stop : decimal string
        Terminal event where theta falls through it; in (0, theta(0)).
    precision : {"double", "long", "quad", "mp:BITS"}
    work_exponent : int, optional
        Exponent of sin(theta) in W's integrand; only for negative controls (default: the law's n).
    """
    prec = parse_precision(precision)
    model = dissipative_disk(name)
    compiled = compile_model(model, prec)
    values = dict(params or {})
    if c is not None:
        values["c"] = c
    resolve_parameters(model, values, prec)
    if state is None:
        s = spindown("disk", THETA0, "cm-at-rest", {k: v for k, v in values.items() if k != "c"})
        state = {"theta": THETA0, "phidot": mpmath.nstr(s.phidot, 45), "psidot": mpmath.nstr(s.psidot, 45)}
    y0, pars = validation.validate(model, state, values, prec, compiled)  # as solve checks a start
    th_stop = prec.number(theta_stop)
    if not 0 < float(th_stop) < float(y0[0]):
        raise ValueError(f"theta_stop={theta_stop} must lie in (0, theta(0) = {float(y0[0]):.17g})")
    grid = [prec.number(v) for v in t_eval]
    if not grid or not float(grid[0]) > 0 or any(not b > a for a, b in zip(grid, grid[1:])):
        raise ValueError("t_eval must be a non-empty, strictly increasing sequence of times > 0")
    problem = Problem(model, prec, pars, y0, prec.zero())
    start = time.perf_counter()
    run = propagate_in_turns(problem, grid, (("W", work_rate(name, work_exponent)),), (prec.zero(),), th_stop,
                             _SEGMENT_RADIANS)
    wall = time.perf_counter() - start
    y = run.y
    values8, normal = inv.evaluate(compiled, np.ascontiguousarray(y[:8]), pars)
    energy = values8["energy"]
    balance = max(abs(float(e + w - energy[0])) for e, w in zip(energy, y[8])) / abs(float(energy[0]))
    n = get_law(name).exponent if work_exponent is None else int(work_exponent)
    return WorkRun(name, float(pars["c"]), {k: prec.to_text(v) for k, v in pars.items()}, prec.name, n,
                   run.t, y, energy, normal, run.outcome, run.steps, balance, prec.eps, wall)


# --- 4. fitted exponents ------------------------------------------------------------------------

@dataclass(frozen=True)
class ExponentFit:
    """Exponents, t0 and turns fitted on a run, against the predictions.

    ``slope_rate`` (s) and ``slope_phidot`` (r) are least-squares slopes of log|dtheta/dt| and
    log phidot against log theta over the window (secants between samples); p = 1/(1 - s),
    q = p r.  ``*_transported`` are the same fits on the transported prediction's levels.
    ``t0`` is the intercept of t = t0 - B theta^(1/p) over the lower half (in log theta) of
    the window; ``turns`` = phi / 2 pi observed down to theta_stop (or, if the run broke down
    above it, to the window's foot) + the family law's remainder from there to theta = 0.

    Tolerances (on |p - p_predicted|, |q - q_predicted|): a least-squares slope is a
    positively weighted mean of the slopes between neighbouring points, so |s - m| is at most
    the largest |local slope - m| in the window.  The local slopes are those of the
    transported drift (the exact family law has O(theta^2) terms, the omega3 it picks up
    O(theta^1/2) ones) plus what the drift's adiabatic picture leaves out, allowed A_MAX
    (measured: <= 2e-4 at a = A_MAX, falling like a^2, 1e-5 below a = 1e-4).  The interval
    for s (and r) is mapped exactly to p = 1/(1 - s) and q = p r.
    """

    window: tuple  # (theta_low, theta_high)
    points: int
    slope_rate: float
    slope_phidot: float
    slope_rate_transported: float
    slope_phidot_transported: float
    p: float
    q: float
    p_predicted: sp.Rational
    q_predicted: sp.Rational
    p_tolerance: float
    q_tolerance: float
    t0: float
    turns: float
    turns_observed: float  # phi / 2 pi up to turns_reference_theta
    turns_remainder: float  # family law, from turns_reference_theta to theta = 0
    turns_reference_theta: float  # theta_stop, or the window's foot if the run broke down above it
    breakdown_theta: float  # first secant where phidot is 10% below the transported drift (nan: none)

    @property
    def p_ok(self) -> bool:
        return abs(self.p - float(self.p_predicted)) <= self.p_tolerance

    @property
    def q_ok(self) -> bool:
        return abs(self.q - float(self.q_predicted)) <= self.q_tolerance

    @property
    def t0_finite(self) -> bool:
        """theta reaches 0 at a finite time: the fitted p > 0 and t0 came out finite."""
        return self.p > 0 and math.isfinite(self.t0)

    @property
    def turns_finite(self) -> bool:
        """int phidot dt converges at t0: phidot ~ (t0 - t)^q with q > -1."""
        return self.q > -1 and math.isfinite(self.turns)

    @property
    def matches_transported(self) -> bool:
        """The run's slopes equal the transported drift's over the same window within A_MAX."""
        return (abs(self.slope_rate - self.slope_rate_transported) <= A_MAX
                and abs(self.slope_phidot - self.slope_phidot_transported) <= A_MAX)


def _secants(t, th, ph):
    t, th, ph = (np.asarray(v, float) for v in (t, th, ph))
    dt = np.diff(t)
    ok = (dt > 0) & (th[1:] > 0) & (th[:-1] > 0)
    dt = np.where(ok, dt, 1.0)
    mid = np.sqrt(np.abs(th[1:] * th[:-1]))
    return mid[ok], (np.abs(np.diff(th)) / dt)[ok], (np.diff(ph) / dt)[ok]


def secants(run: WorkRun):
    """(theta_mid, |dtheta/dt|, phidot) between consecutive samples, theta_mid the geometric mean:
    secant slopes, which average over the nutation."""
    return _secants(run.t, run["theta"], run["phi"])


def fit_window(pred: Prediction) -> tuple:
    """(theta_low, FIT_TOP): down to where the predicted a(theta) reaches A_MAX (or theta_stop)."""
    grid = np.geomspace(FIT_TOP, float(pred.levels[-1]), 4000)
    inside = grid[pred.adiabatic_parameter(grid) <= A_MAX]
    if len(inside) == 0:
        raise ValueError(f"c = {float(pred.c):g} is too large: the drift is not adiabatic (a > {A_MAX:g}) "
                         f"anywhere below theta = {FIT_TOP}")
    return float(inside[-1]), FIT_TOP


def _ols(x, y) -> float:
    return float(np.polyfit(x, y, 1)[0])


def _window_slopes(mid, rate, phd, lo, hi):
    sel = (mid >= lo) & (mid <= hi) & (rate > 0) & (phd > 0)
    x = np.log(mid[sel])
    return x, np.log(rate[sel]), np.log(phd[sel])


def fit_exponents(run: WorkRun, pred: Prediction) -> ExponentFit:
    """Fit p, q, t0 and the turns on ``run`` (sampled at ``pred``'s level times) over :func:`fit_window`."""
    lo, hi = fit_window(pred)
    x, lr, lp = _window_slopes(*secants(run), lo, hi)
    if len(x) < 4:
        raise ValueError(f"only {len(x)} samples in the fit window [{lo:.3g}, {hi:.3g}]; the run is too short")
    s, r = _ols(x, lr), _ols(x, lp)
    xt, lrt, lpt = _window_slopes(*pred.secant_table(), lo, hi)
    p = 1.0 / (1.0 - s)
    q = p * r
    p_tol, q_tol = _tolerances(pred, xt, lrt, lpt)
    t0 = _fit_t0(run, p, lo, hi)
    breakdown = _breakdown(run, pred)
    ref = _turns_reference(run, lo, breakdown)
    observed = float(run["phi"][ref]) / (2 * math.pi)
    rest = float(pred.family_remainder(float(run["theta"][ref]))[1])
    return ExponentFit((lo, hi), len(x), s, r, _ols(xt, lrt), _ols(xt, lpt), p, q, pred.p, pred.q, p_tol, q_tol,
                       t0, observed + rest, observed, rest, float(run["theta"][ref]), breakdown)


def _turns_reference(run: WorkRun, lo: float, breakdown: float) -> int:
    """The sample the turns are counted to: theta_stop if the run got there without breaking
    down, otherwise the foot of the fit window (the last sample the law is trusted at)."""
    if run.outcome == "event:theta_stop" and math.isnan(breakdown):
        return len(run.t) - 1
    return int(np.nonzero(np.asarray(run["theta"], float) >= lo)[0][-1])


def _tolerances(pred: Prediction, x, lrate, lphd):
    """(p_tol, q_tol) from the transported drift's local slopes in the window (see ExponentFit)."""
    fl = family_law(pred.law)
    m, r_inf = float(fl.rate_exponent), float(fl.phidot_exponent)
    ds = float(np.max(np.abs(np.diff(lrate) / np.diff(x) - m))) + A_MAX
    dr = float(np.max(np.abs(np.diff(lphd) / np.diff(x) - r_inf))) + A_MAX
    p_inf, q_inf = float(fl.p), float(fl.q)
    ps = [1.0 / (1.0 - (m + e)) for e in (-ds, ds)]
    qs = [pp * (r_inf + e) for pp in ps for e in (-dr, dr)]
    return max(abs(v - p_inf) for v in ps), max(abs(v - q_inf) for v in qs)


def _fit_t0(run: WorkRun, p: float, lo: float, hi: float) -> float:
    """t0 from t = t0 - B theta^(1/p) on the samples in the lower half (in log theta) of the window."""
    th, t = np.asarray(run["theta"], float), np.asarray(run.t, float)
    sel = (th >= lo) & (th <= math.sqrt(lo * hi))
    if sel.sum() < 2:
        return math.nan
    A = np.vstack([np.ones(int(sel.sum())), -th[sel] ** (1.0 / p)]).T
    (t0, _), *_ = np.linalg.lstsq(A, t[sel], rcond=None)
    return float(t0)


def _breakdown(run: WorkRun, pred: Prediction) -> float:
    """The first secant theta where phidot is 10% below the transported drift's (nan: never)."""
    mid, _, phd = secants(run)
    pmid, _, pphd = pred.secant_table()
    expected = np.exp(np.interp(-np.log(mid), -np.log(pmid), np.log(pphd)))
    bad = np.nonzero(phd < 0.9 * expected)[0]
    return float(mid[bad[0]]) if len(bad) else math.nan


# --- the study ------------------------------------------------------------------------------------

@dataclass(frozen=True)
class LawStudy:
    """One law: its closed-form family law, the predictions, the run and the fit."""

    law: str
    family: FamilyLaw
    prediction: Prediction
    run: WorkRun
    fit: ExponentFit


def sample_times(pred: Prediction) -> np.ndarray:
    """The transported drift's level times, then a tail past its t0 (should the run be slower)."""
    t = np.asarray(pred.t_levels, float)
    t = t[np.concatenate([[True], np.diff(t) > 0])]
    tail = pred.t0_transported * (1 + np.geomspace(1e-6, 0.5, 40))
    return np.concatenate([t, tail[tail > t[-1]]])


def study(name: str, c=None, theta_stop: str = THETA_STOP) -> LawStudy:
    """Predict, run and fit one law from THETA0 (default coefficient: :data:`STUDY_C`)."""
    c = STUDY_C[get_law(name).name] if c is None else c
    pred = predict(name, c, THETA0, theta_stop)
    run = integrate_with_work(name, sample_times(pred), c, theta_stop=theta_stop)
    return LawStudy(name, family_law(name), pred, run, fit_exponents(run, pred))


def dissipation_study(laws=LAW_NAMES, progress=None) -> tuple:
    """Both laws (what the report runs; ~30 s on a 2-core machine)."""
    out = []
    for name in laws:
        if progress:
            progress(f"dissipation {name}")
        out.append(study(name))
    return tuple(out)


# --- records ------------------------------------------------------------------------------

def _d(x, digits: int = 12) -> str:
    """A decimal string (mpmath, sympy, float)."""
    if isinstance(x, mpmath.mpf):
        return mpmath.nstr(x, digits, strip_zeros=False)
    if isinstance(x, sp.Basic):
        return str(x)
    x = float(x)
    return repr(x) if not math.isfinite(x) else f"{x:.{digits}g}"


def to_record(s: LawStudy) -> dict:
    """One law's study as a JSON-ready dict; numbers as decimal strings.  Byte-reproducible:
    the run's wall time (``s.run.wall_seconds``) is left out, for timing.json."""
    fl, pr, run, fit = s.family, s.prediction, s.run, s.fit
    return {
        "law": s.law,
        "couple_exponent": fl.exponent,
        "c": _d(pr.c),
        "params": {k: _d(v) for k, v in pr.params.items()},
        "theta0": _d(pr.theta0),
        "family": {
            "phidot_squared": str(fl.phidot_squared), "energy": str(fl.energy), "power": str(fl.power),
            "dtheta_dt": str(fl.rate), "leading": f"-({fl.rate_coefficient}) theta^({fl.rate_exponent})",
            "p": str(fl.p), "q": str(fl.q), "time_to_singularity": str(fl.time_to_singularity),
            "turns_to_singularity": str(fl.turns_to_singularity),
            "finite_time": fl.finite_time, "finite_turns": fl.finite_turns,
        },
        "predicted": {
            "t0_family": _d(pr.t0_family), "turns_family": _d(pr.turns_family),
            "t0_transported": _d(pr.t0_transported), "turns_transported": _d(pr.turns_transported),
            "omega3_at_singularity_transported": _d(pr.omega3_final),
        },
        "run": {
            "precision": run.precision, "outcome": run.outcome, "steps": run.steps, "t_end": _d(run.t[-1]),
            "theta_end": _d(run["theta"][-1]), "turns_end": _d(float(run["phi"][-1]) / (2 * math.pi)),
            "energy_balance": _d(run.balance, 4), "energy_balance_eps": _d(run.balance_in_eps, 4),
            "energy_balance_bound_eps": _d(run.balance_bound_in_eps, 4), "energy_balance_ok": run.balance_ok,
        },
        "fit": {
            "window": [_d(fit.window[0], 6), _d(fit.window[1], 6)], "points": fit.points,
            "adiabatic_bound": _d(A_MAX, 3),
            "slope_rate": _d(fit.slope_rate, 8), "slope_rate_transported": _d(fit.slope_rate_transported, 8),
            "slope_phidot": _d(fit.slope_phidot, 8), "slope_phidot_transported": _d(fit.slope_phidot_transported, 8),
            "matches_transported": fit.matches_transported,
            "p": _d(fit.p, 8), "p_predicted": str(fit.p_predicted), "p_tolerance": _d(fit.p_tolerance, 3),
            "p_ok": fit.p_ok,
            "q": _d(fit.q, 8), "q_predicted": str(fit.q_predicted), "q_tolerance": _d(fit.q_tolerance, 3),
            "q_ok": fit.q_ok,
            "t0": _d(fit.t0), "t0_finite": fit.t0_finite,
            "turns": _d(fit.turns), "turns_observed": _d(fit.turns_observed), "turns_remainder": _d(fit.turns_remainder),
            "turns_reference_theta": _d(fit.turns_reference_theta, 6),
            "turns_finite": fit.turns_finite,
            "breakdown_theta": _d(fit.breakdown_theta, 4),
        },
    }

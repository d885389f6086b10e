"""The dissipative disk integrated with W(t), the work of its couple, as a ninth variable (item 3 of
the package docstring)."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import mpmath
import numpy as np

from models.dissipative import dissipative_disk, law as get_law, work_rate
from models.symbols import STATE_NAMES

from ...engine import invariants as inv
from ...engine import validation
from ...engine.compile import compile_model
from ...engine.problem import Problem
from ...engine.single import propagate_in_turns, resolve_parameters
from ...precision import parse_precision
from ..spindown import spindown
from .protocol import THETA0, THETA_STOP

#: Segments of this many radians of the fastest rate; phi, psi rebased by whole turns beyond it
#: (keeps them below the rates, so they never loosen heyoka's step-size control; see
#: verify.engine.single.propagate_in_turns).
_SEGMENT_RADIANS = 32 * math.pi


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
        10 eps sqrt(N) for every conserved quantity (docs/accuracy.md; measured there <=
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

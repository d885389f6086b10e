"""Reference runs of the Coulomb cases: a body that rolls, slides and sticks again.

A Coulomb case (:attr:`verify.reference.cases.ReferenceCase.friction` set) is integrated by the
event-driven hybrid of :mod:`verify.engine.hybrid` (rolling phases by the rolling model, sliding phases
by :mod:`models.coulomb`, each switch located by heyoka's event root finding to the precision's
epsilon), twice in MPFR as every case is.  Beside the eight state components it keeps, on the same
grid, E + W (conserved by the exact flow: the file's ``invariants``) and the ``columns`` energy E, work W
done by friction, slip speed s and the centre of mass's horizontal velocity (v_x, v_y) (the rolling one
plus the slip s (cos alpha, sin alpha): the Euler angles and their rates do not hold it while the
contact slides); and the switch times themselves (where a phase ends and the next begins), agreed between the two
runs like any other value.  Two runs that do not switch the same number of times, in the same order,
do not make a reference: that raises.

The conditioning (how an error in the start grows) cannot come from heyoka's variational equations
here: they know nothing of the switches, whose times move with the start (the saltation of the
transition matrix).  It is measured instead by central differences of whole hybrid runs in quad
precision, each start component (and the skid's two velocity components) moved by 1e-12 of its size
(at least 1e-12): the differences keep about 10 digits (rounding 1e-34 / 1e-12, truncation 1e-24),
far more than the 4 the conditioning block keeps.  Each parameter (and mu) is moved the same way for
the parameter terms.  A perturbed run that switches differently (a grazing switch) raises: the flow
is not differentiable there and no row sum would mean anything.
"""
from __future__ import annotations

from dataclasses import dataclass

import mpmath
import sympy as sp

from models import get_model
from models.symbols import STATE, STATE_NAMES

from ..engine.hybrid import solve as solve_hybrid
from ..engine.hybrid_run import grid_rows, switch_kinds
from ..precision import parse_precision
from .cases import ReferenceCase

#: The invariant kept beside the state, on the grid (the file's ``invariants`` block).
INVARIANTS = ("energy_plus_work",)
#: The other columns kept on the grid (the file's ``columns`` block).
COLUMNS = ("energy", "work", "slip_speed", "velocity_x", "velocity_y")
#: Relative size of the central differences of the conditioning (quad runs; see the module).
STEP = mpmath.mpf("1e-12")


@dataclass(frozen=True)
class HybridRun:
    """One Coulomb case at one precision: the grid's values as decimal strings, and the switches."""

    case: str
    precision: str
    steps: int
    outcome: str
    state: dict  # name -> [text per grid time]
    invariants: dict  # name -> [text per grid time]: E + W
    columns: dict  # name -> [text per grid time]: E, W, slip speed, C's velocity
    phases: list  # the phase ('rolling' or 'sliding') each grid time belongs to
    switch_kinds: list  # 'rolling -> sliding', 'sliding -> rolling', ... in order
    switch_times: list  # [text per switch]


def solve_case(c: ReferenceCase, precision, times=None, state=None, params=None, velocity=None, friction=None):
    """The hybrid run of Coulomb case ``c`` at ``precision`` on ``times`` (default: its grid); ``state``,
    ``params``, ``velocity``, ``friction`` override the case's (the conditioning's perturbed runs)."""
    times = list(times or c.grid())
    return solve_hybrid(c.run_model, times[-1], state or c.state, params or c.exact_params,
                        friction=friction or c.friction, velocity=velocity or c.velocity, precision=precision,
                        t_eval=times)


def run_case(c: ReferenceCase, precision: str) -> HybridRun:
    """Integrate Coulomb case ``c`` at ``precision`` on its grid; raise unless it reaches t_end."""
    p = parse_precision(precision)
    sol = solve_case(c, p)
    if sol.outcome != "ok":
        raise RuntimeError(f"reference case {c.name} at {precision}: {sol.outcome} at t = {float(sol.t[-1]):.9g}; "
                           "a reference run must reach t_end")
    rows = grid_rows(sol, c.grid(), p)
    text = p.to_text
    state = {n: [text(sol.y[i][j]) for j in rows] for i, n in enumerate(STATE_NAMES)}
    vx, vy = cm_velocity(c, sol, rows, p)
    columns = {"energy": [text(sol.energy[j]) for j in rows], "work": [text(sol.work[j]) for j in rows],
               "slip_speed": [text(sol.slip_speed[j]) for j in rows], "velocity_x": vx, "velocity_y": vy}
    invariants = {"energy_plus_work": [text(sol.energy[j] + sol.work[j]) for j in rows]}
    phases = [sol.phases[sol.phase_index[j]].kind for j in rows]
    return HybridRun(c.name, p.name, sol.steps, sol.outcome, state, invariants, columns, phases, switch_kinds(sol),
                     [text(t) for t in sol.switch_times])


def cm_velocity(c: ReferenceCase, sol, rows: list, p) -> tuple:
    """C's horizontal velocity at the outputs ``rows`` as text at precision ``p``: the rolling model's no-slip
    velocity at the state plus the slip s (cos alpha, sin alpha) (paper Eq. 7 with u = v_C + omega x r_P)."""
    model = get_model(c.model)
    params = c.exact_params
    subs = {q.symbol: params.get(q.name, q.default) for q in model.parameters}
    f = sp.lambdify(STATE, [e.subs(subs) for e in model.velocity_xy], "mpmath")
    out = ([], [])
    with mpmath.workprec(p.bits + 16):
        for j in rows:
            v = f(*(p.to_mpf(sol.y[i][j]) for i in range(8)))
            s = p.to_mpf(sol.slip_speed[j])
            alpha = p.to_mpf(sol.slip_direction[j]) if s else mpmath.mpf(0)
            for k, slip in enumerate((s * mpmath.cos(alpha), s * mpmath.sin(alpha))):
                out[k].append(p.to_text(p.number(mpmath.mpf(v[k]) + slip)))
    return out


def check_same_switches(low: HybridRun, high: HybridRun) -> None:
    """Two runs of one case must switch in the same order (otherwise they are not the same motion)."""
    if low.switch_kinds != high.switch_kinds or low.phases != high.phases:
        raise RuntimeError(f"reference case {low.case}: the {low.precision} and {high.precision} runs switch "
                           f"differently ({low.switch_kinds} against {high.switch_kinds}): no agreement to keep")


def conditioning(c: ReferenceCase) -> dict:
    """Row sums of |Phi(t, 0)| and the parameter terms on the grid, by central differences of quad runs."""
    quad = parse_precision("quad")
    grid = c.grid()
    base = solve_case(c, quad)
    base_kinds = switch_kinds(base)
    inputs = []  # (label, state, velocity, params, friction) of each perturbed pair
    start = {n: mpmath.mpf(c.state.get(n, "0")) for n in STATE_NAMES}
    params = {k: mpmath.mpf(sp.N(v, 50)) for k, v in c.exact_params.items()}
    with mpmath.workdps(50):
        for n in STATE_NAMES:
            h = STEP * max(abs(start[n]), 1)
            inputs.append(("state", h, [({**c.state, n: _text(start[n] + s * h)}, c.velocity, None, None)
                                        for s in (1, -1)]))
        for k in range(len(c.velocity or ())):
            v = mpmath.mpf(c.velocity[k])
            h = STEP * max(abs(v), 1)
            inputs.append(("state", h, [(None, tuple(_text(v + s * h) if i == k else c.velocity[i]
                                                     for i in range(2)), None, None) for s in (1, -1)]))
        for name, value in list(params.items()) + [("mu", mpmath.mpf(c.friction))]:
            h = STEP * abs(value)
            moved = [value + s * h for s in (1, -1)]
            if name == "mu":
                inputs.append(("parameter", value / (2 * h), [(None, c.velocity, None, _text(m)) for m in moved]))
            else:
                inputs.append(("parameter", value / (2 * h),
                               [(None, c.velocity, {**c.exact_params, name: sp.Rational(_text(m))}, None)
                                for m in moved]))
    rows = {n: [mpmath.mpf(0)] * len(grid) for n in STATE_NAMES}
    terms = {n: [mpmath.mpf(0)] * len(grid) for n in STATE_NAMES}
    with mpmath.workdps(50):
        for kind, h, pair in inputs:
            runs = []
            for state, velocity, pars, mu in pair:
                sol = solve_case(c, quad, state=state, params=pars, velocity=velocity, friction=mu)
                if sol.outcome != "ok" or switch_kinds(sol) != base_kinds:
                    raise RuntimeError(f"conditioning of {c.name}: a start moved by 1e-12 switches differently "
                                       f"({switch_kinds(sol)} against {base_kinds}, {sol.outcome}): not differentiable")
                at = grid_rows(sol, grid, quad)
                runs.append([[quad.to_mpf(sol.y[i][j]) for j in at] for i in range(8)])
            for i, n in enumerate(STATE_NAMES):
                for j in range(len(grid)):
                    d = abs(runs[0][i][j] - runs[1][i][j])
                    if kind == "state":
                        rows[n][j] += d / (2 * h)
                    else:
                        terms[n][j] += d * h
    fmt = lambda x: float(f"{float(x):.3e}")  # noqa: E731 -- magnitudes: 4 digits are plenty, and stable
    return {
        "method": "central differences of hybrid runs (verify.engine.hybrid) in quad precision: each start component "
                  "(and each component of a skid's CM velocity) and each parameter (and mu) moved by 1e-12 of its size "
                  "(at least 1e-12 for the start); state_row_sum[i] = sum_j |dy_i(t)/dy_j(0)| (the switch times move "
                  "with the start: the saltation is in it), parameter_term[i] = sum_k |dy_i(t)/dp_k| |p_k|; the variational "
                  "equations of heyoka know nothing of the switches",
        "state_row_sum": {n: [1.0] + [fmt(r) for r in rows[n][1:]] for n in STATE_NAMES},
        "parameter_term": {n: [0.0] + [fmt(r) for r in terms[n][1:]] for n in STATE_NAMES},
    }


def _text(x) -> str:
    return mpmath.nstr(x, 40, strip_zeros=False)


__all__ = ["COLUMNS", "INVARIANTS", "HybridRun", "cm_velocity", "check_same_switches", "conditioning", "grid_rows", "run_case", "solve_case"]

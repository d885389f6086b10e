"""Re-integrate a reference case at a working precision and measure it against the agreeing digits.

The expected error of a run at epsilon ``eps`` after N Taylor steps, for component y_i at
time t, is bounded to first order by

    eps (sqrt(N) R*(t) Y + P_i(t) + |y_i(t)|)

* ``sqrt(N) R*(t) Y``: every step commits a local error of at most eps Y in each component
  (heyoka's tolerance is relative to the largest component of the state it integrates; the
  suite keeps phi, psi, x, y out of it, so Y is the largest of theta, the rates and 4 pi);
  errors of independent sign add like sqrt(N).  An error committed at time s reaches y_i(t)
  through row i of Phi(t, s), which the variational equations give only for s = 0; its row
  sum is bounded by R*(t), the largest row sum of Phi(s', 0) of any component at any
  s' <= t.  That is exact for the rounding of the start and an estimate for later errors
  (the flows are integrable and Phi grows secularly, so later errors meet a younger, smaller
  Phi); the per-component R_i(t) alone is not enough where a row of Phi(t, 0) passes
  through a small value while Phi(t, s) does not (measured: 0.95 of that bound for theta of
  the ring's Fig. 10 run in long double);
* ``P_i``: the parameters are rounded once (relative eps), and reach y_i through P_i;
* ``|y_i|``: the final rounding of the value itself, and of the offsets phi, psi, x, y
  carry between segments.

The row sums and P_i come with the case file (variational equations).  To this the reference's own
uncertainty ``abs_error`` is added.  A check passes when every value of every grid time is
within its bound; the ratio error / bound is what is reported (typically 1e-3 to 1e-1: the
bound is a bound, not an estimate).

Where the case has proved enclosures (:mod:`.proved`), the run is also measured against them:
its distance from each proved ball (0 inside it), in units of the same bound without
``abs_error`` (the ball is proved, not agreed, so no allowance is added for it).  A run at a
working precision cannot land inside a ball 10^-30 wide; what it must do is come within its own
error bound of it.  A check passes only when both ratios are at most 1.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import mpmath
import sympy as sp

from models.symbols import STATE_NAMES

from ..engine.hybrid import solve as solve_hybrid
from ..engine.single import solve
from ..precision import parse_precision
from ..engine.hybrid_run import grid_rows, switch_kinds
from .make import equations_fingerprint
from .store import reduced_scale

CHECK_PRECISIONS = ("double", "long", "quad")


@dataclass(frozen=True)
class CaseCheck:
    """The outcome of re-integrating one case at one precision.

    ``ratio`` is the largest error / bound over every component and grid time, at ``where``;
    ``reference_share`` is the part of the bound there that is the reference's own abs_error
    (near 1: the check is limited by the reference, not by the run).
    """

    case: str
    precision: str
    steps: int
    ratio: float
    where: str
    error: float
    bound: float
    reference_share: float
    ok: bool
    message: str = ""
    proof_ratio: Optional[float] = None
    proof_where: str = ""

    def to_record(self) -> dict:
        out = {"case": self.case, "precision": self.precision, "steps": self.steps, "ratio": float(f"{self.ratio:.3e}"),
               "where": self.where, "error": float(f"{self.error:.3e}"), "bound": float(f"{self.bound:.3e}"),
               "reference_share": round(self.reference_share, 3), "ok": self.ok, "message": self.message}
        if self.proof_ratio is not None:
            out.update(proof_ratio=float(f"{self.proof_ratio:.3e}"), proof_where=self.proof_where)
        return out


def check_case(record: dict, precision: str = "double", params: Optional[dict] = None,
               proofs: Optional[list] = None) -> CaseCheck:
    """Integrate the case of ``record`` at ``precision`` and compare every value with the reference.

    ``params`` overrides parameters (decimal strings): only for negative controls.  ``proofs``:
    the case's proved enclosures (:func:`.proved.load_proofs`), measured against as well.
    """
    prec = parse_precision(precision)
    name = record["name"]
    model = record["model"]["name"]
    hybrid = "friction" in record
    if record["model"]["equations_sha256"] != equations_fingerprint(record["friction"]["model"] if hybrid else model):
        return CaseCheck(name, prec.name, 0, math.inf, "-", math.nan, math.nan, 0.0, False,
                         "stale: the model's equations changed since the reference was made "
                         "(equations_sha256 differs); run 'python -m verify reference --make'")
    values = {k: sp.Rational(v["exact"]) for k, v in record["model"]["parameters"].items()}
    values.update(params or {})
    grid = record["grid"]
    if hybrid:
        sol, message = _hybrid_run(record, values, prec)
        if message:
            return CaseCheck(name, prec.name, sol.steps, math.inf, f"t = {float(sol.t[-1]):.6g}", math.nan, math.nan,
                             0.0, False, message)
    else:
        sol = solve(model, record["t_end"], record["initial_state"], values, precision=prec, t_eval=grid)
    if sol.outcome != "ok" or len(sol.t) != len(grid):
        return CaseCheck(name, prec.name, sol.steps, math.inf, f"t = {float(sol.t[-1]):.6g}", math.nan, math.nan, 0.0,
                         False, f"the run stopped early: {sol.outcome}")
    scale = reduced_scale(record)
    root_n = math.sqrt(max(sol.steps, 1))
    worst = (-1.0, "", 0.0, 0.0, 0.0)
    rows = record["conditioning"]["state_row_sum"]
    r_star = [max(max(rows[n][:j + 1]) for n in STATE_NAMES) for j in range(len(grid))]
    with mpmath.workprec(320):
        eps = mpmath.mpf(2) ** (1 - prec.bits)
        for i, n in enumerate(STATE_NAMES):
            col = record["state"][n]
            P = record["conditioning"]["parameter_term"][n]
            for j in range(len(grid)):
                ref = mpmath.mpf(col["value"][j])
                err = abs(prec.to_mpf(sol.y[i, j]) - ref)
                ref_err = mpmath.mpf(col["abs_error"][j])
                bound = eps * (root_n * r_star[j] * scale + P[j] + abs(ref)) + ref_err
                ratio = float(err / bound)
                if ratio > worst[0]:
                    worst = (ratio, f"{n} at t = {grid[j]}", float(err), float(bound), float(ref_err / bound))
    ratio, where, error, bound, share = worst
    proof_ratio, proof_where = _against_proofs(record, proofs or [], sol, prec, root_n, r_star, scale)
    ok = ratio <= 1.0 and (proof_ratio is None or proof_ratio <= 1.0)
    return CaseCheck(name, prec.name, sol.steps, ratio, where, error, bound, share, ok,
                     proof_ratio=proof_ratio, proof_where=proof_where)


@dataclass(frozen=True)
class _GridRun:
    """A hybrid run's outputs at the case's grid times only (the shape the check reads)."""

    t: list
    y: object  # (8, grid) array
    steps: int
    outcome: str


def _hybrid_run(record: dict, values: dict, prec):
    """The Coulomb case re-run by the hybrid at ``prec``: (its grid outputs, '' or why it fails).

    A run that switches differently from the reference (another sequence of rolling and sliding) fails
    by name: its values would be compared with another motion's."""
    friction = record["friction"]
    params = {k: v for k, v in values.items() if k != "mu"}
    sol = solve_hybrid(friction["model"], record["t_end"], record["initial_state"], params,
                       friction=values.get("mu", friction["mu"]), velocity=friction["initial_velocity_xy"],
                       precision=prec, t_eval=record["grid"])
    kinds = switch_kinds(sol)
    if sol.outcome == "ok" and kinds != record["switches"]["kinds"]:
        return sol, f"the run switches differently from the reference ({kinds} against {record['switches']['kinds']})"
    if sol.outcome != "ok":
        return sol, f"the run stopped early: {sol.outcome}"
    rows = grid_rows(sol, record["grid"], prec)
    return _GridRun([sol.t[j] for j in rows], sol.y[:, rows], sol.steps, sol.outcome), ""


def _against_proofs(record, proofs, sol, prec, root_n, r_star, scale):
    """The largest distance of the run from a proved ball over the run's own bound, and where."""
    if not proofs:
        return None, ""
    grid = record["grid"]
    worst, where = 0.0, ""
    with mpmath.workprec(max(320, 4 * max(p["settings"]["prec"] for p in proofs))):
        eps = mpmath.mpf(2) ** (1 - prec.bits)
        for proof in proofs:
            for j, t in enumerate(proof["times"]):
                index = grid.index(t)
                for i, n in enumerate(STATE_NAMES):
                    mid = mpmath.mpf(proof["state"][n]["mid"][j])
                    rad = mpmath.mpf(proof["state"][n]["rad"][j])
                    gap = max(abs(prec.to_mpf(sol.y[i, index]) - mid) - rad, 0)
                    bound = eps * (root_n * r_star[index] * scale + record["conditioning"]["parameter_term"][n][index]
                                   + abs(mid))
                    ratio = float(gap / bound)
                    if ratio > worst or not where:
                        worst, where = ratio, f"{n} at t = {t} ({proof['settings']['prec']}-bit proof)"
    return worst, where


def render_checks(checks: list) -> str:
    """A plain-text table of checks (what ``reference --check`` prints)."""
    lines = [f"{'case':<28} {'precision':<9} {'steps':>6} {'error/bound':>12}  {'worst value':<26} "
             f"{'error':>9} {'bound':>9} {'ref share':>9} {'proof gap/bound':>15}  result"]
    for c in checks:
        result = "ok" if c.ok else ("FAIL " + c.message if c.message else "FAIL")
        proof = "-" if c.proof_ratio is None else f"{c.proof_ratio:.3e}"
        lines.append(f"{c.case:<28} {c.precision:<9} {c.steps:>6} {c.ratio:>12.3e}  {c.where:<26} "
                     f"{c.error:>9.2e} {c.bound:>9.2e} {c.reference_share:>9.3f} {proof:>15}  {result}")
    return "\n".join(lines)

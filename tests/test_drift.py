"""The three drift figures of an invariant (verify/invariants.py, InvariantTrace).

max_abs_drift = max |I(t) - I(0)|; max_rel_drift = that / |I(0)| (NaN where |I(0)| is within
NEGLIGIBLE_INITIAL eps of the term scale); max_drift_vs_terms = that / term scale, the
largest sum along the run of the magnitudes of I's terms.  Checked on the README's quad run
against arithmetic done here, on an invariant that starts at zero, and with a jump injected
into an energy trace (negative control).
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import STATE
from verify import solve
from verify.engine.invariants import NEGLIGIBLE_INITIAL, trace
from verify.precision import parse_precision

README_RUN = dict(model="disk", t_end="2", state={"theta": "1.2", "psidot": "10"}, precision="quad")


@pytest.fixture(scope="module")
def readme_run():
    r = README_RUN
    return solve(r["model"], t_end=r["t_end"], state=r["state"], precision=r["precision"])


def exact(value) -> mpmath.mpf:
    """A real128 as the exact mpmath number (three doubles hold its 113 bits; every subtraction
    below is exact in quad, the remainder having fewer bits than the number)."""
    parts, rest = [], value
    for _ in range(3):
        hi = float(rest)
        parts.append(hi)
        rest = rest - type(value)(hi)
    assert float(rest) == 0.0
    with mpmath.workprec(256):
        return mpmath.fsum(mpmath.mpf(x) for x in parts)


def test_readme_run_relative_drift_is_max_abs_change_over_initial(readme_run):
    """max_rel_drift is max |E - E(0)| / |E(0)| of the returned energies, done here exactly."""
    e = readme_run.invariants["energy"]
    with mpmath.workprec(256):
        vals = [exact(v) for v in e.values]
        worst = max(abs(v - vals[0]) for v in vals)
        rel = worst / abs(vals[0])
    # The class takes each difference in quad (exact: Sterbenz) and rounds it and |E(0)| to
    # double, then divides: at most three roundings of 2^-53 from the exact ratio.
    assert abs(e.max_abs_drift - float(worst)) <= 2.0 ** -52 * float(worst)
    assert abs(e.max_rel_drift - float(rel)) <= 2.0 ** -51 * float(rel)
    # The term-scale figure divides the same drift by the term scale (173 |E(0)| here: the
    # disk dips to theta = 0.25, where the expanded (phidot cos theta + psidot)^2 cancels).
    assert e.max_drift_vs_terms == e.max_abs_drift / e.term_scale
    assert e.max_drift_vs_terms_in_eps == e.max_drift_vs_terms / readme_run.precision.eps
    assert e.term_scale > 100 * abs(float(e.initial))
    assert e.max_rel_drift > 100 * e.max_drift_vs_terms
    # README: "~5e-33"; and not the old figure, which was the term-scale one (3e-35).
    assert 1e-33 < e.max_rel_drift < 1e-32


def test_readme_run_relative_drift_is_the_energy_change_of_the_stored_states(readme_run):
    """Recompute E from sol.y with the model's sympy expression at 256 bits (the exact energy of
    the states the run returned): the run's relative drift differs from that one only by the
    rounding of the run's own evaluation of E, and both respect Brouwer's bound carried over to
    the relative figure.

    Bounds: |rel_run - rel_exact| <= 2 delta / |E(0)|, delta = the largest error of the run's
    evaluation of E (triangle inequality on both ends of the largest difference); delta itself
    <= 10 eps term scale (a sum of ~10 terms, each rounded relative to its magnitude, and the
    term scale bounds them: the test_conservation argument).  In units of eps, both relative
    drifts stay below 10 sqrt(N) term scale / |E(0)| (that argument's bound on the term-scale
    figure, times the ratio between the two figures).  Measured: rel_run 26.9 eps, rel_exact
    27.0 eps, delta 2.6 eps |E(0)| = 0.015 eps term scale.
    """
    sol = readme_run
    e, eps = sol.invariants["energy"], sol.precision.eps
    model = get_model("disk")
    f = sp.lambdify(list(STATE) + [p.symbol for p in model.parameters], model.invariants[0].expr, modules="mpmath")
    with mpmath.workprec(256):
        pars = [exact(sol.params[p.name]) for p in model.parameters]
        true = [f(*[exact(v) for v in col], *pars) for col in sol.y.T]
        run = [exact(v) for v in e.values]
        e0 = abs(true[0])
        rel_exact = float(max(abs(v - true[0]) for v in true) / e0)
        delta = float(max(abs(a - b) for a, b in zip(run, true)))
    assert delta <= 10 * eps * e.term_scale
    assert abs(e.max_rel_drift - rel_exact) <= 2 * delta / float(e0) + 2.0 ** -50 * rel_exact
    brouwer = 10 * math.sqrt(sol.steps) * e.term_scale / float(e0)
    assert e.max_rel_drift / eps <= brouwer and rel_exact / eps <= brouwer
    assert rel_exact > 100 * e.max_drift_vs_terms  # the relative figure is the larger one, independently


def _zero_spin_state() -> dict:
    """Sliding disk with psidot = -phidot cos(theta): omega3 = 0, so p_psi = 2 k omega3 is zero in
    exact arithmetic and, from the rounded state, a few ulps of its terms."""
    with mpmath.workdps(60):
        psidot = -5 * mpmath.cos(mpmath.mpf("1.2"))
        return {"theta": "1.2", "phidot": "5", "psidot": mpmath.nstr(psidot, 50)}


@pytest.mark.parametrize("precision", ["double", "quad"])
def test_invariant_starting_at_zero_has_no_relative_drift(precision):
    sol = solve("sliding-disk", "2", _zero_spin_state(), precision=precision, n_eval=51)
    p = sol.invariants["p_psi"]
    eps = sol.precision.eps
    assert sol.outcome == "ok"
    assert abs(float(p.initial)) <= NEGLIGIBLE_INITIAL * eps * p.term_scale and p.initial_negligible
    assert math.isnan(p.max_rel_drift)
    assert math.isfinite(p.max_abs_drift)
    # omega3 is carried as psidot + phidot cos(theta): each step rounds them at eps relative, a
    # random walk (test_conservation's bound); the absolute drift is that times the term scale.
    assert p.max_drift_vs_terms <= 10 * eps * math.sqrt(sol.steps)
    assert p.max_abs_drift == pytest.approx(p.max_drift_vs_terms * p.term_scale, rel=2.0 ** -50)
    # ... while p_phi and the energy, far from zero, keep their relative figure.
    assert all(math.isfinite(sol.invariants[k].max_rel_drift) for k in ("energy", "p_phi"))


def test_cli_json_gives_null_for_an_undefined_relative_drift(capsys):
    import json

    from verify.cli import main

    argv = ["trajectory", "sliding-disk", "--t-end", "0.5", "--format", "json"]
    for k, v in _zero_spin_state().items():
        argv += ["--state", f"{k}={v}"]
    assert main(argv) == 0
    rec = json.loads(capsys.readouterr().out)["invariants"]
    assert rec["p_psi"]["max_rel_drift"] is None
    assert isinstance(rec["p_psi"]["max_abs_drift"], float) and isinstance(rec["p_psi"]["max_drift_vs_terms"], float)
    assert isinstance(rec["energy"]["max_rel_drift"], float)


def test_trace_rule_for_zero_and_negligible_initial_values():
    eps = parse_precision("double").eps
    # I(0) = 0 exactly: relative undefined, absolute and term-scale figures defined.
    t = trace("I", np.array([0.0, 3e-16, -5e-16]), 2.0, eps)
    assert math.isnan(t.max_rel_drift) and t.max_abs_drift == 5e-16 and t.max_drift_vs_terms == 2.5e-16
    # Zero term scale (every term vanishes along the run): no ratio at all, never an absolute number.
    t = trace("I", np.array([0.0, 0.0]), 0.0, eps)
    assert math.isnan(t.max_rel_drift) and math.isnan(t.max_drift_vs_terms) and t.max_abs_drift == 0.0
    # At the threshold, relative is undefined; just above, it is the plain ratio.
    at = NEGLIGIBLE_INITIAL * eps * 1.0
    assert math.isnan(trace("I", np.array([at, at]), 1.0, eps).max_rel_drift)
    above = 2 * at
    t = trace("I", np.array([above, above + 1e-20]), 1.0, eps)
    assert t.max_rel_drift == t.max_abs_drift / above


def test_injected_jump_raises_every_figure(readme_run):
    """Negative control: the README run's energy with a jump of 1e-20 |E(0)| at one late grid
    point.  All three figures must grow to the jump (the clean run is at 5e-33 relative)."""
    e = readme_run.invariants["energy"]
    bad = e.values.copy()
    jump = type(bad[0])("1e-20") * bad[0]
    bad[-20] = bad[-20] + jump
    t = trace("energy", bad, e.term_scale, e.eps)
    j = abs(float(jump))
    assert t.max_abs_drift >= 0.99 * j > 1e9 * e.max_abs_drift
    assert t.max_rel_drift >= 0.99e-20 > 1e9 * e.max_rel_drift
    assert t.max_drift_vs_terms >= 0.99 * j / e.term_scale > 1e9 * e.max_drift_vs_terms
    assert t.max_drift_vs_terms_in_eps > 1e9 * e.max_drift_vs_terms_in_eps


def test_cli_text_names_the_figures_and_prints_n_a(capsys):
    from verify.cli import main

    argv = ["trajectory", "sliding-disk", "--t-end", "0.5"]
    for k, v in _zero_spin_state().items():
        argv += ["--state", f"{k}={v}"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "max |I - I(0)|, that / |I(0)|, that / term scale in eps" in out
    p_psi = next(ln for ln in out.splitlines() if ln.strip().startswith("p_psi"))
    assert p_psi.split()[4] == "n/a"

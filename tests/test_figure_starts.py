"""The figure starts (verify/figure_starts.py) against the claim code's own formulas, to the last bit.

Each start's state is recomputed here from the formula the figure's caption names (Eq. 21's
psidot, the Eq. 32 and Eq. 41 rates, the spin-down states of Fig. 6, the ring's circle of Eq. 58
and equilibrium of Eq. 62, the hurricane balls' Eqs. 72 and 82), with the claim code's functions
and constants, and compared with the registry's strings; and every simulated figure panel has a start.
"""
from __future__ import annotations

import math
import re
import subprocess
import sys

import pytest

from verify.figure_starts import DENSE, SIDES, STARTS, figures_with_runs, panel_sides, start, starts_of


def _r(value) -> str:
    return value if isinstance(value, str) else repr(float(value))


def _formulas() -> dict:
    """name -> (model, state as repr strings, t_end, params) from the claim code's formulas."""
    import mpmath

    from models.steady import steady_state
    from verify.claims.disk_spindown import fig6_rates
    from verify.claims.simulations import disk, hurricane, ring
    from verify.claims.simulations.runs import G, K, RING_PRINTED, SQRT_G

    out = {}

    def add(name, model, state, t_end, params=None):
        out[name] = (model, {k: _r(v) for k, v in state.items()}, str(t_end), dict(params or {}))

    add("fig2", "disk", {"theta": 1.8, "phidot": 5.0, "psidot": disk._eq21_psidot(1.8, 5.0)}, 4)
    crit32 = math.sqrt(G / (2 * (2 * K + 1)))  # Eq. 32
    th3, rate = math.pi / 2 + 0.1, 1.001 * crit32
    add("fig3-lhs", "disk", {"theta": th3, "psidot": rate}, 10)
    add("fig3-lhs-family", "disk", {"theta": th3, "psidot": rate, "phidot": 2 * rate * 0.1}, 10)
    add("fig3-rhs", "disk", {"theta": th3, "psidot": 0.9 * crit32}, 10)
    circle = {"theta": 1.3, "phidot": 5.0, "psidot": disk._eq21_psidot(1.3, 5.0)}
    add("fig4-lhs", "disk", circle, 5)
    add("fig4-rhs", "disk", dict(circle, phidot=0.0), 5)
    crit41 = math.sqrt(G / (K + 1))  # Eq. 41
    member = lambda phd: 2 * (K + 1) * phd * 0.01 / (2 * K + 1)
    for side, f in (("lhs", 1.1), ("rhs", 0.9)):
        add(f"fig5-{side}", "disk", {"theta": math.pi / 2 + 0.01, "phidot": f * crit41, "psidot": member(f * crit41)}, 10)
    for side, family in (("lhs", "no-vertical-spin"), ("rhs", "cm-at-rest")):
        phr, psr, _ = fig6_rates("1/100", family)
        add(f"fig6-{side}", "disk", {"theta": "0.01", "phidot": float(mpmath.nstr(phr, 30)),
                                     "psidot": float(mpmath.nstr(psr, 30))}, 0.5)
    phd9, psd9 = ring._ring_cm_rest_rates(0.1, +1)
    for side, f in (("lhs", 1.01), ("rhs", 0.99)):
        add(f"fig9-{side}", "ring", {"theta": 0.1, "phidot": phd9, "psidot": f * psd9}, 10, RING_PRINTED)
    eq = math.atan2(1, float(RING_PRINTED["h"]))  # cot^-1 h
    for side, rate10 in (("lhs", 19.3), ("rhs", 18.8)):
        add(f"fig10-{side}", "ring", {"theta": eq + 2e-4, "psidot": rate10}, 5, RING_PRINTED)
    root = float(steady_state("ring", "diameter-spin", "25.7", RING_PRINTED)["theta"])
    add("fig11-lhs", "ring", {"theta": 1.225, "phidot": SQRT_G}, 20, RING_PRINTED)
    add("fig11-rhs", "ring", {"theta": root + (1.225 - ring._fig11_lhs_root()), "phidot": 25.7}, 20, RING_PRINTED)
    add("fig12", "ring", {"theta": math.pi / 2 - 0.55, "phidot": 4.5 * SQRT_G}, 3, RING_PRINTED)
    phd15 = math.sqrt(2.6 * G)
    th15 = hurricane._hb_steady_theta(phd15)  # Eq. 72
    add("fig15-lhs", "hurricane", {"theta": th15, "phidot": phd15, "psidot": phd15}, 5)
    add("fig15-rhs", "hurricane", {"theta": th15 + 0.01, "phidot": phd15, "psidot": phd15}, 5)
    phd16 = math.sqrt(25 * G)
    th16 = hurricane._hb_steady_theta(phd16)
    add("fig16-lhs", "hurricane", {"theta": th16 + 0.01, "phidot": phd16, "psidot": phd16}, 3)
    add("fig16-rhs", "hurricane", {"theta": th16, "phidot": phd16, "psidot": 1.1 * phd16}, 3)
    eq82 = lambda rho, th: math.sqrt(G / ((1.4 * rho - 1) - (2 - rho) * math.cos(th)))  # Eq. 82 for phidot
    phd17 = eq82(1.2, 0.578)
    add("fig17-lhs", "hurricane", {"theta": 0.578, "phidot": phd17, "psidot": 1.2 * phd17}, 2)
    add("fig17-rhs", "hurricane", {"theta": 0.578 + 0.01, "phidot": phd17, "psidot": 1.2 * phd17}, 2)
    for side, f in (("lhs", 0.98), ("rhs", 0.97)):
        add(f"fig18-{side}", "hurricane", {"theta": 0.01, "phidot": f * SQRT_G, "psidot": f * SQRT_G}, 10)
    for side, f in (("lhs", 1.95), ("rhs", 1.9)):
        add(f"fig19-{side}", "hurricane", {"theta": 0.01, "psidot": f * SQRT_G}, 10)
    phd20 = eq82(3.535, 0.01)
    for name, theta, t_end in (("fig20-lhs", 0.01, 10), ("fig20-lhs-deviation", 0.01 + 0.001, 100),
                               ("fig20-rhs", 0.01 + 0.05, 10)):
        add(name, "hurricane", {"theta": theta, "phidot": phd20, "psidot": 3.535 * phd20}, t_end)
    return out


@pytest.fixture(scope="module")
def formulas():
    return _formulas()


def test_every_start_is_its_formula_to_the_last_bit(formulas):
    assert sorted(formulas) == sorted(s.name for s in STARTS)
    for s in STARTS:
        model, state, t_end, params = formulas[s.name]
        assert (s.model, s.t_end, s.params) == (model, t_end, params), s.name
        assert s.state == state, s.name
        for value in s.state.values():  # the shortest repr of the double: parses back to itself
            assert repr(float(value)) == value, (s.name, value)


def test_grids_and_events_are_the_claim_code_s():
    from verify.claims.simulations.runs import DENSE as RUNS_DENSE

    assert DENSE == RUNS_DENSE
    assert {s.name: s.n_eval for s in STARTS if s.n_eval != DENSE} == {
        "fig6-lhs": 2001, "fig6-rhs": 2001, "fig10-lhs": 10001, "fig10-rhs": 10001, "fig12": 3001}
    assert [s.name for s in STARTS if not s.events] == ["fig12"]


def test_every_simulated_panel_has_a_start():
    """Every figure with a simulation claim has starts, one per panel its claims name (LHS/RHS)."""
    from verify.claims import all_claims

    panels, simulated = {}, set()
    for c in all_claims():
        m = re.match(r"Fig\. (\d+)\b(.*)", c.source)
        if m:
            side = re.search(r"\b(LHS|RHS)\b", m.group(2))
            panels.setdefault(int(m.group(1)), set()).add(side.group(1).lower() if side else None)
            if c.method == "simulation":
                simulated.add(int(m.group(1)))
    assert simulated == set(figures_with_runs())
    panels = {f: sides for f, sides in panels.items() if f in simulated}
    for figure, sides in panels.items():
        named = {s for s in sides if s}
        assert named <= set(panel_sides(figure)), figure
        for side in named:
            assert starts_of(figure, side), (figure, side)
        if not named:
            assert [s.side for s in starts_of(figure)] == [None], figure
    for s in STARTS:
        assert s.side in SIDES + (None,)
        assert s.name.startswith(f"fig{s.figure}" + (f"-{s.side}" if s.side else "")), s.name


def test_unknown_start_names_the_allowed():
    with pytest.raises(ValueError, match="fig5-lhs"):
        start("fig5-left")


def test_registry_imports_nothing_heavy():
    code = ("import sys, verify.figure_starts; "
            "print(sorted(m for m in ('numpy', 'sympy', 'heyoka', 'matplotlib', 'mpmath') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"

"""One rule for one situation (issue 28, item 6): Figs. 10 RHS, 11 RHS and 18 RHS each say the motion
leaves at a rate the exact linear threshold calls stable, and leave only from a finite offset.  The
rule of :mod:`verify.studies.finite_offset` gives them one verdict; its negative control, each
figure's own start moved inside the offset needed, flips that verdict to erratum for all three."""
from __future__ import annotations

import pytest

from verify.claims import all_claims
from verify.claims.simulations.hurricane import _fig18_rhs_rule
from verify.claims.simulations.ring import _fig10_rhs_rule, _fig11_rhs_rule
from verify.claims.simulations.runs import all_hold
from verify.studies.finite_offset import ERRATUM, NOT_CHECKABLE, QUALIFIED, finite_offset_verdict

CASES = {"fig-10-rhs": _fig10_rhs_rule, "fig-11-rhs": _fig11_rhs_rule, "fig-18-rhs": _fig18_rhs_rule}


def _verdict(case):
    readings, stable, offset, bracket = case
    return finite_offset_verdict(stable, all_hold(readings), offset, bracket)


def test_the_three_figures_are_the_same_situation_and_get_one_verdict():
    starts = {fig: rule()[0] for fig, rule in CASES.items()}
    assert all(stable for _, stable, _, _ in starts.values()), "each rate lies on the stable side of its threshold"
    assert all(offset >= bracket[1] for _, _, offset, bracket in starts.values()), "each start lies beyond the offset"
    assert {fig: _verdict(case) for fig, case in starts.items()} == dict.fromkeys(CASES, QUALIFIED)
    verdicts = {c.id: c.evaluate().verdict for c in all_claims() if c.id in CASES}
    assert verdicts == dict.fromkeys(CASES, QUALIFIED), "the claims apply the rule"


def test_negative_control_a_start_within_the_offset_is_an_erratum_for_all_three():
    controls = {fig: rule()[1] for fig, rule in CASES.items()}
    assert all(offset <= bracket[0] for _, _, offset, bracket in controls.values())
    assert {fig: _verdict(case) for fig, case in controls.items()} == dict.fromkeys(CASES, ERRATUM)


@pytest.mark.parametrize("leaves, offset, want", [
    (True, 2.0, QUALIFIED), (False, 0.5, ERRATUM),
    (True, 0.5, NOT_CHECKABLE),  # leaves from within the bracket: the run and the bisection disagree
    (False, 2.0, NOT_CHECKABLE),  # stays from beyond it
    (None, 2.0, NOT_CHECKABLE),  # the run's two measures disagree
])
def test_rule_table(leaves, offset, want):
    assert finite_offset_verdict(True, leaves, offset, (1.0, 1.5)) == want


def test_a_linearly_unstable_rate_is_not_this_situation():
    """Fig. 19 RHS (1.9 sqrt(g/a), below the sleeping threshold) leaves by the linear instability: no rule verdict."""
    assert finite_offset_verdict(False, True, 0.01, (0.0, 0.001)) is None


def test_the_thresholds_table_applies_the_same_rule():
    """The table's verdict cell (verify.studies.summary._verdict) calls the same rule: a caption's start that
    leaves is qualified, one that stays is an erratum; a rate whose stability the caption states rightly agrees."""
    from verify.studies.summary import _verdict

    assert "qualified (the one rule)" in _verdict(False, True, 18.8, 18.6756, ("event:rim_switch", "ok"))
    assert "erratum (the one rule)" in _verdict(False, True, 18.8, 18.6756, ("ok", "ok"))
    assert _verdict(False, False, 18.0, 18.6756, ("event:rim_switch", "ok")) == "agrees"

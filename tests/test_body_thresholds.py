"""The report's table of the bodies' thresholds (verify.studies.body_thresholds): each threshold checked by the
full equations and, for the paper's bodies, by the built-in model; a wrong second route is flagged."""
import pytest

from verify.studies import body_thresholds as bt


@pytest.fixture
def only_disk(monkeypatch):
    monkeypatch.setattr(bt, "shipped", lambda: ["disk"])


def test_the_disks_thresholds_from_its_profile_are_the_built_in_ones_and_hold_on_the_full_equations(only_disk):
    table = bt.rows()
    assert [r["motion"] for r in table] == ["straight-line", "diameter-spin"]
    for r in table:
        assert r["nonlinear"]["agrees"] and r["nonlinear"]["grows"] == [True, False]  # stable above
        assert r["built_in"]["agrees"]
    assert bt.failures(table) == []


def test_a_wrong_built_in_threshold_or_a_nonlinear_run_that_disagrees_is_a_failure(only_disk, monkeypatch):
    """Negative control: the hoop's k for the disk's built-in threshold (another body: 15.65 against 18.07),
    and a nonlinear verdict flipped, each named in a failure line."""
    monkeypatch.setitem(bt.PAPER_MODELS, "disk", ("disk", {"k": "0.5"}))
    table = bt.rows()
    bad = bt.failures(table)
    assert len(bad) == 2 and all("from the built-in disk" in line for line in bad)
    table[0]["nonlinear"]["agrees"] = False
    assert any("nonlinear runs" in line for line in bt.failures(table))


def test_nineteen_digits_are_compared():
    """The built-in threshold is kept to 20 significant digits (half a unit of the 20th is its rounding): 19
    must agree, and a change in the 18th digit is caught."""
    assert bt._agree("18.0739222823012787975032385323", "18.073922282301278798")
    assert not bt._agree("18.0739222823012786975032385323", "18.073922282301278798")

"""The ring's two parameter sets: the paper's printed four digits and the exact annular cylinder.

The paper (text after Eq. 62) gives formulas for an annular cylinder with R = 7.32/2 cm,
h = 3.18/2 cm, w = 0.5 cm and prints I1 = 0.4993, I3 = 0.8727, h = 0.4344.  The model's
defaults are the formulas evaluated exactly (``models.ring.ANNULAR``); ``models.ring.PRINTED``
is the paper's numbers.  Independent routes here: the formulas redone with Python's Fraction,
Decimal rounding, the README's closed form of the straight-line threshold in mpmath, and runs.
"""
from __future__ import annotations

import json
from decimal import ROUND_HALF_EVEN, Decimal
from fractions import Fraction

import mpmath
import pytest
import sympy as sp

from models import get_model, ring
from verify.engine.single import solve


def _fraction(v) -> Fraction:
    return Fraction(str(sp.Rational(v)))


def test_annular_set_is_the_papers_formulas_evaluated_exactly():
    R, h, w = Fraction(732, 200), Fraction(318, 200), Fraction(1, 2)
    expected = {"I3": (1 + (1 - w / R) ** 2) / 2, "I1": (3 * (1 + (1 - w / R) ** 2) + (2 * h / R) ** 2) / 12,
                "h": h / R}
    assert {k: _fraction(v) for k, v in ring.ANNULAR.items()} == expected
    defaults = {p.name: _fraction(p.default) for p in get_model("ring").parameters if p.name in expected}
    assert defaults == expected  # the annular set is the model's default


@pytest.mark.parametrize("name", ["I1", "I3", "h"])
def test_annular_set_rounds_to_the_printed_set(name):
    exact = _fraction(ring.ANNULAR[name])
    value = Decimal(exact.numerator) / Decimal(exact.denominator)
    assert value.quantize(Decimal("0.0001"), rounding=ROUND_HALF_EVEN) == Decimal(ring.PRINTED[name])
    # and not by a hair: the exact value is well inside the printed value's rounding interval
    assert abs(exact - Fraction(ring.PRINTED[name])) < Fraction(45, 1000000)
    assert exact != Fraction(ring.PRINTED[name])  # the two sets really differ


def test_printed_set_reproduces_the_papers_printed_numbers():
    """cot^-1 h = 1.161 (Fig. 10), theta0 between 1.16 and 1.32 (after Eq. 62, the fast end with the
    paper's + h^2), theta0 = 1.205 at phidot0 = 25.7 (Fig. 11 RHS), each to its printed digits."""
    from models.steady import ring_theta0_limits, steady_state

    lim = ring_theta0_limits(ring.PRINTED)
    assert mpmath.nstr(lim["slow"], 4) == "1.161"
    assert mpmath.nstr(lim["slow"], 3) == "1.16"
    assert mpmath.nstr(lim["fast_as_printed"], 3) == "1.32"
    assert mpmath.nstr(mpmath.mpf(steady_state("ring", "diameter-spin", "25.7", ring.PRINTED)["theta"]), 4) == "1.205"
    # the fast end is where Eq. 62's branch goes: the root at a huge rate, printed set
    far = mpmath.mpf(steady_state("ring", "diameter-spin", "1e6", ring.PRINTED)["theta"])
    assert abs(far - lim["fast"]) < 1e-9


def test_parameter_set_accessor():
    assert ring.parameter_set("printed") == {"I1": "0.4993", "I3": "0.8727", "h": "0.4344"}
    assert ring.parameter_set("annular") == dict(ring.ANNULAR)
    got = ring.parameter_set("printed")
    got["h"] = "0.5"
    assert ring.PRINTED["h"] == "0.4344"  # a copy
    with pytest.raises(TypeError):
        ring.PRINTED["h"] = "0.5"  # read-only
    with pytest.raises(ValueError, match="allowed: annular, printed"):
        ring.parameter_set("paper")


def test_parameter_set_name():
    assert ring.parameter_set_name({}) == "annular"
    assert ring.parameter_set_name(ring.parameter_set("annular")) == "annular"
    assert ring.parameter_set_name({**ring.PRINTED, "g": "980"}) == "printed"
    assert ring.parameter_set_name({"h": "0.4344"}) is None  # printed h with annular I1, I3: neither
    assert ring.parameter_set_name({"h": "0.434426"}) is None  # a short rounding of the annular h is not it


def test_parameter_set_name_of_the_20_digit_values_a_threshold_reports():
    """threshold().params (and so a stability map's title) carries 20-digit decimals: they name their set."""
    from verify.studies.thresholds import threshold

    assert ring.parameter_set_name(threshold("ring", "straight-line").params) == "annular"
    assert ring.parameter_set_name(threshold("ring", "straight-line", ring.PRINTED).params) == "printed"


def test_runs_use_the_set_they_are_given():
    """The straight-line motion at theta = cot^-1 h is steady for the set whose h it is: started at the
    printed set's angle, the printed ring stays (to round-off) and the annular ring does not (control)."""
    th = mpmath.nstr(mpmath.acot(mpmath.mpf("0.4344")), 20)
    state = {"theta": th, "psidot": "25"}
    own = solve("ring", "1", state, ring.parameter_set("printed"), n_eval=51)
    other = solve("ring", "1", state, ring.parameter_set("annular"), n_eval=51)
    dev = lambda sol: max(abs(float(v) - float(th)) for v in sol["theta"])  # noqa: E731
    assert own.outcome == other.outcome == "ok"
    assert dev(own) < 1e-12
    assert dev(other) > 1e-6


def test_models_listing_says_where_the_defaults_come_from(capsys):
    from verify.cli import main

    assert main(["models", "--format", "json"]) == 0
    rec = {r["model"]: r for r in json.loads(capsys.readouterr().out)["models"]}["ring"]
    for name, printed in ring.PRINTED.items():
        desc = rec["parameters"][name]["description"]
        assert "annular cylinder" in desc and f"the paper prints {printed}" in desc, desc
        assert rec["parameters"][name]["default"] == str(ring.ANNULAR[name])


# --- the report's rows about the paper's ring -----------------------------------------------

def test_report_rows_about_the_papers_ring_use_the_printed_set():
    from verify.report import sections
    from verify.studies import summary

    ring_cases = [c for c in summary.THRESHOLD_CASES if c[0] == "ring"]
    assert ring_cases and all(ring.parameter_set_name(p) == "printed" for _, _, p in ring_cases)
    assert sections._params_cell({"parameter_set": "printed", "params": dict(ring.PRINTED)}) == \
        "printed: I1 = 0.4993, I3 = 0.8727, h = 0.4344"
    assert sections._params_cell({"params": {}}) == "defaults"
    assert summary.with_other_set("18.68", "18.67") == "18.68 (annular: 18.67)"
    assert summary.with_other_set("0.410", "0.410") == "0.410"


def test_ring_parameter_comparison_rows():
    from verify.report.sections import _ring_parameter_lines
    from verify.studies.summary import ring_parameter_comparison

    rows = {q["quantity"]: q for q in ring_parameter_comparison("straight-line")}
    thr = rows["linear threshold psidot0"]
    assert thr["printed"].startswith("18.6755970") and thr["annular"].startswith("18.6749710")
    assert thr["agree_digits"] == 3  # 18.68 against 18.67 at four digits
    acot = rows["theta = cot^-1 h (CM above the contact)"]
    assert mpmath.nstr(mpmath.mpf(acot["printed"]), 4) == mpmath.nstr(mpmath.mpf(acot["annular"]), 4) == "1.161"
    lines = _ring_parameter_lines([{"motion": "straight-line", "parameter_sets": list(rows.values())}])
    assert any("printed against annular" in line for line in lines)
    assert sum(line.startswith("| straight-line |") for line in lines) == len(rows)


def test_caption_and_spindown_rows_of_the_ring_are_labelled_and_carry_the_annular_value():
    from verify.report.sections import _map_lines, _spindown_lines
    from verify.studies.summary import caption_rows, spindown_rows

    caps = [c for c in caption_rows() if c["figure"] in ("Fig. 10", "Fig. 11")]
    assert len(caps) == 4 and all(c["parameter_set"] == "printed" and c["params"] == dict(ring.PRINTED) for c in caps)
    assert all("threshold (printed parameters) " in c["exact"] and "(annular: " in c["exact"] for c in caps)
    fig11 = [c for c in caps if c["figure"] == "Fig. 11"]
    assert "equilibrium 1.20543; annular: 1.20541" in fig11[1]["case"]  # the two sets part at the sixth digit
    rows = [r for r in spindown_rows() if r["model"] == "ring"]
    assert rows and all(r["parameter_set"] == "printed" and "relative_error_annular" in r for r in rows)
    assert rows[-1]["relative_error"] != rows[-1]["relative_error_annular"]
    json.dumps(caps + rows)
    text = "\n".join(_spindown_lines({"spindown": rows, "precision": []}))
    assert "| ring (printed) |" in text and "(annular: " in text
    maps = _map_lines([{"model": "ring", "motion": "straight-line", "trajectories": 1, "linear_threshold": "18.67",
                        "switch_at_tilt_1e-6": ["1", "2"], "figure": "f.png"}])
    assert any(line.startswith("| ring (annular) | straight-line |") for line in maps)  # the report's maps: defaults

"""Exact steady spin-down states (issue 4, part 2, begun) and the paper's Eqs. 45 and 61.

Independent routes: the leading-order laws derived by hand from the Taylor series of row 1
(on the centre-of-mass-at-rest family phidot^2 theta -> g/I1, on the family with no vertical
spin -> g/(h^2 + I1)); and integration: the exact state, run in quad, keeps theta constant.
"""
from __future__ import annotations

import json

import mpmath
import pytest
import sympy as sp

from models import get_model
from verify.cli import main
from verify.engine.single import solve
from verify.studies.spindown import spindown


def test_eq45_is_exact_for_the_disk_at_rest_family():
    for th in ("0.1", "1e-4", "1e-8"):
        s = spindown("disk", th)
        assert abs(s.relative_error) < mpmath.mpf(10) ** -40


def _ring_numbers():
    return {p.name: mpmath.mpf(sp.N(p.default, 40)) for p in get_model("ring").parameters}


@pytest.mark.parametrize("family,limit", [
    ("cm-at-rest", lambda p: mpmath.sqrt((1 - p["h"]) * p["I1"] / (p["h"] ** 2 + p["I1"])) - 1),
    ("zero-vertical-spin", lambda p: mpmath.sqrt(1 - p["h"]) - 1),
])
def test_eq61_error_tends_to_the_leading_order_ratio(family, limit):
    p = _ring_numbers()
    with mpmath.workdps(40):
        s = spindown("ring", "1e-8", family)
        assert abs(s.relative_error - limit(p)) < 1e-6  # next order is O(theta) = 1e-8 times O(100) coefficients


@pytest.mark.parametrize("name,family", [("disk", "zero-vertical-spin"), ("ring", "cm-at-rest"), ("ring", "zero-vertical-spin")])
def test_exact_states_are_steady_under_integration(name, family):
    s = spindown(name, "0.1", family)
    state = {"theta": "0.1", "phidot": mpmath.nstr(s.phidot, 40), "psidot": mpmath.nstr(s.psidot, 40)}
    sol = solve(name, "0.2", state, precision="quad", n_eval=11)
    assert max(abs(float(v) - 0.1) for v in sol["theta"]) < 1e-28
    assert abs(float(sol.invariants["energy"].initial) - float(s.energy)) < 1e-9 * float(s.energy)


def test_spindown_json_contract(capsys):
    assert main(["spindown", "ring", "--theta", "0.01", "--family", "zero-vertical-spin", "--format", "json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    for key in ("phidot", "psidot", "energy", "relative_error"):
        assert len(rec[key].replace("-", "").replace(".", "").lstrip("0")) >= 15
    assert rec["paper_formula"] == "Eq. 61"


@pytest.mark.parametrize("argv,message", [
    (["spindown", "hurricane", "--theta", "0.1"], "has no spin-down study"),
    (["spindown", "disk", "--theta", "2"], "outside (0, pi/2)"),
    (["spindown", "disk", "--theta", "abc"], "'abc' is not a number"),
    (["spindown", "disk", "--theta", "0.1", "--family", "spinning"], "unknown family 'spinning'"),
])
def test_spindown_bad_input(capsys, argv, message):
    assert main(argv) == 2
    assert message in capsys.readouterr().err


def test_family_quantities_scale_as_stated_in_the_report():
    """Along the disk's family with no vertical spin: |omega| ~ theta^1/2, v_CM ~ theta^3/2,
    contact speed and w2 diverge like theta^-1/2 and theta^-1, N/(Mg) -> 1; the slopes come from two
    exact states four decades apart."""
    from verify.studies.spindown import family_quantities

    a, b = (family_quantities(spindown("disk", th, "zero-vertical-spin")) for th in ("1e-4", "1e-8"))
    slope = lambda k: mpmath.log10(b[k] / a[k]) / -4  # noqa: E731  (d log q / d log theta)
    for key, expected in (("omega", 0.5), ("v_cm", 1.5), ("v_contact", -0.5), ("w2", -1)):
        assert abs(slope(key) - expected) < 1e-3, (key, slope(key))
    assert abs(b["normal_force"] - 1) < 1e-7
    rest = family_quantities(spindown("disk", "1e-6", "cm-at-rest"))
    assert rest["v_cm"] < mpmath.mpf(10) ** -40


def test_double_loses_two_digits_of_omega3_per_decade_of_theta():
    """omega3 = psidot + phidot cos(theta) ~ -phidot theta^2 on the family with no vertical spin: a
    cancellation costing 2 log10(1/theta) digits; quad, with the same loss, keeps its other digits."""
    import math

    from verify.studies.spindown import family_state, precision_runs

    for th, lost in (("1e-3", 6), ("1e-5", 10)):
        runs = {r.precision: r for r in precision_runs("test", family_state(th, "zero-vertical-spin"),
                                                       precisions=("double", "quad"), turns=2)}
        d = runs["double"]
        digits_lost = math.log10(d.omega3_error / d.omega3_scale / 2.0**-52)
        assert lost - 1.5 < digits_lost < lost + 1.5, (th, digits_lost)
        q = runs["quad"]
        assert q.omega3_error / q.omega3_scale < 1e-18

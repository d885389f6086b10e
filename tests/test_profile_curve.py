"""The ``curve`` profile kind (models.profile_curve): a convex meridian given as r(s), z(s).

An ellipse written as a curve must be the ``ellipse`` kind (a sympy identity, and a run agreeing to a bound argued
below); the egg's contact point must be its lowest point by brute force (not by the first-order condition the
module solves); bad curves are refused in one line naming the value (each rule has a curve that breaks it: the
negative controls); the egg rolls keeping its energy and Chaplygin's two integrals.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from models.bodies import body_from_mapping, load, model_of
from models.profiles import InvalidBody, contact
from models.symbols import theta
from verify.engine.single import solve

ELLIPSE_CURVE = {"kind": "curve", "r": "cos(s)/2", "z": "sin(s)", "s_min": "-pi/2", "s_max": "pi/2"}


def _body(profile, inertia=("1/4", "1/10"), **extra):
    return body_from_mapping({"name": "c", "profile": profile, "inertia": {"I1": inertia[0], "I3": inertia[1]},
                              **extra})


def test_an_ellipse_written_as_a_curve_is_the_ellipse_kind_exactly():
    curve = contact("curve", _body(ELLIPSE_CURVE).values)
    ellipse = contact("ellipse", {"a": sp.Rational(1, 2), "c": sp.Integer(1), "centre_height": sp.Integer(0)})
    assert (curve.theta_min, curve.theta_max, curve.below, curve.above) == (0, sp.pi, "axis_vertical",
                                                                            "axis_vertical")
    for a, b in ((curve.r2, ellipse.r2), (curve.r3, ellipse.r3)):
        # equal squares (an identity) and the same sign where neither vanishes: r2 < 0 on (0, pi), r3 changes sign
        # only at pi/2 for both; so the same function on the domain
        assert sp.simplify(sp.expand_trig(a ** 2 - b ** 2)) == 0
        for t in (0.3, 1.2, 2.0, 2.9):
            assert np.sign(float(a.subs(theta, t))) == np.sign(float(b.subs(theta, t)))


def test_an_ellipse_curve_rolls_as_the_prolate_ellipsoid_to_rounding():
    # the same equations in other roundings: the curve's r2 = -1/(2 sqrt(1 + 4 cot^2)) against the ellipse's
    # -a^2 sin/D with a a runtime parameter; each step differs by a few eps, carried by the flow's transition matrix
    # (row sums ~1e3 by 0.5 s, HEYOKA.md) over ~100 steps: eps sqrt(N) |Phi| = 2.2e-16 x 10 x 1e3 = 2e-12 relative;
    # 1e-11 leaves a factor 5 (the disk's identity run, tests/test_bodies.py, argues the same)
    start = {"theta": "1.1", "phidot": "2", "psidot": "8"}
    a = solve(model_of(load("prolate-ellipsoid")), "0.5", start, n_eval=9)
    b = solve(model_of(_body(ELLIPSE_CURVE)), "0.5", start, n_eval=9)
    assert a.outcome == b.outcome == "ok"
    assert np.max(np.abs(a.y - b.y) / (1 + np.abs(a.y))) < 1e-11


def test_the_eggs_contact_point_is_its_lowest_point_by_brute_force():
    """20001 points of the egg's meridian; the lowest at each tilt lies within the sampling's resolution of the
    contact formula.  Spacing h = pi/20000 = 1.6e-4 in s, speed |(r', z')| <= 1.51, curvature radius rho between
    0.375 and 1.51 (measured on the grid): the nearest sample is at most h |v| / 2 = 1.2e-4 along the curve from
    the contact, so heights agree to its square over 2 rho_min, (1.2e-4)^2 / 0.75 = 1.9e-8 (held to 1e-7) and
    positions to 2 x 1.2e-4 = 2.4e-4 (held to 1e-3)."""
    body = load("egg")
    c = contact(body.kind, body.values)
    s = sp.Symbol("s", real=True)
    rz = sp.lambdify(s, [body.values["r"], body.values["z"]], "numpy")
    grid = np.linspace(0, math.pi, 20001)
    rho, zeta = rz(grid)
    for th in (0.05, 0.7, 1.5708, 2.4, 3.1):
        heights = -rho * math.sin(th) + zeta * math.cos(th)
        j = int(np.argmin(heights))
        r2, r3 = (float(e.subs(theta, th)) for e in (c.r2, c.r3))
        assert heights[j] == pytest.approx(r2 * math.sin(th) + r3 * math.cos(th), abs=1e-7), th
        assert math.hypot(rho[j] + r2, zeta[j] - r3) < 1e-3, th


def test_the_egg_rolls_keeping_energy_and_chaplygins_integrals():
    body = load("egg")
    model = model_of(body)
    assert model.chaplygin is not None and [i.name for i in model.invariants] == ["energy"]
    sol = solve(model, "2", {"theta": "1.4", "phidot": "10"}, n_eval=21)
    assert sol.outcome == "ok" and sol.steps > 50
    for name in ("energy", "chaplygin_1", "chaplygin_2"):
        # each step commits about eps of the invariant's term scale (the Taylor tolerance) plus a few roundings of
        # its terms: 16 eps a step at most, adding like a random walk over the steps, a factor 4 to spare (the
        # Routh sphere's bound, tests/test_bodies.py); Chaplygin's are transported at >= 10 more bits
        # (verify.engine.chaplygin), so their evaluation adds less than one eps
        drift = sol.invariants[name].max_drift_vs_terms
        assert drift <= 64 * 2.0 ** -52 * math.sqrt(sol.steps), (name, drift)


@pytest.mark.parametrize("change, words", [
    ({"r": "cos(s)/2", "z": "sin(s) + 2"}, "centre of mass is not inside"),  # C below the bottom pole
    # the support function 1 + cos(2s)/2 has radius of curvature 1 - 3 cos(2s)/2 < 0 near the poles: cusps
    ({"r": "(1 + cos(2*s)/2)*sin(s) - sin(2*s)*cos(s)", "z": "-(1 + cos(2*s)/2)*cos(s) - sin(2*s)*sin(s)",
      "s_min": "0", "s_max": "pi"}, "not convex"),
    ({"r": "cos(s)/2", "z": "sin(s)", "s_min": "pi/2", "s_max": "-pi/2"}, "s_min < s_max"),
    ({"r": "-cos(s)/2"}, "not convex"),  # on the wrong side of the axis: its normal turns the other way
    ({"r": "cos(s)/3"}, "round to double"),  # heyoka would round 1/3
    ({"r": "cos(s)/2 + s**2/64"}, "no closed form"),  # s mixed with functions of s
    ({"r": "__import__('os')"}, "the call"),
    ({"r": "s.real"}, "not allowed"),
    ({"r": "cos(s)**99"}, "integer exponent of at most 8"),
    ({"r": "foo(s)"}, "the call 'foo(s)'"),
    ({"r": "cos(t)"}, "the name 't'"),
    ({"r": "1e999*cos(s)"}, "too long"),
    ({"r": "cos(s"}, "not an expression"),
    ({"r": 1}, "as a string of s"),
    ({"s_max": "s"}, "not a number"),
])
def test_bad_curves_are_refused_naming_the_value(change, words):
    with pytest.raises(InvalidBody, match=words.replace("(", "\\(").replace(")", "\\)").replace("*", "\\*")):
        _body({**ELLIPSE_CURVE, **change})


def test_a_half_curve_stops_at_its_corner_and_a_domain_past_it_is_refused():
    """The ellipse's lower half (s in (-pi/2, 0)) ends at the equator, where its normal is horizontal: the contact
    reaches the edge at theta = pi/2 (``curve_end``), and a file domain beyond it is refused."""
    half = {**ELLIPSE_CURVE, "s_max": "0"}
    c = contact("curve", _body(half).values)
    assert (c.theta_min, c.theta_max, c.above) == (0, sp.pi / 2, "curve_end")
    with pytest.raises(InvalidBody, match="domain"):
        _body(half, domain={"theta_max": "2"})
    assert _body(half, domain={"theta_max": "3/2"}).theta_max == sp.Rational(3, 2)

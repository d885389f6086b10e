"""Exact solutions the paper names, integrated by the derived equations.

The initial states come from the paper's own conditions (Eqs. 21, 45, 72 and the
knife-edge motions after Eq. 18), evaluated at 40 digits; the check is that the
integrated motion stays on them.  Bound in double: 100 eps sqrt(N) times the largest rate
(for the rates, times the rate itself).  Why: these steady motions are neutrally stable, so
theta and the rates carry their local round-off (eps per step, random-walking) and are not
amplified like the full state, whose transition norm |Phi(1, 0)| (48 to 4e4 here, dominated
by the secular growth of phi and x) is not what is checked.  Measured: theta moves at most
0.15 and the rates at most 5.4 of eps sqrt(N) rate, so 100 leaves a margin of about 20.
Quad runs must keep theta to 1e-28 (the issue's quad bound; measured deviations are 0 at
double resolution).
"""
from __future__ import annotations

import math

import mpmath
import pytest

from verify import solve

G, K = 980, mpmath.mpf(1) / 4
DIGITS = mpmath.workdps(40)  # local to these helpers: the global mpmath precision is not touched


@DIGITS
def s(x):
    return mpmath.nstr(x, 38)


@DIGITS
def circular_disk(theta, phidot):
    """Eq. 21, last line, solved for psidot (I1 = k, I3 = 2k)."""
    c, sn = mpmath.cos(theta), mpmath.sin(theta)
    psidot = (-G * c / (phidot * sn) - (1 + K) * phidot * c) / (1 + 2 * K)
    return {"theta": s(theta), "phidot": s(phidot), "psidot": s(psidot)}


@DIGITS
def steady_hurricane(phidot):
    """Eq. 72: cos(theta) = 2/5 - g/phidot^2 with psidot = phidot (CM at rest)."""
    return {"theta": s(mpmath.acos(mpmath.mpf(2) / 5 - G / phidot**2)), "phidot": s(phidot), "psidot": s(phidot)}


@DIGITS
def spin_down_disk(theta):
    """Eq. 45: phidot = sqrt(g/(k sin theta)), psidot = -phidot cos(theta) (CM at rest)."""
    phidot = mpmath.sqrt(G / (K * mpmath.sin(theta)))
    return {"theta": s(theta), "phidot": s(phidot), "psidot": s(-phidot * mpmath.cos(theta))}


with DIGITS:  # the parameters below are read at 40 digits too
    HALF_PI = mpmath.pi / 2
    CASES = {
        "straight line (theta = pi/2, phidot = 0)": ("disk", {"theta": s(HALF_PI), "psidot": "20"}),
        "diameter spin (theta = pi/2, psidot = 0)": ("disk", {"theta": s(HALF_PI), "phidot": "80"}),
        "Eq. 21 circle, theta = 1.3": ("disk", circular_disk(mpmath.mpf("1.3"), mpmath.mpf(5))),
        "Eq. 21 circle, theta = 1.8": ("disk", circular_disk(mpmath.mpf("1.8"), mpmath.mpf(-5))),
        "Eq. 72 precession, phidot^2 = 25 g": ("hurricane", steady_hurricane(mpmath.sqrt(25 * G))),
        "Eq. 45 spin-down, theta = 0.5": ("disk", spin_down_disk(mpmath.mpf("0.5"))),
        "Eq. 45 spin-down, theta = 0.01": ("disk", spin_down_disk(mpmath.mpf("0.01"))),
    }


def _check(sol, state, bound):
    th0 = float(state["theta"])
    rates = [float(state.get(n, 0)) for n in ("phidot", "psidot")]
    dev = max(abs(float(v) - th0) for v in sol["theta"])
    assert dev <= bound, f"theta moved by {dev:.3e} > {bound:.3e}"
    for name, r in zip(("phidot", "psidot"), rates):
        moved = max(abs(float(v) - r) for v in sol[name])
        assert moved <= bound * max(1.0, abs(r)), f"{name} moved by {moved:.3e}"


@pytest.mark.parametrize("label", sorted(CASES))
def test_exact_solution_in_double(label):
    model, state = CASES[label]
    sol = solve(model, "1", state, precision="double", n_eval=101)
    assert sol.outcome == "ok"
    rate = max(1.0, *(abs(float(state.get(n, 0))) for n in ("phidot", "psidot")))
    _check(sol, state, 100 * sol.precision.eps * math.sqrt(sol.steps) * rate)


@pytest.mark.parametrize("label", ["Eq. 45 spin-down, theta = 0.01", "Eq. 72 precession, phidot^2 = 25 g",
                                   "Eq. 21 circle, theta = 1.3"])
def test_exact_solution_in_quad(label):
    model, state = CASES[label]
    sol = solve(model, "1", state, precision="quad", n_eval=21)
    _check(sol, state, 1e-28)


def test_centre_of_mass_motion_of_exact_solutions():
    # straight line: v_C = -omega x r_P = -psidot e1, e1 = x at phi = 0
    sol = solve("disk", "2", CASES["straight line (theta = pi/2, phidot = 0)"][1], precision="quad", n_eval=3)
    assert abs(float(sol["x"][-1]) + 40.0) < 1e-28 and abs(float(sol["y"][-1])) < 1e-28
    # Eq. 45 and Eq. 72 states have the centre of mass at rest
    for label in ("Eq. 45 spin-down, theta = 0.01", "Eq. 72 precession, phidot^2 = 25 g"):
        model, state = CASES[label]
        sol = solve(model, "1", state, precision="quad", n_eval=11)
        assert max(abs(float(v)) for v in sol["x"]) < 1e-28, label


def test_a_wrong_steady_state_is_not_steady():
    """Negative control: Eq. 45 with k -> 1.01 k is not a steady motion of the disk."""
    wrong = spin_down_disk(mpmath.mpf("0.5"))
    with DIGITS:
        wrong["phidot"] = s(mpmath.mpf(wrong["phidot"]) / mpmath.sqrt(mpmath.mpf("1.01")))
    sol = solve("disk", "1", wrong, precision="double", n_eval=101)
    with pytest.raises(AssertionError):
        _check(sol, wrong, 100 * sol.precision.eps * math.sqrt(sol.steps) * 300)

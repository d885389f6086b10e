"""The measures behind the simulation verdicts (verify/circling.py, verify/behaviour.py).

Each measure is run on synthetic paths whose answer is known by construction, with a
negative control that must flip its reading: a measure that cannot say 'no' (or 'yes')
decides nothing.  Then one physical control: the mirror image of a run reverses the sense.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from verify.behaviour import both_sides, leaves, one_side, oscillates, spirals_out
from verify.circling import circling, epicycle, running_mean, theta_maxima

T = np.linspace(0.0, 20.0, 40001)


@pytest.mark.parametrize("guide, loops", [(0.8, -40.0), (-0.8, -40.0), (0.8, 40.0), (-0.8, 40.0)])
def test_slow_path_sense_is_the_guide_not_the_loops(guide, loops):
    """Loops in either sense on a guide circle in either sense: both measures read the guide."""
    x, y, th = epicycle(T, guide, loops)
    c = circling(T, x, y, th)
    expected = guide * T[-1] / (2 * math.pi)
    assert c.agree and c.sign == int(np.sign(guide))
    for s in (c.strobe, c.mean):
        assert s.turns == pytest.approx(expected, rel=0.02)


def test_raw_path_turning_reads_the_loops_negative_control():
    """The old measure (total turning of the raw path) follows the loops: it gets the guide wrong here."""
    x, y, th = epicycle(T, 0.8, -40.0)
    direction = np.unwrap(np.arctan2(np.diff(y), np.diff(x)))
    assert direction[-1] - direction[0] < 0  # clockwise loops
    assert circling(T, x, y, th).sign == +1  # counter-clockwise guide


def test_a_drift_without_circling_decides_nothing():
    x = 0.01 * T + 0.3 * np.cos(40 * T)
    y = 0.3 * np.sin(40 * T)
    th = 0.1 + 0.01 * np.cos(40 * T)
    c = circling(T, x, y, th)
    assert c.sign == 0 and not c.agree


def test_aliased_samples_give_no_stroboscopic_sense():
    """A circle traversed at 0.57 turn per nutation would look backwards if sampled once per nutation."""
    nut = 2 * math.pi / 0.285
    x, y = np.cos(2 * math.pi * 0.57 / 0.285 * T), np.sin(2 * math.pi * 0.57 / 0.285 * T)
    th = 0.1 + 0.01 * np.cos(nut * T)
    c = circling(T, x, y, th)
    assert math.isnan(c.strobe.turns) and c.sign == 0
    # for a whole path, the orbit is then the path's own circling (counter-clockwise here)
    whole = circling(T, x, y, th, whole_path=True)
    assert whole.agree and whole.sign == +1 and whole.strobe.turns == pytest.approx(0.57 / 0.285 * 20, rel=0.01)
    mirrored = circling(T, x, -y, th, whole_path=True)
    assert mirrored.agree and mirrored.sign == -1


def test_no_nutation_reads_the_path_itself():
    x, y = np.cos(-2.0 * T), np.sin(-2.0 * T)
    c = circling(T, x, y, np.full_like(T, 0.3))
    assert c.agree and c.sign == -1 and math.isnan(c.nutation_period)


def test_theta_maxima_are_refined_between_grid_points():
    t = np.linspace(0, 10, 1001)
    marks = theta_maxima(t, np.cos(2 * math.pi * 0.73 * t))
    assert np.allclose(np.diff(marks), 1 / 0.73, atol=1e-4)


def test_running_mean_removes_one_period_exactly():
    t = np.linspace(0, 10, 10001)
    centre, m = running_mean(t, 2.0 + np.sin(2 * math.pi * t), 1.0)
    assert np.max(np.abs(m - 2.0)) < 1e-5


def test_sides_of_a_level_and_its_negative_control():
    t = np.linspace(0, 10, 2001)
    straddling = 0.05 * np.sin(3 * t)
    one_sided = 0.1 + 0.05 * np.sin(3 * t)
    assert both_sides(t, straddling, 0.0).holds is True and one_side(t, straddling, 0.0).holds is False
    assert both_sides(t, one_sided, 0.0).holds is False and one_side(t, one_sided, 0.0).holds is True


def test_measures_that_disagree_give_no_verdict():
    """One brief dip below the level: two sign changes but 0.5% of the time below -> undecided."""
    t = np.linspace(0, 10, 20001)
    v = np.where(np.abs(t - 5) < 0.025, -0.01, 0.1)
    r = both_sides(t, v, 0.0)
    assert r.first[2] is True and r.second[2] is False and r.holds is None


def test_oscillation_bounded_and_growing():
    t = np.linspace(0, 10, 4001)
    assert oscillates(t, 0.3 + 0.01 * np.sin(5 * t), True).holds is True
    growing = oscillates(t, 0.3 + 0.01 * np.exp(0.5 * t) * np.sin(5 * t), True)
    assert growing.first[2] is True and growing.second[2] is False and growing.holds is None  # turns back, unbounded
    assert oscillates(t, 0.3 + 0.1 * t, True).holds is False  # runs away without turning back
    assert oscillates(t, 0.3 + 0.01 * np.sin(5 * t), False).holds is False  # a stopped run does not oscillate


def test_leaving_by_event_and_by_grid():
    t = np.linspace(0, 5, 501)
    rising = 1.2 + 0.2 * t
    assert leaves("event:rim_switch", "rim_switch", 1.85, t, rising, math.pi / 2).holds is True
    assert leaves("ok", "rim_switch", 5.0, t, np.full_like(t, 1.2), math.pi / 2).holds is False
    # an event the free run does not confirm: the measures disagree
    assert leaves("event:rim_switch", "rim_switch", 1.0, t, np.full_like(t, 1.2), math.pi / 2).holds is None


def test_spiral_out_against_circle_and_straight_line():
    t = np.linspace(0, 10, 10001)
    r = 0.01 * np.exp(0.4 * t)
    assert spirals_out(t, r * np.cos(6 * t) - r[0], r * np.sin(6 * t)).holds is True
    assert spirals_out(t, np.cos(6 * t) - 1, np.sin(6 * t)).holds is False  # circles, does not recede
    line = spirals_out(t, 0.01 * np.exp(0.4 * t), np.zeros_like(t))
    assert line.first[2] is True and line.second[2] is False  # recedes without turning: not a spiral


def test_mirror_image_reverses_the_slow_sense():
    """Physical control: the ring's run and its mirror image (phidot, psidot -> -phidot, -psidot)."""
    from verify.claims.simulations import ring as S

    r = S._fig9_runs()
    for side in ("LHS", "RHS"):
        a, b = S._sense(r[side]), S._sense(r[side + " mirror"])
        assert a.agree and b.agree and a.sign == -b.sign
    assert S._sense(r["LHS"]).sign == -S._sense(r["RHS"]).sign  # +-1% reverse the slow sense

"""The terminal event ``slips``: where a rolling motion needs more friction than a given coefficient.

The event is located by heyoka on (F_h/(Mg mu))^2 - (N/(Mg))^2 (``verify.engine.compile``).  The
checks here come from elsewhere: the friction cfunc (mu_req = |F_h|/N, written apart from the event)
evaluated on a run *without* the event, at a higher precision, at the event time the run with it
reports; and the runs' own records.  A deliberately wrong event function must fail the same check.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

import heyoka as hy
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import ACCELERATIONS
from verify.engine import compile as comp
from verify.engine import validation
from verify.engine.conditioning import transition_norms
from verify.engine.problem import problem
from verify.engine.single import propagate, solve
from verify.precision import parse_precision

START = dict(theta="1.3", phi="0.3", psi="-0.7", thetadot="0.5", phidot="3", psidot="20")
HIGHER = {"double": "quad", "long": "quad", "quad": "mp:192"}


def slip_mismatch_in_eps(sol, mu: str, referee: str) -> float:
    """|mu_req - mu| / (mu eps) at the run's event time, mu_req from a run without the event at ``referee``.

    The referee integrates the same start without friction to the reported event time (read
    exactly at the higher precision), and evaluates mu_req there with the friction cfunc: an
    independent route to the friction the motion needs at that instant.
    """
    t_event = sol.t_events["slips"]
    ref = solve(sol.model, parse_precision(referee).number(str(t_event)), START,
                precision=referee, n_eval=2)
    need = ref.friction_required[-1]
    eps = sol.precision.eps
    return float(abs(need - parse_precision(referee).number(mu)) / parse_precision(referee).number(mu)) / eps


def bound_in_eps(sol) -> float:
    # The state at the event carries the integration's error, tol = eps per step relative, over
    # sol.steps steps; the event's root is found to the rounding of its function (a few eps on each
    # square, their difference conditioned by ~1 at a crossing where both are ~1); the cfunc adds
    # its own rounding.  8 eps per step (plus one) covers these with room; measured 0.07-4.7 eps
    # (double, long, quad; mu = 0.3 and 0.5, 4 and 9 steps).  This holds for a well-conditioned start
    # only: near an unstable motion (a disk spun about its upright diameter) the dynamics amplify the
    # state's error, and the sweeps' tests measure hundreds of eps (tests/test_sweep_friction.py).
    return 8.0 * (1 + sol.steps)


@pytest.mark.parametrize("precision", ["double", "long", "quad"])
@pytest.mark.parametrize("mu", ["0.3", "0.5"])
def test_slip_time_agrees_with_the_friction_needed_at_a_higher_precision(precision, mu):
    sol = solve("disk", 2, START, precision=precision, friction=mu)
    assert sol.outcome == "event:slips" and sol.status == 1
    assert float(sol.t_events["slips"]) == float(sol.t[-1])
    mismatch = slip_mismatch_in_eps(sol, mu, HIGHER[precision])
    assert mismatch <= bound_in_eps(sol), (mismatch, sol.steps)


ROLLING_STARTS = {
    "ring": dict(theta="1.2", thetadot="0.5", phidot="3", psidot="15"),
    "hurricane": dict(theta="0.8", thetadot="1", phidot="10", psidot="5"),  # needs 0.287 rising to 0.317
    "disk+moffatt": dict(theta="1.2", thetadot="0.5", phidot="3", psidot="15"),
}


@pytest.mark.parametrize("name", sorted(ROLLING_STARTS))
def test_other_rolling_models_slip_where_they_need_the_coefficient(name):
    model = get_model(name)
    start = ROLLING_STARTS[name]
    plain = solve(model, 1, start)
    top = float(np.nanmax(plain.friction_required))
    assert top > 1.01 * float(plain.friction_required[0]), "the start must need more friction later"
    mu = str(0.5 * (float(plain.friction_required[0]) + top))  # between the start's need and the run's largest
    sol = solve(model, 1, start, friction=mu)
    assert sol.outcome == "event:slips"
    assert abs(float(sol.friction_required[-1]) / float(mu) - 1) <= bound_in_eps(sol) * sol.precision.eps
    assert np.all(sol.friction_required[:-1] < float(mu))


#: Starts that roll well within any coefficient: this file's START, and one whose plain and limited errors
#: differ the most of six measured (8x apart on the compact branch, with either larger on other starts).
QUIET_STARTS = {"start": START,
                "steeper": dict(theta="1.1", phi="0.3", psi="-0.7", thetadot="0.3", phidot="4", psidot="16")}
GRID = np.linspace(0, 10, 11)


@lru_cache(maxsize=None)
def quad_and_conditioning(start: str) -> tuple:
    """(the quad run of QUIET_STARTS[start] on GRID as doubles, |Phi(t, 0)| at GRID[1:], non-decreasing)."""
    quad = solve("disk", 10, QUIET_STARTS[start], t_eval=GRID, precision="quad").y.astype(float)
    phi = np.maximum.accumulate(transition_norms("disk", GRID[1:], QUIET_STARTS[start]))
    return quad, phi


def error_over_bound(sol, start: str) -> float:
    """max over t in GRID[1:] of |y(t) - y_quad(t)| / (eps sqrt(steps) |Phi(t, 0)| max|y|) (max norms).

    The bound of tests/test_precision.py: every step commits a local error of at most eps |y| (tol = eps,
    relative to the state's max norm, which grows with the angles: max|y| over the run, 346 for START),
    errors of independent sign add like sqrt(steps), and the flow carries each by at most |Phi(t, 0)|
    (taken non-decreasing in t, so an error made at any earlier time is covered).  Quad's own error is
    ~1e-17 of this.  A worst case: the runs below measure 0.0002 to 0.0016 of it.
    """
    quad, phi = quad_and_conditioning(start)
    bound = sol.precision.eps * np.sqrt(sol.steps) * phi * np.abs(quad).max()
    return float((np.abs(sol.y - quad).max(axis=0)[1:] / bound).max())


@pytest.mark.parametrize("start", sorted(QUIET_STARTS))
def test_a_run_that_never_needs_the_coefficient_is_as_accurate_as_one_without_it(start):
    """Each run -- without the coefficient, and with one it never needs (1e6, 1e9) -- within the conditioning
    bound of the quad run at every time.  Not one run's error against the other's: the slip event enters
    heyoka's step-size rule (its Taylor coefficients count with the state's), so the steps part at the
    ulp level after a few steps (1741 and 1742 over 10 s) and the two errors are two draws of the same
    rounding noise amplified by |Phi| ~ 1e4: measured on six starts, limited/plain from 0.2 to 8 (main's
    uncompacted forms: 0.2 to 1.7), none better or worse by start.  Measured here: 0.0002 to 0.0016 of
    the bound, plain and limited alike."""
    plain = solve("disk", 10, QUIET_STARTS[start], t_eval=GRID)
    assert plain.outcome == "ok"
    assert error_over_bound(plain, start) <= 1
    for mu in ("1e6", "1e9"):
        limited = solve("disk", 10, QUIET_STARTS[start], t_eval=GRID, friction=mu)
        assert limited.outcome == "ok" and limited.friction == float(mu)
        assert error_over_bound(limited, start) <= 1, mu


def test_negative_control_a_coefficient_that_takes_over_the_step_size_fails_the_accuracy_check():
    """The event written as friction - mu_req (the naive form) has the coefficient's size, 1e9, and no
    more in its derivatives: heyoka's step size, relative to the largest magnitude among the state and
    the events, then grows (772 steps where the right event takes 1742) and the run loses accuracy that
    the bound above sees: measured 44 times the bound (1e-6 against the quad run, where the right event's
    run is 3e-11).  (At 1e6 the same naive event costs 35 times the accuracy, 1089 steps, but stays at
    0.018 of this worst-case bound: the check sees losses of a few hundred times and more.)"""
    model = get_model("disk")
    prec = parse_precision("double")
    right = comp.compile_with_friction(model, prec)
    fx, fy = (a / comp.g for a in model.horizontal_acceleration)
    naive = comp.FRICTION - sp.sqrt(fx ** 2 + fy ** 2) / comp.contact_event_function(model)
    mapping = comp.symbol_map(model, right.variables)
    mapping[comp.FRICTION] = hy.par[len(model.parameters)]
    mapping.update(zip(ACCELERATIONS, [rhs for _, rhs in right.system[3:6]]))
    naive_event = ("slips", comp.to_heyoka(naive, mapping, compact=True), hy.event_direction.negative)
    mislabelled = replace(model, name="disk-with-a-naive-slip-event")  # its own integrator template
    p = problem(mislabelled, START, friction="1e9")
    p.__dict__["compiled"] = replace(right, model=mislabelled, events=right.events[:-1] + (naive_event,))
    sol = propagate(p, prec.number(10), GRID)
    assert sol.outcome == "ok"  # it never fires either: only its accuracy differs
    assert error_over_bound(sol, "start") > 10


def test_a_start_that_already_slips_is_refused_naming_its_need():
    with pytest.raises(validation.InvalidStart, match=r"mu_req = \|F_h\|/N = 0\.2307") as err:
        solve("disk", 2, START, friction="0.2")
    assert err.value.reason == "slips"


@pytest.mark.parametrize("bad, words", [
    ("0", "positive finite"), ("-1", "positive finite"), ("nan", "not a finite"),
])
def test_bad_coefficients_are_named(bad, words):
    with pytest.raises(ValueError, match=words):
        solve("disk", 2, START, friction=bad)


def test_friction_needs_a_rolling_contact_and_events():
    with pytest.raises(ValueError, match="no rolling contact"):
        solve("sliding-disk", 1, dict(theta=1.2), friction="0.5")
    with pytest.raises(ValueError, match="events=False"):
        solve("disk", 1, START, friction="0.5", events=False)


def test_negative_control_a_wrong_event_function_fails_the_check():
    """mu not squared: the event then lands where mu_req^2 = mu, and the referee sees it."""
    model = get_model("disk")
    prec = parse_precision("double")
    right = comp.compile_with_friction(model, prec)
    fx, fy = (a / comp.g for a in model.horizontal_acceleration)
    wrong_f = (fx ** 2 + fy ** 2) / comp.FRICTION - comp.contact_event_function(model) ** 2
    mapping = comp.symbol_map(model, right.variables)
    mapping[comp.FRICTION] = hy.par[len(model.parameters)]
    mapping.update(zip(ACCELERATIONS, [rhs for _, rhs in right.system[3:6]]))
    wrong_event = ("slips", comp.to_heyoka(wrong_f, mapping, compact=True), hy.event_direction.positive)
    mislabelled = replace(model, name="disk-with-a-wrong-slip-event")  # its own integrator template
    wrong = replace(right, model=mislabelled, events=right.events[:-1] + (wrong_event,))
    p = problem(mislabelled, START, friction="0.3")
    p.__dict__["compiled"] = wrong  # cached_property: the problem now integrates the wrong event
    sol = propagate(p, prec.number(2), np.array([0.0, 2.0]))
    assert sol.outcome == "event:slips"
    mismatch = slip_mismatch_in_eps(replace(sol, model="disk"), "0.3", "quad")
    assert mismatch > 1e6 * bound_in_eps(sol)

"""The friction a rolling motion needs: mu_req = |F_h| / N (paper Eq. 6, F = M (a_C + g Z)).

* on steady motions the horizontal contact force is the centripetal force of the centre of
  mass's circle, M phidot^2 r_C = M |phidot| |v_C| (the configuration turns rigidly about the
  vertical at phidot, so C moves on a circle at speed |v_C| with angular rate phidot), derived
  here from the state and the no-slip velocity, not from a_C; zero on the disk's diameter spin
  and on every straight line;
* negative controls: away from a steady motion the centripetal formula fails, and the rolling
  formula fed the frictionless sliding disk's accelerations does not vanish;
* the API evaluates it lazily, in the run's precision; the CLI's JSON carries its maximum.
"""
from __future__ import annotations

import json
import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.steady import exact_parameters, steady_state
from models.symbols import ACCELERATIONS, STATE, g, phi, phidot, psi, psidot, theta, thetadot
from verify import solve
from verify.cli import main
from verify.engine import invariants
from verify.engine.compile import compile_model
from verify.precision import parse_precision

DPS = 40


def _at(model, expr, state: dict):
    """``expr`` at ``state`` (symbol -> mpf) and the default parameters, at DPS digits."""
    pars = exact_parameters(model, {})
    f = sp.lambdify(list(STATE) + list(pars), expr, "mpmath")
    with mpmath.workdps(DPS):
        return f(*[state.get(s, mpmath.mpf(0)) for s in STATE], *[mpmath.mpf(sp.N(v, DPS)) for v in pars.values()])


def _disk_circle(tilt, rate):
    """The disk rolling steadily on a circle, tilted at theta = ``tilt`` with phidot = ``rate``: thetaddot = 0
    (row 1 of the derived equations at thetadot = 0) is linear in psidot, solved exactly."""
    model = get_model("disk")
    row1 = model.accelerations[0].subs({thetadot: 0, theta: tilt, phidot: rate}).subs(exact_parameters(model, {}))
    (spin,) = sp.solve(sp.numer(sp.together(row1)), psidot)
    return {"theta": str(sp.N(tilt, DPS)), "phidot": str(sp.N(rate, DPS)), "psidot": str(sp.N(spin, DPS))}


def _steady(name, motion, rate, tilt=0):
    s = _disk_circle(sp.Rational(6, 5), sp.Integer(rate)) if motion == "circle" else steady_state(name, motion, rate, {})
    with mpmath.workdps(DPS):
        return {theta: mpmath.mpf(s["theta"]) + tilt, phidot: mpmath.mpf(s["phidot"]), psidot: mpmath.mpf(s["psidot"]),
                phi: mpmath.mpf("0.7")}  # phi: any heading; the check is in the fixed frame


def _centripetal(model, state):
    """|phidot| |v_C| / g and v_C (horizontal), from the no-slip velocity of C."""
    vx, vy = (_at(model, v, state) for v in model.velocity_xy)
    gv = _at(model, g, state)
    with mpmath.workdps(DPS):
        return abs(state[phidot]) * mpmath.sqrt(vx**2 + vy**2) / gv, (vx, vy)


STEADY = [
    ("disk", "diameter-spin", "7", True),   # C at rest: F_h = 0
    ("disk", "straight-line", "9", True),   # C on a straight line at constant speed: F_h = 0
    ("ring", "straight-line", "9", True),
    ("ring", "diameter-spin", "9", False),  # C on a small circle (phidot |v_C| / g = 8.4e-4)
    ("hurricane", "precession", "40", True),  # C, where the balls touch, stays on the vertical: F_h = 0
    ("disk", "circle", "3", False),  # tilted at 1.2 rad: C at 84 R/s on a circle of radius 28 R, mu_req = 0.26
]


@pytest.mark.parametrize("name,motion,rate,zero", STEADY)
def test_steady_motion_needs_the_centripetal_force(name, motion, rate, zero):
    model = get_model(name)
    state = _steady(name, motion, rate)
    fx, fy = (_at(model, f, state) for f in model.horizontal_force)
    expected, (vx, vy) = _centripetal(model, state)
    with mpmath.workdps(DPS):
        size = mpmath.sqrt(fx**2 + fy**2)
        assert abs(_at(model, model.normal_force, state) - 1) < mpmath.mpf(10) ** (5 - DPS)  # steady: N = M g
        assert abs(size - expected) <= mpmath.mpf(10) ** (5 - DPS) * (1 + expected)
        assert abs(fx * vx + fy * vy) <= mpmath.mpf(10) ** (5 - DPS) * (1 + expected * mpmath.sqrt(vx**2 + vy**2))
        if zero is True:
            assert expected == 0 or expected < mpmath.mpf(10) ** (5 - DPS)
        elif zero is False:
            assert expected > mpmath.mpf("1e-4")  # a real circle, so the check is not 0 = 0
        # wiring only (the definition |F_h| / N, not an independent route)
        mu = _at(model, model.friction_required, state)
        assert abs(mu - size / _at(model, model.normal_force, state)) <= mpmath.mpf(10) ** (5 - DPS) * (1 + size)


@pytest.mark.parametrize("name", ["disk", "ring", "hurricane"])
def test_horizontal_force_is_the_time_derivative_of_the_cm_velocity(name):
    """Away from any steady motion (all three accelerations nonzero): F_h / (M g) = (d v_C / dt) / g,
    d v_C / dt by the chain rule on the no-slip velocity of C (angles moved by the rates, rates by
    the model's own accelerations) -- a route that never forms a_C from the vectors."""
    model = get_model(name)
    q, qd = (theta, phi, psi), (thetadot, phidot, psidot)
    acc = dict(zip(ACCELERATIONS, model.accelerations))
    state = {theta: mpmath.mpf("1.1"), phi: mpmath.mpf("0.7"), psi: mpmath.mpf("0.3"), thetadot: mpmath.mpf("0.9"),
             phidot: mpmath.mpf("2.3"), psidot: mpmath.mpf("-4.1")}
    for v, f in zip(model.velocity_xy, model.horizontal_force):
        dv = sum(sp.diff(v, a) * b for a, b in zip(q, qd)) + sum(sp.diff(v, b) * acc[a2] for b, a2 in zip(qd, ACCELERATIONS))
        with mpmath.workdps(DPS):
            expected = _at(model, dv / g, state)
            got = _at(model, f, state)
            assert abs(expected) > mpmath.mpf("1e-3")  # not 0 = 0
            assert abs(got - expected) <= mpmath.mpf(10) ** (5 - DPS) * (1 + abs(expected))


def test_centripetal_check_fails_off_a_steady_motion():
    """Negative control: tilted off the disk's circle, F_h is no longer phidot |v_C|."""
    model = get_model("disk")
    state = _steady("disk", "circle", "3", tilt=mpmath.mpf("0.05"))
    fx, fy = (_at(model, f, state) for f in model.horizontal_force)
    expected, _ = _centripetal(model, state)
    with mpmath.workdps(DPS):
        assert abs(mpmath.sqrt(fx**2 + fy**2) - expected) > mpmath.mpf("1e-3") * expected


def test_sliding_accelerations_in_the_rolling_formula_do_not_vanish():
    """Negative control: the rolling a_C fed the frictionless disk's accelerations asks for friction."""
    rolling, sliding = get_model("disk"), get_model("sliding-disk")
    assert sliding.horizontal_acceleration is None and sliding.friction_required is None
    assert rolling.parameter_names == sliding.parameter_names
    on_sliding = dict(zip(ACCELERATIONS, sliding.accelerations))
    with mpmath.workdps(DPS):
        state = {theta: mpmath.mpf("1.2"), phidot: mpmath.mpf(3), psidot: mpmath.mpf(5), thetadot: mpmath.mpf("0.5")}
    rolled = [_at(rolling, f, state) for f in rolling.horizontal_force]
    slid = [_at(rolling, a.subs(on_sliding) / g, state) for a in rolling.horizontal_acceleration]
    with mpmath.workdps(DPS):
        assert mpmath.sqrt(sum((a - b) ** 2 for a, b in zip(rolled, slid))) > mpmath.mpf("0.01")
        assert mpmath.sqrt(sum(b**2 for b in slid)) > mpmath.mpf("0.01")


@pytest.mark.parametrize("name", ["sliding-disk", "gyroscope", "effective"])
def test_no_rolling_contact_no_friction(name):
    assert get_model(name).horizontal_acceleration is None
    sol = solve(name, "0.1", {"theta": "1.2", "phidot": "3", "psidot": "3"})
    assert sol.friction_required is None


def test_api_on_a_steady_motion_matches_the_centripetal_force():
    model = get_model("disk")
    s = _disk_circle(sp.Rational(6, 5), sp.Integer(3))
    sol = solve("disk", "0.05", {"theta": s["theta"], "phidot": s["phidot"], "psidot": s["psidot"]}, n_eval=6)
    expected, _ = _centripetal(model, _steady("disk", "circle", "3"))
    mu = sol.friction_required
    assert mu.shape == sol.t.shape
    # the state is the steady one rounded to double, then mu is evaluated in double: 64 eps is an
    # empirical bound (measured 1.9 eps; the evaluation's own rounding, 26.5 eps at most on the run
    # of the quad test below, dominates), not one derived from the expression's condition number
    assert abs(mu[0] - float(expected)) <= 64 * 2.0**-52 * float(expected)


def test_lazy_evaluation(monkeypatch):
    calls = []
    real = invariants.friction_function
    monkeypatch.setattr(invariants, "friction_function", lambda *a: calls.append(a) or real(*a))
    sol = solve("disk", "0.5", {"theta": "1.2", "phidot": "3", "psidot": "5"})
    sol.invariants, sol.normal_force
    assert calls == []
    first = sol.friction_required
    assert len(calls) == 1
    assert sol.friction_required is first and len(calls) == 1


def test_nan_where_the_normal_force_is_not_positive():
    compiled = compile_model(get_model("disk"), parse_precision("double"))
    # theta = 1.2 with phidot = 3, psidot = 5: N > 0 at rest in theta, N < 0 once thetadot = 40 (the rim is flung up)
    y = np.array([[1.2, 0, 0, 0, 3, 5, 0, 0], [1.2, 0, 0, 40, 3, 5, 0, 0]]).T
    pars = {p.name: float(sp.N(p.default)) for p in compiled.model.parameters}
    normal = invariants.evaluate(compiled, np.ascontiguousarray(y), pars)[1]
    mu = invariants.friction_required(compiled, np.ascontiguousarray(y), pars)
    assert normal[0] > 0 and normal[1] <= 0
    assert math.isfinite(mu[0]) and math.isnan(mu[1])


def test_json_record(capsys):
    argv = ["trajectory", "disk", "--state", "theta=1.2", "--state", "phidot=3", "--state", "psidot=5", "--t-end", "1"]
    assert main(argv + ["--format", "json"]) == 0
    rec = json.loads(capsys.readouterr()[0])["friction_required"]
    assert list(rec) == ["max", "t_max"]
    sol = solve("disk", 1, {"theta": "1.2", "phidot": "3", "psidot": "5"})
    mu = sol.friction_required
    assert rec["max"] == float(np.nanmax(mu)) and rec["t_max"] == float(sol.t[int(np.nanargmax(mu))])
    assert main(["trajectory", "sliding-disk", "--state", "theta=1.2", "--t-end", "0.1", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr()[0])["friction_required"] is None


def test_quad_gives_the_double_value_to_double_accuracy():
    """The same states evaluated by the double and the quad cfunc: the double value within 64 eps of
    max(1, mu) of the quad one (absolute where mu < 1).  mu is a few hundred operations on the rates
    whose terms cancel to |F_h| and N; the bound is empirical, not derived: on this run the largest
    difference is 26.5 eps (mu up to 2.43), and the factor 2.4 is left for another CPU's vector
    sin/cos (heyoka evaluates the double cfunc in SIMD batches, about 1 ulp from scalar libm)."""
    model = get_model("disk")
    quad, double = parse_precision("quad"), parse_precision("double")
    sol = solve("disk", 1, {"theta": "1.2", "phidot": "3", "psidot": "5"}, precision="quad")
    y_double = sol.y.astype(float)
    pars = {n: v for n, v in sol.params.items()}
    mu_quad = invariants.friction_required(compile_model(model, quad), quad.array(y_double.ravel()).reshape(y_double.shape), pars)
    mu_double = invariants.friction_required(compile_model(model, double), y_double, {n: float(v) for n, v in pars.items()})
    err = np.abs(mu_double - mu_quad.astype(float)) / np.maximum(1, mu_quad.astype(float))
    assert np.all(np.isfinite(mu_double))
    assert err.max() <= 64 * double.eps, err.max() / double.eps
    run = sol.friction_required.astype(float)  # the run's own, in quad: the same values to 64 eps
    assert np.all(np.abs(run - mu_quad.astype(float)) <= 64 * double.eps * np.maximum(1, np.abs(run)))

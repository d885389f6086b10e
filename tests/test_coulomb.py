"""Rolling and sliding with Coulomb friction (models/coulomb.py, verify/engine/hybrid.py).

Tolerances are in units of the run's epsilon and argued where they are set; each check that could
pass vacuously has a negative control that must fail it.
"""
from __future__ import annotations

import json

import mpmath
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import STATE
from verify.engine import hybrid, hybrid_guards, hybrid_switches, hybrid_system, slip_onset
from verify.engine.trajectory import IntegrationError
from verify.studies.coulomb_examples import perturbed_circle, steady_circle
from verify.engine.single import solve
from verify.precision import parse_precision

UPRIGHT = "1.57079632679489661923132169163975144209858"  # pi/2 to 42 digits: read once at each precision


def _f(values):
    return np.array([float(v) for v in values])


# --- 3. the planar wheel: closed form ------------------------------------------------------------
#
# Upright (theta = pi/2, no tilt or precession rate) with CM velocity v0 along X and spin psidot0, the
# contact slips with u = v0 + psidot0 (omega x r_P = psidot0 X).  Sliding: dv/dt = -mu g sgn(u),
# I3 dpsidot/dt = -mu g sgn(u) (torque of F_h about C along e3 = -Y), so du/dt = -mu g sgn(u) (1 + 1/I3):
#     t_s = |u0| / (mu g (1 + 1/I3)),   v_f = (v0 - I3 psidot0) / (1 + I3)
# (the second is the conservation of angular momentum about the contact line); I3 = 2k = 1/2 for the disk.

WHEEL = {"v0": 30, "psidot0": -60, "mu": sp.Rational(3, 10), "g": 980, "I3": sp.Rational(1, 2)}


def _wheel_exact():
    w = WHEEL
    u0 = w["v0"] + w["psidot0"]
    t_s = sp.Abs(u0) / (w["mu"] * w["g"] * (1 + 1 / w["I3"]))
    v_f = (w["v0"] - w["I3"] * w["psidot0"]) / (1 + w["I3"])
    return t_s, v_f


def _wheel(precision, t_end="0.1"):
    return hybrid.solve("disk+coulomb", t_end, {"theta": UPRIGHT, "psidot": str(WHEEL["psidot0"])},
                        friction=WHEEL["mu"], velocity=(str(WHEEL["v0"]), "0"), precision=precision, n_eval=11)


@pytest.mark.parametrize("precision", ["double", "long", "quad"])
def test_planar_wheel_sticks_at_the_closed_form_time_and_speed(precision):
    """The sliding motion is polynomial in t (linear rates), so the Taylor series is exact and the only
    errors are the roundings of the start, of the coefficients and of the event's root: a few eps.
    Bound: 8 eps relative for t_s (the root of a linear s(t) from a rounded start and slope) and for v_f."""
    sol = _wheel(precision)
    prec = parse_precision(precision)
    assert [p.kind for p in sol.phases] == ["sliding", "rolling"] and sol.phases[0].ended == "sticks"
    j = list(sol.phase_index).index(1)  # the first output of the rolling phase: the stick state
    with mpmath.workprec(256):
        t_s, v_f = (mpmath.mpf(sp.N(v, 80)) for v in _wheel_exact())
        t_switch = prec.to_mpf(sol.switch_times[0])
        vx = -prec.to_mpf(sol.y[5, j])  # rolling upright along X: v_C = -psidot X
        assert abs(t_switch - t_s) <= 8 * prec.eps * t_s
        assert abs(vx - v_f) <= 8 * prec.eps * abs(v_f)
    assert sol.outcome == "ok"


def _launch_energy():
    """E(0) from the start as the user gives it: (v0^2 + I3 psidot0^2)/2 + g (per m R^2)."""
    w = WHEEL
    return sp.Rational(1, 2) * (w["v0"] ** 2 + w["I3"] * w["psidot0"] ** 2) + w["g"]


@pytest.mark.parametrize("wrong", ["direction_flipped", "velocity_not_mapped"])
def test_a_wrong_launch_map_fails_the_wheel_checks(wrong, monkeypatch):
    """Negative controls: the launch map with the slip direction flipped, or with the CM velocity not
    mapped (u = omega x r_P as if v_C = 0), must fail the closed form (t_s and v_f together: a flipped
    direction keeps s, hence t_s, but not v_f) and the launch energy."""
    right = hybrid.launch_slip

    def wrong_map(c, y0, velocity, pars):
        if wrong == "velocity_not_mapped":
            velocity = [v * 0 for v in velocity]
        s, alpha = right(c, y0, velocity, pars)
        return (s, alpha + c.precision.number(sp.pi)) if wrong == "direction_flipped" else (s, alpha)

    monkeypatch.setattr(hybrid, "launch_slip", wrong_map)
    sol = _wheel("double")
    t_s, v_f = _wheel_exact()
    j = list(sol.phase_index).index(1)
    closed_form_holds = (abs(float(sol.switch_times[0]) - float(t_s)) <= 8 * 2.0 ** -52 * float(t_s)
                         and abs(-float(sol.y[5, j]) - float(v_f)) <= 8 * 2.0 ** -52 * float(v_f))
    launch_energy_holds = abs(float(sol.energy[0]) - float(_launch_energy())) <= 8 * 2.0 ** -52 * float(_launch_energy())
    assert not closed_form_holds and not launch_energy_holds
    monkeypatch.setattr(hybrid, "launch_slip", right)
    sol = _wheel("double")  # and the right map holds both (the positive side of the control)
    assert abs(float(sol.energy[0]) - float(_launch_energy())) <= 8 * 2.0 ** -52 * float(_launch_energy())


# --- 5. energy: conserved rolling, decreasing sliding, E + W constant ------------------------------

TILTED = {"theta": "1.2", "phidot": "3", "psidot": "25"}  # a wobbling disk launched with a skid


def _tilted(precision):
    return hybrid.solve("disk+coulomb", "0.5", TILTED, friction="1", velocity=("3", "1"), precision=precision,
                        n_eval=51)


@pytest.mark.parametrize("precision", ["double", "long", "quad", pytest.param("mp:128", marks=pytest.mark.slow)])
def test_energy_balance_through_a_stick(precision):
    """E + W = E(0) throughout, E constant while rolling, non-increasing while sliding.

    Bound 64 eps of E's term scale for E + W: each Taylor step has a local error of ~eps times the
    term scale; the run takes a few hundred steps, whose errors add as a random walk (sqrt(N) ~ 20)
    with a margin of 3 for the switch (the same numbers handed over; E re-evaluated on another
    formula, both rounded).  Sliding: E(t_{i+1}) <= E(t_i) + 64 eps scale (the same allowance on a
    quantity that falls by mu N s dt)."""
    sol = _tilted(precision)
    prec = parse_precision(precision)
    assert [p.kind for p in sol.phases] == ["sliding", "rolling"] and sol.phases[0].ended == "sticks"
    assert sol.energy_plus_work_drift_in_eps <= 64
    allowance = 64 * prec.eps * sol.energy_scale
    e = np.array([float(prec.to_mpf(v)) for v in sol.energy])
    w = np.array([float(prec.to_mpf(v)) for v in sol.work])
    sliding = sol.phase_index == 0
    assert np.all(np.diff(e[sliding]) <= allowance)
    assert e[sliding][-1] < e[0] - 1e3 * allowance  # it does dissipate: the check above is not vacuous
    rolling = sol.phase_index == 1
    assert np.ptp(e[rolling]) <= 2 * allowance and np.ptp(w[rolling]) == 0


def test_a_wrong_stick_map_fails_the_energy_balance(monkeypatch):
    """Negative control: handing the rolling model the state of the last output before the stick
    (slip not yet zero, a CM velocity that is not the no-slip one) must break E + W.  Only the first stick
    is handed over wrongly: the wrong state rolls until it slips again (the slips onset), and a wrong map at
    every stick would go round that cycle until the steps collapse."""
    right = hybrid_switches.after_stick
    wrong_ones = []

    def early(run, t, y8):
        if wrong_ones:
            return right(run, t, y8)
        wrong_ones.append(t)
        before = [i for i, k in enumerate(run.index) if k == len(run.phases) - 1][-2]
        return right(run, t, run.prec.array(list(run.y[before])))

    monkeypatch.setattr(hybrid_switches, "after_stick", early)
    with pytest.raises(IntegrationError) as err:  # the run's own guard stops it: never handed out
        _tilted("double")
    assert err.value.outcome == "failed:energy_balance", err.value
    assert err.value.trajectory.outcome == "failed:energy_balance" and err.value.trajectory.status == 1
    assert err.value.trajectory.energy_plus_work_drift_in_eps > 1e6  # measured: 2.9e12


# --- 1. mu = 0 is the smooth plane (sliding-disk) ------------------------------------------------

SMOOTH = {"theta": "1.2", "phidot": "3", "psidot": "10"}


def _smooth_difference(model_k=None):
    """max over components and times of |hybrid(mu = 0) - sliding-disk| in double, against the
    sliding-disk's own double error (its distance to the quad run)."""
    params = None if model_k is None else {"k": model_k}
    sol = hybrid.solve("disk+coulomb", "0.5", SMOOTH, params, friction="0", velocity=("0", "0"), n_eval=11)
    ref_d = solve("sliding-disk", "0.5", SMOOTH, precision="double", n_eval=11)
    ref_q = solve("sliding-disk", "0.5", SMOOTH, precision="quad", n_eval=11)
    assert [p.kind for p in sol.phases] == ["sliding"] and sol.outcome == "ok"
    exact = np.array([[float(v) for v in row] for row in ref_q.y])
    own_error = np.abs(ref_d.y - exact).max(axis=1)
    return np.abs(sol.y - exact).max(axis=1), own_error


def test_no_friction_reproduces_the_sliding_disk():
    """With mu = 0 and no horizontal CM velocity, the rows are the smooth plane's.  The two double runs
    integrate the same flow in different coordinates, so each is off the exact (quad) solution by the
    flow's amplification of its roundings; that amplification is measured by the sliding-disk's own
    double error, and the hybrid run may be off by 8 times it (two independent random walks of the same
    size, margin 4) plus 16 eps of the component (the final roundings)."""
    diff, own = _smooth_difference()
    scale = np.array([abs(float(v)) for v in solve("sliding-disk", "0.5", SMOOTH, n_eval=2).y[:, -1]]) + 1
    # x, y: the sliding-disk keeps them exactly; here x' = s e(alpha) - (omega x r_P)_h is a cancellation of
    # terms of the size of the rates (|r_P| = 1), so x, y are off by at most t_end times the rates' error
    own[6:] = 0.5 * own[3:6].max()
    assert np.all(diff <= 8 * own + 16 * 2.0 ** -52 * scale)


def test_no_friction_with_another_body_is_not_the_sliding_disk():
    """Negative control: the hoop (k = 1/2) against the disk's sliding run differs beyond the bound in the
    six Euler components, and the disk against itself does not (x, y are left out: the sliding disk keeps
    them exactly, so its own error there is 0 and any rounding would exceed a multiple of it)."""
    diff, own = _smooth_difference(model_k="0.5")
    assert np.any(diff[:6] > 1e6 * own[:6]), (diff[:6], own[:6])
    same_diff, same_own = _smooth_difference()
    assert not np.any(same_diff[:6] > 1e6 * same_own[:6]), (same_diff[:6], same_own[:6])


# --- 2. mu large: the rolling disk ---------------------------------------------------------------

def test_large_friction_reproduces_the_rolling_disk():
    """A rolling start with mu = 1e6 never slips: one rolling phase, the engine's disk run with the slip
    event, and the same numbers as the disk run without it up to the amplified roundings (the event
    changes heyoka's steps, so not bit for bit): bound 8 times the disk's own double error against
    quad plus 16 eps, as above."""
    st = {"theta": "1.2", "psidot": "10"}
    sol = hybrid.solve("disk+coulomb", "1", st, friction="1e6", n_eval=11)
    assert [p.kind for p in sol.phases] == ["rolling"] and sol.outcome == "ok"
    ref_d = solve("disk", "1", st, n_eval=11)
    exact = np.array([[float(v) for v in row] for row in solve("disk", "1", st, precision="quad", n_eval=11).y])
    own = np.abs(ref_d.y - exact).max(axis=1)
    scale = np.abs(exact).max(axis=1) + 1
    assert np.all(np.abs(sol.y - exact).max(axis=1) <= 8 * own + 16 * 2.0 ** -52 * scale)
    assert np.all(np.abs(sol.energy - sol.energy[0]) <= 64 * 2.0 ** -52 * sol.energy_scale)


# --- 4. Le Saux, Leine & Glocker: stationary circular rolling --------------------------------------
#
# g/r = 196.2 s^-2 (r = 5 cm), inclination 5 deg read as theta = 5 deg (the disk 5 deg off the plane),
# and rho = 0.1 read as the radius of the centre of mass's circle in units of r (assumptions: the paper
# itself was not available to us).  Steady rolling of the thin disk (k = 1/4): thetaddot = 0 at
# thetadot = 0 with psidot = phidot (rho - cos theta) gives phidot; mu_req is then constant.

def _steady():
    return steady_circle()  # the report's example shares it (verify.studies.coulomb_examples)


def test_stationary_circular_rolling_keeps_rolling_above_its_friction_and_slips_below():
    state, params = _steady()
    run = solve("disk", "0.2", state, params, precision="quad", n_eval=5)
    quad = parse_precision("quad")
    with mpmath.workprec(240):
        need = [quad.to_mpf(v) for v in run.friction_required]
        # constant on the steady circle: its spread in quad is roundings, a few quad eps of mu_req per step
        # of a short run (measured 2.1 eps); 64 quad eps leaves room for the four samples' steps
        spread = (max(need) - min(need)) / (quad.eps * need[0])
        assert spread <= 64, f"mu_req spread {float(spread):.3g} quad eps of mu_req"
    mu_req = float(run.friction_required[0])
    above = hybrid.solve("disk+coulomb", "0.2", state, params, friction=str(float(1.01 * mu_req)), precision="quad",
                         n_eval=5)
    assert [p.kind for p in above.phases] == ["rolling"] and above.outcome == "ok"
    with mpmath.workprec(240):
        # still steady: theta stays at 5 deg to the quad run's roundings (64 quad eps of theta; measured 5e-36)
        drift = abs(quad.to_mpf(above["theta"][-1]) - mpmath.pi * 5 / 180) / (quad.eps * mpmath.pi * 5 / 180)
        assert drift <= 64, f"theta drift {float(drift):.3g} quad eps of theta"
    # below its mu_req the start cannot roll: the slip starts at t = 0 from s = 0 (then sticks again)
    below = hybrid.solve("disk+coulomb", "0.2", state, params, friction=str(float(0.99 * mu_req)), n_eval=5)
    assert below.phases[0].kind == "sliding" and float(below.phases[0].t_start) == 0
    assert float(below.slip_speed[0]) == 0 and float(below.phases[0].t_end) > 0
    assert below.energy_plus_work_drift_in_eps <= 64  # the bound argued in test_energy_balance_through_a_stick


# --- a slip that starts from s = 0 where rolling needs more than mu ----------------------------------

def _below_circle(precision="double", velocity=None, t_end="0.2"):
    """The steady circle with mu = 0.9 of its need: it slides from t = 0 (onset at s = 0), then sticks."""
    state, params = _steady()
    need = solve("disk", "0.2", state, params, precision="quad", n_eval=2).friction_required[0]
    return hybrid.solve("disk+coulomb", t_end, state, params, friction=str(float(0.9 * float(need))),
                        precision=precision, n_eval=5, velocity=velocity)


def _nearby_launch(delta: str, turn: float, precision="double"):
    """A launch whose contact already slips by ``delta`` (cm/s) in the onset's direction turned by ``turn``."""
    state, params = _steady()
    rolling = get_model("disk")
    values = {q: sp.Float(state.get(str(q), "0"), 50) for q in STATE}  # the rolling start's no-slip velocity
    vx, vy = (sp.N(e.subs(rolling.parameter("k").symbol, sp.Rational(1, 4)).subs(values), 50)
              for e in rolling.velocity_xy)
    onset = _below_circle(precision).slip_direction[0]
    with mpmath.workdps(50):
        a = mpmath.mpf(float(onset)) + turn
        d = mpmath.mpf(delta)
        velocity = (mpmath.nstr(mpmath.mpf(str(vx)) + d * mpmath.cos(a), 45),
                    mpmath.nstr(mpmath.mpf(str(vy)) + d * mpmath.sin(a), 45))
    return _below_circle(precision, velocity=velocity)


def _final_gap(a, b) -> float:
    """The largest relative difference of the angles and rates at the end of two runs."""
    return max(abs(float(a.y[i, -1] - b.y[i, -1])) / abs(float(b.y[i, -1])) for i in (0, 1, 2, 4, 5))


def test_a_slip_from_rest_of_the_contact_is_the_limit_of_launches_with_a_vanishing_slip():
    """An independent route to the onset (its direction alpha0, rate lambda and Taylor start): runs
    launched with a slip of delta in another direction (turned by 0.5 rad) converge to it linearly in
    delta.  Measured: gap / delta = 0.010509 at delta = 1e-6 and 1e-7; any error of the onset that does
    not vanish with delta shows as a gap / delta growing tenfold from 1e-6 to 1e-7."""
    onset = _below_circle()
    assert [p.kind for p in onset.phases] == ["sliding", "rolling"] and onset.phases[0].ended == "sticks"
    assert onset.energy_plus_work_drift_in_eps <= 64
    ratios = [_final_gap(_nearby_launch(d, 0.5), onset) / float(d) for d in ("1e-6", "1e-7")]
    assert abs(ratios[1] / ratios[0] - 1) < 0.01, ratios
    assert ratios[1] < 1.0  # a slip of delta moves the end by about delta / 100, not more


def _lift_guards(monkeypatch):
    """The run's switch and balance guards off (verify.engine.hybrid_guards), to measure what they stop."""
    monkeypatch.setattr(hybrid_guards, "check_switch", lambda *args: None)
    monkeypatch.setattr(hybrid_guards, "check_balance", lambda *args: None)
    monkeypatch.setattr(hybrid_guards, "check_sliding_start", lambda *args: None)


def test_negative_control_an_onset_in_the_wrong_direction_is_not_that_limit(monkeypatch):
    """An onset turned by 0.5 rad from the right direction: its Taylor start is off its own path, which the
    onset's switch guard sees (E + W at the start against the onset: measured 1.2e-3 against a bound of
    8.6e-10), and, with that guard lifted, the run is far from the limit of launches (measured: 7.9e7 delta)."""
    right = hybrid_switches.onset_directions
    monkeypatch.setattr(hybrid_switches, "onset_directions",
                        lambda c, y, p: [(a + 0.5, lam) for a, lam in right(c, y, p)])
    with pytest.raises(IntegrationError) as err:
        _below_circle()
    assert err.value.outcome == "failed:switch_constraint" and "onset of slip" in str(err.value)
    _lift_guards(monkeypatch)
    wrong = _below_circle()
    monkeypatch.setattr(hybrid_switches, "onset_directions", right)
    gap = _final_gap(_nearby_launch("1e-7", 0.5), wrong)
    assert gap / 1e-7 > 1e3  # measured: 7.9e7
    assert wrong.energy_plus_work_drift_in_eps > 64  # measured: 6e5 (the start is off its own path)


def test_a_slip_from_rest_of_the_contact_agrees_across_precisions_to_its_conditioning():
    """double against quad through the onset and the stick, within four times what one or two ulps of the
    start move the double run (the median of phidot nudged by +-1 and +-2 ulps): its end state (the
    motion's own conditioning, measured 2e-15 to 2.6e-14 relative) and its stick time.

    The stick time is judged by the same rule as the state, not relative to itself: it is the root of the
    slip speed, so its error is the slip speed's rounding error over the slip's deceleration -- an absolute
    time set by the state's scale, not a fraction of the 0.027 s it took.  Measured: the nudges move it by
    0.1-1.3e-15 s (medians 0.56e-15 on the uncompacted equations, 1.1e-15 on the compact ones,
    verify.engine.compact); double against quad 0.06e-15 s uncompacted and 1.2e-15 s compact, the same
    rounding noise in another order.  (A bound of 64 eps of t_stick, 3.8e-16 s, held before by luck: one
    ulp of the start moved the double run's stick by more.)"""
    double, quad = _below_circle("double"), _below_circle("quad")
    state, params = _steady()
    need = solve("disk", "0.2", state, params, precision="quad", n_eval=2).friction_required[0]
    moved = [hybrid.solve("disk+coulomb", "0.2", dict(state, phidot=str(float(state["phidot"]) * (1 + k * 2.0 ** -52))),
                          params, friction=str(float(0.9 * float(need))), n_eval=5) for k in (1, -1, 2, -2)]
    conditioning = float(np.median([_final_gap(m, double) for m in moved]))
    time_conditioning = float(np.median([abs(float(m.switch_times[0]) - float(double.switch_times[0])) for m in moved]))
    assert conditioning > 0 and time_conditioning > 0
    gap = max(abs(float(double.y[i, -1]) - float(quad.y[i, -1])) / abs(float(quad.y[i, -1])) for i in (0, 1, 2, 4, 5))
    assert gap <= 4 * conditioning + 16 * 2.0 ** -52, (gap, conditioning)
    t_stick = float(quad.switch_times[0])
    assert abs(float(double.switch_times[0]) - t_stick) <= 4 * time_conditioning + 16 * 2.0 ** -52 * t_stick


# --- a slip that starts from rolling where mu_req reaches mu (the slips event) ----------------------

def _perturbed_circle(precision="double", state_change=None):
    """The steady circle tilted by 0.01 rad (mu_req oscillates), mu halfway between its extremes (the
    report's example, verify.studies.coulomb_examples.perturbed_circle).

    Returns the run and the rolling run without the slip event (its mu_req on a fine grid)."""
    state, params, mu = perturbed_circle()
    state = dict(state, **(state_change or {}))
    free = solve("disk", "0.2", state, params, n_eval=2001)
    run = hybrid.solve("disk+coulomb", "0.2", state, params, friction=mu, n_eval=11, precision=precision)
    return run, free


def _conditioning() -> float:
    """How far one ulp of phidot at the start moves the double run's end (relative, max over angles and rates)."""
    state, _ = _steady()
    run, _ = _perturbed_circle()
    phidot = float(state["phidot"]) * (1 + 2.0 ** -52)
    moved, _ = _perturbed_circle(state_change={"phidot": str(phidot)})
    return _final_gap(moved, run)


def test_a_perturbed_circle_slips_when_its_required_friction_reaches_mu_and_slides_until_it_sticks():
    """The run leaves rolling at the first time mu_req reaches mu (which the rolling run without the slip
    event shows on a fine grid), starts sliding from s = 0 by the onset's series (verify.engine.slip_onset),
    sticks and rolls on; E + W within the bound argued in test_energy_balance_through_a_stick (64 eps;
    measured 0.46)."""
    sol, free = _perturbed_circle()
    mu_t = _f(free.friction_required)
    assert [p.kind for p in sol.phases] == ["rolling", "sliding", "rolling"], sol.phases
    assert [p.ended for p in sol.phases] == ["slips", "sticks", "ok"] and sol.outcome == "ok"
    first = float(free.t[np.argmax(mu_t >= float(sol.params["mu"]))])
    step = float(free.t[1])
    assert first - step <= float(sol.switch_times[0]) <= first
    sliding = sol.phase_index == 1
    assert float(sol.slip_speed[sliding][0]) == 0 and np.all(_f(sol.slip_speed[sliding][1:-1]) > 0)
    assert sol.energy_plus_work_drift_in_eps <= 64
    assert float(sol.work[-1]) > 0


def test_the_onset_from_rolling_agrees_across_precisions_to_its_conditioning():
    """double against quad through the slips event, the onset's series and the stick, within four times
    what one ulp of the start moves the double run's end (measured: gap 27 eps, conditioning 9.6 eps) plus
    16 eps, as for the onset from a start (test_a_slip_from_rest_of_the_contact_agrees_across_precisions...)."""
    double, _ = _perturbed_circle()
    quad, _ = _perturbed_circle("quad")
    assert [p.kind for p in quad.phases] == [p.kind for p in double.phases]
    conditioning = _conditioning()
    assert conditioning > 0
    gap = _final_gap(double, quad)
    assert gap <= 4 * conditioning + 16 * 2.0 ** -52, (gap, conditioning)
    assert quad.energy_plus_work_drift_in_eps <= 64


def _start_later(monkeypatch, factor):
    """Sum the onset's series at ``factor`` times the step cap (it is summed at the cap itself otherwise)."""
    right = slip_onset.series_start
    monkeypatch.setattr(slip_onset, "series_start", lambda *args: right(*args[:-1], args[-1] * factor))


def test_the_onset_series_summed_at_half_its_time_gives_the_same_motion(monkeypatch):
    """An independent route through the onset: the series summed at t1 / 2 and heyoka from there (through
    the stiff stretch from t1 / 2 to t1, where the direction's pull-back rate A_s / t^2 is four times what
    it is at t1) against the series at t1.  Within the conditioning bound above (measured: 12 eps)."""
    at_cap, _ = _perturbed_circle()
    _start_later(monkeypatch, 0.5)
    at_half, _ = _perturbed_circle()
    assert [p.kind for p in at_half.phases] == ["rolling", "sliding", "rolling"]
    assert at_half.energy_plus_work_drift_in_eps <= 64
    gap = _final_gap(at_half, at_cap)
    assert gap <= 4 * _conditioning() + 16 * 2.0 ** -52, gap


@pytest.mark.parametrize("wrong", ["alpha1", "sigma"])
def test_negative_control_a_wrong_onset_series_fails_the_checks(wrong, monkeypatch):
    """alpha1 (the direction's first rate) or sigma = 2 s_2 (the slip's second derivative) off by one part
    in 10^6: the start at t1 leaves the slow solution.  It must fail the t1 / 2 route by far (measured: gaps
    of 1.4e7 and 1.8e7 eps) and E + W (measured: 1.5e5 and 912 eps).  The run's guards stop such a run
    (sigma: E + W at t1 against the onset, 2.0e-6 against a bound of 7.9e-10; alpha1: E + W 1.5e5 eps past
    its bound of 1.2e3); the gaps are measured with them lifted."""
    right_run, _ = _perturbed_circle()
    extend = slip_onset.OnsetSeries.extend

    def off(self, order):
        extend(self, order)
        if wrong == "alpha1":
            self.alpha[1] *= 1 + 1e-6
        else:
            self.s[2] *= 1 + 1e-6

    monkeypatch.setattr(slip_onset.OnsetSeries, "extend", off)
    with pytest.raises(IntegrationError) as err:
        _perturbed_circle()
    assert err.value.outcome in ("failed:switch_constraint", "failed:energy_balance"), err.value
    _lift_guards(monkeypatch)
    sol, _ = _perturbed_circle()
    assert _final_gap(sol, right_run) > 1e3 * (4 * _conditioning() + 16 * 2.0 ** -52)
    assert sol.energy_plus_work_drift_in_eps > 64


def test_an_onset_series_that_does_not_settle_is_not_integrated(monkeypatch):
    """With only four orders the series cannot reach eps at any start time tried: the run stops at the
    slips event with UnsupportedTransition and the run up to there, as before the series existed."""
    right = slip_onset.series_start
    monkeypatch.setattr(slip_onset, "series_start", lambda *args: right(*args, orders=4))
    with pytest.raises(hybrid.UnsupportedTransition) as err:
        _perturbed_circle()
    assert err.value.trajectory.phases[-1].ended == "slips"
    assert "does not settle" in str(err.value)


def test_the_ring_slides_sticks_and_rolls_with_its_energy_balanced():
    """ring+coulomb (the printed ring's sliding rows, about 3500 operations, in compact mode): a skid
    at mu = 1 sticks and rolls on; E + W within the bound argued for the disk (64 eps of E's term scale)."""
    sol = hybrid.solve("ring+coulomb", "0.3", TILTED, friction="1", velocity=("3", "1"), n_eval=11)
    assert [p.kind for p in sol.phases] == ["sliding", "rolling"] and sol.phases[0].ended == "sticks"
    assert sol.energy_plus_work_drift_in_eps <= 64
    e = np.array([float(v) for v in sol.energy])
    assert e[sol.phase_index == 1][-1] < e[0] - 1e3 * 64 * 2.0 ** -52 * sol.energy_scale  # friction did work


@pytest.mark.parametrize("argv, words", [
    (["--friction", "abc"], "--friction abc: allowed a positive finite number"),
    (["--friction", "nan"], "--friction nan: allowed a positive finite number"),
    (["--friction", "-0.1"], "--friction -0.1: allowed a positive finite number such as 0.5 (a Coulomb coefficient > 0)"),
    (["--friction", "0"], "--friction 0: allowed a positive finite number"),
    (["--friction", "1", "--velocity", "1,abc"], "--velocity VX,VY: 'abc' is not a number"),
    (["--friction", "1", "--t-end", "abc"], "--t-end abc"),
])
def test_bad_input_names_the_value_and_exits_2(capsys, argv, words):
    from verify.cli import main

    args = ["trajectory", "disk+coulomb", "--state", "theta=1.2"] + argv
    if "--t-end" not in argv:
        args += ["--t-end", "1"]
    code = main(args)
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and words in err and "Traceback" not in err


def test_a_sliding_start_outside_the_domain_is_bad_input_and_a_reached_one_is_a_failed_run(capsys, monkeypatch):
    """A start lying flat (theta = 0) with a skid is refused before any phase (exit 2, the domain named).  A skid
    that lays the disk flat while sliding (theta = 0.3, velocity (0, 50), mu = 0.2) ends at the domain's end,
    event:lies_flat (exit 0), theta within the event's allowance of 0 (measured 9.5e-14: the Euler angles'
    rates blow up there and the steps stall ulps before the root).  Negative control: the same run judged
    against a narrower domain (theta > 0.3) leaves it: the issue's run (theta = 1.2, psidot = 10, mu = 0.5) dips
    to theta = 0.2 by t = 0.17 s: failed:outside_domain, exit 1, the run up to there."""
    from verify.cli import main

    code = main(["trajectory", "disk+coulomb", "--state", "theta=0", "--friction", "0.5", "--velocity", "1,2",
                 "--t-end", "0.2"])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and "outside the domain" in err and "Traceback" not in err
    flat = ["trajectory", "disk+coulomb", "--state", "theta=0.3", "--friction", "0.2", "--velocity", "0,50",
            "--t-end", "1", "--format", "json"]
    code = main(flat)
    out, err = capsys.readouterr()
    record = json.loads(out)
    assert code == 0 and record["outcome"] == "event:lies_flat", (record["outcome"], err)
    assert 0 <= float(record["state"]["theta"]) <= 1e-12
    right = hybrid_system.domain_end
    monkeypatch.setattr(hybrid_system, "domain_end", lambda end, prec: prec.number("0.3") if end == 0 else right(end, prec))
    code = main(["trajectory", "disk+coulomb", "--state", "theta=1.2", "--state", "psidot=10", "--friction", "0.5",
                 "--t-end", "0.3", "--format", "json"])
    out, err = capsys.readouterr()
    record = json.loads(out)
    assert code == 1 and record["outcome"] == "failed:outside_domain" and "left its domain" in err
    assert float(record["state"]["theta"]) < 0.3  # the run up to the first output outside

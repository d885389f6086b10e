"""The Coulomb reference cases (a coin that rolls, slides and sticks) and scoring runs against them.

The committed files are read, never written.  The runs scored here are this suite's own hybrid in double
(a different precision from the MPFR pair that made the files), written in form (b) with the centre of
mass's velocity of each phase; negative controls flip every verdict: a run without the skid, a run of the
rolling model that never slips, another mu.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from models.symbols import STATE_NAMES
from verify.engine.hybrid import solve as solve_hybrid
from verify.frames import QUATERNION, euler_to_b
from verify.reference import DIRECTORY, check_case, load_set
from verify.reference.cases import case
from verify.engine.hybrid_run import grid_rows
from verify.precision import parse_precision
from verify.scoring import InvalidRun, score

SLIP, SKID = "coin-coulomb-slip-1", "coin-coulomb-skid-1"


@pytest.fixture(scope="module")
def records():
    return {r["name"]: r for r in load_set(DIRECTORY, [SLIP, SKID])}


def test_the_files_say_what_the_cases_are(records):
    slip, skid = records[SLIP], records[SKID]
    assert slip["switches"]["kinds"] == ["rolling -> sliding", "sliding -> rolling"]
    assert skid["switches"]["kinds"] == ["sliding -> rolling"]
    assert slip["friction"]["initial_velocity_xy"] is None and slip["friction"]["mu"] == "0.87"
    assert skid["friction"]["mu"] == "0.3" and len(skid["friction"]["initial_velocity_xy"]) == 2
    for r in records.values():
        assert r["friction"]["model"] == "ring+coulomb" and r["model"]["name"] == "ring"
        # the phases on the grid follow the switch times
        times = [float(t) for t in r["switches"]["times"]["value"]]
        for t, phase in zip(r["grid"], r["phases"]):
            k = sum(float(t) >= s for s in times)
            kinds = ["sliding" if r["friction"]["initial_velocity_xy"] else "rolling"] + \
                [k_.split(" -> ")[1] for k_ in r["switches"]["kinds"]]
            assert phase == kinds[k], (r["name"], t)


def test_switch_times_and_the_energy_balance_are_agreed_to_30_digits(records):
    for r in records.values():
        assert min(r["switches"]["times"]["digits"]) >= 30, r["switches"]["times"]
        ew = r["invariants"]["energy_plus_work"]
        with mpmath.workdps(60):
            first = mpmath.mpf(ew["value"][0])
            for text, err in zip(ew["value"], ew["abs_error"]):  # E + W constant within its agreed error
                assert abs(mpmath.mpf(text) - first) <= mpmath.mpf(err) + mpmath.mpf(ew["abs_error"][0])
        work = [float(v) for v in r["columns"]["work"]["value"]]
        assert work[0] == 0 and work[-1] > 0 and all(b >= a for a, b in zip(work, work[1:]))  # friction only takes
        for phase, s in zip(r["phases"], r["columns"]["slip_speed"]["double"]):
            assert (s == 0) == (phase == "rolling")


def test_the_slip_starts_where_the_required_friction_reaches_mu(records):
    """Independent of the hybrid's event: the rolling model alone (no friction in it), integrated in quad to
    the stored switch time, needs mu_req = mu there, and less just before."""
    from verify.engine.single import solve

    r = records[SLIP]
    c = case(SLIP)
    t_slip = r["switches"]["times"]["value"][0]
    sol = solve("ring", t_slip, c.state, c.exact_params, precision="quad", t_eval=["0", "0.07", t_slip])
    mu_req = np.asarray(sol.columns()["mu_req"], float)
    assert mu_req[-1] == pytest.approx(0.87, abs=1e-12) and mu_req[1] < 0.87


def test_both_cases_pass_the_check_in_double_and_a_wrong_mu_fails_it(records):
    for r in records.values():
        good = check_case(r, "double")
        assert good.ok and 0 < good.ratio <= 1, good
    wrong = check_case(records[SKID], "double", params={"mu": "0.3000001"})
    assert not wrong.ok and wrong.ratio > 10, wrong


def _hybrid_form_b(name: str, times=None, friction=None):
    """This suite's double run of a Coulomb case in form (b): C's velocity is the rolling one plus the slip."""
    c = case(name)
    times = times or c.grid()
    double = parse_precision("double")
    sol = solve_hybrid(c.run_model, times[-1], c.state, c.exact_params, friction=friction or c.friction,
                       velocity=c.velocity, t_eval=times)
    rows = grid_rows(sol, times, double)
    euler = {n: np.array([float(sol.y[i][j]) for j in rows]) for i, n in enumerate(STATE_NAMES)}
    params = {k: float(v) for k, v in c.exact_params.items()}
    params.setdefault("g", 980.0)
    b = euler_to_b("ring", euler, params)
    s = np.array([float(sol.slip_speed[j]) for j in rows])
    alpha = np.nan_to_num(np.array([float(sol.slip_direction[j]) for j in rows]))
    b["vx"] = b["vx"] + s * np.cos(alpha)
    b["vy"] = b["vy"] + s * np.sin(alpha)
    run = {"t": np.array([float(t) for t in times]), **{k: v for k, v in b.items() if k not in QUATERNION}}
    return run, b, s


@pytest.mark.parametrize("name", [SLIP, SKID])
def test_a_double_run_of_the_hybrid_scores_its_digits_its_energy_and_its_slip(name):
    # The same hybrid at another precision (a check of its precision, not of its model: the model is checked by
    # the rolling model's own mu_req at the slip time and by the negative controls below).  Bounds from the
    # case's conditioning: row sums <= 753 at t_end, rates up to Y = 73, N ~ 300 steps: eps sqrt(N) R Y =
    # 2.2e-16 x 17 x 753 x 73 = 2e-10 in the rates (the slip speed's error is of that order: 1e-9 allows 5x),
    # 2e-10 / Y ~ 3e-12 of the scale: more than 11 digits; E + W is held by the hybrid's own guard to 4 eps a
    # step, 1200 eps = 2.7e-13 of E's term scale: below 1e-12 of E(0)
    run, _, _ = _hybrid_form_b(name)
    s = score(run, name)
    assert s.reference_source == "stored grid" and not s.partial
    assert s.min_digits > 11, s.verdict
    assert s.energy_rel_error < 1e-12 and s.slip_speed_error < 1e-9, s.verdict
    assert [k for k, _ in s.switches] == load_set(DIRECTORY, [name])[0]["switches"]["kinds"]
    assert "slip speed error" in s.verdict and "slip speed error" in s.table()


def test_off_grid_times_are_scored_against_the_hybrid_in_quad():
    times = [f"{j / 40:.3f}".rstrip("0").rstrip(".") or "0" for j in range(41)]  # 0, 0.025, ...: not grid times
    run, _, _ = _hybrid_form_b(SKID, times)
    s = score(run, SKID)
    assert s.reference_source == "quad re-integration" and s.min_digits > 11 and s.energy_rel_error < 1e-12


def test_a_run_that_never_slips_is_found_out(records):
    """Negative control: the rolling model alone (as if mu were infinite) from the slip case's start. It
    agrees until mu_req reaches 0.87 and then not: few digits, and a slip speed error equal to the
    reference's whole slip."""
    from verify.engine.single import solve

    c = case(SLIP)
    sol = solve("ring", c.t_end, c.state, c.exact_params, t_eval=c.grid())
    euler = {n: np.asarray(sol.y[i], float) for i, n in enumerate(STATE_NAMES)}
    params = {k: float(v) for k, v in c.exact_params.items()} | {"g": 980.0}
    b = euler_to_b("ring", euler, params)
    run = {"t": np.asarray(sol.t, float), **{k: v for k, v in b.items() if k not in QUATERNION}}
    s = score(run, SLIP)
    assert s.min_digits < 3, s.verdict
    assert s.slip_speed_error == pytest.approx(s.slip_speed_max, rel=1e-6) and s.slip_speed_max > 0.1
    t_slip = float(records[SLIP]["switches"]["times"]["value"][0])  # the stored slip time, 0.0779947...
    assert float(s.worst.split(" at t = ")[1]) > t_slip  # worst after the slip, where the two motions part


def test_a_skid_without_its_velocity_and_an_euler_run_are_refused():
    run, _, _ = _hybrid_form_b(SKID)
    rolling_start = dict(run)
    rolling_start["vx"] = run["vx"].copy()
    rolling_start["vx"][0] *= 2  # the rolling velocity: no skid
    with pytest.raises(InvalidRun, match="vx of the centre of mass"):
        score(rolling_start, SKID)
    record = load_set(DIRECTORY, [SKID])[0]
    euler = {"t": run["t"], **{n: np.array([float(v) for v in record["state"][n]["value"]]) for n in STATE_NAMES}}
    with pytest.raises(InvalidRun, match="form \\(b\\)"):
        score(euler, SKID)


def test_the_coulomb_cases_are_not_offered_to_the_prover(records):
    from verify.reference.proved import prove_case

    with pytest.raises(ValueError, match="agreed, not proved"):
        prove_case(records[SKID])
    assert math.isfinite(float(records[SKID]["conditioning"]["state_row_sum"]["theta"][-1]))

"""The Python API of solve(): the forms of its input, the output grid, failures as named outcomes,
the MPFR floor and the progress hook.  Each refusal names the bad value and what is allowed."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import STATE_NAMES, theta, thetadot, x
from verify import IntegrationError, solve
from verify.engine import segments
from verify.engine import single as integrate
from verify.engine.heyoka_log import collect
from verify.precision import MIN_MPFR_BITS, parse_precision
from verify.standard import STANDARD_STATES
from verify.engine.validation import InvalidStart

START = {"theta": "1.2", "psidot": "10", "phidot": "0.5"}
VECTOR = [1.2, 0.0, 0.0, 0.0, 0.5, 10.0, 0.0, 0.0]


# --- the state: a mapping or a full-length sequence in state order ---------------------------------

@pytest.mark.parametrize("form", [np.array, list, tuple])
def test_a_state_vector_in_state_order_is_the_same_start(form):
    by_name = solve("disk", "0.5", START, n_eval=5)
    by_order = solve("disk", "0.5", form(VECTOR), n_eval=5)
    assert np.array_equal(by_name.y, by_order.y) and by_order.outcome == "ok"


def test_a_quad_state_vector_keeps_its_digits():
    p = parse_precision("quad")
    vec = np.array([p.number("1.2"), *[p.zero()] * 4, p.number("10"), p.zero(), p.zero()])
    sol = solve("disk", "0.01", vec, precision="quad", n_eval=2)
    assert sol.y[0, 0] == p.number("1.2") and sol.y[5, 0] == p.number("10")


@pytest.mark.parametrize("state,words,shape", [
    ([1.2, 0, 0], "state has 3 values (1.2, 0, 0)", True),
    (np.zeros((2, 8)), "array of shape (2, 8)", True),
    ("1.2", "state='1.2' is a string", True),
    (1.2, "state=1.2 of type float", True),
    ([1.2, 0, 0, 0, 0, "ten", 0, 0], "state psidot='ten': 'ten' is not a number", False),
    ([math.nan, 0, 0, 0, 0, 0, 0, 0], "state theta=nan: nan is not a finite number", False),
    ({"omega": 1}, "unknown state variable 'omega'; allowed", False),
])
def test_other_states_are_refused_naming_the_value_and_what_is_allowed(state, words, shape):
    with pytest.raises(InvalidStart) as err:
        solve("disk", "1", state)
    text = str(err.value)
    assert words in text, text
    if shape:  # what is allowed: a mapping, or the eight values in this order
        assert err.value.reason == "shape" and "allowed: a mapping" in text and ", ".join(STATE_NAMES) in text


def test_params_must_be_a_mapping():
    with pytest.raises(ValueError, match=r"params=\[0.3\] is a list; allowed: a mapping of parameter names \(k, g\)"):
        solve("disk", "1", START, [0.3])


# --- the output grid -----------------------------------------------------------------------------

def test_t_eval_returns_exactly_the_requested_times():
    sol = solve("disk", "1", START, t_eval=[0.01, 0.02])
    assert list(sol.t) == [0.01, 0.02] and sol.y.shape == (8, 2) and sol.normal_force.shape == (2,)
    full = solve("disk", "1", START, t_eval=[0, 0.01, 0.02])
    assert list(full.t) == [0.0, 0.01, 0.02]
    assert np.array_equal(sol.y, full.y[:, 1:])  # the same integration, without t = 0
    for name, tr in sol.invariants.items():  # drifts are still measured from the start
        ref = full.invariants[name]
        assert tr.initial == ref.values[0] and len(tr.values) == 2
        assert tr.max_abs_drift == ref.max_abs_drift and np.array_equal(tr.values, ref.values[1:])


def test_t_eval_past_a_terminal_event_ends_at_the_event():
    sol = solve("disk", "1", {"theta": "1.2"}, t_eval=[0.01, 0.02, 0.5])
    assert sol.outcome == "event:contact_lost" and list(sol.t[:2]) == [0.01, 0.02] and len(sol.t) == 3
    assert sol.t[-1] == sol.t_events["contact_lost"] < 0.5


@pytest.mark.parametrize("kwargs,words", [
    ({"n_eval": 2.5}, "n_eval=2.5 is not an integer"),
    ({"n_eval": True}, "n_eval=True is not an integer"),
    ({"n_eval": 1}, "n_eval=1 must be at least 2"),
    ({"n_eval": 5, "t_eval": [0.5]}, "t_eval and n_eval=5 are both given"),
    ({"t_eval": []}, "t_eval is empty"),
    ({"t_eval": [0.2, 0.1]}, "strictly increasing"),
    ({"t_eval": [0.5, 2]}, "must lie in [0, t_end=1"),
    ({"t_eval": 0.5}, "t_eval=0.5: allowed: a sequence"),
    ({"t_eval": [0.1, math.inf]}, "t_eval value inf"),
])
def test_bad_grids_are_refused(kwargs, words):
    with pytest.raises(ValueError) as err:
        solve("disk", "1", START, **kwargs)
    assert words in str(err.value)


def test_default_grid_and_integral_n_eval():
    assert len(solve("disk", "0.1", START).t) == integrate.N_EVAL_DEFAULT == 101
    assert list(solve("disk", "0.1", START, n_eval=np.int64(3)).t) == [0.0, 0.05, 0.1]


# --- failures: named outcomes, never text on stdout, never ok outside the domain ---------------------

def test_a_start_just_above_the_plane_is_a_named_failure_and_stdout_stays_clean(capfd):
    with pytest.raises(IntegrationError) as err:
        solve("disk", 1, {"theta": "1e-300"})
    out, _ = capfd.readouterr()
    assert out == ""  # heyoka's "event detection failed" warning is ours now
    e = err.value
    assert e.outcome == "failed:event_detection" and "event detection failed" in str(e)
    part = e.trajectory  # the run up to its last valid output
    assert part.status == -1 and not part.success and part.outcome == "failed:event_detection"
    assert all(0 < float(v) < math.pi for v in part["theta"])


def test_without_events_leaving_the_domain_is_labelled_never_ok():
    """events=False integrates on past the domain's end, by request (the claims read how far theta
    goes), but the outcome says so."""
    sol = solve("disk", 1, {"theta": "1.2"}, events=False)
    assert sol.outcome == "outside_domain" and sol.status == 2 and float(sol["theta"][-1]) < 0
    assert "theta left the domain" in sol.message


def test_events_off_still_integrates_a_run_that_stays_in_the_domain():
    """Negative control: no events, contact not enforced, theta inside (0, pi/2): an ordinary result."""
    sol = solve("ring", "0.5", {"theta": "1.2", "phidot": "25"}, events=False, n_eval=3)
    assert sol.outcome == "ok" and sol.status == 0


def test_a_non_finite_state_is_named():
    bad = replace(get_model("disk"), accelerations=(thetadot**2, sp.Integer(0), sp.Integer(0)), normal_force=None)
    with pytest.raises(IntegrationError) as err:
        solve(bad, "2", {"theta": "1.0", "thetadot": "2"}, events=False)
    assert err.value.outcome == "failed:non_finite" and "non-finite" in str(err.value)
    assert err.value.trajectory is not None and err.value.trajectory.t[-1] < 0.5


def test_a_collapsing_step_size_is_named_instead_of_hanging():
    """theta oscillates about 1 at the frequency (1 - x)^-4 with x = t: near t = 1 the steps shrink
    without bound while the state stays finite (heyoka would never return)."""
    m = get_model("disk")
    bad = replace(m, accelerations=(-(theta - 1) / (1 - x) ** 8, sp.Integer(0), sp.Integer(0)),
                  velocity_xy=(sp.Integer(1), sp.Integer(0)), normal_force=None)
    with pytest.raises(IntegrationError) as err:
        solve(bad, "2", {"theta": "1.1"}, events=False)
    assert err.value.outcome == "failed:step_size_collapse" and 0.9 < float(err.value.t) < 1
    assert err.value.outcome in integrate.FAILURES


def test_a_valid_start_still_runs_ok():
    sol = solve("disk", "1", STANDARD_STATES["disk"], n_eval=11)
    assert sol.outcome == "ok" and sol.status == 0 and all(0 < float(v) < math.pi for v in sol["theta"])


# --- the MPFR floor ---------------------------------------------------------------------------------

@pytest.mark.parametrize("bits", [2, 3, 4, 52])
def test_mpfr_below_the_floor_is_refused_naming_the_minimum(bits):
    with pytest.raises(ValueError, match=rf"'mp:{bits}': {bits} bits is below the minimum of {MIN_MPFR_BITS} bits"):
        solve("disk", "1", START, precision=f"mp:{bits}")


def test_mpfr_at_the_floor_runs():
    sol = solve("disk", "0.1", START, precision=f"mp:{MIN_MPFR_BITS}", n_eval=3)
    assert sol.outcome == "ok" and sol.precision.bits == 53


def test_a_grid_that_rounds_to_repeated_times_is_refused():
    """The rule behind the floor, checked for any grid: t_k = k t_end / n strictly increasing."""
    with pytest.raises(ValueError, match="not strictly increasing in double"):
        solve("disk", "1e-320", START, n_eval=10000)


# --- the progress hook ------------------------------------------------------------------------------

def test_progress_is_called_with_time_and_steps_and_changes_nothing(monkeypatch):
    quiet = solve("disk", "3", STANDARD_STATES["disk"], n_eval=4)
    monkeypatch.setattr(segments, "PROGRESS_SECONDS", 0.0)  # every opportunity, so the test does not time
    calls = []
    sol = solve("disk", "3", STANDARD_STATES["disk"], n_eval=4, progress=lambda t, steps: calls.append((t, steps)))
    assert np.array_equal(sol.y, quiet.y) and sol.steps == quiet.steps  # bit for bit
    assert len(calls) > 10 and all(isinstance(t, float) and isinstance(n, int) for t, n in calls)
    assert all(a[0] <= b[0] and a[1] <= b[1] for a, b in zip(calls, calls[1:]))
    assert 0 < calls[0][0] and calls[-1][0] <= 3.0 and calls[-1][1] <= sol.steps


def test_progress_can_stop_a_run(monkeypatch):
    class Stop(Exception):
        pass

    def hook(t, steps):
        raise Stop(t)

    monkeypatch.setattr(segments, "PROGRESS_SECONDS", 0.0)
    with pytest.raises(Stop):
        solve("disk", "3", STANDARD_STATES["disk"], progress=hook)
    with pytest.raises(ValueError, match="progress=3 is not callable"):
        solve("disk", "3", STANDARD_STATES["disk"], progress=3)


# --- heyoka's log ---------------------------------------------------------------------------------------

def test_collected_output_keeps_other_lines_and_nests(capfd):
    import os

    with collect() as outer:
        os.write(1, b"[2026-01-01 00:00:00.000] [heyoka-7.13.0] [warning] polynomial root finding during event "
                    b"detection failed due to too many iterations at the batch index 3\n")
        with collect() as inner:
            os.write(1, b"a line of the user's\n")
        assert inner == []
    out, _ = capfd.readouterr()
    assert out == "a line of the user's\n"
    assert len(outer) == 1 and outer[0].level == "warning" and outer[0].event_detection and outer[0].lane == 3


def test_a_collection_does_not_see_the_lines_of_the_one_before(capfd):
    """The file behind a collection is reused once emptied: the next one starts from nothing."""
    import os

    line = (b"[2026-01-01 00:00:00.000] [heyoka-7.13.0] [warning] polynomial root finding during event "
            b"detection failed due to too many iterations\n")
    with collect() as first:
        os.write(1, line + b"the user's first line\n")
    with collect() as second:
        os.write(1, b"the user's second line\n")
    with collect() as third:
        os.write(1, line)
    out, _ = capfd.readouterr()
    assert len(first) == 1 and second == [] and len(third) == 1
    assert out == "the user's first line\nthe user's second line\n"


# --- the tolerance: from the precision's epsilon to 1 ----------------------------------------------

@pytest.mark.parametrize("precision,tol", [("double", "1e-17"), ("double", "1e-400"), ("double", 1e-300),
                                           ("quad", "1e-40")])
def test_a_tolerance_below_the_precisions_epsilon_is_refused_before_compiling(precision, tol):
    # (tol = 1e-300 in double would ask heyoka for a Taylor order ~346: a quarter of an hour compiling)
    with pytest.raises(ValueError, match=rf"tol={tol!r} is below the {precision} epsilon: allowed: "):
        solve("disk", "1", START, precision=precision, tol=tol)


@pytest.mark.parametrize("tol", ["1", "2.5"])
def test_a_tolerance_of_one_or_more_is_refused(tol):
    with pytest.raises(ValueError, match=rf"tol={tol!r} is not below 1; allowed: "):
        solve("disk", "1", START, tol=tol)


def test_the_epsilon_itself_is_a_valid_tolerance_and_the_default():
    eps = parse_precision("double").eps
    assert solve("disk", "0.1", START, tol=eps, n_eval=3).tol == solve("disk", "0.1", START, n_eval=3).tol == eps


@pytest.mark.parametrize("flag", ["events", "high_accuracy"])
@pytest.mark.parametrize("value", ["yes", 1, None])
def test_switches_take_true_or_false_only(flag, value):
    with pytest.raises(ValueError, match=rf"{flag}={value!r}: allowed: True or False"):
        solve("disk", "1", START, **{flag: value})


def test_a_start_whose_energy_overflows_the_precision_is_refused():
    """psidot = 1e200 is a finite double, but I3 psidot^2 / 2 is not: refused before heyoka's first step.
    In quad (exponent range to 1e4932) the same start is valid."""
    with pytest.raises(InvalidStart, match=r"has energy = inf: its values overflow double") as err:
        solve("disk", "1", {"theta": "1.2", "psidot": "1e200"})
    assert err.value.reason == "non_finite"
    from verify.engine.validation import validate
    validate(get_model("disk"), {"theta": "1.2", "psidot": "1e200"}, None, parse_precision("quad"))


def test_rates_too_fast_for_the_precision_fail_as_non_finite_naming_the_last_good_time():
    with pytest.raises(IntegrationError, match=r"failed after t = 0: heyoka reached a non-finite state") as err:
        solve("disk", "1", {"theta": "1.2", "psidot": "1e100"})
    assert err.value.outcome == "failed:non_finite"

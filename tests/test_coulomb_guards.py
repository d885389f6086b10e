"""No Coulomb run is silently wrong (verify/engine/hybrid_guards.py): Painleve's jam, the regression start,
and property tests over random starts.

A run of disk+coulomb or ring+coulomb, and a rolling run with ``friction=``, either ends ``ok`` or at a
physical event with theta inside the domain at every output and E + W within its bound, or ends with a
named failure.  The random starts are drawn from a fixed seed (reproducible); the slow set draws 300.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from models import coulomb, disk, ring
from verify.engine import hybrid, hybrid_guards, hybrid_run
from verify.engine.single import solve
from verify.engine.failures import SLIP_SLACK_EPS
from verify.engine.trajectory import IntegrationError

NAMED = set(hybrid_guards.FAILED_OUTCOMES) | {"failed:non_finite", "failed:step_size_collapse",
                                               "failed:event_detection", "unsupported:slip_onset"}


# --- Painleve's margin and the critical friction -----------------------------------------------------

def test_painleve_margin_of_the_disk_is_the_hand_derivation():
    """Row 1 of Eq. 5 is the only one with thetaddot; with N = g + cos(theta) thetaddot - sin(theta) thetadot^2
    and F_3 = N (cos theta + mu sin(beta) sin theta), beta = alpha - phi, its coefficient is k + cos^2 theta +
    mu sin(beta) sin theta cos theta.  The derived margin (a 3x3 determinant) must be that over k + cos^2."""
    th, beta, k, mu = sp.symbols("theta beta k mu")
    _, sliding, _ = coulomb.body("disk+coulomb")
    derived = sliding.painleve_margin
    hand = (k + sp.cos(th) ** 2 + mu * sp.sin(beta) * sp.sin(th) * sp.cos(th)) / (k + sp.cos(th) ** 2)
    rng = np.random.default_rng(3)
    for _ in range(20):
        t, a, f, kk, m = rng.uniform(0, 3), rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0.1, 1), rng.uniform(0, 2)
        values = {coulomb.theta: t, coulomb.slip_direction: a, coulomb.phi: f, disk.k: kk, coulomb.mu: m}
        got = float(derived.subs(values))
        want = float(hand.subs({th: t, beta: a - f, k: kk, mu: m}))
        # both evaluated by sympy in double from floats: a few ulps each; 1e-12 is far from any wrong sign or factor
        assert abs(got - want) <= 1e-12 * max(1, abs(want)), (got, want)


@pytest.mark.parametrize("name, params", [("disk+coulomb", {}), ("disk+coulomb", {"k": "0.5"}),
                                          ("ring+coulomb", {}), ("ring+coulomb", dict(ring.PRINTED))])
def test_critical_friction_is_the_closed_form(name, params):
    """min over theta of (I1 + H'^2) / |H H'| by search against the closed form 2 sqrt(k'(k' + 1)) with
    k' = I1 / (1 + h^2) (H = h cos theta + sin theta = sqrt(1 + h^2) sin(theta + atan h); the thin disk:
    h = 0, I1 = k, so 2 sqrt(k (k + 1)) = 1.1180 for k = 1/4).  Bound 1e-12 relative: the search is at 30
    digits, its float rounded once."""
    rolling, _, parameters = coulomb.body(name)
    values = {p.name: sp.nsimplify(sp.sympify(params.get(p.name, p.default))) for p in parameters if p.name != "mu"}
    if name == "disk+coulomb":
        i1, h = values["k"], 0
    else:
        i1, h = values["I1"], values["h"]
    kp = float(i1 / (1 + h ** 2))
    closed = 2 * math.sqrt(kp * (kp + 1))
    assert abs(coulomb.critical_friction(name, params) - closed) <= 1e-12 * closed


def test_below_the_critical_friction_the_margin_stays_positive_and_above_it_does_not():
    """P >= 1 - mu / mu_c for mu < mu_c; at mu = 1.01 mu_c some (theta, beta) give P < 0 (the control)."""
    _, sliding, _ = coulomb.body("disk+coulomb")
    f = sp.lambdify((coulomb.theta, coulomb.slip_direction, coulomb.phi, coulomb.mu),
                    sliding.painleve_margin.subs(disk.k, sp.Rational(1, 4)), "numpy")
    mu_c = coulomb.critical_friction("disk+coulomb")
    th, a = np.meshgrid(np.linspace(0.001, math.pi - 0.001, 801), np.linspace(-math.pi, math.pi, 801))
    assert f(th, a, 0.0, 0.99 * mu_c).min() >= 1 - 0.99 - 1e-12  # 1 - mu/mu_c, less numpy's double roundings
    assert f(th, a, 0.0, 1.01 * mu_c).min() < 0


JAM = ({"theta": "0.9786", "thetadot": "3.797", "phidot": "-8.716", "psidot": "10.751"}, ("22.205", "-16.361"))


def test_a_skid_above_the_critical_friction_ends_in_painleves_jam_and_below_it_does_not(capsys):
    """mu = 1.916 > 1.118: N grows like 1 / P while the disk slides (measured: the steps stall at P = 2.5e-7,
    N / (M g) = 1.6e6, t = 0.00207 s): painleve:jam, exit 1, with the run up to there.  The same skid at
    mu = 1.1 (below mu_c) slides, sticks and ends ok."""
    from verify.cli import main

    state, velocity = JAM
    with pytest.raises(IntegrationError) as err:
        hybrid.solve("disk+coulomb", "0.3", state, friction="1.916", velocity=velocity, n_eval=31)
    assert err.value.outcome == "painleve:jam" and len(err.value.trajectory.t) > 1
    assert "1.118" in str(err.value)  # the body's critical mu, named
    argv = ["trajectory", "disk+coulomb", "--friction", "1.916", "--velocity", ",".join(velocity), "--t-end", "0.3"]
    argv += [a for k, v in state.items() for a in ("--state", f"{k}={v}")]
    assert main(argv) == 1
    out, errtext = capsys.readouterr()
    assert "painleve:jam" in out and "Traceback" not in errtext
    below = hybrid.solve("disk+coulomb", "0.3", state, friction="1.1", velocity=velocity, n_eval=31)
    assert below.outcome == "ok" and "sticks" in [p.ended for p in below.phases]


# --- the start ----------------------------------------------------------------------------------

def test_the_regression_start_tells_one_story_in_double_and_quad(capsys):
    """theta = 1.2, psidot = 10, mu = 0.5 for 0.3 s (the issue's run to t = 2; the wrong switch was at 0.148 s): it ended event:contact_lost at theta = -2.59 with E + W
    off by 1e11 eps and exit 0, and quad told another story, because the onset's series was summed at
    J = 3 at the step cap (its terms compared with its divergent tail's).  Now both precisions take the same
    phases, E + W within 64 eps, and the ends agree within four times what one ulp of phidot moves the double
    run, plus 16 eps (measured: gap 1.1e-13 relative at t = 2, both precisions, 59 phases)."""
    from verify.cli import main

    start = {"theta": "1.2", "psidot": "10"}
    double = hybrid.solve("disk+coulomb", "0.3", start, friction="0.5", n_eval=11)
    quad = hybrid.solve("disk+coulomb", "0.3", start, friction="0.5", precision="quad", n_eval=11)
    assert double.outcome == quad.outcome == "ok"
    assert [(p.kind, p.ended) for p in double.phases] == [(p.kind, p.ended) for p in quad.phases]
    assert len(double.phases) > 3  # stick-slip: the case the series' switch failed on
    assert double.energy_plus_work_drift_in_eps <= 64 and quad.energy_plus_work_drift_in_eps <= 64
    conditioning = _conditioning("disk+coulomb", start, None, "0.5", double, t_end="0.3", n_eval=11)
    assert conditioning > 0
    assert _gap(double, quad) <= agreement_bound(double, conditioning), (_gap(double, quad), conditioning)
    assert main(["trajectory", "disk+coulomb", "--friction", "0.5", "--state", "theta=1.2", "--state", "psidot=10",
                 "--t-end", "0.3"]) == 0
    capsys.readouterr()


def _conditioning(body, state, velocity, mu, run, t_end="0.3", n_eval=31) -> float | None:
    """The largest end gap (as :func:`_gap`) one ulp of any of theta, thetadot, phidot, psidot moves the double
    run by, whether or not it changes the phases (a slip that grazes s = 0 sticks for an instant in one run and
    not in the other, with the same motion; measured: double 15 phases, quad 13, ends 1e-13 apart); None if a
    nudged run fails."""
    worst = 0.0
    for name in ("theta", "thetadot", "phidot", "psidot"):
        value = float(state.get(name, "0"))
        if value == 0:  # an exact 0 stays exact in every precision: there is no ulp of it to lose
            continue
        nudged = dict(state, **{name: repr(float(np.nextafter(value, np.inf)))})
        try:
            moved = hybrid.solve(body, t_end, nudged, friction=mu, velocity=velocity, n_eval=n_eval)
        except IntegrationError:
            return None
        worst = max(worst, _gap(moved, run))
    return worst


def agreement_bound(run, conditioning) -> float:
    """How far the double run's end may be from quad's: each of its N Taylor steps and switches commits about
    one ulp, carried to the end with about the one-ulp conditioning; as independent roundings they add like a
    random walk, sqrt(N) (measured: 0.7 to 5 times the one-ulp gap on 1 to 22 phases); 4 as margin, plus 16
    eps for the final roundings."""
    return 4 * math.sqrt(run.steps + len(run.phases)) * conditioning + 16 * 2.0 ** -52


def _gap(a, b) -> float:
    """Largest difference at the end, relative to each component's size (angles, rates; at least 1)."""
    return max(abs(float(a.y[i, -1]) - float(b.y[i, -1])) / max(1.0, abs(float(b.y[i, -1]))) for i in range(6))


# --- property: random starts ---------------------------------------------------------------------------

def _random_start(rng, body):
    hi = math.pi - 0.2 if body == "disk+coulomb" else math.pi / 2 - 0.1
    state = {"theta": f"{rng.uniform(0.2, hi):.6f}", "thetadot": f"{rng.uniform(-5, 5):.4f}",
             "phidot": f"{rng.uniform(-10, 10):.4f}", "psidot": f"{rng.uniform(-30, 30):.4f}"}
    velocity = None if rng.random() < 0.4 else (f"{rng.uniform(-30, 30):.4f}", f"{rng.uniform(-30, 30):.4f}")
    return state, velocity, f"{rng.uniform(0, 2):.4f}"


def _starts(seed, n):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        body = "disk+coulomb" if rng.random() < 0.6 else "ring+coulomb"
        out.append((body, *_random_start(rng, body)))
    return out


def _judge(body, state, velocity, mu, precision):
    """The run, or its named failure; asserts the property either way.  Returns the run or None."""
    try:
        sol = hybrid.solve(body, "0.3", state, friction=mu, velocity=velocity, precision=precision, n_eval=31)
    except IntegrationError as err:
        assert err.outcome in NAMED, (err.outcome, str(err))
        return None
    assert sol.outcome == "ok" or sol.outcome.startswith("event:"), sol.outcome
    lo, hi = (0.0, math.pi) if body == "disk+coulomb" else (0.0, math.pi / 2)
    theta = np.array([float(v) for v in sol["theta"]])
    ended_at_end = sol.phases[-1].ended in ("lies_flat", "rim_switch")
    inner = theta[:-1] if ended_at_end else theta
    assert np.all((lo < inner) & (inner < hi)), (body, state, velocity, mu, theta.min(), theta.max())
    if ended_at_end:  # on the end the event reached, within the guard's own allowance (hybrid_guards.EVENT_ULPS)
        allowance = hybrid_guards.EVENT_ULPS * sol.precision.eps * (abs(float(sol["thetadot"][-1])) * 1.0 + 1.0)
        assert lo - allowance <= theta[-1] <= hi + allowance
    # the bound of the run's own steps and switches (a property of the handed-out run, checked here again)
    assert sol.energy_plus_work_drift_in_eps <= hybrid_guards.balance_bound_in_eps(sol.steps, len(sol.phases) - 1)
    return sol


@pytest.mark.parametrize("case", _starts(11, 24), ids=lambda c: f"{c[0][:4]}-mu{c[3]}")
def test_random_coulomb_starts_end_ok_inside_the_domain_or_with_a_named_failure(case):
    _judge(*case, "double")


@pytest.mark.slow
@pytest.mark.parametrize("case", _starts(2026, 300), ids=lambda c: f"{c[0][:4]}-mu{c[3]}")
def test_300_random_coulomb_starts_double_and_quad(case):
    """300 starts, both bodies, mu from 0 to 2: the property in double and quad, and where both are handed
    out, their ends agree within :func:`agreement_bound` of the one-ulp conditioning measured on each start
    (the phases may differ by a slip grazing s = 0: the ends are compared, not the phase lists)."""
    body, state, velocity, mu = case
    double = _judge(body, state, velocity, mu, "double")
    quad = _judge(body, state, velocity, mu, "quad")
    if double is None or quad is None:
        return
    if double.outcome == "ok":
        assert double.t[-1] == 0.3 and float(quad.t[-1]) == 0.3
    conditioning = _conditioning(body, state, velocity, mu, double)
    if conditioning is None:
        pytest.skip("a run one ulp away from the start failed: no conditioning measured")
    assert _gap(double, quad) <= agreement_bound(double, conditioning), case


def test_a_run_whose_end_falls_inside_a_slip_onsets_series_ends_there(monkeypatch):
    """The series of a slips onset at t = 0.2990584 reaches t1 past t_end = 0.3 in double (not in quad): the
    run ended ok at the onset, its state 0.065 (relative) from quad's at t = 0.3.  The output times between an
    onset and heyoka's start now come from the onset's own series; both end at 0.3 and agree within
    :func:`agreement_bound` (measured: 5e-13 relative against the 0.065 of the wrong end)."""
    case = ("disk+coulomb", {"theta": "2.623285", "thetadot": "0.4530", "phidot": "-9.6958", "psidot": "-10.4970"},
            ("-1.3625", "-17.1864"), "0.6997")
    double = _judge(*case, "double")
    quad = _judge(*case, "quad")
    assert double.outcome == quad.outcome == "ok" and double.t[-1] == 0.3 and float(quad.t[-1]) == 0.3
    assert [p.kind for p in double.phases] == [p.kind for p in quad.phases] and len(double.phases) == 9
    conditioning = _conditioning(*case, double)
    assert conditioning is not None and _gap(double, quad) <= agreement_bound(double, conditioning)
    # negative control: without the onset's outputs the run stops short of t_end, and says so
    monkeypatch.setattr(hybrid_run.Run, "outputs_before", lambda self, t, t0, state_at: [])
    with pytest.raises(IntegrationError) as err:
        hybrid.solve(case[0], "0.3", case[1], friction=case[3], velocity=case[2], n_eval=31)
    assert err.value.outcome == "failed:short_run"


# --- the rolling models with friction= -------------------------------------------------------------------

def _rolling_starts(seed, n):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        name = "disk" if rng.random() < 0.6 else "ring"
        hi = math.pi - 0.2 if name == "disk" else math.pi / 2 - 0.1
        state = {"theta": f"{rng.uniform(0.2, hi):.6f}", "thetadot": f"{rng.uniform(-5, 5):.4f}",
                 "phidot": f"{rng.uniform(-10, 10):.4f}", "psidot": f"{rng.uniform(-30, 30):.4f}"}
        out.append((name, state, f"{rng.uniform(0, 2):.4f}"))
    return out


@pytest.mark.parametrize("case", _rolling_starts(7, 40), ids=lambda c: f"{c[0]}-mu{c[2]}")
def test_random_rolling_starts_with_friction_stop_at_slips_or_hold_mu(case):
    """A rolling run with friction=mu ends ok with mu_req <= mu at every output, or at the slips event with
    mu_req = mu there, or at another event, inside the domain; or its start is refused (it needs more than mu
    at t = 0); or it fails with a named failure.  mu_req to the engine's slack, SLIP_SLACK_EPS eps times
    max(1, mu) (verify.engine.failures: the friction cfunc's rounding; the slips event is located to eps)."""
    from verify.engine.validation import InvalidStart

    name, state, mu = case
    try:
        sol = solve(name, "0.3", state, friction=mu, n_eval=31)
    except InvalidStart as err:
        assert err.reason in ("slips", "normal_force"), err
        return
    except IntegrationError as err:
        assert err.outcome in NAMED, err
        return
    need = np.array([float(v) for v in sol.friction_required])
    slack = SLIP_SLACK_EPS * 2.0 ** -52 * max(1.0, float(mu))
    lo, hi = (0.0, math.pi) if name == "disk" else (0.0, math.pi / 2)
    theta = np.array([float(v) for v in sol["theta"]])
    if sol.outcome == "ok":
        assert np.all(need <= float(mu) + slack) and np.all((lo < theta) & (theta < hi))
    else:
        assert sol.outcome.startswith("event:"), sol.outcome
        assert np.all(need[:-1] <= float(mu) + slack) and np.all((lo < theta[:-1]) & (theta[:-1] < hi))
        if sol.outcome == "event:slips":
            assert abs(need[-1] - float(mu)) <= slack

"""A friction coefficient in the sweeps: the terminal event ``slips`` per batch lane against
``solve(..., friction=MU)`` on the same starts, a wrong event function as negative control, the spec's
new keys and the categorical map.

The lanes and the single engine integrate the same equations with the same event function
(``verify.engine.compile.slip_event_function``) but take their own steps, so they agree to the
integration error, not bit for bit; the bounds below are argued in units of eps.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest

from verify.cli import main
from verify.engine.single import solve
from verify.precision import parse_precision
from verify.sweep import SPECS, InvalidPoint, SpecError, load, parse
from verify.sweep.engine import run_chunk, validate_points
from verify.sweep.plot import categories, render

EPS = np.finfo(float).eps
TILT = 1e-3
T_END = 1.0

SPEC = """
[sweep]
name = "friction-small"
model = "disk"
t_end = {t_end}
samples = 41
chunk = 64
store = "unused.sqlite"

[params]
k = 0.25
g = 980

[start]
steady = "diameter-spin"

[[axis]]
name = "phidot"
from = 0
to = 36
count = 4

[[axis]]
name = "friction"
from = 0.05
to = 1.0
count = 3
scale = "log"

[[axis]]
name = "tilt"
from = {tilt}
to = {tilt}
count = 1

[record]
quantities = ["slipped", "t_slip", "theta_at_slip", "max_friction_required_on_grid"]

[plot]
x = "phidot"
y = "friction"
quantity = "outcome"
"""


def small_spec(t_end=T_END):
    return parse(SPEC.format(t_end=t_end, tilt=TILT))


def single(row, t_end, **kw):
    return _single(row["in_phidot"], t_end, tuple(sorted(kw.items())))


@lru_cache(maxsize=None)  # the same starts at both widths: run once
def _single(phidot, t_end, kw):
    start = {"theta": repr(math.pi / 2 + TILT), "phidot": repr(phidot)}
    return solve("disk", repr(t_end), start, params={"k": "0.25", "g": "980"}, **dict(kw))


@lru_cache(maxsize=None)
def _mismatch_in_eps(phidot, t, mu) -> float:
    return mismatch_in_eps({"in_phidot": phidot}, t, mu)


def mismatch_in_eps(row, t, mu) -> float:
    """|mu_req - mu| / (mu eps) at time ``t`` (a double, read exactly) of a quad run without the event
    from the lane's own start (the doubles, read exactly): how far from slipping a reported event time is."""
    quad = parse_precision("quad")
    start = {"theta": math.pi / 2 + TILT, "phidot": row["in_phidot"]}  # floats: read exactly
    ref = solve("disk", quad.number(t), start, params={"k": "0.25", "g": "980"}, precision="quad", n_eval=2)
    return float(abs(ref.friction_required[-1] - quad.number(mu)) / quad.number(mu)) / EPS


def disagreements(rows, t_end) -> list:
    """Every way a lane's record differs from solve(friction=...) on its start, beyond the bounds.

    Outcome and ``slipped``: equal.  The slip time: the two take their own steps, so their event
    times differ (by 17-94 eps t measured); each is judged by what the motion needs there, from a
    quad run without the event from the same doubles (``mismatch_in_eps``).  These starts sit near
    the unstable upright equilibrium, whose flow amplifies a step's rounding: the single engine's
    own mismatch m_s (28-490 eps here, against 0.07-4.7 eps on tests/test_slip_event.py's start) is
    that start's measure of it.  The lane is an integration of the same kind (same equations,
    tolerance and step cap; its steps taken as at most twice the single's S), so its mismatch is
    allowed 8 m_s + 8 (1 + 2 S) eps: measured at most 4.9 m_s.  theta at the slip: the time shift
    times |thetadot|, plus 8 eps a step of the lane (measured: 0-2 ulp).  The largest need on the
    grid (lanes that do not slip): the same samples of both runs, whose states differ by the
    integration error; 1e-9 relative is ~10^3 above it and far below any reading of a coefficient.
    """
    out = []
    for r in rows:
        mu = r["in_friction"]
        sol = single(r, t_end, friction=repr(mu), n_eval=41)
        slipped = sol.outcome == "event:slips"
        if r["outcome"] != ("slips" if slipped else sol.outcome.removeprefix("event:")):
            out.append((r["idx"], "outcome", r["outcome"], sol.outcome))
            continue
        if r["slipped"] != float(slipped):
            out.append((r["idx"], "slipped", r["slipped"], slipped))
        steps = sol.steps
        if slipped:
            t_single = float(sol.t_events["slips"])
            m_single = _mismatch_in_eps(r["in_phidot"], t_single, mu)
            m_lane = _mismatch_in_eps(r["in_phidot"], r["t_slip"], mu)
            # the single engine's own mismatch sets the yardstick, so it is capped: measured 28-490 eps
            if not m_single <= 1e3:
                out.append((r["idx"], "single engine's slip mismatch in eps above its cap 1e3", m_single))
            if not m_lane <= 8 * m_single + 8 * (1 + 2 * steps):
                out.append((r["idx"], "t_slip", r["t_slip"], t_single, f"lane mismatch {m_lane:.3g} eps",
                            f"single mismatch {m_single:.3g} eps"))
            thetadot = abs(float(sol["thetadot"][-1]))
            allowed = thetadot * abs(r["t_slip"] - t_single) + 8 * (1 + 2 * steps) * EPS * abs(r["theta_at_slip"])
            if not abs(r["theta_at_slip"] - float(sol["theta"][-1])) <= allowed:
                out.append((r["idx"], "theta_at_slip", r["theta_at_slip"], float(sol["theta"][-1])))
        else:
            if not (math.isnan(r["t_slip"]) and math.isnan(r["theta_at_slip"])):
                out.append((r["idx"], "t_slip of a run that did not slip", r["t_slip"]))
            need = float(np.nanmax(sol.friction_required))
            if not abs(r["max_friction_required_on_grid"] - need) <= 1e-9 * need:
                out.append((r["idx"], "max_friction_required_on_grid", r["max_friction_required_on_grid"], need))
            if not need < mu * (1 - 1e-3):  # a start near tangency would make the verdict a coin toss
                out.append((r["idx"], "too close to the coefficient to judge", need, mu))
    return out


@pytest.mark.parametrize("width", [4, 8])
def test_every_lane_agrees_with_solve_with_the_same_coefficient(width):
    rows = run_chunk(small_spec(), 0, threads=1, batch_size=width)
    assert len(rows) == 12
    assert {r["outcome"] for r in rows} == {"slips", "ok"}  # both verdicts are exercised
    assert disagreements(rows, T_END) == []


def test_negative_control_a_wrong_event_function_is_caught(monkeypatch):
    """The event with mu not squared lands where mu_req^2 = mu: later than it should for mu < 1."""
    from verify.engine import compile as comp

    def wrong(model):
        fx, fy = (a / comp.g for a in model.horizontal_acceleration)
        return (fx ** 2 + fy ** 2) / comp.FRICTION - comp.contact_event_function(model) ** 2

    spec = small_spec(t_end=0.75)  # its own cooldown, hence its own cached system
    from verify.engine import ensemble, lanes

    monkeypatch.setattr(lanes, "slip_event_function", wrong)
    ensemble.clear()
    try:
        rows = run_chunk(spec, 0, threads=1, batch_size=4)
    finally:
        monkeypatch.undo()
        ensemble.clear()
    assert len(disagreements(rows, 0.75)) >= 3


def test_a_lane_without_the_coefficient_runs_as_before():
    """The coefficient is a per-lane parameter: a sweep without one compiles no slip event."""
    spec = load(SPECS / "disk-diameter-spin.toml")
    assert not spec.slips and spec.friction is None
    from verify.engine.ensemble import ensemble

    assert "slips" not in ensemble("disk", "full", 4, 21.0, False, False).lanes.events
    assert ensemble("disk", "full", 4, 21.0, False, True).lanes.events[-1] == "slips"


# --- the spec --------------------------------------------------------------------------------------

def test_the_shipped_friction_spec_is_valid_and_slips():
    spec = load(SPECS / "disk-diameter-spin-friction.toml")
    assert spec.slips and spec.friction is None
    assert [a.name for a in spec.axes] == ["phidot", "friction", "tilt"]
    assert spec.plot["quantity"] == "outcome"


def test_a_fixed_coefficient_is_read_from_params():
    spec = parse(SPEC.format(t_end=1, tilt=TILT).replace('name = "friction"\nfrom = 0.05\nto = 1.0\ncount = 3\n'
                                                          'scale = "log"', 'name = "psidot"\nfrom = 0\nto = 0\ncount = 1')
                 .replace("g = 980", "g = 980\nfriction = 0.3").replace('y = "friction"', 'y = "psidot"'))
    assert spec.friction == 0.3 and spec.slips and "friction" not in spec.params


@pytest.mark.parametrize("change, message", [
    (('model = "disk"', 'model = "sliding-disk"'), "no rolling contact"),
    (("g = 980", "g = 980\nfriction = 0.3"), "both an axis and a fixed value"),
    (("from = 0.05", "from = 0"), "a log axis needs positive ends"),
    (('from = 0.05\nto = 1.0\ncount = 3\nscale = "log"', 'from = -1\nto = 1.0\ncount = 3'),
     "a friction coefficient must be positive"),
])
def test_bad_friction_keys_are_refused_naming_them(change, message):
    text = SPEC.format(t_end=1, tilt=TILT).replace(*change)
    with pytest.raises(SpecError, match=message):
        parse(text)


@pytest.mark.parametrize("value, message", [("0", "must be positive"), ("-0.5", "must be positive"),
                                            ('"x"', "is not a number")])
def test_a_bad_fixed_coefficient_is_refused(value, message):
    text = SPEC.format(t_end=1, tilt=TILT).replace(
        '[[axis]]\nname = "friction"\nfrom = 0.05\nto = 1.0\ncount = 3\nscale = "log"\n', "").replace(
        "g = 980", f"g = 980\nfriction = {value}").replace('y = "friction"', 'y = "tilt"')
    with pytest.raises(SpecError, match=message):
        parse(text)


def test_slip_records_need_a_coefficient_and_categories_need_every_axis_drawn():
    no_mu = SPEC.format(t_end=1, tilt=TILT).replace(
        '[[axis]]\nname = "friction"\nfrom = 0.05\nto = 1.0\ncount = 3\nscale = "log"\n', "").replace(
        'y = "friction"', 'y = "tilt"')
    with pytest.raises(SpecError, match="slipped needs a friction coefficient"):
        parse(no_mu)
    parse(no_mu.replace('"slipped", "t_slip", "theta_at_slip", ', ""))  # the need alone is fine
    hidden = SPEC.format(t_end=1, tilt=TILT).replace("from = 0.001\nto = 0.001\ncount = 1",
                                                    "from = 0.001\nto = 0.002\ncount = 2")
    with pytest.raises(SpecError, match="drawn as categories.*'tilt'"):
        parse(hidden)


def test_the_command_line_refuses_a_bad_coefficient_in_one_line(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(SPEC.format(t_end=1, tilt=TILT).replace("from = 0.05", "from = -0.05"))
    assert main(["sweep", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert "friction" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "unused.sqlite").exists()


def test_a_start_that_already_needs_the_coefficient_refuses_the_sweep():
    # at tilt 0.3 the diameter spin at 36 s^-1 already needs more than 0.05
    spec = parse(SPEC.format(t_end=1, tilt=0.3).replace("from = 0\nto = 36", "from = 36\nto = 36").replace(
        "count = 4", "count = 1"))
    with pytest.raises(InvalidPoint, match="mu_req") as err:
        validate_points(spec)
    assert err.value.reason == "slips"


# --- the map ------------------------------------------------------------------------------------

def test_the_map_draws_categories_with_the_three_named_ones():
    spec = small_spec()
    rows = [{"idx": i, "in_phidot": p, "in_friction": m, "in_tilt": TILT, "outcome": o, "slipped": float(o == "slips")}
            for i, (p, m, o) in enumerate([(0.0, 0.05, "slips"), (36.0, 1.0, "ok"), (12.0, 1.0, "failed:non_finite")])]
    assert categories(spec, rows, "outcome") == ("slipped", "did not slip by t_end", "lost contact first",
                                                 "failed:non_finite")
    assert categories(spec, rows, "slipped") == ("yes", "no", "failed:non_finite (no value)")
    assert render(spec, rows).startswith(b"\x89PNG")

"""MuJoCo adapter (examples/engines/mujoco_adapter.py): the start read back, a short scored run, negative controls.

Skipped where MuJoCo is not installed (pip ``mujoco``; measured with 4.0.0).

The floor of the score: disk-standard-1 to t = 0.1 s at the "best" setting scored 4.08 digits
(min over components and times) on MuJoCo 4.0.0, x86-64.  MuJoCo is deterministic for one
build, but another build (compiler, FMA, another MuJoCo release) changes the contact solver's
iterates at roundoff level, and the run is chaotic enough near the stiff contact that such
changes grow; across the sweep, neighbouring settings (dt doubled: 4.13, RK4 instead of
implicitfast: 4.03) moved the score by up to 0.1 digits.  A floor of 3.75 (0.33 digits, a
factor 2 in the error, three times that spread) catches a real regression -- the default
contact scores below 0 and a stiffness 10 times lower 3.6 -- without depending on the last bit.
"""
from __future__ import annotations


import pytest

from verify.leaderboard import load_adapter

mujoco = pytest.importorskip("mujoco", reason="MuJoCo is not installed (pip install mujoco)")

CASE = "disk-standard-1"
T_END = 0.1
MEASURED = 4.17  # min digits to t = 0.1 s, best setting, MuJoCo 4.0.0, on the scorer's whole-case scales
FLOOR = MEASURED - 0.33


@pytest.fixture(scope="module")
def adapter():
    return load_adapter("mujoco")


@pytest.fixture(scope="module")
def best_run(adapter):
    return adapter.run_case(CASE, "best", T_END)


def test_start_read_back(adapter):
    """The engine's state at t = 0, read back (omega turned from body to world), is the case's start."""
    import numpy as np

    from models.symbols import STATE_NAMES
    from verify.frames import euler_to_b

    record = adapter.case_record(CASE)
    body = adapter.body_of(record, adapter.BEST["half_height"])
    m = mujoco.MjModel.from_xml_string(adapter.mjcf(body, adapter.BEST))
    d = mujoco.MjData(m)
    start = {n: np.array([float(record["initial_state"][n])]) for n in STATE_NAMES}
    b0 = {c: float(v[0]) for c, v in euler_to_b("disk", start, body["params"]).items()}
    adapter.set_start(mujoco, m, d, b0)
    back = adapter.read_state(mujoco, m, d)
    assert adapter.check_start(back, b0, record) <= 1e-12
    # the free joint's angular velocity is in body components: it is not the world omega here
    assert max(abs(d.qvel[3 + i] - b0[c]) for i, c in enumerate(("wx", "wy", "wz"))) > 1.0


def test_best_short_run_scores(best_run):
    r = best_run
    assert r["outcome"] == "ok", r["outcome"]
    assert r["start_readback"] <= 1e-12
    assert r["score"]["min_digits"] >= FLOOR, r["score"]
    assert r["score"]["contact_height"] < 1e-4  # the rim stays on the plane (a 1e-5 thin cylinder, stiff contact)


def test_wrong_gravity_scores_far_lower(adapter, best_run):
    """Negative control: MuJoCo's own gravity (-9.81, SI) instead of the case's 980 in R = 1 cm units."""
    import json

    xml = adapter.mjcf
    try:
        adapter.mjcf = lambda body, s: xml(dict(body, g=9.81), s)
        r = adapter.run_case(CASE, "best", T_END)
    finally:
        adapter.mjcf = xml
    assert r["outcome"] == "ok", r["outcome"]
    assert r["score"]["min_digits"] < best_run["score"]["min_digits"] - 2, json.dumps(r["score"])


def test_start_in_wrong_frame_is_refused(adapter):
    """Negative control: omega given to qvel in world components (the free joint wants body ones) is caught."""
    set_start = adapter.set_start

    def world_omega(mujoco_, m, d, b0):
        set_start(mujoco_, m, d, b0)
        d.qvel[3:6] = [b0["wx"], b0["wy"], b0["wz"]]
        mujoco_.mj_forward(m, d)

    try:
        adapter.set_start = world_omega
        r = adapter.run_case(CASE, "best", 0.01)
    finally:
        adapter.set_start = set_start
    assert r["outcome"].startswith("error: MuJoCo's start read back differs"), r["outcome"]
    assert r["score"] is None


# --- the Coulomb cases (finite friction: the coin rolls, slides and sticks) ------------------------------------
COULOMB = "coin-coulomb-skid-1"
T_COULOMB = 0.125  # s: the skid slides from the start, sticks (the reference at 0.0765) and rolls 48 ms after it
#: min digits to T_COULOMB at "best", MuJoCo 4.0.0: 1.13 (phidot at t = 0.125); deterministic on one build, the
#: margin as the disk's above (0.33 digits: a factor 2 in the error).  MuJoCo's skid sticks at 0.0690, 7 ms
#: before the reference's 0.0765 (the coin hops while it slides: the adapter's docstring), seen by the contact's
#: slip speed at 1 ms outputs; the test holds it to 2 ms: a run that never sticks, or sticks at once, fails.
COULOMB_MEASURED = 1.13
STICKS_AT = 0.0690


@pytest.fixture(scope="module")
def coulomb_run(adapter):
    return adapter.run_case(COULOMB, "best", T_COULOMB)


def test_a_skid_is_scored_and_sticks_once(coulomb_run):
    r = coulomb_run
    assert r["outcome"] == "ok" and r["start_readback"] <= 1e-12
    assert r["parameters"]["friction"] == "0.3 0 0"  # mu on both geoms: MuJoCo takes the element-wise max
    s = r["score"]
    assert s["partial"] and s["t_last"] == pytest.approx(T_COULOMB)
    assert [w["kind"] for w in s["switches"]] == ["sliding -> rolling"]
    assert s["min_digits"] >= COULOMB_MEASURED - 0.33, s["verdict"]
    (slide,) = r["friction"]["run"]["slides"]  # one slide, from the start to the stick
    assert slide[0] == 0 and abs(slide[1] - STICKS_AT) < 2e-3, slide


def test_a_skid_starts_with_the_cases_velocity_read_back(adapter):
    """The skid's centre of mass moves at the case's (half the rolling speed): set, read back, a wrong one refused."""
    import numpy as np

    record = adapter.case_record("coin-coulomb-skid-1")
    s = adapter.with_friction(dict(adapter.BEST), record)
    body = adapter.body_of(record, s["half_height"])
    m = mujoco.MjModel.from_xml_string(adapter.mjcf(body, s))
    d = mujoco.MjData(m)
    b0 = adapter.friction_cases.start_b(record, body["model"], body["params"])
    adapter.set_start(mujoco, m, d, b0)
    back = adapter.read_state(mujoco, m, d)
    assert adapter.check_start(back, b0, record) <= 1e-12
    assert (back["vx"], back["vy"]) == pytest.approx((36.35066065398451, 0.0), abs=1e-12)
    slip = adapter.friction_cases.slip_speed({k: np.array([v]) for k, v in back.items()}, record)
    assert slip[0] == pytest.approx(36.35066065398451, rel=1e-12)  # the contact slides at t = 0: a skid
    with pytest.raises(RuntimeError, match="differs from case"):
        adapter.check_start(back, dict(b0, vx=b0["vx"] * (1 + 1e-9)), record)

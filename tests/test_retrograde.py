"""The retrograde-turn reading: the orbit is the slow path of the centre of mass, not the turning of
the line of nodes.  Negative controls on synthetic runs, the conservative ring, a mirrored start,
and the study's summary.

A synthetic run here is a CM path made of loops (one per nutation, at the phi rate) on a guide
circle (the slow path), with theta nutating once per loop: exactly the two motions the reading
has to tell apart.
"""
from __future__ import annotations

import math
import sys

import numpy as np
import pytest

from verify.studies import orbits
from verify.studies.orbits import senses
from verify.sweep import engine, parse
from verify.sweep.spec import SENSE_KEYS
from verify.report import retrograde as retrograde_section
from verify.studies import retrograde

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

NUTATION = 2 * math.pi * 5  # 5 nutations (and loops) a second
T_END = 40.0


def synthetic(loop_angle, guide_angle, spin=1.0, guide_radius=1.0, loop_radius=0.3):
    """(t, y, omega_z) of a run whose CM draws loops at ``loop_angle(t)`` (= phi, the line of nodes) on a
    guide circle at ``guide_angle(t)``; theta has its maxima once per nutation, where the loop phase is 0."""
    t = np.linspace(0.0, T_END, 16001)  # 2.5 ms: 80 points a nutation
    y = np.zeros((len(t), 8))
    phi, alpha = loop_angle(t), guide_angle(t)
    y[:, orbits.TH] = 1.0 + 0.01 * np.cos(NUTATION * t)
    y[:, orbits.PH] = phi
    y[:, orbits.X] = guide_radius * np.cos(alpha) + loop_radius * np.cos(phi)
    y[:, orbits.Y] = guide_radius * np.sin(alpha) + loop_radius * np.sin(phi)
    return t, y, np.full(len(t), spin)


def test_slow_path_that_reverses_under_one_way_loops_is_a_retrograde_turn():
    """The guide (slow path) turns at 0.5 Hz (1 - 2t/T): counter-clockwise, then clockwise; the loops and
    phi turn counter-clockwise throughout.  The reading must see the reversal; the former reading (the
    net turn of phi) must not -- that is the defect this reading mends."""
    t, y, wz = synthetic(lambda t: NUTATION * t, lambda t: 2 * math.pi * 0.5 * (t - t**2 / T_END))
    s = senses(t, y, wz)
    assert (s["orbit_start"], s["orbit_end"], s["orbit_last"]) == (1, -1, -1)
    assert (s["spin_start"], s["spin_end"]) == (1, 1)
    assert s["retrograde_turn"] == 1 and s["retrograde_by_last_read"] == 1 and s["orbit_reversal"] == 1
    # the guide stops at t = 20 s; windows within ~8 s of that turn less than half a turn
    assert 20 < s["t_retrograde"] < 30 and s["t_retrograde"] == s["t_orbit_reversal"]
    assert s["windows"] == 16 and 0 < s["windows_undecided"] < 8
    assert (s["node_turn_start"], s["node_turn_end"], s["node_retrograde_turn"]) == (1, 1, 0)
    assert s["points_per_nutation"] == pytest.approx(80, rel=1e-3)


def test_loops_that_reverse_over_a_steady_slow_path_are_no_turn():
    """The loops (and phi) reverse at T/2; the guide keeps turning counter-clockwise at 0.5 Hz.  The
    reading must not call it a turn; the former reading does."""
    half = T_END / 2
    t, y, wz = synthetic(lambda t: NUTATION * np.where(t < half, t, T_END - t), lambda t: 2 * math.pi * 0.5 * t)
    s = senses(t, y, wz)
    assert (s["orbit_start"], s["orbit_end"], s["orbit_last"]) == (1, 1, 1)
    assert s["retrograde_turn"] == 0 and s["retrograde_by_last_read"] == 0 and s["orbit_reversal"] == 0
    assert math.isnan(s["t_retrograde"])
    assert (s["node_turn_start"], s["node_turn_end"], s["node_retrograde_turn"]) == (1, -1, 1)


def test_a_window_whose_two_measures_disagree_is_undecided():
    """Loops at 0.85 turn a nutation (no scale separation, as a ring near flat): once per nutation the CM
    steps back 0.15 turn, while its mean over a nutation keeps circling forwards.  No sense is picked."""
    t, y, wz = synthetic(lambda t: 0.85 * NUTATION * t, lambda t: 0 * t, guide_radius=0.0)
    s = senses(t, y, wz)
    assert s["windows_undecided"] == s["windows"] > 0
    assert s["strobe_last"] < -0.5 and s["mean_last"] > 0.5  # both decide, opposite ways
    assert math.isnan(s["orbit_start"]) and math.isnan(s["retrograde_turn"]) and s["orbit_last"] == 0


# --- runs of the ring ------------------------------------------------------------------------------

# every ring run here lasts 10 s: the compiled system is cached per (model, lanes, t_end)
def control_spec(mechanism: str, t_end=10, samples=4001):
    """The mechanism's conservative control (c = 0) at the four corner bodies, ``t_end`` seconds."""
    data = tomllib.loads(retrograde.control_text(mechanism))
    data["sweep"].update(t_end=t_end, samples=samples, chunk=4)
    for axis in data["axis"]:
        axis["count"] = 2
    return parse(retrograde.dumps_toml(data), f"{mechanism} control", store="unused.sqlite")


@pytest.mark.parametrize("mechanism", retrograde.MECHANISMS)
def test_conservative_controls_do_not_turn(mechanism):
    """c = 0 at the four corners (flat disk, flat ring, thick disk, paper's ring), 10 s, output every
    2.5 ms: no run turns or reverses its slow path, and the flat ring decides (not a vacuous pass).  The
    other three are undecided: their once-per-nutation samples step 0.26 turn, past the 0.25 that
    verify.circling accepts as unaliased."""
    spec = control_spec(mechanism)
    rows = engine.run_chunk(spec, 0, threads=2, senses=senses)
    assert len(rows) == 4 and all(r["outcome"] == "ok" for r in rows)
    assert not any(r["retrograde_turn"] == 1 or r["retrograde_by_last_read"] == 1 or r["orbit_reversal"] == 1
                   for r in rows)
    decided = [r for r in rows if not math.isnan(r["retrograde_turn"])]
    assert [(r["in_h"], r["in_w"]) for r in decided] == [(0.01, 0.1366)]
    assert all(r["retrograde_turn"] == 0 and r["orbit_start"] == r["orbit_last"] == r["spin_end"] == 1
               and r["windows_undecided"] == 0 for r in decided)
    assert all(r["node_retrograde_turn"] == 0 for r in rows)


MIRROR = """
[sweep]
name = "mirror"
model = "ring+rolling-friction"
t_end = 10
samples = 4001
chunk = 4
store = "unused.sqlite"

[geometry]
kind = "annulus"

[params]
h = 0.26464
w = 0.48196
c = {c}

[start]
theta = 1.2
phidot = {phidot}
psidot = {psidot}

[[axis]]
name = "x"
from = 0
to = 0
count = 1

[record]
quantities = [{keys}]

[stop]
theta_below = 0.1
"""


@pytest.mark.parametrize("c", ["0", "0.1"])
def test_a_mirrored_start_flips_orbit_and_spin_together(c):
    """(phidot, psidot) -> (-phidot, -psidot) is the mirror image of the run (x -> -x: theta is the same
    to the bit), so every sense flips and every verdict stays."""
    keys = ", ".join(f'"{k}"' for k in SENSE_KEYS)
    specs = [parse(MIRROR.format(c=c, phidot=sign * 40, psidot=sign * 5, keys=keys)) for sign in (1, -1)]
    rows = [engine.run_chunk(spec, 0, senses=senses)[0] for spec in specs]
    a, b = rows
    assert a["t_stop"] == b["t_stop"] and a["windows"] == b["windows"] >= 2
    flips = ("orbit_start", "orbit_end", "orbit_last", "spin_start", "spin_end", "node_turn_start", "node_turn_end",
             "path_start", "path_end")
    assert any(a[k] != 0 for k in flips)
    for k in flips:
        assert (math.isnan(a[k]) and math.isnan(b[k])) or a[k] == -b[k], k
    for k in ("retrograde_turn", "retrograde_by_last_read", "orbit_reversal", "t_retrograde", "windows_undecided",
              "node_retrograde_turn", "roll_reversal"):
        assert (math.isnan(a[k]) and math.isnan(b[k])) or a[k] == b[k], k
    assert a["spin_start"] == a["orbit_start"] == 1  # the start goes with its spin


# --- the study ----------------------------------------------------------------------------------------

def corners(text: str, name: str, store, t_end=10, samples=4001):
    """A study spec cut to the four corner bodies (h, w at their ends), ``t_end`` seconds."""
    data = tomllib.loads(text)
    data["sweep"].update(t_end=t_end, samples=samples, chunk=8)
    for axis in data["axis"]:
        if axis["name"] in ("h", "w"):
            axis["count"] = 2
    return parse(retrograde.dumps_toml(data), name, store=str(store))


def test_study_summary_counts_and_renders(tmp_path):
    """summarise and render_markdown over the corners (both c and the control), 10 s runs."""
    from verify.sweep import Store, run_sweep

    study = {}
    for m in retrograde.MECHANISMS:
        results = {}
        for label, text in (("sweep", retrograde.spec_path(m).read_text()), ("control", retrograde.control_text(m))):
            spec = corners(text, f"{m} {label}", tmp_path / f"{m}-{label}.sqlite")
            run_sweep(spec, threads=2, progress=False, senses=senses)
            with Store(spec) as store:
                results[label] = (spec, store.rows(), 0.0)
        study[m] = s = retrograde.summarise(m, results)
        assert s["trajectories"] == 8 and s["control"]["runs"] == 4
        assert s["judged"] + s["undecided"] == 8 and s["turned"] <= s["judged"]
        assert s["control"]["turned"] == s["control"]["read_turned"] == 0
        assert len(s["bodies"]) == 8
        assert {b["retrograde_turn"] for b in s["bodies"]} <= {"turns", "does not turn", "undecided"}
        assert s["min_points_per_nutation"] >= 20
        figures = retrograde_section.figures(m, *results["sweep"][:2])
        assert sorted(figures) == [f"retrograde-{m}-roll.png", f"retrograde-{m}.png"]
        assert all(im.data[:8] == b"\x89PNG\r\n\x1a\n" and im.alt for im in figures.values())
    text = "\n".join(retrograde_section.render_markdown(study))
    assert "## The ring's retrograde turn: air drag or rolling friction" in text and "issue" not in text.lower()
    assert "slow path" in text and "node-turn reading" in text.lower()


@pytest.mark.slow
def test_full_study_controls_do_not_turn_and_resolve_the_nutation():
    """The study as `make report` runs it (~25-40 s on 2 cores): no conservative control turns, and the
    output grid holds at least 20 points in the shortest nutation of any run."""
    study = retrograde.run_study().summaries  # (its speed is the benchmark's business, not a test's)
    for m, s in study.items():
        assert s["control"]["turned"] == s["control"]["read_turned"] == s["control"]["orbit_reversal"] == 0, m
        assert s["min_points_per_nutation"] >= 20, m
        assert s["trajectories"] == 72 and s["judged"] + s["undecided"] == 72

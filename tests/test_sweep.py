"""Sweeps: the TOML contract, the store (chunks, resume after a kill, no duplicates), Dask, the
engine against scalar runs, the dissipative ring terms, and the retrograde-turn senses.

Everything is written to temporary folders.
"""
from __future__ import annotations

import ast
import math
import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from verify.cli import main
from verify.engine.single import solve
from verify.sweep import SPECS, SpecError, Store, StoreError, load, parse, run_sweep
from verify.studies.orbits import senses

ROOT = Path(__file__).resolve().parent.parent

SMALL = """
[sweep]
name = "small"
model = "disk"
t_end = {t_end}
samples = 101
chunk = {chunk}
store = "{store}"

[start]
steady = "diameter-spin"

[[axis]]
name = "phidot"
from = 20
to = 36
count = {n_rates}

[[axis]]
name = "tilt"
from = 1e-4
to = 1e-2
count = 4
scale = "log"

[record]
quantities = ["growth", "max_theta_deviation", "final_theta", "final_phi"]

[plot]
x = "phidot"
y = "tilt"
quantity = "growth"
log = true
"""


def small(tmp_path, name="small", t_end=2, chunk=8, n_rates=6):
    path = tmp_path / f"{name}.toml"
    path.write_text(SMALL.format(t_end=t_end, chunk=chunk, store=tmp_path / f"{name}.sqlite", n_rates=n_rates))
    return path


def rows_of(path):
    db = sqlite3.connect(path)
    try:
        return db.execute("SELECT * FROM runs ORDER BY idx").fetchall()
    finally:
        db.close()


# --- the spec -----------------------------------------------------------------------------------

def test_shipped_specs_are_valid():
    for path in sorted(SPECS.glob("*.toml")):
        spec = load(path)
        assert spec.n_points >= 2 and spec.plot, path.name
    assert load(SPECS / "disk-diameter-spin.toml").n_points == 10_000


@pytest.mark.parametrize("change,message", [
    (("model = \"disk\"", "model = \"disc\""), "model = 'disc' is unknown"),
    (("name = \"phidot\"", "name = \"omega\""), "name = 'omega'"),
    (("from = 1e-4", "from = -1e-4"), "a log axis needs positive ends"),
    (("count = 4", "count = 0"), "count = 0 must be at least 1"),
    (("t_end = 2", "t_end = -2"), "t_end = -2 must be positive"),
    (("[plot]", "[plot]\ncolour = \"red\""), "unknown key 'colour'"),
    (("\"growth\", ", "\"speed\", "), "quantity 'speed' is unknown"),
    (("steady = \"diameter-spin\"", "steady = \"sleeping\""), "steady = 'sleeping' for 'disk'"),
    (("[sweep]", "[sweeep]\n[sweep]"), "unknown key 'sweeep'"),
])
def test_bad_specs_are_refused_with_the_bad_value(tmp_path, change, message):
    text = small(tmp_path).read_text().replace(*change, 1)
    with pytest.raises(SpecError, match=message.replace("(", r"\(").replace(")", r"\)")):
        parse(text)


def test_points_are_row_major_over_the_axes(tmp_path):
    spec = load(small(tmp_path))
    assert spec.n_points == 24 and spec.n_chunks == 3
    assert spec.point(0) == {"phidot": 20.0, "tilt": 1e-4}
    assert spec.point(1)["phidot"] == 20.0 and spec.point(4)["phidot"] == spec.axes[0].values[1]


# --- running, resuming, the store ---------------------------------------------------------------

def test_a_sweep_fills_its_store_once_and_resumes_without_repeating(tmp_path):
    spec = load(small(tmp_path))
    first = run_sweep(spec, threads=2, progress=False)
    assert (first.chunks_run, first.rows) == (3, 24)
    again = run_sweep(spec, threads=2, progress=False)
    assert (again.chunks_run, again.chunks_skipped, again.rows) == (0, 3, 24)
    rows = rows_of(spec.store)
    assert [r[0] for r in rows] == list(range(24))
    with Store(spec) as store:
        got = store.rows()
    # ~600 Taylor steps in 2 s: round-off walks the energy by ~eps sqrt(N) = 5e-15 of its scale;
    # 1e-13 is 20x that (measured: 7e-16)
    assert all(r["outcome"] == "ok" and r["energy_drift_vs_terms"] < 1e-13 for r in got)
    # below the Eq. 41 threshold (28) the tilt grows a thousandfold within 2 s; above it the body
    # oscillates about a neighbouring steady motion displaced by ~1/w2 (growth 14 at 17% above)
    slow = [r for r in got if r["in_phidot"] < 25 and r["in_tilt"] < 1e-3]
    fast = [r for r in got if r["in_phidot"] > 31]
    assert min(r["growth"] for r in slow) > 500 and max(r["growth"] for r in fast) < 50


def test_a_store_of_another_spec_is_refused(tmp_path):
    spec = load(small(tmp_path))
    run_sweep(spec, threads=1, progress=False)
    other = parse(spec.text.replace("count = 4", "count = 5"), store=str(spec.store))
    with pytest.raises(StoreError, match="different spec"):
        Store(other)


def _running_in_group(pgid: int) -> bool:
    """Whether a process of group ``pgid`` is still running (a zombie waiting for its reaper is not)."""
    proc = Path("/proc")
    if not proc.is_dir():
        try:
            os.killpg(pgid, 0)
        except ProcessLookupError:
            return False
        return True
    for stat in proc.glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[2]) == pgid and fields[0] != "Z":  # fields after the name: state, ppid, pgrp, ...
            return True
    return False


def test_killed_sweep_keeps_whole_chunks_and_resumes_to_the_same_rows(tmp_path):
    """The issue's test: kill -9 mid-run, then the same command finishes without repeats or duplicates."""
    ref_path = small(tmp_path, "reference", t_end=10, chunk=4, n_rates=12)
    run_sweep(load(ref_path), threads=1, progress=False)
    path = small(tmp_path, "killed", t_end=10, chunk=4, n_rates=12)
    spec = load(path)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    cmd = [sys.executable, "-m", "verify", "sweep", str(path), "--quiet", "--threads", "1"]
    proc = subprocess.Popen(cmd, env=env, cwd=tmp_path, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)  # its own process group: the command's child can be waited for
    deadline = time.monotonic() + 120
    done = 0
    while time.monotonic() < deadline and proc.poll() is None:
        if Path(spec.store).exists():
            try:
                db = sqlite3.connect(spec.store, timeout=1)
                done = db.execute("SELECT COUNT(*) FROM chunks").fetchone()[0]
                db.close()
            except sqlite3.OperationalError:
                done = 0
        if done >= 2:
            break
        time.sleep(0.05)
    assert proc.poll() is None, f"the sweep ended before it could be killed: {proc.stderr.read().decode()[-500:]}"
    os.kill(proc.pid, signal.SIGKILL)  # the command the shell started, as a user's kill -9 does
    proc.wait()
    # The command computes in a child (verify.guard.supervise), which the kernel kills when its parent
    # dies (PR_SET_PDEATHSIG); the store is read only once it is gone too, so no commit lands after
    gone = time.monotonic() + 30
    while time.monotonic() < gone and _running_in_group(proc.pid):
        time.sleep(0.05)
    assert not _running_in_group(proc.pid), "the sweep's computing child outlived the killed command"
    db = sqlite3.connect(spec.store)
    chunks = db.execute("SELECT COUNT(*), COALESCE(SUM(n), 0) FROM chunks").fetchone()
    runs = db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    db.close()
    assert 2 <= chunks[0] < spec.n_chunks and runs == chunks[1] == 4 * chunks[0]  # whole chunks only
    resumed = subprocess.run(cmd, env=env, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert resumed.returncode == 0, resumed.stderr
    assert f"{spec.n_chunks - chunks[0]} chunks run, {chunks[0]} already there" in resumed.stdout
    assert rows_of(spec.store) == rows_of(load(ref_path).store)  # same rows (incl. chunk numbers), no duplicates


def test_local_dask_cluster_gives_the_same_rows(tmp_path):
    """Dask rows equal local rows; the spec records senses, so the reading travels to the workers too."""
    path = small(tmp_path)
    path.write_text(path.read_text().replace('"final_phi"]', '"final_phi", "windows", "orbit_start"]'))
    spec = load(path)
    run_sweep(spec, threads=2, progress=False, senses=senses)
    dask_store = tmp_path / "dask.sqlite"
    result = run_sweep(spec, dask="local", progress=False, store_path=dask_store, senses=senses)
    assert result.where.startswith("local Dask cluster") and result.rows == spec.n_points
    assert rows_of(dask_store) == rows_of(spec.store)


def test_plot_draws_the_map_from_the_store(tmp_path, capsys):
    path = small(tmp_path)
    assert main(["sweep", str(path), "--plot"]) == 2  # nothing stored yet
    assert "first" in capsys.readouterr().err
    assert main(["sweep", str(path), "--quiet"]) == 0
    assert main(["sweep", str(path), "--plot"]) == 0
    png = tmp_path / "small.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("argv,message", [
    (["sweep", "/nonexistent.toml"], "no sweep spec"),
    (["sweep", "{spec}", "--threads", "0"], "--threads 0 must be at least 1"),
    (["sweep", "{spec}", "--plot", "--dask", "local"], "--plot draws from the store"),
    (["sweep", "{spec}", "--dask", "nowhere", "--quiet"], "--dask 'nowhere': no Dask scheduler there"),
    (["sweep", "{spec}", "--store", "{junk}", "--quiet"], "file is not a database"),
    (["sweep", "{spec}", "--store", "{junk}/under-a-file.sqlite", "--quiet"], "cannot open the sweep store"),
])
def test_sweep_bad_input(tmp_path, capsys, argv, message):
    path = small(tmp_path)
    junk = tmp_path / "junk.sqlite"
    junk.write_bytes(b"not a database")
    assert main([a.format(spec=path, junk=junk) for a in argv]) == 2
    assert message in capsys.readouterr().err
    assert junk.read_bytes() == b"not a database"  # a refused store is left as it was


# --- the engine against the scalar integrator ---------------------------------------------------

def test_sweep_rows_agree_with_solve(tmp_path):
    """Batch lanes (heyoka batch + ensemble) against verify.solve on the same points: same equations,
    different integrators (SIMD lanes, no offsets), so they agree to the conditioning of the flow:
    eps sqrt(N) |Phi| ~ 1e-16 * 30 * 1e3 at t = 2 s; 1e-9 leaves a margin of ~300."""
    spec = load(small(tmp_path))
    run_sweep(spec, threads=2, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    for r in rows[::7]:
        th0 = math.pi / 2 + r["in_tilt"]
        sol = solve("disk", "2", {"theta": repr(th0), "phidot": repr(r["in_phidot"])}, n_eval=101)
        assert abs(float(sol["theta"][-1]) - r["final_theta"]) < 1e-9
        assert abs(float(sol["phi"][-1]) - r["final_phi"]) < 1e-9 * max(1.0, abs(r["final_phi"]))
        dev = max(abs(float(v) - math.pi / 2) for v in sol["theta"])
        assert abs(dev - r["max_theta_deviation"]) < 1e-9


# --- the dissipative ring ------------------------------------------------------------------------

@pytest.mark.parametrize("law", ["air-drag", "rolling-friction"])
def test_ring_dissipation_loses_energy_at_the_rate_it_says(law):
    """dE/dt along the equations + the model's dissipation = 0 (sympy, exact), the dissipation is >= 0 at
    random states, and c = 0 gives the conservative ring's accelerations."""
    from models import get_model
    from models.ring_dissipation import c, couple, dissipative_ring
    from models.symbols import ACCELERATIONS, STATE, omega_body, time_derivative

    m = dissipative_ring(law)
    rate = time_derivative(m.energy).subs(dict(zip(ACCELERATIONS, m.accelerations)))
    rng = np.random.default_rng(1)
    ring = get_model("ring")
    for _ in range(3):
        st = dict(zip(STATE, [sp.Float(v, 30) for v in (rng.uniform(0.3, 1.3), 0.2, 0.4, rng.uniform(-3, 3),
                                                          rng.uniform(-20, 20), rng.uniform(-20, 20), 0, 0)]))
        pv = {p.symbol: sp.nsimplify(p.default) for p in m.parameters}
        total = (rate + m.dissipation).subs(st).subs(pv)
        assert abs(sp.N(total, 30)) < 1e-20
        assert sp.N(m.dissipation.subs(st).subs(pv)) >= 0
        assert abs(sp.N(-couple(law).dot(omega_body()).subs(st).subs(pv) - m.dissipation.subs(st).subs(pv), 30)) < 1e-25
        rp = {p.symbol: sp.nsimplify(p.default) for p in ring.parameters}
        for a, b in zip(m.accelerations, ring.accelerations):
            assert abs(sp.N(a.subs(st).subs({**pv, c: 0}) - b.subs(st).subs(rp), 30)) < 1e-20


def short_air_drag_sweep(tmp_path):
    """The shipped ring+air-drag spec cut to 8 runs of 3 s."""
    text = (SPECS / "ring-retrograde-air-drag.toml").read_text()
    text = text.replace("t_end = 120", "t_end = 3").replace("samples = 48001", "samples = 301") \
               .replace("count = 6", "count = 2")
    return parse(text, store=str(tmp_path / "ring.sqlite"))


def test_dissipative_sweep_keeps_energy_plus_work(tmp_path):
    """E + W = E(0) along every run of a short ring+air-drag sweep (to 1e-13 relative: ~1e3 eps over
    ~1e3 steps, the bound of the dissipation study)."""
    spec = short_air_drag_sweep(tmp_path)
    run_sweep(spec, threads=2, progress=False, senses=senses)
    with Store(spec) as store:
        rows = store.rows()
    assert len(rows) == spec.n_points == 8
    assert max(r["energy_drift_vs_terms"] for r in rows) < 1e-13


def test_energy_drift_column_sees_unaccounted_work(tmp_path, monkeypatch):
    """Negative control for the column above: the same sweep with the work W dropped from the balance
    (samples' W zeroed before the reduction) must show the energy the couple removed."""
    from verify.sweep import engine

    reduce = engine._reduce

    def without_work(spec, ens, indices, grid, samples, *rest):
        samples = samples.copy()  # (states, lanes, grid)
        samples[ens.lanes.row("W")] = 0.0
        return reduce(spec, ens, indices, grid, samples, *rest)

    monkeypatch.setattr(engine, "_reduce", without_work)
    spec = short_air_drag_sweep(tmp_path)
    run_sweep(spec, threads=2, progress=False, senses=senses)
    with Store(spec) as store:
        drifts = [r["energy_drift_vs_terms"] for r in store.rows()]
    assert min(drifts) > 1e-6, drifts


# --- the senses of orbit and spin (more in tests/test_retrograde.py) -------------------------------

def _run(phi_rate, spin):
    """A run without nutation: the CM on a circle, moving along e1 = (cos phi, sin phi)."""
    t = np.linspace(0, 10, 2001)
    phi = np.cumsum(np.r_[0, np.diff(t) * phi_rate(t[1:])])
    y = np.zeros((len(t), 8))
    y[:, 1] = phi
    radius = 0.2
    y[:, 6], y[:, 7] = radius * np.sin(phi), -radius * np.cos(phi)  # CM on a circle, velocity along e1
    return t, y, spin(t)


def test_senses_read_a_prograde_run():
    """No nutation: the path is its own slow path, read over 20 equal windows (0.8 turn each here)."""
    t, y, wz = _run(lambda t: 10 + 0 * t, lambda t: 3 + 0 * t)
    s = senses(t, y, wz)
    assert (s["orbit_start"], s["orbit_end"], s["orbit_last"], s["spin_start"], s["spin_end"]) == (1, 1, 1, 1, 1)
    assert s["windows"] == 20 and s["windows_undecided"] == 0 and math.isnan(s["points_per_nutation"])
    assert s["retrograde_turn"] == 0 and s["orbit_reversal"] == 0 and s["path_start"] == 1 and s["roll_reversal"] == 0


def test_senses_catch_an_orbit_that_turns_against_the_spin():
    """Negative-control pair: the same spin, the orbit's rate changes sign at t = 5.  The windows
    around the reversal turn less than half a turn and stay undecided; the first to decide the
    other way starts at 6.5 s."""
    t, y, wz = _run(lambda t: 4 * (5 - t), lambda t: 3 + 0 * t)
    s = senses(t, y, wz)
    assert s["orbit_start"] == 1 and s["orbit_end"] == -1 and s["orbit_last"] == -1
    assert s["retrograde_turn"] == 1 and s["retrograde_by_last_read"] == 1 and s["orbit_reversal"] == 1
    assert 5 <= s["t_retrograde"] <= 7 and s["t_retrograde"] == s["t_orbit_reversal"]
    assert 0 < s["windows_undecided"] < 10


def test_senses_of_a_run_too_short_to_read_are_nan():
    t, y, wz = _run(lambda t: 10 + 0 * t, lambda t: 3 + 0 * t)
    s = senses(t[:30], y[:30], wz[:30])
    assert all(math.isnan(v) for v in s.values())


def test_a_sense_without_its_reading_is_refused_before_anything_is_written(tmp_path):
    """The senses are a study's reading (verify.studies.orbits), passed in: a spec that records one and
    gets no reading is refused by name before a store exists; with the reading the same spec runs."""
    text = SMALL.format(t_end=2, chunk=8, store=tmp_path / "senses.sqlite", n_rates=2).replace(
        '"final_phi"]', '"final_phi", "orbit_start", "windows"]')
    spec = parse(text)
    with pytest.raises(SpecError, match="records 'orbit_start'.*senses=verify.studies.orbits.senses"):
        run_sweep(spec, threads=1, progress=False)
    assert not (tmp_path / "senses.sqlite").exists()
    assert run_sweep(spec, threads=1, progress=False, senses=senses).rows == 8  # the control: it runs


def studies_imported(source: str, module: str) -> list:
    """The modules of verify.studies that ``source`` (the text of module ``module``) imports, by ast."""
    package = module.rsplit(".", 1)[0].split(".")
    found = []
    for node in ast.walk(ast.parse(source)):
        names = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            names = [".".join(base + ([node.module] if node.module else []))]
            names += [f"{names[0]}.{a.name}" for a in node.names]
        found += [n for n in names if n == "verify.studies" or n.startswith("verify.studies.")]
    return found


def test_the_sweep_imports_no_study():
    """The sweep is the machinery below the studies (docs/architecture.md): none of its modules imports
    verify.studies, at the top or inside a function.  Negative control: the same reader finds a study
    imported relatively from a module of the sweep."""
    for path in sorted((ROOT / "verify" / "sweep").glob("*.py")):
        assert studies_imported(path.read_text(), f"verify.sweep.{path.stem}") == [], path.name
    assert studies_imported("def f():\n    from ..studies.orbits import senses\n", "verify.sweep.engine") == [
        "verify.studies.orbits", "verify.studies.orbits.senses"]
    assert studies_imported("from verify.studies import orbits\n", "verify.sweep.engine") == [
        "verify.studies", "verify.studies.orbits"]


def test_rows_do_not_depend_on_how_many_batches_are_reduced_together(tmp_path, monkeypatch):
    """The reductions run over groups of batches (memory); each lane's row is its own, so the
    grouping changes no bit."""
    from verify.sweep import engine

    spec = load(small(tmp_path, n_rates=10))
    together = engine.run_chunk(spec, 0, 2, 4)
    monkeypatch.setattr(engine, "REDUCE_GROUP", 1)
    one_by_one = engine.run_chunk(spec, 0, 2, 4)
    assert len(together) == 8 and repr(together) == repr(one_by_one)  # repr: NaN equal to NaN, floats to the bit


FALLS = """
[sweep]
name = "falls"
model = "disk"
t_end = 3
samples = 31
chunk = 4
store = "{store}"

[start]
theta = 1.2

[[axis]]
name = "psidot"
from = 0
to = 2
count = 3

[record]
quantities = ["final_theta", "final_phi", "final_psi", "final_thetadot", "final_phidot", "final_psidot",
              "final_x", "final_y", "min_theta"]
"""


def test_a_stopped_runs_final_state_is_the_state_at_its_stop(tmp_path):
    """A disk let go at theta = 1.2 with little spin loses contact at t ~ 0.065 s, before the grid's second
    sample (0.1 s): its final_* are the state the event recorded at t_stop, equal to solve's final state
    at its own contact_lost event (same equations, scalar integrator: a few steps, eps sqrt(N) |Phi| ~ 1e-14;
    held to 1e-12), and a run that reaches t_end keeps its last sample (3 s: held to 1e-9 as in
    test_sweep_rows_agree_with_solve; measured 2e-11).  With [stop] theta_below = 0.6,
    final_theta is 0.6 (the event's root, to 1e-13).  Negative control: the samples alone hold only the
    start before the stop (min_theta = 1.2), which is what final_theta said before (format 1 stores)."""
    path = tmp_path / "falls.toml"
    path.write_text(FALLS.format(store=tmp_path / "falls.sqlite"))
    spec = load(path)
    run_sweep(spec, threads=1, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    assert sorted(r["outcome"] for r in rows) == ["contact_lost", "contact_lost", "ok"]
    for r in rows:
        sol = solve("disk", "3", {"theta": "1.2", "psidot": repr(r["in_psidot"])}, n_eval=2)
        assert sol.outcome == ("ok" if r["outcome"] == "ok" else "event:contact_lost")
        assert abs(float(sol.t[-1]) - r["t_stop"]) < 1e-12
        tol = 1e-12 if r["outcome"] != "ok" else 1e-9  # 3 s: test_sweep_rows_agree_with_solve's argument
        for name, value in sol.final_state.items():
            assert abs(float(value) - r[f"final_{name}"]) < tol * max(1.0, abs(float(value))), (name, r)
        if r["outcome"] != "ok":
            assert r["min_theta"] == 1.2 and r["final_theta"] < 0.5  # the samples saw only the start
    stop = tmp_path / "stop.toml"
    stop.write_text(FALLS.format(store=tmp_path / "stop.sqlite") + "\n[stop]\ntheta_below = 0.6\n")
    spec = load(stop)
    run_sweep(spec, threads=1, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    assert {r["outcome"] for r in rows} == {"theta_stop"}
    assert all(abs(r["final_theta"] - 0.6) < 1e-13 and r["min_theta"] == 1.2 for r in rows)


def test_a_store_of_the_former_format_is_refused(tmp_path, capsys):
    """A format-1 store (final_* of a stopped run the last sample) is not resumed with format-2 rows."""
    path = small(tmp_path)
    assert main(["sweep", str(path), "--quiet"]) == 0
    with sqlite3.connect(tmp_path / "small.sqlite") as db:
        db.execute("UPDATE meta SET value = 'rolling-verify sweep store, format 1' WHERE key = 'format'")
    db.close()
    assert main(["sweep", str(path), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "format 1" in err and "format 2" in err and "delete it" in err


def test_a_shipped_spec_is_found_by_name_from_any_folder(tmp_path, monkeypatch):
    """From a folder without the file, ``sweep disk-diameter-spin`` (or ``.toml``) is the shipped spec; a file of
    that name in the working folder is the user's own; an unknown name lists the shipped ones."""
    monkeypatch.chdir(tmp_path)
    shipped = load(SPECS / "disk-diameter-spin.toml")
    assert load("disk-diameter-spin").sha256 == load("disk-diameter-spin.toml").sha256 == shipped.sha256
    (tmp_path / "disk-diameter-spin.toml").write_text(small(tmp_path).read_text())
    assert load("disk-diameter-spin.toml").name == "small"
    with pytest.raises(SpecError, match="shipped spec by name: disk-diameter-spin, "):
        load("no-such-spec")

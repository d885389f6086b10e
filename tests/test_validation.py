"""One validation path for a start, whichever way it arrives (solve, a sweep's fixed values, a sweep's
axis, a reference case, a study), the sweep's refusal before its store exists, its size limits, and
the outcomes of sweep runs that fail.  Everything is written to temporary folders."""
from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest

from models import get_model
from models.ring_dissipation import annulus_inertia
from models.symbols import STATE_NAMES
from verify import solve
from verify.cli import main
from verify.sweep import (
    SPECS, InvalidPoint, SpecError, Store, SweepTooLarge, estimate, load, parse, run_sweep, runner,
)
from verify.sweep import engine
from verify.sweep.plot import grid_of
from verify.engine.lanes import simd_width
from verify.engine.validation import InvalidStart

SPEC = """
[sweep]
name = "v"
model = "disk"
t_end = 0.5
samples = 11
chunk = 4
store = "{store}"
{params}
[start]
{start}
[[axis]]
name = "{axis}"
from = {lo}
to = {hi}
count = {count}
[record]
quantities = ["final_theta", "min_theta"]
"""


def spec_text(tmp_path, axis="psidot", lo=1, hi=10, count=3, start="theta = 1.2", params="", name="v"):
    return SPEC.format(store=tmp_path / f"{name}.sqlite", axis=axis, lo=lo, hi=hi, count=count, start=start,
                       params=params)


def solve_message(state, params=None) -> InvalidStart:
    with pytest.raises(InvalidStart) as err:
        solve("disk", "0.5", state, params)
    return err.value


# --- the same checks, the same words, every way in ------------------------------------------------------

# (a start solve refuses, the same start as a sweep's fixed values, as an axis through it, the words
# of the rule that solve and the sweep both print)
CASES = {
    "outside_domain": ({"theta": "3.5"}, "", "theta = 3.5", ("theta", 1.0, 3.5),
                       "state theta=3.5 is outside the domain of 'disk': 0 < theta < 3.1415926535897931 (at the "
                       "lower end: lies_flat; at the upper end: lies_flat)"),
    "normal_force": ({"theta": "1.5", "thetadot": "-50"}, "", "theta = 1.5\nthetadot = -50", ("thetadot", 0, -50),
                     "the initial state of 'disk' has normal force N/(Mg) = -1.54863 <= 0: the body would leave the "
                     "plane; allowed: states with N > 0"),
    "parameter_range": ({"theta": "1.2"}, {"k": "0.75"}, "theta = 1.2", None,
                        "parameter k=0.75 is out of its physical range (0, 0.5] (I1/(m R^2)"),
}


@pytest.mark.parametrize("reason", sorted(CASES))
def test_solve_and_a_sweep_refuse_the_same_start_with_the_same_words(tmp_path, reason):
    state, params, start, axis, core = CASES[reason]
    err = solve_message(state, params or None)
    assert err.reason == reason and core in str(err)
    # the sweep's fixed values
    fixed_params = "[params]\nk = 0.75" if params else ""
    text = spec_text(tmp_path, start=start, params=fixed_params)
    with pytest.raises(SpecError) as sweep_err:
        run_sweep(parse(text), progress=False)
    assert core in str(sweep_err.value)
    assert not (tmp_path / "v.sqlite").exists()  # refused before the store
    # an axis through it
    if axis is not None:
        name, lo, hi = axis
        text = spec_text(tmp_path, axis=name, lo=lo, hi=hi, count=2,
                         start="\n".join(ln for ln in start.splitlines() if not ln.startswith(name)) or "psidot = 1")
        with pytest.raises(InvalidPoint) as axis_err:
            run_sweep(parse(text), progress=False)
        assert axis_err.value.reason == reason and axis_err.value.index == 1 and core in str(axis_err.value)
        assert not (tmp_path / "v.sqlite").exists()


def test_a_parameter_out_of_range_is_refused_at_parse_and_the_corrected_spec_runs(tmp_path):
    """The defect: k = 0.75 made the store, then a traceback, and the empty store blocked the fix."""
    bad = spec_text(tmp_path, params="[params]\nk = 0.75")
    with pytest.raises(SpecError, match=r"\[params\] k = 0.75: parameter k=0.75 is out of its physical range \(0, 0.5\]"):
        parse(bad)
    assert not (tmp_path / "v.sqlite").exists()
    good = parse(spec_text(tmp_path, params="[params]\nk = 0.5"))
    assert run_sweep(good, threads=1, progress=False).rows == 3


def test_a_parameter_axis_is_checked_by_its_ends(tmp_path):
    with pytest.raises(SpecError, match=r"\[\[axis\]\] k to = 0.75: parameter k=0.75 is out of its physical range"):
        parse(spec_text(tmp_path, axis="k", lo=0.25, hi=0.75))


def test_an_axis_across_the_domain_names_its_first_bad_point(tmp_path):
    text = spec_text(tmp_path, axis="theta", lo=-0.5, hi=3.5, count=9, start="psidot = 5")
    with pytest.raises(InvalidPoint) as err:
        run_sweep(parse(text), progress=False)
    e = err.value
    assert e.index == 0 and e.point == {"theta": -0.5} and e.reason == "outside_domain"
    assert "point 0 of 9 (theta = -0.5)" in str(e) and "0 < theta < 3.14159" in str(e)
    assert not (tmp_path / "v.sqlite").exists()
    # the upper end: the first bad point is the last one
    text = spec_text(tmp_path, axis="theta", lo=0.5, hi=3.5, count=9, start="psidot = 5")
    with pytest.raises(InvalidPoint) as err:
        run_sweep(parse(text), progress=False)
    assert err.value.index == 8


def test_a_refused_sweep_prints_one_line_and_no_plan(tmp_path, capsys):
    """The command line on a spec with a bad point: exit 2 and the one line naming it, not the plan line
    (size and estimated time) first.  Control: the same spec corrected prints its plan."""
    path = tmp_path / "v.toml"
    path.write_text(spec_text(tmp_path, axis="theta", lo=-0.5, hi=3.5, count=9, start="psidot = 5"))
    assert main(["sweep", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "point 0 of 9 (theta = -0.5)" in err[0], err
    path.write_text(spec_text(tmp_path, axis="theta", lo=0.5, hi=1.5, count=3, start="psidot = 5"))
    assert main(["sweep", str(path)]) == 0
    assert "v:" in capsys.readouterr().err


def test_a_sweep_refused_by_its_store_prints_one_line(tmp_path, capsys):
    """A store made by another spec: the one line naming it, not the plan line before it (the store is checked
    before the plan is printed)."""
    path = tmp_path / "v.toml"
    path.write_text(spec_text(tmp_path, axis="theta", lo=0.5, hi=1.5, count=3, start="psidot = 5"))
    assert main(["sweep", str(path), "--quiet"]) == 0
    path.write_text(spec_text(tmp_path, axis="theta", lo=0.5, hi=1.4, count=3, start="psidot = 5"))
    assert main(["sweep", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "made by a different spec" in err[0], err


def test_starts_below_the_stop_angle_are_refused(tmp_path):
    text = spec_text(tmp_path, axis="theta", lo=0.05, hi=1.2, count=3, start="psidot = 5") + "[stop]\ntheta_below = 0.1\n"
    with pytest.raises(InvalidPoint, match="not above \\[stop\\] theta_below = 0.1") as err:
        run_sweep(parse(text), progress=False)
    assert err.value.reason == "below_stop"


def test_a_reference_case_and_a_study_go_through_the_same_check():
    from verify.reference.check import check_case
    from verify.reference.make import equations_fingerprint
    from verify.studies.dissipation import integrate_with_work

    expected = str(solve_message({"theta": "1.5", "thetadot": "-50"}))
    record = {"name": "invalid", "model": {"name": "disk", "equations_sha256": equations_fingerprint("disk"),
                                           "parameters": {"k": {"exact": "1/4"}, "g": {"exact": "980"}}},
              "grid": ["0", "0.5"], "t_end": "0.5", "initial_state": {"theta": "1.5", "thetadot": "-50"}}
    with pytest.raises(InvalidStart) as ref:
        check_case(record)
    assert str(ref.value) == expected
    with pytest.raises(InvalidStart) as study:
        integrate_with_work("moffatt", ["0.5"], state={"theta": "1.5", "thetadot": "-50"})
    assert study.value.reason == "normal_force" and "N/(Mg) = -1.54" in str(study.value)


# --- a valid sweep writes the rows it always wrote --------------------------------------------------------

def _old_lane_inputs(spec, indices):
    """The engine's inputs as computed before validation (point by point), kept as the reference."""
    from verify.engine.single import resolve_parameters
    from verify.precision import parse_precision
    from verify.sweep.engine import _steady_cached
    from verify.sweep.spec import RATE_AXIS

    model = get_model(spec.model)
    prec = parse_precision("double")
    states, pars, refs = [], [], []
    for i in indices:
        point = spec.point(i)
        values = {**spec.params, **{k: v for k, v in point.items() if k in spec.params or k not in STATE_NAMES}}
        values.pop("tilt", None)
        if spec.geometry == "annulus":
            hh, ww = values.get("h"), values.pop("w")
            i1, i3 = annulus_inertia(hh, ww)
            values.update(I1=i1, I3=i3)
            if "w" in model.parameter_names:
                values["w"] = ww
        resolved = resolve_parameters(model, {k: repr(float(v)) for k, v in values.items()}, prec)
        start = {**spec.start, **{k: v for k, v in point.items() if k in STATE_NAMES}}
        ref = start.get("theta", 0.0)
        if spec.steady is not None:
            text = tuple((k, repr(float(v))) for k, v in values.items())
            steady = _steady_cached(spec.model, spec.steady, repr(float(point[RATE_AXIS[spec.steady]])), text)
            start.update(steady)
            ref = steady["theta"]
        y = np.zeros(8)
        for k, v in start.items():
            y[STATE_NAMES.index(k)] = v
        y[0] = ref + point.get("tilt", 0.0)
        states.append(y)
        pars.append([float(v) for v in resolved.values()])
        refs.append(ref)
    return np.array(states).T, np.array(pars).T, np.array(refs)


@pytest.mark.parametrize("name", ["disk-diameter-spin", "ring-retrograde-air-drag"])
def test_the_vectorised_inputs_are_the_old_ones_bit_for_bit(name):
    spec = load(SPECS / f"{name}.toml")
    idx = list(range(0, spec.n_points, max(1, spec.n_points // 300)))
    new, old = engine.lane_inputs(spec, idx), _old_lane_inputs(spec, idx)
    assert all(np.array_equal(a, b) for a, b in zip(new, old))


def test_a_valid_sweep_stores_the_rows_of_its_lanes_unchanged_by_the_new_machinery(tmp_path, monkeypatch):
    """The same spec twice: as it runs, and with every batch integrated again lane by lane (the
    path of a failed batch); lanes do not interact, so the rows are the same bits."""
    text = spec_text(tmp_path, axis="psidot", lo=0, hi=30, count=10, start="theta = 1.2\nphidot = 1")
    spec = parse(text)
    run_sweep(spec, threads=2, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    assert {r["outcome"] for r in rows} <= {"ok", "lies_flat", "contact_lost"}
    monkeypatch.setattr(engine, "_batch_ok", lambda *a: False)
    again = parse(text, store=str(tmp_path / "again.sqlite"))
    run_sweep(again, threads=2, progress=False)
    with Store(again) as store:
        assert store.rows() == rows


def test_lanes_run_again_alone_only_once_no_group_is_integrating(tmp_path, monkeypatch):
    """A chunk's groups integrate one while the one before is reduced; a group with a failed batch drains
    the rest first, so that heyoka's messages during the lone runs are theirs.  With a group of one batch
    and the first batch taken as failed, every yield of the propagator comes before the first lone run,
    and the rows are the same bits as a run without the failure."""
    n = 3 * simd_width()  # three batches at any width
    text = spec_text(tmp_path, axis="psidot", lo=0, hi=30, count=n, start="theta = 1.2\nphidot = 1").replace(
        "chunk = 4", f"chunk = {n}")
    spec = parse(text)
    run_sweep(spec, threads=2, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    from verify.engine import ensemble as ensemble_module

    log = []
    real_propagate, real_alone = ensemble_module.Ensemble.propagate, ensemble_module.Ensemble.alone

    def propagate(self, *args, **kwargs):
        for item in real_propagate(self, *args, **kwargs):
            log.append("yield")
            yield item

    def alone(self, *args, **kwargs):
        log.append("alone")
        return real_alone(self, *args, **kwargs)

    monkeypatch.setattr(engine, "REDUCE_GROUP", 1)
    monkeypatch.setattr(engine, "_batch_ok", lambda b, n: b.index != 0)
    monkeypatch.setattr(ensemble_module.Ensemble, "propagate", propagate)
    monkeypatch.setattr(ensemble_module.Ensemble, "alone", alone)
    again = parse(text, store=str(tmp_path / "again.sqlite"))
    run_sweep(again, threads=2, progress=False)
    with Store(again) as store:
        assert store.rows() == rows
    assert log.count("yield") == 3 and "alone" in log  # three groups, and lone runs
    assert log.index("alone") > max(i for i, e in enumerate(log) if e == "yield")


# --- runs that fail are stored as failures, never as data --------------------------------------------------

def test_failing_lanes_are_named_and_their_neighbours_keep_their_bits(tmp_path):
    text = spec_text(tmp_path, axis="theta", lo="1e-300", hi=1.5, count=2, start="psidot = 3") \
        .replace('count = 2\n', 'count = 2\nscale = "log"\n')
    spec = parse(text)
    run_sweep(spec, threads=2, progress=False)
    with Store(spec) as store:
        rows = store.rows()
    assert rows[0]["outcome"].startswith("failed:") and rows[0]["final_theta"] is None
    assert rows[0]["energy_drift_vs_terms"] is None
    alone = parse(spec_text(tmp_path, axis="theta", lo=1.5, hi=1.5, count=1, start="psidot = 3", name="alone"))
    run_sweep(alone, threads=2, progress=False)
    with Store(alone) as store:
        ref = store.rows()[0]
    assert {k: v for k, v in rows[1].items() if k not in ("idx",)} == {k: v for k, v in ref.items() if k != "idx"}
    _, _, z = grid_of(spec, rows, "final_theta", "theta", "theta")
    assert math.isnan(z[0, 0]) and math.isfinite(z[1, 1])  # a map leaves the failure white


def test_a_missed_event_is_a_failed_row_not_data(tmp_path, monkeypatch):
    """Negative control of the guard: with the stop event's freezing disabled (as if heyoka had missed
    it), the lane goes on below [stop] theta_below and the row says failed:event_detection."""
    text = spec_text(tmp_path, axis="psidot", lo=0, hi=1, count=2, start="theta = 1.2") + "[stop]\ntheta_below = 0.6\n"
    spec = parse(text)
    run_sweep(spec, threads=1, progress=False)
    with Store(spec) as store:
        assert [r["outcome"] for r in store.rows()] == ["theta_stop", "theta_stop"]
    from verify.engine.batch import Freeze

    monkeypatch.setattr(Freeze, "__call__", lambda self, ta, d_sgn, lane: True)
    missed = parse(text, store=str(tmp_path / "missed.sqlite"))
    run_sweep(missed, threads=1, progress=False)
    with Store(missed) as store:
        rows = store.rows()
    assert [r["outcome"] for r in rows] == ["failed:event_detection"] * 2
    assert all(r["final_theta"] is None and 0 < r["t_stop"] < 0.5 for r in rows)


# --- size: stated, bounded, lazy ---------------------------------------------------------------------------

def test_a_grid_typo_is_refused_at_once_without_building_the_grid(tmp_path):
    text = spec_text(tmp_path, axis="psidot", lo=1, hi=10, count=100_000_000)
    text += '[[axis]]\nname = "phidot"\nfrom = 0\nto = 1\ncount = 100000000\n'
    tracemalloc.start()
    try:
        spec = parse(text)
        with pytest.raises(SweepTooLarge) as err:
            run_sweep(spec, progress=False)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 20e6, peak  # the axes are never listed (the old tuples took 11.9 GB)
    e = err.value
    assert isinstance(e, SpecError) and e.estimate.points == 10 ** 16
    assert "10,000,000,000,000,000 points (limit 10,000,000)" in str(e) and "yes=True" in str(e) and "--yes" in str(e)
    assert not (tmp_path / "v.sqlite").exists()
    assert spec.point(10 ** 16 - 1) == {"psidot": 10.0, "phidot": 1.0}  # any point on demand


def test_the_size_is_stated_before_the_run_and_yes_overrides_the_limits(tmp_path, monkeypatch, capsys):
    spec = parse(spec_text(tmp_path))
    monkeypatch.setitem(runner.LIMITS, "points", 2)
    with pytest.raises(SweepTooLarge, match="3 points \\(limit 2\\)") as err:
        run_sweep(spec, threads=1, progress=True)
    assert "v: 3 points in 1 chunks" in str(err.value)  # the plan is in the one line of the refusal
    assert capsys.readouterr().err == ""
    assert not (tmp_path / "v.sqlite").exists()
    result = run_sweep(spec, threads=1, progress=False, yes=True)
    assert result.rows == 3 and result.estimate.points == 3


def test_memory_per_chunk_is_bounded(tmp_path):
    text = spec_text(tmp_path).replace("samples = 11", "samples = 2000000").replace("chunk = 4", "chunk = 400")
    text = text.replace("count = 3", "count = 400")
    e = estimate(parse(text), threads=2)
    assert e.memory_bytes > runner.LIMITS["memory_bytes"] and "of memory per chunk (limit 2 GiB)" in e.over()[0]


def test_the_shipped_sweeps_are_within_the_limits():
    for path in sorted(SPECS.glob("*.toml")):
        assert estimate(load(path), threads=2).over() == [], path.name


@pytest.mark.parametrize("precision,theta", [("quad", "1e-400"), ("mp:200", "1e-1000"),
                                             ("quad", "3.141592653589793"), ("long", "3.14159265358979323")])
def test_the_domain_is_checked_at_the_starts_own_precision(precision, theta):
    """theta = 1e-400 is a positive quad number (0 in double), and float(pi) < pi in quad and long:
    both are inside (0, pi) at those precisions, whatever double would say."""
    from models import get_model
    from verify import parse_precision
    from verify.engine.validation import validate

    validate(get_model("disk"), {"theta": theta, "psidot": "10"}, None, parse_precision(precision))


def test_the_domain_end_rounded_to_double_is_refused_in_double():
    """Negative control of the test above: in double float(pi) is the domain's end itself."""
    from models import get_model
    from verify import parse_precision
    from verify.engine.validation import InvalidStart, validate

    with pytest.raises(InvalidStart, match="outside the domain"):
        validate(get_model("disk"), {"theta": "3.141592653589793", "psidot": "10"}, None, parse_precision("double"))

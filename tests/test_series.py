"""A run's time series: columns with units, the three file formats, the picture, and the CLI options."""
import json
import warnings

import numpy as np
import pytest

from verify import solve
from verify.cli import main
from verify.engine import hybrid
from verify.series import read_run, run_columns, write_run
from verify.series.files import RunFileError, to_csv_text
from verify.series.plot import plot_bytes

START = {"theta": "1.2", "psidot": "10"}


@pytest.fixture(scope="module")
def disk_double():
    return solve("disk", "0.5", START, n_eval=41)


@pytest.mark.parametrize("ext", [".csv", ".json", ".npz"])
def test_double_round_trip_is_bit_exact(tmp_path, disk_double, ext):
    cols = run_columns(disk_double)
    back = read_run(write_run(cols, tmp_path / f"run{ext}"))
    assert back.names == cols.names and back.units == cols.units
    for name in cols.names:
        a, b = np.asarray(cols.values[name], float), back.values[name]
        assert b.dtype == np.float64 and np.array_equal(a, b, equal_nan=True), name
    assert back.meta["model"] == "disk" and back.meta["outcome"] == "ok" and back.meta["precision"] == "double"


@pytest.mark.parametrize("precision", ["long", "quad"])
def test_extended_precisions_keep_every_digit(tmp_path, precision):
    sol = solve("disk", "0.2", START, n_eval=5, precision=precision)
    cols = run_columns(sol)
    for ext in (".csv", ".json", ".npz"):
        back = read_run(write_run(cols, tmp_path / f"run{ext}"))
        p = sol.precision
        for name in ("t", "theta", "energy"):
            got = back.values[name]
            got = [p.to_text(v) for v in got] if got.dtype == np.longdouble else [str(v) for v in got]  # npz in long
            assert got == [p.to_text(v) for v in cols.values[name]], (ext, name)
        # the strings read back at the precision give the same numbers
        assert all(p.number(str(s)) == v for s, v in zip(back.values["theta"], sol["theta"]))


def test_columns_and_units(disk_double):
    cols = run_columns(disk_double)
    assert cols.names[:9] == ("t", "theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y")
    assert cols.names[9:] == ("energy", "chaplygin_1", "chaplygin_2", "normal_force", "mu_req")
    header = to_csv_text(cols).splitlines()
    heading = next(line for line in header if not line.startswith("# "))
    assert heading.startswith("t [s],theta [rad],phi [rad],psi [rad],thetadot [1/s],phidot [1/s],psidot [1/s],x [R],y [R],"
                              "energy [m R^2/s^2]")
    comments = {line[2:].split(": ", 1)[0] for line in header if line.startswith("# ")}
    assert {"format", "model", "params", "precision", "start", "outcome", "version"} <= comments
    hb = run_columns(solve("hurricane", "0.1", {"theta": "0.578", "phidot": "313.77", "psidot": "376.52"}, n_eval=3))
    assert hb.units["x"] == "a" and hb.units["energy"] == "2 m a^2/s^2" and hb.units["jellett"] == "2 m a^3/s"


def test_coulomb_run_has_phase_slip_and_work(tmp_path):
    sol = hybrid.solve("disk+coulomb", "0.3", START, {}, friction="0.5", n_eval=31)
    cols = run_columns(sol)
    for name in ("phase", "slip_speed", "slip_direction", "energy", "work", "energy_plus_work"):
        assert name in cols.values
    assert set(cols.values["phase"]) <= {"rolling", "sliding"}
    back = read_run(write_run(cols, tmp_path / "c.csv"))
    assert list(back.values["phase"]) == list(cols.values["phase"])
    assert np.array_equal(back.values["slip_direction"], np.asarray(cols.values["slip_direction"], float), equal_nan=True)


def test_api_methods(tmp_path, disk_double):
    assert set(disk_double.columns()) == set(run_columns(disk_double).names)
    disk_double.to_csv(tmp_path / "a.csv")
    disk_double.to_json(tmp_path / "a.json")
    assert json.loads((tmp_path / "a.json").read_text())["units"]["t"] == "s"
    assert disk_double.plot(tmp_path / "a.png").stat().st_size > 1000
    with pytest.raises(ValueError, match="a .csv file name"):
        disk_double.to_csv(tmp_path / "a.json")


@pytest.mark.parametrize("suffix", [".png", ".svg", ".pdf"])
def test_plot_renders_without_warnings_and_is_reproducible(disk_double, suffix):
    cols = run_columns(disk_double)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        a = plot_bytes(cols, suffix)
    assert a == plot_bytes(cols, suffix) and len(a) > 1000


def test_reading_bad_files(tmp_path):
    with pytest.raises(RunFileError, match="no run file"):
        read_run(tmp_path / "missing.csv")
    (tmp_path / "x.csv").write_text("a,b\n1,2\n")
    with pytest.raises(RunFileError, match="format"):
        read_run(tmp_path / "x.csv")
    (tmp_path / "x.txt").write_text("")
    with pytest.raises(RunFileError, match="extension"):
        read_run(tmp_path / "x.txt")


def _main(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv, message", [
    (["--output", "{d}/nofolder/run.csv"], "does not exist"),
    (["--output", "{d}/run.txt"], "unknown extension '.txt'"),
    (["--output", "{d}"], "is a folder"),
    (["--plot", "{d}/run.bmp"], "unknown extension '.bmp'"),
    (["--start", "nope"], "unknown start 'nope'"),
    (["--state", "theta=pi/2x"], "--state theta='pi/2x'"),
    (["--state", "theta=sqrt(-1)"], "not a finite real number"),
])
def test_bad_output_options_exit_2_and_write_nothing(capsys, tmp_path, argv, message):
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    code, out, err = _main(capsys, "trajectory", "disk", "--t-end", "0.1", *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and message in err
    assert list(tmp_path.iterdir()) == []


def test_output_overwrites_atomically_and_plot_reads_it_back(capsys, tmp_path):
    target = tmp_path / "run.csv"
    target.write_text("old")
    code, out, _ = _main(capsys, "trajectory", "disk", "--t-end", "0.2", "--output", str(target),
                         "--plot", str(tmp_path / "run.png"))
    assert code == 0 and f"wrote       {target}" in out
    assert read_run(target).meta["outcome"] == "ok"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv", "run.png"]  # no temporary left
    code, out, _ = _main(capsys, "plot", str(target), "--out", str(tmp_path / "again.svg"))
    assert code == 0 and (tmp_path / "again.svg").stat().st_size > 1000
    code, _, err = _main(capsys, "plot", str(tmp_path / "none.csv"), "--out", str(tmp_path / "x.png"))
    assert code == 2 and "no run file" in err and not (tmp_path / "x.png").exists()


def test_a_run_file_of_a_reference_start_is_scored_by_verify_score(capsys, tmp_path):
    """The suite's own run files are what `verify score` reads (units in the headings, metadata as comments)."""
    from verify import score

    for ext in (".csv", ".json"):
        path = tmp_path / f"run{ext}"
        code, _, err = _main(capsys, "trajectory", "--start", "disk-standard-1", "--output", str(path), "--n-eval", "41")
        assert code == 0, err
        assert score(path, "disk-standard-1").min_digits > 10


def test_the_scorer_knows_the_run_format_by_name():
    from verify.scoring import runs
    from verify.series import FORMAT

    assert runs._SUITE_FORMAT == FORMAT


def test_infinities_survive_every_format(tmp_path):
    from verify.series.columns import FORMAT, RunColumns

    cols = RunColumns({"t": np.array([0.0, 1.0]), "x": np.array([np.inf, -np.inf]), "y": np.array([np.nan, 0.5])},
                      {"t": "s", "x": "R", "y": "R"}, {"format": FORMAT, "model": "disk", "precision": "double"})
    for ext in (".csv", ".json", ".npz"):
        back = read_run(write_run(cols, tmp_path / f"r{ext}"))
        assert np.array_equal(back.values["x"], cols.values["x"]) and np.isnan(back.values["y"][0]), ext


def test_random_starts_round_trip_and_keep_their_outcome(tmp_path):
    """Property over random starts (not only chosen ones): whatever the run does (rolls to t_end, lies flat,
    loses contact), its file reads back to the same bits and says the same outcome as the run."""
    rng = np.random.default_rng(29)
    for k in range(6):
        state = {"theta": repr(float(rng.uniform(0.2, 2.9))), "thetadot": repr(float(rng.uniform(-5, 5))),
                 "phidot": repr(float(rng.uniform(-20, 20))), "psidot": repr(float(rng.uniform(-30, 30)))}
        try:
            sol = solve("disk", "0.5", state, n_eval=21)
        except ValueError:  # a start the model refuses (N <= 0): bad input, nothing to write
            continue
        cols = run_columns(sol)
        back = read_run(write_run(cols, tmp_path / f"r{k}.csv"))
        assert back.meta["outcome"] == sol.outcome
        for name in cols.names:
            assert np.array_equal(back.values[name], np.asarray(cols.values[name], float), equal_nan=True), (k, name)

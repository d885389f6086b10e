"""The command line under a new user's hands: each defect found on a fresh clone, reproduced.

In-process where the behaviour is the CLI's own (messages, exit statuses, JSON), in a real
process where it is the process's (file descriptors, pipes, signals).
"""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from dataclasses import replace

import mpmath
import pytest

from verify.cli import arguments, output, progress
from verify.engine import single
from verify.studies.orbits import senses
from verify.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = dict(os.environ, PYTHONPATH=ROOT)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def error_lines(err: str) -> list:
    """stderr without heyoka's own log lines ([date] [heyoka-...] [warning] ...)."""
    return [ln for ln in err.splitlines() if ln.strip() and "[heyoka" not in ln]


def one_error_line(err: str) -> str:
    lines = error_lines(err)
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    assert "Traceback" not in err
    return lines[0]


# --- theta = 1e-300: failed event detection must not come out as ok, JSON stays JSON ----------

def test_a_run_that_leaves_the_domain_is_not_ok_and_its_json_is_valid(capsys):
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1e-300", "--t-end", "1", "--format", "json")
    doc = json.loads(out)  # one valid document (NaN would not parse; two documents would not either)
    assert code == 1
    assert doc.get("outcome") != "ok"  # the record with a failed outcome, or an error document
    line = one_error_line(err)
    assert "disk" in line


def test_the_same_run_as_text_is_not_labelled_ok(capsys):
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1e-300", "--t-end", "1")
    assert code == 1
    assert "outcome     ok" not in out
    one_error_line(err)


def test_what_cpp_prints_to_stdout_during_a_run_goes_to_stderr():
    """File descriptor 1 points at 2 while the command computes: writes to fd 1 and C stdio's
    buffered printf (as heyoka's or LLVM's would be) end on stderr, the JSON alone on stdout."""
    script = (
        "import ctypes, os, sys\n"
        "import verify.cli as cli\n"
        "import verify.engine.single as single\n"
        "real = single.solve\n"
        "def noisy(*a, **k):\n"
        "    os.write(1, b'fd-noise\\n')\n"
        "    ctypes.CDLL(None).printf(b'c-noise\\n')\n"
        "    print('python-noise')\n"
        "    return real(*a, **k)\n"
        "single.solve = noisy\n"
        "sys.exit(cli.main(['trajectory', 'disk', '--state', 'theta=1e-300', '--t-end', '1', '--format', 'json']))\n"
    )
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=ENV, cwd=ROOT, timeout=120)
    doc = json.loads(p.stdout)
    assert p.returncode == 1 and doc.get("outcome") != "ok"
    for noise in ("fd-noise", "c-noise", "python-noise"):
        assert noise in p.stderr and noise not in p.stdout


@pytest.mark.parametrize("argv", [
    ["trajectory", "disk", "--t-end", "1", "--state", "theta=abc", "--format", "json"],
    ["trajectory", "disk", "--t-end", "1", "--format=json", "--precision", "mp:2"],
    ["models", "--format", "json", "--bogus"],
])
def test_json_mode_failures_still_print_one_json_document(capsys, argv):
    code, out, err = run(capsys, *argv)
    doc = json.loads(out)
    assert code == 2 and doc["exit_status"] == 2 and doc["error"] in err
    one_error_line(err)


def test_nan_in_a_record_is_null_not_invalid_json():
    text = output._dumps({"a": float("nan"), "b": [float("inf"), 1.5], "c": {"d": float("-inf")}})
    assert json.loads(text) == {"a": None, "b": [None, 1.5], "c": {"d": None}}


# --- the MPFR floor ----------------------------------------------------------------------------

@pytest.mark.parametrize("bits", ["2", "3", "4", "52", "0", "-5"])
def test_mpfr_below_53_bits_is_refused(capsys, bits):
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--precision", f"mp:{bits}")
    line = one_error_line(err)
    assert code == 2 and out == ""
    assert f"mp:{bits}" in line and "from 53" in line and "double, long, quad" in line


def test_mpfr_at_the_floor_and_junk_precisions(capsys):
    assert arguments._precision("mp:53").bits == 53
    for bad in ("mp:abc", "mp:", "octuple", "", "mp:99999999999999999999999"):
        code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--precision", bad)
        assert code == 2 and "allowed: double, long, quad or mp:BITS" in one_error_line(err)


# --- spindown at tiny theta --------------------------------------------------------------------

def test_spindown_below_its_smallest_tilt_is_refused(capsys):
    code, out, err = run(capsys, "spindown", "disk", "--theta", "1e-1001")
    line = one_error_line(err)
    assert code == 2 and out == "" and "1e-1001" in line and "1e-1000 <= theta" in line


@pytest.mark.parametrize("theta", ["1e-20", "1e-60", "1e-300"])
def test_spindown_at_tiny_tilts_is_exact(capsys, theta):
    """The disk's cm-at-rest family is Eq. 45 exactly, at any tilt: the working precision grows
    with log10(1/theta), so the 60 digits survive the cancellation (at a fixed 60 digits
    theta = 1e-60 was a ZeroDivisionError)."""
    code, out, err = run(capsys, "spindown", "disk", "--theta", theta, "--format", "json")
    rec = json.loads(out)
    assert code == 0 and abs(mpmath.mpf(rec["relative_error"])) < 1e-45


def test_spindown_negative_control_a_wrong_rate_is_seen(capsys, monkeypatch):
    """The same comparison flags a rate off by one part in 1e30 (the check above can fail)."""
    import verify.studies.spindown as sd

    real = sd.spindown

    def off(*args, **kwargs):
        s = real(*args, **kwargs)
        with mpmath.workdps(80):
            return replace(s, phidot=s.phidot * (1 + mpmath.mpf("1e-30")))

    monkeypatch.setattr(sd, "spindown", off)
    code, out, _ = run(capsys, "spindown", "disk", "--theta", "1e-60", "--format", "json")
    assert code == 0 and abs(mpmath.mpf(json.loads(out)["relative_error"])) > 1e-31


@pytest.mark.parametrize("theta", ["nan", "-inf", "", "abc", "0", "-0.0", "2"])
def test_spindown_bad_theta(capsys, theta):
    code, out, err = run(capsys, "spindown", "ring", "--theta", theta)
    assert code == 2 and one_error_line(err).startswith("error: --theta")


# --- negative numbers as values ------------------------------------------------------------------

@pytest.mark.parametrize("argv,message", [
    (["--tol", "-1e-15"], "--tol -1e-15: allowed a positive finite number"),
    (["--tol", "-1"], "--tol -1: allowed a positive finite number"),
    (["--tol", "-inf"], "--tol -inf: allowed a positive finite number"),
    (["--tol", "-x"], "--tol -x: allowed a positive finite number"),
    (["--n-eval", "-3"], "--n-eval -3 must be at least 2"),
    (["--tol", "--format", "json"], "argument --tol: expected one argument"),
])
def test_negative_values_parse_and_are_checked(capsys, argv, message):
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1", *argv)
    assert code == 2 and message in one_error_line(err)


def test_negative_t_end_and_theta(capsys):
    code, _, err = run(capsys, "trajectory", "disk", "--t-end", "-1e-3", "--state", "theta=1")
    assert code == 2 and "--t-end -1e-3: allowed a positive finite number" in one_error_line(err)
    code, _, err = run(capsys, "spindown", "disk", "--theta", "-1e-3")
    assert code == 2 and "-1e-3" in one_error_line(err)


def test_argparse_errors_are_one_line(capsys):
    for argv in (["trajectory", "--state", "theta=1"], [], ["nope"], ["models", "--format", "xml"], ["trajectory"]):
        code, out, err = run(capsys, *argv)
        assert code == 2 and out == ""
        one_error_line(err)


# --- pipes ---------------------------------------------------------------------------------------

def _shell(command: str):
    return subprocess.run(["bash", "-c", f"set -o pipefail; {command}"], capture_output=True, text=True, env=ENV,
                          cwd=ROOT, timeout=120)


def test_models_into_head_is_quiet():
    p = _shell(f"{sys.executable} -m verify models | head -1")
    assert p.stderr == "" and p.returncode in (0, 141)
    assert p.stdout.startswith("disk:") and p.stdout.count("\n") == 1


def test_a_reader_that_is_gone_before_the_output_exits_141_quietly():
    """`| true` closes the pipe before anything is written: the write fails every time."""
    p = _shell(f"{sys.executable} -m verify trajectory disk --state theta=1.2 --t-end 0.01 --format json | true")
    assert p.returncode == 141 and p.stderr == ""


def test_closed_stdout_and_stderr_are_no_traceback():
    p = _shell(f"{sys.executable} -m verify trajectory disk --state theta=abc --t-end 1 2>&-; echo rc=$?")
    assert p.stdout == "rc=2\n"
    p = _shell(f"{sys.executable} -m verify models >&-")
    assert p.returncode == 1 and p.stderr == "error: stdout is closed; the result was not written\n"


# --- Ctrl-C --------------------------------------------------------------------------------------

def test_ctrl_c_during_a_long_run_exits_130_with_one_line():
    p = subprocess.Popen([sys.executable, "-m", "verify", "trajectory", "disk", "--state", "theta=1.2", "--state",
                          "psidot=10", "--t-end", "1e6", "--progress"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV, cwd=ROOT)
    try:
        first = p.stderr.readline()  # the first progress line: the run is under way
        assert first.startswith("trajectory disk:"), first
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=300)  # not a timing test: only that it ends, at 130
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 130 and out == ""
    lines = [ln for ln in err.splitlines() if not ln.startswith("trajectory disk:")]
    assert lines == ["error: interrupted (Ctrl-C)"], err


def test_ctrl_c_while_heyoka_compiles_for_minutes_exits_130_within_seconds():
    """At mp:100000 heyoka's JIT runs for many minutes inside one C++ call, where Python cannot act
    on Ctrl-C; the CLI's supervisor process (the one the test started; it needs no GIL but its own)
    does, after INTERRUPT_GRACE seconds, with the same one line (and under --format json the error
    document)."""
    p = subprocess.Popen([sys.executable, "-m", "verify", "trajectory", "disk", "--state", "theta=1.2", "--t-end", "1",
                          "--precision", "mp:100000", "--format", "json", "--progress"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=ENV, cwd=ROOT)
    try:
        first = p.stderr.readline()  # progress while compiling: "setting up (compiling the equations)"
        assert first.startswith("trajectory disk: setting up"), first
        p.send_signal(signal.SIGINT)
        # the compile at mp:100000 lasts many minutes, so an exit within 300 s (the supervisor acts after
        # INTERRUPT_GRACE = 2 s) can only be the supervisor's, however loaded the machine
        out, err = p.communicate(timeout=300)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 130
    assert json.loads(out) == {"error": "interrupted (Ctrl-C)", "exit_status": 130}
    assert [ln for ln in err.splitlines() if not ln.startswith("trajectory disk:")] == ["error: interrupted (Ctrl-C)"]


_HOLD_THE_GIL = """
import ctypes, sys
from verify.guard import supervise

argv = sys.argv[1:]
supervise(argv)  # as python -m verify does; what follows runs in the supervised child
import verify.engine.single
from verify import cli, sweep

def hold_the_gil(*args, **kwargs):
    print("holding the GIL", file=sys.stderr, flush=True)
    libc = ctypes.PyDLL(None)  # PyDLL: the call keeps the GIL, as heyoka's JIT may
    mutex = ctypes.create_string_buffer(64)  # zeros: an unlocked glibc mutex
    libc.pthread_mutex_lock(mutex)
    libc.pthread_mutex_lock(mutex)  # locked twice by one thread: waits forever, and signals do not end the wait

verify.engine.single.solve = sweep.run_sweep = hold_the_gil
sys.exit(cli.main(argv))
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="a glibc mutex holds the GIL forever")
@pytest.mark.parametrize("command", ["trajectory", "sweep"])
def test_ctrl_c_while_a_c_call_holds_the_gil_forever_exits_130(command, tmp_path):
    """The defect behind the supervisor, made certain: a C call that holds the GIL and never returns
    (no thread of that process can act), interrupted.  The supervisor ends it with the one line it
    would have said, a sweep's resume note included, and under --format json the error document."""
    spec = os.path.join(ROOT, "verify", "sweep", "specs", "disk-diameter-spin.toml")
    argv = {"trajectory": ["trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--format", "json"],
            "sweep": ["sweep", spec, "--store", str(tmp_path / "s.sqlite"), "--quiet", "--yes"]}[command]
    p = subprocess.Popen([sys.executable, "-c", _HOLD_THE_GIL, *argv], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=ENV, cwd=ROOT)
    try:
        first = p.stderr.readline()
        assert first == "holding the GIL\n", first + p.stderr.read()
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=300)  # the call never returns: only the supervisor can end this
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 130
    line = one_error_line(err)
    if command == "trajectory":
        assert line == "error: interrupted (Ctrl-C)"
        assert json.loads(out) == {"error": "interrupted (Ctrl-C)", "exit_status": 130}
    else:
        assert out == "" and str(tmp_path / "s.sqlite") in line and "rerun the same command to resume" in line


def test_ctrl_c_in_process(capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(single, "solve", interrupted)
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1")
    assert code == 130 and out == "" and one_error_line(err) == "error: interrupted (Ctrl-C)"
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--format", "json")
    assert code == 130 and json.loads(out)["exit_status"] == 130


def test_ctrl_c_during_a_sweep_says_the_store_resumes(capsys, monkeypatch, tmp_path):
    import verify.sweep as sweep

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(sweep, "run_sweep", interrupted)
    store = tmp_path / "s.sqlite"
    spec = os.path.join(ROOT, "verify", "sweep", "specs", "disk-diameter-spin.toml")
    code, out, err = run(capsys, "sweep", spec, "--store", str(store), "--quiet")
    line = one_error_line(err)
    assert code == 130 and out == ""
    assert "interrupted" in line and str(store) in line and "keeps the finished chunks" in line
    assert "rerun the same command to resume" in line


def test_sweep_yes_reaches_run_sweep(capsys, monkeypatch, tmp_path):
    import verify.sweep as sweep

    seen = {}

    def run_sweep(spec, dask=None, threads=None, progress=True, store_path=None, yes=False, senses=None):
        seen.update(yes=yes, senses=senses)
        raise sweep.SpecError("stop here")

    monkeypatch.setattr(sweep, "run_sweep", run_sweep)
    spec = os.path.join(ROOT, "verify", "sweep", "specs", "disk-diameter-spin.toml")
    code, _, err = run(capsys, "sweep", spec, "--store", str(tmp_path / "s.sqlite"), "--quiet", "--yes")
    assert code == 2 and one_error_line(err) == "error: stop here" and seen.get("yes") is True
    assert seen.get("senses") is senses  # the command passes the orbit study's reading (the sweep imports no study)


TINY_SPEC = """
[sweep]
name = "tiny"
model = "disk"
t_end = 0.05
samples = 3
store = "{store}"
[start]
theta = 1.2
psidot = 10
[[axis]]
name = "phidot"
from = 0
to = 1
count = 2
[record]
quantities = ["max_theta"]
"""


def test_sweep_plot_out_a_folder_is_refused_naming_it(capsys, tmp_path):
    spec = tmp_path / "tiny.toml"
    spec.write_text(TINY_SPEC.format(store=tmp_path / "tiny.sqlite"))
    assert run(capsys, "sweep", str(spec), "--quiet")[0] == 0
    folder = tmp_path / "maps"
    folder.mkdir()
    code, out, err = run(capsys, "sweep", str(spec), "--plot", "--out", str(folder))
    line = one_error_line(err)
    assert code == 2 and out == "" and f"--out {folder} is a folder; allowed: a file name" in line
    assert list(folder.iterdir()) == []
    code, out, _ = run(capsys, "sweep", str(spec), "--plot", "--out", str(folder / "map.png"))
    assert code == 0 and (folder / "map.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# --- unexpected errors and --debug -------------------------------------------------------------------

def test_an_unexpected_error_is_one_line_and_debug_shows_the_traceback(capsys, monkeypatch):
    def broken(*args, **kwargs):
        return 1 / 0

    monkeypatch.setattr(single, "solve", broken)
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1")
    line = one_error_line(err)
    assert code == 1 and out == "" and "ZeroDivisionError" in line and "--debug" in line
    code, out, err = run(capsys, "--debug", "trajectory", "disk", "--state", "theta=1", "--t-end", "1")
    assert code == 1 and "Traceback" in err and "ZeroDivisionError" in err
    code, out, err = run(capsys, "trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--debug")
    assert code == 1 and "Traceback" in err


# --- the threshold's bracket in text -----------------------------------------------------------------

def test_threshold_text_prints_the_nonlinear_bracket(capsys, monkeypatch):
    import verify.studies.thresholds as thresholds

    calls = []

    def bracket(name, motion, tilt, params=None, **kwargs):  # the bisection itself is tested in test_thresholds
        calls.append((name, motion, tilt))
        return mpmath.mpf("27.9201208353"), mpmath.mpf("27.920122087")

    monkeypatch.setattr(thresholds, "bracket", bracket)
    code, out, err = run(capsys, "threshold", "disk", "diameter-spin", "--nonlinear-tilt", "1e-4")
    assert code == 0 and calls == [("disk", "diameter-spin", "1e-4")]
    assert "nonlinear bracket at tilt 1e-4 rad: phidot0 in [27.9201208353, 27.920122087] s^-1" in out
    assert "bisection on the rate" in out


# --- progress ---------------------------------------------------------------------------------------

def _until_reported(stream, text, seconds):
    """Wait while a progress thread runs and has not yet written ``text`` (as long as the machine's
    load needs, up to ``seconds``); with no progress thread there is nothing to wait for."""
    import threading

    deadline = time.monotonic() + seconds
    while (any(t.name == "verify-progress" for t in threading.enumerate()) and text not in stream.getvalue()
           and time.monotonic() < deadline):
        time.sleep(0.01)


def _slow_solve(seconds):
    real = single.solve

    def solve(model, t_end, state=None, params=None, *, progress=None, **kwargs):
        if progress is not None:
            for k in range(1, 6):
                progress(float(t_end) * k / 10, 100 * k)
        _until_reported(sys.stderr, "steps/s", seconds)
        return real(model, t_end, state, params, **kwargs)

    return solve


def test_progress_through_solves_hook(capsys, monkeypatch):
    """With solve(progress=callable(t, steps)) the CLI shows t, steps and the rate on stderr: by default where
    stderr is a terminal (captured here: not one, so none), with --progress anywhere; with --format json only
    under --progress."""
    monkeypatch.setattr(progress, "PROGRESS_INTERVAL", 0.05)
    monkeypatch.setattr(single, "solve", _slow_solve(60))
    argv = ["trajectory", "disk", "--state", "theta=1.2", "--state", "psidot=10", "--t-end", "1"]
    code, out, err = run(capsys, *argv)
    assert code == 0 and "outcome     ok" in out and "steps/s" not in err
    code, out, err = run(capsys, *argv, "--progress")
    assert code == 0 and "outcome     ok" in out
    assert "trajectory disk: t = 0.5 of 1 s (50 %), 500 steps" in err and "steps/s" in err
    code, out, err = run(capsys, *argv, "--format", "json")
    assert code == 0 and json.loads(out)["outcome"] == "ok" and err == ""
    code, out, err = run(capsys, *argv, "--format", "json", "--progress")
    assert code == 0 and json.loads(out)["outcome"] == "ok" and "trajectory disk: t = " in err
    code, out, err = run(capsys, *argv, "--no-progress")
    assert code == 0 and err == ""


def test_progress_before_the_first_step_says_the_equations_compile():
    import io

    stream = io.StringIO()
    bar = progress._Progress(stream, "trajectory disk", "1e6", True, interval=0.05)
    with bar:
        _until_reported(stream, "setting up", 60)
    assert "trajectory disk: setting up (compiling the equations), t_end = 1e6 s" in stream.getvalue()


def test_a_curve_body_has_no_threshold_and_says_so_at_once(capsys):
    """The egg's steady motions are not built (sympy ran past ten minutes on them): threshold refuses it in one
    line before any analysis starts, whatever motion is named; a body of another kind still answers."""
    for argv in (("threshold", "--body", "egg", "nosuchmotion"), ("threshold", "body:egg", "straight-line")):
        code, out, err = run(capsys, *argv)
        assert code == 2 and "curve body" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
    code, out, err = run(capsys, "threshold", "body:disk", "straight-line")
    assert code == 0 and "psidot0 = 18.07392228230127" in out


def test_a_sweep_map_is_written_as_png_only(tmp_path, capsys):
    spec = tmp_path / "s.toml"
    spec.write_text(f'[sweep]\nname = "s"\nmodel = "disk"\nt_end = 0.2\nsamples = 3\nchunk = 4\nstore = "{tmp_path / "s.sqlite"}"\n'
                    '[start]\ntheta = 1.2\n[[axis]]\nname = "psidot"\nfrom = 1\nto = 2\ncount = 2\n'
                    '[record]\nquantities = ["max_theta"]\n')
    assert run(capsys, "sweep", str(spec))[0] == 0
    code, out, err = run(capsys, "sweep", str(spec), "--plot", "--out", str(tmp_path / "m.bmp"))
    assert code == 2 and ".png" in err and not (tmp_path / "m.bmp").exists()
    code, out, err = run(capsys, "sweep", str(spec), "--plot", "--out", str(tmp_path / "m.png"))
    assert code == 0 and (tmp_path / "m.png").read_bytes()[:4] == b"\x89PNG"

"""Property-based tests of the command line (hypothesis).

Property, for any argv built from model names, state and parameter names and values (NaN, +-inf,
huge, tiny, -0.0, words, empty), precisions, --t-end, --tol and --n-eval:

* exit 0 with valid output (under --format json: exactly one JSON document, ``json.loads`` of all
  of stdout), or exit 2 with exactly one line on stderr naming a value given, or exit 1 (a failed
  integration) with exactly one line, heyoka's own log lines aside;
* never a traceback, never an "unexpected" error (the CLI's catch-all for bugs);
* nothing written to the working directory (hypothesis' example database is off).

Budget: ``FAST`` examples a property in ``make test`` (derandomized: the same cases every time);
``SLOW``, drawn afresh, under the ``slow`` marker (``make test-all``); ``VERIFY_FUZZ_EXAMPLES=N``
overrides both.  Runs are short (t_end <= 0.01, theta >= 0.8 where the disk's Chaplygin integrals
are cheap to evaluate).
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from models import ALL_NAMES, get_model  # noqa: E402
from models.symbols import STATE_NAMES  # noqa: E402
from verify.cli import main  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FAST, SLOW = 25, 400


def budget(n: int):
    """The examples of one property: the ``make test`` budget is derandomized (the same cases on
    every run, so that the suite does not flake), larger ones explore afresh each time."""
    n = int(os.environ.get("VERIFY_FUZZ_EXAMPLES", n))
    return settings(max_examples=n, deadline=None, database=None, derandomize=n <= FAST,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    """An empty working directory for the whole module; it must stay empty."""
    here = os.getcwd()
    path = tmp_path_factory.mktemp("fuzz-cwd")
    os.chdir(path)
    try:
        yield path
    finally:
        os.chdir(here)
    assert list(path.iterdir()) == [], "the CLI wrote to the working directory"


# --- strategies ---------------------------------------------------------------------------------

ODD = ["nan", "NaN", "-nan", "inf", "-inf", "+inf", "Infinity", "1e400", "-1e400", "1e-400", "5e-324", "0", "-0.0",
       "", " ", "abc", "1_0", "0x10", "1.2.3", "\u0661", "1e", "e5", "--1", "1/4", "1,5", "+", "-", "1e99999", "=", "\x00"]


def _float_text(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False).map(repr)


def mostly(valid, invalid, odds: int = 5):
    """``valid`` (odds - 1 times in odds) or ``invalid``: most argvs are valid in most of their parts,
    so that a fair share of the cases run, and each bad part is met alone as well as in company."""
    return st.integers(0, odds - 1).flatmap(lambda i: invalid if i == odds - 1 else valid)


BAD_VALUES = st.one_of(st.sampled_from(ODD), _float_text(-1e300, 1e300), st.text(max_size=6))
VALUES = mostly(_float_text(-20, 20), BAD_VALUES)
THETA = mostly(_float_text(0.8, 1.4), st.sampled_from(ODD + ["1e-300", "1.5707963267948966", "3.2", "0.05"]))
GOOD_PRECISIONS = ["double"] * 6 + ["long", "quad", "mp:64"]
BAD_PRECISIONS = ["mp:0", "mp:-5", "mp:abc", "mp:2", "mp:52", "mp:", "MP:64", "quad ", "Double",
                  "mp:99999999999999999999", "float", "", "mp:1e3", "mp:64.0"]
PRECISIONS = GOOD_PRECISIONS + BAD_PRECISIONS
T_END = mostly(st.one_of(st.sampled_from(["0.01", "0.005", "1e-3"]), _float_text(1e-6, 0.01)),
               st.sampled_from(["0", "-0.0", "-1", "-1e-15", "nan", "inf", "-inf", "abc", "", "1e-400", "5e-324",
                                "1e-310", " 0.01", "0.01s", "1e-320"]))
TOL = mostly(st.sampled_from([None, None, None, "1e-15", "1e-10", "1e-6", "1e-16", "1"]),
             st.sampled_from(["0", "-1e-15", "nan", "abc", "1e-400", "1e300", "-0.0", "", "inf"]))
N_EVAL = mostly(st.sampled_from([None, None, None, "2", "3", "11", "101", "1000"]),
                st.sampled_from(["1", "0", "-5", "abc", "1e3", "2.5", "1000001", "", " 7", "99999999999999999999"]))
MODEL = mostly(st.sampled_from(ALL_NAMES), st.sampled_from(["disc", "", "DISK", "disk ", "ring+", "-ring"]), odds=10)
STATE_NAME = mostly(st.sampled_from(STATE_NAMES[1:]), st.sampled_from(["omega", "", "theta ", "Theta", "=", "x=1"]))


@st.composite
def trajectory_argv(draw):
    model = draw(MODEL)
    fmt = draw(st.sampled_from(["json", "text"]))
    argv = ["trajectory", model, "--t-end", draw(T_END), "--format", fmt]
    argv += ["--state", f"theta={draw(THETA)}"]
    for name in draw(st.lists(STATE_NAME, max_size=3, unique=True)):
        argv += ["--state", f"{name}={draw(VALUES)}"]
    if model in ALL_NAMES and draw(st.integers(0, 4)) == 0:
        pnames = list(get_model(model).parameter_names) + ["kk", ""]
        for name in draw(st.lists(st.sampled_from(pnames), max_size=2, unique=True)):
            argv += ["--param", f"{name}={draw(st.one_of(VALUES, _float_text(0.01, 2)))}"]
    precision = draw(mostly(st.sampled_from(GOOD_PRECISIONS), st.sampled_from(BAD_PRECISIONS)))
    if precision != "double" or draw(st.booleans()):
        argv += ["--precision", precision]
    for option, strategy in (("--tol", TOL), ("--n-eval", N_EVAL)):
        value = draw(strategy)
        if value is not None:
            argv += [option, value] if draw(st.booleans()) else [f"{option}={value}"]
    if draw(st.integers(0, 3)) == 0:
        argv += ["--equations", draw(st.sampled_from(["derived", "paper", "paper", "", "printed"]))]
    return argv, fmt


# --- the property -------------------------------------------------------------------------------

def call(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(argv))
    return code, out.getvalue(), err.getvalue()


def check(argv, fmt):
    json_mode = fmt == "json"
    code, out, err = call(argv)
    note = f"argv={argv!r}\nexit {code}\nstdout={out[:500]!r}\nstderr={err[:1000]!r}"
    assert "Traceback" not in err and "Traceback" not in out, note
    assert "unexpected" not in err, note
    assert code in (0, 1, 2), note
    if json_mode and (code == 0 or out):
        json.loads(out)  # all of stdout: exactly one document
    lines = [ln for ln in err.splitlines() if ln.strip() and "[heyoka" not in ln and not ln.startswith("trajectory ")]
    if code == 0:
        assert out.strip() and lines == [], note
        if json_mode:
            assert json.loads(out).get("outcome", "ok") == "ok" or json.loads(out)["outcome"].startswith("event:"), note
        return code
    assert len(lines) == 1 and lines[0].startswith("error: "), note
    if code == 2:
        shown = lines[0]
        # the values the user gave, not the command's own words: no subcommand, no option names, no --format
        # value (every message would contain one of those, and the check could not fail)
        values = [a for i, a in enumerate(argv[1:], 1)
                  if not (a.startswith("--") and a[2:3].isalpha()) and argv[i - 1] != "--format"]
        values += [a.partition("=")[2] for a in argv if a.startswith("--") and "=" in a]  # --tol=VALUE
        given = values + [part for a in values if "=" in a for part in a.partition("=")[::2]]
        # (a value that looks like an option, '-ring' for the model, leaves the positional missing: argparse
        # then names the missing argument instead of the value)
        assert any((g.strip() and g.strip() in shown) or repr(g) in shown or repr(g.strip()) in shown for g in given) \
            or ("the following arguments are required" in shown and any(g.startswith("-") for g in values)), note
    return code


@budget(FAST)
@given(trajectory_argv())
def test_trajectory_fuzz(workdir, case):
    check(*case)


@pytest.mark.slow
@budget(SLOW)
@given(trajectory_argv())
def test_trajectory_fuzz_long(workdir, case):
    check(*case)


@budget(FAST)
@given(st.sampled_from(PRECISIONS + ["mp:53", "mp:3", "mp:4", " mp:64", "mp:+64", "mp:-0"]),
       st.sampled_from(["json", "text"]))
def test_precision_fuzz(workdir, precision, fmt):
    check(["trajectory", "disk", "--state", "theta=1.2", "--state", "psidot=10", "--t-end", "0.01",
           "--precision", precision, "--format", fmt], fmt)


def _study_argv():
    spindown = st.builds(lambda m, th, fam, fmt: (["spindown", m, "--theta", th, "--family", fam, "--format", fmt], fmt),
                         st.sampled_from(["disk", "ring", "hurricane", "", "disc"]),
                         st.one_of(THETA, st.sampled_from(["1e-20", "1e-19", "1e-21", "1e-60", "0.1"])),
                         st.sampled_from(["cm-at-rest", "zero-vertical-spin", "", "x"]), st.sampled_from(["json", "text"]))
    threshold = st.builds(
        lambda m, mo, p, fmt: (["threshold", m, mo, "--format", fmt] + (["--param", p] if p else []), fmt),
        st.sampled_from(["disk", "ring", "hurricane", "sliding-disk", "gyroscope", "effective", "x"]),
        st.sampled_from(["diameter-spin", "straight-line", "precession", "sleeping", "", "spin"]),
        st.one_of(st.none(), st.builds(lambda n, v: f"{n}={v}", st.sampled_from(["k", "g", "I1", "I3", "h", "zz"]),
                                       st.one_of(st.sampled_from(ODD), _float_text(0.01, 2)))),
        st.sampled_from(["json", "text"]))
    return st.one_of(spindown, threshold)


@budget(FAST)
@given(_study_argv())
def test_study_fuzz(workdir, case):
    check(*case)


@pytest.mark.slow
@budget(SLOW)
@given(_study_argv())
def test_study_fuzz_long(workdir, case):
    check(*case)


# --- a few real processes -------------------------------------------------------------------------

@pytest.mark.parametrize("argv", [
    ["trajectory", "disk", "--state", "theta=nan", "--t-end", "0.01", "--format", "json"],
    ["trajectory", "disk", "--state", "theta=1.2", "--t-end", "0.01", "--precision", "mp:-5", "--format", "json"],
    ["trajectory", "ring", "--state", "theta=1", "--state", "phidot=-3", "--t-end", "0.01", "--tol", "-1e-15"],
    ["trajectory", "disk", "--state", "theta=1.2", "--state", "psidot=-0.0", "--t-end", "0.01", "--format", "json"],
])
def test_in_a_real_process(tmp_path, argv):
    env = dict(os.environ, PYTHONPATH=ROOT)
    p = subprocess.run([sys.executable, "-m", "verify", *argv], capture_output=True, text=True, env=env, cwd=tmp_path,
                       timeout=120)
    assert "Traceback" not in p.stderr and p.returncode in (0, 2)
    if "json" in argv:
        json.loads(p.stdout)
    if p.returncode == 2:
        assert len(p.stderr.splitlines()) == 1
    assert list(tmp_path.iterdir()) == []

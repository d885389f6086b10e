"""Starts a person can type: named and default starts, values as exact expressions, and listings that answer at once."""
import json
import os
import random
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from models.catalogue import ALIASES, ALL_NAMES, COULOMB_NAMES
from verify.cli import main
from verify.cli.arguments import MP_MIN_BITS
from verify.expressions import ExpressionError, read_value
from verify.precision import MIN_MPFR_BITS, parse_precision
from verify.series import read_run
from verify.starts import all_starts, default_start, find

ROOT = Path(__file__).resolve().parent.parent


def _main(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("model", ALL_NAMES + COULOMB_NAMES + tuple(ALIASES))
def test_every_model_runs_from_its_default_start(capsys, model):
    code, out, err = _main(capsys, "trajectory", model, "--format", "json", "--t-end", "0.5")
    assert code == 0, err
    record = json.loads(out)
    assert record["outcome"] == "ok" or record["outcome"].startswith("event:")
    assert record["start"].startswith(f"the default start of {model}")


def test_names_are_unique_and_every_figure_panel_and_reference_case_is_there():
    names = [s.name for s in all_starts()]
    assert len(names) == len(set(names))
    from verify.figure_starts import STARTS, figures_with_runs, panel_sides

    for n in figures_with_runs():
        for side in panel_sides(n) or (None,):
            assert any(s.figure == n and s.side == side for s in STARTS)
    cases = json.loads((ROOT / "reports" / "reference" / "index.json").read_text())["cases"]
    assert {c["name"] for c in cases} <= set(names)


def test_a_figure_start_on_the_command_line_is_the_report_s_run(capsys, tmp_path):
    """trajectory --start fig5-lhs gives the bits of the run the report draws for Fig. 5 LHS."""
    from verify.claims.simulations.runs import run_start

    _, data = run_start("fig5-lhs", "Fig. 5 LHS")
    code, _, err = _main(capsys, "trajectory", "--start", "fig5-lhs", "--output", str(tmp_path / "r.npz"))
    assert code == 0, err
    cols = read_run(tmp_path / "r.npz")
    assert np.array_equal(cols.values["theta"], np.array(data.theta)) and np.array_equal(cols.values["x"], np.array(data.x))


def test_a_reference_start_reads_exact_parameters(capsys):
    start = find("ring-standard-10")
    assert start.params["I1"] == "16720/33489"
    code, out, _ = _main(capsys, "trajectory", "--start", "ring-standard-10", "--t-end", "0.1", "--format", "json",
                         "--precision", "quad")
    assert code == 0
    assert json.loads(out)["params"]["I1"] == str(parse_precision("quad").number(sp.Rational(16720, 33489)))


def test_overrides_and_mismatches(capsys):
    code, out, _ = _main(capsys, "trajectory", "--start", "disk-standard-1", "--state", "psidot=12", "--t-end", "0.1",
                         "--format", "json")
    assert code == 0 and json.loads(out)["start"].startswith("--start disk-standard-1")
    code, _, err = _main(capsys, "trajectory", "ring", "--start", "disk-standard-1")
    assert code == 2 and "a start of the model 'disk', not 'ring'" in err
    code, _, err = _main(capsys, "trajectory", "hoop", "--param", "k=0.3")
    assert code == 2 and "'hoop' is the disk with k = 0.5" in err
    assert default_start("hoop").params["k"] == "0.5"


@pytest.mark.parametrize("text, exact", [
    ("pi/2", sp.pi / 2), ("pi/2 - 0.05", sp.pi / 2 - sp.Rational(1, 20)), ("sqrt(980/1.25)", sp.Integer(28)),
    ("2**-3", sp.Rational(1, 8)), ("-e", -sp.E), ("acos(2/5)", sp.acos(sp.Rational(2, 5))), ("1e-3*pi", sp.pi / 1000),
])
def test_expressions_are_read_exactly(text, exact):
    value = read_value(text)
    assert sp.simplify(value - exact) == 0
    for precision in ("double", "quad", "mp:256"):
        p = parse_precision(precision)
        assert p.number(value) == p.number(exact)


def test_a_decimal_stays_text():
    assert read_value(" 1.25 ") == "1.25" and read_value("-3e-4") == "-3e-4"


@pytest.mark.parametrize("text", ["((10**1000)**1000)**1000", "(((9**999)**999)**999)**999", "exp(exp(exp(exp(10))))",
                                  "sin(exp(exp(1000)))", "__import__('os')", "x + 1", "(1).real", "[1]", "lambda: 1", "2**10**10", "sqrt(-1)",
                                  "1/0", "log(0)", "pi/2x", "", "sin(1, 2)", "f(1)", "1 if 1 else 2", "'a'", "True"])
def test_anything_else_is_refused_with_one_line(text):
    with pytest.raises(ExpressionError) as err:
        read_value(text, "--state theta")
    assert "--state theta" in str(err.value) and "\n" not in str(err.value)


def test_random_expressions_agree_with_sympy():
    """Property: random sums and products of decimals, pi and sqrt read to sympy's exact value."""
    rng = random.Random(29)
    atoms = ["pi", "e", "sqrt(2)", "0.1", "3", "1.5e-2", "(7/3)"]
    for _ in range(50):
        text = rng.choice(atoms)
        for _ in range(rng.randint(1, 4)):
            text = f"({text}) {rng.choice('+-*/')} {rng.choice(atoms)}"
        expected = sp.sympify(text.replace("e", "E").replace("1.5E-2", "(3/200)").replace("0.1", "(1/10)"),
                              rational=True)
        assert sp.simplify(read_value(text) - expected) == 0, text


def test_the_cli_knows_the_mpfr_floor():
    assert MP_MIN_BITS == MIN_MPFR_BITS


@pytest.mark.parametrize("argv", [["--help"], ["models"], ["starts"], ["figure", "--list"], ["trajectory", "--help"]])
def test_listings_import_nothing_heavy(argv):
    """--help and the listings answer at once: no sympy, heyoka, numpy or matplotlib is imported."""
    res = subprocess.run([sys.executable, "-X", "importtime", "-m", "verify", *argv], capture_output=True, text=True,
                         cwd=ROOT, env=dict(os.environ, PYTHONPATH=str(ROOT)), timeout=120)
    assert res.returncode == 0, res.stderr[-500:]
    imported = {line.split("|")[-1].strip().split(".")[0] for line in res.stderr.splitlines()
                if line.startswith("import time:")}
    assert imported.isdisjoint({"sympy", "heyoka", "numpy", "matplotlib", "mpmath"}), argv

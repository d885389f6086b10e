"""The light scorer: ``from verify.scoring import score`` and a score on the grid times need numpy and
mpmath only; its numpy geometry is the symbolic one of verify.frames and models (this test uses sympy)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import STATE, theta
from verify.frames import (BODIES_ON_PLANE, contact_vector, euler_to_b, from_euler_expressions, quaternion,
                           rotation_matrix)
from verify.scoring import score
from verify import contact_geometry as geometry
from verify.scoring.casefiles import load_set

ROOT = Path(__file__).resolve().parent.parent
MODELS = ("disk", "ring", "hurricane", "sliding-disk", "gyroscope", "effective")
RNG = np.random.default_rng(20261127)


def _states(n=50):
    """Random states away from theta = 0, pi (where phidot = (w . e2) / sin theta is singular)."""
    return {"theta": RNG.uniform(0.2, np.pi - 0.2, n), "phi": RNG.uniform(-20, 20, n), "psi": RNG.uniform(-20, 20, n),
            "thetadot": RNG.uniform(-10, 10, n), "phidot": RNG.uniform(-10, 10, n), "psidot": RNG.uniform(-30, 30, n),
            "x": RNG.uniform(-5, 5, n), "y": RNG.uniform(-5, 5, n)}


def _params(model):
    return {p.name: float(p.default) for p in get_model(model).parameters}


def _exact(expr, args, values):
    """``expr`` at every row of ``values`` (a list of arrays) at 30 digits, rounded to doubles."""
    f = sp.lambdify(args, expr, "mpmath")
    with mpmath.workdps(30):
        return np.array([float(f(*[mpmath.mpf(float(v[i])) for v in values])) for i in range(len(values[0]))])


@pytest.mark.parametrize("model", MODELS)
def test_energy_is_the_models_expression(model):
    m = get_model(model)
    _, names = geometry.ENERGY[model]
    assert names == tuple(p.name for p in m.parameters)
    s, p = _states(), _params(model)
    got = geometry.energy(model, s, p)
    args = list(STATE) + [q.symbol for q in m.parameters]
    values = [s[n] for n in geometry.STATE_NAMES] + [np.full(50, p[q]) for q in names]
    np.testing.assert_allclose(got, _exact(m.energy, args, values), rtol=1e-14, atol=1e-14 * np.max(np.abs(got)))
    # the very doubles of the symbolic path the scorer used before (sympy.lambdify to numpy)
    old = sp.lambdify(args, m.energy, "numpy")(*values)
    assert np.array_equal(np.broadcast_to(old, got.shape), got)


@pytest.mark.parametrize("model", BODIES_ON_PLANE)
def test_contact_vector_is_the_papers(model):
    s, p = _states(), _params(model)
    got = geometry.contact_vector(model, s["theta"], s["phi"], p)
    args = list(STATE) + [q.symbol for q in get_model(model).parameters]
    values = [s[n] for n in geometry.STATE_NAMES] + [np.full(50, p[q.name]) for q in get_model(model).parameters]
    for i in range(3):
        np.testing.assert_allclose(got[i], _exact(contact_vector(model)[i], args, values), rtol=1e-14, atol=1e-15)
    # and the height of C that form (b) writes is -z of r_P
    np.testing.assert_allclose(-got[2], _exact(from_euler_expressions(model)["z"], args, values), rtol=1e-14,
                               atol=1e-15)


def test_rotation_and_quaternion_are_the_symbolic_ones():
    s = _states()
    args = [theta] + list(STATE[1:3])
    values = [s["theta"], s["phi"], s["psi"]]
    R = geometry.rotation_from_euler(*values)
    Rq = geometry.matrix_from_quaternion(*[_exact(q, args, values) for q in quaternion()])
    for i in range(3):
        for j in range(3):
            exact = _exact(rotation_matrix()[i, j], args, values)
            np.testing.assert_allclose(R[i, j], exact, rtol=0, atol=1e-14)
            np.testing.assert_allclose(Rq[i, j], exact, rtol=0, atol=1e-14)


@pytest.mark.parametrize("model", BODIES_ON_PLANE)
@pytest.mark.parametrize("rotation", ["matrix", "quaternion"])
def test_b_to_euler_inverts_the_symbolic_form_b_and_the_constraints_hold(model, rotation):
    s, p = _states(), _params(model)
    b = euler_to_b(model, s, p)
    columns = {k: v for k, v in b.items() if (k[0] != "q" if rotation == "matrix" else k[0] != "R")}
    back, R, w = geometry.b_to_euler(columns)
    for n in geometry.STATE_NAMES:
        d = back[n] - s[n]
        if n in ("phi", "psi"):
            d = np.remainder(d + np.pi, 2 * np.pi) - np.pi
        scale = 30.0 if n.endswith("dot") else 10.0
        assert np.max(np.abs(d)) < 1e-13 * scale, n
    assert np.max(geometry.rotation_defect(R, columns)) < 1e-14
    height, speed = geometry.contact_point(model, columns, back, w, p)
    assert np.max(np.abs(height)) < 1e-14 and np.max(speed) < 1e-12


# --- the scoring path itself, in a fresh interpreter --------------------------------------------------------

CASE = "disk-standard-1"


def _case_run(form: str, off_grid: bool = False) -> dict:
    (record,) = load_set(names=[CASE])
    t = np.array([float(v) for v in record["grid"]])
    if off_grid:
        t[5] += 1e-3  # one time not on the grid
    state = {n: np.array([float(v) for v in record["state"][n]["double"]]) for n in geometry.STATE_NAMES}
    if form == "euler":
        return {"t": t, **state}
    params = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    return {"t": t, **{k: v for k, v in euler_to_b("disk", state, params).items() if k[0] != "R"}}


def _write_csv(path: Path, columns: dict) -> Path:
    names = list(columns)
    rows = [",".join(names)] + [",".join(repr(float(columns[n][i])) for n in names) for i in range(len(columns["t"]))]
    path.write_text("\n".join(rows) + "\n")
    return path


def _light(code: str, block: bool = False) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter; with ``block``, heyoka and sympy cannot be imported there."""
    shim = "import sys; sys.modules['heyoka'] = None; sys.modules['sympy'] = None\n" if block else "import sys\n"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-c", shim + code], capture_output=True, text=True, env=env, cwd=ROOT,
                          timeout=300)


@pytest.mark.parametrize("form", ["euler", "quaternion"])
def test_scoring_imports_neither_sympy_nor_heyoka_and_scores_as_the_full_suite(form, tmp_path):
    path = _write_csv(tmp_path / f"{form}.csv", _case_run(form))
    code = (f"import json\nfrom verify.scoring import score\ns = score({str(path)!r}, {CASE!r})\n"
            "heavy = sorted({m.split('.')[0] for m in sys.modules} & {'sympy', 'heyoka', 'models', 'matplotlib'})\n"
            "assert not heavy, heavy\nprint(json.dumps(s.to_record()))\n")
    done = _light(code)
    assert done.returncode == 0, done.stderr
    light = json.loads(done.stdout)
    full = json.loads(json.dumps(score(path, CASE).to_record()))  # here sympy and the models are loaded
    assert light == full
    assert light["reference_source"] == "stored grid" and light["form"] == form


def test_the_command_line_scores_without_sympy_or_heyoka(tmp_path):
    path = _write_csv(tmp_path / "run.csv", _case_run("euler"))
    done = _light("from verify.cli import main\nsys.argv = ['verify', 'score', "
                  f"{str(path)!r}, '--case', {CASE!r}, '--min-digits', '6']\nsys.exit(main())\n", block=True)
    assert done.returncode == 0, done.stderr
    assert "PASS" in done.stdout


def test_off_grid_times_without_heyoka_are_refused_in_one_line(tmp_path):
    path = _write_csv(tmp_path / "off.csv", _case_run("euler", off_grid=True))
    done = _light("from verify.scoring import InvalidRun, score\ntry:\n"
                  f"    score({str(path)!r}, {CASE!r})\nexcept InvalidRun as err:\n    print(err)\n", block=True)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("the run's times are not the case's grid times (t = ")
    assert "without heyoka" in lines[0] and "give the grid times (listed in the case file" in lines[0]
    assert "install the full suite" in lines[0]
    # with heyoka present the same times are scored against a quad re-integration, as before
    # (tests/test_score.py::test_off_grid_times_are_scored_against_a_quad_reintegration_that_matches_the_stored_grid)


"""Scoring another simulator's run against the reference set (verify.score, verify.scoring) and the export.

The runs here are synthetic: the stored reference trajectory, perturbed by a known amount,
converted to the rotation-matrix form, wrapped modulo 2 pi, or put in a wrong frame.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.symbols import STATE, STATE_NAMES, frame_vectors, omega_body, phidot, psidot, thetadot, to_inertial
from verify.reference.store import DIRECTORY, load_set
from verify.scoring import InvalidRun, score
from verify.frames import QUATERNION, euler_to_b, from_euler_expressions, rotation_matrix
from verify.scoring.agreement import _reference

CASE = "disk-standard-1"


def _stored(case=CASE):
    (record,) = load_set(DIRECTORY, [case])
    cols = {"t": np.array([float(s) for s in record["grid"]])}
    cols.update({n: np.array([float(v) for v in record["state"][n]["value"]]) for n in STATE_NAMES})
    params = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    return record, cols, params


def _documented_scales(cols) -> dict:
    """The scales the README documents, written out here (not the scorer's ``_scales``, so a wrong scale
    there would not cancel): pi for the angles, the largest |rate| for the rates, the largest horizontal
    distance of C (at least 1) for x and y; each as (value, description) like the scorer's."""
    rate = max(float(np.max(np.abs(cols[n]))) for n in ("thetadot", "phidot", "psidot"))
    length = max(1.0, float(np.max(np.sqrt(cols["x"] ** 2 + cols["y"] ** 2))))
    out = {n: (math.pi, "pi") for n in ("theta", "phi", "psi")}
    out.update({n: (rate, "rate") for n in ("thetadot", "phidot", "psidot")})
    out.update({n: (length, "length") for n in ("x", "y")})
    return out


def _perturbed(cols, delta):
    """Every component moved by delta times its documented scale after t = 0 (the start stays the case's,
    as a real run's does), the sign alternating over time."""
    scales = _documented_scales(cols)
    sign = np.where(np.arange(len(cols["t"])) % 2 == 0, 1.0, -1.0)
    sign[0] = 0.0
    out = {"t": cols["t"]}
    out.update({n: cols[n] + sign * delta * scales[n][0] for n in STATE_NAMES})
    return out


def _form_b(model, euler, params, rotation="matrix"):
    b = euler_to_b(model, {n: euler[n] for n in STATE_NAMES}, params)
    drop = QUATERNION if rotation == "matrix" else tuple(k for k in b if k.startswith("R"))
    return {"t": euler["t"], **{k: v for k, v in b.items() if k not in drop}}


@pytest.mark.parametrize("exponent", [5, 8, 11])
def test_a_perturbed_copy_scores_the_digits_of_its_perturbation(exponent):
    _, cols, _ = _stored()
    s = score(_perturbed(cols, 10.0 ** -exponent), CASE)
    assert s.reference_source == "stored grid"
    for n, c in s.components.items():
        # the perturbation is delta x scale exactly, up to the doubles' rounding (1e-16 of the scale)
        assert c.min_digits == pytest.approx(exponent, abs=1e-3), n
        assert c.median_digits == pytest.approx(exponent, abs=1e-3), n
    assert s.min_digits == pytest.approx(exponent, abs=1e-3)
    assert f"to {exponent}.0 digits over the whole case" in s.verdict and not s.partial


def test_an_exact_copy_scores_a_doubles_resolution_and_an_angle_off_by_pi_scores_zero():
    _, cols, _ = _stored()
    exact = score(cols, CASE)
    assert exact.components["theta"].min_digits > 15.5
    bad = dict(cols)
    bad["psi"] = cols["psi"] + np.where(cols["t"] > 0.5, math.pi, 0.0)  # half a turn off, after the start
    s = score(bad, CASE)
    assert s.components["psi"].min_digits == pytest.approx(0.0, abs=1e-12)  # modulo 2 pi hides nothing but turns


@pytest.mark.parametrize("case,rotation", [(CASE, "matrix"), (CASE, "quaternion"), ("ring-standard-10", "matrix"),
                                           ("hurricane-fig18-lhs", "quaternion")])
def test_the_same_run_in_form_b_scores_as_in_form_a(case, rotation):
    record, cols, params = _stored(case)
    run = _perturbed(cols, 1e-9)
    a = score(run, case)
    b = score(_form_b(record["model"]["name"], run, params, rotation), case)
    assert b.form == rotation
    for n in STATE_NAMES:
        assert b.components[n].min_digits == pytest.approx(a.components[n].min_digits, abs=0.02), n
    # the constraints of a run converted from an exact Euler state hold to rounding (lengths ~1, rates ~300)
    assert b.contact_height < 1e-14 and b.contact_velocity < 1e-11 and b.rotation_defect < 1e-14


def test_form_b_is_the_papers_frame_independently():
    """R's columns are b1, b2, e3 of models.symbols; dR/dt R^T is the paper's omega; v_C the model's; q is R."""
    R = rotation_matrix()
    e1, e2, e3 = frame_vectors()
    rng = np.random.default_rng(1)
    w = to_inertial(omega_body())
    rdot = sum((R.diff(q) * r for q, r in zip(STATE[:3], (thetadot, phidot, psidot))), sp.zeros(3, 3))
    spin = rdot * R.T
    exprs = from_euler_expressions("disk")
    model = get_model("disk")
    for _ in range(3):
        values = dict(zip(STATE, rng.uniform(-3, 3, 8)))
        values[STATE[0]] = rng.uniform(0.2, 3.0)
        num = lambda e, values=values: float(sp.N(e.subs(values)))  # noqa: E731
        assert [num(v) for v in R[:, 2]] == pytest.approx([num(v) for v in e3], abs=1e-13)
        assert [num(v) for v in R[:, 0]] == pytest.approx(
            [num(sp.cos(STATE[2]) * a + sp.sin(STATE[2]) * b) for a, b in zip(e1, e2)], abs=1e-13)
        assert [num(spin[2, 1]), num(spin[0, 2]), num(spin[1, 0])] == pytest.approx([num(c) for c in w], abs=1e-12)
        # rolling: v_C = -omega x r_P with r_P = -e2 (paper Eq. 7), against the model's own velocity_xy
        v = -w.cross(-e2)
        assert [num(exprs["vx"]), num(exprs["vy"]), num(exprs["vz"])] == pytest.approx([num(c) for c in v], abs=1e-12)
        assert [num(c) for c in model.velocity_xy] == pytest.approx([num(v[0]), num(v[1])], abs=1e-12)
        qw, qx, qy, qz = (num(exprs[c]) for c in QUATERNION)
        from verify.frames import matrix_from_quaternion

        Rq = matrix_from_quaternion(*(np.array([c]) for c in (qw, qx, qy, qz)))[:, :, 0]
        assert Rq == pytest.approx(np.array([[num(c) for c in row] for row in R.tolist()]), abs=1e-13)


def test_angles_wrapped_modulo_2pi_score_as_unwrapped():
    record, cols, params = _stored("hurricane-fig18-lhs")  # psi reaches about 10^3 rad
    run = _perturbed(cols, 1e-10)
    wrapped = dict(run)
    for n in ("phi", "psi"):
        wrapped[n] = np.remainder(run[n] + np.pi, 2 * np.pi) - np.pi
    assert np.max(np.abs(run["psi"])) > 100
    a, w = score(run, "hurricane-fig18-lhs"), score(wrapped, "hurricane-fig18-lhs")
    for n in STATE_NAMES:
        assert w.components[n].min_digits == pytest.approx(a.components[n].min_digits, abs=0.01), n


def test_off_grid_times_are_scored_against_a_quad_reintegration_that_matches_the_stored_grid():
    record, cols, _ = _stored()
    shifted = dict(record, grid=["0", "1"])  # forces the quad path at the stored grid's own times
    quad, source, _ = _reference(shifted, cols["t"])
    stored, _, _ = _reference(record, cols["t"])
    assert source == "quad re-integration"
    for n in STATE_NAMES:
        assert np.max(np.abs(quad[n] - stored[n])) <= 1e-15 * _documented_scales(stored)[n][0], n
    from verify import solve

    times = [j / 10 for j in range(11)]  # 0.1 is not on the dyadic grid
    sol = solve("disk", "1", record["initial_state"], precision="double", t_eval=times)
    run = {"t": np.array(times), **{n: np.asarray(sol.y[i], float) for i, n in enumerate(STATE_NAMES)}}
    s = score(run, CASE)
    assert s.reference_source == "quad re-integration"
    assert 12 < s.min_digits < 16  # a double run at its epsilon (reference --check bounds it)


def test_negative_controls_are_refused_with_their_reason():
    record, cols, params = _stored()
    with pytest.raises(InvalidRun, match="start does not match"):
        score(cols, "disk-fig3-lhs")  # another case's start
    degrees = dict(cols, theta=np.degrees(cols["theta"]))
    with pytest.raises(InvalidRun, match="start does not match case disk-standard-1: theta"):
        score(degrees, CASE)
    b = _form_b("disk", cols, params)
    y_up = dict(b)  # the same motion in a frame with Y up: (x, y, z) -> (x, z, -y)
    for v in (("x", "y", "z"), ("vx", "vy", "vz"), ("wx", "wy", "wz")):
        y_up[v[1]], y_up[v[2]] = b[v[2]], -b[v[1]]
    for j in (1, 2, 3):
        y_up[f"R2{j}"], y_up[f"R3{j}"] = b[f"R3{j}"], -b[f"R2{j}"]
    with pytest.raises(InvalidRun):
        score(y_up, CASE)
    mirrored = dict(b, R13=-b["R13"], R23=-b["R23"], R33=-b["R33"])  # a left-handed body frame
    with pytest.raises(InvalidRun, match="not a rotation"):
        score(mirrored, CASE)
    floating = dict(b, z=b["z"] + 0.01)  # the body held 0.01 R above the plane
    with pytest.raises(InvalidRun, match="constraint is violated at t = 0: height"):
        score(floating, CASE)
    skidding = dict(b, vx=b["vx"] + 1.0)
    with pytest.raises(InvalidRun, match="velocity of the contact point"):
        score(skidding, CASE)
    with pytest.raises(InvalidRun, match="missing"):
        score({k: v for k, v in cols.items() if k != "psidot"}, CASE)
    with pytest.raises(InvalidRun, match="beyond"):
        score(dict(cols, t=cols["t"] * 2), CASE)
    # the controls' positive twin: the untouched form (b) run is accepted
    assert score(b, CASE).min_digits > 14


def test_cli_scores_a_file_and_refuses_a_bad_one_with_exit_2(tmp_path, capsys):
    from verify.cli import main

    _, cols, _ = _stored()
    good = tmp_path / "run.json"
    good.write_text(json.dumps({k: v.tolist() for k, v in _perturbed(cols, 1e-7).items()}))
    assert main(["score", str(good), "--case", CASE, "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["min_digits"] == pytest.approx(7, abs=1e-2) and out["verdict"].startswith("verdict:")
    bad = tmp_path / "run.csv"
    bad.write_text("t,theta,phi\n0,1.2,0\n1,1.2,0\n")
    assert main(["score", str(bad), "--case", CASE]) == 2
    assert "none of the documented forms" in capsys.readouterr().err


def test_export_writes_every_case_and_each_form_b_file_scores_as_the_reference(tmp_path):
    from verify.cli import main

    assert main(["reference", "--export", str(tmp_path), "--format", "csv"]) == 0
    names = [e["name"] for e in json.loads((DIRECTORY / "index.json").read_text())["cases"]]
    readme = (tmp_path / "README.md").read_text()
    for n in names:
        assert (tmp_path / f"{n}.euler.csv").exists() and f"### `{n}`" in readme
        record, _, _ = _stored(n)
        # form (b) is defined for the paper's bodies on the plane (verify/contact_geometry.py); not yet for body files
        if record["model"]["name"] in ("gyroscope", "effective") or record["model"]["name"].startswith("body:"):
            assert not (tmp_path / f"{n}.matrix.csv").exists()
            continue
        s = score(tmp_path / f"{n}.matrix.csv", n)
        if "friction" in record:  # the contact slides: its velocity is the slip, its C's velocity is exported
            assert s.min_digits > 15 and s.contact_height < 1e-15 and s.slip_speed_error < 1e-12, n
            assert s.energy_rel_error < 1e-14, n
            continue
        assert s.min_digits > 15 and s.contact_height < 1e-15 and s.contact_velocity < 1e-12, n
    assert main(["reference", "--export", str(tmp_path / "README.md"), "--format", "json"]) == 2


@pytest.mark.parametrize("target", ["reference-set", "other-files", "empty-name"])
def test_export_refuses_to_overwrite_what_it_does_not_own(tmp_path, target):
    """--export over a reference set (its case files share the export's names), over a folder of other
    files, or to an empty name: one line naming the folder and what is allowed, exit 2, nothing written."""
    import shutil
    import subprocess
    import sys
    from pathlib import Path

    if target == "reference-set":
        folder = tmp_path / "set"
        shutil.copytree(DIRECTORY, folder, ignore=shutil.ignore_patterns("proved"))
    elif target == "other-files":
        folder = tmp_path / "mine"
        folder.mkdir()
        (folder / "notes.txt").write_text("mine\n")
    else:
        folder = ""
    before = {p.name: p.read_bytes() for p in Path(folder or tmp_path).iterdir() if p.is_file()} if folder else {}
    out = subprocess.run([sys.executable, "-m", "verify", "reference", "--export", str(folder), "--format", "json"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 2, out.stderr
    assert "allowed" in out.stderr and "Traceback" not in out.stderr and len(out.stderr.strip().splitlines()) == 1
    if folder:
        assert {p.name: p.read_bytes() for p in Path(folder).iterdir() if p.is_file()} == before
    else:
        assert list(tmp_path.iterdir()) == []


# --- the scorer for CI -----------------------------------------------------------------------------

def test_the_start_is_checked_strictly_per_component_and_loosened_only_by_request():
    _, cols, _ = _stored()
    off = dict(cols, theta=cols["theta"] + np.where(cols["t"] == 0, 1e-9, 0.0))  # theta(0) off by 1e-9
    with pytest.raises(InvalidRun, match=r"theta\(0\).*own scale.*more than 1e-12"):
        score(off, CASE)
    loose = score(off, CASE, start_tolerance=1e-6)
    assert "loosened by request from 1e-12" in loose.verdict
    # thetadot's own scale is its own largest |value| (22 here), not the shared rate scale (over 300): a
    # start off by 1e-9 of the shared scale is 1.5e-8 of its own and refused at 1e-8
    rate = _documented_scales(cols)["thetadot"][0]
    own = float(np.max(np.abs(cols["thetadot"])))
    assert rate > 10 * own
    off = dict(cols, thetadot=cols["thetadot"] + np.where(cols["t"] == 0, 1e-9 * rate, 0.0))
    score(off, CASE, start_tolerance=1e-9 * rate / own * 1.01)
    with pytest.raises(InvalidRun, match="thetadot"):
        score(off, CASE, start_tolerance=1e-9 * rate / own * 0.99)


def test_scales_are_the_case_s_not_the_run_s_times():
    _, cols, _ = _stored()
    run = _perturbed(cols, 1e-8)
    early = {k: v[:11] for k, v in run.items()}  # the first quarter of the grid only
    whole, part = score(run, CASE), score(early, CASE)
    for n in STATE_NAMES:
        assert part.components[n].scale == whole.components[n].scale
    assert part.partial and not whole.partial and "PARTIAL" in part.verdict


def test_a_partial_or_weak_run_fails_min_digits_and_names_why():
    from verify.scoring import assert_scores

    _, cols, _ = _stored()
    run = _perturbed(cols, 1e-8)
    assert_scores(run, CASE, min_digits=7.9)
    with pytest.raises(AssertionError, match=r"8.00 digits, below the 9 required: the weakest is \w+ at t = "):
        assert_scores(run, CASE, min_digits=9)
    with pytest.raises(AssertionError, match="partial run: it stops at t = 0.3125 s"):
        assert_scores({k: v[:11] for k, v in run.items()}, CASE, min_digits=3)


def test_energy_of_a_form_b_run_is_its_own():
    """A run whose height (z) drifts while its orientation is right: converted to Euler angles it would
    look perfect; the energy from its own z shows the drift."""
    record, cols, params = _stored()
    b = _form_b(record["model"]["name"], cols, params, "matrix")
    assert score(b, CASE).energy_rel_drift < 1e-14
    sunk = dict(b, z=b["z"] - 1e-6 * cols["t"])  # sinking by 1e-6 R per second
    s = score(sunk, CASE)
    # g dz / E(0) at t = 1, all of it seen (the run's Euler-angle conversion shows none of it)
    energy = float(record["invariants"]["energy"]["value"][0])
    assert s.energy_rel_drift == pytest.approx(980e-6 / abs(energy), rel=0.01)
    assert s.contact_height > 9e-7


def test_cli_min_digits_exit_status(tmp_path, capsys):
    from verify.cli import main

    _, cols, _ = _stored()
    good = tmp_path / "run.json"
    good.write_text(json.dumps({k: v.tolist() for k, v in _perturbed(cols, 1e-7).items()}))
    assert main(["score", str(good), "--case", CASE, "--min-digits", "6"]) == 0
    assert "PASS: at least 6 digits" in capsys.readouterr().out
    assert main(["score", str(good), "--case", CASE, "--min-digits", "8"]) == 1
    out, err = capsys.readouterr()
    assert "FAIL: 7.00 digits, below the 8 required" in out and err.strip().startswith("error: score")

"""Body files wherever a model name goes (issue 32, item 1): names, friction runs kept and drawn, thresholds, spin-down.

Each equality below compares two routes: a body file's model, derived from its profile by the one derivation of
every body (models/rolling.py), against the paper's own model (its closed forms, models/disk.py, models/ring.py);
each has a negative control that would make it fail (another body, a tampered file, a wrong hash).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.bodies import DIRECTORY, body_from_mapping, load, model_name, model_of, shipped, to_toml
from verify.cli import main

EPS = 2.0 ** -52


def _cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out = capsys.readouterr()
    return code, out.out, out.err


def _body_file(tmp_path, shipped_name: str, new_name: str) -> Path:
    """A copy of a shipped body under another name, in a temp folder: not a shipped body, so body:NAME@HASH."""
    text = (DIRECTORY / f"{shipped_name}.toml").read_text().replace(f'name = "{shipped_name}"', f'name = "{new_name}"', 1)
    path = tmp_path / f"{new_name}.toml"
    path.write_text(text)
    return path


def _one_line_refusal(code, err):
    assert code == 2 and "Traceback" not in err and len(err.strip().splitlines()) == 1, err


# --- names ---------------------------------------------------------------------------------------------------------

def test_every_shipped_body_round_trips_through_its_text_and_keeps_its_name():
    for name in shipped():
        body = load(name)
        import tomllib

        assert body_from_mapping(tomllib.loads(to_toml(body))) == body
        assert model_name(body) == f"body:{name}"  # the shipped file itself: no hash (model_of names by this)
    assert model_of(load("disk")).name == "body:disk"


def test_a_body_file_anywhere_is_named_by_its_fingerprint_and_resolves_here_and_in_another_process(tmp_path, monkeypatch):
    cache = tmp_path / "cache"
    monkeypatch.setenv("HEYOKA_CACHE_DIR", str(cache))
    path = _body_file(tmp_path, "rounded-coin", "my-coin")
    body = load(path)
    name = model_of(body).name
    assert name.startswith("body:my-coin@") and len(name.split("@")[1]) == 12
    assert get_model(name).name == name and get_model(name).parameters == get_model("body:rounded-coin").parameters
    # the same file with other equations (I1 changed) gets another name: a name cannot reach a different body
    path.write_text(path.read_text().replace('I1 = "301/1200"', 'I1 = "3/10"'))
    other = model_of(load(path)).name
    assert other.startswith("body:my-coin@") and other != name
    # another process on this machine reads the registered text back from the cache
    env = {**os.environ, "HEYOKA_CACHE_DIR": str(cache), "PYTHONPATH": str(Path(__file__).resolve().parents[1])}
    probe = [sys.executable, "-c", f"from models import get_model; print(get_model({name!r}).name)"]
    done = subprocess.run(probe, env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and done.stdout.strip() == name, done.stderr
    # negative controls: a process without the cache refuses the name loudly; a tampered saved file is refused
    bare = subprocess.run(probe, env={**env, "HEYOKA_CACHE_DIR": str(tmp_path / "empty")}, capture_output=True, text=True,
                          timeout=300)
    assert bare.returncode != 0 and "no body file with this name and fingerprint" in bare.stderr
    saved = cache / "bodies" / "registered" / f"{name[len('body:'):]}.toml"
    saved.write_text(saved.read_text().replace('I1 = "301/1200"', 'I1 = "3/10"'))
    tampered = subprocess.run(probe, env=env, capture_output=True, text=True, timeout=300)
    assert tampered.returncode != 0 and "not the name's" in tampered.stderr
    with pytest.raises(ValueError, match="no body file"):
        get_model("body:my-coin@0123456789ab")


# --- thresholds and spin-down: the body's generic study against the paper's models ----------------------------------

def _threshold(capsys, *argv):
    code, out, err = _cli(capsys, "threshold", *argv, "--format", "json")
    assert code == 0, err
    return json.loads(out)


@pytest.mark.parametrize("model, motion", [("disk", "straight-line"), ("disk", "diameter-spin"),
                                           ("ring", "straight-line"), ("ring", "diameter-spin"),
                                           ("hurricane", "sleeping")])
def test_a_body_files_threshold_is_the_models_to_every_printed_digit(tmp_path, capsys, model, motion):
    """The model's value is its closed form (disk, hurricane) or its own Eq. 62 branch (ring); the body's is the
    generic study on the equations derived from the profile: 20 significant digits, every one equal."""
    expected = _threshold(capsys, model, motion)
    for given in (["--body", _body_file(tmp_path, model, f"my-{model}")], [f"body:{model}"]):
        got = _threshold(capsys, *given, motion)
        assert got["threshold"]["value"] == expected["threshold"]["value"] is not None
        assert got["threshold"]["value"].replace(".", "").isdigit() and len(got["threshold"]["value"]) == 21
        assert set(expected) <= set(got)  # the models' shape, and the body's theta0, stable, branch
    if model == "disk":  # negative control: the hoop's body is not the disk's, and it is the disk's with k = 1/2
        hoop = _threshold(capsys, "body:hoop", motion)
        assert hoop["threshold"]["value"] != expected["threshold"]["value"]
        assert hoop["threshold"]["value"] == _threshold(capsys, "disk", motion, "--param", "k=0.5")["threshold"]["value"]


def test_spindown_of_a_body_is_the_models_and_the_closed_form_only_where_the_paper_has_one(tmp_path, capsys):
    for model, family in (("disk", "cm-at-rest"), ("ring", "cm-at-rest"), ("ring", "zero-vertical-spin")):
        code, out, _ = _cli(capsys, "spindown", model, "--theta", "0.05", "--family", family, "--format", "json")
        expected = json.loads(out)
        code, out, err = _cli(capsys, "spindown", "--body", _body_file(tmp_path, model, f"my-{model}"), "--theta",
                              "0.05", "--family", family, "--format", "json")
        got = json.loads(out)
        assert code == 0, err
        for key in ("phidot", "psidot", "energy", "paper_formula", "paper_phidot"):
            assert got[key] == expected[key], key
    coin = _body_file(tmp_path, "rounded-coin", "my-coin")
    code, out, _ = _cli(capsys, "spindown", "--body", coin, "--theta", "0.05", "--format", "json")
    rec = json.loads(out)
    assert code == 0 and rec["paper_formula"] is None and rec["relative_error"] is None and float(rec["phidot"]) > 0
    # negative control: a disk body whose inertia is not the thin disk's (I3 != 2 I1) shows no Eq. 45
    code, out, _ = _cli(capsys, "spindown", "body:disk", "--theta", "0.05", "--param", "I3=0.4", "--format", "json")
    assert code == 0 and json.loads(out)["paper_formula"] is None


# --- friction runs of a body file, kept and drawn ---------------------------------------------------------------------

def _rolling_velocity(model, columns, params):
    """C's velocity by the rolling constraint (the model's velocity_xy, numpy): the independent route."""
    from models.symbols import STATE

    subs = {p.symbol: float(params[p.name]) for p in model.parameters}
    f = sp.lambdify(STATE, [e.subs(subs) for e in model.velocity_xy], "numpy")
    return np.array(f(*[np.asarray(columns[n], dtype=float) for n in
                        ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y")]))


def test_a_body_file_rolls_and_slides_under_both_laws_and_its_run_is_kept_drawn_and_redrawn(tmp_path, capsys):
    top = _body_file(tmp_path, "tippe-top", "my-top")
    run, picture = tmp_path / "top.json", tmp_path / "top.png"
    code, out, err = _cli(capsys, "trajectory", "--body", top, "--friction", "0.3", "--friction-law", "smooth",
                          "--slip-scale", "1", "--velocity", "0,0", "--t-end", "0.05", "--n-eval", "51",
                          "--output", run, "--plot", picture)
    assert code == 0, err
    assert "the start in the [start] table of body my-top" in out and str(top) not in out.split("start")[1]
    data = json.loads(run.read_text())
    units, columns, meta = data["units"], data["columns"], data["meta"]
    assert units["xdot"] == units["slip_e1"] == "L/s" and units["energy_plus_work"] == "M L^2/s^2"
    assert meta["model"].startswith("body:my-top@") and meta["body"]["name"] == "my-top"
    assert picture.read_bytes()[:4] == b"\x89PNG"
    # C's velocity: the smooth equations' own x', y' (heyoka, the run's precision) against the rolling constraint's
    # v_C plus the slip turned to the plane, v = v_roll + R(phi) u (numpy); each side is ~20 double operations on
    # terms no larger than the scale, so they agree to 2^10 eps of it
    model = get_model(meta["body"]["model"])
    v_roll = _rolling_velocity(model, columns, meta["params"])
    phi, u1, u2 = (np.asarray(columns[n], dtype=float) for n in ("phi", "slip_e1", "slip_h"))
    v = v_roll + np.array([u1 * np.cos(phi) - u2 * np.sin(phi), u1 * np.sin(phi) + u2 * np.cos(phi)])
    got = np.array([columns["xdot"], columns["ydot"]], dtype=float)
    scale = 1 + np.max(np.abs(v_roll)) + np.max(np.hypot(u1, u2))
    assert np.max(np.abs(got - v)) <= 2 ** 10 * EPS * scale
    assert np.max(np.abs(got[:, 0])) <= 2 ** 10 * EPS * scale  # --velocity 0,0: C starts at rest
    # a saved body run is redrawn to the same bytes, and an edited body text is refused, nothing written
    again = tmp_path / "again.png"
    code, out, err = _cli(capsys, "plot", run, "--out", again)
    assert code == 0 and again.read_bytes() == picture.read_bytes() and "the body my-top" in out
    meta["body"]["toml"] = meta["body"]["toml"].replace('I1 = "11/25"', 'I1 = "12/25"')
    run.write_text(json.dumps(data))
    code, _, err = _cli(capsys, "plot", run, "--out", tmp_path / "edited.png")
    _one_line_refusal(code, err)
    assert "does not match its fingerprint" in err and not (tmp_path / "edited.png").exists()


def test_a_body_file_under_exact_coulomb_friction_keeps_phases_switches_and_cs_velocity(tmp_path, capsys):
    coin = _body_file(tmp_path, "rounded-coin", "my-coin")
    run = tmp_path / "coin.csv"
    code, out, err = _cli(capsys, "trajectory", "--body", coin, "--friction", "0.5", "--t-end", "0.3", "--n-eval", "61",
                          "--output", run, "--format", "json")
    assert code == 0, err
    record = json.loads(out)
    assert [p["kind"] for p in record["phases"]] == ["rolling", "sliding", "rolling"] and len(record["switch_times"]) == 2
    from verify.series.files import read_run

    cols = read_run(run)
    assert [float(t) for t in cols.meta["switch_times"]] == record["switch_times"]  # every digit (repr) in the file
    assert cols.units["xdot"] == "L/s" and cols.meta["body"]["model"] == record["model"].removesuffix("+coulomb")
    model = get_model(cols.meta["body"]["model"])
    values = {n: cols.values[n] for n in cols.names}
    v_roll = _rolling_velocity(model, values, cols.meta["params"])
    s = np.asarray(values["slip_speed"], dtype=float)
    a = np.nan_to_num(np.asarray(values["slip_direction"], dtype=float))
    v = v_roll + np.array([s * np.cos(a), s * np.sin(a)])  # v_C = v_roll + u, u = s (cos alpha, sin alpha)
    got = np.array([values["xdot"], values["ydot"]], dtype=float)
    scale = 1 + np.max(np.abs(v_roll)) + np.max(s)  # as above: 2^10 eps of the terms' scale
    assert np.max(np.abs(got - v)) <= 2 ** 10 * EPS * scale
    assert np.max(s) > 1  # the check covers a sliding phase, not only the rolling constraint


# --- bad input: one line, exit 2, nothing written --------------------------------------------------------------------

@pytest.mark.parametrize("argv, words", [
    (["threshold", "--body", "{tmp}/missing.toml", "sleeping"], "No such file"),
    (["threshold", "body:rounded-coin", "precession"], "allowed: diameter-spin, straight-line"),
    (["threshold", "body:routh-sphere", "sleeping"], "give --theta0"),
    (["threshold", "body:routh-sphere", "sleeping", "--theta0", "1"], "no sleeping"),
    (["threshold", "body:disk", "straight-line", "--nonlinear-tilt", "1e-6"], "steady_confirm"),
    (["threshold", "disk", "straight-line", "--theta0", "0"], "give a body"),
    (["threshold", "body:disk@0123456789ab", "straight-line"], "no body file"),
    (["spindown", "body:disk", "--theta", "4"], "outside the domain"),
    (["spindown", "body:hurricane", "--theta", "0.3"], "no steady cm-at-rest motion"),
    (["reference", "--check", "--body", "disk"], "no case of body:disk"),
    (["trajectory", "body:disk", "--body", "disk"], "give the body once"),
    (["trajectory", "--body", "{tmp}/missing.toml", "--friction", "0.3", "--output", "{tmp}/run.csv"], "No such file"),
    (["trajectory", "--body", "disk", "--friction", "-1", "--output", "{tmp}/run.csv", "--plot", "{tmp}/run.png"],
     "--friction"),
])
def test_bad_body_input_is_one_line_exit_2_and_writes_nothing(tmp_path, capsys, argv, words):
    code, out, err = _cli(capsys, *[a.replace("{tmp}", str(tmp_path)) for a in argv])
    _one_line_refusal(code, err)
    assert words in err and not list(tmp_path.glob("run.*"))

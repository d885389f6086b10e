"""The command line: the JSON contract, the model listing, and bad input (exit status 2)."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import heyoka as hy
import pytest

from verify.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_trajectory_json_in_double(capsys):
    code, out, _ = run(capsys, "trajectory", "disk", "--state", "theta=1.2", "--state", "psidot=10",
                       "--t-end", "1", "--format", "json")
    assert code == 0
    rec = json.loads(out)
    assert list(rec) == ["model", "equations", "precision", "params", "t_end", "outcome", "t", "steps", "state",
                         "invariants", "friction_required", "friction", "start", "files"]
    assert rec["friction"] is None  # unlimited friction unless --friction is given
    assert rec["model"] == "disk" and rec["equations"] == "derived" and rec["precision"] == "double"
    assert rec["params"] == {"k": 0.25, "g": 980.0}
    assert rec["outcome"] == "ok" and rec["t"] == 1.0 and rec["steps"] > 0
    assert list(rec["state"]) == ["theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y"]
    assert all(isinstance(v, float) for v in rec["state"].values())
    assert set(rec["invariants"]) == {"energy", "chaplygin_1", "chaplygin_2"}
    assert list(rec["invariants"]["energy"]) == ["initial", "final", "max_abs_drift", "max_rel_drift", "term_scale",
                                                 "max_drift_vs_terms", "max_drift_vs_terms_in_eps"]
    e = rec["invariants"]["energy"]
    assert e["max_rel_drift"] == e["max_abs_drift"] / abs(e["initial"])
    assert e["max_drift_vs_terms"] == e["max_abs_drift"] / e["term_scale"]


def test_trajectory_json_in_quad_carries_every_digit(capsys):
    code, out, _ = run(capsys, "trajectory", "ring", "--equations", "paper", "--state", "theta=1.0",
                       "--state", "psidot=20", "--state", "phidot=-3", "--t-end", "0.5", "--precision", "quad",
                       "--format", "json")
    assert code == 0
    rec = json.loads(out)
    assert rec["equations"] == "paper" and rec["precision"] == "quad"
    assert all(isinstance(v, str) for v in rec["state"].values())
    assert hy.real128(rec["state"]["theta"]) == hy.real128(rec["state"]["theta"])  # parses
    assert len(rec["state"]["psidot"].replace("-", "").replace(".", "").lstrip("0")) >= 33
    assert set(rec["params"]) == {"I1", "I3", "h", "g"}


def test_event_outcome_on_the_command_line(capsys):
    code, out, _ = run(capsys, "trajectory", "disk", "--state", "theta=1.0", "--t-end", "2", "--format", "json")
    assert code == 0 and json.loads(out)["outcome"] == "event:lies_flat"


def test_models_lists_every_model(capsys):
    code, out, _ = run(capsys, "models", "--format", "json")
    rec = {m["model"]: m for m in json.loads(out)["models"]}
    assert code == 0
    assert set(rec) == {"disk", "ring", "hurricane", "sliding-disk", "gyroscope", "effective",
                        "disk+moffatt", "disk+contact-rate", "ring+air-drag", "ring+rolling-friction"}
    assert rec["hurricane"]["invariants"] == ["energy", "jellett", "routh"]
    assert rec["disk"]["parameters"]["k"]["default"] == "1/4"


BAD = [
    (["trajectory", "disc", "--t-end", "1"], "unknown model 'disc'"),
    (["trajectory", "disk", "--param", "kk=1", "--t-end", "1"], "unknown parameter 'kk'"),
    (["trajectory", "disk", "--state", "omega=1", "--t-end", "1"], "unknown state variable 'omega'"),
    (["trajectory", "disk", "--state", "theta=abc", "--t-end", "1"], "--state theta='abc': unknown name 'abc'"),
    (["trajectory", "disk", "--state", "theta=nan", "--t-end", "1"], "'nan' is not a finite number"),
    (["trajectory", "disk", "--param", "g=inf", "--t-end", "1"], "'inf' is not a finite number"),
    (["trajectory", "disk", "--param", "k=0", "--state", "theta=1", "--t-end", "1"], "k=0 is out of its physical range (0, 0.5]"),
    (["trajectory", "disk", "--param", "k=0.7", "--state", "theta=1", "--t-end", "1"], "k=0.7 is out of its physical range"),
    (["trajectory", "ring", "--param", "h=-0.1", "--state", "theta=1", "--t-end", "1"], "h=-0.1 is out of its physical range [0, +inf)"),
    (["trajectory", "ring", "--param", "I3=2", "--state", "theta=1", "--t-end", "1"], "violate I3 <= 2 I1"),
    (["trajectory", "disk", "--state", "theta=0", "--t-end", "1"], "theta=0 is outside the domain"),
    (["trajectory", "ring", "--state", "theta=1.6", "--t-end", "1"], "theta=1.6 is outside the domain"),
    (["trajectory", "disk", "--state", "theta=1.5", "--state", "thetadot=40", "--t-end", "1"], "normal force"),
    (["trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--tol", "0"], "--tol 0: allowed a positive finite number"),
    (["trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--tol=-1e-9"], "--tol -1e-9: allowed a positive finite number"),
    (["trajectory", "disk", "--state", "theta=1", "--t-end", "-1"], "--t-end -1: allowed a positive finite number"),
    (["trajectory", "disk", "--state", "theta=1", "--t-end", "1", "--precision", "octuple"], "unknown precision 'octuple'"),
    (["trajectory", "sliding-disk", "--equations", "paper", "--state", "theta=1", "--t-end", "1"], "allowed: derived"),
    (["trajectory", "effective", "--state", "theta=1", "--state", "phidot=3", "--t-end", "1"], "psidot - phidot"),
    (["trajectory", "disk", "--param", "k", "--t-end", "1"], "is not NAME=VALUE"),
]


@pytest.mark.parametrize("argv,message", BAD, ids=[m for _, m in BAD])
def test_bad_input_exits_2_with_a_clear_message(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert out == ""
    assert message in err, err


@pytest.mark.parametrize("command", [["report"], ["bench", "--quick"]])
def test_an_unwritable_output_folder_is_refused_before_anything_runs(tmp_path, capsys, command):
    """The folder is checked first: a report or a benchmark does not run for minutes and then fail."""
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    code, out, err = run(capsys, *command, "--out", str(blocker / "reports"))
    assert code == 2 and out == ""
    assert "--out: cannot write to the folder" in err and str(blocker / "reports") in err
    assert blocker.read_text() == "x"


def test_exit_status_from_a_real_process():
    env = dict(os.environ, PYTHONPATH=ROOT)
    bad = subprocess.run([sys.executable, "-m", "verify", "trajectory", "disk", "--t-end", "1", "--param", "k=-1"],
                         capture_output=True, text=True, env=env, cwd=ROOT)
    assert bad.returncode == 2 and "k=-1 is out of its physical range" in bad.stderr and bad.stdout == ""
    missing = subprocess.run([sys.executable, "-m", "verify", "trajectory", "--state", "theta=1"],
                             capture_output=True, text=True, env=env, cwd=ROOT)
    assert missing.returncode == 2 and "give a model" in missing.stderr


def test_trajectory_with_friction_stops_where_it_slips(capsys):
    code, out, _ = run(capsys, "trajectory", "disk", "--state", "theta=1.3", "--state", "thetadot=0.5", "--state",
                       "phidot=3", "--state", "psidot=20", "--t-end", "2", "--friction", "0.3", "--format", "json")
    assert code == 0
    rec = json.loads(out)
    assert rec["outcome"] == "event:slips" and rec["friction"] == 0.3
    assert abs(rec["friction_required"]["max"] - 0.3) < 1e-14 and rec["friction_required"]["t_max"] == rec["t"]


@pytest.mark.parametrize("argv, words", [
    (["disk", "--state", "theta=1.3", "--friction", "-1"], "--friction -1: allowed a positive finite number"),
    (["sliding-disk", "--state", "theta=1.3", "--friction", "0.2"], "has no rolling contact"),
    (["disk", "--state", "theta=1.3", "--state", "thetadot=0.5", "--state", "phidot=3", "--state", "psidot=20",
      "--friction", "0.2"], "needs the friction coefficient mu_req"),
])
def test_trajectory_friction_bad_input_is_one_line_and_exit_2(capsys, argv, words):
    code, out, err = run(capsys, "trajectory", *argv, "--t-end", "1")
    assert code == 2 and out == "" and words in err and err.count("\n") == 1 and "Traceback" not in err

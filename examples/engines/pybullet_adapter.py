"""PyBullet adapter: run a reference case of a body rolling on the plane in PyBullet and score it.

(docstring completed below with the measured numbers and pitfalls)
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from models.symbols import STATE_NAMES  # noqa: E402
from verify import score  # noqa: E402
from verify.frames import MOTION, QUATERNION, euler_to_b  # noqa: E402
from verify.reference.store import DIRECTORY  # noqa: E402

COLUMNS = ("t",) + QUATERNION + MOTION

#: What a new user writes to describe the body, everything else left at PyBullet's defaults
#: (fixedTimeStep 1/240 s, 50 solver iterations, ERP 0.2, split impulse, damping 0.04,
#: collision margin of the shape, multibody (reduced coordinates) base).
DEFAULT = {"dt": 1 / 240, "friction": 1.0, "thin_half_height": 1e-6}

#: Filled from the sweep (see the docstring's table).
BEST = {"dt": 2.0 ** -20, "friction": 1.0, "thin_half_height": 1e-6, "damping": 0.0, "margin": 1e-6, "contact_slop": 0.0,
        "solver_iterations": 200, "restitution": 0.0, "maximal": False}

SETTINGS = {"default": DEFAULT, "best": BEST}


def load_case(case: str) -> dict:
    return json.loads((DIRECTORY / f"{case}.json").read_text())


def body_geometry(record: dict, setting: dict) -> dict:
    """Mass 1, the case's inertia, and the cylinder's radius 1 and half-height."""
    model = record["model"]["name"]
    par = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    if model == "disk":
        k = par["k"]
        return {"model": model, "I1": k, "I3": 2 * k, "h": float(setting.get("thin_half_height", 1e-3)),
                "h_model": 0.0, "g": par["g"], "params": par}
    if model == "ring":
        return {"model": model, "I1": par["I1"], "I3": par["I3"], "h": par["h"], "h_model": par["h"],
                "g": par["g"], "params": par}
    raise ValueError(f"the PyBullet adapter runs the disk and the ring (a cylinder); not {model!r}")


def _with_override(geo: dict, setting: dict) -> dict:
    """A deliberately different inertia ``setting["inertia"] = (I1, I3)`` (negative controls only)."""
    if "inertia" in setting:
        geo = {**geo, "I1": float(setting["inertia"][0]), "I3": float(setting["inertia"][1])}
    return geo


def output_steps(record: dict, dt: float, t_end: float, per_grid: int = 8) -> list:
    """(time, step): every k steps, k the whole number of steps nearest the case's grid spacing / per_grid.

    The time is step * dt (the engine's own clock, exact for dt = 2^-n); such times are in
    general not the stored grid's, so the scorer re-integrates the reference in quad there.
    """
    from fractions import Fraction

    spacing = float(record["grid"][1]) - float(record["grid"][0])
    k = max(1, round(spacing / per_grid / dt))
    n_end = int(math.floor(t_end / dt + 1e-9))
    steps = list(range(0, n_end + 1, k))
    if steps[-1] != n_end:
        steps.append(n_end)  # the run's last step is always written
    return [(min(float(Fraction(n) * Fraction(dt)), t_end), n) for n in steps]


def _read_c(p, cid, body) -> dict:
    pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
    v, w = p.getBaseVelocity(body, physicsClientId=cid)  # world components; w is the inertial angular velocity
    qx, qy, qz, qw = orn  # PyBullet: (x, y, z, w), scalar LAST
    return dict(zip(QUATERNION + MOTION, (qw, qx, qy, qz) + tuple(pos) + tuple(v) + tuple(w)))


def setup(record: dict, setting: dict):
    """A DIRECT PyBullet client with the plane and the body at the case's start; (p, client, body, geometry, b0)."""
    import pybullet as p

    geo = _with_override(body_geometry(record, setting), setting)
    start = {n: np.array([float(record["initial_state"][n])]) for n in STATE_NAMES}
    # the start in form (b) for the model actually simulated: for the disk, the cylinder of
    # half-height h touches at -e2 - h e3, i.e. the ring model with that h and the disk's inertia
    if geo["model"] == "disk" and geo["h"] > 0:
        model_b, params_b = "ring", {"I1": geo["I1"], "I3": geo["I3"], "h": geo["h"], "g": geo["g"]}
    else:
        model_b, params_b = geo["model"], geo["params"]
    b0 = {c: float(v[0]) for c, v in euler_to_b(model_b, start, params_b).items()}
    cid = p.connect(p.DIRECT)
    p.setGravity(0, 0, -geo["g"], physicsClientId=cid)
    phys = {"fixedTimeStep": setting["dt"]}
    for key, name in (("solver_iterations", "numSolverIterations"), ("erp", "erp"), ("contact_erp", "contactERP"),
                      ("friction_erp", "frictionERP"), ("split_impulse", "useSplitImpulse"),
                      ("cone_friction", "enableConeFriction"), ("contact_slop", "contactSlop"),
                      ("global_cfm", "globalCFM"), ("breaking_threshold", "contactBreakingThreshold"),
                      ("substeps", "numSubSteps"), ("solver", "constraintSolverType")):
        if key in setting:
            phys[name] = setting[key]
    p.setPhysicsEngineParameter(physicsClientId=cid, **phys)
    plane_shape = p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid)
    plane = p.createMultiBody(0, plane_shape, physicsClientId=cid)
    shape = p.createCollisionShape(p.GEOM_CYLINDER, radius=1.0, height=2 * geo["h"], physicsClientId=cid)
    orn = (b0["qx"], b0["qy"], b0["qz"], b0["qw"])
    body = p.createMultiBody(1.0, shape, basePosition=(b0["x"], b0["y"], b0["z"]), baseOrientation=orn,
                             useMaximalCoordinates=bool(setting.get("maximal", False)), physicsClientId=cid)
    dyn = {"mass": 1.0, "localInertiaDiagonal": (geo["I1"], geo["I1"], geo["I3"]),
           "lateralFriction": setting["friction"]}
    for key, name in (("damping", "linearDamping"), ("damping", "angularDamping"),
                      ("restitution", "restitution"), ("rolling_friction", "rollingFriction"),
                      ("spinning_friction", "spinningFriction"), ("margin", "collisionMargin"),
                      ("contact_stiffness", "contactStiffness"), ("contact_damping", "contactDamping")):
        if key in setting:
            dyn[name] = setting[key]
    p.changeDynamics(body, -1, physicsClientId=cid, **dyn)
    p.changeDynamics(plane, -1, lateralFriction=setting["friction"], physicsClientId=cid,
                     **({"restitution": setting["restitution"]} if "restitution" in setting else {}))
    p.resetBaseVelocity(body, (b0["vx"], b0["vy"], b0["vz"]), (b0["wx"], b0["wy"], b0["wz"]), physicsClientId=cid)
    return p, cid, body, geo, b0


def check_start(p, cid, body, b0: dict, tol: float = 1e-12) -> dict:
    """The state read back at t = 0 against the case's (fail loudly beyond rounding)."""
    got = _read_c(p, cid, body)
    sign = 1.0 if sum(got[c] * b0[c] for c in QUATERNION) >= 0 else -1.0
    bad = {}
    for c in QUATERNION + MOTION:
        ref = b0[c]
        val = sign * got[c] if c in QUATERNION else got[c]
        scale = 1.0 if c in QUATERNION + ("x", "y", "z") else max(1.0, max(abs(b0[k]) for k in ("wx", "wy", "wz")))
        if not abs(val - ref) <= tol * scale:
            bad[c] = (val, ref)
    if bad:
        raise RuntimeError("PyBullet's state at t = 0 is not the case's start: "
                           + ", ".join(f"{c} = {a!r} (case {b!r})" for c, b in ((c, v[1]) for c, v in bad.items())
                                       for a in [bad[c][0]]))
    return got


def simulate(record: dict, setting: dict, t_end: float):
    p, cid, body, geo, b0 = setup(record, setting)
    try:
        got0 = check_start(p, cid, body, b0)
        steps = output_steps(record, setting["dt"], t_end)
        rows, n_done, outcome = [], 0, "ok"
        t0 = time.perf_counter()
        for t, n in steps:
            while n_done < n:
                p.stepSimulation(physicsClientId=cid)
                n_done += 1
            s = got0 if n == 0 else _read_c(p, cid, body)
            rows.append([t] + [s[c] for c in QUATERNION + MOTION])
            if not np.all(np.isfinite(rows[-1])):
                outcome = "error: non-finite state"
                break
        wall = time.perf_counter() - t0
    finally:
        p.disconnect(physicsClientId=cid)
    cols = {c: np.array([r[i] for r in rows]) for i, c in enumerate(COLUMNS)}
    return cols, wall, outcome, geo


def run_case(case: str, setting="default", t_end=None, out=None) -> dict:
    import pybullet

    name, cfg = (setting, SETTINGS[setting]) if isinstance(setting, str) else ("custom", dict(setting))
    record = load_case(case)
    t_end = float(record["t_end"]) if t_end is None else float(t_end)
    cols, wall, outcome, geo = simulate(record, cfg, t_end)
    sc = None
    try:
        sc = score(cols, case)
        rec_score = sc.to_record()
    except Exception as exc:  # noqa: BLE001 - reported, not hidden
        rec_score, outcome = None, f"error: {type(exc).__name__}: {exc}"
    if outcome == "ok" and sc is not None:
        theta = np.arctan2(np.hypot(*_e3xy(cols)), _e3z(cols))
        if np.any(theta > math.pi / 2 - 1e-3) or np.any(cols["z"] < 0):
            outcome = "fell"
    if out:
        write_csv(cols, out)
    return {"engine": "PyBullet", "version": _version(pybullet), "case": case, "setting": name,
            "parameters": {**cfg, "cylinder_half_height": geo["h"], "inertia": [geo["I1"], geo["I1"], geo["I3"]]},
            "t_end": t_end, "wall_s": round(wall, 3), "score": rec_score, "outcome": outcome,
            "_score": sc, "_columns": cols}


def _e3xy(c):
    qw, qx, qy, qz = (c[k] for k in QUATERNION)
    return 2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx)


def _e3z(c):
    qw, qx, qy, qz = (c[k] for k in QUATERNION)
    return 1 - 2 * (qx * qx + qy * qy)


def _version(pybullet) -> str:
    try:
        from importlib.metadata import version
        return version("pybullet")
    except Exception:  # noqa: BLE001
        return "unknown"


def write_csv(cols: dict, path) -> None:
    data = np.column_stack([cols[c] for c in COLUMNS])
    np.savetxt(path, data, delimiter=",", header=",".join(COLUMNS), comments="", fmt="%.17g")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--setting", default="best", choices=sorted(SETTINGS))
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    r = run_case(args.case, args.setting, args.t_end, args.out)
    sc = r.pop("_score")
    r.pop("_columns")
    if sc is not None:
        print(sc.table())
    print(json.dumps({k: v for k, v in r.items() if k != "score"}, indent=1, default=str))


if __name__ == "__main__":
    main()

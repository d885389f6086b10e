"""PyBullet adapter: a reference case of a body rolling on the plane, run in PyBullet and scored.

``run_case(case, setting="default" | "best" | dict, t_end=None) -> dict`` (JSON-ready but for the
keys ``_score``, the Score, and ``_columns``, the run); ``python examples/engines/pybullet_adapter.py
--case disk-standard-1 --setting best [--t-end 1] [--out run.csv]`` prints the score table.
Measured with pip ``pybullet`` 3.2.7 (prebuilt x86_64 wheel, double precision), Python 3.11.

Model: a cylinder (GEOM_CYLINDER, radius 1, half-height h) of mass 1 with the case's inertia set
by ``changeDynamics(localInertiaDiagonal=(I1, I1, I3))``, on a GEOM_PLANE at z = 0, gravity
(0, 0, -980), lateral friction 1 on both (Bullet multiplies the two: mu = 1; 10 and 100 change
nothing: it does not slip).  A cylinder touches on its rim edge, r_P = -e2 - h e3: exactly the
ring model with h of the case.  The thin disk (r_P = -e2) is a cylinder of h = 1e-6: the model
difference, h cos(theta) <= 1e-6 in C's height, is below the scorer's start tolerance (1e-6) and
far below the engine's error; a "thin" cylinder of h = 0.01 is refused by the scorer at t = 0
(contact height 3.6e-3 for the disk model).  Start: ``verify.frames.euler_to_b`` (for the thin
disk with the ring model at that h), read back from PyBullet and checked to 1e-12 before running.
Output: the quaternion form every k steps (k steps nearest 1/8 of the case's grid spacing) and
the last step; those are not grid times, so the scorer re-integrates the reference in quad there
(about 1 s for 250 times).  The scorer accepts a run that stops before t_end and scores it on
[0, t_last] (it refuses only times beyond t_end or not starting at 0): the 10 s cases are run to 1 s.

Measured (``python examples/engines/pybullet_adapter.py --table``: run_case for each case and setting, t_end 1 s;
digits = Score.min_digits, final = the fewest final digits, E = energy drift, zP, vP = max contact
height and velocity; wall = the stepping alone, 2 shared cores):

  case              setting  outcome  digits  final   E        zP       vP       wall
  disk-standard-1   default  fell     -0.16   0.36    9.9e-01  4.0e-01  3.1e+01  0.02 s
  disk-standard-1   best     ok        1.70   2.65    3.1e-04  6.8e-07  7.6e-03  5.9-7.5 s
  hoop-general-10   default  fell     -0.02   0.01    8.2e-01  2.0e-01  1.4e+01  0.01 s
  hoop-general-10   best     ok        2.68   2.77    1.3e-04  6.5e-07  2.3e-03  6.6 s
  ring-standard-10  default  ok       -0.11   0.00    3.5e-01  5.1e-02  1.5e+00  0.01 s
  ring-standard-10  best     ok        3.40   3.40    2.9e-06  4.2e-07  6.1e-05  5.6 s

Sweep (``--sweep``: disk-standard-1 to 1 s, best setting but dt; the error is first order in dt: +0.3
digits per halving, and no other knob matters):

  dt      2^-10  2^-12  2^-14  2^-16  2^-18  2^-20   (1/240 default: fell)
  digits  -0.25   0.00   0.01   0.49   1.10   1.70
  E       5.0e-1 1.3e-1 2.1e-2 4.9e-3 1.2e-3 3.1e-4
  wall s  0.02   0.04   0.08   0.29   1.24   5.85

At dt = 8.1e-6 on the same case these changed nothing (0.93 digits each): numSolverIterations
10/50/200, useSplitImpulse 0, ERP/contactERP/frictionERP 0.9, enableConeFriction 0,
constraintSolverType 1, lateral friction 10 or 100; ERP 0 lost 0.8 digits (the contact sinks
5e-3).  useMaximalCoordinates (btRigidBody instead of a one-link btMultiBody) lost 0.15 digits.
collisionMargin 1e-6 with contactSlop 0 took the ring from 2.83 to 3.10 digits at 2^-19 and the
contact height from 5e-5 to 4e-7.  "best" = dt 2^-20 (a wall budget of about 6 s per simulated
second; smaller steps keep gaining 0.3 digits per halving at twice the cost), 200 solver
iterations, damping 0, margin 1e-6, contactSlop 0, restitution 0.

Pitfalls (each silently wrong at defaults):

* Units: PyBullet has none, but its defaults are tuned for metres and 1/240 s.  Here R = 1 and
  g = 980, so one natural time sqrt(R/g) = 0.032 s is only 7.6 default steps: the disk and the
  hoop fall flat and the thin cylinder then sinks through the plane (C at z = -0.30 by t = 0.8);
  the ring loses 35 % of its energy in 1 s.
* Default damping: linearDamping = angularDamping = 0.04 on every body (changeDynamics to 0):
  at the best step it alone turns 3.4 digits on the ring into -0.05 (energy -27 % in 1 s).
* Inertia: createMultiBody computes it from the collision shape; set localInertiaDiagonal after.
* Quaternions are (x, y, z, w), scalar last; the scorer's is (w, x, y, z).  getBaseVelocity's
  angular velocity is in world (inertial) components, as the scorer wants; the base position is
  the centre of mass (no inertial-frame offset given).
* Contact geometry: the cylinder touches on the rim EDGE half a thickness off the mid-plane (the
  coin); a thin disk needs h near 0 to be the disk model.  Bullet's collision margin (0.04 by
  default, clamped to 0.1 of the smallest half-extent) rounds the rim: set collisionMargin.
* Contact softness: with the default contactSlop and margin the contact sits 5e-5 into the
  plane; ERP 0 lets it sink.  The no-slip condition is a velocity-level impulse at the contact
  point of the step's start while the contact point moves round the rim: the error is first
  order in dt whatever the solver settings (contact velocity 7.6e-3 at 2^-20).
* The run is deterministic (same build), so the test's threshold allows for another build.

Coulomb cases (coin-coulomb-slip-1: mu = 0.87, rolls, slides from 0.0780 to 0.0966, rolls; coin-coulomb-skid-1:
mu = 0.3, starts sliding, sticks at 0.0765; ``friction_cases``)

* Friction coefficient: Bullet MULTIPLIES the two objects' friction, mu = mu_body mu_plane clamped to [-10, 10]
  (``btManifoldResult::calculateCombinedFriction``, bullet3 src/BulletCollision/CollisionDispatch/
  btManifoldResult.cpp, the default callback PyBullet uses).  Every object starts at lateralFriction 0.5
  (``getDynamicsInfo``): a user who gives only the coin mu gets mu/2.  Here the coin gets mu and the plane 1
  (the record's ``parameters.lateral_friction``); spinning and rolling friction 0 (their defaults, set anyway).
* Cone: PyBullet's world is a btMultiBodyDynamicsWorld, whose constructor turns on two friction directions
  (SOLVER_USE_2_FRICTION_DIRECTIONS, btMultiBodyDynamicsWorld.cpp) with implicit cone friction left on
  (``enableConeFriction``, SOLVER_DISABLE_IMPLICIT_CONE_FRICTION off): each solver iteration clips the two
  friction impulses together to the disc mu * normal impulse
  (``btMultiBodyConstraintSolver::resolveConeFrictionConstraintRows``).  No regularisation: friction is a
  velocity-level impulse per step, a rolling contact creeps only by the step's error.
* The clipped impulse keeps the DIRECTION of the impulse that would stop the slip in one step, which is not
  opposite to the slip (the contact's effective mass is not isotropic): measured from getContactPoints'
  friction forces against the slip velocity during the skid (dt 2^-16), up to 9 degrees off (171 to 180).
  It dissipates less than Coulomb's law, and the skid sticks at 0.0800, 3.5 ms after the reference's
  0.0765, at every step from 2^-16 to 2^-20: a model difference, not a convergence error.  On slip-1 the
  slide's times are right (0.0793 to 0.0965 at the 0.1 R/s threshold, the reference's own 0.0793 to
  0.0964); both runs end near 1 digit.
* Settings: "default" is DEFAULT with the friction above (1/240 s: the coin falls on both cases); "best" is
  BEST at dt = 2^-18 (COULOMB_SETTINGS): the digits stop changing from 2^-18 on, at a quarter of 2^-20's cost.

Coulomb sweep (``run_case(case, {**BEST, "dt": ...})``, min digits over the whole second by ``verify.score``,
slip-1 / skid-1, and where the skid sticks; wall = stepping)::

    dt       slip-1   skid-1   sticks at   wall s
    1/240    falls    falls    never       0.01
    2^-16    0.69     0.71     0.0800      0.7
    2^-18    1.13     0.70     0.0800      3.3   <- best
    2^-20    1.09     0.70     0.0800      5.9

Measured on the Coulomb cases (``python -m verify engines --case coin-coulomb-slip-1 --case coin-coulomb-skid-1``,
each run in a process of its own on 2 shared cores, scored by ``verify.score`` against the reference files; energy
= max |E - E_ref| / E_ref(0), slip = max | |u| - s_ref | in R/s, z_P = max |contact height|, slides where the
contact's slip speed exceeds 0.1 R/s; the reference slides from 0.0780 to 0.0966 on slip-1, its own slip speed
crossing 0.1 R/s at 0.0793 and 0.0964, and the skid sticks at 0.0765, crossing at 0.0761)::

    case    setting  outcome   min digits (where)        energy   slip    z_P      slides                         wall s
    slip-1  default  fell     -0.02 (y, t = 1)          1.1      26      0.37     0.0288-0.8018 and 2 more       0.01
    slip-1  best     ok        1.13 (y, t = 0.892)      7.6e-4   0.11    1.5e-6   0.0793-0.0965                  1.6
    skid-1  default  fell     -0.26 (phidot, t = 0.996) 0.89     32      0.36     0- (never sticks)              0.003
    skid-1  best     ok        0.70 (phidot, t = 0.971) 7.2e-3   1.6     4.4e-7   0-0.0800                       1.1

(fell: theta below 0.1 rad or C below the plane; the rolling creep where the reference rolls is 3.1e-3 R/s on
slip-1 and 5.4e-4 on the skid at "best"; wall = the stepping alone.)
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from fractions import Fraction
from importlib import metadata
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))  # friction_cases, beside this file

from verify import score  # noqa: E402
from verify.frames import MOTION, QUATERNION  # noqa: E402
from verify.scoring import START_TOLERANCE  # noqa: E402
import friction_cases  # noqa: E402

COLUMNS = ("t",) + QUATERNION + MOTION

#: What a new user writes to describe the body, everything else left at PyBullet's defaults
#: (fixedTimeStep 1/240 s, 50 solver iterations, ERP 0.2, split impulse, damping 0.04,
#: collision margin of the shape, multibody (reduced coordinates) base).
DEFAULT = {"dt": 1 / 240, "friction": 1.0, "thin_half_height": 1e-6}

#: Filled from the sweep (see the docstring's table).
BEST = {"dt": 2.0 ** -20, "friction": 1.0, "thin_half_height": 1e-6, "damping": 0.0, "margin": 1e-6, "contact_slop": 0.0,
        "solver_iterations": 200, "restitution": 0.0, "maximal": False}

SETTINGS = {"default": DEFAULT, "best": BEST}
#: A Coulomb case (coin-coulomb-*): the same defaults; its best is BEST at dt = 2^-18 (the Coulomb sweep in the
#: docstring: the digits stop changing there, at a quarter of 2^-20's cost).
COULOMB_SETTINGS = {"default": DEFAULT, "best": {**BEST, "dt": 2.0 ** -18}}
#: a run whose tilt theta drops below this (rad) has fallen flat (the references stay above 0.236)
FLAT = 0.1


def load_case(case: str) -> dict:
    """The case's record (:func:`friction_cases.load_case`: with ``friction`` and ``velocity``)."""
    return friction_cases.load_case(case)


def lateral_friction(record: dict, setting: dict) -> tuple:
    """(the body's, the plane's) lateralFriction.  Bullet multiplies the two
    (``btManifoldResult::calculateCombinedFriction``: mu = mu_body mu_plane, clamped to [-10, 10]), so a
    Coulomb case gets mu on the body and 1 on the plane; a rolling case the setting's value on both."""
    mu = friction_cases.friction_of(record)
    return (setting["friction"], setting["friction"]) if mu is None else (mu, 1.0)


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
    import pybullet as p  # lazy: optional package (pybullet)

    geo = _with_override(body_geometry(record, setting), setting)
    # the start in form (b) for the model actually simulated: for the disk, the cylinder of
    # half-height h touches at -e2 - h e3, i.e. the ring model with that h and the disk's inertia
    if geo["model"] == "disk" and geo["h"] > 0:
        model_b, params_b = "ring", {"I1": geo["I1"], "I3": geo["I3"], "h": geo["h"], "g": geo["g"]}
    else:
        model_b, params_b = geo["model"], geo["params"]
    b0 = friction_cases.start_b(record, model_b, params_b)  # a skid's CM velocity where the case gives one
    mu_body, mu_plane = lateral_friction(record, setting)
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
           "lateralFriction": mu_body}
    for key, name in (("damping", "linearDamping"), ("damping", "angularDamping"),
                      ("restitution", "restitution"), ("rolling_friction", "rollingFriction"),
                      ("spinning_friction", "spinningFriction"), ("margin", "collisionMargin"),
                      ("contact_stiffness", "contactStiffness"), ("contact_damping", "contactDamping")):
        if key in setting:
            dyn[name] = setting[key]
    if friction_cases.friction_of(record) is not None:  # Coulomb: no torsional or rolling friction (0 by default: said, not assumed)
        dyn.update(spinningFriction=0.0, rollingFriction=0.0)
    p.changeDynamics(body, -1, physicsClientId=cid, **dyn)
    p.changeDynamics(plane, -1, lateralFriction=mu_plane, physicsClientId=cid,
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


def start_tolerance(geo: dict) -> float:
    """The scorer's start tolerance for this body: its strict default (1e-12) for the ring, which the
    cylinder is exactly; for the disk, the cylinder's rim sits half its height off the zero-thickness
    disk's, so C starts h cos(theta) higher than the disk's C: the model difference, not an engine error,
    allowed for at 4 h (said in the score's verdict as a loosened start)."""
    return max(START_TOLERANCE, 4 * (geo["h"] - geo["h_model"]))


def simulate(record: dict, setting: dict, t_end: float):
    p, cid, body, geo, b0 = setup(record, setting)
    try:
        got0 = check_start(p, cid, body, b0)
        # a Coulomb case every 2^-10 s (1/32 of its grid spacing), to resolve the slip phase and the stick
        steps = output_steps(record, setting["dt"], t_end, 32 if friction_cases.friction_of(record) is not None else 8)
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
    import pybullet  # lazy: optional package (pybullet)

    record = load_case(case)
    table = COULOMB_SETTINGS if friction_cases.friction_of(record) is not None else SETTINGS
    name, cfg = (setting, dict(table[setting])) if isinstance(setting, str) else ("custom", dict(setting))
    t_end = float(record["t_end"]) if t_end is None else float(t_end)
    cols, wall, outcome, geo = simulate(record, cfg, t_end)
    if outcome == "ok":
        theta = np.arctan2(np.hypot(*_e3xy(cols)), _e3z(cols))
        # theta is the tilt of e3 from the vertical: pi/2 upright, 0 lying flat; C below the plane: sunk
        if np.any(theta < FLAT) or np.any(cols["z"] < -1e-3):
            outcome = "fell"
    friction = friction_cases.friction_record(cols, record)  # None for a rolling case
    sc = None
    try:
        sc = score(cols, case, start_tolerance=start_tolerance(geo))
        rec_score = sc.to_record()
    except Exception as exc:  # noqa: BLE001 - reported, not hidden
        rec_score, outcome = None, f"error: {type(exc).__name__}: {exc}"
    if out:
        write_csv(cols, out)
    mu_body, mu_plane = lateral_friction(record, cfg)
    rec = {"engine": "PyBullet", "version": _version(pybullet), "case": case, "setting": name,
           "parameters": {**cfg, "cylinder_half_height": geo["h"], "inertia": [geo["I1"], geo["I1"], geo["I3"]],
                          "lateral_friction": {"body": mu_body, "plane": mu_plane, "combined": mu_body * mu_plane}},
           "t_end": t_end, "wall_s": round(wall, 3), "score": rec_score, "outcome": outcome,
           "_score": sc, "_columns": cols}
    if friction is not None:
        rec["friction"] = friction
    return rec


def _e3xy(c):
    qw, qx, qy, qz = (c[k] for k in QUATERNION)
    return 2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx)


def _e3z(c):
    qw, qx, qy, qz = (c[k] for k in QUATERNION)
    return 1 - 2 * (qx * qx + qy * qy)


def _version(pybullet) -> str:
    try:
        return metadata.version("pybullet")
    except Exception:  # noqa: BLE001
        return "unknown"


def write_csv(cols: dict, path) -> None:
    data = np.column_stack([cols[c] for c in COLUMNS])
    np.savetxt(path, data, delimiter=",", header=",".join(COLUMNS), comments="", fmt="%.17g")


def _row(r: dict) -> str:
    s = r["score"]
    if s is None:
        return f"{r['case']:<19} {r['setting']:<8} {r['outcome']}"
    fin = min(c["final_digits"] for c in s["components"].values())
    # a Coulomb case: the energy error against the reference's (friction takes energy) and where the run slides
    energy = s["energy_rel_error"] if s.get("energy_rel_error") is not None else s["energy_rel_drift"]
    slides = "" if not r.get("friction") else f"  slides {r['friction']['run']['slides'][:3]}"
    return (f"{r['case']:<19} {str(r['setting']):<8} {r['outcome']:<7} {s['min_digits']:6.2f} {fin:6.2f}  "
            f"{energy:.1e}  {s['contact_height']:.1e}  {s['contact_velocity']:.1e}  {r['wall_s']:.2f} s{slides}")


def table(t_end: float = 1.0) -> list:
    """The measured table of the docstring: every case at "default" and "best" to t_end."""
    rows = []
    for case in ("disk-standard-1", "hoop-general-10", "ring-standard-10", "coin-coulomb-slip-1", "coin-coulomb-skid-1"):
        for name in ("default", "best"):
            r = run_case(case, name, t_end)
            print(_row(r), flush=True)
            rows.append({k: v for k, v in r.items() if not k.startswith("_")})
    return rows


def sweep(case: str = "disk-standard-1", exponents=(10, 12, 14, 16, 18, 20), t_end: float = 1.0) -> list:
    """The step sweep of the docstring: the best setting with dt = 2^-n."""
    rows = []
    for n in exponents:
        r = run_case(case, {**BEST, "dt": 2.0 ** -n}, t_end)
        r["setting"] = f"2^-{n}"
        print(_row(r), flush=True)
        rows.append({k: v for k, v in r.items() if not k.startswith("_")})
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--setting", default="best", choices=sorted(SETTINGS))
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--out", default=None)
    ap.add_argument("--table", action="store_true", help="the docstring's table (all cases, both settings, 1 s)")
    ap.add_argument("--sweep", action="store_true", help="the docstring's step sweep on --case")
    args = ap.parse_args()
    if args.table or args.sweep:
        table() if args.table else sweep(args.case)
        return
    r = run_case(args.case, args.setting, args.t_end, args.out)
    sc = r.pop("_score")
    r.pop("_columns")
    if sc is not None:
        print(sc.table())
    print(json.dumps({k: v for k, v in r.items() if k != "score"}, indent=1, default=str))


if __name__ == "__main__":
    main()

"""The reference cases run in MuJoCo (pip ``mujoco``; measured with 4.0.0) and scored by ``verify.score``.

    python examples/engines/mujoco_adapter.py --case disk-standard-1 --setting best --out run.csv

``run_case(case, setting="default" | "best" | dict, t_end=None) -> dict`` builds the body in
MuJoCo, sets the case's start (``verify.frames.euler_to_b``), reads it back and checks it,
steps, writes the run in form (b) with a quaternion (``t, qw, qx, qy, qz, x, y, z, vx, vy,
vz, wx, wy, wz``), scores it and returns a JSON-ready record.  ``SWEEP`` holds the measured
convergence sweep (see the end of this docstring).

Mapping and pitfalls (each one silently wrong if missed):

* Units: MuJoCo has none of its own; lengths in R (R = 1), m = 1, gravity ``0 0 -980``
  (g/R in s^-2 with R = 1 cm), time in s.  MuJoCo's default gravity is -9.81: keep it and
  the body falls 100 times too slowly.
* Inertia: set explicitly (``<inertial mass="1" diaginertia="I1 I1 I3"/>``); otherwise MuJoCo
  derives mass and inertia from the geom at density 1000, and the cylinder's own inertia is
  not the case's (a thin disk is I1 = 1/4, I3 = 1/2; the ring's I1, I3 are not a uniform
  cylinder's).  The body frame is then the inertial frame, its z axis the symmetry axis e3.
* Quaternion: MuJoCo's qpos[3:7] is (w, x, y, z), scalar first, body -> world, the suite's order.
* Angular velocity: a free joint's qvel[0:3] is C's velocity in WORLD components but
  qvel[3:6] is omega in BODY (local) components; the scorer wants inertial components:
  omega_world = R omega_body (and the start's omega must be turned back with R^T).
* Geometry: a cylinder geom (``size="1 h"``, axis local z) touches the plane on a rim edge,
  half a thickness h off the mid-plane: r_P = -e2 - h e3, exactly the suite's ring (a coin).
  The thin disk (r_P = -e2) is modelled as a cylinder of half-height ``half_height`` (1e-4 R):
  the body is then the ring model with h = 1e-4, a model difference of order h, below the
  engine's errors measured here (about 1e-3); it is not zero.
* Friction: condim 3 (sliding only).  condim 4 or 6 would add torsional/rolling friction
  that the ideal rolling body does not have (it may pivot freely about the normal).
  MuJoCo's friction is soft too: a rolling contact creeps (the contact point's velocity is
  not 0) unless the friction constraint is stiff; ``noslip_iterations`` post-projects it.
* Contact softness: the default contact (solref 0.02 1, solimp 0.9 0.95 0.001) is a spring
  of time constant 20 ms: under g = 980 the rim sinks into the plane by a large fraction of
  a length unit (measured below as "contact height"), the tilt and the rates follow a
  sunk body.  MuJoCo clamps a positive time constant to >= 2 dt (refsafe); the direct form
  ``solref="-stiffness -damping"`` is not clamped.  The start has the rim exactly at z = 0,
  so a soft contact begins with a sink-in transient (part of the engine's error here).
* Damping: joints have 0 damping by default and a free joint gets none; no global damping
  (``option/@viscosity`` 0, no air density).  Nothing to switch off, but the default
  integrator (semi-implicit Euler, dt = 2 ms) drifts in energy.
* Margins: geom margin 0 by default; a positive margin makes contacts active before touch.
* Output: MuJoCo's state at t = n dt; output times are multiples of dt (every ~1 ms),
  not the case's stored grid, so the scorer re-integrates the reference in quad at them.
  The scorer accepts a run that stops before t_end and scores it over its own times (a run
  that fell is scored to the fall; ``outcome`` says so).  "fell": e3 within 0.05 rad of
  vertical (the reference's theta stays above 0.23 rad on all three cases).
* Dead ends (no change in the score): impratio 10..1000, noslip_iterations 10/20, friction 10,
  solimp 0.999/0.9999.  A pyramidal cone loses 1.2 digits against elliptic (creep).  Too stiff
  a contact for the thickness bounces: k = 1e10 with h = 1e-4 and k = 1e12 with h = 1e-5
  lift the rim by ~9e-4 (contact height) and lose ~0.4-0.8 digits.

Measured (MuJoCo 4.0.0, x86-64, 2 shared cores; min digits = score.min_digits; "k b" is solref
"-k -b"; h the disk's half-height; E the energy drift; command: ``run_case(case, setting, t_end)``)

disk-standard-1 to t = 0.1 s (elliptic, solimp 0.99 0.999 unless said):
  default (Euler 2 ms, solref 0.02 1, pyramidal)    fell at 0.17 s; -0.1 digits, E 0.95, sinks 0.62 R
  RK4 2e-6, k 1e7 b 1e2 / 1e3, h 1e-4                0.60 / 1.38
  RK4 2e-6, k 1e8 b 1e4, h 1e-4 (dt 1e-5: same)      2.31 (E 4.5e-3)
  RK4 2e-6, k 1e9 b 3e4 / dt 1e-5 b 6.3e4            2.76 / 2.97
  implicitfast 1e-5, k 1e9 b 6.3e4 (dt 1e-4: blows)  3.10
  RK4 2e-6, k 1e10 b 2e5, h 1e-4 / 1e-5 / 1e-6       3.21 / 3.61 / 3.67
  RK4 5e-7, k 1e11 b 6.3e5, h 1e-5                   4.03 (3.5 s)
  implicitfast 1e-6 / 5e-7, k 1e11 b 6.3e5, h 1e-5   4.13 (1.5 s) / 4.08 (1.7 s)
  implicitfast 2e-7, k 1e12 b 2e6                    3.25 (bounces)
disk-standard-1 to t = 1 s (implicitfast, k 1e11 b 6.3e5, h 1e-5 unless said), digits / wall:
  RK4 1e-5 k 1e9 b 6.3e4: 1.05 / 2.5 s;  k 1e10 b 2e5 dt 2e-6: 1.43 / 9.3 s;
  dt 1e-6: 1.72 / 7.3 s (h 1e-6: 1.71);  dt 5e-7 ("best"): 2.04 / 17 s;  dt 2.5e-7: 2.16 / 15 s;
  RK4 5e-7: 2.08 / 39 s.  The error grows in the fast low-tilt phases (t ~ 0.88 s, rates ~270 s^-1).

Coulomb cases (coin-coulomb-slip-1: mu = 0.87, rolls, slides from 0.0780 to 0.0966, rolls; coin-coulomb-skid-1:
mu = 0.3, starts sliding, sticks at 0.0765; ``friction_cases``)
---------------------------------------------------------------------------------------------------------
* Friction coefficient: ``friction="mu 0 0"`` on BOTH geoms, condim 3 (sliding friction only: the torsional
  and rolling coefficients are not used).  MuJoCo combines two geoms of equal priority by the element-wise
  MAXIMUM of their friction (doc/modeling.rst, "Contact parameters", shipped in the wheel at
  ``mujoco/doc/modeling.rst``): mu on both is mu; mu on the coin alone would leave the plane's default 1.
* Cone: MuJoCo's default is pyramidal (``option/@cone``): for condim 3 four edges n +- mu t1, n +- mu t2, so
  the friction force is bounded by |f1| + |f2| <= mu N in the contact frame's two tangent axes: mu N along an
  axis, mu N / sqrt 2 diagonal to them (doc/computation/index.rst, "Friction cones"): not Coulomb's isotropic
  cone.  "best" is elliptic (exactly ||f_t|| <= mu N).
* Friction is regularised: the constraints are soft, and the friction rows of an elliptic cone have no position
  term, their reference acceleration is pure damping (computation/index.rst, "reference acceleration"): a
  rolling contact creeps (the largest slip speed where the reference rolls, 10 ms off its switches: 1.3e-3
  R/s on slip-1, 1.3e-4 on the skid at "best") and a slip starts and ends smoothly.  ``impratio`` (friction "harder" than the normal) and the
  NoSlip post-solver change nothing measurable here (below).
* The coin HOPS while it slides.  MuJoCo's convex model gives up complementarity: "the only way to initiate
  slip is to generate some motion in the normal direction" (computation/index.rst, overview).  Measured on
  the skid at "best": the rim leaves the plane by up to 4.3e-3 R and touches it in 46 of the 100000 steps of
  the first 50 ms; the friction impulses come in kicks, and the skid sticks at 0.0690, 7 ms BEFORE the
  reference's 0.0765, at every step (2.5e-7 to 1e-6), stiffness (-1e10 to -1e12), solver (Newton, PGS),
  impratio (1, 10) and NoSlip setting tried: a model difference, not a convergence error.  On slip-1 the
  slide is short and slow (3 R/s) and its times are right (0.0793 to 0.0966 at the 0.1 R/s threshold, the
  reference's own 0.0793 to 0.0964); the run still ends near 1 digit (worst y near t = 0.89).
* Start: a skid's centre-of-mass velocity goes into qvel[0:3] (world components) like a rolling one; the
  read-back check covers it (start_readback 8e-15 on the skid).
* Settings: "default" is DEFAULT with mu on both geoms (pyramidal cone, Euler 2 ms, solref 0.02 1); "best" is
  the rolling cases' BEST: no variant of the Coulomb sweep did better.

Coulomb sweep (min digits over the whole second, slip-1 / skid-1, and where the skid sticks; the runs compared
with this suite's hybrid run in double at their own times, the scorer's scales; "best" gives the same digits
with ``verify.score`` against the reference files)::

    best (implicitfast 5e-7, k 1e11 b 6.3e5, elliptic)   1.00 / 0.64   0.0690   (15 s / 8 s)
    dt 1e-6                                              0.97 / 0.64   0.0698
    dt 2.5e-7                                               - / 0.64   0.0688
    k 1e10 b 2e5, dt 1e-6                                1.01 / 0.64   0.0689
    k 1e12 b 2e6, dt 2.5e-7                              0.99 / 0.65   0.0695
    solref 0.001 1 (1 ms time constant), dt 2e-6         0.00 / 0.64   0.0685   (slip-1: 7 slides from 0.051)
    RK4 1e-6 / PGS / impratio 10 / noslip 10             1.01, 1.00, -, - / 0.65, 0.64, 0.64, 0.64
    pyramidal cone                                          - / -0.61  slides to 0.67 s (5 slides)

Measured on the Coulomb cases (``python -m verify engines --case coin-coulomb-slip-1 --case coin-coulomb-skid-1``,
each run in a process of its own on 2 shared cores, scored by ``verify.score`` against the reference files; energy
= max |E - E_ref| / E_ref(0), slip = max | |u| - s_ref | in R/s, z_P = max |contact height|, slides where the
contact's slip speed exceeds 0.1 R/s; the reference slides from 0.0780 to 0.0966 on slip-1, its own slip speed
crossing 0.1 R/s at 0.0793 and 0.0964, and the skid sticks at 0.0765, crossing at 0.0761)::

    case    setting  outcome   min digits (where)        energy   slip    z_P      slides                         wall s
    slip-1  default  fell      0.07 (y, t = 0.178)      1.1      27      0.60     0.0062-0.0328, 0.0389-         0.6
    slip-1  best     ok        1.00 (y, t = 0.892)      8.1e-4   0.088   1.2e-5   0.0793-0.0966                  15.2
    skid-1  default  fell     -0.13 (phidot, t = 0.44)  0.94     36      0.70     0- (never sticks)              0.4
    skid-1  best     ok        0.64 (phidot, t = 0.957) 1.2e-2   2.1     4.3e-3   0-0.0690                       11.9

(fell: e3 within 0.05 rad of vertical, the coin lying flat; start read back to 3e-15 and 8e-15.)
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parent))  # friction_cases, beside this file

from models.symbols import STATE_NAMES  # noqa: E402
from verify import score  # noqa: E402
from verify.frames import QUATERNION_FORM, b_to_euler  # noqa: E402
from verify.scoring import START_TOLERANCE  # noqa: E402
import friction_cases  # noqa: E402

#: MuJoCo's own defaults (option and geom), as a new user gets them: only what describes the body is set.
DEFAULT = {"dt": 0.002, "integrator": "Euler", "solver": "Newton", "cone": "pyramidal", "iterations": 100,
           "tolerance": 1e-8, "noslip_iterations": 0, "impratio": 1.0, "solref": "0.02 1", "solimp": "0.9 0.95 0.001 0.5 2",
           "friction": "1 0.005 0.0001", "condim": 3, "margin": 0.0, "half_height": 1e-5}
#: the best of the sweep below (SWEEP)
BEST = dict(DEFAULT, dt=5e-7, integrator="implicitfast", cone="elliptic", solref="-1e11 -6.3e5",
            solimp="0.99 0.999 0.001 0.5 2")
SETTINGS = {"default": DEFAULT, "best": BEST}

#: convergence sweep, disk-standard-1 to t = 1 s, MuJoCo 4.0.0: (changes from BEST, min digits, wall s)
SWEEP = [({"integrator": "RK4", "dt": 1e-5, "solref": "-1e9 -6.3e4"}, 1.05, 2.5),
         ({"dt": 2e-6, "solref": "-1e10 -2e5"}, 1.43, 9.3), ({"dt": 1e-6}, 1.72, 7.3),
         ({"dt": 1e-6, "half_height": 1e-6}, 1.71, 6.3), ({}, 2.04, 16.8), ({"dt": 2.5e-7}, 2.16, 15.2),
         ({"integrator": "RK4"}, 2.08, 38.9)]
#: the runs of the report (run_case(case, setting, t_end)): (case, t_end, setting, min digits, final digits
#: (fewest of any component), energy drift, contact height, contact velocity, wall s, outcome)
MEASURED = [("disk-standard-1", 1, "default", -0.11, -0.11, 0.95, 0.62, 32.0, 0.7, "fell at 0.17 s"),
            ("disk-standard-1", 1, "best", 2.04, 2.26, 3.8e-4, 9.6e-6, 0.044, 15.9, "ok"),
            ("hoop-general-10", 2, "default", -0.09, 0.05, 0.95, 0.52, 19.5, 0.03, "fell at 0.854 s"),
            ("hoop-general-10", 2, "best", 1.71, 1.71, 2.9e-4, 1.7e-4, 0.30, 16.0, "ok"),
            ("ring-standard-10", 2, "default", -0.29, -0.29, 0.40, 0.28, 2.8, 2.2, "ok (sunk 0.28 R)"),
            ("ring-standard-10", 2, "best", 3.25, 3.27, 4.0e-6, 1.0e-9, 6.0e-5, 17.8, "ok")]

OUTPUT_EVERY = 1e-3  # s, about


def case_record(case: str) -> dict:
    """The case's record (:func:`friction_cases.load_case`: with ``friction`` and ``velocity``)."""
    return friction_cases.load_case(case)


def with_friction(s: dict, record: dict) -> dict:
    """The setting for this case: a Coulomb case's mu on both geoms (MuJoCo takes the element-wise maximum
    of the two geoms' friction: the same mu on both is mu), torsional and rolling 0 (unused at condim 3)."""
    mu = friction_cases.friction_of(record)
    return s if mu is None else dict(s, friction=f"{mu!r} 0 0")


def body_of(record: dict, half_height: float) -> dict:
    """(model, I1, I3, cylinder half-height, params for euler_to_b) of a case."""
    p = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    name = record["model"]["name"]
    if name == "disk":
        return {"model": "disk", "I1": p["k"], "I3": 2 * p["k"], "h": half_height, "g": p["g"], "params": p}
    if name == "ring":
        return {"model": "ring", "I1": p["I1"], "I3": p["I3"], "h": p["h"], "g": p["g"], "params": p}
    raise ValueError(f"case {record['name']} is a {name}: this adapter runs the disk/hoop and the ring (coin)")


def mjcf(body: dict, s: dict) -> str:
    contact = (f'friction="{s["friction"]}" condim="{s["condim"]}" solref="{s["solref"]}" solimp="{s["solimp"]}" '
               f'margin="{s["margin"]}"')
    return f"""<mujoco model="rolling">
  <option timestep="{s['dt']!r}" integrator="{s['integrator']}" solver="{s['solver']}" cone="{s['cone']}"
          iterations="{s['iterations']}" tolerance="{s['tolerance']!r}" noslip_iterations="{s['noslip_iterations']}"
          impratio="{s['impratio']!r}"
          gravity="0 0 {-body['g']!r}"/>
  <worldbody>
    <geom name="plane" type="plane" size="0 0 1" {contact}/>
    <body name="body">
      <freejoint/>
      <inertial pos="0 0 0" mass="1" diaginertia="{body['I1']!r} {body['I1']!r} {body['I3']!r}"/>
      <geom name="rim" type="cylinder" size="1 {body['h']!r}" {contact}/>
    </body>
  </worldbody>
</mujoco>"""


def read_state(mujoco, m, d) -> dict:
    """Form (b) columns (no t) of MuJoCo's current state: omega turned from body to world components."""
    q = np.array(d.qpos[3:7])
    R = np.empty(9)
    mujoco.mju_quat2Mat(R, q)
    w = R.reshape(3, 3) @ np.array(d.qvel[3:6])
    cols = dict(zip(("qw", "qx", "qy", "qz"), q))
    cols.update(zip(("x", "y", "z"), d.qpos[0:3]))
    cols.update(zip(("vx", "vy", "vz"), d.qvel[0:3]))
    cols.update(zip(("wx", "wy", "wz"), w))
    return {k: float(v) for k, v in cols.items()}


def set_start(mujoco, m, d, b0: dict) -> None:
    q = np.array([b0[c] for c in ("qw", "qx", "qy", "qz")])
    R = np.empty(9)
    mujoco.mju_quat2Mat(R, q)
    w_world = np.array([b0["wx"], b0["wy"], b0["wz"]])
    d.qpos[:] = [b0["x"], b0["y"], b0["z"], *q]
    d.qvel[:] = [b0["vx"], b0["vy"], b0["vz"], *(R.reshape(3, 3).T @ w_world)]
    mujoco.mj_forward(m, d)


def check_start(back: dict, b0: dict, record: dict) -> float:
    """Largest difference of the read-back start from the case's form (b) start and Euler start; raises beyond rounding."""
    worst = max(abs(back[c] - b0[c]) / max(1.0, abs(b0[c])) for c in back)
    state, _, _ = b_to_euler({c: np.array([v]) for c, v in back.items()})
    for n in STATE_NAMES:
        want = float(record["initial_state"][n])
        diff = abs(float(state[n][0]) - want)
        if n in ("phi", "psi"):
            diff = abs((diff + np.pi) % (2 * np.pi) - np.pi)
        worst = max(worst, diff / max(1.0, abs(want)))
    if not worst <= 1e-12:
        raise RuntimeError(f"MuJoCo's start read back differs from case {record['name']} by {worst:.2e} "
                           f"(relative): {back} vs {b0}")
    return worst


def simulate(record: dict, s: dict, t_end: float) -> tuple:
    """(columns dict of arrays, outcome, start check, number of contacts at the end)."""
    import mujoco  # lazy: optional package (mujoco)

    body = body_of(record, s["half_height"])
    m = mujoco.MjModel.from_xml_string(mjcf(body, s))
    d = mujoco.MjData(m)
    b0 = friction_cases.start_b(record, body["model"], body["params"])  # a skid's CM velocity where given
    set_start(mujoco, m, d, b0)
    back = read_state(mujoco, m, d)
    check = check_start(back, b0, record)
    stride = max(1, int(round(OUTPUT_EVERY / s["dt"])))
    n_out = int(np.floor(t_end / (stride * s["dt"]) + 1e-9))
    rows = [dict(back, t=0.0)]
    outcome = "ok"
    for k in range(1, n_out + 1):
        mujoco.mj_step(m, d, nstep=stride)
        warned = [mujoco.mjtWarning(i).name for i in range(len(d.warning)) if d.warning[i].number > 0]
        if not np.all(np.isfinite(d.qpos)) or warned:
            outcome = f"error: {', '.join(warned) or 'non-finite state'} at t = {d.time:.6g}"
            break
        row = read_state(mujoco, m, d)
        row["t"] = k * stride * s["dt"]  # the exact time of step k*stride (d.time accumulates rounding)
        rows.append(row)
        # e3's vertical component is cos(theta): flat on the plane is the fall (the cases stay well tilted)
        if 1 - 2 * (row["qx"] ** 2 + row["qy"] ** 2) > np.cos(0.05):
            outcome = f"fell (flat on the plane) at t = {row['t']:.4g}"
            break
    cols = {c: np.array([r[c] for r in rows]) for c in QUATERNION_FORM}
    return cols, outcome, check, mujoco.__version__


def resolve(setting) -> tuple:
    if isinstance(setting, dict):
        return setting.get("name", "custom"), dict(DEFAULT, **{k: v for k, v in setting.items() if k != "name"})
    return setting, dict(SETTINGS[setting])


def start_tolerance(record: dict, setting: dict) -> float:
    """The scorer's start tolerance: its strict default (1e-12) for the ring, which the cylinder is
    exactly; for the disk the cylinder's rim sits ``half_height`` off the zero-thickness disk's, so C
    starts h cos(theta) higher than the disk's C -- the model difference, not an engine error, allowed
    for at 4 h and said in the score's verdict."""
    if record["model"]["name"] != "disk":
        return START_TOLERANCE
    return max(START_TOLERANCE, 4 * float(setting["half_height"]))


def run_case(case: str, setting="default", t_end=None, out=None) -> dict:
    """Run ``case`` in MuJoCo at ``setting`` ('default', 'best' or a dict of DEFAULT's keys) to ``t_end``
    (the case's by default), score it and return a JSON-ready record; ``out`` writes the run's CSV."""
    record = case_record(case)
    name, s = resolve(setting)
    s = with_friction(s, record)
    t_end = float(record["t_end"]) if t_end is None else float(t_end)
    result = {"engine": "MuJoCo", "version": None, "case": case, "setting": name, "parameters": s, "t_end": t_end}
    t0 = time.perf_counter()
    try:
        cols, outcome, check, version = simulate(record, s, t_end)
    except Exception as err:  # noqa: BLE001 -- reported, not hidden
        result.update(wall_s=round(time.perf_counter() - t0, 3), score=None, outcome=f"error: {err}")
        return result
    result.update(version=version, wall_s=round(time.perf_counter() - t0, 3), start_readback=float(f"{check:.2e}"),
                  outcome=outcome)
    if out is not None:
        write_csv(cols, out)
    result["_columns"] = cols  # not JSON: the run itself
    if friction_cases.friction_of(record) is not None:  # where the run slides and sticks, beside the reference's switches
        result["friction"] = friction_cases.friction_record(cols, record)
    try:
        sc = score(cols, case, start_tolerance=start_tolerance(record, s))
    except Exception as err:  # noqa: BLE001
        result.update(score=None, outcome=f"error: score: {err}")
        return result
    result["score"] = sc.to_record()
    result["_score"] = sc  # not JSON: the Score itself (dropped by json_ready)
    return result


def json_ready(result: dict) -> dict:
    return {k: v for k, v in result.items() if not k.startswith("_")}


def write_csv(cols: dict, path) -> None:
    names = list(QUATERNION_FORM)
    table = np.column_stack([cols[n] for n in names])
    np.savetxt(path, table, delimiter=",", header=",".join(names), comments="", fmt="%.17g")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--setting", default="best", choices=sorted(SETTINGS))
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--out", default=None, help="write the run as CSV (form (b), quaternion)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="override one of the setting's parameters, e.g. --set dt=1e-5")
    args = ap.parse_args(argv)
    setting = args.setting
    if args.set:
        s = dict(SETTINGS[args.setting], name=args.setting + "+" + ",".join(args.set))
        for kv in args.set:
            k, v = kv.split("=", 1)
            s[k] = type(DEFAULT[k])(v) if not isinstance(DEFAULT[k], str) else v
        setting = s
    r = run_case(args.case, setting, args.t_end, args.out)
    if r.get("_score") is not None:
        print(r["_score"].table())
    rec = json_ready(r)
    rec.pop("score", None)
    print(json.dumps(rec))
    return 0 if r["outcome"] == "ok" else 1


if __name__ == "__main__":
    sys.exit(main())

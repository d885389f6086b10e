"""Drake (pip ``drake``) running the suite's reference cases, scored by ``verify.score``.

Measured with Drake 1.51.1 (``pip install drake``), Python 3.11, x86_64 Linux, on 2 shared cores.

Usage::

    python examples/engines/drake_adapter.py --case disk-standard-1 --setting best --out run.csv
    python examples/engines/drake_adapter.py --case ring-standard-10 --setting default --t-end 2

``run_case(case, setting, t_end)`` returns a JSON-ready record (engine, version, case, setting,
parameters, t_end, wall_s, score = ``Score.to_record()``, outcome 'ok' | 'fell' | 'error: ...').
The body is a MultibodyPlant free body (mass 1, the case's I1, I3 about C) with a ``Cylinder``
collision geometry (radius 1; half-height h for the ring, 1e-6 for the thin disk) on a
``HalfSpace``; gravity (0, 0, -980).  The run is written in the quaternion form at 1/128 s
(at multiples of the time step for a discrete plant) and scored against the quad reference.

Settings
--------
* default: ``MultibodyPlantConfig()`` and ``Simulator()`` as they come: discrete, time_step 1e-3,
  'lagged' (SAP) contact, hydroelastic_with_fallback (point contact here: no hydroelastic
  properties), stiffness and Hunt-Crossley dissipation estimated from penetration_allowance
  1e-3, mu = 1.
* best: continuous plant (time_step 0), RK3 with error control (accuracy 1e-4), point
  stiffness 1e9 (static sink m g / k ~ 1e-6 R), Hunt-Crossley dissipation 0, stiction tolerance
  1e-3, mu = 1.

Sweep on disk-standard-1 (min digits / final digits / energy drift / wall s; wall times on a
loaded machine, +-30 %).  To t = 1 s:

====================================================  =====  =====  =======  ======
setting                                               min    final  E drift  wall s
====================================================  =====  =====  =======  ======
default (discrete 1e-3, lagged): sinks, 'fell'        -0.19   0.00  5.2e-1     1.1
discrete lagged 1e-5, k 1e8, d 0                       0.68   1.63  3.2e-3    11.5
discrete lagged 5e-6, k 1e8, d 0                       1.00   1.94  1.7e-3    61
continuous RK3 1e-4, k 1e8, d 0, stiction 1e-2         1.19   1.27  3.7e-3     7.5
continuous RK3 1e-4, k 1e8, d 0, stiction 3e-3         1.71   1.78  1.1e-3    27.7
continuous RK3 1e-4, k 1e9, d 0, stiction 3e-3         1.73   1.79  1.1e-3    20.4
continuous RK3 1e-4, k 1e8, d 0, stiction 1e-3         2.14   2.22  6.2e-4    57.6
best: continuous RK3 1e-4, k 1e9, d 0, stiction 1e-3    2.20   2.27  3.8e-4    48.5
====================================================  =====  =====  =======  ======

To t = 0.25 s (min digits): default 0.02; discrete 1e-4 0.04; discrete 1e-5, k 1e8, mu 10 with
the default dissipation: lagged 0.68, sap 0.98, similar 1.10; the same with dissipation 0:
1.83 (lagged and similar alike; k 1e9 or mu 1 instead of 10: 1.83); 2e-5: 1.53; 'tamsi' (stiction
1e-3): its solver fails to converge at t = 0.075.  Continuous RK3 at accuracy 1e-6, stiction
1e-3: 3.46 digits in 87 s.  The digits follow the stiction tolerance (1e-2, 3e-3, 1e-3 ->
1.2, 1.7, 2.1) and the time step of the discrete plant (first order), not the stiffness.

The other cases, first 2 s (``--t-end 2``; the scorer accepts a run that stops before t_end
and scores [0, t_last] against the quad re-integration at the run's times):

=====================================  =====  =====  =======  ========  ========  ======
case, setting                          min    final  E drift  max |zP|  max |vP|  wall s
=====================================  =====  =====  =======  ========  ========  ======
hoop-general-10 default ('fell')        0.00   0.27  4.9e-1   1.2       13          0.7
hoop-general-10 best                    1.96   1.96  4.7e-4   1.7e-6    7.7e-3     55.7
ring-standard-10 default (a coin)       0.00   0.00  6.0e-3   3.1e-2    3.3e-1      1.3
ring-standard-10 best (a coin)          2.67   2.67  6.8e-5   1.7e-6    2.6e-2     75.4
disk-standard-1 default ('fell', 1 s)  -0.19   0.00  5.2e-1   1.3       18          0.5
disk-standard-1 best (1 s)              2.20   2.27  3.8e-4   3.6e-6    1.7e-2     48.5
=====================================  =====  =====  =======  ========  ========  ======

The ring at defaults stays up but sinks 0.03 R into the plane and its precession phase
(phi) is wrong by ~pi at t = 2 s.

Pitfalls (each one silently wrong, not an error)
------------------------------------------------
* Units: Drake is nominally SI, but nothing in it is unit-aware; here lengths are R (= 1 cm),
  so g = 980 and the defaults penetration_allowance 1e-3 (m) and stiction_tolerance 1e-4 (m/s)
  become 1e-3 R and 1e-4 R/s.  The default point stiffness is estimated from the allowance,
  the mass and |g| at Finalize: set gravity before ``Finalize()``.
* At defaults the disk SINKS THROUGH THE PLANE: at the nutation's dips (theta ~ 0.25, rates
  ~ 270 rad/s) the rim moves ~0.2 R per 1 ms step, the point contact is lost and C ends at
  z = -0.96 by t = 0.96 s; half the energy is gone.  hoop-general-10 does the same.  Even at
  dt = 1e-5 the default Hunt-Crossley dissipation costs a digit and spins the disk down:
  set dissipation 0.
* Friction is regularised: the continuous plant's Stribeck model lets the contact slide at up
  to the stiction tolerance, the discrete SAP solvers regularise it too.  No setting is truly
  "no slip"; mu = 1 vs 10 makes no difference, the stiction tolerance (continuous) or time step
  (discrete) sets the digits.  A small stiction tolerance makes the continuous plant stiff
  (RK3's steps shrink: 1e-3 is ~8x slower than 1e-2).
* Point stiffnesses (and dissipations) of two geometries combine in series, k1 k2 / (k1 + k2):
  both get 2k to make the pair k.
* Angular velocity: ``SpatialVelocity(w, v)`` is angular FIRST; ``SetFreeBodySpatialVelocity``
  and ``EvalBodySpatialVelocityInWorld`` are in WORLD components, about the body origin (= C:
  the inertia is given about it).  In 1.51 the argument order is (context, body, V); the old
  (body, V, context) is deprecated.  The free body's generalized velocities are (w, v), world.
* Quaternion: ``Quaternion(w, x, y, z)`` and the positions (qw, qx, qy, qz, x, y, z) are scalar
  first, as the suite's; Eigen's own coefficient vector is (x, y, z, w).  The continuous
  plant's state quaternion is not kept unit: the pose's rotation (normalised) is read.
* Discrete time: after ``AdvanceTo(k dt)`` the context holds x_k (checked by free fall: one
  update per step), so output times must be multiples of dt (1/32 s is not one of 1e-3).
* Geometry: the collision geometry carries no mass, the inertia is what is given; a
  ``Cylinder`` touches on its rim EDGE, half its length off the mid-plane: with length 2h it is
  the ring of models/ring.py exactly (r_P = -e2 - h e3, a coin), and the thin disk is a
  cylinder of length 2e-6 (an error of 1e-6 R in the contact point, far below the rest).
  No collision margin applies to point contact; the compliant contact sinks m g / k.
* "WARNING: Rigid half spaces are not currently supported for deformable contact" at
  Finalize is harmless here (no deformable bodies).

Coulomb cases (coin-coulomb-slip-1: mu = 0.87, rolls, slides from 0.0780 to 0.0966, rolls; coin-coulomb-skid-1:
mu = 0.3, starts sliding, sticks at 0.0765; ``friction_cases``)
---------------------------------------------------------------------------------------------------------
* Friction coefficient: ``CoulombFriction(mu, mu)`` (static = dynamic, as the cases) on BOTH geometries.
  Drake combines two surfaces' coefficients as mu = 2 mu1 mu2 / (mu1 + mu2), static and dynamic apart
  (``CalcContactFrictionFromSurfaceProperties`` and the ``CoulombFriction`` class docstring, pydrake 1.51.1):
  mu with mu is mu; mu on the coin and the default 1 elsewhere would not be.
* Regularisation: the continuous plant uses the Stribeck approximation, parameterised by the stiction
  tolerance v_s, "the slip velocity that we'd have when we are at edge of the friction cone" (smaller inside
  it; ``MultibodyPlant.set_stiction_tolerance``): a rolling contact creeps by up to v_s, and a small v_s makes
  the plant stiff (RK3's steps shrink).  The discrete approximations tamsi, similar and lagged are regularised
  by the same tolerance, sap by the numerics alone; sap and similar "glide" in sliding contact, O(dt)
  (``DiscreteContactApproximation`` docstring).
* Settings: "default" is DEFAULT with mu (discrete 1 ms, lagged: the coin sinks and falls on slip-1, and the
  skid's first slide ends at 0.011 s); "best" is BEST with the stiction tolerance 3e-4 (COULOMB_SETTINGS): the
  digits follow v_s, and 1e-4 would take well over the 5 minutes a run may take.
* The discrete lagged plant at dt = 1e-5 (k 1e9, dissipation 0) never slides on slip-1 (-0.23 digits): where
  mu_req reaches mu for 19 ms it holds on; on the skid it sticks at 0.0752, 1 ms early (1.65 digits).
* Error control: RK3 at accuracy 1e-5 (instead of 1e-4) is no better: 1.66 digits on slip-1, and on the skid
  the stick is followed by four spurious short slides (2.65 digits against 3.45).

Coulomb sweep (continuous RK3, k 1e9, dissipation 0 unless said; min digits over the whole second, slip-1 /
skid-1; the skid's stick; wall s of stepping, slip-1 / skid-1, loaded machine; the runs compared with this
suite's hybrid run in double at their own times, the scorer's scales, which ``verify.score`` confirms)::

    default (discrete 1 ms, lagged)                    0.00 / 0.32   0.0109, slides again at 0.050   0.4 / 0.6
    discrete lagged 1e-5                              -0.23 / 1.65   0.0752 (slip-1 never slides)    10 / 8
    stiction 1e-3, accuracy 1e-4 (the rolling best)    1.63 / 3.45   0.0761                          70 / 15
    stiction 1e-3, accuracy 1e-5                       1.66 / 2.65   0.0761, then 4 short slides     54 / 17
    stiction 3e-4, accuracy 1e-4 (best)                1.96 / 3.49   0.0761                         148 / 31

The skid's stick at 0.0761 is where the reference's own slip speed crosses the 0.1 R/s threshold (its stick
is at 0.0765): Drake's continuous plant slides and sticks as the exact motion does.

Measured on the Coulomb cases (``python -m verify engines --case coin-coulomb-slip-1 --case coin-coulomb-skid-1``,
each run in a process of its own on 2 shared cores, scored by ``verify.score`` against the reference files; energy
= max |E - E_ref| / E_ref(0), slip = max | |u| - s_ref | in R/s, z_P = max |contact height|, slides where the
contact's slip speed exceeds 0.1 R/s; the reference slides from 0.0780 to 0.0966 on slip-1, its own slip speed
crossing 0.1 R/s at 0.0793 and 0.0964, and the skid sticks at 0.0765, crossing at 0.0761)::

    case    setting  outcome   min digits (where)        energy   slip    z_P      slides                         wall s
    slip-1  default  fell      0.00 (psi, t = 0.634)    1.6      18      1.2      0.0187-0.0400, 0.0401-         2.0
    slip-1  best     ok        1.96 (phi, t = 0.892)    1.4e-4   0.030   4.2e-6   0.0793-0.0965                  273
    skid-1  default  ok        0.32 (psi, t = 1)        6.5e-2   29      3.7e-2   0-0.0109, 0.0505-              1.1
    skid-1  best     ok        3.49 (thetadot, t = 0.001) 7.0e-5 0.017   1.4e-6   0-0.0761                       62

(wall = simulator set-up and stepping, on a machine loaded by another run: 148 s and 31 s alone; the skid's
fewest digits are the undamped contact's first sink into the plane, 3.97 digits at the end; the creep where
the reference rolls is 4.4e-4 and 3.8e-4 R/s at "best", 1.5 and 1.3 times the stiction tolerance 3e-4.)
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from importlib import metadata
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))  # friction_cases, beside this file

from verify import score  # noqa: E402
from verify.frames import QUATERNION_FORM  # noqa: E402
from verify.scoring import START_TOLERANCE  # noqa: E402
import friction_cases  # noqa: E402

#: What a new user gets: MultibodyPlantConfig() and Simulator() untouched (time_step 1e-3,
#: 'lagged' SAP, hydroelastic_with_fallback -> point contact for these geometries, stiffness
#: from penetration_allowance 1e-3, stiction_tolerance 1e-4).  Only the body and mu are given.
DEFAULT = {"time_step": 1e-3, "discrete_contact_approximation": "lagged",
           "contact_model": "hydroelastic_with_fallback", "penetration_allowance": 1e-3,
           "stiction_tolerance": 1e-4, "point_stiffness": None, "dissipation": None, "relaxation_time": None,
           "mu": 1.0, "disk_half_thickness": 1e-6, "integrator": None, "accuracy": None, "max_step": None,
           "output_dt": 1 / 128}
#: The best found by the sweep below (BEST_SWEEP).
BEST = {**DEFAULT, "time_step": 0.0, "integrator": "runge_kutta3", "accuracy": 1e-4, "point_stiffness": 1e9,
        "dissipation": 0.0, "stiction_tolerance": 1e-3, "mu": 1.0}
SETTINGS = {"default": DEFAULT, "best": BEST}
#: A Coulomb case (coin-coulomb-*): the same defaults; its best is BEST with a tighter stiction tolerance (3e-4:
#: the slip phase and the rolling after it are set by it), from the Coulomb sweep in the docstring.
COULOMB_SETTINGS = {"default": DEFAULT, "best": {**BEST, "stiction_tolerance": 3e-4}}
#: The sweep on disk-standard-1 to t = 1 s (the docstring's table): (changes from DEFAULT, min digits,
#: final digits, energy drift, wall s).  None: the run sank through the plane ('fell').
_C = {"time_step": 0.0, "integrator": "runge_kutta3", "accuracy": 1e-4, "dissipation": 0.0}
SWEEP = [({}, -0.19, 0.00, 5.2e-1, 1.1),
         ({"time_step": 1e-5, "point_stiffness": 1e8, "dissipation": 0.0}, 0.68, 1.63, 3.2e-3, 11.5),
         ({"time_step": 5e-6, "point_stiffness": 1e8, "dissipation": 0.0}, 1.00, 1.94, 1.7e-3, 61.0),
         ({**_C, "point_stiffness": 1e8, "stiction_tolerance": 1e-2}, 1.19, 1.27, 3.7e-3, 7.5),
         ({**_C, "point_stiffness": 1e8, "stiction_tolerance": 3e-3}, 1.71, 1.78, 1.1e-3, 27.7),
         ({**_C, "point_stiffness": 1e9, "stiction_tolerance": 3e-3}, 1.73, 1.79, 1.1e-3, 20.4),
         ({**_C, "point_stiffness": 1e8, "stiction_tolerance": 1e-3}, 2.14, 2.22, 6.2e-4, 57.6),
         ({**_C, "point_stiffness": 1e9, "stiction_tolerance": 1e-3}, 2.20, 2.27, 3.8e-4, 48.5)]


def load_case(case: str) -> dict:
    """The case's record (:func:`friction_cases.load_case`: with ``friction`` and ``velocity``)."""
    return friction_cases.load_case(case)


def with_friction(s: dict, record: dict) -> dict:
    """The setting for this case: a Coulomb case's mu as static and dynamic coefficient of both geometries
    (Drake combines two surfaces' coefficients as 2 mu1 mu2 / (mu1 + mu2): mu and mu give mu), and its
    output every 2^-10 s (to resolve the slip phase and the stick)."""
    mu = friction_cases.friction_of(record)
    return s if mu is None else {**s, "mu": mu, "output_dt": min(s["output_dt"], 2.0 ** -10)}


def start_tolerance(record: dict, setting: dict) -> float:
    """The scorer's start tolerance: its strict default (1e-12) for the ring, which the cylinder is
    exactly; for the disk the cylinder's rim sits ``disk_half_thickness`` off the zero-thickness disk's,
    so C starts h cos(theta) higher than the disk's C -- the model difference, not an engine error,
    allowed for at 4 h and said in the score's verdict."""
    if record["model"]["name"] != "disk":
        return START_TOLERANCE
    return max(START_TOLERANCE, 4 * float(setting["disk_half_thickness"]))


def body_of(record: dict) -> dict:
    """Mass-normalised inertia and the collision cylinder (radius 1, half-height) of the case's body."""
    model = record["model"]["name"]
    p = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    if model == "disk":
        return {"model": model, "I1": p["k"], "I3": 2 * p["k"], "h": None, "params": p}
    if model == "ring":
        return {"model": model, "I1": p["I1"], "I3": p["I3"], "h": p["h"], "params": p}
    raise ValueError(f"the Drake adapter runs the disk and ring (coin) cases, not {model!r}")


def start_of(record: dict, body: dict) -> dict:
    """The case's start in form (b) (verify.frames.euler_to_b), as floats; a skid's CM velocity where given."""
    return friction_cases.start_b(record, body["model"], body["params"])


def build(body: dict, s: dict):
    """(simulator, plant, plant context, rigid body) for the settings ``s``."""
    from pydrake.geometry import AddContactMaterial, Cylinder, HalfSpace, ProximityProperties  # lazy: optional
    from pydrake.multibody.plant import AddMultibodyPlant, CoulombFriction, MultibodyPlantConfig  # lazy: optional
    from pydrake.multibody.tree import SpatialInertia, UnitInertia  # lazy: optional package (pydrake)
    from pydrake.math import RigidTransform  # lazy: optional package (pydrake)
    from pydrake.systems.analysis import Simulator  # lazy: optional package (pydrake)
    from pydrake.systems.framework import DiagramBuilder  # lazy: optional package (pydrake)

    builder = DiagramBuilder()
    config = MultibodyPlantConfig(time_step=s["time_step"], penetration_allowance=s["penetration_allowance"],
                                  stiction_tolerance=s["stiction_tolerance"], contact_model=s["contact_model"],
                                  discrete_contact_approximation=s["discrete_contact_approximation"])
    plant, scene_graph = AddMultibodyPlant(config, builder)
    # m = 1, so the unit inertia is the inertia; about C, symmetry axis the body's z axis
    rigid = plant.AddRigidBody("body", SpatialInertia(1.0, np.zeros(3), UnitInertia(body["I1"], body["I1"], body["I3"])))
    half = body["h"] if body["h"] is not None else s["disk_half_thickness"]
    friction = CoulombFriction(s["mu"], s["mu"])

    def props():
        p = ProximityProperties()
        # both geometries get 2k: point stiffnesses combine in series, k1 k2 / (k1 + k2) = k
        k = None if s["point_stiffness"] is None else 2 * s["point_stiffness"]
        AddContactMaterial(dissipation=s["dissipation"], point_stiffness=k, friction=friction, properties=p)
        if s["relaxation_time"] is not None:
            p.AddProperty("material", "relaxation_time", s["relaxation_time"])
        return p

    # Drake's Cylinder is along its frame's z axis: the body's third axis, as the suite's e3
    plant.RegisterCollisionGeometry(rigid, RigidTransform(), Cylinder(1.0, 2 * half), "rim", props())
    plant.RegisterCollisionGeometry(plant.world_body(), RigidTransform(), HalfSpace(), "plane", props())
    plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, -body["params"]["g"]])
    plant.Finalize()
    diagram = builder.Build()
    sim = Simulator(diagram)
    if s["time_step"] == 0:
        from pydrake.systems.analysis import ApplySimulatorConfig, SimulatorConfig  # lazy: optional package (pydrake)

        cfg = SimulatorConfig()
        if s["integrator"]:
            cfg.integration_scheme = s["integrator"]
        if s["accuracy"]:
            cfg.accuracy = s["accuracy"]
        if s["max_step"]:
            cfg.max_step_size = s["max_step"]
        ApplySimulatorConfig(cfg, sim)
    context = plant.GetMyMutableContextFromRoot(sim.get_mutable_context())
    return sim, plant, context, rigid


def set_start(plant, context, rigid, b0: dict) -> None:
    from pydrake.common.eigen_geometry import Quaternion  # lazy: optional package (pydrake)
    from pydrake.math import RigidTransform, RotationMatrix  # lazy: optional package (pydrake)
    from pydrake.multibody.math import SpatialVelocity  # lazy: optional package (pydrake)

    q = Quaternion(b0["qw"], b0["qx"], b0["qy"], b0["qz"])  # Drake's order is (w, x, y, z), like the suite's
    plant.SetFreeBodyPose(context, rigid, RigidTransform(RotationMatrix(q), [b0["x"], b0["y"], b0["z"]]))
    # SpatialVelocity(w, v): angular first, both in WORLD components (as the suite's wx, wy, wz)
    plant.SetFreeBodySpatialVelocity(context, rigid, SpatialVelocity([b0["wx"], b0["wy"], b0["wz"]],
                                                            [b0["vx"], b0["vy"], b0["vz"]]))


def read_state(plant, context, rigid) -> list:
    """One row of the quaternion form: qw, qx, qy, qz, x, y, z, vx, vy, vz, wx, wy, wz."""
    pose = plant.EvalBodyPoseInWorld(context, rigid)
    V = plant.EvalBodySpatialVelocityInWorld(context, rigid)  # world frame, about C (the body origin)
    q = pose.rotation().ToQuaternion()
    return [q.w(), q.x(), q.y(), q.z(), *pose.translation(), *V.translational(), *V.rotational()]


def check_start(row: list, b0: dict, tol: float = 1e-12) -> None:
    """Fail loudly if the state read back at t = 0 is not the case's start (beyond rounding)."""
    names = QUATERNION_FORM[1:]
    want = np.array([b0[n] for n in names])
    got = np.array(row)
    if np.dot(want[:4], got[:4]) < 0:  # q and -q are one rotation
        got[:4] = -got[:4]
    scale = np.array([1.0] * 7 + [max(1.0, np.abs(want[7:]).max())] * 6)
    err = np.abs(got - want) / scale
    if not np.all(err <= tol):
        bad = {n: (float(g), float(w)) for n, g, w, e in zip(names, got, want, err) if not e <= tol}
        raise RuntimeError(f"Drake's state at t = 0 is not the case's start: {bad}")


def simulate(record: dict, s: dict, t_end: float) -> dict:
    body = body_of(record)
    b0 = start_of(record, body)
    sim, plant, context, rigid = build(body, s)
    set_start(plant, context, rigid, b0)
    sim.Initialize()
    first = read_state(plant, context, rigid)
    check_start(first, b0)
    dt = s["time_step"]
    every = s["output_dt"] if dt == 0 else dt * max(1, round(s["output_dt"] / dt))
    n = int(np.floor(t_end / every + 1e-9))
    times = [k * every for k in range(n + 1)]
    rows = [first]
    for t in times[1:]:
        sim.AdvanceTo(t)
        rows.append(read_state(plant, context, rigid))
        if not np.all(np.isfinite(rows[-1])):
            break
    cols = {"t": np.array(times[:len(rows)])}
    cols.update(zip(QUATERNION_FORM[1:], np.array(rows).T))
    return cols


def outcome_of(cols: dict, body: dict) -> str:
    """'ok', or 'fell' (C at or below the height of a body lying flat, or the rim's plane at the ground)."""
    if not all(np.all(np.isfinite(v)) for v in cols.values()):
        return "error: non-finite state"
    qw, qx, qy = cols["qw"], cols["qx"], cols["qy"]
    n2 = qw ** 2 + qx ** 2 + qy ** 2 + cols["qz"] ** 2
    cos_theta = 1 - 2 * (qx ** 2 + qy ** 2) / n2  # R33: e3's vertical component
    flat = (body["h"] or 0.0) + 0.05
    if np.any(cols["z"] < flat) or np.any(np.abs(cos_theta) > 0.999):
        return "fell"
    return "ok"


def version() -> str:
    return metadata.version("drake")


def run_case(case: str, setting="default", t_end: float | None = None, out: str | None = None) -> dict:
    """Run ``case`` in Drake at ``setting`` ('default', 'best' or a dict over DEFAULT), score it."""
    record = load_case(case)
    name = setting if isinstance(setting, str) else "custom"
    table = COULOMB_SETTINGS if friction_cases.friction_of(record) is not None else SETTINGS
    s = dict(table[setting]) if isinstance(setting, str) else {**table["default"], **setting}
    s = with_friction(s, record)
    t_end = float(record["t_end"]) if t_end is None else min(float(t_end), float(record["t_end"]))
    rec = {"engine": "Drake", "version": version(), "case": case, "setting": name, "parameters": s, "t_end": t_end}
    t0 = time.perf_counter()
    try:
        cols = simulate(record, s, t_end)
    except Exception as exc:  # noqa: BLE001 -- reported, not hidden
        rec.update(wall_s=time.perf_counter() - t0, score=None, outcome=f"error: {exc}")
        return rec
    rec["wall_s"] = round(time.perf_counter() - t0, 3)
    rec["outcome"] = outcome_of(cols, body_of(record))
    rec["_columns"] = cols  # not JSON: the run itself
    if friction_cases.friction_of(record) is not None:  # where the run slides and sticks, beside the reference's switches
        rec["friction"] = friction_cases.friction_record(cols, record)
    if out:
        write_csv(cols, out)
    try:
        sc = score(cols, case, start_tolerance=start_tolerance(record, s))
        rec["score"] = sc.to_record()
        rec["table"] = sc.table()
    except Exception as exc:  # noqa: BLE001
        rec["score"] = None
        rec["outcome"] = f"error: scoring: {exc}"
    rec["t_last"] = float(cols["t"][-1])
    return rec


def write_csv(cols: dict, path: str) -> None:
    names = list(QUATERNION_FORM)
    data = np.column_stack([cols[n] for n in names])
    np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.17g")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--setting", default="best", choices=sorted(SETTINGS))
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--out", default=None, help="write the run as CSV (quaternion form)")
    ap.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE", help="override a setting (JSON value)")
    args = ap.parse_args()
    setting = args.setting
    if args.set:
        table = COULOMB_SETTINGS if friction_cases.friction_of(load_case(args.case)) is not None else SETTINGS
        setting = {**table[args.setting], **{k: json.loads(v) for k, v in (a.split("=", 1) for a in args.set)}}
    rec = run_case(args.case, setting, args.t_end, args.out)
    print(f"Drake {rec['version']}, {rec['case']}, setting {rec['setting']}: outcome {rec['outcome']}, "
          f"wall {rec['wall_s']} s")
    print({k: v for k, v in rec["parameters"].items() if v is not None})
    if rec.get("table"):
        print(rec["table"])
        sc = rec["score"]
        print(json.dumps({"min_digits": sc["min_digits"], "final_digits_min": min(c["final_digits"] for c in
                          sc["components"].values()), "energy": sc["energy_rel_drift"],
                          "height": sc["contact_height"], "velocity": sc["contact_velocity"]}))


if __name__ == "__main__":
    main()

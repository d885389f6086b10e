"""The reference cases of bodies rolling on a plane run in Exudyn, scored by ``verify.score``.

Exudyn 1.13.6 (``pip install exudyn``).  ``run_case(case, setting, t_end)`` sets the case up with an
ideal rolling-disc joint (``ObjectJointRollingDisc``), checks the start Exudyn reports against the
case, runs, scores the run in form (b) (rotation matrix) and returns a JSON-ready record.  Cases:
``disk-*`` (k = 1/4 disk, k = 1/2 hoop), ``ring-*`` and ``coin-*`` (the coin); the Coulomb cases
``coin-coulomb-*`` on the penalty connector instead (its section at the end).  Command line::

    python examples/engines/exudyn_adapter.py --case disk-standard-1 --setting best --out run.csv

Mapping (verify.frames; replaces the never-run examples/exudyn_disk.py)
-------------------------------------------------------------------------
* Units: R = 1, m = 1, g = 980 (cm/s^2 with R = 1 cm), time in s: Exudyn has no units, gravity
  [0, 0, -980] is all it needs.  Z up, the plane z = 0 (the joint's ``planeNormal=[0,0,1]`` on ground).
* Body: ``RigidBodyInertia(mass=1, inertiaTensor=diag(I1, I1, I3), inertiaTensorAtCOM=True)`` with the
  symmetry axis the body's third axis (``discAxis=[0,0,1]``; the joint's default is [1,0,0]).  The thin
  disk I1 = k, I3 = 2k; the ring's I1, I3, h from the case.  No ``InertiaCylinder``: its density and
  length would have to be tuned to give the case's inertia and it is not needed.
* Orientation: Exudyn's rotation matrix (``OutputVariableType.RotationMatrix``, 9 values row-major)
  maps body to global components, the same R = Rz(phi) Rx(theta) Rz(psi) as the suite.
* Angular velocity: ``CreateRigidBody(initialAngularVelocity=...)`` and ``OutputVariableType.
  AngularVelocity`` are GLOBAL components (``AngularVelocityLocal`` is the body frame): the form
  (b) columns wx, wy, wz, no conversion.
* Start: ``verify.frames.euler_to_b`` gives R, C and v_C (rolling) and omega; after ``Assemble``
  the state Exudyn reports (``GetObjectOutputBody``, initial configuration) and the first sensor
  row must equal it to 1e-12 relative, or ``run_case`` fails loudly.  Measured: 2.2e-16.
* Coin: the joint's disc centre is a body marker.  For the ring, ``MarkerBodyRigid(localPosition=
  [0, 0, -h])``: a disc of radius 1 centred half a thickness below C rolls on its rim, which is
  exactly r_P = -e2 - h e3 (the scorer's contact height at best settings: 2e-9).  The joint's
  docstring says the body's reference point must be the disc centre; the offset marker works.
* Output: body sensors stored in memory (``storeInternal=True, writeToFile=False``) every grid
  step of the case (so the scorer compares with the stored grid, no re-integration); the
  default setting keeps Exudyn's sensor period 0.01 s (the scorer re-integrates at those times).

Pitfalls (what is silently wrong at defaults)
---------------------------------------------
1. The default step: ``SimulationSettings()`` has numberOfSteps = 100 for endTime = 1, i.e. dt = 0.01
   (kept as dt for longer runs).  The solver is second order and the disk's rates reach 266 s^-1:
   at dt = 0.01 the disk of disk-standard-1 has no correct digit (-0.6), energy off by 66 %,
   and the hoop (hoop-general-10) passes through flat (theta >= pi/2 at t = 1.69 s, up to 2.76
   rad: the ideal joint keeps the disc on the plane upside down; outcome "fell").  No warning.
2. Default numerical damping: generalized-alpha's spectralRadius = 0.9 (dissipative); 0.5 costs a
   digit at dt = 2^-10.  At small dt it no longer matters (rho = 0.9 and 1 within 0.3 digits).
3. The normal (height) constraint of ObjectJointRollingDisc holds the contact point's VELOCITY,
   not its height: the height drifts with the integration error (1.2e-1 R at dt = 0.01, 1.2e-3 at
   2^-10, 1.8e-8 at 2^-18).  The contact point's velocity is held to Newton tolerance.  The disc
   may also lift off (the joint's own note): nothing projects back onto the plane.
4. Explicit solvers (RK44, DOPRI5, ...) are refused with this joint ("explicit integrator detected
   node 0 which contains algebraic variables" with Euler parameters; "object 2 which contains
   constraints that cannot be solved" with Rxyz or rotation-vector nodes).  Only GeneralizedAlpha
   and TrapezoidalIndex2 run.  ``useIndex2Constraints=True`` needs ``useNewmark=True`` (else
   ExudynValueError); index 2 and TrapezoidalIndex2 leave a contact velocity of 1e-2 at dt = 2^-10.
5. Files: by default SolveDynamic writes ``solution/coordinatesSolution.txt`` (and sensor files)
   into the working directory: ``solution.file.write = False``, sensors ``writeToFile=False``.
   The old names (``solutionSettings.writeSolutionToFile``, ``sensorsWritePeriod``) still work but
   warn; ``sensorsWritingPeriod`` (the old script) does not exist.
6. A failed solve prints a banner and raises (ModelError, ExudynValueError); the sensors then hold
   no rows.  Newton at relativeTolerance 1e-12 fails at dt = 2^-20 (rounding floor): the record
   says "error: solver stopped at t = ...".
7. Accuracy floor: about 6 digits on disk-standard-1 (dt = 2^-18); halving dt again loses digits
   (5.5 at 2^-20 with the default Newton, 4.4 at 2^-19 with tolerance 1e-10): roundoff in the
   index-3 solve with tiny steps.

Sweep (disk-standard-1, 0..1 s, 33 grid times, this machine, wall = SolveDynamic only)
--------------------------------------------------------------------------------------
GeneralizedAlpha, Euler parameters, modified Newton 1e-8, rho = 1 unless noted::

    dt      variant                          min dig  final  energy  z_P     wall s
    0.01    default (rho 0.9, 0.01-s output)  -0.57   -0.39  6.6e-1  1.2e-1  0.013
    2^-10                                      1.24    1.47  2.9e-2  1.2e-3  0.015
    2^-12                                      2.45    2.62  2.1e-3  7.5e-5  0.05
    2^-14                                      3.66    3.82  1.3e-4  4.7e-6  0.20
    2^-16                                      4.86    5.02  5.3e-6  2.9e-7  0.79
    2^-18                                      5.73    6.22  3.8e-6  1.8e-8  3.7
    2^-20                                      5.51    6.02  4.8e-6  1.2e-9  13.4
    2^-18   rho 0.9                            6.04    6.21  1.5e-7  1.9e-8  4.2
    2^-18   Rxyz, full Newton 1e-12 (best)     6.09    6.26  1.5e-7  1.7e-8  5.2
    2^-17   Rxyz, full Newton 1e-12            5.48    5.65  5.9e-7  6.8e-8  2.4
    2^-20   full Newton 1e-12                  solver stopped at t = 0.5625
    2^-16 Rxyz / rotation vector / TrapezoidalIndex2: 4.88 / 4.90 / 4.86 (all second order)

The best setting (``BEST``): dt = 2^-18, rho = 1, Rxyz nodes, full Newton, tolerances 1e-12/1e-14.

Measured (``python examples/engines/exudyn_adapter.py --case C --setting S [--t-end T] --json``)::

    case              setting  t     outcome  min dig  final  energy   z_P      wall s
    disk-standard-1   default  1     ok       -0.57    -0.39  6.6e-1   1.2e-1   0.010
    disk-standard-1   best     1     ok        6.09     6.26  1.5e-7   1.7e-8   6.4
    hoop-general-10   default  10    fell     -1.18    -1.15  4.3      1.5e-1   0.09
    hoop-general-10   best     2     ok        6.06     6.06  9.8e-9   2.2e-9   11.9
    ring-standard-10  default  10    ok        0.54     0.54  1.3e-3   6.3e-4   0.028
    ring-standard-10  best     2     ok        8.00     8.00  1.5e-10  1.1e-10  13.6

(final = the fewest final digits of any component; z_P = max |contact height|; runs that stop
before t_end are scored on [0, t] by ``verify.score``.)

Coulomb cases (coin-coulomb-slip-1: mu = 0.87, rolls, slides from 0.0780 to 0.0966, rolls; coin-coulomb-skid-1:
mu = 0.3, starts sliding, sticks at 0.0765; ``friction_cases``)
---------------------------------------------------------------------------------------------------------
* The ideal ObjectJointRollingDisc cannot slip: a Coulomb case runs on ``ObjectConnectorRollingDiscPenalty``
  (with its NodeGenericData of 3 data coordinates, the discontinuous iteration's memory), the same disc
  marker C - h e3.  Its forces (the item's documentation, ``exudyn.itemInterface`` docstring and
  docs/RST/items/ObjectConnectorRollingDiscPenalty.rst in Exudyn's repository): a normal penalty
  f_n = (k_c p_C + d_c v_C) . n on the contact point, and friction f_t = mu phi(|v_t|, v_mu) f_n e_t with
  e_t the slip's direction, mu = diag(mu_x, mu_y) in the joint's lateral/forward axes: ``dryFriction =
  [mu, mu]`` is isotropic Coulomb friction.  There is no second surface and no combination rule: the pair's
  mu is the connector's.  phi regularises: (2 - v/v_mu) v/v_mu below v_mu (quadratic), or v/v_mu with
  ``useLinearProportionalZone`` ("performs better in implicit time integration as the Jacobian has a
  constant tangent in the sticking case"), v_mu = ``dryFrictionProportionalZone``: a rolling contact creeps.
* Its stiffness and damping have no usable default (0: no contact at all).  "default" takes the example of
  ``MainSystem.CreateRollingDiscPenalty``'s docstring, contactStiffness 1e5 and contactDamping 2e3 (here
  a static sink of g/k = 1e-2 R, overdamped), the connector's own dryFrictionProportionalZone 0 (Coulomb
  unregularised, resolved by the discontinuous iteration) and SimulationSettings() as DEFAULT: the
  skid never sticks and slip-1 slides from the start (0 digits).  v_mu = 0 chatters even at dt = 1e-4:
  88 slides after the skid's stick (k 1e6).
* "best" (COULOMB_BEST): k 1e8, d 2e4 (critical for the unit mass: sink 1e-5 R), linear zone v_mu = 1e-5
  R/s, generalized-alpha rho 0.9, full Newton, dt 2^-21, sensors every 2^-10 s.  The digits follow v_mu and
  the step together (a smaller zone needs a smaller step and full Newton: v_mu = 1e-4 at 2^-20 with the
  quadratic zone and modified Newton stops at t = 1 ms, "SolveDynamic terminated"), about 0.15 digits a
  halving of the step at v_mu = 1e-5; rho = 1 instead of 0.9 changed nothing (0.67 both, slip-1 at 2^-18).
* Explicit solvers: refused with Euler-parameter nodes ("explicit integrator detected node 0 which contains
  algebraic variables"); with Rxyz nodes RK44 at 2^-21 gives the generalized-alpha's digits (4.74 against
  4.72 on the skid to 0.125 s) at 4 times the wall, and DOPRI5's step control stalls at the stick (warning
  "reached minStepSize", 63 s for 0.125 s).

Coulomb sweep (min digits over the whole second, skid-1 / slip-1; wall s of SolveDynamic, skid / slip; the
first rows compared with this suite's hybrid run in double at the run's times, the scorer's scales; those
marked * scored by ``verify.score`` against the reference files)::

    k      d      v_mu  zone   dt     Newton    skid / slip    wall
    1e5    2e3    0     quad   0.01   mod.      0.05 / 0.01    0.02  (default: never sticks / slides from 0)
    1e6    2e3    1e-2  quad   2^-14  mod.      1.86 / 0.00          (slip-1: 28 slides)
    1e7    6.3e3  1e-2  quad   2^-16  mod.      2.35 / 0.47
    1e8    2e4    1e-2  quad   2^-16  mod.      2.42 / 0.58
    1e8    2e4    1e-3  quad   2^-16  mod.      2.25 / 0.04
    1e8    2e4    1e-3  quad   2^-18  mod.      3.27 / 0.67
    1e8    2e4    1e-3  lin    2^-18  mod.         - / 1.28
    1e8    2e4    1e-3  quad   2^-20  full      3.38 / 1.60 *
    1e8    2e4    1e-3  lin    2^-20  mod.      3.27 / 1.51 *    5 / 5
    1e9    6.3e4  1e-4  lin    2^-20  full         - / 1.98
    1e8    2e4    1e-4  lin    2^-20  full      3.80 / 1.87 *   16 / 27
    1e8    2e4    1e-4  lin    2^-21  full      3.86 / 2.05 *   41 / 40
    1e7    6.3e3  1e-5  lin    2^-21  full      3.08 / 1.07 *   35 / 34
    1e8    2e4    1e-5  lin    2^-21  full      4.00 / 2.16 *   31 / 47   <- best
    1e8    2e4    1e-5  lin    2^-22  full      4.05 / 2.30 *  204 / 231  (loaded machine)

Slip-1's fewest digits are phi near t = 0.89 s (the fast low-tilt phase, as for the rolling coin, where
the creep accumulates); the skid's phidot near 0.97 s.  Both runs slide where the reference does: slip-1
from 0.0793 to 0.0965 at the 0.1 R/s threshold (the reference's own crossings 0.0793 and 0.0964), the
skid sticks at 0.0761 (the reference's crossing 0.0761, its stick 0.0765).

Measured on the Coulomb cases (``python -m verify engines --case coin-coulomb-slip-1 --case coin-coulomb-skid-1``,
each run in a process of its own on 2 shared cores, scored by ``verify.score`` against the reference files; energy
= max |E - E_ref| / E_ref(0), slip = max | |u| - s_ref | in R/s, z_P = max |contact height|, slides where the
contact's slip speed exceeds 0.1 R/s; the reference slides from 0.0780 to 0.0966 on slip-1, its own slip speed
crossing 0.1 R/s at 0.0793 and 0.0964, and the skid sticks at 0.0765, crossing at 0.0761)::

    case    setting  outcome   min digits (where)        energy   slip    z_P      slides                         wall s
    slip-1  default  ok        0.01 (phi, t = 0.69)     0.46     18      2.0e-2   0.0001- (never sticks)         0.05
    slip-1  best     ok        2.16 (phi, t = 0.892)    1.5e-4   7.8e-3  4.2e-5   0.0793-0.0965                  75
    skid-1  default  ok        0.05 (psi, t = 1)        0.11     11      1.2e-2   0- (never sticks)              0.04
    skid-1  best     ok        4.00 (phidot, t = 0.966) 6.5e-6   4.2e-4  1.4e-5   0-0.0761                       47

(wall = SolveDynamic, on a loaded machine; start read back to 2e-16 and 3e-16; the creep where the reference
rolls is 5.1e-4 R/s on slip-1, 9.2e-6 on the skid at "best".)
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
sys.path.insert(0, str(Path(__file__).resolve().parent))  # friction_cases, beside this file

from verify import score  # noqa: E402
from verify.frames import MATRIX, MATRIX_ENTRIES  # noqa: E402
import friction_cases  # noqa: E402

#: What a new user gets (SimulationSettings() untouched but for endTime): generalized-alpha with
#: spectral radius 0.9 (numerical damping), the default 100 steps per default endTime 1, i.e. dt = 0.01,
#: modified Newton with relative tolerance 1e-8, index-3 constraints, Euler-parameter nodes, and
#: sensors written every 0.01 s.
DEFAULT = {"dt": 0.01, "solver": "GeneralizedAlpha", "spectralRadius": 0.9, "index2": False,
           "nodeType": "RotationEulerParameters", "newtonRelTol": 1e-8, "newtonAbsTol": 1e-10,
           "modifiedNewton": True, "newmark": False, "output": 0.01}
#: The best setting of the sweep in the module's docstring.
BEST = dict(DEFAULT, dt=2.0 ** -18, spectralRadius=1.0, nodeType="RotationRxyz", modifiedNewton=False,
            newtonRelTol=1e-12, newtonAbsTol=1e-14, output="grid")
SETTINGS = {"default": DEFAULT, "best": BEST}
#: A Coulomb case (coin-coulomb-*) runs on the penalty connector ObjectConnectorRollingDiscPenalty (the ideal
#: joint cannot slip).  Its contact stiffness and damping have no usable default (0: no contact at all):
#: "default" takes the values of the example in the docstring of MainSystem.CreateRollingDiscPenalty
#: (contactStiffness 1e5, contactDamping 2e3), the connector's own defaults otherwise (dryFrictionProportionalZone
#: 0: unregularised Coulomb friction resolved by the discontinuous iteration, the quadratic zone), and
#: SimulationSettings() as DEFAULT.
COULOMB_DEFAULT = dict(DEFAULT, contactStiffness=1e5, contactDamping=2e3, proportionalZone=0.0, linearZone=False)
#: The best of the Coulomb sweep in the module's docstring.
COULOMB_BEST = dict(COULOMB_DEFAULT, dt=2.0 ** -21, spectralRadius=0.9, contactStiffness=1e8, contactDamping=2e4,
                    proportionalZone=1e-5, linearZone=True, modifiedNewton=False, output=2.0 ** -10)
COULOMB_SETTINGS = {"default": COULOMB_DEFAULT, "best": COULOMB_BEST}


def load_case(case: str) -> dict:
    """The case's record (:func:`friction_cases.load_case`: with ``friction`` and ``velocity``)."""
    return friction_cases.load_case(case)


def body_of(record: dict) -> dict:
    """Mass 1, radius 1, I1, I3 about C and h, the offset of the rolling rim's plane from C along -e3."""
    model = record["model"]["name"]
    p = {k: float(v["decimal"]) for k, v in record["model"]["parameters"].items()}
    if model == "disk":  # thin disk (k = 1/4) or hoop (k = 1/2): I1 = k, I3 = 2k, contact r_P = -e2
        return {"model": model, "I1": p["k"], "I3": 2 * p["k"], "h": 0.0, "g": p["g"], "params": p}
    if model == "ring":  # coin: r_P = -e2 - h e3, the rim edge half a thickness below the mid-plane
        return {"model": model, "I1": p["I1"], "I3": p["I3"], "h": p["h"], "g": p["g"], "params": p}
    raise ValueError(f"case {record['name']}: model {model!r} has no Exudyn set-up here (disk, hoop and ring only)")


def start_b(record: dict, body: dict) -> dict:
    """The case's start in form (b) (floats), from the suite's own tested conversion; a skid's CM velocity
    where the case gives one."""
    return friction_cases.start_b(record, body["model"], body["params"])


def build(record: dict, setting: dict):
    """(mbs, body, sensors, b0): the system assembled with the case's start."""
    import exudyn as exu  # lazy: optional package (exudyn)
    from exudyn.utilities import (MarkerBodyRigid, NodeGenericData, ObjectConnectorRollingDiscPenalty, ObjectGround,
                                  ObjectJointRollingDisc, RigidBodyInertia, SensorBody)  # lazy: optional

    body = body_of(record)
    b0 = start_b(record, body)
    R0 = np.array([[b0[f"R{i}{j}"] for j in (1, 2, 3)] for i in (1, 2, 3)])
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    inertia = RigidBodyInertia(mass=1.0, inertiaTensor=np.diag([body["I1"], body["I1"], body["I3"]]),
                               com=[0, 0, 0], inertiaTensorAtCOM=True)
    oBody = mbs.CreateRigidBody(inertia=inertia, referencePosition=[b0["x"], b0["y"], b0["z"]],
                                referenceRotationMatrix=R0, initialVelocity=[b0["vx"], b0["vy"], b0["vz"]],
                                initialAngularVelocity=[b0["wx"], b0["wy"], b0["wz"]],  # global components
                                gravity=[0, 0, -body["g"]], nodeType=getattr(exu.NodeType, setting["nodeType"]))
    mGround = mbs.AddMarker(MarkerBodyRigid(bodyNumber=mbs.AddObject(ObjectGround())))
    # the disc's centre is the marker: C for the disk, C - h e3 (the rim plane) for the coin
    mDisc = mbs.AddMarker(MarkerBodyRigid(bodyNumber=oBody, localPosition=[0, 0, -body["h"]]))
    mu = friction_cases.friction_of(record)
    if mu is None:  # rolling without slipping: the ideal joint
        mbs.AddObject(ObjectJointRollingDisc(markerNumbers=[mGround, mDisc], constrainedAxes=[1, 1, 1],
                                             discRadius=1.0, discAxis=[0, 0, 1], planeNormal=[0, 0, 1]))
    else:  # Coulomb: the penalty connector, its friction f_t = mu phi(|v_t|, v_mu) f_n e_t (both axes mu: isotropic)
        nData = mbs.AddNode(NodeGenericData(initialCoordinates=[0, 0, 0], numberOfDataCoordinates=3))
        mbs.AddObject(ObjectConnectorRollingDiscPenalty(
            markerNumbers=[mGround, mDisc], nodeNumber=nData, discRadius=1.0, discAxis=[0, 0, 1], planeNormal=[0, 0, 1],
            contactStiffness=setting["contactStiffness"], contactDamping=setting["contactDamping"], dryFriction=[mu, mu],
            dryFrictionProportionalZone=setting["proportionalZone"], useLinearProportionalZone=setting["linearZone"]))
    kinds = {"p": exu.OutputVariableType.Position, "v": exu.OutputVariableType.Velocity,
             "w": exu.OutputVariableType.AngularVelocity, "R": exu.OutputVariableType.RotationMatrix}
    sensors = {k: mbs.AddSensor(SensorBody(bodyNumber=oBody, storeInternal=True, writeToFile=False,
                                           outputVariableType=v)) for k, v in kinds.items()}
    mbs.Assemble()
    return mbs, oBody, sensors, b0


def read_back(mbs, oBody, configuration=None) -> dict:
    """The body's state in form (b) columns (no t) as Exudyn reports it."""
    import exudyn as exu  # lazy: optional package (exudyn)

    conf = configuration or exu.ConfigurationType.Initial
    get = lambda kind: np.asarray(mbs.GetObjectOutputBody(oBody, kind, localPosition=[0, 0, 0], configuration=conf))
    out = dict(zip(("x", "y", "z"), get(exu.OutputVariableType.Position)))
    out.update(zip(("vx", "vy", "vz"), get(exu.OutputVariableType.Velocity)))
    out.update(zip(("wx", "wy", "wz"), get(exu.OutputVariableType.AngularVelocity)))
    out.update(zip(MATRIX_ENTRIES, get(exu.OutputVariableType.RotationMatrix).ravel()))  # row-major
    return out


def check_start(got: dict, b0: dict, what: str, tol: float = 1e-12) -> float:
    """Largest |Exudyn's start - the case's| over form (b)'s columns (relative to max(1, |value|)); raises beyond tol."""
    errs = {c: abs(got[c] - b0[c]) / max(1.0, abs(b0[c])) for c in MATRIX[1:]}
    worst = max(errs, key=errs.get)
    if not errs[worst] <= tol:
        raise RuntimeError(f"{what}: Exudyn's start differs from the case's: {worst} = {got[worst]!r}, "
                           f"the case's {b0[worst]!r} (relative {errs[worst]:.1e} > {tol:g})")
    return errs[worst]


def simulation_settings(setting: dict, t_end: float, grid_step: float):
    import exudyn as exu  # lazy: optional package (exudyn)

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = t_end
    ti.numberOfSteps = int(round(t_end / setting["dt"]))
    ti.verboseMode = 0
    ti.generalizedAlpha.spectralRadius = setting["spectralRadius"]
    ti.generalizedAlpha.useIndex2Constraints = setting["index2"]
    ti.generalizedAlpha.useNewmark = setting["newmark"]
    ti.newton.relativeTolerance = setting["newtonRelTol"]
    ti.newton.absoluteTolerance = setting["newtonAbsTol"]
    ti.newton.useModifiedNewton = setting["modifiedNewton"]
    s.solution.file.write = False  # else a solution/ folder appears in the working directory
    s.solution.sensors.writePeriod = grid_step if setting["output"] == "grid" else setting["output"]
    return s


def run_columns(record: dict, setting: dict, t_end: float) -> tuple:
    """(form (b) columns of the run, wall seconds, start error, solver's success flag)."""
    import exudyn as exu  # lazy: optional package (exudyn)

    mbs, oBody, sensors, b0 = build(record, setting)
    err0 = check_start(read_back(mbs, oBody), b0, "after Assemble")
    grid = [float(v) for v in record["grid"]]
    s = simulation_settings(setting, t_end, grid[1] - grid[0])
    solver = getattr(exu.DynamicSolverType, setting["solver"])
    wall = time.perf_counter()
    try:
        ok = mbs.SolveDynamic(s, solverType=solver)
    except Exception as err:  # Exudyn raises on a failed solve (and refuses explicit solvers with this joint)
        ok = f"{type(err).__name__}: " + " ".join(str(err).split())[:200]
    wall = time.perf_counter() - wall
    data = {k: np.asarray(mbs.GetSensorStoredData(v)) for k, v in sensors.items()}
    if data["p"].ndim != 2 or len(data["p"]) < 2:  # nothing stored: the solver refused or died at once
        raise RuntimeError(f"no output ({ok})")
    run = {"t": data["p"][:, 0]}
    run.update(zip(("x", "y", "z"), data["p"][:, 1:4].T))
    run.update(zip(("vx", "vy", "vz"), data["v"][:, 1:4].T))
    run.update(zip(("wx", "wy", "wz"), data["w"][:, 1:4].T))  # AngularVelocity: global components
    run.update(zip(MATRIX_ENTRIES, data["R"][:, 1:10].T))  # body -> global, row-major
    if len(run["t"]):
        err0 = max(err0, check_start({c: run[c][0] for c in MATRIX[1:]}, b0, "first sensor row"))
    return run, wall, err0, ok


def resolve(setting, record: dict | None = None) -> tuple:
    """(name, setting dict): a Coulomb case's from COULOMB_SETTINGS (a dict overrides COULOMB_DEFAULT's keys)."""
    table = COULOMB_SETTINGS if record is not None and friction_cases.friction_of(record) is not None else SETTINGS
    if isinstance(setting, dict):
        return "custom", dict(table["default"], **setting)
    return setting, dict(table[setting])


def run_case(case: str, setting="default", t_end=None, out=None) -> dict:
    """Run ``case`` in Exudyn at ``setting`` ('default', 'best' or a dict overriding DEFAULT's keys) up to
    ``t_end`` (default the case's), score it and return a JSON-ready record (the columns under '_run')."""
    import exudyn as exu  # lazy: optional package (exudyn)

    record = load_case(case)
    name, st = resolve(setting, record)
    t_end = float(record["t_end"]) if t_end is None else float(t_end)
    result = {"engine": "Exudyn", "version": exu.__version__, "case": case, "setting": name, "parameters": st,
              "t_end": t_end, "wall_s": None, "score": None, "outcome": None}
    try:
        run, wall, err0, ok = run_columns(record, st, t_end)
    except Exception as err:
        return dict(result, outcome=f"error: {type(err).__name__}: {err}")
    result.update(wall_s=round(wall, 4), start_error=err0)
    t = run["t"]
    if ok is not True:
        result["outcome"] = f"error: solver stopped at t = {t[-1] if len(t) else 0:g} ({ok})"
    elif t[-1] < t_end - 1e-9:
        result["outcome"] = f"error: output stops at t = {t[-1]:g}"
    keep = t <= float(record["t_end"])
    run = {k: v[keep] for k, v in run.items()}
    theta = np.arctan2(np.hypot(run["R13"], run["R23"]), run["R33"])
    if result["outcome"] is None:
        result["outcome"] = "fell" if np.any(theta >= math.pi / 2) else "ok"
    if out:
        write_csv(run, out)
    if friction_cases.friction_of(record) is not None:  # where the run slides and sticks, beside the reference's switches
        result["friction"] = friction_cases.friction_record(run, record)
    try:
        sc = score(run, case)
        result["score"] = sc.to_record()
        result["_table"] = sc.table()
    except Exception as err:
        result["score"] = None
        if result["outcome"] == "ok":
            result["outcome"] = f"error: not scorable: {err}"
    result["_run"] = run
    return result


def write_csv(run: dict, path) -> None:
    cols = MATRIX
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for j in range(len(run["t"])):
            f.write(",".join(repr(float(run[c][j])) for c in cols) + "\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--setting", default="best", help="default, best, or a JSON object of DEFAULT's keys")
    ap.add_argument("--t-end", type=float, default=None)
    ap.add_argument("--out", default=None, help="CSV file of the run (form (b), rotation matrix)")
    ap.add_argument("--json", action="store_true", help="print the record as JSON")
    args = ap.parse_args()
    setting = json.loads(args.setting) if args.setting.startswith("{") else args.setting
    rec = run_case(args.case, setting, args.t_end, args.out)
    table = rec.pop("_table", None)
    rec.pop("_run", None)
    if args.json:
        print(json.dumps(rec, indent=1))
    else:
        print(f"Exudyn {rec['version']}, case {rec['case']}, setting {rec['setting']} {rec['parameters']}")
        print(f"outcome {rec['outcome']}, wall {rec['wall_s']} s, start read back to {rec.get('start_error', float('nan')):.1e}")
        print(table or "(not scored)")


if __name__ == "__main__":
    main()

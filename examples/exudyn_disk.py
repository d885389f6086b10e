"""A worked comparison: the reference disk case set up in Exudyn, scored by ``verify.score``.

NOT RUN in this repository's environment: Exudyn is not installable there (no wheel in the
local package index, no network), so no number from this script appears anywhere in the
repository.  It is written against Exudyn's documented Python API (``mbs.CreateRigidBody``,
``ObjectJointRollingDisc``, body sensors); check it against your Exudyn version.

Mapping of conventions (verify.frames, models/symbols.py):

* Units: lengths in R (R = 1), mass m = 1, g = 980 (g/R in s^-2, R = 1 cm), time in s.
  The thin disk of the case has I1 = k m R^2, I3 = 2k m R^2 with k = 1/4 (a uniform disk).
* Frame: Exudyn's ground frame with Z up and the plane z = 0, gravity (0, 0, -g).
* Orientation: the body frame's third axis is the disk's symmetry axis e3, and
  R = Rz(phi) Rx(theta) Rz(psi) maps body to global components (Exudyn's rotation matrix
  A is the same map), so the rolling disc joint gets ``discAxis = [0, 0, 1]``.
* Start: C at (x0, y0, sin theta0) (the contact point is C - e2, at z = 0); the initial
  angular velocity in global components is omega = thetadot e1 + phidot sin(theta) e2 +
  (phidot cos(theta) + psidot) e3; C's velocity is -omega x r_P with r_P = -e2 (no slip).
  Both come from ``verify.frames.euler_to_b`` so that the mapping is the tested one.
* Output: the run is written in form (b), ``t, R11..R33, x, y, z, vx, vy, vz, wx, wy, wz``
  (global angular velocity), and scored; R is read back to (theta, phi, psi) exactly and
  phi, psi are compared modulo 2 pi.

Usage (with Exudyn installed, e.g. ``pip install exudyn``)::

    python examples/exudyn_disk.py [--case disk-standard-1] [--steps 100000]
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from models.symbols import STATE_NAMES  # noqa: E402
from verify import score  # noqa: E402
from verify.reference.store import DIRECTORY  # noqa: E402
from verify.frames import MATRIX_ENTRIES, euler_to_b  # noqa: E402


def run_exudyn(record: dict, steps: int, solver: str) -> dict:
    import exudyn as exu
    from exudyn.itemInterface import MarkerBodyRigid, MarkerNodeRigid, ObjectGround, ObjectJointRollingDisc  # noqa
    from exudyn.utilities import InertiaCylinder, SensorBody

    k = float(record["model"]["parameters"]["k"]["decimal"])
    g = float(record["model"]["parameters"]["g"]["decimal"])
    start = {n: np.array([float(record["initial_state"][n])]) for n in STATE_NAMES}
    b0 = {c: float(v[0]) for c, v in euler_to_b("disk", start, {"k": k, "g": g}).items()}
    R0 = np.array([[b0[f"R{i}{j}"] for j in (1, 2, 3)] for i in (1, 2, 3)])

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    # a thin disk of mass 1, radius 1: an almost flat cylinder whose inertia is then set exactly
    inertia = InertiaCylinder(density=1 / (np.pi * 1e-6), length=1e-6, outerRadius=1.0, axis=2)
    inertia = inertia.Translated([0, 0, 0])
    inertia.inertiaTensor = np.diag([k, k, 2 * k])  # I1 = k, I3 = 2k about C (m = R = 1)
    body = mbs.CreateRigidBody(inertia=inertia, referencePosition=[b0["x"], b0["y"], b0["z"]],
                               referenceRotationMatrix=R0, initialVelocity=[b0["vx"], b0["vy"], b0["vz"]],
                               initialAngularVelocity=[b0["wx"], b0["wy"], b0["wz"]], gravity=[0, 0, -g])
    ground = mbs.AddObject(ObjectGround())
    m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))
    m_body = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
    mbs.AddObject(ObjectJointRollingDisc(markerNumbers=[m_ground, m_body], constrainedAxes=[1, 1, 1],
                                         discRadius=1.0, discAxis=[0, 0, 1]))
    sensors = {what: mbs.AddSensor(SensorBody(bodyNumber=body, storeInternal=True, outputVariableType=kind))
               for what, kind in (("position", exu.OutputVariableType.Position),
                                  ("velocity", exu.OutputVariableType.Velocity),
                                  ("omega", exu.OutputVariableType.AngularVelocity),
                                  ("rotation", exu.OutputVariableType.RotationMatrix))}
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = float(record["t_end"])
    settings.timeIntegration.numberOfSteps = steps
    settings.solutionSettings.sensorsWritingPeriod = float(record["t_end"]) / (len(record["grid"]) - 1)
    if solver == "generalized-alpha":
        settings.timeIntegration.generalizedAlpha.spectralRadius = 1.0
        exu.SolveDynamic(mbs, settings)
    else:
        exu.SolveDynamic(mbs, settings, solverType=exu.DynamicSolverType.RK44)
    data = {w: mbs.GetSensorStoredData(s) for w, s in sensors.items()}
    t = data["position"][:, 0]
    run = {"t": t}
    run.update(zip(("x", "y", "z"), data["position"][:, 1:4].T))
    run.update(zip(("vx", "vy", "vz"), data["velocity"][:, 1:4].T))
    run.update(zip(("wx", "wy", "wz"), data["omega"][:, 1:4].T))
    run.update(zip(MATRIX_ENTRIES, data["rotation"][:, 1:10].T))  # row-major A11, A12, ..., A33
    return run


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="disk-standard-1")
    ap.add_argument("--steps", type=int, nargs="+", default=[1000, 100000])
    args = ap.parse_args()
    record = json.loads((DIRECTORY / f"{args.case}.json").read_text())
    for solver in ("generalized-alpha", "rk44"):
        for steps in args.steps:
            run = run_exudyn(record, steps, solver)
            s = score(run, args.case)
            print(f"{solver}, {steps} steps: {s.verdict}")


if __name__ == "__main__":
    main()

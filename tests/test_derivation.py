"""Derived equations against the paper's printed ones, and against independent formulations.

* symbolic identity, row by row, of the Newton-Euler rows derived from the vectors
  (models/rolling.py) and the rows as printed (models/paper.py): Eqs. 17, 18, 50, 80 = 81;
* the same at random states in 50-digit arithmetic, on the solved accelerations;
* an independent formulation (Kane's method, sympy.physics.mechanics) for every rolling
  body, and Lagrangians for the smooth-plane disk and the gyroscope;
* a negative control: the comparison notices a deliberately misprinted row.
"""
from __future__ import annotations

import mpmath
import pytest
import sympy as sp

from models import disk, get_model, gyroscope, hurricane, paper, ring, sliding_disk
from models.lagrange import euler_lagrange
from models.rolling import derive
from models.symbols import (
    ACCELERATIONS, g, omega_body, phi, phidot, phiddot, psi, psidot, psiddot, theta, thetadot,
    thetaddot,
)

from .conftest import mp_evaluator, random_states

I1s, I3s = sp.symbols("I1 I3", positive=True)

PRINTED = {
    "Eq. 17": (lambda: derive(I1s, I3s, sp.Integer(-1), sp.Integer(0)).rows, lambda: paper.eq17_rows(I1s, I3s)),
    "Eq. 18": (lambda: derive(disk.k, 2 * disk.k, disk.R2, disk.R3).rows, lambda: paper.eq18_rows(disk.k)),
    "Eq. 50": (lambda: derive(ring.I1, ring.I3, ring.R2, ring.R3).rows, lambda: paper.eq50_rows(ring.I1, ring.I3, ring.h)),
    "Eqs. 80 = 81": (
        lambda: derive(hurricane.I1, hurricane.I3, hurricane.R2, hurricane.R3).rows,
        lambda: paper.eq80_81_rows(hurricane.I1, hurricane.I3),
    ),
}

#: Exact differences (printed - derived) per row, where the paper is wrong.  Every
#: transcribed equation of motion turned out to be right: all differences are zero.
PINNED = {key: (0, 0, 0) for key in PRINTED}


def row_differences(derived_rows, printed_rows):
    return [sp.simplify(sp.expand_trig(printed_rows[i] - derived_rows[i])) for i in range(3)]


@pytest.mark.parametrize("source", sorted(PRINTED))
def test_printed_rows_equal_derived_rows(source):
    derived, printed = PRINTED[source]
    diffs = row_differences(derived(), printed())
    for i, (d, pinned) in enumerate(zip(diffs, PINNED[source])):
        assert sp.simplify(d - pinned) == 0, f"{source} row {i + 1}: printed - derived = {d}"


def test_comparison_catches_a_misprinted_row():
    """Negative control: Eq. 18 with (k + 1) misprinted as (k + 2) in row 1 must differ."""
    derived = derive(disk.k, 2 * disk.k, disk.R2, disk.R3).rows
    wrong = paper.eq18_rows(disk.k)
    wrong[0] = wrong[0] + phidot**2 * sp.sin(theta) * sp.cos(theta)  # (k+1) -> (k+2)
    diffs = row_differences(derived, wrong)
    assert diffs[0] != 0 and diffs[1] == 0 and diffs[2] == 0


def test_eq50_omega_form_equals_its_explicit_form():
    lhs_w = paper.eq50_omega_lhs(ring.I1, ring.I3, ring.h)
    lhs_mid = paper.eq50_middle_lhs(ring.I1, ring.I3, ring.h)
    assert [sp.simplify(a - b) for a, b in zip(lhs_w, lhs_mid)] == [0, 0, 0]


@pytest.mark.parametrize("name", ["disk", "ring", "hurricane", "gyroscope"])
def test_printed_accelerations_at_random_states(name, mp50):
    """Solved accelerations agree to 45 digits at random states (relative)."""
    derived, printed = get_model(name, "derived"), get_model(name, "paper")
    fd, fp = mp_evaluator(derived.accelerations, derived), mp_evaluator(printed.accelerations, printed)
    for state in random_states(10, seed=hash(name) % 1000):
        a, b = fd(state), fp(state)
        for x, y in zip(a, b):
            assert abs(x - y) <= mpmath.mpf(10) ** -45 * (1 + abs(x)), (name, state, x, y)


def test_random_state_check_catches_a_wrong_acceleration(mp50):
    """Negative control: the 50-digit comparison notices a relative change of 1e-30."""
    derived = get_model("disk")
    fd = mp_evaluator(derived.accelerations, derived)
    wrong = mp_evaluator([derived.accelerations[0] * (1 + sp.Rational(1, 10**30))] + list(derived.accelerations[1:]), derived)
    state = random_states(1, seed=1)[0]
    assert abs(fd(state)[0] - wrong(state)[0]) > mpmath.mpf(10) ** -45 * (1 + abs(fd(state)[0]))


# --- independent formulations --------------------------------------------------------------

def kane_accelerations(I1, I3, r2, r3):
    """Accelerations of a rolling body of revolution by Kane's method (sympy.physics.mechanics).

    Independent of models/rolling.py: frames by successive rotations, the centre of mass
    velocity from the rolling constraint on the body point at P (v_P = 0), generalised
    speeds the Euler rates, and the contact force non-contributing.
    """
    me = pytest.importorskip("sympy.physics.mechanics")
    q1, q2, q3 = me.dynamicsymbols("q1 q2 q3")  # phi, theta, psi
    u1, u2, u3 = me.dynamicsymbols("u1 u2 u3")
    N = me.ReferenceFrame("N")
    Y = N.orientnew("Y", "Axis", [q1, N.z])
    L = Y.orientnew("L", "Axis", [q2, Y.x])  # the paper's 1-2-3 frame: e1 = L.x, e3 = L.z
    B = L.orientnew("B", "Axis", [q3, L.z])
    B.set_ang_vel(N, u1 * N.z + u2 * Y.x + u3 * L.z)
    t = me.dynamicsymbols._t
    sub = {theta: q2}
    rP = r2.subs(sub) * L.y + r3.subs(sub) * L.z
    C = me.Point("C")
    C.set_vel(N, B.ang_vel_in(N).cross(-rP))  # v_C = -omega x r_P
    body = me.RigidBody("B", C, B, 1, (me.inertia(L, I1, I1, I3), C))
    forces = [(C, -g * N.z)]
    kd = [q1.diff(t) - u1, q2.diff(t) - u2, q3.diff(t) - u3]
    km = me.KanesMethod(N, q_ind=[q1, q2, q3], u_ind=[u1, u2, u3], kd_eqs=kd)
    fr, frstar = km.kanes_equations([body], forces)
    udot = km.mass_matrix.LUsolve(km.forcing)
    back = {q2: theta, u1: phidot, u2: thetadot, u3: psidot, q1: phi, q3: psi}
    acc = [sp.sympify(udot[i]).subs(back) for i in range(3)]
    return acc[1], acc[0], acc[2]  # theta, phi, psi


@pytest.mark.parametrize("name", ["disk", "ring", "hurricane"])
def test_kane_formulation_agrees(name, mp50):
    module = {"disk": disk, "ring": ring, "hurricane": hurricane}[name]
    model = get_model(name)
    I1 = model.parameters[0].symbol if name != "disk" else disk.k
    I3 = model.parameters[1].symbol if name != "disk" else 2 * disk.k
    kane = kane_accelerations(I1, I3, module.R2, module.R3)
    fk, fd = mp_evaluator(kane, model), mp_evaluator(model.accelerations, model)
    for state in random_states(6, seed=7):
        for x, y in zip(fd(state), fk(state)):
            assert abs(x - y) <= mpmath.mpf(10) ** -40 * (1 + abs(x)), (name, state, x, y)


def test_sliding_disk_matches_its_lagrangian():
    k = sliding_disk.k
    w = omega_body()
    zdot = sp.cos(theta) * thetadot
    L = sp.Rational(1, 2) * (k * (w[0] ** 2 + w[1] ** 2) + 2 * k * w[2] ** 2 + zdot**2) - g * sp.sin(theta)
    acc, energy, _ = euler_lagrange(L, ((theta, thetadot, thetaddot), (phi, phidot, phiddot), (psi, psidot, psiddot)))
    model = get_model("sliding-disk")
    for got, q in zip(model.accelerations, ACCELERATIONS):
        assert sp.simplify(got - acc[q]) == 0
    assert sp.simplify(model.energy - energy) == 0


def test_gyroscope_eq86_is_the_vector_lagrangian():
    assert sp.simplify(gyroscope.lagrangian_from_vectors() - paper.eq86_lagrangian(gyroscope.I1, gyroscope.I3)) == 0


@pytest.mark.parametrize("name", ["gyroscope", "effective"])
def test_heyoka_lagrangian_agrees(name):
    """heyoka.lagrangian (valid here: both are holonomic) gives the same right-hand side."""
    import heyoka as hy
    import numpy as np

    from verify.engine.compile import symbol_map, to_heyoka

    model = get_model(name)
    I1, I3 = model.parameters[0].symbol, model.parameters[1].symbol
    L = gyroscope.lagrangian_from_vectors() if name == "gyroscope" else paper.eq96_lagrangian(I1, I3)
    coords = (theta, phi, psi) if name == "gyroscope" else (theta, phi)
    speeds = (thetadot, phidot, psidot) if name == "gyroscope" else (thetadot, phidot)
    names = [str(c) for c in coords] + [str(s) for s in speeds]
    hv = hy.make_vars(*names)
    mapping = dict(zip(list(coords) + list(speeds), hv))
    mapping.update({p.symbol: hy.par[i] for i, p in enumerate(model.parameters)})
    sys = hy.lagrangian(to_heyoka(L, mapping), list(hv[: len(coords)]), list(hv[len(coords):]))
    ref = hy.cfunc([rhs for _, rhs in sys], hv)
    ours_map = symbol_map(model, hy.make_vars("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y"))
    ours = hy.cfunc([to_heyoka(a, ours_map) for a in model.accelerations[: len(coords)]],
                    [ours_map[s] for s in (theta, phi, psi, thetadot, phidot, psidot)])
    pars = np.array([float(p.default) for p in model.parameters])
    for st in random_states(5, seed=3):
        x = np.array([float(st[str(c)]) for c in coords] + [float(st[str(s)]) for s in speeds])
        full = np.array([float(st[n]) for n in ("theta", "phi", "psi", "thetadot", "phidot", "psidot")])
        a = ref(x, pars=pars)[len(coords):]
        b = ours(full, pars=pars)
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12)


# --- invariants are invariants, symbolically ---------------------------------------------

def _ddt(expr, accelerations):
    from models.symbols import time_derivative

    return time_derivative(expr).subs(dict(zip(ACCELERATIONS, accelerations)))


@pytest.mark.parametrize("name,equations", [("disk", "derived"), ("ring", "derived"), ("hurricane", "derived"),
                                            ("sliding-disk", "derived"), ("gyroscope", "derived"),
                                            ("effective", "derived"), ("hurricane", "paper")])
def test_closed_form_invariants_are_conserved(name, equations):
    model = get_model(name, equations)
    for inv in model.invariants:
        rate = sp.simplify(sp.expand_trig(sp.cancel(_ddt(inv.expr, model.accelerations))))
        assert rate == 0, f"d({inv.name})/dt = {rate}"


def test_energy_check_catches_a_wrong_term():
    """Negative control: with g cos(theta) -> 1.01 g cos(theta) in thetaddot, dE/dt != 0."""
    model = get_model("disk")
    wrong = (model.accelerations[0] - sp.Rational(1, 100) * g * sp.cos(theta) / (disk.k + 1),) + model.accelerations[1:]
    assert sp.simplify(_ddt(model.energy, wrong)) != 0

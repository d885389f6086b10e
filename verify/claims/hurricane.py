"""Claims of the hurricane-ball part of the paper (Eqs. 63-82, Fig. 14, text)."""
from __future__ import annotations

import mpmath
import sympy as sp

from models import hurricane, paper
from models.rolling import derive
from models.symbols import g, phidot, phiddot, psidot, psiddot, theta, thetadot, thetaddot

from .base import Claim, decide, definition, rows_identity
from .vectors import E1, E2, E3, c, omega_body, omega_body_dot, omega_frame, s, same, show, vertical_in_frame

SECTION = "Hurricane balls (Eqs. 63-82)"
I1, I3 = hurricane.I1, hurricane.I3
RP = -s * E2 - (1 + c) * E3
GVEC = -g * vertical_in_frame()


def _rows():
    return derive(I1, I3, hurricane.R2, hurricane.R3).rows


def _check_eq63():
    centre = -E3  # lower ball's centre, a below C along the axis (a = 1)
    contact = centre - vertical_in_frame()  # the lowest point of that ball
    return decide(same(contact, RP), show(contact.T), "a (0, -sin(theta), -1 - cos(theta))",
                  "C at the balls' touching point; P = lower centre - a Z, with Z = sin(theta) e2 + cos(theta) e3")


def _check_eq64():
    x, y, z, a, m = sp.symbols("x y z a m", positive=True)
    r, t, u = sp.symbols("r t u", positive=True)
    # a uniform ball of radius a by spherical integration, then the parallel-axis shift by a
    jac = r**2 * sp.sin(t)
    X, Y, Z = r * sp.sin(t) * sp.cos(u), r * sp.sin(t) * sp.sin(u), r * sp.cos(t)
    vol = lambda f: sp.integrate(sp.integrate(sp.integrate(f * jac, (r, 0, a)), (t, 0, sp.pi)), (u, 0, 2 * sp.pi))
    V = vol(1)
    own_axial = sp.simplify(vol(X**2 + Y**2) / V)  # per unit mass
    own_transverse = sp.simplify(vol(Y**2 + Z**2) / V)
    I3_pair = 2 * own_axial / (2 * a**2)  # in units of 2 m a^2 (m: one ball)
    I1_pair = 2 * (own_transverse + a**2) / (2 * a**2)
    ok = same(I1_pair, sp.Rational(7, 5)) and same(I3_pair, sp.Rational(2, 5))
    return decide(ok, f"I1 = {I1_pair}, I3 = {I3_pair} (units of 2 m a^2)", "(2/5) m a^2 diag(7, 7, 2) = 2 m a^2 diag(7/5, 7/5, 2/5)",
                  "ball moments by integration, parallel-axis shift a for the transverse axis")


def _check_eq65():
    w = omega_body()
    printed = sp.Matrix([thetadot, phidot * c, phidot * s + psidot])
    return decide(same(w, printed), show(w.T), show(printed.T), "omega of Eq. 16 (rotation matrices)",
                  correction="omega = (thetadot, phidot sin(theta), phidot cos(theta) + psidot), as in Eq. 16")


def _check_eq66():
    v = -omega_body().cross(RP)
    printed = sp.Matrix([(phidot - psidot) * s, -thetadot * (1 + c), thetadot * s])
    return decide(same(v, printed), show(v.T), show(printed.T), "-w x r_P with the omega of Eq. 16 (not the printed Eq. 65)")


def _check_height():
    z = -RP.dot(vertical_in_frame())
    return decide(same(z, 1 + c), show(sp.simplify(z)), "z = a (1 + cos(theta))", "-r_P . Z")


def _check_cm_rest():
    v = (-omega_body().cross(RP)).subs(thetadot, 0)
    sol = sp.solve(v[0], psidot)
    ok = sol == [phidot] and same(v[1], 0) and same(v[2], 0)
    return decide(ok, f"v_C = 0 with thetadot = 0 iff psidot = {sol}", "Delta psi = Delta phi", "Eq. 66 with thetadot = 0")


def _check_inconsistent():
    rows = paper.eq80_81_rows(I1, I3).subs({phiddot: 0, psiddot: 0, psidot: phidot})
    row3 = sp.factor(sp.simplify(rows[2]))
    ok = same(row3, -phidot * thetadot * s * (I3 + c + 1))
    return decide(ok, f"row 3 with phidot = psidot constant: {show(row3)} = 0", "forces thetadot = 0",
                  "I3 + cos(theta) + 1 > 0, so phidot thetadot sin(theta) = 0")


def _check_eq67():
    horizontal = RP - RP.dot(vertical_in_frame()) * vertical_in_frame()
    arm = sp.sqrt(sp.simplify(horizontal.dot(horizontal)))
    ok = same(arm**2, s**2)
    return decide(ok, f"lever arm of N about C: |r_P horizontal| = {show(sp.simplify(arm))} (a = 1); N = 2 m g",
                  "Gamma = 2 m g a sin(theta)", "with the CM at rest N balances the weight 2 m g")


def _steady_row1():
    return sp.factor(sp.simplify(-_rows()[0].subs({thetaddot: 0, thetadot: 0})))


def _check_eq68_70():
    L_perp = I3 * (psidot + phidot * c) * s - I1 * phidot * s * c
    e68 = (L_perp * phidot - g * s).subs(psidot, phidot)
    e70 = (I3 - (I1 - I3) * c) * phidot**2 - g
    derived = _steady_row1().subs(psidot, phidot)
    ok = same(e68, s * e70) and same(sp.simplify(derived / s), -e70)
    return decide(ok, f"derived row 1 at constant theta, psidot = phidot: {show(derived)} = 0", "Eqs. 68-70",
                  "Eq. 68 with psidot = phidot is sin(theta) times Eq. 70, which is the derived condition")


def _check_eq71_72():
    e70 = (I3 - (I1 - I3) * c)
    got = e70.subs({I1: sp.Rational(7, 5), I3: sp.Rational(2, 5)})
    ok = same(got, sp.Rational(2, 5) - c)
    return decide(ok, f"I3 - (I1 - I3) cos(theta) = {show(got)}", "2/5 - cos(theta) = g/phidot^2",
                  "I1 = 7/5, I3 = 2/5")


def _eq73():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    from models.symbols import time_derivative

    I = sp.diag(I1, I1, I3)
    v = -w.cross(RP)
    rdot = RP.applyfunc(time_derivative)
    return I * wd + Om.cross(I * w) - RP.cross(-wd.cross(RP) - w.cross(rdot) + Om.cross(v) - GVEC)


def _eq74():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    from models.symbols import time_derivative

    I = sp.diag(I1, I1, I3)
    rdot = RP.applyfunc(time_derivative)
    return I * wd + RP.cross(wd.cross(RP)) - (-Om.cross(I * w) + RP.cross(-w.cross(rdot) + Om.cross(RP.cross(w)) - GVEC))


def _identity(id, source, statement, printed):
    return rows_identity(id, source, SECTION, statement, printed, _rows, "hurricane balls (per 2m, a = 1)")


def _check_energy_terms():
    from models.symbols import time_derivative

    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    I = sp.diag(I1, I1, I3)
    L = I * w
    rdot = RP.applyfunc(time_derivative)
    t75 = same(w.dot(I * wd), time_derivative(w.dot(I * w) / 2))
    vc = w.cross(RP)
    t76 = same(w.dot(RP.cross(wd.cross(RP) + w.cross(rdot))), vc.dot(vc.applyfunc(time_derivative))) and \
        same(vc.dot(vc.applyfunc(time_derivative)), time_derivative(vc.dot(vc) / 2))
    t77 = same(-w.dot(Om.cross(L)), 0)
    t78 = same(w.dot(RP.cross(Om.cross(RP.cross(w)))), 0)
    t79 = same(-w.dot(RP.cross(GVEC)), g * s * thetadot) and same(g * s * thetadot, -time_derivative(g * c))
    ok = all((t75, t76, t77, t78, t79))
    return decide(ok, f"Eq. 75 {t75}, 76 {t76}, 77 {t77}, 78 {t78}, 79 {t79}", "each term as printed",
                  "Eq. 77's intermediate '(w x e3) x (w x e3)' is garbled (it is the zero vector); the statement it supports, "
                  "w . (Omega x L) = 0, holds because Omega = w - psidot e3 and L = I1 w + (I3 - I1) w3 e3")


def _check_eq80_81():
    ok = same(paper.eq80_81_rows(I1, I3), _rows())
    return decide(ok, "derived rows", "Eqs. 80 = 81 as printed", "row-by-row identity ('Mathematica finds')")


def _check_text_after_80():
    rates = {psidot: phidot, thetadot: 0, thetaddot: 0, phiddot: 0, psiddot: 0}
    rhs = paper.eq80_rhs(I1, I3).subs(rates).subs({I1: sp.Rational(7, 5), I3: sp.Rational(2, 5)})
    rhs = rhs.subs(c, sp.Rational(2, 5) - g / phidot**2)
    ok = same(rhs, sp.zeros(3, 1))
    return decide(ok, show(sp.simplify(rhs).T), "zero", "Eq. 80 with psidot = phidot, thetadot = 0, cos = 2/5 - g/phidot^2")


def _check_eq82():
    rho = sp.Symbol("rho")
    row = paper.eq80_rhs(sp.Rational(7, 5), sp.Rational(2, 5))[0].subs({thetadot: 0, psidot: rho * phidot}) / s
    sol = sp.solve(sp.Eq(row.subs(c, sp.Symbol("C")), 0), sp.Symbol("C"))
    printed = ((sp.Rational(7, 5) * rho - 1) - g / phidot**2) / (2 - rho)
    ok = len(sol) == 1 and same(sol[0], printed)
    return decide(ok, f"cos(theta) = {show(sol)}", show(printed), "Eq. 80 row 1 with psidot = rho phidot, thetadot = 0")


def _check_rho_ranges():
    rho = sp.Symbol("rho", positive=True)
    high_spin = ((sp.Rational(7, 5) * rho - 1)) / (2 - rho)
    at1, at54 = high_spin.subs(rho, 1), high_spin.subs(rho, sp.Rational(5, 4))
    ok = same(at1, sp.Rational(2, 5)) and same(at54, 1)
    return decide(ok, f"phidot -> oo: cos(theta) = {at1} at rho = 1, {at54} at rho = 5/4",
                  "rho from 5/4 to 1 gives 0 < theta < cos^-1(2/5)", "Eq. 82 with g/phidot^2 -> 0")


def _check_minimum():
    with mpmath.workdps(40):
        f = lambda r: (1 + r) / mpmath.sqrt(12 * r / 5 - 3)  # (phidot + psidot)/sqrt(g) at cos(theta) = 1
        rmin = mpmath.findroot(lambda r: mpmath.diff(f, r), 3)
        fmin = f(rmin)
    ok = abs(rmin - mpmath.mpf("3.5")) < 1e-20 and abs(fmin - mpmath.mpf("1.94")) <= 0.005
    return decide(ok, f"minimum of (phidot + psidot)/sqrt(g) at theta -> 0: {mpmath.nstr(fmin, 10)} at rho = {mpmath.nstr(rmin, 10)}",
                  "~1.94 sqrt(g) at rho = 3.5", "Eq. 82 with cos(theta) = 1; tolerance: the printed digits")


def claims() -> list:
    d = SECTION
    return [
        definition("fig-14", "Fig. 14", d, "two spheres rigidly attached at a point", "a photograph/diagram of the toy"),
        Claim("eq-63", "Eq. 63", d, "r_P = a (0, -sin(theta), -1 - cos(theta))", _check_eq63),
        Claim("eq-64", "Eq. 64", d, "I = (2/5) m a^2 diag(7, 7, 2) = 2 m a^2 diag(I1, I1, I3)", _check_eq64),
        Claim("text-before-65", "text before Eq. 65", d, "with the CM fixed, Delta psi = Delta phi", _check_cm_rest),
        Claim("eq-65", "Eq. 65", d, "omega = (thetadot, phidot cos(theta), phidot sin(theta) + psidot)", _check_eq65,
              known_failure="sin and cos exchanged"),
        Claim("eq-66", "Eq. 66", d, "v_CM = a ((phidot - psidot) sin, -thetadot (1 + cos), thetadot sin)", _check_eq66),
        Claim("text-after-66", "text after Eq. 66", d, "z = a (1 + cos(theta))", _check_height),
        Claim("text-after-66b", "text after Eq. 66", d, "phidot = psidot = constant is inconsistent with thetadot != 0",
              _check_inconsistent),
        Claim("eq-67", "Eq. 67", d, "Gamma = 2 m g a sin(theta)", _check_eq67),
        Claim("eq-68-70", "Eqs. 68-70", d, "phidot^2 [I3 - (I1 - I3) cos(theta)] = g", _check_eq68_70),
        Claim("eq-71-72", "Eqs. 71-72", d, "2/5 - g/phidot^2 = cos(theta)", _check_eq71_72),
        _identity("eq-73", "Eq. 73", "I.w' + Omega x L = 2m r_P x (-w' x r_P - w x r_P' + Omega x v_C - g)", _eq73),
        _identity("eq-74", "Eq. 74", "the same with the w' terms on the left", _eq74),
        Claim("eq-75-79", "Eqs. 75-79", d, "energy conservation, term by term", _check_energy_terms),
        Claim("eq-80-81", "Eqs. 80-81", d, "the equations of motion of the hurricane balls", _check_eq80_81),
        Claim("text-after-80", "text after Eq. 80", d, "psidot = phidot, thetadot = 0, cos = 2/5 - g/phidot^2 gives zero",
              _check_text_after_80),
        Claim("eq-82", "Eq. 82", d, "cos(theta) = ((7/5) rho - 1 - g/phidot^2) / (2 - rho)", _check_eq82),
        Claim("text-after-82", "text after Eq. 82", d, "rho from 5/4 to 1: high-spin solutions with 0 < theta < cos^-1(2/5)",
              _check_rho_ranges),
        Claim("text-after-82b", "text after Eq. 82", d, "smallest phidot + psidot ~ 1.94 sqrt(g) at rho = 3.5",
              _check_minimum, "numbers", "the printed digits; mpmath 40 digits"),
    ]

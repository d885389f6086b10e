"""Claims of the hurricane-ball part of the paper (Eqs. 63-82, Fig. 14, text).

Independent routes: the rows derived from the vectors (models/rolling.py), with m and a kept
wherever the paper keeps them; the geometry of the two balls; the contact force and its
torque from the vectors; ball moments by integration; roots and minima with mpmath.
"""
from __future__ import annotations

import mpmath
import sympy as sp

from models import hurricane, paper
from models.rolling import derive
from models.symbols import g, phidot, phiddot, psidot, psiddot, thetadot, thetaddot, time_derivative

from ..mathtext import equation, latex, tex
from .base import TYPO, Claim, decide, definition, rows_identity
from .vectors import E1, E2, E3, c, omega_body, omega_body_dot, omega_frame, s, same, vertical_in_frame

SECTION = "Hurricane balls (Eqs. 63-82)"
I1, I3 = hurricane.I1, hurricane.I3
m, a = sp.symbols("m a", positive=True)  # m is the mass of one ball (Eq. 64), a the balls' radius
RP = -s * E2 - (1 + c) * E3  # Eq. 63 in units of a
RPA = a * RP  # with a kept
GVEC = -g * vertical_in_frame()
HORIZONTAL_AXLE = s * E3 - c * E2  # Z x it = e1, "out of the page" as in Fig. 8
NUMBERS = {I1: sp.Rational(7, 5), I3: sp.Rational(2, 5)}

SCALED = ("I1, I3 in units of 2 m a^2 (Eq. 64), lengths in units of a, g <- g/a (the scaling stated before Eq. 68)")
KEPT = "m (one ball) and a kept; I = 2 m a^2 diag(I1, I1, I3) (Eq. 64), r_P of Eq. 63, L = I.w, v_C = -w x r_P"


def _rows():
    return derive(I1, I3, hurricane.R2, hurricane.R3).rows


def _rows_kept():
    """The derived rows times 2 m a^2, with g/a for the scaled g: the dimensional Newton-Euler rows."""
    return 2 * m * a**2 * _rows().subs(g, g / a)


def _identity(id, source, statement, printed, derived=None, quote="", reading=None):
    body = "hurricane balls" + (", m and a kept" if derived is not None else " (per 2 m a^2, a = 1)")
    return rows_identity(id, source, SECTION, statement, printed, derived or _rows, body, quote=quote, reading=reading)


def _check_eq63():
    centre = -a * E3  # lower ball's centre, a below C along the axis
    contact = centre - a * vertical_in_frame()  # the lowest point of that ball
    return decide(same(contact, RPA), equation(sp.Symbol("r_P"), contact), r"$a (0, -\sin\theta, -1 - \cos\theta)$",
                  r"$C$ at the balls' touching point; $P$ = lower centre $- a Z$, with "
                  r"$Z = \sin\theta \, \mathbf{e}_2 + \cos\theta \, \mathbf{e}_3$")


def _check_eq64():
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
    ok = same(I1_pair, sp.Rational(7, 5)) and same(I3_pair, sp.Rational(2, 5)) and I1_pair > I3_pair
    return decide(ok, f"{equation(I1, I1_pair)}, {equation(I3, I3_pair)} (units of $2 m a^2$), so $I_1 > I_3$",
                  r"$(2/5) m a^2 \operatorname{diag}(7, 7, 2) = 2 m a^2 \operatorname{diag}(7/5, 7/5, 2/5)$",
                  "ball moments by integration, parallel-axis shift a for the transverse axis")


def _check_cm_rest():
    Z = vertical_in_frame()
    on_plane = RPA - RPA.dot(Z) * Z  # C fixed: P circles below C at the horizontal distance |on_plane|
    on_ball = -a * Z - (-a * Z).dot(E3) * E3  # P relative to the lower centre, off the ball's axis e3
    radii = same(on_plane.dot(on_plane), a**2 * s**2) and same(on_ball.dot(on_ball), a**2 * s**2)
    v = (-omega_body().cross(RPA)).subs(thetadot, 0)
    sol = sp.solve(v[0], psidot)
    rest = sol == [phidot] and same(v[1], 0) and same(v[2], 0)
    return decide(radii and rest, r"radii of $P$'s circles on the plane and on the lower ball: $a \sin\theta$ both "
                                  rf"({radii}); $v_C = 0$ with $\dot{{\theta}} = 0$ iff "
                                  + ", ".join(equation(psidot, x) for x in sol),
                  r"radius $a \sin\theta$ twice; $\Delta\psi = \Delta\phi$",
                  r"geometry of $r_P$, and $v_C = -\omega \times r_P$ with $\dot{\theta} = 0$")


def _check_eq65():
    w = omega_body()
    printed_w = sp.Matrix([thetadot, phidot * c, phidot * s + psidot])
    printed_v = -a * printed_w.cross(RP)
    e66 = a * sp.Matrix([(phidot - psidot) * s, -thetadot * (1 + c), thetadot * s])
    follows = same(-w.cross(RPA), e66)  # Eq. 66 follows from Eq. 16's omega, not from the printed one
    return decide(same(w, printed_w), f"{equation(sp.Symbol('omega'), w)} (Eq. 16, rotation matrices)",
                  equation(sp.Symbol("omega"), printed_w),
                  f"the printed product is {tex(sp.simplify(printed_v))}, which is not Eq. 66; Eq. 16's $\\omega$ gives "
                  f"Eq. 66 ({follows})",
                  correction=r"$v_{CM} = -a \left(\dot{\theta}, \dot{\phi} \sin\theta, \dot{\phi} \cos\theta + \dot{\psi}\right) "
                             r"\times (0, -\sin\theta, -1 - \cos\theta)$, with the $\omega$ of Eq. 16")


def _check_eq66():
    v = -omega_body().cross(RPA)
    printed = a * sp.Matrix([(phidot - psidot) * s, -thetadot * (1 + c), thetadot * s])
    return decide(same(v, printed), equation(sp.Symbol("v_CM"), v), equation(sp.Symbol("v_CM"), printed),
                  r"$-\omega \times r_P$ with the $\omega$ of Eq. 16 (not the printed Eq. 65)")


def _check_height():
    Z = vertical_in_frame()
    z = -RPA.dot(Z)
    v = -omega_body().cross(RPA)
    rest = same(v.subs({psidot: phidot, thetadot: 0}), sp.zeros(3, 1))
    vertical = sp.simplify(v.dot(Z))
    horizontal = v - v.dot(Z) * Z
    moving = same(vertical, time_derivative(z)) and same(vertical, -a * s * thetadot) \
        and same(horizontal.subs(psidot, phidot).dot(horizontal.subs(psidot, phidot)), a**2 * thetadot**2 * (1 + c) ** 2)
    ok = same(z, a * (1 + c)) and rest and moving
    return decide(ok, rf"$z = -r_P \cdot Z = {latex(sp.simplify(z))}$; at $\dot{{\psi}} = \dot{{\phi}}$, "
                      rf"$\dot{{\theta}} = 0$, $v_C = 0$ ({rest}); otherwise vertical $v_C \cdot Z = {latex(vertical)}$ and, at "
                      r"$\dot{\psi} = \dot{\phi}$, horizontal speed $a \lvert \dot{\theta} \rvert (1 + \cos\theta)$",
                  r"at rest iff $\dot{\phi} = \dot{\psi}$, $\dot{\theta} = 0$; else vertical ($z = a (1 + \cos\theta)$) and "
                  "horizontal motion",
                  r"$v_C = -\omega \times r_P$")


def _check_inconsistent():
    rows = _rows().subs({phiddot: 0, psiddot: 0, psidot: phidot})
    row3 = sp.factor(sp.simplify(rows[2]))
    ok = same(row3, -phidot * thetadot * s * (I3 + c + 1))
    return decide(ok, rf"derived row 3 with $\dot{{\phi}} = \dot{{\psi}}$ constant: {equation(row3, 0)}",
                  r"forces $\dot{\theta} = 0$",
                  r"$I_3 + \cos\theta + 1 > 0$, so $\dot{\phi} \dot{\theta} \sin\theta = 0$; the printed third component "
                  "of Eq. 80-81 is the same row")


def _check_eq67():
    Z = vertical_in_frame()
    # CM at rest: a_C = 0, so the contact force is the weight of both balls, F = 2 m g Z
    torque = sp.simplify(RPA.cross(2 * m * g * Z))
    L = (_inertia_scaled() * omega_body()).subs({thetadot: 0, psidot: phidot})
    dL = omega_frame().subs(thetadot, 0).cross(L)
    ok = same(torque, 2 * m * g * a * s * E1)
    return decide(ok, rf"$r_P \times (2 m g Z) = {latex(torque)}$: out of the page ($\mathbf{{e}}_1$, Fig. 8) for "
                      rf"$0 < \theta < \pi/2$; $\frac{{dL}}{{dt}}$ per $2 m a^2$ = ${latex(sp.factor(dL[0]))} \, \mathbf{{e}}_1$, "
                      r"$> 0$ on the steady states ($\cos\theta < 2/5$)",
                  r"$\Gamma = 2 m g a \sin\theta$, out of the page", "the normal force of the CM-at-rest state about $C$")


def _inertia_scaled():
    return sp.diag(I1, I1, I3)


def _steady_row1():
    return sp.factor(sp.simplify(-_rows()[0].subs({thetaddot: 0, thetadot: 0})))


def _check_eq68():
    L = _inertia_scaled() * omega_body().subs(thetadot, 0)
    L_perp = L.dot(HORIZONTAL_AXLE)
    printed_lhs = phidot * (I3 * (psidot + phidot * c) * s - I1 * phidot * s * c)
    lhs_ok = same(L_perp * phidot, printed_lhs)
    torque = RPA.cross(2 * m * g * vertical_in_frame()).dot(E1)  # Eq. 67, from the vectors
    scaled = sp.simplify((torque / (2 * m * a**2)).subs(g, g * a))  # divide out 2 m a^2, then g <- g/a
    printed_rhs = 2 * m * g * a * s
    rhs_ok = same(printed_rhs, scaled)
    return decide(lhs_ok and rhs_ok, rf"$L_\perp \dot{{\phi}} = {latex(printed_lhs)}$ ({lhs_ok}); "
                                     rf"$\Gamma / (2 m a^2)$ with $g \leftarrow g/a$: {tex(scaled)}",
                  r"$\ldots = 2 m g a \sin\theta$",
                  "the printed right side keeps the $2 m a$ the sentence divides out: in the scaled units it is $2 m a$ times "
                  r"the torque; Eq. 69 uses $g \sin\theta$, so what follows is right",
                  correction=r"$L_\perp \dot{\phi} = \dot{\phi} \left[I_3 (\dot{\psi} + \dot{\phi} \cos\theta) \sin\theta "
                             r"- I_1 \dot{\phi} \sin\theta \cos\theta\right] = g \sin\theta$")


def _check_eq69_70():
    derived = _steady_row1().subs(psidot, phidot)
    e69 = phidot**2 * (I3 * (1 + c) - I1 * c) - g
    e70 = (I3 - (I1 - I3) * c) - g / phidot**2
    ok = same(sp.simplify(derived / s), -e69) and same(e69 / phidot**2, e70)
    return decide(ok, rf"derived row 1 at constant $\theta$, $\dot{{\psi}} = \dot{{\phi}}$: {equation(derived, 0)}",
                  "Eqs. 69-70",
                  r"the derived condition divided by $\sin\theta$ is Eq. 69; Eq. 70 is Eq. 69 divided by $\dot{\phi}^2$")


def _check_eq71_72():
    got = (I3 - (I1 - I3) * c).subs(NUMBERS)
    ok = same(got, sp.Rational(2, 5) - c)
    return decide(ok, rf"$I_3 - (I_1 - I_3) \cos\theta = {latex(got)}$", r"$2/5 - \cos\theta = g/\dot{\phi}^2$",
                  "$I_1 = 7/5$, $I_3 = 2/5$ (Eq. 64)")


def _eq73():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    I = 2 * m * a**2 * _inertia_scaled()
    v = -w.cross(RPA)
    rdot = RPA.applyfunc(time_derivative)
    return I * wd + Om.cross(I * w) - 2 * m * RPA.cross(-wd.cross(RPA) - w.cross(rdot) + Om.cross(v) - GVEC)


def _eq74():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    I = 2 * m * a**2 * _inertia_scaled()
    rdot = RPA.applyfunc(time_derivative)
    return (I * wd + 2 * m * RPA.cross(wd.cross(RPA))
            - (-Om.cross(I * w) + 2 * m * RPA.cross(-w.cross(rdot) + Om.cross(RPA.cross(w)) - GVEC)))


def _check_eq75_76():
    w, wd = omega_body(), omega_body_dot()
    I = 2 * m * a**2 * _inertia_scaled()
    rdot = RPA.applyfunc(time_derivative)
    t75 = same(w.dot(I * wd), time_derivative(w.dot(I * w) / 2))
    vc = w.cross(RPA)
    dvc = wd.cross(RPA) + w.cross(rdot)  # d/dt (w x r_P), components in 1-2-3: the two terms Eq. 74 carries
    t76 = same(2 * m * w.dot(RPA.cross(dvc)), 2 * m * vc.dot(dvc)) and same(2 * m * vc.dot(dvc), time_derivative(m * vc.dot(vc)))
    return decide(t75 and t76, f"Eq. 75: {t75}; Eq. 76: {t76} " r"(CM KE = $\frac{1}{2} (2m) \lvert \omega \times r_P \rvert^2$)",
                  "each term as printed",
                  r"the $\omega$-dotted terms of Eq. 74; the magnitude $\lvert \omega \times r_P \rvert$ is the same in every "
                  "frame")


def _check_eq77():
    w, Om = omega_body(), omega_frame()
    L = _inertia_scaled() * w  # per 2 m a^2
    OxL = Om.cross(L)
    u = w.cross(E3)
    factor = (I3 - I1) * w[2] + I1 * psidot
    proportional = same(OxL, factor * u)  # what the step means: Omega x L is along w x e3
    zero_vector = same(u.cross(u), sp.zeros(3, 1))
    nonzero = not same(OxL, sp.zeros(3, 1))
    conclusion = same(-w.dot(OxL), 0)
    printed_step = not nonzero  # Omega x L ~ (w x e3) x (w x e3) = 0 would need Omega x L = 0
    ok = printed_step and conclusion
    return decide(ok, rf"$\Omega \times L = \left({latex(factor)}\right) (\omega \times \mathbf{{e}}_3)$ per $2 m a^2$, "
                      rf"not zero ({nonzero}); $-\omega \cdot \Omega \times L = 0$ ({conclusion})",
                  r"$-\omega \cdot \Omega \times L \sim \omega \cdot (\omega \times \mathbf{e}_3) \times "
                  r"(\omega \times \mathbf{e}_3) \sim \omega \cdot (\omega \times \mathbf{e}_3) = 0$",
                  r"$(\omega \times \mathbf{e}_3) \times (\omega \times \mathbf{e}_3)$ is the zero vector "
                  rf"({zero_vector}), so the middle step says nothing about $\Omega \times L$; $\Omega \times L$ is "
                  rf"proportional to $\omega \times \mathbf{{e}}_3$ ({proportional}), which is what the conclusion needs",
                  correction=r"$-\omega \cdot \Omega \times L = -\left((I_3 - I_1) \omega_3 + I_1 \dot{\psi}\right) "
                             r"\omega \cdot (\omega \times \mathbf{e}_3) = 0$, since "
                             r"$\Omega \times L = \left((I_3 - I_1) \omega_3 + I_1 \dot{\psi}\right) (\omega \times \mathbf{e}_3)$ "
                             "($I$ per $2 m a^2$)")


def _check_eq78():
    w, Om = omega_body(), omega_frame()
    lhs = RPA.cross(Om.cross(RPA.cross(w)))
    middle = RPA.cross(-Om.dot(RPA) * w)
    ok = same(lhs, middle) and same(2 * m * w.dot(middle), 0)
    return decide(ok, r"$r_P \times (\Omega \times (r_P \times \omega)) = r_P \times (-(\Omega \cdot r_P) \omega)$: "
                      rf"{same(lhs, middle)}; dotted with $\omega$: 0",
                  r"$2m \, \omega \cdot r_P \times (\Omega \times (r_P \times \omega)) = 2m \, \omega \cdot r_P \times "
                  r"(-\Omega \cdot r_P) \omega = 0$", "vector identities, $a$ kept")


def _check_eq79():
    w = omega_body()
    got = -2 * m * w.dot(RPA.cross(GVEC))
    potential = 2 * m * g * (-RPA.dot(vertical_in_frame()))  # 2 m g z_C
    printed = (2 * m * g * w.dot(E1) * s, 2 * m * g * s * thetadot, -time_derivative(2 * m * g * c))
    steps = [same(got, p) for p in printed]
    consistent = same(got, -time_derivative(potential))
    ok = all(steps)
    return decide(ok, rf"$-2m \, \omega \cdot r_P \times g = {latex(sp.factor(got))} = -\frac{{d}}{{dt}}(2 m g z_C)$, "
                      rf"$z_C = a (1 + \cos\theta)$ ({consistent})",
                  r"$2 m g \, \omega \cdot \mathbf{e}_1 \sin\theta = 2 m g \sin\theta \, \dot{\theta} = "
                  r"-\frac{d}{dt}(2 m g \cos\theta)$",
                  rf"$r_P = a (0, -\sin\theta, -1 - \cos\theta)$ (Eq. 63): the printed forms drop the factor $a$ (steps {steps}); "
                  "energy conservation, which the equation is for, is unaffected",
                  correction=r"$-2m \, \omega \cdot r_P \times g = 2 m g a \, \omega \cdot \mathbf{e}_1 \sin\theta = "
                             r"2 m g a \sin\theta \, \dot{\theta} = -\frac{d}{dt}(2 m g a \cos\theta)$")


def _check_eq80_81():
    ok = same(paper.eq80_81_rows(I1, I3), _rows())
    return decide(ok, "derived rows", "Eqs. 80 = 81 as printed", "row-by-row identity ('Mathematica finds')")


def _check_text_after_80():
    rates = {psidot: phidot, thetadot: 0, thetaddot: 0, phiddot: 0, psiddot: 0}
    rhs = paper.eq80_rhs(I1, I3).subs(rates).subs(NUMBERS)
    rhs = rhs.subs(c, sp.Rational(2, 5) - g / phidot**2)
    ok = same(rhs, sp.zeros(3, 1))
    return decide(ok, tex(sp.simplify(rhs)), "zero",
                  r"Eq. 80 with $\dot{\psi} = \dot{\phi}$, $\dot{\theta} = 0$, $\cos\theta = 2/5 - g/\dot{\phi}^2$")


def _cos_on_circle():
    """cos(theta) of the steady circles psidot = rho phidot, from the derived row 1 (I1 = 7/5, I3 = 2/5)."""
    rho, C = sp.Symbol("rho"), sp.Symbol("C")
    row = sp.simplify(_steady_row1().subs(psidot, rho * phidot).subs(NUMBERS) / s).subs(c, C)
    sol = sp.solve(sp.Eq(row, 0), C)
    return rho, sol


def _check_eq82():
    rho, sol = _cos_on_circle()
    printed = ((sp.Rational(7, 5) * rho - 1) - g / phidot**2) / (2 - rho)
    # the horizontal (centripetal) part of the contact force 2 m a_C and its torque about C, against the normal force's
    w, Om = omega_body().subs({thetadot: 0, psidot: rho * phidot}), omega_frame().subs(thetadot, 0)
    a_C = Om.cross(-w.cross(RPA))
    centripetal = sp.factor(sp.simplify(RPA.cross(2 * m * a_C).dot(E1)))
    normal = sp.simplify(RPA.cross(2 * m * g * vertical_in_frame()).dot(E1))
    opposes = same(centripetal, 2 * m * a**2 * phidot**2 * (1 - rho) * s * (1 + c)) and same(normal, 2 * m * g * a * s)
    ok = len(sol) == 1 and same(sol[0], printed) and opposes
    return decide(ok, ", ".join(equation(c, x) for x in sol) + "; torque of the centripetal force "
                      rf"${latex(centripetal)} \, \mathbf{{e}}_1$ against the normal force's ${latex(normal)} \, \mathbf{{e}}_1$",
                  f"{equation(c, printed)}; " r"$\rho > 1$: the centripetal torque opposes the normal force's, $\rho < 1$ "
                  "the reverse",
                  r"derived row 1 with $\dot{\psi} = \rho \dot{\phi}$, $\dot{\theta} = 0$; the centripetal torque carries "
                  r"the sign of $1 - \rho$")


def _check_rho_ranges():
    rho, sol = _cos_on_circle()
    high_spin = sp.limit(sol[0], phidot, sp.oo)
    at1, at54 = high_spin.subs(rho, 1), high_spin.subs(rho, sp.Rational(5, 4))
    increasing = sp.simplify(sp.diff(high_spin, rho))  # > 0: theta falls monotonically from cos^-1(2/5) to 0
    radius = sp.simplify((-omega_body().cross(RP))[0].subs({thetadot: 0, psidot: rho * phidot}) / phidot)
    P = sp.Symbol("P", positive=True)  # phidot^2
    sleeping = sp.solve(sp.Eq(sol[0].subs(phidot**2, P), 1), P)
    rate2 = sp.simplify(sleeping[0]) if len(sleeping) == 1 else None
    ok = same(at1, sp.Rational(2, 5)) and same(at54, 1) and bool(sp.simplify(increasing * (2 - rho) ** 2) > 0) \
        and rate2 is not None and same(rate2, g / (sp.Rational(12, 5) * rho - 3))
    return decide(ok, rf"$\dot{{\phi}} \to \infty$: {equation(c, high_spin)}: ${latex(at1)}$ at $\rho = 1$, "
                      rf"${latex(at54)}$ at $\rho = 5/4$, increasing ($\frac{{d}}{{d\rho}} = {latex(increasing)}$); "
                      rf"CM circle radius {tex(radius)} ($a = 1$), at most $\sin\theta / 4$ here; "
                      rf"$\theta \to 0$ needs {equation(phidot**2, rate2)}, finite iff $\rho > 5/4$",
                  r"$\rho$ from 5/4 to 1: high-spin solutions with $0 < \theta < \cos^{-1}(2/5)$, small CM motion; "
                  r"$\rho > 5/4$: $\theta \approx 0$ with finite $\dot{\phi}$",
                  r"derived row 1 with $\dot{\psi} = \rho \dot{\phi}$, $\dot{\theta} = 0$")


def _check_minimum():
    rho, sol = _cos_on_circle()
    P = sp.Symbol("P", positive=True)  # phidot^2
    rate = sp.sqrt(sp.solve(sp.Eq(sol[0].subs(phidot**2, P), 1), P)[0])  # phidot of the theta -> 0 circle
    f = sp.lambdify(rho, ((1 + rho) * rate / sp.sqrt(g)).subs(g, 1), "mpmath")  # (phidot + psidot)/sqrt(g)
    with mpmath.workdps(40):
        rmin = mpmath.findroot(lambda r: mpmath.diff(f, r), 3)
        fmin = f(rmin)
    ok = abs(rmin - mpmath.mpf("3.5")) < 1e-20 and abs(fmin - mpmath.mpf("1.94")) <= 0.005
    return decide(ok, r"minimum of $(\dot{\phi} + \dot{\psi})/\sqrt{g}$ on the $\theta \to 0$ circles: "
                      f"{mpmath.nstr(fmin, 10)} at $\\rho = {mpmath.nstr(rmin, 10)}$",
                  r"$\approx 1.94 \sqrt{g}$ at $\rho = 3.5$",
                  r"derived row 1 at $\cos\theta = 1$; tolerance: the printed digits")


def claims() -> list:
    d = SECTION
    return [
        definition("fig-14", "Fig. 14", d, "two spheres rigidly attached at a point", "a photograph/diagram of the toy",
                   quote="Hurricane Balls consist of two spheres rigidly attached at a point."),
        Claim("eq-63", "Eq. 63", d, "r_P = a (0, -sin(theta), -1 - cos(theta))", _check_eq63,
              quote=(r"First \mathbf{r}_P is not a constant:", r"\mathbf{r}_P = a(0, -\sin \theta, -1 - \cos \theta)"),
              reading="C at the balls' touching point, the lower ball's centre a below it on the axis e3"),
        Claim("eq-64", "Eq. 64", d, "I = (2/5) m a^2 diag(7, 7, 2) = 2 m a^2 diag(I1, I1, I3)", _check_eq64,
              quote=(r"Second, it is ‘prolate’, i.e., $I_1 > I_3$:",
                     r"\mathbf{I} = \frac{2}{5} ma^2 \begin{pmatrix} 7 & 0 & 0 \\ 0 & 7 & 0 \\ 0 & 0 & 2 \end{pmatrix} = 2ma^2 \begin{pmatrix} I_1 & 0 & 0 \\ 0 & I_1 & 0 \\ 0 & 0 & I_3 \end{pmatrix}",
                     "where m is the mass of one ball."),
              reading="two uniform balls of radius a; moments about C"),
        Claim("text-before-65", "text before Eq. 65", d, "with the CM fixed, P circles with radius a sin(theta); Delta psi = Delta phi",
              _check_cm_rest,
              quote=r"If the CM remains fixed (hence θ fixed), the contact point P will make a circle of radius $a \sin \theta$ "
                    r"in the plane. That contact will also inscribe a circle on the lower ball which also has radius "
                    r"$a \sin \theta$. As the object rotates, the arc length inscribed on the plane and on the lower ball must "
                    r"be the same; same arc length and same radius means same angle, so $\Delta\psi = \Delta\phi$."),
        Claim("eq-65", "Eq. 65", d, "v_CM = -a (thetadot, phidot cos(theta), phidot sin(theta) + psidot) x r_P/a", _check_eq65,
              known_failure="sin and cos exchanged in omega", severity=TYPO,
              quote=r"\mathbf{v}_{CM} = -\boldsymbol{\omega} \times \mathbf{r}_P = -a(\dot{\theta}, \dot{\phi} \cos \theta, \dot{\phi} \sin \theta + \dot{\psi}) \times (0, -\sin \theta, -1 - \cos \theta)",
              reading="the triple is omega in e1, e2, e3 components, as in Eq. 16"),
        Claim("eq-66", "Eq. 66", d, "v_CM = a ((phidot - psidot) sin, -thetadot (1 + cos), thetadot sin)", _check_eq66,
              quote=r"= a \left((\dot{\phi} - \dot{\psi}) \sin \theta, -\dot{\theta}(1 + \cos \theta), \dot{\theta} \sin \theta \right)"),
        Claim("text-after-66", "text after Eq. 66", d, "at rest iff phidot = psidot, thetadot = 0; z = a (1 + cos(theta))",
              _check_height,
              quote=r"So if $\dot{\phi} = \dot{\psi}$ and $\dot{\theta} = 0$ the CM is at rest, but if $\dot{\theta} \neq 0$ the "
                    r"CM will have both vertical (since $z = a(1 + \cos \theta)$) and horizontal components of velocity."),
        Claim("text-after-66b", "text after Eq. 66", d, "phidot = psidot = constant is inconsistent with thetadot != 0",
              _check_inconsistent,
              quote=r"$\dot{\phi} = \dot{\psi} = \text{constant}$ is inconsistent with $\dot{\theta} \neq 0$ (see the third "
                    r"component of Eq. (80-81) below).",
              reading=f"phidot != 0 and 0 < theta < pi/2; {SCALED}"),
        Claim("eq-67", "Eq. 67", d, "Gamma = 2 m g a sin(theta), out of the page", _check_eq67,
              quote=(r"P is to the right of the CM so the torque due to the normal force is out of the page, which is as "
                     r"expected as $\dot{\phi} = \dot{\psi} > 0$.", r"the torque due to the normal force is",
                     r"\Gamma = 2mga \sin \theta"),
              reading="the CM at rest (psidot = phidot, thetadot = 0), so the normal force is the weight 2 m g of both "
                      "balls; 'out of the page' is e1 as in Fig. 8"),
        Claim("eq-68", "Eq. 68", d, "L_perp phidot = phidot [I3 (psidot + phidot cos) sin - I1 phidot sin cos] = 2 m g a sin",
              _check_eq68, known_failure="the scaled torque printed as 2 m g a sin(theta) for g sin(theta)", severity=TYPO,
              quote=(r"Setting $L_{\perp} \dot{\phi} = \Gamma$, dividing out the scale factor $2ma^2$, and using "
                     r"$g \leftarrow g/a$ results",
                     r"L_{\perp} \dot{\phi} = \dot{\phi} \left[I_3(\dot{\psi} + \dot{\phi} \cos \theta) \sin \theta - I_1 \dot{\phi} \sin \theta \cos \theta \right] = 2mga \sin \theta"),
              reading="I1, I3 in units of 2 m a^2 (Eq. 64); L_perp as in Eq. 51, the torque Gamma of Eq. 67"),
        Claim("eq-69-70", "Eqs. 69-70", d, "phidot^2 [I3 (1 + cos) - I1 cos] = g, i.e. I3 - (I1 - I3) cos(theta) = g/phidot^2",
              _check_eq69_70,
              quote=(r"\dot{\phi}^2 [I_3(1 + \cos \theta) - I_1 \cos \theta] = g",
                     r"[I_3 - (I_1 - I_3) \cos \theta] = \frac{g}{\dot{\phi}^2}"),
              reading=f"psidot = phidot (the CM at rest); {SCALED}"),
        Claim("eq-71-72", "Eqs. 71-72", d, "2/5 - g/phidot^2 = cos(theta)", _check_eq71_72,
              quote=(r"\frac{2}{5} - \cos \theta = \frac{g}{\dot{\phi}^2}", r"\frac{2}{5} - \frac{g}{\dot{\phi}^2} = \cos \theta")),
        _identity("eq-73", "Eq. 73", "I.w' + Omega x L = 2m r_P x (-w' x r_P - w x r_P' + Omega x v_C - g)", _eq73, _rows_kept,
                  quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + \boldsymbol{\Omega} \times \mathbf{L} = 2m\mathbf{r}_P \times (-\dot{\boldsymbol{\omega}} \times \mathbf{r}_P - \boldsymbol{\omega} \times \dot{\mathbf{r}}_P + \boldsymbol{\Omega} \times \mathbf{v}_C - \mathbf{g})",
                  reading=KEPT + "; r_P' the time derivative of its 1-2-3 components"),
        _identity("eq-74", "Eq. 74", "the same with the w' terms on the left", _eq74, _rows_kept,
                  quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + 2m\mathbf{r}_P \times (\dot{\boldsymbol{\omega}} \times \mathbf{r}_P) = -\boldsymbol{\Omega} \times \mathbf{L} + 2m\mathbf{r}_P \times (-\boldsymbol{\omega} \times \dot{\mathbf{r}}_P + \boldsymbol{\Omega} \times (\mathbf{r}_P \times \boldsymbol{\omega}) - \mathbf{g})",
                  reading=KEPT),
        Claim("eq-75-76", "Eqs. 75-76", d, "w . I . w' = d/dt(rot KE); the r_P terms give d/dt(CM KE)", _check_eq75_76,
              quote=(r"You can quickly check energy conservation in this form, by dotting with $\boldsymbol{\omega}$:",
                     r"\boldsymbol{\omega} \cdot \mathbf{I} \cdot \dot{\boldsymbol{\omega}} = \frac{d}{dt}(\text{rotational KE})",
                     r"2m \boldsymbol{\omega} \cdot \left[\mathbf{r}_P \times \frac{d}{dt}(\boldsymbol{\omega} \times \mathbf{r}_P) \right] = 2m (\boldsymbol{\omega} \times \mathbf{r}_P) \cdot \frac{d}{dt}(\boldsymbol{\omega} \times \mathbf{r}_P) = \frac{d}{dt}(\text{CM KE})"),
              reading=KEPT + "; d/dt of the 1-2-3 components, as in Eq. 74"),
        Claim("eq-77", "Eq. 77", d, "-w . Omega x L ~ w . (w x e3) x (w x e3) ~ w . (w x e3) = 0", _check_eq77,
              known_failure="the middle step (w x e3) x (w x e3) is the zero vector; Omega x L is along w x e3",
              severity=TYPO,
              quote=r"-\boldsymbol{\omega} \cdot \boldsymbol{\Omega} \times \mathbf{L} \sim \boldsymbol{\omega} \cdot (\boldsymbol{\omega} \times \mathbf{e}_3) \times (\boldsymbol{\omega} \times \mathbf{e}_3) \sim \boldsymbol{\omega} \cdot (\boldsymbol{\omega} \times \mathbf{e}_3) = 0",
              reading="'~' read as 'is proportional to' (a vector statement about Omega x L)"),
        Claim("eq-78", "Eq. 78", d, "2m w . r_P x (Omega x (r_P x w)) = 2m w . r_P x (-Omega . r_P) w = 0", _check_eq78,
              quote=r"2m \boldsymbol{\omega} \cdot \mathbf{r}_P \times (\boldsymbol{\Omega} \times (\mathbf{r}_P \times \boldsymbol{\omega})) = 2m \boldsymbol{\omega} \cdot \mathbf{r}_P \times (-\boldsymbol{\Omega} \cdot \mathbf{r}_P) \boldsymbol{\omega} = 0"),
        Claim("eq-79", "Eq. 79", d, "-2m w . r_P x g = 2 m g w . e1 sin = 2 m g sin thetadot = -d/dt(2 m g cos)", _check_eq79,
              known_failure="the factor a of r_P is dropped", severity=TYPO,
              quote=r"-2m \boldsymbol{\omega} \cdot \mathbf{r}_P \times \mathbf{g} = 2mg \boldsymbol{\omega} \cdot \mathbf{e}_1 \sin \theta = 2mg \sin \theta \dot{\theta} = -\frac{d}{dt}(2mg \cos \theta)",
              reading="r_P of Eq. 63 (a kept, as Eqs. 67 and 85 keep it), g = -g Z"),
        Claim("eq-80-81", "Eqs. 80-81", d, "the equations of motion of the hurricane balls", _check_eq80_81,
              quote=(r"\begin{pmatrix} \sin \theta \left(g + \dot{\phi}^2((I_1 - I_3 + 1) \cos \theta + 1) - \dot{\phi} \dot{\psi}(I_3 + \cos \theta + 1) + \dot{\theta}^2 \right) \\ \dot{\theta} \left(\dot{\psi}(I_3 + \cos^2 \theta + \cos \theta) - \dot{\phi} \cos \theta (I_1 - I_3 + \cos \theta + 1) \right) \\ \dot{\theta} \sin \theta \cos \theta (\dot{\phi} - \dot{\psi}) \end{pmatrix}",
                     r"\begin{pmatrix} \ddot{\theta}(I_1 + 2 \cos \theta + 2) \\ \sin \theta \left(\ddot{\phi}(I_1 + \cos \theta + 1) - \ddot{\psi}(\cos \theta + 1) \right) + \dot{\phi} \dot{\theta}(I_1 \cos \theta + (1 + \cos \theta)^2) \\ \ddot{\phi}(I_3 \cos \theta + \cos^2 \theta - 1) - \dot{\phi} \dot{\theta} \sin \theta (I_3 + \cos \theta + 1) + \ddot{\psi}(I_3 - \cos^2 \theta + 1) \end{pmatrix}"),
              reading=f"LHS (Eq. 81) = RHS (Eq. 80); {SCALED}"),
        Claim("text-after-80", "text after Eq. 80", d, "psidot = phidot, thetadot = 0, cos = 2/5 - g/phidot^2 gives zero",
              _check_text_after_80,
              quote=r"You can check that $\dot{\psi} = \dot{\phi}$, $\dot{\theta} = 0$, and $\cos \theta = 2/5 - g/\dot{\phi}^2$ "
                    r"gives zero for the above.",
              reading="I1 = 7/5, I3 = 2/5"),
        Claim("eq-82", "Eq. 82", d, "cos(theta) = ((7/5) rho - 1 - g/phidot^2) / (2 - rho)", _check_eq82,
              quote=(r"We can now look for circular CM motions with $\dot{\psi} = \rho \dot{\phi}$.",
                     r"requires a centripetal force to the left whose torque opposes the normal force's torque, and the "
                     r"reverse for $\rho < 1$.",
                     "Seeking the first component of Eq. (80) to be zero:",
                     r"\cos \theta = \frac{\left(\frac{7}{5} \rho - 1\right) - \frac{g}{\dot{\phi}^2}}{2 - \rho}"),
              reading=f"theta constant (thetadot = 0); I1 = 7/5, I3 = 2/5; {SCALED}"),
        Claim("text-after-82", "text after Eq. 82", d, "rho from 5/4 to 1: high-spin solutions with 0 < theta < cos^-1(2/5)",
              _check_rho_ranges,
              quote=(r"So as ρ ranges from $\frac{5}{4}$ to 1, high-spin solutions with $0 < \theta < \cos^{-1}\left(\frac{2}{5}\right)$ "
                     r"are found but they have (fairly small) CM motion.",
                     r"For $\rho > \frac{5}{4}$, we can find constant θ , circular CM motions with finite $\dot{\phi}$ and "
                     r"$\theta \approx 0$."),
              reading="high spin: g/phidot^2 -> 0 in Eq. 82"),
        Claim("text-after-82b", "text after Eq. 82", d, r"smallest $\dot{\phi} + \dot{\psi} \approx 1.94 \sqrt{g}$ at $\rho = 3.5$",
              _check_minimum, "numbers", "the printed digits; mpmath 40 digits",
              quote=r"The solution with the smallest $\dot{\phi} + \dot{\psi} \approx 1.94\sqrt{g}$ occurs at $\rho = 3.5$.",
              reading="among the theta ~ 0 circles of the sentence before (cos(theta) = 1 in Eq. 82); g is the scaled g/a"),
    ]

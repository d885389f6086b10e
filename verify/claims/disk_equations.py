"""Claims of the thin disk and hoop, Eqs. 1-24 and Fig. 1: inertia, the vector equations, the frame, the rows.

Independent routes: the rows derived from the vectors (models/rolling.py, itself checked against Kane's method in
the tests), with m and R kept wherever the paper keeps them; rotation matrices for the angular velocities; the
contact force F = m (a_C + g Z) for the torques of the steady circle (Eqs. 20-21); direct integration for the
moments of inertia (Eq. 4).  The symbols and rows here are shared by :mod:`verify.claims.disk_stability` and
:mod:`verify.claims.disk_spindown`; :mod:`verify.claims.disk` lists the section's claims.
"""
from __future__ import annotations

import sympy as sp

from models import paper
from models.rolling import derive
from models.symbols import (
    frame_vectors, g, phidot, phiddot, psidot, psiddot, theta, thetadot, thetaddot, time_derivative,
)

from ..mathtext import equation, tex
from .base import TYPO, Claim, decide, definition, rows_identity
from .vectors import (
    E1, E2, E3, c, euler_angles_omega, omega_body, omega_body_dot, omega_frame, s, same,
    to_inertial, vertical_in_frame,
)

SECTION = "Thin disk and hoop (Eqs. 1-46)"
I1, I3, k = sp.symbols("I1 I3 k", positive=True)
m, R = sp.symbols("m R", positive=True)  # kept where the paper keeps them (Eqs. 7-11, 20-23, 33, 46)
RPK = -R * E2  # r_P = -R e2 (text before Eq. 5), R kept; the scaled equations take R = 1
GVEC = -g * vertical_in_frame()  # the vector g of Eq. 6 points down
HORIZONTAL_AXLE = s * E3 - c * E2  # unit vector along the horizontal projection of e3; Z x it = e1

SCALED = "I <- I/(m R^2) and g <- g/R, as the paper states before Eq. 12 (so m = R = 1)"
OMEGA_DOT = "omega_dot_i are the time derivatives of the components of omega (Eq. 16)"


def disk_rows():
    """Derived Newton-Euler rows of the thin body, per unit mass, R = 1 (LHS - RHS)."""
    return derive(I1, I3, sp.Integer(-1), sp.Integer(0)).rows


def disk_rows_kept():
    """The same rows with R kept: I1, I3 per unit mass (units of length^2), g in length/time^2."""
    return derive(I1, I3, -R, sp.Integer(0)).rows


def inertia_matrix():
    """The inertia tensor diag(I1, I1, I3) of a body symmetric about e3 (Eq. 4 without its stray 1), per unit mass."""
    return sp.diag(I1, I1, I3)


def _vector_identity(id, source, statement, printed_minus, derived=None, quote="", reading=None):
    body = "thin disk (general I1, I3)" + (", m and R kept" if derived is not None else ", R = 1")
    return rows_identity(id, source, SECTION, statement, printed_minus, derived or disk_rows, body,
                         quote=quote, reading=reading)


# --- Eq. 4: inertia -------------------------------------------------------------------

def _inertia_integrals():
    r, a, R_ = sp.symbols("r a R", positive=True)
    x, y = r * sp.cos(a), r * sp.sin(a)
    disk = lambda f: sp.integrate(sp.integrate(f * r, (r, 0, R_)), (a, 0, 2 * sp.pi)) / (sp.pi * R_**2)
    hoop = lambda f: sp.integrate(f.subs(r, R_), (a, 0, 2 * sp.pi)) / (2 * sp.pi)
    out = {}
    for name, avg in (("disk", disk), ("hoop", hoop)):
        out[name] = sp.Matrix([[avg(y**2), -avg(x * y), 0], [-avg(x * y), avg(x**2), 0], [0, 0, avg(x**2 + y**2)]]) / R_**2
    return out


def _check_eq4_bodies():
    got = _inertia_integrals()
    printed = {"disk": sp.Rational(1, 4) * sp.diag(1, 1, 2), "hoop": sp.Rational(1, 2) * sp.diag(1, 1, 2)}
    printed_k = {"disk": sp.Rational(1, 4), "hoop": sp.Rational(1, 2)}
    ok = all(same(got[n], printed[n]) and same(2 * got[n][0, 0], got[n][2, 2]) and same(got[n][0, 0], printed_k[n])
             for n in got)
    return decide(ok, "; ".join(f"{n}: {tex(mat)}" for n, mat in got.items()),
                  "; ".join(f"{n}: {tex(mat)}" for n, mat in printed.items()),
                  "moments of a uniform disk and hoop by integration over the body, in units of $m R^2$; "
                  "$2 I_1 = I_3$ for both and $I_1 = k m R^2$ with $k = 1/4$ (disk), $1/2$ (hoop)")


def _check_eq4_general():
    got = _inertia_integrals()["disk"]
    printed_entry = sp.Integer(1)  # the printed matrix has a 1 in row 1, column 2
    ok = same(got[0, 1], printed_entry)
    return decide(ok, f"{equation(sp.Symbol('I_12'), got[0, 1])} (product of inertia of a body symmetric about "
                      r"$\mathbf{e}_3$)", "$I_{12} = 1$",
                  "the printed general matrix has a stray 1 in row 1, column 2",
                  correction=equation(sp.Symbol("I"), inertia_matrix()))


# --- Eqs. 7-12: the vector equations -------------------------------------------------------

def _check_eq7():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    v = -w.cross(RPK)
    e1, e2, e3 = frame_vectors()
    a_inertial = to_inertial(v).applyfunc(time_derivative)
    a_123 = sp.Matrix([a_inertial.dot(e) for e in (e1, e2, e3)])
    printed = -wd.cross(RPK) + Om.cross(v)
    ok = same(a_123, printed)
    return decide(ok, r"$\frac{d}{dt}$ of the inertial components of $v_C = -\omega \times r_P$, projected on "
                      r"$\mathbf{e}_1, \mathbf{e}_2, \mathbf{e}_3$ ($R$ kept)",
                  r"$-\dot{\omega} \times r_P + \Omega \times v_C$", "the inertial acceleration of C for a contact vector fixed in the 1-2-3 frame")


def _eq8():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    I = m * inertia_matrix()  # the body's inertia; Eq. 9 renames I <- I/m
    v = -w.cross(RPK)
    return I * wd + Om.cross(I * w) - m * RPK.cross(-wd.cross(RPK) + Om.cross(v) - GVEC)


def _eq9():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    return inertia_matrix() * wd + Om.cross(inertia_matrix() * w) - RPK.cross(-wd.cross(RPK) + Om.cross(RPK.cross(w)) - GVEC)


def _eq10():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    return inertia_matrix() * wd + RPK.cross(wd.cross(RPK)) - (-Om.cross(inertia_matrix() * w) + RPK.cross(Om.cross(RPK.cross(w)) - GVEC))


def _eq11():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    return inertia_matrix() * wd + R**2 * wd - R**2 * wd[1] * E2 - (-Om.cross(inertia_matrix() * w) + RPK.cross(R * Om[1] * w - GVEC))


def _eq12():
    w, wd, Om = omega_body(), omega_body_dot(), omega_frame()
    return inertia_matrix() * wd + wd - wd[1] * E2 - (-Om.cross(inertia_matrix() * w) - E2.cross(Om[1] * w) - E1 * c * g)


# --- Eqs. 13-16 ---------------------------------------------------------------------------

def _check_eq14():
    _, _, Om = euler_angles_omega()
    printed = sp.Matrix([thetadot, phidot * s, phidot * c])
    return decide(same(Om, printed), equation(sp.Symbol("Omega"), Om), equation(sp.Symbol("Omega"), printed),
                  r"frame rate from $R_z(\phi) R_x(\theta)$")


def _check_eq16():
    _, w, _ = euler_angles_omega()
    printed = sp.Matrix([thetadot, phidot * s, phidot * c + psidot])
    return decide(same(w, printed), equation(sp.Symbol("omega"), w), equation(sp.Symbol("omega"), printed),
                  r"body rate from $R_z(\phi) R_x(\theta) R_z(\psi)$")


def _check_fig1():
    frame, _, _ = euler_angles_omega()
    e1, e2 = frame[:, 0], frame[:, 1]
    horizontal = same(e1[2], 0)
    # P is the lowest point of the rim C + R (cos(b) e1 + sin(b) e2): height R sin(b) sin(theta), least at b = -pi/2
    b = sp.Symbol("b")
    height = (sp.cos(b) * e1 + sp.sin(b) * e2)[2]
    lowest = same(height.subs(b, -sp.pi / 2), -s) and same(sp.diff(height, b).subs(b, -sp.pi / 2), 0) \
        and same(sp.diff(height, b, 2).subs(b, -sp.pi / 2), s)
    # rolling with phidot = thetadot = 0 at any theta: v_C = -R psidot e1
    w = omega_body().subs({phidot: 0, thetadot: 0})
    v = -w.cross(RPK)
    trailing = same(v, -R * psidot * E1)
    ok = horizontal and lowest and trailing
    return decide(ok, r"$\mathbf{e}_1$ horizontal; $P = C - R \mathbf{e}_2$ is the lowest point of the rim "
                      r"($0 < \theta < \pi$), so $\mathbf{e}_2$ points from $P$ to $C$; rolling with "
                      rf"$\dot{{\phi}} = \dot{{\theta}} = 0$ gives {equation(sp.Symbol('v_C'), v)} "
                      r"(along $-\mathbf{e}_1$ for $\dot{\psi} > 0$)",
                  r"1 parallel to the plane and trailing if $\dot{\psi} > 0$; 2 away from $P$",
                  r"from the rotation matrices and $v_C = -\omega \times r_P$")


# --- Eqs. 17-24 ---------------------------------------------------------------------------

def _check_eq17():
    ok = same(paper.eq17_rows(I1, I3), disk_rows())
    return decide(ok, "derived rows (general I1, I3)", "Eq. 17 as printed", "row-by-row identity")


def _check_eq18():
    rows = derive(k, 2 * k, sp.Integer(-1), sp.Integer(0)).rows
    ok = same(paper.eq18_rows(k), rows)
    return decide(ok, "derived rows with I1 = k, I3 = 2k", "Eq. 18 as printed", "row-by-row identity")


def _eq18_sides():
    """The printed lhs and rhs of Eq. 18 (the rows of models.paper are lhs - rhs)."""
    wd = omega_body_dot()
    lhs = sp.Matrix([(k + 1) * wd[0], k * wd[1], (2 * k + 1) * wd[2]])
    return lhs, lhs - paper.eq18_rows(k)


def _check_knife_edge():
    lhs, rhs = _eq18_sides()
    upright = {theta: sp.pi / 2, thetadot: 0}
    constant_rates = {thetaddot: 0, phiddot: 0, psiddot: 0}
    rhs0 = rhs.subs(upright)
    straight, diameter = rhs0.subs(phidot, 0), rhs0.subs(psidot, 0)
    still = lhs.subs(constant_rates).subs(upright)  # constant rates: the lhs vanishes too, so both are solutions
    ok = same(straight, sp.zeros(3, 1)) and same(diameter, sp.zeros(3, 1)) and same(still, sp.zeros(3, 1))
    return decide(ok, r"printed rhs of Eq. 18 at $\theta = \pi/2$, $\dot{\theta} = 0$: "
                      rf"$\dot{{\phi}} = 0$ gives {tex(straight)}, $\dot{{\psi}} = 0$ gives {tex(diameter)}; "
                      f"the lhs at constant rates is {tex(still)}",
                  "the rhs of Eq. 18 is zero", "both motions solve Eq. 18")


def _check_eq19():
    w = omega_body().subs(thetadot, 0)
    L = inertia_matrix() * w
    alpha = theta - sp.pi / 2
    printed = I3 * (psidot + phidot * c) * sp.cos(alpha) + I1 * phidot * s * sp.sin(alpha)
    ok = same(L.dot(HORIZONTAL_AXLE), printed) and same(L.dot(vertical_in_frame().cross(HORIZONTAL_AXLE)), 0)
    return decide(ok, r"$L \cdot (\sin\theta \, \mathbf{e}_3 - \cos\theta \, \mathbf{e}_2)$ with $\dot{\theta} = 0$ "
                      "($L$ has no other horizontal part)", equation(sp.Symbol("L_perp"), printed),
                  "the horizontal component of L = I.w when theta is constant, along the horizontal projection of the axle")


def _steady_disk():
    """Steady circle (theta, rates constant), m and R kept: contact force, torque about C and dL/dt."""
    w, Om = omega_body().subs(thetadot, 0), omega_frame().subs(thetadot, 0)
    v = -w.cross(RPK)
    a = Om.cross(v)  # the 1-2-3 components of v_C are constant
    force = m * (a + g * vertical_in_frame())
    L = m * inertia_matrix() * w  # I1, I3 per unit mass: L = (body inertia) . w
    return v, a, force, RPK.cross(force), Om.cross(L), L.dot(HORIZONTAL_AXLE)


def _check_eq20():
    rho = sp.Symbol("rho", positive=True)
    alpha = theta - sp.pi / 2
    v, a, force, torque, dL, L_perp = _steady_disk()
    on_circle = {psidot: rho * phidot / R}
    printed = m * g * R * sp.sin(alpha) - m * (rho - R * sp.sin(alpha)) * phidot**2 * R * sp.cos(alpha)
    out_of_page = same(dL, L_perp * phidot * E1)  # dL/dt = L_perp phidot e1: e1 is "out of the page"
    torque_ok = same(torque.subs(on_circle), printed * E1)
    normal = same(force.dot(vertical_in_frame()), m * g)
    centripetal = same(a.dot(a).subs(on_circle), ((rho - R * sp.sin(alpha)) * phidot**2) ** 2) \
        and same(a.dot(vertical_in_frame()), 0)
    # the contact point moves with v_C + Omega x r_P = -(w - Omega) x r_P: speed R |psidot| = rho |phidot|
    vP = -(omega_body() - omega_frame()).cross(RPK)
    path = same(vP.dot(vP), R**2 * psidot**2)
    ok = out_of_page and torque_ok and normal and centripetal and path
    return decide(ok, r"$r_P \times m (a_C + g Z)$ with $\dot{\psi} = \rho \dot{\phi} / R$: "
                      f"{tex(sp.simplify(torque.subs(on_circle)))}; "
                      r"$\frac{dL}{dt} = \Omega \times L = L_\perp \dot{\phi} \, \mathbf{e}_1$",
                  r"$\Gamma = m g R \sin\alpha - m (\rho - R \sin\alpha) \dot{\phi}^2 R \cos\alpha$, out of the page",
                  rf"$\alpha = \theta - \pi/2$; steps: $\frac{{dL}}{{dt}}$ along $\mathbf{{e}}_1$ {out_of_page}, "
                  rf"torque {torque_ok}, $N = m g$ {normal}, centripetal $m (\rho - R \sin\alpha) \dot{{\phi}}^2$ "
                  rf"{centripetal}, path lengths $R \dot{{\psi}} = \rho \dot{{\phi}}$ {path}")


def _check_eq21():
    rho = sp.Symbol("rho", positive=True)
    steady = {thetaddot: 0, thetadot: 0}
    row1_kept = disk_rows_kept()[0].subs(steady)  # per unit mass, R kept
    row1 = disk_rows()[0].subs(steady)
    # line 1: the body's moments m I1, m I3 (I1, I3 per unit mass), m and R kept
    line1 = (-m * g * R * c - m * (rho + R * c) * phidot**2 * R * s) \
        - (m * I3 * (psidot + phidot * c) * s - m * I1 * phidot * s * c) * phidot
    line2 = (-g * c - (psidot + phidot * c) * phidot * s) - (I3 * (psidot + phidot * c) - I1 * phidot * c) * phidot * s
    line3 = -g * c - (psidot * (1 + I3) + (1 + I3 - I1) * phidot * c) * phidot * s
    steps = (same(line1.subs(rho, R * psidot / phidot), -m * row1_kept), same(line2, -row1), same(line3, -row1))
    return decide(all(steps), "derived row 1 at $\\theta$ = const: " + equation(sp.simplify(-row1), 0) + " (scaled), and "
                  "$m$ times the same row with $R$ kept", "Eq. 21, three lines",
                  r"line 1 ($m$, $R$ kept, $\dot{\psi} = \rho \dot{\phi} / R$) = $m$ × derived row; lines 2 and 3 = "
                  rf"derived row (scaled); steps {steps}; the row is component 1 of Eq. 17 with $\dot{{\omega}}_1 = 0$")


def _check_eq22_24():
    alpha = sp.Symbol("alpha")
    tipping = {phidot: 0, psidot: 0}
    acc = [e.subs(tipping) for e in derive(I1, I3, -R, sp.Integer(0)).accelerations]  # per unit mass, R kept
    acc_scaled = derive(I1, I3, sp.Integer(-1), sp.Integer(0)).accelerations[0].subs(tipping)
    stays = same(acc[1], 0) and same(acc[2], 0)  # phidot = psidot = 0 persists: a pure tip
    # the body's moment is m I1; alpha = theta - pi/2, so alpha'' = theta'' = w1' (Eq. 16 with phidot = 0)
    eq22 = sp.solve(sp.Eq((m * I1 + m * R**2) * sp.Symbol("a2"), m * g * R * sp.sin(alpha)), sp.Symbol("a2"))[0]
    eq23 = -m * g * R * c / (m * I1 + m * R**2)
    eq24 = -g * c / (I1 + 1)
    steps = (same(eq22.subs(alpha, theta - sp.pi / 2), acc[0]), same(eq23, acc[0]), same(eq24, acc_scaled))
    ok = stays and all(steps)
    return decide(ok, r"derived $\ddot{\theta}$ with $\dot{\phi} = \dot{\psi} = 0$ ($m$, $R$ kept): "
                      f"{equation(thetaddot, sp.simplify(acc[0]))}; scaled: {equation(thetaddot, acc_scaled)}",
                  r"$(I_1 + m R^2) \ddot{\alpha} = m g R \sin\alpha$; $(I_1 + m R^2) \dot{\omega}_1 = -m g R \cos\theta$; "
                  r"$(I_1 + 1) \dot{\omega}_1 = -g \cos\theta$",
                  r"$\alpha = \theta - \pi/2$ so $\sin\alpha = -\cos\theta$; $\ddot{\phi} = \ddot{\psi} = 0$ there "
                  f"({stays}); Eqs. 22, 23, 24: {steps}")


def claims() -> list:
    """The claims of Eqs. 1-24 and Fig. 1, in the paper's order."""
    d = SECTION
    return [
        definition("eq-1", "Eq. 1", d, "x = R cos(theta)", "an example of a holonomic constraint (a definition)",
                   quote=r"x = R \cos \theta"),
        definition("eq-2", "Eq. 2", d, "y = R sin(theta)", "an example of a holonomic constraint (a definition)",
                   quote=r"y = R \sin \theta"),
        definition("eq-3", "Eq. 3", d, "z = 0", "an example of a holonomic constraint (a definition)",
                   quote=r"$$z = 0 \quad (3)$$"),
        Claim("eq-4-bodies", "Eq. 4 (disk, hoop)", d, "I_disk = (1/4) m R^2 diag(1,1,2), I_hoop = (1/2) m R^2 diag(1,1,2)",
              _check_eq4_bodies, "algebra",
              quote=(r"Note that since $2I_1 = I_3$ for plane symmetric figures, different I can be parametrized by the "
                     r"fraction in front of mR^2 : $k = \frac{1}{2}$ for a hoop; $k = \frac{1}{4}$ for a disk.",
                     r"\mathbf{I}_{\text{disk}} = \frac{1}{4} mR^2 \begin{pmatrix} 1 & 0 & 0 \\ 0 & 1 & 0 \\ 0 & 0 & 2 \end{pmatrix}",
                     r"\mathbf{I}_{\text{hoop}} = \frac{1}{2} mR^2 \begin{pmatrix} 1 & 0 & 0 \\ 0 & 1 & 0 \\ 0 & 0 & 2 \end{pmatrix}"),
              reading="moments about the centre, axis 3 the axle (normal to the disk), 1 and 2 in its plane"),
        Claim("eq-4-general", "Eq. 4 (general)", d, "I = ((I1, 1, 0), (0, I1, 0), (0, 0, I3))", _check_eq4_general,
              "algebra", known_failure="stray 1 off the diagonal", severity=TYPO,
              quote=r"\mathbf{I} = \begin{pmatrix} I_1 & 1 & 0 \\ 0 & I_1 & 0 \\ 0 & 0 & I_3 \end{pmatrix}"),
        definition("eq-5", "Eq. 5", d, "dL/dt|_123 + Omega x L = r_P x F",
                   "Euler's law in a rotating frame (a law, used by the derivation; its consequences are checked from Eq. 8 on)",
                   quote=r"\left. \frac{d\mathbf{L}}{dt} \right|_{123} + \boldsymbol{\Omega} \times \mathbf{L} = \mathbf{r}_P \times \mathbf{F}"),
        definition("eq-6", "Eq. 6", d, "m (dv_C/dt|_123 + Omega x v_C) = F + m g",
                   "Newton's law in a rotating frame (a law; its consequences are checked from Eq. 7 on)",
                   quote=r"m\dot{\mathbf{v}}_C = m \left(\left. \frac{d\mathbf{v}_C}{dt} \right|_{123} + \mathbf{\Omega} \times \mathbf{v}_C \right) = \mathbf{F} + m\mathbf{g}"),
        Claim("eq-7", "Eq. 7", d, "m(-w' x r_P + Omega x v_C) = F + m g", _check_eq7,
              quote=(r"By the no-slip rolling condition: $\mathbf{v}_C = -\boldsymbol{\omega} \times \mathbf{r}_P$. Since "
                     r"\mathbf{r}_P is a constant in 123, we have:",
                     r"m(-\dot{\boldsymbol{\omega}} \times \mathbf{r}_P + \mathbf{\Omega} \times \mathbf{v}_C) = \mathbf{F} + m\mathbf{g}"),
              reading="r_P = -R e2 (text before Eq. 5), R kept; the left side is m times the acceleration of C"),
        _vector_identity("eq-8", "Eq. 8", "I.w' + Omega x L = m r_P x (-w' x r_P + Omega x v_C - g)", _eq8,
                         lambda: m * disk_rows_kept(),
                         quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + \mathbf{\Omega} \times \mathbf{L} = m\mathbf{r}_P \times (-\dot{\boldsymbol{\omega}} \times \mathbf{r}_P + \mathbf{\Omega} \times \mathbf{v}_C - \mathbf{g})",
                         reading="I the body's inertia (m times the per-unit-mass diag(I1, I1, I3)), L = I.w, "
                                 "v_C = -w x r_P, r_P = -R e2; m and R kept"),
        _vector_identity("eq-9", "Eq. 9", "I.w' + Omega x (I.w) = r_P x (-w' x r_P + Omega x (r_P x w) - g)", _eq9,
                         disk_rows_kept,
                         quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + \mathbf{\Omega} \times (\mathbf{I} \cdot \boldsymbol{\omega}) = \mathbf{r}_P \times (-\dot{\boldsymbol{\omega}} \times \mathbf{r}_P + \mathbf{\Omega} \times (\mathbf{r}_P \times \boldsymbol{\omega}) - \mathbf{g})",
                         reading="I <- I/m, as the paper states before Eq. 9; R kept"),
        _vector_identity("eq-10", "Eq. 10", "I.w' + r_P x (w' x r_P) = -Omega x (I.w) + r_P x (Omega x (r_P x w) - g)",
                         _eq10, disk_rows_kept,
                         quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + \mathbf{r}_P \times (\dot{\boldsymbol{\omega}} \times \mathbf{r}_P) = -\mathbf{\Omega} \times (\mathbf{I} \cdot \boldsymbol{\omega}) + \mathbf{r}_P \times (\mathbf{\Omega} \times (\mathbf{r}_P \times \boldsymbol{\omega}) - \mathbf{g})",
                         reading="I per unit mass (I <- I/m before Eq. 9); R kept"),
        _vector_identity("eq-11", "Eq. 11", "I.w' + R^2 w' - R^2 w2' e2 = -Omega x (I.w) + r_P x (R Omega2 w - g)", _eq11,
                         disk_rows_kept,
                         quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + R^2\dot{\boldsymbol{\omega}} - R^2\dot{\omega}_2\mathbf{e}_2 = -\mathbf{\Omega} \times (\mathbf{I} \cdot \boldsymbol{\omega}) + \mathbf{r}_P \times (R\mathbf{\Omega}_2\boldsymbol{\omega} - \mathbf{g})",
                         reading="I per unit mass (I <- I/m before Eq. 9); R kept"),
        _vector_identity("eq-12", "Eq. 12", "I.w' + w' - w2' e2 = -Omega x (I.w) - e2 x Omega2 w - e1 cos(theta) g", _eq12,
                         quote=r"\mathbf{I} \cdot \dot{\boldsymbol{\omega}} + \dot{\boldsymbol{\omega}} - \dot{\omega}_2\mathbf{e}_2 = -\mathbf{\Omega} \times (\mathbf{I} \cdot \boldsymbol{\omega}) - \mathbf{e}_2 \times \mathbf{\Omega}_2\boldsymbol{\omega} - \mathbf{e}_1 \cos\theta g",
                         reading="I <- I/R^2 and g <- g/R, as the paper states before Eq. 12 (so R = 1)"),
        definition("eq-13", "Eq. 13", d, "Omega = (thetadot, 0, 0) + M_theta^-1 (0, 0, phidot)",
                   "the construction whose result Eq. 14 states (checked there)",
                   quote=r"\mathbf{\Omega} = \begin{pmatrix} \dot{\theta} \\ 0 \\ 0 \end{pmatrix} + \mathcal{M}_\theta^{-1} \begin{pmatrix} 0 \\ 0 \\ \dot{\phi} \end{pmatrix}"),
        Claim("eq-14", "Eq. 14", d, "Omega = (thetadot, phidot sin(theta), phidot cos(theta))", _check_eq14,
              quote=r"= (\dot{\theta}, \dot{\phi} \sin\theta, \dot{\phi} \cos\theta) \quad (14)",
              reading="components along e1, e2, e3 of the 3-1-3 (phi, theta, psi) frame of Fig. 1"),
        definition("eq-15", "Eq. 15", d, "omega = (0,0,psidot) + (thetadot,0,0) + M_theta^-1 (0,0,phidot)",
                   "the construction whose result Eq. 16 states (checked there)",
                   quote=r"\boldsymbol{\omega} = \begin{pmatrix} 0 \\ 0 \\ \dot{\psi} \end{pmatrix} + \begin{pmatrix} \dot{\theta} \\ 0 \\ 0 \end{pmatrix} + \mathcal{M}_\theta^{-1} \begin{pmatrix} 0 \\ 0 \\ \dot{\phi} \end{pmatrix}"),
        Claim("eq-16", "Eq. 16", d, "omega = (thetadot, phidot sin(theta), phidot cos(theta) + psidot)", _check_eq16,
              quote=r"= (\dot{\theta}, \dot{\phi} \sin(\theta), \dot{\phi} \cos(\theta) + \dot{\psi}) \quad (16)",
              reading="components along e1, e2, e3 of the 3-1-3 (phi, theta, psi) frame of Fig. 1"),
        Claim("fig-1", "Fig. 1", d, "Axis 3 is the axle; 1 is parallel to the plane and trailing if psidot > 0; 2 points away from P",
              _check_fig1,
              quote=r"Axis 3 is in the direction of the disk’s axle; 1 is always parallel to the plane and in the trailing "
                    r"direction if $\dot{\psi} > 0$; 2 points away from the contact point P .",
              reading="'trailing': opposite to the velocity of C when the disk rolls with phidot = thetadot = 0"),
        Claim("eq-17", "Eq. 17", d, "equations of motion of the thin disk, general I1, I3", _check_eq17,
              quote=r"\begin{pmatrix} (I_1 + 1) \dot{\omega}_1 \\ I_1 \dot{\omega}_2 \\ (I_3 + 1) \dot{\omega}_3 \end{pmatrix} = \begin{pmatrix} -(\dot{\psi}(1 + I_3) + \dot{\phi}(1 + I_3 - I_1) \cos\theta) \dot{\phi} \sin\theta - g \cos\theta \\ \dot{\theta}(\dot{\psi}I_3 + \dot{\phi}(I_3 - I_1) \cos\theta) \\ \dot{\phi} \dot{\theta} \sin\theta \end{pmatrix}",
              reading=f"{SCALED}; {OMEGA_DOT}"),
        Claim("eq-18", "Eq. 18", d, "equations of motion with I1 = k, I3 = 2k", _check_eq18,
              quote=r"\begin{pmatrix} (k + 1) \dot{\omega}_1 \\ k \dot{\omega}_2 \\ (2k + 1) \dot{\omega}_3 \end{pmatrix} = \begin{pmatrix} -(\dot{\psi}(2k + 1) + \dot{\phi}(k + 1) \cos\theta) \dot{\phi} \sin\theta - g \cos\theta \\ k \dot{\theta}(2\dot{\psi} + \dot{\phi} \cos\theta) \\ \dot{\phi} \dot{\theta} \sin\theta \end{pmatrix}",
              reading=f"{SCALED}; {OMEGA_DOT}"),
        Claim("text-knife-edge", "text after Eq. 18", d, "on a knife edge (theta = pi/2), straight-line rolling and spinning "
              "on a diameter make the rhs of Eq. 18 zero", _check_knife_edge,
              quote=r"$\theta = \pi/2$, and either straight-line rolling ($\dot{\psi} \neq 0, \dot{\phi} = 0$) or spinning on "
                    r"a diameter ($\dot{\psi} = 0, \dot{\phi} \neq 0$)...yes the rhs of Eq. (18) is zero.",
              reading="theta held at pi/2 (thetadot = 0), the rates constant"),
        Claim("eq-19", "Eq. 19", d, "L_perp = I3 (psidot + phidot cos) cos(alpha) + I1 phidot sin(theta) sin(alpha)", _check_eq19,
              quote=(r"L_{\perp} = I_3(\dot{\psi} + \dot{\phi} \cos \theta) \cos \alpha + I_1 \dot{\phi} \sin \theta \sin \alpha",
                     r"Note that $\theta = \alpha + \pi/2$ so $\sin \alpha = -\cos \theta$ and $\cos \alpha = \sin \theta$"),
              reading="theta constant (Fig. 2); L_perp is the component of L along the horizontal projection of the axle e3"),
        Claim("eq-20", "Eq. 20", d, "Gamma = m g R sin(alpha) - m (rho - R sin(alpha)) phidot^2 R cos(alpha), out of the page",
              _check_eq20,
              quote=(r"the vertical component of the contact force: $N = mg$. The horizontal contact force must provide the "
                     r"centripetal force to move the CM in a circle of radius $\rho - R \sin \alpha$.",
                     r"$d\mathbf{L}/dt$ is then out of the page with magnitude $L_{\perp} \dot{\phi}$. The net torque (out of the page) is:",
                     r"\Gamma = mgR \sin \alpha - m(\rho - R \sin \alpha) \dot{\phi}^2 R \cos \alpha",
                     r"$\dot{\psi} = \rho \dot{\phi} / R$ which is required by the equality of the path lengths: $\rho \dot{\phi} = R \dot{\psi}$."),
              reading="alpha = theta - pi/2 (text after Eq. 20); 'out of the page' is the direction e1 of dL/dt = Omega x L; "
                      "the contact force is F = m (a_C + g Z) for the steady circle; m, R and the body's moments kept"),
        Claim("eq-21", "Eq. 21", d, "the torque balance of the steady circle, reducing to component 1 of Eq. 17", _check_eq21,
              quote=(r"\begin{aligned} -mgR \cos \theta - m(\rho + R \cos \theta) \dot{\phi}^2 R \sin \theta &= \left(I_3(\dot{\psi} + \dot{\phi} \cos \theta) \sin \theta - I_1 \dot{\phi} \sin \theta \cos \theta \right) \dot{\phi} \\ -g \cos \theta - (\dot{\psi} + \dot{\phi} \cos \theta) \dot{\phi} \sin \theta &= \left(I_3(\dot{\psi} + \dot{\phi} \cos \theta) - I_1 \dot{\phi} \cos \theta \right) \dot{\phi} \sin \theta \\ -g \cos \theta - (\dot{\psi}(1 + I_3) + (1 + I_3 - I_1) \dot{\phi} \cos \theta) \dot{\phi} \sin \theta &= 0 \end{aligned}",
                     r"(In the second line we make the replacements $I \leftarrow I/mR^2$, $g \leftarrow g/R$, and "
                     r"$\dot{\psi} = \rho \dot{\phi} / R$.)",
                     "Compare to component 1 of Eq. (17)."),
              reading="line 1 with the body's moments I1, I3, m and R kept, and psidot = rho phidot / R (text after Eq. 20); "
                      "lines 2-3 scaled as the parenthesis says"),
        Claim("eq-22-24", "Eqs. 22-24", d, "(I1 + mR^2) alpha'' = mgR sin(alpha), i.e. (I1 + 1) w1' = -g cos(theta)",
              _check_eq22_24,
              quote=(r"(I_1 + mR^2) \ddot{\alpha} = mgR \sin \alpha", r"(I_1 + mR^2) \dot{\omega}_1 = -mgR \cos \theta",
                     r"(I_1 + 1) \dot{\omega}_1 = -g \cos \theta", "where in the last line we have scaled out mR^2 ."),
              reading="phidot = psidot = 0 (a disk tipping over); alpha = theta - pi/2 as after Eq. 20; I1 the body's moment "
                      "about the centre; m and R kept in Eqs. 22-23"),
    ]

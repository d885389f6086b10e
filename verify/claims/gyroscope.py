"""Claims of the gyroscope and effective-Lagrangian part (Eqs. 83-100, numbers in Figs. 15-16).

Independent routes: kinetic and potential energies from the vectors with m and a kept;
Legendre transform and series by sympy; the rolling balls' own equations (models/rolling.py)
for what the effective Lagrangian is compared with; roots with mpmath.
"""
from __future__ import annotations

import mpmath
import sympy as sp

from models import effective, hurricane, paper
from models.common import PAPER_G
from models.symbols import g, phidot, psidot, theta, thetadot, thetaddot, time_derivative

from ..mathtext import equation, latex, tex
from .base import TYPO, Claim, decide, definition
from .hurricane import _cos_on_circle
from .vectors import E3, c, omega_body, s, same, vertical_in_frame

SECTION = "Gyroscope and effective Lagrangian (Eqs. 83-100)"
I1, I3 = hurricane.I1, hurricane.I3  # in units of 2 m a^2 (Eq. 64)
m, a = sp.symbols("m a", positive=True)  # m is the mass of one ball (Eq. 64), a the balls' radius
NUMBERS = {I1: sp.Rational(7, 5), I3: sp.Rational(2, 5)}
J1, pf, pp = sp.symbols("J1 p_phi p_psi", positive=True)  # J1: the I1 of Eqs. 87-93, i.e. I1~ with the tilde dropped
TILDES = "tildes dropped (text after Eq. 86): I1 stands for I1~ = I1 + 4 and g for g~, both in units of 2 m a^2"


T_ROT = sp.Symbol("T_rot")


def _body_inertia():
    return 2 * m * a**2 * sp.diag(I1, I1, I3)


def _check_eq83():
    w = omega_body()
    T = (I1 * (w[0] ** 2 + w[1] ** 2) + I3 * w[2] ** 2) / 2
    printed = I1 * (phidot**2 * s**2 + thetadot**2) / 2 + I3 * (phidot * c + psidot) ** 2 / 2
    return decide(same(T, printed), equation(T_ROT, T), equation(T_ROT, printed),
                  r"$\frac{1}{2} \omega \cdot I \cdot \omega$ with $\omega$ from the rotation matrices (Eq. 16)")


def _gyroscope_energies():
    """T_rot, T_CM and V of the gyroscope, m and a kept: the pivot r_B = -2a e3 from C is fixed."""
    w = omega_body()
    d = 2 * a * E3  # C relative to the pivot
    v = w.cross(d)
    T_rot = w.dot(_body_inertia() * w) / 2
    T_cm = 2 * m * v.dot(v) / 2  # mass 2m
    V = 2 * m * g * d.dot(vertical_in_frame())  # height of C above the pivot
    return T_rot, T_cm, V


def _check_eq84_85():
    _, T_cm, V = _gyroscope_energies()
    printed84 = sp.Rational(1, 2) * 2 * m * (2 * a) ** 2 * (phidot**2 * s**2 + thetadot**2)
    printed85 = 2 * m * 2 * a * g * c
    ok = same(T_cm, printed84) and same(V, printed85)
    return decide(ok, f"{equation(sp.Symbol('T_CM'), sp.factor(T_cm))}, {equation(sp.Symbol('V'), V)}",
                  r"$\frac{1}{2} 2m (2a)^2 (\dot{\phi}^2 \sin^2\theta + \dot{\theta}^2)$, $2m \, 2a \, g \cos\theta$",
                  r"$v_C = \omega \times (2a \, \mathbf{e}_3)$ about the fixed pivot; $V = 2 m g z_C$ with $z_C$ measured "
                  "from the pivot")


def _check_eq86():
    T_rot, T_cm, V = _gyroscope_energies()
    got = sp.expand((T_rot + T_cm - V) / (2 * m * a**2))
    I1t, gt = I1 + 4, 2 * g / a  # the printed I1~ and g~
    printed = (sp.Rational(1, 2) * I1t * (phidot**2 * s**2 + thetadot**2) + sp.Rational(1, 2) * I3 * (phidot * c + psidot) ** 2
               - gt * c)
    return decide(same(got, printed), equation(sp.Symbol("L"), got),
                  r"Eq. 86 with $\tilde{I}_1 = I_1 + 4$ and $\tilde{g} = 2g/a$",
                  r"$(T_{rot} + T_{CM} - V) / (2 m a^2)$ from the vectors, $I_1$ in units of $2 m a^2$ (Eq. 64); "
                  r"$4 = 2m (2a)^2 / (2 m a^2)$")


def _tilde_lagrangian():
    return J1 * (phidot**2 * s**2 + thetadot**2) / 2 + I3 * (phidot * c + psidot) ** 2 / 2 - g * c


def _check_eq87_88():
    L = _tilde_lagrangian()
    ppsi, pphi = sp.diff(L, psidot), sp.diff(L, phidot)
    ok = same(ppsi, I3 * (phidot * c + psidot)) and same(pphi, I3 * c * (phidot * c + psidot) + J1 * phidot * s**2) \
        and same(pphi, ppsi * c + J1 * phidot * s**2)
    return decide(ok, f"{equation(pp, ppsi)}, {equation(pf, sp.expand(pphi))}", "Eqs. 87-88",
                  r"$\partial L / \partial \dot{\psi}$, $\partial L / \partial \dot{\phi}$ of Eq. 86")


def _energy_in_momenta():
    L = _tilde_lagrangian()
    E = thetadot * sp.diff(L, thetadot) + phidot * sp.diff(L, phidot) + psidot * sp.diff(L, psidot) - L
    sol = sp.solve([sp.Eq(pp, sp.diff(L, psidot)), sp.Eq(pf, sp.diff(L, phidot))], [phidot, psidot], dict=True)[0]
    return sp.simplify(E.subs(sol))


def _check_eq89_90():
    got = _energy_in_momenta()
    V90 = (pf - pp * c) ** 2 / (2 * J1 * s**2) + g * c
    printed = J1 * thetadot**2 / 2 + V90 + pp**2 / (2 * I3)
    ok = same(got, printed) and not sp.simplify(got - J1 * thetadot**2 / 2 - V90).has(theta, thetadot)
    return decide(ok, equation(sp.Symbol("E"), got), equation(sp.Symbol("E"), printed),
                  "the energy with the rates eliminated for the momenta; $V$ of Eq. 90 is the rest up to the constant "
                  r"$p_\psi^2/(2 I_3)$")


def _check_eq91_93():
    th, delta = sp.symbols("th delta", positive=True)
    V = lambda pphi: (pphi - pp * sp.cos(th)) ** 2 / (2 * J1 * sp.sin(th) ** 2) + g * sp.cos(th)
    finite = sp.limit(V(pp), th, 0) == g and sp.limit(V(pp + delta), th, 0) == sp.oo  # p_phi = p_psi, else V -> oo
    series = sp.series(V(pp), th, 0, 3).removeO()
    e91 = pp**2 / (2 * J1) * (th**2 / 4) - g * (th**2 / 2)
    e92 = th**2 / 2 * (pp**2 / (4 * J1) - g)
    w3 = omega_body()[2]
    e93 = th**2 / 2 * (I3**2 * sp.Symbol("omega3") ** 2 / (4 * J1) - g)
    steps = (finite, same(series - g, e91), same(e91, e92),
             same(e92.subs(pp, I3 * w3), e93.subs(sp.Symbol("omega3"), w3)) and same(sp.diff(_tilde_lagrangian(), psidot), I3 * w3))
    return decide(all(steps), r"series of $V$ (Eq. 90, $p_\phi = p_\psi$) to second order: "
                  f"{equation(sp.Symbol('V'), sp.expand(series))}",
                  "Eqs. 91-93",
                  r"$p_\phi = p_\psi$ keeps $V$ finite at $\theta = 0$; Eq. 91 is the series (constant $g$), Eq. 92 the same "
                  r"quadratic, Eq. 93 with $p_\psi = I_3 \omega_3$ (Eq. 87, $\omega_3$ of Eq. 16); " f"steps {steps}")


def _rolling_sleeping_threshold():
    """Least (phidot + psidot)^2 / g on the rolling balls' theta -> 0 circles (derived row 1, I1 = 7/5, I3 = 2/5)."""
    rho, sol = _cos_on_circle()
    P = sp.Symbol("P", positive=True)
    rate2 = sp.solve(sp.Eq(sol[0].subs(phidot**2, P), 1), P)[0]
    f = sp.simplify((1 + rho) ** 2 * rate2 / g)
    crit = [r for r in sp.solve(sp.diff(f, rho), rho) if r > sp.Rational(5, 4)]
    return crit[0], f.subs(rho, crit[0])


def _check_eq95():
    W = sp.Symbol("W", positive=True)  # omega3^2
    from_93 = sp.solve(sp.Eq(I3**2 * W / (4 * I1) - g, 0), W) == [4 * I1 * g / I3**2]  # Eq. 93's bracket changes sign
    got = (4 * I1 / I3**2).subs(NUMBERS)
    worse = (4 * (I1 + 4) * 2 / I3**2).subs(NUMBERS)  # I1~ = I1 + 4, g~ = 2g (units of a)
    rho_min, rolling = _rolling_sleeping_threshold()
    ok = from_93 and same(got, 35) and worse > got and got > 5 * rolling
    return decide(ok, r"Eq. 93's bracket is positive iff $\omega_3^2 > 4 I_1 g / I_3^2$ " f"({from_93}); "
                      f"$4 I_1 / I_3^2 = {got}$; with the tildes $4 (I_1 + 4) 2 / I_3^2 = {worse}$; the rolling balls' own "
                      rf"$\theta \to 0$ steady motions need only $(\dot{{\phi}} + \dot{{\psi}})^2 \geq {latex(rolling)} g$ "
                      rf"(at $\rho = {latex(rho_min)}$), i.e. $\omega_3^2 \geq {sp.N(rolling, 4)} g$, "
                      f"{sp.N(got / rolling, 3)} times less",
                  "$35 g$, way too big; the tildes make it worse",
                  r"$I_1 = 7/5$, $I_3 = 2/5$ (Eq. 64); 'too big' against the rolling balls (text after Eq. 82; Fig. 18 shows "
                  r"$\omega_3 \approx 2 \times 0.98 \sqrt{g/a}$ stable)")


def _check_pe_text():
    Z = vertical_in_frame()
    lower_centre = a * Z  # above P, at height a
    cm_above_centre = (a * E3).dot(Z)  # C is a e3 from the lower ball's centre
    height = lower_centre.dot(Z) + cm_above_centre
    pe = 2 * m * g * height  # two balls of mass m (Eq. 64)
    printed = m * g * a * c
    ok = same(pe - pe.subs(theta, sp.pi / 2), printed)  # up to a constant
    eq96 = same((pe / (2 * m * a**2)).subs(g, g * a), g * c + g)  # Eq. 96's -g cos(theta): PE per 2 m a^2, g <- g/a
    return decide(ok and same(cm_above_centre, a * c),
                  rf"$\mathrm{{PE}} = 2 m g z_C = {latex(sp.simplify(pe))}$, i.e. $2 m g a \cos\theta$ + const; "
                  rf"Eq. 96's $g \cos\theta$ is this per $2 m a^2$ ({eq96})",
                  r"$\mathrm{PE} = m g a \cos\theta$ ($C$ is $a \cos\theta$ above the lower centre, which is $a$ above the plane)",
                  r"mass $2m$ (Eq. 64: $m$ is one ball); the height $a \cos\theta$ is right, the mass is halved",
                  correction=r"$\mathrm{PE} = 2 m g a \cos\theta$ (+ constant), which is what Eq. 96 uses")


def _check_effective_height():
    r_P = a * sp.Matrix([0, -s, -1 - c])  # Eq. 63
    z = sp.simplify(-r_P.dot(vertical_in_frame()))
    zdot = time_derivative(z)
    ke = sp.Rational(1, 2) * 2 * m * zdot**2
    ok = same(z, a * (1 + c)) and same(zdot, -a * s * thetadot) and same(ke, m * a**2 * s**2 * thetadot**2)
    return decide(ok, rf"$z_C = -r_P \cdot Z = {latex(z)}$; $\dot{{z}} = {latex(zdot)}$; "
                      rf"$\frac{{1}}{{2}} (2m) \dot{{z}}^2 = {latex(ke)}$",
                  r"$\dot{z} = -a \sin\theta \, \dot{\theta}$; KE $\frac{1}{2} 2m a^2 \sin^2\theta \, \dot{\theta}^2$",
                  "$r_P$ of Eq. 63, mass $2m$")


def _effective_construction():
    """Eq. 96 assembled from the paper's stated pieces, per 2 m a^2, g <- g/a, psi = phi."""
    w = omega_body().subs(psidot, phidot)
    T_rot = w.dot(sp.diag(I1, I1, I3) * w) / 2
    z = 1 + c  # units of a
    T_vertical = time_derivative(z) ** 2 / 2  # 1/2 (2m) a^2 zdot^2 per 2 m a^2
    return T_rot + T_vertical - g * z


def _check_eq96():
    got = _effective_construction()
    printed = paper.eq96_lagrangian(I1, I3)
    return decide(same(got + g, printed), equation(sp.Symbol("L"), sp.expand(got)), "Eq. 96 (up to the constant $g$)",
                  r"$T_{rot}$ of Eq. 83 with $\dot{\psi} = \dot{\phi}$, + $\frac{1}{2} (2m) \dot{z}^2$ with "
                  r"$z_C = a (1 + \cos\theta)$, $- 2 m g z_C$, per $2 m a^2$, $g \leftarrow g/a$; this decides that Eq. 96 assembles its stated pieces, not that the construction is physics")


def _check_eq97():
    L = paper.eq96_lagrangian(I1, I3)
    printed = I1 * phidot**2 * s * c - I3 * phidot**2 * (c + 1) * s + thetadot**2 * s * c + g * s
    ddt = time_derivative(sp.diff(L, thetadot))
    ok = same(sp.diff(L, theta), printed) and same(ddt.subs({thetadot: 0, thetaddot: 0}), 0)
    return decide(ok, rf"$\frac{{\partial L}}{{\partial \theta}} = {latex(sp.diff(L, theta))}$; "
                      rf"$\frac{{d}}{{dt}} \frac{{\partial L}}{{\partial \dot{{\theta}}}} = {latex(sp.factor(ddt))}$, zero at "
                      r"$\dot{\theta} = \ddot{\theta} = 0$",
                  r"$\frac{\partial L}{\partial \theta} = \frac{d}{dt} \frac{\partial L}{\partial \dot{\theta}} = 0$",
                  r"the Euler-Lagrange $\theta$ equation of Eq. 96, at $\theta$ = constant")


def _check_eq98_100():
    acc = effective.model().accelerations[0].subs(thetadot, 0)
    C = sp.Symbol("C")
    sol = sp.solve(sp.numer(sp.together(acc)).subs(c, C), C)  # steady angle from the Euler-Lagrange equations of Eq. 96
    sol = [x for x in sol if not x.has(sp.sin(theta))]
    e98 = phidot**2 * ((I1 - I3) * c - I3) + g
    e99 = sp.solve(sp.Eq((I1 - I3) * C, I3 - g / phidot**2), C)
    e97 = I1 * phidot**2 * s * c - I3 * phidot**2 * (c + 1) * s + g * s
    ok = len(sol) == 1 and same(e97, s * e98) and same(sol[0], e99[0]) \
        and same(sol[0].subs(NUMBERS), sp.Rational(2, 5) - g / phidot**2)
    return decide(ok, "steady angle of the Euler-Lagrange equations of Eq. 96: "
                      + ", ".join(equation(c, x) for x in sol),
                  r"Eq. 98; $(I_1 - I_3) \cos\theta = I_3 - g/\dot{\phi}^2$ (Eq. 99); "
                  r"$\cos\theta = 2/5 - g/\dot{\phi}^2$ (Eq. 100)",
                  r"Eq. 97 at $\dot{\theta} = 0$ is $\sin\theta$ times Eq. 98; $I_1 - I_3 = 1$, $I_3 = 2/5$; the same steady "
                  "precession as Eq. 72")


def _check_effective_differs():
    rolling = hurricane.model().accelerations[0]
    eff = effective.model().accelerations[0].subs(psidot, phidot)
    diff = sp.simplify(sp.expand_trig(rolling.subs(psidot, phidot) - eff))
    state = {theta: sp.Rational(6, 5), thetadot: 3, phidot: 150, g: PAPER_G, **NUMBERS}
    value = sp.N(diff.subs(state), 15)
    inertia_eff = sp.diff(sp.diff(paper.eq96_lagrangian(I1, I3), thetadot), thetadot)  # coefficient of thetaddot
    inertia_81 = sp.diff(paper.eq81_lhs(I1, I3)[0], thetaddot)
    ok = diff != 0 and not same(inertia_eff, inertia_81)
    return decide(ok, rf"$\ddot{{\theta}}$ coefficient: Eq. 96 gives {tex(inertia_eff)}, Eq. 81 {tex(inertia_81)}; "
                      r"$\ddot{\theta}_\mathrm{rolling} - \ddot{\theta}_\mathrm{effective}$ at $\dot{\psi} = \dot{\phi}$ "
                      r"is nonzero (at $\theta = 1.2$, $\dot{\theta} = 3$, $\dot{\phi} = 150$: " f"{value})", "the resulting dynamics are wrong (do not match Eq. 81)",
                  "the paper's statement is that the two differ; the difference is not identically zero")


def _steady_root(rate2_over_g, bracket):
    acc = hurricane.model().accelerations[0].subs({thetadot: 0, psidot: phidot})
    f = sp.lambdify((theta, phidot, I1, I3, g), sp.numer(sp.together(acc)), "mpmath")
    pars = (mpmath.mpf(7) / 5, mpmath.mpf(2) / 5, mpmath.mpf(PAPER_G))
    return mpmath.findroot(lambda t: f(t, mpmath.sqrt(rate2_over_g * PAPER_G), *pars), bracket, solver="anderson")


def _check_fig15_16_numbers():
    """Both numbers from the derived equations, not from Eq. 72: the slow-spin limit is the rate
    whose steady angle (thetaddot = 0 at psidot = phidot) reaches pi/2, theta0 the steady angle
    at phidot^2 = 25 g (roots of the derived row 1, mpmath 30 digits)."""
    acc = hurricane.model().accelerations[0].subs({thetadot: 0, psidot: phidot})
    f = sp.lambdify((theta, phidot, I1, I3, g), sp.numer(sp.together(acc)), "mpmath")
    with mpmath.workdps(30):
        pars = (mpmath.mpf(7) / 5, mpmath.mpf(2) / 5, mpmath.mpf(PAPER_G))
        th16 = _steady_root(25, (mpmath.mpf("0.9"), mpmath.mpf("1.5")))
        th15 = _steady_root(mpmath.mpf("2.6"), (mpmath.mpf("1.4"), mpmath.mpf("1.5707")))
        slow = mpmath.findroot(lambda r: f(mpmath.pi / 2, r, *pars), (mpmath.mpf(30), mpmath.mpf(80)), solver="anderson") ** 2 / PAPER_G
    ok = abs(slow - mpmath.mpf("2.5")) < 1e-20 and abs(th16 - mpmath.mpf("1.20")) <= 0.005 and 0 < th15 < mpmath.pi / 2
    return decide(ok, rf"derived: $\theta_0$ reaches $\pi/2$ at $\dot{{\phi}}^2 = {mpmath.nstr(slow, 8)} g$; $\theta_0$ at "
                      rf"$\dot{{\phi}}^2 = 2.6 g$: {mpmath.nstr(th15, 6)} (below $\pi/2$, so a steady state exists); at "
                      rf"$\dot{{\phi}}^2 = 25 g$: {mpmath.nstr(th16, 6)}",
                  r"$\sqrt{2.6 g/a}$ near the slow spin limit $\sqrt{2.5 g/a}$; $\theta_0 = 1.20$ at $\sqrt{25 g/a}$",
                  r"roots of the derived row 1 with $\dot{\psi} = \dot{\phi}$")


def _check_fig16_limit():
    with mpmath.workdps(30):
        limit = mpmath.acos(mpmath.mpf(2) / 5)  # Eq. 72 as g/phidot^2 -> 0
        printed_expr = mpmath.cos(mpmath.mpf(2) / 5) ** 2
    ok = abs(printed_expr - mpmath.mpf("1.16")) <= 0.005
    return decide(ok, rf"$\cos^{{-1}}(2/5) = {mpmath.nstr(limit, 6)}$; $\cos^2(2/5) = {mpmath.nstr(printed_expr, 6)}$",
                  r"the limit $\cos^2(2/5) = 1.16$", r"the number 1.16 is $\cos^{-1}(2/5)$, the expression printed is not",
                  correction=r"the limit $\cos^{-1}(2/5) = 1.159$")


def claims() -> list:
    d = SECTION
    return [
        Claim("eq-83", "Eq. 83", d, "T_rot = 1/2 I1 (phidot^2 sin^2 + thetadot^2) + 1/2 I3 (phidot cos + psidot)^2", _check_eq83,
              quote=("From previous results we have the rotational KE:",
                     r"T_{rot} = \frac{1}{2} I_1 \left(\dot{\phi}^2 \sin^2(\theta) + \dot{\theta}^2 \right) + \frac{1}{2} I_3 \left(\dot{\phi} \cos(\theta) + \dot{\psi} \right)^2")),
        Claim("eq-84-85", "Eqs. 84-85", d, "T_CM = 1/2 2m (2a)^2 (phidot^2 sin^2 + thetadot^2), V = 2m 2a g cos", _check_eq84_85,
              quote=(r"a gyroscope made of hurricane balls with the bottom ball bottom ($\mathbf{r}_B = (0, 0, -2a)$) held fixed.",
                     r"T_{CM} = \frac{1}{2} 2m(2a)^2 \left(\dot{\phi}^2 \sin^2(\theta) + \dot{\theta}^2 \right)",
                     r"V = 2m2ag \cos \theta"),
              reading="m one ball's mass (Eq. 64); V measured from the pivot's height"),
        Claim("eq-86", "Eq. 86", d, "L = 1/2 I1~ (...) + 1/2 I3 (...)^2 - g~ cos(theta), I1~ = I1 + 4, g~ = 2g/a", _check_eq86,
              quote=(r"Of course we'll want to scale out the usual $2ma^2$.",
                     r"with results $\tilde{I}_1 = I_1 + 4$ (this is basically the parallel axis theorem) and $\tilde{g} = 2g/a$.",
                     r"L = \frac{1}{2} \tilde{I}_1 \left(\dot{\phi}^2 \sin^2(\theta) + \dot{\theta}^2 \right) + \frac{1}{2} I_3 \left(\dot{\phi} \cos(\theta) + \dot{\psi} \right)^2 - \tilde{g} \cos \theta"),
              reading="L per 2 m a^2, I1 and I3 in units of 2 m a^2 (Eq. 64), g the unscaled gravity"),
        Claim("eq-87-88", "Eqs. 87-88", d, "p_psi = I3 (phidot cos + psidot), p_phi = p_psi cos + I1 phidot sin^2", _check_eq87_88,
              quote=(r"p_\psi = \frac{\partial T}{\partial \dot{\psi}} = I_3 \left(\dot{\phi} \cos(\theta) + \dot{\psi} \right)",
                     r"p_\phi = \frac{\partial T}{\partial \dot{\phi}} = I_3 \cos(\theta) \left(\dot{\phi} \cos(\theta) + \dot{\psi} \right) + I_1 \dot{\phi} \sin^2(\theta) = p_\psi \cos(\theta) + I_1 \dot{\phi} \sin^2(\theta)"),
              reading=TILDES),
        Claim("eq-89-90", "Eqs. 89-90", d, "E = 1/2 I1 thetadot^2 + (p_phi - p_psi cos)^2/(2 I1 sin^2) + p_psi^2/(2 I3) + g cos",
              _check_eq89_90,
              quote=(r"E = \frac{1}{2} I_1 \dot{\theta}^2 + \frac{(p_\phi - p_\psi \cos(\theta))^2}{2I_1 \sin^2(\theta)} + \frac{p_\psi^2}{2I_3} + g \cos \theta = \frac{1}{2} I_1 \dot{\theta}^2 + V(\theta)",
                     r"V = \frac{(p_\phi - p_\psi \cos(\theta))^2}{2I_1 \sin^2(\theta)} + g \cos \theta + \text{constant}"),
              reading=TILDES),
        Claim("eq-91-93", "Eqs. 91-93", d, "V = (p_psi^2/(2 I1)) (theta^2/4) - g theta^2/2 = theta^2/2 (p_psi^2/(4 I1) - g)",
              _check_eq91_93,
              quote=(r"note $p_\phi = p_\psi$ to avoid infinite PE at $\theta = 0$. Next: Taylor expand V :",
                     r"V = \frac{p_\psi^2}{2I_1} \left(\frac{\theta^2}{4} \right) - g \left(\frac{\theta^2}{2} \right) + \text{constant}",
                     r"= \frac{\theta^2}{2} \left(\frac{p_\psi^2}{4I_1} - g \right)",
                     r"= \frac{\theta^2}{2} \left(\frac{I_3^2 \omega_3^2}{4I_1} - g \right)"),
              reading=f"{TILDES}; to second order in theta; Eqs. 92-93 take the constant of Eq. 90 so that V(0) = 0"),
        definition("eq-94", "Eq. 94", d, "(empty)", "the equation number carries no equation", quote="$$(94)$$"),
        Claim("eq-95", "Eq. 95", d, "omega3^2 > 4 I1 g / I3^2 = 35 g, way too big", _check_eq95, "numbers", "exact",
              quote=(r"one should actually use the original I_1 & g , in which case the condition becomes:",
                     r"\omega_3^2 > \frac{4I_1 g}{I_3^2} = 35g",
                     r"which is way too big. (And note using \tilde{I}_1 and \tilde{g} would have made things worse.)"),
              reading="I1 = 7/5, I3 = 2/5 (Eq. 64), g the scaled g/a; 'too big' measured against the rolling balls' own "
                      "sleeping (theta -> 0) motions"),
        Claim("text-before-96", "text before Eq. 96", d, "PE = m g a cos(theta) (C a cos(theta) above the lower centre)",
              _check_pe_text, known_failure="the mass is 2m: PE = 2 m g a cos(theta)", severity=TYPO,
              quote=r"The CM is a distance $a \cos \theta$ above the bottom ball's center which is a constant (a) above the "
                    r"plane, so PE= $mga \cos \theta$ works.",
              reading="m is the mass of one ball (Eq. 64); PE up to a constant"),
        Claim("text-before-96b", "text before Eq. 96", d, "zdot = -a sin(theta) thetadot; KE 1/2 2m a^2 sin^2 thetadot^2",
              _check_effective_height,
              quote=r"If CM can be thought of as attached to a fixed vertical wire so it can only move vertically and "
                    r"$\dot{z} = -a \sin \theta \dot{\theta}$ whose KE contribution should be "
                    r"$\frac{1}{2} 2ma^2 \sin^2 \theta \dot{\theta}^2$",
              reading="z the height of C, a (1 + cos(theta)) from Eq. 63; mass 2m"),
        Claim("eq-96", "Eq. 96", d, "the 'effective Lagrangian' assembled from T_rot (psi = phi), the vertical KE and the PE",
              _check_eq96,
              quote=(r"giving us an ‘effective Lagrangian’",
                     r"L = \frac{1}{2} I_1 \left(\dot{\phi}^2 \sin^2(\theta) + \dot{\theta}^2 \right) + \frac{1}{2} I_3 \dot{\phi}^2 (\cos(\theta) + 1)^2 + \frac{1}{2} \sin^2 \theta \dot{\theta}^2 - g \cos \theta"),
              reading="the paper's construction (psi = phi, the CM on a vertical wire), per 2 m a^2 with g <- g/a and "
                      "I1, I3 of Eq. 64 (no tildes); the potential up to a constant"),
        Claim("eq-97", "Eq. 97", d, "dL/dtheta of Eq. 96 = d/dt dL/dthetadot = 0 at theta = constant", _check_eq97,
              quote=(r"Focusing on the θ equation, and seeking a solution $\theta = \text{constant}$, we have:",
                     r"I_1 \dot{\phi}^2 \sin \theta \cos \theta - I_3 \dot{\phi}^2 (\cos \theta + 1) \sin \theta + \dot{\theta}^2 \sin \theta \cos \theta + g \sin \theta = \frac{d}{dt} \frac{\partial L}{\partial \dot{\theta}} = 0"),
              reading="L is Eq. 96; the left side is dL/dtheta (the Euler-Lagrange theta equation)"),
        Claim("eq-98-100", "Eqs. 98-100", d, "cos(theta) = 2/5 - g/phidot^2", _check_eq98_100,
              quote=(r"\dot{\phi}^2 ((I_1 - I_3) \cos \theta - I_3) + g = 0", r"(I_1 - I_3) \cos \theta = I_3 - \frac{g}{\dot{\phi}^2}",
                     r"\cos \theta = \frac{2}{5} - \frac{g}{\dot{\phi}^2}"),
              reading="thetadot = 0; I1 = 7/5, I3 = 2/5 in Eq. 100"),
        Claim("text-after-100", "text after Eq. 100", d, "the terms do not match Eq. 81, so the resulting dynamics are wrong",
              _check_effective_differs,
              quote=r"however the terms that would be on the rhs (related to $\dot{\theta}$ and $\ddot{\theta}$) do not match "
                    r"Eq. (81) so the resulting dynamics are wrong."),
        Claim("fig-15-16-numbers", "Figs. 15-16 (numbers)", d, r"slow spin limit $\sqrt{2.5 g/a}$; $\theta_0 = 1.20$ at $\sqrt{25 g/a}$",
              _check_fig15_16_numbers, "numbers", "the printed digits",
              quote=(r"with $\dot{\psi}_0 = \dot{\phi}_0 \approx \sqrt{2.6g/a}$ (i.e., near the slow spin limit "
                     r"$\dot{\phi}_0 = \sqrt{2.5g/a}$)",
                     r"$\dot{\psi}_0 = \sqrt{25g/a}$, and hence $\theta_0 = 1.20$"),
              reading="g/a = 980 s^-2; psidot = phidot; the slow spin limit is where the steady angle reaches pi/2 "
                      "(the upper ball touches)"),
        Claim("fig-16-limit", "Fig. 16 (limit)", d, "the limit cos^2(2/5) = 1.16", _check_fig16_limit, "numbers",
              "the printed digits", known_failure="cos^2 for cos^-1", severity=TYPO,
              quote=r"near the limit $\cos^2(\frac{2}{5}) = 1.16$",
              reading="the fast-spin limit of the steady angle (Eq. 72 as g/phidot^2 -> 0)"),
    ]

"""The thick ring's Chaplygin integrals in closed form (Gauss's 2F1, ``models.ring_chaplygin``) against the transport.

The derivation's steps (the module docstring) are checked by sympy one by one; the closed form's
basis is checked against the ring's own A(theta) to 1e-30 (1e-100 in the slow run); then the two routes are compared
on the same inputs along ring runs.

Tolerance of the comparison, in eps * (|c1| + |c2|) (eps the run's epsilon): 2.  Each route is
within 1 of the exact integral at the run's inputs: the transport by the bound argued in
tests/test_chaplygin.py (rounded once, 0.5, plus at most 0.5 for a transport at bits + 10), the
closed form likewise (rounded once, 0.5; mpmath's 2F1 at bits + 10, more near theta = 0, leaves it
9 guard bits for the other 0.5).  Measured: both are within 0.29 of the closed form at bits + 80 at
thetas from 1e-12 to 3.1, and along 41-point runs of both parameter sets they differ by at most 0.06
(double), 0.67 (quad) and 0 (mp:200).
"""
from __future__ import annotations

import dataclasses

import mpmath
import numpy as np
import pytest
import sympy as sp

from models import get_model
from models.ring import I1, I3, R2, R3, h, parameter_set
from models.ring_chaplygin import (THETA_REF, chaplygin_closed_form, coefficients,
                                   fundamental_solutions, hypergeometric_parameters, integrals)
from models.rolling import derive
from models.symbols import theta
from verify import solve
from verify.engine.chaplygin import chaplygin_integrals
from verify.engine.compile import compile_model
from verify.engine.single import resolve_parameters
from verify.precision import parse_precision

TOLERANCE = 2.0  # eps * (|c1| + |c2|), argued in the module docstring

# --- the derivation, step by step (sympy) ---------------------------------------------------------

z, s0, sinf = sp.symbols("z s0 sinf")
_g = sp.Function("g")


def _riemann_operator(Z, alpha, mu, p_at_zero=sp.Rational(1, 2)):
    """Step 3's equation in z applied to Z(z) (``p_at_zero``: the 1/(2z) coefficient, for the negative control)."""
    return (Z.diff(z, 2) + (p_at_zero / z + 1 / (z - 1)) * Z.diff(z)
            + (mu * (z - 1) + sp.I * alpha * (z + 1)) / (4 * z**2 * (z - 1)) * Z)


def test_the_ring_matrix_is_cot_plus_constants():
    """A(theta) of the derivation (models.rolling.derive for the ring) is [[-cot - alpha, beta], [gamma, alpha]]."""
    A = derive(I1, I3, R2, R3).chaplygin_matrix
    alpha, beta, gamma = coefficients(I1, I3, h)
    expected = sp.Matrix([[-sp.cot(theta) - alpha, beta], [gamma, alpha]])
    assert all(sp.simplify(A[i, j] - expected[i, j]) == 0 for i in range(2) for j in range(2))
    assert sp.simplify(A[0, 0] - (-alpha)) != 0  # negative control: without its cot term A00 is not matched


def test_omega3_obeys_one_second_order_equation():
    """Steps 1-2: with omega2 = (omega3' - alpha omega3)/gamma, row 2 holds identically and gamma x row 1 is
    omega3'' + cot omega3' - (alpha cot + alpha^2 + beta gamma) omega3."""
    alpha, beta, gamma = sp.symbols("alpha beta gamma")
    w3 = sp.Function("f")(theta)
    w2 = (w3.diff(theta) - alpha * w3) / gamma
    row1 = w2.diff(theta) - ((-sp.cot(theta) - alpha) * w2 + beta * w3)
    row2 = w3.diff(theta) - (gamma * w2 + alpha * w3)
    second = (w3.diff(theta, 2) + sp.cot(theta) * w3.diff(theta)
              - (alpha * sp.cot(theta) + alpha**2 + beta * gamma) * w3)
    assert sp.simplify(row2) == 0
    assert sp.simplify(gamma * row1 - second) == 0


@pytest.mark.parametrize("p_at_zero, holds", [(sp.Rational(1, 2), True), (sp.Rational(1, 3), False)])
def test_z_equals_exp_2i_theta_gives_the_riemann_equation(p_at_zero, holds):
    """Step 3: the theta equation is -4 z^2 times the z equation at z = exp(2 i theta) (a wrong 1/(3z) fails)."""
    alpha, mu = sp.symbols("alpha mu")
    W = _g(sp.exp(2 * sp.I * theta))
    in_theta = W.diff(theta, 2) + sp.cot(theta) * W.diff(theta) - (alpha * sp.cot(theta) + mu) * W
    in_z = (-4 * z**2 * _riemann_operator(_g(z), alpha, mu, p_at_zero)).subs(z, sp.exp(2 * sp.I * theta))
    assert (sp.simplify((in_theta - in_z).doit().rewrite(sp.exp)) == 0) is holds


def _alpha_mu():
    """alpha and mu in s0, sinf: s0^2 = 1 - 4 mu + 4 i alpha, sinf^2 = 1 - 4 mu - 4 i alpha, solved."""
    return (s0**2 - sinf**2) / (8 * sp.I), (2 - s0**2 - sinf**2) / 8


def test_the_exponents_at_the_three_singular_points():
    """Step 3's exponents: (1 -+ s0)/4 at 0, 0 twice at 1, (1 -+ sinf)/4 at infinity (omega3 ~ z^-rho)."""
    alpha, mu = _alpha_mu()
    p = 1 / (2 * z) + 1 / (z - 1)
    q = (mu * (z - 1) + sp.I * alpha * (z + 1)) / (4 * z**2 * (z - 1))
    x = sp.Symbol("x")
    at_zero = x * (x - 1) + sp.limit(z * p, z, 0) * x + sp.limit(z**2 * q, z, 0)
    at_one = x * (x - 1) + sp.limit((z - 1) * p, z, 1) * x + sp.limit((z - 1)**2 * q, z, 1)
    at_infinity = x * (x + 1) - sp.limit(z * p, z, sp.oo) * x + sp.limit(z**2 * q, z, sp.oo)
    assert sp.expand(16 * at_zero - (4 * x - 1 - s0) * (4 * x - 1 + s0)) == 0
    assert sp.expand(at_one) == x**2
    assert sp.expand(16 * at_infinity - (4 * x - 1 - sinf) * (4 * x - 1 + sinf)) == 0


@pytest.mark.parametrize("sign", [-1, 1])
def test_z_to_the_r_times_gauss(sign):
    """Step 4: z (1 - z) z^-r L[z^r F] is Gauss's operator with the module's (a, b, c), identically in s0, sinf."""
    alpha, mu = _alpha_mu()
    r = (1 + sign * s0) / 4
    a, b, c = (2 + sign * s0 + sinf) / 4, (2 + sign * s0 - sinf) / 4, 1 + sign * s0 / 2
    F = _g(z)
    gauss = z * (1 - z) * F.diff(z, 2) + (c - (a + b + 1) * z) * F.diff(z) - a * b * F
    lhs = z * (1 - z) * sp.powsimp(sp.expand(_riemann_operator(z**r * F, alpha, mu) / z**r))
    assert sp.simplify(sp.expand(lhs - gauss)) == 0


def test_the_module_parameters_are_the_derived_ones():
    """hypergeometric_parameters gives step 4's (r, a, b, c) with s0^2 = 1 - 4 mu + 4 i alpha, at 110 digits."""
    with mpmath.workdps(110):
        values = {k: mpmath.mpf(sp.Rational(v).p) / sp.Rational(v).q for k, v in parameter_set("annular").items()}
        hg = hypergeometric_parameters(values["I1"], values["I3"], values["h"])
        alpha, beta, gamma = coefficients(values["I1"], values["I3"], values["h"])
        mu = alpha**2 + beta * gamma
        S0, Sinf = 1 - 4 * hg.exponents_at_zero[0], 1 - 4 * hg.exponents_at_infinity[0]  # r = (1 - s0)/4, rho = (1 - sinf)/4
        tiny = mpmath.mpf(10) ** -100
        assert abs(S0**2 - (1 - 4 * mu + 4j * alpha)) < tiny and abs(Sinf**2 - (1 - 4 * mu - 4j * alpha)) < tiny
        assert abs(Sinf - mpmath.conj(S0)) < tiny
        for sign, sol in zip((-1, 1), hg.solutions):
            assert abs(sol.exponent - (1 + sign * S0) / 4) < tiny
            assert abs(sol.a - (2 + sign * S0 + Sinf) / 4) < tiny and abs(sol.b - (2 + sign * S0 - Sinf) / 4) < tiny
            assert abs(sol.c - (1 + sign * S0 / 2)) < tiny


THETAS_CHECKED = ("1e-8", "0.01", "0.3", "0.5235987755982988", "0.7", "1.2", "1.5707963", "2.4", "3.1")
WRONG_CHECKED = ("0.01", "0.3", "1.2")


@pytest.mark.parametrize("parameters, digits, step, bound", [
    ("annular", 60, "1e-18", "1e-30"),
    pytest.param("printed", 60, "1e-18", "1e-30", marks=pytest.mark.slow),
    pytest.param("annular", 200, "1e-60", "1e-100", marks=pytest.mark.slow),  # ~2 min a set: 2F1 at 200 digits
    pytest.param("printed", 200, "1e-60", "1e-100", marks=pytest.mark.slow),
])
def test_the_basis_solves_the_ring_system(parameters, digits, step, bound):
    """dM/dtheta = A(theta) M, A the derivation's own matrix (not the module's coefficients), to ``bound``
    relative at thetas across (0, pi), near the lower end, and at pi/6 (z = exp(i pi/3), where mpmath
    switches to Gosper's recurrence); and Phi = M M(theta_ref)^-1 is real.  The derivative is the central
    difference with ``step`` x min(1, theta) at ``digits`` digits (truncation ~step^2, rounding ~10^-digits /
    step, both below the bound).  Negative control: the first solution with c off by 1e-9 does not solve it."""
    exact = {k: sp.Rational(v) for k, v in parameter_set(parameters).items()}
    A_of = sp.lambdify(theta, get_model("ring").chaplygin.matrix.subs({I1: exact["I1"], I3: exact["I3"], h: exact["h"]}),
                       modules="mpmath")
    with mpmath.workdps(digits):
        values = {k: mpmath.mpf(v.p) / v.q for k, v in exact.items()}
        hg = hypergeometric_parameters(values["I1"], values["I3"], values["h"])
        first = hg.solutions[0]
        wrong = dataclasses.replace(hg, solutions=(dataclasses.replace(first, c=first.c * (1 + mpmath.mpf("1e-9"))),
                                                   hg.solutions[1]))
        step, bound = mpmath.mpf(step), mpmath.mpf(bound)
        ref_inverse = fundamental_solutions(hg, mpmath.pi / 4) ** -1

        def residuals(system, th):
            """Per column: max_i |M'_ij - (A M)_ij| / (max_i |M_ij| (1 + |A_11|))."""
            M = fundamental_solutions(system, th)
            dt = step * min(1, th)  # M varies on the scale theta near 0
            dM = (fundamental_solutions(system, th + dt) - fundamental_solutions(system, th - dt)) / (2 * dt)
            Am = mpmath.matrix(A_of(th).tolist())
            AM = Am * M
            return [max(abs(dM[i, j] - AM[i, j]) for i in range(2)) / (max(abs(M[0, j]), abs(M[1, j])) * (1 + abs(Am[0, 0])))
                    for j in range(2)], M

        for t in THETAS_CHECKED:
            th = mpmath.mpf(t)
            (r1, r2), M = residuals(hg, th)
            assert r1 <= bound and r2 <= bound, t
            if t in WRONG_CHECKED:
                assert residuals(wrong, th)[0][0] > bound, t
            Phi = M * ref_inverse
            assert max(abs(mpmath.im(Phi[i, j])) for i in range(2) for j in range(2)) < bound * mpmath.mnorm(Phi, 1)


def test_degenerate_exponents_are_refused():
    """h = 0 and I1 (1 + I3) = 4 I3 (I1 = 2, I3 = 1: exact in binary): s0 = 0, one solution only."""
    with pytest.raises(ValueError, match="s0 = 0"):
        hypergeometric_parameters(2, 1, 0)


@pytest.mark.parametrize("precision", ["double", "quad"])
def test_nearly_coincident_exponents_keep_their_digits(precision):
    """h = 0, I3 = 1, I1 = 2 + 1e-13 (s0 ~ 1e-7): with 2 log2(1/|s0|) more bits the closed form meets the
    transport within the bound; without them it was 300 (double) and 1000 (quad) eps * scale off."""
    p, model = parse_precision(precision), get_model("ring")
    params = resolve_parameters(model, {"I1": "2.0000000000001", "I3": "1", "h": "0"}, p)
    thetas, w2, w3 = p.array(["0.01", "0.3", "1.0", "1.5"]), p.array(["1", "2", "-1", "0.5"]), p.array(["0.3", "-1", "2", "1"])
    closed = chaplygin_integrals(model, p, params, thetas, w2, w3, method="closed-form")
    moved = chaplygin_integrals(model, p, params, thetas, w2, w3, method="fundamental-matrix")
    assert max(_disagreement_in_eps(p, closed, moved)) <= TOLERANCE


def test_a_nan_theta_gives_nan():
    nan = chaplygin_closed_form(mpmath.mpf("nan"), mpmath.mpf(1), mpmath.mpf(2), {"I1": 0.5, "I3": 0.87, "h": 0.43})
    assert all(mpmath.isnan(v) for v in nan)


# --- the two routes along ring runs --------------------------------------------------------------

#: Starts of ring runs: near the steady diameter spin (theta 1.03..1.2), nutating (0.47..1.0) and
#: falling towards lies_flat (0.5 down to 0.04 within 2 s).
RUNS = {
    "diameter spin": ({"theta": "1.2", "phidot": "25"}, "1"),
    "nutating": ({"theta": "1.0", "phidot": "-6", "psidot": "9"}, "2"),
    "falling": ({"theta": "0.5", "psidot": "4"}, "2"),
}


def _run_inputs(sol):
    """(theta, omega2, omega3) at every output point, in the run's precision, as the suite evaluates them."""
    model, p = get_model("ring"), sol.precision
    compiled = compile_model(model, p)
    y = np.ascontiguousarray(sol.y)
    pars = np.ascontiguousarray(np.repeat(compiled.parameter_vector(sol.params, for_function=True)[:, None], y.shape[1], axis=1))
    out = compiled.invariant_function(y, pars=pars)
    return y[0], out[-2], out[-1]


def _disagreement_in_eps(p, closed, moved) -> list:
    out = []
    with mpmath.workprec(p.bits + 20):
        for j in range(len(closed[0])):
            a1, a2, b1, b2 = (p.to_mpf(v[j]) for v in (closed[0], closed[1], moved[0], moved[1]))
            out.append(float(max(abs(a1 - b1), abs(a2 - b2)) / (p.eps * (abs(b1) + abs(b2)))))
    return out


# quad on the falling run (theta to 0.035, where quad's 2F1 costs ~0.1 s a point) is the slow part: 14 s a set
ALONG_RUNS = [pytest.param(r, p, s, marks=pytest.mark.slow) if (r, p) == ("falling", "quad") else (r, p, s)
              for r in RUNS for p in ("double", "quad") for s in ("annular", "printed")]


@pytest.mark.parametrize("run, precision, parameters", ALONG_RUNS)
def test_closed_form_equals_the_transport_along_runs(run, precision, parameters):
    state, t_end = RUNS[run]
    sol = solve("ring", t_end, state, params=parameter_set(parameters), precision=precision, n_eval=6)
    assert sol.outcome == "ok"
    p, model = sol.precision, get_model("ring")
    thetas, w2, w3 = _run_inputs(sol)
    closed = chaplygin_integrals(model, p, sol.params, thetas, w2, w3, method="closed-form")
    moved = chaplygin_integrals(model, p, sol.params, thetas, w2, w3, method="fundamental-matrix")
    assert max(_disagreement_in_eps(p, closed, moved)) <= TOLERANCE
    # what the run reports (method "auto": every theta is inside (0, pi/2), so the transport's bytes)
    assert sol.invariants["chaplygin_1"].values.tobytes() == moved[0].tobytes()
    assert sol.invariants["chaplygin_2"].values.tobytes() == moved[1].tobytes()


def test_closed_form_equals_the_transport_in_mpfr():
    """mp:200 on a short nutating run of the printed ring (MPFR runs cost seconds a step batch)."""
    sol = solve("ring", "0.3", {"theta": "1.0", "phidot": "-6", "psidot": "9"}, params=parameter_set("printed"),
                precision="mp:200", n_eval=5)
    p, model = sol.precision, get_model("ring")
    thetas, w2, w3 = _run_inputs(sol)
    closed = chaplygin_integrals(model, p, sol.params, thetas, w2, w3, method="closed-form")
    moved = chaplygin_integrals(model, p, sol.params, thetas, w2, w3, method="fundamental-matrix")
    assert max(_disagreement_in_eps(p, closed, moved)) <= TOLERANCE


@pytest.mark.parametrize("precision", ["double", pytest.param("quad", marks=pytest.mark.slow)])  # quad: 15 s
def test_a_basis_with_c_off_by_1e_9_fails_the_comparison(precision):
    """Negative control: the closed form with the first solution's c moved by 1e-9 (relative) is out of
    the bound at the thetas of the falling run far from theta_ref, in double too."""
    state, t_end = RUNS["falling"]
    sol = solve("ring", t_end, state, precision=precision, n_eval=6)
    p, model = sol.precision, get_model("ring")
    thetas, w2, w3 = _run_inputs(sol)
    moved = chaplygin_integrals(model, p, sol.params, thetas, w2, w3, method="fundamental-matrix")
    wrong1, wrong2 = [], []
    with mpmath.workprec(p.bits + 80):
        pm = {k: p.to_mpf(v) for k, v in sol.params.items()}
        hg = hypergeometric_parameters(pm["I1"], pm["I3"], pm["h"])
        first = hg.solutions[0]
        hg = dataclasses.replace(hg, solutions=(dataclasses.replace(first, c=first.c * (1 + mpmath.mpf("1e-9"))),
                                                hg.solutions[1]))
        for t, a, b in zip(thetas, w2, w3):
            c1, c2 = integrals(hg, p.to_mpf(t), p.to_mpf(a), p.to_mpf(b))
            wrong1.append(p.number(c1))
            wrong2.append(p.number(c2))
    errors = _disagreement_in_eps(p, (p.array(wrong1), p.array(wrong2)), moved)
    far = [abs(float(t) - float(THETA_REF)) > 0.3 for t in thetas]
    assert sum(far) >= 3
    assert all(e > TOLERANCE for e, f in zip(errors, far) if f)

"""Chaplygin's integrals two ways, and the hurricane balls' closed forms against them."""
from __future__ import annotations

from dataclasses import replace

import mpmath
import pytest
import sympy as sp

from models import get_model, hurricane
from models.base import ChaplyginSystem
from models.rolling import derive
from models.symbols import omega_body
from verify.engine.chaplygin import chaplygin_integrals, fundamental_matrices
from verify.engine.single import resolve_parameters
from verify.precision import parse_precision


@pytest.mark.parametrize("k", ["0.25", "0.5", "0.1"])
def test_disk_closed_form_equals_fundamental_matrix(k):
    """Legendre functions (mpmath 2F1) against heyoka's integration of the linear ODE, in quad."""
    p = parse_precision("quad")
    model = get_model("disk")
    params = resolve_parameters(model, {"k": k}, p)
    thetas = [p.number(t) for t in ("0.05", "0.4", "1.0", "1.5707963", "2.2", "3.0")]
    w2 = p.array(["1.7", "-3.0", "0.2", "5.0", "-1.1", "2.5"])
    w3 = p.array(["0.3", "2.0", "-4.0", "1.0", "0.9", "-0.6"])
    a1, a2 = chaplygin_integrals(model, p, params, thetas, w2, w3, method="closed-form")
    b1, b2 = chaplygin_integrals(model, p, params, thetas, w2, w3, method="fundamental-matrix")
    for x, y in list(zip(a1, b1)) + list(zip(a2, b2)):
        # 1e-30: both routes work at quad (eps 1.9e-34); the transport near theta = 0.05
        # integrates through cot(theta) ~ 20, costing up to three digits.
        assert abs(float(x - y)) <= 1e-30 * (1 + abs(float(y)))


def test_closed_form_detects_a_wrong_k():
    """Negative control: the closed form with k = 0.26 disagrees with the transport at k = 0.25."""
    p = parse_precision("double")
    model = get_model("disk")
    good, bad = resolve_parameters(model, {}, p), resolve_parameters(model, {"k": "0.26"}, p)
    th, w2, w3 = [p.number("0.5")], p.array(["1.0"]), p.array(["2.0"])
    a = chaplygin_integrals(model, p, bad, th, w2, w3, method="closed-form")
    b = chaplygin_integrals(model, p, good, th, w2, w3, method="fundamental-matrix")
    assert abs(float(a[0][0] - b[0][0])) > 1e-4


def test_jellett_and_routh_are_the_chaplygin_integrals_of_the_hurricane_balls():
    """J = P1(theta) . w and R = P2(theta) . w, so P(theta) Phi(theta) must equal P(theta_ref)."""
    p = parse_precision("quad")
    base = get_model("hurricane")
    d = derive(hurricane.I1, hurricane.I3, hurricane.R2, hurricane.R3)
    w = omega_body()
    model = replace(base, chaplygin=ChaplyginSystem(sp.ImmutableMatrix(d.chaplygin_matrix), (w[1], w[2]), sp.pi / 4))
    params = resolve_parameters(model, {}, p)
    I1, I3 = float(params["I1"]), float(params["I3"])

    def P(th):
        th = float(th)
        r2, r3 = -mpmath.sin(th), -(1 + mpmath.cos(th))
        return [[I1 * r2, I3 * r3], [0, mpmath.sqrt(I1 * I3 + I1 * r2**2 + I3 * r3**2)]]

    thetas = [p.number(t) for t in ("0.1", "0.5", "1.0", "1.4")]
    ref = P(mpmath.pi / 4)
    for th, phi in zip(thetas, fundamental_matrices(model, p, params, thetas)):
        Pm = P(th)
        M = [[float(phi[0]), float(phi[1])], [float(phi[2]), float(phi[3])]]
        for i in range(2):
            for j in range(2):
                got = Pm[i][0] * M[0][j] + Pm[i][1] * M[1][j]
                assert abs(got - ref[i][j]) < 1e-12 * (1 + abs(ref[i][j]))


def test_invariants_are_evaluated_on_first_read_and_equal_an_eager_evaluation():
    """solve defers the invariants (Chaplygin's closed form costs milliseconds a point); when read
    they are the values verify.engine.invariants.evaluate gives on every output of the run."""
    import numpy as np

    from verify import solve
    from verify.engine import invariants as inv
    from verify.engine.compile import compile_model
    from verify.standard import STANDARD_STATES

    sol = solve("disk", 1, STANDARD_STATES["disk"], t_eval=[0.25, 0.5, 1.0])
    assert sol.evaluation._traces is None  # nothing evaluated yet (the guard's normal force aside)
    compiled = compile_model(get_model("disk"), sol.precision)
    y_all = np.ascontiguousarray(sol.evaluation._y)
    assert y_all.shape[1] == len(sol.t) + 1  # t = 0 is kept for the drifts
    values, normal = inv.evaluate(compiled, y_all, sol.params)
    traces = sol.invariants
    assert sol.evaluation._traces is traces and sol.invariants is traces  # evaluated once, kept
    for name, tr in traces.items():
        assert tr.values.tobytes() == values[name][1:].tobytes()
        assert tr.initial == values[name][0]
        assert tr.max_abs_drift == max(abs(float(v - values[name][0])) for v in values[name])
    assert sol.normal_force.tobytes() == normal[1:].tobytes()


def _trace_per_point(values):
    """The drift as the per-point loop computed it (the specification the vectorised trace keeps)."""
    diffs = [abs(float(v - values[0])) for v in values]
    return max(diffs)


@pytest.mark.parametrize("precision", ["double", "long", "quad", "mp:100"])
def test_vectorised_drift_has_the_per_point_bits(precision):
    """trace's differences in the run's dtype, rounded to double and maxed: the loop's bits exactly
    (IEEE subtraction in each dtype and a correctly rounded cast leave nothing to vary), on a run's
    Chaplygin and energy values, and with Python max()'s NaN rule (a NaN after the first passed over,
    a NaN first kept)."""
    import math

    import numpy as np

    from verify import solve
    from verify.engine.invariants import trace

    sol = solve("disk", "0.5", {"theta": "1.2", "phidot": "1", "psidot": "10"}, precision=precision, n_eval=21)
    for name, tr in sol.invariants.items():
        values = np.asarray(tr.values)
        got = trace(name, values, tr.term_scale, tr.eps)
        assert got.max_abs_drift == _trace_per_point(values) > 0
    v = sol.invariants["energy"].values
    zero = v[:1] - v[:1]
    with np.errstate(invalid="ignore"):
        later_nan = np.concatenate([v[:3], zero / zero, v[3:]])  # 0/0: a NaN of the run's dtype
    assert trace("I", later_nan, 1.0, 1e-16).max_abs_drift == _trace_per_point(later_nan)
    assert math.isnan(trace("I", later_nan[3:], 1.0, 1e-16).max_abs_drift)


@pytest.mark.parametrize("name", ["disk", "ring", "hurricane", "sliding-disk", "gyroscope", "effective"])
def test_vectorised_term_scale_equals_the_per_column_one(name):
    """scale_over (numpy over the columns) against lambdify(modules="math") column by column.  Every
    scale is a sum of non-negative terms (absolute values, squares), each a product of at most ~6
    factors from sin, cos, pow, sqrt, each correctly rounded or within 1 ulp in either library (glibc,
    or numpy's SIMD on AVX-512): the two sums differ by at most ~8 eps relative, 16 allowed.  Where
    numpy calls glibc (AVX2), they agree to the bit (float_power keeps libm's pow)."""
    import sympy as sp

    from models.symbols import STATE
    from verify import solve
    from verify.engine.invariants import scale_over
    from verify.standard import STANDARD_STATES

    model = get_model(name)
    for precision in ("double", "quad"):
        sol = solve(name, "1", STANDARD_STATES[name], precision=precision, n_eval=31)
        y = sol.evaluation._y
        for inv in model.invariants:
            f = sp.lambdify(list(STATE) + [p.symbol for p in model.parameters], inv.scale, modules="math")
            pars = [float(sol.params[p.name]) for p in model.parameters]
            per_column = max(f(*[float(v) for v in col], *pars) for col in y.T)
            assert abs(scale_over(model, inv.scale, y, sol.params) - per_column) <= 16 * 2.0**-52 * per_column

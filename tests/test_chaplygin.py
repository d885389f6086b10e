"""Chaplygin's integrals of the disk: the compiled transport against the closed form (Legendre functions).

The reference in every comparison is the closed form (``models.disk.chaplygin_closed_form``, mpmath's
2F1) evaluated at the run's bits + 80 on the same inputs (the run-precision numbers, exact in mpmath):
an independent route to the exact integrals at those inputs, to far below the run's epsilon.

Tolerance, in eps * (|c1| + |c2|) (eps the run's epsilon): 1.  The transport's value is the exact
integral rounded once to the run's precision (at most half an ulp of |c_i|, so 0.5 eps * scale), plus
the error of the transport itself, which runs at >= bits + 10 (heyoka's tolerance 2^-(bits+10) per
step along the theta path, then the 2x2 solve): the bound leaves it the other 0.5 eps * scale, i.e. the
transport may lose 9 of its 10 guard bits before the test fails.  Measured: at most 0.33 eps * scale,
from theta = 1e-12 to pi - 1e-9.  Near theta = 0 and pi, Phi's condition number reaches 1e13, but its
large entries sit in one row (omega2 ~ 1/sin(theta)) and the transport's error is relative to them;
the 2-norm condition number would be a vacuous bound there.
"""
from __future__ import annotations

import threading

import mpmath
import numpy as np
import pytest

from models import get_model
from verify import solve
from verify.engine import integrators
from verify.engine.chaplygin import GUARD_BITS, chaplygin_integrals, transport_precision
from verify.engine.single import resolve_parameters
from verify.precision import parse_precision

#: Near 0 and pi (the singular ends of A(theta)), ordinary, and either side of theta_ref = pi/2.
THETAS = ("1e-9", "1e-3", "0.05", "0.4", "1.0", "1.5707963", "1.5707964", "2.2", "3.0", "3.1405926",
          "3.141592652")
W2 = ("1.7", "-3.0", "0.2", "5.0", "-1.1", "2.5", "1", "-1", "0.7", "3", "-2")
W3 = ("0.3", "2.0", "-4.0", "1.0", "0.9", "-0.6", "2", "1", "-1.5", "0.1", "1")


def reference(p, params, thetas, w2, w3, k=None):
    """The closed form at the run's bits + 80 (``k`` overrides the parameter: negative control)."""
    model = get_model("disk")
    with mpmath.workprec(p.bits + 80):
        pm = {name: p.to_mpf(v) for name, v in params.items()}
        if k is not None:
            pm["k"] = mpmath.mpf(k)
        return [model.chaplygin.closed_form(p.to_mpf(t), p.to_mpf(a), p.to_mpf(b), pm) for t, a, b in zip(thetas, w2, w3)]


def errors_in_eps(p, values, ref) -> list:
    """max_i |value_i - ref_i| / (eps (|ref_1| + |ref_2|)) at each point."""
    out = []
    with mpmath.workprec(p.bits + 80):
        for j, (r1, r2) in enumerate(ref):
            err = max(abs(p.to_mpf(values[0][j]) - r1), abs(p.to_mpf(values[1][j]) - r2))
            out.append(float(err / (p.eps * (abs(r1) + abs(r2)))))
    return out


def inputs(p, k):
    model = get_model("disk")
    return model, resolve_parameters(model, {"k": k}, p), p.array(THETAS), p.array(W2), p.array(W3)


@pytest.mark.parametrize("precision", ["double", "quad"])
@pytest.mark.parametrize("k", ["0.1", "0.25", "0.5"])
def test_transport_equals_the_closed_form(precision, k):
    p = parse_precision(precision)
    model, params, thetas, w2, w3 = inputs(p, k)
    ref = reference(p, params, thetas, w2, w3)
    fast = chaplygin_integrals(model, p, params, thetas, w2, w3, method="fundamental-matrix")
    assert max(errors_in_eps(p, fast, ref)) <= 1.0
    auto = chaplygin_integrals(model, p, params, thetas, w2, w3)  # what solve uses: every theta is inside (0, pi)
    assert all(a.tobytes() == b.tobytes() for a, b in zip(auto, fast))


@pytest.mark.parametrize("precision", ["double", "quad"])
def test_closed_form_keeps_its_digits_near_the_ends(precision):
    """The closed form at its production precision (bits + 10, and 2 log2(1/sin theta) more) is within
    the same bound of itself at bits + 80; without the extra bits it was 800 eps off at theta = 1e-6
    in quad and NaN at 1e-12 in double."""
    p = parse_precision(precision)
    model, params, thetas, w2, w3 = inputs(p, "0.25")
    closed = chaplygin_integrals(model, p, params, thetas, w2, w3, method="closed-form")
    assert max(errors_in_eps(p, closed, reference(p, params, thetas, w2, w3))) <= 1.0


@pytest.mark.parametrize("precision", ["double", "quad"])
def test_a_perturbed_k_fails_the_comparison(precision):
    """Negative control: the reference at k (1 + 1e-9) is out of the bound at every theta the
    transport moves far (|theta - pi/2| > 0.5): the comparison resolves a relative change of 1e-9
    in the parameter, in double too."""
    p = parse_precision(precision)
    model, params, thetas, w2, w3 = inputs(p, "0.25")
    wrong = reference(p, params, thetas, w2, w3, k=mpmath.mpf("0.25") * (1 + mpmath.mpf("1e-9")))
    fast = chaplygin_integrals(model, p, params, thetas, w2, w3)
    far = [abs(float(t) - np.pi / 2) > 0.5 for t in thetas]
    assert sum(far) >= 7
    assert all(err > 1.0 for err, f in zip(errors_in_eps(p, fast, wrong), far) if f)


@pytest.mark.parametrize("precision", ["long", "mp:80"])
def test_transport_in_long_and_mpfr(precision):
    p = parse_precision(precision)
    assert transport_precision(p).bits >= p.bits + GUARD_BITS
    model, params, thetas, w2, w3 = inputs(p, "0.25")
    pick = [1, 4, 7, 9]  # 1e-3, 1.0, 2.2, pi - 1e-3
    thetas, w2, w3 = thetas[pick], w2[pick], w3[pick]
    fast = chaplygin_integrals(model, p, params, thetas, w2, w3)
    assert all(v.dtype == thetas.dtype for v in fast)
    assert max(errors_in_eps(p, fast, reference(p, params, thetas, w2, w3))) <= 1.0


def test_outside_the_domain_the_closed_form_gives_the_values():
    """events=False runs on past theta = 0 (by request); the transport cannot pass sin(theta) = 0, so
    there the values are the closed form's (its formula continued, what the suite always gave), and
    inside they are the transport's: every output point has a value."""
    sol = solve("disk", 1, {"theta": "1.2"}, events=False, n_eval=41)
    assert sol.outcome == "outside_domain"
    model, p = get_model("disk"), sol.precision
    y = sol.evaluation._y
    outside = np.array([float(t) <= 0 for t in y[0]])
    assert 0 < outside.sum() < len(outside)
    from verify.engine.invariants import evaluate
    from verify.engine.compile import compile_model

    compiled = compile_model(model, p)
    out = compiled.invariant_function(np.ascontiguousarray(y), pars=np.ascontiguousarray(np.repeat(
        compiled.parameter_vector(sol.params, for_function=True)[:, None], y.shape[1], axis=1)))
    w2, w3 = out[-2], out[-1]
    values, _ = evaluate(compiled, y, sol.params)
    closed = chaplygin_integrals(model, p, sol.params, y[0][outside], w2[outside], w3[outside], method="closed-form")
    moved = chaplygin_integrals(model, p, sol.params, y[0][~outside], w2[~outside], w3[~outside],
                                method="fundamental-matrix")
    for i, name in enumerate(("chaplygin_1", "chaplygin_2")):
        assert values[name][outside].tobytes() == closed[i].tobytes()
        assert values[name][~outside].tobytes() == moved[i].tobytes()
    assert len(sol.invariants["chaplygin_1"].values) == len(sol.t)


def test_a_nan_theta_gives_nan_not_the_identity():
    """A NaN theta is transported nowhere, and gives NaN (the former transport left it at theta_ref: the
    integrals were then w itself); "auto" sends it to the transport too, not to the closed form it uses
    outside the domain (whose inputs are exact rationals: a NaN raised there)."""
    for name in ("ring", "disk"):
        model = get_model(name)
        for precision in ("double", "quad"):
            p = parse_precision(precision)
            thetas = p.array(["0.5", "0.5"])
            thetas[0] = thetas[0] * float("nan")  # a NaN of the precision's type
            for method in ("fundamental-matrix", "auto"):
                c1, c2 = chaplygin_integrals(model, p, resolve_parameters(model, {}, p), thetas,
                                             p.array(["1", "1"]), p.array(["2", "2"]), method=method)
                assert c1[0] != c1[0] and c2[0] != c2[0] and c1[1] == c1[1] and c2[1] == c2[1], (name, precision, method)


def test_one_transport_integrator_per_system_and_precision_shared_by_threads():
    """The transport is compiled once and borrowed; four threads at once give the serial bytes."""
    p = parse_precision("double")
    model, params, thetas, w2, w3 = inputs(p, "0.25")
    serial = chaplygin_integrals(model, p, params, thetas, w2, w3)
    templates = [k for k in integrators._templates if type(k).__name__ == "_Transport" and k.precision == transport_precision(p)
                 and k.parameter_names == ("k",)]
    results, errors = [None] * 4, []

    def run(i):
        try:
            for _ in range(5):
                results[i] = chaplygin_integrals(model, p, params, thetas, w2, w3)
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert all(r[0].tobytes() == serial[0].tobytes() and r[1].tobytes() == serial[1].tobytes() for r in results)
    after = [k for k in integrators._templates if type(k).__name__ == "_Transport" and k.precision == transport_precision(p)
             and k.parameter_names == ("k",)]
    assert len(templates) == len(after) == 1

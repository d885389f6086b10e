"""Precisions against each other, and numbers read at the run's precision."""
from __future__ import annotations

import math

import heyoka as hy
import mpmath
import pytest

from models import MODEL_NAMES
from verify import parse_precision, solve
from verify.engine.conditioning import transition_norms
from verify.standard import STANDARD_STATES


@pytest.mark.parametrize("name", MODEL_NAMES)
def test_double_agrees_with_quad_within_the_conditioning_bound(name):
    """|y_double - y_quad| <= eps sqrt(N) |Phi(t,0)| |y(0)| (max norms).

    First-order error propagation: every step commits a local error of at most
    eps |y| (tol = eps, relative to the state's max norm), errors of independent sign
    add like sqrt(N), and the flow carries each by at most |Phi(t, 0)| (|Phi| grows
    monotonically on these runs).  Quad's own error is 1e-17 times smaller.  Measured
    ratio of error to bound: 0.003 to 0.13 (sliding disk).
    """
    t_end = "2"
    d = solve(name, t_end, STANDARD_STATES[name], precision="double", n_eval=5)
    q = solve(name, t_end, STANDARD_STATES[name], precision="quad", n_eval=5)
    err = max(abs(float(a) - float(b)) for a, b in zip(d.y[:, -1], q.y[:, -1]))
    phi = transition_norms(name, [2.0], STANDARD_STATES[name])[-1]
    y0 = max(abs(float(v)) for v in d.y[:, 0])
    bound = d.precision.eps * math.sqrt(d.steps) * phi * y0
    assert err <= bound, f"{name}: {err:.3e} > {bound:.3e}"
    assert err > 0  # the two runs are genuinely different computations


def test_quad_agrees_with_mpfr_to_30_digits():
    q = solve("disk", "1", STANDARD_STATES["disk"], precision="quad", n_eval=3)
    m = solve("disk", "1", STANDARD_STATES["disk"], precision="mp:160", n_eval=3)
    with mpmath.workprec(200):
        for a, b in zip(q.y[:, -1], m.y[:, -1]):
            qa, mb = q.precision.to_mpf(a), m.precision.to_mpf(b)
            assert abs(qa - mb) <= mpmath.mpf(10) ** -27 * (1 + abs(mb))


@pytest.mark.parametrize("name", ["long", "quad", "mp:200"])
def test_decimal_strings_are_read_at_the_run_precision(name):
    p = parse_precision(name)
    x = p.number("1.3")
    with mpmath.workprec(400):
        exact = mpmath.mpf(13) / 10
        err = abs(p.to_mpf(x) - exact)
        assert err <= mpmath.mpf(2) ** (-p.bits) * 1.3  # half an ulp at most
        assert err < abs(mpmath.mpf(1.3) - exact)  # better than the double nearest 1.3


def test_a_quad_run_starts_from_the_quad_number():
    sol = solve("disk", "0.01", {"theta": "1.3", "psidot": "10"}, precision="quad", n_eval=2)
    assert sol.y[0, 0] == hy.real128("1.3")
    assert sol.y[0, 0] != hy.real128(1.3)


def test_printing_keeps_every_digit():
    for name in ("double", "long", "quad", "mp:256"):
        p = parse_precision(name)
        x = p.number("0.1") / p.number(3)
        assert p.number(p.to_text(x)) == x


@pytest.mark.parametrize("bad", ["float", "mp:", "mp:1", "quadruple", "mp:x"])
def test_unknown_precisions_are_refused(bad):
    with pytest.raises(ValueError, match="precision"):
        parse_precision(bad)

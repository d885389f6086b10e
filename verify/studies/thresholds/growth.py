"""Confirmation of the linear thresholds by a growth protocol: the full nonlinear equations and the linearisation.

Start on the steady motion at a rate, perturb theta alone by a tilt (rates kept: the body moves onto a neighbouring
member of the family) and say whether theta leaves its steady value by more than :data:`GROWTH` times the tilt
within t_end (:func:`grows`, in double on the derived equations; :func:`linear_grows`, the same protocol on the
linearisation, in closed form).  :func:`bracket` bisects the rate between growth and no growth around the exact
threshold of :func:`verify.studies.thresholds.threshold`.
"""
from __future__ import annotations

import mpmath

from ...engine.single import solve
from .linear import linear_coefficients, steady_at, threshold

GROWTH = 1000  # a run "grows" when theta leaves its steady value by more than GROWTH x the tilt


def nonlinear_path(name, motion, rate, tilt, params, t_end="10") -> tuple:
    """(outcome, theta - theta_steady on the grid) of the full equations under the protocol of :func:`grows`.

    theta is perturbed alone by ``tilt`` (rates kept: the body moves onto a neighbouring member
    of the family); the deviation is measured from the unperturbed steady angle on the grid of
    :func:`linear_deviation` (401 points), in double.
    """
    state = steady_at(name, motion, rate, params)
    with mpmath.workdps(40):
        th0 = mpmath.mpf(state["theta"])
        state["theta"] = mpmath.nstr(th0 + mpmath.mpf(tilt), 36)
    sol = solve(name, t_end, state, params, n_eval=401)
    return sol.outcome, [float(v) - float(th0) for v in sol["theta"]]


def nonlinear_deviation(name, motion, rate, tilt, params, t_end="10") -> tuple:
    """(outcome, max |theta - theta_steady|) of :func:`nonlinear_path`."""
    outcome, path = nonlinear_path(name, motion, rate, tilt, params, t_end)
    return outcome, max(abs(v) for v in path)


def grows(name, motion, rate, tilt, params, t_end="10") -> bool:
    """Perturb theta alone by ``tilt`` (rates kept: the body moves onto a neighbouring member of the
    family) and report whether theta leaves its steady value by more than GROWTH x tilt, or the
    run leaves the model's domain, within ``t_end``."""
    outcome, dev = nonlinear_deviation(name, motion, rate, tilt, params, t_end)
    return outcome != "ok" or dev > GROWTH * float(tilt)


def _grid(t_end, n: int = 401):
    return [float(t_end) * i / (n - 1) for i in range(n)]


def linear_deviation(name, motion, rate, tilt, params=None, t_end="10", n: int = 401, phidot0=0) -> float:
    """max |theta - theta_steady| on the grid of :func:`grows`, from the linearised equations.

    The protocol of :func:`grows` (theta perturbed by ``tilt``, rates kept) applied to the
    linearisation.  With the reduced Jacobian's entries a, c, d, e, f, phidot and psidot follow
    theta (d phidot = e (d theta - tilt), d psidot = f (d theta - tilt)), so

        d theta'' = -w2 d theta - s tilt,   s = c e + d f:
        d theta(t) = d* + (tilt - d*) cos(sqrt(w2) t),   d* = -s tilt / w2

    (cosh for w2 < 0): the perturbed body oscillates about a neighbouring member of the family
    of steady motions, displaced by d*, which grows like 1/w2 near the threshold.  For the
    sleeping motion u'' = A u + i B u' with u(0) = tilt, u'(0) = i phidot0 tilt (default phidot0 = 0,
    the protocol of :func:`grows`; psidot0 = rate - phidot0).
    """
    params = dict(params or {})
    f = linear_coefficients(name, motion, tuple(sorted(params.items())))
    times = _grid(t_end, n)
    with mpmath.workdps(30):
        tilt, rate = mpmath.mpf(tilt), mpmath.mpf(rate)
        if motion == "sleeping":
            value, _ = _sleeping_solution(f, rate, tilt, phidot0, times[-1])
            return float(max(value(t) for t in times))
    return float(max(abs(v) for v in linear_path(name, motion, rate, tilt, params, t_end, n)))


def _sleeping_solution(f, rate, tilt, phidot0, t_max):
    """(t -> |u(t)|, a bound on |u| for 0 <= t <= t_max) of the sleeping motion's u'' = A u + i B u'
    (:func:`linear_deviation`), as 30-digit mpmath numbers; call it, and the function it returns,
    under ``workdps(30)``.  u = c1 exp(l1 t) + c2 exp(l2 t), so for t between 0 and t_max (either
    sign) |u| <= sum |c_k| exp(max(Re l_k t_max, 0)): a decaying root grows backwards in time."""
    A, B = f(rate)
    root = mpmath.sqrt(mpmath.mpc(4 * A - B**2))
    l1, l2 = (1j * B + root) / 2, (1j * B - root) / 2
    v0 = 1j * mpmath.mpf(phidot0) * tilt
    c1, c2 = (v0 - l2 * tilt) / (l1 - l2), (l1 * tilt - v0) / (l1 - l2)
    bound = sum(abs(c) * mpmath.exp(max(l.real * t_max, 0)) for c, l in ((c1, l1), (c2, l2)))
    return (lambda t: abs(c1 * mpmath.exp(l1 * t) + c2 * mpmath.exp(l2 * t))), bound


def linear_path(name, motion, rate, tilt, params=None, t_end="10", n: int = 401) -> list:
    """theta - theta_steady on the grid of :func:`grows` from the linearised equations (not sleeping).

    d theta(t) = d* + (tilt - d*) cos(sqrt(w2) t) of :func:`linear_deviation` (cosh for w2 < 0).
    """
    with mpmath.workdps(30):
        value, _ = _linear_solution(name, motion, rate, tilt, params)
        return [float(value(t)) for t in _grid(t_end, n)]


def _linear_solution(name, motion, rate, tilt, params):
    """(t -> d theta(t), a bound on |d theta| over every t >= 0 or None) of :func:`linear_path`,
    as 30-digit mpmath numbers; call it, and the function it returns, under ``workdps(30)``.

    The bound |d*| + |tilt - d*| holds for the oscillating solution (w2 > 0); the growing one has none.
    """
    params = dict(params or {})
    f = linear_coefficients(name, motion, tuple(sorted(params.items())))
    tilt, rate = mpmath.mpf(tilt), mpmath.mpf(rate)
    s = steady_at(name, motion, rate, params)
    a, c, d, e, ff = f(*(mpmath.mpf(s[k]) for k in ("theta", "phidot", "psidot")))
    w2 = -(a + c * e + d * ff)
    shift = -(c * e + d * ff) * tilt / w2
    amplitude = tilt - shift
    if w2 > 0:
        root = mpmath.sqrt(w2)
        return (lambda t: shift + amplitude * mpmath.cos(root * t)), abs(shift) + abs(amplitude)
    root = mpmath.sqrt(-w2)
    return (lambda t: shift + amplitude * mpmath.cosh(root * t)), None


#: Relative margin on a 30-digit bound before it decides :func:`linear_grows` without the grid:
#: far above the bound's own rounding (~1e-29) and the double rounding of the comparison (~1e-16).
_BOUND_MARGIN = 1e-9


def linear_grows(name, motion, rate, tilt, params, t_end="10", growth=GROWTH) -> bool:
    """Whether :func:`linear_deviation` exceeds ``growth`` x the tilt, with the same answer for every input.

    For the oscillating solution (w2 > 0) every value on the grid is at most |d*| + |tilt - d*|
    (to 30 digits; for the sleeping motion sum |c_k| exp(max(Re l_k t_end, 0))); when that
    bound, with :data:`_BOUND_MARGIN`, is below the limit no value can exceed it, and the 401
    cosines (exponentials) are not evaluated.  Otherwise the grid is searched, its end first (where
    a growing solution is largest), and the search stops at the first value above the limit: the
    maximum exceeds a number exactly when one value does (rounding to double is monotonic).
    """
    limit = growth * float(tilt)
    times = _grid(t_end)
    with mpmath.workdps(30):
        if motion == "sleeping":
            f = linear_coefficients(name, motion, tuple(sorted(dict(params or {}).items())))
            value, bound = _sleeping_solution(f, mpmath.mpf(rate), mpmath.mpf(tilt), 0, times[-1])
        else:
            value, bound = _linear_solution(name, motion, rate, tilt, params)
        if bound is not None and float(bound) * (1 + _BOUND_MARGIN) < limit:
            return False
        return any(abs(float(value(t))) > limit for t in times[-1:] + times[:-1])


CRITERIA = ("nonlinear", "linear")


def bracket(name: str, motion: str, tilt: str, params=None, iterations: int = 25, t_end: str = "10",
            criterion: str = "nonlinear", growth: float = GROWTH):
    """Bisect the rate between growth and no growth, starting from [lin/2, 2 lin].

    ``criterion`` is ``"nonlinear"`` (full equations, :func:`grows`) or ``"linear"`` (the same
    protocol on the linearisation, :func:`linear_deviation`): the nonlinear bracket tends to the
    linear-protocol one as the tilt shrinks, and that one to the threshold as GROWTH and t_end grow.
    """
    if criterion not in CRITERIA:
        raise ValueError(f"criterion {criterion!r}; allowed: {', '.join(CRITERIA)}")
    if criterion == "linear":
        test = lambda *args: linear_grows(*args, growth=growth)  # noqa: E731
    elif growth != GROWTH:
        raise ValueError("the nonlinear criterion uses GROWTH; a different growth factor is for criterion='linear'")
    else:
        test = grows
    params = dict(params or {})
    lin = threshold(name, motion, params).value
    if lin is None:
        return None
    lo, hi = lin / 2, lin * 2
    if not test(name, motion, lo, tilt, params, t_end) or test(name, motion, hi, tilt, params, t_end):
        raise RuntimeError(f"{name} {motion}: no sign change of the growth test on [{lo}, {hi}] at tilt {tilt}")
    for _ in range(iterations):
        mid = (lo + hi) / 2
        if test(name, motion, mid, tilt, params, t_end):
            lo = mid
        else:
            hi = mid
    return lo, hi

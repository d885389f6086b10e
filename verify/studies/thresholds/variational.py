"""Confirmation of the linear thresholds by heyoka's variational equations along the steady motion.

The stability coefficient w2 recovered from the trace of the state-transition matrix over a quarter nutation
period (:func:`variational_w2`): a route that shares nothing with the sympy linearisation of
:mod:`verify.studies.thresholds.linear` but the model's accelerations.
"""
from __future__ import annotations

from dataclasses import dataclass

import mpmath
import numpy as np

from models import get_model

from ...engine.conditioning import transition_matrix
from ...precision import parse_precision
from .linear import linear_coefficients, steady_at


@dataclass(frozen=True)
class Variational:
    """The stability coefficient recovered from the state-transition matrix of the full equations."""

    model: str
    motion: str
    rate: mpmath.mpf
    precision: str
    period: mpmath.mpf  # T = quarter nutation period pi / (2 sqrt|w2|)
    w2_linear: mpmath.mpf  # from the sympy linearisation
    w2_variational: mpmath.mpf  # from trace(Phi_reduced(T)) = 2 + 2 cos(sqrt(w2) T)
    multipliers: tuple  # eigenvalues of Phi_reduced(T) (complex, double)

    @property
    def relative_difference(self):
        with mpmath.workdps(50):
            return abs(self.w2_variational / self.w2_linear - 1)


def variational_w2(name: str, motion: str, rate, params=None, precision: str = "double") -> Variational:
    """w2 from heyoka's variational equations along the steady motion (order 1, compact mode).

    The reduced block (theta, thetadot, phidot, psidot) of Phi(T) = exp(J T) has eigenvalues
    1, 1 (the family of steady motions) and exp(+-i sqrt(w2) T), so its trace is
    2 + 2 cos(sqrt(w2) T) (cosh for w2 < 0); at a quarter nutation period the cosine is
    best conditioned.  The route shares nothing with the sympy linearisation but the model's
    accelerations: the derivatives are heyoka's, along the integrated (not assumed) motion.
    Not available for the sleeping motion (Euler angles are singular at theta = 0).
    """
    if motion == "sleeping":
        raise ValueError("the variational check needs Euler angles regular along the motion; 'sleeping' sits at theta = 0")
    params = dict(params or {})
    prec = parse_precision(precision)
    model = get_model(name)
    steady = steady_at(name, motion, rate, params)
    f = linear_coefficients(name, motion, tuple(sorted(params.items())))
    with mpmath.workdps(45):  # w2 to beyond quad: the steady state carries 36 digits
        a, c, d, e, ff = f(*(mpmath.mpf(steady[k]) for k in ("theta", "phidot", "psidot")))
        w2 = -(a + c * e + d * ff)
        T = mpmath.pi / (2 * mpmath.sqrt(abs(w2)))
    phi = transition_matrix(model, steady, params, prec.number(mpmath.nstr(T, 40)), prec)
    idx = (0, 3, 4, 5)  # theta, thetadot, phidot, psidot in STATE order
    block = [[prec.to_mpf(phi[i, j]) for j in idx] for i in idx]
    with mpmath.workdps(max(45, prec.digits + 5)):
        half = (sum(block[i][i] for i in range(4)) - 2) / 2
        root = mpmath.acos(half) if w2 > 0 else mpmath.acosh(half)
        w2v = (root / mpmath.mpf(T)) ** 2 * (1 if w2 > 0 else -1)
    mult = np.linalg.eigvals(np.array([[float(x) for x in row] for row in block]))
    mult = tuple(sorted((complex(m) for m in mult), key=lambda z: (round(z.real, 9), z.imag)))
    return Variational(name, motion, mpmath.mpf(rate), prec.name, T, w2, w2v, mult)

"""Chaplygin's integrals of the thick ring in closed form: Gauss's hypergeometric function (paper Eqs. 47-50).

The rows of the ring's rolling equations without thetaddot (:func:`models.rolling.derive` with
I1, I3, r2 = -1, r3 = -h; the ring's Eq. 50) make w = (omega2, omega3) obey dw/dtheta = A(theta) w with

    A = [[-cot(theta) - alpha, beta], [gamma, alpha]],
    alpha = I3 h / D,  beta = I3 (1 + I3) / D,  gamma = I1 / D,  D = I1 (1 + I3) + I3 h^2

(only the cot term depends on theta).  Appell (1900) reduced a body of revolution rolling on a
circular edge to Gauss's equation; for the ring the steps are these (each is checked by sympy in
``tests/test_ring_chaplygin.py``):

1. Row 2 gives omega2 = (omega3' - alpha omega3) / gamma (' = d/dtheta).
2. Row 1, as (sin(theta) omega2)' = sin(theta) (beta omega3 - alpha omega2), with step 1 gives one
   second-order equation for omega3:

       omega3'' + cot(theta) omega3' - (alpha cot(theta) + mu) omega3 = 0,   mu = alpha^2 + beta gamma.

   (h = 0: alpha = 0, the thin disk's Legendre equation in cos(theta), ``models.disk``.)
3. z = exp(2 i theta): cot(theta) = i (z + 1)/(z - 1), d/dtheta = 2 i z d/dz, and the equation becomes

       omega3_zz + (1/(2 z) + 1/(z - 1)) omega3_z + (mu (z - 1) + i alpha (z + 1)) / (4 z^2 (z - 1)) omega3 = 0,

   a Riemann P-equation: regular singular points z = 0 (theta -> +i inf), z = 1 (theta = 0, pi: the
   ring lies flat) and z = inf, and no other.  Its exponents (Fuchs' sum 1):

       z = 0:    r   = (1 -+ s0) / 4,  s0   = sqrt(1 - 4 mu + 4 i alpha)   (4 r^2 - 2 r + mu - i alpha = 0)
       z = 1:    0, 0                                                        (a logarithm: omega3 ~ log(theta))
       z = inf:  rho = (1 -+ sinf) / 4, sinf = sqrt(1 - 4 mu - 4 i alpha)  (omega3 ~ z^-rho)

   (for real I1, I3, h, sinf = conj(s0)).
4. omega3 = z^r f(z) takes out the exponent at 0; f has exponents 0 and 1 - c at 0, 0 and
   c - a - b = 0 at 1, and a, b at infinity: Gauss's equation z (1 - z) f'' + (c - (a + b + 1) z) f'
   - a b f = 0 with

       r = (1 - s0)/4:  a = (2 - s0 + sinf)/4,  b = (2 - s0 - sinf)/4,  c = 1 - s0/2,
       r = (1 + s0)/4:  a = (2 + s0 + sinf)/4,  b = (2 + s0 - sinf)/4,  c = 1 + s0/2,

   so omega3 = z^r 2F1(a, b; c; z), the two Kummer solutions about z = 0.  They are independent
   unless s0 = 0 (then c = 1 for both: h = 0 and I3 = I1 (1 + I3)/4 exactly), which is refused.
5. omega3' = 2 i z^r (r F + z F_z), F_z = (a b / c) 2F1(a + 1, b + 1; c + 1; z), and omega2 from step 1:
   the matrix M(theta) = [[omega2 of each], [omega3 of each]] is a (complex) fundamental matrix, and
   the real one with Phi(theta_ref) = identity is Phi(theta) = M(theta) M(theta_ref)^-1.  Chaplygin's
   integrals, w carried back to theta_ref = pi/4, are Phi(theta)^-1 w = M(theta_ref) M(theta)^-1 w;
   real, the imaginary part being rounding.

For theta in (0, pi), z = exp(2 i theta) runs along the unit circle without touching z = 1, so
it never crosses the principal branch cut [1, inf) of 2F1, and z^r is taken as exp(2 i theta r):
the formula is analytic on (0, pi), the ring's domain (0, pi/2) and beyond its upper end to pi,
and equals the transport of :mod:`verify.engine.chaplygin` there.  Outside (0, pi) it is the
formula continued (the transport cannot pass sin(theta) = 0).  mpmath's 2F1 on |z| = 1 uses its
1 - z, z/(z - 1) transformations and, near z = exp(+-i pi/3) (theta near pi/6 and 5 pi/6), Gosper's
recurrence; at theta -> 0 the 1 - z transformation is the degenerate c - a - b = 0 case.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import mpmath
import sympy as sp

#: Where the transport starts (Phi = identity): the ring's theta_ref.
THETA_REF = sp.pi / 4


def coefficients(I1, I3, h) -> tuple:
    """(alpha, beta, gamma) of A(theta) = [[-cot(theta) - alpha, beta], [gamma, alpha]] (any number type, sympy too)."""
    D = I1 * (1 + I3) + I3 * h * h
    return I3 * h / D, I3 * (1 + I3) / D, I1 / D


@dataclass(frozen=True)
class KummerSolution:
    """omega3 = z^exponent 2F1(a, b; c; z), z = exp(2 i theta): one solution about z = 0."""

    exponent: object
    a: object
    b: object
    c: object


@dataclass(frozen=True)
class RingHypergeometric:
    """The ring's Chaplygin system as a Riemann P-equation: its coefficients, exponents and two solutions."""

    alpha: object
    gamma: object
    exponents_at_zero: tuple  # r = (1 -+ s0)/4
    exponents_at_infinity: tuple  # rho = (1 -+ sinf)/4 (omega3 ~ z^-rho)
    solutions: tuple  # of two KummerSolution


def hypergeometric_parameters(I1, I3, h) -> RingHypergeometric:
    """Exponents and (a, b, c) of the two Kummer solutions about z = 0, as mpmath numbers at the working precision.

    Raises
    ------
    ValueError
        s0 = 0 (h = 0 and I3 = I1 (1 + I3)/4): the two solutions coincide and the closed form
        needs a logarithmic one, which this module does not build.
    """
    alpha, beta, gamma = coefficients(mpmath.mpf(I1), mpmath.mpf(I3), mpmath.mpf(h))
    mu = alpha * alpha + beta * gamma
    s0 = mpmath.sqrt(mpmath.mpc(1 - 4 * mu, 4 * alpha))
    sinf = mpmath.sqrt(mpmath.mpc(1 - 4 * mu, -4 * alpha))
    if s0 == 0:
        raise ValueError(f"ring parameters I1={I1}, I3={I3}, h={h}: the exponents at z = 0 coincide (s0 = 0), "
                         "the hypergeometric closed form is degenerate there")
    solutions = tuple(KummerSolution((1 + sign * s0) / 4, (2 + sign * s0 + sinf) / 4, (2 + sign * s0 - sinf) / 4,
                                     1 + sign * s0 / 2) for sign in (-1, 1))
    return RingHypergeometric(alpha, gamma, ((1 - s0) / 4, (1 + s0) / 4), ((1 - sinf) / 4, (1 + sinf) / 4), solutions)


def fundamental_solutions(system: RingHypergeometric, theta) -> mpmath.matrix:
    """M(theta) = [[omega2 of each solution], [omega3 of each]] (complex, at the working precision)."""
    z = mpmath.expj(2 * theta)
    columns = []
    for sol in system.solutions:
        F = mpmath.hyp2f1(sol.a, sol.b, sol.c, z)
        dF = sol.a * sol.b / sol.c * mpmath.hyp2f1(sol.a + 1, sol.b + 1, sol.c + 1, z)
        power = mpmath.expj(2 * theta * sol.exponent)  # z^r continued along theta, never across the cut
        w3 = power * F
        dw3 = 2j * power * (sol.exponent * F + z * dF)
        columns.append(((dw3 - system.alpha * w3) / system.gamma, w3))
    return mpmath.matrix([[columns[0][0], columns[1][0]], [columns[0][1], columns[1][1]]])


def integrals(system: RingHypergeometric, theta, omega2, omega3, reference=None) -> tuple:
    """M(theta_ref) M(theta)^-1 (omega2, omega3): (omega2, omega3) carried back to theta_ref, real parts.

    ``reference``: M(theta_ref) if already computed (it depends on the parameters only).
    """
    M = fundamental_solutions(system, theta)
    ref = reference if reference is not None else fundamental_solutions(system, mpmath.pi / 4)
    det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    k1 = (M[1, 1] * omega2 - M[0, 1] * omega3) / det
    k2 = (M[0, 0] * omega3 - M[1, 0] * omega2) / det
    return mpmath.re(ref[0, 0] * k1 + ref[0, 1] * k2), mpmath.re(ref[1, 0] * k1 + ref[1, 1] * k2)


@lru_cache(maxsize=64)
def _at_reference(I1, I3, h, prec: int) -> tuple:
    """(the system, M(theta_ref)) at ``prec`` bits: per parameter set, shared by every point."""
    with mpmath.workprec(prec):
        system = hypergeometric_parameters(I1, I3, h)
        return system, fundamental_solutions(system, mpmath.pi / 4)


def chaplygin_closed_form(theta, omega2, omega3, params):
    """Chaplygin's integrals of the thick ring in closed form (Gauss's 2F1; the module docstring derives it).

    Parameters
    ----------
    theta, omega2, omega3 : mpmath numbers
        The tilt and the body rates omega2 = phidot sin(theta), omega3 = phidot cos(theta) + psidot.
    params : mapping
        ``I1``, ``I3``, ``h`` as mpmath numbers (others ignored).

    Returns
    -------
    (chaplygin_1, chaplygin_2)
        (omega2, omega3) carried back to theta_ref = pi/4: the numbers the transport of
        :mod:`verify.engine.chaplygin` computes, as real mpf.  NaN for a non-finite theta.

    Works at the caller's precision plus 2 log2(1/|sin(theta)|) bits, as the disk's closed form:
    near theta = 0 (z -> 1) omega3 grows like log(sin(theta)) and omega2 like 1/sin(theta), and
    solving for the constants cancels about that many bits.  At sin(theta) = 0 the basis is
    singular and the division fails.  Likewise 2 log2(1/|s0|) bits more where the exponents at
    z = 0 nearly coincide (h = 0 and I1 (1 + I3) near 4 I3, no ring of the paper): the two
    solutions differ by O(s0) there.
    """
    if not mpmath.isfinite(theta):
        return mpmath.mpf("nan"), mpmath.mpf("nan")
    I1, I3, h = (mpmath.mpf(params[k]) for k in ("I1", "I3", "h"))
    s = mpmath.sin(theta)
    extra = (2 * max(0, -mpmath.mag(s)) if s else 0) + _degeneracy_bits(I1, I3, h, mpmath.mp.prec)
    with mpmath.extraprec(extra):
        system, reference = _at_reference(I1, I3, h, mpmath.mp.prec)
        return integrals(system, theta, omega2, omega3, reference)


@lru_cache(maxsize=64)
def _degeneracy_bits(I1, I3, h, prec: int) -> int:
    with mpmath.workprec(prec):
        low, high = hypergeometric_parameters(I1, I3, h).exponents_at_zero
        return 2 * max(0, -mpmath.mag(2 * (high - low)))  # high - low = s0/2

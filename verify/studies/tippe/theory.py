"""Where a spun tippe top can end: Jellett's integral, the energy, and the thresholds on the spin.

A sphere of radius R whose centre sits c above the centre of mass C on the axis (alpha = c/R), inertia
I1, I3 per unit mass, on a plane with friction at the contact P (any law: smooth or Coulomb).

Jellett's lambda = L_C . r_P is conserved (:mod:`models.smooth_friction`), the energy E does not increase
(dE/dt = F_h . u <= 0).  With r_P = (0, -R sin theta, c - R cos theta) (:mod:`models.profiles`), the least
energy a state of tilt theta can have at a given lambda is reached with C at rest and omega parallel to r_P
(minimise I1 w2^2 + I3 w3^2 over I1 w2 r2 + I3 w3 r3 = lambda: w = k r_P), so the contact does not slip:

    V_lambda(theta) = lambda^2 / (2 D(theta)) + g z_C(theta),
    D(theta) = I1 R^2 sin^2(theta) + I3 (c - R cos(theta))^2,   z_C = R - c cos(theta).

Friction dissipates while the contact slips, so a motion ends where it no longer slips, at a critical point
of V_lambda (the tilted rolling steady motions, theta-dot = 0 with omega = k r_P: a sympy check in the tests
that the rolling model's accelerations vanish there), and only at one with V_lambda <= E(0).

* **the energy bound** (necessary): the inverted vertical spin can be reached only if V_lambda(pi) < E(0).
  For the start theta0, spin n about the axis, C at rest (E0 = I3 n^2/2 + g z_C(theta0),
  lambda = I3 n (c - R cos theta0)):

      n_E^2 = 2 g c (1 + cos theta0) / (I3 (1 - ((R cos theta0 - c)/(R + c))^2))  ->  g (R + c)^2 / (I3 R)
      (theta0 -> 0).

* **the inverted state a minimum** (what decides): V_lambda''(pi) > 0 iff
  lambda^2 > lambda_s^2 = g c I3^2 (R + c)^4 / (R (I3 (R + c) - I1 R)), which needs I1/I3 < 1 + alpha
  (Rauch-Wojciechowski & Rutstam 2014, SIGMA 10, 017, print the same threshold with R = 1, m = 1:
  lambda_thres = sqrt(m g R^3 I3 alpha) (1 + alpha)^2 / sqrt(1 + alpha - I1/I3)).
* **the upright state unstable**: V_lambda''(0) < 0 iff lambda^2 > lambda_u^2 = g c I3^2 (R - c)^4 /
  (R (I1 R - I3 (R - c))), which needs I1/I3 > 1 - alpha.

Hence the inertia window 1 - alpha < I1/I3 < 1 + alpha: inside it the upright spin is unstable and the
inverted one stable for a fast enough spin; below it (``tippe-top-stable``) the upright spin is a minimum
at every spin; above it the inverted spin never is (the top ends tilted).
"""
from __future__ import annotations

from dataclasses import dataclass

import mpmath
import sympy as sp

from models.bodies import load

#: sympy symbols of the formulas
R, c, I1, I3, g, theta0, n, lam, th = sp.symbols("R c I1 I3 g theta0 n lambda theta", positive=True)


@dataclass(frozen=True)
class Top:
    """A sphere-profile body's exact numbers: radius, centre height, inertia, gravity."""

    name: str
    R: sp.Expr
    c: sp.Expr
    I1: sp.Expr
    I3: sp.Expr
    g: sp.Expr = sp.Integer(980)

    @property
    def values(self) -> dict:
        return {R: self.R, c: self.c, I1: self.I1, I3: self.I3, g: self.g}

    @property
    def ratio(self) -> sp.Expr:
        return self.I1 / self.I3

    @property
    def window(self) -> tuple:
        """(1 - alpha, 1 + alpha): I1/I3 inside it lets a fast spin invert the top."""
        alpha = self.c / self.R
        return (1 - alpha, 1 + alpha)

    @property
    def group(self) -> str:
        lo, hi = self.window
        if self.ratio <= lo:
            return "upright stable at every spin (I1/I3 <= 1 - alpha)"
        if self.ratio >= hi:
            return "never inverts, ends tilted (I1/I3 >= 1 + alpha)"
        return "inverts above a spin threshold (1 - alpha < I1/I3 < 1 + alpha)"


def top(name: str = "tippe-top") -> Top:
    """The :class:`Top` of a shipped sphere body file."""
    body = load(name)
    if body.kind != "sphere":
        raise ValueError(f"body {name!r} is a {body.kind}; the tippe top's analysis needs a sphere profile")
    v = body.values
    return Top(name, v["radius"], v["centre_height"], body.I1, body.I3)


# --- the formulas (sympy) ------------------------------------------------------------------------------

D = I1 * R ** 2 * sp.sin(th) ** 2 + I3 * (c - R * sp.cos(th)) ** 2
HEIGHT = R - c * sp.cos(th)
V = lam ** 2 / (2 * D) + g * HEIGHT
#: the standard start: tilt theta0, spin n about the axis, theta-dot = phi-dot = 0, C at rest
START_LAMBDA = I3 * n * (c - R * sp.cos(theta0))
START_ENERGY = I3 * n ** 2 / 2 + g * (R - c * sp.cos(theta0))
#: the energy bound n_E^2 (V_lambda(pi) = E0) and the thresholds on lambda^2
ENERGY_BOUND_SQ = 2 * g * c * (1 + sp.cos(theta0)) / (I3 * (1 - ((R * sp.cos(theta0) - c) / (R + c)) ** 2))
INVERTED_MIN_SQ = g * c * I3 ** 2 * (R + c) ** 4 / (R * (I3 * (R + c) - I1 * R))
UPRIGHT_UNSTABLE_SQ = g * c * I3 ** 2 * (R - c) ** 4 / (R * (I1 * R - I3 * (R - c)))


def check_formulas() -> dict:
    """The closed forms above against V_lambda itself, exactly (sympy): each entry 0 when they hold."""
    at_pi = sp.simplify(V.subs(th, sp.pi).subs(lam, START_LAMBDA) - START_ENERGY)
    bound = sp.simplify(at_pi.subs(n, sp.sqrt(ENERGY_BOUND_SQ)))
    d = sp.symbols("delta")
    v2_pi = sp.series(V.subs(th, sp.pi + d), d, 0, 3).removeO().coeff(d, 2)
    v2_0 = sp.series(V.subs(th, d), d, 0, 3).removeO().coeff(d, 2)
    return {"energy_bound": bound,
            "inverted_min": sp.simplify(v2_pi.subs(lam, sp.sqrt(INVERTED_MIN_SQ))),
            "upright_unstable": sp.simplify(v2_0.subs(lam, sp.sqrt(UPRIGHT_UNSTABLE_SQ))),
            "limit_theta0_0": sp.simplify(sp.limit(ENERGY_BOUND_SQ, theta0, 0) - g * (R + c) ** 2 / (I3 * R))}


@dataclass(frozen=True)
class Thresholds:
    """The spin thresholds of a top for the standard start at theta0 (s^-1, mpmath at ``dps`` digits)."""

    energy_bound: mpmath.mpf  # n_E: below it the inverted spin is out of energetic reach
    inverted_minimum: mpmath.mpf | None  # n_s: above it the inverted spin is a minimum of V_lambda (None: never)
    upright_unstable: mpmath.mpf | None  # n_u: above it the upright spin is not a minimum (None: never)
    exact: dict  # the same as sympy expressions


def thresholds(t: Top, start_tilt="1/10", dps: int = 30) -> Thresholds:
    """:class:`Thresholds` of ``t`` for the standard start at tilt ``start_tilt`` (exact text)."""
    values = {**t.values, theta0: sp.sympify(start_tilt, rational=True)}
    per_lambda = 1 / (I3 * (R * sp.cos(theta0) - c))  # n = |lambda| / (I3 (R cos theta0 - c))
    n_e = sp.sqrt(ENERGY_BOUND_SQ.subs(values))
    n_s = sp.sqrt(INVERTED_MIN_SQ.subs(values)) * per_lambda.subs(values) if t.ratio < 1 + t.c / t.R else None
    n_u = sp.sqrt(UPRIGHT_UNSTABLE_SQ.subs(values)) * per_lambda.subs(values) if t.ratio > 1 - t.c / t.R else None
    num = (lambda e: None if e is None else mpmath.mpf(str(sp.N(e, dps + 5))))
    with mpmath.workdps(dps):
        return Thresholds(num(n_e), num(n_s), num(n_u), {"energy_bound": n_e, "inverted_minimum": n_s,
                                                          "upright_unstable": n_u})


def landscape(t: Top, spin, start_tilt="1/10", samples: int = 2000, dps: int = 30) -> dict:
    """V_lambda of the standard start (tilt ``start_tilt``, spin ``spin``): its minima and the start's reach.

    Returns ``lambda``, ``energy`` E0, ``minima`` [(theta, V, 'upright' | 'tilted' | 'inverted')] over [0, pi] (an end counts when V rises from
    it; interior ones refined by mpmath's root finder on V' to ``dps`` digits), ``V_pi``, and ``reach``: the
    interval of tilts around theta0 where V_lambda <= E0 (on the grid), which the motion cannot leave (E >=
    V_lambda(theta) always, and E does not increase).
    """
    with mpmath.workdps(dps):
        tilt = sp.sympify(start_tilt, rational=True)
        values = {**t.values, theta0: tilt, n: sp.sympify(spin, rational=True)}
        lam_value = START_LAMBDA.subs(values)
        energy = mpmath.mpf(str(sp.N(START_ENERGY.subs(values), dps + 5)))
        f = sp.lambdify(th, V.subs({**values, lam: lam_value}), "mpmath")
        df = sp.lambdify(th, sp.diff(V, th).subs({**values, lam: lam_value}), "mpmath")
        grid = [mpmath.pi * i / samples for i in range(samples)] + [+mpmath.pi]
        vals = [f(x) for x in grid]
        minima = []
        for i in range(samples + 1):
            left = vals[i - 1] if i > 0 else mpmath.inf
            right = vals[i + 1] if i < samples else mpmath.inf
            if vals[i] < left and vals[i] < right:
                x = grid[i]
                if 0 < i < samples:
                    x = mpmath.findroot(df, (grid[i - 1], grid[i + 1]), solver="anderson")
                minima.append((x, f(x), "upright" if i == 0 else "inverted" if i == samples else "tilted"))
        start = min(range(samples + 1), key=lambda i: abs(grid[i] - mpmath.mpf(str(sp.N(tilt, dps)))))
        lo = hi = start
        while lo > 0 and vals[lo - 1] <= energy:
            lo -= 1
        while hi < samples and vals[hi + 1] <= energy:
            hi += 1
        return {"lambda": mpmath.mpf(str(sp.N(lam_value, dps + 5))), "energy": energy, "minima": minima,
                "V_pi": vals[-1], "reach": (grid[lo], grid[hi])}


def predict(t: Top, spin, start_tilt="1/10") -> dict:
    """What the top ends in, by the energy-Jellett argument: ``upright``, ``tilted`` (at ``theta``) or ``inverted``.

    The motion stays where V_lambda <= E0 around theta0 (``reach``) and ends at a critical point of V_lambda
    there; where that interval holds one minimum, that is the prediction (else ``ambiguous``, naming them)."""
    land = landscape(t, spin, start_tilt)
    lo, hi = land["reach"]
    inside = [m for m in land["minima"] if lo <= m[0] <= hi]
    if len(inside) != 1:
        return {"verdict": "ambiguous", "theta": None, "inside": inside, **land}
    x, _, verdict = inside[0]
    return {"verdict": verdict, "theta": x, "inside": inside, **land}


def steady_rates(t: Top, theta, lam_value) -> tuple:
    """(phidot, psidot) of the tilted rolling steady motion at ``theta`` with Jellett's ``lam_value``: omega =
    k r_P, k = lambda / D(theta), so phidot Z + psidot e3 = k (c e3 - R Z)."""
    k = lam_value / sp.lambdify(th, D.subs(t.values), "mpmath")(theta)
    return -k * t.R, k * t.c


def steady_spin_axis_angle(t: Top, theta, lam_value):
    """gamma, the angle between L_C and e3 (rad), at the rolling steady motion at ``theta`` with Jellett's
    ``lam_value`` (omega = k r_P: L_C = k (0, I1 r2, I3 r3), cos gamma = sign(k) I3 r3 / |(I1 r2, I3 r3)|): what the
    second inversion measure of :mod:`.runs` reads at a settled end, by a route that does not integrate."""
    radius, centre, i1, i3 = (mpmath.mpf(str(sp.N(x, 40))) for x in (t.R, t.c, t.I1, t.I3))
    r2, r3 = -radius * mpmath.sin(theta), centre - radius * mpmath.cos(theta)
    return mpmath.acos(mpmath.sign(lam_value) * i3 * r3 / mpmath.sqrt((i1 * r2) ** 2 + (i3 * r3) ** 2))


__all__ = ["Thresholds", "Top", "check_formulas", "landscape", "predict", "steady_rates", "steady_spin_axis_angle", "thresholds",
           "top"]

"""The cases of the reference set: which body, which start, how long, which output grid.

Every model of the paper is covered (disk, hoop, ring, hurricane balls, smooth-plane disk,
gyroscope, effective Lagrangian), quiet motions (steady or close to it) and wild ones
(large nutation, unstable starts), runs of 1 to 100 time units (seconds, g/R = 980), and the
paper's own figure runs where they stay inside the model's domain.

Initial states are exact decimal strings.  Where a caption asks for a steady motion (an
Eq. 21 circle, an Eq. 72 precession, ...) the missing rate is the root of the *derived*
row 1 (thetaddot = 0 at thetadot = 0) computed with mpmath at 50 digits and written with
40: the paper's formula is only the starting guess of the root finder.

Output grids have a dyadic spacing (t_end / n is a short binary fraction), so every grid
time is exactly representable at every precision and the runs being compared are sampled
at the same instants.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from functools import lru_cache

import mpmath
import sympy as sp

from models import get_model
from models.common import PAPER_G
from models.symbols import STATE, STATE_NAMES, phidot, psidot, theta, thetadot
from verify.standard import STANDARD_STATES

DIGITS = 40  # digits written for computed initial values (beyond the 128-bit run's 38.5)


@dataclass(frozen=True)
class ReferenceCase:
    """One reference trajectory: model, parameters, initial state, duration and output grid.

    Attributes
    ----------
    name : str
        File stem under ``reports/reference/`` (``<name>.json``).
    model : str
        Model name (``python -m verify models``); the derived equations are integrated.
    state, params : dict of str
        Exact decimal strings (parameters may be exact fractions, 301/1200); unset state components are 0, unset parameters take the
        model's exact defaults.
    t_end : str
        Duration in seconds (decimal string).
    intervals : int
        The output grid is ``t_end * j / intervals``, j = 0..intervals (a dyadic spacing).
    kind : {"quiet", "wild"}
        Steady or near-steady motion, or one with large excursions.
    source : str
        Where the start comes from (a paper figure, or this suite's standard state).
    description : str
    friction : str, optional
        The Coulomb coefficient mu (static = kinetic) of a case that rolls or slides: the run is the
        event-driven hybrid of :mod:`verify.engine.hybrid` (``<model>+coulomb``).
    velocity : pair of str, optional
        The centre of mass's horizontal velocity at t = 0 of a Coulomb case that starts sliding (a
        skid); None: it starts rolling (the velocity the no-slip constraint sets).
    """

    name: str
    model: str
    state: dict
    t_end: str
    intervals: int
    kind: str
    source: str
    description: str
    params: dict = field(default_factory=dict)
    friction: str | None = None
    velocity: tuple | None = None

    @property
    def hybrid(self) -> bool:
        """A body that rolls or slides with Coulomb friction (``<model>+coulomb``, :mod:`verify.engine.hybrid`)."""
        return self.friction is not None

    @property
    def run_model(self) -> str:
        """The model the run integrates: ``model``, or ``model+coulomb`` for a Coulomb case."""
        return f"{self.model}+coulomb" if self.hybrid else self.model

    @property
    def exact_params(self) -> dict:
        """The parameters as exact sympy numbers (a fraction such as 301/1200 is not a decimal string)."""
        return {k: sp.Rational(v) for k, v in self.params.items()}

    def grid(self) -> list:
        """The output times as exact decimal strings."""
        step = Fraction(self.t_end) / self.intervals
        if step.denominator & (step.denominator - 1):
            raise ValueError(f"case {self.name}: t_end/intervals = {step} is not a dyadic fraction")
        return [_decimal(step * j) for j in range(self.intervals + 1)]


def _decimal(q: Fraction) -> str:
    """The exact decimal expansion of a dyadic fraction."""
    if q == int(q):
        return str(int(q))
    digits = 0
    while (q * 10**digits).denominator != 1:
        digits += 1
    text = f"{int(q * 10**digits):0{digits + 1}d}"
    return (text[:-digits] or "0") + "." + text[-digits:]


# --- steady rates from the derived equations ---------------------------------------------

@lru_cache(maxsize=None)
def _row1(model_name: str, params_key: tuple):
    model = get_model(model_name)
    values = dict(params_key)
    subs = {p.symbol: sp.Rational(values[p.name]) if p.name in values else p.default for p in model.parameters}
    row = sp.numer(sp.together(model.accelerations[0].subs({thetadot: 0}).subs(subs)))
    return sp.lambdify((theta, phidot, psidot), row, "mpmath")


def steady_rate(model_name: str, unknown: str, guess, theta_value: str, params=None, **known) -> str:
    """The rate ``unknown`` ('phidot' or 'psidot') that makes thetaddot = 0 at thetadot = 0.

    ``known`` gives the other rate as a decimal string, or ``ratio`` = psidot/phidot (the
    Eq. 82 circles, psidot = rho phidot).  The root of the derived row 1 near ``guess``,
    50 digits, returned with :data:`DIGITS` significant digits.
    """
    f = _row1(model_name, tuple(sorted((params or {}).items())))
    with mpmath.workdps(50):
        th = mpmath.mpf(theta_value)
        if "ratio" in known:
            r = mpmath.mpf(known["ratio"])
            g = lambda w: f(th, w, r * w)  # noqa: E731
        elif unknown == "psidot":
            phd = mpmath.mpf(known["phidot"])
            g = lambda w: f(th, phd, w)  # noqa: E731
        else:
            psd = mpmath.mpf(known["psidot"])
            g = lambda w: f(th, w, psd)  # noqa: E731
        root = mpmath.findroot(g, mpmath.mpf(guess), tol=mpmath.mpf(10) ** -45)
        if abs(g(root)) > mpmath.mpf(10) ** -35 * (1 + abs(root)) ** 2:
            raise RuntimeError(f"steady {unknown} for {model_name} at theta = {theta_value} did not converge")
        return mpmath.nstr(root, DIGITS, strip_zeros=False)


def _exact(expr) -> str:
    with mpmath.workdps(50):
        return mpmath.nstr(mpmath.mpf(sp.N(expr, 50)), DIGITS, strip_zeros=False)


# --- the cases ------------------------------------------------------------------------------

G = PAPER_G
_HALF_PI = sp.pi / 2


def _standard(model: str) -> dict:
    return dict(STANDARD_STATES[model])


def _cases() -> tuple:
    k = sp.Rational(1, 4)
    straight = sp.sqrt(G / (2 * (2 * k + 1)))  # Eq. 32 threshold (confirmed by the suite's linearisation)
    spin = sp.sqrt(G / (k + 1))  # Eq. 41 threshold
    hoop_spin = sp.sqrt(G / (sp.Rational(1, 2) + 1))
    olsson = sp.sqrt(G / k)  # smooth plane
    h_ring = get_model("ring").parameter("h").default
    sqrt_g = sp.sqrt(G)
    fig2_psidot = steady_rate("disk", "psidot", -3, "1.8", phidot="5")
    fig16_rate = _exact(sp.sqrt(25 * G))
    fig16_theta = mpmath.nstr(_steady_theta("hurricane", fig16_rate, fig16_rate, guess="1.2"), DIGITS, strip_zeros=False)
    fig17_phidot = steady_rate("hurricane", "phidot", 60, "0.578", ratio="1.2")
    skid_state = {"theta": "1.2", "phidot": "3", "psidot": steady_rate("ring", "psidot", -70, "1.2", COIN, phidot="3")}
    skid_velocity = tuple(_exact(v / 2) for v in rolling_velocity("ring", skid_state, COIN))
    return (
        ReferenceCase("disk-fig2-circle", "disk", {"theta": "1.8", "phidot": "5", "psidot": fig2_psidot}, "10", 40,
                      "quiet", "paper Fig. 2 (Eq. 21 circle)",
                      "steady circle, theta = 1.8, phidot = 5, psidot the root of the derived row 1"),
        ReferenceCase("disk-fig2-circle-100", "disk", {"theta": "1.8", "phidot": "5", "psidot": fig2_psidot}, "100", 100,
                      "quiet", "paper Fig. 2 (Eq. 21 circle)", "the same steady circle over 100 s"),
        ReferenceCase("disk-fig3-lhs", "disk", {"theta": _exact(_HALF_PI + sp.Rational(1, 10)),
                                                 "psidot": _exact(sp.Rational(1001, 1000) * straight)}, "10", 40,
                      "wild", "paper Fig. 3 LHS", "straight-line start 0.1% above the Eq. 32 threshold, alpha = 0.1"),
        ReferenceCase("disk-fig3-rhs", "disk", {"theta": _exact(_HALF_PI + sp.Rational(1, 10)),
                                                 "psidot": _exact(sp.Rational(9, 10) * straight)}, "10", 40,
                      "wild", "paper Fig. 3 RHS", "straight-line start at 90% of the Eq. 32 threshold, alpha = 0.1"),
        ReferenceCase("disk-fig5-rhs", "disk", {"theta": _exact(_HALF_PI + sp.Rational(1, 100)),
                                                 "phidot": _exact(sp.Rational(9, 10) * spin)}, "10", 40,
                      "wild", "paper Fig. 5 RHS", "spin about a vertical diameter at 90% of Eq. 41, alpha = 0.01: spirals out"),
        ReferenceCase("disk-fig6-lhs", "disk", {"theta": "0.01", "phidot": "-625.917", "psidot": "625.948"}, "1", 64,
                      "quiet", "paper Fig. 6 LHS (numbers as printed)",
                      "fast spin-down state near the zero-vertical-spin family, theta = 0.01"),
        ReferenceCase("disk-standard-1", "disk", _standard("disk"), "1", 32, "wild", "suite's standard state",
                      "ordinary rolling with nutation (short: for slow integrators)"),
        ReferenceCase("disk-standard-100", "disk", _standard("disk"), "100", 100, "wild", "suite's standard state",
                      "ordinary rolling with nutation over 100 s"),
        ReferenceCase("hoop-general-10", "disk", {"theta": "1.0", "phidot": "2", "psidot": "15"}, "10", 40, "wild",
                      "hoop (k = 1/2)", "hoop rolling with large nutation", {"k": "0.5"}),
        ReferenceCase("hoop-fig5-lhs", "disk", {"theta": _exact(_HALF_PI + sp.Rational(1, 100)),
                                                 "phidot": _exact(sp.Rational(11, 10) * hoop_spin)}, "10", 40,
                      "quiet", "paper Fig. 5 LHS, for the hoop", "hoop spinning about a vertical diameter at 1.1 x Eq. 41",
                      {"k": "0.5"}),
        ReferenceCase("ring-fig10-lhs", "ring", {"theta": _exact(sp.acot(h_ring) + sp.Rational(2, 10000)), "psidot": "19.3"},
                      "5", 40, "quiet", "paper Fig. 10 LHS", "ring rolling straight with its CM nearly above the contact"),
        ReferenceCase("ring-fig11-lhs", "ring", {"theta": "1.225", "phidot": _exact(sqrt_g)}, "10", 40, "quiet",
                      "paper Fig. 11 LHS", "ring 'diameter spin' near its equilibrium angle, phidot = sqrt(g/R)"),
        ReferenceCase("ring-standard-10", "ring", _standard("ring"), "10", 40, "wild", "suite's standard state",
                      "ring rolling with nutation"),
        ReferenceCase("ring-standard-100", "ring", _standard("ring"), "100", 100, "wild", "suite's standard state",
                      "ring rolling with nutation over 100 s"),
        ReferenceCase("hurricane-fig16", "hurricane", {"theta": fig16_theta, "phidot": fig16_rate, "psidot": fig16_rate},
                      "10", 40, "quiet", "paper Fig. 16 (Eq. 72 precession)",
                      "steady precession at phidot = psidot = sqrt(25 g), theta the root of the derived row 1"),
        ReferenceCase("hurricane-fig17", "hurricane", {"theta": "0.578", "phidot": fig17_phidot,
                                                       "psidot": _times("1.2", fig17_phidot)}, "10", 40,
                      "quiet", "paper Fig. 17 (Eq. 82 circle, rho = 1.2)", "circling hurricane balls, psidot = 1.2 phidot"),
        ReferenceCase("hurricane-fig18-lhs", "hurricane", {"theta": "0.01", "phidot": _exact(sp.Rational(98, 100) * sqrt_g),
                                                           "psidot": _exact(sp.Rational(98, 100) * sqrt_g)}, "10", 40,
                      "wild", "paper Fig. 18 LHS", "nearly sleeping balls just above the sleeping threshold, theta0 = 0.01"),
        ReferenceCase("sliding-disk-standard-10", "sliding-disk", _standard("sliding-disk"), "10", 40, "wild",
                      "suite's standard state", "disk on a frictionless plane"),
        ReferenceCase("sliding-disk-olsson", "sliding-disk", {"theta": _exact(_HALF_PI + sp.Rational(1, 100)),
                                                              "phidot": _exact(sp.Rational(9, 10) * olsson)}, "10", 40,
                      "wild", "Olsson's threshold (footnote 2)",
                      "frictionless-plane diameter spin at 90% of g/k: unstable, large excursions"),
        ReferenceCase("gyroscope-standard-10", "gyroscope", _standard("gyroscope"), "10", 40, "wild",
                      "suite's standard state", "hurricane-ball gyroscope about its fixed bottom point (Eq. 86)"),
        ReferenceCase("effective-standard-10", "effective", _standard("effective"), "10", 40, "wild",
                      "suite's standard state", "the paper's effective Lagrangian (Eq. 96), near its Eq. 98-100 precession"),
        ReferenceCase("coin-standard-1", "ring", _standard("disk"), "1", 32, "wild",
                      "a coin: the ring model as a uniform solid cylinder of thickness 2h = R/10",
                      "a coin as engines draw one (a cylinder touching on its rim edge, half a thickness off the "
                      "mid-plane): I1 = 1/4 + h^2/3, I3 = 1/2, h = 1/20; the disk's standard start",
                      COIN),
        ReferenceCase("coin-coulomb-slip-1", "ring", _standard("disk"), "1", 32, "wild",
                      "a coin (as coin-standard-1) with Coulomb friction mu = 0.87: rolling, a slip phase, rolling",
                      "the coin's standard start rolling on a table with mu = 0.87 (static = kinetic): mu_req reaches "
                      "mu near t = 0.078, the contact slides, sticks near t = 0.097 and rolls to t_end",
                      COIN, friction="0.87"),
        ReferenceCase("coin-coulomb-skid-1", "ring", skid_state, "1", 32, "wild",
                      "a coin (as coin-standard-1) with Coulomb friction mu = 0.3: a skid that sticks",
                      "the coin launched on its steady Eq. 21 circle (theta = 1.2, phidot = 3, psidot the root of the "
                      "derived row 1) with half the rolling speed of its centre of mass: it slides, the friction "
                      "brings the slip to 0 near t = 0.076, and it rolls to t_end",
                      COIN, friction="0.3", velocity=skid_velocity),
        ReferenceCase("rounded-coin-upright-1", "body:rounded-coin",
                      {"theta": _exact(_HALF_PI - sp.Rational(1, 20)), "thetadot": "3", "psidot": "20"}, "1", 32, "wild",
                      "body file models/bodies/rounded-coin.toml (torus rims, tube radius = half-thickness = 1/20)",
                      "a coin with rounded rims rolling and rocking through the upright six times in 1 s (the paper's "
                      "ring stops at theta = pi/2: its rims switch)"),
        ReferenceCase("routh-sphere-standard-10", "body:routh-sphere", {"theta": "0.5", "phidot": "3", "psidot": "30"},
                      "10", 40, "wild", "body file models/bodies/routh-sphere.toml",
                      "Routh's sphere (centre of mass 3/10 below the centre) rolling and nutating; energy, Jellett's "
                      "and Routh's integrals"),
        ReferenceCase("prolate-ellipsoid-1", "body:prolate-ellipsoid", {"theta": "1.2", "phidot": "2", "psidot": "20"},
                      "1", 32, "wild", "body file models/bodies/prolate-ellipsoid.toml",
                      "a uniform prolate ellipsoid of revolution (1/2 x 1) rolling with nutation"),
        ReferenceCase("oblate-ellipsoid-1", "body:oblate-ellipsoid", {"theta": "0.8", "phidot": "3", "psidot": "15"},
                      "1", 32, "wild", "body file models/bodies/oblate-ellipsoid.toml",
                      "a uniform oblate ellipsoid of revolution (1 x 1/2) rolling with nutation"),
        ReferenceCase("tippe-top-coulomb-1", "body:tippe-top", {"theta": "0.1", "psidot": "200"}, "1", 32, "wild",
                      "body file models/bodies/tippe-top.toml; the start of the tippe-top study (docs/tippe-top.md)",
                      "the tippe top spun at 200 s^-1 about its axis tilted 0.1 rad, C at rest, on a table with exact "
                      "Coulomb friction mu = 0.3: the contact slides, sticks near t = 0.024 and the top rolls (it "
                      "does not turn over)", friction="0.3", velocity=("0", "0")),
    )


#: The coin: the ring model as a uniform solid cylinder of radius R and thickness 2h = R/10 (I1 = 1/4 + h^2/3).
COIN = {"I1": "301/1200", "I3": "1/2", "h": "1/20"}


def rolling_velocity(model_name: str, state: dict, params: dict) -> tuple:
    """The centre of mass's horizontal velocity (exact sympy) that rolling without slipping sets at ``state``."""
    model = get_model(model_name)
    subs = {p.symbol: sp.Rational(params[p.name]) if p.name in params else p.default for p in model.parameters}
    subs.update({s: sp.Rational(state.get(n, "0")) for s, n in zip(STATE, STATE_NAMES)})
    return tuple(sp.nsimplify(e).subs(subs) for e in model.velocity_xy)


def _times(a: str, b: str) -> str:
    with mpmath.workdps(50):
        return mpmath.nstr(mpmath.mpf(a) * mpmath.mpf(b), DIGITS, strip_zeros=False)


def _steady_theta(model_name: str, phidot_value: str, psidot_value: str, guess: str):
    f = _row1(model_name, ())
    with mpmath.workdps(50):
        a, b = mpmath.mpf(phidot_value), mpmath.mpf(psidot_value)
        return mpmath.findroot(lambda t: f(t, a, b), mpmath.mpf(guess), tol=mpmath.mpf(10) ** -45)


@lru_cache(maxsize=None)
def cases() -> tuple:
    """All reference cases (computed once: the steady rates need sympy and mpmath)."""
    out = _cases()
    names = [c.name for c in out]
    if len(set(names)) != len(names):
        raise RuntimeError("duplicate reference case names")
    return out


def case(name: str) -> ReferenceCase:
    """The case called ``name``; ``ValueError`` naming it and the allowed names otherwise."""
    for c in cases():
        if c.name == name:
            return c
    raise ValueError(f"unknown reference case {name!r}; allowed: {', '.join(c.name for c in cases())}")


__all__ = ["ReferenceCase", "case", "cases", "steady_rate"]

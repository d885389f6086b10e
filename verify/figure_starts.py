"""The paper's figure starts as data: one named start per panel of every figure with a run.

The figures of the paper (Figs. 2-6, 9-12, 15-20) are lost; the suite regenerates them from the
captions' words (verify/claims/simulations/).  Each panel's start is recorded here once, as the
decimal strings of the exact doubles the figure's run uses (``repr(float)``, the shortest string
that gives the same double back), with the words that say how the caption became that start.
The claim code builds its panel runs from this registry (:func:`verify.claims.simulations.runs.
run_start`), so the run the report draws is the run a reader gets from the start's name;
tests/test_figure_starts.py recomputes every string from the claim code's own formulas (Eq. 21's
psidot, the Eq. 32 and Eq. 41 rates, the steady states of Eqs. 58, 62, 72, 82) to the last bit.

This module imports nothing beyond the standard library, so listing the starts is instant.

Names are ``fig<N>`` for a figure with one panel (Figs. 2 and 12), ``fig<N>-lhs`` and
``fig<N>-rhs`` for the two panels, and ``fig<N>-<side>-<what>`` where a panel's caption is read
with a second run (Fig. 3 LHS: the unstated phidot0; Fig. 20 LHS: the small deviation).
Controls and other runs the checks make (mirror images, bisections, runs without events) are
not figure starts: they stay in the claim code.
"""
from __future__ import annotations

from dataclasses import dataclass

#: Output points of a figure run unless the start says otherwise (verify.claims.simulations.runs.DENSE).
DENSE = 20001
SIDES = ("lhs", "rhs")
#: the printed ring's parameters (text before Fig. 9; models.ring.PRINTED)
_RING = {"I1": "0.4993", "I3": "0.8727", "h": "0.4344"}


@dataclass(frozen=True)
class FigureStart:
    """One panel's start of a paper figure.

    Parameters
    ----------
    name : str
        ``fig5-lhs``, ``fig2``, ... (see the module's docstring).
    figure : int
        The paper's figure number.
    side : str or None
        ``"lhs"`` or ``"rhs"``; None for a figure with one panel.
    model : str
        The model name (``disk``, ``ring``, ``hurricane``).
    params : dict of str to str
        Parameters given to the run (empty: the model's defaults).
    state : dict of str to str
        The initial values given (unset components are 0), as ``repr(float)`` strings.
    t_end : str
        The run's end time in s.
    reading : str
        How the caption's words became this start.
    n_eval : int
        Output points from 0 to ``t_end`` (the figure's grid).
    events : bool
        Whether the run stops at the model's events (False only for Fig. 12, whose start
        loses contact at once: the caption's statements are about the rolling equations' run).
    """

    name: str
    figure: int
    side: str | None
    model: str
    params: dict
    state: dict
    t_end: str
    reading: str
    n_eval: int = DENSE
    events: bool = True


_EQ21 = "psidot0 from Eq. 21 (the steady circle at theta0, phidot0)"
_EQ41_FAMILY = ("psidot0 = 2(k+1) phidot0 alpha0/(2k+1), the member of the family the linearisation uses "
                "(row 3 of Eq. 39 integrated with constant 0), k = 1/4")

STARTS = (
    FigureStart("fig2", 2, None, "disk", {}, {"theta": "1.8", "phidot": "5.0", "psidot": "31.43167061547864"}, "4",
                f"no numbers in the caption: theta0 = 1.8 (> pi/2, as drawn), phidot0 = 5 chosen; {_EQ21}"),
    FigureStart("fig3-lhs", 3, "lhs", "disk", {}, {"theta": "1.6707963267948966", "psidot": "18.091996204583577"}, "10",
                "psidot0 = 1.001 x Eq. 32 = 1.001 sqrt(g/(2(2k+1))), k = 1/4; alpha = .1 read as theta0 = pi/2 + 0.1; "
                "phidot0 not stated: 0"),
    FigureStart("fig3-lhs-family", 3, "lhs", "disk", {},
                {"theta": "1.6707963267948966", "psidot": "18.091996204583577", "phidot": "3.6183992409167156"}, "10",
                "as fig3-lhs, with phidot0 = 2 psidot0 alpha0 (the member of the family Eq. 30 assumes: "
                "(2k+1) psidot = 2(k+1) phidot alpha at k = 1/4)"),
    FigureStart("fig3-rhs", 3, "rhs", "disk", {}, {"theta": "1.6707963267948966", "psidot": "16.26653005407115"}, "10",
                "psidot0 = 0.9 x Eq. 32; theta0 = pi/2 + 0.1 as the LHS; phidot0 = 0"),
    FigureStart("fig4-lhs", 4, "lhs", "disk", {}, {"theta": "1.3", "phidot": "5.0", "psidot": "-37.3896896006428"}, "5",
                f"'exactly the right initial values for circular motion': theta0 = 1.3, phidot0 = 5 (not stated); {_EQ21}"),
    FigureStart("fig4-rhs", 4, "rhs", "disk", {}, {"theta": "1.3", "phidot": "0.0", "psidot": "-37.3896896006428"}, "5",
                "the LHS's start with phidot0 = 0 ('leaving everything else unchanged')"),
    FigureStart("fig5-lhs", 5, "lhs", "disk", {},
                {"theta": "1.5807963267948966", "phidot": "30.800000000000004", "psidot": "0.5133333333333334"}, "10",
                f"theta0 = pi/2 + 0.01 (alpha = .01), phidot0 = 1.1 x Eq. 41 = 1.1 sqrt(g/(k+1)); {_EQ41_FAMILY}"),
    FigureStart("fig5-rhs", 5, "rhs", "disk", {},
                {"theta": "1.5807963267948966", "phidot": "25.2", "psidot": "0.42"}, "10",
                f"theta0 = pi/2 + 0.01, phidot0 = 0.9 x Eq. 41; {_EQ41_FAMILY}"),
    FigureStart("fig6-lhs", 6, "lhs", "disk", {},
                {"theta": "0.01", "phidot": "-625.9164919259526", "psidot": "625.9477890545946"}, "0.5",
                "the exact spin-down state with no z rotation at theta = 0.01 (Fig. 6 LHS: phidot = -625.917, "
                "psidot = 625.948 printed), solved at 30 digits and rounded once to double", n_eval=2001),
    FigureStart("fig6-rhs", 6, "rhs", "disk", {},
                {"theta": "0.01", "phidot": "-626.1042512310202", "psidot": "626.0729462793345"}, "0.5",
                "the exact spin-down state with the CM at rest (v_CM = 0) at theta = 0.01, solved at 30 digits and "
                "rounded once to double", n_eval=2001),
    FigureStart("fig9-lhs", 9, "lhs", "ring", _RING,
                {"theta": "0.1", "phidot": "142.6671041663262", "psidot": "-137.12490010192215"}, "10",
                "theta0 = .1 on the circle with the CM at rest (Eq. 58, rho = cos - h sin), phidot0 > 0; "
                "'psi_0 just 1% above' read as |psidot0| 1.01 times the circle's; the printed ring"),
    FigureStart("fig9-rhs", 9, "rhs", "ring", _RING,
                {"theta": "0.1", "phidot": "142.6671041663262", "psidot": "-134.40955554544843"}, "10",
                "as fig9-lhs with |psidot0| 0.99 times the circle's ('1% below')"),
    FigureStart("fig10-lhs", 10, "lhs", "ring", _RING, {"theta": "1.1611908118713177", "psidot": "19.3"}, "5",
                "theta0 = cot^-1 h + .0002 (the sign of Delta theta is not stated: the check also runs -.0002), "
                "psidot0 = 19.3 (psi_0 read as the rate), phidot0 = 0; the printed ring", n_eval=10001),
    FigureStart("fig10-rhs", 10, "rhs", "ring", _RING, {"theta": "1.1611908118713177", "psidot": "18.8"}, "5",
                "theta0 = cot^-1 h + .0002, psidot0 = 18.8, phidot0 = 0; the printed ring", n_eval=10001),
    FigureStart("fig11-lhs", 11, "lhs", "ring", _RING, {"theta": "1.225", "phidot": "31.304951684997057"}, "20",
                "phidot0 = sqrt(g/R) (printed 31.3), theta0 = 1.225, psidot0 = 0; the printed ring"),
    FigureStart("fig11-rhs", 11, "rhs", "ring", _RING, {"theta": "1.2158208011564509", "phidot": "25.7"}, "20",
                "phidot0 = 25.7, psidot0 = 0; theta0 'near' the equilibrium 1.205 names: the equilibrium at 25.7 "
                "(Eq. 62 branch) plus the LHS's own offset above its equilibrium (1.225 - theta_eq(sqrt(g/R)))"),
    FigureStart("fig12", 12, None, "ring", _RING, {"theta": "1.0207963267948965", "phidot": "140.87228258248675"}, "3",
                "Jalali et al.'s start: theta0 = pi/2 - .55, phidot0 = 4.5 sqrt(g/R), psidot0 = 0; run without the "
                "contact event (N < 0 from 5 ms: the caption is about the rolling equations' run)",
                n_eval=3001, events=False),
    FigureStart("fig15-lhs", 15, "lhs", "hurricane", {},
                {"theta": "1.5554111044574523", "phidot": "50.47771785649585", "psidot": "50.47771785649585"}, "5",
                "phidot0 = psidot0 = sqrt(2.6 g/a); theta0 from Eq. 72, cos theta0 = 2/5 - g/phidot0^2"),
    FigureStart("fig15-rhs", 15, "rhs", "hurricane", {},
                {"theta": "1.5654111044574524", "phidot": "50.47771785649585", "psidot": "50.47771785649585"}, "5",
                "the LHS's start with theta 'slightly off': theta0 + 0.01"),
    FigureStart("fig16-lhs", 16, "lhs", "hurricane", {},
                {"theta": "1.2125284333582567", "phidot": "156.52475842498527", "psidot": "156.52475842498527"}, "3",
                "phidot0 = psidot0 = sqrt(25 g/a), theta0 = Eq. 72's angle + .01 ('θ .01 above')"),
    FigureStart("fig16-rhs", 16, "rhs", "hurricane", {},
                {"theta": "1.2025284333582567", "phidot": "156.52475842498527", "psidot": "172.1772342674838"}, "3",
                "theta0 from Eq. 72 at phidot0 = sqrt(25 g/a), psidot0 = 1.1 phidot0 ('10% above')"),
    FigureStart("fig17-lhs", 17, "lhs", "hurricane", {},
                {"theta": "0.578", "phidot": "313.7660243728086", "psidot": "376.51922924737033"}, "2",
                "rho = 1.2, theta0 = 0.578; phidot0 from Eq. 82, g/phidot0^2 = (1.4 rho - 1) - (2 - rho) cos theta0; "
                "psidot0 = rho phidot0"),
    FigureStart("fig17-rhs", 17, "rhs", "hurricane", {},
                {"theta": "0.588", "phidot": "313.7660243728086", "psidot": "376.51922924737033"}, "2",
                "the LHS's start with theta0 + 0.01"),
    FigureStart("fig18-lhs", 18, "lhs", "hurricane", {},
                {"theta": "0.01", "phidot": "30.678852651297117", "psidot": "30.678852651297117"}, "10",
                "psidot0 = phidot0 = .98 sqrt(g/a); theta0 'near 0' read as 0.01"),
    FigureStart("fig18-rhs", 18, "rhs", "hurricane", {},
                {"theta": "0.01", "phidot": "30.365803134447145", "psidot": "30.365803134447145"}, "10",
                "psidot0 = phidot0 = .97 sqrt(g/a); theta0 'near 0' read as 0.01"),
    FigureStart("fig19-lhs", 19, "lhs", "hurricane", {}, {"theta": "0.01", "psidot": "61.04465578574426"}, "10",
                "phidot0 = 0, psidot0 = 1.95 sqrt(g/a); theta0 = 0.01 (not stated)"),
    FigureStart("fig19-rhs", 19, "rhs", "hurricane", {}, {"theta": "0.01", "psidot": "59.47940820149441"}, "10",
                "phidot0 = 0, psidot0 = 1.9 sqrt(g/a); theta0 = 0.01 (not stated)"),
    FigureStart("fig20-lhs", 20, "lhs", "hurricane", {},
                {"theta": "0.01", "phidot": "13.368028224012555", "psidot": "47.255979771884384"}, "10",
                "Eq. 82 exactly satisfied at theta0 = .01, rho = 3.535: phidot0 from Eq. 82, psidot0 = rho phidot0"),
    FigureStart("fig20-lhs-deviation", 20, "lhs", "hurricane", {},
                {"theta": "0.011", "phidot": "13.368028224012555", "psidot": "47.255979771884384"}, "100",
                "the LHS's 'small deviation' read as theta0 + 0.001; run 100 s (the oscillation's period is ~30 s)"),
    FigureStart("fig20-rhs", 20, "rhs", "hurricane", {},
                {"theta": "0.060000000000000005", "phidot": "13.368028224012555", "psidot": "47.255979771884384"}, "10",
                "'larger deviations' read as theta0 + 0.05"),
)

_BY_NAME = {s.name: s for s in STARTS}


def start(name: str) -> FigureStart:
    """The start called ``name``; a ValueError naming the allowed names otherwise."""
    try:
        return _BY_NAME[name]
    except KeyError:
        raise ValueError(f"unknown figure start {name!r}; allowed: {', '.join(_BY_NAME)}") from None


def starts_of(figure: int, side: str | None = None) -> tuple:
    """The starts of paper figure ``figure`` (of one side when ``side`` is ``"lhs"`` or ``"rhs"``)."""
    return tuple(s for s in STARTS if s.figure == figure and (side is None or s.side == side))


def figures_with_runs() -> tuple:
    """The figure numbers with a regenerated run, ascending."""
    return tuple(sorted({s.figure for s in STARTS}))


def panel_sides(figure: int) -> tuple:
    """The panel sides (``"lhs"``, ``"rhs"``) of ``figure``'s starts; empty for a one-panel figure."""
    return tuple(side for side in SIDES if any(s.side == side for s in starts_of(figure)))
